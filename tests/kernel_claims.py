"""The kernels that no process has compiled yet, shared out between the suite's
process and its kernels job (conftest.py): whoever meets such a kernel first claims it
and compiles it; the other, meeting it later, waits until it is in Numba's disk cache
and loads it from there. Numba compiles on one core and a kernel's compile is not
shared between processes: before, a test that met a kernel the job had not compiled
yet waited, its core idle, while the job compiled its kernels one after another in
warm_all's order (about 80 s of the tests' process in a clean clone); without the
wait, both had compiled the same kernels side by side.

The job takes warm_all's pictures from the last one back, while the tests meet
their kernels in about warm_all's order (main()).

A claim is a file created with O_EXCL in a folder both processes know (CLAIMS_ENV in
the job's environment), one for each of floatcol's kernels (floatcol.warmup's
every_kernel), taken only where the kernel has no compiled signature in this process
and no index in the cache. A process waits for a claimed kernel while the claimer
lives (alive()), WAIT s at most; then it compiles the kernel itself.
"""
import os
import time

#: the job's environment variable naming the folder of claims
CLAIMS_ENV = "FLOATCOL_KERNEL_CLAIMS"
#: seconds a process waits at most for another's compile of a kernel
WAIT = 600.0


def install(folder, alive):
    """Wrap Numba's Dispatcher.compile in this process: floatcol's kernels are claimed
    in ``folder`` or waited for while ``alive()`` (the other process runs)."""
    from numba.core.dispatcher import Dispatcher
    compile_ = Dispatcher.compile
    kernels = {}

    def compile(self, sig):
        if not kernels:
            from floatcol.warmup import every_kernel
            kernels.update((id(k), name) for name, k in every_kernel().items())
        name = kernels.get(id(self))
        cache_file = (getattr(getattr(self, "_cache", None), "_cache_file", None)
                      if name is not None and not self.overloads else None)
        if cache_file is not None and not os.path.exists(cache_file._index_path) \
                and not _claim(folder, name):
            deadline = time.monotonic() + WAIT
            while not os.path.exists(cache_file._index_path) and alive() \
                    and time.monotonic() < deadline:
                time.sleep(0.2)
        return compile_(self, sig)
    Dispatcher.compile = compile


def claim(path, who=""):
    """True where this process now holds ``path`` (a file created with O_EXCL, ``who``
    its content), False where another process created it first."""
    try:
        fd = os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
    except FileExistsError:
        return False
    os.write(fd, who.encode())
    os.close(fd)
    return True


def _claim(folder, name):
    try:
        return claim(os.path.join(folder, name))
    except OSError:                 # (the folder is gone: the session has ended)
        return True


def main():
    """The kernels job's process: ``python kernel_claims.py`` (CLAIMS_ENV set)
    compiles every kernel (floatcol.warmup.warm_all's pictures) as it claims them; it
    waits for the suite's process while that lives (its parent). It takes warm_all's
    pictures from the last one back: the tests meet their kernels in about warm_all's
    order, so each of the two compiles those the other will reach last, and they meet
    in the middle (in warm_all's order, the job had been compiling the very kernel a
    test waited for: the test's core idle for about 70 s in a clean clone)."""
    parent = os.getppid()
    install(os.environ[CLAIMS_ENV], lambda: os.getppid() == parent)
    os.environ["FLOATCOL_DRAFT"] = "0"
    from floatcol import warmup
    warmup.warm()
    for step in reversed(warmup.warm_all_steps()):
        step()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

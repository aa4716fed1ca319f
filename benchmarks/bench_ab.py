"""Two versions of floatcol in one process, their renders alternating: the way to
compare speeds on a machine whose speed drifts (a shared virtual machine's does, by
up to 1.5x within minutes, so runs made apart cannot be compared).

    python benchmarks/bench_ab.py REV [REPEATS] [--kernels]

REV is a git revision (HEAD, a commit, a tag): its floatcol/ is exported to a
temporary folder as the package ``floatcol_ab`` (compiled there on first use, about
a minute) and rendered against the working tree's floatcol, the same scenes, best
and median of REPEATS (default 11) after a warm-up. Pictures of the two are
compared too (``same`` when rgba, side and w_limits are bit-identical).

With ``--kernels`` it times the two kernels of each version instead, the column
pass and the finishing pass, each called again and again on the buffers of one
render (captured from render()): less noise than whole renders, where a change is
inside one kernel.
"""
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

# the kernels' pictures, not a fresh process's draft (passes/draft.py) while they compile
os.environ.setdefault("FLOATCOL_DRAFT", "0")
EXPR = "3*sin(u*cos(v))"
DOM = dict(u=(-5, 5), v=(-5, 5))
SCENES = [((1920, 1080), "orthographic"), ((1920, 1080), "perspective"),
          ((1024, 768), "orthographic"), ((1024, 768), "perspective")]


def export(rev):
    """The folder holding REV's floatcol as the package floatcol_ab."""
    root = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True,
                          text=True, check=True).stdout.strip()
    sha = subprocess.run(["git", "rev-parse", "--short", rev], capture_output=True, text=True,
                         check=True, cwd=root).stdout.strip()
    folder = os.path.join(tempfile.gettempdir(), f"floatcol_ab_{sha}")
    if not os.path.isdir(os.path.join(folder, "floatcol_ab")):
        os.makedirs(folder, exist_ok=True)
        archive = subprocess.run(["git", "archive", rev, "floatcol"], capture_output=True,
                                 check=True, cwd=root).stdout
        subprocess.run(["tar", "-x", "-C", folder, "--transform", "s/^floatcol/floatcol_ab/"],
                       input=archive, check=True)
    return folder, sha


def _kernel_args(fc, size, proj):
    """{kernel name: (the kernel, copies of its arguments)} of one render by fc."""
    # the module that calls each kernel: the passes' since the scene (issue 27), else
    # render's
    callers = {"column_kernel": (".passes.geometry", ".render"),
               "finish_kernel": (".passes.finish", ".render")}
    got = {}
    patched = []
    for name, where in callers.items():
        module = next(sys.modules[fc.__name__ + m] for m in where
                      if fc.__name__ + m in sys.modules
                      and hasattr(sys.modules[fc.__name__ + m], name))
        kernel = getattr(module, name)

        def capture(*args, kernel=kernel, name=name):
            got[name] = (kernel, [a.copy() if isinstance(a, np.ndarray) else a
                                  for a in args])
            return kernel(*args)
        setattr(module, name, capture)
        patched.append((module, name, kernel))
    try:
        fc.render(EXPR, size=size, projection=proj, **DOM)
    finally:
        for module, name, kernel in patched:
            setattr(module, name, kernel)
    return got


def kernels(then, now, sha, repeats):
    print(f"| scene | kernel | {sha} best / median ms | working tree best / median ms "
          "| ratio of bests |")
    print("|---|---|---|---|---|")
    for size, proj in SCENES:
        calls = {"then": _kernel_args(then, size, proj), "now": _kernel_args(now, size, proj)}
        for name in ("column_kernel", "finish_kernel"):
            ts = {"then": [], "now": []}
            for rep in range(repeats + 1):
                for which in ("then", "now"):
                    kernel, args = calls[which][name]
                    t = time.perf_counter()
                    kernel(*args)
                    ts[which].append((time.perf_counter() - t) * 1e3)
            a, b = (ts[k][1:] for k in ("then", "now"))
            print(f"| {size[0]}x{size[1]} {proj} | {name} | {min(a):.2f} / "
                  f"{statistics.median(a):.2f} | {min(b):.2f} / {statistics.median(b):.2f} | "
                  f"{min(a) / min(b):.3f} |", flush=True)


def main():
    args = [a for a in sys.argv[1:] if a != "--kernels"]
    if not args:
        sys.exit(__doc__)
    rev = args[0]
    repeats = int(args[1]) if len(args) > 1 else 11
    folder, sha = export(rev)
    sys.path.insert(0, folder)
    import floatcol as now
    import floatcol_ab as then
    if "--kernels" in sys.argv[1:]:
        kernels(then, now, sha, repeats)
        return
    print(f"| scene | {sha} best / median ms | working tree best / median ms | ratio of bests "
          "| pictures |")
    print("|---|---|---|---|---|")
    for size, proj in SCENES:
        ts = {"then": [], "now": []}
        pics = {}
        for rep in range(repeats + 1):
            for name, fc in (("then", then), ("now", now)):
                t = time.perf_counter()
                r = fc.render(EXPR, size=size, projection=proj, **DOM)
                ts[name].append((time.perf_counter() - t) * 1e3)
                if rep == 0:
                    pics[name] = (r.rgba.copy(), r.side.copy(), r.stats.get("w_limits"))
                del r
        a, b = (ts[k][1:] for k in ("then", "now"))
        same = all(np.array_equal(x, y) if isinstance(x, np.ndarray) else x == y
                   for x, y in zip(pics["then"], pics["now"]))
        print(f"| {size[0]}x{size[1]} {proj} | {min(a):.1f} / {statistics.median(a):.1f} | "
              f"{min(b):.1f} / {statistics.median(b):.1f} | {min(a) / min(b):.3f} | "
              f"{'same' if same else 'differ'} |", flush=True)


if __name__ == "__main__":
    main()

import os
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))
# Every picture of the suite is the kernels' (reproducible), never a fresh install's
# draft (floatcol/warmup.py); tests/test_draft.py turns drafts on where it tests them.
os.environ["FLOATCOL_DRAFT"] = "0"

#: the repository's folder
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
#: The suite's kernels are compiled with Numba's bounds checks: an index out of range
#: in any test's picture, in this process or in one it starts (the CLI's, the fuzz
#: workers', a cluster's workers), is an IndexError, not a read or write past a
#: buffer (inside a kernel's parallel loop too: one thread, below). The checks change
#: the code but no value (the kernels use no fast-math), and they go into a kernel cache
#: of the suite's own, so that a render outside the suite never loads a checked kernel
#: (Numba's cache index does not tell them apart).
#: LLVM optimises them at level 1: the same values, a tenth less compile. Before, the
#: suite ran the unchecked kernels and compiled them a second time with the checks for
#: 19 pictures (test_fuzz's bounds-checked job: about 130 s of CPU in a clean clone).
#: And OpenMP's threads wait for work asleep, not spinning: two test processes
#: (second_process.py) and the jobs share the cores, where a spinning thread takes a
#: core from a process that has work (about 50 s of CPU in a clean clone).
#: And glibc's malloc keeps the memory that numpy's arrays of up to 32 MiB free (the
#: reference ray casters' temporaries) for the next ones, instead of handing it back
#: to the system and faulting every page of the next array in again: its own rule
#: (a threshold that grows with the blocks freed) depends on what a process allocated
#: first: the second test process of a clean clone, which starts after the kernels'
#: compile, faulted 42 M times in its tests (a soft-shadow test 4.4 M times) where
#: the first faulted 1.4 M times in its own. Kept, the helper's tests fault 0.1 M
#: times: a clean clone's suite 294 -> 244 s, its system time 100 -> 27 s.
MALLOC_MMAP = 32 << 20
MALLOC_TRIM = 512 << 20
#: And one thread for every kernel of the suite (NUMBA_NUM_THREADS=1, in this process and
#: every process it starts), so that those bounds checks reach the test from inside the
#: kernels' parallel loops too: Numba reports an exception raised in a parallel loop only
#: where the launching thread ran into it; in another thread's share of the loop it is
#: dropped and the rest of that share skipped (numba#2811: an index out of range in the
#: last column of a picture returned as if nothing had happened, its columns left
#: unrendered). With one thread the launching thread runs the whole loop (the launcher
#: turns Numba's SystemError back into the IndexError: kernels/_jit.py _Exclusive). The
#: two test processes keep both cores busy; the tests of thread counts start a process
#: of their own with more (test_threads.py).
SUITE_ENV = {"NUMBA_BOUNDSCHECK": "1", "NUMBA_OPT": "1", "NUMBA_NUM_THREADS": "1",
             "NUMBA_CACHE_DIR": os.path.join(ROOT, ".pytest_cache", "numba"),
             "OMP_WAIT_POLICY": "PASSIVE",
             "MALLOC_MMAP_THRESHOLD_": str(MALLOC_MMAP), "MALLOC_TRIM_THRESHOLD_": str(MALLOC_TRIM)}
os.environ.update(SUITE_ENV)


def _keep_freed_memory():
    """This process's malloc as SUITE_ENV sets its children's (read at their start):
    mallopt's M_MMAP_THRESHOLD (-3) and M_TRIM_THRESHOLD (-1), where the C library
    is glibc."""
    import ctypes
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):           # (not glibc: its own rules stay)
        return
    mallopt(-3, MALLOC_MMAP)
    mallopt(-1, MALLOC_TRIM)


_keep_freed_memory()
if "numba" in sys.modules:                 # (read at its import: read again)
    from numba.core import config as _numba_config
    _numba_config.reload_config()

import floatcol as fc  # noqa: E402
import kernel_claims  # noqa: E402
import second_process  # noqa: E402
from reference import numpy_surface, raycast  # noqa: E402


def reference_for(r, expr, u, v, elev, azim, projection, **kw):
    """Ray-cast the same picture as render result ``r`` (same scale, d1, d2)."""
    vw = r.view
    return raycast(numpy_surface(expr), u, v, (vw.width, vw.height), elev, azim, projection,
                   vw.d1, vw.d2, vw.scale, center=vw.center, **kw)


def matplotlib_agrees(view, world, box_points, limits, elev, azim):
    """Whether matplotlib's own Axes3D camera (orthographic, default box aspect, axis
    limits ``limits``) projects the points ``world`` (3, n) as floatcol's ``view``
    projects ``box_points`` (the same points in the view's box), up to scale and shift
    (to 1e-9 of the picture's spread)."""
    import matplotlib.pyplot as plt
    import numpy as np
    from mpl_toolkits.mplot3d import proj3d
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d", proj_type="ortho")
    for lim, set_lim in zip(limits, (ax.set_xlim, ax.set_ylim, ax.set_zlim)):
        set_lim(*lim)
    ax.view_init(elev, azim)
    mx, my, _ = proj3d.proj_transform(*world, ax.get_proj())
    plt.close(fig)
    col, row = view.project(*box_points)
    ours = np.stack([col, -row], 1)
    theirs = np.stack([mx, my], 1)
    ours = (ours - ours.mean(0)) / np.linalg.norm(ours - ours.mean(0))
    theirs = (theirs - theirs.mean(0)) / np.linalg.norm(theirs - theirs.mean(0))
    return np.abs(ours - theirs).max() < 1e-9


def red_overlap(ours, theirs, setup, proj):
    """(intersection over union, mplot3d's red pixels): where two drawings into a fresh
    6.4 x 4.8 inch 3-D Axes (proj_type ``proj``), ``ours(ax)`` (floatcol's) and
    ``theirs(ax)`` (mplot3d's own), each flat red and followed by ``setup(ax)``
    (limits, view), paint red."""
    import matplotlib.pyplot as plt

    def red(draw):
        fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
        ax = fig.add_subplot(projection="3d", proj_type=proj)
        draw(ax)
        setup(ax)
        fig.canvas.draw()
        a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
        plt.close(fig)
        return (a[..., 0] > 200) & (a[..., 1] < 60) & (a[..., 2] < 60)
    a, b = red(ours), red(theirs)
    return (a & b).sum() / max((a | b).sum(), 1), int(b.sum())


def plane(antialias, scale=42.3):
    """w = 0 on [-1, 1]^2, orthographic, elev 30, azim 0, origin at the image centre:
    the far edge v = 1 projects to screen y = 0.5, the near edge to -0.5, the side
    edges to x = -1 and 1."""
    return fc.render("0*u", u=(-1, 1), v=(-1, 1), size=(121, 121), elev=30, azim=0,
                     scale=scale, center=(0, 0, 0), background=(0, 0, 0, 0), antialias=antialias,
                     upper_color="white")


def assert_plane_edges(r):
    """plane()'s far and near edges cover their pixels by the analytic fraction. Far
    edge: y = 0.5 * 42.3 + 60 = 81.15 rows from the bottom; pixel 81 spans [80.5, 81.5]
    and is covered up to 81.15: 0.65. Near edge: y = 38.85, pixel 39 is covered from
    38.85 to 39.5: 0.65 too. Returns the columns checked."""
    alpha = r.rgba[..., 3] / 255.0
    top, bot = 120 - 81, 120 - 39
    cols = slice(30, 90)
    assert np.allclose(alpha[top, cols], 0.65, atol=1 / 255)
    assert np.allclose(alpha[bot, cols], 0.65, atol=1 / 255)
    assert np.all(alpha[top + 1:bot, cols] == 1.0)
    assert np.all(alpha[:top, cols] == 0.0) and np.all(alpha[bot + 1:, cols] == 0.0)
    return cols


def render_with_switch_off(monkeypatch, index, expr, **kw):
    """The render of ``expr`` with view parameter ``index`` (one of vp's test-only
    switches, kernels/layout.py) set to 0, and patched so for the rest of the test."""
    from floatcol import view as view_mod
    params = view_mod.View.params

    def switched_off(self):
        vp = params(self)
        vp[index] = 0.0
        return vp
    monkeypatch.setattr(view_mod.View, "params", switched_off)
    return fc.render(expr, **kw)


@pytest.fixture(scope="session")
def demo():
    """Gordon's 3 sin(u cos v), orthographic, rendered once."""
    return fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(160, 120), elev=30, azim=20,
                     shading="lambert")


# ---------------------------------------------------------------------------------
# Background jobs. A clean clone's suite (CI) is CPU-bound on 2 cores, and most of
# its CPU goes to Numba compiling: the GPU kernels' PTX (test_cuda, about 80 s) shares
# nothing with the other tests and runs in a process of its own; every CPU kernel
# (about 170 s: the default picture's and those that sub-columns, area sampling,
# translucency, shadows, textures, ... add) is compiled into the suite's cache by one
# more process (_compile_every_kernel, below) and by the tests, each kernel by
# whichever meets it first (kernel_claims.py); then a second test process runs the
# modules the first has not reached (second_process.py).
# A test module registers such work as a job (background_job); once the tests are
# collected, the jobs of the selected tests run in threads of this process, one
# after another within a lane, each thread waiting on its subprocess, while the
# suite goes on; the test takes the outcome (background_result, which waits for it,
# or runs the job itself where it was not started) and asserts on it as before.
# ---------------------------------------------------------------------------------

class _Job:
    def __init__(self, name, consumer, fn, order, lane):
        self.name = name
        self.consumer = consumer        # the test function that asserts on the outcome
        self.fn = fn
        self.order = order              # the jobs of a lane run in this order
        self.lane = lane                # lanes run side by side
        self.started = False
        self.done = threading.Event()
        self.value = None
        self.error = None
        self.procs = []                 # subprocesses to stop if the session ends first
        self.wanted = threading.Event()  # set once its consumer waits for it
        self._lock = threading.Lock()

    def run(self):
        """Run the job here, unless it has been started (then: nothing)."""
        with self._lock:
            if self.started:
                return
            self.started = True
        try:
            self.value = self.fn(self)
        except BaseException as exc:     # (pytest.skip's too: re-raised in the test)
            self.error = exc
        finally:
            self.done.set()


_JOBS = {}


def background_job(name, consumer, order, lane=0):
    """Register fn(job) as the background job ``name`` whose outcome the test function
    named ``consumer`` asserts on (the job runs where that test is selected); fn may
    add the subprocesses it starts to job.procs (stopped if the session ends before
    they do). The jobs of a ``lane`` run one after another by ``order``, the lanes
    side by side; their consumers run after every other test, so that the jobs have
    the whole session to finish."""
    def register(fn):
        _JOBS[name] = _Job(name, consumer, fn, order, lane)
        return fn
    return register


def background_result(name):
    """The value that job ``name`` returned (waiting for it), or the exception it raised,
    raised again here."""
    job = _JOBS[name]
    job.wanted.set()
    job.run()
    job.done.wait()
    if job.error is not None:
        raise job.error
    return job.value


#: the CPU priority (nice) of the background jobs' processes that no test waits for
#: until the last tests
BEHIND = 10


# (A job's process starts in ROOT, not in the current folder, which a test may have
# changed to a temporary one that is gone by the time the job runs:
# test_bounds_checked_kernels failed with a FileNotFoundError from os.getcwd().)


def _behind():
    os.nice(BEHIND)


#: preexec_fn of a background job's process whose outcome only the last tests take
#: (the PTX): a lower CPU priority, so that the tests and the kernels job go on at
#: full speed while it runs, and it takes the core they leave idle (None where
#: processes have no nice value: Windows, which takes no preexec_fn either)
behind_the_tests = _behind if hasattr(os, "nice") else None


def _run_jobs(jobs, then=None):
    for job in jobs:
        job.run()
    if then is not None:
        then()


def _test_name(item):
    return getattr(item, "originalname", item.name)


def pytest_collection_modifyitems(session, config, items):
    consumers = {job.consumer for job in _JOBS.values()}
    last = [item for item in items if _test_name(item) in consumers]
    if last:
        items[:] = [item for item in items if _test_name(item) not in consumers] + last
    if _MAIN:
        _MAIN[0].stay = {item.nodeid for item in last}


#: the main process's side of the second test process (second_process.Main), where
#: there is one
_MAIN = []


def pytest_configure(config):
    if os.environ.get(second_process.HELPER_ENV):
        config.pluginmanager.register(second_process.Helper(
            os.environ[second_process.HELPER_ENV], config), "floatcol-helper")
    elif second_process.wanted(config):
        _MAIN.append(second_process.Main(config, set()))
        config.pluginmanager.register(_MAIN[0], "floatcol-main")


def _start_the_helper(session):
    """The second test process, once the kernel cache holds the default picture's
    kernels (where lane 1's jobs did not wait for them: a run of a few modules)."""
    from floatcol import warmup
    deadline = time.monotonic() + 600.0
    while not warmup.kernels_ready() and time.monotonic() < deadline:
        time.sleep(0.5)
    _MAIN[0].start(session)


#: whether Numba's cache held the default picture's kernels when the tests began (a
#: warm run: _compile_every_kernel has nothing to do), set once they are collected
_WARM_AT_START = []


def pytest_collection_finish(session):
    if session.config.option.collectonly or os.environ.get(second_process.HELPER_ENV):
        return
    from floatcol import warmup
    _WARM_AT_START.append(warmup.kernels_ready())
    wanted = {_test_name(item) for item in session.items}
    jobs = sorted((job for job in _JOBS.values() if job.consumer in wanted),
                  key=lambda job: job.order)
    # lane 1 (the kernels job, the bounds-checked cases) ends by starting the second
    # test process, on the kernels it has compiled (second_process.py)
    helper = (lambda: _start_the_helper(session)) if _MAIN else None
    for lane in sorted({job.lane for job in jobs} | ({1} if helper else set())):
        threading.Thread(target=_run_jobs, args=([j for j in jobs if j.lane == lane],
                                                 helper if lane == 1 else None),
                         name=f"floatcol-test-jobs-{lane}", daemon=True).start()


def pytest_sessionfinish(session):
    for job in _JOBS.values():
        for proc in job.procs:
            if proc.poll() is None:
                proc.kill()
                proc.wait()
    if _CLAIMS:
        import shutil
        shutil.rmtree(_CLAIMS[0], ignore_errors=True)


@background_job("kernels", consumer="test_warm_all_compiles_every_kernel", order=0, lane=1)
def _compile_every_kernel(job):
    """Compile the CPU kernels that the default picture does not use
    (floatcol.warmup.warm_all's pictures: sub-columns, area sampling, translucency,
    shadows, textures, colour fields, the fly engine, ...) into the suite's Numba
    cache in a process of its own (kernel_claims.main), once the first tests have
    compiled the default picture's (which the others call too: loaded, not compiled
    twice). The tests and the job share them out: whichever meets a kernel first
    claims and compiles it, the other loads it (kernel_claims.py). Where the cache held
    the default kernels when the tests began it does nothing (not where the first
    tests have compiled them since); where its consumer asks for it first (it alone
    selected, say), it waits no longer."""
    from floatcol import warmup
    if (_WARM_AT_START[0] if _WARM_AT_START else warmup.kernels_ready()):
        return None
    deadline = time.monotonic() + 600.0
    while not (warmup.kernels_ready() or job.wanted.is_set()) and time.monotonic() < deadline:
        time.sleep(0.5)
    proc = subprocess.Popen([sys.executable, os.path.join(ROOT, "tests", "kernel_claims.py")],
                            env=dict(os.environ, FLOATCOL_DRAFT="0"), cwd=ROOT,
                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    job.procs.append(proc)
    _, err = proc.communicate()
    return proc.returncode, err


#: the folder of the kernels' claims (kernel_claims.py) that this process and the
#: kernels job share
_CLAIMS = []


def _another_compiles():
    """Whether a process that may hold claims runs: the kernels job, the helper."""
    job = _JOBS.get("kernels")
    procs = (job.procs[-1:] if job is not None else []) + \
        ([_MAIN[0].proc] if _MAIN and _MAIN[0].proc is not None else [])
    return any(proc.poll() is None for proc in procs)


def pytest_sessionstart(session):
    if os.environ.get(second_process.HELPER_ENV):
        # the helper (its parent this session's main process), in the main process's
        # folder of claims: where it starts before every kernel is compiled (a run of
        # some modules only), it compiles no kernel twice
        parent = os.getppid()
        kernel_claims.install(os.environ[kernel_claims.CLAIMS_ENV],
                              lambda: os.getppid() == parent)
        return
    import tempfile
    _CLAIMS.append(tempfile.mkdtemp(prefix="floatcol-claims-"))
    os.environ[kernel_claims.CLAIMS_ENV] = _CLAIMS[0]      # (the job's and the helper's)
    kernel_claims.install(_CLAIMS[0], _another_compiles)

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

import floatcol as fc  # noqa: E402
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
# Background jobs. A clean clone's suite (CI) is CPU-bound on 2 cores, and about 450
# of its 660 s of CPU go to Numba compiling: the kernels with Numba's bounds checks
# (test_fuzz, its own cache, about 110 s) and the GPU kernels' PTX (test_cuda, about
# 80 s) share nothing with the other tests and run in processes of their own; every
# CPU kernel (about 170 s: the default picture's and those that sub-columns, area
# sampling, translucency, shadows, textures, ... add) is compiled into the suite's
# cache by one more process (_compile_every_kernel, below), which the tests wait for
# rather than compile a kernel a second time beside it (_wait_for_the_kernels_job).
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


#: the repository's folder: a job's process starts there, not in the current folder,
#: which a test may have changed to a temporary one that is gone by the time the job
#: runs (test_bounds_checked_kernels failed with a FileNotFoundError from os.getcwd())
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _behind():
    os.nice(BEHIND)


#: preexec_fn of a background job's process whose outcome only the last tests take
#: (the PTX, the bounds-checked kernels): a lower CPU priority, so that the tests
#: (which cannot use both cores) go on at full speed while it runs, and it takes the
#: core they leave idle, and the whole of it once the tests are done (None where
#: processes have no nice value: Windows, which takes no preexec_fn either)
behind_the_tests = _behind if hasattr(os, "nice") else None


def _run_jobs(jobs):
    for job in jobs:
        job.run()


def _test_name(item):
    return getattr(item, "originalname", item.name)


def pytest_collection_modifyitems(session, config, items):
    consumers = {job.consumer for job in _JOBS.values()}
    last = [item for item in items if _test_name(item) in consumers]
    if last:
        items[:] = [item for item in items if _test_name(item) not in consumers] + last


#: whether Numba's cache held the default picture's kernels when the tests began (a
#: warm run: _compile_every_kernel has nothing to do), set once they are collected
_WARM_AT_START = []


def pytest_collection_finish(session):
    if session.config.option.collectonly:
        return
    from floatcol import warmup
    _WARM_AT_START.append(warmup.kernels_ready())
    wanted = {_test_name(item) for item in session.items}
    jobs = sorted((job for job in _JOBS.values() if job.consumer in wanted),
                  key=lambda job: job.order)
    for lane in sorted({job.lane for job in jobs}):
        threading.Thread(target=_run_jobs, args=([j for j in jobs if j.lane == lane],),
                         name=f"floatcol-test-jobs-{lane}", daemon=True).start()


def pytest_sessionfinish(session):
    for job in _JOBS.values():
        for proc in job.procs:
            if proc.poll() is None:
                proc.kill()
                proc.wait()


@background_job("kernels", consumer="test_warm_all_compiles_every_kernel", order=0, lane=1)
def _compile_every_kernel(job):
    """Compile the CPU kernels that the default picture does not use
    (floatcol.warmup.warm_all: sub-columns, area sampling, translucency, shadows,
    textures, colour fields, the fly engine, ...) into the suite's Numba cache in a
    process of its own, once the first tests have compiled the default picture's
    (which the others call too: waited for, not compiled twice). A test that meets
    one of them meanwhile waits for it there (_wait_for_the_kernels_job): before, each
    such kernel that a test met before the job had compiled it was compiled twice, by
    both (about 60 s of CPU in a clean clone: sub-columns, translucent layers,
    textures, area sampling, ...). Where the cache held the default kernels when the
    tests began it does nothing (not where the first tests have compiled them since);
    where its consumer asks for it first (it alone selected, say), it waits no longer."""
    from floatcol import warmup
    if (_WARM_AT_START[0] if _WARM_AT_START else warmup.kernels_ready()):
        return None
    deadline = time.monotonic() + 600.0
    while not (warmup.kernels_ready() or job.wanted.is_set()) and time.monotonic() < deadline:
        time.sleep(0.5)
    proc = subprocess.Popen([sys.executable, "-m", "floatcol.warmup", "--all"],
                            env=dict(os.environ, FLOATCOL_DRAFT="0"), cwd=ROOT,
                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    job.procs.append(proc)
    _, err = proc.communicate()
    return proc.returncode, err


#: seconds a test waits at most for the kernels job's compile of a kernel (a job that
#: hangs: the test compiles it itself after that)
WAIT_FOR_THE_JOB = 600.0


def _wait_for_the_kernels_job(compile_):
    """Dispatcher.compile, but a kernel that no process has compiled yet (no index in
    Numba's cache) waits while the kernels job's process runs, until that process has
    compiled it: then it is loaded from the cache (or, for a signature the job did not
    compile, compiled here). Numba's compiles are not shared between processes: the
    test and the job compiled such a kernel each, side by side. (Before the job's
    process starts, the tests compile the default picture's kernels themselves.)"""
    kernels = {}

    def compile(self, sig):
        job = _JOBS.get("kernels")
        if job is not None and job.procs and not job.done.is_set():
            if not kernels:
                from floatcol.warmup import every_kernel
                kernels.update((id(k), k) for k in every_kernel().values())
            cache_file = (getattr(getattr(self, "_cache", None), "_cache_file", None)
                          if id(self) in kernels and not self.overloads else None)
            if cache_file is not None:
                deadline = time.monotonic() + WAIT_FOR_THE_JOB
                while not os.path.exists(cache_file._index_path) and not job.done.is_set() \
                        and time.monotonic() < deadline:
                    time.sleep(0.2)
        return compile_(self, sig)
    return compile


def pytest_sessionstart(session):
    from numba.core.dispatcher import Dispatcher
    Dispatcher.compile = _wait_for_the_kernels_job(Dispatcher.compile)

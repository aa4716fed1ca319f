"""Columns are independent: identical arrays for any number of threads."""
import os
import subprocess
import sys

import numpy as np
import pytest

import floatcol as fc

#: the threads of the process that renders every case with one thread and with these
#: (the suite's own processes launch their kernels with one: conftest.SUITE_ENV)
THREADS = max(2, os.cpu_count() or 1)

CASES = [dict(projection="orthographic", method="column"),
         dict(projection="perspective", method="column"),
         dict(projection="perspective", method="horizon", elev=60),
         dict(projection="perspective", antialias=3, sampling="adaptive"),
         dict(projection="orthographic", antialias=2, interpolation="intensity"),
         # shadows: the sweeps (a line per thread) and the lookup (a column per thread)
         dict(projection="orthographic", lightsource=(315, 25), shadows=True),
         dict(projection="perspective", lightsource=(120, 10), shadows=True, antialias=3),
         # soft shadows (the hulls, a line per thread); on the fly (a band of lines per
         # thread, each pixel answered by one)
         dict(projection="orthographic", lightsource=(315, 25), shadows=True, light_radius=3),
         dict(projection="perspective", lightsource=(200, 20), shadows="on-the-fly"),
         # translucency: every layer, a column per thread, lists a band at a time
         dict(projection="orthographic", opacity=0.5),
         dict(projection="perspective", opacity=0.4, lightsource=(315, 25), shadows=True),
         # columns whose curve folds back, traced (kernels/fold.py), opaque and
         # translucent (every crossing of the traced pieces, fold.trace_layers_into)
         dict(projection="perspective", elev=40, azim=-30, dom=(-2.2, 2.2),
              expr="4.9*(sqrt(4 - u**2 - v**2) + sqrt(u**2 + v**2 - 1) - 2)"),
         dict(projection="perspective", elev=40, azim=-30, dom=(-2.2, 2.2), opacity=0.5,
              expr="4.9*(sqrt(4 - u**2 - v**2) + sqrt(u**2 + v**2 - 1) - 2)"),
         # exact area sampling (kernels/area.py)
         dict(projection="perspective", antialias="area"),
         dict(projection="orthographic", antialias="area", elev=50,
              expr="4.9*(sqrt(4 - u**2 - v**2) + sqrt(u**2 + v**2 - 1) - 2)"),
         # perspective planes in SIMD batches (each column's Newton iterations start
         # from the columns before it in its group: column.py guesses_for), at a size
         # the batches are not used otherwise
         dict(projection="perspective", batch=True),
         dict(projection="perspective", batch=True, antialias=3, lightsource=(315, 25),
              shadows=True),
         # objects' shadows (kernels/raster.py occluded_kernel, a column per thread)
         dict(projection="perspective", lightsource=(300, 30), shadows=True,
              objects=[fc.box(-1, 0, 1.5, 1.5, 2), fc.tree(2, -2, 3), fc.pole(0, 2, 3)]),
         # a fly-through over a fractal DEM (test_lod.py's): the level-of-detail engine
         # with area weights, and the ray march
         dict(fly="lod"), dict(fly="march"),
         # ... lit smooth (kernels/normals.py, a tile per thread)
         dict(fly="smooth")]


def render_case(k):
    """CASES[k] rendered at 160x120 ("batch": the SIMD batches at any size; "fly":
    test_lod.py's fly-through by that engine)."""
    from floatcol.passes import geometry
    kw = dict(CASES[k])
    if "fly" in kw:
        from test_lod import _fly_scene
        _, _, hf, fly = _fly_scene(129)
        if kw["fly"] == "march":
            return fc.render(hf, antialias=False, **dict(fly, sampling="march"))
        if kw["fly"] == "smooth":
            return fc.render(hf, smooth_shading=True, **fly)
        return fc.render(hf, antialias="area", **fly)
    batch_min = geometry.BATCH_MIN_SAMPLES
    if kw.pop("batch", False):
        geometry.BATCH_MIN_SAMPLES = 0
    try:
        e, dom = kw.pop("expr", "3*sin(u*cos(v))"), kw.pop("dom", (-5, 5))
        return fc.render(e, u=dom, v=dom, size=(160, 120), **kw)
    finally:
        geometry.BATCH_MIN_SAMPLES = batch_min


#: every case rendered in one process (one process start and kernel load for all,
#: instead of one a case: 16 s of the suite) with NUMBA_NUM_THREADS threads, each case's
#: arrays saved to <folder>/<k>-<threads>.npz; with more than one thread the cases go
#: last to first, so that no buffer of a case can hold what the same case left in it
#: in the other process (a read of memory a kernel did not write differs then)
SCRIPT = """
import os, sys, numpy as np, numba
sys.path.insert(0, sys.argv[2])
from test_threads import CASES, render_case
n = numba.get_num_threads()
assert n == int(os.environ["NUMBA_NUM_THREADS"])
for k in (range(len(CASES)) if n == 1 else reversed(range(len(CASES)))):
    r = render_case(k)
    np.savez(os.path.join(sys.argv[1], f"{k}-{n}.npz"), rgba=r.rgba, intensity=r.intensity,
             side=r.side, depth=r.depth, samples=r.stats["samples"])
"""


@pytest.fixture(scope="module")
def pictures(tmp_path_factory):
    """The folder of SCRIPT's pictures, from a process with one thread and one with
    THREADS."""
    folder = tmp_path_factory.mktemp("threads")
    for n in (1, THREADS):
        env = dict(os.environ, NUMBA_NUM_THREADS=str(n))
        subprocess.run([sys.executable, "-c", SCRIPT, str(folder), os.path.dirname(__file__)],
                       check=True, env=env)
    return folder


@pytest.mark.parametrize("k", range(len(CASES)))
def test_one_thread_equals_all(pictures, k):
    one = np.load(pictures / f"{k}-1.npz")
    every = np.load(pictures / f"{k}-{THREADS}.npz")
    for name in ("rgba", "intensity", "side", "depth", "samples"):
        np.testing.assert_array_equal(one[name], every[name], err_msg=name)


CONCURRENT = """
import sys, threading, numpy as np, numba, floatcol as fc
exprs = ["3*sin(u*cos(v))", "u*v/5", "sin(u) + cos(v)", "exp(-(u*u + v*v)/8)*4"]
kws = [dict(), dict(projection="perspective"), dict(antialias="area", lightsource=(315, 25),
                                                    shadows=True), dict(opacity=0.6)]
alone = [fc.render(e, size=(96, 72), **kw).rgba for e, kw in zip(exprs, kws)]
assert numba.threading_layer() == "workqueue", numba.threading_layer()
same, errors = [], []
def work(k):
    try:
        for _ in range(6):
            same.append(np.array_equal(fc.render(exprs[k], size=(96, 72), **kws[k]).rgba,
                                       alone[k]))
    except Exception as exc:
        errors.append(repr(exc))
threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
for t in threads:
    t.start()
for t in threads:
    t.join()
assert not errors, errors
assert len(same) == 24 and all(same), same
print("ok")
"""


def test_renders_from_several_threads_with_numbas_workqueue_layer():
    """Numba's workqueue threading layer (where neither TBB nor OpenMP loads: a Mac
    without libomp, a slim container) is not thread-safe: two Python threads launching
    parallel kernels at once made it abort the process ("Concurrent access has been
    detected"). Four threads render at once under it (its kernels' launches take one
    lock there, kernels/_jit.py _Exclusive): every picture as rendered alone."""
    env = dict(os.environ, NUMBA_THREADING_LAYER="workqueue", FLOATCOL_DRAFT="0",
               NUMBA_NUM_THREADS=str(THREADS))
    res = subprocess.run([sys.executable, "-c", CONCURRENT], env=env, capture_output=True,
                         text=True, timeout=900)
    assert res.returncode == 0 and res.stdout.strip().endswith("ok"), res.stderr[-2000:]


def _short(allocate, part):
    """geometry.allocate with one buffer too small: the horizon records of the last
    column missing ("hrec", read in the column kernel's own loop), or the edge buffer's
    top 8 rows ("ebuf", written inside render_column, which the kernel calls through
    its address)."""
    def short(W, H, n_lines, sub_columns):
        gbuf, ebuf, hrec = allocate(W, H, n_lines, sub_columns)
        if part == "hrec":
            return gbuf, ebuf, np.empty((W - 1,) + hrec.shape[1:])
        return gbuf, np.zeros(ebuf.shape[:2] + (H - 8, ebuf.shape[3]), ebuf.dtype), hrec
    return short


@pytest.mark.parametrize("part", ["hrec", "ebuf"])
@pytest.mark.parametrize("projection", ["orthographic", "perspective"])
def test_an_index_out_of_range_in_a_kernels_loop_is_an_index_error(monkeypatch, part,
                                                                   projection):
    """The suite's bounds checks (conftest.SUITE_ENV) reach the test from inside a
    kernel's parallel loop, in the picture's last column too: the suite launches its
    kernels with one thread (conftest.SUITE_ENV; in another thread's share of the loop
    Numba drops the exception and skips the rest of the share, numba#2811), and the
    launcher raises Numba's SystemError's cause, the IndexError (_jit._Exclusive)."""
    import numba
    assert numba.get_num_threads() == 1
    from floatcol.passes import geometry
    monkeypatch.setattr(geometry, "allocate", _short(geometry.allocate, part))
    with pytest.raises(IndexError):
        fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(64, 48),
                  projection=projection)


def test_row_blocks_are_spread_over_the_threads():
    """kernels/shade.py spread: iteration p of a loop over n blocks of rows takes block
    p s mod n, a permutation of the blocks (each written once: the same picture, as
    test_one_thread_equals_all checks), whose first half takes blocks from both halves
    of the picture (a fly-through's nearly empty sky is not one thread's share)."""
    from floatcol.kernels.shade import spread, spread_stride
    for n in range(1, 400):
        s = spread_stride(n)
        order = [spread(p, n, s) for p in range(n)]
        assert sorted(order) == list(range(n)), n
        if n >= 8:
            low = sum(b < n // 2 for b in order[:n // 2])
            assert 0.3 * (n // 2) <= low <= 0.7 * (n // 2), (n, low)

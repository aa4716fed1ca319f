"""The buffer pool (floatcol/_pool.py): a render reuses a buffer of an earlier one only
when nothing refers to it any more; results that are still held never change."""
import threading

import numpy as np
import pytest

import floatcol as fc
from floatcol import _pool

E1 = "3*sin(u*cos(v))"
E2 = "u*v/5"
KW = dict(u=(-5, 5), v=(-5, 5), size=(320, 240))


@pytest.fixture
def small_pool(monkeypatch):
    """Pool the buffers of 320x240 renders too (normally only those of 1 MiB on)."""
    monkeypatch.setattr(_pool, "MIN_BYTES", 1 << 16)
    _pool.clear()
    yield
    _pool.clear()


def _arrays(r):
    return {"rgba": r.rgba, "intensity": r.intensity, "side": r.side, "depth": r.depth,
            "gbuffer": r.gbuffer, "_gbuf": r._gbuf}


def test_held_results_are_never_overwritten(small_pool):
    r1 = fc.render(E1, **KW)
    before = {k: a.copy() for k, a in _arrays(r1).items()}
    r2 = fc.render(E2, **KW)
    r3 = fc.render(E1, elev=-40, **KW)
    for k, a in _arrays(r1).items():
        assert np.array_equal(a, before[k], equal_nan=True), k
        assert not np.shares_memory(a, _arrays(r2)[k]), k
        assert not np.shares_memory(a, _arrays(r3)[k]), k
    # and the later renders are right: the same as without the pool
    for r, expr, kw in ((r2, E2, {}), (r3, E1, {"elev": -40})):
        _pool.clear()
        fresh = fc.render(expr, **kw, **KW)
        for k, a in _arrays(fresh).items():
            if k == "_gbuf":
                continue                # set only where a surface is seen: gbuffer
            assert np.array_equal(a, _arrays(r)[k], equal_nan=True), k


def test_intensity_and_depth_read_late_are_those_of_their_render(small_pool):
    # a Render computes them from its G-buffer when first read: other renders, and
    # their own intensity and depth (pooled), must not have touched what it reads
    r1 = fc.render(E1, **KW)
    r2 = fc.render(E2, **KW)
    r2.intensity, r2.depth
    del r2
    r3 = fc.render(E1, elev=-40, **KW)
    r3.intensity
    late = r1.intensity.copy(), r1.depth.copy()
    _pool.clear()
    fresh = fc.render(E1, **KW)
    assert np.array_equal(late[0], fresh.intensity, equal_nan=True)
    assert np.array_equal(late[1], fresh.depth)
    assert not np.shares_memory(r1.intensity, r3.intensity)
    assert (r1.side != 0).any() and np.isnan(late[0][r1.side == 0]).all()
    assert np.isfinite(late[0][r1.side != 0]).all() and np.isinf(late[1][r1.side == 0]).all()


def test_a_view_keeps_its_buffer(small_pool):
    r1 = fc.render(E1, **KW)
    rgba = r1.rgba                  # a pooled buffer
    g = r1._gbuf[..., 0]            # a view of the G-buffer
    before = rgba.copy(), g.copy()
    del r1
    r2 = fc.render(E2, **KW)
    assert np.array_equal(rgba, before[0]) and np.array_equal(g, before[1], equal_nan=True)
    assert not np.shares_memory(rgba, r2.rgba) and not np.shares_memory(g, r2._gbuf)


def test_released_buffers_are_reused(small_pool):
    r1 = fc.render(E1, **KW)
    address = r1._gbuf.ctypes.data
    del r1
    r2 = fc.render(E2, **KW)
    assert r2._gbuf.ctypes.data == address
    assert _pool.pooled_bytes() > 0
    _pool.clear()
    assert _pool.pooled_bytes() == 0


def test_concurrent_renders_of_one_size(small_pool):
    """Renders in several Python threads (the kernels release the GIL) each get their
    own buffers: every picture equals the one rendered alone."""
    exprs = [E1, E2, "sin(u)+cos(v)", "exp(-(u*u+v*v)/8)*3"]
    alone = [fc.render(e, **KW).rgba.copy() for e in exprs]
    got = [None] * len(exprs)

    def work(i):
        for _ in range(3):
            got[i] = fc.render(exprs[i], **KW).rgba

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(exprs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for i in range(len(exprs)):
        assert np.array_equal(got[i], alone[i]), exprs[i]


def test_no_stale_values_leak_through_the_accessors(small_pool):
    """The G-buffer is written only where a surface is seen; a reused buffer holds an
    earlier render's values elsewhere, which u, v, w, normal and gbuffer must hide."""
    r1 = fc.render(E1, elev=60, **KW)            # covers much of the picture
    del r1
    r2 = fc.render("exp(-u*u-v*v)", u=(-1, 1), v=(-1, 1), size=KW["size"], scale=40)
    none = r2.side == 0
    assert 0.3 < none.mean() < 0.97
    for a in (r2.u, r2.v, r2.w, r2.normal[..., 0]):
        assert np.isnan(a[none]).all() and np.isfinite(a[~none]).all()
    g = r2.gbuffer                                # (W, H, G_SIZE), rows from the bottom
    assert np.array_equal(np.isnan(g[..., 0]).T[::-1], none)


@pytest.mark.parametrize("kw", [dict(), dict(projection="perspective", elev=20),
                                dict(antialias=3), dict(method="horizon", lines=12)])
def test_buffers_full_of_garbage_change_nothing(monkeypatch, kw):
    """Every buffer a render takes from the pool is written before it is read where it
    matters: the edge buffer's coverage planes, kept only where a pixel is flagged
    (kernels/coverage.py), and the G-buffer, written only where a surface is seen. A
    pool that hands out buffers full of garbage (finite, NaN) must give the picture of
    fresh memory, bit for bit."""
    monkeypatch.setattr(_pool, "MIN_BYTES", 1 << 16)
    _pool.clear()
    args = dict(u=(-5, 5), v=(-5, 5), size=(160, 120), **kw)
    clean = fc.render(E1, **args)
    for junk in (0.37, np.nan, 9.0):
        real_empty = np.empty

        def dirty(shape, dtype, junk=junk):
            a = real_empty(shape, dtype)
            a[...] = junk if np.dtype(dtype).kind == "f" else 77
            return a

        monkeypatch.setattr(_pool, "empty", dirty)
        r = fc.render(E1, **args)
        for name in ("rgba", "intensity", "side", "depth"):
            assert np.array_equal(getattr(r, name), getattr(clean, name), equal_nan=True), \
                (junk, name)
        assert np.array_equal(r.gbuffer, clean.gbuffer, equal_nan=True), junk
    _pool.clear()

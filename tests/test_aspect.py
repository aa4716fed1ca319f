"""aspect: the picture's box, as matplotlib's 3-D axes (render's aspect and box).

Bounds measured on 2026-12-02 at 160x120, shading="lambert", default corrections:
the stretched surface against the ray caster of the stretched expression gave
100 % agreement and 72.89 / 72.02 / 69.68 dB (the three views below), like the
unstretched suite of test_reference.py; the batch evaluator (SIMD) and the scalar
path gave bit-identical pictures, and so did the kernels' stretch and sympy's
(the expression rewritten by hand).
"""
import math
import sys

import numpy as np
import pytest

import floatcol as fc
from conftest import matplotlib_agrees, reference_for
from reference import bilinear_surface, psnr

F = "0.05*sin(u)*cos(2*v)"         # 0.1 high over a 6 x 3 domain: flat in true proportions
U, V = (-3.0, 3.0), (-1.5, 1.5)


def stretched(box):
    """F with u, v, w stretched by box = (a, b, c), written out for sympy."""
    a, b, c = box
    return f"{c!r}*0.05*sin(u/{a!r})*cos(2*v/{b!r})", (U[0] * a, U[1] * a), (V[0] * b, V[1] * b)


def test_auto_box_is_matplotlibs_4_4_3():
    r = fc.render(F, U, V, size=(80, 60), aspect="auto")
    a, b, c = r.stats["box"]
    # u keeps its units; v's 3 units fill as much as u's 6; w's range (about 0.1, the
    # fit grid's) fills 3/4 of that
    assert (a, b) == (1.0, 2.0)
    assert c * 0.1 == pytest.approx(0.75 * 6.0, rel=0.01)
    assert fc.render(F, U, V, size=(80, 60)).stats["box"] == (1.0, 1.0, 1.0)   # "equal"
    a, b, c = fc.render(F, U, V, size=(80, 60), aspect="equalxy").stats["box"]
    assert (a, b) == (1.0, 1.0) and c * 0.1 == pytest.approx(0.75 * 6.0, rel=0.01)
    a, b, c = fc.render(F, U, V, size=(80, 60), aspect=(1, 1, 1)).stats["box"]
    assert (a, b) == (1.0, 2.0) and c * 0.1 == pytest.approx(6.0, rel=0.01)


@pytest.mark.parametrize("proj,elev,azim,min_psnr", [
    ("orthographic", 30, 20, 69.0),        # measured 72.89 dB
    ("perspective", 25, -40, 69.0),        # 72.02
    ("orthographic", -20, 130, 66.0),      # 69.68
])
def test_stretched_surface_matches_the_ray_caster(proj, elev, azim, min_psnr):
    """The picture is that of the stretched function: the ray caster, given the
    expression rewritten with the render's box, sees the same surface."""
    r = fc.render(F, U, V, size=(160, 120), elev=elev, azim=azim, projection=proj,
                  shading="lambert", aspect="auto")
    g, gu, gv = stretched(r.stats["box"])
    ref = reference_for(r, g, gu, gv, elev, azim, proj)
    assert (r.side == ref.side).mean() >= 0.9999
    assert psnr(r.intensity, ref.intensity) >= min_psnr


def test_seen_points_stay_in_the_surfaces_units():
    r = fc.render(F, U, V, size=(160, 120), aspect="auto", projection="perspective")
    m = r.side != 0
    u, v, w = r.u[m], r.v[m], r.w[m]
    assert U[0] - 1e-3 <= u.min() and u.max() <= U[1] + 1e-3
    assert V[0] - 1e-3 <= v.min() and v.max() <= V[1] + 1e-3
    # w = f(u, v) at each seen point (float32 G-buffer: measured 1.8e-5)
    assert np.abs(w - 0.05 * np.sin(u) * np.cos(2 * v)).max() < 1e-4
    lo, hi = r.stats["w_limits"]             # the colormap's range, in f's units
    assert -0.05 <= lo < -0.045 and 0.045 < hi <= 0.05
    r2 = fc.render(F, U, V, size=(160, 120), aspect="auto", vmin=-0.2, vmax=0.1)
    assert r2.stats["w_limits"] == (-0.2, 0.1)


def test_center_is_in_the_surfaces_units():
    """A centre given in f's units lands at the picture's centre."""
    r = fc.render(F, U, V, size=(161, 121), aspect="auto", center=(1.0, 0.5, 0.0), scale=20)
    a, b, c = r.stats["box"]
    col, row = r.view.project(1.0 * a, 0.5 * b, 0.0 * c)
    assert col == pytest.approx(80.0) and row == pytest.approx(60.0)


def test_batch_and_scalar_paths_stretch_alike(monkeypatch):
    """Orthographic pictures this big evaluate f in SIMD batches (column._batch_planes
    stretches the batch), smaller ones one point at a time (sample.surface_eval)."""
    kw = dict(size=(1024, 768), aspect="auto", elev=30, azim=20)
    batched = fc.render(F, U, V, **kw)
    render_module = sys.modules["floatcol.passes.geometry"]  # the column pass
    monkeypatch.setattr(render_module, "BATCH_MIN_SAMPLES", 10 ** 12)
    scalar = fc.render(F, U, V, **kw)
    assert (batched.side == scalar.side).mean() >= 0.9999
    assert np.abs(batched.rgba.astype(int) - scalar.rgba).max() <= 1
    m = (batched.side != 0) & (scalar.side != 0)
    assert np.abs(batched.normal[m] - scalar.normal[m]).max() < 1e-5
    # and the kernels' stretch draws what sympy's does
    g, gu, gv = stretched(batched.stats["box"])
    by_hand = fc.render(g, gu, gv, size=(1024, 768), elev=30, azim=20)
    assert (batched.side == by_hand.side).mean() >= 0.9999
    assert np.abs(batched.rgba.astype(int) - by_hand.rgba).max() <= 1


def test_heightfield_stretches_its_grid():
    rng = np.random.default_rng(3)
    z = 0.01 * rng.random((12, 20))
    hf = fc.HeightField(z, u=(0, 19), v=(0, 11))
    r = fc.render(hf, size=(160, 120), aspect="auto", elev=40)
    a, b, c = r.stats["box"]
    assert a == 1.0 and b == pytest.approx(19 / 11)
    f, _, _ = bilinear_surface(z, (0, 19), (0, 11))
    m = r.side != 0
    assert m.mean() > 0.3
    # the G-buffer's u, v, w are interpolated between samples, across the grid's kinks:
    # measured 4.9e-5 off the bilinear height (z spans 0.01; unstretched it would be
    # c = 1521 times that)
    assert np.abs(r.w[m] - f(r.u[m], r.v[m])).max() < 2e-4


def test_matplotlibs_axes3d_box():
    """plot_surface's default box is matplotlib's: the corners of the data box
    projected by matplotlib's own Axes3D camera (orthographic, default box aspect,
    limits the ranges of x, y and f) and by floatcol's View agree up to scale and
    shift."""
    # 50 x y over [-1, 1] x [-2, 2]: f's range [-100, 100], reached at the corners
    corners = np.array([[-1.0, 1.0, 1.0, -1.0] * 2, [-2.0, -2.0, 2.0, 2.0] * 2,
                        [-100.0] * 4 + [100.0] * 4])
    for elev, azim in [(30, -60), (45, 30), (20, 160)]:
        p = fc.plot_surface("50*x*y", ("x", -1, 1), ("y", -2, 2), elev=elev, azim=azim,
                            proj_type="ortho", size=(200, 200))
        r = p.draw()
        in_box = corners * np.array(r.stats["box"])[:, None]
        assert matplotlib_agrees(r.view, corners, in_box, [(-1, 1), (-2, 2), (-100, 100)],
                                 elev, azim), (elev, azim)


def test_several_surfaces_share_one_box():
    items = [("u**2 + v**2", (-10, 10), (-10, 10)), ("100 - u**2", (-10, 10), (-10, 10))]
    r = fc.render_many(items, size=(120, 90), aspect="auto")
    # the union of the ranges: 0 to 200 over 20 units of u
    assert r.stats["box"][2] == pytest.approx(0.75 * 20 / 200, rel=0.01)
    assert set(np.unique(r.stats["surface"])) == {-1, 0, 1}
    p = fc.plot_surface(["x**2 + y**2", "100 - x**2"], size=(120, 90))
    assert p.draw().stats["box"] == r.stats["box"]


def test_a_clip_keeps_one_box():
    """A growing bump: the box comes from all frames' range, not each frame's."""
    anim = fc.animate("t*exp(-(x^2 + y^2))", ("x", -2, 2), ("y", -2, 2), t=(0.1, 1),
                      frames=3, size=(60, 45), endpoint=True, progress=False)
    box = anim.stats["camera"]["box"]
    assert box[2] == pytest.approx(0.75 * 4 / 1.0, rel=0.02)      # range about 0 .. 1
    first = fc.plot_surface("0.1*exp(-(x^2 + y^2))", ("x", -2, 2), ("y", -2, 2),
                            size=(60, 45), **anim.stats["camera"])
    assert np.abs(first.rgba.astype(int) - anim.frames[0]).max() <= 1


@pytest.mark.parametrize("kw,needle", [
    (dict(aspect="cube"), "aspect must be one of"),
    (dict(aspect=(1, 0, 1)), "positive"),
    (dict(aspect=(1, 1)), "box proportions"),
    (dict(box=(1, -1, 1)), "positive"),
    (dict(box="big"), "stretch factors"),
])
def test_bad_aspect_names_what_to_fix(kw, needle):
    with pytest.raises(ValueError, match=needle):
        fc.render(F, U, V, size=(40, 30), **kw)


@pytest.mark.parametrize("expr", ["1e300*u", "exp(100*u)", "1e-300*u"])
@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
def test_huge_and_tiny_heights_fill_the_box(expr, proj):
    """f finite but far beyond the domain's size (up to 1e300): no overflow, no
    warning; in true proportions a sliver narrower than a pixel, in the box a
    picture."""
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        equal = fc.render(expr, U, V, size=(80, 60), projection=proj)
        auto = fc.render(expr, U, V, size=(80, 60), projection=proj, aspect="auto")
    if expr != "1e-300*u":
        assert (equal.side != 0).mean() == 0.0
    assert (auto.side != 0).mean() > 0.2


def test_a_flat_surface_keeps_its_height():
    assert fc.render("0*u + 2", U, V, size=(40, 30), aspect="auto").stats["box"][2] == 1.0
    assert math.isfinite(fc.render("exp(40*u)", U, V, size=(40, 30),
                                   aspect="auto").stats["box"][2])

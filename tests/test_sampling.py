"""Locally adaptive sampling (Gordon section 6.3) against the ray caster."""
import numpy as np
import pytest

import floatcol as fc
from conftest import reference_for, render_with_switch_off
from reference import psnr

TERRAIN = "0.3*sin(u)*cos(0.7*v) + 0.1*sin(3*u + v)"
FLY = dict(u=(-30, 30), v=(-30, 30), size=(160, 120), elev=25, azim=20, shading="lambert",
           projection="perspective", focal_length=0.5)


def test_adaptive_planes_spare_samples_far_away_and_keep_the_picture():
    """A low flight over a wide terrain: far planes need not be a near pixel apart."""
    uni = fc.render(TERRAIN, sampling="uniform", **FLY)
    ada = fc.render(TERRAIN, sampling="adaptive", **FLY)
    ref = reference_for(uni, TERRAIN, FLY["u"], FLY["v"], 25, 20, "perspective")
    # measured at 160x120: 55.7 dB uniform, 50.9 dB adaptive; side agreement 100 %
    assert psnr(ada.intensity, ref.intensity) >= 47.0
    assert (ada.side == ref.side).mean() >= 0.9995
    # the saving grows with the resolution: measured 0.83 of the samples at 160x120,
    # 0.42 at 640x480 (0.37 at 800x600); since the perspective Newton iteration starts
    # on a parabola (2026-11-23), which spares more evaluations between evenly spaced
    # planes, 0.54 at 640x480 (173677 of 322140 evaluations)
    big = dict(FLY, size=(640, 480))
    n_uni = fc.render(TERRAIN, sampling="uniform", **big).stats["samples"]
    n_ada = fc.render(TERRAIN, sampling="adaptive", **big).stats["samples"]
    assert n_ada <= 0.6 * n_uni


def test_adaptive_planes_refine_where_the_normal_turns_fast():
    """Ripples: fewer samples on the flat rim, more across the crests; the picture
    stays close to the ray caster (measured 2026-11-23: 74.36 dB uniform, 62.47 dB
    adaptive with 0.66 of the samples, both 100 % agreement; before the column passes
    looked between planes that both miss the domain, 50.14 and 49.91 dB)."""
    expr = "2*exp(-(u**2+v**2))*cos(3*sqrt(u**2+v**2))"
    kw = dict(u=(-3, 3), v=(-3, 3), size=(160, 120), elev=25, azim=40, shading="lambert",
              projection="perspective")
    uni = fc.render(expr, **kw)
    ada = fc.render(expr, sampling="adaptive", **kw)
    ref = reference_for(uni, expr, (-3, 3), (-3, 3), 25, 40, "perspective")
    assert psnr(ada.intensity, ref.intensity) >= 60.0
    assert (ada.side == ref.side).mean() >= 0.99999
    assert ada.stats["samples"] <= 0.8 * uni.stats["samples"]


def test_line_drawings_keep_their_planes():
    kw = dict(u=(-5, 5), v=(-5, 5), size=(120, 90), method="horizon", projection="perspective")
    a = fc.render("3*sin(u*cos(v))", sampling="adaptive", **kw)
    b = fc.render("3*sin(u*cos(v))", **kw)
    assert np.array_equal(a.rgba, b.rgba)


def test_sampling_must_be_known():
    with pytest.raises(ValueError, match="sampling"):
        fc.render("u", size=(8, 8), sampling="fast")


# A perspective column samples only the planes between the last and the first that
# surely miss the domain (column._pass_planes, vp's VP_CLIP): it must change no
# picture and no count of evaluations, only the work.
CLIP_CASES = [
    ("3*sin(u*cos(v))", 5, dict(elev=30, azim=-110)),
    ("sqrt(1 - u**2 - v**2)", 1.2, dict(elev=20, azim=35, antialias=3)),
    ("u**3 - 3*u*v**2", 1.5, dict(elev=89.5, azim=10, method="horizon")),
    ("exp(-(u**2 + v**2))*cos(3*sqrt(u**2 + v**2))", 3, dict(elev=1, azim=75,
                                                            focal_length=0.7)),
    ("Heaviside(u)*2 + v", 3, dict(elev=-15, azim=160, placement="paper")),
    ("tan(u*v)", 2, dict(elev=45, azim=-20, shading="lambert")),
]


@pytest.mark.parametrize("expr,d,view", CLIP_CASES)
def test_skipping_planes_a_column_surely_misses_changes_nothing(expr, d, view, monkeypatch):
    from floatcol.kernels.layout import VP_CLIP
    kw = dict(u=(-d, d), v=(-0.7 * d, d), size=(150, 110), projection="perspective", **view)
    r = fc.render(expr, **kw)
    r0 = render_with_switch_off(monkeypatch, VP_CLIP, expr, **kw)   # every plane
    assert r.stats["samples"] == r0.stats["samples"]
    for k in ("rgba", "side", "intensity", "depth"):
        assert np.array_equal(getattr(r, k), getattr(r0, k), equal_nan=True), k


@pytest.mark.parametrize("elev,azim", [(30, -110), (5, 0), (60, 90), (-20, 45), (89.5, 200)])
def test_a_columns_range_of_planes_holds_every_plane_that_may_meet_it(elev, azim):
    """column._column_t_range against asking _may_meet_domain plane by plane, 4000
    planes over the whole range of t, for columns across the picture, its middle
    and beyond its edges: every plane that may meet lies inside the range, and the
    range is tight (a plane within 1 % of its length of either end may meet)."""
    from floatcol.kernels.column import _column_t_range, _may_meet_domain
    from floatcol.kernels.layout import VP_T0, VP_T1
    from floatcol.kernels.sample import column_x0
    r = fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-3, 5), size=(120, 90), elev=elev,
                  azim=azim, projection="perspective")
    vp = r.view.params()
    t0, t1 = vp[VP_T0] - 1.0, vp[VP_T1] + 1.0
    ts = np.linspace(t0, t1, 4000)
    empty = 0
    for c in list(range(-60, 181, 7)) + [59.5]:
        x0 = column_x0(vp, c) if c != 59.5 else 0.0
        lo, hi = _column_t_range(vp, x0)
        meets = np.array([_may_meet_domain(vp, x0, t) for t in ts])
        if not meets.any():
            assert not lo <= hi
            empty += 1
            continue
        tol = 1e-9 * (t1 - t0)
        assert lo - tol <= ts[meets].min() and ts[meets].max() <= hi + tol
        ends = np.abs(ts - lo) <= 0.01 * (hi - lo) + 2 * (ts[1] - ts[0])
        assert meets[ends & (ts >= lo)].any()
        ends = np.abs(ts - hi) <= 0.01 * (hi - lo) + 2 * (ts[1] - ts[0])
        assert meets[ends & (ts <= hi)].any()
    assert empty > 0        # columns beyond the picture's edges meet nothing

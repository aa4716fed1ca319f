"""Perspective columns whose curve folds back in t are traced (kernels/fold.py).

Bounds measured on 2026-12-02 at 200x160, shading="lambert", against the ray caster
with 4000 march steps (finer than its default, for the vertical rims): the annulus
below, stretched 4.9 times in height, elev 40, azim -30: 99.14 % side agreement and
26.56 dB with the folds traced, 93.88 % and 20.23 dB without (one point per plane:
streaks of the wrong side, the outer wall missed at the picture's sides).
"""
import numpy as np

import floatcol as fc
from conftest import render_with_switch_off
from floatcol.kernels import layout as L
from reference import numpy_surface, psnr, raycast

ANNULUS = "4.9*(sqrt(4 - u**2 - v**2) + sqrt(u**2 + v**2 - 1) - 2)"
KW = dict(u=(-2.2, 2.2), v=(-2.2, 2.2), size=(200, 160), elev=40, azim=-30,
          projection="perspective", shading="lambert")


def _reference(r):
    vw = r.view
    return raycast(numpy_surface(ANNULUS), KW["u"], KW["v"], KW["size"], KW["elev"],
                   KW["azim"], "perspective", vw.d1, vw.d2, vw.scale, center=vw.center,
                   steps=4000)


def test_a_wall_steeper_than_the_column_plane_is_drawn(monkeypatch):
    r = fc.render(ANNULUS, **KW)
    ref = _reference(r)
    assert (r.side == ref.side).mean() >= 0.987            # measured 0.99144
    assert psnr(r.intensity, ref.intensity) >= 24.5         # measured 26.56
    plain = render_with_switch_off(monkeypatch, L.VP_FOLD, ANNULUS, **KW)
    assert (plain.side == ref.side).mean() < 0.95           # measured 0.93881
    assert psnr(plain.intensity, ref.intensity) < 22.0      # measured 20.23


def test_a_traced_column_is_shaded_as_traced_where_both_agree():
    """Where the column pass and the traced curve see the same surface at the same
    depth, the traced point (exact within a pixel) is kept: the column pass's had
    its normal lerped across the fold (streaks of a lighter shade down the outer
    wall). Pixels where both this render and the ray caster see the same side but
    their intensities differ by more than 0.1: measured 74 before, 0 after (PSNR
    26.08 -> 26.56 dB)."""
    r = fc.render(ANNULUS, **KW)
    ref = _reference(r)
    both = (r.side == ref.side) & (r.side != 0)
    assert both.sum() > 14000                               # measured 14830
    wrong = both & (np.abs(np.nan_to_num(r.intensity) - np.nan_to_num(ref.intensity)) > 0.1)
    assert wrong.sum() <= 5                                 # measured 0


def test_columns_without_folds_are_untouched(monkeypatch):
    """The paper's function folds nowhere: the same picture with and without."""
    kw = dict(u=(-5, 5), v=(-5, 5), size=(160, 120), projection="perspective", elev=30,
              azim=20)
    traced = fc.render("3*sin(u*cos(v))", **kw)
    plain = render_with_switch_off(monkeypatch, L.VP_FOLD, "3*sin(u*cos(v))", **kw)
    np.testing.assert_array_equal(traced.rgba, plain.rgba)
    assert traced.stats["samples"] == plain.stats["samples"]


def test_orthographic_columns_never_fold():
    """An orthographic column plane is vertical (k = 0): its curve is a graph over t,
    so nothing is traced, whatever the slopes."""
    kw = dict(KW, projection="orthographic")
    r = fc.render(ANNULUS, **kw)
    ref = raycast(numpy_surface(ANNULUS), kw["u"], kw["v"], kw["size"], kw["elev"],
                  kw["azim"], "orthographic", scale=r.view.scale, center=r.view.center,
                  steps=4000)
    assert (r.side == ref.side).mean() >= 0.985            # measured 0.98709 (rims)


def test_traced_points_lie_on_the_surface_where_it_oscillates_wildly():
    """y sin(1/x) near x = 0: its partials blow up, the columns are traced, and the
    corrector's first-order test (|G| within a tolerance times |grad G|) accepted
    points far off the surface there: lines across the whole picture. A traced point
    now also has f within 2 pixels of its height (fold.S_TOL_PX; half a pixel cost
    the stretched annulus 0.05 dB at its rims). Every seen pixel must lie
    inside the picture of the box [-1, 1]^2 x [-1, 1] that holds the surface.
    Measured (400x300, aspect equal): seen rows 0-299 before, 36-291 after; the box's
    rows 25.4-302.3."""
    import itertools
    r = fc.render("v*sin(1/u)", u=(-1, 1), v=(-1, 1), size=(400, 300), elev=30, azim=-30,
                  projection="perspective")
    corners = np.array(list(itertools.product((-1, 1), repeat=3)), float).T
    col, row = r.view.project(corners[0], corners[1], corners[2])
    rows, cols = np.nonzero(r.side)
    assert len(rows) > 20000                                # measured 30140
    assert rows.min() >= np.floor(row.min()) - 1 and rows.max() <= np.ceil(row.max()) + 1
    assert cols.min() >= np.floor(col.min()) - 1 and cols.max() <= np.ceil(col.max()) + 1


def test_a_piece_born_at_a_fold_beside_the_domains_edge_is_drawn():
    """Near the domain's edge a piece of the curve in Pi can be born at a fold in t
    while its other branch runs out of the domain: the planes between hold two roots
    inside the domain (g has the same sign at the ends of the line's part inside, so
    the sample was dropped as outside), and the column pass never samples the folding
    branch that would mark the column. A run whose bisected edge lies inside the
    domain marks it, and the tracer seeds at the first row of every piece the column
    pass saw. Measured (2026-12-06, 480x270, the ray caster's default 1500 steps):
    57.51 dB and 2 pixels of the wrong side (67.97 dB and 2 with the jump's tests
    below); before, 36.38 dB and 180 (one-column streaks of background or of a
    farther surface down the picture)."""
    e = "3*sin(u*cos(v))"
    kw = dict(u=(-5, 5), v=(-5, 5), size=(480, 270), elev=50, azim=120,
              projection="perspective", shading="lambert")
    r = fc.render(e, **kw)
    vw = r.view
    ref = raycast(numpy_surface(e), kw["u"], kw["v"], kw["size"], kw["elev"], kw["azim"],
                  "perspective", vw.d1, vw.d2, vw.scale, center=vw.center)
    assert (r.side != ref.side).sum() <= 12                 # measured 2
    assert psnr(r.intensity, ref.intensity) >= 60.0         # measured 67.97


def _paper_function_against_ray_caster(size, elev, azim):
    e = "3*sin(u*cos(v))"
    kw = dict(u=(-5, 5), v=(-5, 5), size=size, elev=elev, azim=azim,
              projection="perspective", shading="lambert")
    r = fc.render(e, **kw)
    vw = r.view
    ref = raycast(numpy_surface(e), kw["u"], kw["v"], size, elev, azim, "perspective",
                  vw.d1, vw.d2, vw.scale, center=vw.center)
    return r, ref


def test_two_pieces_of_the_curve_are_not_joined_across_a_jump():
    """A wall's halving leaves a tight bracket whose rows jump though f does not: in
    perspective its two sides may lie on two pieces of the curve in Pi (the sample's
    Newton iteration went over to another one), and the span between them was a band
    of surface where there is none (33 pixels in one column near the corner u = v =
    -5, where the ray caster sees background). G = f - cw - s at the middle height on
    the bracket's two sides tells them apart (column._joined). Measured (2026-12-06):
    71.74 dB, no pixel of the wrong side; before, 46.74 dB and 33."""
    r, ref = _paper_function_against_ray_caster((512, 384), 30, -60)
    assert (r.side != ref.side).sum() <= 3                  # measured 0
    assert psnr(r.intensity, ref.intensity) >= 66.0         # measured 71.74


def test_a_halving_plane_that_meets_no_surface_ends_the_run():
    """Where a plane in the middle of a wall's halving meets no surface (the curve in
    Pi left the domain between the span's ends, or ended at a fold), the run ends at
    its edge after the first end and a new one starts before the second
    (column._break_run); the span had been painted whole. Measured (2026-12-06,
    240x180): 48.44 dB; 39.00 without the run's break, 34.60 before this and the
    tracer's seeds and marks above."""
    r, ref = _paper_function_against_ray_caster((240, 180), 50, 120)
    assert (r.side != ref.side).sum() <= 10                 # measured 5
    assert psnr(r.intensity, ref.intensity) >= 46.0         # measured 48.44


def test_a_trace_that_runs_over_a_traced_piece_stops():
    """At a corner of the curve in Pi (the dome of sqrt(Max(0, 4 - u^2 - v^2)) meets
    its floor with a vertical tangent) the tangent's sign is a toss-up, and a trace
    could turn back and walk its own piece again, to its cap of steps: a step that
    crosses a plane where a crossing was traced already (fold.RETRACE_PX) ends it.
    Measured (2026-12-06, 320x240): 244 527 evaluations, 1 656 879 without the stop
    (at 1920x1080 5.5 million against 37 million, 158 against 1 308 ms); the picture
    as close to the ray caster as the trace without the stop."""
    e = "sqrt(Max(0, 4 - u**2 - v**2))"
    kw = dict(u=(-2.5, 2.5), v=(-2.5, 2.5), elev=35, azim=30, projection="perspective")
    r = fc.render(e, size=(320, 240), **kw)
    assert r.stats["samples"] < 500_000
    small = fc.render(e, size=(160, 120), shading="lambert", **kw)
    vw = small.view
    ref = raycast(numpy_surface(e), kw["u"], kw["v"], (160, 120), 35, 30, "perspective",
                  vw.d1, vw.d2, vw.scale, center=vw.center)
    assert (small.side != ref.side).sum() <= 4              # measured 0

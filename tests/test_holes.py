"""NaN, infinite or complex values of f are holes: skipped, never painted, no crash."""
import numpy as np
import pytest

import floatcol as fc
from conftest import reference_for

CASES = [("log(u)", (-2, 2), (-2, 2)), ("sqrt(v)", (-2, 2), (-2, 2)),
         ("1/(u - v)", (-2, 2), (-2, 2)), ("u**v", (-2, 2), (-2, 2)),
         ("sqrt(1 - u**2 - v**2)", (-1.5, 1.5), (-1.5, 1.5))]


@pytest.mark.parametrize("expr,u,v", CASES)
@pytest.mark.parametrize("projection", ["orthographic", "perspective"])
@pytest.mark.parametrize("method", ["column", "horizon"])
def test_bad_points_render_without_error(expr, u, v, projection, method):
    r = fc.render(expr, u=u, v=v, size=(120, 90), elev=30, azim=20, projection=projection,
                  method=method)
    assert r.rgba.shape == (90, 120, 4)
    assert (r.side != 0).sum() > 100


@pytest.mark.parametrize("expr,coord", [("log(u)", "u"), ("sqrt(v)", "v"), ("u**v", "u")])
def test_nothing_is_painted_inside_a_hole(expr, coord):
    r = fc.render(expr, u=(-2, 2), v=(-2, 2), size=(120, 90), elev=30, azim=20)
    seen = r.side != 0
    vals = getattr(r, coord)[seen]
    # the hole's edge is found by bisection to 2**-16 of a step
    assert (vals >= -1e-4).mean() > 0.999
    assert vals.min() > -0.05


def test_hole_edges_match_ray_caster():
    expr, u, v = "sqrt(1 - u**2 - v**2)", (-1.5, 1.5), (-1.5, 1.5)
    r = fc.render(expr, u=u, v=v, size=(160, 120), elev=30, azim=20, shading="lambert")
    ref = reference_for(r, expr, u, v, 30, 20, "orthographic")
    # the hemisphere's rim is vertical: measured 99.51 % agreement, the differences on
    # the one-pixel rim where the ray caster's marching grazes the wall
    assert (r.side == ref.side).mean() > 0.993


def test_complex_values_are_holes():
    r = fc.render("sqrt(-1)*u + 1", u=(-1, 1), v=(-1, 1), size=(40, 30))
    assert (r.side == 0).all()
    assert np.isnan(r.intensity).all()


@pytest.mark.parametrize("projection", ["orthographic", "perspective"])
def test_ring_with_two_vertical_rims_matches_ray_caster(projection):
    """An annulus whose inner and outer rims are vertical (f_u, f_v infinite there).
    In perspective, Newton's placement on the column plane used to leave the surface
    at the rims and whole columns went missing; the bracketed fallback finds them.
    Measured agreement: 98.89 % ortho, 99.10 % persp (the rims, which the ray
    caster's marching also grazes)."""
    expr, u = "sqrt(4 - u**2 - v**2) + sqrt(u**2 + v**2 - 1) - 2", (-2.2, 2.2)
    r = fc.render(expr, u=u, v=u, size=(160, 120), elev=30, azim=20, shading="lambert",
                  projection=projection)
    ref = reference_for(r, expr, u, u, 30, 20, projection)
    assert (r.side == ref.side).mean() > 0.985
    # every column the ray caster sees surface in, floatcol does too
    assert ((r.side != 0).any(axis=0) == (ref.side != 0).any(axis=0)).mean() > 0.98

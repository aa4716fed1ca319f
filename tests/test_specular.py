"""Phong highlights: where the analytic half-vector says, as bright as it says."""
import math

import numpy as np
import pytest

import floatcol as fc


def _screen_to_world(view, d):
    """A screen direction (x, y, z) in world (u, v, w): eqs. (1)-(2) inverted."""
    a, b = -math.radians(view.elev), math.radians(view.azim)
    x, y, z = d
    s = y * math.cos(a) + z * math.sin(a)
    t = -y * math.sin(a) + z * math.cos(a)
    return x * math.cos(b) + t * math.sin(b), -x * math.sin(b) + t * math.cos(b), s


@pytest.mark.parametrize("light", [(-0.45, 0.55, -1.0), (0.6, 0.2, -1.0)])
def test_highlight_of_a_sphere_sits_at_the_half_vector(light):
    """On the unit hemisphere the normal at P is P itself, so the highlight of a
    distant light L seen along V = (0, 0, -1) is the point P = H = (L + V)/|L + V|."""
    kw = dict(u=(-1.2, 1.2), v=(-1.2, 1.2), size=(240, 200), elev=35, azim=25,
              upper_color=(0.2, 0.2, 0.2), light=light, shininess=60.0)
    lit = fc.render("sqrt(1 - u**2 - v**2)", specular=0.8, **kw)
    dull = fc.render("sqrt(1 - u**2 - v**2)", specular=0.0, **kw)
    gain = lit.rgba[..., 0].astype(float) - dull.rgba[..., 0]
    row, col = np.unravel_index(np.argmax(gain), gain.shape)
    L = np.array(light) / np.linalg.norm(light)
    H = L + np.array([0.0, 0.0, -1.0])
    H /= np.linalg.norm(H)
    pu, pv, pw = _screen_to_world(lit.view, H)
    want_col, want_row = lit.view.project(pu, pv, pw)
    assert math.hypot(col - want_col, row - want_row) <= 1.5
    # R.V = 1 at the exact point; the nearest pixel centre is within 0.71 px of it,
    # where (R.V)^60 drops by at most 3 %
    assert 0.97 * 0.8 * 255 - 1 <= gain.max() <= 0.8 * 255 + 1
    assert np.array_equal(lit.intensity, dull.intensity, equal_nan=True)   # diffuse only


def test_no_highlight_when_the_light_is_behind_the_seen_side():
    """A plane seen from above, lit from below: the seen side gets no highlight."""
    kw = dict(u=(-1, 1), v=(-1, 1), size=(60, 40), elev=40, upper_color=(0.3, 0.3, 0.3),
              shininess=5.0)
    below = (0.0, -1.0, 0.2)
    lit = fc.render("0*u", light=below, specular=1.0, **kw)
    dull = fc.render("0*u", light=below, specular=0.0, **kw)
    assert np.array_equal(lit.rgba, dull.rgba)


def test_specular_options_are_checked():
    with pytest.raises(ValueError, match="specular"):
        fc.render("u", size=(8, 8), specular=2.0)
    with pytest.raises(ValueError, match="shininess"):
        fc.render("u", size=(8, 8), shininess=0)
    with pytest.raises(ValueError, match="lambert"):
        fc.render("u", size=(8, 8), shading="lambert", specular=0.5)

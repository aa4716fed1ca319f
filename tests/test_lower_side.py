"""lower_color="same": the lower side coloured as the upper side at its height (both
sides alike, as mplot3d colours them), in every pass that colours a side: the
finishing kernel, translucent layers, textures' transparent parts, colour fields,
drafts. The default (a tan lower side) is left as it was."""
import numpy as np
import pytest

import floatcol as fc
from floatcol.color import DEFAULT_LOWER, colormap_lut, to_rgb

#: the saddle from a low elevation: both sides in view
SCENE = dict(expr="u*v/3", u=(-2, 2), v=(-2, 2), size=(120, 90), elev=12, azim=30)


def _render(**kw):
    s = dict(SCENE)
    return fc.render(s.pop("expr"), **s, **kw)


def _interior(r, side):
    """Pixels well inside one side: that side in the pixel and its 8 neighbours,
    opaque."""
    m = r.side == side
    k = m.copy()
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            k &= np.roll(np.roll(m, dy, 0), dx, 1)
    return k & (r.rgba[..., 3] == 255)


def test_the_lower_side_takes_the_colour_map_at_its_height():
    """Unlit (ambient 1, no highlight), a pixel's colour is its side's colour: on the
    lower side with lower_color="same", the colour map's row at its height, as the
    finishing kernel indexes it (against the lut and r.w, computed here)."""
    r = _render(lower_color="same", ambient=1.0, specular=0.0, cmap="plasma")
    lower = _interior(r, -1)
    assert lower.sum() > 300
    lut = colormap_lut("plasma").astype(np.float64)
    lo, hi = r.stats["w_limits"]
    x = (r.w[lower] - lo) / (hi - lo) * (len(lut) - 1)
    want = np.round(lut[np.clip(x, 0, len(lut) - 1).astype(int)] * 255)
    assert np.abs(r.rgba[lower][:, :3] - want).max() <= 1
    # the default: the tan lower side
    d = _render(ambient=1.0, specular=0.0, cmap="plasma")
    tan = np.round(np.array(to_rgb(DEFAULT_LOWER, "lower_color")) * 255)
    assert np.abs(d.rgba[_interior(d, -1)][:, :3] - tan).max() <= 1


@pytest.mark.parametrize("kw", [
    dict(opacity=0.6),                                           # translucent layers
    dict(texture=np.zeros((4, 4, 4))),                           # a transparent texture
    dict(color="u + v", cmap="plasma"),                          # a colour field
    dict(texture=lambda u, v: (u * 0, u * 0, u * 0, u * 0)),     # a transparent function
    dict(color=np.full((5, 5), np.nan)),                         # a field of no values
], ids=["translucent", "texture", "colour field", "texture function", "NaN field"])
def test_every_pass_colours_the_lower_side_alike(kw):
    """With one colour for the upper side (upper_color red), lower_color="same" and
    lower_color="red" draw the same picture in each pass that colours a side (a
    colour field colours both sides from its values either way)."""
    same = _render(upper_color="red", lower_color="same", **kw)
    red = _render(upper_color="red", lower_color="red", **kw)
    assert (same.side < 0).sum() > 300
    np.testing.assert_array_equal(same.rgba, red.rgba)


def test_a_draft_colours_the_lower_side_alike(monkeypatch):
    """A fresh install's draft (passes/draft.py) too."""
    from floatcol import warmup
    monkeypatch.setattr(warmup, "drafting", lambda *a: True)
    same = _render(upper_color="red", lower_color="same")
    red = _render(upper_color="red", lower_color="red")
    assert same.stats["engine"] == "draft" and (same.side < 0).sum() > 300
    np.testing.assert_array_equal(same.rgba, red.rgba)

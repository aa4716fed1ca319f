"""From intensities and sides to RGBA: colormaps, two-sided colours, line drawings."""
from __future__ import annotations

import functools

import numpy as np

DEFAULT_LOWER = "#d9925b"      # the underside: a warm tan, distinct from any sequential cmap
LAMBERT_LOWER = (1.0, 0.78, 0.55)
LINE_UPPER = "#1b2a49"
LINE_LOWER = "#b8322a"


def to_rgb(color, name="color"):
    """An (r, g, b) float triple in [0, 1] from any matplotlib colour spec."""
    if isinstance(color, (tuple, list, np.ndarray)) and len(color) in (3, 4) and all(
            isinstance(c, (int, float, np.number)) and not isinstance(c, bool) for c in color):
        rgb = np.asarray(color[:3], dtype=float)
        if rgb.max() > 1.0:
            rgb = rgb / 255.0
        if (rgb < 0).any() or (rgb > 1).any():
            raise ValueError(f"{name} {color!r} has components outside [0, 1] (or 0..255)")
        return tuple(rgb)
    from matplotlib.colors import to_rgb as mpl_to_rgb
    try:
        return tuple(mpl_to_rgb(color))
    except (ValueError, TypeError):
        raise ValueError(f"{name} {color!r} is not a colour: use a name ('tan'), hex ('#d9925b') "
                         "or an (r, g, b) tuple") from None


def to_rgba8(color, name="background"):
    if color is None:
        return np.array([0, 0, 0, 0], dtype=np.uint8)
    if isinstance(color, (tuple, list)) and len(color) == 4:
        rgb = to_rgb(color[:3], name)
        a = float(color[3])
        a = a / 255.0 if a > 1 else a
    else:
        rgb = to_rgb(color, name)
        a = 1.0
    return np.round(np.array([*rgb, a]) * 255).astype(np.uint8)


def colormap_lut(cmap):
    """(256, 3) float LUT of a matplotlib colormap (a name or a Colormap)."""
    if isinstance(cmap, str):
        return _named_lut(cmap)
    from matplotlib.colors import Colormap
    if not isinstance(cmap, Colormap):
        raise ValueError(f"cmap must be a matplotlib colormap or its name, got {cmap!r}")
    return cmap(np.linspace(0.0, 1.0, 256))[:, :3].astype(np.float32)


@functools.lru_cache(maxsize=32)
def _named_lut(cmap):
    import matplotlib
    try:
        cm = matplotlib.colormaps[cmap]
    except KeyError:
        raise ValueError(f"unknown colormap {cmap!r}: use a matplotlib name such as 'viridis'") from None
    return cm(np.linspace(0.0, 1.0, 256))[:, :3].astype(np.float32)


def extremes(cmap):
    """(under, over): a Colormap's colours for heights below and above its range
    (``cmap.with_extremes(under=..., over=...)``, ``set_under``) where they differ from
    its end colours, else None each (a name's registered map has none)."""
    from matplotlib.colors import Colormap
    if not isinstance(cmap, Colormap):
        return None, None
    try:
        under, over = cmap.get_under(), cmap.get_over()
        lo, hi = cmap(0.0), cmap(1.0)
    except (AttributeError, TypeError, ValueError):
        return None, None
    return (None if np.allclose(under[:3], lo[:3]) else np.asarray(under[:3], dtype=np.float64),
            None if np.allclose(over[:3], hi[:3]) else np.asarray(over[:3], dtype=np.float64))


def bad(cmap):
    """A Colormap's colour for values it cannot map (NaN: ``set_bad``,
    ``with_extremes(bad=...)``) as RGB where it is set to a visible one (alpha > 0),
    else None (matplotlib's default is transparent)."""
    from matplotlib.colors import Colormap
    if not isinstance(cmap, Colormap):
        return None
    try:
        rgba = np.asarray(cmap.get_bad(), dtype=np.float64)
    except (AttributeError, TypeError, ValueError):
        return None
    return rgba[:3] if rgba.shape == (4,) and rgba[3] > 0.0 else None


#: lower_color's word for "as the upper side" (mplot3d colours both sides alike)
SAME = "same"


def side_colors(shading, cmap="viridis", upper_color=None, lower_color=DEFAULT_LOWER):
    """(lut, lower_rgb): the upper side's colour table indexed by height (one row for
    a flat colour) and the lower side's colour; NaN where ``lower_color`` is "same"
    (SAME: the lower side takes the upper side's colour at its height, as mplot3d
    colours both sides; the kernels' shade._side_rgb). The reference model ("lambert")
    is grey above and warm-tinted below, so the two sides stay distinguishable."""
    same = isinstance(lower_color, str) and lower_color.strip().lower() == SAME
    if shading == "lambert":
        lower = np.full(3, np.nan) if same else np.array(LAMBERT_LOWER)
        return np.ones((1, 3), dtype=np.float64), lower
    if upper_color is not None:
        lut = np.array([to_rgb(upper_color, "upper_color")], dtype=np.float64)
    else:
        lut = colormap_lut(cmap).astype(np.float64)
    if same:
        return lut, np.full(3, np.nan)
    return lut, np.array(to_rgb(lower_color, "lower_color"), dtype=np.float64)


def lower_or_upper(lower_rgb, upper_rgb):
    """The lower side's colour: ``lower_rgb``, or where it is "same" (NaN) the upper
    side's ``upper_rgb`` (an array of colours, or one)."""
    lower = np.asarray(lower_rgb, dtype=np.float64)[:3]
    return upper_rgb if np.isnan(lower).any() else lower


def line_rgba(side, background=(255, 255, 255, 255)):
    """A horizon line drawing: dark lines for the upper side, red for the lower."""
    H, W = side.shape
    out = np.empty((H, W, 4), dtype=np.uint8)
    out[:] = to_rgba8(background)
    out[side > 0] = to_rgba8(LINE_UPPER)
    out[side < 0] = to_rgba8(LINE_LOWER)
    return out

"""Lines on the surface, drawn from the G-buffer after the finishing pass (Gordon
6.7's texture idea applied to lines): contour lines of f (or of the colour field) and
wireframe lines at u = const and v = const.

Not geometry: at each pixel where the surface is seen, the field q (w, the colour
field, u or v) and its change to the neighbouring pixels give the distance to the
nearest level in pixels, d = |q - level| / |grad q| (the screen gradient from the
smaller one-sided difference each way, so a silhouette's neighbour across it does not
count); the line covers the pixel by clip(width / 2 + 1/2 - d, 0, 1), which draws it
antialiased, of constant width in pixels at any distance, and only where the surface
itself is seen: a hidden part of a line is never drawn.
"""
from __future__ import annotations

import numpy as np

from .. import color
from .colour import field_values, levels_of, picture_planes


def _screen_gradient(q, seen):
    """|grad q| in units of q per pixel: each way the smaller one-sided difference
    to a seen neighbour (a silhouette's far neighbour is not one), NaN where none."""
    out = np.zeros(q.shape)
    for axis in (0, 1):
        d = np.full(q.shape, np.inf)
        for shift in (1, -1):
            qs = np.roll(q, shift, axis=axis)
            ok = np.roll(seen, shift, axis=axis) & seen
            edge = [slice(None)] * 2
            edge[axis] = slice(0, 1) if shift == 1 else slice(-1, None)
            ok[tuple(edge)] = False
            d = np.minimum(d, np.where(ok, np.abs(q - qs), np.inf))
        out += np.where(np.isfinite(d), d * d, np.nan)
    return np.sqrt(out)


def _coverage(q, seen, levels, width, spacing=None):
    """How much of each pixel the lines q = level cover (0 to 1)."""
    grad = _screen_gradient(q, seen)
    if spacing is not None:                         # levels origin + k spacing
        origin = levels
        k = np.rint((q - origin) / spacing)
        dist = np.abs(q - (origin + k * spacing))
    else:
        lv = np.sort(np.asarray(levels, dtype=np.float64))
        if lv.size == 0:
            return np.zeros(q.shape)
        i = np.clip(np.searchsorted(lv, q), 1, max(lv.size - 1, 1))
        dist = np.abs(q - lv[i - 1])
        if lv.size > 1:
            dist = np.minimum(dist, np.abs(q - lv[i]))
    with np.errstate(divide="ignore", invalid="ignore"):
        px = np.where(grad > 0, dist / grad, np.where(dist == 0, 0.0, np.inf))
    cov = np.clip(width / 2.0 + 0.5 - px, 0.0, 1.0)
    return np.where(seen & np.isfinite(cov), cov, 0.0)


def _over(rgba, cov, rgb):
    """Blend the colour rgb (0-1) over rgba (uint8, in place) by cov."""
    m = cov > 0
    if not m.any():
        return
    a = cov[m][:, None]
    px = rgba[m, :3] / 255.0
    rgba[m, :3] = np.clip((px * (1 - a) + np.asarray(rgb)[:3] * a) * 255.0 + 0.5, 0, 255
                          ).astype(np.uint8)


def contour_levels(contours, lo, hi):
    """The levels of ``contours``: N evenly spaced inside (lo, hi), or the values."""
    if isinstance(contours, bool):
        raise ValueError(f"contours must be a count or a list of levels, got {contours!r}")
    if isinstance(contours, (int, np.integer)):
        if not 1 <= contours <= 1000:
            raise ValueError(f"contours must be a count from 1 to 1000, got {contours}")
        return levels_of(int(contours), lo, hi)
    try:
        lv = np.asarray(contours, dtype=np.float64).ravel()
    except (TypeError, ValueError):
        raise ValueError("contours must be a count or a list of levels (numbers), got "
                         f"{contours!r}") from None
    if lv.size == 0 or lv.size > 10000 or not np.isfinite(lv).all():
        raise ValueError("contours must be 1 to 10000 finite levels")
    return lv


def wire_counts(wireframe):
    """(nu, nv) lines of a wireframe: N both ways, or a pair."""
    vals = wireframe if isinstance(wireframe, (tuple, list)) else (wireframe, wireframe)
    if len(vals) != 2 or any(isinstance(x, bool) or not isinstance(x, (int, np.integer))
                             or not 2 <= x <= 10000 for x in vals):
        raise ValueError("wireframe must be a count of lines from 2 to 10000, or (nu, nv), "
                         f"got {wireframe!r}")
    return int(vals[0]), int(vals[1])


def overlay_pass(rgba, material, source, geom, W, box, w_limits, c_limits, domain):
    """Draw the material's contour and wireframe lines into rgba (in place)."""
    u, v, w, side = picture_planes(geom, W)
    seen = side != 0.0
    if not seen.any():
        return
    a, b, c = box
    u, v, w = u / a, v / b, w / c
    if material.wireframe is not None:
        nu, nv = wire_counts(material.wireframe)
        rgb = color.to_rgb(material.edgecolor, "edgecolor")
        (ua, ub), (va, vb) = domain
        for q, lo, hi, n in ((u, ua, ub, nu), (v, va, vb, nv)):
            _over(rgba, _coverage(q, seen, lo, material.linewidth, (hi - lo) / (n - 1)), rgb)
    if material.contours is not None:
        if source is not None and source.field is not None:
            q = np.full(u.shape, np.nan)
            q[seen] = field_values(source.field, u, v, seen, source.extent)
            lo, hi = c_limits if c_limits is not None else (np.nanmin(q), np.nanmax(q))
        else:
            q = w
            lo, hi = w_limits
        levels = contour_levels(material.contours, lo, hi)
        rgb = color.to_rgb(material.contour_color, "contour_color")
        _over(rgba, _coverage(q, seen & np.isfinite(q), levels, material.contour_width), rgb)

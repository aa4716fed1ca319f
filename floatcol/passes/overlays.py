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

from dataclasses import replace

import numpy as np

from .. import color
from ..kernels.texture import lines_kernel
from .colour import field_values, levels_of, picture_planes


def _draw(rgba, q, seen, width, rgb, levels=None, origin=0.0, spacing=0.0):
    """Lines of q (H, W) at ``levels`` or at origin + k spacing, over rgba in place
    (kernels/texture.py's lines_kernel)."""
    lv = np.zeros(0) if levels is None else np.sort(np.asarray(levels, dtype=np.float64))
    lines_kernel(np.ascontiguousarray(q, dtype=np.float64), np.ascontiguousarray(seen), lv,
                 float(origin), float(spacing), float(width),
                 np.asarray(rgb, dtype=np.float64)[:3], rgba)


def grid_distance(q, origin, spacing):
    """|q - the nearest of origin + k spacing| (lines_kernel's wireframe distance)."""
    return np.abs(q - (origin + np.floor((q - origin) / spacing + 0.5) * spacing))


def level_distance(levels, q):
    """|q - the nearest of the sorted ``levels``| (inf: none; NaN where q is)."""
    if levels.size == 0:
        return np.full(np.shape(q), np.inf)
    k = np.searchsorted(levels, np.nan_to_num(q))
    up = np.where(k < levels.size, levels[np.minimum(k, levels.size - 1)] - q, np.inf)
    down = np.where(k > 0, q - levels[np.maximum(k - 1, 0)], np.inf)
    return np.where(np.isnan(q), np.nan, np.minimum(up, down))


def line_cover(dist, grad, width):
    """The part of a pixel a line of ``width`` pixels covers at ``dist`` (q's units)
    from it, q changing ``grad`` a pixel: clip(width / 2 + 1/2 - d, 0, 1) of d = dist /
    grad pixels (lines_kernel's; NaN where dist or grad is)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        px = np.where(grad > 0.0, dist / np.where(grad > 0.0, grad, 1.0),
                      np.where(dist == 0.0, 0.0, np.inf))
        return np.clip(width * 0.5 + 0.5 - px, 0.0, 1.0)


def draw_lines(rgba, q, seen, width, rgb, levels=None, origin=0.0, spacing=0.0):
    """_draw in numpy (a fresh install's drafts: no compile), lines_kernel's arithmetic:
    the lines q = level (the sorted ``levels``, or origin + k spacing where spacing >
    0) over rgba in place, each covering a pixel by clip(width / 2 + 1/2 - d, 0, 1), d
    = |q - level| / |grad q| pixels, |grad q| from the smaller one-sided difference to a
    seen neighbour each way (none either way: no line there)."""
    qs = np.where(seen, q, np.nan)
    p = np.pad(qs, 1, constant_values=np.nan)
    c = p[1:-1, 1:-1]
    with np.errstate(invalid="ignore"):
        gx = np.fmin(np.abs(p[1:-1, :-2] - c), np.abs(p[1:-1, 2:] - c))
        gy = np.fmin(np.abs(p[:-2, 1:-1] - c), np.abs(p[2:, 1:-1] - c))
        grad = np.where(np.isfinite(gx) & np.isfinite(gy), np.sqrt(gx * gx + gy * gy), np.nan)
        if spacing > 0.0:
            dist = grid_distance(qs, origin, spacing)
        else:
            lv = np.sort(np.asarray(levels, dtype=np.float64)) if levels is not None \
                else np.zeros(0)
            if lv.size == 0:
                return
            dist = level_distance(lv, qs)
        cov = line_cover(dist, grad, width)
    at = seen & np.isfinite(qs) & np.isfinite(grad) & np.isfinite(dist) & (cov > 0.0)
    if not at.any():
        return
    cv = cov[at][:, None]
    val = rgba[at, :3] / 255.0 * (1.0 - cv) + np.asarray(rgb, dtype=np.float64)[:3] * cv
    rgba[at, :3] = np.floor(np.clip(val * 255.0 + 0.5, 0.0, 255.0)).astype(np.uint8)


def _draw_rim(rgba, q, qe, seen, width, rgb, lo, hi, n, levels=None):
    """The wireframe lines q = lo + k (hi - lo) / (n - 1) (or q = the sorted
    ``levels``, lo and hi their ends) on the pixels just off the surface: the outer
    half of a line along the domain's edge, which no pixel centre on the surface
    draws. Where the edge buffer has the surface there (qe: its q, NaN
    elsewhere: the ends of the columns' runs), any line at its q; elsewhere (across
    the columns) the edge lines q = lo, hi where q carried on from the two pixels
    beside it on the surface (2 q1 - q2) lies outside [lo, hi] (a silhouette, where
    the surface goes on behind, does not). Each takes the change of q a pixel of its
    seen neighbours (their own: lines_kernel's smaller one-sided difference each way;
    the largest of them)."""
    H, W = seen.shape
    spacing = (hi - lo) / (n - 1)
    qs = np.where(seen, q, np.nan)
    p = np.pad(qs, 2, constant_values=np.nan)
    centre = p[2:-2, 2:-2]

    def shifted(di, dj):
        return p[2 + di:2 + di + H, 2 + dj:2 + dj + W]
    with np.errstate(invalid="ignore"):
        ways = [np.fmin(np.abs(shifted(-1, 0) - centre), np.abs(shifted(1, 0) - centre)),
                np.fmin(np.abs(shifted(0, -1) - centre), np.abs(shifted(0, 1) - centre))]
        grad = np.pad(np.sqrt(ways[0] ** 2 + ways[1] ** 2), 1, constant_values=np.nan)
        near = np.fmax(np.fmax(grad[:-2, 1:-1], grad[2:, 1:-1]),
                       np.fmax(grad[1:-1, :-2], grad[1:-1, 2:]))
        rim = ~seen & np.isfinite(qe)
        if levels is None:
            nearest = lo + np.floor((qe - lo) / spacing + 0.5) * spacing
        else:
            k = np.clip(np.searchsorted(levels, np.nan_to_num(qe)), 1, max(len(levels) - 1, 1))
            a, b = levels[k - 1], levels[np.minimum(k, len(levels) - 1)]
            nearest = np.where(np.abs(qe - a) <= np.abs(qe - b), a, b)
        dist = np.where(rim, np.abs(qe - nearest), np.nan)
        # across the columns: q carried on from the two pixels beside, each way
        for di, dj in ((0, -1), (0, 1), (-1, 0), (1, 0)):
            ext = 2.0 * shifted(di, dj) - shifted(2 * di, 2 * dj)
            edge = np.where(ext < lo, lo - ext, np.where(ext > hi, ext - hi, np.nan))
            take = ~seen & ~rim & np.isfinite(edge)
            dist = np.where(take, np.fmin(dist, edge), dist)
        cov = np.clip(width * 0.5 + 0.5 - dist / near, 0.0, 1.0)
    at = ~seen & np.isfinite(cov) & (near > 0.0) & (cov > 0.0)
    if not at.any():
        return
    c = cov[at][:, None]
    line = np.asarray(rgb, dtype=np.float64)[:3] * 255.0
    rgba[at, :3] = np.round(rgba[at, :3] * (1.0 - c) + line * c).astype(np.uint8)


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
    """(nu, nv) lines of a wireframe: N both ways, or a pair (wire_lines' counts of
    evenly spaced lines; ValueError for lines at given positions)."""
    vals = wireframe if isinstance(wireframe, (tuple, list)) else (wireframe, wireframe)
    if len(vals) != 2 or any(isinstance(x, bool) or not isinstance(x, (int, np.integer))
                             or not 2 <= x <= 10000 for x in vals):
        raise ValueError("wireframe must be a count of lines from 2 to 10000, or (nu, nv), "
                         f"got {wireframe!r}")
    return int(vals[0]), int(vals[1])


def _positions(name, x):
    """The sorted positions of a wireframe's lines along one axis (wire_lines)."""
    try:
        a = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError):
        a = np.zeros((0, 0))
    if a.ndim != 1 or not 1 <= a.size <= 10000 or not np.isfinite(a).all():
        raise ValueError(f"wireframe's {name} positions must be 1 to 10000 finite numbers")
    return np.unique(a)


def wire_lines(wireframe):
    """The wireframe's lines along u and along v (or along a mesh's two coordinates,
    Material.wire_coords): each (levels, n), ``levels`` None for n evenly spaced lines
    over the domain (wireframe N or (nu, nv)), else the sorted positions of its lines
    (wireframe (positions along u, positions along v): a mesh's own lines)."""
    if isinstance(wireframe, (tuple, list)) and len(wireframe) == 2 and \
            all(np.ndim(x) == 1 for x in wireframe):
        return [(_positions(name, x), 0) for name, x in zip(("first", "second"), wireframe)]
    return [(None, n) for n in wire_counts(wireframe)]


def _draw_boundary(rgba, q, step, seen, width, rgb, lo, hi):
    """A curvilinear mesh's lines q = lo and q = hi where they are its edge: the
    resampled surface ends at its last whole grid cell, up to two cells inside the
    mesh's edge, so those lines lie up to two cells' change of q (``step``, at each
    pixel) off the seen surface. A seen pixel on the surface's edge (a neighbour not
    seen) within that of lo or hi takes the line, covering it by min(width, 1)."""
    H, W = seen.shape
    p = np.pad(seen, 1, constant_values=False)
    edge = seen & ~(p[:-2, 1:-1] & p[2:, 1:-1] & p[1:-1, :-2] & p[1:-1, 2:])
    with np.errstate(invalid="ignore"):
        near = edge & np.isfinite(q) & ((np.abs(q - lo) <= 2.0 * step) |
                                        (np.abs(q - hi) <= 2.0 * step))
    if not near.any():
        return
    c = min(float(width), 1.0)
    line = np.asarray(rgb, dtype=np.float64)[:3] * 255.0
    rgba[near, :3] = np.round(rgba[near, :3] * (1.0 - c) + line * c).astype(np.uint8)


def _cell_steps(grid):
    """The most each of a grid's two coordinates changes over one of its cells, at its
    nodes (NaN where no neighbour is finite)."""
    out = np.full(grid.shape, np.nan)
    with np.errstate(invalid="ignore"):
        for axis in (0, 1):
            d = np.abs(np.diff(grid, axis=axis))
            lo = [slice(None)] * 3
            hi = [slice(None)] * 3
            lo[axis], hi[axis] = slice(0, -1), slice(1, None)
            out[tuple(lo)] = np.fmax(out[tuple(lo)], d)
            out[tuple(hi)] = np.fmax(out[tuple(hi)], d)
    return out


def _coordinates(material, u, v, seen, rims):
    """(fields, their rims', their steps): the two fields whose levels the wireframe's
    lines are, u and v (and ``rims``), or a resampled mesh's column and row index
    (Material.wire_coords: a grid (ny, nx, 2) over an extent, bilinear as a height
    field's) at the seen pixels (NaN elsewhere; no rims: the mesh's edge lies inside
    its grid's extent, _draw_boundary's) with how much each changes over a grid cell
    there (_cell_steps; None for u and v)."""
    if material.wire_coords is None:
        return (u, v), rims, (None, None)
    grid, extent = material.wire_coords
    cell = _cell_steps(np.asarray(grid, dtype=np.float64))
    qs, steps = [], []
    for c in range(2):
        q = np.full(u.shape, np.nan)
        st = np.full(u.shape, np.nan)
        if seen.any():
            q[seen] = field_values(grid[..., c], u, v, seen, extent)
            st[seen] = field_values(np.nan_to_num(cell[..., c]), u, v, seen, extent)
        qs.append(q)
        steps.append(st)
    return tuple(qs), (None, None), tuple(steps)


def overlay_pass(rgba, material, source, geom, W, box, w_limits, c_limits, domain,
                 bg8=(255, 255, 255, 255), edges=False):
    """Draw the material's contour and wireframe lines into rgba (in place); with
    ``fill`` False, the lines alone over the background ``bg8`` (a hidden-line
    drawing: the surface, not drawn, hides those behind it). With ``edges`` the
    wireframe reaches the pixels whose centre is off the surface but whose edge
    surface (section 6.4's edge buffer) is seen: the lines along the domain's edges
    are whole there, not their inner half."""
    if not material.fill:
        lines_alone(rgba, material, source, picture_planes(geom, W, box, edges=True), w_limits,
                    c_limits, domain, bg8, edges=True)
        return
    overlay_planes(rgba, material, source, picture_planes(geom, W, box, edges=edges), w_limits,
                   c_limits, domain, edges)


def overlay_planes(rgba, material, source, planes, w_limits, c_limits, domain, edges=False,
                   draw=_draw):
    """overlay_pass's lines (the surface filled) from the picture's planes (u, v, w,
    side[, eu, ev]: colour.picture_planes', top row first, or a draft's), each kind
    drawn by ``draw`` (_draw: kernels/texture.py's lines_kernel; a draft's numpy
    draw_lines)."""
    u, v, w, side, *rim_uv = planes
    seen = side != 0.0
    if not seen.any():
        return
    if material.wireframe is not None:
        lines = wire_lines(material.wireframe)
        rgb = color.to_rgb(material.edgecolor, "edgecolor")
        (ua, ub), (va, vb) = domain
        rims = rim_uv if edges else (None, None)
        qs, qes, steps = _coordinates(material, u, v, seen, rims)
        for q, qe, st, lo, hi, (levels, n) in zip(qs, qes, steps, (ua, va), (ub, vb), lines):
            if levels is not None:             # (a mesh's own lines)
                draw(rgba, q, seen & np.isfinite(q), material.linewidth, rgb, levels=levels)
                if st is not None:
                    _draw_boundary(rgba, q, st, seen, material.linewidth, rgb, levels[0],
                                   levels[-1])
                if qe is not None:
                    _draw_rim(rgba, q, qe, seen, material.linewidth, rgb, levels[0],
                              levels[-1], max(len(levels), 2), levels=levels)
                continue
            draw(rgba, q, seen, material.linewidth, rgb, origin=lo, spacing=(hi - lo) / (n - 1))
            if qe is not None:
                _draw_rim(rgba, q, qe, seen, material.linewidth, rgb, lo, hi, n)
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
        draw(rgba, q, seen & np.isfinite(q), material.contour_width, rgb, levels=levels)


def lines_alone(rgba, material, source, planes, w_limits, c_limits, domain, bg8, edges=False,
                draw=_draw):
    """overlay_pass with fill=False from the picture's planes (overlay_planes'): each
    kind of line drawn white on black to find the part of each pixel it covers (the
    same ``draw``), then the contours over the wireframe over the background, straight
    alpha; the surface's own colours gone (a draft's lines too, draw=draw_lines)."""
    kinds = []
    for keep in ("wireframe", "contours"):
        if getattr(material, keep) is None:
            continue
        canvas = np.zeros_like(rgba)
        alone = replace(material, fill=True, edgecolor="white", contour_color="white",
                        **{k: None for k in ("wireframe", "contours") if k != keep})
        overlay_planes(canvas, alone, source, planes, w_limits, c_limits, domain, edges, draw)
        cov = canvas[..., 0].astype(np.float64) / 255.0
        rgb = color.to_rgb(material.edgecolor if keep == "wireframe" else
                           material.contour_color, "edgecolor" if keep == "wireframe"
                           else "contour_color")
        kinds.append((cov, np.asarray(rgb, dtype=np.float64)[:3]))
    bg = np.asarray(bg8, dtype=np.float64) / 255.0
    pre = np.zeros(rgba.shape[:2] + (3,))
    a = np.zeros(rgba.shape[:2])
    for cov, rgb in kinds:                      # (premultiplied: each over the last)
        pre = cov[..., None] * rgb + (1.0 - cov[..., None]) * pre
        a = cov + (1.0 - cov) * a
    pre += (1.0 - a)[..., None] * bg[:3] * bg[3]
    a += (1.0 - a) * bg[3]
    out = np.where(a[..., None] > 0.0, pre / np.maximum(a, 1e-12)[..., None], 0.0)
    rgba[..., :3] = np.round(np.clip(out, 0.0, 1.0) * 255.0).astype(np.uint8)
    rgba[..., 3] = np.round(np.clip(a, 0.0, 1.0) * 255.0).astype(np.uint8)

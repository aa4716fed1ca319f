"""matplotlib's plot_surface(X, Y, Z) on meshes that are not an evenly spaced grid.

floatcol draws a mesh as a HeightField: bilinear over an evenly spaced grid. A mesh
whose x or y values are spaced unevenly (a meshgrid of np.geomspace), or whose
(X, Y) is a curvilinear grid (matplotlib's surface3d_radial example: X = R cos P,
Y = R sin P) is resampled onto one here, as the surface mplot3d draws of it:

- uneven spacing: the mesh's own bilinear surface (each cell's), evaluated at the
  nodes of an evenly spaced grid fine enough for the smallest cell (at most
  MAX_NODES a side);
- a curvilinear grid: each quad split into two triangles (mplot3d draws a quad as a
  flat polygon; a triangle is the flat piece a height field can hold), the surface
  linear on each, at the nodes of an evenly spaced grid over its extent with
  CURVED_NODES_PER_LINE nodes a mesh line (at most MAX_NODES a side;
  kernels/mesh.py rasterises the triangles); outside the mesh, a hole.

A curvilinear (X, Y) that is not a function's grid (a parametric surface such as a
sphere: its quads fold over one another in the x-y plane, or lie over one another)
raises ValueError: floatcol draws w = f(x, y). Points that coincide (a polar grid's
centre, the seam where its angle comes round) are one, at their heights' mean.
"""
from __future__ import annotations

import numpy as np

#: the resampled grid's nodes a side at most
MAX_NODES = 2049
#: a curvilinear mesh's resampled grid: nodes per mesh line along its longer side
CURVED_NODES_PER_LINE = 16
#: ... and at least this many a side
MIN_NODES = 65
#: the nodes the kernel may test, summed over the triangles' boxes (about a second)
MAX_VISITS = 4e8


def _linear(a, values, new, axis):
    """``values`` linear along ``axis`` between the ascending coordinates ``a``, at
    ``new`` (within a's range): the bilinear cell's value where applied on both axes."""
    i = np.clip(np.searchsorted(a, new, side="right") - 1, 0, len(a) - 2)
    shape = [1] * values.ndim
    shape[axis] = len(new)
    lo = np.take(values, i, axis=axis)
    hi = np.take(values, i + 1, axis=axis)
    with np.errstate(over="ignore", invalid="ignore"):
        t = ((new - a[i]) / (a[i + 1] - a[i])).reshape(shape)
        return lo + (hi - lo) * t


def _as_colours(resampled, like):
    """Resampled colours back in the type of ``like`` (uint8 stays uint8), the texels
    outside the mesh (NaN) taking their neighbours' (two texels deep: the texture's
    bilinear filter reads no farther at the surface's edge), else 0."""
    out = np.array(resampled, dtype=float)
    for _ in range(2):
        bad = ~np.isfinite(out).all(axis=-1)
        if not bad.any():
            break
        acc = np.zeros_like(out)
        cnt = np.zeros(out.shape[:2] + (1,))
        for axis in (0, 1):
            for shift in (1, -1):
                nb = np.roll(out, shift, axis=axis)
                good = np.isfinite(nb).all(axis=-1, keepdims=True)
                acc += np.where(good, nb, 0.0)
                cnt += good
        fill = bad & (cnt[..., 0] > 0)
        out[fill] = acc[fill] / cnt[fill]
    out[~np.isfinite(out)] = 0.0
    like = np.asarray(like)
    if like.dtype.kind in "iu":
        info = np.iinfo(like.dtype)
        return np.clip(np.round(out), info.min, info.max).astype(like.dtype)
    # (barycentric weights sum to 1 within rounding: a flat colour of 1 came out
    # 1 + 2e-16, beyond a colour's range)
    fin = np.isfinite(like)
    if not fin.any():
        return out
    return np.clip(out, like[fin].min(), like[fin].max())


def _even(a):
    """An evenly spaced grid over the ascending coordinates ``a``, fine enough for
    their smallest step."""
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        steps = (a[-1] - a[0]) / np.diff(a).min()      # (inf beyond the doubles)
    n = np.clip(np.ceil(steps) + 1, len(a), MAX_NODES) if steps == steps else MAX_NODES
    return np.linspace(a[0], a[-1], int(n))


def uneven(x, y, Z):
    """(x, y, Z) of the rectilinear mesh with ascending, unevenly spaced x (Z's
    columns) and y (its rows), resampled bilinearly onto evenly spaced ones (its
    facecolors: face_texture)."""
    xe, ye = _even(x), _even(y)
    return xe, ye, _linear(y, _linear(x, Z, xe, 1), ye, 0)


#: facecolors as a texture (face_texture): about this many texels a side, each face a
#: power of two of them (at most 64: its edges then blur over 1/64 of a face where it
#: is magnified, and its level of the mip-map is the faces' colours exactly) ...
FACE_TEXELS = 1024
#: ... and at most this many (faces narrower than a texel then share them)
MAX_FACE_TEXELS = 4096


def _face_texels(a):
    """The texels along the ascending node coordinates ``a`` of a row of faces: each
    texel's face (the one its centre lies in) and the extent of the texels' centres
    (the texture's, node-centred as a height field's grid)."""
    span = a[-1] - a[0]
    cells = span / np.diff(a).min()                  # (an even grid: its faces)
    if abs(cells - round(cells)) <= 1e-6 * cells:
        cells = float(round(cells))
    k = 2 ** int(np.clip(np.floor(np.log2(FACE_TEXELS / cells)), 0, 6))
    n = int(min(np.ceil(cells * k - 1e-9), MAX_FACE_TEXELS))
    centres = a[0] + (np.arange(n) + 0.5) * (span / n)
    face = np.clip(np.searchsorted(a, centres, side="right") - 1, 0, len(a) - 2)
    half = 0.5 * span / n
    return face, (a[0] + half, a[-1] - half)


def face_texture(x, y, faces):
    """matplotlib's facecolors over a rectilinear mesh as a texture: ``faces`` (rows,
    columns, channels) the colour of each face, face (i, j) between y[i], y[i + 1] and
    x[j], x[j + 1] (x, y ascending, evenly spaced or not). Returns (texture, extent):
    each face whole texels of its own colour (evenly spaced faces: the same number
    each), so that its edges stay sharp where the picture magnifies it and the
    mip-map averages the faces where it shrinks them."""
    fx, (u0, u1) = _face_texels(np.asarray(x, dtype=float))
    fy, (v0, v1) = _face_texels(np.asarray(y, dtype=float))
    return np.ascontiguousarray(np.asarray(faces)[fy][:, fx]), (u0, u1, v0, v1)


def _parametric(why):
    return ValueError(f"plot_surface(X, Y, Z): X and Y are not the grid of a function "
                      f"z = f(x, y) ({why}); floatcol draws such surfaces, not parametric "
                      f"ones")


def curvilinear(X, Y, Z, faces=None, coords=False):
    """(x, y, Z, colours) of the curvilinear mesh X, Y, Z (2-D, one shape), linear on
    the two triangles of each quad, at the nodes of an evenly spaced grid (NaN
    outside the mesh); ValueError where it is not a function's grid. ``faces``: a
    colour for each quad (rows - 1, columns - 1, channels), its two triangles that
    colour: ``colours`` at the grid's nodes (a texture over its extent; None
    without). ``coords``: (x, y, Z, colours, ij) with ij (ny, nx, 2) the mesh's
    column and row index at the grid's nodes, linear on each triangle as the heights
    (a mesh line is a level of one: its edges, Material.wire_coords)."""
    m, n = Z.shape
    x, y, z = X.ravel(), Y.ravel(), Z.ravel()
    ok = np.isfinite(x) & np.isfinite(y)
    if ok.sum() < 3:
        raise ValueError("plot_surface(X, Y, Z): X and Y need at least 3 finite points")
    lo_x, hi_x = x[ok].min(), x[ok].max()
    lo_y, hi_y = y[ok].min(), y[ok].max()
    with np.errstate(over="ignore"):
        size = max(hi_x - lo_x, hi_y - lo_y)
    if not np.isfinite(size):
        raise ValueError("plot_surface(X, Y, Z): X or Y spans more than the largest double")
    if not size > 0:
        raise ValueError("plot_surface(X, Y, Z): X and Y span no area")
    # points that coincide (a polar grid's centre, the seam where its angle comes
    # round) become one, at their heights' mean (data with noise there; a parametric
    # surface's two heights at one point are caught as its fold below)
    key = np.round(np.column_stack([x[ok], y[ok]]) / (size * 1e-9))
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    where = np.flatnonzero(ok)
    node = np.full(x.size, -1)
    node[where] = first[inverse.ravel()]
    node[where] = where[node[where]]
    fin = np.isfinite(z[where])
    total = np.bincount(node[where][fin], weights=z[where][fin], minlength=x.size)
    count = np.bincount(node[where][fin], minlength=x.size)
    z = z.copy()
    merged = np.flatnonzero(count > 1)
    with np.errstate(over="ignore", invalid="ignore"):
        z[merged] = total[merged] / count[merged]
    idx = np.arange(m * n).reshape(m, n)
    a, b, c, d = idx[:-1, :-1], idx[:-1, 1:], idx[1:, 1:], idx[1:, :-1]
    tris = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3),
                           np.stack([a, c, d], -1).reshape(-1, 3)])
    quad = np.tile(np.arange(a.size), 2)                 # (each triangle's quad)
    orig = tris                                          # (the corners' own indices)
    tris = node[tris]
    keep = (tris >= 0).all(axis=1)
    tris, quad, orig = tris[keep], quad[keep], orig[keep]
    px, py = x[tris], y[tris]
    area = 0.5 * ((px[:, 1] - px[:, 0]) * (py[:, 2] - py[:, 0])
                  - (px[:, 2] - px[:, 0]) * (py[:, 1] - py[:, 0]))
    flat = np.abs(area) <= 1e-12 * size * size
    tris, area, px, py, quad = tris[~flat], area[~flat], px[~flat], py[~flat], quad[~flat]
    orig = orig[~flat]
    if len(tris) == 0:
        raise ValueError("plot_surface(X, Y, Z): X and Y span no area")
    # the quads of a function's grid all turn one way in the x-y plane; a parametric
    # surface's fold over (a sphere's at its equator)
    big = np.abs(area) > 1e-3 * np.abs(area).max()
    if (area[big] > 0).any() and (area[big] < 0).any():
        raise _parametric("its quads fold over one another")
    # triangles that do not overlap cover at most the mesh's box
    if np.abs(area).sum() > 1.05 * (hi_x - lo_x) * (hi_y - lo_y):
        raise _parametric("its quads overlap")
    nodes = int(np.clip(CURVED_NODES_PER_LINE * max(m, n), MIN_NODES, MAX_NODES))
    corners = z[tris][..., None]                         # (triangles, 3, values)
    if faces is not None:               # a quad's colour on both its triangles, flat
        colours = np.asarray(faces, dtype=float).reshape(a.size, -1)[quad]
        corners = np.concatenate([corners, np.repeat(colours[:, None], 3, axis=1)], axis=2)
    if coords:                          # each corner's column and row in the mesh
        corners = np.concatenate([corners, (orig % n)[..., None].astype(float),
                                  (orig // n)[..., None].astype(float)], axis=2)
    xe, ye, out, hits = _rasterise(
        x[tris], y[tris], corners, (lo_x, hi_x, lo_y, hi_y), nodes,
        "plot_surface(X, Y, Z): the mesh's cells are too long and thin to resample (a "
        "curvilinear grid whose quads cross much of it)")
    # quads that lie over one another without folding (a mesh wound round twice)
    if hits.max() > 1:
        raise _parametric("its quads overlap")
    colours = None if faces is None else _as_colours(out[..., 1:out.shape[2] - 2 * coords],
                                                     faces)
    if coords:
        return xe, ye, out[..., 0], colours, _carried_on(out[..., -2:])
    return xe, ye, out[..., 0], colours


def _carried_on(ij, rings=2):
    """The index grids ``ij`` (ny, nx, 2) carried on linearly past the mesh's edge by
    ``rings`` nodes (each NaN node beside finite ones: the mean of 2 q1 - q2 over the
    directions where its next two nodes are finite): the surface ends at its last
    whole grid cell, up to a cell inside the mesh's edge, and a seen pixel there reads
    its indices bilinearly from the cell's four nodes (Material.wire_coords)."""
    q = np.array(ij, dtype=np.float64)
    for _ in range(rings):
        p = np.pad(q, ((2, 2), (2, 2), (0, 0)), constant_values=np.nan)
        ny, nx = q.shape[:2]
        total = np.zeros_like(q)
        count = np.zeros(q.shape[:2] + (1,))
        for di, dj in ((0, 1), (0, -1), (1, 0), (-1, 0)):
            q1 = p[2 + di:2 + di + ny, 2 + dj:2 + dj + nx]
            q2 = p[2 + 2 * di:2 + 2 * di + ny, 2 + 2 * dj:2 + 2 * dj + nx]
            ok = np.isfinite(q1).all(axis=2) & np.isfinite(q2).all(axis=2)
            total[ok] += 2.0 * q1[ok] - q2[ok]
            count[ok] += 1.0
        fill = ~np.isfinite(q).all(axis=2) & (count[..., 0] > 0)
        if not fill.any():
            break
        q[fill] = total[fill] / count[fill]
    return np.ascontiguousarray(q)


def _rasterise(px, py, corners, extent, nodes, too_thin):
    """(xe, ye, out, hits): triangles with corners (px, py) (k, 3) and values there
    (k, 3, c), linear on each, at the nodes of an evenly spaced grid over ``extent``
    (x0, x1, y0, y1) with ``nodes`` nodes along its longer side (kernels/mesh.py: out
    (ny, nx, c) NaN outside them, hits where a node lies inside one); ValueError
    ``too_thin`` where the triangles' boxes hold more than MAX_VISITS nodes."""
    from .kernels.mesh import mesh_kernel
    lo_x, hi_x, lo_y, hi_y = extent
    step = max(hi_x - lo_x, hi_y - lo_y) / (nodes - 1)
    xe = np.linspace(lo_x, hi_x, max(int(round((hi_x - lo_x) / step)) + 1, 2))
    ye = np.linspace(lo_y, hi_y, max(int(round((hi_y - lo_y) / step)) + 1, 2))
    # the kernel visits each triangle's box of nodes: long thin cells across the
    # whole mesh would take minutes
    boxes = ((np.ptp(px, axis=1) / step + 1) * (np.ptp(py, axis=1) / step + 1)).sum()
    if boxes > MAX_VISITS:
        raise ValueError(too_thin)
    out = np.full((len(ye), len(xe), corners.shape[2]), np.nan)
    hits = np.zeros((len(ye), len(xe)), dtype=np.int64)
    mesh_kernel(np.ascontiguousarray(px, dtype=float), np.ascontiguousarray(py, dtype=float),
                np.ascontiguousarray(corners, dtype=float), xe[0], xe[1] - xe[0], len(xe),
                ye[0], ye[1] - ye[0], len(ye), out, hits)
    return xe, ye, out, hits


#: plot_trisurf's resampled grid: nodes along its longer side per point along it (the
#: square root of the number of points), and at most MAX_NODES
TRI_NODES_PER_POINT = 16


def triangulated(x, y, z, triangles):
    """(x, y, Z) of matplotlib's plot_trisurf: the surface through the points (x, y, z)
    (1-D, n), linear on ``triangles`` (k, 3) of point indices, at the nodes of an
    evenly spaced grid over the points' extent with TRI_NODES_PER_POINT sqrt(n) nodes
    along its longer side (at least MIN_NODES, at most MAX_NODES); NaN outside the
    triangles. ValueError where the triangles overlap, span no area, or are too long
    and thin to resample."""
    x, y, z = (np.asarray(a, dtype=float) for a in (x, y, z))
    tris = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    px, py = x[tris], y[tris]
    with np.errstate(over="ignore", invalid="ignore"):
        area = 0.5 * ((px[:, 1] - px[:, 0]) * (py[:, 2] - py[:, 0])
                      - (px[:, 2] - px[:, 0]) * (py[:, 1] - py[:, 0]))
        lo_x, hi_x, lo_y, hi_y = x.min(), x.max(), y.min(), y.max()
        size = max(hi_x - lo_x, hi_y - lo_y)
    if not np.isfinite(size):
        raise ValueError("plot_trisurf: x or y spans more than the largest double")
    keep = np.abs(area) > 1e-12 * size * size
    if not keep.any():
        raise ValueError("plot_trisurf: the points span no area (all on one line)")
    nodes = int(np.clip(TRI_NODES_PER_POINT * np.sqrt(len(x)), MIN_NODES, MAX_NODES))
    xe, ye, out, hits = _rasterise(
        px[keep], py[keep], z[tris[keep]][..., None], (lo_x, hi_x, lo_y, hi_y), nodes,
        "plot_trisurf: the triangles are too long and thin to resample")
    if hits.max() > 1:
        raise ValueError("plot_trisurf: triangles lie over one another; give triangles "
                         "that do not overlap (or none: the points' Delaunay triangulation)")
    return xe, ye, out[..., 0]

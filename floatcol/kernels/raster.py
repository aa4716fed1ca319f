"""A z-buffer for the objects on a surface (floatcol/objects.py; Szenberg 1997):
triangles rasterised at the pixel centres against the picture's depth."""
import math

import numpy as np

from numba import prange

# (exact products: _jit.py _MATH)
from ._jit import function_type, kernel_calling
from ._jit import ngjit_exact as ngjit
from ._jit import ngjit_inline_exact as ngjit_inline
from ._jit import ngjit_parallel_exact as ngjit_parallel


@ngjit
def raster_kernel(cx, cy, e, tris, rgb, ortho, d3, zbuf, rgba, drawn, wp, point, z_under,
                  touched):
    """Draw triangles ``tris`` (m, 3) of vertices at pixel coordinates (cx, cy)
    (column, array row) and distance e along the view axis, each of colour rgb (m, 3)
    in [0, 1], where nearer than zbuf (H, W) screen z (e - d3; updated): the depth
    interpolated linearly on the screen in orthographic pictures, 1/e linearly in
    perspective (perspective-correct). rgba (H, W, 4) uint8 and drawn (H, W) int32 (the
    triangle's index + 1) are written where a triangle wins, and where ``point`` (H, W,
    3) is not empty the point seen there, interpolated as the depth from the vertices'
    ``wp`` (n, 3). Where ``touched`` (H, W, TOUCH_SLOTS) is not empty (antialiasing) it
    takes, at each pixel, the first triangles that do not win the centre but cover one
    of the pixel's EDGE_SS x EDGE_SS sub-samples in front of z_under (H, W: what lies
    under the objects), for object_edges_kernel: an object thinner than a pixel between
    the centres. Serial, in the triangles' order."""
    H, W = zbuf.shape
    for k in range(tris.shape[0]):
        i0 = tris[k, 0]
        i1 = tris[k, 1]
        i2 = tris[k, 2]
        x0, x1, x2 = cx[i0], cx[i1], cx[i2]
        y0, y1, y2 = cy[i0], cy[i1], cy[i2]
        if not (math.isfinite(x0) and math.isfinite(x1) and math.isfinite(x2)
                and math.isfinite(y0) and math.isfinite(y1) and math.isfinite(y2)):
            continue
        det = (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2)
        if det == 0.0:
            continue
        # (clamped as floats before the conversion: a float far outside an int's range
        # converts to anything in LLVM, and an object 1e50 tall wrote past the picture)
        c0 = int(min(max(math.floor(min(x0, x1, x2)), 0.0), W))
        c1 = int(max(min(math.ceil(max(x0, x1, x2)), W - 1.0), -1.0))
        r0 = int(min(max(math.floor(min(y0, y1, y2)), 0.0), H))
        r1 = int(max(min(math.ceil(max(y0, y1, y2)), H - 1.0), -1.0))
        r8 = np.uint8(min(max(round(rgb[k, 0] * 255.0), 0.0), 255.0))
        g8 = np.uint8(min(max(round(rgb[k, 1] * 255.0), 0.0), 255.0))
        b8 = np.uint8(min(max(round(rgb[k, 2] * 255.0), 0.0), 255.0))
        # (antialiasing: a pixel centre within SUB_REACH of the triangle may have a
        # sub-sample in it; its distance to edge k is l_k |det| / |edge k|)
        g0 = g1 = g2 = 0.0
        if touched.shape[0] > 0:
            c0 = max(c0 - 1, 0)
            c1 = min(c1 + 1, W - 1)
            r0 = max(r0 - 1, 0)
            r1 = min(r1 + 1, H - 1)
            g0 = abs(det) / max(math.hypot(x1 - x2, y1 - y2), 1e-300)
            g1 = abs(det) / max(math.hypot(x2 - x0, y2 - y0), 1e-300)
            g2 = abs(det) / max(math.hypot(x0 - x1, y0 - y1), 1e-300)
        for r in range(r0, r1 + 1):
            for c in range(c0, c1 + 1):
                l0 = ((y1 - y2) * (c - x2) + (x2 - x1) * (r - y2)) / det
                l1 = ((y2 - y0) * (c - x2) + (x0 - x2) * (r - y2)) / det
                l2 = 1.0 - l0 - l1
                if l0 < -1e-9 or l1 < -1e-9 or l2 < -1e-9:
                    if touched.shape[0] > 0 and touched[r, c, TOUCH_SLOTS - 1] == 0 \
                            and l0 * g0 > -SUB_REACH and l1 * g1 > -SUB_REACH \
                            and l2 * g2 > -SUB_REACH \
                            and _covers_a_subsample(x0, x1, x2, y0, y1, y2, det, e[i0],
                                                    e[i1], e[i2], ortho, d3, r, c,
                                                    z_under[r, c]):
                        _touch(touched, r, c, k + 1)
                    continue
                if ortho:
                    depth = l0 * e[i0] + l1 * e[i1] + l2 * e[i2]
                else:
                    depth = 1.0 / (l0 / e[i0] + l1 / e[i1] + l2 / e[i2])
                z = depth - d3
                if touched.shape[0] > 0 and z >= zbuf[r, c] \
                        and touched[r, c, TOUCH_SLOTS - 1] == 0 \
                        and _covers_a_subsample(x0, x1, x2, y0, y1, y2, det, e[i0], e[i1],
                                                e[i2], ortho, d3, r, c, z_under[r, c]):
                    _touch(touched, r, c, k + 1)  # (hidden at the centre, not everywhere)
                if z < zbuf[r, c]:
                    zbuf[r, c] = z
                    rgba[r, c, 0] = r8
                    rgba[r, c, 1] = g8
                    rgba[r, c, 2] = b8
                    rgba[r, c, 3] = 255
                    drawn[r, c] = k + 1
                    if point.shape[0] > 0:
                        # the weights of the vertices at the pixel: the screen's, or
                        # l_i / e_i normalised (perspective-correct)
                        m0, m1, m2 = l0, l1, l2
                        if not ortho:
                            m0 = l0 / e[i0] * depth
                            m1 = l1 / e[i1] * depth
                            m2 = l2 / e[i2] * depth
                        for q in range(3):
                            point[r, c, q] = m0 * wp[i0, q] + m1 * wp[i1, q] + m2 * wp[i2, q]


#: sub-samples along each side of an object's edge pixel (antialiasing: 16 a pixel)
EDGE_SS = 4


@ngjit_inline
def _barycentric(x0, x1, x2, y0, y1, y2, det, x, y):
    """The barycentric coordinates (l0, l1, l2) of the screen point (x, y) in a
    triangle (det its determinant: _on_screen's)."""
    l0 = ((y1 - y2) * (x - x2) + (x2 - x1) * (y - y2)) / det
    l1 = ((y2 - y0) * (x - x2) + (x0 - x2) * (y - y2)) / det
    return l0, l1, 1.0 - l0 - l1


@ngjit
def _covers_a_subsample(x0, x1, x2, y0, y1, y2, det, e0, e1, e2, ortho, d3, r, c, z_max):
    """Whether the triangle covers one of pixel (r, c)'s EDGE_SS x EDGE_SS sub-samples
    nearer than screen z z_max (raster_kernel's depth)."""
    S = EDGE_SS
    for a in range(S):
        y = r + (a + 0.5) / S - 0.5
        for b in range(S):
            x = c + (b + 0.5) / S - 0.5
            l0, l1, l2 = _barycentric(x0, x1, x2, y0, y1, y2, det, x, y)
            if l0 < -1e-9 or l1 < -1e-9 or l2 < -1e-9:
                continue
            if ortho:
                depth = l0 * e0 + l1 * e1 + l2 * e2
            else:
                depth = 1.0 / (l0 / e0 + l1 / e1 + l2 / e2)
            if depth - d3 < z_max:
                return True
    return False


#: the farthest a sub-sample lies from its pixel's centre (pixels), and a little more
SUB_REACH = (0.5 - 0.5 / EDGE_SS) * math.sqrt(2.0) + 1e-6
#: triangles a pixel keeps that cover its sub-samples but not its centre
TOUCH_SLOTS = 3


@ngjit
def _touch(touched, r, c, t):
    """Triangle t (index + 1) into pixel (r, c)'s first free slot."""
    for q in range(TOUCH_SLOTS):
        if touched[r, c, q] == 0:
            touched[r, c, q] = t
            return


#: a point on a triangle's edge counts as inside (barycentric tolerance)
EDGE_TOL = 1e-12


@ngjit_inline
def _blocked_at(px, py, pz, mine, frame, coef, start, items, ga, gb, inv_cell, na, nb, bias):
    """Whether a triangle other than ``mine`` hides the point (px, py, pz) from the
    light (occluded_kernel's test)."""
    pa = px * frame[0, 0] + py * frame[0, 1] + pz * frame[0, 2]
    pb = px * frame[1, 0] + py * frame[1, 1] + pz * frame[1, 2]
    pd = px * frame[2, 0] + py * frame[2, 1] + pz * frame[2, 2]
    x = (pa - ga) * inv_cell
    y = (pb - gb) * inv_cell
    if not (x >= 0.0 and x < na and y >= 0.0 and y < nb):
        return False                    # (NaN too)
    cell = int(y) * na + int(x)
    for q in range(start[cell], start[cell + 1]):
        t = items[q]
        if t == mine:
            continue
        da = pa - coef[t, 0]
        db = pb - coef[t, 1]
        l1 = coef[t, 2] * da + coef[t, 3] * db
        l2 = coef[t, 4] * da + coef[t, 5] * db
        if l1 < -EDGE_TOL or l2 < -EDGE_TOL or l1 + l2 > 1.0 + EDGE_TOL:
            continue
        if coef[t, 6] + l1 * coef[t, 7] + l2 * coef[t, 8] > pd + bias:
            return True
    return False


@ngjit_parallel
def occluded_kernel(point, test, own, grid_index, frame, coef, start, items, ga, gb, inv_cell,
                    na, nb, bias, out):
    """Which seen points a triangle hides from a directional light (the objects' cast
    shadows, floatcol/objects.py Occluders). point (H, n, T, 3): the point of pixel
    (i, j) in the box at point[i, j // T, j % T] (a tiled G-buffer's layout, or T = 1),
    where ``test`` (H, W) is set; frame (3, 3): rows e1, e2 across the light and L
    toward it. In the light's frame a ray toward the light is a point (a, b) = (P.e1,
    P.e2) at height d = P.L: it is blocked where a triangle's projection holds (a, b)
    and the triangle there lies nearer the light than d by more than ``bias``. coef
    (m, 9): a triangle's first vertex (a, b), the inverse of its edge matrix
    (barycentric l1, l2 from the offset) and its height toward the light at the vertex
    and along its two edges; the triangles of grid cell c (na x nb cells of 1 /
    inv_cell from (ga, gb)) are items[start[c]:start[c + 1]]. out (H, W): 1 blocked,
    else 0. A point's own triangle does not count: own (H, W) its rasterised triangle
    + 1 (0: none; own empty: no point has one), grid_index that triangle's number among
    coef's (-1: none). In parallel over the columns, each pixel alone: the same for any
    number of threads."""
    H, W = test.shape
    T = point.shape[2]
    for jp in prange(W):
        j = np.int64(jp)
        b = j // T
        lane = j - b * T
        for i in range(H):
            out[i, j] = 0
            if not test[i, j]:
                continue
            mine = -1
            if own.shape[0] > 0 and own[i, j] > 0:
                mine = grid_index[own[i, j] - 1]
            if _blocked_at(np.float64(point[i, b, lane, 0]), np.float64(point[i, b, lane, 1]),
                           np.float64(point[i, b, lane, 2]), mine, frame, coef, start, items,
                           ga, gb, inv_cell, na, nb, bias):
                out[i, j] = 1


#: points along each side of a pixel's footprint at the edge of an object's shadow
SHADOW_EDGE_SAMPLES = 4


@ngjit_parallel
def shadow_edges_kernel(point, seen, edge, frame, coef, start, items, ga, gb, inv_cell, na,
                        nb, bias, out):
    """At the edge of the objects' shadows (``edge`` (H, W)), the part of each pixel's
    footprint on the surface that a triangle hides from the light: the mean over
    SHADOW_EDGE_SAMPLES^2 points spread over it, the footprint spanned by the pixel's
    steps to its neighbours (point as occluded_kernel's; the shorter of the two steps
    each way among the ``seen`` neighbours, so that a silhouette's far side does not
    stretch it). out (H, W) written at the edge pixels. In parallel over the columns."""
    H, W = edge.shape
    T = point.shape[2]
    S = SHADOW_EDGE_SAMPLES
    for jp in prange(W):
        j = np.int64(jp)
        step = np.empty((2, 3))
        for i in range(H):
            if not edge[i, j]:
                continue
            b = j // T
            p0 = np.empty(3)
            for q in range(3):
                p0[q] = point[i, b, j - b * T, q]
            for axis in range(2):
                best = np.inf
                for q in range(3):
                    step[axis, q] = 0.0
                for sgn in (-1, 1):
                    i2 = i + sgn if axis == 1 else i
                    j2 = j + sgn if axis == 0 else j
                    if i2 < 0 or i2 >= H or j2 < 0 or j2 >= W or not seen[i2, j2]:
                        continue
                    b2 = j2 // T
                    d0 = sgn * (point[i2, b2, j2 - b2 * T, 0] - p0[0])
                    d1 = sgn * (point[i2, b2, j2 - b2 * T, 1] - p0[1])
                    d2 = sgn * (point[i2, b2, j2 - b2 * T, 2] - p0[2])
                    length = d0 * d0 + d1 * d1 + d2 * d2
                    if length < best:
                        best = length
                        step[axis, 0] = d0
                        step[axis, 1] = d1
                        step[axis, 2] = d2
            hits = 0
            for a in range(S):
                oy = (a + 0.5) / S - 0.5
                for c in range(S):
                    ox = (c + 0.5) / S - 0.5
                    if _blocked_at(p0[0] + ox * step[0, 0] + oy * step[1, 0],
                                   p0[1] + ox * step[0, 1] + oy * step[1, 1],
                                   p0[2] + ox * step[0, 2] + oy * step[1, 2], -1, frame,
                                   coef, start, items, ga, gb, inv_cell, na, nb, bias):
                        hits += 1
            out[i, j] = hits / (S * S)


@ngjit_inline
def _on_screen(tris, cx, cy, k):
    """Triangle k's vertices (i0, i1, i2), their pixel coordinates (x0, x1, x2, y0, y1,
    y2) and the determinant of its barycentric coordinates (0 or NaN: none)."""
    i0 = tris[k, 0]
    i1 = tris[k, 1]
    i2 = tris[k, 2]
    x0, x1, x2 = cx[i0], cx[i1], cx[i2]
    y0, y1, y2 = cy[i0], cy[i1], cy[i2]
    return i0, i1, i2, x0, x1, x2, y0, y1, y2, (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2)


@ngjit_parallel
def object_shadow_edges_kernel(drawn, edge, cx, cy, e, tris, wp, ortho, grid_index, frame, coef,
                               start, items, ga, gb, inv_cell, na, nb, bias, out):
    """At the edge of the objects' shadows on the objects themselves (``edge`` (H, W):
    object pixels whose 3 x 3 neighbourhood has points in them and out of them), the
    part of each pixel's footprint on its own triangle that another triangle hides from
    the light: the mean over SHADOW_EDGE_SAMPLES^2 sub-samples spread over the pixel,
    each the point of the triangle's plane it shows (the screen's barycentric weights,
    perspective-correct, from the vertices' ``wp`` (n, 3) in the box: raster_kernel's
    point, extended past the triangle's edges). drawn (H, W) raster_kernel's triangle +
    1; grid_index that triangle's number among the occluders' (its own does not count,
    -1: none). out (H, W) written at the edge pixels. In parallel over the columns."""
    H, W = edge.shape
    S = SHADOW_EDGE_SAMPLES
    for jp in prange(W):
        j = np.int64(jp)
        for i in range(H):
            if not edge[i, j] or drawn[i, j] <= 0:
                continue
            k = drawn[i, j] - 1
            i0, i1, i2, x0, x1, x2, y0, y1, y2, det = _on_screen(tris, cx, cy, k)
            if det == 0.0 or det != det:
                continue
            hits = 0
            for a in range(S):
                y = i + (a + 0.5) / S - 0.5
                for c in range(S):
                    x = j + (c + 0.5) / S - 0.5
                    l0, l1, l2 = _barycentric(x0, x1, x2, y0, y1, y2, det, x, y)
                    if not ortho:
                        l0 /= e[i0]
                        l1 /= e[i1]
                        l2 /= e[i2]
                        q = l0 + l1 + l2
                        l0 /= q
                        l1 /= q
                        l2 /= q
                    if _blocked_at(l0 * wp[i0, 0] + l1 * wp[i1, 0] + l2 * wp[i2, 0],
                                   l0 * wp[i0, 1] + l1 * wp[i1, 1] + l2 * wp[i2, 1],
                                   l0 * wp[i0, 2] + l1 * wp[i1, 2] + l2 * wp[i2, 2],
                                   grid_index[k], frame, coef, start, items, ga, gb,
                                   inv_cell, na, nb, bias):
                        hits += 1
            out[i, j] = hits / (S * S)


@ngjit
def object_edges_column(j, drawn, touched, cx, cy, e, tris, rgb, ortho, d3, z_under, before,
                        after, rgba):
    """object_edges_kernel's column j, with its own scratch; the kernel calls it through
    its address (_jit.kernel_calling: compiled once, not again in each of the kernel's
    libraries)."""
    H, W = drawn.shape
    S = EDGE_SS
    cand = np.empty(9 * (1 + TOUCH_SLOTS), np.int64)
    pl = np.empty((9 * (1 + TOUCH_SLOTS), 9))
    col = np.empty((9 * (1 + TOUCH_SLOTS), 4))
    acc = np.empty(4)
    for i in range(H):
        d0 = drawn[i, j]
        n = 0
        edge = touched[i, j, 0] > 0
        for di in range(-1, 2):
            for dj in range(-1, 2):
                ii = i + di
                jj = j + dj
                if ii < 0 or ii >= H or jj < 0 or jj >= W:
                    continue
                if drawn[ii, jj] != d0:
                    edge = True
                for slot in range(-1, TOUCH_SLOTS):
                    d = drawn[ii, jj] if slot < 0 else touched[ii, jj, slot]
                    if d > 0:
                        new = True
                        for p in range(n):
                            if cand[p] == d:
                                new = False
                        if new:
                            cand[n] = d
                            n += 1
        if not edge:
            continue
        # each candidate once: its barycentric planes l = a + bx x + by y, its
        # vertices' e (1 / e in perspective) and its colour at this pixel
        m = 0
        for q in range(n):
            k = cand[q] - 1
            i0, i1, i2, x0, x1, x2, y0, y1, y2, det = _on_screen(tris, cx, cy, k)
            if det == 0.0 or det != det:
                continue
            inv = 1.0 / det
            pl[m, 1] = (y1 - y2) * inv
            pl[m, 2] = (x2 - x1) * inv
            pl[m, 0] = -(pl[m, 1] * x2 + pl[m, 2] * y2)
            pl[m, 4] = (y2 - y0) * inv
            pl[m, 5] = (x0 - x2) * inv
            pl[m, 3] = -(pl[m, 4] * x2 + pl[m, 5] * y2)
            for v in range(3):
                ev = e[tris[k, v]]
                pl[m, 6 + v] = ev if ortho else 1.0 / ev
            # its colour: the nearest pixel of the neighbourhood where it won (the
            # centre, the 4 neighbours, the corners), else its own lit colour
            found = False
            for step in range(3):
                for di in range(-1, 2):
                    for dj in range(-1, 2):
                        if found or abs(di) + abs(dj) != step:
                            continue
                        ii = i + di
                        jj = j + dj
                        if 0 <= ii < H and 0 <= jj < W and drawn[ii, jj] == k + 1:
                            for v in range(4):
                                col[m, v] = after[ii, jj, v]
                            found = True
            if not found:
                for v in range(3):
                    col[m, v] = min(max(round(rgb[k, v] * 255.0), 0.0), 255.0)
                col[m, 3] = 255.0
            m += 1
        for q in range(4):
            acc[q] = 0.0
        for a in range(S):
            y = i + (a + 0.5) / S - 0.5
            for b in range(S):
                x = j + (b + 0.5) / S - 0.5
                best = -1
                best_z = z_under[i, j]
                for q in range(m):
                    l0 = pl[q, 0] + pl[q, 1] * x + pl[q, 2] * y
                    l1 = pl[q, 3] + pl[q, 4] * x + pl[q, 5] * y
                    l2 = 1.0 - l0 - l1
                    if l0 < -1e-9 or l1 < -1e-9 or l2 < -1e-9:
                        continue
                    if ortho:
                        depth = l0 * pl[q, 6] + l1 * pl[q, 7] + l2 * pl[q, 8]
                    else:
                        depth = 1.0 / (l0 * pl[q, 6] + l1 * pl[q, 7] + l2 * pl[q, 8])
                    if depth - d3 < best_z:
                        best_z = depth - d3
                        best = q
                if best < 0:
                    for q in range(4):
                        acc[q] += before[i, j, q]
                else:
                    for q in range(4):
                        acc[q] += col[best, q]
        for q in range(4):
            rgba[i, j, q] = np.uint8(min(max(round(acc[q] / (S * S)), 0.0), 255.0))


def _object_edges_functions(drawn, touched, cx, cy, e, tris, rgb, ortho, d3, z_under, before,
                            after, rgba):
    """object_edges_kernel's jitted function: object_edges_column (_jit.kernel_calling)."""
    return ((object_edges_column,
             function_type(object_edges_column, np.int64(0), drawn, touched, cx, cy, e, tris,
                           rgb, ortho, d3, z_under, before, after, rgba)),)


@kernel_calling(_object_edges_functions, (object_edges_column,), exact=True)
def object_edges_kernel(drawn, touched, cx, cy, e, tris, rgb, ortho, d3, z_under, before,
                        after, rgba, column):
    """Antialias the objects' edges (floatcol/objects.py): a pixel whose 3 x 3
    neighbourhood shows more than one thing (drawn (H, W): raster_kernel's triangle + 1,
    0 where none), or that a triangle touches without winning its centre (``touched``
    (H, W, TOUCH_SLOTS), raster_kernel's), takes the mean of EDGE_SS x EDGE_SS
    sub-samples spread evenly over it. At each sub-sample the nearest of the triangles
    drawn or touching in the neighbourhood that covers it (its depth as raster_kernel's)
    is seen, else what lies under the objects (z_under (H, W) its screen z, ``before``
    (H, W, 4) its colour); a triangle's colour
    is the one ``after`` (H, W, 4) holds at the nearest pixel of the neighbourhood where
    it won (its light and shadow there), else its own ``rgb`` (m, 3; a sliver no pixel
    centre lies on: with shadows, lit and shadowed at its centroid, objects.py
    _sliver_colours). Writes rgba at the edge pixels only. In parallel
    over the columns, each pixel alone (reads drawn, before, after). ``column``:
    object_edges_column as a function value (_jit.kernel_calling; the launch passes
    it)."""
    for jp in prange(drawn.shape[1]):
        column(np.int64(jp), drawn, touched, cx, cy, e, tris, rgb, ortho, d3, z_under,
               before, after, rgba)

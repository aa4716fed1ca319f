"""A z-buffer for the objects on a surface (floatcol/objects.py; Szenberg 1997):
triangles rasterised at the pixel centres against the picture's depth."""
import math

import numpy as np

from numba import prange

from ._jit import ngjit, ngjit_parallel


@ngjit
def raster_kernel(cx, cy, e, tris, rgb, ortho, d3, zbuf, rgba, drawn, wp, point):
    """Draw triangles ``tris`` (m, 3) of vertices at pixel coordinates (cx, cy)
    (column, array row) and distance e along the view axis, each of colour rgb (m, 3)
    in [0, 1], where nearer than zbuf (H, W) screen z (e - d3; updated): the depth
    interpolated linearly on the screen in orthographic pictures, 1/e linearly in
    perspective (perspective-correct). rgba (H, W, 4) uint8 and drawn (H, W) int32 (the
    triangle's index + 1) are written where a triangle wins, and where ``point`` (H, W,
    3) is not empty the point seen there, interpolated as the depth from the vertices'
    ``wp`` (n, 3). Serial, in the triangles' order."""
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
        for r in range(r0, r1 + 1):
            for c in range(c0, c1 + 1):
                l0 = ((y1 - y2) * (c - x2) + (x2 - x1) * (r - y2)) / det
                l1 = ((y2 - y0) * (c - x2) + (x0 - x2) * (r - y2)) / det
                l2 = 1.0 - l0 - l1
                if l0 < -1e-9 or l1 < -1e-9 or l2 < -1e-9:
                    continue
                if ortho:
                    depth = l0 * e[i0] + l1 * e[i1] + l2 * e[i2]
                else:
                    depth = 1.0 / (l0 / e[i0] + l1 / e[i1] + l2 / e[i2])
                z = depth - d3
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


#: a point on a triangle's edge counts as inside (barycentric tolerance)
EDGE_TOL = 1e-12


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
    for j in prange(W):
        b = j // T
        lane = j - b * T
        for i in range(H):
            out[i, j] = 0
            if not test[i, j]:
                continue
            px = np.float64(point[i, b, lane, 0])
            py = np.float64(point[i, b, lane, 1])
            pz = np.float64(point[i, b, lane, 2])
            mine = -1
            if own.shape[0] > 0 and own[i, j] > 0:
                mine = grid_index[own[i, j] - 1]
            pa = px * frame[0, 0] + py * frame[0, 1] + pz * frame[0, 2]
            pb = px * frame[1, 0] + py * frame[1, 1] + pz * frame[1, 2]
            pd = px * frame[2, 0] + py * frame[2, 1] + pz * frame[2, 2]
            x = (pa - ga) * inv_cell
            y = (pb - gb) * inv_cell
            if not (x >= 0.0 and x < na and y >= 0.0 and y < nb):
                continue                # (NaN too)
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
                    out[i, j] = 1
                    break

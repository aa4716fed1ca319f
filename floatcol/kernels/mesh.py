"""Triangles rasterised at the nodes of an evenly spaced grid: matplotlib's
curvilinear meshes resampled into a height field (floatcol/mesh.py)."""
import math

from ._jit import ngjit
from .index import ceil_index, floor_index

#: a node within this much (barycentric) of a triangle's edge belongs to it; one
#: farther inside than this counts as a hit (two hits: triangles over one another)
EDGE = 1e-9


@ngjit
def mesh_kernel(tx, ty, tv, x0, dx, nx, y0, dy, ny, out, hits):
    """For each triangle t (corners (tx[t, c], ty[t, c]), values tv[t, c, :]) and
    each node (x0 + i dx, y0 + j dy) in it: out[j, i, :] the values linear over the
    triangle there (barycentric), hits[j, i] += 1 where the node lies inside, not on
    an edge. A triangle with a corner not finite, or of no area, is skipped."""
    k = tv.shape[2]
    for t in range(tx.shape[0]):
        xa, xb, xc = tx[t, 0], tx[t, 1], tx[t, 2]
        ya, yb, yc = ty[t, 0], ty[t, 1], ty[t, 2]
        det = (xb - xa) * (yc - ya) - (xc - xa) * (yb - ya)
        if not (math.isfinite(det) and det != 0.0):
            continue
        i0 = max(ceil_index((min(xa, xb, xc) - x0) / dx), 0)
        i1 = min(floor_index((max(xa, xb, xc) - x0) / dx), nx - 1)
        j0 = max(ceil_index((min(ya, yb, yc) - y0) / dy), 0)
        j1 = min(floor_index((max(ya, yb, yc) - y0) / dy), ny - 1)
        for j in range(j0, j1 + 1):
            y = y0 + j * dy
            for i in range(i0, i1 + 1):
                x = x0 + i * dx
                l1 = ((x - xa) * (yc - ya) - (xc - xa) * (y - ya)) / det
                l2 = ((xb - xa) * (y - ya) - (x - xa) * (yb - ya)) / det
                l0 = 1.0 - l1 - l2
                if l0 < -EDGE or l1 < -EDGE or l2 < -EDGE:
                    continue
                if l0 > EDGE and l1 > EDGE and l2 > EDGE:
                    hits[j, i] += 1
                for c in range(k):
                    out[j, i, c] = l0 * tv[t, 0, c] + l1 * tv[t, 1, c] + l2 * tv[t, 2, c]

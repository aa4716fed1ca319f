"""Smooth shading of a height field (``smooth_shading=True``): the G-buffer's normals
interpolated between the grid's nodes, as a hillshade or a mesh with vertex normals
lights a DEM, where the bilinear cells' own normals light each cell as a facet.

A height field is bilinear in each cell (its heights, hence every engine's geometry),
so its exact normal jumps at every cell edge: seen from nearer than its cells are
wide, a coarse DEM is a quilt of lit facets. This pass, run over the G-buffer and the
edge buffer after the geometry pass, replaces each seen point's normal (and its
intensity, which area sampling and iis light with) by the one of the gradient
interpolated bilinearly between the central differences at the cell's four nodes
(kernels/lod.py's _smooth_gradient of level 0, as the lod engine lights its coarser
levels): continuous across the cells, the geometry unchanged.

Where a pixel is wider than a cell the facets are smaller than the pixels and the
engines light them already: the level-of-detail engines (lod, march, area sampling)
take their pyramid's smoothed levels there. So the pass acts where a pixel's
footprint is at most half a cell and fades out linearly to a footprint of a whole
cell (as the lod engine's levels blend toward level 1), leaving farther pixels as
they were. A node beside a hole has no central difference: there the normal stays
the cell's own."""
import math

import numpy as np
from numba import prange

from ._jit import ngjit_inline, ngjit_parallel
from .coverage import flagged, seen_side
from .layout import (E_COV, E_DEPTH, E_I, E_NX, E_SEEN, E_U, E_V, G_DEPTH, G_I, G_NX, G_U,
                     G_V, VP_CU, VP_CV, VP_D1, VP_H, VP_ORTHO, VP_SCALE)
from .lod import _smooth_gradient, footprint_at_depth
from .sample import column_x0, lambert, unit_normal


@ngjit_inline
def smooth_weight(vp, z, cell):
    """How much of the smooth normal a point at screen depth z takes: 1 where a
    pixel's footprint there (world units: kernels/lod.py's footprint_at_depth) is at
    most half of ``cell``, 0 from a whole cell on, linear between."""
    return min(max(2.0 - 2.0 * footprint_at_depth(vp, z) / cell, 0.0), 1.0)


@ngjit_inline
def _smoothed(flat, lt, hfp, vp, a, x0, j, u, v, nx, ny, nz, lam):
    """(nx, ny, nz, intensity) of the point (u, v) seen at pixel row j of column x0:
    the smooth normal blended with the point's own (nx, ny, nz) by a (smooth_weight's,
    > 0), and its Lambert intensity (eq. 12, toward the viewpoint along the pixel's
    ray); the point's own where the nodes' gradient is not finite."""
    gu, gv = _smooth_gradient(flat, lt, 0, hfp, u, v)
    if not (math.isfinite(gu) and math.isfinite(gv)):
        return nx, ny, nz, lam
    sx, sy, sz = unit_normal(vp, gu, gv)                  # eq. (11)
    if a < 1.0:
        sx = a * sx + (1.0 - a) * nx
        sy = a * sy + (1.0 - a) * ny
        sz = a * sz + (1.0 - a) * nz
        q = 1.0 / math.sqrt(sx * sx + sy * sy + sz * sz)
        sx *= q
        sy *= q
        sz *= q
    if vp[VP_ORTHO] != 0.0:
        vx = 0.0
        vy = 0.0
        vz = -1.0
    else:                                                 # (as shade.py's _light)
        vx = -x0 * vp[VP_SCALE]
        vy = (vp[VP_H] - 1.0) * 0.5 - j
        vz = -vp[VP_D1] * vp[VP_SCALE]
    return sx, sy, sz, lambert(vp, vx, vy, vz, sx, sy, sz)


@ngjit_inline
def _smooth_entry(flat, lt, hfp, vp, cell, x0, j, cu, cv, p, c_depth, c_u, c_v, c_n, c_i):
    """One surface's entry p of a pixel (a G-buffer's or an edge buffer's: its channels
    c_depth, c_u, c_v, the normal's three from c_n, c_i) smoothed in place by
    _smoothed. Its weight first, from its depth alone: a pixel wider than a cell (most
    of a dense DEM's) is neither read further nor written."""
    a = smooth_weight(vp, p[c_depth], cell)
    if a > 0.0:
        nx, ny, nz, lam = _smoothed(flat, lt, hfp, vp, a, x0, j, p[c_u] + cu, p[c_v] + cv,
                                    p[c_n], p[c_n + 1], p[c_n + 2], p[c_i])
        p[c_n] = nx
        p[c_n + 1] = ny
        p[c_n + 2] = nz
        p[c_i] = lam


@ngjit_parallel
def smooth_normals_kernel(flat, lt, hfp, vp, cell, width, gbuf, ebuf, rows):
    """Every seen pixel's normal and intensity in the tiled gbuf and ebuf (layout.py)
    by _smoothed: the surface at its centre and, where the coverage planes hold one,
    its edge surface. ``flat``, ``lt``: the height field's pyramid (passes/area.py
    levels) and kernels/lod.py's level_table of it; ``cell`` its level 0's cell (the
    smaller side); rows: each tile's rows where E_SEEN may be set. Each tile on its
    own: the same picture for any number of threads."""
    n_tiles = gbuf.shape[0]
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    cu = vp[VP_CU]
    cv = vp[VP_CV]
    for b_ in prange(n_tiles):
        b = np.int64(b_)  # (_jit.py: prange_index)
        for lane in range(min(T, width - b * T)):
            x0 = column_x0(vp, b * T + lane)
            for j in range(max(int(rows[b, 0]), 0), min(int(rows[b, 1]), H - 1) + 1):
                x = ebuf[b, E_SEEN, j, lane]
                if x == 0.0:
                    continue
                if seen_side(x) != 0.0:
                    _smooth_entry(flat, lt, hfp, vp, cell, x0, j, cu, cv, gbuf[b, j, lane],
                                  G_DEPTH, G_U, G_V, G_NX, G_I)
                if flagged(x) and ebuf[b, E_COV, j, lane] > 0.0:
                    _smooth_entry(flat, lt, hfp, vp, cell, x0, j, cu, cv, ebuf[b, :, j, lane],
                                  E_DEPTH, E_U, E_V, E_NX, E_I)

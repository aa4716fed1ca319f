"""The level-of-detail column (``sampling="lod"``): a fly-through's fast floating
column over a height field's pyramid (Cohen-Or 1997's multiresolution traversal,
Guedes 1997's growing step), with each sample placed exactly on its column plane.

A perspective column x0 is sampled front to back on the planes t = const, as in
column.py, but the planes are spaced by the footprint of a pixel there (KAPPA
footprints apart) and each samples the pyramid level (passes/area.py) whose cells
match LOD (2**bias) footprints, blended with the next level over the middle half of
its span (level_blend: brilinear, a GPU's trade for a mip-map's trilinear filter; no
level boundary pops). So a column takes about D ln(far / near) / KAPPA
samples (D the focal length in pixels) whatever the grid's size, where the uniform
planes of column.py take one per cell: 19 000 a column for a 2049^2 DEM at 640x360.

The planes are one table a frame (plane_table: spaced by the footprint at the
surface's middle height), which every column walks from its first plane in view.

A sample is the point of the (blended) surface on the line where column x0's plane Pi
meets plane t: Newton's iteration in s from the line through the column's last two
samples (ERRATA 2; the plane is tilted when the camera pitches, Guedes's non-vertical
view plane, so the point is not the one under the plane's ground line) until it lies
within TOL_PX of Pi at its depth. The column keeps one floating horizon, the highest
row covered; a span from the last sample is painted above it (pixel centres:
``area=False``), or (``area=True``) each pixel takes the visible parts of the spans
that cross it, weighted by their length on screen (Cohen-Or's Fig. 12 weights, as
kernels/area.py), their total the pixel's coverage. Spans are cut at the level's cell
edges, where they rise more than REFINE_ROWS, and at a ridge between two samples.
One horizon is exact for a surface seen from above it (a terrain under a fly camera,
passes/lod.py checks the eye is above the ground under it) with no holes; behind a
hole a farther surface is drawn where it rises above the nearer ones only.

Where the column's last sample is hidden it tries to skip the planes ahead: the
pyramid's block maxima (passes/lod.py block_maxima) bound the surface over the ground
where Pi meets them above the horizon's ray (_hidden_until); where they do not, one
evaluation a plane, where the horizon's ray crosses it, tells whether the surface
there is hidden (_scan_hidden), without Newton's iteration: a column's planes are
two-thirds or more hidden in a fly-through, and these tests, independent of each
other, cost a third of a Newton step each; the planes skipped need no sample until
one may show (the 1280x720 fly-through of benchmarks/bench_terrain.py 199 -> 138 ms).
"""
import math

import numba
import numpy as np
from numba import prange, types

from ._jit import function_type, kernel_calling, ngjit, ngjit_inline, ngjit_nrt_free
from .area import (AC_SIZE, LV_CELL, LV_NU, LV_NV, LV_OFF, _below_picture, add_piece,
                   clear_accumulators, resolve_pixel, seen_heights)
from .column import _column_t_range
from .layout import (E_SEEN, G_DEPTH, G_I, G_NX, G_NY, G_NZ, G_T, G_U,
                     G_V, G_W, SURF_HEIGHTFIELD, VP_CA, VP_CB, VP_CU, VP_CV, VP_CW, VP_D1,
                     VP_D3, VP_H, VP_ORTHO, VP_SA, VP_SB, VP_SCALE, VP_T0, VP_T1, VP_WORG)
from .sample import column_x0, in_domain, into_domain, lambert, surface_eval, unit_normal

#: planes a footprint apart (1: a plane per pixel's width at its distance)
KAPPA = 1.0
#: the middle part of each pyramid level's span of footprints over which it is blended
#: with the next (level_blend; 1: trilinear). 0.5, brilinear: the 4097^2 DEM's
#: 1280x720 fly-through (benchmarks/bench_terrain.py), its kernel 65 -> 58 ms a frame
#: by the ray march, 125 -> 111 ms area sampled; on test_lod.py's dense DEM its intensities
#: nearer the exact ray caster's (36-37 % within 0.02 instead of 31-32 %; the
#: pyramid's smoothing keeps the rest off), its sides as near (98.63-98.65 % against
#: 98.65-98.67 %), Cohen-Or's flicker measure over a slow turn 2 734 -> 2 655 pixels by
#: the march, 3 492 -> 3 601 by the lod engine, 2 998 -> 3 134 area sampled
BLEND_BAND = 0.5
#: a sample is placed when it lies within this many pixels of its column's plane
TOL_PX = 0.05
NEWTON_MAX = 8
#: a hidden column tries to skip this many planes at first by the block maxima,
#: doubling while it succeeds up to SKIP_MAX, halving after a failure
SKIP_MIN = 4
SKIP_MAX = 1024
#: ... and where they do not, tests the next max(that many, SCAN_PLANES) planes one
#: by one (_scan_hidden); it tries them again after 1, 2, 4 .. BLOCK_BACKOFF such
#: steps as they keep failing (most of their tests fail where the scan is needed)
SCAN_PLANES = 64
BLOCK_BACKOFF = 8.0
#: planes a frame at most (their spacing doubles until they fit)
MAX_PLANES = 200_000
#: a visible span is cut in two (its middle sampled) where it rises more than this
#: many rows, up to this many times
REFINE_ROWS = 1.0
REFINE_DEPTH = 5
#: ... and cut where it crosses an edge of its level's cells while rising more rows
#: than this (where the surface bends; a straight span there is off by a fraction of
#: its rise). 0.25: the 4097^2 fly-through area sampled (benchmarks/bench_terrain.py)
#: 132 -> 115 ms a frame over the rough DEM, 271 -> 173 ms over the smooth one (a
#: cut is a placement, a normal and a span painted); against the ray caster
#: (test_lod.py's scene) 97.29 % of the intensities within 0.02 point sampled (0.05:
#: 97.47 %), 95.63 % of the grey levels of whole pixels within 0.02 of the box-filtered
#: ray caster's area sampled (95.72 %), flicker 3 661 and 3 112 (3 601, 3 134); 1.0:
#: 96.19 %, 94.72 %, 165 ms over the smooth DEM
CROSS_ROWS = 0.25
#: a ridge between two samples is looked for where it may rise this many rows above
#: the horizon, by this many bisections
RIDGE_PX = 0.25
RIDGE_STEPS = 4
#: a sample that Newton leaves farther than this from its plane (pixels) breaks the run
GIVE_UP_PX = 0.5
#: A sample: t, s, u, v, w, f_u, f_v, row, depth, level, blend, normal, intensity, done
Q_T = 0
Q_S = 1
Q_U = 2
Q_V = 3
Q_W = 4
Q_WU = 5
Q_WV = 6
Q_Y = 7
Q_Z = 8
Q_K = 9
Q_A = 10
Q_NX = 11
Q_NY = 12
Q_NZ = 13
Q_I = 14
Q_DONE = 15
Q_DEP = 16        # (a refinement stack's entry: how many times it was cut)
Q_SIZE = 17
#: level_table's columns
LT_OFF = 0
LT_NU = 1
LT_NV = 2
LT_SU = 3
LT_SV = 4
LT_SIZE = 5
#: level_ints' columns
LK_OFF = 0
LK_NU = 1
LK_NV2 = 2
LK_SIZE = 3


@ngjit_inline
def _bilinear(flat, lt, k, hfp, u, v):
    """(w, f_u, f_v) of level k at (u, v) inside the extent: bilinear, its partials
    the cell's. lt: level_table's."""
    nu = int(lt[k, LT_NU])
    su = lt[k, LT_SU]
    sv = lt[k, LT_SV]
    gx = (u - hfp[0]) * su
    gy = (v - hfp[2]) * sv
    i = min(max(int(gx), 0), nu - 2)             # (gx >= 0 inside the extent)
    j = min(max(int(gy), 0), int(lt[k, LT_NV]) - 2)
    fx = gx - i
    fy = gy - j
    b = int(lt[k, LT_OFF]) + j * nu + i
    z00 = flat[b]
    z10 = flat[b + 1]
    z01 = flat[b + nu]
    z11 = flat[b + nu + 1]
    a0 = z00 + fx * (z10 - z00)
    a1 = z01 + fx * (z11 - z01)
    w = a0 + fy * (a1 - a0)
    wu = ((z10 - z00) + fy * ((z11 - z01) - (z10 - z00))) * su
    wv = (a1 - a0) * sv
    return w, wu, wv


@ngjit_inline
def _smooth_gradient(flat, lt, k, hfp, u, v):
    """(f_u, f_v) of level k at (u, v) interpolated bilinearly between its cell's
    nodes' central differences (one-sided at the grid's edges; as area.py's
    _smooth_normal): a smoothed level's light does not jump from one facet to the
    next. The four nodes' differences from the twelve heights about the cell, its
    indices found once (the smooth shading pass, kernels/normals.py, 9.8 -> 8.7 ms
    at 1280x720 against each node on its own; the same values bit for bit)."""
    nu = int(lt[k, LT_NU])
    nv = int(lt[k, LT_NV])
    su = lt[k, LT_SU]
    sv = lt[k, LT_SV]
    off = int(lt[k, LT_OFF])
    gx = (u - hfp[0]) * su
    gy = (v - hfp[2]) * sv
    i = min(max(int(gx), 0), nu - 2)
    j = min(max(int(gy), 0), nv - 2)
    fx = min(max(gx - i, 0.0), 1.0)
    fy = min(max(gy - j, 0.0), 1.0)
    # columns i - 1 .. i + 2 and rows j - 1 .. j + 2, clamped; a node's step halved
    # where its difference spans two cells
    im = max(i - 1, 0)
    ip = min(i + 2, nu - 1)
    jm = max(j - 1, 0)
    jp = min(j + 2, nv - 1)
    hu0 = su if i - im == 0 else 0.5 * su          # node i: (i + 1) - max(i - 1, 0)
    hu1 = su if ip - i == 1 else 0.5 * su          # node i + 1: min(i + 2, nu - 1) - i
    hv0 = sv if j - jm == 0 else 0.5 * sv
    hv1 = sv if jp - j == 1 else 0.5 * sv
    r0 = off + j * nu
    r1 = r0 + nu
    a_u = (flat[r0 + i + 1] - flat[r0 + im]) * hu0
    b_u = (flat[r0 + ip] - flat[r0 + i]) * hu1
    c_u = (flat[r1 + i + 1] - flat[r1 + im]) * hu0
    d_u = (flat[r1 + ip] - flat[r1 + i]) * hu1
    a_v = (flat[r1 + i] - flat[off + jm * nu + i]) * hv0
    b_v = (flat[r1 + i + 1] - flat[off + jm * nu + i + 1]) * hv0
    c_v = (flat[off + jp * nu + i] - flat[r0 + i]) * hv1
    d_v = (flat[off + jp * nu + i + 1] - flat[r0 + i + 1]) * hv1
    return ((a_u * (1 - fx) + b_u * fx) * (1 - fy) + (c_u * (1 - fx) + d_u * fx) * fy,
            (a_v * (1 - fx) + b_v * fx) * (1 - fy) + (c_v * (1 - fx) + d_v * fx) * fy)


@ngjit_inline
def _height(kind, fg, hf0, flat, lt, hfp, k, a, u, v):
    """(w, f_u, f_v) of the surface at (u, v): a height field's level k blended with
    level k + 1 by a (trilinear), a function surface itself."""
    if kind != SURF_HEIGHTFIELD:
        return surface_eval(kind, fg, hf0, hfp, u, v)
    w, wu, wv = _bilinear(flat, lt, k, hfp, u, v)
    if a > 0.0:
        w1, wu1, wv1 = _bilinear(flat, lt, k + 1, hfp, u, v)
        b = 1.0 - a
        w = b * w + a * w1
        wu = b * wu + a * wu1
        wv = b * wv + a * wv1
    return w, wu, wv


@ngjit_inline
def _place(kind, fg, hf0, flat, lt, hfp, vp, x0, t, k, a, s, q):
    """The sample of plane t into q (Q_*) from Newton's start s: False where it
    falls in a hole, outside the domain, in front of the screen or off its plane.
    Returns (placed, evaluations)."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    d1 = vp[VP_D1]
    d3 = vp[VP_D3]
    cw = vp[VP_CW]
    inv_d1 = 1.0 / d1
    r0 = x0 * (t * ca + d3) * inv_d1             # eq. (9): Pi at height s = 0
    kx = x0 * sa * inv_d1                        # dr/ds inside Pi (ERRATA 2)
    ev = 0
    u = 0.0
    v = 0.0
    w = np.nan
    wu = 0.0
    wv = 0.0
    g = np.inf
    # Pi's distance in pixels at the point's depth: |kx g| scale d1 / q
    tol = TOL_PX * max(t * ca + s * sa + d3, d1) * inv_d1 / vp[VP_SCALE]
    for _ in range(NEWTON_MAX):
        r = r0 + kx * s
        u = vp[VP_CU] + r * cb + t * sb          # eq. (2)
        v = vp[VP_CV] - r * sb + t * cb
        if not in_domain(vp, u, v):
            return False, ev
        u, v = into_domain(vp, u, v)
        w, wu, wv = _height(kind, fg, hf0, flat, lt, hfp, k, a, u, v)
        ev += 1
        if not (math.isfinite(w) and math.isfinite(wu) and math.isfinite(wv)):
            return False, ev
        g = (w - cw) - s
        if abs(kx * g) <= tol:
            break
        dg = kx * (wu * cb - wv * sb) - 1.0
        if dg == 0.0:
            break
        s = s - g / dg
    if abs(kx * g) > tol * (GIVE_UP_PX / TOL_PX):
        return False, ev
    s = w - cw
    y1 = s * ca - t * sa                         # eqs. (4), (10)
    z1 = s * sa + t * ca
    if z1 + d3 <= d1:                            # in front of the screen
        return False, ev
    ypix = y1 * d1 / (z1 + d3) * vp[VP_SCALE] + (vp[VP_H] - 1.0) * 0.5
    q[Q_T] = t
    q[Q_S] = s
    q[Q_U] = u
    q[Q_V] = v
    q[Q_W] = w
    q[Q_WU] = wu
    q[Q_WV] = wv
    q[Q_Y] = ypix
    q[Q_Z] = z1
    q[Q_K] = k
    q[Q_A] = a
    q[Q_DONE] = 0.0
    return True, ev


@ngjit_inline
def _finish(kind, flat, lt, hfp, vp, q):
    """The normal and intensity of a sample that is drawn (computed once)."""
    if q[Q_DONE] != 0.0:
        return
    wu = q[Q_WU]
    wv = q[Q_WV]
    k = int(q[Q_K])
    a = q[Q_A]
    if kind == SURF_HEIGHTFIELD and (k > 0 or a > 0.0):
        # a smoothed level's partials interpolated between its nodes (level 0 keeps
        # its exact ones), blended as the heights are
        if k > 0:
            gu, gv = _smooth_gradient(flat, lt, k, hfp, q[Q_U], q[Q_V])
        else:
            gu = wu
            gv = wv
        if a > 0.0:
            hu, hv = _smooth_gradient(flat, lt, k + 1, hfp, q[Q_U], q[Q_V])
            gu = (1.0 - a) * gu + a * hu
            gv = (1.0 - a) * gv + a * hv
        if math.isfinite(gu) and math.isfinite(gv):
            wu = gu
            wv = gv
    nx, ny, nz = unit_normal(vp, wu, wv)
    r = (q[Q_U] - vp[VP_CU]) * vp[VP_CB] - (q[Q_V] - vp[VP_CV]) * vp[VP_SB]
    y1 = q[Q_S] * vp[VP_CA] - q[Q_T] * vp[VP_SA]
    q[Q_NX] = nx
    q[Q_NY] = ny
    q[Q_NZ] = nz
    q[Q_I] = lambert(vp, -r, -y1, -(vp[VP_D3] + q[Q_Z]), nx, ny, nz)    # eq. (12)
    q[Q_DONE] = 1.0


@ngjit_inline
def _weight(yq, p, c, d3):
    """Perspective-correct weight of sample c at screen row yq of the chord p -> c."""
    ls = min(max((yq - p[Q_Y]) / (c[Q_Y] - p[Q_Y]), 0.0), 1.0)
    qp = 1.0 / (p[Q_Z] + d3)
    qc = 1.0 / (c[Q_Z] + d3)
    return ls * qc / ((1.0 - ls) * qp + ls * qc)


@ngjit_inline
def _store(g, lw, p, c, cu, cv, wo):
    """Pixel g of the G-buffer at weight lw of the chord p -> c (u, v from the view's
    centre (cu, cv), w from wo: layout.py G_U, G_W)."""
    g[G_DEPTH] = p[Q_Z] + lw * (c[Q_Z] - p[Q_Z])
    g[G_U] = (p[Q_U] - cu) + lw * (c[Q_U] - p[Q_U])
    g[G_V] = (p[Q_V] - cv) + lw * (c[Q_V] - p[Q_V])
    g[G_W] = (p[Q_W] - wo) + lw * (c[Q_W] - p[Q_W])
    g[G_NX] = p[Q_NX] + lw * (c[Q_NX] - p[Q_NX])
    g[G_NY] = p[Q_NY] + lw * (c[Q_NY] - p[Q_NY])
    g[G_NZ] = p[Q_NZ] + lw * (c[Q_NZ] - p[Q_NZ])
    g[G_I] = p[Q_I] + lw * (c[Q_I] - p[Q_I])
    g[G_T] = p[Q_T] + lw * (c[Q_T] - p[Q_T])


#: where a sample record (Q_*) holds what area.add_piece takes
PIECE_FIELDS = (Q_U, Q_V, Q_W, Q_NX, Q_NY, Q_NZ, Q_I, Q_T, Q_Z)


@ngjit_inline
def _footprint(vp, t, s):
    """The width of a pixel, in world units, at height s on plane t."""
    return footprint_at_depth(vp, s * vp[VP_SA] + t * vp[VP_CA])


@ngjit_inline
def footprint_at_depth(vp, z):
    """The width of a pixel, in world units, at screen depth z (layout.py G_DEPTH: z +
    d3 from the eye, at least d1): 1 / scale in an orthographic view."""
    if vp[VP_ORTHO] != 0.0:
        return 1.0 / vp[VP_SCALE]
    return max(z + vp[VP_D3], vp[VP_D1]) / (vp[VP_D1] * vp[VP_SCALE])


@ngjit_inline
def level_blend(lf, n_lv, band):
    """(k, a): the level k and the blend a with level k + 1 for the level lf (log2 of
    a cell's size over level 0's, >= 0) of a pyramid of n_lv levels. ``band`` 1:
    trilinear (a mip-map's: k = floor(lf), a = lf - k); less: brilinear (a GPU's
    trade), the blend squeezed into the middle ``band`` of each level's span, each
    level alone outside it (a = 0: one bilinear look-up instead of two), the level
    still continuous in lf (nothing pops)."""
    if lf >= n_lv - 1:
        return n_lv - 1, 0.0
    k = int(lf)
    a = lf - k
    if band < 1.0:
        a = min(max((a - 0.5) / band + 0.5, 0.0), 1.0) if band > 0.0 else \
            (0.0 if a < 0.5 else 1.0)
        if a >= 1.0:                             # (k + 1 <= n_lv - 1 here)
            return k + 1, 0.0
    return k, a


@ngjit
def plane_table(kind, lv, vp, lod, kappa, s_ref):
    """The sampling planes every column takes, (n, 3): t, level k, blend a. From the
    viewpoint's t to the last plane, each ``kappa`` footprints of a pixel after the
    last (at the height s_ref: a footprint there), the level whose cells are ``lod``
    footprints (a mip-map's level, blended with the next over the middle BLEND_BAND
    of its span: level_blend)."""
    d3 = vp[VP_D3]
    t0 = max(-d3 * vp[VP_CA], vp[VP_T0])
    t1 = vp[VP_T1]
    n_lv = lv.shape[0]
    cell0 = lv[0, LV_CELL]
    if not (math.isfinite(t0) and math.isfinite(t1) and t0 <= t1):
        return np.empty((0, 3))
    n = MAX_PLANES + 1
    while n > MAX_PLANES:                        # (a step that grows, not a hang)
        n = 0
        t = t0
        while t <= t1 and n <= MAX_PLANES:
            n += 1
            t += max(kappa * _footprint(vp, t, s_ref), 1e-9 * (abs(t) + 1.0))
        if n > MAX_PLANES:
            kappa *= 2.0
    out = np.empty((n + 1, 3))
    t = t0
    for i in range(n + 1):
        if i == n:
            t = t1                               # the last plane on the far end
        fw = _footprint(vp, t, s_ref)
        k = 0
        a = 0.0
        if kind == SURF_HEIGHTFIELD:
            k, a = level_blend(math.log2(max(fw * lod / cell0, 1.0)), n_lv, BLEND_BAND)
        out[i, 0] = t
        out[i, 1] = k
        out[i, 2] = a
        t += max(kappa * fw, 1e-9 * (abs(t) + 1.0))
    return out


@ngjit
def level_table(lv, hfp):
    """Each level's offset, nodes along u and v, and nodes per unit of u and v."""
    lt = np.empty((lv.shape[0], LT_SIZE))
    for k in range(lv.shape[0]):
        lt[k, LT_OFF] = lv[k, LV_OFF]
        lt[k, LT_NU] = lv[k, LV_NU]
        lt[k, LT_NV] = lv[k, LV_NV]
        lt[k, LT_SU] = (lv[k, LV_NU] - 1.0) / (hfp[1] - hfp[0])
        lt[k, LT_SV] = (lv[k, LV_NV] - 1.0) / (hfp[3] - hfp[2])
    return lt


@ngjit
def level_ints(lv):
    """Each level's offset, nodes along u and nodes along v less 2, as integers."""
    lk = np.empty((lv.shape[0], LK_SIZE), dtype=np.int64)
    for k in range(lv.shape[0]):
        lk[k, LK_OFF] = int(lv[k, LV_OFF])
        lk[k, LK_NU] = int(lv[k, LV_NU])
        lk[k, LK_NV2] = int(lv[k, LV_NV]) - 2
    return lk


@ngjit_inline
def _last_before(planes, t):
    """The index of the last plane at or before t (0 where none)."""
    lo = 0
    hi = planes.shape[0] - 1
    if hi < 0:
        return 0
    if planes[hi, 0] <= t:
        return hi
    while hi - lo > 1:
        m = (lo + hi) // 2
        if planes[m, 0] <= t:
            lo = m
        else:
            hi = m
    return lo


#: A lane's state in lod_tile: its t range, first plane, Newton's next start s and
#: the slope ds/dt of its last two samples, the floating horizon, whether the last
#: sample continues a run, whether it is done, evaluations, rows set; its column's
#: x0, its next plane, how many planes it tries to skip, how many more hidden steps
#: leave out the block maxima' test (after a failure), whether the planes before its
#: next one were skipped (hidden, not sampled), how many steps the last failure's
#: pause was
ST_TA = 0
ST_TB = 1
ST_I0 = 2
ST_S = 3
ST_SLOPE = 4
ST_YMAX = 5
ST_HAVE = 6
ST_DONE = 7
ST_EVALS = 8
ST_JLO = 9
ST_JHI = 10
ST_DY = 11
ST_X0 = 12
ST_I = 13
ST_JUMP = 14
ST_WAIT = 15
ST_SKIP = 16
ST_BACK = 17
ST_CU = 18         # the view's centre (vp's VP_CU, VP_CV): the G-buffer's u, v are
ST_CV = 19         # stored from it (layout.py G_U)
ST_WO = 20         # ... and its w from vp's VP_WORG (layout.py G_W)
ST_SIZE = 21


@ngjit_inline
def column_t_span(vp, x0, s_lo, s_hi):
    """(ta, tb): the planes t of column x0 that may show the surface (ta > tb: none),
    the viewpoint's plane or later, less the first ones whose points all fall below
    the picture (the ground under a fly camera) where the surface's heights relative
    to the centre, [s_lo, s_hi], are known."""
    d3 = vp[VP_D3]
    lo, hi = _column_t_range(vp, x0)
    ta = max(lo, -d3 * vp[VP_CA], vp[VP_T0])
    tb = min(hi, vp[VP_T1])
    if ta <= tb and s_lo == s_lo and _below_picture(vp, ta, s_lo, s_hi):
        # bisect for the last plane below the picture (each end's row is monotone in
        # t along a line of constant s)
        if _below_picture(vp, tb, s_lo, s_hi):
            ta = tb + 1.0
        else:
            a = ta
            b = tb
            for _ in range(60):
                m = 0.5 * (a + b)
                if _below_picture(vp, m, s_lo, s_hi):
                    a = m
                else:
                    b = m
            ta = a
    return ta, tb


@ngjit_inline
def _start(vp, x0, s_lo, s_hi, planes, st):
    """A lane's state before its first plane."""
    ta, tb = column_t_span(vp, x0, s_lo, s_hi)
    st[ST_TA] = ta
    st[ST_TB] = tb
    st[ST_I0] = _last_before(planes, ta)
    st[ST_S] = 0.5 * (s_lo + s_hi) if s_lo == s_lo else 0.0
    st[ST_SLOPE] = 0.0
    st[ST_YMAX] = -0.5
    st[ST_HAVE] = 0.0
    st[ST_DONE] = 1.0 if ta > tb else 0.0
    st[ST_EVALS] = 0.0
    st[ST_DY] = 0.0
    st[ST_CU] = vp[VP_CU]
    st[ST_CV] = vp[VP_CV]
    st[ST_WO] = vp[VP_WORG]


@ngjit_inline
def _sample_lane(kind, fg, hf0, flat, lt, hfp, vp, x0, t, k, a, st, prev, cur):
    """One plane's sample of one lane into cur, from Newton's start on the line
    through its last two samples. Returns whether it was placed."""
    s_start = st[ST_S]
    if st[ST_HAVE] != 0.0:
        s_start += st[ST_SLOPE] * (t - prev[Q_T])
    ok, ev = _place(kind, fg, hf0, flat, lt, hfp, vp, x0, t, k, a, s_start, cur)
    st[ST_EVALS] += ev
    return ok


@ngjit_inline
def _crossing(lt, k, hfp, p, c):
    """Where the segment p -> c (ground points) first crosses an edge of level k's
    cells, as a fraction of it in (0.02, 0.98); 0 where it crosses none there."""
    best = 1.0
    for axis in range(2):
        o = hfp[0] if axis == 0 else hfp[2]
        sc = lt[k, LT_SU] if axis == 0 else lt[k, LT_SV]
        a = (p[Q_U if axis == 0 else Q_V] - o) * sc
        b = (c[Q_U if axis == 0 else Q_V] - o) * sc
        fa = math.floor(a)
        fb = math.floor(b)
        if fa != fb:
            edge = fb if b > a else fa
            lam = (edge - a) / (b - a)
            if 0.02 < lam < 0.98:
                best = min(best, lam)
    return best if best < 1.0 else 0.0


@ngjit_inline
def _paint(area, st, prev, cur, gcol, ecol, acc, d3):
    """The part of the span prev -> cur above the floating horizon, which rises to
    cur's row: pixel centres, or (area) each pixel's visible pieces (Fig. 12)."""
    H = gcol.shape[0]
    y = cur[Q_Y]
    lo_f = max(st[ST_YMAX], prev[Q_Y])
    if area:
        j = int(math.floor(lo_f + 0.5))
        while j < H:
            pa = max(lo_f, j - 0.5)
            pb = min(y, j + 0.5)
            if pb > pa and j >= 0:
                add_piece(acc[j], pb - pa, _weight(0.5 * (pa + pb), prev, cur, d3), prev, cur,
                          PIECE_FIELDS, 1.0)
                st[ST_JLO] = min(st[ST_JLO], j)
                st[ST_JHI] = max(st[ST_JHI], j)
            if j + 0.5 >= y:
                break
            j += 1
    else:
        j0 = max(int(math.floor(lo_f)) + 1, 0)
        j1 = min(int(math.floor(y)), H - 1)
        for j in range(j0, j1 + 1):
            _store(gcol[j], _weight(j, prev, cur, d3), prev, cur, st[ST_CU], st[ST_CV],
                   st[ST_WO])
            ecol[E_SEEN, j] = 1.0
        if j1 >= j0:
            st[ST_JLO] = min(st[ST_JLO], j0)
            st[ST_JHI] = max(st[ST_JHI], j1)
    st[ST_YMAX] = y


@ngjit_inline
def _draw_lane(kind, fg, hf0, flat, lt, hfp, vp, x0, area, st, pts, gcol, ecol, acc):
    """The span from a lane's last sample pts[0] to its new one pts[1] where it rises
    above the floating horizon, cut at midpoints (up to REFINE_DEPTH times, pts[2:]
    the stack) while its visible part spans more than REFINE_ROWS rows: a steep
    stretch that one straight span would misplace. The new sample becomes the last."""
    d3 = vp[VP_D3]
    prev = pts[0]
    cur = pts[1]
    have = st[ST_HAVE] != 0.0
    st[ST_SLOPE] = (cur[Q_S] - prev[Q_S]) / (cur[Q_T] - prev[Q_T]) if have else 0.0
    dy = st[ST_DY]
    st[ST_DY] = (cur[Q_Y] - prev[Q_Y]) / (cur[Q_T] - prev[Q_T]) if have else 0.0
    s_new = cur[Q_S]
    if have and cur[Q_Y] > st[ST_YMAX]:
        k = int(cur[Q_K])
        a = cur[Q_A]
        for q in range(Q_SIZE):
            pts[2, q] = cur[q]
        pts[2, Q_DEP] = 0.0
        sp = 2
        while sp >= 2:
            right = pts[sp]
            lo_f = max(st[ST_YMAX], prev[Q_Y])
            if right[Q_Y] > lo_f:
                d = right[Q_DEP]
                rise = right[Q_Y] - lo_f
                lam = 0.5
                cut = rise > REFINE_ROWS
                if kind == SURF_HEIGHTFIELD and rise > CROSS_ROWS:
                    # the span crosses an edge of its level's cells, where the
                    # surface bends: cut it there (as column.py's height-field spans)
                    c = _crossing(lt, k, hfp, prev, right)
                    if c > 0.0:
                        lam = c
                        cut = True
                if cut and d < REFINE_DEPTH:
                    mid = pts[sp + 1]
                    ok, ev = _place(kind, fg, hf0, flat, lt, hfp, vp, x0,
                                    prev[Q_T] + lam * (right[Q_T] - prev[Q_T]), k, a,
                                    prev[Q_S] + lam * (right[Q_S] - prev[Q_S]), mid)
                    st[ST_EVALS] += ev
                    if ok:
                        right[Q_DEP] = d + 1.0
                        mid[Q_DEP] = d + 1.0
                        sp += 1
                        continue
                _finish(kind, flat, lt, hfp, vp, prev)
                _finish(kind, flat, lt, hfp, vp, right)
                _paint(area, st, prev, right, gcol, ecol, acc, d3)
            for q in range(Q_SIZE):
                prev[q] = right[q]
            sp -= 1
    elif have and prev[Q_Y] >= st[ST_YMAX] and cur[Q_Y] < prev[Q_Y] \
            and dy * (cur[Q_T] - prev[Q_T]) > RIDGE_PX:
        # a ridge between the top sample and this one, which may rise above the
        # horizon by up to the last rise's slope times the step (section 5.1's
        # problem): bisect toward it, drawing each point found above the horizon
        k = int(cur[Q_K])
        a = cur[Q_A]
        right = pts[2]
        for q in range(Q_SIZE):
            right[q] = cur[q]
        mid = pts[3]
        for _ in range(RIDGE_STEPS):
            ok, ev = _place(kind, fg, hf0, flat, lt, hfp, vp, x0, 0.5 * (prev[Q_T] + right[Q_T]),
                            k, a, 0.5 * (prev[Q_S] + right[Q_S]), mid)
            st[ST_EVALS] += ev
            if not ok:
                break
            if mid[Q_Y] > prev[Q_Y]:
                _finish(kind, flat, lt, hfp, vp, prev)
                _finish(kind, flat, lt, hfp, vp, mid)
                _paint(area, st, prev, mid, gcol, ecol, acc, d3)
                for q in range(Q_SIZE):
                    prev[q] = mid[q]
            else:
                for q in range(Q_SIZE):
                    right[q] = mid[q]
        for q in range(Q_SIZE):
            prev[q] = cur[q]
    else:
        for q in range(Q_SIZE):
            prev[q] = cur[q]
    st[ST_S] = s_new
    st[ST_HAVE] = 1.0


@ngjit_inline
def _resolve(area, gcol, ecol, acc, st):
    """A lane's G-buffer from its accumulators (area); returns the lowest and
    highest w seen (+inf and -inf: none)."""
    H = gcol.shape[0]
    w_lo = np.inf
    w_hi = -np.inf
    for j in range(max(int(st[ST_JLO]), 0), min(int(st[ST_JHI]), H - 1) + 1):
        if not area:
            if ecol[E_SEEN, j] != 0.0:
                w = gcol[j, G_W]
                w_lo = min(w_lo, w)
                w_hi = max(w_hi, w)
            continue
        # (the pieces show the upper side: add_piece's side 1)
        side = resolve_pixel(acc[j], gcol[j], ecol, j, st[ST_CU], st[ST_CV], st[ST_WO])
        if side != 0.0:
            w_lo, w_hi = seen_heights(gcol, ecol, j, side, w_lo, w_hi)
    # (as the G-buffer holds them, less VP_WORG: layout.py G_W)
    return w_lo + st[ST_WO], w_hi + st[ST_WO]


@ngjit_inline
def _region_max(mx, mt, n_m, lt, k, hfp, u0, u1, v0, v1):
    """The highest height of level k over the box [u0, u1] x [v0, v1] (its cells'
    nodes), from the maxima of its blocks (mx, mt: passes/lod.py block_maxima); -inf
    where the box misses the grid."""
    su = lt[k, LT_SU]
    sv = lt[k, LT_SV]
    nu = int(lt[k, LT_NU])
    nv = int(lt[k, LT_NV])
    fu0 = (u0 - hfp[0]) * su
    fu1 = (u1 - hfp[0]) * su
    fv0 = (v0 - hfp[2]) * sv
    fv1 = (v1 - hfp[2]) * sv
    if fu1 < 0.0 or fv1 < 0.0 or fu0 > nu - 1.0 or fv0 > nv - 1.0:
        return -np.inf
    ci0 = min(max(int(fu0), 0), nu - 2)
    ci1 = min(max(int(fu1), 0), nu - 2)
    cj0 = min(max(int(fv0), 0), nv - 2)
    cj1 = min(max(int(fv1), 0), nv - 2)
    ext = max(ci1 - ci0, cj1 - cj0) + 1
    m = 1
    while (2 << m) < ext and m < n_m - 1:       # blocks half the box: 3 x 3 at most
        m += 1
    row = k * n_m + m
    off = int(mt[row, 0])
    nc = int(mt[row, 2])
    best = -np.inf
    for bj in range(cj0 >> m, (cj1 >> m) + 1):
        for bi in range(ci0 >> m, (ci1 >> m) + 1):
            best = max(best, mx[off + bj * nc + bi])
    return best


@ngjit_inline
def _horizon_ray(vp, ymax):
    """(a, b): the ray of screen row ymax meets plane t of a column plane Pi at the
    height s = a t + b (relative to the centre): (s ca - t sa) d1 = y0 (s sa + t ca +
    d3), eqs. (4), (10). A point of Pi on plane t is seen above row ymax iff it lies
    above that height (its row is monotone in s)."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    d1 = vp[VP_D1]
    y0 = (ymax - (vp[VP_H] - 1.0) * 0.5) / vp[VP_SCALE]
    den = ca * d1 - y0 * sa                      # > 0: the rays point forward
    return (y0 * ca + sa * d1) / den, y0 * vp[VP_D3] / den


@ngjit_inline
def _hidden_until(mx, mt, n_m, lt, hfp, vp, x0, planes, i, j, s_lo, s_hi, ymax):
    """Are all points of the surface on column x0's plane between planes i and j
    surely below the floating horizon ymax? The plane's points there over the
    heights [s_lo, s_hi] lie in a parallelogram of the ground (Pi leans with the
    pitch); the highest height of the levels sampled over its box, projected at both
    ends (a constant height's row is monotone in t), must be below ymax."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    d1 = vp[VP_D1]
    d3 = vp[VP_D3]
    # the height of the horizon's ray on planes i and j (a point of Pi on plane t is
    # seen only above it)
    a_r, b_r = _horizon_ray(vp, ymax)
    s_min = s_hi
    for e in range(2):
        t = planes[i, 0] if e == 0 else planes[j, 0]
        s_min = min(s_min, a_r * t + b_r)
    if s_min > s_hi:
        return True                              # above the highest point
    s_min = max(s_min, s_lo)
    u0 = np.inf
    u1 = -np.inf
    v0 = np.inf
    v1 = -np.inf
    kx = x0 * sa / d1
    for e in range(2):
        t = planes[i, 0] if e == 0 else planes[j, 0]
        r0 = x0 * (t * ca + d3) / d1
        for s in (s_min, s_hi):
            r = r0 + kx * s
            u = vp[VP_CU] + r * cb + t * sb
            v = vp[VP_CV] - r * sb + t * cb
            u0 = min(u0, u)
            u1 = max(u1, u)
            v0 = min(v0, v)
            v1 = max(v1, v)
    top = -np.inf
    k_hi = min(int(planes[j, 1]) + 1, lt.shape[0] - 1)
    for k in range(int(planes[i, 1]), k_hi + 1):
        top = max(top, _region_max(mx, mt, n_m, lt, k, hfp, u0, u1, v0, v1))
    if top == -np.inf:
        return True
    s_top = top - vp[VP_CW]
    for e in range(2):
        t = planes[i, 0] if e == 0 else planes[j, 0]
        q = s_top * sa + t * ca + d3
        if q <= d1:
            return False
        y = (s_top * ca - t * sa) * d1 / q * vp[VP_SCALE] + (vp[VP_H] - 1.0) * 0.5
        if not y <= ymax:
            return False
    return True


@ngjit_inline
def _bilinear_at(flat, off, nu, nv2, gx, gy):
    """w of the level at offset off (level_ints' LK_OFF) with nu nodes along u and nv2
    + 2 along v at grid coordinates (gx, gy) (>= 0 inside the extent), as _bilinear's;
    _scan_hidden holds a level's parameters while its planes last."""
    i = min(max(int(gx), 0), nu - 2)
    j = min(max(int(gy), 0), nv2)
    fx = gx - i
    fy = gy - j
    b = off + j * nu + i
    z00 = flat[b]
    z01 = flat[b + nu]
    a0 = z00 + fx * (flat[b + 1] - z00)
    a1 = z01 + fx * (flat[b + nu + 1] - z01)
    return a0 + fy * (a1 - a0)


@ngjit_inline
def level_params(lt, lk, k):
    """What a walk over the planes holds while their level k lasts: the offset, nodes
    along u, nodes along v less 2 and nodes per unit of u and v of level k and of
    level k + 1 (the last level's own at the last), for blended_at."""
    k1 = min(k + 1, lk.shape[0] - 1)
    return (lk[k, LK_OFF], lk[k, LK_NU], lk[k, LK_NV2], lt[k, LT_SU], lt[k, LT_SV],
            lk[k1, LK_OFF], lk[k1, LK_NU], lk[k1, LK_NV2], lt[k1, LT_SU], lt[k1, LT_SV])


@ngjit_inline
def blended_at(flat, par, a, x, y):
    """The height at (x, y) from the extent's corner (u - u_a, v - v_a) of level k
    blended with level k + 1 by a (trilinear, as a mip-map's: no level boundary
    pops); par level_params(k)'s."""
    w = _bilinear_at(flat, par[0], par[1], par[2], x * par[3], y * par[4])
    if a > 0.0:
        w = (1.0 - a) * w + a * _bilinear_at(flat, par[5], par[6], par[7], x * par[8],
                                             y * par[9])
    return w


@ngjit_inline
def _scan_hidden(flat, lt, lk, hfp, vp, x0, planes, i, m_end, ymax):
    """The first plane m in i .. m_end - 1 whose surface point on column x0's plane
    Pi may rise above the floating horizon ymax (m_end where none does), one
    evaluation of the height field a plane: plane t's point of Pi at height s is
    seen above ymax iff s is above s_ray(t), where the horizon's ray crosses plane t
    (a point's row is monotone in s, eqs. 4, 10), and the surface's point on Pi lies
    above s_ray iff the surface there is, g(s) = f(u(s), v(s)) - s decreasing (as
    Newton's iteration in _place takes it). Each plane's test is independent of the
    last (no Newton chain): they overlap in the processor. A plane outside the
    domain or in a hole is not surely hidden. Returns m, the surface's height
    (relative to the centre) there on plane m - 1 (Newton's start for its sample)
    and the evaluations."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    d1 = vp[VP_D1]
    d3 = vp[VP_D3]
    cw = vp[VP_CW]
    a_r, b_r = _horizon_ray(vp, ymax)            # s_ray(t) = a_r t + b_r
    # Pi's point at s_ray(t): r = x0 (t ca + d3) / d1 + kx s_ray (eq. 9, ERRATA 2),
    # linear in t, and so are u and v (eq. 2)
    kx = x0 * sa / d1
    r0 = x0 * d3 / d1 + kx * b_r
    r1 = x0 * ca / d1 + kx * a_r
    u0 = vp[VP_CU] + r0 * cb
    du = r1 * cb + sb
    v0 = vp[VP_CV] - r0 * sb
    dv = cb - r1 * sb
    m = i
    s_last = np.nan
    ev = 0
    kc = -1                                      # the level whose parameters are held
    par = level_params(lt, lk, 0)
    ou = hfp[0]
    ov = hfp[2]
    while m < m_end:
        t = planes[m, 0]
        u = u0 + du * t
        v = v0 + dv * t
        if not in_domain(vp, u, v):
            break
        u, v = into_domain(vp, u, v)
        k = int(planes[m, 1])
        a = planes[m, 2]
        if k != kc:
            kc = k
            par = level_params(lt, lk, k)
        w = blended_at(flat, par, a, u - ou, v - ov)
        ev += 1
        if not w - cw < a_r * t + b_r:           # (a hole: not surely hidden)
            break
        s_last = w - cw
        m += 1
    return m, s_last, ev


@ngjit_inline
def _last_within(planes, i, j, tb):
    """The last plane from i to j (both taken, at most the last plane) at or before
    t = tb; i where none after i is."""
    j = min(j, planes.shape[0] - 1)
    while j > i and planes[j, 0] > tb:
        j -= 1
    return j


@ngjit_inline
def _step_lane(kind, fg, hf0, flat, lt, lk, mx, mt, n_m, hfp, vp, area, planes, skips, s_lo,
               s_hi, top, sl, pts, gcol, ecol, acc):
    """One lane's next plane (sl[ST_I]): the lane ends where its planes or its
    picture do. Where its last sample is hidden (or planes were skipped) it skips
    the planes up to ST_I + ST_JUMP that the block maxima show hidden (_hidden_until;
    not for a few steps after a failure), else those of the next max(ST_JUMP, SCAN_PLANES)
    that one evaluation each shows hidden (_scan_hidden); planes skipped need no
    sample (ST_SKIP) until one may show, when the last of them is sampled, the next
    run's first point."""
    n = planes.shape[0]
    i = int(sl[ST_I])
    if i >= n or planes[i, 0] > sl[ST_TB] or sl[ST_YMAX] >= top:
        sl[ST_DONE] = 1.0
        return
    x0 = sl[ST_X0]
    prev = pts[0]
    cur = pts[1]
    skipped = sl[ST_SKIP] != 0.0
    if skips and (skipped or (sl[ST_HAVE] != 0.0 and prev[Q_Y] < sl[ST_YMAX])):
        jump = int(sl[ST_JUMP])
        j = _last_within(planes, i, i + jump, sl[ST_TB])
        if sl[ST_WAIT] == 0.0 and j > i + 1 and _hidden_until(
                mx, mt, n_m, lt, hfp, vp, x0, planes, i, j, s_lo, s_hi, sl[ST_YMAX]):
            sl[ST_JUMP] = min(2 * jump, SKIP_MAX)
            sl[ST_BACK] = 0.0
            sl[ST_SKIP] = 1.0
            sl[ST_I] = j + 1
            return
        if sl[ST_WAIT] == 0.0:
            # failed: the next 1, 2, 4, 8 hidden steps after successive failures
            # leave the test out
            sl[ST_JUMP] = max(jump // 2, SKIP_MIN)
            sl[ST_BACK] = min(max(2.0 * sl[ST_BACK], 1.0), BLOCK_BACKOFF)
            sl[ST_WAIT] = sl[ST_BACK]
        else:
            sl[ST_WAIT] -= 1.0
        j = _last_within(planes, i, max(j, i + SCAN_PLANES), sl[ST_TB])
        m, s_last, ev = _scan_hidden(flat, lt, lk, hfp, vp, x0, planes, i, j + 1, sl[ST_YMAX])
        sl[ST_EVALS] += ev
        if m == j + 1:
            # all hidden: nothing to sample yet
            sl[ST_SKIP] = 1.0
            sl[ST_S] = s_last
            sl[ST_I] = j + 1
            return
        # plane m may show: the plane before it (hidden, skipped) is the next run's
        # first point, sampled now (Newton from the surface's height there)
        if m > i:
            i = m - 1
            sl[ST_S] = s_last
            sl[ST_HAVE] = 0.0
        elif skipped:
            i -= 1
            sl[ST_HAVE] = 0.0
        sl[ST_SKIP] = 0.0
    if _sample_lane(kind, fg, hf0, flat, lt, hfp, vp, x0, planes[i, 0], int(planes[i, 1]),
                    planes[i, 2], sl, prev, cur):
        _draw_lane(kind, fg, hf0, flat, lt, hfp, vp, x0, area, sl, pts, gcol, ecol, acc)
    else:
        sl[ST_HAVE] = 0.0
    sl[ST_I] = i + 1


@ngjit_nrt_free
def lod_tile(kind, fg, hf0, flat, lt, lk, mx, mt, hfp, vp, c0, l0, lanes, area, planes, s_lo,
             s_hi, gtile, etile, acc, pts, st, out):
    """Render the columns c0 + l0 .. c0 + l0 + lanes - 1 of one tile (gtile (H, TILE,
    G_SIZE), etile (E_SIZE, H, TILE); lanes l0 .. l0 + lanes - 1) one after another: the
    CPU's tile all its lanes, a GPU thread one (kernels/cuda.py). ``area``: Cohen-Or's
    weights (acc: lanes x H x AC_SIZE) instead of pixel centres; ``planes``
    plane_table's, [s_lo, s_hi] the surface's heights relative to the centre; mx, mt a
    height field's block maxima (passes/lod.py), which let a column skip the planes
    where the surface is surely hidden. Writes each lane's evaluations, lowest and
    highest w seen, lowest and highest row set to out[lane - l0] (acc, pts and st
    indexed so too)."""
    H = gtile.shape[0]
    top = H - 0.5
    n_m = mt.shape[0] // max(lt.shape[0], 1)
    skips = kind == SURF_HEIGHTFIELD and mt.shape[0] > 0 and s_lo == s_lo
    for L in range(l0, l0 + lanes):
        k = L - l0
        etile[E_SEEN, :, L] = 0.0
        if area:
            clear_accumulators(acc[k])
        x0 = column_x0(vp, c0 + L)
        sl = st[k]
        _start(vp, x0, s_lo, s_hi, planes, sl)
        sl[ST_JLO] = H
        sl[ST_JHI] = -1
        sl[ST_X0] = x0
        sl[ST_I] = sl[ST_I0]
        sl[ST_JUMP] = SKIP_MIN
        sl[ST_WAIT] = 0.0
        sl[ST_BACK] = 0.0
        sl[ST_SKIP] = 0.0
        while sl[ST_DONE] == 0.0:
            _step_lane(kind, fg, hf0, flat, lt, lk, mx, mt, n_m, hfp, vp, area, planes, skips,
                       s_lo, s_hi, top, sl, pts[k], gtile[:, L], etile[:, :, L], acc[k])
        w_lo, w_hi = _resolve(area, gtile[:, L], etile[:, :, L], acc[k], sl)
        out[k, 0] = sl[ST_EVALS]
        out[k, 1] = w_lo
        out[k, 2] = w_hi
        out[k, 3] = sl[ST_JLO]
        out[k, 4] = sl[ST_JHI]


def _lod_functions(kind, fg, hf0, flat, lv, mx, mt, hfp, vp, area, lod, kappa, s_lo, s_hi,
                   gbuf, ebuf, evals, wrange, rows):
    """lod_kernel's jitted functions: lod_tile, called with the kernel's arguments, its
    tables and a tile's buffers and scratch (_jit.kernel_calling)."""
    i64 = types.int64
    grid = types.Array(types.float64, 2, "C")
    block = types.Array(types.float64, 3, "C")
    tiles = types.Array(numba.from_dtype(gbuf.dtype), 3, "C")
    return ((lod_tile, function_type(
        lod_tile, kind, fg, hf0, flat, grid, types.Array(i64, 2, "C"), mx, mt, hfp, vp, i64,
        i64, i64, area, grid, s_lo, s_hi, tiles,
        types.Array(numba.from_dtype(ebuf.dtype), 3, "C"), block, block, grid, grid)),)


@kernel_calling(_lod_functions, (lod_tile,))
def lod_kernel(kind, fg, hf0, flat, lv, mx, mt, hfp, vp, area, lod, kappa, s_lo, s_hi, gbuf,
               ebuf, evals, wrange, rows, tile):
    """Every tile by lod_tile into the tiled gbuf and ebuf (layout.py), the tiles in
    parallel; each tile's scratch is its own, each column starts afresh (the picture
    is the same for any number of threads). ``tile``: lod_tile as a function value
    (_jit.kernel_calling)."""
    n_tiles = gbuf.shape[0]
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    W = evals.shape[0]
    s_ref = 0.5 * (s_lo + s_hi) if s_lo == s_lo else 0.0
    planes = plane_table(kind, lv, vp, lod, kappa, s_ref)
    lt = level_table(lv, hfp)
    lk = level_ints(lv)
    for b_ in prange(n_tiles):
        b = np.int64(b_)  # (_jit.py: prange_index)
        acc = np.empty((T, H if area else 1, AC_SIZE))
        pts = np.empty((T, 3 + REFINE_DEPTH, Q_SIZE))
        st = np.empty((T, ST_SIZE))
        out = np.empty((T, 5))
        lanes = min(T, W - b * T)
        tile(kind, fg, hf0, flat, lt, lk, mx, mt, hfp, vp, b * T, 0, lanes, area, planes, s_lo,
             s_hi, gbuf[b], ebuf[b], acc, pts, st, out)
        rows[b, 0] = H
        rows[b, 1] = -1
        for L in range(lanes):
            c = b * T + L
            evals[c] = int(out[L, 0])
            wrange[c, 0] = out[L, 1]
            wrange[c, 1] = out[L, 2]
            rows[b, 0] = min(rows[b, 0], int(out[L, 3]))
            rows[b, 1] = max(rows[b, 1], int(out[L, 4]))

"""Every layer of a surface along each pixel's ray (Gordon 6.5), composited front to
back (6.6) with the layers of other surfaces.

Section 6.5: between two successive sampling planes the surface's curve in a column
covers the pixel rows between its two samples; the opaque column keeps only the rows
outside the floating interval, a translucent surface needs them all. Every pixel
centre between two samples is a crossing of its ray with the surface, its depth,
normal, height and intensity interpolated as the opaque column's, in the order of the
planes, which is front to back along each ray (column.py's module note: in
perspective the passes go from the viewpoint's t outward).

Each crossing is lit (shade.py's _light, the shadow texture's point_shadow, or
soft_shadow under a light of a radius) and
coloured (shade._side_rgb) as the opaque surface's pixel would be, and kept in the
pixel's list: up to K records per surface, sorted by depth, colour and intensity
premultiplied by alpha. A full list folds its two deepest records into one (the over
operator is associative: exact when no other surface's crossing falls between them),
so K = 1 is exact for one surface alone; a surface whose own transmittance at the
pixel has fallen below STOP takes no more crossings there. The composite kernel
merges the surfaces' lists by depth and composites them over a transmittance that
stops at STOP too.

Antialiasing (vp's VP_AA): a crossing covers the part of its pixel's height that its
monotone stretch of the curve covers: where the curve turns (a silhouette, the fold of
6.5's hidden layers) or ends (the domain's edge, a hole) inside a pixel, its alpha is
that part of the opacity. Without it a crossing is a pixel centre between two samples,
full opacity: the composite is then exactly sum_k a (1 - a)^k I_k.

Memory: the lists of a band of columns (passes/translucency.py picks the band), each
column's scratch its own (no shared scratch across the parallel columns).
"""
import math

import numpy as np
from numba import prange, types

from ._jit import (function_type, kernel_calling, ngjit, ngjit_inline, ngjit_nrt_free,
                   ngjit_parallel)
from .column import (
    _column_t_range, _copy, _grid_range, _ortho_chord, CLIP_MARGIN_PLANES, CLIP_TOL,
    store_sample)
from .index import ceil_index, floor_index
from .layout import (
    A_BUMP, A_I, A_NX, A_NY, A_NZ, A_SIZE, A_T, A_U, A_V, A_VN, A_W, A_Y, A_Z,
    G_DEPTH, G_I, G_NX, G_NY, G_NZ, G_SIZE, G_T, G_U, G_V, G_W,
    M_ALPHA, M_LOWER, M_SPAN, M_WLO, S_OK,
    VP_AA, VP_CA, VP_CB, VP_CU, VP_CV, VP_CW, VP_D1, VP_D3, VP_DT, VP_FOLD, VP_H, VP_ORTHO,
    VP_SA, VP_SB,
    VP_SCALE, VP_T0, VP_T1, VP_W, VP_WORG,
)
from .fold import (
    FOLD_NEAR, P_I, P_NX, P_NY, P_NZ, P_T, P_U, P_V, P_W, X_DEPTH, XING_COUNT, XING_SIZE,
    fold_test, layers_fold_scratch, trace_layers_into)
from .sample import column_x0, sample_point
from .shade import _light, _side_rgb, toward_viewer
from .texture import LN_FN, LN_WIRE, layer_field, layer_lines, layer_texel, layer_wire_coords
from .raster import _blocked_at
from .shadow import point_shadow, soft_shadow

#: transmittance below which nothing behind shows (1/512: under half a level of 8 bits)
STOP = 1.0 / 512.0
#: bisections that find where a run of samples meets the domain's edge or a hole
EDGE_BISECTIONS = 12
#: a span between two samples is halved (at most REFINE_DEPTH times: 1/64 of a step)
#: where the curve folds between them (the seen side changes: a silhouette, section
#: 5.1's ridge) or where it spans more than REFINE_ROWS rows while its normal turns by
#: more than REFINE_TURN (cos of the angle): linear interpolation would misplace the
#: layers there
REFINE_DEPTH = 6
REFINE_ROWS = 1.5
REFINE_TURN = 0.98
#: rows of a pass's scratch: prev, cur, edge, tmp, pend, crec, wk, then the stack
SCR_STACK = 7

# A crossing's record in the lists (float32)
C_DEPTH = 0
C_R = 1           # colour times alpha (premultiplied)
C_G = 2
C_B = 3
C_I = 4           # intensity times alpha
C_A = 5           # alpha
C_SIDE = 6        # +1 upper side, -1 lower side (of the front record, once folded)
C_SHADOW = 7      # 1 in shadow, 0 lit (likewise)
C_SIZE = 8

# The shadow vector sh (float64): passes/shadow.py's Texture of the light, or SH_ON 0
SH_LX = 0         # the light's direction in screen coordinates (point_shadow's light)
SH_LY = 1
SH_LZ = 2
SH_ON = 3
SH_LAYER = 4      # this surface's layer of the texture
SH_GU = 5
SH_GV = 6
SH_TAN = 7
SH_S0 = 8
SH_T0 = 9
SH_H = 10
SH_GRAZING = 11
SH_BIAS = 12
# the objects' occluders (objects.Occluders, or DiskOccluders' directions over a
# light's disk; occ = (frames, coef, start, items, grids)): SH_OBJ how many directions
# a crossing's ray toward the light is tested in against their triangles (0: none)
SH_OBJ = 13
SH_RHO = 14       # the light's angular radius (radians; 0: hard shadows, point_shadow)
SH_SIZE = 15
# a direction's row of occ's grids (float64): its grid's origin across the light, its
# cells per unit and size, the bias, and where its coef, start and items begin
OG_A = 0
OG_B = 1
OG_INV = 2
OG_NA = 3
OG_NB = 4
OG_BIAS = 5       # a triangle blocks a point below it by more than this
OG_COEF = 6
OG_START = 7
OG_ITEMS = 8
OG_SIZE = 9

# The walker's state, wk (float64): a run's stretch of the curve (monotone in y) and
# the pixel it is in, whose crossing waits until the stretch leaves it or ends
W_DIR = 0         # +1 rising, -1 falling, 0 not yet known
W_PJ = 1          # the waiting pixel (row from the bottom); W_NONE: none
W_PSTART = 2      # where the stretch's part in it began (a y)
W_PCEN = 3        # 1.0: the stretch crossed its centre (the record is the centre's)
W_FOLD = 4        # 1.0: a perspective sample where the curve folds back in t (fold.py)
W_SIZE = 5
W_NONE = -1e18


@ngjit_inline
def _round_row(y):
    return floor_index(y + 0.5)


@ngjit_inline
def _weight(vp, p, q, y):
    """Where row y lies between samples p and q (0 at p, 1 at q): in perspective the
    fraction of the chord between the two points (a line in the world is a line on
    the screen, but its parameter is not linear in y: eq. 10's division by depth)."""
    h2 = (vp[VP_H] - 1.0) * 0.5
    yp = p[A_Y] - h2
    yq = q[A_Y] - h2
    yc = y - h2
    if vp[VP_ORTHO] != 0.0:
        return (yc - yp) / (yq - yp)
    qp = (p[A_Z] + vp[VP_D3]) * (yp - yc)
    qq = (q[A_Z] + vp[VP_D3]) * (yq - yc)
    return qp / (qp - qq)


@ngjit_inline
def _between(rec, p, q, lam, y):
    """rec: the point a fraction lam from p to q, on row y."""
    for k in range(A_SIZE):
        rec[k] = p[k] + (q[k] - p[k]) * lam
    rec[A_Y] = y


@ngjit_inline
def _over(lists, b, j, x, y):
    """Record x of pixel (b, j) = x over y (premultiplied: x in front)."""
    t = 1.0 - lists[b, j, x, C_A]
    for k in range(C_R, C_A):
        lists[b, j, x, k] += t * lists[b, j, y, k]
    lists[b, j, x, C_A] = 1.0 - t * (1.0 - lists[b, j, y, C_A])


@ngjit_nrt_free
def _keep(lists, b, j, off, K, n, rec):
    """Put the crossing ``rec`` (C_SIZE) into the pixel's sorted list lists[b, j, off:off
    + K] of n records; returns (the new n, its place: 0 the front)."""
    d = rec[C_DEPTH]
    pos = n
    while pos > 0 and lists[b, j, off + pos - 1, C_DEPTH] > d:
        pos -= 1
    if n == K:
        if pos == K:                     # behind them all: folded into the last
            t = 1.0 - lists[b, j, off + K - 1, C_A]
            for k in range(C_R, C_A):
                lists[b, j, off + K - 1, k] += t * rec[k]
            lists[b, j, off + K - 1, C_A] = 1.0 - t * (1.0 - rec[C_A])
            return n, pos
        if K == 1:                       # in front of the one: it goes over it
            t = 1.0 - rec[C_A]
            for k in range(C_R, C_A):
                lists[b, j, off, k] = rec[k] + t * lists[b, j, off, k]
            lists[b, j, off, C_A] = 1.0 - t * (1.0 - lists[b, j, off, C_A])
            lists[b, j, off, C_DEPTH] = rec[C_DEPTH]
            lists[b, j, off, C_SIDE] = rec[C_SIDE]
            lists[b, j, off, C_SHADOW] = rec[C_SHADOW]
            return n, pos
        _over(lists, b, j, off + K - 2, off + K - 1)   # room: the two deepest become one
        n -= 1
    for m in range(n, pos, -1):
        for k in range(C_SIZE):
            lists[b, j, off + m, k] = lists[b, j, off + m - 1, k]
    for k in range(C_SIZE):
        lists[b, j, off + pos, k] = rec[k]
    return n + 1, pos


#: |N.V| below which _axis_grads takes it as this (a silhouette's grazing tangent
#: plane: the lines there as wide as at 1/GRAZE of the obliquity, not infinitely)
GRAZE = 0.05


@ngjit_inline
def _pixel_step(vp, nx, ny, nz, vx, vy, vz, depth):
    """(cos alpha, sin alpha, cos beta, sin beta, m, N.V) of _axis_grads: the view's
    angles, the pixel's step m across the ray at ``depth``, and N.V kept from GRAZE."""
    m = 1.0 / vp[VP_SCALE]
    if vp[VP_ORTHO] == 0.0:
        m *= (depth + vp[VP_D3]) / vp[VP_D1]
    nv = nx * vx + ny * vy + nz * vz
    if abs(nv) < GRAZE:
        nv = GRAZE if nv >= 0.0 else -GRAZE
    return vp[VP_CA], vp[VP_SA], vp[VP_CB], vp[VP_SB], m, nv


@ngjit_inline
def _axis_grads(vp, nx, ny, nz, vx, vy, vz, depth):
    """How much u, v and w (the box's units) change from a point of the surface to
    the one a pixel away on the screen, (nx, ny, nz) its unit normal and (vx, vy, vz)
    the unit vector toward the viewer there (screen coordinates): the pixel's step m
    across the ray (1 / scale, times the distance over d1 in perspective) and along
    the ray back onto the tangent plane, ΔP = m (a, b, 0) + c D with D = -V and
    N.ΔP = 0, so that Δq = m (a (g_x - n_x k) + b (g_y - n_y k)), k = g.V / N.V,
    for g the screen image of q's axis (the rotation of eqs. 1-2's columns)."""
    ca, sa, cb, sb, m, nv = _pixel_step(vp, nx, ny, nz, vx, vy, vz, depth)
    # the axes u, v, w on the screen: (cb, -sa sb, ca sb), (-sb, -sa cb, ca cb), (0, ca, sa)
    return (_along(cb, -sa * sb, ca * sb, nx, ny, vx, vy, vz, nv, m),
            _along(-sb, -sa * cb, ca * cb, nx, ny, vx, vy, vz, nv, m),
            _along(0.0, ca, sa, nx, ny, vx, vy, vz, nv, m))


@ngjit_inline
def _along(gx, gy, gz, nx, ny, vx, vy, vz, nv, m):
    """_axis_grads' Δq a pixel for q's gradient g = (gx, gy, gz) on the screen."""
    k = (gx * vx + gy * vy + gz * vz) / nv
    return m * math.hypot(gx - nx * k, gy - ny * k)


@ngjit_inline
def _field_grad(vp, qu, qv, nx, ny, nz, vx, vy, vz, depth):
    """_axis_grads for a colour field q(u, v) of partials qu, qv (box units): its
    gradient on the screen qu times u's axis plus qv times v's."""
    ca, sa, cb, sb, m, nv = _pixel_step(vp, nx, ny, nz, vx, vy, vz, depth)
    return _along(qu * cb - qv * sb, -(qu * sb + qv * cb) * sa, (qu * sb + qv * cb) * ca,
                  nx, ny, vx, vy, vz, nv, m)


@ngjit_inline
def _objects_block(u, v, w, occ, n):
    """The part of occ's n directions toward the light (one: a point light) in which
    a triangle hides the point (u, v, w): raster.occluded_kernel's test in each (the
    objects' cast shadow, as objects.Occluders or DiskOccluders.blocked)."""
    frames, coef, start, items, grids = occ
    hit = 0
    for k in range(n):
        g = grids[k]
        if _blocked_at(u, v, w, -1, frames[k], coef[int(g[OG_COEF]):],
                       start[int(g[OG_START]):], items[int(g[OG_ITEMS]):], g[OG_A], g[OG_B],
                       g[OG_INV], int(g[OG_NA]), int(g[OG_NB]), g[OG_BIAS]):
            hit += 1
    return hit / n


@ngjit_nrt_free
def _emit(vp, x0, j, p, cov, mp, lut, sh, hmax, hmin, hsurf, slopes, occ, lists, off, K,
          counts, trans, gfirst, hits, b, crec):
    """The crossing of row j's ray at the point p (A_SIZE), covering ``cov`` of the
    pixel: lit, coloured and kept in the pixel's list."""
    H = trans.shape[0]
    if j < 0 or j >= H or not cov > 0.0:
        return
    hits[b, j] += 1
    if trans[j] < STOP:
        return                           # this surface hides whatever else of it follows
    depth = p[A_Z]
    nx = p[A_NX]
    ny = p[A_NY]
    nz = p[A_NZ]
    vx, vy, vz = toward_viewer(vp, x0, j, depth)
    side = 1.0 if nx * vx + ny * vy + nz * vz >= 0.0 else -1.0
    shade = 0.0
    if sh[SH_ON] != 0.0:
        if sh[SH_RHO] > 0.0:             # a light of a radius: the part of its disk hidden
            # (w from the texture's origin, the view's w_origin: layout.py G_W)
            shade = soft_shadow(side, p[A_U], p[A_V], p[A_W] - vp[VP_WORG], nx, ny, nz, sh,
                                hmax, hmin, hsurf, slopes, int(sh[SH_LAYER]), sh[SH_GU],
                                sh[SH_GV], sh[SH_TAN], sh[SH_S0], sh[SH_T0], sh[SH_H],
                                sh[SH_GRAZING], sh[SH_BIAS], sh[SH_RHO])
        else:
            shade = point_shadow(side, p[A_U], p[A_V], p[A_W] - vp[VP_WORG], nx, ny, nz, sh,
                                 hmax, hmin, hsurf, int(sh[SH_LAYER]), sh[SH_GU], sh[SH_GV],
                                 sh[SH_TAN], sh[SH_S0], sh[SH_T0], sh[SH_H], sh[SH_GRAZING],
                                 sh[SH_BIAS])
        if sh[SH_OBJ] != 0.0 and shade < 1.0:
            shade = max(shade, _objects_block(p[A_U], p[A_V], p[A_W], occ, int(sh[SH_OBJ])))
    inten, spec = _light(vp, x0, j, nx, ny, nz, p[A_I], mp, 1.0 - shade)
    # ``lut`` is the tuple (lut, levels, offsets, shapes, tp, lines) of texture.py's
    # TP_* and LN_*: the side's colour table, a texture (no levels: none) over it, and
    # lines (empty: none)
    r, g, bl = _side_rgb(side, p[A_W], lut[0], mp[M_WLO], mp[M_SPAN], mp[M_LOWER:])
    if lut[1].shape[0] > 0:
        # the pixel's footprint on the surface: 1 / scale on the screen, at the point's
        # distance (perspective), stretched by the obliquity (|N.V|, from 0.05)
        fp = 1.0 / vp[VP_SCALE]
        if vp[VP_ORTHO] == 0.0:
            fp *= (depth + vp[VP_D3]) / vp[VP_D1]
        fp /= max(abs(nx * vx + ny * vy + nz * vz), 0.05)
        tex = crec[C_SIZE:C_SIZE + 4]
        layer_texel(lut, p[A_U], p[A_V], fp, tex)
        r = tex[0] + (1.0 - tex[3]) * r
        g = tex[1] + (1.0 - tex[3]) * g
        bl = tex[2] + (1.0 - tex[3]) * bl
    a = mp[M_ALPHA] * min(cov, 1.0)
    crec[C_DEPTH] = depth
    crec[C_R] = a * min(r * inten + spec, 1.0)
    crec[C_G] = a * min(g * inten + spec, 1.0)
    crec[C_B] = a * min(bl * inten + spec, 1.0)
    crec[C_I] = a * inten
    if lut[5].shape[0] > 0:
        # contour and wireframe lines on the surface, of its opacity (matplotlib's edges
        # of a translucent surface: its alpha): the lines' part la of the pixel at
        # alpha a laid over the lit crossing, an unlit colour as the opaque overlays';
        # the intensity, which those leave alone, the crossing's at the alpha of both
        gu, gv, gw = _axis_grads(vp, nx, ny, nz, vx, vy, vz, depth)
        q = p[A_W]
        if lut[5][LN_FN] > 0.0:          # the contours are a colour field's
            q, qu, qv = layer_field(lut[5], p[A_U], p[A_V])
            gw = _field_grad(vp, qu, qv, nx, ny, nz, vx, vy, vz, depth)
        wa = p[A_U]
        wb = p[A_V]
        if lut[5][LN_WIRE] == 3.0:       # a curvilinear mesh's lines: of its indices
            wa, au, av, wb, bu, bv = layer_wire_coords(lut[5], p[A_U], p[A_V])
            gu = _field_grad(vp, au, av, nx, ny, nz, vx, vy, vz, depth)
            gv = _field_grad(vp, bu, bv, nx, ny, nz, vx, vy, vz, depth)
        lr, lg, lb, la = layer_lines(lut[5], wa, wb, q, gu, gv, gw)
        if la > 0.0:
            keep = 1.0 - a * la
            crec[C_R] = a * lr + keep * crec[C_R]
            crec[C_G] = a * lg + keep * crec[C_G]
            crec[C_B] = a * lb + keep * crec[C_B]
            a = a * la + keep * a
            crec[C_I] = a * inten
    crec[C_A] = a
    crec[C_SIDE] = side
    crec[C_SHADOW] = shade
    trans[j] *= 1.0 - a
    counts[b, j], pos = _keep(lists, b, j, off, K, counts[b, j], crec)
    if pos == 0:                         # the surface's nearest crossing: its G-buffer
        gfirst[b, j, G_DEPTH] = depth
        gfirst[b, j, G_U] = p[A_U] - vp[VP_CU]     # (from the centre: layout.py G_U)
        gfirst[b, j, G_V] = p[A_V] - vp[VP_CV]
        gfirst[b, j, G_W] = p[A_W] - vp[VP_WORG]   # (layout.py G_W)
        gfirst[b, j, G_NX] = nx
        gfirst[b, j, G_NY] = ny
        gfirst[b, j, G_NZ] = nz
        gfirst[b, j, G_I] = p[A_I]
        gfirst[b, j, G_T] = p[A_T]


@ngjit_nrt_free
def _flush(vp, x0, wk, pend, end_y, aa, mp, lut, sh, hmax, hmin, hsurf, slopes, occ, lists,
           off, K, counts, trans, gfirst, hits, b, crec):
    """The waiting pixel's crossing, its stretch ending (or leaving it) at end_y."""
    j = wk[W_PJ]
    if j == W_NONE:
        return
    wk[W_PJ] = W_NONE
    if aa:
        lo = j - 0.5
        hi = j + 0.5
        cov = abs(min(max(end_y, lo), hi) - min(max(wk[W_PSTART], lo), hi))
    else:
        cov = 1.0 if wk[W_PCEN] != 0.0 else 0.0
    _emit(vp, x0, int(j), pend, cov, mp, lut, sh, hmax, hmin, hsurf, slopes, occ, lists, off,
          K, counts, trans, gfirst, hits, b, crec)


@ngjit_nrt_free
def _wait(wk, pend, j, start, rec, centre):
    wk[W_PJ] = j
    wk[W_PSTART] = start
    wk[W_PCEN] = 1.0 if centre else 0.0
    _copy(pend, rec)


@ngjit_inline
def _segment(vp, x0, p, q, wk, pend, tmp, aa, mp, lut, sh, hmax, hmin, hsurf, slopes, occ,
             lists, off, K, counts, trans, gfirst, hits, b, crec):
    """The crossings between successive samples p and q of a run (section 6.5)."""
    H = trans.shape[0]
    dy = q[A_Y] - p[A_Y]
    if not dy != 0.0:
        return
    d = 1.0 if dy > 0.0 else -1.0
    if wk[W_DIR] != 0.0 and d != wk[W_DIR]:
        # the curve turns at p: the stretch before ends there, a new one begins
        _flush(vp, x0, wk, pend, p[A_Y], aa, mp, lut, sh, hmax, hmin, hsurf, slopes, occ,
               lists, off, K, counts, trans, gfirst, hits, b, crec)
        _wait(wk, pend, _round_row(p[A_Y]), p[A_Y], p, False)
    wk[W_DIR] = d
    # the pixel centres j crossed: p.y <= j < q.y rising, q.y < j <= p.y falling
    if d > 0.0:
        ja = max(ceil_index(p[A_Y]), -1)
        jb = min(ceil_index(q[A_Y]) - 1, H)
    else:
        ja = min(floor_index(p[A_Y]), H)
        jb = max(floor_index(q[A_Y]) + 1, -1)
    jq = _round_row(q[A_Y])
    step = 1 if d > 0.0 else -1
    n = (jb - ja) * step + 1
    for m in range(max(n, 0)):
        j = ja + m * step
        _between(tmp, p, q, _weight(vp, p, q, float(j)), float(j))
        if j == wk[W_PJ]:
            _copy(pend, tmp)
            wk[W_PCEN] = 1.0
            continue
        _flush(vp, x0, wk, pend, wk[W_PJ] + 0.5 * d, aa, mp, lut, sh, hmax, hmin,
               hsurf, slopes, occ, lists, off, K, counts, trans, gfirst, hits, b, crec)
        if j == jq:                      # the stretch is still in this pixel at q
            _wait(wk, pend, j, j - 0.5 * d, tmp, True)
        else:
            _emit(vp, x0, j, tmp, 1.0, mp, lut, sh, hmax, hmin, hsurf, slopes, occ, lists, off,
                  K, counts, trans, gfirst, hits, b, crec)
    if jq != wk[W_PJ]:                   # q lies in a pixel whose centre it has not reached
        _flush(vp, x0, wk, pend, wk[W_PJ] + 0.5 * d, aa, mp, lut, sh, hmax, hmin,
               hsurf, slopes, occ, lists, off, K, counts, trans, gfirst, hits, b, crec)
        _wait(wk, pend, jq, jq - 0.5 * d, q, False)


@ngjit_nrt_free
def _sample(kind, f, fg, hf, hfp, vp, x0, t, out, guess):
    """The surface's point on plane t into out (A_*); returns (status, evaluations,
    the Newton start for the next plane)."""
    st, ev, y, z, u, v, w, nx, ny, nz, lam = sample_point(kind, f, fg, hf, hfp, vp, x0, t,
                                                          guess)
    store_sample(out, y, z, u, v, w, nx, ny, nz, lam, t)
    out[A_BUMP] = 0.0
    if st == S_OK:
        vx, vy, vz = toward_viewer(vp, x0, y, z)
        out[A_VN] = nx * vx + ny * vy + nz * vz
    return st, ev, (w - vp[VP_CW]) if st == S_OK else guess


@ngjit_inline
def _refined(kind, f, fg, hf, hfp, vp, x0, p, q, scr, evals, wk, pend, tmp, aa, mp, lut,
             sh, hmax, hmin, hsurf, slopes, occ, lists, off, K, counts, trans, gfirst, hits, b,
             crec):
    """_segment from p to q, the span halved where it needs it (REFINE_*), the halves
    in order (a stack of right ends in scr's rows from SCR_STACK). Returns evals plus
    the evaluations made."""
    stack = scr[SCR_STACK:]
    left = scr[SCR_STACK - 1 + stack.shape[0]]          # (the last row: the left end)
    _copy(left, p)
    _copy(stack[0], q)
    top = 0
    while top >= 0:
        right = stack[top]
        depth = right[A_BUMP]
        split = False
        if depth < REFINE_DEPTH and top + 1 < stack.shape[0] - 1:
            if (left[A_VN] > 0.0) != (right[A_VN] > 0.0):
                split = True
            elif abs(right[A_Y] - left[A_Y]) > REFINE_ROWS:
                dot = (left[A_NX] * right[A_NX] + left[A_NY] * right[A_NY]
                       + left[A_NZ] * right[A_NZ])
                split = dot < REFINE_TURN
        if split:
            mid = stack[top + 1]
            st, ev, _ = _sample(kind, f, fg, hf, hfp, vp, x0, 0.5 * (left[A_T] + right[A_T]),
                                mid, (left[A_W] + right[A_W]) * 0.5 - vp[VP_CW])
            evals += ev
            if st == S_OK:
                right[A_BUMP] = depth + 1.0
                mid[A_BUMP] = depth + 1.0
                top += 1
                continue
        _segment(vp, x0, left, right, wk, pend, tmp, aa, mp, lut, sh, hmax, hmin,
                 hsurf, slopes, occ, lists, off, K, counts, trans, gfirst, hits, b, crec)
        _copy(left, right)
        top -= 1
    return evals


@ngjit_nrt_free
def _start(wk, pend, p):
    """A run of samples begins at p."""
    wk[W_DIR] = 0.0
    _wait(wk, pend, _round_row(p[A_Y]), p[A_Y], p, False)


@ngjit_nrt_free
def _layer_pass(kind, f, fg, hf, hfp, vp, x0, ta, tb, mp, lut, sh, hmax, hmin,
                hsurf, slopes, occ, lists, off, K, counts, trans, gfirst, hits, b, scr):
    """One pass over the planes from ta to tb (front to back along the column's rays:
    the grid's planes t0 + k dt between them, as the opaque column's); returns the
    evaluations of f. Where a run of samples begins or ends between two planes (the
    domain's edge, a hole, the screen plane) its end is found by bisection."""
    prev = scr[0]
    cur = scr[1]
    edge = scr[2]
    tmp = scr[3]
    pend = scr[4]
    crec = scr[5]
    wk = scr[6]
    aa = vp[VP_AA] != 0.0
    folds = vp[VP_ORTHO] == 0.0 and vp[VP_FOLD] != 0.0
    t0 = vp[VP_T0]
    dt = vp[VP_DT]
    lo = min(ta, tb)
    hi = max(ta, tb)
    ka, kb = _grid_range(t0, dt, lo, hi)
    n = max(kb - ka + 1, 0) + 2 if hi > lo else 1
    up = tb >= ta
    evals = 0
    guess = np.nan
    prev_ok = False
    prev_t = ta
    wk[W_DIR] = 0.0
    wk[W_PJ] = W_NONE
    for i in range(n):
        if i == 0:
            t = ta
        elif i == n - 1:
            t = tb
        else:
            t = t0 + (ka + i - 1 if up else kb - (i - 1)) * dt
        st, ev, guess = _sample(kind, f, fg, hf, hfp, vp, x0, t, cur, guess)
        evals += ev
        ok = st == S_OK
        if ok and folds and fold_test(vp, x0, cur[A_NX], cur[A_NY], cur[A_NZ], 0.0):
            wk[W_FOLD] = 1.0
        if ok != prev_ok and i > 0:
            t_in = t if ok else prev_t
            t_out = prev_t if ok else t
            found = False
            g = guess
            for _ in range(EDGE_BISECTIONS):
                tm = 0.5 * (t_in + t_out)
                sm, ev, g2 = _sample(kind, f, fg, hf, hfp, vp, x0, tm, tmp, g)
                evals += ev
                if sm == S_OK:
                    t_in = tm
                    _copy(edge, tmp)
                    found = True
                    g = g2
                else:
                    t_out = tm
            if found and folds and fold_test(vp, x0, edge[A_NX], edge[A_NY], edge[A_NZ],
                                             FOLD_NEAR):
                wk[W_FOLD] = 1.0                # (a rim's last sample: nearly a fold)
            if ok:
                _start(wk, pend, edge if found else cur)
                if found:
                    evals = _refined(kind, f, fg, hf, hfp, vp, x0, edge, cur, scr, evals, wk, pend,
                                     tmp, aa, mp, lut, sh, hmax, hmin, hsurf, slopes, occ, lists,
                                     off, K, counts, trans, gfirst, hits, b, crec)
            else:
                last = prev
                if found:
                    evals = _refined(kind, f, fg, hf, hfp, vp, x0, prev, edge, scr, evals, wk, pend,
                                     tmp, aa, mp, lut, sh, hmax, hmin, hsurf, slopes, occ, lists,
                                     off, K, counts, trans, gfirst, hits, b, crec)
                    last = edge
                _flush(vp, x0, wk, pend, last[A_Y], aa, mp, lut, sh, hmax, hmin,
                       hsurf, slopes, occ, lists, off, K, counts, trans, gfirst, hits, b, crec)
        elif ok and i == 0:
            _start(wk, pend, cur)
        elif ok:
            evals = _refined(kind, f, fg, hf, hfp, vp, x0, prev, cur, scr, evals, wk, pend, tmp,
                             aa, mp, lut, sh, hmax, hmin, hsurf, slopes, occ, lists, off, K,
                             counts, trans, gfirst, hits, b, crec)
        if ok:
            _copy(prev, cur)
        prev_ok = ok
        prev_t = t
    if prev_ok:
        _flush(vp, x0, wk, pend, prev[A_Y], aa, mp, lut, sh, hmax, hmin, hsurf, slopes, occ,
               lists, off, K, counts, trans, gfirst, hits, b, crec)
    return evals


@ngjit_nrt_free
def _column_layers(kind, f, fg, hf, hfp, vp, x0, mp, lut, sh, hmax, hmin, hsurf, slopes, occ,
                   lists, off, K, counts, trans, gfirst, hits, b, scr):
    """Every crossing of one column (column.py's render_column_into: ascending t in
    orthographic; in perspective from the viewpoint's t outward, both ways, over the
    planes that may meet the surface)."""
    if vp[VP_ORTHO] != 0.0:
        lo, hi = _ortho_chord(vp, x0)
        if not lo <= hi:
            return 0
        return _layer_pass(kind, f, fg, hf, hfp, vp, x0, lo, hi, mp, lut, sh, hmax,
                           hmin, hsurf, slopes, occ, lists, off, K, counts, trans, gfirst,
                           hits, b, scr)
    lo, hi = _column_t_range(vp, x0)
    if not lo <= hi:
        return 0
    m = CLIP_MARGIN_PLANES * vp[VP_DT] + CLIP_TOL * (1.0 + abs(lo) + abs(hi))
    t_lo = max(vp[VP_T0], lo - m)
    t_hi = min(vp[VP_T1], hi + m)
    t_view = -vp[VP_D3] * vp[VP_CA]      # the viewpoint's t, eq. (1)
    evals = 0
    if t_hi > t_view and t_hi >= t_lo:
        evals += _layer_pass(kind, f, fg, hf, hfp, vp, x0, max(t_lo, t_view), t_hi, mp, lut,
                             sh, hmax, hmin, hsurf, slopes, occ, lists, off, K, counts, trans,
                             gfirst, hits, b, scr)
    if t_lo < t_view and t_hi >= t_lo:
        evals += _layer_pass(kind, f, fg, hf, hfp, vp, x0, min(t_hi, t_view), t_lo, mp, lut,
                             sh, hmax, hmin, hsurf, slopes, occ, lists, off, K, counts, trans,
                             gfirst, hits, b, scr)
    return evals


@ngjit_nrt_free
def _column_layers_folded(kind, f, fg, hf, hfp, vp, x0, mp, lut, sh, hmax, hmin, hsurf, slopes,
                          occ, lists, off, K, counts, trans, gfirst, hits, b, scr, saved, tg, te,
                          cross, n_cross, fa, fb):
    """_column_layers, and where a perspective column's curve folds back in t (a sample
    with 1 - k f_r < 0, or nearly at a run's end: fold.py's fold_test), which one point
    a plane cannot follow, its crossings again from the curve's traced pieces instead
    (fold.trace_layers_into: every crossing of each row's ray, sorted by depth here
    and emitted front to back, each covering its pixel whole) on every row a traced
    piece crosses; the others keep the pass's (a piece's last steps toward the
    domain's edge or a hole stop short of it, where the pass bisects the run's end).
    ``saved`` (H,), tg .. fb: layers_fold_scratch's."""
    H = trans.shape[0]
    wk = scr[6]
    wk[W_FOLD] = 0.0
    traced = vp[VP_ORTHO] == 0.0 and vp[VP_FOLD] != 0.0
    if traced:
        for j in range(H):
            saved[j] = hits[b, j]
    evals = _column_layers(kind, f, fg, hf, hfp, vp, x0, mp, lut, sh, hmax, hmin, hsurf,
                           slopes, occ, lists, off, K, counts, trans, gfirst, hits, b, scr)
    if not traced or wk[W_FOLD] == 0.0:
        return evals
    lo, hi = _column_t_range(vp, x0)     # (the planes that may meet the domain)
    margin = CLIP_MARGIN_PLANES * vp[VP_DT] + CLIP_TOL * (1.0 + abs(lo) + abs(hi))
    evals += trace_layers_into(kind, f, fg, hf, hfp, vp, x0, lo - margin, hi + margin, tg, te,
                               cross, n_cross, fa, fb)
    rec = scr[3]
    crec = scr[5]
    for j in range(H):
        n = int(te[XING_COUNT, j])
        if n == 0:
            continue                     # no traced piece there: the pass's crossings stay
        counts[b, j] = 0                 # the row's crossings, as before the pass
        trans[j] = 1.0
        hits[b, j] = int(saved[j])
        row = tg[j]
        for m in range(1, n):            # by depth (insertion: a few a row)
            q = m
            while q > 0 and row[(q - 1) * XING_SIZE + X_DEPTH] > row[q * XING_SIZE + X_DEPTH]:
                for k in range(XING_SIZE):
                    swap = row[(q - 1) * XING_SIZE + k]
                    row[(q - 1) * XING_SIZE + k] = row[q * XING_SIZE + k]
                    row[q * XING_SIZE + k] = swap
                q -= 1
        for m in range(n):
            xing = row[m * XING_SIZE:(m + 1) * XING_SIZE]
            depth = xing[X_DEPTH]
            rec[A_Y] = j
            rec[A_Z] = depth
            rec[A_U] = xing[1 + P_U]
            rec[A_V] = xing[1 + P_V]
            rec[A_W] = xing[1 + P_W]
            rec[A_NX] = xing[1 + P_NX]
            rec[A_NY] = xing[1 + P_NY]
            rec[A_NZ] = xing[1 + P_NZ]
            rec[A_I] = xing[1 + P_I]
            rec[A_T] = xing[1 + P_T]
            rec[A_BUMP] = 0.0
            vx, vy, vz = toward_viewer(vp, x0, float(j), depth)
            rec[A_VN] = rec[A_NX] * vx + rec[A_NY] * vy + rec[A_NZ] * vz
            _emit(vp, x0, j, rec, 1.0, mp, lut, sh, hmax, hmin, hsurf, slopes, occ, lists, off,
                  K, counts, trans, gfirst, hits, b, crec)
    return evals


@ngjit
def layers_scratch(H):
    """_column_layers' scratch for a column of H rows, as it must start: (trans
    (H,) ones, scr zeros)."""
    return np.ones(H), np.zeros((SCR_STACK + REFINE_DEPTH + 3, A_SIZE))


def _layers_functions(kind, f, fg, hf, hfp, vp, c0, mp, lut, sh, hmax, hmin, hsurf, slopes,
                      occ, lists, off, K, counts, gfirst, hits, evals):
    """layers_kernel's jitted functions: _column_layers, called with the kernel's
    arguments, a column's x0 and number b and layers_scratch's arrays
    (_jit.kernel_calling)."""
    trans, scr = function_type(layers_scratch, types.int64).signature.return_type.types
    fold = function_type(layers_fold_scratch, vp, types.int64).signature.return_type.types
    return ((_column_layers_folded, function_type(
        _column_layers_folded, kind, f, fg, hf, hfp, vp, types.float64, mp, lut, sh, hmax,
        hmin, hsurf, slopes, occ, lists, off, K, counts, trans, gfirst, hits, types.int64, scr,
        trans, *fold)),)


@kernel_calling(_layers_functions, (_column_layers_folded,))
def layers_kernel(kind, f, fg, hf, hfp, vp, c0, mp, lut, sh, hmax, hmin, hsurf, slopes, occ,
                  lists, off, K, counts, gfirst, hits, evals, column):
    """One surface's crossings in the band of columns c0 .. c0 + B - 1 (B =
    lists.shape[0]; columns from vp's VP_W on are left alone): into lists[b, j, off:off
    + K] (records C_*, sorted by depth), counts[b, j] of them, gfirst[b, j] the G-buffer
    record (layout.py G_*) of the nearest, hits[b, j] += every crossing met; evals[b]
    the evaluations of f. sh, hmax, hmin, hsurf: the shadow texture (SH_*), slopes its
    horizons' slopes where SH_RHO > 0 (passes/shadow.py Texture.slopes); occ the
    objects' occluders (frames, coef, start, items, grids), tested where sh's SH_OBJ
    says.
    counts must be 0 on entry; the columns in parallel, each with its own scratch.
    ``column``: _column_layers_folded as a function value (_jit.kernel_calling)."""
    B = lists.shape[0]
    H = lists.shape[1]
    W = int(vp[VP_W])
    for b_ in prange(B):
        b = np.int64(b_)  # (_jit.py: prange_index)
        c = c0 + b
        if c >= W:
            continue
        trans, scr = layers_scratch(H)
        saved = np.empty(H)
        tg, te, cross, n_cross, fa, fb = layers_fold_scratch(vp, H)
        x0 = column_x0(vp, c)
        evals[b] += column(kind, f, fg, hf, hfp, vp, x0, mp, lut, sh, hmax, hmin, hsurf,
                           slopes, occ, lists, off, K, counts, trans, gfirst, hits, b, scr,
                           saved, tg, te, cross, n_cross, fa, fb)


# The composite's sums per pixel, acc (H, W, ACC_SIZE) float64
ACC_R = 0         # premultiplied colour
ACC_G = 1
ACC_B = 2
ACC_A = 3         # 1 - transmittance
ACC_I = 4         # sum_k a_k T_k I_k
ACC_SIZE = 5


@ngjit_inline
def _before(lists, b, j, x, y):
    """Whether record x goes before record y of the same depth (two surfaces that meet
    exactly): by their colours, so that the order the surfaces were given in does not
    change the picture."""
    for k in range(C_R, C_SIZE):
        if lists[b, j, x, k] != lists[b, j, y, k]:
            return lists[b, j, x, k] < lists[b, j, y, k]
    return False


@ngjit_inline
def _accumulate(a, first, weight, r, g, bl, tr, it):
    """acc's pixel a: the sums of one pass (ACC_*), set by a band's first pass (acc is
    not cleared), added by the others."""
    if first:
        a[ACC_R] = weight * r
        a[ACC_G] = weight * g
        a[ACC_B] = weight * bl
        a[ACC_A] = weight * (1.0 - tr)
        a[ACC_I] = weight * it
    else:
        a[ACC_R] += weight * r
        a[ACC_G] += weight * g
        a[ACC_B] += weight * bl
        a[ACC_A] += weight * (1.0 - tr)
        a[ACC_I] += weight * it


@ngjit_parallel
def composite_kernel(lists, counts, offs, gfirst, c0, weight, first, acc, side, depth, shadow,
                     which, gbuf, stop, front_acc, opaque):
    """Merge the surfaces' lists of a band (layers_kernel's; counts (n, B, H), offs the
    surfaces' first slots, gfirst (n, B, H, G_SIZE)) by depth, front to back, over a
    transmittance that stops below STOP: acc[i, c] += weight * the sums (ACC_*), row i
    = H - 1 - j from the top, column c = c0 + b. With ``first`` (a band's first pass):
    acc[i, c] = weight * the sums, and side, depth, shadow (NaN: none), which (the
    surface in front, -1: none) of the nearest crossing, and its G-buffer record into
    the tiled gbuf (layout.py; only where a crossing is: gbuf is not cleared).

    Objects among the layers (objects.py): ``stop`` (H, W) the depth of the nearest
    object at each pixel (inf: none; empty: no objects). front_acc (H, W, ACC_SIZE)
    then takes the sums of the crossings nearer than it, as acc the whole list's (what
    lies over the object: its colour shows through the rest, 1 - ACC_A), and with
    ``first`` opaque (H, W) the depth at which the transmittance falls below STOP (inf:
    never), behind which no object shows."""
    n = counts.shape[0]
    B = lists.shape[0]
    H = lists.shape[1]
    W = acc.shape[1]
    T = gbuf.shape[2]
    objects = stop.shape[0] > 0
    for b_ in prange(B):
        b = np.int64(b_)  # (_jit.py: prange_index)
        c = c0 + b
        if c >= W:
            continue
        head = np.zeros(n, dtype=np.int64)
        tile = c // T
        lane = c - tile * T
        for j in range(H):
            i = H - 1 - j
            for s in range(n):
                head[s] = 0
            tr = 1.0
            r = 0.0
            g = 0.0
            bl = 0.0
            it = 0.0
            front = -1
            f_side = 0.0
            f_depth = np.inf
            f_shadow = np.nan
            z_stop = stop[i, c] if objects else np.inf
            snap = False                 # the sums before z_stop taken
            while tr >= STOP:
                best = -1
                best_d = np.inf
                for s in range(n):
                    if head[s] < counts[s, b, j]:
                        d = lists[b, j, offs[s] + head[s], C_DEPTH]
                        if best < 0 or d < best_d or (d == best_d and _before(
                                lists, b, j, offs[s] + head[s], offs[best] + head[best])):
                            best = s
                            best_d = d
                if best < 0:
                    break
                rec = lists[b, j, offs[best] + head[best]]
                if objects and not snap and rec[C_DEPTH] >= z_stop:
                    _accumulate(front_acc[i, c], first, weight, r, g, bl, tr, it)
                    snap = True
                if front < 0:
                    front = best
                    f_side = rec[C_SIDE]
                    f_depth = rec[C_DEPTH]
                    f_shadow = rec[C_SHADOW]
                head[best] += 1
                r += tr * rec[C_R]
                g += tr * rec[C_G]
                bl += tr * rec[C_B]
                it += tr * rec[C_I]
                tr *= 1.0 - rec[C_A]
                if objects and first and tr < STOP:
                    opaque[i, c] = rec[C_DEPTH]
            if objects:
                if not snap:
                    _accumulate(front_acc[i, c], first, weight, r, g, bl, tr, it)
                if first and tr >= STOP:
                    opaque[i, c] = np.inf
            _accumulate(acc[i, c], first, weight, r, g, bl, tr, it)
            if first:
                which[i, c] = front
                side[i, c] = int(f_side)
                depth[i, c] = f_depth
                shadow[i, c] = f_shadow
                if front >= 0:
                    for k in range(G_SIZE):
                        gbuf[tile, j, lane, k] = gfirst[front, b, j, k]


@ngjit_parallel
def picture_kernel(acc, bg, rgba, intensity):
    """The composite's sums acc (H, W, ACC_SIZE) over the background bg (r, g, b, a in
    [0, 1]): rgba (H, W, 4) uint8, straight alpha; intensity (H, W) the sum of the
    layers' intensities over black, NaN where no layer is."""
    H = acc.shape[0]
    W = acc.shape[1]
    for i in prange(H):
        for c in range(W):
            x = acc[i, c]
            a = x[ACC_A]
            rest = (1.0 - a) * bg[3]
            alpha = a + rest
            q = 1.0 / alpha if alpha > 0.0 else 1.0
            for k in range(3):
                v = (x[k] + rest * bg[k]) * q * 255.0
                rgba[i, c, k] = np.uint8(min(max(round(v), 0.0), 255.0))
            rgba[i, c, 3] = np.uint8(min(max(round(alpha * 255.0), 0.0), 255.0))
            intensity[i, c] = x[ACC_I] if a > 0.0 else np.nan

"""The ray march (``sampling="march"``): a point-sampled fly-through's pixel rays
marched through the level-of-detail engine's planes (kernels/lod.py's plane_table:
a pixel's footprint apart, each with its pyramid level and blend), front to back, over
a height field's pyramid (Cohen-Or 1997's multiresolution traversal, Guedes 1997's
growing step, VoxelSpace's one walk a column).

Column x0's rays all lie in its plane Pi (tilted when the camera pitches, Guedes'
non-vertical view plane). The ray of screen row y (y0 in screen units from the middle)
meets plane t at lam = (t + d3 cos a) / (d1 cos a - y0 sin a) from the eye (eqs. 4 and
10 inverted): r = lam x0, s = lam (d1 sin a + y0 cos a) - d3 sin a (eq. 9 with ERRATA
2), so r, s and the ground point (u, v) (eq. 2) are linear in t. Guedes' eq. (7)
corrects his slices' ground points toward these; here they are exact for every ray on
every plane, with no Newton iteration (the lod engine's sample on a tilted plane).

A column walks the planes once, its rays from the bottom row up: the lowest ray not
yet placed is tested on the next plane, d = s_ray - (f - w_c) its height above the
surface there. Where d <= 0 it has met the surface since its last plane: the point is
placed by the secant of d between the two planes, shaded there (the level's normal,
smoothed between its nodes past level 0 as the lod engine's), and the next ray, one
row higher, is tested from the same plane (it meets the surface no nearer where Pi's
cut of the surface does not fold back). A ray cannot meet the surface before it has
come down to it at the surface's steepest slope (each pyramid level's bound,
passes/march.py slopes): a ray that high above it steps 2, 4, 16 or 64 planes at
once, with no picture changed. A ray above the surface's highest point and rising
ends the column, since every ray above it misses.

A hole (a NaN height) or the domain's outside lets a ray pass: a farther surface
shows behind it. A ray below the surface on its first plane after a hole came under
the surface through it: it sees the surface's lower side where it comes up through
it, nothing where it stays under to the end, and the next ray starts where it went
under.

It draws pixel centres only; an antialiased view takes the lod engine's area weights
(passes/march.py)."""
import math

import numpy as np
from numba import prange

from ._jit import ngjit_inline, ngjit_nrt_free, ngjit_parallel
from .layout import (E_SEEN, G_DEPTH, G_I, G_NX, G_NY, G_NZ, G_T, G_U, G_V, G_W,
                     SURF_HEIGHTFIELD, VP_CA, VP_CB, VP_CU, VP_CV, VP_CW, VP_D1, VP_D3,
                     VP_H, VP_SA, VP_SB, VP_SCALE, VP_UA, VP_UB, VP_VA, VP_VB, VP_WORG)
from .lod import (_bilinear, _last_before, _smooth_gradient, blended_at, column_t_span,
                  level_ints, level_params, level_table, plane_table)
from .sample import column_x0, lambert, unit_normal

#: planes a footprint apart (as kernels/lod.py's KAPPA)
KAPPA = 1.0
#: A placed point: u, v, w, normal, intensity, t, depth
P_U = 0
P_V = 1
P_W = 2
P_NX = 3
P_NY = 4
P_NZ = 5
P_I = 6
P_T = 7
P_Z = 8
P_SIZE = 9


@ngjit_inline
def _ray(vp, x0, y):
    """(rr, ar, br) of column x0's ray through screen row y (from the bottom, in
    pixels): at plane t it lies at r = (t + d3 cos a) rr and height s = ar t + br
    relative to the centre (the module's note; ar, br as lod._horizon_ray's)."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    d1 = vp[VP_D1]
    y0 = (y - (vp[VP_H] - 1.0) * 0.5) / vp[VP_SCALE]
    m = 1.0 / (d1 * ca - y0 * sa)                # > 0: the rays point forward
    return x0 * m, (y0 * ca + sa * d1) * m, y0 * vp[VP_D3] * m


@ngjit_inline
def _point(flat, lt, hfp, vp, k, a, rr, ar, br, t, p):
    """The ray (rr, ar, br)'s point on plane t, shaded by level k blended with k + 1
    by a, into p (P_*); False where the surface there is a hole."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    d3 = vp[VP_D3]
    r = (t + d3 * ca) * rr
    u = min(max(vp[VP_CU] + r * cb + t * sb, vp[VP_UA]), vp[VP_UB])     # eq. (2)
    v = min(max(vp[VP_CV] - r * sb + t * cb, vp[VP_VA]), vp[VP_VB])
    w, wu, wv = _bilinear(flat, lt, k, hfp, u, v)
    if k > 0:
        # a smoothed level's partials interpolated between its nodes (as lod._finish;
        # where level 0 is blended with level 1 its own exact partials are, where
        # lod._finish blends the blended surface's: a fifth to a third of a dense
        # DEM's pixels would change)
        gu, gv = _smooth_gradient(flat, lt, k, hfp, u, v)
        if math.isfinite(gu) and math.isfinite(gv):
            wu = gu
            wv = gv
    if a > 0.0:
        w1, hu, hv = _bilinear(flat, lt, k + 1, hfp, u, v)
        gu, gv = _smooth_gradient(flat, lt, k + 1, hfp, u, v)
        if math.isfinite(gu) and math.isfinite(gv):
            hu = gu
            hv = gv
        w = (1.0 - a) * w + a * w1
        wu = (1.0 - a) * wu + a * hu
        wv = (1.0 - a) * wv + a * hv
    if not (math.isfinite(w) and math.isfinite(wu) and math.isfinite(wv)):
        return False
    s = ar * t + br                              # the ray's height: its pixel's row
    nx, ny, nz = unit_normal(vp, wu, wv)         # eq. (11)
    y1 = s * ca - t * sa                         # eqs. (4), (10)
    z1 = s * sa + t * ca
    p[P_U] = u
    p[P_V] = v
    p[P_W] = w
    p[P_NX] = nx
    p[P_NY] = ny
    p[P_NZ] = nz
    p[P_I] = lambert(vp, -r, -y1, -(d3 + z1), nx, ny, nz)      # eq. (12)
    p[P_T] = t
    p[P_Z] = z1
    return True


@ngjit_inline
def _store(g, p, cu, cv, wo):
    """A pixel's G-buffer entry g from the point p (u, v from the view's centre, w
    from VP_WORG: layout.py G_U, G_W)."""
    g[G_DEPTH] = p[P_Z]
    g[G_U] = p[P_U] - cu
    g[G_V] = p[P_V] - cv
    g[G_W] = p[P_W] - wo
    g[G_NX] = p[P_NX]
    g[G_NY] = p[P_NY]
    g[G_NZ] = p[P_NZ]
    g[G_I] = p[P_I]
    g[G_T] = p[P_T]


@ngjit_inline
def _height_above(flat, lt, lk, hfp, planes, m, u0, du, v0, dv, ar, br, cw, ua, ub, va, vb):
    """The height of the ray (ground line u0 + du t, v0 + dv t; s = ar t + br) above the
    surface on plane m (NaN outside the domain or in a hole)."""
    t = planes[m, 0]
    u = u0 + du * t
    v = v0 + dv * t
    if not (u >= ua and u <= ub and v >= va and v <= vb):
        return np.nan
    w = blended_at(flat, level_params(lt, lk, int(planes[m, 1])), planes[m, 2], u - hfp[0],
                   v - hfp[2])
    return ar * t + br - (w - cw)


@ngjit_nrt_free
def march_column(flat, lt, lk, slope, hfp, vp, planes, x0, s_lo, s_hi, gcol, ecol, p, out):
    """Column x0 into gcol (H, G_SIZE) and ecol (E_SIZE, H), a ray at each pixel's
    centre; p a point's scratch (P_SIZE); [s_lo, s_hi] the surface's heights relative
    to the view's centre. Writes the evaluations, the lowest and highest w seen and
    the lowest and highest row set to out[0:5]."""
    H = gcol.shape[0]
    ca = vp[VP_CA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    d3 = vp[VP_D3]
    d3ca = d3 * ca
    cu = vp[VP_CU]
    cv = vp[VP_CV]
    cw = vp[VP_CW]
    wo = vp[VP_WORG]
    ua = vp[VP_UA]
    ub = vp[VP_UB]
    va = vp[VP_VA]
    vb = vp[VP_VB]
    ou = hfp[0]
    ov = hfp[2]
    ecol[E_SEEN, :] = 0.0
    evals = 0
    jlo = H
    jhi = -1
    w_lo = np.inf
    w_hi = -np.inf
    ta, tb = column_t_span(vp, x0, s_lo, s_hi)
    n = planes.shape[0] if ta <= tb else 0
    i = _last_before(planes, ta)
    i0 = i
    j = 0                                        # the ray: row j's centre
    rr = ar = br = u0 = du = v0 = dv = 0.0
    d_prev = np.nan                              # its height above the surface on plane ip
    ip = -1
    fresh = True                                 # (not yet tested on a plane)
    under = False                                # below the surface, come through a hole
    i_under = 0                                  # ... since plane i_under
    kc = -1                                      # the level whose parameters are held
    par = level_params(lt, lk, 0)
    kr = -1                                      # ... and whose slope bound gives rate
    rate = 0.0
    inv_rate = 0.0
    while j < H:
        if fresh:
            rr, ar, br = _ray(vp, x0, float(j))
            # its ground point on plane t: (u0 + du t, v0 + dv t) (eq. 2)
            u0 = cu + d3ca * rr * cb
            du = rr * cb + sb
            v0 = cv - d3ca * rr * sb
            dv = cb - rr * sb
            kr = -1
        if i >= n or planes[i, 0] > tb:
            if under:
                # it stayed under the surface to the end: nothing seen; the next ray
                # from where it went under
                j += 1
                i = i_under
                fresh = True
                under = False
                d_prev = np.nan
                ip = -1
                continue
            break                                # it and every ray above it miss
        t = planes[i, 0]
        k = int(planes[i, 1])
        a = planes[i, 2]
        if k != kc:
            kc = k
            par = level_params(lt, lk, k)
        u = u0 + du * t
        v = v0 + dv * t
        sr = ar * t + br
        d = np.nan
        if u >= ua and u <= ub and v >= va and v <= vb:
            evals += 1
            d = sr - (blended_at(flat, par, a, u - ou, v - ov) - cw)
        if under:
            # it passes under the surface until it comes up through it (the lower side
            # seen there) or through a hole
            if not d > 0.0 or d_prev != d_prev:
                if d > 0.0:
                    under = False                # (up through a hole: above it again)
                d_prev = d
                ip = i
                i += 1
                continue
        elif not d <= 0.0:                       # above the surface, a hole, outside
            if ar >= 0.0 and sr > s_hi:
                break                            # it and every ray above it miss
            # the ray cannot meet the surface before it has come down to it at the
            # surface's steepest (the slope bound of the level of its plane before
            # this one; the planes after hold that level or coarser ones, no
            # steeper): from its height there, steps of 64, 16, 4 or 2 planes where
            # they stay short of that (the step does not wait for this plane's
            # height: the loop's iterations overlap in the processor); 2 tested
            # first, where most rays fail (the frame 5-7 % faster than 64 first)
            behind = d_prev if not fresh else 0.0
            t_behind = planes[ip, 0] if not fresh else t
            kb = int(planes[ip, 1]) if not fresh else k
            d_prev = d
            ip = i
            fresh = False
            if behind > 0.0 and i + 2 < n:
                if kb != kr:
                    kr = kb
                    rate = slope[kb, 0] * abs(du) + slope[kb, 1] * abs(dv) - ar
                    inv_rate = 1.0 / rate if rate > 0.0 else np.inf
                t_safe = t_behind + behind * inv_rate   # (a product: 5 % of a frame)
                if not planes[i + 2, 0] < t_safe:
                    i += 1
                elif i + 64 < n and planes[i + 64, 0] < t_safe:
                    i += 64
                elif i + 16 < n and planes[i + 16, 0] < t_safe:
                    i += 16
                elif i + 4 < n and planes[i + 4, 0] < t_safe:
                    i += 4
                else:
                    i += 2
            else:
                i += 1
            continue
        else:
            # below the surface: met since the plane before (from above), where the
            # ray was above it there, or stepped over it (its height there taken now:
            # the secant's bracket is the same as without steps); under it where the
            # surface there is a hole (or the domain's outside): it came under
            # through the hole
            if (fresh or ip < i - 1) and i > i0:
                d_prev = _height_above(flat, lt, lk, hfp, planes, i - 1, u0, du, v0, dv, ar,
                                       br, cw, ua, ub, va, vb)
                ip = i - 1
                evals += 1
            if d_prev != d_prev and ip == i - 1 and ip >= i0:
                fresh = False
                under = True
                i_under = i
                d_prev = d
                ip = i
                i += 1
                continue
        # the ray met the surface between planes ip and i, from above (or from below
        # where it was under it): the secant of d
        th = t
        if d_prev == d_prev and ip >= i0 and (d_prev > 0.0 or under):
            tp = planes[ip, 0]
            th = tp + d_prev / (d_prev - d) * (t - tp)
        ok = _point(flat, lt, hfp, vp, k, a, rr, ar, br, th, p)
        if not ok and th != t:                   # (a hole between: the plane's point)
            ok = _point(flat, lt, hfp, vp, k, a, rr, ar, br, t, p)
        evals += 1
        if ok:
            _store(gcol[j], p, cu, cv, wo)
            ecol[E_SEEN, j] = -1.0 if under else 1.0
            w_lo = min(w_lo, p[P_W])
            w_hi = max(w_hi, p[P_W])
            jlo = min(jlo, j)
            jhi = j
        j += 1
        if under:
            i = i_under                          # (the next ray from where it went under)
        d_prev = np.nan
        ip = -1
        fresh = True
        under = False
    out[0] = evals
    out[1] = w_lo
    out[2] = w_hi
    out[3] = jlo
    out[4] = jhi


@ngjit_parallel
def march_kernel(flat, lv, slope, hfp, vp, lod, kappa, s_lo, s_hi, gbuf, ebuf, evals, wrange,
                 rows):
    """Every tile's columns by march_column into the tiled gbuf and ebuf (layout.py),
    the tiles in parallel, each column on its own (the picture is the same for any
    number of threads). The planes are plane_table's (``lod`` footprints a level's
    cell, ``kappa`` footprints apart); [s_lo, s_hi] the height field's heights
    relative to the view's centre."""
    n_tiles = gbuf.shape[0]
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    W = evals.shape[0]
    planes = plane_table(SURF_HEIGHTFIELD, lv, vp, lod, kappa, 0.5 * (s_lo + s_hi))
    lt = level_table(lv, hfp)
    lk = level_ints(lv)
    for b_ in prange(n_tiles):
        b = np.int64(b_)
        p = np.empty(P_SIZE)
        out = np.empty(5)
        rows[b, 0] = H
        rows[b, 1] = -1
        for L in range(min(T, W - b * T)):
            c = b * T + L
            march_column(flat, lt, lk, slope, hfp, vp, planes, column_x0(vp, c), s_lo, s_hi,
                         gbuf[b, :, L], ebuf[b, :, :, L], p, out)
            evals[c] = int(out[0])
            wrange[c, 0] = out[1]
            wrange[c, 1] = out[2]
            rows[b, 0] = min(rows[b, 0], int(out[3]))
            rows[b, 1] = max(rows[b, 1], int(out[4]))

"""Exact area sampling along the columns (Cohen-Or 1997, section 4.3 and Fig. 12), with
a height field's level of detail (his multiresolution traversal).

A pixel of column x0 spans the rows [j - 1/2, j + 1/2] (from the bottom). Cohen-Or's
ray R_i climbs the voxels of pixel i until it reaches R_(i+1), and each voxel it hits
adds its colour with the weight W_k = H' - H(R) it shows between the two rays (Fig.
12). Here the column's samples, front to back, are joined by spans on screen; the part
of a span that no nearer span covers is what it shows, and each pixel takes the
visible parts that fall in it, each weighted by its length on screen: the same
weights, on the exact surface instead of voxels, so every visible cell counts and
only the visible ones. The pieces of a pixel fall in two groups (piece_group): the
nearest and those that continue it, and those of a farther surface. Each group's
attributes (u, v, w, normal, intensity) are its weighted means, its coverage its total
weight (the part of the pixel it shows), its depth its nearest piece's: the first is
the pixel's surface (the G-buffer), the second its edge surface (section 6.4's, in
the edge buffer), each coloured by its own height and blended with the background by
the finishing pass (resolve_pixel).

Where a height field's cells are smaller than a pixel is wide, the column samples a
pyramid of the heights smoothed and halved level by level (passes/area.py): the
level whose cells match the pixel's footprint at that distance, blended with the next
so that no level boundary pops (trilinear, as a mip-map), and the planes step by the
level's half cell (Cohen-Or 1996's step that grows with the footprint). A function
surface samples itself with planes a pixel's footprint apart.

The covered part of the column is a set of disjoint intervals of screen rows (a
hole lets a farther surface show between nearer ones), kept sorted; a column holds
at most MAX_INTERVALS, and merges its two closest beyond that (the gap between them
counted as covered).
"""
import math

import numba
import numpy as np
from numba import prange, types

from ._jit import function_type, kernel_calling, ngjit, ngjit_inline, ngjit_nrt_free
from .column import _column_t_range, _domain_test, _may_meet_domain, _ortho_chord
from .layout import (
    E_COV, E_COV0, E_DEPTH, E_FLAG, E_I, E_NX, E_NY, E_NZ, E_SEEN, E_SIDE, E_U, E_V, E_W,
    G_DEPTH, G_I, G_NX, G_NY, G_NZ, G_T, G_U, G_V, G_W, S_OK,
    SURF_HEIGHTFIELD, VP_CA, VP_CU, VP_CV, VP_CW, VP_D1, VP_D3, VP_DT, VP_H, VP_ORTHO, VP_WHI,
    VP_WLO, VP_SA, VP_SCALE, VP_T0, VP_T1, VP_WORG,
)
from .coverage import flagged
from .sample import column_x0, lambert, sample_point, unit_normal

#: Accumulator of one pixel: two groups of pieces (AC_G1, AC_G2 + the fields below),
#: each its total weight, weighted sums of u, v, w, the normal, the intensity, t and
#: the side, and its nearest depth. The first group holds the nearest piece and the
#: pieces that continue it along the column; a piece that does not continue the last
#: one (a farther surface rising behind a silhouette, the other side of a hole) starts
#: the second, which takes the rest. The pixel shows the first as its surface and the
#: second as its edge surface (section 6.4's): each coloured by its own height, so a
#: silhouette pixel mixes the colours of the two surfaces instead of taking the colour
#: of their mean height (a colour of neither).
AC_W = 0
AC_U = 1
AC_V = 2
AC_WW = 3
AC_NX = 4
AC_NY = 5
AC_NZ = 6
AC_I = 7
AC_T = 8
AC_SIDE = 9
AC_Z = 10
AC_GROUP = 11         # fields of a group
AC_TA = 11            # the last piece's span: its ends' t (NaN: none yet), and its
AC_TB = 12            # group's offset
AC_LAST = 13
AC_G1 = 0
AC_G2 = 14
AC_SIZE = AC_G2 + AC_GROUP
#: A sample: row, depth, u, v, w, normal, intensity, t
P_Y = 0
P_Z = 1
P_U = 2
P_V = 3
P_W = 4
P_NX = 5
P_NY = 6
P_NZ = 7
P_I = 8
P_T = 9
P_DEP = 10        # (a refinement stack's entry: how many times it was cut)
P_SIZE = 11
MAX_INTERVALS = 64
#: Level table rows (passes/area.py): offset of the level's heights in the flat
#: array, rows (along v), columns (along u), cell size (the longer side), heights
LV_OFF = 0
LV_NV = 1
LV_NU = 2
LV_CELL = 3
LV_ZMIN = 4       # the level's lowest and highest height (NaN: unknown, a function)
LV_ZMAX = 5
LV_SIZE = 6
#: planes per cell of the level sampled
STEPS_PER_CELL = 2.0
#: a column takes at most about this many planes: the step grows past it where a
#: pixel's footprint is tiny against the view's depth (view.py caps the column pass's
#: planes at 40 000 likewise). Where the depth is 1e300 times the picture's width (a
#: domain of 11.5 by 1e300, seen along its long side), steps of a footprint were a
#: floor of 1/1000 of the column pass's step: 2.4 billion evaluations, 93 s for a 64 x
#: 120 picture
MAX_PLANES = 160_000
#: bisections that locate a run's end (a hole, the domain's edge)
EDGE_BISECTIONS = 14
#: a span is cut in two (its middle sampled) where it covers more rows than this, or
#: its intensity changes more than this, up to this many times
REFINE_ROWS = 1.0
REFINE_JUMP = 1.0 / 16.0
REFINE_DEPTH = 6
#: a coverage this close to 1 is whole
WHOLE = 1.0 - 1e-6


@ngjit_inline
def _footprint(vp, t, s_guess):
    """The width of a pixel, in world units, at the surface on plane t (s_guess: the
    height of the last sample relative to the centre, for its depth)."""
    if vp[VP_ORTHO] != 0.0:
        return 1.0 / vp[VP_SCALE]
    q = s_guess * vp[VP_SA] + t * vp[VP_CA] + vp[VP_D3]     # its depth from the eye
    # (behind the eye, |q|: the planes there grow apart as fast as in front)
    return max(abs(q), vp[VP_D1]) / (vp[VP_D1] * vp[VP_SCALE])


@ngjit_inline
def _node_gradient(hf, hfp, i, j):
    """(f_u, f_v) at node (i, j) of a level by central differences (one-sided at the
    border); NaN next to a hole."""
    nv, nu = hf.shape
    i0 = max(i - 1, 0)
    i1 = min(i + 1, nu - 1)
    j0 = max(j - 1, 0)
    j1 = min(j + 1, nv - 1)
    du = (hfp[1] - hfp[0]) / (nu - 1)
    dv = (hfp[3] - hfp[2]) / (nv - 1)
    return ((hf[j, i1] - hf[j, i0]) / ((i1 - i0) * du),
            (hf[j1, i] - hf[j0, i]) / ((j1 - j0) * dv))


@ngjit_inline
def _smooth_normal(hf, hfp, vp, x0, u, v, y, z, nx, ny, nz, lam):
    """The normal and intensity of a smoothed level's point (u, v) from the partials
    interpolated bilinearly between its cell's nodes (their central differences):
    continuous across the cells' edges, so a column that moves across a cell does
    not jump from one facet's light to the next's. Keeps the exact ones by a hole."""
    nv, nu = hf.shape
    gx = (u - hfp[0]) / (hfp[1] - hfp[0]) * (nu - 1)
    gy = (v - hfp[2]) / (hfp[3] - hfp[2]) * (nv - 1)
    i = min(max(int(math.floor(gx)), 0), nu - 2)
    j = min(max(int(math.floor(gy)), 0), nv - 2)
    fx = min(max(gx - i, 0.0), 1.0)
    fy = min(max(gy - j, 0.0), 1.0)
    a_u, a_v = _node_gradient(hf, hfp, i, j)
    b_u, b_v = _node_gradient(hf, hfp, i + 1, j)
    c_u, c_v = _node_gradient(hf, hfp, i, j + 1)
    d_u, d_v = _node_gradient(hf, hfp, i + 1, j + 1)
    wu = (a_u * (1 - fx) + b_u * fx) * (1 - fy) + (c_u * (1 - fx) + d_u * fx) * fy
    wv = (a_v * (1 - fx) + b_v * fx) * (1 - fy) + (c_v * (1 - fx) + d_v * fx) * fy
    if not (math.isfinite(wu) and math.isfinite(wv)):
        return nx, ny, nz, lam
    nx, ny, nz = unit_normal(vp, wu, wv)
    if vp[VP_ORTHO] != 0.0:
        return nx, ny, nz, lambert(vp, 0.0, 0.0, -1.0, nx, ny, nz)
    m = (z + vp[VP_D3]) / vp[VP_D1]             # screen point -> the point itself
    y1 = (y - (vp[VP_H] - 1.0) * 0.5) / vp[VP_SCALE] * m
    return nx, ny, nz, lambert(vp, -x0 * m, -y1, -(vp[VP_D3] + z), nx, ny, nz)


@ngjit
def _sample(kind, f, fg, flat, lv, hfp, vp, x0, lod, t, guess, out):
    """The sample of plane t into ``out`` (P_*), at the level of detail of its
    footprint: blended between two levels of a height field's pyramid. ``guess``
    (per level: the last solution s and its t, the slope) starts the perspective
    Newton iterations and is updated. Returns (status, evaluations, step to the next
    plane)."""
    n_lv = lv.shape[0]
    s_last = guess[n_lv, 0]                    # the last sample's height (its depth)
    fw = _footprint(vp, t, s_last if s_last == s_last else 0.0)
    k = 0
    a = 0.0
    step = fw
    if kind == SURF_HEIGHTFIELD:
        lf = math.log2(max(fw * lod / lv[0, LV_CELL], 1.0))
        if lf >= n_lv - 1:
            k = n_lv - 1
        else:
            k = int(lf)
            a = lf - k
        step = min(lv[k, LV_CELL] / STEPS_PER_CELL, fw)
    step = max(step, vp[VP_DT] * 1e-3, (vp[VP_T1] - vp[VP_T0]) * (1.0 / MAX_PLANES))
    ev = 0
    for m in range(2):
        kk = k + m
        if m == 1 and a <= 0.0:
            break
        g = guess[kk]
        sg = np.nan
        if g[0] == g[0]:
            sg = g[0] + g[2] * (t - g[1])
        o = int(lv[kk, LV_OFF])
        nv = int(lv[kk, LV_NV])
        nu = int(lv[kk, LV_NU])
        hf = flat[o:o + nv * nu].reshape((nv, nu))     # the level's heights (a view)
        st, e, y, z, u, v, w, nx, ny, nz, lam = sample_point(kind, f, fg, hf, hfp, vp, x0, t, sg)
        ev += e
        if st != S_OK:
            return st, ev, step
        if kk > 0:
            nx, ny, nz, lam = _smooth_normal(hf, hfp, vp, x0, u, v, y, z, nx, ny, nz, lam)
        s = w - vp[VP_CW]
        if g[0] == g[0] and t != g[1]:
            g[2] = (s - g[0]) / (t - g[1])
        g[0] = s
        g[1] = t
        if m == 0:
            out[P_Y] = y
            out[P_Z] = z
            out[P_U] = u
            out[P_V] = v
            out[P_W] = w
            out[P_NX] = nx
            out[P_NY] = ny
            out[P_NZ] = nz
            out[P_I] = lam
        else:                        # the next level's point on the same plane, blended
            b = 1.0 - a
            out[P_Y] = b * out[P_Y] + a * y
            out[P_Z] = b * out[P_Z] + a * z
            out[P_U] = b * out[P_U] + a * u
            out[P_V] = b * out[P_V] + a * v
            out[P_W] = b * out[P_W] + a * w
            mx = b * out[P_NX] + a * nx
            my = b * out[P_NY] + a * ny
            mz = b * out[P_NZ] + a * nz
            q = math.sqrt(mx * mx + my * my + mz * mz)
            if q > 0.0:
                out[P_NX] = mx / q
                out[P_NY] = my / q
                out[P_NZ] = mz / q
            out[P_I] = b * out[P_I] + a * lam
    if a <= 0.0 and k + 1 < n_lv:
        guess[k + 1, 0] = np.nan               # (its last solution is stale now)
    out[P_T] = t
    guess[n_lv, 0] = out[P_W] - vp[VP_CW]
    return S_OK, ev, step


@ngjit_nrt_free
def _uncovered(cov, n, lo, hi, gaps):
    """The parts of [lo, hi] outside the sorted disjoint intervals cov[:n] into gaps
    (pairs); returns how many."""
    m = 0
    a = lo
    for i in range(n):
        if cov[i, 1] <= a:
            continue
        if cov[i, 0] >= hi:
            break
        if cov[i, 0] > a:
            gaps[m, 0] = a
            gaps[m, 1] = cov[i, 0]
            m += 1
        a = max(a, cov[i, 1])
        if a >= hi:
            break
    if a < hi:
        gaps[m, 0] = a
        gaps[m, 1] = hi
        m += 1
    return m


@ngjit_inline
def _overlapping(cov, n, lo, hi):
    """(i, j): the intervals cov[i:j] of the sorted cov[:n] that [lo, hi] meets (i = j:
    none, and i is where it goes)."""
    i = 0
    while i < n and cov[i, 1] < lo:
        i += 1
    j = i
    while j < n and cov[j, 0] <= hi:
        j += 1
    return i, j


@ngjit_nrt_free
def _cover(cov, n, lo, hi):
    """[lo, hi] added to the sorted disjoint intervals cov[:n]; returns their count.
    A full list first merges its two closest neighbours (the gap counted covered)."""
    i, j = _overlapping(cov, n, lo, hi)
    if j == i and n == cov.shape[0]:
        best = 0
        gap = np.inf
        for k in range(n - 1):
            d = cov[k + 1, 0] - cov[k, 1]
            if d < gap:
                gap = d
                best = k
        cov[best, 1] = cov[best + 1, 1]
        for k in range(best + 1, n - 1):
            cov[k, 0] = cov[k + 1, 0]
            cov[k, 1] = cov[k + 1, 1]
        n -= 1
        i, j = _overlapping(cov, n, lo, hi)
    if j == i:                                  # a new interval at i
        for k in range(n, i, -1):
            cov[k, 0] = cov[k - 1, 0]
            cov[k, 1] = cov[k - 1, 1]
        cov[i, 0] = lo
        cov[i, 1] = hi
        return n + 1
    lo = min(lo, cov[i, 0])                     # cov[i:j] merge into one
    hi = max(hi, cov[j - 1, 1])
    cov[i, 0] = lo
    cov[i, 1] = hi
    shift = j - i - 1
    for k in range(j, n):
        cov[k - shift, 0] = cov[k, 0]
        cov[k - shift, 1] = cov[k, 1]
    return n - shift


@ngjit_inline
def clear_accumulators(acc):
    """acc (n, AC_SIZE): no pieces yet."""
    for j in range(acc.shape[0]):
        for k in range(AC_SIZE):
            acc[j, k] = 0.0
        acc[j, AC_G1 + AC_Z] = np.inf
        acc[j, AC_G2 + AC_Z] = np.inf
        acc[j, AC_TA] = np.nan
        acc[j, AC_TB] = np.nan


#: where a sample record (P_*) holds u, v, w, the normal, the intensity, t and the depth
#: (add_piece; the lod engine's records hold them elsewhere)
SAMPLE_FIELDS = (P_U, P_V, P_W, P_NX, P_NY, P_NZ, P_I, P_T, P_Z)


@ngjit_inline
def add_piece(c, wgt, lam, p, q, at, side):
    """A visible piece of the span between the sample records p and q (its middle at
    lam along it, its length on screen wgt) into a pixel's accumulator c, in its group
    (piece_group). ``at``: the records' indices of u, v, w, the normal, the intensity,
    t and the depth (SAMPLE_FIELDS); ``side`` the side it shows (+1, -1)."""
    iu, iv, iw, inx, iny, inz, ii, it, iz = at
    g = piece_group(c, p[it], q[it])
    c[g + AC_W] += wgt
    c[g + AC_U] += wgt * (p[iu] + lam * (q[iu] - p[iu]))
    c[g + AC_V] += wgt * (p[iv] + lam * (q[iv] - p[iv]))
    c[g + AC_WW] += wgt * (p[iw] + lam * (q[iw] - p[iw]))
    c[g + AC_NX] += wgt * (p[inx] + lam * (q[inx] - p[inx]))
    c[g + AC_NY] += wgt * (p[iny] + lam * (q[iny] - p[iny]))
    c[g + AC_NZ] += wgt * (p[inz] + lam * (q[inz] - p[inz]))
    c[g + AC_I] += wgt * (p[ii] + lam * (q[ii] - p[ii]))
    c[g + AC_T] += wgt * (p[it] + lam * (q[it] - p[it]))
    c[g + AC_SIDE] += wgt * side
    c[g + AC_Z] = min(c[g + AC_Z], p[iz] + lam * (q[iz] - p[iz]))


@ngjit_inline
def piece_group(c, ta, tb):
    """The group (its offset in the accumulator c, AC_*) of a piece of the span
    between planes ta and tb: the first piece's is the first group; a piece of the
    same span as the last piece, or of the span after it (starting where that one
    ended), goes where the last one went; any other (hidden spans or a break between
    them and the last piece) to the second group."""
    if c[AC_G1 + AC_W] <= 0.0:
        g = AC_G1
    elif ta == c[AC_TB] or (ta == c[AC_TA] and tb == c[AC_TB]):
        g = int(c[AC_LAST])
    else:
        g = AC_G2
    c[AC_TA] = ta
    c[AC_TB] = tb
    c[AC_LAST] = g
    return g


@ngjit_nrt_free
def _add_span(acc, cov, n, gaps, prev, cur, sigma, H, share):
    """The visible parts of the span prev -> cur into the pixels' accumulators, each
    weighted by its length on screen times ``share`` (the slice's part of the pixel's
    width); returns the count of covered intervals after it."""
    ya = prev[P_Y]
    yb = cur[P_Y]
    lo = min(ya, yb)
    hi = max(ya, yb)
    if not (hi > -0.5 and lo < H - 0.5) or hi <= lo:
        if hi > lo:
            return _cover(cov, n, lo, hi)
        return n
    side = sigma if yb > ya else -sigma         # rising in the pass: the upper side
    inv = 1.0 / (yb - ya)
    m = _uncovered(cov, n, max(lo, -0.5), min(hi, H - 0.5), gaps)
    for g in range(m):
        p = gaps[g, 0]
        q = gaps[g, 1]
        j = int(math.floor(p + 0.5))
        while j < H:
            a = max(p, j - 0.5)
            b = min(q, j + 0.5)
            if b <= a:
                if j + 0.5 >= q:
                    break
                j += 1
                continue
            wgt = (b - a) * share
            lam = (0.5 * (a + b) - ya) * inv             # the piece's middle on the span
            add_piece(acc[j], wgt, lam, prev, cur, SAMPLE_FIELDS, side)
            if b >= q:
                break
            j += 1
    return _cover(cov, n, lo, hi)


@ngjit_nrt_free
def _edge(kind, f, fg, flat, lv, hfp, vp, x0, lod, good, t_bad, guess, edge, tmp):
    """Where a run ends (a hole, the domain's edge): bisect between the sample
    ``edge`` (valid, at t ``edge[P_T]``) and the failed plane t_bad, EDGE_BISECTIONS
    times; ``edge`` ends as the last valid sample found. Returns the evaluations."""
    evals = 0
    t_good = good
    for _ in range(EDGE_BISECTIONS):
        tm = 0.5 * (t_good + t_bad)
        st, ev, _ = _sample(kind, f, fg, flat, lv, hfp, vp, x0, lod, tm, guess, tmp)
        evals += ev
        if st == S_OK:
            t_good = tm
            for i in range(P_SIZE):
                edge[i] = tmp[i]
        else:
            t_bad = tm
    return evals


@ngjit_nrt_free
def _refined_span(kind, f, fg, flat, lv, hfp, vp, x0, lod, acc, cov, n, gaps, guess, prev,
                  cur, stk, sigma, H, share):
    """The span prev -> cur, cut at midpoints (up to REFINE_DEPTH times) where it
    spans more than REFINE_ROWS rows or its intensity changes by more than
    REFINE_JUMP (a steep or bending stretch that one straight span would misplace or
    misshade). Returns (covered intervals, evaluations)."""
    evals = 0
    left = stk[0]
    for i in range(P_SIZE):
        left[i] = prev[i]
        stk[1, i] = cur[i]
    sp = 1
    stk[1, P_DEP] = 0.0
    while sp > 0:
        b = stk[sp]
        d = b[P_DEP]
        if d < REFINE_DEPTH and (abs(b[P_Y] - left[P_Y]) > REFINE_ROWS
                                 or abs(b[P_I] - left[P_I]) > REFINE_JUMP):
            mid = stk[sp + 1]
            st, ev, _ = _sample(kind, f, fg, flat, lv, hfp, vp, x0, lod,
                                0.5 * (left[P_T] + b[P_T]), guess, mid)
            evals += ev
            if st == S_OK:
                b[P_DEP] = d + 1.0
                sp += 1
                mid[P_DEP] = d + 1.0
                continue
        n = _add_span(acc, cov, n, gaps, left, b, sigma, H, share)
        for i in range(P_SIZE):
            left[i] = b[i]
        sp -= 1
    return n, evals


@ngjit_inline
def _below_picture(vp, t, s_lo, s_hi):
    """Do all points of plane t on a column plane Pi, over the heights s in [s_lo,
    s_hi] (relative to the centre), fall more than a pixel below the picture? (Screen
    y is monotone in s there, eq. 10, where both ends lie beyond the screen plane.)"""
    for s in (s_lo, s_hi):
        q = s * vp[VP_SA] + t * vp[VP_CA] + vp[VP_D3]
        if q <= vp[VP_D1]:
            return False
        y = (s * vp[VP_CA] - t * vp[VP_SA]) * vp[VP_D1] / q * vp[VP_SCALE] \
            + (vp[VP_H] - 1.0) * 0.5
        if y >= -1.5:
            return False
    return True


@ngjit_nrt_free
def _pass(kind, f, fg, flat, lv, hfp, vp, x0, lod, ta, tb, sigma, acc, cov, n, gaps, guess,
          pts, H, share):
    """One pass of the column from ta to tb (sigma = +1 ascending, -1 descending).
    Returns (covered intervals, evaluations)."""
    prev = pts[0]
    cur = pts[1]
    edge = pts[2]
    tmp = pts[3]
    stk = pts[4:]
    evals = 0
    have = False
    t_bad = np.nan                             # the failed plane before a run starts
    t = ta
    persp = vp[VP_ORTHO] == 0.0
    guess[:, 0] = np.nan
    t_below = np.nan                           # the last plane wholly below the picture
    while (t - tb) * sigma <= 0.0:
        skip = False
        below = False
        if persp:
            # the whole plane behind the screen plane (behind the eye: the range of w
            # puts every point of Pi on it nearer than d1), or surely off the domain
            s_lo = vp[VP_WLO] - vp[VP_CW]
            s_hi = vp[VP_WHI] - vp[VP_CW]
            q_far = max(s_lo * vp[VP_SA], s_hi * vp[VP_SA]) + t * vp[VP_CA] + vp[VP_D3]
            skip = q_far <= vp[VP_D1]
            if not skip:
                known = _domain_test(vp, x0, t)
                skip = known == 0 or (known < 0 and not _may_meet_domain(vp, x0, t))
            # before a run: the planes whose points all fall below the picture (the
            # ground under a fly camera, out of view) are not sampled, only the last
            # of them, as the run's first sample
            if not skip and not have and lv[0, LV_ZMAX] == lv[0, LV_ZMAX]:
                below = _below_picture(vp, t, lv[0, LV_ZMIN] - vp[VP_CW],
                                       lv[0, LV_ZMAX] - vp[VP_CW])
        st = -1
        if skip or below:
            step = _footprint(vp, t, 0.0)
            if kind == SURF_HEIGHTFIELD:
                step = min(step, lv[0, LV_CELL] / STEPS_PER_CELL)
            step = max(step, vp[VP_DT])
            if below:
                t_below = t
        else:
            if t_below == t_below and not have:
                st, ev, _ = _sample(kind, f, fg, flat, lv, hfp, vp, x0, lod, t_below, guess,
                                    prev)
                evals += ev
                if st == S_OK:
                    have = True
                    t_bad = np.nan
            t_below = np.nan
            st, ev, step = _sample(kind, f, fg, flat, lv, hfp, vp, x0, lod, t, guess, cur)
            evals += ev
        if st == S_OK:
            if not have and t_bad == t_bad:    # a run begins: its edge first
                for i in range(P_SIZE):
                    edge[i] = cur[i]
                evals += _edge(kind, f, fg, flat, lv, hfp, vp, x0, lod, t, t_bad, guess, edge, tmp)
                for i in range(P_SIZE):
                    prev[i] = edge[i]
                have = True
            if have:
                n, ev = _refined_span(kind, f, fg, flat, lv, hfp, vp, x0, lod, acc, cov, n,
                                      gaps, guess, prev, cur, stk, sigma, H, share)
                evals += ev
            for i in range(P_SIZE):
                prev[i] = cur[i]
            have = True
            t_bad = np.nan
        else:
            if have:                           # a run ends: up to its edge
                for i in range(P_SIZE):
                    edge[i] = prev[i]
                evals += _edge(kind, f, fg, flat, lv, hfp, vp, x0, lod, prev[P_T], t, guess, edge,
                               tmp)
                n = _add_span(acc, cov, n, gaps, prev, edge, sigma, H, share)
            have = False
            t_bad = t
        if t == tb:
            break
        t += sigma * step
        if (t - tb) * sigma > 0.0:
            t = tb                             # the last plane on the far end
    return n, evals


@ngjit_nrt_free
def area_column(kind, f, fg, flat, lv, hfp, vp, x0, slices, lod, gcol, ecol, acc, cov, gaps,
                guess, pts):
    """Render one column by area sampling into gcol (H, G_SIZE) and ecol (E_SIZE,
    H): ``slices`` columns evenly across the pixel's width (each exact along its
    column, their mean the pixel's box filter), ``lod`` the footprint's multiplier
    in choosing a level (2**bias). Returns (evaluations, lowest and highest w with
    the upper side seen, lowest and highest row set)."""
    H = gcol.shape[0]
    clear_accumulators(acc)
    evals = 0
    share = 1.0 / slices
    for k in range(slices):
        xk = x0 + ((k + 0.5) * share - 0.5) / vp[VP_SCALE]
        n = np.int64(0)                 # (not a literal 0: _pass compiles once)
        if vp[VP_ORTHO] != 0.0:
            lo, hi = _ortho_chord(vp, xk)
            if lo <= hi:
                n, ev = _pass(kind, f, fg, flat, lv, hfp, vp, xk, lod, lo, hi, 1.0, acc, cov, n,
                              gaps, guess, pts, H, share)
                evals += ev
            continue
        lo, hi = _column_t_range(vp, xk)
        if lo <= hi:
            m = 4.0 * vp[VP_DT]
            lo = max(lo - m, vp[VP_T0])
            hi = min(hi + m, vp[VP_T1])
            t_view = -vp[VP_D3] * vp[VP_CA]
            if hi > t_view:
                n, ev = _pass(kind, f, fg, flat, lv, hfp, vp, xk, lod, max(lo, t_view), hi, 1.0,
                              acc, cov, n, gaps, guess, pts, H, share)
                evals += ev
            if lo < t_view:
                n, ev = _pass(kind, f, fg, flat, lv, hfp, vp, xk, lod, min(hi, t_view), lo, -1.0,
                              acc, cov, n, gaps, guess, pts, H, share)
                evals += ev
    w_lo = np.inf
    w_hi = -np.inf
    j_lo = H
    j_hi = -1
    for j in range(H):
        side = resolve_pixel(acc[j], gcol[j], ecol, j, vp[VP_CU], vp[VP_CV], vp[VP_WORG])
        if side == 0.0:
            ecol[E_SEEN, j] = 0.0
            continue
        w_lo, w_hi = seen_heights(gcol, ecol, j, side, w_lo, w_hi)
        j_lo = min(j_lo, j)
        j_hi = max(j_hi, j)
    # (the seen heights as the G-buffer holds them, less VP_WORG: layout.py G_W)
    return evals, w_lo + vp[VP_WORG], w_hi + vp[VP_WORG], j_lo, j_hi


@ngjit_inline
def _group_normal(c, grp):
    """The unit normal of the group at offset grp of accumulator c (its weighted sum
    made unit; 0 where it is 0)."""
    nx = c[grp + AC_NX]
    ny = c[grp + AC_NY]
    nz = c[grp + AC_NZ]
    q = math.sqrt(nx * nx + ny * ny + nz * nz)
    q = 1.0 / q if q > 0.0 else 0.0
    return nx * q, ny * q, nz * q


@ngjit_inline
def resolve_pixel(c, g, ecol, j, cu, cv, wo):
    """Pixel j's G-buffer entry g and edge-buffer entry from its accumulator c (AC_*):
    the first group's weighted means (the normal made unit) the pixel's surface, its
    total weight that surface's coverage; the second group's, where it has pieces, the
    pixel's edge surface (E_*, its coverage E_COV); flagged where the coverages are
    not one whole surface. Returns the side seen (0: nothing, g untouched)."""
    wgt = c[AC_W]
    if wgt <= 0.0:
        return 0.0
    inv = 1.0 / wgt
    g[G_DEPTH] = c[AC_Z]
    g[G_U] = c[AC_U] * inv - cu          # (from the view's centre: layout.py G_U)
    g[G_V] = c[AC_V] * inv - cv
    g[G_W] = c[AC_WW] * inv - wo         # (from VP_WORG: layout.py G_W)
    g[G_NX], g[G_NY], g[G_NZ] = _group_normal(c, AC_G1)
    g[G_I] = c[AC_I] * inv
    g[G_T] = c[AC_T] * inv
    side = 1.0 if c[AC_SIDE] >= 0.0 else -1.0
    w2 = c[AC_G2 + AC_W]
    if w2 > 0.0:
        ecol[E_SEEN, j] = side + E_FLAG
        ecol[E_COV0, j] = wgt
        ecol[E_COV, j] = w2
        inv = 1.0 / w2
        ecol[E_NX, j], ecol[E_NY, j], ecol[E_NZ, j] = _group_normal(c, AC_G2)
        ecol[E_W, j] = c[AC_G2 + AC_WW] * inv - wo
        ecol[E_I, j] = c[AC_G2 + AC_I] * inv
        ecol[E_SIDE, j] = 1.0 if c[AC_G2 + AC_SIDE] >= 0.0 else -1.0
        ecol[E_DEPTH, j] = c[AC_G2 + AC_Z]
        ecol[E_U, j] = c[AC_G2 + AC_U] * inv - cu
        ecol[E_V, j] = c[AC_G2 + AC_V] * inv - cv
    elif wgt >= WHOLE:
        ecol[E_SEEN, j] = side
    else:
        ecol[E_SEEN, j] = side + E_FLAG
        ecol[E_COV0, j] = wgt
        ecol[E_COV, j] = 0.0
    return side


@ngjit_inline
def seen_heights(gcol, ecol, j, side, w_lo, w_hi):
    """(w_lo, w_hi) widened by the heights pixel j shows with the upper side (the
    colour map's range): its surface's (side > 0) and its edge surface's
    (resolve_pixel's second group)."""
    if side > 0.0:
        w_lo = min(w_lo, gcol[j, G_W])
        w_hi = max(w_hi, gcol[j, G_W])
    x = ecol[E_SEEN, j]
    if flagged(x):                              # (its coverages kept: coverage.py)
        if ecol[E_COV, j] > 0.0 and ecol[E_SIDE, j] > 0.0:
            w_lo = min(w_lo, ecol[E_W, j])
            w_hi = max(w_hi, ecol[E_W, j])
    return w_lo, w_hi


@ngjit
def area_scratch(H, n_lv):
    """area_column's scratch for a column of H rows and n_lv levels: (acc, cov, gaps,
    guess, pts); guess is to be zeroed before each column."""
    return (np.empty((H, AC_SIZE)), np.empty((MAX_INTERVALS, 2)),
            np.empty((MAX_INTERVALS + 1, 2)), np.empty((max(n_lv, 1) + 1, 3)),
            np.empty((4 + REFINE_DEPTH + 2, P_SIZE)))


def _area_functions(kind, f, fg, flat, lv, hfp, vp, slices, lod, gbuf, ebuf, *rest):
    """area_kernel's jitted functions: area_column, called with the kernel's arguments, a
    column's x0, its G-buffer and edge buffer columns and area_scratch's arrays
    (_jit.kernel_calling)."""
    scratch = function_type(area_scratch, types.int64, types.int64).signature.return_type
    return ((area_column, function_type(
        area_column, kind, f, fg, flat, lv, hfp, vp, types.float64, slices, lod,
        types.Array(numba.from_dtype(gbuf.dtype), 2, "A"),
        types.Array(numba.from_dtype(ebuf.dtype), 2, "A"), *scratch.types)),)


@kernel_calling(_area_functions, (area_column,))
def area_kernel(kind, f, fg, flat, lv, hfp, vp, slices, lod, gbuf, ebuf, evals, wrange, rows,
                column):
    """Every column by area sampling (area_column) into the tiled gbuf and ebuf
    (layout.py), the tiles in parallel, as column_kernel: ``flat`` and ``lv`` the
    height field's levels (passes/area.py; ignored for a function surface). Each
    tile's scratch is its own. ``column``: area_column as a function value
    (_jit.kernel_calling)."""
    n_tiles = gbuf.shape[0]
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    W = evals.shape[0]
    n_lv = lv.shape[0]
    for b in prange(n_tiles):
        acc, cov, gaps, guess, pts = area_scratch(H, n_lv)
        rows[b, 0] = H
        rows[b, 1] = -1
        for lane in range(T):
            c = b * T + lane
            if c >= W:
                break
            guess[:, :] = 0.0
            ev, w_lo, w_hi, j_lo, j_hi = column(
                kind, f, fg, flat, lv, hfp, vp, column_x0(vp, c), slices, lod, gbuf[b, :, lane],
                ebuf[b, :, :, lane], acc, cov, gaps, guess, pts)
            evals[c] = ev
            wrange[c, 0] = w_lo
            wrange[c, 1] = w_hi
            rows[b, 0] = min(rows[b, 0], j_lo)
            rows[b, 1] = max(rows[b, 1], j_hi)

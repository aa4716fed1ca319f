"""The shaded floating column, App. A.2, in independent column mode.

Each pixel column is rendered on its own, front to back: sampling planes t = const
advance away from the viewer, the column keeps the floating interval [ymin, ymax] of
screen rows already covered, and every newly visible span between the previous and
the current sample is filled by interpolation (depth, u, v, w, normal, intensity).

Coverage is decided at pixel centres from the floating-point screen row of the
samples, so silhouettes land where the exact surface puts them. A hole (f NaN,
infinite or complex), the domain edge and the near clipping plane break the run; the
break is located by bisection, so edges are clean, and the next valid sample starts a
fresh run. Pixels painted by an earlier run stay (they are nearer), which keeps
occlusion exact when a run does not cover one interval.

In perspective the sampling planes are ordered by distance from the viewpoint along
t: rays whose direction has a positive t component meet the surface in increasing t,
rays pointing back past the nadir in decreasing t, so a column runs an ascending pass
from the viewpoint's t outward and, if the domain reaches behind it, a descending one.
"""
import math

import numba
import numpy as np
from numba import prange, types

from ._jit import (
    array_as_tuple, array_ptr, function_type, kernel_calling, ngjit, ngjit_inline,
    ngjit_nrt_free)
from .index import ceil_index, floor_index, trunc_index
from .layout import (
    A_BUMP, A_I, A_NX, A_NY, A_NZ, A_SIZE, A_SLOPE, A_T, A_U, A_V, A_VN, A_W, A_Y, A_Z,
    GROUP_TILES,
    E_COV, E_COV0, E_DEPTH, E_FLAG, E_I, E_NX, E_NY, E_NZ, E_SEEN, E_SIDE, E_U, E_V, E_W,
    G_DEPTH, G_I, G_NX, G_NY, G_NZ, G_T, G_U, G_V, G_W, HFP_CW, HFP_IU, HFP_IV,
    DETECT_RIDGE, DETECT_WALL, FIX_ADAPTIVE, FIX_NONE, FIX_SPLINE, FIX_SUPER, S_OK, S_OUTSIDE,
    SURF_HEIGHTFIELD,
    VP_CA, VP_CB, VP_CU, VP_CV, VP_CW, VP_D1, VP_D3, VP_DETECT, VP_DT, VP_FIX_RIDGE,
    VP_FIX_SHADE, VP_ORTHO, VP_RATE, VP_SA, VP_SB, VP_SPLINE_TOL, VP_T0, VP_T1,
    VP_WHI, VP_WLO, VP_AA, VP_ADAPT, VP_QNEAR, VP_BATCH, VP_SIZE, VP_INV_D1, VP_UA, VP_UB,
    VP_VA, VP_VB, VP_H, VP_CLIP, VP_KEEP_TOP, VP_FOLD, VP_PASS_HIDDEN, VP_SCALE, VP_HOLE_N,
    VP_WORG,
)
from .coverage import coverages, flagged, keep_coverages, seen_side
from .fold import FOLD_NEAR, fold_test, trace_column
from .correct import (
    WALL_DEPTH, hermite_extremum, lambert_at, probe, probe_ortho, probe_persp, ridge_between,
    shading_problem, wall_between, wall_jump, wall_normal,
)
from .sample import (
    DOMAIN_EPS, _clip_line, _g_at, _line_uv, _r_interval, bracket_ends, column_x0, in_domain,
    heightfield_eval, in_known_hole, into_domain, lambert, ortho_point, sample_point,
    surface_eval,
)


EDGE_BISECTIONS = 16
#: a perspective run's edge (bisected next to a plane whose sample lies outside the
#: domain) counts as on the domain's boundary within this fraction of its size; the
#: bisection places a real entry 2**-EDGE_BISECTIONS of a plane from it
EDGE_TOL = 1e-3
#: Spline iterations when VP_SPLINE_TOL > 0 (section 5.2's optional iteration)
SPLINE_MAX_ITERS = 8
#: Locally adaptive sampling (section 6.3): the step may grow this much with distance
ADAPT_MAX_GROWTH = 16.0
#: A height field's span is cut at no more than this many cell edges
HF_MAX_CROSSINGS = 64
# _hidden_cells: the most cells a span's box may have each way, and the margin (in
# pixels, far above a rounding) by which the box's rows must lie inside the interval
HIDDEN_CELLS = 4
HIDDEN_MARGIN = 1e-6
#: ... and the normal should turn about ADAPT_TURN (radians) from one plane to the
#: next: the step shrinks to ADAPT_MIN_STEP or grows to ADAPT_MAX_STEP times its size
ADAPT_TURN = 0.1
ADAPT_ROWS = 2.0      # pixel rows between successive planes, at most (when coarsening)
ADAPT_MIN_STEP = 0.25
ADAPT_MAX_STEP = 4.0
#: Depth of the correction stack (its last two rows are scratch for walls): adaptive
#: subdivision down to 1/256 of a step, walls down to 2**-WALL_DEPTH
STACK_SIZE = 24
#: added to a stack entry's depth while a wall is being located
WALL_MODE = 1000
#: where the normal of a wall's far end is taken, in widths of the wall's bracket
WALL_BEYOND = 64.0
# Column state ``run``: is a run open, its floating interval, and the last s found
# (at which t, with which ds/dt) to start the next perspective Newton iteration
RUN_OPEN = 0
RUN_YMIN = 1
RUN_YMAX = 2
RUN_GUESS = 3      # the newest solution s, at t RUN_GUESS_T, of any sample
RUN_GUESS_T = 4
RUN_SLOPE = 5      # (s - s') / (t - t') with the sample before
RUN_MS = 6         # the newest solution of the pass's own planes, at t RUN_MT0, and
RUN_MT0 = 7        # the two before (t RUN_MT1, RUN_MT2): the slopes of the two pairs
RUN_MSLOPE = 8
RUN_MSLOPE1 = 9
RUN_MT1 = 10
RUN_MT2 = 11
RUN_MN = 12        # how many of those three there are
RUN_WLO = 13       # the lowest and highest w painted with the upper side seen (the
RUN_WHI = 14       # colormap's range), over all the column's passes
RUN_JLO = 15       # rows (from the bottom) between which the column's passes may have
RUN_JHI = 16       # set E_SEEN (the finishing pass reads none outside them)
RUN_EDGE_J = 17    # antialiasing: the row of the edge surface held back (-1: none), and
RUN_EDGE = 18      # its E_NX, E_NY, E_NZ, E_W, E_I, E_DEPTH, E_SIDE, E_U, E_V (_hold_edge)
RUN_TOP_J = 27     # antialiasing: the top pixel of the run's interval whose coverage
RUN_TOP_KIND = 28  # is kept here, not yet in ecol (-1: none; _fill, _settle_top), its
RUN_TOP_COV = 29   # kind (TOP_EDGE, TOP_CENTRE) and coverage; RUN_TOP_ON: whether it
RUN_TOP_ON = 30    # may (vp's VP_KEEP_TOP)
RUN_FOLD = 31      # 1.0: a sample's curve folds back in t (fold.py): trace the column
RUN_CU = 32        # the view's centre (vp's VP_CU, VP_CV): the G-buffer's and the edge
RUN_CV = 33        # buffer's u, v are stored from it (layout.py G_U)
RUN_WO = 34        # ... and w from vp's VP_WORG (layout.py G_W); RUN_WLO, RUN_WHI too
RUN_SIZE = 35
#: RUN_TOP_KIND: the pixel's centre lies outside the interval (an edge surface covers
#: RUN_TOP_COV of the pixel: its bottom, or where the run began above the centre, a
#: part above it) or inside it (the surface at the centre covers RUN_TOP_COV of it)
TOP_EDGE = 0.0
TOP_CENTRE = 1.0
#: _newton_start keeps the parabola while its bend is at most this fraction of the
#: line's step (measured on the fidelity suite in perspective: 0.25, 0.5, 1 and 4 give
#: the same pictures; 1080p evaluations 1.36 M, 1.34 M, 1.31 M, 1.30 M; the line
#: alone 1.73 M)
QUAD_START_MAX = 1.0
# Horizon-line records (see horizon.py): per column and line, the line's screen row,
# the run's floating interval just before it, and the t where that run started.
H_Y = 0
H_LO = 1
H_HI = 2
H_TS = 3
H_SIZE = 4
#: Orthographic planes per call of the batch evaluator (_batch_planes), and the rows
#: of its scratch bat (BATCH values each): the point; f, f_u, f_v (3 rows, which fb
#: fills m apart for m planes); the sample's status, row, depth, normal, intensity
BATCH = 64
BAT_U = 0
BAT_V = 1
BAT_W = 2
BAT_ST = 5
BAT_Y = 6
BAT_Z = 7
BAT_NX = 8
BAT_NY = 9
BAT_NZ = 10
BAT_I = 11
BAT_VN = 12       # probe()'s values, where vp's VP_DETECT asks for them
BAT_BUMP = 13
BAT_SLOPE = 14
BAT_US = 15       # u and v of f where the surface is box-scaled (HFP_IU, HFP_IV)
BAT_VS = 16
BAT_T = 17        # perspective (_batch_planes_persp): each plane's t, r0 (eq. 9), the
BAT_R0 = 18       # Newton iterate s, the solution s = w - cw
BAT_SI = 19
BAT_S = 20
BAT_PT = 21       # 1.0: an S_OUTSIDE plane's point (BAT_U, BAT_V) lies where its root is
BAT_ACT = 22      # 1.0: the plane is still iterating, 2.0: it has converged, 0.0: neither
BAT_LAZY = 23     # 1.0: its normal, intensity and probe()'s values are still to come
BAT_SIZE = 24
#: a perspective plane the batch leaves to the scalar path (_sample_at): Newton did not
#: converge in BATCH_NEWTON vector steps, or the point is not a plain one (a hole, the
#: domain's edge, in front of the screen, a root outside with one inside it may hide)
S_RETRY = 4
BATCH_NEWTON = 4
#: how far (in pixels) a batched perspective sample's point may lie off its column plane
BATCH_TOL_PX = 0.01
#: a batched perspective solution is taken where it lies within this many pixels of
#: the scalar path's Newton start (_newton_start): the root that path would find
BATCH_ACCEPT_PX = 0.5


@ngjit_inline
def _newton_start(run, t):
    """Where the perspective Newton iteration for plane t may start: returns (line,
    parabola). The line goes through the last two solutions of any samples (Gordon's
    neighbour start, extrapolated); the parabola through the last three solutions of
    the pass's own planes, NaN where it bends away from the line by more than
    QUAD_START_MAX times the line's step (or while there are fewer than three). Between
    two planes, where corrections sample, the parabola interpolates. Before any
    solution both are NaN: Newton starts at Gordon's point s = 0."""
    if run[RUN_GUESS_T] == 0.0 and run[RUN_GUESS] == 0.0 and run[RUN_SLOPE] == 0.0:
        return np.nan, np.nan
    s0 = run[RUN_GUESS]
    lin = s0 + run[RUN_SLOPE] * (t - run[RUN_GUESS_T])
    if run[RUN_MN] < 3.0:
        return lin, np.nan
    span = run[RUN_MT0] - run[RUN_MT2]
    if span == 0.0:
        return lin, np.nan
    c = (run[RUN_MSLOPE] - run[RUN_MSLOPE1]) / span      # the second divided difference
    quad = run[RUN_MS] + (t - run[RUN_MT0]) * (run[RUN_MSLOPE] + c * (t - run[RUN_MT1]))
    if abs(quad - lin) <= QUAD_START_MAX * abs(lin - s0):
        return lin, quad
    return lin, np.nan


@ngjit_inline
def _keep_solution(run, s, t, main):
    """Perspective: remember sample (t, s) for _newton_start: every sample's solution
    updates the line, only those of the pass's own planes (``main``) the parabola."""
    dt = t - run[RUN_GUESS_T]
    run[RUN_SLOPE] = (s - run[RUN_GUESS]) / dt if dt != 0.0 else 0.0
    run[RUN_GUESS] = s
    run[RUN_GUESS_T] = t
    if main:
        n = run[RUN_MN]
        dt = t - run[RUN_MT0]
        if n > 0.0 and dt != 0.0:
            run[RUN_MSLOPE1] = run[RUN_MSLOPE]
            run[RUN_MT2] = run[RUN_MT1]
            run[RUN_MT1] = run[RUN_MT0]
            run[RUN_MSLOPE] = (s - run[RUN_MS]) / dt
            run[RUN_MN] = min(n + 1.0, 3.0)
        elif n == 0.0:
            run[RUN_MN] = 1.0
        run[RUN_MS] = s
        run[RUN_MT0] = t


@ngjit_inline
def store_sample(out, y, z, u, v, w, nx, ny, nz, lam, t):
    """A sample's attributes into its record ``out`` (layout.py A_*)."""
    out[A_Y] = y
    out[A_Z] = z
    out[A_U] = u
    out[A_V] = v
    out[A_W] = w
    out[A_NX] = nx
    out[A_NY] = ny
    out[A_NZ] = nz
    out[A_I] = lam
    out[A_T] = t


@ngjit_nrt_free
def _sample_into(kind, f, fg, hf, hfp, vp, x0, t, out, run):
    """_sample_at as a call (where sampling is rare: corrections, edges)."""
    return _sample_at(kind, f, fg, hf, hfp, vp, x0, t, out, run, False, out, -1)


@ngjit_inline
def _sample_at(kind, f, fg, hf, hfp, vp, x0, t, out, run, main, bat, kb):
    """Sample plane t of column x0 into ``out`` (the A_* attributes). Returns (status,
    evaluations of f). Inlined in the column's main loop. In perspective the Newton
    iteration starts from ``run``'s last solutions (_newton_start): every sample's
    solution updates the line, only those of the pass's own planes (``main``) the
    parabola (the samples of corrections, edges and slivers go back and forth in t
    between two planes). Planes sampled ahead by _batch_planes (_batch_planes_persp)
    come as number kb >= 0 of bat."""
    if kb >= 0:
        if vp[VP_ORTHO] == 0.0:
            _finish_batched(vp, x0, bat, kb)        # (where it is S_OK and still lazy)
        st = int(bat[BAT_ST * BATCH + kb])
        # (a perspective batch counts its evaluations itself: _batch_planes_persp)
        ev = 0 if st == S_OUTSIDE or vp[VP_ORTHO] == 0.0 else 1
        u = bat[BAT_U * BATCH + kb]
        v = bat[BAT_V * BATCH + kb]
        y = bat[BAT_Y * BATCH + kb]
        z = bat[BAT_Z * BATCH + kb]
        w = bat[BAT_W * BATCH + kb]
        nx = bat[BAT_NX * BATCH + kb]
        ny = bat[BAT_NY * BATCH + kb]
        nz = bat[BAT_NZ * BATCH + kb]
        lam = bat[BAT_I * BATCH + kb]
        if st == S_OK and vp[VP_DETECT] != 0.0:
            out[A_VN] = bat[BAT_VN * BATCH + kb]
            out[A_BUMP] = bat[BAT_BUMP * BATCH + kb]
            out[A_SLOPE] = bat[BAT_SLOPE * BATCH + kb]
    else:
        if vp[VP_ORTHO] == 0.0:
            known = _domain_test(vp, x0, t)
            if known == 0 or (known < 0 and not _may_meet_domain(vp, x0, t)):
                return S_OUTSIDE, 0
        lin = np.nan
        quad = np.nan
        if vp[VP_ORTHO] == 0.0:
            lin, quad = _newton_start(run, t)
            if kind == SURF_HEIGHTFIELD:
                quad = np.nan       # bilinear patches: the curve bends at the creases only
        st, ev, y, z, u, v, w, nx, ny, nz, lam = sample_point(kind, f, fg, hf, hfp, vp, x0, t,
                                                              quad if quad == quad else lin)
    if st != S_OK:
        if ev > 0:                  # where the failed point lies (_column_pass's slivers)
            out[A_U] = u
            out[A_V] = v
        return st, ev
    if vp[VP_ORTHO] == 0.0:
        _keep_solution(run, w - vp[VP_CW], t, main)
        if vp[VP_FOLD] != 0.0 and fold_test(vp, x0, nx, ny, nz, 0.0 if main else FOLD_NEAR):
            run[RUN_FOLD] = 1.0         # (fold.py)
    store_sample(out, y, z, u, v, w, nx, ny, nz, lam, t)
    if vp[VP_DETECT] != 0.0 and kb < 0:
        out[A_VN], out[A_BUMP], out[A_SLOPE] = probe(vp, x0, out)
    return st, ev


@ngjit_nrt_free
def _run_edge(kind, f, fg, hf, hfp, vp, x0, t_ok, t_bad, st_bad, tmp, edge, run):
    """The edge of a run between plane t_ok (its sample taken) and t_bad (its sample's
    status st_bad), bisected EDGE_BISECTIONS times: ``edge`` gets the last sample taken
    (tmp is scratch). Returns (found, evaluations).

    In perspective a run starts or ends inside the domain next to a plane whose sample
    was dropped as outside only where its line held an even number of roots inside
    the domain (g of one sign at the ends of its part inside, sample._root_inside): a
    piece of the curve born or ended at a fold in t (where the curve enters or leaves
    the domain, the edge lies on its boundary). That marks the column for the fold
    tracer (fold.py), where vp's VP_FOLD allows."""
    found = False
    evals = 0
    for _ in range(EDGE_BISECTIONS):
        tm = 0.5 * (t_ok + t_bad)
        st_m, ev_m = _sample_into(kind, f, fg, hf, hfp, vp, x0, tm, tmp, run)
        evals += ev_m
        if st_m == S_OK:
            t_ok = tm
            _copy(edge, tmp)
            found = True
        else:
            t_bad = tm
            st_bad = st_m
    if found and vp[VP_ORTHO] == 0.0 and st_bad == S_OUTSIDE and vp[VP_FOLD] != 0.0 and \
            not _on_domain_edge(vp, edge[A_U], edge[A_V]):
        run[RUN_FOLD] = 1.0
    return found, evals


@ngjit_inline
def _on_domain_edge(vp, u, v):
    """Does (u, v) lie within EDGE_TOL of the domain's size of its boundary?"""
    du = EDGE_TOL * (vp[VP_UB] - vp[VP_UA])
    dv = EDGE_TOL * (vp[VP_VB] - vp[VP_VA])
    return (u - vp[VP_UA] <= du or vp[VP_UB] - u <= du or v - vp[VP_VA] <= dv
            or vp[VP_VB] - v <= dv)


@ngjit_inline
def _copy(dst, src):
    """dst[:] = src for two A_SIZE sample vectors (no slice views)."""
    for k in range(A_SIZE):
        dst[k] = src[k]


#: _domain_test's margins: far above the rounding of it and of _may_meet_domain, and
#: above _may_meet_domain's own tolerance
SURELY_MEETS = 1e-9
SURELY_MISSES = 1e-8
#: ... and the least |cos(beta)|, |sin(beta)| for which it says "misses" (a smaller
#: one, unless under _clip_line's 1e-15, makes _may_meet_domain's tolerance, relative
#: to the clipped ends, large)
MISS_MIN_SLOPE = 1e-3


@ngjit_inline
def _domain_test(vp, x0, t):
    """_may_meet_domain's answer where it is sure without its 6 divisions (a profile
    put 15 % of a perspective render's time on them; two thirds of the planes of a
    column miss the domain; the column pass measured 2-3 % faster): 1 where the column
    plane's point at t and the middle of the estimated range of w lies inside the
    domain, 0 where the ends of the range both lie beyond one of the domain's edges, by
    margins far above the rounding and _may_meet_domain's tolerance; -1 (ask
    _may_meet_domain) elsewhere."""
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    s_lo = vp[VP_WLO] - vp[VP_CW]
    s_hi = vp[VP_WHI] - vp[VP_CW]
    q = t * vp[VP_CA] + vp[VP_D3]
    k = x0 * vp[VP_INV_D1]
    bu = vp[VP_CU] + t * sb                      # eq. (2): u = bu + r cb, v = bv - r sb
    bv = vp[VP_CV] + t * cb
    r = k * (0.5 * (s_lo + s_hi) * vp[VP_SA] + q)
    u = bu + r * cb
    v = bv - r * sb
    mu = SURELY_MEETS * (vp[VP_UB] - vp[VP_UA] + abs(u))
    mv = SURELY_MEETS * (vp[VP_VB] - vp[VP_VA] + abs(v))
    if vp[VP_UA] + mu < u < vp[VP_UB] - mu and vp[VP_VA] + mv < v < vp[VP_VB] - mv:
        return 1
    ra = k * (s_lo * vp[VP_SA] + q)
    rb = k * (s_hi * vp[VP_SA] + q)
    # a bound of |hi|, to which _may_meet_domain's tolerance is relative: its clipped
    # ends, (edge - base) / slope, where a slope is not under _clip_line's 1e-15
    big = abs(ra) + abs(rb)
    if abs(cb) >= 1e-15:
        if abs(cb) < MISS_MIN_SLOPE:
            return -1
        big += (abs(vp[VP_UA]) + abs(vp[VP_UB]) + abs(bu)) / abs(cb)
    if abs(sb) >= 1e-15:
        if abs(sb) < MISS_MIN_SLOPE:
            return -1
        big += (abs(vp[VP_VA]) + abs(vp[VP_VB]) + abs(bv)) / abs(sb)
    m = SURELY_MISSES * (1.0 + big)
    ua = bu + ra * cb
    ub = bu + rb * cb
    va = bv - ra * sb
    vb = bv - rb * sb
    if ((ua < vp[VP_UA] - m and ub < vp[VP_UA] - m) or (ua > vp[VP_UB] + m and ub > vp[VP_UB] + m)
            or (va < vp[VP_VA] - m and vb < vp[VP_VA] - m)
            or (va > vp[VP_VB] + m and vb > vp[VP_VB] + m)):
        return 0
    return -1


@ngjit_nrt_free
def _may_meet_domain(vp, x0, t):
    """Perspective pre-check: can the column plane's point at t lie in the domain,
    given the estimated range of w? Saves Newton solves far outside."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    d1 = vp[VP_D1]
    d3 = vp[VP_D3]
    s_lo = vp[VP_WLO] - vp[VP_CW]
    s_hi = vp[VP_WHI] - vp[VP_CW]
    ra = x0 * (s_lo * sa + t * ca + d3) / d1
    rb = x0 * (s_hi * sa + t * ca + d3) / d1
    # along r on plane t: u = cu + t sb + r cb, v = cv + t cb - r sb   (eq. 2)
    lo, hi = _clip_line(vp, vp[VP_CU] + t * sb, cb, vp[VP_CV] + t * cb, -sb, min(ra, rb), max(ra, rb))
    return lo <= hi + 1e-9 * (1.0 + abs(hi))


@ngjit_nrt_free
def _ortho_chord(vp, x0):
    """t-interval of the orthographic column line r = x0 inside the domain."""
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    # along t on r = x0: u = cu + x0 cb + t sb, v = cv - x0 sb + t cb   (eq. 3)
    return _clip_line(vp, vp[VP_CU] + x0 * cb, sb, vp[VP_CV] - x0 * sb, cb, -np.inf, np.inf)


#: _column_t_range: a point meets a constraint when it misses it by at most this,
#: relative (far above the rounding: the range only decides which planes are tested)
CLIP_TOL = 1e-7
#: ... and _pass_planes tests this many planes more on each side of the range
CLIP_MARGIN_PLANES = 4.0


@ngjit_inline
def _pass_constraint(vp, x0, idx):
    """Constraint idx (0 to 5) of perspective column x0 as a t + b s + c >= 0 over the
    plane of (t, s), s = w - cw: the point of sampling plane t at height s, at
    r = x0 (s sa + t ca + d3) / d1 on Pi (as _may_meet_domain has it), lies inside the
    domain, u = cu + t sb + r cb in [ua, ub] and v = cv + t cb - r sb in [va, vb]
    (eq. 2), and s inside the estimated range of w."""
    k = x0 * vp[VP_INV_D1]
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    d3 = vp[VP_D3]
    if idx == 0:                                 # u >= ua
        return sb + cb * k * ca, cb * k * sa, vp[VP_CU] + cb * k * d3 - vp[VP_UA]
    if idx == 1:                                 # u <= ub
        return -(sb + cb * k * ca), -(cb * k * sa), vp[VP_UB] - vp[VP_CU] - cb * k * d3
    if idx == 2:                                 # v >= va
        return cb - sb * k * ca, -(sb * k * sa), vp[VP_CV] - sb * k * d3 - vp[VP_VA]
    if idx == 3:                                 # v <= vb
        return -(cb - sb * k * ca), sb * k * sa, vp[VP_VB] - vp[VP_CV] + sb * k * d3
    if idx == 4:                                 # s >= the lowest w
        return 0.0, 1.0, vp[VP_CW] - vp[VP_WLO]
    return 0.0, -1.0, vp[VP_WHI] - vp[VP_CW]      # s <= the highest w


@ngjit_nrt_free
def _column_t_range(vp, x0):
    """The range of t over which perspective column x0's plane Pi may meet the
    surface, as far as the estimated range of w tells (the per-plane question of
    _may_meet_domain, for all planes at once): the least and the greatest t of the
    polygon that _pass_constraint's six constraints leave of the plane of (t, s),
    found among its vertices (where two constraint lines cross). Returns (lo, hi),
    lo > hi where the polygon is empty (the column meets nothing)."""
    lines = (_pass_constraint(vp, x0, 0), _pass_constraint(vp, x0, 1),
             _pass_constraint(vp, x0, 2), _pass_constraint(vp, x0, 3),
             _pass_constraint(vp, x0, 4), _pass_constraint(vp, x0, 5))
    lo = np.inf
    hi = -np.inf
    for i in range(6):
        ai, bi, ci = lines[i]
        for j in range(i + 1, 6):
            aj, bj, cj = lines[j]
            det = ai * bj - aj * bi
            if abs(det) <= 1e-14 * (abs(ai) + abs(bi)) * (abs(aj) + abs(bj)):
                continue                         # parallel
            t = (bi * cj - bj * ci) / det
            s = (aj * ci - ai * cj) / det
            inside = True
            for m in range(6):
                a, b, c = lines[m]
                if a * t + b * s + c < -CLIP_TOL * ((abs(a) + abs(b)) * (1.0 + abs(t) + abs(s))
                                                  + abs(c)):
                    inside = False
                    break
            if inside:
                lo = min(lo, t)
                hi = max(hi, t)
    return lo, hi


@ngjit_nrt_free
def _pass_planes(vp, x0, sigma, n, ka, kb, t0, dt):
    """The planes i_first to i_end - 1 of a uniform perspective pass (numbered as
    _column_pass steps: 0 is ta, n - 1 is tb, the grid's planes t0 + k dt between)
    that it needs to sample. Outside _column_t_range's range (and CLIP_MARGIN_PLANES
    planes more) every plane is surely outside: _may_meet_domain says so, and the
    sample costs no evaluation and changes nothing. Of those, the pass still samples
    the last before the range and the first after it (a run's edge is bisected from
    them). Most planes of a column miss the domain: sampling them all was about a
    tenth of a perspective render's time. Returns (0, 0) where the column meets
    nothing."""
    lo, hi = _column_t_range(vp, x0)
    if not lo <= hi:
        return 0, 0
    m = CLIP_MARGIN_PLANES * dt + CLIP_TOL * (1.0 + abs(lo) + abs(hi))
    lo -= m
    hi += m
    if sigma > 0.0:                  # k = ka + i - 1: t grows with i
        i_first = ceil_index((lo - t0) / dt) - 1 - ka + 1       # the last t < lo
        i_after = floor_index((hi - t0) / dt) + 1 - ka + 1      # the first t > hi
    else:                            # k = kb - (i - 1): t falls
        i_first = kb - (floor_index((hi - t0) / dt) + 1) + 1    # the last t > hi
        i_after = kb - (ceil_index((lo - t0) / dt) - 1) + 1     # the first t < lo
    i_first = min(max(i_first, 0), max(n - 2, 0))
    i_end = min(max(i_after, 1) + 1, n)
    return i_first, i_end


@ngjit_nrt_free
def _fill_span(gcol, ecol, run, prev, cur, sigma, persp, d3, H, aa):
    """_fill as a call (outside the column's main loop)."""
    _fill(gcol, ecol, run, prev, cur, sigma, persp, d3, H, aa)


@ngjit_inline
def _fill(gcol, ecol, run, prev, cur, sigma, persp, d3, H, aa):
    """Paint the rows that the span prev -> cur newly uncovers (App. A.2 Interpolate).

    With ``aa`` (section 6.4) the floating interval's float ends also give each
    pixel's coverage: ecol's E_COV0 for the surface at the pixel's centre, and an edge
    surface for the part of a pixel that a span covers without its centre (where the
    surface reappears beyond an extremum, or at a silhouette), blended by coverage
    later.

    The pixel at the top of a span going up, covered in part, is kept in ``run``
    (RUN_TOP_*), not flagged in ecol: the next span of the run nearly always goes on
    through it and covers the rest, and then the pixel is whole and nothing needs
    writing. Any other span settles it first (_settle_top), so ecol holds what
    flagging it at once would have written whenever another span reads it."""
    y = cur[A_Y]
    if run[RUN_OPEN] == 0.0:
        _settle_top(ecol, run)
        run[RUN_OPEN] = 1.0
        run[RUN_YMIN] = y
        run[RUN_YMAX] = y
        return
    up = y > run[RUN_YMAX]
    if up:                                     # above the column's max: upper side if ascending
        lo_f = run[RUN_YMAX]
        hi_f = y
        cont = prev[A_Y] >= lo_f               # the same surface goes on from the max
        j_cont = floor_index(lo_f + 0.5)
        j0 = floor_index(run[RUN_YMAX]) + 1
        j1 = floor_index(y)
        side = sigma
        run[RUN_YMAX] = y
    elif y < run[RUN_YMIN]:                    # below the min
        lo_f = y
        hi_f = run[RUN_YMIN]
        cont = prev[A_Y] <= hi_f
        j_cont = floor_index(hi_f + 0.5)
        j0 = ceil_index(y)
        j1 = ceil_index(run[RUN_YMIN]) - 1
        side = -sigma
        run[RUN_YMIN] = y
    else:
        return                          # hidden: inside the floating interval
    # the top pixel kept in run: this span goes on through it (then taken over here:
    # pj, its kind and coverage), or it is settled
    pj = -1
    p_edge = False
    p_cov = 0.0
    if run[RUN_TOP_J] >= 0.0:
        if up and cont and aa and int(run[RUN_TOP_J]) == j_cont:
            pj = j_cont
            p_edge = run[RUN_TOP_KIND] == TOP_EDGE
            p_cov = run[RUN_TOP_COV]
            run[RUN_TOP_J] = -1.0
        else:
            _settle_top(ecol, run)
    # the pixel holding the new top (-1: none to keep)
    j_top = floor_index(hi_f + 0.5) if up and run[RUN_TOP_ON] != 0.0 else -1
    if pj >= 0 and (lo_f < pj or not p_edge) and 0 <= j_top < H and \
            (j_top == pj or ecol[E_SEEN, j_top] == 0.0):
        _fill_on(gcol, ecol, run, prev, cur, side, persp, d3, H, lo_f, hi_f, j0, j1, pj,
                 p_edge, p_cov, j_top)
        return
    yp, inv_dy, qp, qc = _span_rows(run, prev, cur, persp, d3, H, lo_f, hi_f)
    # a new edge surface (section 6.4) made by this span, held back (_hold_edge)
    new_j = -1
    e_nx = e_ny = e_nz = e_w = e_i = e_z = e_side = e_u = e_v = 0.0
    if aa:
        # pixels the span covers in part without their centre: the two ends
        for e in range(2):
            jp = floor_index((lo_f if e == 0 else hi_f) + 0.5)
            if (e == 1 and jp == floor_index(lo_f + 0.5)) or jp < 0 or jp >= H:
                continue
            if jp >= j0 and jp <= j1:
                continue                # its centre is painted below
            a = max(lo_f, jp - 0.5)
            b = min(hi_f, jp + 0.5)
            cov = b - a
            if cov <= 0.0:
                continue
            if jp == pj:                # the top pixel kept in run (e == 0)
                if p_edge:              # its centre not reached: more of it covered
                    _keep_top(run, jp, TOP_EDGE, min(p_cov + cov, 1.0))
                else:                   # the rest of it covered: whole (unflagged)
                    c0 = min(p_cov + cov, 1.0)
                    if c0 < 1.0:        # (short of 1 by a rounding)
                        _keep_top(run, jp, TOP_CENTRE, c0)
                if j_top != jp:
                    _settle_top(ecol, run)      # no longer the top
                pj = -1
                continue
            x_p = ecol[E_SEEN, jp]
            seen_p = seen_side(x_p) != 0.0
            cov0_p, ecov_p = coverages(ecol, jp)
            if seen_p and cont and jp == j_cont:
                c0 = min(cov0_p + cov, 1.0)
                if c0 >= 1.0 and ecov_p <= 0.0:
                    ecol[E_SEEN, jp] = seen_side(ecol[E_SEEN, jp])   # whole: unflagged
                elif c0 != cov0_p:
                    keep_coverages(ecol, jp)
                    ecol[E_COV0, jp] = c0
                continue
            room = 1.0 - (cov0_p if seen_p else 0.0)
            if ecov_p > 0.0:
                ecol[E_COV, jp] = min(ecov_p + cov, room)
                continue
            # the new top's pixel, untouched so far: kept in run (its coverage alone)
            keep_top = jp == j_top and x_p == 0.0 and np.float32(min(cov, room)) > 0.0
            if not keep_top:
                keep_coverages(ecol, jp)
            lw = _chord_weight(0.5 * (a + b), yp, inv_dy, persp, qp, qc)
            if new_j >= 0:              # the span's second: hold the first now
                _hold_edge(ecol, run, new_j, e_nx, e_ny, e_nz, e_w, e_i, e_z, e_side, e_u,
                           e_v)
            new_j = jp                  # held back: _hold_edge, below
            e_nx, e_ny, e_nz, e_w, e_i, e_z, e_u, e_v = _chord_at(prev, cur, lw)
            e_side = side
            if keep_top:
                _keep_top(run, jp, TOP_EDGE, min(cov, room))
            else:
                ecol[E_COV, jp] = min(cov, room)
    _paint(gcol, ecol, run, prev, cur, side, persp, H, yp, inv_dy, qp, qc, lo_f, hi_f, j0, j1,
           aa, False, cont, j_cont, pj, p_cov, j_top)
    if new_j >= 0:
        _hold_edge(ecol, run, new_j, e_nx, e_ny, e_nz, e_w, e_i, e_z, e_side, e_u, e_v)


@ngjit_inline
def _span_rows(run, prev, cur, persp, d3, H, lo_f, hi_f):
    """Widen the rows the column may mark (RUN_JLO, RUN_JHI) to the span's: its pixels
    from the floor of its low end to the one holding its high end (the partly
    covered pixels included). Returns what _chord_weight takes of the chord prev ->
    cur: (yp, inv_dy, qp, qc)."""
    run[RUN_JLO] = min(run[RUN_JLO], max(math.floor(lo_f), 0.0))
    run[RUN_JHI] = max(run[RUN_JHI], min(math.floor(hi_f + 0.5), H - 1.0))
    yp = prev[A_Y]
    qp = 1.0
    qc = 1.0
    if persp:
        qp = 1.0 / (prev[A_Z] + d3)
        qc = 1.0 / (cur[A_Z] + d3)
    return yp, 1.0 / (cur[A_Y] - yp), qp, qc


@ngjit_inline
def _chord_at(prev, cur, lw):
    """(nx, ny, nz, w, intensity, depth, u, v) at weight lw of the chord prev -> cur."""
    return (prev[A_NX] + lw * (cur[A_NX] - prev[A_NX]), prev[A_NY] + lw * (cur[A_NY] - prev[A_NY]),
            prev[A_NZ] + lw * (cur[A_NZ] - prev[A_NZ]), prev[A_W] + lw * (cur[A_W] - prev[A_W]),
            prev[A_I] + lw * (cur[A_I] - prev[A_I]), prev[A_Z] + lw * (cur[A_Z] - prev[A_Z]),
            prev[A_U] + lw * (cur[A_U] - prev[A_U]), prev[A_V] + lw * (cur[A_V] - prev[A_V]))


@ngjit_inline
def _paint(gcol, ecol, run, prev, cur, side, persp, H, yp, inv_dy, qp, qc, lo_f, hi_f, j0, j1,
           aa, on, cont, j_cont, pj, p_cov, j_top):
    """Paint rows j0 to j1 of the span prev -> cur (from lo_f to hi_f) where no
    earlier, nearer run did: the G-buffer interpolated along the chord, the side seen,
    and with ``aa`` each pixel's coverage (_fill). ``on`` (a constant): the span goes
    on through the top pixel kept in run, pj (_fill_on): every pixel it paints is
    whole there but where an edge surface of an earlier run shares it."""
    j0 = max(j0, 0)
    j1 = min(j1, H - 1)
    upper = side > 0.0
    w_lo = run[RUN_WLO]
    w_hi = run[RUN_WHI]
    # the chord's ends, read once: the stores below might alias prev and cur for all
    # LLVM knows, which made it load all 18 again for every pixel
    z0 = prev[A_Z]
    u0 = prev[A_U]
    v0 = prev[A_V]
    w0 = prev[A_W]
    nx0 = prev[A_NX]
    ny0 = prev[A_NY]
    nz0 = prev[A_NZ]
    i0 = prev[A_I]
    t0 = prev[A_T]
    dz = cur[A_Z] - z0
    du = cur[A_U] - u0
    dv = cur[A_V] - v0
    dw = cur[A_W] - w0
    dnx = cur[A_NX] - nx0
    dny = cur[A_NY] - ny0
    dnz = cur[A_NZ] - nz0
    di = cur[A_I] - i0
    dt = cur[A_T] - t0
    # u, v and w stored from the view's centre and VP_WORG (layout.py G_U, G_W)
    u0r = u0 - run[RUN_CU]
    v0r = v0 - run[RUN_CV]
    w0r = w0 - run[RUN_WO]
    for j in range(j0, j1 + 1):
        x = ecol[E_SEEN, j]
        if seen_side(x) != 0.0:
            # painted by an earlier, nearer run; where that covers it in part (a
            # silhouette's pixel, the run ended by a hole), this span shows through
            # the rest, as its edge surface
            if aa and flagged(x):
                _cover_rest(ecol, run, j, max(min(hi_f, j + 0.5) - max(lo_f, j - 0.5), 0.0),
                            side, _chord_weight(j, yp, inv_dy, persp, qp, qc), prev, cur)
            continue
        lw = _chord_weight(j, yp, inv_dy, persp, qp, qc)
        gcol[j, G_DEPTH] = z0 + lw * dz
        gcol[j, G_U] = u0r + lw * du
        gcol[j, G_V] = v0r + lw * dv
        w32 = np.float32(w0r + lw * dw)  # (the value stored, in the G-buffer's type)
        gcol[j, G_W] = w32
        if upper:
            w_lo = min(w_lo, w32)
            w_hi = max(w_hi, w32)
        gcol[j, G_NX] = nx0 + lw * dnx
        gcol[j, G_NY] = ny0 + lw * dny
        gcol[j, G_NZ] = nz0 + lw * dnz
        gcol[j, G_I] = i0 + lw * di
        gcol[j, G_T] = t0 + lw * dt
        if aa:
            c0 = max(min(hi_f, j + 0.5) - max(lo_f, j - 0.5), 0.0)
            if not on:                  # (on: whole, unless an edge surface shares it)
                if j == pj:
                    # the top pixel kept in run, its centre not reached until now: its
                    # edge surface covered the part under this span, the same surface
                    # goes on through the centre (as below, where it is flagged)
                    c0 = min(c0 + p_cov, 1.0)
                    if c0 >= 1.0:
                        ecol[E_SEEN, j] = side
                        continue
                elif cont and j == j_cont and x != 0.0:
                    # The pixel at the interval's continuing end: its edge surface is
                    # the part this run's spans covered below (above) the centre. The
                    # same surface goes on through the centre, so the pixel is the
                    # centre's, as every pixel inside a run (the end pixel of a span
                    # was a blend of two points of one surface: 10 % of the pixels at
                    # 1920x1080)
                    c0 = min(c0 + ecol[E_COV, j], 1.0)
                    ecol[E_COV, j] = 0.0
                    if c0 >= 1.0:
                        ecol[E_SEEN, j] = side
                        continue
                if x == 0.0 and c0 != 1.0 and j == j_top:
                    ecol[E_SEEN, j] = side      # the new top, covered in part: kept in run
                    _keep_top(run, j, TOP_CENTRE, c0)
                    continue
            if x != 0.0 or (c0 != 1.0 and not on):  # in part, or shared with an edge
                keep_coverages(ecol, j)
                ecol[E_COV0, j] = c0
                ecol[E_SEEN, j] = side + E_FLAG
                continue
        ecol[E_SEEN, j] = side
    run[RUN_WLO] = w_lo
    run[RUN_WHI] = w_hi


@ngjit_inline
def _cover_rest(ecol, run, j, cov, side, lw, prev, cur):
    """A span covers ``cov`` of pixel j, which an earlier run covers in part (flagged,
    coverage.py): it shows through the rest (1 - E_COV0), as the pixel's edge surface
    (the one there, with more coverage; or this span's, at weight lw of its chord).
    Within one run the floating interval's ends do this (_fill); a later run (after a
    hole) met such a pixel only inside a span, where it was skipped as painted, and
    the background showed through the rest (a light dot at a rim's silhouette over
    the surface behind)."""
    cov0 = ecol[E_COV0, j]
    ecov = ecol[E_COV, j]
    room = 1.0 - cov0
    if cov <= 0.0 or ecov >= room:
        return
    if ecov <= 0.0:
        nx, ny, nz, w, lam, z, u, v = _chord_at(prev, cur, lw)
        _store_edge(ecol, j, nx, ny, nz, w - run[RUN_WO], lam, z, side, u - run[RUN_CU],
                    v - run[RUN_CV])
    ecol[E_COV, j] = min(ecov + cov, room)


@ngjit_inline
def _fill_on(gcol, ecol, run, prev, cur, side, persp, d3, H, lo_f, hi_f, j0, j1, pj, p_edge,
             p_cov, j_top):
    """_fill of an antialiased span that goes on up from the top of the run's interval
    (lo_f, in pixel pj, kept in run: p_edge and p_cov its kind and coverage; pj's
    centre not reached yet where p_edge) to hi_f (in pixel j_top, untouched so far
    unless it is pj): what _fill's general path writes, without its branches on
    where the span's ends fall inside their pixels (half go either way; the two cost
    about a tenth of the column pass). The pixels between are whole; pj is whole now
    unless the span ends inside it (or a rounding leaves it short of 1); the new top
    is kept in run (its kind and coverage chosen by selects); and its edge surface is
    held (_hold_edge), whatever its kind: one that a pixel does not keep (its E_COV
    0) is never written."""
    yp, inv_dy, qp, qc = _span_rows(run, prev, cur, persp, d3, H, lo_f, hi_f)
    _paint(gcol, ecol, run, prev, cur, side, persp, H, yp, inv_dy, qp, qc, lo_f, hi_f, j0, j1,
           True, True, True, pj, pj, p_cov, j_top)
    # (branch-free where the outcome is a toss: where the span ends inside its pixels)
    same = j_top == pj
    # pj's rest covered (its centre from below, or its top part): whole unless a
    # rounding leaves it short
    c0 = min(p_cov + ((pj + 0.5) - lo_f), 1.0)
    if (not same) & (c0 < 1.0):
        _keep_top(run, pj, TOP_CENTRE, c0)
        _settle_top(ecol, run)          # (its centre is painted: E_SEEN holds the side)
    a = max(lo_f, j_top - 0.5)
    cov = min(p_cov + (hi_f - lo_f), 1.0) if same else hi_f - a
    centre = hi_f >= j_top
    keep = (cov < 1.0) if centre else (cov > 0.0)
    run[RUN_TOP_J] = j_top if keep else -1.0
    run[RUN_TOP_KIND] = TOP_CENTRE if centre else TOP_EDGE
    run[RUN_TOP_COV] = np.float32(cov)
    # the new top's edge surface, for where its centre is not covered, held as
    # _hold_edge holds it (held where the centre is covered as well; where the span
    # stays in pj, the one held before stays)
    if run[RUN_EDGE_J] != j_top:
        _write_edge(ecol, run)
    run[RUN_EDGE_J] = j_top
    if not same:
        e_nx, e_ny, e_nz, e_w, e_i, e_z, e_u, e_v = _chord_at(
            prev, cur, _chord_weight(0.5 * (a + hi_f), yp, inv_dy, persp, qp, qc))
        held = (e_nx, e_ny, e_nz, e_w, e_i, e_z, side, e_u, e_v)
        for k in range(9):
            run[RUN_EDGE + k] = held[k]


@ngjit_inline
def _keep_top(run, j, kind, cov):
    """Keep pixel j, the top of the run's interval, in run (RUN_TOP_*): its kind and
    its coverage, as ecol's float32 plane would hold it."""
    run[RUN_TOP_J] = j
    run[RUN_TOP_KIND] = kind
    run[RUN_TOP_COV] = np.float32(cov)


@ngjit_inline
def _settle_top(ecol, run):
    """Write the top pixel kept in run (_fill) to ecol as flagging it at once would
    have: its coverages kept and flagged (coverage.py), an edge surface's in E_COV,
    the centre's in E_COV0."""
    j = int(run[RUN_TOP_J])
    if j < 0:
        return
    x = ecol[E_SEEN, j]                 # 0 (TOP_EDGE), or the side (TOP_CENTRE)
    ecol[E_COV0, j] = run[RUN_TOP_COV] if run[RUN_TOP_KIND] == TOP_CENTRE else 0.0
    ecol[E_COV, j] = run[RUN_TOP_COV] if run[RUN_TOP_KIND] == TOP_EDGE else 0.0
    ecol[E_SEEN, j] = x + E_FLAG
    run[RUN_TOP_J] = -1.0


@ngjit_inline
def _hold_edge(ecol, run, j, nx, ny, nz, w, lam, z, side, u, v):
    """Hold row j's new edge surface (section 6.4: normal, w, intensity, depth, side,
    u, v)
    in ``run`` instead of writing it to ecol's planes, after writing out the one held
    before (_write_edge), unless that was row j's. Most edge surfaces are the top of a
    span, which the next span of the run goes on through the pixel's centre and sets
    the pixel's E_COV to 0 (_fill, after its ends): then they are never read. Written
    at once, each to a plane of its own, they cost 7 scattered stores a span (the
    column pass at 1920x1080 measured 2-6 % faster held). The edge planes are only
    written while the column is rendered, the finishing pass reads them."""
    if run[RUN_EDGE_J] != j:
        _write_edge(ecol, run)
    run[RUN_EDGE_J] = j
    run[RUN_EDGE] = nx
    run[RUN_EDGE + 1] = ny
    run[RUN_EDGE + 2] = nz
    run[RUN_EDGE + 3] = w
    run[RUN_EDGE + 4] = lam
    run[RUN_EDGE + 5] = z
    run[RUN_EDGE + 6] = side
    run[RUN_EDGE + 7] = u
    run[RUN_EDGE + 8] = v


@ngjit_inline
def _write_edge(ecol, run):
    """Write the edge surface that ``run`` holds (_hold_edge) to its row of ecol's
    planes where it is still there (E_COV > 0: an edge's coverage only goes back up
    from 0 with a new edge surface), and hold none."""
    j = int(run[RUN_EDGE_J])
    if j >= 0 and coverages(ecol, j)[1] > 0.0:
        _store_edge(ecol, j, run[RUN_EDGE], run[RUN_EDGE + 1], run[RUN_EDGE + 2],
                    run[RUN_EDGE + 3] - run[RUN_WO], run[RUN_EDGE + 4], run[RUN_EDGE + 5],
                    run[RUN_EDGE + 6], run[RUN_EDGE + 7] - run[RUN_CU],
                    run[RUN_EDGE + 8] - run[RUN_CV])
    run[RUN_EDGE_J] = -1.0


@ngjit_inline
def _store_edge(ecol, j, nx, ny, nz, w, lam, z, side, u, v):
    """Write row j's edge surface (normal, w, intensity, depth, side, u, v: from the
    view's centre, layout.py G_U) to ecol's planes."""
    ecol[E_NX, j] = nx
    ecol[E_NY, j] = ny
    ecol[E_NZ, j] = nz
    ecol[E_W, j] = w
    ecol[E_I, j] = lam
    ecol[E_DEPTH, j] = z
    ecol[E_SIDE, j] = side
    ecol[E_U, j] = u
    ecol[E_V, j] = v


@ngjit_inline
def _chord_weight(yq, yp, inv_dy, persp, qp, qc):
    """Weight of the current sample at screen row yq on the chord prev -> cur (inv_dy:
    1 / its rise in rows), perspective-correct in perspective."""
    ls = min(max((yq - yp) * inv_dy, 0.0), 1.0)
    if persp:
        return ls * qc / ((1.0 - ls) * qp + ls * qc)
    return ls


@ngjit_nrt_free
def _span(kind, f, fg, hf, hfp, vp, x0, prev, cur, gcol, ecol, run, sigma, persp, d3, H, aa,
          stk, sdepth, left, mid, xs):
    """_segment, but a height field's span is first cut where the column crosses the
    grid's cell edges: a bilinear surface's normal jumps there (a crease), so a sample
    on the edge keeps interpolation from mixing two patches, and a crease seen
    edge-on gets its top exactly. ``prev`` ends as the last sample used."""
    if kind != SURF_HEIGHTFIELD or vp[VP_DETECT] == 0.0:
        return _segment(kind, f, fg, hf, hfp, vp, x0, prev, cur, gcol, ecol, run, sigma,
                        persp, d3, H, aa, stk, sdepth, left, mid)
    au, bu, av, bv, iu, iv = _cell_path(hf, hfp, prev, cur)
    ta = prev[A_T]
    tb = cur[A_T]
    evals = 0
    for _ in range(HF_MAX_CROSSINGS):
        lu, lv, lam = _crossing(au, bu, av, bv, iu, iv)
        if not _inside_span(lam):
            break
        if lu <= lv:
            iu += 1.0 if bu > au else -1.0
        else:
            iv += 1.0 if bv > av else -1.0
        # (in perspective the ground path bends a little between samples, so the
        # sample lands near the edge, not on it: secant steps onto it measured no
        # better against the ray caster, for 12 % more samples)
        # (_sample_into's sample, inline here: a height field's most frequent one)
        st, ev = _sample_at(kind, f, fg, hf, hfp, vp, x0, ta + lam * (tb - ta), xs, run, False,
                            xs, np.int64(-1))
        evals += ev
        if st == S_OK:
            if _problem(vp, x0, prev, xs, run):
                evals += _segment(kind, f, fg, hf, hfp, vp, x0, prev, xs, gcol, ecol, run,
                                  sigma, persp, d3, H, aa, stk, sdepth, left, mid)
            else:
                _fill(gcol, ecol, run, prev, xs, sigma, persp, d3, H, aa)  # (_segment's)
            _copy(prev, xs)
    if _problem(vp, x0, prev, cur, run):
        evals += _segment(kind, f, fg, hf, hfp, vp, x0, prev, cur, gcol, ecol, run, sigma,
                          persp, d3, H, aa, stk, sdepth, left, mid)
    else:
        _fill(gcol, ecol, run, prev, cur, sigma, persp, d3, H, aa)
    return evals


@ngjit_inline
def _cuts_cells(kind, hf, hfp, vp, prev, cur):
    """Would _span cut the span prev -> cur at a cell edge of a height field (its
    first crossing's test, exactly)? A span inside one cell is drawn as a function's
    is, inline in the column's main loop (_span's call, and _segment's and
    _fill_span's under it, took most of a height field's time)."""
    if kind != SURF_HEIGHTFIELD or vp[VP_DETECT] == 0.0:
        return False
    return _crosses_cells(hf, hfp, prev[A_U], prev[A_V], cur[A_U], cur[A_V])


@ngjit_inline
def _crosses_cells(hf, hfp, pu, pv, cu, cv):
    """Does the span from (pu, pv) to (cu, cv) cross a cell edge strictly inside?"""
    return _inside_span(_crossing(*_cell_path_uv(hf, hfp, pu, pv, cu, cv))[2])


@ngjit_inline
def _hidden_cells(hf, hfp, vp, x0, pu, pv, pt, cu, cv, ct, run):
    """Does a height field over the cells around the span prev -> cur lie strictly
    inside the floating interval (up to HIDDEN_CELLS cells each way, the nodes'
    heights bounding each bilinear cell)? Then no point of the span shows: the samples
    at its cell edges and the corrections between them (all on the span's stretch of
    the column, _span) would paint nothing, and _span is passed over. Two thirds of a
    mesh's spans are hidden; their cuts were a third of its orthographic time.

    In perspective the points of Pi between the span's planes lie off the straight
    ground path between its ends (r grows with the height s, eq. 2): the box takes a
    cell more each way, and the points of Pi over the box's heights and the span's
    planes (a parallelogram of the ground, r and u, v linear in t and s) must lie in
    it; a row (eq. 10) is then largest and smallest at that rectangle's corners. The
    span runs from (pu, pv) on plane pt to (cu, cv) on plane ct."""
    nv, nu = hf.shape
    persp = vp[VP_ORTHO] == 0.0
    au, bu, av, bv, _, _ = _cell_path_uv(hf, hfp, pu, pv, cu, cv)
    m = 1 if persp else 0
    i0 = max(floor_index(min(au, bu)) - m, 0)
    i1 = min(floor_index(max(au, bu)) + m, nu - 2)
    j0 = max(floor_index(min(av, bv)) - m, 0)
    j1 = min(floor_index(max(av, bv)) + m, nv - 2)
    if not (i1 - i0 < HIDDEN_CELLS + 2 * m and j1 - j0 < HIDDEN_CELLS + 2 * m):
        return False
    w_lo = np.inf
    w_hi = -np.inf
    for j in range(j0, j1 + 2):
        for i in range(i0, i1 + 2):
            z = hf[j, i]
            w_lo = min(w_lo, z)
            w_hi = max(w_hi, z)
    if not (w_lo == w_lo and w_hi == w_hi and w_lo > -np.inf and w_hi < np.inf):
        return False                    # a hole (NaN) among them
    sa = vp[VP_SA]
    ca = vp[VP_CA]
    cw = vp[VP_CW]
    sc = vp[VP_SCALE]
    half = (vp[VP_H] - 1.0) * 0.5
    if not persp:
        # screen rows of the corners of [w_lo, w_hi] x [ta, tb] (ortho_point's, eq. 4):
        # the rows of every point of the span lie between them
        ya = (w_lo - cw) * ca * sc
        yb = (w_hi - cw) * ca * sc
        ta = -pt * sa * sc
        tb = -ct * sa * sc
        y_lo = min(ya, yb) + min(ta, tb) + half
        y_hi = max(ya, yb) + max(ta, tb) + half
    else:
        d1 = vp[VP_D1]
        d3 = vp[VP_D3]
        cb = vp[VP_CB]
        sb = vp[VP_SB]
        gu = (nu - 1) / (hfp[1] - hfp[0])
        gv = (nv - 1) / (hfp[3] - hfp[2])
        y_lo = np.inf
        y_hi = -np.inf
        for c in range(4):
            t = pt if c < 2 else ct
            s = (w_lo if c % 2 == 0 else w_hi) - cw
            r = x0 * (t * ca + d3) / d1 + x0 * sa / d1 * s    # eqs. (2), (9)
            gx = (vp[VP_CU] + r * cb + t * sb - hfp[0]) * gu
            gy = (vp[VP_CV] - r * sb + t * cb - hfp[2]) * gv
            if not (gx >= i0 and gx <= i1 + 1 and gy >= j0 and gy <= j1 + 1):
                return False
            e = s * sa + t * ca + d3
            if not e > d1:
                return False            # in front of the screen
            y = (s * ca - t * sa) * d1 / e * sc + half       # eq. (10)
            y_lo = min(y_lo, y)
            y_hi = max(y_hi, y)
    return y_lo > run[RUN_YMIN] + HIDDEN_MARGIN and y_hi < run[RUN_YMAX] - HIDDEN_MARGIN


@ngjit_inline
def _cell_path(hf, hfp, prev, cur):
    """The span prev -> cur in a height field's grid coordinates (au, bu along u, av,
    bv along v) and the first grid line it meets each way (iu, iv)."""
    return _cell_path_uv(hf, hfp, prev[A_U], prev[A_V], cur[A_U], cur[A_V])


@ngjit_inline
def _cell_path_uv(hf, hfp, pu, pv, cu, cv):
    """_cell_path of the span from (pu, pv) to (cu, cv)."""
    nv, nu = hf.shape
    au = (pu - hfp[0]) / (hfp[1] - hfp[0]) * (nu - 1)
    bu = (cu - hfp[0]) / (hfp[1] - hfp[0]) * (nu - 1)
    av = (pv - hfp[2]) / (hfp[3] - hfp[2]) * (nv - 1)
    bv = (cv - hfp[2]) / (hfp[3] - hfp[2]) * (nv - 1)
    iu = math.floor(au) + 1.0 if bu > au else math.ceil(au) - 1.0
    iv = math.floor(av) + 1.0 if bv > av else math.ceil(av) - 1.0
    return au, bu, av, bv, iu, iv


@ngjit_inline
def _crossing(au, bu, av, bv, iu, iv):
    """(lu, lv, lam): the fractions of the span (_cell_path's) where it meets grid lines
    iu and iv (2: never), and the nearer of them."""
    lu = (iu - au) / (bu - au) if bu != au else 2.0
    lv = (iv - av) / (bv - av) if bv != av else 2.0
    return lu, lv, min(lu, lv)


@ngjit_inline
def _inside_span(lam):
    """Is a crossing at fraction lam a cut (strictly inside the span)?"""
    return lam > 1e-9 and lam < 1.0 - 1e-9


@ngjit_inline
def _problem(vp, x0, prev, cur, run):
    """Does the span prev -> cur need a correction (App. A.2's Problem())?"""
    detect = int(vp[VP_DETECT])
    if detect == 0:
        return False
    fix_r = int(vp[VP_FIX_RIDGE]) if detect & DETECT_RIDGE else FIX_NONE
    fix_s = int(vp[VP_FIX_SHADE])
    return ((fix_r != FIX_NONE and ridge_between(vp, x0, prev, cur, run[RUN_YMIN], run[RUN_YMAX]))
            or (fix_s != FIX_NONE and shading_problem(vp, x0, prev, cur, detect, run[RUN_YMIN],
                                                      run[RUN_YMAX]))
            or ((detect & DETECT_WALL) != 0
                and wall_between(prev, cur, run[RUN_YMIN], run[RUN_YMAX], False, vp[VP_H])))


@ngjit_nrt_free
def _segment(kind, f, fg, hf, hfp, vp, x0, prev, cur, gcol, ecol, run, sigma, persp, d3, H, aa,
             stk, sdepth, left, mid):
    """Fill the span prev -> cur of an open run, correcting the problems that
    App. A.2's Problem() finds (Problem_Correction()): a ridge by the cubic spline's
    extremum taken as an extra sample (section 5.2), or by supersampling; an intensity
    jump or a bump by supersampling at VP_RATE times the frequency, or adaptively:
    halving the span while the problem persists, down to 1/VP_RATE of it. Returns the
    number of evaluations of f."""
    if not _problem(vp, x0, prev, cur, run):
        _fill_span(gcol, ecol, run, prev, cur, sigma, persp, d3, H, aa)     # the common case
        return 0
    detect = int(vp[VP_DETECT])
    fix_r = int(vp[VP_FIX_RIDGE]) if detect & DETECT_RIDGE else FIX_NONE
    fix_s = int(vp[VP_FIX_SHADE])
    walls = (detect & DETECT_WALL) != 0
    rate = max(int(vp[VP_RATE]), 2)
    max_depth = min(ceil_index(math.log2(rate) - 1e-9), STACK_SIZE - 2)
    evals = 0
    _copy(left, prev)
    _copy(stk[0], cur)
    sdepth[0] = 0
    n = 1
    w0 = stk[STACK_SIZE - 2]            # scratch: the wall's two ends
    w1 = stk[STACK_SIZE - 1]
    while n > 0:
        right = stk[n - 1]
        searching = sdepth[n - 1] >= WALL_MODE     # inside a wall's bisection
        d = sdepth[n - 1] - (WALL_MODE if searching else 0)
        if walls and wall_between(left, right, run[RUN_YMIN], run[RUN_YMAX], searching, H):
            # end of section 5: halve while the jump persists; then shade it as a wall
            halvings = d if searching else 0
            if halvings < WALL_DEPTH and n < STACK_SIZE - 2:
                tm = 0.5 * (left[A_T] + right[A_T])
                st, ev = _sample_into(kind, f, fg, hf, hfp, vp, x0, tm, mid, run)
                evals += ev
                if st == S_OK:
                    n = _push(stk, sdepth, n, mid, WALL_MODE + halvings + 1)
                    continue
                if persp and st == S_OUTSIDE:
                    # In perspective the jump's ends can lie on two pieces of the curve
                    # in Pi with none of it between them: here the plane in between
                    # meets the surface only outside the domain (the curve left it, or
                    # ended at a fold). (Not at a hole or in front of the screen: at a
                    # pole of tan(uv) that changed the sides of whole columns)
                    evals += _break_run(kind, f, fg, hf, hfp, vp, x0, left, right, tm, st,
                                        gcol, ecol, run, sigma, d3, H, aa, w0, w1)
                    _copy(left, right)
                    n -= 1
                    continue
            else:
                m_jump, real = wall_jump(kind, f, hf, hfp, left, right)
                if not real:
                    # (only where the fold tracer can draw what lies between: without
                    # it a new run's first span takes a side from its direction alone,
                    # and the lerp below had the side of a fold's hidden branch right)
                    joined, ev = _joined(kind, f, hf, hfp, vp, x0, left, right) \
                        if persp and vp[VP_FOLD] != 0.0 else (True, 0)
                    evals += ev
                    if not joined:
                        # two pieces of the curve on both sides of the tight bracket: a
                        # new run from the second, and the column to the fold tracer
                        _new_run(gcol, ecol, run, left, right, sigma, d3, H, aa)
                    else:               # a fold seen edge-on: its own normals
                        _fill_span(gcol, ecol, run, left, right, sigma, persp, d3, H, aa)
                    _copy(left, right)
                    n -= 1
                    continue
                nx, ny, nz = wall_normal(kind, f, hf, hfp, vp, left, right, m_jump)
                lam = lambert_at(vp, x0, left, nx, ny, nz)
                _copy(w0, left)
                _copy(w1, right)
                _set_normal(w0, nx, ny, nz, lam)
                _set_normal(w1, nx, ny, nz, lam)
                _fill_span(gcol, ecol, run, w0, w1, sigma, persp, d3, H, aa)
                _copy(left, right)
                n -= 1
                # the wall's far end may sit on the jump, where difference quotients
                # give f_u, f_v no meaning: take the normal a little beyond it
                st, ev = _sample_into(kind, f, fg, hf, hfp, vp, x0,
                                      right[A_T] + WALL_BEYOND * (right[A_T] - w0[A_T]), mid,
                                      run)
                evals += ev
                if st == S_OK:
                    _set_normal(left, mid[A_NX], mid[A_NY], mid[A_NZ], mid[A_I])
                continue
        fix = FIX_NONE
        if fix_r != FIX_NONE and ridge_between(vp, x0, left, right, run[RUN_YMIN], run[RUN_YMAX]):
            fix = fix_r
            if fix == FIX_SPLINE and d > 0:
                fix = FIX_NONE          # one spline per span; its own iteration refines it
        if fix == FIX_NONE and fix_s != FIX_NONE and \
                shading_problem(vp, x0, left, right, detect, run[RUN_YMIN], run[RUN_YMAX]):
            fix = fix_s
        if fix == FIX_SPLINE or (fix == FIX_ADAPTIVE and d < max_depth):
            # one more sample inside the span: the spline's top, or the middle
            if fix == FIX_SPLINE:
                st, ev = _spline_top(kind, f, fg, hf, hfp, vp, x0, left, right, mid, run)
            else:
                st, ev = _sample_into(kind, f, fg, hf, hfp, vp, x0,
                                      0.5 * (left[A_T] + right[A_T]), mid, run)
            evals += ev
            if st == S_OK:
                n = _push(stk, sdepth, n, mid, d + 1)
                continue
        elif fix == FIX_SUPER:
            ta = left[A_T]
            h = (right[A_T] - ta) / rate
            for k in range(1, rate):
                st, ev = _sample_into(kind, f, fg, hf, hfp, vp, x0, ta + k * h, mid, run)
                evals += ev
                if st == S_OK:
                    _fill_span(gcol, ecol, run, left, mid, sigma, persp, d3, H, aa)
                    _copy(left, mid)
        _fill_span(gcol, ecol, run, left, right, sigma, persp, d3, H, aa)
        _copy(left, right)
        n -= 1
    return evals


@ngjit_nrt_free
def _joined(kind, f, hf, hfp, vp, x0, a, b):
    """Does the curve in Pi run from perspective sample a to b (a wall's tight bracket,
    its rows far apart, f continuous) inside their planes' narrow strip? Then it
    crosses the strip at every height between them, and G = f - cw - s has opposite
    signs at the middle height on the strip's two sides; on two pieces of the curve
    (the sample's Newton iteration went over to another one: the first ended at a fold
    between the planes, or both run on) the same sign. Returns (joined, evaluations);
    joined where a point lies outside the domain or at a hole (no sign to tell)."""
    s_m = 0.5 * (a[A_W] + b[A_W]) - vp[VP_CW]
    k = x0 * vp[VP_SA] / vp[VP_D1]
    evals = 0
    sg = 0.0
    for q in range(2):
        t = a[A_T] if q == 0 else b[A_T]
        r0 = x0 * (t * vp[VP_CA] + vp[VP_D3]) / vp[VP_D1]          # eq. (9)
        u, v = _line_uv(vp, r0, k, t, s_m)
        if not in_domain(vp, u, v):
            return True, evals
        g, ev = _g_at(kind, f, hf, hfp, vp, r0, k, t, s_m)
        evals += ev
        if not math.isfinite(g):
            return True, evals
        if q == 0:
            sg = g
        elif (g >= 0.0) == (sg >= 0.0):
            return False, evals
    return True, evals


@ngjit_inline
def _new_run(gcol, ecol, run, a, b, sigma, d3, H, aa):
    """End the run at perspective sample a and start a new one at b (where the curve
    from a does not reach b), and mark the column for the fold tracer."""
    run[RUN_OPEN] = 0.0
    # (persp a bool, not the literal True: _fill_span and what it calls compile once
    # for every caller, 3 s less of a first picture)
    _fill_span(gcol, ecol, run, a, b, sigma, np.bool_(True), d3, H, aa)     # (opens it at b)
    run[RUN_FOLD] = 1.0


@ngjit_nrt_free
def _break_run(kind, f, fg, hf, hfp, vp, x0, a, b, tm, st_m, gcol, ecol, run, sigma, d3, H,
               aa, tmp, edge):
    """Perspective samples a and b of one run, and plane tm between them whose sample
    lies outside the domain (status st_m): the run ends at its edge after a and a new
    one starts at its edge before b, both bisected as the column pass bisects a run's
    edges (_run_edge), and painted from a and to b. Returns the evaluations of f."""
    persp = np.bool_(True)              # (as _new_run's)
    found, evals = _run_edge(kind, f, fg, hf, hfp, vp, x0, a[A_T], tm, st_m, tmp, edge, run)
    if found:
        _fill_span(gcol, ecol, run, a, edge, sigma, persp, d3, H, aa)
    run[RUN_OPEN] = 0.0
    found, ev = _run_edge(kind, f, fg, hf, hfp, vp, x0, b[A_T], tm, st_m, tmp, edge, run)
    evals += ev
    start = edge if found else b
    _fill_span(gcol, ecol, run, start, start, sigma, persp, d3, H, aa)    # (opens the run)
    if found:
        _fill_span(gcol, ecol, run, edge, b, sigma, persp, d3, H, aa)
    return evals


@ngjit_inline
def _set_normal(a, nx, ny, nz, lam):
    """Give sample ``a`` the normal (nx, ny, nz) and the intensity lam."""
    a[A_NX] = nx
    a[A_NY] = ny
    a[A_NZ] = nz
    a[A_I] = lam


@ngjit_nrt_free
def _push(stk, sdepth, n, mid, depth):
    """Split the span (left, stk[n-1]) at sample ``mid``: both halves get ``depth``."""
    _copy(stk[n], mid)
    sdepth[n] = depth
    sdepth[n - 1] = depth
    return n + 1


@ngjit_nrt_free
def _spline_top(kind, f, fg, hf, hfp, vp, x0, a, b, out, run):
    """Sample the surface at the extremum of the cubic spline between samples a and b
    (eqs. 13-22, see correct.py); with VP_SPLINE_TOL > 0, repeat on the half that
    still holds the sign change while |V.N| there exceeds the tolerance (end of
    section 5.2). Returns (status, evaluations); the sample is left in ``out``."""
    ta = a[A_T]
    tb = b[A_T]
    ya = a[A_Y]
    yb = b[A_Y]
    vna = a[A_VN]
    ma = a[A_SLOPE]
    mb = b[A_SLOPE]
    tol = vp[VP_SPLINE_TOL]
    iters = SPLINE_MAX_ITERS if tol > 0.0 else 1
    evals = 0
    st = S_OUTSIDE
    for _ in range(iters):
        tau, _ = hermite_extremum(ya, yb, ma, mb, tb - ta)
        t2 = ta + tau * (tb - ta)
        st, ev = _sample_into(kind, f, fg, hf, hfp, vp, x0, t2, out, run)
        evals += ev
        if st != S_OK:
            break
        vn2 = out[A_VN]
        m2 = out[A_SLOPE]
        if tol <= 0.0 or abs(vn2) <= tol:
            break
        if vn2 * vna > 0.0:
            ta = t2
            ya = out[A_Y]
            ma = m2
        else:
            tb = t2
            yb = out[A_Y]
            mb = m2
    return st, evals


@ngjit_nrt_free
def _grid_range(t0, dt, ta, tb):
    """Indices k of the planes t0 + k dt strictly between ta < tb."""
    eps = 1e-6 * dt
    ka = floor_index((ta - t0) / dt) + 1
    if t0 + ka * dt <= ta + eps:
        ka += 1
    kb = ceil_index((tb - t0) / dt) - 1
    if t0 + kb * dt >= tb - eps:
        kb -= 1
    return ka, kb


@ngjit_inline
def _pass_plane(i, n, ta, tb, t0, ka, kb, dt, sigma):
    """(t, k) of a uniform pass's plane number i of n: ta, the grid's planes t0 + k dt
    (from k = ka up when sigma > 0, from kb down when not), tb; k = -1 at the ends."""
    if i == 0:
        return ta, -1
    if i == n - 1:
        return tb, -1
    k = ka + (i - 1) if sigma > 0 else kb - (i - 1)
    return t0 + k * dt, k


@ngjit_nrt_free
def _batch_planes(kind, fg, fb, hf, hfp, vp, x0, bat, i_lo, i_hi, n, ta, tb, t0, ka, dt):
    """Sample an orthographic column's planes i_lo to i_hi - 1 ahead into bat, BATCH
    values per attribute (BAT_*): f, f_u, f_v with one call of the batch evaluator fb
    (SIMD code), then each point's status, screen row and depth, unit normal and
    intensity (sample.ortho_point), in loops whose iterations do not wait on one
    another. fb writes the m = i_hi - i_lo values of f, f_u, f_v to bat from
    BAT_W * BATCH on, m apart; a point where any of them is not finite is evaluated
    again by fg, which alone decides a hole (vmath's functions give NaN where they
    cannot answer)."""
    m = i_hi - i_lo
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    u0 = vp[VP_CU] + x0 * cb            # eq. (3), as sample_point computes it
    v0 = vp[VP_CV] - x0 * sb
    vt = array_as_tuple(vp, VP_SIZE)    # (in registers: the loops below become SIMD code)
    for k in range(m):
        t = _pass_plane(i_lo + k, n, ta, tb, t0, ka, 0, dt, 1.0)[0]
        u = u0 + t * sb
        v = v0 + t * cb
        bat[BAT_U * BATCH + k] = u
        bat[BAT_V * BATCH + k] = v
    o = BAT_W * BATCH
    if kind == SURF_HEIGHTFIELD:
        # a height field's bilinear cells, read as sample_point reads them (no batch
        # evaluator: the grid is the kernel's own argument)
        for k in range(m):
            bat[o + k], bat[o + m + k], bat[o + 2 * m + k] = heightfield_eval(
                hf, hfp, bat[BAT_U * BATCH + k], bat[BAT_V * BATCH + k])
    else:
        iu = hfp[HFP_IU]
        iv = hfp[HFP_IV]
        c = hfp[HFP_CW]
        boxed = iu != 1.0 or iv != 1.0 or c != 1.0       # (surface_eval's scaling)
        pu = BAT_U * BATCH
        pv = BAT_V * BATCH
        if boxed:
            for k in range(m):
                bat[BAT_US * BATCH + k] = bat[pu + k] * iu
                bat[BAT_VS * BATCH + k] = bat[pv + k] * iv
            pu = BAT_US * BATCH
            pv = BAT_VS * BATCH
        fb(array_ptr(bat, pu), array_ptr(bat, pv), hfp[0], array_ptr(bat, o), m)
        if boxed:
            for k in range(m):
                bat[o + k] *= c
                bat[o + m + k] *= c * iu
                bat[o + 2 * m + k] *= c * iv
    for k in range(m):
        u = bat[BAT_U * BATCH + k]
        v = bat[BAT_V * BATCH + k]
        ui, vi = into_domain(vt, u, v)
        # a point on the domain's edge: f at it moved inside (as sample_point does)
        edge = (ui != u or vi != v) and in_domain(vt, u, v)
        if edge or not (math.isfinite(bat[o + k]) and math.isfinite(bat[o + m + k])
                        and math.isfinite(bat[o + 2 * m + k])):
            if edge:
                bat[BAT_U * BATCH + k] = ui
                bat[BAT_V * BATCH + k] = vi
            bat[o + k], bat[o + m + k], bat[o + 2 * m + k] = surface_eval(
                kind, fg, hf, hfp, bat[BAT_U * BATCH + k], bat[BAT_V * BATCH + k])
    detect = vt[VP_DETECT] != 0.0
    for k in range(m):
        t = _pass_plane(i_lo + k, n, ta, tb, t0, ka, 0, dt, 1.0)[0]
        if in_domain(vt, bat[BAT_U * BATCH + k], bat[BAT_V * BATCH + k]):
            st, y, z, nx, ny, nz, lam = ortho_point(vt, t, bat[o + k], bat[o + m + k],
                                                    bat[o + 2 * m + k])
        else:
            st, y, z, nx, ny, nz, lam = S_OUTSIDE, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
        bat[BAT_ST * BATCH + k] = st
        bat[BAT_Y * BATCH + k] = y
        bat[BAT_Z * BATCH + k] = z
        bat[BAT_NX * BATCH + k] = nx
        bat[BAT_NY * BATCH + k] = ny
        bat[BAT_NZ * BATCH + k] = nz
        bat[BAT_I * BATCH + k] = lam
        if detect:
            # probe()'s values here, in SIMD code (its division was the column loop's
            # slowest instruction, the loop waiting on it sample after sample)
            bat[BAT_VN * BATCH + k], bat[BAT_BUMP * BATCH + k], bat[BAT_SLOPE * BATCH + k] = \
                probe_ortho(vt, ny, nz)


@ngjit_nrt_free
def _batch_planes_persp(kind, f, fg, fb, hf, hfp, vp, x0, bat, i_lo, i_hi, n, ta, tb, t0, ka,
                        kb, dt, sigma, run, sg, rot):
    """Sample a perspective column's planes i_lo to i_hi - 1 ahead into bat, as
    _batch_planes does in orthographic: Newton's iteration on each plane's line inside
    Pi (sample_point's, eqs. 2, 9) run for all the planes at once, f, f_u, f_v of all
    of them from one call of the batch evaluator fb (SIMD code) a step, until every
    plane has converged or BATCH_NEWTON steps (a plane that has converged keeps its s,
    and so its values). Each plane starts from the previous columns' solutions on it
    (_guess: the line through the last two columns', or the last column's; the
    columns of a group of tiles run one after another on one thread), else from the
    run's line (_newton_start), else at Gordon's point s = 0. A plane that converges to
    a plain point (finite, strictly inside the domain, outside the known holes, behind
    the screen) gets its sample (_batch_points: status, row, depth, the solution BAT_S; its
    normal, intensity and probe()'s values when it is used, _finish_batched). A plane
    whose root lies outside the domain is S_OUTSIDE where g = f - cw - s has no sign
    change over the part of its line inside the domain (the scalar path's test:
    sample._root_inside), as it is where the domain test is sure; the others are
    S_RETRY, for the scalar path. Returns the evaluations of f."""
    m = i_hi - i_lo
    ca = vp[VP_CA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    cu = vp[VP_CU]
    cv = vp[VP_CV]
    cw = vp[VP_CW]
    d1 = vp[VP_D1]
    d3 = vp[VP_D3]
    scale = vp[VP_SCALE]
    kp = x0 * vp[VP_SA] / d1                  # dr/ds inside Pi
    iu = hfp[HFP_IU]
    iv = hfp[HFP_IV]
    c = hfp[HFP_CW]
    o = BAT_W * BATCH
    na = 0
    for j in range(m):
        t, kg = _pass_plane(i_lo + j, n, ta, tb, t0, ka, kb, dt, sigma)
        bat[BAT_T * BATCH + j] = t
        bat[BAT_PT * BATCH + j] = 0.0
        bat[BAT_LAZY * BATCH + j] = 0.0
        bat[BAT_R0 * BATCH + j] = x0 * (t * ca + d3) / d1      # eq. (9)
        s = 0.0
        if _domain_test(vp, x0, t) == 0:
            bat[BAT_ST * BATCH + j] = S_OUTSIDE
            bat[BAT_ACT * BATCH + j] = 0.0
        else:
            bat[BAT_ST * BATCH + j] = S_RETRY
            bat[BAT_ACT * BATCH + j] = 1.0
            na += 1
            s = _guess(sg, rot, kg)
            if not math.isfinite(s):
                lin, quad = _newton_start(run, t)
                s = lin if math.isfinite(lin) else 0.0
        bat[BAT_SI * BATCH + j] = s
    for j in range(m, BATCH):                   # (evaluated, never used)
        bat[BAT_T * BATCH + j] = 0.0
        bat[BAT_R0 * BATCH + j] = 0.0
        bat[BAT_SI * BATCH + j] = 0.0
        bat[BAT_ACT * BATCH + j] = 0.0
    evals = 0
    if na == 0:
        return evals
    # The iterations run over all BATCH planes (fb's values BATCH apart: every row of
    # bat at a fixed offset, so that LLVM compiles both loops to SIMD code); a plane
    # that has converged keeps its s, and fb's last values are its own.
    for _ in range(BATCH_NEWTON):
        for j in range(BATCH):
            t = bat[BAT_T * BATCH + j]
            r = bat[BAT_R0 * BATCH + j] + kp * bat[BAT_SI * BATCH + j]
            u = cu + r * cb + t * sb                            # eq. (2)
            v = cv - r * sb + t * cb
            bat[BAT_U * BATCH + j] = u
            bat[BAT_V * BATCH + j] = v
            bat[BAT_US * BATCH + j] = u * iu
            bat[BAT_VS * BATCH + j] = v * iv
        fb(array_ptr(bat, BAT_US * BATCH), array_ptr(bat, BAT_VS * BATCH), hfp[0],
           array_ptr(bat, o), BATCH)
        evals += m
        left = 0
        for j in range(BATCH):
            # (branch-free) a plane still iterating (BAT_ACT 1) that converges is done
            # (2); one whose values or step are not finite stops (0: S_RETRY)
            w = bat[o + j] * c
            wu = bat[o + BATCH + j] * (c * iu)
            wv = bat[o + 2 * BATCH + j] * (c * iv)
            s = bat[BAT_SI * BATCH + j]
            g = (w - cw) - s
            dg = kp * (wu * cb - wv * sb) - 1.0
            s_next = s - g / dg
            act = bat[BAT_ACT * BATCH + j] == 1.0
            fin = math.isfinite(w) & math.isfinite(wu) & math.isfinite(wv)
            conv = (abs(kp * g) * scale <= BATCH_TOL_PX) | (kp == 0.0)
            done = act & fin & conv
            go = act & fin & (not conv) & math.isfinite(s_next)
            bat[BAT_SI * BATCH + j] = s_next if go else s
            bat[BAT_ACT * BATCH + j] = 1.0 if go else (2.0 if done else (
                bat[BAT_ACT * BATCH + j] if not act else 0.0))
            left += 1 if go else 0
        if left == 0:
            break
    # (u, v): where f was evaluated last, at the plane's final s
    _batch_points(vp, x0, bat, c, iu, iv)
    holes = vp[VP_HOLE_N] != 0.0
    for j in range(m):
        if bat[BAT_ACT * BATCH + j] == 3.0:
            evals += _outside_test(kind, f, hf, hfp, vp, bat, j, kp)
        elif holes and bat[BAT_ST * BATCH + j] == S_OK and \
                in_known_hole(vp, bat[BAT_U * BATCH + j], bat[BAT_V * BATCH + j]):
            bat[BAT_ST * BATCH + j] = S_RETRY      # (the scalar path's, at a known hole)
            bat[BAT_LAZY * BATCH + j] = 0.0
    return evals


@ngjit_inline
def _batch_points(vp, x0, bat, c, iu, iv):
    """The batched perspective planes' converged points (u, v, w) in one branch-free
    loop over the BATCH planes (LLVM's SIMD code; a scalar call per plane was about a
    tenth of the column pass): a converged plane (BAT_ACT 2) whose point is a plain
    one (finite, strictly inside the domain, behind the screen) gets its sample, as
    sample_point computes it (status, screen row, depth, the solution BAT_S, w, and
    with VP_DETECT the sign of V.N, for the hidden samples' ridge test); the rest when
    the sample is used (_finish_batched). A converged plane whose point lies outside
    the domain gets BAT_ACT 3 (for _outside_test); the rest stay S_RETRY (and the
    caller sends a point in a known hole back to them)."""
    eu = DOMAIN_EPS * (vp[VP_UB] - vp[VP_UA])     # (in_domain, into_domain)
    ev = DOMAIN_EPS * (vp[VP_VB] - vp[VP_VA])
    u_lo = vp[VP_UA] - eu
    u_hi = vp[VP_UB] + eu
    v_lo = vp[VP_VA] - ev
    v_hi = vp[VP_VB] + ev
    u_in0 = vp[VP_UA] + eu
    u_in1 = vp[VP_UB] - eu
    v_in0 = vp[VP_VA] + ev
    v_in1 = vp[VP_VB] - ev
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    cw = vp[VP_CW]
    d1 = vp[VP_D1]
    d3 = vp[VP_D3]
    scale = vp[VP_SCALE]
    mid = (vp[VP_H] - 1.0) * 0.5
    detect = vp[VP_DETECT] != 0.0
    cu_ = c * iu
    cv_ = c * iv
    for j in range(BATCH):
        conv = bat[BAT_ACT * BATCH + j] == 2.0
        u = bat[BAT_U * BATCH + j]
        v = bat[BAT_V * BATCH + j]
        inside = (u >= u_lo) & (u <= u_hi) & (v >= v_lo) & (v <= v_hi)
        plain = (u >= u_in0) & (u <= u_in1) & (v >= v_in0) & (v <= v_in1)
        t = bat[BAT_T * BATCH + j]
        w = bat[BAT_W * BATCH + j] * c              # fb's last values (the box's scaling)
        s = w - cw
        y1 = s * ca - t * sa                         # eqs. (4), (10)
        z1 = s * sa + t * ca
        front = not (z1 + d3 <= d1)
        y0 = y1 * d1 / (z1 + d3)
        ypix = y0 * scale + mid
        ok = conv & inside & plain & front & math.isfinite(ypix) & math.isfinite(z1)
        # the normal (eq. 11) not yet of unit length: fold_test's and the ridge test's
        # signs do not need it
        wu = bat[(BAT_W + 1) * BATCH + j] * cu_
        wv = bat[(BAT_W + 2) * BATCH + j] * cv_
        nx = -wu * cb + wv * sb
        ny = wu * sa * sb + ca + wv * sa * cb
        nz = -wu * ca * sb + sa - wv * ca * cb
        bat[BAT_ST * BATCH + j] = S_OK if ok else bat[BAT_ST * BATCH + j]
        bat[BAT_S * BATCH + j] = s if ok else bat[BAT_S * BATCH + j]
        bat[BAT_W * BATCH + j] = w if ok else bat[BAT_W * BATCH + j]
        bat[BAT_Y * BATCH + j] = ypix if ok else bat[BAT_Y * BATCH + j]
        bat[BAT_Z * BATCH + j] = z1 if ok else bat[BAT_Z * BATCH + j]
        bat[BAT_LAZY * BATCH + j] = 1.0 if ok else bat[BAT_LAZY * BATCH + j]
        bat[BAT_NX * BATCH + j] = nx if ok else bat[BAT_NX * BATCH + j]
        bat[BAT_NY * BATCH + j] = ny if ok else bat[BAT_NY * BATCH + j]
        bat[BAT_NZ * BATCH + j] = nz if ok else bat[BAT_NZ * BATCH + j]
        if detect:
            yv = (ypix - mid) / scale                # (probe_persp's V)
            vn = -x0 * nx - yv * ny - d1 * nz
            bat[BAT_VN * BATCH + j] = vn if ok else bat[BAT_VN * BATCH + j]
        bat[BAT_ACT * BATCH + j] = 3.0 if conv & (not inside) else bat[BAT_ACT * BATCH + j]


@ngjit_inline
def _finish_batched(vp, x0, bat, j):
    """The rest of batched perspective sample j, where it is used: its unit normal,
    intensity (eq. 12) and probe()'s values, as sample_point and probe compute them."""
    if bat[BAT_LAZY * BATCH + j] == 0.0:
        return
    bat[BAT_LAZY * BATCH + j] = 0.0
    nx = bat[BAT_NX * BATCH + j]
    ny = bat[BAT_NY * BATCH + j]
    nz = bat[BAT_NZ * BATCH + j]
    q = 1.0 / math.sqrt(nx * nx + ny * ny + nz * nz)         # (unit_normal)
    nx *= q
    ny *= q
    nz *= q
    u = bat[BAT_U * BATCH + j]
    v = bat[BAT_V * BATCH + j]
    t = bat[BAT_T * BATCH + j]
    s = bat[BAT_S * BATCH + j]
    z1 = bat[BAT_Z * BATCH + j]
    r = (u - vp[VP_CU]) * vp[VP_CB] - (v - vp[VP_CV]) * vp[VP_SB]
    y1 = s * vp[VP_CA] - t * vp[VP_SA]
    bat[BAT_NX * BATCH + j] = nx
    bat[BAT_NY * BATCH + j] = ny
    bat[BAT_NZ * BATCH + j] = nz
    bat[BAT_I * BATCH + j] = lambert(vp, -r, -y1, -(vp[VP_D3] + z1), nx, ny, nz)
    if vp[VP_DETECT] != 0.0:
        bat[BAT_VN * BATCH + j], bat[BAT_BUMP * BATCH + j], bat[BAT_SLOPE * BATCH + j] = \
            probe_persp(vp, x0, bat[BAT_Y * BATCH + j], z1, nx, ny, nz)


@ngjit_nrt_free
def _outside_test(kind, f, hf, hfp, vp, bat, j, kp):
    """Batched perspective plane j, whose root lies outside the domain: S_OUTSIDE
    where g has no sign change between the ends of its line's part inside the domain
    (and the scan range), as sample._root_inside decides; else it stays S_RETRY (a
    root inside: the scalar path finds it). Returns the evaluations of f."""
    t = bat[BAT_T * BATCH + j]
    ra, rb = _r_interval(vp, t)
    if ra > rb or kp == 0.0:
        bat[BAT_ST * BATCH + j] = S_OUTSIDE
        return 0
    a, b, ga, gb, evals = bracket_ends(kind, f, hf, hfp, vp, bat[BAT_R0 * BATCH + j], kp, t,
                                       ra, rb)
    if not a < b:
        bat[BAT_ST * BATCH + j] = S_OUTSIDE
        return 0
    if math.isfinite(ga) and math.isfinite(gb) and (ga >= 0.0) == (gb >= 0.0):
        bat[BAT_ST * BATCH + j] = S_OUTSIDE
        bat[BAT_PT * BATCH + j] = 1.0
    return evals


@ngjit_inline
def _batch_taken(vp, x0, run, bat, kb, t):
    """Whether batched perspective sample kb (plane t) is the one the scalar path would
    find: its solution within BATCH_ACCEPT_PX of that path's Newton start."""
    lin, quad = _newton_start(run, t)
    guess = quad if quad == quad else lin
    if not math.isfinite(guess):
        return True
    return abs(x0 * vp[VP_SA] / vp[VP_D1] * (bat[BAT_S * BATCH + kb] - guess)) * vp[VP_SCALE] \
        <= BATCH_ACCEPT_PX


@ngjit_inline
def _prev_from_batch(vp, x0, prev, bat, kb, t, detect):
    """Write batched sample kb (plane t) into ``prev`` as _sample_at writes it."""
    if vp[VP_ORTHO] == 0.0:
        _finish_batched(vp, x0, bat, kb)
    prev[A_Y] = bat[BAT_Y * BATCH + kb]
    prev[A_Z] = bat[BAT_Z * BATCH + kb]
    prev[A_U] = bat[BAT_U * BATCH + kb]
    prev[A_V] = bat[BAT_V * BATCH + kb]
    prev[A_W] = bat[BAT_W * BATCH + kb]
    prev[A_NX] = bat[BAT_NX * BATCH + kb]
    prev[A_NY] = bat[BAT_NY * BATCH + kb]
    prev[A_NZ] = bat[BAT_NZ * BATCH + kb]
    prev[A_I] = bat[BAT_I * BATCH + kb]
    prev[A_T] = t
    if detect:
        prev[A_VN] = bat[BAT_VN * BATCH + kb]
        prev[A_BUMP] = bat[BAT_BUMP * BATCH + kb]
        prev[A_SLOPE] = bat[BAT_SLOPE * BATCH + kb]


@ngjit_nrt_free
def _column_pass(kind, f, fg, fb, hf, hfp, vp, x0, ta, tb, sigma, gcol, ecol, hrec, hstride,
                 prev, cur, edge, tmp, run, stk, sdepth, left, mid, bat, sg, rot):
    """One front-to-back pass over t from ta to tb (sigma = +1 ascending, -1
    descending). Returns the number of evaluations of f. The planes are evaluated
    BATCH at a time into bat (_batch_planes, _batch_planes_persp) where vp's VP_BATCH
    says so; in perspective sg holds the solutions s of the tile's last columns by
    the grid's plane number, where this column's are written."""
    H = gcol.shape[0]
    persp = vp[VP_ORTHO] == 0.0
    aa = vp[VP_AA] != 0.0
    d3 = vp[VP_D3]
    t0 = vp[VP_T0]
    dt = vp[VP_DT]
    lo = min(ta, tb)
    hi = max(ta, tb)
    ka, kb = _grid_range(t0, dt, lo, hi)
    n_inner = max(kb - ka + 1, 0)
    n = n_inner + 2 if hi > lo else 1
    evals = 0
    run[RUN_OPEN] = 0.0
    run_start = 0.0
    prev_st = -1
    prev_t = 0.0
    # section 6.3: locally adaptive planes (not for line drawings, whose lines are
    # every hstride-th plane of the grid)
    adaptive = vp[VP_ADAPT] != 0.0 and hstride == 0 and hi > lo
    q_near = vp[VP_QNEAR]
    coarse = 1.0
    i = 0
    t = ta
    k = -1
    i_end = n
    if persp and not adaptive and hi > lo and vp[VP_CLIP] != 0.0:
        i, i_end = _pass_planes(vp, x0, sigma, n, ka, kb, t0, dt)
        if i >= i_end:
            return 0                    # the column meets nothing
        t, k = _pass_plane(i, n, ta, tb, t0, ka, kb, dt, sigma)
    # the planes evaluated ahead, BATCH at a time: planes b_lo to b_hi - 1
    batched = (vp[VP_BATCH] != 0.0 and not adaptive and (persp or sigma > 0.0)
               and (kind != SURF_HEIGHTFIELD or not persp) and hi > lo)
    b_lo = 0
    b_hi = 0
    # perspective: the failed sample before (where its point lies), and a plane put
    # in between two failed samples, after which the pass resumes at t_resume
    bad_u = 0.0
    bad_v = 0.0
    bad_valid = False
    resume = False
    t_resume = 0.0
    k_resume = -1
    # A batched plane whose sample is hidden (strictly inside the floating interval,
    # the run open since the plane before, and no ridge test it could fail) changes
    # nothing but which sample is the previous one: that stays in the batch (number
    # prev_kb) until a plane that does something needs it in ``prev``
    # (_prev_from_batch). Two thirds of the default picture's samples are hidden.
    # (a height field's, orthographic, where its span is not cut at a cell edge or
    # surely lies inside the interval, _hidden_cells)
    hidden_ok = batched and hstride == 0 and (kind != SURF_HEIGHTFIELD or (
        not persp and vp[VP_PASS_HIDDEN] != 0.0))
    detect = vp[VP_DETECT] != 0.0
    prev_kb = -1
    while True:
        kb_i = -1
        if batched and not resume:
            if i >= b_hi:
                if prev_kb >= 0:
                    _prev_from_batch(vp, x0, prev, bat, prev_kb, prev_t, detect)
                    prev_kb = -1
                b_lo = i
                b_hi = min(i_end, i + BATCH)
                if persp:
                    evals += _batch_planes_persp(kind, f, fg, fb, hf, hfp, vp, x0, bat, b_lo,
                                                 b_hi, n, ta, tb, t0, ka, kb, dt, sigma, run, sg,
                                                 rot)
                else:
                    _batch_planes(kind, fg, fb, hf, hfp, vp, x0, bat, b_lo, b_hi, n, ta, tb, t0,
                                  ka, dt)
            kb_i = i - b_lo
            st_b = bat[BAT_ST * BATCH + kb_i]
            if persp and (st_b == S_RETRY or (st_b == S_OK
                                               and not _batch_taken(vp, x0, run, bat, kb_i, t))):
                kb_i = -1                    # the scalar path's sample instead
                st_b = S_RETRY
            if hidden_ok and prev_st == S_OK and run[RUN_OPEN] != 0.0 and st_b == S_OK:
                y = bat[BAT_Y * BATCH + kb_i]
                hidden = run[RUN_YMIN] < y < run[RUN_YMAX]
                if hidden and detect:
                    vn_prev = bat[BAT_VN * BATCH + prev_kb] if prev_kb >= 0 else prev[A_VN]
                    hidden = not vn_prev * bat[BAT_VN * BATCH + kb_i] < 0.0
                if hidden and kind == SURF_HEIGHTFIELD and detect:
                    # the span from the previous sample, cut at a cell edge (_span)
                    # unless it surely lies inside the interval
                    if prev_kb >= 0:
                        pu = bat[BAT_U * BATCH + prev_kb]
                        pv = bat[BAT_V * BATCH + prev_kb]
                    else:
                        pu = prev[A_U]
                        pv = prev[A_V]
                    cu = bat[BAT_U * BATCH + kb_i]
                    cv = bat[BAT_V * BATCH + kb_i]
                    hidden = not _crosses_cells(hf, hfp, pu, pv, cu, cv) or \
                        _hidden_cells(hf, hfp, vp, x0, pu, pv, prev_t, cu, cv, t, run)
                if hidden:
                    if persp:
                        # what _sample_at does with a perspective sample
                        s_b = bat[BAT_S * BATCH + kb_i]
                        _keep_solution(run, s_b, t, True)
                        if vp[VP_FOLD] != 0.0 and fold_test(vp, x0, bat[BAT_NX * BATCH + kb_i],
                                                            bat[BAT_NY * BATCH + kb_i],
                                                            bat[BAT_NZ * BATCH + kb_i], 0.0):
                            run[RUN_FOLD] = 1.0
                        _keep_guess(sg, rot, k, s_b)
                    else:
                        evals += 1
                    prev_kb = kb_i
                    prev_t = t
                    i += 1                   # the next plane, as below
                    if i >= i_end:
                        break
                    t, k = _pass_plane(i, n, ta, tb, t0, ka, kb, dt, sigma)
                    continue
            if prev_kb >= 0:
                _prev_from_batch(vp, x0, prev, bat, prev_kb, prev_t, detect)
                prev_kb = -1
            st, ev = _sample_at(kind, f, fg, hf, hfp, vp, x0, t, cur, run, True, bat, kb_i)
        else:
            st, ev = _sample_at(kind, f, fg, hf, hfp, vp, x0, t, cur, run, True, bat,
                                np.int64(-1))        # (an int64: _sample_at compiles once)
        evals += ev
        if persp and kb_i >= 0 and bat[BAT_PT * BATCH + kb_i] != 0.0:
            cur[A_U] = bat[BAT_U * BATCH + kb_i]       # where the batch's root lies (for
            cur[A_V] = bat[BAT_V * BATCH + kb_i]       # the slivers below)
            ev = 1
        if persp and st == S_OK:
            _keep_guess(sg, rot, k, cur[A_W] - vp[VP_CW])  # the next columns' start
        if persp and st != S_OK and not resume:
            # A sliver: the surface's curve in Pi may enter the domain and leave it
            # between two planes whose points both lie outside (near a corner, or a
            # spiky edge seen from its side). If the segment between the two points
            # crosses the domain, look once in its middle; if the surface is there,
            # it becomes a plane of its own, with its edges bisected as usual.
            if bad_valid and ev > 0 and prev_st >= 0 and prev_st != S_OK and \
                    not (in_domain(vp, bad_u, bad_v) and in_domain(vp, cur[A_U], cur[A_V])):
                c_lo, c_hi = _clip_line(vp, bad_u, cur[A_U] - bad_u, bad_v, cur[A_V] - bad_v,
                                        0.0, 1.0)
                if c_lo < c_hi:
                    tm = prev_t + 0.5 * (c_lo + c_hi) * (t - prev_t)
                    st_m, ev_m = _sample_into(kind, f, fg, hf, hfp, vp, x0, tm, tmp, run)
                    evals += ev_m
                    if st_m == S_OK:
                        resume = True
                        t_resume = t
                        k_resume = k
                        t = tm
                        k = -1
                        continue
            bad_valid = ev > 0
            bad_u = cur[A_U]
            bad_v = cur[A_V]
        else:
            bad_valid = False
        if prev_st >= 0 and (prev_st == S_OK) != (st == S_OK):
            # A run starts or ends between prev_t and t: bisect for its edge.
            if st == S_OK:
                t_ok = t
                t_bad = prev_t
                st_bad = prev_st
            else:
                t_ok = prev_t
                t_bad = t
                st_bad = st
            found, ev_e = _run_edge(kind, f, fg, hf, hfp, vp, x0, t_ok, t_bad, st_bad, tmp,
                                    edge, run)
            evals += ev_e
            if found:
                if run[RUN_OPEN] == 0.0:
                    run_start = edge[A_T]
                    _fill_span(gcol, ecol, run, prev, edge, sigma, persp, d3, H, aa)
                else:
                    evals += _span(kind, f, fg, hf, hfp, vp, x0, prev, edge, gcol, ecol, run,
                                   sigma, persp, d3, H, aa, stk, sdepth, left, mid, tmp)
                _copy(prev, edge)
        if st == S_OK:
            if run[RUN_OPEN] == 0.0:
                run_start = t
            if hstride > 0 and k >= 0 and k % hstride == 0:
                m = k // hstride
                if m < hrec.shape[0]:
                    hrec[m, H_Y] = cur[A_Y]
                    hrec[m, H_LO] = run[RUN_YMIN] if run[RUN_OPEN] != 0.0 else np.inf
                    hrec[m, H_HI] = run[RUN_YMAX] if run[RUN_OPEN] != 0.0 else -np.inf
                    hrec[m, H_TS] = run_start
            if run[RUN_OPEN] == 0.0:
                _fill_span(gcol, ecol, run, prev, cur, sigma, persp, d3, H, aa)
            else:
                if adaptive:
                    # refine where the normal turns fast, coarsen where it does not
                    turn = math.sqrt((cur[A_NX] - prev[A_NX]) ** 2 + (cur[A_NY] - prev[A_NY]) ** 2
                                     + (cur[A_NZ] - prev[A_NZ]) ** 2)
                    ratio = ADAPT_TURN / turn if turn > 0.0 else 2.0
                    dy = abs(cur[A_Y] - prev[A_Y])      # ... and spans stay short on screen
                    if dy > 0.0:
                        ratio = min(ratio, ADAPT_ROWS / dy)
                    coarse = min(max(coarse * min(max(ratio, 0.5), 2.0), ADAPT_MIN_STEP),
                                 ADAPT_MAX_STEP)
                if not _cuts_cells(kind, hf, hfp, vp, prev, cur) and \
                        not _problem(vp, x0, prev, cur, run):
                    _fill(gcol, ecol, run, prev, cur, sigma, persp, d3, H, aa)  # the common case
                elif kind == SURF_HEIGHTFIELD and vp[VP_PASS_HIDDEN] != 0.0 \
                        and _hidden_cells(hf, hfp, vp, x0, prev[A_U], prev[A_V], prev[A_T],
                                          cur[A_U], cur[A_V], cur[A_T], run):
                    pass        # nothing of the span can show: its cuts would change nothing
                else:
                    evals += _span(kind, f, fg, hf, hfp, vp, x0, prev, cur, gcol, ecol, run,
                                   sigma, persp, d3, H, aa, stk, sdepth, left, mid, tmp)
            prev, cur = cur, prev       # cur becomes prev (its old values: scratch)
        else:
            run[RUN_OPEN] = 0.0
        prev_st = st
        prev_t = t
        # the next plane
        if resume:                      # back to the plane after the sliver
            resume = False
            t = t_resume
            k = k_resume
            continue
        if adaptive:
            if t == tb:
                break
            h = dt
            if st == S_OK:
                # about a pixel on screen: the step grows with the distance of the
                # sample just taken (prev, since the swap above; cur was the one before
                # it, and scratch never written at a run's first sample, whose garbage
                # made t NaN and the loop endless)
                if persp:
                    h *= min(max((prev[A_Z] + d3) / q_near, 1.0), ADAPT_MAX_GROWTH)
                h *= coarse
                if not h >= dt * ADAPT_MIN_STEP:        # (NaN too) the loop must advance
                    h = dt
            else:
                coarse = 1.0
            t_next = t + sigma * h
            t = tb if sigma * (t_next - tb) >= 0.0 else t_next
        else:
            i += 1
            if i >= i_end:
                break
            t, k = _pass_plane(i, n, ta, tb, t0, ka, kb, dt, sigma)
    return evals


# rows of render_column's scratch
SCR_PREV = 0
SCR_CUR = 1
SCR_EDGE = 2
SCR_TMP = 3
SCR_RUN = 4
SCR_LEFT = 5
SCR_MID = 6
SCR_STK = 7
SCR_WIDTH = -(-max(A_SIZE, RUN_SIZE) // 8) * 8    # (whole cache lines a row)


@ngjit
def render_column(kind, f, fg, fb, hf, hfp, vp, col, gcol, ecol, hrec, hstride, sg, rot, into,
                  trace):
    """Render pixel column ``col`` into gcol (H, G_SIZE) and ecol (E_SIZE, H): gcol
    only where ecol's E_SEEN row, cleared here, is not 0 (coverage.py). Returns
    (evaluations of f, the lowest and highest w where the upper side is seen: inf,
    -inf where it is not, the lowest and highest row where E_SEEN may be set: H, -1
    where none is). sg: the perspective solutions of the last columns by plane
    (guesses_for; row rot % 3 gets this column's), or empty; rot: the columns
    rendered into it before. The column's scratch is allocated here; the GPU's
    kernel (kernels/cuda.py) runs the same steps on scratch of its own. ``into`` and
    ``trace``: render_column_into and fold.trace_column as function values, called
    through their addresses (column_functions: each compiled once, not again into
    render_column's code)."""
    scr, sdepth, bat = column_scratch()
    evals = into(kind, f, fg, fb, hf, hfp, vp, col, gcol, ecol, hrec, hstride, sg, rot, scr,
                 sdepth, bat)
    if column_folds(scr, hstride):
        # the column's curve folds back in t: traced, and put in where the column
        # pass missed it (fold.py)
        evals += trace(kind, f, fg, hf, hfp, vp, column_x0(vp, col), gcol, ecol)
        _seen_ranges(gcol, ecol, scr[SCR_RUN])
    return column_result(scr, gcol.shape[0], evals)


@ngjit
def column_scratch():
    """render_column_into's scratch of one column: (scr, sdepth, bat)."""
    return (np.empty((SCR_STK + STACK_SIZE, SCR_WIDTH)), np.zeros(STACK_SIZE, dtype=np.int64),
            np.empty(BAT_SIZE * BATCH))


@ngjit_nrt_free
def render_column_into(kind, f, fg, fb, hf, hfp, vp, col, gcol, ecol, hrec, hstride, sg, rot,
                       scr, sdepth, bat):
    """render_column's passes with the column's scratch given (column_scratch's: scr
    (SCR_STK + STACK_SIZE, SCR_WIDTH), sdepth (STACK_SIZE,) int64, bat (BAT_SIZE *
    BATCH,)); allocates nothing. Returns the evaluations of f; then column_folds says
    whether the fold tracer is to run, and column_result gives render_column's
    values."""
    ecol[E_SEEN, :] = 0.0               # (the coverage planes are kept lazily)
    if sg.shape[1] > 0:
        sg[rot % 3, :] = np.nan
    hrec[:, :] = np.nan
    x0 = column_x0(vp, col)
    # the passes below run without reference counting (_jit.ngjit_nrt_free)
    scr[SCR_RUN, :] = 0.0
    scr[SCR_RUN, RUN_WLO] = np.inf
    scr[SCR_RUN, RUN_WHI] = -np.inf
    scr[SCR_RUN, RUN_JLO] = ecol.shape[1]
    scr[SCR_RUN, RUN_JHI] = -1.0
    scr[SCR_RUN, RUN_EDGE_J] = -1.0
    scr[SCR_RUN, RUN_TOP_J] = -1.0
    scr[SCR_RUN, RUN_TOP_ON] = vp[VP_KEEP_TOP]
    scr[SCR_RUN, RUN_CU] = vp[VP_CU]
    scr[SCR_RUN, RUN_CV] = vp[VP_CV]
    scr[SCR_RUN, RUN_WO] = vp[VP_WORG]
    sdepth[:] = 0
    # The passes: ascending t in orthographic; in perspective from the viewpoint's t
    # outward, both ways. (Here, not in a function of their own: Numba optimises and
    # compiles a called function's code again in each caller, 5 s of a first picture)
    prev = scr[SCR_PREV]
    cur = scr[SCR_CUR]
    edge = scr[SCR_EDGE]
    tmp = scr[SCR_TMP]
    run = scr[SCR_RUN, :RUN_SIZE]
    left = scr[SCR_LEFT]
    mid = scr[SCR_MID]
    stk = scr[SCR_STK:]
    evals = 0
    if vp[VP_ORTHO] != 0.0:
        lo, hi = _ortho_chord(vp, x0)
        if lo <= hi:
            evals += _column_pass(kind, f, fg, fb, hf, hfp, vp, x0, lo, hi, 1.0,
                                  gcol, ecol, hrec, hstride, prev, cur, edge, tmp, run,
                                  stk, sdepth, left, mid, bat, sg, rot)
    else:
        t_lo = vp[VP_T0]
        t_hi = vp[VP_T1]
        t_view = -vp[VP_D3] * vp[VP_CA]      # the viewpoint's t, eq. (1)
        if t_hi > t_view:
            evals += _column_pass(kind, f, fg, fb, hf, hfp, vp, x0, max(t_lo, t_view), t_hi,
                                  1.0, gcol, ecol, hrec, hstride, prev, cur, edge, tmp, run,
                                  stk, sdepth, left, mid, bat, sg, rot)
        if t_lo < t_view:
            evals += _column_pass(kind, f, fg, fb, hf, hfp, vp, x0, min(t_hi, t_view), t_lo,
                                  -1.0, gcol, ecol, hrec, hstride, prev, cur, edge, tmp, run,
                                  stk, sdepth, left, mid, bat, sg, rot)
    _settle_top(ecol, scr[SCR_RUN])
    _write_edge(ecol, scr[SCR_RUN])
    return evals


@ngjit_inline
def column_folds(scr, hstride):
    """Does the column just rendered into scr fold back in t (fold.py; not traced in a
    line drawing)?"""
    return scr[SCR_RUN, RUN_FOLD] != 0.0 and hstride == 0


@ngjit_inline
def column_result(scr, H, evals):
    """render_column's values from the column's scratch."""
    # (the seen heights as the G-buffer holds them, less VP_WORG: layout.py G_W)
    return (evals, scr[SCR_RUN, RUN_WLO] + scr[SCR_RUN, RUN_WO],
            scr[SCR_RUN, RUN_WHI] + scr[SCR_RUN, RUN_WO],
            min(max(trunc_index(scr[SCR_RUN, RUN_JLO]), 0), H),
            min(max(trunc_index(scr[SCR_RUN, RUN_JHI]), -1), H - 1))


@ngjit_nrt_free
def _seen_ranges(gcol, ecol, run):
    """run's RUN_WLO, RUN_WHI (w where the upper side is seen) and RUN_JLO, RUN_JHI
    (the rows set) from a column's buffers."""
    H = gcol.shape[0]
    run[RUN_WLO] = np.inf
    run[RUN_WHI] = -np.inf
    run[RUN_JLO] = H
    run[RUN_JHI] = -1.0
    for j in range(H):
        if ecol[E_SEEN, j] != 0.0:       # (a partial pixel's coverages too: coverage.py)
            run[RUN_JLO] = min(run[RUN_JLO], j)
            run[RUN_JHI] = max(run[RUN_JHI], j)
            if seen_side(ecol[E_SEEN, j]) > 0.0:
                run[RUN_WLO] = min(run[RUN_WLO], gcol[j, G_W])
                run[RUN_WHI] = max(run[RUN_WHI], gcol[j, G_W])


@ngjit
def guesses_for(vp):
    """A tile's perspective Newton starts: the solutions s of its last three columns
    (rows by column number mod 3), one a plane of the grid t0 + k dt (NaN: none);
    empty where the planes are not batched in perspective."""
    if vp[VP_ORTHO] != 0.0 or vp[VP_BATCH] == 0.0 or not vp[VP_DT] > 0.0:
        return np.empty((3, 0))
    n = (vp[VP_T1] - vp[VP_T0]) / vp[VP_DT] + 3.0
    if not n < 1e7:
        return np.empty((3, 0))
    return np.full((3, int(n)), np.nan)


@ngjit_inline
def _guess(sg, rot, k):
    """Column number rot's Newton start on grid plane k from the two columns before
    (sg: guesses_for): the line through their solutions, or the last one's; NaN
    where there is none."""
    if not 0 <= k < sg.shape[1]:
        return np.nan
    a = sg[(rot + 2) % 3, k]
    b = sg[(rot + 1) % 3, k]
    if math.isfinite(b):
        return 2.0 * a - b            # (NaN where a is)
    return a


@ngjit_inline
def _keep_guess(sg, rot, k, s):
    """Column number rot's solution s on grid plane k, for the columns after it."""
    if 0 <= k < sg.shape[1]:
        sg[rot % 3, k] = s


def column_functions(kind, f, fg, fb, hf, hfp, vp, buf_dtype, hrec_dtype):
    """The jitted functions column_kernel and subcolumn_kernel take as values
    (_jit.kernel_calling), as (function, first-class function type) pairs:
    render_column, and render_column_into and fold.trace_column, which render_column
    takes, for the surface's kernel arguments (kind, f, fg, fb, hf, hfp), the view's
    vp, a G-buffer and edge buffer of dtype buf_dtype whose column is a 2-D view
    (layout 'A') and horizon records of hrec_dtype (a column's a C array)."""
    buf = types.Array(numba.from_dtype(buf_dtype), 2, "A")
    hrec = types.Array(numba.from_dtype(hrec_dtype), 2, "C")
    grid = types.Array(types.float64, 2, "C")
    into = function_type(render_column_into, kind, f, fg, fb, hf, hfp, vp, types.float64, buf,
                         buf, hrec, types.int64, grid, types.int64, grid,
                         types.Array(types.int64, 1, "C"), types.Array(types.float64, 1, "C"))
    trace = function_type(trace_column, kind, f, fg, hf, hfp, vp, types.float64, buf, buf)
    render = function_type(render_column, kind, f, fg, fb, hf, hfp, vp, types.float64, buf, buf,
                           hrec, types.int64, grid, types.int64, into, trace)
    return tuple(zip(COLUMN_FUNCTIONS, (render, into, trace)))


#: column_functions' functions, in the order the kernels take them
COLUMN_FUNCTIONS = (render_column, render_column_into, trace_column)


def _column_kernel_functions(kind, f, fg, fb, hf, hfp, vp, gbuf, ebuf, hrec, *rest):
    """column_kernel's jitted functions (column_functions)."""
    return column_functions(kind, f, fg, fb, hf, hfp, vp, gbuf.dtype, hrec.dtype)


@kernel_calling(_column_kernel_functions, COLUMN_FUNCTIONS)
def column_kernel(kind, f, fg, fb, hf, hfp, vp, gbuf, ebuf, hrec, hstride, evals, wrange,
                  rows, render, into, trace):
    """Render every column c into gbuf (n_tiles, H, TILE, G_SIZE) and ebuf (n_tiles,
    E_SIZE, H, TILE) (layout.py: tiles of TILE columns, rows from the bottom), the
    tiles in parallel. ebuf's E_SEEN plane says where the G-buffer is set (it is not
    cleared), and with VP_AA its coverage planes the coverages. hrec (W, n_lines,
    H_SIZE) receives horizon-line records when hstride > 0; evals (W,) the evaluations
    of f; wrange (W, 2) the lowest and highest w where the upper side is seen (inf,
    -inf where it is not), kept while the pixels are painted (_fill); rows (n_tiles,
    2) the lowest and highest row of each tile where E_SEEN may be set (H, -1: none),
    outside which its E_SEEN is 0 and the finishing pass does not read it. A group of
    GROUP_TILES tiles runs on one thread, its columns one after another, and writes
    only its own tiles: no shared scratch. ``render``, ``into``, ``trace``: render_column
    and the two functions it takes, as function values (column_functions; the launch
    passes them: _jit.kernel_calling)."""
    n_tiles = gbuf.shape[0]
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    W = evals.shape[0]
    for g in prange((n_tiles + GROUP_TILES - 1) // GROUP_TILES):
        sg = guesses_for(vp)            # the group's own: its columns run in order
        for b in range(g * GROUP_TILES, min(g * GROUP_TILES + GROUP_TILES, n_tiles)):
            rows[b, 0] = H
            rows[b, 1] = -1
            for lane in range(T):
                c = b * T + lane
                if c >= W:
                    break
                # (the column as a float, as subcolumn_kernel's sub-columns: one compile
                # of render_column for both)
                evals[c], wrange[c, 0], wrange[c, 1], j_lo, j_hi = render(
                    kind, f, fg, fb, hf, hfp, vp, float(c), gbuf[b, :, lane],
                    ebuf[b, :, :, lane], hrec[c], hstride, sg, (b - g * GROUP_TILES) * T + lane,
                    into, trace)
                rows[b, 0] = min(rows[b, 0], j_lo)
                rows[b, 1] = max(rows[b, 1], j_hi)

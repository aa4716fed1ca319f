"""Perspective columns whose curve folds back in t: traced as a curve, drawn by depth.

In perspective with elev != 0 the line where a sampling plane t meets the column
plane Pi is tilted from the vertical (k = x0 sin(alpha) / d1 in r per unit of s).
Where the surface is steeper than that line (k f_r > 1: a vertical rim such as
sqrt(4 - r^2) at r = 2, in a column away from the picture's centre) the line meets
the surface more than once: the curve C that Pi cuts, G(t, s) = f(u, v) - cw - s = 0,
folds back in t, and the floating column, one point per plane taken front to back,
cannot follow it (it paints the backward part as the other side, joins the branches
with a streak, and misses what it does not take).

The column pass notes such a fold (a sample whose upper normal N has N.d < 0, d =
(k, cos(alpha), sin(alpha)) the line's direction on screen: then dG/ds = k f_r - 1
> 0; column._sample_at, where vp's VP_FOLD allows; or a run that begins or ends
inside the domain next to a plane dropped as outside, or whose samples go over to
another piece of the curve: column._column_pass, _segment) and render_column then
traces the column's curve here: every piece of C by predictor-corrector continuation
in (t, s) (steps of at most a pixel on screen), from seeds (the column pass's seen
points every SEED_ROWS rows and at the first row of each piece it saw; the roots of
g on every SEED_STRIDE-th plane, a scan like sample._bracketed_s's that keeps them
all), each step rasterised into a buffer of its own with a depth test, side by N.V.
The traced pixel then replaces the column pass's where that saw nothing, another side
or a farther surface; where both agree the traced point replaces the column pass's
G-buffer entry (lerped across the fold) and the column pass's coverages stay, unless
the traced curve runs on through the pixel (_inside_piece).

The translucent layers (layers.py) trace a folding column's curve the same way
(trace_layers_into), every step's rows kept as crossings (_raster's translucent form),
all of them, not the nearest alone.
"""
import math

import numpy as np

from ._jit import ngjit, ngjit_inline, ngjit_nrt_free
from .index import ceil_index, floor_index, round_index, trunc_index
from .layout import (
    E_SEEN, G_DEPTH, G_I, G_NX, G_NY, G_NZ, G_SIZE, G_T, G_U, G_V, G_W,
    VP_CA, VP_CB, VP_CU, VP_CV, VP_CW, VP_D1, VP_D3, VP_DT, VP_H, VP_WORG,
    VP_SA, VP_SB, VP_SCALE, VP_T0, VP_T1,
)
from .coverage import flagged, seen_side
from .sample import (
    _g_at, in_domain, in_known_hole, lambert, scan_range, surface_eval, unit_normal)

#: a column is traced where a sample has 1 - k f_r < 0 (a fold), or a sample that
#: the column pass takes between its planes (an edge's, a correction's) has 1 - k f_r
#: below FOLD_NEAR (nearly a fold: a rim's last samples, where f_r grows without
#: bound; on its own planes a steep ridge's near-folds are no fault of the column's)
FOLD_NEAR = 0.1
#: seeds: the column pass's seen points every SEED_ROWS rows, and the scan of every
#: SEED_STRIDE-th plane, SEED_SCAN points over the range of f
SEED_ROWS = 8
#: ... and where the seen point's t jumps by more than SEED_DT planes from the row below
SEED_DT = 2.0
SEED_STRIDE = 16
SEED_SCAN = 32
SEED_BISECT = 50
#: the corrector's iterations and tolerance (pixels off the curve)
CORRECT_ITERS = 12
CORRECT_TOL_PX = 1e-4
#: ... and f within this many pixels of the point's height (first order alone took
#: points far off a wildly oscillating surface)
S_TOL_PX = 2.0
#: a step is at most MAX_DY_PX on screen and turns the tangent by at most acos(MIN_TURN)
MAX_DY_PX = 1.0
MIN_TURN = 0.98
#: a piece ends this many pixels off the picture
OFF_PX = 2.0
#: a step that crosses a plane within RETRACE_PX (on screen at the screen plane's
#: distance) of a crossing traced before ends the piece: it runs over a traced one
RETRACE_PX = 0.05
#: largest step, in planes' distances (where the curve runs toward the viewpoint, its
#: steps barely move on screen)
MAX_STEP = 64.0
#: smallest step (a fraction of the planes' distance): below it a piece ends (a hole),
#: or where the step still moves more than JUMP_PX on screen (a jump of f, a pole)
MIN_STEP = 1.0 / 256.0
JUMP_PX = 4.0
#: the traced pixel replaces the column pass's where nearer by DEPTH_EPS d3
DEPTH_EPS = 1e-3
#: crossings of a plane kept (to tell a seed on a traced piece from a new one)
CROSS_MAX = 16
#: a point of a piece: u, v, w, unit upper normal, intensity, side, t
P_U = 0
P_V = 1
P_W = 2
P_NX = 3
P_NY = 4
P_NZ = 5
P_I = 6
P_SIDE = 7
P_T = 8
P_SIZE = 9
#: a translucent column's crossing (trace_layers_into): its depth, then its point (P_*)
X_DEPTH = 0
XING_SIZE = P_SIZE + 1
#: the row of trace_layers_into's ecol that counts each row's crossings (its E_SEEN
#: row stays 0: _seed's _traced_at never takes a translucent column's row as traced)
XING_COUNT = E_SEEN + 1
#: crossings a translucent column keeps a row (the surface's layers along one ray)
XING_MAX = 16


@ngjit_inline
def fold_test(vp, x0, nx, ny, nz, margin):
    """Does the curve fold back in t at a perspective sample with unit upper normal
    (nx, ny, nz), or nearly (within ``margin``)? N.d < margin N.e, d = (k, cos(alpha),
    sin(alpha)), e = (0, cos(alpha), sin(alpha)) the world's up: N.d / N.e = 1 - k f_r
    = -dG/ds, 0 at a fold."""
    up = vp[VP_CA] * ny + vp[VP_SA] * nz
    return (x0 * vp[VP_SA] / vp[VP_D1]) * nx + up < margin * up


@ngjit_inline
def _g_grad(kind, fg, hf, hfp, vp, x0, t, s):
    """(G, dG/dt, dG/ds, u, v, w, f_u, f_v) at (t, s) of column x0's plane Pi; G NaN
    outside the domain or at a hole."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    d1 = vp[VP_D1]
    k = x0 * sa / d1
    drdt = x0 * ca / d1
    r = x0 * (t * ca + vp[VP_D3]) / d1 + k * s           # eq. (9) plus k s inside Pi
    u = vp[VP_CU] + r * cb + t * sb                        # eq. (2)
    v = vp[VP_CV] - r * sb + t * cb
    if not in_domain(vp, u, v) or in_known_hole(vp, u, v):     # (f NaN: hole map)
        return np.nan, 0.0, 0.0, u, v, 0.0, 0.0, 0.0
    w, wu, wv = surface_eval(kind, fg, hf, hfp, u, v)
    if not (math.isfinite(w) and math.isfinite(wu) and math.isfinite(wv)):
        return np.nan, 0.0, 0.0, u, v, 0.0, 0.0, 0.0
    g_t = wu * (drdt * cb + sb) + wv * (cb - drdt * sb)
    g_s = k * (wu * cb - wv * sb) - 1.0
    return w - vp[VP_CW] - s, g_t, g_s, u, v, w, wu, wv


@ngjit_nrt_free
def _correct(kind, fg, hf, hfp, vp, x0, t, s, p):
    """Newton's steps along the gradient of G from (t, s) onto the curve. Returns (ok,
    t, s, dG/dt, dG/ds, evaluations); with ok, p holds the point (P_*)."""
    tol = CORRECT_TOL_PX / vp[VP_SCALE]
    for i in range(CORRECT_ITERS):
        g, g_t, g_s, u, v, w, wu, wv = _g_grad(kind, fg, hf, hfp, vp, x0, t, s)
        if not math.isfinite(g):
            return False, t, s, 0.0, 0.0, i + 1
        n2 = g_t * g_t + g_s * g_s
        if n2 == 0.0:
            return False, t, s, 0.0, 0.0, i + 1
        # on the curve within tol (to first order), and f within S_TOL_PX pixels of the
        # point's height: where f oscillates wildly (y sin(1/x) near x = 0) the first
        # order alone took points far off the surface (lines across the picture)
        if abs(g) <= tol * math.sqrt(n2) and abs(g) <= S_TOL_PX / vp[VP_SCALE]:
            if not _point(vp, x0, t, s, u, v, w, wu, wv, p):
                return False, t, s, 0.0, 0.0, i + 1
            return True, t, s, g_t, g_s, i + 1
        t -= g * g_t / n2
        s -= g * g_s / n2
    return False, t, s, 0.0, 0.0, CORRECT_ITERS


@ngjit_inline
def _screen(vp, t, s):
    """(row from the bottom, screen depth z1, y1) of the point (t, s) of Pi; NaN row in
    front of the screen plane (eqs. 4, 10)."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    y1 = s * ca - t * sa
    z1 = s * sa + t * ca
    if z1 + vp[VP_D3] <= vp[VP_D1]:
        return np.nan, z1, y1
    return (y1 * vp[VP_D1] / (z1 + vp[VP_D3]) * vp[VP_SCALE] + (vp[VP_H] - 1.0) * 0.5,
            z1, y1)


@ngjit_inline
def _point(vp, x0, t, s, u, v, w, wu, wv, p):
    """Fill p (P_*) for the curve's point (t, s); False in front of the screen plane."""
    row, z1, y1 = _screen(vp, t, s)
    if not math.isfinite(row):
        return False
    nx, ny, nz = unit_normal(vp, wu, wv)                 # eq. (11)
    d3 = vp[VP_D3]
    vx = -x0 * (z1 + d3) / vp[VP_D1]                    # toward the viewpoint
    vy = -y1
    vz = -(d3 + z1)
    p[P_U] = u
    p[P_V] = v
    p[P_W] = w
    p[P_NX] = nx
    p[P_NY] = ny
    p[P_NZ] = nz
    p[P_I] = lambert(vp, vx, vy, vz, nx, ny, nz)         # eq. (12)
    p[P_SIDE] = 1.0 if nx * vx + ny * vy + nz * vz > 0.0 else -1.0
    p[P_T] = t
    return True


@ngjit_nrt_free
def _raster(gcol, ecol, ya, za, a, yb, zb, b, cu, cv, wo):
    """Rows between the points a (row ya, depth za) and b of the curve: lerped
    G-buffer entries where nothing nearer is there yet (u, v from the view's centre
    (cu, cv), w from wo: layout.py G_U, G_W). A gcol wider than G_SIZE is a
    translucent column's list of crossings instead (trace_layers_into: every one
    kept, XING_SIZE values each, ecol[XING_COUNT] how many a row holds)."""
    H = gcol.shape[0]
    if yb == ya:
        return
    lo = max(ceil_index(min(ya, yb)), 0)
    hi = min(floor_index(max(ya, yb)), H - 1)
    if gcol.shape[1] > G_SIZE:
        for j in range(lo, hi + 1):
            lam = (j - ya) / (yb - ya)
            n = int(ecol[XING_COUNT, j])
            if n * XING_SIZE + XING_SIZE > gcol.shape[1]:
                continue                          # (the row's list is full)
            rec = gcol[j, n * XING_SIZE:(n + 1) * XING_SIZE]
            rec[X_DEPTH] = za + lam * (zb - za)
            for q in range(P_SIZE):
                rec[1 + q] = a[q] + lam * (b[q] - a[q])
            ecol[XING_COUNT, j] = n + 1
        return
    for j in range(lo, hi + 1):
        lam = (j - ya) / (yb - ya)
        z = za + lam * (zb - za)
        if ecol[E_SEEN, j] != 0.0 and gcol[j, G_DEPTH] <= z:
            continue
        g = gcol[j]
        g[G_DEPTH] = z
        g[G_U] = (a[P_U] - cu) + lam * (b[P_U] - a[P_U])
        g[G_V] = (a[P_V] - cv) + lam * (b[P_V] - a[P_V])
        g[G_W] = (a[P_W] - wo) + lam * (b[P_W] - a[P_W])
        g[G_NX] = a[P_NX] + lam * (b[P_NX] - a[P_NX])
        g[G_NY] = a[P_NY] + lam * (b[P_NY] - a[P_NY])
        g[G_NZ] = a[P_NZ] + lam * (b[P_NZ] - a[P_NZ])
        g[G_I] = a[P_I] + lam * (b[P_I] - a[P_I])
        g[G_T] = a[P_T] + lam * (b[P_T] - a[P_T])
        ecol[E_SEEN, j] = a[P_SIDE] if lam < 0.5 else b[P_SIDE]


@ngjit_nrt_free
def _trace(kind, fg, hf, hfp, vp, x0, t, s, direction, s_min, s_max, gcol, ecol, cross,
           n_cross, a, b):
    """Trace the piece of the curve through (t, s) one way (direction +1 or -1 along
    the tangent (-dG/ds, dG/dt)) while s stays in [s_min, s_max], rasterising each
    step, noting where it crosses the planes (cross, n_cross). Returns (closed: back
    at its start, evaluations)."""
    ok, t, s, g_t, g_s, evals = _correct(kind, fg, hf, hfp, vp, x0, t, s, a)
    if not ok or s < s_min or s > s_max:
        return False, evals
    dt = vp[VP_DT]
    t0 = vp[VP_T0]
    n = cross.shape[0]
    tg_rows = gcol.shape[0]
    ya, za, _ = _screen(vp, t, s)
    if not -OFF_PX <= ya <= tg_rows - 1.0 + OFF_PX:
        return False, evals
    norm = math.sqrt(g_t * g_t + g_s * g_s)
    tt = -g_s / norm * direction
    ts = g_t / norm * direction
    h = dt
    t_start = t
    s_start = s
    travelled = 0.0
    retrace = RETRACE_PX / vp[VP_SCALE]
    for _ in range(16 * n + 64):
        ok, qt, qs, g_t, g_s, ev = _correct(kind, fg, hf, hfp, vp, x0, t + h * tt, s + h * ts,
                                            b)
        evals += ev
        if not ok:
            if h > dt * MIN_STEP:
                h *= 0.5
                continue
            return False, evals                 # the piece ends (a hole, the domain's edge)
        if qs < s_min or qs > s_max:
            return False, evals                 # toward a pole: the piece ends
        yb, zb, _ = _screen(vp, qt, qs)
        if not -OFF_PX <= yb <= tg_rows - 1.0 + OFF_PX:
            return False, evals                 # off the picture (a seed of its own
            #                                     finds it where it comes back)
        norm = math.sqrt(g_t * g_t + g_s * g_s)
        nt = -g_s / norm
        ns = g_t / norm
        turn = nt * tt + ns * ts
        if turn < 0.0:
            nt = -nt
            ns = -ns
            turn = -turn
        step = math.sqrt((qt - t) ** 2 + (qs - s) ** 2)
        if abs(yb - ya) > MAX_DY_PX or turn < MIN_TURN or step > 1.5 * h:
            if h > dt * MIN_STEP:
                h *= 0.5
                continue
            if abs(yb - ya) > JUMP_PX:
                return False, evals             # a jump of f or a pole: the piece ends
        _raster(gcol, ecol, ya, za, a, yb, zb, b, vp[VP_CU], vp[VP_CV], vp[VP_WORG])
        ia = (t - t0) / dt                      # the planes this step crosses
        ib = (qt - t0) / dt
        if ib != ia:
            for i in range(max(ceil_index(min(ia, ib)), 0),
                           min(floor_index(max(ia, ib)), n - 1) + 1):
                s_i = s + (i - ia) / (ib - ia) * (qs - s)
                for c in range(n_cross[i]):
                    if abs(cross[i, c] - s_i) < retrace:
                        # on a piece traced already (by this trace turned back at a
                        # corner of the curve, where the tangent's sign is a toss-up,
                        # or by another seed's): the rest is drawn
                        return False, evals
                if n_cross[i] < CROSS_MAX:
                    cross[i, n_cross[i]] = s_i
                    n_cross[i] += 1
        dy = abs(yb - ya)
        travelled += step
        t = qt
        s = qs
        ya = yb
        za = zb
        for q in range(P_SIZE):
            a[q] = b[q]
        tt = nt
        ts = ns
        if travelled > 4.0 * dt and math.sqrt((t - t_start) ** 2 + (s - s_start) ** 2) < 1.01 * h:
            return True, evals                  # a closed curve
        if t < vp[VP_T0] - dt or t > vp[VP_T1] + dt:
            return False, evals
        h = min(h * (1.5 if dy < 0.3 * MAX_DY_PX else 1.1), MAX_STEP * dt)
    return False, evals


@ngjit_nrt_free
def _seed(kind, fg, hf, hfp, vp, x0, t, s, s_min, s_max, tg, te, cross, n_cross, a, b):
    """Trace the piece through (t, s) of plane number i = (t - T0) / DT both ways,
    unless a traced piece crosses plane i near s already. Returns the evaluations."""
    dt = vp[VP_DT]
    i = round_index((t - vp[VP_T0]) / dt)
    if 0 <= i < cross.shape[0]:
        for c in range(n_cross[i]):
            if abs(cross[i, c] - s) < 2.0 * dt:
                return 0
    row, z, _ = _screen(vp, t, s)
    if math.isfinite(row):                  # a traced surface there, as far: known
        j = round_index(row)
        if 0 <= j < tg.shape[0] and _traced_at(tg, te, j, z, vp):
            return 0
    closed, evals = _trace(kind, fg, hf, hfp, vp, x0, t, s, 1.0, s_min, s_max, tg, te, cross,
                           n_cross, a, b)
    if not closed:
        _, ev = _trace(kind, fg, hf, hfp, vp, x0, t, s, -1.0, s_min, s_max, tg, te, cross,
                       n_cross, a, b)
        evals += ev
    return evals


@ngjit
def trace_column(kind, f, fg, hf, hfp, vp, x0, gcol, ecol):
    """Trace column x0's curve (the module's docstring) into a buffer of its own, then
    put it into gcol and ecol (the column pass's) where the column pass saw nothing,
    another side, or a farther surface; where both agree, the traced point with the
    column pass's coverages (the module's docstring). Seeds: the column pass's seen points every
    SEED_ROWS rows, and the roots on every SEED_STRIDE-th plane. Returns the
    evaluations of f."""
    tg, te, cross, n_cross, a, b = fold_scratch(vp, gcol.shape[0], gcol.shape[1])
    return trace_column_into(kind, f, fg, hf, hfp, vp, x0, gcol, ecol, tg, te, cross, n_cross,
                             a, b)


@ngjit
def fold_scratch(vp, H, width):
    """trace_column_into's scratch for a column of H rows of ``width`` values (the
    G-buffer's G_SIZE): (tg (H, width), te (E_SEEN + 1, H), cross (planes, CROSS_MAX),
    n_cross (planes,) int64, a, b (P_SIZE,))."""
    n = fold_planes(vp)
    return (np.empty((H, width)), np.zeros((E_SEEN + 1, H)), np.empty((n, CROSS_MAX)),
            np.zeros(n, dtype=np.int64), np.empty(P_SIZE), np.empty(P_SIZE))


@ngjit_inline
def fold_planes(vp):
    """The planes the fold tracer keeps crossings of."""
    return trunc_index((vp[VP_T1] - vp[VP_T0]) / vp[VP_DT]) + 2


@ngjit_nrt_free
def trace_column_into(kind, f, fg, hf, hfp, vp, x0, gcol, ecol, tg, te, cross, n_cross, a, b):
    """trace_column with its scratch given (fold_scratch's; te and n_cross are cleared
    here); allocates nothing."""
    H = gcol.shape[0]
    te[:, :] = 0.0
    n_cross[:] = 0
    t0 = vp[VP_T0]
    dt = vp[VP_DT]
    s_lo, s_hi = scan_range(vp)                          # as sample._bracketed_s
    s_min = s_lo - (s_hi - s_lo)                          # beyond: toward a pole
    s_max = s_hi + (s_hi - s_lo)
    evals = 0
    for j in range(0, H, SEED_ROWS):                      # the column pass's points
        if seen_side(ecol[E_SEEN, j]) != 0.0:
            i = round((gcol[j, G_T] - t0) / dt)
            evals += _seed(kind, fg, hf, hfp, vp, x0, t0 + i * dt,
                           gcol[j, G_W] + (vp[VP_WORG] - vp[VP_CW]), s_min, s_max, tg, te,
                           cross, n_cross, a, b)
    evals += _scan_seeds(kind, f, fg, hf, hfp, vp, x0, s_lo, s_hi, s_min, s_max, 0,
                         fold_planes(vp), SEED_STRIDE, False, tg, te, cross, n_cross, a, b)
    side_before = 0.0
    for j in range(H):
        # the first row of each piece the column pass saw, where no trace runs through
        # it yet: a piece a few rows high (born at a fold beside the domain's edge) may
        # hold none of the rows and planes above. From the nearest plane at the
        # point's height, as above, else from the point itself (near the domain's
        # edge that plane's point may lie outside it, where the corrector stops)
        side = seen_side(ecol[E_SEEN, j])
        first = side != 0.0 and (side != side_before or abs(gcol[j, G_T] - gcol[j - 1, G_T])
                                 > SEED_DT * dt)
        side_before = side
        if first and not _traced_at(tg, te, j, gcol[j, G_DEPTH], vp):
            i = round((gcol[j, G_T] - t0) / dt)
            s = gcol[j, G_W] + (vp[VP_WORG] - vp[VP_CW])    # (layout.py G_W)
            evals += _seed(kind, fg, hf, hfp, vp, x0, t0 + i * dt, s, s_min, s_max, tg, te,
                           cross, n_cross, a, b)
            if not _traced_at(tg, te, j, gcol[j, G_DEPTH], vp):
                evals += _seed(kind, fg, hf, hfp, vp, x0, gcol[j, G_T], s, s_min, s_max, tg,
                               te, cross, n_cross, a, b)
    eps = DEPTH_EPS * vp[VP_D3]
    for j in range(H):
        side = te[E_SEEN, j]
        if side == 0.0:
            continue
        seen = seen_side(ecol[E_SEEN, j])
        # the column pass saw nothing there, another side or a farther surface
        missed = seen == 0.0 or seen != side or tg[j, G_DEPTH] < gcol[j, G_DEPTH] - eps
        if not missed and tg[j, G_DEPTH] > gcol[j, G_DEPTH] + eps:
            continue                                      # a nearer surface: it stays
        # missed, or the same surface: the traced point (exact within a pixel)
        # replaces the column pass's, which interpolates across the fold (a wall's
        # normal and intensity lerped between its plane's two sides)
        for q in range(gcol.shape[1]):
            gcol[j, q] = tg[j, q]
        if missed or (flagged(ecol[E_SEEN, j]) and _inside_piece(tg, te, j, side, eps)):
            # whole (no coverages kept): the column pass's edge at the same surface
            # (where it lost the curve at the fold) is none where the traced surface
            # goes on through both neighbours
            ecol[E_SEEN, j] = side
    return evals


@ngjit_nrt_free
def _scan_seeds(kind, f, fg, hf, hfp, vp, x0, s_lo, s_hi, s_min, s_max, i_lo, i_hi, stride,
                known, tg, te, cross, n_cross, a, b):
    """Seeds what the column pass never met: every root of g on every stride-th plane
    from i_lo to i_hi (SEED_SCAN points over [s_lo, s_hi], each sign change bisected),
    each traced
    (_seed); with ``known``, a sign change whose bracket a traced piece crosses already
    is not bisected (trace_layers_into's scan of every plane). Returns the
    evaluations."""
    t0 = vp[VP_T0]
    dt = vp[VP_DT]
    ca = vp[VP_CA]
    d1 = vp[VP_D1]
    k = x0 * vp[VP_SA] / d1
    evals = 0
    ds = (s_hi - s_lo) / (SEED_SCAN - 1)
    for i in range(i_lo, i_hi, stride):
        t = t0 + i * dt
        r0 = x0 * (t * ca + vp[VP_D3]) / d1              # eq. (9)
        g_prev = np.nan
        for m in range(SEED_SCAN):
            s = s_lo + m * ds
            g, ev = _g_at(kind, f, hf, hfp, vp, r0, k, t, s)
            evals += ev
            if math.isfinite(g) and math.isfinite(g_prev) and (g >= 0.0) != (g_prev >= 0.0) \
                    and not (known and _known_root(vp, cross, n_cross, i, t, s - ds, s)):
                lo = s - ds
                hi = s
                g_lo = g_prev
                for _ in range(SEED_BISECT):
                    mid = 0.5 * (lo + hi)
                    gm, ev = _g_at(kind, f, hf, hfp, vp, r0, k, t, mid)
                    evals += ev
                    if not math.isfinite(gm):
                        break
                    if (gm >= 0.0) == (g_lo >= 0.0):
                        lo = mid
                        g_lo = gm
                    else:
                        hi = mid
                # a sign change across a pole of f is no root
                if abs(g_lo) <= 2.0 * abs(hi - lo) + CORRECT_TOL_PX / vp[VP_SCALE]:
                    evals += _seed(kind, fg, hf, hfp, vp, x0, t, 0.5 * (lo + hi), s_min,
                                   s_max, tg, te, cross, n_cross, a, b)
            g_prev = g
    return evals


@ngjit_inline
def _known_root(vp, cross, n_cross, i, t, lo, hi):
    """Is the root of g between s = lo and hi on plane i (at t) one to pass over: a
    traced piece crosses there, or it lies off the picture (its piece, where it comes
    back, is seeded there; _trace does not start off it)?"""
    row = _screen(vp, t, 0.5 * (lo + hi))[0]
    if not -OFF_PX - 1.0 <= row <= vp[VP_H] + OFF_PX:
        return True
    if i >= cross.shape[0]:
        return False
    for c in range(n_cross[i]):
        if lo <= cross[i, c] <= hi:
            return True
    return False


#: a translucent column's seeds: the roots on every LAYER_SEED_STRIDE-th plane (its
#: column pass's points are not kept)
LAYER_SEED_STRIDE = 1


@ngjit
def layers_fold_scratch(vp, H):
    """trace_layers_into's scratch for a column of H rows: (tg (H, XING_MAX *
    XING_SIZE), te (XING_COUNT + 1, H), cross, n_cross, a, b) as fold_scratch's."""
    n = fold_planes(vp)
    return (np.empty((H, XING_MAX * XING_SIZE)), np.zeros((XING_COUNT + 1, H)),
            np.empty((n, CROSS_MAX)), np.zeros(n, dtype=np.int64), np.empty(P_SIZE),
            np.empty(P_SIZE))


@ngjit_nrt_free
def trace_layers_into(kind, f, fg, hf, hfp, vp, x0, ta, tb, tg, te, cross, n_cross, a, b):
    """Every crossing of column x0's folding curve with each row's ray, for the
    translucent layers (layers.py): the curve's pieces traced as trace_column_into
    traces them (seeded by the roots on every LAYER_SEED_STRIDE-th plane from t = ta to
    tb, the column's planes), each step's rows kept in the row's list (tg, te:
    layers_fold_scratch's, _raster's translucent form) instead of the nearest alone.
    Returns the evaluations."""
    te[:, :] = 0.0
    n_cross[:] = 0
    s_lo, s_hi = scan_range(vp)
    i_lo = max(floor_index((ta - vp[VP_T0]) / vp[VP_DT]), 0)
    i_hi = min(ceil_index((tb - vp[VP_T0]) / vp[VP_DT]) + 1, fold_planes(vp))
    return _scan_seeds(kind, f, fg, hf, hfp, vp, x0, s_lo, s_hi, s_lo - (s_hi - s_lo),
                       s_hi + (s_hi - s_lo), i_lo, i_hi, LAYER_SEED_STRIDE, True, tg, te, cross,
                       n_cross, a, b)


@ngjit_inline
def _traced_at(tg, te, j, z, vp):
    """Does a traced piece run through row j at depth z (the same surface as a point
    there at that depth)?"""
    return te[E_SEEN, j] != 0.0 and abs(tg[j, G_DEPTH] - z) < 4.0 * DEPTH_EPS * vp[VP_D3]


@ngjit_inline
def _inside_piece(tg, te, j, side, eps):
    """Is traced row j inside one smooth piece: rows j - 1 and j + 1 traced too, the
    same side, the depth going on without a jump (neither step more than 3 times
    the other, up to eps)?"""
    if j < 1 or j > tg.shape[0] - 2 or te[E_SEEN, j - 1] != side or te[E_SEEN, j + 1] != side:
        return False
    a = abs(tg[j, G_DEPTH] - tg[j - 1, G_DEPTH])
    b = abs(tg[j + 1, G_DEPTH] - tg[j, G_DEPTH])
    return max(a, b) <= 3.0 * min(a, b) + eps

"""One sample: the surface point where a column plane meets a sampling plane t = t1.

Shared by every kernel. Eq. numbers are those of Gordon (2001).
"""
import math

import numpy as np

from ._jit import ngjit, ngjit_inline, ngjit_nrt_free, stack_pair
from .index import ceil_index, floor_index
from .layout import (
    HFP_CW, HFP_IU, HFP_IV, S_BEHIND, S_HOLE, S_OK, S_OUTSIDE, SURF_HEIGHTFIELD,
    VP_CA, VP_CB, VP_CU, VP_CV, VP_CW, VP_D1, VP_D3, VP_H, VP_LX, VP_LY, VP_LZ, VP_ORTHO,
    VP_FHI, VP_FLO, VP_HOLE_N, VP_HOLE_SU, VP_HOLE_SV, VP_HOLE_U0, VP_HOLE_V0, VP_PAPER,
    VP_SA, VP_SB, VP_SIZE, VP_W, VP_SCALE, VP_UA, VP_UB, VP_VA, VP_VB, VP_XOFF,
)

# Relative slack of the domain test, so chord endpoints computed in floating
# point still count as inside.
DOMAIN_EPS = 1e-9
NEWTON_ITERS = 12
#: perspective: a sample is placed when it lies within this many pixels of its
#: column's plane (ERRATA 2)
NEWTON_TOL_PX = 1e-3
SCAN_MIN = 3          # fallback scan of s when Newton fails (holes, steep rims):
SCAN_MAX = 24         # about one point per SCAN_PIXELS of the searched segment
SCAN_PIXELS = 4.0
BISECT_ITERS = 40
EDGE_BISECT = 6      # where the scan crosses the edge of the finite part of f
#: central differences' step (relative, as surface.py's for callables) where f's
#: formula gives partials that are not finite though f is
DIFF_STEP = 6e-6


@ngjit_nrt_free
def heightfield_eval(hf, hfp, u, v):
    """Bilinear height and its exact piecewise partials (the paper's section 2)."""
    nv, nu = hf.shape
    gx = (u - hfp[0]) / (hfp[1] - hfp[0]) * (nu - 1)
    gy = (v - hfp[2]) / (hfp[3] - hfp[2]) * (nv - 1)
    if not (gx >= -1e-9 and gx <= nu - 1 + 1e-9 and gy >= -1e-9 and gy <= nv - 1 + 1e-9):
        return np.nan, np.nan, np.nan
    i = min(max(floor_index(gx), 0), nu - 2)
    j = min(max(floor_index(gy), 0), nv - 2)
    fx = gx - i
    fy = gy - j
    z00 = hf[j, i]
    z10 = hf[j, i + 1]
    z01 = hf[j + 1, i]
    z11 = hf[j + 1, i + 1]
    w = (z00 * (1 - fx) + z10 * fx) * (1 - fy) + (z01 * (1 - fx) + z11 * fx) * fy
    wu = ((z10 - z00) * (1 - fy) + (z11 - z01) * fy) * (nu - 1) / (hfp[1] - hfp[0])
    wv = ((z01 - z00) * (1 - fx) + (z11 - z10) * fx) * (nv - 1) / (hfp[3] - hfp[2])
    return w, wu, wv


@ngjit_inline
def surface_eval(kind, fg, hf, hfp, u, v):
    """w = f(u, v) and its partials, from one call of the fused function fg; NaN w
    means a hole (partials that are not finite where w is: central differences,
    _differences). A function surface's parameter t (the time of an animation) is
    hfp[0], its box scaling hfp's HFP_IU, HFP_IV and HFP_CW (layout.py)."""
    if kind == SURF_HEIGHTFIELD:
        return heightfield_eval(hf, hfp, u, v)
    p = stack_pair()
    iu = hfp[HFP_IU]
    iv = hfp[HFP_IV]
    c = hfp[HFP_CW]
    w = fg(u * iu, v * iv, hfp[0], p) * c
    if not math.isfinite(w):
        return np.nan, np.nan, np.nan
    wu = p[0]
    wv = p[1]
    if not (math.isfinite(wu) and math.isfinite(wv)):
        wu, wv = _differences(fg, u * iu, v * iv, hfp[0], wu, wv)
    return w, wu * (c * iu), wv * (c * iv)


@ngjit_nrt_free
def _differences(fg, u, v, t, wu, wv):
    """f's partials by central differences where its formula's are not finite though f
    is: the formula's own 0/0 (the floor of sqrt(Max(0, 4 - u^2 - v^2)): sympy's
    partial there is u Heaviside(...) / sqrt(0)). A partial that is finite stays; one
    whose difference is not (f NaN beside a rim) stays NaN: a hole, as before."""
    p = stack_pair()
    if not math.isfinite(wu):
        h = DIFF_STEP * max(1.0, abs(u))
        wu = (fg(u + h, v, t, p) - fg(u - h, v, t, p)) / (2.0 * h)
    if not math.isfinite(wv):
        h = DIFF_STEP * max(1.0, abs(v))
        wv = (fg(u, v + h, t, p) - fg(u, v - h, t, p)) / (2.0 * h)
    return wu, wv


@ngjit_inline
def surface_value(kind, f, hf, hfp, u, v):
    """w = f(u, v) alone (NaN at a hole), where no partials are needed."""
    if kind == SURF_HEIGHTFIELD:
        return heightfield_eval(hf, hfp, u, v)[0]
    w = f(u * hfp[HFP_IU], v * hfp[HFP_IV], hfp[0]) * hfp[HFP_CW]
    return w if math.isfinite(w) else np.nan


@ngjit_inline
def in_domain(vp, u, v):
    eu = DOMAIN_EPS * (vp[VP_UB] - vp[VP_UA])
    ev = DOMAIN_EPS * (vp[VP_VB] - vp[VP_VA])
    return (u >= vp[VP_UA] - eu and u <= vp[VP_UB] + eu
            and v >= vp[VP_VA] - ev and v <= vp[VP_VB] + ev)


@ngjit_inline
def into_domain(vp, u, v):
    """(u, v) moved inside the domain by DOMAIN_EPS of its size where they lie on
    its edge or within in_domain's slack outside: f there is its limit from inside
    (floor(v) at the edge v = 3 of [-3, 3] is 3, the next step's height: an edge
    sample taking it drew a spike a step high along the edge)."""
    eu = DOMAIN_EPS * (vp[VP_UB] - vp[VP_UA])
    ev = DOMAIN_EPS * (vp[VP_VB] - vp[VP_VA])
    return (min(max(u, vp[VP_UA] + eu), vp[VP_UB] - eu),
            min(max(v, vp[VP_VA] + ev), vp[VP_VB] - ev))


@ngjit_nrt_free
def _clip_line(vp, u0, du, v0, dv, lo, hi):
    """Clip [lo, hi] to the parameters lam with (u0 + lam du, v0 + lam dv) inside the
    domain rectangle. Returns (lo, hi); lo > hi when the line misses it."""
    for base, slope, a, b in ((u0, du, vp[VP_UA], vp[VP_UB]), (v0, dv, vp[VP_VA], vp[VP_VB])):
        if abs(slope) < 1e-15:
            if base < a or base > b:
                return 1.0, -1.0
        else:
            l1 = (a - base) / slope
            l2 = (b - base) / slope
            lo = max(lo, min(l1, l2))
            hi = min(hi, max(l1, l2))
    return lo, hi


@ngjit_inline
def _r_interval(vp, t):
    """The r-interval of sampling plane t inside the domain rectangle (eq. 2: u = cu +
    r cb + t sb, v = cv - r sb + t cb); ra > rb when the plane misses it."""
    sb = vp[VP_SB]
    cb = vp[VP_CB]
    return _clip_line(vp, vp[VP_CU] + t * sb, cb, vp[VP_CV] + t * cb, -sb, -np.inf, np.inf)


@ngjit_inline
def column_x0(vp, col):
    """Screen x of pixel column ``col`` (DESIGN.md section 3)."""
    return (col + vp[VP_XOFF] - (vp[VP_W] - 1.0) * 0.5) / vp[VP_SCALE]


@ngjit_inline
def sample_point(kind, f, fg, hf, hfp, vp, x0, t, s_guess):
    """Surface point on column plane x = x0 and sampling plane t.

    Returns (status, evaluations, ypix, z, u, v, w, nx, ny, nz, intensity):
    ypix is the screen row counted from the bottom as a float, z the screen depth,
    (nx, ny, nz) the unit upper-side normal in screen coordinates, and intensity the
    lambert |L.N| with the light at the viewpoint. ``s_guess`` starts the
    perspective Newton iteration (the previous sample's s converges in 1-3 steps).
    """
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    cu = vp[VP_CU]
    cv = vp[VP_CV]
    cw = vp[VP_CW]
    ortho = vp[VP_ORTHO] != 0.0
    d1 = vp[VP_D1]
    d3 = vp[VP_D3]
    evals = 0
    if ortho:
        r = x0                                   # eq. (3): r = x = x0
        u = cu + r * cb + t * sb
        v = cv - r * sb + t * cb
        if not in_domain(vp, u, v):
            return S_OUTSIDE, evals, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
        u, v = into_domain(vp, u, v)
        w, wu, wv = surface_eval(kind, fg, hf, hfp, u, v)
        st, ypix, z1, nx, ny, nz, lam = ortho_point(vp, t, w, wu, wv)
        if st != S_OK:
            return st, 1, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
        return S_OK, 1, ypix, z1, u, v, w, nx, ny, nz, lam
    else:
        # Exact placement on the column plane (ERRATA 2): Pi is r = x0 (z + d3) / d1
        # with z = s sin(a) + t cos(a); solve s = f(u(r(s), t), v(r(s), t)) by
        # Newton; Gordon's point is s = 0 (eq. 9), a neighbour's s starts closer.
        r0 = x0 * (t * ca + d3) / d1             # eq. (9)
        k = x0 * sa / d1                          # dr/ds inside Pi
        s = s_guess if math.isfinite(s_guess) else 0.0
        scan_lo, scan_hi = scan_range(vp)      # where the fallback looks for the surface
        w = np.nan
        wu = 0.0
        wv = 0.0
        u = 0.0
        v = 0.0
        g = np.inf
        paper = vp[VP_PAPER] != 0.0
        if paper:
            # The paper's approximation (ERRATA 2): f at the eq. (9) point s = 0,
            # displayed in this column although it lies off Pi when alpha != 0.
            s = 0.0
            k = 0.0
        for _ in range(NEWTON_ITERS):
            u, v = _line_uv(vp, r0, k, t, s)     # eq. (2)
            if in_known_hole(vp, u, v):          # (hole_map): f is NaN there
                w = np.nan
            else:
                w, wu, wv = surface_eval(kind, fg, hf, hfp, u, v)
                evals += 1
            if not math.isfinite(w):
                if not paper and not in_domain(vp, u, v):
                    # An iterate outside the domain where f is not defined (a height
                    # field beyond its grid): a tenth of a height field's perspective
                    # samples, for planes that pass beside the grid. Only the part of
                    # the plane's line inside the domain can hold the sample: none
                    # where the line misses the domain; the root there where g
                    # changes sign between the part's ends (as where Newton leaves
                    # the domain below); else the fallback scans that part alone,
                    # not the whole line (those samples took 60 % of the evaluations)
                    ra, rb = _r_interval(vp, t)
                    scan_lo, scan_hi = _inside_part(vp, r0, k, ra, rb)
                    if not scan_lo < scan_hi:
                        return S_OUTSIDE, evals, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
                    ok, s_in, w_in, wu_in, wv_in, g_in, n_in = _root_inside(
                        kind, f, fg, hf, hfp, vp, r0, k, t, ra, rb)
                    evals += n_in
                    if ok:
                        s = s_in
                        w, wu, wv, g = w_in, wu_in, wv_in, g_in
                        u, v = _line_uv(vp, r0, k, t, s)
                break
            g = (w - cw) - s
            # Done when the point (exactly on the surface) lies within NEWTON_TOL_PX
            # pixel of Pi.
            if abs(k * g) * vp[VP_SCALE] <= NEWTON_TOL_PX or k == 0.0:
                break
            dg = k * (wu * cb - wv * sb) - 1.0
            if dg == 0.0 or not math.isfinite(dg):
                break
            s_next = s - g / dg
            if not paper and not in_domain(vp, u, v):
                # Outside the domain: give up once the next point lies outside it by
                # more than twice the step (Newton's steps shrink): the sample would
                # be dropped anyway. Saves a third of the evaluations in perspective.
                ra, rb = _r_interval(vp, t)
                r_next = r0 + k * s_next
                out = max(ra - r_next, r_next - rb)
                if out > 2.0 * abs(k * (s_next - s)) and out > 1e-9 * (1.0 + abs(r_next)):
                    # Newton may have started outside next to a root inside (at the
                    # domain's edge): look there before dropping the sample
                    ok, s_in, w, wu, wv, g, n_in = _root_inside(kind, f, fg, hf, hfp, vp, r0, k,
                                                                t, ra, rb)
                    evals += n_in
                    if not ok:
                        u, v = _line_uv(vp, r0, k, t, s_next)
                        return S_OUTSIDE, evals, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
                    s = s_in
                    u, v = _line_uv(vp, r0, k, t, s)
                    break
            s = s_next
        if not paper and (not math.isfinite(w) or abs(k * g) * vp[VP_SCALE] > NEWTON_TOL_PX):
            # Newton left the surface (a hole, or a steep rim where f_u, f_v blow
            # up): bracket a root of g(s) = f - cw - s over the range of w instead.
            s_b, n_b = _bracketed_s(kind, f, hf, hfp, vp, r0, k, t, s, scan_lo, scan_hi)
            evals += n_b
            if not math.isfinite(s_b):
                return S_HOLE, evals, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
            u, v = _line_uv(vp, r0, k, t, s_b)
            w, wu, wv = surface_eval(kind, fg, hf, hfp, u, v)
            evals += 1
            if not math.isfinite(w):
                return S_HOLE, evals, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
        if not math.isfinite(w):
            return S_HOLE, evals, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
        if not in_domain(vp, u, v):
            return S_OUTSIDE, evals, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
        ui, vi = into_domain(vp, u, v)
        if ui != u or vi != v:
            # on the edge: f's limit from inside (into_domain)
            u = ui
            v = vi
            w, wu, wv = surface_eval(kind, fg, hf, hfp, u, v)
            evals += 1
            if not math.isfinite(w):
                return S_HOLE, evals, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
        s = w - cw
        r = (u - cu) * cb - (v - cv) * sb
    if not (math.isfinite(wu) and math.isfinite(wv)):
        return S_HOLE, evals, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
    y1 = s * ca - t * sa                         # eqs. (4), (10)
    z1 = s * sa + t * ca
    if z1 + d3 <= d1:                            # z1 <= -d2: in front of the screen
        return S_BEHIND, evals, 0.0, z1, u, v, w, 0.0, 0.0, 0.0, 0.0
    y0 = y1 * d1 / (z1 + d3)
    ypix = y0 * vp[VP_SCALE] + (vp[VP_H] - 1.0) * 0.5
    if not (math.isfinite(ypix) and math.isfinite(z1)):   # f near the double's limit
        return S_HOLE, evals, 0.0, 0.0, u, v, 0.0, 0.0, 0.0, 0.0, 0.0
    nx, ny, nz = unit_normal(vp, wu, wv)
    # eq. (12): light at the viewpoint (or vp's directional light)
    lam = lambert(vp, -r, -y1, -(d3 + z1), nx, ny, nz)
    return S_OK, evals, ypix, z1, u, v, w, nx, ny, nz, lam


@ngjit_inline
def unit_normal(vp, wu, wv):
    """Eq. (11): the unit upper-side normal (-f_u, 1, -f_v) in screen coordinates."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    nx = -wu * cb + wv * sb
    ny = wu * sa * sb + ca + wv * sa * cb
    nz = -wu * ca * sb + sa - wv * ca * cb
    q = 1.0 / math.sqrt(nx * nx + ny * ny + nz * nz)
    return nx * q, ny * q, nz * q


@ngjit_inline
def ortho_point(vp, t, w, wu, wv):
    """An orthographic sample on plane t whose point (inside the domain) has f, f_u,
    f_v = w, wu, wv: (status, ypix, z, nx, ny, nz, intensity) as sample_point."""
    if not (math.isfinite(w) and math.isfinite(wu) and math.isfinite(wv)):
        return S_HOLE, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    s = w - vp[VP_CW]
    y1 = s * ca - t * sa                         # eq. (4)
    z1 = s * sa + t * ca
    ypix = y1 * vp[VP_SCALE] + (vp[VP_H] - 1.0) * 0.5
    if not (math.isfinite(ypix) and math.isfinite(z1)):
        return S_HOLE, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0     # f near the double's limit
    nx, ny, nz = unit_normal(vp, wu, wv)
    # eq. (12): the light toward the viewer (0, 0, -1), or vp's directional light
    return S_OK, ypix, z1, nx, ny, nz, lambert(vp, 0.0, 0.0, -1.0, nx, ny, nz)


@ngjit_inline
def lambert(vp, vx, vy, vz, nx, ny, nz):
    """|L.N| in [0, 1] for the unit normal N (eq. 12): L is vp's directional light
    (a unit vector), or the direction (vx, vy, vz) toward the viewpoint when that is
    zero (the headlight)."""
    if vp[VP_LX] != 0.0 or vp[VP_LY] != 0.0 or vp[VP_LZ] != 0.0:
        lam = abs(vp[VP_LX] * nx + vp[VP_LY] * ny + vp[VP_LZ] * nz)
    else:
        lam = abs(vx * nx + vy * ny + vz * nz) / math.sqrt(vx * vx + vy * vy + vz * vz)
    return min(lam, 1.0)


@ngjit
def eval_grid(kind, f, fg, fb, hf, hfp, u, v, out):
    """out[i] = (w, f_u, f_v) at (u[i], v[i]); NaN rows where the surface has a hole.
    (fb, the batch evaluator, is not used: this serves small grids.)"""
    for i in range(u.shape[0]):
        w, wu, wv = surface_eval(kind, fg, hf, hfp, u[i], v[i])
        out[i, 0] = w
        out[i, 1] = wu
        out[i, 2] = wv


@ngjit_inline
def finite_cells(vp, u_a, v_a, u_b, v_b):
    """How many cells of vp's hole map (layout.py; view.hole_map) where f may be
    finite lie in the box of cells that holds the points (u_a, v_a) and (u_b, v_b)
    and the segment between them: 0 where f is NaN all over it (as far as the map
    knows), -1 where the box leaves the map (or there is none). Four reads of the
    map's summed-area table."""
    n = vp[VP_HOLE_N]
    if n == 0.0:
        return -1.0
    su = vp[VP_HOLE_SU]
    sv = vp[VP_HOLE_SV]
    x0 = (min(u_a, u_b) - vp[VP_HOLE_U0]) * su
    x1 = (max(u_a, u_b) - vp[VP_HOLE_U0]) * su
    y0 = (min(v_a, v_b) - vp[VP_HOLE_V0]) * sv
    y1 = (max(v_a, v_b) - vp[VP_HOLE_V0]) * sv
    if not (x0 >= 0.0 and x1 < n and y0 >= 0.0 and y1 < n):
        return -1.0
    m = int(n) + 1
    k0 = int(x0)
    k1 = int(x1) + 1
    i0 = int(y0) * m
    i1 = (int(y1) + 1) * m
    return (vp[VP_SIZE + i1 + k1] - vp[VP_SIZE + i0 + k1] - vp[VP_SIZE + i1 + k0]
            + vp[VP_SIZE + i0 + k0])


@ngjit_inline
def in_known_hole(vp, u, v):
    """Whether f is NaN at (u, v) as far as vp's hole map knows: f need not be
    evaluated there."""
    return finite_cells(vp, u, v, u, v) == 0.0


@ngjit_inline
def _line_uv(vp, r0, k, t, s):
    """(u, v) of the point at height s on the line of plane t inside Pi, where
    r = r0 + k s (eq. 2)."""
    r = r0 + k * s
    return (vp[VP_CU] + r * vp[VP_CB] + t * vp[VP_SB],
            vp[VP_CV] - r * vp[VP_SB] + t * vp[VP_CB])


@ngjit_nrt_free
def _g_at(kind, f, hf, hfp, vp, r0, k, t, s):
    """(g(s), evaluations): g = f(u(s), v(s)) - cw - s on the line of plane t inside
    Pi, NaN at a hole, without evaluating f (0 evaluations) where the hole map knows
    one."""
    u, v = _line_uv(vp, r0, k, t, s)
    if in_known_hole(vp, u, v):
        return np.nan, 0
    w = surface_value(kind, f, hf, hfp, u, v)
    return w - vp[VP_CW] - s, 1


@ngjit_inline
def bracket_ends(kind, f, hf, hfp, vp, r0, k, t, ra, rb):
    """The part of plane t's line inside Pi (k != 0) that lies inside the domain (r in
    [ra, rb]) and inside the scan range, s from a to b, and g at its ends: an end at
    the scan range's bottom (top) has g > 0 (< 0) without evaluating f there.
    Returns (a, b, g(a), g(b), evaluations); a >= b (and no evaluation) where the part
    is empty."""
    a, b = _inside_part(vp, r0, k, ra, rb)
    if not a < b:
        return a, b, 1.0, -1.0, 0
    s_lo, s_hi = scan_range(vp)
    evals = 0
    ga = 1.0
    if a > s_lo:
        ga, ev = _g_at(kind, f, hf, hfp, vp, r0, k, t, a)
        evals += ev
    gb = -1.0
    if b < s_hi:
        gb, ev = _g_at(kind, f, hf, hfp, vp, r0, k, t, b)
        evals += ev
    return a, b, ga, gb, evals


@ngjit_inline
def _inside_part(vp, r0, k, ra, rb):
    """The heights s from lo to hi of the part of plane t's line inside Pi (r = r0 + k
    s, k != 0) whose r lies in [ra, rb] (the domain) and whose s lies in scan_range;
    lo >= hi where there is none."""
    if ra > rb or k == 0.0:
        return 0.0, 0.0
    s1 = (ra - r0) / k
    s2 = (rb - r0) / k
    s_lo, s_hi = scan_range(vp)
    return max(min(s1, s2), s_lo), min(max(s1, s2), s_hi)


@ngjit_nrt_free
def _root_inside(kind, f, fg, hf, hfp, vp, r0, k, t, ra, rb):
    """The root of g on the part of plane t's line inside Pi that lies inside the
    domain (r in [ra, rb]) and inside the scan range, where Newton's iterates left
    the domain. Only a sign change of g between that part's ends counts; an end at
    the scan range's bottom (top) has g > 0 (< 0) without evaluating f there.
    Safeguarded Newton inside the bracket, NEWTON_ITERS steps at most (a pole's sign
    change does not converge). Returns (found, s, w, wu, wv, g, evaluations)."""
    if ra > rb or k == 0.0:
        return False, 0.0, np.nan, 0.0, 0.0, np.inf, 0
    a, b, ga, gb, evals = bracket_ends(kind, f, hf, hfp, vp, r0, k, t, ra, rb)
    if not a < b:
        return False, 0.0, np.nan, 0.0, 0.0, np.inf, 0
    if not (math.isfinite(ga) and math.isfinite(gb)) or (ga >= 0.0) == (gb >= 0.0):
        return False, 0.0, np.nan, 0.0, 0.0, np.inf, evals
    s_lo, s_hi = scan_range(vp)
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    s = a - ga * (b - a) / (gb - ga) if (a > s_lo and b < s_hi) else 0.5 * (a + b)
    w = np.nan
    wu = 0.0
    wv = 0.0
    g = np.inf
    for _ in range(NEWTON_ITERS):
        u, v = _line_uv(vp, r0, k, t, s)
        w, wu, wv = surface_eval(kind, fg, hf, hfp, u, v)
        evals += 1
        if not math.isfinite(w):
            return False, 0.0, np.nan, 0.0, 0.0, np.inf, evals
        g = (w - vp[VP_CW]) - s
        if abs(k * g) * vp[VP_SCALE] <= NEWTON_TOL_PX:
            return True, s, w, wu, wv, g, evals
        if (g >= 0.0) == (ga >= 0.0):
            a = s
            ga = g
        else:
            b = s
        dg = k * (wu * cb - wv * sb) - 1.0
        s_n = s - g / dg if dg != 0.0 else np.nan
        if not (s_n > a and s_n < b):          # NaN too: bisect
            s_n = 0.5 * (a + b)
        s = s_n
    # no convergence: a pole (tan), where g changes sign through infinity
    return False, 0.0, np.nan, 0.0, 0.0, np.inf, evals


@ngjit_inline
def scan_range(vp):
    """(s_lo, s_hi): the heights (relative to the centre) a scan for the surface on a
    perspective plane's line searches: the range of f on the fitting grid, with a
    quarter of it to spare on each side."""
    spare = 0.25 * (vp[VP_FHI] - vp[VP_FLO]) + 1e-9
    return vp[VP_FLO] - spare - vp[VP_CW], vp[VP_FHI] + spare - vp[VP_CW]


@ngjit_nrt_free
def _bracketed_s(kind, f, hf, hfp, vp, r0, k, t, s_near, s_lo, s_hi):
    """The root of g nearest ``s_near``, found by scanning s from s_lo to s_hi (the
    range of f on the fitting grid with a quarter of it to spare on each side,
    scan_range; or the part of it inside the domain), about one point per
    SCAN_PIXELS of the segment's length on screen, then bisecting. NaN when g has no
    sign change between two finite values (the line meets only holes). Returns (s,
    evaluations)."""
    # a line that the hole map knows is a hole all along: nothing to scan
    pad = 1e-9 * (s_hi - s_lo + 1.0)
    u_a, v_a = _line_uv(vp, r0, k, t, s_lo - pad)
    u_b, v_b = _line_uv(vp, r0, k, t, s_hi + pad)
    if finite_cells(vp, u_a, v_a, u_b, v_b) == 0.0:
        return np.nan, 0
    seg_px = abs(k) * (s_hi - s_lo) * vp[VP_SCALE]
    n = min(SCAN_MAX, max(SCAN_MIN, ceil_index(seg_px / SCAN_PIXELS) + 1))
    ds = (s_hi - s_lo) / (n - 1)
    evals = 0
    best_a = np.nan
    best_b = np.nan
    ga_best = np.nan
    prev_s = s_lo
    prev_g, ev = _g_at(kind, f, hf, hfp, vp, r0, k, t, s_lo)
    evals += ev
    for i in range(1, n):
        cur_s = s_lo + i * ds
        cur_g, ev = _g_at(kind, f, hf, hfp, vp, r0, k, t, cur_s)
        evals += ev
        # the pair to test for a sign change; where f is finite at one end only (the
        # domain's edge, or a hole's), the finite part's end, located by bisection,
        # stands in for the other: a root just inside an edge is found too
        pa = prev_s
        pga = prev_g
        pb = cur_s
        pgb = cur_g
        prev_fin = math.isfinite(prev_g)
        if prev_fin != math.isfinite(cur_g):
            fin_s, fin_g, nan_s = (prev_s, prev_g, cur_s) if prev_fin else (cur_s, cur_g, prev_s)
            for _ in range(EDGE_BISECT):
                m = 0.5 * (fin_s + nan_s)
                gm, ev = _g_at(kind, f, hf, hfp, vp, r0, k, t, m)
                evals += ev
                if math.isfinite(gm):
                    fin_s = m
                    fin_g = gm
                else:
                    nan_s = m
            if prev_fin:
                pb = fin_s
                pgb = fin_g
            else:
                pa = fin_s
                pga = fin_g
        if math.isfinite(pga) and math.isfinite(pgb) and (pga >= 0.0) != (pgb >= 0.0):
            mid = 0.5 * (pa + pb)
            if not math.isfinite(best_a) or abs(mid - s_near) < abs(0.5 * (best_a + best_b) - s_near):
                best_a = pa
                best_b = pb
                ga_best = pga
        prev_s = cur_s
        prev_g = cur_g
    if not math.isfinite(best_a):
        return np.nan, evals
    a = best_a
    b = best_b
    ga = ga_best
    tol = 1e-4 / (vp[VP_SCALE] * max(abs(k), 1e-12))
    for _ in range(BISECT_ITERS):
        m = 0.5 * (a + b)
        gm, ev = _g_at(kind, f, hf, hfp, vp, r0, k, t, m)
        evals += ev
        if not math.isfinite(gm):
            # a hole inside the bracket: keep the half next to the finite end a
            b = m
        elif (gm >= 0.0) == (ga >= 0.0):
            a = m
            ga = gm
        else:
            b = m
        if abs(k * (b - a)) * vp[VP_SCALE] <= 1e-4 and abs(b - a) <= tol:
            break
    return a if math.isfinite(ga) else np.nan, evals

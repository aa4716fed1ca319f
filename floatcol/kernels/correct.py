"""Problem detection and the cubic spline of Gordon section 5 (App. A.2 Problem()).

Everything here reads two successive samples of one column (attribute vectors, see
layout.A_*) and the view; the column pass (column.py) decides what to sample next.

The curve that a column plane Pi cuts from the surface is handled through its screen
row Y(t) as a function of the sampling plane t. The view vector V from a sample toward
the viewpoint lies in Pi, so V.N_Pi = V.N, and its sign is the sign of dY/dt: a ridge
(L.N_Pi changing sign, App. A.2 test 1) is an extremum of Y between the samples, and
the spline's top (eq. 22, tangent parallel to the view direction) is where dY/dt = 0.
In orthographic projection Y = s cos(a) - t sin(a), so the Hermite cubic of Y is
cos(a) times that of s (eqs. 13-17) minus a linear term, and dY/dt = 0 is exactly
p'(t) = tan(a) of eq. (22). In perspective (the paper's last paragraph of 5.2) the
same construction holds with N_Pi taken against Pi's normal (A, B, C) of eq. (8) and
V pointing from each sample toward the viewpoint.
"""
import math

import numpy as np

from ._jit import ngjit_inline, ngjit_nrt_free
from .layout import (
    A_BUMP, A_I, A_NX, A_NY, A_NZ, A_SLOPE, A_T, A_U, A_V, A_VN, A_W, A_Y, A_Z, DETECT_BUMP,
    DETECT_JUMP, VP_CA, VP_CB, VP_D1, VP_D3, VP_H, VP_JUMP, VP_LX, VP_LY, VP_LZ,
    VP_ORTHO, VP_SA, VP_SB, VP_SCALE,
)
from .sample import lambert, surface_value

#: A wall (end of section 5): a span whose screen rows jump by more than WALL_MIN_PX and
#: by more than WALL_RATIO times what the slopes at its ends predict. The span is
#: halved while that holds, down to 2**-WALL_DEPTH of it; what still jumps is a wall.
WALL_MIN_PX = 1.5
WALL_RATIO = 4.0
WALL_DEPTH = 12
WALL_SEARCH = 16.0     # the wall's direction: its jump is sought up to this many times
WALL_ASIDE = 2.0       # the offset along a parallel line WALL_ASIDE pixels aside
WALL_BISECT = 30
WALL_REAL = 0.5        # wall_jump(): the part of the bracket's height difference f must jump

#: A ridge is corrected only when its spline top may reach a new pixel row; the
#: spline's error is allowed this many pixels.
RIDGE_MARGIN_PX = 0.5


@ngjit_inline
def probe(vp, x0, a):
    """(V.N / |V|, bump scalar, dY/dt) of sample ``a`` on column plane x = x0.

    V points from the sample toward the viewpoint (orthographic: (0, 0, -1)), N is the
    unit upper-side normal. The bump scalar is n_Pi . (L x N) = n_Pi . (L x N_Pi)
    (section 5.3; the part of N or L across Pi drops out), with L = V for the
    headlight. dY/dt is the slope of the screen row, in pixels per unit of t, along
    the curve inside Pi, whose tangent is n_Pi x N.
    """
    nx = a[A_NX]
    ny = a[A_NY]
    nz = a[A_NZ]
    if vp[VP_ORTHO] != 0.0:
        return probe_ortho(vp, ny, nz)
    return probe_persp(vp, x0, a[A_Y], a[A_Z], nx, ny, nz)


@ngjit_inline
def probe_persp(vp, x0, ypix, z, nx, ny, nz):
    """probe() in perspective, of a sample at screen row ypix and depth z with the unit
    normal (nx, ny, nz) (for the batched planes too: column._batch_points)."""
    scale = vp[VP_SCALE]
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    d1 = vp[VP_D1]
    y0 = (ypix - (vp[VP_H] - 1.0) * 0.5) / scale
    vx = -x0
    vy = -y0
    vz = -d1
    px = d1                       # Pi through the viewpoint: d1 x - x0 z = x0 d3 (eq. 8)
    pz = -x0
    vlen = math.sqrt(vx * vx + vy * vy + vz * vz)
    vn = (vx * nx + vy * ny + vz * nz) / vlen
    if vp[VP_LX] != 0.0 or vp[VP_LY] != 0.0 or vp[VP_LZ] != 0.0:
        lx = vp[VP_LX]
        ly = vp[VP_LY]
        lz = vp[VP_LZ]
    else:
        lx = vx
        ly = vy
        lz = vz
    # n_Pi . (L x N) with n_Pi = (px, 0, pz)
    bump = px * (ly * nz - lz * ny) + pz * (lx * ny - ly * nx)
    # tangent T = n_Pi x N (its x part is not needed), and how fast t and the
    # screen row change along it
    ty = pz * nx - px * nz
    tz = px * ny
    dt = -ty * sa + tz * ca                       # t = -y sin(a) + z cos(a), eq. (1)
    q = z + vp[VP_D3]                             # y0 = y1 d1 / (z1 + d3), eq. (10)
    y1 = y0 * q / d1
    dy = d1 * (ty * q - y1 * tz) / (q * q)
    if dt == 0.0:
        slope = math.copysign(1e30, dy)
    else:
        slope = dy / dt * scale
    return vn, bump, slope


@ngjit_inline
def probe_ortho(vp, ny, nz):
    """probe() in orthographic projection, of a unit normal (., ny, nz): V = (0, 0, -1)
    and n_Pi = (1, 0, 0) (no root, no division but the slope's: this runs for every
    sample; for the batched planes in _batch_planes' SIMD loop, vp a tuple there)."""
    if vp[VP_LX] != 0.0 or vp[VP_LY] != 0.0 or vp[VP_LZ] != 0.0:
        bump = vp[VP_LY] * nz - vp[VP_LZ] * ny
    else:
        bump = ny
    dt = nz * vp[VP_SA] + ny * vp[VP_CA]
    return -nz, bump, (-nz / dt * vp[VP_SCALE] if dt != 0.0 else math.copysign(1e30, -nz))


@ngjit_nrt_free
def hermite_extremum(ya, yb, ma, mb, h):
    """Fraction tau in (0, 1) where the cubic through (0, ya), (1, yb) with slopes
    ma, mb (per unit of t, the interval being h long) has zero slope: eqs. (13)-(17)
    in normalised form, and eq. (22) solved with p'(tau) = 0. Returns (tau, p(tau))."""
    m0 = ma * h
    m1 = mb * h
    a = 2.0 * (ya - yb) + m0 + m1          # eq. (17), tau in [0, 1]
    b = 3.0 * (yb - ya) - 2.0 * m0 - m1
    c = m0
    # 3a tau^2 + 2b tau + c = 0  (eq. 22)
    tau = 0.5
    if abs(a) <= 1e-12 * (abs(b) + abs(c) + 1e-300):
        if b != 0.0:
            tau = -c / (2.0 * b)
    else:
        disc = b * b - 3.0 * a * c
        if disc >= 0.0:
            q = -(b + math.copysign(math.sqrt(disc), b))
            r1 = q / (3.0 * a)
            r2 = c / q if q != 0.0 else r1
            if 0.0 <= r1 <= 1.0:
                tau = r1
            elif 0.0 <= r2 <= 1.0:
                tau = r2
    if not (tau >= 0.0 and tau <= 1.0):
        tau = 0.5
    y = ((a * tau + b) * tau + c) * tau + ya
    return tau, y


@ngjit_inline
def ridge_between(vp, x0, a, b, run_lo, run_hi):
    """(Samples carry A_VN, A_BUMP, A_SLOPE from probe.) App. A.2 test 1: V.N changes sign between samples a and b, and the spline's
    extremum may uncover a new pixel row above run_hi or below run_lo (a ridge
    hidden behind nearer surface needs no correction)."""
    if not a[A_VN] * b[A_VN] < 0.0:
        return False
    _, ye = hermite_extremum(a[A_Y], b[A_Y], a[A_SLOPE], b[A_SLOPE], b[A_T] - a[A_T])
    top = max(ye, a[A_Y], b[A_Y]) + RIDGE_MARGIN_PX
    bot = min(ye, a[A_Y], b[A_Y]) - RIDGE_MARGIN_PX
    return new_rows_seen(top, bot, run_lo, run_hi, vp[VP_H])


@ngjit_inline
def new_rows_seen(top, bot, run_lo, run_hi, H):
    """Whether the screen rows from bot to top (a span, or its spline) reach a pixel
    row that the floating interval [run_lo, run_hi] does not cover, inside the
    picture: rows -1 to H (one to spare on each side for the antialiasing's partly
    covered pixels). A part of the surface beyond the picture's top or bottom gets no
    correction: nothing of it is seen. Surfaces with poles spent most of their samples
    there (320x240: tan(u v) 15.4 times the samples of its uncorrected render, log(u v)
    2.6 times; 1.29 and 1.64 times since)."""
    up = math.floor(top) > math.floor(run_hi) and top >= -1.0 and run_hi < H
    down = math.ceil(bot) < math.ceil(run_lo) and bot <= H and run_lo > -1.0
    return up or down


@ngjit_inline
def shading_problem(vp, x0, a, b, detect, run_lo, run_hi):
    """App. A.2 tests 2 and 3 on a span that paints at least one new row: the
    intensity jumps by more than VP_JUMP, or the samples straddle a bump (section
    5.3: (L x N_Pi)0 . (L x N_Pi)1 < 0 while L.N keeps its sign)."""
    y = b[A_Y]
    if not new_rows_seen(y, y, run_lo, run_hi, vp[VP_H]):
        return False
    if detect & DETECT_JUMP and abs(b[A_I] - a[A_I]) > vp[VP_JUMP]:
        return True
    if detect & DETECT_BUMP:
        if a[A_VN] * b[A_VN] > 0.0 and a[A_BUMP] * b[A_BUMP] < 0.0:
            return True
    return False


@ngjit_inline
def wall_between(a, b, run_lo, run_hi, searching, H):
    """A discontinuity between samples a and b (end of section 5: "a big jump in the
    y-values" where the normals do not explain it): the rows jump by more than
    WALL_MIN_PX and WALL_RATIO times what the smaller end slope predicts, on a span
    that paints new rows. While ``searching`` (halving a span found so) the jump alone
    counts: samples that land on a discontinuity may carry any slope."""
    dy = abs(b[A_Y] - a[A_Y])
    if dy <= WALL_MIN_PX:
        return False
    y = b[A_Y]
    if not new_rows_seen(y, y, run_lo, run_hi, H):
        return False
    if searching:
        return True
    # the smaller slope: a sample that lands on the jump itself may carry a huge one
    pred = min(abs(a[A_SLOPE]), abs(b[A_SLOPE])) * abs(b[A_T] - a[A_T])
    return dy > WALL_RATIO * pred


@ngjit_nrt_free
def _locate_jump(kind, f, hf, hfp, u0, v0, u1, v1):
    """Bisect the segment (u0, v0) -> (u1, v1) for the jump of f: keep the half whose
    ends differ more. Returns (fraction along the segment, the jump left across the
    final bracket); NaN where f has a hole there."""
    lo = 0.0
    hi = 1.0
    f_lo = surface_value(kind, f, hf, hfp, u0, v0)
    f_hi = surface_value(kind, f, hf, hfp, u1, v1)
    for _ in range(WALL_BISECT):
        m = 0.5 * (lo + hi)
        fm = surface_value(kind, f, hf, hfp, u0 + m * (u1 - u0), v0 + m * (v1 - v0))
        if not (math.isfinite(fm) and math.isfinite(f_lo) and math.isfinite(f_hi)):
            return np.nan, 0.0
        if abs(fm - f_lo) >= abs(f_hi - fm):
            hi = m
            f_hi = fm
        else:
            lo = m
            f_lo = fm
    return 0.5 * (lo + hi), abs(f_hi - f_lo)


@ngjit_nrt_free
def wall_jump(kind, f, hf, hfp, a, b):
    """Where f jumps between the ground points of samples a and b, the tight bracket a
    wall's halving leaves (_locate_jump's fraction of the way from a to b, 0 where a
    hole stops the search), and whether it does: more than WALL_REAL of their
    heights' difference left across its final bracket (a hole there counts). A
    continuous f leaves nothing: the bracket's rows differ because the column's curve
    is steep on the screen there (a fold of the surface seen edge-on, near a
    silhouette), not because f jumps, and its samples' own normals light it (a wall's
    normal, horizontal, had drawn streaks of a wrong light down such columns)."""
    m, left_over = _locate_jump(kind, f, hf, hfp, a[A_U], a[A_V], b[A_U], b[A_V])
    if not math.isfinite(m):
        return 0.0, True
    return m, left_over > WALL_REAL * abs(b[A_W] - a[A_W])


@ngjit_nrt_free
def wall_normal(kind, f, hf, hfp, vp, a, b, m):
    """Screen-coordinate unit normal of the wall between the tight bracket a, b, whose
    jump lies a fraction m of the way from a to b (wall_jump).

    The wall is vertical; its direction on the ground comes from the same jump found
    on a parallel line WALL_ASIDE pixels aside. Its normal faces the viewer's side.
    Falls back to facing the viewer straight along the column when the jump is not
    found there (the wall ends)."""
    ca = vp[VP_CA]
    sa = vp[VP_SA]
    cb = vp[VP_CB]
    sb = vp[VP_SB]
    jump = abs(b[A_W] - a[A_W])
    # A point of the wall line: a and b lie on either side of it (in perspective far
    # apart: inside Pi the ground point moves along r with the height, by dr/ds
    # times the jump).
    pu = a[A_U] + m * (b[A_U] - a[A_U])
    pv = a[A_V] + m * (b[A_V] - a[A_V])
    if vp[VP_ORTHO] != 0.0:
        delta = WALL_ASIDE / vp[VP_SCALE]
    else:
        delta = WALL_ASIDE * (a[A_Z] + vp[VP_D3]) / (vp[VP_D1] * vp[VP_SCALE])
    sgn = 1.0 if b[A_T] > a[A_T] else -1.0
    du = sb * sgn                     # ground direction from a to b (t, eq. 2)
    dv = cb * sgn
    eu = cb                           # ground direction of r
    ev = -sb
    nu = -du
    nv = -dv
    # windows of growing width along the column's direction: a narrow one first,
    # where the smooth part of f varies less than the jump
    lim = delta
    found = False
    along = 0.0
    while lim <= WALL_SEARCH * delta * 1.0001:
        qu = pu + delta * eu - lim * du
        qv = pv + delta * ev - lim * dv
        m2, left_over = _locate_jump(kind, f, hf, hfp, qu, qv, qu + 2.0 * lim * du,
                                     qv + 2.0 * lim * dv)
        if math.isfinite(m2) and left_over > 0.5 * jump:
            along = (2.0 * m2 - 1.0) * lim
            found = True
            break
        lim *= 2.0
    if found:
        tu = delta * eu + along * du      # the wall's direction on the ground
        tv = delta * ev + along * dv
        tn = math.sqrt(tu * tu + tv * tv)
        nu = tv / tn
        nv = -tu / tn
        if nu * du + nv * dv > 0.0:   # face the viewer's side (back along the column)
            nu = -nu
            nv = -nv
    # world (nu, 0, nv) to screen coordinates, eqs. (1)-(2)
    tc = nu * sb + nv * cb
    return nu * cb - nv * sb, -tc * sa, tc * ca


@ngjit_nrt_free
def lambert_at(vp, x0, a, nx, ny, nz):
    """|L.N| of unit normal N at sample a's place (eq. 12, or the directional light);
    the view direction there is -(x0, y0, d1), as in probe."""
    if vp[VP_ORTHO] != 0.0:
        return lambert(vp, 0.0, 0.0, -1.0, nx, ny, nz)
    y0 = (a[A_Y] - (vp[VP_H] - 1.0) * 0.5) / vp[VP_SCALE]
    return lambert(vp, -x0, -y0, -vp[VP_D1], nx, ny, nz)

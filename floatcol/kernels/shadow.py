"""Cast shadows of a directional light (Gordon section 6.2.1): floating-horizon sweeps
over the (u, v) domain along planes through the light.

For a directional light the planes through it are parallel; each meets the domain in
a line along the light's ground direction g. Along such a line, with sigma the
distance toward the light and tan(theta) the light's rise per unit of ground, a point
p is in the shadow of the upper side where some point q farther toward the light has

    f(q) - sigma_q tan(theta)  >  f(p) - sigma_p tan(theta)

(the light's ray from p passes under the surface at q): the running maximum of
H = f - sigma tan(theta), swept from the light's side, is the floating horizon seen
from the light. Its running minimum does the same for the lower side (a light from
below). A hole casts nothing; a wall (a jump of f) casts its shadow as any slope.

One line of the shadow texture per parallel plane, in parallel: each keeps its own
maximum and minimum (no shared scratch).

Soft shadows (a light of angular radius rho, a disk): the steepest rise of H from each
texel to its line's texels beyond it (horizon_slopes, by the line's upper convex hull
kept on a stack from the light's side: O(n) a line) gives the angle phi of the
horizon toward the light above the point and the distance D of what makes it; the
part of the disk below it is _blocked((phi - theta) / rho) (horizon mapping, Max
1988). Across the light's direction the disk is cut in strips, each taking the
horizon of the point displaced by D times its angle (soft_shadow): the lateral
penumbra grows with the occluder's distance as the other.
"""
import math

import numpy as np
from numba import prange

from ._jit import array_ptr, ngjit, ngjit_inline, ngjit_parallel
from .index import floor_index
from .layout import E_FLAG, E_SEEN, G_NX, G_NY, G_NZ, G_U, G_V, G_W, HFP_CW, HFP_IU, HFP_IV
from .sample import surface_value

#: "no horizon": finite, so that interpolating it with a real height stays finite
NONE = 1e30
#: horizon_slopes' "nothing beyond": a rise no surface makes (steeper than 89.99994
#: degrees), finite for the lookup's averages
SLOPE_NONE = 1e6
#: texels whose heights differ by more than this many texels of ground (a slope
#: steeper than 84 degrees) have a wall between them
WALL = 10.0


@ngjit_inline
def _cell(a, y, x):
    """(i, j, fy, fx): the texel cell of a[k] (ny, nx) holding the float indices (y, x),
    clamped to its edges (index.py: defined for any double), and the place in it."""
    i = min(max(floor_index(y), 0), a.shape[1] - 2)
    j = min(max(floor_index(x), 0), a.shape[2] - 2)
    return i, j, min(max(y - i, 0.0), 1.0), min(max(x - j, 0.0), 1.0)


@ngjit_inline
def _bilinear(a, k, y, x):
    """a[k] (ny, nx) at the float indices (y, x), clamped to its edges."""
    i, j, fy, fx = _cell(a, y, x)
    return ((a[k, i, j] * (1.0 - fx) + a[k, i, j + 1] * fx) * (1.0 - fy)
            + (a[k, i + 1, j] * (1.0 - fx) + a[k, i + 1, j + 1] * fx) * fy)


@ngjit_inline
def _texels_rise(hsurf, k, i, j):
    """The highest less the lowest H of the surface's texels (i..i+1, j..j+1) of
    hsurf[k] (-inf where none is the surface's)."""
    lo = np.inf
    hi = -np.inf
    for di in range(2):
        for dj in range(2):
            hs = hsurf[k, i + di, j + dj]
            if hs == hs:
                lo = min(lo, hs)
                hi = max(hi, hs)
    return hi - lo


@ngjit_inline
def _own_depth(hext, hsurf, k, y, x, upper, hp, h):
    """How far below its own layer's horizon the surface lies around (y, x): the
    texels' own depths (hmax - H for the upper side, H - hmin for the lower) averaged
    bilinearly over the neighbours where the surface is (NaN where none is). Depths,
    not horizons, are interpolated: a lit slope's neighbours are all above their own
    horizons, whatever their heights. Where a wall stands between the texels (their
    heights differ by more than WALL texels of ground: its top and its foot) only
    those on the point's side of it count (H within half the wall of the point's hp):
    the top edge of a cliff is not darkened by its foot's shadow."""
    i, j, fy, fx = _cell(hsurf, y, x)
    rise = _texels_rise(hsurf, k, i, j)
    near = 0.5 * rise if rise > WALL * h else np.inf
    acc = 0.0
    wsum = 0.0
    for di in range(2):
        for dj in range(2):
            hs = hsurf[k, i + di, j + dj]
            if hs == hs and abs(hs - hp) <= near:
                wgt = (fy if di else 1.0 - fy) * (fx if dj else 1.0 - fx)
                d = hext[k, i + di, j + dj] - hs if upper else hs - hext[k, i + di, j + dj]
                acc += wgt * d
                wsum += wgt
    return acc / wsum if wsum > 1e-9 else np.nan


@ngjit_inline
def point_shadow(s, u, v, w, nx, ny, nz, light, hmax, hmin, hsurf, layer, gu, gv, tan_theta,
                 s0, t0, h, grazing, bias):
    """How much of the light a point of layer ``layer`` misses (1 in shadow, 0 lit,
    between at an edge): its side s (+1 upper, -1 lower) is seen, (nx, ny, nz) its
    upper-side normal and ``light`` the light's direction, both in screen coordinates;
    (u, v, w) the point in the box, w from the texture's origin (its heights'; the
    view's w_origin, layout.py G_W). Attached where the seen side faces away from the
    light; cast where it lies under its own layer's horizon or between another layer's
    extremes (shadow_lookup)."""
    nn = math.sqrt(nx * nx + ny * ny + nz * nz)
    facing = s * (nx * light[0] + ny * light[1] + nz * light[2]) / nn if nn > 0.0 else 0.0
    if not facing > 0.0:
        return 1.0                              # attached
    n_layers = hmax.shape[0]
    if n_layers == 0:
        return 0.0
    rise = abs(tan_theta) * h
    width_m = max(rise, 1e-300)
    along = u * gu + v * gv
    ps = (along - s0) / h
    pt = (-u * gv + v * gu - t0) / h
    hp = w - along * tan_theta
    margin = _own_depth(hmax if s > 0.0 else hmin, hsurf, layer, pt, ps, s > 0.0, hp, h)
    if margin != margin:            # no texel of the surface around: the horizon
        if s > 0.0:
            margin = _bilinear(hmax, layer, pt, ps) - hp
        else:
            margin = hp - _bilinear(hmin, layer, pt, ps)
    margin = _crossed(hmax, hmin, layer, pt, ps, hp, margin)
    bs = bias * rise if facing < grazing else 0.0
    return min(max((margin - bs) / width_m + 0.5, 0.0), 1.0)


@ngjit_inline
def _crossed(hmax, hmin, layer, pt, ps, hp, margin):
    """max(margin, how far the point at H = hp lies between another layer's extremes
    beyond it (the light's ray crosses that layer))."""
    for m in range(hmax.shape[0]):
        if m != layer:
            crossed = min(_bilinear(hmax, m, pt, ps) - hp, hp - _bilinear(hmin, m, pt, ps))
            margin = max(margin, crossed)
    return margin


@ngjit_inline
def _blocked(x):
    """The part of a disk of radius 1 below a chord x above its centre."""
    x = min(max(x, -1.0), 1.0)
    return (x * math.sqrt(1.0 - x * x) + math.asin(x)) / math.pi + 0.5


@ngjit_inline
def _half_chords(x):
    """The integral of sqrt(1 - x^2) from 0 to x (x in [-1, 1])."""
    x = min(max(x, -1.0), 1.0)
    return 0.5 * (x * math.sqrt(1.0 - x * x) + math.asin(x))


@ngjit_inline
def _strip_blocked(x0, x1, y):
    """The area of the unit disk's strip x0 <= x <= x1 below the line at height y."""
    if y >= 1.0:
        return 2.0 * (_half_chords(x1) - _half_chords(x0))
    if y <= -1.0:
        return 0.0
    c = math.sqrt(1.0 - y * y)        # the line cuts the disk's edge at x = +-c
    a = max(x0, -c)
    b = min(x1, c)
    area = 0.0
    if b > a:                         # chords from -s(x) to y
        area += y * (b - a) + _half_chords(b) - _half_chords(a)
    if y > 0.0:                       # beyond +-c the whole chord lies below
        if x0 < -c:
            area += 2.0 * (_half_chords(min(x1, -c)) - _half_chords(x0))
        if x1 > c:
            area += 2.0 * (_half_chords(x1) - _half_chords(max(x0, c)))
    return area


@ngjit_inline
def _own_slope(slopes, k, hsurf, layer, y, x):
    """slopes[k] averaged bilinearly over the texels around (y, x) where layer's
    surface is (NaN where none is)."""
    i, j, fy, fx = _cell(hsurf, y, x)
    acc = 0.0
    wsum = 0.0
    for di in range(2):
        for dj in range(2):
            if hsurf[layer, i + di, j + dj] == hsurf[layer, i + di, j + dj]:
                wgt = (fy if di else 1.0 - fy) * (fx if dj else 1.0 - fx)
                acc += wgt * slopes[k, i + di, j + dj]
                wsum += wgt
    return acc / wsum if wsum > 1e-9 else np.nan


@ngjit_inline
def _occluder(slopes, k, hsurf, layer, y, x):
    """(H, D): the height H = f - sigma tan(theta) and the ground distance of what
    makes the horizon (slopes[k], horizon_slopes') of the texels around (y, x),
    averaged bilinearly over those of layer's surface with something beyond; (NaN, 0)
    where none has."""
    i, j, fy, fx = _cell(hsurf, y, x)
    acc_h = 0.0
    acc_d = 0.0
    wsum = 0.0
    for di in range(2):
        for dj in range(2):
            hs = hsurf[layer, i + di, j + dj]
            d = slopes[k + 2, i + di, j + dj]
            if hs == hs and d > 0.0:
                wgt = (fy if di else 1.0 - fy) * (fx if dj else 1.0 - fx)
                acc_h += wgt * (hs + slopes[k, i + di, j + dj] * d)
                acc_d += wgt * d
                wsum += wgt
    if wsum > 1e-9:
        return acc_h / wsum, acc_d / wsum
    return np.nan, 0.0


@ngjit_inline
def _wall(hsurf, layer, y, x, h):
    """Whether the texels of layer's surface around (y, x) straddle a wall."""
    i, j, _, _ = _cell(hsurf, y, x)
    return _texels_rise(hsurf, layer, i, j) > WALL * h


#: vertical strips of the light's disk, each with its own horizon, where the
#: penumbra is wider than a texel across the light's direction
STRIPS = 8
#: the lateral spread (texels) below which the disk takes one horizon
STRIP_SPREAD = 0.5


@ngjit_inline
def _disk_below(slopes, k, hsurf, layer, pt, ps, hp, m, D, sgn, theta, tan_theta, rho, h):
    """The part of the light's disk below the horizon of a point at texel (pt, ps) whose
    H is hp (soft_shadow's): the horizon rising at m over the light's ray, made at
    ground distance D (slopes[k], layer's surface: _occluder). Where the disk's rays
    spread across the light over more than STRIP_SPREAD texels at that distance, it is
    cut in STRIPS strips, each with the horizon of the line so displaced (a line whose
    occluder is much nearer than D keeps m)."""
    spread = D * math.tan(rho) / (math.cos(theta) * h)      # across the light, in texels
    if not spread > STRIP_SPREAD:
        return _blocked(sgn * (math.atan(tan_theta + m) - theta) / rho)
    area = 0.0
    dx = 2.0 / STRIPS
    for q in range(STRIPS):
        x0 = -1.0 + q * dx
        hk, dk = _occluder(slopes, k, hsurf, layer, pt + (x0 + 0.5 * dx) * spread, ps)
        if hk != hk:
            mk = -sgn * SLOPE_NONE                   # nothing beyond: the strip is lit
        elif dk < 0.5 * D:
            mk = m
        else:
            mk = (hk - hp) / dk
        area += _strip_blocked(x0, x0 + dx, sgn * (math.atan(tan_theta + mk) - theta) / rho)
    return min(area / math.pi, 1.0)


@ngjit_inline
def soft_shadow(s, u, v, w, nx, ny, nz, light, hmax, hmin, hsurf, slopes, layer, gu, gv,
                tan_theta, s0, t0, h, grazing, bias, rho):
    """point_shadow for a light of angular radius rho (radians): the part of the
    light's disk that its own layer's horizons hide, at least another layer's (hard,
    antialiased) crossing. Along the light's direction the horizon's elevation phi
    (horizon_slopes) against the disk's: the part below it. Across, the disk is cut
    in STRIPS vertical strips: the rays toward strip x (in disk radii) pass the
    occluder's distance D displaced x D tan(rho) / cos(theta) across the light's
    direction, where the line through the point so displaced has its own occluder
    (_occluder): the strip's horizon is the elevation of that occluder seen from the
    point (the lateral penumbra, growing with D as the other). A displaced line whose
    occluder is much nearer than D (its own slope) keeps the point's horizon. Attached shadows stay those of the disk's centre
    (the diffuse light goes to zero there anyway)."""
    nn = math.sqrt(nx * nx + ny * ny + nz * nz)
    facing = s * (nx * light[0] + ny * light[1] + nz * light[2]) / nn if nn > 0.0 else 0.0
    if not facing > 0.0:
        return 1.0                              # attached
    along = u * gu + v * gv
    ps = (along - s0) / h
    pt = (-u * gv + v * gu - t0) / h
    side = 0 if s > 0.0 else 1
    m = _own_slope(slopes, 4 * layer + side, hsurf, layer, pt, ps)
    if m != m or _wall(hsurf, layer, pt, ps, h):
        # no texel of the surface around, or a wall between them (its top and its
        # foot: the point's horizon is neither's): the hard answer
        return point_shadow(s, u, v, w, nx, ny, nz, light, hmax, hmin, hsurf, layer, gu, gv,
                            tan_theta, s0, t0, h, grazing, bias)
    theta = math.atan(tan_theta)
    sgn = 1.0 if s > 0.0 else -1.0
    D = _own_slope(slopes, 4 * layer + 2 + side, hsurf, layer, pt, ps)   # the occluder's
    val = _disk_below(slopes, 4 * layer + side, hsurf, layer, pt, ps, w - along * tan_theta,
                      m, D, sgn, theta, tan_theta, rho, h)
    if hmax.shape[0] > 1:           # other layers: their hard, antialiased crossings
        hp = w - along * tan_theta
        margin = _crossed(hmax, hmin, layer, pt, ps, hp, -NONE)
        val = max(val, min(max(margin / max(abs(tan_theta) * h, 1e-300) + 0.5, 0.0), 1.0))
    return val


@ngjit_parallel
def shadow_lookup(gbuf, ebuf, width, cu, cv, light, hmax, hmin, hsurf, slopes, layer, gu, gv,
                  tan_theta, s0, t0, h, grazing, bias, rho, shadow, lit):
    """The shadow pass of one layer over its tiled G-buffer and edge buffer
    (layout.py; its u, v from the view's centre (cu, cv), layout.py G_U; its w from
    the view's w_origin, G_W, as the texture's heights): shadow (H, W) 1 / 0 / between, NaN where nothing is seen, and lit =
    1 - shadow (1 where nothing is seen), top row first. Attached where the seen
    side's normal faces away from ``light`` (screen coordinates); cast where the
    point lies under its own layer's horizon (hmax / hmin[layer], the sweeps') or
    between another layer's extremes (the ray crosses it); the margin over one
    texel's rise along the ray antialiases the edge (passes/shadow.py). With rho > 0
    (a light of that angular radius, radians) the part of its disk hidden (soft_shadow,
    ``slopes`` horizon_slopes')."""
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    # tile by tile, a row's lanes innermost: the G-buffer's reads and the pictures'
    # writes both run along memory (a column at a time wrote a cache line a pixel)
    for b in prange(gbuf.shape[0]):
        for j in range(H):
            i = H - 1 - j
            for lane in range(min(T, width - b * T)):
                c = b * T + lane
                x = ebuf[b, E_SEEN, j, lane]
                s = x - E_FLAG if x > 0.5 * E_FLAG else x
                if s == 0.0:
                    shadow[i, c] = np.nan
                    lit[i, c] = 1.0
                    continue
                g = gbuf[b, j, lane]
                if rho > 0.0:
                    val = soft_shadow(s, g[G_U] + cu, g[G_V] + cv, g[G_W], g[G_NX], g[G_NY],
                                      g[G_NZ],
                                      light, hmax, hmin, hsurf, slopes, layer, gu, gv,
                                      tan_theta, s0, t0, h, grazing, bias, rho)
                else:
                    val = point_shadow(s, g[G_U] + cu, g[G_V] + cv, g[G_W], g[G_NX],
                                       g[G_NY], g[G_NZ], light, hmax, hmin, hsurf, layer, gu, gv,
                                       tan_theta, s0, t0, h, grazing, bias)
                shadow[i, c] = val
                lit[i, c] = 1.0 - val


@ngjit_parallel
def horizon_sweeps(kind, f, fb, hf, hfp, domain, gu, gv, tan_theta, s0, tau0, h, hmax, hmin,
                   hsurf, layer, wo):
    """hmax[layer, k, i] (hmin[...]): the highest (lowest) H = f - wo - sigma tan_theta on
    line k strictly beyond sample i toward the light, -NONE (+NONE) where there is none
    (finite, so that the lookup's interpolation stays finite). Line k's sample i lies at
    sigma = s0 + i h, tau = tau0 + k h, that is at (u, v) = sigma (gu, gv) + tau (-gv,
    gu); domain = (ua, ub, va, vb): outside it, and at holes, nothing casts. f is
    evaluated a line at a time by the batch evaluator fb (SIMD code, kernels/_jit.py
    BATCH_SIG; surface.py's stand-in leaves every point NaN); a point it leaves NaN is
    evaluated again by f alone, which alone decides holes. hsurf[layer, k, i]: the
    sample's own H (NaN outside the domain and at holes). The heights are kept from wo
    (the view's w_origin, as the G-buffer's w: layout.py G_W), so float32 holds them
    to the picture's own spread however far f lies from 0."""
    n_lines = hmax.shape[1]
    n = hmax.shape[2]
    ua, ub, va, vb = domain[0], domain[1], domain[2], domain[3]
    iu = hfp[HFP_IU]
    iv = hfp[HFP_IV]
    cw = hfp[HFP_CW]
    for k in prange(n_lines):
        tau = tau0 + k * h
        us = np.empty(n)
        vs = np.empty(n)
        out = np.empty(3 * n)
        for i in range(n):
            sigma = s0 + i * h
            us[i] = (sigma * gu - tau * gv) * iu
            vs[i] = (sigma * gv + tau * gu) * iv
        fb(array_ptr(us, 0), array_ptr(vs, 0), hfp[0], array_ptr(out, 0), n)
        run_max = -NONE
        run_min = NONE
        for i in range(n - 1, -1, -1):          # from the light's side
            hmax[layer, k, i] = run_max
            hmin[layer, k, i] = run_min
            H = _texel_height(kind, f, hf, hfp, ua, ub, va, vb, gu, gv, tan_theta,
                              s0 + i * h, tau, out[i] * cw, wo)
            hsurf[layer, k, i] = H
            if H == H:
                run_max = max(run_max, H)
                run_min = min(run_min, H)


@ngjit_inline
def _texel_height(kind, f, hf, hfp, ua, ub, va, vb, gu, gv, tan_theta, sigma, tau, w, wo):
    """H = f - wo - sigma tan(theta) of the texel at (sigma, tau), f there ``w`` (the
    batch evaluator's; f alone decides where it left NaN); NaN outside the domain
    ua..ub, va..vb and at holes (a hole casts no shadow)."""
    u = sigma * gu - tau * gv
    v = sigma * gv + tau * gu
    if u < ua or u > ub or v < va or v > vb:
        return np.nan
    if not math.isfinite(w):
        w = surface_value(kind, f, hf, hfp, u, v)
        if not math.isfinite(w):
            return np.nan
    return (w - wo) - sigma * tan_theta


@ngjit_parallel
def horizon_slopes(hsurf, layer, h, slopes):
    """The horizons toward the light for soft shadows, from the texture's own heights
    hsurf[layer] (H = f - sigma tan(theta)): slopes[4 layer + 0, k, i] the steepest
    rise of H from texel i of line k to the texels beyond it toward the light, max over
    q > i of (H_q - H_i) / ((q - i) h) (the horizon's elevation above the light's:
    tan(phi) = tan(theta) + rise), and slopes[4 layer + 2, k, i] the ground distance to
    that texel (the occluder's); slopes[4 layer + 1] and [4 layer + 3] the same of the
    steepest descent (the lower side's). By the line's upper (lower) convex hull, kept
    on a stack from the light's side: a texel under the chord from texel i to the next
    hull texel is under the hull of every texel nearer still, so each is pushed and
    popped once: O(n) a line. NaN where hsurf is (outside the domain, holes: a hole
    casts nothing); a rise of -SLOPE_NONE (descent +SLOPE_NONE) at distance 0 where
    nothing lies beyond."""
    n_lines = hsurf.shape[1]
    n = hsurf.shape[2]
    for k in prange(n_lines):
        hline = hsurf[layer, k]
        su = np.empty(n, dtype=np.int64)
        sl = np.empty(n, dtype=np.int64)
        nu = 0
        nl = 0
        for i in range(n - 1, -1, -1):
            H = hline[i]
            if H != H:
                for m in range(4):
                    slopes[4 * layer + m, k, i] = np.nan
                continue
            rise, d, nu = _hull_step(hline, su, nu, i, H, h, 1.0)
            slopes[4 * layer, k, i] = rise
            slopes[4 * layer + 2, k, i] = d
            rise, d, nl = _hull_step(hline, sl, nl, i, H, h, -1.0)
            slopes[4 * layer + 1, k, i] = rise
            slopes[4 * layer + 3, k, i] = d


@ngjit_inline
def _hull_step(hline, stack, n, i, H, h, sign):
    """horizon_slopes' step at sample i of height H: (the steepest rise (sign 1; the
    steepest descent with sign -1) to the samples beyond on the hull stack[:n], the
    ground distance to that sample, the stack's new size with i pushed)."""
    while n >= 2:
        a = stack[n - 1]
        b = stack[n - 2]
        if sign * (hline[a] - H) * (b - i) <= sign * (hline[b] - H) * (a - i):
            n -= 1
        else:
            break
    if n > 0:
        a = stack[n - 1]
        rise = (hline[a] - H) / ((a - i) * h)
        d = (a - i) * h
    else:
        rise = -sign * SLOPE_NONE
        d = 0.0
    stack[n] = i
    return rise, d, n + 1


# -- section 6.2.2: shadows on the fly ------------------------------------------------
#: lines of the sweep's front per band (one thread's); a band keeps two samples a line
BAND = 64


@ngjit_parallel
def sweep_cells(gbuf, ebuf, width, cu, cv, gu, gv, s0, t0, h, n_sig, n_tau, cell):
    """cell[i, c] (top row first; gbuf's u, v from the view's centre (cu, cv):
    layout.py G_U): the step of the on-the-fly sweep that answers the seen pixel (i,
    c), band * n_sig + sample (the sample below the point's sigma, whose next sample
    toward the light is the other end of its interpolation); -1 where nothing is
    seen."""
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    for b in prange(gbuf.shape[0]):              # (in memory order, as shadow_lookup)
        for j in range(H):
            i = H - 1 - j
            for lane in range(min(T, width - b * T)):
                c = b * T + lane
                x = ebuf[b, E_SEEN, j, lane]
                if (x - E_FLAG if x > 0.5 * E_FLAG else x) == 0.0:
                    cell[i, c] = -1
                    continue
                u = gbuf[b, j, lane, G_U] + cu          # (layout.py G_U)
                v = gbuf[b, j, lane, G_V] + cv
                ps = (u * gu + v * gv - s0) / h          # as point_shadow's
                pt = (-u * gv + v * gu - t0) / h
                k = min(max(floor_index(pt), 0), n_tau - 2)
                m = min(max(floor_index(ps), 0), n_sig - 2)
                cell[i, c] = (k // BAND) * n_sig + m


@ngjit
def sweep_order(cell, n_cells, start, order):
    """A counting sort of the seen pixels (flat indices into cell) by their cell:
    cell k's pixels are order[start[k]:start[k + 1]]."""
    flat = cell.ravel()
    for k in range(n_cells + 1):
        start[k] = 0
    for p in range(flat.size):
        if flat[p] >= 0:
            start[flat[p] + 1] += 1
    for k in range(n_cells):
        start[k + 1] += start[k]
    fill = start[:n_cells].copy()
    for p in range(flat.size):
        k = flat[p]
        if k >= 0:
            order[fill[k]] = p
            fill[k] += 1


@ngjit_parallel
def shadow_sweep(kind, f, fb, hf, hfp, domain, gu, gv, tan_theta, s0, t0, h, n_sig, n_tau,
                 gbuf, ebuf, width, cu, cv, wo, light, start, order, grazing, bias, shadow,
                 lit):
    """Section 6.2.2: the shadows of the seen pixels of one surface, computed while
    the planes through the light sweep the domain, without a texture. The planes
    advance from the light's side (sample n_sig - 1 down to 0, a sample h of ground
    apart); the lines, BAND to a thread, keep their running extremes of H = f - sigma
    tan(theta) (horizon_sweeps') and only their last two samples: the front, O(lines)
    memory. When the front holds samples m and m + 1, the pixels of that step
    (sweep_order's cells) are answered from it as from the texture (point_shadow: the
    same interpolation). Pixels not seen are left as they are. The G-buffer's u, v are
    kept from (cu, cv), its w and the sweep's heights from wo (layout.py G_U, G_W)."""
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    n_bands = (n_tau - 2) // BAND + 1
    ua, ub, va, vb = domain[0], domain[1], domain[2], domain[3]
    iu = hfp[HFP_IU]
    iv = hfp[HFP_IV]
    cw = hfp[HFP_CW]
    for bd in prange(n_bands):
        k0 = bd * BAND
        nl = min(BAND + 1, n_tau - k0)
        hmax = np.empty((1, nl, 2), dtype=np.float32)
        hmin = np.empty((1, nl, 2), dtype=np.float32)
        hsurf = np.empty((1, nl, 2), dtype=np.float32)
        run_max = np.full(nl, -NONE)
        run_min = np.full(nl, NONE)
        us = np.empty(nl)
        vs = np.empty(nl)
        out = np.empty(3 * nl)
        for i in range(n_sig - 1, -1, -1):
            sigma = s0 + i * h
            for q in range(nl):
                tau = t0 + (k0 + q) * h
                us[q] = (sigma * gu - tau * gv) * iu
                vs[q] = (sigma * gv + tau * gu) * iv
                hmax[0, q, 1] = hmax[0, q, 0]
                hmin[0, q, 1] = hmin[0, q, 0]
                hsurf[0, q, 1] = hsurf[0, q, 0]
            fb(array_ptr(us, 0), array_ptr(vs, 0), hfp[0], array_ptr(out, 0), nl)
            for q in range(nl):
                hmax[0, q, 0] = run_max[q]
                hmin[0, q, 0] = run_min[q]
                Hq = _texel_height(kind, f, hf, hfp, ua, ub, va, vb, gu, gv, tan_theta, sigma,
                                   t0 + (k0 + q) * h, out[q] * cw, wo)
                hsurf[0, q, 0] = Hq
                if Hq == Hq:
                    run_max[q] = max(run_max[q], Hq)
                    run_min[q] = min(run_min[q], Hq)
            if i > n_sig - 2:
                continue
            cell = bd * n_sig + i
            for p in range(start[cell], start[cell + 1]):
                pix = order[p]
                r = pix // width
                c = pix - r * width
                j = H - 1 - r
                b = c // T
                lane = c - b * T
                x = ebuf[b, E_SEEN, j, lane]
                s = x - E_FLAG if x > 0.5 * E_FLAG else x
                g = gbuf[b, j, lane]
                val = point_shadow(s, g[G_U] + cu, g[G_V] + cv, g[G_W], g[G_NX], g[G_NY],
                                   g[G_NZ], light, hmax, hmin, hsurf, 0, gu, gv, tan_theta, sigma,
                                   t0 + k0 * h, h, grazing, bias)
                shadow[r, c] = val
                lit[r, c] = 1.0 - val


@ngjit_inline
def _texel_of(u, v, w, gu, gv, tan_theta, s0, t0, h):
    """(ps, pt, hp): the point (u, v, w)'s place in the shadow texture (texels along
    and across the light) and its H = w - sigma tan(theta)."""
    along = u * gu + v * gv
    return (along - s0) / h, (-u * gv + v * gu - t0) / h, w - along * tan_theta


@ngjit_parallel
def points_shadow(point, test, hmax, hsurf, slopes, gu, gv, tan_theta, s0, t0, h, rho, out):
    """The surfaces' cast shadow on points above them (the objects' seen points,
    floatcol/objects.py): point (H, W, 3) in the box where ``test`` (H, W) is set. A
    point's ray toward the light is blocked where some layer's horizon beyond it
    (hmax, the texture's) rises above the ray's H = w - sigma tan(theta); the margin
    over one texel's rise antialiases the edge as the surface's own (point_shadow).

    For a light of angular radius rho > 0 (radians; ``slopes`` horizon_slopes', empty
    where rho is 0) the part of the disk a layer's horizon hides, as soft_shadow's:
    what makes the horizon of the surface's texels around the point (_occluder: its H
    and distance D, the point at the same distance toward the light) seen from the
    point rises at m = (H - hp) / D over the light's ray, and the disk's part below it
    is _disk_below's (across the light, the strips of the lines beside). Where the
    texels know no occluder, or where it lies under the ray while the hard horizon is
    above it (a farther ridge makes the point's horizon, higher than the surface's),
    the hard answer. The strongest of the layers. out (H, W): 1 in shadow, 0 lit,
    between at an edge or in a penumbra; 0 where not tested. In parallel over the
    columns."""
    H, W = test.shape
    width_m = max(abs(tan_theta) * h, 1e-300)
    soft = rho > 0.0 and slopes.shape[0] > 0
    theta = math.atan(tan_theta)
    for j in prange(W):
        for i in range(H):
            out[i, j] = 0.0
            if not test[i, j]:
                continue
            ps, pt, hp = _texel_of(point[i, j, 0], point[i, j, 1], point[i, j, 2], gu, gv,
                                   tan_theta, s0, t0, h)
            margin = -np.inf            # the hard layers' (one clamp of the greatest)
            val = 0.0                   # the soft layers'
            for k in range(hmax.shape[0]):
                mk = _bilinear(hmax, k, pt, ps) - hp
                if soft:
                    hk, dk = _occluder(slopes, 4 * k, hsurf, k, pt, ps)
                    m = (hk - hp) / dk if hk == hk else np.nan
                    if m == m and not (mk > 0.0 and not m > 0.0):
                        val = max(val, _disk_below(slopes, 4 * k, hsurf, k, pt, ps, hp, m,
                                                   dk, 1.0, theta, tan_theta, rho, h))
                        continue
                if mk > margin:
                    margin = mk
            out[i, j] = max(val, min(max(margin / width_m + 0.5, 0.0), 1.0))

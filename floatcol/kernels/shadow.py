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
horizon toward the light above the point; the part of the disk below it is
_blocked((phi - theta) / rho). The horizon is taken along the light's azimuth alone
(horizon mapping, Max 1988): across the disk's width in azimuth it is assumed the same.
"""
import math

import numpy as np
from numba import prange

from ._jit import array_ptr, ngjit_inline, ngjit_parallel
from .index import floor_index
from .layout import E_FLAG, E_SEEN, G_NX, G_NY, G_NZ, G_U, G_V, G_W, HFP_CW, HFP_IU, HFP_IV
from .sample import surface_value

#: "no horizon": finite, so that interpolating it with a real height stays finite
NONE = 1e300
#: horizon_slopes' "nothing beyond": a rise no surface makes (steeper than 89.99994
#: degrees), finite for the lookup's averages
SLOPE_NONE = 1e6


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
def _own_depth(hext, hsurf, k, y, x, upper):
    """How far below its own layer's horizon the surface lies around (y, x): the
    texels' own depths (hmax - H for the upper side, H - hmin for the lower) averaged
    bilinearly over the neighbours where the surface is (NaN where none is). Depths,
    not horizons, are interpolated: a lit slope's neighbours are all above their own
    horizons, whatever their heights."""
    i, j, fy, fx = _cell(hsurf, y, x)
    acc = 0.0
    wsum = 0.0
    for di in range(2):
        for dj in range(2):
            hs = hsurf[k, i + di, j + dj]
            if hs == hs:
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
    (u, v, w) the point in the box. Attached where the seen side faces away from the
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
    margin = _own_depth(hmax if s > 0.0 else hmin, hsurf, layer, pt, ps, s > 0.0)
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
def soft_shadow(s, u, v, w, nx, ny, nz, light, hmax, hmin, hsurf, slopes, layer, gu, gv,
                tan_theta, s0, t0, h, grazing, bias, rho):
    """point_shadow for a light of angular radius rho (radians): the part of the
    light's disk that its own layer's horizon toward the light hides (horizon_slopes),
    at least another layer's (hard) crossing. Attached shadows stay those of the
    disk's centre (the diffuse light goes to zero there anyway)."""
    nn = math.sqrt(nx * nx + ny * ny + nz * nz)
    facing = s * (nx * light[0] + ny * light[1] + nz * light[2]) / nn if nn > 0.0 else 0.0
    if not facing > 0.0:
        return 1.0                              # attached
    along = u * gu + v * gv
    ps = (along - s0) / h
    pt = (-u * gv + v * gu - t0) / h
    m = _own_slope(slopes, 2 * layer + (0 if s > 0.0 else 1), hsurf, layer, pt, ps)
    if m != m:                      # no texel of the surface around: the hard answer
        return point_shadow(s, u, v, w, nx, ny, nz, light, hmax, hmin, hsurf, layer, gu, gv,
                            tan_theta, s0, t0, h, grazing, bias)
    theta = math.atan(tan_theta)
    phi = math.atan(tan_theta + m)  # the horizon's elevation toward the light
    val = _blocked((phi - theta) / rho if s > 0.0 else (theta - phi) / rho)
    if hmax.shape[0] > 1:           # other layers: their hard, antialiased crossings
        hp = w - along * tan_theta
        margin = _crossed(hmax, hmin, layer, pt, ps, hp, -NONE)
        val = max(val, min(max(margin / max(abs(tan_theta) * h, 1e-300) + 0.5, 0.0), 1.0))
    return val


@ngjit_parallel
def shadow_lookup(gbuf, ebuf, width, light, hmax, hmin, hsurf, slopes, layer, gu, gv, tan_theta,
                  s0, t0, h, grazing, bias, rho, shadow, lit):
    """The shadow pass of one layer over its tiled G-buffer and edge buffer
    (layout.py): shadow (H, W) 1 / 0 / between, NaN where nothing is seen, and lit =
    1 - shadow (1 where nothing is seen), top row first. Attached where the seen
    side's normal faces away from ``light`` (screen coordinates); cast where the
    point lies under its own layer's horizon (hmax / hmin[layer], the sweeps') or
    between another layer's extremes (the ray crosses it); the margin over one
    texel's rise along the ray antialiases the edge (passes/shadow.py). With rho > 0
    (a light of that angular radius, radians) the part of its disk hidden (soft_shadow,
    ``slopes`` horizon_slopes')."""
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    for c in prange(width):
        b = c // T
        lane = c - b * T
        for j in range(H):
            i = H - 1 - j
            x = ebuf[b, E_SEEN, j, lane]
            s = x - E_FLAG if x > 0.5 * E_FLAG else x
            if s == 0.0:
                shadow[i, c] = np.nan
                lit[i, c] = 1.0
                continue
            g = gbuf[b, j, lane]
            if rho > 0.0:
                val = soft_shadow(s, g[G_U], g[G_V], g[G_W], g[G_NX], g[G_NY], g[G_NZ], light,
                                  hmax, hmin, hsurf, slopes, layer, gu, gv, tan_theta, s0, t0,
                                  h, grazing, bias, rho)
            else:
                val = point_shadow(s, g[G_U], g[G_V], g[G_W], g[G_NX], g[G_NY], g[G_NZ], light,
                                   hmax, hmin, hsurf, layer, gu, gv, tan_theta, s0, t0, h,
                                   grazing, bias)
            shadow[i, c] = val
            lit[i, c] = 1.0 - val


@ngjit_parallel
def horizon_sweeps(kind, f, fb, hf, hfp, domain, gu, gv, tan_theta, s0, tau0, h, hmax, hmin,
                   hsurf, layer):
    """hmax[layer, k, i] (hmin[...]): the highest (lowest) H = f - sigma tan_theta on
    line k strictly beyond sample i toward the light, -NONE (+NONE) where there is none
    (finite, so that the lookup's interpolation stays finite). Line k's sample i lies at
    sigma = s0 + i h, tau = tau0 + k h, that is at (u, v) = sigma (gu, gv) + tau (-gv,
    gu); domain = (ua, ub, va, vb): outside it, and at holes, nothing casts. f is
    evaluated a line at a time by the batch evaluator fb (SIMD code, kernels/_jit.py
    BATCH_SIG; surface.py's stand-in leaves every point NaN); a point it leaves NaN is
    evaluated again by f alone, which alone decides holes. hsurf[layer, k, i]: the
    sample's own H (NaN outside the domain and at holes)."""
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
            hsurf[layer, k, i] = np.nan
            sigma = s0 + i * h
            u = sigma * gu - tau * gv
            v = sigma * gv + tau * gu
            if u < ua or u > ub or v < va or v > vb:
                continue
            w = out[i] * cw
            if not math.isfinite(w):
                w = surface_value(kind, f, hf, hfp, u, v)
                if not math.isfinite(w):
                    continue                      # a hole casts no shadow
            H = w - sigma * tan_theta
            hsurf[layer, k, i] = H
            run_max = max(run_max, H)
            run_min = min(run_min, H)


@ngjit_parallel
def horizon_slopes(hsurf, layer, h, slopes):
    """slopes[2 layer, k, i]: the steepest rise of H from texel i of line k to the
    texels beyond it toward the light, max over q > i of (H_q - H_i) / ((q - i) h)
    (the horizon's elevation toward the light: tan(phi) = tan(theta) + rise);
    slopes[2 layer + 1, k, i] the steepest descent (min; the lower side's). By the
    line's upper (lower) convex hull, kept on a stack from the light's side: a point
    under the chord from texel i to the next hull point is under the hull of every
    texel nearer still, so each is pushed and popped once. NaN where hsurf is (outside
    the domain, holes: a hole casts nothing); -SLOPE_NONE (+SLOPE_NONE) where nothing
    lies beyond."""
    n_lines = hsurf.shape[1]
    n = hsurf.shape[2]
    up = 2 * layer
    lo = up + 1
    for k in prange(n_lines):
        su = np.empty(n, dtype=np.int64)
        sl = np.empty(n, dtype=np.int64)
        nu = 0
        nl = 0
        for i in range(n - 1, -1, -1):
            H = hsurf[layer, k, i]
            if H != H:
                slopes[up, k, i] = np.nan
                slopes[lo, k, i] = np.nan
                continue
            while nu >= 2:          # rise to the top no steeper than to the one below it
                a = su[nu - 1]
                b = su[nu - 2]
                if (hsurf[layer, k, a] - H) * (b - i) <= (hsurf[layer, k, b] - H) * (a - i):
                    nu -= 1
                else:
                    break
            if nu > 0:
                a = su[nu - 1]
                slopes[up, k, i] = (hsurf[layer, k, a] - H) / ((a - i) * h)
            else:
                slopes[up, k, i] = -SLOPE_NONE
            su[nu] = i
            nu += 1
            while nl >= 2:
                a = sl[nl - 1]
                b = sl[nl - 2]
                if (hsurf[layer, k, a] - H) * (b - i) >= (hsurf[layer, k, b] - H) * (a - i):
                    nl -= 1
                else:
                    break
            if nl > 0:
                a = sl[nl - 1]
                slopes[lo, k, i] = (hsurf[layer, k, a] - H) / ((a - i) * h)
            else:
                slopes[lo, k, i] = SLOPE_NONE
            sl[nl] = i
            nl += 1

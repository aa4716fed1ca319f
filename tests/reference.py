"""An independent reference renderer: per-pixel ray casting on the exact f.

Shares no code with floatcol's kernels. Each pixel's ray (same camera and pixel
convention as DESIGN.md section 3) is clipped to the domain's vertical prism, marched
densely in world coordinates with numpy, and the first sign change of
g = w_ray - f(u, v) is refined by bisection. Where f's bounds are known (a height
grid's extremes; interval arithmetic over the expression, ``expr_bounds``), a ray's
steps above or below every value of f, where no sign change can be, are left out. The upper side is seen where the ray
comes from above (g goes from + to -). Intensity is the lambert model
I = |L.N| / (|L||N|) with N = (-f_u, 1, -f_v) in world coordinates and L toward the
viewpoint (orthographic: toward the viewer).
"""
from __future__ import annotations

from dataclasses import dataclass

import math

import numpy as np
import sympy as sp


@dataclass
class Reference:
    side: np.ndarray        # (H, W) int8
    intensity: np.ndarray   # (H, W) float, NaN where nothing
    depth: np.ndarray       # (H, W) screen z, inf where nothing
    t: np.ndarray           # (H, W) t of the hit (relative to the origin)
    u: np.ndarray
    v: np.ndarray


class Funcs(tuple):
    """(f, f_u, f_v), with ``bounds(u_rng, v_rng)``: (lo, hi) such that lo <= f <= hi
    wherever f is finite on the domain (infinite where no bound is known). The march
    uses it to leave out the steps of a ray that lie above hi or below lo, where no
    crossing can be."""

    def __new__(cls, funcs, bounds=None):
        out = super().__new__(cls, funcs)
        out._bounds = bounds
        return out

    def bounds(self, u_rng, v_rng):
        return (-np.inf, np.inf) if self._bounds is None else self._bounds(u_rng, v_rng)


def _bounds_of(funcs, u_rng, v_rng):
    """f's bounds where funcs knows them (a Funcs), else (-inf, inf)."""
    return funcs.bounds(u_rng, v_rng) if isinstance(funcs, Funcs) else (-np.inf, np.inf)


def numpy_surface(expr, names=("u", "v")):
    """(f, f_u, f_v) as numpy functions of a sympy expression or string."""
    su, sv = sp.symbols(names)
    e = sp.sympify(expr, locals={names[0]: su, names[1]: sv}) if isinstance(expr, str) else expr
    fs = [sp.lambdify((su, sv), x, "numpy") for x in (e, sp.diff(e, su), sp.diff(e, sv))]

    def wrap(fn):
        def g(u, v):
            with np.errstate(all="ignore"):
                out = np.asarray(fn(u, v))
                if np.iscomplexobj(out):
                    out = np.where(np.abs(out.imag) <= 1e-12 * (1 + np.abs(out.real)), out.real, np.nan)
                return np.broadcast_to(out, np.broadcast(u, v).shape).astype(float)
        return g
    f, fu, fv = (wrap(fn) for fn in fs)

    def partial(formula, axis):
        # where the formula's partial is not finite though f is (its own 0/0, as
        # sqrt(Max(0, 4 - u^2 - v^2))' on the floor), the surface's slope there:
        # central differences (a 5-point stencil, independent of floatcol's 2-point)
        def g(u, v):
            d = formula(u, v)
            w = f(u, v)
            bad = ~np.isfinite(d) & np.isfinite(w)
            if bad.any():
                u_b, v_b = (np.broadcast_to(x, d.shape)[bad] for x in (u, v))
                x = u_b if axis == 0 else v_b
                h = 1e-4 * np.maximum(1.0, np.abs(x))

                def at(k):
                    return f(u_b + k * h, v_b) if axis == 0 else f(u_b, v_b + k * h)
                d = d.copy()
                d[bad] = (at(-2) - 8 * at(-1) + 8 * at(1) - at(2)) / (12 * h)
            return d
        return g
    return Funcs((f, partial(fu, 0), partial(fv, 1)),
                 lambda u_rng, v_rng: expr_bounds(e, su, sv, u_rng, v_rng))


#: expr_bounds splits the domain into BOUND_BOXES x BOUND_BOXES boxes
BOUND_BOXES = 32


def expr_bounds(e, su, sv, u_rng, v_rng):
    """(lo, hi) enclosing every finite value of the sympy expression e over the domain:
    interval arithmetic on each of BOUND_BOXES^2 boxes of (u, v), widened for rounding.
    A form it does not know (Piecewise, a symbolic power, ...) gives (-inf, inf)."""
    n = BOUND_BOXES
    cu = np.linspace(u_rng[0], u_rng[1], n + 1)
    cv = np.linspace(v_rng[0], v_rng[1], n + 1)
    env = {su: (np.repeat(cu[:-1], n), np.repeat(cu[1:], n)),
           sv: (np.tile(cv[:-1], n), np.tile(cv[1:], n))}
    with np.errstate(all="ignore"):
        lo, hi = _interval(e, env)
    if np.isnan(lo).any() or np.isnan(hi).any():
        return -np.inf, np.inf
    lo, hi = float(lo.min()), float(hi.max())
    pad = 1e-6 * (abs(lo) + abs(hi)) + 1e-9
    return lo - pad, hi + pad


def _widen(lo, hi):
    """An interval widened by a few ulps either way (the enclosure stays an enclosure
    under rounding)."""
    return lo - 4 * np.spacing(np.abs(lo)), hi + 4 * np.spacing(np.abs(hi))


def _interval(e, env):
    """Interval arithmetic over arrays of boxes: (lo, hi) of e, each an array. A part
    whose values are never finite (sqrt of a negative interval) may give any interval:
    f is a hole there. Unknown forms give (-inf, inf)."""
    inf = np.full_like(env[next(iter(env))][0], np.inf)
    if e in env:
        return env[e]
    if e.is_number:
        try:
            c = float(e)
        except TypeError:               # complex: a hole
            return -inf, inf
        return _widen(np.full_like(inf, c), np.full_like(inf, c))
    args = [_interval(a, env) for a in e.args]
    if isinstance(e, sp.Add):
        lo, hi = args[0]
        for a, b in args[1:]:
            lo, hi = _widen(lo + a, hi + b)
        return lo, hi
    if isinstance(e, sp.Mul):
        lo, hi = args[0]
        for a, b in args[1:]:
            c = np.stack([lo * a, lo * b, hi * a, hi * b])
            bad = np.isnan(c).any(axis=0)           # 0 * inf
            lo, hi = _widen(np.where(bad, -inf, c.min(axis=0)), np.where(bad, inf, c.max(axis=0)))
        return lo, hi
    if isinstance(e, sp.Pow) and e.exp.is_number and e.exp.is_real:
        (a, b), p = args[0], float(e.exp)
        if p == int(p):
            n = int(abs(p))
            if n % 2 == 0:
                lo = np.where((a <= 0) & (b >= 0), 0.0, np.minimum(np.abs(a), np.abs(b)) ** n)
                hi = np.maximum(np.abs(a), np.abs(b)) ** n
            else:
                lo, hi = a ** n, b ** n
        else:                           # x^p, p not whole: finite only where x >= 0
            # (a box where x < 0 throughout is a hole: any interval will do)
            a, b = np.maximum(a, 0.0), np.maximum(b, 0.0)
            lo, hi = (a ** abs(p), b ** abs(p))
        lo, hi = _widen(lo, hi)
        if p < 0:                       # 1/x^|p|: unbounded where x^|p| may be 0
            zero = (lo <= 0) & (hi >= 0)
            lo, hi = np.where(zero, -inf, 1 / hi), np.where(zero, inf, 1 / lo)
            lo, hi = _widen(lo, hi)
        return lo, hi
    if isinstance(e, (sp.sin, sp.cos)):
        a, b = args[0]
        shift = 0.0 if isinstance(e, sp.cos) else -np.pi / 2      # sin x = cos(x - pi/2)
        a, b = a + shift, b + shift
        ca, cb = np.cos(a), np.cos(b)
        lo, hi = np.minimum(ca, cb), np.maximum(ca, cb)
        # a maximum 2 pi k or a minimum pi + 2 pi k inside [a, b] (a little widened)
        k_max = np.ceil(a / (2 * np.pi) - 1e-9) <= np.floor(b / (2 * np.pi) + 1e-9)
        k_min = np.ceil((a - np.pi) / (2 * np.pi) - 1e-9) <= np.floor((b - np.pi) / (2 * np.pi) + 1e-9)
        wide = ~np.isfinite(a) | ~np.isfinite(b) | (b - a >= 2 * np.pi)
        hi = np.where(k_max | wide, 1.0, hi)
        lo = np.where(k_min | wide, -1.0, lo)
        lo, hi = _widen(lo, hi)
        return np.maximum(lo, -1.0), np.minimum(hi, 1.0)
    if isinstance(e, sp.exp):
        a, b = args[0]
        return _widen(np.exp(a), np.exp(b))
    if isinstance(e, sp.log):
        a, b = args[0]
        return _widen(np.log(np.maximum(a, 0.0)), np.log(np.maximum(b, 0.0)))
    if isinstance(e, sp.Abs):
        a, b = args[0]
        lo = np.where((a <= 0) & (b >= 0), 0.0, np.minimum(np.abs(a), np.abs(b)))
        return lo, np.maximum(np.abs(a), np.abs(b))
    return -inf, inf


def bilinear_surface(z, u_rng, v_rng):
    """(f, f_u, f_v) of a height grid read bilinearly, z[j, i] at (u_i, v_j)."""
    z = np.asarray(z, float)
    nv, nu = z.shape

    def cell(u, v):
        gx = (u - u_rng[0]) / (u_rng[1] - u_rng[0]) * (nu - 1)
        gy = (v - v_rng[0]) / (v_rng[1] - v_rng[0]) * (nv - 1)
        bad = (gx < -1e-9) | (gx > nu - 1 + 1e-9) | (gy < -1e-9) | (gy > nv - 1 + 1e-9)
        i = np.clip(np.floor(gx).astype(int), 0, nu - 2)
        j = np.clip(np.floor(gy).astype(int), 0, nv - 2)
        fx, fy = gx - i, gy - j
        c = z[j, i], z[j, i + 1], z[j + 1, i], z[j + 1, i + 1]
        return bad, fx, fy, c

    def f(u, v):
        bad, fx, fy, (z00, z10, z01, z11) = cell(u, v)
        w = (z00 * (1 - fx) + z10 * fx) * (1 - fy) + (z01 * (1 - fx) + z11 * fx) * fy
        return np.where(bad, np.nan, w)

    def fu(u, v):
        bad, fx, fy, (z00, z10, z01, z11) = cell(u, v)
        return ((z10 - z00) * (1 - fy) + (z11 - z01) * fy) * (nu - 1) / (u_rng[1] - u_rng[0])

    def fv(u, v):
        bad, fx, fy, (z00, z10, z01, z11) = cell(u, v)
        return ((z01 - z00) * (1 - fx) + (z11 - z10) * fx) * (nv - 1) / (v_rng[1] - v_rng[0])
    # bilinear values are weighted means of a cell's corners
    lo, hi = (float(np.nanmin(z)), float(np.nanmax(z))) if np.isfinite(z).any() else (0.0, 0.0)
    return Funcs((f, fu, fv), lambda u_rng, v_rng: (lo, hi))


def smooth_bilinear_surface(z, u_rng, v_rng):
    """bilinear_surface's heights with its partials smoothed (floatcol's
    smooth_shading): the nodes' central differences (numpy's gradient: one-sided at
    the grid's edges) interpolated bilinearly across each cell."""
    z = np.asarray(z, float)
    nv, nu = z.shape
    du = (u_rng[1] - u_rng[0]) / (nu - 1)
    dv = (v_rng[1] - v_rng[0]) / (nv - 1)
    gv, gu = np.gradient(z, dv, du)
    f = bilinear_surface(z, u_rng, v_rng)

    def lerp(g):
        def at(u, v):
            gx = (u - u_rng[0]) / du
            gy = (v - v_rng[0]) / dv
            i = np.clip(np.floor(gx).astype(int), 0, nu - 2)
            j = np.clip(np.floor(gy).astype(int), 0, nv - 2)
            fx, fy = np.clip(gx - i, 0, 1), np.clip(gy - j, 0, 1)
            return ((g[j, i] * (1 - fx) + g[j, i + 1] * fx) * (1 - fy)
                    + (g[j + 1, i] * (1 - fx) + g[j + 1, i + 1] * fx) * fy)
        return at
    return Funcs((f[0], lerp(gu), lerp(gv)), f.bounds)


def _rays(u_rng, v_rng, size, elev, azim, projection, d1, d2, scale, w_bound, center,
          yscale=None):
    """Each pixel's ray (origin, direction; lam in [lam_lo, lam_hi] inside the domain's
    prism, ``live`` where it meets it) and ``world``: screen (x, y, z) -> (u, w, v, t)."""
    W, H = size
    a, b = -np.radians(elev), np.radians(azim)
    ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
    c = np.arange(W)[None, :].repeat(H, 0).astype(float)
    j = (H - 1 - np.arange(H))[:, None].repeat(W, 1).astype(float)
    x0 = (c - (W - 1) / 2) / scale
    y0 = (j - (H - 1) / 2) / (scale if yscale is None else yscale)
    ortho = projection.startswith("ortho")

    cu, cv, cw = center

    def world(x, y, z):           # screen -> (u, w, v): eqs. (1)-(2), then the centre
        r, s, t = x, y * ca + z * sa, -y * sa + z * ca
        return cu + r * cb + t * sb, cw + s, cv - r * sb + t * cb, t

    if ortho:
        big = 4 * (abs(u_rng[0]) + abs(u_rng[1]) + abs(v_rng[0]) + abs(v_rng[1]) + (w_bound or 10))
        org = np.stack([x0, y0, np.full_like(x0, -big)])
        dirn = np.stack([np.zeros_like(x0), np.zeros_like(x0), np.ones_like(x0)])
        lam_lo, lam_hi = np.zeros_like(x0), np.full_like(x0, 2 * big)
    else:
        d3 = d1 + d2
        org = np.stack([np.zeros_like(x0), np.zeros_like(x0), np.full_like(x0, -d3)])
        dirn = np.stack([x0, y0, np.full_like(x0, d1)])
        lam_lo, lam_hi = np.ones_like(x0), np.full_like(x0, 1e6)   # beyond the screen plane
    # Clip the ray's ground track to the domain rectangle.
    uo, _, vo, _ = world(*org)
    ud, _, vd, _ = (world(*(org + dirn))[k] - world(*org)[k] for k in range(4))
    for o, d, (lo, hi) in ((uo, ud, u_rng), (vo, vd, v_rng)):
        with np.errstate(divide="ignore", invalid="ignore"):
            l1, l2 = (lo - o) / d, (hi - o) / d
        par = np.abs(d) < 1e-14
        inside = (o >= lo) & (o <= hi)
        lam_lo = np.where(par, np.where(inside, lam_lo, np.inf), np.maximum(lam_lo, np.minimum(l1, l2)))
        lam_hi = np.where(par, np.where(inside, lam_hi, -np.inf), np.minimum(lam_hi, np.maximum(l1, l2)))
    live = lam_lo < lam_hi
    lam_hi = np.where(live, lam_hi, lam_lo)

    return org, dirn, lam_lo, lam_hi, live, world


#: _march takes this many of a ray's steps at a time (one numpy call for all of them),
#: for this many rays at a time (their arrays stay in the processor's cache)
MARCH_BLOCK = 16
MARCH_RAYS = 2048


def _gap(f, world, o, d, lam):
    """w - f(u, v) at the points o + d lam (screen coordinates) of rays."""
    u, w, v, _ = world(*(o + d * lam))
    return w - f(u, v)


def _step_blocks(steps):
    """The fractions k / steps, k = 1 .. steps, MARCH_BLOCK at a time (arrays)."""
    for k0 in range(1, steps + 1, MARCH_BLOCK):
        yield np.array([k / steps for k in range(k0, min(k0 + MARCH_BLOCK, steps + 1))])


def _window(world, org, dirn, lam_lo, lam_hi, steps, bounds):
    """Each ray's steps where a crossing can be, given lo <= f <= hi (``bounds``): along
    the ray w is linear in lam, and where w > hi (or w < lo) g = w - f is positive (or
    negative) wherever it is finite, so two steps on the same side of the slab never
    cross. Returns (k_start, k_end): the last step before the ray's first part beyond
    the slab ends, and the first of its last part beyond it (two steps of margin each);
    a crossing at step k (between k - 1 and k) needs k_start < k <= k_end."""
    lo_b, hi_b = bounds
    k_start = np.zeros(lam_lo.shape, np.int64)
    k_end = np.full(lam_lo.shape, steps, np.int64)
    if not (np.isfinite(lo_b) and np.isfinite(hi_b)):
        return k_start, k_end
    w0 = world(*(org + dirn * lam_lo))[1]
    w1 = world(*(org + dirn * lam_hi))[1]
    with np.errstate(all="ignore"):
        slope = (w1 - w0) / steps              # w's change a step
        up = slope > 0
        first, last = np.where(up, lo_b, hi_b), np.where(up, hi_b, lo_b)
        x_first, x_last = (first - w0) / slope, (last - w0) / slope
    flat = ~(np.abs(slope) > 0) | ~np.isfinite(x_first) | ~np.isfinite(x_last)
    inside = (w0 >= lo_b) & (w0 <= hi_b)
    ks = np.clip(np.floor(np.where(flat, 0, x_first)) - 2, 0, steps).astype(np.int64)
    ke = np.clip(np.ceil(np.where(flat, steps, x_last)) + 2, 0, steps).astype(np.int64)
    # a level ray beyond the slab never crosses; one in it may anywhere
    ke = np.where(flat & ~inside & np.isfinite(w0), 0, ke)
    return ks, ke


def _march(f, org, dirn, lam_lo, lam_hi, live, world, steps, bounds=(-np.inf, np.inf)):
    """The first crossing of each ray: steps uniform steps from lam_lo to lam_hi, a hit
    where w - f changes sign between two finite values (from a non-zero one). Returns
    (found, side: +1 from above, -1 from below, and the step's ends l_a, l_b), each the
    rays' shape. The same values, step for step, as marching every ray through every
    step at once (what this did before); only the rays still marching are evaluated,
    MARCH_RAYS rays and MARCH_BLOCK steps at a time: a third of the suite's time
    before, most rays hit early. With ``bounds`` (lo <= f <= hi where finite) a ray
    takes only the blocks of its steps where it is within the slab (``_window``): most
    rays that miss the surface had marched every step."""
    shape = lam_lo.shape
    found = np.zeros(shape, bool)
    side = np.zeros(shape, np.int8)
    l_a = np.zeros(shape)
    l_b = np.zeros(shape)
    org = org.reshape(3, -1)
    dirn = dirn.reshape(3, -1)
    lam_lo = lam_lo.reshape(-1)
    lam_hi = lam_hi.reshape(-1)
    k_start, k_end = _window(world, org, dirn, lam_lo, lam_hi, steps, bounds)
    rays = np.flatnonzero(live.reshape(-1) & (k_start < k_end))
    for c0 in range(0, rays.size, MARCH_RAYS):
        ray = rays[c0:c0 + MARCH_RAYS]
        ks, ke = k_start[ray], k_end[ray]
        # a ray's sign and lam a step before the block (a ray that starts later takes
        # sign 0: no crossing at its first block's first step, which k_start rules out)
        s_prev = np.zeros(ray.size)
        lam_prev = lam_lo[ray].copy()
        now = np.flatnonzero(ks == 0)
        with np.errstate(all="ignore"):
            g0 = _gap(f, world, org[:, ray[now]], dirn[:, ray[now]], lam_lo[ray[now]])
        s_prev[now] = np.sign(np.where(np.isfinite(g0), g0, np.nan))
        looking = np.ones(ray.size, bool)
        for q in _step_blocks(steps):
            k0 = int(round(q[0] * steps))
            k1 = k0 + q.size - 1
            act = np.flatnonzero(looking & (ks <= k1) & (ke >= k0))
            if not act.size:
                if not (looking & (ke >= k0)).any():
                    break
                continue
            idx = ray[act]
            o, d, lo = org[:, idx], dirn[:, idx], lam_lo[idx]
            lam = lo[None, :] + (lam_hi[idx] - lo)[None, :] * q[:, None]   # (steps, rays)
            with np.errstate(all="ignore"):
                g = _gap(f, world, o[:, None, :], d[:, None, :], lam)
            g[~np.isfinite(g)] = np.nan
            sg = np.sign(g)                      # (NaN where g is: never a crossing)
            sp_ = np.concatenate([s_prev[act][None, :], sg[:-1]], axis=0)   # a step before
            # a crossing: both finite, their signs differ, the one before not zero
            cross = (sg != sp_) & (sp_ != 0) & (sg == sg) & (sp_ == sp_)
            hit = cross.any(axis=0)
            if hit.any():
                cols = np.flatnonzero(hit)
                first = cross[:, cols].argmax(axis=0)
                lp = np.concatenate([lam_prev[act][None, :], lam[:-1]], axis=0)
                at = idx[cols]
                found[np.unravel_index(at, shape)] = True
                side[np.unravel_index(at, shape)] = np.where(sp_[first, cols] > 0, 1, -1)
                l_a[np.unravel_index(at, shape)] = lp[first, cols]
                l_b[np.unravel_index(at, shape)] = lam[first, cols]
                looking[act[cols]] = False
            s_prev[act] = sg[-1]
            lam_prev[act] = lam[-1]
    return found, side, l_a, l_b


def raycast(funcs, u_rng, v_rng, size, elev, azim, projection="orthographic", d1=None, d2=None,
            scale=None, steps=1500, bisections=40, w_bound=None, center=(0.0, 0.0, 0.0),
            wall_normal=None, yscale=None):
    """Ray-cast the surface given as numpy (f, f_u, f_v). scale and, in perspective,
    d1 and d2 must be given (take them from the render being checked); ``center`` is
    the world point (u, v, w) at the screen origin; ``yscale`` (default scale) the
    pixels per unit down the picture. ``wall_normal(u, v) -> (n_u, n_v)``
    shades hits on a discontinuity of f (where f still jumps across the final
    bisection bracket) as a vertical wall with that ground normal."""
    f, fu, fv = funcs
    org, dirn, lam_lo, lam_hi, live, world = _rays(u_rng, v_rng, size, elev, azim, projection,
                                                   d1, d2, scale, w_bound, center, yscale)
    ortho = projection.startswith("ortho")
    found, side, l_a, l_b = _march(f, org, dirn, lam_lo, lam_hi, live, world, steps,
                                   _bounds_of(funcs, u_rng, v_rng))
    # refine: the root lies in [l_a, l_b] (g at l_a carried over: the one computed)
    ga = _gap(f, world, org, dirn, l_a)
    for _ in range(bisections):
        m = 0.5 * (l_a + l_b)
        gm = _gap(f, world, org, dirn, m)
        same = np.sign(gm) == np.sign(ga)
        l_a = np.where(same, m, l_a)
        l_b = np.where(same, l_b, m)
        ga = np.where(same, gm, ga)
    lam = np.where(found, 0.5 * (l_a + l_b), np.nan)
    p = org + dirn * np.where(found, lam, 0.0)
    u, w, v, t = world(*p)
    nu, nw, nv = -fu(u, v), np.ones_like(u), -fv(u, v)
    if wall_normal is not None:
        ua, _, va, _ = world(*(org + dirn * np.where(found, l_a, 0.0)))
        ub, _, vb, _ = world(*(org + dirn * np.where(found, l_b, 0.0)))
        with np.errstate(invalid="ignore"):
            on_wall = found & (np.abs(f(ua, va) - f(ub, vb)) > 1e-6)
        wn_u, wn_v = wall_normal(u, v)
        nu = np.where(on_wall, wn_u, nu)
        nw = np.where(on_wall, 0.0, nw)
        nv = np.where(on_wall, wn_v, nv)
    if ortho:
        lx, ly, lz = -dirn
    else:
        lx, ly, lz = org - p
    lu, lw, lv, _ = (world(lx, ly, lz)[k] - world(0.0, 0.0, 0.0)[k] for k in range(4))
    with np.errstate(all="ignore"):
        inten = np.abs(lu * nu + lw * nw + lv * nv) / (
            np.sqrt(lu ** 2 + lw ** 2 + lv ** 2) * np.sqrt(nu ** 2 + nw ** 2 + nv ** 2))
    nan = np.nan
    return Reference(side=side, intensity=np.where(found, inten, nan),
                     depth=np.where(found, p[2], np.inf), t=np.where(found, t, nan),
                     u=np.where(found, u, nan), v=np.where(found, v, nan))


def fractal(n, beta=2.4, seed=7):
    """A test terrain: an n x n fractal DEM by spectral synthesis (power spectrum
    ~ k^-beta, random phases of ``seed``), mean 0, std 1."""
    rng = np.random.default_rng(seed)
    k = np.fft.fftfreq(n)[:, None] ** 2 + np.fft.fftfreq(n)[None, :] ** 2
    k[0, 0] = 1.0
    spec = (rng.normal(size=(n, n)) + 1j * rng.normal(size=(n, n))) * k ** (-beta / 4)
    spec[0, 0] = 0.0
    z = np.fft.ifft2(spec).real
    return (z - z.mean()) / z.std()


def psnr(a, b):
    """PSNR in dB of two intensity images in [0, 1], background (NaN) counted as 0."""
    a = np.nan_to_num(np.asarray(a, float))
    b = np.nan_to_num(np.asarray(b, float))
    mse = float(np.mean((a - b) ** 2))
    return np.inf if mse == 0 else 10 * np.log10(1.0 / mse)


def table6(frames):
    """Cohen-Or's Table 6 measure of flicker: the pixels whose grey level (ITU-R 601
    luma of the rgba frames, rounded) changes by 6 to 60 from one frame to the next,
    summed over the frames."""
    lum = [np.asarray(f)[..., :3] @ np.array([0.299, 0.587, 0.114]) for f in frames]
    d = np.round(np.abs(np.diff(lum, axis=0)))
    return int(((d >= 6) & (d <= 60)).sum())


def raycast_box(funcs, u_rng, v_rng, size, elev, azim, projection="orthographic", d1=None,
                d2=None, scale=None, k=4, **kw):
    """The pixel-area (box-filtered) picture: ray-cast k x k sub-pixels per pixel and
    average. Returns (intensity with the background counted as 0, coverage), both
    (H, W). Sub-pixel centres sit at offsets (i + 1/2)/k - 1/2 from the pixel centre:
    the k-times finer grid of the same camera, scale multiplied by k."""
    W, H = size
    ref = raycast(funcs, u_rng, v_rng, (W * k, H * k), elev, azim, projection, d1, d2,
                  scale * k, **kw)
    inten = np.nan_to_num(ref.intensity).reshape(H, k, W, k).mean(axis=(1, 3))
    cover = (ref.side != 0).reshape(H, k, W, k).mean(axis=(1, 3))
    return inten, cover


def raycast_column_box(funcs, u_rng, v_rng, size, elev, azim, projection="orthographic",
                       d1=None, d2=None, scale=None, k=16, **kw):
    """The pixels box-filtered along their column (Cohen-Or's area sampling): k rays
    per pixel at the column's centre, at heights (i + 1/2)/k - 1/2 of a pixel.
    Returns (mean intensity of the rays that hit, NaN where none; coverage: the part
    of them that hit), both (H, W)."""
    W, H = size
    ref = raycast(funcs, u_rng, v_rng, (W, H * k), elev, azim, projection, d1, d2, scale,
                  yscale=scale * k, **kw)
    hit = (ref.side != 0).reshape(H, k, W)
    inten = np.nan_to_num(ref.intensity).reshape(H, k, W).sum(axis=1)
    n = hit.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(n > 0, inten / np.maximum(n, 1), np.nan), n / k


def shadow_rays(funcs, ref, u_rng, v_rng, light, steps=2000, start=1e-4, radius=0.0,
                n_disk=48):
    """Shadows at the reference's hits (Gordon 6.2, independently): a hit is in
    shadow where its seen side faces away from ``light`` (a direction toward the light
    in world (u, v, w)), or where the ray from it toward the light crosses the surface
    (w_ray - f changes sign) before it leaves the domain. Returns (H, W) float: 1
    shadow, 0 lit, NaN where nothing is seen. With ``radius`` (degrees) the light is a
    disk of that angular radius: the cast part is the fraction of ``n_disk`` rays,
    spread evenly over the disk (a sunflower spiral), that the surface stops."""
    f, fu, fv = funcs
    L = np.asarray(light, float)
    L = L / np.linalg.norm(L)
    seen = ref.side != 0
    u, v = ref.u[seen], ref.v[seen]
    w = f(u, v)
    side = ref.side[seen].astype(float)
    n = np.stack([-fu(u, v), -fv(u, v), np.ones_like(u)], axis=1)
    attached = side * (n @ L) <= 0.0
    rays = _disk(L, radius, n_disk)
    cast = np.zeros(u.shape)
    for Lk in rays:
        cast += _cast(f, u, v, w, side, Lk, u_rng, v_rng, steps, start)
    cast /= len(rays)
    out = np.full(ref.side.shape, np.nan)
    out[seen] = np.where(attached, 1.0, cast)
    return out


def _cast(f, u, v, w, side, L, u_rng, v_rng, steps, start):
    """Whether the ray from each point (u, v, w) toward L crosses the surface before
    it leaves the domain."""
    s_max = np.full(u.shape, np.inf)
    for o, d, (lo, hi) in ((u, L[0], u_rng), (v, L[1], v_rng)):
        if abs(d) > 1e-14:
            s_max = np.minimum(s_max, np.maximum((lo - o) / d, (hi - o) / d))
    diag = np.hypot(u_rng[1] - u_rng[0], v_rng[1] - v_rng[0])
    s_max = np.minimum(s_max, diag / max(np.hypot(L[0], L[1]), 1e-12))
    cast = np.zeros(u.shape, bool)
    # each ray stepped until it is stopped (the same steps as stepping all to the end),
    # MARCH_RAYS rays and MARCH_BLOCK steps at a time
    s0 = start * diag
    for c0 in range(0, u.size, MARCH_RAYS):
        idx = np.arange(c0, min(c0 + MARCH_RAYS, u.size))
        for q in _step_blocks(steps):
            if not idx.size:
                break
            s = s0 + (s_max[idx] - s0)[None, :] * q[:, None]      # (the block's steps, rays)
            with np.errstate(all="ignore"):
                g = (w[idx] + s * L[2]) - f(u[idx] + s * L[0], v[idx] + s * L[1])
                stop = ((s <= s_max[idx]) & np.isfinite(g) & (side[idx] * g < 0)).any(axis=0)
            cast[idx[stop]] = True
            idx = idx[~stop]
    return cast


def layer_hits(funcs, u_rng, v_rng, size, elev, azim, projection="orthographic", d1=None,
               d2=None, scale=None, steps=1500, bisections=40, w_bound=None,
               center=(0.0, 0.0, 0.0)):
    """Every crossing of each pixel's ray with the surface (not only the first, as
    raycast): the sign changes of g = w_ray - f along the marched ray, each refined by
    bisection. Returns (pixel index into the (H, W) picture raveled, screen depth,
    lambert intensity |L.N| with L toward the viewpoint, side +1/-1), one entry a
    crossing."""
    f, fu, fv = funcs
    org, dirn, lam_lo, lam_hi, live, world = _rays(u_rng, v_rng, size, elev, azim, projection,
                                                   d1, d2, scale, w_bound, center)
    org = org.reshape(3, -1)
    dirn = dirn.reshape(3, -1)
    lam_lo, lam_hi, live = lam_lo.ravel(), lam_hi.ravel(), live.ravel()
    ortho = projection.startswith("ortho")

    def g_at(lam, o=org, d=dirn):
        return _gap(f, world, o, d, lam)

    # a ray's steps from k_start to k_end only (its crossings lie between; _window)
    k_start, k_end = _window(world, org, dirn, lam_lo, lam_hi, steps,
                             _bounds_of(funcs, u_rng, v_rng))
    live = live & (k_start < k_end)
    idx, la, lb, sides = [], [], [], []
    g_prev = np.full(lam_lo.shape, np.nan)
    now = np.flatnonzero(live & (k_start == 0))
    g_prev[now] = g_at(lam_lo[now], org[:, now], dirn[:, now])
    lam_prev = lam_lo.copy()
    for k in range(1, steps + 1):
        at = np.flatnonzero(live & (k_start <= k) & (k_end >= k))
        if not at.size:
            continue
        lam = lam_lo[at] + (lam_hi[at] - lam_lo[at]) * (k / steps)
        g = g_at(lam, org[:, at], dirn[:, at])
        gp = g_prev[at]
        with np.errstate(invalid="ignore"):
            hit = (k_start[at] < k) & np.isfinite(g) & np.isfinite(gp) \
                & (np.sign(g) != np.sign(gp)) & (gp != 0)
        where = np.nonzero(hit)[0]
        idx.append(at[where])
        la.append(lam_prev[at][where])
        lb.append(lam[where])
        sides.append(np.where(gp[where] > 0, 1, -1))
        g_prev[at] = np.where(np.isfinite(g), g, np.nan)
        lam_prev[at] = lam
    idx, l_a, l_b, side = (np.concatenate(x) for x in (idx, la, lb, sides))
    o, d = org[:, idx], dirn[:, idx]
    for _ in range(bisections):
        m = 0.5 * (l_a + l_b)
        same = np.sign(g_at(m, o, d)) == np.sign(g_at(l_a, o, d))
        l_a = np.where(same, m, l_a)
        l_b = np.where(same, l_b, m)
    p = o + d * (0.5 * (l_a + l_b))
    u, w, v, _ = world(*p)
    nu, nw, nv = -fu(u, v), np.ones_like(u), -fv(u, v)
    lx, ly, lz = -d if ortho else o - p
    lu, lw, lv, _ = (world(lx, ly, lz)[k] - world(0.0, 0.0, 0.0)[k] for k in range(4))
    with np.errstate(all="ignore"):
        inten = np.abs(lu * nu + lw * nw + lv * nv) / (
            np.sqrt(lu ** 2 + lw ** 2 + lv ** 2) * np.sqrt(nu ** 2 + nw ** 2 + nv ** 2))
    return idx, p[2], inten, side


def composite_layers(surfaces, size, elev, azim, projection="orthographic", **kw):
    """The translucent composite of several surfaces, every crossing of each ray
    (layer_hits), sorted by depth: I = sum_k a_k prod_{m<k} (1 - a_m) I_k over black.
    ``surfaces``: (funcs, u_rng, v_rng, alpha) each. Returns (intensity (H, W), NaN
    where no crossing; crossings per pixel)."""
    W, H = size
    parts = [layer_hits(funcs, u, v, size, elev, azim, projection, **kw) + (np.full(0, a),)
             for funcs, u, v, a in surfaces]
    idx = np.concatenate([x[0] for x in parts])
    depth = np.concatenate([x[1] for x in parts])
    inten = np.concatenate([x[2] for x in parts])
    alpha = np.concatenate([np.full(len(x[0]), a) for x, (_, _, _, a) in zip(parts, surfaces)])
    order = np.lexsort((depth, idx))
    idx, inten, alpha = idx[order], inten[order], alpha[order]
    # transmittance in front of each crossing: the product over the pixel's nearer ones
    log_t = np.log(np.maximum(1.0 - alpha, 1e-300))
    cum = np.cumsum(log_t)
    start = np.r_[0, np.nonzero(np.diff(idx))[0] + 1]
    group = np.repeat(start, np.diff(np.r_[start, len(idx)]))
    before = cum - log_t - np.where(group > 0, cum[np.maximum(group - 1, 0)], 0.0)
    out = np.zeros(W * H)
    np.add.at(out, idx, alpha * np.exp(before) * inten)
    count = np.bincount(idx, minlength=W * H)
    out = np.where(count > 0, out, np.nan)
    return out.reshape(H, W), count.reshape(H, W)


def triangle_hits(o, d, tris, t_min=0.0, chunk=4096):
    """The nearest crossing of each ray o + t d (o, d: (k, 3)) with the triangles
    (m, 3, 3) at t > t_min (Moeller and Trumbore's test). Only the pairs whose ray
    passes within a triangle's bounding sphere are tested (a sphere around its
    centroid through its farthest vertex, a little widened: no crossing is left out).
    Returns (t: inf where none, the triangle's index: -1 where none)."""
    k = len(o)
    best_t = np.full(k, np.inf)
    best_i = np.full(k, -1)
    v0, e1, e2 = tris[:, 0], tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]
    cen = tris.mean(axis=1)
    rad = np.sqrt(((tris - cen[:, None, :]) ** 2).sum(axis=2).max(axis=1))
    rad = rad * (1 + 1e-6) + 1e-12 * (1 + np.abs(cen).max(axis=1))
    for c0 in range(0, k, chunk):
        oo, dd = o[c0:c0 + chunk], d[c0:c0 + chunk]
        with np.errstate(all="ignore"):
            dn = dd / np.linalg.norm(dd, axis=1, keepdims=True)
            oc = cen[None, :, :] - oo[:, None, :]                  # (rays, triangles, 3)
            along = np.einsum("rtj,rj->rt", oc, dn)
            near = (oc ** 2).sum(axis=2) - along ** 2 <= rad[None, :] ** 2
        ri, ti = np.nonzero(near)
        if not len(ri):
            continue
        dr, orr = dd[ri], oo[ri]
        p = np.cross(dr, e2[ti])
        det = np.sum(e1[ti] * p, axis=1)
        with np.errstate(all="ignore"):
            inv = 1.0 / det
            sv = orr - v0[ti]
            a = np.sum(sv * p, axis=1) * inv
            q = np.cross(sv, e1[ti])
            b = np.sum(dr * q, axis=1) * inv
            t = np.sum(e2[ti] * q, axis=1) * inv
            ok = (np.abs(det) > 1e-300) & (a >= 0) & (b >= 0) & (a + b <= 1) & (t > t_min)
        ri, ti, t = ri[ok], ti[ok], t[ok]
        if not len(ri):
            continue
        order = np.lexsort((t, ri))                # each ray's nearest first
        ri, ti, t = ri[order], ti[order], t[order]
        first = np.r_[True, ri[1:] != ri[:-1]]
        best_t[c0 + ri[first]] = t[first]
        best_i[c0 + ri[first]] = ti[first]
    return best_t, best_i


def objects_reference(funcs, u_rng, v_rng, size, elev, azim, projection, d1, d2, scale,
                      center, tris, light, steps=2000, radius=0.0, n_disk=24):
    """A picture of a surface with triangles standing on it (tris (m, 3, 3) in world
    (u, v, w)) and their shadows from a directional light (``light`` toward it, world
    (u, v, w)), independently of floatcol: each pixel's ray meets the surface
    (raycast) or a triangle (triangle_hits), the nearer seen; a seen point is in
    shadow where its seen side (the surface's, or the triangle's turned toward the
    eye) faces away from the light, or where its ray toward the light meets the
    surface (_cast) or another triangle; with ``radius`` (degrees) the light is a disk
    and the cast part the share of ``n_disk`` rays over it (a sunflower spiral, as
    shadow_rays') that are stopped. Returns (kind (H, W): 0 nothing, 1 the surface, 2 a
    triangle; depth (screen z); shadow: 1 / 0 or the share, NaN where nothing)."""
    f, fu, fv = funcs
    ref = raycast(funcs, u_rng, v_rng, size, elev, azim, projection, d1, d2, scale,
                  center=center)
    org, dirn, _, _, _, world = _rays(u_rng, v_rng, size, elev, azim, projection, d1, d2,
                                      scale, None, center)
    ow = np.stack(world(*org)[:3])                          # (u, w, v) at lam = 0
    dw = np.stack(world(*(org + dirn))[:3]) - ow
    o = np.stack([ow[0], ow[2], ow[1]], axis=-1).reshape(-1, 3)    # (u, v, w)
    d = np.stack([dw[0], dw[2], dw[1]], axis=-1).reshape(-1, 3)
    t_tri, i_tri = triangle_hits(o, d, tris, t_min=0.0 if projection.startswith("ortho")
                                 else 1.0)
    hit = i_tri.reshape(org[2].shape) >= 0
    depth_tri = np.where(hit, org[2] + dirn[2] * np.where(hit, t_tri.reshape(hit.shape), 0.0),
                         np.inf)
    H, W = ref.side.shape
    on_tri = (i_tri.reshape(H, W) >= 0) & (depth_tri < ref.depth)
    kind = np.where(on_tri, 2, np.where(ref.side != 0, 1, 0))
    depth = np.where(on_tri, depth_tri, ref.depth)
    L = np.asarray(light, float)
    L = L / np.linalg.norm(L)
    shadow = np.full((H, W), np.nan)
    # the surface's points
    s1 = kind == 1
    u, v = ref.u[s1], ref.v[s1]
    w = f(u, v)
    side = ref.side[s1].astype(float)
    n = np.stack([-fu(u, v), -fv(u, v), np.ones_like(u)], axis=1)
    attached = side * (n @ L) <= 0.0
    pts = np.c_[u, v, w]
    rays = _disk(L, radius, n_disk)
    part = np.zeros(len(pts))
    for Lk in rays:
        cast = _cast(f, u, v, w, side, Lk, u_rng, v_rng, steps, 1e-4)
        by_tri = triangle_hits(pts, np.tile(Lk, (len(pts), 1)), tris, t_min=1e-9)[1] >= 0
        part += cast | by_tri
    shadow[s1] = np.where(attached, 1.0, part / len(rays))
    # the triangles' points
    s2 = kind == 2
    k = i_tri.reshape(H, W)[s2]
    p = o.reshape(H, W, 3)[s2] + t_tri.reshape(H, W)[s2][:, None] * d.reshape(H, W, 3)[s2]
    nrm = np.cross(tris[k, 1] - tris[k, 0], tris[k, 2] - tris[k, 0])
    nrm *= -np.sign(np.sum(nrm * d.reshape(H, W, 3)[s2], axis=1))[:, None]   # toward the eye
    attached = nrm @ L <= 0.0
    part = np.zeros(len(p))
    for Lk in rays:
        cast = _cast(f, p[:, 0], p[:, 1], p[:, 2], np.ones(len(p)), Lk, u_rng, v_rng, steps,
                     1e-4)
        t_o, i_o = triangle_hits(p, np.tile(Lk, (len(p), 1)), tris, t_min=1e-9)
        part += cast | ((i_o >= 0) & (i_o != k))
    shadow[s2] = np.where(attached, 1.0, part / len(rays))
    return kind, depth, shadow


def _disk(L, radius, n_disk):
    """Directions spread evenly over a light's disk of ``radius`` degrees around L (a
    sunflower spiral), or L alone."""
    if radius <= 0.0:
        return L[None]
    e1 = np.cross(L, [0.0, 0.0, 1.0] if abs(L[2]) < 0.9 else [1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(L, e1)
    k = np.arange(n_disk) + 0.5
    r = math.tan(math.radians(radius)) * np.sqrt(k / n_disk)
    a = k * math.pi * (3.0 - math.sqrt(5.0))
    rays = L + r[:, None] * (np.cos(a)[:, None] * e1 + np.sin(a)[:, None] * e2)
    return rays / np.linalg.norm(rays, axis=1, keepdims=True)


def inner(mask):
    """The pixels of mask whose four neighbours are in it too (away from a silhouette,
    where antialiasing blends a pixel with what lies beside it)."""
    m = mask.copy()
    m[1:] &= mask[:-1]
    m[:-1] &= mask[1:]
    m[:, 1:] &= mask[:, :-1]
    m[:, :-1] &= mask[:, 1:]
    return m

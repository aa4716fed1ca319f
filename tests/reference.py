"""An independent reference renderer: per-pixel ray casting on the exact f.

Shares no code with floatcol's kernels. Each pixel's ray (same camera and pixel
convention as DESIGN.md section 3) is clipped to the domain's vertical prism, marched
densely in world coordinates with numpy, and the first sign change of
g = w_ray - f(u, v) is refined by bisection. The upper side is seen where the ray
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
    return tuple(wrap(fn) for fn in fs)


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
    return f, fu, fv


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


def _march(f, org, dirn, lam_lo, lam_hi, live, world, steps):
    """The first crossing of each ray: steps uniform steps from lam_lo to lam_hi, a hit
    where w - f changes sign between two finite values (from a non-zero one). Returns
    (found, side: +1 from above, -1 from below, and the step's ends l_a, l_b), each the
    rays' shape. The same values, step for step, as marching every ray through every
    step at once (what this did before); only the rays still marching are evaluated,
    MARCH_RAYS rays and MARCH_BLOCK steps at a time: a third of the suite's time
    before, most rays hit early."""
    shape = lam_lo.shape
    found = np.zeros(shape, bool)
    side = np.zeros(shape, np.int8)
    l_a = np.zeros(shape)
    l_b = np.zeros(shape)
    rays = np.flatnonzero(live)
    org = org.reshape(3, -1)
    dirn = dirn.reshape(3, -1)
    lam_lo = lam_lo.reshape(-1)
    lam_hi = lam_hi.reshape(-1)
    for c0 in range(0, rays.size, MARCH_RAYS):
        idx = rays[c0:c0 + MARCH_RAYS]
        o, d, lo = org[:, idx], dirn[:, idx], lam_lo[idx]
        span = lam_hi[idx] - lo
        with np.errstate(all="ignore"):
            g_prev = _gap(f, world, o, d, lo)
        g_prev = np.where(np.isfinite(g_prev), g_prev, np.nan)
        s_prev = np.sign(g_prev)
        lam_prev = lo.copy()
        for q in _step_blocks(steps):
            if not idx.size:
                break
            lam = lo[None, :] + span[None, :] * q[:, None]        # (the block's steps, rays)
            with np.errstate(all="ignore"):
                g = _gap(f, world, o[:, None, :], d[:, None, :], lam)
            g[~np.isfinite(g)] = np.nan
            sg = np.sign(g)                      # (NaN where g is: never a crossing)
            sp = np.concatenate([s_prev[None, :], sg[:-1]], axis=0)   # a step before
            # a crossing: both finite, their signs differ, the one before not zero
            cross = (sg != sp) & (sp != 0) & (sg == sg) & (sp == sp)
            hit = cross.any(axis=0)
            if hit.any():
                cols = np.flatnonzero(hit)
                first = cross[:, cols].argmax(axis=0)
                lp = np.concatenate([lam_prev[None, :], lam[:-1]], axis=0)
                at = idx[cols]
                found.reshape(-1)[at] = True
                side.reshape(-1)[at] = np.where(sp[first, cols] > 0, 1, -1)
                l_a.reshape(-1)[at] = lp[first, cols]
                l_b.reshape(-1)[at] = lam[first, cols]
                keep = ~hit
                idx, o, d, lo, span = idx[keep], o[:, keep], d[:, keep], lo[keep], span[keep]
                sg, lam = sg[:, keep], lam[:, keep]
            s_prev = sg[-1]
            lam_prev = lam[-1]
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
    found, side, l_a, l_b = _march(f, org, dirn, lam_lo, lam_hi, live, world, steps)
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
    if radius > 0.0:
        e1 = np.cross(L, [0.0, 0.0, 1.0] if abs(L[2]) < 0.9 else [1.0, 0.0, 0.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(L, e1)
        k = np.arange(n_disk) + 0.5
        r = math.tan(math.radians(radius)) * np.sqrt(k / n_disk)
        a = k * math.pi * (3.0 - math.sqrt(5.0))
        rays = L + r[:, None] * (np.cos(a)[:, None] * e1 + np.sin(a)[:, None] * e2)
        rays /= np.linalg.norm(rays, axis=1, keepdims=True)
    else:
        rays = L[None]
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

    idx, la, lb, sides = [], [], [], []
    g_prev = np.where(live, g_at(lam_lo), np.nan)
    lam_prev = lam_lo.copy()
    for k in range(1, steps + 1):
        lam = lam_lo + (lam_hi - lam_lo) * (k / steps)
        g = g_at(lam)
        with np.errstate(invalid="ignore"):
            hit = live & np.isfinite(g) & np.isfinite(g_prev) & (np.sign(g) != np.sign(g_prev)) \
                & (g_prev != 0)
        where = np.nonzero(hit)[0]
        idx.append(where)
        la.append(lam_prev[where])
        lb.append(lam[where])
        sides.append(np.where(g_prev[where] > 0, 1, -1))
        g_prev = np.where(np.isfinite(g), g, np.nan)
        lam_prev = lam
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

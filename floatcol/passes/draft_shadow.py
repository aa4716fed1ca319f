"""A draft's shadows (passes/draft.py, Gordon section 6.2) in numpy: a fresh install's
first picture with shadows while the kernels compile (floatcol/warmup.py).

The same shadow texture as passes/shadow.py's, made and read without a compile:

- **the texture** (section 6.2.1, kernels/shadow.py horizon_sweeps): f on the texel
  grid of the light's lines (passes/shadow.py Texture.grid, at most MAX_TEXELS texels:
  the on-the-fly method's larger grid too), H = f - sigma tan(theta), and each texel's
  highest and lowest H strictly beyond it toward the light: a running maximum and
  minimum from the light's side, numpy's ``maximum.accumulate`` over every line at
  once;
- **the lookup** (point_shadow): attached where the seen side faces away from the
  light; cast where the point lies below its own horizon, by the texels' own depths
  averaged bilinearly on the point's side of a wall; the margin over one texel's rise
  antialiases the edge, with the same bias where the light grazes;
- **soft shadows** (a light of angular radius rho, soft_shadow): the part of the
  light's disk below the horizon, along the light from the steepest rise of H to the
  texels beyond (each line's convex hull, horizon_slopes', every line's stack popped
  at once: _hull_slopes), across it in STRIPS strips each with its displaced line's
  occluder.

Given the kernels' G-buffer, it gives the kernels' shadows (within float rounding:
tests/test_draft.py).

Several surfaces (render_many) have a layer each in the texture, and a point takes
another layer's shadow where the light's ray crosses it (the kernels' _crossed: between
that layer's extremes beyond it). Objects cast their shadows on the draft's points by
the kernels' own code (the objects' kernels compile in a few seconds), and the
surfaces' fall on them from the draft's planes.
"""
from __future__ import annotations

import math

import numpy as np

from ..kernels import layout as L
from ..kernels.shadow import NONE, SLOPE_NONE, STRIP_SPREAD, STRIPS, WALL
from .shadow import BIAS_TEXELS, GRAZING, MAX_TEXELS


def texture_planes(texture):
    """A draft's shadow texture of the layers ``texture.drawn`` (the object ``texture``,
    passes/shadow.py Texture, not swept): hmax, hmin, hsurf (layers, lines, samples)
    float32 as the kernels' horizon_sweeps make them (on a grid of at most MAX_TEXELS
    texels), and for a light of a radius the slopes (4 layers, lines, samples) of
    horizon_slopes; made once a texture (every layer's draft reads them)."""
    from types import SimpleNamespace
    held = getattr(texture, "draft_planes", None)
    if held is not None:
        return held
    h, s0, t0, n_sig, n_tau = texture.grid(MAX_TEXELS)
    gu, gv, tan_theta = texture.gu, texture.gv, texture.tan_theta
    n = len(texture.drawn)
    hmax = np.empty((n, n_tau, n_sig), dtype=np.float32)
    hmin = np.empty((n, n_tau, n_sig), dtype=np.float32)
    hsurf = np.empty((n, n_tau, n_sig), dtype=np.float32)
    sigma = s0 + np.arange(n_sig) * h
    tau = (t0 + np.arange(n_tau) * h)[:, None]
    u = sigma * gu - tau * gv
    v = sigma * gv + tau * gu
    for layer, (surface, ((ua, ub), (va, vb))) in enumerate(texture.drawn):
        inside = (u >= ua) & (u <= ub) & (v >= va) & (v <= vb)
        w = np.full(u.shape, np.nan)
        if inside.any():
            w[inside] = surface.evaluate(u[inside], v[inside])
        with np.errstate(invalid="ignore"):
            hs = np.where(np.isfinite(w), (w - texture.w_origin) - sigma * tan_theta, np.nan)
        del w, inside
        # the running extremes from the light's side (the last sample), strictly beyond
        run = np.maximum.accumulate(np.where(np.isnan(hs), -NONE, hs)[:, ::-1], axis=1)[:, ::-1]
        hmax[layer, :, :-1] = run[:, 1:]
        hmax[layer, :, -1] = -NONE
        run = np.minimum.accumulate(np.where(np.isnan(hs), NONE, hs)[:, ::-1], axis=1)[:, ::-1]
        hmin[layer, :, :-1] = run[:, 1:]
        hmin[layer, :, -1] = NONE
        del run
        hsurf[layer] = hs
    out = SimpleNamespace(h=h, s0=s0, t0=t0, gu=gu, gv=gv, tan_theta=tan_theta,
                          rho=texture.rho, hmax=hmax, hmin=hmin, hsurf=hsurf, slopes=None)
    if texture.rho > 0.0:
        out.slopes = np.concatenate([_slopes(hsurf[layer], h) for layer in range(n)])
    texture.draft_planes = out
    return out


def _slopes(hs, h):
    """horizon_slopes' planes (4, lines, samples) of the heights hs (lines, samples)
    float32: the steepest rise to a texel beyond toward the light and its ground
    distance, the steepest descent and its distance; NaN where hs is, a rise of
    -SLOPE_NONE (descent +SLOPE_NONE) at distance 0 where nothing lies beyond."""
    out = np.empty((4,) + hs.shape)
    out[0], out[2] = _hull_slopes(hs, h, 1.0)
    out[1], out[3] = _hull_slopes(hs, h, -1.0)
    out[:, np.isnan(hs)] = np.nan
    return out


def _hull_slopes(hs, h, sign):
    """kernels/shadow.py horizon_slopes' sweep of every line at once: each line's upper
    (sign 1) or lower (-1) convex hull on a stack from the light's side, a texel's
    steepest rise (descent) the one to the hull's last texel once those under the chord
    to the next are popped. The lines pop together, as many rounds as the line with
    the most pops needs, each round over the lines still popping. The arithmetic is
    the kernel's (float32 differences), so the planes are its own."""
    n_lines, n = hs.shape
    stack = np.zeros((n_lines, n), dtype=np.int64)
    size = np.zeros(n_lines, dtype=np.int64)
    rise = np.full(hs.shape, -sign * SLOPE_NONE)
    dist = np.zeros(hs.shape)
    lines = np.arange(n_lines)
    for i in range(n - 1, -1, -1):
        H = hs[:, i]
        ok = ~np.isnan(H)
        act = lines[ok & (size >= 2)]
        while act.size:
            k = size[act]
            a = stack[act, k - 1]
            b = stack[act, k - 2]
            Hi = H[act]
            pop = sign * (hs[act, a] - Hi) * (b - i) <= sign * (hs[act, b] - Hi) * (a - i)
            act = act[pop]
            size[act] -= 1
            act = act[size[act] >= 2]
        have = lines[ok & (size > 0)]
        a = stack[have, size[have] - 1]
        rise[have, i] = (hs[have, a] - H[have]) / ((a - i) * h)
        dist[have, i] = (a - i) * h
        put = lines[ok]
        stack[put, size[put]] = i
        size[put] += 1
    return rise, dist


class _Cells:
    """The texel cells of points at float texel indices (y, x) (kernels/shadow.py
    _cell's: clamped to the texture's edges) and the bilinear weights of their four
    texels; each plane's four texels gathered once (``corners``)."""

    def __init__(self, shape, y, x):
        y = np.where(np.isfinite(y), y, 0.0)
        x = np.where(np.isfinite(x), x, 0.0)
        i = np.clip(np.floor(y), 0, shape[0] - 2).astype(np.int64)
        j = np.clip(np.floor(x), 0, shape[1] - 2).astype(np.int64)
        fy = np.clip(y - i, 0.0, 1.0)
        fx = np.clip(x - j, 0.0, 1.0)
        at = i * shape[1] + j
        self.at = [at, at + 1, at + shape[1], at + shape[1] + 1]
        self.weights = [(1.0 - fy) * (1.0 - fx), (1.0 - fy) * fx, fy * (1.0 - fx), fy * fx]
        self._got = {}

    def corners(self, a):
        """a's four texels around each point (float64; NaN where a has them)."""
        got = self._got.get(id(a))
        if got is None or got[0] is not a:
            flat = a.ravel()
            got = self._got[id(a)] = (a, [flat.take(k).astype(np.float64) for k in self.at])
        return got[1]

    def bilinear(self, a):
        return sum(val * wgt for val, wgt in zip(self.corners(a), self.weights))

    def average(self, a, ok):
        """a averaged with the bilinear weights over the texels where ``ok`` (a list of
        four masks), NaN where none is."""
        acc = 0.0
        wsum = 0.0
        for val, wgt, k in zip(self.corners(a) if not isinstance(a, list) else a,
                               self.weights, ok):
            acc = acc + np.where(k, wgt * val, 0.0)
            wsum = wsum + np.where(k, wgt, 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(wsum > 1e-9, acc / wsum, np.nan)


def _texels_rise(hsurf, cells):
    """The highest less the lowest H of the surface's four texels (-inf where none)."""
    hs = np.stack(cells.corners(hsurf))
    with np.errstate(invalid="ignore"):
        return np.fmax.reduce(hs, axis=0) - np.fmin.reduce(hs, axis=0)


def _hard(t, upper, facing, hp, cells, layer=0, crossed=None):
    """point_shadow's cast part over arrays (layer ``layer``'s points of one side): the
    point's depth below its own horizon over one texel's rise, 1 in shadow, 0 lit,
    between at the edge. The depth: the texels' own (hmax - H upper, H - hmin lower)
    averaged over those of the surface on the point's side of a wall (_own_depth),
    else the horizon interpolated; at least how far it lies inside another layer
    (``crossed``, _crossed's)."""
    hext = t.hmax[layer] if upper else t.hmin[layer]
    hsurf = cells.corners(t.hsurf[layer])
    rise = _texels_rise(t.hsurf[layer], cells)
    with np.errstate(invalid="ignore"):
        near = np.where(rise > WALL * t.h, 0.5 * rise, np.inf)
        ok = [~np.isnan(hs) & (np.abs(hs - hp) <= near) for hs in hsurf]
    depth = [he - hs if upper else hs - he for hs, he in zip(hsurf, cells.corners(hext))]
    margin = cells.average(depth, ok)
    horizon = cells.bilinear(hext) - hp if upper else hp - cells.bilinear(hext)
    margin = np.where(np.isnan(margin), horizon, margin)
    if crossed is not None:
        margin = np.maximum(margin, crossed)
    width = abs(t.tan_theta) * t.h
    bs = np.where(facing < GRAZING, BIAS_TEXELS * width, 0.0)
    return np.clip((margin - bs) / max(width, 1e-300) + 0.5, 0.0, 1.0)


def _occluder(rise, dist, hsurf, cells):
    """kernels/shadow.py _occluder over arrays: (H, D) of what makes the horizon of
    the texels around, averaged over those of the surface with something beyond;
    (NaN, 0) where none has."""
    hs, r, d = cells.corners(hsurf), cells.corners(rise), cells.corners(dist)
    with np.errstate(invalid="ignore"):
        ok = [~np.isnan(a) & (b > 0.0) for a, b in zip(hs, d)]
    occ = cells.average([a + b * c for a, b, c in zip(hs, r, d)], ok)
    return occ, np.nan_to_num(cells.average(d, ok), nan=0.0)


def _half_chords(x):
    x = np.clip(x, -1.0, 1.0)
    return 0.5 * (x * np.sqrt(1.0 - x * x) + np.arcsin(x))


def _blocked(x):
    """The part of a disk of radius 1 below a chord x above its centre."""
    x = np.clip(x, -1.0, 1.0)
    return (x * np.sqrt(1.0 - x * x) + np.arcsin(x)) / math.pi + 0.5


def _strip_blocked(x0, x1, y):
    """kernels/shadow.py _strip_blocked over an array y: the area of the unit disk's
    strip x0 <= x <= x1 below the line at height y."""
    yc = np.clip(y, -1.0, 1.0)
    c = np.sqrt(1.0 - yc * yc)
    a = np.maximum(x0, -c)
    b = np.minimum(x1, c)
    area = np.where(b > a, yc * (b - a) + _half_chords(b) - _half_chords(a), 0.0)
    above = yc > 0.0
    area += np.where(above & (x0 < -c),
                     2.0 * (_half_chords(np.minimum(x1, -c)) - _half_chords(x0)), 0.0)
    area += np.where(above & (x1 > c),
                     2.0 * (_half_chords(x1) - _half_chords(np.maximum(x0, c))), 0.0)
    full = 2.0 * (_half_chords(x1) - _half_chords(x0))
    return np.where(y >= 1.0, full, np.where(y <= -1.0, 0.0, area))


def _soft(t, upper, pt, ps, hp, cells, hard, layer=0, crossed=None):
    """soft_shadow's value over arrays (layer ``layer``'s points of one side), ``hard``
    the hard answer, kept where the texels know no horizon or straddle a wall: the part
    of the light's disk below the horizon rising at m over the light's ray, made at
    distance D; where the disk's rays spread over more than STRIP_SPREAD texels
    across the light, STRIPS strips each with its displaced line's occluder
    (_disk_below); at least another layer's hard, antialiased crossing (``crossed``)."""
    side = 0 if upper else 1
    hsurf = t.hsurf[layer]
    rise, dist = t.slopes[4 * layer + side], t.slopes[4 * layer + 2 + side]
    surface = [~np.isnan(hs) for hs in cells.corners(hsurf)]
    m = cells.average(rise, surface)
    D = cells.average(dist, surface)
    soft = ~np.isnan(m) & ~(_texels_rise(hsurf, cells) > WALL * t.h)
    out = hard.copy()
    if not soft.any():
        return out
    m, D, pt, ps, hp = m[soft], D[soft], pt[soft], ps[soft], hp[soft]
    theta = math.atan(t.tan_theta)
    rho = t.rho
    sgn = 1.0 if upper else -1.0
    spread = D * math.tan(rho) / (math.cos(theta) * t.h)        # across, in texels
    val = _blocked(sgn * (np.arctan(t.tan_theta + m) - theta) / rho)
    wide = spread > STRIP_SPREAD
    if wide.any():
        m, D, pt, ps, hp, spread = m[wide], D[wide], pt[wide], ps[wide], hp[wide], spread[wide]
        area = np.zeros(m.shape)
        dx = 2.0 / STRIPS
        for q in range(STRIPS):
            x0 = -1.0 + q * dx
            hk, dk = _occluder(rise, dist, hsurf,
                               _Cells(hsurf.shape, pt + (x0 + 0.5 * dx) * spread, ps))
            with np.errstate(invalid="ignore", divide="ignore"):
                mk = np.where(np.isnan(hk), -sgn * SLOPE_NONE,
                              np.where(dk < 0.5 * D, m, (hk - hp) / dk))
            area += _strip_blocked(x0, x0 + dx,
                                   sgn * (np.arctan(t.tan_theta + mk) - theta) / rho)
        val[wide] = np.minimum(area / math.pi, 1.0)
    if crossed is not None:     # other layers: their hard, antialiased crossings
        val = np.maximum(val, np.clip(crossed[soft] / max(abs(t.tan_theta) * t.h, 1e-300)
                                      + 0.5, 0.0, 1.0))
    out[soft] = val
    return out


def draft_shadow(texture, layer, view, g, side):
    """(shadow, lit) (H, W) float32, rows from the bottom, of layer ``layer``'s draft
    G-buffer g (H, W, G_SIZE: u, v from the view's centre, w from its w_origin, unit
    normals) and seen sides ``side`` (+1, -1, 0): shadow 1 / 0 / between, NaN where
    nothing is seen; lit = 1 - shadow (1 where nothing is seen), as passes/shadow.py
    shadow_pass's. ``texture`` the light's passes/shadow.py Texture (not swept) of
    the layers ``texture.drawn``."""
    H, W = side.shape
    shadow = np.full((H, W), np.nan, dtype=np.float32)
    seen = side != 0
    planes = shadow_planes(texture)
    if seen.any():
        shadow[seen] = shadow_of(planes, view, g[seen], side[seen], layer)
    lit = np.where(seen, 1.0 - shadow, 1.0).astype(np.float32)
    if texture.occluders is not None:
        # the objects: their shadows on the surface (passes/shadow.py objects_cast, the
        # kernels' own code on the draft's points), and the texture's planes the draft's,
        # which the objects pass reads for the surface's shadows on them (objects.py
        # _surfaces_cast)
        adopt(texture)
        from .shadow import objects_cast
        with np.errstate(invalid="ignore"):
            point = np.stack([g[..., L.G_U] + view.center[0], g[..., L.G_V] + view.center[1],
                              g[..., L.G_W] + view.w_origin], axis=-1)[::-1].astype(np.float64)
        # (as tiles of one lane: the kernels' layout, (H, tiles, lanes, 3))
        objects_cast(texture.occluders, point.reshape(H, W, 1, 3), shadow[::-1], lit[::-1])
    return shadow, lit


def adopt(texture):
    """The draft's planes (texture_planes') as the Texture's own, as its kernels' sweep
    leaves them (passes/shadow.py Texture._sweep): what the objects pass reads for the
    surfaces' shadows on the objects (none at the zenith)."""
    if texture.zenith:
        return
    t = texture_planes(texture)
    texture.hmax, texture.hmin, texture.hsurf = t.hmax, t.hmin, t.hsurf
    texture.slopes = np.zeros((0, 1, 1)) if t.slopes is None else t.slopes
    texture.texels = t.hsurf.size


def shadow_planes(texture):
    """What shadow_of reads: (texture, its planes (texture_planes'), or None where the
    light stands at the zenith: attached shadows alone)."""
    return texture, None if texture.zenith else texture_planes(texture)


def shadow_of(planes, view, g, s, layer=0):
    """The shadow (n,) of layer ``layer``'s points g (n, G_SIZE) seen from sides s (n,)
    (+1 upper, -1 lower): 1 attached (the seen side faces away from the light) or in
    the cast shadow (its own layer's horizon, or another layer that the light's ray
    crosses), 0 lit, between at an edge or in a penumbra; ``planes`` shadow_planes'."""
    texture, t = planes
    light = np.asarray(view.light, dtype=np.float64)
    nx, ny, nz = (g[:, ch].astype(np.float64) for ch in (L.G_NX, L.G_NY, L.G_NZ))
    nn = np.sqrt(nx * nx + ny * ny + nz * nz)
    with np.errstate(invalid="ignore", divide="ignore"):
        facing = np.where(nn > 0.0, s * (nx * light[0] + ny * light[1] + nz * light[2]) / nn,
                          0.0)
    out = np.ones(s.shape)                         # attached where not facing the light
    lit_side = facing > 0.0
    if t is None or not lit_side.any():
        return np.where(lit_side, 0.0, out)
    for upper in (True, False):
        at = lit_side & ((s > 0) if upper else (s < 0))
        if not at.any():
            continue
        u = g[at, L.G_U].astype(np.float64) + view.center[0]    # (layout.py G_U, G_W)
        v = g[at, L.G_V].astype(np.float64) + view.center[1]
        w = g[at, L.G_W].astype(np.float64)       # (from w_origin, as the texture's)
        along = u * t.gu + v * t.gv
        ps = (along - t.s0) / t.h
        pt = (-u * t.gv + v * t.gu - t.t0) / t.h
        hp = w - along * t.tan_theta
        cells = _Cells(t.hsurf[0].shape, pt, ps)
        crossed = _crossed(t, layer, hp, cells)
        val = _hard(t, upper, facing[at], hp, cells, layer, crossed)
        if t.rho > 0.0:
            val = _soft(t, upper, pt, ps, hp, cells, val, layer, crossed)
        out[at] = val
    return out


def _crossed(t, layer, hp, cells):
    """kernels/shadow.py _crossed over arrays: how far each point at H = hp lies between
    another layer's extremes beyond it (the light's ray crosses that layer), the most
    over the other layers; None with one layer."""
    out = None
    for m in range(t.hmax.shape[0]):
        if m != layer:
            c = np.minimum(cells.bilinear(t.hmax[m]) - hp, hp - cells.bilinear(t.hmin[m]))
            out = c if out is None else np.maximum(out, c)
    return out

"""The shadow pass (Gordon section 6.2): which seen points the light does not reach.

After the geometry pass of a layer, for a directional light L (a direction in the
box's (u, v, w)):

- **attached shadow**: the seen side faces away from the light, (side N) . L <= 0;
- **cast shadow** (section 6.2.1's shadow texture): the floating-horizon sweeps of
  kernels/shadow.py over the domain along the light's ground direction, at about one
  texel per pixel of the picture, give each point's horizon seen from the light;
  a seen point (u, v, w from the G-buffer) below the horizon interpolated at its
  (u, v) is in shadow. Its margin below the horizon, over the height that one texel
  of ground makes along the light's ray, antialiases the shadow's edge: a value
  between 0 and 1 where the edge crosses the pixel.

A light of angular radius rho (``Light.radius``, degrees: the sun's 0.27) casts soft
shadows: from each texel's horizon toward the light (kernels/shadow.py
horizon_slopes), the part of the light's disk that the horizon hides; the penumbra
behind an edge at distance D is about 2 rho D wide on the ground.

Section 6.2.2, ``method="on-the-fly"``: no texture; the same planes through the light
sweep the domain from the light's side keeping only their front (each line's running
extremes and last two samples), and each seen pixel is answered when the front
passes it (kernels/shadow.py shadow_sweep), with the same interpolation: O(lines)
memory instead of the texture's O(lines x samples). One surface at a time (the
texture lets several shadow each other).

Returns ``shadow`` (H, W) float32: 1 in shadow, 0 lit, between at edges, NaN where
nothing is seen; and ``lit`` = 1 - shadow (1 where nothing is seen), which the
finishing pass multiplies the diffuse and specular light by.
"""
from __future__ import annotations

import math
import weakref

import numpy as np

from .. import _pool
from ..kernels.layout import G_U, G_W, SURF_FUNCTION, VP_CU, VP_CV, VP_WORG
from ..kernels.shadow import (
    BAND, horizon_slopes, horizon_sweeps, shadow_lookup, shadow_sweep, sweep_cells, sweep_order,
)
from .geometry import BATCH_MIN_SAMPLES

#: most texels of a shadow texture (its memory: three float32 planes a layer, 46 MiB;
#: soft shadows four float64 planes more)
MAX_TEXELS = 4_000_000
#: most cells of the on-the-fly sweep's grid (section 6.2.2: no texture, but a sweep
#: over every cell; a fly camera's nearest footprint over a whole DEM asked 1.4e11 of
#: them and the process was killed for memory)
MAX_SWEEP_CELLS = 16_000_000
#: texels per pixel of the picture along each axis
TEXELS_PER_PIXEL = 1.0
#: a light within this of the zenith (|ground| / |L|) casts no shadow of its own:
#: the sweeps' lines would have no direction
ZENITH = 1e-9
#: the bias against a point's own surface where the light grazes it (its N.L below
#: GRAZING), in texels of rise along the ray
BIAS_TEXELS = 1.0
GRAZING = 0.03


#: the last shadow texture of one surface: (a weak reference to the surface, what it
#: was made for, its planes), or None; one at a time (a texture is up to 46 MiB, soft
#: shadows' 168)
_held = [None]


def forget():
    """Let the kept shadow texture go (benchmarks/bench_shadow.py times a new
    light's)."""
    _held[0] = None


def _gone(ref):
    """The kept texture's surface is gone: let its texture go too."""
    held = _held[0]
    if held is not None and held[0] is ref:
        _held[0] = None


def empty():
    """The finishing pass's ``lit`` when shadows are off: all light everywhere."""
    return np.zeros((0, 0), dtype=np.float32)


class Texture:
    """The shadow texture of a light over the layers' domains (section 6.2.1): for
    each layer and texel the highest and lowest H = f - sigma tan(theta) strictly
    beyond it toward the light (``hmax``, ``hmin``: (layers, lines, samples)); a point
    is shadowed by its own layer's horizon, and by another layer where the ray crosses
    it (kernels/shadow.py shadow_lookup), so layers shadow each other."""

    def __init__(self, drawn, view, light_world, radius=0.0, method="texture", sweep=True):
        lw = np.asarray(light_world, dtype=np.float64)
        #: the layers (surface, domain) it is the texture of
        self.drawn = drawn
        #: the objects' triangles as casters (objects.Occluders), or None
        self.occluders = None
        #: the light's angular radius in radians (0: a point at infinity, hard shadows)
        self.rho = math.radians(radius)
        #: soft shadows' horizons (4 layers, lines, samples: horizon_slopes'), or empty
        self.slopes = np.zeros((0, 1, 1))
        #: section 6.2.2: no texture, the sweep runs with the lookup (shadow_pass)
        self.on_the_fly = method == "on-the-fly"
        self.light = lw / np.linalg.norm(lw)
        #: what the texture's heights are kept from: the view's w_origin, as the
        #: G-buffer's w (layout.py G_W)
        self.w_origin = view.w_origin
        ground = math.hypot(self.light[0], self.light[1])
        self.texels = 0
        #: whether the planes are made (sweep=False: a draft's, passes/draft_shadow.py)
        self.swept = False
        self.zenith = ground <= ZENITH
        if self.zenith:
            return
        self.gu, self.gv = self.light[0] / ground, self.light[1] / ground
        self.tan_theta = self.light[2] / ground
        corners = np.array([(u, v) for _, ((ua, ub), (va, vb)) in drawn
                            for u in (ua, ub) for v in (va, vb)])
        self._sig = corners @ np.array([self.gu, self.gv])
        self._tau = corners @ np.array([-self.gv, self.gu])
        # a pixel's footprint on the ground: 1 / scale, in perspective at the nearest
        # point of the surface (as the sampling planes' step)
        self._h = 1.0 / (view.scale * TEXELS_PER_PIXEL)
        if not view.orthographic:
            self._h *= max(view.q_near / view.d1, 1.0)
        cap = MAX_SWEEP_CELLS if self.on_the_fly else MAX_TEXELS
        h, self.s0, self.t0, n_sig, n_tau = self.grid(cap)
        self.h = h
        self.n_sig, self.n_tau = n_sig, n_tau
        if self.on_the_fly:
            if self.rho > 0.0:
                raise ValueError("soft shadows (light_radius) need the shadow texture, their "
                                 "penumbrae reaching across its lines: use shadows=True")
            if len(drawn) > 1:
                raise ValueError("shadows='on-the-fly' draws the shadows of one surface: "
                                 "use shadows=True (the shadow texture) for several")
            return
        if sweep:
            self._sweep(drawn)

    def grid(self, cap):
        """(h, s0, t0, n_sig, n_tau): the texel grid over the layers' domains, texels h
        apart along the light's ground direction (sigma from s0) and across it (tau from
        t0), about a pixel's footprint each and at most ``cap`` of them."""
        span_sig = float(self._sig.max() - self._sig.min())
        span_tau = float(self._tau.max() - self._tau.min())
        h = self._h
        if not (math.isfinite(span_sig) and math.isfinite(span_tau) and math.isfinite(h)
                and h > 0.0):
            raise ValueError("shadows need a domain of a finite size: the ranges of u and v "
                             "are too wide")
        # (a huge domain against the pixel's footprint: the cap below takes it)
        h = max(h, max(span_sig, span_tau) / (MAX_SWEEP_CELLS + MAX_TEXELS))
        n_sig = int(math.ceil(span_sig / h)) + 3
        n_tau = int(math.ceil(span_tau / h)) + 3
        if n_sig * n_tau > cap:
            h *= math.sqrt(n_sig * n_tau / cap)
            n_sig = int(math.ceil(span_sig / h)) + 3
            n_tau = int(math.ceil(span_tau / h)) + 3
        return h, float(self._sig.min() - h), float(self._tau.min() - h), n_sig, n_tau

    def _sweep(self, drawn):
        """The planes hmax, hmin, hsurf (and soft shadows' slopes) by kernels/shadow.py's
        sweeps, or the kept ones of the same surface, light and grid."""
        h, n_sig, n_tau = self.h, self.n_sig, self.n_tau
        self.swept = True
        # the last texture of one surface is kept (_held) for the same light and texel
        # grid: a fly-through's frames (the grid capped at MAX_TEXELS: the same for
        # every frame) or an orthographic view turned at one scale need it again (a
        # 4097^2 DEM's sweeps took 85 of a 1280x720 frame's 219 ms)
        key = (self.light.tobytes(), self.rho, h, self.s0, self.t0, n_sig, n_tau,
               self.w_origin, tuple((float(ua), float(ub), float(va), float(vb))
                                    for _, ((ua, ub), (va, vb)) in drawn))
        held = _held[0]
        if (held is not None and len(drawn) == 1 and held[0]() is drawn[0][0]
                and held[1] == key):
            self.hmax, self.hmin, self.hsurf, self.slopes = held[2]
            self.texels = n_sig * n_tau
            return
        # one texture per layer: a layer's own surface is a height field under which
        # nothing of it lies (its horizon's maximum decides), while another layer
        # shadows a point only where the ray crosses it (it may pass under a plate)
        self.hmax = _pool.empty((len(drawn), n_tau, n_sig), np.float32)
        self.hmin = _pool.empty((len(drawn), n_tau, n_sig), np.float32)
        self.hsurf = _pool.empty((len(drawn), n_tau, n_sig), np.float32)
        for layer, (surface, ((ua, ub), (va, vb))) in enumerate(drawn):
            domain = np.array([ua, ub, va, vb], dtype=np.float64)
            # f a line at a time in SIMD code where the texture repays the evaluator's
            # compile (as the column pass's batches: geometry.BATCH_MIN_SAMPLES)
            fb = (surface.batch() if n_sig * n_tau >= BATCH_MIN_SAMPLES
                  and surface.kind == SURF_FUNCTION else None)
            kind, f, _, fb, hf, hfp = surface.kernel_args(fb)
            horizon_sweeps(kind, f, fb, hf, hfp, domain, self.gu, self.gv, self.tan_theta,
                           self.s0, self.t0, h, self.hmax, self.hmin, self.hsurf, layer,
                           self.w_origin)
        if self.rho > 0.0:
            self.slopes = _pool.empty((4 * len(drawn), n_tau, n_sig), np.float64)
            for layer in range(len(drawn)):
                horizon_slopes(self.hsurf, layer, h, self.slopes)
        self.texels = n_sig * n_tau * len(drawn)
        _held[0] = None if len(drawn) != 1 else (
            weakref.ref(drawn[0][0], _gone), key,
            (self.hmax, self.hmin, self.hsurf, self.slopes))


def shadow_pass(texture, view, geom, W, H, layer=0):
    """(shadow, lit) of one layer: ``texture`` the light's (Texture), ``view`` the
    layer's View (its light: the same one, in screen coordinates), ``geom`` its
    Geometry (kernels/shadow.py shadow_lookup, in parallel over the columns)."""
    # (pooled: fresh pages cost their faults; every pixel is written below)
    shadow = _pool.empty((H, W), np.float32)
    lit = _pool.empty((H, W), np.float32)
    light = np.asarray(view.light, dtype=np.float64)
    if texture.on_the_fly and not texture.zenith:
        return _on_the_fly(texture, geom, W, H, light, shadow, lit)
    _lookup(texture, geom, W, light, shadow, lit, layer)
    if texture.occluders is not None:
        # the G-buffer's seen points, top row first: (H, tiles, lanes, u v w), a view
        # (u, v from the view's centre: layout.py G_U; the G-buffer holds anything where
        # nothing is seen, signalling NaNs too: not read there)
        with np.errstate(invalid="ignore"):
            point = geom.gbuf[:, ::-1, :, G_U:G_W + 1].transpose(1, 0, 2, 3).astype(np.float64)
            point[..., 0] += geom.vp[VP_CU]
            point[..., 1] += geom.vp[VP_CV]
            point[..., 2] += geom.vp[VP_WORG]
        objects_cast(texture.occluders, point, shadow, lit)
    return shadow, lit


def objects_cast(occluders, point, shadow, lit):
    """The objects' cast shadows on a layer's seen points ``point`` (H, tiles, lanes,
    3) as a tiled G-buffer holds them (a draft's: lanes 1), in the box, top row first
    (objects.Occluders or DiskOccluders ``cast``), into shadow and lit (H, W) in place:
    1 where a triangle stands between the point and the light, the part of the pixel in
    shadow at the shadow's edge, the part of the light's disk hidden for a light of a
    radius (a draft's too, passes/draft_shadow.py)."""
    cast = occluders.cast(point, shadow < 1.0, ~np.isnan(shadow))   # (NaN: nothing seen)
    np.maximum(shadow, cast, out=shadow)                      # (NaN stays NaN)
    changed = cast > 0.0
    lit[changed] = 1.0 - shadow[changed]


def _lookup(texture, geom, W, light, shadow, lit, layer):
    """shadow_pass's texture lookup (kernels/shadow.py shadow_lookup)."""
    cu, cv = geom.vp[VP_CU], geom.vp[VP_CV]     # (the G-buffer's u, v from there)
    if texture.zenith:
        none = np.zeros((0, 1, 1), dtype=np.float32)
        shadow_lookup(geom.gbuf, geom.ebuf, W, cu, cv, light, none, none, none, none,
                      layer, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, GRAZING, BIAS_TEXELS, 0.0, shadow,
                      lit)
    else:
        shadow_lookup(geom.gbuf, geom.ebuf, W, cu, cv, light, texture.hmax, texture.hmin,
                      texture.hsurf, texture.slopes, layer, texture.gu, texture.gv,
                      texture.tan_theta, texture.s0, texture.t0, texture.h, GRAZING,
                      BIAS_TEXELS, texture.rho, shadow, lit)


def _on_the_fly(sweep, geom, W, H, light, shadow, lit):
    """shadow_pass by section 6.2.2 (kernels/shadow.py shadow_sweep)."""
    n_sig, n_tau, h = sweep.n_sig, sweep.n_tau, sweep.h
    cell = _pool.empty((H, W), np.int32)
    cu, cv = geom.vp[VP_CU], geom.vp[VP_CV]     # (the G-buffer's u, v from there, and
    wo = geom.vp[VP_WORG]                       # its w and the sweep's heights from wo)
    sweep_cells(geom.gbuf, geom.ebuf, W, cu, cv, sweep.gu, sweep.gv, sweep.s0, sweep.t0, h,
                n_sig, n_tau, cell)
    n_cells = ((n_tau - 2) // BAND + 1) * n_sig
    start = np.empty(n_cells + 1, dtype=np.int64)
    seen = cell >= 0
    order = np.empty(int(seen.sum()), dtype=np.int32)
    sweep_order(cell, n_cells, start, order)
    shadow[~seen] = np.nan
    lit[~seen] = 1.0
    surface, ((ua, ub), (va, vb)) = sweep.drawn[0]
    fb = (surface.batch() if n_sig * n_tau >= BATCH_MIN_SAMPLES
          and surface.kind == SURF_FUNCTION else None)
    kind, f, _, fb, hf, hfp = surface.kernel_args(fb)
    shadow_sweep(kind, f, fb, hf, hfp, np.array([ua, ub, va, vb], dtype=np.float64), sweep.gu,
                 sweep.gv, sweep.tan_theta, sweep.s0, sweep.t0, h, n_sig, n_tau, geom.gbuf,
                 geom.ebuf, W, cu, cv, wo, light, start, order, GRAZING, BIAS_TEXELS, shadow,
                 lit)
    return shadow, lit

"""Render: what a picture is, as arrays (the public contract of DESIGN.md section 3)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import _pool
from .kernels.layout import G_NX, G_NZ, G_U, G_V, G_W
from .kernels.shade import centre_kernel
from .output import png_bytes, save_image
from .passes.tiles import untile as _untile
from .view import View


@dataclass
class Render:
    """The result of :func:`render`. Array row 0 is the top row of the picture.

    rgba (H, W, 4) uint8; intensity (H, W) float32 in [0, 1], NaN where no surface is
    seen; side (H, W) int8, +1 where the upper side is seen, -1 the lower, 0 nothing;
    depth (H, W) float32 screen z of the seen point (larger = farther), +inf where none;
    stats: "samples" (evaluations of f), "seconds", and more. ``u``, ``v``, ``w`` and
    ``normal`` give the seen point's coordinates and unit normal per pixel.

    A shaded render computes ``intensity`` and ``depth`` from its G-buffer when they
    are first asked for (the picture does not need them: it is ready sooner), then
    keeps them.
    """
    rgba: np.ndarray
    _intensity: np.ndarray = field(repr=False)
    side: np.ndarray
    _depth: np.ndarray = field(repr=False)
    stats: dict
    view: View = field(repr=False)
    #: the column pass's tiled G-buffer (kernels/layout.py), set only where a surface
    #: is seen (``gbuffer`` is the cleaned copy)
    _gbuf: np.ndarray = field(repr=False)
    #: method="horizon": t (relative to the centre) of the line at each line pixel
    line_t: np.ndarray = field(default=None, repr=False)
    #: (H, W) bool, where a surface is seen, when ``side`` does not say it (horizon)
    _seen: np.ndarray = field(default=None, repr=False)
    #: (vp, material vector, lit): how centre_kernel lights the G-buffer while
    #: intensity and depth are still None
    _light_args: tuple = field(default=None, repr=False)
    #: render's ``aspect``: the stretch (a, b, c) of u, v and w in the picture's box
    #: (the G-buffer's u, v, w are the box's; ``u``, ``v``, ``w`` divide it out)
    box: tuple = field(default=(1.0, 1.0, 1.0), repr=False)
    #: (H, W) float32 with shadows=True (section 6.2): 1 where the seen point is in
    #: shadow (its seen side faces away from the light, or the surface lies between it
    #: and the light), 0 lit, between at antialiased shadow edges, NaN where nothing is
    #: seen; None without shadows
    shadow: np.ndarray = field(default=None, repr=False)
    #: translucent layers with objects (passes/translucency.py): (front_acc (H, W, 5),
    #: opaque (H, W)) what lies over the nearest object at each pixel and the depth
    #: behind which nothing shows, for the objects pass; None otherwise
    _front: tuple = field(default=None, repr=False)

    def _centres(self):
        if self._intensity is None or self._depth is None:
            vp, mp, lit = self._light_args
            intensity = _pool.empty(self.side.shape, np.float32)
            depth = _pool.empty(self.side.shape, np.float32)
            centre_kernel(self._gbuf, vp, mp, lit, self.side, intensity, depth)
            self._intensity, self._depth = intensity, depth

    @property
    def intensity(self):
        """(H, W) float32 ambient + diffuse light of the surface at each pixel's centre,
        in [0, 1]; NaN where no surface is seen."""
        self._centres()
        return self._intensity

    @property
    def depth(self):
        """(H, W) float32 screen z of the seen point (larger = farther); +inf where no
        surface is seen."""
        self._centres()
        return self._depth

    def _mask(self):
        return self.side != 0 if self._seen is None else self._seen

    def _picture(self, channels):
        """G-buffer channels as a picture, top row first (set only where _mask())."""
        return _untile(self._gbuf[..., channels], self.side.shape[1])[::-1]

    def _channel(self, g):
        return np.where(self._mask(), self._picture(g), np.float32(np.nan))

    @property
    def gbuffer(self):
        """(W, H, G_SIZE) float32 G-buffer, rows from the bottom (floatcol.kernels.layout's
        G_* channels; u and v the box's, as the others), NaN where no surface is seen:
        a copy."""
        g = np.where(self._mask()[..., None], self._picture(slice(None)), np.float32(np.nan))
        if self.view.center[0] != 0.0 or self.view.center[1] != 0.0:
            g[..., G_U] += np.float32(self.view.center[0])   # (kept from the centre)
            g[..., G_V] += np.float32(self.view.center[1])
        if self.view.w_origin != 0.0:
            g[..., G_W] += np.float32(self.view.w_origin)    # (layout.py G_W)
        return g[::-1].transpose(1, 0, 2)

    def _from_origin(self, g, k, origin):
        """u (k 0), v (1) or w (2) in float64: the G-buffer keeps u and v from the
        view's centre and w from its w_origin in float32 (layout.py G_U, G_W), which
        keeps a millimetre's precision over a kilometre's picture however far its
        coordinates lie from 0 (a DEM in UTM metres); the origin is added back in
        double precision."""
        x = self._channel(g).astype(np.float64) + origin
        return x if self.box[k] == 1.0 else x / self.box[k]

    @property
    def u(self):
        """(H, W) float64 u of the seen point at each pixel, NaN where none."""
        return self._from_origin(G_U, 0, self.view.center[0])

    @property
    def v(self):
        """(H, W) float64 v of the seen point at each pixel, NaN where none."""
        return self._from_origin(G_V, 1, self.view.center[1])

    @property
    def w(self):
        """(H, W) float64 w of the seen point at each pixel, NaN where none."""
        return self._from_origin(G_W, 2, self.view.w_origin)

    @property
    def normal(self):
        """(H, W, 3) unit upper-side normal in screen coordinates (NaN where none)."""
        n = self._picture(slice(G_NX, G_NZ + 1))
        n = np.where(self._mask()[..., None], n, np.float32(np.nan)).astype(np.float64)
        with np.errstate(invalid="ignore", divide="ignore"):
            return n / np.linalg.norm(n, axis=2, keepdims=True)

    def window_depth(self, near, far):
        """(H, W) float32: the depth as OpenGL's depth buffer holds it with a
        perspective projection of ``near`` and ``far`` planes and glDepthRange(0, 1)
        (Szenberg 1997, eq. 7): (far - far near / e) / (far - near), e the point's
        distance from the eye along the view axis (depth + d1 + d2); 1 (the cleared
        buffer) where nothing is seen; clipped to [0, 1]. An orthographic picture's
        is linear, (e - near) / (far - near), e measured from d1 + d2 in front of the
        centre. Lets a floatcol picture go under an OpenGL scene (glDrawPixels of both
        buffers), as Szenberg composes his terrain with OpenGL's objects."""
        from .view import _number
        near = _number("near", near, positive=True)
        far = _number("far", far, positive=True)
        if not far > near:
            raise ValueError(f"far must be beyond near, got near={near}, far={far}")
        e = self.depth.astype(np.float64) + self.view.d3
        with np.errstate(invalid="ignore", divide="ignore"):
            if self.view.orthographic:
                d = (e - near) / (far - near)
            else:
                d = (far - far * near / e) / (far - near)      # eq. (7), i = e
        d = np.where(np.isfinite(self.depth), np.clip(d, 0.0, 1.0), 1.0)
        return d.astype(np.float32)

    def save(self, path):
        """Write ``rgba`` to a PNG (or .jpg, .pdf, .svg), atomically: a temporary file
        renamed at the end."""
        save_image(self.rgba, path)

    def _repr_png_(self):
        return png_bytes(self.rgba)

"""render(): validate, build the View, run the kernels, return a Render."""
from __future__ import annotations

import dataclasses
import numbers
import os
import math
import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from . import _pool, color
from .kernels.antialias import subcolumn_kernel
from .kernels.column import H_SIZE, column_kernel
from .kernels.horizon import horizon_kernel
from .kernels.silhouette import silhouette_kernel
from .kernels import layout as L
from .kernels.layout import G_DEPTH, G_NX, G_NZ, G_SIZE, G_U, G_V, G_W
from .kernels.shade import (
    INTERP_INTENSITY, INTERP_NORMAL, centre_kernel, finish_kernel)
from .output import png_bytes, save_image
from .surface import Surface, as_surface, check_range
from .view import View, _number, build_view, nowhere_finite

METHODS = ("column", "horizon")
SHADINGS = ("default", "lambert")
INTERPOLATIONS = {"normal": INTERP_NORMAL, "nis": INTERP_NORMAL,
                  "intensity": INTERP_INTENSITY, "iis": INTERP_INTENSITY}
DEFAULT_RANGE = (-10.0, 10.0)   # as sympy's plot3d
DEFAULT_LINES = 160             # horizon lines, as in the paper's figures
#: Orthographic pictures with at least this many samples evaluate f in batches of SIMD
#: code (Surface.batch): about 58 ns less per sample, for a compile of 0.1-0.2 s once
#: per expression (1024x768 of 3 sin(u cos v): 380 000 samples)
BATCH_MIN_SAMPLES = 200_000
#: the key light of the default shading: from the upper left, toward the viewer
DEFAULT_LIGHT = (-0.45, 0.55, -1.0)
DEFAULT_AMBIENT = 0.25
#: Phong highlights of the default shading (the paper has none)
DEFAULT_SPECULAR = 0.2
DEFAULT_SHININESS = 30.0
#: artifact corrections (section 5): what fixes a ridge, and what fixes a shading
#: problem (intensity jump, bump); the default is the best picture per cost measured
#: by benchmarks/bench_fidelity.py
CORRECTIONS = {"none": (L.FIX_NONE, L.FIX_NONE),
               "spline": (L.FIX_SPLINE, L.FIX_NONE),
               "supersample": (L.FIX_SUPER, L.FIX_SUPER),
               "adaptive": (L.FIX_ADAPTIVE, L.FIX_ADAPTIVE),
               "spline+supersample": (L.FIX_SPLINE, L.FIX_SUPER),
               "spline+adaptive": (L.FIX_SPLINE, L.FIX_ADAPTIVE)}
DEFAULT_CORRECTIONS = "spline+adaptive"
DETECTORS = {"ridge": L.DETECT_RIDGE, "intensity": L.DETECT_JUMP, "bump": L.DETECT_BUMP,
             "wall": L.DETECT_WALL}
DEFAULT_JUMP = 1.0 / 16.0       # the paper's threshold: 1/16 of the maximal intensity
DEFAULT_RATE = 16               # the paper's supersampling rate


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
    #: (vp, interpolation, ambient): how centre_kernel lights the G-buffer while
    #: intensity and depth are still None
    _light_args: tuple = field(default=None, repr=False)
    #: render's ``aspect``: the stretch (a, b, c) of u, v and w in the picture's box
    #: (the G-buffer's u, v, w are the box's; ``u``, ``v``, ``w`` divide it out)
    box: tuple = field(default=(1.0, 1.0, 1.0), repr=False)

    def _centres(self):
        if self._intensity is None or self._depth is None:
            vp, interp, ambient = self._light_args
            intensity = _pool.empty(self.side.shape, np.float32)
            depth = _pool.empty(self.side.shape, np.float32)
            centre_kernel(self._gbuf, vp, interp, ambient, self.side, intensity, depth)
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
        G_* channels), NaN where no surface is seen: a copy."""
        g = np.where(self._mask()[..., None], self._picture(slice(None)), np.float32(np.nan))
        return g[::-1].transpose(1, 0, 2)

    def _unboxed(self, g, k):
        x = self._channel(g)
        return x if self.box[k] == 1.0 else (x / self.box[k]).astype(np.float32)

    @property
    def u(self):
        return self._unboxed(G_U, 0)

    @property
    def v(self):
        return self._unboxed(G_V, 1)

    @property
    def w(self):
        return self._unboxed(G_W, 2)

    @property
    def normal(self):
        """(H, W, 3) unit upper-side normal in screen coordinates (NaN where none)."""
        n = self._picture(slice(G_NX, G_NZ + 1))
        n = np.where(self._mask()[..., None], n, np.float32(np.nan)).astype(np.float64)
        with np.errstate(invalid="ignore", divide="ignore"):
            return n / np.linalg.norm(n, axis=2, keepdims=True)

    def save(self, path):
        """Write ``rgba`` to a PNG (or .jpg, .pdf, .svg), atomically: a temporary file
        renamed at the end."""
        save_image(self.rgba, path)

    def _repr_png_(self):
        return png_bytes(self.rgba)


def save_png(rgba, path):
    """Write an RGBA array as a PNG, atomically (kept for callers of 0.1)."""
    save_image(rgba, path)


def render(expr, u=None, v=None, size=(400, 300), elev=30.0, azim=30.0,
           projection="orthographic", d1=None, d2=None, scale=None, method="column",
           shading="default", *, interpolation="normal", step=None, lines=DEFAULT_LINES,
           vars=None, center=None, cmap="viridis", upper_color=None,
           lower_color=color.DEFAULT_LOWER, vmin=None, vmax=None, norm=None, background=None,
           light=None, ambient=None, focal_length=None, pixel_step=1.0,
           placement="exact", specular=None, shininess=None,
           corrections=DEFAULT_CORRECTIONS, detect=None, jump_threshold=DEFAULT_JUMP,
           supersample_rate=DEFAULT_RATE, spline_tolerance=None,
           antialias=None, sampling="uniform", aspect="equal", box=None) -> Render:
    """Render w = f(u, v) with the floating column algorithm (Gordon 2001).

    Parameters
    ----------
    expr : sympy expression, str, callable f(u, v), Surface or HeightField
        Free symbols are u and v unless ``vars=(x, y)`` names others.
    u, v : (low, high)
        The domain rectangle; default (-10, 10), or a HeightField's own extent.
    size : (width, height) in pixels.
    elev, azim : degrees. elev > 0 looks down on the surface; alpha = -elev, beta = azim.
    projection : "orthographic" or "perspective" (d1: viewpoint-to-screen distance,
        d2: screen-to-origin distance, as in eqs. (9)-(10)).
    scale : pixels per unit (the paper's Ratio); None fits the surface in the image.
    method : "column" (shaded) or "horizon" (monochrome line drawing, ``lines`` lines).
    shading : "default" (ambient + diffuse key light, height colormap, two-coloured
        sides) or "lambert" (I = |L.N|/(|L||N|), light at the viewpoint, no ambient).
    interpolation : "normal" (nis, per-pixel lighting) or "intensity" (iis, Gouraud).
    cmap, vmin, vmax : the upper side's colormap (a matplotlib name or Colormap) and the
        heights at its ends (default: the range of w where the upper side is seen).
    norm : instead of vmin/vmax, a matplotlib norm (LogNorm, PowerNorm, ...; any
        monotonic w -> [0, 1] with an ``inverse``), unscaled ends scaled to the seen
        range; the colormap's rows begin at norm.inverse(k / 255).
    step : distance between sampling planes; default ``pixel_step`` (1) pixels on screen
        (at the nearest point in perspective).
    specular, shininess : Phong highlights on top of the diffuse light (default
        shading only; default 0.2 and 30; ``specular=0`` turns them off). They are
        added to ``rgba``; ``intensity`` stays the ambient + diffuse term.
    placement : perspective only: "exact" puts every sample on its column's plane
        (ERRATA 2, the default); "paper" uses Gordon's approximate eq. (9) point,
        which lies off the plane when elev != 0 (to reproduce the paper's figures).
    corrections : the artifact corrections of section 5, applied between two samples
        where a problem is detected: "none", "spline" (ridges: the extremum of a
        cubic spline, eqs. 13-22, becomes a sample), "supersample" (``supersample_rate``
        samples across the span), "adaptive" (halve the span while the problem
        persists, down to 1/``supersample_rate``), or "spline+supersample" /
        "spline+adaptive" (splines for ridges, the other for shading problems).
    detect : which problems to look for, any of "ridge" (V.N changes sign),
        "intensity" (a jump above ``jump_threshold``), "bump" (section 5.3) and
        "wall" (a discontinuity of f, end of section 5: located by halving and shaded
        as a vertical wall). Default: ridge, intensity and wall, plus bump with
        interpolation="intensity". corrections="none" turns all of them off.
    spline_tolerance : iterate the spline (end of section 5.2) until |V.N| at its
        extremum is at most this; None: one step, as in the paper.
    sampling : section 6.3. "adaptive": per column, the distance between sampling
        planes grows with the distance from the viewer in perspective (up to 16
        times), grows where the normal turns slowly (up to 4 times, while spans stay
        within 2 pixel rows) and shrinks to a quarter where it turns fast; "uniform"
        (default): planes ``step`` apart everywhere, as the paper and the line drawings.
    antialias : section 6.4. True: coverage-weighted blending along columns (the
        floating interval's float ends give each silhouette pixel its coverage, and
        where the surface reappears beyond an extremum the pixel blends both
        surfaces), and across columns the staircase of an edge steeper than a row
        per column where the side seen changes (a silhouette against the background,
        the lower side in front of the upper), from the columns' ends
        (kernels/silhouette.py); 2, 3 or 4: the coverage along columns and as many
        sub-columns per pixel, averaged (instead of the staircases' pass); False:
        off. Default: True for shading="default", False for "lambert" and the
        horizon. Only ``rgba`` is blended; ``intensity``, ``side``, ``depth`` and the
        G-buffer describe the surface at each pixel centre.
    focal_length : perspective only, instead of d1/d2: matplotlib's focal length
        (the surface's bounding sphere fills a field of view of 2 atan(1/f)).
    center : world point (u, v, w) at the image centre. None: the middle of the
        domain and of the range of f when scale is fitted, the origin (as in the
        paper and DESIGN.md's pixel convention) when scale is given; or "auto".
    aspect : the proportions of the picture's box, as matplotlib's 3-D axes.
        "equal" (default): u, v and w in true proportions, as the paper. "auto"
        (matplotlib's default, and plot_surface's): the domain's u and v ranges and
        the range of f stretched to a box of proportions 4 : 4 : 3, so a surface
        much flatter or taller than its domain is wide as much as it is high;
        "equalxy": u and v in true proportions, w stretched to 3/4 of the longer
        side; or (bu, bv, bw): a box of those proportions. ``scale`` then counts
        pixels per unit of u; ``center``, vmin/vmax and the Render's u, v, w stay in
        the surface's units; ``depth``, ``normal`` and ``view`` are the box's.
    box : (a, b, c), instead of aspect: stretch u, v and w by these factors (a
        picture's ``stats["box"]``, to draw another in the same box).

    Returns
    -------
    Render
        with ``rgba``, ``intensity``, ``side``, ``depth`` and ``stats``.

    Examples
    --------
    >>> import floatcol as fc
    >>> r = fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(160, 120))
    >>> r.rgba.shape, r.side.dtype
    ((120, 160, 4), dtype('int8'))
    """
    t_start = time.perf_counter()
    if not isinstance(method, str) or method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    if not isinstance(shading, str) or shading not in SHADINGS:
        raise ValueError(f"shading must be one of {', '.join(SHADINGS)}, got {shading!r}")
    if not isinstance(interpolation, str) or interpolation not in INTERPOLATIONS:
        raise ValueError("interpolation must be 'normal' (nis) or 'intensity' (iis), "
                         f"got {interpolation!r}")
    surface = as_surface(expr, vars)
    domain = user_domain = _domain(surface, u, v)
    surface, domain, center, box = in_box(surface, domain, center, aspect, box)
    if shading == "lambert":
        if light is not None:
            raise ValueError("shading='lambert' lights from the viewpoint; leave light=None "
                             "or use shading='default'")
        if specular:
            raise ValueError("shading='lambert' is the diffuse reference model; use "
                             "shading='default' for specular highlights")
        light_dir = None
        amb = 0.0 if ambient is None else _fraction("ambient", ambient)
        spec = 0.0
    else:
        light_dir = DEFAULT_LIGHT if light is None else light
        amb = DEFAULT_AMBIENT if ambient is None else _fraction("ambient", ambient)
        spec = DEFAULT_SPECULAR if specular is None else _fraction("specular", specular)
    shine = DEFAULT_SHININESS if shininess is None else _number("shininess", shininess, positive=True)
    view = build_view(surface, domain, size, elev, azim, projection, d1, d2, scale,
                      center, step, light_dir, focal_length, pixel_step, placement)
    hstride = 0
    n_lines = 1
    if method == "horizon":
        # n_lines planes evenly spread over t; the dense planes between them (about a
        # pixel apart) only decide what is hidden.
        n_lines = _whole("lines", lines)
        t0, t1 = view.t_range
        spacing = (t1 - t0) / max(n_lines - 1, 1)
        hstride = max(1, int(math.ceil(spacing / view.step - 1e-9)))
        view = dataclasses.replace(view, step=spacing / hstride)
    if background is None:
        background = default_background(method, shading)
    _check_norm(norm, vmin, vmax)
    fixes = _corrections(corrections, detect, interpolation, jump_threshold, supersample_rate,
                         spline_tolerance)
    aa_cov, sub_columns = _antialias(antialias, method, shading)
    t_setup = time.perf_counter()

    W, H = view.width, view.height
    vp = view.params()
    if sampling not in ("adaptive", "uniform"):
        raise ValueError(f"sampling must be 'adaptive' or 'uniform', got {sampling!r}")
    if method == "column":
        vp[L.VP_ADAPT] = 1.0 if sampling == "adaptive" else 0.0
        (vp[L.VP_FIX_RIDGE], vp[L.VP_FIX_SHADE], vp[L.VP_DETECT], vp[L.VP_JUMP], vp[L.VP_RATE],
         vp[L.VP_SPLINE_TOL]) = fixes
    n_tiles = -(-W // L.TILE)
    _check_memory(W, H, n_tiles, n_lines, sub_columns)
    try:
        gbuf = _pool.empty((n_tiles, H, L.TILE, G_SIZE), np.float32)
        hrec = np.empty((W, n_lines, H_SIZE), dtype=np.float64)
        ebuf = _pool.empty((n_tiles, L.E_SIZE, H, L.TILE), np.float32)
    except MemoryError:
        raise ValueError(_too_large(W, H, _buffer_bytes(W, H, n_tiles, n_lines, sub_columns)))\
            from None
    evals = np.zeros(W, dtype=np.int64)
    vp[L.VP_AA] = 1.0 if aa_cov else 0.0
    if surface.derivatives not in ("symbolic", "bilinear"):
        vp[L.VP_FOLD] = 0.0     # (layout.py: central differences tilt normals at jumps)
    wrange = np.empty((W, 2))
    rows = np.empty((n_tiles, 2), dtype=np.int64)
    fb = _batch_evaluator(surface, view, method, sampling)
    vp[L.VP_BATCH] = 0.0 if fb is None else 1.0
    column_kernel(*surface.kernel_args(fb), vp, gbuf, ebuf, hrec, hstride, evals, wrange,
                  rows)
    t_kernel = time.perf_counter()
    line_t = None
    w_limits = None
    seen = None

    if method == "horizon":
        lines_img = np.zeros((W, H), dtype=np.int8)
        lt = np.full((W, H), np.nan, dtype=np.float32)
        horizon_kernel(hrec, gbuf, ebuf, vp, hstride, lines_img, lt)
        line_t = np.ascontiguousarray(lt[:, ::-1].T)
        side = np.ascontiguousarray(lines_img[:, ::-1].T)
        on = side != 0
        intensity = np.where(on, np.float32(1.0), np.float32(np.nan)).astype(np.float32)
        e_seen = _untile(ebuf[:, L.E_SEEN], W)[::-1]
        seen = (e_seen != 0) & (e_seen != L.E_FLAG)      # kernels/coverage.py
        depth = np.where(on & seen, _untile(gbuf[..., G_DEPTH], W)[::-1],
                         np.inf).astype(np.float32)
        rgba = color.line_rgba(side, background=background)
    else:
        lut, lower_rgb = color.side_colors(shading, cmap, upper_color, lower_color)
        c_w = box[2]
        w_lo, w_hi = _height_limits(wrange if c_w == 1.0 else wrange / c_w, vmin, vmax)
        if norm is not None and lut.shape[0] > 1:
            lut, w_lo, w_hi = _norm_lut(norm, lut, w_lo, w_hi)
        w_limits = (w_lo, w_hi)
        if c_w != 1.0:                  # the kernels colour the box's heights
            w_lo, w_hi = w_lo * c_w, w_hi * c_w
            if lut.shape[1] > 3:
                lut = lut.copy()
                lut[:, 3] *= c_w
        bg8 = color.to_rgba8(background)
        shade_args = (INTERPOLATIONS[interpolation], amb, spec, shine)

        intensity = depth = None        # Render computes them when asked (centre_kernel)
        side = _pool.empty((H, W), np.int8)
        rgba = _pool.empty((H, W, 4), np.uint8)
        finish_kernel(gbuf, ebuf, rows, vp, *shade_args, lut, w_lo, w_hi, lower_rgb, bg8, side,
                      rgba.view(np.uint32)[..., 0])
        if aa_cov and sub_columns == 1:
            # section 6.4 across columns: the staircases of steep edges where the side
            # seen changes, from the columns' ends
            flat = side.reshape(-1)
            silhouette_kernel(ebuf, gbuf, side, flat[:flat.size // 8 * 8].view(np.uint64),
                              rgba.view(np.uint32)[..., 0])
        if sub_columns > 1:
            # section 6.4 across columns: sub-columns at even offsets inside each pixel,
            # averaged (premultiplied), one column of scratch per thread; the
            # G-buffer and the arrays other than rgba stay those of the pixel centres
            offsets = (np.arange(sub_columns) + 0.5) / sub_columns - 0.5
            acc = np.zeros((H, W, 4))
            if np.any(offsets == 0.0):           # the centre is the pass above
                a = rgba[..., 3:4] / 255.0
                acc[..., :3] += rgba[..., :3] / 255.0 * a
                acc[..., 3:4] += a
                offsets = offsets[offsets != 0.0]
            ev2 = np.zeros(W, dtype=np.int64)
            subcolumn_kernel(*surface.kernel_args(fb), vp, offsets, *shade_args, lut, w_lo,
                             w_hi, lower_rgb, bg8, acc, ev2)
            evals += ev2
            a = acc[..., 3:4]
            rgb = np.where(a > 0, acc[..., :3] / np.maximum(a, 1e-12), 0.0)
            rgba = np.empty((H, W, 4), dtype=np.uint8)
            rgba[..., :3] = np.clip(rgb * 255 + 0.5, 0, 255).astype(np.uint8)
            rgba[..., 3] = np.clip(a[..., 0] / sub_columns * 255 + 0.5, 0, 255).astype(np.uint8)
    t_end = time.perf_counter()
    if nowhere_finite(surface, domain) and not (side != 0 if seen is None else seen).any():
        warnings.warn(_empty_message(surface, user_domain), RuntimeWarning, stacklevel=2)
    stats = {
        "samples": int(evals.sum()),
        "seconds": t_end - t_start,
        "kernel_seconds": t_kernel - t_setup,
        "setup_seconds": t_setup - t_start,
        "planes": view.planes,
        "step": view.step,
        "scale": view.scale,
        "lines": n_lines if method == "horizon" else 0,
        "method": method,
        "derivatives": surface.derivatives,
        "w_limits": w_limits,      # the colormap's height range (column method)
        "box": box,                # aspect's stretch of u, v and w (1, 1, 1: none)
    }
    return Render(rgba, intensity, side, depth, stats, view, gbuf, line_t, seen,
                  (vp, INTERPOLATIONS[interpolation], amb), box)


#: No stretch: u, v and w in true proportions (aspect="equal")
NO_BOX = (1.0, 1.0, 1.0)
#: The proportions of aspect="auto"'s box: matplotlib's default box aspect
DEFAULT_BOX = (4.0, 4.0, 3.0)
ASPECTS = ("equal", "auto", "equalxy")


def box_factors(aspect, surface, domain, w_range=None):
    """(a, b, c): how much render's ``aspect`` stretches u, v and w (a = 1: u keeps
    its units). The range of f is its robust range on the fit grid (a pole does
    not flatten the box) unless ``w_range`` gives it; a flat f keeps c = 1."""
    if isinstance(aspect, str):
        if aspect not in ASPECTS:
            raise ValueError(f"aspect must be one of {', '.join(map(repr, ASPECTS))} or box "
                             f"proportions (bu, bv, bw), got {aspect!r}")
        if aspect == "equal":
            return NO_BOX
    (ua, ub), (va, vb) = domain
    du, dv = ub - ua, vb - va
    if isinstance(aspect, str) and aspect == "auto":
        bu, bv, bw = DEFAULT_BOX
    elif isinstance(aspect, str):                     # equalxy
        longest = max(du, dv)
        bu, bv, bw = du / longest, dv / longest, DEFAULT_BOX[2] / DEFAULT_BOX[0]
    else:
        try:
            bu, bv, bw = (float(x) for x in aspect)
        except (TypeError, ValueError):
            raise ValueError("aspect must be 'equal', 'auto', 'equalxy' or box proportions "
                             f"(bu, bv, bw), got {aspect!r}") from None
        if not all(math.isfinite(x) and x > 0 for x in (bu, bv, bw)):
            raise ValueError(f"aspect's box proportions must be positive numbers, got {aspect!r}")
    if w_range is None:
        from .view import _fit
        w_range = _fit(surface, domain)["range"]
    dw = float(w_range[1]) - float(w_range[0])
    b = bv / bu * du / dv
    c = bw / bu * du / dw if dw > 0 else 1.0
    if not (math.isfinite(c) and c > 0.0):       # a range too small to divide by
        c = 1.0
    return (1.0, b, c)


def _check_box(box):
    try:
        a, b, c = (float(x) for x in box)
    except (TypeError, ValueError):
        raise ValueError(f"box must be stretch factors (a, b, c), got {box!r}") from None
    if not all(math.isfinite(x) and x > 0 for x in (a, b, c)):
        raise ValueError(f"box's stretch factors must be positive numbers, got {box!r}")
    return a, b, c


def in_box(surface, domain, center, aspect, box):
    """(surface, domain, center, box) as render draws them: stretched by ``box`` (a, b,
    c) if given, else by ``aspect``'s (box_factors); unchanged for true proportions."""
    box = box_factors(aspect, surface, domain) if box is None else _check_box(box)
    if box == NO_BOX:
        return surface, domain, center, box
    return (*_boxed(surface, domain, center, box), box)


def _boxed(surface, domain, center, box):
    """(surface, domain, center) stretched by box's (a, b, c) (box_factors): what
    the kernels draw for render's ``aspect``."""
    a, b, c = box
    (ua, ub), (va, vb) = domain
    return surface.scaled(a, b, c), ((ua * a, ub * a), (va * b, vb * b)), \
        box_point(center, box)


def box_point(center, box):
    """A point (u, v, w) in the box of ``box`` (box_factors); None or a string as
    is (and anything else, for build_view to say what is wrong with it)."""
    if isinstance(center, (str, type(None))):
        return center
    try:
        return tuple(float(x) * k for x, k in zip(center, box, strict=True))
    except (TypeError, ValueError):
        return center


def _batch_evaluator(surface, view, method, sampling):
    """The surface's batch evaluator (Surface.batch, SIMD code) where the column
    kernel can use it, on the uniform planes of an orthographic view, and where the
    picture has at least BATCH_MIN_SAMPLES of them to repay its compile; else None."""
    if not view.orthographic or (method == "column" and sampling != "uniform"):
        return None
    (ua, ub), (va, vb) = view.domain
    # the lattice of columns (1 / scale apart) and planes (step apart) in the domain
    samples = min((ub - ua) * (vb - va) * view.scale / view.step,
                  float(view.width) * view.planes)
    if samples < BATCH_MIN_SAMPLES:
        return None
    return surface.batch()


def default_background(method, shading):
    """Black behind the reference model's shaded pictures, white otherwise."""
    black = method == "column" and shading == "lambert"
    return (0, 0, 0, 255) if black else (255, 255, 255, 255)


def _untile(a, width=None):
    """(n_tiles, H, TILE, ...) -> (H, W, ...): a tiled buffer (kernels/layout.py) as a
    picture, rows as in the buffer; W = n_tiles * TILE unless ``width`` says."""
    n, h, t = a.shape[:3]
    flat = a.transpose(1, 0, 2, *range(3, a.ndim)).reshape(h, n * t, *a.shape[3:])
    return flat[:, :width]


def _corrections(corrections, detect, interpolation, jump, rate, tol):
    """Check the correction options; the six VP_FIX_RIDGE .. VP_SPLINE_TOL values."""
    if not isinstance(corrections, str) or corrections not in CORRECTIONS:
        raise ValueError(f"corrections must be one of {', '.join(map(repr, CORRECTIONS))}, "
                         f"got {corrections!r}")
    fix_r, fix_s = CORRECTIONS[corrections]
    if corrections == "none":
        detect = ()                   # the plain floating column of section 4
    if detect is None:
        detect = ("ridge", "intensity", "wall") + (("bump",) if INTERPOLATIONS[interpolation]
                                                    == INTERP_INTENSITY else ())
    elif isinstance(detect, str):
        detect = (detect,)
    mask = 0
    try:
        names = list(detect)
    except TypeError:
        raise ValueError(f"detect must be a list of {', '.join(DETECTORS)}, got {detect!r}") from None
    for name in names:
        if name not in DETECTORS:
            raise ValueError(f"detect: unknown problem {name!r}; use any of "
                             f"{', '.join(DETECTORS)}")
        mask |= DETECTORS[name]
    jump = _fraction("jump_threshold", jump)
    if isinstance(rate, bool) or not isinstance(rate, (int, np.integer)) or not 2 <= rate <= 256:
        raise ValueError(f"supersample_rate must be a whole number from 2 to 256, got {rate!r}")
    tol = 0.0 if tol is None else _fraction("spline_tolerance", tol)
    return float(fix_r), float(fix_s), float(mask), jump, float(rate), tol


def _antialias(antialias, method, shading):
    """(coverage blending along columns, sub-columns per pixel)."""
    if antialias is None:
        antialias = method == "column" and shading == "default"
    if isinstance(antialias, (bool, np.bool_)):
        return bool(antialias) and method == "column", 1
    if isinstance(antialias, (int, np.integer)) and 2 <= antialias <= 4:
        if method != "column":
            raise ValueError("antialias with sub-columns applies to method='column' only")
        return True, int(antialias)
    raise ValueError(f"antialias must be True, False or 2, 3, 4 sub-columns, got {antialias!r}")


def _buffer_bytes(W, H, n_tiles, n_lines, sub_columns):
    """Bytes of the buffers a render of W x H pixels holds at once: the G-buffer and
    the edge buffer (float32), the horizon records, the picture and its sides, and
    with sub-columns their accumulator."""
    need = n_tiles * L.TILE * H * (G_SIZE + L.E_SIZE) * 4 + W * n_lines * H_SIZE * 8 + W * H * 5
    if sub_columns > 1:
        need += W * H * 4 * 8
    return need


def _too_large(W, H, need):
    return (f"size {W}x{H} needs about {need / 2**30:.1f} GiB of buffers, more than this "
            "machine has: use a smaller size")


def _check_memory(W, H, n_tiles, n_lines, sub_columns):
    """A picture whose buffers cannot fit in the machine's memory is a bad size (a
    ValueError naming it), not a MemoryError halfway through."""
    need = _buffer_bytes(W, H, n_tiles, n_lines, sub_columns)
    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):      # (not POSIX: MemoryError decides)
        return
    if need > 0.8 * total:
        raise ValueError(_too_large(W, H, need))


def _check_norm(norm, vmin, vmax):
    for name, x in (("vmin", vmin), ("vmax", vmax)):
        if x is not None and not (isinstance(x, numbers.Real) and math.isfinite(x)):
            raise ValueError(f"{name} must be a finite number, got {x!r}")
    if vmin is not None and vmax is not None and vmin > vmax:
        raise ValueError(f"vmin must not exceed vmax, got vmin={vmin!r} > vmax={vmax!r} "
                         "(as in matplotlib)")
    if norm is None:
        return
    if not (callable(norm) and callable(getattr(norm, "inverse", None))):
        raise ValueError(f"norm must be a matplotlib norm (callable, with an inverse), got {norm!r}")
    if vmin is not None or vmax is not None:
        raise ValueError("give either norm or vmin/vmax, not both (as in matplotlib)")


def _norm_lut(norm, lut, w_lo, w_hi):
    """(lut (n, 4), w_lo, w_hi) for a non-linear norm: each row's colour and the height
    where it begins, norm.inverse(k / (n - 1)) (shade._side_rgb). A norm without
    ends gets the seen range's (as a matplotlib mappable's autoscale)."""
    if getattr(norm, "vmin", 0.0) is None or getattr(norm, "vmax", 0.0) is None:
        norm.autoscale_None(np.array([w_lo, w_hi]))
    n = lut.shape[0]
    try:
        starts = np.asarray(norm.inverse(np.linspace(0.0, 1.0, n)), dtype=np.float64)
    except (ValueError, TypeError, ZeroDivisionError) as e:
        raise ValueError(f"norm {norm!r} cannot be inverted: {e}") from None
    if starts.shape != (n,) or not np.isfinite(starts).all() or (np.diff(starts) < 0).any():
        raise ValueError(f"norm {norm!r} must map heights to [0, 1] monotonically "
                         "(its inverse gave non-finite or decreasing heights)")
    return np.column_stack([lut[:, :3], starts]), float(starts[0]), float(starts[-1])


def _height_limits(wrange, vmin, vmax):
    """The colormap's height range: vmin/vmax, else that of the seen upper side
    (wrange: column_kernel's per-column range)."""
    if vmin is None or vmax is None:
        lo_s, hi_s = float(wrange[:, 0].min()), float(wrange[:, 1].max())
        if not lo_s <= hi_s:
            lo_s, hi_s = 0.0, 1.0
    w_lo = lo_s if vmin is None else float(vmin)
    w_hi = hi_s if vmax is None else float(vmax)
    return w_lo, w_hi


def _empty_message(surface, domain):
    (ua, ub), (va, vb) = domain
    a, b = surface.variables
    if surface.expr is None:
        what = "f"
    else:
        import sympy
        text = sympy.sstr(surface.expr, full_prec=False)
        what = f"f = {text if len(text) <= 60 else text[:57] + '...'}"
    return (f"{what} is NaN, infinite or complex everywhere on {a} in [{ua:g}, {ub:g}], "
            f"{b} in [{va:g}, {vb:g}]: the picture is empty (check the expression and the "
            "ranges)")


def _domain(surface: Surface, u, v):
    default = surface.default_domain
    if u is None:
        u = default[0] if default else DEFAULT_RANGE
    if v is None:
        v = default[1] if default else DEFAULT_RANGE
    return check_range(surface.variables[0], u), check_range(surface.variables[1], v)


def _fraction(name, x):
    try:
        x = float(x)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number in [0, 1], got {x!r}") from None
    if not 0.0 <= x <= 1.0 or math.isnan(x):
        raise ValueError(f"{name} must be in [0, 1], got {x}")
    return x


def _whole(name, x):
    if isinstance(x, bool) or not isinstance(x, (int, np.integer)) or x < 1:
        raise ValueError(f"{name} must be a positive whole number, got {x!r}")
    return int(x)

"""The camera: Gordon's eqs. (1)-(10), the pixel convention, fitting and step size.

Screen coordinates x, y, z (z into the screen); r, s, t by tilting y = 0 by alpha
about x (eq. 1); u, w, v by turning r, t by beta about s = w (eq. 2). Public angles
are matplotlib-like: ``alpha = -radians(elev)`` (ERRATA 3: elev > 0 looks down),
``beta = radians(azim)``. Perspective: viewpoint at (0, 0, -d3), screen plane at
distance d1 from it, d3 = d1 + d2 (ERRATA 1). Pixel column c and paper row j (0 at
the bottom) sit at ``x0 = (c - (W-1)/2) / scale``, ``y0 = (j - (H-1)/2) / scale``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .kernels import layout as L
from .light import tame_direction
from .surface import fit_grid

PROJECTIONS = {"orthographic": True, "ortho": True, "perspective": False, "persp": False}
#: View.w_origin: w is stored from the centre where it lies this many spreads of f
#: from 0 (float32 then still holds the spread in 2**24 / 256 steps)
W_ORIGIN_SPREADS = 256.0
FIT_GRID = 65          # samples per side used to fit the picture and estimate w
FIT_MARGIN = 0.05      # fraction of the half-size left free around the fitted picture
MAX_PLANES = 40000     # cap on sampling planes per column (the step grows past it)


@dataclass(frozen=True)
class View:
    width: int
    height: int
    elev: float
    azim: float
    orthographic: bool
    d1: float
    d2: float
    scale: float
    center: tuple          # world point (u, v, w) at the screen origin
    domain: tuple          # ((ua, ub), (va, vb))
    t_range: tuple         # first and last sampling plane t (relative to center)
    step: float            # distance between sampling planes
    w_range: tuple         # estimated range of w over the domain
    light: tuple = (0.0, 0.0, 0.0)   # toward a directional light; zeros = headlight
    f_range: tuple = (0.0, 0.0)       # min and max of f on the fitting grid
    placement: str = "exact"          # perspective: "exact" on Pi, or "paper" (eq. 9)
    q_near: float = 0.0               # perspective: nearest depth z + d3 (step is set there)
    #: perspective, a surface with holes: hole_map's (n, u0, v0, cells per unit u,
    #: per unit v, summed-area table); None: no map
    holes: tuple = field(default=None, compare=False, repr=False)
    #: a band of a wider picture (a tiled poster, floatcol/cluster.py): its first
    #: column there, and the kernels' offset of the columns (kernels/sample.py
    #: column_x0: first + (width - the picture's width) / 2)
    first_column: int = 0
    x_offset: float = 0.0
    #: w_origin as given (camera.fit: one for all the layers of a picture); None: its rule
    w_org: float = None

    @property
    def w_origin(self):
        """What the G-buffer stores w from (vp's VP_WORG, layout.py G_W): 0, unless the
        centre's w lies more than W_ORIGIN_SPREADS times the spread of f (on the
        fitting grid, none for a flat f) from 0, where float32 would hold w in too few
        steps to colour it (1e6 + sin u cos v: 32 steps of its spread); then the
        centre's."""
        if self.w_org is not None:
            return self.w_org
        lo, hi = self.f_range
        cw = float(self.center[2])
        far = hi > lo and abs(cw) > W_ORIGIN_SPREADS * (hi - lo)    # (False for NaNs)
        return cw if far else 0.0

    def column(self, x):
        """The column (a float) of screen x: the whole picture's, less the band's
        first column (exactly: a whole number off a float no larger)."""
        return x * self.scale + ((self.width - 1) / 2 - self.x_offset
                                 + self.first_column) - self.first_column

    @property
    def alpha(self):
        return -math.radians(self.elev)

    @property
    def beta(self):
        return math.radians(self.azim)

    @property
    def d3(self):
        return self.d1 + self.d2

    @property
    def planes(self):
        return int(math.floor((self.t_range[1] - self.t_range[0]) / self.step)) + 1

    def params(self) -> np.ndarray:
        """The flat float64 vector the kernels read (kernels/layout.py)."""
        vp = np.zeros(L.VP_SIZE)
        vp[L.VP_ORTHO] = 1.0 if self.orthographic else 0.0
        vp[L.VP_CA] = math.cos(self.alpha)
        vp[L.VP_SA] = math.sin(self.alpha)
        vp[L.VP_CB] = math.cos(self.beta)
        vp[L.VP_SB] = math.sin(self.beta)
        vp[L.VP_D1] = self.d1
        vp[L.VP_INV_D1] = 1.0 / self.d1 if self.d1 else 0.0
        vp[L.VP_D3] = self.d3
        vp[L.VP_SCALE] = self.scale
        vp[L.VP_W] = self.width
        vp[L.VP_H] = self.height
        vp[L.VP_CU], vp[L.VP_CV], vp[L.VP_CW] = self.center
        (vp[L.VP_UA], vp[L.VP_UB]), (vp[L.VP_VA], vp[L.VP_VB]) = self.domain
        vp[L.VP_WLO], vp[L.VP_WHI] = self.w_range
        vp[L.VP_T0], vp[L.VP_T1] = self.t_range
        vp[L.VP_DT] = self.step
        vp[L.VP_LX], vp[L.VP_LY], vp[L.VP_LZ] = self.light
        vp[L.VP_FLO], vp[L.VP_FHI] = self.f_range
        vp[L.VP_WORG] = self.w_origin
        vp[L.VP_PAPER] = 1.0 if self.placement == "paper" else 0.0
        vp[L.VP_QNEAR] = self.q_near
        vp[L.VP_CLIP] = 1.0
        vp[L.VP_KEEP_TOP] = 1.0
        vp[L.VP_PASS_HIDDEN] = 1.0
        vp[L.VP_FOLD] = 0.0 if self.placement == "paper" else 1.0
        vp[L.VP_XOFF] = self.x_offset
        if self.holes is not None:
            n, u0, v0, su, sv, sat = self.holes
            vp[L.VP_HOLE_N], vp[L.VP_HOLE_U0], vp[L.VP_HOLE_V0] = n, u0, v0
            vp[L.VP_HOLE_SU], vp[L.VP_HOLE_SV] = su, sv
            vp = np.concatenate([vp, sat.ravel()])
        return vp

    def to_screen(self, u, v, w):
        """Screen (x, y, z) of world points, eqs. (1)-(2) inverted."""
        ca, sa = math.cos(self.alpha), math.sin(self.alpha)
        cb, sb = math.cos(self.beta), math.sin(self.beta)
        du = np.asarray(u, dtype=float) - self.center[0]
        dv = np.asarray(v, dtype=float) - self.center[1]
        s = np.asarray(w, dtype=float) - self.center[2]
        r = du * cb - dv * sb
        t = du * sb + dv * cb
        return r, s * ca - t * sa, s * sa + t * ca

    def project(self, u, v, w):
        """Pixel coordinates (column, array row with 0 at the top) of world points;
        NaN where a point is in front of the perspective screen plane."""
        x, y, z = self.to_screen(u, v, w)
        if not self.orthographic:
            depth = z + self.d3
            ok = depth > self.d1
            m = np.where(ok, self.d1 / np.where(ok, depth, 1.0), np.nan)
            x, y = x * m, y * m
        col = self.column(x)
        row = (self.height - 1) / 2 - y * self.scale
        return col, row


def viewpoint_distances(radius, d1=None, d2=None, focal_length=None):
    """Perspective (d1, d2) for a surface within ``radius`` of the centre: given, or
    twice the radius each, or, with ``focal_length`` f (matplotlib's meaning), where a
    sphere of that radius fills a field of view of 2 atan(1/f)."""
    if focal_length is not None:
        if d1 is not None or d2 is not None:
            raise ValueError("give either focal_length or d1/d2, not both")
        f = _number("focal_length", focal_length, positive=True)
        d3 = radius * math.sqrt(1.0 + f * f)      # sphere of `radius` fills the view
        d1 = 0.9 * (d3 - radius)                  # screen plane in front of it all
        return d1, d3 - d1
    return (2.0 * radius if d1 is None else _number("d1", d1, positive=True),
            2.0 * radius if d2 is None else _number("d2", d2, positive=True))


def _number(name, value, positive=False):
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {value!r}")
    if positive and x <= 0:
        raise ValueError(f"{name} must be positive, got {value!r}")
    return x


def check_size(size):
    try:
        w, h = size
    except (TypeError, ValueError):
        raise ValueError(f"size must be (width, height) in pixels, got {size!r}") from None
    out = []
    for name, x in (("width", w), ("height", h)):
        if isinstance(x, bool) or not isinstance(x, (int, np.integer, float)) or x != int(x):
            raise ValueError(f"size {name} must be a whole number of pixels, got {x!r}")
        if int(x) <= 0:
            raise ValueError(f"size {name} must be positive, got {x!r}")
        if int(x) > 32768:
            raise ValueError(f"size {name} = {x} is too large (at most 32768 pixels)")
        out.append(int(x))
    return tuple(out)


def build_view(surface, domain, size, elev=30.0, azim=30.0, projection="orthographic",
               d1=None, d2=None, scale=None, center=None, step=None, light=None,
               focal_length=None, pixel_step=1.0, placement="exact") -> View:
    """Validate the camera options and fit what was left as None.

    ``scale=None`` fits the domain and the range of f into the image with a small
    margin, centred on the middle of both unless ``center`` says otherwise (a given
    scale keeps the paper's origin at the image centre); ``d1``/``d2`` default to twice the radius of the surface's bounding box
    each, or, given ``focal_length`` f (matplotlib's meaning), the viewpoint sits where
    the surface's bounding sphere fills a field of view of 2 atan(1/f); ``step=None`` puts the sampling planes about one pixel apart on screen
    (at the nearest point in perspective), or ``pixel_step`` pixels apart.
    """
    width, height = check_size(size)
    if placement not in ("exact", "paper"):
        raise ValueError(f"placement must be 'exact' (samples on the column plane) or 'paper' "
                         f"(Gordon's approximate eq. 9 point), got {placement!r}")
    elev = _number("elev", elev)
    if not -90.0 <= elev <= 90.0:
        raise ValueError(f"elev must be between -90 and 90 degrees, got {elev}")
    azim = _number("azim", azim)
    if not isinstance(projection, str) or projection.lower() not in PROJECTIONS:
        raise ValueError(f"projection must be 'orthographic' or 'perspective', got {projection!r}")
    ortho = PROJECTIONS[projection.lower()]
    (ua, ub), (va, vb) = domain

    # A grid over the domain: the extent of the surface for fitting.
    fit = _fit(surface, domain)
    gu, gw, ok = fit["u"], fit["w"], fit["ok"]
    w_lo, w_hi = fit["range"]
    if center is None:
        # A fitted picture is centred; a given scale keeps the paper's origin.
        center = "auto" if scale is None else (0.0, 0.0, 0.0)
    if isinstance(center, str) and center == "auto":
        center = (0.5 * (ua + ub), 0.5 * (va + vb), 0.5 * (w_lo + w_hi))
    elif isinstance(center, str):
        raise ValueError(f"center must be None, 'auto' or (u, v, w), got {center!r}")
    else:
        try:
            center = tuple(_number("center", c) for c in center)
        except TypeError:
            raise ValueError(f"center must be None, 'auto' or (u, v, w), got {center!r}") from None
        if len(center) != 3:
            raise ValueError(f"center must be None, 'auto' or (u, v, w), got {center!r}")

    pu = fit["pu"]
    pv = fit["pv"]
    pw = np.concatenate([np.clip(gw[ok], w_lo, w_hi), np.full(gu.size, center[2]),
                         fit["pw_extra"]])
    if not ok.any():
        pw[:] = center[2]
    # (hypot: no overflow where f is finite but huge, 1e300 u)
    radius = float(np.hypot(np.hypot(pu - center[0], pv - center[1]), pw - center[2]).max())
    radius = max(radius, 1e-9)
    if ortho:
        d1 = 1.0 if d1 is None else _number("d1", d1, positive=True)
        d2 = 1.0 if d2 is None else _number("d2", d2, positive=True)
    else:
        d1, d2 = viewpoint_distances(radius, d1, d2, focal_length)

    cb, sb = math.cos(math.radians(azim)), math.sin(math.radians(azim))
    corners_t = [(cu_ - center[0]) * sb + (cv_ - center[1]) * cb
                 for cu_ in (ua, ub) for cv_ in (va, vb)]
    t_range = (min(corners_t), max(corners_t))
    spread = max(w_hi - w_lo, 1e-9)
    wmin_all, wmax_all = fit["all"]
    w_range = (wmin_all - spread, wmax_all + spread)

    proto = View(width, height, elev, azim, ortho, d1, d2, 1.0, center, domain, t_range,
                 1.0, w_range, (0.0, 0.0, 0.0))
    x, y, z = proto.to_screen(pu, pv, pw)       # the fit points on screen
    if scale is None:
        if not ortho:
            depth = z + proto.d3
            keep = depth > d1
            if not keep.any():
                raise ValueError("the whole surface is in front of the screen plane: "
                                 "increase d1 + d2 (move the viewpoint back)")
            m = d1 / depth[keep]
            x, y = x[keep] * m, y[keep] * m
        half_w = 0.5 * max(width - 1, 1) * (1 - FIT_MARGIN)
        half_h = 0.5 * max(height - 1, 1) * (1 - FIT_MARGIN)
        ax = max(float(np.abs(x).max()), 1e-12)
        ay = max(float(np.abs(y).max()), 1e-12)
        scale = min(half_w / ax, half_h / ay)
    else:
        scale = _number("scale", scale, positive=True)

    nearest = 0.0 if ortho else max(float((z + proto.d3).min()), d1)
    if step is None:
        px = _number("pixel_step", pixel_step, positive=True)
        if ortho:
            step = px / scale
        else:
            step = px * nearest / (d1 * scale)
    else:
        step = _number("step", step, positive=True)
    step = max(step, (t_range[1] - t_range[0]) / MAX_PLANES)

    if light is None:
        light = (0.0, 0.0, 0.0)
    else:
        try:
            lv = np.array([_number("light", c) for c in light], dtype=float)
        except TypeError:
            raise ValueError(f"light must be a direction (x, y, z) in screen coordinates, got {light!r}") from None
        if lv.shape == (3,):
            lv = np.array(tame_direction(lv))
        if lv.shape != (3,) or not np.linalg.norm(lv) > 0:
            raise ValueError(f"light must be a non-zero direction (x, y, z), got {light!r}")
        light = tuple(lv / np.linalg.norm(lv))
    holes = None
    if not ortho and placement == "exact" and not ok.all():
        holes = hole_map(surface, domain, fit)
    return View(width, height, elev, azim, ortho, float(d1), float(d2), float(scale),
                tuple(float(c) for c in center), ((float(ua), float(ub)), (float(va), float(vb))),
                t_range, float(step), w_range, light, (wmin_all, wmax_all), placement, nearest,
                holes)


#: hole_map's cells per side, how far its box reaches beyond the domain (a fraction of
#: the domain's size on each side), and how many cells around a cell must be holes
HOLE_CELLS = 256
HOLE_MARGIN = 0.125
HOLE_DILATE = 2


def hole_map(surface, domain, fit):
    """Where f is surely a hole, for the perspective sample's fallback scan.

    A perspective sample whose Newton iteration fails (its start lies in a hole, or
    at a steep rim) scans the line of its plane in Pi for the surface: up to 24
    evaluations of f, then bisections, and a plane through a hole scans in vain. On a
    hemisphere sqrt(1 - u^2 - v^2) over a square, most planes of the corner columns
    do (1920x1080: 23.7 million evaluations, 344 ms, against 1 million for a surface
    without holes). The map, HOLE_CELLS cells a side over the domain and HOLE_MARGIN
    of its size around it (the scanned lines reach beyond it), marks a cell 0 where f
    is NaN on every point of a (HOLE_CELLS + 1)^2 grid within HOLE_DILATE cells of
    it, and the scan takes f as NaN there without evaluating it
    (kernels/sample._g_at). A finite part of f that no grid point within
    HOLE_DILATE cells sees (an island or a sliver narrower than a cell, about 1/200
    of the domain, away from the rest of the surface) can so be missed by the scan;
    Newton's iteration, which follows the surface from plane to plane, never reads
    the map. Computed once per fit grid (the Surface keeps it), only where the fit
    grid saw a hole. Returns (n, u0, v0, cells per unit u, cells per unit v, sat):
    sat (n + 1, n + 1) the summed-area table of the cells where f may be finite
    (rows along v), which tells in four reads whether a box of cells holds any
    (kernels/sample.finite_cells)."""
    if "holes" in fit:
        return fit["holes"]
    (ua, ub), (va, vb) = domain
    n = HOLE_CELLS
    mu = HOLE_MARGIN * (ub - ua)
    mv = HOLE_MARGIN * (vb - va)
    u0, u1, v0, v1 = ua - mu, ub + mu, va - mv, vb + mv
    gu, gv = np.meshgrid(np.linspace(u0, u1, n + 1), np.linspace(v0, v1, n + 1))
    with np.errstate(all="ignore"):
        finite = np.isfinite(surface.evaluate(gu, gv))
    # a cell may hold finite values if any of its corners does, or any corner of the
    # cells within HOLE_DILATE of it
    k = 2 * HOLE_DILATE + 2                       # grid points per side of the window
    pad = np.pad(finite, HOLE_DILATE)
    rows = np.zeros((n, pad.shape[1]), dtype=bool)
    for di in range(k):
        rows |= pad[di:di + n]
    win = np.zeros((n, n), dtype=bool)
    for dk in range(k):
        win |= rows[:, dk:dk + n]
    # stored as its summed-area table: sat[i, k] = cells below row i, left of column k
    sat = np.zeros((n + 1, n + 1))
    sat[1:, 1:] = win.cumsum(0).cumsum(1)
    sat.flags.writeable = False
    holes = (float(n), u0, v0, n / (u1 - u0), n / (v1 - v0), sat)
    fit["holes"] = holes
    return holes


def nowhere_finite(surface, domain):
    """Is f NaN, infinite or complex at every point of the fit grid (FIT_GRID^2
    points over the domain)? Such a surface is a hole everywhere, as far as the grid
    sees: render warns when its picture then shows nothing."""
    return not _fit(surface, domain)["ok"].any()


def _fit(surface, domain):
    """The fit grid (surface.fit_grid, which a Surface keeps) with what build_view
    derives from it alone, computed once per grid: where f is finite ("ok"), its
    robust range and its extremes, and the fit points' u and v (the surface's, then
    the whole grid's, which build_view puts at the centre's height). A height field's
    range is its data's, whole, and its highest and lowest nodes are fit points too
    (their heights "pw_extra"; HeightField.extremes)."""
    fit = fit_grid(surface, domain, FIT_GRID)
    if "ok" not in fit:
        gu, gv, gw = fit["u"], fit["v"], fit["w"]
        ok = np.isfinite(gw)
        seen = ok.any()
        xu = xv = xw = np.zeros(0)
        if seen and hasattr(surface, "extremes"):
            # a height field's heights are data: every one in the picture, a spike at
            # a node too, which the grid may miss and _robust_range would trim
            xu, xv, xw = surface.extremes(domain)
            both = np.concatenate([gw[ok], xw])
            fit["range"] = fit["all"] = (float(both.min()), float(both.max()))
        else:
            fit["range"] = _robust_range(gw) if seen else (0.0, 0.0)
            fit["all"] = (float(gw[ok].min()), float(gw[ok].max())) if seen else (0.0, 0.0)
        fit["pu"] = np.concatenate([gu[ok], gu.ravel(), xu])
        fit["pv"] = np.concatenate([gv[ok], gv.ravel(), xv])
        fit["pw_extra"] = xw
        for a in (ok, fit["pu"], fit["pv"], xw):
            a.flags.writeable = False
        fit["ok"] = ok                  # last: the mark that the rest is there
    return fit


def _robust_range(grid):
    """min and max of w over the fit grid, unless a tail runs off like a pole: then
    the bulk's range with some room, so a spike to infinity does not shrink the
    picture. A pole shows as an extreme that grows when the grid is refined (the
    full grid against every other point); a resolved peak does not."""
    w = grid[np.isfinite(grid)]
    coarse = grid[::2, ::2]
    coarse = coarse[np.isfinite(coarse)]
    lo, hi = float(w.min()), float(w.max())
    if coarse.size < 4:
        return lo, hi
    med = float(np.median(w))
    p5, p95 = (float(x) for x in np.percentile(w, [5.0, 95.0]))
    bulk = max(p95 - p5, 1e-12)
    if hi - p95 > bulk and hi - med > 1.8 * (float(coarse.max()) - med):
        hi = p95 + 0.5 * bulk
    if p5 - lo > bulk and med - lo > 1.8 * (med - float(coarse.min())):
        lo = p5 - 0.5 * bulk
    return lo, hi

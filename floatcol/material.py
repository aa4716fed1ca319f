"""Material: how a surface looks, packed in one object (PyVista's ``Property``).

A :class:`Material` holds what the shading and finishing passes read of one layer:
the shading model, the colormap of the upper side and its limits (``cmap``,
``norm``/``vmin``/``vmax`` or one ``upper_color``), the lower side's colour, the
ambient, specular and shininess terms and the interpolation (nis/iis). Every layer of
a :class:`~floatcol.scene.Scene` carries its own, so two surfaces in one picture can
have two colormaps. ``render`` and ``render_many`` build them from their flat keywords.

Adding a field: give it a default here, validate it in ``check``, and read it in the
pass that needs it; a value the kernels read gets a slot of the material vector
(kernels/layout.py ``M_*``), filled in :meth:`Material.table`, and is read there by the
kernel: no kernel signature changes (docs/architecture.md).
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from . import color
from .kernels import layout as L
from .kernels.shade import INTERP_INTENSITY, INTERP_NORMAL

SHADINGS = ("default", "lambert")
INTERPOLATIONS = {"normal": INTERP_NORMAL, "nis": INTERP_NORMAL,
                  "intensity": INTERP_INTENSITY, "iis": INTERP_INTENSITY}
DEFAULT_AMBIENT = 0.25
#: Phong highlights of the default shading (the paper has none)
DEFAULT_SPECULAR = 0.2
DEFAULT_SHININESS = 30.0


@dataclass
class Material:
    """The look of one surface.

    shading : "default" (ambient + diffuse key light, height colormap, two-coloured
        sides, Phong highlights) or "lambert" (I = |L.N|, the reference model: no
        ambient, no colormap, light at the viewpoint).
    cmap, norm, vmin, vmax : the upper side's colormap and its height limits (default:
        the range of w where the upper side is seen).
    upper_color : one colour for the upper side instead of the colormap.
    lower_color : the lower side's colour; "same": the upper side's colour at its
        height (cmap or color), both sides alike as mplot3d colours them.
    ambient, specular, shininess : the light's terms (None: the shading's defaults).
    interpolation : "normal" (nis, per-pixel lighting) or "intensity" (iis, Gouraud).
    smooth_shading : a height field lit by normals interpolated between its nodes
        (central differences) instead of its bilinear cells' own, where a pixel is
        narrower than a cell: no facets on a coarse DEM seen up close (passes/normals.py).
        The geometry is the same; a function surface is smooth already.
    opacity : in [0, 1]; below 1 every layer of the surface along a ray shows,
        composited front to back (Gordon 6.5-6.6, passes/translucency.py).
    texture : an image over the domain (Gordon 6.7, passes/colour.py): an array
        (h, w, 3|4) of uint8 or floats in [0, 1] indexed as HeightField's heights
        (``img[j, i]`` the colour at (u_i, v_j)), an image file's path, or a
        function T(u, v) -> RGB(A) of arrays. Both sides take it; its alpha lays it
        over the surface's own colour.
    texture_extent : (u0, u1, v0, v1) the texture (or colour array) spans; default
        the surface's domain.
    texture_filter : "mipmap" (trilinear, the default: no shimmer), "linear" or
        "point".
    color : colour from data: a second expression of u and v (or a 2-D array indexed
        as heights) mapped through cmap and norm/vmin/vmax instead of the height.
    contours : contour lines on the surface (passes/overlays.py): N evenly spaced
        levels, or the levels; of f, or of ``color`` when it is given.
    contour_color, contour_width : their colour and width in pixels.
    wireframe : lines at u = const and v = const: N lines each way, or (nu, nv) (as
        matplotlib's rcount, ccount), or (us, vs) the lines' positions (1-D sequences:
        an unevenly spaced mesh's own lines); ``edgecolor``, ``linewidth`` (pixels).
    wire_coords : (grid, extent): the wireframe's lines are those of two other
        coordinates than u and v, bilinear from ``grid`` (ny, nx, 2) over ``extent``
        (u0, u1, v0, v1), at the positions ``wireframe`` gives (a curvilinear mesh's
        column and row index: plot_surface(X, Y, Z, edgecolor=...) sets it).
    fill : False draws the lines alone (a hidden-line drawing: plot_wireframe): the
        surface is not drawn but still hides the lines behind it.
    """
    shading: str = "default"
    cmap: Any = "viridis"
    norm: Any = None
    vmin: float | None = None
    vmax: float | None = None
    upper_color: Any = None
    lower_color: Any = color.DEFAULT_LOWER
    ambient: float | None = None
    specular: float | None = None
    shininess: float | None = None
    interpolation: str = "normal"
    smooth_shading: bool = False
    opacity: float = 1.0
    texture: Any = None
    texture_extent: Any = None
    texture_filter: str = "mipmap"
    color: Any = None
    contours: Any = None
    contour_color: Any = "black"
    contour_width: float = 1.0
    wireframe: Any = None
    edgecolor: Any = "black"
    linewidth: float = 0.75
    fill: bool = True
    wire_coords: Any = None

    def check(self):
        """Validate the fields (ValueError naming what to fix); returns self."""
        if not isinstance(self.shading, str) or self.shading not in SHADINGS:
            raise ValueError(f"shading must be one of {', '.join(SHADINGS)}, got {self.shading!r}")
        if not isinstance(self.interpolation, str) or self.interpolation not in INTERPOLATIONS:
            raise ValueError("interpolation must be 'normal' (nis) or 'intensity' (iis), "
                             f"got {self.interpolation!r}")
        if not isinstance(self.smooth_shading, (bool, np.bool_)):
            raise ValueError(f"smooth_shading must be True or False, got {self.smooth_shading!r}")
        if isinstance(self.opacity, bool):
            raise ValueError(f"opacity must be a number in [0, 1], got {self.opacity!r}")
        self.opacity = fraction("opacity", self.opacity)
        from .passes.colour import check_filter
        check_filter(self.texture_filter)
        if not isinstance(self.fill, (bool, np.bool_)):
            raise ValueError(f"fill must be True or False, got {self.fill!r}")
        if not self.fill:
            if not self.overlaid:
                raise ValueError("fill=False draws the surface's lines alone: give "
                                 "wireframe= or contours=")
            if self.opacity < 1.0:
                raise ValueError("fill=False draws no surface to see through: give "
                                 "opacity=1")
        if self.wireframe is not None:
            from .passes.overlays import wire_lines
            wire_lines(self.wireframe)           # (a clear error now)
        if self.wire_coords is not None:
            _check_wire_coords(self.wire_coords, self.wireframe)
        for name in ("contour_width", "linewidth"):
            x = getattr(self, name)
            if isinstance(x, bool) or not isinstance(x, numbers.Real) or \
                    not math.isfinite(x) or not 0.0 < x <= 64.0:
                raise ValueError(f"{name} must be a number of pixels in (0, 64], got {x!r}")
        return self

    @property
    def colored(self):
        """Whether a texture or a colour field colours the surface."""
        return self.texture is not None or self.color is not None

    @property
    def overlaid(self):
        """Whether lines are drawn on the surface."""
        return self.contours is not None or self.wireframe is not None

    @property
    def interp(self):
        """The kernels' code of the interpolation (kernels/shade.py)."""
        return INTERPOLATIONS[self.interpolation]

    def light_terms(self):
        """(ambient, specular, shininess) as the shading passes take them."""
        from .view import _number
        if self.shading == "lambert":
            if self.specular:
                raise ValueError("shading='lambert' is the diffuse reference model; use "
                                 "shading='default' for specular highlights")
            amb = 0.0 if self.ambient is None else fraction("ambient", self.ambient)
            spec = 0.0
        else:
            amb = DEFAULT_AMBIENT if self.ambient is None else fraction("ambient", self.ambient)
            spec = DEFAULT_SPECULAR if self.specular is None else fraction("specular", self.specular)
        shine = (DEFAULT_SHININESS if self.shininess is None
                 else _number("shininess", self.shininess, positive=True))
        return amb, spec, shine

    def check_limits(self):
        """vmin/vmax finite and ordered, norm a matplotlib norm and not both."""
        norm, vmin, vmax = self.norm, self.vmin, self.vmax
        for name, x in (("vmin", vmin), ("vmax", vmax)):
            if x is not None and not (isinstance(x, numbers.Real) and math.isfinite(x)):
                raise ValueError(f"{name} must be a finite number, got {x!r}")
        if vmin is not None and vmax is not None and vmin > vmax:
            raise ValueError(f"vmin must not exceed vmax, got vmin={vmin!r} > vmax={vmax!r} "
                             "(as in matplotlib)")
        if norm is None:
            return
        if isinstance(norm, str):
            scale_norm(norm)             # (a clear error for an unknown name, now)
            return                       # (vmin/vmax with a scale's name: matplotlib's too)
        if not (callable(norm) and callable(getattr(norm, "inverse", None))):
            raise ValueError(f"norm must be a matplotlib norm (callable, with an inverse), "
                             f"got {norm!r}")
        if vmin is not None or vmax is not None:
            raise ValueError("give either norm or vmin/vmax, not both (as in matplotlib)")

    def colors(self):
        """(lut, lower_rgb): the upper side's colour table and the lower side's colour
        (color.side_colors)."""
        return color.side_colors(self.shading, self.cmap, self.upper_color, self.lower_color)

    def color_table(self, wrange, c_w=1.0):
        """(lut, w_lo, w_hi, w_limits): the upper side's colour table and the heights at
        its ends as the kernels take them (in the box's units, ``c_w`` its stretch of
        w), and the limits in the surface's units (Render.stats["w_limits"]), from the
        column pass's seen range ``wrange``."""
        lut, _ = self.colors()
        seen = wrange if c_w == 1.0 else wrange / c_w
        w_lo, w_hi = height_limits(seen, self.vmin, self.vmax)
        if self.norm is not None and lut.shape[0] > 1:
            norm = self.norm
            if isinstance(norm, str):
                # a scale's name: a norm of its own each picture, its ends vmin and vmax
                # where given, else autoscaled to the seen range as a norm object's
                norm = scale_norm(norm)
                norm.vmin, norm.vmax = self.vmin, self.vmax
            lut, w_lo, w_hi = norm_lut(norm, lut, w_lo, w_hi, seen, name=self.norm)
        if lut.shape[0] > 1 and self.upper_color is None and self.shading != "lambert":
            lut = with_extremes(lut, w_lo, w_hi, *color.extremes(self.cmap))
        w_limits = (w_lo, w_hi)
        if c_w != 1.0:                  # the kernels colour the box's heights
            w_lo, w_hi = w_lo * c_w, w_hi * c_w
            if lut.shape[1] > 3:
                lut = lut.copy()
                lut[:, 3] *= c_w
        return lut, w_lo, w_hi, w_limits

    def table(self, wrange, c_w=1.0, interp=None):
        """The kernels' colours of this material (:class:`Colours`): its material
        vector, colour table and heights for the column pass's seen range ``wrange``
        (color_table's arguments); ``interp`` overrides the interpolation (area
        sampling averages intensities)."""
        lut, w_lo, w_hi, w_limits = self.color_table(wrange, c_w)
        _, lower_rgb = self.colors()
        amb, spec, shine = self.light_terms()
        mp = np.zeros(L.M_SIZE)
        mp[L.M_ALPHA] = self.opacity
        mp[L.M_INTERP] = self.interp if interp is None else interp
        mp[L.M_AMBIENT] = amb
        mp[L.M_SPECULAR] = spec
        mp[L.M_SHININESS] = shine
        mp[L.M_WLO] = w_lo
        mp[L.M_SPAN] = w_hi - w_lo if w_hi > w_lo else 1.0
        mp[L.M_LOWER:L.M_LOWER + 3] = np.asarray(lower_rgb, dtype=np.float64)[:3]
        return Colours(mp, np.ascontiguousarray(lut, dtype=np.float64), w_lo, w_hi, w_limits,
                       np.asarray(lower_rgb, dtype=np.float64))


class Colours(NamedTuple):
    """What the kernels colour one layer with (Material.table): ``mp`` the material
    vector (kernels/layout.py M_*), ``lut`` the upper side's colour table, ``w_lo`` and
    ``w_hi`` its heights' ends in the box's units, ``w_limits`` the same in the
    surface's (Render.stats["w_limits"]), ``lower_rgb`` the lower side's colour."""
    mp: np.ndarray
    lut: np.ndarray
    w_lo: float
    w_hi: float
    w_limits: tuple
    lower_rgb: np.ndarray


def fraction(name, x):
    try:
        x = float(x)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number in [0, 1], got {x!r}") from None
    if not 0.0 <= x <= 1.0 or math.isnan(x):
        raise ValueError(f"{name} must be in [0, 1], got {x}")
    return x


def with_extremes(lut, w_lo, w_hi, under, over):
    """The colour table with a colour map's extremes (color.extremes): heights below
    w_lo take ``under``, above w_hi ``over``, as matplotlib colours values outside
    vmin/vmax; a table (n, 4) whose rows begin at the heights in its last column
    (shade._side_rgb; a linear table's rows begin k (w_hi - w_lo) / (n - 1) above
    w_lo). Unchanged where both are None (no extremes: bit for bit the same picture)."""
    if (under is None and over is None) or not w_hi > w_lo:
        return lut
    if lut.shape[1] == 3:
        starts = w_lo + np.arange(lut.shape[0]) * ((w_hi - w_lo) / (lut.shape[0] - 1))
        starts[-1] = w_hi
        lut = np.column_stack([lut, starts])
    rows = [lut]
    if under is not None:
        rows.insert(0, np.r_[np.asarray(under, dtype=np.float64)[:3], -np.inf][None])
    if over is not None:
        rows.append(np.r_[np.asarray(over, dtype=np.float64)[:3],
                          np.nextafter(w_hi, np.inf)][None])
    return np.concatenate(rows)


def _check_wire_coords(coords, wireframe):
    """Material.wire_coords: (grid (ny, nx, 2) of numbers, extent of 4 finite numbers
    with u0 < u1, v0 < v1), with a wireframe of positions."""
    try:
        grid, extent = coords
        grid = np.asarray(grid, dtype=np.float64)
        extent = tuple(float(x) for x in extent)
    except (TypeError, ValueError):
        grid, extent = np.zeros(0), ()
    if grid.ndim != 3 or grid.shape[2] != 2 or min(grid.shape[:2]) < 2 or len(extent) != 4 \
            or not all(math.isfinite(x) for x in extent) or not (
                extent[0] < extent[1] and extent[2] < extent[3]):
        raise ValueError("wire_coords must be (grid of shape (ny, nx, 2), (u0, u1, v0, v1)) "
                         "with u0 < u1 and v0 < v1")
    from .passes.overlays import wire_lines
    if wireframe is None or wire_lines(wireframe)[0][0] is None:
        raise ValueError("wire_coords needs wireframe=(positions, positions): the levels of "
                         "its two coordinates")


def scale_norm(name):
    """A matplotlib norm from a scale's name ("log", "symlog", "asinh", "logit",
    "linear"), as matplotlib's mappables take ``norm="log"`` (matplotlib 3.6's); its
    vmin and vmax unset. A ValueError names the scales where ``name`` is none."""
    import matplotlib.cm
    import matplotlib.scale
    names = [n for n in matplotlib.scale.get_scale_names() if not n.startswith("function")]
    if name not in names:
        raise ValueError(f"norm must be a matplotlib norm or a scale's name: one of "
                         f"{', '.join(repr(n) for n in names)}, got {name!r}")
    return matplotlib.cm.ScalarMappable(norm=name).norm


def norm_lut(norm, lut, w_lo, w_hi, seen=None, name=None):
    """(lut (n, 4), w_lo, w_hi) for a non-linear norm: each row's colour and the height
    where it begins, norm.inverse(k / (n - 1)) (shade._side_rgb); a BoundaryNorm's, a
    row a bin. A norm without ends gets the seen heights' (``seen``: the columns' lowest
    and highest; else [w_lo, w_hi]), as a matplotlib mappable's autoscale: a LogNorm's
    vmin the lowest positive of them (its scale masks the others). ``name``: what
    errors call the norm (default its class's name)."""
    name = repr(name) if isinstance(name, str) else type(norm).__name__
    if getattr(norm, "vmin", 0.0) is None or getattr(norm, "vmax", 0.0) is None:
        seen = np.array([w_lo, w_hi]) if seen is None else np.asarray(seen, np.float64)
        norm.autoscale_None(seen[np.isfinite(seen)] if np.isfinite(seen).any() else
                            np.array([w_lo, w_hi]))
    n = lut.shape[0]
    bounds = getattr(norm, "boundaries", None)
    if bounds is not None:
        # matplotlib's BoundaryNorm (discrete levels; it has no inverse): a row a bin,
        # beginning at its lower boundary, coloured as the norm colours its middle (the
        # norm gives an index into a colour map of norm.Ncmap colours)
        try:
            b = np.asarray(bounds, dtype=np.float64)
            k = np.ma.filled(np.ma.asarray(norm(0.5 * (b[:-1] + b[1:])), dtype=np.float64),
                             0.0)
        except (ValueError, TypeError) as e:
            raise ValueError(f"norm {name}: {e}") from None
        if b.ndim != 1 or len(b) < 2 or not np.isfinite(b).all() or (np.diff(b) <= 0).any():
            raise ValueError(f"norm {name} must have ascending, finite boundaries")
        rows = np.clip(np.round(k / max(getattr(norm, "Ncmap", n) - 1, 1) * (n - 1)), 0, n - 1)
        return (np.column_stack([lut[rows.astype(np.int64), :3], b[:-1]]), float(b[0]),
                float(b[-1]))
    try:
        starts = np.asarray(norm.inverse(np.linspace(0.0, 1.0, n)), dtype=np.float64)
    except (ValueError, TypeError, ZeroDivisionError) as e:
        raise ValueError(f"norm {name} cannot colour heights from {norm.vmin!r} to "
                         f"{norm.vmax!r} ({e}): give vmin= and vmax= inside its scale's "
                         "domain") from None
    if starts.shape != (n,) or not np.isfinite(starts).all() or (np.diff(starts) < 0).any():
        raise ValueError(f"norm {name} must map heights to [0, 1] monotonically "
                         "(its inverse gave non-finite or decreasing heights)")
    return np.column_stack([lut[:, :3], starts]), float(starts[0]), float(starts[-1])


def height_limits(wrange, vmin, vmax):
    """The colormap's height range: vmin/vmax, else that of the seen upper side
    (wrange: column_kernel's per-column range)."""
    if vmin is None or vmax is None:
        lo_s, hi_s = float(wrange[:, 0].min()), float(wrange[:, 1].max())
        if not lo_s <= hi_s:
            lo_s, hi_s = 0.0, 1.0
    w_lo = lo_s if vmin is None else float(vmin)
    w_hi = hi_s if vmax is None else float(vmax)
    return w_lo, w_hi

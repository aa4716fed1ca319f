"""plot_surface(): sympy plot3d's call form, matplotlib's option names.

``fc.plot_surface(expr, (x, -2, 2), (y, -2, 2), cmap="magma", elev=30, azim=-60)``
returns a :class:`SurfacePlot`. Angles follow matplotlib's ``view_init``: the eye is at
azimuth ``azim`` (degrees from the +x axis, counter-clockwise seen from above) and
elevation ``elev``; :func:`floatcol.render` keeps the paper's angles, and
:func:`mpl_to_paper_angles` converts.
"""
from __future__ import annotations

import inspect

import numpy as np
from matplotlib.cm import ScalarMappable as _ScalarMappable
from matplotlib.colors import Normalize as _Normalize

from . import color
from .color import colormap_lut
from .output import png_bytes, save_image
from .light import world_to_screen_direction  # noqa: F401 (kept importable here)
from .material import scale_norm
from .mesh import face_texture
from .render import DEFAULT_RANGE, Render, render
from .kernels.layout import SURF_HEIGHTFIELD
from .surface import HeightField, Surface, as_surface, check_range, free_names, heights_array
from .surface import array_like as _array_like
from .view import _number, _robust_range

#: plot_surface's own defaults where they differ from render()'s
DEFAULT_SIZE = (800, 600)
DEFAULT_ELEV = 30.0
DEFAULT_AZIM = -60.0          # matplotlib's default view
DEFAULT_PROJ = "persp"        # matplotlib's default proj_type
DEFAULT_ASPECT = "auto"       # matplotlib's 3-D box: u, v, w ranges fill 4 : 4 : 3
PROJ_TYPES = {"persp": "perspective", "perspective": "perspective",
              "ortho": "orthographic", "orthographic": "orthographic"}

#: render() options that plot_surface passes through under their own names
_RENDER_OPTIONS = set(inspect.signature(render).parameters) - {
    "expr", "u", "v", "size", "elev", "azim", "projection", "vars", "cmap", "vmin",
    "vmax", "upper_color", "light", "ambient", "focal_length", "tiles", "client"}
_OWN_OPTIONS = {"cmap", "norm", "vmin", "vmax", "color", "shade", "lightsource", "elev",
                "azim", "proj_type", "focal_length", "size", "dpi", "ambient", "light",
                "upper_color", "projection", "alpha", "axlim_clip"}


def mpl_to_paper_angles(elev, azim):
    """(elev, azim) of matplotlib's view_init -> those of :func:`floatcol.render`.

    Gordon's camera looks along (cos e sin b, cos e cos b, -sin e) in (u, v, w) with
    b the paper's azimuth; matplotlib's eye sits at (cos e cos a, cos e sin a, sin e).
    The eye is opposite the view direction, so b = -90 - a."""
    return float(elev), _wrap(-90.0 - float(azim))


def _wrap(a):
    return (a + 180.0) % 360.0 - 180.0


def parse_ranges(expr, ranges, extra=()):
    """Variables and domain from sympy's (symbol, low, high) ranges.

    Returns ((name_u, name_v), ((a, b), (c, d)) or None per missing range). Missing
    variables come from the expression's free symbols (sorted by name, as sympy does,
    ``extra`` names such as the time t left out); missing ranges default to (-10, 10).
    """
    if len(ranges) > 2:
        raise ValueError(f"give at most two ranges (symbol, low, high), got {len(ranges)}")
    names, bounds = [], []
    function = isinstance(expr, (Surface, HeightField)) or (callable(expr) and
                                                            not _is_expression(expr))
    for k, rng in enumerate(ranges):
        try:
            if function and len(rng) == 2:
                # a function's ranges need no symbol: (low, high) of its k-th argument
                sym, (lo, hi) = _argument_name(expr, k), rng
            else:
                sym, lo, hi = rng
        except (TypeError, ValueError):
            raise ValueError(f"a range must be (symbol, low, high), e.g. (x, -2, 2)"
                             f"{' (or (low, high) for a function)' if function else ''}, "
                             f"got {rng!r}") from None
        name = str(sym)
        if not name.isidentifier():
            raise ValueError(f"range variable {sym!r} must be a symbol or a name such as 'x'")
        names.append(name)
        bounds.append(check_range(name, (_real(name, lo), _real(name, hi))))
    if function:
        free = []
    else:
        free = [n for n in free_names(expr) if n not in extra]
    for n in free:
        if len(names) < 2 and n not in names:
            names.append(n)
            bounds.append(None)
    if len(names) == 2 and names[0] == names[1]:
        raise ValueError(f"the two ranges name the same variable {names[0]!r}")
    # a formula in one variable: its usual partner (u -> v, x -> y) names the other
    partner = {"u": ("v",), "v": ("u",), "x": ("y",), "y": ("x",)}.get(
        names[0] if len(names) == 1 else "", ())
    if partner and names[0] in ("v", "y") and bounds[0] is None:
        names.insert(0, partner[0])         # y alone: (x, y), not (y, x)
        bounds.insert(0, None)
    for fallback in partner + ("x", "y", "u", "v"):
        if len(names) < 2 and fallback not in names:
            names.append(fallback)
            bounds.append(None)
    unknown = [n for n in free if n not in names]
    if unknown:
        euler = "; Euler's number is E or exp(1)" if "e" in unknown else ""
        raise ValueError(f"unknown symbol{'s' if len(unknown) > 1 else ''} "
                         f"{', '.join(unknown)}: the variables are {names[0]} and {names[1]} "
                         f"(give a range (symbol, low, high) for each variable{euler})")
    return tuple(names), tuple(bounds)


def _argument_name(f, k):
    """The name of a callable's k-th argument (a Surface's k-th variable; x, y where it
    has none)."""
    if isinstance(f, Surface):
        return f.variables[k]
    try:
        params = [q.name for q in inspect.signature(f).parameters.values()
                  if q.kind in (q.POSITIONAL_ONLY, q.POSITIONAL_OR_KEYWORD)]
    except (TypeError, ValueError):
        params = []
    return params[k] if k < len(params) else ("x", "y")[k]


def _is_expression(obj):
    import sympy
    return isinstance(obj, (str, sympy.Basic))


def _real(name, x):
    try:
        return float(x)
    except (TypeError, ValueError):
        raise ValueError(f"the bounds of {name} must be real numbers, got {x!r}") from None


class SurfacePlot(_ScalarMappable):
    """A surface ready to draw; made by :func:`plot_surface`.

    ``draw(size)`` renders at a pixel size and keeps the result as ``.render``;
    ``rgba`` / ``save`` / ``show`` / ``_repr_png_`` draw at ``size`` on first use. The
    plot is a matplotlib ScalarMappable for its height colormap (``fig.colorbar(plot)``).
    In an Axes (``ax=``) it re-renders at the Axes' pixel size on every figure draw.
    """

    def __init__(self, surface, domain, *, size=DEFAULT_SIZE, elev=DEFAULT_ELEV,
                 azim=DEFAULT_AZIM, proj_type=DEFAULT_PROJ, focal_length=None, cmap=None,
                 norm=None, vmin=None, vmax=None, color=None, shade=True, lightsource=None,
                 light=None, ambient=None, dpi=100, label="", render_options=None, others=(),
                 axlim_clip=False):
        from .view import check_size

        self.surface = surface
        self.domain = domain
        #: more (surface, domain) pairs drawn into the same picture (render_many)
        self.others = list(others)
        self.label = _label(label, 1 + len(self.others))
        self.size = check_size(size)
        self.dpi = _number("dpi", dpi, positive=True)
        self.elev, self.azim = _number("elev", elev), _number("azim", azim)
        if not -90.0 <= self.elev <= 90.0:
            raise ValueError(f"elev must be between -90 and 90 degrees, got {elev}")
        if not isinstance(proj_type, str) or proj_type.lower() not in PROJ_TYPES:
            raise ValueError(f"proj_type must be 'persp' or 'ortho', got {proj_type!r}")
        self.projection = PROJ_TYPES[proj_type.lower()]
        self.focal_length = focal_length if self.projection == "perspective" else None
        if focal_length is not None:
            _number("focal_length", focal_length, positive=True)
        self.shade = bool(shade)
        if lightsource is not None and light is not None:
            raise ValueError("give either lightsource (a matplotlib LightSource) or light, not both")
        if lightsource is not None and not hasattr(lightsource, "direction"):
            from .light import _sun
            lightsource = _sun(lightsource)           # (azdeg, altdeg)
        self.lightsource = lightsource
        self.light = light
        self.ambient = ambient
        self.upper_color = None
        if color is not None and cmap is None:
            self.upper_color = _rgb(color)
        if isinstance(norm, str):
            norm = scale_norm(norm)      # norm="log": matplotlib's, vmin/vmax allowed
        elif norm is not None and not isinstance(norm, _Normalize):
            raise ValueError(f"norm must be a matplotlib.colors.Normalize or a scale's name "
                             f"('log', 'symlog', ...), got {norm!r}")
        elif norm is not None and (vmin is not None or vmax is not None):
            raise ValueError("give either norm or vmin/vmax, not both (as in matplotlib)")
        self.options = dict(render_options or {})
        if not isinstance(axlim_clip, (bool, np.bool_)):
            raise ValueError(f"axlim_clip must be True or False, got {axlim_clip!r}")
        #: in a 3-D Axes, hide what lies outside its view limits (mplot3d's axlim_clip)
        self.axlim_clip = bool(axlim_clip)
        self._clips = {}               # (limits) -> the clipped surfaces (_clipped)
        self.zoom = 1.0
        self.pixel_step = None         # None: the render default (1 pixel)
        self.shrink = 1                # a drag's preview: the picture f times smaller
        self.render: Render | None = None
        self.artist = None
        self._placed = []              # the objects put on it (scatter, plot, text, quiver)
        self._w_range = None           # the heights' range (w_range), once computed

        if isinstance(cmap, str):
            colormap_lut(cmap)                # a clear error for an unknown name, now
        super().__init__(norm=norm, cmap=cmap or "viridis")
        lo, hi = self._height_range() if vmin is None or vmax is None else (vmin, vmax)
        norm = self.norm
        if norm.vmin is None:
            norm.vmin = float(lo if vmin is None else vmin)
            if vmin is None and lo <= 0.0 and not _valid_ends(norm, hi):
                # a log scale's norm: autoscaled to the positive heights, as matplotlib's
                # mappables mask the others (those heights take the lowest colour)
                norm.vmin = self._w_positive
        if norm.vmax is None:
            norm.vmax = float(hi if vmax is None else vmax)
        self.set_array(np.array([norm.vmin, norm.vmax]))

    @property
    def axes(self):
        """The Axes the plot draws into (None when standalone): fig.colorbar(plot)
        takes its room from there."""
        return None if self.artist is None else self.artist.axes

    def changed(self):
        # a new cmap / clim / norm: the picture must be drawn again
        super().changed()
        self._entry()
        self._stale()

    # -- matplotlib's artist methods ---------------------------------------------
    # (mplot3d's plot_surface returns an artist, a Poly3DCollection: scripts remove it
    # to animate a surface, hide it, label it for a legend, set its alpha or zorder)
    @property
    def figure(self):
        """The Figure the plot draws into (None when standalone)."""
        return None if self.artist is None else self.artist.figure

    def _in_axes(self, what):
        if self.artist is None:
            raise ValueError(f"{what} needs the plot in an Axes: plot_surface(..., ax=ax)")
        return self.artist

    def remove(self):
        """Take the plot out of its Axes, as matplotlib's Artist.remove (the way to
        animate a surface: remove the last frame's, plot the next): its picture, its
        legend entry and the objects put on it (``scatter``, ``plot``, ``text``,
        ``quiver``) go; the Axes' limits stay, as matplotlib's do."""
        art = self._in_axes("remove()")
        fig = art.figure
        for obj in getattr(self, "_placed", []):
            if obj.axes is not None:
                obj.remove()
        self._placed = []
        art.remove()
        self.artist = None
        if fig is not None:
            fig.stale = True

    def get_visible(self):
        return True if self.artist is None else self.artist.get_visible()

    def set_visible(self, b):
        """Show or hide the surface in its Axes (the others there are drawn without
        it), as Artist.set_visible."""
        if not isinstance(b, (bool, np.bool_)):
            raise ValueError(f"set_visible takes True or False, got {b!r}")
        self._in_axes("set_visible()").set_visible(bool(b))

    def get_zorder(self):
        return 0 if self.artist is None else self.artist.get_zorder()

    def set_zorder(self, z):
        """The surface's place among the Axes' artists, as Artist.set_zorder (mplot3d's
        artists with a zorder below it are drawn under the surface's picture)."""
        self._in_axes("set_zorder()").set_zorder(_number("zorder", z))

    def get_label(self):
        return self.label

    def set_label(self, s):
        """The surface's name in ``ax.legend()`` (one that begins with an underscore is
        left out, as matplotlib's); for a plot of several surfaces also a list, one
        name a surface (an entry each)."""
        self.label = _label(s, 1 + len(self.others))
        self._entry()

    def labels(self):
        """The names of the plot's legend entries: its label, or one a surface."""
        return list(self.label) if isinstance(self.label, list) else [self.label]

    def get_alpha(self):
        """matplotlib's alpha: the surface's opacity (None: opaque)."""
        return self.options.get("opacity")

    def set_alpha(self, alpha):
        """The surface's opacity as matplotlib's alpha (below 1 every layer of it shows,
        docs/translucency.md; None: opaque)."""
        if alpha is None:
            self.options.pop("opacity", None)
        else:
            a = _number("alpha", alpha)
            if not 0.0 <= a <= 1.0:
                raise ValueError(f"alpha must be between 0 and 1, got {alpha!r}")
            self.options["opacity"] = a
        self.render = None
        self._entry()
        self._stale()

    def legend_colour(self, k=0):
        """The colour of surface k's legend entry, as mplot3d's (its first face's): the
        colour map at f's value at its domain's first corner (``color``: that colour),
        at its alpha."""
        surface, ((ua, _), (va, _)) = self._items()[k]
        if self.upper_color is not None:
            rgb = tuple(self.upper_color[:3])
        else:
            with np.errstate(all="ignore"):
                w = np.asarray(surface.evaluate(np.array([ua]), np.array([va])),
                               dtype=float).ravel()
            x = float(self.norm(w[0])) if w.size and np.isfinite(w[0]) else 0.5
            rgb = tuple(float(c) for c in self.cmap(x if np.isfinite(x) else 0.5)[:3])
        alpha = self.get_alpha()
        if isinstance(alpha, (list, tuple, np.ndarray)):
            alpha = alpha[k]
        return (*rgb, 1.0 if alpha is None else float(alpha))

    def _entry(self):
        entries = getattr(self.artist, "entries", None)
        if entries:
            from .mpl import update_entries
            update_entries(entries, self)

    def _height_range(self):
        """The colormap's default range: f over the whole domain, as matplotlib takes
        the range of the mesh (not of what one view happens to show); with a colour
        field (``color_field``), that field's."""
        field = self.options.get("color_field")
        if field is not None:
            from .material import Material
            from .passes.colour import field_values, prepare
            (ua, ub), (va, vb) = self.domain
            src = prepare(Material(color=field, texture_extent=self.options.get(
                "texture_extent")), self.domain, self.surface.variables)
            gu, gv = np.meshgrid(np.linspace(ua, ub, 129), np.linspace(va, vb, 129))
            c = field_values(src.field, gu, gv, np.ones(gu.shape, bool), src.extent)
            c = c[np.isfinite(c)]
            self._w_positive = float(c[c > 0].min()) if (c > 0).any() else 1.0
            if c.size == 0:
                return 0.0, 1.0
            lo, hi = float(c.min()), float(c.max())
            return (lo, hi) if hi > lo else (lo - 0.5, hi + 0.5)
        return self.w_range()

    def w_range(self):
        """The range of the surfaces' heights over their domains (a 129 x 129 grid's,
        robust to poles; a mesh's every height): the colormap's default range, and
        what a 3-D Axes' z limits take (not the colour range: vmin/vmax or a colour
        field do not move them, as in mplot3d). Computed once."""
        if self._w_range is None:
            self._w_range = self._heights()
        return self._w_range

    def _heights(self):
        los, his = [], []
        pos = [np.inf]
        for surface, ((ua, ub), (va, vb)) in [(self.surface, self.domain), *self.others]:
            gu, gv = np.meshgrid(np.linspace(ua, ub, 129), np.linspace(va, vb, 129))
            w = surface.evaluate(gu, gv)
            if np.isfinite(w).any():
                if hasattr(surface, "extremes"):   # data (a mesh): its every height
                    both = np.concatenate([w[np.isfinite(w)], surface.extremes(
                        ((ua, ub), (va, vb)))[2]])
                    lo, hi = float(both.min()), float(both.max())
                else:
                    lo, hi = _robust_range(np.where(np.isfinite(w), w, np.nan))
                w = w[np.isfinite(w) & (w > 0.0)]
                pos.append(float(w.min()) if w.size else np.inf)
                los.append(lo)
                his.append(hi)
        #: the lowest positive height (a log norm's autoscaled vmin)
        self._w_positive = min(pos) if min(pos) < np.inf else 1.0
        if not los:
            return 0.0, 1.0
        lo, hi = min(los), max(his)
        return (lo, hi) if hi > lo else (lo - 0.5, hi + 0.5)

    # -- camera -------------------------------------------------------------------
    # -- objects --------------------------------------------------------------------
    def scatter(self, xs, ys, zs, **style):
        """Markers at the points (xs, ys, zs) of the surface's space, depth-tested
        against the picture on every draw: hidden where the surface lies in front of
        them, drawn over it where they lie in front (mplot3d draws a scatter over or
        under a whole surface). ``style``: s, c or color, marker and PathCollection's
        keywords. Returns the artist (mpl.OccludedObjects; ``.visible`` after a draw)."""
        return self._objects(xs, ys, zs, "points", style)

    def plot(self, xs, ys, zs, **style):
        """A polyline through the points (xs, ys, zs), depth-tested as ``scatter`` a
        pixel at a time: the parts behind the surface are hidden. ``style``: Line2D's
        keywords (color, linewidth, linestyle, ...)."""
        return self._objects(xs, ys, zs, "line", style)

    def text(self, x, y, z, s, **style):
        """Text anchored at (x, y, z), drawn where the anchor lies in front of the
        surface, hidden where the surface hides it. ``style``: Text's keywords."""
        obj = self._objects([x], [y], [z], "text", style)
        obj.text = str(s)
        return obj

    def quiver(self, x, y, z, u, v, w, length=1.0, arrow_length_ratio=0.3, **style):
        """Arrows from (x, y, z) along (u, v, w) times ``length``, as mplot3d's quiver
        (a shaft and a two-stroke head, ``arrow_length_ratio`` of it), depth-tested a
        pixel at a time as ``plot``."""
        try:
            p = np.column_stack([np.ravel(np.asarray(a, dtype=float)) for a in (x, y, z)])
            d = np.column_stack([np.ravel(np.asarray(a, dtype=float))
                                 for a in (u, v, w)]) * _number("length", length)
        except (TypeError, ValueError):
            p = d = None
        if p is None or p.shape != d.shape:
            raise ValueError("quiver: x, y, z, u, v, w must be numbers or arrays of one "
                             "length, and length a number")
        arrow_length_ratio = _number("arrow_length_ratio", arrow_length_ratio)
        tip = p + d
        # the head: two strokes back from the tip, in the plane of the arrow and z
        side = np.cross(d, np.array([0.0, 0.0, 1.0]))
        flat = np.linalg.norm(side, axis=1) < 1e-12 * (1.0 + np.linalg.norm(d, axis=1))
        side[flat] = np.cross(d[flat], np.array([1.0, 0.0, 0.0]))
        side /= np.maximum(np.linalg.norm(side, axis=1), 1e-300)[:, None]
        back = d * arrow_length_ratio
        wing = side * (np.linalg.norm(back, axis=1) * 0.5)[:, None]
        nan = np.full_like(p, np.nan)
        pieces = np.stack([p, tip, nan, tip - back + wing, tip, tip - back - wing, nan], axis=1)
        xyz = pieces.reshape(-1, 3)
        return self._objects(xyz[:, 0], xyz[:, 1], xyz[:, 2], "line", style)

    def _objects(self, xs, ys, zs, kind, style):
        if self.artist is None:
            raise ValueError("objects on the surface need the plot in an Axes: "
                             "plot_surface(..., ax=ax)")
        from .mpl import OccludedObjects
        try:
            xyz = np.column_stack([np.ravel(np.asarray(a, dtype=float)) for a in (xs, ys, zs)])
        except (TypeError, ValueError):
            raise ValueError("xs, ys and zs must be numbers or arrays of one length") from None
        obj = OccludedObjects(self, xyz, kind, style)
        ax = self.artist.axes
        ax.add_artist(obj)
        self._placed.append(obj)
        finite = np.isfinite(xyz).all(axis=1) & (np.abs(xyz) < 1e100).all(axis=1)
        if getattr(ax, "name", "") == "3d" and finite.any():   # the limits take them in
            ax.auto_scale_xyz(xyz[finite, 0], xyz[finite, 1], xyz[finite, 2], had_data=True)
        return obj

    def view_init(self, elev=None, azim=None):
        """Set the view as matplotlib's Axes3D.view_init does (degrees)."""
        if elev is not None:
            self.elev = float(np.clip(_number("elev", elev), -90.0, 90.0))
        if azim is not None:
            self.azim = _number("azim", azim)
        ax = None if self.artist is None else self.artist.axes
        if getattr(ax, "name", "") == "3d":      # a 3-D Axes owns the camera
            ax.view_init(elev=self.elev, azim=self.azim)
        self._stale()

    def _stale(self):
        if self.artist is not None:
            self.artist.stale = True

    def render_kwargs(self, size):
        """The render() call this plot makes at a pixel size."""
        elev, azim = mpl_to_paper_angles(self.elev, self.azim)
        kw = dict(self.options)
        if "color_field" in kw:                   # render's colour from data
            kw["color"] = kw.pop("color_field")
        kw.update(size=tuple(size), elev=elev, azim=azim, projection=self.projection,
                  u=self.domain[0], v=self.domain[1])
        if self.focal_length is not None:
            kw["focal_length"] = self.focal_length
        if kw.get("method", "column") == "column":
            kw["cmap"] = self.cmap
            if type(self.norm) is _Normalize:
                kw.update(vmin=self.norm.vmin, vmax=self.norm.vmax)
            else:
                kw["norm"] = self.norm            # LogNorm, PowerNorm, ...
            if self.upper_color is not None:
                kw["upper_color"] = self.upper_color
        shading = kw.get("shading", "default")
        if shading != "lambert":
            if not self.shade:
                kw["ambient"] = 1.0           # shade=False: flat colours, as matplotlib
                kw["specular"] = 0.0
            elif self.ambient is not None:
                kw["ambient"] = self.ambient
            if self.lightsource is not None:
                # fixed to the surface: it turns with the camera (light.py)
                from .light import Light
                kw["light"] = Light.directional(tuple(float(x) for x in
                                                      self.lightsource.direction))
            elif self.light is not None:
                kw["light"] = self.light
        if self.pixel_step is not None and kw.get("step") is None:
            # a drag preview: coarser planes, no corrections or antialiasing (the
            # picture is drawn again at full quality on release)
            kw["pixel_step"] = self.pixel_step
            if kw.get("method", "column") == "column":
                kw["corrections"] = "none"
                kw["antialias"] = False
        if self.shrink != 1 and kw.get("scale") is not None:
            kw["scale"] = kw["scale"] / self.shrink    # the same view, f times smaller
        if self.zoom != 1.0 and kw.get("scale") is None:
            if self.others:
                from .camera import joint_box, joint_camera
                box = kw.get("box")
                if box is None:
                    box = joint_box(self._items(), kw.get("aspect", "equal"))
                fit = joint_camera(self._items(), kw["size"], kw["elev"], kw["azim"],
                                    kw["projection"], kw.get("d1"), kw.get("d2"), None,
                                    kw.get("center"), kw.get("focal_length"), box)
                kw.update(d1=fit["d1"], d2=fit["d2"])     # the camera is fixed now
                kw.pop("focal_length", None)
                kw["scale"], kw["center"] = fit["scale"] * self.zoom, fit["center"]
                kw["box"] = box
            else:
                fit, box = render_view(self.surface, kw)
                kw["scale"] = fit.scale * self.zoom
                kw["center"] = tuple(x / k for x, k in zip(fit.center, box))
                kw["box"] = box
        return kw

    def _items(self):
        return [(self.surface, self.domain), *self.others]

    # -- drawing ------------------------------------------------------------------
    def scene(self, size=None):
        """(Scene, composite): what this plot draws at a pixel size (default: the
        plot's), and whether its layers are composited (several surfaces)."""
        from .scene import scene_from_options
        kw = self.render_kwargs(size or self.size)
        u, v = kw.pop("u"), kw.pop("v")
        if self.others:
            return scene_from_options([(s, *d) for s, d in self._items()], **kw), True
        return scene_from_options([(self.surface, u, v)], **kw), False

    def _clipped(self, limits):
        """The plot's (surface, domain) pairs with what lies outside the 3-D Axes' view
        limits ((x0, x1), (y0, y1), (z0, z1)) made a hole, as mplot3d's axlim_clip
        hides the patches with a vertex outside them: a mesh's (HeightField's) points
        outside are holes, so the cells around them are (mplot3d's patches); an
        expression's surface is cut exactly where it leaves the limits (a Piecewise
        that is NaN outside). Kept for the last few limits (a drag draws the same)."""
        key = tuple(tuple(float(x) for x in lim) for lim in limits)
        if key in self._clips:
            return self._clips[key]
        (x0, x1), (y0, y1), (z0, z1) = (sorted(lim) for lim in key)
        out = []
        for surface, domain in self._items():
            if surface.kind == SURF_HEIGHTFIELD:
                (ua, ub), (va, vb) = surface.default_domain
                nv, nu = surface.hf.shape
                x = np.linspace(ua, ub, nu)[None, :]
                y = np.linspace(va, vb, nv)[:, None]
                z = surface.hf
                with np.errstate(invalid="ignore"):
                    outside = (z < z0) | (z > z1) | (x < x0) | (x > x1) | (y < y0) | (y > y1)
                out.append((HeightField(np.where(outside, np.nan, z), u=(ua, ub), v=(va, vb)),
                            domain))
            elif surface.expr is not None:
                import sympy
                e = surface.expr
                named = {str(x): x for x in e.free_symbols}
                u, v = (named.get(str(n), sympy.Symbol(str(n))) for n in surface.variables)
                inside = sympy.And(e >= z0, e <= z1, u >= x0, u <= x1, v >= y0, v <= y1)
                clipped = sympy.Piecewise((e, inside), (sympy.nan, True))
                out.append((as_surface(clipped, vars=surface.variables, time=surface.time),
                            domain))
            else:
                raise ValueError("axlim_clip=True clips a mesh (X, Y, Z) or an expression, "
                                 "not a Python function: give the surface as one of those")
        if len(self._clips) >= 4:
            self._clips.pop(next(iter(self._clips)))
        self._clips[key] = out
        return out

    def draw_with(self, size, camera, limits=None) -> Render:
        """Render at ``size`` with the camera keywords ``camera`` (a 3-D Axes', mpl.py
        axes_camera: angles, projection, box, centre, scale) over a transparent
        background, and keep it as ``.render``; with ``limits`` (the Axes' view limits
        ((x0, x1), (y0, y1), (z0, z1)): axlim_clip) what lies outside them hidden."""
        from .renderer import render_scene
        scene, many = self.scene_with(size, camera, limits)
        r = render_scene(scene, composite=many)
        self.render = r
        return r

    def translucent(self):
        """Whether the plot's surface is translucent (alpha below 1)."""
        a = self.options.get("opacity")
        if isinstance(a, (list, tuple, np.ndarray)):
            return any(float(x) < 1.0 for x in a)
        return a is not None and float(a) < 1.0

    def scene_with(self, size, camera, limits=None):
        """(Scene, composite) that draw_with renders."""
        from .scene import scene_from_options
        kw = self.render_kwargs(size)
        for k in ("aspect", "focal_length", "d1", "d2", "scale", "center", "box"):
            kw.pop(k, None)
        kw.update(camera)
        kw["background"] = (0, 0, 0, 0)
        u, v = kw.pop("u"), kw.pop("v")
        items = self._items() if limits is None else self._clipped(limits)
        if self.others:
            return scene_from_options([(s, *d) for s, d in items], **kw), True
        return scene_from_options([(items[0][0], u, v)], **kw), False

    def __getstate__(self):
        # (pickled without its last render, which the next draw makes again: a 3-D
        # figure of 400 x 300 pixels pickled in 6 MB, now 0.15 MB)
        return {**super().__getstate__(), "render": None, "_clips": {}}

    def draw(self, size=None) -> Render:
        """Render at ``size`` (default: the plot's) and keep it as ``.render``."""
        from .renderer import render_scene
        scene, many = self.scene(size)
        r = render_scene(scene, composite=many)
        self.render = r
        return r

    def _current(self):
        if self.render is None or self.render.rgba.shape[1::-1] != self.size:
            self.draw(self.size)
        return self.render

    @property
    def rgba(self):
        """(H, W, 4) uint8 picture of the most recent draw (drawn at ``size`` if none)."""
        return self._current().rgba

    def save(self, path, dpi=None):
        """Write the picture at ``size``: .png, .jpg, .tif, .webp, .pdf, .svg, .eps or .ps
        (atomically)."""
        from .output import check_output
        check_output(path)
        dpi = self.dpi if dpi is None else _number("dpi", dpi, positive=True)
        return save_image(self._current().rgba, path, dpi=dpi)

    def show(self):
        """Show the picture in a matplotlib window (or inline in Jupyter)."""
        import matplotlib.pyplot as plt
        if self.artist is not None:
            plt.show()
            return
        w, h = self.size
        fig = plt.figure(figsize=(w / self.dpi, h / self.dpi), dpi=self.dpi)
        ax = fig.add_axes((0, 0, 1, 1))
        attach(self, ax)
        plt.show()

    def _repr_png_(self):
        return png_bytes(self._current().rgba)

    def __repr__(self):
        return (f"SurfacePlot({self.label or self.surface!r}, size={self.size}, "
                f"elev={self.elev:g}, azim={self.azim:g}, proj_type={self.projection!r})")


def draw_together(plots, size, camera, limits):
    """One picture of several plots in one 3-D Axes (mpl.py Surface3DImage), where one
    of them is translucent: their layers in one scene, each with its own material
    (colours, colour map, alpha), so that every layer of each shows through the
    translucent ones (section 6.6's merge by depth; a composite of their separate
    pictures would let the nearest surface hide the rest). The scene's light,
    quality and objects are the first plot's. ``limits``: each plot's axlim_clip
    limits, or None. Each plot keeps the picture as its ``.render``."""
    from .renderer import render_scene
    from .scene import Scene
    scenes = [p.scene_with(size, camera, lim)[0] for p, lim in zip(plots, limits)]
    first = scenes[0]
    joint = Scene([layer for s in scenes for layer in s.layers], camera=first.camera,
                  light=first.light, quality=first.quality, background=first.background,
                  vars=first.vars, objects=first.objects)
    r = render_scene(joint, composite=True)
    for p in plots:
        p.render = r
    return r


def render_view(surface, kw):
    """(View, box): the View render() would fit for these keyword arguments (the one
    camera fit, camera.fit), and its box stretch (the View's coordinates are the
    box's)."""
    from .camera import Camera, fit
    from .quality import Quality
    from .renderer import layer_domain
    cam = Camera(size=kw["size"], elev=kw["elev"], azim=kw["azim"],
                 projection=kw.get("projection", "orthographic"), d1=kw.get("d1"),
                 d2=kw.get("d2"), center=kw.get("center"), focal_length=kw.get("focal_length"),
                 aspect=kw.get("aspect", "equal"), box=kw.get("box"))
    views, _, box = fit([(surface, layer_domain(surface, kw.get("u"), kw.get("v")))], cam,
                        Quality())
    return views[0], box


def _labels(Z):
    """(x, y): the coordinates of a labelled 2-D array's columns and rows: a pandas
    DataFrame's columns and index, an xarray DataArray's coordinates of its second and
    first dimensions (as its plot.surface takes them), where they are numbers, one a
    column and one a row; None otherwise (a plain array: its indices)."""
    try:
        if hasattr(Z, "columns") and hasattr(Z, "index"):
            x, y = np.asarray(Z.columns), np.asarray(Z.index)
        elif hasattr(Z, "dims") and hasattr(Z, "coords") and len(Z.dims) == 2:
            ydim, xdim = Z.dims
            if xdim not in Z.coords or ydim not in Z.coords:
                return None
            x, y = np.asarray(Z.coords[xdim]), np.asarray(Z.coords[ydim])
        else:
            return None
    except (TypeError, ValueError, KeyError, AttributeError):
        return None
    rows, cols = np.shape(Z)
    if x.shape != (cols,) or y.shape != (rows,) or x.dtype.kind not in "iuf" or \
            y.dtype.kind not in "iuf":
        return None
    return x.astype(float), y.astype(float)


def _valid_ends(norm, hi):
    """Whether ``norm``, its vmin set, takes its ends (a LogNorm's vmin must be > 0);
    its vmax set to ``hi`` for the test, then unset."""
    vmax = norm.vmax
    norm.vmax = float(hi) if vmax is None else vmax
    try:
        norm(np.array([norm.vmin, norm.vmax]))
        return True
    except ValueError:
        return False
    finally:
        norm.vmax = vmax


def _label(label, n):
    """A plot's label: a string, or a list of one a surface (of n)."""
    if isinstance(label, (list, tuple)):
        if len(label) != n:
            raise ValueError(f"label: give one string, or a list of one a surface ({n}), got "
                             f"{len(label)}")
        return [str(x) for x in label]
    return "" if label is None else str(label)


def _rgb(c):
    return color.to_rgb(c, "color")


def plot_surface(expr, *ranges, ax=None, interactive=False, label="", **options) -> SurfacePlot:
    """Draw w = f(x, y) with the floating column algorithm, in sympy's call form.

    Parameters
    ----------
    expr : sympy expression, string, callable, Surface or HeightField; or a list of
        them (several surfaces in one picture, hiding each other: render_many), an
        item ``(expr, (x, a, b), (y, c, d))`` with ranges of its own. Or a 2-D array
        of heights alone (MATLAB's ``surf(Z)``): the mesh over its columns' and rows'
        indices, as ``plot_surface(arange(columns), arange(rows), Z)``; a pandas
        DataFrame's columns and index, an xarray DataArray's coordinates.
    *ranges : (symbol, low, high), up to two, as sympy's ``plot3d`` ((low, high) for
        a Python function: of its first and second argument); a missing range is
        (-10, 10) (a HeightField's own extent for a HeightField).
    ax : a matplotlib Axes to draw into (re-rendered at its pixel size on every draw).
    interactive : with ``ax``: drag to rotate, scroll to zoom.
    cmap, norm, vmin, vmax, color, shade, lightsource : as matplotlib's plot_surface.
    facecolors : as matplotlib's: an array of colours, one per point of the mesh (or
        of a grid over the ranges; or one per face), each face of the mesh taking its
        first corner's colour (with rstride/cstride or rcount/ccount, mplot3d's larger
        faces; without, every cell is a face), drawn as a texture over the surface.
    edgecolor, linewidth, rcount, ccount, rstride, cstride : as matplotlib's: with an
        edge colour, the mesh's lines drawn on the exact surface (a wireframe of
        linewidth points; render's ``wireframe``).
    color_field : colour from data: a second expression of the variables (or an
        array over the grid) coloured through cmap, norm/vmin/vmax; the colorbar shows
        its range (render's ``color``).
    texture, contours, wireframe : as :func:`floatcol.render`.
    alpha : as matplotlib's: below 1 the surface is translucent, every layer of it
        showing (``opacity`` of :func:`floatcol.render`); with several surfaces, one
        value or a list of one per surface.
    elev, azim : matplotlib's view_init angles (default 30, -60).
    proj_type : "persp" (default, as matplotlib) or "ortho"; ``focal_length`` as
        matplotlib's.
    size : (width, height) pixels when not in an Axes (default 800x600); ``dpi`` for
        PDF/SVG output.
    aspect : "auto" (default, as matplotlib's 3-D axes: the ranges of x, y and the
        surface's height fill a box of proportions 4 : 4 : 3), "equal" (true
        proportions, as :func:`floatcol.render`), "equalxy", or box proportions
        (bx, by, bz); see :func:`floatcol.render`.
    **options : any other :func:`floatcol.render` option: method, shading,
        interpolation, step, pixel_step, lines, upper_color, lower_color, background,
        ambient, light, scale, center, d1, d2.

    Returns
    -------
    SurfacePlot
    """
    facecolors = options.pop("facecolors", None)
    faces = face_tex = None
    if facecolors is not None:
        facecolors = _face_colours(facecolors)
    mesh_shape = None
    resampled = False
    mesh_lines = None
    if not ranges and heights_array(expr) is not None:
        # plot_surface(Z) (MATLAB's surf(Z)): the mesh of Z over its columns' and rows'
        # indices, x along a row, as plot_surface(arange(columns), arange(rows), Z); a
        # labelled array's own coordinates (a DataFrame's, a DataArray's)
        rows, cols = np.shape(expr)
        x, y = _labels(expr) or (np.arange(cols, dtype=float), np.arange(rows, dtype=float))
        expr, ranges = x, (y, expr)
    if _is_mesh(expr, ranges):                # matplotlib's plot_surface(X, Y, Z, ...)
        mesh_shape = np.shape(ranges[1])
        edges = _edge_colour(options) is not None
        if facecolors is None:
            expr = mesh_surface(expr, *ranges, lines=edges)
        else:
            faces = _faces(facecolors, np.shape(ranges[1]), options)
            expr, face_tex = mesh_surface(expr, *ranges, faces=faces, lines=edges)
        ranges = ()
        resampled = expr.resampled
        mesh_lines = getattr(expr, "mesh_lines", None)
    if facecolors is not None:                # the colours of the faces: a texture
        if "texture" in options or "color_field" in options:
            raise ValueError("give one of facecolors, texture and color_field")
        if faces is None:                     # (over the grid of the ranges: below)
            faces = _faces(facecolors, facecolors.shape[:2], options)
    _mesh_lines(options, mesh_shape, resampled, mesh_lines)   # edgecolor: mplot3d's lines
    zorder = options.pop("zorder", None)
    unknown = sorted(set(options) - _RENDER_OPTIONS - _OWN_OPTIONS - {"color_field"})
    if unknown:
        known = ", ".join(sorted(_RENDER_OPTIONS | _OWN_OPTIONS))
        raise ValueError(f"unknown option{'s' if len(unknown) > 1 else ''} "
                         f"{', '.join(unknown)}; plot_surface knows: {known}")
    if "projection" in options:
        if "proj_type" in options:
            raise ValueError("give either proj_type or projection, not both")
        options["proj_type"] = options.pop("projection")
    if "alpha" in options:                   # matplotlib's word for opacity
        if "opacity" in options:
            raise ValueError("give either alpha or opacity, not both")
        options["opacity"] = options.pop("alpha")
    if "upper_color" in options and "color" not in options:
        options["color"] = options.pop("upper_color")
    options.setdefault("aspect", DEFAULT_ASPECT)
    if isinstance(expr, list):
        # several surfaces in one picture: each an expression (the shared ranges) or
        # (expr, (x, a, b), (y, c, d)) with its own
        if not expr:
            raise ValueError("expr is an empty list: give at least one expression")
        items = [_surface_domain(e[0], e[1:]) if _has_ranges(e) else _surface_domain(e, ranges)
                 for e in expr]
    else:
        items = [_surface_domain(expr, ranges)]
    (surface, domain), others = items[0], items[1:]
    if faces is not None:
        if face_tex is None:                  # the faces between the points of a grid
            (ua, ub), (va, vb) = domain       # over the ranges
            face_tex = face_texture(np.linspace(ua, ub, faces.shape[1] + 1),
                                    np.linspace(va, vb, faces.shape[0] + 1), faces)
        options["texture"], extent = face_tex
        if extent is not None:
            options["texture_extent"] = extent
    own = {k: options.pop(k) for k in list(options) if k in _OWN_OPTIONS}
    if ax is not None:
        own.setdefault("size", _axes_pixels(ax))
    plot = SurfacePlot(surface, domain, label=label, render_options=options, others=others,
                       **own)
    if ax is not None:
        art = attach(plot, ax, interactive=interactive)
        if zorder is not None:
            art.set_zorder(zorder)
        if getattr(ax, "name", "") == "3d":
            # a 3-D Axes owns the camera: the angles and projection asked for go to it
            if "elev" in own or "azim" in own:
                ax.view_init(elev=plot.elev, azim=plot.azim)
            if "proj_type" in own or "focal_length" in own:
                ax.set_proj_type("persp" if plot.projection == "perspective" else "ortho",
                                 **({"focal_length": plot.focal_length}
                                    if plot.projection == "perspective" and
                                    plot.focal_length is not None else {}))
    elif interactive:
        raise ValueError("interactive=True needs a matplotlib Axes: pass ax=")
    return plot


def plot_wireframe(expr, *ranges, ax=None, interactive=False, label="",
                   **options) -> SurfacePlot:
    """matplotlib's ``plot_wireframe`` (and its call form): the mesh's lines, the
    lines behind the surface hidden (mplot3d draws them all). ``fc.plot_wireframe(X, Y,
    Z, ax=ax, rstride=10, cstride=10)`` or ``fc.plot_wireframe(expr, (x, a, b), (y, c,
    d))``: rcount, ccount (default 50), rstride, cstride as matplotlib's; ``color``
    (default "C0") and ``linewidth`` (points, default 1.5) the lines'; any
    :func:`plot_surface` option else (``contours=`` adds contour lines). The surface
    itself is not drawn (``fill=False``): it hides the lines behind it and shows the
    Axes' panes and whatever is behind it where no line runs."""
    for name in ("fill", "edgecolor", "edgecolors", "ec"):
        if name in options:
            raise ValueError(f"plot_wireframe draws the lines alone in ``color``: it takes "
                             f"no {name}")
    colour = options.pop("color", options.pop("colors", "C0"))
    if isinstance(colour, (list, tuple)) and len(colour) and not isinstance(
            colour[0], (int, float, np.number)):
        colour = colour[0]                        # (a Line3DCollection's list: the first)
    options.setdefault("linewidth", 1.5)
    return plot_surface(expr, *ranges, ax=ax, interactive=interactive, label=label,
                        edgecolor=colour, fill=False, **options)


def plot_trisurf(*args, ax=None, interactive=False, label="", **options) -> SurfacePlot:
    """matplotlib's ``Axes3D.plot_trisurf`` call form: the surface through scattered
    points, ``fc.plot_trisurf(x, y, z, ax=ax, cmap="viridis")``, linear on the triangles
    of their Delaunay triangulation, or on ``triangles`` (``plot_trisurf(x, y,
    triangles, z)`` or ``triangles=``), less those ``mask`` hides, or on a matplotlib
    ``Triangulation`` (``plot_trisurf(tri, z)``); holes outside them. It is resampled
    onto an evenly spaced grid (mesh.py's ``triangulated``: 16 sqrt(n) nodes a side for
    n points, at most 2049) and drawn as a height field, coloured by height a pixel at
    a time (mplot3d colours each triangle by its mean height). ``edgecolor`` and
    ``linewidth`` draw the triangles' edges in a 3-D Axes (mplot3d's own lines, hidden
    where the surface lies in front of them); any :func:`plot_surface` option else."""
    from matplotlib.tri import Triangulation

    from .mesh import triangulated
    edges = {k: options.pop(k) for k in list(options)
             if k in ("edgecolor", "edgecolors", "ec", "linewidth", "linewidths", "lw")}
    for k in ("antialiased", "antialiaseds", "aa"):
        options.pop(k, None)                  # (floatcol antialiases by its own rules)
    tri_kw = {k: options.pop(k) for k in ("triangles", "mask") if k in options}
    if args and isinstance(args[0], Triangulation):
        pts = (args[0].x, args[0].y)
    elif len(args) >= 2:
        pts = args[:2]
    else:
        raise ValueError("plot_trisurf(x, y, z): give the points' x, y and z (or a "
                         "matplotlib Triangulation and z)")
    try:
        x, y = (np.asarray(a, dtype=float) for a in pts)
    except (TypeError, ValueError):
        raise ValueError("plot_trisurf(x, y, z): x and y must be arrays of numbers") from None
    if x.ndim != 1 or x.shape != y.shape:
        raise ValueError(f"plot_trisurf(x, y, z): x and y must be 1-D of one length, got "
                         f"shapes {x.shape} and {y.shape}")
    if not (np.isfinite(x).all() and np.isfinite(y).all()):
        raise ValueError("plot_trisurf(x, y, z): x and y must be finite (a missing "
                         "height is a NaN z)")
    if len(x) < 3 or np.linalg.matrix_rank(np.column_stack([x - x.mean(), y - y.mean()]),
                                           tol=1e-12 * max(np.ptp(x), np.ptp(y), 1e-300)) < 2:
        raise ValueError("plot_trisurf(x, y, z): the points span no area (fewer than 3, or "
                         "all on one line)")
    try:
        tri, rest, extra = Triangulation.get_from_args_and_kwargs(*args, **tri_kw)
        mask = tri.mask
        triangles = tri.get_masked_triangles()
    except (ValueError, TypeError, IndexError, RuntimeError) as exc:
        raise ValueError(f"plot_trisurf: {exc}") from None
    if len(rest) != 1 or extra:
        raise ValueError("plot_trisurf(x, y, z): give x, y (or a Triangulation, or x, y, "
                         "triangles) and then z, one height a point")
    try:
        z = np.ma.filled(np.ma.asarray(rest[0], dtype=float), np.nan)
    except (TypeError, ValueError):
        raise ValueError("plot_trisurf(x, y, z): z must be an array of numbers") from None
    if z.shape != x.shape:
        raise ValueError(f"plot_trisurf(x, y, z): z must have one height a point, shape "
                         f"{x.shape}, got {z.shape}")
    if mask is not None and len(triangles) == 0:
        raise ValueError("plot_trisurf: the mask hides every triangle")
    xe, ye, Z = triangulated(tri.x, tri.y, z, triangles)
    hf = HeightField(Z, u=(xe[0], xe[-1]), v=(ye[0], ye[-1]))
    hf.resampled = True
    plot = plot_surface(hf, ax=ax, interactive=interactive, label=label, **options)
    _triangle_edges(plot, ax, tri.x, tri.y, z, triangles, edges)
    return plot


def _triangle_edges(plot, ax, x, y, z, triangles, edges):
    """plot_trisurf's edgecolor: the triangles' edges as mplot3d's own lines in a 3-D
    Axes (depth-tested against the surface, mpl.py's DepthTested); elsewhere a
    RuntimeWarning says they are not drawn."""
    ec = next((edges[k] for k in ("edgecolor", "edgecolors", "ec") if k in edges), None)
    if ec is None or (isinstance(ec, str) and ec in ("none", "face")):
        return
    lw = next((edges[k] for k in ("linewidth", "linewidths", "lw") if k in edges), 1.0)
    if getattr(ax, "name", "") != "3d":
        import warnings
        warnings.warn("plot_trisurf: the triangles' edges (edgecolor) are drawn in a "
                      "matplotlib 3-D Axes only (ax=fig.add_subplot(projection='3d'))",
                      RuntimeWarning, stacklevel=3)
        return
    from mpl_toolkits.mplot3d.art3d import Line3DCollection
    pairs = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    pairs = np.unique(np.sort(pairs, axis=1), axis=0)
    seg = np.stack([np.column_stack([x[pairs[:, k]], y[pairs[:, k]], z[pairs[:, k]]])
                    for k in (0, 1)], axis=1)
    lines = Line3DCollection(seg, colors=ec, linewidths=lw)
    ax.add_collection3d(lines)
    plot._placed.append(lines)            # (removed with the plot)


#: Axes3D.plot_surface's keywords about its polygon mesh: the lines of its edges, drawn
#: as a wireframe on the exact surface where an edge colour is given (_mesh_lines);
#: antialiasing by floatcol's own rules (docs/options.md)
_MPL_MESH_OPTIONS = {"rstride", "cstride", "rcount", "ccount", "linewidth", "linewidths",
                     "lw", "edgecolor", "edgecolors", "ec", "antialiased", "antialiaseds",
                     "aa"}
#: matplotlib's default rcount and ccount
MPL_MESH_COUNT = 50


def _face_colours(facecolors):
    """matplotlib's facecolors as an (n, m, 3|4) image (a texture)."""
    arr = np.asarray(facecolors)
    if arr.ndim == 3 and arr.shape[2] in (3, 4) and arr.dtype.kind in "fiu":
        return arr
    if arr.ndim == 2:                            # colour names or specs
        from matplotlib.colors import to_rgba_array
        try:
            return to_rgba_array(arr.ravel()).reshape(arr.shape + (4,))
        except (ValueError, TypeError) as exc:
            raise ValueError(f"facecolors must be colours, one per point: {exc}") from None
    raise ValueError(f"facecolors must be an array of colours of shape (rows, columns, 3|4), "
                     f"got shape {arr.shape}")


def _faces(colours, shape, options):
    """matplotlib's facecolors (one colour per point of a mesh of ``shape``, or per
    face) as the colour of each face (rows - 1, columns - 1, channels): a face takes
    the colour of its first corner, as mplot3d's. With rstride/cstride (or rcount/
    ccount) the faces are mplot3d's, of that many cells, each the colour of its first
    corner; without them every cell is a face (floatcol draws the whole mesh: mplot3d
    thins it to 50 x 50 faces)."""
    if len(shape) != 2:
        raise ValueError(f"plot_surface(X, Y, Z): Z must be 2-D, got shape {tuple(shape)}")
    rows, cols = shape
    if colours.shape[:2] not in ((rows, cols), (rows - 1, cols - 1)):
        raise ValueError(f"facecolors must have a colour for each point of the mesh, shape "
                         f"{(rows, cols)} (or for each face, {(rows - 1, cols - 1)}), got "
                         f"{colours.shape[:2]}")
    given = any(k in options for k in ("rstride", "cstride", "rcount", "ccount"))
    rs = _mpl_stride(rows, options, "rstride", "rcount") if given else 1
    cs = _mpl_stride(cols, options, "cstride", "ccount") if given else 1
    return colours[(np.arange(rows - 1) // rs) * rs][:, (np.arange(cols - 1) // cs) * cs]


def _edge_colour(options):
    """matplotlib's edge colour among plot_surface's keywords (None: no edges)."""
    ec = next((options[k] for k in ("edgecolor", "edgecolors", "ec") if k in options), None)
    return None if ec is None or (isinstance(ec, str) and ec in ("none", "face")) else ec


def _mpl_stride(n, options, key_stride, key_count):
    """mplot3d's stride along n rows (or columns) of a mesh: the stride given (10 where
    only the other one is: strides before counts), or n / count rounded up (count 50
    by default)."""
    try:
        if "rstride" in options or "cstride" in options:
            return max(int(options.get(key_stride, 10)), 1)
        return max(int(np.ceil(n / max(int(options.get(key_count, MPL_MESH_COUNT)), 1))), 1)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{key_stride} and {key_count} must be whole numbers") from None


def _mpl_line_rows(n, options, key_stride, key_count):
    """The rows (or columns) of a mesh of n whose lines mplot3d's plot_surface draws:
    0, s, 2 s, ... and the last (_mpl_stride's s)."""
    s = _mpl_stride(n, options, key_stride, key_count)
    return np.array(list(range(0, n - 1, s)) + [n - 1])


def _mesh_lines(options, shape, resampled=False, mesh_lines=None):
    """matplotlib's mesh keywords: with an edge colour, the mesh's lines (rcount x
    ccount of them, or every rstride-th / cstride-th row and column of a mesh of
    ``shape``) as a wireframe of linewidth points; without one they draw nothing.
    A ``resampled`` mesh's (mesh.py: not an evenly spaced grid) are its own lines,
    ``mesh_lines`` (MeshLines), at mplot3d's rows and columns: at their positions, or
    the levels of a curvilinear mesh's index."""
    mesh = {k: options.pop(k) for k in list(options) if k in _MPL_MESH_OPTIONS}
    ec = _edge_colour(mesh)
    if ec is None:
        return
    lw = next((mesh[k] for k in ("linewidth", "linewidths", "lw") if k in mesh), 1.0)
    if np.ndim(lw) > 0:
        lw = np.ravel(lw)[0]
    if not (isinstance(lw, (int, float, np.number)) and not isinstance(lw, bool)) or lw <= 0:
        return
    if resampled:
        if mesh_lines is None or shape is None:     # (mesh_surface gives them)
            return
        options.update(mesh_lines.wireframe(_mpl_line_rows(shape[0], mesh, "rstride", "rcount"),
                                            _mpl_line_rows(shape[1], mesh, "cstride", "ccount")))
    else:
        rows, cols = shape if shape is not None else (MPL_MESH_COUNT, MPL_MESH_COUNT)

        def count(n, key_count, key_stride):
            if key_stride in mesh and shape is not None:
                return int(np.ceil((n - 1) / max(int(mesh[key_stride]), 1))) + 1
            return min(int(mesh.get(key_count, MPL_MESH_COUNT)), n)
        nv = max(count(rows, "rcount", "rstride"), 2)      # lines at v = const
        nu = max(count(cols, "ccount", "cstride"), 2)      # lines at u = const
        options["wireframe"] = (nu, nv)
    options["edgecolor"] = ec if not isinstance(ec, np.ndarray) else tuple(ec)
    options["linewidth"] = min(float(lw) * 100.0 / 72.0, 64.0)     # points -> pixels


def _is_mesh(expr, ranges):
    """matplotlib's (X, Y, Z): three arrays (numpy's, or anything numpy reads as one:
    pandas, xarray), Z 2-D or an array (mesh_surface says what is wrong with one that
    is not)."""
    return (len(ranges) == 2 and all(_array_like(a) or
                                     (isinstance(a, (list, tuple)) and _numeric(a))
                                     for a in (expr, *ranges))
            and (np.ndim(ranges[1]) == 2 or _array_like(ranges[1])))




def _numeric(a):
    try:
        return np.asarray(a, dtype=float).ndim >= 1
    except (TypeError, ValueError):
        return False


def _close(a, b):
    """np.allclose without the warnings of values near the doubles' edge."""
    with np.errstate(over="ignore", invalid="ignore"):
        return np.allclose(a, b)


def _constant(a):
    """Whether every value of ``a`` is its first (np.ptp == 0, without its overflow)."""
    return bool(np.all(a == a[:1]))


class MeshLines:
    """A resampled mesh's own lines (mesh_surface's ``lines``): for an unevenly spaced
    one, the coordinate of each of Z's rows and columns (``rows``, ``cols``) and the
    axis its rows run across ("v", or "u" for meshgrid's ij indexing); for a
    curvilinear one, ``coords`` (grid (ny, nx, 2) of the column and row index, extent)."""

    def __init__(self, rows=None, cols=None, row_axis="v", coords=None):
        self.rows, self.cols, self.row_axis, self.coords = rows, cols, row_axis, coords

    def wireframe(self, rows, cols):
        """render()'s wireframe (and wire_coords) for the lines of Z's rows ``rows`` and
        columns ``cols`` (indices)."""
        if self.coords is not None:
            return dict(wireframe=(cols.astype(float), rows.astype(float)),
                        wire_coords=self.coords)
        at_rows, at_cols = self.rows[rows], self.cols[cols]
        return dict(wireframe=(at_cols, at_rows) if self.row_axis == "v" else (at_rows, at_cols))


def mesh_surface(X, Y, Z, faces=None, lines=False):
    """The HeightField of matplotlib's plot_surface(X, Y, Z): X and Y a meshgrid (either
    indexing) or 1-D x (along Z's columns) and y (along its rows), ascending or
    descending (a north-up raster); unevenly spaced, or a curvilinear grid of Z's
    shape, resampled onto an evenly spaced one (mesh.py: ``resampled`` says so). With
    ``faces`` (a colour for each face: Z's shape less one, and a third axis; _faces),
    (HeightField, (texture, texture_extent)): the faces' colours as a texture (extent
    None: the HeightField's domain). ``lines``: a resampled mesh's HeightField holds
    its own lines, ``mesh_lines`` (MeshLines: plot_surface's edgecolor)."""
    try:
        # (a masked array's masked values are holes, as mplot3d leaves them out)
        X, Y, Z = (np.ma.filled(np.ma.asarray(a, dtype=float), np.nan) for a in (X, Y, Z))
    except (TypeError, ValueError):
        raise ValueError("plot_surface(X, Y, Z): X, Y and Z must be arrays of numbers") from None
    if Z.ndim != 2:
        raise ValueError(f"plot_surface(X, Y, Z): Z must be 2-D, got shape {Z.shape}")
    if faces is not None and np.shape(faces)[:2] != (Z.shape[0] - 1, Z.shape[1] - 1):
        raise ValueError(f"plot_surface(X, Y, Z): facecolors must have a colour a face, "
                         f"shape {(Z.shape[0] - 1, Z.shape[1] - 1)}, got {np.shape(faces)}")
    transposed = False
    if X.ndim == 2 and X.shape == Z.shape and Y.shape == Z.shape and \
            _constant(X[0]) and _constant(Y[:, 0]) and Z.shape != (1, 1):
        X, Y, Z = X.T, Y.T, Z.T                    # meshgrid(..., indexing="ij")
        transposed = True
        if faces is not None:
            faces = np.swapaxes(faces, 0, 1)
    if min(Z.shape) < 2:
        raise ValueError(f"plot_surface(X, Y, Z): Z must have at least 2 x 2 values (a "
                         f"surface between them), got shape {Z.shape}")
    if X.ndim == 2 and X.shape == Z.shape and Y.shape == Z.shape and \
            not (_close(X, X[:1]) and _close(Y, Y[:, :1])):
        # a curvilinear grid (X = R cos P, Y = R sin P): resampled (mesh.py)
        from .mesh import curvilinear
        x, y, Z, colours, *ij = curvilinear(X, Y, Z, faces=faces, coords=lines)
        mesh_lines = MeshLines(coords=(ij[0], (x[0], x[-1], y[0], y[-1]))) if lines else None
        return _mesh_field(x, y, Z, None if colours is None else (colours, None),
                           resampled=True, lines=mesh_lines)
    if X.ndim == 2:
        if X.shape != Z.shape or not _close(X, X[:1]):
            raise ValueError("plot_surface(X, Y, Z): X must repeat one row of x values "
                             "(a meshgrid), or X and Y be a curvilinear grid of Z's shape")
        X = X[0]
    if Y.ndim == 2:
        if Y.shape != Z.shape or not _close(Y, Y[:, :1]):
            raise ValueError("plot_surface(X, Y, Z): Y must repeat one column of y values "
                             "(a meshgrid), or X and Y be a curvilinear grid of Z's shape")
        Y = Y[:, 0]
    if X.shape != (Z.shape[1],) or Y.shape != (Z.shape[0],):
        hint = (" (Z.T has a row for each y and a column for each x, as matplotlib's Z)"
                if X.shape == (Z.shape[0],) and Y.shape == (Z.shape[1],) else "")
        raise ValueError(f"plot_surface(X, Y, Z): x has {X.size} and y {Y.size} values for Z "
                         f"of shape {Z.shape}{hint}")
    even = True
    for name, a in (("X", X), ("Y", Y)):
        with np.errstate(over="ignore", invalid="ignore"):
            d = np.diff(a)
        if not np.all(np.isfinite(a)) or not (np.all(d > 0) or np.all(d < 0)):
            raise ValueError(f"plot_surface(X, Y, Z): {name} must be finite and ascending "
                             "or descending")
        with np.errstate(over="ignore"):
            if not np.isfinite(a[-1] - a[0]):
                raise ValueError(f"plot_surface(X, Y, Z): {name} spans more than the "
                                 "largest double")
        even = even and np.allclose(d, d[0], rtol=1e-6, atol=0)
    # (each of Z's rows' and columns' coordinate, in its order: the mesh's lines)
    mesh_lines = MeshLines(rows=X.copy() if transposed else Y.copy(),
                           cols=Y.copy() if transposed else X.copy(),
                           row_axis="u" if transposed else "v") if lines else None
    if X[1] < X[0]:
        X, Z = X[::-1], Z[:, ::-1]
        faces = None if faces is None else faces[:, ::-1]
    if Y[1] < Y[0]:
        Y, Z = Y[::-1], Z[::-1]
        faces = None if faces is None else faces[::-1]
    # (the faces between the mesh's x and y)
    texture = None if faces is None else face_texture(X, Y, faces)
    if not even:                              # (np.geomspace's): resampled (mesh.py)
        from .mesh import uneven
        X, Y, Z = uneven(X, Y, Z)
    return _mesh_field(X, Y, Z, texture, resampled=not even,
                       lines=None if even else mesh_lines)


def _mesh_field(x, y, Z, texture, resampled, lines=None):
    """The HeightField of heights Z over x, y; with ``texture`` (image, extent or None),
    (HeightField, texture). ``lines``: a resampled mesh's own (MeshLines)."""
    hf = HeightField(Z, u=(x[0], x[-1]), v=(y[0], y[-1]))
    hf.resampled = resampled                  # (mesh.py: not the mesh's own grid)
    hf.mesh_lines = lines
    return hf if texture is None else (hf, (np.ascontiguousarray(texture[0]), texture[1]))


def _has_ranges(e):
    return isinstance(e, tuple) and len(e) in (2, 3) and all(
        isinstance(r, (tuple, list)) and len(r) == 3 for r in e[1:])


def _surface_domain(expr, ranges):
    """(Surface, domain) of one expression and its sympy-style ranges."""
    names, bounds = parse_ranges(expr, ranges)
    if isinstance(expr, Surface):
        surface = expr
    else:
        surface = as_surface(expr, names if not callable(expr) or _is_expression(expr) else None)
    default = surface.default_domain
    domain = tuple(
        b if b is not None else (default[i] if default else DEFAULT_RANGE)
        for i, b in enumerate(bounds))
    return surface, tuple(check_range(surface.variables[i], d) for i, d in enumerate(domain))


def _axes_pixels(ax):
    bb = ax.bbox
    return max(1, int(round(bb.width))), max(1, int(round(bb.height)))


def attach(plot, ax, interactive=False):
    from .mpl import Surface3DImage, SurfaceImage
    if getattr(ax, "name", "") == "3d":       # mplot3d's own Axes: its camera, its mouse
        return Surface3DImage.attach(plot, ax)
    return SurfaceImage.attach(plot, ax, interactive=interactive)

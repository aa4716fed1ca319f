"""A sympy plotting backend: ``plot3d(expr, (x, a, b), (y, c, d), backend=SympyBackend)``.

sympy hands the backend its data series; the surface series z = f(x, y) are drawn by
:func:`floatcol.plot_surface` into one matplotlib Axes, several of them into one
picture where they hide each other (``plot3d(f, g, ...)``). floatcol options (elev, azim,
cmap, proj_type, method, ...) can be given to ``plot3d`` directly, as can sympy's
``title`` and ``size`` (inches, as for sympy's matplotlib backend). As sympy's
matplotlib backend, it draws into a figure and Axes given (``fig=``, ``ax=``; sympy's
``PlotGrid`` of several plots gives each its cell), and ``.fig``, ``.ax`` are
matplotlib's.
"""
from __future__ import annotations

from sympy.plotting.plot import Plot

from .plot import _OWN_OPTIONS, _RENDER_OPTIONS, plot_surface

#: options plot3d passes on that floatcol takes
_FLOATCOL_OPTIONS = (_OWN_OPTIONS | _RENDER_OPTIONS) - {"size"}


class SympyBackend(Plot):
    """sympy ``Plot`` subclass drawing surfaces with floatcol (show, save, close)."""

    def __init__(self, *series, **kwargs):
        self._fc_options = {k: kwargs.pop(k) for k in list(kwargs) if k in _FLOATCOL_OPTIONS}
        self._zlim = kwargs.get("zlim")          # (sympy's Plot keeps no zlim of its own)
        # a function given as surface_color (sympy's older form): sympy 1.14's series
        # drop it for their default color_func, so it is read here (_surface_colour)
        self._colour_function = kwargs.get("surface_color") if callable(
            kwargs.get("surface_color")) else None
        # a figure and Axes to draw into, as sympy's MatplotlibBackend (PlotGrid sets
        # them before it calls process_series)
        self._plotgrid_fig = kwargs.pop("fig", None)
        self._plotgrid_ax = kwargs.pop("ax", None)
        super().__init__(*series, **kwargs)
        if any(getattr(s, "is_parametric", False) for s in self._series):
            raise ValueError("floatcol's sympy backend draws surfaces z = f(x, y) (plot3d); "
                             "use sympy's default backend for parametric plots")
        self._fig = self._ax = None
        self._want_window = False      # show() builds the figure through pyplot
        self.plots = []

    @property
    def fig(self):
        """The matplotlib Figure (built on first use)."""
        if self._fig is None:
            self._build()
        return self._fig

    @property
    def ax(self):
        """The matplotlib Axes the surfaces are drawn in (built on first use)."""
        if self._fig is None:
            self._build()
        return self._ax

    def process_series(self):
        """Draw the series (again) into the figure: sympy's PlotGrid calls this once it
        has given the plot its cell's figure and Axes."""
        self._fig = None
        self._build()

    def _build(self):
        from matplotlib.figure import Figure
        surfaces = [s for s in self._series if getattr(s, "is_3Dsurface", False)]
        others = [s for s in self._series if s not in surfaces]
        if others or any(getattr(s, "is_parametric", False) for s in surfaces):
            raise ValueError("floatcol's sympy backend draws surfaces z = f(x, y) "
                             "(plot3d); use sympy's default backend for other plots")
        if not surfaces:
            raise ValueError("nothing to draw: plot3d needs an expression")
        figsize = self.size if self.size else (8.0, 6.0)
        if self._plotgrid_ax is not None:         # (given: PlotGrid's cell, or ax=)
            ax = self._plotgrid_ax
            fig = self._plotgrid_fig if self._plotgrid_fig is not None else ax.figure
        else:
            if self._want_window:
                import matplotlib.pyplot as plt
                fig = plt.figure(figsize=figsize)
            else:
                fig = Figure(figsize=figsize)
            # matplotlib's own 3-D Axes, as sympy's default backend: panes, ticks,
            # labels, limits and title stay (mpl.py Surface3DImage)
            ax = fig.add_subplot(projection="3d")
        # several surfaces: one picture where they hide each other (render_many)
        items = [(s.expr, (s.var_x, s.start_x, s.end_x), (s.var_y, s.start_y, s.end_y))
                 for s in surfaces]
        colours = [_surface_colour(s, self._fc_options, self._colour_function)
                   for s in surfaces]
        if any(colours):
            # sympy's surface_color (or color_func): each surface its own plot_surface
            # in the Axes, with its colours (they still hide one another a pixel at a
            # time, mpl.py)
            self.plots = [plot_surface(*item, ax=ax, label=str(s.expr),
                                       **{**self._fc_options, **c})
                          for item, s, c in zip(items, surfaces, colours)]
        else:
            self.plots = [plot_surface(items, ax=ax, label=[str(s.expr) for s in surfaces],
                                       **self._fc_options)]
        first = surfaces[0]
        labels = [getattr(self, k, None) for k in ("xlabel", "ylabel", "zlabel")]
        ax.set_xlabel(str(labels[0]) if labels[0] else str(first.var_x))
        ax.set_ylabel(str(labels[1]) if labels[1] else str(first.var_y))
        ax.set_zlabel(str(labels[2]) if labels[2] else f"f({first.var_x}, {first.var_y})")
        for lim, setter in ((getattr(self, "xlim", None), ax.set_xlim),
                            (getattr(self, "ylim", None), ax.set_ylim),
                            (self._zlim, ax.set_zlim)):
            if lim:
                setter(*(float(x) for x in lim))
        if self.title:
            ax.set_title(str(self.title))
        if getattr(self, "legend", False):
            ax.legend()                  # (an entry a surface: its expression, mpl.py)
        self._fig, self._ax = fig, ax

    def show(self):
        import matplotlib.pyplot as plt
        self._want_window = True
        if self._fig is None or not plt.fignum_exists(getattr(self._fig, "number", -1)):
            self._fig = None
            self._build()
        plt.show()

    def save(self, path):
        """Write the figure (any format matplotlib writes), atomically."""
        from .output import atomic_file, check_output
        path, ext = check_output(path)
        with atomic_file(path) as tmp:
            self.fig.savefig(tmp, format=ext[1:].replace("jpg", "jpeg"))

    def close(self):
        if self._fig is not None:
            import matplotlib.pyplot as plt
            plt.close(self._fig)
        self._fig = None


#: a colour function's values are read on a grid of this many points a side (a colour
#: field over the surface's domain, bilinear between them)
COLOUR_GRID = 256


def _surface_colour(series, options, given=None):
    """plot_surface keywords for a sympy surface series' colours, as sympy's matplotlib
    backend draws them: ``color_func`` (or ``surface_color``, ``given``: the function
    plot3d was given as surface_color) a function of x, of (x, y) or of (x, y, z), or
    a sympy expression: a colour field through the colour map (a function's values on
    a COLOUR_GRID grid; an expression compiled as the surface is); a number: one
    value, the colour map's first colour (matplotlib maps a constant there); a colour:
    that colour. {} where none is given (the default colour by height)."""
    from sympy import Expr

    func = getattr(series, "color_func", None)
    value = getattr(series, "surface_color", None)
    if isinstance(func, Expr):
        return {"color_field": func}
    if callable(func) and getattr(func, "__module__", "") != "sympy.plotting.series":
        return {"color_field": _colour_grid(series, func)}
    if given is not None:
        return {"color_field": _colour_grid(series, given)}
    if value is None:
        return {}
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        import matplotlib
        cmap = options.get("cmap", "viridis")
        cmap = matplotlib.colormaps[cmap] if isinstance(cmap, str) else cmap
        return {"color": tuple(float(c) for c in cmap(0.0))}
    from matplotlib.colors import to_rgba
    try:
        return {"color": to_rgba(value)}
    except (TypeError, ValueError):
        raise ValueError(f"surface_color must be a colour, a number or a function of x, y "
                         f"(and z), got {value!r}") from None


def _colour_grid(series, func):
    """The values of a colour function on a COLOUR_GRID x COLOUR_GRID grid over the
    series' domain (rows along y): called with arrays, as sympy's backend calls it, or
    a point at a time where it takes no arrays."""
    import inspect

    import numpy as np

    from .surface import as_surface
    n = COLOUR_GRID
    x = np.linspace(float(series.start_x), float(series.end_x), n)
    y = np.linspace(float(series.start_y), float(series.end_y), n)
    X, Y = np.meshgrid(x, y)
    try:
        nargs = len(inspect.signature(func).parameters)
    except (TypeError, ValueError):
        nargs = 3
    args = [X, Y]
    if nargs >= 3:
        surface = as_surface(series.expr, [series.var_x, series.var_y])
        args.append(surface.evaluate(X, Y))
    args = args[:max(1, min(nargs, 3))]
    try:
        with np.errstate(all="ignore"):
            vals = _real(func(*args))
        if vals.shape != X.shape:
            vals = np.broadcast_to(vals, X.shape).astype(float)
    except Exception:                             # (a function of numbers, not arrays)
        try:
            with np.errstate(all="ignore"):
                vals = np.vectorize(lambda *a: float(_real(func(*a))), otypes=[float])(*args)
        except Exception as exc:
            raise ValueError(f"color_func (surface_color): the colour function failed: "
                             f"{exc}") from None
    vals = np.array(vals, dtype=float)
    vals[~np.isfinite(vals)] = np.nan
    return vals


def _real(values):
    """A colour function's values as real numbers: a complex value is NaN (no colour)
    unless its imaginary part is 0, as sympy's backend reads them."""
    import numpy as np
    a = np.asarray(values)
    if np.iscomplexobj(a):
        return np.where(np.isclose(a.imag, 0.0), a.real, np.nan)
    return np.asarray(a, dtype=float)

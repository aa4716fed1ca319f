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

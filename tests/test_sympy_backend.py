"""sympy's plot3d with backend=floatcol.SympyBackend."""
import matplotlib
import numpy as np
import pytest
import sympy as sp
from PIL import Image

matplotlib.use("Agg")
from sympy.plotting import plot, plot3d  # noqa: E402

import floatcol as fc  # noqa: E402

x, y = sp.symbols("x y")


def _figure_matches_render(im, surface_plot):
    """The share of the render's fully covered pixels that the saved figure shows
    unchanged (to 1 level) where the 3-D Axes' artist put them (mpl.py: pixel (col,
    row) at the canvas point (ox + col, oy - row))."""
    r = surface_plot.render
    T = surface_plot.artist.placed
    ox, oy = T[0, 2], T[1, 2]
    rows, cols = np.nonzero((r.side != 0) & (r.rgba[..., 3] == 255))
    ix = np.round(ox + cols - 0.5).astype(int)
    iy = im.shape[0] - 1 - np.round(oy - rows - 0.5).astype(int)
    ok = (ix >= 0) & (ix < im.shape[1]) & (iy >= 0) & (iy < im.shape[0])
    diff = np.abs(im[iy[ok], ix[ok], :3].astype(int) - r.rgba[rows[ok], cols[ok], :3]).max(axis=1)
    return (diff <= 1).mean(), ok.sum()


def test_plot3d_saves_a_png_drawn_by_floatcol(tmp_path):
    p = plot3d(sp.sin(x) * sp.cos(y), (x, -3, 3), (y, -2, 2), backend=fc.SympyBackend,
               show=False, size=(4, 3), elev=40, azim=-50, cmap="magma")
    assert isinstance(p, fc.SympyBackend)
    p.save(tmp_path / "s.png")
    im = np.asarray(Image.open(tmp_path / "s.png"))
    assert im.shape[:2] == (300, 400)
    (surface_plot,) = p.plots
    assert surface_plot.domain == ((-3.0, 3.0), (-2.0, 2.0))
    assert (surface_plot.elev, surface_plot.azim) == (40.0, -50.0)
    assert surface_plot.cmap.name == "magma"
    # the saved figure is floatcol's render, pixel for pixel where the surface is,
    # inside matplotlib's 3-D Axes (ticks and labels drawn around it)
    share, n = _figure_matches_render(im, surface_plot)
    assert n > 5000 and share > 0.99
    ax = p.fig.axes[0]
    assert ax.name == "3d" and ax.get_xlabel() == "x" and ax.get_zlabel() == "f(x, y)"
    p.close()


def test_title_and_default_range(tmp_path):
    p = plot3d(x * y, backend=fc.SympyBackend, show=False, title="xy", size=(3, 3))
    p.save(tmp_path / "t.png")
    assert p.plots[0].domain == ((-10.0, 10.0), (-10.0, 10.0))
    assert p.fig.axes[0].get_title() == "xy"


def test_labels_and_limits(tmp_path):
    p = plot3d(sp.sin(x) * sp.cos(y), (x, -3, 3), (y, -2, 2), backend=fc.SympyBackend,
               show=False, xlabel="east", ylabel="north", zlabel="height", zlim=(-2, 2),
               size=(4, 3))
    p.save(tmp_path / "l.png")
    ax = p.fig.axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()) == ("east", "north", "height")
    assert ax.get_zlim() == (-2.0, 2.0)
    p.close()


def test_parametric_surfaces_refused_when_made():
    from sympy.plotting import plot3d_parametric_surface
    with pytest.raises(ValueError, match="z = f"):
        plot3d_parametric_surface(sp.cos(x), sp.sin(x), y, (x, 0, 1), (y, 0, 1),
                                  backend=fc.SympyBackend, show=False)


def test_non_surface_plots_are_refused_clearly(tmp_path):
    p = plot(sp.sin(x), backend=fc.SympyBackend, show=False)
    with pytest.raises(ValueError, match="surfaces z = f"):
        p.save(tmp_path / "l.png")
    assert list(tmp_path.iterdir()) == []


def test_several_surfaces_share_one_picture(tmp_path):
    """plot3d(f, g) draws both into one picture where they hide each other: each
    surface is seen somewhere, and the saved figure is the composite's pixels."""
    p = plot3d(x * y / 3, 2 * sp.exp(-x ** 2 - y ** 2) - sp.Rational(1, 2), (x, -2, 2),
               (y, -2, 2), backend=fc.SympyBackend, show=False, size=(4, 3))
    p.save(tmp_path / "two.png")
    (surface_plot,) = p.plots
    assert len(surface_plot.others) == 1
    r = surface_plot.render
    which = r.stats["surface"]
    assert (which == 0).sum() > 2000 and (which == 1).sum() > 2000
    im = np.asarray(Image.open(tmp_path / "two.png"))
    share, n = _figure_matches_render(im, surface_plot)
    assert n > 5000 and share > 0.99
    p.close()


def test_legend_true_shows_an_entry_a_surface():
    """plot3d(f, g, ..., legend=True) shows a legend, as sympy's own backend: an entry a
    surface, its expression with a patch of its colour (the colour map's at its first
    corner, as mplot3d's first face: x*y = 1 and x**2 - y**2 = 0 at (-1, -1)); without
    legend=True there is none. A label list of the wrong length is a ValueError."""
    p = plot3d(x * y, x ** 2 - y ** 2, (x, -1, 1), (y, -1, 1), show=False, legend=True,
               backend=fc.SympyBackend)
    leg = p.fig.axes[0].get_legend()
    assert [t.get_text() for t in leg.get_texts()] == ["x*y", "x**2 - y**2"]
    plot = p.plots[0]
    for handle, w in zip(leg.legend_handles, (1.0, 0.0)):
        assert np.allclose(handle.get_facecolor(), plot.cmap(plot.norm(w)))
    q = plot3d(x * y, (x, -1, 1), (y, -1, 1), show=False, backend=fc.SympyBackend)
    assert q.fig.axes[0].get_legend() is None
    p.close()
    q.close()
    with pytest.raises(ValueError, match="one a surface"):
        fc.plot_surface([x * y, x - y], (x, -1, 1), (y, -1, 1), label=["only one"])


def test_plotgrid_gives_each_plot_its_cell(tmp_path):
    """sympy's PlotGrid of a 2-D plot and two floatcol plots (it raised AttributeError:
    no process_series): each floatcol plot draws into its own cell's 3-D Axes, and the
    saved grid shows each render where that Axes put it (as the single plot's test)."""
    from sympy.plotting import PlotGrid
    p1 = plot(sp.sin(x), show=False)
    p2 = plot3d(sp.sin(x * y), (x, -2, 2), (y, -2, 2), backend=fc.SympyBackend, show=False)
    p3 = plot3d(sp.cos(x) * y, (x, -2, 2), (y, -2, 2), backend=fc.SympyBackend, show=False,
                cmap="magma")
    g = PlotGrid(1, 3, p1, p2, p3, show=False, size=(9, 3))
    g.save(tmp_path / "grid.png")
    assert p2.fig is g.fig and p3.fig is g.fig
    assert p2.ax is not p3.ax and {p2.ax, p3.ax} <= set(g.fig.axes)
    assert p2.ax.name == "3d" and p2.plots[0].artist.axes is p2.ax
    im = np.asarray(Image.open(tmp_path / "grid.png"))
    for p in (p2, p3):
        share, n = _figure_matches_render(im, p.plots[0])
        assert n > 2000 and share > 0.99
    # the cells' Axes lie side by side: the two pictures are not the same place
    assert p2.plots[0].artist.placed[0, 2] < p3.plots[0].artist.placed[0, 2]


def test_fig_and_ax_given_are_drawn_into(tmp_path):
    import matplotlib.pyplot as plt
    fig = plt.figure(figsize=(4, 3))
    ax = fig.add_subplot(projection="3d")
    p = plot3d(x * y, (x, -2, 2), (y, -2, 2), backend=fc.SympyBackend, show=False,
               fig=fig, ax=ax)
    p.save(tmp_path / "given.png")
    assert p.fig is fig and p.ax is ax and p.plots[0].artist.axes is ax
    plt.close(fig)


@pytest.mark.parametrize("how", ["color_func", "surface_color function", "expression",
                                 "function of z"])
def test_colour_functions_colour_the_surface(how, tmp_path):
    """sympy's colour function (color_func=, or the older surface_color=function; a
    function of x, y or of x, y, z; a sympy expression) colours the surface through
    the colour map as sympy's matplotlib backend does (it was ignored). Unshaded, each
    pixel's colour is the colour map's at the function's value at its seen (x, y), to
    4 levels at 99 % of the wholly seen pixels (measured 2026-12-06: median 0.76, 99th
    percentile 3.01: the colour map's 256 rows against matplotlib's continuous map)."""
    import matplotlib
    f = {"color_func": dict(color_func=lambda a, b: a + b * b),
         "surface_color function": dict(surface_color=lambda a, b: a + b * b),
         "expression": dict(color_func=x + y * y),
         "function of z": dict(color_func=lambda a, b, c: c - a)}[how]
    p = plot3d(sp.sin(x) * y, (x, -2, 2), (y, -1.5, 1.5), backend=fc.SympyBackend,
               show=False, size=(4, 3), shade=False, **f)
    p.save(tmp_path / "c.png")
    (sp_,) = p.plots
    r = sp_.render
    u, v = np.nan_to_num(r.u), np.nan_to_num(r.v)
    val = np.sin(u) * v - u if how == "function of z" else u + v * v
    lo, hi = sp_.norm.vmin, sp_.norm.vmax
    assert hi - lo > 1.0
    want = (matplotlib.colormaps["viridis"](np.clip((val - lo) / (hi - lo), 0, 1))[..., :3]
            * 255)
    seen = (r.side == 1) & (r.rgba[..., 3] == 255)
    assert seen.sum() > 3000
    off = np.abs(r.rgba[..., :3].astype(float) - want).max(axis=-1)
    assert (off[seen] <= 4).mean() > 0.99


def test_surface_colour_values(tmp_path):
    """surface_color a colour: that colour; a number: the colour map's first (as
    matplotlib maps a constant); not a colour: a ValueError that says so."""
    import matplotlib
    for value, want in (("red", (255, 0, 0)), ((0.2, 0.5, 0.9), (51, 128, 230)),
                        (0.5, tuple(round(255 * c) for c in
                                    matplotlib.colormaps["viridis"](0.0)[:3]))):
        p = plot3d(x * y, (x, -2, 2), (y, -2, 2), backend=fc.SympyBackend, show=False,
                   size=(4, 3), shade=False, surface_color=value)
        p.save(tmp_path / "c.png")
        r = p.plots[0].render
        seen = (r.side == 1) & (r.rgba[..., 3] == 255)
        assert seen.sum() > 2000
        assert (np.abs(r.rgba[seen][:, :3].astype(int) - want).max(axis=1) <= 1).mean() > 0.99
    with pytest.raises(ValueError, match="surface_color must be a colour"):
        plot3d(x * y, (x, -2, 2), (y, -2, 2), backend=fc.SympyBackend, show=False,
               surface_color="nocolour").fig


def test_a_colour_functions_complex_values_are_no_colour(tmp_path):
    """A colour function's complex values (sqrt of a negative) are NaN in the colour
    field, as sympy's backend reads them, whether it takes arrays or numbers; one that
    fails says so in a ValueError."""
    import cmath
    for f in (lambda a, b: np.sqrt(a + 0j), lambda a, b: cmath.sqrt(a)):
        p = plot3d(x * y, (x, -2, 2), (y, -2, 2), backend=fc.SympyBackend, show=False,
                   size=(3, 2), color_func=f)
        p.save(tmp_path / "c.png")
        field = p.plots[0].options["color_field"]
        xs = np.linspace(-2, 2, field.shape[1])
        assert np.isnan(field[:, xs < -1e-9]).all() and np.isfinite(field[:, xs > 0]).all()
    with pytest.raises(ValueError, match="colour function failed"):
        plot3d(x * y, (x, -2, 2), (y, -2, 2), backend=fc.SympyBackend, show=False,
               color_func=lambda a, b: 1 / 0).fig

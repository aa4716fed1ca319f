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

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
    # the saved figure is floatcol's render, pixel for pixel where the surface is
    r = surface_plot.render
    assert r.rgba.shape[:2] == (300, 400)
    seen = r.side != 0
    assert seen.mean() > 0.2
    assert (np.abs(im[..., :3].astype(int) - r.rgba[..., :3]).max(axis=2)[seen] <= 1).mean() > 0.999
    p.close()


def test_title_and_default_range(tmp_path):
    p = plot3d(x * y, backend=fc.SympyBackend, show=False, title="xy", size=(3, 3))
    p.save(tmp_path / "t.png")
    assert p.plots[0].domain == ((-10.0, 10.0), (-10.0, 10.0))
    assert p.fig._suptitle.get_text() == "xy"


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
    seen = r.side != 0
    assert (np.abs(im[..., :3].astype(int) - r.rgba[..., :3]).max(axis=2)[seen] <= 1).mean() > 0.999
    p.close()

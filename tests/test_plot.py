"""plot_surface: sympy plot3d's call forms, matplotlib's option names and angles."""
import io

import matplotlib
import numpy as np
import pytest
import sympy as sp
from PIL import Image

matplotlib.use("Agg")

import floatcol as fc  # noqa: E402
from floatcol.plot import mpl_to_paper_angles  # noqa: E402
from conftest import matplotlib_agrees  # noqa: E402
from reference import inner  # noqa: E402

x, y, a, b = sp.symbols("x y a b")
SMALL = (64, 48)


def test_call_forms_agree():
    """Symbols, strings and sympy objects name the same surface and domain."""
    ref = fc.plot_surface(sp.sin(x * y), (x, -2, 2), (y, -1, 1), size=SMALL)
    same = [fc.plot_surface("sin(x*y)", ("x", -2, 2), ("y", -1, 1), size=SMALL),
            fc.plot_surface("sin(x*y)", (x, -2, 2), (y, -1, 1), size=SMALL),
            fc.plot_surface(sp.sin(x * y), (x, -2, 2), ("y", -1, 1), size=SMALL)]
    for p in same:
        assert p.surface.variables == ("x", "y")
        assert p.domain == ((-2.0, 2.0), (-1.0, 1.0))
        assert np.array_equal(p.rgba, ref.rgba)


def test_range_order_decides_the_axes():
    """The first range is the horizontal u axis, whatever the names sort to."""
    p = fc.plot_surface(a + 2 * b, (b, 0, 1), (a, -3, 3), size=SMALL)
    assert p.surface.variables == ("b", "a")
    assert p.domain == ((0.0, 1.0), (-3.0, 3.0))
    w = p.surface.evaluate(np.array([1.0]), np.array([0.5]))     # b = 1, a = 0.5
    assert w[0] == pytest.approx(2.5)


def test_default_ranges_are_sympys():
    p = fc.plot_surface(x * y, size=SMALL)
    assert p.surface.variables == ("x", "y")                      # sorted, as sympy
    assert p.domain == ((-10.0, 10.0), (-10.0, 10.0))
    q = fc.plot_surface("u - v", ("u", 0, 1), size=SMALL)          # the other: default
    assert q.domain == ((0.0, 1.0), (-10.0, 10.0))


def test_heightfield_keeps_its_extent():
    z = np.add.outer(np.arange(5.0), np.arange(7.0))
    p = fc.plot_surface(fc.HeightField(z, u=(0, 3), v=(0, 2)), size=SMALL)
    assert p.domain == ((0.0, 3.0), (0.0, 2.0))


@pytest.mark.parametrize("bad,needle", [
    (dict(ranges=[(x, 2, 1)]), "reversed"),
    (dict(ranges=[(x, 0, 1), (x, 0, 1)]), "same variable"),
    (dict(ranges=[(x, 0, 1), (y, 0, 1), ("z", 0, 1)]), "at most two"),
    (dict(ranges=[(x, 0)]), "(symbol, low, high)"),
    (dict(expr=x * y * a, ranges=[(x, 0, 1), (y, 0, 1)]), "unknown symbol a"),
    (dict(expr=x * y * a), "unknown symbol y: the variables are a and x"),
    (dict(options=dict(camera=3)), "unknown option camera"),
    (dict(options=dict(proj_type="fisheye")), "proj_type"),
    (dict(options=dict(cmap="nosuchmap")), "nosuchmap"),
    (dict(options=dict(norm=3)), "Normalize"),
    (dict(options=dict(lightsource="north")), "LightSource"),
    (dict(options=dict(elev=100)), "elev"),
    (dict(options=dict(interactive=True)), "ax="),
])
def test_bad_input_names_what_to_fix(bad, needle):
    expr = bad.get("expr", sp.sin(x * y))
    with pytest.raises(ValueError, match=needle.replace("(", r"\(").replace(")", r"\)")):
        fc.plot_surface(expr, *bad.get("ranges", []), size=SMALL, **bad.get("options", {}))


def test_angles_follow_matplotlib():
    """Project the domain's corners with matplotlib's own Axes3D camera (orthographic,
    equal x/y ranges, so its box scaling is uniform) and with floatcol's View for the
    same elev/azim: the two quadrilaterals agree up to scale and shift."""
    corners = np.array([[-1.0, 1.0, 1.0, -1.0], [-1.0, -1.0, 1.0, 1.0], [0.0] * 4])
    for elev, azim in [(30, -60), (45, 30), (20, 160), (60, -135)]:
        p = fc.plot_surface("0*x", ("x", -1, 1), ("y", -1, 1), elev=elev, azim=azim,
                            proj_type="ortho", size=(200, 200))
        assert matplotlib_agrees(p.draw().view, corners, corners, [(-1, 1)] * 3, elev, azim), \
            (elev, azim)
    assert mpl_to_paper_angles(30, -60) == (30.0, -30.0)


def test_lightsource_is_a_world_direction():
    """A LightSource straight overhead lights a horizontal plane fully and equally in
    every view; one at the horizon leaves it at the ambient level."""
    from matplotlib.colors import LightSource
    for azim in (-60, 40):
        top = fc.plot_surface("0*x + 1", ("x", -1, 1), ("y", -1, 1), size=SMALL, azim=azim,
                              lightsource=LightSource(azdeg=0, altdeg=90), ambient=0.2).draw()
        seen = top.side != 0
        assert np.allclose(top.intensity[seen], 1.0, atol=1e-5)
        low = fc.plot_surface("0*x + 1", ("x", -1, 1), ("y", -1, 1), size=SMALL, azim=azim,
                              lightsource=LightSource(azdeg=0, altdeg=0), ambient=0.2).draw()
        assert np.allclose(low.intensity[low.side != 0], 0.2, atol=1e-5)


def test_a_functions_ranges_need_no_symbol():
    """plot_surface(f, (a, b), (c, d)) with a Python function: (low, high) of its first
    and second argument (they raised "a range must be (symbol, low, high)"); the
    surface is f there (to 1e-12), the symbol form still works, and an expression still
    needs its symbols (which of its names a range is would be a guess). numpy's
    functions of two arguments (np.hypot, np.arctan2) are functions too (Numba could
    not compile them)."""
    def f(x, y):
        return x * y + 0.5 * x

    p = fc.plot_surface(f, (-1, 1), (-2, 3), size=SMALL)
    assert p.domain == ((-1.0, 1.0), (-2.0, 3.0))
    u, v = np.array([-1.0, 0.3, 1.0]), np.array([3.0, -0.7, -2.0])
    assert np.abs(p.surface.evaluate(u, v) - f(u, v)).max() < 1e-12
    assert fc.plot_surface(f, ("x", -1, 1), (-2, 3), size=SMALL).domain == p.domain
    assert fc.plot_surface(lambda a, b: a - b, (0, 2), size=SMALL).domain[0] == (0.0, 2.0)
    with pytest.raises(ValueError, match=r"a range must be \(symbol, low, high\)"):
        fc.plot_surface("x*y", (-1, 1), (-1, 1))
    # numpy's functions of two arguments (ufuncs: Numba cannot compile them as they
    # are, "The decorated object is not a function")
    for uf in (np.hypot, np.arctan2):
        q = fc.plot_surface(uf, (-1, 1), (-1, 1), size=SMALL)
        assert np.abs(q.surface.evaluate(u, v / 3) - uf(u, v / 3)).max() < 1e-12
        assert q.draw().side.any()
    with pytest.raises(ValueError, match="'sin' must take two arguments"):
        fc.plot_surface(np.sin, (-1, 1), (-1, 1))


def test_shade_false_gives_flat_colour():
    p = fc.plot_surface("x*y", ("x", -1, 1), ("y", -1, 1), size=SMALL, color="red", shade=False)
    up = inner(p.render_kwargs(SMALL) and p.draw().side > 0)
    assert up.sum() > 100
    assert np.all(p.rgba[up][:, :3] == [255, 0, 0])


def test_vmin_vmax_and_norm_set_the_colours():
    from matplotlib.colors import LogNorm, Normalize
    # antialias=False: the plane is seen at a grazing angle, so an antialiased pixel
    # averages colours over a visible range of w; here the colour of w itself is tested
    p = fc.plot_surface("x + 2", ("x", -1, 1), ("y", -1, 1), size=SMALL, shade=False,
                        cmap="gray", vmin=1, vmax=3, antialias=False)
    r = p.draw()
    up = inner(r.side > 0)
    want = np.round((r.w[up] - 1) / 2 * 255)
    assert np.abs(r.rgba[up][:, 0].astype(float) - want).max() <= 1.5
    q = fc.plot_surface("x + 2", ("x", -1, 1), ("y", -1, 1), size=SMALL, shade=False,
                        cmap="gray", norm=LogNorm(1, 3), antialias=False)
    rq = q.draw()
    upq = inner(rq.side > 0)
    want = np.round(np.log(rq.w[upq]) / np.log(3) * 255)
    assert np.abs(rq.rgba[upq][:, 0].astype(float) - want).max() <= 1.5
    lin = fc.plot_surface("x + 2", ("x", -1, 1), ("y", -1, 1), size=SMALL, norm=Normalize(1, 3))
    assert (lin.norm.vmin, lin.norm.vmax) == (1, 3)


@pytest.mark.parametrize("name", ["log", "symlog", "asinh", "linear"])
def test_a_scales_name_is_a_norm_as_in_matplotlib(name):
    """norm="log" (a scale's name, matplotlib 3.6's form; it raised "must be a
    Normalize") colours as that scale's norm does, in plot_surface and render, with
    vmin/vmax (allowed beside a name, as in matplotlib) or autoscaled: every whole pixel
    has matplotlib's colour for its seen height, to 2 levels (measured 2026-12-06: at
    most 1, the colour table's rows against matplotlib's continuous map)."""
    import matplotlib
    cm = matplotlib.colormaps["gray"]
    expr, rx, ry = "exp(x)*(1 + y*y)", ("x", -3, 2), ("y", -1, 1)
    for kw in (dict(vmin=0.1, vmax=8.0), {}):
        p = fc.plot_surface(expr, rx, ry, size=(120, 90), shade=False, cmap="gray",
                            norm=name, antialias=False, **kw)
        r = p.draw()
        up = inner(r.side > 0)
        assert up.sum() > 1500
        n = matplotlib.cm.ScalarMappable(norm=name).norm
        n.vmin, n.vmax = r.stats["w_limits"]
        if kw:
            assert (n.vmin, n.vmax) == pytest.approx((0.1, 8.0))
        else:          # plot_surface's autoscale: f over its domain, as matplotlib's mesh
            assert (n.vmin, n.vmax) == pytest.approx((np.exp(-3), 2 * np.exp(2)), rel=1e-3)
        want = np.round(cm(n(r.w[up]))[:, 0] * 255)
        assert np.abs(r.rgba[up][:, 0].astype(float) - want).max() <= 2.0
        assert type(p.norm).__name__ == type(n).__name__
    r = fc.render("exp(u)*(1 + v*v)", u=(-3, 2), v=(-1, 1),
                  size=(120, 90), shading="lambert", antialias=False, norm=name, vmin=0.1,
                  vmax=8.0, cmap="gray")
    assert r.stats["w_limits"] == pytest.approx((0.1, 8.0))


def test_a_log_norm_autoscales_to_the_positive_heights():
    """A log norm over heights that reach zero or below takes its vmin from the positive
    ones, as matplotlib's autoscale masks the others (it raised "cannot be inverted"):
    in plot_surface (f over the domain) and render (the heights seen); those below take
    the lowest colour. A scale with no norm (or none) raises ValueError naming them."""
    p = fc.plot_surface("x*y", ("x", 0, 2), ("y", -1, 2), size=(80, 60), norm="log")
    p.draw()
    assert 0.0 < p.norm.vmin < 1e-3 and p.norm.vmax == pytest.approx(4.0, rel=1e-3)
    r = fc.render("u*v", u=(0, 2), v=(-1, 2), size=(80, 60), norm="log")
    lo, hi = r.stats["w_limits"]
    seen = fc.render("u*v", u=(0, 2), v=(-1, 2), size=(80, 60)).stats["w_limits"]
    assert seen[0] < -1.5 and 0.0 < lo < 0.1 and hi == pytest.approx(seen[1])  # (seen top)
    for bad in ("function", "Log", "lin"):
        with pytest.raises(ValueError, match="'log', 'logit', 'symlog'"):
            fc.plot_surface("x*y", ("x", 0, 2), ("y", -1, 2), norm=bad)
        with pytest.raises(ValueError, match="'log', 'logit', 'symlog'"):
            fc.render("u*v", norm=bad, size=(40, 30))


@pytest.mark.parametrize("ncolors, cmap", [(256, "viridis"), (4, "listed")])
def test_a_boundary_norm_colours_in_bands(ncolors, cmap):
    """matplotlib's BoundaryNorm (discrete levels, no inverse: it raised "cannot be
    inverted") colours each band between two boundaries with the colour the norm gives
    it: every whole pixel away from a boundary (by 0.01) has matplotlib's colour for its
    seen height, to 1 level (measured 2026-12-06: all of them, 0 off)."""
    import matplotlib
    from matplotlib.colors import BoundaryNorm, ListedColormap
    cm = (matplotlib.colormaps[cmap] if cmap != "listed" else
          ListedColormap(["tab:blue", "tab:green", "tab:orange", "tab:red"]))
    bounds = np.array([-1.0, -0.6, -0.1, 0.3, 1.0]) if ncolors == 4 else \
        np.linspace(-1, 1, 9)
    norm = BoundaryNorm(bounds, ncolors)
    p = fc.plot_surface("sin(x)*cos(y)", ("x", -3, 3), ("y", -3, 3), size=(160, 120),
                        shade=False, cmap=cm, norm=norm, antialias=False)
    r = p.draw()
    up = inner(r.side > 0)
    w = r.w[up]
    away = np.abs(w[:, None] - bounds[None, :]).min(axis=1) > 0.01
    assert away.sum() > 3000
    want = np.round(cm(norm(w[away]))[:, :3] * 255)
    assert np.abs(r.rgba[up][away][:, :3].astype(float) - want).max() <= 1.0
    assert len(np.unique(r.rgba[up][away][:, :3], axis=0)) == min(ncolors, len(bounds) - 1)


@pytest.mark.parametrize("norm", [None, "log"])
def test_a_colour_maps_extremes_colour_beyond_vmin_vmax(norm):
    """cmap.with_extremes(under=, over=) colours heights below vmin and above vmax as
    matplotlib does (they took the map's end colours): every whole pixel away from
    vmin and vmax (by 0.01) has matplotlib's colour for its seen height, to 4 levels
    (measured 2026-12-06: at most 3, the colour table's 256 rows against matplotlib's
    continuous map), and both extremes show."""
    import matplotlib
    from matplotlib.colors import LogNorm, Normalize
    cm = matplotlib.colormaps["viridis"].with_extremes(under="black", over="red")
    lo, hi = 1.4, 2.6
    kw = dict(norm=LogNorm(lo, hi)) if norm else dict(vmin=lo, vmax=hi)
    p = fc.plot_surface("2 + sin(x)*cos(y)", ("x", -3, 3), ("y", -3, 3), size=(160, 120),
                        shade=False, cmap=cm, antialias=False, **kw)
    r = p.draw()
    up = inner(r.side > 0)
    w = r.w[up]
    away = (np.abs(w - lo) > 0.01) & (np.abs(w - hi) > 0.01)
    n = LogNorm(lo, hi) if norm else Normalize(lo, hi)
    want = np.round(cm(n(w[away]))[:, :3] * 255)
    got = r.rgba[up][away][:, :3].astype(float)
    assert np.abs(got - want).max() <= 4.0
    assert (w[away] < lo).sum() > 300 and (w[away] > hi).sum() > 300
    assert (got[w[away] > hi] == [255, 0, 0]).all() and (got[w[away] < lo] == 0).all()


def test_a_nonlinear_norm_keeps_highlights_and_antialiasing():
    """A LogNorm colours inside the kernel (each colormap row starts at
    norm.inverse(k/255)), so the picture keeps what the linear colormap has: the
    coverage of silhouette pixels (alpha over a transparent background, identical to
    the linear norm's) and the specular highlights (an earlier recolouring of the
    finished picture lost both)."""
    from matplotlib.colors import LogNorm
    kw = dict(size=SMALL, background=(0, 0, 0, 0), elev=25)
    expr, rx, ry = "x*x + y*y + 1", ("x", -1, 1), ("y", -1, 1)
    log = fc.plot_surface(expr, rx, ry, norm=LogNorm(1, 3), **kw).draw()
    lin = fc.plot_surface(expr, rx, ry, vmin=1, vmax=3, **kw).draw()
    dull = fc.plot_surface(expr, rx, ry, norm=LogNorm(1, 3), specular=0.0, **kw).draw()
    alpha = log.rgba[..., 3]
    assert np.array_equal(alpha, lin.rgba[..., 3])
    assert ((alpha > 0) & (alpha < 255)).sum() > 50             # antialiased edges
    # the highlight adds up to 29 levels here (measured); recolouring added nothing
    assert (log.rgba[..., :3].astype(int) - dull.rgba[..., :3]).max() >= 15
    assert log.stats["w_limits"] == pytest.approx((1, 3))


def test_default_colour_range_is_f_over_the_domain():
    p = fc.plot_surface("x", ("x", -3, 5), ("y", 0, 1), size=SMALL)
    assert p.norm.vmin == pytest.approx(-3) and p.norm.vmax == pytest.approx(5)


def test_focal_length_widens_the_perspective():
    """A shorter focal length puts the eye nearer: the near edge grows relative to the
    far edge, as with matplotlib's focal_length."""
    def ratio(fl):
        p = fc.plot_surface("0*x", ("x", -1, 1), ("y", -1, 1), size=(200, 200), elev=30,
                            azim=-90, focal_length=fl)
        view = p.draw().view
        near = np.ptp(view.project(np.array([-1.0, 1.0]), np.array([-1.0, -1.0]), np.zeros(2))[0])
        far = np.ptp(view.project(np.array([-1.0, 1.0]), np.array([1.0, 1.0]), np.zeros(2))[0])
        return near / far
    assert ratio(0.5) > ratio(2.0) > ratio(8.0) > 1.0


@pytest.mark.parametrize("ext,magic", [(".png", b"\x89PNG"), (".jpg", b"\xff\xd8\xff"),
                                       (".pdf", b"%PDF"), (".svg", b"<?xml")])
def test_save_formats(tmp_path, ext, magic):
    p = fc.plot_surface("sin(x)*y", ("x", -2, 2), ("y", -1, 1), size=SMALL)
    p.save(tmp_path / ("s" + ext))
    assert (tmp_path / ("s" + ext)).read_bytes()[:len(magic)] == magic
    assert [f.name for f in tmp_path.iterdir()] == ["s" + ext]


def test_save_refuses_unknown_format_and_writes_nothing(tmp_path):
    p = fc.plot_surface("x", ("x", 0, 1), ("y", 0, 1), size=SMALL)
    with pytest.raises(ValueError, match="must end in"):
        p.save(tmp_path / "s.bmp")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("call,needle", [
    # (numpy's UFuncTypeError from clipping a string; Python's TypeError dividing by one)
    (lambda p, d: p.view_init("x"), "elev must be a number, got 'x'"),
    (lambda p, d: p.view_init(30, float("inf")), "azim must be finite"),
    (lambda p, d: p.save(d / "s.pdf", dpi="x"), "dpi must be a number, got 'x'"),
    (lambda p, d: p.save(d / "s.svg", dpi=-1), "dpi must be positive"),
    # (numpy's "operands could not be broadcast together with shapes (5,3) (10,3)")
    (lambda p, d: p.quiver(*[np.zeros(5)] * 3, *[np.zeros((5, 2))] * 3),
     "quiver: x, y, z, u, v, w must be numbers or arrays of one length"),
    (lambda p, d: p.quiver(0, 0, 0, 1, 1, 1, arrow_length_ratio="x"),
     "arrow_length_ratio must be a number"),
])
def test_a_plots_methods_name_what_to_fix(tmp_path, call, needle):
    p = fc.plot_surface("x", ("x", 0, 1), ("y", 0, 1), size=SMALL)
    with pytest.raises(ValueError, match=needle):
        call(p, tmp_path)
    assert list(tmp_path.iterdir()) == []


def test_repr_png_is_the_picture():
    p = fc.plot_surface("cos(x)*cos(y)", ("x", -3, 3), ("y", -3, 3), size=SMALL)
    data = p._repr_png_()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(data))), p.rgba)
    assert p.render.rgba.shape == (48, 64, 4)


def test_a_list_draws_several_surfaces_with_one_colour_range():
    p = fc.plot_surface(["x*y/3", ("x + y + 3", ("x", 0, 1), ("y", 0, 1))],
                        ("x", -2, 2), ("y", -2, 2), size=SMALL)
    assert p.others[0][1] == ((0.0, 1.0), (0.0, 1.0))
    assert (p.norm.vmin, p.norm.vmax) == pytest.approx((-4 / 3, 5))   # over both
    r = p.draw()
    assert {0, 1} <= set(np.unique(r.stats["surface"]))
    with pytest.raises(ValueError, match="empty list"):
        fc.plot_surface([], ("x", -1, 1))

"""matplotlib's plot_surface(X, Y, Z) on meshes that are not an evenly spaced grid
(floatcol/mesh.py): unevenly spaced x or y, and curvilinear grids (matplotlib's
surface3d_radial example), resampled into a height field; parametric surfaces
refused."""
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import floatcol as fc  # noqa: E402
from conftest import red_overlap  # noqa: E402
from floatcol.plot import mesh_surface  # noqa: E402


def _polar(n_r=30, n_p=50, r0=0.0, r1=1.25, turns=1.0):
    r = np.linspace(r0, r1, n_r)
    p = np.linspace(0, 2 * np.pi * turns, n_p)
    R, P = np.meshgrid(r, p)
    return R * np.cos(P), R * np.sin(P)


def test_uneven_spacing_keeps_the_meshs_own_bilinear_surface():
    """A bilinear function is its own bilinear interpolation on any grid: resampled
    from np.geomspace x and uneven y, the height field is that function everywhere
    (to rounding), at points off every node."""
    x = np.geomspace(0.1, 100.0, 25)
    y = np.array([-2.0, -1.5, -0.2, 0.0, 0.3, 1.7, 2.0])
    X, Y = np.meshgrid(x, y)

    def f(x, y):
        return 1.5 + 0.02 * x - 0.7 * y + 0.01 * x * y
    hf = mesh_surface(X, Y, f(X, Y))
    assert hf.resampled
    (ua, ub), (va, vb) = hf.default_domain
    assert (ua, ub, va, vb) == (0.1, 100.0, -2.0, 2.0)
    rng = np.random.default_rng(3)
    u, v = rng.uniform(0.1, 100.0, 500), rng.uniform(-2.0, 2.0, 500)
    assert np.abs(hf.evaluate(u, v) - f(u, v)).max() < 1e-9
    # descending x (a north-up raster's rows) too
    hf2 = mesh_surface(X[:, ::-1], Y[:, ::-1], f(X, Y)[:, ::-1])
    assert np.abs(hf2.evaluate(u, v) - f(u, v)).max() < 1e-9


def test_a_polar_grid_is_resampled_exactly_where_the_surface_is_linear():
    """On a polar grid a linear function is linear on every triangle of every quad:
    the resampled nodes inside the mesh carry it exactly, those outside the disk are
    holes, and the holes are the disk's outside to within a node."""
    X, Y = _polar()

    def f(x, y):
        return 0.3 + 0.5 * x - 0.25 * y
    hf = mesh_surface(X, Y, f(X, Y))
    (ua, ub), (va, vb) = hf.default_domain
    u = np.linspace(ua, ub, hf.hf.shape[1])
    v = np.linspace(va, vb, hf.hf.shape[0])
    U, V = np.meshgrid(u, v)
    z = hf.hf
    inside = np.isfinite(z)
    assert np.abs(z[inside] - f(U, V)[inside]).max() < 1e-9
    r = np.hypot(U, V)
    step = u[1] - u[0]
    assert not inside[r > 1.25 + 1e-9].any()
    # the polygon of 50 angles inscribed in the circle holds all within cos(pi/49) r
    assert inside[r < 1.25 * np.cos(np.pi / 49) - step].all()
    # facecolors, a colour a quad (its angle's row, its radius's column): each node
    # inside the mesh takes its quad's, the quad bounded by two rays and two chords
    n_p, n_r = X.shape
    k, l_ = np.meshgrid(np.arange(n_p - 1), np.arange(n_r - 1), indexing="ij")
    faces = np.stack([k / (n_p - 2), l_ / (n_r - 2), 0.5 + 0 * k], axis=-1)
    hf, (tex, extent) = mesh_surface(X, Y, f(X, Y), faces=faces)
    assert extent is None and tex.shape[:2] == z.shape      # at the height field's nodes
    dp = 2 * np.pi / (n_p - 1)
    ang = np.mod(np.arctan2(V, U), 2 * np.pi)
    kk = np.clip(np.floor(ang / dp).astype(int), 0, n_p - 2)
    chord = r * np.cos(ang - kk * dp - dp / 2) / np.cos(dp / 2)     # (radius at the ray)
    ll = np.clip(np.floor(chord / (1.25 / (n_r - 1))).astype(int), 0, n_r - 2)
    edge = 1.25 / (n_r - 1)
    clear = inside & (np.abs(chord / edge - np.rint(chord / edge)) * edge > 1e-6) & \
        (np.abs(ang / dp - np.rint(ang / dp)) * r > 1e-6)     # (not on an edge)
    assert clear.sum() > 0.9 * inside.sum()
    assert np.abs(tex[clear] - faces[kk, ll][clear]).max() < 1e-9
    assert np.isfinite(tex).all() and tex.min() >= 0.0 and tex.max() <= 1.0


def test_the_radial_example_where_mplot3d_draws_it():
    """matplotlib's surface3d_radial example with fc.plot_surface: the surface covers
    where mplot3d draws the same mesh, both flat red (intersection over union;
    measured 2026-12-06: 0.978 perspective and orthographic)."""
    r = np.linspace(0, 1.25, 50)
    p = np.linspace(0, 2 * np.pi, 50)
    R, P = np.meshgrid(r, p)
    Z = (R ** 2 - 1) ** 2
    X, Y = R * np.cos(P), R * np.sin(P)

    for proj in ("persp", "ortho"):
        iou, theirs = red_overlap(
            lambda ax: fc.plot_surface(X, Y, Z, ax=ax, color="red", lower_color="red",
                                       shade=False),
            lambda ax: ax.plot_surface(X, Y, Z, color="red", shade=False, linewidth=0,
                                       antialiased=False),
            lambda ax: ax.set(xlim=(-1.3, 1.3), ylim=(-1.3, 1.3), zlim=(0, 1.01)), proj)
        assert theirs > 20000 and iou > 0.95


@pytest.mark.parametrize("make, why", [
    # a sphere: it folds over at its equator
    (lambda: (np.outer(np.cos(np.linspace(0, 6.3, 40)), np.sin(np.linspace(0, 3.1, 20))),
              np.outer(np.sin(np.linspace(0, 6.3, 40)), np.sin(np.linspace(0, 3.1, 20))),
              np.outer(np.ones(40), np.cos(np.linspace(0, 3.1, 20)))), "fold"),
    # an annulus wound round twice: its quads lie over one another
    (lambda: (*_polar(10, 100, 0.5, 1.0, turns=2.0), np.zeros((100, 10))), "overlap"),
])
def test_a_parametric_surface_is_refused_saying_why(make, why):
    X, Y, Z = make()
    with pytest.raises(ValueError, match=f"not the grid of a function.*{why}"):
        fc.plot_surface(X, Y, Z, size=(40, 30))


def test_masked_values_are_holes():
    """matplotlib's missing data, a masked array: its masked values are holes (as
    mplot3d leaves them out), not the numbers under the mask."""
    x = np.linspace(-2, 2, 21)
    X, Y = np.meshgrid(x, x)
    Z = np.exp(-X ** 2 - Y ** 2)
    hole = X ** 2 + Y ** 2 < 0.5
    hf = mesh_surface(X, Y, np.ma.masked_where(hole, Z))
    assert np.isnan(hf.hf[hole]).all() and np.isfinite(hf.hf[~hole]).all()
    Xr, Yr = _polar(8, 16)
    Zr = np.ma.masked_where(Xr > 0.9, Xr + Yr)
    hf = mesh_surface(Xr, Yr, Zr)
    (ua, ub), (va, vb) = hf.default_domain
    U, V = np.meshgrid(np.linspace(ua, ub, hf.hf.shape[1]), np.linspace(va, vb, hf.hf.shape[0]))
    assert not np.isfinite(hf.hf[U > 1.0]).any()


def test_coinciding_points_are_one_at_their_mean_height():
    """A polar grid's centre (every angle's r = 0) and its seam (angle 0 and 2 pi)
    with heights that differ (data with noise): one point each, at the mean."""
    X, Y = _polar(10, 21)
    Z = 0.5 * X - 0.25 * Y
    Z[:, 0] = np.linspace(-1.0, 1.0, 21) + 0.3           # the centre: mean 0.3
    hf = mesh_surface(X, Y, Z)
    (ua, ub), (va, vb) = hf.default_domain
    # (at the centre, bilinear between the resampled nodes around it, which lie a
    # half-node from it on triangles rising to the first ring: 0.2885 measured; the
    # first angle's height would give -0.7, the last's 1.3)
    assert abs(hf.evaluate(np.array([0.0]), np.array([0.0]))[0] - 0.3) < 0.03
    # away from the centre's triangles, the plane
    u, v = np.array([0.9, -0.5]), np.array([0.2, -0.8])
    assert np.abs(hf.evaluate(u, v) - (0.5 * u - 0.25 * v)).max() < 1e-9


def test_a_resampled_meshs_edges_are_not_drawn_and_it_says_so():
    X, Y = _polar(12, 24)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        p = fc.plot_surface(X, Y, X * Y, edgecolor="k", linewidth=0.5, size=(60, 40))
    assert any("edges of a mesh that is not an evenly spaced grid" in str(w.message)
               for w in caught)
    assert p.render is None or p.rgba.shape == (40, 60, 4)
    assert p.rgba[..., 3].any()


def test_plot_wireframe_of_a_resampled_mesh_says_what_to_do():
    """fc.plot_wireframe draws the mesh's lines on the exact surface: a mesh that is
    resampled has none there, and it says so (it said fill=False needs a wireframe)."""
    X, Y = _polar(12, 24)
    with pytest.raises(ValueError, match="plot_wireframe.*not an evenly spaced grid.*"
                                         "ax.plot_wireframe"):
        fc.plot_wireframe(X, Y, X * Y, rstride=2, cstride=2)


def test_odd_meshes_are_holes_or_a_clear_error_never_a_crash():
    """Not-a-number coordinates and heights, a mesh with no area, a single line of
    points, facecolors: holes, or a ValueError that says what to fix."""
    X, Y = _polar(8, 16)
    Z = X + Y
    Xn, Zn = X.copy(), Z.copy()
    Xn[3, 4] = np.nan
    Zn[5, 5] = np.inf
    p = fc.plot_surface(Xn, Y, Zn, size=(40, 30))
    assert p.rgba[..., 3].any()
    line = np.arange(25.0).reshape(5, 5)         # every point on the line y = x
    with pytest.raises(ValueError, match="span no area"):
        fc.plot_surface(line, line, np.ones((5, 5)), size=(40, 30))
    colours = np.random.default_rng(1).uniform(0, 1, X.shape + (3,))
    for c in (colours, np.round(colours * 255).astype(np.uint8)):
        p = fc.plot_surface(X, Y, Z, facecolors=c, size=(40, 30))
        assert p.rgba[..., 3].any()
    # quads that each cross the whole mesh (slivers along its diagonal): refused
    # rather than minutes of resampling
    k = np.arange(2000) * 1e-6
    Xs = np.stack([k, 1.0 + k])
    Ys = np.stack([0.0 * k, 1.0 + 0.0 * k])
    with pytest.raises(ValueError, match="too long and thin"):
        fc.plot_surface(Xs, Ys, Xs + Ys, size=(40, 30))
    with pytest.raises(ValueError, match="spans more than the largest double"):
        fc.plot_surface(np.array([-1e308, 0.0, 1e308]), np.array([0.0, 1.0]), np.ones((2, 3)))
    with pytest.raises(ValueError, match="spans more than the largest double"):
        fc.plot_surface(X * 1e308, Y * 1e308, Z, size=(40, 30))
    with pytest.raises(ValueError, match="finite and ascending or descending"):
        fc.plot_surface(np.array([0.0, 2.0, 1.0]), np.array([0.0, 1.0]), np.ones((2, 3)))


@pytest.mark.parametrize("projection", ["orthographic", "perspective"])
def test_a_spike_in_a_mesh_is_shown_whole(projection):
    """A mesh's heights are data: a spike at one node (5 over a hill of 1) is a value
    to show, as mplot3d's limits show it, not a pole to trim. The picture's fit takes
    the mesh's highest and lowest nodes in (its box, aspect "auto", spans 5, and the
    spike's top projects inside the picture: the fit grid of 65 x 65 points misses
    the node, and its robust range took the spike for a pole), and the colour map
    spans the data's range exactly. Before: the box spanned -0.90 .. 2.32, the top
    lay 189 (orthographic) and 233 (perspective) rows above the picture, vmax 4.49."""
    x = np.linspace(-3, 3, 50)
    X, Y = np.meshgrid(x, x)
    Z = np.exp(-(X ** 2 + Y ** 2)) + 0.3 * X
    Z[10, 10] = 5.0
    hf = fc.HeightField(Z, u=(-3, 3), v=(-3, 3))
    r = fc.render(hf, size=(400, 300), elev=30, azim=-60, aspect="auto",
                  projection=projection)
    box = r.box
    col, row = r.view.project(np.array([X[10, 10] * box[0]]), np.array([Y[10, 10] * box[1]]),
                              np.array([5.0 * box[2]]))
    assert 0.0 <= row[0] <= 299.0 and 0.0 <= col[0] <= 399.0
    assert box[2] == pytest.approx(0.75 * 6.0 / (5.0 - Z.min()))   # (4 : 4 : 3 of the data)
    plot = fc.plot_surface(X, Y, Z, size=(80, 60))
    assert (plot.norm.vmin, plot.norm.vmax) == (pytest.approx(Z.min()), 5.0)


def _scatter(n=300, seed=4):
    rng = np.random.default_rng(seed)
    r = np.sqrt(rng.uniform(0, 1, n)) * 1.5
    a = rng.uniform(0, 2 * np.pi, n)
    return r * np.cos(a), r * np.sin(a)


def _plot_hf(p):
    hf = p.surface
    (ua, ub), (va, vb) = hf.default_domain
    U, V = np.meshgrid(np.linspace(ua, ub, hf.hf.shape[1]), np.linspace(va, vb, hf.hf.shape[0]))
    return U, V, hf.hf


def test_trisurf_is_linear_on_the_points_delaunay_triangles():
    """fc.plot_trisurf(x, y, z) at scattered points: at every node of the resampled
    grid inside the points' hull, the height matplotlib's LinearTriInterpolator gives on
    the same Delaunay triangulation (to 1e-9); holes outside the hull (to within a
    node); a linear function comes out exact."""
    from matplotlib.tri import LinearTriInterpolator, Triangulation
    x, y = _scatter()
    z = x * x + np.sin(2 * y)
    p = fc.plot_trisurf(x, y, z, size=(40, 30))
    U, V, H = _plot_hf(p)
    assert max(H.shape) == int(np.clip(16 * np.sqrt(len(x)), 65, 2049))
    want = LinearTriInterpolator(Triangulation(x, y), z)(U, V).filled(np.nan)
    both = np.isfinite(H) & np.isfinite(want)
    assert both.sum() > 0.7 * np.isfinite(want).sum()
    assert np.abs(H[both] - want[both]).max() < 1e-9
    # nodes more than a node's step inside the hull are drawn; outside it, none
    step = U[0, 1] - U[0, 0]
    inside_hull = LinearTriInterpolator(Triangulation(x, y), 0 * z)
    for du, dv in ((step, 0), (-step, 0), (0, step), (0, -step)):
        near = ~np.ma.getmaskarray(inside_hull(U + du, V + dv))
        inside = ~np.ma.getmaskarray(inside_hull(U, V)) & near
    assert np.isfinite(H[inside]).all()
    assert not np.isfinite(H[np.ma.getmaskarray(inside_hull(U, V))]).any()
    lin = fc.plot_trisurf(x, y, 0.3 + 0.5 * x - 0.25 * y, size=(40, 30))
    U, V, H = _plot_hf(lin)
    ok = np.isfinite(H)
    assert np.abs(H[ok] - (0.3 + 0.5 * U[ok] - 0.25 * V[ok])).max() < 1e-9


def test_trisurf_call_forms_and_mask():
    """mplot3d's call forms give one surface: (x, y, z), (x, y, triangles, z),
    triangles=, (Triangulation, z); a mask's triangles are holes."""
    from matplotlib.tri import Triangulation
    x, y = _scatter(80, 7)
    z = np.cos(x) * y
    tri = Triangulation(x, y)
    base = _plot_hf(fc.plot_trisurf(x, y, z, size=(40, 30)))[2]
    for args, kw in (((x, y, tri.triangles, z), {}), ((x, y, z), {"triangles": tri.triangles}),
                     ((tri, z), {})):
        np.testing.assert_array_equal(_plot_hf(fc.plot_trisurf(*args, size=(40, 30), **kw))[2],
                                      base)
    mask = np.zeros(len(tri.triangles), dtype=bool)
    mask[::3] = True
    U, V, H = _plot_hf(fc.plot_trisurf(x, y, z, mask=mask, size=(40, 30)))
    hidden = Triangulation(x, y, tri.triangles, mask=~mask).get_trifinder()(U, V) >= 0
    assert hidden.sum() > 1000 and not np.isfinite(H[hidden]).any()
    assert np.isfinite(H).sum() > 0.5 * np.isfinite(base).sum()


@pytest.mark.parametrize("args, match", [
    ((np.zeros(5), np.arange(5.0), np.ones(5)), "span no area"),
    ((np.arange(2.0), np.arange(2.0), np.ones(2)), "span no area"),
    ((np.array([np.nan, 0, 1, 0]), np.array([0, 0, 1, 1.0]), np.ones(4)), "finite"),
    ((np.arange(4.0), np.array([0, 1, 0, 1.0]), np.ones(3)), "one height a point"),
    ((np.arange(4.0),), "give the points"),
    ((np.arange(4.0), np.array([0, 1, 0, 1.0]), [[0, 1, 5]], np.ones(4)), "plot_trisurf"),
    ((np.array([0, 1, 0, 1.0]), np.array([0, 0, 1, 1.0]), [[0, 1, 2], [0, 1, 3]],
      np.ones(4)), "lie over one another"),
])
def test_trisurf_refuses_what_it_cannot_draw_clearly(args, match):
    with pytest.raises(ValueError, match=match):
        fc.plot_trisurf(*args, size=(40, 30))


def test_trisurf_where_mplot3d_draws_it():
    """matplotlib's trisurf3d example (points on circles, sin(-xy)) with
    fc.plot_trisurf: the surface covers where mplot3d draws the same triangles, both
    flat red (intersection over union; measured 2026-12-06: 0.962 perspective, 0.959
    orthographic, the rest along the antialiased rim); its edges (edgecolor) are
    mplot3d's own lines, depth-tested, and go with plot.remove()."""
    radii = np.linspace(0.125, 1.0, 8)
    angles = np.linspace(0, 2 * np.pi, 36, endpoint=False)[:, None]
    x = np.append(0, (radii * np.cos(angles)).ravel())
    y = np.append(0, (radii * np.sin(angles)).ravel())
    z = np.sin(-x * y)

    for proj in ("persp", "ortho"):
        iou, theirs = red_overlap(
            lambda ax: fc.plot_trisurf(x, y, z, ax=ax, color="red", lower_color="red",
                                       shade=False),
            lambda ax: ax.plot_trisurf(x, y, z, color="red", shade=False, linewidth=0,
                                       antialiased=False),
            lambda ax: ax.set(xlim=(-1.05, 1.05), ylim=(-1.05, 1.05), zlim=(-0.5, 0.5)), proj)
        assert theirs > 20000 and iou > 0.95
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    p = fc.plot_trisurf(x, y, z, ax=ax, edgecolor="k", linewidth=0.3)
    (lines,) = [c for c in ax.collections if c in p._placed]
    from matplotlib.tri import Triangulation
    assert len(lines._segments3d) == len(Triangulation(x, y).edges)   # each edge once
    fig.canvas.draw()
    p.remove()
    assert lines.axes is None
    plt.close(fig)
    with pytest.warns(RuntimeWarning, match="3-D Axes only"):
        fc.plot_trisurf(x, y, z, edgecolor="k", size=(40, 30))

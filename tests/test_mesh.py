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
from reference import inner  # noqa: E402
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


def _bilinear_at(Z, u, v):
    """Z (rows along v, columns along u, at their indices) bilinear at (u, v)."""
    i = np.clip(np.floor(v).astype(int), 0, Z.shape[0] - 2)
    j = np.clip(np.floor(u).astype(int), 0, Z.shape[1] - 2)
    fy, fx = v - i, u - j
    return ((Z[i, j] * (1 - fx) + Z[i, j + 1] * fx) * (1 - fy) +
            (Z[i + 1, j] * (1 - fx) + Z[i + 1, j + 1] * fx) * fy)


def test_an_array_alone_is_heights_over_its_indices():
    """plot_surface(Z) and render(Z) (MATLAB's surf(Z), plotly's Surface(z=Z)): Z's
    heights over its columns' (u) and rows' (v) indices, bilinear between them (they
    raised "cannot draw ndarray", the whole array in the message): the surface is Z's
    bilinear interpolation (to 1e-9 at random points), and each seen pixel's height
    that at its (u, v) within 0.02 of heights spanning 12 (the pixels' values are
    interpolated between the column's samples: measured 2026-12-06, at most 0.0083),
    for a numpy array, a list of lists and a masked array (its masked values holes)."""
    rng = np.random.default_rng(4)
    Z = np.cumsum(rng.normal(size=(9, 14)), axis=1)
    masked = np.ma.masked_where(np.add.outer(np.arange(9), np.arange(14)) < 4, Z)
    pu, pv = rng.uniform(0, 13, 500), rng.uniform(0, 8, 500)
    for arg in (Z, Z.tolist(), masked):
        p = fc.plot_surface(arg, size=(120, 90))
        assert p.domain == ((0, 13), (0, 8))
        far = np.floor(pu) + np.floor(pv) >= 4      # (cells with no masked corner)
        got = p.surface.evaluate(pu[far], pv[far])
        assert np.abs(got - _bilinear_at(Z, pu[far], pv[far])).max() < 1e-9
        for r in (p.draw(), fc.render(arg, size=(120, 90), elev=40, azim=20)):
            seen = r.side != 0
            assert seen.sum() > 2000
            u, v, w = r.u[seen], r.v[seen], r.w[seen]
            assert u.min() > -1e-6 and u.max() < 13 + 1e-6 and v.max() < 8 + 1e-6
            assert np.abs(w - _bilinear_at(Z, u, v)).max() < 0.02
            if arg is masked:
                assert (u + v > 3.9).all()         # the masked corner's cells: a hole
    with pytest.raises(ValueError, match=r"cannot draw an array of shape \(5,\)") as e:
        fc.plot_surface(np.zeros(5))
    assert len(str(e.value)) < 200
    with pytest.raises(ValueError, match="cannot draw an array of shape"):
        fc.render(np.zeros((3, 3, 3)))


def test_a_labelled_array_alone_takes_its_coordinates():
    """plot_surface(df) and plot_surface(da): a pandas DataFrame over its columns (x)
    and index (y), an xarray DataArray over its coordinates (x its second dimension's,
    as da.plot.surface) -- stand-ins with their attributes, neither is installed here:
    a bilinear function's heights on the labels' grid come out as that function at
    any point of those coordinates (to 1e-9: the resampling of an uneven grid keeps a
    bilinear function); labels that are not numbers leave the indices."""
    x, y = np.geomspace(1, 50, 8), np.linspace(-3, 3, 6)
    X, Y = np.meshgrid(x, y)

    def f(u, v):
        return 0.5 + 0.1 * u - 0.7 * v + 0.02 * u * v
    Z = f(X, Y)

    class Frame:
        def __init__(self, z, columns, index):
            self.z, self.columns, self.index = z, columns, index

        def __array__(self, dtype=None, copy=None):
            return self.z if dtype is None else self.z.astype(dtype)

    class DataArray(Frame):
        def __init__(self, z, coords):
            self.z, self.dims, self.coords = z, ("lat", "lon"), coords
    want_u = np.array([1.0, 7.5, 50.0, 20.0])
    want_v = np.array([-3.0, 0.3, 3.0, -1.2])
    want = f(want_u, want_v)
    for labelled in (Frame(Z, x, y), DataArray(Z, {"lon": x, "lat": y})):
        p = fc.plot_surface(labelled, size=(60, 40))
        assert p.domain == ((1.0, 50.0), (-3.0, 3.0))
        assert np.abs(p.surface.evaluate(want_u, want_v) - want).max() < 1e-9
    p = fc.plot_surface(Frame(Z, np.array(list("abcdefgh")), y), size=(60, 40))
    assert p.domain == ((0, 7), (0, 5))


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


def _pixels_off(q, levels, seen):
    """Each seen pixel's distance in pixels to the nearest line q = level, from q's
    screen gradient (the smaller one-sided difference each way, as the overlay's)."""
    qs = np.where(seen, q, np.nan)
    p = np.pad(qs, 1, constant_values=np.nan)
    c = p[1:-1, 1:-1]
    with np.errstate(invalid="ignore"):
        gy = np.fmin(np.abs(p[:-2, 1:-1] - c), np.abs(p[2:, 1:-1] - c))
        gx = np.fmin(np.abs(p[1:-1, :-2] - c), np.abs(p[1:-1, 2:] - c))
        near = np.min(np.abs(qs[..., None] - np.asarray(levels)[None, None, :]), axis=2)
        return near / np.hypot(gx, gy)


def _line_pixels(X, Y, Z, coords, levels, size=(320, 240), **kw):
    """(off, drawn, seen): a mesh's edges (red, 1 pixel wide) against its picture
    without them: each seen pixel's distance in pixels to the nearest of the mesh's
    lines (``coords(u, v)`` the two coordinates whose ``levels`` they are, from each
    pixel's seen point), and whether the edges changed it."""
    plain = fc.plot_surface(X, Y, Z, size=size, cmap="gray", **kw).draw()
    lined = fc.plot_surface(X, Y, Z, size=size, cmap="gray", edgecolor="red",
                            linewidth=72 / 100, **kw).draw()
    assert np.array_equal(plain.side, lined.side)
    seen = inner(plain.side != 0)
    drawn = np.abs(lined.rgba.astype(int) - plain.rgba).sum(axis=2) > 0
    a, b = coords(plain.u, plain.v)
    off = np.fmin(_pixels_off(a, levels[0], seen), _pixels_off(b, levels[1], seen))
    return off, drawn, seen


def test_an_uneven_meshs_edges_are_its_own_lines():
    """plot_surface(X, Y, Z, edgecolor=) of an unevenly spaced mesh (np.geomspace's)
    draws mplot3d's lines, its rows and columns 0, s, 2 s, ... and the last (they were
    left out with a warning): of the seen pixels a third of a pixel from one (at the
    seen point's (u, v), in pixels of its screen gradient) 99 % are drawn, and 99 % of
    the drawn pixels lie within 1.5 pixels of one (measured 2026-12-06: 99.77 % of 871
    and 99.85 %; a 1-pixel line covers pixels up to 1 away)."""
    x, y = np.geomspace(0.1, 10, 30), np.linspace(-2, 2, 25)
    X, Y = np.meshgrid(x, y)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        off, drawn, seen = _line_pixels(X, Y, np.log(X) * np.cos(Y), lambda u, v: (u, v),
                                        (x[[0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 29]],
                                         y[[0, 3, 6, 9, 12, 15, 18, 21, 24]]),
                                        rstride=3, cstride=3)
    on = seen & (off < 0.33)
    assert on.sum() > 800 and drawn[on].mean() >= 0.99
    assert (off[seen & drawn] <= 1.5).mean() >= 0.99


def test_a_curvilinear_meshs_edges_follow_its_index():
    """A polar grid's edges (mplot3d's rcount=ccount=15 of its 40 angles and 30 radii)
    are its own circles and rays, drawn as the levels of the mesh's index (a chord
    between two nodes, as the surface is linear on the quads' triangles): of the seen
    pixels 0.3 px from one (the chords' and rays' exact index at the seen point; the
    chords lie up to 1.5 px inside the circles here) 99 % are drawn, and 99 % of the
    drawn pixels lie within 2 px of one (measured 2026-12-06: 99.84 % of 1901 and
    99.98 %), away from the centre where the rays meet. The mesh's outer edge is drawn
    along the surface's edge, which ends up to two grid cells inside it: of the edge's
    pixels 1.5 indices from it, more than half (measured 92.7 % of 245)."""
    n_r, n_p = 30, 40
    X, Y = _polar(n_r, n_p)
    Z = (X ** 2 + Y ** 2 - 1) ** 2

    def index(u, v):
        # the mesh's circles are chords between its nodes: a point's radius along the
        # chords' direction in its sector (the rays through the nodes are exact)
        step = 2 * np.pi / (n_p - 1)
        a = np.arctan2(v, u) % (2 * np.pi)
        mid = (np.floor(a / step) + 0.5) * step
        rho = np.hypot(u, v) * np.cos(a - mid) / np.cos(step / 2)
        return rho / 1.25 * (n_r - 1), a / step
    rows = np.array(list(range(0, n_p - 1, 3)) + [n_p - 1])       # ceil(40 / 15) = 3
    cols = np.array(list(range(0, n_r - 1, 2)) + [n_r - 1])       # ceil(30 / 15) = 2
    off, drawn, seen = _line_pixels(X, Y, Z, index, (cols, rows), size=(400, 300), rcount=15,
                                    ccount=15)
    plain = fc.plot_surface(X, Y, Z, size=(400, 300)).draw()
    away = seen & (np.hypot(plain.u, plain.v) > 0.3)
    on = away & (off < 0.3)
    assert on.sum() > 1000 and drawn[on].mean() >= 0.99
    assert (off[away & drawn] <= 2.0).mean() >= 0.99
    # the outer edge: the pixels on the surface's edge (a neighbour not seen) near it
    on_surface = plain.side != 0
    rim = on_surface & ~inner(on_surface) & (index(plain.u, plain.v)[0] > n_r - 1.5)
    assert rim.sum() > 100 and drawn[rim].mean() > 0.5


def test_plot_wireframe_of_a_resampled_mesh_draws_its_lines():
    """fc.plot_wireframe of a mesh that is resampled draws the mesh's own lines alone
    (it raised "not drawn" before): lines of an uneven grid at its own positions, 99 %
    of the dark pixels within 1.5 px of one (measured 2026-12-06: 99.63 % of 1709)."""
    x, y = np.geomspace(0.1, 10, 20), np.linspace(-2, 2, 15)
    X, Y = np.meshgrid(x, y)
    p = fc.plot_wireframe(X, Y, np.log(X) * np.cos(Y), rstride=4, cstride=4, size=(240, 180),
                          color="black")
    r = p.draw()
    dark = r.rgba[..., :3].max(axis=2) < 128
    seen = inner(r.side != 0)
    off = np.fmin(_pixels_off(r.u, x[[0, 4, 8, 12, 16, 19]], seen),
                  _pixels_off(r.v, y[[0, 4, 8, 12, 14]], seen))
    assert dark.sum() > 300 and (off[seen & dark] <= 1.5).mean() >= 0.99
    assert (r.rgba[seen & (off > 3)][:, :3] == 255).all()          # no surface drawn


@pytest.mark.parametrize("grid", ["uneven", "polar"])
def test_a_translucent_resampled_meshs_edges_are_its_own_lines(grid):
    """With alpha < 1 (the translucent layers' kernel, every layer's lines at its
    alpha) the same lines: an uneven mesh's at their positions, a polar one's as levels
    of its index (they were left out with a warning). A surface that does not lie over
    itself, seen from above, so that each pixel shows one layer: of the seen pixels a
    third of a pixel from a line 99 % drawn, 99 % of the drawn ones within 2 px of one
    (measured 2026-12-06: uneven 100 % of 1 364 and 99.90 %; polar 100 % of 2 594 and
    99.95 %)."""
    if grid == "uneven":
        x, y = np.geomspace(0.1, 10, 30), np.linspace(-2, 2, 25)
        X, Y = np.meshgrid(x, y)
        Z = 0.3 * np.log(X) + 0.2 * Y
        rows, cols = np.arange(0, 25, 3), np.array(list(range(0, 29, 3)) + [29])

        def coords(u, v):
            return u, v
        levels = (x[cols], y[rows])
    else:
        X, Y = _polar(30, 40)
        Z = 0.2 * (X ** 2 + Y ** 2)
        step = 2 * np.pi / 39

        def coords(u, v):          # (test_a_curvilinear_meshs_edges_follow_its_index's)
            a = np.arctan2(v, u) % (2 * np.pi)
            mid = (np.floor(a / step) + 0.5) * step
            return np.hypot(u, v) * np.cos(a - mid) / np.cos(step / 2) / 1.25 * 29, a / step
        levels = (np.array(list(range(0, 29, 2)) + [29]),
                  np.array(list(range(0, 39, 3)) + [39]))
    off, drawn, seen = _line_pixels(X, Y, Z, coords, levels, size=(320, 240), alpha=0.5,
                                    elev=60, rstride=3, cstride=3) if grid == "uneven" else \
        _line_pixels(X, Y, Z, coords, levels, size=(320, 240), alpha=0.5, elev=60,
                     rcount=15, ccount=15)
    if grid == "polar":
        plain = fc.plot_surface(X, Y, Z, size=(320, 240), elev=60).draw()
        seen &= np.hypot(plain.u, plain.v) > 0.3          # (away from where rays meet)
    on = seen & (off < 0.33)
    assert on.sum() > 800 and drawn[on].mean() >= 0.99
    assert (off[seen & drawn] <= 2.0).mean() >= 0.99


@pytest.mark.parametrize("kw, match", [
    (dict(wireframe=([0.0, np.nan], [1.0])), "wireframe's first positions"),
    (dict(wireframe=([0.0], [])), "wireframe's second positions"),
    (dict(wireframe=([0.0], [0.0]), wire_coords=(np.zeros((4, 4)), (0, 1, 0, 1))),
     "wire_coords must be"),
    (dict(wireframe=4, wire_coords=(np.zeros((4, 4, 2)), (0, 1, 0, 1))),
     "wire_coords needs wireframe"),
])
def test_wireframe_positions_are_checked(kw, match):
    with pytest.raises(ValueError, match=match):
        fc.render("u*v", size=(40, 30), **kw)


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
    # Z with a row per x (the transposed layout): the message says Z.T
    with pytest.raises(ValueError, match=r"x has 3 and y 2 values for Z of shape \(3, 2\) "
                                         r"\(Z.T has a row for each y"):
        fc.plot_surface(np.arange(3.0), np.arange(2.0), np.ones((3, 2)))
    with pytest.raises(ValueError, match=r"of shape \(4, 2\)$"):
        fc.plot_surface(np.arange(3.0), np.arange(2.0), np.ones((4, 2)))


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

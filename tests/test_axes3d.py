"""floatcol inside matplotlib's own 3-D Axes (issue 30): matplotlib's call form, the
Axes' camera, everything mplot3d draws kept, and the surface exactly where mplot3d
draws the same mesh.

Measured intersection over union of the surface's region against mplot3d's own
drawing of the same data in the same Axes (both flat red, 640x480), 2026-12-03:
surface3d (sin r, perspective) 0.975, orthographic 0.974, elev 60 / azim 20 with
limits cut to x in [-3, 6] 0.983 (the bounds below leave a margin; the goal is 0.9).
The rest lies along the edges: mplot3d's polygons are drawn without antialiasing
and floatcol's silhouettes with it, and the red test takes only near-pure red.
"""
import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib import cm  # noqa: E402
from matplotlib.ticker import LinearLocator  # noqa: E402

import floatcol as fc  # noqa: E402
from conftest import red_overlap  # noqa: E402


def _data():
    X = np.arange(-5, 5, 0.25)
    Y = np.arange(-5, 5, 0.25)
    X, Y = np.meshgrid(X, Y)
    return X, Y, np.sin(np.sqrt(X ** 2 + Y ** 2))


def _red(fig):
    fig.canvas.draw()
    a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    return (a[..., 0] > 200) & (a[..., 1] < 60) & (a[..., 2] < 60)


def _figure(draw, proj="persp", view=(30, -60), limits=None, inverted=""):
    fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
    ax = fig.add_subplot(projection="3d", proj_type=proj)
    draw(ax)
    ax.set_zlim(-1.01, 1.01)
    if limits:
        ax.set_xlim(*limits)
    for name in inverted:                       # "x", "y", "z": ax.invert_xaxis(), ...
        getattr(ax, f"invert_{name}axis")()
    ax.view_init(*view)
    mask = _red(fig)
    plt.close(fig)
    return mask


def _against_mplot3d(*camera):
    """(intersection over union of floatcol's surface and mplot3d's own mesh of the
    same data in the same Axes, both flat red; mplot3d's red pixels)."""
    X, Y, Z = _data()
    ours = _figure(lambda ax: fc.plot_surface(X, Y, Z, ax=ax, color="red", lower_color="red",
                                              shade=False, linewidth=0, antialiased=False),
                   *camera)
    theirs = _figure(lambda ax: ax.plot_surface(X, Y, Z, color="red", shade=False,
                                                linewidth=0, antialiased=False),
                     *camera)
    return (ours & theirs).sum() / (ours | theirs).sum(), theirs.sum()


@pytest.mark.parametrize("proj,view,limits,bound", [
    ("persp", (30, -60), None, 0.95),
    ("ortho", (30, -60), None, 0.95),
    ("persp", (60, 20), (-3, 6), 0.96),
])
def test_surface_where_mplot3d_draws_the_mesh(proj, view, limits, bound):
    iou, theirs = _against_mplot3d(proj, view, limits)
    assert theirs > 20000
    assert iou >= bound


@pytest.mark.parametrize("proj,view,inverted", [
    ("persp", (30, -60), "x"),
    ("ortho", (30, -60), "z"),
    ("persp", (60, 20), "y"),
    ("persp", (25, 35), "xz"),
    ("ortho", (40, 120), "xyz"),
])
def test_inverted_axes_show_the_surface_where_mplot3d_does(proj, view, inverted):
    """An inverted axis (ax.invert_zaxis(), limits high to low) shows the data mirrored
    in it: floatcol's draw raised "box's stretch factors must be positive numbers" (the
    figure could not be drawn; found by fuzzing the Axes). The mirrored eye sees the
    surface as the Axes' eye sees the mirrored data, up to a turn and, for an odd
    number of inverted axes, a reflection of the picture. Intersection over union
    against mplot3d's own mesh, measured 0.975-0.979 (the bound as the test above's);
    the x limits not symmetric, so that a mirror shows."""
    iou, theirs = _against_mplot3d(proj, view, (-3, 6), inverted)
    assert theirs > 20000
    assert iou >= 0.95


def test_surface3d_example_keeps_axes_and_colorbar(tmp_path):
    """matplotlib's surface3d example with only its plot_surface call changed."""
    X, Y, Z = _data()
    fig, ax = plt.subplots(subplot_kw={"projection": "3d"})
    surf = fc.plot_surface(X, Y, Z, ax=ax, cmap=cm.coolwarm, linewidth=0, antialiased=False)
    ax.set_zlim(-1.01, 1.01)
    ax.zaxis.set_major_locator(LinearLocator(10))
    ax.zaxis.set_major_formatter('{x:.02f}')
    cb = fig.colorbar(surf, shrink=0.5, aspect=5)
    ax.set_xlabel("x")
    fig.savefig(tmp_path / "s.png")
    assert ax._axis3don and ax.get_zlim() == (-1.01, 1.01)
    labels = [t.get_text() for t in ax.zaxis.get_ticklabels()]
    assert len(labels) == 10 and labels[0].replace("\u2212", "-") == "-1.01"
    assert ax.xaxis.get_label().get_text() == "x"
    # the tick labels are drawn: dark pixels left of the panes where mplot3d puts them
    rend = fig.canvas.get_renderer()
    for t in ax.xaxis.get_ticklabels():
        if t.get_text():
            assert t.get_window_extent(rend).width > 0
    assert cb.mappable is surf
    # the surface is drawn: colormap colours inside the Axes
    a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    assert ((a[..., 0] > 150) & (a[..., 2] < 120)).sum() > 2000     # the red top
    plt.close(fig)


def test_mesh_call_forms():
    X, Y, Z = _data()
    x, y = X[0], Y[:, 0]
    hf = fc.plot.mesh_surface(X, Y, Z)
    assert hf.default_domain == ((-5.0, 4.75), (-5.0, 4.75))
    # 1-D x and y; a meshgrid with indexing="ij"; a north-up raster (y descending)
    for args in ((x, y, Z), (X.T, Y.T, Z.T), (X[::-1], Y[::-1], Z[::-1])):
        other = fc.plot.mesh_surface(*args)
        assert other.default_domain == hf.default_domain
        np.testing.assert_array_equal(other.hf, hf.hf)
    # uneven x is resampled (tests/test_mesh.py); x that turns back is refused
    assert fc.plot.mesh_surface(x ** 3, y, Z).resampled
    with pytest.raises(ValueError, match="ascending or descending"):
        fc.plot.mesh_surface(x ** 2, y, Z)
    with pytest.raises(ValueError, match="Z must be 2-D"):
        fc.plot.mesh_surface(x, y, Z[0])
    # ... and so says plot_surface (it named a range: "(symbol, low, high)")
    for bad in (Z[0], Z[None]):
        with pytest.raises(ValueError, match="Z must be 2-D"):
            fc.plot_surface(x, y, bad)
    # one row of values: no surface between them (it said "Y must be evenly spaced")
    with pytest.raises(ValueError, match="at least 2 x 2"):
        fc.plot.mesh_surface(X[:1], Y[:1], Z[:1])


def test_matplotlib_keywords_accepted():
    X, Y, Z = _data()
    p = fc.plot_surface(X, Y, Z, rstride=1, cstride=1, rcount=50, ccount=50, linewidth=0,
                        edgecolor="none", antialiased=False, zorder=3, size=(80, 60))
    assert p.draw().rgba.shape == (60, 80, 4)
    assert "wireframe" not in p.options              # no edge colour: no mesh lines
    # facecolors are drawn (a texture; tests/test_texture.py checks where), no warning
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        q = fc.plot_surface(X, Y, Z, facecolors=cm.viridis(Z), size=(40, 30))
    tex = q.options["texture"]                       # whole texels a face (mesh.py)
    assert tex.shape[2] == 4 and tex.shape[0] % (Z.shape[0] - 1) == 0 and \
        tex.shape[1] % (Z.shape[1] - 1) == 0


def _blue(fig):
    fig.canvas.draw()
    a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    return (a[..., 2] > 150) & (a[..., 0] < 100) & (a[..., 2] - a[..., 0] > 80)


def test_plot_wireframe_draws_mplot3ds_lines_less_the_hidden_ones():
    """fc.plot_wireframe(X, Y, Z, ax=ax, rstride=10, cstride=10): the mesh's lines as
    mplot3d draws them, less those the surface hides (a hidden-line drawing: mplot3d
    draws them all). Against ax.plot_wireframe of the same data in the same Axes:
    measured 99.7 % of floatcol's line pixels within 2 pixels of mplot3d's, and 89.5 %
    of mplot3d's within 2 pixels of floatcol's (the rest are the hidden lines, away
    from any seen one); the Axes' panes show between the lines."""
    from mpl_toolkits.mplot3d import axes3d
    X, Y, Z = axes3d.get_test_data(0.05)

    def lines(draw):
        fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
        ax = fig.add_subplot(projection="3d")
        draw(ax)
        ax.view_init(15, -60)
        mask = _blue(fig)
        plt.close(fig)
        return mask

    ours = lines(lambda ax: fc.plot_wireframe(X, Y, Z, ax=ax, rstride=10, cstride=10))
    theirs = lines(lambda ax: ax.plot_wireframe(X, Y, Z, rstride=10, cstride=10))

    from floatcol.objects import _dilate

    def near(mask):                         # (within 2 pixels: 5 x 5)
        return _dilate(_dilate(mask))
    assert ours.sum() > 3000
    assert (ours & near(theirs)).sum() >= 0.95 * ours.sum()
    assert (theirs & near(ours)).sum() <= 0.95 * theirs.sum()        # (hidden ones gone)
    with pytest.raises(ValueError, match="takes no edgecolor"):
        fc.plot_wireframe(X, Y, Z, edgecolor="k")


def _clipped_figure(draw, proj, view, xlim, zlim):
    fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
    ax = fig.add_subplot(projection="3d", proj_type=proj)
    draw(ax)
    ax.set_zlim(*zlim)
    ax.set_xlim(*xlim)
    ax.view_init(*view)
    mask = _red(fig)
    plt.close(fig)
    return mask


@pytest.mark.parametrize("proj,view,xlim,zlim", [
    ("persp", (30, -60), (-3, 4), (-0.5, 0.6)),
    ("ortho", (50, 20), (-4, 2), (-1.01, 0.3)),
])
def test_axlim_clip_hides_what_lies_outside_the_limits(proj, view, xlim, zlim):
    """axlim_clip=True (matplotlib 3.10's keyword; it was an "unknown option"): what lies
    outside the Axes' view limits is not drawn. A mesh's points outside are holes, so
    the cells around them are, as mplot3d hides its patches with a vertex outside
    (where one vertex of four is outside, mplot3d still draws the triangle of the
    other three: floatcol does not). An expression is cut exactly where it leaves the
    limits: against mplot3d's own clip of a 401 x 401 mesh of it. Measured: all of
    floatcol's mesh pixels are mplot3d's too, which has 10 and 7 % more (the
    triangles); 43 and 39 % of the unclipped picture's are left; the expression's
    intersection over union 0.988 and 0.969 (unclipped: 0.988 and 0.988)."""
    X, Y, Z = _data()
    style = dict(color="red", shade=False, linewidth=0, antialiased=False, axlim_clip=True)
    ours = _clipped_figure(lambda ax: fc.plot_surface(X, Y, Z, ax=ax, lower_color="red",
                                                      **style), proj, view, xlim, zlim)
    theirs = _clipped_figure(lambda ax: ax.plot_surface(X, Y, Z, **style), proj, view, xlim,
                             zlim)
    whole = _clipped_figure(lambda ax: fc.plot_surface(X, Y, Z, ax=ax, lower_color="red",
                                                       **dict(style, axlim_clip=False)),
                            proj, view, xlim, zlim)
    both = (ours & theirs).sum()
    assert ours.sum() < 0.6 * whole.sum()                # (it clips)
    assert both >= 0.995 * ours.sum()
    assert both >= 0.85 * theirs.sum()
    Xf, Yf = np.meshgrid(np.linspace(-5, 5, 401), np.linspace(-5, 5, 401))
    fine = _clipped_figure(lambda ax: ax.plot_surface(Xf, Yf, np.sin(np.hypot(Xf, Yf)),
                                                      rcount=400, ccount=400, **style),
                           proj, view, xlim, zlim)
    exact = _clipped_figure(lambda ax: fc.plot_surface(
        "sin(sqrt(x**2 + y**2))", ("x", -5, 5), ("y", -5, 5), ax=ax, lower_color="red",
        antialias=False, **{k: x for k, x in style.items() if k not in ("linewidth",
                                                                       "antialiased")}),
        proj, view, xlim, zlim)
    iou = (exact & fine).sum() / (exact | fine).sum()
    assert iou >= 0.96


def test_axlim_clip_says_what_it_takes():
    X, Y, Z = _data()
    with pytest.raises(ValueError, match="axlim_clip must be True or False"):
        fc.plot_surface(X, Y, Z, axlim_clip="yes")
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    fc.plot_surface(lambda x, y: x * y, ("x", -1, 1), ("y", -1, 1), ax=ax, axlim_clip=True)
    with pytest.raises(ValueError, match="axlim_clip=True clips a mesh"):
        fig.canvas.draw()
    plt.close(fig)
    # off, or with no Axes to take limits from, it changes nothing
    p = fc.plot_surface(X, Y, Z, size=(60, 45), axlim_clip=True)
    q = fc.plot_surface(X, Y, Z, size=(60, 45))
    assert np.array_equal(p.draw().rgba, q.draw().rgba)


def test_a_translucent_mesh_with_its_edges():
    """matplotlib's gallery idiom, plot_surface(X, Y, Z, edgecolor=..., lw=0.5,
    rstride=8, cstride=8, alpha=0.3) (its "projecting contour profiles" example): the
    mesh's lines on the translucent surface, every layer's (it was a ValueError:
    lines needed opacity=1). The lines change the picture where they run, bluer there
    (measured: 10.9 % of the pixels, all bluer; tests/test_translucency.py checks the
    lines against the opaque ones)."""
    from mpl_toolkits.mplot3d import axes3d
    X, Y, Z = axes3d.get_test_data(0.05)
    kw = dict(lw=0.5, rstride=8, cstride=8, alpha=0.3, size=(320, 240))
    lined = fc.plot_surface(X, Y, Z, edgecolor="royalblue", **kw)
    plain = fc.plot_surface(X, Y, Z, **kw)
    assert lined.options["wireframe"] == (16, 16) and lined.options["opacity"] == 0.3
    a, b = (p.draw().rgba[..., :3].astype(float) for p in (lined, plain))
    drawn = np.abs(a - b).sum(axis=-1) > 6
    assert 0.03 < drawn.mean() < 0.3
    assert (a[..., 2] - a[..., 0] >= b[..., 2] - b[..., 0])[drawn].mean() > 0.9   # bluer
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    fc.plot_surface(X, Y, Z, ax=ax, edgecolor="royalblue", lw=0.5, rstride=8, cstride=8,
                    alpha=0.3)
    fig.canvas.draw()
    plt.close(fig)


@pytest.mark.parametrize("proj", ["persp", "ortho"])
def test_roll_turns_the_picture_with_the_axes(proj):
    """view_init(elev, azim, roll): the picture is rendered without the roll and turned
    onto the Axes (bilinear). Measured IoU against mplot3d's mesh, roll 25: 0.970 persp,
    0.968 ortho."""
    X, Y, Z = _data()

    def fig_of(draw):
        fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
        ax = fig.add_subplot(projection="3d", proj_type=proj)
        draw(ax)
        ax.set_zlim(-1.01, 1.01)
        ax.view_init(30, -60, 25)
        mask = _red(fig)
        plt.close(fig)
        return mask
    ours = fig_of(lambda ax: fc.plot_surface(X, Y, Z, ax=ax, color="red", lower_color="red",
                                             shade=False))
    theirs = fig_of(lambda ax: ax.plot_surface(X, Y, Z, color="red", shade=False, linewidth=0,
                                               antialiased=False))
    assert (ours & theirs).sum() / (ours | theirs).sum() >= 0.93


@pytest.mark.parametrize("fmt", ["png", "pdf", "svg"])
def test_export(tmp_path, fmt):
    X, Y, Z = _data()
    fig = plt.figure(figsize=(3, 2.4))
    ax = fig.add_subplot(projection="3d")
    fc.plot_surface(X, Y, Z, ax=ax, cmap="viridis")
    out = tmp_path / f"f.{fmt}"
    fig.savefig(out)
    assert out.stat().st_size > 1000
    plt.close(fig)


def _hidden_by_rays(f, pts, eye_dir=None, eye=None, dom=(-3, 3), steps=4000):
    """Independently of the render: whether the segment from each point toward the
    viewer (a direction, orthographic; or the eye, perspective) crosses w = f(x, y)
    inside the domain. Returns a bool array (True: hidden)."""
    hidden = np.zeros(len(pts), bool)
    for k, p in enumerate(pts):
        if eye is not None:
            d = np.asarray(eye) - p
        else:
            d = np.asarray(eye_dir) * 100.0
        t = np.linspace(1e-4, 1.0, steps)[:, None]
        q = p + t * d
        inside = ((q[:, 0] >= dom[0]) & (q[:, 0] <= dom[1]) & (q[:, 1] >= dom[0])
                  & (q[:, 1] <= dom[1]))
        g = q[:, 2] - f(q[:, 0], q[:, 1])
        g0 = p[2] - f(p[0], p[1])
        hidden[k] = bool(np.any(inside & (np.sign(g) != np.sign(g0))))
    return hidden


def _hill_with_points(proj, own):
    """A hill and 400 random points away from it (|z - f| > 0.05), as a scatter of
    mplot3d's own (``own``) or the SurfacePlot's; (fig, ax, plot, points, scatter,
    hidden by rays cast from each point toward the eye)."""
    def f(x, y):
        return 2 * np.exp(-(x ** 2 + y ** 2) / 2)
    fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
    ax = fig.add_subplot(projection="3d", proj_type=proj)
    p = fc.plot_surface("2*exp(-(x**2+y**2)/2)", ("x", -3, 3), ("y", -3, 3), ax=ax,
                        cmap="Blues")
    rng = np.random.default_rng(7)
    pts = rng.uniform([-3, -3, 0], [3, 3, 2.2], (600, 3))
    pts = pts[np.abs(pts[:, 2] - f(pts[:, 0], pts[:, 1])) > 0.05][:400]
    add = ax.scatter if own else p.scatter
    sc = add(pts[:, 0], pts[:, 1], pts[:, 2], color="red", s=10)
    fig.canvas.draw()
    # the eye in data coordinates: mplot3d's, undone by the box's stretch
    box = np.asarray(p.render.box)
    e, a = np.radians(ax.elev), np.radians(ax.azim)
    ps = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    lims = np.array([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()])
    centre = lims.mean(axis=1)
    if proj == "ortho":
        hidden = _hidden_by_rays(f, pts, eye_dir=ps / box)
    else:
        hidden = _hidden_by_rays(f, pts, eye=centre + ax._dist * ax._focal_length * ps / box)
    return fig, ax, p, pts, sc, hidden


@pytest.mark.parametrize("proj", ["ortho", "persp"])
def test_points_behind_a_hill_are_hidden(proj):
    """A point is drawn where it lies in front of the surface, hidden where the surface
    lies between it and the eye: against rays cast from each point toward the eye.
    Measured agreement 2026-12-03: 99.75 % ortho, 100 % persp on 400 points away
    from the surface (|z - f| > 0.05)."""
    fig, ax, p, pts, sc, hidden = _hill_with_points(proj, own=False)
    plt.close(fig)
    assert 0.1 < hidden.mean() < 0.9
    assert (sc.visible == ~hidden).mean() >= 0.98


def _canvas_pixels(ax, pts):
    """(rows, columns) of the canvas pixels where mplot3d puts the points (n, 3)."""
    from mpl_toolkits.mplot3d import proj3d
    xs, ys, _ = proj3d.proj_transform(pts[:, 0], pts[:, 1], pts[:, 2], ax.M)
    d = ax.transData.transform(np.column_stack([xs, ys]))
    H = ax.figure.canvas.get_width_height()[1]
    return np.round(H - d[:, 1] - 0.5).astype(int), np.round(d[:, 0] - 0.5).astype(int)


@pytest.mark.parametrize("proj", ["ortho", "persp"])
def test_mplot3ds_own_scatter_is_depth_tested_too(proj):
    """``ax.scatter`` of mplot3d's own, in an Axes with a floatcol surface, is drawn
    where each point lies in front of the surface: against rays cast from each point
    toward the eye, and in the picture (red where a lone point is drawn, none where it
    is hidden; the surface is blue). Measured 2026-12-06: 99.75 % (ortho) and 100 %
    (persp) of the points agree with the rays, as SurfacePlot.scatter's; in the
    picture every lone point's pixel agrees."""
    fig, ax, p, pts, sc, hidden = _hill_with_points(proj, own=True)
    a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    rows, cols = _canvas_pixels(ax, pts)
    plt.close(fig)
    assert 0.1 < hidden.mean() < 0.9
    assert (sc.draw.visible == ~hidden).mean() >= 0.98
    # points with no other point within 8 pixels on the canvas: the picture itself
    gap = np.hypot(rows[:, None] - rows[None], cols[:, None] - cols[None])
    np.fill_diagonal(gap, np.inf)
    lone = gap.min(axis=1) > 8
    red = (a[rows, cols, 0] > 150) & (a[rows, cols, 0] - np.maximum(a[rows, cols, 1],
                                                                     a[rows, cols, 2]) > 60)
    assert lone.sum() > 40 and (hidden[lone]).sum() > 5
    assert (red[lone] == ~hidden[lone]).mean() >= 0.97


def test_mplot3ds_own_line_text_and_quiver_are_depth_tested_too():
    """mplot3d's own ``ax.plot`` (a line through the hill: its middle hidden, its
    markers only where seen), ``ax.text`` and ``ax.quiver`` (an arrow up through the
    hill's top: its lower part hidden), as the SurfacePlot's."""
    fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
    ax = fig.add_subplot(projection="3d")
    fc.plot_surface("2*exp(-(x**2+y**2)/2)", ("x", -3, 3), ("y", -3, 3), ax=ax, cmap="Blues")
    t = np.linspace(0, 1, 50)
    ln, = ax.plot(-3 + 6 * t, 0 * t, 0.8 + 0 * t, "r-o", markevery=7)
    front = ax.text(0, -2.5, 0.5, "in front")
    behind = ax.text(0, 2.5, 0.3, "behind")          # the hill lies between it and the eye
    q = ax.quiver([0.0], [0.0], [1.0], [0.0], [0.0], [1.0], length=2.0, color="red",
                  arrow_length_ratio=0.1)
    ax.set_zlim(0, 3.5)
    ax.view_init(20, -90)                            # looking along +y, low
    fig.canvas.draw()
    a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    pts = np.column_stack([-3 + 6 * t, 0 * t, 0.8 + 0 * t])
    rows, cols = _canvas_pixels(ax, pts)
    shaft = np.column_stack([0 * t, 0 * t, 1 + 2 * t])
    s_rows, s_cols = _canvas_pixels(ax, shaft)
    plt.close(fig)
    v = ln.draw.visible
    assert v[:5].all() and v[-5:].all() and not v.all()
    # in the picture: red at the line's ends, none where the hill (|x| < 1.52) hides it
    red = (a[..., 0] > 150) & (a[..., 0] - np.maximum(a[..., 1], a[..., 2]) > 60)
    x = pts[:, 0]
    assert red[rows[x < -2], cols[x < -2]].all() and red[rows[x > 2], cols[x > 2]].all()
    inside = np.abs(x) < 1.2
    assert not red[rows[inside], cols[inside]].any()
    assert front.draw.visible[0] and not behind.draw.visible[0]
    # the arrow's shaft (z from 1 to 3): hidden below the hill's top (z = 2), drawn above
    z = shaft[:, 2]
    assert not red[s_rows[z < 1.8], s_cols[z < 1.8]].any()
    assert red[s_rows[(z > 2.2) & (z < 2.7)], s_cols[(z > 2.2) & (z < 2.7)]].all()
    assert 0 < q.draw.visible.mean() < 1


@pytest.mark.parametrize("second", [False, True])
def test_what_a_surface_hides_is_drawn_under_its_picture(second):
    """The hidden part of mplot3d's own artists is drawn under the surface's picture:
    nothing of it shows through an opaque surface (the pixel is the picture without
    it), and a translucent surface (alpha 0.4: one layer over the point's pixel)
    shows it as matplotlib composites an image over a marker, 0.4 of the surface's
    colour over 0.6 of the marker's. Measured 2026-12-06: the same pixel opaque;
    (183, 53, 67) translucent against 0.4 (75, 133, 169) + 0.6 (255, 0, 0). The same
    with a second floatcol surface in the Axes (a small plate in a corner, away from
    the point: the two drawn as one composite)."""
    pixel = {}
    for alpha in (1.0, 0.4):
        for marker in (False, True):
            fig = plt.figure(figsize=(4, 3), dpi=100)
            ax = fig.add_subplot(projection="3d")
            fc.plot_surface("2*exp(-(x**2+y**2)/2)", ("x", -3, 3), ("y", -3, 3), ax=ax,
                            cmap="Blues", alpha=alpha)
            if second:
                fc.plot_surface("0.1 + 0*x", ("x", 2.4, 3), ("y", -3, -2.4), ax=ax,
                                color="green")
            pts = np.array([[-1.0, 1.73, 0.2]])     # behind the hill
            if marker:
                sc = ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], color="red", s=150,
                                depthshade=False)
            ax.set(xlim=(-3, 3), ylim=(-3, 3), zlim=(0, 2.2))
            fig.canvas.draw()
            rows, cols = _canvas_pixels(ax, pts)
            pixel[alpha, marker] = np.asarray(fig.canvas.buffer_rgba())[rows[0], cols[0], :3]
            plt.close(fig)
        assert not sc.draw.visible[0]
    assert np.abs(pixel[1.0, True].astype(int) - pixel[1.0, False]).max() <= 2
    want = 0.4 * pixel[1.0, False] + 0.6 * np.array([255, 0, 0])
    assert np.abs(pixel[0.4, True] - want).max() <= 15, (pixel, want)


def _floor(kind, ax):
    """Something of mplot3d's own below the hill (z = -0.5), as matplotlib's
    contourf3d example puts a contour's projection under a surface."""
    x = np.linspace(-3, 3, 41)
    X, Y = np.meshgrid(x, x)
    Z = np.cos(X) * np.sin(Y)
    if kind == "contourf":
        ax.contourf(X, Y, Z, zdir="z", offset=-0.5, cmap="autumn")
    elif kind == "contour":
        ax.contour(X, Y, Z, zdir="z", offset=-0.5, cmap="autumn", linewidths=3)
    else:
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection
        ax.add_collection3d(Poly3DCollection(
            [[(-3, -3, -0.5), (3, -3, -0.5), (3, 3, -0.5), (-3, 3, -0.5)],
             [(-1, -1, -0.5), (1, -1, -0.4), (0, 2, -0.5)]], facecolor=["orange", "red"]))


@pytest.mark.parametrize("kind", ["contourf", "contour", "polygons"])
def test_mplot3ds_own_polygons_and_contours_stay_behind_the_surface(kind):
    """A contourf's projection, a contour's lines and Poly3DCollection polygons under
    the hill: where the hill is (its pixels, less two at its edges) the picture
    is the hill's alone, as mplot3d draws its own surface over them; where it is not,
    they show. (Drawn after the surface as whole artists, they had covered it.)"""
    def picture(surface, floor):
        fig = plt.figure(figsize=(4, 3), dpi=100)
        ax = fig.add_subplot(projection="3d")
        if surface:
            fc.plot_surface("2*exp(-(x**2+y**2)/2)", ("x", -3, 3), ("y", -3, 3), ax=ax,
                            cmap="Blues")
        if floor:
            _floor(kind, ax)
        ax.set(xlim=(-3, 3), ylim=(-3, 3), zlim=(-0.5, 2.2))
        fig.canvas.draw()
        a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
        plt.close(fig)
        return a
    empty, hill, floor, both = (picture(s, f) for s, f in
                                ((False, False), (True, False), (False, True), (True, True)))
    on_hill = (hill != empty).any(axis=2)
    # (less two pixels at its edges: the floor shows through the antialiased ones,
    # and a line's width reaches over them from where it is seen)
    core = on_hill.copy()
    for dy in range(-2, 3):
        for dx in range(-2, 3):
            core &= np.roll(np.roll(on_hill, dy, 0), dx, 1)
    under = core & (floor != empty).any(axis=2)       # where both lie on the canvas
    assert under.sum() > 500
    # (measured 2026-12-06: all within 2 levels but, for the contour's lines, 3 of 6153
    # pixels by 6-7 at the hill's front edge, where a steep edge's blend is 3 wide;
    # drawn over the hill as whole artists: 216 levels)
    off = np.abs(both[under] - hill[under]).max(axis=1)
    assert (off > 2).mean() <= 0.002 and off.max() <= 16
    alone = (floor != empty).any(axis=2) & ~on_hill
    assert alone.sum() > 300
    assert ((both[alone] != empty[alone]).any(axis=1)).mean() > 0.95


def test_mplot3ds_own_calls_after_the_surface_keep_its_limits():
    """ax.plot after fc.plot_surface widens the Axes' limits to hold both, as after
    mplot3d's own plot_surface (its autoscale had forgotten the surface: a line at
    y = 0 took the y limits down to 0 -+ 0.04)."""
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_subplot(projection="3d")
    fc.plot_surface("2*exp(-(x**2+y**2)/2)", ("x", -3, 3), ("y", -3, 3), ax=ax)
    ax.plot([-4, 4], [0, 0], [0.8, 0.8])
    lo, hi = ax.get_ylim3d()
    assert lo <= -3 and hi >= 3
    lo, hi = ax.get_xlim3d()
    assert lo <= -4 and hi >= 4
    assert ax.get_legend_handles_labels() == ([], [])
    plt.close(fig)


def test_mplot3ds_own_artists_as_they_were_without_a_surface_drawn():
    """Where no floatcol surface was drawn with the Axes' projection (hidden, or none
    in the Axes), mplot3d's artists are drawn as mplot3d draws them."""
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_subplot(projection="3d")
    p = fc.plot_surface("2*exp(-(x**2+y**2)/2)", ("x", -3, 3), ("y", -3, 3), ax=ax)
    sc = ax.scatter([-1.0], [1.73], [0.2], color="red")  # behind the hill
    fig.canvas.draw()
    assert not sc.draw.visible[0]
    p.artist.set_visible(False)
    fig.canvas.draw()
    assert sc.draw.visible is None
    plt.close(fig)


def test_a_line_through_a_hill():
    fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
    ax = fig.add_subplot(projection="3d", proj_type="ortho")
    p = fc.plot_surface("2*exp(-(x**2+y**2)/2)", ("x", -3, 3), ("y", -3, 3), ax=ax)
    t = np.linspace(0, 1, 50)
    ln = p.plot(-3 + 6 * t, 0 * t, 0.8 + 0 * t, color="k")
    fig.canvas.draw()
    plt.close(fig)
    v = ln.visible
    # the part inside the hill (|x| < 1.52, where f > 0.8) is hidden, the ends shown
    assert v[:5].all() and v[-5:].all() and not v.all()
    with pytest.raises(ValueError, match="in an Axes"):
        fc.plot_surface("x*y", size=(40, 30)).scatter([0], [0], [0])


@pytest.mark.parametrize("ext", [".png", ".jpg", ".tif", ".webp", ".pdf", ".svg", ".eps"])
def test_every_savefig_format_from_plot_save_and_the_cli(tmp_path, ext, capsys):
    # (the CLI's main in this process: its own process start is test_cli's)
    from floatcol.cli import main
    p = fc.plot_surface("sin(x*y)", ("x", -2, 2), ("y", -2, 2), size=(60, 40))
    out = tmp_path / f"p{ext}"
    p.save(out)
    assert out.stat().st_size > 200
    cli = tmp_path / f"c{ext}"
    assert main(["render", "x*y", "--size", "40x30", "-o", str(cli)]) == 0, \
        capsys.readouterr().err
    assert cli.stat().st_size > 200


def test_mplot3d_rotation_redraws_with_a_preview():
    """mplot3d's own mouse rotation changes the Axes' angles: the next draw follows
    them, with coarser planes while the button is held."""
    X, Y, Z = _data()
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_subplot(projection="3d")
    p = fc.plot_surface(X, Y, Z, ax=ax)
    fig.canvas.draw()
    full = p.render.stats["samples"]
    ax.view_init(50, 10)
    ax.button_pressed = ax._rotate_btn[0]
    fig.canvas.draw()
    preview = p.render
    # the release: mplot3d draws nothing; the artist asks for the full-quality frame
    ax.button_pressed = None
    asked = []
    fig.canvas.draw_idle = lambda: asked.append(1)
    p.artist.on_release(None)
    assert asked and p.artist.stale
    fig.canvas.draw()
    assert preview.stats["samples"] < 0.6 * p.render.stats["samples"]
    assert p.render.stats["samples"] != full          # the new view, at full quality
    assert p.pixel_step is None
    plt.close(fig)


def test_text_and_quiver_are_depth_tested():
    fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
    ax = fig.add_subplot(projection="3d")
    p = fc.plot_surface("2*exp(-(x**2+y**2)/2)", ("x", -3, 3), ("y", -3, 3), ax=ax)
    front = p.text(0, -2.5, 0.5, "in front")
    behind = p.text(0, 2.5, 0.3, "behind")           # the hill lies between it and the eye
    # an arrow up through the hill's top: its lower part inside the hill is hidden
    q = p.quiver([0.0], [0.0], [1.0], [0.0], [0.0], [1.0], length=2.0)
    ax.set_zlim(0, 3.5)
    ax.view_init(20, -90)                            # looking along +y, low
    fig.canvas.draw()
    plt.close(fig)
    assert front.visible[0] and not behind.visible[0]
    # the shaft (z from 1 to 3, sampled a pixel apart) is hidden below the top (z = 2)
    assert not q.visible[:10].any() and q.visible[60:90].all()


def test_angles_and_projection_given_go_to_the_axes():
    X, Y, Z = _data()
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    p = fc.plot_surface(X, Y, Z, ax=ax, elev=45, azim=10, proj_type="ortho")
    assert (ax.elev, ax.azim) == (45, 10) and ax._focal_length == np.inf
    p.view_init(elev=20, azim=-30)
    assert (ax.elev, ax.azim) == (20, -30)
    plt.close(fig)


def test_objects_far_off_or_not_numbers_are_simply_not_shown():
    import warnings
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    p = fc.plot_surface("x*y", ("x", -1, 1), ("y", -1, 1), ax=ax)
    o = p.scatter([0, np.inf, np.nan, 1e300], [0, 0, 0, 0], [0, 0, 0, 0])
    p.plot([0, np.inf, 1], [0, 0, 1], [0, 0, 0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig.canvas.draw()
    plt.close(fig)
    assert list(o.visible) == [True, False, False, False]
    with pytest.raises(ValueError, match="numbers"):
        p.scatter(["a"], [0], [0])


@pytest.mark.parametrize("add,needle", [
    (lambda p: p.scatter([0, 1, 0.5], [0, 1, 0], [0, 1, 0], bogus=1),
     "scatter: a style matplotlib cannot draw .*unexpected keyword argument 'bogus'"),
    (lambda p: p.scatter([0, 1, 0.5], [0, 1, 0], [0, 1, 0], s=[1, 2]), r"2 sizes for 3 points"),
    (lambda p: p.scatter([0, 1, 0.5], [0, 1, 0], [0, 1, 0], c=["r", "g"]),
     r"2 colours for 3 points"),
    (lambda p: p.plot([0, 1], [0, 1], [0, 1], color="nope"), "plot: a style matplotlib"),
    (lambda p: p.text(0, 0, 0, "peak", fontsize="huge"), "text: a style matplotlib"),
])
def test_a_style_matplotlib_cannot_draw_is_refused_when_added(add, needle):
    """A style that failed at the figure's draw (an unknown keyword, sizes or colours
    for another number of points) was kept, and every later draw of the figure failed
    with it (found by fuzzing the plot's methods): a ValueError when it is added
    instead, and the figure draws on."""
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    p = fc.plot_surface("x*y", ("x", -1, 1), ("y", -1, 1), ax=ax)
    with pytest.raises(ValueError, match=needle):
        add(p)
    good = p.scatter([0, 1, 0.5], [0, 1, 0], [0, 1, 0], c=["r", "g", "b"], s=[5, 6, 7])
    fig.canvas.draw()
    plt.close(fig)
    assert good.visible is not None and len(good.visible) == 3


def test_mplot3d_preview_shrinks_and_stays_in_place():
    """A preview rendered MAX_SHRINK times smaller each way lands where the full
    frame of the same view does (its pixels enlarged)."""
    from floatcol.mpl import MAX_SHRINK
    X, Y, Z = _data()
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_subplot(projection="3d")
    ax.set_axis_off()
    p = fc.plot_surface(X, Y, Z, ax=ax)
    fig.canvas.draw()
    full = np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()
    full_size = p.render.rgba.shape
    ax.button_pressed = ax._rotate_btn[0]
    p.artist._preview.seconds_per_pixel = 1.0
    fig.canvas.draw()
    assert p.render.rgba.shape[0] <= full_size[0] // MAX_SHRINK + 2
    preview = np.asarray(fig.canvas.buffer_rgba())[..., :3]
    a, b = (preview != 255).any(-1), (full != 255).any(-1)
    assert (a & b).sum() / (a | b).sum() > 0.9          # measured 0.941
    ax.button_pressed = None
    plt.close(fig)


def test_a_rotation_fits_its_camera_on_grids_computed_once(monkeypatch):
    """A 3-D Axes draws its mesh stretched by the Axes' box: the same stretch is the
    same HeightField (HeightField.scaled keeps it), so a rotation's draw fits its
    camera and takes its hole map without evaluating the mesh on a grid again."""
    from floatcol.surface import SCALED_KEPT, HeightField
    X, Y, Z = _data()
    hf = HeightField(Z, u=(-5, 4.75), v=(-5, 4.75))
    s = hf.scaled(2.0, 3.0, 0.5)
    assert hf.scaled(2.0, 3.0, 0.5) is s and s.default_domain == ((-10, 9.5), (-15, 14.25))
    assert np.array_equal(s.hf, Z * 0.5)
    others = [hf.scaled(1.0 + k, 1.0, 1.0) for k in range(SCALED_KEPT)]
    assert hf.scaled(2.0, 3.0, 0.5) is not s and others[-1] is hf.scaled(SCALED_KEPT, 1.0, 1.0)
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_subplot(projection="3d", proj_type="persp")
    fc.plot_surface(X, Y, Z, ax=ax)
    fig.canvas.draw()
    grids = []
    real = HeightField.evaluate

    def evaluate(self, u, v, derivatives=False):
        grids.append(np.size(u))
        return real(self, u, v, derivatives)

    monkeypatch.setattr(HeightField, "evaluate", evaluate)
    ax.view_init(40, -20)
    fig.canvas.draw()
    assert max(grids, default=0) < 100         # (a fit grid has 65^2 points, a hole map 257^2)
    plt.close(fig)


def test_an_invisible_mplot3d_artist_stays_undrawn():
    """A hidden artist (set_visible(False)) beside a surface draws nothing, as mplot3d
    draws it: its depth test is not even run (visible stays None)."""
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_subplot(projection="3d")
    fc.plot_surface("exp(-(x**2+y**2))", ("x", -2, 2), ("y", -2, 2), ax=ax)
    line, = ax.plot([-2, 2], [-2, 2], [2, 2], color="red", lw=4)
    fig.canvas.draw()
    assert line.draw.visible is not None and _red(fig).any()
    line.set_visible(False)
    fig.canvas.draw()
    assert line.draw.visible is None and not _red(fig).any()
    plt.close(fig)


def test_a_pickled_3d_figure_draws_the_same_and_redraws_on_release():
    """A 3-D Axes with a floatcol mesh and mplot3d's own scatter pickles; the copy draws
    the same pixels, and its release handler (the full-quality frame after a drag's
    previews) is connected to the copy's canvas at its first draw."""
    import pickle

    from matplotlib.backend_bases import MouseEvent
    X, Y, Z = _data()
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_subplot(projection="3d")
    fc.plot_surface(X, Y, Z, ax=ax, cmap="viridis")
    ax.scatter([0], [0], [1.2], color="red")
    fig.canvas.draw()
    before = np.asarray(fig.canvas.buffer_rgba()).copy()
    other = pickle.loads(pickle.dumps(fig))
    other.canvas.draw()
    assert np.array_equal(np.asarray(other.canvas.buffer_rgba()), before)
    oax = other.axes[0]
    art = [a for a in oax.artists if hasattr(a, "on_release")][0]
    oax.view_init(50, 10)
    oax.button_pressed = oax._rotate_btn[0]
    other.canvas.draw()
    assert art.preview
    oax.button_pressed = None
    asked = []
    other.canvas.draw_idle = lambda: asked.append(1)
    other.canvas.callbacks.process("button_release_event", MouseEvent(
        "button_release_event", other.canvas, 10, 10, button=1))
    assert asked and not art.preview
    plt.close(other)
    plt.close(fig)


def test_two_plot_surface_calls_in_one_axes_hide_each_other_per_pixel():
    """Two fc.plot_surface calls in one 3-D Axes (mplot3d draws each of its own surfaces
    whole, one over the other): the planes w = x/2 (red) and w = -x/2 (blue) cross
    along x = 0; seen from above, each is in front where it is the upper one. The
    first surface's artist renders both with the Axes' camera and draws their
    composite by depth; each plot keeps its own render."""
    from mpl_toolkits.mplot3d import proj3d
    fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
    ax = fig.add_subplot(projection="3d")
    red = fc.plot_surface("x/2", ("x", -2, 2), ("y", -2, 2), ax=ax, color="red", shade=False)
    blue = fc.plot_surface("-x/2", ("x", -2, 2), ("y", -2, 2), ax=ax, color="blue",
                           shade=False)
    fig.canvas.draw()
    a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    x = np.linspace(0.3, 1.7, 8)                # (the edges at |x| = 2 antialiased)
    for sign, colour in ((1.0, (255, 0, 0)), (-1.0, (0, 0, 255))):
        # points of the upper plane on both sides of the crossing, over y
        px, py = np.meshgrid(sign * x, np.linspace(-1.8, 1.8, 7))
        xs, ys, _ = proj3d.proj_transform(px.ravel(), py.ravel(), np.abs(px.ravel()) / 2, ax.M)
        X, Y = ax.transData.transform(np.column_stack([xs, ys])).T
        got = a[np.round(a.shape[0] - Y).astype(int), np.round(X).astype(int)]
        assert (got == colour).all(axis=1).mean() >= 0.95    # (measured 1.0; 0.375 drawn whole)
    assert red.render is not blue.render and red.render.rgba.shape == blue.render.rgba.shape
    assert red.artist.drawn_for(ax) and blue.artist.drawn_for(ax)
    plt.close(fig)


def _plates(alpha, red_first=True, red=("0.1 + 0*x",), blue="-0.1 + 0*x"):
    """Flat plates in one 3-D Axes with no panes (the figure's white behind), flat
    colours (shade=False): red ones (one fc.plot_surface call; z = 0.1 first) of
    opacity ``alpha`` and an opaque blue one (z = -0.1 first), over x, y in [-3, 3];
    the figure, its Axes, the two plots, and the canvas pixel of the point (0, 0,
    0.1), through which the eye's ray goes down to z = -0.1 0.35 from the plates'
    centre (from elevation 30)."""
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_subplot(projection="3d")
    ax.set_axis_off()
    kw = dict(ax=ax, shade=False, lower_color="same")
    plates = [(list(red) if len(red) > 1 else red[0],
               dict(color="red", alpha=alpha, label="red")),
              (blue, dict(color="blue", label="blue"))]
    made = [fc.plot_surface(e, ("x", -3, 3), ("y", -3, 3), **kw, **o)
            for e, o in (plates if red_first else plates[::-1])]
    ax.set(xlim=(-3, 3), ylim=(-3, 3), zlim=(-1, 1))
    ax.view_init(30, -60)
    fig.canvas.draw()
    rows, cols = _canvas_pixels(ax, np.array([[0.0, 0.0, 0.1]]))
    got = np.asarray(fig.canvas.buffer_rgba())[rows[0], cols[0], :3].astype(int)
    return fig, ax, made if red_first else made[::-1], got


@pytest.mark.parametrize("red_first", [True, False])
@pytest.mark.parametrize("layers", [1, 2])
def test_a_translucent_plot_shows_the_plot_behind_it_in_one_axes(layers, red_first):
    """fc.plot_surface calls in one 3-D Axes, the nearer translucent (alpha 0.4):
    where it lies over the other, the pixel is 0.4 of its flat colour over 0.6 of
    the one behind, (102, 0, 153) for red over blue, whichever was plotted first.
    With two red plates (one call, z = 0.1 and -0.1) about the blue one (z = 0) the
    lower red plate lies behind the blue and shows nothing: the plots' layers are
    merged by depth (section 6.6). Before: the nearest plot's picture hid the other
    (0.4 red over the white figure, (255, 153, 153)); and a composite of the two
    pictures that let the one behind show through gave (163, 0, 92) with two plates,
    both red layers over the blue. Measured 2026-12-06: exactly (102, 0, 153) in all
    four; the bound leaves 2 levels."""
    red = ("0.1 + 0*x", "-0.1 + 0*x")[:layers]
    fig, _, _, got = _plates(0.4, red_first, red, "-0.1 + 0*x" if layers == 1 else "0*x")
    plt.close(fig)
    assert np.abs(got - np.array([102, 0, 153])).max() <= 2, got


def test_a_plot_is_removed_hidden_labelled_and_made_translucent_as_an_artist():
    """SurfacePlot answers the artist calls scripts make on mplot3d's plot_surface
    result: ``ax.legend()`` shows each label with a patch of its colour (an empty
    label none); ``set_alpha`` makes it translucent (0.4 red over the blue behind);
    ``set_visible(False)`` hides it (the blue alone at its pixel); ``remove()``
    takes it, its legend entry and its objects out of the Axes, so that removing and
    plotting again (matplotlib's way to animate a surface) leaves the Axes as it
    was; calls on a plot in no Axes are refused with a ValueError that says so."""
    fig, ax, (red, blue), got = _plates(1.0)
    assert (got == (255, 0, 0)).all()
    leg = ax.legend()
    assert [t.get_text() for t in leg.get_texts()] == ["red", "blue"]
    assert [tuple(h.get_facecolor()) for h in leg.legend_handles] == [(1, 0, 0, 1),
                                                                      (0, 0, 1, 1)]
    leg.remove()
    rows, cols = _canvas_pixels(ax, np.array([[0.0, 0.0, 0.1]]))

    def pixel():
        fig.canvas.draw()
        return np.asarray(fig.canvas.buffer_rgba())[rows[0], cols[0], :3].astype(int)

    red.set_alpha(0.4)
    assert red.get_alpha() == 0.4 and red.translucent()
    assert np.abs(pixel() - np.array([102, 0, 153])).max() <= 2
    red.set_visible(False)
    assert not red.get_visible() and (pixel() == (0, 0, 255)).all()
    red.set_visible(True)
    n = len(ax.get_children())
    red.scatter([0], [0], [0.5], color="k")
    red.remove()
    assert red.artist is None and red.figure is None
    assert (pixel() == (0, 0, 255)).all()
    assert len(ax.get_children()) == n - 2        # its picture and its legend entry
    for k in range(3):                            # an animation's frames
        frame = fc.plot_surface(f"{0.1 * k} + 0*x", ("x", -3, 3), ("y", -3, 3), ax=ax,
                                color="red", shade=False)
        frame.scatter([0], [0], [0.5], color="k")
        pixel()
        frame.remove()
    assert len(ax.get_children()) == n - 2
    for call in (red.remove, lambda: red.set_visible(False), lambda: red.set_zorder(2)):
        with pytest.raises(ValueError, match="needs the plot in an Axes"):
            call()
    with pytest.raises(ValueError, match="alpha must be between 0 and 1"):
        blue.set_alpha(2)
    blue.set_label("_hidden")
    with pytest.warns(UserWarning, match="No artists with labels"):
        assert ax.legend().get_texts() == []
    plt.close(fig)


def test_the_checkerboard_example_as_mplot3d_draws_it():
    """matplotlib's surface3d_3 example (facecolors, a checkerboard of yellow and blue
    faces) in a 3-D Axes, drawn by mplot3d and by fc.plot_surface: of the pixels both
    paint yellow or blue, the two agree on the colour at 99 % (measured 2026-12-06:
    99.19 % of 21 217; the rest along the faces' edges. The faces' colours read as a
    texture through the points, as before, blended them: 49.6 % of 10 746)."""
    X, Y = np.meshgrid(np.arange(-5, 5, 0.25), np.arange(-5, 5, 0.25))
    Z = np.sin(np.sqrt(X ** 2 + Y ** 2))
    colors = np.where(np.add.outer(np.arange(40), np.arange(40)) % 2 == 0, "y", "b")

    def classes(draw):
        fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
        ax = fig.add_subplot(projection="3d")
        draw(ax)
        ax.set_zlim(-1, 1)
        ax.set_axis_off()
        fig.canvas.draw()
        a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
        plt.close(fig)
        return ((a[..., 0] > 100) & (a[..., 1] > 100) & (a[..., 2] < 80),
                (a[..., 2] > 100) & (a[..., 0] < 80) & (a[..., 1] < 80))
    ym, bm = classes(lambda ax: ax.plot_surface(X, Y, Z, facecolors=colors, linewidth=0))
    yf, bf = classes(lambda ax: fc.plot_surface(X, Y, Z, ax=ax, facecolors=colors,
                                                linewidth=0))
    both = (ym | bm) & (yf | bf)
    assert both.sum() > 15000
    assert ((ym == yf) & (bm == bf))[both].mean() > 0.98


def _svg_images(fig, monkeypatch):
    """The figure saved as SVG (its text), and its images drawn in order over white
    on a canvas of the figure's pixels (at its dpi, top row first, as Agg's canvas)."""
    from matplotlib.backends.backend_svg import RendererSVG
    drawn = []
    own = RendererSVG.draw_image

    def record(self, gc, x, y, im, transform=None):
        drawn.append((x, y, np.array(im), transform))
        return own(self, gc, x, y, im, transform)
    monkeypatch.setattr(RendererSVG, "draw_image", record)
    buf = io.StringIO()
    fig.savefig(buf, format="svg", dpi=fig.dpi)
    W, H = (int(round(x)) for x in fig.get_size_inches() * fig.dpi)
    canvas = np.full((H, W, 3), 255.0)
    m = fig.dpi / 72.0                             # (x, y: points from the bottom left)
    for x, y, im, transform in drawn:
        assert transform is None
        h, w = im.shape[:2]
        x0, y0 = int(round(x * m)), int(round(y * m))
        rows = H - 1 - (y0 + np.arange(h))         # (im: its bottom row first)
        a = im[..., 3:4] / 255.0
        part = canvas[rows[:, None], x0 + np.arange(w)[None, :]]
        canvas[rows[:, None], x0 + np.arange(w)[None, :]] = im[..., :3] * a + part * (1 - a)
    return buf.getvalue(), np.round(canvas).astype(int)


@pytest.mark.parametrize("plane, output", [
    ("plot_surface", "png"), ("contourf", "png"), ("translucent", "png"),
    ("plot_surface", "svg"), ("contourf", "svg"), ("translucent", "svg")])
def test_mplot3d_polygons_through_the_surface_are_cut_a_pixel_at_a_time(plane, output,
                                                                      monkeypatch):
    """mplot3d's own plot_surface of a plane z = 0.2 through a floatcol surface in one
    3-D Axes: the plane shows exactly where it lies in front of the surface, its line
    through the surface drawn a pixel at a time (its polygons that cross the surface
    were drawn whole over it, a staircase of quads; mplot3d alone draws the whole plane
    over the surface). The same plane as a filled contour projected at offset 0.2
    (``ax.contourf(..., zdir="z", offset=0.2)``: its flat levels drawn through the
    plane's homography, a pixel at a time; it too was drawn whole over the surface).
    Orthographic: the ray to the surface's point (u, v, w) seen at a pixel meets the
    plane in front of it where w < 0.2 and the ray crosses z = 0.2 over the plane's
    square. Of the pixels whose 3 x 3 neighbourhood sees the surface away from the
    plane's height and edges, red exactly there at 99.5 % (measured 2026-12-06:
    plot_surface's 100 % of 10 628, 99.86 % before the polygons' outlines took the side
    of the surface beside them; contourf's 100 % of 6 746. Drawn whole: 91.8 % and
    64.1 %). A translucent plane (alpha 0.5, 8 x 8 quads) the same: its tint over the
    surface exactly there, the surface's own colour elsewhere (measured 2026-12-06:
    100 % of 10 628; it was drawn whole over the surface, 85.2 %). In a vector file
    (SVG, as PDF and EPS) the same: the picture and the polygons cut through it are
    one image at the figure's dpi there, the plane no longer a vector path (it was,
    whole over the surface: the file's images alone had no red). Measured 2026-12-06
    on the SVG's images: the same 100 %, 100 % and 100 %."""
    X, Y = np.meshgrid(np.linspace(-3, 3, 60), np.linspace(-3, 3, 60))
    P, Q = np.meshgrid(np.linspace(-5.5, 5.5, 12), np.linspace(-5.5, 5.5, 12))
    fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
    ax = fig.add_subplot(projection="3d", proj_type="ortho")
    p = fc.plot_surface(X, Y, np.sin(X) * np.cos(Y), ax=ax, cmap="viridis")
    if plane == "plot_surface":
        ax.plot_surface(P, Q, 0 * P + 0.2, color="red", shade=False, linewidth=0)
    elif plane == "translucent":
        ax.plot_surface(P, Q, 0 * P + 0.2, color="red", alpha=0.5, shade=False, linewidth=0,
                        rcount=8, ccount=8)
    else:
        ax.contourf(P, Q, P, levels=[-6, 0, 6], colors="red", zdir="z", offset=0.2)
        ax.set(xlim=(-5.5, 5.5), ylim=(-5.5, 5.5))
    if output == "svg":
        ax.set_axis_off()
        text, a = _svg_images(fig, monkeypatch)
        assert "#ff0000" not in text                  # (no red vector path)
    else:
        fig.canvas.draw()
        a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    plt.close(fig)
    r, T = p.render, p.artist.placed
    assert abs(T[0, 1]) < 1e-9 and abs(T[1, 0]) < 1e-9       # (no roll)
    red = (a[..., 0] > 150) & (a[..., 1] < 60) & (a[..., 2] < 60)
    rows, cols = np.mgrid[0:r.side.shape[0], 0:r.side.shape[1]]
    ix = np.round(T[0, 0] * cols + T[0, 2] - 0.5).astype(int)
    iy = a.shape[0] - 1 - np.round(T[1, 1] * rows + T[1, 2] - 0.5).astype(int)
    # the view's direction in the data's units: screen z from the box's (to_screen)
    lin = np.array([r.view.to_screen(*e) for e in np.eye(3)]).T - \
        np.array(r.view.to_screen(0.0, 0.0, 0.0))[:, None]
    d = np.linalg.solve(lin, [0.0, 0.0, 1.0]) / np.asarray(r.box, dtype=float)
    u, v = (np.nan_to_num(np.asarray(q, dtype=float)) for q in (r.u, r.v))
    w = np.nan_to_num(np.asarray(r.w, dtype=float), nan=0.2)
    t = (0.2 - w) / d[2]
    cu, cv = u + t * d[0], v + t * d[1]                        # where the ray meets z = 0.2
    want = (w < 0.2) & (np.abs(cu) < 5.5) & (np.abs(cv) < 5.5)
    seen = (r.side != 0) & (r.rgba[..., 3] == 255) & (np.abs(w - 0.2) > 0.05) & \
        (np.abs(np.abs(cu) - 5.5) > 0.1) & (np.abs(np.abs(cv) - 5.5) > 0.1)
    ok = seen.copy()
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            ok &= np.roll(np.roll(seen, di, 0), dj, 1) & \
                (np.roll(np.roll(want, di, 0), dj, 1) == want)
    ok &= (ix >= 0) & (ix < a.shape[1]) & (iy >= 0) & (iy < a.shape[0])
    assert ok.sum() > 5000 and 0.2 < want[ok].mean() < 0.8
    if plane == "translucent":     # tinted: nearer the plane over the surface than it alone
        surf = r.rgba[..., :3].astype(float)[ok]
        blend = 0.5 * np.array([255.0, 0.0, 0.0]) + 0.5 * surf
        got = a[iy[ok], ix[ok]]
        red = np.zeros(a.shape[:2], bool)
        red[iy[ok], ix[ok]] = np.abs(got - blend).sum(axis=1) < np.abs(got - surf).sum(axis=1)
    assert (red[iy[ok], ix[ok]] == want[ok]).mean() > 0.995


def test_z_limits_follow_the_heights_not_the_colours():
    """In a 3-D Axes the z limits take the surface's heights, as mplot3d's: vmin/vmax
    and a colour field's range colour it only (they set z to -5..5 for heights in
    -1..1, and to a colour field's -2..2 for heights in -4..4)."""
    X, Y = np.meshgrid(np.linspace(-2, 2, 40), np.linspace(-2, 2, 40))
    for kw, Z in ((dict(vmin=-5, vmax=5), np.sin(X) * np.cos(Y)),
                  (dict(color_field=X), X * Y)):
        fig = plt.figure()
        ax = fig.add_subplot(projection="3d")
        fc.plot_surface(X, Y, Z, ax=ax, **kw)
        mine = ax.get_zlim()
        plt.close(fig)
        fig = plt.figure()
        ax = fig.add_subplot(projection="3d")
        ax.plot_surface(X, Y, Z)
        theirs = ax.get_zlim()
        plt.close(fig)
        assert mine == pytest.approx(theirs, abs=1e-9)
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    p = fc.plot_surface("x*y", ("x", -2, 2), ("y", -2, 2), ax=ax, color_field="x")
    assert p.norm.vmin == pytest.approx(-2) and ax.get_zlim()[1] > 3.9    # (x y reaches 4)
    plt.close(fig)


@pytest.mark.parametrize("elev, azim, roll, vertical, inverted, box", [
    (25, -50, 0, "y", "", None), (25, -50, 0, "x", "", None), (60, 30, 40, "y", "", None),
    (120, 30, 0, "z", "", None), (-120, 30, 0, "z", "", None), (179, -60, 0, "z", "", None),
    (100, 10, 0, "y", "", None), (141, 99, -65, "x", "z", (1.6, 0.7, 1.2)),
    (171, 33, 96, "y", "xyz", (0.8, 1.9, 0.6)), (-140, -159, 0, "y", "y", None)])
def test_views_as_mplot3d_draws_them(elev, azim, roll, vertical, inverted, box):
    """view_init(elev, azim, roll, vertical_axis) (mplot3d's eye and box rolled to a
    vertical axis "y" or "x"; an elev past 90, where a drag over the top takes it, the
    view upside down), with inverted axes and box aspects too: the surface covers where
    mplot3d draws the same mesh, both flat red (intersection over union; measured
    2026-12-06: 0.94-0.99 perspective and orthographic, the least on the smallest
    pictures, whose rims weigh most; 60 random such views: at least 0.939. Before,
    another vertical axis was drawn as if z were up, 0.16, and an elev past 90 raised
    ValueError from the Axes' draw)."""
    X, Y = np.meshgrid(np.linspace(-3, 3, 40), np.linspace(-2, 2, 30))
    Z = np.sin(X) * np.cos(Y) + 0.3 * X

    def setup(ax):
        if box is not None:
            ax.set_box_aspect(box)
        ax.view_init(elev=elev, azim=azim, roll=roll, vertical_axis=vertical)
        for name in inverted:
            getattr(ax, f"invert_{name}axis")()
    for proj in ("persp", "ortho"):
        iou, theirs = red_overlap(
            lambda ax: fc.plot_surface(X, Y, Z, ax=ax, color="red", lower_color="red",
                                       shade=False),
            lambda ax: ax.plot_surface(X, Y, Z, color="red", shade=False, linewidth=0,
                                       antialiased=False), setup, proj)
        assert theirs > 5000 and iou > 0.93


def test_the_line_through_the_surface_is_antialiased():
    """Where an mplot3d polygon passes through the surface, each pixel shows the part
    of it on the polygon's side (mpl._coverage, from the gap in depth at the pixels'
    centres and its change across them): against the exact share of each pixel on one
    side of straight lines at 13 angles (a 16 x 16 sub-pixel count), mean error under
    0.005 and at most 0.06 (measured 2026-12-06: means 0.0002-0.0010, at most 0.041);
    no surface there: all of it; no polygon: none."""
    from floatcol.mpl import _coverage
    H, W = 40, 50
    yy, xx = np.mgrid[0:H, 0:W].astype(float)
    s = (np.arange(16) + 0.5) / 16 - 0.5
    sx, sy = np.meshgrid(s, s)
    for ang in np.linspace(0, np.pi, 13):
        a, b = np.cos(ang), np.sin(ang)
        c = -(a * 25.3 + b * 20.7)
        cov = _coverage(0.37 * (a * xx + b * yy + c))
        exact = ((a * (xx[..., None, None] + sx) + b * (yy[..., None, None] + sy) + c) < 0
                 ).mean(axis=(-1, -2))
        err = np.abs(cov - exact)[2:-2, 2:-2]
        assert err.mean() < 0.005 and err.max() < 0.06
        assert ((cov > 0.05) & (cov < 0.95)).sum() > 20              # (a blended line)
    d = np.full((4, 4), np.inf)
    d[1, 1], d[2, 2] = -np.inf, 0.5
    cov = _coverage(d)
    assert cov[1, 1] == 1.0 and cov[0, 0] == 0.0 and cov[2, 2] == 0.0


def test_objects_numpy_reads_as_arrays_are_a_mesh():
    """X, Y, Z that numpy reads through __array__ (pandas' Index and DataFrame,
    xarray's DataArray: not installed here, so a stand-in) are matplotlib's mesh, the
    same picture as numpy arrays (they were taken for an expression and its ranges:
    "a range must be (symbol, low, high)")."""
    class Frame:
        def __init__(self, a):
            self.a = np.asarray(a)

        def __array__(self, dtype=None, copy=None):
            return self.a if dtype is None else self.a.astype(dtype)
    x, y = np.linspace(-2, 2, 30), np.linspace(-1, 1, 20)
    X, Y = np.meshgrid(x, y)
    Z = np.sin(X) * Y
    p = fc.plot_surface(Frame(x), Frame(y), Frame(Z), size=(60, 40))
    q = fc.plot_surface(x, y, Z, size=(60, 40))
    assert p.domain == ((-2.0, 2.0), (-1.0, 1.0))
    assert np.array_equal(p.draw().rgba, q.draw().rgba)
    t = fc.plot_trisurf(Frame(X.ravel()), Frame(Y.ravel()), Frame(Z.ravel()), size=(60, 40))
    assert t.draw().rgba[..., 3].any()
    # ... and a colour from data as such an object (render's color=)
    c = np.cos(X) * Y
    a = fc.render("sin(u)*cos(v)", u=(-2, 2), v=(-1, 1), size=(60, 40), color=Frame(c))
    b = fc.render("sin(u)*cos(v)", u=(-2, 2), v=(-1, 1), size=(60, 40), color=c)
    assert np.array_equal(a.rgba, b.rgba)


def test_a_crossing_polygon_keeps_mplot3ds_order_among_its_collection():
    """Two quads of one Poly3DCollection over a flat surface z = 0, seen from the
    front: the near (red) one passes through the surface, the far (blue) one stands
    wholly above it and behind the red one. mplot3d's order among them holds (the far
    one, not crossing, was drawn after the crossing one and covered it): blue shows
    where mplot3d alone shows it, and red where mplot3d shows it less the part below
    the surface, 0.3 of its 1.3 in height (measured 2026-12-06: blue 2 006 pixels as
    mplot3d's; red 78.3 % of mplot3d's, all inside it)."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    X, Y = np.meshgrid(np.linspace(-3, 3, 30), np.linspace(-3, 3, 30))
    near = [(-1, -0.5, -0.3), (1, -0.5, -0.3), (1, -0.5, 1.0), (-1, -0.5, 1.0)]
    far = [(-1, 0.5, 0.05), (1, 0.5, 0.05), (1, 0.5, 1.35), (-1, 0.5, 1.35)]

    def picture(with_surface):
        fig = plt.figure(figsize=(5, 4), dpi=100)
        ax = fig.add_subplot(projection="3d")
        if with_surface:
            fc.plot_surface(X, Y, 0 * X, ax=ax, color="lightgrey")
        ax.add_collection3d(Poly3DCollection([near, far], facecolors=["red", "blue"],
                                             edgecolors="k"))
        ax.set(xlim=(-3, 3), ylim=(-3, 3), zlim=(-1, 1.5))
        ax.view_init(25, -90)
        fig.canvas.draw()
        a = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
        plt.close(fig)
        return ((a[..., 0] > 200) & (a[..., 1] < 60) & (a[..., 2] < 60),
                (a[..., 2] > 200) & (a[..., 0] < 60) & (a[..., 1] < 60))
    (red, blue), (red0, blue0) = picture(True), picture(False)
    assert blue0.sum() > 1000 and red0.sum() > 2000
    assert abs(int(blue.sum()) - int(blue0.sum())) <= 0.03 * blue0.sum()
    assert (red & ~red0).sum() == 0 and 0.72 < red.sum() / red0.sum() < 0.84

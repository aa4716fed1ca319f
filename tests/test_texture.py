"""Textures, colour from data and lines on the surface (Gordon 6.7; passes/colour.py,
passes/overlays.py) against the ray caster's (u, v) at each hit (tests/reference.py).

Bounds measured on 2026-12-03 at 200x150, then loosened by a small margin (figures in
the comments). "Away from the checker edges": pixels whose 3 x 3 neighbourhood in the
truth has one checker colour (the filtered lookup blends the two across an edge, as
it should).
"""
import numpy as np
import pytest

import floatcol as fc
from conftest import reference_for
from reference import numpy_surface, raycast

N_CHECK = 8        # checker squares along each side of the domain


def checker(n_texels=256, squares=N_CHECK):
    k = (np.add.outer(np.arange(n_texels) * squares // n_texels,
                      np.arange(n_texels) * squares // n_texels) % 2).astype(np.uint8)
    return np.stack([k * 255, (1 - k) * 255, np.full_like(k, 64)], axis=-1)


def truth_checker(u, v, dom_u, dom_v, n_texels=256, squares=N_CHECK):
    """The checker's class (1: red square) at world (u, v): the texel nearest to
    (u, v) on the node-centred grid over the domain, as the texture is indexed."""
    u, v = np.nan_to_num(u), np.nan_to_num(v)
    i = np.rint((u - dom_u[0]) / (dom_u[1] - dom_u[0]) * (n_texels - 1))
    j = np.rint((v - dom_v[0]) / (dom_v[1] - dom_v[0]) * (n_texels - 1))
    return ((i * squares // n_texels + j * squares // n_texels) % 2).astype(int)


def _interior(cls, seen):
    """Pixels whose 3 x 3 neighbourhood is seen and of one class."""
    H, W = cls.shape
    ok = seen.copy()
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            sh = np.roll(np.roll(cls, di, 0), dj, 1)
            ss = np.roll(np.roll(seen, di, 0), dj, 1)
            ok &= ss & (sh == cls)
    ok[0, :] = ok[-1, :] = ok[:, 0] = ok[:, -1] = False
    return ok


CASES = [
    # expr, u, v, elev, azim, projection, filter, min agreement (measured: 100 % in
    # each, on 2250-10926 pixels; also 100 % on sin(u) cos(v), (u^2 - v^2) / 3 and a
    # hemisphere not in the suite)
    ("3*sin(u*cos(v))", (-5, 5), (-5, 5), 30, 20, "orthographic", "mipmap", 0.995),
    ("3*sin(u*cos(v))", (-5, 5), (-5, 5), 30, 20, "perspective", "mipmap", 0.995),
    ("exp(-(u*u+v*v))*2", (-2, 2), (-2, 2), 45, -35, "perspective", "point", 0.995),
    ("u*v/2", (-2, 2), (-2, 2), 25, 60, "orthographic", "linear", 0.995),
]


@pytest.mark.parametrize("expr,u,v,elev,azim,proj,filt,min_agree", CASES)
def test_checkerboard_matches_the_ray_casters_uv(expr, u, v, elev, azim, proj, filt, min_agree):
    r = fc.render(expr, u=u, v=v, size=(200, 150), elev=elev, azim=azim, projection=proj,
                  texture=checker(), texture_filter=filt, shading="lambert")
    ref = reference_for(r, expr, u, v, elev, azim, proj)
    seen = (ref.side != 0) & (r.side != 0)
    truth = np.where(seen, truth_checker(ref.u, ref.v, u, v), -1)
    rgb = r.rgba[..., :3].astype(int)
    lit = rgb.max(-1) > 24                       # (a grazing pixel is too dark to tell)
    mine = (rgb[..., 0] > rgb[..., 1]).astype(int)
    inside = _interior(truth, seen) & lit
    assert inside.sum() > 0.25 * seen.sum()
    agree = (mine[inside] == truth[inside]).mean()
    assert agree >= min_agree, f"{agree:.5f} of {inside.sum()} pixels"


def test_texture_from_a_file_and_from_a_function(tmp_path):
    from PIL import Image
    img = checker(64)
    path = tmp_path / "checker.png"
    Image.fromarray(img[::-1]).save(path)       # a file's first row is the top (v high)
    kw = dict(u=(-2, 2), v=(-2, 2), size=(120, 90), shading="lambert")
    a = fc.render("u*v/3", texture=img, **kw)
    b = fc.render("u*v/3", texture=str(path), **kw)
    assert np.abs(a.rgba.astype(int) - b.rgba.astype(int)).max() <= 1

    def fn(u, v):                                # the same checker as a function
        k = truth_checker(u, v, (-2, 2), (-2, 2), 64)
        return np.stack([k * 1.0, 1.0 - k, np.full(k.shape, 64 / 255)], axis=-1)
    c = fc.render("u*v/3", texture=fn, texture_filter="point", **kw)
    d = fc.render("u*v/3", texture=img, texture_filter="point", **kw)
    assert (np.abs(c.rgba.astype(int) - d.rgba.astype(int)).max(-1) > 2).mean() < 0.01


def test_texture_alpha_lays_it_over_the_surfaces_colour():
    kw = dict(u=(-2, 2), v=(-2, 2), size=(80, 60), ambient=1.0, specular=0.0)
    clear = np.zeros((4, 4, 4), dtype=np.uint8)
    plain = fc.render("u*v/3", **kw)
    assert np.array_equal(fc.render("u*v/3", texture=clear, **kw).rgba, plain.rgba)
    half = clear.copy()
    half[..., 0] = 255
    half[..., 3] = 128                           # red at alpha 1/2 over the colormap
    r = fc.render("u*v/3", texture=half, **kw)
    seen = _interior(np.zeros(plain.side.shape, int), plain.side > 0)   # whole pixels
    expect = 0.5 * 255 + 0.5 * plain.rgba[..., 0].astype(float)
    assert np.abs(r.rgba[..., 0][seen] - expect[seen]).max() <= 2.5


def test_colour_from_data_follows_the_field_at_each_hit():
    """color='u + v', flat colours (ambient 1): each pixel is the colormap's colour of
    u + v at the ray caster's hit (measured: 99.9 % within 6 levels)."""
    import matplotlib
    expr, dom = "sin(u)*cos(v)", (-3, 3)
    r = fc.render(expr, u=dom, v=dom, size=(200, 150), color="u + v", cmap="viridis",
                  ambient=1.0, specular=0.0, elev=40, azim=25)
    lo, hi = r.stats["c_limits"]
    assert lo == pytest.approx(-6, abs=0.3) and hi == pytest.approx(6, abs=0.3)
    ref = reference_for(r, expr, dom, dom, 40, 25, "orthographic")
    seen = (ref.side != 0) & (r.side != 0)
    cmap = matplotlib.colormaps["viridis"]
    want = cmap(np.clip((ref.u + ref.v - lo) / (hi - lo), 0, 1))[..., :3] * 255
    err = np.abs(r.rgba[..., :3] - want).max(-1)
    inside = _interior(np.zeros(seen.shape, int), seen)
    assert (err[inside] <= 6).mean() >= 0.995
    # the same field as an array over the domain (a height field's indexing)
    x = np.linspace(-3, 3, 61)
    arr = np.add.outer(x, x)                     # arr[j, i] = u_i + v_j
    a = fc.render(expr, u=dom, v=dom, size=(200, 150), color=arr, ambient=1.0,
                  specular=0.0, elev=40, azim=25)
    assert np.abs(a.rgba.astype(int) - r.rgba.astype(int)).max() <= 2


def _line_pixels(r, plain):
    """Where the picture with lines differs from the one without."""
    return np.abs(r.rgba[..., :3].astype(int) - plain.rgba[..., :3].astype(int)).max(-1) > 40


@pytest.mark.parametrize("opacity", [1.0, 0.99])
def test_a_colour_fields_nan_takes_the_colour_maps_bad_colour(opacity):
    """Where a colour field is NaN (an array's missing values, an expression's
    undefined ones) the surface takes the colour map's "bad" colour where one is set
    (``with_extremes(bad=...)``, ``set_bad``), as matplotlib colours a NaN: red at
    every pixel inside the NaN region, lit flat (they took the lower side's colour, or
    through a translucent surface its own). Without one it keeps its colour as before:
    the lower side's (opaque), the surface's own (translucent). Translucent within 6
    levels (the layer's alpha 0.99 over the background, the field's texture filtered:
    measured 2026-12-06, at most 4)."""
    import matplotlib
    cm = matplotlib.colormaps["viridis"].with_extremes(bad="red")
    C = np.add.outer(np.linspace(0, 1, 64), np.linspace(0, 1, 64))
    C[20:44, 20:44] = np.nan                          # u, v in about (-1.1, 1.1)
    kw = dict(u=(-3, 3), v=(-3, 3), size=(120, 90), elev=70, ambient=1.0, specular=0.0,
              antialias=False, opacity=opacity)
    for field, inside in ((C, lambda u, v: (np.abs(u) < 0.9) & (np.abs(v) < 0.9)),
                          ("sqrt(u*u + v*v - 1)", lambda u, v: u * u + v * v < 0.8)):
        red = fc.render("0*u", color=field, cmap=cm, **kw)
        where = (red.side != 0) & inside(red.u, red.v)
        assert where.sum() > 150
        got = red.rgba[where][:, :3].astype(int)
        assert np.abs(got - [255, 0, 0]).max() <= (0 if opacity == 1.0 else 6)
        plain = fc.render("0*u", color=field, cmap="viridis", **kw)
        want = [217, 146, 91] if opacity == 1.0 else [70, 4, 86]    # tan; viridis at 0
        assert np.abs(plain.rgba[where][:, :3].astype(int) - want).max() <= 1


def test_contours_lie_on_the_level_sets_of_f():
    """Contour pixels' true f (at the ray caster's hit) lies within 1.5 pixels' change
    of f of a level (measured: 100 % of 2179); the pixels within a quarter pixel of a
    level are drawn (measured 100 %)."""
    expr, dom = "3*sin(u*cos(v))", (-5, 5)
    kw = dict(u=dom, v=dom, size=(200, 150), elev=50, azim=20, contour_color="white")
    plain = fc.render(expr, **{k: x for k, x in kw.items() if k != "contour_color"})
    r = fc.render(expr, contours=[-2, -1, 0, 1, 2], **kw)
    ref = reference_for(r, expr, dom, dom, 50, 20, "orthographic")
    f = 3 * np.sin(ref.u * np.cos(ref.v))
    seen = (ref.side != 0) & (r.side == ref.side)
    # f's change per pixel at each hit (the truth's own screen gradient)
    gy, gx = np.gradient(np.where(seen, f, np.nan))
    grad = np.hypot(gx, gy)
    dist = np.abs(f - np.clip(np.rint(f), -2, 2)) / grad     # pixels to the nearest level
    line = _line_pixels(r, plain) & seen & np.isfinite(dist)
    assert line.sum() > 300
    assert (dist[line] <= 1.5).mean() >= 0.98
    near = seen & np.isfinite(dist) & (dist < 0.25) & (grad < 0.5)
    assert (line[near]).mean() >= 0.9


def test_wireframe_lines_at_constant_u_and_v():
    expr, dom = "exp(-(u*u+v*v))*2", (-2, 2)
    kw = dict(u=dom, v=dom, size=(200, 150), elev=35, azim=30, projection="perspective")
    plain = fc.render(expr, **kw)
    r = fc.render(expr, wireframe=(9, 5), edgecolor="red", linewidth=1.0, **kw)
    ref = reference_for(r, expr, dom, dom, 35, 30, "perspective")
    seen = (ref.side != 0) & (r.side == ref.side)
    line = _line_pixels(r, plain) & seen
    du = np.abs(ref.u - np.rint(ref.u / 0.5) * 0.5)          # 9 lines: 0.5 apart in u
    dv = np.abs(ref.v - np.rint(ref.v / 1.0) * 1.0)          # 5 lines: 1 apart in v
    gu = np.hypot(*np.gradient(np.where(seen, ref.u, np.nan)))
    gv = np.hypot(*np.gradient(np.where(seen, ref.v, np.nan)))
    near = np.minimum(du / gu, dv / gv)                     # pixels to the nearest line
    ok = line & np.isfinite(near)
    assert ok.sum() > 300
    assert (near[ok] <= 1.5).mean() >= 0.98                   # measured 100 % of 1030
    assert (r.rgba[line][:, 0] > r.rgba[line][:, 1]).mean() > 0.9      # red lines


def test_lines_are_hidden_where_the_surface_is():
    """A contour behind a hill is not drawn: every line pixel shows the seen surface's
    own level set (the nearest surface along the ray, not one behind it)."""
    expr = "2*exp(-(u*u+v*v))"
    kw = dict(u=(-3, 3), v=(-3, 3), size=(160, 120), elev=10, azim=0)
    plain = fc.render(expr, **kw)
    r = fc.render(expr, contours=[0.05], contour_width=1.0, contour_color="red", **kw)
    line = _line_pixels(r, plain)
    w = r.w
    assert line.any()
    assert np.nanmax(np.abs(w[line] - 0.05)) < 0.05


@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
def test_fill_false_draws_the_lines_alone_hidden_where_the_surface_is(proj):
    """fill=False: a hidden-line drawing. Over a transparent background each pixel is
    the lines' colour at the part of the pixel they cover, the same part as over the
    opaque surface (black lines over white: alpha equal to 1 - the grey level on every
    pixel; the lines along the domain's edges also on the pixels just off it where
    the edge buffer has the surface); the surface is not drawn (transparent elsewhere:
    68-70 % of its pixels);
    and the lines behind the hill are hidden: every line pixel's nearest surface point
    (the ray caster's) lies within 1.5 pixels of a grid line (measured 100 %), which
    a line drawn behind the hill would not (1005 and 979 line pixels)."""
    expr, dom = "2*exp(-(u*u+v*v))", (-2, 2)
    kw = dict(u=dom, v=dom, size=(200, 150), elev=15, azim=30, projection=proj,
              wireframe=(9, 9), edgecolor="black", linewidth=1.0)
    alone = fc.render(expr, fill=False, background=(0, 0, 0, 0), **kw)
    over = fc.render(expr, ambient=1.0, specular=0.0, upper_color="white",
                     lower_color="white", **kw)
    cov_over = 1.0 - over.rgba[..., :3].astype(float).mean(axis=-1) / 255.0
    seen = over.side != 0
    a = alone.rgba[..., 3].astype(float) / 255.0
    assert np.abs(a - cov_over)[seen].max() * 255 <= 1.5
    assert (alone.rgba[..., :3][a > 0] == 0).all()           # black lines
    assert a[seen].mean() > 0.05 and (a[seen] == 0).mean() > 0.5   # lines, and gaps
    from floatcol.objects import _dilate
    assert (a[~_dilate(seen)] == 0).all()
    # the lines along the domain's edges reach past the pixels whose centre is on the
    # surface where its edge surface is seen (section 6.4: their outer half)
    assert (a[~seen & _dilate(seen)] > 0.2).sum() > 20
    ref = reference_for(alone, expr, dom, dom, 15, 30, proj)
    ok = (ref.side != 0) & (alone.side == ref.side)
    line = ok & (a > 0.5)
    du = np.abs(ref.u - np.rint(ref.u / 0.5) * 0.5)          # 9 lines: 0.5 apart
    dv = np.abs(ref.v - np.rint(ref.v / 0.5) * 0.5)
    gu = np.hypot(*np.gradient(np.where(ok, ref.u, np.nan)))
    gv = np.hypot(*np.gradient(np.where(ok, ref.v, np.nan)))
    near = np.minimum(du / gu, dv / gv)
    line &= np.isfinite(near)
    assert line.sum() > 500
    assert (near[line] <= 1.5).mean() >= 0.99


def test_fill_false_draws_the_domains_edge_lines_whole():
    """A line along the domain's edge has its outer half on the pixels just off the
    surface: fill=False draws it there too, from the edge buffer at the ends of the
    columns' runs and, across the columns, where u or v carried on from the two pixels
    beside leaves the domain. A plane seen nearly along v (its left and right edges
    across the columns): the pixel just off each row's first and last on the surface
    covered more than 0.3 in 65 % of the rows (24 % before, the line's inner half
    alone: dashed)."""
    r = fc.render("0.3*u + 0*v", u=(-2, 2), v=(-2, 2), size=(200, 150), elev=30, azim=80,
                  wireframe=5, fill=False, background=(0, 0, 0, 0))
    a = r.rgba[..., 3] / 255.0
    seen = r.side != 0
    outer = []
    for i in range(seen.shape[0]):
        js = np.nonzero(seen[i])[0]
        if js.size and 0 < js[0] and js[-1] < seen.shape[1] - 1:
            outer += [a[i, js[0] - 1], a[i, js[-1] + 1]]
    outer = np.array(outer)
    assert outer.size > 200 and (outer > 0.3).mean() > 0.5


def test_fill_false_says_what_it_needs():
    kw = dict(u=(-1, 1), v=(-1, 1), size=(20, 15))
    with pytest.raises(ValueError, match="give wireframe= or contours="):
        fc.render("u*v", fill=False, **kw)
    with pytest.raises(ValueError, match="give opacity=1"):
        fc.render("u*v", fill=False, wireframe=5, opacity=0.5, **kw)
    with pytest.raises(ValueError, match="fill must be True or False"):
        fc.render("u*v", fill="no", wireframe=5, **kw)
    with pytest.raises(ValueError, match="render it by itself"):
        fc.render_many(["u*v", "u"], fill=False, wireframe=5, size=(20, 15))


def test_bad_texture_and_line_options_name_what_to_fix(tmp_path):
    kw = dict(u=(-1, 1), v=(-1, 1), size=(20, 15))
    for bad, match in ((np.zeros((4, 4)), "texture must be an image array"),
                       (np.full((4, 4, 3), 2.0), r"floats in \[0, 1\]"),
                       (str(tmp_path / "none.png"), "cannot be read"),
                       (lambda u, v: 1 / 0, "texture function failed")):
        with pytest.raises(ValueError, match=match):
            fc.render("u*v", texture=bad, **kw)
    big = np.broadcast_to(np.zeros((1, 1, 3), np.uint8), (9000, 8000, 3))   # (no memory)
    with pytest.raises(ValueError, match="more than 67108864"):
        fc.render("u*v", texture=big, **kw)
    (tmp_path / "bad.png").write_text("not an image")
    with pytest.raises(ValueError, match="cannot be read as an image"):
        fc.render("u*v", texture=str(tmp_path / "bad.png"), **kw)
    with pytest.raises(ValueError, match="texture_filter must be one of"):
        fc.render("u*v", texture=checker(8), texture_filter="cubic", **kw)
    with pytest.raises(ValueError, match="texture_extent"):
        fc.render("u*v", texture=checker(8), texture_extent=(0, 0, 1, 2), **kw)
    with pytest.raises(ValueError, match="contours must be"):
        fc.render("u*v", contours=[np.nan], **kw)
    with pytest.raises(ValueError, match="wireframe must be"):
        fc.render("u*v", wireframe=1, **kw)
    with pytest.raises(ValueError, match="linewidth must be"):
        fc.render("u*v", wireframe=4, linewidth=-1, **kw)
    with pytest.raises(ValueError, match="method='column'"):
        fc.render("u*v", contours=3, method="horizon", **kw)
    with pytest.raises(ValueError, match="either texture or color"):
        fc.render("u*v", texture=checker(8), color="u", **kw)


def _sub_rays(r, expr, dom, elev, azim, proj, n):
    """The ray caster's n rays across each pixel of render r, at the sub-columns'
    offsets (i + 1/2)/n - 1/2 (a picture n times as wide, its rows the same):
    (ray-cast picture, its (H, W, n) hits, the pixels whose rays and their vertical
    neighbours' all hit the surface)."""
    vw = r.view
    W, H = vw.width, vw.height
    ref = raycast(numpy_surface(expr), dom, dom, (W * n, H), elev, azim, proj, vw.d1, vw.d2,
                  vw.scale * n, center=vw.center, yscale=vw.scale)
    hit = (ref.side != 0).reshape(H, W, n)
    full = hit.all(-1)
    full[1:] &= hit[:-1].all(-1)
    full[:-1] &= hit[1:].all(-1)
    return ref, hit, full


@pytest.mark.parametrize("expr,dom,elev,azim,proj", [
    ("3*sin(u*cos(v))", (-5, 5), 30, 20, "orthographic"),
    ("exp(-(u*u+v*v))*2", (-2, 2), 45, -35, "perspective")])
def test_sub_columns_mix_a_textures_colours_across_the_pixel(expr, dom, elev, azim, proj):
    """antialias=3 with a texture: each pixel averages three whole pictures drawn at
    the sub-columns' offsets (vp's VP_XOFF; renderer._textured_columns), textured as
    the centre's. A point-filtered checkerboard, red and green: where the ray caster's
    three rays across a pixel see both colours (a checker edge), the pixel's part of
    red, r / (r + g), is their intensity-weighted part (measured mean error 0.0203 and
    0.0038 on 805 and 448 such pixels; antialias=True, which mixes nothing across the
    columns inside the surface, 0.278 and 0.332); where they see one colour, the pixel
    keeps it (99.204 % and 99.962 % within 0.1)."""
    n = 3
    kw = dict(u=dom, v=dom, size=(200, 150), elev=elev, azim=azim, projection=proj,
              texture=checker(), texture_filter="point", shading="lambert")
    for aa, bound in ((n, 0.03), (True, None)):
        r = fc.render(expr, antialias=aa, **kw)
        ref, hit, full = _sub_rays(r, expr, dom, elev, azim, proj, n)
        H, W = hit.shape[:2]
        cls = truth_checker(ref.u, ref.v, dom, dom).reshape(H, W, n)
        inten = np.nan_to_num(ref.intensity).reshape(H, W, n)
        red = (cls * inten).sum(-1) / np.maximum(inten.sum(-1), 1e-9)
        rgb = r.rgba[..., :3].astype(float)
        lit = rgb[..., 0] + rgb[..., 1] > 48
        mine = rgb[..., 0] / np.maximum(rgb[..., 0] + rgb[..., 1], 1e-9)
        mixed = full & lit & (cls.min(-1) != cls.max(-1))
        err = np.abs(mine - red)
        assert mixed.sum() > 300
        if bound is None:
            assert err[mixed].mean() > 0.25        # (the test tells them apart)
            continue
        assert err[mixed].mean() < bound, err[mixed].mean()
        pure = full & lit & (cls.min(-1) == cls.max(-1))
        assert (err[pure] < 0.1).mean() > 0.99


@pytest.mark.parametrize("n,proj", [(2, "orthographic"), (3, "perspective"), (4, "orthographic")])
def test_a_textures_sub_columns_are_the_sub_column_kernels(n, proj):
    """The two ways to draw sub-columns agree: a white texture's (whole pictures at
    each offset, textured and finished as the centre's) and a white surface's
    (kernels/antialias.py's kernel, a column at a time): within a level's rounding
    (measured at most 1 level on 2x, 3x and 4x, both projections), the same
    evaluations."""
    kw = dict(u=(-5, 5), v=(-5, 5), size=(200, 150), elev=30, azim=20, projection=proj,
              antialias=n, lower_color="white")
    plain = fc.render("3*sin(u*cos(v))", upper_color="white", **kw)
    textured = fc.render("3*sin(u*cos(v))", texture=np.full((4, 4, 3), 255, np.uint8), **kw)
    assert np.abs(plain.rgba.astype(int) - textured.rgba.astype(int)).max() <= 1
    assert textured.stats["samples"] == plain.stats["samples"]


@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
def test_a_colour_fields_sub_columns_share_the_centres_colour_map(proj):
    """antialias=3 with a colour field: each sub-column's picture is coloured on the
    centre picture's range of the field (stats["c_limits"], as antialias=True's), so
    a grey map of v^2 at full light is the mean of the grey the ray caster's three rays
    across the pixel find (measured 97.100 % and 96.909 % of the pixels within 3
    levels; the centre picture against its one ray, 96.670 % and 96.863 %: ridges,
    where the rays hit two sheets, and the colour table's steps)."""
    expr, dom, n = "3*sin(u*cos(v))", (-5, 5), 3
    kw = dict(u=dom, v=dom, size=(200, 150), elev=30, azim=20, projection=proj, color="v*v",
              cmap="gray", ambient=1.0, specular=0.0)
    r = fc.render(expr, antialias=n, **kw)
    assert r.stats["c_limits"] == fc.render(expr, **kw).stats["c_limits"]
    lo, hi = r.stats["c_limits"]
    ref, hit, full = _sub_rays(r, expr, dom, 30, 20, proj, n)
    H, W = hit.shape[:2]
    grey = np.clip((np.nan_to_num(ref.v) ** 2 - lo) / (hi - lo), 0, 1).reshape(H, W, n)
    d = np.abs(r.rgba[..., 0] - grey.mean(-1) * 255)[full & (r.side > 0)]
    assert d.size > 8000
    assert (d <= 3).mean() > 0.965


def test_holes_take_no_colour_and_no_lines():
    for kw in (dict(texture=checker(16)), dict(color="u*v")):
        r = fc.render("sqrt(1-u*u-v*v)", u=(-1.2, 1.2), v=(-1.2, 1.2), size=(80, 60),
                      contours=4, wireframe=6, **kw)
        empty = _interior(np.zeros(r.side.shape, int), r.side == 0)  # away from its edges
        assert (r.side != 0).any() and empty.any() and (r.rgba[empty] == 255).all()


@pytest.mark.parametrize("layout", ["xy", "ij", "y descending"])
def test_matplotlib_facecolors_follow_the_mesh(layout):
    """plot_surface(X, Y, Z, facecolors=...): each point's colour lands at its point,
    whichever way the mesh is laid out (red where x > 0, blue where x < 0; measured
    100 % of the pixels a tenth of the range away from x = 0)."""
    x = np.linspace(-2, 2, 41)
    y = np.linspace(-1, 3, 31)
    if layout == "y descending":
        y = y[::-1]
    X, Y = np.meshgrid(x, y, indexing="ij" if layout == "ij" else "xy")
    Z = np.sin(X) * np.cos(Y) * 0.5
    fcol = np.where((X > 0)[..., None], [1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0])
    p = fc.plot_surface(X, Y, Z, facecolors=fcol, size=(160, 120), shade=False)
    r = p.render if p.render is not None else p.draw()
    seen = _interior(np.zeros(r.side.shape, int), r.side != 0)   # whole pixels
    right, left = seen & (r.u > 0.2), seen & (r.u < -0.2)
    assert right.sum() > 500 and left.sum() > 500
    assert (r.rgba[right][:, 0] > 200).mean() > 0.99 and (r.rgba[right][:, 2] < 60).mean() > 0.99
    assert (r.rgba[left][:, 2] > 200).mean() > 0.99 and (r.rgba[left][:, 0] < 60).mean() > 0.99


PALETTE = np.array([[230, 25, 75], [60, 180, 75], [255, 225, 25], [0, 130, 200],
                    [145, 30, 180]], dtype=np.uint8)


@pytest.mark.parametrize("layout", ["xy", "ij", "y descending", "uneven", "strided",
                                    "counted", "one per face", "expression"])
def test_matplotlib_facecolors_colour_whole_faces(layout):
    """plot_surface(X, Y, Z, facecolors=...) colours each face of the mesh with the
    colour of its first corner, as mplot3d does (its checkerboard example, surface3d_3,
    was a blur of yellow and blue when the colours were read as a texture through the
    points). Against the analytic answer: the face that holds each pixel's seen (u, v).
    Pixels whose 5 x 5 neighbourhood lies in one face have that face's colour: 99.9 %
    within 2 levels, none more than 8 off (measured 2026-12-06: all of them 0 levels
    off, but for one pixel 5 off of the uneven mesh's 7 648, whose texels do not end
    where its faces do; with 3 x 3 neighbourhoods 99.9 % within 2, up to 17 off where
    the mip-map's footprint, long across the far faces, reaches the next face)."""
    rng = np.random.default_rng(5)
    x = np.linspace(-2.0, 2.0, 9)
    if layout == "uneven":
        x = -2.0 + 4.0 * (np.geomspace(1.0, 6.0, 9) - 1.0) / 5.0
    y = np.linspace(-1.5, 1.5, 7)
    pc = rng.integers(0, len(PALETTE), (7, 9))            # per point, rows along y
    rs, cs = {"strided": (2, 3), "counted": (3, 2)}.get(layout, (1, 1))
    # each face (row i along y, column j along x) takes the colour of its first
    # corner; with strides the first corner of its block of rs x cs cells
    face = pc[(np.arange(6) // rs) * rs][:, (np.arange(8) // cs) * cs]
    X, Y = np.meshgrid(x, y)
    Z = 0.3 * np.sin(X) * np.cos(Y)
    colours, kw = PALETTE[pc], dict(size=(240, 180), shade=False, elev=50, azim=-70)
    if layout == "ij":
        X, Y, Z, colours = X.T, Y.T, Z.T, colours.transpose(1, 0, 2)
    elif layout == "y descending":              # a north-up raster: row 0 the top
        X, Y, Z = X[::-1], Y[::-1], Z[::-1]
        down = np.zeros_like(pc)
        down[:-1, :-1] = face[::-1]             # its face i is the ascending face 5 - i
        colours = PALETTE[down]
    elif layout == "strided":
        kw.update(rstride=2, cstride=3)
    elif layout == "counted":                   # 7 rows / 3 -> 3; 9 columns / 5 -> 2
        kw.update(rcount=3, ccount=5)
    elif layout == "one per face":
        colours = PALETTE[face]
    if layout == "expression":
        p = fc.plot_surface("0.3*sin(x)*cos(y)", ("x", -2, 2), ("y", -1.5, 1.5),
                            facecolors=colours, **kw)
    else:
        p = fc.plot_surface(X, Y, Z, facecolors=colours, **kw)
    r = p.render if p.render is not None else p.draw()
    seen = r.side != 0
    fi = np.clip(np.searchsorted(y, np.nan_to_num(r.v), side="right") - 1, 0, 5)
    fj = np.clip(np.searchsorted(x, np.nan_to_num(r.u), side="right") - 1, 0, 7)
    inside = _interior(fi * 8 + fj, _interior(fi * 8 + fj, seen))
    assert inside.sum() > 3000
    want = PALETTE[face[fi, fj]].astype(int)
    off = np.abs(r.rgba[..., :3].astype(int) - want).max(axis=-1)
    assert (off[inside] <= 2).mean() >= 0.999 and off[inside].max() <= 8


def test_matplotlib_facecolors_on_a_polar_grid_colour_its_quads():
    """A curvilinear mesh's facecolors (matplotlib's surface3d_radial with a colour a
    quad): each quad's two triangles take its colour. Pixels whose 5 x 5 neighbourhood
    lies in one quad have its colour: 99 % within 2 levels, none more than 12 off
    (measured 2026-12-06: 99.65 %, 7 off at most; 7 x 7: all of them exactly). The
    colours are a texture at the resampled grid's nodes, a sixteenth of a mesh line
    apart, so its edges blur over a texel and the mip-map's footprint."""
    nr, npp = 6, 13
    r = np.linspace(0.2, 1.25, nr)
    p = np.linspace(0, 2 * np.pi, npp)
    R, P = np.meshgrid(r, p)                                # rows along the angle
    pc = np.random.default_rng(3).integers(0, len(PALETTE), R.shape)
    plot = fc.plot_surface(R * np.cos(P), R * np.sin(P), 0.2 * R ** 2,
                           facecolors=PALETTE[pc], size=(240, 180), shade=False, elev=70)
    rr = plot.render if plot.render is not None else plot.draw()
    u, v = np.nan_to_num(rr.u), np.nan_to_num(rr.v)
    rad, ang = np.hypot(u, v), np.mod(np.arctan2(v, u), 2 * np.pi)
    # the quad between angles k, k + 1 and radii l, l + 1 is bounded by straight rays
    # and chords: a point lies beyond the chord at radius r_l where its distance along
    # the sector's bisector exceeds r_l cos(half the sector)
    dp = p[1] - p[0]
    k = np.clip(np.floor(ang / dp).astype(int), 0, npp - 2)
    da = ang - k * dp
    s_ = rad * np.cos(da - dp / 2) / np.cos(dp / 2)
    l_ = np.searchsorted(r, s_, side="right") - 1
    ok = (rr.side != 0) & (l_ >= 0) & (l_ < nr - 1)
    l_ = np.clip(l_, 0, nr - 2)
    cls = k * (nr - 1) + l_
    ok = _interior(cls, _interior(cls, ok))
    assert ok.sum() > 4000
    want = PALETTE[pc[k, l_]].astype(int)
    off = np.abs(rr.rgba[..., :3].astype(int) - want).max(axis=-1)
    assert (off[ok] <= 2).mean() > 0.99 and off[ok].max() <= 12


def test_matplotlib_edges_are_a_wireframe():
    x = np.linspace(-3, 3, 60)
    X, Y = np.meshgrid(x, x)
    Z = np.sin(X) * np.cos(Y)
    p = fc.plot_surface(X, Y, Z, edgecolor="k", linewidth=0.72, rcount=15, ccount=10)
    assert p.options["wireframe"] == (10, 15) and p.options["linewidth"] == pytest.approx(1.0)
    p = fc.plot_surface(X, Y, Z, edgecolor="k", rstride=5, cstride=10)
    assert p.options["wireframe"] == (7, 13)          # every 10th of 60 columns, 5th row
    for kw in (dict(), dict(linewidth=0, edgecolor="k"), dict(edgecolor="none", rcount=5)):
        assert "wireframe" not in fc.plot_surface(X, Y, Z, **kw).options


def test_wireframe_lines_in_a_stretched_box():
    """In matplotlib's 3-D box (u, v and w stretched) the lines stay at the same u:
    the picture's line pixels have u near a multiple of 0.5 as in true proportions."""
    kw = dict(u=(-2, 2), v=(-2, 2), size=(160, 120), wireframe=(9, 9), linewidth=1.0)
    for aspect in ("equal", (3.0, 1.0, 2.0)):
        plain = fc.render("u*v/4", **{k: x for k, x in kw.items()
                                      if k not in ("wireframe", "linewidth")}, aspect=aspect)
        r = fc.render("u*v/4", aspect=aspect, **kw)
        line = _line_pixels(r, plain) & (r.side != 0)
        du = np.abs(r.u - np.rint(r.u / 0.5) * 0.5)
        dv = np.abs(r.v - np.rint(r.v / 0.5) * 0.5)
        gu = np.hypot(*np.gradient(r.u))                   # u's change per pixel
        gv = np.hypot(*np.gradient(r.v))
        near = np.minimum(du / gu, dv / gv)                # pixels to the nearest line
        ok = line & np.isfinite(near)
        assert ok.sum() > 200
        assert (near[ok] <= 1.5).mean() > 0.97             # measured 100 % both


def test_colour_field_in_plot_surface_sets_the_colorbar():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    p = fc.plot_surface("sin(x)*cos(y)", ("x", -3, 3), ("y", -3, 3), ax=ax,
                        color_field="sqrt(x**2 + y**2)", cmap="magma")
    assert p.norm.vmin == pytest.approx(0.0, abs=1e-9)
    assert p.norm.vmax == pytest.approx(np.sqrt(18), rel=1e-6)
    cb = fig.colorbar(p, ax=ax)
    fig.canvas.draw()
    assert cb.vmax == pytest.approx(np.sqrt(18), rel=1e-6)
    assert p.render.stats["c_limits"] == pytest.approx((0.0, np.sqrt(18)), rel=1e-6)
    plt.close(fig)


def test_cli_texture_colour_and_lines(tmp_path, capsys, monkeypatch):
    from PIL import Image

    from floatcol.cli import main
    Image.fromarray(checker(32)).save(tmp_path / "tex.png")
    monkeypatch.chdir(tmp_path)
    base = ["render", "3*sin(x*cos(y))", "--x=-5:5", "--y=-5:5", "--size", "160x120"]
    assert main(base + ["-o", "plain.png"]) == 0
    for extra in (["--texture", "tex.png"], ["--color-by", "x*y", "--contours", "6"],
                  ["--wireframe", "12"], ["--wireframe", "12", "--lines-only"]):
        assert main(base + extra + ["-o", "out.png"]) == 0
        a = np.asarray(Image.open(tmp_path / "out.png"))
        b = np.asarray(Image.open(tmp_path / "plain.png"))
        assert a.shape == b.shape and (np.abs(a.astype(int) - b).max(-1) > 30).mean() > 0.02
    # --lines-only: the lines over the white background, no surface
    assert (a[..., :3].min(-1) > 250).mean() > 0.8
    capsys.readouterr()
    for extra, match in ((["--texture", "none.png"], "cannot be read"),
                         (["--contours", "0"], "contours must be from 1"),
                         (["--lines-only"], "give --wireframe or --contours"),
                         (["--color-by", "__import__('os')"], "not allowed")):
        try:
            code = main(base + extra + ["-o", "bad.png"])
        except SystemExit as e:                     # (argparse's own errors)
            code = e.code
        err = capsys.readouterr().err.strip()
        assert code == 2 and match in err and len(err.splitlines()) == 1
        assert not (tmp_path / "bad.png").exists()


def test_a_translucent_surface_keeps_its_texture():
    """opacity < 1: each layer takes the texture at its own (u, v) (the mip level from
    the pixel's footprint at the point). A plane at opacity 0.5 over black is half the
    opaque textured plane's colour (measured: within 2.5 levels on 100 % of the 5682
    whole pixels away from the checker's edges), its squares where the opaque one's
    are."""
    kw = dict(u=(-2, 2), v=(-2, 2), size=(160, 120), elev=35, azim=25, ambient=1.0,
              specular=0.0, background="black", texture=checker(64))
    opaque = fc.render("0*u + 0.2*v", **kw)
    half = fc.render("0*u + 0.2*v", opacity=0.5, **kw)
    # whole pixels away from the checker's edges (the two paths filter edges alike but
    # not identically: the layers' mip level comes from the footprint at the point)
    squares = np.where(opaque.side != 0, truth_checker(opaque.u, opaque.v, (-2, 2),
                                                       (-2, 2), 64), -1)
    inside = _interior(squares, opaque.side != 0)
    diff = np.abs(half.rgba[..., :3].astype(float) * half.rgba[..., 3:4] / 255.0
                  - 0.5 * opaque.rgba[..., :3].astype(float))[inside].max(-1)
    assert inside.sum() > 3000 and (diff <= 2.5).mean() > 0.99
    # red and green squares, as the opaque one
    assert (half.rgba[inside][:, 0] > half.rgba[inside][:, 1]).mean() == pytest.approx(
        (opaque.rgba[inside][:, 0] > opaque.rgba[inside][:, 1]).mean(), abs=0.01)


@pytest.mark.parametrize("how", ["texture", "color"])
def test_silhouette_pixels_take_the_texture_too(how):
    """An antialiased silhouette pixel blends two surfaces (section 6.4): the one at
    its centre and the edge surface (the ebuf carries its u, v). With a uniformly red
    texture (or a colour field of one value through a red colormap), flat colours over
    white, every pixel is a blend of red and white: no colormap colour anywhere, not
    even in the edge pixels (before the ebuf carried u, v they kept viridis)."""
    from matplotlib.colors import ListedColormap
    red = np.zeros((4, 4, 3), dtype=np.uint8)
    red[..., 0] = 255
    kw = dict(u=(-5, 5), v=(-5, 5), size=(200, 150), elev=20, azim=30, ambient=1.0,
              specular=0.0, background="white", lower_color="red")
    if how == "texture":
        r = fc.render("3*sin(u*cos(v))", texture=red, **kw)
    else:
        r = fc.render("3*sin(u*cos(v))", color="1 + 0*u", vmin=0, vmax=2,
                      cmap=ListedColormap([(1, 0, 0)] * 3), **kw)
    rgb = r.rgba[..., :3].astype(int)
    partial = (r.rgba[..., 3] == 255) & (rgb[..., 1] < 250) & (rgb[..., 1] > 5)
    assert partial.sum() > 50                     # antialiased edge pixels exist
    assert (np.abs(rgb[..., 1] - rgb[..., 2]) <= 2).all()       # red + white only
    assert (rgb[..., 0] >= rgb[..., 1] - 2).all()


def test_a_translucent_surface_keeps_its_texture_function():
    """opacity < 1 with a texture function: its colours sampled on a 1024 x 1024 grid
    over the extent and read as a texture by every layer (it was a ValueError). The
    checker as a function on a plane at opacity 0.5 over black is half the opaque
    plane's colour with the same function (which calls it at each pixel's point):
    measured within 2.5 levels on 96.9 % of the 5522 whole pixels away from the
    squares' edges, 13.5 at most (far off, where the grid's mip-map blends a square
    with its neighbours over the pixel's footprint: the function has no filter); and
    its transparent half shows the surface's own colour, as opaque."""
    def fn(u, v):
        k = truth_checker(u, v, (-2, 2), (-2, 2), 64)
        return np.stack([k * 1.0, 1.0 - k, np.full(k.shape, 64 / 255),
                         np.where(v > 0, 1.0, 0.0)], axis=-1)
    kw = dict(u=(-2, 2), v=(-2, 2), size=(160, 120), elev=35, azim=25, ambient=1.0,
              specular=0.0, background="black", texture=fn, texture_filter="point")
    opaque = fc.render("0*u + 0.2*v", **kw)
    half = fc.render("0*u + 0.2*v", opacity=0.5, **kw)
    squares = np.where(opaque.side != 0, truth_checker(opaque.u, opaque.v, (-2, 2),
                                                       (-2, 2), 64), -1)
    inside = _interior(squares, opaque.side != 0) & (np.abs(np.nan_to_num(opaque.v)) > 0.1)
    diff = np.abs(half.rgba[..., :3].astype(float) * half.rgba[..., 3:4] / 255.0
                  - 0.5 * opaque.rgba[..., :3].astype(float))[inside].max(-1)
    assert inside.sum() > 3000 and (diff <= 2.5).mean() > 0.95 and diff.max() < 20
    # the textured half (red or green squares) and the bare half (the colormap's colour)
    top = inside & (opaque.v > 0)
    assert (np.abs(half.rgba[top][:, 0].astype(int) - half.rgba[top][:, 1]) > 40).mean() > 0.99
    assert top.sum() > 1000 and (inside & (opaque.v < 0)).sum() > 1000


def test_a_translucent_surface_keeps_its_colour_field():
    """opacity < 1 with color=: the field sampled on a 1024 x 1024 grid and read as a
    texture by every layer. A plane at opacity 0.5 over black is half the opaque
    plane's colour (measured: within 1 level on 100 % of the 8822 whole pixels)."""
    kw = dict(u=(-2, 2), v=(-2, 2), size=(160, 120), elev=35, azim=25, ambient=1.0,
              specular=0.0, background="black", color="u + v", vmin=-4, vmax=4)
    opaque = fc.render("0*u + 0.2*v", **kw)
    half = fc.render("0*u + 0.2*v", opacity=0.5, **kw)
    inside = _interior(np.zeros(opaque.side.shape, int), opaque.side != 0)
    diff = np.abs(half.rgba[..., :3].astype(float) * half.rgba[..., 3:4] / 255.0
                  - 0.5 * opaque.rgba[..., :3].astype(float))[inside].max(-1)
    assert inside.sum() > 3000 and (diff <= 3.0).mean() > 0.99

"""Exact area sampling along the columns (antialias="area", Cohen-Or 1997): against an
analytic coverage, against the ray caster box-filtered along each column
(tests/reference.py raycast_column_box: 8 rays a pixel), and in motion against point
sampling on a dense fractal DEM (Cohen-Or's flicker measure)."""
import numpy as np
import pytest
from matplotlib.colors import LinearSegmentedColormap

import floatcol as fc
from floatcol.passes.area import _halve, levels
from conftest import assert_plane_edges, plane
from reference import fractal, numpy_surface, raycast, raycast_column_box, table6


def test_plane_edges_cover_the_analytic_fraction():
    # w = 0 on [-1, 1]^2 seen at elev 30: the far edge at screen y = 0.5, the near one
    # at -0.5: their pixels are covered 0.65 each (as test_antialias's coverage test)
    assert_plane_edges(plane("area"))


@pytest.mark.parametrize("expr, dom, projection, elev, azim", [
    ("3*sin(u*cos(v))", (-5, 5), "orthographic", 30, 20),
    ("3*sin(u*cos(v))", (-5, 5), "perspective", 30, 20),
    # a hole in the middle (r < 1), where the run ends (bisected)
    ("sin(u)*cos(v)*sqrt(u**2 + v**2 - 1)/sqrt(u**2 + v**2 - 1)", (-3, 3), "perspective", 25,
     35),
])
def test_pixels_are_the_column_box_filter_of_the_ray_caster(expr, dom, projection, elev, azim):
    size = (96, 72)
    r = fc.render(expr, u=dom, v=dom, size=size, elev=elev, azim=azim, projection=projection,
                  shading="lambert", antialias="area", background=(0, 0, 0, 0))
    vw = r.view
    ref, cover = raycast_column_box(numpy_surface(expr), dom, dom, size, elev, azim, projection,
                                    vw.d1, vw.d2, vw.scale, center=vw.center, k=16)
    alpha = r.rgba[..., 3] / 255.0
    whole = (cover == 1) & (alpha == 1)
    # the picture's grey level (lambert: the intensity): at a silhouette the pixel's
    # surface (r.intensity) is the nearest piece's, the picture blends both surfaces
    # (against the reference rounded to the picture's 8 bits as the picture is)
    err = np.abs(r.rgba[..., 0] / 255.0 - np.round(np.nan_to_num(ref) * 255.0) / 255.0)[whole]
    # measured (96x72, 16 rays a pixel): 3 sin(u cos v) ortho 99.39 % within 0.02, mean
    # 0.00087; persp 99.16 %, 0.00131; the hole 100 %, 0.00065 (r.intensity, when it
    # was the mean of all the pieces: 99.23 %, 99.03 %, 100 %). Part of it is the
    # reference's: with 8 rays 98.4 %, 97.1 %, 99.5 %; with 32 on the first 99.7 %
    assert whole.sum() > 1000
    assert (err <= 0.02).mean() >= 0.985
    assert err.mean() <= 0.002
    # coverage: the rays' share that hits (steps of 1/16) against the pixel's alpha,
    # over the pixels either shows: measured mean 0.0008, 0.0012, 0.0015; the largest
    # 0.085, 0.412 (one pixel at a fold's silhouette in perspective), 0.036
    seen = (cover > 0) | (alpha > 0)
    assert np.abs(alpha - cover)[seen].mean() <= 0.003
    assert np.abs(alpha - cover)[seen].max() <= 0.45


def test_a_dense_dem_flickers_far_less_than_point_sampling():
    """Cohen-Or's Table 6 measure: pixels changing by 6 to 60 grey levels between
    frames of a slow orbit (0.02 deg a frame), a 257^2 fractal DEM at 120x90."""
    hf = fc.HeightField(fractal(257) * 15, u=(0, 500), v=(0, 500))
    base = fc.render(hf, size=(120, 90), elev=25, azim=30, projection="perspective")
    kw = dict(size=(120, 90), elev=25, projection="perspective", scale=base.view.scale,
              center=base.view.center, d1=base.view.d1, d2=base.view.d2)

    def flicker(aa):
        return table6([fc.render(hf, azim=30 + 0.02 * k, antialias=aa, **kw).rgba
                       for k in range(8)])

    point, area = flicker(False), flicker("area")
    # measured: point 1567, area 22 (0.014x; 0.05 deg a frame: 3085, 180, 0.058x)
    assert point > 800
    assert area <= 0.1 * point


def test_holes_in_a_dem_stay_holes():
    z = fractal(65) * 3
    z[20:40, 25:45] = np.nan
    r = fc.render(fc.HeightField(z), elev=90, azim=0, size=(130, 130), antialias="area",
                  background=(0, 0, 0, 0))
    col, row = r.view.project(np.array([35.0]), np.array([30.0]), np.array([0.0]))
    assert r.side[int(round(row[0])), int(round(col[0]))] == 0      # the hole's middle
    assert (r.side != 0).mean() > 0.5
    assert np.isfinite(r.intensity[r.side != 0]).all()


def test_the_pyramid_keeps_the_extent_and_smooths():
    z = fractal(129)
    hf = fc.HeightField(z, u=(0, 10), v=(0, 20))
    flat, lv = levels(hf)
    assert lv.shape[0] == 8                       # 129 -> 65 -> ... -> 2
    assert list(lv[:, 2]) == [129, 65, 33, 17, 9, 5, 3, 2]
    assert np.allclose(lv[:, 3], [20 / 128 * 2 ** k for k in range(7)] + [20.0])
    one = flat[int(lv[1, 0]):int(lv[1, 0] + 65 * 65)].reshape(65, 65)
    assert np.allclose(one.mean(), z.mean(), atol=0.05)
    assert one.std() < z.std()
    # a stretched copy (render's aspect) shares the source's pyramid, heights scaled
    flat2, _ = levels(hf.scaled(1.0, 1.0, 3.0))
    assert np.allclose(flat2, 3 * flat)
    # NaN-aware: a hole of one node fills from its neighbours, a wide one stays
    z = np.ones((9, 9))
    z[4, 4] = np.nan
    z[0:4, 0:4] = np.nan
    h = _halve(z)
    assert h.shape == (5, 5) and np.isfinite(h[2, 2]) and np.isnan(h[0, 0])


def test_the_heights_are_kept_once():
    """A height field's heights, and a stretched copy's (fc.terrain's exaggeration), are
    their pyramids' level 0 once the pyramid is made: the same values, no second copy
    (a 4097^2 DEM from its file to a fly view: peak 1.40 -> 1.10 GB, 1.03 -> 0.72 GB
    held after)."""
    z = fractal(65)
    z[3, 4] = np.nan
    hf = fc.HeightField(z.copy(), u=(0, 10), v=(0, 10))
    tall = hf.scaled(1.0, 1.0, 3.0)
    want, want_tall = hf.hf.copy(), tall.hf.copy()
    flat, lv = levels(hf)
    assert np.shares_memory(hf.hf, flat)
    assert np.array_equal(hf.hf, want, equal_nan=True)
    flat3, _ = levels(tall)
    assert np.shares_memory(tall.hf, flat3) and not np.shares_memory(flat3, flat)
    assert np.array_equal(tall.hf, want_tall, equal_nan=True)
    # and its pictures are those of a copy that was never stretched from a source
    kw = dict(size=(80, 60), elev=30, azim=20, antialias="area")
    alone = fc.HeightField(want_tall, u=(0, 10), v=(0, 10))
    assert np.array_equal(fc.render(tall, **kw).rgba, fc.render(alone, **kw).rgba)


def _smooth_by_index(z, axis):
    """The (1, 2, 1)/4 filter written plainly (the pyramid's first version: copies by
    index, the weights of the finite nodes always), the reference for its sliced one."""
    ok = np.isfinite(z)
    zz = np.where(ok, z, 0.0)
    w = ok.astype(np.float64)

    def filt(a):
        p = np.concatenate([np.take(a, [0], axis), a, np.take(a, [-1], axis)], axis)
        n = a.shape[axis]
        return (np.take(p, range(0, n), axis) + 2 * np.take(p, range(1, n + 1), axis)
                + np.take(p, range(2, n + 2), axis))
    s, k = filt(zz), filt(w)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(k > 0, s / np.where(k > 0, k, 1.0), np.nan)


def _resample_by_index(z, axis, m):
    """The pyramid's resampling written for any count (copies by index), the
    reference for its sliced every-other-node case."""
    n = z.shape[axis]
    x = np.linspace(0.0, n - 1.0, m)
    i0 = np.minimum(np.floor(x).astype(int), n - 2)
    shape = [1, 1]
    shape[axis] = m
    f = (x - i0).reshape(shape)
    a, b = np.take(z, i0, axis), np.take(z, i0 + 1, axis)
    with np.errstate(invalid="ignore"):
        return np.where(np.isfinite(a) & np.isfinite(b), a * (1 - f) + b * f,
                        np.where(f < 0.5, a, b))


@pytest.mark.parametrize("shape", [(1, 1), (1, 6), (7, 1), (2, 2), (3, 8), (65, 64), (129, 97),
                                   (4097, 5)])
@pytest.mark.parametrize("holes", [None, "nan", "inf"])
def test_the_pyramid_is_the_plain_filter_bit_for_bit(shape, holes):
    """The pyramid's filter by slices (and without weights where every node is
    finite) gives the plain filter's values bit for bit, signs of zero included; the
    block maxima by strided maxima those of each block's reshaped maximum."""
    from floatcol.passes import lod as P
    from floatcol.passes.area import _resample, _smooth
    rng = np.random.default_rng(sum(shape))
    z = rng.normal(size=shape) * 50.0
    z[rng.random(shape) < 0.1] = -0.0
    if holes is not None:
        z[rng.random(shape) < 0.2] = np.nan if holes == "nan" else -np.inf
    for axis in (0, 1):
        a, b = _smooth(z, axis), _smooth_by_index(z, axis)
        assert np.array_equal(a, b, equal_nan=True)
        assert np.array_equal(np.signbit(a), np.signbit(b))
        # every other node of an odd count by slices: the general resampling's values
        n = z.shape[axis]
        if n > 2 and n % 2:
            m = (n - 1) // 2 + 1
            a, b = _resample(z, axis, m), _resample_by_index(z, axis, m)
            assert np.array_equal(a, b, equal_nan=True)
            assert np.array_equal(np.signbit(a), np.signbit(b))
    if min(shape) < 2:
        return
    hf = fc.HeightField(z, u=(0, 10), v=(0, 7))
    flat, lv = levels(hf)
    mx, mt = P.block_maxima(hf)
    for k in range(lv.shape[0]):
        o, nv, nu = (int(x) for x in lv[k, :3])
        g = flat[o:o + nv * nu].reshape(nv, nu)
        g = np.where(np.isfinite(g), g, -np.inf)
        cells = np.maximum(np.maximum(g[:-1, :-1], g[:-1, 1:]), np.maximum(g[1:, :-1], g[1:, 1:]))
        for m in range(1, P.BLOCK_LEVELS):
            r, c = cells.shape
            cells = np.pad(cells, ((0, r % 2), (0, c % 2)), constant_values=-np.inf)
            cells = cells.reshape(cells.shape[0] // 2, 2, cells.shape[1] // 2, 2).max(
                axis=(1, 3))
            off, rows, cols = (int(x) for x in mt[k * P.BLOCK_LEVELS + m])
            assert (rows, cols) == cells.shape
            assert np.array_equal(mx[off:off + rows * cols].reshape(rows, cols), cells)


def test_errors():
    with pytest.raises(ValueError, match="antialias='area' applies to method='column'"):
        fc.render("u*v", method="horizon", antialias="area")
    with pytest.raises(ValueError, match="opacity=1"):
        fc.render("u*v", opacity=0.5, antialias="area")
    with pytest.raises(ValueError, match="'area'"):
        fc.render("u*v", antialias="areas")


def test_a_view_deeper_than_its_planes_allow_steps_wider():
    """A domain of 11.5 by 1e300 seen along its long side: a pixel's footprint is
    1e-301 of the depth. The column pass caps its planes at 40 000 (view.py); the area
    pass's steps grow likewise (kernels/area.py MAX_PLANES): measured 9.6 million
    evaluations, 0.4 s (a step of a footprint, floored at 1/1000 of the column pass's:
    2.4 billion, 93 s, a hang to the fuzzer). The plane is seen edge-on: it covers
    nothing, as in the column pass's picture."""
    from floatcol.kernels.area import MAX_PLANES
    kw = dict(u=(-6.241, 5.246), v=(1e9, 1e300), size=(64, 120), elev=0, azim=0)
    r = fc.render("2.5", antialias="area", **kw)
    assert 64 * 1000 <= r.stats["samples"] <= 64 * 2 * MAX_PLANES
    assert not (r.side != 0).any() and not (fc.render("2.5", **kw).side != 0).any()


#: a colour map whose middle (green) neither end has: a pixel that mixes a high and a
#: low surface must mix red and blue, not take green, the colour of their mean height
RGB = LinearSegmentedColormap.from_list("rgb", [(1, 0, 0), (0, 1, 0), (0, 0, 1)])
PLATEAU = "1/(1 + exp(6*(sqrt(u**2 + v**2) - 2)))"      # a flat top 1 high, 2 wide


def _silhouette_green(r, funcs, dom, k=16):
    """(pixels where the plateau's rim is seen against the plain behind it, the green
    share g / (r + g + b) of r's colour there, the reference's: the mean share of the
    colours of k rays a pixel up its column, each ray's colour by its hit's height)."""
    vw = r.view
    W, H = vw.width, vw.height
    ref = raycast(funcs, dom, dom, (W, H * k), vw.elev, vw.azim,
                  "orthographic" if vw.orthographic else "perspective", vw.d1, vw.d2,
                  vw.scale, center=vw.center, yscale=vw.scale * k)
    hit = ref.side != 0
    w = np.where(hit, funcs[0](np.nan_to_num(ref.u), np.nan_to_num(ref.v)), np.nan)
    col = RGB(np.clip(np.nan_to_num(w), 0, 1))[..., :3]
    share = np.where(hit, col[..., 1] / col.sum(-1), np.nan).reshape(H, k, W)
    w = w.reshape(H, k, W)
    rim = np.zeros((H, W), bool)
    seen = hit.reshape(H, k, W).any(axis=1)
    rim[seen] = ((np.nanmax(w, axis=1, initial=-1, where=~np.isnan(w)) > 0.8)
                 & (np.nanmin(w, axis=1, initial=2, where=~np.isnan(w)) < 0.2))[seen]
    rim &= r.side != 0
    ref_share = np.nanmean(np.where(rim[:, None, :], share, 0.0), axis=1)
    rgb = r.rgba[..., :3].astype(float)
    return rim, rgb[..., 1] / np.maximum(rgb.sum(-1), 1.0), ref_share


@pytest.mark.parametrize("projection", ["orthographic", "perspective"])
def test_a_silhouette_pixel_mixes_the_colours_of_its_surfaces(projection):
    """The rim of a plateau (height 1, blue) seen against the plain (0, red) behind it:
    each silhouette pixel holds both, and must show a mix of their colours, not the
    colour map at their mean height (green; it did, as dark outlines along every
    ridge of an area-sampled terrain)."""
    dom = (-8, 8)
    r = fc.render(PLATEAU, u=dom, v=dom, size=(120, 90), elev=10, azim=10,
                  projection=projection, specular=0.0, cmap=RGB, vmin=0, vmax=1,
                  antialias="area", background=(0, 0, 0, 0))
    rim, green, ref = _silhouette_green(r, numpy_surface(PLATEAU), dom)
    # measured: 20 (orthographic) and 16 (perspective) rim pixels; green share 0.030 and
    # 0.018 against the reference's 0.029 and 0.016, at most 0.009 above it (the colour
    # of the mean height: 0.480 and 0.716, up to 0.750 and 0.937 above it)
    assert rim.sum() >= 12
    assert (green - ref)[rim].max() <= 0.05
    assert green[rim].mean() <= ref[rim].mean() + 0.03

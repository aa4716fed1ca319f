"""The level-of-detail engine of fly-throughs (sampling="lod", passes/lod.py): against
the ray caster where the pyramid's level is the grid itself, its samples set by the
footprint and not by the grid, Cohen-Or's flicker measure in motion, where it hands
a view to the column pass, and its option errors."""
import numpy as np
import pytest

import floatcol as fc
from reference import bilinear_surface, fractal, raycast, table6


def _fly_scene(n=65):
    z = fractal(n, seed=5) * 30
    ext = 40.0 * (n - 1)
    hf = fc.HeightField(z, u=(0, ext), v=(0, ext))
    kw = fc.fly(hf, (0.3 * ext, 0.1 * ext), heading=25, pitch=-12, fov=60, size=(160, 90),
                above=60)
    # (the lod engine's point samples too: fc.fly's default draws those by the ray
    # march, test_march.py)
    return z, ext, hf, dict(kw, sampling="lod")


@pytest.fixture(scope="module")
def fly_reference():
    """_fly_scene's point-sampled lod picture's ray-caster reference."""
    z, ext, hf, kw = _fly_scene()
    vw = fc.render(hf, antialias=False, **kw).view
    ref = raycast(bilinear_surface(z, (0, ext), (0, ext)), (0, ext), (0, ext), (160, 90),
                  vw.elev, vw.azim, "perspective", vw.d1, vw.d2, vw.scale, center=vw.center,
                  steps=3000)
    return hf, kw, ref


def _against(r, ref):
    """(sides agreeing, intensities within 0.02 where both show the surface, their
    mean error, pixels where both do)."""
    both = (r.side != 0) & (ref.side != 0)
    err = np.abs(r.intensity - ref.intensity)[both]
    return ((r.side != 0) == (ref.side != 0)).mean(), (err <= 0.02).mean(), err.mean(), both.sum()


def test_fly_views_take_the_lod_engine_close_to_the_ray_caster(fly_reference):
    hf, kw, ref = fly_reference
    r = fc.render(hf, antialias=False, shading="lambert", background=(0, 0, 0, 0), **kw)
    assert r.stats["geometry"] == "lod"
    agree, close, mean, both = _against(r, ref)
    # measured (160x90, cells of 40 units, the pyramid's level 0 throughout): sides
    # 99.965 %, 97.29 % of the intensities within 0.02, mean 0.0044 (97.47 %, 0.0042
    # with lod.CROSS_ROWS 0.05; the exact column
    # pass with adaptive planes: 99.972 %, 98.80 %, 0.0012). What remains is at
    # silhouettes of ridges, a pixel off where the top falls between two planes.
    assert both > 10000
    assert agree >= 0.999
    assert close >= 0.965
    assert mean <= 0.006


def test_levels_blend_over_the_middle_of_their_span():
    """lod.level_blend: at band 1 a mip-map's trilinear level and blend; at the
    engines' BLEND_BAND (brilinear) each level alone over the outer parts of its span,
    the blend squeezed into the middle, the level k + a still continuous and rising
    in lf (nothing pops); and a fly view's plane table takes it."""
    from floatcol.kernels.layout import SURF_HEIGHTFIELD
    from floatcol.kernels.lod import BLEND_BAND, level_blend, plane_table
    from floatcol.passes.area import LOD_BIAS, levels
    n_lv = 6
    lfs = np.linspace(0.0, 7.0, 7001)
    tri = np.array([level_blend(x, n_lv, 1.0) for x in lfs])
    assert np.array_equal(tri[:, 0], np.minimum(np.floor(lfs), n_lv - 1))
    assert np.allclose(tri[:, 1], np.where(lfs < n_lv - 1, lfs - np.floor(lfs), 0.0))
    assert BLEND_BAND == 0.5
    bri = np.array([level_blend(x, n_lv, BLEND_BAND) for x in lfs])
    frac = lfs - np.floor(lfs)
    inside = lfs < n_lv - 1
    alone = inside & ((frac <= 0.25) | (frac >= 0.75))
    assert np.all(bri[alone, 1] == 0.0)                  # one level: one lookup
    assert np.array_equal(bri[alone & (frac <= 0.25), 0], np.floor(lfs[alone & (frac <= 0.25)]))
    assert np.array_equal(bri[alone & (frac >= 0.75), 0],
                          np.floor(lfs[alone & (frac >= 0.75)]) + 1)
    mid = inside & (frac > 0.26) & (frac < 0.74)
    assert np.allclose(bri[mid, 1], 2.0 * frac[mid] - 0.5)
    assert np.array_equal(bri[mid, 0], np.floor(lfs[mid]))
    level = bri[:, 0] + bri[:, 1]
    assert np.all(np.diff(level) >= 0.0)
    assert np.max(np.diff(level)) <= 2.0 * (lfs[1] - lfs[0]) + 1e-12      # continuous
    assert np.all(bri[~inside] == [n_lv - 1, 0.0])
    # a fly view over a dense DEM: about half its planes blend two levels
    hf = dense_dem()
    r = fc.render(hf, **fc.fly(hf, (600, 200), heading=20, pitch=-12, fov=60, size=(160, 90),
                               above=60))
    _, lv = levels(hf)
    planes = plane_table(SURF_HEIGHTFIELD, lv, r.view.params(), 2.0 ** LOD_BIAS, 1.0, 0.0)
    past0 = planes[:, 1] + planes[:, 2] > 0.0                # (level 0 alone nearest)
    assert past0.sum() > 100
    assert 0.4 <= (planes[past0, 2] > 0.0).mean() <= 0.6


def test_samples_follow_the_footprint_not_the_grid():
    counts = {}
    for n in (257, 1025):
        hf = fc.HeightField(fractal(n, seed=4) * 20, u=(0, 2000), v=(0, 2000))
        kw = fc.fly(hf, (600, 200), heading=20, pitch=-12, fov=60, size=(160, 90), above=60)
        kw["sampling"] = "lod"
        counts[n] = fc.render(hf, antialias=False, **kw).stats["samples"]
        if n == 1025:
            exact = fc.render(hf, antialias=False, **dict(kw, sampling="adaptive"))
            assert exact.stats["geometry"] == "column"
            counts["exact"] = exact.stats["samples"]
    # measured: 102 882 and 122 376 evaluations; the exact pass 1 202 697 on 1025^2
    assert counts[1025] <= 1.3 * counts[257]
    assert counts[1025] <= 0.2 * counts["exact"]


def dense_dem():
    """The flicker tests' dense 1025^2 fractal DEM."""
    return fc.HeightField(fractal(1025, seed=9) * 20, u=(0, 2000), v=(0, 2000))


def turn_flicker(hf, geometry=None, **kw):
    """Cohen-Or's Table 6 measure (reference.py table6) over a slow turn of a fly
    camera (0.02 deg a frame) above hf, each frame rendered with kw (its sampling
    replacing fly's); ``geometry``: the engine each frame must be drawn by."""
    frames = []
    for k in range(8):
        cam = fc.fly(hf, (600, 200), heading=20 + 0.02 * k, pitch=-12, fov=60,
                     size=(160, 90), above=60)
        r = fc.render(hf, **dict(cam, **kw))
        if geometry is not None:
            assert r.stats["geometry"] == geometry
        frames.append(r.rgba)
    return table6(frames)


def test_area_weights_flicker_less_than_point_sampling():
    """Cohen-Or's Table 6 measure over a slow turn above a dense DEM (turn_flicker)."""
    hf = dense_dem()
    point = turn_flicker(hf, antialias=False, sampling="adaptive")
    lod_point = turn_flicker(hf, antialias=False, sampling="lod")
    lod_area = turn_flicker(hf, antialias="area", sampling="lod")
    # measured: exact point sampling 15 469 (the exact area pass 2 478, 0.16x); the
    # lod engine 3 661 at pixel centres, 3 112 with area weights (0.20x; 3 492 and
    # 2 998 with trilinear levels and CROSS_ROWS 0.05), nearly all
    # of it in the nearest third of the picture, as the exact area pass's
    assert point > 8000
    assert lod_area <= 0.3 * point
    assert lod_area <= lod_point


def test_views_it_cannot_draw_take_the_column_pass():
    z, ext, hf, kw = _fly_scene()
    # orthographic
    a = fc.render(hf, size=(80, 60), elev=30, azim=20, sampling="lod")
    b = fc.render(hf, size=(80, 60), elev=30, azim=20, sampling="adaptive")
    assert a.stats["geometry"] == "column" and np.array_equal(a.rgba, b.rgba)
    # the eye below the ground under it
    ground = float(hf.evaluate(np.array([0.3 * ext]), np.array([0.1 * ext]))[0])
    low = fc.fly(hf, (0.3 * ext, 0.1 * ext, ground - 5.0), heading=25, pitch=-12,
                 size=(80, 45))
    a = fc.render(hf, **low)
    b = fc.render(hf, **dict(low, sampling="adaptive"))
    assert a.stats["geometry"] == "column" and np.array_equal(a.rgba, b.rgba)
    # looking down past the nadir
    down = fc.fly(hf, (0.5 * ext, 0.5 * ext), pitch=-80, fov=90, size=(80, 45))
    assert fc.render(hf, **down).stats["geometry"] == "column"


def test_a_function_surface_in_a_lod_view():
    expr = "2*sin(u)*cos(v)"
    kw = fc.fly(expr, (-8, -8), heading=45, pitch=-10, size=(120, 68), above=2)
    a = fc.render(expr, antialias=False, **kw)
    b = fc.render(expr, antialias=False, **dict(kw, sampling="adaptive"))
    assert a.stats["geometry"] == "lod" and b.stats["geometry"] == "column"
    both = (a.side != 0) & (b.side != 0)
    # measured: the sides agree at 99.89 % of the pixels, intensities within 0.02 at
    # 99.79 % (the exact column pass with adaptive planes as the reference)
    assert ((a.side != 0) == (b.side != 0)).mean() >= 0.995
    assert (np.abs(a.intensity - b.intensity)[both] <= 0.02).mean() >= 0.97


def test_options_it_cannot_take():
    with pytest.raises(ValueError,
                       match="sampling must be 'uniform', 'adaptive', 'lod' or 'march'"):
        fc.render("u*v", sampling="footprint")
    with pytest.raises(ValueError, match="not sub-columns"):
        fc.render("u*v", sampling="lod", antialias=2)


def test_skipping_hidden_planes_costs_no_accuracy(fly_reference, monkeypatch):
    """A column skips the planes the block maxima or one evaluation each show hidden
    (kernels/lod.py _hidden_until, _scan_hidden): as close to the ray caster as
    sampling every plane, with fewer evaluations (the scan's included)."""
    import floatcol.passes.lod as lod_pass
    hf, kw, ref = fly_reference
    opts = dict(antialias=False, shading="lambert", background=(0, 0, 0, 0), **kw)
    skipping = fc.render(hf, **opts)
    monkeypatch.setattr(lod_pass, "block_maxima", lambda surface: lod_pass._NO_BLOCKS)
    every = fc.render(hf, **opts)
    a_s, c_s, m_s, _ = _against(skipping, ref)
    a_e, c_e, m_e, _ = _against(every, ref)
    # measured: 95 476 evaluations instead of 135 801; sides 99.965 % both, within
    # 0.02 97.294 % and 97.286 %, mean error 0.00440 and 0.00432. Not the same picture
    # array for array: a run restarted after a skip starts Newton from another point,
    # which places its samples elsewhere within TOL_PX of their planes and so cuts a
    # span (REFINE_ROWS) or not (on a 513^2 DEM 0.4 % of the pixels change by more
    # than 16 levels that way, either picture as close to the ray caster as the other).
    assert skipping.stats["samples"] <= 0.75 * every.stats["samples"]
    assert a_s >= a_e - 2e-4
    assert c_s >= c_e - 0.003
    assert m_s <= m_e + 0.0005


def test_a_silhouette_pixel_mixes_the_colours_of_its_surfaces():
    """test_area's plateau as a height field (its grid read bilinearly, cells under a
    pixel near the rim: the pyramid's level 0 there), flown toward with area weights:
    the rim's pixels mix the plateau's and the plain's colours (area.piece_group)."""
    from test_area import RGB, _silhouette_green
    n, dom = 129, (-8.0, 8.0)
    g = np.linspace(*dom, n)
    U, V = np.meshgrid(g, g)
    z = 1 / (1 + np.exp(6 * (np.hypot(U, V) - 2)))
    hf = fc.HeightField(z, u=dom, v=dom)
    kw = fc.fly(hf, (0.0, -7.5), heading=0, pitch=-20, fov=50, size=(120, 90), above=4.0)
    r = fc.render(hf, specular=0.0, cmap=RGB, vmin=0, vmax=1, antialias=True,
                  background=(0, 0, 0, 0), **kw)
    assert r.stats["geometry"] == "lod"
    rim, green, ref = _silhouette_green(r, bilinear_surface(z, dom, dom), dom)
    # measured: 54 rim pixels, green share 0.056 against the reference's 0.063, at most
    # 0.009 above it (the colour of the mean height: up to 0.956 above it)
    assert rim.sum() >= 12
    assert (green - ref)[rim].max() <= 0.05
    assert green[rim].mean() <= ref[rim].mean() + 0.03

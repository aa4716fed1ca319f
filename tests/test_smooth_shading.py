"""smooth_shading=True (passes/normals.py, kernels/normals.py): a height field lit by
its normals interpolated between the nodes, on every engine, against the ray caster
lit by the same normals (tests/reference.py smooth_bilinear_surface); pixels wider
than a cell unchanged; a function surface unchanged; what it does not draw says so."""
import numpy as np
import pytest

import floatcol as fc
from reference import bilinear_surface, fractal, raycast, smooth_bilinear_surface
from test_lod import dense_dem, turn_flicker

N = 17
Z = fractal(N, 3.0, seed=4) * 120
EXT = 100.0 * (N - 1)                    # cells of 100 units, about 10 pixels wide
DOM = (0.0, EXT)
SIZE = (160, 120)
HF = fc.HeightField(Z, u=DOM, v=DOM)
FLY = fc.fly(HF, (0.3 * EXT, 0.05 * EXT), heading=25, pitch=-15, fov=60, size=SIZE, above=120)

#: name: (render keywords, least share of the pixels both show whose intensities lie
#: within 0.02 of the ray caster's, largest mean error); measured 2026-12-07 (smooth
#: against the smooth ray caster; the cells' own normals against the exact one in
#: brackets):
#: column perspective 100.0 % mean 0.0001 (99.35 %, 0.0006); orthographic 100.0 %,
#: 0.0001 (98.91 %, 0.0011); area sampling 96.51 %, 0.0078 (84.74 %, 0.0194: a pixel's
#: mean against the ray caster's point); the march 99.92 %, 0.0002 (99.72 %, 0.0010);
#: the lod engine 99.96 %, 0.0001 (99.13 %, 0.0014), its area weights 99.55 %, 0.0014
#: (97.83 %, 0.0033). Against the exact normals the smooth pictures agree at 9-19 %
#: (mean 0.09-0.12): the two lights differ.
ENGINES = {
    "column-perspective": (dict(projection="perspective", elev=30, azim=20), "column",
                           0.995, 0.001),
    "column-orthographic": (dict(elev=40, azim=-30), "column", 0.995, 0.001),
    "area": (dict(projection="perspective", elev=30, azim=20, antialias="area"), "area",
             0.95, 0.012),
    "march": (dict(FLY, antialias=False), "march", 0.995, 0.001),
    "lod": (dict(FLY, antialias=False, sampling="lod"), "lod", 0.995, 0.001),
    "lod-area": (dict(FLY, antialias="area"), "lod", 0.99, 0.003),
}


def _reference(funcs, r):
    vw = r.view
    return raycast(funcs, DOM, DOM, SIZE, vw.elev, vw.azim,
                   "orthographic" if vw.orthographic else "perspective", vw.d1, vw.d2,
                   vw.scale, center=vw.center, steps=3000)


def _close(r, ref):
    both = (r.side != 0) & (ref.side != 0)
    d = np.abs(r.intensity[both] - ref.intensity[both])
    return both.sum(), (d <= 0.02).mean(), d.mean()


@pytest.mark.parametrize("name", list(ENGINES))
def test_every_engine_lights_the_nodes_normals(name):
    kw, engine, least, mean_max = ENGINES[name]
    kw = dict(kw, size=SIZE, shading="lambert", background=(0, 0, 0, 0))
    r = fc.render(HF, smooth_shading=True, **kw)
    assert r.stats["geometry"] == engine
    both, close, mean = _close(r, _reference(smooth_bilinear_surface(Z, DOM, DOM), r))
    assert both > 5000
    assert close >= least and mean <= mean_max
    # the cells' own normals light another picture, which the exact ray caster agrees
    # with and the smooth one's light does not
    r0 = fc.render(HF, **kw)
    assert np.array_equal(r0.side, r.side)               # (the same geometry)
    _, close_smooth_vs_exact, _ = _close(r, _reference(bilinear_surface(Z, DOM, DOM), r))
    assert close_smooth_vs_exact <= 0.3


def test_it_flickers_less_than_the_cells_own_normals():
    """Cohen-Or's Table 6 measure (pixels changing 6 to 60 grey levels a frame) over
    test_lod.py's slow turn above a dense 1025^2 DEM, fc.fly's area-sampled view:
    measured 2 625 pixels smooth against 3 112 with the cells' own normals (point
    sampled: the lod engine 2 737 against 3 661, the march 2 452 against 2 655; with
    trilinear levels and lod.CROSS_ROWS 0.05, 2 501 against 2 998)."""
    hf = dense_dem()
    smooth, own = (turn_flicker(hf, antialias="area", smooth_shading=s) for s in (True, False))
    assert smooth <= 0.9 * own
    assert smooth <= 2700


def test_pixels_wider_than_a_cell_are_unchanged():
    """Where the facets are smaller than the pixels the pass leaves the picture as it
    was (a 257^2 DEM drawn 80 pixels wide: a cell is a third of a pixel); between half
    a cell and a cell it fades out."""
    hf = fc.HeightField(fractal(257, 3.0, seed=2) * 50, u=(0, 2560), v=(0, 2560))
    kw = dict(size=(80, 60), projection="perspective", elev=35, azim=10)
    for aa in (True, "area", False):
        a = fc.render(hf, antialias=aa, **kw)
        b = fc.render(hf, antialias=aa, smooth_shading=True, **kw)
        assert np.array_equal(a.rgba, b.rgba)
        assert np.array_equal(a.intensity, b.intensity, equal_nan=True)


def _node_by_node(z, su, sv, gx, gy):
    """The smooth gradient as it was computed before (each node's central difference
    on its own, one-sided at the edges; interpolated bilinearly), in Python's doubles:
    the kernel's must be the same but for the roundings its fused multiply-adds save."""
    nv, nu = z.shape
    i = min(max(int(gx), 0), nu - 2)
    j = min(max(int(gy), 0), nv - 2)
    fx = min(max(gx - i, 0.0), 1.0)
    fy = min(max(gy - j, 0.0), 1.0)

    def node(i, j):
        i0, i1, j0, j1 = max(i - 1, 0), min(i + 1, nu - 1), max(j - 1, 0), min(j + 1, nv - 1)
        hu = su if i1 - i0 == 1 else 0.5 * su
        hv = sv if j1 - j0 == 1 else 0.5 * sv
        return (z[j, i1] - z[j, i0]) * hu, (z[j1, i] - z[j0, i]) * hv
    (a_u, a_v), (b_u, b_v) = node(i, j), node(i + 1, j)
    (c_u, c_v), (d_u, d_v) = node(i, j + 1), node(i + 1, j + 1)
    return ((a_u * (1 - fx) + b_u * fx) * (1 - fy) + (c_u * (1 - fx) + d_u * fx) * fy,
            (a_v * (1 - fx) + b_v * fx) * (1 - fy) + (c_v * (1 - fx) + d_v * fx) * fy)


def test_the_smooth_gradient_is_the_node_by_node_one():
    """kernels/lod.py's _smooth_gradient (the cell's indices found once; the smooth
    pass's, the lod engine's and the march's) against _node_by_node, within a rounding
    or two (bit for bit before the kernels' FMA contraction), at every level of the
    pyramid, at random points and on the grid's edges and corners, on tiny grids too."""
    from floatcol.kernels.area import LV_NU, LV_NV, LV_OFF
    from floatcol.kernels.lod import LT_SU, LT_SV, _smooth_gradient, level_table
    from floatcol.passes.area import levels
    for z in (Z, fractal(5, 3.0, seed=1)[:, :4], np.arange(6.0).reshape(2, 3)):
        hf = fc.HeightField(z, u=(-3.0, 9.0), v=(2.0, 5.0))
        flat, lv = levels(hf)
        lt = level_table(lv, hf.hfp)
        rng = np.random.default_rng(0)
        pts = list(zip(rng.uniform(-3, 9, 200), rng.uniform(2, 5, 200)))
        pts += [(u, v) for u in (-3.0, 9.0, 3.0) for v in (2.0, 5.0, 3.5)]
        for k in range(lv.shape[0]):
            o, nv, nu = int(lv[k, LV_OFF]), int(lv[k, LV_NV]), int(lv[k, LV_NU])
            zk = flat[o:o + nv * nu].reshape(nv, nu)
            su, sv = lt[k, LT_SU], lt[k, LT_SV]
            for u, v in pts:
                want = _node_by_node(zk, su, sv, (u - hf.hfp[0]) * su, (v - hf.hfp[2]) * sv)
                got = _smooth_gradient(flat, lt, k, hf.hfp, u, v)
                # (within the roundings that the kernels' fused multiply-adds leave out:
                # kernels/_jit.py _MATH)
                tol = 1e-13 * (1.0 + max(abs(want[0]), abs(want[1])))
                assert abs(got[0] - want[0]) <= tol and abs(got[1] - want[1]) <= tol, \
                    (k, u, v)


def test_the_fade_between_half_a_cell_and_a_cell():
    from floatcol.kernels.layout import VP_D1, VP_D3, VP_ORTHO, VP_SCALE, VP_SIZE
    from floatcol.kernels.normals import smooth_weight
    vp = np.zeros(VP_SIZE)
    vp[VP_ORTHO] = 1.0
    for scale, want in ((4.0, 1.0), (2.0, 1.0), (1.5, 2.0 - 2.0 / 1.5), (1.0, 0.0),
                        (0.5, 0.0)):
        vp[VP_SCALE] = scale                   # a pixel is 1/scale wide; a cell is 1
        assert smooth_weight(vp, 0.0, 1.0) == pytest.approx(want)
    vp[VP_ORTHO] = 0.0
    vp[VP_D1] = 10.0
    vp[VP_D3] = 5.0
    vp[VP_SCALE] = 2.0                         # at depth z a pixel is (z + 5) / 20 wide
    assert smooth_weight(vp, 5.0, 1.0) == 1.0
    assert smooth_weight(vp, 10.0, 1.0) == pytest.approx(0.5)
    assert smooth_weight(vp, 15.0, 1.0) == 0.0


def test_a_function_surface_is_unchanged():
    kw = dict(u=(-3, 3), v=(-3, 3), size=(120, 90), projection="perspective")
    a = fc.render("sin(u)*cos(v)", **kw)
    b = fc.render("sin(u)*cos(v)", smooth_shading=True, **kw)
    assert np.array_equal(a.rgba, b.rgba)


def test_terrain_takes_it_by_default_and_the_cli_either_way(tmp_path):
    """fc.terrain's landscape defaults light a DEM smooth (where its options allow:
    not sub-columns, not translucent); `floatcol terrain` as the call, and
    --no-smooth-shading turns it off; `floatcol render` takes --smooth-shading."""
    from PIL import Image
    from floatcol.cli import main
    kw = dict(extent=(0, EXT, 0, EXT), vert_exag=1, size=(160, 120), elev=30, azim=-70,
              proj_type="persp")
    on = fc.terrain(Z, **kw).draw().rgba
    off = fc.terrain(Z, smooth_shading=False, **kw).draw().rgba
    assert not np.array_equal(on, off)
    assert fc.terrain(Z, antialias=2, **kw).draw().rgba.shape == on.shape   # (allowed)
    assert fc.terrain(Z, alpha=0.5, antialias=True, **kw).draw().rgba.shape == on.shape
    dem = tmp_path / "dem.npy"
    np.save(dem, Z)                         # (read north-up, as fc.terrain reads an array)
    argv = ["terrain", str(dem), "--extent", f"0:{EXT}:0:{EXT}", "--vert-exag", "1",
            "--size", "160x120", "--elev", "30", "--azim", "-70", "--proj", "persp"]
    for extra, want in (([], on), (["--no-smooth-shading"], off)):
        out = tmp_path / "t.png"
        assert main(argv + extra + ["-o", str(out)]) == 0
        assert np.array_equal(np.asarray(Image.open(out).convert("RGBA")), want)
    out = tmp_path / "r.png"
    assert main(["render", "sin(u)*cos(v)", "--smooth-shading", "--size", "40x30", "-o",
                 str(out)]) == 0


@pytest.mark.parametrize("kw, match", [
    (dict(smooth_shading="yes"), "smooth_shading must be True or False"),
    (dict(smooth_shading=True, method="horizon"), "method='column'"),
    (dict(smooth_shading=True, antialias=3), "not sub-columns"),
    (dict(smooth_shading=True, opacity=0.5), "opacity=1"),
])
def test_what_it_does_not_draw_says_so(kw, match):
    with pytest.raises(ValueError, match=match):
        fc.render(HF, size=(40, 30), **kw)

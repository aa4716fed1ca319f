"""Antialiasing (Gordon section 6.4) against the pixel-area answer: an analytic
coverage on a plane, and a 4x4-supersampled ray caster (tests/reference.py) on curved
surfaces."""
import numpy as np
import pytest

import floatcol as fc
from conftest import assert_plane_edges, plane, reference_for, render_with_switch_off
from reference import numpy_surface, raycast, raycast_box


def test_silhouette_pixel_coverage_is_the_analytic_fraction():
    r = plane(True)
    cols = assert_plane_edges(r)       # 0.65 of the edge pixels (conftest.py)
    # without antialiasing the same pixels are all or nothing
    hard = plane(False).rgba[..., 3]
    assert set(np.unique(hard[:, cols])) <= {0, 255}
    # the centre's arrays are the point-sampled ones in both
    assert np.array_equal(r.side, plane(False).side)


def test_sub_columns_cover_vertical_edges():
    """The side edge x = 1 falls at column 60 + 42.3 = 102.3; 4 sub-columns at
    offsets -3/8, -1/8, 1/8, 3/8 put 3 of 4 inside."""
    alpha = plane(4).rgba[..., 3] / 255.0
    rows = slice(45, 75)
    assert np.allclose(alpha[rows, 102], 0.75, atol=1 / 255)
    assert np.allclose(alpha[rows, 18], 0.75, atol=1 / 255)   # x = -1: 17.7, mirrored
    assert np.all(alpha[rows, 19:102] == 1.0)
    assert np.allclose(plane(True).rgba[rows, 102, 3], 255)   # coverage alone: point test


def _clipped_area(poly, x0, x1, y0, y1):
    """Area of the convex polygon poly ((n, 2) points) inside the box [x0, x1] x [y0, y1]
    (Sutherland-Hodgman clipping, then the shoelace formula)."""
    pts = [tuple(p) for p in poly]
    for axis, bound, keep_above in ((0, x0, True), (0, x1, False), (1, y0, True), (1, y1, False)):
        out = []
        for k in range(len(pts)):
            p, q = pts[k], pts[(k + 1) % len(pts)]
            p_in = (p[axis] >= bound) == keep_above
            q_in = (q[axis] >= bound) == keep_above
            if p_in:
                out.append(p)
            if p_in != q_in:
                t = (bound - p[axis]) / (q[axis] - p[axis])
                out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
        pts = out
        if not pts:
            return 0.0
    a = np.array(pts)
    return 0.5 * abs(np.dot(a[:, 0], np.roll(a[:, 1], 1)) - np.dot(a[:, 1], np.roll(a[:, 0], 1)))


@pytest.mark.parametrize("azim, before, bound", [(5, 0.0660, 0.025), (-10, 0.0534, 0.03),
                                                 (170, 0.0534, 0.03)])
def test_steep_silhouettes_are_blended_across_columns(azim, before, bound):
    """kernels/silhouette.py: the plane's side edges, seen from azim 5 or -10, climb
    5.7 or 2.8 rows a column; coverage along the columns alone left them staircases.
    Against the exact area of each pixel inside the projected square, the mean error
    of alpha over the partly covered pixels was ``before`` with the coverage alone and
    is now 0.0198 (azim 5) and 0.0241 (-10, 170): under ``bound``. The rest is mostly
    at the corners, where two edges meet in one pixel."""
    r = fc.render("0*u", u=(-1, 1), v=(-1, 1), size=(121, 121), elev=30, azim=azim,
                  scale=42.3, center=(0, 0, 0), background=(0, 0, 0, 0), antialias=True,
                  upper_color="white")
    col, row = r.view.project(np.array([-1.0, 1, 1, -1]), np.array([-1.0, -1, 1, 1]),
                              np.zeros(4))
    quad = np.stack([col, row], 1)
    exact = np.array([[_clipped_area(quad, c - 0.5, c + 0.5, i - 0.5, i + 0.5)
                       for c in range(121)] for i in range(121)])
    edge = (exact > 1e-9) & (exact < 1 - 1e-9)
    alpha = r.rgba[..., 3] / 255.0
    assert edge.sum() > 250
    err = np.abs(alpha - exact)[edge].mean()
    assert err <= bound < before
    # whole pixels stay whole, empty ones empty, but for two pixels next to a corner,
    # where the silhouette's line runs from the steep edge to the shallow one and
    # cuts the corner (azim 5: 0.788 at 2 pixels)
    ii, cc = np.mgrid[0:121, 0:121]
    near = np.zeros(exact.shape, dtype=bool)
    for x, y in quad:
        near |= (np.abs(cc - x) < 3) & (np.abs(ii - y) < 6)
    assert np.all(alpha[(exact >= 1 - 1e-9) & ~near] == 1.0)
    assert np.all(alpha[exact <= 1e-9] == 0.0)


@pytest.mark.parametrize("elev, azim, proj, before, now", [
    (30, -30, "orthographic", 0.2218, 0.1271), (20, -60, "perspective", 0.2316, 0.1375)])
def test_staircases_between_the_sides_are_blended(elev, azim, proj, before, now):
    """kernels/silhouette.py also blends the staircases where the lower side of a fold
    stands in front of the upper side behind it (and the reverse). With the upper
    side white, the lower side and the background black and no shading, a pixel's red
    is the part of it where the upper side is seen: against the ray caster's 3x3
    sub-pixels, the mean error over the pixels the edges cross was 0.306 / 0.303 with
    antialiasing off, ``before`` with the coverage along columns alone, and is ``now``
    (3 sub-columns, the same sub-pixels across: 0.020 / 0.030)."""
    expr, size, k = "3*sin(u*cos(v))", (100, 75), 3
    out = {}
    for aa in (False, True):
        r = fc.render(expr, u=(-5, 5), v=(-5, 5), size=size, elev=elev, azim=azim,
                      projection=proj, upper_color="white", lower_color="black", ambient=1.0,
                      specular=0, background=(0, 0, 0, 255), antialias=aa)
        if aa is False:
            vw = r.view
            ref = raycast(numpy_surface(expr), (-5, 5), (-5, 5), (size[0] * k, size[1] * k),
                          elev, azim, proj, vw.d1, vw.d2, vw.scale * k, center=vw.center,
                          steps=1500)
            upper = (ref.side == 1).reshape(size[1], k, size[0], k).mean(axis=(1, 3))
            edge = (upper > 0) & (upper < 1)
        out[aa] = np.abs(r.rgba[..., 0] / 255.0 - upper)[edge].mean()
    assert edge.sum() > 350                                   # measured 401, 440
    assert out[False] > 0.29
    assert out[True] <= now + 0.02 < before


CASES = [
    # measured PSNR (dB) of rgba against the 4x4 box-filtered ray caster, whole image /
    # partly covered pixels: off, coverage (with kernels/silhouette.py; the coverage
    # alone: 29.91/15.82, 30.20/15.89, 38.46/33.02), 3 sub-columns, at 120x90
    ("3*sin(u*cos(v))", 5, 30, 20, "orthographic"),   # 26.63/12.97, 30.89/17.79, 37.01/23.57
    ("3*sin(u*cos(v))", 5, 30, 20, "perspective"),    # 27.17/12.74, 31.18/17.31, 37.91/24.61
    ("2*exp(-(u**2+v**2))*cos(3*sqrt(u**2+v**2))", 3, 25, 40, "orthographic"),
    #                                                  32.99/18.69, 38.46/33.02, 46.72/37.96
]


@pytest.mark.parametrize("expr,d,elev,azim,proj", CASES)
def test_antialiasing_reduces_the_error_at_silhouettes(expr, d, elev, azim, proj):
    out = {}
    for aa in (False, True, 3):
        r = fc.render(expr, u=(-d, d), v=(-d, d), size=(120, 90), elev=elev, azim=azim,
                      projection=proj, shading="lambert", antialias=aa)
        if aa is False:
            vw = r.view
            # (500 steps a ray: every PSNR above within 0.02 dB of 1500 steps', 3x faster)
            box, cov = raycast_box(numpy_surface(expr), (-d, d), (-d, d), (120, 90), elev,
                                   azim, proj, vw.d1, vw.d2, vw.scale, center=vw.center, k=4,
                                   steps=500)
            edge = (cov > 0) & (cov < 1)
            plain = r
        err = (r.rgba[..., 0] / 255.0 - box) ** 2
        out[aa] = (10 * np.log10(1 / err.mean()), 10 * np.log10(1 / err[edge].mean()))
        # blending touches rgba only
        assert np.array_equal(r.side, plain.side)
        assert np.array_equal(r.intensity, plain.intensity, equal_nan=True)
    assert edge.sum() > 200
    assert out[True][0] >= out[False][0] + 2.0 and out[True][1] >= out[False][1] + 2.0
    assert out[3][0] >= out[True][0] + 3.0 and out[3][1] >= out[True][1] + 2.0


OPAQUE_CASES = [
    # (expr, d, projection, pixels inside the ray caster's silhouette left partly
    # transparent, measured at 200x150 before the fix: 63, 28, 8; after: 0)
    ("4.181540550352056*(sqrt(4 - u**2 - v**2) + sqrt(u**2 + v**2 - 1) - 2)", 2, "perspective"),
    ("4.181540550352056*(sqrt(4 - u**2 - v**2) + sqrt(u**2 + v**2 - 1) - 2)", 2, "orthographic"),
    ("1.25*3*sin(u*cos(v))", 5, "perspective"),
]


@pytest.mark.parametrize("expr, d, proj", OPAQUE_CASES)
def test_a_pixel_inside_the_silhouette_is_opaque(expr, d, proj):
    """Where a pixel and its 8 neighbours show a surface at their centres (the ray
    caster's side mask), surfaces cover the whole pixel: with a transparent
    background its alpha is 255. A rim's silhouette over the surface behind a hole
    (the annulus's inner lip over its far wall; 3 sin(u cos v) past the domain's
    edge in perspective) left the rest of the pixel empty: the run after the hole
    skipped the pixel as painted (a light dot on a white background)."""
    r = fc.render(expr, u=(-d, d), v=(-d, d), elev=30, azim=-30, projection=proj,
                  size=(200, 150), background=(0, 0, 0, 0))
    ref = reference_for(r, expr, (-d, d), (-d, d), 30, -30, proj, steps=4000)
    m = ref.side != 0
    inner = np.zeros_like(m)
    inner[1:-1, 1:-1] = True
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            inner[1:-1, 1:-1] &= m[1 + dy:m.shape[0] - 1 + dy, 1 + dx:m.shape[1] - 1 + dx]
    assert inner.sum() > 10000                              # measured 10306 - 15092
    assert (inner & (r.rgba[..., 3] < 255)).sum() == 0


def test_antialias_defaults_and_errors():
    expr = "3*sin(u*cos(v))"
    kw = dict(u=(-5, 5), v=(-5, 5), size=(80, 60))
    assert np.array_equal(fc.render(expr, **kw).rgba, fc.render(expr, antialias=True, **kw).rgba)
    lam = fc.render(expr, shading="lambert", **kw)
    assert np.array_equal(lam.rgba, fc.render(expr, shading="lambert", antialias=False, **kw).rgba)
    for bad in (5, 1.5, "yes"):
        with pytest.raises(ValueError, match="antialias"):
            fc.render(expr, antialias=bad, **kw)
    with pytest.raises(ValueError, match="antialias"):
        fc.render(expr, method="horizon", antialias=3, **kw)


@pytest.mark.parametrize("expr, kw", [
    ("3*sin(u*cos(v))", dict(u=(-5, 5), v=(-5, 5))),
    ("3*sin(u*cos(v))", dict(u=(-5, 5), v=(-5, 5), projection="perspective", elev=50)),
    ("sqrt(1 - u**2 - v**2)", dict(u=(-1.2, 1.2), v=(-1.2, 1.2), elev=-20)),   # hole, lower side
    ("floor(u) + 0.3*v", dict(u=(-3, 3), v=(-3, 3))),                          # walls
])
def test_the_finishing_pass_skips_only_rows_no_column_marked(monkeypatch, expr, kw):
    # column_kernel's rows bound, per tile, where E_SEEN may be set (antialiased
    # partial pixels included); the finishing pass reads nothing outside it
    import sys
    from floatcol.kernels.layout import E_SEEN
    render_module = sys.modules["floatcol.passes.geometry"]  # the column pass
    seen = {}
    kernel = render_module.column_kernel

    def spy(*args):
        kernel(*args)
        seen["ebuf"], seen["rows"] = args[8].copy(), args[-1].copy()
    monkeypatch.setattr(render_module, "column_kernel", spy)
    W = 203
    fc.render(expr, size=(W, 151), **kw)
    e, rows = seen["ebuf"][:, E_SEEN], seen["rows"]       # (tiles, H, TILE)
    e[-1, :, W - (len(e) - 1) * e.shape[2]:] = 0.0        # lanes past the picture's
    H = e.shape[1]                                        # edge: never written nor read
    j = np.arange(H)[None, :, None]
    outside = (j < rows[:, 0, None, None]) | (j > rows[:, 1, None, None])
    assert not (outside & (e != 0)).any()
    # ... and a tight one: within a row of the marked rows (the floor of a span's low
    # end), H and -1 where a tile marks none
    marked = (e != 0).any(axis=2)
    some = marked.any(axis=1)
    first = marked.argmax(axis=1)
    last = H - 1 - marked[:, ::-1].argmax(axis=1)
    assert (rows[some, 0] >= first[some] - 1).all() and (rows[some, 1] <= last[some] + 1).all()
    assert (rows[~some, 0] == H).all() and (rows[~some, 1] == -1).all()
    assert some.any() and (rows[some, 1] - rows[some, 0] + 1).sum() < 0.8 * H * some.sum()


@pytest.mark.parametrize("expr, kw", [
    ("3*sin(u*cos(v))", dict(u=(-5, 5), v=(-5, 5))),
    ("3*sin(u*cos(v))", dict(u=(-5, 5), v=(-5, 5), projection="perspective", elev=50)),
    ("sqrt(1 - u**2 - v**2)", dict(u=(-1.2, 1.2), v=(-1.2, 1.2), elev=-20)),   # hole, lower side
])
def test_every_edge_surface_left_in_a_pixel_is_written(monkeypatch, expr, kw):
    # The column pass holds a new edge surface back (column._hold_edge) and writes it
    # out only where its pixel still has one when the next is made or the column
    # ends; the finishing pass reads the planes of every pixel whose E_COV > 0. The
    # buffer is filled with NaN first: a surface not written out stays NaN.
    import sys
    from floatcol.kernels.coverage import flagged
    from floatcol.kernels.layout import (E_COV, E_DEPTH, E_I, E_NX, E_NY, E_NZ, E_SEEN,
                                         E_SIDE, E_W)
    render_module = sys.modules["floatcol.passes.geometry"]  # the column pass
    seen = {}
    kernel = render_module.column_kernel

    def spy(*args):
        args[8][...] = np.nan                       # ebuf
        kernel(*args)
        seen["ebuf"] = args[8].copy()
    monkeypatch.setattr(render_module, "column_kernel", spy)
    W = 203
    fc.render(expr, size=(W, 151), **kw)
    e = seen["ebuf"]                                 # (tiles, E_SIZE, H, TILE)
    e = e.transpose(1, 2, 0, 3).reshape(e.shape[1], e.shape[2], -1)[:, :, :W]
    x = e[E_SEEN]
    assert not np.isnan(x).any()                     # every pixel's E_SEEN is set
    edge = np.vectorize(flagged)(x) & (e[E_COV] > 0)
    assert edge.sum() > 20                           # silhouettes, reappearing surface
    planes = e[[E_NX, E_NY, E_NZ, E_W, E_I, E_DEPTH, E_SIDE]][:, edge]
    assert np.isfinite(planes).all()
    assert set(np.unique(e[E_SIDE][edge])) <= {-1.0, 1.0}
    n = np.sqrt(e[E_NX][edge] ** 2 + e[E_NY][edge] ** 2 + e[E_NZ][edge] ** 2)
    assert (n > 0.3).all() and (n < 1.0001).all()    # between two unit normals


# An antialiased run keeps the coverage of its top pixel in its state until the next
# span (column._fill, _fill_on): nearly always that span goes on through the pixel and
# makes it whole. It must leave every buffer as flagging the pixel at once does.
KEEP_TOP_CASES = [
    ("3*sin(u*cos(v))", dict(u=(-5, 5), v=(-5, 5), size=(203, 151))),
    ("3*sin(u*cos(v))", dict(u=(-5, 5), v=(-5, 5), size=(150, 110), projection="perspective",
                             elev=50, azim=-110)),
    ("3*sin(u*cos(v))", dict(u=(-5, 5), v=(-5, 5), size=(120, 90), antialias=3,
                             corrections="supersample", interpolation="intensity")),
    ("sqrt(1 - u**2 - v**2)", dict(u=(-1.2, 1.2), v=(-1.2, 1.2), size=(160, 120),
                                   elev=-20)),                         # hole, lower side
    ("floor(2*u)*0.5 + 0.2*v", dict(u=(-3, 3), v=(-3, 3), size=(160, 120), elev=25,
                                    azim=-30)),                        # walls
    ("sin(8*u)*cos(7*v)", dict(u=(-3, 3), v=(-3, 3), size=(400, 300), elev=45, azim=-135)),
    ("exp(-(u**2 + v**2))*cos(3*sqrt(u**2 + v**2))", dict(u=(-3, 3), v=(-3, 3),
                                                          size=(160, 120), elev=5,
                                                          shading="lambert",
                                                          antialias=True)),
]


@pytest.mark.parametrize("expr, kw", KEEP_TOP_CASES)
def test_keeping_a_runs_top_pixel_in_its_state_changes_nothing(monkeypatch, expr, kw):
    import sys
    from floatcol.kernels.coverage import flagged
    from floatcol.kernels.layout import (E_COV, E_COV0, E_DEPTH, E_I, E_NX, E_NY, E_NZ,
                                         E_SEEN, E_SIDE, E_W, VP_KEEP_TOP)
    render_module = sys.modules["floatcol.passes.geometry"]  # the column pass
    kernel = render_module.column_kernel
    seen = []

    def spy(*args):
        args[8][...] = np.nan                       # ebuf: what is not written stays NaN
        kernel(*args)
        seen.append(args[8].copy())
    monkeypatch.setattr(render_module, "column_kernel", spy)
    r = fc.render(expr, **kw)
    r0 = render_with_switch_off(monkeypatch, VP_KEEP_TOP, expr, **kw)   # flagged at once
    assert r.stats["samples"] == r0.stats["samples"]
    for k in ("rgba", "side", "intensity", "depth"):
        assert np.array_equal(getattr(r, k), getattr(r0, k), equal_nan=True), k
    # the edge buffers of the last column pass (a sub-column's), pixel by pixel:
    # E_SEEN everywhere, the coverages where flagged, the edge surface where it has one
    e, e0 = seen[len(seen) // 2 - 1], seen[-1]
    assert np.array_equal(e[:, E_SEEN], e0[:, E_SEEN], equal_nan=True)   # (NaN: lanes
    # past the picture's right edge)
    flag = np.vectorize(flagged)(e0[:, E_SEEN])
    assert flag.sum() > 20
    for p in (E_COV0, E_COV):
        assert np.array_equal(e[:, p][flag], e0[:, p][flag])
    edge = flag & (e0[:, E_COV] > 0)
    assert edge.sum() > 5
    for p in (E_NX, E_NY, E_NZ, E_W, E_I, E_DEPTH, E_SIDE):
        assert np.array_equal(e[:, p][edge], e0[:, p][edge])

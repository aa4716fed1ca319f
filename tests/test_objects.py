"""Objects on a surface by z-buffer (Szenberg 1997) and the window depth of his eq. 7."""
import warnings

import numpy as np
import pytest

import floatcol as fc
from conftest import reference_for


def test_a_box_seen_from_above_has_its_exact_footprint_and_depth():
    # a 2 x 1 box, 0.5 tall, on the plane w = 0, straight from above, 20 px a unit:
    # its top is 40 x 20 pixels, at screen depth -0.5 (nearer than the plane's 0)
    kw = dict(u=(-4, 4), v=(-4, 4), size=(161, 161), elev=90, azim=0, scale=20.0,
              center=(0, 0, 0), upper_color="white")
    plain = fc.render("0*u", **kw)
    r = fc.render("0*u", objects=[fc.box(0.525, 1.025, 2.0, 1.0, 0.5, color="red")], **kw)
    red = (r.rgba[..., 0] > 100) & (r.rgba[..., 1] < 60)
    rows, cols = np.nonzero(red)
    # column c at u = (c - 80) / 20, row i at v = (80 - i) / 20 (screen y = v from
    # above): centres inside u in [-0.475, 1.525], v in [0.525, 1.525]
    assert (cols.min(), cols.max(), rows.min(), rows.max()) == (71, 110, 50, 69)
    assert red.sum() == 40 * 20
    assert r.stats["object_pixels"] == 800
    assert np.allclose(r.depth[red], -0.5, atol=1e-6)
    assert np.array_equal(r.depth[~red], plain.depth[~red])
    assert np.array_equal(r.rgba[~red], plain.rgba[~red])


def test_objects_hide_behind_the_surface_and_in_front_of_it():
    # a ridge along u at v = 0; the camera looks from the south (low v), tilted down
    expr = "2*exp(-v**2)"
    kw = dict(u=(-4, 4), v=(-4, 4), size=(160, 120), elev=10, azim=0,
              projection="perspective")
    behind = fc.render(expr, objects=[fc.box(0, 2.5, 1, 1, 0.8)], **kw)
    front = fc.render(expr, objects=[fc.box(0, -2.5, 1, 1, 0.8)], **kw)
    assert behind.stats["object_pixels"] == 0             # hidden by the ridge
    assert front.stats["object_pixels"] > 100
    # a pole taller than the ridge shows above it
    tall = fc.render(expr, objects=[fc.pole(0, 2.5, 4.0, radius=0.15)], **kw)
    assert tall.stats["object_pixels"] > 20


def test_window_depth_is_eq_7_of_the_ray_casters_depth():
    expr = "sin(u)*cos(v)"
    kw = dict(u=(-3, 3), v=(-3, 3), elev=30, azim=20, projection="perspective")
    r = fc.render(expr, size=(80, 60), **kw)
    ref = reference_for(r, expr, (-3, 3), (-3, 3), 30, 20, "perspective")
    near, far = 1.0, 40.0
    e = ref.depth + r.view.d3
    want = (far - far * near / e) / (far - near)
    both = (r.side != 0) & (ref.side != 0)
    wd = r.window_depth(near, far)
    # the depths differ by at most 0.0066 (the picture's interpolated between
    # samples; median 0.0003): measured |difference| max 2.6e-5, median 1.2e-6
    assert both.sum() > 1000
    assert np.abs(wd[both] - want[both]).max() < 1e-4
    assert np.median(np.abs(wd[both] - want[both])) < 1e-5
    assert (wd[r.side == 0] == 1.0).all()
    # orthographic: linear in the distance from the eye plane d1 + d2 (here 1 + 3)
    # in front of the centre: the plane w = 0 seen from above is 4 away
    o = fc.render("0*u", size=(40, 30), u=(-3, 3), v=(-3, 3), elev=90, center=(0, 0, 0),
                  d1=1, d2=3)
    seen = o.side != 0
    assert seen.sum() > 300
    assert np.allclose(o.window_depth(0.5, 20)[seen], (4 - 0.5) / 19.5, atol=1e-6)
    with pytest.raises(ValueError, match="far"):
        r.window_depth(5, 2)


def test_bad_objects():
    with pytest.raises(ValueError, match="objects must be"):
        fc.render("u*v", size=(40, 30), objects=[3])
    with pytest.raises(ValueError, match="height"):
        fc.tree(0, 0, -1)
    with pytest.raises(ValueError, match="mesh"):
        fc.render("u*v", size=(40, 30), objects=[fc.Mesh(0, 0, [[0, 0, 0]], [[0, 1, 2]])])


def test_a_mesh_of_one_colour_a_triangle():
    # a square of two triangles standing upright, red and blue, seen from the front
    verts = [(-1, 0, 0), (1, 0, 0), (1, 0, 2), (-1, 0, 2)]
    mesh = fc.Mesh(0, 0, verts, [(0, 1, 2), (0, 2, 3)], ["red", "blue"])
    r = fc.render("0*u", u=(-3, 3), v=(-3, 3), size=(120, 90), elev=0.0, azim=0,
                  scale=15.0, center=(0, 0, 1), objects=[mesh], upper_color="white")
    red = (r.rgba[..., 0] > 80) & (r.rgba[..., 2] < 40)
    blue = (r.rgba[..., 2] > 80) & (r.rgba[..., 0] < 40)
    # the lower-right half red, the upper-left blue: 30 x 30 pixels between them
    assert red.sum() > 300 and blue.sum() > 300
    assert red.sum() + blue.sum() == pytest.approx(900, abs=40)
    rows, cols = np.nonzero(red)
    assert np.mean(cols) > 59.5 and np.mean(rows) > 44.5


def test_an_object_reaching_past_the_eye_is_clipped_not_dropped():
    """A fly-through: a wall beside the eye, from behind it to far ahead (one quad of
    two triangles, each with a corner behind the eye). Its part behind the screen
    plane is cut off (objects.clip_near) and the rest drawn, where rays from the eye
    meet it; before, both triangles were left out (0 pixels). Measured: 9461 pixels,
    exactly where the rays say (the right half of the picture below the wall's top)."""
    hf = fc.HeightField(np.zeros((11, 11)), u=(0, 1000), v=(0, 1000))
    eye = np.array([500.0, 200.0, 30.0])
    W, H = 201, 101
    kw = fc.fly(hf, tuple(eye), heading=0, pitch=-10, fov=60, size=(W, H))
    wall = fc.Mesh(505.0, 250.0, [[0, -150, 0], [0, 150, 0], [0, 150, 60], [0, -150, 60]],
                   [[0, 1, 2], [0, 2, 3]], color="red", base=0.0)
    kw["antialias"] = False                 # (the pixel centres: no edge blended)
    plain = fc.render(hf, **kw)
    r = fc.render(hf, objects=[wall], **kw)
    got = np.any(r.rgba != plain.rgba, axis=-1)
    vw = r.view
    # the ray through each pixel centre: ahead * d1 + right * x + up * y
    a = np.radians(-10.0)
    ahead = np.array([0.0, np.cos(a), np.sin(a)])
    right = np.array([1.0, 0.0, 0.0])
    up = np.array([0.0, -np.sin(a), np.cos(a)])
    cols, rows = np.meshgrid(np.arange(W), np.arange(H))
    x = (cols - (W - 1) / 2) / vw.scale
    y = ((H - 1) / 2 - rows) / vw.scale
    d = vw.d1 * ahead + x[..., None] * right + y[..., None] * up
    # (the rays go where the camera projects: a point on one lands on its pixel)
    pc, pr = vw.project(*(eye + 40.0 * d[30, 150])[:, None])
    assert (pc[0], pr[0]) == pytest.approx((150, 30), abs=1e-6)
    with np.errstate(divide="ignore", invalid="ignore"):
        lam = (505.0 - eye[0]) / d[..., 0]
        p = eye + lam[..., None] * d
    want = (d[..., 0] > 0) & (lam >= 1.0) & (p[..., 1] >= 100) & (p[..., 1] <= 400) \
        & (p[..., 2] >= 0) & (p[..., 2] <= 60)
    assert want.sum() > 2000
    assert r.stats["object_pixels"] == got.sum()
    assert (got != want).sum() <= 10                        # measured 0


def test_an_object_of_any_size_draws_what_a_large_one_does():
    """A pole 1e50 or 1e300 tall: its screen corners far outside an int's range were
    converted to pixel indices as they were, which LLVM leaves undefined (a segfault
    or an endless loop, found by tests/fuzzing.py's terrain cases). Seen from 30
    degrees up it is a stripe to the top of the picture, as a pole 100 tall (1700
    pixels) is: the same pixels but at most 4 of 220 where the rounding of coordinates
    near 1e50 moves a silhouette (measured 0, 3 and 0 for 1e10, 1e50 and 1e300)."""
    kw = dict(u=(-4, 4), v=(-4, 4), size=(81, 61), elev=30, azim=0, scale=10.0,
              center=(0, 0, 0), antialias=False)
    plain = fc.render("0*u", **kw)
    masks = []
    with warnings.catch_warnings():
        warnings.simplefilter("error")                  # (numpy's overflow: none shown)
        for h in (100.0, 1e10, 1e50, 1e300):
            r = fc.render("0*u", objects=[fc.pole(0.0, 0.0, h, radius=0.3)], **kw)
            masks.append(np.any(r.rgba != plain.rgba, axis=-1))
            assert r.stats["object_pixels"] == masks[-1].sum()
    assert masks[0][0, 40] and masks[0][:, 40].sum() > 25 and masks[0].sum() > 200
    for m in masks[1:]:
        assert (m != masks[0]).sum() <= 4
    # in perspective too (its corners behind the eye clipped)
    r = fc.render("0*u", u=(-4, 4), v=(-4, 4), size=(81, 61), elev=30,
                  projection="perspective", objects=[fc.pole(0.0, 0.0, 1e300, radius=0.3)])
    assert r.stats["object_pixels"] > 0
    with warnings.catch_warnings():                     # antialiased edges too
        warnings.simplefilter("error")
        kw["antialias"] = True
        plain = fc.render("0*u", **kw)
        aa = [np.any(fc.render("0*u", objects=[fc.pole(0.0, 0.0, h, radius=0.3)],
                               **kw).rgba != plain.rgba, axis=-1) for h in (100.0, 1e300)]
    # the same pixels blended (their colours differ: a face 1e300 tall has no normal),
    # but for the rounding near 1e300 (measured 4)
    assert aa[0].sum() > 200 and (aa[0] != aa[1]).sum() <= 8


def _coverage(r, plain, colour):
    """The part of each pixel an object of ``colour`` (RGB 0..255) covers, from the
    blend of its colour and the plain picture's (the green channel: red against
    white)."""
    p = plain.rgba[..., 1].astype(float)
    return (p - r.rgba[..., 1]) / (p - colour[1])


@pytest.mark.parametrize("heading, mean_bound", [(0.0, 0.09), (30.0, 0.025)])
def test_an_objects_edges_are_antialiased_by_its_coverage(heading, mean_bound):
    """A box's top seen from straight above, 20 px a unit, its edges across pixels: an
    edge pixel is the blend of the box's red and the plane's white by the part of the
    pixel the top covers (16 sub-samples, 4 a side: within 1/8 of the exact area), the
    inside red, the outside white. Measured (mean / largest |error| over the edge
    pixels): 0.081 / 0.110 with the edges along the pixels (4 sub-samples across an
    edge: its place in the pixel quantised), 0.017 / 0.052 turned 30 degrees; point
    sampled 0.325 and 0.178."""
    kw = dict(u=(-4, 4), v=(-4, 4), size=(161, 161), elev=90, azim=0, scale=20.0,
              center=(0, 0, 0), upper_color="white", specular=0.0)
    plain = fc.render("0*u", **kw)
    box = fc.box(0.51, 1.03, 2.03, 1.07, 0.5, color="red", heading=heading)
    r = fc.render("0*u", objects=[box], **kw)
    red = fc.render("0*u", objects=[box], **dict(kw, antialias=False))
    colour = red.rgba[80 - 21, 80 + 10]                    # (the top's middle)
    assert colour[0] > 150 and colour[1] < 60
    # the exact area: the pixel's 40 x 40 grid of points inside the top's rectangle
    c, s_ = np.cos(np.radians(heading)), np.sin(np.radians(heading))
    k = (np.arange(40) + 0.5) / 40 - 0.5
    cols, rows = np.meshgrid(np.arange(161), np.arange(161))
    area = np.zeros((161, 161))
    for dy in k:
        for dx in k:
            u = (cols + dx - 80) / 20 - 0.51
            v = (80 - rows - dy) / 20 - 1.03
            x, y = u * c - v * s_, u * s_ + v * c                # (the box's own axes)
            area += (np.abs(x) <= 2.03 / 2) & (np.abs(y) <= 1.07 / 2)
    area /= 40 * 40
    got = _coverage(r, plain, colour)
    edge = (area > 0) & (area < 1)
    assert edge.sum() > 100
    err = np.abs(got - area)
    assert err[edge].max() <= 0.13 and err[edge].mean() < mean_bound
    assert err[~edge].max() < 0.01                         # inside and outside: exact
    # point-sampled, the edge pixels are all or nothing
    assert np.abs(_coverage(red, plain, colour) - area)[edge].mean() > 0.15


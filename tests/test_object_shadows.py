"""Objects' shadows (floatcol/objects.py Occluders; passes/shadow.py): the objects cast
shadows on the surface and on each other, and take the surface's, against an
independent reference (tests/reference.py objects_reference: every ray against every
triangle, the surface ray-cast and marched toward the light).

Bounds measured on 2026-12-05 (160x120, antialias=False), then loosened a little:
agreement is the part of the pixels, among those where both see the same thing (the
surface or an object, at the same depth), whose shadow (>= 0.5) agrees.

    case, projection     surface pixels  agree     object pixels  agree    shadowed by
                                                                           objects alone
    gentle, ortho        7178            99.86 %   816            100 %    683, 100 %
    gentle, persp        6174            99.77 %   748            100 %    637, 100 %
    hill, ortho          7155            99.94 %   793            100 %    301, 99.67 %
    hill, persp          6175            99.95 %   618            100 %    224, 100 %

(the surface's 0.05-0.23 % are pixels at the objects' shadow edges, antialiased: the
part of the footprint in shadow is on the other side of 0.5 from the centre; with hard
edges they had agreed at 99.97-100 %.)
"""
import math

import numpy as np
import pytest

import floatcol as fc
from reference import numpy_surface, objects_reference

BUMP = "1.6*exp(-((u-0.5)**2 + v**2)/0.6) + 0.1*sin(2*u)*cos(v)"


def _scene(expr, objects, proj, sun, elev=35, azim=20, size=(160, 120), radius=0.0,
           n_disk=32, steps=2000, **kw):
    dom = (-4, 4)
    r = fc.render(expr, u=dom, v=dom, size=size, elev=elev, azim=azim, projection=proj,
                  lightsource=sun, shadows=True, objects=objects, antialias=False,
                  light_radius=radius, **kw)
    f = numpy_surface(expr)
    tris = []
    for obj in objects:
        foot = float(f[0](np.array([obj.u]), np.array([obj.v]))[0])
        p = np.asarray(obj.vertices, float) + [obj.u, obj.v, foot]
        tris.append(p[np.asarray(obj.triangles)])
    vw = r.view
    kind, depth, shadow = objects_reference(
        f, dom, dom, size, elev, azim, proj, vw.d1, vw.d2, vw.scale, vw.center,
        np.vstack(tris), fc.Light.sun(*sun).direction, radius=radius, n_disk=n_disk,
        steps=steps)
    return r, kind, depth, shadow


def _behind(sun, center, k):
    """A point k units from ``center`` away from the sun along the ground."""
    L = fc.Light.sun(*sun).direction
    g = np.array(L[:2]) / math.hypot(L[0], L[1])
    return tuple(np.asarray(center) - k * g)


CASES = [
    # objects on a gentle surface: their shadows on it and on each other
    ("0.2*sin(u)*cos(v)", (300, 30), lambda: [
        fc.box(-1, 0, 1, 1, 1.5, color="firebrick"), fc.pole(1.5, 1, 2.0),
        fc.tree(0, -2, 2.0), fc.marker(2, -1, 0.5), fc.tree(0.6, -1.0, 1.2)]),
    # a hill's shadow falling on the objects behind it
    (BUMP, (120, 20), lambda: [
        fc.box(*_behind((120, 20), (0.5, 0.0), 2.2), 1.4, 1.4, 1.0, color="firebrick"),
        fc.pole(*_behind((120, 20), (0.5, 0.0), 1.2), 1.5, radius=0.12),
        fc.tree(*_behind((120, 20), (0.5, 0.0), 3.4), 1.8)]),
]


@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
@pytest.mark.parametrize("case", range(len(CASES)))
def test_object_shadows_agree_with_the_reference(case, proj):
    expr, sun, objects = CASES[case]
    r, kind, depth, shadow = _scene(expr, objects(), proj, sun)
    d = r.depth.astype(float)
    with np.errstate(invalid="ignore"):            # (inf - inf where nothing is seen)
        same = np.isfinite(d) & (kind > 0) & (np.abs(d - depth) < 0.02)
    for k, what in ((1, "surface"), (2, "objects")):
        at = same & (kind == k)
        assert at.sum() > 300, what
        agree = ((r.shadow[at] >= 0.5) == (shadow[at] >= 0.5)).mean()
        assert agree >= 0.996, (what, agree)
    # objects' shadows are there: surface pixels the objects alone shadow
    plain = fc.render(expr, u=(-4, 4), v=(-4, 4), size=(160, 120), elev=35, azim=20,
                      projection=proj, lightsource=sun, shadows=True, antialias=False)
    by_objects = same & (kind == 1) & (shadow >= 0.5) & (plain.shadow < 0.5)
    assert by_objects.sum() > 200
    assert (r.shadow[by_objects] >= 0.5).mean() >= 0.99


@pytest.mark.parametrize("case, proj", [(0, "perspective"), (1, "orthographic")])
def test_translucent_surfaces_take_the_objects_shadows(case, proj):
    """opacity < 1: every layer's crossing is tested against the objects' triangles
    (kernels/layers.py, with raster.py's occluded test), the nearest crossing's shadow
    in r.shadow. Against the same reference as the opaque surfaces (the nearest crossing
    is what it sees), hard edges: measured 100 % and 100 % (gentle, perspective; 637
    pixels the objects alone shadow, all shadowed), 99.97 % and 100 % (hill,
    orthographic; 301 pixels, 99.67 %): the opaque surfaces' figures. Before, a
    translucent surface took no object's shadow (none of those pixels shadowed)."""
    expr, sun, objects = CASES[case]
    r, kind, depth, shadow = _scene(expr, objects(), proj, sun, opacity=0.5)
    assert r.stats["translucent"]
    d = r.depth.astype(float)
    with np.errstate(invalid="ignore"):
        same = np.isfinite(d) & (kind > 0) & (np.abs(d - depth) < 0.02)
    for k, what in ((1, "surface"), (2, "objects")):
        at = same & (kind == k)
        assert at.sum() > 500, what
        agree = ((r.shadow[at] >= 0.5) == (shadow[at] >= 0.5)).mean()
        assert agree >= 0.996, (what, agree)
    plain = fc.render(expr, u=(-4, 4), v=(-4, 4), size=(160, 120), elev=35, azim=20,
                      projection=proj, lightsource=sun, shadows=True, antialias=False,
                      opacity=0.5)
    by_objects = same & (kind == 1) & (shadow >= 0.5) & (plain.shadow < 0.5)
    assert by_objects.sum() > 200
    assert (r.shadow[by_objects] >= 0.5).mean() >= 0.99
    # ... and the picture darker there (the layers lit with the light that reaches
    # them): measured by 27-47 levels (r + g + b, 1st percentile and median; the hill
    # under a low sun 18-30), all pixels but the one whose shadow disagrees
    darker = (plain.rgba[..., :3].astype(float).sum(axis=-1)
              - r.rgba[..., :3].astype(float).sum(axis=-1))[by_objects]
    assert (darker >= 3).mean() >= 0.99 and np.median(darker) >= 15


def test_a_poles_shadow_on_flat_ground_is_as_long_as_trig_says():
    """A pole h tall under a sun at altitude a throws a shadow h / tan(a) long, straight
    away from the sun, as wide as the pole."""
    h, alt, az = 2.0, 30.0, 300.0
    r = fc.render("0.0*u + 0.0*v", u=(-4, 4), v=(-4, 4), size=(320, 320), elev=70, azim=10,
                  lightsource=(az, alt), shadows=True, objects=[fc.pole(0, 0, h, radius=0.08)],
                  antialias=False)
    L = fc.Light.sun(az, alt).direction
    g = -np.array(L[:2]) / math.hypot(L[0], L[1])          # away from the sun
    across = np.array([-g[1], g[0]])
    length = h / math.tan(math.radians(alt))               # 3.46
    pts = {"shadow": [g * k for k in (0.5, 1.5, 2.5, 0.97 * length)],
           "lit": [g * 1.03 * length, g * 3.9, g * 1.5 + across * 0.2, -g * 1.0]}
    for want, ps in pts.items():
        for p in ps:
            col, row = r.view.project(np.array([p[0]]), np.array([p[1]]), np.array([0.0]))
            s = r.shadow[int(round(row[0])), int(round(col[0]))]
            assert (s >= 0.5) == (want == "shadow"), (want, p, s)


def test_objects_take_their_shadows_from_the_texture():
    with pytest.raises(ValueError, match="shadows=True"):
        fc.render("u*v", size=(40, 30), lightsource=(300, 30), shadows="on-the-fly",
                  objects=[fc.pole(0, 0, 2.0)])


@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
def test_antialiased_object_edges_approach_the_supersampled_picture(proj):
    """At the objects' edges (pixels they cover in part), an antialiased picture is the
    box filter of a picture drawn at 4 x 4 the pixels (point sampled) within a fraction
    of the point-sampled picture's error, shadows on. Measured (mean |error| of the RGB
    levels over the edge pixels): orthographic 4.6 against 17.6, perspective 5.1
    against 19.8 (before slivers between the pixel centres were found, 8.4 and 12.8)."""
    expr, sun, objects = CASES[0]
    kw = dict(u=(-4, 4), v=(-4, 4), elev=35, azim=20, projection=proj, lightsource=sun,
              shadows=True, objects=objects())
    n, err = _edge_errors(expr, kw, 0.2)
    assert n > 60
    assert err[True] < 0.35 * err[False]


def _edge_errors(expr, kw, part):
    """(pixels, {antialias: mean |RGB error|}) at the objects' edges (pixels they cover
    by part to 1 - part) of 120 x 90 pictures with and without antialiasing, against the
    picture drawn at 4 x 4 the pixels (point sampled) and box-filtered."""
    big = dict(kw, size=(480, 360), antialias=False)
    r4 = fc.render(expr, **big)
    # the objects' footprint at 4 x 4: where they change the picture without shadows
    plain4 = fc.render(expr, **dict(big, shadows=False, objects=()))
    obj4 = fc.render(expr, **dict(big, shadows=False))
    cover = np.any(obj4.rgba != plain4.rgba, axis=-1).reshape(90, 4, 120, 4).mean(axis=(1, 3))
    want = r4.rgba[..., :3].astype(float).reshape(90, 4, 120, 4, 3).mean(axis=(1, 3))
    edge = (cover > part) & (cover < 1.0 - part)
    err = {}
    for aa in (True, False):
        r = fc.render(expr, **dict(kw, size=(120, 90), antialias=aa))
        err[aa] = np.abs(r.rgba[..., :3].astype(float) - want)[edge].mean()
    return int(edge.sum()), err


@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
def test_thin_poles_in_a_shadow_stay_in_shadow_at_their_edges(proj):
    """36 poles under a pixel wide in a wall's shadow: most of their pixels are
    slivers between the pixel centres, which the antialiased edges colour by their
    triangle. Against the picture drawn at 4 x 4 the pixels and box-filtered (as
    above), the edges' mean RGB error: measured 9.1 (ortho) / 8.2 (persp) against 28.7 /
    27.8 point-sampled; before a sliver took its shadow (its triangle's light and
    shadows at its centroid), 33.3 / 28.6: the shadowed poles drawn white, worse than
    no antialiasing."""
    objs = [fc.box(-3.0, 0, 0.4, 7, 3.0, color="firebrick")] + [
        fc.pole(-2.2 + 0.5 * k, -2.5 + 0.9 * m, 1.8, radius=0.03, color="white")
        for k in range(6) for m in range(6)]
    expr = "0.2*sin(u)*cos(v)"
    kw = dict(u=(-4, 4), v=(-4, 4), elev=30, azim=20, projection=proj, lightsource=(270, 25),
              shadows=True, objects=objs)
    n, err = _edge_errors(expr, kw, 0.05)
    assert n > 500
    assert err[True] < 0.5 * err[False], err


def test_object_shadow_edges_are_the_part_of_the_pixel_in_shadow():
    """At the edge of an object's shadow on the surface a pixel holds the part of its
    footprint in shadow: against the reference at 2 x 2 the pixels, box-filtered, it is
    nearer than the reference's own shadow at the pixel centre (what hard edges would
    give at best). Measured (mean |error| over the edge pixels, 110 of them): 0.093
    against 0.414."""
    expr, sun, _ = CASES[0]
    # (a box and a thick pole: few triangles for the reference's every-ray test)
    objs = [fc.box(-1, 0, 1, 1, 1.5), fc.pole(1.5, 1, 2.0, radius=0.15), fc.box(0, -2, 1.5, 0.5, 1)]
    # (the reference's march over the surface coarser: the surface is gentle)
    r, kind, depth, shadow = _scene(expr, objs, "perspective", sun, steps=300)
    _, kind3, _, shadow3 = _scene(expr, objs, "perspective", sun, size=(320, 240), steps=300)
    plain = fc.render(expr, u=(-4, 4), v=(-4, 4), size=(160, 120), elev=35, azim=20,
                      projection="perspective", lightsource=sun, shadows=True,
                      antialias=False)
    ground = (kind3 == 1).reshape(120, 2, 160, 2).all(axis=(1, 3))
    frac = np.nan_to_num(shadow3).reshape(120, 2, 160, 2).mean(axis=(1, 3))
    edge = ground & (kind == 1) & (frac > 0) & (frac < 1) & (plain.shadow < 0.05) \
        & (r.shadow == r.shadow)
    assert edge.sum() > 60
    err_aa = np.abs(r.shadow[edge] - frac[edge]).mean()
    err_centre = np.abs(shadow[edge] - frac[edge]).mean()
    assert err_aa < 0.5 * err_centre


def test_under_a_sun_of_a_radius_objects_take_the_surfaces_penumbra():
    """light_radius: a hill's penumbra falling on objects is the part of the sun's disk
    the hill hides from their points (kernels/shadow.py points_shadow with the radius: the horizon
    of the surface around, seen from the point, and across the light the strips of the
    lines beside), against the reference's 32 rays over the disk. Measured on the object
    pixels the reference puts in a penumbra (106, perspective): mean |difference| 0.097,
    80 % of them soft here too; with the hard lookup (before) 0.174 and 35 %. The
    surface's own penumbra there: 0.049."""
    sun = (120, 20)
    objs = [fc.box(*_behind(sun, (0.5, 0.0), 2.2), 1.4, 1.4, 1.0, color="firebrick"),
            fc.box(*_behind(sun, (0.5, 0.0), 3.4), 1.0, 1.0, 1.4),
            fc.pole(*_behind(sun, (0.5, 0.0), 1.2), 1.5, radius=0.12)]
    r, kind, depth, shadow = _scene(BUMP, objs, "perspective", sun, radius=4.0, steps=300)
    d = r.depth.astype(float)
    with np.errstate(invalid="ignore"):
        same = np.isfinite(d) & (kind == 2) & (np.abs(d - depth) < 0.02)
    pen = same & (shadow > 0.05) & (shadow < 0.95)
    assert pen.sum() > 60
    assert np.abs(r.shadow[pen] - shadow[pen]).mean() < 0.13
    assert ((r.shadow[pen] > 0.05) & (r.shadow[pen] < 0.95)).mean() > 0.65
    assert np.abs(r.shadow[same] - shadow[same]).mean() < 0.02     # (measured 0.015)


def test_an_objects_shadow_edge_on_another_is_the_part_of_the_pixel_in_shadow():
    """A pole's shadow across a box (antialiasing on, the default): at its edge a box
    pixel holds the part of its footprint on its face that the pole hides (16 points of
    the face's plane under the pixel, kernels/raster.py object_shadow_edges_kernel).
    Against the reference at 2 x 2 the pixels, box-filtered, on the box pixels that the
    pole's shadow edge crosses (in part in shadow with the pole, lit without it): mean
    |error| measured 0.118 (36 pixels) against 0.458 for the reference's own centre
    (what the point-sampled edge gives at best, and gave before)."""
    sun = (300, 30)
    expr = "0.2*sin(u)*cos(v)"

    def objs(pole=True):
        return [fc.box(*_behind(sun, (0.0, 0.0), 1.3), 1.6, 1.6, 1.2, color="lightgrey")] + \
            ([fc.pole(0.0, 0.0, 3.0, radius=0.15)] if pole else [])
    r, kind, depth, shadow = _scene(expr, objs(), "perspective", sun, steps=300)
    _, kind2, _, shadow2 = _scene(expr, objs(), "perspective", sun, size=(320, 240), steps=300)
    _, kind_n, _, shadow_n = _scene(expr, objs(False), "perspective", sun, size=(320, 240),
                                    steps=300)

    def per_pixel(a):
        return a.reshape(120, 2, 160, 2)
    on_box = per_pixel((kind2 == 2) & (kind_n == 2)).all(axis=(1, 3)) & (kind == 2)
    part = per_pixel(np.nan_to_num(shadow2)).mean(axis=(1, 3))
    lit_without = per_pixel(np.nan_to_num(shadow_n)).mean(axis=(1, 3)) == 0
    edge = on_box & (part > 0) & (part < 1) & lit_without
    assert edge.sum() > 25
    aa = fc.render(expr, u=(-4, 4), v=(-4, 4), size=(160, 120), elev=35, azim=20,
                   projection="perspective", lightsource=sun, shadows=True, objects=objs())
    err_aa = np.abs(aa.shadow[edge] - part[edge]).mean()
    err_centre = np.abs(shadow[edge] - part[edge]).mean()
    assert err_aa < 0.4 * err_centre, (err_aa, err_centre)
    # (antialias=False: the centre's point test, as the reference's centre)
    assert np.abs(r.shadow[edge] - shadow[edge]).mean() < 0.05


def test_objects_near_floats_limit_cast_without_a_warning():
    """Objects 1e50 to 1e300 tall: their triangles' products overflow; those beyond
    floating point cast nothing, the rest their shadows, and no warning or error shows
    (an OverflowError before the grid was guarded)."""
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for h in (1e50, 1e300):
            for proj in ("orthographic", "perspective"):
                r = fc.render("0.2*sin(u)", u=(-4, 4), v=(-4, 4), size=(60, 40),
                              lightsource=(300, 30), shadows=True, projection=proj,
                              objects=[fc.tree(0, 0, h), fc.pole(1, 1, h),
                                       fc.box(2, 2, h, h, h)])
                assert np.isfinite(r.shadow[r.side != 0]).all()


@pytest.mark.parametrize("opacity", [1.0, 0.5])
def test_a_sun_of_a_radius_gives_the_objects_shadows_penumbrae(opacity):
    """light_radius: an object's shadow on the surface is the part of the sun's disk
    it hides (16 directions), against the reference's 32 rays over the disk (its march
    over the surface coarser: the surface is gentle). Measured on the 266 pixels of the
    surface the objects alone shadow, in part or whole: mean |difference| 0.027; all of
    the reference's 120 penumbra pixels (0.1 .. 0.9) are in a penumbra here too. A
    translucent surface (opacity 0.5: each crossing tested in the 16 directions,
    kernels/layers.py) gives the same figures (before, opacity < 1 with light_radius
    was a ValueError)."""
    objs = [fc.pole(0.0, 0.0, 2.5, radius=0.1), fc.box(-1.5, 1.0, 0.8, 0.8, 1.2)]
    sun = (300, 30)
    r, kind, depth, shadow = _scene("0.2*sin(u)*cos(v)", objs, "perspective", sun,
                                    size=(120, 90), radius=3.0, steps=300, opacity=opacity)
    plain = fc.render("0.2*sin(u)*cos(v)", u=(-4, 4), v=(-4, 4), size=(120, 90), elev=35,
                      azim=20, projection="perspective", lightsource=sun, shadows=True,
                      antialias=False, light_radius=3.0, opacity=opacity)
    d = r.depth.astype(float)
    with np.errstate(invalid="ignore"):
        at = (kind == 1) & (np.abs(d - depth) < 0.02) & (plain.shadow < 0.05) & (shadow > 0)
    pen = at & (shadow > 0.1) & (shadow < 0.9)
    assert at.sum() > 150 and pen.sum() > 60
    assert np.abs(r.shadow[at] - shadow[at]).mean() < 0.045
    assert ((r.shadow[pen] > 0.05) & (r.shadow[pen] < 0.95)).mean() > 0.8

"""The scene and its parts (scene.py, material.py, light.py, camera.py, quality.py,
renderer.py and the passes): several surfaces with their own materials, lights in
their frames, the one camera fit."""
import numpy as np
import pytest

import floatcol as fc
from floatcol.camera import fit
from floatcol.passes.tiles import tile, untile

DOM = ((-2.0, 2.0), (-2.0, 2.0))


def test_two_colormaps_in_one_picture():
    """Each layer keeps its own material: a saddle in reds, a bump in blues. Where the
    composite shows layer k (stats["surface"]), its pixels take layer k's colours:
    the reds have more red than blue, the blues more blue than red."""
    scene = fc.Scene([fc.Layer("u*v/3", DOM, fc.Material(cmap="Reds", vmin=-3, vmax=1)),
                      fc.Layer("2*exp(-u**2-v**2) - 0.5", DOM,
                               fc.Material(cmap="Blues", vmin=-3, vmax=1))],
                     camera=fc.Camera(size=(160, 120), elev=30, azim=30))
    r = fc.render_scene(scene)
    which = r.stats["surface"]
    rgb = r.rgba[..., :3].astype(int)
    whole = r.rgba[..., 3] == 255
    reds = (which == 0) & whole
    blues = (which == 1) & whole
    assert reds.sum() > 2000 and blues.sum() > 300            # both are seen
    assert (rgb[reds, 0] > rgb[reds, 2]).mean() > 0.99
    assert (rgb[blues, 2] > rgb[blues, 0]).mean() > 0.99
    # render_many takes Layers among its items the same way
    r2 = fc.render_many([scene.layers[0], ("2*exp(-u**2-v**2) - 0.5", *DOM)], size=(160, 120),
                        cmap="Blues", vmin=-3, vmax=1)
    assert np.array_equal(r2.rgba, r.rgba)


def test_the_kernels_read_a_material_from_its_vector():
    """Material.table packs what the kernels read (kernels/layout.py M_*): the lower
    side's colour there is the one the picture shows where the lower side is seen
    under a flat light (ambient 1: the colour itself)."""
    from floatcol.kernels import layout as L
    m = fc.Material(lower_color=(0.2, 0.4, 0.6), ambient=1.0, specular=0.0, opacity=0.5)
    t = m.table(np.array([[-1.0, 2.0]]))
    assert t.mp.shape == (L.M_SIZE,)
    assert t.mp[L.M_LOWER:L.M_LOWER + 3].tolist() == [0.2, 0.4, 0.6]
    assert (t.mp[L.M_AMBIENT], t.mp[L.M_SPECULAR], t.mp[L.M_ALPHA]) == (1.0, 0.0, 0.5)
    assert (t.mp[L.M_WLO], t.mp[L.M_SPAN]) == (-1.0, 3.0)
    # a saddle seen from below shows its lower side: the colour given, exactly
    r = fc.render("u*v", (-1, 1), (-1, 1), size=(60, 40), elev=-30, lower_color=(0.2, 0.4, 0.6),
                  ambient=1.0, specular=0.0, antialias=False)
    lower = r.side == -1
    assert lower.sum() > 200
    assert (r.rgba[lower, :3] == np.array([51, 102, 153])).all()


def test_a_layers_order_changes_only_which_index_it_has():
    a = fc.Layer("u*v/3", DOM, fc.Material(cmap="Reds"))
    b = fc.Layer("2*exp(-u**2-v**2) - 0.5", DOM, fc.Material(cmap="Blues"))
    cam = fc.Camera(size=(120, 90))
    r1 = fc.render_scene(fc.Scene([a, b], camera=cam))
    r2 = fc.render_scene(fc.Scene([b, a], camera=cam))
    s1, s2 = r1.stats["surface"], r2.stats["surface"]
    assert np.array_equal(s1 == 0, s2 == 1) and np.array_equal(s1 == 1, s2 == 0)
    assert np.array_equal(r1.side, r2.side)


def test_a_world_light_is_fixed_to_the_surface():
    """A plane w = (u + 2v)/3 under a directional light: with no ambient and no
    highlight the intensity is |L.N| with L and N in world coordinates, whatever the
    camera's azimuth (a key light's turns with the camera)."""
    d = np.array([1.0, -0.5, 2.0])
    n = np.array([-1 / 3, -2 / 3, 1.0])
    want = abs(d @ n) / np.linalg.norm(d) / np.linalg.norm(n)
    key = []
    for azim in (-50, 10, 70, 160):
        kw = dict(u=(-1, 1), v=(-1, 1), size=(60, 45), azim=azim, elev=35, ambient=0.0,
                  specular=0.0)
        r = fc.render("(u + 2*v)/3", light=fc.Light.directional(tuple(d)), **kw)
        i = r.intensity[r.side != 0]
        assert np.abs(i - want).max() < 1e-5
        key.append(np.nanmean(fc.render("(u + 2*v)/3", light=tuple(d), **kw).intensity))
    assert max(key) - min(key) > 0.1


def test_the_sun_is_matplotlibs_lightsource():
    from matplotlib.colors import LightSource
    for az, alt in ((315, 45), (90, 10), (200, 70)):
        assert np.allclose(fc.Light.sun(az, alt).direction, LightSource(az, alt).direction)


@pytest.mark.parametrize("make,message", [
    (lambda: fc.Light("spot"), "kind must be one of"),
    (lambda: fc.Light.key((0, 0, 0)), "non-zero direction"),
    (lambda: fc.Light.directional("up"), "light must be a direction (u, v, w)"),
    (lambda: fc.Light("headlight", (1, 0, 0)), "takes no direction"),
    (lambda: fc.render("u", size=(8, 6), shading="lambert", light=fc.Light.sun()),
     "lights from the viewpoint"),
    (lambda: fc.render_scene(fc.Scene([fc.Layer("u", material=fc.Material(shading="x"))])),
     "shading must be one of"),
    (lambda: fc.render_scene(fc.Scene([])), "surfaces is empty"),
    (lambda: fc.render_scene(fc.Scene([fc.Layer("u")], quality=fc.Quality(method="ray"))),
     "method must be one of"),
    # (these two said "not enough values to unpack" and "too many values to unpack")
    (lambda: fc.render_scene(fc.Scene([fc.Layer("u", domain=((-1, 1),))])),
     "a layer's domain must be ((u_low, u_high), (v_low, v_high)) or None"),
    (lambda: fc.render_scene(fc.Scene([fc.Layer("u", domain="((0,1),(0,1))")])),
     "a layer's domain must be ((u_low, u_high), (v_low, v_high)) or None"),
])
def test_parts_say_what_to_fix(make, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        make()


def test_a_lights_direction_at_any_scale():
    """A direction is only a direction: (1e300, 1e300, 2e300) overflowed in its length
    (numpy's warning, with shadows too) and three 1e-300s underflowed to "a non-zero
    direction" error. The same pictures as (1, 1, 2), warning-free; an ordinary
    direction is kept as given."""
    import warnings
    kw = dict(u=(-3, 3), v=(-3, 3), size=(40, 30))
    ref = fc.render("sin(u)*v", light=fc.Light.directional((1, 1, 2), shadows=True), **kw).rgba
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for s in (1e300, 1e-300):
            light = fc.Light.directional((s, s, 2 * s), shadows=True)
            assert np.array_equal(fc.render("sin(u)*v", light=light, **kw).rgba, ref)
        screen = fc.render("sin(u)*v", light=(1, 2, 3), **kw).rgba
        assert np.array_equal(fc.render("sin(u)*v", light=(1e-300, 2e-300, 3e-300), **kw).rgba,
                              screen)
    assert fc.Light.directional((3, 0, 4)).direction == (3.0, 0.0, 4.0)


def test_one_camera_for_every_layer():
    """camera.fit: one scale, centre and viewpoint for all the layers, and the union
    of them fits the picture (the farther surface widens the fit)."""
    small = fc.as_surface("u*v/3")
    big = fc.as_surface("u + v")
    cam = fc.Camera(size=(200, 150), projection="perspective", elev=30, azim=20)
    q = fc.Quality()
    views, drawn, box = fit([(small, DOM), (big, ((-6, 6), (-6, 6)))], cam, q)
    assert box == (1.0, 1.0, 1.0)
    assert views[0].scale == views[1].scale and views[0].center == views[1].center
    assert (views[0].d1, views[0].d2) == (views[1].d1, views[1].d2)
    alone, _, _ = fit([(small, DOM)], cam, q)
    assert alone[0].scale > views[0].scale


def test_tiles_round_trip():
    rng = np.random.default_rng(1)
    mask = rng.random((7, 37)) > 0.5
    t = tile(mask, 16, 3)
    assert t.shape == (3, 7, 16)
    assert np.array_equal(untile(t, 37), mask)

"""Shadows (Gordon section 6.2): attached and cast, against the reference ray caster's
shadow rays (tests/reference.py shadow_rays, which shares no code with
passes/shadow.py) and an analytic outline.

Measured agreement of the lit/shadow state (shadow >= 0.5) on the pixels both see,
160x120, elev 35, azim 20 (2026-12-03; the bounds below leave a margin):

    surface          projection   sun 315/25   120/10   45/60
    exp(-u^2-v^2)    ortho          99.91 %    99.86 %  100 %
                     persp          99.90 %    99.81 %  100 %
    3 sin(u cos v)   ortho          99.76 %    99.18 %  99.43 %
                     persp          99.78 %    99.14 %  99.67 %
    sin u cos v      ortho          99.61 %    99.89 %  100 %
                     persp          99.83 %    99.90 %  100 %
    u^2 - v^2        ortho          98.77 %    99.59 %  100 %
                     persp          99.02 %    99.85 %  100 %

The misses lie along the terminator (|N.L| < 0.01: the G-buffer's interpolated
normal against the exact one) and along the edges of cast shadows (a texel wide).
"""
import numpy as np
import pytest

import floatcol as fc
from conftest import reference_for
from reference import numpy_surface, shadow_rays

CASES = [("exp(-u*u-v*v)", (-3, 3), (-3, 3), 0.996),
         ("3*sin(u*cos(v))", (-5, 5), (-5, 5), 0.989),
         ("sin(u)*cos(v)", (-5, 5), (-5, 5), 0.994),
         ("u**2 - v**2", (-2, 2), (-2, 2), 0.985)]


def _agreement(expr, U, V, proj, az, alt, size=(160, 120), elev=35, azim=20, method=True):
    r = fc.render(expr, u=U, v=V, size=size, projection=proj, elev=elev, azim=azim,
                  lightsource=(az, alt), shadows=method)
    ref = reference_for(r, expr, U, V, elev, azim, proj)
    rs = shadow_rays(numpy_surface(expr), ref, U, V, fc.Light.sun(az, alt).direction)
    both = (r.side != 0) & (ref.side == r.side)
    return ((r.shadow[both] >= 0.5) == (rs[both] >= 0.5)).mean(), r, rs, both


@pytest.mark.parametrize("expr,U,V,bound", CASES)
@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
def test_shadows_agree_with_shadow_rays(expr, U, V, bound, proj):
    for az, alt in ((315, 25), (120, 10)):
        agree, r, rs, both = _agreement(expr, U, V, proj, az, alt)
        assert agree >= bound, (az, alt, agree)
        # the same amount of shadow, within a percent of the pixels
        assert abs(np.mean(r.shadow[both] >= 0.5) - np.mean(rs[both])) < 0.015


def test_a_bumps_shadow_on_a_plane_has_its_analytic_outline():
    """A hemisphere of radius 1 on the plane w = 0 under a sun at altitude 30 deg from
    the +u direction: its shadow on the plane is the disc's shadow, the union of the
    unit disc and the ellipse-capped strip behind it, reaching u = -1/tan(30 deg) from
    the centre along the ground (the top's shadow) and |v| <= 1 across."""
    expr = "Piecewise((sqrt(1 - u**2 - v**2), u**2 + v**2 < 1), (0, True))"
    r = fc.render(expr, u=(-4, 2), v=(-2, 2), size=(300, 200), elev=89.9, azim=0,
                  lightsource=(90, 30), shadows=True, antialias=False)
    plane = (r.side != 0) & (np.abs(r.w) < 1e-6)
    u, v = r.u[plane], r.v[plane]
    s = r.shadow[plane] >= 0.5
    # a point (u, v) of the plane is shadowed iff the ray toward the sun, rising
    # tan(30 deg) per unit of -u ... going to +u, meets the sphere: its distance to
    # the centre's line is below the sphere's radius at that height
    t = np.tan(np.radians(30))
    # the ray p + s (1, 0, t) hits the unit sphere iff (u + s)^2 + v^2 + (t s)^2 < 1
    # for some s > 0: the discriminant of s^2 (1 + t^2) + 2 u s + u^2 + v^2 - 1
    disc = u ** 2 - (1 + t ** 2) * (u ** 2 + v ** 2 - 1)
    want = (disc > 0) & (u < 0) | (u ** 2 + v ** 2 < 1)
    near_edge = np.abs(disc) < 0.08                      # within about a pixel
    assert (s[~near_edge] == want[~near_edge]).mean() > 0.999
    assert want.sum() > 1000


def test_a_hole_casts_no_shadow_and_a_wall_does():
    sun = dict(lightsource=(90, 20), shadows=True, size=(160, 120), elev=60, azim=10)
    # a tall block that is a hole: nothing on the plane behind it is shadowed
    hole = fc.render("Piecewise((nan, Abs(u) < 0.5), (0, True))", u=(-3, 3), v=(-2, 2), **sun)
    seen = hole.side != 0
    assert np.nanmax(hole.shadow[seen]) < 0.5
    # the same block as a wall of height 2: the plane at -u of it is in shadow
    wall = fc.render("Piecewise((2, Abs(u) < 0.5), (0, True))", u=(-3, 3), v=(-2, 2), **sun)
    behind = (wall.side != 0) & (np.abs(wall.w) < 1e-6) & (wall.u < -0.6) & (wall.u > -0.5 - 2 / np.tan(np.radians(20)) + 0.2)
    assert behind.sum() > 200
    assert (wall.shadow[behind] >= 0.5).mean() > 0.98


def test_surfaces_shadow_each_other():
    """A floating square plate w = 1 over a plane w = 0: the plate's shadow falls on
    the plane, which the plate alone does not cast on a plane of its own."""
    plate = ("1 + 0*u", (-0.5, 0.5), (-0.5, 0.5))
    ground = ("0*u", (-3, 3), (-3, 3))
    kw = dict(size=(160, 120), elev=70, azim=15, lightsource=(90, 45), shadows=True)
    r = fc.render_many([ground, plate], **kw)
    on_ground = (r.stats["surface"] == 0) & (r.side != 0)
    u, v = r.u[on_ground], r.v[on_ground]
    # the plate's shadow on the ground: the square shifted by -1/tan(45 deg) in u
    inside = (np.abs(u + 1.0) < 0.45) & (np.abs(v) < 0.45)
    outside = (np.abs(u + 1.0) > 0.55) | (np.abs(v) > 0.55)
    assert inside.sum() > 50
    assert (r.shadow[on_ground][inside] >= 0.5).all()
    assert (r.shadow[on_ground][outside] < 0.5).mean() > 0.99
    # and the order of the surfaces does not matter
    r2 = fc.render_many([plate, ground], **kw)
    assert np.array_equal(np.isnan(r.shadow), np.isnan(r2.shadow))
    assert np.nanmax(np.abs(r.shadow - r2.shadow)) < 1e-6


def test_shadowed_points_get_ambient_light_only():
    kw = dict(u=(-5, 5), v=(-5, 5), size=(120, 90), lightsource=(315, 25), ambient=0.3,
              specular=0.0)
    r = fc.render("sin(u)*cos(v)", shadows=True, **kw)
    dark = r.shadow == 1.0
    assert dark.sum() > 500
    assert np.allclose(r.intensity[dark], 0.3, atol=1e-6)
    lit = r.shadow == 0.0
    assert (r.intensity[lit] > 0.3).mean() > 0.99
    # without shadows the same light lights both (|L.N|) and shadows nothing
    r0 = fc.render("sin(u)*cos(v)", **kw)
    assert r0.shadow is None
    assert (r0.intensity[dark] > 0.3).mean() > 0.5


def test_shadow_edges_are_antialiased_and_nan_where_nothing_is_seen():
    r = fc.render("exp(-u*u-v*v)", u=(-3, 3), v=(-3, 3), size=(160, 120),
                  lightsource=(315, 20), shadows=True, elev=50)
    assert np.isnan(r.shadow[r.side == 0]).all()
    s = r.shadow[r.side != 0]
    between = (s > 0.02) & (s < 0.98)
    assert 10 < between.sum() < 0.1 * s.size            # along the edges only


@pytest.mark.parametrize("kw,message", [
    (dict(shading="lambert", shadows=True), "lights from the viewpoint"),
    (dict(lightsource="north"), "lightsource must be"),
    (dict(lightsource=(315, 25), light=(1, 0, 0)), "either lightsource or light"),
    (dict(method="horizon", shadows=True), "shadows need shaded pictures"),
])
def test_shadow_options_say_what_to_fix(kw, message):
    with pytest.raises(ValueError, match=message):
        fc.render("u*v", size=(20, 15), **kw)


def test_the_cli_and_plot_surface_take_the_sun(tmp_path):
    from floatcol.cli import main
    out = tmp_path / "s.png"
    assert main(["render", "sin(x)*cos(y)", "--x=-5:5", "--y=-5:5", "--light", "315/25",
                 "--shadows", "--size", "80x60", "-o", str(out)]) == 0
    assert out.exists()
    p = fc.plot_surface("sin(x)*cos(y)", ("x", -5, 5), ("y", -5, 5), lightsource=(315, 25),
                        shadows=True, size=(80, 60))
    assert p.draw().shadow is not None
    # soft shadows through both doors: a penumbra of partly shadowed pixels
    soft = tmp_path / "soft.png"
    assert main(["render", "sin(x)*cos(y)", "--x=-5:5", "--y=-5:5", "--light", "315/25",
                 "--shadows", "--light-radius", "4", "--size", "80x60", "-o", str(soft)]) == 0
    assert soft.exists()
    assert main(["render", "x*y", "--light-radius", "4", "-o", str(tmp_path / "no.png")]) == 2
    assert not (tmp_path / "no.png").exists()
    bump = ("exp(-x**2-y**2)", ("x", -3, 3), ("y", -3, 3))
    sh = fc.plot_surface(*bump, lightsource=(315, 25), shadows=True, light_radius=4,
                         size=(160, 120)).draw().shadow
    hard = fc.plot_surface(*bump, lightsource=(315, 25), shadows=True,
                           size=(160, 120)).draw().shadow
    partly = lambda a: np.sum((a > 0.02) & (a < 0.98))    # noqa: E731
    assert partly(sh) > 1.2 * partly(hard)          # measured 81 and 59 pixels


def test_a_moving_sun_in_an_animation():
    a = fc.animate("exp(-x**2-y**2)*(1 + 0*t)", ("x", -3, 3), ("y", -3, 3), t=(0, 180),
                   frames=3, size=(64, 48), lightsource=lambda t: (t, 30), shadows=True,
                   progress=False)
    frames = [np.asarray(f) for f in a.frames]
    # the bump's shadow turns with the sun: the frames differ
    assert not np.array_equal(frames[0], frames[1])
    assert not np.array_equal(frames[1], frames[2])


# Soft shadows (light_radius): the part of the light's disk that the horizon hides.
# Measured against shadow_rays with the disk sampled by 32 rays (its values come in
# 1/24 steps), 160x120, elev 35, azim 20, shadow values on the pixels both see
# (2026-12-03):
#
#     surface, sun, radius          projection   mean |d|   |d| < 0.1
#     exp(-u^2-v^2), 315/25, 3 deg  ortho        0.0012     99.75 %
#                                   persp        0.0012     99.77 %
#     3 sin(u cos v), 120/15, 1 deg ortho        0.0062     98.66 %
#                                   persp        0.0056     98.79 %
#
# (with the disk's horizon along the light's azimuth alone, no strips: 0.0016 and
# 0.0079.) The misses: the terminator (as for hard shadows) and penumbrae narrower
# than a texel.
# The last bound: the part of the reference's penumbra pixels (0.1 .. 0.9) that are
# partly shadowed here too (measured 1.0 and 0.43-0.45: a 1 degree penumbra is
# narrower than a texel of these pictures, so half its pixels are the hard edge's).
SOFT = [("exp(-u*u-v*v)", (-3, 3), (-3, 3), (315, 25), 3.0, 0.004, 0.995, 0.8),
        ("3*sin(u*cos(v))", (-5, 5), (-5, 5), (120, 15), 1.0, 0.012, 0.975, 0.35)]


@pytest.mark.parametrize("expr,U,V,sun,radius,mean_bound,near_bound,soft_bound", SOFT)
@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
def test_soft_shadows_agree_with_rays_over_the_disk(expr, U, V, sun, radius, mean_bound,
                                                    near_bound, soft_bound, proj):
    r = fc.render(expr, u=U, v=V, size=(160, 120), projection=proj, elev=35, azim=20,
                  lightsource=sun, shadows=True, light_radius=radius)
    ref = reference_for(r, expr, U, V, 35, 20, proj)
    rs = shadow_rays(numpy_surface(expr), ref, U, V, fc.Light.sun(*sun).direction,
                     radius=radius, n_disk=24, steps=800)
    both = (r.side != 0) & (ref.side == r.side)
    d = np.abs(r.shadow[both] - rs[both])
    assert d.mean() < mean_bound
    assert np.mean(d < 0.1) > near_bound
    # there is a penumbra, and it is soft in the picture too
    pen = both & (rs > 0.1) & (rs < 0.9)
    assert pen.sum() > 40
    assert np.mean((r.shadow[pen] > 0.02) & (r.shadow[pen] < 0.98)) > soft_bound


def test_a_steps_penumbra_is_the_hidden_part_of_the_disk():
    """A step of height 1 along v (f = 1 for u < 0, else 0) under a sun of radius
    5 deg at 30 deg from -u: at u > 0 on the plane the horizon toward the sun stands
    at phi = atan(1/u), and the part of the disk below it is the segment
    (x sqrt(1 - x^2) + asin x) / pi + 1/2, x = (phi - 30) / 5. The penumbra spans
    u = cot 35 .. cot 25 = 1.43 .. 2.14 (measured: within 0.0046 everywhere). Away
    from the step's ends at v = -1, 1: there the rays toward the disk's sides pass
    beside the step (the penumbra reaches up to 2.14 tan 5 / cos 30 = 0.22 across)."""
    th, rho = 30.0, 5.0
    r = fc.render("Piecewise((1, u < 0), (0, True))", u=(-1, 4), v=(-1, 1), size=(500, 200),
                  elev=89.9, azim=0, lightsource=(270, th), shadows=True, light_radius=rho,
                  antialias=False)
    plane = (r.side != 0) & (np.abs(r.w) < 1e-6) & (r.u > 0.05) & (np.abs(r.v) < 0.7)
    u, s = r.u[plane], r.shadow[plane]
    # at the ends the sides of the disk show past the step: less shadow there
    end = (r.side != 0) & (np.abs(r.w) < 1e-6) & (np.abs(r.u - 1.8) < 0.1)
    assert r.shadow[end & (np.abs(r.v) > 0.97)].mean() < r.shadow[end & (np.abs(r.v) < 0.5)].mean() - 0.1
    x = np.clip((np.degrees(np.arctan2(1.0, u)) - th) / rho, -1, 1)
    want = (x * np.sqrt(1 - x * x) + np.arcsin(x)) / np.pi + 0.5
    assert np.abs(s - want).max() < 0.01
    pen = (u > 1.0 / np.tan(np.radians(th + rho))) & (u < 1.0 / np.tan(np.radians(th - rho)))
    assert pen.sum() > 5000 and (s[pen] > 0.0).all() and (s[pen] < 1.0).all()
    # a smaller sun, a narrower penumbra: the hard shadow's edge in the limit
    hard = fc.render("Piecewise((1, u < 0), (0, True))", u=(-1, 4), v=(-1, 1),
                     size=(500, 200), elev=89.9, azim=0, lightsource=(270, th), shadows=True,
                     antialias=False)
    edge = 1.0 / np.tan(np.radians(th))
    far = plane & (np.abs(r.u - edge) > 0.8)
    assert np.array_equal(r.shadow[far] >= 0.5, hard.shadow[far] >= 0.5)


@pytest.mark.parametrize("kw,message", [
    (dict(light_radius=1.0), "shadows=True"),
    (dict(shadows=True, light_radius=-1), r"light_radius must be in \[0, 30\]"),
    (dict(shadows=True, light_radius="big"), "light_radius must be an angle"),
])
def test_soft_shadow_options_say_what_to_fix(kw, message):
    with pytest.raises(ValueError, match=message):
        fc.render("sin(u)*cos(v)", size=(40, 30), lightsource=(315, 25), **kw)


@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
def test_shadows_on_the_fly_agree_with_shadow_rays(proj):
    """Section 6.2.2: the sweep without a texture. It answers each pixel from the same
    samples with the same interpolation as the texture: the same agreement (and below
    the texture's size cap the same values)."""
    expr, U, V, bound = CASES[1]
    for az, alt in ((315, 25), (120, 10)):
        agree, r, rs, both = _agreement(expr, U, V, proj, az, alt, method="on-the-fly")
        assert agree >= bound, (az, alt, agree)
        tex = fc.render(expr, u=U, v=V, size=(160, 120), projection=proj, elev=35, azim=20,
                        lightsource=(az, alt), shadows=True)
        assert np.array_equal(r.shadow, tex.shadow, equal_nan=True)


def test_on_the_fly_shadows_say_what_to_fix(tmp_path):
    from floatcol.cli import main
    with pytest.raises(ValueError, match="shadows=True .the shadow texture. for several"):
        fc.render_many([("u*v", (-1, 1), (-1, 1)), ("1 + 0*u", (-1, 1), (-1, 1))],
                       size=(40, 30), lightsource=(315, 25), shadows="on-the-fly")
    with pytest.raises(ValueError, match="soft shadows .light_radius. need the shadow texture"):
        fc.render("u*v", size=(40, 30), shadows="on-the-fly", light_radius=1)
    with pytest.raises(ValueError, match="shadows must be True, False, 'texture', 'on-the-fly'"):
        fc.render("u*v", size=(40, 30), shadows="fast")
    out = tmp_path / "x.png"
    assert main(["render", "u*v", "--shadow-method", "on-the-fly", "-o", str(out)]) == 2
    assert not out.exists()
    assert main(["render", "u*v", "--shadows", "--shadow-method", "on-the-fly", "--size",
                 "40x30", "-o", str(out)]) == 0
    assert out.exists()


def test_a_shadow_texture_is_kept_with_its_surface(monkeypatch):
    """A surface keeps its shadow texture for the last light and texel grid: a view
    turned at the same scale, or a flight's frames (the grid capped at
    passes/shadow.py MAX_TEXELS), sweep once; the pictures are those of a fresh
    surface's own texture, and another light sweeps again."""
    from matplotlib.cbook import get_sample_data

    from floatcol.passes import shadow as S
    calls = []
    sweeps = S.horizon_sweeps
    monkeypatch.setattr(S, "horizon_sweeps", lambda *a: (calls.append(1), sweeps(*a))[1])
    z = np.add.outer(np.sin(np.linspace(0, 6, 60)), np.cos(np.linspace(0, 5, 50))).T
    hf = fc.HeightField(z, u=(-5, 5), v=(-4, 4))
    kw = dict(size=(120, 90), elev=40, scale=10.0, lightsource=(315, 25), shadows=True)
    first = fc.render(hf, azim=20, **kw)
    turned = fc.render(hf, azim=35, **kw)
    assert len(calls) == 1
    fresh = fc.render(fc.HeightField(z, u=(-5, 5), v=(-4, 4)), azim=35, **kw)
    assert len(calls) == 2
    assert np.array_equal(turned.shadow, fresh.shadow, equal_nan=True)
    assert np.array_equal(turned.rgba, fresh.rgba)
    other = fc.render(hf, azim=20, **dict(kw, lightsource=(120, 25)))
    assert len(calls) == 3 and not np.array_equal(other.shadow, first.shadow, equal_nan=True)
    # a flight's three frames: one sweep; its last frame as a fresh DEM's picture
    dem = get_sample_data("jacksboro_fault_dem.npz", asfileobj=False)
    calls.clear()
    clip = fc.fly_through(dem, [(15000, 2500), (15500, 9000)], frames=3, size=(96, 54),
                          above=900, vert_exag=2, shadows=True, progress=False)
    assert len(calls) == 1
    fresh_dem = fc.read_dem(dem, vert_exag=2)               # (a new height field)
    last = fc.terrain(fresh_dem, vert_exag=1, shadows=True, fly=dict(
        position=tuple(clip.stats["positions"][2]), heading=clip.stats["headings"][2],
        size=(96, 54)))
    assert np.array_equal(clip.frames[2], last.rgba) and len(calls) == 2
    # the texture goes with its surface
    import gc
    assert S._held[0] is not None
    del clip, last, fresh_dem
    gc.collect()
    assert S._held[0] is None

"""Discontinuities (the end of Gordon section 5, not implemented in the paper): a jump
of f is located by halving and shaded as a vertical wall, not smeared."""
import math

import numpy as np
import pytest

import floatcol as fc
from conftest import reference_for
from reference import psnr, raycast

STAIRS = "floor(u + 0.5*v)"     # walls on the lines u + v/2 = k


def _world_normals(r):
    """The seen unit normals in world (u, w, v) coordinates, eqs. (1)-(2) inverted."""
    vw = r.view
    ca, sa = math.cos(vw.alpha), math.sin(vw.alpha)
    cb, sb = math.cos(vw.beta), math.sin(vw.beta)
    n = r.normal
    x, y, z = n[..., 0], n[..., 1], n[..., 2]
    s, t = y * ca + z * sa, -y * sa + z * ca
    return x * cb + t * sb, s, -x * sb + t * cb


@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
def test_walls_of_a_staircase_get_the_analytic_normal(proj):
    kw = dict(u=(-2, 2), v=(-2, 2), size=(300, 220), elev=30, azim=30, projection=proj,
              shading="lambert")
    r = fc.render(STAIRS, **kw)
    nu, nw, nv = _world_normals(r)
    seen = r.side != 0
    wall = seen & (np.abs(nw) < 0.05)
    want = np.array([-1.0, -0.5]) / math.hypot(1, 0.5)     # facing the viewer (azim 30)
    assert wall.sum() > 3000        # measured: 8914 px (ortho), 7592 px (persp)
    err = np.hypot(nu[wall] - want[0], nv[wall] - want[1])
    # measured: every wall pixel within 1e-3 in orthographic, 99.38 % in perspective
    # (the rest at a wall's upper end, where a sample on the jump has a meaningless
    # difference-quotient normal)
    assert (err < 1e-3).mean() >= (1.0 if proj == "orthographic" else 0.99)
    # everything else is a tread: the normal points straight up
    assert (seen & ~wall & (nw < 0.999)).sum() <= 10       # measured: 1 px, 6 px
    # without wall detection the risers are smeared: tread normals on them (measured:
    # no wall-like normal in orthographic, 168 px in perspective, where samples that
    # land on a jump carry a meaningless difference-quotient normal)
    plain = fc.render(STAIRS, detect=("ridge", "intensity"), **kw)
    assert (plain.side != 0).sum() == pytest.approx(seen.sum(), rel=0.01)
    assert (np.abs(_world_normals(plain)[1][plain.side != 0]) < 0.05).sum() < 0.05 * wall.sum()
    # the lambert intensity of a wall pixel is |V.N| of the wall's normal
    if proj == "orthographic":
        nz = r.normal[..., 2]
        assert np.allclose(r.intensity[wall], np.abs(nz[wall]), atol=1e-4)


def test_walls_keep_the_silhouettes_of_the_ray_caster():
    dom = (-2, 2)
    r = fc.render(STAIRS, u=dom, v=dom, size=(160, 120), elev=30, azim=30, shading="lambert")
    zero = lambda u, v: np.zeros(np.broadcast(u, v).shape)             # noqa: E731
    funcs = (lambda u, v: np.floor(u + 0.5 * v), zero, zero)
    ref = raycast(funcs, dom, dom, (160, 120), 30, 30, "orthographic", scale=r.view.scale,
                  center=r.view.center)
    assert (ref.side != 0).mean() > 0.2
    assert (r.side == ref.side).mean() >= 0.998     # measured 100 %


def test_a_piecewise_step_is_a_wall_too():
    """Exact derivatives this time (sympy differentiates Piecewise): a wall along v = 0."""
    r = fc.render("Piecewise((0, v < 0), (1, True))", u=(-1, 1), v=(-1, 1), size=(160, 120),
                  elev=30, azim=0, shading="lambert")
    nu, nw, nv = _world_normals(r)
    wall = (r.side != 0) & (np.abs(nw) < 0.05)
    assert wall.sum() > 2000        # measured: 6344 px
    assert np.abs(nv[wall] + 1).max() < 1e-3 and np.abs(nu[wall]).max() < 1e-3


@pytest.mark.parametrize("expr", ["tanh(8*u)*cos(v)", "3*sin(u*cos(v))"])
def test_steep_smooth_surfaces_are_not_walls(expr):
    """A steep but smooth slope must not be taken for a wall: the picture agrees with
    the ray caster as well with wall detection as without (measured: identical
    pictures and sample counts, 72.8 and 65.0 dB, 100 % agreement)."""
    kw = dict(u=(-3, 3), v=(-3, 3), size=(160, 120), elev=30, azim=20, shading="lambert")
    on = fc.render(expr, **kw)
    off = fc.render(expr, detect=("ridge", "intensity"), **kw)
    ref = reference_for(on, expr, (-3, 3), (-3, 3), 30, 20, "orthographic")
    assert psnr(on.intensity, ref.intensity) >= psnr(off.intensity, ref.intensity) - 0.5
    assert (on.side == ref.side).mean() >= 0.9995


def test_a_fold_seen_edge_on_is_not_a_wall():
    """Near a silhouette the column's curve turns back (a fold): its rows can jump by
    pixels between samples a hair apart in t, though f is continuous. The halving of a
    wall stopped there and lit the bracket as a vertical wall: streaks of a wrong light
    down the columns that graze the fold. A wall now needs f to jump across its
    bracket (correct.py's wall_jump). Measured (2026-12-06, perspective, elev 30, azim
    -60, 200x150): 58.37 dB against the ray caster, no pixel off by more than 0.1 in
    intensity; with every such bracket a wall, 32.66 dB and 52 pixels (30.73 dB at
    256x192, 30.80 at 512x384)."""
    expr = "3*sin(u*cos(v))"
    r = fc.render(expr, u=(-5, 5), v=(-5, 5), size=(200, 150), elev=30, azim=-60,
                  projection="perspective", shading="lambert")
    ref = reference_for(r, expr, (-5, 5), (-5, 5), 30, -60, "perspective")
    both = (r.side != 0) & (ref.side != 0)
    off = np.abs(np.nan_to_num(r.intensity) - np.nan_to_num(ref.intensity)) > 0.1
    assert psnr(r.intensity, ref.intensity) > 55.0
    assert (both & off).sum() <= 2


@pytest.mark.parametrize("proj", ["orthographic", "perspective"])
@pytest.mark.parametrize("aspect", ["equal", "auto"])
def test_no_walls_along_the_domains_edge_where_f_jumps_on_it(proj, aspect):
    """floor(u) + floor(v) over [-3, 3]^2 jumps on the domain's edges themselves
    (floor(3) = 3, floor(-3 - 1e-12) = -4). An edge sample takes f's limit from
    inside (sample.into_domain): it took f on the edge or just outside it (within the
    domain test's slack), and a wall a step high was drawn along the edge (spikes
    above the back edge, below the front). Every seen pixel whose w is not a whole
    number (a wall's) must lie on an inner step line, u or v within 0.05 of -2..2.
    Measured at 400x300, elev 30, azim -30 (pixels off the lines, before -> after):
    orthographic 2717 / 4745 (equal / auto) -> 0, perspective 66 / 402 -> 0."""
    r = fc.render("floor(u)+floor(v)", u=(-3, 3), v=(-3, 3), size=(400, 300), elev=30,
                  azim=-30, projection=proj, aspect=aspect)
    seen = r.side != 0
    w, u, v = r.w[seen], r.u[seen], r.v[seen]
    wall = np.abs(w - np.round(w)) > 0.01
    assert wall.sum() > 5000                                # measured 8439 - 15728
    lines = np.arange(-2, 3)
    on_line = ((np.abs(u[:, None] - lines).min(1) < 0.05)
               | (np.abs(v[:, None] - lines).min(1) < 0.05))
    assert (wall & ~on_line).sum() == 0

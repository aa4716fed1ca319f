import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))
# Every picture of the suite is the kernels' (reproducible), never a fresh install's
# draft (floatcol/warmup.py); tests/test_draft.py turns drafts on where it tests them.
os.environ["FLOATCOL_DRAFT"] = "0"

import floatcol as fc  # noqa: E402
from reference import numpy_surface, raycast  # noqa: E402


def reference_for(r, expr, u, v, elev, azim, projection, **kw):
    """Ray-cast the same picture as render result ``r`` (same scale, d1, d2)."""
    vw = r.view
    return raycast(numpy_surface(expr), u, v, (vw.width, vw.height), elev, azim, projection,
                   vw.d1, vw.d2, vw.scale, center=vw.center, **kw)


def matplotlib_agrees(view, world, box_points, limits, elev, azim):
    """Whether matplotlib's own Axes3D camera (orthographic, default box aspect, axis
    limits ``limits``) projects the points ``world`` (3, n) as floatcol's ``view``
    projects ``box_points`` (the same points in the view's box), up to scale and shift
    (to 1e-9 of the picture's spread)."""
    import matplotlib.pyplot as plt
    import numpy as np
    from mpl_toolkits.mplot3d import proj3d
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d", proj_type="ortho")
    for lim, set_lim in zip(limits, (ax.set_xlim, ax.set_ylim, ax.set_zlim)):
        set_lim(*lim)
    ax.view_init(elev, azim)
    mx, my, _ = proj3d.proj_transform(*world, ax.get_proj())
    plt.close(fig)
    col, row = view.project(*box_points)
    ours = np.stack([col, -row], 1)
    theirs = np.stack([mx, my], 1)
    ours = (ours - ours.mean(0)) / np.linalg.norm(ours - ours.mean(0))
    theirs = (theirs - theirs.mean(0)) / np.linalg.norm(theirs - theirs.mean(0))
    return np.abs(ours - theirs).max() < 1e-9


def plane(antialias, scale=42.3):
    """w = 0 on [-1, 1]^2, orthographic, elev 30, azim 0, origin at the image centre:
    the far edge v = 1 projects to screen y = 0.5, the near edge to -0.5, the side
    edges to x = -1 and 1."""
    return fc.render("0*u", u=(-1, 1), v=(-1, 1), size=(121, 121), elev=30, azim=0,
                     scale=scale, center=(0, 0, 0), background=(0, 0, 0, 0), antialias=antialias,
                     upper_color="white")


def assert_plane_edges(r):
    """plane()'s far and near edges cover their pixels by the analytic fraction. Far
    edge: y = 0.5 * 42.3 + 60 = 81.15 rows from the bottom; pixel 81 spans [80.5, 81.5]
    and is covered up to 81.15: 0.65. Near edge: y = 38.85, pixel 39 is covered from
    38.85 to 39.5: 0.65 too. Returns the columns checked."""
    alpha = r.rgba[..., 3] / 255.0
    top, bot = 120 - 81, 120 - 39
    cols = slice(30, 90)
    assert np.allclose(alpha[top, cols], 0.65, atol=1 / 255)
    assert np.allclose(alpha[bot, cols], 0.65, atol=1 / 255)
    assert np.all(alpha[top + 1:bot, cols] == 1.0)
    assert np.all(alpha[:top, cols] == 0.0) and np.all(alpha[bot + 1:, cols] == 0.0)
    return cols


def render_with_switch_off(monkeypatch, index, expr, **kw):
    """The render of ``expr`` with view parameter ``index`` (one of vp's test-only
    switches, kernels/layout.py) set to 0, and patched so for the rest of the test."""
    from floatcol import view as view_mod
    params = view_mod.View.params

    def switched_off(self):
        vp = params(self)
        vp[index] = 0.0
        return vp
    monkeypatch.setattr(view_mod.View, "params", switched_off)
    return fc.render(expr, **kw)


@pytest.fixture(scope="session")
def demo():
    """Gordon's 3 sin(u cos v), orthographic, rendered once."""
    return fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(160, 120), elev=30, azim=20,
                     shading="lambert")

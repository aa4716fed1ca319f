import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(__file__))

import floatcol as fc  # noqa: E402
from reference import numpy_surface, raycast  # noqa: E402


def reference_for(r, expr, u, v, elev, azim, projection, **kw):
    """Ray-cast the same picture as render result ``r`` (same scale, d1, d2)."""
    vw = r.view
    return raycast(numpy_surface(expr), u, v, (vw.width, vw.height), elev, azim, projection,
                   vw.d1, vw.d2, vw.scale, center=vw.center, **kw)


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

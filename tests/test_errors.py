"""Bad input raises ValueError naming what to fix."""
import warnings

import pytest

import floatcol as fc

class _Norm:
    """A norm as matplotlib's: callable, with an inverse (here a bad one if asked)."""
    vmin = vmax = 1.0

    def __init__(self, decreasing=False):
        self.decreasing = decreasing

    def __call__(self, w):
        return w

    def inverse(self, x):
        return -x if self.decreasing else x


CASES = [
    (dict(expr="x*y"), "unknown symbols x, y"),
    (dict(expr="3*sin(u"), "could not parse expression '3*sin(u'"),
    (dict(expr="u +* v"), "at character"),
    (dict(expr=""), "expression is empty"),
    (dict(expr="u < v"), "not a scalar expression"),
    (dict(expr=object()), "cannot draw"),
    (dict(expr="u", u=(1, 1)), "range u = (1.0, 1.0) is empty"),
    (dict(expr="u", v=(2, -2)), "range v = (2.0, -2.0) is reversed"),
    (dict(expr="u", u=("a", 1)), "range u must be a pair"),
    (dict(expr="u", u=(0, float("inf"))), "must be finite"),
    # (its width overflowed: "box's stretch factors must be positive numbers, got (1.0,
    # inf, 1.0)" after numpy's overflow warnings)
    (dict(expr="u", u=(-1e308, 1e308)), "range u = (-1e+308, 1e+308) is too wide"),
    (dict(expr="u", size=(0, 10)), "size width must be positive"),
    (dict(expr="u", size=(10, -3)), "size height must be positive"),
    (dict(expr="u", size=(10.5, 3)), "whole number"),
    (dict(expr="u", size=100), "size must be (width, height)"),
    (dict(expr="u", method="raytrace"), "method must be one of column, horizon"),
    (dict(expr="u", shading="phong"), "shading must be one of default, lambert"),
    (dict(expr="u", interpolation="cubic"), "interpolation must be"),
    (dict(expr="u", projection="fisheye"), "projection must be 'orthographic' or 'perspective'"),
    (dict(expr="u", elev=120), "elev must be between -90 and 90"),
    (dict(expr="u", azim="east"), "azim must be a number"),
    (dict(expr="u", scale=-1), "scale must be positive"),
    (dict(expr="u", projection="perspective", d1=0), "d1 must be positive"),
    (dict(expr="u", step=0), "step must be positive"),
    (dict(expr="u", norm=3), "norm must be a matplotlib norm"),
    (dict(expr="u", norm=_Norm(), vmin=0), "either norm or vmin/vmax"),
    (dict(expr="u", norm=_Norm(decreasing=True)), "monotonically"),
    (dict(expr="u", vars=("x", "x")), "two different variables"),
    (dict(expr="u", method="horizon", lines=0), "lines must be a positive whole number"),
    (dict(expr="u", cmap="no-such-map"), "unknown colormap 'no-such-map'"),
    (dict(expr="u", lower_color="notacolour"), "is not a colour"),
    (dict(expr="u", shading="lambert", light=(1, 0, 0)), "lights from the viewpoint"),
    (dict(expr="u", vmin=3, vmax=1), "vmin must not exceed vmax"),
    (dict(expr="u", vmin=float("nan")), "vmin must be a finite number"),
    (dict(expr="u", vmax="top"), "vmax must be a finite number"),
]


@pytest.mark.parametrize("kwargs,message", CASES)
def test_value_error_says_what_to_fix(kwargs, message):
    kwargs = dict(kwargs)
    expr = kwargs.pop("expr")
    with pytest.raises(ValueError) as info:
        fc.render(expr, size=kwargs.pop("size", (20, 15)), **kwargs)
    assert message in str(info.value)


def test_heightfield_errors():
    with pytest.raises(ValueError, match="2-D array of at least 2 x 2"):
        fc.HeightField([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="2-D array of numbers"):
        fc.HeightField([["a", "b"], ["c", "d"]])
    # (a range given downward is the grid flipped: test_terrain.py; an empty one is not)
    with pytest.raises(ValueError, match="range u"):
        fc.HeightField([[0, 1], [1, 0]], u=(1, 1))
    with pytest.raises(ValueError, match="range v"):
        fc.HeightField([[0, 1], [1, 0]], v=(0, float("nan")))


def test_uncompilable_callable_is_a_clear_error():
    def f(u, v):
        return {"a": u}["a"] + object()
    with pytest.raises(ValueError, match="cannot compile the callable 'f'"):
        fc.render(f, size=(20, 15))


def test_unknown_symbol_suggests_vars():
    with pytest.raises(ValueError, match=r"pass vars=\('x', 'y'\)"):
        fc.render("sin(x*y)", size=(20, 15))
    r = fc.render("sin(x*y)", vars=("x", "y"), size=(20, 15))
    assert (r.side != 0).any()


def test_a_size_beyond_the_machines_memory_is_a_bad_size(monkeypatch):
    """30000x30000 needs 74.6 GiB of buffers: a MemoryError halfway through the render
    before. Here the machine is said to have 1 GiB, and 4000x4000 needs 1.3."""
    import os
    real = os.sysconf
    monkeypatch.setattr(os, "sysconf", lambda name: 2**18 if name == "SC_PHYS_PAGES"
                        else 4096 if name == "SC_PAGE_SIZE" else real(name))
    with pytest.raises(ValueError, match=r"size 4000x4000 needs about 1\.3 GiB"):
        fc.render("u", size=(4000, 4000))
    fc.render("u", size=(400, 300))                    # 0.01 GiB: drawn
    # where the machine cannot tell its memory, a MemoryError says the same
    monkeypatch.setattr(os, "sysconf", real)
    from floatcol import _pool

    def no_memory(shape, dtype):
        raise MemoryError
    monkeypatch.setattr(_pool, "empty", no_memory)
    with pytest.raises(ValueError, match="size 400x300 needs about"):
        fc.render("u", size=(400, 300))


def test_a_surface_that_is_nowhere_finite_warns():
    # a hole everywhere: an empty picture, and a warning that says so (not an error:
    # the picture is what f is)
    with pytest.warns(RuntimeWarning, match=r"sqrt\(-u\*\*2 - 1\) is NaN, infinite or "
                      r"complex everywhere on u in \[0, 2\], v in \[1, 3\]"):
        r = fc.render("sqrt(-1-u**2)", u=(0, 2), v=(1, 3), size=(40, 30))
    assert not (r.side != 0).any()
    with pytest.warns(RuntimeWarning, match="x in"):
        fc.render("log(-1-x**2)", vars=("x", "y"), size=(40, 30), method="horizon")


@pytest.mark.parametrize("expr", ["sqrt(1-u**2-v**2)", "u*v"])
def test_a_surface_with_something_to_see_does_not_warn(expr):
    # a surface finite somewhere (the hemisphere: on a fifth of the domain) is drawn
    # without a word
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = fc.render(expr, u=(-2, 2), v=(-2, 2), size=(40, 30))
    assert (r.side != 0).any()

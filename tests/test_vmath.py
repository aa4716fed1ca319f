"""The batch evaluator: vmath's SIMD sin, cos, exp against libm, and pictures drawn
with batches against the same pictures drawn one point at a time."""
import re
import sys

import numba
import numpy as np
import pytest

import floatcol as fc
from floatcol.surface import Surface
from floatcol.kernels.vmath import VEXP_MAX, VEXP_MIN, VTRIG_MAX, vcos, vexp, vsin

render_module = sys.modules["floatcol.passes.geometry"]  # the column pass


@numba.njit(error_model="numpy")
def _apply(xs, out):
    for i in range(xs.size):
        out[0, i] = vsin(xs[i])
        out[1, i] = vcos(xs[i])
        out[2, i] = vexp(xs[i])


def _vm(xs):
    xs = np.asarray(xs, dtype=np.float64)
    out = np.empty((3, xs.size))
    _apply(xs, out)
    return out


def test_sin_cos_agree_with_libm_to_a_few_ulps():
    rng = np.random.default_rng(3)
    xs = np.concatenate([np.linspace(-30, 30, 200_001), rng.uniform(-VTRIG_MAX, VTRIG_MAX, 50_000),
                         np.arange(-40, 41) * (np.pi / 4), [0.0, 1e-300, 5e-324, -1e-8]])
    s, c, _ = _vm(xs)
    # measured: 2.2e-16 at most (2 ulp of numbers near 1); libm itself is within 1 ulp
    assert np.max(np.abs(s - np.sin(xs))) <= 4.5e-16
    assert np.max(np.abs(c - np.cos(xs))) <= 4.5e-16
    big = np.abs(np.sin(xs)) > 1e-2
    assert np.max(np.abs(s - np.sin(xs))[big] / np.spacing(np.abs(np.sin(xs[big])))) <= 2.0
    assert s[-3] == 1e-300 and s[-2] == 5e-324           # sin x = x for tiny x


def test_exp_agrees_with_libm_to_a_few_ulps():
    rng = np.random.default_rng(4)
    xs = np.concatenate([np.linspace(-20, 20, 100_001), rng.uniform(VEXP_MIN, VEXP_MAX, 50_000),
                         [0.0, VEXP_MIN, VEXP_MAX, 1e-300]])
    e = _vm(xs)[2]
    ref = np.exp(xs)
    assert np.max(np.abs(e - ref) / ref) <= 2.5e-16      # measured 2.2e-16 (1 ulp)
    assert e[-4] == 1.0


def test_out_of_range_is_nan_for_the_scalar_path_to_answer():
    xs = [VTRIG_MAX, -2e7, np.inf, -np.inf, np.nan]
    s, c, _ = _vm(xs)
    assert np.isnan(s).all() and np.isnan(c).all()
    e = _vm([VEXP_MAX + 1, VEXP_MIN - 1, 800.0, -800.0, np.inf, -np.inf, np.nan])[2]
    assert np.isnan(e).all()


def test_the_batch_loop_is_simd_code():
    fb = fc.as_surface("3*sin(u*cos(v)) + exp(-u*v)").batch()
    assert fb is not None
    ir = fb.inspect_llvm()
    # vectors of doubles, as wide as the machine has: 2 (SSE), 4 (AVX2), 8 (AVX-512)
    assert re.search(r"<(2|4|8) x double>", ir)


@pytest.mark.parametrize("expr, batch", [
    ("log(1 + u**2)", False),          # a libm call: the loop would stay scalar
    ("u**v", False),
    ("Piecewise((u, u < 0), (v, True))", False),
    ("sqrt(1 - u**2 - v**2) + u*v", True),
    ("exp(-u**2) * cos(v) / (1 + u**2)", True),
])
def test_which_expressions_get_a_batch_evaluator(expr, batch):
    assert (fc.as_surface(expr).batch() is not None) == batch


def test_a_height_field_and_a_callable_have_none():
    assert fc.HeightField(np.zeros((3, 3))).batch() is None
    assert fc.as_surface(lambda u, v: u * v).batch() is None


def _pair(monkeypatch, expr, **kw):
    """The same picture drawn with batches and one point at a time."""
    kw = dict(dict(u=(-2, 2), v=(-2, 2), size=(160, 120), shading="lambert"), **kw)
    monkeypatch.setattr(render_module, "BATCH_MIN_SAMPLES", 0)
    a = fc.render(expr, **kw)
    monkeypatch.setattr(render_module, "BATCH_MIN_SAMPLES", float("inf"))
    b = fc.render(expr, **kw)
    return a, b


@pytest.mark.parametrize("expr", [
    "3*sin(u*cos(v))",
    "sqrt(1 - u**2 - v**2)",            # holes: NaN from the batch, fg decides
    "u*v + exp(-300*(u**2 + v**2))",    # exp(x < -708): vexp says NaN, fg gives 0
    "sin(4e6*u) / 1e6 + u*v",           # beyond vsin's range: fg answers
    "cos(u)**2 - sin(v)/(u**2 + 1)",
])
def test_batches_draw_the_picture_of_single_points(monkeypatch, expr):
    a, b = _pair(monkeypatch, expr, antialias=True)
    assert a.stats["samples"] == b.stats["samples"]
    assert np.array_equal(a.side, b.side)
    seen = a.side != 0
    assert seen.mean() > 0.05
    # float32 intensity of float64 results within a few ulps: measured equal
    assert np.nanmax(np.abs(a.intensity - b.intensity)) <= 1e-6
    assert np.max(np.abs(a.rgba.astype(int) - b.rgba)) <= 1


@pytest.mark.parametrize("kw", [
    dict(shading="default"),
    dict(shading="default", corrections="spline+supersample", elev=15),
    dict(shading="default", interpolation="intensity", corrections="adaptive", elev=50),
    dict(shading="default", antialias=False, elev=-30, azim=40),
])
def test_hidden_batched_samples_change_nothing(monkeypatch, kw):
    """A batched sample strictly inside the floating interval is passed over
    (column._column_pass keeps it in the batch as the previous sample): with the
    detectors and corrections on, every sample they would have made is still made,
    and the picture is that of single points (two thirds of the default picture's
    samples are hidden)."""
    expr = "3*sin(u*cos(v))"
    a, b = _pair(monkeypatch, expr, **dict(dict(u=(-5, 5), v=(-5, 5), size=(240, 180)), **kw))
    assert a.stats["samples"] == b.stats["samples"]
    assert np.array_equal(a.side, b.side)
    assert np.nanmax(np.abs(a.intensity - b.intensity)) <= 1e-6
    assert np.max(np.abs(a.rgba.astype(int) - b.rgba)) <= 1


def test_batches_of_a_surface_in_time_use_its_time(monkeypatch):
    s = fc.as_surface("sin(u + 2*t) * cos(v)", time="t")
    a, b = _pair(monkeypatch, s.at(0.7), elev=40)
    assert np.array_equal(a.side, b.side)
    assert np.nanmax(np.abs(a.intensity - b.intensity)) <= 1e-6
    c = fc.render(s.at(0.0), u=(-2, 2), v=(-2, 2), size=(160, 120), shading="lambert", elev=40)
    assert np.nanmax(np.abs(a.intensity - c.intensity)) > 0.1   # t reaches the batch


def _wrong_batch(expr, other):
    """A new Surface of expr (not the memoized one) whose batch evaluator is other's."""
    s = fc.as_surface(expr)
    wrong = Surface(s.f, s.fg, expr=s.expr)
    wrong._batch["fn"] = fc.as_surface(other).batch()
    return wrong


def test_the_kernel_reads_the_batch(monkeypatch):
    """A batch evaluator of another function changes the picture: the kernel takes
    the planes' values from it (edges and corrections still sample f itself)."""
    s = _wrong_batch("u*v/2", "sin(3*u)*cos(2*v)")
    a, b = _pair(monkeypatch, s)
    # measured: 15 % of the pixels change side, and the shade where both see the
    # surface by 0.26 on average
    assert np.mean(a.side != b.side) > 0.05
    assert np.nanmean(np.abs(a.intensity - b.intensity)) > 0.1


def test_the_perspective_kernel_reads_the_batch(monkeypatch):
    """In perspective the batch's Newton steps place the planes' samples
    (_batch_planes_persp): a batch evaluator of another function changes the picture
    where its roots pass the scalar path's continuity test."""
    monkeypatch.setattr(render_module, "BATCH_MIN_SAMPLES", 0)
    s = _wrong_batch("u*v/2", "sin(3*u)*cos(2*v)")
    ref = fc.as_surface("u*v/2")
    a = fc.render(s, u=(-2, 2), v=(-2, 2), size=(80, 60), projection="perspective")
    b = fc.render(ref, u=(-2, 2), v=(-2, 2), size=(80, 60), projection="perspective")
    # measured (2026-12-06): 6.0 % of the pixels change side, 14.1 % change, the shade
    # where both see the surface by 0.037 on average (11.0 %, 26.3 % and 0.11 before
    # a run was broken where its samples go over to another piece of the curve,
    # column._joined and _break_run: the wrong batch's samples jump between pieces)
    assert np.mean(a.side != b.side) > 0.03
    assert np.mean(np.any(a.rgba != b.rgba, axis=-1)) > 0.07
    assert np.nanmean(np.abs(a.intensity - b.intensity)) > 0.02


def test_adaptive_sampling_does_not_batch(monkeypatch):
    monkeypatch.setattr(render_module, "BATCH_MIN_SAMPLES", 0)
    s = _wrong_batch("u*v/2", "sin(3*u)*cos(2*v)")         # would show if it were used
    ref = fc.as_surface("u*v/2")
    for kw in (dict(sampling="adaptive"), dict(sampling="adaptive", projection="perspective")):
        a = fc.render(s, u=(-2, 2), v=(-2, 2), size=(80, 60), **kw)
        b = fc.render(ref, u=(-2, 2), v=(-2, 2), size=(80, 60), **kw)
        assert np.array_equal(a.rgba, b.rgba)

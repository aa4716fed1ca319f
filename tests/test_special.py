"""Bessel functions in formulas (floatcol/kernels/special.py), of whole orders and of
any other real order, and the spherical ones:
besselj / jv / jn / j0 / j1, bessely / yv / yn / y0 / y1, besseli / iv / i0 / i1 and
besselk / kv / kn / k0 / k1, against mpmath (sympy's own
arbitrary-precision library) and, drawn, against the ray caster with a Bessel function
of its own (Bessel's integral, below), not floatcol's."""
import mpmath
import numpy as np
import pytest
import sympy as sp

import floatcol as fc
from floatcol.kernels.special import besseli, besselj, besselk, bessely
from reference import psnr, raycast


def _points():
    rng = np.random.default_rng(7)
    return np.concatenate([rng.uniform(-30, 30, 40), rng.uniform(-300, 300, 20),
                           [1e-7, 3e-6, 0.2, 24.9, 25.1, 59.9, 60.1, 1e3, 2e4]])


ORDERS = list(range(-6, 7)) + [10, 20, 45, 100]


def test_besselj_agrees_with_mpmath():
    """J_n over whole orders -6..6, 10, 20, 45, 100 and |x| up to 2e4, each regime
    (Miller's recurrence, Hankel's expansion with the upward recurrence, the tiny-x
    series): measured 2026-12-06 an absolute error of at most 1.2e-15 (at 2e4: the
    cosine of a large argument) and, where |J_n| > 1e-3, a relative one of at most
    2.2e-13."""
    worst_abs = worst_rel = 0.0
    for n in ORDERS:
        for x in _points():
            got = besselj(n, float(x))
            assert got == besselj(float(n), float(x))          # (an order as a float)
            want = float(mpmath.besselj(n, mpmath.mpf(float(x))))
            worst_abs = max(worst_abs, abs(got - want))
            if abs(want) > 1e-3:
                worst_rel = max(worst_rel, abs(got - want) / abs(want))
    assert worst_abs < 1e-14 and worst_rel < 2e-12


def test_bessely_agrees_with_mpmath():
    """Y_n for x > 0 (Miller's sweep with Neumann's series for Y_0 and its derivative
    for Y_1, Hankel's expansion beyond 25, the upward recurrence for n >= 2, which is
    stable for Y): measured 2026-12-06 an error of at most 7.1e-15 of max(1, |Y_n|)
    and, where |Y_n| > 1e-3, 3.7e-13 of |Y_n|."""
    worst_abs = worst_rel = 0.0
    for n in ORDERS[:-1]:                       # (Y_100 overflows below x = 40)
        for x in np.abs(_points()):
            want = float(mpmath.bessely(n, mpmath.mpf(float(x))))
            if not np.isfinite(want):
                continue
            got = bessely(n, float(x))
            worst_abs = max(worst_abs, abs(got - want) / max(1.0, abs(want)))
            if abs(want) > 1e-3:
                worst_rel = max(worst_rel, abs(got - want) / abs(want))
    assert worst_abs < 1e-13 and worst_rel < 5e-12


def test_besseli_agrees_with_mpmath():
    """I_n, the series and the asymptotic expansion: measured 2026-12-06 a relative
    error of at most 8.5e-14 (|x| up to 300, values up to 1e128)."""
    worst = 0.0
    for n in ORDERS:
        for x in _points():
            if abs(x) > 600:
                continue
            got = besseli(n, float(x))
            want = float(mpmath.re(mpmath.besseli(n, mpmath.mpf(float(x)))))
            if want != 0.0:
                worst = max(worst, abs(got - want) / abs(want))
    assert worst < 1e-12


def test_besselk_agrees_with_mpmath():
    """K_n by the trapezoid rule on its integral: measured 2026-12-06 a relative error
    of at most 2.0e-14 (orders 0..200, x from 1e-300 to 700; values within the
    doubles)."""
    worst = 0.0
    for n in (0, 1, 2, 3, 5, 10, 50, 200, -4):
        for x in [1e-300, 1e-8, 1e-3, 0.1, 0.5, 1.0, 2.5, 7.0, 20.0, 80.0, 300.0, 700.0]:
            want = mpmath.besselk(n, x)
            if not (1e-300 < want < 1e300):
                continue
            worst = max(worst, abs(besselk(n, x) - float(want)) / float(want))
    assert worst < 1e-13


def test_orders_and_values_that_are_not_numbers():
    """An order beyond MAX_ORDER or not a number is NaN (a hole), an infinite x J's
    limit 0 and I's infinity, NaN stays NaN: nothing raises in a kernel."""
    assert np.isnan(besselj(np.nan, 1.0)) and np.isnan(besseli(np.inf, 1.0))
    assert np.isnan(besselj(0.5, -1.0)) and np.isnan(besselk(2.5, -1.0))   # (complex)
    assert besselj(0.5, 0.0) == 0.0 and besselj(-0.5, 0.0) == np.inf
    assert besseli(1.5, np.inf) == np.inf and besselk(1.5, np.inf) == 0.0
    assert besselj(0, np.inf) == 0.0 and besseli(3, np.inf) == np.inf
    assert besseli(1, -np.inf) == -np.inf
    assert np.isnan(besselj(0, np.nan)) and np.isnan(besseli(0, np.nan))
    assert besselj(0, 0.0) == 1.0 and besselj(3, 0.0) == 0.0 and besseli(0, 0.0) == 1.0
    assert np.isnan(besselj(5000, 1.0))                   # (beyond MAX_ORDER)
    assert np.isnan(bessely(0, -1.0)) and bessely(0, 0.0) == -np.inf    # (complex; a pole)
    assert bessely(2, np.inf) == 0.0 and np.isnan(bessely(5000.5, 1.0))
    assert np.isnan(besselk(0, -1.0)) and besselk(1, 0.0) == np.inf
    assert besselk(0, np.inf) == 0.0 and besselk(0, 1e6) == 0.0       # (underflows)
    # (x^2 overflowed past 1e154: a step of 0 and a million terms an evaluation)
    assert besselk(1, 1e300) == 0.0 and besselk(1000, 1e155) == 0.0


@pytest.mark.parametrize("text, other", [
    ("besselj(2, u)", sp.besselj(2, sp.Symbol("u"))),
    ("jv(2, u)", sp.besselj(2, sp.Symbol("u"))),
    ("jn(2, u)", sp.besselj(2, sp.Symbol("u"))),
    ("j0(u) + j1(v)", sp.besselj(0, sp.Symbol("u")) + sp.besselj(1, sp.Symbol("v"))),
    ("np.i0(u) * iv(3, v)", sp.besseli(0, sp.Symbol("u")) * sp.besseli(3, sp.Symbol("v"))),
    ("y0(u) + yn(2, v) + yv(1, u)", sp.bessely(0, sp.Symbol("u")) +
     sp.bessely(2, sp.Symbol("v")) + sp.bessely(1, sp.Symbol("u"))),
    ("k0(u) * kv(2, v) + kn(1, u) + k1(v)", sp.besselk(0, sp.Symbol("u")) *
     sp.besselk(2, sp.Symbol("v")) + sp.besselk(1, sp.Symbol("u")) +
     sp.besselk(1, sp.Symbol("v"))),
])
def test_formulas_name_them_as_sympy_and_scipy_do(text, other):
    """The same surface from a string in sympy's, scipy's or numpy's names as from
    sympy's expression: the same heights."""
    u = np.linspace(0.5, 9.0, 7)
    a, b = fc.as_surface(text), fc.as_surface(other)
    for x in u:
        for y in u:
            assert a.f(x, y, 0.0) == b.f(x, y, 0.0)
    assert np.isfinite(a.f(3.0, 2.0, 0.0))


@pytest.mark.parametrize("text, match", [
    ("besselj(u, v)", "order must be a number from -1000 to 1000"),
    ("iv(2000, u)", "order must be a number from"), ("besseli(v, 2)", "order must be a"),
    ("yv(I, u)", "order must be a number"),
    ("spherical_jn(0.5, u)", "jn's order must be a whole number")])
def test_an_order_that_is_not_a_number_in_range_says_so(text, match):
    with pytest.raises(ValueError, match=match):
        fc.render(text, u=(-3, 3), v=(-3, 3), size=(20, 15))


FRACTIONAL = [0.5, -0.5, 1 / 3, -1 / 3, 2 / 3, 1.5, 2.25, -2.25, 7.5, 10.1, -10.1, 45.5,
              100.3, 0.001, -0.999, 999.5]


@pytest.mark.parametrize("fn, ref", [(besselj, mpmath.besselj), (bessely, mpmath.bessely),
                                     (besseli, mpmath.besseli), (besselk, mpmath.besselk)])
def test_orders_that_are_not_whole_agree_with_mpmath(fn, ref):
    """J_nu, Y_nu (Steed's and Temme's methods, Numerical Recipes' bessjy, or Hankel's
    expansion at the order's fraction and the upward recurrence), I_nu (its series or
    asymptotic expansion) and K_nu (the trapezoid rule) over orders from -10.1 to 999.5
    and x up to 2e4 (I and K: 600): measured 2026-12-07 an error of at most 6.9e-14 of
    max(1, |value|), and where |value| > 1e-3, 7.4e-12 relative (at x = 2e4: the
    cosine of a large argument; 7e-14 below x = 300). Before, a hole (NaN)."""
    rng = np.random.default_rng(5)
    xs = np.concatenate([rng.uniform(0, 30, 40), rng.uniform(30, 300, 10),
                         [1e-8, 1e-3, 1.999, 2.001, 24.9, 25.1, 1e3, 2e4]])
    worst_abs = worst_rel = 0.0
    with mpmath.workdps(40):
        for nu in FRACTIONAL:
            for x in xs:
                if fn in (besseli, besselk) and x > 600:
                    continue
                want = ref(mpmath.mpf(nu), mpmath.mpf(float(x)))
                if mpmath.im(want) != 0 or not mpmath.isfinite(want) or abs(want) > 1e300:
                    continue
                want = float(mpmath.re(want))
                got = fn(nu, float(x))
                worst_abs = max(worst_abs, abs(got - want) / max(1.0, abs(want)))
                if abs(want) > 1e-3:
                    worst_rel = max(worst_rel, abs(got - want) / abs(want))
    assert worst_abs < 5e-13 and worst_rel < 5e-11


def test_spherical_bessel_functions_agree_with_mpmath():
    """j_n and y_n (sympy's jn and yn, scipy's spherical_jn and spherical_yn), whole
    orders -3..20, x of both signs: 5.7e-13 relative measured (j_1 near a zero at
    x = 300)."""
    from floatcol.kernels.special import sph_jn, sph_yn
    worst = 0.0
    with mpmath.workdps(40):
        for n in (0, 1, 2, 5, 20, -1, -3):
            for x in (1e-5, 0.3, 1.0, 2.5, 7.0, 30.0, 300.0, -2.5, -30.0):
                ax = mpmath.mpf(abs(x))
                for fn, ref, odd in ((sph_jn, mpmath.besselj, n % 2),
                                     (sph_yn, mpmath.bessely, (n + 1) % 2)):
                    want = mpmath.sqrt(mpmath.pi / (2 * ax)) * ref(n + 0.5, ax)
                    want = float(want) * (-1.0 if x < 0 and odd else 1.0)
                    worst = max(worst, abs(fn(float(n), x) - want) / abs(want))
    assert worst < 5e-12
    assert sph_jn(0.0, 0.0) == 1.0 and sph_jn(3.0, 0.0) == 0.0 and sph_yn(1.0, 0.0) == -np.inf


def _jn(n, x, nodes=64):
    """J_n(x) by Bessel's integral (1/2pi) int_0^2pi cos(n t - x sin t) dt (A&S 9.1.21),
    the trapezoid rule on its periodic integrand (exact to double precision for
    |x| + n well below ``nodes``)."""
    t = np.linspace(0.0, 2.0 * np.pi, nodes, endpoint=False)
    x = np.asarray(x, dtype=float)
    return np.cos(n * t - x[..., None] * np.sin(t)).mean(axis=-1)


def test_the_integral_is_bessels():
    """The reference's own J_n (the trapezoid rule) against mpmath: 1e-14."""
    x = np.linspace(0.0, 14.0, 57)
    for n in (1, 2, 3):
        want = np.array([float(mpmath.besselj(n, float(v))) for v in x])
        assert np.abs(_jn(n, x) - want).max() < 1e-14


#: the ray caster's J_1, J_2, J_3: Bessel's integral on r in [0, R_MAX] every 1/2048,
#: linear between (its error below 1e-7: h^2 / 8 |J''|)
R_MAX = 8.5
_TABLE_R = np.linspace(0.0, R_MAX, int(R_MAX * 2048) + 1)
_TABLE = {}


def _j(n, r):
    if n not in _TABLE:
        _TABLE[n] = _jn(n, _TABLE_R)
    return np.interp(r, _TABLE_R, _TABLE[n], right=np.nan)


def _drum_mode():
    """w = J_2(r) cos(2 phi) = J_2(r) (u^2 - v^2) / r^2 and its partials, for the ray
    caster (J_2' = (J_1 - J_3) / 2, A&S 9.1.27)."""
    def parts(u, v):
        r2 = u * u + v * v
        r = np.sqrt(r2)
        c = (u * u - v * v) / r2
        return r, c, _j(2, r), 0.5 * (_j(1, r) - _j(3, r))

    def f(u, v):
        with np.errstate(all="ignore"):
            u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
            r2 = u * u + v * v
            return _j(2, np.sqrt(r2)) * (u * u - v * v) / r2

    def fu(u, v):
        with np.errstate(all="ignore"):
            u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
            r, c, j2, dj2 = parts(u, v)
            return dj2 * u / r * c + j2 * 4.0 * u * v * v / r ** 4

    def fv(u, v):
        with np.errstate(all="ignore"):
            u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
            r, c, j2, dj2 = parts(u, v)
            return dj2 * v / r * c - j2 * 4.0 * u * u * v / r ** 4
    return f, fu, fv


@pytest.mark.parametrize("projection, min_psnr", [("orthographic", 72.0),
                                                  ("perspective", 75.0)])
def test_a_drum_mode_matches_the_ray_caster(projection, min_psnr):
    """A drum's (2, 2) mode J_2(r) cos(2 phi) on r < 8.4, drawn from the formula (its
    partials sympy's, through J_1 and J_3) against the ray caster with Bessel's
    integral: measured 2026-12-06 100 % of the pixels on the same side, 77.47 dB
    orthographic and 80.73 dB perspective."""
    expr = "besselj(2, sqrt(u^2 + v^2)) * (u^2 - v^2) / (u^2 + v^2)"
    dom = (-6.0, 6.0)
    r = fc.render(expr, u=dom, v=dom, size=(100, 75), elev=35, azim=30,
                  projection=projection, shading="lambert")
    vw = r.view
    ref = raycast(_drum_mode(), dom, dom, (100, 75), 35, 30, projection, vw.d1, vw.d2,
                  vw.scale, center=vw.center)
    assert (ref.side != 0).mean() > 0.3
    assert (r.side == ref.side).mean() >= 0.9999
    assert psnr(r.intensity, ref.intensity) >= min_psnr

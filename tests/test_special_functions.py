"""Special functions in formulas beyond Bessel's (floatcol/kernels/airy.py,
integrals.py, gammas.py): Airy's, the exponential, logarithmic, sine, cosine and
Fresnel integrals, erfi, the inverse error functions, the polygamma functions,
Lambert's W, the zeta functions and the elliptic integrals, against mpmath (sympy's
own arbitrary-precision library, at 40 digits) and, drawn, against the ray caster
with mpmath's values interpolated, not floatcol's. The bounds are what was measured
on 2026-12-07, with a margin."""
import functools
import math

import mpmath
import numba
import numpy as np
import pytest
import sympy as sp

import floatcol as fc
from floatcol.kernels import airy, gammas, integrals
from reference import psnr, raycast

RNG = np.random.default_rng(2026)


@pytest.fixture(autouse=True)
def _forty_digits():
    with mpmath.workdps(40):
        yield


def _worst(fn, ref, xs, floor=1e-300):
    """The largest relative error of fn against mpmath's ref over xs, where ref is
    real and finite; errors are relative to max(|ref|, floor)."""
    worst = 0.0
    for x in xs:
        want = ref(mpmath.mpf(float(x)))
        if mpmath.im(want) != 0 or not mpmath.isfinite(want):
            continue
        want = float(mpmath.re(want))
        worst = max(worst, abs(fn(float(x)) - want) / max(abs(want), floor))
    return worst


def test_airy_functions_agree_with_mpmath():
    """Ai, Bi, Ai', Bi': x > 0 relative errors of at most 1.5e-13 (measured); x < 0,
    where they oscillate, errors of at most 1.7e-12 of the envelope |x|^-1/4 (|x|^1/4
    for the derivatives), at x = -7 where the series hands over to the oscillating
    expansions, 1e-15 elsewhere."""
    pos = np.concatenate([RNG.uniform(0.0, 15.0, 60), [1e-300, 0.99, 1.01, 11.9, 12.1, 50,
                                                       100]])
    neg = np.concatenate([RNG.uniform(-40.0, 0.0, 60), [-6.99, -7.0, -7.01, -100.0]])
    for fn, ref, power in ((airy.airyai, mpmath.airyai, -0.25),
                           (airy.airybi, mpmath.airybi, -0.25),
                           (airy.airyaiprime, lambda x: mpmath.airyai(x, 1), 0.25),
                           (airy.airybiprime, lambda x: mpmath.airybi(x, 1), 0.25)):
        assert _worst(fn, ref, pos) < 1e-12
        worst = max(abs(fn(float(x)) - float(ref(mpmath.mpf(float(x)))))
                    / max(abs(x), 1.0) ** power for x in neg)
        assert worst < 1e-11
    assert airy.airyai(np.inf) == 0.0 and airy.airyai(1e300) == 0.0
    assert airy.airybi(200.0) == np.inf                        # (beyond the doubles)
    assert np.isnan(airy.airyai(-np.inf)) and np.isnan(airy.airybi(np.nan))
    assert airy.airyai(0.0) == airy.C1 and airy.airyaiprime(0.0) == -airy.C2


def test_exponential_and_trigonometric_integrals_agree_with_mpmath():
    """Si, Ci, Shi, Chi, Ei, li and E_n (orders -10 to 50): relative errors of at most
    6e-15 measured, but near the zeros of Ci, Chi and li, where the errors are taken
    relative to max(|value|, 0.01): 4.6e-14 (an absolute error of 5e-16)."""
    xs = np.concatenate([np.linspace(-60.0, 60.0, 121), RNG.uniform(-5.0, 5.0, 60),
                         [1e-300, 1e-8, 1.9999, 2.0001, 39.99, 40.01, 100.0, 700.0, 1e5]])
    for fn, ref in ((integrals.Si, mpmath.si), (integrals.Shi, mpmath.shi),
                    (integrals.Ei, mpmath.ei)):
        assert _worst(fn, ref, xs[np.abs(xs) < 700]) < 2e-14
    pos = xs[xs > 0]
    assert _worst(integrals.Ci, mpmath.ci, pos, floor=1e-2) < 1e-13
    assert _worst(integrals.Chi, mpmath.chi, pos[pos < 700], floor=1e-2) < 1e-13
    assert _worst(integrals.li, mpmath.li, pos, floor=1e-2) < 1e-13
    assert _worst(integrals.Li, lambda x: mpmath.li(x, offset=True), pos + 2.5) < 2e-14
    for n in (0, 1, 2, 3, 10, 50, -1, -3, -10):
        assert _worst(lambda x: integrals.expint(float(n), x),
                      lambda x: mpmath.expint(n, x), pos) < 2e-14, n
    # holes where complex or a pole; limits at infinity
    assert np.isnan(integrals.Ci(-1.0)) and np.isnan(integrals.Chi(-1.0))
    assert np.isnan(integrals.expint(1.0, -1.0)) and np.isnan(integrals.expint(1.5, 1.0))
    assert integrals.expint(1.0, 0.0) == np.inf and integrals.expint(3.0, 0.0) == 0.5
    assert integrals.Si(np.inf) == math.pi / 2 and integrals.Ci(np.inf) == 0.0
    assert integrals.Ei(-np.inf) == 0.0 and integrals.Ei(0.0) == -np.inf
    assert integrals.li(0.0) == 0.0 and integrals.li(1.0) == -np.inf


def test_fresnel_integrals_and_erfi_agree_with_mpmath():
    """S, C (sympy's normalisation) and erfi: 8e-15 measured, but 7e-12 for C at x =
    1e5 (the cosine of pi x^2 / 2 = 1.6e10, an argument known to its last bits) and
    5.4e-14 for erfi at x = 25.6 (exp(x^2) of x^2 = 655)."""
    xs = np.concatenate([np.linspace(-60.0, 60.0, 241), RNG.uniform(-3.0, 3.0, 40),
                         [1e-300, 1.4999, 1.5001, 1e3]])
    assert _worst(integrals.fresnels, mpmath.fresnels, xs) < 2e-13
    assert _worst(integrals.fresnelc, mpmath.fresnelc, xs) < 2e-13
    assert _worst(integrals.erfi, mpmath.erfi, xs[np.abs(xs) < 26]) < 2e-13
    assert abs(integrals.fresnelc(1e5) - float(mpmath.fresnelc(1e5))) < 1e-11
    assert abs(integrals.fresnels(1e9) - 0.5) < 1e-9          # (the far asymptote)
    assert integrals.fresnels(-np.inf) == -0.5 and integrals.erfi(-np.inf) == -np.inf


def test_polygamma_agrees_with_mpmath():
    """psi^(n), n = 0..200: x > 0 relative errors of at most 1.7e-13 measured (n =
    200); x < 0, among the poles, errors of at most 6e-14 of the nearest pole's term
    n! / d^(n+1) (the value itself may be far smaller: the poles' terms cancel at
    half-integers, and so would any method's digits)."""
    pos = np.concatenate([RNG.uniform(0.0, 40.0, 40), [1e-8, 0.5, 1.0, 15.9, 16.1, 1e5]])
    neg = np.concatenate([RNG.uniform(-20.0, 0.0, 30), [-0.5, -1.5, -2.7, -100.3]])
    for n in (0, 1, 2, 3, 6, 20, 50, 200):
        assert _worst(lambda x: gammas.polygamma(float(n), x),
                      lambda x: mpmath.polygamma(n, x), pos) < 1e-12, n
        for x in neg:
            d = x - math.floor(x)
            d = min(d, 1.0 - d)
            term = float(mpmath.factorial(n)) / d ** (n + 1)
            want = float(mpmath.polygamma(n, x))
            if np.isfinite(want):           # (psi^(200) of x < 0 overflows: a hole here)
                got = gammas.polygamma(float(n), float(x))
                assert abs(got - want) <= 5e-13 * term, (n, x)
    assert np.isnan(gammas.polygamma(0.0, -3.0)) and np.isnan(gammas.polygamma(1.5, 2.0))
    assert gammas.polygamma(0.0, np.inf) == np.inf and gammas.polygamma(2.0, np.inf) == 0.0


def test_inverse_error_functions_agree_with_mpmath():
    """erfinv and erfcinv to 2.2e-16 relative (measured), down to erfcinv(1e-300)."""
    ys = np.concatenate([RNG.uniform(-1.0, 1.0, 200), [1e-300, 0.49999, 0.50001,
                                                       0.999999, 1 - 1e-15, -1 + 1e-12]])
    assert _worst(gammas.erfinv, mpmath.erfinv, ys) < 1e-15
    zs = np.concatenate([RNG.uniform(0.0, 2.0, 200), [1e-300, 1e-20, 1e-5, 1.5,
                                                      2 - 1e-15]])
    want = []
    for z in zs:                        # (1 - z in enough digits to hold z)
        with mpmath.workdps(400 if z < 1e-12 else 40):
            want.append(float(mpmath.erfinv(1 - mpmath.mpf(float(z)))))
    got = np.array([gammas.erfcinv(float(z)) for z in zs])
    assert np.abs(got - want).max() / np.abs(want).max() < 1e-15
    assert np.all(np.abs(got - want) <= 1e-15 * np.abs(want))
    assert gammas.erfinv(1.0) == np.inf and gammas.erfcinv(2.0) == -np.inf
    assert np.isnan(gammas.erfinv(1.5)) and np.isnan(gammas.erfcinv(-0.1))


def test_lambert_w_agrees_with_mpmath():
    """Both real branches to 1.3e-15 relative (measured), at the branch point too,
    where x + 1/e is taken with 1/e in two doubles and W is its series there."""
    x0 = np.concatenate([RNG.uniform(-0.3678, 10.0, 100), np.exp(RNG.uniform(-50, 700, 40)),
                         [-0.3678794411714, -0.36787944117144, -1e-10, 1e-300, 3.0]])
    assert _worst(lambda x: gammas.LambertW(x, 0.0), lambda x: mpmath.lambertw(x, 0),
                  x0) < 1e-14
    xm = np.concatenate([RNG.uniform(-0.3678, 0.0, 100), [-0.3678794411714, -1e-300]])
    assert _worst(lambda x: gammas.LambertW(x, -1.0), lambda x: mpmath.lambertw(x, -1),
                  xm) < 1e-14
    assert gammas.LambertW(-1 / math.e, 0.0) == pytest.approx(-1.0, abs=1e-8)
    assert np.isnan(gammas.LambertW(-0.5, 0.0)) and np.isnan(gammas.LambertW(1.0, -1.0))
    assert np.isnan(gammas.LambertW(1.0, 1.0)) and gammas.LambertW(0.0, -1.0) == -np.inf


def test_zeta_functions_agree_with_mpmath():
    """Riemann's zeta over s from -60 to 60 (its functional equation for s < 0):
    5.2e-14 relative (measured, at s = -56.9); Hurwitz's for s > -1 and a from 0.1 to
    30: 1.3e-10 of max(1, |zeta|) measured (at s = -0.63, a = 0.1, where the
    Euler-Maclaurin sum loses digits), 1e-14 for s > 0; Dirichlet's eta."""
    ss = np.concatenate([RNG.uniform(-60.0, 60.0, 120), [-2.0, -1.0, 0.0, 0.5, 0.999999,
                                                        1.000001, 40.5, 1e3]])
    assert _worst(lambda s: gammas.zeta(s, 1.0), mpmath.zeta, ss[ss != -2]) < 2e-13
    assert _worst(gammas.dirichlet_eta, mpmath.altzeta, ss) < 2e-13
    for a in (0.1, 0.5, 2.5, 30.0):
        for s in ss[(ss > -1.0) & (ss != 1.0)]:
            want = float(mpmath.zeta(s, a))
            if not np.isfinite(want):
                assert gammas.zeta(float(s), a) == want
                continue
            err = abs(gammas.zeta(float(s), a) - want)
            assert err <= (1e-13 if s > 0 else 1e-9) * max(1.0, abs(want)), (s, a)
    assert gammas.zeta(-2.0, 1.0) == 0.0 and gammas.zeta(-1e300, 1.0) == 0.0
    assert gammas.zeta(1.0, 1.0) == np.inf and gammas.zeta(1e300, 1.0) == 1.0
    assert np.isnan(gammas.zeta(-3.5, 2.0)) and np.isnan(gammas.zeta(2.0, -1.0))


def test_beta_past_where_its_gammas_overflow():
    """Euler's B(a, b) for a + b > 171, where the quotient Gamma(a) Gamma(b) / Gamma(a + b)
    sympy prints is inf/inf (a hole): against Gamma's logarithms at 60 digits (mpmath's
    own beta gives beta(1e100, 2) = 1.0 even at 40 digits) and B(a, 2) = 1 / (a (a +
    1)). The error of exp(x) is that of x relative to 1, so the bound is relative to
    |ln B|: measured 1.04e-15 |ln B| B at worst over 9 000 random pairs (a = 51, b =
    157; 2.9e-13 relative at B = 1e-242); below a + b = 171 the quotient as before,
    bit for bit."""
    def want(a, b):
        with mpmath.workdps(60):
            a, b = mpmath.mpf(a), mpmath.mpf(b)
            return float(mpmath.exp(mpmath.loggamma(a) + mpmath.loggamma(b)
                                    - mpmath.loggamma(a + b)))
    pairs = [(85.6, 85.6), (90.0, 81.5), (100.0, 100.0), (170.0, 1.5), (300.0, 0.5),
             (1e6, 3.5), (2.0, 1e10), (1e3, 700.0), (171.0, 1e-300)]
    pairs += [tuple(x) for x in RNG.uniform(1.0, 400.0, (40, 2)) if x.sum() > 171.0]
    for a, b in pairs:
        got, ref = gammas.beta(a, b), want(a, b)
        if ref == 0.0:                                  # (under the doubles)
            assert got == 0.0, (a, b, got)
            continue
        assert abs(got - ref) <= 2e-15 * max(1.0, abs(math.log(ref))) * ref, (a, b, got, ref)
    for a in (1e10, 1e20, 1e100, 1e150):
        ref = 1.0 / (a * (a + 1.0))
        assert abs(gammas.beta(a, 2.0) - ref) <= 2e-15 * abs(math.log(ref)) * ref, a
    assert gammas.beta(1e300, 2.0) == 0.0 and gammas.beta(1e300, 1e300) == 0.0
    # (the quotient sympy printed, compiled: Numba's gamma, an ulp off Python's at times)
    quotient = numba.njit(lambda a, b: math.gamma(a) * math.gamma(b) / math.gamma(a + b))
    for a, b in ((5.0, 2.0), (0.5, 2.0), (-0.5, 2.0), (3.5, 7.25), (100.0, 70.5),
                 (170.0, 0.9)):
        assert gammas.beta(a, b) == quotient(a, b)
    # a formula's and a constant's the same
    s = fc.as_surface("beta(u, 2) + beta(1e10, v)")
    w = s.evaluate(np.array([1e10, 1e100]), np.array([2.0, 2.0]))
    b10 = 1.0 / (1e10 * (1e10 + 1.0))
    assert abs(w[0] - 2 * b10) <= 1e-12 * b10 and abs(w[1] - (1e-200 + b10)) <= 1e-12 * b10
    c = fc.as_surface("beta(1e100, 2) + 0*u").evaluate(np.zeros(1), np.zeros(1))[0]
    assert abs(c - 1e-200) <= 1e-12 * 1e-200


def test_elliptic_integrals_agree_with_mpmath():
    """K(m), E(m), F(phi|m), E(phi|m), sympy's and scipy's parameter m: 7.8e-16
    relative (measured; the arithmetic-geometric mean had run on where a and b stayed
    an ulp apart, E(-10.97) a hundredth off: that case is here)."""
    ms = np.concatenate([RNG.uniform(-50.0, 1.0, 100), [0.0, 1 - 1e-12, -1e6, -10.97]])
    assert _worst(gammas.elliptic_k, mpmath.ellipk, ms) < 2e-15
    assert _worst(gammas.elliptic_e1, mpmath.ellipe, ms) < 2e-15
    for phi in RNG.uniform(-8.0, 8.0, 25):
        for m in list(ms[:10]) + [0.9, 1.5]:
            for fn, ref in ((gammas.elliptic_f, mpmath.ellipf),
                            (gammas.elliptic_e, mpmath.ellipe)):
                want = ref(mpmath.mpf(float(phi)), mpmath.mpf(float(m)))
                got = fn(float(phi), float(m))
                if mpmath.im(want) != 0:
                    assert np.isnan(got)
                else:
                    assert abs(got - float(want)) <= 2e-15 * abs(float(want)) + 1e-300
    assert gammas.elliptic_k(1.0) == np.inf and np.isnan(gammas.elliptic_k(1.5))
    assert gammas.elliptic_e1(1.0) == 1.0


#: every function at extreme arguments: each returns (a number, an infinity or a hole)
#: at once; before, zeta(1e300) summed 1e300 terms and S(1e300) ran its continued
#: fraction 100 000 times on NaN
EXTREMES = [0.0, -0.0, 5e-324, 1e-300, -1e-300, 1e300, -1e300, np.inf, -np.inf, np.nan,
            0.5, -0.5, 1.0, -1.0, 709.0, 745.0, -745.0, 1e10, -1e10]


@pytest.mark.parametrize("fn", [
    airy.airyai, airy.airybi, airy.airyaiprime, airy.airybiprime, integrals.Si,
    integrals.Ci, integrals.Shi, integrals.Chi, integrals.Ei, integrals.li,
    integrals.fresnels, integrals.fresnelc, integrals.erfi, gammas.erfinv, gammas.erfcinv,
    gammas.elliptic_k, gammas.elliptic_e1, gammas.dirichlet_eta,
    lambda x: integrals.expint(5.0, x), lambda x: integrals.expint(-5.0, x),
    lambda x: gammas.polygamma(3.0, x), lambda x: gammas.LambertW(x, -1.0),
    lambda x: gammas.LambertW(x, 0.0), lambda x: gammas.zeta(x, 1.0),
    lambda x: gammas.zeta(x, 0.3), lambda x: gammas.zeta(2.0, x),
    lambda x: gammas.elliptic_f(x, 0.5), lambda x: gammas.elliptic_e(1.0, x),
    lambda x: gammas.beta(x, 2.5), lambda x: gammas.beta(x, x)])
def test_extreme_arguments_give_a_number_or_a_hole(fn):
    for x in EXTREMES:
        y = fn(x)
        assert isinstance(y, float)
        if np.isnan(x):
            assert np.isnan(y)


U, V = sp.symbols("u v")
#: sympy's names that its mpmath printer does not translate
MPMATH_NAMES = {"airyaiprime": lambda x: mpmath.airyai(x, 1),
                "airybiprime": lambda x: mpmath.airybi(x, 1),
                "Li": lambda x: mpmath.li(x, offset=True),
                "erfcinv": lambda x: mpmath.erfinv(1 - x)}


@pytest.mark.parametrize("text, other", [
    ("airyai(u) + airybi(v) + airyaiprime(u) * airybiprime(v)",
     sp.airyai(U) + sp.airybi(V) + sp.airyaiprime(U) * sp.airybiprime(V)),
    ("Si(u) + Ci(v) + Shi(u) * Chi(v) + expi(u) + exp1(v) + expn(2, v) + li(v) + Li(v)",
     sp.Si(U) + sp.Ci(V) + sp.Shi(U) * sp.Chi(V) + sp.Ei(U) + sp.expint(1, V) +
     sp.expint(2, V) + sp.li(V) + sp.Li(V)),
    ("fresnels(u) + fresnelc(v) + erfi(u) + erfinv(v / 10) + erfcinv(v / 10)",
     sp.fresnels(U) + sp.fresnelc(V) + sp.erfi(U) + sp.erfinv(V / 10) +
     sp.erfcinv(V / 10)),
    ("psi(u) + polygamma(2, v) + trigamma(u) + factorial(v) + gammaln(u) + beta(u, v)",
     sp.digamma(U) + sp.polygamma(2, V) + sp.trigamma(U) + sp.gamma(V + 1) +
     sp.loggamma(U) + sp.beta(U, V)),
    ("lambertw(u) + LambertW(-v / 30, -1) + zeta(u + 1) + zeta(v, u) + dirichlet_eta(v)",
     sp.LambertW(U) + sp.LambertW(-V / 30, -1) + sp.zeta(U + 1) + sp.zeta(V, U) +
     sp.dirichlet_eta(V)),
    ("ellipk(-u) + ellipe(-v) + ellipkinc(u, v / 10) + ellipeinc(v, u / 10) + "
     "elliptic_e(-u)", sp.elliptic_k(-U) + sp.elliptic_e(-V) + sp.elliptic_f(U, V / 10) +
     sp.elliptic_e(V, U / 10) + sp.elliptic_e(-U)),
])
def test_formulas_name_them_as_sympy_and_scipy_do(text, other):
    """The same surface from a string in sympy's or scipy's names as from sympy's
    expression, and its heights mpmath's (each function's compiled form reached
    through sympy's printer: factorial as gamma, zeta's and LambertW's second
    argument, elliptic_e of one and of two arguments, the Fresnel integrals, which
    sympy's printer refuses)."""
    pts = [(0.7, 1.3), (1.9, 2.6), (3.1, 0.45)]
    a, b = fc.as_surface(text), fc.as_surface(other)
    mp = sp.lambdify((U, V), other, [MPMATH_NAMES, "mpmath"])
    for x, y in pts:
        got = a.f(x, y, 0.0)
        assert got == b.f(x, y, 0.0)
        want = complex(mp(mpmath.mpf(x), mpmath.mpf(y)))
        assert abs(got - want.real) <= 1e-12 * max(1.0, abs(want.real)), (x, y)


@pytest.mark.parametrize("text, match", [
    ("expint(2.5, u)", "expint's order must be a whole number"),
    ("expn(v, u)", "expint's order must be a whole number"),
    ("polygamma(u, v)", "polygamma's order must be a whole number from 0"),
    ("LambertW(u, 1)", "LambertW's branch must be 0 or -1"),
    ("elliptic_pi(u, v)", "unknown function elliptic_pi"),
    (sp.elliptic_pi(U, V), "no compiled form of elliptic_pi"),
    (sp.airyai(U) + sp.hyper([1], [2], V), "no compiled form of hyper"),
])
def test_what_is_not_computed_says_so(text, match):
    with pytest.raises(ValueError, match=match):
        fc.render(text, u=(0.1, 0.9), v=(0.1, 0.9), size=(20, 15))


def _hermite(nodes, values, slopes):
    """The cubic Hermite interpolant of a 1-D function from its values and slopes on
    uniform nodes (error h^4 / 384 |g''''|), NaN outside them."""
    h = nodes[1] - nodes[0]

    def g(x):
        x = np.asarray(x, dtype=float)
        i = np.clip(((x - nodes[0]) // h).astype(int), 0, len(nodes) - 2)
        t = (x - nodes[i]) / h
        t2, t3 = t * t, t * t * t
        out = ((2 * t3 - 3 * t2 + 1) * values[i] + (t3 - 2 * t2 + t) * h * slopes[i]
               + (-2 * t3 + 3 * t2) * values[i + 1] + (t3 - t2) * h * slopes[i + 1])
        return np.where((x >= nodes[0]) & (x <= nodes[-1]), out, np.nan)
    return g


@functools.lru_cache(maxsize=1)
def _airy_si_reference():
    """w = Ai(2u) + Si(3v)/2 and its partials for the ray caster, from mpmath's Ai, Ai',
    Si on nodes 1/128 apart, Hermite-interpolated (Ai'' = x Ai; Si' = sin x / x; the
    interpolation's error below 1e-9), a little beyond the domain (a ray at its edge
    may compute u = 3 + 1 ulp)."""
    xa = np.linspace(-6.25, 6.25, 25 * 64 + 1)
    ai = np.array([float(mpmath.airyai(x)) for x in xa])
    aip = np.array([float(mpmath.airyai(x, 1)) for x in xa])
    g_ai, g_aip = _hermite(xa, ai, aip), _hermite(xa, aip, xa * ai)
    xs = np.linspace(-9.25, 9.25, 37 * 64 + 1)
    si = np.array([float(mpmath.si(x)) for x in xs])
    sinc = np.sinc(xs / np.pi)
    dsinc = np.where(xs == 0, 0.0, (xs * np.cos(xs) - np.sin(xs)) / np.where(xs == 0, 1, xs) ** 2)
    g_si, g_sinc = _hermite(xs, si, sinc), _hermite(xs, sinc, dsinc)

    def f(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        return g_ai(2 * u) + 0.5 * g_si(3 * v)

    def fu(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        return 2 * g_aip(2 * u) + 0 * v

    def fv(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        return 1.5 * g_sinc(3 * v) + 0 * u
    return f, fu, fv


@pytest.mark.parametrize("projection, min_psnr", [("orthographic", 65.0),
                                                  ("perspective", 66.0)])
def test_an_airy_and_sine_integral_surface_matches_the_ray_caster(projection, min_psnr):
    """Ai(2u) + Si(3v)/2 on [-3, 3]^2, drawn from the formula (its partials sympy's:
    Ai' and sin(3v)/v) against the ray caster with mpmath's values interpolated:
    measured 2026-12-07 100 % of the pixels on the same side, 67.8 dB orthographic
    and 69.3 dB perspective."""
    dom = (-3.0, 3.0)
    r = fc.render("airyai(2*u) + Si(3*v)/2", u=dom, v=dom, size=(100, 75), elev=35,
                  azim=30, projection=projection, shading="lambert")
    vw = r.view
    ref = raycast(_airy_si_reference(), dom, dom, (100, 75), 35, 30, projection, vw.d1,
                  vw.d2, vw.scale, center=vw.center)
    assert (ref.side != 0).mean() > 0.3
    assert (r.side == ref.side).mean() >= 0.9999
    assert psnr(r.intensity, ref.intensity) >= min_psnr


@pytest.mark.parametrize("n, m, bound", [(0, 0, 1e-14), (1, 1, 1e-14), (3, 1, 1e-13),
                                         (5, -2, 1e-13), (4, -4, 1e-13), (20, 0, 2e-9)])
def test_spherical_harmonics_agree_with_mpmath(n, m, bound):
    """Ynm(n, m, theta, phi) in closed form (sympy's expand_func over real angles, its
    constants in doubles): Abs, re and im against mpmath's spherharm, absolute errors
    measured 2026-12-07 of at most 2e-14 up to degree 5 and 3.9e-10 at degree 20 (a
    polynomial in cos theta whose coefficients cancel); Znm of m > 0 is sqrt(2) re Ynm.
    Before: "no compiled form of Ynm"."""
    rng = np.random.default_rng(n * 10 + m)
    pts = rng.uniform((0.0, 0.0), (math.pi, 2 * math.pi), (12, 2))
    parts = [("Abs", abs), ("re", mpmath.re), ("im", mpmath.im)]
    if n == 20:
        parts = parts[:1]                   # (each compile of degree 20 takes seconds)
    for part, ref in parts:
        s = fc.as_surface(f"{part}(Ynm({n}, {m}, u, v))")
        for th, ph in pts:
            want = float(ref(mpmath.spherharm(n, m, th, ph)))
            assert abs(s.f(th, ph, 0.0) - want) <= bound, (part, th, ph)
    if m > 0:
        z = fc.as_surface(sp.Znm(n, m, U, V))
        for th, ph in pts:
            want = math.sqrt(2) * float(mpmath.re(mpmath.spherharm(n, m, th, ph)))
            assert abs(z.f(th, ph, 0.0) - want) <= bound


@pytest.mark.parametrize("text", ["Ynm(2.5, 1, u, v)", "Ynm(2, 3, u, v)", "Ynm(u, 1, u, v)",
                                  "sph_harm_y(21, 0, u, v)"])
def test_a_spherical_harmonic_out_of_range_says_so(text):
    with pytest.raises(ValueError, match=r"needs whole numbers with \|m\| <= n <= 20"):
        fc.render(text, u=(0, 3), v=(0, 6), size=(20, 15))


@pytest.mark.parametrize("text, ref", [
    ("Abs(hankel1(0, u))", lambda x: abs(mpmath.hankel1(0, x))),
    ("re(hankel2(0.5, u))", lambda x: mpmath.re(mpmath.hankel2(0.5, x))),
    ("im(hankel2(2, u))", lambda x: mpmath.im(mpmath.hankel2(2, x))),
    (sp.Abs(sp.hn1(1, U)), lambda x: abs(mpmath.sqrt(mpmath.pi / (2 * x)) *
                                         mpmath.hankel1(1.5, x))),
])
def test_hankel_functions_are_j_plus_or_minus_i_y(text, ref):
    """hankel1 = J + iY, hankel2 = J - iY (A&S 9.1.3-4; the spherical hn1, hn2 of jn and
    yn), drawn through their Abs, re or im (their re and im of a fractional order, which
    sympy cannot take away over a real variable, through complex arithmetic): as mpmath's
    to 1e-14. Before: "no compiled form of hankel1"."""
    s = fc.as_surface(text)
    for x in (0.7, 2.5, 7.3, 19.0):
        assert abs(s.f(x, 0.0, 0.0) - float(ref(mpmath.mpf(x)))) < 1e-14

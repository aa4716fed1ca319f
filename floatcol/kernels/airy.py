"""Airy functions for compiled surfaces: Ai(x), Bi(x) and their derivatives (sympy's
airyai, airybi, airyaiprime, airybiprime), which Numba's math module lacks. The
solutions of y'' = x y: a particle at a linear potential, light near a caustic (the
rainbow's), a wave at a turning point.

- Every x between SERIES_NEG and the series' upper bound: the Maclaurin series
  Ai = c1 f - c2 g, Bi = sqrt(3) (c1 f + c2 g) (Abramowitz & Stegun 10.4.2, 10.4.3),
  f = sum 3^k (1/3)_k x^3k / (3k)!, g = sum 3^k (2/3)_k x^(3k+1) / (3k+1)!, each
  term from the one before (a_(k+1) = a_k x^3 / ((3k+2)(3k+3)), b_(k+1) = b_k x^3 /
  ((3k+3)(3k+4))), and the derivatives' series term by term. For x < 0 the terms
  alternate in sign and grow to about exp(zeta) (zeta = 2/3 |x|^(3/2)) before they
  fall: that many ulps of the value are lost; hence the bound below.
- Ai(x), Ai'(x), x > AI_SERIES_MAX: the modified Bessel function of order 1/3 and 2/3
  (A&S 10.4.14, 10.4.16), Ai = sqrt(x/3) K_1/3(zeta) / pi, Ai' = -x K_2/3(zeta) /
  (pi sqrt 3), each by the trapezoid rule on K_nu's integral (special._kv), which
  loses nothing where Ai is exponentially small (its series would lose all).
- Bi(x), Bi'(x), x > BI_SERIES_MAX: their asymptotic expansions in 1/zeta (A&S
  10.4.63, 10.4.66), summed until the terms stop falling.
- x < SERIES_NEG: the oscillating asymptotic expansions (A&S 10.4.60, 10.4.62,
  10.4.64, 10.4.67), their terms u_k and v_k (10.4.58, 10.4.59).

Agreement with mpmath (tests/test_special.py, x from -100 to 100): 1.7e-12 of the
envelope |x|^(-1/4) (|x|^(1/4) for the derivatives) where the series meets the
oscillating expansion (x near -7, where both are worst; 1e-15 from x = -8 on, 4e-12
at -1e4: the cosine of a large argument); 1.5e-13 relative for x > 0. NaN is NaN;
Ai(oo), Ai'(oo) are 0, Bi(oo), Bi'(oo) and any x at -oo a hole (NaN).
"""
import math

from ._jit import ngjit
from .special import _kv

#: Ai(0) and -Ai'(0) (A&S 10.4.4, 10.4.5)
C1 = 0.355028053887817239260
C2 = 0.258819403792806798405
SQRT3 = 1.7320508075688772935
SQRT_PI = 1.7724538509055160273
#: x below which the oscillating expansions take over from the series
SERIES_NEG = -7.0
#: x above which Ai and Ai' take K_nu, and Bi and Bi' their asymptotic expansions
AI_SERIES_MAX = 1.0
BI_SERIES_MAX = 12.0
#: zeta beyond which Ai and Ai' are 0 in doubles (exp(-zeta) underflows; x = oo too)
ZETA_ZERO = 800.0


@ngjit
def _series(x):
    """(f, g, f', g') of A&S 10.4.2-10.4.3 and their derivatives."""
    x3 = x * x * x
    a = 1.0             # f's terms
    b = x               # g's
    p = 0.5 * x * x     # f''s, from its k = 1 term (its k = 0 term is 0)
    q = 1.0             # g''s
    f = a
    g = b
    fp = p
    gp = q
    for k in range(500):
        a *= x3 / ((3 * k + 2) * (3 * k + 3))
        b *= x3 / ((3 * k + 3) * (3 * k + 4))
        p *= x3 / ((3 * k + 3) * (3 * k + 5))
        q *= x3 / ((3 * k + 1) * (3 * k + 3))
        f += a
        g += b
        fp += p
        gp += q
        if (abs(a) <= 1e-17 * abs(f) and abs(b) <= 1e-17 * abs(g)
                and abs(p) <= 1e-17 * abs(fp) and abs(q) <= 1e-17 * abs(gp)):
            break
    return f, g, fp, gp


@ngjit
def _asymptotic(zeta, sign):
    """(sum of u_k (sign/zeta)^k, the same of v_k), summed while its terms fall."""
    su = 1.0
    sv = 1.0
    u = 1.0
    r = sign / zeta
    last = math.inf
    for k in range(1, 200):
        u *= (6 * k - 5) * (6 * k - 3) * (6 * k - 1) / ((2 * k - 1) * 216.0 * k) * r
        v = -(6 * k + 1) / (6 * k - 1) * u
        if abs(u) >= last:
            break
        last = abs(u)
        su += u
        sv += v
        if abs(u) <= 1e-17 * abs(su):
            break
    return su, sv


@ngjit
def _oscillating(y):
    """(P_u, Q_u, P_v, Q_v) of the expansions at x = -y (A&S 10.4.60-10.4.67):
    sums over the even and the odd terms, (-1)^k u_2k zeta^-2k and
    (-1)^k u_(2k+1) zeta^-(2k+1), as of v."""
    zeta = 2.0 / 3.0 * y * math.sqrt(y)
    pu = 1.0
    qu = 0.0
    pv = 1.0
    qv = 0.0
    u = 1.0
    last = math.inf
    for k in range(1, 200):
        u *= (6 * k - 5) * (6 * k - 3) * (6 * k - 1) / ((2 * k - 1) * 216.0 * k) / zeta
        if abs(u) >= last:
            break
        last = abs(u)
        v = -(6 * k + 1) / (6 * k - 1) * u
        s = 1.0 if (k // 2) % 2 == 0 else -1.0
        if k % 2 == 0:
            pu += s * u
            pv += s * v
        else:
            qu += s * u
            qv += s * v
        if abs(u) <= 1e-17:
            break
    return zeta, pu, qu, pv, qv


@ngjit
def _negative(y):
    """(Ai, Ai', Bi, Bi') at x = -y, y >= -SERIES_NEG (A&S 10.4.60-10.4.67)."""
    zeta, pu, qu, pv, qv = _oscillating(y)
    th = zeta - 0.25 * math.pi
    c = math.cos(th)
    s = math.sin(th)
    r = y ** 0.25
    ai = (c * pu + s * qu) / (SQRT_PI * r)
    aip = r * (s * pv - c * qv) / SQRT_PI
    bi = (-s * pu + c * qu) / (SQRT_PI * r)
    bip = r * (c * pv + s * qv) / SQRT_PI
    return ai, aip, bi, bip


@ngjit
def airyai(x):
    """Ai(x)."""
    if math.isnan(x) or x == -math.inf:
        return math.nan
    if x > AI_SERIES_MAX:
        zeta = 2.0 / 3.0 * x * math.sqrt(x)
        if zeta > ZETA_ZERO:
            return 0.0                      # (exp(-zeta) is below the doubles)
        return math.sqrt(x / 3.0) * _kv(1.0 / 3.0, zeta) / math.pi      # A&S 10.4.14
    if x < SERIES_NEG:
        return _negative(-x)[0]
    f, g, fp, gp = _series(x)
    return C1 * f - C2 * g                                                # A&S 10.4.2


@ngjit
def airyaiprime(x):
    """Ai'(x)."""
    if math.isnan(x) or x == -math.inf:
        return math.nan
    if x > AI_SERIES_MAX:
        zeta = 2.0 / 3.0 * x * math.sqrt(x)
        if zeta > ZETA_ZERO:
            return 0.0
        return -x * _kv(2.0 / 3.0, zeta) / (math.pi * SQRT3)              # A&S 10.4.16
    if x < SERIES_NEG:
        return _negative(-x)[1]
    f, g, fp, gp = _series(x)
    return C1 * fp - C2 * gp


@ngjit
def airybi(x):
    """Bi(x)."""
    if math.isnan(x) or math.isinf(x):
        return math.nan
    if x > BI_SERIES_MAX:
        zeta = 2.0 / 3.0 * x * math.sqrt(x)
        su, sv = _asymptotic(zeta, 1.0)
        return math.exp(zeta) * su / (SQRT_PI * x ** 0.25)               # A&S 10.4.63
    if x < SERIES_NEG:
        return _negative(-x)[2]
    f, g, fp, gp = _series(x)
    return SQRT3 * (C1 * f + C2 * g)                                      # A&S 10.4.3


@ngjit
def airybiprime(x):
    """Bi'(x)."""
    if math.isnan(x) or math.isinf(x):
        return math.nan
    if x > BI_SERIES_MAX:
        zeta = 2.0 / 3.0 * x * math.sqrt(x)
        su, sv = _asymptotic(zeta, 1.0)
        return x ** 0.25 * math.exp(zeta) * sv / SQRT_PI                  # A&S 10.4.66
    if x < SERIES_NEG:
        return _negative(-x)[3]
    f, g, fp, gp = _series(x)
    return SQRT3 * (C1 * fp + C2 * gp)

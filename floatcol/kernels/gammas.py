"""More special functions for compiled surfaces: the polygamma functions (sympy's
polygamma, digamma, trigamma; scipy's psi), the inverse error functions (erfinv,
erfcinv), Lambert's W (both real branches), Riemann's and Hurwitz's zeta and
Dirichlet's eta, the elliptic integrals (elliptic_k, elliptic_e, elliptic_f), which
Numba's math module lacks, and Euler's beta past where its quotient of Gammas overflows.

- polygamma(n, x), a whole n >= 0: the recurrence psi^(n)(x) = psi^(n)(x+1) -
  (-1)^n n! / x^(n+1) (A&S 6.4.6) up to x >= max(POLYGAMMA_X0, n), then the
  asymptotic expansion with Bernoulli's numbers (A&S 6.3.18, 6.4.11); x < 0 by the
  reflection psi(1-x) - psi(x) = pi cot(pi x) (6.3.7) differentiated n times, its
  derivative of cot taken at x's fraction (it has period 1) from the same formula.
- erfinv, erfcinv: M. Giles' approximation ("Approximating the erfinv function",
  GPU Computing Gems, 2011) as the start of Halley's iteration on erf(x) = y, or on
  erfc(x) = 1 - y where |y| > 1/2 (1 - y then exact: no digits lost near +-1).
- LambertW(x) (W_0, x >= -1/e) and LambertW(x, -1) (W_-1, -1/e <= x < 0): Halley's
  iteration on w exp(w) = x, or on w + log|w| = log|x| where |w| > 1, from the
  branch point's series (Corless et al. 1996, eq. 4.22) or log's expansion (4.19).
- zeta(s) and zeta(s, a), a > 0: Euler-Maclaurin summation (DLMF 25.11.5's finite
  form) from N = ZETA_N terms on with EM_TERMS of Bernoulli's numbers, s > -1; for
  s <= -1 Riemann's functional equation (DLMF 25.4.1) in logarithms (Hurwitz's of a
  != 1 there: a hole). dirichlet_eta(s) = (1 - 2^(1-s)) zeta(s) (25.2.3).
- elliptic_k(m), elliptic_e(m): the arithmetic-geometric mean (A&S 17.6.1-17.6.4);
  elliptic_f(phi, m), elliptic_e(phi, m): Carlson's R_F and R_D by duplication
  (Carlson 1995; Numerical Recipes 6.11), the period of phi (F(phi + k pi) =
  F(phi) + 2 k K) taken out first.

Agreement with mpmath: tests/test_special.py (relative errors 1e-15 to 1e-13 but at
the zeros and poles, and near W's branch point, where the arguments' own rounding
is amplified). Complex values and poles are holes (NaN or an infinity); sympy's
parameter m of the elliptic integrals (k^2), as scipy's ellipk.
"""
import math

import numpy as np

from ._jit import ngjit
from .special import _whole

#: Bernoulli's numbers B_2, B_4, ..., B_30
BERNOULLI = np.array([1 / 6, -1 / 30, 1 / 42, -1 / 30, 5 / 66, -691 / 2730, 7 / 6,
                      -3617 / 510, 43867 / 798, -174611 / 330, 854513 / 138,
                      -236364091 / 2730, 8553103 / 6, -23749461029 / 870,
                      8615841276005 / 14322])
#: x from which polygamma takes its asymptotic expansion (and n, if larger)
POLYGAMMA_X0 = 16.0
#: Euler-Maclaurin: a + N at least this (and |s| + 2 EM_TERMS + 10), EM_TERMS terms
ZETA_N = 20.0
EM_TERMS = 15
#: s beyond which zeta(s, a) is its sum itself (a few terms: (a+k)^-s falls fast)
ZETA_DIRECT = 40.0
INV_E = 0.36787944117144232160
INV_E_LO = -1.2428753672788363168e-17          # 1/e - INV_E
#: W's series about the branch point, in p = sqrt(2 (e x + 1)) (Corless et al. 4.22)
BRANCH = np.array([-1.0, 1.0, -1 / 3, 11 / 72, -43 / 540, 769 / 17280, -221 / 8505,
                   680863 / 43545600, -1963 / 204120, 226287557 / 37623398400])
#: p below which W is that series (its next term below 1e-17)
BRANCH_SERIES = 0.01
EPS = 1.0e-16
#: Carlson's duplication stops when the arguments are this close to their mean
RF_TOL = 0.0025
#: -log(1 - y^2) up to which Giles' fit starts erfinv's iteration
GILES_MAX = 36.0
RD_TOL = 0.0015
#: a + b (both positive) from which beta(a, b) is taken in logarithms: Gamma overflows
#: past 171.6, and every Gamma of the quotient is finite below this
BETA_LOG = 171.0
LN_SQRT_2PI = 0.91893853320467274178


@ngjit
def _stirling_rest(x):
    """lgamma(x) less its Stirling terms (x - 1/2) ln x - x + ln(2 pi)/2, x >= 85
    (A&S 6.1.41: 1/12x - 1/360x^3 + 1/1260x^5, the next term under 1e-17 there)."""
    r = 1.0 / (x * x)
    return (1.0 / 12.0 - r * (1.0 / 360.0 - r / 1260.0)) / x


@ngjit
def beta(a, b):
    """Euler's beta function B(a, b) = Gamma(a) Gamma(b) / Gamma(a + b) (A&S 6.2.2), the
    quotient as it reads where its Gammas are finite (a + b < BETA_LOG) or an argument
    is not positive. For positive a >= b past that (a > 85), by logarithms: ln B =
    lgamma(b) + lgamma(a) - lgamma(a + b), the difference of the two large ones from
    Stirling's series (A&S 6.1.41) as -(a - 1/2) log1p(b/a) - b ln(a + b) + b + the
    series' rests, which loses no digits to their size (lgamma(1e10) - lgamma(1e10 + 2)
    subtracted directly keeps 6 of 16); where b >= 85 too, all three from the series,
    -(a - 1/2) log1p(b/a) - (b - 1/2) log1p(a/b) - ln(a + b)/2 + ln(2 pi)/2 + the rests
    (lgamma(b) of a few thousand against ln B of a few hundred lost a digit). The
    quotient of Gammas had been a hole for a + b > 171 (inf/inf): beta(1e10, 2) =
    1e-20."""
    if not (a > 0.0 and b > 0.0) or a + b < BETA_LOG:
        return math.gamma(a) * math.gamma(b) / math.gamma(a + b)
    if a < b:
        a, b = b, a
    c = a + b
    if b >= 85.0:
        # both large: Stirling's series for all three, whose terms (a - 1/2) ln a ...
        # are gathered into ratios (terms of B's own size, not Gamma's)
        return math.exp(-(a - 0.5) * math.log1p(b / a) - (b - 0.5) * math.log1p(a / b)
                        - 0.5 * math.log(c) + LN_SQRT_2PI + _stirling_rest(a)
                        + _stirling_rest(b) - _stirling_rest(c))
    d = -(a - 0.5) * math.log1p(b / a) - b * math.log(c) + b + _stirling_rest(a) \
        - _stirling_rest(c)
    return math.exp(math.lgamma(b) + d)


@ngjit
def polygamma(order, x):
    """psi^(n)(x), the n-th derivative of the digamma function, of a whole n from 0
    to MAX_ORDER: a hole at its poles (x = 0, -1, -2, ...) and where complex."""
    n, ok = _whole(order)
    if not ok or n < 0 or math.isnan(x):
        return math.nan
    if math.isinf(x):
        if x > 0.0:
            return math.inf if n == 0 else 0.0
        return math.nan
    if x <= 0.0 and x == np.floor(x):
        return math.nan                                         # a pole
    if x < 0.0:
        # A&S 6.3.7 differentiated n times: psi^(n)(x) = (-1)^n psi^(n)(1 - x) - pi
        # D_n(x), D_n the n-th derivative of cot(pi x), which has period 1: D_n(x) =
        # D_n(r), r = x - floor(x) in (0, 1), and by the same formula at r, pi D_n(r) =
        # (-1)^n psi^(n)(1 - r) - psi^(n)(r): three values at positive arguments
        r = x - np.floor(x)
        sg = 1.0 if n % 2 == 0 else -1.0
        return sg * polygamma(order, 1.0 - x) - (sg * polygamma(order, 1.0 - r)
                                                  - polygamma(order, r))
    # A&S 6.4.6, upward: psi^(n)(x) = psi^(n)(x + 1) - (-1)^n n! / x^(n+1)
    x0 = max(POLYGAMMA_X0, float(n))
    shift = 0.0
    if n == 0:
        while x < x0:
            shift -= 1.0 / x
            x += 1.0
    else:
        lf = math.lgamma(n + 1.0)
        sign = -1.0 if n % 2 == 0 else 1.0                      # (-1)^(n+1)
        while x < x0:
            shift += sign * math.exp(lf - (n + 1) * math.log(x))
            x += 1.0
    ix2 = 1.0 / (x * x)
    if n == 0:
        # A&S 6.3.18
        total = math.log(x) - 0.5 / x
        p = 1.0
        for k in range(1, BERNOULLI.shape[0] + 1):
            p *= ix2
            term = BERNOULLI[k - 1] / (2 * k) * p
            total -= term
            if abs(term) <= EPS * abs(total):
                break
        return total + shift
    # A&S 6.4.11: (-1)^(n+1) (n-1)!/x^n [1 + n/(2x) + sum B_2k (2k+n-1)!/((2k)!(n-1)!) / x^2k]
    lead = math.exp(math.lgamma(float(n)) - n * math.log(x))
    total = 1.0 + n / (2.0 * x)
    r = 1.0
    p = 1.0
    for k in range(1, BERNOULLI.shape[0] + 1):
        r *= (2 * k + n - 2) * (2 * k + n - 1) / ((2 * k - 1) * (2.0 * k))
        p *= ix2
        term = BERNOULLI[k - 1] * r * p
        total += term
        if abs(term) <= EPS * abs(total):
            break
    sign = 1.0 if n % 2 == 1 else -1.0
    return sign * lead * total + shift


@ngjit
def _giles(a, t):
    """Giles' approximation of erfinv(a), 0 <= a < 1, t = 1 - a."""
    w = -math.log(t * (1.0 + a))
    if w < 6.25:
        w -= 3.125
        p = -3.6444120640178196996e-21
        p = -1.685059138182016589e-19 + p * w
        p = 1.2858480715256400167e-18 + p * w
        p = 1.115787767802518096e-17 + p * w
        p = -1.333171662854620906e-16 + p * w
        p = 2.0972767875968561637e-17 + p * w
        p = 6.6376381343583238325e-15 + p * w
        p = -4.0545662729752068639e-14 + p * w
        p = -8.1519341976054721522e-14 + p * w
        p = 2.6335093153082322977e-12 + p * w
        p = -1.2975133253453532498e-11 + p * w
        p = -5.4154120542946279317e-11 + p * w
        p = 1.051212273321532285e-09 + p * w
        p = -4.1126339803469836976e-09 + p * w
        p = -2.9070369957882005086e-08 + p * w
        p = 4.2347877827932403518e-07 + p * w
        p = -1.3654692000834678645e-06 + p * w
        p = -1.3882523362786468719e-05 + p * w
        p = 0.0001867342080340571352 + p * w
        p = -0.00074070253416626697512 + p * w
        p = -0.0060336708714301490533 + p * w
        p = 0.24015818242558961693 + p * w
        p = 1.6536545626831027356 + p * w
    elif w < 16.0:
        w = math.sqrt(w) - 3.25
        p = 2.2137376921775787049e-09
        p = 9.0756561938885390979e-08 + p * w
        p = -2.7517406297064545428e-07 + p * w
        p = 1.8239629214389227755e-08 + p * w
        p = 1.5027403968909827627e-06 + p * w
        p = -4.013867526981545969e-06 + p * w
        p = 2.9234449089955446044e-06 + p * w
        p = 1.2475304481671778723e-05 + p * w
        p = -4.7318229009055733981e-05 + p * w
        p = 6.8284851459573175448e-05 + p * w
        p = 2.4031110387097893999e-05 + p * w
        p = -0.0003550375203628474796 + p * w
        p = 0.00095328937973738049703 + p * w
        p = -0.0016882755560235047313 + p * w
        p = 0.0024914420961078508066 + p * w
        p = -0.0037512085075692412107 + p * w
        p = 0.005370914553590063617 + p * w
        p = 1.0052589676941592334 + p * w
        p = 3.0838856104922207635 + p * w
    else:
        w = math.sqrt(w) - 5.0
        p = -2.7109920616438573243e-11
        p = -2.5556418169965252055e-10 + p * w
        p = 1.5076572693500548083e-09 + p * w
        p = -3.7894654401267369937e-09 + p * w
        p = 7.6157012080783393804e-09 + p * w
        p = -1.4960026627149240478e-08 + p * w
        p = 2.9147953450901080826e-08 + p * w
        p = -6.7711997758452339498e-08 + p * w
        p = 2.2900482228026654717e-07 + p * w
        p = -9.9298272942317002539e-07 + p * w
        p = 4.5260625972231537039e-06 + p * w
        p = -1.9681778105531670567e-05 + p * w
        p = 7.5995277030017761139e-05 + p * w
        p = -0.00021503011930044477347 + p * w
        p = -0.00013871931833623122026 + p * w
        p = 1.0103004648645343977 + p * w
        p = 4.8499064014085844221 + p * w
    return p * a


@ngjit
def _erfinv(a, t):
    """x >= 0 with erf(x) = a (0 <= a < 1), t = 1 - a given exactly: Halley's
    iteration x <- x - d / (1 + x d), d = (erf(x) - a) / erf'(x), on erfc where a > 1/2."""
    w = -math.log(t * (1.0 + a))
    if w < GILES_MAX:
        x = _giles(a, t)
    else:
        # far in the tail (t < 1e-16), where Giles' fit ends: erfc(x) ~ exp(-x^2) /
        # (x sqrt(pi)) (A&S 7.1.23), solved for x twice
        x = math.sqrt(w)
        x = math.sqrt(w - math.log(x * math.sqrt(math.pi)))
        x = math.sqrt(w - math.log(x * math.sqrt(math.pi)))
    for _ in range(8):
        dp = 2.0 / math.sqrt(math.pi) * math.exp(-x * x)
        if dp == 0.0:
            break
        if a <= 0.5:
            d = (math.erf(x) - a) / dp
        else:
            d = -(math.erfc(x) - t) / dp
        x -= d / (1.0 + x * d)
        if abs(d) <= EPS * abs(x):
            break
    return x


@ngjit
def erfinv(y):
    """The inverse of erf on (-1, 1); +-1: +-infinity; elsewhere a hole."""
    if math.isnan(y) or abs(y) > 1.0:
        return math.nan
    if abs(y) == 1.0:
        return math.copysign(math.inf, y)
    if y == 0.0:
        return y
    a = abs(y)
    x = _erfinv(a, 1.0 - a)
    return -x if y < 0.0 else x


@ngjit
def erfcinv(z):
    """The inverse of erfc on (0, 2); 0 and 2: +- infinity; elsewhere a hole."""
    if math.isnan(z) or z < 0.0 or z > 2.0:
        return math.nan
    if z == 0.0:
        return math.inf
    if z == 2.0:
        return -math.inf
    if z == 1.0:
        return 0.0
    if z < 1.0:
        return _erfinv(1.0 - z, z)
    return -_erfinv(z - 1.0, 2.0 - z)                   # (2 - z exact for 1 <= z <= 2)


@ngjit
def LambertW(x, k):
    """W_k(x), k = 0 (x >= -1/e) or -1 (-1/e <= x < 0): w with w exp(w) = x; other
    branches and arguments are complex: a hole."""
    if math.isnan(x) or x < -INV_E * (1.0 + 4e-16):
        return math.nan
    if k == 0.0:
        if math.isinf(x):
            return math.inf
        if x == 0.0:
            return x
    elif k == -1.0:
        if x >= 0.0:
            return -math.inf if x == 0.0 else math.nan
    else:
        return math.nan
    # 2 (e x + 1) = 2 e (x + 1/e), 1/e in two doubles: x + 1/e is exact near -1/e
    q = 2.0 * math.e * ((x + INV_E) + INV_E_LO)
    p = math.sqrt(max(q, 0.0))
    if p < BRANCH_SERIES:
        # Corless et al. 4.22, the series about the branch point (-p for W_-1)
        if k != 0.0:
            p = -p
        w = 0.0
        for c in BRANCH[::-1]:
            w = w * p + c
        return w
    if k == 0.0:
        if q < 0.5:
            w = -1.0 + p - p * p / 3.0 + 11.0 / 72.0 * p * p * p     # Corless 4.22
        elif x < 3.0:
            w = math.log1p(x) * (1.0 - math.log1p(math.log1p(x)) / (2.0 + math.log1p(x)))
        else:
            lx = math.log(x)
            w = lx - math.log(lx)                                   # Corless 4.19
    else:
        if q < 0.5:
            w = -1.0 - p - p * p / 3.0 - 11.0 / 72.0 * p * p * p
        else:
            lx = math.log(-x)
            w = lx - math.log(-lx)
    if abs(w) > 1.0:
        # Halley on g(w) = w + log|w| - log|x|: g' = 1 + 1/w, g'' = -1/w^2
        lx = math.log(abs(x))
        for _ in range(20):
            g = w + math.log(abs(w)) - lx
            g1 = 1.0 + 1.0 / w
            g2 = -1.0 / (w * w)
            d = g / g1
            step = d / (1.0 - 0.5 * d * g2 / g1)
            w -= step
            if abs(step) <= 4.0 * EPS * abs(w):
                break
        return w
    for _ in range(30):
        # Halley on f(w) = w e^w - x: f' = e^w (w + 1), f'' = e^w (w + 2)
        ew = math.exp(w)
        f = w * ew - x
        if f == 0.0:
            break
        wp1 = w + 1.0
        if wp1 == 0.0:
            break
        step = f / (ew * wp1 - (w + 2.0) * f / (2.0 * wp1))
        w -= step
        if abs(step) <= 4.0 * EPS * max(abs(w), 1e-300):
            break
    return w


@ngjit
def _hurwitz(s, a):
    """zeta(s, a), s > -1, s != 1, a > 0: Euler-Maclaurin (DLMF 25.11.5's finite form);
    for s > ZETA_DIRECT the sum itself, until its terms are below the precision."""
    if s > ZETA_DIRECT:
        total = 0.0
        k = 0
        while True:
            term = (a + k) ** -s
            total += term
            if term <= 0.1 * EPS * total or k >= 100000:
                break
            k += 1
        # (the rest: about int_(a+k+1/2)^oo t^-s dt, far below the precision)
        return total + (a + k + 0.5) ** (1.0 - s) / (s - 1.0)
    big = max(ZETA_N, abs(s) + 2.0 * EM_TERMS + 10.0)
    n = max(0, int(math.ceil(big - a)))
    total = 0.0
    for k in range(n):
        total += (a + k) ** -s
    an = a + n
    total += an ** (1.0 - s) / (s - 1.0) + 0.5 * an ** -s
    # + sum_j B_2j / (2j)! s (s+1) ... (s+2j-2) (a+N)^(-s-2j+1)
    c = s * an ** (-s - 1.0)            # s / (a+N)^(s+1): j = 1's power and rising product
    fact = 2.0
    inv2 = 1.0 / (an * an)
    for j in range(1, EM_TERMS + 1):
        term = BERNOULLI[j - 1] / fact * c
        total += term
        if abs(term) <= EPS * abs(total):
            break
        c *= (s + 2 * j - 1) * (s + 2 * j) * inv2
        fact *= (2 * j + 1) * (2 * j + 2)
    return total


@ngjit
def zeta(s, a):
    """Hurwitz's zeta(s, a) = sum_k (a + k)^-s, Riemann's of a = 1, continued to every
    real s != 1 (a pole: a hole); a > 0, and a = 1 where s <= -1; else a hole."""
    if math.isnan(s) or math.isnan(a) or not a > 0.0 or math.isinf(a):
        return math.nan
    if s == 1.0:
        return math.inf
    if s == math.inf:
        if a < 1.0:
            return math.inf
        return 1.0 if a == 1.0 else 0.0
    if s >= 0.0 or (s > -1.0 and a != 1.0):
        return _hurwitz(s, a)
    if a != 1.0 or s == -math.inf:
        return math.nan
    # DLMF 25.4.1: zeta(s) = 2^s pi^(s-1) sin(pi s / 2) Gamma(1 - s) zeta(1 - s)
    half = 0.5 * s
    r = half - 2.0 * np.floor(0.5 * half)     # s/2 mod 2, exactly: sin(pi s / 2)'s
    if r == 0.0 or r == 1.0:
        return 0.0                              # the trivial zeros, s = -2, -4, ...
    sn = math.sin(math.pi * r)
    z1 = _hurwitz(1.0 - s, 1.0)
    lg = s * math.log(2.0) + (s - 1.0) * math.log(math.pi) + math.lgamma(1.0 - s)
    return math.copysign(1.0, sn) * math.exp(lg + math.log(abs(sn)) + math.log(z1))


@ngjit
def dirichlet_eta(s):
    """Dirichlet's eta(s) = (1 - 2^(1-s)) zeta(s) (DLMF 25.2.3); eta(1) = log 2."""
    if s == 1.0:
        return math.log(2.0)
    if s == math.inf:
        return 1.0
    return -math.expm1((1.0 - s) * math.log(2.0)) * zeta(s, 1.0)


@ngjit
def _agm(m):
    """(K(m), E(m)) for m < 1 by the arithmetic-geometric mean (A&S 17.6.1-17.6.4)."""
    a = 1.0
    b = math.sqrt(1.0 - m)
    c2 = m                              # c_0^2
    total = 0.5 * c2                    # sum 2^(n-1) c_n^2
    pw = 0.5
    for _ in range(100):
        an = 0.5 * (a + b)
        cn = 0.5 * (a - b)
        b = math.sqrt(a * b)
        a = an
        pw *= 2.0
        total += pw * cn * cn
        if abs(cn) <= 8.0 * EPS * a:
            break       # (a and b may stay an ulp apart, while 2^n grows)
    k = 0.5 * math.pi / a
    return k, k * (1.0 - total)


@ngjit
def elliptic_k(m):
    """K(m) = int_0^(pi/2) (1 - m sin^2 t)^(-1/2) dt, m < 1 (m = 1: a pole; m > 1: a
    hole, complex)."""
    if math.isnan(m) or m > 1.0:
        return math.nan
    if m == 1.0:
        return math.inf
    if m == -math.inf:
        return 0.0
    return _agm(m)[0]


@ngjit
def _elliptic_e(m):
    """E(m) = int_0^(pi/2) (1 - m sin^2 t)^(1/2) dt, m <= 1."""
    if math.isnan(m) or m > 1.0:
        return math.nan
    if m == 1.0:
        return 1.0
    if m == -math.inf:
        return math.inf
    return _agm(m)[1]


@ngjit
def _rf(x, y, z):
    """Carlson's R_F(x, y, z) by duplication (Carlson 1995; NR's rf at double
    precision: the deviations below 0.0025, the fifth-order series)."""
    for _ in range(200):
        sx = math.sqrt(x)
        sy = math.sqrt(y)
        sz = math.sqrt(z)
        lam = sx * (sy + sz) + sy * sz
        x = 0.25 * (x + lam)
        y = 0.25 * (y + lam)
        z = 0.25 * (z + lam)
        ave = (x + y + z) / 3.0
        dx = (ave - x) / ave
        dy = (ave - y) / ave
        dz = (ave - z) / ave
        if not max(abs(dx), abs(dy), abs(dz)) >= RF_TOL:       # (NaN: out)
            break
    e2 = dx * dy - dz * dz
    e3 = dx * dy * dz
    return (1.0 + (e2 / 24.0 - 0.1 - 3.0 * e3 / 44.0) * e2 + e3 / 14.0) / math.sqrt(ave)


@ngjit
def _rd(x, y, z):
    """Carlson's R_D(x, y, z) by duplication (NR's rd at double precision)."""
    total = 0.0
    fac = 1.0
    for _ in range(200):
        sx = math.sqrt(x)
        sy = math.sqrt(y)
        sz = math.sqrt(z)
        lam = sx * (sy + sz) + sy * sz
        total += fac / (sz * (z + lam))
        fac *= 0.25
        x = 0.25 * (x + lam)
        y = 0.25 * (y + lam)
        z = 0.25 * (z + lam)
        ave = 0.2 * (x + y + 3.0 * z)
        dx = (ave - x) / ave
        dy = (ave - y) / ave
        dz = (ave - z) / ave
        if not max(abs(dx), abs(dy), abs(dz)) >= RD_TOL:
            break
    ea = dx * dy
    eb = dz * dz
    ec = ea - eb
    ed = ea - 6.0 * eb
    ee = ed + ec + ec
    c1, c2, c3, c4 = 3.0 / 14.0, 1.0 / 6.0, 9.0 / 22.0, 3.0 / 26.0
    c5, c6 = 0.25 * c3, 1.5 * c4
    return 3.0 * total + fac * (1.0 + ed * (-c1 + c5 * ed - c6 * dz * ee)
                                + dz * (c2 * ee + dz * (-c3 * ec + dz * c4 * ea))) / (
        ave * math.sqrt(ave))


@ngjit
def _amplitude(phi):
    """(j, sin phi0, cos phi0^2) of phi = phi0 + j pi, |phi0| <= pi/2."""
    j = np.floor(phi / math.pi + 0.5)
    p0 = phi - j * math.pi
    c = math.cos(p0)
    return j, math.sin(p0), c * c


@ngjit
def elliptic_f(phi, m):
    """F(phi | m) = int_0^phi (1 - m sin^2 t)^(-1/2) dt (a hole where complex)."""
    if not (math.isfinite(phi) and math.isfinite(m)):
        return math.nan
    j, s, c2 = _amplitude(phi)
    f = s * _rf(c2, 1.0 - m * s * s, 1.0)
    if j != 0.0:
        f += 2.0 * j * elliptic_k(m)                     # A&S 17.4.3
    return f


@ngjit
def elliptic_e(phi, m):
    """E(phi | m) = int_0^phi (1 - m sin^2 t)^(1/2) dt (a hole where complex)."""
    if not (math.isfinite(phi) and math.isfinite(m)):
        return math.nan
    j, s, c2 = _amplitude(phi)
    q = 1.0 - m * s * s
    e = s * _rf(c2, q, 1.0) - m / 3.0 * s * s * s * _rd(c2, q, 1.0)
    if j != 0.0:
        e += 2.0 * j * _elliptic_e(m)
    return e


@ngjit
def elliptic_e1(m):
    """E(m), the complete integral (sympy's elliptic_e of one argument)."""
    return _elliptic_e(m)

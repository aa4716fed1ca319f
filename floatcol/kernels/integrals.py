"""Exponential, logarithmic, trigonometric and Fresnel integrals, and the imaginary
error function, for compiled surfaces (sympy's Si, Ci, Shi, Chi, Ei, expint, li, Li,
erfi, fresnels, fresnelc; scipy's expi, exp1, expn under their sympy names): diffraction
(Fresnel's and Si's), antennas and filters (Si, Ci), radiative transfer and wells
(E_n, Ei). Numerical Recipes' algorithms (Press et al., 2nd ed., 6.3, 6.8, 6.9) at
double precision:

- Si, Ci, |x| <= 2: their power series (A&S 5.2.14, 5.2.16); beyond, the continued
  fraction of E_1(i x) by Lentz's method (A&S 5.2.2, 5.2.23: Si = pi/2 + Im,
  Ci = -Re of exp(-i x) times it).
- Ei, x > 0: its series (A&S 5.1.10) up to x = EI_SERIES_MAX, all terms positive,
  beyond, its asymptotic expansion summed while its terms fall; Ei(x < 0) = -E_1(-x).
- E_n, x > 1: the continued fraction (A&S 5.1.22) by Lentz's method; x <= 1: the
  series (A&S 5.1.12), the digamma function's value for the term of n - 1. A
  negative whole order -m (sympy's derivative of E_0 is -E_-1): m! exp(-x) x^-(m+1)
  sum_(k <= m) x^k / k!.
- Shi, Chi: their series (A&S 5.2.18, 5.2.19, all terms positive) up to |x| = 40,
  beyond, (Ei(x) +- E_1(x)) / 2.
- Fresnel's S and C (sympy's normalisation: int_0^x sin(pi t^2 / 2) dt), |x| <=
  1.5: their series; beyond, the continued fraction of erfc (A&S 7.3.22, 7.1.15).
- erfi(x) = -i erf(i x): its series, all terms positive, for |x| <= 6, beyond, its
  asymptotic expansion exp(x^2) / (x sqrt pi) sum (2k-1)!! / (2 x^2)^k.

Agreement with mpmath: tests/test_special.py (relative errors about 1e-15 to 1e-14
except near each function's zeros, where the error is a few ulps of the terms
cancelled). Complex values are holes (Ci, Chi of x < 0; E_n of x < 0), as are the
poles (Ci(0), Chi(0), Ei(0), E_n(0) for n <= 1); NaN is NaN.
"""
import math

from ._jit import ngjit
from .special import EULER_GAMMA, _whole

EPS = 1.0e-16
FPMIN = 1.0e-300
#: |x| above which Si and Ci take the continued fraction
CISI_SERIES_MAX = 2.0
#: x above which Ei takes its asymptotic expansion (-log of the precision)
EI_SERIES_MAX = 40.0
#: |x| above which Shi and Chi are (Ei +- E_1) / 2
SHICHI_SERIES_MAX = 40.0
#: |x| above which Fresnel's integrals take the continued fraction
FRESNEL_SERIES_MAX = 1.5
#: |x| above which erfi takes its asymptotic expansion
ERFI_SERIES_MAX = 6.0
#: |x| beyond which S and C are 1/2 -+ their first asymptotic terms (the next ones
#: below 1e-25)
FRESNEL_FAR = 1.0e8


@ngjit
def _cisi(x):
    """(Si(|x|), Ci(|x|)); NR's cisi."""
    t = abs(x)
    if t == 0.0:
        return 0.0, -math.inf
    if t > CISI_SERIES_MAX:
        b = complex(1.0, t)
        c = complex(1.0 / FPMIN, 0.0)
        d = 1.0 / b
        h = d
        for i in range(2, 100000):
            a = -float((i - 1) * (i - 1))
            b += 2.0
            d = 1.0 / (a * d + b)
            c = b + a / c
            de = c * d
            h *= de
            if abs(de.real - 1.0) + abs(de.imag) < EPS:
                break
        h = complex(math.cos(t), -math.sin(t)) * h
        return 0.5 * math.pi + h.imag, -h.real                  # A&S 5.2.23
    total = 0.0
    sums = 0.0
    sumc = 0.0
    sign = 1.0
    fact = 1.0
    odd = True
    for k in range(1, 200):
        fact *= t / k
        term = fact / k
        total += sign * term
        err = term / abs(total) if total != 0.0 else term
        if odd:
            sign = -sign
            sums = total
            total = sumc
        else:
            sumc = total
            total = sums
        if err < EPS:
            break
        odd = not odd
    return sums, sumc + math.log(t) + EULER_GAMMA                # A&S 5.2.14, 5.2.16


@ngjit
def Si(x):
    """Si(x) = int_0^x sin t / t dt."""
    if math.isnan(x):
        return math.nan
    if math.isinf(x):
        return math.copysign(0.5 * math.pi, x)
    s = _cisi(x)[0]
    return -s if x < 0.0 else s


@ngjit
def Ci(x):
    """Ci(x) = gamma + log x + int_0^x (cos t - 1) / t dt: a hole for x <= 0."""
    if math.isnan(x) or x <= 0.0:
        return math.nan
    if math.isinf(x):
        return 0.0
    return _cisi(x)[1]


@ngjit
def _e1(x):
    """E_1(x), x > 0 (the series or the continued fraction of expint)."""
    return _expint(1, x)


@ngjit
def _expint(n, x):
    """E_n(x) of a whole n >= 0 and x > 0 (NR's expint)."""
    if n == 0:
        return math.exp(-x) / x
    nm1 = n - 1
    if x > 1.0:
        b = x + n
        c = 1.0 / FPMIN
        d = 1.0 / b
        h = d
        for i in range(1, 100000):
            an = -float(i) * (nm1 + i)
            b += 2.0
            d = 1.0 / (an * d + b)
            c = b + an / c
            de = c * d
            h *= de
            if abs(de - 1.0) < EPS:
                break
        return h * math.exp(-x)                                  # A&S 5.1.22
    ans = 1.0 / nm1 if nm1 != 0 else -math.log(x) - EULER_GAMMA
    fact = 1.0
    for i in range(1, 100000):
        fact *= -x / i
        if i != nm1:
            de = -fact / (i - nm1)
        else:
            psi = -EULER_GAMMA
            for ii in range(1, nm1 + 1):
                psi += 1.0 / ii
            de = fact * (-math.log(x) + psi)
        ans += de
        if abs(de) < abs(ans) * EPS:
            break
    return ans                                                   # A&S 5.1.12


@ngjit
def expint(order, x):
    """E_n(x) = int_1^oo exp(-x t) t^-n dt of a whole order n (|n| <= MAX_ORDER):
    a hole for x < 0 (complex), and at 0 where n <= 1 (a pole)."""
    n, ok = _whole(order)
    if not ok or math.isnan(x) or x < 0.0:
        return math.nan
    if math.isinf(x):
        return 0.0
    if x == 0.0:
        return 1.0 / (n - 1) if n > 1 else math.inf
    if n < 0:
        # E_-m(x) = m! exp(-x) / x^(m+1) sum_(k<=m) x^k / k!, from k = m down
        t = 1.0 / x
        total = t
        for k in range(-n, 0, -1):
            t *= k / x
            total += t
        return math.exp(-x) * total
    return _expint(n, x)


@ngjit
def Ei(x):
    """Ei(x) = -PV int_-x^oo exp(-t) / t dt: a hole at 0 (a pole)."""
    if math.isnan(x) or x == 0.0:
        return math.nan if math.isnan(x) else -math.inf
    if x < 0.0:
        return -_e1(-x) if x > -math.inf else 0.0
    if math.isinf(x):
        return math.inf
    if x <= EI_SERIES_MAX:
        total = 0.0
        fact = 1.0
        for k in range(1, 1000):
            fact *= x / k
            term = fact / k
            total += term
            if term < EPS * total:
                break
        return total + math.log(x) + EULER_GAMMA                 # A&S 5.1.10
    total = 0.0
    term = 1.0
    for k in range(1, 1000):
        prev = term
        term *= k / x
        if term < EPS:
            break
        if term < prev:
            total += term
        else:
            total -= prev
            break
    return math.exp(x) * (1.0 + total) / x


@ngjit
def _shichi(x):
    """(Shi(t), Chi(t)) of t = |x| > 0, t <= SHICHI_SERIES_MAX (A&S 5.2.18, 5.2.19)."""
    t = abs(x)
    shi = t
    chi = 0.0
    term = t                            # t^(2k+1) / (2k+1)!
    for k in range(1, 1000):
        term *= t / (2 * k)
        dc = term / (2 * k)             # t^2k / (2k)! / 2k
        chi += dc
        term *= t / (2 * k + 1)
        ds = term / (2 * k + 1)
        shi += ds
        if ds <= EPS * shi and dc <= EPS * abs(chi):
            break
    return shi, chi + math.log(t) + EULER_GAMMA


@ngjit
def Shi(x):
    """Shi(x) = int_0^x sinh t / t dt."""
    if math.isnan(x) or x == 0.0:
        return x
    t = abs(x)
    if math.isinf(t):
        s = math.inf
    elif t <= SHICHI_SERIES_MAX:
        s = _shichi(t)[0]
    else:
        s = 0.5 * (Ei(t) + _e1(t))
    return -s if x < 0.0 else s


@ngjit
def Chi(x):
    """Chi(x) = gamma + log x + int_0^x (cosh t - 1) / t dt: a hole for x <= 0."""
    if math.isnan(x) or x <= 0.0:
        return math.nan
    if math.isinf(x):
        return math.inf
    if x <= SHICHI_SERIES_MAX:
        return _shichi(x)[1]
    return 0.5 * (Ei(x) - _e1(x))


@ngjit
def _fresnel(x):
    """(S(|x|), C(|x|)), sympy's normalisation; NR's frenel."""
    ax = abs(x)
    if ax < 1e-150:
        return 0.0, ax
    if ax <= FRESNEL_SERIES_MAX:
        total = 0.0
        sums = 0.0
        sumc = ax
        sign = 1.0
        fact = 0.5 * math.pi * ax * ax
        odd = True
        term = ax
        n = 3
        for k in range(1, 1000):
            term *= fact / k
            total += sign * term / n
            test = abs(total) * EPS
            if odd:
                sign = -sign
                sums = total
                total = sumc
            else:
                sumc = total
                total = sums
            if term < test:
                break
            odd = not odd
            n += 2
        return sums, sumc
    if ax > FRESNEL_FAR:
        # A&S 7.3.9, 7.3.10 with f = 1 / (pi x), g = 0 to the precision
        f = 1.0 / (math.pi * ax)
        ph = 0.5 * math.pi * ax * ax
        return 0.5 - f * math.cos(ph), 0.5 + f * math.sin(ph)
    pix2 = math.pi * ax * ax
    b = complex(1.0, -pix2)
    cc = complex(1.0 / FPMIN, 0.0)
    d = 1.0 / b
    h = d
    n = -1
    for k in range(2, 100000):
        n += 2
        a = -float(n * (n + 1))
        b += 4.0
        d = 1.0 / (a * d + b)
        cc = b + a / cc
        de = cc * d
        h *= de
        if abs(de.real - 1.0) + abs(de.imag) < EPS:
            break
    h *= complex(ax, -ax)
    cs = complex(0.5, 0.5) * (1.0 - complex(math.cos(0.5 * pix2), math.sin(0.5 * pix2)) * h)
    return cs.imag, cs.real


@ngjit
def _fresnel_odd(x, k):
    """S (k = 0) or C (k = 1) at x: odd functions, +-1/2 at +-infinity."""
    if math.isnan(x):
        return math.nan
    if math.isinf(x):
        return math.copysign(0.5, x)
    v = _fresnel(x)[k]
    return -v if x < 0.0 else v


@ngjit
def fresnels(x):
    """Fresnel's S(x) = int_0^x sin(pi t^2 / 2) dt."""
    return _fresnel_odd(x, 0)


@ngjit
def fresnelc(x):
    """Fresnel's C(x) = int_0^x cos(pi t^2 / 2) dt."""
    return _fresnel_odd(x, 1)


@ngjit
def erfi(x):
    """erfi(x) = 2 / sqrt(pi) int_0^x exp(t^2) dt."""
    if math.isnan(x) or math.isinf(x):
        return x
    t = abs(x)
    if t <= ERFI_SERIES_MAX:
        # 2 / sqrt(pi) sum x^(2k+1) / (k! (2k+1)), every term positive
        p = t
        total = t
        t2 = t * t
        for k in range(1, 1000):
            p *= t2 / k
            term = p / (2 * k + 1)
            total += term
            if term <= EPS * total:
                break
        s = 2.0 / math.sqrt(math.pi) * total
    else:
        q = 1.0 / (2.0 * t * t)
        term = 1.0
        total = 1.0
        for k in range(1, 1000):
            nxt = term * (2 * k - 1) * q
            if nxt >= term or nxt <= EPS * total:
                break
            term = nxt
            total += term
        s = math.exp(t * t) / (t * math.sqrt(math.pi)) * total
    return -s if x < 0.0 else s


@ngjit
def li(x):
    """The logarithmic integral li(x) = Ei(log x) (A&S 5.1.3), x >= 0 (li(0) = 0;
    x = 1: a pole; x < 0: a hole)."""
    if math.isnan(x) or x < 0.0:
        return math.nan
    if x == 0.0:
        return 0.0
    return Ei(math.log(x))


#: li(2), the offset of Li (A&S 5.1.3's note)
LI2 = 1.0451637801174927848


@ngjit
def Li(x):
    """The offset logarithmic integral Li(x) = li(x) - li(2)."""
    return li(x) - LI2

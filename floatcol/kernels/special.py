"""Bessel functions of whole order for compiled surfaces: J_n(x) (sympy's besselj,
scipy's jv) and I_n(x) (besseli, iv), which Numba's math module lacks. A drum's modes
J_n(k r) cos(n phi), a heat kernel's I_n: the surfaces physics plots most after the
elementary functions.

- J_n, |x| <= MILLER_MAX or n > |x|: Miller's backward recurrence from an order well
  above n and |x|, J_{k-1} = (2k/x) J_k - J_{k+1}, normalised by the identity
  J_0 + 2 (J_2 + J_4 + ...) = 1 (Abramowitz & Stegun 9.1.46, 9.1.27; Numerical
  Recipes' bessj). Stable for every order: the recurrence's error shrinks downward.
- J_n, |x| > MILLER_MAX and n <= |x|: J_0 and J_1 from Hankel's asymptotic expansion
  (A&S 9.2.5, 9.2.9, 9.2.10) summed until its terms are below double precision, then
  J_{k+1} = (2k/x) J_k - J_{k-1} upward, stable while k < |x| (A&S 9.1.27).
- I_n: its power series (A&S 9.6.10), every term positive (no cancellation), for
  |x| <= ISERIES_MAX or n^2 > |x|; beyond, the asymptotic expansion (A&S 9.7.1).

Agreement with mpmath (tests/test_special.py, orders -6..100, |x| up to 2e4): J_n to
1.2e-15 absolute, and 2.2e-13 relative where |J_n| > 1e-3; I_n to 8.5e-14 relative. A
whole order only (|n| <= MAX_ORDER): another order
is NaN (a hole; the expression's compile refuses a symbolic one, surface.py). Infinite
x: J_n 0, I_n infinite (a hole); NaN: NaN.
"""
import math

from ._jit import ngjit

#: |x| up to which J_n takes Miller's recurrence for every order
MILLER_MAX = 25.0
#: how far above max(n, |x|) Miller's recurrence starts: sqrt(MILLER_ACC max(n, |x|))
#: orders more (Numerical Recipes' ACC, raised from 40 for double precision)
MILLER_ACC = 160.0
#: rescale the recurrence's values past this size (they grow downward)
_BIG = 1.0e10
#: |x| up to which I_n sums its series
ISERIES_MAX = 60.0
#: the largest order (a larger one is NaN; the expression's compile refuses it)
MAX_ORDER = 1000
#: |x| below which both take their series' first two terms (A&S 9.1.10, 9.6.10)
TINY = 1.0e-5


@ngjit
def _whole(order):
    """(n, ok): the order as an int, and whether it is a whole number."""
    if not math.isfinite(order) or abs(order) > MAX_ORDER:
        return 0, False
    n = int(order)
    return n, n == order


@ngjit
def _hankel01(x):
    """(J_0(x), J_1(x)) for x > MILLER_MAX: Hankel's expansion (A&S 9.2.5, 9.2.9-10),
    P and Q summed until a term is below 1e-17 of the sum or the terms grow."""
    out0 = 0.0
    out1 = 0.0
    for nu in range(2):
        mu = 4.0 * nu * nu
        p = 1.0
        q = 0.0
        term = 1.0
        last = 1.0e300
        for k in range(1, 200):
            term *= (mu - (2.0 * k - 1.0) ** 2) / (k * 8.0 * x)
            size = abs(term)
            if size >= last:
                break
            last = size
            # P = sum over even k of (-1)^(k/2) t_k; Q over odd k of (-1)^((k-1)/2) t_k
            if k % 2 == 0:
                p += term if k % 4 == 0 else -term
            else:
                q += term if k % 4 == 1 else -term
            if size < 1.0e-17:
                break
        chi = x - (0.5 * nu + 0.25) * math.pi
        value = math.sqrt(2.0 / (math.pi * x)) * (p * math.cos(chi) - q * math.sin(chi))
        if nu == 0:
            out0 = value
        else:
            out1 = value
    return out0, out1


@ngjit
def _miller(n, x):
    """J_n(x), x > 0, by Miller's backward recurrence normalised by
    J_0 + 2 sum J_2k = 1 (A&S 9.1.46)."""
    top = max(float(n), x)
    m = 2 * ((int(top) + int(math.sqrt(MILLER_ACC * top)) + 16) // 2)
    tox = 2.0 / x
    bjp = 0.0
    bj = 1.0
    total = 0.0
    ans = 0.0
    even = False
    for j in range(m, 0, -1):
        bjm = j * tox * bj - bjp            # J_{j-1} = (2j/x) J_j - J_{j+1} (A&S 9.1.27)
        bjp = bj
        bj = bjm
        if abs(bj) > _BIG:
            bj /= _BIG
            bjp /= _BIG
            ans /= _BIG
            total /= _BIG
        if even:
            total += bj
        even = not even
        if j == n:
            ans = bjp
    if n == 0:
        ans = bj
    return ans / (2.0 * total - bj)


@ngjit
def besselj(order, x):
    """J_order(x), the Bessel function of the first kind of a whole order."""
    n, ok = _whole(order)
    if not ok or math.isnan(x):
        return math.nan
    sign = 1.0
    if n < 0:                               # J_{-n} = (-1)^n J_n (A&S 9.1.5)
        n = -n
        if n % 2 == 1:
            sign = -sign
    if x < 0.0 and n % 2 == 1:              # J_n(-x) = (-1)^n J_n(x)
        sign = -sign
    ax = abs(x)
    if ax == 0.0:
        return sign if n == 0 else 0.0
    if math.isinf(ax):
        return 0.0
    if ax < TINY:                           # (x/2)^n / n! (1 - (x/2)^2 / (n + 1))
        half = 0.5 * ax
        lead = math.exp(n * math.log(half) - math.lgamma(n + 1.0))
        return sign * lead * (1.0 - half * half / (n + 1.0))
    if ax <= MILLER_MAX or n > ax:
        return sign * _miller(n, ax)
    j0, j1 = _hankel01(ax)
    if n == 0:
        return sign * j0
    prev = j0
    cur = j1
    for k in range(1, n):                   # upward: J_{k+1} = (2k/x) J_k - J_{k-1}
        nxt = (2.0 * k / ax) * cur - prev
        prev = cur
        cur = nxt
    return sign * cur


@ngjit
def besseli(order, x):
    """I_order(x), the modified Bessel function of the first kind of a whole order."""
    n, ok = _whole(order)
    if not ok or math.isnan(x):
        return math.nan
    n = abs(n)                              # I_{-n} = I_n (A&S 9.6.6)
    sign = -1.0 if (x < 0.0 and n % 2 == 1) else 1.0
    ax = abs(x)
    if ax == 0.0:
        return 1.0 if n == 0 else 0.0
    if math.isinf(ax):
        return sign * math.inf
    if ax <= ISERIES_MAX or n * n > ax:
        # sum_k (x/2)^(2k+n) / (k! (k+n)!) (A&S 9.6.10), its first term through
        # logarithms (no overflow of (x/2)^n or n! on the way)
        half = 0.5 * ax
        term = math.exp(n * math.log(half) - math.lgamma(n + 1.0))
        total = term
        q = half * half
        for k in range(1, 100000):
            if total == 0.0 or math.isinf(total):
                break                       # (under- or overflowed: 0 or a hole)
            term *= q / (k * (k + n))
            total += term
            if term < 1.0e-17 * total:
                break
        return sign * total
    # e^x / sqrt(2 pi x) sum_k (-1)^k prod_j (4n^2 - (2j-1)^2) / (k! (8x)^k) (A&S 9.7.1)
    mu = 4.0 * n * n
    total = 1.0
    term = 1.0
    last = 1.0e300
    for k in range(1, 200):
        term *= -(mu - (2.0 * k - 1.0) ** 2) / (k * 8.0 * ax)
        if abs(term) >= last:
            break
        last = abs(term)
        total += term
        if last < 1.0e-17:
            break
    return sign * math.exp(ax) / math.sqrt(2.0 * math.pi * ax) * total

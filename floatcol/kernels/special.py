"""Bessel functions of whole order for compiled surfaces: J_n(x) (sympy's besselj,
scipy's jv), Y_n(x) (bessely, yv), I_n(x) (besseli, iv) and K_n(x) (besselk, kv),
which Numba's math module lacks. A drum's modes J_n(k r) cos(n phi), an annulus's J
and Y together, a heat kernel's I_n and K_n: the surfaces physics plots most after the
elementary functions.

- J_n, |x| <= MILLER_MAX or n > |x|: Miller's backward recurrence from an order well
  above n and |x|, J_{k-1} = (2k/x) J_k - J_{k+1}, normalised by the identity
  J_0 + 2 (J_2 + J_4 + ...) = 1 (Abramowitz & Stegun 9.1.46, 9.1.27; Numerical
  Recipes' bessj). Stable for every order: the recurrence's error shrinks downward.
- J_n, |x| > MILLER_MAX and n <= |x|: J_0 and J_1 from Hankel's asymptotic expansion
  (A&S 9.2.5, 9.2.9, 9.2.10) summed until its terms are below double precision, then
  J_{k+1} = (2k/x) J_k - J_{k-1} upward, stable while k < |x| (A&S 9.1.27).
- Y_n, x > 0: Y_0 by Neumann's series over the J_2k of Miller's sweep (A&S 9.1.88)
  and Y_1 by its derivative, or Hankel's expansion beyond MILLER_MAX; then
  Y_{k+1} = (2k/x) Y_k - Y_{k-1} upward, stable for every order (Y grows with it).
- I_n: its power series (A&S 9.6.10), every term positive (no cancellation), for
  |x| <= ISERIES_MAX or n^2 > |x|; beyond, the asymptotic expansion (A&S 9.7.1).

- K_n, x > 0: the trapezoid rule on K_n(x) = int_0^oo exp(-x cosh t) cosh(n t) dt
  (A&S 9.6.24), whose integrand is analytic in a strip: its error falls
  exponentially with 1/h. The step resolves the integrand's peak (at sinh t = n/x,
  (x^2 + n^2)^(-1/4) wide): h = min(0.1, 0.4 / sqrt(hypot(x, n) + 1)), to a term below
  1e-17 of the sum past the peak.

Agreement with mpmath (tests/test_special.py, orders -6..100, |x| up to 2e4): J_n to
1.2e-15 absolute, and 2.2e-13 relative where |J_n| > 1e-3; Y_n to 7.1e-15 of
max(1, |Y_n|) and 3.7e-13 relative where |Y_n| > 1e-3; I_n to 8.5e-14 and K_n to
2e-14 relative. A
whole order only (|n| <= MAX_ORDER): another order is NaN (a hole; the expression's
compile refuses a symbolic one, surface.py). Infinite x: J_n, Y_n and K_n 0, I_n
infinite (a hole); Y_n and K_n of x <= 0 a hole (complex, or a pole at 0); NaN: NaN.
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
#: Euler's constant gamma
EULER_GAMMA = 0.57721566490153286061
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
def _order(order):
    """(|n|, the sign of J_n and Y_n against J_|n| and Y_|n|, whether the order is
    whole): C_{-n} = (-1)^n C_n (A&S 9.1.5)."""
    n, ok = _whole(order)
    if n < 0:
        return -n, (-1.0 if n % 2 != 0 else 1.0), ok
    return n, 1.0, ok


@ngjit
def _upward(n, x, c0, c1):
    """C_n(x) from C_0 and C_1 by C_{k+1} = (2k/x) C_k - C_{k-1} (A&S 9.1.27), for
    J (stable while n <= x) and Y (stable always); it stops at an overflow."""
    if n == 0:
        return c0
    prev = c0
    cur = c1
    for k in range(1, n):
        nxt = (2.0 * k / x) * cur - prev
        prev = cur
        cur = nxt
        if math.isinf(cur):
            break
    return cur


@ngjit
def _hankel01(x):
    """(J_0(x), J_1(x), Y_0(x), Y_1(x)) for x > MILLER_MAX: Hankel's expansion (A&S
    9.2.5-6, 9.2.9-10), P and Q summed until a term is below 1e-17 of the sum or the
    terms grow."""
    out0 = 0.0
    out1 = 0.0
    y0 = 0.0
    y1 = 0.0
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
        amp = math.sqrt(2.0 / (math.pi * x))
        value = amp * (p * math.cos(chi) - q * math.sin(chi))
        other = amp * (p * math.sin(chi) + q * math.cos(chi))
        if nu == 0:
            out0 = value
            y0 = other
        else:
            out1 = value
            y1 = other
    return out0, out1, y0, y1


@ngjit
def _miller(n, x):
    """(J_n(x), Y_0(x), Y_1(x)), x > 0, by Miller's backward recurrence from an order
    well above n and x, J_{j-1} = (2j/x) J_j - J_{j+1} (A&S 9.1.27), normalised by
    J_0 + 2 sum_k J_2k = 1 (A&S 9.1.46). The same sweep's J_m give Y_0 by Neumann's
    series, (2/pi) ((ln(x/2) + gamma) J_0 - 2 sum_k (-1)^k J_2k / k) (A&S 9.1.88),
    and Y_1 = -Y_0', through J_0' = -J_1 and J_2k' = (J_2k-1 - J_2k+1) / 2:
    -(2/pi) (J_0 / x - (ln(x/2) + gamma) J_1 - sum_k (-1)^k (J_2k-1 - J_2k+1) / k)."""
    top = max(float(n), x)
    m = 2 * ((int(top) + int(math.sqrt(MILLER_ACC * top)) + 16) // 2)
    tox = 2.0 / x
    bjp = 0.0
    bj = 1.0
    total = 0.0
    ans = 0.0
    s0 = 0.0                                # sum_k (-1)^k J_2k / k
    s1 = 0.0                                # sum_k (-1)^k (J_2k-1 - J_2k+1) / k
    j1 = 0.0
    even = False
    for j in range(m, 0, -1):
        bjm = j * tox * bj - bjp
        bjp = bj
        bj = bjm
        if abs(bj) > _BIG:
            bj /= _BIG
            bjp /= _BIG
            ans /= _BIG
            total /= _BIG
            s0 /= _BIG
            s1 /= _BIG
            j1 /= _BIG
        if even:
            total += bj
        even = not even
        if j == n:
            ans = bjp
        i = j - 1                           # (bj is J_i)
        if i >= 2 and i % 2 == 0:
            k = i // 2
            s0 += bj / k if k % 2 == 0 else -bj / k
        elif i % 2 == 1:                    # J_{2k+1}: from the terms k + 1 and k
            k = (i - 1) // 2
            c = 1.0 / (k + 1.0) + (1.0 / k if k >= 1 else 0.0)
            s1 += c * bj if k % 2 == 1 else -c * bj
        if i == 1:
            j1 = bj
    if n == 0:
        ans = bj
    norm = 2.0 * total - bj
    lg = math.log(0.5 * x) + EULER_GAMMA
    j0 = bj / norm
    y0 = (2.0 / math.pi) * (lg * j0 - 2.0 * s0 / norm)
    y1 = -(2.0 / math.pi) * (j0 / x - lg * j1 / norm - s1 / norm)
    return ans / norm, y0, y1


@ngjit
def bessely(order, x):
    """Y_order(x), the Bessel function of the second kind of a whole order: a hole
    (NaN) for x < 0, where it is complex, and at 0 (minus infinity)."""
    n, sign, ok = _order(order)
    if not ok or math.isnan(x) or x < 0.0:
        return math.nan
    if x == 0.0:
        return -math.inf if n % 2 == 0 or sign > 0.0 else math.inf
    if math.isinf(x):
        return 0.0
    if x < 1.0e-100:                        # the series' leading terms (A&S 9.1.13)
        y0 = (2.0 / math.pi) * (math.log(0.5 * x) + EULER_GAMMA)
        y1 = -2.0 / (math.pi * x)
    elif x <= MILLER_MAX:
        _, y0, y1 = _miller(0, x)
    else:
        _, _, y0, y1 = _hankel01(x)
    return sign * _upward(n, x, y0, y1)           # (stable for Y at every order)


@ngjit
def besselj(order, x):
    """J_order(x), the Bessel function of the first kind of a whole order."""
    n, sign, ok = _order(order)
    if not ok or math.isnan(x):
        return math.nan
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
        return sign * _miller(n, ax)[0]
    j0, j1, _, _ = _hankel01(ax)
    return sign * _upward(n, ax, j0, j1)          # (stable for J while n <= x)


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


@ngjit
def besselk(order, x):
    """K_order(x), the modified Bessel function of the second kind of a whole order:
    a hole (NaN) for x < 0, where it is complex, and at 0 (infinity)."""
    n, ok = _whole(order)
    if not ok or math.isnan(x) or x < 0.0:
        return math.nan
    n = abs(n)                              # K_{-n} = K_n (A&S 9.6.6)
    if x == 0.0:
        return math.inf
    if math.isinf(x):
        return 0.0
    return _kv(float(n), x)


@ngjit
def _kv(nu, x):
    """K_nu(x) of a real order nu >= 0 and x > 0: the trapezoid rule on
    int_0^oo exp(-x cosh t) cosh(nu t) dt (A&S 9.6.24)."""
    # (through hypot: x^2 overflows past 1e154, which made h 0 and the loop endless)
    h = min(0.1, 0.4 / math.sqrt(math.hypot(x, nu) + 1.0))
    peak = math.asinh(nu / x)
    total = 0.5 * math.exp(-x)              # (the trapezoid's half weight at t = 0)
    for k in range(1, 1000000):
        t = k * h
        a = -x * math.cosh(t)
        term = 0.5 * (math.exp(a + nu * t) + math.exp(a - nu * t))
        total += term
        if (t > peak and term <= 1.0e-17 * total) or math.isinf(total):
            break
    return h * total

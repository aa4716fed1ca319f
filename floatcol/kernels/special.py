"""Bessel functions for compiled surfaces: J_n(x) (sympy's besselj, scipy's jv), Y_n(x)
(bessely, yv), I_n(x) (besseli, iv) and K_n(x) (besselk, kv) of whole orders and of
any other real order nu, and the spherical j_n and y_n (sympy's jn, yn), which
Numba's math module lacks. A drum's modes J_n(k r) cos(n phi), an annulus's J
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

Orders that are not whole (x > 0; x < 0 is complex: a hole):

- J_nu, Y_nu, x > MILLER_MAX and nu <= x: Hankel's expansion (A&S 9.2.5-9.2.10) at
  the order's fraction mu and mu + 1, then the upward recurrence; elsewhere Steed's
  continued fractions and Temme's series (Numerical Recipes' bessjy, at double
  precision, Gamma's functions of mu directly); negative orders by A&S 9.1.2.
- I_nu: the series and asymptotic expansion of a whole order's (9.6.10, 9.7.1);
  I_-nu = I_nu + (2/pi) sin(nu pi) K_nu (9.6.2). K_nu: the trapezoid rule as above.
- j_n(x) = sqrt(pi / 2x) J_(n+1/2)(x), y_n likewise (A&S 10.1.1).

Agreement with mpmath (tests/test_special.py, orders -6..100, |x| up to 2e4): J_n to
1.2e-15 absolute, and 2.2e-13 relative where |J_n| > 1e-3; Y_n to 7.1e-15 of
max(1, |Y_n|) and 3.7e-13 relative where |Y_n| > 1e-3; I_n to 8.5e-14 and K_n to
2e-14 relative; orders that are not whole (-10.1 to 999.5) to 6.9e-14 of max(1,
|value|). |order| <= MAX_ORDER: another is NaN (a hole; the expression's compile
refuses it and a symbolic one, surface.py). Infinite x: J_n, Y_n and K_n 0, I_n
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
def _fractional(order):
    """Is the order a finite number, |order| <= MAX_ORDER, that is not whole?"""
    return math.isfinite(order) and abs(order) <= MAX_ORDER and order != math.floor(order)


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
    """(J_0(x), J_1(x), Y_0(x), Y_1(x)) for x > MILLER_MAX: Hankel's expansion
    (_hankel)."""
    j0, y0 = _hankel(0.0, x)
    j1, y1 = _hankel(1.0, x)
    return j0, j1, y0, y1


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
    if _fractional(order):
        if math.isnan(x) or x < 0.0:
            return math.nan
        if x == 0.0 or math.isinf(x):
            return -math.inf if x == 0.0 else 0.0
        return _frac_jy(order, x)[1]
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
    """J_order(x), the Bessel function of the first kind: of a whole order, or of
    another real one for x >= 0 (for x < 0 it is complex: a hole)."""
    if _fractional(order):
        if math.isnan(x) or x < 0.0:
            return math.nan
        if x == 0.0 or math.isinf(x):
            return (0.0 if order > 0.0 else math.inf) if x == 0.0 else 0.0
        return _frac_jy(order, x)[0]
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
    """I_order(x), the modified Bessel function of the first kind: of a whole order, or
    of another real one for x >= 0."""
    if _fractional(order):
        if math.isnan(x) or x < 0.0:
            return math.nan
        if x == 0.0 or math.isinf(x):
            return (0.0 if order > 0.0 else math.inf) if x == 0.0 else math.inf
        nu = abs(order)
        i = _i_real(nu, x)
        if order < 0.0:                     # I_-nu = I_nu + (2/pi) sin(nu pi) K_nu (9.6.2)
            i += 2.0 / math.pi * _sincospi(nu)[0] * _kv(nu, x)
        return i
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
    return sign * _i_real(float(n), ax)


@ngjit
def besselk(order, x):
    """K_order(x), the modified Bessel function of the second kind of a whole order:
    a hole (NaN) for x < 0, where it is complex, and at 0 (infinity); any real order."""
    if _fractional(order):
        if math.isnan(x) or x < 0.0:
            return math.nan
        if x == 0.0 or math.isinf(x):
            return math.inf if x == 0.0 else 0.0
        return _kv(abs(order), x)                # K_-nu = K_nu (A&S 9.6.6)
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


# -- orders that are not whole numbers -----------------------------------------------

#: Taylor coefficients of 1 / Gamma(1 + z) at 0 (A&S 6.1.34), the odd ones: gam1 of
#: Temme's method for |mu| < GAM_SERIES
_RGAMMA_ODD = (0.5772156649015329, -0.04200263503409524, -0.04219773455554433,
               0.0072189432466631, -0.00021524167411495098)
GAM_SERIES = 0.01
#: Steed's and Temme's methods (Numerical Recipes' bessjy) at x below this; the
#: orders' fractions by Hankel's expansion beyond, where nu <= x
TEMME_XMIN = 2.0
_EPS = 1.0e-16
_FPMIN = 1.0e-300
_MAXIT = 100000


@ngjit
def _temme_gammas(mu):
    """(gam1, gam2, 1/Gamma(1+mu), 1/Gamma(1-mu)) of Temme's method, |mu| <= 1/2."""
    gampl = 1.0 / math.gamma(1.0 + mu)
    gammi = 1.0 / math.gamma(1.0 - mu)
    if abs(mu) < GAM_SERIES:
        m2 = mu * mu
        gam1 = -(_RGAMMA_ODD[0] + m2 * (_RGAMMA_ODD[1] + m2 * (_RGAMMA_ODD[2] + m2 * (
            _RGAMMA_ODD[3] + m2 * _RGAMMA_ODD[4]))))
    else:
        gam1 = (gammi - gampl) / (2.0 * mu)
    return gam1, 0.5 * (gammi + gampl), gampl, gammi


@ngjit
def _hankel(nu, x):
    """(J_nu(x), Y_nu(x)) by Hankel's asymptotic expansion (A&S 9.2.5-6, 9.2.9-10),
    x >> nu^2: P = sum over even k of (-1)^(k/2) t_k, Q over odd k of (-1)^((k-1)/2)
    t_k, summed until a term is below 1e-17 or the terms grow."""
    m = 4.0 * nu * nu
    p = 1.0
    q = 0.0
    term = 1.0
    last = math.inf
    for k in range(1, 400):
        term *= (m - (2.0 * k - 1.0) ** 2) / (k * 8.0 * x)
        if abs(term) >= last:
            break
        last = abs(term)
        if k % 4 == 1:
            q += term
        elif k % 4 == 2:
            p -= term
        elif k % 4 == 3:
            q -= term
        else:
            p += term
        if last < 1e-17:
            break
    chi = x - (0.5 * nu + 0.25) * math.pi
    s = math.sqrt(2.0 / (math.pi * x))
    c = math.cos(chi)
    sn = math.sin(chi)
    return s * (p * c - q * sn), s * (p * sn + q * c)


@ngjit
def _steed_temme(nu, x):
    """(J_nu(x), Y_nu(x)) for nu >= 0, x > 0: Numerical Recipes' bessjy (Steed's
    continued fractions CF1, CF2 and Temme's series for x < TEMME_XMIN), at double
    precision; Gamma's functions of mu directly (_temme_gammas)."""
    nl = int(nu + 0.5) if x < TEMME_XMIN else max(0, int(nu - x + 1.5))
    xmu = nu - nl
    xmu2 = xmu * xmu
    xi = 1.0 / x
    xi2 = 2.0 * xi
    w = xi2 / math.pi
    isign = 1.0
    h = max(nu * xi, _FPMIN)
    b = xi2 * nu
    d = 0.0
    c = h
    for _ in range(_MAXIT):                 # CF1: J'_nu / J_nu (NR 6.7.2)
        b += xi2
        d = b - d
        if abs(d) < _FPMIN:
            d = _FPMIN
        c = b - 1.0 / c
        if abs(c) < _FPMIN:
            c = _FPMIN
        d = 1.0 / d
        de = c * d
        h = de * h
        if d < 0.0:
            isign = -isign
        if abs(de - 1.0) < _EPS:
            break
    rjl = isign * _FPMIN
    rjpl = h * rjl
    rjl1 = rjl
    fact = nu * xi
    for _ in range(nl, 0, -1):              # down to mu (A&S 9.1.27)
        rjtemp = fact * rjl + rjpl
        fact -= xi
        rjpl = fact * rjtemp - rjl
        rjl = rjtemp
    if rjl == 0.0:
        rjl = _EPS
    f = rjpl / rjl
    if x < TEMME_XMIN:                      # Temme's series for Y_mu, Y_mu+1
        x2 = 0.5 * x
        pimu = math.pi * xmu
        fact = 1.0 if abs(pimu) < _EPS else pimu / math.sin(pimu)
        d = -math.log(x2)
        e = xmu * d
        fact2 = 1.0 if abs(e) < _EPS else math.sinh(e) / e
        gam1, gam2, gampl, gammi = _temme_gammas(xmu)
        ff = 2.0 / math.pi * fact * (gam1 * math.cosh(e) + gam2 * fact2 * d)
        e = math.exp(e)
        p = e / (gampl * math.pi)
        q = 1.0 / (e * math.pi * gammi)
        pimu2 = 0.5 * pimu
        fact3 = 1.0 if abs(pimu2) < _EPS else math.sin(pimu2) / pimu2
        r = math.pi * pimu2 * fact3 * fact3
        c = 1.0
        d = -x2 * x2
        total = ff + r * q
        total1 = p
        for i in range(1, _MAXIT):
            ff = (i * ff + p + q) / (i * i - xmu2)
            c *= d / i
            p /= i - xmu
            q /= i + xmu
            de = c * (ff + r * q)
            total += de
            de1 = c * p - i * de
            total1 += de1
            if abs(de) < (1.0 + abs(total)) * _EPS:
                break
        rymu = -total
        ry1 = -total1 * xi2
        rymup = xmu * xi * rymu - ry1
        rjmu = w / (rymup - f * rymu)       # the Wronskian (A&S 9.1.16)
    else:                                   # CF2: p + i q (NR 6.7.3), Lentz
        a = 0.25 - xmu2
        p = -0.5 * xi
        q = 1.0
        br = 2.0 * x
        bi = 2.0
        fact = a * xi / (p * p + q * q)
        cr = br + q * fact
        ci = bi + p * fact
        den = br * br + bi * bi
        dr = br / den
        di = -bi / den
        dlr = cr * dr - ci * di
        dli = cr * di + ci * dr
        temp = p * dlr - q * dli
        q = p * dli + q * dlr
        p = temp
        for i in range(2, _MAXIT):
            a += 2 * (i - 1)
            bi += 2.0
            dr = a * dr + br
            di = a * di + bi
            if abs(dr) + abs(di) < _FPMIN:
                dr = _FPMIN
            fact = a / (cr * cr + ci * ci)
            cr = br + cr * fact
            ci = bi - ci * fact
            if abs(cr) + abs(ci) < _FPMIN:
                cr = _FPMIN
            den = dr * dr + di * di
            dr /= den
            di /= -den
            dlr = cr * dr - ci * di
            dli = cr * di + ci * dr
            temp = p * dlr - q * dli
            q = p * dli + q * dlr
            p = temp
            if abs(dlr - 1.0) + abs(dli) < _EPS:
                break
        gam = (p - f) / q
        rjmu = math.sqrt(w / ((p - f) * gam + q))
        rjmu = math.copysign(rjmu, rjl)
        rymu = rjmu * gam
        rymup = rymu * (p + q / gam)
        ry1 = xmu * xi * rymu - rymup
    fact = rjmu / rjl
    rj = rjl1 * fact
    for i in range(1, nl + 1):              # Y upward (stable)
        rytemp = (xmu + i) * xi2 * ry1 - rymu
        rymu = ry1
        ry1 = rytemp
    return rj, rymu


@ngjit
def _jy(nu, x):
    """(J_nu(x), Y_nu(x)), nu >= 0, x > 0, any real order: Hankel's expansion at the
    order's fraction and the upward recurrence where x > HANKEL_MIN and nu <= x, else
    Steed's and Temme's methods."""
    if x > MILLER_MAX and nu <= x:
        mu = nu - math.floor(nu)
        j0, y0 = _hankel(mu, x)
        if nu == mu:
            return j0, y0
        j1, y1 = _hankel(mu + 1.0, x)
        k = mu + 1.0
        while k < nu - 0.5:                 # (J and Y upward: stable while k < x)
            j0, j1 = j1, 2.0 * k / x * j1 - j0
            y0, y1 = y1, 2.0 * k / x * y1 - y0
            k += 1.0
        return j1, y1
    return _steed_temme(nu, x)


@ngjit
def _frac_jy(order, x):
    """(J, Y) of a real order that is not whole, x > 0 (A&S 9.1.2 for a negative one:
    J_-nu = cos(nu pi) J_nu - sin(nu pi) Y_nu, Y_-nu = sin(nu pi) J_nu + cos(nu pi) Y_nu)."""
    nu = abs(order)
    j, y = _jy(nu, x)
    if order >= 0.0:
        return j, y
    s, c = _sincospi(nu)
    return c * j - s * y, s * j + c * y


@ngjit
def _sincospi(nu):
    """(sin(pi nu), cos(pi nu)), exact where they are 0 or +-1 (cos(pi / 2) in doubles
    is 6e-17, which took 6e-17 Y_1/2(x) into Y_-1/2(x): a relative error of 6e-9 at
    x = 1e-8)."""
    r = nu - 2.0 * math.floor(0.5 * nu)     # (nu mod 2, exactly)
    if r == 0.5:
        return 1.0, 0.0
    if r == 1.5:
        return -1.0, 0.0
    return math.sin(math.pi * r), math.cos(math.pi * r)


@ngjit
def _i_real(nu, x):
    """I_nu(x), nu >= 0, 0 < x < oo: its series (A&S 9.6.10), every term positive (no
    cancellation), for x <= ISERIES_MAX or nu^2 > x, its first term through logarithms
    (no overflow of (x/2)^nu or nu! on the way); beyond, the asymptotic expansion
    e^x / sqrt(2 pi x) sum_k (-1)^k prod_j (4 nu^2 - (2j-1)^2) / (k! (8x)^k) (9.7.1)."""
    if x <= ISERIES_MAX or nu * nu > x:
        half = 0.5 * x
        term = math.exp(nu * math.log(half) - math.lgamma(nu + 1.0))
        total = term
        q = half * half
        for k in range(1, 100000):
            if total == 0.0 or math.isinf(total):
                break                       # (under- or overflowed: 0 or a hole)
            term *= q / (k * (k + nu))
            total += term
            if term < 1.0e-17 * total:
                break
        return total
    mu = 4.0 * nu * nu
    total = 1.0
    term = 1.0
    last = 1.0e300
    for k in range(1, 200):
        term *= -(mu - (2.0 * k - 1.0) ** 2) / (k * 8.0 * x)
        if abs(term) >= last:
            break
        last = abs(term)
        total += term
        if last < 1.0e-17:
            break
    return math.exp(x) / math.sqrt(2.0 * math.pi * x) * total


@ngjit
def sph_jn(order, x):
    """The spherical Bessel function j_n(x) = sqrt(pi / 2x) J_(n+1/2)(x) of a whole
    order (A&S 10.1.1; sympy's jn, scipy's spherical_jn); j_n(-x) = (-1)^n j_n(x)."""
    n, ok = _whole(order)
    if not ok or math.isnan(x):
        return math.nan
    if x == 0.0:
        return (1.0 if n == 0 else 0.0) if n >= 0 else math.inf
    sign = -1.0 if (x < 0.0 and n % 2 != 0) else 1.0
    ax = abs(x)
    if math.isinf(ax):
        return 0.0
    return sign * math.sqrt(0.5 * math.pi / ax) * _frac_jy(n + 0.5, ax)[0]


@ngjit
def sph_yn(order, x):
    """The spherical Bessel function y_n(x) = sqrt(pi / 2x) Y_(n+1/2)(x) of a whole
    order (A&S 10.1.1; sympy's yn, scipy's spherical_yn); y_n(-x) = (-1)^(n+1) y_n(x)."""
    n, ok = _whole(order)
    if not ok or math.isnan(x):
        return math.nan
    if x == 0.0:
        return -math.inf
    sign = -1.0 if (x < 0.0 and n % 2 == 0) else 1.0
    ax = abs(x)
    if math.isinf(ax):
        return 0.0
    return sign * math.sqrt(0.5 * math.pi / ax) * _frac_jy(n + 0.5, ax)[1]

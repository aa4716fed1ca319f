"""sin, cos and exp that a compiler can vectorise: for the batch evaluator.

libm's functions are calls, and a loop with a call in it stays scalar: evaluating
3 sin(u cos v) with its two partials costs about 66 ns per point that way, most of it
in libm's sincos. These are branch-free (selects only) and small: LLVM inlines them
into the batch evaluator's loop (a cached function carries its bitcode for that) and
turns the loop into SIMD code (4 points per instruction with AVX2, 8 with AVX-512):
the same evaluation costs 3-8 ns per point.

They are not inlined at Numba's level (``inline="always"``): Numba copies the callee's
IR and runs its passes on the copy at every call site, nested, which made a new
expression's batch evaluator take 0.8-1.4 s to compile instead of 0.1-0.2 s
(3 sin(u cos v), sin(u v) + cos(u), exp(-u^2 - v^2) cos(3u)), with the same SIMD code.

They agree with libm to 2 units in the last place (tests/test_vmath.py), and outside
the range where that holds they return NaN, which the batch evaluator's caller takes
as "evaluate this point again with the scalar function" (column.py), never as a hole:
sin and cos for |x| >= VTRIG_MAX (the reduction below is exact only up to there), exp
outside [VEXP_MIN, VEXP_MAX] (overflow and subnormal results).
"""
import numba
import numpy as np
from numba import types
from numba.extending import intrinsic

#: Compiled once (cached on disk); LLVM inlines them into the caller (module docstring);
#: a multiplication and an addition may be one FMA instruction (_jit.py _MATH)
_vjit = numba.njit(cache=True, nogil=True, error_model="numpy", fastmath={"contract"})

# Cody-Waite reduction by pi/2 in three parts (fdlibm's constants): PIO2_1 has 33
# significant bits, so k * PIO2_1 is exact for |k| < 2**20.
TWO_OVER_PI = 6.36619772367581382433e-01
PIO2_1 = 1.57079632673412561417e+00
PIO2_2 = 6.07710050630396597660e-11
PIO2_3 = 2.02226624871116645580e-21
VTRIG_MAX = 1.0e6
# fdlibm's minimax kernels of sin and cos on [-pi/4, pi/4]
S1 = -1.66666666666666324348e-01
S2 = 8.33333333332248946124e-03
S3 = -1.98412698298579493134e-04
S4 = 2.75573137070700676789e-06
S5 = -2.50507602534068634195e-08
S6 = 1.58969099521155010221e-10
C1 = 4.16666666666666019037e-02
C2 = -1.38888888888741095749e-03
C3 = 2.48015872894767294178e-05
C4 = -2.75573143513906633035e-07
C5 = 2.08757232129817482790e-09
C6 = -1.13596475577881948265e-11
# exp: x = k ln2 + r, |r| <= ln2 / 2, exp(r) by its Taylor series to r**13 (the
# remainder is below 1e-17), times 2**k built in the exponent bits
INV_LN2 = 1.44269504088896338700e+00
LN2_HI = 6.93147180369123816490e-01
LN2_LO = 1.90821492927058770002e-10
VEXP_MIN = -708.0
VEXP_MAX = 709.0
_INV_FACT = tuple(1.0 / float(np.prod(np.arange(1, n + 1))) for n in range(14))


@intrinsic
def _int_bits_to_float(typingctx, i):
    """The float64 whose bits are those of the int64 i."""
    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], context.get_value_type(types.float64))
    return types.float64(types.int64), codegen


@_vjit
def _reduce(x):
    """(quadrant k mod 4, r) with x = k pi/2 + r, |r| <= pi/4."""
    k = np.rint(x * TWO_OVER_PI)
    r = ((x - k * PIO2_1) - k * PIO2_2) - k * PIO2_3
    return np.int64(k) & 3, r


@_vjit
def _kernel_sin(r, z):
    return r + r * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))))


@_vjit
def _kernel_cos(z):
    return 1.0 - 0.5 * z + z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))))


@_vjit
def _sincos(x):
    """(sin x, cos x) for |x| < VTRIG_MAX: the kernels at r, by x's quadrant."""
    q, r = _reduce(x)
    z = r * r
    s = _kernel_sin(r, z)
    c = _kernel_cos(z)
    sx = s if (q & 1) == 0 else c
    cx = c if (q & 1) == 0 else s
    return (-sx if q >= 2 else sx), (-cx if (q == 1 or q == 2) else cx)


@_vjit
def vsin(x):
    """sin(x); NaN where |x| >= VTRIG_MAX or x is not finite (evaluate again)."""
    return _sincos(x)[0] if abs(x) < VTRIG_MAX else np.nan


@_vjit
def vcos(x):
    """cos(x); NaN where |x| >= VTRIG_MAX or x is not finite (evaluate again)."""
    return _sincos(x)[1] if abs(x) < VTRIG_MAX else np.nan


@_vjit
def vexp(x):
    """exp(x); NaN outside [VEXP_MIN, VEXP_MAX] or for NaN (evaluate again)."""
    inside = x >= VEXP_MIN and x <= VEXP_MAX
    xc = x if inside else 0.0
    k = np.rint(xc * INV_LN2)
    r = (xc - k * LN2_HI) - k * LN2_LO
    p = 1.0 / 6227020800.0                 # 1/13!, then Horner down to 1/0!
    for n in range(12, -1, -1):
        p = p * r + _INV_FACT[n]
    scale = _int_bits_to_float((np.int64(k) + 1023) << 52)
    return p * scale if inside else np.nan


#: What the batch evaluator's lambdify maps sympy's functions to (surface.py)
VECTOR_FUNCTIONS = {"sin": vsin, "cos": vcos, "exp": vexp}

"""Float -> index conversions that are defined for every double.

In LLVM a conversion of a float to an integer is undefined (a "poison" value) where
the float is NaN, infinite or beyond the integer's range, and the optimiser may then
drop the bounds tests that follow it: a surface whose screen rows reach 1e300
(``tan(1/u)**2e10``) wrote past a column's buffers. Every float the kernels turn into
a row, a plane or a count goes through these: the float is clamped to +-2**52 first
(NaN to the low end), which changes nothing for any index a picture can hold.
"""
import math

from ._jit import ngjit_inline

#: the clamp: far beyond any row, plane or count, exact as a double and an int64
LIMIT = 4503599627370496.0      # 2**52


@ngjit_inline
def floor_index(x):
    """floor(x) as an int; -2**52 for NaN and below, 2**52 above."""
    if x >= LIMIT:
        return 4503599627370496
    if x > -LIMIT:
        return int(math.floor(x))
    return -4503599627370496


@ngjit_inline
def ceil_index(x):
    """ceil(x) as an int; -2**52 for NaN and below, 2**52 above."""
    if x >= LIMIT:
        return 4503599627370496
    if x > -LIMIT:
        return int(math.ceil(x))
    return -4503599627370496


@ngjit_inline
def round_index(x):
    """round(x) (half to even, as Python's) as an int; clamped as floor_index."""
    if x >= LIMIT:
        return 4503599627370496
    if x > -LIMIT:
        return int(round(x))
    return -4503599627370496


@ngjit_inline
def trunc_index(x):
    """int(x) (toward zero) as an int; clamped as floor_index."""
    if x >= LIMIT:
        return 4503599627370496
    if x > -LIMIT:
        return int(x)
    return -4503599627370496

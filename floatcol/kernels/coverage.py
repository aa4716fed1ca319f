"""The edge buffer's coverage planes, kept only where they say something (layout.py).

Most pixels a surface covers whole (E_COV0 = 1, no edge surface, E_COV = 0) or not
at all (both 0): for them the planes are neither cleared, written nor read. A pixel
whose planes hold values carries E_FLAG in its E_SEEN value (E_SEEN is then
side + E_FLAG: 7, 8 or 9 for the sides -1, 0, +1). With antialiasing off nothing is
flagged. At 1920x1080 this spares the column pass two of the three planes it cleared
per column, and the finishing pass two of the three it read per pixel.
"""
from ._jit import ngjit_inline
from .layout import E_COV, E_COV0, E_FLAG, E_SEEN


@ngjit_inline
def seen_side(x):
    """The side seen at a pixel's centre (+1, -1; 0 none) from its E_SEEN value x."""
    return x - E_FLAG if x > 0.5 * E_FLAG else x


@ngjit_inline
def coverages(ecol, j):
    """(E_COV0, E_COV) of row j of a column's edge buffer ecol (E_SIZE, H)."""
    x = ecol[E_SEEN, j]
    if x > 0.5 * E_FLAG:
        return ecol[E_COV0, j], ecol[E_COV, j]
    return (1.0 if x != 0.0 else 0.0), 0.0


@ngjit_inline
def keep_coverages(ecol, j):
    """Write row j's implied coverages into the planes and flag it (before one of
    them changes)."""
    x = ecol[E_SEEN, j]
    if x <= 0.5 * E_FLAG:
        ecol[E_COV0, j] = 1.0 if x != 0.0 else 0.0
        ecol[E_COV, j] = 0.0
        ecol[E_SEEN, j] = x + E_FLAG

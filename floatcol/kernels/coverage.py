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
def flagged(x):
    """Do the coverage planes hold the values of the pixel whose E_SEEN value is x?"""
    return x > 0.5 * E_FLAG


@ngjit_inline
def seen_side(x):
    """The side seen at a pixel's centre (+1, -1; 0 none) from its E_SEEN value x."""
    return x - E_FLAG if flagged(x) else x


@ngjit_inline
def implied_coverages(x):
    """(E_COV0, E_COV) of a pixel that is not flagged: whole where a surface is seen."""
    return (1.0 if x != 0.0 else 0.0), 0.0


@ngjit_inline
def coverages(ecol, j):
    """(E_COV0, E_COV) of row j of a column's edge buffer ecol (E_SIZE, H)."""
    x = ecol[E_SEEN, j]
    if flagged(x):
        return ecol[E_COV0, j], ecol[E_COV, j]
    return implied_coverages(x)


@ngjit_inline
def keep_coverages(ecol, j):
    """Write row j's implied coverages into the planes and flag it (before one of
    them changes)."""
    x = ecol[E_SEEN, j]
    if not flagged(x):
        ecol[E_COV0, j], ecol[E_COV, j] = implied_coverages(x)
        ecol[E_SEEN, j] = x + E_FLAG

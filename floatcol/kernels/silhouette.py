"""Antialiasing across columns at silhouettes, from the columns' own edges (section 6.4).

Coverage antialiasing along a column (column.py, coverage.py) blends the pixel where a
column's run of surface ends. Where a silhouette against the background is steeper than
a pixel row per column, the run ends of neighbouring columns lie rows apart, and the
pixels between them are all surface in one column and all background in the next: a
staircase. Sub-columns (antialias=2-4) average it away at 2-4 times the cost. This pass
instead reads where the silhouette crosses each of the two columns, the run ends at
float rows that the coverages of the runs' end pixels give, and takes the silhouette as
the straight line between them: each pixel of the staircase is then covered by the part
of it on the surface's side of that line (Wu's antialiased lines, with the ends known to
a fraction of a pixel).

A pair of neighbouring pixels in a row, one whole (covered by its centre's surface,
coverage 1, no edge surface) and one empty (nothing at its centre or in it), lies on a
run of such rows: rows r0..r1, pixel columns cs (surface) and ce (empty). The
silhouette is either

- below: the surface lies under it; ce shows surface just below the run (row r0 - 1)
  and cs stops being whole just above it (row r1 + 1). The silhouette crosses ce at the
  top of ce's surface, y_ce, and cs at the top of cs's, y_cs;
- or above: mirrored.

At row j of the run it crosses the row's centre line a fraction f = (j - y_ce) /
(y_cs - y_ce) of the way from ce's centre to cs's. The surface pixel keeps the part
beyond: coverage 1.5 - f where f > 1/2; the empty pixel gets the part before: 1/2 - f
where f < 1/2, in the colour of its surface neighbour. A pixel with such neighbours on
both sides adds the two (a sliver of surface: the two covered parts overlap). A run
longer than SIL_SCAN rows (a silhouette within 2 degrees of vertical), one that reaches
the picture's edge, and one whose ends say neither (a notch) are left as they are;
silhouettes over a farther surface are not touched (the edge surfaces of the coverage
pass blend those along the columns).

Only rgba changes. Each row is one parallel iteration that writes only its own pixels
(reading the original colour of a neighbour it has changed from a local), so the
picture is the same for any number of threads.
"""
import numpy as np
from numba import prange

from ._jit import ngjit_inline, ngjit_parallel_nrt_free
from .coverage import flagged, seen_side
from .layout import E_COV, E_COV0, E_SEEN
from .shade import LITTLE_ENDIAN, _rgba32

#: the longest staircase step (rows) whose silhouette is placed
SIL_SCAN = 32
#: a kept coverage at least this is whole (a float32 a little under 1 rounds to 255)
FULL = 1.0 - 1.0 / 512.0
EMPTY = 0
WHOLE = 1
PART = 2
#: 8 bytes of the side plane at once: the high bit of each byte that is not 0
LOW7 = np.uint64(0x7F7F7F7F7F7F7F7F)
HIGH = np.uint64(0x8080808080808080)


@ngjit_inline
def pixel_state(ebuf, c, j):
    """EMPTY, WHOLE or PART: how the surfaces cover pixel row j (from the bottom) of
    column c, from the tiled edge buffer (layout.py, coverage.py)."""
    T = ebuf.shape[3]
    x = ebuf[c // T, E_SEEN, j, c % T]
    if x == 0.0:
        return EMPTY
    if not flagged(x):
        return WHOLE
    if ebuf[c // T, E_COV, j, c % T] > 0.0:
        return PART
    if seen_side(x) == 0.0:
        return EMPTY
    return WHOLE if ebuf[c // T, E_COV0, j, c % T] >= FULL else PART


@ngjit_inline
def covered(ebuf, c, j):
    """The part of pixel row j of column c that surfaces cover."""
    T = ebuf.shape[3]
    x = ebuf[c // T, E_SEEN, j, c % T]
    if x == 0.0:
        return 0.0
    if not flagged(x):
        return 1.0
    cv = ebuf[c // T, E_COV, j, c % T]
    if seen_side(x) != 0.0:
        cv += ebuf[c // T, E_COV0, j, c % T]
    return min(max(cv, 0.0), 1.0)


@ngjit_inline
def crossing(ebuf, H, cs, ce, j):
    """f: where the silhouette between the whole pixel (cs, j) and the empty (ce, j)
    crosses row j's centre line, as a fraction of the way from ce's centre to cs's;
    -1 where the run's ends do not place it (the module's docstring)."""
    r0 = j
    n = 0
    while r0 > 0 and n < SIL_SCAN:
        if pixel_state(ebuf, cs, r0 - 1) != WHOLE or pixel_state(ebuf, ce, r0 - 1) != EMPTY:
            break
        r0 -= 1
        n += 1
    r1 = j
    m = 0
    while r1 < H - 1 and m < SIL_SCAN:
        if pixel_state(ebuf, cs, r1 + 1) != WHOLE or pixel_state(ebuf, ce, r1 + 1) != EMPTY:
            break
        r1 += 1
        m += 1
    if n == SIL_SCAN or m == SIL_SCAN or r0 == 0 or r1 == H - 1:
        return -1.0
    below = (pixel_state(ebuf, ce, r0 - 1) != EMPTY
             and pixel_state(ebuf, cs, r1 + 1) != WHOLE)     # the surface under the line
    above = (pixel_state(ebuf, ce, r1 + 1) != EMPTY
             and pixel_state(ebuf, cs, r0 - 1) != WHOLE)
    if below == above:
        return -1.0
    if below:
        # the tops of the two columns' surfaces (a part-covered end pixel is covered
        # from below)
        y_ce = r0 - 1.5 + covered(ebuf, ce, r0 - 1)
        y_cs = r1 + 0.5 + covered(ebuf, cs, r1 + 1)
        return (j - y_ce) / (y_cs - y_ce)
    y_ce = r1 + 1.5 - covered(ebuf, ce, r1 + 1)
    y_cs = r0 - 0.5 - covered(ebuf, cs, r0 - 1)
    return (y_ce - j) / (y_ce - y_cs)


@ngjit_inline
def _channels(p):
    """(r, g, b) in [0, 1] of a pixel's uint32 (_rgba32's byte order)."""
    if LITTLE_ENDIAN:
        r, g, b = p, p >> np.uint32(8), p >> np.uint32(16)
    else:
        r, g, b = p >> np.uint32(24), p >> np.uint32(16), p >> np.uint32(8)
    m = np.uint32(255)
    return (r & m) / 255.0, (g & m) / 255.0, (b & m) / 255.0


@ngjit_inline
def _over(r, g, b, cov, background):
    """An opaque colour covering cov of the pixel over the background (straight alpha,
    as shade.pixel_rgba)."""
    bga = background[3] / 255.0
    a = cov + (1.0 - cov) * bga
    if a <= 0.0:
        return _rgba32(background[0], background[1], background[2], 0)
    rest = (1.0 - cov) * bga / 255.0
    return _rgba32(min((cov * r + rest * background[0]) / a, 1.0) * 255.0 + 0.5,
                   min((cov * g + rest * background[1]) / a, 1.0) * 255.0 + 0.5,
                   min((cov * b + rest * background[2]) / a, 1.0) * 255.0 + 0.5,
                   a * 255.0 + 0.5)


@ngjit_inline
def _pixel(ebuf, H, W, i, j, c, left, right, prev, f_left, rgba, background):
    """Blend pixel (i, c) of the picture (row j from the bottom) with the silhouettes
    on its left and right (where the side plane changes); prev is the original colour
    of pixel c - 1, f_left the crossing between c - 1 and c if known (else NaN).
    Returns pixel c's original colour and the crossing between c and c + 1 (NaN if
    none was computed)."""
    here = rgba[i, c]
    state = pixel_state(ebuf, c, j)
    f_right = np.nan
    if state == WHOLE:
        cl = 1.0
        cr = 1.0
        if left and pixel_state(ebuf, c - 1, j) == EMPTY:
            f = f_left if f_left == f_left else crossing(ebuf, H, c, c - 1, j)
            if f > 0.5:
                cl = 1.5 - f
        if right and pixel_state(ebuf, c + 1, j) == EMPTY:
            f = f_right = crossing(ebuf, H, c, c + 1, j)
            if f > 0.5:
                cr = 1.5 - f
        cov = cl + cr - 1.0
        if cov < 1.0:
            r, g, b = _channels(here)
            rgba[i, c] = _over(r, g, b, max(cov, 0.0), background)
    elif state == EMPTY:                  # finish_kernel's background
        cl = 0.0
        cr = 0.0
        r = 0.0
        g = 0.0
        b = 0.0
        if left and pixel_state(ebuf, c - 1, j) == WHOLE:
            f = f_left if f_left == f_left else crossing(ebuf, H, c - 1, c, j)
            if 0.0 <= f < 0.5:
                cl = 0.5 - f
                pr, pg, pb = _channels(prev)
                r += cl * pr
                g += cl * pg
                b += cl * pb
        if right and pixel_state(ebuf, c + 1, j) == WHOLE:
            f = f_right = crossing(ebuf, H, c + 1, c, j)
            if 0.0 <= f < 0.5:
                cr = 0.5 - f
                pr, pg, pb = _channels(rgba[i, c + 1])
                r += cr * pr
                g += cr * pg
                b += cr * pb
        cov = cl + cr
        if cov > 0.0:
            rgba[i, c] = _over(r / cov, g / cov, b / cov, min(cov, 1.0), background)
    return here, f_right


@ngjit_parallel_nrt_free
def silhouette_kernel(ebuf, side, words, background, rgba):
    """Blend the staircases of steep silhouettes against the background into rgba
    (an (H, W, 4) uint8 picture viewed as (H, W) uint32, finish_kernel's), from the
    tiled edge buffer ebuf and finish_kernel's side plane (H, W), top row first;
    ``words`` is the side plane's bytes read 8 at a time (the first H W // 8 of them:
    a run of 8 pixels with no change of side = 0 and no change at either end is
    skipped in one test). The module's docstring says how."""
    H, W = side.shape
    n_words = words.shape[0]
    for i in prange(H):
        j = H - 1 - i
        base = i * W
        prev = rgba[i, 0]
        prev_c = -1                       # the pixel whose original colour prev is,
        f_prev = np.nan                   # and the crossing on its right
        c = 0
        while c < W:
            k = base + c
            if (k & 7) == 0 and c + 8 <= W and (k >> 3) < n_words:
                w = words[k >> 3]
                m = (((w & LOW7) + LOW7) | w) & HIGH
                if m == 0 or m == HIGH:
                    nz = m != 0
                    if (c == 0 or (side[i, c - 1] != 0) == nz) and \
                            (c + 8 == W or (side[i, c + 8] != 0) == nz):
                        c += 8
                        continue
            s_here = side[i, c] != 0
            left = c > 0 and (side[i, c - 1] != 0) != s_here
            right = c < W - 1 and (side[i, c + 1] != 0) != s_here
            if left or right:
                if prev_c != c - 1:
                    prev = rgba[i, max(c - 1, 0)]     # not blended: as it was
                    f_prev = np.nan
                prev, f_prev = _pixel(ebuf, H, W, i, j, c, left, right, prev, f_prev, rgba,
                                      background)
                prev_c = c
            c += 1

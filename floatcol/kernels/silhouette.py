"""Antialiasing across columns at steep edges, from the columns' own ends (section 6.4).

Coverage antialiasing along a column (column.py, coverage.py) blends the pixel where a
column's run of surface ends. Where an edge is steeper than a pixel row per column, the
run ends of neighbouring columns lie rows apart, and the pixels between them show one
thing in one column and another in the next: a staircase. Such an edge is a silhouette
against the background, or a boundary between the two sides of the surface (the lower
side of a fold in front of the upper side behind it, say). Sub-columns (antialias=2-4)
average the staircases away at 2-4 times the cost. This pass instead reads where the
edge crosses each of the two columns, at the run ends (at the float rows that the
coverages of the runs' end pixels give against the background; at an end pixel's
centre between sides), and takes the edge as the straight line between them: each
pixel of the staircase is then covered by the part of it on each side of that line
(Wu's antialiased lines, with the ends known to a fraction of a pixel).

Each pixel is of a kind: empty, upper side or lower side, whole (one surface covers
all of it), or part (coverage.py blends it already). A pair of neighbouring pixels in a
row, both whole or empty and of different kinds, lies on a run of rows r0..r1 where the
two columns keep their kinds. One of them is the edge's near side, cs (a surface over
the background; the nearer of two surfaces); the other, ce. The edge is either

- below: the near side lies under it; ce shows the near side's kind (or a part pixel)
  just below the run (row r0 - 1) and cs shows another just above it (row r1 + 1);
- or above: mirrored.

At row j of the run the edge crosses the row's centre line a fraction f = (j - y_ce) /
(y_cs - y_ce) of the way from ce's centre to cs's, y_ce and y_cs where the edge crosses
the two columns. Pixel cs takes 1.5 - f of its own colour and the rest of ce's where f >
1/2; pixel ce takes 1/2 - f of cs's colour where f < 1/2 (premultiplied by alpha, so
against the background it is coverage). A run longer than SIL_SCAN rows (an edge within
2 degrees of vertical), one that reaches the picture's edge, and one whose ends say
neither (a notch) are left as they are. Silhouettes of a surface over another part of
the same side are not seen here (the side plane does not change there): the edge
surfaces of the coverage pass blend those along the columns.

Only rgba changes. Blocks of SIL_ROWS rows are the parallel iterations; a block keeps,
per pair of columns, the run and line it found last, so a run's rows in the block find
them once. Each block writes only its own rows, reading the original colour of a
neighbour it has changed from a local: the picture is the same for any number of
threads.
"""
import numpy as np
from numba import prange

from ._jit import function_type, kernel_calling, ngjit, ngjit_inline
from .coverage import coverages, flagged, seen_side
from .layout import E_COV, E_COV0, E_FLAG, E_SEEN, G_DEPTH
from .shade import LITTLE_ENDIAN, _rgba32, spread, spread_stride

#: the longest staircase step (rows) whose edge is placed
SIL_SCAN = 32
#: rows per parallel block
SIL_ROWS = 32
#: a kept coverage at least this is whole (a float32 a little under 1 rounds to 255)
FULL = 1.0 - 1.0 / 512.0
# pixel kinds
PART = -1
EMPTY = 0
UPPER = 1
LOWER = 2
#: 8 bytes of the side plane at once: each byte equal to the first
BYTES = np.uint64(0x0101010101010101)


@ngjit_inline
def pixel_kind(ebuf, c, j):
    """PART, EMPTY, UPPER or LOWER: what covers pixel row j (from the bottom) of column
    c, from the tiled edge buffer alone (layout.py, coverage.py); UPPER and LOWER are
    whole pixels of that side."""
    T = ebuf.shape[3]
    x = ebuf[c // T, E_SEEN, j, c % T]
    if x == 0.0:
        return EMPTY
    if not flagged(x):
        return UPPER if x > 0.0 else LOWER
    if ebuf[c // T, E_COV, j, c % T] > 0.0:
        return PART
    s = x - E_FLAG
    if s == 0.0:
        return EMPTY
    if ebuf[c // T, E_COV0, j, c % T] >= FULL:
        return UPPER if s > 0.0 else LOWER
    return PART


@ngjit_inline
def covered(ebuf, c, j):
    """The part of pixel row j of column c that surfaces cover: the centre's surface
    (where one is seen there) and the edge surface (coverage.py's planes)."""
    T = ebuf.shape[3]
    cov0, cov = coverages(ebuf[c // T, :, :, c % T], j)
    if seen_side(ebuf[c // T, E_SEEN, j, c % T]) != 0.0:
        cov += cov0
    return min(max(cov, 0.0), 1.0)


@ngjit_inline
def _crossing_row(ebuf, c, r, kind, ks, background, near_below):
    """The row where the edge crosses column c at its run's end pixel r (of kind
    ``kind``; the near side's is ks), the near side below the crossing or above it:
    the pixel's top or bottom; for a part pixel, against the background where its
    coverage ends, between sides its centre."""
    if kind == PART:
        if not background:
            return float(r)
        cv = covered(ebuf, c, r)
        return r - 0.5 + cv if near_below else r + 0.5 - cv
    if (kind == ks) == near_below:
        return r + 0.5
    return r - 0.5


@ngjit_inline
def edge_line(ebuf, H, cs, ce, j, ks, ke):
    """(r0, r1, a, b): the run of rows r0..r1 around j where column cs is of kind ks
    and ce of kind ke, and the edge's crossing f = a j' + b at its rows j' (the
    module's docstring); a = b = NaN where the run's ends do not place the edge, and
    r0 = r1 = j where the run is longer than SIL_SCAN."""
    r0 = j
    n = 0
    while r0 > 0 and n < SIL_SCAN:
        if pixel_kind(ebuf, cs, r0 - 1) != ks or pixel_kind(ebuf, ce, r0 - 1) != ke:
            break
        r0 -= 1
        n += 1
    r1 = j
    m = 0
    while r1 < H - 1 and m < SIL_SCAN:
        if pixel_kind(ebuf, cs, r1 + 1) != ks or pixel_kind(ebuf, ce, r1 + 1) != ke:
            break
        r1 += 1
        m += 1
    if n == SIL_SCAN or m == SIL_SCAN:
        return j, j, np.nan, np.nan
    if r0 == 0 or r1 == H - 1:
        return r0, r1, np.nan, np.nan
    ce_lo = pixel_kind(ebuf, ce, r0 - 1)
    cs_lo = pixel_kind(ebuf, cs, r0 - 1)
    ce_hi = pixel_kind(ebuf, ce, r1 + 1)
    cs_hi = pixel_kind(ebuf, cs, r1 + 1)
    below = (ce_lo == ks or ce_lo == PART) and cs_hi != ks     # the near side under it
    above = (ce_hi == ks or ce_hi == PART) and cs_lo != ks
    if below == above:
        return r0, r1, np.nan, np.nan
    bg = ke == EMPTY
    if below:
        y_ce = _crossing_row(ebuf, ce, r0 - 1, ce_lo, ks, bg, True)
        y_cs = _crossing_row(ebuf, cs, r1 + 1, cs_hi, ks, bg, True)
    else:
        y_ce = _crossing_row(ebuf, ce, r1 + 1, ce_hi, ks, bg, False)
        y_cs = _crossing_row(ebuf, cs, r0 - 1, cs_lo, ks, bg, False)
    a = 1.0 / (y_cs - y_ce)
    return r0, r1, a, -y_ce * a


@ngjit_inline
def _pair_crossing(ebuf, gbuf, H, j, p, lo, hi, near, la, lb):
    """(f, near column) of the pair of pixel columns p, p + 1 at row j, or (NaN, -1)
    where they are not a staircase's pair (the module's docstring); the block's
    arrays lo, hi, near, la, lb keep the pair's last run and line."""
    if lo[p] <= j <= hi[p]:                       # the run found before: same kinds
        return la[p] * j + lb[p], near[p]
    k0 = pixel_kind(ebuf, p, j)
    k1 = pixel_kind(ebuf, p + 1, j)
    if k0 == PART or k1 == PART or k0 == k1:
        return np.nan, -1
    if k1 == EMPTY:
        cs = p
    elif k0 == EMPTY:
        cs = p + 1
    else:                                         # two sides: the nearer is in front
        T = gbuf.shape[2]
        d0 = gbuf[p // T, j, p % T, G_DEPTH]
        d1 = gbuf[(p + 1) // T, j, (p + 1) % T, G_DEPTH]
        cs = p if d0 <= d1 else p + 1
    ce = 2 * p + 1 - cs
    r0, r1, a, b = edge_line(ebuf, H, cs, ce, j, k0 if cs == p else k1, k1 if cs == p else k0)
    lo[p] = r0
    hi[p] = r1
    near[p] = cs
    la[p] = a
    lb[p] = b
    return a * j + b, cs


@ngjit_inline
def _weight(f, this_is_near):
    """The part of a pixel that its neighbour's colour takes, f the edge's crossing."""
    if not f >= 0.0:                              # NaN or -1: no edge placed
        return 0.0
    if this_is_near:
        return f - 0.5 if f > 0.5 else 0.0
    return 0.5 - f if f < 0.5 else 0.0


@ngjit_inline
def _unpack(p):
    """(r, g, b, a) in [0, 1] of a pixel's uint32 (_rgba32's byte order)."""
    m = np.uint32(255)
    if LITTLE_ENDIAN:
        return ((p & m) / 255.0, ((p >> np.uint32(8)) & m) / 255.0,
                ((p >> np.uint32(16)) & m) / 255.0, (p >> np.uint32(24)) / 255.0)
    return ((p >> np.uint32(24)) / 255.0, ((p >> np.uint32(16)) & m) / 255.0,
            ((p >> np.uint32(8)) & m) / 255.0, (p & m) / 255.0)


@ngjit_inline
def _add(r, g, b, a, w, p):
    """The premultiplied sums (r, g, b, a) plus part w of the pixel p."""
    r2, g2, b2, a2 = _unpack(p)
    wa = w * a2
    return r + wa * r2, g + wa * g2, b + wa * b2, a + wa


@ngjit_inline
def _blend(here, wl, left, wr, right):
    """The pixel ``here`` with parts wl and wr of it taken by the colours left and
    right, mixed premultiplied by alpha (uint32 pixels, straight alpha)."""
    tot = wl + wr
    if tot > 1.0:
        wl /= tot
        wr /= tot
        tot = 1.0
    r, g, b, a = _add(0.0, 0.0, 0.0, 0.0, 1.0 - tot, here)
    if wl > 0.0:
        r, g, b, a = _add(r, g, b, a, wl, left)
    if wr > 0.0:
        r, g, b, a = _add(r, g, b, a, wr, right)
    if a <= 0.0:
        return here
    return _rgba32(min(r / a, 1.0) * 255.0 + 0.5, min(g / a, 1.0) * 255.0 + 0.5,
                   min(b / a, 1.0) * 255.0 + 0.5, min(a, 1.0) * 255.0 + 0.5)


@ngjit
def silhouette_block(blk, ebuf, gbuf, side, words, rgba):
    """silhouette_kernel's block number blk (rows blk SIL_ROWS to (blk + 1) SIL_ROWS - 1,
    top row first), with its own scratch; the kernel calls it through its address
    (_jit.kernel_calling: compiled once, not again in each of the kernel's libraries)."""
    H, W = side.shape
    n_words = words.shape[0]
    # per pair of columns (p, p + 1): the rows, near column and line of the run
    # found last in this block
    n_pairs = max(W - 1, 1)
    lo = np.full(n_pairs, H, dtype=np.int64)       # none yet: lo > hi
    hi = np.zeros(n_pairs, dtype=np.int64)
    near = np.zeros(n_pairs, dtype=np.int64)
    la = np.zeros(n_pairs)
    lb = np.zeros(n_pairs)
    for i in range(blk * SIL_ROWS, min(H, (blk + 1) * SIL_ROWS)):
        j = H - 1 - i
        base = i * W
        prev = rgba[i, 0]
        prev_c = -1                           # the pixel whose original colour is prev
        c = 0
        while c < W:
            k = base + c
            if (k & 7) == 0 and c + 8 <= W and (k >> 3) < n_words:
                w = words[k >> 3]
                if w == (w & np.uint64(255)) * BYTES:         # 8 pixels of one side
                    s0 = side[i, c]
                    if (c == 0 or side[i, c - 1] == s0) and \
                            (c + 8 == W or side[i, c + 8] == s0):
                        c += 8
                        continue
            s_here = side[i, c]
            left = c > 0 and side[i, c - 1] != s_here
            right = c < W - 1 and side[i, c + 1] != s_here
            if left or right:
                if prev_c != c - 1:
                    prev = rgba[i, max(c - 1, 0)]            # not blended: as it was
                here = rgba[i, c]
                wl = 0.0
                wr = 0.0
                if left:
                    f, cs = _pair_crossing(ebuf, gbuf, H, j, c - 1, lo, hi, near, la, lb)
                    wl = _weight(f, cs == c)
                if right:
                    f, cs = _pair_crossing(ebuf, gbuf, H, j, c, lo, hi, near, la, lb)
                    wr = _weight(f, cs == c)
                if wl > 0.0 or wr > 0.0:
                    rgba[i, c] = _blend(here, wl, prev, wr, rgba[i, c + 1] if right else here)
                prev = here
                prev_c = c
            c += 1


def _silhouette_functions(ebuf, gbuf, side, words, rgba):
    """silhouette_kernel's jitted function: silhouette_block (_jit.kernel_calling)."""
    return ((silhouette_block, function_type(silhouette_block, np.int64(0), ebuf, gbuf, side,
                                             words, rgba)),)


@kernel_calling(_silhouette_functions, (silhouette_block,))
def silhouette_kernel(ebuf, gbuf, side, words, rgba, block):
    """Blend the staircases of steep edges in rgba (an (H, W, 4) uint8 picture viewed
    as (H, W) uint32, finish_kernel's), from the tiled edge buffer ebuf, the tiled
    G-buffer gbuf (depths, to tell the near side) and finish_kernel's side plane
    (H, W), top row first; ``words`` is the side plane's bytes read 8 at a time (its
    first H W // 8: a run of 8 pixels of one side, with the same side on both ends,
    is passed in one test). The module's docstring says how. ``block``:
    silhouette_block as a function value (_jit.kernel_calling; the launch passes it)."""
    n_blocks = -(-side.shape[0] // SIL_ROWS)
    stride = spread_stride(n_blocks)            # (blocks from all over on each thread)
    for blk_ in prange(n_blocks):
        block(spread(np.int64(blk_), n_blocks, stride), ebuf, gbuf, side, words, rgba)

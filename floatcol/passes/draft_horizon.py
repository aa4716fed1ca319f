"""A fresh install's line drawing (``method="horizon"``) in numpy, while the kernels
compile (floatcol/warmup.py): Gordon's modified floating horizon (App. A.1) as
kernels/horizon.py draws it, on the draft's samples (passes/draft.py).

The draft samples the line drawing's planes (geometry.horizon_planes: every
``hstride``-th of them a line) for a block of columns at once; each column's record
of line k is what the column pass writes (kernels/column.py H_*): the line's screen
row on its plane, the column's floating interval [ymin, ymax] over the run before it
(+inf, -inf where the line's sample opens a run) and the t where that run began.
A line is the polyline through its rows in neighbouring columns; column c draws the
half of each segment that lies in it, at the pixels outside its floating interval
and not covered by a nearer run (horizon_kernel's _mark), each pixel taking the last
line the kernel would have written there. What the draft leaves out is the kernels':
the corrections of section 5 (the floating interval from the samples alone).
"""
from __future__ import annotations

import math

import numpy as np

from .. import color
from ..kernels import layout as L
from ..kernels.column import H_HI, H_LO, H_SIZE, H_TS, H_Y
from .geometry import check_bytes, too_large

#: Bytes a pixel of a line drawing's draft holds at most at once (draft.DRAFT_BYTES's
#: G-buffer and picture, the line planes)
LINE_BYTES = 96
#: Pixels marked at once (the columns go in groups of about this many marks)
MARKS = 1 << 22


def horizon_records(smp, pair, t, hstride, out, index):
    """Write the horizon records of one pass over a block of columns into ``out`` (m,
    lines, H_SIZE; a split view's two passes write lines of their own): from the
    draft's samples ``smp`` on planes ``t`` (n,) and its ``pair`` (draft._samples'),
    ``index`` each plane's number on the grid (draft.halves', -1 at a pass's ends),
    line l on plane number l hstride, as column.py's _column_pass records it: its row
    (NaN where that plane's sample is not on the surface), the run's floating interval
    before it and the run's first t."""
    y, ok, edge, tt = smp["y"], smp["ok"], smp["edge"], smp["t"]
    n, m = y.shape
    nh = out.shape[1]
    lo = np.full(m, np.inf)
    hi = np.full(m, -np.inf)
    start = np.full(m, np.nan)
    for k in range(n):
        if k > 0:                        # the run goes on from the sample before, or not
            on = pair[k - 1]
            lo = np.where(on, lo, np.inf)
            hi = np.where(on, hi, -np.inf)
            start = np.where(on, start, tt[k])
        else:
            start = tt[0].copy()
        g = int(index[k])
        if g >= 0 and g % hstride == 0 and g // hstride < nh:
            # a line where the plane's own sample is on the surface (not a run's end
            # bisected into its place, nor an orthographic plane clipped to the domain)
            line = ok[k] & ~edge[k] & (tt[k] == t[k])
            rec = out[:, g // hstride]
            rec[:, H_Y] = np.where(line, y[k], np.nan)
            rec[:, H_LO] = lo
            rec[:, H_HI] = hi
            rec[:, H_TS] = start
        lo = np.where(ok[k], np.fmin(lo, y[k]), lo)
        hi = np.where(ok[k], np.fmax(hi, y[k]), hi)


def _marks(hrec, cols, H):
    """Every pixel kernels/horizon.py's horizon_kernel tries to mark in columns
    ``cols``: (column, row from the bottom, the row's exact height, line index), in
    the order the kernel marks them (line by line; its own row, then the half
    segments toward the columns on the left and on the right)."""
    W, nh = hrec.shape[:2]
    yc = hrec[cols, :, H_Y]                                  # (m, nh)
    out = []
    jc = np.floor(yc + 0.5)
    own = np.isfinite(yc)
    c, k = np.nonzero(own)
    # (a row far beyond the picture marks nothing: clipped before it becomes an int)
    out.append((cols[c], np.clip(jc[c, k], -1.0, H), yc[c, k], k,
                np.zeros(c.size, dtype=np.int64), np.zeros(c.size, dtype=np.int64)))
    for part, dc in ((1, -1), (2, 1)):
        nb = cols + dc
        inside = (nb >= 0) & (nb < W)
        yn = np.full(yc.shape, np.nan)
        yn[inside] = hrec[nb[inside], :, H_Y]
        both = own & np.isfinite(yn)
        c, k = np.nonzero(both)
        a, b = jc[c, k], np.floor(0.5 * (yc[c, k] + yn[c, k]) + 0.5)
        step = np.where(b > a, 1.0, -1.0)
        # rows beyond the picture mark nothing: only those inside are walked
        first = np.where(step > 0, np.maximum(a + 1.0, -1.0), np.minimum(a - 1.0, H))
        last = np.where(step > 0, np.minimum(b, H), np.maximum(b, -1.0))
        cnt = np.maximum((last - first) * step + 1.0, 0.0).astype(np.int64)
        e = np.repeat(np.arange(c.size), cnt)
        i = np.arange(e.size) - np.repeat(np.cumsum(cnt) - cnt, cnt)
        j = first[e] + step[e] * i
        out.append((cols[c][e], j, j, k[e], np.full(e.size, part, dtype=np.int64), i))
    cc, jj, yy, kk, pp, ii = (np.concatenate(x) for x in zip(*out))
    order = np.lexsort((ii, pp, kk, cc))
    return cc[order], jj[order].astype(np.int64), yy[order], kk[order]


def _mark(hrec, cols, g_t, seen, view, hstride, lines, line_t):
    """horizon_kernel's marks of columns ``cols`` into lines and line_t (W, H), rows
    from the bottom, with the draft's t and seen pixels (H, W), rows from the bottom:
    the last mark the kernel would write at a pixel wins."""
    W, H = lines.shape
    c, j, y, k = _marks(hrec, cols, H)
    keep = (j >= 0) & (j < H)
    c, j, y, k = c[keep], j[keep], y[keep], k[keep]
    rec = hrec[c, k]
    t0 = view.t_range[0]
    tk = t0 + k * hstride * view.step
    t_view = -math.inf if view.orthographic else -view.d3 * math.cos(view.alpha)
    sigma = np.where(tk >= t_view, 1, -1)
    side = np.where(y > rec[:, H_HI], sigma, np.where(y < rec[:, H_LO], -sigma, 0))
    # covered by a nearer, earlier run of the column
    covered = seen[j, c] & (sigma * (g_t[j, c] - rec[:, H_TS]) < -1e-12)
    keep = (side != 0) & ~covered
    pix = (c * H + j)[keep]
    last = pix.size - 1 - np.unique(pix[::-1], return_index=True)[1]
    lines.ravel()[pix[last]] = side[keep][last]
    line_t.ravel()[pix[last]] = tk[keep][last]


def draft_line_pass(surface, view, hstride, n_lines, background):
    """The draft of a line drawing on the planes of ``view`` (horizon_planes'):
    horizon.line_pass's (rgba, side, intensity, depth, seen, line_t), top row first,
    with the tiled G-buffer and the evaluations per column."""
    from .draft import draft_geometry, tiled
    W, H = view.width, view.height
    check_bytes(W, H, W * H * LINE_BYTES + W * n_lines * H_SIZE * 8)
    hrec = np.empty((W, n_lines, H_SIZE))
    hrec[..., H_Y] = np.nan
    try:
        g, seen, evals = draft_geometry(surface, view, hrec, hstride)
    except MemoryError:
        raise ValueError(too_large(W, H, W * H * LINE_BYTES)) from None
    lines = np.zeros((W, H), dtype=np.int8)
    lt = np.full((W, H), np.nan, dtype=np.float32)
    g_t = g[..., L.G_T].astype(np.float64)
    # groups of columns whose marks fit in MARKS (a line's half segments span at most
    # the picture's rows)
    spread = np.abs(np.diff(np.nan_to_num(hrec[..., H_Y], nan=0.0), axis=0)).clip(0, H)
    per_col = n_lines + spread.sum(axis=1).mean() if W > 1 else n_lines
    group = max(1, int(MARKS // max(per_col, 1.0)))
    for c0 in range(0, W, group):
        _mark(hrec, np.arange(c0, min(W, c0 + group)), g_t, seen, view, hstride, lines, lt)
    line_t = np.ascontiguousarray(lt[:, ::-1].T)
    side = np.ascontiguousarray(lines[:, ::-1].T)
    on = side != 0
    intensity = np.where(on, np.float32(1.0), np.float32(np.nan)).astype(np.float32)
    seen_top = seen[::-1]
    depth = np.where(on & seen_top, g[::-1, :, L.G_DEPTH], np.inf).astype(np.float32)
    rgba = color.line_rgba(side, background=background)
    return rgba, side, intensity, depth, seen_top, line_t, tiled(g), evals

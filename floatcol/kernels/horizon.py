"""The monochrome modified floating horizon, App. A.1, in independent column mode.

The column pass (column.py) samples every column densely and records, for each
horizon line k (every ``hstride``-th sampling plane), the line's screen row in that
column and the column's floating interval [ymin, ymax] just before it. A line is
then the polyline through its rows in neighbouring columns, as in A.1's
Line(col-1, ., col, .), and column c draws the half of each segment that lies in
column c, keeping only the pixels outside column c's floating interval: this is
A.1's visibility test, and its "partial line" to the horizon falls out of the same
test. Pixels painted by an earlier run of the column (before a hole) hide the line
too. Each column writes only its own pixels, so columns run in parallel.
"""
import math
import numpy as np

from numba import prange

from ._jit import ngjit, ngjit_parallel
from .index import floor_index
from .column import H_HI, H_LO, H_TS, H_Y
from .coverage import seen_side
from .layout import E_SEEN, G_T, VP_CA, VP_D3, VP_DT, VP_ORTHO, VP_T0


@ngjit
def _mark(lines, line_t, gcol, ecol, c, j, rec, sigma, exact_y, tk):
    H = gcol.shape[0]
    if j < 0 or j >= H:
        return
    y = exact_y
    if y > rec[H_HI]:
        side = sigma
    elif y < rec[H_LO]:
        side = -sigma
    else:
        return                              # inside the floating interval: hidden
    if seen_side(ecol[E_SEEN, j]) != 0.0 and sigma * (gcol[j, G_T] - rec[H_TS]) < -1e-12:
        return                              # covered by a nearer, earlier run
    lines[c, j] = side
    line_t[c, j] = tk


@ngjit_parallel
def horizon_kernel(hrec, gbuf, ebuf, vp, hstride, lines, line_t):
    """gbuf and ebuf: the column pass's tiled buffers (layout.py).
    lines (W, H) int8 receives +1 / -1 (upper / lower side) on line pixels, and
    line_t the t of the sampling plane each line pixel belongs to."""
    W = hrec.shape[0]
    nh = hrec.shape[1]
    t0 = vp[VP_T0]
    dt = vp[VP_DT]
    t_view = -math.inf if vp[VP_ORTHO] != 0.0 else -vp[VP_D3] * vp[VP_CA]
    T = gbuf.shape[2]
    H = gbuf.shape[1]
    for c_ in prange(W):
        c = np.int64(c_)  # (_jit.py: prange_index)
        gcol = gbuf[c // T, :, c % T]
        ecol = ebuf[c // T, :, :, c % T]
        for k in range(nh):
            rec = hrec[c, k]
            yc = rec[H_Y]
            if not math.isfinite(yc):
                continue
            tk = t0 + k * hstride * dt
            sigma = 1.0 if tk >= t_view else -1.0
            jc = floor_index(yc + 0.5)
            _mark(lines, line_t, gcol, ecol, c, jc, rec, sigma, yc, tk)
            for nb in (c - 1, c + 1):
                if nb < 0 or nb >= W:
                    continue
                yn = hrec[nb, k, H_Y]
                if not math.isfinite(yn):
                    continue
                jm = floor_index(0.5 * (yc + yn) + 0.5)
                step = 1 if jm > jc else -1
                j = jc + step
                # rows beyond the picture mark nothing: walk only those inside (a
                # pole's rows reach 1e15, which took hours)
                if step > 0:
                    j = max(j, -1)
                    jm = min(jm, H)
                else:
                    j = min(j, H)
                    jm = max(jm, -1)
                while (j - jm) * step <= 0:
                    _mark(lines, line_t, gcol, ecol, c, j, rec, sigma, float(j), tk)
                    j += step

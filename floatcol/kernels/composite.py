"""Several opaque layers of one camera merged per pixel by depth (passes/composite.py).

Per pixel, the layers in order of the depth of the surface at the pixel's centre
(stable: equal depths keep the layers' order; no surface there: +inf), each over what
the nearer ones leave: its alpha times (1 - hidden), where ``hidden`` grows by what a
layer covers (its alpha, or all of the pixel where its surface is at the centre), over
the background. The arithmetic is numpy's of the pass before it, value for value.
"""
import numpy as np
from numba import prange

from ._jit import ngjit_parallel


@ngjit_parallel
def composite_kernel(depth, rgba, seen, bg, out, which):
    """depth (n, H, W) float64 (+inf where a layer's surface is not at the centre),
    rgba (n, H, W, 4) uint8 straight alpha, seen (n, H, W) bool, bg (4,) in [0, 1]:
    out (H, W, 4) uint8, which (H, W) int8 (the nearest layer, -1: none)."""
    n = depth.shape[0]
    H = depth.shape[1]
    W = depth.shape[2]
    for i in prange(H):
        order = np.empty(n, dtype=np.int64)
        for c in range(W):
            for k in range(n):                       # a stable insertion sort by depth
                m = k
                while m > 0 and depth[order[m - 1], i, c] > depth[k, i, c]:
                    order[m] = order[m - 1]
                    m -= 1
                order[m] = k
            r = 0.0
            g = 0.0
            b = 0.0
            acc_a = 0.0
            hidden = 0.0
            for k in range(n):
                s = order[k]
                la = rgba[s, i, c, 3] / 255.0
                a = la * (1.0 - hidden)
                r += rgba[s, i, c, 0] / 255.0 * a
                g += rgba[s, i, c, 1] / 255.0 * a
                b += rgba[s, i, c, 2] / 255.0 * a
                acc_a += a
                hidden += (1.0 - hidden) * max(la, 1.0 if seen[s, i, c] else 0.0)
            rest = (1.0 - acc_a) * bg[3]
            alpha = acc_a + rest
            q = alpha if alpha > 0 else 1.0
            out[i, c, 0] = np.uint8(min(max(round((r + rest * bg[0]) / q * 255.0), 0), 255))
            out[i, c, 1] = np.uint8(min(max(round((g + rest * bg[1]) / q * 255.0), 0), 255))
            out[i, c, 2] = np.uint8(min(max(round((b + rest * bg[2]) / q * 255.0), 0), 255))
            out[i, c, 3] = np.uint8(min(max(round(alpha * 255.0), 0), 255))
            near = order[0]
            which[i, c] = near if depth[near, i, c] < np.inf else -1

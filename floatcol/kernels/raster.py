"""A z-buffer for the objects on a surface (floatcol/objects.py; Szenberg 1997):
triangles rasterised at the pixel centres against the picture's depth."""
import math

import numpy as np

from ._jit import ngjit


@ngjit
def raster_kernel(cx, cy, e, tris, rgb, ortho, d3, zbuf, rgba, drawn):
    """Draw triangles ``tris`` (m, 3) of vertices at pixel coordinates (cx, cy)
    (column, array row) and distance e along the view axis, each of colour rgb (m, 3)
    in [0, 1], where nearer than zbuf (H, W) screen z (e - d3; updated): the depth
    interpolated linearly on the screen in orthographic pictures, 1/e linearly in
    perspective (perspective-correct). rgba (H, W, 4) uint8 and drawn (H, W) uint8 are
    written where a triangle wins. Serial, in the triangles' order."""
    H, W = zbuf.shape
    for k in range(tris.shape[0]):
        i0 = tris[k, 0]
        i1 = tris[k, 1]
        i2 = tris[k, 2]
        x0, x1, x2 = cx[i0], cx[i1], cx[i2]
        y0, y1, y2 = cy[i0], cy[i1], cy[i2]
        if not (math.isfinite(x0) and math.isfinite(x1) and math.isfinite(x2)
                and math.isfinite(y0) and math.isfinite(y1) and math.isfinite(y2)):
            continue
        det = (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2)
        if det == 0.0:
            continue
        # (clamped as floats before the conversion: a float far outside an int's range
        # converts to anything in LLVM, and an object 1e50 tall wrote past the picture)
        c0 = int(min(max(math.floor(min(x0, x1, x2)), 0.0), W))
        c1 = int(max(min(math.ceil(max(x0, x1, x2)), W - 1.0), -1.0))
        r0 = int(min(max(math.floor(min(y0, y1, y2)), 0.0), H))
        r1 = int(max(min(math.ceil(max(y0, y1, y2)), H - 1.0), -1.0))
        r8 = np.uint8(min(max(round(rgb[k, 0] * 255.0), 0.0), 255.0))
        g8 = np.uint8(min(max(round(rgb[k, 1] * 255.0), 0.0), 255.0))
        b8 = np.uint8(min(max(round(rgb[k, 2] * 255.0), 0.0), 255.0))
        for r in range(r0, r1 + 1):
            for c in range(c0, c1 + 1):
                l0 = ((y1 - y2) * (c - x2) + (x2 - x1) * (r - y2)) / det
                l1 = ((y2 - y0) * (c - x2) + (x0 - x2) * (r - y2)) / det
                l2 = 1.0 - l0 - l1
                if l0 < -1e-9 or l1 < -1e-9 or l2 < -1e-9:
                    continue
                if ortho:
                    depth = l0 * e[i0] + l1 * e[i1] + l2 * e[i2]
                else:
                    depth = 1.0 / (l0 / e[i0] + l1 / e[i1] + l2 / e[i2])
                z = depth - d3
                if z < zbuf[r, c]:
                    zbuf[r, c] = z
                    rgba[r, c, 0] = r8
                    rgba[r, c, 1] = g8
                    rgba[r, c, 2] = b8
                    rgba[r, c, 3] = 255
                    drawn[r, c] = 1

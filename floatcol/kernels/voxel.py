"""Guedes, Gattass and Carvalho (1997): the voxel terrain renderers of a fly-through,
for comparison with floatcol's exact perspective (benchmarks/bench_terrain.py).

The terrain is Guedes' voxel model: each grid cell a column whose height is the
nearest grid height. The eye at height h_e (above w = 0) looks along a horizontal
forward direction f with pitch p (negative down); r is to its right. Pixel (k, j),
j from the bottom, km and jm the middle column and row, D the focal length in pixels.
In the eye's frame (x along r, y along f, z up) the exact ray of pixel (k, j) is
D (0, cos p, sin p) + (k - km) (1, 0, 0) + (j - jm) (0, -sin p, cos p). Variants:

- VX_STANDARD: a vertical view plane with the window shifted (his section 3, Alg. 1):
  the rays of column k lie in the vertical plane of direction (k - km, D), slopes
  m_j = (j - j_h)/d_pk with the horizon at row j_h = jm - D tan p, d_pk = |(k - km, D)|.
- VX_NAIVE: his 5a: each column the middle one slid along the middle row in a vertical
  plane, slopes m_j = (d_pk sin p + (j - jm) cos p) / (d_pk cos p - (j - jm) sin p).
- VX_UNCORRECTED, VX_CORRECTED: his 5b (Alg. 2): column k's tilted plane sampled
  along the lines where it meets the slices y = i, starting at P_k = (-(k - km) h_e
  sin p / D, 0) (eq. 6) in steps s_k = ((k - km) cos p / D, 1) (eq. 5), with the middle
  column's slopes for all columns; the terrain sampled at P, or at P + z c_j with c_j
  = ((k - km) sin p / D, 0) (eq. 7) where the ray's height z > 0.
- VX_BRUTE: every ray cast on its own over the voxels, a step of STEP cells.

Each writes, per pixel, the world point (u, v) of the voxel it shows (NaN: sky).
"""
import math

import numpy as np
from numba import prange

from ._jit import ngjit_inline, ngjit_parallel

VX_STANDARD = 0
VX_NAIVE = 1
VX_UNCORRECTED = 2
VX_CORRECTED = 3
VX_BRUTE = 4
#: the brute force's step along a ray, in cells (of the ray's ground track)
STEP = 0.25


@ngjit_inline
def _height(hf, ext, x, y):
    """The voxel height at world (x, y): the nearest grid height; NaN outside."""
    nv, nu = hf.shape
    gx = (x - ext[0]) / (ext[1] - ext[0]) * (nu - 1)
    gy = (y - ext[2]) / (ext[3] - ext[2]) * (nv - 1)
    if not (gx >= -0.5 and gx < nu - 0.5 and gy >= -0.5 and gy < nv - 0.5):
        return np.nan
    return hf[int(math.floor(gy + 0.5)), int(math.floor(gx + 0.5))]


@ngjit_parallel
def voxel_kernel(hf, ext, eye, fwd, variant, pitch, focal, steps, out):
    """Render out (H, W, 2) = the world (u, v) each pixel shows (NaN: sky) by a
    variant of Guedes' algorithm. ext (ua, ub, va, vb); eye (u, v, w); fwd (fu, fv)
    the unit forward direction; pitch in radians; focal D in pixels; steps the march
    length in cells; the step is a cell (the smaller side)."""
    H = out.shape[0]
    W = out.shape[1]
    nv, nu = hf.shape
    cell = min((ext[1] - ext[0]) / (nu - 1), (ext[3] - ext[2]) / (nv - 1))
    fu = fwd[0]
    fv = fwd[1]
    ru = fv                              # right of forward: (fv, -fu)
    rv = -fu
    cp = math.cos(pitch)
    sp = math.sin(pitch)
    km = 0.5 * (W - 1)
    jm = 0.5 * (H - 1)
    he = eye[2]
    for k in prange(W):
        for j in range(H):
            out[H - 1 - j, k, 0] = np.nan
            out[H - 1 - j, k, 1] = np.nan
        dk = k - km
        if variant == VX_BRUTE:
            for j in range(H):
                dj = j - jm
                hx = dk                                  # the ray's horizontal part
                hy = focal * cp - dj * sp
                vz = focal * sp + dj * cp
                lh = math.sqrt(hx * hx + hy * hy)
                if lh <= 0.0:
                    continue
                m = vz / lh
                gx = (hx * ru + hy * fu) / lh            # its ground direction (world)
                gy = (hx * rv + hy * fv) / lh
                s = STEP * cell
                while s < steps * cell:
                    x = eye[0] + s * gx
                    y = eye[1] + s * gy
                    h = _height(hf, ext, x, y)
                    if h == h and h >= he + m * s:
                        out[H - 1 - j, k, 0] = x
                        out[H - 1 - j, k, 1] = y
                        break
                    s += STEP * cell
            continue
        if variant == VX_STANDARD or variant == VX_NAIVE:
            dpk = math.sqrt(focal * focal + dk * dk)
            gx = (dk * ru + focal * fu) / dpk            # the vertical plane's direction
            gy = (dk * rv + focal * fv) / dpk
            j_h = jm - focal * math.tan(pitch)
            j = 0
            for i in range(1, steps + 1):
                x = eye[0] + i * cell * gx
                y = eye[1] + i * cell * gy
                h = _height(hf, ext, x, y)
                if h != h:
                    continue
                while j < H:
                    if variant == VX_STANDARD:
                        m = (j - j_h) / dpk                           # eq. (1)
                    else:                                              # 5a's slope
                        dj = j - jm
                        m = (dpk * sp + dj * cp) / (dpk * cp - dj * sp)
                    if not h > he + m * i * cell:
                        break
                    out[H - 1 - j, k, 0] = x
                    out[H - 1 - j, k, 1] = y
                    j += 1
                if j >= H:
                    break
            continue
        # section 5b: the tilted plane of column k, slices y = i (local frame)
        sx = dk * cp / focal                             # eq. (5): s_k = (sx, 1)
        px0 = -dk * he * sp / focal                      # eq. (6): P_k = (px0, 0)
        cx = dk * sp / focal                             # eq. (7): c_j = (cx, 0)
        j = 0
        for i in range(1, steps + 1):
            ly = i * cell
            lx = px0 + sx * ly
            while j < H:
                dj = j - jm
                m = (focal * sp + dj * cp) / (focal * cp - dj * sp)   # the middle column's
                z = he + m * ly
                qx = lx
                if variant == VX_CORRECTED and z > 0.0:
                    qx = lx + z * cx
                x = eye[0] + qx * ru + ly * fu
                y = eye[1] + qx * rv + ly * fv
                h = _height(hf, ext, x, y)
                if not h > z:
                    break
                out[H - 1 - j, k, 0] = x
                out[H - 1 - j, k, 1] = y
                j += 1
            if j >= H:
                break

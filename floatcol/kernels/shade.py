"""Per-pixel lighting of the G-buffer (after the column pass)."""
import math

import numpy as np
from numba import prange

from ._jit import ngjit_parallel
from .layout import (
    G_DEPTH, G_I, G_NX, G_NY, G_NZ, G_SIDE, G_W, VP_D1, VP_D3, VP_H, VP_LX, VP_LY, VP_LZ,
    VP_ORTHO, VP_SCALE, VP_W,
)

INTERP_INTENSITY = 0   # the paper's iis (Gouraud): lit at the samples, interpolated
INTERP_NORMAL = 1      # nis: the normal is interpolated and lit at each pixel


@ngjit_parallel
def shade_kernel(gbuf, vp, interp, ambient, specular, shininess, out, spec_out):
    """out (W, H) float32: I = ambient + (1 - ambient) |L.N| / (|L| |N|) in [0, 1],
    NaN where nothing is seen. The light is vp's directional light, or the viewpoint
    when that is zero (the exact reference model, eq. 12); the surface is two-sided.

    spec_out (W, H) float32: Phong's specular term specular * max(R.V, 0)^shininess
    (the paper has none), with V toward the viewpoint, N turned toward the viewer
    (the side that is seen) and R the reflection of L about N; zero where the light
    is behind the seen side. It uses the per-pixel normal in both interpolations.
    """
    W = gbuf.shape[0]
    H = gbuf.shape[1]
    ortho = vp[VP_ORTHO] != 0.0
    d1 = vp[VP_D1]
    d3 = vp[VP_D3]
    scale = vp[VP_SCALE]
    lx0 = vp[VP_LX]
    ly0 = vp[VP_LY]
    lz0 = vp[VP_LZ]
    headlight = lx0 == 0.0 and ly0 == 0.0 and lz0 == 0.0
    for c in prange(W):
        x0 = (c - (vp[VP_W] - 1.0) * 0.5) / scale
        for j in range(H):
            px = gbuf[c, j]
            if px[G_SIDE] == 0.0:
                out[c, j] = np.nan
                spec_out[c, j] = 0.0
                continue
            # V: from the seen point toward the viewpoint (orthographic: the viewer)
            if ortho:
                vx = 0.0
                vy = 0.0
                vz = -1.0
            else:
                y0 = (j - (vp[VP_H] - 1.0) * 0.5) / scale
                m = (px[G_DEPTH] + d3) / d1
                vx = -x0 * m
                vy = -y0 * m
                vz = -(px[G_DEPTH] + d3)
                vn = math.sqrt(vx * vx + vy * vy + vz * vz)
                vx /= vn
                vy /= vn
                vz /= vn
            if headlight:
                lx = vx
                ly = vy
                lz = vz
            else:
                lx = lx0
                ly = ly0
                lz = lz0
            nx = px[G_NX]
            ny = px[G_NY]
            nz = px[G_NZ]
            nn = math.sqrt(nx * nx + ny * ny + nz * nz)
            if interp == INTERP_INTENSITY:
                lam = px[G_I]
            else:
                ll = math.sqrt(lx * lx + ly * ly + lz * lz)
                lam = abs(lx * nx + ly * ny + lz * nz) / (ll * nn) if nn > 0.0 else 0.0
            out[c, j] = ambient + (1.0 - ambient) * min(lam, 1.0)
            sp = 0.0
            if specular > 0.0 and nn > 0.0:
                nx /= nn
                ny /= nn
                nz /= nn
                if nx * vx + ny * vy + nz * vz < 0.0:        # the seen side's normal
                    nx = -nx
                    ny = -ny
                    nz = -nz
                ll = math.sqrt(lx * lx + ly * ly + lz * lz)
                nl = (nx * lx + ny * ly + nz * lz) / ll
                if nl > 0.0:
                    rx = 2.0 * nl * nx - lx / ll
                    ry = 2.0 * nl * ny - ly / ll
                    rz = 2.0 * nl * nz - lz / ll
                    rv = rx * vx + ry * vy + rz * vz
                    if rv > 0.0:
                        sp = specular * rv ** shininess
            spec_out[c, j] = sp


@ngjit_parallel
def upper_w_range(gbuf, lo, hi):
    """Per column: min and max of w over pixels where the upper side is seen."""
    W = gbuf.shape[0]
    H = gbuf.shape[1]
    for c in prange(W):
        a = np.inf
        b = -np.inf
        for j in range(H):
            if gbuf[c, j, G_SIDE] > 0.0:
                w = gbuf[c, j, G_W]
                a = min(a, w)
                b = max(b, w)
        lo[c] = a
        hi[c] = b


@ngjit_parallel
def finish_kernel(gbuf, shade, spec, lut, w_lo, w_hi, lower_rgb, background,
                  intensity, side, depth, rgba):
    """Assemble the public arrays, top row first: intensity, side, depth and rgba.

    The upper side takes its colour from ``lut`` indexed by w over [w_lo, w_hi]
    (a one-row lut is a flat colour), the lower side ``lower_rgb``; both are
    multiplied by the shade, plus the white specular term ``spec``. Background
    pixels get ``background`` (uint8 RGBA).
    """
    W = gbuf.shape[0]
    H = gbuf.shape[1]
    n_lut = lut.shape[0]
    span = w_hi - w_lo if w_hi > w_lo else 1.0
    for c in prange(W):
        for j in range(H):
            i = H - 1 - j
            s = gbuf[c, j, G_SIDE]
            side[i, c] = np.int8(s)
            depth[i, c] = gbuf[c, j, G_DEPTH]
            lam = shade[c, j]
            intensity[i, c] = lam
            if s == 0.0:
                for k in range(4):
                    rgba[i, c, k] = background[k]
                continue
            if s > 0.0:
                x = (gbuf[c, j, G_W] - w_lo) / span * (n_lut - 1)
                idx = int(min(max(x, 0.0), n_lut - 1.0)) if x == x else 0
                r = lut[idx, 0]
                g = lut[idx, 1]
                b = lut[idx, 2]
            else:
                r = lower_rgb[0]
                g = lower_rgb[1]
                b = lower_rgb[2]
            sp = spec[c, j]
            rgba[i, c, 0] = np.uint8(min((r * lam + sp) * 255.0 + 0.5, 255.0))
            rgba[i, c, 1] = np.uint8(min((g * lam + sp) * 255.0 + 0.5, 255.0))
            rgba[i, c, 2] = np.uint8(min((b * lam + sp) * 255.0 + 0.5, 255.0))
            rgba[i, c, 3] = 255

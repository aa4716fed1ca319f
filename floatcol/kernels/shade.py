"""Per-pixel lighting of the G-buffer (after the column pass)."""
import math

import numpy as np
from numba import prange

from ._jit import ngjit, ngjit_parallel
from .layout import (
    E_COV, E_COV0, E_DEPTH, E_I, E_NX, E_NY, E_NZ, E_SIDE, E_W,
    G_DEPTH, G_I, G_NX, G_NY, G_NZ, G_SIDE, G_W, VP_AA, VP_D1, VP_D3, VP_H, VP_LX, VP_LY,
    VP_LZ, VP_ORTHO, VP_SCALE, VP_W, VP_XOFF,
)

INTERP_INTENSITY = 0   # the paper's iis (Gouraud): lit at the samples, interpolated
INTERP_NORMAL = 1      # nis: the normal is interpolated and lit at each pixel


@ngjit
def _light(vp, x0, j, depth, nx, ny, nz, lam_iis, interp, ambient, specular, shininess):
    """(I, specular) of one pixel: I = ambient + (1 - ambient) |L.N| / (|L| |N|), and
    Phong's specular * max(R.V, 0)^shininess (the paper has none), with V toward the
    viewpoint, N turned toward the viewer (the side that is seen) and R the
    reflection of L about N; zero where the light is behind the seen side. The light
    is vp's directional light, or the viewpoint when that is zero (eq. 12)."""
    if vp[VP_ORTHO] != 0.0:
        vx = 0.0
        vy = 0.0
        vz = -1.0
    else:
        d1 = vp[VP_D1]
        d3 = vp[VP_D3]
        y0 = (j - (vp[VP_H] - 1.0) * 0.5) / vp[VP_SCALE]
        m = (depth + d3) / d1
        vx = -x0 * m
        vy = -y0 * m
        vz = -(depth + d3)
        vn = math.sqrt(vx * vx + vy * vy + vz * vz)
        vx /= vn
        vy /= vn
        vz /= vn
    if vp[VP_LX] == 0.0 and vp[VP_LY] == 0.0 and vp[VP_LZ] == 0.0:
        lx = vx
        ly = vy
        lz = vz
    else:
        lx = vp[VP_LX]
        ly = vp[VP_LY]
        lz = vp[VP_LZ]
    nn = math.sqrt(nx * nx + ny * ny + nz * nz)
    if interp == INTERP_INTENSITY:
        lam = lam_iis
    else:
        ll = math.sqrt(lx * lx + ly * ly + lz * lz)
        lam = abs(lx * nx + ly * ny + lz * nz) / (ll * nn) if nn > 0.0 else 0.0
    inten = ambient + (1.0 - ambient) * min(lam, 1.0)
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
    return inten, sp


@ngjit_parallel
def shade_kernel(gbuf, ebuf, vp, interp, ambient, specular, shininess, out, spec_out,
                 eout, espec_out):
    """out (W, H) float32: the intensity of the surface at each pixel centre (see
    _light), NaN where nothing is seen; spec_out its specular term. With VP_AA the
    edge surfaces of ebuf are lit too, into eout / espec_out (else those may be
    (1, 1) and are not touched). Both interpolations use the per-pixel normal for the
    specular term."""
    W = gbuf.shape[0]
    H = gbuf.shape[1]
    aa = vp[VP_AA] != 0.0
    for c in prange(W):
        x0 = (c + vp[VP_XOFF] - (vp[VP_W] - 1.0) * 0.5) / vp[VP_SCALE]
        for j in range(H):
            px = gbuf[c, j]
            if px[G_SIDE] == 0.0:
                out[c, j] = np.nan
                spec_out[c, j] = 0.0
            else:
                out[c, j], spec_out[c, j] = _light(
                    vp, x0, j, px[G_DEPTH], px[G_NX], px[G_NY], px[G_NZ], px[G_I],
                    interp, ambient, specular, shininess)
            if aa:
                ex = ebuf[c, j]
                if ex[E_COV] > 0.0:
                    eout[c, j], espec_out[c, j] = _light(
                        vp, x0, j, ex[E_DEPTH], ex[E_NX], ex[E_NY], ex[E_NZ], ex[E_I],
                        interp, ambient, specular, shininess)
                else:
                    eout[c, j] = 0.0
                    espec_out[c, j] = 0.0


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


@ngjit
def _side_rgb(side, w, lut, w_lo, span, lower_rgb):
    if side > 0.0:
        n_lut = lut.shape[0]
        x = (w - w_lo) / span * (n_lut - 1)
        idx = int(min(max(x, 0.0), n_lut - 1.0)) if x == x else 0
        return lut[idx, 0], lut[idx, 1], lut[idx, 2]
    return lower_rgb[0], lower_rgb[1], lower_rgb[2]


@ngjit
def pixel_rgba(gpx, epx, aa, lam, sp, e_lam, e_sp, lut, w_lo, span, lower_rgb, background):
    """One pixel's colour (r, g, b, alpha) in [0, 1], straight alpha.

    The upper side takes its colour from ``lut`` indexed by w over [w_lo, w_lo + span]
    (a one-row lut is a flat colour), the lower side ``lower_rgb``; both multiplied by
    the shade ``lam``, plus the white specular term ``sp``. With ``aa`` (section 6.4)
    the colour is the coverage-weighted mean of the surface at the pixel's centre
    (gpx), the edge surface (epx, shaded e_lam, e_sp) and the background (uint8 RGBA).
    """
    s = gpx[G_SIDE]
    cov0 = 0.0
    r = 0.0
    g = 0.0
    b = 0.0
    if s != 0.0:
        cov0 = epx[E_COV0] if aa else 1.0
        r, g, b = _side_rgb(s, gpx[G_W], lut, w_lo, span, lower_rgb)
        r = min(r * lam + sp, 1.0)
        g = min(g * lam + sp, 1.0)
        b = min(b * lam + sp, 1.0)
    cov1 = 0.0
    if aa and epx[E_COV] > 0.0:
        cov1 = min(epx[E_COV], 1.0 - cov0)
        er, eg, eb = _side_rgb(epx[E_SIDE], epx[E_W], lut, w_lo, span, lower_rgb)
        r = r * cov0 + min(er * e_lam + e_sp, 1.0) * cov1
        g = g * cov0 + min(eg * e_lam + e_sp, 1.0) * cov1
        b = b * cov0 + min(eb * e_lam + e_sp, 1.0) * cov1
    else:
        r *= cov0
        g *= cov0
        b *= cov0
    # straight alpha over the background: the covered part is opaque surface
    bga = background[3] / 255.0
    cov = cov0 + cov1
    a = cov + (1.0 - cov) * bga
    if a <= 0.0:
        return background[0] / 255.0, background[1] / 255.0, background[2] / 255.0, 0.0
    rest = (1.0 - cov) * bga
    return (min((r + rest * background[0] / 255.0) / a, 1.0),
            min((g + rest * background[1] / 255.0) / a, 1.0),
            min((b + rest * background[2] / 255.0) / a, 1.0), a)


@ngjit_parallel
def finish_kernel(gbuf, ebuf, aa, shade, spec, eshade, espec, lut, w_lo, w_hi, lower_rgb,
                  background, intensity, side, depth, rgba):
    """Assemble the public arrays, top row first: intensity, side, depth and rgba
    (pixel_rgba; with ``aa`` only rgba is blended, intensity, side and depth stay
    those of the pixel's centre)."""
    W = gbuf.shape[0]
    H = gbuf.shape[1]
    span = w_hi - w_lo if w_hi > w_lo else 1.0
    for c in prange(W):
        for j in range(H):
            i = H - 1 - j
            s = gbuf[c, j, G_SIDE]
            side[i, c] = np.int8(s)
            depth[i, c] = gbuf[c, j, G_DEPTH]
            intensity[i, c] = shade[c, j]
            if not aa and s == 0.0:
                for k in range(4):
                    rgba[i, c, k] = background[k]
                continue
            ce = np.int64(c) if aa else np.int64(0)      # ebuf may be (1, 1, E_SIZE)
            je = np.int64(j) if aa else np.int64(0)
            r, g, b, a = pixel_rgba(gbuf[c, j], ebuf[ce, je], aa, shade[c, j], spec[c, j],
                                    eshade[ce, je], espec[ce, je], lut, w_lo, span, lower_rgb,
                                    background)
            rgba[i, c, 0] = np.uint8(r * 255.0 + 0.5)
            rgba[i, c, 1] = np.uint8(g * 255.0 + 0.5)
            rgba[i, c, 2] = np.uint8(b * 255.0 + 0.5)
            rgba[i, c, 3] = np.uint8(a * 255.0 + 0.5)

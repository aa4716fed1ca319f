"""Per-pixel lighting of the G-buffer (after the column pass)."""
import math
import sys

import numpy as np
from numba import prange

from ._jit import ngjit_inline, ngjit_parallel_nrt_free
from .layout import (
    E_COV, E_COV0, E_I, E_NX, E_NY, E_NZ, E_SEEN, E_SIDE, E_W,
    G_DEPTH, G_I, G_NX, G_NY, G_NZ, G_W, M_AMBIENT, M_INTERP, M_LOWER, M_SHININESS, M_SPAN,
    M_SPECULAR, M_WLO, VP_AA, VP_D1, VP_D3, VP_H, VP_LX, VP_LY, VP_LZ, VP_ORTHO, VP_SCALE,
    VP_WORG,
)
from .coverage import flagged, implied_coverages, seen_side
from .sample import column_x0

INTERP_INTENSITY = 0   # the paper's iis (Gouraud): lit at the samples, interpolated
INTERP_NORMAL = 1      # nis: the normal is interpolated and lit at each pixel
#: finish_kernel writes a pixel's 4 bytes (r, g, b, alpha) as one uint32 (_rgba32)
LITTLE_ENDIAN = sys.byteorder == "little"


@ngjit_inline
def _power(x, e):
    """x ** e for x > 0: by squaring when e is a whole number up to 1024 (the
    default shininess 30 takes 8 multiplications instead of a call of pow)."""
    if e == math.floor(e) and 0.0 <= e <= 1024.0:
        n = int(e)
        r = 1.0
        while n > 0:
            if n & 1:
                r *= x
            x *= x
            n >>= 1
        return r
    return x ** e


@ngjit_inline
def toward_viewer(vp, x0, j, depth):
    """The unit vector from the point at depth ``depth`` on row j (from the bottom) of
    column x0 toward the viewpoint (orthographic: toward the viewer, (0, 0, -1))."""
    if vp[VP_ORTHO] != 0.0:
        return 0.0, 0.0, -1.0
    y0 = (j - (vp[VP_H] - 1.0) * 0.5) / vp[VP_SCALE]
    e = depth + vp[VP_D3]
    m = e / vp[VP_D1]
    vx = -x0 * m
    vy = -y0 * m
    vz = -e
    q = 1.0 / math.sqrt(vx * vx + vy * vy + vz * vz)
    return vx * q, vy * q, vz * q


@ngjit_inline
def _light(vp, x0, j, nx, ny, nz, lam_iis, mp, lit):
    """(I, specular) of one pixel: I = ambient + (1 - ambient) |L.N| / (|L| |N|), and
    Phong's specular * max(R.V, 0)^shininess (the paper has none), with V toward the
    viewpoint, N turned toward the viewer (the side that is seen) and R the
    reflection of L about N; zero where the light is behind the seen side. The light
    is vp's directional light (a unit vector), or the viewpoint when that is zero
    (eq. 12). The material vector mp (layout.py M_*) holds the interpolation, ambient,
    specular and shininess. ``lit`` in [0, 1]: the part of the light that reaches the
    point (0 in a shadow: ambient only; 1 without shadows, which leaves every value as
    it was).

    V is toward_viewer's direction without its square root and division (the
    direction alone does not depend on the depth): R.V = (2 (L.N)(N.v) / |N|^2 - L.v)
    / |v| for v of any length, and the product (L.N)(N.v) keeps its sign when N turns
    toward the viewer, so a pixel takes one square root and one division (two of each
    before: the finishing pass of 3 sin(u cos v) at 1920x1080 in perspective 9.0 -> 7.0
    ms, orthographic 8.5 -> 8.1; the pictures bit for bit the same, the intensities
    within a float32 rounding), a second square root only where a highlight may be.
    (The depth is not needed for that: every point seen lies beyond the screen, where
    the direction is the same.)"""
    ambient = mp[M_AMBIENT]
    specular = mp[M_SPECULAR]
    # toward the viewpoint (toward_viewer's direction, times |v| scale / e)
    if vp[VP_ORTHO] != 0.0:
        vx = 0.0
        vy = 0.0
        vz = -1.0
    else:
        vx = -x0 * vp[VP_SCALE]
        vy = (vp[VP_H] - 1.0) * 0.5 - j
        vz = -vp[VP_D1] * vp[VP_SCALE]
    vv = vx * vx + vy * vy + vz * vz
    headlight = vp[VP_LX] == 0.0 and vp[VP_LY] == 0.0 and vp[VP_LZ] == 0.0
    nn2 = nx * nx + ny * ny + nz * nz
    nv = nx * vx + ny * vy + nz * vz              # N.v
    if headlight:
        ln = nv                                   # L.N |v|
        q = 1.0 / math.sqrt(nn2 * vv) if nn2 > 0.0 else 0.0
    else:
        ln = vp[VP_LX] * nx + vp[VP_LY] * ny + vp[VP_LZ] * nz
        q = 1.0 / math.sqrt(nn2) if nn2 > 0.0 else 0.0
    nl = ln * q                                   # N.L / |N|, L a unit vector
    lam = lam_iis if mp[M_INTERP] == INTERP_INTENSITY else abs(nl)
    inten = ambient + (1.0 - ambient) * min(lam, 1.0) * lit
    sp = 0.0
    if specular > 0.0 and nn2 > 0.0 and (ln * nv > 0.0 or (nv == 0.0 and ln > 0.0)):
        if headlight:
            rv = 2.0 * nl * nl - 1.0              # L = V
        else:
            b = 2.0 * ln * nv / nn2 - (vp[VP_LX] * vx + vp[VP_LY] * vy + vp[VP_LZ] * vz)
            rv = b / math.sqrt(vv) if b > 0.0 else 0.0
        if rv > 0.0:
            sp = specular * _power(rv, mp[M_SHININESS]) * lit
    return inten, sp


@ngjit_inline
def _side_rgb(side, w, lut, w_lo, span, lower_rgb):
    """The colour of a side: the lower side's, or the upper side's from ``lut`` (n, 3)
    indexed linearly by w over [w_lo, w_lo + span]; a lut (n, 4) carries in its last
    column the ascending heights where its rows begin (a non-linear norm: row k from
    norm.inverse(k / (n - 1))), found by np.searchsorted. A lower side's colour NaN
    (lower_color="same", color.side_colors) takes the upper side's."""
    if side > 0.0 or lower_rgb[0] != lower_rgb[0]:
        n_lut = lut.shape[0]
        if lut.shape[1] > 3:                     # the last row starting at or below w
            idx = max(np.searchsorted(lut[:, 3], w, side="right") - 1, 0) if w == w else 0
        else:
            x = (w - w_lo) / span * (n_lut - 1)
            idx = int(min(max(x, 0.0), n_lut - 1.0)) if x == x else 0
        return lut[idx, 0], lut[idx, 1], lut[idx, 2]
    return lower_rgb[0], lower_rgb[1], lower_rgb[2]


@ngjit_inline
def held(mp):
    """The material vector mp (layout.py M_*) as a tuple: the kernels read its values
    from registers instead of memory that the picture's stores may alias (the
    finishing kernel 2 % faster). _light and _colour take either."""
    return (mp[0], mp[1], mp[2], mp[3], mp[4], mp[5], mp[6], mp[7], mp[8], mp[9])


@ngjit_inline
def _colour(side, w, mp, lut):
    """_side_rgb with the material vector mp's heights and lower side."""
    return _side_rgb(side, w, lut, mp[M_WLO], mp[M_SPAN], mp[M_LOWER:])


@ngjit_inline
def pixel_rgba(s, w, cov0, lam, sp, e_cov, e_side, e_w, e_lam, e_sp, mp, lut, background):
    """One pixel's colour (r, g, b, alpha) in [0, 1], straight alpha.

    The surface at the pixel's centre has side s (0: none), height w, coverage cov0
    (1 without antialiasing), shade lam and specular term sp; the edge surface of
    section 6.4 (coverage e_cov, 0: none) likewise. The upper side takes its colour
    from ``lut`` indexed by w over the material vector mp's [w_lo, w_lo + span] (a
    one-row lut is a flat colour), the lower side mp's lower colour; both multiplied by the shade, plus the
    white specular term. The colour is the coverage-weighted mean of the two surfaces
    and the background (uint8 RGBA).
    """
    r = 0.0
    g = 0.0
    b = 0.0
    if s != 0.0:
        r, g, b = _colour(s, w, mp, lut)
    er = 0.0
    eg = 0.0
    eb = 0.0
    if e_cov > 0.0:
        er, eg, eb = _colour(e_side, e_w, mp, lut)
    return blend(s, r, g, b, cov0, lam, sp, e_cov, er, eg, eb, e_lam, e_sp, background)


@ngjit_inline
def blend(s, r, g, b, cov0, lam, sp, e_cov, er, eg, eb, e_lam, e_sp, background):
    """pixel_rgba's colour of a pixel whose surfaces have the colours (r, g, b) at its
    centre (side s, 0: none) and (er, eg, eb) of the edge surface (coverage e_cov, 0:
    none), before their light (lam, sp; e_lam, e_sp)."""
    if s != 0.0:
        r = min(r * lam + sp, 1.0)
        g = min(g * lam + sp, 1.0)
        b = min(b * lam + sp, 1.0)
    else:
        r = 0.0
        g = 0.0
        b = 0.0
        cov0 = 0.0
    cov1 = 0.0
    if e_cov > 0.0:
        cov1 = min(e_cov, 1.0 - cov0)
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


@ngjit_inline
def _rgba32(r, g, b, a):
    """The bytes r, g, b, a (each a whole number 0 to 255, any type) in memory order
    as one uint32: a pixel of an (H, W, 4) uint8 picture viewed as (H, W) uint32."""
    r, g, b, a = np.uint32(r), np.uint32(g), np.uint32(b), np.uint32(a)
    if LITTLE_ENDIAN:
        return r | (g << np.uint32(8)) | (b << np.uint32(16)) | (a << np.uint32(24))
    return (r << np.uint32(24)) | (g << np.uint32(16)) | (b << np.uint32(8)) | a


@ngjit_inline
def shade_pixel(gbuf, ebuf, tile, lane, j, aa, vp, x0, mp, lut, background, lit, base, i, c):
    """Light (_light) and colour (pixel_rgba) row j of the column in lane ``lane`` of
    tile ``tile`` of the G-buffer gbuf and the edge buffer ebuf (layout.py; E_SEEN,
    and with ``aa`` the coverages, coverage.py), with the material vector mp and its
    colour table lut. ``base`` (H, W, 6): the colours of the surface at the centre
    of pixel (i, c), both sides (a texture's, passes/colour.py), and of its edge
    surface, instead of their sides'; or an empty array. Returns (intensity at the
    centre, NaN where no surface; r, g, b, alpha)."""
    g = gbuf[tile, j, lane]
    x = ebuf[tile, E_SEEN, j, lane]
    s = seen_side(x)
    lam = np.nan
    sp = 0.0
    w = 0.0
    if s != 0.0:
        w = g[G_W] + vp[VP_WORG]                  # (layout.py G_W)
        lam, sp = _light(vp, x0, j, g[G_NX], g[G_NY], g[G_NZ], g[G_I], mp, lit)
    cov0 = 1.0
    e_cov = 0.0
    e_side = 0.0
    e_w = 0.0
    e_lam = 0.0
    e_sp = 0.0
    if aa and not flagged(x):
        cov0, e_cov = implied_coverages(x)
    elif aa:
        e = ebuf[tile, :, j, lane]
        cov0 = e[E_COV0]
        e_cov = e[E_COV]
        if e_cov > 0.0:
            e_side = e[E_SIDE]
            e_w = e[E_W] + vp[VP_WORG]
            e_lam, e_sp = _light(vp, x0, j, e[E_NX], e[E_NY], e[E_NZ], e[E_I], mp, lit)
    if base.shape[0] > 0:
        r, gr, bl, a = blend(s, base[i, c, 0], base[i, c, 1], base[i, c, 2], cov0, lam, sp,
                             e_cov, base[i, c, 3], base[i, c, 4], base[i, c, 5], e_lam, e_sp,
                             background)
        return lam, r, gr, bl, a
    r, gr, bl, a = pixel_rgba(s, w, cov0, lam, sp, e_cov, e_side, e_w, e_lam, e_sp, mp, lut,
                              background)
    return lam, r, gr, bl, a


#: Rows of the picture per block of the finishing pass (finish_kernel)
FINISH_ROWS = 16


@ngjit_inline
def _picture_blocks(gbuf, side):
    """(tiles, H, tile width, W, blocks of FINISH_ROWS rows) of a tiled G-buffer and
    its picture (finish_kernel and centre_kernel go block by block, in parallel)."""
    H = gbuf.shape[1]
    return gbuf.shape[0], H, gbuf.shape[2], side.shape[1], -(-H // FINISH_ROWS)


@ngjit_inline
def spread_stride(n):
    """A stride coprime with n near n / phi, for spread."""
    s = max(int(n * 0.6180339887498949), 1)
    while True:
        a = n
        b = s
        while b:                                 # (Euclid's gcd)
            a, b = b, a % b
        if a == 1:
            return s
        s += 1


@ngjit_inline
def spread(p, n, stride):
    """The block that iteration p of a parallel loop over n blocks of rows takes
    (stride: spread_stride(n)'s): p stride mod n, a permutation. Numba gives each
    thread a run of a loop's iterations; in order, one thread would take the bottom
    of the picture and the other its top, and a fly-through's sky at the top is
    nearly empty (its finishing pass on 2 threads 1.48x as fast as on one); spread,
    each takes blocks from all over (1.9x: 1280x720 10.0 -> 7.9 ms). Each block
    writes its own rows: the same picture."""
    return (p * stride) % n


@ngjit_inline
def _block_rows(blk, H):
    """Rows j_lo to j_hi - 1 (from the bottom) of block blk."""
    j_lo = blk * FINISH_ROWS
    return j_lo, min(H, j_lo + FINISH_ROWS)


@ngjit_parallel_nrt_free
def finish_kernel(gbuf, ebuf, rows, vp, mp, lut, background, lit, base, side, rgba):
    """Light, colour and assemble the picture, top row first, in one pass: side and
    rgba (shade_pixel; rgba an (H, W, 4) uint8 picture viewed as (H, W) uint32, one
    store a pixel: _rgba32), from the tiled G-buffer gbuf and edge buffer ebuf
    (layout.py).
    With VP_AA, ebuf holds the coverages (where E_SEEN is flagged, coverage.py) and
    rgba is blended; side stays that of the pixel's centre. The G-buffer is read only
    where ebuf's E_SEEN plane says a surface is seen. Intensity and depth at the
    centres are centre_kernel's, when they are asked for (Render's lazy arrays): the
    picture alone stores 5 bytes per pixel instead of 13 (1920x1080: 14.2 -> 9.9 ms).

    The picture goes in blocks of FINISH_ROWS rows, in parallel (spread over the
    threads): a block's rows are first filled with the background in runs (most
    pixels are background), then the tiles are read, each a run of FINISH_ROWS rows,
    and only the pixels that show a surface are written again. Every store so lands
    in the few cache lines of the block's rows; going down the tiles' columns instead
    (their own order) missed the cache on every store (1920x1080: 5-17 % slower). A
    tile whose rows (column_kernel's ``rows``: where its E_SEEN may be set) miss the
    block is background there: not read at all. ``lit`` (H, W): the part of the light
    reaching each pixel's point (passes/shadow.py), or an empty array: all of it. mp:
    the material vector (layout.py M_*), lut its colour table (Material.table).
    ``base`` (H, W, 6) float32: the colour of the surface seen at each pixel's centre,
    both sides, and of its edge surface (a texture or a colour field's,
    passes/colour.py), or an empty array: their sides' colours (lut by w, or the lower
    side's)."""
    n_tiles, H, T, W, n_blocks = _picture_blocks(gbuf, side)
    aa = vp[VP_AA] != 0.0
    shadows = lit.shape[0] > 0
    textured = base.shape[0] > 0
    mt = held(mp)
    wo = vp[VP_WORG]                    # the G-buffer's w from there (layout.py G_W)
    stride = spread_stride(n_blocks)
    for blk_ in prange(n_blocks):
        blk = spread(np.int64(blk_), n_blocks, stride)  # (_jit.py: prange_index)
        j_lo, j_hi = _block_rows(blk, H)
        bg = _rgba32(background[0], background[1], background[2], background[3])
        for j in range(j_lo, j_hi):
            i = H - 1 - j
            for c in range(W):
                side[i, c] = 0
                rgba[i, c] = bg
        for b in range(n_tiles):
            if rows[b, 1] < j_lo or rows[b, 0] >= j_hi:
                continue                                   # only background here
            n_lanes = min(T, W - b * T)
            for j in range(j_lo, j_hi):
                i = H - 1 - j
                for lane in range(n_lanes):
                    x = ebuf[b, E_SEEN, j, lane]
                    if x == 0.0:                           # the background
                        continue
                    s = seen_side(x)
                    cov0 = 1.0
                    e_cov = 0.0
                    if flagged(x):                         # coverages kept (coverage.py)
                        cov0 = ebuf[b, E_COV0, j, lane]
                        e_cov = ebuf[b, E_COV, j, lane]
                        if e_cov <= 0.0 and s == 0.0:
                            continue
                    c = b * T + lane
                    side[i, c] = np.int8(s)
                    x0 = column_x0(vp, c)
                    lt = lit[i, c] if shadows else 1.0
                    if e_cov <= 0.0 and cov0 >= 1.0:
                        # a surface covering the whole pixel: shade_pixel's colour,
                        # without the blend
                        lam, sp = _light(vp, x0, j, gbuf[b, j, lane, G_NX],
                                         gbuf[b, j, lane, G_NY], gbuf[b, j, lane, G_NZ],
                                         gbuf[b, j, lane, G_I], mt, lt)
                        if textured:
                            r = base[i, c, 0]
                            g = base[i, c, 1]
                            bl = base[i, c, 2]
                        else:
                            r, g, bl = _colour(s, gbuf[b, j, lane, G_W] + wo, mt, lut)
                        rgba[i, c] = _rgba32(min(r * lam + sp, 1.0) * 255.0 + 0.5,
                                             min(g * lam + sp, 1.0) * 255.0 + 0.5,
                                             min(bl * lam + sp, 1.0) * 255.0 + 0.5, 255)
                        continue
                    _, r, g, bl, a = shade_pixel(gbuf, ebuf, b, lane, j, aa, vp, x0, mt, lut,
                                                 background, lt, base, i, c)
                    rgba[i, c] = _rgba32(r * 255.0 + 0.5, g * 255.0 + 0.5, bl * 255.0 + 0.5,
                                         a * 255.0 + 0.5)


@ngjit_parallel_nrt_free
def centre_kernel(gbuf, vp, mp, lit, side, intensity, depth):
    """intensity (ambient + diffuse, NaN where nothing is seen) and depth (+inf where
    nothing is seen) at the pixel centres, top row first, from the tiled G-buffer
    gbuf where ``side`` (finish_kernel's) says a surface is seen: the values
    finish_kernel lights the picture with (_light at the centre). In finish_kernel's
    order: blocks of FINISH_ROWS rows filled in runs, then tile by tile."""
    n_tiles, H, T, W, n_blocks = _picture_blocks(gbuf, side)
    shadows = lit.shape[0] > 0
    stride = spread_stride(n_blocks)
    for blk_ in prange(n_blocks):
        blk = spread(np.int64(blk_), n_blocks, stride)  # (_jit.py: prange_index)
        j_lo, j_hi = _block_rows(blk, H)
        for j in range(j_lo, j_hi):
            i = H - 1 - j
            for c in range(W):
                intensity[i, c] = np.nan
                depth[i, c] = np.inf
        for b in range(n_tiles):
            for j in range(j_lo, j_hi):
                i = H - 1 - j
                for lane in range(min(T, W - b * T)):
                    c = b * T + lane
                    if side[i, c] == 0:
                        continue
                    g = gbuf[b, j, lane]
                    lam, _ = _light(vp, column_x0(vp, c), j, g[G_NX], g[G_NY], g[G_NZ],
                                    g[G_I], mp, lit[i, c] if shadows else 1.0)
                    intensity[i, c] = lam
                    depth[i, c] = g[G_DEPTH]

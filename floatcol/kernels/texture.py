"""Per-pixel kernels of the colour and overlay passes (passes/colour.py,
passes/overlays.py): the G-buffer's planes as pictures, filtered texture lookups, and
lines on the surface. Rows in parallel; every pixel writes only its own output."""
import math

import numpy as np
from numba import prange

from ._jit import ngjit_inline, ngjit_parallel
from .coverage import flagged, seen_side
from .layout import E_COV, E_SEEN, E_SIDE, E_U, E_V, E_W, G_U, G_V, G_W
from .sample import surface_value
from .shade import _side_rgb

FILTER_POINT = 0
FILTER_LINEAR = 1
FILTER_MIPMAP = 2


@ngjit_parallel
def planes_kernel(gbuf, ebuf, W, a, b, c, cu, cv, wo, u, v, w, side, eu, ev):
    """u, v, w (H, W) float64, top row first, of the seen point at each pixel (NaN
    where none; the G-buffer's u, v from the view's centre (cu, cv) and w from wo,
    layout.py G_U, G_W;
    divided by the box's stretch a, b, c) and the side seen there (+1, -1,
    0), from the tiled G-buffer and edge buffer (layout.py); eu, ev those of the
    pixel's edge surface (section 6.4; NaN where none), unless they are empty. Tile
    by tile (each tile's memory in order: row by row across the tiles was 3x slower,
    a page a tile)."""
    n_tiles = gbuf.shape[0]
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    edges = eu.shape[0] > 0
    for t_ in prange(n_tiles):
        t = np.int64(t_)  # (_jit.py: prange_index)
        for j in range(H):
            i = H - 1 - j
            for lane in range(min(T, W - t * T)):
                col = t * T + lane
                x = ebuf[t, E_SEEN, j, lane]
                s = seen_side(x)
                side[i, col] = s
                if edges:
                    has = _has_edge(ebuf, t, j, lane)
                    eu[i, col] = (ebuf[t, E_U, j, lane] + cu) / a if has else np.nan
                    ev[i, col] = (ebuf[t, E_V, j, lane] + cv) / b if has else np.nan
                if s == 0.0:
                    u[i, col] = np.nan
                    v[i, col] = np.nan
                    w[i, col] = np.nan
                else:
                    u[i, col] = (gbuf[t, j, lane, G_U] + cu) / a
                    v[i, col] = (gbuf[t, j, lane, G_V] + cv) / b
                    w[i, col] = (gbuf[t, j, lane, G_W] + wo) / c


@ngjit_inline
def _texel(levels, off, h, w, x, y, ch):
    """Level texel (x, y) clamped to its edge: channel ch."""
    xi = min(max(x, 0), w - 1)
    yi = min(max(y, 0), h - 1)
    return levels[off + (yi * w + xi) * 4 + ch]


@ngjit_inline
def _bilinear(levels, off, h, w, x, y, out, weight):
    """Add weight times the bilinear lookup at texel coordinates (x, y) (texel k's
    centre at k; clamped to the level's edge) to out[0:4]."""
    x = min(max(x, 0.0), w - 1.0)
    y = min(max(y, 0.0), h - 1.0)
    x0 = int(x)
    y0 = int(y)
    fx = x - x0
    fy = y - y0
    x1 = min(x0 + 1, w - 1)
    y1 = min(y0 + 1, h - 1)
    p00 = off + (y0 * w + x0) * 4
    p01 = off + (y0 * w + x1) * 4
    p10 = off + (y1 * w + x0) * 4
    p11 = off + (y1 * w + x1) * 4
    w00 = (1.0 - fx) * (1.0 - fy) * weight
    w01 = fx * (1.0 - fy) * weight
    w10 = (1.0 - fx) * fy * weight
    w11 = fx * fy * weight
    for ch in range(4):
        out[ch] += (levels[p00 + ch] * w00 + levels[p01 + ch] * w01 + levels[p10 + ch] * w10
                    + levels[p11 + ch] * w11)


@ngjit_inline
def texel_at(levels, offsets, shapes, x, y, lod, out):
    """out[0:4] = the mip-map's trilinear lookup at level-0 texel coordinates (x, y)
    and level of detail ``lod`` (0: the full texture; clamped to the pyramid)."""
    for ch in range(4):
        out[ch] = 0.0
    n_lev = offsets.shape[0]
    lod = min(max(lod, 0.0), n_lev - 1.0)
    k = int(lod)
    f = lod - k
    k1 = min(k + 1, n_lev - 1)
    sc = 1.0 / (1 << k)
    _bilinear(levels, offsets[k], shapes[k, 0], shapes[k, 1], (x + 0.5) * sc - 0.5,
              (y + 0.5) * sc - 0.5, out, 1.0 - f)
    if f > 0.0:
        s1 = 1.0 / (1 << k1)
        _bilinear(levels, offsets[k1], shapes[k1, 0], shapes[k1, 1], (x + 0.5) * s1 - 0.5,
                  (y + 0.5) * s1 - 0.5, out, f)


#: A layer's texture for the translucent layers (kernels/layers.py): the tuple
#: (lut, levels, offsets, shapes, tp, lines), tp[TP_*] the texel map of the box's (u, v)
TP_OU = 0        # texel x = (u - ou) su, y = (v - ov) sv
TP_SU = 1
TP_OV = 2
TP_SV = 3
TP_SIZE = 4


#: ... and its lines (the tuple's sixth item, float64; empty: none), drawn on each
#: crossing as overlays.py draws them on the opaque surface's pixels
LN_NLEV = 0      # contour levels of w (box units), sorted, from LN_SIZE on
LN_CW = 1        # their width in pixels, their colour (0-1)
LN_CR = 2
LN_CG = 3
LN_CB = 4
LN_WIRE = 5      # 1: wireframe lines at u = U0 + k DU and v = V0 + k DV (box units)
LN_U0 = 6
LN_DU = 7
LN_V0 = 8
LN_DV = 9
LN_EW = 10       # their width in pixels, their colour
LN_ER = 11
LN_EG = 12
LN_EB = 13
LN_FN = 14       # > 0: the contours are a colour field's, its values on an LN_FN x LN_FN
LN_FU0 = 15      # grid after the levels (rows along v), at x = (u - FU0) FSU,
LN_FSU = 16      # y = (v - FV0) FSV (u, v in box units), the levels in its units
LN_FV0 = 17
LN_FSV = 18
LN_NWU = 19      # LN_WIRE 2: wireframe lines at the LN_NWU sorted positions of u and the
LN_NWV = 20      # LN_NWV of v (box units) after the colour field's grid; 3: of a curvilinear
LN_GNX = 21      # mesh's column and row index, bilinear on an LN_GNY x LN_GNX grid of
LN_GNY = 22      # pairs after the positions (rows along v), at x = (u - GU0) GSU,
LN_GU0 = 23      # y = (v - GV0) GSV (u, v in box units)
LN_GSU = 24
LN_GV0 = 25
LN_GSV = 26
LN_SIZE = 27


@ngjit_inline
def _line_cover(dist, grad, width):
    """The part of a pixel a line of ``width`` pixels covers at ``dist`` (q's units)
    from it, q changing ``grad`` a pixel: clip(width / 2 + 1/2 - d, 0, 1) of d =
    dist / grad pixels, lines_kernel's."""
    if not (grad == grad and dist == dist):
        return 0.0
    if grad > 0.0:
        px = dist / grad
    elif dist == 0.0:
        px = 0.0
    else:
        return 0.0
    return min(max(width * 0.5 + 0.5 - px, 0.0), 1.0)


@ngjit_inline
def _grid_bilinear(lines, base, stride, channel, nx, ny, x, y, su, sv):
    """(q, dq/du, dq/dv): a grid in ``lines`` from ``base`` (ny rows of nx nodes, rows
    along v, ``stride`` values a node, q its ``channel``-th) bilinear at the grid
    coordinates (x, y) (clamped to it), su and sv its nodes per unit of u and v."""
    x = min(max(x, 0.0), nx - 1.0)
    y = min(max(y, 0.0), ny - 1.0)
    i = min(int(y), ny - 2)
    j = min(int(x), nx - 2)
    fx = x - j
    fy = y - i
    g00 = lines[base + (i * nx + j) * stride + channel]
    g01 = lines[base + (i * nx + j + 1) * stride + channel]
    g10 = lines[base + ((i + 1) * nx + j) * stride + channel]
    g11 = lines[base + ((i + 1) * nx + j + 1) * stride + channel]
    q = (g00 * (1.0 - fx) + g01 * fx) * (1.0 - fy) + (g10 * (1.0 - fx) + g11 * fx) * fy
    qx = (g01 - g00) * (1.0 - fy) + (g11 - g10) * fy
    qy = (g10 - g00) * (1.0 - fx) + (g11 - g01) * fx
    return q, qx * su, qy * sv


@ngjit_inline
def layer_field(lines, u, v):
    """(q, dq/du, dq/dv): the colour field of ``lines`` (LN_FN) at (u, v) (box units),
    bilinear on its grid (clamped to it), and its partials; NaN at its holes."""
    n = int(lines[LN_FN])
    return _grid_bilinear(lines, LN_SIZE + int(lines[LN_NLEV]), 1, 0, n, n,
                          (u - lines[LN_FU0]) * lines[LN_FSU],
                          (v - lines[LN_FV0]) * lines[LN_FSV], lines[LN_FSU], lines[LN_FSV])


@ngjit_inline
def _wire_base(lines):
    """Where the wireframe's positions begin in ``lines`` (after the contour levels
    and the colour field's grid)."""
    n = int(lines[LN_FN])
    return LN_SIZE + int(lines[LN_NLEV]) + n * n


@ngjit_inline
def layer_wire_coords(lines, u, v):
    """(a, da/du, da/dv, b, db/du, db/dv): a curvilinear mesh's column and row index
    at (u, v) (box units; LN_WIRE 3), bilinear on their grid (clamped to it)."""
    base = _wire_base(lines) + int(lines[LN_NWU]) + int(lines[LN_NWV])
    nx = int(lines[LN_GNX])
    ny = int(lines[LN_GNY])
    x = (u - lines[LN_GU0]) * lines[LN_GSU]
    y = (v - lines[LN_GV0]) * lines[LN_GSV]
    a, au, av = _grid_bilinear(lines, base, 2, 0, nx, ny, x, y, lines[LN_GSU], lines[LN_GSV])
    b, bu, bv = _grid_bilinear(lines, base, 2, 1, nx, ny, x, y, lines[LN_GSU], lines[LN_GSV])
    return a, au, av, b, bu, bv


@ngjit_inline
def _to_level(levels, q):
    """|q - the nearest of the sorted ``levels``| (inf: none)."""
    n = levels.shape[0]
    k = np.searchsorted(levels, q)
    dist = np.inf
    if k < n:
        dist = levels[k] - q
    if k > 0:
        dist = min(dist, q - levels[k - 1])
    return dist


@ngjit_inline
def _to_grid(q, q0, dq):
    """|q - the nearest of q0 + k dq| (lines_kernel's wireframe distance)."""
    return abs(q - (q0 + math.floor((q - q0) / dq + 0.5) * dq))


@ngjit_inline
def _over(r, g, b, al, lines, k, cov):
    """The premultiplied (r, g, b, al) under a line of lines[k:k + 3] covering cov."""
    keep = 1.0 - cov
    return (cov * lines[k] + keep * r, cov * lines[k + 1] + keep * g,
            cov * lines[k + 2] + keep * b, cov + keep * al)


@ngjit_inline
def layer_lines(lines, u, v, w, grad_u, grad_v, grad_w):
    """The lines of a translucent layer's crossing at (u, v) (box units): their
    colour premultiplied by the part of the pixel they cover, and that part, (r, g, b,
    a); the wireframe's and then the contours over them (LN_*, overlays.py's order),
    u, v and w (the contours' q: the height in box units, or the colour field's value)
    changing grad_u, grad_v, grad_w a pixel across the picture there."""
    r = 0.0
    g = 0.0
    b = 0.0
    al = 0.0
    if lines[LN_WIRE] == 1.0:
        cov = _line_cover(_to_grid(u, lines[LN_U0], lines[LN_DU]), grad_u, lines[LN_EW])
        if cov > 0.0:
            r, g, b, al = _over(r, g, b, al, lines, LN_ER, cov)
        cov = _line_cover(_to_grid(v, lines[LN_V0], lines[LN_DV]), grad_v, lines[LN_EW])
        if cov > 0.0:
            r, g, b, al = _over(r, g, b, al, lines, LN_ER, cov)
    elif lines[LN_WIRE] != 0.0:
        # a mesh's own lines at their positions (of u and v, or of its indices: the
        # caller's u, v and their changes are then those, layer_wire_coords')
        base = _wire_base(lines)
        nu = int(lines[LN_NWU])
        nv = int(lines[LN_NWV])
        cov = _line_cover(_to_level(lines[base:base + nu], u), grad_u, lines[LN_EW])
        if cov > 0.0:
            r, g, b, al = _over(r, g, b, al, lines, LN_ER, cov)
        cov = _line_cover(_to_level(lines[base + nu:base + nu + nv], v), grad_v, lines[LN_EW])
        if cov > 0.0:
            r, g, b, al = _over(r, g, b, al, lines, LN_ER, cov)
    n = int(lines[LN_NLEV])
    if n > 0:
        cov = _line_cover(_to_level(lines[LN_SIZE:LN_SIZE + n], w), grad_w, lines[LN_CW])
        if cov > 0.0:
            r, g, b, al = _over(r, g, b, al, lines, LN_CR, cov)
    return r, g, b, al


@ngjit_inline
def layer_texel(colours, u, v, footprint, out):
    """out[0:4]: the texture of ``colours`` (TP_*) at the point (u, v) whose pixel
    covers ``footprint`` units of the box each way (trilinear, the level from it)."""
    levels = colours[1]
    tp = colours[4]
    su = tp[TP_SU]
    sv = tp[TP_SV]
    rho = footprint * max(abs(su), abs(sv))
    lod = math.log2(rho) if rho > 1.0 else 0.0
    texel_at(levels, colours[2], colours[3], (u - tp[TP_OU]) * su, (v - tp[TP_OV]) * sv, lod,
             out)


@ngjit_inline
def _one_sided(x, y, seen, i, col, di, dc):
    """The smaller of the two one-sided changes of (x, y) to the neighbours (i - di,
    col - dc) and (i + di, col + dc) that are seen, squared (inf where neither is)."""
    H, W = seen.shape
    best = np.inf
    for sgn in (-1, 1):
        i2 = i + sgn * di
        c2 = col + sgn * dc
        if 0 <= i2 < H and 0 <= c2 < W and seen[i2, c2]:
            dx = x[i2, c2] - x[i, col]
            dy = y[i2, c2] - y[i, col]
            d = dx * dx + dy * dy
            if d < best:
                best = d
    return best


@ngjit_parallel
def texture_kernel(gbuf, ebuf, W, ou, su, ov, sv, wo, levels, offsets, shapes, filt, lut,
                   w_lo, w_hi, lower_rgb, tx, ty, wp, sides, side, base):
    """base (H, W, 3) float32, top row first: at each seen pixel the texture's colour
    over the surface's own (its side's: lut by w, or lower_rgb; the texture's alpha
    lays it over), from the tiled G-buffer and edge buffer. The texel coordinates of
    a point are tx = (u - ou) su, ty = (v - ov) sv (texel k's centre at k; u, v the
    G-buffer's, from the view's centre: layout.py G_U, and ou, ov from there too; its
    w from wo, layout.py G_W); the mip-map ``levels`` flattened (level k at offsets[k], shapes[k] =
    (h, w), 4 premultiplied channels each). FILTER_POINT: the nearest texel;
    FILTER_LINEAR: bilinear; FILTER_MIPMAP: trilinear, the level from the pixel's
    footprint (the longer of the changes of (tx, ty) to the next pixel across and
    down, each the smaller one-sided one, so a silhouette's far neighbour does not
    count). base[..., 3:6]: likewise the colour of the pixel's edge surface (section
    6.4: the surface sharing a pixel at a silhouette) where it has one, at its own
    (u, v) in the ebuf, the level of the pixel's footprint (or, where nothing is seen
    at its centre, of the seen neighbour's). tx, ty, wp (H, W) float64, sides (H, W)
    int8 and side (H, W) bool: scratch."""
    n_tiles = gbuf.shape[0]
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    span = w_hi - w_lo if w_hi > w_lo else 1.0
    for t_ in prange(n_tiles):                 # every pixel's texel coordinates, tile by
        t = np.int64(t_)  # (_jit.py: prange_index)
        for j in range(H):                    # tile (planes_kernel)
            i = H - 1 - j
            for lane in range(min(T, W - t * T)):
                col = t * T + lane
                x = ebuf[t, E_SEEN, j, lane]
                sd = seen_side(x)
                side[i, col] = sd != 0.0
                sides[i, col] = np.int8(sd)
                if sd != 0.0:
                    tx[i, col] = (gbuf[t, j, lane, G_U] - ou) * su
                    ty[i, col] = (gbuf[t, j, lane, G_V] - ov) * sv
                    wp[i, col] = gbuf[t, j, lane, G_W] + wo
    for i_ in prange(H):
        i = np.int64(i_)  # (_jit.py: prange_index)
        acc = np.empty(4)
        for col in range(W):
            if not side[i, col]:
                continue
            rho2 = _footprint2(tx, ty, side, i, col) if filt == FILTER_MIPMAP else 0.0
            _lookup(levels, offsets, shapes, filt, tx[i, col], ty[i, col], rho2, acc)
            r, g, b = _side_rgb(float(sides[i, col]), wp[i, col], lut, w_lo, span, lower_rgb)
            _put(base, i, col, 0, acc, r, g, b)
    for t_ in prange(n_tiles):                 # the edge surfaces' colours
        t = np.int64(t_)  # (_jit.py: prange_index)
        acc = np.empty(4)
        for j in range(H):
            i = H - 1 - j
            for lane in range(min(T, W - t * T)):
                if not _has_edge(ebuf, t, j, lane):
                    continue
                col = t * T + lane
                rho2 = np.inf
                if filt == FILTER_MIPMAP and side[i, col]:
                    rho2 = _footprint2(tx, ty, side, i, col)
                elif filt == FILTER_MIPMAP:    # a seen neighbour's footprint
                    for di, dc in ((0, 1), (0, -1), (1, 0), (-1, 0)):
                        i2 = i + di
                        c2 = col + dc
                        if 0 <= i2 < H and 0 <= c2 < W and side[i2, c2]:
                            rho2 = _footprint2(tx, ty, side, i2, c2)
                            break
                _lookup(levels, offsets, shapes, filt, (ebuf[t, E_U, j, lane] - ou) * su,
                        (ebuf[t, E_V, j, lane] - ov) * sv, rho2, acc)
                r, g, b = _side_rgb(ebuf[t, E_SIDE, j, lane], ebuf[t, E_W, j, lane] + wo, lut,
                                    w_lo, span, lower_rgb)
                _put(base, i, col, 3, acc, r, g, b)


@ngjit_inline
def _has_edge(ebuf, t, j, lane):
    """Whether the pixel has an edge surface (section 6.4): its coverages are kept
    (coverage.py) and the edge's is above 0."""
    return flagged(ebuf[t, E_SEEN, j, lane]) and ebuf[t, E_COV, j, lane] > 0.0


@ngjit_inline
def _footprint2(tx, ty, side, i, col):
    """The pixel's footprint in texels, squared: the longer of the changes of (tx, ty)
    to the next pixel across and down (_one_sided)."""
    return max(_one_sided(tx, ty, side, i, col, 0, 1), _one_sided(tx, ty, side, i, col, 1, 0))


@ngjit_inline
def _lookup(levels, offsets, shapes, filt, x, y, rho2, acc):
    """acc[0:4] = the texture at texel coordinates (x, y): the nearest texel, bilinear,
    or trilinear at the level of the squared footprint rho2 (FILTER_*)."""
    h0 = shapes[0, 0]
    w0 = shapes[0, 1]
    if filt == FILTER_POINT:
        xi = int(math.floor(min(max(x, 0.0), w0 - 1.0) + 0.5))
        yi = int(math.floor(min(max(y, 0.0), h0 - 1.0) + 0.5))
        for ch in range(4):
            acc[ch] = _texel(levels, 0, h0, w0, xi, yi, ch)
    elif filt == FILTER_LINEAR or offsets.shape[0] == 1:
        for ch in range(4):
            acc[ch] = 0.0
        _bilinear(levels, 0, h0, w0, x, y, acc, 1.0)
    else:
        lod = 0.5 * math.log2(rho2) if math.isfinite(rho2) and rho2 > 1.0 else 0.0
        texel_at(levels, offsets, shapes, x, y, lod, acc)


@ngjit_inline
def _put(base, i, col, k, acc, r, g, b):
    """base[i, col, k:k + 3] = the premultiplied texel acc over the colour (r, g, b)."""
    rest = 1.0 - acc[3]
    base[i, col, k] = min(max(acc[0] + rest * r, 0.0), 1.0)
    base[i, col, k + 1] = min(max(acc[1] + rest * g, 0.0), 1.0)
    base[i, col, k + 2] = min(max(acc[2] + rest * b, 0.0), 1.0)


@ngjit_inline
def _change(q, seen, i, col, di, dc):
    """The smaller |change| of q to the seen neighbours (i - di, col - dc) and (i + di,
    col + dc) (inf where neither is seen)."""
    H, W = seen.shape
    best = np.inf
    for sgn in (-1, 1):
        i2 = i + sgn * di
        c2 = col + sgn * dc
        if 0 <= i2 < H and 0 <= c2 < W and seen[i2, c2]:
            d = abs(q[i2, c2] - q[i, col])
            if d < best:
                best = d
    return best


@ngjit_inline
def _grad(q, seen, i, col):
    """|grad q| in q per pixel: each way the smaller one-sided difference to a seen
    neighbour; NaN where a way has none."""
    gx = _change(q, seen, i, col, 0, 1)
    gy = _change(q, seen, i, col, 1, 0)
    if not (math.isfinite(gx) and math.isfinite(gy)):
        return np.nan
    return math.sqrt(gx * gx + gy * gy)


@ngjit_parallel
def lines_kernel(q, seen, levels, origin, spacing, width, rgb, rgba):
    """Blend the lines q = level (the sorted ``levels``, or origin + k spacing where
    spacing > 0) of colour rgb (0-1) over rgba (H, W, 4) uint8 in place, each
    covering a pixel by clip(width / 2 + 1/2 - d, 0, 1), d its distance in pixels
    (|q - level| / |grad q|)."""
    H, W = seen.shape
    n = levels.shape[0]
    for i_ in prange(H):
        i = np.int64(i_)  # (_jit.py: prange_index)
        for col in range(W):
            x = q[i, col]
            if not seen[i, col] or x != x:
                continue
            if spacing > 0.0:
                dist = _to_grid(x, origin, spacing)
            elif n == 0:
                continue
            else:
                dist = _to_level(levels, x)
            cov = _line_cover(dist, _grad(q, seen, i, col), width)
            if cov <= 0.0:
                continue
            for ch in range(3):
                val = rgba[i, col, ch] / 255.0 * (1.0 - cov) + rgb[ch] * cov
                rgba[i, col, ch] = np.uint8(min(max(val * 255.0 + 0.5, 0.0), 255.0))


@ngjit_parallel
def values_kernel(kind, f, fg, fb, hf, hfp, u, v, out):
    """out[i] = f(u[i], v[i]) (NaN at a hole) for the points in parallel: a colour
    field at the seen pixels (f alone: no partials)."""
    n = u.shape[0]
    chunk = 4096
    for c in prange((n + chunk - 1) // chunk):
        for i in range(c * chunk, min(n, (c + 1) * chunk)):
            out[i] = surface_value(kind, f, hf, hfp, u[i], v[i])


@ngjit_parallel
def field_kernel(gbuf, ebuf, W, a, b, cu, cv, kind, f, fg, fb, hf, hfp, vals, e_vals):
    """vals (H, W), top row first: the colour field f at the seen point of each pixel
    (the G-buffer's u, v from the view's centre (cu, cv), layout.py G_U, divided by the
    box's stretch a, b), e_vals at its edge surface's (section
    6.4); NaN where none. Tile by tile (planes_kernel)."""
    n_tiles = gbuf.shape[0]
    H = gbuf.shape[1]
    T = gbuf.shape[2]
    for t_ in prange(n_tiles):
        t = np.int64(t_)  # (_jit.py: prange_index)
        for j in range(H):
            i = H - 1 - j
            for lane in range(min(T, W - t * T)):
                col = t * T + lane
                x = ebuf[t, E_SEEN, j, lane]
                s = seen_side(x)
                vals[i, col] = np.nan
                e_vals[i, col] = np.nan
                if s != 0.0:
                    vals[i, col] = surface_value(kind, f, hf, hfp,
                                                 (gbuf[t, j, lane, G_U] + cu) / a,
                                                 (gbuf[t, j, lane, G_V] + cv) / b)
                if _has_edge(ebuf, t, j, lane):
                    e_vals[i, col] = surface_value(kind, f, hf, hfp,
                                                   (ebuf[t, E_U, j, lane] + cu) / a,
                                                   (ebuf[t, E_V, j, lane] + cv) / b)


@ngjit_parallel
def colour_kernel(vals, e_vals, lut, lo, hi, lower_rgb, base):
    """base (H, W, 6): the colours of vals and e_vals through the colour table lut over
    [lo, hi] (shade._side_rgb; NaN: lower_rgb)."""
    H, W = vals.shape
    span = hi - lo if hi > lo else 1.0
    for i_ in prange(H):
        i = np.int64(i_)  # (_jit.py: prange_index)
        for col in range(W):
            for k in range(2):
                x = vals[i, col] if k == 0 else e_vals[i, col]
                side = 1.0 if x == x else -1.0
                r, g, b = _side_rgb(side, x, lut, lo, span, lower_rgb)
                base[i, col, 3 * k] = r
                base[i, col, 3 * k + 1] = g
                base[i, col, 3 * k + 2] = b

"""A draft's translucent surface (passes/draft.py; Gordon sections 6.5 and 6.6) in
numpy: a fresh install's first picture with ``opacity`` below 1 while the kernels
compile (floatcol/warmup.py).

The draft's samples (draft._samples: the same planes, a block of columns at a time)
and every pixel centre that a span of surface between two successive samples passes
over (draft.crossings): each is a crossing of that pixel's ray with the surface
(6.5), its point interpolated between the span's two samples, lit and coloured as
the opaque draft's pixels are (draft.shade: the side it turns toward the viewer, the
colour map over f's range as the kernels' layers take it, the shadow texture's
lookup with shadows, passes/draft_shadow.py). The planes go from the viewer outward,
so a pixel's crossings in plane order are front to back (6.6), and a surface alone
composites them with the ``over`` operator:

    C = sum_k T_k a c_k,    T_k = (1 - a)^k,

stopping where T falls below 1/512 (kernels/layers.py STOP), then C + T times the
background, as kernels/layers.py's picture_kernel. ``Render.intensity`` is the
layers' intensities composited over black; side, depth, shadow and the G-buffer the
nearest crossing's; ``stats["layers"]`` how many crossings each pixel's ray met.

Several surfaces (draft_translucent_layers): each layer's first crossings at a pixel,
merged with the other layers' by depth and composited front to back, each with its own
opacity, while the transmittance stays above STOP; with objects (one surface or more),
what lies over each object's depth kept apart for the objects pass, as the kernels'
composite keeps it, and the objects' shadows on every crossing.

A texture or colour field (the translucent path's texture: passes/colour.py prepare)
colours each crossing from the mip level of its pixel's footprint (_textured), and
contours and wireframes lie on it at its opacity (_lines: kernels/texture.py's
layer_lines in numpy, from translucency.layer_lines' parameters), which changes the
crossing's alpha (such a surface is composited by draft_translucent_layers, crossing by
crossing).

What it leaves out, until the kernels are there: antialiasing (a crossing covers its
pixel whole) and the halving of spans that fold or turn.
"""
from __future__ import annotations

import math

import numpy as np

from ..kernels import layout as L
from . import draft
from .geometry import check_bytes, too_large
from .overlays import grid_distance, level_distance, line_cover

#: the transmittance below which a pixel takes no more crossings (kernels/layers.py's)
STOP = 1.0 / 512.0
#: crossings a block of columns holds at once (their fields: some 20 float64 each)
BLOCK_CROSSINGS = 1 << 21

def shown(opacity):
    """How many crossings of a surface of this opacity a pixel composites: those in
    front of the transmittance's fall below STOP."""
    if opacity <= 0.0:
        return 0
    if opacity >= 1.0:
        return 1
    return int(math.ceil(math.log(STOP) / math.log1p(-opacity)))


def draft_translucent(surface, view, material, terms, box, bg8, shadows=None, source=None):
    """The draft picture of one translucent layer, top row first: (rgba, side,
    intensity, depth, tiled G-buffer, evaluations per column, w_limits, shadow or None,
    layers (H, W) int16); ``shadows`` as draft.draft_pass's, ``source`` its texture or
    colour field (passes/colour.py prepare's: a translucent one's is a texture), or
    None. Without its lines: they change each crossing's alpha, which
    draft_translucent_layers composites (renderer.py sends such a surface there)."""
    W, H = view.width, view.height
    check_bytes(W, H, W * H * draft.DRAFT_BYTES)
    try:
        return _composited(surface, view, material, terms, box, bg8, shadows, source)
    except MemoryError:
        raise ValueError(too_large(W, H, W * H * draft.DRAFT_BYTES)) from None


def _layer_colours(view, material, box, texture, source=None, domain=None):
    """One layer's (opacity, crossings shown, colours, w_limits): colours (_block's) the
    colour map over f's range (as the kernels' layers take it: hidden ones show), the
    lower side's colour, the shadow planes or None, its texture
    (translucency.layer_texture's) or None, and its contours and wireframe
    (translucency.layer_lines', over its ``domain``; None without a domain) or None."""
    from .translucency import layer_lines, layer_texture
    a = float(material.opacity)
    lut, w_lo, w_hi, w_limits = material.color_table(np.array([view.f_range]), box[2])
    _, lower_rgb = material.colors()
    planes = None
    if texture is not None:
        from .draft_shadow import shadow_planes
        planes = shadow_planes(texture)
    tex = layer_texture(source, box)
    lines = layer_lines(material, domain, box, w_limits, source) \
        if material.overlaid and domain is not None else np.zeros(0)
    return a, shown(a), ((lut, w_lo, w_hi), lower_rgb, planes, tex if tex[0].size else None,
                         lines if lines.size else None), w_limits


def _pixel_grads(view, pts, vx, vy, vz):
    """kernels/layers.py _axis_grads over arrays: (along, the view's (cos a, sin a, cos
    b, sin b)), where along(gx, gy, gz) is how much a quantity whose gradient's screen
    image is g changes from each crossing's point to the one a pixel away on the
    screen."""
    from ..kernels.layers import GRAZE
    ca, sa, cb, sb = draft._params(view)
    m = np.full(pts.shape[0], 1.0 / view.scale)
    if not view.orthographic:
        m *= (pts[:, L.G_DEPTH] + view.d3) / view.d1
    nx, ny, nz = pts[:, L.G_NX], pts[:, L.G_NY], pts[:, L.G_NZ]
    nv = nx * vx + ny * vy + nz * vz
    nv = np.where(np.abs(nv) < GRAZE, np.where(nv >= 0.0, GRAZE, -GRAZE), nv)

    def along(gx, gy, gz):
        k = (gx * vx + gy * vy + gz * vz) / nv
        return m * np.hypot(gx - nx * k, gy - ny * k)
    return along, (ca, sa, cb, sb)


def _grid_bilinear(grid, nx, ny, x, y, su, sv):
    """kernels/texture.py _grid_bilinear over arrays: (q, dq/du, dq/dv) of a grid (ny,
    nx) bilinear at grid coordinates (x, y), clamped to it."""
    x = np.clip(x, 0.0, nx - 1.0)
    y = np.clip(y, 0.0, ny - 1.0)
    i = np.minimum(y.astype(np.int64), ny - 2)
    j = np.minimum(x.astype(np.int64), nx - 2)
    fx, fy = x - j, y - i
    g00, g01, g10, g11 = grid[i, j], grid[i, j + 1], grid[i + 1, j], grid[i + 1, j + 1]
    q = (g00 * (1.0 - fx) + g01 * fx) * (1.0 - fy) + (g10 * (1.0 - fx) + g11 * fx) * fy
    qx = (g01 - g00) * (1.0 - fy) + (g11 - g10) * fy
    qy = (g10 - g00) * (1.0 - fx) + (g11 - g01) * fx
    return q, qx * su, qy * sv


def _cover(dist, grad, width):
    """overlays.line_cover, none where dist or grad is not a number (kernels/texture.py
    _line_cover)."""
    return np.where(np.isfinite(dist) & ~np.isnan(grad), line_cover(dist, grad, width), 0.0)


def _lines(view, ln, pts, vx, vy, vz):
    """kernels/texture.py layer_lines of each crossing, its gradients as _emit takes
    them (kernels/layers.py): the lines' colour premultiplied by the part of the pixel
    they cover (n, 3), and that part (n,): the wireframe's, then the contours over it."""
    from ..kernels import texture as T
    along, (ca, sa, cb, sb) = _pixel_grads(view, pts, vx, vy, vz)
    u = pts[:, L.G_U] + view.center[0]
    v = pts[:, L.G_V] + view.center[1]
    q = pts[:, L.G_W] + view.w_origin
    gu = along(cb, -sa * sb, ca * sb)           # the axes u, v, w on the screen
    gv = along(-sb, -sa * cb, ca * cb)
    gw = along(0.0, ca, sa)

    def field_grad(qu, qv):
        return along(qu * cb - qv * sb, -(qu * sb + qv * cb) * sa, (qu * sb + qv * cb) * ca)
    nlev = int(ln[T.LN_NLEV])
    fn = int(ln[T.LN_FN])
    if fn > 0:                                  # the contours are a colour field's
        grid = ln[T.LN_SIZE + nlev:T.LN_SIZE + nlev + fn * fn].reshape(fn, fn)
        q, qu, qv = _grid_bilinear(grid, fn, fn, (u - ln[T.LN_FU0]) * ln[T.LN_FSU],
                                   (v - ln[T.LN_FV0]) * ln[T.LN_FSV], ln[T.LN_FSU],
                                   ln[T.LN_FSV])
        gw = field_grad(qu, qv)
    out = np.zeros((u.size, 3))
    al = np.zeros(u.size)

    def over(k, cov):
        keep = 1.0 - cov
        for c in range(3):
            out[:, c] = cov * ln[k + c] + keep * out[:, c]
        al[:] = cov + keep * al
    wire = ln[T.LN_WIRE]
    if wire == 1.0:
        for x, x0, dx, grad in ((u, ln[T.LN_U0], ln[T.LN_DU], gu),
                                (v, ln[T.LN_V0], ln[T.LN_DV], gv)):
            over(T.LN_ER, _cover(grid_distance(x, x0, dx), grad, ln[T.LN_EW]))
    elif wire != 0.0:
        base = T.LN_SIZE + nlev + fn * fn
        nu, nw = int(ln[T.LN_NWU]), int(ln[T.LN_NWV])
        wa, wb = u, v
        if wire == 3.0:                         # a curvilinear mesh's indices
            gnx, gny = int(ln[T.LN_GNX]), int(ln[T.LN_GNY])
            ij = ln[base + nu + nw:base + nu + nw + 2 * gnx * gny].reshape(gny, gnx, 2)
            x = (u - ln[T.LN_GU0]) * ln[T.LN_GSU]
            y = (v - ln[T.LN_GV0]) * ln[T.LN_GSV]
            wa, au, av = _grid_bilinear(ij[..., 0], gnx, gny, x, y, ln[T.LN_GSU], ln[T.LN_GSV])
            wb, bu, bv = _grid_bilinear(ij[..., 1], gnx, gny, x, y, ln[T.LN_GSU], ln[T.LN_GSV])
            gu, gv = field_grad(au, av), field_grad(bu, bv)
        for levels, q_wire, grad in ((ln[base:base + nu], wa, gu),
                                     (ln[base + nu:base + nu + nw], wb, gv)):
            over(T.LN_ER, _cover(level_distance(levels, q_wire), grad, ln[T.LN_EW]))
    if nlev > 0:
        levels = ln[T.LN_SIZE:T.LN_SIZE + nlev]
        over(T.LN_CR, _cover(level_distance(levels, q), gw, ln[T.LN_CW]))
    return out, al


def _mip(tex, x, y, lod):
    """kernels/texture.py texel_at over arrays: (n, 4) the mip-map ``tex``
    (layer_texture's flat levels, offsets, shapes) looked up trilinearly at level-0
    texel coordinates (x, y) and levels of detail ``lod``."""
    from .colour import _bilinear
    flat, offsets, shapes = tex[:3]
    n_lev = offsets.shape[0]
    lod = np.clip(lod, 0.0, n_lev - 1.0)
    k = lod.astype(np.int64)
    f = lod - k
    k1 = np.minimum(k + 1, n_lev - 1)
    out = np.zeros((x.size, 4))
    for lv in np.unique(np.r_[k, k1[f > 0.0]]):
        h, w = (int(q) for q in shapes[lv])
        level = flat[int(offsets[lv]):int(offsets[lv]) + h * w * 4].reshape(h, w, 4)
        sc = 1.0 / (1 << int(lv))
        for sel, wgt in ((k == lv, 1.0 - f), ((k1 == lv) & (f > 0.0), f)):
            if sel.any():
                out[sel] += wgt[sel, None] * _bilinear(level, (x[sel] + 0.5) * sc - 0.5,
                                                       (y[sel] + 0.5) * sc - 0.5)
    return out


def _textured(view, tex, pts, s, vx, vy, vz, colours):
    """(n, 3) the crossings' colours with the texture over the sides' own
    (kernels/layers.py _emit's: the level of detail from the pixel's footprint at the
    point, 1 / scale, times the distance over d1 in perspective, over |N.V| from
    0.05; kernels/texture.py layer_texel)."""
    from ..color import lower_or_upper
    from .colour import colour_table_rgb
    (lut, w_lo, w_hi), lower_rgb = colours[:2]
    w = pts[:, L.G_W] + view.w_origin
    upper = colour_table_rgb(w, lut, w_lo, w_hi)
    own = np.where((s > 0)[:, None], upper, lower_or_upper(lower_rgb, upper))
    fp = np.full(w.shape, 1.0 / view.scale)
    if not view.orthographic:
        fp *= (pts[:, L.G_DEPTH] + view.d3) / view.d1
    nv = np.abs(pts[:, L.G_NX] * vx + pts[:, L.G_NY] * vy + pts[:, L.G_NZ] * vz)
    fp /= np.maximum(nv, 0.05)
    ou, su, ov, sv = tex[3]
    rho = fp * max(abs(su), abs(sv))
    with np.errstate(divide="ignore"):
        lod = np.where(rho > 1.0, np.log2(np.maximum(rho, 1.0)), 0.0)
    u = pts[:, L.G_U] + view.center[0]
    v = pts[:, L.G_V] + view.center[1]
    texel = _mip(tex, (u - ou) * su, (v - ov) * sv, lod)
    return texel[:, :3] + (1.0 - texel[:, 3:4]) * own


def _block(surface, view, material, terms, colours, t, cols, c0, n_show, layer=0):
    """The crossings of the columns ``cols`` (from c0) of one layer on planes t, each
    pixel's first n_show in front-to-back order: a dict of at (the pixel, rows from the
    bottom: row W + column), rows, xs (its column), rank, pts (G-buffer entries), s
    (the side seen), rgb, inten, shade (its shadow, or None); with ``hit`` (the pixels
    met, one a group: at) and ``count`` (how many crossings each), and the evaluations
    of f; None where no span crosses a pixel centre."""
    W, H = view.width, view.height
    m = cols.size
    (lut, w_lo, w_hi), lower_rgb, planes, tex, ln = colours
    smp, pair, ev = draft._samples(surface, view, cols, t)
    seg, pix = draft.crossings(smp["y"], pair, H)
    if seg.size == 0:
        return None, ev
    order = np.argsort(pix, kind="stable")         # by pixel, each front to back
    seg, pix = seg[order], pix[order]
    start = np.flatnonzero(np.r_[True, pix[1:] != pix[:-1]])
    count = np.diff(np.r_[start, pix.size])
    rank = np.arange(pix.size) - np.repeat(start, count)
    rows, c = pix // m, pix % m
    at = rows * W + c0 + c                  # the picture's pixel (rows from the bottom)
    out = dict(hit=at[start], count=count)  # (one pixel a group)
    keep = rank < n_show
    seg, rows, c, at, rank = seg[keep], rows[keep], c[keep], at[keep], rank[keep]
    pts = draft.span_points(smp, seg // m + 1, c, rows, view)
    n = pts[:, L.G_NX:L.G_NZ + 1]
    norm = np.sqrt((n * n).sum(-1, keepdims=True))
    pts[:, L.G_NX:L.G_NZ + 1] = np.where(norm > 0, n / np.where(norm > 0, norm, 1.0), 0.0)
    xs = c0 + c
    vx, vy, vz = draft.viewer_at(view, xs, rows, pts[:, L.G_DEPTH])
    s = np.where(pts[:, L.G_NX] * vx + pts[:, L.G_NY] * vy + pts[:, L.G_NZ] * vz >= 0.0,
                 1, -1).astype(np.int8)
    lit = shade_of = None
    if planes is not None:
        from .draft_shadow import shadow_of
        shade_of = shadow_of(planes, view, pts, s, layer)
        occluders = planes[0].occluders
        if occluders is not None:       # the objects' shadows (kernels/layers.py's too)
            point = np.stack([pts[:, L.G_U] + view.center[0], pts[:, L.G_V] + view.center[1],
                              pts[:, L.G_W] + view.w_origin], axis=-1)[None]
            shade_of = np.maximum(shade_of, occluders.blocked(point, (shade_of < 1.0)[None])[0])
        lit = 1.0 - shade_of
    base = None if tex is None else _textured(view, tex, pts, s, vx, vy, vz, colours)
    rgb, inten = draft.shade(view, pts, s, xs, rows, material, terms, lut, w_lo, w_hi,
                             lower_rgb, base, lit)
    if ln is not None:
        # contours and wireframe lines of the surface's opacity laid over the lit
        # crossing (kernels/layers.py _emit): its alpha and colour change
        a = float(material.opacity)
        lrgb, la = _lines(view, ln, pts, vx, vy, vz)
        keep = 1.0 - a * la
        alpha = a * la + keep * a
        rgb = (a * lrgb + keep[:, None] * (a * rgb)) / alpha[:, None]
        out["alpha"] = alpha
    out.update(at=at, rows=rows, xs=xs, rank=rank, pts=pts, s=s, rgb=rgb, inten=inten,
               shade=shade_of)
    return out, ev


def _picture(acc, trans, bg8, H, W):
    """(rgba (H, W, 4) uint8, rows from the bottom) of the crossings' sums ``acc``
    (colour times alpha) and what they let through ``trans`` over the background."""
    bg = np.asarray(bg8, dtype=np.float64) / 255.0
    rest = trans * bg[3]
    alpha = (1.0 - trans) + rest
    q = np.where(alpha > 0.0, 1.0 / np.where(alpha > 0.0, alpha, 1.0), 1.0)
    rgba = np.empty((H * W, 4), dtype=np.uint8)
    for k in range(3):
        rgba[:, k] = np.clip(np.round((acc[k] + rest * bg[k]) * q * 255.0), 0, 255)
    rgba[:, 3] = np.clip(np.round(alpha * 255.0), 0, 255)
    return rgba.reshape(H, W, 4)


def _composited(surface, view, material, terms, box, bg8, shadows, source):
    W, H = view.width, view.height
    texture, layer = shadows if shadows is not None else (None, 0)
    a, n_show, colours, w_limits = _layer_colours(view, material, box, texture, source)
    planes = colours[2]
    acc = np.zeros((4, H * W))                   # colour times alpha, intensity
    hits = np.zeros(H * W, dtype=np.int64)       # crossings met
    g = np.zeros((H, W, L.G_SIZE), dtype=np.float32)
    side = np.zeros((H, W), dtype=np.int8)
    shadow = np.full((H, W), np.nan, dtype=np.float32)
    evals = np.zeros(W, dtype=np.int64)
    t = draft._planes(view)
    block = max(1, min(draft.BLOCK_SAMPLES // max(t.size, 1), BLOCK_CROSSINGS // (4 * H)))
    for c0 in range(0, W if n_show else 0, block):
        cols = np.arange(c0, min(W, c0 + block), dtype=np.float64)
        for th in draft.halves(view, t):    # (two passes where the view looks down past
            x, ev = _block(surface, view, material, terms, colours, th, cols, c0,   # the
                           n_show, layer)                                          # nadir)
            evals[c0:c0 + cols.size] += ev // max(cols.size, 1)
            if x is not None:
                _add(x, a, acc, hits, g, side, shadow)
    trans = (1.0 - a) ** np.minimum(hits, n_show)      # what the crossings let through
    rgba = _picture(acc, trans, bg8, H, W)
    intensity = np.where(trans < 1.0, acc[3], np.nan).astype(np.float32)
    seen = side != 0
    depth = np.where(seen, g[..., L.G_DEPTH], np.inf).astype(np.float32)
    layers = np.minimum(hits, np.iinfo(np.int16).max).astype(np.int16).reshape(H, W)
    return (rgba[::-1], side[::-1], intensity.reshape(H, W)[::-1],
            depth[::-1], draft.tiled(g), evals, w_limits,
            None if planes is None else shadow[::-1], layers[::-1])


def _add(x, a, acc, hits, g, side, shadow):
    """One pass's crossings x (_block's) of one surface of opacity a into the sums acc
    and the crossings met, its nearest crossing's into g, side and shadow."""
    hits[x["hit"]] += x["count"]
    at, rank, rgb = x["at"], x["rank"], x["rgb"]
    wgt = a * (1.0 - a) ** rank                    # T_k a
    for q in range(3):
        acc[q] += np.bincount(at, wgt * rgb[:, q], minlength=hits.size)
    acc[3] += np.bincount(at, wgt * x["inten"], minlength=hits.size)
    front = rank == 0                               # the nearest crossing
    fr, fc = x["rows"][front], x["xs"][front]
    g[fr, fc] = x["pts"][front]
    side[fr, fc] = x["s"][front]
    if x["shade"] is not None:
        shadow[fr, fc] = x["shade"][front]


def draft_translucent_layers(layers, views, drawn, box, bg8, texture=None, stop=None):
    """The draft of several surfaces, one at least translucent (renderer.py's prepared
    layers, one View each from one camera; ``texture`` the light's shadow texture, not
    swept, or None): every layer's crossings (each layer's first shown(opacity) at a
    pixel) merged by depth at each pixel and composited front to back (6.6),

        C = sum_j T_j a_j c_j,    T_j = prod_{i<j} (1 - a_i),

    while T_j stays above STOP, as kernels/layers.py composite_kernel. Returns (rgba,
    side, intensity, depth, tiled G-buffer, evaluations per column, w_limits (a list),
    shadow or None, crossings met (H, W) int16, the nearest layer (H, W) int8: -1
    none, front), top row first. With objects, ``stop`` (H, W) the depth of the
    nearest at each pixel (objects.depth_map's, inf: none), front is composite_kernel's
    (front_acc (H, W, ACC_SIZE): the sums of the crossings nearer than it; opaque (H,
    W): the depth at which the transmittance falls below STOP, inf: never), else
    None."""
    view0 = views[0]
    W, H = view0.width, view0.height
    check_bytes(W, H, W * H * draft.DRAFT_BYTES * len(layers))
    try:
        return _merged(layers, views, drawn, box, bg8, texture, stop)
    except MemoryError:
        raise ValueError(too_large(W, H, W * H * draft.DRAFT_BYTES * len(layers))) from None


def _merged(layers, views, drawn, box, bg8, texture, stop):
    W, H = views[0].width, views[0].height
    if stop is not None:
        from ..kernels.layers import ACC_A, ACC_B, ACC_G, ACC_I, ACC_R, ACC_SIZE
        z_stop = np.asarray(stop, dtype=np.float64)[::-1].ravel()   # (rows from the bottom)
        front_acc = np.zeros((ACC_SIZE, H * W))
        front_trans = np.ones(H * W)
        opaque = np.full(H * W, np.inf)
    n = len(layers)
    info = [_layer_colours(view, p.material, box, texture, p.source, p.domain)
            for p, view in zip(layers, views)]
    ts = [draft._planes(view) for view in views]
    acc = np.zeros((4, H * W))
    trans = np.ones(H * W)
    hits = np.zeros(H * W, dtype=np.int64)
    g = np.zeros((H, W, L.G_SIZE), dtype=np.float32)
    side = np.zeros((H, W), dtype=np.int8)
    which = np.full((H, W), -1, dtype=np.int8)
    shadow = np.full((H, W), np.nan, dtype=np.float32)
    evals = np.zeros(W, dtype=np.int64)
    most = max(t.size for t in ts)
    block = max(1, min(draft.BLOCK_SAMPLES // max(most, 1), BLOCK_CROSSINGS // (4 * H * n)))
    for c0 in range(0, W, block):
        cols = np.arange(c0, min(W, c0 + block), dtype=np.float64)
        parts = []
        for k, (p, view, (surface, _)) in enumerate(zip(layers, views, drawn)):
            a, n_show, colours, _ = info[k]
            if n_show == 0:             # (not drawn, nor its crossings counted)
                continue
            for th in draft.halves(view, ts[k]):    # (two passes past the nadir)
                x, ev = _block(surface, view, p.material, p.terms, colours, th, cols, c0,
                               n_show, k)
                evals[c0:c0 + cols.size] += ev // max(cols.size, 1)
                if x is None:
                    continue
                hits[x["hit"]] += x["count"]
                x["a"] = x.pop("alpha", np.full(x["at"].size, a))
                x["layer"] = np.full(x["at"].size, k, dtype=np.int8)
                if x["shade"] is None:
                    x["shade"] = np.full(x["at"].size, np.nan)
                parts.append(x)
        if not parts:
            continue
        x = {name: np.concatenate([q[name] for q in parts])
             for name in ("at", "rows", "xs", "pts", "s", "rgb", "inten", "shade", "a", "layer")}
        order = np.lexsort((x["pts"][:, L.G_DEPTH], x["at"]))   # by pixel, near to far
        x = {name: v[order] for name, v in x.items()}
        at, a = x["at"], x["a"]
        start = np.flatnonzero(np.r_[True, at[1:] != at[:-1]])
        count = np.diff(np.r_[start, at.size])
        rank = np.arange(at.size) - np.repeat(start, count)
        # T before each crossing: the product of what the nearer ones let through
        t_before = np.ones(at.size)
        for r in range(1, int(count.max())):
            j = start[count > r] + r
            t_before[j] = t_before[j - 1] * (1.0 - a[j - 1])
        keep = t_before >= STOP
        wgt = np.where(keep, t_before * a, 0.0)
        for q in range(3):
            acc[q] += np.bincount(at, wgt * x["rgb"][:, q], minlength=H * W)
        acc[3] += np.bincount(at, wgt * x["inten"], minlength=H * W)
        np.multiply.at(trans, at[keep], 1.0 - a[keep])
        if stop is not None:            # what lies over the objects, and where none shows
            over = keep & (x["pts"][:, L.G_DEPTH] < z_stop[at])
            for q, val in ((ACC_R, x["rgb"][:, 0]), (ACC_G, x["rgb"][:, 1]),
                           (ACC_B, x["rgb"][:, 2]), (ACC_I, x["inten"])):
                front_acc[q] += np.bincount(at, np.where(over, wgt * val, 0.0),
                                            minlength=H * W)
            np.multiply.at(front_trans, at[over], 1.0 - a[over])
            last = keep & (t_before * (1.0 - a) < STOP)
            opaque[at[last]] = x["pts"][last, L.G_DEPTH]
        front = rank == 0                               # the nearest crossing
        fr, fc = x["rows"][front], x["xs"][front]
        g[fr, fc] = x["pts"][front]
        side[fr, fc] = x["s"][front]
        which[fr, fc] = x["layer"][front]
        shadow[fr, fc] = x["shade"][front]
    rgba = _picture(acc, trans, bg8, H, W)
    intensity = np.where(trans < 1.0, acc[3], np.nan).astype(np.float32)
    seen = side != 0
    depth = np.where(seen, g[..., L.G_DEPTH], np.inf).astype(np.float32)
    met = np.minimum(hits, np.iinfo(np.int16).max).astype(np.int16).reshape(H, W)
    front = None
    if stop is not None:
        front_acc[ACC_A] = 1.0 - front_trans
        front = (np.ascontiguousarray(front_acc.T.reshape(H, W, ACC_SIZE)[::-1]),
                 opaque.reshape(H, W)[::-1].astype(np.float32))
    return (rgba[::-1], side[::-1], intensity.reshape(H, W)[::-1], depth[::-1],
            draft.tiled(g), evals, [q[3] for q in info],
            None if texture is None else shadow[::-1], met[::-1], which[::-1], front)

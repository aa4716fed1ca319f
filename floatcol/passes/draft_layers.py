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

What it leaves out, until the kernels are there: antialiasing (a crossing covers its
pixel whole), the halving of spans that fold or turn, textures, colour fields and
lines (those pictures wait for the kernels), several surfaces.
"""
from __future__ import annotations

import math

import numpy as np

from ..kernels import layout as L
from . import draft
from .geometry import check_bytes, too_large

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


def draft_translucent(surface, view, material, terms, box, bg8, shadows=None):
    """The draft picture of one translucent layer, top row first: (rgba, side,
    intensity, depth, tiled G-buffer, evaluations per column, w_limits, shadow or None,
    layers (H, W) int16); ``shadows`` as draft.draft_pass's."""
    W, H = view.width, view.height
    check_bytes(W, H, W * H * draft.DRAFT_BYTES)
    try:
        return _composited(surface, view, material, terms, box, bg8, shadows)
    except MemoryError:
        raise ValueError(too_large(W, H, W * H * draft.DRAFT_BYTES)) from None


def _composited(surface, view, material, terms, box, bg8, shadows):
    W, H = view.width, view.height
    a = float(material.opacity)
    n_show = shown(a)           # (0: the surface is not drawn, nor its crossings counted)
    # (the colour map over f's range, as the kernels' layers: hidden ones show)
    lut, w_lo, w_hi, w_limits = material.color_table(np.array([view.f_range]), box[2])
    _, lower_rgb = material.colors()
    planes = None
    if shadows is not None:
        from .draft_shadow import shadow_planes
        planes = shadow_planes(shadows[0])
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
        m = cols.size
        smp, pair, ev = draft._samples(surface, view, cols, t)
        evals[c0:c0 + m] = ev // max(m, 1)
        seg, pix = draft.crossings(smp["y"], pair, H)
        if seg.size == 0:
            continue
        order = np.argsort(pix, kind="stable")         # by pixel, each front to back
        seg, pix = seg[order], pix[order]
        start = np.flatnonzero(np.r_[True, pix[1:] != pix[:-1]])
        count = np.diff(np.r_[start, pix.size])
        rank = np.arange(pix.size) - np.repeat(start, count)
        rows, c = pix // m, pix % m
        at = rows * W + c0 + c                  # the picture's pixel (rows from the bottom)
        hits[at[start]] += count                # (one pixel a group)
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
            shade_of = shadow_of(planes, view, pts, s)
            lit = 1.0 - shade_of
        rgb, inten = draft.shade(view, pts, s, xs, rows, material, terms, lut, w_lo, w_hi,
                                 lower_rgb, None, lit)
        wgt = a * (1.0 - a) ** rank                    # T_k a
        for q in range(3):
            acc[q] += np.bincount(at, wgt * rgb[:, q], minlength=H * W)
        acc[3] += np.bincount(at, wgt * inten, minlength=H * W)
        front = rank == 0                               # the nearest crossing
        fr, fc = rows[front], xs[front]
        g[fr, fc] = pts[front]
        side[fr, fc] = s[front]
        if shade_of is not None:
            shadow[fr, fc] = shade_of[front]
    trans = (1.0 - a) ** np.minimum(hits, n_show)      # what the crossings let through
    bg = np.asarray(bg8, dtype=np.float64) / 255.0
    rest = trans * bg[3]
    alpha = (1.0 - trans) + rest
    q = np.where(alpha > 0.0, 1.0 / np.where(alpha > 0.0, alpha, 1.0), 1.0)
    rgba = np.empty((H * W, 4), dtype=np.uint8)
    for k in range(3):
        rgba[:, k] = np.clip(np.round((acc[k] + rest * bg[k]) * q * 255.0), 0, 255)
    rgba[:, 3] = np.clip(np.round(alpha * 255.0), 0, 255)
    intensity = np.where(trans < 1.0, acc[3], np.nan).astype(np.float32)
    seen = side != 0
    depth = np.where(seen, g[..., L.G_DEPTH], np.inf).astype(np.float32)
    layers = np.minimum(hits, np.iinfo(np.int16).max).astype(np.int16).reshape(H, W)
    return (rgba.reshape(H, W, 4)[::-1], side[::-1], intensity.reshape(H, W)[::-1],
            depth[::-1], draft.tiled(g), evals, w_limits,
            None if planes is None else shadow[::-1], layers[::-1])

"""The composite pass (Gordon 6.5): several layers of one camera merged front to back
by the depth of the surface seen at each pixel's centre; a pixel a layer covers only
in part (an antialiased silhouette) has no depth at its centre for that layer: it is
put behind the layers that cover the centre, so a hidden silhouette never shows
through."""
from __future__ import annotations

import numpy as np

from .. import color
from ..kernels.composite import composite_kernel
from ..kernels.layout import G_DEPTH, G_W
from ..result import Render
from .tiles import tile, untile


def composite(renders, background=(255, 255, 255, 255)) -> Render:
    """Combine Renders of one camera (and size), each over a transparent background,
    front to back by the depth of the surface at each pixel's centre (partial,
    centre-less coverage behind), over ``background`` (an RGBA uint8 quadruple or
    colour). A surface hides what lies behind it even where it is transparent in its
    own picture (between the lines of a line drawing); a translucent one (opacity
    below 1) lets what lies behind its nearest layer show through as its picture's
    alpha says (exact where all its layers lie in front of the others'; render_many
    merges the layers themselves, section 6.6). Returns a Render as
    :func:`render_many` describes."""
    if not renders:
        raise ValueError("nothing to composite")
    shape = renders[0].rgba.shape
    if any(r.rgba.shape != shape for r in renders):
        raise ValueError("composite needs renders of one size")
    if isinstance(background, np.ndarray):
        background = tuple(int(x) for x in background)
    bg8 = color.to_rgba8(background)
    # the depth of the surface at each pixel's centre (for a line drawing, the surface
    # behind the lines too: it hides what lies behind it, lines or not)
    W = shape[1]
    seen_k = np.stack([r._mask() for r in renders])              # (n, H, W)
    depth = np.stack([np.where(m, untile(r._gbuf[..., G_DEPTH], W)[::-1], np.inf)
                      for r, m in zip(renders, seen_k)])
    out = np.empty(shape, dtype=np.uint8)
    which = np.empty(shape[:2], dtype=np.int8)
    # a translucent render (its layers composited: translucency.py) hides no more
    # than its picture's alpha: what lies behind its nearest layer shows through
    hides = np.stack([np.zeros_like(m) if r.stats.get("translucent") else m
                      for r, m in zip(renders, seen_k)])
    composite_kernel(depth, np.stack([r.rgba for r in renders]), hides,
                     bg8.astype(np.float64) / 255.0, out, which)
    seen = which >= 0

    def pick(name):
        x = getattr(renders[0], name).copy()
        for k, r in enumerate(renders[1:], start=1):
            mask = which == k
            x[mask] = getattr(r, name)[mask]
        return x

    intensity = np.where(seen, pick("intensity"), np.float32(np.nan)).astype(np.float32)
    side = np.where(seen, pick("side"), 0).astype(np.int8)
    depth_out = np.where(seen, pick("depth"), np.inf).astype(np.float32)
    shadow = None
    if any(r.shadow is not None for r in renders):
        shadows = [r.shadow if r.shadow is not None
                   else np.where(r.side != 0, 0.0, np.nan).astype(np.float32) for r in renders]
        shadow = shadows[0].copy()
        for k in range(1, len(renders)):
            shadow[which == k] = shadows[k][which == k]
        shadow = np.where(seen, shadow, np.float32(np.nan)).astype(np.float32)
    gbuf = renders[0]._gbuf.copy()
    w0 = renders[0].view.w_origin
    for k, r in enumerate(renders[1:], start=1):
        mask = tile((which == k)[::-1], gbuf.shape[2], gbuf.shape[0])
        gbuf[mask] = r._gbuf[mask]
        if r.view.w_origin != w0:        # (its w from its own origin: layout.py G_W)
            gbuf[mask, G_W] += np.float32(r.view.w_origin - w0)
    stats = {"samples": sum(int(r.stats["samples"]) for r in renders),
             "seconds": sum(r.stats["seconds"] for r in renders),
             "surfaces": len(renders), "surface": which,
             "method": renders[0].stats.get("method"),
             "w_limits": [r.stats.get("w_limits") for r in renders],
             # whether each layer shows its upper side in its own picture (the heights
             # its colormap spans come from there: cluster.py's posters)
             "upper_seen": [bool((r.side == 1).any()) for r in renders],
             "box": renders[0].box}
    return Render(out, intensity, side, depth_out, stats, renders[0].view, gbuf, None, seen,
                  box=renders[0].box, shadow=shadow)

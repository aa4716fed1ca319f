"""The composite pass (Gordon 6.5): several layers of one camera merged front to back
by the depth of the surface seen at each pixel's centre; a pixel a layer covers only
in part (an antialiased silhouette) has no depth at its centre for that layer: it is
put behind the layers that cover the centre, so a hidden silhouette never shows
through."""
from __future__ import annotations

import numpy as np

from .. import color
from ..kernels.layout import G_DEPTH
from ..result import Render
from .tiles import tile, untile


def composite(renders, background=(255, 255, 255, 255)) -> Render:
    """Combine Renders of one camera (and size), each over a transparent background,
    front to back by the depth of the surface at each pixel's centre (partial,
    centre-less coverage behind), over ``background`` (an RGBA uint8 quadruple or
    colour). A surface hides what lies behind it even where it is transparent in its
    own picture (between the lines of a line drawing). Returns a Render as
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
    order = np.argsort(depth, axis=0, kind="stable")             # nearest first
    rgba = np.stack([r.rgba for r in renders]).astype(np.float64) / 255.0
    acc = np.zeros(shape[:2] + (3,))
    acc_a = np.zeros(shape[:2])
    hidden = np.zeros(shape[:2])          # how much of the pixel nearer layers cover
    for k in range(len(renders)):
        layer = np.take_along_axis(rgba, order[k][None, ..., None], axis=0)[0]
        opaque = np.take_along_axis(seen_k, order[k][None], axis=0)[0]
        a = layer[..., 3] * (1.0 - hidden)
        acc += layer[..., :3] * a[..., None]
        acc_a += a
        hidden += (1.0 - hidden) * np.maximum(layer[..., 3], opaque)
    bg = bg8.astype(np.float64) / 255.0
    rest = (1.0 - acc_a) * bg[3]
    alpha = acc_a + rest
    rgb = (acc + rest[..., None] * bg[:3]) / np.where(alpha > 0, alpha, 1.0)[..., None]
    out = np.empty(shape, dtype=np.uint8)
    out[..., :3] = np.clip(np.round(rgb * 255.0), 0, 255)
    out[..., 3] = np.clip(np.round(alpha * 255.0), 0, 255)

    nearest = order[0]
    seen = np.isfinite(np.take_along_axis(depth, nearest[None], axis=0)[0])
    which = np.where(seen, nearest, -1).astype(np.int8)

    def pick(name):
        arrays = np.stack([getattr(r, name) for r in renders])
        return np.take_along_axis(arrays, nearest[None], axis=0)[0]

    intensity = np.where(seen, pick("intensity"), np.float32(np.nan)).astype(np.float32)
    side = np.where(seen, pick("side"), 0).astype(np.int8)
    depth_out = np.where(seen, pick("depth"), np.inf).astype(np.float32)
    shadow = None
    if any(r.shadow is not None for r in renders):
        shadows = np.stack([r.shadow if r.shadow is not None
                            else np.where(r.side != 0, 0.0, np.nan).astype(np.float32)
                            for r in renders])
        shadow = np.where(seen, np.take_along_axis(shadows, nearest[None], axis=0)[0],
                          np.float32(np.nan)).astype(np.float32)
    gbuf = renders[0]._gbuf.copy()
    for k, r in enumerate(renders[1:], start=1):
        mask = tile((which == k)[::-1], gbuf.shape[2], gbuf.shape[0])
        gbuf[mask] = r._gbuf[mask]
    stats = {"samples": sum(int(r.stats["samples"]) for r in renders),
             "seconds": sum(r.stats["seconds"] for r in renders),
             "surfaces": len(renders), "surface": which,
             "method": renders[0].stats.get("method"),
             "w_limits": [r.stats.get("w_limits") for r in renders],
             "box": renders[0].box}
    return Render(out, intensity, side, depth_out, stats, renders[0].view, gbuf, None, seen,
                  box=renders[0].box, shadow=shadow)

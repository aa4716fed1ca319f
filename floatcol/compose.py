"""Several surfaces in one picture: one camera for all, composited by depth.

Each surface is rendered by :func:`floatcol.render` from the same camera (the scale,
centre and, in perspective, d1/d2 fitted to all of them together) over a transparent
background; the pictures are then combined per pixel front to back by the depth of
the surface seen at the pixel's centre, so the surfaces hide each other correctly
where they overlap or cross. A pixel that a surface covers only in part (an
antialiased silhouette) has no depth at its centre for that surface: it is put behind
the surfaces that cover the centre, so a hidden silhouette never shows through.
"""
from __future__ import annotations

import math
import time

import numpy as np

from . import color
from .kernels.layout import G_DEPTH
from .render import (
    NO_BOX, Render, _boxed, _check_box, _domain, _untile, box_factors, box_point,
    default_background, render)
from .surface import as_surface
from .view import _fit, build_view, viewpoint_distances


def render_many(surfaces, size=(400, 300), elev=30.0, azim=30.0, projection="orthographic",
                d1=None, d2=None, scale=None, center=None, *, background=None, vars=None,
                focal_length=None, **options) -> Render:
    """Render several surfaces w = f(u, v) into one picture.

    Parameters
    ----------
    surfaces : a list of expressions (strings, sympy expressions, callables, Surfaces
        or HeightFields) or of (expr, u, v) triples giving each its own domain.
    size, elev, azim, projection, d1, d2, scale, center, focal_length : the one camera,
        as :func:`floatcol.render`; left as None they are fitted to all the surfaces.
    background : the picture's background (default white, black for
        shading="lambert").
    **options : any other :func:`floatcol.render` option, the same for every surface
        (shading, cmap, vmin, vmax, light, antialias, ...). Each surface takes the
        colormap over its own seen heights unless vmin/vmax say otherwise.

    Returns
    -------
    Render
        the composite: ``rgba``, and ``intensity``, ``side``, ``depth``, ``u``, ``v``,
        ``w``, ``normal`` of the nearest surface at each pixel; ``stats["samples"]``
        and ``["seconds"]`` of all of them, ``stats["surface"]`` (H, W) int8 the index of
        the surface seen at each pixel (-1: none).
    """
    t_start = time.perf_counter()
    items = _items(surfaces, vars)
    if background is None:
        background = default_background(options.get("method", "column"),
                                        options.get("shading", "default"))
    bg8 = color.to_rgba8(background)
    box = options.pop("box", None)
    aspect = options.pop("aspect", "equal")
    box = joint_box(items, aspect) if box is None else _check_box(box)
    cam = _joint_camera(items, size, elev, azim, projection, d1, d2, scale, center,
                        focal_length, box)
    renders = [render(s, u=dom[0], v=dom[1], size=size, elev=elev, azim=azim,
                      projection=projection, background=(0, 0, 0, 0), box=box, **cam,
                      **options)
               for s, dom in items]
    out = composite(renders, bg8)
    out.stats["seconds"] = time.perf_counter() - t_start
    return out


def _items(surfaces, vars):
    if isinstance(surfaces, (str, bytes)) or not hasattr(surfaces, "__iter__"):
        raise ValueError("surfaces must be a list of expressions or of (expr, u, v) triples, "
                         f"got {surfaces!r}")
    items = []
    for item in surfaces:
        if isinstance(item, tuple) and len(item) == 3:
            expr, u, v = item
        else:
            expr, u, v = item, None, None
        s = as_surface(expr, vars)
        items.append((s, _domain(s, u, v)))
    if not items:
        raise ValueError("surfaces is empty: give at least one expression")
    return items


def joint_box(items, aspect):
    """render's box stretch (a, b, c) for ``aspect`` shared by several (surface,
    domain) items: that of the union of their domains and of the ranges of f."""
    if isinstance(aspect, str) and aspect == "equal":
        return NO_BOX
    ranges = [_fit(s, dom)["range"] for s, dom in items]
    union = tuple((min(d[k][0] for _, d in items), max(d[k][1] for _, d in items))
                  for k in (0, 1))
    return box_factors(aspect, None, union, (min(lo for lo, _ in ranges),
                                             max(hi for _, hi in ranges)))


def _joint_camera(items, size, elev, azim, projection, d1, d2, scale, center, focal_length,
                  box=NO_BOX):
    """scale, center, d1, d2 that fit every surface (render()'s rules, on the union),
    for the surfaces stretched by ``box`` (joint_box); center in the surfaces' units."""
    if box != NO_BOX:
        items = [_boxed(s, dom, None, box)[:2] for s, dom in items]
        center = box_point(center, box)
    cam = _fitted_camera(items, size, elev, azim, projection, d1, d2, scale, center,
                         focal_length)
    if box != NO_BOX:
        cam["center"] = tuple(x / k for x, k in zip(cam["center"], box))
    return cam


def _fitted_camera(items, size, elev, azim, projection, d1, d2, scale, center, focal_length):
    """_joint_camera's camera for surfaces as they are drawn (already stretched)."""
    views = [build_view(s, dom, size, elev, azim, projection, d1, d2, scale, "auto", None,
                        None, focal_length) for s, dom in items]
    if center is None or (isinstance(center, str) and center == "auto"):
        # the middle of the union of the domains and of the ranges of f
        (u_lo, u_hi), (v_lo, v_hi), (w_lo, w_hi) = (
            (min(lo for lo, _ in spans), max(hi for _, hi in spans))
            for spans in ([v.domain[0] for v in views], [v.domain[1] for v in views],
                          [v.f_range for v in views]))
        center = (0.5 * (u_lo + u_hi), 0.5 * (v_lo + v_hi), 0.5 * (w_lo + w_hi))
    cam = {"center": center, "d1": views[0].d1, "d2": views[0].d2}
    if not views[0].orthographic and d1 is None and d2 is None:
        # render()'s rule on the joint radius: the same viewpoint for every surface
        cam["d1"], cam["d2"] = viewpoint_distances(max(_radius(v, center) for v in views),
                                                   focal_length=focal_length)
    if scale is None:
        scale = min(build_view(s, dom, size, elev, azim, projection, cam["d1"], cam["d2"],
                               None, center).scale for s, dom in items)
    cam["scale"] = scale
    return cam


def _radius(view, center):
    """Distance from ``center`` to the farthest corner of a view's domain times the
    range of f on its fitting grid."""
    (ua, ub), (va, vb) = view.domain
    w_lo, w_hi = view.f_range
    return max(math.dist(center, (u, v, w)) for u in (ua, ub) for v in (va, vb)
               for w in (w_lo, w_hi))


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
    depth = np.stack([np.where(m, _untile(r._gbuf[..., G_DEPTH], W)[::-1], np.inf)
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
    gbuf = renders[0]._gbuf.copy()
    for k, r in enumerate(renders[1:], start=1):
        mask = _tile((which == k)[::-1], gbuf.shape[2], gbuf.shape[0])
        gbuf[mask] = r._gbuf[mask]
    stats = {"samples": sum(int(r.stats["samples"]) for r in renders),
             "seconds": sum(r.stats["seconds"] for r in renders),
             "surfaces": len(renders), "surface": which,
             "method": renders[0].stats.get("method"),
             "w_limits": [r.stats.get("w_limits") for r in renders],
             "box": renders[0].box}
    return Render(out, intensity, side, depth_out, stats, renders[0].view, gbuf, None, seen,
                  box=renders[0].box)


def _tile(mask, tile, n_tiles):
    """(H, W) -> (n_tiles, H, tile): a picture-shaped mask in the G-buffer's tiles
    (kernels/layout.py), rows as given; padding columns False."""
    H, W = mask.shape
    padded = np.zeros((H, n_tiles * tile), dtype=bool)
    padded[:, :W] = mask
    return padded.reshape(H, n_tiles, tile).transpose(1, 0, 2)

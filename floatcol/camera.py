"""Camera: where the picture is seen from, and the one camera fit.

A :class:`Camera` holds the picture's size, the view angles, the projection and its
distances (d1, d2 or matplotlib's focal length), the scale and centre (None: fitted)
and the box (``aspect`` or explicit ``box`` stretch factors). :func:`fit` turns a
camera and the layers of a scene into one :class:`~floatcol.view.View` per layer:
the same scale, centre and viewpoint for all of them, fitted to their union. render,
render_many, plot_surface (zoom), animate and the CLI all fit through it.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

from .view import _fit, build_view, viewpoint_distances

#: No stretch: u, v and w in true proportions (aspect="equal")
NO_BOX = (1.0, 1.0, 1.0)
#: The proportions of aspect="auto"'s box: matplotlib's default box aspect
DEFAULT_BOX = (4.0, 4.0, 3.0)
ASPECTS = ("equal", "auto", "equalxy")


@dataclass
class Camera:
    """size (width, height) in pixels; elev, azim in degrees (the paper's angles:
    alpha = -elev, beta = azim); projection "orthographic" or "perspective" with d1,
    d2 (eqs. 9-10) or ``focal_length``; scale (pixels per unit) and center (a world
    point at the picture's centre) fitted when None; the box: ``aspect`` ("equal",
    "auto", "equalxy" or proportions) or ``box`` stretch factors (a, b, c)."""
    size: Any = (400, 300)
    elev: float = 30.0
    azim: float = 30.0
    projection: str = "orthographic"
    d1: float | None = None
    d2: float | None = None
    scale: float | None = None
    center: Any = None
    focal_length: float | None = None
    aspect: Any = "equal"
    box: Any = None
    #: (first, count): draw only these columns of the picture (a band of a tiled
    #: poster, floatcol/cluster.py): the camera is fitted to the whole size
    columns: Any = None


def box_factors(aspect, surface, domain, w_range=None):
    """(a, b, c): how much render's ``aspect`` stretches u, v and w (a = 1: u keeps
    its units). The range of f is its robust range on the fit grid (a pole does
    not flatten the box) unless ``w_range`` gives it; a flat f keeps c = 1."""
    if isinstance(aspect, str):
        if aspect not in ASPECTS:
            raise ValueError(f"aspect must be one of {', '.join(map(repr, ASPECTS))} or box "
                             f"proportions (bu, bv, bw), got {aspect!r}")
        if aspect == "equal":
            return NO_BOX
    (ua, ub), (va, vb) = domain
    du, dv = ub - ua, vb - va
    if isinstance(aspect, str) and aspect == "auto":
        bu, bv, bw = DEFAULT_BOX
    elif isinstance(aspect, str):                     # equalxy
        longest = max(du, dv)
        bu, bv, bw = du / longest, dv / longest, DEFAULT_BOX[2] / DEFAULT_BOX[0]
    else:
        try:
            bu, bv, bw = (float(x) for x in aspect)
        except (TypeError, ValueError):
            raise ValueError("aspect must be 'equal', 'auto', 'equalxy' or box proportions "
                             f"(bu, bv, bw), got {aspect!r}") from None
        if not all(math.isfinite(x) and x > 0 for x in (bu, bv, bw)):
            raise ValueError(f"aspect's box proportions must be positive numbers, got {aspect!r}")
    if w_range is None:
        w_range = _fit(surface, domain)["range"]
    dw = float(w_range[1]) - float(w_range[0])
    b = bv / bu * du / dv
    c = bw / bu * du / dw if dw > 0 else 1.0
    if not (math.isfinite(c) and c > 0.0):       # a range too small to divide by
        c = 1.0
    return (1.0, b, c)


def check_box(box):
    try:
        a, b, c = (float(x) for x in box)
    except (TypeError, ValueError):
        raise ValueError(f"box must be stretch factors (a, b, c), got {box!r}") from None
    if not all(math.isfinite(x) and x > 0 for x in (a, b, c)):
        raise ValueError(f"box's stretch factors must be positive numbers, got {box!r}")
    return a, b, c


def in_box(surface, domain, center, aspect, box):
    """(surface, domain, center, box) as render draws them: stretched by ``box`` (a, b,
    c) if given, else by ``aspect``'s (box_factors); unchanged for true proportions."""
    box = box_factors(aspect, surface, domain) if box is None else check_box(box)
    if box == NO_BOX:
        return surface, domain, center, box
    return (*boxed(surface, domain, center, box), box)


def boxed(surface, domain, center, box):
    """(surface, domain, center) stretched by box's (a, b, c) (box_factors): what
    the kernels draw for render's ``aspect``."""
    a, b, c = box
    (ua, ub), (va, vb) = domain
    return surface.scaled(a, b, c), ((ua * a, ub * a), (va * b, vb * b)), \
        box_point(center, box)


def box_point(center, box):
    """A point (u, v, w) in the box of ``box`` (box_factors); None or a string as
    is (and anything else, for build_view to say what is wrong with it)."""
    if isinstance(center, (str, type(None))):
        return center
    try:
        return tuple(float(x) * k for x, k in zip(center, box, strict=True))
    except (TypeError, ValueError):
        return center


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


def joint_camera(items, size, elev, azim, projection, d1, d2, scale, center, focal_length,
                 box=NO_BOX):
    """scale, center, d1, d2 that fit every surface (render()'s rules, on the union),
    for the surfaces stretched by ``box`` (joint_box); center in the surfaces' units."""
    if box != NO_BOX:
        items = [boxed(s, dom, None, box)[:2] for s, dom in items]
        center = box_point(center, box)
    cam = _fitted_camera(items, size, elev, azim, projection, d1, d2, scale, center,
                         focal_length)
    if box != NO_BOX:
        cam["center"] = tuple(x / k for x, k in zip(cam["center"], box))
    return cam


def _fitted_camera(items, size, elev, azim, projection, d1, d2, scale, center, focal_length):
    """joint_camera's camera for surfaces as they are drawn (already stretched)."""
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


def fit(layers, camera, quality, light_dir=None, joint=False):
    """The camera fit, for one layer or many: (views, drawn, box) with one View per
    layer (the same scale, centre and viewpoint for all), the (surface, domain) pairs
    as the kernels draw them (stretched by the box), and the box's stretch (a, b, c).
    ``layers``: (surface, domain) pairs; ``light_dir`` the kernels' light (a screen
    direction, None: the headlight). ``joint``: fit one layer as several are (the
    union's rules), as render_many does."""
    cam = camera
    if len(layers) == 1 and not joint:
        surface, domain = layers[0]
        s, dom, center, box = in_box(surface, domain, cam.center, cam.aspect, cam.box)
        view = build_view(s, dom, cam.size, cam.elev, cam.azim, cam.projection, cam.d1,
                          cam.d2, cam.scale, center, quality.step, light_dir,
                          cam.focal_length, quality.pixel_step, quality.placement)
        return [view], [(s, dom)], box
    box = joint_box(layers, cam.aspect) if cam.box is None else check_box(cam.box)
    fitted = joint_camera(layers, cam.size, cam.elev, cam.azim, cam.projection, cam.d1,
                          cam.d2, cam.scale, cam.center, cam.focal_length, box)
    views, drawn = [], []
    for surface, domain in layers:
        s, dom, center, _ = in_box(surface, domain, fitted["center"], cam.aspect, box)
        views.append(build_view(s, dom, cam.size, cam.elev, cam.azim, cam.projection,
                                fitted["d1"], fitted["d2"], fitted["scale"], center,
                                quality.step, light_dir, None, quality.pixel_step,
                                quality.placement))
        drawn.append((s, dom))
    # one origin of the G-buffer's w for all (their G-buffers are merged: layout.py
    # G_W): the shared centre's where any layer's needs it
    origin = views[0].center[2] if any(v.w_origin != 0.0 for v in views) else 0.0
    views = [dataclasses.replace(v, w_org=float(origin)) for v in views]
    return views, drawn, box


def fly(surface, position, heading=0.0, pitch=-10.0, fov=60.0, size=(1280, 720),
        above=None, near=None):
    """A fly-through camera (Guedes 1997): the eye at ``position`` inside the scene,
    looking along compass ``heading`` (degrees clockwise from +v, "north") and
    ``pitch`` (degrees, negative down) with a horizontal field of view ``fov``; the
    view plane is tilted with the pitch (his non-vertical view plane). Returns the
    keywords of render() that place it: projection, elev, azim, center, d1, d2,
    scale, size, step, and sampling="march": a point-sampled view (antialias=False)
    of a height field by each pixel's ray marched through planes a pixel's footprint
    apart over the height field's pyramid (passes/march.py), an antialiased view or a
    function surface by the level-of-detail engine over the same planes and levels
    (passes/lod.py, its area weights); a 1280x720 view over a 4097^2 DEM takes about
    0.1 s point sampled, 0.16-0.18 s area sampled, where the exact column pass with
    adaptive planes takes 1.8-3.2 s. Set sampling="lod" in the dict for the
    level-of-detail engine's point samples too, or sampling="adaptive" for the exact
    surface everywhere (docs/terrain.md compares them).

    position: (u, v, w), or (u, v) inside the domain with the eye ``above``
        (default: 5 % of the domain's longer side) the surface there.
    near: the near clipping distance (the screen plane, d1; default 1/1000 of the
        domain's longer side): nearer points are not drawn.
    The sampling planes start a pixel's footprint apart where the lowest ray of the
    picture meets the ground under the eye (render's ``step``); with
    ``antialias="area"`` they grow with distance (kernels/area.py); with
    ``sampling="lod"`` or ``"march"`` the planes and levels follow the footprint.
    """
    from .surface import as_surface
    from .view import _number, check_size
    s = as_surface(surface)
    domain = s.default_domain or ((-10.0, 10.0), (-10.0, 10.0))
    (ua, ub), (va, vb) = domain
    side = max(ub - ua, vb - va)
    try:
        pos = [_number("position", p) for p in position]
    except TypeError:
        raise ValueError(f"position must be (u, v, w) or (u, v), got {position!r}") from None
    if len(pos) not in (2, 3):
        raise ValueError(f"position must be (u, v, w) or (u, v), got {position!r}")
    heading = _number("heading", heading)
    pitch = _number("pitch", pitch)
    if not -89.0 <= pitch <= 89.0:
        raise ValueError(f"pitch must be between -89 and 89 degrees, got {pitch}")
    fov = _number("fov", fov)
    if not 1.0 <= fov <= 170.0:
        raise ValueError(f"fov must be between 1 and 170 degrees, got {fov}")
    W, H = check_size(size)
    import numpy as np
    ground = float(s.evaluate(np.array([pos[0]]), np.array([pos[1]]))[0])
    if len(pos) == 2:
        if not (ua <= pos[0] <= ub and va <= pos[1] <= vb):
            # (no ground there to be above: the eye would be placed at w = 0 + above,
            # under a DEM at 3000 m, or looking at nothing)
            raise ValueError(f"position ({pos[0]:g}, {pos[1]:g}) lies outside the surface "
                             f"(u {ua:g} to {ub:g}, v {va:g} to {vb:g}): give a point "
                             f"inside it, or the eye's height too, (u, v, w)")
        rise = 0.05 * side if above is None else _number("above", above, positive=True)
        pos.append((ground if np.isfinite(ground) else 0.0) + rise)
    d1 = 1e-3 * side if near is None else _number("near", near, positive=True)
    d2 = d1
    # eqs. (1)-(2): the screen's z axis (the view direction) is (ca sb, ca cb, sa) in
    # (u, v, w): beta = heading, alpha = pitch (elev = -pitch)
    a, b = math.radians(pitch), math.radians(heading)
    view = (math.cos(a) * math.sin(b), math.cos(a) * math.cos(b), math.sin(a))
    center = tuple(p + (d1 + d2) * c for p, c in zip(pos, view))
    # (a picture one pixel wide: its field of view as if two, as build_view fits one)
    scale = 0.5 * max(W - 1, 1) / (d1 * math.tan(math.radians(fov) / 2))
    # the footprint of a pixel where the lowest ray meets the ground below the eye
    height = pos[2] - ground if np.isfinite(ground) else 0.0
    down = math.radians(-pitch) + math.atan(0.5 * (H - 1) / scale / d1)
    reach = height / math.sin(down) if height > 0 and down > 0 else side
    step = max(min(reach, side), d1) / (d1 * scale)
    return dict(projection="perspective", elev=-pitch, azim=heading, center=center, d1=d1,
                d2=d2, scale=scale, size=(W, H), step=step, sampling="march")

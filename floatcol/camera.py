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

    position: (u, v, w), or (u, v) with the eye ``above`` (default: 5 % of the
        domain's longer side) the surface there (outside the domain: at its nearest
        point, so an eye may come in from beyond the edge of a DEM; in a hole: 0).
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
    ground = float(_ground(s, domain, pos[0], pos[1]))
    if len(pos) == 2:
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


#: a flight's waypoints at most (each makes DENSE points of its curve), and its frames
MAX_WAYPOINTS = 10_000
MAX_FRAMES = 100_000
#: points a segment of a flight's curve that measure its length
DENSE = 256


def _ground(s, domain, u, v):
    """The surface's height under (u, v): at the domain's nearest point where (u, v)
    lies outside it (a DEM's ground continued beyond its edge); NaN in a hole."""
    import numpy as np
    (ua, ub), (va, vb) = domain
    u = np.clip(np.asarray(u, dtype=float), ua, ub)
    v = np.clip(np.asarray(v, dtype=float), va, vb)
    return s.evaluate(np.atleast_1d(u), np.atleast_1d(v)).reshape(u.shape)


def flight(surface, path, frames, heading=None, above=None, closed=False, look_ahead=0.0):
    """Where the eye of a flight through the waypoints ``path`` is at each of
    ``frames`` frames, and where it looks: the points at equal distances along a
    centripetal Catmull-Rom curve through the waypoints (it passes through each, turns
    smoothly, and makes no loop or cusp between close ones), the first frame at the
    first waypoint, the last at the last; ``closed``: the curve goes on from the last
    waypoint back to the first, as smoothly, and the frames go round it once, the last
    a step short of the first (a clip that loops without a seam).

    path: waypoints all (u, v), the eye ``above`` (as fly's: default 5 % of the
        domain's longer side) the ground at each (beyond the domain's edge its nearest
        point's), and never nearer the ground than half that between them (over a
        ridge), or all (u, v, w), followed exactly.
    heading: None, along the curve (compass degrees, clockwise from +v), or a number.
    look_ahead: with heading None, look from each frame's point toward the curve's
        point this far ahead along it (the surface's units; 0: along its tangent), so
        the camera turns into a sharp corner before it and out of it after, as a driver
        looks (near an open curve's end, where less of it is left, toward its end).
    Returns (positions (frames, 3), headings (frames,), distances (frames,): how far
    along the curve each frame is, in the surface's units)."""
    import numpy as np

    from .surface import as_surface
    from .view import _number
    s = as_surface(surface)
    domain = s.default_domain or ((-10.0, 10.0), (-10.0, 10.0))
    (ua, ub), (va, vb) = domain
    side = max(ub - ua, vb - va)
    if isinstance(frames, bool) or not isinstance(frames, (int, np.integer)) or frames < 1:
        raise ValueError(f"frames must be a positive whole number, got {frames!r}")
    if frames > MAX_FRAMES:
        raise ValueError(f"frames must be at most {MAX_FRAMES} (83 minutes at 20 fps), got "
                         f"{frames}")
    try:
        points = [[_number("path", x) for x in p] for p in path]
    except TypeError:
        raise ValueError("path must be waypoints (u, v) or (u, v, w), at least two, e.g. "
                         f"[(0, 0), (100, 50)]; got {path!r}") from None
    if len(points) > MAX_WAYPOINTS:
        raise ValueError(f"path has {len(points)} waypoints; at most {MAX_WAYPOINTS}")
    dims = {len(p) for p in points}
    if len(points) < 2 or len(dims) != 1 or dims - {2, 3}:
        raise ValueError("path must be waypoints all (u, v) or all (u, v, w), at least two, "
                         f"e.g. [(0, 0), (100, 50)]; got {path!r}")
    if heading is not None:
        heading = _number("heading", heading)
    look_ahead = _number("look_ahead", look_ahead)
    if look_ahead < 0.0:
        raise ValueError(f"look_ahead must be a distance of 0 or more, got {look_ahead:g}")
    P = np.array(points, dtype=float)
    rise = None
    if P.shape[1] == 2:
        rise = 0.05 * side if above is None else _number("above", above, positive=True)
        ground = _ground(s, domain, P[:, 0], P[:, 1])
        P = np.column_stack([P, np.where(np.isfinite(ground), ground, 0.0) + rise])
    # the waypoints less repeats (a repeat would make a knot interval of 0)
    keep = np.concatenate([[True], np.any(np.diff(P, axis=0) != 0.0, axis=1)])
    P = P[keep]
    if closed:
        if len(P) > 1 and np.array_equal(P[0], P[-1]):
            P = P[:-1]                          # (the start repeated to close it)
        if len(P) < 3:
            raise ValueError("a closed flight needs three different waypoints or more, got "
                             f"{len(P)}")
    if len(P) == 1:
        if heading is None:
            raise ValueError("the path's waypoints are all one point: give a heading")
        return (np.repeat(P, frames, axis=0), np.full(frames, heading), np.zeros(frames))
    ctrl, knots = _curve(P, closed)
    # the curve's length along it from 256 points a segment; a frame's point is the
    # curve's own at the parameter its distance falls on (between two of those points),
    # its heading the curve's own direction there: smooth however many frames there are
    seg, par = _samples(knots, DENSE)
    dense = _curve_at(ctrl, knots, seg, par)
    along = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(dense, axis=0), axis=1))])
    at = np.linspace(0.0, along[-1], frames, endpoint=closed is False) if frames > 1 \
        else np.zeros(1)

    def parameter(dist):
        # (segment, parameter) where the curve is ``dist`` along
        idx = np.clip(np.searchsorted(along, dist, "right") - 1, 0, len(dense) - 2)
        span = along[idx + 1] - along[idx]
        w = np.where(span > 0.0, (dist - along[idx]) / np.where(span > 0.0, span, 1.0), 0.0)
        sk = seg[idx]
        p_next = np.where(seg[idx + 1] == sk, par[idx + 1], knots[sk, 1])
        return sk, par[idx] + np.clip(w, 0.0, 1.0) * (p_next - par[idx])
    s_k, fp = parameter(at)
    pos = _curve_at(ctrl, knots, s_k, fp)
    if rise is not None:
        # over a ridge between two waypoints the curve may pass under the ground
        g = _ground(s, domain, pos[:, 0], pos[:, 1])
        low = np.isfinite(g) & (pos[:, 2] < g + 0.5 * rise)
        pos[low, 2] = g[low] + 0.5 * rise
    if heading is not None:
        heads = np.full(frames, heading)
    else:
        # the curve's direction over the ground at each frame; where it climbs
        # straight up, the heading before
        h = 1e-6 * (knots[s_k, 1] - knots[s_k, 0])
        d = (_curve_at(ctrl, knots, s_k, np.minimum(fp + h, knots[s_k, 1]))
             - _curve_at(ctrl, knots, s_k, np.maximum(fp - h, knots[s_k, 0])))
        heads = np.degrees(np.arctan2(d[:, 0], d[:, 1]))
        flat = np.hypot(d[:, 0], d[:, 1]) <= 1e-12 * side
        for k in range(frames):
            if flat[k]:
                heads[k] = heads[k - 1] if k > 0 else 0.0
        if look_ahead > 0.0:
            ahead = at + look_ahead
            ahead = np.mod(ahead, along[-1]) if closed else np.minimum(ahead, along[-1])
            target = _curve_at(ctrl, knots, *parameter(ahead))
            d = target - _curve_at(ctrl, knots, s_k, fp)
            far = np.hypot(d[:, 0], d[:, 1]) > 1e-9 * side   # (else the tangent's)
            heads = np.where(far, np.degrees(np.arctan2(d[:, 0], d[:, 1])), heads)
    return pos, heads, at


def _curve(P, closed=False):
    """The centripetal Catmull-Rom curve through the rows of P, a segment between each
    two (Barry and Goldman's pyramid, knots the square roots of the chords; its ends
    continued by reflection, or, ``closed``, round through P[0] again): (control
    points (segments, 4, 3), knots (segments, 3): t1, t2, t3 after t0 = 0; a segment
    runs from t1 to t2)."""
    import numpy as np
    if closed:
        Q = np.vstack([P[-1:], P, P[:2]])
    else:
        Q = np.vstack([2.0 * P[0] - P[1], P, 2.0 * P[-1] - P[-2]])
    ctrl = np.stack([Q[i - 1:i + 3] for i in range(1, len(Q) - 2)])
    chords = np.linalg.norm(np.diff(ctrl, axis=1), axis=2) ** 0.5
    return ctrl, np.cumsum(chords, axis=1)


def _curve_at(ctrl, knots, seg, t):
    """The points of segments ``seg`` at parameters ``t`` (arrays of one length)."""
    p0, p1, p2, p3 = (ctrl[seg, k] for k in range(4))
    t1, t2, t3 = (knots[seg, k][:, None] for k in range(3))
    t = t[:, None]
    a1 = ((t1 - t) * p0 + t * p1) / t1
    a2 = ((t2 - t) * p1 + (t - t1) * p2) / (t2 - t1)
    a3 = ((t3 - t) * p2 + (t - t2) * p3) / (t3 - t2)
    b1 = ((t2 - t) * a1 + t * a2) / t2
    b2 = ((t3 - t) * a2 + (t - t1) * a3) / (t3 - t1)
    return ((t2 - t) * b1 + (t - t1) * b2) / (t2 - t1)


def _samples(knots, n):
    """(segments, parameters) of n points a segment evenly in its parameter, and the
    last segment's end."""
    import numpy as np
    m = len(knots)
    seg = np.append(np.repeat(np.arange(m), n), m - 1)
    frac = np.append(np.tile(np.arange(n) / n, m), 1.0)
    return seg, knots[seg, 0] + frac * (knots[seg, 1] - knots[seg, 0])


def _catmull_rom(P, n, closed=False):
    """n points a segment (and the last) of _curve's curve through the rows of P."""
    ctrl, knots = _curve(P, closed)
    return _curve_at(ctrl, knots, *_samples(knots, n))

"""Objects on a surface (Szenberg 1997): markers, poles, boxes and trees drawn by a
z-buffer against the surface's depth.

Szenberg renders a terrain by the floating horizon, keeps each pixel's depth, and
lets a z-buffer (OpenGL's) draw houses, vehicles and power lines into the same
picture. Here the objects are small triangle meshes standing on the surface (their
base at f(u, v)); the objects pass projects them with the picture's own camera,
rasterises each triangle at the pixel centres with perspective-correct depth, keeps
the nearest of them and of the surface (Render.depth), and lights each face flat by
the picture's light (ambient 0.35). ``Render.window_depth(near, far)`` (his eq. 7)
gives the surface's depth as OpenGL's depth buffer holds it, for the opposite way
round: a floatcol terrain under an OpenGL scene.

>>> import floatcol as fc
>>> r = fc.render("exp(-(u**2 + v**2) / 8)", u=(-4, 4), v=(-4, 4), size=(160, 120),
...               objects=[fc.tree(1, 1, 0.8), fc.box(-2, 0, 0.6, 0.6, 0.5)])
>>> r.stats["objects"]
2
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import color

#: light of a face turned away from the light (flat shading: ambient + diffuse)
AMBIENT = 0.35
#: sides of a pole's and a tree's cone
ROUND_SIDES = 12


@dataclass
class Mesh:
    """A triangle mesh standing on the surface: ``vertices`` (n, 3) as (du, dv, h)
    offsets from its foot (u, v) on the surface (h up from f(u, v), or from ``base``
    where given), ``triangles`` (m, 3) vertex indices, one ``color`` per triangle or
    one for all."""
    u: float
    v: float
    vertices: np.ndarray
    triangles: np.ndarray
    color: object = "grey"
    base: float | None = None

    def check(self):
        try:
            u, v = float(self.u), float(self.v)
        except (TypeError, ValueError):
            raise ValueError(f"an object's position must be numbers, got {self.u!r}, "
                             f"{self.v!r}") from None
        verts = np.asarray(self.vertices, dtype=float)
        tris = np.asarray(self.triangles)
        if verts.ndim != 2 or verts.shape[1] != 3 or tris.ndim != 2 or tris.shape[1] != 3 \
                or tris.dtype.kind not in "iu" or tris.size == 0 \
                or tris.min() < 0 or tris.max() >= len(verts):
            raise ValueError("an object's mesh must be vertices (n, 3) and triangles (m, 3) of "
                             "vertex indices")
        if not (math.isfinite(u) and math.isfinite(v) and np.isfinite(verts).all()):
            raise ValueError("an object's position and vertices must be finite numbers")
        cols = self.color
        if isinstance(cols, np.ndarray) and cols.ndim == 2 and len(cols) == len(tris):
            cols = list(cols)                   # (one RGB row a triangle)
        if isinstance(cols, (list, tuple)) and len(cols) == len(tris) \
                and not isinstance(cols[0], (int, float, np.number)):
            rgb = np.array([color.to_rgb(c, "object color") for c in cols])
        else:
            rgb = np.tile(color.to_rgb(cols, "object color"), (len(tris), 1))
        return u, v, verts, tris, rgb


def box(u, v, width, depth, height, color="lightgrey", heading=0.0, base=None):
    """A box (a house, a vehicle) of ``width`` along u and ``depth`` along v turned by
    ``heading`` degrees (clockwise from +v), ``height`` tall, its foot centred at (u,
    v) on the surface."""
    w, d, h = (_positive(n, x) for n, x in (("width", width), ("depth", depth),
                                            ("height", height)))
    c, s = math.cos(math.radians(heading)), math.sin(math.radians(heading))
    corners = []
    for z in (0.0, h):
        for x, y in ((-w / 2, -d / 2), (w / 2, -d / 2), (w / 2, d / 2), (-w / 2, d / 2)):
            corners.append((x * c + y * s, -x * s + y * c, z))
    faces = [(0, 1, 2), (0, 2, 3), (4, 6, 5), (4, 7, 6)]
    for k in range(4):
        a, b = k, (k + 1) % 4
        faces += [(a, b, b + 4), (a, b + 4, a + 4)]
    return Mesh(u, v, np.array(corners), np.array(faces), color, base)


def pole(u, v, height, radius=None, color="dimgrey", base=None):
    """A pole (a mast, a power-line tower) ``height`` tall, ``radius`` thick (default
    1/40 of its height)."""
    h = _positive("height", height)
    r = h / 40 if radius is None else _positive("radius", radius)
    verts, tris = _cylinder(r, r, 0.0, h)
    return Mesh(u, v, verts, tris, color, base)


def tree(u, v, height, color="forestgreen", trunk="saddlebrown", base=None):
    """A tree: a cone crown (the upper 3/4 of ``height``, its radius 1/3 of the
    height) on a trunk."""
    h = _positive("height", height)
    tv, tt = _cylinder(h / 25, h / 25, 0.0, 0.3 * h)
    cv, ct = _cylinder(h / 3, 0.0, 0.25 * h, h)
    verts = np.vstack([tv, cv])
    tris = np.vstack([tt, ct + len(tv)])
    colors = [trunk] * len(tt) + [color] * len(ct)
    return Mesh(u, v, verts, tris, colors, base)


def marker(u, v, size, color="red", above=None, base=None):
    """A marker: an octahedron ``size`` across floating ``above`` the surface
    (default: its own size)."""
    s = _positive("size", size) / 2
    lift = 2 * s if above is None else float(above) + s
    verts = np.array([(s, 0, lift), (-s, 0, lift), (0, s, lift), (0, -s, lift),
                      (0, 0, lift + s), (0, 0, lift - s)])
    tris = np.array([(4, 0, 2), (4, 2, 1), (4, 1, 3), (4, 3, 0),
                     (5, 2, 0), (5, 1, 2), (5, 3, 1), (5, 0, 3)])
    return Mesh(u, v, verts, tris, color, base)


def _cylinder(r0, r1, z0, z1):
    """A closed cylinder or cone (radius r0 at z0, r1 at z1) of ROUND_SIDES sides."""
    n = ROUND_SIDES
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    ring0 = np.c_[r0 * np.cos(a), r0 * np.sin(a), np.full(n, z0)]
    ring1 = np.c_[r1 * np.cos(a), r1 * np.sin(a), np.full(n, z1)]
    verts = np.vstack([ring0, ring1, [(0, 0, z0), (0, 0, z1)]])
    tris = []
    for k in range(n):
        m = (k + 1) % n
        tris += [(k, m, n + m), (k, n + m, n + k), (2 * n, m, k), (2 * n + 1, n + k, n + m)]
    return verts, np.array(tris)


def _positive(name, x):
    try:
        x = float(x)
    except (TypeError, ValueError):
        raise ValueError(f"an object's {name} must be a positive number, got {x!r}") from None
    if not (math.isfinite(x) and x > 0):
        raise ValueError(f"an object's {name} must be a positive number, got {x!r}")
    return x


def clip_near(pts, tris, rgb, z_near):
    """Triangles (vertex indices ``tris`` into ``pts`` (n, 3) screen x, y, z; colours
    ``rgb``) cut by the plane z = z_near: the parts at or behind it (Sutherland and
    Hodgman's clipping of each triangle that crosses it: a triangle or a quad, in two
    triangles, of the same colour; new vertices appended). Returns (pts, tris, rgb)."""
    inside = pts[tris, 2] >= z_near                    # (m, 3)
    count = inside.sum(axis=1)
    keep = count == 3
    cross = np.nonzero((count > 0) & (count < 3))[0]
    if len(cross) == 0:
        return pts, tris[keep], rgb[keep]
    new_pts = [pts]
    new_tris = [tris[keep]]
    new_rgb = [rgb[keep]]
    n = len(pts)
    for k in cross:
        poly = []
        for i in range(3):
            a = pts[tris[k, i]]
            b = pts[tris[k, (i + 1) % 3]]
            a_in = a[2] >= z_near
            b_in = b[2] >= z_near
            if a_in:
                poly.append(a)
            if a_in != b_in:                           # the edge meets the plane
                f = (z_near - a[2]) / (b[2] - a[2])
                q = a + f * (b - a)
                q[2] = z_near
                poly.append(q)
        fan = np.array([[n, n + j, n + j + 1] for j in range(1, len(poly) - 1)])
        new_pts.append(np.array(poly))
        new_tris.append(fan)
        new_rgb.append(np.tile(rgb[k], (len(fan), 1)))
        n += len(poly)
    return np.vstack(new_pts), np.vstack(new_tris).astype(np.int64), np.vstack(new_rgb)


def objects_pass(r, objects, surface, light_dir):
    """Draw ``objects`` (Mesh) into Render ``r`` in place: its rgba, and its depth
    where an object is nearer than the surface (side, intensity and the G-buffer stay
    the surface's); ``stats["objects"]`` and ``stats["object_pixels"]``. They stand
    on ``surface`` (in its own units; r.box stretches them as the picture); light_dir
    is the screen direction toward the light (None or zeros: the headlight). The
    meshes are projected and lit here (numpy), rasterised by kernels/raster.py."""
    # (an object far larger than the scene overflows its normals' products: a face
    # without a normal takes the ambient light, and numpy's warnings are no news)
    with np.errstate(over="ignore", invalid="ignore"):
        return _objects_pass(r, objects, surface, light_dir)


def _objects_pass(r, objects, surface, light_dir):
    from .kernels.raster import raster_kernel
    view = r.view
    H, W = r.side.shape
    a, b, c = r.box
    ortho = view.orthographic
    verts, tris, rgbs = [], [], []
    n = 0
    for obj in objects:
        u0, v0, vv, tt, rgb = obj.check()
        if obj.base is None:
            foot = float(np.asarray(surface.evaluate(np.array([u0]), np.array([v0])))[0])
            if not math.isfinite(foot):
                continue                        # (over a hole: nothing to stand on)
        else:
            foot = float(obj.base)
        verts.append(np.c_[(u0 + vv[:, 0]) * a, (v0 + vv[:, 1]) * b, (foot + vv[:, 2]) * c])
        tris.append(tt + n)
        rgbs.append(rgb)
        n += len(vv)
    r.stats["objects"] = len(objects)
    r.stats["object_pixels"] = 0
    if not verts:
        return r
    p = np.vstack(verts)
    tris = np.vstack(tris).astype(np.int64)
    rgb = np.vstack(rgbs)
    x, y, z = view.to_screen(p[:, 0], p[:, 1], p[:, 2])
    # flat light: each face's normal turned toward the eye, against the light
    pts = np.c_[x, y, z]
    nrm = np.cross(pts[tris[:, 1]] - pts[tris[:, 0]], pts[tris[:, 2]] - pts[tris[:, 0]])
    length = np.linalg.norm(nrm, axis=1, keepdims=True)
    nrm = np.where(length > 0, nrm / np.where(length > 0, length, 1.0), 0.0)
    if ortho:
        to_eye = np.tile([0.0, 0.0, -1.0], (len(tris), 1))
    else:
        to_eye = np.array([0.0, 0.0, -view.d3]) - pts[tris].mean(axis=1)
        to_eye /= np.linalg.norm(to_eye, axis=1, keepdims=True)
    nrm *= np.sign(np.sum(nrm * to_eye, axis=1, keepdims=True) + 1e-300)
    ld = np.zeros(3) if light_dir is None else np.asarray(light_dir, dtype=float)
    lv = to_eye if not ld.any() else np.tile(ld / np.linalg.norm(ld), (len(tris), 1))
    shade = AMBIENT + (1 - AMBIENT) * np.clip(np.sum(nrm * lv, axis=1), 0.0, None)
    rgb = np.clip(rgb * shade[:, None], 0.0, 1.0)
    if not ortho:
        # the parts of the triangles behind the screen plane (a fly-through's objects
        # reach past the eye)
        pts, tris, rgb = clip_near(pts, tris, rgb, view.d1 - view.d3)
    x, y, z = pts[:, 0], pts[:, 1], pts[:, 2]
    e = z + view.d3                              # distance along the view axis
    m = np.ones_like(e) if ortho else view.d1 / e
    col = view.column(x * m)
    row = (H - 1) / 2 - y * m * view.scale
    depth = r.depth
    zbuf = np.where(np.isfinite(depth), depth.astype(np.float64), np.inf)
    drawn = np.zeros((H, W), np.uint8)
    raster_kernel(col, row, e, tris, rgb, ortho, float(view.d3), zbuf, r.rgba, drawn)
    hit = drawn.astype(bool)
    r.stats["object_pixels"] = int(hit.sum())
    if hit.any():
        d = depth.copy()
        d[hit] = zbuf[hit].astype(np.float32)
        r._depth = d
    return r

"""Objects on a surface (Szenberg 1997): markers, poles, boxes and trees drawn by a
z-buffer against the surface's depth.

Szenberg renders a terrain by the floating horizon, keeps each pixel's depth, and
lets a z-buffer (OpenGL's) draw houses, vehicles and power lines into the same
picture. Here the objects are small triangle meshes standing on the surface (their
base at f(u, v)); the objects pass projects them with the picture's own camera,
rasterises each triangle at the pixel centres with perspective-correct depth, keeps
the nearest of them and of the surface (Render.depth), and lights each face flat by
the picture's light (ambient 0.35). With shadows (a shadow texture, passes/shadow.py)
they cast shadows on the surfaces and on each other (Occluders: exact for a point;
antialiased on the surfaces, passes/shadow.py) and
take the surfaces' (the texture's horizons). With antialiasing their edges are
antialiased by 16 sub-samples (kernels/raster.py object_edges_kernel).
``Render.window_depth(near, far)`` (his eq. 7)
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
            # (each colour converted once: a tree's triangles name two)
            seen = {}
            rgb = np.array([seen[k] if (k := _colour_key(c)) in seen
                            else seen.setdefault(k, color.to_rgb(c, "object color"))
                            for c in cols])
        else:
            rgb = np.tile(color.to_rgb(cols, "object color"), (len(tris), 1))
        return u, v, verts, tris, rgb


def _colour_key(c):
    """A colour as a dictionary key (a name, or an RGB(A) sequence as a tuple)."""
    if isinstance(c, str):
        return c
    try:
        return tuple(float(x) for x in c)
    except (TypeError, ValueError):
        return id(c)


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
    """Triangles (vertex indices ``tris`` into ``pts`` (n, 3 or more) screen x, y, z
    and any other columns, interpolated as they; a row ``rgb`` of each, its colour and
    any other columns) cut by the plane z = z_near: the parts at or behind it
    (Sutherland and Hodgman's clipping of each triangle that crosses it: a triangle or
    a quad, in two triangles, with the same row; new vertices appended). Returns (pts,
    tris, rgb)."""
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


def meshes(objects, surface, box):
    """The objects' triangles in the picture's box: (vertices (n, 3) as (u, v, w)
    stretched by ``box``, triangles (m, 3), colours (m, 3)), each standing on
    ``surface`` (its foot at f(u, v), or its ``base``; one over a hole is left out)."""
    a, b, c = box
    checked = [obj.check() for obj in objects]
    # the feet on the surface, in one call
    feet = surface.evaluate(np.array([x[0] for x in checked], dtype=np.float64),
                            np.array([x[1] for x in checked], dtype=np.float64))
    verts, tris, rgbs = [], [], []
    n = 0
    for obj, (u0, v0, vv, tt, rgb), foot in zip(objects, checked, np.atleast_1d(feet)):
        if obj.base is None:
            foot = float(foot)
            if not math.isfinite(foot):
                continue                        # (over a hole: nothing to stand on)
        else:
            foot = float(obj.base)
        verts.append(np.c_[(u0 + vv[:, 0]) * a, (v0 + vv[:, 1]) * b, (foot + vv[:, 2]) * c])
        tris.append(tt + n)
        rgbs.append(rgb)
        n += len(vv)
    if not verts:
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64), np.zeros((0, 3))
    return np.vstack(verts), np.vstack(tris).astype(np.int64), np.vstack(rgbs)


def light_frame(light):
    """(3, 3): rows e1, e2 across a directional light (toward it: ``light``) and its
    unit direction L."""
    L = np.asarray(light, dtype=np.float64)
    L = L / np.linalg.norm(L)
    ref = np.array([0.0, 0.0, 1.0]) if abs(L[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    e1 = np.cross(L, ref)
    e1 /= np.linalg.norm(e1)
    return np.ascontiguousarray(np.vstack([e1, np.cross(L, e1), L]))


#: the occluders' grid: about this many cells a triangle, at most this many a side,
#: and at most this many (cell, triangle) entries in all
CELLS_PER_TRIANGLE = 4
MAX_CELLS_SIDE = 512
MAX_ENTRIES = 4_000_000
#: a triangle blocks a point lying below it toward the light by more than this
#: part of the objects' size (its own triangle never does)
OCCLUDER_BIAS = 1e-7


class Occluders:
    """The objects' triangles as casters of shadows from a directional light ``light``
    (toward it, in the box's (u, v, w)): in the light's frame, where a ray toward the
    light is a point, each triangle is a 2-D triangle with a height toward the light,
    binned in a grid (kernels/raster.py occluded_kernel). Exact for points: a point is
    in an object's shadow where some triangle's projection holds it and lies nearer
    the light (no penumbra; passes/shadow.py antialiases the edges on the surfaces by
    points over each edge pixel's footprint)."""

    def __init__(self, verts, tris, light):
        #: rows e1, e2 (across the light) and L
        self.frame = light_frame(light)
        pa, pb, pd = (verts @ self.frame.T).T
        A, B, D = pa[tris], pb[tris], pd[tris]               # (m, 3) each
        det = (A[:, 1] - A[:, 0]) * (B[:, 2] - B[:, 0]) - (A[:, 2] - A[:, 0]) * (B[:, 1] - B[:, 0])
        size = float(np.ptp(verts, axis=0).max()) if len(verts) else 0.0
        # a triangle seen edge-on from the light blocks nothing (its neighbours do); one
        # beyond floating point (an object 1e300 tall) is left out
        with np.errstate(all="ignore"):
            keep = (np.abs(det) > 1e-12 * np.float64(max(size, 1e-300)) ** 2) & np.isfinite(det) \
                & np.isfinite(A).all(axis=1) & np.isfinite(B).all(axis=1) \
                & np.isfinite(D).all(axis=1)
        A, B, D, det = A[keep], B[keep], D[keep], det[keep]
        #: the triangles' index among ``tris`` (a point's own is left out)
        self.index = np.nonzero(keep)[0]
        self.coef = np.ascontiguousarray(np.c_[
            A[:, 0], B[:, 0],
            (B[:, 2] - B[:, 0]) / det, -(A[:, 2] - A[:, 0]) / det,
            -(B[:, 1] - B[:, 0]) / det, (A[:, 1] - A[:, 0]) / det,
            D[:, 0], D[:, 1] - D[:, 0], D[:, 2] - D[:, 0]])
        ok = np.isfinite(self.coef).all(axis=1)
        if not ok.all():
            self.index, self.coef = self.index[ok], np.ascontiguousarray(self.coef[ok])
            A, B = A[ok], B[ok]
        self.bias = OCCLUDER_BIAS * size if math.isfinite(size) else 0.0
        self._grid(A, B)

    def _grid(self, A, B):
        m = len(A)
        if m == 0:
            self.ga = self.gb = 0.0
            self.inv_cell, self.na, self.nb = 1.0, 1, 1
            self.start = np.zeros(2, np.int64)
            self.items = np.zeros(0, np.int64)
            return
        lo_a, hi_a, lo_b, hi_b = A.min(axis=1), A.max(axis=1), B.min(axis=1), B.max(axis=1)
        self.ga, self.gb = float(lo_a.min()), float(lo_b.min())
        span = max(float(hi_a.max()) - self.ga, float(hi_b.max()) - self.gb, 1e-300)
        side = int(min(max(math.sqrt(CELLS_PER_TRIANGLE * m), 1), MAX_CELLS_SIDE))
        if not math.isfinite(span * 2.0):       # (a footprint near float's limit: one cell)
            span, side = float(np.finfo(np.float64).max) / 4, 1
            self.ga, self.gb = -span, -span
        while True:
            cell = span / side * (1 + 1e-9)
            na = int(min((float(hi_a.max()) - self.ga) / cell, side - 1)) + 1
            nb = int(min((float(hi_b.max()) - self.gb) / cell, side - 1)) + 1
            ia0 = np.clip(((lo_a - self.ga) / cell).astype(np.int64), 0, na - 1)
            ia1 = np.clip(((hi_a - self.ga) / cell).astype(np.int64), 0, na - 1)
            ib0 = np.clip(((lo_b - self.gb) / cell).astype(np.int64), 0, nb - 1)
            ib1 = np.clip(((hi_b - self.gb) / cell).astype(np.int64), 0, nb - 1)
            wa = ia1 - ia0 + 1
            counts = wa * (ib1 - ib0 + 1)
            total = int(counts.sum())
            if total <= MAX_ENTRIES or side == 1:
                break
            side = max(side // 2, 1)
        tri = np.repeat(np.arange(m), counts)
        local = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
        w = wa[tri]
        cells = (ib0[tri] + local // w) * na + ia0[tri] + local % w
        order = np.argsort(cells, kind="stable")
        self.items = np.ascontiguousarray(tri[order])
        self.start = np.r_[0, np.cumsum(np.bincount(cells, minlength=na * nb))].astype(np.int64)
        self.inv_cell, self.na, self.nb = 1.0 / cell, na, nb

    def blocked(self, point, test, drawn=None, src=None):
        """(H, W) uint8: 1 where the ray from a pixel's point toward the light meets a
        triangle, for the pixels where ``test`` is set. ``point``: (H, W, 3) in the box,
        or (H, n, T, 3) as a tiled G-buffer holds them (kernels/raster.py
        occluded_kernel). A point on an object does not meet its own triangle: ``drawn``
        (H, W) the rasteriser's triangle + 1 at each pixel, ``src`` each rasterised
        triangle's index among ``tris``."""
        from .kernels.raster import occluded_kernel
        H, W = test.shape
        if point.ndim == 3:
            point = point.reshape(H, W, 1, 3)
        own = np.zeros((0, 0), np.int32)
        grid_index = np.zeros(0, np.int64)
        if drawn is not None:
            own, grid_index = drawn, self._grid_index(src)
        out = np.empty((H, W), np.uint8)
        occluded_kernel(point, test, own, grid_index, self.frame, self.coef, self.start,
                        self.items, self.ga, self.gb, self.inv_cell, self.na, self.nb,
                        self.bias, out)
        return out


    def _grid_index(self, src):
        """Each of ``src``'s triangles' number among the grid's (those kept), -1: none."""
        where = np.full(max(int(src.max(initial=0)), int(self.index.max(initial=0))) + 1,
                        -1, np.int64)
        where[self.index] = np.arange(len(self.index))
        return where[src]

    def edges_on_objects(self, drawn, edge, screen, src, out):
        """The part of each ``edge`` pixel's footprint on its own triangle that another
        triangle hides, into out (H, W) float32 there (kernels/raster.py
        object_shadow_edges_kernel; drawn and src as blocked's, screen the rasterised
        triangles: (cx, cy, e, tris, wp, ortho))."""
        from .kernels.raster import object_shadow_edges_kernel
        object_shadow_edges_kernel(drawn, edge, *screen, self._grid_index(src), self.frame,
                                   self.coef, self.start, self.items, self.ga, self.gb,
                                   self.inv_cell, self.na, self.nb, self.bias, out)

    def edges(self, point, seen, edge, out):
        """The part of each ``edge`` pixel's footprint in the objects' shadow, into out
        (H, W) float32 there (kernels/raster.py shadow_edges_kernel; point as
        blocked's, tiled)."""
        from .kernels.raster import shadow_edges_kernel
        shadow_edges_kernel(point, seen, edge, self.frame, self.coef, self.start, self.items,
                            self.ga, self.gb, self.inv_cell, self.na, self.nb, self.bias, out)


    def cast(self, point, test, seen):
        """The objects' shadow on the surface's points (H, W) float32, where ``test``:
        1 blocked, 0 not, and at the shadow's edge (a pixel whose 3 x 3 neighbourhood
        has points in it and out of it) the part of its footprint in shadow (edges;
        ``seen``: the pixels whose points count as neighbours)."""
        blocked = self.blocked(point, test) > 0
        edge = test & _dilate(blocked) & _dilate(test & ~blocked)
        out = blocked.astype(np.float32)
        if edge.any():
            self.edges(point, seen, edge, out)
        return out


#: a light of a radius: the directions over its disk the objects' shadows take
DISK_DIRECTIONS = 16


class DiskOccluders:
    """The objects as casters of a light of angular radius ``rho`` (radians): an
    Occluders for each of DISK_DIRECTIONS directions spread evenly over the disk (a
    sunflower spiral); a point's shadow is the part of them blocked (penumbrae that
    widen with the distance from the caster, in steps of 1/16)."""

    def __init__(self, verts, tris, light, rho):
        e1, e2, L = light_frame(light)
        k = np.arange(DISK_DIRECTIONS) + 0.5
        r = math.tan(rho) * np.sqrt(k / DISK_DIRECTIONS)
        a = k * math.pi * (3.0 - math.sqrt(5.0))
        dirs = L + r[:, None] * (np.cos(a)[:, None] * e1 + np.sin(a)[:, None] * e2)
        self.parts = [Occluders(verts, tris, d) for d in dirs]

    def blocked(self, point, test, drawn=None, src=None):
        """(H, W) float32: the part of the directions in which a triangle hides the
        point (Occluders.blocked's arguments)."""
        out = np.zeros(test.shape, np.float32)
        for part in self.parts:
            out += part.blocked(point, test, drawn, src)
        return out / len(self.parts)

    def cast(self, point, test, seen):
        """Occluders.cast for the disk: the part of the directions blocked (the
        penumbra stands for the edge's antialiasing)."""
        return self.blocked(point, test)


def _dilate(mask):
    """Where mask holds in a pixel's 3 x 3 neighbourhood."""
    m = np.pad(mask, 1)
    out = np.zeros_like(mask)
    for di in range(3):
        for dj in range(3):
            out |= m[di:di + mask.shape[0], dj:dj + mask.shape[1]]
    return out


def occluders(objects, surface, box, light, rho=0.0):
    """The objects as casters for the shadow texture (passes/shadow.py): Occluders, or
    DiskOccluders for a light of angular radius rho > 0 (radians), or None; it keeps
    their ``meshes`` (the objects pass draws the same)."""
    m = meshes(objects, surface, box)
    if not len(m[1]):
        return None
    with np.errstate(all="ignore"):             # (objects near float's limit: left out)
        out = Occluders(m[0], m[1], light) if rho <= 0.0 else \
            DiskOccluders(m[0], m[1], light, rho)
    out.meshes = m
    return out


def objects_pass(r, objects, surface, light_dir, texture=None, antialias=False):
    """Draw ``objects`` (Mesh) into Render ``r`` in place: its rgba, and its depth
    where an object is nearer than the surface (side, intensity and the G-buffer stay
    the surface's); ``stats["objects"]`` and ``stats["object_pixels"]``. They stand
    on ``surface`` (in its own units; r.box stretches them as the picture); light_dir
    is the screen direction toward the light (None or zeros: the headlight). The
    meshes are projected and lit here (numpy), rasterised by kernels/raster.py. With
    the shadow ``texture`` (passes/shadow.py; shadows on) an object's point takes the
    surfaces' shadows (their horizons in the texture) and the other triangles' (the
    texture's occluders), and r.shadow holds its shadow where an object is seen. With
    ``antialias`` the objects' edges are antialiased (kernels/raster.py
    object_edges_kernel: 16 sub-samples in each pixel where the objects' edges pass;
    depth, shadow and object_pixels stay the pixel centre's)."""
    # (an object far larger than the scene overflows its normals' products: a face
    # without a normal takes the ambient light, and numpy's warnings are no news)
    with np.errstate(over="ignore", invalid="ignore"):
        return _objects_pass(r, objects, surface, light_dir, texture, antialias)


def _objects_pass(r, objects, surface, light_dir, texture, antialias):
    from .kernels.raster import TOUCH_SLOTS, raster_kernel
    view = r.view
    H, W = r.side.shape
    ortho = view.orthographic
    r.stats["objects"] = len(objects)
    r.stats["object_pixels"] = 0
    casters = None if texture is None else texture.occluders
    p, tris, base = casters.meshes if casters is not None else meshes(objects, surface, r.box)
    if not len(tris):
        return r
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
    facing = np.clip(np.sum(nrm * lv, axis=1), 0.0, None)
    rgb = np.clip(base * (AMBIENT + (1 - AMBIENT) * facing)[:, None], 0.0, 1.0)
    # the points seen where shadows are asked: each vertex's place in the box goes
    # through the clipping and the rasteriser with it; each triangle's own index too
    shadows = texture is not None
    pts = np.c_[pts, p] if shadows else pts
    pts, tris, attrs, col, row, e = _projected(view, pts, tris,
                                               np.c_[rgb, np.arange(len(tris))], H)
    rgb, src = attrs[:, :3], attrs[:, 3].astype(np.int64)
    depth = r.depth
    # translucent layers (passes/translucency.py): an object shows through them, down
    # to where the layers over it let nothing more through
    front = r._front
    limit = depth if front is None else front[1]
    zbuf = np.where(np.isfinite(limit), limit.astype(np.float64), np.inf)
    drawn = np.zeros((H, W), np.int32)
    wp = np.ascontiguousarray(pts[:, 3:]) if shadows else np.zeros((0, 3))
    point = np.empty((H, W, 3) if shadows else (0, 0, 3))    # (read where drawn only)
    under = (zbuf.copy(), r.rgba.copy()) if antialias else (np.zeros((0, 0)), None)
    touched = np.zeros((H, W, TOUCH_SLOTS) if antialias else (0, 0, 0), np.int32)
    raster_kernel(col, row, e, tris, np.ascontiguousarray(rgb), ortho, float(view.d3), zbuf,
                  r.rgba, drawn, wp, point, under[0], touched)
    hit = drawn > 0
    r.stats["object_pixels"] = int(hit.sum())
    if hit.any():
        d = depth.copy()
        d[hit] = np.minimum(d[hit], zbuf[hit].astype(np.float32))
        behind = hit & (depth < zbuf)            # (a translucent layer over the object)
        kept = None if r.shadow is None else r.shadow[behind]
        r._depth = d
        if shadows:
            screen = (col, row, e, tris, np.ascontiguousarray(pts[:, 3:]), ortho)
            _receive(r, hit, drawn, src, point, base, facing, texture,
                     screen if antialias else None)
        if front is not None:
            _through(r, hit, front[0])
            if kept is not None:
                r.shadow[behind] = kept          # (the nearest thing's, as depth)
    if antialias and (hit.any() or touched.any()):
        from .kernels.raster import object_edges_kernel
        if shadows:
            # (a sliver no pixel centre lies on takes its triangle's colour, in shadow
            # where it is: lit, it drew thin poles in a shadow white)
            rgb = _sliver_colours(pts[:, 3:], tris, src, base, facing, texture)
        object_edges_kernel(drawn, touched, col, row, e, tris, np.ascontiguousarray(rgb),
                            ortho, float(view.d3), under[0], under[1], r.rgba.copy(), r.rgba)
    return r


def _sliver_colours(wp, tris, src, base, facing, texture):
    """(m, 3): each rasterised triangle's colour lit at its centroid (wp (n, 3) its
    vertices in the box) with the shadows there, as _receive lights a pixel's point:
    the colour object_edges_kernel gives a sliver of it that no pixel centre lies on."""
    n = len(tris)
    point = np.ascontiguousarray(wp[tris].mean(axis=1)[None])       # (1, m, 3)
    shadow = (facing[src] <= 0.0).astype(np.float64)                 # attached
    test = (shadow < 1.0)[None]
    if texture.texels and not texture.zenith:
        shadow = np.maximum(shadow, _surfaces_cast(point, test, texture)[0])
        test = (shadow < 1.0)[None]
    if texture.occluders is not None:
        own = np.arange(1, n + 1, dtype=np.int32)[None]             # (its own: not counted)
        shadow = np.maximum(shadow, texture.occluders.blocked(point, test, own, src)[0])
    lit = (1.0 - shadow)[:, None]
    return np.clip(base[src] * (AMBIENT + (1 - AMBIENT) * facing[src][:, None] * lit), 0.0,
                   1.0)


def _projected(view, pts, tris, attrs, H):
    """The triangles on the screen: (pts, tris, attrs, col, row, e) with pts (n, k)
    screen (x, y, z) and any more columns, in perspective the parts of the triangles
    behind the screen plane cut off (a fly-through's objects reach past the eye: their
    vertices and per-triangle attrs clipped along), col and row each vertex's pixel
    coordinates (row 0 at the top), e its distance along the view axis."""
    ortho = view.orthographic
    if not ortho:
        pts, tris, attrs = clip_near(pts, tris, attrs, view.d1 - view.d3)
    x, y, z = pts[:, 0], pts[:, 1], pts[:, 2]
    e = z + view.d3                              # distance along the view axis
    m = np.ones_like(e) if ortho else view.d1 / e
    return pts, tris, attrs, view.column(x * m), (H - 1) / 2 - y * m * view.scale, e


def depth_map(objects, surface, box, view, texture=None):
    """(H, W) float32: the depth (screen z) of the nearest object at each pixel centre,
    inf where none: where translucent layers (passes/translucency.py) stop composing
    what lies over an object. The triangles as objects_pass rasterises them (the
    texture's occluders keep the meshes where shadows are on)."""
    from .kernels.raster import raster_kernel
    casters = None if texture is None else texture.occluders
    p, tris, _ = casters.meshes if casters is not None else meshes(objects, surface, box)
    H, W = view.height, view.width
    zbuf = np.full((H, W), np.inf)
    if len(tris):
        with np.errstate(over="ignore", invalid="ignore"):
            x, y, z = view.to_screen(p[:, 0], p[:, 1], p[:, 2])
            pts = np.c_[x, y, z]
            pts, tris, attrs, col, row, e = _projected(view, pts, tris,
                                                       np.zeros((len(tris), 3)), H)
        raster_kernel(col, row, e, tris, attrs, view.orthographic, float(view.d3), zbuf,
                      np.empty((H, W, 4), np.uint8), np.zeros((H, W), np.int32),
                      np.zeros((0, 3)), np.empty((0, 0, 3)), np.zeros((0, 0)),
                      np.zeros((0, 0, 0), np.int32))
    return zbuf.astype(np.float32)


def _through(r, hit, front_acc):
    """Object pixels seen through translucent layers: what lies over the object
    (front_acc, the layers' premultiplied sums nearer than it: composite_kernel's)
    over its colour, 1 - ACC_A of which shows."""
    from .kernels.layers import ACC_A
    at = np.nonzero(hit)
    over = front_acc[at]
    rgb = over[:, :3] + (1.0 - over[:, ACC_A:ACC_A + 1]) * (r.rgba[at][:, :3] / 255.0)
    r.rgba[at[0], at[1], :3] = np.round(np.clip(rgb, 0.0, 1.0) * 255.0).astype(np.uint8)
    r.rgba[at[0], at[1], 3] = 255


def _surfaces_cast(point, test, texture):
    """The surfaces' shadow on points above them (H, W, 3), where ``test``: their
    horizons in the texture (kernels/shadow.py points_shadow: hard, its edge
    antialiased as the surface's; under a sun of a radius the part of its disk they
    hide, the penumbra the surface around takes too)."""
    from .kernels.shadow import points_shadow
    cast = np.empty(test.shape)
    if texture.w_origin != 0.0:         # (the texture's heights are kept from there)
        point = point.copy()
        point[..., 2] -= texture.w_origin
    points_shadow(point, test, texture.hmax, texture.hsurf, texture.slopes, texture.gu,
                  texture.gv, texture.tan_theta, texture.s0, texture.t0, texture.h,
                  texture.rho, cast)
    return cast


def _receive(r, hit, drawn, src, point, base, facing, texture, screen=None):
    """The objects' seen points in shadow (objects_pass with shadows): attached where
    the face turns away from the light, cast by the surfaces (the texture's horizons,
    kernels/shadow.py points_shadow) and by the other triangles (its occluders); the
    face lit again with the light that reaches it, and r.shadow set there. With
    ``screen`` (antialiasing: the rasterised triangles, Occluders.edges_on_objects') the
    edges of the other triangles' shadows take the part of the pixel in shadow."""
    at = np.nonzero(hit)
    k = src[drawn[at] - 1]                      # each pixel's triangle among the meshes
    shadow = (facing[k] <= 0.0).astype(np.float64)         # attached
    test = np.zeros(hit.shape, bool)
    test[at] = shadow < 1.0
    if texture.texels and not texture.zenith:
        shadow = np.maximum(shadow, _surfaces_cast(point, test, texture)[at])
        test[at] = shadow < 1.0
    if texture.occluders is not None:
        blocked = texture.occluders.blocked(point, test, drawn, src)
        cast = blocked[at].astype(np.float64)
        if screen is not None and isinstance(texture.occluders, Occluders):
            # (a sun of a radius: DiskOccluders' part of the disk is the edge's blend)
            b = blocked > 0
            edge = test & _dilate(b) & _dilate(test & ~b)
            if edge.any():
                part = np.zeros(hit.shape, np.float32)
                texture.occluders.edges_on_objects(drawn, edge, screen, src, part)
                cast = np.where(edge[at], part[at], cast)
        shadow = np.maximum(shadow, cast)
    lit = (1.0 - shadow)[:, None]
    rgb = np.clip(base[k] * (AMBIENT + (1 - AMBIENT) * facing[k][:, None] * lit), 0.0, 1.0)
    r.rgba[at[0], at[1], :3] = np.round(rgb * 255.0).astype(np.uint8)
    r.shadow[at] = shadow                  # (the Render's own array: the shadow pass's)

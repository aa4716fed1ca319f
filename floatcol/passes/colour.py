"""The colour pass (Gordon 6.7): the colour of the surface at each pixel from its
(u, v) in the G-buffer, before the finishing pass lights it.

- A texture T(u, v): an image indexed as HeightField's heights (``img[j, i]`` the
  colour at (u_i, v_j), nodes spread over the extent, by default the domain), read
  through a mip-map pyramid with trilinear filtering: each pixel averages about the
  texels its footprint covers (the footprint from its neighbours' (u, v), the
  smaller one-sided difference each way, so a silhouette does not blur it), which
  keeps distant and oblique textures from shimmering as the camera moves
  (benchmarks/bench_texture.py measures the flicker). ``texture_filter="point"``
  takes the nearest texel (no filtering), ``"linear"`` the bilinear mix of the four
  nearest. A texture's alpha lays it over the surface's own colour (a decal). A
  callable T(u, v) -> RGB(A) is called on the seen pixels' u and v.
- A colour field: ``color=`` a second expression of u and v, or an array indexed as
  heights, mapped through the material's cmap and norm/vmin/vmax (its range over the
  seen pixels by default) instead of f.

Both sides of the surface take the colour. Nothing here runs where a material has
neither (the finishing pass then colours by height, as before).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _pool, color
from ..color import lower_or_upper
from ..kernels.layout import VP_CU, VP_CV, VP_WORG
from ..kernels.texture import (
    FILTER_LINEAR, FILTER_MIPMAP, FILTER_POINT, colour_kernel, field_kernel, planes_kernel,
    texture_kernel, values_kernel,
)

#: texture_filter's values and their kernel codes
FILTERS = {"mipmap": FILTER_MIPMAP, "linear": FILTER_LINEAR, "point": FILTER_POINT}
#: The most texels a texture may have (its mip-map pyramid: about 1.4 GB of float32)
MAX_TEXELS = 1 << 26


def _centre(geom):
    """(cu, cv): the view's centre, from which the G-buffer holds u and v (layout.py
    G_U)."""
    return float(geom.vp[VP_CU]), float(geom.vp[VP_CV])


def _w_origin(geom):
    """What the G-buffer holds w from (layout.py G_W)."""
    return float(geom.vp[VP_WORG])


def picture_planes(geom, W, box=(1.0, 1.0, 1.0), edges=False):
    """(u, v, w, side) of each pixel, top row first, from a layer's tiled G-buffer
    and edge buffer (the column pass's), in the surface's units (the box's stretch
    divided out): side +1 upper, -1 lower, 0 nothing (NaN u, v, w there); with
    ``edges`` also (eu, ev) of each pixel's edge surface (NaN where none)."""
    H = geom.gbuf.shape[1]
    # pooled (fresh memory's page faults were most of the pass; each is written in full)
    u, v, w, side = (_pool.empty((H, W), np.float64) for _ in range(4))
    eu, ev = (_pool.empty((H, W), np.float64) if edges else np.empty((0, 0)) for _ in range(2))
    planes_kernel(geom.gbuf, geom.ebuf, W, *(float(x) for x in box), *_centre(geom),
                  _w_origin(geom), u, v, w, side, eu, ev)
    return (u, v, w, side, eu, ev) if edges else (u, v, w, side)


# -- textures --------------------------------------------------------------------

def read_image(texture):
    """A texture as an (h, w, 4) float32 array in [0, 1] (alpha 1 where it has none),
    rows along v, columns along u: an array (h, w, 3|4) of uint8 or floats in [0, 1],
    or the path of an image file."""
    import os
    if isinstance(texture, (str, os.PathLike)):
        path = os.fspath(texture)
        from PIL import Image
        try:
            with Image.open(path) as im:
                if im.width * im.height > MAX_TEXELS:
                    raise ValueError(f"texture {path!r} has {im.width}x{im.height} pixels, "
                                     f"more than {MAX_TEXELS} (8192x8192): use a smaller image")
                arr = np.asarray(im.convert("RGBA"))
        except (OSError, Image.DecompressionBombError, SyntaxError) as exc:
            raise ValueError(f"texture {path!r} cannot be read as an image: {exc}") from None
        return np.ascontiguousarray(arr[::-1] / np.float32(255.0), dtype=np.float32)
    try:
        arr = np.asarray(texture)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"texture must be an image array or a file's path: {exc}") from None
    if arr.ndim != 3 or arr.shape[2] not in (3, 4) or arr.shape[0] < 1 or arr.shape[1] < 1:
        raise ValueError("texture must be an image array of shape (h, w, 3) or (h, w, 4), "
                         f"got shape {arr.shape}")
    if arr.shape[0] * arr.shape[1] > MAX_TEXELS:
        raise ValueError(f"texture has {arr.shape[1]}x{arr.shape[0]} texels, more than "
                         f"{MAX_TEXELS} (8192x8192): use a smaller image")
    if arr.dtype == np.uint8:
        arr = arr / np.float32(255.0)
    elif arr.dtype.kind in "fiub":
        arr = arr.astype(np.float64)
        if not np.isfinite(arr).all() or arr.min() < 0.0 or arr.max() > 1.0:
            raise ValueError("texture values must be uint8 or floats in [0, 1]")
    else:
        raise ValueError(f"texture must hold numbers, got dtype {arr.dtype}")
    out = np.ones(arr.shape[:2] + (4,), dtype=np.float32)
    out[..., :arr.shape[2]] = arr
    return out


def pyramid(img):
    """The mip-map levels of an (h, w, 4) image: each the 2 x 2 box average of the
    level before (an odd row or column repeated), down to one texel. Colours are
    premultiplied by alpha so that transparent texels do not darken."""
    level = img.copy()
    level[..., :3] *= level[..., 3:4]
    levels = [level]
    while level.shape[0] > 1 or level.shape[1] > 1:
        if level.shape[0] % 2:
            level = np.concatenate([level, level[-1:]], axis=0)
        if level.shape[1] % 2:
            level = np.concatenate([level, level[:, -1:]], axis=1)
        level = 0.25 * (level[0::2, 0::2] + level[1::2, 0::2] + level[0::2, 1::2]
                        + level[1::2, 1::2])
        levels.append(level.astype(np.float32))
    return levels


class Levels:
    """A texture's mip-map levels flattened for texture_kernel: ``flat`` float32, level
    k's (h, w, 4) texels from offsets[k], shapes[k] = (h, w)."""

    def __init__(self, levels):
        self.shapes = np.array([lv.shape[:2] for lv in levels], dtype=np.int64)
        sizes = np.array([lv.size for lv in levels], dtype=np.int64)
        self.offsets = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(np.int64)
        self.flat = np.concatenate([lv.ravel() for lv in levels]).astype(np.float32)


def _bilinear(level, x, y):
    """Bilinear lookup of ``level`` at texel coordinates (x along columns, y along
    rows; texel k's centre at k), clamped to its edge."""
    h, w = level.shape[:2]
    x = np.clip(x, 0.0, w - 1.0)
    y = np.clip(y, 0.0, h - 1.0)
    x0 = np.minimum(np.floor(x).astype(np.int64), w - 1)
    y0 = np.minimum(np.floor(y).astype(np.int64), h - 1)
    x1 = np.minimum(x0 + 1, w - 1)
    y1 = np.minimum(y0 + 1, h - 1)
    fx = (x - x0)[:, None]
    fy = (y - y0)[:, None]
    top = level[y0, x0] * (1 - fx) + level[y0, x1] * fx
    bot = level[y1, x0] * (1 - fx) + level[y1, x1] * fx
    return top * (1 - fy) + bot * fy


def texture_base(tex, geom, W, H, box, extent, filt, lut, w_lo, w_hi, lower_rgb):
    """base (H, W, 3) float32 of a texture (Levels) over the surface's own colours
    (kernels/texture.py's texture_kernel)."""
    h, w = (int(x) for x in tex.shapes[0])
    u0, u1, v0, v1 = extent
    a, b = float(box[0]), float(box[1])
    # node-centred as a height field's grid: texel i at u0 + i (u1 - u0) / (w - 1);
    # the G-buffer's u is the box's, a u
    su = (w - 1) / ((u1 - u0) * a) if w > 1 else 0.0
    sv = (h - 1) / ((v1 - v0) * b) if h > 1 else 0.0
    # (pooled: fresh memory's page faults cost more than the lookups; every buffer is
    # read only where the kernel wrote it: where a surface is seen)
    base = _pool.empty((H, W, 6), np.float32)
    tx, ty = _pool.empty((H, W), np.float64), _pool.empty((H, W), np.float64)
    wp = _pool.empty((H, W), np.float64)
    sides = _pool.empty((H, W), np.int8)
    seen = _pool.empty((H, W), np.bool_)
    cu, cv = _centre(geom)             # (the G-buffer's u, v from there: layout.py G_U)
    texture_kernel(geom.gbuf, geom.ebuf, W, u0 * a - cu, su, v0 * b - cv, sv, _w_origin(geom),
                   tex.flat, tex.offsets,
                   tex.shapes, FILTERS[filt], lut, float(w_lo), float(w_hi),
                   np.asarray(lower_rgb, dtype=np.float64), tx, ty, wp, sides, seen, base)
    return base


def _called(fn, u, v):
    """A callable texture's (n, 4) premultiplied colours at (u, v)."""
    try:
        res = fn(u, v)
    except Exception as exc:        # the user's function: any failure is theirs to fix
        raise ValueError(f"texture function failed: {type(exc).__name__}: {exc}") from None
    if isinstance(res, (tuple, list)):
        res = np.stack([np.broadcast_to(np.asarray(c, dtype=np.float64), u.shape)
                        for c in res], axis=-1)
    res = np.asarray(res, dtype=np.float64)
    if res.shape[:1] != u.shape or res.ndim != 2 or res.shape[1] not in (3, 4):
        raise ValueError("a texture function must return colours of shape (n, 3) or (n, 4) "
                         "(or a tuple of 3 or 4 arrays) for n points")
    res = np.clip(np.nan_to_num(res, nan=0.0), 0.0, 1.0)
    out = np.ones((u.size, 4))
    out[:, :res.shape[1]] = res
    out[:, :3] *= out[:, 3:4]
    return out


# -- colour fields ----------------------------------------------------------------

def field_values(field, u, v, seen, extent):
    """The colour field at the seen pixels: a Surface (its f), or a 2-D array
    bilinear over ``extent`` as a height field."""
    us, vs = u[seen], v[seen]
    if isinstance(field, np.ndarray):
        h, w = field.shape
        u0, u1, v0, v1 = extent
        x = (us - u0) / (u1 - u0) * (w - 1)
        y = (vs - v0) / (v1 - v0) * (h - 1)
        return _bilinear(field[..., None], x, y)[:, 0]
    out = np.empty(us.size)
    values_kernel(*field.kernel_args(), np.ascontiguousarray(us, dtype=np.float64),
                  np.ascontiguousarray(vs, dtype=np.float64), out)
    return out


def colour_table_rgb(values, lut, lo, hi):
    """Colours of ``values`` from a material's colour table (as shade._side_rgb)."""
    if lut.shape[1] > 3:
        idx = np.maximum(np.searchsorted(lut[:, 3], values, side="right") - 1, 0)
    else:
        span = hi - lo if hi > lo else 1.0
        x = np.nan_to_num((values - lo) / span * (lut.shape[0] - 1))
        idx = np.clip(x, 0, lut.shape[0] - 1).astype(np.int64)
    return lut[idx, :3]


def field_table(material, vals, lower_rgb, c_range=None):
    """A colour field's colour map over the values seen (``vals``, NaN where none; or
    ``c_range`` (lo, hi) where given): (lut, lo, hi, c_limits, the colour of a NaN
    value: the colour map's "bad" colour where one is set, else the lower side's)."""
    if c_range is not None:
        rng = np.array([c_range], dtype=np.float64)
    else:
        finite = vals[np.isfinite(vals)]
        rng = np.array([[finite.min(), finite.max()]]) if finite.size else \
            np.array([[0.0, 1.0]])
    lut, lo, hi, limits = material.color_table(rng)
    nan_rgb = color.bad(material.cmap)
    if nan_rgb is None:
        nan_rgb = lower_or_upper(lower_rgb, lut[0, :3])
    return lut, lo, hi, limits, nan_rgb


def field_rgb(vals, table):
    """The colours of a colour field's values on its map (field_table's)."""
    lut, lo, hi, _, nan_rgb = table
    rgb = colour_table_rgb(vals, lut, lo, hi)
    rgb[~np.isfinite(vals)] = nan_rgb
    return rgb


def field_base(material, field, geom, W, H, box, lower_rgb, c_range=None):
    """(base (H, W, 6) float32, c_limits) of a colour field given as an expression
    (kernels/texture.py's field_kernel and colour_kernel); c_range as base_colours'."""
    vals = _pool.empty((H, W), np.float64)
    e_vals = _pool.empty((H, W), np.float64)
    field_kernel(geom.gbuf, geom.ebuf, W, float(box[0]), float(box[1]), *_centre(geom),
                 *field.kernel_args(), vals, e_vals)
    with np.errstate(all="ignore"):
        lo, hi = np.nanmin(vals) if np.isfinite(vals).any() else 0.0, \
            np.nanmax(vals) if np.isfinite(vals).any() else 1.0
    if c_range is not None:
        lo, hi = c_range
    lut, c_lo, c_hi, limits = material.color_table(np.array([[lo, hi]], dtype=np.float64))
    base = _pool.empty((H, W, 6), np.float32)
    # (a NaN value: the colour map's "bad" colour where one is set, else the lower side's)
    nan_rgb = color.bad(material.cmap)
    colour_kernel(vals, e_vals, np.ascontiguousarray(lut, dtype=np.float64), float(c_lo),
                  float(c_hi), np.asarray(lower_rgb if nan_rgb is None else nan_rgb,
                                          dtype=np.float64), base)
    return base, (limits if np.isfinite(vals).any() else None)


def base_colours(material, source, geom, W, H, box, colours, c_range=None):
    """(base (H, W, 6) float32, c_limits or None): the colour of the surface at each
    pixel and of its edge surface (finish_kernel's ``base``) from a material's texture
    or colour field (``source``, prepare's) over its own colours (``colours``,
    Material.table). A colour field's colour map spans the values seen, or
    ``c_range`` (lo, hi) where given (a sub-column's picture takes the centre's
    c_limits)."""
    lut, w_lo, w_hi, lower_rgb = colours.lut, colours.w_lo, colours.w_hi, colours.lower_rgb
    if source.field is None and not callable(source.texture):
        return texture_base(source.texture, geom, W, H, box, source.extent, source.filter,
                            lut, w_lo, w_hi, lower_rgb), None
    if source.field is not None and not isinstance(source.field, np.ndarray):
        return field_base(material, source.field, geom, W, H, box, lower_rgb, c_range)
    u, v, w, side, eu, ev = picture_planes(geom, W, (box[0], box[1], 1.0), edges=True)
    seen = side != 0.0
    edge = np.isfinite(eu)
    base = np.zeros((H, W, 6), dtype=np.float32)
    if not seen.any():
        return base, None
    limits = None
    if source.field is not None:
        vals = field_values(source.field, u, v, seen, source.extent)
        table = field_table(material, vals, lower_rgb, c_range)
        limits = table[3]
        own = field_rgb(vals, table)
        if edge.any():                                 # the edge surfaces' own values
            e_vals = field_values(source.field, eu, ev, edge, source.extent)
            base[edge, 3:] = np.clip(field_rgb(e_vals, table), 0.0, 1.0)
    else:
        # the surface's own colour under a texture's transparent parts: its side's
        # (w and the table's ends both in the box's units)
        own = colour_table_rgb(w[seen], lut, w_lo, w_hi)
        lower = side[seen] < 0
        own[lower] = lower_or_upper(lower_rgb, own[lower])
    if source.texture is not None:                     # a texture function
        tex = _called(source.texture, u[seen], v[seen])
        own = tex[:, :3] + (1.0 - tex[:, 3:4]) * own    # premultiplied over its own colour
        if edge.any():                                 # (over the lower side's colour)
            e_tex = _called(source.texture, eu[edge], ev[edge])
            base[edge, 3:] = np.clip(e_tex[:, :3] + (1.0 - e_tex[:, 3:4]) *
                                     lower_or_upper(lower_rgb, lut[0, :3]), 0.0, 1.0)
    base[seen, :3] = np.clip(own, 0.0, 1.0)
    return base, limits


@dataclass
class Source:
    """A layer's colour source: the texture's mip-map levels (or its function), the
    colour field (a Surface or an array), the extent (u0, u1, v0, v1) both span, the
    texture's filter."""
    texture: object
    field: object
    extent: tuple
    filter: str
    #: a translucent surface's colour field sampled on the FIELD_TEXELS grid over the
    #: extent (its contours are drawn from it: kernels/texture.py LN_*), and the
    #: limits of its colours (vmin, vmax or its range)
    grid: object = None
    limits: object = None


_LEVELS = {}          # a texture's mip-map levels, by its identity and contents


def _levels(texture):
    import hashlib
    import os
    if isinstance(texture, (str, os.PathLike)):
        path = os.fspath(texture)
        try:
            key = ("file", path, os.path.getmtime(path), os.path.getsize(path))
        except OSError as exc:
            raise ValueError(f"texture {path!r} cannot be read: {exc.strerror}") from None
    else:
        arr = np.asarray(texture) if not isinstance(texture, np.ndarray) else texture
        if arr.ndim == 3 and arr.shape[0] * arr.shape[1] > MAX_TEXELS:
            return Levels(pyramid(read_image(arr)))     # (read_image says what is wrong)
        key = ("array", arr.shape, str(arr.dtype),
               hashlib.blake2b(np.ascontiguousarray(arr).tobytes(), digest_size=16).digest())
    if key not in _LEVELS:
        if len(_LEVELS) >= 4:
            _LEVELS.pop(next(iter(_LEVELS)))
        _LEVELS[key] = Levels(pyramid(read_image(texture)))
    return _LEVELS[key]


def prepare(material, domain, vars=None):
    """A layer's Source, or None where its material has no texture and no colour
    field."""
    if not material.colored:
        return None
    if material.texture is not None and material.color is not None:
        raise ValueError("give either texture or color (colour from data), not both")
    (ua, ub), (va, vb) = domain
    extent = material.texture_extent
    if extent is None:
        extent = (ua, ub, va, vb)
    else:
        try:
            extent = tuple(float(x) for x in extent)
        except (TypeError, ValueError):
            raise ValueError("texture_extent must be (u0, u1, v0, v1), four numbers, got "
                             f"{extent!r}") from None
        if len(extent) != 4 or not all(math.isfinite(x) for x in extent) or \
                extent[0] == extent[1] or extent[2] == extent[3]:
            raise ValueError("texture_extent must be (u0, u1, v0, v1), finite, with u0 != u1 "
                             f"and v0 != v1, got {material.texture_extent!r}")
    tex = material.texture
    if tex is not None and not callable(tex):
        tex = _levels(tex)
    field = material.color
    if field is not None:
        from ..surface import array_like, as_surface
        if (isinstance(field, list) or array_like(field)) and np.ndim(field) == 2:
            try:
                field = np.array(field, dtype=np.float64)
            except (TypeError, ValueError):
                raise ValueError("color as an array must hold numbers") from None
            if field.shape[0] < 2 or field.shape[1] < 2:
                raise ValueError(f"color as an array needs at least 2 x 2 values, got shape "
                                 f"{field.shape}")
            field[~np.isfinite(field)] = np.nan
        else:
            field = as_surface(field, vars)
    if field is not None and material.opacity < 1.0:
        # the translucent layers read a texture: the field sampled on a grid, coloured
        vals = _field_grid(field, extent)
        levels, limits = _field_texture(material, vals)
        return Source(levels, None, extent, "mipmap", vals, limits)
    if callable(tex) and material.opacity < 1.0:
        # ... and a texture function's colours on that grid
        return Source(_function_texture(tex, extent), None, extent, "mipmap")
    return Source(tex, field, extent, material.texture_filter)


#: A colour field or a texture function on a translucent surface is read as a texture
#: of this many texels a side (sampled at their nodes over the extent)
FIELD_TEXELS = 1024


def _function_texture(fn, extent):
    """Levels of a texture function's colours on a FIELD_TEXELS grid (its alpha kept:
    the surface's own colour shows where it is transparent)."""
    n = FIELD_TEXELS
    u0, u1, v0, v1 = extent
    gu, gv = np.meshgrid(np.linspace(u0, u1, n), np.linspace(v0, v1, n))
    pre = _called(fn, gu.ravel(), gv.ravel())            # (premultiplied)
    img = np.zeros((n * n, 4), dtype=np.float32)
    a = pre[:, 3]
    img[:, 3] = a
    ok = a > 0.0
    img[ok, :3] = pre[ok, :3] / a[ok, None]              # (pyramid premultiplies again)
    return Levels(pyramid(img.reshape(n, n, 4)))


def _field_grid(field, extent):
    """The colour field's values at the nodes of a FIELD_TEXELS grid over ``extent``
    (rows along v; NaN at its holes)."""
    n = FIELD_TEXELS
    u0, u1, v0, v1 = extent
    gu, gv = np.meshgrid(np.linspace(u0, u1, n), np.linspace(v0, v1, n))
    return field_values(field, gu, gv, np.ones(gu.shape, dtype=bool), extent).reshape(n, n)


def _field_texture(material, vals):
    """(levels, limits): the mip-map levels of the colour field's colours on its grid
    ``vals`` (NaN: the colour map's "bad" colour where one is set, else transparent:
    the surface's own colour shows) and the limits of its
    colours (Material.color_table's, in the field's units)."""
    n = vals.shape[0]
    finite = vals[np.isfinite(vals)]
    rng = np.array([[finite.min(), finite.max()]]) if finite.size else np.array([[0.0, 1.0]])
    lut, lo, hi, limits = material.color_table(rng)
    img = np.zeros((n, n, 4), dtype=np.float32)
    ok = np.isfinite(vals)
    img[ok, :3] = colour_table_rgb(vals[ok], lut, lo, hi)
    img[ok, 3] = 1.0
    nan_rgb = color.bad(material.cmap)                 # a "bad" colour set: NaN takes it
    if nan_rgb is not None:
        img[~ok, :3] = nan_rgb
        img[~ok, 3] = 1.0
    return Levels(pyramid(img)), limits


def check_filter(name):
    if not isinstance(name, str) or name not in FILTERS:
        raise ValueError(f"texture_filter must be one of {', '.join(FILTERS)}, got {name!r}")
    return name


def levels_of(n, lo, hi):
    """N levels evenly inside (lo, hi) (matplotlib's contour picks 'nice' ones; these
    split the range in N + 1 equal parts)."""
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
        return np.zeros(0)
    return lo + (hi - lo) * np.arange(1, n + 1) / (n + 1)

"""The area-sampling geometry pass (``antialias="area"``; Cohen-Or 1997): every column
by exact area sampling (kernels/area.py) into the same tiled G-buffer and edge buffer
as the column pass, so finishing, shadows, textures and lines read it unchanged. A
height field is sampled through a pyramid of its heights (``levels``), the level of
each plane by the footprint of a pixel there."""
from __future__ import annotations

import math

import numpy as np

from ..kernels.area import (LV_CELL, LV_NU, LV_NV, LV_OFF, LV_SIZE, LV_ZMAX, LV_ZMIN,
                            area_kernel)
from ..kernels.layout import SURF_HEIGHTFIELD
from .geometry import Geometry, pass_outputs

#: how much coarser than a pixel's footprint the level sampled is, in levels (a
#: mip-map's bias), and columns per pixel: measured by benchmarks/bench_terrain.py's
#: flicker (pixels changing 6-60 levels over a 0.02 deg/frame orbit, 1025^2 fractal
#: DEMs at 320x240 in perspective; against point sampling, seeds 11 and 7): bias 0.5
#: 0.116x and 0.102x, 0.75 0.106x and 0.094x, 1 0.093x and 0.080x (blurrier); two
#: columns a pixel at 0.5: 0.110x and 0.103x for twice the time. What remains is at the
#: silhouettes, whose motion (up to 0.06 px a frame) changes even an exact box filter's
#: pixels by 6 levels and more where the contrast is high.
LOD_BIAS = 1.0
SLICES = 1
#: levels of a pyramid at most (a 2**16-cell grid halves to 2 x 2 in 16)
MAX_LEVELS = 16
#: a function surface's level table: no heights, no cell
_NO_HEIGHTS = np.zeros(0)
_NO_LEVELS = np.array([[0.0, 0.0, 0.0, np.inf, np.nan, np.nan]])


def area_pass(surface, view, vp, buffers, device="cpu"):
    """Run the area kernel of one layer into ``buffers`` (geometry.allocate's), on the
    CPU's cores or (``device="cuda"``) an NVIDIA GPU's (kernels/cuda.py)."""
    gbuf, ebuf, hrec = buffers
    evals, wrange, rows = pass_outputs(view.width, gbuf.shape[0])
    flat, lv = levels(surface)
    if device == "cuda":
        from ..kernels.cuda import area_kernel_cuda
        area_kernel_cuda(surface, flat, lv, vp, SLICES, 2.0 ** LOD_BIAS, gbuf, ebuf, evals,
                         wrange, rows)
        return Geometry(gbuf, ebuf, hrec, rows, wrange, evals, vp, None, 0)
    kind, f, fg, _, hf, hfp = surface.kernel_args(None)
    area_kernel(kind, f, fg, flat, lv, hfp, vp, SLICES, 2.0 ** LOD_BIAS, gbuf, ebuf, evals,
                wrange, rows)
    return Geometry(gbuf, ebuf, hrec, rows, wrange, evals, vp, None, 0)


def levels(surface):
    """(flat heights, level table (n, LV_SIZE)) of a surface's level-of-detail
    pyramid: level 0 the heights themselves, each next one smoothed by the binomial
    filter (1, 2, 1)/4 along both axes (NaN-aware: a hole stays a hole only where all
    its neighbours are) and resampled to half the cells over the same extent, until
    2 x 2. Kept on the height field (its box-stretched copies share their source's).
    A function surface has none."""
    if surface.kind != SURF_HEIGHTFIELD:
        return _NO_HEIGHTS, _NO_LEVELS
    source, c = getattr(surface, "stretched_from", (surface, 1.0))
    cache = source.__dict__.setdefault("_pyramids", {})
    if c not in cache:
        base = cache.get(1.0)
        if base is None:
            base = cache[1.0] = _pyramid(source.hf)
            # the heights kept once: the source's are the pyramid's level 0 (the same
            # values; a 4097^2 DEM's 134 MB not twice)
            source.hf = base[0]
        if c != 1.0:
            cache.clear()
            cache[1.0] = base
            # (the stretched pyramid in one array too, its levels views into it)
            cache[c] = _views(base[0].base * c, [z.shape for z in base])
    grids = cache[c]
    if surface is not source and surface.hf.shape == grids[0].shape \
            and surface.hf.base is not grids[0].base:
        # a stretched copy's heights are its pyramid's level 0 too (the same values,
        # its source's times c: kept once)
        surface.hf = grids[0]
    (ua, ub), (va, vb) = surface.default_domain
    lv = np.empty((len(grids), LV_SIZE))
    off = 0
    for k, z in enumerate(grids):
        nv, nu = z.shape
        lv[k, LV_OFF] = off
        lv[k, LV_NV] = nv
        lv[k, LV_NU] = nu
        lv[k, LV_CELL] = max((ub - ua) / (nu - 1), (vb - va) / (nv - 1))
        lv[k, LV_ZMIN], lv[k, LV_ZMAX] = _height_range(source, c, k, z)
        off += z.size
    key = ("flat", c)
    held = source.__dict__.get("_flat")
    if held is None or held[0] != key:
        # the one array the levels are views into (_pyramid, _views)
        held = source.__dict__["_flat"] = (key, grids[0].base)
    return held[1], lv


def _height_range(source, c, k, z):
    """(lowest, highest) finite height of level k of a pyramid (NaN, NaN: none),
    kept on the source with it."""
    ranges = source.__dict__.setdefault("_height_ranges", {})
    if (c, k) not in ranges:
        if len(ranges) > 64:
            ranges.clear()
        if np.isfinite(z).any():
            ranges[(c, k)] = (float(np.nanmin(z)), float(np.nanmax(z)))
        else:
            ranges[(c, k)] = (np.nan, np.nan)
    return ranges[(c, k)]


def _pyramid(z):
    """The levels, views into one flat float64 array (their ``base``): level 0 the
    heights z, each next one _halve's of the one before. One array from the start:
    no second copy of every level to concatenate (a 4097^2 DEM's 180 MB)."""
    shapes = [tuple(z.shape)]
    while len(shapes) < MAX_LEVELS and max(shapes[-1]) > 2:
        shapes.append(tuple(_halved(n) for n in shapes[-1]))
    flat = np.empty(sum(a * b for a, b in shapes))
    grids = _views(flat, shapes)
    grids[0][...] = z
    for k in range(1, len(grids)):
        grids[k][...] = _halve(grids[k - 1])
    return grids


def _views(flat, shapes):
    """The grids of these shapes one after the other in ``flat``, as views."""
    out = []
    off = 0
    for shape in shapes:
        n = shape[0] * shape[1]
        out.append(flat[off:off + n].reshape(shape))
        off += n
    return out


def _halved(n):
    """The nodes along an axis of n nodes at the next level."""
    return max(2, int(math.ceil((n - 1) / 2)) + 1) if n > 2 else n


def _halve(z):
    """z smoothed (1, 2, 1)/4 along both axes, NaN-aware, and resampled to
    ceil((n - 1) / 2) + 1 nodes along each axis over the same extent."""
    for axis in (0, 1):
        z = _smooth(z, axis)
    for axis in (0, 1):
        z = _resample(z, axis, _halved(z.shape[axis]))
    return np.ascontiguousarray(z)


def _smooth(z, axis):
    """z filtered (1, 2, 1)/4 along ``axis``, its ends repeated; NaN-aware: the
    weights of the finite nodes among the three, NaN where none is. Slices, not
    copies by index (a 4097^2 DEM's pyramid 1.7 -> 0.5 s; the same values bit for
    bit, tests/test_area.py), and no weights where every node is finite (they are
    all 4 there)."""
    ok = np.isfinite(z)
    if ok.all():
        s = _filt(z, axis)
        s /= 4.0
        return s
    zz = np.where(ok, z, 0.0)
    s = _filt(zz, axis)
    k = _filt(ok.astype(np.float64), axis)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(k > 0, s / np.where(k > 0, k, 1.0), np.nan)


def _filt(a, axis):
    """a[i - 1] + 2 a[i] + a[i + 1] along ``axis`` (in that order), a's ends
    repeated."""
    a = np.moveaxis(a, axis, 0)
    out = np.empty_like(a)
    n = a.shape[0]
    if n == 1:
        out[0] = a[0] + 2 * a[0] + a[0]
        return np.moveaxis(out, 0, axis)
    out[1:-1] = a[:-2] + 2 * a[1:-1]
    out[1:-1] += a[2:]
    out[0] = a[0] + 2 * a[0] + a[1]
    out[-1] = a[-2] + 2 * a[-1] + a[-1]
    return np.moveaxis(out, 0, axis)


def _resample(z, axis, m):
    """z at m nodes evenly over its extent along ``axis``: linear between the two
    nodes about each (NaN-aware: a node next to a hole keeps the finite neighbour's
    height)."""
    n = z.shape[axis]
    if m == n:
        return z
    if n > 2 and (n - 1) % 2 == 0 and m == (n - 1) // 2 + 1:
        # every other node (an odd count, as 4097): linspace's nodes 0, 2, .., n - 1
        # exactly, so i0 = x but for the last (n - 2, f = 1): slices instead of copies
        # by index (a 4097^2 DEM's pyramid 0.24 -> 0.1 s), the same formula below
        zz = np.moveaxis(z, axis, 0)
        a = np.concatenate([zz[0:n - 1:2], zz[n - 2:n - 1]])
        b = np.concatenate([zz[1:n:2], zz[n - 1:n]])
        f = np.zeros((m,) + (1,) * (z.ndim - 1))
        f[-1] = 1.0
        with np.errstate(invalid="ignore"):        # (an infinite height: a hole)
            out = np.where(np.isfinite(a) & np.isfinite(b), a * (1 - f) + b * f,
                           np.where(f < 0.5, a, b))
        return np.moveaxis(out, 0, axis)
    x = np.linspace(0.0, n - 1.0, m)
    i0 = np.minimum(np.floor(x).astype(int), n - 2)
    f = x - i0
    a = np.take(z, i0, axis)
    b = np.take(z, i0 + 1, axis)
    shape = [1, 1]
    shape[axis] = m
    f = f.reshape(shape)
    # (NaN-aware: a node next to a hole keeps the finite neighbour's height)
    with np.errstate(invalid="ignore"):            # (an infinite height: a hole)
        out = np.where(np.isfinite(a) & np.isfinite(b), a * (1 - f) + b * f,
                       np.where(f < 0.5, a, b))
    return out

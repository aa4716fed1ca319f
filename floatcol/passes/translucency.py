"""The translucency pass (Gordon 6.5-6.6): every layer of every surface along each
pixel's ray, composited front to back.

A scene where some layer's material has ``opacity`` < 1 takes this pass instead of
the opaque column, shading and composite passes (renderer.py): per band of columns,
kernels/layers.py's layers_kernel collects each surface's crossings into per-pixel
lists (one record a pixel for a surface alone; up to MAX_RECORDS where several
must be merged), and composite_kernel merges the surfaces' lists by depth and
composites them over the transmittance, stopping when it falls below 1/512. The
bands are as wide as LIST_BYTES of lists allow: the memory is bounded whatever the
picture's size and the number of layers.

With antialiasing (the default shading's), each crossing's alpha is the part of its
pixel its stretch of the curve covers (silhouettes, folds, the domain's edge, holes),
and SUB_COLUMNS columns a pixel (offsets -1/3, 0, 1/3) are averaged across; antialias
= 2, 3 or 4 asks for that many. Render.side, depth, shadow, the G-buffer (u, v, w,
normal) and stats["surface"] describe the nearest crossing at the pixel's centre
column (or the sub-column nearest it); ``intensity`` is the composite of the
layers' intensities over black, sum_k a_k prod_{m<k} (1 - a_m) I_k; ``rgba`` the
composite of their colours over the background.
"""
from __future__ import annotations

import math

import numpy as np

from .. import _pool, color
from ..kernels import layers as K
from ..kernels.layout import G_SIZE, TILE, VP_AA, VP_XOFF
from ..result import Render
from . import geometry
from .overlays import contour_levels, wire_counts, wire_lines
from .shadow import BIAS_TEXELS, GRAZING

#: bytes of crossing lists and their G-buffer records a band of columns may hold
LIST_BYTES = 64 * 2**20
#: sub-columns a pixel where antialiasing asks for them and names no number
SUB_COLUMNS = 3
#: most records a pixel keeps of one surface where several are merged (deeper ones
#: fold into the last: exact unless another surface's crossing falls between them)
MAX_RECORDS = 16


def records(opacity, n_surfaces):
    """Records a pixel keeps of a surface of this opacity: one alone (folding is
    exact), else as many as can show through (1 - a)^k >= STOP, at most MAX_RECORDS;
    none where the surface is invisible."""
    if opacity <= 0.0:
        return 0
    if n_surfaces == 1 or opacity >= 1.0:
        return 1
    need = math.ceil(math.log(K.STOP) / math.log1p(-opacity))
    return int(min(max(need, 1), MAX_RECORDS))


def offsets(sub_columns):
    """The sub-columns' offsets in pixels, and which is nearest the centre."""
    off = (np.arange(sub_columns) - (sub_columns - 1) / 2.0) / sub_columns
    return off, int(np.argmin(np.abs(off)))


def band_columns(W, H, slots, n):
    """Columns a band may hold: its lists (slots records a pixel) and G-buffer records
    (n surfaces) within LIST_BYTES."""
    per_column = H * (slots * K.C_SIZE * 4 + n * (G_SIZE * 4 + 4) + 4)
    return int(max(1, min(W, LIST_BYTES // max(per_column, 1))))


_NO_TEXTURE = (np.zeros(0, np.float32), np.zeros(1, np.int64), np.ones((1, 2), np.int64),
               np.zeros(4))


def layer_texture(source, box):
    """(levels, offsets, shapes, tp) of a layer's texture for kernels/layers.py
    (texture.py's TP_*: the texel map of the box's u, v), or empty levels: none."""
    if source is None or source.texture is None:
        return _NO_TEXTURE
    tex = source.texture
    h, w = (int(x) for x in tex.shapes[0])
    u0, u1, v0, v1 = source.extent
    a, b = float(box[0]), float(box[1])
    tp = np.array([u0 * a, (w - 1) / ((u1 - u0) * a) if w > 1 else 0.0,
                   v0 * b, (h - 1) / ((v1 - v0) * b) if h > 1 else 0.0])
    return tex.flat, tex.offsets, tex.shapes, tp


_NO_LINES = np.zeros(0)


def layer_lines(material, domain, box, w_limits, source=None):
    """A layer's lines for kernels/layers.py (texture.py's LN_*: its contours of w, or
    of its colour field from the field's grid (``source.grid``), and its wireframe,
    as overlays.overlay_pass draws them on an opaque surface, in the box's units), or
    an empty array: none."""
    from ..kernels import texture as T
    if not material.overlaid:
        return _NO_LINES
    levels = np.zeros(0)
    grid = np.zeros(0)
    head = np.zeros(T.LN_SIZE)
    if material.contours is not None:
        if source is not None and source.grid is not None:     # a colour field's
            levels = np.sort(contour_levels(material.contours, *source.limits))
            grid = np.ascontiguousarray(source.grid, dtype=np.float64).ravel()
            n = source.grid.shape[0]
            u0, u1, v0, v1 = source.extent
            head[T.LN_FN] = n
            head[T.LN_FU0], head[T.LN_FSU] = u0 * box[0], (n - 1) / ((u1 - u0) * box[0])
            head[T.LN_FV0], head[T.LN_FSV] = v0 * box[1], (n - 1) / ((v1 - v0) * box[1])
        else:                                                   # w's, in the box's units
            levels = np.sort(contour_levels(material.contours, *w_limits)) * box[2]
        head[T.LN_NLEV] = len(levels)
        head[T.LN_CW] = material.contour_width
        head[T.LN_CR:T.LN_CB + 1] = color.to_rgb(material.contour_color, "contour_color")[:3]
    wire = []
    if material.wireframe is not None:
        (pu, _), (pv, _) = wire_lines(material.wireframe)
        if pu is None:                       # evenly spaced over the domain
            nu, nv = wire_counts(material.wireframe)
            (ua, ub), (va, vb) = domain
            head[T.LN_WIRE] = 1.0
            head[T.LN_U0], head[T.LN_DU] = ua * box[0], (ub - ua) / (nu - 1) * box[0]
            head[T.LN_V0], head[T.LN_DV] = va * box[1], (vb - va) / (nv - 1) * box[1]
        elif material.wire_coords is None:   # a mesh's own lines at their u and v
            head[T.LN_WIRE] = 2.0
            wire = [pu * box[0], pv * box[1]]
        else:                                # ... at levels of its column and row index
            ij, (u0, u1, v0, v1) = material.wire_coords
            ij = np.ascontiguousarray(ij, dtype=np.float64)
            head[T.LN_WIRE] = 3.0
            head[T.LN_GNY], head[T.LN_GNX] = ij.shape[:2]
            head[T.LN_GU0], head[T.LN_GSU] = u0 * box[0], (ij.shape[1] - 1) / ((u1 - u0) * box[0])
            head[T.LN_GV0], head[T.LN_GSV] = v0 * box[1], (ij.shape[0] - 1) / ((v1 - v0) * box[1])
            wire = [pu, pv, ij.ravel()]
        if pu is not None:
            head[T.LN_NWU], head[T.LN_NWV] = len(pu), len(pv)
        head[T.LN_EW] = material.linewidth
        head[T.LN_ER:T.LN_EB + 1] = color.to_rgb(material.edgecolor, "edgecolor")[:3]
    return np.concatenate([head, levels, grid, *wire])


#: kernels/layers.py's occ where no objects cast shadows
NO_OCCLUDERS = (np.zeros((1, 3, 3)), np.zeros((0, 9)), np.zeros(2, np.int64),
                np.zeros(0, np.int64), np.zeros((1, K.OG_SIZE)))
_NO_TEXTURE_PLANES = np.zeros((0, 1, 1), dtype=np.float32)
_NO_SLOPES = np.zeros((0, 1, 1))


def occluder_arrays(occluders):
    """kernels/layers.py's occ of objects.Occluders or DiskOccluders (one Occluders a
    direction over the light's disk): their frames, coef, start and items one after
    another, and a row of grids (OG_*) a direction, where its own begin."""
    parts = getattr(occluders, "parts", [occluders])
    grids = np.zeros((len(parts), K.OG_SIZE))
    at = np.zeros(3, np.int64)
    for k, o in enumerate(parts):
        grids[k, :K.OG_COEF] = o.ga, o.gb, o.inv_cell, o.na, o.nb, o.bias
        grids[k, K.OG_COEF:] = at
        at += len(o.coef), len(o.start), len(o.items)
    return (np.ascontiguousarray([o.frame for o in parts], dtype=np.float64),
            np.ascontiguousarray(np.concatenate([o.coef for o in parts]), dtype=np.float64),
            np.concatenate([o.start for o in parts]).astype(np.int64),
            np.concatenate([o.items for o in parts]).astype(np.int64), grids)


def shadow_vector(texture, view, layer):
    """kernels/layers.py's sh, the texture's planes (hmax, hmin, hsurf), its horizons'
    slopes (a light of a radius) and the objects' occluders occ of a layer."""
    sh = np.zeros(K.SH_SIZE)
    none = _NO_TEXTURE_PLANES
    if texture is None:
        return sh, none, none, none, _NO_SLOPES, NO_OCCLUDERS
    sh[K.SH_LX:K.SH_LZ + 1] = view.light
    sh[K.SH_ON] = 1.0
    sh[K.SH_LAYER] = layer
    sh[K.SH_GRAZING] = GRAZING
    sh[K.SH_BIAS] = BIAS_TEXELS
    occ = NO_OCCLUDERS
    o = texture.occluders
    if o is not None and len(getattr(o, "parts", [o])[0].items):
        occ = occluder_arrays(o)
        sh[K.SH_OBJ] = len(occ[0])
    if texture.zenith:
        sh[K.SH_H] = 1.0
        return sh, none, none, none, _NO_SLOPES, occ
    sh[K.SH_GU], sh[K.SH_GV], sh[K.SH_TAN] = texture.gu, texture.gv, texture.tan_theta
    sh[K.SH_S0], sh[K.SH_T0], sh[K.SH_H] = texture.s0, texture.t0, texture.h
    slopes = _NO_SLOPES
    if texture.rho > 0.0:
        sh[K.SH_RHO] = texture.rho
        slopes = texture.slopes
    return sh, texture.hmax, texture.hmin, texture.hsurf, slopes, occ


def translucent_pass(layers, views, drawn, box, quality, background, texture, stop=None):
    """The picture of ``layers`` (renderer.py's prepared layers; one View each, from
    one camera), every layer of each surface composited by depth. Returns
    (rgba, intensity, side, depth, shadow, which, gbuf, stats, front). With objects,
    ``stop`` (H, W) float32 the depth of the nearest at each pixel (inf: none), and
    front (front_acc, opaque) what lies over them (kernels/layers.py composite_kernel:
    the sums of the crossings nearer than ``stop``, and the depth behind which nothing
    shows); else front is None."""
    aa_cov, sub = quality.antialiasing(layers[0].material.shading)
    if aa_cov and sub == 1 and quality.antialias is not False:
        sub = SUB_COLUMNS
    view0 = views[0]
    W, H = view0.width, view0.height
    n = len(layers)
    # (with objects a surface alone keeps several records too: folding its crossings
    # into one would put those behind an object over it)
    ks = [records(p.material.opacity, n if stop is None else max(n, 2)) for p in layers]
    slots = max(int(sum(ks)), 1)
    B = band_columns(W, H, slots, n)
    # the picture's sums and arrays, and a band's lists: a bad size, not a MemoryError
    need = W * H * (8 * K.ACC_SIZE + 20 + 4 * G_SIZE) + LIST_BYTES
    geometry.check_bytes(W, H, need)
    try:
        return _composited(layers, views, drawn, box, background, texture, ks, slots, B,
                           aa_cov, sub, quality.device, stop)
    except MemoryError:
        raise ValueError(geometry.too_large(W, H, need)) from None


def _composited(layers, views, drawn, box, background, texture, ks, slots, B, aa_cov, sub,
                device="cpu", stop=None):
    """translucent_pass's work, its sizes settled; the layers of each band on
    ``device`` (kernels/cuda.py's layers_kernel_cuda on "cuda"), their composite
    here."""
    view0 = views[0]
    W, H = view0.width, view0.height
    n = len(layers)
    offs = np.concatenate([[0], np.cumsum(ks)[:-1]]).astype(np.int64)
    plans = []
    w_limits = []
    for k, (p, view, (surface, _)) in enumerate(zip(layers, views, drawn)):
        vp = geometry.view_params(view, "column", "uniform", (0.0,) * 6, aa_cov, surface)
        vp[VP_AA] = 1.0 if aa_cov else 0.0
        table = p.material.table(np.array([view.f_range]), box[2])
        w_limits.append(table.w_limits)
        sh, hmax, hmin, hsurf, slopes, occ = shadow_vector(texture, view, k)
        colours = (table.lut, *layer_texture(p.source, box),
                   layer_lines(p.material, p.domain, box, table.w_limits, p.source))
        plans.append((surface, vp, table.mp, colours, sh, hmax, hmin, hsurf, slopes, occ))
    offsets_px, centre = offsets(sub)
    order = [centre] + [i for i in range(sub) if i != centre]
    # (lists and gfirst are read only below counts, gbuf only where a layer is seen,
    # the rest written in full by each band's first pass: none is cleared)
    lists = _pool.empty((B, H, slots, K.C_SIZE), np.float32)
    counts = _pool.empty((n, B, H), np.int32)
    gfirst = _pool.empty((n, B, H, G_SIZE), np.float32)
    hits = _pool.empty((B, H), np.int32)
    evals = np.zeros(B, dtype=np.int64)
    acc = _pool.empty((H, W, K.ACC_SIZE), np.float64)
    side = _pool.empty((H, W), np.int8)
    depth = _pool.empty((H, W), np.float32)
    shadow = _pool.empty((H, W), np.float32)
    which = _pool.empty((H, W), np.int8)
    layers_seen = np.empty((H, W), dtype=np.int16)
    gbuf = _pool.empty((-(-W // TILE), H, TILE, G_SIZE), np.float32)
    if stop is None:
        stop = np.zeros((0, 0), np.float32)
        front_acc = np.zeros((0, 0, K.ACC_SIZE))
        opaque = np.zeros((0, 0), np.float32)
    else:
        front_acc = np.empty((H, W, K.ACC_SIZE))
        opaque = np.empty((H, W), np.float32)
    total_evals = 0
    weight = 1.0 / sub
    for c0 in range(0, W, B):
        for m in order:
            counts[:] = 0
            hits[:] = 0
            evals[:] = 0
            for k, plan in enumerate(plans):
                surface, vp, mp, lut, sh, hmax, hmin, hsurf, slopes, occ = plan
                if ks[k] == 0:
                    continue
                vpk = vp.copy()
                vpk[VP_XOFF] = vp[VP_XOFF] + offsets_px[m]
                if device == "cuda":
                    from ..kernels.cuda import layers_kernel_cuda
                    layers_kernel_cuda(surface, vpk, c0, mp, lut, sh, hmax, hmin, hsurf,
                                       slopes, occ, lists, offs[k], ks[k], counts[k],
                                       gfirst[k], hits, evals)
                    continue
                kind, f, fg, _, hf, hfp = surface.kernel_args(None)
                K.layers_kernel(kind, f, fg, hf, hfp, vpk, c0, mp, lut, sh, hmax,
                                hmin, hsurf, slopes, occ, lists, offs[k], ks[k], counts[k],
                                gfirst[k], hits, evals)
            total_evals += int(evals.sum())
            first = m == centre
            K.composite_kernel(lists, counts, offs, gfirst, c0, weight, first, acc, side, depth,
                               shadow, which, gbuf, stop, front_acc, opaque)
            if first:
                cols = min(B, W - c0)
                layers_seen[:, c0:c0 + cols] = hits[:cols, ::-1].T
    rgba, intensity = _picture(acc, background)
    stats = {"samples": total_evals, "translucent": True, "sub_columns": sub,
             "band_columns": B, "records": ks,
             "list_bytes": lists.nbytes + counts.nbytes + gfirst.nbytes + hits.nbytes,
             "layers": layers_seen, "w_limits": w_limits if n > 1 else w_limits[0]}
    return (rgba, intensity, side, depth, shadow if texture is not None else None, which,
            gbuf, stats, (front_acc, opaque) if stop.shape[0] else None)


def _picture(acc, background):
    """(rgba uint8, intensity float32) of the composite's sums over ``background``."""
    bg = color.to_rgba8(background).astype(np.float64) / 255.0
    rgba = np.empty(acc.shape[:2] + (4,), dtype=np.uint8)
    intensity = np.empty(acc.shape[:2], dtype=np.float32)
    K.picture_kernel(acc, bg, rgba, intensity)
    return rgba, intensity


def render_translucent(layers, views, drawn, box, quality, background, texture, t_start,
                       stop=None):
    """translucent_pass as a Render (renderer.py's door for it); with objects (their
    depth ``stop``) the Render keeps what lies over them for the objects pass
    (Render._front: translucent_pass's front)."""
    import time
    rgba, intensity, side, depth, shadow, which, gbuf, stats, front = translucent_pass(
        layers, views, drawn, box, quality, background, texture, stop)
    stats.update({"seconds": time.perf_counter() - t_start, "method": "column",
                  "engine": "kernels",
                  "box": box, "planes": views[0].planes, "step": views[0].step,
                  "scale": views[0].scale, "surfaces": len(layers)})
    if len(layers) > 1:
        stats["surface"] = which
    return Render(rgba, intensity, side, depth, stats, views[0], gbuf, box=box, shadow=shadow,
                  _front=front)

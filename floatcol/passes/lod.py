"""The level-of-detail geometry pass (``sampling="lod"``, the fly-through's engine):
every column by kernels/lod.py into the same tiled G-buffer and edge buffer as the
column pass, so finishing, shadows, textures, lines and objects read it unchanged.
A height field is sampled through its pyramid (passes/area.py ``levels``).

It draws perspective views whose rays all point forward (away from the eye's
vertical plane) from an eye above the surface under it, which a fly camera's are;
any other view (orthographic, looking down past the nadir, the eye below the
ground) takes the column pass with adaptive planes (``supports``)."""
from __future__ import annotations

import math

import numpy as np

from ..kernels import layout as L
from ..kernels.area import LV_ZMAX, LV_ZMIN
from ..kernels.lod import KAPPA, lod_kernel
from .area import LOD_BIAS, levels
from .geometry import Geometry, pass_outputs


def supports(surface, view):
    """Can the lod kernel draw this view (see the module's note)?"""
    if view.orthographic:
        return False
    vp = view.params()
    ca, sa, d1, d3, scale = (vp[L.VP_CA], vp[L.VP_SA], vp[L.VP_D1], vp[L.VP_D3],
                             vp[L.VP_SCALE])
    # a ray of screen row y0 (screen units) goes farther in t with its distance iff
    # d1 cos(a) - y0 sin(a) > 0 (eqs. 4 and 10 inverted): the top and bottom rows
    half = (vp[L.VP_H] + 1.0) * 0.5 / scale
    if min(d1 * ca - y0 * sa for y0 in (-half, half)) <= 0.0:
        return False
    # the eye (screen point (0, 0, -d3)) above the surface under it
    t_e = -d3 * ca
    s_e = -d3 * sa
    u_e = vp[L.VP_CU] + t_e * vp[L.VP_SB]
    v_e = vp[L.VP_CV] + t_e * vp[L.VP_CB]
    w = float(surface.evaluate(np.array([u_e]), np.array([v_e]))[0])
    inside = (vp[L.VP_UA] <= u_e <= vp[L.VP_UB]) and (vp[L.VP_VA] <= v_e <= vp[L.VP_VB])
    if inside and not (math.isfinite(w) and w < vp[L.VP_CW] + s_e):
        return False
    if not inside and surface.kind != L.SURF_HEIGHTFIELD:
        return False            # (a function's heights are not known beyond its grid)
    if not inside:
        _, lv = levels(surface)
        if not lv[0, LV_ZMAX] < vp[L.VP_CW] + s_e:
            return False
    return True


def lod_pass(surface, view, vp, buffers, area, device="cpu"):
    """Run the lod kernel of one layer into ``buffers`` (geometry.allocate's);
    ``area``: Cohen-Or's area weights along the columns, else pixel centres; on the
    CPU's cores or (``device="cuda"``) an NVIDIA GPU's, a thread a column
    (kernels/cuda.py: the same column code)."""
    gbuf, ebuf, hrec = buffers
    evals, wrange, rows = pass_outputs(view.width, gbuf.shape[0])
    flat, lv = levels(surface)
    kind, f, fg, _, hf, hfp = surface.kernel_args(None)
    if kind == L.SURF_HEIGHTFIELD and lv[0, LV_ZMIN] == lv[0, LV_ZMIN]:
        s_lo = lv[0, LV_ZMIN] - vp[L.VP_CW]
        s_hi = lv[0, LV_ZMAX] - vp[L.VP_CW]
    else:
        s_lo = s_hi = np.nan
    mx, mt = block_maxima(surface)
    if device == "cuda":
        from ..kernels.cuda import lod_kernel_cuda
        lod_kernel_cuda(surface, kind, hf, flat, lv, mx, mt, hfp, vp, bool(area),
                        2.0 ** LOD_BIAS, KAPPA, s_lo, s_hi, gbuf, ebuf, evals, wrange, rows)
    else:
        lod_kernel(kind, fg, hf, flat, lv, mx, mt, hfp, vp, bool(area), 2.0 ** LOD_BIAS, KAPPA,
                   s_lo, s_hi, gbuf, ebuf, evals, wrange, rows)
    return Geometry(gbuf, ebuf, hrec, rows, wrange, evals, vp, None, 0)


#: block sizes of the maxima: 2**1 .. 2**(BLOCK_LEVELS - 1) cells a side
BLOCK_LEVELS = 16
_NO_BLOCKS = (np.zeros(0), np.zeros((0, 3)))


def block_maxima(surface):
    """(mx, mt): for each level k of a height field's pyramid and each m in 1 ..
    BLOCK_LEVELS - 1, the highest height over each block of 2**m x 2**m of its cells
    (their nodes; a hole ignored, -inf where all are holes), in one flat array;
    mt[k * BLOCK_LEVELS + m] = (offset, rows, columns). The lod kernel bounds the
    surface over a stretch of a column with them, to skip what is surely hidden.
    Kept on the height field with its pyramid; a function surface has none."""
    if surface.kind != L.SURF_HEIGHTFIELD:
        return _NO_BLOCKS
    flat, lv = levels(surface)
    held = surface.__dict__.get("_lod_blocks")
    if held is not None and held[0] is flat:
        return held[1]
    parts = []
    mt = np.zeros((lv.shape[0] * BLOCK_LEVELS, 3))
    off = 0
    for k in range(lv.shape[0]):
        o, nv, nu = (int(x) for x in lv[k, :3])
        z = flat[o:o + nv * nu].reshape(nv, nu)
        z = np.where(np.isfinite(z), z, -np.inf)
        cells = np.maximum(np.maximum(z[:-1, :-1], z[:-1, 1:]), np.maximum(z[1:, :-1], z[1:, 1:]))
        for m in range(1, BLOCK_LEVELS):
            r, c = cells.shape
            if r % 2 or c % 2:
                cells = np.pad(cells, ((0, r % 2), (0, c % 2)), constant_values=-np.inf)
            cells = np.maximum(np.maximum(cells[0::2, 0::2], cells[0::2, 1::2]),
                               np.maximum(cells[1::2, 0::2], cells[1::2, 1::2]))
            mt[k * BLOCK_LEVELS + m] = (off, cells.shape[0], cells.shape[1])
            parts.append(cells.ravel())
            off += cells.size
    mx = np.concatenate(parts)
    surface.__dict__["_lod_blocks"] = (flat, (mx, mt))
    return mx, mt

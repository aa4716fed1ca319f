"""The ray-march geometry pass (``sampling="march"``): every column's pixel rays
marched through the level-of-detail engine's planes by kernels/march.py, into the
same tiled G-buffer and edge buffer as the column pass, so finishing, shadows,
textures, lines and objects read it unchanged.

It draws a point-sampled (``antialias=False``) view of a height field that the lod
engine draws (passes/lod.py ``supports``: a perspective view from inside the scene,
the eye above the ground); an antialiased view, a function surface or any other view
takes the lod engine's way (passes/lod.py, else the column pass)."""
from __future__ import annotations

import numpy as np

from ..kernels import layout as L
from ..kernels import march as M
from ..kernels.area import LV_ZMAX, LV_ZMIN
from . import lod
from .area import LOD_BIAS, levels
from .geometry import Geometry, pass_outputs


def supports(surface, view, antialiased):
    """Can the ray march draw this view? Point sampled, a height field whose heights
    are not all holes, in a view the lod kernel draws."""
    if antialiased or surface.kind != L.SURF_HEIGHTFIELD:
        return False
    _, lv = levels(surface)
    if not lv[0, LV_ZMIN] <= lv[0, LV_ZMAX]:
        return False
    return lod.supports(surface, view)


def march_pass(surface, view, vp, buffers, device="cpu"):
    """Run the ray march of one layer into ``buffers`` (geometry.allocate's), on the
    CPU's cores or (``device="cuda"``) an NVIDIA GPU's, a thread a column
    (kernels/cuda.py: the same column code)."""
    gbuf, ebuf, hrec = buffers
    evals, wrange, rows = pass_outputs(view.width, gbuf.shape[0])
    flat, lv = levels(surface)
    s_lo = lv[0, LV_ZMIN] - vp[L.VP_CW]
    s_hi = lv[0, LV_ZMAX] - vp[L.VP_CW]
    args = (flat, lv, slopes(surface), surface.hfp, vp, 2.0 ** LOD_BIAS, M.KAPPA, s_lo, s_hi,
            gbuf, ebuf, evals, wrange, rows)
    if device == "cuda":
        from ..kernels.cuda import march_kernel_cuda
        march_kernel_cuda(surface, *args)
    else:
        M.march_kernel(*args)
    return Geometry(gbuf, ebuf, hrec, rows, wrange, evals, vp, None, 0)


def slopes(surface):
    """(n_levels, 2): for each level of a height field's pyramid the steepest slope of
    its bilinear cells along u and along v (their partials' largest magnitudes:
    within a cell each partial lies between its two edges' differences); holes
    ignored. Kept with the pyramid. Each level's is at most the one before's, whose
    heights it averages."""
    flat, lv = levels(surface)
    held = surface.__dict__.get("_march_slopes")
    if held is not None and held[0] is flat:
        return held[1]
    out = np.zeros((lv.shape[0], 2))
    ua, ub, va, vb = (float(x) for x in surface.hfp[:4])     # (the kernel's extent)
    for k in range(lv.shape[0]):
        o, nv, nu = (int(x) for x in lv[k, :3])
        z = flat[o:o + nv * nu].reshape(nv, nu)
        with np.errstate(invalid="ignore"):
            du = np.abs(np.diff(z, axis=1))
            dv = np.abs(np.diff(z, axis=0))
        gu = np.nanmax(du, initial=0.0) * (nu - 1) / (ub - ua)
        gv = np.nanmax(dv, initial=0.0) * (nv - 1) / (vb - va)
        out[k] = (gu, gv)
    surface.__dict__["_march_slopes"] = (flat, out)
    return out

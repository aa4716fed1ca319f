"""Smooth shading (``smooth_shading=True``): a height field's normals interpolated
between its nodes over the G-buffer and the edge buffer, after any engine's geometry
pass (kernels/normals.py). A function surface's normals are its own partials, smooth
already: there the pass does nothing."""
from __future__ import annotations

from ..kernels import layout as L
from ..kernels.area import LV_CELL
from ..kernels.lod import level_table
from ..kernels.normals import smooth_normals_kernel
from .area import levels


def smooth_pass(surface, view, geom):
    """Smooth the normals and intensities of the pixels ``geom`` (a Geometry) shows of
    ``surface``, in place."""
    if surface.kind != L.SURF_HEIGHTFIELD:
        return
    flat, lv = levels(surface)
    if lv.shape[0] == 0:
        return
    smooth_normals_kernel(flat, level_table(lv, surface.hfp), surface.hfp, geom.vp,
                          float(lv[0, LV_CELL]), view.width, geom.gbuf, geom.ebuf, geom.rows)

"""The finishing pass: one layer's G-buffer lit and coloured by its material
(kernels/shade.py): the picture and the side seen at each pixel."""
from __future__ import annotations

import numpy as np

from .. import _pool
from ..kernels.shade import finish_kernel


#: finish_kernel's ``base`` when the side's colours are the surface's (no texture)
NO_BASE = np.zeros((0, 0, 6), dtype=np.float32)


def finish_pass(geom, H, W, colours, bg8, lit, base=NO_BASE):
    """(rgba (H, W, 4) uint8, side (H, W) int8). ``colours``: the material's
    (Material.table: its material vector and colour table); bg8 the background; lit
    (H, W) the part of the light reaching each pixel (passes/shadow.py), or empty;
    base (H, W, 6) float32 the colour of the surface at each pixel and of its edge
    surface (passes/colour.py), or empty (NO_BASE): their sides'."""
    side = _pool.empty((H, W), np.int8)
    rgba = _pool.empty((H, W, 4), np.uint8)
    finish_kernel(geom.gbuf, geom.ebuf, geom.rows, geom.vp, colours.mp, colours.lut, bg8, lit,
                  base, side, rgba.view(np.uint32)[..., 0])
    return rgba, side

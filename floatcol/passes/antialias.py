"""Antialiasing across columns (section 6.4): the staircases' pass
(kernels/silhouette.py), or sub-columns averaged (kernels/antialias.py; a textured
surface's as whole pictures at each offset)."""
from __future__ import annotations

import numpy as np

from ..kernels.antialias import subcolumn_kernel
from ..kernels.silhouette import silhouette_kernel


def staircase_pass(geom, side, rgba):
    """Blend the staircases of steep edges where the side seen changes, from the
    columns' ends, into ``rgba`` (in place)."""
    flat = side.reshape(-1)
    silhouette_kernel(geom.ebuf, geom.gbuf, side, flat[:flat.size // 8 * 8].view(np.uint64),
                      rgba.view(np.uint32)[..., 0])


def subcolumn_pass(surface, geom, sub_columns, rgba, colours, bg8, lit, picture=None):
    """The picture averaged over ``sub_columns`` columns at even offsets inside each
    pixel (premultiplied), one column of scratch per thread; the G-buffer and the
    arrays other than rgba stay those of the pixel centres; ``colours`` the material's
    (Material.table). ``picture``: where given, picture(offset) -> (rgba, evals), the
    whole picture drawn at that offset in pixels (vp's VP_XOFF: a textured surface's,
    finished with its colours, passes/colour.py), instead of the sub-columns' kernel.
    Returns (rgba, evals)."""
    H, W = rgba.shape[:2]
    offsets = (np.arange(sub_columns) + 0.5) / sub_columns - 0.5
    acc = np.zeros((H, W, 4))
    if np.any(offsets == 0.0):           # the centre is the pass above
        _add(acc, rgba)
        offsets = offsets[offsets != 0.0]
    ev2 = np.zeros(W, dtype=np.int64)
    if picture is None:
        subcolumn_kernel(*surface.kernel_args(geom.fb), geom.vp, offsets, colours.mp,
                         colours.lut, bg8, lit, acc, ev2)
    else:
        for o in offsets:
            sub, ev = picture(float(o))
            _add(acc, sub)
            ev2 += ev
    a = acc[..., 3:4]
    rgb = np.where(a > 0, acc[..., :3] / np.maximum(a, 1e-12), 0.0)
    out = np.empty((H, W, 4), dtype=np.uint8)
    out[..., :3] = np.clip(rgb * 255 + 0.5, 0, 255).astype(np.uint8)
    out[..., 3] = np.clip(a[..., 0] / sub_columns * 255 + 0.5, 0, 255).astype(np.uint8)
    return out, ev2


def _add(acc, rgba):
    """A picture's colours premultiplied by its alpha, and the alpha, into acc."""
    a = rgba[..., 3:4] / 255.0
    acc[..., :3] += rgba[..., :3] / 255.0 * a
    acc[..., 3:4] += a

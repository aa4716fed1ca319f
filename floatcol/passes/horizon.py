"""The horizon pass: a line drawing from the column pass's horizon records
(Gordon's modified floating horizon, App. A.1; kernels/horizon.py)."""
from __future__ import annotations

import numpy as np

from .. import color
from ..kernels import layout as L
from ..kernels.horizon import horizon_kernel
from ..kernels.layout import G_DEPTH
from .tiles import untile


def line_pass(geom, W, H, background):
    """(rgba, side, intensity, depth, seen, line_t) of a line drawing: side +1 / -1
    on the lines of the upper / lower side, seen where the surface hides what is
    behind it (between the lines too)."""
    lines_img = np.zeros((W, H), dtype=np.int8)
    lt = np.full((W, H), np.nan, dtype=np.float32)
    horizon_kernel(geom.hrec, geom.gbuf, geom.ebuf, geom.vp, geom.hstride, lines_img, lt)
    line_t = np.ascontiguousarray(lt[:, ::-1].T)
    side = np.ascontiguousarray(lines_img[:, ::-1].T)
    on = side != 0
    intensity = np.where(on, np.float32(1.0), np.float32(np.nan)).astype(np.float32)
    e_seen = untile(geom.ebuf[:, L.E_SEEN], W)[::-1]
    seen = (e_seen != 0) & (e_seen != L.E_FLAG)      # kernels/coverage.py
    depth = np.where(on & seen, untile(geom.gbuf[..., G_DEPTH], W)[::-1],
                     np.inf).astype(np.float32)
    rgba = color.line_rgba(side, background=background)
    return rgba, side, intensity, depth, seen, line_t

"""The G-buffer's tiles (kernels/layout.py) as pictures and back."""
from __future__ import annotations

import numpy as np


def untile(a, width=None):
    """(n_tiles, H, TILE, ...) -> (H, W, ...): a tiled buffer (kernels/layout.py) as a
    picture, rows as in the buffer; W = n_tiles * TILE unless ``width`` says."""
    n, h, t = a.shape[:3]
    flat = a.transpose(1, 0, 2, *range(3, a.ndim)).reshape(h, n * t, *a.shape[3:])
    return flat[:, :width]


def tile(mask, tile, n_tiles):
    """(H, W) -> (n_tiles, H, tile): a picture-shaped mask in the G-buffer's tiles
    (kernels/layout.py), rows as given; padding columns False."""
    H, W = mask.shape
    padded = np.zeros((H, n_tiles * tile), dtype=bool)
    padded[:, :W] = mask
    return padded.reshape(H, n_tiles, tile).transpose(1, 0, 2)

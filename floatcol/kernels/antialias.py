"""Antialiasing across columns (Gordon section 6.4), a few columns at a time.

"We generate just a few (two to four) columns of the supersampled image and then
perform an averaging operation to obtain one column of the final image ... only O(n)
space is required." Each thread renders the sub-columns of one pixel column into a
scratch G-buffer that holds one column, lights and colours it at once, and adds the
colour to the pixel column's sum: the memory does not grow with the image's width.
"""
import numpy as np
from numba import prange

from ._jit import kernel_calling
from .column import COLUMN_FUNCTIONS, H_SIZE, column_functions, guesses_for
from .layout import E_SIZE, G_SIZE
from .sample import column_x0
from .shade import shade_pixel


def _subcolumn_functions(kind, f, fg, fb, hf, hfp, vp, *rest):
    """subcolumn_kernel's jitted functions: column_kernel's, of the types column_kernel
    calls them with (one compile for both; _jit.kernel_calling)."""
    return column_functions(kind, f, fg, fb, hf, hfp, vp, np.float32, np.float64)


@kernel_calling(_subcolumn_functions, COLUMN_FUNCTIONS)
def subcolumn_kernel(kind, f, fg, fb, hf, hfp, vp, offsets, mp, lut, background, lit, acc,
                     evals, render, into, trace):
    """For every pixel column c and every offset o (in pixels), render the column at
    c + o with coverage antialiasing, colour it (shade_pixel) and add the colour,
    premultiplied by its alpha, and the alpha into acc (H, W, 4) float64, top row first.
    evals[c] receives the evaluations of f. Each thread has its own one-column scratch.
    ``lit`` (H, W): the part of the light reaching each pixel (its centre's point, for
    every sub-column; passes/shadow.py), or an empty array: all of it. mp: the
    material vector (layout.py M_*), lut its colour table (Material.table). ``render``:
    column.render_column as a function value, ``into`` and ``trace`` the functions it
    takes (column.column_functions; _jit.kernel_calling)."""
    H = acc.shape[0]
    shadows = lit.shape[0] > 0
    W = acc.shape[1]
    no_base = np.zeros((0, 0, 6), dtype=np.float32)     # the sides' own colours
    for c in prange(W):
        # one column in column_kernel's layouts (and array types: one compilation)
        gcol = np.empty((1, H, 1, G_SIZE), dtype=np.float32)
        ecol = np.empty((1, E_SIZE, H, 1), dtype=np.float32)
        hrec = np.empty((1, H_SIZE))
        sg = guesses_for(vp)            # (the sub-columns of c, in order)
        ev = 0
        for k in range(offsets.shape[0]):
            col = c + offsets[k]
            # (no horizon lines: an int64 0, as column_kernel's hstride, not the literal
            # 0, which Numba compiled render_column for again: 17 s of a first
            # picture with sub-columns)
            ev += render(kind, f, fg, fb, hf, hfp, vp, col, gcol[0, :, 0], ecol[0, :, :, 0],
                         hrec, np.int64(0), sg, k, into, trace)[0]
            x0 = column_x0(vp, col)
            for j in range(H):
                i = H - 1 - j
                _, r, g, b, a = shade_pixel(gcol, ecol, 0, 0, j, True, vp, x0, mp, lut,
                                            background, lit[i, c] if shadows else 1.0,
                                            no_base, i, c)
                acc[i, c, 0] += r * a
                acc[i, c, 1] += g * a
                acc[i, c, 2] += b * a
                acc[i, c, 3] += a
        evals[c] = ev

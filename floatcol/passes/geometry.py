"""The geometry pass: the floating column over every pixel column of one layer
(kernels/column.py), into a tiled G-buffer and its edge buffer (kernels/layout.py)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _pool
from .._memory import fits
from ..kernels import layout as L
from ..kernels.column import H_SIZE, column_kernel
from ..kernels.layout import G_SIZE

#: Orthographic pictures with at least this many samples evaluate f in batches of SIMD
#: code (Surface.batch): about 58 ns less per sample, for a compile of 0.1-0.2 s once
#: per expression (1024x768 of 3 sin(u cos v): 380 000 samples)
BATCH_MIN_SAMPLES = 200_000


@dataclass
class Geometry:
    """What the column pass leaves: the tiled G-buffer ``gbuf`` and edge buffer
    ``ebuf``, the horizon records ``hrec``, each tile's rows ``rows``, each column's
    seen heights ``wrange`` and evaluations ``evals``; ``vp`` the view parameters
    the later passes read, ``fb`` the batch evaluator used (or None)."""
    gbuf: np.ndarray
    ebuf: np.ndarray
    hrec: np.ndarray
    rows: np.ndarray
    wrange: np.ndarray
    evals: np.ndarray
    vp: np.ndarray
    fb: object
    hstride: int


def horizon_planes(view, lines):
    """(view, hstride): a line drawing's ``lines`` planes evenly spread over t; the
    dense planes between them (about a pixel apart) only decide what is hidden."""
    import dataclasses
    t0, t1 = view.t_range
    spacing = (t1 - t0) / max(lines - 1, 1)
    hstride = max(1, int(math.ceil(spacing / view.step - 1e-9)))
    return dataclasses.replace(view, step=spacing / hstride), hstride


def view_params(view, method, sampling, fixes, aa_cov, surface):
    """The kernels' view parameters vp (kernels/layout.py VP_*) of a layer."""
    vp = view.params()
    if method == "column":
        vp[L.VP_ADAPT] = 1.0 if sampling in ("adaptive", "lod", "march") else 0.0
        (vp[L.VP_FIX_RIDGE], vp[L.VP_FIX_SHADE], vp[L.VP_DETECT], vp[L.VP_JUMP], vp[L.VP_RATE],
         vp[L.VP_SPLINE_TOL]) = fixes
    vp[L.VP_AA] = 1.0 if aa_cov else 0.0
    if surface.derivatives != "symbolic":
        # (layout.py: central differences tilt normals at jumps.) A height field's
        # facets face away from the eye at every hidden slope of a rough terrain, so
        # nearly every column of a dense DEM was traced as folding: 64 M evaluations
        # and 2.8 s for a 320x240 perspective view of a 1025^2 fractal DEM, 0.54 M and
        # 48 ms without; against the ray caster (160x120) a 257^2 fractal's PSNR 27.44
        # dB with the tracing, 27.46 without, sides agreeing 99.86 % and 99.92 %;
        # matplotlib's Jacksboro DEM the same picture (no column folded)
        vp[L.VP_FOLD] = 0.0
    return vp


def allocate(W, H, n_lines, sub_columns):
    """The column pass's buffers (gbuf, ebuf, hrec), or ValueError for a size beyond
    the machine's memory."""
    n_tiles = -(-W // L.TILE)
    check_memory(W, H, n_tiles, n_lines, sub_columns)
    try:
        gbuf = _pool.empty((n_tiles, H, L.TILE, G_SIZE), np.float32)
        hrec = np.empty((W, n_lines, H_SIZE), dtype=np.float64)
        ebuf = _pool.empty((n_tiles, L.E_SIZE, H, L.TILE), np.float32)
    except MemoryError:
        raise ValueError(too_large(W, H, buffer_bytes(W, H, n_tiles, n_lines, sub_columns)))\
            from None
    return gbuf, ebuf, hrec


def column_pass(surface, view, vp, buffers, hstride, fb, device="cpu"):
    """Run the column kernel of one layer into ``buffers`` (allocate's), on the CPU's
    cores or (``device="cuda"``) an NVIDIA GPU's (kernels/cuda.py: the same column
    code, without batches)."""
    gbuf, ebuf, hrec = buffers
    evals, wrange, rows = pass_outputs(view.width, gbuf.shape[0])
    # (a height field's orthographic planes are batched without an evaluator: the
    # kernel reads its cells itself)
    batched = fb is not None or (surface.kind == L.SURF_HEIGHTFIELD and view.orthographic)
    vp[L.VP_BATCH] = 1.0 if batched else 0.0
    if device == "cuda":
        from ..kernels.cuda import column_kernel_cuda
        column_kernel_cuda(surface, vp, gbuf, ebuf, hrec, hstride, evals, wrange, rows)
    else:
        column_kernel(*surface.kernel_args(fb), vp, gbuf, ebuf, hrec, hstride, evals, wrange,
                      rows)
    return Geometry(gbuf, ebuf, hrec, rows, wrange, evals, vp, fb, hstride)


def pass_outputs(W, n_tiles):
    """A geometry pass's per-column outputs: (evals (W,), wrange (W, 2), rows (n_tiles,
    2)), as Geometry holds them."""
    return (np.zeros(W, dtype=np.int64), np.empty((W, 2)),
            np.empty((n_tiles, 2), dtype=np.int64))


def batch_evaluator(surface, view, method, sampling):
    """The surface's batch evaluator (Surface.batch, SIMD code) where the column
    kernel can use it, on uniform planes (in perspective with exact placement: the
    kernel's Newton steps for many planes at once), and where the picture has at least
    BATCH_MIN_SAMPLES of them to repay its compile; else None."""
    if method == "column" and sampling != "uniform":
        return None
    if not view.orthographic and view.placement != "exact":
        return None
    (ua, ub), (va, vb) = view.domain
    # the lattice of columns (1 / scale apart) and planes (step apart) in the domain
    samples = min((ub - ua) * (vb - va) * view.scale / view.step,
                  float(view.width) * view.planes)
    if samples < BATCH_MIN_SAMPLES:
        return None
    return surface.batch()


def buffer_bytes(W, H, n_tiles, n_lines, sub_columns):
    """Bytes of the buffers a render of W x H pixels holds at once: the G-buffer and
    the edge buffer (float32), the horizon records, the picture and its sides, and
    with sub-columns their accumulator."""
    need = n_tiles * L.TILE * H * (G_SIZE + L.E_SIZE) * 4 + W * n_lines * H_SIZE * 8 + W * H * 5
    if sub_columns > 1:
        need += W * H * 4 * 8
    return need


def too_large(W, H, need):
    return (f"size {W}x{H} needs about {need / 2**30:.1f} GiB of buffers, more than this "
            "machine has: use a smaller size")


def check_memory(W, H, n_tiles, n_lines, sub_columns):
    """A picture whose buffers cannot fit in the machine's memory is a bad size (a
    ValueError naming it), not a MemoryError halfway through."""
    check_bytes(W, H, buffer_bytes(W, H, n_tiles, n_lines, sub_columns))


def check_bytes(W, H, need):
    """ValueError (too_large) where ``need`` bytes of buffers would not fit in 80 % of
    the machine's memory (_memory.fits)."""
    if not fits(need):
        raise ValueError(too_large(W, H, need))

"""The column kernel on an NVIDIA GPU (numba.cuda): one thread a pixel column.

Gordon's columns are independent (section 1, 6.1), so a GPU runs each on a thread of
its own, with the very code the CPU kernel runs: ``render_column_into`` and all it
calls (column.py, sample.py, correct.py, coverage.py, fold.py) are compiled a second
time by Numba's CUDA target, the surface's functions f and fg with them as device
functions. The pictures are the CPU kernel's: exact placement, the corrections of
section 5, the coverages of section 6.4's antialiasing, the fold tracer; only the
batched SIMD evaluations (a CPU's) are off (vp's VP_BATCH), as the CPU kernel runs
without them. Area sampling (``antialias="area"``, area.py's ``area_column``) and
translucent layers (``opacity < 1``, layers.py's ``_column_layers``, a band of columns
a launch, composited on the CPU) have kernels of their own, made the same way.

Nothing here allocates on the device: each column's scratch (column_scratch's and
fold.fold_scratch's) is a row of arrays made once per call on the host side, and the
column writes only its own lane of the tiled buffers; the per-tile rows are reduced
after the kernel.

Under Numba's CUDA simulator (``NUMBA_ENABLE_CUDASIM=1``, how the tests run on a
machine without a GPU) the kernel's body runs as Python threads, which cannot hand
the simulator's arrays to compiled code: there the column is the CPU's compiled
function, called with the arrays the simulator wraps. ``ptx`` compiles the kernel for
a GPU without one (a check that the whole column compiles for the device).

This module imports numba.cuda (numba-cuda, the ``floatcol[cuda]`` extra) only when a
kernel is asked for.
"""
import math

import numpy as np

from .column import (
    column_folds, column_result, column_scratch, render_column_into, _seen_ranges, SCR_RUN,
)
from ._jit import ngjit_inline
from .fold import fold_scratch, trace_column_into
from .layout import SURF_FUNCTION, VP_BATCH

#: numba.cuda once _cuda() has imported it (a global: the simulator swaps a kernel's
#: global numba.cuda for its own)
cuda = None

#: Threads per block: a warp. Columns are independent, and a picture has few of them
#: for a GPU (1920 at 1080p): small blocks spread them over more of its multiprocessors
THREADS = 32
#: Columns per launch at most (the fold tracer's scratch is about 250 KB a column at
#: 1080p: a launch of 4096 columns holds about 1 GiB of it)
MAX_COLUMNS = 4096


def _cuda():
    """numba.cuda (numba-cuda's, where installed: Numba hands its name over), or
    ValueError naming what to install."""
    global cuda
    try:
        from numba import cuda as module
    except Exception as exc:                   # pragma: no cover - depends on the machine
        raise ValueError(f"device='cuda' needs the CUDA extra ({exc}): pip install "
                         "'floatcol[cuda]'") from None
    cuda = module
    return cuda


def simulated():
    """Is numba.cuda Numba's simulator (NUMBA_ENABLE_CUDASIM=1)?"""
    from numba import config
    return bool(getattr(config, "ENABLE_CUDASIM", 0))


def check_device():
    """ValueError where device='cuda' cannot run: no numba-cuda, or no GPU (and not
    the simulator)."""
    if not simulated():
        try:
            import numba_cuda  # noqa: F401  (the maintained CUDA target)
        except ImportError:
            raise ValueError("device='cuda' needs the CUDA extra: pip install "
                             "'floatcol[cuda]' (or use device='cpu')") from None
    try:
        ok = _cuda().is_available()
    except Exception:                          # pragma: no cover - a broken driver
        ok = False
    if not ok:
        raise ValueError("device='cuda' needs an NVIDIA GPU with its driver, and this "
                         "machine has none that CUDA can use: use device='cpu'")


def device_functions(surface):
    """(f, fg, fb) of a surface as the GPU kernel calls them: the surface's Python
    functions (their compiled cfuncs' sources) compiled by Numba, which the CUDA target
    compiles again as device functions; fb a stand-in that is never called (VP_BATCH
    is 0 on the GPU). Under the simulator, the surface's own CPU functions. A Python
    callable is a ValueError: its wrapper catches the callable's exceptions (a hole),
    which the CUDA target cannot compile."""
    if surface.kind == SURF_FUNCTION and surface.expr is None:
        raise ValueError("device='cuda' draws surfaces given as formulas (text or symbolic "
                         "expressions) and height fields: a Python callable runs on "
                         "device='cpu'")
    if simulated():
        return surface.f, surface.fg, surface.kernel_args()[3]
    key = "_cuda_functions"
    fns = getattr(surface, "_fits", {}).get(key)
    if fns is None:
        import numba
        try:
            f_py = surface.f._pyfunc
            fg_py = surface.fg._pyfunc
        except AttributeError:                  # pragma: no cover - not a compiled surface
            raise ValueError("device='cuda' draws surfaces given as expressions and "
                             "height fields") from None
        jit = numba.njit(error_model="numpy")
        fns = (jit(f_py), jit(fg_py), jit(_no_batch))
        surface._fits[key] = fns
    return fns


@ngjit_inline
def _column_of(first, i, gbuf):
    """Thread i's column c of a launch from column ``first``: (c, its tile b, its lane
    in the tile) of the tiled buffers (layout.py)."""
    c = first + i
    b = c // gbuf.shape[2]
    return c, b, c - b * gbuf.shape[2]


@ngjit_inline
def _report(evals, wrange, jrange, i, n, w_lo, w_hi, j_lo, j_hi):
    """Thread i's column's evaluations, lowest and highest w seen and lowest and highest
    row set, into the launch's outputs (reduced on the host: _launch)."""
    evals[i] = n
    wrange[i, 0] = w_lo
    wrange[i, 1] = w_hi
    jrange[i, 0] = j_lo
    jrange[i, 1] = j_hi


def _no_batch(u, v, t, out, n):
    """The batch evaluator's stand-in (never called: VP_BATCH is 0)."""
    for i in range(3 * n):
        out[i] = math.nan


def _kernel_source(f, fg, fb, column, folds, fold_trace, seen_ranges, result, x0_of, at,
                   report):
    """The column kernel's Python function, closing over the surface's functions and
    the column's (the CPU's compiled ones, which the CUDA target compiles for the GPU;
    or, under the simulator, wrappers that hand them the simulator's arrays
    unwrapped)."""
    _cuda()

    def kernel(kind, hf, hfp, vp, hstride, sg, first, gbuf, ebuf, hrec, scr, sdepth, bat,
               tg, te, cross, n_cross, pa, pb, evals, wrange, jrange):
        i = cuda.grid(1)
        if i >= evals.shape[0]:
            return
        c, b, lane = at(first, i, gbuf)      # (c: the picture's column)
        gcol = gbuf[b, :, lane]
        ecol = ebuf[b, :, :, lane]
        s = scr[i]
        ev = column(kind, f, fg, fb, hf, hfp, vp, c, gcol, ecol, hrec[c], hstride, sg, 0,
                    s, sdepth[i], bat[i])
        if folds(s, hstride):
            ev += fold_trace(kind, f, fg, hf, hfp, vp, x0_of(vp, c), gcol, ecol, tg[i], te[i],
                             cross[i], n_cross[i], pa[i], pb[i])
            seen_ranges(gcol, ecol, s[SCR_RUN])
        n, wlo, whi, jlo, jhi = result(s, gcol.shape[0], ev)
        report(evals, wrange, jrange, i, n, wlo, whi, jlo, jhi)
    return kernel


def _area_source(f, fg, area, x0_of, at, report):
    """The area-sampling kernel's Python function (area.area_column a thread), as
    _kernel_source."""
    _cuda()

    def kernel(kind, flat, lv, hfp, vp, slices, lod, first, gbuf, ebuf, hrec, acc, cov, gaps,
               guess, pts, evals, wrange, jrange):
        i = cuda.grid(1)
        if i >= evals.shape[0]:
            return
        c, b, lane = at(first, i, gbuf)
        g = guess[i]
        g[:, :] = 0.0
        n, wlo, whi, jlo, jhi = area(kind, f, fg, flat, lv, hfp, vp, x0_of(vp, c), slices,
                                     lod, gbuf[b, :, lane], ebuf[b, :, :, lane], acc[i], cov[i],
                                     gaps[i], g, pts[i])
        report(evals, wrange, jrange, i, n, wlo, whi, jlo, jhi)
    return kernel


def _layers_source(f, fg, column_layers, x0_of):
    """The translucent layers' kernel's Python function (layers._column_layers a
    thread: one band's columns), as _kernel_source. The colour tuple (lut, texture
    levels, offsets, shapes, tp, lines) comes as six arguments, the objects' occluders
    (frames, coef, start, items, grids) as five."""
    _cuda()

    def kernel(kind, hf, hfp, vp, c0, mp, lut, levels, offsets, shapes, tp, lines, sh, hmax,
               hmin, hsurf, slopes, frames, coef, start, items, grids, lists, off, K, counts,
               gfirst, hits, evals, trans, scr, width):
        b = cuda.grid(1)
        if b >= lists.shape[0] or c0 + b >= width:
            return
        t = trans[b]
        t[:] = 1.0
        s = scr[b]
        s[:, :] = 0.0
        evals[b] += column_layers(kind, f, fg, hf, hfp, vp, x0_of(vp, c0 + b), mp,
                                  (lut, levels, offsets, shapes, tp, lines), sh, hmax, hmin,
                                  hsurf, slopes, (frames, coef, start, items, grids), lists,
                                  off, K, counts, t, gfirst, hits, b, s)
    return kernel


def _march_source(march, x0_of, at, report):
    """The ray march's kernel (march.march_column a thread, sampling="march"), as
    _kernel_source; the planes and the pyramid's tables made on the host (a frame's
    plane_table, level_table, level_ints)."""
    _cuda()

    def kernel(flat, lt, lk, slope, hfp, vp, planes, s_lo, s_hi, first, gbuf, ebuf, hrec, p,
               o, evals, wrange, jrange):
        i = cuda.grid(1)
        if i >= evals.shape[0]:
            return
        c, b, lane = at(first, i, gbuf)
        out = o[i]
        march(flat, lt, lk, slope, hfp, vp, planes, x0_of(vp, c), s_lo, s_hi,
              gbuf[b, :, lane], ebuf[b, :, :, lane], p[i], out)
        report(evals, wrange, jrange, i, int(out[0]), out[1], out[2], int(out[3]),
               int(out[4]))
    return kernel


def _lod_source(fg, tile, at, report):
    """The level-of-detail engine's kernel (lod.lod_tile a thread, its one lane the
    thread's column: sampling="lod"), as _kernel_source; the planes and the pyramid's
    tables made on the host."""
    _cuda()

    def kernel(kind, hf0, flat, lt, lk, mx, mt, hfp, vp, area, planes, s_lo, s_hi, first,
               gbuf, ebuf, hrec, acc, pts, st, o, evals, wrange, jrange):
        i = cuda.grid(1)
        if i >= evals.shape[0]:
            return
        c, b, lane = at(first, i, gbuf)
        out = o[i]
        tile(kind, fg, hf0, flat, lt, lk, mx, mt, hfp, vp, c - lane, lane, 1, area, planes,
             s_lo, s_hi, gbuf[b], ebuf[b], acc[i], pts[i], st[i], out)
        report(evals, wrange, jrange, i, int(out[0, 0]), out[0, 1], out[0, 2],
               int(out[0, 3]), int(out[0, 4]))
    return kernel


def _on_device(*fns):
    """The column's functions as the kernel calls them: themselves on a GPU; under the
    simulator, wrappers that unwrap its arrays."""
    return tuple(_unwrapped(fn) for fn in fns) if simulated() else fns


def _column_functions():
    """(column, folds, fold_trace, seen_ranges, result, x0_of, at, report): the steps
    of column.render_column the kernel runs, and the thread's column and outputs."""
    from .sample import column_x0
    return _on_device(render_column_into, column_folds, trace_column_into, _seen_ranges,
                      column_result, column_x0, _column_of, _report)


def _area_functions():
    """(area, x0_of, at, report): the area-sampling kernel's column."""
    from .area import area_column
    from .sample import column_x0
    return _on_device(area_column, column_x0, _column_of, _report)


def _layers_functions():
    """(column_layers, x0_of): the translucent layers' kernel's column."""
    from .layers import _column_layers
    from .sample import column_x0
    return _on_device(_column_layers, column_x0)


def _march_functions():
    """(march, x0_of, at, report): the ray march's column."""
    from .march import march_column
    from .sample import column_x0
    return _on_device(march_column, column_x0, _column_of, _report)


def _lod_functions():
    """(tile, at, report): the lod engine's tile, one lane of it a thread."""
    from .lod import lod_tile
    return _on_device(lod_tile, _column_of, _report)


def _unwrapped(fn):
    """fn called with the simulator's array wrappers unwrapped (their numpy arrays),
    in tuples too."""
    def bare(a):
        if isinstance(a, tuple):
            return tuple(bare(x) for x in a)
        a = vars(a).get("_item", a) if hasattr(a, "__dict__") else a   # (within a kernel)
        return getattr(a, "_ary", a)

    def call(*args):
        return fn(*[bare(a) for a in args])
    return call


def kernel(surface, which="column"):
    """The compiled (cuda.jit) kernel of ``surface``: "column" (the column pass),
    "area" (area sampling's) or "layers" (translucent layers'); kept with it: its
    functions are device functions compiled into the kernel, so each surface has a
    kernel of its own (a surface at another time or scale shares it)."""
    fns = surface._fits
    key = "_cuda_" + which
    if key not in fns:
        fns[key] = _cuda().jit(_source(surface, which))
    return fns[key]


def _source(surface, which):
    """The Python function of ``surface``'s kernel ``which`` (kernel's)."""
    f, fg, fb = device_functions(surface)
    if which == "march":
        return _march_source(*_march_functions())
    if which == "lod":
        return _lod_source(fg, *_lod_functions())
    if which == "area":
        return _area_source(f, fg, *_area_functions())
    if which == "layers":
        return _layers_source(f, fg, *_layers_functions())
    return _kernel_source(f, fg, fb, *_column_functions())


def scratch(n, H, vp, width):
    """The column kernel's scratch of n columns: (scr, sdepth, bat, tg, te, cross,
    n_cross, pa, pb), each a row per column, shaped as column_scratch's and
    fold_scratch's."""
    scr, sdepth, bat = column_scratch()
    return _rows(n, (scr, sdepth, bat) + fold_scratch(vp, H, width))


def _rows(n, arrays):
    return tuple(np.empty((n,) + a.shape, a.dtype) for a in arrays)


def column_kernel_cuda(surface, vp, gbuf, ebuf, hrec, hstride, evals, wrange, rows):
    """column.column_kernel's work on the GPU (the same arguments, f and fg the
    surface's): gbuf, ebuf, hrec, evals, wrange and rows are filled on the host."""
    _cuda()
    vp = vp.copy()
    vp[VP_BATCH] = 0.0
    kind, _, _, _, hf, hfp = surface.kernel_args()
    d = cuda.to_device
    head = (kind, d(np.ascontiguousarray(hf)), d(hfp), d(vp), hstride, d(np.empty((3, 0))))
    H = gbuf.shape[1]
    _launch(kernel(surface), head, lambda n: scratch(n, H, vp, gbuf.shape[3]), gbuf, ebuf,
            hrec, evals, wrange, rows)


def area_kernel_cuda(surface, flat, lv, vp, slices, lod, gbuf, ebuf, evals, wrange, rows):
    """area.area_kernel's work on the GPU (the same arguments, f and fg the
    surface's)."""
    from .area import area_scratch
    _cuda()
    kind, _, _, _, _, hfp = surface.kernel_args()
    d = cuda.to_device
    head = (kind, _resident(surface, "flat", flat),
            d(np.ascontiguousarray(lv, dtype=np.float64)), d(hfp), d(vp), int(slices),
            float(lod))
    H = gbuf.shape[1]
    hrec = np.empty((evals.shape[0], 1, 1))
    _launch(kernel(surface, "area"), head,
            lambda n: _rows(n, area_scratch(H, lv.shape[0])), gbuf, ebuf, hrec, evals, wrange,
            rows)


def _resident(surface, name, array, dtype=np.float64):
    """``array`` (a surface's heights, its pyramid or block maxima) on the device, copied
    once and kept with the surface while the array is the one it holds: a fly-through's
    frames share the copy (a 4097^2 DEM's pyramid is 180 MB)."""
    key = "_cuda_resident_" + name
    held = surface._fits.get(key)
    if held is None or held[0] is not array:
        held = (array, cuda.to_device(np.ascontiguousarray(array, dtype=dtype)))
        surface._fits[key] = held
    return held[1]


def _frame_tables(kind, lv, hfp, vp, lod, kappa, s_ref):
    """A frame's planes and its pyramid's tables (kernels/lod.py's plane_table,
    level_table, level_ints), made on the host for the fly-through kernels."""
    from .lod import level_ints, level_table, plane_table
    return (plane_table(kind, lv, vp, lod, kappa, s_ref), level_table(lv, hfp),
            level_ints(lv))


def march_kernel_cuda(surface, flat, lv, slope, hfp, vp, lod, kappa, s_lo, s_hi, gbuf, ebuf,
                      evals, wrange, rows):
    """march.march_kernel's work on the GPU (the same arguments and surface)."""
    from .layout import SURF_HEIGHTFIELD
    from .march import P_SIZE
    _cuda()
    planes, lt, lk = _frame_tables(SURF_HEIGHTFIELD, lv, hfp, vp, lod, kappa, 0.5 * (s_lo + s_hi))
    d = cuda.to_device
    head = (_resident(surface, "flat", flat), d(lt), d(lk),
            d(np.ascontiguousarray(slope, dtype=np.float64)), d(hfp), d(vp), d(planes),
            float(s_lo), float(s_hi))
    hrec = np.empty((evals.shape[0], 1, 1))
    _launch(kernel(surface, "march"), head,
            lambda n: (np.empty((n, P_SIZE)), np.empty((n, 5))), gbuf, ebuf, hrec, evals,
            wrange, rows)


def lod_kernel_cuda(surface, kind, hf0, flat, lv, mx, mt, hfp, vp, area, lod, kappa, s_lo, s_hi,
                    gbuf, ebuf, evals, wrange, rows):
    """lod.lod_kernel's work on the GPU (its arguments but the surface's functions), a
    thread a column."""
    from .lod import AC_SIZE, Q_SIZE, REFINE_DEPTH, ST_SIZE
    _cuda()
    s_ref = 0.5 * (s_lo + s_hi) if s_lo == s_lo else 0.0
    planes, lt, lk = _frame_tables(kind, lv, hfp, vp, lod, kappa, s_ref)
    d = cuda.to_device
    head = (kind, _resident(surface, "hf", hf0, hf0.dtype), _resident(surface, "flat", flat),
            d(lt), d(lk), _resident(surface, "mx", mx), d(np.ascontiguousarray(mt, np.float64)),
            d(hfp), d(vp), bool(area), d(planes), float(s_lo), float(s_hi))
    H = gbuf.shape[1]
    hrec = np.empty((evals.shape[0], 1, 1))
    _launch(kernel(surface, "lod"), head,
            lambda n: (np.empty((n, 1, H if area else 1, AC_SIZE)),
                       np.empty((n, 1, 3 + REFINE_DEPTH, Q_SIZE)), np.empty((n, 1, ST_SIZE)),
                       np.empty((n, 1, 5))), gbuf, ebuf, hrec, evals, wrange, rows)


def layers_kernel_cuda(surface, vp, c0, mp, colours, sh, hmax, hmin, hsurf, slopes, occ, lists,
                       off, K, counts, gfirst, hits, evals):
    """layers.layers_kernel's work on the GPU (the same arguments but the surface's
    functions; ``colours`` its (lut, levels, offsets, shapes, tp, lines)): lists, counts,
    gfirst, hits and evals are updated on the host."""
    from .layers import layers_scratch
    from .layout import VP_W
    _cuda()
    kind, _, _, _, hf, hfp = surface.kernel_args()
    d = cuda.to_device
    B, H = lists.shape[0], lists.shape[1]
    trans, scr = layers_scratch(H)
    out = [d(a) for a in (lists, counts, gfirst, hits, evals)]
    k = kernel(surface, "layers")
    k[-(-B // THREADS), THREADS](
        kind, d(np.ascontiguousarray(hf)), d(hfp), d(vp), int(c0), d(mp),
        *(d(np.ascontiguousarray(a)) for a in colours), d(sh), d(hmax), d(hmin), d(hsurf),
        d(np.ascontiguousarray(slopes, dtype=np.float64)),
        *(d(np.ascontiguousarray(a)) for a in occ), *out[:1], int(off), int(K), *out[1:],
        cuda.device_array((B,) + trans.shape), cuda.device_array((B,) + scr.shape),
        int(vp[VP_W]))
    for host, dev in zip((lists, counts, gfirst, hits, evals), out):
        host[...] = dev.copy_to_host()


def _launch(k, head, scratch_of, gbuf, ebuf, hrec, evals, wrange, rows):
    """Launch kernel k over the picture's columns, MAX_COLUMNS at a time: its
    arguments ``head``, the column's first number, the buffers, ``scratch_of(n)``'s
    arrays for n columns, the per-column outputs; then the buffers, evals, wrange and
    each tile's rows (column_kernel's ``rows``) filled on the host."""
    n_tiles, H, T = gbuf.shape[0], gbuf.shape[1], gbuf.shape[2]
    W = evals.shape[0]
    d_g = cuda.device_array(gbuf.shape, gbuf.dtype)
    d_e = cuda.device_array(ebuf.shape, ebuf.dtype)
    d_h = cuda.device_array(hrec.shape, hrec.dtype)
    jrange = np.empty((W, 2), dtype=np.int64)
    for first in range(0, W, MAX_COLUMNS):
        n = min(MAX_COLUMNS, W - first)
        bufs = [cuda.device_array(a.shape, a.dtype) for a in scratch_of(n)]
        d_ev = cuda.device_array(n, np.int64)
        d_wr = cuda.device_array((n, 2), np.float64)
        d_jr = cuda.device_array((n, 2), np.int64)
        k[-(-n // THREADS), THREADS](*head, first, d_g, d_e, d_h, *bufs, d_ev, d_wr, d_jr)
        evals[first:first + n] = d_ev.copy_to_host()
        wrange[first:first + n] = d_wr.copy_to_host()
        jrange[first:first + n] = d_jr.copy_to_host()
    gbuf[...] = d_g.copy_to_host()
    ebuf[...] = d_e.copy_to_host()
    hrec[...] = d_h.copy_to_host()
    pad = n_tiles * T - W
    lo = np.concatenate([jrange[:, 0], np.full(pad, H, np.int64)]).reshape(n_tiles, T)
    hi = np.concatenate([jrange[:, 1], np.full(pad, -1, np.int64)]).reshape(n_tiles, T)
    rows[:, 0] = lo.min(axis=1)
    rows[:, 1] = hi.max(axis=1)


def ptx(surface, cc=(9, 0), opt=True, which="column"):
    """``surface``'s kernel ``which`` ("column", "area", "layers", "march" or "lod":
    kernel's) compiled
    to PTX for compute capability ``cc``, on a machine with or without a GPU (the CUDA
    toolkit's NVVM, which numba-cuda's extra brings, is enough): (PTX text, seconds).
    ``opt=False``: without NVVM's optimisation (the same check that everything
    compiles for the device; the column kernel 21-49 s instead of 123 s on 2 cores).
    Device functions ask the current device for its compute capability; without a
    GPU, ``cc`` stands for it while this compiles."""
    import time
    from numba import types
    from numba.cuda import dispatcher as cuda_dispatcher
    _cuda()
    if simulated():
        raise ValueError("ptx() compiles for a real GPU: not under NUMBA_ENABLE_CUDASIM")
    f64, f32, i32, i64 = types.float64, types.float32, types.int32, types.int64

    def arr(t, nd):
        return types.Array(t, nd, "C")
    bufs = (i64, arr(f32, 4), arr(f32, 4), arr(f64, 3))           # first, gbuf, ebuf, hrec
    outs = (arr(i64, 1), arr(f64, 2), arr(i64, 2))                # evals, wrange, jrange
    if which == "area":
        sig = (i64, arr(f64, 1), arr(f64, 2), arr(f64, 1), arr(f64, 1), i64, f64) + bufs + \
            (arr(f64, 3),) * 5 + outs
    elif which == "march":
        sig = (arr(f64, 1), arr(f64, 2), arr(i64, 2), arr(f64, 2), arr(f64, 1), arr(f64, 1),
               arr(f64, 2), f64, f64) + bufs + (arr(f64, 2), arr(f64, 2)) + outs
    elif which == "lod":
        sig = (i64, arr(f64, 2), arr(f64, 1), arr(f64, 2), arr(i64, 2), arr(f64, 1),
               arr(f64, 2), arr(f64, 1), arr(f64, 1), types.boolean, arr(f64, 2), f64,
               f64) + bufs + (arr(f64, 4), arr(f64, 4), arr(f64, 3), arr(f64, 3)) + outs
    elif which == "layers":
        sig = (i64, arr(f64, 2), arr(f64, 1), arr(f64, 1), i64, arr(f64, 1),
               arr(f64, 2), arr(f32, 1), arr(i64, 1), arr(i64, 2), arr(f64, 1),
               arr(f64, 1), arr(f64, 1), arr(f32, 3), arr(f32, 3), arr(f32, 3), arr(f64, 3),
               arr(f64, 3), arr(f64, 2), arr(i64, 1), arr(i64, 1), arr(f64, 2),  # occluders
               arr(f32, 4), i64, i64,
               arr(i32, 2), arr(f32, 3), arr(i32, 2), arr(i64, 1), arr(f64, 2), arr(f64, 3),
               i64)
    else:
        sig = (i64, arr(f64, 2), arr(f64, 1), arr(f64, 1), i64, arr(f64, 2)) + bufs + \
            (arr(f64, 3), arr(i64, 2), arr(f64, 2), arr(f64, 3), arr(f64, 3), arr(f64, 3),
             arr(i64, 2), arr(f64, 2), arr(f64, 2)) + outs
    source = _source(surface, which)

    class _Device:
        compute_capability = tuple(cc)

    saved = cuda_dispatcher.get_current_device
    cuda_dispatcher.get_current_device = lambda: _Device()
    try:
        t = time.perf_counter()
        text, _ = cuda.compile_ptx(source, sig, cc=tuple(cc), opt=bool(opt))
        return text, time.perf_counter() - t
    finally:
        cuda_dispatcher.get_current_device = saved

"""The one place where Numba decorator options are spelled."""
import threading

import numba
import numpy as np
from numba import types
from numba.core import cgutils
from numba.core.ccallback import CFunc
from numba.extending import intrinsic

#: Signature of every user function the kernels call: w = f(u, v, t), t the surface's
#: parameter (the time of a time-varying surface; ignored by most functions).
SURFACE_SIG = types.float64(types.float64, types.float64, types.float64)
#: First-class function type of such a function (DESIGN.md section 4).
SurfaceFn = types.FunctionType(SURFACE_SIG)
#: The fused value-and-gradient function: w = fg(u, v, t, p) also writes f_u to p[0]
#: and f_v to p[1]. One call shares the common subexpressions of f, f_u and f_v
#: (sympy's cse): 3 sin(u cos v) needs 4 trigonometric calls instead of 7.
GRAD_SIG = types.float64(types.float64, types.float64, types.float64,
                         types.CPointer(types.float64))
GradFn = types.FunctionType(GRAD_SIG)
#: The batch evaluator: fb(u, v, t, out, n) writes w, f_u, f_v of the n points
#: (u[i], v[i]) to out[i], out[n + i], out[2n + i]. Its loop is compiled to SIMD code
#: (vmath.py); a point where any of the three is not finite must be evaluated again
#: with the scalar fg (column.py does), which alone decides holes.
BATCH_SIG = types.void(types.CPointer(types.float64), types.CPointer(types.float64),
                       types.float64, types.CPointer(types.float64), types.int64)
BatchFn = types.FunctionType(BATCH_SIG)


def _option(name, value, otherwise=None):
    """{name: value} where this Numba has the decorator option ``name``, else
    ``otherwise`` (default: no option)."""
    try:
        from numba.core.cpu import CPUTargetOptions
    except ImportError:  # pragma: no cover - layout of another Numba
        return dict(otherwise or {})
    return {name: value} if hasattr(CPUTargetOptions, name) else dict(otherwise or {})


#: LLVM inlines the function wherever it is called (Numba's ``forceinline``: LLVM's
#: alwaysinline attribute; compiled once, its code goes with the caller's library);
#: where a Numba lacks the option, Numba's own inlining (same code, slower compile).
_LLVM_INLINE = _option("forceinline", True, otherwise={"inline": "always"})
#: The function stays a call: a function that does not say ``forceinline`` takes its
#: first caller's while that compiles.
_LLVM_CALL = _option("forceinline", False)
#: Numba's (private, long-standing) option that compiles without its runtime; where a
#: Numba lacks it the functions are compiled with reference counting.
_NRT_OFF = _option("_nrt", False)


#: The one fast-math flag of the kernels and the surfaces' functions: LLVM may fuse a
#: multiplication and an addition into one FMA instruction (a rounding fewer, the
#: product kept exact). No other: NaN and the infinities are holes and tested for
#: (nnan, ninf), sums keep their order (reassoc), divisions and square roots their
#: IEEE results (arcp, afn). 1920x1080 of 3 sin(u cos v): perspective 37.0 -> 34.0 ms,
#: orthographic 23.9 -> 22.0 ms; a 2049^2 DEM's fly-through frame 50.9 -> 48.3 ms by
#: the ray march, 95.0 -> 87.6 ms area sampled (medians, alternate runs, 2026-12-08).
#: The rasteriser of objects (kernels/raster.py) keeps exact products (the *_exact
#: decorators): its edge functions decide coverage at coordinates up to 1e300, where a
#: fused product changed which side of an edge 57 pixels of a pole lay.
_MATH = {"fastmath": {"contract"}}

#: Functions called (where LLVM's heuristics do not inline them).
ngjit = numba.njit(cache=True, nogil=True, error_model="numpy", **_MATH, **_LLVM_CALL)
#: ... and without FMA contraction (_MATH: kernels/raster.py's)
ngjit_exact = numba.njit(cache=True, nogil=True, error_model="numpy", **_LLVM_CALL)
#: Per-sample and per-pixel helpers, inlined into their callers by LLVM. Without
#: reference counting (they allocate nothing), as their callers (ngjit_nrt_free,
#: ngjit_parallel_nrt_free): in a caller that counts references, LLVM's inlining
#: leaves the increments and decrements of the counts of the arrays passed around
#: each call (atomic operations, about 8 ns each; the finishing pass was 15-20 %
#: slower with them). Not Numba's inlining (``inline="always"``), which copies the
#: callee's IR and runs Numba's passes on the copy at every call site, nested: the
#: first render of a fresh install compiled for 106 s that way instead of 46-54 s
#: (2 cores), to the same code and speed.
ngjit_inline = numba.njit(cache=True, nogil=True, error_model="numpy", **_MATH, **_NRT_OFF,
                          **_LLVM_INLINE)
ngjit_inline_exact = numba.njit(cache=True, nogil=True, error_model="numpy", **_NRT_OFF,
                                **_LLVM_INLINE)


#: The column's loop and what it calls, none of which allocates: compiled without
#: Numba's reference counting (its runtime, NRT), so passing an array or inlining a
#: helper that takes one costs no call of NRT_incref/NRT_decref. Those calls were
#: about a fifth of the column loop even where the arrays were views without owner
#: (each call then a null test). Allocating here is a compile error.
ngjit_nrt_free = numba.njit(cache=True, nogil=True, error_model="numpy", **_MATH, **_NRT_OFF,
                            **_LLVM_CALL)
#: Kernels: ``prange`` over pixel columns (launched from Python only, through
#: _Exclusive).
_parallel = numba.njit(cache=True, nogil=True, parallel=True, error_model="numpy", **_MATH,
                       **_LLVM_CALL)
_parallel_exact = numba.njit(cache=True, nogil=True, parallel=True, error_model="numpy",
                             **_LLVM_CALL)
#: ... and one that allocates nothing and calls helpers with arrays per pixel (the
#: finishing pass): no reference counting, as ngjit_nrt_free.
_parallel_nrt_free = numba.njit(cache=True, nogil=True, parallel=True, error_model="numpy",
                                **_MATH, **_NRT_OFF, **_LLVM_CALL)

# prange_index: Numba types a parallel kernel twice, the whole function first (a
# prange's index an int64) and then the loop's body on its own (the index a uint64),
# and it compiles every helper the body calls with the index for both. A kernel's
# loop therefore starts ``for c_ in prange(n): c = np.int64(c_)``, one signature in
# both typings (the layers kernel's column code had compiled twice, 8 s of a fresh
# install's warm-up). Likewise a literal argument (``0``, ``-1``) where another call
# passes a variable: ``np.int64(0)`` is an int64.

#: held by a parallel kernel's launch while Numba's threading layer may be workqueue
_LAUNCH = threading.RLock()
#: the threading layer, once Numba has chosen it (at the first parallel launch)
_layer = None


def _thread_safe_layer():
    """Whether Numba's threading layer is known to take launches from several Python
    threads at once (TBB, OpenMP): workqueue does not, nor is it known before the
    first launch."""
    global _layer
    if _layer is None:
        try:
            _layer = numba.threading_layer()
        except ValueError:                 # (no parallel function has run yet)
            return False
    return _layer != "workqueue"


class _Exclusive:
    """A parallel kernel whose launches take one lock while Numba's threading layer is
    workqueue (or not yet chosen): that layer is not thread-safe, and two Python
    threads rendering at once (a notebook's widgets, a web server's requests) made it
    abort the whole process ("Concurrent access has been detected"). Numba takes it
    where neither TBB nor OpenMP loads (a Mac without libomp, a slim container
    without libgomp). With TBB or OpenMP the kernel is called as it is. Attributes are
    the dispatcher's (py_func, signatures, ...)."""

    def __init__(self, dispatcher, functions=None, called=()):
        self._dispatcher = dispatcher
        self.__doc__ = dispatcher.__doc__
        self.__name__ = dispatcher.__name__
        self.__wrapped__ = dispatcher
        self._functions = functions
        #: the jitted functions it takes as values (kernel_calling), for warmup's list
        self.called = called
        self._entries = {}              # _type_key's of the arguments -> (entry, functions)

    def __call__(self, *args, **kwargs):
        try:
            if self._functions is not None:
                return self._call_with_functions(args)
            if _thread_safe_layer():
                return self._dispatcher(*args, **kwargs)
            with _LAUNCH:
                return self._dispatcher(*args, **kwargs)
        except SystemError as exc:
            # Numba reports an exception raised inside a parallel loop (by the launching
            # thread: in another thread's share of the loop Numba drops it, numba#2811)
            # as a SystemError caused by it: the exception itself, an index out of range
            # under NUMBA_BOUNDSCHECK (the test suite's kernels, tests/conftest.py)
            if isinstance(exc.__cause__, Exception) and \
                    not isinstance(exc.__cause__, SystemError):
                raise exc.__cause__ from None
            raise

    def _call_with_functions(self, args):
        """The kernel called with its arguments and, after them, the jitted functions
        that functions(*args) gives as (function, first-class function type) pairs:
        compiled (or loaded from the cache) for exactly those types, so that Numba
        types each function as a value (its address) and not as a Dispatcher, which it
        would compile and link into the kernel (kernel_calling)."""
        key = tuple(_type_key(a) for a in args)
        hit = self._entries.get(key)
        if hit is None:
            pairs = self._functions(*args)
            tys = tuple(numba.typeof(a) for a in args) + tuple(t for _, t in pairs)
            hit = self._entries[key] = (self._dispatcher.compile(tys),
                                        tuple(fn for fn, _ in pairs))
        entry, values = hit
        if _thread_safe_layer():
            return entry(*args, *values)
        with _LAUNCH:
            return entry(*args, *values)

    def __getattr__(self, name):
        return getattr(self._dispatcher, name)


def _type_key(a):
    """What numba.typeof(a) of a kernel's argument depends on, found in a microsecond or
    two (numba.typeof builds its types anew: 15 arguments took 0.2 ms, a launch's
    Python): an array's class, dtype, dimensions and flags, a number's class, a tuple's
    items'; anything else's type itself."""
    if isinstance(a, np.ndarray):
        f = a.flags
        return (type(a), a.dtype, a.ndim, f.c_contiguous, f.f_contiguous, f.writeable,
                f.aligned)
    if isinstance(a, (int, float, bool, np.number, np.bool_)):
        return type(a)
    if isinstance(a, tuple):
        return tuple(_type_key(x) for x in a)
    if isinstance(a, CFunc):                    # (typed by its signature)
        return CFunc, a._sig
    return numba.typeof(a)


def ngjit_parallel(fn):
    """Kernels: ``prange`` over pixel columns (_parallel), launched through _Exclusive."""
    return _Exclusive(_parallel(fn))


def ngjit_parallel_exact(fn):
    """As ngjit_parallel, without FMA contraction (_MATH)."""
    return _Exclusive(_parallel_exact(fn))


def ngjit_parallel_nrt_free(fn):
    """As ngjit_parallel, without reference counting (_parallel_nrt_free)."""
    return _Exclusive(_parallel_nrt_free(fn))


def function_type(fn, *args):
    """The first-class function type (types.FunctionType) of the jitted function fn
    called with ``args``, each a Numba type or a value of the type (numba.typeof), for
    which it is compiled here (or loaded from its cache)."""
    args = tuple(a if isinstance(a, types.Type) else numba.typeof(a) for a in args)
    key = (fn, args)
    ft = _FUNCTION_TYPES.get(key)
    if ft is None:
        fn.compile(args)
        ft = _FUNCTION_TYPES[key] = types.FunctionType(fn.overloads[args].signature)
    return ft


#: function_type's answers, by (function, argument types)
_FUNCTION_TYPES = {}


def kernel_calling(functions, called, exact=False):
    """A parallel kernel (ngjit_parallel) whose last parameters are jitted functions
    (``called``) that it calls as first-class function values, through their
    addresses, where ``functions(*args)`` gives them for its other arguments as
    (function, function_type(...)) pairs; it is launched with those other arguments
    alone. Numba compiles a function that a kernel calls by name into the kernel's
    code, and optimises and compiles that code again for each library that links it:
    the callee's own, the kernel's parallel loop's, the loop's wrapper's and the
    kernel's. The column pass's code was so compiled again three times for
    column_kernel and three for subcolumn_kernel (their own compiles 19.9 and 21.4 s,
    render_column's 4.9 s); called through its address it is compiled once, for both,
    and the kernels' own compiles take 1-2 s (every kernel, bounds-checked, one core:
    246 -> 181 s; benchmarks/bench_first.py --compile). A function's exceptions reach
    the kernel's loop as a direct call's do: Numba calls a Dispatcher's function value
    by its compiled function's own address, which reports them (a parallel loop
    reports them where the launching thread runs into them and drops them in another
    thread's share, numba#2811: _Exclusive.__call__). ``exact``: without FMA
    contraction (_MATH)."""
    def make(fn):
        return _Exclusive((_parallel_exact if exact else _parallel)(fn), functions, called)
    return make


def compile_surface_fn(pyfunc):
    """Compile a scalar Python function ``(u, v, t) -> float`` to a Numba cfunc.

    ``error_model="numpy"`` makes 1/0 an infinity (a hole), never an exception.
    """
    return numba.cfunc(SURFACE_SIG, error_model="numpy", nopython=True, **_MATH)(pyfunc)


def compile_grad_fn(pyfunc):
    """Compile ``(u, v, t, p) -> w`` (writing f_u, f_v to p[0], p[1]) to a cfunc."""
    return numba.cfunc(GRAD_SIG, error_model="numpy", nopython=True, **_MATH)(pyfunc)


def compile_batch_fn(pyfunc):
    """Compile ``(u, v, t, out, n) -> None`` (BATCH_SIG) to a cfunc."""
    return numba.cfunc(BATCH_SIG, error_model="numpy", nopython=True, **_MATH)(pyfunc)


@intrinsic
def array_ptr(typingctx, arr, offset):
    """Pointer to element ``offset`` of the contiguous 1-D array arr (for a cfunc)."""
    def codegen(context, builder, signature, args):
        ary = context.make_array(signature.args[0])(context, builder, args[0])
        return builder.gep(ary.data, [args[1]])
    return types.CPointer(arr.dtype)(arr, offset), codegen


@intrinsic
def stack_pair(typingctx):
    """Two float64 on the calling function's stack, as a pointer: where a fused
    gradient function writes f_u and f_v (no heap allocation, no reference count)."""
    def codegen(context, builder, signature, args):
        return cgutils.alloca_once(builder, context.get_value_type(types.float64), size=2)
    return types.CPointer(types.float64)(), codegen


@intrinsic(prefer_literal=True)
def array_as_tuple(typingctx, arr, n):
    """The first n (a literal) values of the 1-D array arr as a tuple: values in
    registers, which a loop's stores cannot change, so a loop that reads them (the
    view parameters vp, say) needs neither reloads nor run-time alias checks."""
    if not isinstance(n, types.IntegerLiteral):
        return None
    size = n.literal_value
    tup = types.UniTuple(arr.dtype, size)

    def codegen(context, builder, signature, args):
        ary = context.make_array(signature.args[0])(context, builder, args[0])
        intp = context.get_value_type(types.intp)
        vals = [builder.load(builder.gep(ary.data, [intp(i)])) for i in range(size)]
        return context.make_tuple(builder, tup, vals)
    return tup(arr, n), codegen

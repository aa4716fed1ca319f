"""The one place where Numba decorator options are spelled."""
import numba
from numba import types
from numba.core import cgutils
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

#: Small helpers inlined into kernels.
ngjit = numba.njit(cache=True, nogil=True, error_model="numpy")
#: Per-pixel and per-sample helpers with array arguments, inlined into their callers
#: by Numba itself: a call that is not inlined increments and decrements the
#: reference count of every array it is passed (atomic operations, about 8 ns each).
ngjit_inline = numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
#: The column's loop and what it calls, none of which allocates: compiled without
#: Numba's reference counting (its runtime, NRT), so passing an array or inlining a
#: helper that takes one costs no call of NRT_incref/NRT_decref. Those calls were
#: still about a fifth of the column loop with views without owner (``unmanaged``),
#: where each is a null test behind a call. Allocating here is a compile error.
ngjit_nrt_free = numba.njit(cache=True, nogil=True, error_model="numpy", _nrt=False)
#: Kernels: ``prange`` over pixel columns.
ngjit_parallel = numba.njit(cache=True, nogil=True, parallel=True, error_model="numpy")


def compile_surface_fn(pyfunc):
    """Compile a scalar Python function ``(u, v, t) -> float`` to a Numba cfunc.

    ``error_model="numpy"`` makes 1/0 an infinity (a hole), never an exception.
    """
    return numba.cfunc(SURFACE_SIG, error_model="numpy", nopython=True)(pyfunc)


def compile_grad_fn(pyfunc):
    """Compile ``(u, v, t, p) -> w`` (writing f_u, f_v to p[0], p[1]) to a cfunc."""
    return numba.cfunc(GRAD_SIG, error_model="numpy", nopython=True)(pyfunc)


@intrinsic
def stack_pair(typingctx):
    """Two float64 on the calling function's stack, as a pointer: where a fused
    gradient function writes f_u and f_v (no heap allocation, no reference count)."""
    def codegen(context, builder, signature, args):
        return cgutils.alloca_once(builder, context.get_value_type(types.float64), size=2)
    return types.CPointer(types.float64)(), codegen


@intrinsic
def unmanaged(typingctx, arr):
    """The same array without its reference-counted owner (meminfo NULL).

    Numba increments and decrements an array's reference count (atomically) wherever
    it passes an array to a function that it does not fully inline, and Numba's own
    inlining still leaves most of those pairs in branching code: in the column loop
    that was about half of the time. On a view without owner those operations are a
    null test. The caller must keep the original array alive while the view is in
    use: kernels make these views of their arguments and of scratch they hold."""
    if not isinstance(arr, types.Array):
        return None

    def codegen(context, builder, signature, args):
        src = context.make_array(signature.args[0])(context, builder, value=args[0])
        dst = context.make_array(signature.return_type)(context, builder)
        for name in ("parent", "nitems", "itemsize", "data", "shape", "strides"):
            setattr(dst, name, getattr(src, name))
        dst.meminfo = cgutils.get_null_value(dst.meminfo.type)
        return dst._getvalue()
    return arr(arr), codegen

"""The one place where Numba decorator options are spelled."""
import numba
from numba import types

#: Signature of every user function the kernels call: w = f(u, v, t), t the surface's
#: parameter (the time of a time-varying surface; ignored by most functions).
SURFACE_SIG = types.float64(types.float64, types.float64, types.float64)
#: First-class function type of such a function (DESIGN.md section 4).
SurfaceFn = types.FunctionType(SURFACE_SIG)

#: Small helpers inlined into kernels.
ngjit = numba.njit(cache=True, nogil=True, error_model="numpy")
#: Kernels: ``prange`` over pixel columns.
ngjit_parallel = numba.njit(cache=True, nogil=True, parallel=True, error_model="numpy")


def compile_surface_fn(pyfunc):
    """Compile a scalar Python function ``(u, v, t) -> float`` to a Numba cfunc.

    ``error_model="numpy"`` makes 1/0 an infinity (a hole), never an exception.
    """
    return numba.cfunc(SURFACE_SIG, error_model="numpy", nopython=True)(pyfunc)

"""Surfaces: what the kernels sample.

A Surface carries f, and f fused with f_u and f_v in one function, as compiled Numba
cfuncs (DESIGN.md section 4), so a new expression costs about a tenth of a second
and never recompiles a kernel (big orthographic pictures add a batch evaluator of
the three in SIMD code, compiled on first use: Surface.batch); or a height grid read
as a bilinear function (the paper's "digital height field").
"""
from __future__ import annotations

import copy
import functools
import logging
import math
import numbers

import numba
import numpy as np

from .expression import constant_number, parse_cached
from .kernels._jit import compile_batch_fn, compile_grad_fn, compile_surface_fn
from .kernels.layout import HFP_CW, HFP_IU, HFP_IV, SURF_FUNCTION, SURF_HEIGHTFIELD
from .kernels.sample import eval_grid


def array_like(a):
    """An array, or an object numpy reads as one through __array__ (a pandas Index or
    DataFrame, an xarray DataArray), not a sympy object (a Matrix has __array__) nor a
    Surface."""
    if isinstance(a, np.ndarray):
        return True
    if isinstance(a, (str, bytes)) or not hasattr(a, "__array__"):
        return False
    from sympy import Basic
    from sympy.matrices import MatrixBase
    return not isinstance(a, (Basic, MatrixBase, Surface))

def heights_array(a):
    """``a`` as a 2-D array of heights (float, NaN where masked or not finite) where it
    is one: a numpy array, anything numpy reads as one (array_like), or a list of lists
    of numbers, of 2 dimensions and a numeric dtype; None otherwise (an expression, a
    list of them, a callable)."""
    if not (array_like(a) or (isinstance(a, list) and a and isinstance(a[0], (list, tuple)))):
        return None
    try:
        arr = np.ma.asarray(a)
    except (TypeError, ValueError):
        return None
    if arr.ndim != 2 or arr.dtype.kind not in "biuf":
        return None
    with np.errstate(invalid="ignore"):
        return np.ma.filled(arr.astype(np.float64), np.nan)


log = logging.getLogger(__name__)

DEFAULT_VARS = ("u", "v")


class Surface:
    """A function surface w = f(u, v) ready for the kernels.

    Build one with :func:`as_surface` (sympy expression, string or callable) or
    :class:`HeightField`. ``evaluate(u, v)`` gives w with NaN at holes.
    """

    kind = SURF_FUNCTION

    def __init__(self, f, fg, *, expr=None, variables=DEFAULT_VARS,
                 derivatives="symbolic", time=None, batch_source=None):
        self.f = f          # cfunc w = f(u, v, t)
        self.fg = fg        # cfunc w = fg(u, v, t, p), p <- (f_u, f_v)
        # the batch evaluator (kernels/_jit.py BATCH_SIG), compiled on first use by
        # batch(); a dict, so that the copies made by at() share it
        self._batch = {"source": batch_source}
        self.expr = expr
        self.variables = tuple(variables)
        self.derivatives = derivatives
        self.time = time            # name of the time parameter, or None
        self.hf = np.zeros((2, 2))
        # hfp[0]: the time t; HFP_IU, HFP_IV, HFP_CW: the box scaling (scaled())
        self.hfp = np.array([0.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0])
        self._fits = {}     # fit_grid's, shared by the copies made by at()

    def __copy__(self):
        # (at() and scaled() copy: the same compiled functions and caches, shared)
        other = object.__new__(type(self))
        other.__dict__.update(self.__dict__)
        return other

    def __reduce__(self):
        """Pickling (a matplotlib figure that holds a plot, ``copy.deepcopy``): the
        surface is made again from what it was made of, its expression or its Python
        function, with its time and box scaling; compiled functions are not pickled."""
        if self.expr is not None:
            return _rebuilt, (_compiled_expression, (self.expr, self.variables, self.time),
                              self.hfp)
        fn = self.__dict__.get("source")
        if fn is not None:
            return _rebuilt, (_callable_surface, (fn, self.variables), self.hfp)
        raise TypeError("cannot pickle a Surface made of compiled functions: make it from "
                        "an expression or a Python function (floatcol.as_surface)")

    def at(self, t):
        """The same surface at time ``t`` (same compiled functions, no recompile)."""
        if self.kind != SURF_FUNCTION:
            raise ValueError("only a function surface has a time parameter")
        other = copy.copy(self)
        other.hfp = self.hfp.copy()
        other.hfp[0] = float(t)
        return other

    def scaled(self, a, b, c):
        """The surface stretched by a along u, b along v and c along w: w = c f(p / a,
        q / b) over the domain times (a, b), with the same compiled functions (the
        kernels scale each evaluation, layout.py's HFP_*). render's ``aspect``
        draws a box-scaled surface this way."""
        if self.kind != SURF_FUNCTION:
            raise ValueError("only a function surface scales through its parameters")
        other = copy.copy(self)
        other.hfp = self.hfp.copy()
        other.hfp[HFP_IU] /= a
        other.hfp[HFP_IV] /= b
        other.hfp[HFP_CW] *= c
        return other

    #: Default domain when the caller gives none (None: the caller must choose).
    default_domain = None

    def batch(self):
        """The batch evaluator of f, f_u and f_v (SIMD code, kernels/vmath.py), or None
        where there is none (a height field, a callable, a complex expression, one
        with functions that do not vectorise). Compiled on the first call, about a
        tenth of a second once per expression; render() asks for it only where a
        picture has enough samples to repay that (render.BATCH_MIN_SAMPLES)."""
        if "fn" not in self._batch:
            source = self._batch["source"]
            self._batch["fn"] = _compile_batch(*source) if source is not None else None
        return self._batch["fn"]

    def kernel_args(self, fb=None):
        """(kind, f, fg, fb, hf, hfp): what every kernel takes to sample the surface;
        fb the batch evaluator ``batch()``, or (None) a stand-in that leaves every
        point to fg (a kernel uses fb only where vp's VP_BATCH says so)."""
        return self.kind, self.f, self.fg, _no_batch() if fb is None else fb, self.hf, self.hfp

    def evaluate(self, u, v, derivatives=False):
        """w = f(u, v) on arrays (NaN at holes); with derivatives, (w, f_u, f_v)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=np.float64),
                                   np.asarray(v, dtype=np.float64))
        out = np.empty((u.size, 3))
        eval_grid(*self.kernel_args(), np.ascontiguousarray(u).ravel(),
                  np.ascontiguousarray(v).ravel(), out)
        res = [out[:, i].reshape(u.shape) for i in range(3)]
        return tuple(res) if derivatives else res[0]

    def __repr__(self):
        what = self.expr if self.expr is not None else "callable"
        return f"Surface({what}, vars={self.variables}, derivatives={self.derivatives})"


#: HeightField.extremes: the highest and the lowest nodes the picture's fit takes in
EXTREME_NODES = 64


class HeightField(Surface):
    """A grid of heights read as a bilinear function with exact piecewise partials.

    ``z[j, i]`` is the height at ``(u_i, v_j)`` (rows follow v, columns follow u, as
    in matplotlib's ``plot_surface(X, Y, Z)`` with ``meshgrid``); the grid spans
    ``u = (a, b)`` and ``v = (c, d)``, by default the index ranges; a range given
    downward, ``v = (north, south)`` for rows that run north to south as a DEM's, is
    the same grid read that way. NaN cells are holes. ``read_dem`` (floatcol.terrain)
    makes one from a DEM file.
    """

    kind = SURF_HEIGHTFIELD
    #: True where matplotlib's mesh was resampled onto this grid (mesh.py)
    resampled = False

    def __init__(self, z, u=None, v=None):
        try:
            with np.errstate(invalid="ignore"):          # (signalling NaNs: holes below)
                z = np.array(z, dtype=np.float64)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"HeightField needs a 2-D array of numbers: {exc}") from None
        if z.ndim != 2 or z.shape[0] < 2 or z.shape[1] < 2:
            raise ValueError(
                f"HeightField needs a 2-D array of at least 2 x 2 heights, got shape {z.shape}")
        z[~np.isfinite(z)] = np.nan
        nv, nu = z.shape
        # a range that runs downward (rows north to south, v = (north, south)) is the
        # grid flipped: kept ascending
        u, flip_u = _ascending("u", u)
        v, flip_v = _ascending("v", v)
        if flip_u:
            z = z[:, ::-1]
        if flip_v:
            z = z[::-1]
        u = check_range("u", (0.0, nu - 1.0) if u is None else u)
        v = check_range("v", (0.0, nv - 1.0) if v is None else v)
        super().__init__(*_zero_fns(), variables=DEFAULT_VARS,
                         derivatives="bilinear")
        self.hf = np.ascontiguousarray(z)
        self.hfp = np.array([u[0], u[1], v[0], v[1], 1.0, 1.0, 1.0], dtype=np.float64)
        self.default_domain = (u, v)

    def extremes(self, domain, n=EXTREME_NODES):
        """(u, v, w) of the highest node of each of the n rows whose highest is
        highest, and likewise the lowest, among the finite nodes of the grid inside
        ``domain`` ((ua, ub), (va, vb)): the grid's extremes and its tallest peaks
        and deepest pits (one pass over the grid, row by row: a 4097^2 DEM in tens
        of ms). A height field's heights are data, not a formula: a spike at one
        node is a value to show, not a pole to trim (view._robust_range); the
        picture's fit takes these in (view._fit). Empty where none is finite. Kept
        with the height field for its last domain (a flight's frames, each a plot of
        the same DEM: 19 ms a frame for a 4097^2 DEM), as its pyramid is."""
        key = (tuple(map(tuple, domain)), n)
        held = self.__dict__.get("_extremes_held")
        if held is not None and held[0] == key:
            return held[1]
        out = self._extremes(domain, n)
        for a in out:
            a.flags.writeable = False           # (shared by every caller)
        self.__dict__["_extremes_held"] = (key, out)
        return out

    def _extremes(self, domain, n):
        (ua, ub), (va, vb) = domain
        (u0, u1), (v0, v1) = self.default_domain
        nv, nu = self.hf.shape
        x = np.linspace(u0, u1, nu)
        y = np.linspace(v0, v1, nv)
        c0, c1 = np.searchsorted(x, ua, "left"), np.searchsorted(x, ub, "right")
        r0, r1 = np.searchsorted(y, va, "left"), np.searchsorted(y, vb, "right")
        z = self.hf[r0:r1, c0:c1]                  # (the nodes inside: a view)
        if z.size == 0:
            return np.zeros(0), np.zeros(0), np.zeros(0)
        us, vs, ws = [], [], []
        for sign in (1.0, -1.0):                    # the highest, then the lowest
            # each row's extreme, holes (NaN) left out: NaN only for a row of holes
            m = np.fmax.reduce(z, axis=1) if sign > 0 else np.fmin.reduce(z, axis=1)
            rows = np.nonzero(np.isfinite(m))[0]
            if rows.size > n:
                rows = rows[np.argpartition(-sign * m[rows], n)[:n]]
            sub = z[rows]
            j = np.nanargmax(sub, axis=1) if sign > 0 else np.nanargmin(sub, axis=1)
            us.append(x[c0 + j])
            vs.append(y[r0 + rows])
            ws.append(m[rows])
        return np.concatenate(us), np.concatenate(vs), np.concatenate(ws)

    def __reduce__(self):
        """Pickling: the heights, their extent and whether they were resampled."""
        u, v = self.default_domain
        return _heightfield, (self.hf, u, v, bool(self.resampled))

    def scaled(self, a, b, c):
        """The height field stretched by a along u, b along v and c along w (a new
        grid: heights times c over the extent times (a, b)). The last SCALED_KEPT
        are kept: the same stretch gives the same HeightField, whose fit grids
        (fit_grid) and hole map (view.hole_map) are then computed once, not at every
        draw of a 3-D Axes (its box is a stretch: a drag at 1920x1080 in perspective
        fitted its camera in 7 ms a frame, most of it these)."""
        key = (float(a), float(b), float(c))
        kept = self.__dict__.setdefault("_scaled", {})
        out = kept.get(key)
        if out is None:
            (ua, ub), (va, vb) = self.default_domain
            out = HeightField(self.hf * c, u=(ua * a, ub * a), v=(va * b, vb * b))
            source, c0 = getattr(self, "stretched_from", (self, 1.0))
            out.stretched_from = (source, c0 * c)  # (its level-of-detail pyramid: passes/area.py)
            if a == 1.0 and b == 1.0 and getattr(self, "dem", None) is not None:
                # heights exaggerated, the DEM's ground unchanged (terrain.lonlat)
                out.dem = dict(self.dem, vert_exag=self.dem["vert_exag"] * c)
            while len(kept) >= SCALED_KEPT:
                kept.pop(next(iter(kept)))
            kept[key] = out
        return out

    def __repr__(self):
        (a, b), (c, d) = self.default_domain
        return f"HeightField({self.hf.shape[0]}x{self.hf.shape[1]}, u=({a}, {b}), v=({c}, {d}))"


def _rebuilt(make, args, hfp):
    """A pickled Surface made again (Surface.__reduce__): ``make(*args)``, with the time
    and box scaling of ``hfp``."""
    s = make(*args)
    if not np.array_equal(s.hfp, hfp):
        s = copy.copy(s)
        s.hfp = np.array(hfp, dtype=np.float64)
    return s


def _heightfield(z, u, v, resampled):
    """A pickled HeightField made again (HeightField.__reduce__)."""
    out = HeightField(z, u=u, v=v)
    if resampled:
        out.resampled = True
    return out


def _ascending(name, rng):
    """(range ascending, whether it was given descending) of a HeightField's extent."""
    if rng is None:
        return None, False
    try:
        a, b = rng
        if float(b) < float(a):
            return (b, a), True
    except (TypeError, ValueError):
        pass                                  # (check_range says what is wrong)
    return rng, False


def check_range(name, rng):
    """A validated (low, high) float pair, or ValueError naming what to fix."""
    try:
        lo, hi = rng
        lo = float(lo)
        hi = float(hi)
    except (TypeError, ValueError):
        raise ValueError(f"range {name} must be a pair (low, high) of numbers, got {rng!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise ValueError(f"range {name} = ({lo}, {hi}) must be finite")
    if hi < lo:
        raise ValueError(f"range {name} = ({lo}, {hi}) is reversed: low must be below high")
    if hi == lo:
        raise ValueError(f"range {name} = ({lo}, {hi}) is empty: low must be below high")
    if not math.isfinite(hi - lo):
        raise ValueError(f"range {name} = ({lo}, {hi}) is too wide: high - low must be a finite "
                         "number (below 1.8e308)")
    return lo, hi


#: fit_grid keeps this many grids per Surface (domains, sizes, times)
FITS_KEPT = 8
#: HeightField.scaled keeps this many stretched copies
SCALED_KEPT = 2


def fit_grid(surface, domain, n):
    """f of ``surface`` (a Surface, or anything with ``evaluate(u, v)``) on an n x n
    grid over domain ((ua, ub), (va, vb)), NaN at holes, as a dict of read-only
    arrays "u", "v", "w" (rows follow v), where its user may keep what it derives
    from them alone. A Surface keeps the last FITS_KEPT: the same dict comes back for
    the same domain, n and time (view.build_view fits every picture's camera on it;
    the grid and its range took 0.7 of the 0.9 ms a render spent in Python)."""
    (ua, ub), (va, vb) = domain
    keep = isinstance(surface, Surface)
    if keep:
        key = (float(ua), float(ub), float(va), float(vb), int(n), surface.hfp.tobytes())
        fit = surface._fits.get(key)
        if fit is not None:
            return fit
    gu, gv = np.meshgrid(np.linspace(ua, ub, n), np.linspace(va, vb, n))
    gw = surface.evaluate(gu, gv)
    for a in (gu, gv, gw):
        a.flags.writeable = False
    fit = {"u": gu, "v": gv, "w": gw}
    if keep:
        # (only grids are let go: the dict holds the surface's GPU kernels and device
        # copies too, kernels/cuda.py, under string keys)
        grids = [k for k in surface._fits if isinstance(k, tuple)]
        for old in grids[:max(len(grids) - FITS_KEPT + 1, 0)]:
            del surface._fits[old]
        surface._fits[key] = fit
    return fit


def as_surface(expr, vars=None, time=None) -> Surface:
    """A Surface from a sympy expression, a string, a number, a callable f(u, v), or a
    Surface (returned as is). Free symbols must be the two variables (``vars``,
    default u and v) and, if ``time`` names it, a time parameter: then
    ``surface.at(t)`` gives the surface at time t without compiling again."""
    if isinstance(expr, Surface):
        return expr
    z = heights_array(expr)
    if z is not None:          # (MATLAB's surf(Z): heights over their rows' and columns'
        if time is not None:   # indices, u along a row, as HeightField's)
            raise ValueError("a time-varying surface must be an expression, not an array")
        return HeightField(z)
    names = _variable_names(vars)
    if callable(expr) and not _is_sympy(expr) and not isinstance(expr, str):
        if time is not None:
            raise ValueError("a time-varying surface must be an expression, not a callable")
        return _callable_surface(expr, names)
    if time is not None:
        time = str(time)
        if not time.isidentifier() or time in names:
            raise ValueError(f"the time {time!r} must be a name other than {names[0]} and {names[1]}")
        e = parse_expression(expr, names + (time,))
    else:
        e = parse_expression(expr, names)
    return _compiled_expression(e, names, time)


def _variable_names(vars):
    if vars is None:
        return DEFAULT_VARS
    try:
        names = tuple(str(x) for x in vars)
    except TypeError:
        raise ValueError(f"vars must name two variables, e.g. vars=('x', 'y'), got {vars!r}") from None
    if len(names) != 2 or names[0] == names[1] or not all(n.isidentifier() for n in names):
        raise ValueError(f"vars must name two different variables, e.g. vars=('x', 'y'), got {vars!r}")
    return names


def _is_sympy(obj):
    try:
        import sympy
    except ImportError:  # pragma: no cover - sympy is a dependency
        return False
    return isinstance(obj, sympy.Basic)


def sympy_expression(expr, names=()):
    """The sympy expression of a string / number / sympy object, with ``names`` read as
    plain sympy Symbols; its free symbols are not checked. ValueError says what to fix."""
    import sympy as sp

    if isinstance(expr, str):
        text = expr.strip()
        if not text:
            a, b = (tuple(names) + DEFAULT_VARS)[:2] if len(names) < 2 else names[:2]
            raise ValueError("the expression is empty: give a formula in "
                             f"{a} and {b}, e.g. '3*sin({a}*cos({b}))'")
        # floatcol's own parser: it never evaluates the text (sympify would eval it)
        e = parse_cached(text, tuple(names))
    elif isinstance(expr, numbers.Number) and not isinstance(expr, bool):
        e = constant_number(expr)
    elif isinstance(expr, sp.Basic):
        e = expr
    else:
        import reprlib
        what = (f"an array of shape {np.shape(expr)}" if array_like(expr) else
                f"{type(expr).__name__} {reprlib.repr(expr)}")
        raise ValueError(f"cannot draw {what}: pass a sympy expression, a string, a callable "
                         "f(u, v), a 2-D array of heights, a Surface or a HeightField")
    if not isinstance(e, sp.Expr) or isinstance(e, (sp.core.relational.Relational,
                                                     sp.logic.boolalg.BooleanFunction,
                                                     sp.logic.boolalg.BooleanAtom)):
        raise ValueError(f"{expr!r} is not a scalar expression: give a formula for the height w")
    return e


def free_names(expr):
    """Sorted names of the free symbols of an expression or string."""
    return sorted({s.name for s in sympy_expression(expr).free_symbols})


def parse_expression(expr, names=DEFAULT_VARS):
    """The sympy expression of a string / number / sympy object, in the variables
    ``names`` (as plain sympy Symbols). ValueError says what to fix."""
    import sympy as sp
    syms = {n: sp.Symbol(n) for n in names}
    e = sympy_expression(expr, names)
    by_name = {}
    unknown = []
    for s in sorted(e.free_symbols, key=str):
        if s.name in syms:
            by_name[s] = syms[s.name]
        else:
            unknown.append(s.name)
    if unknown:
        hint = f" (or pass vars={tuple(unknown)} to use them)" if len(unknown) == 2 else ""
        if "e" in unknown:
            hint += " (Euler's number is E or exp(1))"
        raise ValueError(
            f"unknown symbol{'s' if len(unknown) > 1 else ''} {', '.join(unknown)} in "
            f"{e}: the variables are {names[0]} and {names[1]}{hint}")
    e = _closed_forms(e.xreplace(by_name))
    if e.has(sp.re, sp.im, sp.arg, sp.conjugate, sp.I):
        # The variables are real. sympy, knowing nothing of them, writes
        # re(sqrt(x + I*y)) with re(x) and im(y), and im(log(x + I*y)) as arg(x + I*y),
        # none of which compiles: re-built over real symbols, they become x, 0 and
        # atan2(y, x).
        real = {s: sp.Dummy(s.name, real=True) for s in syms.values()}
        try:
            e = e.xreplace(real)
            e = e.xreplace({f: f.rewrite(sp.atan2) for f in e.atoms(sp.arg)})
            e = e.xreplace({d: s for s, d in real.items()})
        except (TypeError, ValueError, ArithmeticError):
            # re-evaluated over real variables, a part is undefined everywhere:
            # im(u) % ... is a modulus by 0, Max(nan, ...) has no value. A hole.
            e = sp.nan
    return e


# ---------------------------------------------------------------- compilation

#: Inner functions of the compiled surfaces: 1/0 is an infinity (a hole), never an
#: exception (which a cfunc could only swallow); FMA contraction as the kernels'
#: (kernels/_jit.py _MATH)
_njit = numba.njit(error_model="numpy", fastmath={"contract"})


def _numba_namespace():
    from .kernels import airy, gammas, integrals, special

    @numba.njit(cache=False)
    def dirac_delta(x, *args):
        return 0.0

    space = {"DiracDelta": dirac_delta}
    space.update(jn=special.sph_jn, yn=special.sph_yn)     # (sympy's: the spherical ones)
    for module, names in ((special, ("besselj", "bessely", "besseli", "besselk")),
                          (airy, ("airyai", "airybi", "airyaiprime", "airybiprime")),
                          (integrals, ("Si", "Ci", "Shi", "Chi", "Ei", "expint", "li", "Li",
                                       "fresnels", "fresnelc", "erfi")),
                          (gammas, ("beta", "polygamma", "erfinv", "erfcinv", "LambertW",
                                    "zeta",
                                    "dirichlet_eta", "elliptic_k", "elliptic_e",
                                    "elliptic_e1", "elliptic_f"))):
        space.update({n: getattr(module, n) for n in names})
    return space


def _orders():
    """{sympy function: (its order's argument, least, greatest, whether it must be whole,
    what it is)} for the functions of kernels/special.py, integrals.py and gammas.py
    whose order must be a number in a range (they compute no other)."""
    import sympy as sp
    from .kernels.special import MAX_ORDER
    whole = f"a whole number from -{MAX_ORDER} to {MAX_ORDER}"
    real = f"a number from -{MAX_ORDER} to {MAX_ORDER}"
    bessel = (0, -MAX_ORDER, MAX_ORDER, False, real)
    return {sp.besselj: bessel, sp.bessely: bessel, sp.besseli: bessel, sp.besselk: bessel,
            sp.jn: (0, -MAX_ORDER, MAX_ORDER, True, whole),
            sp.yn: (0, -MAX_ORDER, MAX_ORDER, True, whole),
            sp.expint: (0, -MAX_ORDER, MAX_ORDER, True, whole),
            sp.polygamma: (0, 0, MAX_ORDER, True, f"a whole number from 0 to {MAX_ORDER}"),
            sp.LambertW: (1, -1, 0, True, "0 or -1 (the real branches)")}


def _check_orders(e):
    """ValueError where a Bessel function's order is not a number from -MAX_ORDER to
    MAX_ORDER (a formula of the variables, say), E_n's, polygamma's or a spherical Bessel
    function's not a whole one in its range, or LambertW's branch not a real one (the
    kernels compute no other)."""
    import sympy as sp
    orders = _orders()
    for fn in e.atoms(*orders):
        at, lo, hi, whole, what = orders[fn.func]
        if at >= len(fn.args):
            continue                            # (LambertW(x): the branch 0)
        order = fn.args[at]
        ok = order.is_Integer if whole else (order.is_number and order.is_real is True)
        if not (ok and lo <= float(order) <= hi):
            name = type(fn).__name__
            kind = "branch" if fn.func is sp.LambertW else "order"
            example = ("LambertW(x, -1)" if fn.func is sp.LambertW else f"{name}(2, x)")
            raise ValueError(f"cannot draw f = {_short(e)}: {name}'s {kind} must be "
                             f"{what}, e.g. {example}, got {_short(order)}")


#: the largest degree of a spherical harmonic: its closed form is a polynomial in cos
#: theta whose coefficients grow with the degree (about 1e5 at 20; their cancellation
#: costs that many ulps)
MAX_HARMONIC = 20


def _closed_forms(e):
    """e with the Hankel functions as J +- i Y (hankel1, hankel2; the spherical hn1,
    hn2 as jn +- i yn), and sympy's spherical harmonics Ynm(n, m, theta, phi) and their
    real forms Znm in closed form (sin, cos and exp(i m phi) of the angles: sympy's
    expand_func), which the kernels compute; a ValueError where n and m are not whole
    numbers with |m| <= n <= MAX_HARMONIC. Both are complex: draw re, im or Abs."""
    import sympy as sp
    subs = {}
    for fn in e.atoms(sp.hankel1, sp.hankel2, sp.hn1, sp.hn2):
        j, y = (sp.besselj, sp.bessely) if fn.func in (sp.hankel1, sp.hankel2) else (sp.jn, sp.yn)
        sign = 1 if fn.func in (sp.hankel1, sp.hn1) else -1
        subs[fn] = j(*fn.args) + sign * sp.I * y(*fn.args)          # A&S 9.1.3, 9.1.4
    for fn in e.atoms(sp.Ynm, sp.Znm):
        n, m = fn.args[:2]
        if not (n.is_Integer and m.is_Integer and abs(int(m)) <= int(n) <= MAX_HARMONIC):
            name = type(fn).__name__
            raise ValueError(f"cannot draw f = {_short(e)}: {name}(n, m, theta, phi) needs "
                             f"whole numbers with |m| <= n <= {MAX_HARMONIC}, e.g. "
                             f"{name}(3, 1, theta, phi), got n = {_short(n)}, m = {_short(m)}")
        # expanded in real angles (a negative m's conjugate is then of sin and cos, not
        # of re and im of a complex angle), its constants in doubles (sqrt(21)/(8
        # sqrt(pi)); past int64 from n = 25)
        th, ph = sp.Dummy(real=True), sp.Dummy(real=True)
        closed = sp.expand_func(type(fn)(n, m, th, ph)).evalf(20)
        subs[fn] = closed.xreplace({th: fn.args[2], ph: fn.args[3]})
    return e.xreplace(subs) if subs else e


def kernel_closed_form(call):
    """A special function called with numbers (a sympy node built unevaluated) as the
    kernels compute it: _closed_forms' (Ynm, Znm, the Hankel functions), under their
    rules (_check_orders: a Bessel function's order from -MAX_ORDER to MAX_ORDER, ...).
    ValueError naming the function where they refuse its arguments."""
    try:
        e = _closed_forms(call)
        _check_orders(e)
    except ValueError as exc:
        raise ValueError(str(exc).split(": ", 1)[-1]) from None      # (not "cannot draw f")
    return e


def kernel_double(e):
    """The double the kernels compute for a constant real expression e
    (kernel_closed_form's, of real numbers): NaN where it is not finite in Python's
    math and Numba gives an infinity or NaN (gamma(1e300), a pole)."""
    try:
        return float(_lambdify_real((), e)())
    except (OverflowError, ZeroDivisionError, ValueError, TypeError):
        return math.nan


@functools.lru_cache(maxsize=256)
def _compiled_expression(e, names, time=None):
    """Surface for expression e (memoized on the expression and variable names)."""
    import sympy as sp
    su, sv = (sp.Symbol(n) for n in names)
    st = sp.Symbol(time) if time is not None else sp.Dummy("t")
    if not e.free_symbols:
        # a constant: its value in doubles; one that is not a real number (I, oo, zoo,
        # nan) is a hole everywhere
        from .expression import constant_value
        value = constant_value(e)
        e = sp.Float(value) if math.isfinite(value) else sp.nan
    f_py, f = _compile_scalar(e, su, sv, st)
    fg = None
    how = "symbolic"
    try:
        derivs = [sp.diff(e, su), sp.diff(e, sv)]
    except (TypeError, ValueError, ArithmeticError, RecursionError):
        derivs = [sp.Derivative(e, su), sp.Derivative(e, sv)]     # central differences
    if not any(d.has(sp.Derivative, sp.Subs) for d in derivs):
        try:
            fg = _compile_fused(e, derivs, su, sv, st)
        except ValueError:
            fg = None
    if fg is None:
        how = "central differences"
        fg = _central_difference(f_py)
    batch_source = None
    if how == "symbolic" and _vectorises(e, derivs):
        batch_source = (e, tuple(derivs), su, sv, st)
    return Surface(f, fg, expr=e, variables=names, derivatives=how, time=time,
                   batch_source=batch_source)


def _is_complex(e):
    """Does e need complex arithmetic: a complex constant, or a real or imaginary part,
    argument or conjugate that sympy could not take away over the real variables
    (re(besselj(1/2, u)): J of a fractional order is complex for u < 0)?"""
    import sympy as sp
    return (bool(e.has(sp.I, sp.re, sp.im, sp.arg, sp.conjugate))
            or any(n.is_real is False for n in e.atoms(sp.Number)))


def _compile_error(e, exc):
    """A ValueError that says what the user can change, never Numba's or sympy's
    internals (those go to the debug log)."""
    import re
    log.debug("cannot compile %s: %s", e, exc)
    text = _short(e)
    missing = re.search(r"name '(\w+)' is not defined", str(exc))
    if missing:
        why = f"the renderer has no compiled form of {missing.group(1)}"
    elif _is_complex(e):
        why = ("a part of it is complex where the renderer needs a real number (floor, "
               "atan2, Min, Max, a comparison, ... of a complex value)")
    else:
        why = "the renderer cannot compile one of its functions for real numbers"
    return ValueError(f"cannot draw f = {text}: {why}; rewrite that part")


def _short(e):
    import sympy as sp
    text = sp.sstr(e, full_prec=False)
    return text if len(text) <= 80 else text[:77] + "..."


def _vectorises(e, derivs):
    """Do f and its partials use only what the batch evaluator compiles to SIMD code:
    arithmetic, whole and half powers, abs, and the functions of
    kernels/vmath.VECTOR_FUNCTIONS? (Anything else is a call of libm, which keeps the
    loop scalar: no faster than the scalar fg, so not worth compiling.)"""
    import sympy as sp
    from .kernels.vmath import VECTOR_FUNCTIONS
    allowed = {getattr(sp, name) for name in VECTOR_FUNCTIONS} | {sp.Abs}
    for x in (e, *derivs):
        if _is_complex(x):
            return False
        for fn in x.atoms(sp.Function):
            if fn.func not in allowed:
                return False
        for p in x.atoms(sp.Pow):
            if not (p.exp.is_Integer or p.exp in (sp.S.Half, -sp.S.Half)):
                return False
    return True


def _compile_batch(e, derivs, su, sv, st):
    """The batch evaluator (kernels/_jit.py BATCH_SIG) of f and its partials: sympy's
    lambdify with vmath's sin, cos and exp, inlined into a loop over the points that
    LLVM vectorises. None if it does not compile."""
    from .kernels.vmath import VECTOR_FUNCTIONS
    try:
        g = numba.njit(error_model="numpy", inline="always", fastmath={"contract"})(
            _lambdify_real((su, sv, st), (e, *derivs), cse=True, functions=VECTOR_FUNCTIONS))

        def batch(u, v, t, out, n):
            for i in range(n):
                w, wu, wv = g(u[i], v[i], t)
                out[i] = w
                out[n + i] = wu
                out[2 * n + i] = wv
        log.debug("compiling the batch evaluator of %s", e)
        return compile_batch_fn(batch)
    except Exception as exc:               # pragma: no cover - the scalar fg remains
        log.debug("no batch evaluator for %s: %s", e, exc)
        return None


@functools.lru_cache(maxsize=1)
def _no_batch():
    """The stand-in batch evaluator: NaN everywhere, which sends every point to fg."""
    def none(u, v, t, out, n):
        for i in range(3 * n):
            out[i] = math.nan
    return compile_batch_fn(none)


def _lambdify_real(args, e, cse=False, functions=None, modules="math"):
    """sympy's lambdify for Numba, with a power printed so that it cannot raise.

    In Numba, ``0.0 ** -2`` raises ZeroDivisionError even in numpy's error model
    (which makes 1 / 0.0 an infinity), and a compiled function that may raise needs
    a try block, which doubles its compile time (about 200 ms instead of 35 ms for
    sin(u) cos(v)). So x ** -n is printed 1 / x ** n: at a pole, an infinity, which
    the kernels read as a hole. Nothing else in real math raises there (log(0),
    sqrt(-1), 1 % 0.0 give infinities and NaN)."""
    import sympy as sp
    from sympy.printing.pycode import PythonCodePrinter

    class _Printer(PythonCodePrinter):
        def _print_Pow(self, expr, rational=False):
            if expr.exp.is_Integer and expr.exp < -1:
                return "(1/(%s))" % self._print(sp.Pow(expr.base, -expr.exp, evaluate=False))
            if not expr.exp.is_Number:
                # an exponent that is a formula: a double, so that 0.0 ** -2 is an
                # infinity; one of whole numbers (u**floor(v), where floor is an int)
                # raised a ZeroDivisionError at u = 0 from inside the kernels
                return "%s**float(%s)" % (self.parenthesize(expr.base, 61),
                                          self._print(expr.exp))
            return super()._print_Pow(expr, rational=rational)

        def _print_Piecewise(self, expr):
            # where no condition holds, NaN (a hole): sympy's printer gives None there
            # (Piecewise((u, u > 0)), factorial2's rewrite), which a compiled function
            # returning a double raised as a TypeError at every such point ("Exception
            # ignored" printed from inside the kernels, the value undefined)
            if expr.args[-1].cond is not sp.true:
                expr = sp.Piecewise(*expr.args, (sp.nan, True), evaluate=False)
            return super()._print_Piecewise(expr)

        # the special functions' compiled forms (kernels/gammas.py) take every argument
        def _print_factorial(self, expr):
            return "gamma(%s + 1)" % self._print(expr.args[0])

        def _print_beta(self, expr):
            # (sympy prints a quotient of gammas: inf/inf, a hole, past a + b = 171)
            a = self._print(expr.args[0])
            b = self._print(expr.args[1]) if len(expr.args) > 1 else a
            return "beta(%s, %s)" % (a, b)

        def _print_zeta(self, expr):
            a = self._print(expr.args[1]) if len(expr.args) > 1 else "1.0"
            return "zeta(%s, %s)" % (self._print(expr.args[0]), a)

        def _print_LambertW(self, expr):
            k = self._print(expr.args[1]) if len(expr.args) > 1 else "0"
            return "LambertW(%s, float(%s))" % (self._print(expr.args[0]), k)

        def _print_fresnels(self, expr):             # (sympy's printer refuses these)
            return self._print_Function(expr)

        _print_fresnelc = _print_fresnels

        def _print_elliptic_e(self, expr):
            if len(expr.args) == 1:
                return "elliptic_e1(%s)" % self._print(expr.args[0])
            return "elliptic_e(%s, %s)" % tuple(self._print(a) for a in expr.args[:2])

    namespace = _numba_namespace()
    if functions:
        namespace.update(functions)
    printer = _Printer({"fully_qualified_modules": False, "inline": True,
                        "allow_unknown_functions": True,
                        "user_functions": {k: k for k in namespace}})
    return sp.lambdify(args, e, modules=[namespace, modules], printer=printer, cse=cse)


def _complex_namespace():
    """What a complex expression's code calls: cmath's functions (sympy's own cmath
    printer recursed without end on a Float), and the parts of a complex number."""
    import cmath

    @numba.njit(cache=False)
    def re(z):
        return (z + 0j).real

    @numba.njit(cache=False)
    def im(z):
        return (z + 0j).imag

    @numba.njit(cache=False)
    def arg(z):
        return cmath.phase(z + 0j)

    @numba.njit(cache=False)
    def conjugate(z):
        return (z + 0j).conjugate()

    names = ["sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "asinh",
             "acosh", "atanh", "exp", "log", "sqrt", "log10"]
    space = {n: getattr(cmath, n) for n in names}
    space.update(re=re, im=im, arg=arg, conjugate=conjugate)
    return space


def _lambdify_complex(args, e, cse=False):
    """lambdify of an expression with complex constants: cmath's functions for
    math's (a value that is not real is a hole, _real_part)."""
    return _lambdify_real(args, e, cse=cse, functions=_complex_namespace(), modules="cmath")


def _compile_scalar(e, su, sv, st):
    """(njit-able python function that never raises, cfunc) for a scalar sympy
    expression."""
    _check_orders(e)
    try:
        if _is_complex(e):
            g = _njit(_lambdify_complex((su, sv, st), e))

            def py(u, v, t):
                try:
                    return _real_part(g(u, v, t) + 0j)
                except Exception:        # e.g. complex division by zero: a hole
                    return math.nan
        else:
            py = _lambdify_real((su, sv, st), e)
        log.debug("compiling %s", e)
        return py, compile_surface_fn(py)
    except Exception as exc:
        raise _compile_error(e, exc) from None


def _compile_fused(e, derivs, su, sv, st):
    """The fused cfunc w = fg(u, v, t, p), p <- (f_u, f_v): f and both partials in
    one function, their common subexpressions computed once (sympy's cse)."""
    triple = (e, derivs[0], derivs[1])
    try:
        if any(_is_complex(x) for x in triple):
            g = _njit(_lambdify_complex((su, sv, st), triple, cse=True))

            def fused(u, v, t, p):
                try:
                    w, wu, wv = g(u, v, t)
                except Exception:
                    return math.nan
                p[0] = _real_part(wu + 0j)
                p[1] = _real_part(wv + 0j)
                return _real_part(w + 0j)
        else:
            fused = _fused_function(_lambdify_real((su, sv, st), triple, cse=True))
        return compile_grad_fn(fused)
    except Exception as exc:
        raise _compile_error(e, exc) from None


def _fused_function(g):
    """The fused Python function (u, v, t, p) -> w, p <- (f_u, f_v), from lambdify's
    g (u, v, t) -> (w, f_u, f_v): g's own source, its returned triple written to p,
    so that Numba compiles one function (half the time of compiling g and a wrapper
    that calls it). Falls back to that wrapper where g's source is not as expected."""
    import ast
    import inspect
    try:
        tree = ast.parse(inspect.getsource(g))
        fn = tree.body[0]
        ret = fn.body[-1]
        names = {a.arg for a in fn.args.args}
        if (isinstance(fn, ast.FunctionDef) and isinstance(ret, ast.Return)
                and isinstance(ret.value, ast.Tuple) and len(ret.value.elts) == 3
                and len(names) == 3 and "_fc_partials" not in names):
            w, wu, wv = ret.value.elts
            out = ast.Name("_fc_partials", ast.Load())
            fn.name = "_fc_fused"
            fn.args.args.append(ast.arg("_fc_partials"))
            fn.body[-1:] = [
                ast.Assign([ast.Subscript(out, ast.Constant(0), ast.Store())], wu),
                ast.Assign([ast.Subscript(out, ast.Constant(1), ast.Store())], wv),
                ast.Return(w)]
            ast.fix_missing_locations(tree)
            namespace = dict(g.__globals__)
            exec(compile(tree, "<floatcol fused>", "exec"), namespace)
            return namespace["_fc_fused"]
    except (OSError, TypeError, SyntaxError, IndexError):   # pragma: no cover
        pass
    gj = _njit(g)                                             # pragma: no cover

    def fused(u, v, t, p):                                    # pragma: no cover
        w, wu, wv = gj(u, v, t)
        p[0] = wu
        p[1] = wv
        return w
    return fused


@_njit
def _real_part(z):
    """The real part of a value that is real up to rounding; NaN (a hole) if not."""
    if abs(z.imag) <= 1e-12 * (1.0 + abs(z.real)):
        return z.real
    return math.nan


def _central_difference(py):
    """The fused function by central differences of f (when sympy cannot
    differentiate the expression, and for plain callables; py never raises)."""
    fj = _njit(py)

    def fused(u, v, t, p):
        hu = 6e-6 * max(1.0, abs(u))
        hv = 6e-6 * max(1.0, abs(v))
        p[0] = (fj(u + hu, v, t) - fj(u - hu, v, t)) / (2.0 * hu)
        p[1] = (fj(u, v + hv, t) - fj(u, v - hv, t)) / (2.0 * hv)
        return fj(u, v, t)
    return compile_grad_fn(fused)


def _callable_surface(fn, names):
    import inspect

    py = getattr(fn, "py_func", None) or getattr(fn, "_pyfunc", None) or fn
    if isinstance(fn, np.ufunc):         # np.hypot, np.arctan2, ...: called as Numba can
        if fn.nin != 2 or fn.nout != 1:
            raise ValueError(f"the numpy function {fn.__name__!r} must take two arguments "
                             f"(u, v) and give one value; it takes {fn.nin}")

        def py(u, v):
            return fn(u, v)
        py.__name__ = fn.__name__
    try:
        params = inspect.signature(py).parameters.values()
    except (TypeError, ValueError):      # builtins may have no signature: let Numba judge
        params = ()
    required = [p for p in params if p.default is p.empty
                and p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    if len(required) > 2:
        raise ValueError(f"the callable {getattr(py, '__name__', py)!r} must take two arguments (u, v)")
    try:
        fj = _njit(py)

        def py3(u, v, t):
            try:
                return fj(u, v)
            except Exception:            # e.g. 1/0 in the user's code: a hole
                return math.nan
        f = compile_surface_fn(py3)
    except Exception as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise ValueError(
            f"cannot compile the callable {getattr(py, '__name__', py)!r} with Numba ({first}); "
            "write it with scalar math (the math module) or pass a sympy expression") from None
    out = Surface(f, _central_difference(py3), variables=names, derivatives="central differences")
    out.source = fn                     # (what a pickled copy is made from again)
    return out


@functools.lru_cache(maxsize=1)
def _zero_fns():
    """f = 0 and its fused gradient (placeholders: a height field reads its grid)."""
    def zero(u, v, t):
        return 0.0

    def zero_grad(u, v, t, p):
        p[0] = 0.0
        p[1] = 0.0
        return 0.0
    return compile_surface_fn(zero), compile_grad_fn(zero_grad)

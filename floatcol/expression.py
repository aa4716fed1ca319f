"""Formulas from untrusted text, parsed without ever evaluating them.

sympy's ``sympify`` and ``parse_expr`` call Python's ``eval``: a string such as
``"__import__('os').system(...)"`` runs. This module reads a formula with its own
tokenizer and Python's ``ast`` (mode "eval", which only parses) and builds the sympy
expression node by node from a whitelist: numbers, names, the constants of
:data:`CONSTANTS`, the operators ``+ - * / // % ** ^``, comparisons and ``and``/``or``
(for ``Piecewise`` and ``a if cond else b``), and calls of the functions of
:data:`FUNCTIONS` by name. Anything else is a ValueError that names the construct and
points at it.

The input is bounded (:data:`MAX_LENGTH` characters, :data:`MAX_DEPTH` levels), and so
is every number: a constant part of the formula (no variable in it) is kept exact only
while it is a small rational (``1/2``, ``3**4``); anything else is folded to a double
at once (``2**10**10`` is ``oo``, ``1e999`` is ``oo``), so that sympy never starts an
exact computation that would not end. A complex constant stays complex: the surface is
a hole where its value is not real.
"""
from __future__ import annotations

import ast
import functools
import math
import re

#: longest formula accepted, in characters
MAX_LENGTH = 2000
#: deepest nesting of parentheses
MAX_DEPTH = 100
#: deepest nesting of the formula's tree (a sum of 150 terms is 150 deep)
MAX_TREE_DEPTH = 200
#: an exact rational constant keeps at most this many bits in numerator and denominator
#: (an int64 of the compiled code)
MAX_BITS = 62


def _functions():
    import sympy as sp
    names = ["sin", "cos", "tan", "cot", "sec", "csc", "asin", "acos", "atan", "acot",
             "asec", "acsc", "atan2", "sinh", "cosh", "tanh", "coth", "sech", "csch",
             "asinh", "acosh", "atanh", "acoth", "asech", "acsch", "exp", "log", "sqrt",
             "cbrt", "root", "Abs", "sign", "floor", "ceiling", "frac", "Min", "Max", "re",
             "im", "arg", "conjugate", "erf", "erfc", "gamma", "Heaviside", "DiracDelta",
             "sinc", "Mod", "Piecewise"]
    table = {n: getattr(sp, n) for n in names}
    table.update(ln=sp.log, abs=sp.Abs, ceil=sp.ceiling, min=sp.Min, max=sp.Max,
                 arcsin=sp.asin, arccos=sp.acos, arctan=sp.atan, arctan2=sp.atan2,
                 arcsinh=sp.asinh, arccosh=sp.acosh, arctanh=sp.atanh,
                 # numpy's and the math module's names
                 mod=sp.Mod, heaviside=sp.Heaviside, fabs=sp.Abs, absolute=sp.Abs,
                 log10=_log_base(sp, 10), log2=_log_base(sp, 2), hypot=_hypot(sp),
                 where=sp.Piecewise)
    table.update({n: getattr(sp, f) for n, f in _BESSEL.items()})
    table.update({n: _bessel(getattr(sp, f), k) for n, (f, k) in _BESSEL_OF_ORDER.items()})
    table.update({n: getattr(sp, f) for n, f in _SPECIAL.items()})
    table.update(expn=sp.expint, ellipkinc=sp.elliptic_f, ellipeinc=sp.elliptic_e,
                 spherical_jn=sp.jn, spherical_yn=sp.yn, sph_harm_y=sp.Ynm,
                 hankel1=sp.hankel1, hankel2=sp.hankel2)
    return table


#: Bessel functions of a whole order, (order, x), by sympy's names and scipy's
_BESSEL = {"besselj": "besselj", "jv": "besselj", "jn": "besselj",
           "bessely": "bessely", "yv": "bessely", "yn": "bessely",
           "besseli": "besseli", "iv": "besseli", "besselk": "besselk", "kv": "besselk",
           "kn": "besselk"}
#: ... and of one order, (x), by scipy's and numpy's names
_BESSEL_OF_ORDER = {f"{c}{k}": (f, k) for c, f in (("j", "besselj"), ("y", "bessely"),
                                                    ("i", "besseli"), ("k", "besselk"))
                    for k in (0, 1)}


#: other special functions (kernels/airy.py, integrals.py, gammas.py), by sympy's names
#: and scipy's (expi, exp1, psi, gammaln, lambertw, ellipk, ellipe; expn, ellipkinc,
#: ellipeinc, spherical_jn, spherical_yn and sph_harm_y take the same arguments as
#: expint, elliptic_f, elliptic_e and sympy's jn, yn and Ynm; a bare jn is scipy's, J_n)
_SPECIAL = {**{n: n for n in (
    "airyai", "airybi", "airyaiprime", "airybiprime", "Si", "Ci", "Shi", "Chi", "Ei", "E1",
    "expint", "li", "Li", "erfi", "erfinv", "erfcinv", "fresnels", "fresnelc",
    "polygamma", "digamma", "trigamma", "factorial", "loggamma", "beta", "LambertW",
    "zeta", "dirichlet_eta", "elliptic_k", "elliptic_e", "elliptic_f", "Ynm", "Znm")},
    "expi": "Ei", "exp1": "E1", "psi": "digamma", "gammaln": "loggamma",
    "lgamma": "loggamma", "lambertw": "LambertW", "ellipk": "elliptic_k",
    "ellipe": "elliptic_e"}


def _bessel(fn, order):
    """j0, y1, i0, k1, ... (scipy's and numpy's names): fn of that order."""
    def bessel(x, evaluate=True):
        return fn(order, x)
    return bessel


def _log_base(sp, base):
    """log10, log2: sympy's log to that base (log(x) / log(base))."""
    def log_base(x, evaluate=True):
        return sp.log(x, base)
    return log_base


def _hypot(sp):
    def hypot(x, y, evaluate=True):
        return sp.sqrt(x ** 2 + y ** 2)
    return hypot


def _constants():
    import sympy as sp
    return {"pi": sp.pi, "E": sp.E, "I": sp.I, "oo": sp.oo, "inf": sp.oo, "zoo": sp.zoo,
            "nan": sp.nan, "EulerGamma": sp.EulerGamma, "GoldenRatio": sp.GoldenRatio,
            "True": sp.true, "False": sp.false}


#: the functions a formula may call (lazily filled: sympy is imported on first parse)
FUNCTIONS: dict = {}
#: the names that stand for constants
CONSTANTS: dict = {}

#: how many arguments each function takes, where sympy would accept other counts or
#: fail with an internal message
_ARITY = {"atan2": (2, 2), "arctan2": (2, 2), "log": (1, 2), "ln": (1, 2), "root": (2, 2),
          "Mod": (2, 2), "Min": (1, 32), "Max": (1, 32), "min": (1, 32), "max": (1, 32),
          "Piecewise": (1, 32), "DiracDelta": (1, 1), "Heaviside": (1, 1), "mod": (2, 2),
          "heaviside": (1, 2), "hypot": (2, 2), "where": (3, 3),
          **dict.fromkeys(_BESSEL, (2, 2)),
          **dict.fromkeys(("expint", "expn", "polygamma", "beta", "elliptic_f", "ellipkinc",
                           "ellipeinc", "spherical_jn", "spherical_yn", "hankel1", "hankel2"),
                          (2, 2)),
          **dict.fromkeys(("LambertW", "lambertw", "zeta", "elliptic_e"), (1, 2)),
          **dict.fromkeys(("Ynm", "Znm", "sph_harm_y"), (4, 4))}

#: functions whose value is undefined (a hole), not an error, where sympy refuses
#: the arguments (NaN, a complex number, a zero modulus)
_HOLE_WHEN_UNDEFINED = {"Min", "Max", "min", "max", "Mod", "mod"}

_TOKEN = re.compile(r"""
    (?P<space>\s+)
  | (?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?[jJ]?)
  | (?P<name>(?:(?:np|numpy|math|cmath|sp|sympy)\.)?[A-Za-z_][A-Za-z_0-9]*)
  | (?P<op>\*\*|//|<=|>=|==|!=|[-+*/%^()<>,&|~])
""", re.VERBOSE)

_KEYWORDS = {"and", "or", "not", "if", "else"}
#: numpy's and math's constants by the names they have there (np.e, math.inf)
_PREFIXED = {"e": "E", "euler_gamma": "EulerGamma", "Inf": "inf", "NaN": "nan", "NAN": "nan",
             "PINF": "inf"}


def _tables():
    if not FUNCTIONS:
        FUNCTIONS.update(_functions())
        CONSTANTS.update(_constants())


class _Reject(Exception):
    """A construct that is not allowed, at an offset of the Python text."""

    def __init__(self, what, offset):
        super().__init__(what)
        self.what = what
        self.offset = offset


def _tokens(text):
    """(kind, token, offset in text) for each token, or ValueError at a bad character."""
    out = []
    pos = 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:
            ch = text[pos]
            what = f"the character {ch!r}" if ch.isprintable() else f"the character {ascii(ch)}"
            raise _Reject(f"{what} is not allowed", ("text", pos))
        kind = m.lastgroup
        if kind != "space":
            out.append((kind, m.group(), pos))
        pos = m.end()
    return out


def _python_text(text, names=()):
    """The formula as Python text: ``^`` is ``**``, and a product written without ``*``
    (``2u``, ``2 sin(u)``, ``u v``, ``(u+1)(v-1)``, ``2(u+1)``, ``u(v+1)``) gets its
    ``*``. Returns (python text, list mapping each python offset to the formula's)."""
    _tables()
    pieces, where = [], []
    prev = None
    for kind, tok, pos in _tokens(text):
        if tok == "^":
            tok = "**"
        if kind == "name" and "." in tok:
            # numpy's, math's or sympy's name (np.sin, math.pi, np.e): the name alone,
            # its constants as sympy's; never an attribute looked up
            prefix, tok = tok.split(".")
            pos += len(prefix) + 1
            tok = _PREFIXED.get(tok, tok)
        if prev is not None and _implicit_product(prev, kind, tok, names):
            pieces.append("*")
            where.append(pos)
        pieces.append(tok)
        where.extend(min(pos + i, len(text)) for i in range(len(tok)))
        pieces.append(" ")
        where.append(pos + len(tok))
        prev = (kind, tok)
    where.append(len(text))
    return "".join(pieces), where


def _implicit_product(prev, kind, tok, names):
    pkind, ptok = prev
    left = pkind == "number" or ptok == ")" or (pkind == "name" and ptok not in _KEYWORDS)
    right = kind in ("number", "name") or tok == "("
    if not (left and right) or tok in _KEYWORDS or (kind == "number" and pkind == "number"):
        return False
    if tok == "(" and pkind == "name":
        # a call, unless the name is a variable or a constant: u(v+1) is u*(v+1), and
        # foo(u) is refused as an unknown function
        return ptok in names or ptok in CONSTANTS
    return True


def parse(text, names=()):
    """The sympy expression of the formula ``text`` (a str), in the variables
    ``names`` (plain sympy Symbols; other names become Symbols too, for the caller to
    judge). Never evaluates the text. ValueError says what is wrong and where."""
    if not isinstance(text, str):
        raise ValueError(f"a formula must be a string, got {type(text).__name__}")
    if len(text) > MAX_LENGTH:
        raise ValueError(f"the expression is {len(text)} characters long: at most {MAX_LENGTH}")
    text = text.strip()
    try:
        py, where = _python_text(text, tuple(names))
        depth = 0
        for ch in py:
            depth += (ch == "(") - (ch == ")")
            if depth > MAX_DEPTH:
                raise _Reject(f"parentheses nest more than {MAX_DEPTH} deep", ("py", py.index(ch)))
        tree = _parse_python(py, text, where)
        return _Builder(names, py).build(tree)
    except _Reject as rej:
        kind, off = rej.offset
        pos = off if kind == "text" else where[min(max(off, 0), len(where) - 1)]
        pos = min(max(pos, 0), len(text))
        raise ValueError(f"{rej.what} in expression {text!r} at character {pos + 1}: "
                         f"{text[:pos]}<here>{text[pos:]}") from None
    except (RecursionError, MemoryError):
        raise ValueError(f"the expression {text!r} is too complicated: simplify it") from None


def _parse_python(py, text, where):
    try:
        return ast.parse(py, mode="eval")
    except SyntaxError as se:
        off = (se.offset or 0) - 1
        if off < 0 or off >= len(py.rstrip()):
            off = len(py)                       # Python blames the end: the formula is incomplete
        pos = where[min(off, len(where) - 1)] if off < len(py) else len(text)
        pos = min(max(pos, 0), len(text))
        msg = se.msg if se.msg and "invalid syntax" not in se.msg else "invalid syntax"
        raise ValueError(f"could not parse expression {text!r} ({msg}) at character {pos + 1}: "
                         f"{text[:pos]}<here>{text[pos:]}") from None
    except (ValueError, MemoryError, RecursionError, OverflowError) as exc:
        raise ValueError(f"could not parse expression {text!r}: "
                         f"{str(exc).splitlines()[0] if str(exc) else 'too complicated'}") from None


_OPS = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.Pow: "**",
        ast.FloorDiv: "//", ast.Mod: "%", ast.BitAnd: "&", ast.BitOr: "|"}

_REFUSED = {
    ast.Attribute: "attribute access (.name)", ast.Subscript: "indexing ([...])",
    ast.Lambda: "a lambda", ast.ListComp: "a comprehension", ast.SetComp: "a comprehension",
    ast.DictComp: "a comprehension", ast.GeneratorExp: "a comprehension",
    ast.List: "a list", ast.Dict: "a dict", ast.Set: "a set", ast.JoinedStr: "an f-string",
    ast.Starred: "a starred argument (*x)", ast.NamedExpr: "an assignment (:=)",
    ast.Await: "await", ast.Yield: "yield", ast.YieldFrom: "yield", ast.Slice: "a slice",
}


class _Builder:
    def __init__(self, names, py):
        import sympy as sp
        self.sp = sp
        self.names = {n: sp.Symbol(n) for n in names}
        self.py = py
        self.depth = 0

    def build(self, tree):
        return self.node(tree.body)

    def reject(self, what, node):
        raise _Reject(f"{what} is not allowed", ("py", getattr(node, "col_offset", 0)))

    def node(self, node):
        self.depth += 1
        if self.depth > MAX_TREE_DEPTH:
            raise _Reject(f"the expression nests more than {MAX_TREE_DEPTH} levels deep",
                          ("py", getattr(node, "col_offset", 0)))
        try:
            method = getattr(self, "_" + type(node).__name__, None)
            if method is None:
                self.reject(_REFUSED.get(type(node), type(node).__name__.lower()), node)
            return method(node)
        except (TypeError, ValueError, ArithmeticError, AttributeError) as exc:
            # sympy refusing to form a node, e.g. a comparison with a complex number
            raise _Reject(f"this part cannot be formed ({_first_line(exc)})",
                          ("py", getattr(node, "col_offset", 0))) from None
        finally:
            self.depth -= 1

    # -- leaves
    def _Constant(self, node):
        sp = self.sp
        value = node.value
        if isinstance(value, bool):
            return sp.true if value else sp.false
        if isinstance(value, int):
            if value.bit_length() <= MAX_BITS:
                return sp.Integer(value)
            return _number(float("inf"))
        if isinstance(value, float):
            return _number(value)
        if isinstance(value, complex):
            return _number(value)
        what = "a string" if isinstance(value, (str, bytes)) else repr(value)
        self.reject(what, node)

    def _Name(self, node):
        name = node.id
        if name in self.names:
            return self.names[name]
        if name in CONSTANTS:
            return CONSTANTS[name]
        if name in FUNCTIONS:
            raise _Reject(f"the function {name} must be called, e.g. {name}(u)",
                          ("py", node.col_offset))
        if name.startswith("_"):
            self.reject(f"the name {name}", node)
        return self.sp.Symbol(name)

    # -- operators
    def _UnaryOp(self, node):
        sp = self.sp
        x = self.node(node.operand)
        if isinstance(node.op, ast.USub):
            return _fold(lambda: -x, self.numeric(x))
        if isinstance(node.op, ast.UAdd):
            return x
        if isinstance(node.op, (ast.Not, ast.Invert)):
            return sp.Not(self.boolean(x, node))
        self.reject("this operator", node)

    def _BinOp(self, node):
        sp = self.sp
        op = _OPS.get(type(node.op))
        if op is None:
            self.reject(f"the operator {type(node.op).__name__}", node)
        a, b = self.node(node.left), self.node(node.right)
        if op in ("&", "|"):
            a, b = self.boolean(a, node.left), self.boolean(b, node.right)
            return sp.And(a, b) if op == "&" else sp.Or(a, b)
        self.scalar(a, node.left)
        self.scalar(b, node.right)
        numeric = self.numeric(a) and self.numeric(b)
        if op == "**":
            if numeric and not _exact_power_is_small(a, b):
                return _power(a, b)
            return _fold(lambda: sp.Pow(a, b), numeric)
        if op == "%":
            try:
                return _fold(lambda: sp.Mod(a, b), numeric)
            except (TypeError, ValueError, ArithmeticError):
                return sp.nan                   # u % 0: undefined, a hole
        build = {"+": lambda: sp.Add(a, b), "-": lambda: sp.Add(a, -b),
                 "*": lambda: sp.Mul(a, b), "/": lambda: sp.Mul(a, sp.Pow(b, -1)),
                 "//": lambda: sp.floor(sp.Mul(a, sp.Pow(b, -1))),
                 "%": lambda: sp.Mod(a, b)}[op]
        return _fold(build, numeric)

    def _Compare(self, node):
        sp = self.sp
        rel = {ast.Lt: sp.Lt, ast.LtE: sp.Le, ast.Gt: sp.Gt, ast.GtE: sp.Ge,
               ast.Eq: sp.Eq, ast.NotEq: sp.Ne}
        left = self.node(node.left)
        self.scalar(left, node.left)
        parts = []
        for op, right_node in zip(node.ops, node.comparators):
            cls = rel.get(type(op))
            if cls is None:
                self.reject(f"the comparison {type(op).__name__}", node)
            right = self.node(right_node)
            self.scalar(right, right_node)
            parts.append(cls(left, right))
            left = right
        return sp.And(*parts)

    def _BoolOp(self, node):
        sp = self.sp
        args = [self.boolean(self.node(v), v) for v in node.values]
        return sp.And(*args) if isinstance(node.op, ast.And) else sp.Or(*args)

    def _IfExp(self, node):
        sp = self.sp
        cond = self.boolean(self.node(node.test), node.test)
        a, b = self.node(node.body), self.node(node.orelse)
        self.scalar(a, node.body)
        self.scalar(b, node.orelse)
        return sp.Piecewise((a, cond), (b, True))

    def _Tuple(self, node):
        self.reject("a tuple (outside Piecewise)", node)

    # -- calls
    def _Call(self, node):
        sp = self.sp
        if not isinstance(node.func, ast.Name):
            self.reject(_REFUSED.get(type(node.func), "calling this"), node.func)
        name = node.func.id
        fn = FUNCTIONS.get(name)
        if fn is None:
            if name in self.names or name in CONSTANTS:
                raise _Reject(f"{name} is not a function (write {name}*(...) for a product)",
                              ("py", node.col_offset))
            raise _Reject(f"unknown function {name}", ("py", node.col_offset))
        if node.keywords:
            self.reject("a keyword argument", node.keywords[0].value)
        lo, hi = _ARITY.get(name, (1, 1))
        if not lo <= len(node.args) <= hi:
            want = f"{lo}" if lo == hi else f"{lo} to {hi}"
            raise _Reject(f"{name} takes {want} argument{'s' if hi > 1 else ''}, "
                          f"got {len(node.args)}", ("py", node.col_offset))
        if name == "Piecewise":
            return self.piecewise(node)
        if name == "where":                 # numpy's where(condition, a, b)
            cond = self.boolean(self.node(node.args[0]), node.args[0])
            a, b = self.node(node.args[1]), self.node(node.args[2])
            self.scalar(a, node.args[1])
            self.scalar(b, node.args[2])
            return sp.Piecewise((a, cond), (b, True))
        args = []
        for a in node.args:
            x = self.node(a)
            self.scalar(x, a)
            args.append(x)
        numeric = all(self.numeric(x) for x in args)
        try:
            if numeric:         # its value in doubles, never an exact gamma(10**60)
                return _numeric_call(fn(*args, evaluate=False))
            return fn(*args)
        except _Reject:
            raise
        except (TypeError, ValueError, ArithmeticError, AttributeError) as exc:
            if name in _HOLE_WHEN_UNDEFINED:    # Max(nan, u), Max(I, u), Mod(u, 0)
                return sp.nan
            raise _Reject(f"{name}(...) cannot be formed ({_first_line(exc)})",
                          ("py", node.col_offset)) from None

    def piecewise(self, node):
        sp = self.sp
        pairs = []
        for a in node.args:
            if not (isinstance(a, ast.Tuple) and len(a.elts) == 2):
                raise _Reject("Piecewise takes pairs (value, condition), e.g. "
                              "Piecewise((u, u > 0), (0, True))", ("py", a.col_offset))
            value = self.node(a.elts[0])
            self.scalar(value, a.elts[0])
            cond = self.boolean(self.node(a.elts[1]), a.elts[1])
            pairs.append((value, cond))
        try:
            return sp.Piecewise(*pairs)
        except (TypeError, ValueError) as exc:
            raise _Reject(f"Piecewise(...) cannot be formed ({_first_line(exc)})",
                          ("py", node.col_offset)) from None

    # -- kinds
    def numeric(self, x):
        return not x.free_symbols

    def scalar(self, x, node):
        sp = self.sp
        if not isinstance(x, sp.Expr):
            raise _Reject("a condition where a number is expected (use "
                          "Piecewise((value, condition), ...) or a if condition else b)",
                          ("py", getattr(node, "col_offset", 0)))

    def boolean(self, x, node):
        sp = self.sp
        if isinstance(x, sp.Expr):
            raise _Reject("a number where a condition is expected (e.g. u > 0)",
                          ("py", getattr(node, "col_offset", 0)))
        return x


def _first_line(exc):
    text = str(exc).strip()
    return text.splitlines()[0] if text else type(exc).__name__


def _number(value):
    """A sympy number for a Python float or complex: oo, -oo, nan for non-finite reals,
    an Integer for whole doubles below 2**53 (so ``u**2.0`` is ``u**2``, whose
    derivative and code are the same as ``u**2``'s)."""
    import sympy as sp
    if isinstance(value, complex):
        if value.imag == 0.0:
            value = value.real
        elif math.isfinite(value.real) and math.isfinite(value.imag):
            return sp.Add(_number(value.real), sp.Mul(_number(value.imag), sp.I))
        else:
            return sp.zoo if not (math.isnan(value.real) or math.isnan(value.imag)) else sp.nan
    if math.isnan(value):
        return sp.nan
    if math.isinf(value):
        return sp.oo if value > 0 else -sp.oo
    if value.is_integer() and abs(value) < 2.0**53:
        return sp.Integer(int(value))
    return sp.Float(value)


def _exact_power_is_small(a, b):
    """May sympy compute a**b exactly? Only small rationals to small powers."""
    import sympy as sp
    if not (isinstance(a, sp.Rational) and isinstance(b, sp.Rational)):
        return False
    bits = max(a.p.bit_length(), a.q.bit_length())
    if isinstance(b, sp.Integer):
        return abs(b.p) * bits <= MAX_BITS
    return b.q <= 16 and abs(b.p) <= 16 and bits <= 32


def _power(a, b):
    """a**b of two bounded constants in double (complex) arithmetic: never an exact
    computation that would not end (2**10**10 is oo)."""
    import sympy as sp
    try:
        ca, cb = complex(sp.N(a, 17)), complex(sp.N(b, 17))
    except (TypeError, ValueError, ArithmeticError):
        return sp.nan
    if any(math.isnan(x) for x in (ca.real, ca.imag, cb.real, cb.imag)):
        return sp.nan
    try:
        if ca.imag == 0.0 and cb.imag == 0.0 and (ca.real >= 0.0 or cb.real.is_integer()):
            value = ca.real ** cb.real
        else:
            value = ca ** cb
    except ZeroDivisionError:
        return sp.zoo
    except OverflowError:
        return sp.zoo if ca.imag or cb.imag or ca.real < 0.0 else sp.oo
    return _collapse(_number(value)) if isinstance(value, (float, complex)) else sp.nan


def _leaf_constant(a):
    import sympy as sp
    return a in (sp.pi, sp.E, sp.I, sp.EulerGamma, sp.GoldenRatio)


def _fold(build, numeric):
    """build() (a sympy node); for a constant node, a bounded one (see the module's
    docstring)."""
    import sympy as sp
    if not numeric:
        return build()
    x = build()
    if isinstance(x, sp.Rational):
        if max(x.p.bit_length(), x.q.bit_length()) <= MAX_BITS:
            return x
        return _collapse(x)
    if isinstance(x, sp.Float) or x in (sp.oo, -sp.oo, sp.nan, sp.zoo, sp.I) or _leaf_constant(x):
        return x
    if _tame(x):
        return x                        # pi/2, 2*pi, 1 + I: exact, as sympy writes them
    if isinstance(x, sp.Expr):
        return _collapse(x)
    return x                                            # a condition between numbers


def _tame(x, depth=0):
    """A constant that stays exact: sums and products of small rationals and the
    named constants (pi, E, I, ...), at most a few levels deep, integer powers up to
    4. Nothing in it can grow without bound."""
    import sympy as sp
    if depth > 4:
        return False
    if isinstance(x, sp.Rational):
        return max(x.p.bit_length(), x.q.bit_length()) <= MAX_BITS
    if _leaf_constant(x) or isinstance(x, sp.Float):
        return True
    if isinstance(x, (sp.Add, sp.Mul)):
        return len(x.args) <= 8 and all(_tame(a, depth + 1) for a in x.args)
    if isinstance(x, sp.Pow):
        return (isinstance(x.exp, sp.Integer) and abs(x.exp.p) <= 4
                and _tame(x.base, depth + 1))
    return False


#: the parts of a special function's complex arguments that mpmath evaluates it within
#: (past them a hole: its time grows without bound with them)
COMPLEX_SPECIAL = 64.0
#: ... the functions so called, by their sympy names (the kernels compute them for real
#: arguments: kernels/special.py, airy.py, integrals.py, gammas.py); gamma's kin stay
#: mpmath's (but beta, whose mpmath gave beta(1e300, 2) = 1.0 for 1e-600)
_SPECIAL_NAMES = (frozenset(_BESSEL.values()) | frozenset(_SPECIAL.values())
                  | {"jn", "yn", "hankel1", "hankel2"}) - {"factorial", "loggamma"}
#: what mpmath (sympy's evalf) may raise for a constant it cannot evaluate (its
#: NoConvergence is an Exception of its own; NotImplementedError and RecursionError
#: are RuntimeErrors)
_EVALF_FAILURES = (TypeError, ValueError, ArithmeticError, AttributeError, RuntimeError)


@functools.lru_cache(maxsize=1)
def _evalf_failures():
    try:
        from mpmath.libmp.libhyper import NoConvergence
    except ImportError:                          # pragma: no cover - another mpmath
        return _EVALF_FAILURES
    return _EVALF_FAILURES + (NoConvergence,)


def _numeric_call(node):
    """A function called with numbers (a sympy node built unevaluated), as a bounded
    sympy number.

    sympy's evalf (mpmath, 17 digits) takes a time that grows without bound with a
    special function's arguments: zeta(-1e300, 2.5), digamma(10**6) and besseli(1e15,
    1e15) did not end, expint(1000, 1000) took 4 s, others raised mpmath's
    NoConvergence after seconds (gamma, loggamma, factorial and beta stay quick). So a
    special function whose arguments are real takes the kernels' double value (what a
    picture of it computes, in bounded time) under their rules (a Bessel function's
    order up to 1000 and a spherical harmonic's degree up to 20: ValueError past
    them); with complex arguments mpmath's, where each part of them lies within
    COMPLEX_SPECIAL, else NaN (a hole). Elementary functions take mpmath's
    (_collapse)."""
    import sympy as sp
    if not isinstance(node, sp.Function) or type(node).__name__ not in _SPECIAL_NAMES:
        return _collapse(node)
    from .surface import kernel_closed_form, kernel_double
    name = type(node).__name__
    if name in ("hankel1", "hankel2"):           # J +- i Y (A&S 9.1.3, 9.1.4)
        try:
            j, y = (_numeric_call(f(*node.args, evaluate=False))
                    for f in (sp.besselj, sp.bessely))
        except ValueError as exc:
            raise ValueError(str(exc).replace("besselj", name)) from None
        try:
            return _number(complex(j) + (1j if name == "hankel1" else -1j) * complex(y))
        except TypeError:                        # (oo, zoo, nan)
            return sp.nan
    if name in ("digamma", "trigamma"):          # (as sympy writes them)
        node = sp.polygamma(int(name == "trigamma"), *node.args, evaluate=False)
    e = kernel_closed_form(node)
    if name in ("Ynm", "Znm"):
        return _collapse(e)                      # (sin, cos and exp of the angles)
    try:
        parts = [complex(a) for a in node.args]  # (nan and zoo: nan + nan i)
    except TypeError:
        return sp.nan
    if all(c.imag == 0.0 for c in parts) and not e.has(sp.I):
        return _number(kernel_double(e))
    if all(abs(c.real) <= COMPLEX_SPECIAL and abs(c.imag) <= COMPLEX_SPECIAL for c in parts):
        return _collapse(e)
    return sp.nan


def _collapse(x):
    """The double (or complex double) value of a constant sympy node whose parts are
    bounded, as a sympy number (oo, -oo, nan, zoo where it is not finite)."""
    import sympy as sp
    try:
        c = complex(sp.N(x, 17))
    except _evalf_failures():
        return sp.nan
    if c.imag != 0.0 and not math.isnan(c.imag) and abs(c.imag) <= 1e-15 * abs(c.real):
        c = complex(c.real, 0.0)
    return _number(c)


@functools.lru_cache(maxsize=512)
def parse_cached(text, names):
    """parse(), memoized (sympy expressions are immutable)."""
    return parse(text, names)


def constant(text, what="the value"):
    """A real number from untrusted text: ``2.5``, ``-pi``, ``2*pi``, ``sqrt(2)``,
    ``1e3``, ``inf``. ValueError (naming ``what``) for anything else."""
    try:
        return float(text)
    except (TypeError, ValueError):
        pass
    try:
        e = parse(str(text))
    except ValueError as exc:
        raise ValueError(f"{what} {text!r} is not a number: {exc}") from None
    import sympy as sp
    if not isinstance(e, sp.Expr) or e.free_symbols:
        raise ValueError(f"{what} {text!r} must be a number such as 2, -pi or 2*pi")
    c = _collapse(e)
    try:
        return float(c)
    except TypeError:
        raise ValueError(f"{what} {text!r} is not a real number") from None


def constant_number(x):
    """A Python number (int, float, complex, numpy scalar) as a bounded sympy number:
    an Integer up to 62 bits, else its double (oo past the double range)."""
    import numbers
    import sympy as sp
    if isinstance(x, numbers.Integral):
        x = int(x)
        if x.bit_length() <= MAX_BITS:
            return sp.Integer(x)
        try:
            return _number(float(x))
        except OverflowError:
            return _number(float("inf") if x > 0 else float("-inf"))
    if isinstance(x, numbers.Real):
        return _number(float(x))
    if isinstance(x, numbers.Complex):
        return _number(complex(x))
    raise ValueError(f"{x!r} is not a number")


def constant_value(e):
    """The double of a constant sympy expression; NaN where it is not a finite real
    number."""
    c = _collapse(e) if not isinstance(e, (int, float)) else e
    try:
        x = float(c)
    except (TypeError, ValueError):
        return math.nan
    return x if math.isfinite(x) else math.nan

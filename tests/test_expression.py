"""floatcol's formula parser (floatcol/expression.py): it never evaluates the text.

Injection strings go through every door a user's string reaches (render, plot_surface,
the CLI's expression, range, --vmin/--vmax and --vars arguments); none may run code
or create a file.
"""
import math
import os
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp

import floatcol as fc
from floatcol.expression import MAX_DEPTH, MAX_LENGTH, MAX_TREE_DEPTH, constant, parse

u, v = sp.symbols("u v")

# each writes the marker file if it is ever evaluated
INJECTIONS = [
    "__import__('os').system('touch {m}')",
    "u + 0*__import__('os').system('touch {m}')",
    "open('{m}', 'w').write('x')",
    "().__class__.__base__.__subclasses__()",
    "exec(\"open('{m}','w')\")",
    "eval(\"open('{m}','w')\")",
    "lambda: open('{m}', 'w')",
    "[open('{m}', 'w') for _ in (1,)]",
    "getattr(u, '__class__')",
    "u.__class__",
    "Symbol('x').__class__",
    "sin(u)[0]",
    "sin(x=open('{m}', 'w'))",
    "f'{{open(\"{m}\", \"w\")}}'",
    "__builtins__",
]


@pytest.mark.parametrize("text,expected", [
    ("3*sin(u*cos(v))", 3 * sp.sin(u * sp.cos(v))),
    ("u^2 - v^2", u**2 - v**2),
    ("2u + 3 v", 2 * u + 3 * v),                     # products without '*'
    ("2 sin(u)", 2 * sp.sin(u)),
    ("(u+1)(v-1)", (u + 1) * (v - 1)),
    ("u(v+1)", u * (v + 1)),
    ("1/2*u", u / 2),
    ("exp(-u*u-v*v)", sp.exp(-u * u - v * v)),
    ("Abs(u) + abs(v) + ln(u)", sp.Abs(u) + sp.Abs(v) + sp.log(u)),
    ("atan2(v, u) + Min(u, v, 1) + Max(u, 2)", sp.atan2(v, u) + sp.Min(u, v, 1) + sp.Max(u, 2)),
    ("u // 2 + u % 3", sp.floor(u / 2) + sp.Mod(u, 3)),
    ("u if u > 0 else -u", sp.Piecewise((u, u > 0), (-u, True))),
    ("Piecewise((u, u > 0 and v > 0), (0, True))",
     sp.Piecewise((u, sp.And(u > 0, v > 0)), (0, True))),
    ("sqrt(-1)*u", sp.I * u),
    ("pi", sp.pi),
    ("2**10**10", sp.oo),                    # past the doubles: oo, never an exact power
    ("1.0e+4342944819", sp.oo),              # hung sympy's Float
    ("gamma(10**60)", sp.oo),                # folded in doubles, not a factorial
    ("exp(exp(exp(100)))*u", sp.oo * u),
    ("10**10**10**10", sp.oo),
    # numpy's and the math module's spellings (copied from NumPy code)
    ("np.sin(u)*math.cos(v)", sp.sin(u) * sp.cos(v)),
    ("numpy.exp(u) + sympy.pi + np.e", sp.exp(u) + sp.pi + sp.E),
    ("log10(u)", sp.log(u) / sp.log(10)),
    ("np.log2(u)", sp.log(u) / sp.log(2)),
    ("mod(u, 2)", sp.Mod(u, 2)),
    ("np.hypot(u, v)", sp.sqrt(u ** 2 + v ** 2)),
    ("fabs(u) + np.absolute(v)", sp.Abs(u) + sp.Abs(v)),
    ("np.heaviside(u, 0.5)", sp.Heaviside(u, 0.5)),
    ("np.where(u > 0, u, v)", sp.Piecewise((u, u > 0), (v, True))),
])
def test_parse_builds_the_expression(text, expected):
    assert parse(text, ("u", "v")) == expected


@pytest.mark.parametrize("text,what,where", [
    ("__import__('os')", "the character \"'\" is not allowed", 12),
    ("u.real", "the character '.' is not allowed", 2),
    ("np.sin.__class__", "the character '.' is not allowed", 7),   # a name, not attributes
    ("os.system(u)", "the character '.' is not allowed", 3),
    ("np.foo(u)", "unknown function foo", 4),
    ("where(u, 1, 2)", "a number where a condition is expected", 7),
    ("u[0]", "the character '[' is not allowed", 2),
    ("lambda: 1", "the character ':' is not allowed", 7),
    ("sin(*u)", "a starred argument (*x) is not allowed", 5),
    ("(u, v)", "a tuple (outside Piecewise) is not allowed", 1),
    ("foo(u)", "unknown function foo", 1),
    ("__class__", "the name __class__ is not allowed", 1),
    ("sin", "the function sin must be called", 1),
    ("atan2(u)", "atan2 takes 2 arguments, got 1", 1),
    ("u +* v", "could not parse expression 'u +* v' (invalid syntax)", 4),
    ("3*sin(u", "'(' was never closed", 6),
    ("not u", "a number where a condition is expected", 1),
    ("u > 0", None, None),                   # a condition parses; render refuses it
])
def test_refusals_name_the_construct_and_point_at_it(text, what, where):
    if what is None:
        parse(text, ("u", "v"))
        return
    with pytest.raises(ValueError) as info:
        parse(text, ("u", "v"))
    msg = str(info.value)
    assert what in msg
    assert f"at character {where}:" in msg
    assert "<here>" in msg


def test_the_input_is_bounded():
    with pytest.raises(ValueError, match=f"at most {MAX_LENGTH}"):
        parse("u+" * MAX_LENGTH + "u")
    with pytest.raises(ValueError, match="nest more than"):
        parse("(" * (MAX_DEPTH + 5) + "u" + ")" * (MAX_DEPTH + 5))
    with pytest.raises(ValueError, match="levels deep"):
        parse("-" * (MAX_TREE_DEPTH + 5) + "u")
    with pytest.raises(ValueError, match="levels deep"):
        parse("u+" * (MAX_TREE_DEPTH + 5) + "u")
    assert parse("u+" * 150 + "u") == 151 * sp.Symbol("u")     # long, but not deep


@pytest.mark.parametrize("text,value", [("2*pi", 2 * math.pi), ("-pi", -math.pi),
                                        ("sqrt(2)", math.sqrt(2)), ("1e3", 1000.0),
                                        ("inf", math.inf), ("-5", -5.0), ("pi/2^2", math.pi / 4)])
def test_constant(text, value):
    assert constant(text) == value


@pytest.mark.parametrize("text", ["u", "I", "__import__('os')", "1+", "sin"])
def test_constant_refuses_what_is_not_a_real_number(text):
    with pytest.raises(ValueError, match="the value"):
        constant(text)


@pytest.mark.parametrize("template", INJECTIONS)
def test_injection_through_the_api_runs_nothing(template, tmp_path):
    marker = tmp_path / "pwned"
    text = template.format(m=marker)
    for call in (lambda: fc.render(text, size=(8, 6)),
                 lambda: fc.render("u", u=(text, 1), size=(8, 6)),
                 lambda: fc.plot_surface(text, size=(8, 6)).rgba,
                 lambda: fc.render_many([text, "u"], size=(8, 6)),
                 lambda: fc.animate(text, frames=2, size=(8, 6))):
        with pytest.raises(ValueError):
            call()
    assert not marker.exists()


def _cli(*args, cwd):
    return subprocess.run([sys.executable, "-m", "floatcol.cli", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=300)


#: the CLI's doors in one process: each argument list a fresh call of the CLI's main, its
#: exit status and what it printed to stderr (json)
DOORS = """
import contextlib, io, json, sys
from floatcol.cli import main
out = []
for args in json.loads(sys.argv[1]):
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        try:
            code = main(args)
        except SystemExit as exc:
            code = exc.code
    out.append([code, err.getvalue()])
print(json.dumps(out))
"""


def test_injection_through_the_cli_runs_nothing(tmp_path):
    """Every string argument of the CLI (with all the injection strings of a door in one
    call where the CLI stops at the first: the expression): each door a call of the CLI's
    main in one process of its own (one process a door took 8 s of the suite; the
    process-level exit status and stderr line are test_cli's), and the first door as a
    user runs it, ``python -m floatcol.cli``."""
    import json
    marker = tmp_path / "pwned"
    payload = f"__import__('os').system('touch {marker}')"
    calls = [
        ["render", payload, "-o", "a.png"],
        ["render", f"u + 0*{payload}", "-o", "a.png"],
        ["render", "sin(u)", f"--u={payload}:5", "-o", "a.png"],
        ["render", "sin(u)", f"--v=0:{payload}", "-o", "a.png"],
        ["render", "sin(u)", f"--vmin={payload}", "-o", "a.png"],
        ["render", "sin(u)", f"--vars={payload},v", "-o", "a.png"],
        ["render", "sin(u)", f"--aspect={payload}", "-o", "a.png"],
        ["render", "sin(u)", f"--cmap={payload}", "-o", "a.png"],
        ["render", "sin(u)", f"--opacity={payload}", "-o", "a.png"],
        ["animate", payload, "--frames", "2", "-o", "a.gif"],
        ["animate", "sin(u+t)", f"--t=0:{payload}", "--frames", "2", "-o", "a.gif"],
    ]
    res = _cli(*calls[0], cwd=tmp_path)
    assert res.returncode == 2, (calls[0], res.stderr)
    assert res.stderr.startswith("floatcol: error:") and res.stderr.count("\n") == 1
    run = subprocess.run([sys.executable, "-c", DOORS, json.dumps(calls)], cwd=tmp_path,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    outcomes = json.loads(run.stdout)
    assert len(outcomes) == len(calls)
    for args, (code, err) in zip(calls, outcomes):
        assert code == 2, (args, err)
        assert err.startswith("floatcol: error:") and err.count("\n") == 1, (args, err)
    assert not (tmp_path / "a.png").exists() and not (tmp_path / "a.gif").exists()
    assert not marker.exists()
    assert not any(p.name.startswith(".floatcol-") for p in tmp_path.iterdir())


@pytest.mark.parametrize("expr", ["1.0*I", "-oo", "log(floor(u)) - I*pi",
                                  "Abs(sqrt(u)) + 1 + I*pi", "zoo", "nan*u", "Max(nan, u)",
                                  "u % 0"])
def test_complex_and_infinite_constants_are_holes(expr):
    """Each was an error naming sympy's or Numba's internals (maximum recursion depth,
    invalid syntax in lambdifygenerated, 'floor', 'Abs')."""
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)       # "a hole everywhere"
        r = fc.render(expr, u=(0.5, 3), v=(0, 2), size=(30, 20))
    assert r.rgba.shape == (20, 30, 4)
    if expr == "log(floor(u)) - I*pi":
        # log(floor(u)) is real where floor(u) >= 1; minus I*pi it is complex there:
        # a hole, and on 0.5 <= u < 1 log(0) - I*pi is not finite: a hole too
        assert not (r.side != 0).any()


def test_messages_name_no_internals():
    cases = [("lambda: 1", "the character ':' is not allowed"),
             ("atan2(I*u, v)", "cannot draw f = atan2(I*u, v)")]
    for expr, what in cases:
        with pytest.raises(ValueError) as info:
            fc.render(expr, size=(10, 8))
        msg = str(info.value)
        assert what in msg
        for word in ("numba", "nopython", "sympy", "lambdify", "recursion", "Traceback"):
            assert word not in msg.lower()
    with pytest.raises(ValueError, match="azim must be finite, got inf"):
        fc.plot_surface("u*v", azim=math.inf).rgba


def test_the_warning_names_the_formulas_variables():
    with pytest.warns(RuntimeWarning, match=r"on u in \[-10, 10\], v in \[-10, 10\]"):
        fc.plot_surface("sqrt(-1-u**2)", size=(20, 15)).rgba
    with pytest.warns(RuntimeWarning, match=r"on x in \[-10, 10\], y in \[-10, 10\]"):
        fc.plot_surface("sqrt(-1-y**2)", size=(20, 15)).rgba


def test_cli_output_error_names_the_users_path(tmp_path):
    if not os.path.isdir("/proc"):
        pytest.skip("needs /proc: a folder where no file can be created")
    res = _cli("render", "u", "--size", "8x6", "-o", "/proc/a.png", cwd=tmp_path)
    assert res.returncode == 2
    assert "/proc/a.png" in res.stderr and ".floatcol-" not in res.stderr


def test_an_unknown_e_says_eulers_number_is_E():
    """np.e is E; a bare e is a name, and the message says how to write Euler's number."""
    for call in (lambda: fc.render("e**u", size=(20, 10)),
                 lambda: fc.plot_surface("e**x", ("x", -1, 1), ("y", -1, 1))):
        with pytest.raises(ValueError, match=r"unknown symbol e.*Euler's number is E or exp\(1\)"):
            call()
    assert fc.render("np.e**u", u=(-1, 1), v=(-1, 1), size=(20, 10)).side.any()


def test_a_piecewise_without_otherwise_is_a_hole_where_no_condition_holds(capfd):
    """Piecewise((u, u > 0)): where no condition holds, NaN (a hole). sympy's printer
    wrote None there, which the compiled function raised as a TypeError at every such
    point: "Exception ignored" printed from inside the kernels over and over (2 494
    times, with a traceback each, for a 40 x 30 picture), the values there undefined. The same for sympy's
    functions that print as such a Piecewise (factorial2)."""
    s = fc.as_surface("Piecewise((u, u > 0), (v, v > 1))")
    assert s.f(1.0, 0.0, 0.0) == 1.0 and s.f(-1.0, 2.0, 0.0) == 2.0
    assert np.isnan(s.f(-1.0, 0.0, 0.0))
    r = fc.render("Piecewise((u, u > 0))", u=(-2, 2), v=(-2, 2), size=(40, 30))
    seen = r.side != 0
    assert 0.1 < seen.mean() < 0.6 and np.nanmin(r.u[seen]) > -0.05
    out, err = capfd.readouterr()
    assert "Exception ignored" not in err and "TypeError" not in err


def test_a_power_whose_exponent_is_whole_numbers_is_a_hole_at_a_pole(capfd):
    """u**floor(v): floor is an integer in the compiled code, and 0.0 ** -2 raised a
    ZeroDivisionError from inside the kernels at u = 0 (an "Exception ignored" with a
    traceback 33 times for a 40 x 30 picture, the value there undefined: 0); now a
    hole, as u**-2."""
    w = fc.as_surface("u**floor(v)").evaluate([0.0, 2.0, -2.0], [-1.5, 3.5, 3.5])
    assert not np.isfinite(w[0]) and list(w[1:]) == [8.0, -8.0]
    r = fc.render("u**floor(v)", u=(-3, 3), v=(-3, 3), size=(40, 30))
    assert (r.side != 0).mean() > 0.04                  # (measured 0.081: a tall surface)
    out, err = capfd.readouterr()
    assert "Exception ignored" not in err and "ZeroDivisionError" not in err


def test_a_special_function_of_numbers_takes_the_kernels_double():
    """A special function called with numbers is folded to the double the kernels
    compute (expression._numeric_call), under their rules; sympy's evalf (mpmath) had
    run without end for digamma(10**6), zeta(-1e300, 2.5) and dirichlet_eta(1e15) and
    raised mpmath's NoConvergence (not a ValueError) for zeta(1e300, -oo) (their
    renders: test_fuzz.py's REPRODUCERS, in a worker that detects a hang)."""
    # digamma(n) = ln n - 1/(2n) - 1/(12 n^2) + O(n^-4) (A&S 6.3.18)
    n = 10**6
    assert float(parse("digamma(10**6)")) == pytest.approx(
        math.log(n) - 1 / (2 * n) - 1 / (12 * n * n), rel=1e-14)
    # J_1/2(2) = sqrt(2 / (2 pi)) sin 2 (A&S 10.1.11), and the constant is folded
    assert float(parse("besselj(0.5, 2)")) == pytest.approx(
        math.sqrt(1 / math.pi) * math.sin(2), rel=1e-13)
    assert parse("besselj(0.5, 2)*u").free_symbols == {u}
    # sympy's evalf cannot evaluate erfcinv at all (it was a hole): erfc(x) = 1/2 at x
    assert math.erfc(float(parse("erfcinv(0.5)"))) == pytest.approx(0.5, rel=1e-14)
    for text in ("zeta(-1e300, 2.5)", "zeta(1e300, -oo)", "zeta(I, nan)",
                 "zeta(2 + 300*I)"):                       # (complex, past COMPLEX_SPECIAL)
        assert parse(text) is sp.nan, text
    assert float(parse("dirichlet_eta(1e15)")) == 1.0       # 1 - 2^-s + ... in doubles
    # complex arguments within COMPLEX_SPECIAL: mpmath's value (zeta(2 + 3i), DLMF 25.2.1
    # summed here)
    k = np.arange(1, 200001, dtype=float)
    tail = (k[-1] + 0.5) ** (-1 - 3j) / (1 + 3j)           # (Euler-Maclaurin's remainder)
    assert float(parse("re(zeta(2 + 3*I))")) == pytest.approx(
        (np.sum(k ** (-2 - 3j)) + tail).real, rel=1e-9)
    # the kernels' rules: a Bessel order up to 1000, a spherical harmonic's degree to 20
    with pytest.raises(ValueError, match="besseli's order must be a number from -1000 to "
                                         "1000.*got 1.0e\\+300.*at character 1"):
        parse("besseli(1e300, 1e300)")
    with pytest.raises(ValueError, match="n <= 20.*got n = 1000000"):
        parse("Ynm(10**6, 2, 2, 2)")
    with pytest.raises(ValueError, match="hankel1's order must be"):
        parse("hankel1(1e15, -1e15)")                      # (J + iY: it had not ended)
    h = complex(parse("hankel2(0.5, 2)"))                  # J - iY, Y_1/2 = -J_-1/2
    assert h == pytest.approx(math.sqrt(1 / math.pi) * (math.sin(2) + 1j * math.cos(2)),
                              rel=1e-13)

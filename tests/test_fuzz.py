"""No input crashes, hangs or leaks internals (issue 26).

Random render calls (tests/fuzzing.py: expression trees over the parser's operators
and functions with constants at the doubles' edges, degenerate/reversed/infinite/NaN
ranges, random sizes, angles and options) run in a worker process: a segfault is a
failed test here, not a dead test runner, and a case that takes more than the
time-out is a hang. Every case must draw a picture or raise a ValueError whose
message names no internals. benchmarks/fuzz.py runs 10,000 of them.
"""
import random

import pytest

import fuzzing
from conftest import background_job, background_result

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings, strategies as st  # noqa: E402

#: cases of the hypothesis test (a fixed seed: derandomize)
N_CASES = 300


@pytest.fixture(scope="module")
def worker():
    w = fuzzing.Worker(timeout=120.0)
    yield w
    w.close()


def _check(worker, case):
    res = worker.run(case)
    assert res["outcome"] in ("ok", "value"), f"{res['outcome']}: {res['message']}\n{case}"


@settings(max_examples=N_CASES, deadline=None, derandomize=True, database=None,
          suppress_health_check=list(HealthCheck))
@given(st.randoms(use_true_random=False))
def test_random_renders_draw_or_raise_value_error(worker, rnd):
    _check(worker, fuzzing.case(rnd))


#: terrain cases (a fixed seed): height fields with holes, 16-bit, flat, huge or tiny
#: heights, rows either way, fly cameras anywhere, area sampling, lod, shadows, objects
N_TERRAIN = 300


#: what the terrain cases found: a tree 1e50 tall on a DEM (its screen corners
#: converted to pixel indices beyond an int's range: a segfault), a fly camera one
#: pixel wide (a division by zero), on-the-fly shadows seen by a fly camera (1.4e11
#: cells of the sweep: killed for memory), a fly camera's draft beside a DEM a metre
#: wide (tens of millions of planes before its screen plane: killed for memory)
TERRAIN_REPRODUCERS = [
    {"seed": 159015466, "shape": [64, 33], "heights": "relief",
     "extent": [-4893.2, -4894.2, 1609.5, 1859.5], "call": "terrain",
     "kwargs": {"size": [17, 33]},
     "objects": [["tree", -4894.1302986683795, 1785.2028684936238, 1e50]]},
    {"seed": 1584163655, "shape": [3, 64], "heights": "spikes",
     "extent": [-9833.8, -9583.8, 1425.6, 1426.6], "call": "fly", "kwargs": {},
     "fly": {"position": [-9651.3, 1470.4, 40.0], "heading": -220.4, "pitch": 23.3,
             "fov": 145.3, "size": [1, 1]}},
    {"seed": 5, "shape": [129, 129], "heights": "relief", "extent": [0.0, 3e4, 0.0, 3e4],
     "call": "fly", "kwargs": {"shadows": "on-the-fly", "lightsource": [315, 35]},
     "fly": {"position": [15000.0, 7500.0], "heading": 10.0, "pitch": -10.0, "fov": 60.0,
             "size": [64, 36], "above": 300.0}},
    {"seed": 840608283, "shape": [129, 33], "heights": "tiny",
     "extent": [4829.2, 4830.2, -6617.7, -6616.7], "call": "fly", "draft": True,
     "kwargs": {"antialias": "area", "smooth_shading": False},
     "fly": {"position": [4766.4854493240255, -6716.556149471783], "heading": -143.748,
             "pitch": 2.971, "fov": 36.89, "size": [120, 90], "above": 1498.626}},
]


def test_random_terrains_draw_or_raise_value_error(worker):
    for c in TERRAIN_REPRODUCERS:
        res = worker.run({"terrain": c})
        assert res["outcome"] == "ok", f"{res['outcome']}: {res['message']}\n{c}"
    rnd = random.Random(32)
    for _ in range(N_TERRAIN):
        _check(worker, fuzzing.terrain_case(rnd))


#: matplotlib's plot_surface(X, Y, Z) on meshes of every kind (a fixed seed): even,
#: uneven, polar, wound twice, a sphere's, scattered, on a line, at one point; a fifth
#: of them as plot_trisurf's scattered points
N_MESH = 120


def test_random_meshes_draw_or_raise_value_error(worker):
    rnd = random.Random(33)
    grids = set()
    for _ in range(N_MESH):
        c = fuzzing.mesh_case(rnd)
        grids.add(c["mesh"]["grid"])
        _check(worker, c)
    assert grids == set(fuzzing.MESH_GRIDS)


# The reproducers: segfaults in the column kernel (a float -> row conversion of
# screen rows near 1e300, undefined in LLVM), and hangs (an adaptive perspective step
# read from scratch never written: t became NaN)
REPRODUCERS = [
    ("sin(v)^(2*u+v)", dict(u=[-3.682, -1.746], v=[-7.268, 5.162], size=[153, 84],
                            elev=38.595, azim=11.04)),
    ("tan(1/u)**20000000000.0", dict(u=[-0.674, 4.509], v=[-4.631, 6.525], size=[89, 17],
                                     elev=11.09, azim=-23.09)),
    ("(1/u)^((2*v - 1/2)^(sign(u)*sign(v)/cos(1)))",
     dict(u=[-5.706, 7.042], v=[-0.64, 8.84], size=[110, 11], elev=-63.245, azim=-72.89,
          projection="ortho", aspect="auto")),
    ("E/2", dict(u=[-7.907, 6.163], v=[-6.619, 5.946], size=[152, 33], elev=-32.69, azim=0,
                 projection="perspective", shading="lambert", sampling="adaptive")),
    ("0", dict(u=[-0.952, 9.389], v=[-1.991, 0.248], size=[41, 96], elev=-17.25,
               azim=-166.63, projection="persp", sampling="adaptive", corrections="spline")),
    ("1/u", dict(u=[-1, 1], v=[-1, 1], size=[60, 40], method="horizon")),
    # exceptions raised inside the compiled function, printed as "Exception ignored"
    # by the kernels' calls (fuzzing.py's "raised"): 0.0 ** -2 of an integer exponent,
    # sympy's None where no condition of a Piecewise holds
    ("u**floor(v)", dict(u=[-3, 3], v=[-3, 3], size=[40, 30])),
    ("Piecewise((u, u > 0))", dict(u=[-2, 2], v=[-2, 2], size=[40, 30])),
    # constants of special functions that sympy's evalf (mpmath) evaluated without end
    # (the first and third) or raised mpmath's NoConvergence for (2026-12-07,
    # benchmarks/fuzz.py 3000 1207): now the kernels' doubles (expression._numeric_call)
    ("(((zeta(I, nan))^(zeta(2.5, 0)))**(((-1e300)+(1/2))%((-oo)*(0))))*"
     "(cot(im(Mod(2.5, 0))))", dict(u=[1e-09, 1.0], size=[160, 3], elev=-22.83, azim=-213.1,
                                    corrections="spline+supersample", sampling="lod")),
    ("zeta((Abs(conjugate(-1e300)))-(im(dirichlet_eta(-1))), -oo)",
     dict(u=[-1.427, 6.849], v=[7.368, 8.988], size=[33, 3], elev=-90.0, azim=-290.4,
          sampling="march", pixel_step=2.0)),
    ("ceiling(((dirichlet_eta(pi))**(zeta(-1e300, 2.5)))%(tan(I)))",
     dict(u=[8.111, 17.255], v=[3.799, 15.525], size=[101, 1], elev=-47.7, azim=-8.74,
          corrections="none", color="u - v", focal_length=1.0)),
    ("u + digamma(10**6) + expint(1000, 1000)*v + dirichlet_eta(1e15)",
     dict(u=[-1, 1], v=[-1, 1], size=[40, 30])),
]


def test_the_reproducers_render(worker):
    # the hangs depended on memory left by earlier renders: interleave random cases
    rnd = random.Random(5)
    for expr, kw in REPRODUCERS * 3:
        _check(worker, fuzzing.case(rnd))
        _check(worker, {"expr": expr, "kwargs": kw})


@background_job("bounds-checked kernels", order=1, lane=1,
                consumer="test_bounds_checked_kernels")
def _bounds_checked_cases(job):
    """The cases of test_bounds_checked_kernels and their outcomes, run in a worker.
    Every kernel of the suite has Numba's bounds checks (conftest.SUITE_ENV), so
    these cases are a few more pictures that would be an IndexError, not a write past a
    buffer, where an index went out of range; a background job (conftest.py) after
    the kernels job (lane 1), whose cache it loads its kernels from."""
    w = fuzzing.Worker(timeout=600.0)
    w.on_start = job.procs.append
    try:
        rnd = random.Random(7)
        cases = [{"expr": e, "kwargs": kw} for e, kw in REPRODUCERS]
        cases += [fuzzing.case(rnd) for _ in range(12)]
        cases.append({"expr": "3*sin(u*cos(v))", "kwargs": dict(size=[160, 120],
                                                               projection="perspective")})
        return [(c, w.run(c)) for c in cases]
    finally:
        w.close()


def test_bounds_checked_kernels():
    """The issue's reproducers, random cases and a default picture, with Numba's bounds
    checks on (as everywhere in the suite): an index out of range is an IndexError
    there, not a write past a buffer (_bounds_checked_cases)."""
    outcomes = background_result("bounds-checked kernels")
    assert len(outcomes) == len(REPRODUCERS) + 13
    for case, res in outcomes:
        assert res["outcome"] in ("ok", "value"), f"{res['outcome']}: {res['message']}\n{case}"

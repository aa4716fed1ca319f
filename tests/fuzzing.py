"""Fuzzing floatcol in a worker process (tests/test_fuzz.py, benchmarks/fuzz.py).

A case is a render call built from random parts: an expression tree over the
operators and functions the parser allows, constants at the edges of the doubles
(0, +-1, +-1e300, 1e-300, oo, nan, zoo, I), ranges that are degenerate, reversed,
infinite, NaN, tiny or huge, and random sizes, angles, projections and options.
Each case runs in a worker process (``Worker``), so that a segfault is a counted
failure, not a dead test runner, and a hang is a time-out that kills the worker.

Outcomes: "ok" (a picture), "value" (a ValueError), "other" (any other exception: a
bug), "crash" (the worker died), "hang" (no answer within the time-out), "leak" (a
message, error or warning, naming floatcol's, numba's or sympy's internals),
"raised" (an exception raised inside compiled code, a kernel's call of the surface's
function, which Python prints as "Exception ignored" and the kernel goes on with an
undefined value: u**floor(v) at u = 0, Piecewise((u, u > 0)) where u <= 0 were).
"""
from __future__ import annotations

import json
import math
import os
import random
import re
import subprocess
import sys

CONSTANTS = ["0", "1", "-1", "1e300", "-1e300", "1e-300", "oo", "-oo", "nan", "zoo", "I",
             "pi", "E", "2.5", "1/2", "3"]
UNARY = ["sin", "cos", "tan", "cot", "sec", "csc", "asin", "acos", "atan", "sinh", "cosh",
         "tanh", "asinh", "acosh", "atanh", "exp", "log", "sqrt", "cbrt", "Abs", "sign",
         "floor", "ceiling", "frac", "re", "im", "arg", "erf", "gamma", "conjugate",
         "j0", "j1", "y0", "y1", "i0", "i1", "k0", "k1", "airyai", "airybi", "Si", "Ci",
         "Ei", "li", "fresnels", "erfi", "erfinv", "erfcinv", "digamma", "trigamma",
         "factorial", "lambertw", "zeta", "dirichlet_eta", "ellipk", "ellipe"]
BINARY_OPS = ["+", "-", "*", "/", "**", "^", "%"]
BINARY_FNS = ["atan2", "Min", "Max", "Mod", "log", "root", "zeta", "beta", "ellipkinc",
              "ellipeinc"]
OPTIONS = {
    "projection": ["orthographic", "perspective", "ortho", "persp"],
    "shading": ["default", "lambert"],
    "method": ["column", "column", "column", "horizon"],
    "interpolation": ["normal", "intensity"],
    "smooth_shading": [False, False, True, "yes"],
    "corrections": ["none", "spline", "supersample", "adaptive", "spline+supersample",
                    "spline+adaptive"],
    "sampling": ["uniform", "adaptive", "lod", "march"],
    "antialias": [True, False, 2, 3, "area"],
    # (mostly good values: a bad one now and then, so that most cases still draw)
    "opacity": [1.0, 0.5, 0.3, 0.0, 0.8, 0.5, 2.0],
    "contours": [None, 5, 3, 12, [0.0, 0.5], 0, [math.nan]],
    "wireframe": [None, 8, 20, [3, 4], 5, 1e9],
    "fill": [True, True, False, False, "no"],
    "color": [None, "u*v", "sin(u)", "1/u", "u - v", "u**"],
    "pixel_step": [1.0, 0.5, 3.0, 2.0, 1.5, 0.0],
    "focal_length": [None, 1.0, 0.5, 10.0, 2.0, -2.0],
    "specular": [None, 0.5, 0.0, 0.3, 1.0, -1.0],
    "ambient": [None, 0.2, 1.0, 0.0, 0.5, math.nan],
    "aspect": ["equal", "auto", "equalxy", [1, 1, 0.5]],
    "placement": ["exact", "paper"],
    # (no GPU in CI: "cuda" is a ValueError there, as a bad name is)
    "device": ["cpu", "cpu", "cpu", "cuda", "gpu"],
}
BOUNDS = [0.0, 1.0, -1.0, 2.5, -7.3, 1e-300, -1e-300, 1e300, -1e300, math.inf, -math.inf,
          math.nan, 1e-9, 1e9]

#: what a message shown to a user must not contain: floatcol's, numba's or sympy's
#: internals
INTERNAL = re.compile(r"numba|sympy|lambdif|nopython|Traceback|\.py\b|object at 0x|"
                      r"_fc_|Dummy|kernel|cfunc|recursion|CPUDispatcher|llvm|"
                      r"TypingError|AttributeError|KeyError|IndexError|'NoneType'",
                      re.IGNORECASE)


def expression(rng: random.Random, depth: int = 0) -> str:
    """A random formula in u and v."""
    roll = rng.random()
    if depth >= 4 or roll < 0.25:
        return rng.choice(["u", "v", "u", "v"] + CONSTANTS)
    if roll < 0.55:
        return f"{rng.choice(UNARY)}({expression(rng, depth + 1)})"
    if roll < 0.9:
        a, b = expression(rng, depth + 1), expression(rng, depth + 1)
        return f"({a}){rng.choice(BINARY_OPS)}({b})"
    a, b = expression(rng, depth + 1), expression(rng, depth + 1)
    return f"{rng.choice(BINARY_FNS)}({a}, {b})"


def _range(rng):
    r = rng.random()
    if r < 0.8:
        a = rng.uniform(-10, 10)
        return [round(a, 3), round(a + rng.uniform(0.1, 15), 3)]
    if r < 0.85:
        a = rng.uniform(-1, 1)
        return [a, a + rng.choice([1e-12, 1e-300, 5e-324])]          # tiny
    return [rng.choice(BOUNDS), rng.choice(BOUNDS)]                  # anything


def case(rng: random.Random) -> dict:
    """A random render call: {"expr": str, "kwargs": {...}} (JSON-able)."""
    kw = {}
    if rng.random() < 0.9:
        kw["u"] = _range(rng)
    if rng.random() < 0.9:
        kw["v"] = _range(rng)
    kw["size"] = [rng.choice([1, 2, 7, 33, 64, 101, 160]), rng.choice([1, 3, 17, 48, 90, 120])]
    if rng.random() < 0.03:
        kw["size"] = [rng.choice([0, -3, 40.5]), 30]
    kw["elev"] = rng.choice([rng.uniform(-90, 90)] * 8 + [90.0, -90.0, 0.0])
    kw["azim"] = rng.choice([rng.uniform(-360, 360)] * 8 + [0.0, 90.0])
    if rng.random() < 0.04:
        kw[rng.choice(["elev", "azim"])] = rng.choice([math.nan, math.inf, 120.0, -1e300])
    for name, values in OPTIONS.items():
        if rng.random() < 0.4:
            kw[name] = rng.choice(values)
    if rng.random() < 0.1:
        kw["vmin"], kw["vmax"] = rng.choice([[0, 1], [1, 0], [math.nan, 1], [-1e300, 1e300]])
    if rng.random() < 0.25:
        kw["shadows"] = rng.choice([True, True, "on-the-fly", "texture", "soft"])
        if rng.random() < 0.3:
            kw["light_radius"] = rng.choice([0.27, 3.0, 0.0, -1.0, math.nan, 45.0])
        if rng.random() < 0.05:
            kw["tiles"] = rng.choice([1, 3, 0])
        if rng.random() < 0.8:
            kw["lightsource"] = rng.choice([[rng.uniform(0, 360), rng.uniform(-10, 90)],
                                            [0, 90], [45, 0], [math.nan, 30], [10, -90]])
    c = {"expr": expression(rng), "kwargs": kw}
    if rng.random() < 0.15:
        c["draft"] = True               # (a fresh install's draft, where it can draw it)
    return c


#: a terrain case's heights: ordinary relief, a flat or empty DEM, huge or tiny values,
#: holes (NaN, inf), 16-bit integers
TERRAIN_HEIGHTS = ["relief", "relief", "relief", "flat", "nan", "holes", "holes", "huge",
                   "tiny", "uint16", "spikes"]
TERRAIN_NUMBERS = [0.0, -1.0, 1e-300, 1e300, -1e300, math.inf, -math.inf, math.nan]


def _odd(rng, good):
    """A value from ``good`` (a callable), now and then one at the edge of the doubles."""
    return rng.choice(TERRAIN_NUMBERS) if rng.random() < 0.06 else good()


def terrain_case(rng: random.Random) -> dict:
    """A random height-field render (JSON-able; the worker makes the heights from
    ``seed``): one of fc.render of a HeightField, fc.render with fc.fly's camera (the
    lod engine, or its ray march), or fc.terrain, with area sampling, shadows and objects
    on it."""
    sides = [2, 3, 9, 33, 64, 129] * 6 + [1]
    ny, nx = rng.choice(sides), rng.choice(sides)
    extent = [round(rng.uniform(-1e4, 1e4), 1)]
    extent.append(round(extent[0] + rng.choice([1.0, 250.0, 3e4]), 1))
    extent.append(round(rng.uniform(-1e4, 1e4), 1))
    extent.append(round(extent[2] + rng.choice([1.0, 250.0, 3e4]), 1))
    if rng.random() < 0.3:
        extent[1], extent[0] = extent[0], extent[1]          # west > east: rows reversed
    if rng.random() < 0.05:
        extent[rng.randrange(4)] = rng.choice(TERRAIN_NUMBERS)
    c = {"seed": rng.randrange(2 ** 31), "shape": [ny, nx],
         "heights": rng.choice(TERRAIN_HEIGHTS), "extent": extent,
         "call": rng.choice(["render", "fly", "fly", "terrain", "flight"]),
         "draft": rng.random() < 0.2}
    kw = {"size": [rng.choice([1, 2, 17, 64, 120]), rng.choice([1, 3, 33, 90])]}
    if rng.random() < 0.5:
        kw["antialias"] = rng.choice([True, False, "area", "area", 2])
    if rng.random() < 0.3:
        kw["sampling"] = rng.choice(["uniform", "adaptive", "lod", "march", "march"])
    if rng.random() < 0.2:
        kw["shadows"] = rng.choice([True, "texture", "on-the-fly"])
    if rng.random() < 0.2:
        kw["smooth_shading"] = rng.choice([True, False])
    if rng.random() < 0.3:
        kw["lightsource"] = [_odd(rng, lambda: rng.uniform(0, 360)),
                             _odd(rng, lambda: rng.uniform(-10, 90))]
    if rng.random() < 0.2:
        kw["vert_exag"] = rng.choice([1.0, 10.0, 0.0, -2.0, 1e300, math.nan])
    if c["call"] not in ("fly", "flight") and rng.random() < 0.5:
        kw["elev"] = _odd(rng, lambda: rng.uniform(-90, 90))
        kw["azim"] = _odd(rng, lambda: rng.uniform(-360, 360))
        kw["projection"] = rng.choice(["orthographic", "perspective"])
    c["kwargs"] = kw
    if c["call"] == "terrain" and rng.random() < 0.3:
        # a DEM in degrees (or, past the poles, not), its fly eye placed by fc.lonlat
        cell = rng.choice([1e-4, 1e-3, 0.05])
        lon0, lat0 = rng.uniform(-180, 179), rng.uniform(-92, 88)
        extent[:] = [lon0, lon0 + cell * (nx - 1), lat0, lat0 + cell * (ny - 1)]
        c["lonlat"] = [_odd(rng, lambda: rng.uniform(extent[0] - cell, extent[1] + cell)),
                       _odd(rng, lambda: rng.uniform(extent[2] - cell, extent[3] + cell))]
    if c["call"] == "fly":
        u0, u1, v0, v1 = (x if math.isfinite(x) else 0.0 for x in extent)
        def near(a, b):                 # (a coordinate on the map or beside it)
            return _odd(rng, lambda: rng.uniform(min(a, b) - 100, max(a, b) + 100))
        c["fly"] = {"position": [near(u0, u1), near(v0, v1)]
                    + ([_odd(rng, lambda: rng.uniform(-100, 3000))] if rng.random() < 0.3 else []),
                    "heading": _odd(rng, lambda: rng.uniform(-360, 360)),
                    "pitch": _odd(rng, lambda: rng.choice([rng.uniform(-89, 89)] * 8
                                                          + [-89.0, 89.0, 0.0, 90.0])),
                    "fov": _odd(rng, lambda: rng.choice([rng.uniform(1, 170)] * 8
                                                        + [1.0, 170.0, 0.5, 180.0])),
                    "size": kw.pop("size")}
        if rng.random() < 0.3:
            c["fly"]["above"] = _odd(rng, lambda: rng.uniform(0, 2000))
        if rng.random() < 0.2:
            c["fly"]["near"] = _odd(rng, lambda: rng.choice([1e-6, 1.0, 1e5]))
    if c["call"] == "flight":
        # fc.fly_through: 1 to 4 waypoints on the map or beside it (now and then all
        # (u, v, w), one repeated, or odd numbers), 1 to 3 frames
        u0, u1, v0, v1 = (x if math.isfinite(x) else 0.0 for x in extent)
        dim = 3 if rng.random() < 0.3 else 2
        path = [[_odd(rng, lambda: rng.uniform(min(u0, u1) - 100, max(u0, u1) + 100)),
                 _odd(rng, lambda: rng.uniform(min(v0, v1) - 100, max(v0, v1) + 100))]
                + ([_odd(rng, lambda: rng.uniform(-100, 3000))] if dim == 3 else [])
                for _ in range(rng.choice([1, 2, 2, 3, 4]))]
        if len(path) > 1 and rng.random() < 0.2:
            path[1] = list(path[0])
        if rng.random() < 0.05:
            path[0] = path[0][:2] if dim == 3 else path[0] + [1.0]     # mixed
        c["flight"] = {"path": path, "frames": rng.choice([1, 2, 3, 3, 0]),
                       "heading": rng.choice([None, None, _odd(rng, lambda: rng.uniform(
                           -360, 360))]),
                       "size": kw.pop("size")}
        if rng.random() < 0.3:
            c["flight"]["above"] = _odd(rng, lambda: rng.uniform(0, 2000))
        if rng.random() < 0.3:
            c["flight"]["look_ahead"] = _odd(rng, lambda: rng.uniform(0, 5000))
        if rng.random() < 0.2:
            c["flight"]["closed"] = True
    if rng.random() < 0.3:
        u0, u1, v0, v1 = (x if math.isfinite(x) else 0.0 for x in extent)
        c["objects"] = [[rng.choice(["tree", "pole", "box", "marker"]),
                         rng.uniform(min(u0, u1), max(u0, u1)),
                         rng.uniform(min(v0, v1), max(v0, v1)),
                         _odd(rng, lambda: rng.uniform(1, 500))]
                        for _ in range(rng.choice([1, 3]))]
    return {"terrain": c}


def _terrain_heights(c):
    import numpy as np
    rng = np.random.default_rng(c["seed"])
    ny, nx = c["shape"]
    kind = c["heights"]
    z = np.cumsum(np.cumsum(rng.normal(size=(ny, nx)), 0), 1) * 10.0
    if kind == "flat":
        z[:] = 123.0
    elif kind == "nan":
        z[:] = np.nan
    elif kind == "holes":
        z[rng.random((ny, nx)) < 0.2] = rng.choice([np.nan, np.inf, -np.inf])
    elif kind == "huge":
        z *= 1e300
    elif kind == "tiny":
        z *= 1e-300
    elif kind == "uint16":
        z = (np.abs(z) % 65535).astype(np.uint16)
    elif kind == "spikes":
        z[rng.random((ny, nx)) < 0.05] = 1e6
    return z


def _terrain_call(c):
    import floatcol as fc
    z = _terrain_heights(c)
    w, e, s, n = c["extent"]
    kw = dict(c["kwargs"])
    if isinstance(kw.get("size"), list):
        kw["size"] = tuple(kw["size"])
    exag = kw.pop("vert_exag", None)
    # (a box: width, depth and height all o[3])
    objects = [getattr(fc, o[0])(*(o[1:] + [o[3], o[3]] if o[0] == "box" else o[1:]))
               for o in c.get("objects", [])]
    if objects:
        kw["objects"] = objects
    if c["call"] == "terrain":
        if exag is not None:
            kw["vert_exag"] = exag
        if "lonlat" in c:
            at = fc.lonlat(fc.read_dem(z, extent=(w, e, s, n)), *c["lonlat"])
            kw["fly"] = dict(position=at, size=kw.pop("size"))
        return fc.terrain(z, extent=(w, e, s, n), **kw).draw()
    hf = fc.HeightField(z, u=(w, e), v=(n, s))          # rows north-up
    if c["call"] == "flight":
        fl = dict(c["flight"])
        fl["size"] = tuple(fl["size"])
        if exag is not None:
            kw["vert_exag"] = exag
        anim = fc.fly_through(hf, fl.pop("path"), progress=False, **fl, **kw)
        assert len(anim.frames) == len(anim.times) == c["flight"]["frames"]

        class _Last:                    # (the worker reads a picture's rgba)
            rgba = anim.frames[-1]
        return _Last
    if c["call"] == "fly":
        fly = dict(c["fly"])
        fly["size"] = tuple(fly["size"])
        cam = fc.fly(hf, fly.pop("position"), **fly)
        cam.update(kw)
        kw = cam
    return fc.render(hf, **kw)


#: the meshes of mesh_case: matplotlib's plot_surface(X, Y, Z) on grids of every kind
MESH_GRIDS = ["meshgrid", "uneven", "polar", "wound", "sphere", "scatter", "line", "collapsed"]


def mesh_case(rng: random.Random) -> dict:
    """A random plot_surface(X, Y, Z) (JSON-able; the worker makes the arrays from
    ``seed``): evenly and unevenly spaced grids, curvilinear ones (a polar grid, one
    wound round twice, a sphere's), scattered points, points on a line, all at one
    point; heights and coordinates now and then NaN, infinite or at the doubles'
    edges; facecolors, edge lines (or plot_wireframe's lines alone), a 3-D Axes."""
    sides = [1, 2, 3, 5, 17, 40]
    c = {"seed": rng.randrange(2 ** 31), "shape": [rng.choice(sides), rng.choice(sides)],
         "grid": rng.choice(MESH_GRIDS), "scale": rng.choice([1.0, 1.0, 1e-300, 1e300, 1e308, 1e6]),
         "odd": rng.random() < 0.3, "size": [rng.choice([1, 7, 60]), rng.choice([1, 9, 40])]}
    c["facecolors"] = rng.random() < 0.2
    c["edges"] = rng.random() < 0.2
    c["axes3d"] = rng.random() < 0.3
    c["trisurf"] = rng.random() < 0.2         # the points as plot_trisurf's scattered ones
    return {"mesh": c}


def _mesh_arrays(c):
    import numpy as np
    rng = np.random.default_rng(c["seed"])
    m, n = c["shape"]
    a, b = np.linspace(0, 1, n), np.linspace(0, 1, m)
    grid = c["grid"]
    if grid == "meshgrid":
        X, Y = np.meshgrid(a * 4 - 2, b * 3)
    elif grid == "uneven":
        X, Y = np.meshgrid(np.cumsum(rng.uniform(0.01, 1, n)), np.cumsum(rng.uniform(0.01, 1, m)))
    elif grid in ("polar", "wound"):
        R, P = np.meshgrid(a * 1.25, b * 2 * np.pi * (2 if grid == "wound" else 1))
        X, Y = R * np.cos(P), R * np.sin(P)
    elif grid == "sphere":
        U, V = np.meshgrid(a * 2 * np.pi, b * np.pi)
        X, Y = np.cos(U) * np.sin(V), np.sin(U) * np.sin(V)
    elif grid == "scatter":
        X, Y = rng.uniform(-1, 1, (m, n)), rng.uniform(-1, 1, (m, n))
    elif grid == "line":
        X = np.add.outer(b, a)
        Y = 2 * X
    else:
        X, Y = np.zeros((m, n)), np.zeros((m, n))
    X, Y = X * c["scale"], Y * c["scale"]
    Z = np.sin(3 * X) * np.cos(2 * Y) + rng.normal(0, 0.1, X.shape)
    if c["odd"]:
        for arr in (X, Y, Z):
            k = rng.random(arr.shape) < 0.1
            arr[k] = rng.choice([np.nan, np.inf, -np.inf, 1e300, -1e300], size=k.sum())
    return X, Y, Z


def _mesh_call(c):
    import numpy as np

    import floatcol as fc
    X, Y, Z = _mesh_arrays(c)
    kw = {"size": tuple(c["size"])}
    draw = fc.plot_surface
    if c.get("trisurf"):
        X, Y, Z = X.ravel(), Y.ravel(), Z.ravel()
        draw = fc.plot_trisurf
        c = dict(c, facecolors=False)
        if c["edges"]:
            kw.update(edgecolor="k", linewidth=0.5)
            c["edges"] = False
    if c["facecolors"]:
        kw["facecolors"] = np.random.default_rng(1).uniform(0, 1, Z.shape + (3,))
    if c["edges"]:
        kw.update(edgecolor="k", linewidth=0.5, rstride=2, cstride=2)
        if c["seed"] % 3 == 0 and not c["facecolors"]:     # the lines alone
            draw = fc.plot_wireframe
            del kw["edgecolor"]
    if c["axes3d"]:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig = plt.figure(figsize=(2, 1.5), dpi=50)
        ax = fig.add_subplot(projection="3d")
        try:
            p = draw(X, Y, Z, ax=ax, **kw)
            ax.scatter([0.0], [0.0], [0.0])
            ax.plot([0.0, 1.0], [0.0, 1.0], [0.0, 1.0])
            # mplot3d's own polygons through the surface (cut a pixel at a time)
            ax.bar3d([0.0], [0.0], [-1.0], 0.5, 0.5, [2.0])
            fig.canvas.draw()
            return p.render
        finally:
            plt.close(fig)
    return draw(X, Y, Z, **kw).draw()


def run_case(c: dict) -> dict:
    """Run one case here (the worker's side): its outcome and message."""
    import warnings

    import numpy as np

    import floatcol as fc
    kw = dict(c.get("kwargs", {}))
    for k in ("u", "v", "size", "aspect"):
        if isinstance(kw.get(k), list):
            kw[k] = tuple(kw[k])
    unraised = []                       # (exceptions raised inside compiled code)
    hook = sys.unraisablehook
    sys.unraisablehook = unraised.append
    # a draft case: drawn as a fresh install's picture is (passes/draft.py) where it can
    from floatcol import warmup
    drafting = warmup.drafting
    if c.get("draft") or c.get("terrain", {}).get("draft"):
        warmup.drafting = lambda *a: True
    try:
        out, caught = _run_call(c, kw, warnings, np, fc)
    finally:
        sys.unraisablehook = hook
        warmup.drafting = drafting
    messages = [out["message"]] + [str(w.message) for w in caught
                                   if not issubclass(w.category, DeprecationWarning)]
    for m in messages:
        if INTERNAL.search(m):
            out = {"outcome": "leak", "message": m}
    if unraised:
        first = unraised[0].exc_value
        out = {"outcome": "raised", "message": f"{len(unraised)} exceptions raised inside "
               f"compiled code, the first {type(first).__name__}: {first}"}
    return out


def _run_call(c, kw, warnings, np, fc):
    """(outcome, the warnings caught) of one case's call."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            if "terrain" in c:
                r = _terrain_call(c["terrain"])
            elif "mesh" in c:
                r = _mesh_call(c["mesh"])
            else:
                r = fc.render(c["expr"], **kw)
            rgba = r.rgba
            assert rgba.dtype == np.uint8 and rgba.shape[2] == 4
            out = {"outcome": "ok", "message": ""}
        except ValueError as exc:
            out = {"outcome": "value", "message": str(exc)}
        except Exception as exc:                     # noqa: BLE001 - the finding
            out = {"outcome": "other", "message": f"{type(exc).__name__}: {exc}"}
    return out, caught


def serve():
    """The worker's loop: a case per line on stdin, its outcome per line on stdout."""
    import floatcol  # noqa: F401 - load the kernels before the first case
    print(json.dumps({"ready": True}), flush=True)
    for line in sys.stdin:
        result = run_case(json.loads(line))
        print(json.dumps(result), flush=True)


class Worker:
    """A process that runs cases one after another; restarted after a crash or hang."""

    def __init__(self, timeout=60.0, env=None, preexec_fn=None):
        self.timeout = timeout
        self.env = env
        self.preexec_fn = preexec_fn    # (POSIX) run in the process before it starts
        self.proc = None
        self.on_start = None            # called with each process started

    def _start(self):
        here = os.path.dirname(os.path.abspath(__file__))
        env = dict(os.environ, **(self.env or {}))
        env["PYTHONPATH"] = here + os.pathsep + env.get("PYTHONPATH", "")
        # (in the repository's folder: a background job starts it while a test may have
        # made a temporary folder the current one, which is gone by the time it runs)
        self.proc = subprocess.Popen(
            [sys.executable, "-c", "import fuzzing; fuzzing.serve()"], stdin=subprocess.PIPE,
            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, env=env,
            preexec_fn=self.preexec_fn, cwd=os.path.dirname(here))
        if self.on_start is not None:
            self.on_start(self.proc)
        line = self._read(self.timeout * 4)
        if line is None or not json.loads(line).get("ready"):
            raise RuntimeError("the fuzz worker did not start")

    def _read(self, timeout):
        import selectors
        sel = selectors.DefaultSelector()
        sel.register(self.proc.stdout, selectors.EVENT_READ)
        ready = sel.select(timeout)
        sel.close()
        if not ready:
            return None
        return self.proc.stdout.readline() or None

    def run(self, c: dict) -> dict:
        if self.proc is None or self.proc.poll() is not None:
            self.close()
            self._start()
        try:
            self.proc.stdin.write(json.dumps(c) + "\n")
            self.proc.stdin.flush()
        except BrokenPipeError:
            pass
        line = self._read(self.timeout)
        if line is None:
            died = self.proc.poll() is not None
            code = self.proc.returncode
            self.close()
            if died:
                return {"outcome": "crash", "message": f"the worker died (exit {code})"}
            return {"outcome": "hang", "message": f"no answer in {self.timeout:g} s"}
        return json.loads(line)

    def close(self):
        if self.proc is not None:
            if self.proc.poll() is None:
                self.proc.kill()
            self.proc.wait()
            for pipe in (self.proc.stdin, self.proc.stdout):
                try:
                    pipe.close()        # (else a ResourceWarning when the suite ends)
                except (OSError, ValueError):
                    pass
            self.proc = None

"""Surfaces with holes (f NaN over part of the domain), in both projections.

A perspective sample whose Newton iteration fails scans its plane's line in Pi for
the surface, and a plane through a hole scans in vain; where the fit grid saw a hole,
the view's hole map (view.hole_map) lets the scan skip f where it is surely NaN. This
prints, per surface, projection and size: the render's best and median ms, f's
evaluations, and in perspective the same without the map (in the same process, the
two alternating: a shared machine's speed drifts), with the pictures compared (the
map must change none). Every render is warmed up (compiled) first.

    python benchmarks/bench_holes.py [REPEATS]
"""
import statistics
import sys
import time

import numpy as np

import os
os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc
from floatcol import view as view_mod

SURFACES = [("hemisphere", "sqrt(1 - u**2 - v**2)", 1.2),
            ("sqrt(u v)", "sqrt(u*v)", 2.0),
            ("log(u v)", "log(u*v)", 2.0),
            ("dome x waves", "sqrt(4 - u**2 - v**2)*sin(3*u)", 2.2),
            ("no holes: 3 sin(u cos v)", "3*sin(u*cos(v))", 5.0)]
SIZES = [(1920, 1080), (1024, 768)]


def _render(expr, d, size, projection, hole_map=True):
    saved = view_mod.hole_map
    if not hole_map:
        view_mod.hole_map = lambda *a: None
    try:
        t = time.perf_counter()
        r = fc.render(expr, u=(-d, d), v=(-d, d), size=size, projection=projection)
        return r, (time.perf_counter() - t) * 1e3
    finally:
        view_mod.hole_map = saved


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 7
    fc.render("u*v", size=(16, 12))
    print("| surface | projection | size | ms best / median | evaluations "
          "| without the map: ms best / median | evaluations | same picture |")
    print("|---|---|---|---|---|---|---|---|")
    for name, expr, d in SURFACES:
        for projection in ("orthographic", "perspective"):
            for size in SIZES:
                variants = (True, False) if projection == "perspective" else (True,)
                times = {v: [] for v in variants}
                last = {}
                for rep in range(repeats + 1):
                    for v in variants:
                        r, ms = _render(expr, d, size, projection, v)
                        if rep:
                            times[v].append(ms)
                        last[v] = r
                row = [name, projection, f"{size[0]}x{size[1]}",
                       f"{min(times[True]):.1f} / {statistics.median(times[True]):.1f}",
                       str(last[True].stats["samples"])]
                if False in times:
                    a, b = last[True], last[False]
                    same = all(np.array_equal(getattr(a, k), getattr(b, k), equal_nan=True)
                               for k in ("rgba", "side"))
                    row += [f"{min(times[False]):.1f} / {statistics.median(times[False]):.1f}",
                            str(b.stats["samples"]), "yes" if same else "NO"]
                else:
                    row += ["", "", ""]
                print("| " + " | ".join(row) + " |", flush=True)


if __name__ == "__main__":
    main()

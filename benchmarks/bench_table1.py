"""Gordon's Table 1 re-made: the eight configurations of Figs. 7-14 at 480x477.

The paper sampled 159 planes in 159 of the 477 pixel columns (ERRATA 8: every third
column); floatcol renders every column, with planes 3 pixels apart (``pixel_step=3``,
about 159 planes), so absolute counts differ by about 3x and the *ratios* are what
compare: supersampling raised the paper's counts 3.4x (Fig. 9 over Fig. 8) and 4.7x
(Fig. 14 over Fig. 13); Fig. 11 over Fig. 10 is 2.4x.

    python benchmarks/bench_table1.py
"""
import statistics
import time

import os
os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc

EXPR = "3*sin(u*cos(v))"
SIZE = (477, 480)                      # 477 columns, 480 lines
NEAR = dict(u=(-5, 5), v=(-5, 5), elev=30, azim=20)
BIRD = dict(u=(-7, 7), v=(-7, 7), elev=55, azim=20, focal_length=1.0)   # farther, wider
PAPER = {7: 25281, 8: 25281, 9: 86957, 10: 25281, 11: 61149, 12: 61533, 13: 61533, 14: 289575}
# the paper's corrections: ridge, intensity (1/16) and bump, supersampled 16x
SUPER = dict(corrections="supersample", detect=("ridge", "intensity", "bump"),
             supersample_rate=16, jump_threshold=1 / 16)
CONFIGS = [
    (7, "line, perspective", dict(NEAR, projection="perspective", method="horizon", lines=159)),
    (8, "iis, no corrections", dict(NEAR, projection="perspective", interpolation="intensity",
                                    corrections="none")),
    (9, "iis, supersampling", dict(NEAR, projection="perspective", interpolation="intensity",
                                   **SUPER)),
    (10, "nis, spline corrections", dict(NEAR, interpolation="normal", corrections="spline",
                                         detect=("ridge",))),
    (11, "nis, supersampling", dict(NEAR, interpolation="normal", corrections="supersample",
                                    detect=("ridge",))),
    (12, "line, bird's eye", dict(BIRD, projection="perspective", method="horizon", lines=159)),
    (13, "iis, no corrections", dict(BIRD, projection="perspective", interpolation="intensity",
                                     corrections="none")),
    (14, "iis, supersampling", dict(BIRD, projection="perspective", interpolation="intensity",
                                    **SUPER)),
]


def main():
    fc.render(EXPR, size=(32, 32))                                  # compile
    rows = {}
    print(f"{SIZE[0]} columns x {SIZE[1]} lines, planes 3 px apart, shading='lambert', "
          "placement='paper' (as the paper's figures)")
    print("| fig | method | samples | paper | ms (median of 5) |")
    print("|---|---|---|---|---|")
    for fig, label, opts in CONFIGS:
        kw = dict(size=SIZE, shading="lambert", pixel_step=3, placement="paper",
                  antialias=False, **opts)
        if kw.get("method") == "horizon":
            kw.pop("shading"), kw.pop("antialias")
        ts = []
        for _ in range(5):
            t = time.perf_counter()
            r = fc.render(EXPR, **kw)
            ts.append(time.perf_counter() - t)
        rows[fig] = r.stats["samples"]
        print(f"| {fig} | {label} | {rows[fig]} | {PAPER[fig]} | {statistics.median(ts) * 1e3:.1f} |")
    print("\n| ratio | floatcol | paper |")
    print("|---|---|---|")
    for a, b in ((9, 8), (11, 10), (14, 13)):
        print(f"| Fig. {a} / Fig. {b} | {rows[a] / rows[b]:.2f} | {PAPER[a] / PAPER[b]:.2f} |")


if __name__ == "__main__":
    main()

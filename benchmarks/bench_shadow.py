"""Shadows (Gordon 6.2, issue 28): cost and agreement.

    python benchmarks/bench_shadow.py

Prints (1) the cost of shadows at 1920x1080 and 1024x768: render time without and
with shadows=True (best and median of N after a warm-up), the shadow pass's own time
and the shadow texture's texels and memory; (2) the agreement of the lit/shadow state
with the reference ray caster's shadow rays (tests/reference.py) on surfaces, views and
lights that are not in tests/test_shadow.py, both projections.
"""
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
import floatcol as fc  # noqa: E402
from conftest import reference_for  # noqa: E402
from reference import numpy_surface, shadow_rays  # noqa: E402

EXPR = "3*sin(u*cos(v))"
DOM = dict(u=(-5, 5), v=(-5, 5))
N = 11


def timed_pair(**kw):
    """(best, median) ms without and with shadows, the two interleaved so that a drift
    of the machine's speed hits both alike; and the last render with shadows."""
    ts = ([], [])
    r = None
    for _ in range(N):
        for k, shadows in enumerate((False, True)):
            t = time.perf_counter()
            r1 = fc.render(EXPR, **DOM, **kw, shadows=shadows)
            ts[k].append(time.perf_counter() - t)
            if shadows:
                r = r1
    out = []
    for x in ts:
        x.sort()
        out += [x[0] * 1e3, x[N // 2] * 1e3]
    return (*out, r)


def cost():
    print("| size | projection | without ms (best / median) | with shadows ms | + % (best) "
          "| shadow lookup ms | texels | texture MiB |")
    print("|---|---|---|---|---|---|---|---|")
    for size in ((1920, 1080), (1024, 768)):
        for proj in ("orthographic", "perspective"):
            kw = dict(size=size, projection=proj, lightsource=(315, 35))
            fc.render(EXPR, **DOM, **kw, shadows=True)          # warm up
            b0, m0, b1, m1, r = timed_pair(**kw)
            texels = r.stats["shadow_texels"]
            print(f"| {size[0]}x{size[1]} | {proj} | {b0:.1f} / {m0:.1f} | {b1:.1f} / {m1:.1f} "
                  f"| {100 * (b1 / b0 - 1):+.0f} % | {r.stats['shadow_seconds'] * 1e3:.1f} "
                  f"| {texels} | {texels * 24 / 2**20:.1f} |")


CASES = [("2*exp(-((u-1)**2+v**2)) + exp(-((u+1.5)**2+(v-1)**2)/0.5)", (-4, 4), (-4, 4)),
         ("cos(u)*sin(v)*0.8 + 0.3*cos(3*u)", (-6, 6), (-6, 6)),
         ("u*v/2", (-2, 2), (-2, 2)),
         ("sqrt(4 - u**2 - v**2)", (-2, 2), (-2, 2)),
         ("0.5*sin(2*u) + 0.25*v**2", (-3, 3), (-2, 2))]
LIGHTS = [(300, 10), (200, 30), (60, 50), (10, 70)]


def agreement():
    print("\n| surface | projection | " + " | ".join(f"sun {a}/{b}" for a, b in LIGHTS) + " |")
    print("|---|---|" + "---|" * len(LIGHTS))
    worst = 1.0
    for expr, U, V in CASES:
        for proj in ("orthographic", "perspective"):
            row = []
            for az, alt in LIGHTS:
                kw = dict(size=(200, 150), projection=proj, elev=40, azim=-35)
                r = fc.render(expr, u=U, v=V, lightsource=(az, alt), shadows=True, **kw)
                ref = reference_for(r, expr, U, V, 40, -35, proj)
                rs = shadow_rays(numpy_surface(expr), ref, U, V, fc.Light.sun(az, alt).direction)
                both = (r.side != 0) & (ref.side == r.side)
                a = ((r.shadow[both] >= 0.5) == (rs[both] >= 0.5)).mean()
                worst = min(worst, a)
                row.append(f"{100 * a:.2f} %")
            print(f"| {expr} | {proj[:5]} | " + " | ".join(row) + " |")
    print(f"\nworst agreement: {100 * worst:.2f} %")


if __name__ == "__main__":
    cost()
    agreement()

"""Translucency and several surfaces (Gordon 6.5-6.6, issue 29): cost, layers, memory
and agreement.

    python benchmarks/bench_translucency.py [--quick]

Prints (1) the cost at 1920x1080 of 1, 2 and 4 surfaces, opaque against opacity 0.5
(best and median of N after a warm-up, interleaved so that a drift of the machine's
speed hits both alike), with the default shading's antialiasing (3 sub-columns) and
without; matplotlib's plot_surface(alpha=0.5) of a 200x200 mesh saved at the same size
for scale; (2) the histogram of layers per pixel and the memory of the lists; (3) the
agreement (PSNR of Render.intensity, shading="lambert") with the reference's
all-crossings ray caster (tests/reference.py composite_layers) on surfaces and views
that are not in tests/test_translucency.py, both projections.
"""
import io
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc  # noqa: E402
from reference import composite_layers, numpy_surface, psnr  # noqa: E402

EXPR = "3*sin(u*cos(v))"
DOM = (-5, 5)
SIZE = (1920, 1080)
QUICK = "--quick" in sys.argv
N = 3 if QUICK else 7


def _surfaces(n):
    return [(EXPR if k == 0 else f"{EXPR} + {0.8 * k}", DOM, DOM) for k in range(n)]


def timed(calls):
    """best and median ms of each call, interleaved."""
    ts = [[] for _ in calls]
    out = [None] * len(calls)
    for _ in range(N):
        for k, call in enumerate(calls):
            t = time.perf_counter()
            out[k] = call()
            ts[k].append(time.perf_counter() - t)
    return [(min(x) * 1e3, sorted(x)[len(x) // 2] * 1e3) for x in ts], out


def matplotlib_ms(n):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    x = np.linspace(*DOM, 200)
    X, Y = np.meshgrid(x, x)
    Z = 3 * np.sin(X * np.cos(Y))

    def draw():
        fig = plt.figure(figsize=(19.2, 10.8), dpi=100)
        ax = fig.add_subplot(projection="3d")
        for k in range(n):
            ax.plot_surface(X, Y, Z + 0.8 * k, cmap="viridis", alpha=0.5, linewidth=0,
                            antialiased=False)
        fig.savefig(io.BytesIO(), format="png")
        plt.close(fig)
    draw()
    ts = []
    for _ in range(max(N // 2, 1)):
        t = time.perf_counter()
        draw()
        ts.append(time.perf_counter() - t)
    return min(ts) * 1e3


def cost():
    print("## Cost at 1920x1080 (ms, best / median)\n")
    print("| surfaces | antialias | opaque | opacity 0.5 | ratio (best) | fps | "
          "matplotlib alpha=0.5 |")
    print("|---|---|---|---|---|---|---|")
    last = {}
    for n in (1, 2, 4):
        surfaces = _surfaces(n)
        mpl = matplotlib_ms(n)
        for aa in (None, False):
            def draw(op, s=surfaces, aa=aa):
                if len(s) == 1:
                    return fc.render(s[0][0], u=DOM, v=DOM, size=SIZE, opacity=op, antialias=aa)
                return fc.render_many(s, size=SIZE, opacity=op, antialias=aa)
            draw(1.0), draw(0.5)                             # warm up
            (o, t), (_, r) = timed([lambda: draw(1.0), lambda: draw(0.5)])
            label = "3 sub-columns" if aa is None else "off"
            print(f"| {n} | {label} | {o[0]:.0f} / {o[1]:.0f} | {t[0]:.0f} / {t[1]:.0f} | "
                  f"{t[0] / o[0]:.1f} | {1e3 / t[0]:.1f} | {mpl:.0f} |")
            last[(n, aa)] = r
    return last


def layers(last):
    print("\n## Layers per pixel and memory (1920x1080, opacity 0.5)\n")
    print("| surfaces | pixels with 0 / 1 / 2 / 3 / 4 / 5+ layers (%) | mean layers where "
          "any | records a surface | band columns | list memory MiB |")
    print("|---|---|---|---|---|---|")
    for n in (1, 2, 4):
        r = last[(n, False)]
        h = np.bincount(r.stats["layers"].ravel().astype(np.int64), minlength=6)
        h = np.r_[h[:5], h[5:].sum()] / h.sum() * 100
        seen = r.stats["layers"] > 0
        print(f"| {n} | {' / '.join(f'{x:.1f}' for x in h)} | "
              f"{r.stats['layers'][seen].mean():.2f} | {r.stats['records']} | "
              f"{r.stats['band_columns']} | {r.stats['list_bytes'] / 2**20:.1f} |")


UNSEEN = [
    # (surfaces [(expr, U, V, alpha)], elev, azim)
    ([("u**3 - 3*u*v**2", (-1, 1), (-1, 1), 0.5)], 35, 25),
    ([("0.4*sin(5*sqrt(u*u + v*v))", (-2, 2), (-2, 2), 0.4)], 40, -30),
    ([("cos(u*v)", (-3, 3), (-3, 3), 0.5)], 20, 60),
    ([("exp(-u*u)*sin(4*v)", (-2, 2), (-1.5, 1.5), 0.3)], 15, -10),
    ([("3*sin(u*cos(v))", (-5, 5), (-5, 5), 0.5)], 30, 30),
    # f and its Taylor polynomial at 0, intersecting
    ([("sin(u)*cos(v)", (-2, 2), (-2, 2), 0.5),
      ("u - u**3/6 - u*v**2/2", (-2, 2), (-2, 2), 0.5)], 25, -40),
    ([("exp(-u*u - v*v)", (-2, 2), (-2, 2), 0.6),
      ("0.5 + 0.2*u", (-2, 2), (-2, 2), 0.4),
      ("0.3*cos(2*v)", (-2, 2), (-2, 2), 0.5)], 30, 45),
]


def agreement():
    print("\n## Agreement with the all-crossings ray caster (PSNR dB, 160x120, lambert)\n")
    print("| surfaces | elev / azim | orthographic | perspective |")
    print("|---|---|---|---|")
    worst = np.inf
    cases = UNSEEN[:3] if QUICK else UNSEEN
    for surfaces, elev, azim in cases:
        row = []
        for proj in ("orthographic", "perspective"):
            layers = [fc.Layer(e, (U, V), fc.Material(shading="lambert", opacity=a))
                      for e, U, V, a in surfaces]
            r = fc.render_many(layers, size=(160, 120), elev=elev, azim=azim, projection=proj)
            vw = r.view
            kw = {} if proj == "orthographic" else dict(d1=vw.d1, d2=vw.d2)
            ref, _ = composite_layers([(numpy_surface(e), U, V, a) for e, U, V, a in surfaces],
                                      (160, 120), elev, azim, proj, scale=vw.scale,
                                      center=vw.center, **kw)
            p = psnr(r.intensity, ref)
            worst = min(worst, p)
            row.append(f"{p:.1f}")
        names = " + ".join(f"{e} (a={a})" for e, _, _, a in surfaces)
        print(f"| {names} | {elev} / {azim} | {row[0]} | {row[1]} |")
    print(f"\nworst: {worst:.1f} dB (goal >= 30)")


if __name__ == "__main__":
    last = cost()
    layers(last)
    agreement()

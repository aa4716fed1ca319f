"""Core engine timings: new views, new expressions, cold CLI, against matplotlib.

Run: python benchmarks/bench_core.py [--cold]   (prints tables; warm-up compiles first)

With --cold it first times the compile of a fresh install: a new process with an
empty Numba cache renders 1920x1080 orthographic, then perspective (about a minute).
"""
import io
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numba
import numpy as np

os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc

render_module = sys.modules["floatcol.render"]

DEMO = "3*sin(u*cos(v))"
DOM = dict(u=(-5, 5), v=(-5, 5))


def best_ms(fn, repeat=7):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append((time.perf_counter() - t) * 1e3)
    return min(times), statistics.median(times), out


COLD = """
import sys, time
t0 = time.perf_counter()
import floatcol as fc
t1 = time.perf_counter()
fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(1920, 1080))
t2 = time.perf_counter()
fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(1920, 1080), projection="perspective")
t3 = time.perf_counter()
print(f"{t1 - t0:.1f} {t2 - t1:.1f} {t3 - t2:.1f}")
"""


def cold_compile():
    """Seconds of a fresh install's first renders (import, orthographic, perspective),
    in a new process whose Numba cache is empty."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        out = subprocess.run([sys.executable, "-c", COLD], env=env, check=True,
                             capture_output=True, text=True).stdout.split()
    return [float(x) for x in out[-3:]]


def main():
    if "--cold" in sys.argv[1:]:
        imp, ortho, persp = cold_compile()
        print(f"Fresh install (empty Numba cache): import {imp:.1f} s, first render "
              f"(1920x1080 orthographic, compiles the kernels) {ortho:.1f} s, then "
              f"perspective {persp:.1f} s\n")
    threads = numba.get_num_threads()
    print(f"floatcol {fc.__version__}, numba {numba.__version__}, {threads} threads, {os.cpu_count()} cpus")
    # warm-up: compile or load every kernel once
    for m in ("column", "horizon"):
        for p in ("orthographic", "perspective"):
            fc.render(DEMO, size=(64, 48), method=m, projection=p, **DOM)

    print("\nNew view of the same expression (3 sin(u cos v), elev 30, azim 20, default quality)")
    print(f"{'size':>10} {'projection':>12} {'method':>8} {'samples':>9} {'best ms':>8} "
          f"{'median':>8} {'fps':>6} {'Msamples/s/core':>16}")
    for size in ((800, 600), (1024, 768), (1920, 1080)):
        for proj in ("orthographic", "perspective"):
            for method in ("column", "horizon"):
                best, med, r = best_ms(lambda: fc.render(DEMO, size=size, elev=30, azim=20,
                                                         projection=proj, method=method, **DOM))
                k = r.stats["kernel_seconds"]
                rate = r.stats["samples"] / k / threads / 1e6
                print(f"{size[0]}x{size[1]:<5} {proj:>12} {method:>8} {r.stats['samples']:>9} "
                      f"{best:>8.1f} {med:>8.1f} {1e3 / best:>6.1f} {rate:>16.2f}")

    print("\nNew expression, first render in a warm process (compiles f, f_u, f_v; from "
          f"{render_module.BATCH_MIN_SAMPLES} samples on, orthographic, also the batch evaluator)")
    fc.render("sin(u)*cos(v) + exp(-u*v)", size=(1920, 1080), **DOM)   # vmath loaded
    for size in ((800, 600), (1920, 1080)):
        times = []
        for k in range(5):
            expr = f"3*sin(u*cos(v)) + {k + 1}*exp(-(u**2+v**2)/{k + 2 + size[0]})"
            t = time.perf_counter()
            r = fc.render(expr, size=size, **DOM)
            times.append((time.perf_counter() - t) * 1e3)
        print(f"  {size[0]}x{size[1]}: best {min(times):.0f} ms, median "
              f"{statistics.median(times):.0f} ms over 5 new expressions "
              f"({r.stats['samples']} samples)")

    print("\nCold `floatcol render` (new process, import included, kernels cached on disk)")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "s.png")
        cold = []
        for _ in range(3):
            t = time.perf_counter()
            subprocess.run([sys.executable, "-m", "floatcol.cli", "render", DEMO, "--u=-5:5",
                            "--v=-5:5", "-o", out], check=True, capture_output=True)
            cold.append(time.perf_counter() - t)
    print(f"  best {min(cold):.2f} s, median {statistics.median(cold):.2f} s (800x600)")

    print("\nAgainst matplotlib plot_surface (PNG in memory, 800x600)")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def mpl(n):
        uu, vv = np.meshgrid(np.linspace(-5, 5, n), np.linspace(-5, 5, n))
        fig = plt.figure(figsize=(8, 6), dpi=100)
        ax = fig.add_subplot(projection="3d")
        ax.plot_surface(uu, vv, 3 * np.sin(uu * np.cos(vv)), rstride=1, cstride=1,
                        cmap="viridis", antialiased=False)
        buf = io.BytesIO()
        fig.savefig(buf, format="png")
        plt.close(fig)
    fl, _, _ = best_ms(lambda: fc.render(DEMO, size=(800, 600), **DOM).rgba, 5)
    print(f"  floatcol 800x600 column:            {fl:8.1f} ms")
    for n in (100, 400):
        m, _, _ = best_ms(lambda: mpl(n), 2)
        print(f"  matplotlib {n}x{n} mesh, savefig:   {m:8.1f} ms   ratio {m / fl:6.1f}x")


if __name__ == "__main__":
    main()

"""floatcol against what users use today, in one run on the same machine.

floatcol at 1920x1080 and 1024x768, default quality (corrections, antialiasing), in
both projections; matplotlib ``plot_surface`` of a 400x400 mesh saved to PNG at
1024x768; PyVista off-screen (optional: ``pip install -e .[bench]``) of the same mesh
at 1024x768 and 1920x1080, screenshot included (VTK renders with whatever OpenGL the
machine has: on a machine without a GPU, Mesa's software llvmpipe). Every tool is
warmed up first (Numba compilation, VTK context); times are medians (floatcol's best
too: a shared virtual machine's speed drifts, compare ratios within one run).

    python benchmarks/bench_speed.py
"""
import io
import os
import statistics
import time

import numba
import numpy as np

import floatcol as fc

EXPR = "3*sin(u*cos(v))"
DOM = dict(u=(-5, 5), v=(-5, 5))
MESH = 400


def _times_ms(fn, repeat):
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        ts.append((time.perf_counter() - t) * 1e3)
    return ts


def _median_ms(fn, repeat):
    return statistics.median(_times_ms(fn, repeat))


def _mesh():
    u = np.linspace(-5, 5, MESH)
    U, V = np.meshgrid(u, u)
    return U, V, 3 * np.sin(U * np.cos(V))


def matplotlib_ms(size):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    U, V, W = _mesh()

    def once():
        fig = plt.figure(figsize=(size[0] / 100, size[1] / 100), dpi=100)
        ax = fig.add_subplot(projection="3d")
        ax.plot_surface(U, V, W, cmap="viridis", rstride=1, cstride=1, linewidth=0,
                        antialiased=False)
        ax.view_init(30, -110)
        fig.savefig(io.BytesIO(), format="png")
        plt.close(fig)
    once()
    return _median_ms(once, 3)


def pyvista_ms(size):
    try:
        import pyvista as pv
    except ImportError:
        return None
    U, V, W = _mesh()
    grid = pv.StructuredGrid(U, V, W)
    grid["w"] = W.ravel(order="F")
    pl = pv.Plotter(off_screen=True, window_size=list(size))
    pl.add_mesh(grid, scalars="w", cmap="viridis", show_scalar_bar=False)
    pl.camera.elevation = 30
    pl.screenshot(return_img=True)                 # warm-up: context and upload

    def once():
        pl.camera.azimuth += 1.0                    # a new view, as floatcol's
        pl.render()                                 # (screenshot alone may reuse the last frame)
        pl.screenshot(return_img=True)
    ms = _median_ms(once, 10)
    # a new surface each time (a new expression): mesh upload included
    def fresh():
        p2 = pv.Plotter(off_screen=True, window_size=list(size))
        p2.add_mesh(pv.StructuredGrid(U, V, W), cmap="viridis", show_scalar_bar=False)
        p2.screenshot(return_img=True)
        p2.close()
    fresh()
    ms_fresh = _median_ms(fresh, 3)
    pl.close()
    return ms, ms_fresh


def eval_ns():
    """ns per sample for f, f_u and f_v of EXPR together (one fused compiled function,
    sympy cse), on one thread, through the kernels' own evaluation path."""
    from floatcol.kernels.sample import eval_grid
    s = fc.as_surface(EXPR)
    n = 500_000
    rng = np.random.default_rng(1)
    u = rng.uniform(-5, 5, n)
    v = rng.uniform(-5, 5, n)
    out = np.empty((n, 3))
    eval_grid(*s.kernel_args(), u[:10], v[:10], out[:10])
    return _median_ms(lambda: eval_grid(*s.kernel_args(), u, v, out), 5) * 1e6 / n


def main():
    print(f"{os.cpu_count()} cpus, {numba.get_num_threads()} numba threads")
    print(f"f, f_u, f_v of {EXPR}: {eval_ns():.0f} ns per sample (one thread)")
    fc.render(EXPR, size=(64, 48), **DOM)
    fc.render(EXPR, size=(64, 48), projection="perspective", **DOM)
    print("\n| tool | size | projection | samples | median ms | fps | best ms |")
    print("|---|---|---|---|---|---|---|")
    ours = {}
    for size in ((1920, 1080), (1024, 768)):
        for proj in ("orthographic", "perspective"):
            r = fc.render(EXPR, size=size, projection=proj, **DOM)
            ts = _times_ms(lambda: fc.render(EXPR, size=size, projection=proj, **DOM), 9)
            ms = statistics.median(ts)
            ours[size, proj] = ms
            print(f"| floatcol | {size[0]}x{size[1]} | {proj} | {r.stats['samples']} | {ms:.1f} | "
                  f"{1000 / ms:.1f} | {min(ts):.1f} |")
    mpl = matplotlib_ms((1024, 768))
    print(f"| matplotlib plot_surface {MESH}x{MESH}, savefig PNG | 1024x768 | persp | "
          f"{MESH * MESH} vertices | {mpl:.0f} | {1000 / mpl:.2f} | |")
    pv_res = {}
    for size in ((1024, 768), (1920, 1080)):
        res = pyvista_ms(size)
        if res is None:
            print("| PyVista | - | not installed (pip install -e .[bench]) | | | | |")
            break
        pv_res[size] = res
        print(f"| PyVista {MESH}x{MESH}, new view + screenshot | {size[0]}x{size[1]} | persp | "
              f"{MESH * MESH} vertices | {res[0]:.1f} | {1000 / res[0]:.1f} | |")
        print(f"| PyVista {MESH}x{MESH}, new mesh + screenshot | {size[0]}x{size[1]} | persp | "
              f"{MESH * MESH} vertices | {res[1]:.1f} | {1000 / res[1]:.1f} | |")
    print("\n| ratio | value |")
    print("|---|---|")
    for proj in ("orthographic", "perspective"):
        print(f"| matplotlib 1024x768 / floatcol 1024x768 {proj} | {mpl / ours[(1024, 768), proj]:.1f}x |")
    for size, (view_ms, fresh_ms) in pv_res.items():
        ms = ours[size, "perspective"]
        print(f"| PyVista new view / floatcol persp, {size[0]}x{size[1]} | {view_ms / ms:.2f}x |")
        print(f"| PyVista new mesh / floatcol persp, {size[0]}x{size[1]} | {fresh_ms / ms:.2f}x |")


if __name__ == "__main__":
    main()

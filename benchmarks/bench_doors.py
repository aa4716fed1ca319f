"""The doors' timings: live re-renders in a matplotlib Axes, savefig, animation, gallery.

Run: python benchmarks/bench_doors.py   (prints tables; warm-up compiles first)

The interactive figure: an 8 x 6 inch figure at 100 dpi whose Axes fill it, so each
draw renders 800 x 600 pixels. A "drag" re-render is one mouse-motion event (new
azimuth): the artist asks for draw_idle, which on Agg draws the whole figure at once
(a GUI backend does the same draw on its next idle tick), so the time covers the
render and matplotlib's own drawing. Each timed step is checked to render once.
"""
import os
import statistics
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numba  # noqa: E402
from matplotlib.backend_bases import MouseEvent  # noqa: E402

import floatcol as fc  # noqa: E402

DEMO = "3*sin(x*cos(y))"
RNG = (("x", -5, 5), ("y", -5, 5))


def _event(fig, name, x, y, **kw):
    fig.canvas.callbacks.process(name, MouseEvent(name, fig.canvas, x, y, button=1, **kw))


def interactive(proj, n=30):
    fig = plt.figure(figsize=(8, 6), dpi=100)
    ax = fig.add_axes((0, 0, 1, 1))
    plot = fc.plot_surface(DEMO, *RNG, ax=ax, interactive=True, proj_type=proj)
    fig.canvas.draw()
    bb = ax.bbox
    x0, y0 = bb.x0 + 100, bb.y0 + 300
    _event(fig, "button_press_event", x0, y0)
    drag = []
    for k in range(1, n + 1):
        before = plot.render
        t = time.perf_counter()
        _event(fig, "motion_notify_event", x0 + 3 * k, y0 + k)   # draw_idle draws
        drag.append(time.perf_counter() - t)
        assert plot.render is not before
    assert plot.render.stats["step"] > 1.5 / plot.render.view.scale
    _event(fig, "button_release_event", x0 + 3 * n, y0 + n)
    full = []
    for k in range(n // 3):
        t = time.perf_counter()
        plot.view_init(azim=plot.azim + 2)
        fig.canvas.draw()
        full.append(time.perf_counter() - t)
    shape = plot.render.rgba.shape
    plt.close(fig)
    return shape, drag, full


def main():
    print(f"floatcol {fc.__version__}, numba {numba.__version__}, "
          f"{numba.get_num_threads()} threads, {os.cpu_count()} cpus")
    for proj in ("ortho", "persp"):                           # warm-up
        interactive(proj, n=3)

    print("\nLive re-renders in a matplotlib Axes (3 sin(x cos y), Agg draw included)")
    print(f"{'projection':>10} {'pixels':>9} {'mode':>13} {'median ms':>10} {'best ms':>8} {'renders/s':>10}")
    for proj in ("ortho", "persp"):
        shape, drag, full = interactive(proj)
        for mode, ts in (("drag (3 px)", drag), ("full quality", full)):
            med = statistics.median(ts) * 1e3
            print(f"{proj:>10} {shape[1]}x{shape[0]:<5} {mode:>13} {med:>10.1f} "
                  f"{min(ts) * 1e3:>8.1f} {1e3 / med:>10.1f}")

    print("\nsavefig of a figure with one floatcol Axes (8 x 6 in)")
    print(f"{'dpi':>5} {'pixels':>11} {'best ms':>8}")
    fig = plt.figure(figsize=(8, 6))
    ax = fig.add_axes((0, 0, 1, 1))
    plot = fc.plot_surface(DEMO, *RNG, ax=ax)
    with tempfile.TemporaryDirectory() as d:
        for dpi in (100, 200, 300):
            ts = []
            for _ in range(3):
                t = time.perf_counter()
                fig.savefig(os.path.join(d, "f.png"), dpi=dpi)
                ts.append(time.perf_counter() - t)
            sh = plot.render.rgba.shape
            print(f"{dpi:>5} {sh[1]:>5}x{sh[0]:<5} {min(ts) * 1e3:>8.1f}")
    plt.close(fig)

    print("\nanimate: 60 frames of a circular wave, 480 x 360, GIF")
    with tempfile.TemporaryDirectory() as d:
        t = time.perf_counter()
        anim = fc.animate("exp(-(x^2 + y^2)/10) * cos(2*sqrt(x^2 + y^2) - t)", ("x", -6, 6),
                          ("y", -6, 6), frames=60, size=(480, 360), progress=False,
                          output=os.path.join(d, "w.gif"))
        total = time.perf_counter() - t
    print(f"  render {anim.stats['seconds']:.2f} s ({60 / anim.stats['seconds']:.1f} frames/s), "
          f"with GIF encoding {total:.2f} s")

    from floatcol.gallery import build
    with tempfile.TemporaryDirectory() as d:
        t = time.perf_counter()
        res = build(d, progress=False)
        print(f"\ngallery build: {len(res.examples)} examples in {time.perf_counter() - t:.1f} s "
              f"({len(res.failed)} failed)")


if __name__ == "__main__":
    main()

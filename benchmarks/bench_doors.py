"""The doors' timings: live re-renders in a matplotlib Axes, savefig, animation, gallery.

Run: python benchmarks/bench_doors.py   (prints tables; warm-up compiles first)

The interactive figures: 8 x 6 and 19.2 x 10.8 inches at 100 dpi whose Axes fill
them, so each draw renders 800 x 600 or 1920 x 1080 pixels (full screen). A "drag"
re-render is one mouse-motion event (new azimuth): the artist asks for draw_idle,
which on Agg draws the whole figure at once (a GUI backend does the same draw on its
next idle tick), so the time covers the render and matplotlib's own drawing. Each
timed step is checked to render once. The drag's frames are previews whose
resolution adapts to take about mpl.PREVIEW_SECONDS (its first frames find it);
"release" is the full-quality frame after the button is let go. The 3-D Axes rows
are mplot3d's own rotation (its button held, then a new view and a draw) with the
same surface as a plot_surface(X, Y, Z) on a 3-D Axes, axes and panes drawn.
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

os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc  # noqa: E402

DEMO = "3*sin(x*cos(y))"
RNG = (("x", -5, 5), ("y", -5, 5))


def _event(fig, name, x, y, **kw):
    fig.canvas.callbacks.process(name, MouseEvent(name, fig.canvas, x, y, button=1, **kw))


def interactive(proj, n=30, size=(800, 600)):
    fig = plt.figure(figsize=(size[0] / 100, size[1] / 100), dpi=100)
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
    shrunk = plot.render.rgba.shape
    t = time.perf_counter()
    _event(fig, "button_release_event", x0 + 3 * n, y0 + n)
    release = [time.perf_counter() - t]
    assert plot.render.rgba.shape[:2] == (size[1], size[0])
    full = []
    for k in range(n // 3):
        t = time.perf_counter()
        plot.view_init(azim=plot.azim + 2)
        fig.canvas.draw()
        full.append(time.perf_counter() - t)
    plt.close(fig)
    return shrunk, drag[3:], release, full


def axes3d(proj, n=30, size=(800, 600)):
    import numpy as np
    fig = plt.figure(figsize=(size[0] / 100, size[1] / 100), dpi=100)
    ax = fig.add_subplot(projection="3d", proj_type=proj)
    x = np.linspace(-5, 5, 200)
    X, Y = np.meshgrid(x, x)
    plot = fc.plot_surface(X, Y, 3 * np.sin(X * np.cos(Y)), ax=ax, cmap="viridis")
    fig.canvas.draw()
    ax.button_pressed = ax._rotate_btn[0]
    drag = []
    for k in range(1, n + 1):
        before = plot.render
        t = time.perf_counter()
        ax.view_init(30 + k * 0.3, -60 + k)
        fig.canvas.draw()
        drag.append(time.perf_counter() - t)
        assert plot.render is not before
    shrunk = plot.render.rgba.shape
    ax.button_pressed = None
    t = time.perf_counter()
    plot.artist.on_release(None)                 # draw_idle: Agg draws at once
    release = [time.perf_counter() - t]
    assert not plot.artist.preview
    full = []
    for k in range(n // 3):
        t = time.perf_counter()
        ax.view_init(30, -60 + 2 * k)
        fig.canvas.draw()
        full.append(time.perf_counter() - t)
    plt.close(fig)
    return shrunk, drag[3:], release, full


def empty_axes3d(proj, n=10, size=(800, 600)):
    """mplot3d's own drawing: the same 3-D Axes and limits, nothing in it."""
    fig = plt.figure(figsize=(size[0] / 100, size[1] / 100), dpi=100)
    ax = fig.add_subplot(projection="3d", proj_type=proj)
    ax.set_xlim(-5, 5)
    ax.set_ylim(-5, 5)
    ax.set_zlim(-3, 3)
    fig.canvas.draw()
    ts = []
    for k in range(n):
        t = time.perf_counter()
        ax.view_init(30 + k * 0.3, -60 + k)
        fig.canvas.draw()
        ts.append(time.perf_counter() - t)
    plt.close(fig)
    return ts


def main():
    print(f"floatcol {fc.__version__}, numba {numba.__version__}, "
          f"{numba.get_num_threads()} threads, {os.cpu_count()} cpus")
    for proj in ("ortho", "persp"):                           # warm-up
        interactive(proj, n=4)
        axes3d(proj, n=4)

    print("\nLive re-renders in matplotlib (3 sin(x cos y), Agg draw included)")
    print("| Axes | size | projection | mode | picture | median ms | best ms | frames/s |")
    print("|---|---|---|---|---|---|---|---|")
    for size in ((800, 600), (1920, 1080)):
        for name, fn in (("2-D, interactive=True", interactive), ("3-D (mplot3d)", axes3d)):
            for proj in ("ortho", "persp"):
                shrunk, drag, release, full = fn(proj, size=size)
                for mode, ts, pic in (("drag", drag, f"{shrunk[1]}x{shrunk[0]}"),
                                      ("release", release, "full"),
                                      ("full quality", full, "full")):
                    med = statistics.median(ts) * 1e3
                    print(f"| {name} | {size[0]}x{size[1]} | {proj} | {mode} | {pic} | "
                          f"{med:.1f} | {min(ts) * 1e3:.1f} | {1e3 / med:.1f} |")
        ts = empty_axes3d("ortho", size=size)
        med = statistics.median(ts) * 1e3
        print(f"| 3-D (mplot3d), empty: its own axes, panes, ticks | {size[0]}x{size[1]} | ortho "
              f"| new view | - | {med:.1f} | {min(ts) * 1e3:.1f} | {1e3 / med:.1f} |")

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

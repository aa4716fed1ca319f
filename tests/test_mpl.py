"""The matplotlib artist: re-rendered at the Axes' true pixel size on every draw."""
import io
import math

import matplotlib
import numpy as np
import pytest
from PIL import Image

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.backend_bases import MouseEvent  # noqa: E402

import floatcol as fc  # noqa: E402

EXPR = "3*sin(x*cos(y))"
RNG = (("x", -5, 5), ("y", -5, 5))


@pytest.fixture
def fig_ax():
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_axes((0.1, 0.1, 0.6, 0.8))
    yield fig, ax
    plt.close(fig)


def _png(fig, **kw):
    buf = io.BytesIO()
    fig.savefig(buf, format="png", **kw)
    return np.asarray(Image.open(buf))


def test_savefig_renders_at_the_axes_pixel_size(fig_ax):
    fig, ax = fig_ax
    plot = fc.plot_surface(EXPR, *RNG, ax=ax)
    for dpi in (100, 300):
        out = _png(fig, dpi=dpi)
        w, h = round(0.6 * 4 * dpi), round(0.8 * 3 * dpi)
        assert plot.render.rgba.shape == (h, w, 4)
        # the figure holds the render pixel for pixel (no resampling): the Axes
        # occupies rows/columns from its bbox; compare where the surface is
        x0 = round(0.1 * 4 * dpi)
        y0 = out.shape[0] - round(0.1 * 3 * dpi) - h
        region = out[y0:y0 + h, x0:x0 + w, :3].astype(int)
        mine = plot.render.rgba[..., :3].astype(int)
        seen = plot.render.side != 0
        assert (np.abs(region - mine).max(axis=2)[seen] <= 1).mean() > 0.999


def test_resize_gives_a_new_render_size(fig_ax):
    fig, ax = fig_ax
    plot = fc.plot_surface(EXPR, *RNG, ax=ax)
    fig.canvas.draw()
    assert plot.render.rgba.shape[:2] == (240, 240)
    fig.set_size_inches(8, 2)
    fig.canvas.draw()
    assert plot.render.rgba.shape[:2] == (160, 480)


def test_vector_output_embeds_a_full_resolution_image(fig_ax, tmp_path):
    fig, ax = fig_ax
    plot = fc.plot_surface(EXPR, *RNG, ax=ax)
    fig.savefig(tmp_path / "f.pdf", dpi=200)
    assert plot.render.rgba.shape[:2] == (480, 480)
    assert (tmp_path / "f.pdf").read_bytes()[:4] == b"%PDF"


def test_colorbar_shows_the_height_colormap(fig_ax):
    fig, ax = fig_ax
    plot = fc.plot_surface(EXPR, *RNG, ax=ax, cmap="magma", vmin=-3, vmax=3)
    cb = fig.colorbar(plot)
    assert cb.mappable is plot and cb.cmap.name == "magma"
    assert (cb.vmin, cb.vmax) == (-3, 3)
    fig.canvas.draw()
    plot.set_clim(-1, 1)                       # a ScalarMappable change re-colours
    assert plot.artist.stale
    before = plot.render.rgba.copy()
    fig.canvas.draw()
    assert cb.vmin == -1
    assert not np.array_equal(before, plot.render.rgba)


def _mouse(fig, name, x, y, button=1, step=0):
    ev = MouseEvent(name, fig.canvas, x, y, button=button, step=step)
    fig.canvas.callbacks.process(name, ev)


def test_interactive_drag_rotates_and_scroll_zooms(fig_ax):
    fig, ax = fig_ax
    plot = fc.plot_surface(EXPR, *RNG, ax=ax, interactive=True)
    fig.canvas.draw()
    first = plot.render
    bb = ax.bbox
    cx, cy = bb.x0 + bb.width / 2, bb.y0 + bb.height / 2
    _mouse(fig, "button_press_event", cx, cy)
    _mouse(fig, "motion_notify_event", cx + bb.width / 4, cy)      # a quarter: 45 degrees
    assert plot.azim == pytest.approx(-60 - 45)
    fig.canvas.draw()
    drag = plot.render
    assert drag.view.azim != first.view.azim
    _mouse(fig, "button_release_event", cx + bb.width / 4, cy)
    fig.canvas.draw()
    final = plot.render
    # while dragging the planes are DRAG_PIXEL_STEP pixels apart: fewer samples (in
    # the preview's pixels: it may be rendered smaller, as the frames' time says)
    from floatcol.mpl import DRAG_PIXEL_STEP
    assert drag.stats["step"] * drag.stats["scale"] == pytest.approx(
        DRAG_PIXEL_STEP * final.stats["step"] * final.stats["scale"], rel=1e-9)
    assert drag.stats["samples"] < 0.7 * final.stats["samples"]
    assert final.view.azim == drag.view.azim
    _mouse(fig, "scroll_event", cx, cy, button="up", step=2)
    fig.canvas.draw()
    assert plot.render.view.scale == pytest.approx(final.view.scale * 1.1 ** 2, rel=1e-9)


def test_the_scroll_wheels_zoom_stays_finite(fig_ax):
    """A scroll event of 1e9 steps overflowed the zoom (1.1 ** 1e9: OverflowError in the
    callback; a stream of large ones reached infinity): one event counts at most
    ZOOM_STEPS_MAX steps and the zoom stays within ZOOM_LIMIT, and the picture draws."""
    from floatcol.mpl import ZOOM_LIMIT, ZOOM_PER_STEP, ZOOM_STEPS_MAX
    fig, ax = fig_ax
    plot = fc.plot_surface(EXPR, *RNG, ax=ax, interactive=True)
    fig.canvas.draw()
    # (the events' own redraws left out: the Agg canvas draws at once on each, 41
    # pictures and 6 s of the suite; the picture is drawn below at each extreme)
    fig.canvas.draw_idle = lambda *a, **k: None
    bb = ax.bbox
    cx, cy = bb.x0 + bb.width / 2, bb.y0 + bb.height / 2
    _mouse(fig, "scroll_event", cx, cy, button="up", step=1e9)
    assert plot.zoom == pytest.approx(ZOOM_PER_STEP ** ZOOM_STEPS_MAX)
    for _ in range(10):
        _mouse(fig, "scroll_event", cx, cy, button="up", step=1e9)
    assert plot.zoom == ZOOM_LIMIT
    fig.canvas.draw()
    assert (plot.render.side != 0).all()          # (the surface fills the picture)
    for _ in range(30):
        _mouse(fig, "scroll_event", cx, cy, button="down", step=-1e9)
    assert plot.zoom == 1 / ZOOM_LIMIT
    fig.canvas.draw()


def test_cursor_data_is_the_surface_point(fig_ax):
    fig, ax = fig_ax
    plot = fc.plot_surface("x + 2*y", ("x", -1, 1), ("y", -1, 1), ax=ax, proj_type="ortho")
    fig.canvas.draw()
    r = plot.render
    rows, cols = np.nonzero(r.side > 0)
    i = len(rows) // 2
    bb = ax.bbox
    ev = MouseEvent("motion_notify_event", fig.canvas, bb.x0 + (cols[i] + 0.5),
                    bb.y1 - (rows[i] + 0.5))
    u, v, w = plot.artist.get_cursor_data(ev)
    assert w == pytest.approx(u + 2 * v, abs=1e-4)
    assert "w=" in plot.artist.format_cursor_data((u, v, w))


def test_preview_resolution_follows_the_frames_time():
    """_Preview: no shrink for a frame that renders in time, more for a slower one,
    never beyond MAX_SHRINK; the first frame of a full-screen drag starts at half."""
    from floatcol.mpl import FIRST_SHRINK_PIXELS, MAX_SHRINK, PREVIEW_SECONDS, _Preview
    p = _Preview()
    assert p.shrink(800, 600) == 1 and p.shrink(1920, 1080) == 2
    assert 800 * 600 <= FIRST_SHRINK_PIXELS < 1920 * 1080
    p.took(PREVIEW_SECONDS / 2, 1920 * 1080)           # half the budget at full size
    assert p.shrink(1920, 1080) == 1
    p = _Preview()
    p.took(4 * PREVIEW_SECONDS, 1920 * 1080)           # 4x over: half each way
    assert p.shrink(1920, 1080) == 2
    p.took(400 * PREVIEW_SECONDS, 1920 * 1080)         # far over (a loaded machine)
    assert p.shrink(1920, 1080) == MAX_SHRINK


@pytest.mark.parametrize("scale", [None, 30.0])
def test_a_shrunk_preview_shows_the_same_view(scale):
    """A drag's preview rendered f times smaller and enlarged covers the canvas where
    the full-quality frame of the same view does (with the plot's own scale too)."""
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_axes((0, 0, 1, 1))
    opts = {} if scale is None else {"scale": scale}
    plot = fc.plot_surface(EXPR, *RNG, ax=ax, interactive=True, **opts)
    art = plot.artist
    bb = ax.bbox
    _mouse(fig, "button_press_event", bb.x0 + 10, bb.y0 + 10)
    art._preview.seconds_per_pixel = 1.0                  # as slow as can be: MAX_SHRINK
    fig.canvas.draw()
    from floatcol.mpl import MAX_SHRINK
    assert plot.render.rgba.shape[:2] == (300 // MAX_SHRINK, 400 // MAX_SHRINK)
    preview = np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()
    _mouse(fig, "button_release_event", bb.x0 + 10, bb.y0 + 10)
    fig.canvas.draw()
    assert plot.render.rgba.shape[:2] == (300, 400)
    full = np.asarray(fig.canvas.buffer_rgba())[..., :3]
    a, b = (preview != 255).any(-1), (full != 255).any(-1)
    assert a.sum() > 0.1 * a.size
    assert (a & b).sum() / (a | b).sum() > 0.9          # measured 0.933, 0.919 (its 4x4 blocks)
    plt.close(fig)


def test_a_pickled_figure_draws_the_same_and_stays_interactive(fig_ax):
    """A figure with a floatcol plot pickles (and deep-copies): the surface is made
    again from its expression, and the copy draws the same pixels; its mouse handlers
    are connected to the copy's canvas at its first draw, so a drag still turns it."""
    import copy
    import pickle
    fig, ax = fig_ax
    plot = fc.plot_surface(EXPR, *RNG, ax=ax, interactive=True)
    fig.canvas.draw()
    before = np.asarray(fig.canvas.buffer_rgba()).copy()
    for other in (pickle.loads(pickle.dumps(fig)), copy.deepcopy(fig)):
        other.canvas.draw()
        assert np.array_equal(np.asarray(other.canvas.buffer_rgba()), before)
        oax = other.axes[0]
        oplot = oax.images[0].plot
        assert oplot is not plot and oplot.surface.expr == plot.surface.expr
        bb = oax.bbox
        cx, cy = bb.x0 + bb.width / 2, bb.y0 + bb.height / 2
        _mouse(other, "button_press_event", cx, cy)
        _mouse(other, "motion_notify_event", cx + bb.width / 4, cy)
        assert oplot.azim == pytest.approx(-60 - 45) and plot.azim == pytest.approx(-60)
        _mouse(other, "button_release_event", cx + bb.width / 4, cy)
        plt.close(other)


def _bump(x, y):
    return math.exp(-x * x - y * y)


def test_surfaces_pickle_as_what_they_were_made_of():
    """An expression's surface (at a time, stretched by a box), a Python function's
    and a height field pickle and come back evaluating the same values; one made of
    compiled functions alone says what to give instead."""
    import pickle

    import floatcol.surface as S
    wave = fc.as_surface("sin(u*v - t)", time="t").at(0.7).scaled(2.0, 1.0, 3.0)
    func = fc.as_surface(_bump)
    z = np.arange(12.0).reshape(3, 4)
    z[1, 2] = np.nan
    hf = fc.HeightField(z, u=(4, 0), v=(0, 2))  # (u descending: flipped, kept ascending)
    hf.resampled = True
    u = np.linspace(0.1, 3.9, 7)
    v = np.linspace(0.1, 1.9, 7)
    for s in (wave, func, hf):
        back = pickle.loads(pickle.dumps(s))
        assert np.array_equal(back.evaluate(u, v), s.evaluate(u, v), equal_nan=True)
        assert back.default_domain == s.default_domain
    assert np.allclose(wave.evaluate(u, v), 3 * np.sin(u / 2 * v - 0.7))
    assert pickle.loads(pickle.dumps(hf)).resampled
    bare = S.Surface(wave.f, wave.fg)
    with pytest.raises(TypeError, match="expression or a Python function"):
        pickle.dumps(bare)

"""A floatcol surface inside an ordinary matplotlib Axes.

:class:`SurfaceImage` is an AxesImage that renders its SurfacePlot again at the
Axes' true pixel size each time the figure is drawn, so a resized window or
``savefig(dpi=300)`` gets a sharp picture of that size, never a resampled one. With
``interactive=True`` a mouse drag turns the view (elev/azim, as Axes3D does) and the
scroll wheel zooms; while the button is held the picture is a preview: sampling planes
``DRAG_PIXEL_STEP`` pixels apart, no corrections or antialiasing, and a resolution
that drops (down to 1 / MAX_SHRINK of the Axes' each way, its pixels enlarged) until
a frame renders in about PREVIEW_SECONDS (_Preview: measured on the frames before,
so a loaded machine gets coarser frames rather than fewer); at full quality on
release. A GUI backend's draw_idle draws once for the events queued since the last
draw: frames are dropped, never queued.
"""
from __future__ import annotations

import math

import numpy as np
from matplotlib.artist import Artist
from matplotlib.image import AxesImage

DRAG_PIXEL_STEP = 3.0
ZOOM_PER_STEP = 1.1
#: the scroll wheel's zoom stays within 1 / ZOOM_LIMIT .. ZOOM_LIMIT of the fitted view;
#: one event counts at most ZOOM_STEPS_MAX steps
ZOOM_LIMIT = 1e6
ZOOM_STEPS_MAX = 50
#: A drag's preview frame should render in about this many seconds (with
#: matplotlib's own drawing, 30 frames a second at 1920x1080 on 2 cores)
PREVIEW_SECONDS = 0.012
#: ... at no less than 1 / MAX_SHRINK of the Axes' resolution each way
MAX_SHRINK = 4
#: The first preview of a drag larger than this many pixels starts at half resolution
FIRST_SHRINK_PIXELS = 600_000


def legend_entries(plot, ax):
    """The plot's entries in ``ax.legend()``: one, or one a surface where its label is
    a list (plot_surface([f, g], label=["f", "g"])). Each is an empty rectangle (it
    draws nothing and takes no room in the limits: matplotlib skips a patch of no
    size) that carries a label and a colour (SurfacePlot.legend_colour), as mplot3d's
    surface is a Poly3DCollection whose legend entry is a patch of its first face's
    colour. A label that is empty or begins with an underscore keeps it out of the
    legend, as matplotlib's. In a 3-D Axes they are Patch3Ds (Axes3D.draw projects
    every patch); there they also count as data for ``ax.has_data()``, which mplot3d's
    later calls (ax.plot, ax.scatter) read to keep the surface's limits."""
    from matplotlib.patches import Rectangle
    entries = []
    for _ in plot.labels():
        entry = Rectangle((0.0, 0.0), 0.0, 0.0, linewidth=0.0)
        entry.set_in_layout(False)     # (tight_layout and bbox_inches="tight" skip it)
        ax.add_artist(entry)
        if getattr(ax, "name", "") == "3d":
            from mpl_toolkits.mplot3d import art3d
            art3d.patch_2d_to_3d(entry)
        entries.append(entry)
    update_entries(entries, plot)
    return entries


def update_entries(entries, plot):
    """The legend entries' labels, colours and visibility as the plot's now."""
    for k, (entry, label) in enumerate(zip(entries, plot.labels())):
        entry.set_label(label if label else "_floatcol surface")
        entry.set_facecolor(plot.legend_colour(k))
        entry.set_visible(plot.get_visible())


class _Preview:
    """The resolution of a drag's preview frames: each frame's render time per pixel
    (averaged with the frames before) says how far the next must shrink to take
    PREVIEW_SECONDS."""

    def __init__(self):
        self.seconds_per_pixel = None

    def shrink(self, W, H):
        """The factor (1 to MAX_SHRINK) by which a W x H preview shrinks each way."""
        if self.seconds_per_pixel is None:
            return 2 if W * H > FIRST_SHRINK_PIXELS else 1
        f = math.sqrt(W * H * self.seconds_per_pixel / PREVIEW_SECONDS)
        return int(min(max(math.ceil(f - 0.1), 1), MAX_SHRINK))

    def took(self, seconds, pixels):
        s = seconds / max(pixels, 1)
        old = self.seconds_per_pixel
        self.seconds_per_pixel = s if old is None else 0.5 * (old + s)


def _shrunk(size, f):
    """A size shrunk f times each way (rounded up: the enlarged picture covers it)."""
    return max(1, -(-size[0] // f)), max(1, -(-size[1] // f))


def _enlarged(rgba, f):
    """Each pixel of rgba an f x f block."""
    return rgba if f == 1 else np.repeat(np.repeat(rgba, f, axis=0), f, axis=1)


def _remove_entries(art):
    for entry in art.entries:
        if entry.axes is not None:
            entry.remove()
    art.entries = []


def _show_entries(art, b):
    for entry in getattr(art, "entries", ()):
        entry.set_visible(b)


class SurfaceImage(AxesImage):
    """The artist of a :class:`floatcol.plot.SurfacePlot` drawn into an Axes."""

    def __init__(self, ax, plot):
        super().__init__(ax, interpolation="none", origin="upper", resample=False)
        self.plot = plot
        self._drag = None
        self._cids = []
        self._canvas = None       # the canvas the mouse handlers are connected to
        self._preview = _Preview()
        self.entries = []         # the legend's entries (legend_entries)

    def set_visible(self, b):
        super().set_visible(b)
        _show_entries(self, b)

    def __getstate__(self):
        # (a pickled figure gets a new canvas: draw connects the handlers to it)
        return {**super().__getstate__(), "_canvas": None}

    @classmethod
    def attach(cls, plot, ax, interactive=False):
        art = cls(ax, plot)
        art.set_extent((*ax.get_xlim(), *ax.get_ylim()))
        plot.artist = art
        ax.add_image(art)
        ax.set_axis_off()
        art.entries = legend_entries(plot, ax)
        if interactive:
            art.connect_events()
        return art

    def remove(self):
        """Out of its Axes (Artist.remove), with its legend entry and mouse handlers."""
        if self._cids:
            self.disconnect_events()
        _remove_entries(self)
        super().remove()

    def pixel_size(self, renderer):
        """The Axes' size in output pixels for this renderer (vector backends
        embed images at the figure's dpi, which image_magnification gives)."""
        bb = self.axes.bbox
        mag = renderer.get_image_magnification()
        return max(1, int(round(bb.width * mag))), max(1, int(round(bb.height * mag)))

    def draw(self, renderer):
        if self._cids and self._canvas is not self.axes.figure.canvas:
            self.connect_events()     # (a new canvas: an unpickled or copied figure's)
        if not self.get_visible():
            return
        size = self.pixel_size(renderer)
        bb = self.axes.bbox
        if renderer.get_image_magnification() == 1.0 and self.get_alpha() is None:
            # a raster canvas: the render is already the Axes' pixels, so put it
            # there directly (matplotlib's resampling would only copy it); a drag's
            # preview is rendered smaller and its pixels enlarged
            f = self._preview.shrink(*size) if self._drag is not None else 1
            self.plot.shrink = f
            try:
                small = _shrunk(size, f)
                r = self.plot.draw(small)
            finally:
                self.plot.shrink = 1
            if self._drag is not None:
                self._preview.took(r.stats["seconds"], small[0] * small[1])
            rgba = _enlarged(r.rgba, f)[:size[1], :size[0]]
            gc = renderer.new_gc()
            gc.set_clip_rectangle(bb)
            renderer.draw_image(gc, int(round(bb.x0)), int(round(bb.y0)), rgba[::-1])
            gc.restore()
            self.stale = False
            return
        r = self.plot.draw(size)
        x0, x1 = self.axes.get_xlim()
        y0, y1 = self.axes.get_ylim()
        # set the data without the stale callbacks: this is the draw itself
        self._A = r.rgba
        self._imcache = None
        self.set_extent((x0, x1, y0, y1))
        super().draw(renderer)

    def get_window_extent(self, renderer=None):
        return self.axes.bbox

    def to_canvas(self, col, row):
        """Canvas points of the last picture's pixel coordinates (it fills the Axes)."""
        bb = self.axes.bbox
        H, W = self.plot.render.side.shape
        return (bb.x0 + (col + 0.5) * bb.width / W, bb.y1 - (row + 0.5) * bb.height / H)

    def get_cursor_data(self, event):
        """The surface point under the mouse: (u, v, w), or None over background."""
        r = self.plot.render
        if r is None or event.x is None:
            return None
        bb = self.axes.bbox
        H, W = r.side.shape
        c = int((event.x - bb.x0) / bb.width * W)
        row = int((bb.y1 - event.y) / bb.height * H)
        if not (0 <= c < W and 0 <= row < H) or r.side[row, c] == 0:
            return None
        return float(r.u[row, c]), float(r.v[row, c]), float(r.w[row, c])

    def format_cursor_data(self, data):
        if data is None:
            return ""
        names = self.plot.surface.variables
        return f"{names[0]}={data[0]:.4g}, {names[1]}={data[1]:.4g}, w={data[2]:.4g}"

    # -- interaction ----------------------------------------------------------------
    def connect_events(self):
        canvas = self.axes.figure.canvas
        self._canvas = canvas
        self._cids = [canvas.mpl_connect(name, fn) for name, fn in (
            ("button_press_event", self.on_press),
            ("motion_notify_event", self.on_motion),
            ("button_release_event", self.on_release),
            ("scroll_event", self.on_scroll))]

    def disconnect_events(self):
        canvas = self.axes.figure.canvas
        for cid in self._cids:
            canvas.mpl_disconnect(cid)
        self._cids = []

    def on_press(self, event):
        if event.inaxes is not self.axes or event.button != 1:
            return
        self._drag = (event.x, event.y, self.plot.elev, self.plot.azim)
        self.plot.pixel_step = DRAG_PIXEL_STEP

    def on_motion(self, event):
        if self._drag is None or event.x is None:
            return
        x0, y0, elev0, azim0 = self._drag
        bb = self.axes.bbox
        # as Axes3D: a drag across the Axes turns the view by 180 degrees
        self.plot.view_init(elev=elev0 - (event.y - y0) / bb.height * 180.0,
                            azim=azim0 - (event.x - x0) / bb.width * 180.0)
        self.axes.figure.canvas.draw_idle()

    def on_release(self, event):
        if self._drag is None:
            return
        self._drag = None
        self.plot.pixel_step = None
        self.stale = True
        self.axes.figure.canvas.draw_idle()

    def on_scroll(self, event):
        if event.inaxes is not self.axes:
            return
        # (a wheel's steps are small, but a stream of them or a driver's huge one must
        # not overflow the zoom to infinity: it stays within ZOOM_LIMIT either way)
        step = min(max(float(event.step), -ZOOM_STEPS_MAX), ZOOM_STEPS_MAX)
        self.plot.zoom = min(max(self.plot.zoom * ZOOM_PER_STEP ** step, 1.0 / ZOOM_LIMIT),
                             ZOOM_LIMIT)
        self.stale = True
        self.axes.figure.canvas.draw_idle()


class Surface3DImage(Artist):
    """The artist of a SurfacePlot drawn into matplotlib's own 3-D Axes
    (``fig.add_subplot(projection="3d")``): everything mplot3d draws stays (panes,
    grid, ticks, labels, title, limits, box aspect), and the surface is rendered on
    every draw with the Axes' camera, so that it lies exactly where mplot3d would draw
    the same mesh. Its camera, from the Axes (``axes_camera``): the limits' box
    stretched to the box aspect (render's ``box``) about its centre, matplotlib's
    view angles, and in perspective the eye where mplot3d puts it (``_dist`` times the
    focal length from the box's centre); the scale and the picture's place on the
    canvas are fitted on the box's eight corners, which mplot3d's projection and
    floatcol's View then put on the same pixels (to 1e-12 of a pixel). While
    mplot3d's mouse rotation drags, the picture is a lighter preview."""

    def __init__(self, ax, plot):
        super().__init__()
        self.axes = ax
        self.plot = plot
        self.set_zorder(1)
        self.set_clip_box(ax.bbox)
        self.preview = False      # whether the last picture was a drag's preview
        self._preview = _Preview()
        self.placed = None        # T (2, 3) of the last picture: pixel (col, row) at the
                                  # canvas point T @ (col, row, 1) (axes_camera)
        self._drawn_M = None      # the Axes' projection (ax.M) of the last picture
        self._canvas = None       # the canvas on_release is connected to, and its id
        self._cid = None
        self.entries = []         # the legend's entries (legend_entries)

    def __getstate__(self):
        return {**super().__getstate__(), "_canvas": None, "_cid": None}  # (SurfaceImage's)

    def _connect(self):
        """on_release on the figure's canvas (again, where it is a new one)."""
        canvas = self.axes.figure.canvas
        if self._canvas is not canvas:
            self._canvas = canvas
            self._cid = canvas.mpl_connect("button_release_event", self.on_release)

    def remove(self):
        """Out of its Axes (Artist.remove), with its legend entry and its handler."""
        if self._canvas is not None and self._cid is not None:
            self._canvas.mpl_disconnect(self._cid)
        self._canvas = self._cid = None
        _remove_entries(self)
        super().remove()

    def drawn_for(self, ax):
        """Whether the last picture was drawn with ``ax``'s present projection."""
        return (self.get_visible() and self.plot.render is not None
                and self._drawn_M is not None and getattr(ax, "M", None) is not None
                and np.array_equal(self._drawn_M, ax.M))

    @classmethod
    def attach(cls, plot, ax):
        art = cls(ax, plot)
        plot.artist = art
        ax.add_artist(art)
        # mplot3d draws nothing on release: the last frame would stay the preview
        art._connect()
        art.set_clip_path(ax.patch)
        (ua, ub), (va, vb) = plot._items()[0][1]
        for others in plot._items()[1:]:
            (a, b), (c, d) = others[1]
            ua, ub, va, vb = min(ua, a), max(ub, b), min(va, c), max(vb, d)
        # z: the heights (vmin/vmax and a colour field's range colour them only)
        lo, hi = plot.w_range()
        ax.auto_scale_xyz([ua, ub], [va, vb], [lo, hi], had_data=ax.has_data())
        # mplot3d's own calls after this one (ax.plot, ax.scatter) keep the data limits
        # only where ax.has_data(), which counts lines, collections, patches and images,
        # not this artist: the legend's entries, patches that draw nothing, stand for
        # the surface there (else a line at y = 0 took the y limits down to 0 -+ 0.04)
        art.entries = legend_entries(plot, ax)
        return art

    def get_window_extent(self, renderer=None):
        return self.axes.bbox

    def set_visible(self, b):
        super().set_visible(b)
        _show_entries(self, b)

    def to_canvas(self, col, row):
        """Canvas points of the last picture's pixel coordinates."""
        T = self.placed
        return (T[0, 0] * col + T[0, 1] * row + T[0, 2],
                T[1, 0] * col + T[1, 1] * row + T[1, 2])

    def draw(self, renderer):
        self._connect()               # (a new canvas: an unpickled or copied figure's)
        if not self.get_visible():
            return
        ax = self.axes
        # The Axes' floatcol surfaces (several fc.plot_surface calls) hide one another
        # a pixel at a time: the first of them renders each with the one camera and
        # draws their composite by depth (fc.composite); the others draw nothing
        group = [a for a in sorted(ax.artists, key=lambda a: a.get_zorder())
                 if isinstance(a, Surface3DImage) and a.get_visible()]
        if group[0] is not self:
            self.stale = False
            return
        vector = _raster_of(renderer) is None and hasattr(renderer, "start_rasterizing")
        if self._draw_group(renderer, group, vector):
            return
        # a vector file (PDF, SVG, EPS: matplotlib's MixedModeRenderer) where mplot3d's
        # polygons cross the surface: the picture and what is drawn with it (the
        # artists' hidden parts, the crossing polygons cut a pixel at a time) go into
        # the file as one image at the figure's dpi, as matplotlib draws a rasterized
        # artist (set_rasterized); the rest of every artist stays vector
        renderer.start_rasterizing()
        try:
            # (its raster renderer, where this Matplotlib's layout is known; else the
            # mixed renderer itself, which hands the drawing to it all the same)
            inner = _raster_of(renderer)
            self._draw_group(renderer if inner is None else inner, group)
        finally:
            renderer.stop_rasterizing()

    def _draw_group(self, renderer, group, vector=False):
        """Render the surfaces of ``group`` and draw their picture and the
        depth-tested artists' parts that go with it; with ``vector`` (a vector file's
        renderer, not rasterizing), False, drawing nothing, where mplot3d's polygons
        cross the surface (DepthTested.cross), which a raster canvas draws."""
        ax = self.axes
        mag = renderer.get_image_magnification()
        bb = ax.bbox
        W = max(1, int(round(bb.width * mag)))
        H = max(1, int(round(bb.height * mag)))
        preview = getattr(ax, "button_pressed", None) in getattr(ax, "_rotate_btn", ())
        # a preview: rendered f times smaller each way (its pixels f times larger)
        f = self._preview.shrink(W, H) if preview and mag == 1.0 else 1
        kw, T, size = axes_camera(self.plot, ax, *_shrunk((W, H), f), mag / f)
        renders = []
        view_limits = (ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d())
        limits = [view_limits if a.plot.axlim_clip else None for a in group]
        together = len(group) > 1 and any(a.plot.translucent() for a in group) and not \
            any(a.plot.options.get("objects") for a in group[1:])
        try:
            for a in group:
                a.plot.pixel_step = DRAG_PIXEL_STEP if preview else None
            if together:                  # one scene: every layer shows through (plot.py)
                from .plot import draw_together
                renders = [draw_together([a.plot for a in group], size, kw, limits)]
            else:
                renders = [a.plot.draw_with(size, kw, lim) for a, lim in zip(group, limits)]
        finally:
            for a in group:
                a.plot.pixel_step = None
        for a in group:
            a.preview = preview
            a.placed = T
            a._drawn_M = np.array(ax.M, copy=True)
        if len(renders) == 1:
            r = renders[0]
        else:
            from .passes.composite import composite
            r = composite(renders, background=(0, 0, 0, 0))
        if preview:
            self._preview.took(sum(x.stats["seconds"] for x in renders), size[0] * size[1])
        # mplot3d's own artists: what the surfaces hide drawn under their picture (the
        # composite's depth is the nearest surface's), the rest over it when they draw
        depth_test_mplot3d_artists(ax)
        tested = [a.draw for a in sorted(ax.get_children(), key=lambda a: a.get_zorder())
                  if isinstance(a.__dict__.get("draw"), DepthTested) and
                  a.get_zorder() >= self.get_zorder()]
        for d in tested:
            d.cross(renderer, r, vector)      # (polygons through the surface: below)
        if vector and any(d.crosses() for d in tested):
            return False
        for d in tested:
            d.draw_hidden(renderer, [r])
        m = mag / f
        gc = renderer.new_gc()
        gc.set_clip_rectangle(bb)
        if abs(T[0, 1]) <= 1e-12 * abs(T[0, 0]):
            # pixel (col, row) centred at the canvas point (ox + col / m, oy - row / m);
            # a picture reflected onto the canvas (an inverted axis) flipped first
            rgba, D = _enlarged(r.rgba, f), T.copy()
            for axis, sign in ((0, 1.0), (1, -1.0)):
                if D[axis, axis] * sign < 0.0:
                    rgba = np.flip(rgba, 1 - axis)
                    D[:, 2] += D[:, axis] * (size[axis] - 1)
                    D[:, axis] *= -1.0
            renderer.draw_image(gc, D[0, 2] - 0.5 / m, D[1, 2] - (size[1] - 0.5) / m,
                                np.ascontiguousarray(rgba[::-1]))
        else:                                     # a roll: the picture turned onto the Axes
            x0, y0 = int(np.floor(bb.x0)), int(np.floor(bb.y0))
            renderer.draw_image(gc, x0, y0, _turned(r.rgba, T, x0, y0, W, H, m)[::-1])
        gc.restore()
        for d in tested:                      # polygons through the surface, a pixel
            d.draw_crossing(renderer, T)      # at a time
        self.stale = False
        return True


    def on_release(self, event):
        """After a drag drawn as previews, the picture at full quality."""
        if self.preview:
            self.preview = False
            self.stale = True
            self.axes.figure.canvas.draw_idle()


def _turned(rgba, T, x0, y0, W, H, mag):
    """The picture mapped by T (pixel -> canvas) onto W x H pixels whose lower left is
    the canvas point (x0, y0): each pixel centre mapped back, bilinear in premultiplied
    colour."""
    iy, ix = np.mgrid[0:H, 0:W]
    x = x0 + (ix + 0.5) / mag
    y = y0 + (H - 1 - iy + 0.5) / mag
    M = T[:, :2]
    inv = np.linalg.inv(M)
    col = inv[0, 0] * (x - T[0, 2]) + inv[0, 1] * (y - T[1, 2])
    row = inv[1, 0] * (x - T[0, 2]) + inv[1, 1] * (y - T[1, 2])
    src = rgba.astype(np.float64) / 255.0
    src[..., :3] *= src[..., 3:]
    h, w = rgba.shape[:2]
    c0 = np.floor(col).astype(int)
    r0 = np.floor(row).astype(int)
    fc_, fr = col - c0, row - r0
    out = np.zeros((H, W, 4))
    for dr, wr in ((0, 1.0 - fr), (1, fr)):
        for dc, wc in ((0, 1.0 - fc_), (1, fc_)):
            rr, cc = r0 + dr, c0 + dc
            ok = (rr >= 0) & (rr < h) & (cc >= 0) & (cc < w)
            out[ok] += (wr * wc)[ok][:, None] * src[rr[ok], cc[ok]]
    a = out[..., 3:]
    out[..., :3] = np.where(a > 0, out[..., :3] / np.maximum(a, 1e-12), 0.0)
    return np.clip(np.round(out * 255.0), 0, 255).astype(np.uint8)


def axes_camera(plot, ax, W, H, mag=1.0):
    """(render keywords, T, the picture's size): the camera of a 3-D Axes as
    Surface3DImage describes, and T (2, 3) the map of a pixel (col, row, 1) of the
    picture to its canvas point (a turn by the Axes' roll, a scale 1 / mag)."""
    from mpl_toolkits.mplot3d import proj3d

    from .plot import mpl_to_paper_angles
    (x0, x1), (y0, y1), (z0, z1) = ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()
    # (with another vertical axis mplot3d keeps the box's proportions rolled: its
    # get_proj's box_aspect)
    ba = np.roll(np.asarray(ax._box_aspect, dtype=float), getattr(ax, "_vertical_axis", 2) - 2)
    box = (ba[0] / abs(x1 - x0), ba[1] / abs(y1 - y0), ba[2] / abs(z1 - z0))
    center = ((x0 + x1) / 2.0, (y0 + y1) / 2.0, (z0 + z1) / 2.0)
    elev, azim = mpl_to_paper_angles(*_z_up_angles(ax))
    # An inverted axis (ax.invert_zaxis(), limits high to low) shows the data mirrored
    # in it: S W seen from the Axes' eye is W seen from the mirrored eye S C, whose
    # view direction is S d (u: azim -> -azim, v: azim -> 180 - azim, w: elev -> -elev)
    # and whose picture is a proper camera's up to a turn and, for an odd number of
    # inverted axes, a reflection (_fit finds which)
    if x1 < x0:
        azim = -azim
    if y1 < y0:
        azim = 180.0 - azim
    if z1 < z0:
        elev = -elev
    kw = dict(elev=elev, azim=azim, box=box, center=center)
    if ax._focal_length == np.inf:
        kw["projection"] = "orthographic"
    else:
        d3 = ax._dist * ax._focal_length
        kw.update(projection="perspective", d1=0.05 * d3, d2=0.95 * d3)
    cx, cy, cz = (a.ravel() for a in np.meshgrid([x0, x1], [y0, y1], [z0, z1]))
    xs, ys, _ = proj3d.proj_transform(cx, cy, cz, ax.M)
    disp = ax.transData.transform(np.column_stack([xs, ys])) * mag
    # (a roll, or another vertical axis, turns the picture: it must cover the Axes'
    # diagonal)
    turned = (getattr(ax, "roll", 0.0) or getattr(ax, "_vertical_axis", 2) != 2
              or not -90.0 <= ax.elev <= 90.0)
    base = (W, H) if not turned else (int(np.ceil(np.hypot(W, H))),) * 2
    # One fit, at the base size: the picture drawn at any other size with the scale
    # s times the fit's is the same projection about the same centre pixel, the
    # view's centre (the camera's d1, d2 and centre are given): pixel (col, row) of a
    # picture of size (W1, H1) is the fit's (cW + (col - cW1) / s, cH + (row - cH1) /
    # s), whose canvas point (times mag) is A (col0, row0, 1)
    A, trial_scale = _fit(plot, kw, base, (cx, cy, cz), box, disp)
    s = float(np.hypot(A[0, 0], A[0, 1]))
    kw["scale"] = s * trial_scale
    cW, cH = (base[0] - 1) / 2.0, (base[1] - 1) / 2.0
    bb = ax.bbox
    # the picture must cover the Axes: as much larger as its centre is off theirs
    mx = abs(A[0, 0] * cW + A[0, 1] * cH + A[0, 2] - (bb.x0 + bb.width / 2.0) * mag)
    my = abs(A[1, 0] * cW + A[1, 1] * cH + A[1, 2] - (bb.y0 + bb.height / 2.0) * mag)
    size = (base[0] + 2 * int(np.ceil(mx)) + 2, base[1] + 2 * int(np.ceil(my)) + 2)
    cW1, cH1 = (size[0] - 1) / 2.0, (size[1] - 1) / 2.0
    T = np.column_stack([A[:, 0] / s, A[:, 1] / s,
                         A[:, 0] * (cW - cW1 / s) + A[:, 1] * (cH - cH1 / s) + A[:, 2]]) / mag
    return kw, T, size


def _z_up_angles(ax):
    """matplotlib's (elev, azim) of the Axes' eye as seen with z up, elev within
    [-90, 90]. mplot3d puts its eye at np.roll((cos e cos a, cos e sin a, sin e),
    vertical_axis - 2) in the box (its get_proj), with any elev (a drag over the top
    takes it past 90: the view upside down): that direction's angles about z; the
    picture it makes is the Axes' up to a turn, which _fit finds."""
    va = getattr(ax, "_vertical_axis", 2)
    if va == 2 and -90.0 <= ax.elev <= 90.0:
        return ax.elev, ax.azim
    e, a = np.radians(ax.elev), np.radians(ax.azim)
    d = np.roll([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)], va - 2)
    return (float(np.degrees(np.arcsin(np.clip(d[2], -1.0, 1.0)))),
            float(np.degrees(np.arctan2(d[1], d[0]))))


def _fit(plot, kw, size, corners, box, disp):
    """(A (2, 3), the fit's scale): the similarity that puts a corner's pixel (col,
    row) in the picture of ``size`` render_view fits (at its own scale) on its canvas
    point disp, x = a col + b row + dx, y = b col - a row + dy (b = 0 without a roll);
    or, where an odd number of the Axes' axes are inverted, the reflection x = a col
    + b row + dx, y = a row - b col + dy: whichever puts the corners nearer."""
    from .plot import render_view
    cx, cy, cz = corners
    (x0, x1), (y0, y1) = (cx.min(), cx.max()), (cy.min(), cy.max())
    view, _ = render_view(plot.surface, dict(kw, size=size, u=(x0, x1), v=(y0, y1)))
    col, row = view.project(cx * box[0], cy * box[1], cz * box[2])
    n = len(col)
    rhs = np.r_[disp[:, 0], disp[:, 1]]
    best = None
    for flip in (1.0, -1.0):
        M = np.vstack([np.column_stack([col, row, np.ones(n), np.zeros(n)]),
                       np.column_stack([-row * flip, col * flip, np.zeros(n), np.ones(n)])])
        (a, b, dx, dy), *_ = np.linalg.lstsq(M, rhs, rcond=None)
        err = float(np.sum((M @ np.array([a, b, dx, dy]) - rhs) ** 2))
        if best is None or err < best[0]:
            best = (err, np.array([[a, b, dx], [b * flip, -a * flip, dy]]))
    return best[1], view.scale


class OccludedObjects(Artist):
    """Points (markers) or a polyline in the surface's coordinates, drawn over the
    surface's picture where they lie in front of it and hidden where it lies in front
    of them (Gordon 6.1's z-buffer test against the render's depth, Szenberg's objects
    on a terrain): mplot3d draws its own scatter and plot over or under a whole
    surface, never through it. ``SurfacePlot.scatter`` and ``SurfacePlot.plot`` make
    them; ``visible`` says, after a draw, which points (or line samples) were shown."""

    def __init__(self, plot, xyz, kind, style):
        super().__init__()
        self.plot = plot
        self.xyz = np.asarray(xyz, dtype=float)
        _check_style(kind, style, len(self.xyz))
        self.kind = kind                  # "points", "line" or "text"
        self.text = ""
        self.style = style
        self.visible = None
        self.set_zorder(plot.artist.get_zorder() + 1.5)

    def _samples(self, view, box):
        """The points, or the line's points about a pixel apart."""
        if self.kind != "line":
            return self.xyz
        return pixel_samples(view, box, self.xyz)[0]

    def draw(self, renderer):
        from matplotlib.collections import PathCollection
        from matplotlib.lines import Line2D
        from matplotlib.markers import MarkerStyle
        from matplotlib.transforms import IdentityTransform
        r = self.plot.render
        art = self.plot.artist
        if r is None or art is None or not self.get_visible():
            return
        box = r.box
        with np.errstate(invalid="ignore", over="ignore"):   # (points far off: not shown)
            pts = self._samples(r.view, box)
            self.visible = visible_points(r, pts, box)
            col, row = r.view.project(pts[:, 0] * box[0], pts[:, 1] * box[1],
                                      pts[:, 2] * box[2])
            x, y = art.to_canvas(col, row)
        xy = np.column_stack([x, y])
        if self.kind == "text":
            from matplotlib.text import Text
            if self.visible[0]:
                t = Text(x[0], y[0], self.text, transform=IdentityTransform(), **self.style)
                t.set_figure(self.axes.figure)
                t.draw(renderer)
        elif self.kind == "points":
            st = dict(self.style)
            marker = MarkerStyle(st.pop("marker", "o"))
            size = st.pop("s", 20.0)
            color = st.pop("c", st.pop("color", "k"))
            coll = PathCollection([marker.get_path().transformed(marker.get_transform())],
                                  sizes=np.broadcast_to(np.asarray(size, float), len(pts))[
                                      self.visible],
                                  offsets=xy[self.visible], offset_transform=IdentityTransform(),
                                  facecolors=_per_point(color, self.visible), **st)
            coll.set_figure(self.axes.figure)
            coll.set_clip_box(self.axes.bbox)
            coll.draw(renderer)
        else:
            run = np.where(self.visible, 0, 1).cumsum()     # the visible runs
            for k in np.unique(run[self.visible]):
                part = xy[self.visible & (run == k)]
                if len(part) < 2:
                    continue
                line = Line2D(part[:, 0], part[:, 1], transform=IdentityTransform(),
                              **self.style)
                line.set_figure(self.axes.figure)
                line.set_clip_box(self.axes.bbox)
                line.draw(renderer)
        self.stale = False


def pixel_samples(view, box, p):
    """(samples, at): the polyline p (n, 3) in the surface's units sampled about a
    pixel apart in ``view``'s picture (every vertex a sample: p[k] at samples[at[k]], to
    rounding)."""
    if len(p) < 2:
        return p, np.arange(len(p))
    with np.errstate(invalid="ignore", over="ignore"):
        col, row = view.project(p[:, 0] * box[0], p[:, 1] * box[1], p[:, 2] * box[2])
        steps = np.nan_to_num(np.hypot(np.diff(col), np.diff(row)), nan=1.0)
    n = np.clip(np.ceil(steps), 1, 4096).astype(int)
    ends = np.cumsum(n)
    k = np.repeat(np.arange(len(n)), n)                 # each sample's segment
    t = ((np.arange(ends[-1]) - (ends - n)[k] + 1) / n[k])[:, None]
    with np.errstate(invalid="ignore", over="ignore"):
        out = p[k] + (p[k + 1] - p[k]) * t
    return np.concatenate([p[:1], out]), np.r_[0, ends]


#: what a Matplotlib whose mplot3d keeps its artists' data otherwise would raise in
#: DepthTested (which reads their private attributes): the artist is then drawn as
#: mplot3d draws it
_INTERNALS = (AttributeError, TypeError, ValueError, IndexError, KeyError)


class DepthTested:
    """The draw of one of mplot3d's own artists (``ax.scatter``, ``ax.plot``,
    ``ax.text``, ``ax.quiver``, ``ax.plot_wireframe``, ``ax.contour(f)``,
    ``ax.add_collection3d``: Path3DCollection, Line3D, Text3D, Line3DCollection, a
    contour set's Collection3D, Poly3DCollection) in a 3-D Axes that holds floatcol
    surfaces: mplot3d sorts whole artists, so it would draw a scatter entirely over or
    under a surface.
    Surface3DImage puts one in place of each such artist's ``draw`` when it draws;
    while the surfaces' pictures were drawn with the Axes' present projection (they
    draw first: their zorder, 1, is below mplot3d's artists'), what lies behind a
    surface at its pixel (visible_points, as SurfacePlot.scatter's) is left out of a
    copy of the artist that mplot3d then draws as its own: points masked (mplot3d's
    own way of leaving a point out), a line sampled a pixel apart and broken where
    hidden (its markers only at its visible vertices), a text not drawn where its
    anchor is hidden, polygons (a contourf level's, a Poly3DCollection's) whole, over
    the picture where any of their points lies in front of a surface (_faces_kept,
    _paths_kept), but for a Poly3DCollection's polygons (opaque or not) that cross a
    surface on a raster canvas: those a pixel at a time (cross, draw_crossing). The hidden
    part is drawn the same way under the surfaces' picture (``draw_hidden``; with
    several floatcol surfaces, under their composite), so that it shows through a
    translucent surface and at the partly covered pixels of its edges. ``visible``
    says, after a draw, which points (a line's samples, a collection's segments'
    samples end to end) were shown; None where the artist was drawn as it is (no
    surface drawn with the Axes' projection)."""

    def __init__(self, art):
        self.art = art
        self.visible = None
        self._crossing = None     # (render, crossing polygons, their pixels): cross()
        self._front = None        # (render, the polygons with a point in front): cross()
        self._planar = None       # (render, a filled contour set's flat levels): cross()

    def __call__(self, renderer):
        art = self.art
        self.visible = None
        if not art.get_visible():       # (as the artist's own draw: nothing)
            return
        renders = [a.plot.render for a in art.axes.artists
                   if isinstance(a, Surface3DImage) and a.drawn_for(art.axes)]
        if not renders:
            return type(art).draw(art, renderer)
        try:
            self._draw(renderer, renders, True)
        except _INTERNALS:              # (another Matplotlib's mplot3d: drawn as it is)
            self.visible = None
            type(art).draw(art, renderer)

    def crosses(self):
        """Whether the last ``cross`` found polygons to draw a pixel at a time."""
        return self._crossing is not None or self._planar is not None

    def cross(self, renderer, render, vector=False):
        """Find the polygons of a Poly3DCollection that cross the (opaque) surface of
        ``render`` and the picture's pixels where they are not behind it
        (_not_behind_pixels), to be drawn under the picture (draw_hidden) and over it
        at those pixels alone (draw_crossing), not as whole polygons over it: their
        line through the surface a pixel at a time. On a raster canvas (Agg, or a
        vector file's while it rasterizes); ``vector``: on a vector file's canvas,
        which rasterizes where they are found (Surface3DImage.draw)."""
        from mpl_toolkits.mplot3d import art3d
        self._crossing = self._front = self._planar = None
        art = self.art
        raster = vector or _raster_of(renderer) is not None
        if (isinstance(art, getattr(art3d, "Collection3D", ())) and
                hasattr(art, "_3dverts_codes") and getattr(art, "filled", True) and
                raster and art.get_visible()):
            try:
                planar = np.array([_flat_level_crosses(render, np.asarray(vs, dtype=float), cs)
                                   for vs, cs in art._3dverts_codes], dtype=bool)
            except _INTERNALS:
                return
            if planar.any():
                self._planar = (render, planar)
            return
        faces = getattr(art, "_faces", None)
        if not (isinstance(art, art3d.Poly3DCollection) and raster
                and art.get_visible() and faces is not None and len(faces)):
            return
        try:
            crossing, front = _crossing_faces(art, faces, render)
            self._front = (render, front)       # (the passes' whole polygons take it)
            if not crossing.any():
                return
            pixels = _not_behind_pixels(render,
                                        _fan_triangles(_valid_faces(art, faces)[crossing]))
        except _INTERNALS:
            return
        if pixels is not None:
            self._crossing = (render, crossing, front, pixels)

    def _crossing_for(self, renders):
        """The polygons draw_crossing draws (its collection's that go over the picture:
        those that cross the surface and the others with a point in front of it, so
        that mplot3d's order among them holds), for the front pass to leave out."""
        c = self._crossing
        return c[2] if c is not None and len(renders) == 1 and renders[0] is c[0] else None

    def _planar_for(self, renders):
        c = self._planar
        return c[1] if c is not None and len(renders) == 1 and renders[0] is c[0] else None

    def _front_for(self, renders):
        c = self._front
        return c[1] if c is not None and len(renders) == 1 and renders[0] is c[0] else None

    def draw_crossing(self, renderer, T):
        """Draw the collection's polygons that go over the picture (cross): on a canvas
        of their own in mplot3d's order among them, their antialiased edges kept;
        where one that crosses the surface is on top, only at the pixels where it is
        not behind the surface (its coverage there), the rest of it cleared. T: the
        picture's pixel (col, row) at the canvas point T @ (col, row, 1)
        (Surface3DImage.placed)."""
        if self._planar is not None:
            self._draw_planar(renderer)
            return
        if self._crossing is None:
            return
        import copy

        from matplotlib.backends.backend_agg import RendererAgg
        render, crossing, over, pixels = self._crossing
        art = self.art
        try:
            faces = np.where(over[:, None, None], art._faces, np.nan)
            c = copy.copy(art)
            c._faces = faces
            c.do_3d_projection()
            own = RendererAgg(renderer.width, renderer.height, renderer.dpi)
            type(c).draw(c, own)
            # which polygon is on top at each canvas pixel, one that crosses (red) or
            # not (blue): the same polygons drawn again in those flat colours
            flag = copy.copy(art)
            flag._faces = faces
            which = np.where(crossing[:, None], [1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0])
            flag.set_facecolor(which)
            flag.set_edgecolor(which)
            flag.set_antialiased(False)
            flag.do_3d_projection()
            tops = RendererAgg(renderer.width, renderer.height, renderer.dpi)
            type(flag).draw(flag, tops)
        except _INTERNALS:
            return
        buf = np.array(own.buffer_rgba())          # (top row first, straight alpha)
        top = np.asarray(tops.buffer_rgba())
        ys, xs = np.nonzero((buf[..., 3] > 0) & (top[..., 0] > top[..., 2]))
        # each canvas pixel's pixel of the picture (off the picture: no surface there)
        x, y = xs + 0.5, buf.shape[0] - ys - 0.5
        inv = np.linalg.inv(T[:, :2])
        col = np.round(inv[0, 0] * (x - T[0, 2]) + inv[0, 1] * (y - T[1, 2])).astype(int)
        row = np.round(inv[1, 0] * (x - T[0, 2]) + inv[1, 1] * (y - T[1, 2])).astype(int)
        H, W = pixels.shape
        on = (col >= 0) & (col < W) & (row >= 0) & (row < H)
        keep = np.ones(len(xs))
        keep[on] = pixels[row[on], col[on]]
        buf[ys, xs, 3] = np.round(buf[ys, xs, 3] * keep).astype(np.uint8)
        gc = renderer.new_gc()
        gc.set_clip_rectangle(art.axes.bbox)
        renderer.draw_image(gc, 0, 0, np.ascontiguousarray(buf[::-1]))
        gc.restore()

    def _draw_planar(self, renderer):
        """A filled contour set's flat levels (a contourf projected at an ``offset``)
        over the picture a pixel at a time: the levels of each plane drawn on a canvas
        of their own, each canvas pixel's point of the plane found through the plane's
        homography onto the canvas (mplot3d's projection of four of its points), and
        the pixel kept as much as that point is not behind the surface (_coverage)."""
        import copy

        from matplotlib.backends.backend_agg import RendererAgg
        from mpl_toolkits.mplot3d import proj3d
        render, planar = self._planar
        art = self.art
        ax = art.axes
        vc = art._3dverts_codes
        planes = {}
        for i, (vs, _) in enumerate(vc):
            if planar[i]:
                planes.setdefault(_plane_of(np.asarray(vs, dtype=float)), []).append(i)
        for (axis, value), levels in planes.items():
            try:
                c = copy.copy(art)
                c._3dverts_codes = [vc[i] if i in levels else (np.zeros((0, 3)), None)
                                    for i in range(len(vc))]
                c.do_3d_projection()
                own = RendererAgg(renderer.width, renderer.height, renderer.dpi)
                type(c).draw(c, own)
                pts = np.concatenate([np.asarray(vc[i][0], dtype=float) for i in levels])
                other = [k for k in range(3) if k != axis]
                lo, hi = pts[:, other].min(axis=0), pts[:, other].max(axis=0)
                corners = np.zeros((4, 3))
                corners[:, axis] = value
                corners[:, other[0]] = [lo[0], hi[0], hi[0], lo[0]]
                corners[:, other[1]] = [lo[1], lo[1], hi[1], hi[1]]
                xs, ys, _ = proj3d.proj_transform(*corners.T, ax.M)
                disp = ax.transData.transform(np.column_stack([xs, ys]))
                Hm = _homography(corners[:, other], disp)
            except (*_INTERNALS, np.linalg.LinAlgError):
                continue
            if Hm is None:
                continue
            buf = np.array(own.buffer_rgba())
            yy, xx = np.nonzero(buf[..., 3])
            if not len(yy):
                continue
            q = np.linalg.inv(Hm) @ np.vstack([xx + 0.5, buf.shape[0] - yy - 0.5,
                                               np.ones(len(xx))])
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                p3 = np.zeros((len(xx), 3))
                p3[:, axis] = value
                p3[:, other[0]] = q[0] / q[2]
                p3[:, other[1]] = q[1] / q[2]
            grid = np.full(buf.shape[:2], np.inf)
            grid[yy, xx] = _depth_gaps(render, p3)
            cov = _coverage(grid)[yy, xx]
            buf[yy, xx, 3] = np.round(buf[yy, xx, 3] * cov).astype(np.uint8)
            gc = renderer.new_gc()
            gc.set_clip_rectangle(ax.bbox)
            renderer.draw_image(gc, 0, 0, np.ascontiguousarray(buf[::-1]))
            gc.restore()

    def draw_hidden(self, renderer, renders):
        """Draw the part of the artist that the surfaces of ``renders`` hide."""
        if self.art.get_visible():
            try:
                self._draw(renderer, renders, False)
            except _INTERNALS:
                pass

    def _draw(self, renderer, renders, front):
        """Draw the part in front of the surfaces (``front``) or the part behind."""
        import copy

        from mpl_toolkits.mplot3d import art3d
        art = self.art

        def shown(pts):
            vis = np.ones(len(pts), dtype=bool)
            with np.errstate(invalid="ignore", over="ignore"):
                for r in renders:
                    vis &= visible_points(r, pts, r.box)
            if front:
                self.visible = vis
            return vis if front else ~vis & np.isfinite(pts).all(axis=1)

        def xyz(cols):
            cols = np.broadcast_arrays(*(np.ma.filled(np.ma.asarray(c, dtype=float), np.nan)
                                         for c in cols))
            return np.column_stack([np.ravel(c) for c in cols])

        def whole(keep):
            """Draw the artist itself (all kept), nothing (none), or else False."""
            if keep.all():
                type(art).draw(art, renderer)
            return keep.all() or not keep.any()

        if isinstance(art, art3d.Path3DCollection):
            p = xyz(art._offsets3d)
            keep = shown(p)
            if not whole(keep):
                c = copy.copy(art)
                c._offsets3d = tuple(np.ma.array(p[:, k], mask=~keep) for k in range(3))
                c.do_3d_projection()
                type(c).draw(c, renderer)
        elif isinstance(art, art3d.Line3D):
            p = xyz(art.get_data_3d())
            samples, at = pixel_samples(renders[0].view, renders[0].box, p)
            keep = shown(samples)
            if not whole(keep):
                cut = np.where(keep[:, None], samples, np.nan)
                ln = copy.copy(art)
                ln.set_marker("None")
                ln._verts3d = tuple(cut[:, k] for k in range(3))
                type(ln).draw(ln, renderer)
                if art.get_marker() not in (None, "None", "none", "", " "):
                    mk = copy.copy(art)
                    mk.set_linestyle("None")
                    q = np.where(keep[at][:, None], p, np.nan)
                    mk._verts3d = tuple(q[:, k] for k in range(3))
                    type(mk).draw(mk, renderer)
        elif isinstance(art, art3d.Line3DCollection):
            pts, parts = _sampled(renders[0], [xyz(np.asarray(seg, dtype=float).T)
                                               for seg in art._segments3d])
            keep = shown(pts)
            if not whole(keep):
                cuts = np.split(np.where(keep[:, None], pts, np.nan), np.cumsum(parts)[:-1])
                c = copy.copy(art)
                c._segments3d = cuts
                c.do_3d_projection()
                type(c).draw(c, renderer)
        elif isinstance(art, getattr(art3d, "Collection3D", ())) and \
                hasattr(art, "_3dverts_codes"):
            # contour and contourf sets (Matplotlib 3.8 on): a path a level
            vc = art._3dverts_codes
            if getattr(art, "filled", True):
                keep = _paths_kept(vc, renders, front)
                planar = self._planar_for(renders)
                if planar is not None:          # (those: draw_crossing, a pixel at a time)
                    keep = keep & ~planar if front else keep | planar
                if front:
                    self.visible = keep
                if not whole(keep):
                    c = copy.copy(art)
                    c._3dverts_codes = [(vs, cs) if k else (np.zeros((0, 3)), None)
                                        for (vs, cs), k in zip(vc, keep)]
                    c.do_3d_projection()
                    type(c).draw(c, renderer)
            else:
                cut, seen = [], []
                for vs, cs in vc:
                    pts, parts = _sampled(renders[0], _subpaths(np.asarray(vs, dtype=float), cs))
                    keep = shown(pts)
                    seen.append(keep)
                    # the visible runs, each starting with a MOVETO (not NaN points:
                    # mplot3d masks those, and its mask fails on a path's vertices)
                    start = np.zeros(len(pts), dtype=bool)
                    start[np.cumsum(parts, dtype=int)[:-1]] = True
                    start[0:1] = True
                    run_start = keep & (start | ~np.r_[False, keep[:-1]])
                    codes = np.where(run_start, 1, 2).astype(np.uint8)  # MOVETO, LINETO
                    cut.append((pts[keep], codes[keep]))
                keep = np.concatenate(seen) if seen else np.zeros(0, dtype=bool)
                if front:
                    self.visible = keep
                if not whole(keep):
                    c = copy.copy(art)
                    c._3dverts_codes = cut
                    c.do_3d_projection()
                    type(c).draw(c, renderer)
        elif isinstance(art, art3d.Poly3DCollection):
            faces = getattr(art, "_faces", None)
            if faces is None:                   # (another Matplotlib's layout)
                if front:
                    type(art).draw(art, renderer)
                return
            keep = _faces_kept(art, faces, renders, front, self._crossing_for(renders),
                               self._front_for(renders))
            if front:
                self.visible = keep
            if not whole(keep):
                c = copy.copy(art)
                c._faces = np.where(keep[:, None, None], faces, np.nan)
                c.do_3d_projection()
                type(c).draw(c, renderer)
        else:                                   # a text (Text3D): by its anchor
            whole(shown(xyz([[art._x], [art._y], [art._z]])))


#: a polygon's points tested against the surfaces: a lattice of this many steps
#: along the edges of each triangle of its fan
FACE_LATTICE = 6


def _faces_kept(art, faces, renders, front, crossing=None, seen_front=None):
    """Which polygons (faces (n, m, 3), padded) of a Poly3DCollection to draw over the
    surfaces' pictures (``front``) or under them: under where none of the polygon's
    points (its corners and a lattice over the triangles of its fan) lies in front of
    a surface that is there (a contour's filled projection on a far wall, a floor
    below), over where any does; whole polygons. ``crossing`` (n,) bool: polygons that
    cross a surface and are drawn over the picture a pixel at a time
    (DepthTested.draw_crossing): under, and not over. ``seen_front``: which polygons
    have a point in front of the surfaces, where already known (DepthTested.cross)."""
    if seen_front is None:
        seen_front = _face_points_in_front(art, faces, renders)
    if crossing is None:
        return seen_front if front else ~seen_front
    return seen_front & ~crossing if front else ~seen_front | crossing


def _valid_faces(art, faces):
    """A Poly3DCollection's polygons (faces (n, m, 3)) with its invalid corners NaN."""
    n, m, _ = faces.shape
    bad = np.broadcast_to(np.asarray(getattr(art, "_invalid_vertices", False)), (n, m))
    return np.where(bad[..., None], np.nan, faces)


def _fan_points(art, faces):
    """(points (n, k, 3), the lattice over each polygon's fan of triangles) of the
    polygons (faces (n, m, 3), padded with NaN) of a Poly3DCollection."""
    n = faces.shape[0]
    f = _valid_faces(art, faces)
    # (the padding of a polygon with fewer corners is NaN: its fan's triangles that
    # reach it give NaN points, which count for nothing)
    L = FACE_LATTICE
    a, b = np.meshgrid(np.arange(L + 1), np.arange(L + 1))
    keep_ab = a + b <= L
    wa, wb = a[keep_ab] / L, b[keep_ab] / L             # barycentric lattice
    p0 = f[:, :1, None, :]
    p1 = f[:, 1:-1, None, :]
    p2 = f[:, 2:, None, :]
    pts = p0 + wa[None, None, :, None] * (p1 - p0) + wb[None, None, :, None] * (p2 - p0)
    return pts.reshape(n, -1, 3)


def _face_points_in_front(art, faces, renders):
    """Whether any point of each polygon (_fan_points) lies in front of a surface of
    ``renders`` that is there."""
    return _any_in_front(list(_fan_points(art, faces)), renders)


def _crossing_faces(art, faces, render):
    """(crossing, front): which polygons of a Poly3DCollection cross the surface of
    ``render`` (with points of their lattice, _fan_points, both in front of it
    and behind it), and which have a point in front of it (_face_points_in_front's)."""
    pts = _fan_points(art, faces)
    n, k, _ = pts.shape
    flat = pts.reshape(-1, 3)
    good = np.isfinite(flat).all(axis=1)
    with np.errstate(invalid="ignore", over="ignore"):
        _, front, behind = depth_sides(render, np.where(good[:, None], flat, 0.0),
                                       render.box)
    front = (front & good).reshape(n, k).any(axis=1)
    behind = (behind & good).reshape(n, k).any(axis=1)
    return front & behind, front


#: the most pixels the triangles of the polygons that cross a surface may cover in
#: their boxes (_not_behind_pixels; beyond, they are drawn whole, as the others)
MAX_CROSSING_PIXELS = 2e7


def _not_behind_pixels(render, tris):
    """(H, W) in [0, 1]: how much of each pixel of ``render``'s picture the triangles
    ``tris`` (k, 3, 3) in the surface's units cover where they are not behind the
    surface seen there (in front of it within depth_sides's tolerance, or no surface
    there; _coverage: antialiased where they pass through it), at the pixels whose
    centres they cover; None where they cover more than MAX_CROSSING_PIXELS pixels in
    their boxes. Each pixel's point on its triangle is interpolated
    perspective-correctly (weights over the depth of the corners)."""
    view, box = render.view, render.box
    H, W = render.side.shape
    out = np.zeros((H, W))
    P = tris * np.asarray(box, dtype=float)
    with np.errstate(invalid="ignore", over="ignore"):
        col, row = view.project(P[..., 0], P[..., 1], P[..., 2])
        _, _, z = view.to_screen(P[..., 0], P[..., 1], P[..., 2])
        depth = np.ones_like(z) if view.orthographic else z + view.d3
        ok = np.isfinite(col).all(axis=1) & np.isfinite(row).all(axis=1)
        c0 = np.clip(np.ceil(np.nanmin(col, axis=1)), 0, W)
        c1 = np.clip(np.floor(np.nanmax(col, axis=1)), -1, W - 1)
        r0 = np.clip(np.ceil(np.nanmin(row, axis=1)), 0, H)
        r1 = np.clip(np.floor(np.nanmax(row, axis=1)), -1, H - 1)
    nc = np.where(ok, c1 - c0 + 1, 0).clip(0).astype(np.int64)
    nr = np.where(ok, r1 - r0 + 1, 0).clip(0).astype(np.int64)
    counts = nc * nr
    total = int(counts.sum())
    if total > MAX_CROSSING_PIXELS:
        return None
    if total == 0:
        return out
    t = np.repeat(np.arange(len(tris)), counts)
    local = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
    cc = c0[t].astype(np.int64) + local % nc[t]
    rr = r0[t].astype(np.int64) + local // nc[t]
    # the pixel centre's barycentric weights in the picture, then on the triangle
    x0, x1, x2 = col[t, 0], col[t, 1], col[t, 2]
    y0, y1, y2 = row[t, 0], row[t, 1], row[t, 2]
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        b1 = ((cc - x0) * (y2 - y0) - (x2 - x0) * (rr - y0)) / area
        b2 = ((x1 - x0) * (rr - y0) - (cc - x0) * (y1 - y0)) / area
        b0 = 1.0 - b1 - b2
        inside = (b0 >= -1e-9) & (b1 >= -1e-9) & (b2 >= -1e-9) & (area != 0.0)
        q0, q1, q2 = b0 / depth[t, 0], b1 / depth[t, 1], b2 / depth[t, 2]
        q = q0 + q1 + q2
        pts = (tris[t, 0] * (q0 / q)[:, None] + tris[t, 1] * (q1 / q)[:, None]
               + tris[t, 2] * (q2 / q)[:, None])
    inside &= np.isfinite(pts).all(axis=1)
    pts, cc, rr = pts[inside], cc[inside], rr[inside]
    d = np.full((H, W), np.inf)
    np.minimum.at(d, (rr, cc), _depth_gaps(render, pts))   # (the nearest polygon's)
    return _coverage(_outlined(d))


def _outlined(d, rings=2):
    """The gaps ``d`` (H, W) with each pixel whose centre no polygon covers (+inf)
    given its neighbours' least (of the 3 x 3 around it; ``rings`` times): the pixels
    along the polygons' outlines, which their antialiased edges partly cover on the
    canvas (up to 2 pixels beyond the centres covered, measured), take the side of the
    surface the polygon lies on beside them (they were cleared: a seam between two
    polygons, and the outline of a translucent one, showed the surface through it)."""
    H, W = d.shape
    for _ in range(rings):
        p = np.pad(d, 1, constant_values=np.inf)
        near = np.full((H, W), np.inf)
        for di in (0, 1, 2):
            for dj in (0, 1, 2):
                near = np.minimum(near, p[di:di + H, dj:dj + W])
        d = np.where(d == np.inf, near, d)
    return d


def _coverage(d):
    """(H, W) in [0, 1]: how much of each pixel a polygon covers in front of the
    surface, from the gaps ``d`` (H, W) in depth at the pixels' centres (+inf: no
    polygon; -inf: no surface). Where the gap changes sign between pixels the line
    where it is 0 runs through them: the part of a pixel on the polygon's side, from
    the gap over its change a pixel across (the line straight over the pixel),
    antialiases the line where the polygon passes through the surface."""
    fin = np.isfinite(d)
    grads = []
    for axis in (0, 1):
        fwd = np.roll(d, -1, axis)
        bwd = np.roll(d, 1, axis)
        ok_f = np.roll(fin, -1, axis)
        ok_b = np.roll(fin, 1, axis)
        edge = [slice(None), slice(None)]
        edge[axis] = -1
        ok_f[tuple(edge)] = False
        edge[axis] = 0
        ok_b[tuple(edge)] = False
        with np.errstate(invalid="ignore", over="ignore"):
            g = np.where(ok_f & ok_b, 0.5 * (fwd - bwd),
                         np.where(ok_f, fwd - d, np.where(ok_b, d - bwd, 0.0)))
        grads.append(np.where(fin, g, 0.0))
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        slope = np.hypot(*grads)
        cov = np.where(slope > 0.0, np.clip(0.5 - d / slope, 0.0, 1.0), (d < 0.0) * 1.0)
    cov[d == -np.inf] = 1.0
    cov[d == np.inf] = 0.0
    return cov


#: a flat contour level is tested against the surface at its corners and at the
#: points of a lattice this many a side over its box that lie inside it
LEVEL_LATTICE = 16


def _flat_level_crosses(render, vs, codes):
    """Whether a contour level's path (vertices (k, 3), codes) lies in a plane
    (_plane_of) and passes through the surface of ``render``: some of its points (its
    corners and a lattice inside it) in front of the surface, some behind. The
    others are drawn whole, under or over the picture, as before."""
    from matplotlib.path import Path
    plane = _plane_of(vs)
    if plane is None:
        return False
    axis, value = plane
    other = [k for k in range(3) if k != axis]
    fin = vs[np.isfinite(vs).all(axis=1)]
    lo, hi = fin[:, other].min(axis=0), fin[:, other].max(axis=0)
    g = np.linspace(0.0, 1.0, LEVEL_LATTICE)
    a, b = np.meshgrid(lo[0] + g * (hi[0] - lo[0]), lo[1] + g * (hi[1] - lo[1]))
    grid = np.column_stack([a.ravel(), b.ravel()])
    inside = Path(vs[:, other], codes).contains_points(grid) if len(vs) > 2 else \
        np.zeros(len(grid), dtype=bool)
    pts = np.zeros((int(inside.sum()), 3))
    pts[:, axis] = value
    pts[:, other] = grid[inside]
    pts = np.concatenate([fin, pts])
    with np.errstate(invalid="ignore", over="ignore"):
        _, front, behind = depth_sides(render, pts, render.box)
    return bool(front.any() and behind.any())


def _plane_of(vs):
    """(axis, value) of the plane a contour level's vertices (k, 3) lie in, one
    coordinate the same for all (a contourf's zdir and offset), else None."""
    fin = vs[np.isfinite(vs).all(axis=1)]
    if len(fin) < 3:
        return None
    span = np.ptp(fin, axis=0)
    size = float(span.max())
    for axis in (2, 1, 0):
        if size > 0.0 and span[axis] <= 1e-9 * size:
            return axis, float(fin[0, axis])
    return None


def _homography(ab, xy):
    """The 3 x 3 H taking points (a, b) of a plane to their canvas points (x, y) (four
    of each; mplot3d's projection of a plane is one), or None where they are
    degenerate."""
    A = []
    rhs = []
    for (a, b), (x, y) in zip(ab, xy):
        A.append([a, b, 1.0, 0.0, 0.0, 0.0, -a * x, -b * x])
        A.append([0.0, 0.0, 0.0, a, b, 1.0, -a * y, -b * y])
        rhs += [x, y]
    A = np.asarray(A)
    if not np.isfinite(A).all() or abs(np.linalg.det(A)) < 1e-300:
        return None
    h = np.linalg.solve(A, np.asarray(rhs))
    return np.append(h, 1.0).reshape(3, 3)


def _fan_triangles(faces):
    """The triangles (k, 3, 3) of the fans of polygons (faces (n, m, 3), padded and
    invalid corners NaN: their triangles that reach one are left out)."""
    tri = np.stack([np.broadcast_to(faces[:, :1], faces[:, 1:-1].shape), faces[:, 1:-1],
                    faces[:, 2:]], axis=2).reshape(-1, 3, 3)
    return tri[np.isfinite(tri).all(axis=(1, 2))]


def _subpaths(vs, codes):
    """The polylines of a path's vertices (k, 3) and codes (a MOVETO starts one)."""
    if codes is None or len(vs) == 0:
        return [vs] if len(vs) else []
    starts = np.flatnonzero(np.asarray(codes) == 1)        # (Path.MOVETO)
    if len(starts) == 0 or starts[0] != 0:
        starts = np.r_[0, starts]
    return [p for p in np.split(vs, starts[1:]) if len(p)]


def _paths_kept(vc, renders, front):
    """Which paths (filled: a contourf level's polygons) of a Collection3D to draw over
    the surfaces' pictures (``front``: any of its corners in front of a surface that is
    there) or under them (none: a contour's filled projection on a far wall, a
    floor below)."""
    keep = _any_in_front([np.asarray(vs, dtype=float).reshape(-1, 3) for vs, _ in vc],
                         renders)
    return keep if front else ~keep


def _any_in_front(groups, renders):
    """For each group of points (a list of (k, 3) arrays), whether any of its finite
    points lies in front of a surface of ``renders`` that is there (one depth test for
    all of them)."""
    if not groups:
        return np.zeros(0, dtype=bool)
    pts = np.concatenate(groups)
    owner = np.repeat(np.arange(len(groups)), [len(g) for g in groups])
    good = np.isfinite(pts).all(axis=1)
    over = np.zeros(len(pts), dtype=bool)
    with np.errstate(invalid="ignore", over="ignore"):
        for r in renders:
            _, in_front, _ = depth_sides(r, np.where(good[:, None], pts, 0.0), r.box)
            over |= in_front & good
    return np.bincount(owner[over], minlength=len(groups)) > 0


def _sampled(render, polylines):
    """(points, lengths): the polylines (a list of (k, 3)) sampled a pixel apart in
    ``render``'s picture (pixel_samples), end to end."""
    parts = [pixel_samples(render.view, render.box, p)[0] for p in polylines]
    return (np.concatenate(parts) if parts else np.zeros((0, 3)), [len(q) for q in parts])


def _raster_of(renderer):
    """The Agg renderer that draws for ``renderer``: itself on a raster canvas, or a
    vector file's raster renderer while it rasterizes (matplotlib's MixedModeRenderer,
    which hands its drawing to it then); None where the drawing goes into a vector
    file."""
    from matplotlib.backends.backend_agg import RendererAgg
    if isinstance(renderer, RendererAgg):
        return renderer
    inner = getattr(renderer, "__dict__", {}).get("_renderer")
    return inner if isinstance(inner, RendererAgg) else None


def depth_test_mplot3d_artists(ax):
    """Every artist of mplot3d's own kinds in ``ax`` drawn depth-tested from now on
    (DepthTested): an instance's ``draw`` is replaced once."""
    from mpl_toolkits.mplot3d import art3d
    kinds = (art3d.Path3DCollection, art3d.Line3D, art3d.Text3D, art3d.Line3DCollection,
             art3d.Poly3DCollection) + ((art3d.Collection3D,)
                                        if hasattr(art3d, "Collection3D") else ())
    for a in ax.get_children():
        if isinstance(a, kinds) and not isinstance(a.__dict__.get("draw"), DepthTested):
            a.draw = DepthTested(a)


def _check_style(kind, style, n):
    """ValueError where matplotlib could not draw ``n`` points (kind "points"), a line
    or a text in ``style``, as OccludedObjects.draw would make them: checked when they
    are added, since a style that failed at the figure's draw (an unknown keyword, a
    colour or size for each of a different number of points) failed at every later
    draw of it."""
    from matplotlib.collections import PathCollection
    from matplotlib.colors import to_rgba_array
    from matplotlib.lines import Line2D
    from matplotlib.markers import MarkerStyle
    from matplotlib.text import Text
    try:
        if kind == "text":
            Text(0, 0, "", **style)
        elif kind == "points":
            st = dict(style)
            MarkerStyle(st.pop("marker", "o"))
            sizes = np.ravel(np.asarray(st.pop("s", 20.0), float))
            if sizes.size not in (1, n):
                raise ValueError(f"{sizes.size} sizes for {n} points")
            colors = to_rgba_array(st.pop("c", st.pop("color", "k")))
            if len(colors) not in (1, n):
                raise ValueError(f"{len(colors)} colours for {n} points")
            PathCollection([], sizes=sizes, facecolors=colors, **st)
        else:
            Line2D([0.0], [0.0], **style)
    except Exception as exc:
        first = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
        what = {"points": "scatter", "line": "plot", "text": "text"}[kind]
        raise ValueError(f"{what}: a style matplotlib cannot draw ({first})") from None


def _per_point(color, keep):
    from matplotlib.colors import to_rgba_array
    c = to_rgba_array(color)
    return c if len(c) == 1 else c[keep]


def visible_points(r, pts, box, pixels=2.0):
    """Which points (n, 3) in the surface's units lie in front of the surface a Render
    ``r`` saw at their pixel, or where it saw none (the depth test, with a tolerance of
    ``pixels`` pixels of depth so that a point on the surface stays visible)."""
    ok, front, behind = depth_sides(r, pts, box, pixels)
    return ok & ~behind


def depth_sides(r, pts, box, pixels=2.0):
    """(ok, front, behind): which points (n, 3) are numbers that project, and which of
    them lie in front of (or on) the surface the Render ``r`` saw at their pixel, and
    which behind it (neither where it saw none there)."""
    ok, inside, z, seen, tol = _depth_test(r, pts, box, pixels)
    with np.errstate(invalid="ignore", over="ignore"):     # (points far off: not shown)
        there = inside & np.isfinite(seen)
        near = z <= seen + tol
        return ok, ok & there & near, ok & there & ~near


def _depth_test(r, pts, box, pixels=2.0):
    """(ok, inside, z, seen, tol) of points (n, 3) in the surface's units against the
    Render ``r``: which are numbers that project, which of those fall on the picture,
    their screen depth, the depth r saw at their pixel (the nearest pixel clamped to
    the picture) and the tolerance of ``pixels`` pixels of depth (depth_sides)."""
    view = r.view
    bx, by, bz = (pts[:, 0] * box[0], pts[:, 1] * box[1], pts[:, 2] * box[2])
    col, row = view.project(bx, by, bz)
    _, _, z = view.to_screen(bx, by, bz)
    H, W = r.side.shape
    ok = np.isfinite(col) & np.isfinite(row)
    col = np.clip(np.where(ok, col, -1.0), -1.0, W)     # (a point far off: off the picture)
    row = np.clip(np.where(ok, row, -1.0), -1.0, H)
    c = np.clip(np.round(col).astype(int), 0, W - 1)
    j = np.clip(np.round(row).astype(int), 0, H - 1)
    inside = ok & (np.round(col) == c) & (np.round(row) == j)
    tol = pixels / view.scale
    if not view.orthographic:
        tol = tol * (z + view.d3) / view.d1
    return ok, inside, z, np.asarray(r.depth)[j, c], tol


def _depth_gaps(r, pts):
    """Each point's gap in depth behind the surface the Render ``r`` saw at its pixel,
    beyond depth_sides's tolerance (< 0: in front; -inf: no surface there, or off the
    picture; +inf: a point that does not project): _coverage's input."""
    with np.errstate(invalid="ignore", over="ignore"):
        ok, inside, z, seen, tol = _depth_test(r, pts, r.box)
        gap = np.where(inside & np.isfinite(seen), z - seen - tol, -np.inf)
    gap[~(ok & np.isfinite(z))] = np.inf
    return gap

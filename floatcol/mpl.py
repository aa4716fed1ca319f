"""A floatcol surface inside an ordinary matplotlib Axes.

:class:`SurfaceImage` is an AxesImage that renders its SurfacePlot again at the
Axes' true pixel size each time the figure is drawn, so a resized window or
``savefig(dpi=300)`` gets a sharp picture of that size, never a resampled one. With
``interactive=True`` a mouse drag turns the view (elev/azim, as Axes3D does) and the
scroll wheel zooms; while the button is held the picture is drawn with sampling planes
``DRAG_PIXEL_STEP`` pixels apart and without corrections or antialiasing, and at full
quality on release.
"""
from __future__ import annotations

from matplotlib.image import AxesImage

DRAG_PIXEL_STEP = 3.0
ZOOM_PER_STEP = 1.1


class SurfaceImage(AxesImage):
    """The artist of a :class:`floatcol.plot.SurfacePlot` drawn into an Axes."""

    def __init__(self, ax, plot):
        super().__init__(ax, interpolation="none", origin="upper", resample=False)
        self.plot = plot
        self._drag = None
        self._cids = []

    @classmethod
    def attach(cls, plot, ax, interactive=False):
        art = cls(ax, plot)
        art.set_extent((*ax.get_xlim(), *ax.get_ylim()))
        plot.artist = art
        ax.add_image(art)
        ax.set_axis_off()
        if interactive:
            art.connect_events()
        return art

    def pixel_size(self, renderer):
        """The Axes' size in output pixels for this renderer (vector backends
        embed images at the figure's dpi, which image_magnification gives)."""
        bb = self.axes.bbox
        mag = renderer.get_image_magnification()
        return max(1, int(round(bb.width * mag))), max(1, int(round(bb.height * mag)))

    def draw(self, renderer):
        if not self.get_visible():
            return
        size = self.pixel_size(renderer)
        r = self.plot.draw(size)
        bb = self.axes.bbox
        if renderer.get_image_magnification() == 1.0 and self.get_alpha() is None:
            # a raster canvas: the render is already the Axes' pixels, so put it
            # there directly (matplotlib's resampling would only copy it)
            gc = renderer.new_gc()
            gc.set_clip_rectangle(bb)
            renderer.draw_image(gc, int(round(bb.x0)), int(round(bb.y0)), r.rgba[::-1])
            gc.restore()
            self.stale = False
            return
        x0, x1 = self.axes.get_xlim()
        y0, y1 = self.axes.get_ylim()
        # set the data without the stale callbacks: this is the draw itself
        self._A = r.rgba
        self._imcache = None
        self.set_extent((x0, x1, y0, y1))
        super().draw(renderer)

    def get_window_extent(self, renderer=None):
        return self.axes.bbox

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
        self.plot.zoom *= ZOOM_PER_STEP ** event.step
        self.stale = True
        self.axes.figure.canvas.draw_idle()

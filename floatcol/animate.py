"""Time-varying surfaces w = f(u, v, t) (Gordon §6.1: a new picture per frame).

``fc.animate(expr, (u, a, b), (v, c, d), t=(0, 2*pi), frames=60, output="wave.gif")``
renders each frame with one camera, scale and colormap range for the whole clip (fitted
to the envelope of all frames, so nothing jumps) and writes a GIF (Pillow) or an MP4
(imageio-ffmpeg, the optional ``video`` extra).
"""
from __future__ import annotations

import base64
import contextlib
import html
import itertools
import math
import operator
import os
import shutil

import numpy as np

from ._memory import fits
from .output import atomic_file, check_output
from .plot import parse_ranges, plot_surface, render_view
from .render import box_factors
from .surface import as_surface, check_range, sympy_expression

ANIMATION_FORMATS = {".gif": "GIF", ".mp4": "MP4"}
#: a clip written to a file (GIF or MP4) keeps its frames' pictures as well where they
#: take at most this many bytes (130 frames of 1920x1080); a longer one's are read back
#: from the file when asked (_FileFrames), so that its length is bounded by the disk,
#: not memory
KEEP_BYTES = 2**30
#: a notebook shows a clip read back from its file inline up to this size
#: (matplotlib's animation.embed_limit), else names the file
EMBED_BYTES = 20 * 2**20


class Animation:
    """Frames of a time-varying surface: ``frames`` (list of (H, W, 4) uint8; a long
    clip written to a file, a sequence read back from it: KEEP_BYTES), ``times``,
    ``fps``; ``save(path)`` writes .gif or .mp4. ``stats["camera"]`` holds the
    plot_surface options the whole clip was drawn with (scale, center, vmin, ...)."""

    def __init__(self, frames, times, fps, stats=None):
        self.frames = frames if isinstance(frames, _FileFrames) else _check_frames(frames)
        self.times = times
        self.fps = _check_fps(fps)
        self.stats = stats or {}

    def __len__(self):
        return len(self.frames)

    def save(self, path):
        path, ext = check_output(path, ANIMATION_FORMATS)
        held = self.frames
        if isinstance(held, _FileFrames) and ext == held.ext:
            # its own file: a copy, not encoded again
            if not (os.path.exists(path) and os.path.samefile(path, held.path)):
                with atomic_file(path) as tmp:
                    shutil.copyfile(held.path, tmp)
            return path
        # (frames read back from a file go from one file to the other as they are
        # decoded: never held)
        if ext == ".gif":
            write_gif(held, path, self.fps)
        else:
            write_mp4(held, path, self.fps)
        return path

    def _repr_html_(self):
        import io
        if isinstance(self.frames, _FileFrames):
            path = self.frames.path
            if os.path.getsize(path) > EMBED_BYTES:
                return (f"<p>{len(self.frames)} frames in {html.escape(path)} "
                        f"({os.path.getsize(path) / 2**20:.0f} MB)</p>")
            with open(path, "rb") as fh:
                data = base64.b64encode(fh.read()).decode("ascii")
            if self.frames.ext == ".gif":
                return f'<img src="data:image/gif;base64,{data}"/>'
            return (f'<video controls autoplay loop muted src="data:video/mp4;base64,{data}">'
                    '</video>')

        buf = io.BytesIO()
        _save_gif(self.frames, buf, self.fps)
        data = base64.b64encode(buf.getvalue()).decode("ascii")
        return f'<img src="data:image/gif;base64,{data}"/>'


def _quantized(f):
    """A frame over white, quantized to its own 255 colours (median cut): a "P" image."""
    from PIL import Image
    img = Image.fromarray(np.ascontiguousarray(f), "RGBA")
    white = Image.new("RGBA", img.size, (255, 255, 255, 255))
    return Image.alpha_composite(white, img).convert("RGB").quantize(
        colors=255, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)


#: a GIF's frames are quantized this many at a time (_GifSink)
GIF_BATCH = 8

#: the slowest frame rate: a GIF holds a frame at most 655.35 s (a 16-bit count of
#: hundredths of a second; 1/0.01 fps = 100 s)
MIN_FPS = 0.01
GIF_MAX_MS = 655_350


def _check_fps(fps):
    if not isinstance(fps, (int, float)) or isinstance(fps, bool) or not MIN_FPS <= fps <= 120:
        raise ValueError(f"fps must be a number in [{MIN_FPS}, 120], got {fps!r}")
    return fps


def _check_frames(frames):
    """An Animation's frames: one or more (H, W, 4) uint8 pictures (an (H, W, 3) one
    taken as opaque) of one size, as a list; ValueError says what is wrong."""
    try:
        out = [np.asarray(f) for f in frames]
    except TypeError:
        raise ValueError("frames must be a list of (H, W, 4) uint8 pictures, got "
                         f"{frames!r}") from None
    if not out:
        raise ValueError("frames is empty: give at least one (H, W, 4) uint8 picture")
    for k, f in enumerate(out):
        if f.dtype != np.uint8 or f.ndim != 3 or f.shape[2] not in (3, 4) or min(f.shape[:2]) < 1:
            raise ValueError(f"frame {k} must be an (H, W, 4) uint8 picture, got shape "
                             f"{f.shape} of {f.dtype}")
        if f.shape[2] == 3:
            out[k] = np.dstack([f, np.full(f.shape[:2], 255, np.uint8)])
        if out[k].shape != out[0].shape:
            raise ValueError(f"frame {k} is {f.shape[1]}x{f.shape[0]}, frame 0 "
                             f"{out[0].shape[1]}x{out[0].shape[0]}: frames must be of one size")
    return out


def write_gif(frames, path, fps):
    """The frames (any iterable of (h, w, 4) uint8 pictures) as a looping GIF, 1 / fps
    s each (20 ms at least), written as they come (_gif_writer). Frames that equal
    the one before lengthen its hold instead, which a GIF keeps for at most
    GIF_MAX_MS: a picture held longer (a still surface at a slow frame rate) is shown
    that long."""
    with atomic_file(path) as tmp, open(tmp, "wb") as fh:
        _save_gif(frames, fh, fps)


def _save_gif(frames, target, fps):
    """write_gif's GIF to a binary file object."""
    with _gif_writer(target, fps) as send:
        for f in frames:
            send(f)


def _quantized_rgb(f):
    """(_quantized(f), its colours (h, w, 3) uint8): a frame as the GIF shows it."""
    im = _quantized(f)
    return im, np.asarray(im.convert("RGB"))


class _GifSink:
    """_gif_writer's send(frame): frames quantized (_quantized) GIF_BATCH at a time in
    ``threads`` threads (Pillow's quantizer lets the others run: 60 frames of 1000x600
    in 2.3 instead of 4.5 s on 2 cores), so that at most a batch of pictures is held,
    and written in order by Pillow's GIF encoder (GifImagePlugin.getheader and
    getdata: one frame at a time, its own colour table): a frame equal to the one
    before lengthens its hold (at most GIF_MAX_MS), and a frame is written over the
    one shown before it where it differs from it (its bounding box). 300 frames of
    1280x720 from fc.animate: 1.98 GB at the peak when the clip was held and given to
    Pillow whole, 0.38-0.41 GB so, in 25.2 s against 23.3 s (quantizing a frame in
    flight each thread beside the renders instead of batches: no faster, 24-25 s).
    ``counts``: how many of the clip's frames each frame of the file shows."""

    def __init__(self, fh, fps, threads):
        self.fh = fh
        self.step = min(max(20, round(1000 / fps)), GIF_MAX_MS)
        self.threads = max(1, threads)
        self.batch = []                         # frames not yet quantized
        self.pending = None                     # [image, rgb, hold ms, count]: not written
        self.shown = None                       # the picture shown (rgb) after the last
        self.counts = []

    def __call__(self, frame):
        self.batch.append(frame)
        if len(self.batch) >= GIF_BATCH:
            self._quantize()

    def _quantize(self):
        batch, self.batch = self.batch, []
        if self.threads <= 1 or len(batch) <= 1:
            done = [_quantized_rgb(f) for f in batch]
        else:
            from concurrent.futures import ThreadPoolExecutor
            with ThreadPoolExecutor(min(self.threads, len(batch))) as pool:
                done = list(pool.map(_quantized_rgb, batch))
        del batch
        for im, rgb in done:
            self._add(im, rgb)

    def _add(self, im, rgb):
        p = self.pending
        if p is not None and np.array_equal(rgb, p[1]):
            p[2] = min(p[2] + self.step, GIF_MAX_MS)
            p[3] += 1
            return
        self._write()
        self.pending = [im, rgb, self.step, 1]

    def _write(self):
        from PIL import GifImagePlugin
        if self.pending is None:
            return
        im, rgb, hold, count = self.pending
        box = (0, 0) + im.size
        if self.shown is None:
            head, _ = GifImagePlugin.getheader(im.copy(), info={"loop": 0, "duration": hold})
            self.fh.write(b"".join(head))
        else:
            diff = np.any(rgb != self.shown, axis=2)
            rows, cols = np.flatnonzero(diff.any(axis=1)), np.flatnonzero(diff.any(axis=0))
            box = (int(cols[0]), int(rows[0]), int(cols[-1]) + 1, int(rows[-1]) + 1)
        part = im if box == (0, 0) + im.size else im.crop(box)
        self.fh.write(b"".join(GifImagePlugin.getdata(part, offset=box[:2], duration=hold,
                                                      include_color_table=True)))
        self.shown = rgb
        self.counts.append(count)
        self.pending = None

    def close(self):
        self._quantize()
        self._write()
        if self.shown is None:
            raise ValueError("a GIF needs at least one frame")
        self.fh.write(b";")                         # the trailer


@contextlib.contextmanager
def _gif_writer(fh, fps, threads=None):
    """Yield send(frame): each (h, w, 4) uint8 frame, over white, into a looping GIF on
    the binary file object ``fh`` as it comes (_GifSink; send.counts after it). A
    failure leaves the file unfinished (atomic_file lets it go)."""
    send = _GifSink(fh, fps, (os.cpu_count() or 1) if threads is None else threads)
    yield send
    send.close()


def write_mp4(frames, path, fps):
    """The frames (a list, or frames read back from a file: decoded as they are
    written) as an H.264 MP4 (imageio-ffmpeg), over white, 1 / fps s each."""
    shape = frames.shape if isinstance(frames, _FileFrames) else np.asarray(frames[0]).shape[:2]
    with _mp4_writer(path, shape, fps) as send:
        for f in frames:
            send(f)


@contextlib.contextmanager
def _mp4_writer(path, shape, fps):
    """Yield send(frame): each (h, w, 4) uint8 frame of ``shape`` (h, w), over white,
    into an MP4 at ``path`` as it comes (ffmpeg encodes it in its own process). The
    file appears at the end, whole; a failure leaves none."""
    try:
        import imageio_ffmpeg
    except ImportError:
        raise ValueError("writing MP4 needs imageio-ffmpeg: pip install 'floatcol[video]' "
                         "(or write a .gif)") from None
    h, w = shape
    H, W = h + h % 2, w + w % 2                 # yuv420p wants even sides
    rgb = np.full((H, W, 3), 255, dtype=np.uint8)

    def send(f):
        a = f[..., 3:4].astype(np.float32) / 255.0
        rgb[:h, :w] = np.round(f[..., :3] * a + 255.0 * (1.0 - a)).astype(np.uint8)
        writer.send(rgb)

    with atomic_file(path) as tmp:
        writer = imageio_ffmpeg.write_frames(tmp, (W, H), fps=fps, codec="libx264",
                                             pix_fmt_in="rgb24", pix_fmt_out="yuv420p",
                                             macro_block_size=1, quality=8,
                                             output_params=["-f", "mp4"])
        writer.send(None)
        try:
            yield send
        finally:
            writer.close()


class _FileFrames:
    """The frames of a clip written to a file and not held (longer than KEEP_BYTES),
    decoded from the file when asked: (h, w, 4) uint8, opaque (over white), as
    encoded: an MP4's within a few levels of the rendered pictures (H.264 is lossy), a
    GIF's each quantized to its 255 colours (``counts``: how many of the clip's frames
    each of the file's shows, _GifSink). Iterating decodes the file once;
    ``frames[k]`` decodes it up to frame k."""

    def __init__(self, path, n, shape, counts=None):
        self.path = os.path.abspath(path)
        self.ext = os.path.splitext(path)[1].lower()
        self.n = n
        self.shape = shape
        self.counts = counts

    def __len__(self):
        return self.n

    def __iter__(self):
        return itertools.islice(self._gif() if self.ext == ".gif" else self._mp4(), self.n)

    def _mp4(self):
        import imageio_ffmpeg
        h, w = self.shape
        opaque = np.full((h, w, 1), 255, dtype=np.uint8)
        frames = imageio_ffmpeg.read_frames(self.path)
        try:
            W, H = next(frames)["size"]
            for _, raw in zip(range(self.n), frames):
                rgb = np.frombuffer(raw, dtype=np.uint8).reshape(H, W, 3)
                yield np.concatenate([rgb[:h, :w], opaque], axis=2)
        finally:
            frames.close()

    def _gif(self):
        from PIL import Image, ImageSequence
        with Image.open(self.path) as im:
            for count, frame in zip(self.counts, ImageSequence.Iterator(im)):
                rgba = np.asarray(frame.convert("RGBA"))
                for _ in range(count):
                    yield rgba

    def __getitem__(self, k):
        if isinstance(k, slice):                # (the file decoded once)
            wanted = range(*k.indices(self.n))
            if not wanted:
                return []
            got = {i: f for i, f in zip(range(max(wanted) + 1), self) if i in wanted}
            return [got[i] for i in wanted]
        k = operator.index(k)
        if k < 0:
            k += self.n
        if not 0 <= k < self.n:
            raise IndexError(f"frame {k} of {self.n}")
        return next(itertools.islice(iter(self), k, None))


def _streamed(output):
    """Whether a clip's frames go to ``output`` as they come (a .gif or .mp4 file), not
    held."""
    return output is not None and os.path.splitext(output)[1].lower() in ANIMATION_FORMATS


@contextlib.contextmanager
def _clip_writer(path, shape, fps):
    """Yield send(frame): each (h, w, 4) uint8 frame of ``shape`` (h, w) into the GIF
    or MP4 at ``path`` as it comes; the file appears at the end, whole, or not at all."""
    if os.path.splitext(path)[1].lower() == ".mp4":
        with _mp4_writer(path, shape, fps) as send:
            yield send
        return
    with atomic_file(path) as tmp, open(tmp, "wb") as fh, _gif_writer(fh, fps) as send:
        yield send


def _collect(made, n, size, output, fps):
    """A clip's n frames of ``size`` (W, H) from ``made``, an iterable of (rgba,
    samples), as they come: held in a list or, where there is an ``output`` (a .gif or
    .mp4), written to it one by one (and held as well where they take at most
    KEEP_BYTES, else read back from the file: _FileFrames), so that a long clip is
    never held. All of them the kernels' pictures, none a fresh install's draft
    (warmup.full_quality: a clip does not jump from drafts to the kernels' pictures
    when the warm-up is done; warmup imported here, as renderer._drafting says).
    Returns (frames, written, samples)."""
    from .warmup import full_quality
    W, H = size
    kept = []
    samples = 0
    with full_quality():
        if not _streamed(output):
            for f, k in made:
                kept.append(f)
                samples += k
            return kept, False, samples
        keep = n * W * H * 4 <= KEEP_BYTES
        with _clip_writer(output, (H, W), fps) as send:
            for f, k in made:
                send(f)
                samples += k
                if keep:
                    kept.append(f)
    counts = getattr(send, "counts", None)
    return (kept if keep else _FileFrames(output, n, (H, W), counts)), True, samples


class _Lazy:
    """A sequence of n items made when asked, make(k): a clip's surfaces (base.at(t),
    box-scaled) without one object a frame held through the clip."""

    def __init__(self, n, make):
        self.n = n
        self.make = make

    def __len__(self):
        return self.n

    def __getitem__(self, k):
        if not 0 <= k < self.n:
            raise IndexError(k)
        return self.make(k)

    def __iter__(self):
        return (self.make(k) for k in range(self.n))


class _Envelope:
    """The upper or lower envelope of several surfaces: what the clip's camera fits."""

    default_domain = None

    def __init__(self, surfaces, upper):
        self.surfaces = surfaces
        self.upper = upper
        self.variables = surfaces[0].variables

    def scaled(self, a, b, c):
        surfaces = self.surfaces
        return _Envelope(_Lazy(len(surfaces), lambda k: surfaces[k].scaled(a, b, c)),
                         self.upper)

    def evaluate(self, u, v):
        # a running maximum (minimum): a long clip's frames are never stacked (100 000
        # frames of a 65 x 65 grid were 3.4 GB a stack)
        empty = -np.inf if self.upper else np.inf
        out = None
        for s in self.surfaces:
            w = np.asarray(s.evaluate(u, v), dtype=float)
            w = np.where(np.isfinite(w), w, empty)
            out = w if out is None else (np.maximum(out, w) if self.upper else np.minimum(out, w))
        return np.where(np.isfinite(out), out, np.nan)


def _check_memory(frames, size, output=None):
    """A clip holds every frame's picture (Animation.frames): refuse one that cannot
    fit in the machine's memory (_memory.fits) rather than be killed for memory while
    it renders. One written to a file (``output``, a GIF or an MP4) holds none beyond
    KEEP_BYTES (_collect)."""
    if _streamed(output):
        return
    need = frames * int(size[0]) * int(size[1]) * 4
    if not fits(need):
        raise ValueError(f"{frames} frames of {size[0]}x{size[1]} take {need / 2**30:.1f} GiB, "
                         "more than this machine has: give fewer frames or a smaller size")


def _time_range(t):
    if isinstance(t, (tuple, list)) and len(t) == 3:
        name, lo, hi = t
        name = str(name)
    elif isinstance(t, (tuple, list)) and len(t) == 2:
        name, (lo, hi) = "t", t
    else:
        raise ValueError(f"t must be (low, high) or (symbol, low, high), got {t!r}")
    try:
        lo, hi = float(lo), float(hi)
    except (TypeError, ValueError):
        raise ValueError(f"the bounds of {name} must be real numbers, got {t!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi)) or lo == hi:
        raise ValueError(f"the time range {name} = {lo}..{hi} must be finite and not empty")
    return name, lo, hi


def animate(expr, *ranges, t=(0.0, 2 * math.pi), frames=60, output=None, fps=20,
            endpoint=False, progress=True, client=None, **options) -> Animation:
    """Render w = f(u, v, t) at ``frames`` times in ``t`` = (low, high) or
    (symbol, low, high) (the symbol defaults to t). ``endpoint=False`` leaves out
    t = high, so a periodic clip loops without a repeated frame. ``output``: a .gif or
    .mp4 file to write as the frames come (a long clip is never held, _collect),
    ``fps`` frames a second (0.01 to 120). Other options as
    :func:`floatcol.plot_surface`; ``lightsource`` may be a function of t giving
    (azdeg, altdeg) (a moving sun, with ``shadows=True`` its shadows move).
    ``client``: a dask.distributed Client: the frames are rendered as its tasks (each
    worker compiles the expression once; floatcol/cluster.py), the same pictures in
    the same order. A clip whose pictures would not fit in the machine's memory is a
    ValueError before its first frame, unless it is written to a file. Returns an
    :class:`Animation`.
    """
    import time as _time

    from tqdm.auto import tqdm

    t_name, t_lo, t_hi = _time_range(t)
    if isinstance(frames, bool) or not isinstance(frames, (int, np.integer)) or frames < 1:
        raise ValueError(f"frames must be a positive whole number, got {frames!r}")
    _check_fps(fps)
    if output is not None:
        output, _ = check_output(output, ANIMATION_FORMATS)
    start = _time.perf_counter()
    names, bounds = parse_ranges(expr, ranges, extra=(t_name,))
    if t_name in names:
        raise ValueError(f"{t_name} is the time; the surface's variables must be two others")
    sym = sympy_expression(expr, names + (t_name,))
    base = as_surface(sym, names, time=t_name)
    domain = tuple(check_range(n, b if b is not None else (-10.0, 10.0))
                   for n, b in zip(names, bounds))
    times = np.linspace(t_lo, t_hi, frames, endpoint=endpoint and frames > 1)
    # one compilation for the clip; a frame's surface made when its turn comes
    surfaces = _Lazy(len(times), lambda k: base.at(times[k]))
    ranges_ = [(names[0], *domain[0]), (names[1], *domain[1])]

    # a moving sun: lightsource a function of t, called per frame
    sun = options.pop("lightsource", None)
    suns = [sun(tk) if callable(sun) else sun for tk in times]
    if suns[0] is not None:
        options["lightsource"] = suns[0]
    # One camera for the clip: fitted to the envelope of all frames.
    vmin, vmax = options.pop("vmin", None), options.pop("vmax", None)
    first = plot_surface(surfaces[0], *ranges_, vmin=0.0, vmax=1.0, **options)
    _check_memory(frames, first.size, output)
    kw = first.render_kwargs(first.size)
    upper, lower = _Envelope(surfaces, True), _Envelope(surfaces, False)
    (ua, ub), (va, vb) = domain
    gu, gv = np.meshgrid(np.linspace(ua, ub, 65), np.linspace(va, vb, 65))
    hi_grid, lo_grid = upper.evaluate(gu, gv), lower.evaluate(gu, gv)
    w_hi = float(np.nanmax(hi_grid)) if np.isfinite(hi_grid).any() else 1.0
    w_lo = float(np.nanmin(lo_grid)) if np.isfinite(lo_grid).any() else 0.0
    # one box for the clip too: the domain and the range of f over all frames
    fixed = {"box": box_factors(kw.get("aspect", "equal"), None, domain, (w_lo, w_hi))}
    if kw.get("scale") is None:
        center = kw.get("center") or (0.5 * (ua + ub), 0.5 * (va + vb), 0.5 * (w_lo + w_hi))
        kw_fit = dict(kw, center=center, box=fixed["box"])
        views = [render_view(s, kw_fit)[0] for s in (upper, lower)]
        fixed.update(scale=min(v.scale for v in views), center=tuple(center))
        if kw["projection"] == "perspective":
            fixed.update(d1=min(v.d1 for v in views), d2=max(v.d2 for v in views))
            options.pop("focal_length", None)
    if "norm" not in options:
        fixed["vmin"] = w_lo if vmin is None else vmin
        fixed["vmax"] = (w_hi if w_hi > w_lo else w_lo + 1.0) if vmax is None else vmax
    if client is not None:
        from .cluster import _check_client
        _check_client(client)

    def made():
        if client is not None:
            from .cluster import render_frames
            tasks = [(sym, names, t_name, float(tk), ranges_,
                      dict(options, **fixed, **({} if sun_k is None else {"lightsource": sun_k})))
                     for tk, sun_k in zip(times, suns)]
            yield from render_frames(tasks, client)
            return
        for s, sun_k in tqdm(zip(surfaces, suns), total=len(times), desc="floatcol animate",
                             unit="frame", delay=1.0, disable=not progress, leave=False):
            if sun_k is not None:
                options["lightsource"] = sun_k
            r = plot_surface(s, *ranges_, **options, **fixed).draw()
            yield r.rgba, r.stats["samples"]
    out, written, samples = _collect(made(), frames, first.size, output, fps)
    anim = Animation(out, times, fps, {"samples": samples,
                                       "seconds": _time.perf_counter() - start,
                                       "camera": fixed})
    if output is not None and not written:
        anim.save(output)
    return anim

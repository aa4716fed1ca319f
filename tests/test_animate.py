"""Time-varying surfaces: one compilation, one camera, the right frames."""
import math
import sys

import numpy as np
import pytest
from PIL import Image

import floatcol as fc


def test_surface_at_t_equals_the_substituted_expression():
    s = fc.as_surface("sin(u - t)*cos(v)", time="t")
    u = np.linspace(-2, 2, 7)
    v = np.linspace(-1, 1, 7)
    for t in (0.0, 0.7, 2.5):
        st = s.at(t)
        assert st.f is s.f                                    # no recompilation
        fixed = fc.as_surface(f"sin(u - {t})*cos(v)")
        assert np.allclose(st.evaluate(u, v, derivatives=True),
                           fixed.evaluate(u, v, derivatives=True), atol=1e-12)


def test_frames_follow_the_formula_and_share_one_camera():
    anim = fc.animate("sin(x - t)", ("x", -3, 3), ("y", -1, 1), t=(0, 2 * math.pi),
                      frames=4, size=(80, 60), proj_type="ortho", progress=False)
    # t = 2 pi is left out (endpoint=False), so a periodic clip loops cleanly
    assert len(anim) == 4 and anim.times == pytest.approx([0, math.pi / 2, math.pi, 1.5 * math.pi])
    camera = anim.stats["camera"]
    assert {"scale", "center", "vmin", "vmax"} <= set(camera)
    for k in (1, 2):
        alone = fc.plot_surface(f"sin(x - {float(anim.times[k])!r})", ("x", -3, 3), ("y", -1, 1),
                                size=(80, 60), proj_type="ortho", **camera).rgba
        assert np.abs(alone.astype(int) - anim.frames[k]).max() <= 1
    assert not np.array_equal(anim.frames[0], anim.frames[2])


def test_fixed_camera_across_frames():
    """The clip's scale and colour range come from all frames: a bump that grows
    keeps the ground plane fixed on screen."""
    anim = fc.animate("t*exp(-(x^2 + y^2))", ("x", -2, 2), ("y", -2, 2), t=(0, 1), frames=3,
                      endpoint=True, size=(80, 60), progress=False)
    extents = []
    for f in anim.frames:
        rows, cols = np.nonzero(f[..., :3].astype(int).sum(axis=2) < 3 * 250)
        extents.append((rows.max(), cols.min(), cols.max()))
    # the plane's near, left and right corners stay on the same pixels
    assert extents[0] == extents[1] == extents[2]
    # while a single frame fitted on its own would be framed differently
    alone = fc.plot_surface("0*x", ("x", -2, 2), ("y", -2, 2), size=(80, 60)).rgba
    rows, cols = np.nonzero(alone[..., :3].astype(int).sum(axis=2) < 3 * 250)
    assert (rows.max(), cols.min(), cols.max()) != extents[0]


def test_gif_and_mp4(tmp_path):
    anim = fc.animate("sin(x + t)*cos(y)", ("x", -3, 3), ("y", -3, 3), t=(0, 1), frames=5,
                      size=(63, 47), output=tmp_path / "a.gif", progress=False)
    assert Image.open(tmp_path / "a.gif").n_frames == 5
    anim.save(tmp_path / "a.mp4")
    data = (tmp_path / "a.mp4").read_bytes()
    assert data[4:8] == b"ftyp"
    import imageio_ffmpeg
    frames = list(imageio_ffmpeg.read_frames(str(tmp_path / "a.mp4")))
    assert len(frames) - 1 == 5                               # first item is metadata
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.gif", "a.mp4"]
    assert "data:image/gif;base64" in anim._repr_html_()


def test_gif_frames_quantized_in_threads_are_the_serial_ones():
    """Each GIF frame is quantized on its own (to its own 255 colours), so quantizing
    them in threads writes the same file as one after the other, and the file's frames
    are the quantized pictures, pixel for pixel."""
    import io
    from floatcol.animate import _gif_writer, _quantized
    frames = [fc.render("sin(u*v + %g)" % (0.3 * k), u=(-3, 3), v=(-3, 3),
                        size=(90, 60)).rgba for k in range(5)]
    files = []
    for threads in (1, 3):
        buf = io.BytesIO()
        with _gif_writer(buf, 10, threads) as send:
            for f in frames:
                send(f)
        files.append(buf.getvalue())
    assert files[0] == files[1]
    im = Image.open(io.BytesIO(files[0]))
    assert im.n_frames == 5
    for k, f in enumerate(frames):
        im.seek(k)
        assert np.array_equal(np.asarray(im.convert("RGB")),
                              np.asarray(_quantized(f).convert("RGB")))


def test_a_still_gif_at_the_slowest_rate(tmp_path):
    """Frames equal to the one before lengthen its hold, which a GIF keeps to 655.35 s:
    ten equal frames at 0.01 fps (1000 s) are one frame held that long (Pillow merged
    them into a hold its 16 bits could not hold: OverflowError); different frames keep
    their own holds."""
    still = fc.render("u*v", size=(20, 16)).rgba
    fc.Animation([still] * 10, list(range(10)), 0.01).save(tmp_path / "still.gif")
    im = Image.open(tmp_path / "still.gif")
    assert (im.n_frames, im.info["duration"]) == (1, 655_350)
    a, b = (fc.render(e, size=(20, 16)).rgba for e in ("u*v", "u*v + u"))
    fc.Animation([a, a, b, b, b], list(range(5)), 10).save(tmp_path / "two.gif")
    im = Image.open(tmp_path / "two.gif")
    holds = []
    for k in range(im.n_frames):
        im.seek(k)
        holds.append(im.info["duration"])
    assert holds == [200, 300]


def test_a_clip_too_big_to_hold_is_refused_before_it_renders(tmp_path, monkeypatch):
    """A clip without a file keeps every frame's picture: one that cannot fit in memory
    (80 % of the machine's, as a picture's buffers) is a ValueError before the first
    frame, not a process killed for memory (the CLI's --frames=100000 at 480x360 asked
    64 GiB). Its camera's envelope is a running maximum, so no frames x grid stack is
    built either. (One written to a file holds none: below.)"""
    import floatcol._memory as memory
    need = 10 * 20 * 16 * 4
    monkeypatch.setattr(memory, "machine_bytes", lambda: (need - 1) / memory.SHARE)
    with pytest.raises(ValueError, match="10 frames of 20x16 take 0.0 GiB, more than this"):
        fc.animate("sin(x - t)", ("x", -1, 1), ("y", -1, 1), size=(20, 16), frames=10,
                   progress=False)
    assert list(tmp_path.iterdir()) == []


def test_a_clip_too_big_to_hold_is_written_to_an_mp4_as_it_comes(tmp_path, monkeypatch):
    """To an MP4 a clip's frames go to the encoder as they are rendered, so one too big
    to hold is not refused: its frames are read back from the file when asked, within
    a few levels of the pictures (H.264), at their own odd size (the video's even one
    cropped). Kept frames and copies of the file are the same frames; a GIF of it is
    written as its frames are decoded."""
    anim_mod = sys.modules["floatcol.animate"]
    kw = dict(t=(0, 1), size=(21, 15), frames=6, progress=False)
    held = fc.animate("sin(3*x - t)*y", ("x", -1, 1), ("y", -1, 1), **kw)
    monkeypatch.setattr(anim_mod, "fits", lambda need: need < 6 * 21 * 15 * 4)
    with pytest.raises(ValueError, match="6 frames of 21x15 take"):
        fc.animate("sin(3*x - t)*y", ("x", -1, 1), ("y", -1, 1), **kw)
    monkeypatch.setattr(anim_mod, "KEEP_BYTES", 0)
    anim = fc.animate("sin(3*x - t)*y", ("x", -1, 1), ("y", -1, 1),
                      output=tmp_path / "a.mp4", **kw)
    assert not isinstance(anim.frames, list) and len(anim) == 6
    back = list(anim.frames)
    assert len(back) == 6 and all(f.shape == (15, 21, 4) and f.dtype == np.uint8 for f in back)
    assert all((f[..., 3] == 255).all() for f in back)
    for f, g in zip(back, held.frames):
        a = g[..., 3:4] / 255.0
        over_white = g[..., :3] * a + 255 * (1 - a)
        # measured: 2.8-3.4 levels on average (a tiny picture; H.264 at quality 8, its
        # colour at half the resolution)
        assert np.abs(f[..., :3] - over_white).mean() < 5
    assert not np.array_equal(back[0], back[3])
    assert np.array_equal(anim.frames[-1], back[5]) and np.array_equal(anim.frames[2], back[2])
    assert [f.shape for f in anim.frames[1:3]] == [(15, 21, 4)] * 2
    assert all(np.array_equal(a, back[i]) for a, i in zip(anim.frames[::-2], (5, 3, 1)))
    assert anim.frames[4:2] == []
    with pytest.raises(IndexError):
        anim.frames[6]
    anim.save(tmp_path / "copy.mp4")              # the file itself, not encoded again
    assert (tmp_path / "copy.mp4").read_bytes() == (tmp_path / "a.mp4").read_bytes()
    assert anim.save(tmp_path / "a.mp4") == str(tmp_path / "a.mp4")
    anim.save(tmp_path / "a.gif")                 # (decoded as it is written)
    assert Image.open(tmp_path / "a.gif").n_frames == 6
    assert "data:video/mp4;base64" in anim._repr_html_()
    monkeypatch.setattr(anim_mod, "EMBED_BYTES", 10)
    assert "6 frames in" in anim._repr_html_() and "a.mp4" in anim._repr_html_()
    monkeypatch.undo()
    # a clip short enough keeps its pictures too: the same frames as without a file
    kept = fc.animate("sin(3*x - t)*y", ("x", -1, 1), ("y", -1, 1),
                      output=tmp_path / "k.mp4", **kw)
    assert isinstance(kept.frames, list)
    assert all(np.array_equal(a, b) for a, b in zip(kept.frames, held.frames))
    assert len(anim_mod._FileFrames(str(tmp_path / "k.mp4"), 6, (15, 21))[0:6]) == 6


def test_a_clip_too_big_to_hold_is_written_to_a_gif_as_it_comes(tmp_path, monkeypatch):
    """To a GIF too a clip's frames are written as they are rendered (quantized in a
    core's threads, a frame or so in flight each): one too big to hold is not refused,
    and its frames are read back from the file when asked, each the rendered picture
    quantized to its 255 colours, pixel for pixel. Equal frames are one frame of the
    file, held longer, and read back as many. Copies are the file; an MP4 of it is
    written as its frames are decoded; a notebook shows the file."""
    from floatcol.animate import _quantized
    anim_mod = sys.modules["floatcol.animate"]
    kw = dict(t=(0, 1), size=(21, 15), frames=6, progress=False)
    held = fc.animate("sin(3*x - t)*y", ("x", -1, 1), ("y", -1, 1), **kw)
    monkeypatch.setattr(anim_mod, "fits", lambda need: need < 6 * 21 * 15 * 4)
    monkeypatch.setattr(anim_mod, "KEEP_BYTES", 0)
    anim = fc.animate("sin(3*x - t)*y", ("x", -1, 1), ("y", -1, 1),
                      output=tmp_path / "a.gif", **kw)
    assert not isinstance(anim.frames, list) and len(anim) == 6
    back = list(anim.frames)
    assert [f.shape for f in back] == [(15, 21, 4)] * 6
    for f, g in zip(back, held.frames):
        assert np.array_equal(f, np.asarray(_quantized(g).convert("RGBA")))
    assert not np.array_equal(back[0], back[3])
    assert np.array_equal(anim.frames[4], back[4]) and len(anim.frames[1:4]) == 3
    anim.save(tmp_path / "copy.gif")
    assert (tmp_path / "copy.gif").read_bytes() == (tmp_path / "a.gif").read_bytes()
    anim.save(tmp_path / "a.mp4")
    import imageio_ffmpeg
    assert len(list(imageio_ffmpeg.read_frames(str(tmp_path / "a.mp4")))) == 7   # (+ metadata)
    assert "data:image/gif;base64" in anim._repr_html_()
    # a still clip: one frame in the file, held six frames' time, read back six times
    still = fc.animate("sin(3*x)*y + 0*t", ("x", -1, 1), ("y", -1, 1),
                       output=tmp_path / "still.gif", fps=10, **kw)
    with Image.open(tmp_path / "still.gif") as im:
        assert (im.n_frames, im.info["duration"]) == (1, 600)
    frames = list(still.frames)
    assert len(frames) == 6 and all(np.array_equal(f, frames[0]) for f in frames)


@pytest.mark.parametrize("ext", [".mp4", ".gif"])
def test_a_failed_clip_leaves_no_file(tmp_path, monkeypatch, ext):
    """A clip that fails while its frames are written (here the third frame's render)
    leaves no file, not even the encoder's temporary one."""
    import floatcol.plot as plot_mod
    anim_mod = sys.modules["floatcol.animate"]
    calls = []
    real = anim_mod.plot_surface

    def failing(*args, **kw):
        calls.append(1)
        if len(calls) == 4:                     # (the first is the camera's fit)
            raise ValueError("the third frame fails")
        return real(*args, **kw)
    monkeypatch.setattr(anim_mod, "plot_surface", failing)
    with pytest.raises(ValueError, match="third frame"):
        fc.animate("sin(x - t)", ("x", -1, 1), ("y", -1, 1), size=(20, 16), frames=5,
                   output=tmp_path / f"a{ext}", progress=False)
    assert list(tmp_path.iterdir()) == []
    assert plot_mod.plot_surface is real


def test_a_clip_holds_no_surface_a_frame(monkeypatch):
    """A frame's surface (base.at(t), box-scaled for the camera's fit) is made when its
    turn comes: while a 12-frame clip renders, a handful are alive at a time, not one a
    frame (a million frames held a million Surfaces besides their pictures). (12 frames:
    each counts after a full garbage collection, about 0.15 s late in the suite.)"""
    import gc
    import sys
    import weakref
    from floatcol.surface import Surface
    anim_mod = sys.modules["floatcol.animate"]     # (fc.animate is the function)
    made = []
    at = Surface.at

    def tracked(self, t):
        s = at(self, t)
        made.append(weakref.ref(s))
        return s
    monkeypatch.setattr(Surface, "at", tracked)
    alive = []
    plot = anim_mod.plot_surface

    def counting(*a, **k):
        gc.collect()
        alive.append(sum(r() is not None for r in made))
        return plot(*a, **k)
    monkeypatch.setattr(anim_mod, "plot_surface", counting)
    a = fc.animate("sin(x - t)*cos(y)", ("x", -2, 2), ("y", -2, 2), size=(24, 18), frames=12,
                   progress=False)
    assert len(a.frames) == 12 and len(made) >= 12
    assert max(alive) <= 4, alive


@pytest.mark.parametrize("frames,fps,needle", [
    ([], 20, "frames is empty"),
    ([np.zeros((16, 20, 4), np.uint8), np.zeros((17, 20, 4), np.uint8)], 20,
     "frame 1 is 20x17, frame 0 20x16: frames must be of one size"),
    ([np.zeros((16, 20, 4))], 20, r"frame 0 must be an \(H, W, 4\) uint8 picture"),
    ([np.zeros((0, 0, 4), np.uint8)], 20, "frame 0 must be"),
    ([np.zeros((16, 20, 4), np.uint8)], 0, "fps must be a number in"),
    ([np.zeros((16, 20, 4), np.uint8)], "x", "fps must be a number in"),
])
def test_an_animation_made_by_hand_says_what_is_wrong(frames, fps, needle, tmp_path):
    """fc.Animation is public: empty frames, frames of two sizes or of another type, or a
    bad fps crashed at save (IndexError, TypeError, ffmpeg's own lines on stderr)."""
    with pytest.raises(ValueError, match=needle):
        fc.Animation(frames, list(range(len(frames))), fps).save(tmp_path / "a.gif")
    assert list(tmp_path.iterdir()) == []


def test_an_animation_of_opaque_rgb_frames(tmp_path):
    rgb = np.zeros((16, 20, 3), np.uint8)
    rgb[:, 10:] = (255, 0, 0)
    anim = fc.Animation([rgb, rgb[::-1].copy()], [0, 1], 10)
    assert anim.frames[0].shape == (16, 20, 4) and (anim.frames[0][..., 3] == 255).all()
    anim.save(tmp_path / "a.gif")
    assert Image.open(tmp_path / "a.gif").convert("RGB").getpixel((15, 3)) == (255, 0, 0)


@pytest.mark.parametrize("kw,needle", [
    (dict(frames=0), "frames"), (dict(t=(1, 1)), "time range"), (dict(t=5), "t must be"),
    (dict(fps=0), "fps"), (dict(output="clip.avi"), "must end in"),
    # (0.001 fps crashed in Pillow's GIF writer: a frame's hold past its 16 bits)
    (dict(fps=0.001, output="slow.gif"), r"fps must be a number in \[0.01, 120\]"),
])
def test_bad_animation_options(kw, needle, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match=needle):
        fc.animate("sin(x - t)", ("x", -1, 1), ("y", -1, 1), size=(20, 20), progress=False, **kw)
    assert list(tmp_path.iterdir()) == []

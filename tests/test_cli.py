"""The floatcol command: each success writes its file; each user mistake prints one
line on stderr, exits 2, shows no traceback and leaves no file."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from floatcol.cli import main

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def run(*args, cwd):
    return subprocess.run([sys.executable, "-m", "floatcol.cli", *args], cwd=cwd,
                          capture_output=True, text=True)


def run_here(capsys, monkeypatch, tmp_path, *args):
    monkeypatch.chdir(tmp_path)
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def test_render_writes_png(tmp_path):
    p = run("render", "3*sin(u*cos(v))", "--u", "-5:5", "--v=-5:5", "--size", "120x90",
            "--azim", "-40", "-o", "out.png", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "out.png").read_bytes()[:8] == PNG_MAGIC
    im = Image.open(tmp_path / "out.png")
    assert im.size == (120, 90)
    assert list(tmp_path.iterdir()) == [tmp_path / "out.png"]     # no temporary left
    umask = os.umask(0)
    os.umask(umask)
    assert (tmp_path / "out.png").stat().st_mode & 0o777 == 0o666 & ~umask


def test_render_matches_plot_surface(capsys, monkeypatch, tmp_path):
    """The CLI's options mean what plot_surface's do: same picture, pixel for pixel."""
    import floatcol as fc
    code, out, _ = run_here(capsys, monkeypatch, tmp_path, "render", "x**2 - y**2",
                            "--x=-2:2", "--y=-1:1", "--size", "64x48", "--elev", "40",
                            "--azim", "-30", "--proj", "ortho", "--cmap", "magma", "-o", "s.png")
    assert code == 0 and out.startswith("wrote s.png")
    want = fc.plot_surface("x**2 - y**2", ("x", -2, 2), ("y", -1, 1), size=(64, 48), elev=40,
                           azim=-30, proj_type="ortho", cmap="magma").rgba
    got = np.asarray(Image.open(tmp_path / "s.png"))
    assert np.array_equal(got, want)


def test_ranges_take_constant_expressions(capsys, monkeypatch, tmp_path):
    import floatcol as fc
    code, _, err = run_here(capsys, monkeypatch, tmp_path, "render", "sin(x)*cos(y)",
                            "--x", "-pi:2*pi", "--y=-sqrt(2):1e0", "--size", "48x36", "-o", "s.png")
    assert code == 0, err
    want = fc.plot_surface("sin(x)*cos(y)", ("x", -math.pi, 2 * math.pi),
                           ("y", -math.sqrt(2), 1.0), size=(48, 36)).rgba
    assert np.array_equal(np.asarray(Image.open(tmp_path / "s.png")), want)


def test_several_expressions_make_one_picture(capsys, monkeypatch, tmp_path):
    import floatcol as fc
    code, out, _ = run_here(capsys, monkeypatch, tmp_path, "render", "x*y/3",
                            "2*exp(-x^2-y^2) - 0.5", "--x=-2:2", "--y=-2:2", "--size", "64x48",
                            "-o", "two.png")
    assert code == 0 and out.startswith("wrote two.png")
    want = fc.plot_surface(["x*y/3", "2*exp(-x**2-y**2) - 0.5"], ("x", -2, 2), ("y", -2, 2),
                           size=(64, 48))
    assert {0, 1} <= set(np.unique(want.draw().stats["surface"]))
    assert np.array_equal(np.asarray(Image.open(tmp_path / "two.png")), want.rgba)


@pytest.mark.parametrize("flags,opts", [
    (("--corrections", "none", "--antialias", "off"), dict(corrections="none", antialias=False)),
    (("--antialias", "3", "--sampling", "adaptive"), dict(antialias=3, sampling="adaptive")),
    (("--aspect", "equal"), dict(aspect="equal")),
    (("--aspect", "1:2:1"), dict(aspect=(1.0, 2.0, 1.0))),
    (("--ambient", "0.6", "--specular", "0.5", "--shininess", "8"),
     dict(ambient=0.6, specular=0.5, shininess=8.0)),
    (("--pixel-step", "3"), dict(pixel_step=3.0)),
    (("--norm", "symlog", "--vmin", "-2"), dict(norm="symlog", vmin=-2.0)),
    (("--ambient", "1", "--specular", "0"), dict(shade=False)),      # (flat: as --no-shade)
])
def test_fidelity_flags_match_plot_surface(capsys, monkeypatch, tmp_path, flags, opts):
    import floatcol as fc
    code, _, _ = run_here(capsys, monkeypatch, tmp_path, "render", "3*sin(x*cos(y))",
                          "--x=-5:5", "--y=-5:5", "--size", "64x48", *flags, "-o", "s.png")
    assert code == 0
    want = fc.plot_surface("3*sin(x*cos(y))", ("x", -5, 5), ("y", -5, 5), size=(64, 48), **opts)
    default = fc.plot_surface("3*sin(x*cos(y))", ("x", -5, 5), ("y", -5, 5), size=(64, 48))
    got = np.asarray(Image.open(tmp_path / "s.png"))
    assert np.array_equal(got, want.rgba)
    assert not np.array_equal(got, default.rgba)


@pytest.mark.parametrize("ext,magic", [(".jpg", b"\xff\xd8\xff"), (".pdf", b"%PDF"),
                                       (".svg", b"<?xml")])
def test_render_other_formats(capsys, monkeypatch, tmp_path, ext, magic):
    code, _, err = run_here(capsys, monkeypatch, tmp_path, "render", "sin(u)*cos(v)",
                            "--size", "40x30", "-o", "out" + ext)
    assert code == 0, err
    assert (tmp_path / ("out" + ext)).read_bytes()[:len(magic)] == magic
    assert [p.name for p in tmp_path.iterdir()] == ["out" + ext]


def test_animate_writes_gif_with_frames(capsys, monkeypatch, tmp_path):
    code, out, err = run_here(capsys, monkeypatch, tmp_path, "animate", "sin(x - t)*cos(y)",
                              "--x=-3:3", "--y=-3:3", "--size", "48x36", "--frames", "5",
                              "--t", "0:3", "-o", "w.gif")
    assert code == 0, err
    im = Image.open(tmp_path / "w.gif")
    assert im.n_frames == 5 and im.size == (48, 36)
    assert [p.name for p in tmp_path.iterdir()] == ["w.gif"]


@pytest.mark.parametrize("args,needle", [
    (["render", "3*sin(u", "-o", "x.png"], "could not parse"),
    (["render", "x*y*z", "-o", "x.png"], "unknown symbol z"),
    (["render", "u", "--u", "2:1", "-o", "x.png"], "reversed"),
    (["render", "u", "--u", "1:1", "-o", "x.png"], "empty"),
    (["render", "u", "--u", "a:b", "-o", "x.png"], "LOW:HIGH"),
    (["render", "u", "--u=-pi:I", "-o", "x.png"], "LOW:HIGH"),
    (["render", "u", "--size", "0x10", "-o", "x.png"], "positive"),
    (["render", "u", "--size", "big", "-o", "x.png"], "WIDTHxHEIGHT"),
    (["render", "u", "-o", "no/such/dir/x.png"], "does not exist"),
    (["render", "u", "-o", "x.gif"], "must end in .eps, .jpeg, .jpg, .pdf, .png, .ps, .svg, .tif, .tiff, .webp"),
    (["render", "u", "--bogus", "-o", "x.png"], "unrecognized arguments"),
    (["render", "u", "--proj", "fisheye", "-o", "x.png"], "invalid choice"),
    (["render", "u", "--aspect", "cube", "-o", "x.png"], "BX:BY:BZ"),
    (["render", "u", "--aspect", "1:0:1", "-o", "x.png"], "positive"),
    (["render", "u", "--cmap", "nosuchmap", "-o", "x.png"], "nosuchmap"),
    (["render", "u", "--elev", "120", "-o", "x.png"], "elev"),
    (["render", "u*v", "--vars", "u", "-o", "x.png"], "--vars"),
    (["render", "u", "--vmin", "3", "--vmax", "1", "-o", "x.png"], "vmin must not exceed vmax"),
    (["render", "u", "--vmin", "nan", "-o", "x.png"], "vmin must be a finite number"),
    (["render", "u", "--ambient", "2", "-o", "x.png"], "--ambient must be in [0, 1]"),
    (["render", "u*v", "--norm", "logit", "-o", "x.png"], "give --vmin and --vmax inside"),
    (["render", "u", "--specular", "-1", "-o", "x.png"], "--specular must be in [0, 1]"),
    (["render", "u", "--shininess", "0", "-o", "x.png"], "--shininess must be positive"),
    (["render", "u", "--pixel-step", "0", "-o", "x.png"], "--pixel-step must be positive"),
    (["render", "u", "--texture-filter", "cubic", "-o", "x.png"], "invalid choice"),
    (["animate", "sin(u - t)", "--frames", "0", "-o", "x.gif"], "frames"),
    (["animate", "sin(u - t)", "--t", "1:1", "-o", "x.gif"], "time range"),
    (["animate", "sin(u - t)", "-o", "x.png"], "must end in .gif, .mp4"),
    (["gallery"], "gallery build"),
    (["frobnicate"], "invalid choice"),
    ([], "say what to do"),
])
def test_user_mistakes_exit_2_with_one_line(capsys, monkeypatch, tmp_path, args, needle):
    code, out, err = run_here(capsys, monkeypatch, tmp_path, *args)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert needle in lines[0]
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("args,words,not_words", [
    (["--lines-only"], ["--lines-only draws", "give --wireframe or --contours"],
     ["fill=", "wireframe=", "contours="]),
    (["--opacity", "2"], ["--opacity must be in [0, 1], got 2.0"], ["alpha"]),
    (["--light-radius", "1"], ["--light-radius gives soft shadows", "with --shadows"],
     ["light_radius", "shadows=True"]),
    (["--lines-only", "--wireframe", "8", "--opacity", "0.5"], ["give --opacity 1"],
     ["opacity=", "fill="]),
])
def test_errors_of_the_library_speak_the_command_lines_words(capsys, monkeypatch, tmp_path,
                                                               args, words, not_words):
    """The library's errors name its keywords (fill=False, light_radius, shadows=True);
    the command line names its own options for them (cli.cli_words)."""
    code, _, err = run_here(capsys, monkeypatch, tmp_path, "render", "sin(u*v)", "--size",
                            "40x30", *args, "-o", "x.png")
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    for w in words:
        assert w in err, err
    for w in not_words:
        assert w not in err, err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("message,expected", [
    ("the surface's lines alone, its size and shading",
     "the surface's lines alone, its size and shading"),
    ("vmin must not exceed vmax, got vmin=3 > vmax=1",
     "--vmin must not exceed vmax, got vmin=3 > vmax=1"),
    ("shading='lambert' lights from the viewpoint", "--shading lambert lights from the viewpoint"),
    ("use antialias=True or antialias=2", "use --antialias on or --antialias 2"),
    ("got vmin=5 > vmax=-5 (as in matplotlib)", "got vmin=5 > vmax=-5 (as in matplotlib)"),
    ("the variables are x and y (or pass vars=('u', 'v') to use them)",
     "the variables are x and y (or pass --vars u,v to use them)"),
    ("the surface's lines: give wireframe= (the picture's)",
     "the surface's lines: give --wireframe (the picture's)"),
    ("unknown symbols u, v: the variables are x and y (give a range (symbol, low, high) for "
     "each variable)",
     "unknown symbols u, v: the variables are x and y (name the two with --vars X,Y)"),
    # what it quotes is the user's: kept as it is
    ("could not parse expression 'give opacity=1 fill=False light_radius' at 3",
     "could not parse expression 'give opacity=1 fill=False light_radius' at 3"),
    ("cannot write \x000\x00 fill=False", "cannot write \x000\x00 fill=False"),
])
def test_cli_words_leave_plain_words_and_reported_values(message, expected):
    from floatcol.cli import cli_words
    assert cli_words(message) == expected


def test_output_that_is_a_folder(capsys, monkeypatch, tmp_path):
    (tmp_path / "x.png").mkdir()
    code, _, err = run_here(capsys, monkeypatch, tmp_path, "render", "u", "-o", "x.png")
    assert code == 2 and "folder" in err and len(err.strip().splitlines()) == 1
    assert [p.name for p in tmp_path.iterdir()] == ["x.png"] and not any((tmp_path / "x.png").iterdir())


def test_mistake_through_the_real_command_has_no_traceback(tmp_path):
    p = run("render", "sin(u", "-o", "x.png", cwd=tmp_path)
    assert p.returncode == 2
    assert "Traceback" not in p.stderr and len(p.stderr.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


def test_a_surface_that_is_nowhere_finite_warns_in_one_line(capsys, monkeypatch, tmp_path):
    # 1e309 overflows a double: f is infinite (or NaN at u = 0) everywhere. The
    # picture is written (empty), and one line says why it is empty.
    code, out, err = run_here(capsys, monkeypatch, tmp_path, "render", "1e309*u",
                              "--size", "80x60", "-o", "x.png")
    assert code == 0 and (tmp_path / "x.png").is_file()
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("floatcol: warning: ")
    assert "everywhere on u in [-10, 10]" in lines[0] and "empty" in lines[0]


def test_help_has_examples_and_version():
    p = subprocess.run([sys.executable, "-m", "floatcol.cli", "--help"], capture_output=True, text=True)
    assert p.returncode == 0 and "examples:" in p.stdout and "floatcol animate" in p.stdout
    p = subprocess.run([sys.executable, "-m", "floatcol.cli", "--version"], capture_output=True, text=True)
    import floatcol
    assert p.returncode == 0 and p.stdout.strip() == f"floatcol {floatcol.__version__}"

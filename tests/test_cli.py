"""The floatcol command: success writes a PNG; user mistakes print one line, exit 2,
and leave no file."""
import subprocess
import sys

import pytest


def run(*args, cwd):
    return subprocess.run([sys.executable, "-m", "floatcol.cli", *args], cwd=cwd,
                          capture_output=True, text=True)


def test_render_writes_png(tmp_path):
    p = run("render", "3*sin(u*cos(v))", "--u", "-5:5", "--v=-5:5", "--size", "120x90",
            "-o", "out.png", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    data = (tmp_path / "out.png").read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    from PIL import Image
    im = Image.open(tmp_path / "out.png")
    assert im.size == (120, 90)
    assert list(tmp_path.iterdir()) == [tmp_path / "out.png"]     # no temporary left
    import os
    umask = os.umask(0)
    os.umask(umask)
    assert (tmp_path / "out.png").stat().st_mode & 0o777 == 0o666 & ~umask


@pytest.mark.parametrize("args,needle", [
    (["render", "3*sin(u", "-o", "x.png"], "could not parse"),
    (["render", "x*y", "-o", "x.png"], "unknown symbols x, y"),
    (["render", "u", "--u", "2:1", "-o", "x.png"], "reversed"),
    (["render", "u", "--u", "a:b", "-o", "x.png"], "LOW:HIGH"),
    (["render", "u", "--size", "0x10", "-o", "x.png"], "positive"),
    (["render", "u", "-o", "no/such/dir/x.png"], "does not exist"),
    (["render", "u", "-o", "x.jpg"], "must end in .png"),
    (["render", "u", "--bogus", "-o", "x.png"], "unrecognized arguments"),
    (["render", "u", "--proj", "fisheye", "-o", "x.png"], "invalid choice"),
    ([], "say what to do"),
])
def test_user_mistakes_exit_2_with_one_line(tmp_path, args, needle):
    p = run(*args, cwd=tmp_path)
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1, p.stderr
    assert needle in lines[0]
    assert "Traceback" not in p.stderr
    assert list(tmp_path.iterdir()) == []


def test_version():
    p = subprocess.run([sys.executable, "-m", "floatcol.cli", "--version"], capture_output=True, text=True)
    assert p.returncode == 0 and p.stdout.startswith("floatcol ")

"""The gallery: enough examples, each documented; the builder's page links only to
files it wrote."""
import ast
from html.parser import HTMLParser

import pytest

from floatcol.cli import main
from floatcol.gallery import build, default_source

SOURCE = default_source()


class _Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.refs, self.cards = [], 0

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "img":
            self.refs.append(a["src"])
        elif tag == "a":
            self.refs.append(a["href"])
        elif tag == "section":
            self.cards += 1


def _check_page(out, n):
    page = _Links()
    page.feed((out / "index.html").read_text(encoding="utf-8"))
    assert page.cards == n
    assert page.refs, "no links"
    for ref in page.refs:
        assert (out / ref).is_file(), ref
    return page


def test_at_least_twelve_documented_examples():
    scripts = sorted(SOURCE.glob("*.py"))
    assert len(scripts) >= 12
    for p in scripts:
        doc = ast.get_docstring(ast.parse(p.read_text()))
        assert doc and len(doc.splitlines()[0]) > 10, p.name


def test_build_a_subset_writes_pictures_thumbnails_and_index(tmp_path):
    res = build(tmp_path, only=["saddle", "gordon_figures", "wave_animation"], progress=False)
    assert res.failed == {}
    page = _check_page(tmp_path, 3)
    imgs = [r for r in page.refs if r.startswith("img/")]
    thumbs = [r for r in page.refs if r.startswith("thumbs/")]
    srcs = [r for r in page.refs if r.startswith("src/")]
    assert len(imgs) == len(thumbs) == 1 + 4 + 1        # gordon_figures writes four
    assert sorted(srcs) == ["src/gordon_figures.py", "src/saddle.py", "src/wave_animation.py"]
    assert "img/wave_animation.gif" in imgs
    from PIL import Image
    for t in thumbs:
        assert Image.open(tmp_path / t).width <= 360
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]   # no work folders


def test_cli_gallery_build_and_unknown_example(tmp_path, capsys):
    assert main(["gallery", "build", "-o", str(tmp_path / "g"), "--only", "peaks"]) == 0
    _check_page(tmp_path / "g", 1)
    capsys.readouterr()     # the first build's progress bar (shown when it takes over 1 s)
    assert main(["gallery", "build", "-o", str(tmp_path / "h"), "--only", "nosuch"]) == 2
    err = capsys.readouterr().err
    assert "no gallery example named nosuch" in err and len(err.strip().splitlines()) == 1


def test_a_failing_example_is_reported_and_the_rest_still_build(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    (src / "good.py").write_text('"""A good example here."""\nimport floatcol as fc\n'
                                 'fc.plot_surface("x*y", ("x", -1, 1), ("y", -1, 1), size=(40, 30)).save("g.png")\n')
    (src / "bad.py").write_text('"""A broken example here."""\nraise RuntimeError("boom")\n')
    res = build(tmp_path / "out", source=src, progress=False)
    assert set(res.failed) == {"bad"} and "boom" in res.failed["bad"]
    _check_page(tmp_path / "out", 2)


@pytest.mark.parametrize("name", sorted(p.stem for p in SOURCE.glob("*.py")))
def test_every_example_runs(tmp_path, name):
    res = build(tmp_path, only=[name], progress=False)
    assert res.failed == {}, res.failed
    assert res.examples[0].images

"""The user guide documents every option there is, and builds."""
import inspect
import re
import subprocess
import sys
from pathlib import Path

import floatcol as fc
from floatcol.cli import build_parser
from floatcol.plot import _OWN_OPTIONS

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
OPTIONS = (DOCS / "options.md").read_text(encoding="utf-8")


def _documented(name):
    return f"`{name}`" in OPTIONS


def test_every_render_option_is_documented():
    missing = [p for p in inspect.signature(fc.render).parameters if not _documented(p)]
    assert missing == []


def test_every_plot_surface_and_animate_option_is_documented():
    names = set(_OWN_OPTIONS) | {"ax", "interactive", "label"}
    names |= set(inspect.signature(fc.animate).parameters) - {"expr", "ranges", "options"}
    assert sorted(n for n in names if not _documented(n)) == []


def test_every_cli_option_is_documented():
    parser = build_parser()
    sub = parser._subparsers._group_actions[0].choices
    flags = {f for name in ("render", "animate", "terrain") for a in sub[name]._actions
             for f in a.option_strings if f.startswith("--") and f != "--help"}
    assert sorted(f for f in flags if f not in OPTIONS) == []


def test_pictures_and_pages_exist():
    for page in DOCS.glob("*.md"):
        for ref in re.findall(r"!\[[^\]]*\]\(([^)]+)\)", page.read_text(encoding="utf-8")):
            assert (DOCS / ref).is_file(), (page.name, ref)
    nav = re.findall(r":\s*(\S+\.md)", (ROOT / "mkdocs.yml").read_text())
    assert len(nav) >= 6 and all((DOCS / n).is_file() for n in nav)


def test_every_gallery_script_is_on_the_gallery_pages():
    """docs/gallery.md and gallery/README.md name every script of gallery/ (four were
    missing from the docs' page)."""
    pages = [(DOCS / "gallery.md").read_text(encoding="utf-8"),
             (ROOT / "gallery" / "README.md").read_text(encoding="utf-8")]
    scripts = sorted(p.name for p in (ROOT / "gallery").glob("*.py"))
    assert len(scripts) > 10
    for page in pages:
        assert [s for s in scripts if s not in page] == []


def test_mkdocs_builds_strict(tmp_path):
    p = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-q",
                        "-d", str(tmp_path / "site")], cwd=ROOT, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "site" / "options" / "index.html").is_file()

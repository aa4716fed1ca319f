"""Build the example gallery: run each script, collect its pictures, write index.html.

``floatcol gallery build -o DIR`` runs every ``*.py`` in the gallery folder (the
checkout's ``gallery/`` unless ``source=`` says otherwise) in a fresh working folder,
with matplotlib's Agg backend. Each picture a script writes (.png, .gif, .jpg) goes to
``DIR/img/``, a thumbnail to ``DIR/thumbs/``, the script to ``DIR/src/``; ``index.html``
shows the thumbnails, each linking to its full picture and to its source.
"""
from __future__ import annotations

import ast
import html
import os
import shutil
import tempfile
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path

PICTURES = (".png", ".gif", ".jpg", ".jpeg")
THUMB_WIDTH = 360


@dataclass
class Example:
    name: str
    title: str
    description: str
    source: Path
    images: list = field(default_factory=list)     # paths relative to the output folder
    thumbs: list = field(default_factory=list)
    seconds: float = 0.0
    error: str | None = None


@dataclass
class GalleryResult:
    index: Path
    examples: list
    failed: dict


def default_source():
    """The gallery/ folder next to the floatcol package (a checkout or editable install)."""
    return Path(__file__).resolve().parent.parent / "gallery"


def find_examples(source=None, only=None):
    src = Path(source) if source is not None else default_source()
    if not src.is_dir():
        raise ValueError(f"no gallery scripts at {src}: pass --source DIR (the gallery/ "
                         "folder of a floatcol checkout)")
    scripts = sorted(p for p in src.glob("*.py") if not p.name.startswith("_"))
    if only:
        wanted = {Path(n).stem for n in only}
        missing = sorted(wanted - {p.stem for p in scripts})
        if missing:
            raise ValueError(f"no gallery example named {', '.join(missing)}; there are "
                             f"{', '.join(p.stem for p in scripts)}")
        scripts = [p for p in scripts if p.stem in wanted]
    if not scripts:
        raise ValueError(f"no gallery scripts (*.py) in {src}")
    out = []
    for p in scripts:
        doc = ast.get_docstring(ast.parse(p.read_text(encoding="utf-8"))) or p.stem
        title, _, rest = doc.partition("\n")
        out.append(Example(p.stem, title.strip(), " ".join(rest.split()), p))
    return out


def run_example(ex, out):
    """Run one script in a fresh folder; move its pictures to out/img."""
    import runpy

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    work = Path(tempfile.mkdtemp(prefix=f".run-{ex.name}-", dir=out))
    cwd = os.getcwd()
    start = time.perf_counter()
    try:
        os.chdir(work)
        runpy.run_path(str(ex.source), run_name="__main__")
    except BaseException as exc:  # a failing example is reported, the others still run
        if isinstance(exc, KeyboardInterrupt):
            raise
        tb = traceback.extract_tb(exc.__traceback__)
        where = next((f"line {f.lineno}" for f in reversed(tb) if f.filename == str(ex.source)), "")
        ex.error = f"{type(exc).__name__}: {exc}" + (f" ({where})" if where else "")
    finally:
        os.chdir(cwd)
        plt.close("all")
        ex.seconds = time.perf_counter() - start
    made = sorted(p for p in work.iterdir() if p.suffix.lower() in PICTURES)
    if not made and ex.error is None:
        ex.error = "the script wrote no picture"
    for p in made:
        name = f"{ex.name}{p.suffix.lower()}" if len(made) == 1 else f"{ex.name}-{p.stem}{p.suffix.lower()}"
        dest = out / "img" / name
        shutil.move(str(p), dest)
        ex.images.append(f"img/{name}")
        ex.thumbs.append(_thumbnail(dest, out / "thumbs"))
    shutil.rmtree(work, ignore_errors=True)
    shutil.copy2(ex.source, out / "src" / ex.source.name)


def _thumbnail(path, folder):
    from PIL import Image
    with Image.open(path) as im:
        im.seek(0)
        im = im.convert("RGBA")
        h = max(1, round(im.height * THUMB_WIDTH / im.width))
        im = im.resize((THUMB_WIDTH, h), Image.Resampling.LANCZOS) if im.width > THUMB_WIDTH else im
        name = path.stem + ".png"
        im.save(folder / name)
    return f"thumbs/{name}"


def build(out, source=None, only=None, progress=True) -> GalleryResult:
    """Run the examples and write ``out/index.html``; returns what was built."""
    from tqdm.auto import tqdm

    examples = find_examples(source, only)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    for sub in ("img", "thumbs", "src"):
        (out / sub).mkdir(exist_ok=True)
    for ex in tqdm(examples, desc="floatcol gallery", unit="example", delay=1.0,
                   disable=not progress, leave=False):
        run_example(ex, out)
    index = out / "index.html"
    tmp = out / ".index.html.tmp"
    tmp.write_text(_page(examples), encoding="utf-8")
    os.replace(tmp, index)
    return GalleryResult(index, examples, {e.name: e.error for e in examples if e.error})


def _page(examples):
    from . import __version__
    cards = []
    for ex in examples:
        pics = "".join(
            f'<a class="pic" href="{html.escape(img)}"><img src="{html.escape(th)}" '
            f'alt="{html.escape(ex.title)}" loading="lazy"></a>'
            for img, th in zip(ex.images, ex.thumbs))
        err = f'<p class="err">failed: {html.escape(ex.error)}</p>' if ex.error else ""
        cards.append(
            f'<section class="card" id="{html.escape(ex.name)}">{pics}'
            f'<h2>{html.escape(ex.title)}</h2><p>{html.escape(ex.description)}</p>{err}'
            f'<p class="meta"><a href="src/{html.escape(ex.source.name)}">{html.escape(ex.source.name)}</a>'
            f' &middot; {ex.seconds:.2f} s</p></section>')
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>floatcol gallery</title>
<style>
body {{ font-family: system-ui, sans-serif; margin: 2rem; background: #fafafa; color: #222; }}
main {{ display: grid; grid-template-columns: repeat(auto-fill, minmax(380px, 1fr)); gap: 1.2rem; }}
.card {{ background: white; border: 1px solid #ddd; border-radius: 6px; padding: 0.8rem; }}
.card img {{ max-width: 100%; display: block; margin-bottom: 0.4rem; }}
.card h2 {{ font-size: 1.05rem; margin: 0.4rem 0; }}
.card p {{ font-size: 0.9rem; margin: 0.3rem 0; }}
.meta {{ color: #666; }} .err {{ color: #b00; }}
</style></head>
<body><h1>floatcol gallery</h1>
<p>Made by <code>floatcol gallery build</code> with floatcol {html.escape(__version__)}.
Each picture links to its full size; each title to the script that drew it.</p>
<main>
{chr(10).join(cards)}
</main></body></html>
"""

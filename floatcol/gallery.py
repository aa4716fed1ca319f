"""Build the example gallery: run each script, collect its pictures, write index.html.

``floatcol gallery build -o DIR`` runs every ``*.py`` in the gallery folder (the
checkout's ``gallery/`` unless ``source=`` says otherwise) in a fresh working folder
(on the workers of a dask.distributed client with ``client=``, ``--scheduler``),
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
    pictures, ex.seconds, ex.error = run_script(ex.name, ex.source.read_bytes())
    _keep(ex, pictures, out)


def run_script(name, text):
    """Run a gallery script (its text, bytes) as ``__main__`` in a fresh temporary
    folder of this machine, with matplotlib's Agg backend. Returns (the pictures it
    wrote: [(file name, bytes)], seconds, error or None). The task a client's worker
    runs for ``build(..., client=)``: the script travels as text and the pictures
    come back as bytes, so the workers need no folder in common with the caller."""
    import runpy

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    work = Path(tempfile.mkdtemp(prefix=f"floatcol-gallery-{name}-"))
    script = work / f"{name}.py"
    script.write_bytes(text)
    cwd = os.getcwd()
    start = time.perf_counter()
    error = None
    try:
        os.chdir(work)
        runpy.run_path(str(script), run_name="__main__")
    except BaseException as exc:  # a failing example is reported, the others still run
        if isinstance(exc, KeyboardInterrupt):
            raise
        tb = traceback.extract_tb(exc.__traceback__)
        where = next((f"line {f.lineno}" for f in reversed(tb) if f.filename == str(script)), "")
        error = f"{type(exc).__name__}: {exc}" + (f" ({where})" if where else "")
    finally:
        os.chdir(cwd)
        plt.close("all")
        seconds = time.perf_counter() - start
    made = sorted(p for p in work.iterdir() if p.suffix.lower() in PICTURES)
    if not made and error is None:
        error = "the script wrote no picture"
    pictures = [(p.name, p.read_bytes()) for p in made]
    shutil.rmtree(work, ignore_errors=True)
    return pictures, seconds, error


def _keep(ex, pictures, out):
    """An example's pictures (run_script's) written to out/img, with thumbnails and its
    source."""
    for fname, data in pictures:
        p = Path(fname)
        name = f"{ex.name}{p.suffix.lower()}" if len(pictures) == 1 else \
            f"{ex.name}-{p.stem}{p.suffix.lower()}"
        dest = out / "img" / name
        dest.write_bytes(data)
        ex.images.append(f"img/{name}")
        ex.thumbs.append(_thumbnail(dest, out / "thumbs"))
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


def build(out, source=None, only=None, progress=True, client=None) -> GalleryResult:
    """Run the examples and write ``out/index.html``; returns what was built. With
    ``client`` (a dask.distributed Client) every example is a task on its workers
    (run_script), its pictures written here as they come back."""
    from tqdm.auto import tqdm

    from .cluster import _check_client
    client = _check_client(client)
    examples = find_examples(source, only)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    for sub in ("img", "thumbs", "src"):
        (out / sub).mkdir(exist_ok=True)
    bar = tqdm(total=len(examples), desc="floatcol gallery", unit="example", delay=1.0,
               disable=not progress, leave=False)
    if client is None:
        for ex in examples:
            run_example(ex, out)
            bar.update()
    else:
        futures = [client.submit(run_script, ex.name, ex.source.read_bytes(), pure=False)
                   for ex in examples]
        for ex, fut in zip(examples, futures):
            pictures, ex.seconds, ex.error = fut.result()
            _keep(ex, pictures, out)
            bar.update()
    bar.close()
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

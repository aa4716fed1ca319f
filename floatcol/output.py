"""Writing pictures: atomic (a temporary file renamed at the end), by file extension."""
from __future__ import annotations

import contextlib
import os
import tempfile

import numpy as np

#: extension -> how it is written
IMAGE_FORMATS = {".png": "PNG", ".jpg": "JPEG", ".jpeg": "JPEG", ".tif": "TIFF",
                 ".tiff": "TIFF", ".webp": "WEBP", ".pdf": "pdf", ".svg": "svg", ".eps": "eps",
                 ".ps": "ps"}
#: written by Pillow (the others through matplotlib's savefig)
PIL_FORMATS = ("PNG", "JPEG", "TIFF", "WEBP")


def check_output(path, formats=IMAGE_FORMATS):
    """Validate an output path before any work: known extension, existing writable
    folder. Returns (path, extension). ValueError names what to fix."""
    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in formats:
        raise ValueError(f"cannot write {path!r}: the name must end in "
                         f"{', '.join(sorted(formats))}")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise ValueError(f"cannot write {path}: folder {folder} does not exist")
    if not os.access(folder, os.W_OK):
        raise ValueError(f"cannot write {path}: folder {folder} is not writable")
    if os.path.isdir(path):
        raise ValueError(f"cannot write {path}: it is a folder")
    return path, ext


@contextlib.contextmanager
def atomic_file(path):
    """Yield a temporary file name beside ``path``; rename it to ``path`` when the
    block succeeds, delete it when it fails. The result gets the umask's permissions."""
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    suffix = os.path.splitext(path)[1]
    try:
        fd, tmp = tempfile.mkstemp(prefix=".floatcol-", suffix=suffix, dir=folder)
    except OSError as exc:             # the user's path in the message, not a temporary's
        raise OSError(exc.errno, exc.strerror, path) from None
    os.close(fd)
    try:
        yield tmp
        umask = os.umask(0)            # mkstemp makes 0600; give the usual permissions
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError) and exc.filename in (tmp, None):
            raise OSError(exc.errno, exc.strerror, path) from None
        raise


def save_image(rgba, path, dpi=100):
    """Write an (H, W, 4) uint8 picture: PNG, JPEG, TIFF or WebP with Pillow, PDF, SVG,
    EPS or PS through matplotlib (the picture at ``dpi``, so it keeps its pixel size in
    inches)."""
    path, ext = check_output(path)
    rgba = np.ascontiguousarray(rgba)
    fmt = IMAGE_FORMATS[ext]
    with atomic_file(path) as tmp:
        if fmt in PIL_FORMATS:
            from PIL import Image
            img = Image.fromarray(rgba, "RGBA")
            if fmt == "JPEG":
                img = _flatten(img)
                img.save(tmp, format="JPEG", quality=95)
            elif fmt == "WEBP":
                img.save(tmp, format="WEBP", lossless=True)
            else:
                img.save(tmp, format=fmt)
        else:
            from matplotlib.figure import Figure
            h, w = rgba.shape[:2]
            fig = Figure(figsize=(w / dpi, h / dpi), dpi=dpi)
            fig.figimage(rgba, resize=False)
            fig.savefig(tmp, format=fmt, dpi=dpi)
    return path


def _flatten(img):
    from PIL import Image
    white = Image.new("RGBA", img.size, (255, 255, 255, 255))
    return Image.alpha_composite(white, img).convert("RGB")


def png_bytes(rgba):
    import io
    from PIL import Image
    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(rgba), "RGBA").save(buf, format="PNG")
    return buf.getvalue()

"""Numba kernels: one pixel column at a time, front to back.

Nothing here imports sympy or matplotlib; the kernels see a surface only as three
compiled function values (f, f_u, f_v) or a height grid, and a view only as a flat
float64 parameter vector (see ``layout.py``).
"""
import hashlib as _hashlib
import os as _os
from pathlib import Path as _Path


#: kernel files whose functions Numba does not cache on disk (cuda.py launches the GPU
#: kernel, compiled per surface and process): a change there keeps the cache
_NOT_CACHED = ("cuda.py",)


def _drop_stale_cache(here=None):
    """Numba's disk cache checks only the file of the cached function itself, so a
    kernel would keep a stale copy of a helper inlined from another file (sample.py
    into column.py) after that file changes, e.g. after a ``git pull`` of an editable
    install. Key the whole cache on a hash of every kernel source instead: when the
    hash changes, drop the cached kernels (they recompile once)."""
    here = _Path(__file__).resolve().parent if here is None else _Path(here)
    digest = _hashlib.sha256()
    for p in sorted(here.glob("*.py")):
        if p.name in _NOT_CACHED:
            continue
        digest.update(p.name.encode())
        digest.update(p.read_bytes())
    stamp_text = digest.hexdigest()
    stems = {q.stem for q in here.glob("*.py")}
    # Numba's folder for this directory's functions under NUMBA_CACHE_DIR:
    # <dir name>_<sha1 of its path> (numba.core.caching's get_suitable_cache_subpath)
    ours = {f"{here.name}_{_hashlib.sha1(str(p).encode()).hexdigest()}"
            for p in {here, _Path(_os.path.abspath(here))}}
    pycache = here / "__pycache__"
    folders = [(pycache, "floatcol-kernels.stamp", [pycache])]
    if _os.environ.get("NUMBA_CACHE_DIR"):
        # one stamp per kernels folder there, and only that folder's kernels dropped:
        # two installs that share it (two versions, two checkouts) keep each other's
        # kernels (and their stamps taking turns no longer dropped their own at every
        # import)
        shared = _Path(_os.environ["NUMBA_CACHE_DIR"])
        folders.append((shared, f"floatcol-kernels-{min(ours)}.stamp",
                        [shared / name for name in ours]))
    for folder, stamp_name, kernel_folders in folders:
        stamp = folder / stamp_name
        try:
            if stamp.is_file() and stamp.read_text() == stamp_text:
                continue
            for kf in kernel_folders:
                if kf.is_dir():
                    for f in kf.iterdir():
                        if f.suffix in (".nbi", ".nbc") and f.name.split(".")[0] in stems:
                            f.unlink()
            folder.mkdir(parents=True, exist_ok=True)
            stamp.write_text(stamp_text)
        except OSError:          # a read-only install: numba caches elsewhere
            pass


_drop_stale_cache()

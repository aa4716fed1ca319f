"""Kernel caches are dropped when any kernel source changes (Numba alone would keep a
kernel compiled against an old copy of a helper from another file)."""
import hashlib

from floatcol.kernels import _drop_stale_cache


def test_cache_follows_every_kernel_source(tmp_path):
    here = tmp_path / "floatcol" / "kernels"
    cache = here / "__pycache__"
    cache.mkdir(parents=True)
    (here / "column.py").write_text("x = 1\n")
    (here / "sample.py").write_text("y = 2\n")
    entry = cache / "column.render-10.py311.nbi"
    other = cache / "unrelated.txt"
    other.write_text("keep")

    entry.write_text("old")
    _drop_stale_cache(here)                       # no stamp yet: start clean
    assert not entry.exists() and other.exists()

    entry.write_text("fresh")
    _drop_stale_cache(here)                       # nothing changed: keep
    assert entry.read_text() == "fresh"

    (here / "sample.py").write_text("y = 3\n")   # a helper's file changed
    _drop_stale_cache(here)
    assert not entry.exists() and other.exists()


def test_numba_cache_dir_is_followed_too(tmp_path, monkeypatch):
    """Under NUMBA_CACHE_DIR Numba keeps a folder's kernels in <dir name>_<sha1 of its
    path>, whose path need not say floatcol: those go too, another folder's stay."""
    here = tmp_path / "pkg" / "kernels"
    here.mkdir(parents=True)
    (here / "column.py").write_text("x = 1\n")
    cache_dir = tmp_path / "numba-cache"
    ours = cache_dir / f"kernels_{hashlib.sha1(str(here).encode()).hexdigest()}"
    theirs = cache_dir / "kernels_0123456789abcdef"
    ours.mkdir(parents=True)
    theirs.mkdir()
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(cache_dir))
    _drop_stale_cache(here)                       # the stamps
    entry = ours / "column.render_column-1.py311.nbi"
    other = theirs / "column.render_column-1.py311.nbi"
    entry.write_text("old")
    other.write_text("someone else's")
    (here / "column.py").write_text("x = 2\n")  # a kernel source changed
    _drop_stale_cache(here)
    assert not entry.exists() and other.read_text() == "someone else's"

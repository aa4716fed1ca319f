"""Kernel caches are dropped when any kernel source changes (Numba alone would keep a
kernel compiled against an old copy of a helper from another file)."""
import hashlib

from floatcol.kernels import _drop_stale_cache


def test_cache_follows_every_kernel_source(tmp_path, monkeypatch):
    # (the folder's own cache alone, not the suite's NUMBA_CACHE_DIR, conftest.py)
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
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


def test_two_installs_sharing_numba_cache_dir_keep_their_kernels(tmp_path, monkeypatch):
    """Two kernels folders (two versions, two checkouts) under one NUMBA_CACHE_DIR: each
    keeps a stamp of its own there, so neither drops the other's kernels, nor, their
    stamps taking turns, its own at every import. (With one stamp for the folder, the
    suite's test above, run under the suite's NUMBA_CACHE_DIR, had replaced the
    suite's stamp, and the next process to import floatcol dropped every kernel the
    suite had compiled.)"""
    cache_dir = tmp_path / "numba-cache"
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(cache_dir))
    entries = {}
    for name, source in (("a", "x = 1\n"), ("b", "x = 2\n")):
        here = tmp_path / name / "kernels"
        here.mkdir(parents=True)
        (here / "column.py").write_text(source)
        _drop_stale_cache(here)
        ours = cache_dir / f"kernels_{hashlib.sha1(str(here).encode()).hexdigest()}"
        ours.mkdir()
        entries[name] = (here, ours / "column.render_column-1.py311.nbi")
        entries[name][1].write_text(name)
    for _ in range(2):                            # imports of either, in turns
        for here, _entry in entries.values():
            _drop_stale_cache(here)
    assert [entry.read_text() for _, entry in entries.values()] == ["a", "b"]
    (entries["a"][0] / "column.py").write_text("x = 3\n")   # a's source changed
    _drop_stale_cache(entries["a"][0])
    assert not entries["a"][1].exists() and entries["b"][1].read_text() == "b"

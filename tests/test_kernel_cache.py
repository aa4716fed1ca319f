"""Kernel caches are dropped when any kernel source changes (Numba alone would keep a
kernel compiled against an old copy of a helper from another file)."""
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

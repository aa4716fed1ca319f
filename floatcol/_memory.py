"""The machine's memory, which the checks that refuse work too big to hold read: a
picture's buffers (passes/geometry.py), a clip's frames (animate.py), a DEM's heights
(terrain.py)."""
from __future__ import annotations

import os

#: the part of the machine's memory a render may plan to take
SHARE = 0.8


def machine_bytes():
    """The machine's physical memory in bytes, or None where the system does not say
    (then MemoryError decides)."""
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return None


def fits(need):
    """Whether ``need`` bytes fit in SHARE of the machine's memory (True where unknown)."""
    total = machine_bytes()
    return total is None or need <= SHARE * total

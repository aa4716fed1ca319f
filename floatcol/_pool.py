"""Reuse of the large per-render buffers.

A render at 1920x1080 writes about 180 MB of buffers (the G-buffer, the edge buffer
of the antialiasing, the four public arrays). Fresh memory costs the kernels the page
faults and the zeroing of every page: about 12 ms of a 95 ms render on the
development machine. Buffers from 1 MiB on are pooled: glibc's heap reuses smaller
ones without faults, and hands back the picture-sized ones (the four public arrays)
only while nothing else is allocated in between; a Render's intensity and depth,
computed when first read, are (1920x1080: 980 page faults a render, and the two
arrays 7-17 ms instead of 4-5 ms).
Interactive rotation, animations and benchmarks render the same size again and
again, so :func:`empty` hands out a buffer of the same shape that nothing refers to
any more (its reference count says so: a Render that is still held,
or any view of the buffer, keeps it out of reuse). Every buffer handed out is written
in full by the kernels before it is read.

The pool holds at most ``PER_SHAPE`` buffers of a shape and ``MAX_BYTES`` in all
(the least recently used shapes go first); :func:`clear` lets it all go.
"""
from __future__ import annotations

import sys
import threading
from collections import OrderedDict

import numpy as np

#: smaller buffers come back from glibc's heap without page faults
MIN_BYTES = 1 << 20
MAX_BYTES = 512 << 20
PER_SHAPE = 2

_lock = threading.Lock()
_pool: OrderedDict = OrderedDict()     # (shape, dtype) -> [arrays]


def _refs(arrays, i):
    return sys.getrefcount(arrays[i])


def _unreferenced_count():
    # the count of a buffer that only the pool's list refers to, measured the way
    # empty() measures (the interpreter may or may not count the call's own reference)
    probe = [np.empty(1)]
    return _refs(probe, 0)


_FREE = _unreferenced_count()


def empty(shape, dtype):
    """np.empty(shape, dtype), or a pooled buffer of that shape nobody refers to."""
    dtype = np.dtype(dtype)
    shape = tuple(int(n) for n in shape)
    nbytes = int(np.prod(shape, dtype=np.int64)) * dtype.itemsize
    if nbytes < MIN_BYTES or nbytes > MAX_BYTES // PER_SHAPE:
        return np.empty(shape, dtype)
    key = (shape, dtype.str)
    with _lock:
        arrays = _pool.get(key)
        if arrays is not None:
            _pool.move_to_end(key)
            for i in range(len(arrays)):
                if _refs(arrays, i) <= _FREE:
                    return arrays[i]
        a = np.empty(shape, dtype)
        if arrays is None:
            arrays = _pool[key] = []
        if len(arrays) < PER_SHAPE:
            arrays.append(a)
            _trim(key)
        return a


def _trim(keep):
    total = sum(a.nbytes for arrays in _pool.values() for a in arrays)
    for key in list(_pool):
        if total <= MAX_BYTES:
            break
        if key != keep:
            total -= sum(a.nbytes for a in _pool.pop(key))


def clear():
    """Let go of every pooled buffer (those still in use stay with their users)."""
    with _lock:
        _pool.clear()


def pooled_bytes():
    with _lock:
        return sum(a.nbytes for arrays in _pool.values() for a in arrays)

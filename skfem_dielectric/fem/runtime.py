"""Where the assembly runs: its worker threads, the BLAS threads, the heap and the set-up
shared by the models of one process.

* :func:`assembly_threads` -- the worker threads of a batched assembly;
* :func:`blas_threads`, :func:`blas_thread_limit`, :func:`single_threaded_blas` -- the
  threads of the OpenBLAS bundled with numpy and scipy;
* :func:`trim_heap` -- the freed heap handed back to the system after large steps;
* :class:`SetupCache` -- set-up kept by key (operators that depend on the mesh only).

No finite elements: the dof machinery is :mod:`~skfem_dielectric.fem.assembly`.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import glob
import os
import threading
from contextlib import contextmanager

import numpy as np
import scipy

__all__ = ["SetupCache", "TRIM_MIN_UNKNOWNS", "assembly_threads", "blas_threads",
           "blas_thread_limit", "single_threaded_blas", "trim_heap"]

_OPENBLAS: list = []      # [(get_num_threads, set_num_threads) or None], found on first use
_MALLOC_TRIM: list = []   # [malloc_trim or None], found on first use


def assembly_threads() -> int:
    """Default worker threads of a batched assembly: ``min(2, cores this process may
    run on)`` (``os.sched_getaffinity``, else ``os.cpu_count``).

    On one core a pool only hands the chunks from the calling thread to a worker and
    waits for it, so the assembly then runs in the calling thread; beyond two threads the
    batched products gain nothing (docs/performance.md).
    """
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):      # not Linux
        cores = os.cpu_count() or 1
    return max(1, min(2, cores))


class SetupCache:
    """Set-up shared by the models of one process, by key: at most ``size`` entries, the
    oldest dropped first, safe to share between threads (a sweep builds many plates of
    one mesh, whose operators depend on the mesh only).

    Parameters
    ----------
    size
        Entries kept, ``>= 1``.
    """

    def __init__(self, size: int):
        self.size = int(size)
        self._entries: dict = {}
        self._lock = threading.Lock()

    def get(self, key):
        """The entry under ``key``, or ``None``."""
        return self._entries.get(key)

    def put(self, key, value):
        """Keep ``value`` under ``key`` (dropping the oldest entries beyond ``size``);
        returns ``value``."""
        with self._lock:
            while len(self._entries) >= self.size:
                self._entries.pop(next(iter(self._entries)))
            self._entries[key] = value
        return value


#: Systems smaller than this are not worth a :func:`trim_heap`, nor freeing the old
#: factors before the next tangent of a Newton solve is assembled: their temporaries and
#: factors are small beside the process, and handing the memory back only makes the next
#: allocations fault it in again (docs/performance.md).
TRIM_MIN_UNKNOWNS = 100_000


def trim_heap(unknowns: int | None = None) -> bool:
    """Give the free memory of glibc's heaps back to the system (``malloc_trim(0)``).

    glibc serves allocations above ``M_MMAP_THRESHOLD`` by ``mmap`` and unmaps them when
    they are freed, but raises the threshold to the size of each such block freed (up to
    32 MiB): afterwards the assembly's large temporaries (a chunk's material tangent,
    the sub-batch products) and PARDISO's work arrays come from the heaps, whose freed
    space stays resident and is not reused by the larger arrays that follow.  Called
    after each assembly and each factorisation (cheap beside either); fixing the
    threshold instead (``mallopt``) made every large temporary a fresh ``mmap`` and the
    assembly slower.  A no-op where the C library is not glibc, and for a system of fewer
    than :data:`TRIM_MIN_UNKNOWNS` unknowns.  Sizes and costs: docs/performance.md,
    "Measurements behind the code".

    Parameters
    ----------
    unknowns
        Unknowns of the system whose temporaries were just freed (``None``: trim
        whatever the size).

    Returns
    -------
    bool
        Whether memory was returned.
    """
    if unknowns is not None and unknowns < TRIM_MIN_UNKNOWNS:
        return False
    f = _malloc_trim()
    return bool(f is not None and f(0))


def _malloc_trim():
    """glibc's ``malloc_trim`` (``None`` for another C library), found on first use."""
    if not _MALLOC_TRIM:
        found = None
        try:
            libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
            if hasattr(libc, "gnu_get_libc_version") and hasattr(libc, "malloc_trim"):
                found = libc.malloc_trim
                found.argtypes = [ctypes.c_size_t]
                found.restype = ctypes.c_int
        except OSError:
            found = None
        _MALLOC_TRIM.append(found)
    return _MALLOC_TRIM[0]


def _openblas_of(pkg) -> list:
    """The ``(get_num_threads, set_num_threads)`` functions of each OpenBLAS bundled with
    the package ``pkg`` (numpy or scipy: ``<pkg>.libs`` on Linux, ``.dylibs`` on macOS)."""
    here = os.path.dirname(pkg.__file__)
    libs = os.path.join(os.path.dirname(here), f"{pkg.__name__}.libs")
    paths = sorted(glob.glob(os.path.join(libs, "*openblas*"))
                   + glob.glob(os.path.join(here, ".dylibs", "*openblas*")))
    names = [(f"{p}_get_num_threads{s}", f"{p}_set_num_threads{s}")
             for p in ("scipy_openblas", "openblas") for s in ("64_", "")]
    found = []
    for path in paths:
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        pair = next(((getattr(lib, get), getattr(lib, put)) for get, put in names
                     if hasattr(lib, get) and hasattr(lib, put)), None)
        if pair is not None:
            found.append(pair)
    return found


def _openblas_threads():
    """The thread-count functions of numpy's bundled OpenBLAS, or ``None`` (another BLAS,
    or a layout this does not know)."""
    if not _OPENBLAS:
        _OPENBLAS.append(next(iter(_openblas_of(np)), None))
    return _OPENBLAS[0]


_ALL_OPENBLAS: list = []  # [[(get, set), ...]] of numpy's and scipy's bundled OpenBLAS


def _every_openblas() -> list:
    """The thread-count functions of every OpenBLAS bundled with numpy and scipy (scipy's
    serves SuperLU and ARPACK)."""
    if not _ALL_OPENBLAS:
        _ALL_OPENBLAS.append(_openblas_of(np) + _openblas_of(scipy))
    return _ALL_OPENBLAS[0]


@contextmanager
def blas_thread_limit(n: int = 1):
    """Run the block with at most ``n`` threads in every OpenBLAS bundled with numpy and
    scipy (restored afterwards; a no-op for other BLAS libraries).

    SuperLU's supernodes and ARPACK's vectors on the plates of this package are small:
    OpenBLAS threads on them spin more than they compute (docs/performance.md, "BLAS
    threads").  The command line runs its commands inside ``blas_thread_limit(1)``.

    Parameters
    ----------
    n
        Largest thread count, ``>= 1``.
    """
    if int(n) != n or n < 1:
        raise ValueError(f"n must be an integer >= 1, got {n!r}")
    libs = _every_openblas()
    before = [int(get()) for get, _ in libs]
    for (_, put), m in zip(libs, before):
        if m > n:
            put(int(n))
    try:
        yield
    finally:
        for (_, put), m in zip(libs, before):
            put(m)


def blas_threads() -> int | None:
    """Threads of numpy's bundled OpenBLAS (``None`` where numpy uses another BLAS)."""
    f = _openblas_threads()
    return None if f is None else int(f[0]())


@contextmanager
def single_threaded_blas():
    """Run the block in one OpenBLAS thread (restored afterwards).

    The batched assembly does many small matrix products (27 x 81 by 81 x 243 per
    element), in worker threads; OpenBLAS's own threads on top of them cost more than
    they gain, the more so on a machine whose cores are busy (docs/performance.md,
    "Measurements behind the code").  A no-op where numpy uses another BLAS.
    """
    f = _openblas_threads()
    n = blas_threads() or 1
    if n <= 1:
        yield
        return
    f[1](1)
    try:
        yield
    finally:
        f[1](n)

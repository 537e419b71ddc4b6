"""What a unit of the clamp-zone study costs, as its rows record it (:class:`Meter`)."""

from __future__ import annotations

import datetime
import math
import os
import sys
import time

from skfem_dielectric.linalg.solver_base import factorisation_count

try:                                  # POSIX only
    import resource
except ImportError:                   # Windows
    resource = None
if sys.platform == "win32":
    import ctypes
    from ctypes import wintypes

__all__ = ["Meter", "peak_GB", "peak_bytes", "estimated_GB", "physical_GB",
           "GB_PER_1000_ELEMENTS"]

#: peak memory of a clamp-zone unit or count per 1000 eighth-model elements, GB: the
#: largest of the counts table's rows (1.69 on 50x2x36, 1.41-1.56 on n2 = 1), rounded up
GB_PER_1000_ELEMENTS = 1.8


def _rusage_peak() -> int | None:
    """``ru_maxrss`` in bytes where :mod:`resource` exists (kilobytes on Linux and the
    BSDs, bytes on macOS), else ``None``."""
    if resource is None:
        return None
    maxrss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return int(maxrss) if sys.platform == "darwin" else int(maxrss) * 1024


def _proc_peak() -> int | None:
    """``VmHWM`` of ``/proc/self/status`` in bytes (Linux), else ``None``."""
    try:
        with open("/proc/self/status", encoding="ascii", errors="replace") as fh:
            for line in fh:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        return None
    return None


def _windows_peak() -> int | None:
    """The peak working set in bytes (Windows' ``GetProcessMemoryInfo``), else ``None``."""
    if sys.platform != "win32":
        return None

    class _Counters(ctypes.Structure):
        _fields_ = [("cb", wintypes.DWORD), ("PageFaultCount", wintypes.DWORD),
                    ("PeakWorkingSetSize", ctypes.c_size_t),
                    ("WorkingSetSize", ctypes.c_size_t),
                    ("QuotaPeakPagedPoolUsage", ctypes.c_size_t),
                    ("QuotaPagedPoolUsage", ctypes.c_size_t),
                    ("QuotaPeakNonPagedPoolUsage", ctypes.c_size_t),
                    ("QuotaNonPagedPoolUsage", ctypes.c_size_t),
                    ("PagefileUsage", ctypes.c_size_t),
                    ("PeakPagefileUsage", ctypes.c_size_t)]

    counters = _Counters()
    counters.cb = ctypes.sizeof(counters)
    try:
        psapi = ctypes.WinDLL("psapi")
        kernel32 = ctypes.WinDLL("kernel32")
        kernel32.GetCurrentProcess.restype = wintypes.HANDLE
        ok = psapi.GetProcessMemoryInfo(kernel32.GetCurrentProcess(),
                                        ctypes.byref(counters), counters.cb)
    except (OSError, AttributeError):
        return None
    return int(counters.PeakWorkingSetSize) if ok else None


def peak_bytes() -> float:
    """The process's peak resident memory so far, in bytes; ``nan`` where the system
    does not tell.

    Read from ``VmHWM`` of ``/proc/self/status`` on Linux (the peak of this process's
    own image: ``ru_maxrss`` there keeps the peak of the parent it was forked from, so a
    unit started by a large process would report that process's), else from
    ``getrusage`` where :mod:`resource` exists (``ru_maxrss`` in bytes on macOS, in
    kilobytes on the BSDs), else from the peak working set (Windows).
    """
    for read in (_proc_peak, _rusage_peak, _windows_peak):
        value = read()
        if value is not None:
            return float(value)
    return math.nan


def peak_GB() -> float:
    """The process's peak resident memory so far, GB (``1024**3`` bytes, 3 decimals);
    ``nan`` where the system does not tell (:func:`peak_bytes`)."""
    return round(peak_bytes() / 1024**3, 3)


def estimated_GB(elements: int) -> float:
    """The estimated peak memory (GB) of a clamp-zone run on a mesh of ``elements``
    eighth-model elements: :data:`GB_PER_1000_ELEMENTS` per 1000 and 0.3 GB of imports."""
    return 0.3 + GB_PER_1000_ELEMENTS * elements / 1000


def physical_GB() -> float:
    """This machine's physical memory, GB; ``nan`` where the system does not tell."""
    try:
        return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE") / 1024**3
    except (AttributeError, ValueError, OSError):
        pass
    if sys.platform == "win32":
        class _Status(ctypes.Structure):
            _fields_ = [("dwLength", wintypes.DWORD), ("dwMemoryLoad", wintypes.DWORD),
                        ("ullTotalPhys", ctypes.c_ulonglong),
                        ("ullAvailPhys", ctypes.c_ulonglong),
                        ("ullTotalPageFile", ctypes.c_ulonglong),
                        ("ullAvailPageFile", ctypes.c_ulonglong),
                        ("ullTotalVirtual", ctypes.c_ulonglong),
                        ("ullAvailVirtual", ctypes.c_ulonglong),
                        ("ullAvailExtendedVirtual", ctypes.c_ulonglong)]

        status = _Status()
        status.dwLength = ctypes.sizeof(status)
        try:
            if ctypes.WinDLL("kernel32").GlobalMemoryStatusEx(ctypes.byref(status)):
                return status.ullTotalPhys / 1024**3
        except (OSError, AttributeError):
            pass
    return math.nan


class Meter:
    """The costs of a unit of work from the moment it is made: CPU seconds of this process,
    sparse factorisations, peak memory, the solver and the date.

    Examples
    --------
    >>> m = Meter()
    >>> sorted(m.columns("superlu"))
    ['cpu_s', 'date', 'factorisations', 'peak_GB', 'solver']
    """

    def __init__(self):
        self.t0, self.f0 = time.process_time(), factorisation_count()

    def cpu_s(self) -> float:
        """CPU seconds since the meter was made (1 decimal)."""
        return round(time.process_time() - self.t0, 1)

    def columns(self, solver: str) -> dict:
        """``factorisations``, ``cpu_s``, ``peak_GB``, ``solver`` and ``date`` of a row."""
        return {"factorisations": factorisation_count() - self.f0, "cpu_s": self.cpu_s(),
                "peak_GB": peak_GB(), "solver": solver,
                "date": datetime.date.today().isoformat()}

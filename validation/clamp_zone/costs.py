"""What a unit of the clamp-zone study costs, as its rows record it (:class:`Meter`)."""

from __future__ import annotations

import datetime
import resource
import time

from skfem_dielectric.linalg.solver_base import factorisation_count

__all__ = ["Meter", "peak_GB"]


def peak_GB() -> float:
    """The process's peak resident memory so far, GB (3 decimals)."""
    return round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2, 3)


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

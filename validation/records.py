"""What an FE runner reports: one :class:`StepRecord` per converged target, a :class:`RunOutcome`.

These two records are the whole interface between the harness (:mod:`validation.sweep`)
and a runner (:func:`validation.fe.run_fe`, or a stand-in in the tests), so they live
apart from both.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["StepRecord", "RunOutcome", "buckling_crossing"]


@dataclass
class StepRecord:
    """What a runner reports for one converged charge target (dimensionless)."""

    D0: float
    lam1: float
    lam3: float
    min_P33: float
    min_P33_clamp: float = float("nan")
    min_P33_interior: float = float("nan")
    stable: bool | None = None
    iterations: int = 0
    n_negative: int | None = None
    n_unstable: int | None = None
    lowest_eig: float = float("nan")
    fields: dict | None = None
    n_negative_plate: int | None = None
    physical_eig: float = float("nan")
    physical_class: str = ""


@dataclass
class RunOutcome:
    """End of a ramp: ``converged`` is False when a target could not be reached."""

    converged: bool
    reason: str = ""
    failed_D0: float | None = None


def buckling_crossing(D0, physical_eig) -> float | None:
    """The stability-based breakdown of one run: where the whole plate's lowest physical
    eigenvalue crosses zero, linearly interpolated between the last analysed row above
    zero and the first below (the first analysed row's ``D0`` if it is already
    negative); ``None`` if no analysed row is negative."""
    D0 = np.asarray(D0, dtype=float)
    ev = np.asarray(physical_eig, dtype=float)
    rows = np.flatnonzero(np.isfinite(ev))
    neg = rows[ev[rows] < 0]
    if not neg.size:
        return None
    i = int(neg[0])
    before = rows[rows < i]
    if not before.size:
        return float(D0[i])
    j = int(before[-1])
    return float(D0[j] + (D0[i] - D0[j]) * ev[j] / (ev[j] - ev[i]))

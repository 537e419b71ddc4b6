"""What an FE runner reports: one :class:`StepRecord` per converged target, a :class:`RunOutcome`.

These two records are the whole interface between the harness (:mod:`validation.sweep`)
and a runner (:func:`validation.fe.run_fe`, or a stand-in in the tests), so they live
apart from both.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["StepRecord", "RunOutcome"]


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
    #: the located buckling load, on the record of the first state past it (else ``nan``)
    D0_b: float = float("nan")


@dataclass
class RunOutcome:
    """End of a ramp: ``converged`` is False when a target could not be reached."""

    converged: bool
    reason: str = ""
    failed_D0: float | None = None


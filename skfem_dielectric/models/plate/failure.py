"""Why a ramp of the 3D plate stopped: the state where Newton failed, read at its
quadrature points, and how often the ``det F > 0`` guard shortened the Newton steps.

On the clamped plate (loading ``"uniaxial"``, the paper's Sec. 6) the clamp face
``x1 = +-L1/2`` meets the free edge ``x3 = +-L3/2`` at a re-entrant corner of the boundary
conditions, where the stresses of the continuum are singular. A load-controlled Newton
iteration can stall there while the tangent is still positive definite (no stability
signal): the quadrature point next to the corner carries a large compressive ``S33`` and a
``det F`` well below one, and the Newton increments would invert it, so the step limit
(:meth:`~skfem_dielectric.models.plate.problem.PlateProblem.max_step`) cuts them short.
:func:`plate_failure_cause` measures exactly these quantities; :class:`StepLimitCounter`
counts the shortened steps. :func:`~skfem_dielectric.gallery.drivers.run_ramp` uses both to
fill ``RampResult.failure`` and to extend ``RampResult.reason``. The other plates (dead
tractions on their lateral faces) have no clamp and so no such corner: their diagnosis gives
the positions of the extremes only.
"""

from __future__ import annotations

from typing import Any, Callable

import numpy as np

from .problem import PlateProblem

__all__ = ["StepLimitCounter", "plate_failure_cause", "describe_failure"]


class StepLimitCounter:
    """A ``step_limit(x, dx, load)`` that counts how often the wrapped one shortened a step.

    Parameters
    ----------
    step_limit
        The limit to wrap (e.g.
        :meth:`~skfem_dielectric.models.plate.problem.PlateProblem.max_step`).

    Attributes
    ----------
    calls, limited
        Newton steps asked about and those with an admissible fraction below one since the
        last :meth:`reset`.
    smallest
        Smallest admissible fraction returned since the last :meth:`reset` (1.0 if none).
    """

    def __init__(self, step_limit: Callable[[np.ndarray, np.ndarray, Any], float]):
        if not callable(step_limit):
            raise ValueError(f"step_limit must be callable, got {step_limit!r}")
        self.step_limit = step_limit
        self.reset()

    def reset(self) -> None:
        """Start counting afresh (e.g. at every reached target)."""
        self.calls, self.limited, self.smallest = 0, 0, 1.0

    def __call__(self, x: np.ndarray, dx: np.ndarray, load) -> float:
        alpha = float(self.step_limit(x, dx, load))
        self.calls += 1
        if alpha < 1.0:
            self.limited += 1
            self.smallest = min(self.smallest, alpha)
        return alpha


def _corner_distance(problem: PlateProblem, X: np.ndarray) -> float | None:
    """Distance of the reference point ``X`` from the nearest clamp/free-edge corner
    ``(|x1|, |x3|) = (L1/2, L3/2)``, in plate thicknesses; ``None`` for a plate without
    clamps (any loading but ``"uniaxial"``)."""
    if problem.loading != "uniaxial":
        return None
    pm = problem.plate
    return float(np.hypot(abs(X[0]) - pm.L1 / 2, abs(X[2]) - pm.L3 / 2) / pm.H)


def plate_failure_cause(problem: PlateProblem, x: np.ndarray, load) -> dict[str, Any]:
    """Extremes of ``det F`` and of the lateral stress at the quadrature points of a state.

    Parameters
    ----------
    problem
        The plate.
    x, load
        A state, typically the last converged one of a ramp that stopped.

    Returns
    -------
    dict
        ``min_J`` (smallest ``det F``) and ``min_J_at`` (its reference point ``(x1, x2,
        x3)``), ``S33`` (the ``S33/mu`` of largest magnitude, signed; ``S`` the second
        Piola stress, the paper's ``P``) and ``S33_at``, and for both the distance from
        the nearest clamp/free-edge corner in thicknesses, ``min_J_corner_distance`` and
        ``S33_corner_distance`` (``None`` unless the plate is clamped, loading
        ``"uniaxial"``).

    Raises
    ------
    ValueError
        If ``problem`` is not a :class:`~skfem_dielectric.models.plate.problem.PlateProblem`.
    """
    if not isinstance(problem, PlateProblem):
        raise ValueError(f"problem must be a PlateProblem, got {type(problem).__name__}")
    Xq = np.asarray(problem.form.b2.global_coordinates())      # (3, nel, nq)
    mu = problem.material.mu
    min_J, min_J_at, S33, S33_at = np.inf, None, 0.0, None
    for sl, F, G, p in problem.quadrature_fields(x, load):
        st = problem.stresses(F, G, p, load)
        J, S = st["J"], st["S"][2, 2] / mu
        i = np.unravel_index(np.argmin(J), J.shape)
        if J[i] < min_J:
            min_J, min_J_at = float(J[i]), Xq[:, sl][(slice(None),) + i]
        j = np.unravel_index(np.argmax(np.abs(S)), S.shape)
        if S33_at is None or abs(S[j]) > abs(S33):
            S33, S33_at = float(S[j]), Xq[:, sl][(slice(None),) + j]
    return {"min_J": min_J, "min_J_at": tuple(float(v) for v in min_J_at),
            "min_J_corner_distance": _corner_distance(problem, min_J_at),
            "S33": S33, "S33_at": tuple(float(v) for v in S33_at),
            "S33_corner_distance": _corner_distance(problem, S33_at)}


def _point(X) -> str:
    return "(" + ", ".join(f"{v:.3g}" for v in X) + ")"


def describe_failure(cause: dict[str, Any]) -> str:
    """One sentence from :func:`plate_failure_cause` (plus the ``StepLimitCounter`` keys
    ``step_limited``, ``newton_steps``, ``smallest_step_limit`` when present).

    Where the extremes are: their distance from a clamp/free-edge corner on a clamped
    plate, their reference point ``(x1, x2, x3)`` on a plate without clamps."""
    if cause["min_J_corner_distance"] is None:
        text = (f"at the last converged state min det F = {cause['min_J']:.3g} at "
                f"{_point(cause['min_J_at'])} and S33/mu = {cause['S33']:.3g} at "
                f"{_point(cause['S33_at'])}")
    else:
        text = (f"at the last converged state min det F = {cause['min_J']:.3g} "
                f"({cause['min_J_corner_distance']:.2g} thicknesses from a clamp/free-edge "
                f"corner) and S33/mu = {cause['S33']:.3g} "
                f"({cause['S33_corner_distance']:.2g} thicknesses from it)")
    if "step_limited" in cause:
        text += (f"; the det F > 0 step limit shortened {cause['step_limited']} of "
                 f"{cause['newton_steps']} Newton steps towards the failed target "
                 f"(smallest admissible fraction {cause['smallest_step_limit']:.3g})")
    return text

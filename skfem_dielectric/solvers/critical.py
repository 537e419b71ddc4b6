"""Critical load on a load path: where an eigenvalue of the reduced stiffness crosses zero.

Between a stable state ``(x_a, load_a)`` and a load ``load_b`` where the indicator
``eig(x, load)`` (the lowest *physical* eigenvalue, e.g. the ``eigenvalue`` of
:func:`~skfem_dielectric.models.plate.modes.lowest_physical`) is negative, the load is
parametrised as ``load(t) = load_a + t (load_b - load_a)``, ``t in [0, 1]``, and the root of
``t -> eig`` is bracketed by safeguarded secant (Illinois) steps.  Every trial state is
solved by :func:`~skfem_dielectric.solvers.ramp.ramp` from the stable state ``x_a`` (not from the
last trial, which may lie beyond the critical load: a state there can have left the branch).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from ..checks import check_callable, check_positive
from ..problem import Problem
from .ramp import ramp

__all__ = ["CriticalLoad", "critical_load", "illinois"]


def illinois(g: Callable[[float], float], a: float, fa: float, b: float, fb: float, *,
             done: Callable[[float, float, float], bool], maxiter: int,
             safeguard: float = 0.0) -> tuple[float, float, float, float, int]:
    """Illinois (modified regula falsi) iterations for a root of ``g`` between ``a``
    (``g(a) = fa > 0``) and ``b`` (``fb < 0``).

    Each step takes the secant point ``c`` of the bracket (kept at least ``safeguard``
    times the bracket's width from its ends) and halves the retained end's value after two
    steps on the same side.  Stops when ``done(a, b, c)``, at an exact zero or after
    ``maxiter`` steps.

    Returns
    -------
    c, fc : float
        The last trial point and its value.
    a, b : float
        The final bracket (``g > 0`` at ``a``, ``< 0`` at ``b``).
    iterations : int
    """
    side, c, fc, it = 0, b, fb, 0
    for it in range(1, maxiter + 1):
        c = b - fb * (b - a) / (fb - fa)
        if safeguard:
            lo, hi = sorted((a, b))
            c = min(max(c, lo + safeguard * (hi - lo)), hi - safeguard * (hi - lo))
        fc = g(c)
        if fc > 0:
            a, fa = c, fc
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            b, fb = c, fc
            if side == 1:
                fa *= 0.5
            side = 1
        if fc == 0 or done(a, b, c):
            break
    return c, fc, a, b, it


@dataclass
class CriticalLoad:
    """A located critical load.

    Attributes
    ----------
    load
        The critical load (same shape as ``load_a``).
    t
        Its path parameter in ``[0, 1]``.
    eigenvalue
        The indicator at ``load``.
    bracket
        ``(t_lo, t_hi)``: the final bracket (stable, unstable side).
    x
        The state at ``load`` (reduced vector).
    evaluations
        ``(t, eig)`` of every trial, in order.
    """

    load: Any
    t: float
    eigenvalue: float
    bracket: tuple[float, float]
    x: np.ndarray
    evaluations: list[tuple[float, float]] = field(default_factory=list)


def critical_load(problem: Problem, x_a: np.ndarray, load_a: Any, load_b: Any,
                  eig: Callable[[np.ndarray, Any], float], *, tol: float = 1e-4,
                  maxiter: int = 40, **ramp_options) -> CriticalLoad:
    """Locate the load between ``load_a`` and ``load_b`` where ``eig`` vanishes.

    Parameters
    ----------
    problem
        Any :class:`~skfem_dielectric.problem.Problem`.
    x_a, load_a
        A converged state on the stable side (``eig > 0``).
    load_b
        A load on the unstable side (``eig < 0``).
    eig
        ``eig(x, load) -> float``, continuous along the path.
    tol
        Width of the final bracket in the load (largest component, absolute): the
        critical load is located to ``tol``.
    maxiter
        Maximum number of trial states.
    ramp_options
        Passed to :func:`~skfem_dielectric.solvers.ramp.ramp` (``linear_solver``,
        ``settings``, ``step_limit``, ...).

    Returns
    -------
    CriticalLoad

    Raises
    ------
    ValueError
        If ``eig`` does not change sign from ``load_a`` to ``load_b``, if a trial state
        cannot be solved, or on bad arguments.
    """
    if not isinstance(problem, Problem):
        raise ValueError(f"problem must be a skfem_dielectric.Problem, got "
                         f"{type(problem).__name__}")
    check_callable("eig", eig, optional=False)
    tol = check_positive("tol", tol)
    la = np.asarray(load_a, dtype=float)
    lb = np.asarray(load_b, dtype=float)
    if la.shape != lb.shape:
        raise ValueError(f"load_a and load_b must have the same shape, got {la.shape} and "
                         f"{lb.shape}")
    span = float(np.max(np.abs(lb - la)))
    if span == 0.0:
        raise ValueError("load_a and load_b must differ")
    x_a = np.asarray(x_a, dtype=float)
    evals: list[tuple[float, float]] = []

    def at(t):
        return la + t * (lb - la) if la.ndim else float(la + t * (lb - la))

    def g(t):
        res = ramp(problem, [at(t)], x0=x_a, start=at(0.0), **ramp_options)
        if not res.converged:
            raise ValueError(f"no equilibrium at load {at(t)}: {res.reason}")
        v = float(eig(res.x, at(t)))
        evals.append((t, v))
        return v, res.x

    fa = float(eig(x_a, at(0.0)))
    evals.append((0.0, fa))
    fb, xb = g(1.0)
    if not (fa > 0 > fb):
        raise ValueError(f"eig does not change sign from load_a to load_b: {fa:.3e} at "
                         f"{at(0.0)}, {fb:.3e} at {at(1.0)}")
    last = {"x": xb}

    def trial(t):
        v, x = g(t)
        last["x"] = x
        return v

    if span <= tol:
        return CriticalLoad(at(1.0), 1.0, fb, (0.0, 1.0), xb, evals)
    t, v, a, b, _ = illinois(trial, 0.0, fa, 1.0, fb, maxiter=maxiter, safeguard=0.01,
                             done=lambda a, b, c: abs(b - a) * span <= tol)
    x = last["x"]
    return CriticalLoad(at(t), t, v, (a, b), x, evals)

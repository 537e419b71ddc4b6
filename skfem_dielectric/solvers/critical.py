"""Critical load on a load path: where an eigenvalue of the reduced stiffness crosses zero.

Between a stable state ``(x_a, load_a)`` and a load ``load_b`` where the indicator
``eig(x, load)`` (the lowest *physical* eigenvalue, e.g. the ``eigenvalue`` of
:func:`~skfem_dielectric.models.plate.modes.lowest_physical`) is negative, the load is
parametrised as ``load(t) = load_a + t (load_b - load_a)``, ``t in [0, 1]``, and the root of
``t -> eig`` is bracketed by Brent's method (:func:`brent`; :func:`illinois`, safeguarded
regula falsi, is kept for other callers).  Every trial state is
solved by :func:`~skfem_dielectric.solvers.ramp.ramp` from the stable end of the current
bracket (``x_a``, or the last trial found stable, which is nearer): never from a trial on
the unstable side, which may lie beyond the critical load where a state can have left the
branch.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from ..checks import check_callable, check_positive
from ..problem import Problem
from .ramp import ramp

__all__ = ["CriticalLoad", "critical_load", "illinois", "brent"]


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


def brent(g: Callable[[float], float], a: float, fa: float, b: float, fb: float, *,
          xtol: Callable[[float], float] | float, maxiter: int
          ) -> tuple[float, float, float, float, int]:
    """Brent's method (inverse quadratic interpolation, secant and bisection steps) for a
    root of ``g`` between ``a`` (``g(a) = fa > 0``) and ``b`` (``fb < 0``).

    Brent, *Algorithms for Minimization without Derivatives* (1973), ch. 4: each step
    takes the inverse quadratic interpolation through the last three points (the secant
    with two), kept when it stays well inside the bracket and shrinks faster than the
    step before last, else bisects; a step is never shorter than ``xtol / 2``, so that the
    far end of the bracket closes in too.  On a smooth ``g`` it needs fewer evaluations
    than :func:`illinois` for the same final bracket.

    Parameters
    ----------
    g
        The function (one evaluation per step).
    a, fa, b, fb
        The bracket and the values of ``g`` at its ends (``fa > 0 > fb``).
    xtol
        The wanted width of the final bracket, a number or a function of the current
        estimate.
    maxiter
        Maximum number of evaluations.

    Returns
    -------
    c, fc : float
        The last trial point and its value.
    a, b : float
        The final bracket (``g > 0`` at ``a``, ``< 0`` at ``b``).
    iterations : int
    """
    width = xtol if callable(xtol) else (lambda c, w=float(xtol): w)
    xb, gb, xc, gc = b, fb, a, fa           # xb: best estimate, xc: the other end
    xa, ga = xc, gc                         # the previous estimate
    d = e = xb - xc
    c, fc, pos, neg, it = b, fb, a, b, 0
    for it in range(1, maxiter + 1):
        if abs(gc) < abs(gb):
            xa, ga = xb, gb
            xb, gb, xc, gc = xc, gc, xb, gb
        tol1 = 0.5 * width(xb)
        xm = 0.5 * (xc - xb)
        if abs(e) >= tol1 and abs(ga) > abs(gb):
            r1 = gb / ga
            if xa == xc:                    # two points: the secant
                p, q = 2.0 * xm * r1, 1.0 - r1
            else:                           # three: inverse quadratic interpolation
                q0, r2 = ga / gc, gb / gc
                p = r1 * (2.0 * xm * q0 * (q0 - r2) - (xb - xa) * (r2 - 1.0))
                q = (q0 - 1.0) * (r2 - 1.0) * (r1 - 1.0)
            if p > 0:
                q = -q
            p = abs(p)
            if 2.0 * p < min(3.0 * xm * q - abs(tol1 * q), abs(e * q)):
                e, d = d, p / q
            else:
                d = e = xm
        else:
            d = e = xm
        xa, ga = xb, gb
        xb = xb + d if abs(d) > tol1 else xb + math.copysign(tol1, xm)
        gb = float(g(xb))
        c, fc = xb, gb
        if (gb > 0) == (gc > 0):            # the other end is now the previous estimate
            xc, gc = xa, ga
            d = e = xb - xa
        pos, neg = (xb, xc) if gb > 0 else (xc, xb)
        if gb == 0 or abs(pos - neg) <= width(xb):
            break
    return c, fc, pos, neg, it


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

    stable = {"t": 0.0, "x": x_a}     # the stable end of the bracket and its state

    def g(t):
        res = ramp(problem, [at(t)], x0=stable["x"], start=at(stable["t"]), **ramp_options)
        if not res.converged:
            raise ValueError(f"no equilibrium at load {at(t)}: {res.reason}")
        v = float(eig(res.x, at(t)))
        evals.append((t, v))
        if v > 0 and t > stable["t"]:
            stable["t"], stable["x"] = t, res.x
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
    t, v, a, b, _ = brent(trial, 0.0, fa, 1.0, fb, maxiter=maxiter, xtol=tol / span)
    x = last["x"]
    return CriticalLoad(at(t), t, v, (a, b), x, evals)

"""Problem-agnostic Newton solver with a backtracking line search.

:func:`newton` solves ``r(x) = 0`` given ``assemble(x) -> (K, r)`` (sparse tangent and
residual on the *reduced* unknowns, i.e. with Dirichlet conditions and tied dofs already
eliminated).  Full Newton steps are taken when they reduce the residual norm; otherwise a
backtracking line search halves the step (the tangent assembled at the accepted trial point
is reused, so a full step costs one assembly and one solve).  It never raises on
divergence: it returns a :class:`NewtonResult` with ``converged=False`` and a ``reason``.

Convergence: ``||r|| <= atol + rtol * scale`` where ``scale`` is given by the caller
(typically the norm of the external load vector), or the Newton increment is at round-off
level (``||dx|| <= xtol (1 + ||x||)``) while ``||r||`` is below ``1e3 (atol + rtol scale)``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import scipy.sparse as sp

from .linear import LinearSolver, get_linear_solver

__all__ = ["NewtonResult", "newton"]


@dataclass
class NewtonResult:
    """Outcome of one Newton solve.

    Attributes
    ----------
    x
        Last iterate (the solution if ``converged``).
    converged
        Whether the convergence test was met.
    iterations
        Number of Newton iterations (linear solves).
    residual_norms
        ``||r||`` at the initial guess and after every iteration.
    step_norms
        ``||dx||`` of every accepted (possibly damped) increment.
    reason
        Empty if converged, else why it stopped.
    assembly_seconds, solve_seconds
        Wall time per assembly call and per linear solve.
    inertia
        Inertia ``(n_pos, n_neg, n_zero)`` of the last factorised tangent if the linear
        solver reports it (PARDISO), else ``None``.
    """

    x: np.ndarray
    converged: bool
    iterations: int
    residual_norms: list[float]
    step_norms: list[float] = field(default_factory=list)
    reason: str = ""
    assembly_seconds: list[float] = field(default_factory=list)
    solve_seconds: list[float] = field(default_factory=list)
    inertia: tuple[int, int, int] | None = None


def _norm(r: np.ndarray) -> float:
    return float(np.linalg.norm(r))


def newton(assemble: Callable[[np.ndarray], tuple[sp.spmatrix, np.ndarray]],
           x0: np.ndarray, *, residual: Callable[[np.ndarray], np.ndarray] | None = None,
           linear_solver: str | LinearSolver = "superlu", atol: float = 1e-10,
           rtol: float = 1e-10, xtol: float = 1e-13, scale: float | None = None,
           max_iter: int = 25, line_search: bool = True,
           max_backtracks: int = 8) -> NewtonResult:
    """Solve ``r(x) = 0`` by Newton's method with a backtracking line search.

    Parameters
    ----------
    assemble
        ``assemble(x) -> (K, r)``: sparse tangent ``dr/dx`` and residual at ``x``.
    x0
        Initial guess (not modified).
    residual
        Optional ``residual(x) -> r`` used for backtracking trial points; defaults to
        ``assemble(x)[1]``.
    linear_solver
        Name for :func:`get_linear_solver` or a solver instance (reused across calls, which
        lets PARDISO keep its symbolic factorisation).
    atol, rtol, scale
        Converged when ``||r|| <= atol + rtol * scale``; ``scale`` defaults to the initial
        residual norm.
    xtol
        Also converged when ``||dx|| <= xtol (1 + ||x||)`` and
        ``||r|| <= 1e3 (atol + rtol scale)`` (stagnation at round-off).
    max_iter
        Maximum number of Newton iterations.
    line_search
        Backtrack (halve) a step that does not reduce ``||r||``; otherwise take full steps.
    max_backtracks
        Maximum halvings per iteration; if none reduces ``||r||`` the solve fails.

    Returns
    -------
    NewtonResult
        Never raises on divergence, singular tangents or non-finite values: these end the
        iteration with ``converged=False`` and a ``reason``.
    """
    solver = get_linear_solver(linear_solver)
    x = np.array(x0, dtype=float, copy=True)
    res = NewtonResult(x=x, converged=False, iterations=0, residual_norms=[])

    def _assemble(xx):
        t = time.perf_counter()
        try:
            K, r = assemble(xx)
        except (FloatingPointError, ValueError, ZeroDivisionError) as exc:
            res.assembly_seconds.append(time.perf_counter() - t)
            return None, None, f"assembly failed: {exc}"
        res.assembly_seconds.append(time.perf_counter() - t)
        if not np.all(np.isfinite(r)):
            return None, None, "non-finite residual"
        return K, r, ""

    K, r, err = _assemble(x)
    if err:
        res.reason = err
        return res
    rn = _norm(r)
    res.residual_norms.append(rn)
    if scale is None:
        scale = rn
    tol = atol + rtol * scale
    if rn <= tol:
        res.converged = True
        return res
    for it in range(1, max_iter + 1):
        t = time.perf_counter()
        try:
            dx = -solver.solve(K, r)
        except Exception as exc:  # singular matrix, PARDISO error, ...
            res.solve_seconds.append(time.perf_counter() - t)
            res.reason = f"linear solve failed: {exc}"
            return res
        res.solve_seconds.append(time.perf_counter() - t)
        res.inertia = getattr(solver, "inertia", None)
        res.iterations = it
        if not np.all(np.isfinite(dx)):
            res.reason = "non-finite Newton increment (singular tangent?)"
            return res
        alpha = 1.0
        K1, r1, err = _assemble(x + dx)
        rn1 = _norm(r1) if not err else np.inf
        dxn = _norm(dx)

        def acceptable(r_trial, rn_trial, a):
            # residual decrease, or Deuflhard's natural monotonicity test: the simplified
            # Newton correction with the current factorisation shrinks (affine invariant;
            # it accepts the full steps that penalty / saddle-point problems need although
            # their residual norm grows on the first iterations)
            if rn_trial < rn:
                return True
            if not np.isfinite(rn_trial):
                return False
            dxbar = solver.resolve(r_trial)
            return dxbar is not None and _norm(dxbar) <= (1.0 - 0.5 * a) * dxn

        if line_search and not acceptable(r1, rn1, 1.0):
            accepted = False
            for _ in range(max_backtracks):
                alpha *= 0.5
                xt = x + alpha * dx
                if residual is not None:
                    try:
                        rt = residual(xt)
                    except (FloatingPointError, ValueError, ZeroDivisionError):
                        continue
                    rnt = _norm(rt) if np.all(np.isfinite(rt)) else np.inf
                else:
                    _, rt, e2 = _assemble(xt)
                    rnt = _norm(rt) if not e2 else np.inf
                if acceptable(rt, rnt, alpha):
                    accepted = True
                    break
            if not accepted:
                res.reason = (f"line search failed at iteration {it}: no decrease of "
                              f"||r|| = {rn:.3e} after {max_backtracks} halvings")
                return res
            K1, r1, err = _assemble(x + alpha * dx)
            if err:
                res.reason = err
                return res
            rn1 = _norm(r1)
        elif err:
            res.reason = err
            return res
        x = x + alpha * dx
        res.x = x
        K, r, rn = K1, r1, rn1
        res.residual_norms.append(rn)
        dn = alpha * _norm(dx)
        res.step_norms.append(dn)
        if rn <= tol or (dn <= xtol * (1.0 + _norm(x)) and rn <= 1e3 * tol):
            res.converged = True
            return res
    res.reason = f"no convergence in {max_iter} iterations (||r|| = {rn:.3e}, tol {tol:.1e})"
    return res

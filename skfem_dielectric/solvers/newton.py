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

Admissible states: a model whose unknowns must stay in a region (e.g. ``det F > 0``, no
inverted element) passes ``step_limit(x, dx) -> alpha_max``, the largest step fraction
along ``dx`` that stays inside; a step is then started at ``alpha = alpha_max / 2`` when
``alpha_max < 1`` (and backtracked from there), never beyond the boundary.  ``admissible(x)
-> reason`` (empty when admissible) is asked of every converged state: a state it rejects
ends the solve with ``converged=False`` and that reason
(:func:`~skfem_dielectric.kinematics.segment_det_limit` is the ``det F > 0`` step limit
along a segment of deformation gradients).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import scipy.sparse as sp

from ..checks import (check_callable, check_count, check_nonnegative, check_nonnegative_int,
                     check_tolerances)
from ..linalg.linear import get_linear_solver
from ..linalg.solver_base import LinearSolver

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
    factorisations
        Number of tangents factorised (``iterations`` minus the chord steps).
    chord_steps
        Iterations that reused the last factorisation (``chord > 0``).
    residual_seconds, chord_seconds
        Wall time of every residual-only evaluation of a trial point (``chord > 0`` with
        ``residual``) and of every chord back-substitution.
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
    factorisations: int = 0
    chord_steps: int = 0
    residual_seconds: list[float] = field(default_factory=list)
    chord_seconds: list[float] = field(default_factory=list)


def _norm(r: np.ndarray) -> float:
    return float(np.linalg.norm(r))


def newton(assemble: Callable[[np.ndarray], tuple[sp.spmatrix, np.ndarray]],
           x0: np.ndarray, *, residual: Callable[[np.ndarray], np.ndarray] | None = None,
           linear_solver: str | LinearSolver = "superlu", atol: float = 1e-10,
           rtol: float = 1e-10, xtol: float = 1e-13, scale: float | None = None,
           max_iter: int = 25, line_search: bool = True, max_backtracks: int = 8,
           step_limit: Callable[[np.ndarray, np.ndarray], float] | None = None,
           admissible: Callable[[np.ndarray], str] | None = None,
           chord: float = 0.0, reuse_factors: bool = False) -> NewtonResult:
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
        lets PARDISO keep its symbolic factorisation); its ``discard()``, if it has one,
        frees the old factors before a tangent that is factorised next is assembled.
    atol, rtol, scale
        Converged when ``||r|| <= atol + rtol * scale``; ``scale`` defaults to the initial
        residual norm.
    xtol
        Also converged when ``||dx|| <= xtol (1 + ||x||)`` and
        ``||r|| <= 1e3 (atol + rtol scale)`` (stagnation at round-off).
    max_iter
        Maximum number of iterations (Newton and chord steps).
    line_search
        Backtrack (halve) a step that does not reduce ``||r||``; otherwise take full steps.
    max_backtracks
        Maximum halvings per iteration; if none reduces ``||r||`` the solve fails.
    step_limit
        Optional ``step_limit(x, dx) -> alpha_max`` in ``[0, 1]``: the largest admissible
        fraction of the increment ``dx`` (e.g. ``det F > 0`` along the step,
        :meth:`~skfem_dielectric.models.plate.problem.PlateProblem.max_step`).  With ``alpha_max <
        1`` the step starts at ``alpha_max / 2`` (and is backtracked from there); ``alpha_max = 0``
        ends the solve (``converged=False``).
    admissible
        Optional ``admissible(x) -> reason``: empty for an admissible state; a converged
        state it rejects gives ``converged=False`` with ``reason`` (e.g. an inverted
        deformation).
    chord
        Contraction below which the factorisation is reused, in ``[0, 1)``; 0 (default)
        factorises the tangent in every iteration.  After a full step that reduced
        ``||r||`` by at least this factor the next step is a chord step ``dx = -K_old^-1
        r`` with the factors at hand (a back-substitution, no new tangent), and so on while
        each chord step contracts as much; a chord step that contracts less is kept if it
        reduces ``||r||`` (the next step factorises again), else it is discarded.  With
        ``residual`` given, the trial points are then evaluated by ``residual`` and the
        tangent is assembled only where it is factorised.  The converged state satisfies
        the same test, so the solution changes only within the tolerance.
    reuse_factors
        Start with a chord step on the factorisation ``linear_solver`` already holds (e.g.
        the tangent of the converged state before a load step, which a stability analysis
        factorised): a back-substitution instead of the first assembly and factorisation.
        It is kept if it reduces ``||r||`` (and followed by chord steps while they contract
        by ``chord``), else discarded.  Needs a solver instance that supports
        ``resolve``; otherwise the first step factorises as usual.

    Returns
    -------
    NewtonResult
        Never raises on divergence, singular tangents or non-finite values: these end the
        iteration with ``converged=False`` and a ``reason``.

    Raises
    ------
    ValueError
        Invalid arguments, each named: a callable that is not, ``x0`` not a finite 1-D
        vector, negative or non-finite tolerances (or ``atol = rtol = 0``, which can never
        be met), ``max_iter < 1``, ``max_backtracks < 0``, ``chord`` outside ``[0, 1)``.
    """
    check_callable("assemble", assemble, optional=False)
    for name, f in (("residual", residual), ("step_limit", step_limit),
                    ("admissible", admissible)):
        check_callable(name, f)
    atol, rtol = check_tolerances(atol, rtol)
    xtol = check_nonnegative("xtol", xtol)
    scale = None if scale is None else check_nonnegative("scale", scale)
    max_iter = check_count("max_iter", max_iter)
    max_backtracks = check_nonnegative_int("max_backtracks", max_backtracks)
    chord = check_nonnegative("chord", chord)
    if not chord < 1.0:
        raise ValueError(f"chord must be in [0, 1), got {chord!r}")
    solver = get_linear_solver(linear_solver)
    try:
        x = np.array(x0, dtype=float, copy=True)
    except (TypeError, ValueError):
        raise ValueError(f"x0 must be a real vector, got {x0!r}") from None
    if x.ndim != 1 or not np.all(np.isfinite(x)):
        raise ValueError(f"x0 must be a finite 1-D vector, got shape {x.shape}")
    res = NewtonResult(x=x, converged=False, iterations=0, residual_norms=[])
    lazy = chord > 0 and residual is not None   # tangent only where it is factorised

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

    def _trial(xx):
        """``(K or None, r, ||r||, error)`` at a trial point (``||r|| = inf`` on error)."""
        if lazy:
            t = time.perf_counter()
            try:
                rt = residual(xx)
            except (FloatingPointError, ValueError, ZeroDivisionError) as exc:
                return None, None, np.inf, f"residual failed: {exc}"
            finally:
                res.residual_seconds.append(time.perf_counter() - t)
            if not np.all(np.isfinite(rt)):
                return None, None, np.inf, "non-finite residual"
            return None, rt, _norm(rt), ""
        Kt, rt, e = _assemble(xx)
        return Kt, rt, (_norm(rt) if not e else np.inf), e

    discard = getattr(solver, "discard", None)

    def _to_factorise(xx):
        """The tangent at ``xx`` that is factorised next: the old factors (of no more use)
        are freed first, so that they and the new tangent are not held together."""
        if discard is not None:
            discard()
        return _assemble(xx)

    if reuse_factors and lazy:          # the first (chord) step needs no tangent
        K, r, _, err = _trial(x)
    elif reuse_factors:                 # the first (chord) step uses the old factors
        K, r, err = _assemble(x)
    else:
        K, r, err = _to_factorise(x)
    if err:
        res.reason = err
        return res
    rn = _norm(r)
    res.residual_norms.append(rn)
    if scale is None:
        scale = rn
    tol = atol + rtol * scale
    if rn <= tol:
        why = admissible(x) if admissible is not None else ""
        res.converged = not why
        res.reason = f"inadmissible state: {why}" if why else ""
        return res
    use_chord = bool(reuse_factors)
    for it in range(1, max_iter + 1):
        dx = None
        if use_chord:
            t = time.perf_counter()
            dxc = solver.resolve(r)
            res.chord_seconds.append(time.perf_counter() - t)
            if dxc is not None and np.all(np.isfinite(dxc)):
                dx = -dxc
                res.chord_steps += 1
                res.iterations = it
        if dx is None:
            use_chord = False
            if K is None:                   # a chord step came here: the tangent at x
                K, r, err = _to_factorise(x)
                if err:
                    res.reason = err
                    return res
            t = time.perf_counter()
            try:
                dx = -solver.solve(K, r)
            except Exception as exc:  # singular matrix, PARDISO error, ...
                res.solve_seconds.append(time.perf_counter() - t)
                res.reason = f"linear solve failed: {exc}"
                return res
            res.solve_seconds.append(time.perf_counter() - t)
            K = None            # factorised: free its data before the next assembly
            res.factorisations += 1
            res.inertia = getattr(solver, "inertia", None)
            res.iterations = it
        if not np.all(np.isfinite(dx)):
            res.reason = "non-finite Newton increment (singular tangent?)"
            return res
        alpha = 1.0
        if step_limit is not None:
            amax = float(step_limit(x, dx))
            if not amax > 0:
                res.reason = (f"inadmissible Newton step at iteration {it}: no positive step "
                              f"fraction keeps the state admissible")
                return res
            if amax < 1.0:
                alpha = 0.5 * amax
        K1, r1, rn1, err = _trial(x + alpha * dx)
        if use_chord:
            if not rn1 < rn:        # discard the chord step: factorise at x instead
                use_chord = False
                continue
        else:
            dxn = _norm(dx)

            def acceptable(r_trial, rn_trial, a):
                # residual decrease, or Deuflhard's natural monotonicity test: the
                # simplified Newton correction with the current factorisation shrinks
                # (affine invariant; it accepts the full steps that penalty / saddle-point
                # problems need although their residual norm grows on the first iterations)
                if rn_trial < rn:
                    return True
                if not np.isfinite(rn_trial):
                    return False
                dxbar = solver.resolve(r_trial)
                return dxbar is not None and _norm(dxbar) <= (1.0 - 0.5 * a) * dxn

            if line_search and not acceptable(r1, rn1, alpha):
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
                if lazy:
                    K1, r1, rn1 = None, rt, rnt
                else:   # the tangent at the accepted point
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
        use_chord = chord > 0 and alpha == 1.0 and rn1 <= chord * rn
        K, r, rn = K1, r1, rn1
        res.residual_norms.append(rn)
        dn = alpha * _norm(dx)
        res.step_norms.append(dn)
        if rn <= tol or (dn <= xtol * (1.0 + _norm(x)) and rn <= 1e3 * tol):
            why = admissible(x) if admissible is not None else ""
            if why:
                res.reason = f"converged to an inadmissible state: {why}"
                return res
            res.converged = True
            return res
    res.reason = f"no convergence in {max_iter} iterations (||r|| = {rn:.3e}, tol {tol:.1e})"
    return res

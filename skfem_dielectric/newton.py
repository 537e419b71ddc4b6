"""Problem-agnostic Newton solver and load ramp with adaptive cut-back.

This module knows nothing about elasticity: every FE model of the package (3D plate,
2D membrane, 2D cross-section, Maxwell-traction variant) plugs into it.

Newton
------
:func:`newton` solves ``r(x) = 0`` given ``assemble(x) -> (K, r)`` (sparse tangent and
residual on the *reduced* unknowns, i.e. with Dirichlet conditions and tied dofs already
eliminated).  Full Newton steps are taken when they reduce the residual norm; otherwise a
backtracking line search halves the step (the tangent assembled at the accepted trial point
is reused, so a full step costs one assembly and one solve).  It never raises on
divergence: it returns a :class:`NewtonResult` with ``converged=False`` and a ``reason``.

Convergence: ``||r|| <= atol + rtol * scale`` where ``scale`` is given by the caller
(typically the norm of the external load vector), or the Newton increment is at round-off
level (``||dx|| <= xtol (1 + ||x||)``) while ``||r||`` is below ``1e3 (atol + rtol scale)``.

Ramp
----
:func:`ramp` drives a :class:`RampProblem` through a list of target loads.  A load is a
float or a 1-D array (e.g. ``(s, D0)``); between two consecutive targets the load is
interpolated linearly and sub-stepped adaptively: a sub-step whose Newton iteration fails is
halved (cut-back) up to ``max_cutbacks`` times, and after a success the sub-step doubles
again (never beyond the target).  Every target starts from the full interval, so a target's
solution depends only on the state at the previous target: resuming a ramp with
``x0=step.x, start=step.load`` gives bit-for-bit the same subsequent steps as the
uninterrupted run (for a deterministic linear solver such as SuperLU).

After each converged target, ``problem.postprocess(x, load)`` gives a dict of quantities
stored in the :class:`StepResult`, then ``on_step(step)`` is called (the validation harness
writes CSV rows and saves states there).  If the problem has ``stability(inertia)``,
its verdict (``True``/``False``/``None``) is stored as ``quantities["stable"]``.  A target that cannot be reached ends the ramp:
``RampResult.converged=False``, ``reason``, ``failed_at`` (the load of the failed sub-step),
a ``RuntimeWarning`` is issued and all converged steps are kept; the furthest converged
sub-step towards the failed target is appended as a step with ``target_reached=False``.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field
from typing import Any, Callable, Protocol, Sequence

import numpy as np
import scipy.sparse as sp

from .linear import LinearSolver, get_linear_solver

__all__ = ["NewtonResult", "StepResult", "RampResult", "RampProblem", "newton", "ramp"]


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


@dataclass
class StepResult:
    """One converged (or the failed) target load of a ramp.

    Attributes
    ----------
    load
        The target load (float or array, as given to :func:`ramp`).
    converged
        True for every step stored in ``RampResult.steps``.
    iterations
        Newton iterations summed over the sub-steps that reached this target.
    substeps
        Number of converged sub-steps used (1 = reached in one step).
    cutbacks
        Number of failed sub-steps that were halved.
    residual_norms
        Residual history of each converged sub-step (list of lists).
    x
        Reduced solution vector (pass it as ``x0`` to resume a ramp).
    quantities
        Post-processed values from ``problem.postprocess`` (e.g. ``lam1``, ``min_P33``).
    assembly_seconds, solve_seconds
        Total wall time spent in assembly and linear solves for this target.
    inertia
        Inertia of the last factorised tangent of this step if the linear solver reports it
        (PARDISO), else ``None``.
    target_reached
        False for the last step of a ramp that stopped: the furthest converged sub-step on
        the way to the target that could not be reached (its ``load`` is intermediate).
    """

    load: Any
    converged: bool
    iterations: int
    substeps: int
    cutbacks: int
    residual_norms: list[list[float]]
    x: np.ndarray
    quantities: dict[str, Any] = field(default_factory=dict)
    assembly_seconds: float = 0.0
    solve_seconds: float = 0.0
    inertia: tuple[int, int, int] | None = None
    target_reached: bool = True

    def __getitem__(self, key: str) -> Any:
        return self.quantities[key]


@dataclass
class RampResult:
    """Outcome of a load ramp.

    Attributes
    ----------
    steps
        Converged target steps, in order (the starting state is not included).
    converged
        True if every target was reached.
    reason
        Empty if converged, else why the ramp stopped.
    failed_at
        Load of the sub-step that could not be solved (``None`` if converged).
    wall_seconds
        Total wall time of the ramp.
    problem
        The problem that was solved (set by the high-level drivers; use it to evaluate or
        export the stored states), else ``None``.
    iterations_total, assembly_calls, assembly_seconds, solve_seconds
        Totals over *all* Newton attempts of the ramp, including failed sub-steps and
        line-search evaluations (the per-step values count only converged targets).
    assembly_times, solve_times
        Wall time of every assembly call and every linear solve, in order (for medians
        and profiles; their sums are ``assembly_seconds`` and ``solve_seconds``).
    unstable_at
        With ``stop_on_instability``: load of the converged (sub-)step whose tangent was
        judged unstable, where the ramp stopped (``None`` otherwise).
    """

    steps: list[StepResult]
    converged: bool
    reason: str = ""
    failed_at: Any = None
    wall_seconds: float = 0.0
    problem: Any = None
    iterations_total: int = 0
    assembly_calls: int = 0
    assembly_seconds: float = 0.0
    solve_seconds: float = 0.0
    assembly_times: list[float] = field(default_factory=list)
    solve_times: list[float] = field(default_factory=list)
    unstable_at: Any = None

    def column(self, name: str) -> np.ndarray:
        """Array of quantity ``name`` over the converged steps (``"load"`` and
        ``"iterations"`` are also accepted)."""
        if name == "load":
            return np.array([st.load for st in self.steps], dtype=float)
        if name == "iterations":
            return np.array([st.iterations for st in self.steps], dtype=int)
        known = set().union(*(st.quantities for st in self.steps)) if self.steps else set()
        if name not in known:
            raise ValueError(
                f"name must be 'load', 'iterations' or a post-processed quantity "
                f"{sorted(known)}, got {name!r}")
        return np.array([st.quantities[name] for st in self.steps])

    @property
    def x(self) -> np.ndarray | None:
        """Reduced solution vector of the last converged step (``None`` if none)."""
        return self.steps[-1].x if self.steps else None


class RampProblem(Protocol):
    """What :func:`ramp` needs from a discretised problem.

    Required: ``initial_state() -> x`` (reduced vector at zero load) and
    ``assemble(x, load) -> (K, r)`` (reduced sparse tangent and residual).  Optional:
    ``residual(x, load) -> r`` (cheaper residual for the line search),
    ``residual_scale(load) -> float`` (scale for the relative tolerance, e.g. the norm of the
    external load vector) and ``postprocess(x, load) -> dict``.
    """

    def initial_state(self) -> np.ndarray: ...

    def assemble(self, x: np.ndarray, load: Any) -> tuple[sp.spmatrix, np.ndarray]: ...


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


def _as_load(load: Any) -> Any:
    arr = np.asarray(load, dtype=float)
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"loads must be finite, got {load!r}")
    return float(arr) if arr.ndim == 0 else arr.copy()


def ramp(problem: RampProblem, loads: Sequence[Any], *, x0: np.ndarray | None = None,
         start: Any = None, on_step: Callable[[StepResult], Any] | None = None,
         linear_solver: str | LinearSolver = "superlu", max_cutbacks: int = 6,
         atol: float = 1e-10, rtol: float = 1e-10, max_iter: int = 25,
         line_search: bool = True, stop_on_instability: bool = False) -> RampResult:
    """Run ``problem`` through the target ``loads`` with adaptive sub-stepping.

    Parameters
    ----------
    problem
        A :class:`RampProblem`.
    loads
        Target loads in order (floats or equal-length 1-D arrays); each is reached and
        post-processed.  Loads must be finite.
    x0, start
        State to start from: the reduced vector and its load.  Default:
        ``problem.initial_state()`` at zero load.  To resume a ramp pass ``x0=step.x`` and
        ``start=step.load`` of a saved :class:`StepResult` and the remaining loads.
    on_step
        Called as ``on_step(step)`` after every converged target.
    linear_solver
        Name or instance (see :func:`skfem_dielectric.linear.get_linear_solver`); one
        instance is used for the whole ramp.
    max_cutbacks
        How many times a failing sub-step may be halved before the ramp stops.
    atol, rtol, max_iter, line_search
        Newton settings (see :func:`newton`); ``rtol`` is relative to
        ``problem.residual_scale(load)`` when the problem has it, else to the first
        residual of each sub-step.
    stop_on_instability
        Stop at the first converged sub-step that ``problem.stability(inertia)`` judges
        unstable (needs a solver that reports the inertia, i.e. PARDISO; otherwise the
        verdict is ``None`` and the ramp goes on, with one ``RuntimeWarning``).  That step is kept (``target_reached``
        False if it is intermediate) and its load is ``unstable_at``.  A load-controlled
        Newton cannot follow the path through such a point, so without this option the
        ramp spends its cut-backs trying (see ``docs/fe.md``, breakdown).

    Returns
    -------
    RampResult
        Never raises on non-convergence; warns (``RuntimeWarning``) when it stops early.
    """
    t_start = time.perf_counter()
    solver = get_linear_solver(linear_solver)
    targets = [_as_load(ld) for ld in loads]
    x = np.array(problem.initial_state() if x0 is None else x0, dtype=float, copy=True)
    if start is None:
        cur = 0.0 * np.asarray(targets[0], dtype=float) if targets else 0.0
        cur = _as_load(cur)
    else:
        cur = _as_load(start)
    has_scale = hasattr(problem, "residual_scale")
    has_res = hasattr(problem, "residual")
    has_post = hasattr(problem, "postprocess")
    has_stab = hasattr(problem, "stability")
    no_verdict_warned = False
    out = RampResult(steps=[], converged=True)

    def record(load, target_reached):
        """Keep the converged state ``x`` at ``load`` as a step (post-processed, with the
        stability verdict of its last tangent) and report it to ``on_step``."""
        step = StepResult(load=load, converged=True, iterations=iters, substeps=subs,
                          cutbacks=cuts, residual_norms=hist, x=x.copy(),
                          assembly_seconds=t_asm, solve_seconds=t_sol, inertia=inertia,
                          target_reached=target_reached)
        if has_post:
            step.quantities = dict(problem.postprocess(x, load))
        if has_stab:
            step.quantities.setdefault("stable", problem.stability(inertia))
        out.steps.append(step)
        if on_step is not None:
            on_step(step)

    for target in targets:
        a, b = np.asarray(cur, dtype=float), np.asarray(target, dtype=float)
        frac, dfrac = 0.0, 1.0
        iters = subs = cuts = 0
        inertia = None
        hist: list[list[float]] = []
        t_asm = t_sol = 0.0
        failed = ""
        unstable = None
        while frac < 1.0:
            f_new = min(1.0, frac + dfrac)
            load = _as_load(b if f_new >= 1.0 else a + f_new * (b - a))
            scale = problem.residual_scale(load) if has_scale else None
            nr = newton(lambda xx: problem.assemble(xx, load), x,
                        residual=(lambda xx: problem.residual(xx, load)) if has_res else None,
                        linear_solver=solver, atol=atol, rtol=rtol, scale=scale,
                        max_iter=max_iter, line_search=line_search)
            iters += nr.iterations
            t_asm += sum(nr.assembly_seconds)
            t_sol += sum(nr.solve_seconds)
            out.iterations_total += nr.iterations
            out.assembly_calls += len(nr.assembly_seconds)
            out.assembly_seconds += sum(nr.assembly_seconds)
            out.solve_seconds += sum(nr.solve_seconds)
            out.assembly_times.extend(nr.assembly_seconds)
            out.solve_times.extend(nr.solve_seconds)
            if nr.converged:
                x = nr.x
                inertia = nr.inertia
                frac = f_new
                subs += 1
                hist.append(nr.residual_norms)
                dfrac = min(2.0 * dfrac, 1.0)
                if stop_on_instability and has_stab:
                    verdict = problem.stability(inertia)
                    if verdict is False:
                        unstable = load
                        break
                    if verdict is None and not no_verdict_warned:
                        no_verdict_warned = True
                        warnings.warn("stop_on_instability has no effect: the linear solver "
                                      "reports no inertia, so there is no stability verdict "
                                      "(use linear_solver='pardiso')", RuntimeWarning,
                                      stacklevel=2)
            else:
                cuts += 1
                if cuts > max_cutbacks:
                    failed = nr.reason
                    out.failed_at = load
                    break
                dfrac *= 0.5
        if unstable is not None:
            record(unstable, frac >= 1.0)
            out.converged = False
            out.unstable_at = unstable
            out.reason = (f"stability lost at load {unstable!r} (inertia of the tangent: "
                          f"{inertia}); stopped on request (stop_on_instability)")
            warnings.warn(out.reason, RuntimeWarning, stacklevel=2)
            break
        if failed:
            if frac > 0.0:   # keep the furthest converged sub-step towards the target
                record(_as_load(b if frac >= 1.0 else a + frac * (b - a)), False)
            out.converged = False
            out.reason = (f"target load {target!r} not reached after {max_cutbacks} "
                          f"cut-backs; last Newton failure: {failed}")
            warnings.warn(out.reason, RuntimeWarning, stacklevel=2)
            break
        cur = target
        record(target, True)
    out.wall_seconds = time.perf_counter() - t_start
    return out

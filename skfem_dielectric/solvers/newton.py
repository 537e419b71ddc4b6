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
from typing import Any, Callable, NamedTuple

import numpy as np
import scipy.sparse as sp

from ..checks import (check_callable, check_count, check_nonnegative, check_nonnegative_int,
                     check_tolerances)
from ..fem.runtime import TRIM_MIN_UNKNOWNS
from ..linalg.linear import get_linear_solver
from ..linalg.solver_base import LinearSolver

__all__ = ["NewtonSettings", "NewtonResult", "newton"]


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
    factors_at
        The iterate whose tangent was factorised last (the factors the linear solver
        holds afterwards), ``None`` if no tangent was factorised.
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
    factors_at: np.ndarray | None = None


@dataclass(frozen=True)
class NewtonSettings:
    """How :func:`newton` iterates towards ``r(x) = 0`` at one load.

    The options that travel together from a driver through a ramp or a continuation down
    to every Newton solve; one frozen object, checked once where it is made, so that a
    driver is told "solve like this" instead of forwarding each option by hand.  Change
    one field of a given object with :func:`dataclasses.replace`.

    Attributes
    ----------
    atol, rtol
        Converged when ``||r|| <= atol + rtol * scale`` (``scale``: see :func:`newton`);
        both ``>= 0`` and not both zero (a test that can never be met).
    xtol
        Also converged when the increment is at round-off, ``||dx|| <= xtol (1 + ||x||)``,
        and ``||r|| <= 1e3 (atol + rtol scale)``.
    max_iter
        Maximum number of iterations (Newton and chord steps), ``>= 1``.
    line_search
        Backtrack (halve) a step that does not reduce ``||r||`` (and fails the natural
        monotonicity test); otherwise take full steps.
    max_backtracks
        Maximum halvings per iteration, ``>= 0``; if none is accepted the solve fails.
    chord
        Contraction below which the factorisation is reused, in ``[0, 1)``; 0 factorises
        the tangent in every iteration (see :func:`newton`).
    acceleration
        Depth ``m >= 0`` of the Anderson acceleration of the chord steps: each chord step
        is combined with the last ``m`` ones made on the same factors (see
        :func:`newton`); 0 takes the plain chord steps.

    Raises
    ------
    ValueError
        A field out of its range, naming the field and the value.
    """

    atol: float = 1e-10
    rtol: float = 1e-10
    xtol: float = 1e-13
    max_iter: int = 25
    line_search: bool = True
    max_backtracks: int = 8
    chord: float = 0.0
    acceleration: int = 0

    def __post_init__(self) -> None:
        atol, rtol = check_tolerances(self.atol, self.rtol)
        chord = check_nonnegative("chord", self.chord)
        if not chord < 1.0:
            raise ValueError(f"chord must be in [0, 1), got {self.chord!r}")
        if not isinstance(self.line_search, (bool, np.bool_)):
            raise ValueError(f"line_search must be True or False, got {self.line_search!r}")
        checked = dict(atol=atol, rtol=rtol, xtol=check_nonnegative("xtol", self.xtol),
                       max_iter=check_count("max_iter", self.max_iter),
                       line_search=bool(self.line_search),
                       max_backtracks=check_nonnegative_int("max_backtracks",
                                                            self.max_backtracks),
                       chord=chord,
                       acceleration=check_nonnegative_int("acceleration", self.acceleration))
        for name, value in checked.items():     # the checked values, as the solver uses them
            object.__setattr__(self, name, value)


def check_settings(name: str, value: Any, kind: type) -> Any:
    """``value`` if it is a ``kind`` (a settings object), else ``ValueError`` naming
    ``name``."""
    if not isinstance(value, kind):
        raise ValueError(f"{name} must be a {kind.__name__}, got {value!r}")
    return value


def _norm(r: np.ndarray) -> float:
    return float(np.linalg.norm(r))


class _Failed(Exception):
    """Ends a Newton solve; the message becomes :attr:`NewtonResult.reason`."""


class _Point(NamedTuple):
    """An evaluated state: tangent (``None`` where only the residual was evaluated),
    residual, its norm (``inf`` on error) and the error (empty if none)."""

    K: Any
    r: Any
    rn: float
    error: str


def _check_vector_result(who: str, r: Any, n: int) -> None:
    """``ValueError`` unless ``r`` is a real array of shape ``(n,)`` (the residual that
    ``who`` returned for a state of ``n`` unknowns)."""
    if not (isinstance(r, np.ndarray) and r.shape == (n,) and r.dtype.kind in "iuf"):
        got = (f"{type(r).__name__} of shape {r.shape} and dtype {r.dtype}"
               if isinstance(r, np.ndarray) else repr(r)[:80])
        raise ValueError(f"{who} must return the residual as a real array of shape ({n},) "
                         f"(one entry per unknown of x), got {got}")


def _check_assembled(out: Any, n: int) -> None:
    """``ValueError`` unless ``out`` (what ``assemble(x)`` returned for a state of ``n``
    unknowns) is a ``(K, r)`` pair: a tangent of shape ``(n, n)`` and a residual of shape
    ``(n,)``."""
    if not (isinstance(out, (tuple, list)) and len(out) == 2):
        raise ValueError(f"assemble(x) must return a (K, r) pair (sparse tangent dr/dx of "
                         f"shape ({n}, {n}) and residual of shape ({n},)), got "
                         f"{repr(out)[:80]}")
    K, r = out
    if getattr(K, "shape", None) != (n, n):
        raise ValueError(f"assemble(x) must return a (K, r) pair whose tangent K has shape "
                         f"({n}, {n}), got K = {repr(K)[:80]}")
    _check_vector_result("assemble(x)", r, n)


class _NewtonIteration:
    """The state of one Newton solve between two iterations.

    It holds the iterate ``x``, its residual ``r`` and norm ``rn``, the tangent ``K`` at
    ``x`` until it is factorised (``None`` afterwards, or where only the residual was
    evaluated), whether the next step is a chord step on the factors the linear solver
    holds, and the :class:`NewtonResult` that collects iterations, norms and timings.  Its
    methods are the steps of :func:`newton` (start, increment, line search, accept); a
    failure raises :class:`_Failed` with the reason, so that :func:`newton` reads as the
    algorithm.
    """

    def __init__(self, assemble, residual, solver, settings: NewtonSettings, step_limit,
                 admissible, x: np.ndarray) -> None:
        self.assemble, self.residual, self.solver = assemble, residual, solver
        self.settings, self.step_limit, self.admissible = settings, step_limit, admissible
        # with chord steps and a residual-only evaluation, the tangent is assembled only
        # where it is factorised
        self.lazy = settings.chord > 0 and residual is not None
        # the old factors are freed before a new tangent only where they are large
        self.discard = (getattr(solver, "discard", None)
                        if x.shape[0] >= TRIM_MIN_UNKNOWNS else None)
        self.x = x
        self.K = self.r = None
        self.rn = self.tol = np.inf
        self.chord_step = False
        # (iterate, chord correction) pairs on the factors at hand, for the acceleration
        self.history: list[tuple[np.ndarray, np.ndarray]] = []
        self.result = NewtonResult(x=x, converged=False, iterations=0, residual_norms=[])

    # --- evaluations, timed into the result
    def evaluate(self, x: np.ndarray) -> _Point:
        """Tangent and residual at ``x``."""
        t = time.perf_counter()
        try:
            out = self.assemble(x)
        except (FloatingPointError, ValueError, ZeroDivisionError) as exc:
            self.result.assembly_seconds.append(time.perf_counter() - t)
            return _Point(None, None, np.inf, f"assembly failed: {exc}")
        self.result.assembly_seconds.append(time.perf_counter() - t)
        _check_assembled(out, x.shape[0])
        K, r = out
        if not np.all(np.isfinite(r)):
            return _Point(None, None, np.inf, "non-finite residual")
        return _Point(K, r, _norm(r), "")

    def trial(self, x: np.ndarray) -> _Point:
        """A trial point: only its residual where the tangent is assembled lazily."""
        if not self.lazy:
            return self.evaluate(x)
        t = time.perf_counter()
        try:
            r = self.residual(x)
        except (FloatingPointError, ValueError, ZeroDivisionError) as exc:
            return _Point(None, None, np.inf, f"residual failed: {exc}")
        finally:
            self.result.residual_seconds.append(time.perf_counter() - t)
        _check_vector_result("residual", r, x.shape[0])
        if not np.all(np.isfinite(r)):
            return _Point(None, None, np.inf, "non-finite residual")
        return _Point(None, r, _norm(r), "")

    def tangent_to_factorise(self, x: np.ndarray) -> _Point:
        """The tangent at ``x`` that is factorised next: the old factors (of no more use)
        are freed first on a system of at least
        :data:`~skfem_dielectric.fem.runtime.TRIM_MIN_UNKNOWNS` unknowns, so that they and
        the new tangent are not held together (on a smaller one the solver's next
        factorisation reuses their memory)."""
        if self.discard is not None:
            self.discard()
        return self.evaluate(x)

    def inadmissible(self) -> str:
        """Why the iterate is not an admissible state (empty if it is)."""
        return self.admissible(self.x) if self.admissible is not None else ""

    # --- the steps of the algorithm
    def start(self, reuse_factors: bool, scale: float | None) -> bool:
        """Evaluate the initial guess and fix the tolerance; True if it already meets it.
        With ``reuse_factors`` the first step is a chord step on the factors at hand."""
        if reuse_factors and self.lazy:
            p = self.trial(self.x)
        elif reuse_factors:
            p = self.evaluate(self.x)
        else:
            p = self.tangent_to_factorise(self.x)
        if p.error:
            raise _Failed(p.error)
        self.K, self.r, self.rn = p.K, p.r, p.rn
        self.result.residual_norms.append(self.rn)
        self.tol = self.settings.atol + self.settings.rtol * (self.rn if scale is None
                                                              else scale)
        self.chord_step = bool(reuse_factors)
        return self.rn <= self.tol

    def increment(self, it: int) -> np.ndarray:
        """The increment ``dx`` of iteration ``it``: a chord step ``-K_old^-1 r`` when the
        factors are to be reused and the back-substitution succeeds, else a Newton step
        on the tangent at ``x``, factorised now."""
        res = self.result
        dx = None
        if self.chord_step:
            t = time.perf_counter()
            dxc = self.solver.resolve(self.r)
            res.chord_seconds.append(time.perf_counter() - t)
            if dxc is not None and np.all(np.isfinite(dxc)):
                dx = self.accelerated(-dxc)
                res.chord_steps += 1
                res.iterations = it
        if dx is None:
            self.chord_step = False
            dx = self.newton_step(it)
            self.history = [(self.x, dx)]     # a Newton step is the first chord step
        if not np.all(np.isfinite(dx)):
            raise _Failed("non-finite Newton increment (singular tangent?)")
        return dx

    def accelerated(self, g: np.ndarray) -> np.ndarray:
        """The chord correction ``g = -K_old^-1 r`` at ``x``, Anderson-accelerated.

        With the iterates ``x_i`` and chord corrections ``g_i`` of the last ``m``
        (``acceleration``) steps on the same factors, the differences ``dX``, ``dG`` of
        consecutive pairs give ``gamma = argmin ||g - dG gamma||`` and the step ``g - (dX
        + dG) gamma`` (Anderson's type-II update of the fixed-point map ``x + g(x)``,
        Walker & Ni, SIAM J. Numer. Anal. 49, 2011).  On a linear problem it is GMRES
        preconditioned by the old factors; the plain chord step where ``m = 0`` or no
        earlier pair exists.
        """
        m = self.settings.acceleration
        if m == 0:
            return g
        self.history = (self.history + [(self.x, g)])[-(m + 1):]
        h = self.history
        if len(h) < 2:
            return g
        dX = np.stack([b[0] - a[0] for a, b in zip(h[:-1], h[1:])], axis=1)
        dG = np.stack([b[1] - a[1] for a, b in zip(h[:-1], h[1:])], axis=1)
        gamma = np.linalg.lstsq(dG, g, rcond=1e-12)[0]
        step = g - (dX + dG) @ gamma
        return step if np.all(np.isfinite(step)) else g

    def newton_step(self, it: int) -> np.ndarray:
        """Factorise the tangent at ``x`` (assembled now if a chord step came here) and
        solve for the Newton increment."""
        res = self.result
        if self.K is None:
            p = self.tangent_to_factorise(self.x)
            if p.error:
                raise _Failed(p.error)
            self.K, self.r = p.K, p.r
        t = time.perf_counter()
        try:
            dx = -self.solver.solve(self.K, self.r)
        except Exception as exc:  # singular matrix, PARDISO error, ...
            res.solve_seconds.append(time.perf_counter() - t)
            raise _Failed(f"linear solve failed: {exc}") from None
        res.solve_seconds.append(time.perf_counter() - t)
        self.K = None           # factorised: free its data before the next assembly
        res.factorisations += 1
        res.factors_at = self.x
        res.inertia = getattr(self.solver, "inertia", None)
        res.iterations = it
        return dx

    def first_fraction(self, dx: np.ndarray, it: int) -> float:
        """The step fraction tried first: 1, or half the largest admissible one."""
        if self.step_limit is None:
            return 1.0
        amax = float(self.step_limit(self.x, dx))
        if not amax > 0:
            raise _Failed(f"inadmissible Newton step at iteration {it}: no positive step "
                          f"fraction keeps the state admissible")
        return 0.5 * amax if amax < 1.0 else 1.0

    def acceptable(self, r_trial, rn_trial: float, alpha: float, dxn: float) -> bool:
        """Residual decrease, or Deuflhard's natural monotonicity test: the simplified
        Newton correction with the current factorisation shrinks (affine invariant; it
        accepts the full steps that penalty / saddle-point problems need although their
        residual norm grows on the first iterations)."""
        if rn_trial < self.rn:
            return True
        if not np.isfinite(rn_trial):
            return False
        dxbar = self.solver.resolve(r_trial)
        return dxbar is not None and _norm(dxbar) <= (1.0 - 0.5 * alpha) * dxn

    def line_search(self, dx: np.ndarray, alpha: float, trial: _Point,
                    it: int) -> tuple[float, _Point]:
        """The accepted fraction of the Newton step ``dx`` tried at ``alpha`` (reaching
        ``trial``) and the point it reaches: halve it until :meth:`acceptable`, at most
        ``max_backtracks`` times."""
        s = self.settings
        dxn = _norm(dx)
        if not s.line_search or self.acceptable(trial.r, trial.rn, alpha, dxn):
            if trial.error:
                raise _Failed(trial.error)
            return alpha, trial
        for _ in range(s.max_backtracks):
            alpha *= 0.5
            xt = self.x + alpha * dx
            if self.residual is not None:
                try:
                    rt = self.residual(xt)
                except (FloatingPointError, ValueError, ZeroDivisionError):
                    continue
                rnt = _norm(rt) if np.all(np.isfinite(rt)) else np.inf
            else:
                _, rt, rnt, _ = self.evaluate(xt)
            if self.acceptable(rt, rnt, alpha, dxn):
                break
        else:
            raise _Failed(f"line search failed at iteration {it}: no decrease of "
                          f"||r|| = {self.rn:.3e} after {s.max_backtracks} halvings")
        if self.lazy:
            return alpha, _Point(None, rt, rnt, "")
        p = self.evaluate(self.x + alpha * dx)      # the tangent at the accepted point
        if p.error:
            raise _Failed(p.error)
        return alpha, p

    def accept(self, dx: np.ndarray, alpha: float, new: _Point) -> bool:
        """Move to ``x + alpha dx`` (the point ``new``); the next step reuses the factors
        if this was a full step that contracted ``||r||`` by ``chord``.  True when
        converged."""
        s, res = self.settings, self.result
        self.x = self.x + alpha * dx
        res.x = self.x
        self.chord_step = s.chord > 0 and alpha == 1.0 and new.rn <= s.chord * self.rn
        self.K, self.r, self.rn = new.K, new.r, new.rn
        res.residual_norms.append(self.rn)
        dn = alpha * _norm(dx)
        res.step_norms.append(dn)
        if self.rn <= self.tol or (dn <= s.xtol * (1.0 + _norm(self.x))
                                   and self.rn <= 1e3 * self.tol):
            why = self.inadmissible()
            if why:
                raise _Failed(f"converged to an inadmissible state: {why}")
            res.converged = True
            return True
        return False


def newton(assemble: Callable[[np.ndarray], tuple[sp.spmatrix, np.ndarray]],
           x0: np.ndarray, *, residual: Callable[[np.ndarray], np.ndarray] | None = None,
           linear_solver: str | LinearSolver = "superlu",
           settings: NewtonSettings = NewtonSettings(), scale: float | None = None,
           step_limit: Callable[[np.ndarray, np.ndarray], float] | None = None,
           admissible: Callable[[np.ndarray], str] | None = None,
           reuse_factors: bool = False) -> NewtonResult:
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
    settings
        Tolerances, iteration and backtracking limits, chord steps
        (:class:`NewtonSettings`).  With ``chord > 0``: after a full step that reduced
        ``||r||`` by at least this factor the next step is a chord step ``dx = -K_old^-1
        r`` with the factors at hand (a back-substitution, no new tangent), and so on
        while each chord step contracts as much; a chord step that contracts less is kept
        if it reduces ``||r||`` (the next step factorises again), else it is discarded.
        With ``acceleration = m > 0`` every chord step is Anderson-accelerated with the
        last ``m`` steps on the same factors (Anderson's type-II update, Walker & Ni,
        SIAM J. Numer. Anal. 49, 2011: on a linear problem GMRES preconditioned by the
        old factors), so that old factors keep contracting where plain chord steps
        would stall.
        With ``residual`` given, the trial points are then evaluated by ``residual`` and
        the tangent is assembled only where it is factorised.  The converged state
        satisfies the same test, so the solution changes only within the tolerance.
    scale
        The ``scale`` of the convergence test ``||r|| <= atol + rtol * scale``; defaults
        to the initial residual norm.
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
        vector, ``settings`` not a :class:`NewtonSettings`, a negative ``scale``; and, at
        the first evaluation, an ``assemble(x)`` that does not return a ``(K, r)`` pair of
        shapes ``(n, n)`` and ``(n,)`` (``n = len(x0)``) or a ``residual(x)`` that does
        not return a real array of shape ``(n,)``.

    Examples
    --------
    The cube root of 2 as the root of ``x^3 - 2``:

    >>> import numpy as np, scipy.sparse as sp
    >>> res = newton(lambda x: (sp.csr_matrix([[3 * x[0] ** 2]]), x ** 3 - 2), np.ones(1),
    ...              settings=NewtonSettings(atol=1e-14, rtol=0.0))
    >>> res.converged, round(float(res.x[0]), 12)
    (True, 1.259921049895)
    """
    check_callable("assemble", assemble, optional=False)
    for name, f in (("residual", residual), ("step_limit", step_limit),
                    ("admissible", admissible)):
        check_callable(name, f)
    check_settings("settings", settings, NewtonSettings)
    scale = None if scale is None else check_nonnegative("scale", scale)
    solver = get_linear_solver(linear_solver)
    try:
        x = np.array(x0, dtype=float, copy=True)
    except (TypeError, ValueError):
        raise ValueError(f"x0 must be a real vector, got {x0!r}") from None
    if x.ndim != 1 or not np.all(np.isfinite(x)):
        raise ValueError(f"x0 must be a finite 1-D vector, got shape {x.shape}")
    state = _NewtonIteration(assemble, residual, solver, settings, step_limit, admissible, x)
    res = state.result
    try:
        if state.start(reuse_factors, scale):
            why = state.inadmissible()
            res.converged = not why
            res.reason = f"inadmissible state: {why}" if why else ""
            return res
        for it in range(1, settings.max_iter + 1):
            dx = state.increment(it)
            alpha = state.first_fraction(dx, it)
            trial = state.trial(state.x + alpha * dx)
            if state.chord_step:
                if not trial.rn < state.rn:     # discard the chord step: factorise at x
                    state.chord_step = False
                    continue
            else:
                alpha, trial = state.line_search(dx, alpha, trial, it)
            if state.accept(dx, alpha, trial):
                return res
        res.reason = (f"no convergence in {settings.max_iter} iterations "
                      f"(||r|| = {state.rn:.3e}, tol {state.tol:.1e})")
    except _Failed as stop:
        res.reason = str(stop)
    return res

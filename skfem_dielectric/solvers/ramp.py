"""Load ramp with adaptive cut-back for any :class:`~skfem_dielectric.problem.Problem`.

:func:`ramp` drives a problem through a list of target loads.  A load is a float or a 1-D
array (e.g. ``(s, D0)``); between two consecutive targets the load is interpolated linearly
and sub-stepped adaptively: a sub-step whose Newton iteration fails is halved (cut-back) up
to ``max_cutbacks`` times, and after a success the sub-step doubles again (never beyond the
target).  Every target starts from the full interval, so a target's solution depends only on
the state at the previous target and the converged states before it (the predictor's
second and third points, ``StepResult.back`` and ``StepResult.back2``) and, with
``keep_factors``, on the factors the solver holds (``StepResult.factors``): resuming a ramp
with ``x0=step.x, start=step.load, back=step.back, back2=step.back2,
factors=step.factors`` gives bit-for-bit the same
subsequent steps as the uninterrupted run (for a deterministic linear solver such as
SuperLU).

After each converged target, ``problem.postprocess(x, load)`` gives a dict of quantities
stored in the :class:`StepResult`, together with ``stable``, the verdict of
``problem.stability(inertia)`` (``True``/``False``/``None``); then ``on_step(step)`` is
called (the validation harness writes CSV rows and saves states there).  A target that
cannot be reached ends the ramp: ``RampResult.converged=False``, ``reason``, ``failed_at``
(the load of the failed sub-step), a ``RuntimeWarning`` is issued and all converged steps
are kept; the furthest converged sub-step towards the failed target is appended as a step
with ``target_reached=False``.

Admissible states: ``step_limit(x, dx, load) -> alpha_max`` caps every Newton step (e.g.
:meth:`~skfem_dielectric.models.plate.problem.PlateProblem.max_step`, ``det F > 0`` along the step)
and ``admissible(x, load) -> reason`` rejects a converged state (a rejected sub-step is cut back
like a failed one).  They are part of the model: the ramp asks the problem for them
(:meth:`~skfem_dielectric.problem.Problem.newton_guards`; for the 3D plate ``det F > 0``
along every step and no converged inverted state); a caller's own ``step_limit`` or
``admissible`` replaces the model's.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

import numpy as np

from ..checks import check_callable, check_choice, check_nonnegative_int, check_vector
from ..linalg.linear import get_linear_solver
from ..linalg.solver_base import PRECISIONS, LinearSolver
from ..problem import Problem
from .newton import NewtonResult, NewtonSettings, check_settings, newton

__all__ = ["RampSettings", "StepResult", "RampResult", "ramp", "check_callbacks"]

PREDICTORS = ("none", "secant", "quadratic")


@dataclass(frozen=True)
class RampSettings(NewtonSettings):
    """How :func:`ramp` solves each load step: the Newton settings plus what the ramp does
    around the Newton solves.

    A :class:`~skfem_dielectric.solvers.newton.NewtonSettings` (the ramp hands it to every
    Newton solve, which reads only its Newton fields) with the ramp's own retry, start and
    stop rules, so that a driver takes one object for its whole nonlinear solve.  Change one
    field with :func:`dataclasses.replace`, e.g. ``replace(KEPLINGER_SETTINGS,
    stop_on_instability=True)``.

    Attributes
    ----------
    atol, rtol, xtol, max_iter, line_search, max_backtracks, chord
        Newton settings (:class:`~skfem_dielectric.solvers.newton.NewtonSettings`);
        ``rtol`` is relative to ``problem.residual_scale(load)``, or to the first residual
        of each sub-step where that is ``None``.
    max_cutbacks
        How many times a failing sub-step may be halved before the ramp stops, ``>= 0``.
    predictor
        Start of each Newton solve: ``"secant"`` (the default: extrapolated through the
        last two converged states when the load keeps its direction and the extrapolation
        lowers the residual), ``"quadratic"`` (the parabola through the last three
        converged states where their loads lie in order on the line of the new increment
        and it lowers the residual, else the secant's start) or ``"none"`` (the last
        converged state).  The secant start depends on the state before the last one, the
        quadratic one also on the state before that, which every step keeps
        (``StepResult.back``, ``StepResult.back2``): a ramp resumed with them repeats the
        uninterrupted one bit for bit.
    keep_factors
        Start every Newton solve with chord steps on the factors the linear solver holds
        from the solve before (``reuse_factors`` of
        :func:`~skfem_dielectric.solvers.newton.newton`): a load step factorises only
        when the old factors stop contracting (by ``chord``).  Each step records where
        its factors come from (``StepResult.factors``); a ramp resumed with them repeats
        the uninterrupted one bit for bit.
    stop_on_instability
        Stop at the first converged sub-step that ``problem.stability(inertia)`` judges
        unstable (needs a solver that reports the inertia, i.e. PARDISO; otherwise the
        verdict is ``None`` and the ramp goes on, with one ``RuntimeWarning``).  A
        load-controlled Newton cannot follow the path through such a point, so without
        this option the ramp spends its cut-backs trying (see ``docs/fe.md``, breakdown).
    factor_precision
        Precision of the factors of a linear solver given by name where it is PARDISO:
        ``"double"`` (the default) or ``"single"`` (factors in single precision, every
        solve refined in double with the tangent to the same accuracy, in about half the
        time of a factorisation; :class:`~skfem_dielectric.linalg.linear.PardisoSolver`).
        The states converge to the same tolerance; the inertia of a step (its stability
        verdict) is that of its single-precision factors.  A ramp with a
        ``state_analysis`` factorises in double precision (the analysis solves with the
        factors).  SuperLU and a solver instance factorise as they are.

    Raises
    ------
    ValueError
        A field out of its range, naming the field and the value.
    """

    max_cutbacks: int = 6
    predictor: str = "secant"
    stop_on_instability: bool = False
    keep_factors: bool = False
    factor_precision: str = "double"

    def __post_init__(self) -> None:
        super().__post_init__()
        check_choice("predictor", self.predictor, PREDICTORS)
        check_choice("factor_precision", self.factor_precision, PRECISIONS)
        for name in ("stop_on_instability", "keep_factors"):
            if not isinstance(getattr(self, name), (bool, np.bool_)):
                raise ValueError(f"{name} must be True or False, "
                                 f"got {getattr(self, name)!r}")
            object.__setattr__(self, name, bool(getattr(self, name)))
        object.__setattr__(self, "max_cutbacks",
                           check_nonnegative_int("max_cutbacks", self.max_cutbacks))


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
        Newton iterations (with the chord steps) summed over the sub-steps that reached
        this target.
    factorisations
        Tangents factorised in those iterations.
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
    back
        The converged (sub-)step before this one, ``(x, load)``: the second point of the
        secant predictor.  Pass it as ``back=`` together with ``x0=step.x`` and
        ``start=step.load`` to resume a ramp bit for bit (``None`` for the first step of a
        ramp started without ``back``: its start is a guess, not a converged state).
    back2
        The converged (sub-)step before ``back``, ``(x, load)``: the third point of the
        quadratic predictor (``None`` where there is none).  Pass it as ``back2=`` with
        ``back`` to resume a ramp bit for bit.
    factors
        With ``keep_factors``: where the factors the linear solver holds after this step
        come from, ``(x, load)``, the state whose tangent was factorised last (the
        converged state itself where a ``state_analysis`` factorised it); the next step
        starts on them, so pass it as ``factors=`` to resume a ramp bit for bit.  ``None``
        otherwise.
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
    factorisations: int = 0
    back: tuple[np.ndarray, Any] | None = None
    factors: tuple[np.ndarray, Any] | None = None
    back2: tuple[np.ndarray, Any] | None = None

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
    factorisations, chord_steps
        Tangents factorised and chord steps (reused factorisation, ``chord > 0``) over
        all Newton attempts.
    residual_times, chord_times
        Wall time of every residual-only evaluation and every chord back-substitution.
    unstable_at
        With ``stop_on_instability``: load of the converged (sub-)step whose tangent was
        judged unstable, where the ramp stopped (``None`` otherwise).
    stopped_at
        Load of the target step after which the ramp's ``stop`` predicate ended it
        (``None`` otherwise); the ramp is ``converged`` (every step it took converged) and
        the targets after it were not attempted.
    failure
        Where a model's driver diagnoses a Newton failure (the 3D plate:
        :func:`~skfem_dielectric.gallery.drivers.run_ramp`), its measured cause, else empty.
    targets
        The loads the caller asked for, set by the drivers whose ramp passes through loads
        of its own (the plate drivers of :mod:`skfem_dielectric.gallery.drivers`: the
        charge targets ``(s, D0_i)``, with the pre-loaded state ``(s, 0)`` for a zero
        ``D0_i``, not the pre-load steps before it); ``None``: every load of the ramp is
        one.  :meth:`column` with ``targets_only=True`` selects their steps.
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
    stopped_at: Any = None
    factorisations: int = 0
    chord_steps: int = 0
    residual_times: list[float] = field(default_factory=list)
    chord_times: list[float] = field(default_factory=list)
    failure: dict[str, Any] = field(default_factory=dict)
    targets: list[Any] | None = None

    def column(self, name: str, *, targets_only: bool = False) -> np.ndarray:
        """Quantity ``name`` over the converged steps, in ramp order.

        Parameters
        ----------
        name
            ``"load"``, ``"iterations"``, ``"factorisations"`` or a post-processed quantity
            of the steps (e.g. ``"lam1"``).
        targets_only
            False: every converged step, the pre-load steps of a driver included (and the
            last, intermediate step of a ramp that stopped).  True: only the steps at
            :attr:`targets` (every reached target load where ``targets`` is ``None``): for
            a plate driver one entry per charge target, e.g. 4 for ``D0=[0, 2, 4, 6]``, to
            compare with a closed form evaluated at those ``D0``.  Fewer entries where the
            ramp stopped before a target (``converged`` False) or was resumed after one.

        Returns
        -------
        ndarray
            One entry per selected step (``"load"``: one row per step).

        Raises
        ------
        ValueError
            If ``name`` is not a quantity of the steps or ``targets_only`` is not a bool.
        """
        if not isinstance(targets_only, (bool, np.bool_)):
            raise ValueError(f"targets_only must be True or False, got {targets_only!r}")
        steps = self.target_steps() if targets_only else self.steps
        if name == "load":
            return np.array([st.load for st in steps], dtype=float)
        if name in ("iterations", "factorisations"):
            return np.array([getattr(st, name) for st in steps], dtype=int)
        known = set().union(*(st.quantities for st in self.steps)) if self.steps else set()
        if name not in known:
            raise ValueError(
                f"name must be 'load', 'iterations', 'factorisations' or a post-processed "
                f"quantity "
                f"{sorted(known)}, got {name!r}")
        return np.array([st.quantities[name] for st in steps])

    def target_steps(self) -> list[StepResult]:
        """The converged steps at :attr:`targets`, in ramp order (each target at most
        once; a load matches to a relative 1e-12), or every step with ``target_reached``
        where ``targets`` is ``None``."""
        reached = [st for st in self.steps if st.target_reached]
        if self.targets is None:
            return reached
        left = [np.atleast_1d(np.asarray(t, dtype=float)) for t in self.targets]
        out = []
        for st in reached:
            load = np.atleast_1d(np.asarray(st.load, dtype=float))
            for i, t in enumerate(left):
                if t.shape == load.shape and np.allclose(load, t, rtol=1e-12, atol=1e-12):
                    out.append(st)
                    del left[i]
                    break
        return out

    @property
    def x(self) -> np.ndarray | None:
        """Reduced solution vector of the last converged step (``None`` if none)."""
        return self.steps[-1].x if self.steps else None


def _as_load(load: Any) -> Any:
    try:
        arr = np.asarray(load, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"loads must be numbers or 1-D arrays, got {load!r}") from None
    if arr.ndim > 1 or not np.all(np.isfinite(arr)):
        raise ValueError(f"loads must be finite, got {load!r}")
    return float(arr) if arr.ndim == 0 else arr.copy()


def _check_back(back: Any, x0: Any, n: int, name: str = "back"
                ) -> tuple[np.ndarray, Any] | None:
    """``back`` (or ``factors``) of :func:`ramp` checked: ``None`` or ``(x, load)`` with
    ``x`` a finite vector of length ``n``; only with ``x0``."""
    if back is None:
        return None
    if x0 is None:
        raise ValueError(f"{name} given without x0 (it is a state of the ramp before x0)")
    if not isinstance(back, (tuple, list)) or len(back) != 2:
        raise ValueError(f"{name} must be a pair (x, load) (StepResult.{name}), "
                         f"got {back!r:.80}")
    return (np.array(check_vector(name, back[0], n), dtype=float), _as_load(back[1]))


def _secant_guess(problem: Problem, x: np.ndarray, at: Any, back: tuple | None,
                  load: Any) -> tuple[np.ndarray, np.ndarray | None]:
    """Start of the Newton solve at ``load`` from the converged ``x`` at load ``at``: the
    secant extrapolation through the converged state ``back = (x_old, load_old)`` when the
    new load increment continues the last one (same direction) and lowers the residual,
    else ``x``; with the residual at the start where it was evaluated (else ``None``)."""
    if back is None:
        return x, None
    d_old = np.atleast_1d(np.asarray(at, float) - np.asarray(back[1], float))
    d_new = np.atleast_1d(np.asarray(load, float) - np.asarray(at, float))
    n_old, n_new = float(np.linalg.norm(d_old)), float(np.linalg.norm(d_new))
    if not (n_old > 0 and n_new > 0) or abs(d_old @ d_new - n_old * n_new) > 1e-9 * n_old * n_new:
        return x, None
    return _lower_residual(problem, x + (n_new / n_old) * (x - back[0]), x, load)


def _lower_residual(problem: Problem, guess: np.ndarray, x: np.ndarray,
                    load: Any) -> tuple[np.ndarray, np.ndarray | None]:
    """``guess`` and its residual at ``load`` where that is lower than the residual of
    ``x``, else ``x`` and its residual (``x`` and ``None`` where either fails)."""
    try:
        r_guess, r_x = problem.residual(guess, load), problem.residual(x, load)
    except (FloatingPointError, ValueError, ZeroDivisionError):
        return x, None
    if np.all(np.isfinite(r_guess)) and np.linalg.norm(r_guess) < np.linalg.norm(r_x):
        return guess, r_guess
    return x, r_x


def _quadratic_guess(problem: Problem, x: np.ndarray, at: Any, back: tuple | None,
                     back2: tuple | None, load: Any) -> tuple[np.ndarray, np.ndarray | None]:
    """Start of the Newton solve at ``load``: the parabola through the converged states
    ``back2``, ``back`` and ``x`` (at ``at``) evaluated at ``load`` (Lagrange
    extrapolation in the distance along the load line) where the three loads lie in order
    on the line of the new increment and the parabola lowers the residual below that of
    ``x``; else :func:`_secant_guess`."""
    if back is None or back2 is None:
        return _secant_guess(problem, x, at, back, load)
    new = np.atleast_1d(np.asarray(load, float))
    d = new - np.atleast_1d(np.asarray(at, float))
    nd = float(np.linalg.norm(d))
    if not nd > 0:
        return _secant_guess(problem, x, at, back, load)
    t = []
    for ld in (back2[1], back[1], at):
        e = np.atleast_1d(np.asarray(ld, float)) - new
        ti = float(e @ d) / nd
        if np.linalg.norm(e - ti * d / nd) > 1e-9 * max(abs(ti), nd):
            return _secant_guess(problem, x, at, back, load)
        t.append(ti)
    t0, t1, t2 = t
    if not t0 < t1 < t2 < 0.0:
        return _secant_guess(problem, x, at, back, load)
    w0 = t1 * t2 / ((t0 - t1) * (t0 - t2))
    w1 = t0 * t2 / ((t1 - t0) * (t1 - t2))
    w2 = t0 * t1 / ((t2 - t0) * (t2 - t1))
    return _lower_residual(problem, w0 * back2[0] + w1 * back[0] + w2 * x, x, load)


@dataclass
class _Approach:
    """The sub-steps from the last converged load ``start`` towards one ``target``: the
    fraction of the interval reached, the sub-step size, the counters that the target's
    :class:`StepResult` keeps, and how it ended (``failed``: the last Newton failure;
    ``unstable``: the load judged unstable under ``stop_on_instability``)."""

    start: np.ndarray
    target: np.ndarray
    fraction: float = 0.0
    step: float = 1.0
    iterations: int = 0
    substeps: int = 0
    cutbacks: int = 0
    factorisations: int = 0
    inertia: tuple[int, int, int] | None = None
    residual_norms: list[list[float]] = field(default_factory=list)
    assembly_seconds: float = 0.0
    solve_seconds: float = 0.0
    failed: str = ""
    unstable: Any = None

    def load_at(self, fraction: float) -> Any:
        """The load at ``fraction`` of the interval (the target itself at 1)."""
        a, b = self.start, self.target
        return _as_load(b if fraction >= 1.0 else a + fraction * (b - a))


class _Ramp:
    """The state of a ramp between two Newton solves.

    The converged state ``x`` at load ``load`` and the one before it (``back``, for the
    secant predictor), whether the linear solver holds the factors of the tangent at ``x``
    (``reuse``: a ``state_analysis`` factorised it), the :class:`RampResult` that collects
    steps and totals, and the :class:`_Approach` to the current target.  Its methods are
    the parts of :func:`ramp`: approach a target by sub-steps, solve one sub-step, keep a
    converged state as a step.
    """

    def __init__(self, problem: Problem, solver, settings: RampSettings, step_limit,
                 admissible, state_analysis, on_step, x: np.ndarray, load: Any) -> None:
        self.problem, self.solver, self.settings = problem, solver, settings
        self.step_limit, self.admissible = step_limit, admissible
        self.state_analysis, self.on_step = state_analysis, on_step
        # a solver that reads only the upper triangle gets it assembled directly
        self.tangent = (problem.assemble_upper if problem.symmetric
                        and getattr(solver, "reads_upper", False) else problem.assemble)
        self.x, self.load = x, load
        self.back = None     # the converged state before x and its load (secant predictor)
        self.back2 = None    # the one before back (quadratic predictor)
        self.solved = False  # x is a solution (not the initial guess of a fresh ramp)
        self.reuse = False   # the next solve starts with chord steps on the factors at hand
        self.factors = None  # (x, load) whose tangent the solver's factors are of
        self.no_verdict_warned = False
        self.out = RampResult(steps=[], converged=True)
        self.approach: _Approach | None = None

    def approach_target(self, target: Any) -> _Approach:
        """Sub-step from ``load`` towards ``target``: a sub-step whose Newton solve fails
        is halved (at most ``max_cutbacks`` times), after a success the sub-step doubles
        (never beyond the target).  Every target starts from the whole interval."""
        ap = self.approach = _Approach(np.asarray(self.load, dtype=float),
                                       np.asarray(target, dtype=float))
        while ap.fraction < 1.0:
            f_new = min(1.0, ap.fraction + ap.step)
            load = ap.load_at(f_new)
            scale = self.problem.residual_scale(load)
            at = ap.load_at(ap.fraction) if ap.fraction > 0 else self.load
            x_start, r_start = self.predict(at, load)
            nr = self.solve(load, x_start, scale, r_start)
            if nr.converged:
                # the secant's second point is a solution: a converged (sub-)step, or the
                # resumed step whose own back was given (not a mere initial guess)
                self.back2 = self.back if self.solved else None
                self.back = (self.x, at) if self.solved else None
                self.solved = True
                self.x = nr.x
                ap.inertia = nr.inertia
                ap.fraction = f_new
                ap.substeps += 1
                ap.residual_norms.append(nr.residual_norms)
                ap.step = min(2.0 * ap.step, 1.0)
                if self.settings.stop_on_instability and self.unstable(load):
                    ap.unstable = load
                    break
            else:
                ap.cutbacks += 1
                if ap.cutbacks > self.settings.max_cutbacks:
                    ap.failed = nr.reason
                    self.out.failed_at = load
                    break
                ap.step *= 0.5
        return ap

    def predict(self, at: Any, load: Any) -> tuple[np.ndarray, np.ndarray | None]:
        """Start of the Newton solve at ``load`` from ``x`` (at ``at``) by the settings'
        predictor, with its residual where the predictor evaluated it."""
        kind = self.settings.predictor
        if kind == "quadratic":
            return _quadratic_guess(self.problem, self.x, at, self.back, self.back2, load)
        if kind == "secant":
            return _secant_guess(self.problem, self.x, at, self.back, load)
        return self.x, None

    def solve(self, load: Any, x_start: np.ndarray, scale: float | None,
              r_start: np.ndarray | None = None) -> NewtonResult:
        """One Newton solve at ``load`` from ``x_start`` (whose residual ``r_start`` the
        predictor may have evaluated already), its counts added to the approach and to
        the ramp's totals."""
        problem, step_limit, admissible = self.problem, self.step_limit, self.admissible

        first = [r_start]

        def residual(xx):
            r0, first[0] = first[0], None
            if r0 is not None and np.array_equal(xx, x_start):  # the predictor's evaluation
                return r0
            return problem.residual(xx, load)

        nr = newton(lambda xx: self.tangent(xx, load), x_start, residual=residual,
                    linear_solver=self.solver, settings=self.settings, scale=scale,
                    step_limit=None if step_limit is None else
                    (lambda xx, dd: step_limit(xx, dd, load)),
                    admissible=None if admissible is None else
                    (lambda xx: admissible(xx, load)),
                    reuse_factors=self.reuse)
        if nr.factorisations:
            self.factors = (nr.factors_at, load)
        # the next solve starts on these factors (a failed solve's are not trusted)
        self.reuse = (self.settings.keep_factors and nr.converged
                      and self.factors is not None)
        ap, out = self.approach, self.out
        ap.iterations += nr.iterations
        ap.factorisations += nr.factorisations
        out.factorisations += nr.factorisations
        out.chord_steps += nr.chord_steps
        out.residual_times.extend(nr.residual_seconds)
        out.chord_times.extend(nr.chord_seconds)
        ap.assembly_seconds += sum(nr.assembly_seconds)
        ap.solve_seconds += sum(nr.solve_seconds)
        out.iterations_total += nr.iterations
        out.assembly_calls += len(nr.assembly_seconds)
        out.assembly_seconds += sum(nr.assembly_seconds)
        out.solve_seconds += sum(nr.solve_seconds)
        out.assembly_times.extend(nr.assembly_seconds)
        out.solve_times.extend(nr.solve_seconds)
        return nr

    def unstable(self, load: Any) -> bool:
        """Whether the converged state at ``load`` is judged unstable by the inertia of
        its last tangent (warns once when the solver gives no verdict)."""
        verdict = self.problem.stability(self.approach.inertia)
        if verdict is None and not self.no_verdict_warned:
            self.no_verdict_warned = True
            warnings.warn("stop_on_instability has no effect: the linear solver "
                          "reports no inertia, so there is no stability verdict "
                          "(use linear_solver='pardiso')", RuntimeWarning, stacklevel=4)
        return verdict is False

    def prime(self, factors: tuple[np.ndarray, Any] | None = None) -> None:
        """Factorise the tangent the uninterrupted ramp held at the resumed step, so
        that the resumed ramp starts with the same chord steps on the same factors: that
        at ``factors = (x, load)`` (``StepResult.factors``, with ``keep_factors``), or
        that of the starting state, which :meth:`analyse` factorised (a
        ``state_analysis``)."""
        if factors is None:
            x, load = self.x, self.load
            K, _ = self.problem.assemble(x, load)
        else:
            x, load = factors
            K, _ = self.tangent(x, load)
        try:
            self.solver.solve(K, np.zeros(K.shape[0]))
        except Exception:   # a singular tangent: the first sub-step factorises its own
            return
        self.out.factorisations += 1
        self.factors = (x, load)
        self.reuse = True

    def analyse(self, load: Any) -> tuple[dict, tuple[int, int, int] | None]:
        """``state_analysis`` of the converged ``x``: its tangent factorised by the ramp's
        solver (counted with the step); returns ``(quantities, inertia)``."""
        ap, solver = self.approach, self.solver
        if callable(getattr(solver, "discard", None)):
            solver.discard()        # the old factors: not held beside the new tangent
        t = time.perf_counter()
        K, _ = self.problem.assemble(self.x, load)
        ap.assembly_seconds += time.perf_counter() - t
        t = time.perf_counter()
        try:
            solver.solve(K, np.zeros(K.shape[0]))
        except Exception as exc:  # a singular tangent: an exactly critical state
            self.reuse = False
            return {"state_analysis_error": f"factorisation failed: {exc}"}, None
        ap.solve_seconds += time.perf_counter() - t
        ap.factorisations += 1
        self.out.factorisations += 1
        self.reuse = True
        self.factors = (self.x, load)
        return (dict(self.state_analysis(self.problem, self.x, load, K, solver)),
                solver.factor_inertia())

    def record(self, load: Any, target_reached: bool) -> None:
        """Keep the converged state ``x`` at ``load`` as a step (post-processed, with the
        stability verdict of its last tangent) and report it to ``on_step``."""
        ap = self.approach
        extra = {}
        if self.state_analysis is not None:
            extra, ap.inertia = self.analyse(load)
        step = StepResult(load=load, converged=True, iterations=ap.iterations,
                          substeps=ap.substeps, cutbacks=ap.cutbacks,
                          residual_norms=ap.residual_norms, x=self.x.copy(),
                          assembly_seconds=ap.assembly_seconds,
                          solve_seconds=ap.solve_seconds, inertia=ap.inertia,
                          target_reached=target_reached, factorisations=ap.factorisations,
                          back=self.back, back2=self.back2,
                          factors=self.factors if self.settings.keep_factors else None)
        step.quantities = dict(self.problem.postprocess(self.x, load))
        step.quantities.update(extra)
        step.quantities.setdefault("stable", self.problem.stability(ap.inertia))
        self.out.steps.append(step)
        if self.on_step is not None:
            self.on_step(step)


#: The callbacks :func:`ramp` accepts, each callable or ``None``.
CALLBACKS = ("on_step", "stop", "step_limit", "admissible", "state_analysis")


def check_callbacks(options: dict[str, Any]) -> None:
    """``ValueError`` naming the first of :func:`ramp`'s callbacks (:data:`CALLBACKS`) in
    ``options`` that is neither callable nor ``None``; other keys are ignored.  A driver
    calls it on its ramp options before it builds its problem."""
    for name in CALLBACKS:
        check_callable(name, options.get(name))


def ramp(problem: Problem, loads: Sequence[Any], *, x0: np.ndarray | None = None,
         start: Any = None, back: tuple[np.ndarray, Any] | None = None,
         back2: tuple[np.ndarray, Any] | None = None,
         factors: tuple[np.ndarray, Any] | None = None,
         on_step: Callable[[StepResult], Any] | None = None,
         stop: Callable[[StepResult], bool] | None = None,
         linear_solver: str | LinearSolver = "superlu",
         settings: RampSettings = RampSettings(),
         step_limit: Callable[[np.ndarray, np.ndarray, Any], float] | None = None,
         admissible: Callable[[np.ndarray, Any], str] | None = None,
         state_analysis: Callable[..., dict] | None = None) -> RampResult:
    """Run ``problem`` through the target ``loads`` with adaptive sub-stepping.

    Parameters
    ----------
    problem
        A :class:`~skfem_dielectric.problem.Problem`.
    loads
        Target loads in order (floats or equal-length 1-D arrays); each is reached and
        post-processed.  Loads must be finite.
    x0, start
        State to start from: the reduced vector and its load.  Default:
        ``problem.initial_state()`` at zero load.  To resume a ramp pass ``x0=step.x``,
        ``start=step.load``, ``back=step.back`` and ``back2=step.back2`` of a saved
        :class:`StepResult` and the
        remaining loads.
    back
        The converged state before ``x0`` and its load, ``(x, load)``: the second point of
        the secant predictor (``StepResult.back``).  Without it ``x0`` (or the initial
        state) is taken as a guess, not as a solution: the secant starts from the second
        converged sub-step, and a resumed ramp repeats the uninterrupted one only within
        the Newton tolerance.
    back2
        The converged state before ``back`` (``StepResult.back2``): the third point of the
        quadratic predictor; without it the first resumed step starts from the secant.
    factors
        With ``settings.keep_factors``: the state whose tangent the uninterrupted ramp
        held factorised after ``x0``, ``(x, load)`` (``StepResult.factors``); it is
        factorised first so that the resumed ramp repeats the uninterrupted one bit for
        bit.  Without it a resumed ramp with ``keep_factors`` and no ``state_analysis``
        factorises afresh and repeats the uninterrupted one within the Newton tolerance.
    on_step
        Called as ``on_step(step)`` after every converged target.
    stop
        Optional predicate ``stop(step) -> bool``, asked after ``on_step`` at every
        converged target: ``True`` ends the ramp there (``stopped_at``), a result rather
        than an exception; the targets after it are not attempted.
    linear_solver
        Name or instance (see :func:`skfem_dielectric.linalg.linear.get_linear_solver`; a name
        gives a non-symmetric solver for a problem whose ``symmetric`` is False); one
        instance is used for the whole ramp.  A solver that ``reads_upper`` (the symmetric
        PARDISO) gets the tangents of the Newton iterations from
        :meth:`~skfem_dielectric.problem.Problem.assemble_upper`.
    settings
        Newton tolerances and limits, cut-backs, predictor and ``stop_on_instability``
        (:class:`RampSettings`).  A step judged unstable under ``stop_on_instability`` is
        kept (``target_reached`` False if it is intermediate) and its load is
        ``unstable_at``.
    step_limit, admissible
        Optional ``step_limit(x, dx, load) -> alpha_max`` and ``admissible(x, load) ->
        reason`` of the admissible states (see the module docstring and :func:`newton`);
        a sub-step that converges to a state ``admissible`` rejects is cut back.  Default:
        the problem's own (:meth:`~skfem_dielectric.problem.Problem.newton_guards`).
    state_analysis
        Optional ``state_analysis(problem, x, load, K, solver) -> dict``, called for every kept
        step with the tangent ``K`` of the converged state, which ``solver`` has just
        factorised (e.g. :class:`~skfem_dielectric.stability.monitor.StabilityMonitor`: the
        negative-eigenvalue count from the factors, the lowest modes by
        back-substitutions); the dict is added to the step's ``quantities``,
        ``StepResult.inertia`` is that of the converged state's tangent where the factors
        show it, and the next load step starts with a chord step on these factors
        (``reuse_factors`` of :func:`newton`), so that the factorisation is not wasted.

    Returns
    -------
    RampResult
        Never raises on non-convergence; warns (``RuntimeWarning``) when it stops early.

    Raises
    ------
    ValueError
        Invalid arguments, each named: ``problem`` not a ``Problem``, non-finite loads,
        ``x0`` not a finite vector of the problem's length, ``back`` not a pair of such a
        vector and a load (or given without ``x0``), a callable that is not,
        ``settings`` not a :class:`RampSettings`.
    """
    if not isinstance(problem, Problem):
        raise ValueError("problem must be a skfem_dielectric.Problem (see "
                         f"skfem_dielectric.problem), got {type(problem).__name__}")
    check_callbacks({"on_step": on_step, "stop": stop, "step_limit": step_limit,
                     "admissible": admissible, "state_analysis": state_analysis})
    guards = problem.newton_guards()
    step_limit = guards.get("step_limit") if step_limit is None else step_limit
    admissible = guards.get("admissible") if admissible is None else admissible
    check_settings("settings", settings, RampSettings)
    t_start = time.perf_counter()
    solver = get_linear_solver(linear_solver, symmetric=problem.symmetric,
                               precision=("double" if state_analysis is not None
                                          else settings.factor_precision))
    try:
        loads = list(loads)
    except TypeError:
        raise ValueError(f"loads must be a sequence of loads, got {loads!r}") from None
    targets = [_as_load(ld) for ld in loads]
    x_init = problem.initial_state()
    x = np.array(x_init if x0 is None else check_vector("x0", x0, len(x_init)),
                 dtype=float, copy=True)
    if start is None:
        start = 0.0 * np.asarray(targets[0], dtype=float) if targets else 0.0
    run = _Ramp(problem, solver, settings, step_limit, admissible, state_analysis, on_step,
                x, _as_load(start))
    run.back = _check_back(back, x0, len(x_init))
    run.back2 = None if run.back is None else _check_back(back2, x0, len(x_init), "back2")
    run.solved = run.back is not None
    factors = _check_back(factors, x0, len(x_init), "factors")
    if targets and factors is not None and settings.keep_factors:
        run.prime(factors)
    elif x0 is not None and state_analysis is not None and targets:
        run.prime()
    out = run.out
    for target in targets:
        ap = run.approach_target(target)
        if ap.unstable is not None:
            run.record(ap.unstable, ap.fraction >= 1.0)
            out.converged = False
            out.unstable_at = ap.unstable
            out.reason = (f"stability lost at load {ap.unstable!r} (inertia of the tangent: "
                          f"{ap.inertia}); stopped on request (stop_on_instability)")
            warnings.warn(out.reason, RuntimeWarning, stacklevel=2)
            break
        if ap.failed:
            if ap.fraction > 0.0:   # keep the furthest converged sub-step towards the target
                run.record(ap.load_at(ap.fraction), False)
            out.converged = False
            out.reason = (f"target load {target!r} not reached after "
                          f"{settings.max_cutbacks} cut-backs; last Newton failure: "
                          f"{ap.failed}")
            warnings.warn(out.reason, RuntimeWarning, stacklevel=2)
            break
        run.load = target
        run.record(target, True)
        if stop is not None and stop(out.steps[-1]):
            out.stopped_at = target
            break
    out.wall_seconds = time.perf_counter() - t_start
    return out

"""Pseudo-arclength continuation for any :class:`~skfem_dielectric.problem.Problem`.

A load ramp (:func:`~skfem_dielectric.solvers.ramp.ramp`) prescribes the load and so stops where
the load reaches a maximum along the equilibrium path: under voltage control that is the
maximum of ``E0`` at fixed ``s`` (the paper's snap-through, Sec. 3.1, ``det H* = 0``).
Continuation makes the load parameter ``t`` an unknown, ``load(t) = load0 + t direction``
(or a user path), and adds Keller's pseudo-arclength condition

    g(x, t) = tau_x . W (x - x_k) + tau_t (t - t_k) - ds = 0,

``(tau_x, tau_t)`` the unit tangent of the path at the last converged point ``(x_k, t_k)``
in the metric ``W`` (diagonal, ``1/n_d`` on the ``n_d`` displacement-like unknowns, zero on
the multipliers ``p``, ``phi``).  The bordered tangent

    [[K, r_t], [tau_x^T W, tau_t]],    r_t = load_vector(x, load) . dload/dt,

is regular at a limit point (``K`` singular, ``r_t`` outside its range), so Newton's method
passes it.  The tangent at a converged point solves the same bordered system with right
side ``(0, 1)``: its orientation then agrees with the previous tangent (``tau_old . W
tau_new > 0``), which is the direction choice at a limit point -- the path goes on, the
load parameter turns back.

Events between consecutive points:

limit point
    ``tau_t`` (the load-parameter derivative along the path) changes sign.  It is located
    by Illinois regula falsi on ``tau_t`` as a function of the arclength from the last
    point before it (each evaluation a corrector and a tangent solve), to ``|tau_t| <=
    locate_tol``, and inserted as a point of kind ``"limit"``.
bifurcation
    the negative-eigenvalue count of the reduced stiffness
    (:func:`~skfem_dielectric.stability.analysis.tangent_stability`) changes without a sign change
    of ``tau_t``: an eigenvalue crosses zero with the load still monotone (a branch point).

How the path is stepped -- the arclength steps, the predictor, the step control, the
location of limit points and the correctors' Newton settings -- is one
:class:`ContinuationSettings` (``settings=``); the path itself and where it ends (``t_max``,
``t_min``, ``stop``) are arguments of :func:`continuation`.

Failure is data: a corrector that does not converge halves the step (``max_cutbacks``
times); the continuation then stops with ``converged=False`` and a ``reason`` and keeps
every converged point.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
import scipy.sparse as sp

from ..checks import (check_callable, check_choice, check_count, check_nonnegative_int,
                      check_positive)
from ..linalg.linear import nonsymmetric_solver
from ..linalg.solver_base import LinearSolver
from ..problem import Problem
from ..stability.analysis import metric_matrix, tangent_stability
from .newton import NewtonSettings, check_settings, newton

__all__ = ["ContinuationSettings", "ContinuationPoint", "ContinuationEvent",
           "ContinuationResult", "continuation"]

PREDICTORS = ("secant", "tangent")


def _check_bool(name: str, value: Any) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be True or False, got {value!r}")
    return bool(value)


@dataclass(frozen=True)
class ContinuationSettings:
    """How :func:`continuation` steps along the path: arclength steps, predictor, step
    control, location of limit points and the correctors' Newton settings.

    The step control of Keller's pseudo-arclength method (module docstring) as one frozen
    object, checked once where it is made, like
    :class:`~skfem_dielectric.solvers.newton.NewtonSettings` and
    :class:`~skfem_dielectric.solvers.ramp.RampSettings`; the path and its stop criteria
    stay arguments of :func:`continuation`.  Change one field with
    :func:`dataclasses.replace`, e.g. ``replace(ContinuationSettings(), ds=0.1)``.

    Attributes
    ----------
    ds
        Initial arclength step, ``> 0``.
    ds_min, ds_max
        Smallest and largest arclength step, ``> 0``; ``None`` stands for ``ds * 1e-4`` and
        ``ds * 8`` (read through :attr:`step_bounds`, so that a ``replace`` of ``ds``
        scales them).
    max_steps
        Steps before the continuation stops, ``>= 1``.
    predictor
        ``"secant"`` (through the last two points; the tangent on the first step) or
        ``"tangent"``.
    increase
        Initial direction: ``t`` increasing (True) or decreasing.
    target_iterations
        The step is scaled by ``sqrt(target_iterations / iterations)`` (within ``[1/2,
        2]``) after each success, ``>= 1``.
    max_cutbacks
        Halvings of one step (after a failed corrector, or a tangent turning by more than
        ``max_angle``) before the continuation stops, ``>= 0``.
    max_angle
        A step whose tangent turns by more than this angle (radians, ``> 0``) is halved.
    locate, locate_tol
        Locate limit points by regula falsi to ``|tau_t| <= locate_tol`` (``> 0``).
    corrector
        Newton settings of the correctors and of the start
        (:class:`~skfem_dielectric.solvers.newton.NewtonSettings`, default 15 iterations);
        ``rtol`` is relative to ``problem.residual_scale``.

    Raises
    ------
    ValueError
        A field out of its range, naming the field and the value.
    """

    ds: float = 0.05
    ds_min: float | None = None
    ds_max: float | None = None
    max_steps: int = 200
    predictor: str = "secant"
    increase: bool = True
    target_iterations: int = 4
    max_cutbacks: int = 10
    max_angle: float = 0.5
    locate: bool = True
    locate_tol: float = 1e-9
    corrector: NewtonSettings = NewtonSettings(max_iter=15)

    def __post_init__(self) -> None:
        check_choice("predictor", self.predictor, PREDICTORS)
        check_settings("corrector", self.corrector, NewtonSettings)
        checked = dict(
            ds=check_positive("ds", self.ds),
            ds_min=None if self.ds_min is None else check_positive("ds_min", self.ds_min),
            ds_max=None if self.ds_max is None else check_positive("ds_max", self.ds_max),
            max_steps=check_count("max_steps", self.max_steps),
            increase=_check_bool("increase", self.increase),
            target_iterations=check_count("target_iterations", self.target_iterations),
            max_cutbacks=check_nonnegative_int("max_cutbacks", self.max_cutbacks),
            max_angle=check_positive("max_angle", self.max_angle),
            locate=_check_bool("locate", self.locate),
            locate_tol=check_positive("locate_tol", self.locate_tol))
        for name, value in checked.items():     # the checked values, as the solver uses them
            object.__setattr__(self, name, value)

    @property
    def step_bounds(self) -> tuple[float, float]:
        """``(ds_min, ds_max)`` with the defaults ``ds * 1e-4`` and ``ds * 8`` filled in."""
        return (self.ds * 1e-4 if self.ds_min is None else self.ds_min,
                self.ds * 8.0 if self.ds_max is None else self.ds_max)


@dataclass
class ContinuationPoint:
    """One converged equilibrium of a continuation.

    Attributes
    ----------
    t, load
        Load parameter and the load ``load(t)``.
    x
        Reduced state.
    tangent_t
        ``dt/ds`` of the unit path tangent (its sign is the direction of the load).
    arclength
        Arclength from the start (metric of the module docstring).
    iterations
        Newton iterations of the corrector (0 for the start).
    ds
        Step length that reached this point.
    n_negative
        Negative eigenvalues of the reduced stiffness (``None`` without a stability count).
    kind
        ``"start"``, ``"regular"`` or ``"limit"`` (a located limit point).
    quantities
        ``problem.postprocess(x, load)`` plus ``stable`` (``n_negative == 0``, or ``None``).
    """

    t: float
    load: Any
    x: np.ndarray
    tangent_t: float
    arclength: float
    iterations: int
    ds: float
    n_negative: int | None
    kind: str = "regular"
    quantities: dict[str, Any] = field(default_factory=dict)

    def __getitem__(self, key: str) -> Any:
        return self.quantities[key]

    @property
    def stable(self) -> bool | None:
        """``n_negative == 0`` (``None`` without a count)."""
        return None if self.n_negative is None else self.n_negative == 0


@dataclass
class ContinuationEvent:
    """A limit point or bifurcation found between two consecutive points.

    Attributes
    ----------
    kind
        ``"limit"`` or ``"bifurcation"``.
    index
        Index in ``ContinuationResult.points`` of the located limit point, or of the first
        point after a bifurcation.
    t
        Load parameter of the located limit point, or of the point after the bifurcation.
    n_negative_before, n_negative_after
        Counts of the points that bracket the event.
    located
        Whether the limit point was located to ``locate_tol`` (always False for a
        bifurcation, which is only bracketed).
    """

    kind: str
    index: int
    t: float
    n_negative_before: int | None
    n_negative_after: int | None
    located: bool = False


@dataclass
class ContinuationResult:
    """Outcome of :func:`continuation`.

    Attributes
    ----------
    points
        Every converged point in path order (the start first, located limit points
        inserted where they lie).
    events
        Limit points and bifurcations, in path order.
    converged
        True if the continuation ended by a stop criterion (``t_max``, ``t_min``,
        ``max_steps``, ``stop``), False if a corrector failed at the smallest step.
    reason
        Why it ended.
    wall_seconds, iterations_total
        Wall time and Newton iterations over all correctors (failed ones included).
    problem
        The problem that was continued.
    """

    points: list[ContinuationPoint]
    events: list[ContinuationEvent] = field(default_factory=list)
    converged: bool = True
    reason: str = ""
    wall_seconds: float = 0.0
    iterations_total: int = 0
    problem: Any = None

    @property
    def limit_points(self) -> list[ContinuationPoint]:
        """The located limit points, in path order."""
        return [self.points[e.index] for e in self.events if e.kind == "limit"]

    def column(self, name: str) -> np.ndarray:
        """Array over the points of ``"t"``, ``"arclength"``, ``"tangent_t"``,
        ``"n_negative"`` (``-1`` for none), ``"iterations"``, ``"load"`` or a
        post-processed quantity."""
        attrs = ("t", "arclength", "tangent_t", "iterations", "load")
        if name in attrs:
            return np.array([getattr(p, name) for p in self.points], dtype=float)
        if name == "n_negative":
            return np.array([-1 if p.n_negative is None else p.n_negative
                             for p in self.points], dtype=int)
        known = set().union(*(p.quantities for p in self.points)) if self.points else set()
        if name not in known:
            raise ValueError(f"name must be one of {attrs + ('n_negative',)} or a "
                             f"post-processed quantity {sorted(known)}, got {name!r}")
        return np.array([p.quantities[name] for p in self.points])


class _Path:
    """The load path ``t -> load`` and its derivative, with the augmented system."""

    def __init__(self, problem, load0, direction, path, weight, n_load):
        self.problem, self.path, self.load0, self.direction = problem, path, load0, direction
        self.w, self.n_load = weight, n_load
        self.scalar = path is None and np.ndim(load0) == 0

    def load(self, t: float):
        if self.path is not None:
            return self.path(t)
        ld = self.load0 + t * self.direction
        return float(ld) if self.scalar else ld

    def dload(self, t: float) -> np.ndarray:
        if self.path is None:
            return np.atleast_1d(np.asarray(self.direction, dtype=float))
        h = 1e-6 * (1.0 + abs(t))
        return (np.atleast_1d(np.asarray(self.path(t + h), dtype=float))
                - np.atleast_1d(np.asarray(self.path(t - h), dtype=float))) / (2.0 * h)

    def r_t(self, x: np.ndarray, t: float) -> np.ndarray:
        """``d r / d t = load_vector . dload/dt``."""
        n = self.problem.ndofs
        q = np.asarray(self.problem.load_vector(x, self.load(t)), dtype=float)
        q = q.reshape(n, -1) if q.size == n * self.n_load else q
        if q.shape != (n, self.n_load):
            raise ValueError(f"load_vector of {type(self.problem).__name__} must have shape "
                             f"({n}, {self.n_load}), got {q.shape}")
        return q @ self.dload(t)

    def bordered(self, x, t, row_x, row_t):
        """``(K, r, [[K, r_t], [row_x, row_t]])`` at ``(x, t)``."""
        K, r = self.problem.assemble(x, self.load(t))
        A = sp.bmat([[sp.csr_matrix(K), sp.csr_matrix(self.r_t(x, t)[:, None])],
                     [sp.csr_matrix(row_x[None, :]), sp.csr_matrix([[row_t]])]], format="csr")
        return K, r, A

    def unit(self, tau_x, tau_t):
        nrm = math.sqrt(float(np.dot(self.w * tau_x, tau_x)) + tau_t * tau_t)
        return tau_x / nrm, tau_t / nrm


def _check_inputs(problem, load0, direction, path):
    if not isinstance(problem, Problem):
        raise ValueError("problem must be a skfem_dielectric.Problem (layout, initial_state, "
                         f"assemble, load_vector), got {type(problem).__name__}")
    check_callable("path", path)
    if path is None:
        if load0 is None or direction is None:
            raise ValueError("give load0 and direction (load(t) = load0 + t direction) "
                             f"or a path, got load0={load0!r}, direction={direction!r}")
        a0 = np.asarray(load0, dtype=float)
        d = np.asarray(direction, dtype=float)
        if a0.ndim > 1 or d.shape != a0.shape or not np.all(np.isfinite(d)) \
                or not np.all(np.isfinite(a0)) or not np.any(d):
            raise ValueError(f"direction must be a finite, non-zero load of the shape of "
                             f"load0 {a0.shape}, got {direction!r}")
        return (float(a0) if a0.ndim == 0 else a0), (float(d) if d.ndim == 0 else d)
    return load0, direction


class _Continuation:
    """The state of a continuation between two points.

    The load path (:class:`_Path`), the solver of the bordered systems, the corrector's
    Newton settings and the model's guards lifted to the augmented unknowns ``z = (x,
    t)``, the step control, and the :class:`ContinuationResult` that collects the points.
    Its methods are the parts of :func:`continuation`: correct the start, make a point,
    correct a predicted point onto the arclength hyperplane, take one step with
    cut-backs, locate a limit point.
    """

    def __init__(self, problem: Problem, path: _Path, solver, corrector: NewtonSettings,
                 count, step_limit, admissible, *, max_cutbacks: int, ds_min: float,
                 max_angle: float, locate_tol: float) -> None:
        self.problem, self.P, self.solver, self.corrector = problem, path, solver, corrector
        self.count, self.step_limit, self.admissible = count, step_limit, admissible
        self.max_cutbacks, self.ds_min = max_cutbacks, ds_min
        self.max_angle, self.locate_tol = max_angle, locate_tol
        self.guards = {}    # the model's guards on the state part of the augmented unknowns
        if step_limit is not None:
            self.guards["step_limit"] = lambda z, dz: step_limit(z[:-1], dz[:-1],
                                                                 path.load(z[-1]))
        if admissible is not None:
            self.guards["admissible"] = lambda z: admissible(z[:-1], path.load(z[-1]))
        self.out = ContinuationResult(points=[], problem=problem)

    def count_negative(self, x: np.ndarray, t: float, K) -> int | None:
        """Negative eigenvalues of the reduced stiffness at ``(x, t)`` (``None`` without
        a count, or at a singular tangent)."""
        count, problem = self.count, self.problem
        if count is False or (count is True and not problem.symmetric):
            return None
        if callable(count):
            return int(count(x, self.P.load(t)))
        try:
            return int(tangent_stability(problem, K).n_negative)
        except (ValueError, RuntimeError):     # a singular tangent (at a limit point)
            return None

    def point(self, x, t, tau, iterations, step, arc, kind, K) -> ContinuationPoint:
        """The converged ``(x, t)`` with unit tangent ``tau`` as a post-processed point."""
        load = self.P.load(t)
        p = ContinuationPoint(t=float(t), load=load, x=x.copy(), tangent_t=float(tau[1]),
                              arclength=float(arc), iterations=iterations, ds=float(step),
                              n_negative=self.count_negative(x, t, K), kind=kind)
        p.quantities = dict(self.problem.postprocess(x, load))
        p.quantities.setdefault("stable", p.stable)
        return p

    def start(self, x: np.ndarray, t0: float, increase: bool) -> tuple | None:
        """Correct ``x`` at the fixed load ``load(t0)`` and add the start point; returns
        its unit tangent (oriented by ``increase``), or ``None`` with the reason set."""
        problem, P, step_limit, admissible = self.problem, self.P, self.step_limit, \
            self.admissible
        ld = P.load(float(t0))
        nr = newton(lambda xx: problem.assemble(xx, ld), x,
                    residual=lambda xx: problem.residual(xx, ld),
                    scale=problem.residual_scale(ld), linear_solver=self.solver,
                    settings=self.corrector,
                    step_limit=None if step_limit is None else
                    (lambda a, b: step_limit(a, b, ld)),
                    admissible=None if admissible is None else (lambda a: admissible(a, ld)))
        self.out.iterations_total += nr.iterations
        if not nr.converged:
            self.out.converged, self.out.reason = False, f"start not converged: {nr.reason}"
            return None
        x, t = nr.x, float(t0)
        K, _ = problem.assemble(x, ld)
        tx = self.solver.solve(sp.csr_matrix(K), -P.r_t(x, t))
        tau = P.unit(tx, 1.0) if increase else P.unit(-tx, -1.0)
        self.out.points.append(self.point(x, t, tau, 0, 0.0, 0.0, "start", K))
        return tau

    def correct(self, xa, ta, taua, pred_x, pred_t, h):
        """Corrector on the hyperplane ``taua . W (z - z_a) = h`` from ``(pred_x, pred_t)``;
        returns ``(x, t, tau, iterations, K)`` or ``None`` and the reason."""
        problem, P = self.problem, self.P
        rx, rt_ = P.w * taua[0], taua[1]

        def g(z):
            return float(np.dot(rx, z[:-1] - xa) + rt_ * (z[-1] - ta) - h)

        def aug(z):
            _, r, A = P.bordered(z[:-1], z[-1], rx, rt_)
            return A, np.append(r, g(z))

        def aug_res(z):
            return np.append(problem.residual(z[:-1], P.load(z[-1])), g(z))

        res = newton(aug, np.append(pred_x, pred_t), residual=aug_res,
                     scale=problem.residual_scale(P.load(pred_t)), linear_solver=self.solver,
                     settings=self.corrector, **self.guards)
        self.out.iterations_total += res.iterations
        if not res.converged:
            return None, res.reason
        xx, tt = res.x[:-1], float(res.x[-1])
        K_, _, A = P.bordered(xx, tt, rx, rt_)
        sol = self.solver.solve(A, np.append(np.zeros(problem.ndofs), 1.0))
        new = P.unit(sol[:-1], float(sol[-1]))
        return (xx, tt, new, res.iterations, K_), ""

    def advance(self, a: ContinuationPoint, tau, secant, h: float):
        """One step of length ``h`` from point ``a`` (tangent ``tau``; ``secant`` the
        unit secant through the last two points with the secant predictor, else
        ``None``), halved while the corrector
        fails or the tangent turns by more than ``max_angle``; returns ``(solution, h,
        cut-backs, reason)``, the solution ``None`` if the smallest step failed."""
        cuts, sol, why = 0, None, ""
        while True:
            sx, st = tau if secant is None else secant
            sol, why = self.correct(a.x, a.t, tau, a.x + h * sx, a.t + h * st, h)
            if sol is not None:
                cosang = float(np.dot(self.P.w * tau[0], sol[2][0]) + tau[1] * sol[2][1])
                if cosang >= math.cos(self.max_angle):
                    return sol, h, cuts, why
                why = f"the tangent turned by {math.acos(min(1.0, cosang)):.3g} rad"
                sol = None
            cuts += 1
            if cuts > self.max_cutbacks or h * 0.5 < self.ds_min:
                return sol, h, cuts, why
            h *= 0.5

    def locate_limit(self, a: ContinuationPoint, taua, b: ContinuationPoint):
        """Regula falsi on ``tau_t`` over the arclength from point ``a`` to ``b``, with the
        Illinois halving of the retained end.  It differs from
        :func:`~skfem_dielectric.solvers.critical.illinois` in what it stops on (the value
        ``|tau_t| <= locate_tol``; a failed corrector ends it with the last converged
        point) and in how it rounds (the secant point as ``(lo fhi - hi flo) / (fhi -
        flo)``): with ``illinois`` the located limit points differ in their last bits."""
        P = self.P
        lo, flo = 0.0, taua[1]
        hi = float(np.dot(P.w * taua[0], b.x - a.x) + taua[1] * (b.t - a.t))
        fhi, side, best = b.tangent_t, 0, None
        for _ in range(60):
            h = (lo * fhi - hi * flo) / (fhi - flo)
            sol, _ = self.correct(a.x, a.t, taua, a.x + h * taua[0], a.t + h * taua[1], h)
            if sol is None:
                return best
            best = (sol, h)
            f = sol[2][1]
            if abs(f) <= self.locate_tol or abs(hi - lo) <= 1e-15 * (1.0 + abs(hi)):
                return best
            if (f > 0) == (flo > 0):
                lo, flo = h, f
                fhi = fhi / 2 if side == -1 else fhi
                side = -1
            else:
                hi, fhi = h, f
                flo = flo / 2 if side == 1 else flo
                side = 1
        return best


def continuation(problem: Problem, load0: Any = None, direction: Any = None, *,
                 path: Callable[[float], Any] | None = None, x0: np.ndarray | None = None,
                 t0: float = 0.0, t_max: float | None = None, t_min: float | None = None,
                 stop: Callable[[ContinuationPoint], bool] | None = None,
                 settings: ContinuationSettings = ContinuationSettings(),
                 count: bool | Callable = True,
                 linear_solver: str | LinearSolver = "superlu",
                 step_limit: Callable | None = None,
                 admissible: Callable | None = None) -> ContinuationResult:
    """Follow the equilibrium path of ``problem`` through limit points.

    Parameters
    ----------
    problem
        A :class:`~skfem_dielectric.problem.Problem` (its ``load_vector`` gives ``dr/dload``).
    load0, direction
        The load path ``load(t) = load0 + t direction`` (floats or equal-length arrays,
        e.g. ``(s, 0)`` and ``(0, 1)``: ``t`` is then ``E0`` at fixed ``s``).
    path
        Instead of ``load0, direction``: a callable ``t -> load`` (differentiated by
        central differences).
    x0, t0
        Start: a state near equilibrium at ``load(t0)`` (default ``problem.initial_state()``);
        it is corrected at fixed load first.
    t_max, t_min, stop
        Stop when ``t`` leaves ``[t_min, t_max]`` (that point is kept), or when
        ``stop(point)`` is true (besides after ``settings.max_steps`` steps).
    settings
        How the path is stepped (:class:`ContinuationSettings`: arclength steps, predictor,
        step control, location of limit points, the correctors' Newton settings).
    count
        Count the negative eigenvalues of the reduced stiffness at every point (True, for
        a symmetric tangent: :func:`~skfem_dielectric.stability.analysis.tangent_stability`), or a
        callable ``count(x, load) -> int`` (e.g. on a stabilised tangent), or False.
    linear_solver
        Solver for the (non-symmetric) bordered system.
    step_limit, admissible
        Default: the problem's own (:meth:`~skfem_dielectric.problem.Problem.newton_guards`).
        ``step_limit(x, dx, load)`` and ``admissible(x, load)`` of the admissible states, as
        in :func:`~skfem_dielectric.solvers.ramp.ramp`.

    Returns
    -------
    ContinuationResult
        Never raises on non-convergence; warns (``RuntimeWarning``) when a corrector fails
        at the smallest step.

    Raises
    ------
    ValueError
        ``problem`` not a ``Problem``; neither ``load0, direction`` nor ``path``; a zero or
        mis-shaped ``direction``; a ``load_vector`` of the wrong shape; ``x0`` of the wrong
        length; ``settings`` not a ``ContinuationSettings``; ``stop``, ``step_limit``,
        ``admissible`` not callable, ``count`` neither a bool nor callable.

    Examples
    --------
    The load of the scalar problem ``r = x^3 - 3 x - t`` has a maximum ``t = 2`` at ``x =
    -1``; a load ramp stops there, the continuation passes it and locates it:

    >>> import numpy as np, scipy.sparse as sp
    >>> from skfem_dielectric.problem import Layout, Problem
    >>> class Cubic(Problem):
    ...     layout = Layout.single(1)
    ...     def initial_state(self):        # near the root x = -sqrt(3) of t = 0
    ...         return np.array([-1.8])
    ...     def assemble(self, x, load):
    ...         K = sp.csr_matrix([[3 * x[0] ** 2 - 3]])
    ...         return K, np.array([x[0] ** 3 - 3 * x[0] - float(load)])
    >>> res = continuation(Cubic(), 0.0, 1.0, t_max=3.0, count=False,
    ...                    settings=ContinuationSettings(ds=0.2))
    >>> round(res.limit_points[0].t, 8), round(float(res.limit_points[0].x[0]), 4)
    (2.0, -1.0)
    """
    load0, direction = _check_inputs(problem, load0, direction, path)
    check_settings("settings", settings, ContinuationSettings)
    ds, (ds_min, ds_max) = settings.ds, settings.step_bounds
    predictor, max_steps = settings.predictor, settings.max_steps
    target_iterations = settings.target_iterations
    for name, f in (("stop", stop), ("step_limit", step_limit), ("admissible", admissible)):
        check_callable(name, f)
    guards = problem.newton_guards()
    step_limit = guards.get("step_limit") if step_limit is None else step_limit
    admissible = guards.get("admissible") if admissible is None else admissible
    if not (isinstance(count, bool) or callable(count)):
        raise ValueError(f"count must be True, False or a callable count(x, load), got "
                         f"{count!r}")
    t_start = time.perf_counter()
    n = problem.ndofs
    x = problem.initial_state() if x0 is None else np.asarray(x0, dtype=float)
    if x.shape != (n,):
        raise ValueError(f"x0 must have shape ({n},), got {x.shape}")
    n_load = np.atleast_1d(np.asarray(path(float(t0)) if path is not None else load0)).size
    wdiag = metric_matrix(problem).diagonal()
    weight = wdiag / max(1.0, float(wdiag.sum()))
    P = _Path(problem, load0, direction, path, weight, n_load)
    run = _Continuation(problem, P, nonsymmetric_solver(linear_solver), settings.corrector,
                        count, step_limit, admissible, max_cutbacks=settings.max_cutbacks,
                        ds_min=ds_min, max_angle=settings.max_angle,
                        locate_tol=settings.locate_tol)
    out = run.out
    tau = run.start(x, t0, settings.increase)
    if tau is None:
        warnings.warn(out.reason, RuntimeWarning, stacklevel=2)
        return out
    x_prev = t_prev = None
    h, arc = ds, 0.0
    reason = f"max_steps = {max_steps} reached"
    for _ in range(max_steps):
        a = out.points[-1]
        secant = (P.unit(a.x - x_prev, a.t - t_prev)
                  if predictor == "secant" and x_prev is not None else None)
        sol, h, cuts, why = run.advance(a, tau, secant, h)
        if sol is None:
            out.converged = False
            out.reason = (f"corrector failed at t = {a.t:.10g} with ds = {h:.3g} after "
                          f"{cuts} cut-backs: {why}")
            warnings.warn(out.reason, RuntimeWarning, stacklevel=2)
            break
        xb, tb, taub, it, Kb = sol
        arc += h
        b = run.point(xb, tb, taub, it, h, arc, "regular", Kb)
        if (b.tangent_t > 0) != (tau[1] > 0) and tau[1] != 0:
            found = run.locate_limit(a, tau, b) if settings.locate else None
            if found is not None:
                (xl, tl, taul, itl, Kl), hl = found
                out.points.append(run.point(xl, tl, taul, itl, hl, arc - h + hl, "limit", Kl))
            out.events.append(ContinuationEvent(
                "limit", len(out.points) - 1 if found is not None else len(out.points),
                float(found[0][1]) if found is not None else b.t, a.n_negative,
                b.n_negative, found is not None))
        elif a.n_negative is not None and b.n_negative != a.n_negative:
            out.events.append(ContinuationEvent("bifurcation", len(out.points), b.t,
                                                a.n_negative, b.n_negative))
        out.points.append(b)
        x_prev, t_prev, tau = a.x, a.t, taub
        h = float(np.clip(h * np.clip(math.sqrt(target_iterations / max(it, 1)), 0.5, 2.0),
                          ds_min, ds_max))
        if t_max is not None and b.t > t_max:
            reason = f"t = {b.t:.10g} > t_max = {t_max}"
            break
        if t_min is not None and b.t < t_min:
            reason = f"t = {b.t:.10g} < t_min = {t_min}"
            break
        if stop is not None and stop(b):
            reason = f"stop criterion met at t = {b.t:.10g}"
            break
    if out.converged:
        out.reason = reason
    out.wall_seconds = time.perf_counter() - t_start
    return out

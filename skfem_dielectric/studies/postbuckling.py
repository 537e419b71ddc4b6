"""The post-buckled branch of a plate: switch onto it along the critical mode and follow it.

Past the first buckling load ``D0_b`` of a symmetric plate
(:mod:`~skfem_dielectric.studies.buckling`)
the fundamental state is an unstable equilibrium; a load-controlled Newton started from it
stays on it.  The buckled branch is reached by *branch switching*: at a load just past
``D0_b`` Newton is started from the fundamental state plus ``a w``, ``w`` the critical mode
and ``a`` an amplitude of the order of the thickness, on the perfect plate (no imperfection
load); a converged state with a finite deflection is the buckled equilibrium, and the ramp
continues from it in ``D0`` (forward and back towards ``D0_b``).

The model must allow the mode's parities.  A buckled state is the fundamental state plus
the mode and its powers, so it keeps only the mirror symmetries in which the mode is
symmetric: for a bending mode ``x1 S, x2 A, x3 S`` (symmetric about ``x1 = 0`` and ``x3 = 0``,
antisymmetric through the thickness) that is the ``"quarter"`` model (symmetry planes
``x1 = 0`` and ``x3 = 0``, the whole thickness); the mode is then the lowest one of that
model's own class (:func:`critical_mode`).

The deflection is the largest ``|u2|`` on the mid-plane ``X2 = 0``
(:func:`midplane_deflection`): zero on every state symmetric through the thickness.  Near a
symmetric (pitchfork) bifurcation the load is even in the amplitude,
``D0 = D0_b + b w^2 + O(w^4)``, so the branch itself gives ``D0_b`` independently of the
eigenvalue crossing (:meth:`PostBuckledBranch.pitchfork`); ``b > 0`` is a supercritical
(stable) branch, on which the model's own class has no negative eigenvalue left.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, replace
from typing import Any, Sequence

import numpy as np

from ..checks import check_count, check_positive, check_vector
from ..gallery.drivers import run_ramp
from ..models.plate.modes import ModeLabel, lowest_physical
from ..models.plate.problem import PlateProblem
from ..models.plate.symmetry_classes import class_stability, symmetry_classes
from ..solvers.ramp import RampResult, RampSettings, ramp

__all__ = ["BRANCH_SETTINGS", "midplane_nodes", "midplane_deflection", "critical_mode", "BranchSwitch",
           "switch_branch", "follow_branch", "PostBuckledBranch", "post_buckled_branch"]


def midplane_nodes(problem: PlateProblem) -> np.ndarray:
    """Indices of the displacement nodes on the mid-plane ``X2 = 0`` of a plate model
    without the ``x2`` symmetry plane (``ValueError`` for a model that cannot bend or
    has no nodes there: an odd number of elements through the thickness)."""
    if not isinstance(problem, PlateProblem):
        raise ValueError(f"problem must be a PlateProblem, got {type(problem).__name__}")
    if 2 in problem.plate.symmetry:
        raise ValueError(f"problem must not use the x2 symmetry plane (its states cannot "
                         f"bend), got symmetry {problem.plate.symmetry}; use e.g. "
                         f"symmetry='quarter' with an even number of elements through H")
    X2 = problem.b2.doflocs[1]
    mid = np.flatnonzero(np.abs(X2) < 1e-9 * problem.plate.H)
    if not mid.size:
        raise ValueError("problem has no nodes on the mid-plane X2 = 0: use an even number "
                         "of elements through the thickness")
    return mid


def midplane_deflection(problem: PlateProblem, x: np.ndarray, load: Any) -> float:
    """Largest out-of-plane displacement ``|u2|`` on the mid-plane ``X2 = 0`` of a state.

    Parameters
    ----------
    problem
        A plate model without the ``x2`` symmetry plane and with nodes on ``X2 = 0``.
    x, load
        The state (reduced vector) and its load.

    Returns
    -------
    float
        In the plate's length unit (mm for the Keplinger plate); zero (round-off) on any
        state symmetric through the thickness.
    """
    mid = midplane_nodes(problem)
    x = check_vector("x", x, problem.ndofs)
    u2 = problem.full(x, load)[1:problem.n_u:3]
    return float(np.abs(u2[mid]).max())


def critical_mode(problem: PlateProblem, x: np.ndarray, load: Any, *, extra: int = 2,
                  method: str = "auto", grad_div: float | None = None,
                  radius: float | None = None) -> ModeLabel | None:
    """The lowest physical mode of the model's own symmetry class at a state.

    The own class (the increments with the model's symmetries) holds the modes along
    which the model itself can leave the fundamental branch.  Its negative eigenpairs and
    ``extra`` more are computed and classified in ascending order
    (:func:`~skfem_dielectric.models.plate.modes.classify_mode`; clamp-corner and mesh-scale modes
    are skipped, as in :func:`~skfem_dielectric.models.plate.modes.physical_modes`).

    Parameters
    ----------
    problem
        A symmetric-coupling plate model without the ``x2`` symmetry plane.
    x, load
        A converged state.
    extra
        Eigenpairs computed above the negative ones.
    method, grad_div
        Inertia method and grad-div stabilisation of the analysed tangent (default: the
        model's own, the Hessian of its energy), as in
        :func:`~skfem_dielectric.models.plate.symmetry_classes.class_stability`.
    radius
        Corner radius (default :func:`~skfem_dielectric.models.plate.modes.corner_radius`).

    Returns
    -------
    ModeLabel or None
        :class:`~skfem_dielectric.models.plate.modes.ModeLabel` (eigenvalue in the metric of the
        full plate's nodal displacements, full dof vector ``mode``); ``None`` if no
        computed mode is physical.
    """
    midplane_nodes(problem)
    x = check_vector("x", x, problem.ndofs)
    own = symmetry_classes(problem)[0].name
    return lowest_physical(problem, x, load, extra=extra, method=method, grad_div=grad_div,
                           radius=radius, only=[own]).label


@dataclass
class BranchSwitch:
    """Outcome of :func:`switch_branch`.

    Attributes
    ----------
    x, load
        The buckled state (``None`` if none was reached) and its load.
    amplitude
        The perturbation ``a`` that reached it (``nan`` if none).
    deflection
        Its :func:`midplane_deflection`.
    tried
        One ``(amplitude, outcome)`` per attempt, the outcome ``"buckled"``,
        ``"fundamental"`` (converged back onto the symmetric state) or Newton's reason.
    reason
        Why no buckled state was reached (empty if one was).
    """

    x: np.ndarray | None
    load: np.ndarray
    amplitude: float
    deflection: float
    tried: list[tuple[float, str]] = field(default_factory=list)
    reason: str = ""

    @property
    def found(self) -> bool:
        """A buckled state was reached."""
        return self.x is not None


#: How :func:`switch_branch` and :func:`follow_branch` solve their load steps: ``rtol``
#: relative to the external load alone, a large Newton budget (40 iterations, 8 cut-backs)
#: for the first steps off the fundamental branch; :func:`follow_branch` adds the secant
#: predictor.
BRANCH_SETTINGS = RampSettings(atol=0.0, rtol=1e-9, max_iter=40, max_cutbacks=8)


def _newton_options(problem, ramp_options: dict, settings: RampSettings) -> dict:
    opts = dict(linear_solver="auto", settings=settings)
    opts.update(ramp_options)
    return opts


def switch_branch(problem: PlateProblem, x: np.ndarray, load: Any, mode: np.ndarray, *,
                  amplitudes: Sequence[float] | None = None,
                  min_deflection: float | None = None, **ramp_options) -> BranchSwitch:
    """Newton from the fundamental state perturbed along the critical mode, at fixed load.

    Parameters
    ----------
    problem
        A plate model without the ``x2`` symmetry plane.
    x, load
        The fundamental state at a load past the buckling load.
    mode
        The critical mode: a reduced vector of ``problem`` or a full dof vector (e.g.
        ``critical_mode(...).mode``); it is scaled so that its largest mid-plane ``|u2|``
        is 1.
    amplitudes
        Perturbations ``a`` tried in turn, in the plate's length unit (default
        ``(0.2, 0.5, 1, 2) H``); the first that converges to a buckled state is kept.
    min_deflection
        Deflection above which a converged state counts as buckled (default ``1e-3 H``;
        the fundamental state's is round-off).
    **ramp_options
        Options of :func:`~skfem_dielectric.solvers.ramp.ramp`: ``linear_solver`` (default
        ``"auto"``), ``settings`` (default :data:`BRANCH_SETTINGS`), the plate's ``det F >
        0`` guards by default.

    Returns
    -------
    BranchSwitch
        A failed attempt is recorded in ``tried``, never raised.
    """
    mid = midplane_nodes(problem)
    x = check_vector("x", x, problem.ndofs)
    load = np.asarray(load, dtype=float)
    H = problem.plate.H
    mode = np.asarray(mode, dtype=float)
    if mode.shape == (problem.n_full,):
        mode = problem.red.restrict(mode)
    if mode.shape != x.shape or not np.all(np.isfinite(mode)):
        raise ValueError(f"mode must be a finite vector of shape {x.shape} (reduced) or "
                         f"({problem.n_full},) (full), got {mode.shape}")
    u2 = problem.red.expand(mode)[1:problem.n_u:3][mid]
    if not np.abs(u2).max() > 0:
        raise ValueError("mode has no mid-plane deflection: it cannot take the plate off "
                         "its symmetric branch")
    mode = mode / np.abs(u2).max()
    amplitudes = ((0.2 * H, 0.5 * H, H, 2 * H) if amplitudes is None
                  else tuple(check_positive("amplitudes", a) for a in amplitudes))
    if not amplitudes:
        raise ValueError("amplitudes must not be empty")
    wmin = 1e-3 * H if min_deflection is None else check_positive("min_deflection",
                                                                  min_deflection)
    opts = _newton_options(problem, ramp_options, BRANCH_SETTINGS)
    out = BranchSwitch(None, load, float("nan"), float("nan"))
    for a in amplitudes:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            res = ramp(problem, [load], x0=x + a * mode, start=load, **opts)
        if not res.converged or not res.steps:
            out.tried.append((float(a), res.reason or "not converged"))
            continue
        st = res.steps[-1]
        w = midplane_deflection(problem, st.x, st.load)
        if w < wmin:
            out.tried.append((float(a), "fundamental"))
            continue
        out.tried.append((float(a), "buckled"))
        out.x, out.amplitude, out.deflection = st.x, float(a), w
        return out
    out.reason = ("no perturbation reached a buckled state: "
                  + "; ".join(f"a = {a:g}: {o}" for a, o in out.tried))
    return out


def follow_branch(problem: PlateProblem, x: np.ndarray, load: Any, targets: Sequence[Any], *,
                  stability: bool = True, method: str = "auto",
                  **ramp_options) -> RampResult:
    """Continue a (buckled) state through the load ``targets`` and record its deflection.

    Parameters
    ----------
    problem
        A plate model without the ``x2`` symmetry plane.
    x, load
        The converged state to start from and its load.
    targets
        Loads ``(s, D0)`` in order (increasing or decreasing ``D0``).
    stability
        Also count the negative eigenvalues of every symmetry class of the model at each
        state (:func:`~skfem_dielectric.models.plate.symmetry_classes.class_stability`).
    method
        Inertia method of that count.
    **ramp_options
        Options of the ramp (defaults as :func:`switch_branch`, with the secant
        predictor: ``replace(BRANCH_SETTINGS, predictor="secant")``).

    Returns
    -------
    RampResult
        Each step's quantities also hold ``deflection`` and, with ``stability``,
        ``n_negative`` (all classes), ``n_negative_own`` (the model's own class) and
        ``n_negative_classes`` (per class, in :func:`symmetry_classes` order).
    """
    midplane_nodes(problem)
    x = check_vector("x", x, problem.ndofs)
    targets = [np.asarray(t, dtype=float) for t in targets]
    if not targets:
        raise ValueError("targets must not be empty")
    opts = _newton_options(problem, ramp_options,
                           replace(BRANCH_SETTINGS, predictor="secant"))
    if stability:
        symmetry_classes(problem)        # build the classes once, outside the steps

    def hook(step):
        q = step.quantities
        q["deflection"] = midplane_deflection(problem, step.x, step.load)
        if stability:
            cs = class_stability(problem, step.x, step.load, k=0, method=method)
            q["n_negative_classes"] = [r.n_negative for r in cs.results]
            q["n_negative"] = cs.n_negative
            q["n_negative_own"] = cs.results[0].n_negative

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return run_ramp(problem, [np.asarray(load, float)] + targets, x0=x,
                        start=np.asarray(load, float), on_step=hook, **opts)


@dataclass
class PostBuckledBranch:
    """The buckled branch through a switch point, followed forward and back.

    Attributes
    ----------
    switch
        The :class:`BranchSwitch`.
    forward, backward
        The :class:`~skfem_dielectric.solvers.ramp.RampResult` of :func:`follow_branch` away
        from and towards the buckling load (``None`` if not run).
    """

    switch: BranchSwitch
    forward: RampResult | None = None
    backward: RampResult | None = None

    def states(self) -> list[tuple[float, float, Any]]:
        """``(D0, deflection, step)`` of every converged buckled state, by ``D0``
        (the switch point's step is ``None``)."""
        out = []
        if self.switch.found:
            out.append((float(self.switch.load[1]), self.switch.deflection, None))
        for res in (self.backward, self.forward):
            if res is not None:
                out += [(float(st.load[1]), st.quantities["deflection"], st)
                        for st in res.steps]
        return sorted(out, key=lambda t: t[0])

    def pitchfork(self, n: int = 4) -> tuple[float, float]:
        """``D0_b`` and ``b`` of ``D0 = D0_b + b w^2 + c w^4`` fitted through the ``n``
        buckled states of smallest deflection ``w`` between the buckling load and the
        switch point (the switch point and the ``backward`` states; least squares,
        ``n >= 3``).

        Raises
        ------
        ValueError
            ``n < 3`` or fewer than ``n`` such states.
        """
        n = check_count("n", n)
        if n < 3:
            raise ValueError(f"n must be >= 3 (three coefficients), got {n}")
        pts = [(float(self.switch.load[1]), self.switch.deflection)] if self.switch.found else []
        if self.backward is not None:
            pts += [(float(st.load[1]), st.quantities["deflection"])
                    for st in self.backward.steps]
        pts = sorted(pts, key=lambda t: t[1])[:n]
        if len(pts) < n:
            raise ValueError(f"the branch has {len(pts)} buckled states towards the buckling "
                             f"load, fewer than n = {n}")
        D0 = np.array([p[0] for p in pts])
        w2 = np.array([p[1] for p in pts]) ** 2
        _, b, d0 = np.polyfit(w2, D0, 2)
        return float(d0), float(b)


def post_buckled_branch(problem: PlateProblem, x: np.ndarray, load: Any,
                        forward: Sequence[float], backward: Sequence[float] = (), *,
                        mode: np.ndarray | None = None, amplitudes: Sequence[float] | None = None,
                        min_deflection: float | None = None, stability: bool = True,
                        method: str = "auto", **ramp_options) -> PostBuckledBranch:
    """Switch onto the buckled branch at ``load`` and follow it in ``D0``.

    Parameters
    ----------
    problem
        A plate model without the ``x2`` symmetry plane (module docstring).
    x, load
        The fundamental state at a load past the buckling load (where the own class has
        a negative eigenvalue).
    forward, backward
        ``D0`` values to follow the branch to, away from the buckling load and back
        towards it (the dead load ``s`` of ``load`` is kept).
    mode
        The critical mode (default: that of :func:`critical_mode` at ``(x, load)``).
    amplitudes, min_deflection
        As :func:`switch_branch`.
    stability, method
        As :func:`follow_branch`.
    **ramp_options
        Options of every ramp (``linear_solver``, ``settings``, ...; defaults as
        :func:`switch_branch` and :func:`follow_branch`).

    Returns
    -------
    PostBuckledBranch
        ``forward``/``backward`` are ``None`` when the switch found no buckled state
        (``switch.reason`` says why) or the list is empty.
    """
    load = np.asarray(load, dtype=float)
    if mode is None:
        label = critical_mode(problem, x, load, method=method)
        if label is None:
            return PostBuckledBranch(BranchSwitch(None, load, float("nan"), float("nan"),
                                                  reason="no physical mode in the model's "
                                                         "own class at the switch load"))
        mode = label.mode
    sw = switch_branch(problem, x, load, mode, amplitudes=amplitudes,
                       min_deflection=min_deflection, **ramp_options)
    out = PostBuckledBranch(sw)
    if not sw.found:
        return out
    for name, values in (("forward", forward), ("backward", backward)):
        values = [float(v) for v in values]
        if values:
            setattr(out, name, follow_branch(problem, sw.x, load,
                                             [(load[0], v) for v in values],
                                             stability=stability, method=method,
                                             **ramp_options))
    return out

"""The harness's FE runner: a :class:`~validation.specs.RunSpec` solved with :mod:`skfem_dielectric`.

:func:`run_fe` is the default runner of :func:`validation.sweep.run_case`: it builds the
problem (:func:`~validation.fe.model.build_problem`), ramps the load (pre-load first, then
the charge targets) with :func:`skfem_dielectric.solvers.ramp.ramp` and reports each
converged target as a :class:`~validation.records.StepRecord`
(:func:`~validation.fe.columns.step_record`). The saved state is the ramp's reduced
solution vector and its load, so a resumed ramp continues bit for bit.  A run analysed
for buckling (``RunSpec.buckling``) locates its buckling load ``D0_b`` at the first state
whose lowest physical eigenvalue is negative, between that state and the one before it
(:func:`_located_D0_b`): both are at hand also in a resumed ramp, so the located value is
the same.
"""

from __future__ import annotations

import warnings

import numpy as np

import skfem_dielectric as fe

from skfem_dielectric.studies.buckling import buckling_load

from ..records import RunOutcome
from .columns import step_record, stability_monitor
from .model import (BUCKLING_GRAD_DIV, BUCKLING_NEWTON, BUCKLING_TOL, build_problem,
                    ramp_settings, ramp_targets, with_dead_load)

__all__ = ["run_fe"]


class _Stop(Exception):
    """Raised inside ``on_step`` to end a ramp at the breakdown."""


def _analysis(monitor, step, load):
    """The monitor's analysis of ``step`` (``None`` without a monitor, or where the ramp
    could not factorise the step's tangent and the monitor did not see it)."""
    if monitor is None or "state_analysis_error" in step.quantities or not monitor.history \
            or not np.array_equal(np.asarray(monitor.history[-1][0], dtype=float), load):
        return None
    return monitor.last


def _located_D0_b(spec, problem, prev, cur, linear_solver) -> float:
    """The buckling load between the states ``prev`` and ``cur`` (``(x, load)`` pairs), or
    ``nan`` when ``prev`` is already past it (its crossing was located at ``prev``'s own
    row) or there is no ``prev``: the study ``buckling``'s location
    (:func:`skfem_dielectric.studies.buckling.buckling_load`, the stabilised tangent
    :data:`~validation.fe.model.BUCKLING_GRAD_DIV`, to
    :data:`~validation.fe.model.BUCKLING_TOL`), the trial states solved from ``prev``."""
    if prev is None:
        return float("nan")
    method = "pardiso" if linear_solver == "pardiso" else "auto"
    bl = buckling_load(problem, [prev, cur], grad_div=BUCKLING_GRAD_DIV, method=method,
                       tol=BUCKLING_TOL, linear_solver=linear_solver,
                       settings=BUCKLING_NEWTON)
    return float(bl.D0_b)


def run_fe(spec, start, state, on_step, linear_solver="superlu"):
    """Run the FE ramp of ``spec`` from target ``start`` (runner protocol of :mod:`.sweep`).

    Parameters
    ----------
    spec : RunSpec
        A Keplinger run without its dead load (``s=None``) gets it from
        :func:`~validation.fe.model.with_dead_load`.
    start : int
        First target to compute; ``state`` holds ``x`` and ``load`` of target
        ``start - 1`` (``None`` when ``start == 0``).
    state : dict or None
    on_step : callable
        ``on_step(index, record, state) -> stop``.
    linear_solver : str
        Passed to the ramp; SuperLU (deterministic) by default, so that a
        resumed ramp repeats the uninterrupted one bit for bit.

    Returns
    -------
    RunOutcome
    """
    spec = with_dead_load(spec)
    problem = build_problem(spec)
    targets = ramp_targets(spec)
    x0 = None if state is None else np.asarray(state["x"], dtype=float)
    start_load = None if state is None else np.asarray(state["load"], dtype=float)
    if start_load is not None:
        try:
            targets = fe.gallery.remaining_targets(targets, start_load)
        except ValueError:
            raise ValueError(f"saved load {start_load} is not a target of run {spec.key}"
                             ) from None

    monitor = stability_monitor(spec, problem, linear_solver)
    # the previous target's state (for the location of D0_b) and whether it is done
    track = {"prev": None if state is None else (x0, start_load), "located": False}

    def cb(step):
        load = np.asarray(step.load, dtype=float)
        if load[0] != spec.s or not step.target_reached:
            # an intermediate pre-load step, or the furthest converged sub-step towards a
            # target the ramp failed to reach (the failed target is recorded as a row)
            return
        i = spec.D0.index(float(load[1]))
        rec = step_record(spec, problem, step, _analysis(monitor, step, load))
        if spec.buckling and not track["located"] and np.isfinite(rec.physical_eig) \
                and rec.physical_eig < 0:
            rec.D0_b = _located_D0_b(spec, problem, track["prev"], (step.x, load),
                                     linear_solver)
            track["located"] = True
        track["prev"] = (step.x, load)
        if on_step(i, rec, {"x": step.x, "load": load}):
            raise _Stop

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)   # the failure is recorded
            res = fe.ramp(problem, targets, x0=x0, start=start_load, on_step=cb,
                          state_analysis=monitor, **ramp_settings(spec, linear_solver),
                          **fe.gallery.newton_guards(problem))
    except _Stop:
        return RunOutcome(True)
    failed = None if res.failed_at is None else float(np.asarray(res.failed_at).ravel()[-1])
    return RunOutcome(bool(res.converged), res.reason, failed)

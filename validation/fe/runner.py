"""The harness's FE runner: a :class:`~validation.specs.RunSpec` solved with :mod:`skfem_dielectric`.

:func:`run_fe` is the default runner of :func:`validation.sweep.run_case`: it builds the
problem (:func:`~validation.fe.model.build_problem`), ramps the load (pre-load first, then
the charge targets) with :func:`skfem_dielectric.solvers.ramp.ramp` and reports each
converged target as a :class:`~validation.records.StepRecord`
(:func:`~validation.fe.columns.step_record`). The saved state is the ramp's reduced
solution vector and its load, so a resumed ramp continues bit for bit.

A run analysed for buckling (``RunSpec.buckling``) ramps twice to the same loads: the plain
form (:func:`~validation.fe.model.build_problem`), which gives every column a plain run has
(stretches, ``P33``, ``breakdown``, the model's own stability counts), and before it the
grad-div form (:func:`~validation.fe.model.buckling_problem`), whose states are scanned
event by event (:class:`~skfem_dielectric.models.plate.scan.PlateScan`: every symmetry
class counted at every state, modes only where a count changes) for the whole plate's
columns and ``stable`` (:func:`~validation.fe.columns.plate_buckling_columns`), and the
buckling load ``D0_b``, located at the first of its states with a negative mode labelled
physical, between that state and the one before it (:func:`_located_D0_b`).  The saved
state holds both ramps' vectors (``x``, ``x_stab``), the scan's counts and labels and
whether ``D0_b`` is located, so a resumed run continues both ramps and the scan bit for
bit and locates the same value.
"""

from __future__ import annotations

import warnings

import numpy as np

import skfem_dielectric as fe

from skfem_dielectric.models.plate.scan import PlateScan
from skfem_dielectric.studies.buckling import locate_buckling

from ..progress import report_step
from ..records import RunOutcome
from ..store.files import save_points, saved_points
from .columns import plate_buckling_columns, step_record, stability_monitor
from ..specs import LOCATION_TOL
from .model import (BUCKLING_NEWTON, buckling_problem, build_problem,
                    ramp_settings, ramp_targets, with_dead_load)

__all__ = ["run_fe"]


def _analysis(monitor, step, load):
    """The monitor's analysis of ``step`` (``None`` without a monitor, or where the ramp
    could not factorise the step's tangent and the monitor did not see it)."""
    if monitor is None or "state_analysis_error" in step.quantities or not monitor.history \
            or not np.array_equal(np.asarray(monitor.history[-1][0], dtype=float), load):
        return None
    return monitor.last


def _located_D0_b(problem, prev, cur, mode, counts, linear_solver) -> float:
    """The buckling load between the grad-div form's states ``prev`` and ``cur``
    (``(x, load)`` pairs) where the scan found the physical ``mode`` (``counts``: the scan's
    state at ``prev``), or ``nan`` when there is no ``prev``: the study ``buckling``'s
    location (:func:`skfem_dielectric.studies.buckling.locate_buckling`, to
    :data:`~validation.specs.LOCATION_TOL`, trial states solved from ``prev`` with
    :data:`~validation.fe.model.BUCKLING_NEWTON`)."""
    if prev is None or mode is None:
        return float("nan")
    method = "pardiso" if linear_solver == "pardiso" else "auto"
    bl = locate_buckling(problem, prev, cur, mode, counts=counts, method=method,
                         tol=LOCATION_TOL, linear_solver=linear_solver,
                         settings=BUCKLING_NEWTON)
    return float(bl.D0_b)


def _stabilised_states(spec, targets, state, linear_solver) -> dict:
    """The grad-div form's ramp of a run analysed for buckling, from the saved
    ``state["x_stab"]`` (at ``state["load"]``) or from the start: its problem and its
    converged charge targets, ``{D0: x}`` (a target it cannot reach ends it; the rows
    from there on have no whole-plate columns)."""
    problem = buckling_problem(spec)
    if state is not None and "x_stab" not in state:
        return {"problem": problem, "x": {}}      # that ramp had stopped before
    x0 = None if state is None else np.asarray(state["x_stab"], dtype=float)
    start = None if state is None else np.asarray(state["load"], dtype=float)
    states, steps = {}, {}

    def cb(step):
        load = np.asarray(step.load, dtype=float)
        if load[0] == spec.s and step.target_reached:
            states[float(load[1])] = step.x
            report_step(f"{spec.key} D0={load[1]:.3g} (grad-div form, for the whole "
                        f"plate's spectrum)")
            steps[float(load[1])] = step

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)       # its rows show the failure
        fe.ramp(problem, targets, x0=x0, start=start, on_step=cb,
                **saved_points(state, "stab_"), **ramp_settings(spec, linear_solver))
    return {"problem": problem, "x": states, "steps": steps}


def grad_div_states(spec, linear_solver: str = "superlu") -> tuple:
    """The grad-div form's ramp of a run analysed for buckling (``spec.buckling``), from
    the start: ``(problem, [(x, load), ...])`` at its converged charge targets, the states
    the run's whole-plate columns and ``D0_b`` are of (``benchmarks/bench_buckling_scan.py``
    and the tests scan them)."""
    spec = with_dead_load(spec)
    st = _stabilised_states(spec, ramp_targets(spec), None, linear_solver)
    return st["problem"], [(x, np.array([spec.s, d])) for d, x in sorted(st["x"].items())]


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
    stab = _stabilised_states(spec, targets, state, linear_solver) if spec.buckling else None
    # the grad-div form's previous state (for the location of D0_b) and whether it is done
    track = {"prev": None if state is None or "x_stab" not in state
             else (np.asarray(state["x_stab"], dtype=float), start_load),
             "located": state is not None and bool(state.get("located", False))}
    # the event-driven scan of the grad-div form's states, continued from the saved state
    scan = None if stab is None else PlateScan(stab["problem"], state=None if state is None
                                               or "scan_counts" not in state else
                                               {"counts": state["scan_counts"],
                                                "physical": state["scan_physical"]})

    def cb(step):
        load = np.asarray(step.load, dtype=float)
        if load[0] != spec.s or not step.target_reached:
            # an intermediate pre-load step, or the furthest converged sub-step towards a
            # target the ramp failed to reach (the failed target is recorded as a row)
            return
        i = spec.D0.index(float(load[1]))
        rec = step_record(spec, problem, step, _analysis(monitor, step, load))
        saved = {"x": step.x, "load": load}
        save_points(saved, step)
        if stab is not None:
            xs = stab["x"].get(float(load[1]))
            if xs is not None:
                before, scan.last = scan.state, None
                for k, v in plate_buckling_columns(spec, scan, xs, load).items():
                    setattr(rec, k, v)
                row = scan.last
                if not track["located"] and row is not None and row.n_physical > 0:
                    rec.D0_b = _located_D0_b(stab["problem"], track["prev"], (xs, load),
                                             row.new_physical, before, linear_solver)
                    track["located"] = True
                track["prev"] = (xs, load)
                saved["x_stab"] = xs
                save_points(saved, stab["steps"].get(float(load[1])), "stab_")
                after = scan.state
                saved["scan_counts"], saved["scan_physical"] = after["counts"], after["physical"]
            saved["located"] = np.array(track["located"])
        track["stop"] = bool(on_step(i, rec, saved))

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)   # the failure is recorded
        res = fe.ramp(problem, targets, x0=x0, start=start_load,
                      on_step=cb, **saved_points(state),
                      stop=lambda step: track.pop("stop", False),   # at the breakdown
                      state_analysis=monitor, **ramp_settings(spec, linear_solver))
    if res.stopped_at is not None:
        return RunOutcome(True)
    failed = None if res.failed_at is None else float(np.asarray(res.failed_at).ravel()[-1])
    return RunOutcome(bool(res.converged), res.reason, failed)

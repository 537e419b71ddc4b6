"""Negative-mode counts of the whole clamped plate at a few charges, without eigenpairs.

The clamp-zone study's units (:mod:`validation.clamp_zone.units`) scan every state of a unit,
which computes and classifies every negative mode; on the meshes refined in ``n1``,
``n2`` and ``n3`` together that scan does not fit a background unit.  This study ramps the
same plate (eighth model, neo-Hookean, ``g = 9.81``, graded along ``x1``) to each charge of
``--D0`` in one ramp (targets in steps of 0.5 below them) and counts the negative
eigenvalues of every symmetry class there
(:meth:`~skfem_dielectric.models.plate.scan.PlateScan.count`: Sylvester's law of inertia,
one factorisation per class).  The count holds one factorisation at a time: the ramp's
kept factors are freed before a state is counted (the next step factorises again), and
each class's before the next class's.  A count does not tell a physical mode from a clamp-corner or
a mesh-scale one: it says how many negative modes the discrete plate has at that charge,
which is what the refinement of the clamp edge is judged by (a count that falls to the
corner quartet, 4, as the edge is refined, or one that does not).

A row per charge:

* ``alpha``, ``mesh`` (``n1xn2xn3``), ``grading``, ``formulation``, ``grad_div`` (units of
  ``mu``, equilibrium and analysed tangent alike), ``pressure`` (the pressure space:
  ``Q1``, continuous, Taylor-Hood; ``P0``, a constant per element), ``D0``: the state;
* ``dofs``; ``n_negative``: every class's count summed; ``n_x2A``: the counts of the four
  classes antisymmetric in ``x2`` (bending, where the clamp-edge modes sit); ``SSS`` ...
  ``AAA``: the count of the class ``x1 _, x2 _, x3 _`` (``S`` symmetric, ``A``
  antisymmetric, in the order ``x1``, ``x2``, ``x3``);
* ``cpu_s``: the process's CPU seconds up to this row (the ramp included); ``count_cpu_s``:
  the count alone; ``peak_GB``, ``factorisations``, ``solver``, ``date``, ``command``.

The rows go to the ``counts`` table as each state is counted
(``skfem-dielectric clamp-zone counts``); a state already there is skipped.

A ramp of a large mesh takes hours: with ``checkpoint`` its last reached target is kept in
an ``.npz`` (the state, the secant predictor's second point and where the kept factors
were made, written atomically after every target), a later call resumes the ramp from
there bit for bit, and ``budget`` (seconds) pauses it after the first target past that
time (:class:`CountsPaused`), so that a study of any size runs in units of bounded length.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.models.plate.scan import PlateScan

from ..fe.model import BUCKLING_GRAD_DIV
from ..store.files import read_npz, save_points, saved_points, write_npz_atomic
from .costs import Meter
from ..data.registry import CLASS_COLUMNS, TABLES
from ..data.key import UnitKey, mesh_text
from .units import COUNT_PRELOAD_STEPS, UNIT_SETTINGS, charge_path, unit_problem, unit_ramp

__all__ = ["COLUMNS", "CLASS_COLUMNS", "CountsPaused", "run_counts"]


class CountsPaused(Exception):
    """A counts ramp paused by its time budget after a reached target, its state kept in
    the checkpoint: calling again with the same checkpoint continues it."""

    def __init__(self, load, seconds: float, checkpoint):
        self.load, self.seconds, self.checkpoint = load, seconds, checkpoint
        super().__init__(f"paused at s = {load[0]:g}, D0 = {load[1]:g} after "
                         f"{seconds:.0f} s (the budget); the ramp's state is kept in "
                         f"{checkpoint}")


def _save_checkpoint(path, tag: str, step) -> None:
    """The ramp's state after a reached target (``step``) into ``path``, atomically: its
    ``x`` and ``load`` and the two points a resumed ramp restarts on
    (:func:`~validation.store.files.save_point`)."""
    state = {"x": step.x, "load": np.asarray(step.load, float)}
    save_points(state, step)
    write_npz_atomic(path, tag=np.array(tag), **state)


def _load_checkpoint(path, tag: str):
    """``(x, load, back, factors, back2)`` of a checkpoint written for ``tag``, else
    ``None`` (no file, or one of another load path: the ramp starts from the beginning and
    its first target's state replaces it)."""
    if path is None or not Path(path).is_file():
        return None
    z = read_npz(path)
    if str(z["tag"]) != tag:
        return None
    p = saved_points(z)
    return z["x"], z["load"], p["back"], p["factors"], p["back2"]

#: the columns of a row, in order (the ``counts`` table)
COLUMNS = TABLES["counts"].columns


def _column(name: str) -> str:
    """The count column of a class name ``"x1 S, x2 A, x3 S"`` (``"SAS"``)."""
    return "".join(part.strip()[-1] for part in name.split(","))


def run_counts(key: UnitKey, D0, *, grad_div: float = BUCKLING_GRAD_DIV,
                    pressure: str = "Q1", solver: str = "auto", skip=(), progress=None,
                    on_row=None, checkpoint=None, budget: float | None = None) -> list[dict]:
    """Count the negative modes of every class at each charge of ``D0``.

    Parameters
    ----------
    key : UnitKey
        The unit (:class:`~validation.data.key.UnitKey`): weight fraction, eighth-model
        mesh, grading along ``x1`` and formulation.
    grad_div, pressure
        The plate's grad-div weight and pressure space
        (:func:`~validation.clamp_zone.units.unit_problem`).
    D0
        The charges (positive); counted in increasing order along one ramp.
    solver
        Linear solver of the ramp (its factors in the precision of
        :data:`~validation.clamp_zone.units.UNIT_SETTINGS`, single with PARDISO); the
        counts factorise each class in double precision.
    skip
        Charges not to count (already counted); the ramp still passes them.
    progress
        Optional ``progress(text)``.
    on_row
        Optional ``on_row(row)`` called as each state is counted (the caller writes it).
    checkpoint
        Optional ``.npz`` path: the ramp's state after every reached target is kept there,
        and a call that finds it (written for the same plate and charges) resumes from it;
        removed when the last charge is counted.
    budget
        Optional seconds (wall): the ramp pauses after the first reached target past them
        and :class:`CountsPaused` is raised (with ``checkpoint`` the next call continues).

    Returns
    -------
    list of dict
        A row of :data:`COLUMNS` per counted charge.

    Raises
    ------
    ValueError
        A charge not positive and finite, a budget not positive, or the ramp stopping
        before the last charge (the rows of the charges before it are returned through
        ``on_row`` first).
    CountsPaused
        The budget ran out before the last charge (its rows were given to ``on_row``).
    """
    meter = Meter()
    alpha, elements, grading, formulation = key.alpha, key.mesh, key.grading, key.formulation
    D0 = sorted({float(d) for d in D0})
    for d in D0:
        if not (math.isfinite(d) and d > 0):
            raise ValueError(f"D0 must be positive and finite, got {d!r}")
    if budget is not None and not (math.isfinite(budget) and budget > 0):
        raise ValueError(f"budget must be positive and finite, got {budget!r}")
    t0 = time.perf_counter()
    el = tuple(int(n) for n in elements)
    pb, s = unit_problem(alpha, el, grading=grading, formulation=formulation,
                         grad_div=grad_div, pressure=pressure)
    scan = PlateScan(pb)
    wanted = [d for d in D0 if not any(abs(d - k) < 1e-12 for k in skip)]
    rows = []

    def on_step(st):
        load = np.asarray(st.load, dtype=float)
        if not st.target_reached or load[0] != s:
            return
        d = float(load[1])
        if not any(abs(d - w) < 1e-12 for w in wanted):
            return
        t1 = time.process_time()
        if callable(getattr(ramp_solver, "release", None)):
            ramp_solver.release()     # the ramp's factors and analysis: not held beside
                                      # the counts'
        counts = scan.count(st.x, load)
        row = {"alpha": alpha, "mesh": mesh_text(el), "grading": grading,
               "formulation": formulation, "grad_div": grad_div, "pressure": pressure,
               "D0": d, "dofs": pb.ndofs,
               "n_negative": sum(counts.values()),
               "n_x2A": sum(v for k, v in counts.items() if _column(k)[1] == "A"),
               **{_column(k): v for k, v in counts.items()},
               "count_cpu_s": round(time.process_time() - t1, 1),
               **meter.columns(solver)}
        if progress is not None:
            progress(f"D0 = {d:g}: {row['n_negative']} negative ({row['n_x2A']} in x2 A), "
                     f"{row['count_cpu_s']} CPU s")
        rows.append(row)
        if on_row is not None:
            on_row(row)

    if not wanted:
        return rows
    top = max(wanted)
    targets = sorted({*np.round(np.arange(0.5, top, 0.5), 10).tolist(),
                      *[d for d in D0 if d <= top]})
    path = charge_path(s, targets, COUNT_PRELOAD_STEPS)
    tag = (f"{alpha!r} {mesh_text(el)} {grading!r} {formulation} {grad_div!r} {pressure} "
           f"{' '.join(repr(float(v)) for ld in path for v in np.atleast_1d(ld))}")
    start = _load_checkpoint(checkpoint, tag)
    if start is not None and progress is not None:
        progress(f"resumed at D0 = {float(start[1][1]):g} from {checkpoint}")
    # the ramp's factors in the units' precision (the counts' own are double)
    ramp_solver = fe.get_linear_solver(solver, precision=UNIT_SETTINGS.factor_precision)

    def keep(st):
        on_step(st)
        if checkpoint is not None and st.target_reached:
            _save_checkpoint(checkpoint, tag, st)

    def pause(st):
        return budget is not None and time.perf_counter() - t0 > budget

    res = unit_ramp(pb, path, on_step=keep, solver=ramp_solver, start=start, stop=pause)
    if not res.converged:
        raise ValueError(f"the ramp of alpha = {alpha:g} {mesh_text(el)} stopped at "
                         f"D0 = {np.asarray(res.failed_at)[-1]:g}")
    if res.stopped_at is not None and not np.allclose(res.stopped_at, path[-1]):
        raise CountsPaused(np.asarray(res.stopped_at, float), time.perf_counter() - t0,
                           checkpoint)
    if checkpoint is not None and Path(checkpoint).is_file():
        Path(checkpoint).unlink()             # the unit is complete: its state is not needed
    return rows

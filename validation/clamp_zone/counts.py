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
"""

from __future__ import annotations

import math
import time

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.models.plate.scan import PlateScan

from ..fe.model import BUCKLING_GRAD_DIV
from .costs import Meter
from ..data.registry import CLASS_COLUMNS, TABLES
from ..data.key import mesh_text
from .units import charge_path, unit_problem, unit_ramp

__all__ = ["COLUMNS", "CLASS_COLUMNS", "run_edge_counts"]

#: the columns of a row, in order (the ``counts`` table)
COLUMNS = TABLES["counts"].columns


def _column(name: str) -> str:
    """The count column of a class name ``"x1 S, x2 A, x3 S"`` (``"SAS"``)."""
    return "".join(part.strip()[-1] for part in name.split(","))


def run_edge_counts(alpha: float, elements, D0, *, grading: float = 1.0,
                    formulation: str = "mixed", grad_div: float = BUCKLING_GRAD_DIV,
                    pressure: str = "Q1", solver: str = "auto", skip=(), progress=None,
                    on_row=None) -> list[dict]:
    """Count the negative modes of every class at each charge of ``D0``.

    Parameters
    ----------
    alpha, elements, grading, formulation, grad_div, pressure
        The plate (:func:`~validation.clamp_zone.units.unit_problem`).
    D0
        The charges (positive); counted in increasing order along one ramp.
    solver
        Linear solver of the ramp and the counts.
    skip
        Charges not to count (already counted); the ramp still passes them.
    progress
        Optional ``progress(text)``.
    on_row
        Optional ``on_row(row)`` called as each state is counted (the caller writes it).

    Returns
    -------
    list of dict
        A row of :data:`COLUMNS` per counted charge.

    Raises
    ------
    ValueError
        A charge not positive and finite, or the ramp stopping before the last charge
        (the rows of the charges before it are returned through ``on_row`` first).
    """
    meter = Meter()
    D0 = sorted({float(d) for d in D0})
    for d in D0:
        if not (math.isfinite(d) and d > 0):
            raise ValueError(f"D0 must be positive and finite, got {d!r}")
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
        if callable(getattr(ramp_solver, "discard", None)):
            ramp_solver.discard()     # the ramp's factors: not held beside the counts'
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
    ramp_solver = fe.get_linear_solver(solver)
    res = unit_ramp(pb, charge_path(s, targets), on_step=on_step, solver=ramp_solver)
    if not res.converged:
        raise ValueError(f"the ramp of alpha = {alpha:g} {mesh_text(el)} stopped at "
                         f"D0 = {np.asarray(res.failed_at)[-1]:g}")
    return rows

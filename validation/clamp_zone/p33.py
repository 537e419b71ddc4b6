"""The P33 breakdown on the clamp-zone study's graded meshes, located, unit by unit.

A *unit* is the charge ramp of the clamped Keplinger plate (eighth model, neo-Hookean,
``g = 9.81``) for one weight fraction ``alpha`` on one mesh ``n1 x n2 x n3`` graded along
``x1`` towards the clamp, in the **plain form** (``grad_div = 0``: the paper's energy, the
form of the validation harness; the grad-div form's ``P33`` carries its stabilisation stress
``gamma (J - 1)`` where the discrete ``J`` is not one).  At every charge target in steps of
``D0_step`` it reads ``min P33/mu`` on three sets
(:func:`validation.studies.buckling.p33_measures`):

* ``centre_line``: the centre line ``x2 = x3 = 0`` (the whole length);
* ``clamp``: the clamp line, one element inside the clamp;
* ``interior``: the centre line outside the clamps' ``2H`` layer.

For each set, the first step whose value falls below ``-BREAKDOWN_TOL``
(:data:`validation.table.BREAKDOWN_TOL`, the breakdown flag of the harness) brackets the
onset, which is then located to ``1e-4`` in ``D0`` by Brent's method on trial states
solved from the lower end of the bracket
(:func:`skfem_dielectric.solvers.critical.critical_load`).  The row also holds
``newton_limit``: the last charge the plain form's ramp reached where it stopped (empty if
it reached ``D0_max``).  An onset is empty where the value never falls below
``-BREAKDOWN_TOL`` up to the last converged state (the ``note`` says so); ``D0 = 0`` (no
charge) never counts as an onset.

The rows go to the ``p33`` table, one per unit, as soon as the unit is done
(``skfem-dielectric clamp-zone p33``); a unit already there is skipped.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.solvers.critical import critical_load

from ..fe.model import BUCKLING_NEWTON
from ..studies.buckling import p33_measures
from ..table import BREAKDOWN_TOL
from .costs import Meter
from ..data.registry import P33_SETS as SETS, TABLES
from ..specs import LOCATION_TOL
from ..data.key import UnitKey, mesh_text
from .units import charge_path, unit_ramp

__all__ = ["COLUMNS", "SETS", "run_p33"]

#: the columns of a row, in order (the ``p33`` table)
COLUMNS = TABLES["p33"].columns


def run_p33(key: UnitKey, *, D0_step: float = 0.25, D0_max: float = 6.0,
                 solver: str = "auto", progress=None) -> dict:
    """One unit: the row of :data:`COLUMNS` (module docstring).

    Parameters
    ----------
    key : UnitKey
        The unit (:class:`~validation.data.key.UnitKey`): weight fraction, eighth-model
        mesh, grading along ``x1`` and formulation (the formulation is not used: the
        plain form's ``P33`` onsets).
    D0_step, D0_max
        The charge targets ``D0_step, 2 D0_step, ..., D0_max`` of the bracketing ramp.
    solver
        Linear solver of the ramp and the trial states.
    progress
        Optional ``progress(text)`` called once per charge target.

    Returns
    -------
    dict
        An onset is ``nan`` where ``min P33/mu`` stays above ``-BREAKDOWN_TOL`` on every
        converged state (``note`` says up to where).
    """
    meter = Meter()
    alpha, elements, grading = key.alpha, key.mesh, key.grading
    el = tuple(int(n) for n in elements)
    pb = fe.gallery.keplinger_problem(elements=el, symmetry="eighth", grading=grading,
                                      options=fe.PlateOptions())
    s = fe.gallery.keplinger_s(alpha, g=9.81)
    D0 = np.round(np.arange(D0_step, D0_max + 1e-9, D0_step), 10)
    states = []

    def on_step(step):
        load = np.asarray(step.load, dtype=float)
        if step.target_reached and load[0] == s and load[1] > 0:
            m = p33_measures(pb, step.x, load, step.quantities)
            states.append((step.x.copy(), load.copy(), m))
            if progress is not None:
                progress(f"D0 = {load[1]:.4f}: " + ", ".join(f"{k} {m[k]:+.4f}" for k in SETS))

    res = unit_ramp(pb, charge_path(s, D0), on_step=on_step, solver=solver)
    newton_limit = math.nan if res.converged else (float(states[-1][1][1]) if states else 0.0)
    row = {"alpha": alpha, "mesh": mesh_text(el), "grading": grading, "dofs": pb.ndofs,
           "D0_step": D0_step, "newton_limit": newton_limit, "D0_max": D0_max,
           "states": len(states)}
    notes, trials = [], 0
    newton = dict(linear_solver=solver, settings=BUCKLING_NEWTON)
    for k in SETS:
        vals = [m[k] + BREAKDOWN_TOL for _, _, m in states]
        below = [i for i, v in enumerate(vals) if v < 0]
        onset = math.nan
        if not below:
            last = states[-1][1][1] if states else 0.0
            notes.append(f"{k}: above -{BREAKDOWN_TOL:g} up to D0 = {last:g}")
        elif below[0] == 0:
            onset = float(states[0][1][1])
            notes.append(f"{k}: below at the first target (not located)")
        else:
            i = below[0]
            (xa, la, _), (_, lb, _) = states[i - 1], states[i]

            def value(x, load, k=k):
                return p33_measures(pb, x, load, pb.postprocess(x, load))[k] + BREAKDOWN_TOL

            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", RuntimeWarning)
                    crit = critical_load(pb, xa, la, lb, value, tol=LOCATION_TOL, **newton)
                onset = float(crit.load[1])
                trials += len(crit.evaluations)
            except ValueError as exc:     # a result: bracketed, not located
                onset = float(lb[1])
                notes.append(f"{k}: between D0 = {la[1]:g} and {lb[1]:g}, not located "
                             f"({exc})")
        row[f"P33_onset_{k}"] = onset
        if progress is not None:
            progress(f"P33 onset ({k}): {onset:.4f}")
    row.update(trials=trials, note="; ".join(notes), **meter.columns(solver))
    return row

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

Rows go to a CSV (default ``validation/data/p33_units.csv``), one per unit, written
atomically as soon as the unit is done; a unit whose key (``alpha``, mesh, ``grading``) is
already there is skipped, so a list of units run in the background resumes where it
stopped.

Usage::

    python -m validation.studies.p33_units --alpha 1 --mesh 30x1x24 --grading 0.1
"""

from __future__ import annotations

import argparse
import datetime
import math
import resource
import shlex
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.fem import blas_thread_limit
from skfem_dielectric.gallery.drivers import newton_guards
from skfem_dielectric.linalg.solver_base import factorisation_count
from skfem_dielectric.solvers.critical import critical_load

from ..buckling_data import read_data_csv
from ..fe.model import BUCKLING_NEWTON
from ..table import BREAKDOWN_TOL
from .buckling import p33_measures
from .clamp_units import UNIT_SETTINGS, append_row, mesh_text, parse_mesh

__all__ = ["COLUMNS", "DEFAULT_CSV", "SETS", "run_p33_unit", "read_p33_units", "main"]

#: where the rows are kept (provenance in the header lines)
DEFAULT_CSV = Path(__file__).resolve().parents[1] / "data" / "p33_units.csv"
#: the sets whose onset is located
SETS = ("centre_line", "clamp", "interior")
#: the columns of a row, in order
COLUMNS = (("alpha", "mesh", "grading", "dofs", "D0_step")
           + tuple(f"P33_onset_{k}" for k in SETS)
           + ("newton_limit", "D0_max", "states", "trials", "factorisations", "cpu_s",
              "peak_GB", "solver", "date", "note", "command"))
_HEADER = """\
# The P33 breakdown of the Keplinger plate on graded meshes, located (one alpha on one mesh
# per row).  Written by validation.studies.p33_units (the module docstring defines every
# column): eighth model, plain form (grad_div = 0), neo-Hookean, g = 9.81; an onset is the
# D0 where min P33/mu on its set reaches -0.01, located to 1e-4 by Brent's method.
"""
#: location tolerance of an onset in D0
ONSET_TOL = 1e-4


def run_p33_unit(alpha: float, elements, *, grading: float = 1.0, D0_step: float = 0.25,
                 D0_max: float = 6.0, solver: str = "auto", progress=None) -> dict:
    """One unit: the row of :data:`COLUMNS` (module docstring).

    Parameters
    ----------
    alpha
        Weight fraction (``> 0``).
    elements
        ``(n1, n2, n3)`` of the eighth model.
    grading
        Last / first element length along ``x1`` (``< 1``: finer at the clamp).
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
    t0, f0 = time.process_time(), factorisation_count()
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

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = fe.gallery.run_ramp(pb, fe.gallery.preload_then_charge(
            s, D0, fe.gallery.KEPLINGER_PRELOAD_STEPS), on_step=on_step,
            linear_solver=solver, settings=UNIT_SETTINGS)
    newton_limit = math.nan if res.converged else (float(states[-1][1][1]) if states else 0.0)
    row = {"alpha": alpha, "mesh": mesh_text(el), "grading": grading, "dofs": pb.ndofs,
           "D0_step": D0_step, "newton_limit": newton_limit, "D0_max": D0_max,
           "states": len(states)}
    notes, trials = [], 0
    newton = dict(linear_solver=solver, settings=BUCKLING_NEWTON, **newton_guards(pb))
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
                    crit = critical_load(pb, xa, la, lb, value, tol=ONSET_TOL, **newton)
                onset = float(crit.load[1])
                trials += len(crit.evaluations)
            except ValueError as exc:     # a result: bracketed, not located
                onset = float(lb[1])
                notes.append(f"{k}: between D0 = {la[1]:g} and {lb[1]:g}, not located "
                             f"({exc})")
        row[f"P33_onset_{k}"] = onset
        if progress is not None:
            progress(f"P33 onset ({k}): {onset:.4f}")
    row.update(trials=trials, factorisations=factorisation_count() - f0,
               cpu_s=round(time.process_time() - t0, 1),
               peak_GB=round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2, 3),
               solver=solver, date=datetime.date.today().isoformat(), note="; ".join(notes))
    return row


def read_p33_units(path: Path = DEFAULT_CSV) -> list[dict]:
    """The rows of the CSV (comment lines skipped), as dicts of strings."""
    return read_data_csv(path)


def _key(r: dict) -> tuple:
    return f"{float(r['alpha']):g}", str(r["mesh"]), f"{float(r['grading']):g}"


def main(argv: list[str] | None = None) -> int:
    """Run the units ``--alpha`` x ``--mesh`` not yet in ``--csv`` and append their rows.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default: ``sys.argv[1:]``; see the module docstring).

    Returns
    -------
    int
        0; bad arguments exit with argparse's one line and code 2.
    """
    ap = argparse.ArgumentParser(prog="python -m validation.studies.p33_units",
                                 description=__doc__.splitlines()[0])
    ap.add_argument("--alpha", type=float, nargs="+", required=True)
    ap.add_argument("--mesh", type=parse_mesh, nargs="+", required=True)
    ap.add_argument("--grading", type=float, default=1.0)
    ap.add_argument("--D0-step", dest="D0_step", type=float, default=0.25)
    ap.add_argument("--D0-max", dest="D0_max", type=float, default=6.0)
    ap.add_argument("--solver", default="auto", choices=["auto", "superlu", "pardiso"])
    ap.add_argument("--csv", type=Path, default=DEFAULT_CSV)
    a = ap.parse_args(argv)
    command = "python -m validation.studies.p33_units " + " ".join(
        shlex.quote(v) for v in (argv if argv is not None else sys.argv[1:]))
    for alpha in a.alpha:
        for el in a.mesh:
            key = (f"{alpha:g}", mesh_text(el), f"{a.grading:g}")
            if any(_key(r) == key for r in read_p33_units(a.csv)):
                print(f"alpha = {alpha:g} {key[1]} grading {a.grading:g}: kept", flush=True)
                continue
            with blas_thread_limit(1):      # as the command line (docs/performance.md)
                row = run_p33_unit(alpha, el, grading=a.grading, D0_step=a.D0_step,
                                   D0_max=a.D0_max, solver=a.solver,
                                   progress=lambda t: print("  " + t, flush=True))
            row["command"] = command
            append_row(a.csv, row, COLUMNS, _HEADER)
            print(f"alpha = {alpha:g} {key[1]} grading {a.grading:g}: P33 onsets "
                  + ", ".join(f"{k} {row[f'P33_onset_{k}']:.4f}" for k in SETS)
                  + f", Newton limit {row['newton_limit']:g}, {row['dofs']} DOFs, "
                  f"{row['cpu_s']} CPU s, {row['peak_GB']} GB", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

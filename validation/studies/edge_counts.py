"""Negative-mode counts of the whole clamped plate at a few charges, without eigenpairs.

The clamp-zone study (:mod:`validation.studies.clamp_units`) scans every state of a unit,
which computes and classifies every negative mode; on the meshes refined in ``n1``,
``n2`` and ``n3`` together that scan does not fit a background unit.  This study ramps the
same plate (eighth model, neo-Hookean, ``g = 9.81``, graded along ``x1``) to each charge of
``--D0`` in one ramp (targets in steps of 0.5 below them) and counts the negative
eigenvalues of every symmetry class there
(:meth:`~skfem_dielectric.models.plate.scan.PlateScan.count`: Sylvester's law of inertia,
one factorisation per class).  A count does not tell a physical mode from a clamp-corner or
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

Rows go to a CSV (default ``validation/data/edge_counts.csv``), written atomically as each
state is counted; a state whose key (``alpha``, mesh, ``grading``, ``formulation``,
``grad_div``, ``pressure``, ``D0``) is there is skipped, so a unit resumes where it stopped.

Usage::

    python -m validation.studies.edge_counts --solver pardiso --alpha 1.5 --mesh 60x1x36 \\
        --grading 0.1 --D0 4 4.5 4.75
"""

from __future__ import annotations

import argparse
import datetime
import math
import resource
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.fem import blas_thread_limit
from skfem_dielectric.linalg.solver_base import factorisation_count
from skfem_dielectric.models.plate.scan import PlateScan

from ..buckling_data import read_data_csv, unit_key
from ..fe.model import BUCKLING_GRAD_DIV
from .clamp_units import (UNIT_SETTINGS, append_row, foreign_table, mesh_text, parse_mesh,
                          study_command, unit_problem)

__all__ = ["COLUMNS", "CLASS_COLUMNS", "DEFAULT_CSV", "run_edge_counts", "read_edge_counts",
           "main"]

#: where the study's rows are kept (provenance in its header lines)
DEFAULT_CSV = Path(__file__).resolve().parents[1] / "data" / "edge_counts.csv"
#: a column per symmetry class: its parities in the order x1, x2, x3
CLASS_COLUMNS = tuple(a + b + c for a in "SA" for b in "SA" for c in "SA")
#: the columns of a row, in order
COLUMNS = ("alpha", "mesh", "grading", "formulation", "grad_div", "pressure", "D0", "dofs",
           "n_negative",
           "n_x2A") + CLASS_COLUMNS + ("cpu_s", "count_cpu_s", "peak_GB", "factorisations",
                                       "solver", "date", "command")
_HEADER = """\
# Negative-mode counts of the whole clamped plate at a few charges, one row per state.
# Written by validation.studies.edge_counts (the module docstring defines every column):
# eighth model, neo-Hookean, g = 9.81, grading = last / first element length along x1;
# counts by Sylvester's law of inertia (no classification: the corner quartet is 4 of them).
"""


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
        The plate (:func:`~validation.studies.clamp_units.unit_problem`).
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
    t0, f0 = time.process_time(), factorisation_count()
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
        counts = scan.count(st.x, load)
        row = {"alpha": alpha, "mesh": mesh_text(el), "grading": grading,
               "formulation": formulation, "grad_div": grad_div, "pressure": pressure,
               "D0": d, "dofs": pb.ndofs,
               "n_negative": sum(counts.values()),
               "n_x2A": sum(v for k, v in counts.items() if _column(k)[1] == "A"),
               **{_column(k): v for k, v in counts.items()},
               "count_cpu_s": round(time.process_time() - t1, 1),
               "cpu_s": round(time.process_time() - t0, 1),
               "peak_GB": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
                                / 1024**2, 3),
               "factorisations": factorisation_count() - f0, "solver": solver,
               "date": datetime.date.today().isoformat()}
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
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = fe.gallery.run_ramp(
            pb, fe.gallery.preload_then_charge(s, np.asarray(targets),
                                               fe.gallery.KEPLINGER_PRELOAD_STEPS),
            on_step=on_step, linear_solver=solver, settings=UNIT_SETTINGS)
    if not res.converged:
        raise ValueError(f"the ramp of alpha = {alpha:g} {mesh_text(el)} stopped at "
                         f"D0 = {np.asarray(res.failed_at)[-1]:g}")
    return rows


def read_edge_counts(path: Path | None = None) -> list[dict]:
    """The rows of the study's CSV (default: the package's), as dicts of strings."""
    return read_data_csv(path, "data/edge_counts.csv")


def _key(r: dict) -> tuple:
    return (*unit_key(r), f"{float(r['grad_div']):g}", str(r.get("pressure") or "Q1"),
            f"{float(r['D0']):g}")


def main(argv: list[str] | None = None) -> int:
    """Count the states ``--D0`` of the plates ``--alpha`` x ``--mesh`` not yet in ``--csv``.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default: ``sys.argv[1:]``; see the module docstring).

    Returns
    -------
    int
        0; 1 with one line where a ramp stops or ``--csv`` is another table; bad
        arguments exit with argparse's one line and code 2.
    """
    ap = argparse.ArgumentParser(prog="python -m validation.studies.edge_counts",
                                 description=__doc__.splitlines()[0])
    ap.add_argument("--alpha", type=float, nargs="+", required=True)
    ap.add_argument("--mesh", type=parse_mesh, nargs="+", required=True)
    ap.add_argument("--D0", type=float, nargs="+", required=True)
    ap.add_argument("--grading", type=float, default=1.0)
    ap.add_argument("--formulation", default="mixed")
    ap.add_argument("--grad-div", dest="grad_div", type=float, default=BUCKLING_GRAD_DIV)
    ap.add_argument("--pressure", default="Q1", choices=["Q1", "P0"])
    ap.add_argument("--solver", default="auto", choices=["auto", "superlu", "pardiso"])
    ap.add_argument("--csv", type=Path, default=DEFAULT_CSV)
    a = ap.parse_args(argv)
    if foreign_table(a.csv, COLUMNS):
        print(f"error: --csv {a.csv} is not this study's table", file=sys.stderr)
        return 1
    command = study_command("validation.studies.edge_counts", argv)
    for alpha in a.alpha:
        for el in a.mesh:
            unit = {"alpha": alpha, "mesh": mesh_text(el), "grading": a.grading,
                    "formulation": a.formulation, "grad_div": a.grad_div,
                    "pressure": a.pressure}
            done = {float(r["D0"]) for r in read_edge_counts(a.csv)
                    if _key(r)[:6] == _key({**unit, "D0": 1.0})[:6]}
            if {float(d) for d in a.D0} <= done:
                print(f"alpha = {alpha:g} {mesh_text(el)}: kept", flush=True)
                continue

            def write(row):
                row["command"] = command
                append_row(a.csv, row, COLUMNS, _HEADER)

            try:
                with blas_thread_limit(1):
                    run_edge_counts(alpha, el, a.D0, grading=a.grading,
                                    formulation=a.formulation, grad_div=a.grad_div,
                                    pressure=a.pressure, solver=a.solver, skip=done, on_row=write,
                                    progress=lambda t: print("  " + t, flush=True))
            except ValueError as exc:
                print(f"error: {exc}", file=sys.stderr)
                return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

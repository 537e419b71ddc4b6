"""Where the whole plate's flagged negative modes sit at one state of a clamp-zone unit.

The scan of :mod:`validation.studies.clamp_units` flags negative modes that are not
physical (:func:`~skfem_dielectric.models.plate.modes.classify_mode`: a clamp-corner or a
mesh-scale mode) and only counts them.  This study takes one state of a unit -- the plate
(eighth model, grad-div 10, graded along ``x1``), ramped in steps of 0.5 to ``D0`` --
analyses it from scratch (:meth:`~skfem_dielectric.models.plate.scan.PlateScan.analyse`:
every negative mode of every class computed and classified) and writes a row per negative
mode (one row of ``kind`` ``none`` where there is none): its eigenvalue, class, label
(``kind``, ``corner_share``, ``mesh_scale``) and the
energy centroid of its deflection (``X1``, ``X2``, ``X3``,
:func:`validation.studies.local_theory.energy_centroid`), with the unit's element layers
at the clamp (``layer``: 1 for the element next to the clamp, 2 the next, ...).

Rows go to a CSV (default ``validation/data/flagged_modes.csv``), one block per state
(``alpha``, mesh, ``grading``, ``D0``), written atomically when the state is analysed; a
state already there is skipped.

Usage::

    python -m validation.studies.flagged_modes --solver pardiso --alpha 1.5 --mesh 30x1x24 \\
        --grading 0.1 --D0 4.78125
"""

from __future__ import annotations

import argparse
import datetime
import math
import resource
import shlex
import sys
import time
from pathlib import Path

import numpy as np

from skfem_dielectric.fem import blas_thread_limit
from skfem_dielectric.models.plate.scan import PlateScan

from ..buckling_data import read_data_csv
from .clamp_units import append_rows, mesh_text, parse_mesh, ramp_to_charge, unit_problem
from .local_theory import energy_centroid

__all__ = ["COLUMNS", "DEFAULT_CSV", "run_flagged_modes", "read_flagged_modes", "main"]

#: where the study's rows are kept (provenance in its header lines)
DEFAULT_CSV = Path(__file__).resolve().parents[1] / "data" / "flagged_modes.csv"
#: the columns of a row, in order
COLUMNS = ("alpha", "mesh", "grading", "D0", "dofs", "eigenvalue", "class", "kind",
           "corner_share", "mesh_scale", "X1", "X2", "X3", "layer", "cpu_s", "date",
           "command")
_HEADER = """\
# The negative modes of the whole plate at one state of a clamp-zone unit, one row per mode.
# Written by validation.studies.flagged_modes (the module docstring defines every column):
# eighth model, neo-Hookean, g = 9.81, grad-div 10; energy centroid X1, X2, X3 in mm (the
# clamp at X1 = 50); layer = element layer along X1 counted from the clamp; cpu_s of the
# state's analysis.
"""


def run_flagged_modes(alpha: float, elements, D0: float, *, grading: float = 1.0,
                      solver: str = "auto") -> list[dict]:
    """The rows of one state: every negative mode of the whole plate at ``D0``.

    Parameters
    ----------
    alpha, elements, grading
        The plate of a clamp-zone unit (eighth model, mixed form, grad-div 10).
    D0
        The charge of the state (reached in steps of 0.5).
    solver
        Linear solver of the ramp.

    Returns
    -------
    list of dict
        In increasing eigenvalue; a state without negative modes has one row of
        ``kind`` ``"none"`` (the mode columns empty).

    Raises
    ------
    ValueError
        The ramp stops before ``D0``.
    """
    el = tuple(int(n) for n in elements)
    pb, s = unit_problem(alpha, el, grading=grading)
    x, load = ramp_to_charge(pb, s, D0, solver=solver,
                             name=f"alpha = {alpha:g} {mesh_text(el)}")
    t0 = time.process_time()
    row = PlateScan(pb).analyse(x, load)
    g1 = pb.plate.grids[0]
    out = []
    for m in row.labels:
        c = energy_centroid(pb, x, load, m.mode)
        layer = int(np.count_nonzero(g1 > c[0]))        # 1: inside the last element
        out.append({"alpha": alpha, "mesh": mesh_text(el), "grading": grading, "D0": D0,
                    "dofs": pb.ndofs, "eigenvalue": m.eigenvalue, "class": m.symmetry,
                    "kind": m.kind, "corner_share": m.corner_share,
                    "mesh_scale": m.mesh_scale, "X1": float(c[0]), "X2": float(c[1]),
                    "X3": float(c[2]), "layer": layer})
    if not out:                 # a state without negative modes: one row that says so
        out.append({"alpha": alpha, "mesh": mesh_text(el), "grading": grading, "D0": D0,
                    "dofs": pb.ndofs, "kind": "none"})
    cpu = round(time.process_time() - t0, 1)
    today = datetime.date.today().isoformat()
    for r in out:
        r.update(cpu_s=cpu, date=today)
    return out


def read_flagged_modes(path: Path = DEFAULT_CSV) -> list[dict]:
    """The rows of the study's CSV (comment lines skipped), as dicts of strings."""
    return read_data_csv(path)


def main(argv: list[str] | None = None) -> int:
    """Analyse the states ``--alpha`` x ``--mesh`` at ``--D0`` not yet in ``--csv``.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default: ``sys.argv[1:]``; see the module docstring).

    Returns
    -------
    int
        0; 1 with one line where the ramp stops first; bad arguments exit with argparse's
        one line and code 2.
    """
    ap = argparse.ArgumentParser(prog="python -m validation.studies.flagged_modes",
                                 description=__doc__.splitlines()[0])
    ap.add_argument("--alpha", type=float, nargs="+", required=True)
    ap.add_argument("--mesh", type=parse_mesh, nargs="+", required=True)
    ap.add_argument("--D0", type=float, required=True)
    ap.add_argument("--grading", type=float, default=1.0)
    ap.add_argument("--solver", default="auto", choices=["auto", "superlu", "pardiso"])
    ap.add_argument("--csv", type=Path, default=DEFAULT_CSV)
    a = ap.parse_args(argv)
    if not (math.isfinite(a.D0) and a.D0 > 0):
        ap.error(f"--D0 must be a positive charge, got {a.D0:g}")
    command = "python -m validation.studies.flagged_modes " + " ".join(
        shlex.quote(v) for v in (argv if argv is not None else sys.argv[1:]))
    for alpha in a.alpha:
        for el in a.mesh:
            key = (f"{alpha:g}", mesh_text(el), f"{a.grading:g}", f"{a.D0:g}")
            old = read_flagged_modes(a.csv)
            if any((f"{float(r['alpha']):g}", r["mesh"], f"{float(r['grading']):g}",
                    f"{float(r['D0']):g}") == key for r in old):
                print(f"alpha = {alpha:g} {mesh_text(el)} D0 = {a.D0:g}: kept", flush=True)
                continue
            try:
                with blas_thread_limit(1):
                    rows = run_flagged_modes(alpha, el, a.D0, grading=a.grading,
                                             solver=a.solver)
            except ValueError as exc:
                print(f"error: {exc}", file=sys.stderr)
                return 1
            append_rows(a.csv, [{**r, "command": command} for r in rows], COLUMNS,
                        _HEADER)
            kinds = {}
            for r in rows:
                if r["kind"] != "none":
                    kinds[r["kind"]] = kinds.get(r["kind"], 0) + 1
            print(f"alpha = {alpha:g} {mesh_text(el)} D0 = {a.D0:g}: "
                  f"{sum(kinds.values())} negative modes {kinds}, peak "
                  f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2:.2f} GB",
                  flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The clamp-zone wrinkle, unit by unit: one weight fraction on one (graded) mesh per unit.

A *unit* is the buckling run of the clamped Keplinger plate (eighth model, grad-div 10,
neo-Hookean, ``g = 9.81``) for one weight fraction ``alpha`` on one mesh ``n1 x n2 x n3``
with a geometric grading along ``x1`` towards the clamp (``grading`` = last / first element
length, :func:`skfem_dielectric.fem.mesh.plate_mesh`): the charge ramp in steps of
``D0_step``; every state scanned for the whole plate
(:class:`~skfem_dielectric.models.plate.scan.PlateScan`, inertia counts per symmetry
class, modes where a count changes); the ramp stops at the first physical crossing, which
is located to ``1e-4`` (:func:`~skfem_dielectric.studies.buckling.locate_buckling`).  The
unit's row holds what the mesh says about the mode there:

* ``D0_b``, the mode's class, its share at the clamp corners and its mesh scale;
* ``half_waves``: sign changes of its top-face deflection across the whole width, at its
  energy centroid (``validation.studies.local_theory.half_waves``), and
  ``elements_per_half_wave`` (the width's elements over the half-waves);
* ``J_min_clamp``, ``J_max_clamp``: ``J = det F`` at the mid-plane centres of the elements
  next to the clamp, at ``D0_b`` (an incompressible material has ``J = 1``; the discrete
  clamp layer departs from it where the mesh does not resolve it);
* ``n_flagged_b``: the negative eigenvalues of the whole plate that are not physical
  (clamp corner or mesh scale) at the last scanned state; ``scan_counts`` every scanned
  state as ``D0:negative/physical`` (in scan order, refined steps last);
* the unknowns, factorisations, CPU seconds, peak memory, solver, date and command, and a
  ``note`` where no ``D0_b`` was found (no crossing up to ``D0_max``, the ramp stopped, or a
  crossing between two states that the location could not follow).

The mode at ``D0_b`` (the top face's deflection over the whole plate) goes to
``--modes`` (default ``results/clamp-modes``, one ``.npz`` per unit, not data of the
repository); ``python -m validation.figures.clamp_modes`` draws them.

Rows go to a CSV (default ``validation/data/clamp_units.csv``), one per unit, written
atomically as soon as the unit is done; a unit whose key (``alpha``, mesh, ``grading``,
``formulation``) is already there is skipped, so a list of units run in the background
resumes where it stopped.

Usage::

    python -m validation.studies.clamp_units --alpha 1 --mesh 12x1x12 --grading 0.25
    python -m validation.studies.clamp_units --alpha 1 0.7 --mesh 12x1x12 16x1x20 --grading 0.25
    python -m validation.studies.clamp_units --tables     # the study's tables, from the data
"""

from __future__ import annotations

import argparse
import csv
import datetime
import io
import math
import resource
import shlex
import sys
import time
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.fem import blas_thread_limit
from skfem_dielectric.linalg.solver_base import factorisation_count
from skfem_dielectric.models.plate.modes import top_deflection
from skfem_dielectric.models.plate.scan import PlateScan
from skfem_dielectric.studies.buckling import locate_buckling

from ..buckling_data import (MIN_ELEMENTS_PER_HALF_WAVE, clamp_study_tables, clamp_unit_load,
                             read_clamp_units, read_data_csv, unit_key)
from ..fe.model import BUCKLING_GRAD_DIV, BUCKLING_NEWTON, BUCKLING_TOL
from ..store import write_npz_atomic, write_text_atomic
from .local_theory import energy_centroid, half_waves, local_state

__all__ = ["COLUMNS", "DEFAULT_CSV", "MIN_ELEMENTS_PER_HALF_WAVE", "UNIT_SETTINGS",
           "run_unit", "read_units", "clamp_unit_load", "mesh_text", "parse_mesh",
           "append_row", "append_rows", "foreign_table", "study_command", "unit_problem",
           "ramp_states", "ramp_to_charge", "clamp_centre_J", "main"]

#: where the study's rows are kept (provenance in its header lines)
DEFAULT_CSV = Path(__file__).resolve().parents[1] / "data" / "clamp_units.csv"
#: the columns of a unit's row, in order
COLUMNS = ("alpha", "mesh", "grading", "formulation", "dofs", "D0_step", "D0_b", "class",
           "corner_share", "mesh_scale", "half_waves", "elements_per_half_wave",
           "J_min_clamp", "J_max_clamp", "n_flagged_b", "states", "factorisations",
           "cpu_s", "peak_GB", "solver", "date", "scan_counts", "note", "command")
_HEADER = """\
# The clamp-zone wrinkle of the Keplinger plate, unit by unit (one alpha on one mesh per row).
# Written by validation.studies.clamp_units (the module docstring defines every column):
# eighth model, neo-Hookean, g = 9.81, grad-div 10, grading = last / first element length
# along x1 (towards the clamp); D0_b located to 1e-4; J at the mid-plane centres of the
# elements next to the clamp at D0_b; cpu_s and peak_GB of the unit's process.
"""


#: Newton settings of a unit's ramps: the Keplinger plate's, with more cut-backs and
#: iterations (the graded clamp layer)
UNIT_SETTINGS = replace(fe.gallery.KEPLINGER_SETTINGS, max_cutbacks=6, max_iter=25)


def unit_problem(alpha: float, elements, *, grading: float = 1.0,
                 formulation: str = "mixed", grad_div: float = BUCKLING_GRAD_DIV,
                 pressure: str = "Q1"):
    """The plate of a unit and its dead load: ``(problem, s)``.

    The clamped Keplinger plate, eighth model, graded along ``x1`` (``grading``), grad-div
    ``grad_div`` (default :data:`~validation.fe.model.BUCKLING_GRAD_DIV`), ``J = 1`` imposed
    as ``formulation`` with the pressure space ``pressure`` (``"Q1"`` or ``"P0"``,
    :class:`~skfem_dielectric.gallery.plates.PlateOptions`); ``s`` of weight fraction
    ``alpha`` with ``g = 9.81``.
    """
    options = fe.PlateOptions(grad_div=grad_div, formulation=formulation, pressure=pressure)
    pb = fe.gallery.keplinger_problem(elements=tuple(int(n) for n in elements),
                                      symmetry="eighth", grading=grading, options=options)
    return pb, fe.gallery.keplinger_s(alpha, g=9.81)


def ramp_states(problem, s: float, D0: float, *, solver: str = "auto",
                name: str = "") -> list[tuple[float, np.ndarray, np.ndarray]]:
    """The converged states ``(D0_i, x, load)`` of a unit's ramp to the charge ``D0``: the
    dead load ``s`` in the Keplinger pre-load steps (its end is ``D0_i = 0``), then the
    charge in steps of 0.5 and ``D0`` (:data:`UNIT_SETTINGS`), in the ramp's order.

    Raises
    ------
    ValueError
        The ramp stops before ``D0`` (the message names the ramp as ``name``).
    """
    D0 = float(D0)
    targets = [d for d in np.round(np.arange(0.5, D0, 0.5), 10) if d < D0 - 1e-9] + [D0]
    states = {}

    def on_step(step):
        if step.target_reached and step.load[0] == s:
            states[float(step.load[1])] = (float(step.load[1]), step.x, step.load)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = fe.gallery.run_ramp(
            problem, fe.gallery.preload_then_charge(s, np.asarray(targets),
                                                    fe.gallery.KEPLINGER_PRELOAD_STEPS),
            on_step=on_step, linear_solver=solver, settings=UNIT_SETTINGS)
    if not res.converged or D0 not in states:
        raise ValueError(f"the ramp{' of ' + name if name else ''} stopped before "
                         f"D0 = {D0:g}")
    return [states[d] for d in sorted(states)]


def ramp_to_charge(problem, s: float, D0: float, *, solver: str = "auto", name: str = ""):
    """The converged state ``(x, load)`` at charge ``D0`` of a unit's plate: the last of
    :func:`ramp_states`.

    Raises
    ------
    ValueError
        The ramp stops before ``D0`` (the message names the ramp as ``name``).
    """
    _, x, load = ramp_states(problem, s, D0, solver=solver, name=name)[-1]
    return x, load


def mesh_text(elements) -> str:
    """``(n1, n2, n3)`` as the study writes it, ``"n1xn2xn3"``."""
    return "x".join(str(int(n)) for n in elements)


def clamp_centre_J(pb, x, load) -> tuple[float, float]:
    """Smallest and largest ``J`` at the mid-plane centres of the elements next to the
    clamp (eighth model: the last element along ``x1``, every element across ``x3``)."""
    g1, _, g3 = pb.plate.grids
    X1 = 0.5 * (g1[-1] + g1[-2])
    Js = [local_state(pb, x, load, np.array([X1, 0.0, 0.5 * (a + b)])).J
          for a, b in zip(g3[:-1], g3[1:])]
    return float(min(Js)), float(max(Js))


class _Crossed(Exception):
    pass


def run_unit(alpha: float, elements, *, grading: float = 1.0, D0_step: float = 0.5,
             D0_max: float = 6.0, formulation: str = "mixed", solver: str = "auto",
             progress=None, modes_dir: Path | None = None) -> dict:
    """One unit of the study: the row of :data:`COLUMNS` (module docstring).

    Parameters
    ----------
    alpha
        Weight fraction (``> 0``).
    elements
        ``(n1, n2, n3)`` of the eighth model.
    grading
        Last / first element length along ``x1`` (``< 1``: finer at the clamp).
    D0_step, D0_max
        The charge targets ``D0_step, 2 D0_step, ..., D0_max``; the ramp stops at the
        first scanned state with a negative physical mode.  Where several physical modes
        crossed in one step, or the location cannot follow the crossing, that step is
        scanned again in four (at most twice: steps down to ``D0_step / 16``).
    formulation
        How ``J = 1`` is imposed (:class:`~skfem_dielectric.gallery.plates.PlateOptions`).
    solver
        Linear solver of the ramps and trial states.
    progress
        Optional ``progress(text)`` called once per scanned state.
    modes_dir
        Where to write the mode at ``D0_b`` (``<alpha>_<mesh>_g<grading>_<formulation>.npz``:
        the top face's deflection over the whole plate, ``X1``, ``X3``, ``u2``, as
        :func:`~skfem_dielectric.models.plate.modes.top_deflection`); ``None``: not written.

    Returns
    -------
    dict
        ``D0_b`` is ``nan`` (and the mode columns empty) when no physical mode crossed up
        to ``D0_max`` or the ramp stopped first.
    """
    t0, f0 = time.process_time(), factorisation_count()
    el = tuple(int(n) for n in elements)
    pb, s = unit_problem(alpha, el, grading=grading, formulation=formulation)
    track = {"prev": None, "before": None, "row": None, "cur": None, "states": 0,
             "counts": []}

    def on_step(step):
        load = np.asarray(step.load, dtype=float)
        if not step.target_reached or load[0] != s:
            return
        before = scan.state
        row = scan.analyse(step.x, load)
        track["states"] += 1
        track["counts"].append(f"{load[1]:g}:{row.n_negative}/{row.n_physical}")
        if progress is not None:
            progress(f"D0 = {load[1]:.4f}: {row.n_negative} negative, {row.n_physical} "
                     f"physical, {row.cpu:.1f} CPU s")
        if row.n_physical > 0 and track["prev"] is not None:
            track.update(before=before, row=row, cur=(step.x, load, step.back))
            raise _Crossed
        track["prev"] = (step.x, load, step.back)

    def ramp_to(targets, start=None):
        track["row"] = None
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                res = fe.gallery.run_ramp(
                    pb, targets, on_step=on_step, linear_solver=solver, settings=UNIT_SETTINGS,
                    **({} if start is None else dict(x0=start[0], start=start[1],
                                                     back=start[2])))
        except _Crossed:
            return ""
        return "" if res.converged else \
            f"ramp stopped at D0 = {np.asarray(res.failed_at)[-1]:g}"

    # the charge ramp in steps of D0_step, scanned at every target, up to the first state
    # with a physical negative mode; then the located crossing.  A step in which several
    # physical modes crossed, or whose crossing the location cannot follow, is scanned
    # again in four steps (twice at most)
    scan = PlateScan(pb)
    D0 = np.round(np.arange(D0_step, D0_max + 1e-9, D0_step), 10)
    stopped = ramp_to(fe.gallery.preload_then_charge(s, D0, fe.gallery.KEPLINGER_PRELOAD_STEPS))
    bl, step = None, D0_step
    method = "pardiso" if solver == "pardiso" else "auto"
    for refine in range(3):
        if track["row"] is None:
            break
        prev, cur, before, row = track["prev"], track["cur"], track["before"], track["row"]
        lo, hi = float(prev[1][1]), float(cur[1][1])
        try:
            if row.n_physical > 1 and refine < 2:
                raise ValueError(f"{row.n_physical} physical modes crossed at once")
            bl = locate_buckling(pb, prev[:2], cur[:2], row.new_physical, counts=before,
                                 method=method, tol=BUCKLING_TOL, linear_solver=solver,
                                 settings=BUCKLING_NEWTON)
            break
        except ValueError as exc:   # a result: the crossing between lo and hi, unlocated
            stopped = f"physical crossing between D0 = {lo:g} and {hi:g} not located: {exc}"
            if refine == 2:
                break
            step /= 4.0
            scan = PlateScan(pb, state=before)
            fine = [np.array([s, d]) for d in np.round(lo + step * np.arange(0, 5), 10)]
            stopped = ramp_to(fine, start=prev) or stopped
    row = {"alpha": alpha, "mesh": mesh_text(el), "grading": grading,
           "formulation": formulation, "dofs": pb.ndofs, "D0_step": D0_step,
           "states": track["states"], "scan_counts": " ".join(track["counts"])}
    if bl is not None:
        stopped = ""
        lab = bl.label
        point = energy_centroid(pb, bl.x, bl.load, lab.mode)
        n_half = half_waves(pb, lab.mode, lab.increments, point[0])
        jmin, jmax = clamp_centre_J(pb, bl.x, bl.load)
        n3 = el[2] * (2 if 3 in pb.plate.symmetry else 1)
        row.update(D0_b=float(bl.D0_b), **{"class": lab.symmetry},
                   corner_share=lab.corner_share, mesh_scale=lab.mesh_scale,
                   half_waves=n_half, elements_per_half_wave=n3 / n_half,
                   J_min_clamp=jmin, J_max_clamp=jmax,
                   n_flagged_b=track["row"].n_negative - track["row"].n_physical)
        if modes_dir is not None:
            X1, X3, u2 = top_deflection(pb, lab.mode, lab.increments)
            Path(modes_dir).mkdir(parents=True, exist_ok=True)
            write_npz_atomic(Path(modes_dir) / f"{alpha:g}_{mesh_text(el)}_g{grading:g}_"
                                               f"{formulation}.npz",
                             X1=X1, X3=X3, u2=u2, D0_b=float(bl.D0_b))
    else:
        row.update(D0_b=math.nan, n_flagged_b=(track["row"].n_negative - track["row"].n_physical
                                                if track["row"] is not None else ""),
                   note=stopped or f"no physical crossing up to D0 = {D0_max:g}")
    row.update(factorisations=factorisation_count() - f0,
               cpu_s=round(time.process_time() - t0, 1),
               peak_GB=round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2, 3),
               solver=solver, date=datetime.date.today().isoformat())
    return row


def read_units(path: Path = DEFAULT_CSV) -> list[dict]:
    """The rows of the study's CSV (comment lines skipped), as dicts of strings."""
    return read_clamp_units(path)


def _cell(v) -> str:
    if isinstance(v, float):
        return "" if not math.isfinite(v) else f"{v:.6g}"
    return str(v)


def append_rows(path: Path, rows, columns=COLUMNS, header: str = _HEADER) -> None:
    """Rewrite a study's CSV atomically: ``header`` (``#`` lines), ``columns``, the rows it
    holds, then ``rows`` (floats to 6 digits, ``nan`` as an empty cell)."""
    buf = io.StringIO()
    w = csv.DictWriter(buf, columns, restval="", extrasaction="ignore", lineterminator="\n")
    w.writeheader()
    w.writerows(read_data_csv(path) + [{k: _cell(r.get(k, "")) for k in columns}
                                       for r in rows])
    write_text_atomic(path, header + buf.getvalue())


def foreign_table(path: Path, columns) -> bool:
    """Whether ``path`` exists and is not a table of ``columns`` (a folder, or a file whose
    rows have other columns): a study must not rewrite it."""
    path = Path(path)
    if not path.exists():
        return False
    if not path.is_file():
        return True
    rows = read_data_csv(path)
    return bool(rows) and set(rows[0]) != set(columns)


def study_command(module: str, argv: list[str] | None) -> str:
    """The command line of a study's run, as its rows record it: ``python -m module``
    and ``argv`` (default: the process's own arguments), quoted for a shell."""
    return f"python -m {module} " + " ".join(
        shlex.quote(v) for v in (argv if argv is not None else sys.argv[1:]))


def append_row(path: Path, row: dict, columns=COLUMNS, header: str = _HEADER) -> None:
    """:func:`append_rows` of one row."""
    append_rows(path, [row], columns, header)


def parse_mesh(text: str) -> tuple[int, int, int]:
    """``"n1xn2xn3"`` as ``(n1, n2, n3)`` (positive counts), for ``argparse``: an
    ``argparse.ArgumentTypeError`` naming the text otherwise."""
    try:
        n = tuple(int(v) for v in text.split("x"))
    except ValueError:
        n = ()
    if len(n) != 3 or min(n) < 1:
        raise argparse.ArgumentTypeError(f"a mesh is n1xn2xn3 with positive counts, "
                                         f"got {text!r}")
    return n


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
    ap = argparse.ArgumentParser(prog="python -m validation.studies.clamp_units",
                                 description=__doc__.splitlines()[0])
    ap.add_argument("--alpha", type=float, nargs="+")
    ap.add_argument("--mesh", type=parse_mesh, nargs="+")
    ap.add_argument("--tables", action="store_true",
                    help="print the study's tables (Markdown) from the data files and stop")
    ap.add_argument("--grading", type=float, default=1.0)
    ap.add_argument("--formulation", default="mixed")
    ap.add_argument("--D0-step", dest="D0_step", type=float, default=0.5)
    ap.add_argument("--D0-max", dest="D0_max", type=float, default=6.0)
    ap.add_argument("--solver", default="auto", choices=["auto", "superlu", "pardiso"])
    ap.add_argument("--csv", type=Path, default=DEFAULT_CSV)
    ap.add_argument("--modes", type=Path, default=Path("results") / "clamp-modes",
                    help="folder of the modes at D0_b (default results/clamp-modes)")
    a = ap.parse_args(argv)
    if a.tables:
        sys.stdout.write(clamp_study_tables())
        return 0
    if not a.alpha or not a.mesh:
        ap.error("--alpha and --mesh are required (or --tables)")
    command = "python -m validation.studies.clamp_units " + " ".join(
        shlex.quote(v) for v in (argv if argv is not None else sys.argv[1:]))
    for alpha in a.alpha:
        for el in a.mesh:
            row_key = unit_key({"alpha": alpha, "mesh": mesh_text(el),
                                "grading": a.grading, "formulation": a.formulation})
            if any(unit_key(r) == row_key for r in read_units(a.csv)):
                print(f"alpha = {alpha:g} {mesh_text(el)} grading {a.grading:g}: kept",
                      flush=True)
                continue
            with blas_thread_limit(1):      # as the command line (docs/performance.md)
                row = run_unit(alpha, el, grading=a.grading, D0_step=a.D0_step,
                               D0_max=a.D0_max, formulation=a.formulation, solver=a.solver,
                               progress=lambda t: print("  " + t, flush=True),
                               modes_dir=a.modes)
            row["command"] = command
            append_row(a.csv, row)
            print(f"alpha = {alpha:g} {mesh_text(el)} grading {a.grading:g}: D0_b "
                  f"{row['D0_b']:.4f} {row.get('note', '')}, "
                  f"{row.get('half_waves', '')} half-waves, "
                  f"{row['dofs']} DOFs, {row['cpu_s']} CPU s, {row['peak_GB']} GB",
                  flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

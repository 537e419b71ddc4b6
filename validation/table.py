"""The tidy CSV of a case: its columns, the text of a cell, the row of one converged (or
failed) target with the analytic stretches beside the FE ones, and :func:`read_table`.

A row compares the FE stretches with the homogeneous theory at the run's own load
(Eq. (loading_gent), Eq. (DEuniax)); the breakdown column is the paper's ``P33``
criterion (:data:`BREAKDOWN_TOL`).  No FE import: the tables are read (figures, report)
without the finite elements.
"""

from __future__ import annotations

import csv

import numpy as np

import analytic as an

from .cases import analytic_model
from .records import StepRecord
from .specs import Case, RunSpec

__all__ = ["BREAKDOWN_TOL", "FIELD_KEYS", "csv_columns", "format_cell", "analytic_lams",
           "is_breakdown", "case_row", "read_table"]

#: The paper's breakdown: ``min P33/mu`` along the centre line (which runs into
#: the clamps), outside the clamps' boundary layer of width ``2H`` (column
#: ``min_P33_interior``), below ``-BREAKDOWN_TOL``. In the central zone ``P33`` is close
#: to its homogeneous value 0; on coarse meshes it scatters by a few 1e-3
#: around it, while at the breakdown it drops by about 0.2 within one
#: ``D0`` step of 0.5, so ``1e-2`` separates the two.
BREAKDOWN_TOL = 1e-2

_FMT = ".12g"   # 12 significant digits (and at most 12 decimals) in the CSV


def csv_columns(case: Case) -> list[str]:
    """Columns of ``DIR/<case>.csv``.

    The run (``case``, ``run``, ``step``, ``model``, ``variant``, ``alpha`` for the
    uni-axial cases, ``s``), the load ``D0``, FE and analytic stretches at the plate
    centre, the ``P33/mu`` minima, the verdicts ``converged``, ``stable``, the stability
    counts ``n_negative`` (negative eigenvalues of the reduced stiffness), ``n_unstable``
    (those not classified as clamp-corner artefacts) and ``lowest_eig``, ``breakdown`` and
    the Newton ``iterations``; the uni-axial cases also the whole plate's spectrum of the
    runs that analyse it (``n_negative_plate``, ``physical_eig``, ``physical_class``, see
    :func:`validation.fe.plate_buckling_columns`; empty for the others); a case with such
    a run (``RunSpec.buckling``) also ``D0_b``, the run's buckling load located to
    ``1e-4`` where that eigenvalue crosses zero, on the row of the first state past it.
    In such a run the whole plate's columns, ``stable`` and ``D0_b`` are of its grad-div
    form's state at the row's load, every other column of its plain state.

    Parameters
    ----------
    case : Case

    Returns
    -------
    list of str
    """
    cols = ["case", "run", "step", "model", "variant"]
    if case.geometry == "uniaxial":
        cols.append("alpha")
    cols += ["s", "D0", "lam1_fe", "lam1_analytic", "lam3_fe", "lam3_analytic", "min_P33",
             "min_P33_interior", "min_P33_clamp", "converged", "stable", "n_negative",
             "n_unstable", "lowest_eig", "breakdown", "iterations"]
    if case.geometry == "uniaxial":
        cols += ["n_negative_plate", "physical_eig", "physical_class"]
    if any(r.buckling for r in case.quick + case.full):
        cols.append("D0_b")
    return cols


def format_cell(x) -> str:
    """The CSV text of one cell: empty for ``None``, ``True``/``False``, integers as
    integers, strings as they are, floats to 12 significant digits and 12 decimals at
    most (empty if not finite)."""
    if x is None:
        return ""
    if isinstance(x, (bool, np.bool_)):
        return "True" if x else "False"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, str):
        return x
    x = float(x)
    if not np.isfinite(x):
        return ""
    # 12 significant digits and at most 12 decimals: round-off noise (P33 ~ 1e-15 on a
    # homogeneous plate, last bits of threaded BLAS sums) does not reach the file
    return format(round(x, 12) + 0.0, _FMT)


def analytic_lams(spec: RunSpec, D0: float) -> tuple[float, float]:
    """``(lam1, lam3)`` of the homogeneous theory: Eq. (loading_gent) or Eq. (DEuniax)."""
    model = analytic_model(spec.model)
    if spec.geometry == "equibiaxial":
        lam = float(an.equibiaxial_lam(D0, spec.s, model))
        return lam, lam
    lam1 = float(an.uniaxial_lam1(D0, spec.s, model))
    lam3 = float(an.uniaxial_lam3(lam1, spec.s, model)) if np.isfinite(lam1) else float("nan")
    return lam1, lam3


def is_breakdown(spec: RunSpec, rec: StepRecord) -> bool:
    """The ``breakdown`` flag of a uni-axial state: its ``min_P33_interior`` (else
    ``min_P33``) is below ``-BREAKDOWN_TOL``; always ``False`` for other geometries."""
    if spec.geometry != "uniaxial":
        return False
    p = rec.min_P33_interior if np.isfinite(rec.min_P33_interior) else rec.min_P33
    return bool(np.isfinite(p) and p < -BREAKDOWN_TOL)


def case_row(case: Case, spec: RunSpec, index: int, rec: StepRecord | None, converged: bool,
         breakdown: bool, D0: float) -> list[str]:
    """The CSV row of one target ``D0`` of run ``spec`` (:func:`csv_columns` order):
    the FE record ``rec`` (``None`` for a target not reached), the analytic stretches and
    the flags."""
    lam1_an, lam3_an = analytic_lams(spec, D0)
    vals = {"case": case.name, "run": spec.key, "step": index, "model": spec.model,
            "variant": spec.variant, "alpha": spec.alpha, "s": spec.s, "D0": D0,
            "lam1_fe": rec.lam1 if rec else None, "lam1_analytic": lam1_an,
            "lam3_fe": rec.lam3 if rec else None, "lam3_analytic": lam3_an,
            "min_P33": rec.min_P33 if rec else None,
            "min_P33_interior": rec.min_P33_interior if rec else None,
            "min_P33_clamp": rec.min_P33_clamp if rec else None,
            "converged": converged, "stable": rec.stable if rec else None,
            "n_negative": rec.n_negative if rec else None,
            "n_unstable": rec.n_unstable if rec else None,
            "lowest_eig": rec.lowest_eig if rec else None,
            "breakdown": breakdown, "iterations": rec.iterations if rec else None,
            "n_negative_plate": rec.n_negative_plate if rec else None,
            "physical_eig": rec.physical_eig if rec else None,
            "physical_class": rec.physical_class if rec else None,
            "D0_b": rec.D0_b if rec else None}
    return [format_cell(vals[c]) for c in csv_columns(case)]




#: Verdict columns: always bool/None, also when every cell is empty (e.g. ``stable``
#: without PARDISO), so that a table's column types do not depend on its content.
_BOOL_COLUMNS = frozenset({"converged", "stable", "breakdown"})


def read_table(path) -> dict[str, np.ndarray]:
    """Read a tidy CSV written by the harness into columns.

    Numeric columns become float arrays (empty cells ``nan``), ``True``/``False``
    columns (and always ``converged``, ``stable``, ``breakdown``) become object arrays of
    bool/None, the others string arrays. Rows with another number of cells than the
    header (a line cut short by a crash) are left out.
    """
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    if not rows:
        return {}
    header = rows[0]
    body = [r for r in rows[1:] if len(r) == len(header)]   # a half-written line is no row
    table = {}
    for j, name in enumerate(header):
        col = [r[j] for r in body]
        if name in _BOOL_COLUMNS or (col and all(v in ("True", "False", "") for v in col)
                                     and any(col)):
            table[name] = np.array([None if v == "" else v == "True" for v in col], dtype=object)
            continue
        try:
            table[name] = np.array([float(v) if v != "" else np.nan for v in col], dtype=float)
        except ValueError:
            table[name] = np.array(col, dtype=str)
    return table



FIELD_KEYS = ["case", "run", "step", "D0"]


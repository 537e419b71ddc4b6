"""Cases of ``skfem-dielectric validate`` that are not charge ramps.

The registered :data:`~validation.cases.CASES` are FE charge ramps drawn over a paper
figure.  The cases here compute other things -- the continuation through the voltage-
controlled snap-through (:mod:`validation.studies.voltage_control`) and the FE wrinkling of the
cross-section against the Stroh analysis (:mod:`validation.studies.wrinkling`) -- and report one
error measure with its own tolerance.  Each writes ``DIR/<name>.csv`` and the figure
``DIR/<name>.png|pdf``, with the caption line of the case figures
(:func:`validation.figures.run_caption`).
"""

from __future__ import annotations

import csv
import math
import time
from dataclasses import dataclass
from typing import Callable

from .voltage_control import (LIMIT_TOL, VOLTAGE_CONTROL, VOLTAGE_TITLE, run_voltage_control,
                              voltage_runs)
from ..progress import notice
from .wrinkling import run_wrinkling_fe, wrinkling_fe_runs

__all__ = ["ExtraCase", "EXTRA_CASES", "WRINKLING_FE", "WRINKLING_TOL"]

WRINKLING_FE = "wrinkling-fe"
#: relative error of the FE critical D0 (or stretch) against the dispersion relation
WRINKLING_TOL = 1e-3


@dataclass(frozen=True)
class ExtraCase:
    """A validation case that is not a charge ramp.

    Attributes
    ----------
    name, figure, title
        Case name (file stem), what it compares with, one-line description.
    tolerance
        Tolerance of its error measure.
    error_note
        One sentence for the report: what its error measure is.
    run
        ``run(out, quick, force) -> (paths, summary)`` with ``summary`` holding
        ``n_runs``, ``n_points``, ``max_rel_error``, ``max_rel_error_by_run``,
        ``reasons``, ``runtime_s``, ``repairs`` (one line per row a resume dropped and
        recomputed, each also written to stderr) and ``resumed`` (rows kept from an
        earlier run, said in one line on stderr).  It holds the case's lock
        (``out/.state/<name>.lock``, a :class:`~validation.store.StudyStore`) while it
        writes: a second process writing the case into ``out`` is refused.
    count
        ``count(quick) -> int``: its number of FE runs (for ``skfem-dielectric list``).
    """

    name: str
    figure: str
    title: str
    tolerance: float
    error_note: str
    run: Callable
    count: Callable


def _notes() -> tuple[list[str], Callable]:
    """The repairs of a run and ``note(message)``, which keeps one and writes it to
    stderr."""
    repairs: list[str] = []

    def note(msg: str) -> None:
        repairs.append(msg)
        notice(msg)

    return repairs, note


def _run_voltage(out, quick: bool = False, force: bool = False):
    repairs, note = _notes()
    paths, summary = run_voltage_control(out, quick=quick, note=note, say=notice, force=force)
    return paths, {**summary, "repairs": repairs}


def _run_wrinkling(out, quick: bool = False, force: bool = False):
    t0 = time.perf_counter()
    repairs, note = _notes()
    computed = []
    paths = run_wrinkling_fe(out, quick=quick, on_row=computed.append,
                             on_elastic_row=computed.append, note=note, say=notice,
                             force=force)
    with open(paths[0], newline="") as fh:
        lines = list(csv.DictReader(fh))
    with open(paths[1], newline="") as fh:
        elastic = list(csv.DictReader(fh))
    runs = [(f"{r['control']} {r['mode']} lam={r['lam']} kh={r['kh']}", r["rel_error"],
             r["note"]) for r in lines]
    runs += [(f"D0=0 {r['mode']} kh={r['kh']}", r["rel_error"], r["note"]) for r in elastic]
    errors, reasons = {}, {}
    for key, err, why in runs:
        if err:
            errors[key] = abs(float(err))
        elif not why.startswith("no root"):
            reasons[key] = why
            errors[key] = math.inf
    return paths, {"n_runs": _wrinkling_count(quick), "n_points": len(runs),
                   "max_rel_error": max(errors.values()) if errors else None,
                   "max_rel_error_by_run": errors, "reasons": reasons,
                   "runtime_s": time.perf_counter() - t0, "repairs": repairs,
                   "resumed": len(runs) - len(computed)}


def _wrinkling_count(quick: bool) -> int:
    """The FE runs of the case (:func:`~.wrinkling.wrinkling_fe_runs`): the number that
    ``skfem-dielectric list`` shows and ``summary.json``/``report.md`` report."""
    return len(wrinkling_fe_runs(quick))


EXTRA_CASES: dict[str, ExtraCase] = {c.name: c for c in (
    ExtraCase(VOLTAGE_CONTROL, "Hessian: nh-d-e, gent-d-e, figde", VOLTAGE_TITLE, LIMIT_TOL,
              f"For {VOLTAGE_CONTROL} the error is that of lam1 at the limit points (maximum "
              "of E0 under voltage control) of the homogeneous plates against "
              "analytic.max_E0.", _run_voltage,
              lambda quick: len(voltage_runs(quick))),
    ExtraCase(WRINKLING_FE, "Sec. 3 (Stroh)", "FE wrinkling of the cross-section (sliding "
              "ends, one Fourier mode) against the Stroh dispersion relation: charge and "
              "voltage control, both modes, and the uncharged compressed plate",
              WRINKLING_TOL, f"For {WRINKLING_FE} the error is that of the critical D0 (the "
              "critical stretch at D0 = 0) against the root of the dispersion relation.",
              _run_wrinkling, _wrinkling_count),
)}

"""The summary of a case, computed from its CSV (so identical after a resume), and the
results of every case present in an output folder."""

from __future__ import annotations

import csv
import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .cases import CASES
from .studies.extra_cases import EXTRA_CASES
from .specs import Case
from .store import case_manifest
from .table import read_table

__all__ = ["CaseResult", "summarise_case", "folder_results"]


@dataclass
class CaseResult:
    """Summary of one case, computed from its CSV (so identical after a resume)."""

    name: str
    figure: str
    csv: str
    n_runs: int
    n_steps: int
    max_rel_error: float | None
    max_rel_error_by_run: dict = field(default_factory=dict)
    breakdown_D0: dict = field(default_factory=dict)
    breakdown_D0_by_alpha: dict = field(default_factory=dict)
    buckling_D0: dict = field(default_factory=dict)
    buckling_D0_by_alpha: dict = field(default_factory=dict)
    reasons: dict = field(default_factory=dict)
    runtime_s: float = 0.0
    resumed_steps: int = 0
    quick: bool | None = None
    repairs: list = field(default_factory=list)


def summarise_case(case: Case, csv_path: Path, n_runs: int) -> CaseResult:
    """Errors and breakdown points of a case, from its CSV."""
    res = CaseResult(name=case.name, figure=case.figure, csv=csv_path.name, n_runs=n_runs,
                     n_steps=0, max_rel_error=None)
    if not csv_path.exists():
        return res
    t = read_table(csv_path)
    if not t or not len(t["run"]):
        return res
    res.n_steps = len(t["run"])
    conv = np.array([bool(c) for c in t["converged"]])
    err = np.abs(t["lam1_fe"] - t["lam1_analytic"]) / t["lam1_analytic"]
    ok = conv & np.isfinite(err)
    if ok.any():
        res.max_rel_error = float(np.max(err[ok]))
    for key in map(str, dict.fromkeys(t["run"])):
        sel = t["run"] == key
        e = err[sel & ok]
        res.max_rel_error_by_run[key] = float(e.max()) if e.size else None
        brk = np.array([bool(b) for b in t["breakdown"][sel]])
        if brk.any():
            res.breakdown_D0[key] = float(t["D0"][sel][np.argmax(brk)])
        else:
            res.breakdown_D0[key] = None
        if "alpha" in t and np.isfinite(t["alpha"][sel][0]):
            variant = str(t["variant"][sel][0])
            res.breakdown_D0_by_alpha.setdefault(variant, {})[format(t["alpha"][sel][0], "g")] = \
                res.breakdown_D0[key]
        if "D0_b" in t and np.isfinite(t["n_negative_plate"][sel]).any():
            located = t["D0_b"][sel][np.isfinite(t["D0_b"][sel])]
            res.buckling_D0[key] = float(located[0]) if located.size else None
            res.buckling_D0_by_alpha.setdefault(str(t["variant"][sel][0]), {})[
                format(t["alpha"][sel][0], "g")] = res.buckling_D0[key]
        fails = ~conv[sel]
        if fails.any():
            res.reasons[key] = f"no convergence at D0 = {t['D0'][sel][np.argmax(fails)]:g}"
    return res



def folder_results(out, results=()) -> list[CaseResult]:
    """The results of every case present in ``out``: ``results`` and, for the other cases
    with a CSV there, the summary computed from that CSV.

    Parameters
    ----------
    out : path-like
        Output folder of earlier :func:`validate` or :func:`run_case` calls.
    results : sequence of CaseResult
        Fresh results (they replace what the folder says about their cases).

    Returns
    -------
    list of CaseResult
        Registered cases in the order of :data:`~validation.cases.CASES`, then any
        other case of ``results``. Runtime and resumed steps of a case not in
        ``results`` come from the ``summary.json`` already in ``out`` (else 0).
    """
    out = Path(out)
    fresh = {r.name: r for r in results}
    try:
        prev = json.loads((out / "summary.json").read_text())["cases"]
        prev = prev if isinstance(prev, dict) else {}
    except (OSError, ValueError, KeyError, TypeError):
        prev = {}
    every = []
    for name, case in CASES.items():
        if name in fresh:
            every.append(fresh[name])
            continue
        csv_path = out / f"{name}.csv"
        if not csv_path.is_file():
            continue
        try:
            saved = json.loads((out / ".state" / name / "manifest.json").read_text())
        except (OSError, ValueError):
            saved = None
        quick = None if saved is None else saved == case_manifest(case, case.runs(True))
        n_runs = len(saved["runs"]) if isinstance(saved, dict) and "runs" in saved \
            else len(case.runs(bool(quick)))
        try:
            r = summarise_case(case, csv_path, n_runs=n_runs)
        except (OSError, ValueError, csv.Error, UnicodeDecodeError):
            continue
        old = prev.get(name) if isinstance(prev.get(name), dict) else {}
        r.runtime_s = float(old.get("runtime_s", 0.0) or 0.0)
        r.resumed_steps = int(old.get("resumed_steps", 0) or 0)
        r.quick = old.get("quick") if isinstance(old.get("quick"), bool) else quick
        every.append(r)
    every += [r for r in results if r.name not in CASES]
    for name in EXTRA_CASES:
        old = prev.get(name)
        if name not in fresh and isinstance(old, dict) and (out / f"{name}.csv").is_file():
            try:
                r = CaseResult(**{k: old[k] for k in CaseResult.__dataclass_fields__
                                  if k in old})
            except TypeError:
                continue
            r.csv = f"{name}.csv"       # relative to the folder (an earlier version's path)
            every.append(r)
    return every



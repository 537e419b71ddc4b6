"""``summary.json`` and a short human-readable ``report.md`` of a validation run."""

from __future__ import annotations

import json
from dataclasses import asdict
from pathlib import Path

from .cases import get_case
from .store import write_text_atomic

__all__ = ["summary_dict", "write_summary", "write_report"]


def summary_dict(results, *, quick: bool) -> dict:
    """Per case: max relative FE-analytic error of ``lam1``, breakdown ``D0`` per run, runtime.

    Parameters
    ----------
    results : sequence of CaseResult
    quick : bool
        Whether these were ``--quick`` runs.

    Returns
    -------
    dict
        JSON-serialisable; ``breakdown_D0`` maps each run to the first ``D0``
        where ``min P33/mu`` on the centre line fell below ``-0.01`` (or the
        solver stopped), else ``None``; for the uni-axial cases
        ``breakdown_D0_by_alpha`` holds the same per variant and ``alpha``.
    """
    cases = {}
    for r in results:
        d = asdict(r)
        d["title"] = get_case(r.name).title
        cases[r.name] = d
    return {"quick": bool(quick),
            "error_measure": "max over converged steps of |lam1_fe - lam1_analytic| / lam1_analytic",
            "cases": cases}


def write_summary(results, folder, *, quick: bool) -> Path:
    """Write ``folder/summary.json`` atomically (see :func:`summary_dict`).

    Parameters
    ----------
    results : sequence of CaseResult
    folder : path-like
    quick : bool

    Returns
    -------
    Path
    """
    path = Path(folder) / "summary.json"
    return write_text_atomic(path, json.dumps(summary_dict(results, quick=quick), indent=2,
                                              sort_keys=True) + "\n")


def _g(x, fmt=".2e"):
    # The CSV keeps 12 significant digits, so an error of exactly 0 means "below 1e-11".
    if x is None:
        return "-"
    return "< 1e-11" if x == 0 else format(x, fmt)


def write_report(results, folder, *, quick: bool) -> Path:
    """Write ``folder/report.md``: one table row per case and the breakdown points.

    Parameters
    ----------
    results : sequence of CaseResult
        Every case to report (:func:`validation.sweep.folder_results`).
    folder : path-like
        Output folder.
    quick : bool
        Whether this invocation ran ``--quick`` (the title, for results that do not say).

    Returns
    -------
    Path
    """
    kinds = {quick if r.quick is None else r.quick for r in results} or {quick}
    kind = "quick and full runs" if len(kinds) > 1 else f"{'quick' if kinds.pop() else 'full'} run"
    lines = [f"# skfem-dielectric validation ({kind})", "",
             "| case | paper figure | FE runs | FE steps | max rel. error lam1 | runtime (s) |",
             "| --- | --- | --- | --- | --- | --- |"]
    for r in results:
        lines.append(f"| {r.name} | {r.figure} | {r.n_runs} | {r.n_steps} | "
                     f"{_g(r.max_rel_error)} | {r.runtime_s:.1f} |")
    brk = [(r.name, k, v) for r in results for k, v in r.breakdown_D0.items()
           if k.startswith("uniaxial_")]
    if brk:
        lines += ["", "Breakdown (first step with P33/mu < -0.01 on the centre line, at least "
                  "2 thicknesses from the clamps):", ""]
        lines += [f"- {name} / {k}: " + ("none up to the last D0" if v is None else f"D0 = {v:g}")
                  for name, k, v in brk]
    fails = [(r.name, k, v) for r in results for k, v in r.reasons.items()]
    if fails:
        lines += ["", "Runs that stopped (solver):", ""]
        lines += [f"- {name} / {k}: {v}" for name, k, v in fails]
    lines += ["", "Files: `<case>.csv` (one row per FE step), `<case>.png|pdf`, "
              "`summary.json`; `.state/` holds resume states."]
    return write_text_atomic(Path(folder) / "report.md", "\n".join(lines) + "\n")

"""``summary.json`` and a short human-readable ``report.md`` of a validation run."""

from __future__ import annotations

import json
from dataclasses import asdict
from pathlib import Path

from .cases import get_case
from .clamp_zone.tables import breakdown_numbers
from .figures import PAPER_FIGURE
from .markers import BREAKDOWN_MEANINGS
from .store import write_text_atomic
from .studies.extra_cases import EXTRA_CASES

__all__ = ["summary_dict", "write_summary", "write_report", "verdict_lines", "HOMOGENEOUS_TOL",
           "CLAMPED_TOL", "CASE_FIGURES", "case_figures"]


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
        ``breakdown_D0_by_alpha`` holds the same per variant and ``alpha``, and
        ``buckling_D0`` / ``buckling_D0_by_alpha`` the buckling load ``D0_b`` of the runs
        analysed with the whole plate's spectrum (``None`` where no physical negative
        eigenvalue appeared).
    """
    cases = {}
    for r in results:
        d = asdict(r)
        d["title"] = _title(r.name)
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


#: Verdict tolerances on the error measure of ``summary_dict``: a homogeneous state (one
#: element) must reproduce the closed form to the Newton tolerance; the centre of the
#: clamped Keplinger plate follows the homogeneous curve within 1 % (the paper, Sec. 6).
HOMOGENEOUS_TOL = 1e-8
CLAMPED_TOL = 1e-2

_ERROR_DEFINITION = (
    "Error: the largest, over the converged FE steps of a case, of "
    "|lam1_fe - lam1_analytic| / lam1_analytic, where lam1_fe is the FE stretch at the plate "
    "centre and lam1_analytic the homogeneous theory at the same s and D0 (Eq. loading_gent "
    "equi-biaxially, Eq. DEuniax uni-axially). The CSV keeps 12 significant digits, so an "
    "error below 1e-11 is shown as < 1e-11.")


#: The figures a case's results draw besides its own ``<case>.png``: ``{case: ((stem,
#: caption), ...)}``; ``validate`` draws the breakdown map from the uni-axial-ideal case
#: (:func:`validation.sweep.make_breakdown_map`, docs/breakdown.md).
CASE_FIGURES = {
    "uni-axial-ideal": (("breakdown-map", "the breakdown map: the run's P33 breakdowns, "
                         "buckling loads and solver failures per weight against the "
                         "converged buckling loads (docs/breakdown.md)"),),
}


def case_figures(name: str) -> list[tuple[str, str]]:
    """``(file name, caption)`` of every PNG the results of case ``name`` draw into the
    output folder: ``<case>.png`` and those of :data:`CASE_FIGURES`.

    Examples
    --------
    >>> [f for f, _ in case_figures("uni-axial-ideal")]
    ['uni-axial-ideal.png', 'breakdown-map.png']
    """
    return ([(f"{name}.png", f"{name}: {_title(name)}")]
            + [(f"{stem}.png", f"{stem}: {caption}")
               for stem, caption in CASE_FIGURES.get(name, ())])


def _title(name: str) -> str:
    return EXTRA_CASES[name].title if name in EXTRA_CASES else get_case(name).title


def _tolerance(name: str) -> float:
    """The verdict tolerance of a case: homogeneous (every run on one element) or clamped;
    for ``voltage-control`` that of its homogeneous limit points."""
    if name in EXTRA_CASES:
        return EXTRA_CASES[name].tolerance
    runs = get_case(name).quick + get_case(name).full
    homogeneous = all(r.mesh_dict == {"n1": 1, "n2": 1, "n3": 1} for r in runs)
    return HOMOGENEOUS_TOL if homogeneous else CLAMPED_TOL


def _verdict(err, tol) -> str:
    if err is None:
        return "no FE step"
    return "pass" if err <= tol else "**FAIL**"


def verdict_lines(results) -> list[str]:
    """One line per case for the end of a run: its verdict against its tolerance.

    Parameters
    ----------
    results : sequence of CaseResult

    Returns
    -------
    list of str

    Examples
    --------
    >>> from validation.sweep import CaseResult
    >>> verdict_lines([CaseResult("nh-d-e", "fig:nh-d-e", "nh-d-e.csv", 12, 84, 9.3e-11)])
    ['nh-d-e: pass (max rel. error 9.30e-11, tolerance 1e-08, 84 FE steps)']
    """
    out = []
    for r in results:
        tol = _tolerance(r.name)
        verdict = _verdict(r.max_rel_error, tol).strip("*").lower()
        err = "" if r.max_rel_error is None else \
            f"max rel. error {_g(r.max_rel_error)}, tolerance {tol:g}, "
        out.append(f"{r.name}: {verdict} ({err}{r.n_steps} FE steps)")
    return out


def meaning_lines() -> list[str]:
    """The lines of report.md on the three meanings of "breakdown"
    (:data:`~validation.markers.BREAKDOWN_MEANINGS`) and their order as located on the meshes
    that resolve the clamp layer (:func:`~validation.clamp_zone.tables.breakdown_numbers`,
    the table of docs/breakdown.md).

    Returns
    -------
    list of str
    """
    out = ["", "What \"breakdown\" means (docs/breakdown.md): three things, met in this "
           "order as the charge grows:", ""]
    out += [f"{i}. **{name}**: {text}." for i, (name, text) in
            enumerate(BREAKDOWN_MEANINGS, 1)]
    out += ["", "This run's values above are read on its own charge steps and its own coarse "
            "mesh: its P33 step can lie above the converged D0_b, and its D0_b is the "
            "coarse mesh's (too low for the heavier weights, whose clamp-zone wrinkle the "
            "mesh cannot hold).  Located to 1e-4 on meshes graded towards the clamp (the "
            "shipped data; `skfem-dielectric clamp-zone tables --breakdown`):", "",
            "| alpha | P33 onset (interior) | D0_b | Newton limit |", "| --- | --- | --- | --- |"]
    for n in breakdown_numbers():
        out.append(f"| {n['alpha']:g} | {n['interior']:.4f} | {n['D0_b']:.4f} | "
                   + (f"{n['newton_limit']:g} |" if n["newton_limit"] == n["newton_limit"]
                      else "none |"))
    return out


def write_report(results, folder, *, quick: bool) -> Path:
    """Write ``folder/report.md``: what the error is, one table row per case with its
    verdict against the stated tolerance, the breakdown points and a link to every figure
    of the cases in the folder (:func:`case_figures`).

    Parameters
    ----------
    results : sequence of CaseResult
        Every case to report (:func:`validation.results.folder_results`).
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
             _ERROR_DEFINITION + f" Tolerances: {HOMOGENEOUS_TOL:g} for the homogeneous "
             f"cases (one element, any FE model), {CLAMPED_TOL:g} (1 %) for the clamped "
             "Keplinger plate." + "".join(
                 f" {c.error_note} Tolerance {c.tolerance:g}." for c in EXTRA_CASES.values()
                 if any(r.name == c.name for r in results)), "",
             "| case | paper figure | FE runs | FE steps | max rel. error lam1 | tolerance "
             "| verdict | runtime (s) |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in results:
        tol = _tolerance(r.name)
        fig = f"Fig. {PAPER_FIGURE[r.name]} ({r.figure.removeprefix('fig:')})" \
            if r.name in PAPER_FIGURE else r.figure
        lines.append(f"| {r.name} | {fig} | {r.n_runs} | {r.n_steps} | "
                     f"{_g(r.max_rel_error)} | {tol:g} | {_verdict(r.max_rel_error, tol)} | "
                     f"{r.runtime_s:.1f} |")
    brk = [(r.name, k, v) for r in results for k, v in r.breakdown_D0.items()
           if k.startswith("uniaxial_")]
    if brk:
        lines += ["", "Breakdown (first step with P33/mu < -0.01 on the centre line, at least "
                  "2 thicknesses from the clamps):", ""]
        lines += [f"- {name} / {k}: " + ("none up to the last D0" if v is None else f"D0 = {v:g}")
                  for name, k, v in brk]
    bk = [(r.name, k, v) for r in results for k, v in getattr(r, "buckling_D0", {}).items()]
    if bk:
        lines += ["", "Buckling load D0_b (FE stability: where the lowest eigenvalue of the whole "
                  "plate whose mode is classified physical crosses zero, located to 1e-4, on "
                  "that run's mesh - the quick run's is coarse and not mesh-converged; the "
                  "mesh study is `skfem-dielectric buckling`):", ""]
        lines += [f"- {name} / {k}: " + ("no physical negative eigenvalue up to the last D0"
                                         if v is None else f"D0_b = {v:.4f}")
                  for name, k, v in bk]
    if brk or bk:
        lines += meaning_lines()
    fails = [(r.name, k, v) for r in results for k, v in r.reasons.items()]
    if fails:
        lines += ["", "Runs that stopped (solver):", ""]
        lines += [f"- {name} / {k}: {v}" for name, k, v in fails]
    lines += ["", "## Figures", ""]
    for r in results:
        for png, caption in case_figures(r.name):
            if (Path(folder) / png).exists():
                lines += [f"![{caption}]({png})", ""]
    lines += ["Files: `<case>.csv` (one row per FE step), `<case>.png|pdf`, "
              + "".join(f"`{stem}.png|pdf` (with {name}), " for name in CASE_FIGURES
                        if any(r.name == name for r in results)
                        for stem, _ in CASE_FIGURES[name])
              + "`summary.json`; `.state/` holds resume states."]
    return write_text_atomic(Path(folder) / "report.md", "\n".join(lines) + "\n")

"""The figures and files of ``skfem-dielectric check``: *their* dots on *our* curves.

:func:`check_figure` draws one figure per case of a :class:`~validation.checker.CheckResult`
with the closed-form curves of the paper's figure (the plotting functions of
:mod:`validation.figures`: Figs. nh-d-e, gent-d-e, gent-equi-biaxial, figde,
uni-axial-ideal) and, on top, the checked rows: a dot in the colour of its curve, an
orange X for a row beyond its tolerance (``beyond its tolerance``).  :func:`write_check_report` renders every figure
first and then writes ``<case>.png``, ``check.md`` and ``check.json`` into the report
folder, each file atomically, so that a failure leaves no half of a report.
"""

from __future__ import annotations

import io
import json
import math
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.ticker import NullFormatter, ScalarFormatter

import analytic as an
from analytic.units import keplinger_s

from .cases import analytic_model
from .checker import TOLERANCE_SOURCES, CaseCheck, CheckResult
from .figures import (BUCKLING_NAME, LIMIT_NAME, add_caption, plot_equibiaxial_loading,
                      plot_equibiaxial_wrinkling, plot_uniaxial_loading,
                      plot_uniaxial_wrinkling, tag_panels)
from .figures.common import colors
from .figures.uniaxial_wrinkling import reference_layer
from .markers import BEYOND_TOLERANCE, MODE_LINES, line_style
from .specs import KEPLINGER

__all__ = ["check_figure", "report_markdown", "report_json", "write_check_report"]

_DOT = dict(marker="o", ms=5, mec="k", mew=0.6, ls="none", zorder=6, clip_on=False)
_BAD = dict(BEYOND_TOLERANCE.style, ls="none", clip_on=False)


def _legend_extra(case: CaseCheck) -> list:
    files = ", ".join(case.files)
    out = [Line2D([], [], color="0.6", label=f"checked: {files}"[:60], **_DOT)]
    if not case.passed:
        out.append(Line2D([], [], label=BEYOND_TOLERANCE.name, **_BAD))
    return out


def _relegend(ax, case, loc="lower right"):
    handles, _ = ax.get_legend_handles_labels()
    if ax.get_legend() is not None:
        handles = list(ax.get_legend().legend_handles)
    ax.legend(handles=handles + _legend_extra(case), fontsize=7, loc=loc)


#: the largest stretch, D0 and wavenumber a figure's axes reach (rows beyond are scored,
#: not drawn)
_LAM_CAP, _D0_CAP, _KH_CAP = 20.0, 100.0, 1e3
#: the most curves (values of s or alpha) a panel draws
_MAX_CURVES = 12


def _upper(values, floor: float, cap: float) -> float:
    """The top of an axis: ``floor``, raised to 1.05 x the largest finite value, at most
    ``cap``."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    return float(min(max(floor, 1.05 * v.max() if v.size else floor), cap))


def _dots(ax, x, y, ok, color):
    """Dots of the rows within tolerance (in ``color``), an orange X
    (:data:`~validation.markers.BEYOND_TOLERANCE`) for the others; rows far outside the axes
    (or not finite) are not drawn."""
    x, y, ok = np.asarray(x, dtype=float), np.asarray(y, dtype=float), np.asarray(ok, bool)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    with np.errstate(invalid="ignore"):
        inside = (np.isfinite(x) & np.isfinite(y) & (x >= 2 * x0 - x1) & (x <= 2 * x1 - x0)
                  & (y >= 2 * y0 - y1) & (y <= 2 * y1 - y0))
    if (ok & inside).any():
        ax.plot(x[ok & inside], y[ok & inside], color=color, **_DOT)
    if (~ok & inside).any():
        ax.plot(x[~ok & inside], y[~ok & inside], **_BAD)


def _s_values(s) -> list[float]:
    """The distinct values of ``s`` (or ``alpha``), at most :data:`_MAX_CURVES` of them
    (spread over the range) for the curves."""
    v = sorted({round(float(x), 9) for x in s if math.isfinite(x) and abs(x) <= 1e3})
    if len(v) > _MAX_CURVES:
        v = [v[int(i)] for i in np.linspace(0, len(v) - 1, _MAX_CURVES).round()]
    return v


def _loading_panels(case: CaseCheck):
    pt = case.points
    models = sorted(set(pt["model"]))
    wrinkling = case.name == "gent-equi-biaxial"
    ncol = len(models) * (1 if wrinkling else 2)
    fig, axes = plt.subplots(1, ncol, figsize=(6.2 * ncol, 4.8), layout="constrained",
                             squeeze=False)
    axes = list(axes.ravel())
    E0 = pt["D0"] / (pt["lam1"] * pt["lam3"]) ** 2
    k = 0
    for model in models:
        sel = pt["model"] == model
        s_values = _s_values(pt["s"][sel])
        lam_max = _upper(pt["lam1"][sel], 5.0, _LAM_CAP)
        quantities = (None,) if wrinkling else ("D0", "E0")
        for q in quantities:
            ax = axes[k]
            k += 1
            if wrinkling:
                plot_equibiaxial_wrinkling(model, s_values, ax=ax,
                                           D0max=_upper(pt["D0"][sel], 8.0, _D0_CAP))
            elif pt["kind"] == "equibiaxial":
                plot_equibiaxial_loading(model, s_values, q, ax=ax, lam_max=lam_max)
            else:
                plot_uniaxial_loading(model, s_values, q, ax=ax, lam1_max=max(6.0, lam_max))
            y = pt["D0"][sel] if q in (None, "D0") else E0[sel]
            lo, hi = ax.get_ylim()
            ax.set_ylim(lo, _upper(y, hi, _D0_CAP if q != "E0" else 10.0))
            y = pt["D0"] if q in (None, "D0") else E0
            drawn = np.zeros(len(y), dtype=bool)
            for s, c in zip(s_values, colors(len(s_values))):
                rows = sel & np.isclose(pt["s"], s, rtol=0, atol=1e-9)
                drawn |= rows
                _dots(ax, pt["lam1"][rows], y[rows], pt["ok"][rows], c)
            rest = sel & ~drawn                   # an s without its curve: grey dots
            _dots(ax, pt["lam1"][rest], y[rest], pt["ok"][rest], "0.6")
            _relegend(ax, case, "lower right" if q != "E0" else "upper right")
    tag_panels(axes)
    return fig


def _clamped_panel(case: CaseCheck):
    pt = case.points
    buck = pt.get("buckling", [])
    alphas = _s_values(list(pt.get("alpha", ())) + [a for a, _, _ in buck])
    fig, ax = plt.subplots(figsize=(10, 5.4), layout="constrained")
    D0max = _upper(pt.get("D0", ()), 7.0, _D0_CAP)
    plot_uniaxial_wrinkling(fe=None, alphas=tuple(alphas), ax=ax, D0max=D0max)
    m = analytic_model("neo-Hookean")
    handles = list(ax.get_legend().legend_handles)
    for a, c in zip(alphas, colors(len(alphas))):
        if "alpha" in pt:
            rows = np.isclose(pt["alpha"], a, rtol=0, atol=1e-9)
            _dots(ax, pt["lam1"][rows], pt["D0"][rows], pt["ok"][rows], c)
    handles += reference_layer(ax, alphas, D0max)       # the converged study, as validate's
    if buck:
        for a, D0b, ok in buck:
            s = float(keplinger_s(a, g=KEPLINGER["g"]))
            x = float(an.uniaxial_lam1(D0b, s, m))
            if not ok:      # the orange X larger, behind: the checked value shows through
                ax.plot(x, D0b, gid="beyond-tolerance", **{**_BAD, "ms": 18, "zorder": 8})
            ax.plot(x, D0b, marker="P", ms=10, color="C2", mec="k", ls="none", zorder=9,
                    gid="checked-buckling")
        handles.append(Line2D([], [], ls="none", marker="P", ms=10, color="C2", mec="k",
                              label=f"checked {BUCKLING_NAME} $D_{{0b}}$ (on the "
                                    f"homogeneous curve)"))
    ax.legend(handles=handles + _legend_extra(case), fontsize=7, loc="center left",
              bbox_to_anchor=(1.01, 0.5))
    return fig


def _voltage_panels(case: CaseCheck):
    pt = case.points
    keys = sorted({(ld, mo) for ld, mo in zip(pt["loading"], pt["model"])})
    fig, axes = plt.subplots(1, len(keys), figsize=(6.2 * len(keys), 4.8),
                             layout="constrained", squeeze=False)
    axes = list(axes.ravel())
    E0 = pt["D0"] / (pt["lam1"] * pt["lam3"]) ** 2
    for ax, (ld, mo) in zip(axes, keys):
        sel = (pt["loading"] == ld) & (pt["model"] == mo)
        s_values = _s_values(pt["s"][sel])
        lam_max = _upper(pt["lam1"][sel], 5.0 if ld == "equibiaxial" else 6.0, _LAM_CAP)
        if ld == "equibiaxial":
            plot_equibiaxial_loading(mo, s_values, "E0", ax=ax, lam_max=lam_max)
        else:
            plot_uniaxial_loading(mo, s_values, "E0", ax=ax, lam1_max=lam_max)
        drawn = np.zeros(len(E0), dtype=bool)
        for s, c in zip(s_values, colors(len(s_values))):
            rows = sel & np.isclose(pt["s"], s, rtol=0, atol=1e-9)
            drawn |= rows
            _dots(ax, pt["lam1"][rows], E0[rows], pt["ok"][rows], c)
        rest = sel & ~drawn
        _dots(ax, pt["lam1"][rest], E0[rest], pt["ok"][rest], "0.6")
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        for l_, m_, s_, l1, e0, ok in pt.get("limits", ()):
            if l_ == ld and m_ == mo and x0 <= l1 <= x1 and y0 <= e0 <= y1:
                ax.plot(l1, e0, **(dict(marker="*", ms=15, color="gold", mec="k",
                                        ls="none", zorder=9) if ok else _BAD))
        handles = list(ax.get_legend().legend_handles)
        handles.append(Line2D([], [], marker="*", ms=12, color="gold", mec="k", ls="none",
                              label=f"checked {LIMIT_NAME}"))
        ax.legend(handles=handles + _legend_extra(case), fontsize=7, loc="lower right")
    tag_panels(axes)
    return fig


def _wrinkling_panels(case: CaseCheck):
    pt = case.points
    controls = [c for c in ("charge", "voltage") if c in set(pt["control"])]
    fig, axes = plt.subplots(1, len(controls), figsize=(6.2 * len(controls), 4.8),
                             layout="constrained", squeeze=False)
    axes = list(axes.ravel())
    lams = [v for v in _s_values(pt["lam"]) if 0.05 <= v <= 10.0]
    palette = dict(zip(lams, colors(len(lams))))
    kh = np.geomspace(max(min(0.3, 0.8 * float(pt["kh"].min())), 1e-2),
                      min(max(8.0, 1.25 * float(pt["kh"].max())), _KH_CAP), 60)
    for ax, control in zip(axes, controls):
        for lam in lams:
            for mode in sorted(set(pt["mode"])):
                ax.plot(kh, an.critical_D0(lam, kh, mode=mode, control=control),
                        color=palette[lam], lw=1.2, label=f"Stroh, $\\lambda = {lam:g}$, {mode}",
                        **line_style(MODE_LINES[mode]))
                rows = ((pt["control"] == control) & np.isclose(pt["lam"], lam, rtol=0,
                                                                 atol=1e-9)
                        & (pt["mode"] == mode))
                _dots(ax, pt["kh"][rows], pt["D0"][rows], pt["ok"][rows], palette[lam])
        ax.set_xscale("log")
        ax.set_xlim(kh[0], kh[-1])
        ax.xaxis.set_major_formatter(ScalarFormatter())
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel(r"$kh$ (deformed thickness)")
        ax.set_ylabel(r"critical $D_0$")
        ax.set_title(f"{control} control", fontsize=10)
        _relegend(ax, case, "upper right")
    tag_panels(axes)
    return fig


_PANELS = {"equibiaxial": _loading_panels, "uniaxial-free": _loading_panels,
           "clamped": _clamped_panel, "voltage": _voltage_panels,
           "wrinkling": _wrinkling_panels}


def check_figure(case: CaseCheck):
    """The figure of one checked case: our closed-form curves with their rows on top.

    The curves are those of the paper's figure of the case (Eq. loading_gent and
    Eq. DEuniax with the ``det H* = 0`` locus, the wrinkling limits, the Keplinger plate's
    curves with the converged study's reference layer of
    :func:`validation.figures.uniaxial_wrinkling.reference_layer`; the dispersion relation for
    ``wrinkling-fe``), drawn by :mod:`validation.figures` at the file's own ``s`` (or
    ``alpha``) values; an orange X marks a row beyond its tolerance.  The caption line
    names the files and the verdict.

    Parameters
    ----------
    case : CaseCheck

    Returns
    -------
    matplotlib Figure
    """
    try:
        fig = _PANELS[case.points["kind"]](case)
        fig.canvas.draw()                              # a layout that cannot be drawn fails here
    except (ValueError, ArithmeticError) as exc:      # rows beyond what can be drawn
        plt.close("all")
        fig = plt.figure(figsize=(8, 3), layout="constrained")
        fig.text(0.5, 0.5, f"no figure: the rows lie where the curves cannot be drawn\n"
                           f"({' '.join(str(exc).split())[:120]})", ha="center", va="center")
    fig.suptitle(f"skfem-dielectric check: {case.name} -- "
                 f"{'pass' if case.passed else 'FAIL'}", fontsize=11)
    m = case.worst
    add_caption(fig, f"Lines: the closed forms; dots: the rows of {', '.join(case.files)}; "
                     f"worst measure {m.name}: {m.error_text()} (tolerance {m.tol:g}).")
    return fig


def _png(fig) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def report_markdown(result: CheckResult, figures=()) -> str:
    """The text of ``check.md``: the verdicts, every measure with its worst row, what a
    failure looks like, the rows and files not scored, the tolerances and their sources,
    the figures.

    Parameters
    ----------
    result : CheckResult
    figures : iterable of str
        The PNG names to show.

    Returns
    -------
    str
    """
    n = sum(c.passed for c in result.cases)
    lines = [f"# skfem-dielectric check of {result.path}", "",
             f"{n} of {len(result.cases)} cases pass.  Each row of a results CSV is scored "
             "against the closed forms at its own loads; a measure's error is that of its "
             "worst row (docs/check.md).", "", result.table(), ""]
    fails = [(c, m) for c in result.cases for m in c.measures if not m.passed]
    if fails:
        lines += ["## Failures", ""]
        lines += [f"- {c.name} / {m.name}: {m.n_failed} of {m.n} rows beyond {m.tol:g}; "
                  f"worst {m.where}: {m.detail}. {m.diagnosis}" for c, m in fails]
        lines.append("")
    if result.notes:
        lines += ["## Not scored", ""] + [f"- {note}" for note in result.notes] + [""]
    lines += ["## Tolerances", ""]
    lines += [f"- `{k}` = {v:g}: {TOLERANCE_SOURCES[k]}" for k, v in result.tolerances.items()]
    lines.append("")
    if figures:
        lines += ["## Figures", ""] + [f"![{f[:-4]}]({f})\n" for f in figures]
    return "\n".join(lines).rstrip() + "\n"


def _finite(x):
    return x if isinstance(x, float) and math.isfinite(x) else (None if isinstance(x, float)
                                                                else x)


def report_json(result: CheckResult) -> str:
    """The text of ``check.json``: per case its verdict, files, measures (error, tolerance,
    worst row, detail, diagnosis; an infinite error is ``null``) and notes."""
    cases = {c.name: {"passed": c.passed, "files": list(c.files), "notes": list(c.notes),
                      "measures": [{"name": m.name, "what": m.what, "rows": m.n,
                                    "error": _finite(m.error), "tolerance": m.tol,
                                    "failed_rows": m.n_failed, "passed": m.passed,
                                    "worst_row": m.where, "detail": m.detail,
                                    "diagnosis": m.diagnosis} for m in c.measures]}
             for c in result.cases}
    return json.dumps({"path": result.path, "passed": result.passed,
                       "tolerances": result.tolerances, "cases": cases,
                       "notes": list(result.notes)}, indent=2) + "\n"


def _stage(path: Path, data: bytes) -> Path:
    """``data`` written and synced to a temporary file beside ``path``; its path."""
    tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
    try:
        with open(tmp, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return tmp


def write_check_report(result: CheckResult, out) -> list[Path]:
    """Write the report of ``result`` into ``out``: ``<case>.png`` per case, ``check.md``
    and ``check.json``.

    Every figure and text is made before the folder is created or a file written; every
    file is then written to a temporary file beside its place (``fsync``), and only when
    all are written do they replace the old ones, ``check.md`` and ``check.json`` last: a
    failed write leaves the folder as it was, and no report sits beside the figures of
    another check.

    Parameters
    ----------
    result : CheckResult
    out : path-like
        The report folder (created); it may not be the checked folder, whose
        ``<case>.png`` are the figures of ``validate``.

    Returns
    -------
    list of Path
        The files written.

    Raises
    ------
    ValueError
        ``out`` is the checked folder.
    OSError
        A file cannot be written.
    """
    out = Path(out)
    checked = Path(result.path)
    checked = checked if checked.is_dir() else checked.parent
    if out.resolve() == checked.resolve():
        raise ValueError(f"--out must not be the checked folder {result.path}: its "
                         f"<case>.png would be overwritten; give another folder")
    pngs = {f"{c.name}.png": _png(check_figure(c)) for c in result.cases}
    texts = {"check.md": report_markdown(result, list(pngs)), "check.json": report_json(result)}
    files = {**pngs, **{name: text.encode() for name, text in texts.items()}}
    out.mkdir(parents=True, exist_ok=True)
    # every file is staged beside its place first: a failed write changes nothing.  Then
    # the old report goes, the figures take their places and the report comes last, so
    # that no report ever sits beside figures of another check
    staged: dict[Path, Path] = {}
    try:
        for name, data in files.items():
            staged[out / name] = _stage(out / name, data)
        for name in texts:
            (out / name).unlink(missing_ok=True)
        for path, tmp in staged.items():
            os.replace(tmp, path)
    finally:
        for tmp in staged.values():
            tmp.unlink(missing_ok=True)
    return list(staged)

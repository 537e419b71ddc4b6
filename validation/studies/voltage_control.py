"""The case ``voltage-control``: the paper's contrast of charge and voltage control, by FE.

Each run follows a plate under voltage control at a fixed dead load ``s`` by
pseudo-arclength continuation (:func:`skfem_dielectric.solvers.continuation.continuation`) through
the maximum of ``E0`` -- the snap-through, ``det H* = 0`` (Sec. 3.1; Sec. 5, Fig. figde) --
and on along the branch a voltage ramp cannot reach.  At every state it counts the
negative eigenvalues of the voltage-controlled reduced stiffness (``n_unstable``) and,
for the homogeneous plates, of the charge-controlled one at the same state
(``n_negative_charge``): the paper's Hessian result is that the first changes at the
limit point and the second stays zero.

Runs: the homogeneous equi-biaxial plate (neo-Hookean ``s = 0, 1, 2, 3``, Fig. nh-d-e;
Gent ``s = 0, 1, 2.3, 3``, Fig. gent-d-e), the homogeneous uni-axial dead load
(neo-Hookean ``s = 0 ... 3``, Fig. figde), and in full runs the clamped Keplinger plate
per ``alpha`` (coarse mesh); quick runs only the neo-Hookean ``s = 1`` plate under each
homogeneous loading.  The limit point of each run is compared with
:func:`analytic.max_E0`.  Written as ``DIR/voltage-control.csv`` (one row per point of
a path) and ``DIR/voltage-control.png|pdf`` (charge against voltage: FE dots on the
analytic loading curves and the ``det H* = 0`` locus; titles, legends and the caption
line name only the paths drawn, with the names of :mod:`validation.figures`).  The rows
are kept in a :class:`validation.store.StudyStore` (lock ``.state/voltage-control.lock``),
one unit per path: a rerun with the same settings keeps the paths written and computes
the others, so that an interrupted run resumes to the files of an uninterrupted one.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import replace
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D

import analytic as an
import skfem_dielectric as fe
from skfem_dielectric.gallery.loads import keplinger_s
from skfem_dielectric.studies import SNAP_THROUGH_SETTINGS

from ..fe.model import BUCKLING_GRAD_DIV
from ..cases import analytic_model
from ..figures import (MODEL_NAME, PAPER_FIGURE, add_caption, mesh_caption,
                      run_caption, save_figure, tag_panels)
from ..markers import (LIMIT_POINT, STABLE_STATE, UNSTABLE_STATE, VOLTAGE_LIMIT_LOCUS,
                       legend_style, line_style)
from ..specs import ALPHAS, KEPLINGER
from ..data.spec import TableSpec
from ..store import StudyStore

__all__ = ["VOLTAGE_CONTROL", "VOLTAGE_COLUMNS", "RUN_COLUMNS", "POINTS", "RUNS", "LIMIT_TOL",
           "voltage_runs", "voltage_rows",
           "voltage_figure", "voltage_caption", "run_voltage_control"]

VOLTAGE_CONTROL = "voltage-control"
VOLTAGE_TITLE = ("charge vs voltage through the snap-through: FE continuation, limit points "
                 "against max E0, stability counts under voltage and charge control")
VOLTAGE_COLUMNS = ["case", "run", "point", "model", "loading", "variant", "s", "alpha", "kind",
                   "branch", "lam1_fe", "E0", "E0_analytic", "D0", "n_unstable",
                   "n_negative_charge", "stable", "stable_charge", "lam1_max_fe", "E0_max_fe",
                   "lam1_max_analytic", "E0_max_analytic", "iterations", "note"]
#: the resume table (one row per path, written after the path's points; below ``.state``)
RUN_COLUMNS = ["run", "model", "loading", "s", "alpha", "n_points"]
#: the files of the case (:class:`~validation.store.StudyStore`), a path the unit
POINTS = TableSpec.plain(f"{VOLTAGE_CONTROL}.csv", tuple(VOLTAGE_COLUMNS), ("run",))
RUNS = TableSpec.plain(f".state/{VOLTAGE_CONTROL}-runs.csv", tuple(RUN_COLUMNS), ("run",))
#: verdict tolerance on the relative lam1 error of the homogeneous limit points (the
#: stated target is 1e-4 in lam1 and 1e-6 in E0; the limit point is located to
#: ``|dE0/ds| <= 1e-9``, so the measured errors are near 1e-10)
LIMIT_TOL = 1e-6
#: Keplinger plate under voltage control: elements of the eighth model
KEPLINGER_MESH = (10, 1, 5)


def voltage_runs(quick: bool = False) -> list[dict]:
    """The runs: ``model``, ``loading``, ``s``, ``alpha`` (``None`` for homogeneous)."""
    if quick:
        return [dict(model="neo-Hookean", loading=ld, s=1.0, alpha=None)
                for ld in ("equibiaxial", "uniaxial-free")]
    runs = [dict(model="neo-Hookean", loading="equibiaxial", s=float(s), alpha=None)
            for s in (0, 1, 2, 3)]
    runs += [dict(model="Gent", loading="equibiaxial", s=float(s), alpha=None)
             for s in (0, 1, 2.3, 3)]
    runs += [dict(model="neo-Hookean", loading="uniaxial-free", s=float(s), alpha=None)
             for s in (0, 1, 2, 3)]
    runs += [dict(model="neo-Hookean", loading="uniaxial", s=keplinger_s(a, g=KEPLINGER["g"]),
                  alpha=a)
             for a in ALPHAS]
    return runs


def _run_key(r: dict) -> str:
    tag = f"a{r['alpha']:g}" if r["alpha"] is not None else f"s{r['s']:g}"
    return f"{r['loading']}_{'nh' if r['model'] == 'neo-Hookean' else 'gent'}_{tag}"


def _analytic_E0(r: dict, lam1):
    model = analytic_model(r["model"])
    if r["loading"] == "equibiaxial":
        return an.equibiaxial_E0(lam1, r["s"], model)
    return an.uniaxial_E0(lam1, r["s"], model)


def _keplinger_path(r: dict, quick: bool) -> tuple:
    """Voltage-controlled Keplinger plate: pre-load, then continuation in ``E0``; the
    mixed form with the clamp-zone units' grad-div weight (the plain form lets the clamp
    layer's discrete ``J`` collapse and snaps early, docs/clamp-zone.md)."""
    pb = fe.gallery.keplinger_problem(
        elements=KEPLINGER_MESH,
        options=fe.PlateOptions(control="voltage", grad_div=BUCKLING_GRAD_DIV))
    pre = fe.gallery.run_ramp(pb, [np.array([r["s"] * k / 4, 0.0]) for k in range(1, 5)])
    lam0 = pre.steps[-1]["lam1"] if pre.steps else 1.0

    def count(x, load):
        return fe.stability.tangent_stability(pb, pb.assemble(x, load)[0]).n_negative

    path = fe.continuation(pb, np.array([r["s"], 0.0]), np.array([0.0, 1.0]),
                           x0=pre.x if pre.steps else None, count=count,
                           stop=lambda p: p.tangent_t < 0 or p["lam1"] > 2 * lam0,
                           settings=fe.ContinuationSettings(ds=0.05, max_steps=60))
    return path, [None] * len(path.points), [np.sign(p.t) * p["D0_centre"]
                                             for p in path.points]


def _rows_of(r: dict, quick: bool) -> list[list]:
    key = _run_key(r)
    model = analytic_model(r["model"])
    aload = "equibiaxial" if r["loading"] == "equibiaxial" else "uniaxial"
    lam_a, E0_a = (float(v) for v in an.max_E0(r["s"], model, loading=aload))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)    # a stopped path is data
        if r["alpha"] is None:
            st = fe.studies.voltage_snap_through(r["s"], loading=r["loading"], model=r["model"],
                                                 lam_factor=1.5 if quick else 2.0,
                                                 settings=replace(SNAP_THROUGH_SETTINGS,
                                                                  ds=0.1 if quick else 0.05))
            path, n_c, D0 = st.path, st.n_negative_charge, list(st.D0)
        else:
            path, n_c, D0 = _keplinger_path(r, quick)
    lims = path.limit_points
    lam_fe = float(lims[0]["lam1"]) if lims else math.nan
    E0_fe = float(lims[0].t) if lims else math.nan
    rows, seen_limit = [], False
    for i, p in enumerate(path.points):
        if p.kind == "limit":
            branch, seen_limit = "limit", True
        else:
            branch = "falling" if seen_limit or p.tangent_t < 0 else "rising"
        nv = p.n_negative
        rows.append([VOLTAGE_CONTROL, key, i, r["model"], r["loading"], "coupled", r["s"],
                     r["alpha"], p.kind, branch, p["lam1"], p.t,
                     float(_analytic_E0(r, p["lam1"])), D0[i], nv, n_c[i],
                     None if nv is None else nv == 0,
                     None if n_c[i] is None else n_c[i] == 0, lam_fe, E0_fe, lam_a, E0_a,
                     p.iterations, _note(p, i == len(path.points) - 1, path)])
    return rows


def _note(p, last: bool, path) -> str:
    if p.kind == "limit" and "lam1_mean" in p.quantities:
        return (f"lam1_mean = {p['lam1_mean']:.6g}, min_P33 = {p['min_P33']:.3g}, "
                f"lam2 = {p['lam2']:.6g} at the centre")
    return path.reason if last else ""


def voltage_rows(quick: bool = False, on_run=None) -> list[list]:
    """Every row (``on_run(run, rows, seconds)`` after each run, e.g. for progress)."""
    rows = []
    for r in voltage_runs(quick):
        t0 = time.perf_counter()
        new = _rows_of(r, quick)
        rows += new
        if on_run is not None:
            on_run(r, new, time.perf_counter() - t0)
    return rows


def _curve(ax, model, loading, s, lam_hi, style, colour):
    """The analytic loading curve ``(E0, D0)`` up to ``lam_hi``, sampled evenly in
    ``log D0`` (the charge-controlled stretch of each ``D0``)."""
    if loading == "equibiaxial":
        D0_hi = float(an.equibiaxial_D0(lam_hi, s, model))
        lam = an.equibiaxial_lam(np.geomspace(0.02, D0_hi, 300), s, model)
        D0, E0 = an.equibiaxial_D0(lam, s, model), an.equibiaxial_E0(lam, s, model)
    else:
        D0_hi = float(an.uniaxial_D0(lam_hi, s, model))
        lam = an.uniaxial_lam1(np.geomspace(0.02, D0_hi, 300), s, model)
        D0, E0 = an.uniaxial_D0(lam, s, model), an.uniaxial_E0(lam, s, model)
    ax.plot(E0, D0, style, color=colour, lw=1.1)


#: the paper's figure of each kind of path (see :data:`validation.figures.PAPER_FIGURE`)
_PATH_FIGURE = {("equibiaxial", "neo-Hookean"): "nh-d-e", ("equibiaxial", "Gent"): "gent-d-e",
                ("uniaxial-free", "neo-Hookean"): "figde", ("uniaxial", "neo-Hookean"):
                "uni-axial-ideal"}


def _paths(rows: list[list]) -> list[dict]:
    """One dict per path of ``rows``: ``run, model, loading, s, alpha`` and its rows."""
    col = {c: VOLTAGE_COLUMNS.index(c) for c in VOLTAGE_COLUMNS}
    out = []
    for run in dict.fromkeys(r[col["run"]] for r in rows):
        rr = [r for r in rows if r[col["run"]] == run]
        out.append({c: rr[0][col[c]] for c in ("run", "model", "loading", "s", "alpha")}
                   | {"rows": rr})
    return out


def voltage_caption(rows: list[list], quick: bool | None = None) -> str:
    """The caption line of :func:`voltage_figure`: the paper's figures of the paths drawn,
    quick/full run and the FE meshes.

    Parameters
    ----------
    rows : list of list
        Rows of :func:`voltage_rows`.
    quick : bool, optional
        Which run setting produced them (``None``: not known).

    Returns
    -------
    str
    """
    paths = _paths(rows)
    names = [n for n in PAPER_FIGURE if any(_PATH_FIGURE.get((p["loading"], p["model"])) == n
                                            for p in paths)]
    nums = ", ".join(str(PAPER_FIGURE[n]) for n in names)
    head = (f"Paper Fig{'s' if len(names) > 1 else ''}. {nums} ({', '.join(names)}) under "
            "voltage control" if names else "Voltage control")
    n1, n2, n3 = KEPLINGER_MESH
    meshes = [(MODEL_NAME["coupled"], "1 element (homogeneous state)" if p["alpha"] is None
               else f"{n1} x {n2} x {n3} elements (eighth of the Keplinger plate)")
              for p in paths]
    return run_caption(head, quick, mesh_caption(meshes))


def _panel_title(loading_paths: list[dict], equibiaxial: bool) -> str:
    """What a panel shows: the loading, the materials or plates drawn, the paper's
    figures."""
    if equibiaxial:
        models = list(dict.fromkeys(p["model"] for p in loading_paths))
        figs = [_PATH_FIGURE[("equibiaxial", m)] for m in models]
        what = " and ".join(models)
        title = "equi-biaxial dead load"
    else:
        parts, figs = [], []
        if any(p["alpha"] is None for p in loading_paths):
            parts.append("free lateral edges")
            figs.append("figde")
        if any(p["alpha"] is not None for p in loading_paths):
            parts.append("Keplinger plate")
            figs.append("uni-axial-ideal")
        what = " and ".join(parts)
        title = "uni-axial dead load"
    if not loading_paths:
        return f"{title}: no FE path"
    return f"{title}: {what} (Fig{'s' if len(figs) > 1 else ''}. {', '.join(figs)})"


def voltage_figure(rows: list[list], ax=None, quick: bool | None = None):
    """Charge ``D0`` against voltage ``E0`` of every path of ``rows``.

    Panel (a) the equi-biaxial, (b) the uni-axial dead load: the FE points of the
    voltage-controlled continuation (:data:`validation.figures.MODEL_NAME` ``"coupled"``;
    filled: stable under voltage control, open: unstable), red stars at the located
    limit points (:data:`validation.markers.LIMIT_POINT`), the analytic loading curves
    of the homogeneous paths (solid: neo-Hookean, dashed: Gent) and the neo-Hookean
    voltage-control limit locus ``det H* = 0`` (dotted).  Titles and legends name only
    what is drawn; the caption line is :func:`voltage_caption`.

    Parameters
    ----------
    rows : list of list
        Rows of :func:`voltage_rows`.
    ax : pair of matplotlib Axes, optional
    quick : bool, optional
        Which run setting produced ``rows`` (for the caption line).

    Returns
    -------
    pair of matplotlib Axes
    """
    if ax is None:
        _, ax = plt.subplots(1, 2, figsize=(12, 5.0), layout="constrained")
    col = {c: VOLTAGE_COLUMNS.index(c) for c in VOLTAGE_COLUMNS}
    paths = _paths(rows)
    panel_of = {"equibiaxial": 0, "uniaxial-free": 1, "uniaxial": 1}
    drawn = [{"unstable": False, "limit": False} for _ in ax]
    for i, a in enumerate(ax):
        mine = [p for p in paths if panel_of[p["loading"]] == i]
        for k, p in enumerate(mine):
            rr, colour = p["rows"], plt.cm.tab10(k % 10)
            lam = np.array([r[col["lam1_fe"]] for r in rr], dtype=float)
            style = "--" if p["model"] == "Gent" else "-"
            if p["alpha"] is None:
                _curve(a, analytic_model(p["model"]), p["loading"], p["s"],
                       1.02 * np.nanmax(lam), style, colour)
            E0 = np.array([r[col["E0"]] for r in rr], dtype=float)
            D0 = np.array([r[col["D0"]] for r in rr], dtype=float)
            stable = np.array([r[col["stable"]] is True for r in rr])
            label = (f"Keplinger plate, $\\alpha = {p['alpha']:g}$" if p["alpha"] is not None
                     else f"{p['model']}, $s = {p['s']:g}$")
            a.plot(E0[stable], D0[stable], ls="none", **legend_style(STABLE_STATE, color=colour))
            a.plot(E0[~stable], D0[~stable], ls="none",
                   **legend_style(UNSTABLE_STATE, color=colour))
            # the legend entry: the path's colour, with its analytic curve's style if drawn
            a.plot([], [], "o", ls=style if p["alpha"] is None else "none", color=colour,
                   ms=5, label=label)
            lim = [j for j, r in enumerate(rr) if r[col["kind"]] == "limit"]
            a.plot(E0[lim], D0[lim], ls="none", **legend_style(LIMIT_POINT))
            drawn[i]["unstable"] |= bool((~stable).any())
            drawn[i]["limit"] |= bool(lim)
        a.set_title(_panel_title(mine, i == 0), fontsize=10)
    lam = np.linspace(1.0, 6.0, 400)
    ax[0].plot(an.voltage_limit_D0(lam) / lam ** 4, an.voltage_limit_D0(lam),
               label=r"$\det\mathcal{H}^* = 0$ (voltage control limit, neo-Hookean)",
               **line_style(VOLTAGE_LIMIT_LOCUS))
    ax[1].plot(an.uniaxial_voltage_limit_E0(lam), an.uniaxial_voltage_limit_D0(lam),
               label=r"$\det\mathcal{H}^* = 0$ (voltage control limit, neo-Hookean)",
               **line_style(VOLTAGE_LIMIT_LOCUS))
    name = MODEL_NAME["coupled"]
    for a, d in zip(ax, drawn):
        handles, _ = a.get_legend_handles_labels()
        keys = [Line2D([], [], ls="none", **legend_style(STABLE_STATE),
                       label=f"{STABLE_STATE.name}, {name}")]
        if d["unstable"]:
            keys.append(Line2D([], [], ls="none", **legend_style(UNSTABLE_STATE),
                               label=f"{UNSTABLE_STATE.name}, {name}"))
        if d["limit"]:
            keys.append(Line2D([], [], ls="none", **legend_style(LIMIT_POINT),
                               label=LIMIT_POINT.name))
        a.set_xlabel(r"$E_0$ (voltage)")
        a.set_ylabel(r"$D_0$ (charge, log scale)")
        a.set_xlim(0.0, 0.8)
        a.set_yscale("log")
        a.set_ylim(0.02, 200.0)
        a.legend(handles=handles + keys, fontsize=7, loc="lower right")
    tag_panels(ax)
    add_caption(ax[0].figure, voltage_caption(rows, quick))
    return ax


def _fmt(v) -> str:
    if v is None:
        return ""
    if isinstance(v, (bool, np.bool_)):
        return str(bool(v))
    if isinstance(v, str):
        return v
    v = float(v)
    return "" if math.isnan(v) else format(v, ".12g")     # nan: no value, an empty cell


def _read_back(row: dict) -> list:
    """A row of ``voltage-control.csv`` read back (:func:`validation.store.read_rows`) as
    :func:`voltage_rows` gives it: ``stable`` and ``stable_charge`` as ``True``, ``False``
    or ``None``, ``alpha`` ``None`` for a homogeneous plate, no value as ``nan``."""
    out = []
    for c in VOLTAGE_COLUMNS:
        v = row[c]
        if c in ("stable", "stable_charge"):
            v = {"True": True, "False": False}.get(v)
        elif c == "alpha" and math.isnan(v):
            v = None
        out.append(v)
    return out


def run_voltage_control(out, quick: bool = False, on_run=None, note=None, say=None,
                        force: bool = False) -> tuple[list[Path], dict]:
    """Write ``out/voltage-control.csv`` and ``.png|pdf``.

    The paths are the units of a :class:`~validation.store.StudyStore` (lock
    ``out/.state/voltage-control.lock``, held until the figure is written; settings: quick
    or full): the rows of a path are written (atomically, the whole file) when it ends,
    then its line of the resume table ``out/.state/voltage-control-runs.csv`` with its
    number of rows.  A rerun keeps the paths found whole and computes the others; a
    path with a row missing, cut short or added is recomputed.

    Parameters
    ----------
    out : path-like
        The output folder.
    quick : bool
        The quick runs.
    on_run : callable, optional
        ``on_run(run, rows, seconds)`` after each path computed.
    note, say : callable, optional
        ``note(message)``: one line naming the file for each repair (a last row cut short,
        a path's rows incomplete, other settings); ``say(message)``: one line for a
        resumed run, how many paths and rows it kept.
    force : bool
        Discard the paths present.

    Returns
    -------
    paths : list of Path
    summary : dict
        ``n_runs``, ``n_points``, ``max_rel_error`` (largest relative ``lam1`` error of
        the homogeneous limit points against :func:`analytic.max_E0`),
        ``max_rel_error_by_run``, ``E0_error_by_run`` (absolute), ``runtime_s``,
        ``reasons`` (runs whose path stopped on a solver failure), ``resumed`` (rows
        kept from an earlier run).

    Raises
    ------
    validation.store.LockedError
        Another process writes the case into ``out``.
    validation.store.DamagedFileError
        A complete row that cannot be read back (names the file and the row).
    """
    t0 = time.perf_counter()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    runs = voltage_runs(quick)
    with StudyStore(out, VOLTAGE_CONTROL, {"quick": bool(quick)}, RUNS, (POINTS,),
                    plan=[(_run_key(r),) for r in runs], counts={POINTS.file: "n_points"},
                    derived=(f"{VOLTAGE_CONTROL}.png", f"{VOLTAGE_CONTROL}.pdf"), note=note,
                    force=force) as store:
        kept = sum(int(r["n_points"]) for r in store.rows() if store.done((r["run"],)))
        if store.kept() and say is not None:
            say(f"{out / POINTS.file}: kept {store.kept()} of {len(runs)} paths ({kept} rows) "
                f"of an earlier run")
        for r in runs:
            if store.done((_run_key(r),)):
                continue
            t1 = time.perf_counter()
            new = _rows_of(r, quick)
            store.commit({**{c: _fmt(r[c]) for c in ("model", "loading", "s", "alpha")},
                          "run": _run_key(r), "n_points": str(len(new))},
                         {POINTS.file: [dict(zip(VOLTAGE_COLUMNS, map(_fmt, row)))
                                        for row in new]})
            if on_run is not None:
                on_run(r, new, time.perf_counter() - t1)
        rows = [_read_back(row) for row in store.rows(POINTS.file)]
        csv_path = out / POINTS.file
        ax = voltage_figure(rows, quick=quick)
        paths = [csv_path] + save_figure(ax[0].figure, out, VOLTAGE_CONTROL)
    col = {c: VOLTAGE_COLUMNS.index(c) for c in VOLTAGE_COLUMNS}
    lam_err, E0_err, reasons = {}, {}, {}
    for run in dict.fromkeys(r[1] for r in rows):
        last = [r for r in rows if r[1] == run][-1]
        if last[col["note"]].startswith("corrector failed") \
                or last[col["note"]].startswith("start not"):
            reasons[run] = last[col["note"]]
        if last[col["alpha"]] is not None:
            continue
        lf, la = last[col["lam1_max_fe"]], last[col["lam1_max_analytic"]]
        if math.isfinite(la) or math.isfinite(lf):
            lam_err[run] = abs(lf - la) / la if math.isfinite(lf) and math.isfinite(la) \
                else math.inf
            E0_err[run] = abs(last[col["E0_max_fe"]] - last[col["E0_max_analytic"]])
    summary = {"n_runs": len(lam_err) + sum(1 for r in voltage_runs(quick) if r["alpha"]),
               "n_points": len(rows),
               "max_rel_error": max(lam_err.values()) if lam_err else None,
               "max_rel_error_by_run": lam_err, "E0_error_by_run": E0_err,
               "runtime_s": time.perf_counter() - t0, "reasons": reasons, "resumed": kept}
    return paths, summary

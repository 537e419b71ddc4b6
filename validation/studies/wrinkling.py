"""FE wrinkling of a homogeneous plate against the Stroh dispersion relation.

For each stretch ``lam``, wavenumber ``kh`` (deformed thickness), mode (symmetric or
antisymmetric) and control (charge or voltage) the FE critical charge of the section with
sliding ends (:func:`skfem_dielectric.studies.wrinkling_section`,
:func:`skfem_dielectric.studies.section_critical_load`) is compared with
:func:`analytic.critical_D0`, the finite-thickness dispersion relation of the paper's
Sec. 3 (under voltage control both are the critical ``D0 = lam^4 E0``).  Written as
``DIR/wrinkling-fe.csv`` (one row per grid point; a point without a Stroh root says so)
and ``DIR/wrinkling-fe.png|pdf`` (FE dots on the dispersion curves, with the caption
line and the model names of :mod:`validation.figures`).  Both CSVs are the tables of a
:class:`validation.store.StudyStore` (one row per grid point, each rewritten atomically
after every row, under the lock ``.state/wrinkling-fe.lock``): a rerun into the same
folder with the same grid keeps the rows it finds and computes only the missing ones, so
that an interrupted run resumes to the files of an uninterrupted one.
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.ticker import NullFormatter, ScalarFormatter
from scipy.optimize import brentq

import analytic as an
import skfem_dielectric as fe

from ..figures import MODEL_NAME, add_caption, mesh_caption, run_caption, save_figure, tag_panels
from ..markers import (MODE_LINES, SECTION_ANTISYMMETRIC, SECTION_SYMMETRIC, THICK_PLATE_LIMIT,
                       line_style)
from ..data.spec import TableSpec
from ..store import StudyStore

__all__ = ["WRINKLING_COLUMNS", "ELASTIC_COLUMNS", "TABLE", "ELASTIC", "wrinkling_grid",
           "wrinkling_rows",
           "wrinkling_fe_runs",
           "elastic_grid", "elastic_rows", "stroh_critical_stretch", "run_wrinkling_fe",
           "wrinkling_figure", "wrinkling_caption"]

WRINKLING_COLUMNS = ["control", "mode", "lam", "kh", "D0_fe", "D0_stroh", "rel_error", "mesh",
                     "n_negative_below", "n_stroh_below", "note"]
ELASTIC_COLUMNS = ["mode", "kh", "lam_fe", "lam_stroh", "rel_error", "mesh", "note"]
MODES = ("symmetric", "antisymmetric")
CONTROLS = ("charge", "voltage")
#: the files (:class:`~validation.store.StudyStore`), one row per grid point
TABLE = TableSpec.plain("wrinkling-fe.csv", tuple(WRINKLING_COLUMNS), ("control", "mode", "lam", "kh"))
ELASTIC = TableSpec.plain("wrinkling-fe-elastic.csv", tuple(ELASTIC_COLUMNS), ("mode", "kh"))


def wrinkling_grid(quick: bool = False) -> dict:
    """The grid: ``lam``, ``kh`` and the elements per half-wave ``n1`` (quick: a subset)."""
    if quick:
        return {"lam": (1.5,), "kh": (0.5, 2.0), "n1": 8}
    return {"lam": (1.2, 1.5, 2.0), "kh": (0.5, 1.0, 2.0, 5.0), "n1": 8}


def wrinkling_fe_runs(quick: bool = False) -> list[str]:
    """The FE runs of the grid: every point of :func:`wrinkling_grid` and
    :func:`elastic_grid` where the dispersion relation has a root (a point without one is
    a row of the CSV, but no FE run), named as in ``summary.json``'s
    ``max_rel_error_by_run``.  ``skfem-dielectric list`` and the report count these.

    Examples
    --------
    >>> len(wrinkling_fe_runs(quick=True))   # the symmetric charge mode at kh = 0.5: no root
    9
    """
    g = wrinkling_grid(quick)
    runs = [f"{control} {mode} lam={_fmt(lam)} kh={_fmt(kh)}"
            for control in CONTROLS for mode in MODES for lam in g["lam"] for kh in g["kh"]
            if math.isfinite(float(an.critical_D0(lam, kh, mode=mode, control=control)))]
    return runs + [f"D0=0 {mode} kh={_fmt(kh)}" for mode, kh in elastic_grid(quick)["rows"]
                   if math.isfinite(stroh_critical_stretch(kh, mode))]


def stroh_unstable_below(control, mode, lam, kh, n1, D0) -> int:
    """Modes of the section other than the sought one that the Stroh analysis finds
    unstable at ``D0``: the Fourier modes ``1 <= n <= 2 n1`` (wavenumbers ``n kh``; the
    ``2 n1 + 1`` Q2 nodes along the section carry no shorter cosine) of the classes the
    section holds (symmetric on the half thickness, both on the full one).  The FE
    resolves these at best (under-resolved modes are stiffer), so its count below the
    onset must not exceed this number; more would be spurious."""
    classes = ("symmetric",) if mode == "symmetric" else MODES
    count = 0
    for cls in classes:
        ref = an.critical_D0(lam, kh * np.arange(1, 2 * n1 + 1), mode=cls, control=control)
        ref = np.where(np.isfinite(ref), ref, np.inf)
        count += int(np.sum(ref < D0)) - int(cls == mode and ref[0] < D0)
    return count


def _row(control, mode, lam, kh, n1) -> list:
    ref = float(an.critical_D0(lam, kh, mode=mode, control=control))
    base = [control, mode, lam, kh]
    if not math.isfinite(ref):
        return base + [None, None, None, "", None, None, "no root of the dispersion relation"]
    a = math.pi / (lam**3 * kh)
    n2 = max(2, int(round((0.5 if mode == "symmetric" else 1.0) / (a / n1))))
    pb = fe.studies.wrinkling_section(lam, kh, mode, control, n1=n1, n2=n2)
    ref_load = ref if control == "charge" else ref / lam**4
    n_ref = stroh_unstable_below(control, mode, lam, kh, n1, 0.95 * ref)
    try:
        r = fe.studies.section_critical_load(pb, mode, 0.95 * ref_load, 1.05 * ref_load)
    except ValueError as exc:
        return base + [None, ref, None, f"{n1}x{n2}", None, n_ref,
                       str(exc).splitlines()[0][:160]]
    d0 = r.load if control == "charge" else r.D0
    return base + [d0, ref, d0 / ref - 1.0, f"{n1}x{n2}", r.n_negative_below, n_ref, ""]


def _grid_keys(quick: bool) -> list[tuple]:
    g = wrinkling_grid(quick)
    return [(control, mode, lam, kh) for control in CONTROLS for mode in MODES
            for lam in g["lam"] for kh in g["kh"]]


def _stored(store, table: TableSpec, keys, compute, on_row) -> list[list]:
    """The rows of ``keys``: those in ``store`` kept, the others computed
    (``compute(key)``), committed one by one and passed to ``on_row``.  With a store every
    row is returned as written (an empty cell as ``None``), so that what is drawn and
    summarised from a resumed run is what an uninterrupted one gives."""
    rows = []
    for key in keys:
        if store is not None and store.done(key):
            continue
        row = compute(key)
        if store is not None:
            store.commit({c: _fmt(v) for c, v in zip(table.columns, row)}, {})
        if on_row is not None:
            on_row(row)
        rows.append(row)
    if store is None:
        return rows
    written = {table.key_of(r): r for r in store.rows()}
    return [[None if v == "" or (isinstance(v, float) and math.isnan(v)) else v
             for v in written[tuple(_fmt(x) for x in key)].values()] for key in keys]


def wrinkling_rows(quick: bool = False, on_row=None, store: StudyStore | None = None
                   ) -> list[list]:
    """Every row of the grid (``on_row(row)`` after each row computed, e.g. for progress);
    with ``store`` (an open :class:`~validation.store.StudyStore` of :data:`TABLE`) the
    rows in it are reused and each new row is committed (the CSV rewritten atomically)."""
    n1 = wrinkling_grid(quick)["n1"]
    return _stored(store, TABLE, _grid_keys(quick), lambda key: _row(*key, n1), on_row)


def elastic_grid(quick: bool = False) -> dict:
    """The purely elastic rows (``D0 = 0``): ``(mode, kh)`` pairs and elements per
    half-wave.  Symmetric modes have no root above ``lam = 0.3`` for ``kh <= 5``."""
    if quick:
        return {"rows": (("antisymmetric", 1.0), ("antisymmetric", 20.0)), "n1": 8}
    return {"rows": tuple(("antisymmetric", kh) for kh in (0.5, 1.0, 2.0, 5.0, 20.0))
            + (("symmetric", 5.0), ("symmetric", 20.0)), "n1": 8}


def stroh_critical_stretch(kh: float, mode: str, lo: float = 0.3) -> float:
    """Largest equi-biaxial stretch ``lam < 1`` at which the uncharged plate's dispersion
    relation (:func:`analytic.dispersion_function`, ``D0 = 0``) has the root ``kh``; the
    first buckling under increasing compression.  ``nan`` without a root in
    ``(lo, 1)``."""
    lams = np.linspace(0.999, lo, 400)

    def f(lam):
        return float(an.dispersion_function(lam, lam, 0.0, kh, mode=mode))

    vals = np.asarray(an.dispersion_function(lams, lams, 0.0, kh, mode=mode), dtype=float)
    for i in range(len(lams) - 1):
        if np.sign(vals[i]) != np.sign(vals[i + 1]):
            return float(brentq(f, lams[i + 1], lams[i], xtol=1e-14))
    return float("nan")


def _elastic_row(mode, kh, n1) -> list:
    ref = stroh_critical_stretch(kh, mode)
    if not math.isfinite(ref):
        return [mode, kh, None, None, None, "", "no root of the dispersion relation above "
                "lam = 0.3"]
    a = math.pi / (ref**3 * kh)
    thickness = 0.5 if mode == "symmetric" else 1.0
    # elements of about the size along x1 and, for short waves, at most 2/3 of the depth
    # H/kh (reference) over which the mode decays from the faces
    n2 = max(2, int(round(thickness / (a / n1))), math.ceil(1.5 * kh * thickness))
    try:
        lam, _ = fe.studies.section_critical_stretch(kh, mode, 0.97 * ref,
                                                     min(1.03 * ref, 0.9995), n1=n1, n2=n2)
    except ValueError as exc:
        return [mode, kh, None, ref, None, f"{n1}x{n2}", str(exc).splitlines()[0][:160]]
    return [mode, kh, lam, ref, lam / ref - 1.0, f"{n1}x{n2}", ""]


def elastic_rows(quick: bool = False, on_row=None, store: StudyStore | None = None
                 ) -> list[list]:
    """The rows of :func:`elastic_grid` (``on_row`` and ``store``, of :data:`ELASTIC`, as
    in :func:`wrinkling_rows`)."""
    g = elastic_grid(quick)
    return _stored(store, ELASTIC, list(g["rows"]),
                   lambda key: _elastic_row(*key, g["n1"]), on_row)


def _fmt(v) -> str:
    if v is None:
        return ""
    if isinstance(v, str):
        return v
    v = float(v)
    return "" if math.isnan(v) else format(v, ".10g")     # nan: no value, an empty cell


#: the FE cross-section's markers by mode (validation.markers)
_SECTION = {"symmetric": SECTION_SYMMETRIC, "antisymmetric": SECTION_ANTISYMMETRIC}


def _elastic_panel(a, rows):
    kh = np.logspace(np.log10(0.3), np.log10(30.0), 40)
    for mode in ("antisymmetric", "symmetric"):
        a.plot(kh, [stroh_critical_stretch(k, mode) for k in kh], color="k", lw=1.2,
               label=f"Stroh, {mode}", **line_style(MODE_LINES[mode]))
        pts = [(r[1], r[2]) for r in rows if r[0] == mode and r[2] is not None]
        if pts:
            x, y = zip(*pts)
            mk = _SECTION[mode]
            a.plot(x, y, ls="none", label=mk.name, **mk.style)
    a.axhline(an.surface_instability_stretch(),
              label=r"thick-plate limit $\lambda = 0.666$", **line_style(THICK_PLATE_LIMIT))
    thin = kh[kh < 2.5]
    a.plot(thin, 1 - thin**2 / 18, ":", color="C0", lw=1.0, label=r"Euler: $1 - (kh)^2/18$")
    a.set_xscale("log")
    a.set_xticks([0.3, 1, 3, 10, 30])
    a.xaxis.set_major_formatter(ScalarFormatter())
    a.xaxis.set_minor_formatter(NullFormatter())
    a.set_xlabel(r"$kh$ (deformed thickness)")
    a.set_ylabel(r"critical stretch $\lambda$ ($D_0 = 0$)")
    a.set_title("uncharged plate in compression", fontsize=10)
    a.legend(fontsize=7, loc="upper right")


def wrinkling_caption(rows: list[list], elastic: list[list] | None = None,
                      quick: bool | None = None) -> str:
    """The caption line of :func:`wrinkling_figure`: what it compares with, quick/full
    run and the meshes of the cross-section (elements per half-wave x across the
    modelled thickness: half of it for the symmetric modes, all of it for the
    antisymmetric ones).

    Parameters
    ----------
    rows, elastic : list of list
        Rows of :func:`wrinkling_rows` and :func:`elastic_rows`.
    quick : bool, optional
        Which run setting produced them (``None``: not known).

    Returns
    -------
    str
    """
    meshes = {r[7] for r in rows if r[7]} | {r[5] for r in elastic or () if r[5]}
    sizes = sorted({tuple(int(n) for n in m.split("x")) for m in meshes}, key=lambda m: m[::-1])
    text = " x ".join(map(str, sizes[0])) if sizes else ""
    if len(sizes) > 1:
        text += " to " + " x ".join(map(str, sizes[-1]))
    mesh = [(MODEL_NAME["section"], f"{text} elements (per half-wave x modelled thickness)")]
    return run_caption("Paper Sec. 3 (Stroh dispersion relation)", quick,
                       mesh_caption(mesh) if sizes else "")


def wrinkling_figure(rows: list[list], ax=None, elastic: list[list] | None = None,
                     quick: bool | None = None):
    """FE critical loads on the Stroh dispersion curves ``D0(kh)``.

    One panel per control (hexagons: the FE cross-section, open for symmetric and filled
    for antisymmetric modes, :data:`validation.markers.SECTION_SYMMETRIC` and
    :data:`~validation.markers.SECTION_ANTISYMMETRIC`; lines: :func:`analytic.critical_D0`)
    and, with ``elastic``
    rows, a third panel of the uncharged plate's critical stretch.  The caption line is
    :func:`wrinkling_caption`.

    Parameters
    ----------
    rows : list of list
        Rows of :func:`wrinkling_rows`.
    ax : sequence of matplotlib Axes, optional
        Two (three with ``elastic``).
    elastic : list of list, optional
        Rows of :func:`elastic_rows`.
    quick : bool, optional
        Which run setting produced the rows (for the caption line).

    Returns
    -------
    sequence of matplotlib Axes
    """
    if ax is None:
        _, ax = plt.subplots(1, 3 if elastic is not None else 2,
                             figsize=(16 if elastic is not None else 11, 4.6),
                             layout="constrained")
    if elastic is not None:
        _elastic_panel(ax[2], elastic)
    kh = np.logspace(np.log10(0.3), np.log10(8.0), 60)
    lams = sorted({r[2] for r in rows})
    colours = dict(zip(lams, plt.cm.viridis(np.linspace(0.1, 0.8, len(lams)))))
    drawn = set()
    for a, control in zip(ax, CONTROLS):
        for lam in lams:
            for mode in ("symmetric", "antisymmetric"):
                a.plot(kh, an.critical_D0(lam, kh, mode=mode, control=control),
                       color=colours[lam], lw=1.2,
                       label=f"Stroh, $\\lambda = {lam:g}$, {mode}"
                       if control == "charge" else None, **line_style(MODE_LINES[mode]))
                pts = [(r[3], r[4]) for r in rows
                       if r[0] == control and r[1] == mode and r[2] == lam and r[4] is not None]
                if pts:
                    x, y = zip(*pts)
                    a.plot(x, y, ls="none", **{**_SECTION[mode].style,
                                               "color": colours[lam]})
                    drawn.add(mode)
        a.set_xscale("log")
        a.set_xticks([0.3, 0.5, 1, 2, 5])
        a.xaxis.set_major_formatter(ScalarFormatter())
        a.xaxis.set_minor_formatter(NullFormatter())
        a.set_xlabel(r"$kh$ (deformed thickness)")
        a.set_ylabel(r"critical $D_0$" + (r" $= \lambda^4 E_0$" if control == "voltage" else ""))
        a.set_title(f"{control} control", fontsize=10)
    handles, _ = ax[0].get_legend_handles_labels()
    handles += [Line2D([], [], ls="none", label=_SECTION[mode].name, **_SECTION[mode].style)
                for mode in ("symmetric", "antisymmetric") if mode in drawn]
    ax[0].legend(handles=handles, fontsize=7, loc="upper right")
    tag_panels(ax)
    add_caption(ax[0].figure, wrinkling_caption(rows, elastic, quick))
    return ax


def run_wrinkling_fe(out, quick: bool = False, on_row=None, on_elastic_row=None,
                     note=None, say=None, force: bool = False) -> list[Path]:
    """Write ``out/wrinkling-fe.csv``, ``out/wrinkling-fe-elastic.csv`` and the figure
    ``out/wrinkling-fe.png`` and ``.pdf``; return their paths (in this order).

    The two CSVs are the tables of :class:`~validation.store.StudyStore` ``wrinkling-fe``
    and ``wrinkling-fe-elastic`` (their locks ``out/.state/<name>.lock``, held from
    before anything is read until the figure is written; settings: the grid, quick or
    full): rows already there are reused, a folder of the other grid is discarded and
    recomputed.  ``note(message)`` gets one line naming the file for each repair (a last
    row cut short, a row of another length, a file of other columns or settings),
    ``say(message)`` one line per CSV of a resumed run: how many rows it kept.
    ``force`` discards the rows present.

    Raises
    ------
    validation.store.LockedError
        Another process writes the case into ``out``.
    validation.store.DamagedFileError
        A complete row that cannot be read back (names the file and the row).
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    settings = {"quick": bool(quick), "n1": wrinkling_grid(quick)["n1"]}
    kw = dict(note=note, force=force)
    with StudyStore(out, "wrinkling-fe", settings, TABLE, plan=_grid_keys(quick),
                    derived=("wrinkling-fe.png", "wrinkling-fe.pdf"), **kw) as st, \
            StudyStore(out, "wrinkling-fe-elastic", settings, ELASTIC,
                       plan=list(elastic_grid(quick)["rows"]), **kw) as se:
        for store, table in ((st, TABLE), (se, ELASTIC)):
            if store.kept() and say is not None:
                say(f"{out / table.file}: kept {store.kept()} of {len(store.plan)} rows of "
                    f"an earlier run")
        rows = wrinkling_rows(quick, on_row, store=st)
        elastic = elastic_rows(quick, on_elastic_row, store=se)
        ax = wrinkling_figure(rows, elastic=elastic, quick=quick)
        return ([out / TABLE.file, out / ELASTIC.file]
                + save_figure(ax[0].figure, out, "wrinkling-fe"))

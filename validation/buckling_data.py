"""The converged buckling loads of the clamped Keplinger plate, as measured.

Two data files (in the wheel) hold the first physical buckling load ``D0_b`` of the whole
plate:

* ``validation/data/clamp_units.csv``: the clamp-zone study on meshes graded towards the
  clamp (:mod:`validation.studies.clamp_units`, one weight on one mesh per row, with the
  mode's half-wave count, ``J`` at the clamp and the command of each row).  A weight's
  load is the finest mesh's where the two finest hold the mode (at least
  :data:`MIN_ELEMENTS_PER_HALF_WAVE` elements per half-wave across the width), count the
  same half-waves and agree (:func:`clamp_unit_load`);
* ``validation/data/buckling_loads.csv``: three uniform meshes per weight
  (:mod:`validation.studies.buckling`), their Richardson extrapolation with an error
  estimate and order, and where the plain form's Newton ramp stops on the finest mesh;
  its ``#`` header says how they were measured (command, meshes, solver, date, error
  estimate).  Its meshes hold two elements per half-wave of the heavier weights'
  clamp-zone wrinkle, so a weight with a converged graded load takes that one.

:func:`buckling_loads` gives, per weight, the entry the project stands behind; the figures
(paper Fig. 5 and the breakdown map, docs/breakdown.md) and ``skfem-dielectric check``
read it from here.  Reading the files loads no finite elements.

Only converged entries are answers: :func:`converged_buckling_load` refuses a weight
without one (the uniform meshes' ``alpha = 1.5``: its three meshes disagree) or absent
from the file rather than extrapolate or interpolate between weights.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

__all__ = ["BUCKLING_LOADS_FILE", "CLAMP_UNITS_FILE", "MIN_ELEMENTS_PER_HALF_WAVE",
           "BucklingEntry", "buckling_loads", "uniform_buckling_loads", "buckling_provenance",
           "converged_buckling_load", "read_clamp_units", "clamp_unit_load", "clamp_study_tables",
           "newton_limits", "read_data_csv", "P33_UNITS_FILE", "CLASS_ONSETS_FILE",
           "CLAMP_LAYER_FILE", "CLASS_TIE", "LOCATION_TOL", "tied_classes", "unit_key",
           "clamp_unit_row"]

#: the data file of the uniform meshes, relative to the ``validation`` package
BUCKLING_LOADS_FILE = "data/buckling_loads.csv"
#: the data file of the clamp-zone study on graded meshes (one unit per row,
#: :mod:`validation.studies.clamp_units`), relative to the ``validation`` package
CLAMP_UNITS_FILE = "data/clamp_units.csv"
#: the located P33 onsets on the graded meshes (:mod:`validation.studies.p33_units`)
P33_UNITS_FILE = "data/p33_units.csv"
#: each symmetry class's crossing at a unit's bracket (:mod:`validation.studies.class_onsets`)
CLASS_ONSETS_FILE = "data/class_onsets.csv"
#: J and volume ratios at the clamp (:mod:`validation.studies.clamp_layer`)
CLAMP_LAYER_FILE = "data/clamp_layer.csv"
#: elements across the width per half-wave below which a mesh cannot hold the mode
MIN_ELEMENTS_PER_HALF_WAVE = 4.0
#: the tolerance in ``D0`` to which every graded unit's ``D0_b`` is located: the least error
#: of a graded load, whatever its two meshes' spread
LOCATION_TOL = 1e-4
#: modes whose located crossings lie within this of a mesh's first (twice the location
#: tolerance) cross together: the mesh does not order them
CLASS_TIE = 2 * LOCATION_TOL


@dataclass(frozen=True)
class BucklingEntry:
    """The buckling load of one weight fraction.

    Attributes
    ----------
    alpha
        Weight fraction of the dead load (paper Sec. 6, ``s = alpha m g/(mu A)``).
    meshes
        The eighth-model meshes, coarse to fine (``"10x1x5"``, ...).
    D0_b_mesh
        The located ``D0_b`` on each mesh.
    D0_b, error, order
        Richardson extrapolation of ``D0_b_mesh``, its error estimate (distance from the
        finest mesh's value) and the observed order; ``nan`` where not converged.
    newton_limit
        Where the plain form (``grad_div = 0``) stops on the finest mesh; ``nan`` if it
        reached every target (or, for a ``"graded"`` entry, was not run there).
    source
        ``"uniform"``: the three uniform meshes of :data:`BUCKLING_LOADS_FILE`, ``D0_b``
        their Richardson extrapolation; ``"graded"``: the two finest graded meshes of the
        clamp-zone study (:data:`CLAMP_UNITS_FILE`, ``meshes`` named ``"40x1x36 g0.1"``:
        mesh and grading), ``D0_b`` the finest mesh's where the two hold the mode and agree
        (:func:`clamp_unit_load`), ``error`` their difference, ``order`` ``nan`` (nothing
        is extrapolated).
    """

    alpha: float
    meshes: tuple[str, ...]
    D0_b_mesh: tuple[float, ...]
    D0_b: float
    error: float
    order: float
    newton_limit: float
    source: str = "uniform"

    @property
    def converged(self) -> bool:
        """The three meshes give a converged (extrapolated) buckling load."""
        return math.isfinite(self.D0_b)


def _lines() -> list[str]:
    return (resources.files("validation") / BUCKLING_LOADS_FILE).read_text().splitlines()


def _float(cell: str) -> float:
    return float(cell) if cell.strip() else float("nan")


def buckling_provenance() -> str:
    """The ``#`` header of the data file: command, meshes, solver, date, error estimate."""
    return "\n".join(ln[1:].strip() for ln in _lines() if ln.startswith("#"))


def uniform_buckling_loads() -> tuple[BucklingEntry, ...]:
    """Every entry of :data:`BUCKLING_LOADS_FILE` (three uniform meshes), converged or not,
    in increasing ``alpha``.

    Returns
    -------
    tuple of BucklingEntry
    """
    rows = list(csv.DictReader(ln for ln in _lines() if not ln.startswith("#")))
    meshes = tuple(k.removeprefix("D0_b_") for k in rows[0]
                   if k.startswith("D0_b_") and k != "D0_b_error")
    out = [BucklingEntry(alpha=float(r["alpha"]), meshes=meshes,
                         D0_b_mesh=tuple(_float(r[f"D0_b_{m}"]) for m in meshes),
                         D0_b=_float(r["D0_b"]), error=_float(r["D0_b_error"]),
                         order=_float(r["order"]),
                         newton_limit=_float(r[f"newton_limit_{meshes[-1]}"]))
           for r in rows]
    return tuple(sorted(out, key=lambda e: e.alpha))


def _plain_newton_limit(alpha: float, mesh: str, grading: str) -> float:
    """The plain form's Newton limit on a graded mesh (``data/p33_units.csv``), ``nan``
    where it reached every target or was not run."""
    for r in _read_p33_units():
        if (math.isclose(float(r["alpha"]), alpha, rel_tol=0.0, abs_tol=1e-9)
                and r["mesh"] == mesh and r["grading"] == grading):
            return _float(r["newton_limit"])
    return math.nan


def buckling_loads() -> tuple[BucklingEntry, ...]:
    """The buckling load the project stands behind, per weight fraction, in increasing
    ``alpha``: the clamp-zone study's graded meshes where the two finest hold the mode and
    agree (:func:`clamp_unit_load`; ``source="graded"``), else the entry of the three
    uniform meshes (:func:`uniform_buckling_loads`, converged or not).  A graded entry's
    ``error`` is the two finest meshes' difference, at least :data:`LOCATION_TOL` (each is
    located to it: two meshes that agree to the last digit do not make the load exact).

    The uniform meshes of :data:`BUCKLING_LOADS_FILE` have two elements per half-wave of
    the heavier weights' clamp-zone wrinkle: where the graded meshes resolve it, their load
    replaces the uniform extrapolation (docs/validation.md, "The clamp-zone wrinkle on
    graded meshes").

    Returns
    -------
    tuple of BucklingEntry
    """
    out = {round(e.alpha, 9): e for e in uniform_buckling_loads()}
    alphas = {round(float(r["alpha"]), 9) for r in read_clamp_units() if r["D0_b"]}
    for a in alphas:
        try:
            g = clamp_unit_load(a)
        except ValueError:
            continue
        rows = g["rows"][-2:]                  # the two finest, that agree
        fine = rows[-1]
        out[a] = BucklingEntry(
            alpha=a, meshes=tuple(f"{r['mesh']} g{r['grading']}" for r in rows),
            D0_b_mesh=tuple(float(r["D0_b"]) for r in rows), D0_b=g["D0_b"],
            error=max(g["spread"], LOCATION_TOL), order=math.nan,
            newton_limit=_plain_newton_limit(a, fine["mesh"], fine["grading"]),
            source="graded")
    return tuple(sorted(out.values(), key=lambda e: e.alpha))


def newton_limits() -> list[tuple[float, float, str]]:
    """Where the plain form's Newton ramp stops, per weight and mesh: ``(alpha, D0, mesh)``
    of every uniform entry's finest mesh and every graded entry's finest mesh whose plain
    ramp stopped (:mod:`validation.studies.p33_units`), in increasing ``alpha``.

    Returns
    -------
    list of tuple
    """
    out = [(e.alpha, e.newton_limit, e.meshes[-1]) for e in uniform_buckling_loads()
           if math.isfinite(e.newton_limit)]
    out += [(e.alpha, e.newton_limit, e.meshes[-1]) for e in buckling_loads()
            if e.source == "graded" and math.isfinite(e.newton_limit)]
    return sorted(out)


def converged_buckling_load(alpha: float) -> BucklingEntry:
    """The converged buckling load of weight fraction ``alpha``.

    Parameters
    ----------
    alpha : float
        A weight fraction of the data file (matched to ``1e-9``).

    Returns
    -------
    BucklingEntry
        With a finite ``D0_b`` (the extrapolated load) and its ``error``.

    Raises
    ------
    ValueError
        ``alpha`` is not in the file, or its meshes do not converge; the message names the
        weights with a converged load.  No value is extrapolated or interpolated.

    Examples
    --------
    >>> e = converged_buckling_load(1.0)
    >>> round(e.D0_b, 3), e.source, len(e.meshes)
    (3.37, 'graded', 2)
    """
    alpha = float(alpha)
    entries = buckling_loads()
    ok = ", ".join(f"{e.alpha:g}" for e in entries if e.converged)
    bad = ", ".join(f"{e.alpha:g}" for e in entries if not e.converged)
    where = f"converged: alpha = {ok}" + (f"; not converged: alpha = {bad}" if bad else "")
    for e in entries:
        if math.isclose(e.alpha, alpha, rel_tol=0.0, abs_tol=1e-9):
            if e.converged:
                return e
            raise ValueError(f"alpha = {alpha:g} has no converged buckling load (meshes "
                             f"{', '.join(e.meshes)}: "
                             f"{', '.join(f'{v:g}' for v in e.D0_b_mesh)}); {where}")
    raise ValueError(f"alpha = {alpha:g} has no entry in {BUCKLING_LOADS_FILE} or "
                     f"{CLAMP_UNITS_FILE}; {where}")


def read_data_csv(path: Path | None, default: str = CLAMP_UNITS_FILE) -> list[dict]:
    """The rows of one of the data CSVs (``#`` comment lines skipped), as dicts of strings.

    Parameters
    ----------
    path : Path or None
        The file; ``None``: the package's ``default`` (relative to ``validation``).  A
        missing file has no rows.
    default : str
        The package file read for ``path=None``.
    """
    f = resources.files("validation") / default if path is None else Path(path)
    if not f.is_file():
        return []
    return list(csv.DictReader(ln for ln in f.read_text().splitlines()
                               if not ln.startswith("#")))


def unit_key(row: dict) -> tuple[str, str, str, str]:
    """What names a clamp-zone unit in every study's rows: ``(alpha, mesh, grading,
    formulation)`` as text (numbers as ``%g``), from a row of any of the data CSVs."""
    return (f"{float(row['alpha']):g}", str(row["mesh"]), f"{float(row['grading']):g}",
            str(row["formulation"]))


def clamp_unit_row(alpha: float, mesh: str, grading: float, formulation: str, *,
                   path: Path | None = None) -> dict:
    """The clamp-zone study's row of one unit.

    Parameters
    ----------
    alpha, mesh, grading, formulation
        The unit (``mesh`` as ``"n1xn2xn3"``).
    path : Path, optional
        The study's CSV (default: the package's :data:`CLAMP_UNITS_FILE`).

    Raises
    ------
    ValueError
        No such row: the message names the unit and the study to run.
    """
    key = unit_key({"alpha": alpha, "mesh": mesh, "grading": grading,
                    "formulation": formulation})
    for r in read_clamp_units(path):
        if unit_key(r) == key:
            return r
    raise ValueError(f"no clamp-zone unit alpha = {alpha:g} {mesh} grading {grading:g} "
                     f"({formulation}) in the data: run python -m "
                     f"validation.studies.clamp_units first")


def read_clamp_units(path: Path | None = None) -> list[dict]:
    """The rows of the clamp-zone study's CSV (comment lines skipped), as dicts of strings.

    Parameters
    ----------
    path : Path, optional
        Default: the package's :data:`CLAMP_UNITS_FILE`.  A missing file has no rows.
    """
    return read_data_csv(path, CLAMP_UNITS_FILE)


def clamp_unit_load(alpha: float, *, tol: float | None = None, path: Path | None = None,
                    formulation: str = "mixed", classes_path: Path | None = None) -> dict:
    """The clamp-zone buckling load of ``alpha`` where the study's two finest meshes agree.

    The rows of ``alpha`` (``formulation``, a located ``D0_b``) ordered by unknowns; the
    two finest must hold the mode (at least :data:`MIN_ELEMENTS_PER_HALF_WAVE` elements
    across the width per half-wave), count the same half-waves and give ``D0_b`` within
    ``tol`` (default 0.02; 0.05 for ``alpha >= 1.5``).  No value is extrapolated.

    Where the two finest meshes' first crossings differ in half-waves, the modes that
    cross together on each mesh (:func:`tied_classes`: the classes located by
    :mod:`validation.studies.class_onsets` within :data:`CLASS_TIE` of the mesh's first)
    decide: a class tied for first on both meshes with the same half-waves on both is the
    converged mode (its count is reported); without class onsets, or without such a class,
    the count is not converged.

    Parameters
    ----------
    alpha : float
        Weight fraction (matched to ``1e-9``).
    tol : float, optional
        Largest difference of the two finest meshes' ``D0_b``.
    path : Path, optional
        The study's CSV (default: the package's :data:`CLAMP_UNITS_FILE`).
    formulation : str
        How ``J = 1`` is imposed in the rows used.
    classes_path : Path, optional
        The class onsets' CSV (default: the package's :data:`CLASS_ONSETS_FILE`).

    Returns
    -------
    dict
        ``D0_b`` (the finest mesh's), ``spread`` (the two finest meshes' difference),
        ``half_waves``, ``class`` (the mode's symmetry class), ``tied`` (the classes tied
        for first on the finest mesh, ``{class: half-waves}``, empty where the two finest
        rows agreed by themselves), ``meshes`` (the two finest, coarser first), ``rows``
        (every located row of ``alpha`` and ``formulation``, by unknowns).

    Raises
    ------
    ValueError
        ``alpha`` has fewer than two located rows, or the two finest do not hold the mode,
        count different half-waves or differ by more than ``tol``; the message says which
        and gives their numbers.
    """
    alpha = float(alpha)
    if tol is None:
        tol = 0.05 if alpha >= 1.5 else 0.02
    rows = [r for r in read_clamp_units(path) if r["D0_b"] and r["formulation"] == formulation
            and math.isclose(float(r["alpha"]), alpha, rel_tol=0.0, abs_tol=1e-9)]
    rows.sort(key=lambda r: int(r["dofs"]))
    if len(rows) < 2:
        raise ValueError(f"alpha = {alpha:g} has {len(rows)} located clamp-zone unit(s) with "
                         f"formulation {formulation!r} in {path or CLAMP_UNITS_FILE}: two "
                         f"meshes are needed")
    a, b = rows[-2], rows[-1]
    what = (f"alpha = {alpha:g}: {a['mesh']} graded {a['grading']} D0_b {a['D0_b']} "
            f"({a['half_waves']} half-waves, {float(a['elements_per_half_wave']):.1f} "
            f"elements each), {b['mesh']} graded {b['grading']} D0_b {b['D0_b']} "
            f"({b['half_waves']} half-waves, {float(b['elements_per_half_wave']):.1f} "
            f"elements each)")
    coarse = [r["mesh"] for r in (a, b)
              if float(r["elements_per_half_wave"]) < MIN_ELEMENTS_PER_HALF_WAVE]
    if coarse:
        raise ValueError(f"mesh too coarse for the mode ({', '.join(coarse)}: fewer than "
                         f"{MIN_ELEMENTS_PER_HALF_WAVE:g} elements per half-wave); {what}")
    name, n_half, tied = b["class"], int(b["half_waves"]), {}
    if a["half_waves"] != b["half_waves"]:
        ta, tb = tied_classes(a, classes_path), tied_classes(b, classes_path)
        shared = [c for c in tb if ta.get(c) == tb[c]]
        if not shared:
            ties = "; ".join(f"{r['mesh']}: " + (", ".join(
                f"{c} {n}" for c, n in sorted(t.items())) or "no class onsets")
                for r, t in ((a, ta), (b, tb)))
            raise ValueError(f"half-wave count not converged (tied classes: {ties}); {what}")
        name, tied = shared[0], tb
        n_half = tb[name]
    spread = abs(float(b["D0_b"]) - float(a["D0_b"]))
    if spread > tol:
        raise ValueError(f"D0_b not converged (spread {spread:.4f} > tol {tol:g}); {what}")
    return {"D0_b": float(b["D0_b"]), "spread": spread, "half_waves": n_half,
            "class": name, "tied": tied, "meshes": (a["mesh"], b["mesh"]), "rows": rows}


def tied_classes(row: dict, path: Path | None = None) -> dict:
    """The symmetry classes that cross together first on a clamp-zone unit's mesh.

    Parameters
    ----------
    row : dict
        A row of the clamp-zone study (``alpha``, ``mesh``, ``grading``, ``formulation``,
        ``D0_b``).
    path : Path, optional
        The class onsets' CSV (default: the package's :data:`CLASS_ONSETS_FILE`).

    Returns
    -------
    dict
        ``{class: half-waves}`` of the located classes of that unit whose ``D0_c`` lies
        within :data:`CLASS_TIE` of the lowest, in increasing ``D0_c``; empty where the unit
        has no located class or its lowest ``D0_c`` is not within :data:`CLASS_TIE` of the
        unit's ``D0_b`` (the two locations disagree).
    """
    mine = sorted((r for r in read_data_csv(path, CLASS_ONSETS_FILE)
                   if r["D0_c"] and unit_key(r) == unit_key(row)),
                  key=lambda r: float(r["D0_c"]))
    if not mine or abs(float(mine[0]["D0_c"]) - float(row["D0_b"])) > CLASS_TIE:
        return {}
    first = float(mine[0]["D0_c"])
    return {r["class"]: int(r["half_waves"]) for r in mine
            if float(r["D0_c"]) - first <= CLASS_TIE}




def _read_p33_units() -> list[dict]:
    return read_data_csv(None, P33_UNITS_FILE)


def clamp_study_tables() -> str:
    """The clamp-zone study as four Markdown tables, from the data files alone
    (``python -m validation.studies.clamp_units --tables``).

    The first has a row per unit (``formulation``, weight, mesh, grading; by weight and
    unknowns); the second a row per weight: the load of :func:`clamp_unit_load` (or why
    there is none), and the plain form's located ``P33`` onsets and Newton limit on the
    finest graded mesh that :mod:`validation.studies.p33_units` ran for the weight; the
    third a row per located class of :mod:`validation.studies.class_onsets`; the fourth a
    row per unit of :mod:`validation.studies.clamp_layer`.

    Returns
    -------
    str
    """
    rows = [r for r in read_clamp_units() if r["D0_b"]]
    rows.sort(key=lambda r: (float(r["alpha"]), r["formulation"] != "mixed", r["formulation"],
                             int(r["dofs"])))
    out = ["| alpha | mesh (grading) | formulation | unknowns | half-waves | elements per "
           "half-wave | `D0_b` | `J` at the clamp | flagged at `D0_b` | CPU s (solver) |",
           "| --- " * 10 + "|"]
    for r in rows:
        out.append(f"| {float(r['alpha']):g} | {r['mesh']} ({r['grading']}) | "
                   f"{r['formulation']} | {int(r['dofs'])} | {r['half_waves']} | "
                   f"{float(r['elements_per_half_wave']):.1f} | {float(r['D0_b']):.4f} | "
                   f"{float(r['J_min_clamp']):.2f}-{float(r['J_max_clamp']):.2f} | "
                   f"{r['n_flagged_b']} | {r['cpu_s']} ({r['solver']}) |")
    p33 = _read_p33_units()
    out += ["", "| alpha | `D0_b` (two finest meshes, spread) | `P33` onset: centre line / "
            "clamp line / interior (mesh) | Newton limit, plain form |", "| --- " * 4 + "|"]
    for a in sorted({float(r["alpha"]) for r in rows}):
        try:
            g = clamp_unit_load(a)
            load = (f"**{g['D0_b']:.4f}** ({g['meshes'][0]}, {g['meshes'][1]}; "
                    f"{g['spread']:.4f})")
            if g["tied"]:
                load += (f"; `{g['class']}`, {g['half_waves']} half-waves on both, tied "
                         f"with " + ", ".join(f"`{c}` ({n})" for c, n in g["tied"].items()
                                              if c != g["class"]))
        except ValueError as exc:
            load = "none: " + str(exc).split(";")[0]
        mine = [r for r in p33 if math.isclose(float(r["alpha"]), a, abs_tol=1e-9)
                and r["grading"] != "0.25"]
        if mine:
            r = max(mine, key=lambda r: int(r["dofs"]))
            def cell(k):
                name = k.removeprefix("P33_onset_")
                if not r[k]:
                    return "none"
                if f"{name}: below at the first target" in r["note"]:
                    return f"<= {float(r[k]):g} (below from the first step)"
                return f"{float(r[k]):.4f}"

            on = " / ".join(cell(k) for k in ("P33_onset_centre_line", "P33_onset_clamp",
                                               "P33_onset_interior"))
            onset, newton = (f"{on} ({r['mesh']} ({r['grading']}))",
                             r["newton_limit"] or f"none up to {float(r['D0_max']):g}")
        else:
            onset, newton = "not run", "not run"
        out.append(f"| {a:g} | {load} | {onset} | {newton} |")
    classes = [r for r in read_data_csv(None, CLASS_ONSETS_FILE) if r["D0_c"]]
    classes.sort(key=lambda r: (float(r["alpha"]), int(r["dofs"]), r["class"]))
    out += ["", "| alpha | mesh (grading) | class | half-waves | elements per half-wave | "
            "`D0_c` | bracket |", "| --- " * 7 + "|"]
    for r in classes:
        out.append(f"| {float(r['alpha']):g} | {r['mesh']} ({r['grading']}) | "
                   f"`{r['class']}` | {r['half_waves']} | "
                   f"{float(r['elements_per_half_wave']):.1f} | {float(r['D0_c']):.5f} | "
                   f"{r['lo']}-{r['hi']} |")
    layer = read_data_csv(None, CLAMP_LAYER_FILE)
    layer.sort(key=lambda r: (float(r["alpha"]), int(r["dofs"])))
    out += ["", "| alpha | mesh (grading) | `D0` | mean `J`, first / second element layer | "
            "`J` at the first layer's centres | volume ratio, layer 0.5 / 1 / 2 mm | "
            "whole model |", "| --- " * 7 + "|"]
    for r in layer:
        f = {k: float(v) for k, v in r.items() if k.startswith(("J_", "V_"))}
        out.append(f"| {float(r['alpha']):g} | {r['mesh']} ({r['grading']}) | "
                   f"{float(r['D0']):.4f} | {f['J_first_min']:.3f}-{f['J_first_max']:.3f} / "
                   f"{f['J_second_min']:.3f}-{f['J_second_max']:.3f} | "
                   f"{f['J_centre_min']:.3f}-{f['J_centre_max']:.3f} | "
                   f"{f['V_0.5mm']:.4f} / {f['V_1mm']:.4f} / {f['V_2mm']:.4f} | "
                   f"{f['V_plate']:.6f} |")
    return "\n".join(out) + "\n"


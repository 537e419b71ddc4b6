"""The clamp-zone study's tables and what is read from them: one :func:`load` for every
table, shipped or written by a run, the convergence rule of a weight's load
(:func:`clamp_unit_load`) and the tolerances the study locates to.

The shipped tables are package data (``validation/data/<file>``, read-only): the rows the
project's results rest on, each with the command that computed it.  Reading them loads no
finite elements.
"""

from __future__ import annotations

import errno
import math
from importlib import resources
from pathlib import Path

from .key import UnitKey
from .spec import TableSpec, read_table

#: the largest charge the study accepts (``--D0``, ``--D0-max``, ``--bracket``, a unit's
#: ``D0_b`` read from a table): its plates wrinkle or stop below D0 = 6
MAX_D0 = 50.0

__all__ = ["TABLES", "MAX_D0", "load", "table_file", "shipped_path", "unit_row",
           "scan_states", "plain_p33_row", "clamp_unit_load",
           "tied_classes",
           "MIN_ELEMENTS_PER_HALF_WAVE", "LOCATION_TOL", "CLASS_TIE", "LAYER_WIDTHS",
           "P33_SETS", "CLASS_COLUMNS"]

#: elements across the width per half-wave below which a mesh cannot hold the mode
MIN_ELEMENTS_PER_HALF_WAVE = 4.0
#: the tolerance in ``D0`` to which every located load of the study (``D0_b``, ``D0_c``,
#: a ``P33`` onset) is found: the least error of a graded load, whatever its meshes' spread
LOCATION_TOL = 1e-4
#: modes whose located crossings lie within this of a mesh's first (twice the location
#: tolerance) cross together: the mesh does not order them
CLASS_TIE = 2 * LOCATION_TOL
#: widths (mm) of the layers at the clamp whose volume ratio the ``layer`` table holds
LAYER_WIDTHS = (0.5, 1.0, 2.0)
#: the sets of ``P33`` onsets of the ``p33`` table
P33_SETS = ("centre_line", "clamp", "interior")
#: the ``counts`` table's columns of the eight symmetry classes (S/A about x1, x2, x3)
CLASS_COLUMNS = tuple(a + b + c for a in "SA" for b in "SA" for c in "SA")

_UNIT = ("alpha", "mesh", "grading", "formulation")
_MODEL = "eighth model, neo-Hookean, g = 9.81"

#: the study's tables by name (:class:`~validation.clamp_zone.table.TableSpec`)
TABLES = {t.name: t for t in (
    TableSpec("units", "clamp_units.csv",
              _UNIT + ("dofs", "D0_step", "D0_b", "class", "corner_share", "mesh_scale",
                       "half_waves", "elements_per_half_wave", "J_min_clamp", "J_max_clamp",
                       "n_flagged_b", "states", "factorisations", "cpu_s", "peak_GB",
                       "solver", "date", "scan_counts", "note", "command"),
              _UNIT, f"""\
# The clamp-zone wrinkle of the Keplinger plate, unit by unit (one alpha on one mesh per row).
# Written by skfem-dielectric clamp-zone units (docs/clamp-zone.md defines every column):
# {_MODEL}, grad-div 10, grading = last / first element length
# along x1 (towards the clamp); D0_b located to 1e-4; J at the mid-plane centres of the
# elements next to the clamp at D0_b; cpu_s and peak_GB of the unit's process.
"""),
    TableSpec("onsets", "class_onsets.csv",
              _UNIT + ("class", "dofs", "lo", "hi", "D0_c", "half_waves",
                       "elements_per_half_wave", "corner_share", "mesh_scale",
                       "factorisations", "cpu_s", "peak_GB", "solver", "date", "note",
                       "command"),
              _UNIT + ("class",), f"""\
# The first physical crossing of each symmetry class inside the bracket of a clamp-zone unit
# (the units table).  Written by skfem-dielectric clamp-zone onsets (docs/clamp-zone.md
# defines every column): {_MODEL}, grad-div 10; D0_c
# located to 1e-4 with the class's own indicator; cpu_s and peak_GB of the unit's process.
"""),
    TableSpec("p33", "p33_units.csv",
              ("alpha", "mesh", "grading", "dofs", "D0_step")
              + tuple(f"P33_onset_{k}" for k in P33_SETS)
              + ("newton_limit", "D0_max", "states", "trials", "factorisations", "cpu_s",
                 "peak_GB", "solver", "date", "note", "command"),
              ("alpha", "mesh", "grading"), f"""\
# The P33 breakdown of the Keplinger plate on graded meshes, located (one alpha on one mesh
# per row).  Written by skfem-dielectric clamp-zone p33 (docs/clamp-zone.md defines every
# column): {_MODEL}, plain form (grad_div = 0); an onset is the
# D0 where min P33/mu on its set reaches -0.01, located to 1e-4 by Brent's method.
"""),
    TableSpec("layer", "clamp_layer.csv",
              _UNIT + ("dofs", "D0", "J_first_min", "J_first_max", "J_second_min",
                       "J_second_max", "J_centre_min", "J_centre_max",
                       *(f"V_{d:g}mm" for d in LAYER_WIDTHS), "V_plate", "cpu_s",
                       "peak_GB", "solver", "date", "command"),
              _UNIT, """\
# J in the clamp layer of the Keplinger plate at the located clamp-zone onset D0 (= D0_b of
# the units table).  Written by skfem-dielectric clamp-zone layer (docs/clamp-zone.md
# defines every column): element volume ratios of the first and second element
# layers at the clamp, J at the first layer's mid-plane centres, volume ratios of the
# layers L - d < X1 < L and of the whole model.
"""),
    TableSpec("flagged", "flagged_modes.csv",
              ("alpha", "mesh", "grading", "D0", "dofs", "eigenvalue", "class", "kind",
               "corner_share", "mesh_scale", "X1", "X2", "X3", "layer", "cpu_s", "date",
               "command"),
              ("alpha", "mesh", "grading", "D0"), f"""\
# The negative modes of the whole plate at one state of a clamp-zone unit, one row per mode.
# Written by skfem-dielectric clamp-zone flagged (docs/clamp-zone.md defines every column):
# {_MODEL}, grad-div 10; energy centroid X1, X2, X3 in mm (the
# clamp at X1 = 50); layer = element layer along X1 counted from the clamp; cpu_s of the
# state's analysis.
""", multi=True),
    TableSpec("counts", "edge_counts.csv",
              _UNIT + ("grad_div", "pressure", "D0", "dofs", "n_negative", "n_x2A")
              + CLASS_COLUMNS + ("cpu_s", "count_cpu_s", "peak_GB", "factorisations",
                                 "solver", "date", "command"),
              _UNIT + ("grad_div", "pressure", "D0"), f"""\
# Negative-mode counts of the whole clamped plate at a few charges, one row per state.
# Written by skfem-dielectric clamp-zone counts (docs/clamp-zone.md defines every column):
# {_MODEL}, grading = last / first element length along x1;
# counts by Sylvester's law of inertia (no classification: the corner quartet is 4 of them).
"""),
    TableSpec("section", "edge_section.csv",
              ("alpha", "mesh", "grading", "grad_div", "D0", "length", "h0", "k",
               "section_dofs", "n_negative", "base_iterations", "J_min", "J_max",
               "F11_section", "F11_3d", "count_cpu_s", "base_cpu_s", "state_cpu_s",
               "peak_GB", "date", "command"),
              ("alpha", "mesh", "grading", "grad_div", "D0", "length", "h0", "k"), """\
# Negative modes of the clamp-edge section against waves cos/sin(k X3), one row per k.
# Written by skfem-dielectric clamp-zone section (docs/clamp-zone.md defines every column):
# eighth-model plate, neo-Hookean, g = 9.81; section at the centre plane, base state solved
# on the section's own mesh (edge elements h0, mm, H = 1).
"""),
)}


def shipped_path(name: str) -> Path:
    """The shipped table ``name`` (:data:`TABLES`) in the package's ``data`` folder."""
    return Path(str(resources.files("validation") / "data" / TABLES[name].file))


def load(name: str, where=None, *, note=None) -> list[dict]:
    """The rows of one of the study's tables, as dicts of the cells' text.

    Parameters
    ----------
    name : str
        One of :data:`TABLES`: ``units``, ``onsets``, ``p33``, ``layer``, ``flagged``,
        ``counts``, ``section``.
    where : path-like, optional
        The table's file, or a folder that holds it (a run's ``--out``); default: the
        shipped table.  A missing file has no rows.
    note : callable, optional
        ``note(message)`` for each damaged row left out (:func:`~validation.clamp_zone.table.read_table`).

    Raises
    ------
    ValueError
        ``name`` is not a table of the study, or the file is another table.

    Examples
    --------
    >>> rows = load("units")
    >>> sorted({r["alpha"] for r in rows})
    ['0.05', '0.3', '0.7', '1', '1.5']
    """
    if name not in TABLES:
        raise ValueError(f"name must be one of {', '.join(TABLES)}, got {name!r}")
    return read_table(table_file(name, where), TABLES[name], note=note)


def table_file(name: str, where=None) -> Path:
    """The file of the table ``name``: ``where`` itself, or the table's file in the folder
    ``where``, or the shipped table (``where`` is ``None``)."""
    if where is None:
        return shipped_path(name)
    path = Path(where)
    return path / TABLES[name].file if path.is_dir() else path


def scan_states(row: dict) -> list[tuple[float, int, int]]:
    """Every state a unit scanned, ``(D0, negative, physical)`` in scan order (refined
    steps last), from its row's ``scan_counts`` cell (``D0:negative/physical ...``).

    Raises
    ------
    ValueError
        The cell is not of that form; the message names the unit and the item.

    Examples
    --------
    >>> scan_states({"alpha": "1", "mesh": "4x1x2", "scan_counts": "0.5:4/0 1:6/1"})
    [(0.5, 4, 0), (1.0, 6, 1)]
    """
    out = []
    for item in str(row.get("scan_counts") or "").split():
        try:
            d, counts = item.split(":")
            neg, phys = counts.split("/")
            out.append((float(d), int(neg), int(phys)))
        except ValueError:
            raise ValueError(f"the unit alpha = {row.get('alpha')} {row.get('mesh')} has "
                             f"{item!r} in scan_counts, not D0:negative/physical") from None
    return out


def plain_p33_row(alpha: float, where=None) -> dict | None:
    """The ``p33`` row of weight ``alpha`` on its finest graded mesh (most unknowns): the
    plain form's located ``P33`` onsets and Newton limit that the docs and the figures
    quote for the weight; ``None`` if the weight has no row.

    Parameters
    ----------
    alpha : float
        Weight fraction (matched to ``1e-9``).
    where : path-like, optional
        The ``p33`` table (a file or folder; default: the shipped one).
    """
    mine = [r for r in load("p33", where)
            if math.isclose(float(r["alpha"]), float(alpha), rel_tol=0.0, abs_tol=1e-9)]
    return max(mine, key=lambda r: int(r["dofs"])) if mine else None


def unit_row(key: UnitKey, where=None) -> dict:
    """The ``units`` row of one unit: from the table ``where`` (a file or folder) where it
    has the unit, else from the shipped table.

    Raises
    ------
    ValueError
        No table has the unit: the message names it and the command that computes it.
    OSError
        The unit's ``D0_b`` is not empty and not a charge in ``(0, MAX_D0]``: the message
        names the table (exit code 3 of the CLI: a damaged row).
    """
    for source in ((where, None) if where is not None else (None,)):
        for r in load("units", source):
            if UnitKey.from_row(r) == key:
                d0b = float(r["D0_b"] or "nan")
                if r["D0_b"] and not (0 < d0b <= MAX_D0):
                    raise OSError(errno.EINVAL, f"the row of the clamp-zone unit {key} has "
                                  f"D0_b = {r['D0_b']}, not a charge in (0, {MAX_D0:g}]; "
                                  f"compute that unit again", str(table_file("units", source)))
                return r
    raise ValueError(f"no clamp-zone unit {key} in the units table: run skfem-dielectric "
                     f"clamp-zone units for it first")


def clamp_unit_load(alpha: float, *, tol: float | None = None, path=None,
                    formulation: str = "mixed", classes_path=None) -> dict:
    """The clamp-zone buckling load of ``alpha`` where the study's two finest meshes agree.

    The rows of ``alpha`` (``formulation``, a located ``D0_b``) ordered by unknowns; the
    two finest must hold the mode (at least :data:`MIN_ELEMENTS_PER_HALF_WAVE` elements
    across the width per half-wave), count the same half-waves and give ``D0_b`` within
    ``tol`` (default 0.02; 0.05 for ``alpha >= 1.5``).  No value is extrapolated.

    Where the two finest meshes' first crossings differ in half-waves, the modes that
    cross together on each mesh (:func:`tied_classes`: the classes of the ``onsets`` table
    within :data:`CLASS_TIE` of the mesh's first) decide: a class tied for first on both
    meshes with the same half-waves on both is the converged mode (its count is reported);
    without class onsets, or without such a class, the count is not converged.

    Parameters
    ----------
    alpha : float
        Weight fraction (matched to ``1e-9``).
    tol : float, optional
        Largest difference of the two finest meshes' ``D0_b``.
    path : path-like, optional
        The ``units`` table (a file or folder; default: the shipped one).
    formulation : str
        How ``J = 1`` is imposed in the rows used.
    classes_path : path-like, optional
        The ``onsets`` table (default: the shipped one).

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
    rows = [r for r in load("units", path) if r["D0_b"] and r["formulation"] == formulation
            and math.isclose(float(r["alpha"]), alpha, rel_tol=0.0, abs_tol=1e-9)]
    rows.sort(key=lambda r: int(r["dofs"]))
    if len(rows) < 2:
        raise ValueError(f"alpha = {alpha:g} has {len(rows)} located clamp-zone unit(s) with "
                         f"formulation {formulation!r} in "
                         f"{path or shipped_path('units').name}: two meshes are needed")
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


def tied_classes(row: dict, path=None) -> dict:
    """The symmetry classes that cross together first on a clamp-zone unit's mesh.

    Parameters
    ----------
    row : dict
        A row of the ``units`` table (``alpha``, ``mesh``, ``grading``, ``formulation``,
        ``D0_b``).
    path : path-like, optional
        The ``onsets`` table (default: the shipped one).

    Returns
    -------
    dict
        ``{class: half-waves}`` of the located classes of that unit whose ``D0_c`` lies
        within :data:`CLASS_TIE` of the lowest, in increasing ``D0_c``; empty where the unit
        has no located class or its lowest ``D0_c`` is not within :data:`CLASS_TIE` of the
        unit's ``D0_b`` (the two locations disagree).
    """
    key = UnitKey.from_row(row)
    mine = sorted((r for r in load("onsets", path)
                   if r["D0_c"] and UnitKey.from_row(r) == key),
                  key=lambda r: float(r["D0_c"]))
    if not mine or abs(float(mine[0]["D0_c"]) - float(row["D0_b"])) > CLASS_TIE:
        return {}
    first = float(mine[0]["D0_c"])
    return {r["class"]: int(r["half_waves"]) for r in mine
            if float(r["D0_c"]) - first <= CLASS_TIE}

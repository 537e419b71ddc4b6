"""The registry of the measured tables: their schemas (:data:`TABLES`), one :func:`load`
for every table, shipped or written by a run, and the bounds and tolerances of the
clamp-zone study.

The shipped tables are package data (``validation/data/<file>``, read-only): the rows the
project's results rest on, each with the command that computed it.  Reading them loads no
finite elements.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from ..specs import LOCATION_TOL
from .spec import TableSpec, read_table

#: the largest charge the study accepts (``--D0``, ``--D0-max``, ``--bracket``, a unit's
#: ``D0_b`` read from a table): its plates wrinkle or stop below D0 = 6
MAX_D0 = 50.0

__all__ = ["TABLES", "MAX_D0", "load", "table_file", "shipped_path",
           "FORMER_UNTIL", "MIN_ELEMENTS_PER_HALF_WAVE", "CLASS_TIE", "LAYER_WIDTHS", "P33_SETS",
           "CLASS_COLUMNS"]

#: elements across the width per half-wave below which a mesh cannot hold the mode
MIN_ELEMENTS_PER_HALF_WAVE = 4.0
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

#: the last release that reads a table under its former file name
#: (:attr:`~validation.data.spec.TableSpec.former`): each table's file is
#: ``clamp_<name>.csv``, written by ``clamp-zone <name>`` and tested in
#: ``tests/validation/test_clamp_<name>.py``
FORMER_UNTIL = "0.1"

#: the study's tables by name (:class:`~validation.data.spec.TableSpec`)
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
    TableSpec("onsets", "clamp_onsets.csv",
              _UNIT + ("class", "dofs", "lo", "hi", "D0_c", "half_waves",
                       "elements_per_half_wave", "corner_share", "mesh_scale",
                       "factorisations", "cpu_s", "peak_GB", "solver", "date", "note",
                       "command"),
              _UNIT + ("class",), f"""\
# The first physical crossing of each symmetry class inside the bracket of a clamp-zone unit
# (the units table).  Written by skfem-dielectric clamp-zone onsets (docs/clamp-zone.md
# defines every column): {_MODEL}, grad-div 10; D0_c
# located to 1e-4 with the class's own indicator; cpu_s and peak_GB of the unit's process.
""", former="class_onsets.csv"),
    TableSpec("p33", "clamp_p33.csv",
              ("alpha", "mesh", "grading", "dofs", "D0_step")
              + tuple(f"P33_onset_{k}" for k in P33_SETS)
              + ("newton_limit", "D0_max", "states", "trials", "factorisations", "cpu_s",
                 "peak_GB", "solver", "date", "note", "command"),
              ("alpha", "mesh", "grading"), f"""\
# The P33 breakdown of the Keplinger plate on graded meshes, located (one alpha on one mesh
# per row).  Written by skfem-dielectric clamp-zone p33 (docs/clamp-zone.md defines every
# column): {_MODEL}, plain form (grad_div = 0); an onset is the
# D0 where min P33/mu on its set reaches -0.01, located to 1e-4 by Brent's method.
""", former="p33_units.csv"),
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
    TableSpec("flagged", "clamp_flagged.csv",
              ("alpha", "mesh", "grading", "D0", "dofs", "eigenvalue", "class", "kind",
               "corner_share", "mesh_scale", "X1", "X2", "X3", "layer", "cpu_s", "date",
               "command"),
              ("alpha", "mesh", "grading", "D0"), f"""\
# The negative modes of the whole plate at one state of a clamp-zone unit, one row per mode.
# Written by skfem-dielectric clamp-zone flagged (docs/clamp-zone.md defines every column):
# {_MODEL}, grad-div 10; energy centroid X1, X2, X3 in mm (the
# clamp at X1 = 50); layer = element layer along X1 counted from the clamp; cpu_s of the
# state's analysis.
""", multi=True, former="flagged_modes.csv"),
    TableSpec("counts", "clamp_counts.csv",
              _UNIT + ("grad_div", "pressure", "D0", "dofs", "n_negative", "n_x2A")
              + CLASS_COLUMNS + ("cpu_s", "count_cpu_s", "peak_GB", "factorisations",
                                 "solver", "date", "command"),
              _UNIT + ("grad_div", "pressure", "D0"), f"""\
# Negative-mode counts of the whole clamped plate at a few charges, one row per state.
# Written by skfem-dielectric clamp-zone counts (docs/clamp-zone.md defines every column):
# {_MODEL}, grading = last / first element length along x1;
# counts by Sylvester's law of inertia (no classification: the corner quartet is 4 of them).
""", former="edge_counts.csv"),
    TableSpec("section", "clamp_section.csv",
              ("alpha", "mesh", "grading", "grad_div", "pressure", "D0", "length", "h0", "k",
               "section_dofs", "n_negative", "base_iterations", "J_min", "J_max",
               "F11_section", "F11_3d", "count_cpu_s", "base_cpu_s", "state_cpu_s",
               "peak_GB", "date", "command"),
              ("alpha", "mesh", "grading", "grad_div", "pressure", "D0", "length", "h0", "k"),
              """\
# Negative modes of the clamp-edge section against waves cos/sin(k X3), one row per k.
# Written by skfem-dielectric clamp-zone section (docs/clamp-zone.md defines every column):
# eighth-model plate, neo-Hookean, g = 9.81; section at the centre plane, base state solved
# on the section's own mesh (edge elements h0, mm, H = 1); pressure space Q1 or P0.
""", added=(("pressure", "Q1"),), former="edge_section.csv"),
    TableSpec("voltage", "clamp_voltage.csv",
              _UNIT + ("grad_div", "dofs", "s", "E0_limit", "D0_limit", "lam1_limit",
                       "J_min_limit", "J_max_limit", "max_E0",
                       "lam1_max_E0", "ratio", "E0_membrane", "E0_stable", "D0_stable",
                       "E0_physical", "D0_physical", "physical_class",
                       "n_negative_start", "E0_first",
                       "first_eigenvalue", "first_class", "first_kind",
                       "first_corner_share", "first_mesh_scale", "first_X1", "first_X2",
                       "first_X3", "first_layer", "points", "iterations", "factorisations",
                       "cpu_s", "peak_GB", "solver", "date", "note", "command"),
              _UNIT + ("grad_div",), f"""\
# The clamped plate under voltage control, unit by unit (one alpha on one mesh per row).
# Written by skfem-dielectric clamp-zone voltage (docs/clamp-zone.md defines every column):
# {_MODEL}, grad-div grad_div (mu; the units' 10); E0 followed at fixed s by arclength
# continuation, its first limit point located; max_E0: the homogeneous uni-axial limit at s;
# E0_membrane: the limit of the clamped membrane (20 x 10 Q2 elements on the quarter);
# the first point with a physical negative mode and the point before it (E0/D0_physical,
# E0/D0_stable: the crossing lies between them; D0 at the plate's centre);
# the first negative mode the dead load does not have, before the limit, with its energy
# centroid (mm; clamp at X1 = 50); cpu_s and peak_GB of the unit's process.
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
        ``note(message)`` for each damaged row left out (:func:`~validation.data.spec.read_table`).

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
    ``where`` (its :attr:`~validation.data.spec.TableSpec.former` name in a folder of an
    earlier release), or the shipped table (``where`` is ``None``)."""
    if where is None:
        return shipped_path(name)
    path = Path(where)
    if not path.is_dir():
        return path
    spec = TABLES[name]
    if spec.former and not (path / spec.file).exists() and (path / spec.former).is_file():
        return path / spec.former       # a folder written before the table's renaming
    return path / spec.file

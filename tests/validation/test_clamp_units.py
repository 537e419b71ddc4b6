"""The clamp-zone wrinkle study, unit by unit (validation.clamp_zone.units and
``skfem-dielectric clamp-zone units``)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from validation.data.key import UnitKey

import skfem_dielectric as fe
from skfem_dielectric.studies.buckling import buckling_load
from validation.fe.model import BUCKLING_GRAD_DIV, BUCKLING_NEWTON
from validation.cli import main
from validation.data.clamp_zone import clamp_unit_load
from validation.data.registry import TABLES, load
from validation.specs import LOCATION_TOL
from validation.clamp_zone.units import COLUMNS, UNIT_SETTINGS, run_unit


def test_a_unit_locates_the_buckling_studys_load_and_writes_its_row(tmp_path):
    """alpha = 1 on the graded 6 x 1 x 3 eighth model, D0 in steps of 1: the unit's D0_b
    against buckling_load of the whole ramp (another driver of the same scan and
    location: both to 1e-4); the row holds every column, J at the clamp layer is that of
    a compressible-looking discrete layer (the coarse mesh cannot hold it: J < 0.8), the
    half-waves are counted across the whole width, and a rerun keeps the row."""
    row = run_unit(UnitKey(1.0, (6, 1, 3), 0.5), D0_step=1.0, modes_dir=tmp_path / "modes")
    # the mode at D0_b: the top face of the whole plate at the element vertices (both
    # halves of each plane of symmetry: 2 n1 + 1 by 2 n3 + 1 points)
    with np.load(tmp_path / "modes" / "1_6x1x3_g0.5_mixed.npz") as z:
        assert z["D0_b"] == row["D0_b"]
        assert z["X1"].shape == z["X3"].shape == z["u2"].shape
        assert len(np.unique(z["X1"])) == 2 * 6 + 1 and len(np.unique(z["X3"])) == 2 * 3 + 1
        assert np.abs(z["u2"]).max() > 0
    from validation.clamp_zone.modes import clamp_modes_figure, read_clamp_modes
    (mode,) = read_clamp_modes(tmp_path / "modes")
    assert (mode["alpha"], mode["mesh"], mode["grading"], mode["formulation"]) == \
        (1.0, "6x1x3", 0.5, "mixed")
    fig = clamp_modes_figure([mode])
    assert f"{row['D0_b']:.4f}" in fig.axes[0].get_title()
    with pytest.raises(ValueError, match="holds no mode"):
        read_clamp_modes(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = fe.keplinger_plate(1.0, D0=[1.0, 2.0, 3.0, 4.0], elements=(6, 1, 3),
                                 grading=0.5, options=fe.PlateOptions(grad_div=BUCKLING_GRAD_DIV),
                                 settings=UNIT_SETTINGS)
    charge = [st for st in res.steps if st.load[1] > 0]
    states = [res.steps[len(res.steps) - len(charge) - 1]] + charge
    ref = buckling_load(res.problem, [(st.x, st.load) for st in states], tol=LOCATION_TOL,
                        settings=BUCKLING_NEWTON)
    assert ref.found and abs(row["D0_b"] - ref.D0_b) <= 2 * LOCATION_TOL
    assert row["class"] == ref.label.symmetry
    assert row["half_waves"] >= 1 and row["elements_per_half_wave"] == 6 / row["half_waves"]
    assert 0.5 < row["J_min_clamp"] <= row["J_max_clamp"] < 0.8
    assert row["dofs"] == res.problem.ndofs
    run = tmp_path / "run"
    argv = ["clamp-zone", "units", "--alpha", "1", "--mesh", "6x1x3", "--grading", "0.5",
            "--D0-step", "1", "--out", str(run)]
    assert main(argv) == 0
    out = run / "clamp_units.csv"
    rows = load("units", run)
    assert len(rows) == 1 and list(rows[0]) == list(COLUMNS)
    assert rows[0]["command"].startswith("skfem-dielectric clamp-zone units --alpha 1")
    assert (run / "modes" / "1_6x1x3_g0.5_mixed.npz").is_file()
    assert math.isclose(float(rows[0]["D0_b"]), row["D0_b"], abs_tol=1e-5)
    before = out.read_bytes()
    assert main(argv) == 0                      # kept, not recomputed
    assert out.read_bytes() == before


def test_bad_mesh_is_one_message(tmp_path, capsys):
    assert main(["clamp-zone", "units", "--alpha", "1", "--mesh", "6x1",
                 "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "a mesh is n1xn2xn3" in err[0] and "'6x1'" in err[0]
    assert list(tmp_path.iterdir()) == []


def test_the_smallest_committed_unit_is_reproduced():
    """The smallest mesh of the committed study (alpha = 1, 12 x 1 x 6 graded 0.25) run
    again: D0_b within twice its location tolerance, the same class, half-wave count and
    J at the clamp layer (4 digits) as its row in validation/data/clamp_units.csv."""
    ref = next(r for r in load("units") if r["alpha"] == "1" and r["mesh"] == "12x1x6"
               and r["grading"] == "0.25" and r["formulation"] == "mixed")
    row = run_unit(UnitKey(1.0, (12, 1, 6), 0.25))
    assert abs(row["D0_b"] - float(ref["D0_b"])) <= 2 * LOCATION_TOL
    assert row["class"] == ref["class"]
    assert row["half_waves"] == int(ref["half_waves"])
    assert row["dofs"] == int(ref["dofs"])
    assert math.isclose(row["J_min_clamp"], float(ref["J_min_clamp"]), abs_tol=1e-4)
    assert math.isclose(row["J_max_clamp"], float(ref["J_max_clamp"]), abs_tol=1e-4)


def _units(tmp_path, rows):
    path = tmp_path / "units.csv"
    with open(path, "w") as fh:
        fh.write(TABLES["units"].declaration + "\n# test rows\n" + ",".join(COLUMNS) + "\n")
        for r in rows:
            fh.write(",".join(str(r.get(k, "")) for k in COLUMNS) + "\n")
    return path


def _row(mesh, dofs, D0_b, hw, eph):
    return {"alpha": 1, "mesh": mesh, "grading": 0.1, "formulation": "mixed", "dofs": dofs,
            "D0_b": D0_b, "half_waves": hw, "elements_per_half_wave": eph}


def test_clamp_unit_load_needs_two_finest_meshes_that_hold_and_agree(tmp_path):
    """The load is the finest mesh's where the two finest hold the mode (>= 4 elements per
    half-wave), count the same half-waves and agree within 0.02; every other case is a
    ValueError naming why, never an extrapolated value."""
    ok = _units(tmp_path, [_row("10x1x24", 10, 2.9, 22, 2.2), _row("20x1x48", 20, 3.36, 13, 7.4),
                           _row("30x1x48", 30, 3.37, 13, 7.4)])
    got = clamp_unit_load(1.0, path=ok)
    assert got["D0_b"] == 3.37 and math.isclose(got["spread"], 0.01, abs_tol=1e-12)
    assert got["meshes"] == ("20x1x48", "30x1x48") and got["half_waves"] == 13
    cases = {"too coarse": [_row("20x1x24", 20, 3.3687, 13, 3.7), _row("30x1x24", 30, 3.3703, 14, 3.4)],
             "half-wave count": [_row("20x1x40", 20, 3.36, 13, 7.4), _row("30x1x40", 30, 3.37, 14, 6.9)],
             "spread 0.0300": [_row("20x1x40", 20, 3.34, 13, 7.4), _row("30x1x40", 30, 3.37, 13, 7.4)],
             "two meshes are needed": [_row("20x1x40", 20, 3.34, 13, 7.4)]}
    for i, (msg, rows) in enumerate(cases.items()):
        (tmp_path / str(i)).mkdir()
        with pytest.raises(ValueError, match=msg):
            clamp_unit_load(1.0, path=_units(tmp_path / str(i), rows))
    with pytest.raises(ValueError, match="alpha = 2 has 0 located"):
        clamp_unit_load(2.0)             # the committed file has no unit of this weight

"""The whole plate's negative modes at one state (validation.clamp_zone.flagged)."""

from __future__ import annotations

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.models.plate.scan import PlateScan
from validation.fe.model import BUCKLING_GRAD_DIV
from validation.cli import main
from validation.data.registry import load
from validation.clamp_zone.flagged import COLUMNS, run_flagged
from validation.data.key import UnitKey


def test_every_negative_mode_is_a_row_and_the_clamps_mirror_each_other():
    """alpha = 1, 10 x 1 x 24 graded 0.1 at D0 = 2.75: one row per negative eigenvalue of
    the whole plate (Sylvester's count by PlateScan.count at the same state: no eigenpair
    computed), each row's layer the element layer of its centroid's X1, and the modes at
    the clamps come in mirror pairs about the plate's centre (classes x1 S and x1 A, the
    clamps 100 mm apart): equal eigenvalues to 1e-6 of the largest."""
    rows = run_flagged(UnitKey(1.0, (10, 1, 24), 0.1), 2.75)
    res = fe.keplinger_plate(1.0, D0=list(np.arange(0.5, 2.75, 0.5)) + [2.75],
                             elements=(10, 1, 24), grading=0.1,
                             options=fe.PlateOptions(grad_div=BUCKLING_GRAD_DIV),
                             settings=fe.gallery.KEPLINGER_SETTINGS)
    last = res.steps[-1]
    assert last.load[1] == 2.75
    counts = PlateScan(res.problem).count(last.x, last.load)
    assert len(rows) == sum(counts.values()) > 0
    g1 = res.problem.plate.grids[0]
    for r in rows:
        assert g1[len(g1) - 1 - r["layer"]] <= r["X1"] <= g1[len(g1) - r["layer"]]
    sym = sorted(r["eigenvalue"] for r in rows if r["class"].startswith("x1 S"))
    anti = sorted(r["eigenvalue"] for r in rows if r["class"].startswith("x1 A"))
    np.testing.assert_allclose(sym, anti, rtol=0, atol=1e-6 * np.abs(sym).max())


def test_a_state_is_written_once_and_bad_input_is_one_line(tmp_path, capsys):
    out = tmp_path / "clamp_flagged.csv"
    args = ["clamp-zone", "flagged", "--alpha", "1", "--mesh", "4x1x2", "--grading", "0.5",
            "--D0", "0.5", "--out", str(tmp_path)]
    assert main(args) == 0
    rows = load("flagged", tmp_path)
    assert rows and list(rows[0]) == list(COLUMNS)
    before = out.read_bytes()
    assert main(args) == 0 and out.read_bytes() == before
    assert main(["clamp-zone", "flagged", "--alpha", "1", "--mesh", "4x1x2", "--D0", "-1",
                 "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert "--D0 must be > 0 and finite, got -1" in err[-1]
    assert out.read_bytes() == before

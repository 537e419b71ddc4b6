"""Each symmetry class's crossing at a clamp-zone unit's bracket
(validation.clamp_zone.onsets)."""

from __future__ import annotations

from pathlib import Path

import pytest

from validation.data.key import UnitKey

from validation.cli import main
from validation.data.registry import load
from validation.specs import LOCATION_TOL
from validation.clamp_zone.onsets import COLUMNS, bracket, run_onsets


def _unit(alpha: str, mesh: str, grading: str) -> dict:
    return next(r for r in load("units") if r["alpha"] == alpha and r["mesh"] == mesh
                and r["grading"] == grading and r["formulation"] == "mixed")


def test_the_bracket_is_the_last_two_scanned_states_around_D0_b():
    """alpha = 1, 10 x 1 x 24 graded 0.1: its scan ends ... 2.90625:92/0 2.9375:94/2 and
    D0_b = 2.90859 lies between (exact values of the scan's grid)."""
    assert bracket(_unit("1", "10x1x24", "0.1")) == (2.90625, 2.9375)
    with pytest.raises(ValueError, match="no located D0_b"):
        bracket({"alpha": "1", "mesh": "4x1x2", "D0_b": "", "scan_counts": "0.5:0/0"})
    with pytest.raises(ValueError, match="both sides"):
        bracket({"alpha": "1", "mesh": "4x1x2", "D0_b": "1.2", "scan_counts": "0.5:0/0 1:0/0"})


def test_the_class_of_a_unit_reproduces_its_D0_b_along_another_path(tmp_path):
    """alpha = 1, 10 x 1 x 24 graded 0.1: its row's class ('x1 S, x2 A, x3 A', 22
    half-waves) located again from a ramp that scans only the bracket's two ends and with
    that class's indicator alone lands within twice the location tolerance of the row's
    D0_b (the unit located it from its full scan); the row holds every column."""
    ref = _unit("1", "10x1x24", "0.1")
    rows = run_onsets(UnitKey(1.0, (10, 1, 24), 0.1), classes=[ref["class"]])
    assert len(rows) == 1 and rows[0]["class"] == ref["class"]
    assert abs(rows[0]["D0_c"] - float(ref["D0_b"])) <= 2 * LOCATION_TOL
    assert rows[0]["half_waves"] == int(ref["half_waves"])
    assert rows[0]["dofs"] == int(ref["dofs"])
    assert (rows[0]["lo"], rows[0]["hi"]) == bracket(ref)
    assert set(rows[0]) >= set(COLUMNS) - {"note", "command"}


def test_the_mirror_classes_about_the_centre_cross_together():
    """The two clamps are 2 L apart: a mode and its mirror image about x1 = 0 (classes
    'x1 S' and 'x1 A', the same x2, x3 classes) cross at the same charge within the
    location tolerance, with the same half-waves, in every committed row pair."""
    rows = load("onsets")
    pairs = 0
    for r in rows:
        if not r["class"].startswith("x1 S") or not r["D0_c"]:
            continue
        twin = [q for q in rows if q["class"] == "x1 A" + r["class"][4:]
                and (q["alpha"], q["mesh"], q["grading"], q["formulation"])
                == (r["alpha"], r["mesh"], r["grading"], r["formulation"]) and q["D0_c"]]
        for q in twin:
            pairs += 1
            assert abs(float(q["D0_c"]) - float(r["D0_c"])) <= 2 * LOCATION_TOL, (r, q)
            assert q["half_waves"] == r["half_waves"]
    assert pairs >= 1


def test_bad_input_is_one_line(tmp_path, capsys):
    """A unit without a clamp-zone row exits 2 with one line naming it and the command to
    run first; no table is written."""
    assert main(["clamp-zone", "onsets", "--alpha", "0.9", "--mesh", "4x1x2",
                 "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "alpha = 0.9 4x1x2" in err[0] and "clamp-zone units" in err[0]
    assert not (tmp_path / "clamp_onsets.csv").exists()


@pytest.mark.slow
def test_a_given_bracket_needs_no_unit_and_says_so():
    """The bracket of the 10 x 1 x 24 unit given by hand (no unit row read): the same
    class located within twice the tolerance of the unit's D0_b, and the row's note says
    that nothing on this mesh was scanned below lo; a bracket that is not 0 < lo < hi is a
    ValueError naming it."""
    ref = _unit("1", "10x1x24", "0.1")
    rows = run_onsets(UnitKey(1.0, (10, 1, 24), 0.1), classes=[ref["class"]],
                            given=(2.90625, 2.9375), units=Path("/nonexistent.csv"))
    assert abs(rows[0]["D0_c"] - float(ref["D0_b"])) <= 2 * LOCATION_TOL
    assert "bracket given" in rows[0]["note"]
    with pytest.raises(ValueError, match="bracket must be 0 < lo < hi, got 3, 2"):
        run_onsets(UnitKey(1.0, (4, 1, 2), 1.0), given=(3.0, 2.0))

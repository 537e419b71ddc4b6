"""``check`` under careless input: every file ends in a verdict or one line with a
documented exit code, never a traceback, a MemoryError or a dropped row.

References are computed here: the neo-Hookean equi-biaxial loading curve as a polynomial
root (Eq. loading_gent), the converged buckling load as printed in the package's data, the
size bounds as documented (``MAX_FILE_BYTES``, ``MAX_TOTAL_BYTES``)."""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path

import numpy as np
import pytest

import validation
import validation.check_report as check_report
from validation.data.loads import converged_buckling_load
from validation.checker import (MAX_FILE_BYTES, MAX_TOTAL_BYTES, parse_tolerances)
from validation.cli import EXIT_CODES, main


def _lam(D0: float, s: float) -> float:
    """Eq. (loading_gent), neo-Hookean: the positive root of lam^6 - s lam^5 - 1 - D0^2."""
    r = np.roots([1.0, -s, 0.0, 0.0, 0.0, 0.0, -(1.0 + D0**2)])
    return float(max(r[(np.abs(r.imag) < 1e-9) & (r.real > 0)].real))


def _write(path: Path, header, rows) -> Path:
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)
    return path


def _cli(argv, capsys):
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def _one_line(code, err, expect, message):
    assert code == expect and code in EXIT_CODES, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("skfem-dielectric check: error:"), err
    assert message in err, err


# --------------------------------------------------------------------------- conflicts
D0B = float(converged_buckling_load(1.0).D0_b)


@pytest.mark.parametrize("order", ["good first", "bad first"])
def test_two_D0_b_for_one_weight_are_both_scored(order, tmp_path, capsys):
    """A wrong D0_b beside the right one fails in either order (CLI and API): the worst
    counts, and a note names both rows."""
    rows = [["uni-axial-ideal", "1", f"{D0B:.6f}"], ["uni-axial-ideal", "1", "2.9"]]
    if order == "bad first":
        rows.reverse()
    f = _write(tmp_path / "uni-axial-ideal.csv", ["case", "alpha", "D0_b"], rows)
    result = validation.check(f)
    m = result["uni-axial-ideal"].measures[0]
    assert not result.passed and m.n == 2 and m.n_failed == 1
    assert m.error == pytest.approx(abs(2.9 - D0B), abs=1e-12)
    assert any("2 different D0_b" in n for n in result.notes)
    code, out, _ = _cli(["check", str(f)], capsys)
    assert code == 1 and "uni-axial-ideal: FAIL" in out


def test_a_D0_b_repeated_on_every_row_of_a_run_is_one_score(tmp_path):
    rows = [["uni-axial-ideal", "r1", "1", f"{D0B:.6f}"]] * 5
    f = _write(tmp_path / "uni-axial-ideal.csv", ["case", "run", "alpha", "D0_b"], rows)
    m = validation.check(f)["uni-axial-ideal"].measures[0]
    assert m.passed and m.n == 1


# --------------------------------------------------------------------------- bounds
def test_a_device_behind_a_symlink_is_one_line(tmp_path, capsys):
    link = tmp_path / "nh-d-e.csv"
    os.symlink("/dev/zero", link)
    code, _, err = _cli(["check", str(link)], capsys)
    _one_line(code, err, 2, "not a regular file")


def test_a_file_above_the_bound_is_refused_before_reading(tmp_path, capsys):
    f = tmp_path / "nh-d-e.csv"
    with open(f, "wb") as fh:              # sparse: 50 MB that are never written
        fh.write(b"case,s,D0,lam1\n")
        fh.truncate(50 * 1024**2)
    code, _, err = _cli(["check", str(f)], capsys)
    _one_line(code, err, 2, f"above the {MAX_FILE_BYTES // 1024**2} MB")


def test_a_folder_above_the_bound_is_refused(tmp_path, capsys):
    for i in range(MAX_TOTAL_BYTES // MAX_FILE_BYTES + 1):
        with open(tmp_path / f"part{i}.csv", "wb") as fh:
            fh.truncate(MAX_FILE_BYTES)
    with open(tmp_path / "run_fields.csv", "wb") as fh:      # named and skipped: free
        fh.truncate(MAX_TOTAL_BYTES)
    code, _, err = _cli(["check", str(tmp_path)], capsys)
    _one_line(code, err, 2, f"above the {MAX_TOTAL_BYTES // 1024**2} MB")


@pytest.mark.parametrize("size", [131_073, 2_000_000])
def test_a_huge_cell_is_one_line_not_a_csv_error(size, tmp_path, capsys):
    f = tmp_path / "nh-d-e.csv"
    f.write_text("case,s,D0,lam1\nnh-d-e,0,0," + "1" * size + "\n")
    code, _, err = _cli(["check", str(f)], capsys)
    _one_line(code, err, 2, "a line longer than")


def test_a_huge_quoted_cell_without_line_end(tmp_path, capsys):
    f = tmp_path / "nh-d-e.csv"
    f.write_text('case,s,D0,lam1\nnh-d-e,0,0,"' + "x" * 300_000)
    code, _, err = _cli(["check", str(f)], capsys)
    _one_line(code, err, 2, "a line longer than")


# --------------------------------------------------------------------------- values
def test_a_negative_lam3_is_refused(tmp_path, capsys):
    f = _write(tmp_path / "figde.csv", ["case", "s", "D0", "lam1", "lam3"],
               [["figde", "0", "0", "1", "1"], ["figde", "0", "1", "1.2", "-0.8"]])
    code, _, err = _cli(["check", str(f)], capsys)
    _one_line(code, err, 2, "figde.csv line 3, column lam3: -0.8 is not a stretch")


def test_the_stable_verdict_takes_no_tolerance(tmp_path, capsys):
    with pytest.raises(ValueError, match="--tol stable: a verdict"):
        parse_tolerances(["stable=3"])
    f = _write(tmp_path / "nh-d-e.csv", ["case", "s", "D0", "lam1"],
               [["nh-d-e", "0", "0", "1"]])
    code, _, err = _cli(["check", str(f), "--tol", "stable=5"], capsys)
    _one_line(code, err, 2, "a verdict, with no tolerance")


def test_a_failed_report_write_leaves_the_old_report_whole(tmp_path, capsys, monkeypatch):
    """An old PASS report; a new check fails and its report cannot be written: the folder
    keeps the old report and the old figure, and no new figure sits beside them."""
    s = 0.5
    (tmp_path / "in").mkdir()
    good = _write(tmp_path / "in" / "nh-d-e.csv", ["case", "s", "D0", "lam1"],
                  [["nh-d-e", s, d, repr(_lam(d, s))] for d in (0.0, 0.5, 1.0)])
    out = tmp_path / "report"
    assert _cli(["check", str(good), "--out", str(out)], capsys)[0] == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    _write(good, ["case", "s", "D0", "lam1"],
           [["nh-d-e", s, d, repr(1.02 * _lam(d, s))] for d in (0.0, 0.5, 1.0)])
    real = check_report._stage

    def failing(path, data):
        if path.name == "check.md":
            raise OSError(28, "No space left on device", str(path))
        return real(path, data)

    monkeypatch.setattr(check_report, "_stage", failing)
    code, _, err = _cli(["check", str(good), "--out", str(out)], capsys)
    assert code == 3 and "No space left on device" in err
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


# --------------------------------------------------------------------------- diagnosis
def _diagnosis(tmp_path, lam1, D0, s=0.5) -> str:
    f = _write(tmp_path / "nh-d-e.csv", ["case", "s", "D0", "lam1"],
               [["nh-d-e", s, repr(float(d)), repr(float(v))] for d, v in zip(D0, lam1)])
    result = validation.check(f)
    assert not result.passed
    return result["nh-d-e"].measures[0].diagnosis


D0S = np.linspace(0.2, 1.5, 6)
LAMS = np.array([_lam(d, 0.5) for d in D0S])


def test_the_diagnosis_names_a_strain_for_the_stretch(tmp_path):
    assert "holds the strain lam1 - 1" in _diagnosis(tmp_path, LAMS - 1, D0S)


def test_the_diagnosis_names_a_percent_strain(tmp_path):
    assert "strain in percent" in _diagnosis(tmp_path, 100 * (LAMS - 1), D0S)


def test_the_diagnosis_names_D0_in_physical_units(tmp_path):
    # D = D0 sqrt(mu eps): the paper's VHB, mu = 9833 Pa, eps = 4.7 eps_0
    c = math.sqrt(9833.07 * 4.7 * 8.854187817e-12)
    text = _diagnosis(tmp_path, LAMS, D0S * c)
    assert "D0 is in physical units" in text and f"{c:.4g} times" in text


def test_an_unexplained_error_says_so(tmp_path):
    assert "no usual mix-up" in _diagnosis(tmp_path, LAMS * (1 + 0.01 * D0S), D0S)

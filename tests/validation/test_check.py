"""``skfem-dielectric check`` and ``validation.check``: another code's results CSVs scored
against the closed forms.

Every number is asserted against a reference computed here without ``analytic`` (the
neo-Hookean loading curves as polynomial roots, the literature's voltage limit, the
thick-plate limit as a quadratic, the buckling loads as printed in the data file), with
the tolerance stated at the assertion.  The round trip runs the real ``validate`` harness
on a few one-element ramps of three cases (about a second of FE); the full quick run's
round trip is the slow test at the end.
"""

from __future__ import annotations

import csv
import json
import math
import runpy
import shutil
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import validation
import validation.checker.rules
from validation.data.loads import converged_buckling_load, uniform_buckling_loads
from validation.cases import get_case
from validation.checker import (CHECK_CASES, TOLERANCES, CheckInputError, parse_tolerances,
                                read_csv_rows)
from validation.cli import EXIT_CODES, main
from validation.studies.extra_cases import EXTRA_CASES

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "docs" / "examples" / "ex14_check_external_code.py"
EXAMPLE_CSV = ROOT / "docs" / "examples" / "ex14_external_nh-d-e.csv"


# --------------------------------------------------------------------------- references
def _lam_equibiaxial_nh(D0: float, s: float) -> float:
    """Eq. (loading_gent), neo-Hookean: the positive root of lam^6 - s lam^5 - 1 - D0^2."""
    r = np.roots([1.0, -s, 0.0, 0.0, 0.0, 0.0, -(1.0 + D0**2)])
    return float(max(r[(np.abs(r.imag) < 1e-9) & (r.real > 0)].real))


def _lam1_uniaxial_nh(D0: float, s: float) -> float:
    """Eq. (DEuniax), neo-Hookean: the root of lam1^3 - s lam1^2 - sqrt(1 + D0^2)."""
    r = np.roots([1.0, -s, 0.0, -math.sqrt(1.0 + D0**2)])
    return float(max(r[np.abs(r.imag) < 1e-9].real))


def _thick_limit_nh(lam: float) -> float:
    """Eq. (ideal-shortwave): D0^4 - (lam^6 + 3 lam^3 - 2) D0^2 - (lam^9 + lam^6 + 3 lam^3 - 1)."""
    B = lam**6 + 3 * lam**3 - 2
    C = lam**9 + lam**6 + 3 * lam**3 - 1
    return math.sqrt((B + math.sqrt(B * B + 4 * C)) / 2)


def _rows(path: Path) -> tuple[list[str], list[list[str]]]:
    """Header and data rows of a CSV (``#`` lines left out)."""
    with open(path, newline="") as fh:
        rows = list(csv.reader(ln for ln in fh if not ln.startswith("#")))
    return rows[0], rows[1:]


def _write(path: Path, header, rows, comments=()) -> Path:
    with open(path, "w", newline="") as fh:
        for c in comments:
            fh.write(f"# {c}\n")
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)
    return path


def _edit(path: Path, fn) -> None:
    """Rewrite the CSV ``path`` with ``fn(dict_row, index) -> dict_row`` per data row."""
    header, rows = _rows(path)
    out = [[fn(dict(zip(header, r)), i).get(c, "") for c in header] for i, r in
           enumerate(rows)]
    _write(path, header, out)


def run_cli(argv, capsys):
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


# --------------------------------------------------------------------------- round trip
@pytest.fixture(scope="module")
def ours(tmp_path_factory):
    """The ``validate`` harness's own CSVs: one-element ramps of nh-d-e (3D coupled s = 3,
    membrane with the Maxwell traction s = 1), gent-d-e (membrane s = 2.3) and figde
    (membrane s = 2)."""
    from validation.sweep import run_case

    out = tmp_path_factory.mktemp("ours")
    pick = {"nh-d-e": lambda r: (r.variant, r.s) in (("coupled", 3.0),
                                                      ("membrane-maxwell", 1.0)),
            "gent-d-e": lambda r: (r.variant, r.s) == ("membrane", 2.3),
            "figde": lambda r: (r.variant, r.s) == ("membrane", 2.0)}
    for name, keep in pick.items():
        case = get_case(name)
        run_case(replace(case, quick=tuple(r for r in case.quick if keep(r))), out,
                 quick=True, progress=False)
    return out


@pytest.fixture
def copy(ours, tmp_path):
    """A copy of :func:`ours` (CSVs only) to edit."""
    dst = tmp_path / "copy"
    dst.mkdir()
    for p in ours.glob("*.csv"):
        shutil.copy(p, dst / p.name)
    return dst


def _independent_error(path: Path) -> float:
    """max |lam1_fe / lam1 - 1| of a neo-Hookean CSV, lam1 from the polynomial roots."""
    header, rows = _rows(path)
    worst = 0.0
    for r in map(lambda r: dict(zip(header, r)), rows):
        if r["converged"] != "True":
            continue
        D0, s = float(r["D0"]), float(r["s"])
        ref = _lam_equibiaxial_nh(D0, s) if r["case"] == "nh-d-e" else _lam1_uniaxial_nh(D0, s)
        worst = max(worst, abs(float(r["lam1_fe"]) / ref - 1))
    return worst


def test_the_csvs_of_validate_pass_every_case(ours):
    result = validation.check(ours)
    assert [c.name for c in result] == ["nh-d-e", "gent-d-e", "figde"]
    assert result.passed, result.table()
    for name in ("nh-d-e", "figde"):
        m = result[name].measures[0]
        # the same error from an independent closed form: the CSV has 12 digits and the
        # roots are good to ~1e-15, so the two agree to 1e-11
        assert m.error == pytest.approx(_independent_error(ours / f"{name}.csv"), abs=1e-11)
        assert m.error < 1e-8                        # validate's own tolerance
    assert result["gent-d-e"].measures[0].error < 1e-8


def test_one_percent_off_fails_that_case_alone(copy, capsys):
    _, rows = _rows(copy / "nh-d-e.csv")
    bad = 6                                           # data row 6 is line 8 (header on 1)

    def off(r, i):
        if r["lam1_fe"]:
            r["lam1_fe"] = repr(float(r["lam1_fe"]) * (1.015 if i == bad else 1.01))
        return r

    _edit(copy / "nh-d-e.csv", off)
    result = validation.check(copy)
    assert not result.passed
    assert [c.name for c in result if not c.passed] == ["nh-d-e"]
    worst = result.worst
    assert worst.case == "nh-d-e" and worst.where == f"nh-d-e.csv line {bad + 2}"
    # 1.5 % on a row whose error was < 1e-9: the error is 0.015 to 1e-8
    assert worst.error == pytest.approx(0.015, abs=1e-8)
    header, _ = _rows(copy / "nh-d-e.csv")
    converged = sum(1 for r in rows if r[header.index("lam1_fe")])
    assert worst.n_failed == converged               # every converged row is 1 % off
    assert worst.diagnosis.startswith("no usual mix-up")
    code, out, err = run_cli(["check", str(copy)], capsys)
    assert code == 1 and err == ""
    assert f"nh-d-e: FAIL (lam1 1.50e-02 > 1e-06 at nh-d-e.csv line {bad + 2})" in out
    assert "figde: pass" in out and "gent-d-e: pass" in out


def test_the_opposite_sign_of_s_is_named(copy):
    _edit(copy / "nh-d-e.csv", lambda r, i: {**r, "s": repr(-float(r["s"]))})
    m = validation.check(copy, "nh-d-e").worst
    assert not m.passed and m.n_failed > 0
    assert m.diagnosis.startswith("looks like s has the opposite sign")
    # read with the sign flipped back, the error is the original one (< 1e-9)
    assert float(m.diagnosis.rsplit(" ", 1)[1]) < 1e-9


def test_D0_per_current_area_is_named(copy):
    def current(r, i):
        if r["lam1_fe"]:                        # D = D_L/(lam1 lam3): per deformed area
            r["D0"] = repr(float(r["D0"]) / (float(r["lam1_fe"]) * float(r["lam3_fe"])))
        return r

    _edit(copy / "figde.csv", current)
    result = validation.check(copy)
    assert [c.name for c in result if not c.passed] == ["figde"]
    m = result["figde"].worst
    assert m.diagnosis.startswith("looks like D0 is given per current area")
    assert float(m.diagnosis.rsplit(" ", 1)[1]) < 1e-9


def test_the_reader_is_tolerant(copy, tmp_path):
    """Comments, another column order, the short names, E0 for D0, no model column and an
    extra column give the same error as the contract's file."""
    header, rows = _rows(copy / "nh-d-e.csv")
    base = validation.check(copy / "nh-d-e.csv").worst.error
    rs = [dict(zip(header, r)) for r in rows]
    out = [[r["lam1_fe"], "x", repr(float(r["D0"]) / float(r["lam1_fe"]) ** 4)
            if r["lam1_fe"] else "", r["s"], r["case"], r["lam3_fe"]] for r in rs]
    f = _write(tmp_path / "mine.csv", ["lam1", "solver note", "E0", "s", "case", "lam3"], out,
               comments=["written by another code", "E0 = V/(E H) sqrt(eps/mu)"])
    result = validation.check(f)
    assert result.passed
    # D0 = lam1^2 lam3^2 E0 restores D0 to round-off: the errors agree to 1e-12
    assert result.worst.error == pytest.approx(base, abs=1e-12)


def test_the_api_for_test_suites(ours):
    result = validation.check(ours, cases=["figde"], tol={"lam1": 1e-7})
    assert isinstance(result, validation.CheckResult) and len(result) == 1
    assert result.passed and result.worst.case == "figde" and result.worst.tol == 1e-7
    table = result.table().splitlines()
    assert table[0].startswith("| case | measure |") and len(table) == 2 + len(
        result["figde"].measures)
    assert "| figde | lam1 |" in table[2] and table[2].endswith("| pass |")
    with pytest.raises(KeyError, match="no case 'zs22'"):
        result["zs22"]
    assert parse_tolerances(["lam1=2e-4"])["lam1"] == 2e-4
    assert parse_tolerances({"D0_b": 0.01})["lam1"] == TOLERANCES["lam1"]
    for bad, match in ((["lam1"], "NAME=VALUE"), (["lam2=1"], "unknown measure 'lam2'"),
                       (["lam1=-1"], ">= 0"), (["lam1=nan"], ">= 0")):
        with pytest.raises(ValueError, match=match):
            parse_tolerances(bad)


def test_every_case_of_validate_can_be_checked():
    assert set(CHECK_CASES) == set(validation.CASES) | set(EXTRA_CASES)


# --------------------------------------------------------------------------- other measures
def test_buckling_load_against_the_converged_value(tmp_path):
    # the loads of validation.data.loads, read here as the reference (their own tests
    # check them against the rows): alpha = 1 graded (30x1x36 / 40x1x36: 3.3698 / 3.3700,
    # uniform 10x1x5: 2.9147); 0.3 graded 1.4712 +- 0.0005; 2: no entry
    e1, e3 = converged_buckling_load(1.0), converged_buckling_load(0.3)
    f = _write(tmp_path / "uni-axial-ideal.csv", ["case", "alpha", "D0_b"],
               [["uni-axial-ideal", "1", f"{e1.D0_b + 0.8 * e1.error:.7f}"],
                ["uni-axial-ideal", "0.3", f"{e3.D0_b - 0.2 * e3.error:.7f}"],
                ["uni-axial-ideal", "2", "4.4"]])
    result = validation.check(f)
    m = result["uni-axial-ideal"].measures[0]
    assert result.passed and m.name == "D0_b" and m.n == 2
    # the worst row relative to its tolerance: alpha = 1 (0.8 of its error bar)
    assert m.error == pytest.approx(0.8 * e1.error, abs=1e-7)
    assert any("alpha = 2 not scored: no entry" in n for n in result.notes)
    _write(f, ["case", "alpha", "D0_b"], [["uni-axial-ideal", "1", "2.9147"]])
    m = validation.check(f).worst
    assert not m.passed and m.error == pytest.approx(e1.D0_b - 2.9147, abs=1e-9)
    assert m.tol == pytest.approx(e1.error, abs=1e-12) and e1.error < 1e-3
    assert "it is the load of our uniform 10x1x5 mesh" in m.diagnosis
    _write(f, ["case", "alpha", "D0_b", "D0_b_error"],
           [["uni-axial-ideal", "1", "2.9147", "0.5"]])
    m = validation.check(f).worst
    assert m.passed and m.tol == pytest.approx(0.5 + e1.error, abs=1e-12)


def test_the_clamped_plate_centre_within_one_percent(tmp_path):
    # s of alpha = 1 with g = 9.81: 1 * 0.150 * 9.81 / (9833.07 * 50e-6)
    s = 0.150 * 9.81 / (9833.07 * 50e-6)
    rows = [["zs22", "1", f"{D0:g}", repr(_lam1_uniaxial_nh(D0, s) * f)]
            for D0, f in ((0, 1.0), (2, 1.009), (4, 0.995))]
    f = _write(tmp_path / "zs22.csv", ["case", "alpha", "D0", "lam1_fe"], rows)
    m = validation.check(f).worst
    assert m.passed and m.name == "lam1_clamped"
    assert m.error == pytest.approx(0.009, rel=1e-6) and m.where == "zs22.csv line 3"
    rows[2][3] = repr(_lam1_uniaxial_nh(4.0, s) * 0.985)
    _write(f, ["case", "alpha", "D0", "lam1_fe"], rows)
    assert validation.check(f).worst.where == "zs22.csv line 4"
    assert not validation.check(f).passed


def test_a_weight_without_a_converged_load_is_not_scored(tmp_path, monkeypatch):
    """With the uniform meshes' loads alone (alpha = 1.5: its three meshes disagree) a
    D0_b of alpha = 1.5 is a note, not a score; alpha = 1 is scored against 2.84."""
    monkeypatch.setattr(validation.checker.rules, "buckling_loads", uniform_buckling_loads)
    f = _write(tmp_path / "uni-axial-ideal.csv", ["case", "alpha", "D0_b"],
               [["uni-axial-ideal", "1.5", "4.4"], ["uni-axial-ideal", "1", "2.84"]])
    result = validation.check(f)
    assert any("alpha = 1.5 not scored: no converged load (its meshes disagree)" in n
               for n in result.notes)
    m = result["uni-axial-ideal"].measures[0]
    assert m.n == 1 and m.error == pytest.approx(0.0, abs=1e-12)


def test_voltage_limit_point_and_the_hessian_verdict(tmp_path):
    """neo-Hookean, equi-biaxial, s = 0: the limit point lam = 2^(1/3),
    E0 = sqrt(3)/2^(4/3) (the literature's value); the path lam^6 = 1 + D0^2."""
    lam_c, E0_c = 2 ** (1 / 3), math.sqrt(3) / 2 ** (4 / 3)
    head = ["case", "run", "model", "loading", "s", "kind", "lam1_fe", "E0", "stable"]
    rows = []
    for lam, kind in ((1.1, "regular"), (1.2, "regular"), (lam_c, "limit"), (1.4, "regular"),
                      (1.6, "regular")):
        D0 = math.sqrt(lam**6 - 1)
        rows.append(["voltage-control", "p", "neo-Hookean", "equibiaxial", "0", kind,
                     repr(lam), repr(D0 / lam**4), str(lam <= lam_c)])
    f = _write(tmp_path / "voltage-control.csv", head, rows)
    result = validation.check(f)
    got = {m.name: m for m in result["voltage-control"].measures}
    assert result.passed, result.table()
    assert set(got) == {"lam1", "stable", "lam1_limit", "E0_limit"}
    assert got["lam1_limit"].error < 1e-12 and got["E0_limit"].error < 1e-12
    assert got["stable"].n == 4                       # the limit row itself is marginal
    rows[2][7] = repr(E0_c * (1 + 1e-5))              # the maximum 1e-5 too high
    rows[4][8] = "True"                               # past the limit, called stable
    _write(f, head, rows)
    got = {m.name: m for m in validation.check(f)["voltage-control"].measures}
    assert not got["E0_limit"].passed and got["E0_limit"].error == pytest.approx(1e-5, rel=1e-6)
    assert not got["stable"].passed and got["stable"].where == "voltage-control.csv line 6"
    assert got["lam1_limit"].passed                  # E0 alone was changed


def test_wrinkling_deep_in_the_thick_plate_limit(tmp_path):
    """kh = 50: the critical D0 of the finite plate is the thick-plate limit,
    Eq. (ideal-shortwave), to ~1e-14 (the correction decays like exp(-kh))."""
    rows = [["antisymmetric", "2", "50", repr(_thick_limit_nh(2.0)), ""],
            ["symmetric", "1.5", "50", repr(_thick_limit_nh(1.5) * 1.01), "sym"]]
    f = _write(tmp_path / "wrinkling-fe.csv", ["mode", "lam", "kh", "D0_fe", "note"], rows)
    m = validation.check(f).worst
    assert not m.passed and m.n_failed == 1 and m.where == "wrinkling-fe.csv line 3"
    assert m.error == pytest.approx(0.01, abs=1e-9)
    rows[1][3] = repr(_thick_limit_nh(1.5))
    _write(f, ["mode", "lam", "kh", "D0_fe", "note"], rows)
    assert validation.check(f).worst.error < 1e-9


# --------------------------------------------------------------------------- bad input
def _empty(d):
    pass


def _good(d):
    _write(d / "nh-d-e.csv", ["case", "s", "D0", "lam1"],
           [["nh-d-e", "0", "0", "1"], ["nh-d-e", "0", "1", repr(_lam_equibiaxial_nh(1, 0))]])


def _binary(d):
    _good(d)
    (d / "figde.csv").write_bytes(b"case,s\xff\xfe\x00\n")


def _with(name, header, rows, text=None):
    def make(d):
        _good(d)
        if text is not None:
            (d / name).write_text(text)
        else:
            _write(d / name, header, rows)
    return make


BAD = {
    "no CSV": (_empty, 2, "holds no CSV file"),
    "unknown case": (_with("a.csv", ["case", "s", "D0", "lam1"], [["nh-d-x", "0", "0", "1"]]),
                     2, "a.csv line 2, column case: unknown case 'nh-d-x'"),
    "text column": (_with("figde.csv", ["case", "s", "D0", "lam1"],
                          [["figde", "0", "0", "1"], ["figde", "0", "one", "1.2"]]),
                    2, "figde.csv line 3, column D0: 'one' is not a number"),
    "NaN row": (_with("figde.csv", ["case", "s", "D0", "lam1"],
                      [["figde", "nan", "nan", "nan"]]),
                2, "figde.csv line 2, column lam1: nan (leave the cell empty"),
    "another tool's format": (_with("export.csv", None, None,
                                    "% Model: plate.mph\n% lam1 D0\n1.0 0.0\n"),
                              2, "export.csv: not a results CSV of the contract"),
    "semicolons": (_with("results.csv", None, None, "case;s;D0;lam1\nnh-d-e;0;0;1\n"),
                   2, "separated by semicolons or tabs?"),
    "missing column": (_with("figde.csv", ["case", "D0", "lam1"], [["figde", "0", "1"]]),
                       2, "figde.csv: column s missing"),
    "short row": (_with("figde.csv", None, None, "case,s,D0,lam1\nfigde,0,0\n"),
                  2, "figde.csv line 2: 3 cells, the header has 4 columns"),
    "binary": (_binary, 2, "figde.csv: not a text file"),
}


@pytest.mark.parametrize("what", list(BAD))
def test_bad_input_is_one_line_and_writes_nothing(what, tmp_path, capsys):
    make, expect, message = BAD[what]
    src, out = tmp_path / "in", tmp_path / "report"
    src.mkdir()
    make(src)
    before = sorted(p.name for p in src.iterdir())
    code, stdout, err = run_cli(["check", str(src), "--out", str(out)], capsys)
    assert code == expect and code in EXIT_CODES
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("skfem-dielectric check: error:"), err
    assert message in err and stdout == ""
    assert not out.exists() and sorted(p.name for p in src.iterdir()) == before


def test_other_bad_invocations(tmp_path, capsys):
    src = tmp_path / "in"
    src.mkdir()
    _good(src)
    code, _, err = run_cli(["check", str(tmp_path / "missing")], capsys)
    assert code == 3 and "No such file or directory" in err and len(err.splitlines()) == 1
    code, _, err = run_cli(["check", str(src), "--out", str(src)], capsys)
    assert code == 2 and "--out must not be the checked folder" in err
    assert sorted(p.name for p in src.iterdir()) == ["nh-d-e.csv"]
    code, _, err = run_cli(["check", str(src), "--case", "zs22"], capsys)
    assert code == 2 and "no rows of case zs22 (cases found: nh-d-e)" in err
    code, _, err = run_cli(["check", str(src), "--tol", "lam1=x"], capsys)
    assert code == 2 and "--tol lam1 must be a number >= 0" in err
    assert "check: a case fails its tolerance" in EXIT_CODES[1]


def test_the_report_folder(ours, tmp_path, capsys):
    out = tmp_path / "report"
    code, stdout, err = run_cli(["check", str(ours), "--case", "figde", "--out", str(out)],
                                capsys)
    assert code == 0 and err == ""
    assert sorted(p.name for p in out.iterdir()) == ["check.json", "check.md", "figde.png"]
    data = json.loads((out / "check.json").read_text())
    api = validation.check(ours, "figde").worst
    assert data["passed"] is True and data["cases"]["figde"]["measures"][0]["error"] == api.error
    assert (out / "figde.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "![figde](figde.png)" in (out / "check.md").read_text()
    assert f"report: {out / 'check.md'}" in stdout


LAYOUTS = {"nh-d-e": ["s", "D0", "lam1", "stable"],
           "gent-equi-biaxial": ["model", "s", "E0", "lam1"],
           "figde": ["s", "D0", "lam1", "lam3"], "zs22": ["alpha", "D0", "lam1", "D0_b"],
           "voltage-control": ["loading", "model", "s", "lam1", "E0", "kind", "stable"],
           "wrinkling-fe": ["mode", "lam", "kh", "D0_fe", "control"]}
CHOICES = {"model": ["Gent", "neo-Hookean"], "loading": ["equibiaxial", "uniaxial-free"],
           "kind": ["limit", "regular"], "stable": ["True", "False"],
           "mode": ["symmetric", "antisymmetric"], "control": ["charge", "voltage"]}
NUMBERS = ["0", "1", "2.5", "1e300", "1e-300", "0.5", "3", "-1", "1e5", "7"]


def test_generated_files_end_in_a_verdict_or_one_line(tmp_path):
    """Seeded random files (columns of every case, numbers, words, nan, huge values) give a
    result or a one-line ``ValueError``, never another exception (a quarter second)."""
    import random

    rng = random.Random(20261205)
    cols = ["case", "s", "alpha", "D0", "E0", "lam1", "lam1_fe", "lam3", "model", "converged",
            "stable", "stable_charge", "loading", "kind", "run", "D0_b", "D0_b_error", "mode",
            "lam", "kh", "D0_fe", "control", "lam1_max_fe", "E0_max_fe", "x"]
    vals = ["", "0", "1", "-1", "2.5", "1e300", "nan", "inf", "abc", "True", "False", "Gent",
            "neo-Hookean", "equibiaxial", "uniaxial-free", "uniaxial", "limit", "symmetric",
            "antisymmetric", "voltage", "1e-300", "0.5", "3"] + list(CHECK_CASES)
    outcomes = {"result": 0, "error": 0}
    for trial in range(300):
        d = tmp_path / str(trial)
        d.mkdir()
        if trial % 2:                                 # a case's columns, numbers in them
            name, header = rng.choice(list(LAYOUTS.items()))
            rows = [",".join(rng.choice(CHOICES.get(c, NUMBERS)) for c in header)
                    for _ in range(rng.randint(1, 4))]
            name += ".csv"
        else:                                         # any columns, anything in them
            header = rng.sample(cols, rng.randint(1, 10))
            rows = [",".join(rng.choice(list(CHECK_CASES)) if c == "case" and
                             rng.random() < 0.8 else rng.choice(vals) for c in header)
                    for _ in range(rng.randint(0, 5))]
            name = rng.choice(["x.csv", "nh-d-e.csv", "figde.csv", "voltage-control.csv",
                               "wrinkling-fe.csv", "zs22.csv"])
        (d / name).write_text(",".join(header) + "\n" + "\n".join(rows) + "\n")
        try:
            result = validation.check(d)
            result.table(), result.lines(), result.worst
            outcomes["result"] += 1
        except ValueError as exc:
            assert "\n" not in str(exc), str(exc)
            outcomes["error"] += 1
    assert min(outcomes.values()) > 0, outcomes       # both kinds were generated


def test_read_csv_rows_names_lines(tmp_path):
    f = tmp_path / "x.csv"
    f.write_text("# one\n\ncase, s ,D0\n# two\nnh-d-e,0,1\n")
    header, rows = read_csv_rows(f)
    assert header == ["case", "s", "D0"] and rows[0].line == 5 and rows[0].cells["s"] == "0"
    f.write_text("case,s,s\n")
    with pytest.raises(CheckInputError, match="column 's' appears more than once"):
        read_csv_rows(f)


# --------------------------------------------------------------------------- the example
def test_the_external_example_passes_within_its_own_penalty_error(tmp_path, monkeypatch):
    """The committed CSV of ex14 (a compressible plate, kappa = 1e5 mu) is what the script
    writes; it passes with its own tolerance 1e-4 and fails the default 1e-6."""
    monkeypatch.chdir(tmp_path)
    ns = runpy.run_path(str(EXAMPLE), run_name="ex14")
    _, mine = _rows(Path(ns["CSV"]))
    _, committed = _rows(EXAMPLE_CSV)
    assert np.allclose(np.array(mine)[:, 2:].astype(float),
                       np.array(committed)[:, 2:].astype(float), rtol=1e-8, atol=0)
    result = validation.check(EXAMPLE_CSV, tol={"lam1": 1e-4})
    assert result.passed and not validation.check(EXAMPLE_CSV).passed
    # the penalty error against the incompressible roots: the code's own Richardson
    # estimate (written in the file's comment) to 5 %
    worst = max(abs(float(r[4]) / _lam_equibiaxial_nh(float(r[3]), float(r[2])) - 1)
                for r in committed)
    assert result.worst.error == pytest.approx(worst, rel=1e-6)
    assert worst == pytest.approx(ns["penalty_error"], rel=0.05)


@pytest.mark.slow
def test_round_trip_of_the_quick_voltage_and_wrinkling_cases(tmp_path):
    """``validate --quick`` of voltage-control and wrinkling-fe (tens of CPU seconds) passes
    ``check``."""
    assert main(["validate", "--quick", "--case", "voltage-control", "wrinkling-fe",
                 "--out", str(tmp_path), "--no-progress"]) == 0
    result = validation.check(tmp_path)
    assert result.passed, result.table()
    assert [c.name for c in result] == ["voltage-control", "wrinkling-fe"]


def test_a_checked_buckling_load_beyond_tolerance_shows_under_its_mark(tmp_path):
    """A D0_b far from the converged 3.3699 (2.9, the coarse mesh's): the figure draws the
    checked value (green plus) on top and the orange X of `beyond its tolerance` larger
    behind it, so that the legend's green plus is visible at its point."""
    import analytic as an
    from analytic.units import keplinger_s
    from validation.check_report import check_figure
    from validation.checker import check as run_check

    s = float(keplinger_s(1.0, g=9.81))
    path = tmp_path / "r.csv"
    path.write_text("case,alpha,D0,lam1,D0_b\n"
                    f"uni-axial-ideal,1,1.0,{float(an.uniaxial_lam1(1.0, s)):.12g},2.9\n")
    result = run_check(path)
    assert not result.passed
    fig = check_figure(result.cases[0])
    lines = {ln.get_gid(): ln for ax in fig.axes for ln in ax.lines
             if ln.get_gid() in ("beyond-tolerance", "checked-buckling")}
    plus, cross = lines["checked-buckling"], lines["beyond-tolerance"]
    assert (plus.get_xydata() == cross.get_xydata()).all()
    assert plus.get_zorder() > cross.get_zorder()
    assert cross.get_markersize() > plus.get_markersize()

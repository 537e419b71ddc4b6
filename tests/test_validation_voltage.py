"""The harness case voltage-control: CSV, figure and summary of a continuation run."""

import csv
import json

import numpy as np
import pytest

import analytic as an
import validation.voltage_control as vvc
from validation.cli import main

CONTRACT = ["model", "loading", "s", "alpha", "lam1_fe", "E0", "D0", "n_unstable", "stable",
            "branch"]


@pytest.fixture
def one_run(monkeypatch):
    run = dict(model="neo-Hookean", loading="uniaxial-free", s=1.0, alpha=None)
    monkeypatch.setattr(vvc, "voltage_runs", lambda quick=False: [run])
    return run


def test_voltage_control_case_csv_figure_and_report(tmp_path, one_run):
    out = tmp_path / "res"
    assert main(["validate", "--quick", "--case", "voltage-control", "--out", str(out),
                 "--no-progress"]) == 0
    for ext in ("csv", "png", "pdf"):
        assert (out / f"voltage-control.{ext}").is_file()
    with open(out / "voltage-control.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert set(CONTRACT) <= set(rows[0])
    branch = [r["branch"] for r in rows]
    k = branch.index("limit")
    assert set(branch[:k]) == {"rising"} and set(branch[k + 1:]) == {"falling"}
    lam_ref, E0_ref = (float(v) for v in an.max_E0(1.0, loading="uniaxial"))
    # the limit point is located to |dE0/ds| <= 1e-9 on a homogeneous state reproduced to
    # Newton tolerance: 1e-8 in E0, 1e-6 in lam1 (targets 1e-6 and 1e-4); the CSV keeps
    # 12 significant digits
    assert float(rows[k]["E0"]) == pytest.approx(E0_ref, abs=1e-8)
    assert float(rows[k]["lam1_fe"]) == pytest.approx(lam_ref, abs=1e-6)
    # every point lies on the analytic loading curve (Newton tolerance; E0 = 0 at the
    # start, where dE0/dlam1 is infinite, is left out)
    E0 = np.array([float(r["E0"]) for r in rows[1:]])
    np.testing.assert_allclose(E0, [float(r["E0_analytic"]) for r in rows[1:]], atol=1e-8)
    # voltage control: stable before the limit, unstable after; charge control: stable
    assert all(r["stable"] == "True" for r in rows[:k])
    assert all(r["stable"] == "False" for r in rows[k + 1:])
    assert all(r["stable_charge"] == "True" for r in rows)
    summary = json.loads((out / "summary.json").read_text())["cases"]["voltage-control"]
    assert summary["max_rel_error"] < vvc.LIMIT_TOL
    assert "| voltage-control |" in (out / "report.md").read_text()

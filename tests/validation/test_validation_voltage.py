"""The harness case voltage-control: CSV, figure and summary of a continuation run."""

import csv
import json

import numpy as np
import pytest

import analytic as an
import validation.studies.voltage_control as vvc
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
    # a value the point does not have is an empty cell (docs/cli.md), never "nan"
    assert "nan" not in (out / "voltage-control.csv").read_text().lower()
    assert vvc._fmt(float("nan")) == "" and vvc._fmt(None) == ""
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


def _path_rows(*paths):
    """Rows of :data:`VOLTAGE_COLUMNS` holding only what the caption and titles read."""
    col = vvc.VOLTAGE_COLUMNS
    rows = []
    for model, loading, s, alpha in paths:
        r = [None] * len(col)
        for k, v in dict(run=f"{model} {loading} {s} {alpha}", model=model, loading=loading, s=s, alpha=alpha).items():
            r[col.index(k)] = v
        rows.append(r)
    return rows


def test_caption_and_titles_name_only_the_paths_drawn():
    quick = _path_rows(("neo-Hookean", "equibiaxial", 1.0, None),
                       ("neo-Hookean", "uniaxial-free", 1.0, None))
    caption = vvc.voltage_caption(quick, quick=True)
    # the quick paths belong to the paper's Figs. nh-d-e and figde only: no Gent figure,
    # no Keplinger plate, and the one mesh is the homogeneous element
    assert caption.startswith("Paper Figs. ") and "(nh-d-e, figde)" in caption
    assert "gent-d-e" not in caption and "Keplinger" not in caption
    assert "Quick run; meshes: 3D fully coupled: 1 element (homogeneous state)." in caption
    assert vvc._panel_title([], True) == "equi-biaxial dead load: no FE path"
    full = quick + _path_rows(("Gent", "equibiaxial", 1.0, None),
                              ("neo-Hookean", "uniaxial", 2.993, 1.0))
    caption = vvc.voltage_caption(full, quick=False)
    assert "gent-d-e" in caption and "uni-axial-ideal" in caption and "Full run" in caption
    assert "10 x 1 x 5 elements (eighth of the Keplinger plate)" in caption

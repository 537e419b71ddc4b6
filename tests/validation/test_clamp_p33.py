"""The located P33 breakdown on graded meshes (validation.clamp_zone.p33)."""

from __future__ import annotations

import math
import warnings

import numpy as np

import skfem_dielectric as fe
from validation.studies.buckling import p33_measures
from validation.cli import main
from validation.data.registry import load
from validation.specs import LOCATION_TOL as ONSET_TOL
from validation.clamp_zone.p33 import COLUMNS, SETS, run_p33
from validation.clamp_zone.units import UNIT_SETTINGS
from validation.table import BREAKDOWN_TOL
from validation.data.key import UnitKey


def test_a_located_onset_is_where_an_independent_ramp_crosses_the_flag(tmp_path):
    """alpha = 1 on the graded 8 x 1 x 4 eighth model: each located onset lies inside its
    bracketing step, and an independent ramp from D0 = 0 (not the trial states of the
    location) to 2 ONSET_TOL below and above it reads min P33/mu above and below
    -BREAKDOWN_TOL there; the row holds every column and a rerun with its settings keeps it."""
    row = run_p33(UnitKey(1.0, (8, 1, 4), 0.25), D0_step=0.5, D0_max=4.0)
    assert math.isnan(row["newton_limit"]) and row["states"] == 8
    for k in SETS:
        d = row[f"P33_onset_{k}"]
        assert 0.0 < d < 4.0
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            res = fe.keplinger_plate(1.0, D0=[d - 2 * ONSET_TOL, d + 2 * ONSET_TOL],
                                     elements=(8, 1, 4), grading=0.25,
                                     settings=UNIT_SETTINGS)
        pb = res.problem
        lo, hi = (p33_measures(pb, st.x, st.load, st.quantities)[k]
                  for st in res.steps[-2:])
        assert lo > -BREAKDOWN_TOL > hi, (k, d, lo, hi)
    out = tmp_path / "run"
    assert main(["clamp-zone", "p33", "--alpha", "1", "--mesh", "6x1x3", "--grading", "0.5",
                 "--D0-step", "1", "--D0-max", "3", "--out", str(out)]) == 0
    rows = load("p33", out)
    assert len(rows) == 1 and list(rows[0]) == list(COLUMNS)
    assert main(["clamp-zone", "p33", "--alpha", "1", "--mesh", "6x1x3", "--grading", "0.5",
                 "--D0-step", "1", "--D0-max", "3", "--out", str(out)]) == 0
    assert load("p33", out) == rows          # the same settings: kept


def test_the_smallest_committed_unit_is_reproduced():
    """alpha = 1 on 12 x 1 x 6 graded 0.25 run again: every onset within twice its
    location tolerance of its row in validation/data/clamp_p33.csv."""
    ref = next(r for r in load("p33") if r["alpha"] == "1" and r["mesh"] == "12x1x6"
               and r["grading"] == "0.25")
    row = run_p33(UnitKey(1.0, (12, 1, 6), 0.25), D0_step=float(ref["D0_step"]),
                       D0_max=float(ref["D0_max"]))
    for k in SETS:
        assert abs(row[f"P33_onset_{k}"] - float(ref[f"P33_onset_{k}"])) <= 2 * ONSET_TOL
    assert row["dofs"] == int(ref["dofs"])
    assert np.isnan(row["newton_limit"]) == (ref["newton_limit"] == "")

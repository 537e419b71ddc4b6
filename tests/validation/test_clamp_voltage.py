"""The clamped plate under voltage control (``clamp-zone voltage``, table ``voltage``):
the runner against the homogeneous theory where the clamp's influence vanishes, the
located limit point against the path around it, and the command's table and resume."""

from __future__ import annotations

import math

import numpy as np
import pytest

import analytic as an
import skfem_dielectric as fe
from validation.cli import main
from validation.clamp_zone.units import charge_path, unit_problem, unit_ramp
from validation.clamp_zone.voltage import COLUMNS, run_voltage
from validation.data.key import UnitKey
from validation.data.registry import TABLES, load


@pytest.fixture(scope="module")
def light():
    """alpha = 0.05 on the 4 x 1 x 2 plate graded 0.5 (357 unknowns)."""
    return run_voltage(UnitKey(0.05, (4, 1, 2), 0.5), solver="superlu")


def test_a_light_plate_snaps_where_the_homogeneous_plate_does(light):
    """As alpha -> 0 the stretch at the clamp vanishes and the plate is the homogeneous
    uni-axial plate: its limit E0 is max_E0 at its s (Sec. 5, Eq. DEuniax), here within
    2e-3 (the clamps stiffen the plate slightly: 1.4e-4 above).  At a maximum E0 is
    stationary, so the stretch there is fixed only to about the square root of E0's
    error: the centre's lam1 within 1e-2 of the homogeneous one; and the centre is in the
    homogeneous state of its own lam1, its charge the uni-axial D0(lam1, s) within 1e-2."""
    s = fe.gallery.keplinger_s(0.05, g=9.81)
    lam, E0 = (float(v) for v in an.max_E0(s, loading="uniaxial"))
    assert light["max_E0"] == pytest.approx(E0, rel=1e-12)
    assert light["E0_limit"] == pytest.approx(E0, rel=2e-3)
    assert light["ratio"] == pytest.approx(light["E0_limit"] / E0, rel=1e-12)
    assert light["lam1_limit"] == pytest.approx(lam, rel=1e-2)
    D0 = float(an.uniaxial_D0(light["lam1_limit"], s))
    assert light["D0_limit"] == pytest.approx(D0, rel=1e-2)
    assert set(light) - {"mode"} <= set(COLUMNS)


def test_the_limit_point_is_the_path_s_largest_field():
    """The located limit point is the largest field of the branch: a load ramp in E0 (the
    package's ramp, which cannot pass a maximum) from the same pre-load reaches within 3 %
    of it in steps of 2.5 % and stops before 0.2 % above it."""
    key = UnitKey(1.0, (4, 1, 2), 0.5)
    row = run_voltage(key, solver="superlu")
    pb, s = unit_problem(1.0, (4, 1, 2), grading=0.5, control="voltage")
    E0 = row["E0_limit"]
    assert math.isfinite(E0)
    # a ramp in E0 from the pre-load cannot pass the limit: it stops below E0_limit
    steps = []
    res = unit_ramp(pb, charge_path(s, np.linspace(0.05, 1.002, 40) * E0),
                    on_step=lambda st: steps.append(float(st.load[1]))
                    if st.target_reached else None, solver="superlu")
    assert not res.converged
    assert max(steps) <= E0 * (1 + 1e-9)
    assert max(steps) >= E0 * 0.97


def test_the_command_writes_the_row_and_a_rerun_keeps_it(tmp_path, capsys, light):
    argv = ["clamp-zone", "voltage", "--alpha", "0.05", "--mesh", "4x1x2", "--grading",
            "0.5", "--solver", "superlu", "--out", str(tmp_path)]
    assert main(argv) == 0
    (row,) = load("voltage", tmp_path)
    assert float(row["E0_limit"]) == pytest.approx(light["E0_limit"], rel=1e-5)
    assert row["first_kind"] == (light.get("first_kind") or "")
    assert row["command"].startswith("skfem-dielectric clamp-zone voltage")
    before = (tmp_path / TABLES["voltage"].file).read_bytes()
    capsys.readouterr()
    assert main(argv) == 0
    assert (tmp_path / TABLES["voltage"].file).read_bytes() == before

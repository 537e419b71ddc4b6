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
from validation.clamp_zone.voltage import COLUMNS, membrane_voltage_limit, run_voltage
from validation.data.key import UnitKey
from validation.data.registry import TABLES, load


@pytest.fixture(scope="module")
def light():
    """alpha = 0.05 on the 4 x 1 x 2 plate graded 0.5 (357 unknowns)."""
    return run_voltage(UnitKey(0.05, (4, 1, 2), 0.5), solver="superlu")


@pytest.fixture(scope="module")
def heavy():
    """alpha = 1 on the same plate, with the units' grad-div."""
    return run_voltage(UnitKey(1.0, (4, 1, 2), 0.5), solver="superlu")


@pytest.fixture(scope="module")
def membrane():
    """The clamped membrane's voltage limit for alpha = 1 on the default mesh."""
    return membrane_voltage_limit(1.0)


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


def test_the_limit_point_is_the_path_s_largest_field(heavy):
    """The located limit point is the largest field of the branch: a load ramp in E0 (the
    package's ramp, which cannot pass a maximum) from the same pre-load reaches within 3 %
    of it in steps of 2.5 % and stops before 0.2 % above it."""
    pb, s = unit_problem(1.0, (4, 1, 2), grading=0.5, control="voltage")
    E0 = heavy["E0_limit"]
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


def test_the_clamped_membrane_snaps_just_above_the_homogeneous_limit(heavy, membrane):
    """The 2D clamped membrane (no through-thickness corner, no out-of-plane mode): its
    voltage limit for alpha = 1 is the same on 20 x 10 and 40 x 20 Q2 elements to 1e-6
    (mesh-converged), and lies above the homogeneous uni-axial max_E0 by less than 1 %
    (the clamps stiffen the plate; they cannot make it snap earlier); the 3D plate of a
    unit on the coarse 4 x 1 x 2 mesh snaps within 2e-3 of it."""
    E0, lam1 = membrane
    E0_fine, lam1_fine = membrane_voltage_limit(1.0, (40, 20))
    assert E0 == pytest.approx(E0_fine, rel=1e-6)
    assert lam1 == pytest.approx(lam1_fine, rel=1e-4)
    s = fe.gallery.keplinger_s(1.0, g=9.81)
    _, E0_h = (float(v) for v in an.max_E0(s, loading="uniaxial"))
    assert 1.0 < E0 / E0_h < 1.01
    assert heavy["E0_membrane"] == pytest.approx(E0, rel=1e-12)
    assert heavy["E0_limit"] == pytest.approx(E0, rel=2e-3)


def test_bad_input_names_the_parameter():
    with pytest.raises(ValueError, match="alpha must be non-negative"):
        membrane_voltage_limit(-1.0)


def test_the_plain_form_s_early_snap_is_a_discrete_collapse_of_j(heavy, membrane):
    """Without grad-div (the plain mixed form, ``--grad-div 0``) the same plate snaps at
    two thirds of the membrane's limit, and its state there is far from incompressible
    (``J`` below 0.5 somewhere): a collapse the discrete pressure allows, not the
    continuum's; with the units' grad-div the limit is the membrane's (within 2e-3) and
    ``J`` stays within 0.2 of 1 on the same coarse mesh."""
    key = UnitKey(1.0, (4, 1, 2), 0.5)
    plain = run_voltage(key, grad_div=0.0, solver="superlu")
    stab = heavy
    E0_m, _ = membrane
    assert plain["E0_limit"] < 0.7 * E0_m
    assert plain["J_min_limit"] < 0.5 and plain["J_max_limit"] > 1.5
    assert stab["E0_limit"] == pytest.approx(E0_m, rel=2e-3)
    assert 0.8 < stab["J_min_limit"] <= 1.0 <= stab["J_max_limit"] < 1.2
    assert plain["grad_div"] == 0.0 and stab["grad_div"] == 10.0
    with pytest.raises(ValueError, match="grad_div must be non-negative"):
        run_voltage(key, grad_div=-1.0)


def test_the_converged_limit_needs_two_agreeing_meshes(tmp_path):
    """``clamp_voltage_limit`` takes the two finest rows of a weight (by unknowns, with the
    units' grad-div): their relative spread in E0_limit is reported and must be within
    the tolerance; the plain form's rows are not mixed in."""
    from validation.data.clamp_zone import clamp_voltage_limit
    from validation.store import TableWriter

    def row(mesh, dofs, E0, gd=10.0):
        return {"alpha": 1.0, "mesh": mesh, "grading": 0.1, "formulation": "mixed",
                "grad_div": gd, "dofs": dofs, "E0_limit": E0, "D0_limit": 3.7,
                "lam1_limit": 3.35, "ratio": E0 / 0.2893836, "E0_membrane": 0.2905612}
    path = tmp_path / TABLES["voltage"].file
    with TableWriter(path, TABLES["voltage"]) as t:
        t.add([row("10x1x12", 4677, 0.2905674), row("20x1x24", 20482, 0.2905801),
               row("30x1x24", 30722, 0.19, gd=0.0)])
    got = clamp_voltage_limit(1.0, path=tmp_path)
    assert got["E0_limit"] == pytest.approx(0.2905801, abs=5e-7)    # cells: 6 digits
    assert got["spread"] == pytest.approx(0.29058 / 0.290567 - 1, rel=1e-9)
    assert got["meshes"] == ("10x1x12 g0.1", "20x1x24 g0.1")
    assert math.isnan(got["D0_physical"])
    with pytest.raises(ValueError, match="not converged"):
        clamp_voltage_limit(1.0, path=tmp_path, tol=1e-5)
    with pytest.raises(ValueError, match="two meshes are needed"):
        clamp_voltage_limit(1.0, path=tmp_path, grad_div=0.0)


def test_the_physical_crossing_is_bracketed_by_two_points_before_the_limit(heavy):
    """The first physical negative mode of the path lies between two of its points, both
    at or before the limit point: the charge at the centre rises along the path up to the
    limit, so the bracket's charges are ordered below the limit's (alpha = 1 on 6 x 1 x 8
    graded 0.1, whose clamp zone holds the wrinkle).  The 4 x 1 x 2 plate has none before
    its limit: the point past the limit, scanned before the located limit point, is not
    counted as before it."""
    row = run_voltage(UnitKey(1.0, (6, 1, 8), 0.1), solver="superlu")
    assert row["E0_stable"] < row["E0_physical"] <= row["E0_limit"]
    assert row["D0_stable"] < row["D0_physical"] <= row["D0_limit"] + 1e-9
    assert row["physical_class"].startswith("x1 ")
    assert "E0_physical" not in heavy and heavy["points"] > 0

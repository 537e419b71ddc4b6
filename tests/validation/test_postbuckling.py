"""The post-buckled branch of the clamped plate (skfem_dielectric.studies.postbuckling)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

import skfem_dielectric as fe
from skfem_dielectric.models.plate.symmetry_classes import class_stability
from skfem_dielectric.solvers.critical import critical_load
from skfem_dielectric.studies.postbuckling import (critical_mode, midplane_deflection,
                                           post_buckled_branch, switch_branch)
from validation.store import read_rows
from validation.cli import main

NEWTON = dict(settings=fe.RampSettings(rtol=1e-9, atol=0.0))


@pytest.fixture(scope="module")
def lightly_loaded():
    """alpha = 0.05 on the coarse quarter model 10 x 2 x 5 (the whole thickness, so that it
    can bend; the mesh of the eighth model 10 x 1 x 5 mirrored through the mid-plane):
    fundamental states at D0 = 0.75 (stable) and 0.8 (past the buckling load 0.7785 of
    docs/validation.md), and the own class's eigenvalue crossing between them.  Each
    Newton solve starts from the last converged state (``predictor="none"``): its last
    correction is then tiny, so the states stay symmetric through the thickness to
    round-off; a secant start stops one iteration earlier, with a correction whose
    round-off leaves a deflection at the Newton tolerance (7e-8 H at D0 = 0.8), and so do
    single-precision factors (2e-8 H): the study factorises in double precision."""
    res = fe.keplinger_plate(0.05, D0=[0.75, 0.8], elements=(10, 2, 5), symmetry="quarter",
                             options=fe.PlateOptions(grad_div=10.0),
                             settings=replace(fe.gallery.KEPLINGER_SETTINGS, max_cutbacks=6,
                                              max_iter=25, predictor="none",
                                              factor_precision="double"))
    assert res.converged
    pb, a, b = res.problem, res.steps[-2], res.steps[-1]
    crit = critical_load(pb, a.x, a.load, b.load,
                         lambda x, ld: critical_mode(pb, x, ld).eigenvalue,
                         tol=1e-5, **NEWTON)
    return pb, a, b, float(crit.load[1])


@pytest.fixture(scope="module")
def branch(lightly_loaded):
    pb, _, b, d_crit = lightly_loaded
    d = float(b.load[1])
    back = [d_crit + f * (d - d_crit) for f in (0.5, 0.25, 0.12, 0.06)]
    return post_buckled_branch(pb, b.x, b.load, [0.85], back)


def test_critical_load_is_the_eighth_models_class_crossing(lightly_loaded):
    """The quarter model's own class (x1 S, x3 S, either parity through the thickness)
    holds the bending mode; by symmetry its crossing is that of the class x1 S, x2 A,
    x3 S of the eighth model 10 x 1 x 5 (another model, dof layout and reduction: the
    same discrete problem).  Both are located to 1e-5, so they agree to 2e-5."""
    pb, a, b, d_crit = lightly_loaded
    assert critical_mode(pb, a.x, a.load).eigenvalue > 0
    assert critical_mode(pb, b.x, b.load).eigenvalue < 0
    res = fe.keplinger_plate(0.05, D0=[0.75, 0.8], elements=(10, 1, 5),
                             options=fe.PlateOptions(grad_div=10.0),
                             settings=replace(fe.gallery.KEPLINGER_SETTINGS, max_cutbacks=6,
                                              max_iter=25))
    pe, ea, eb = res.problem, res.steps[-2], res.steps[-1]

    def eig(x, ld):
        cs = class_stability(pe, x, ld, k=0, all_negative=True, extra=2,
                             only=["x1 S, x2 A, x3 S"])
        return float(cs.results[0].eigenvalues.min())

    crit = critical_load(pe, ea.x, ea.load, eb.load, eig, tol=1e-5, **NEWTON)
    assert abs(float(crit.load[1]) - d_crit) < 2e-5


def test_fundamental_state_does_not_bend(lightly_loaded):
    pb, _, b, _ = lightly_loaded
    # symmetric through the thickness to round-off (Newton tolerance 1e-9 relative)
    assert midplane_deflection(pb, b.x, b.load) < 1e-8 * pb.plate.H


def test_branch_switch_reaches_one_buckled_state_from_two_perturbations(lightly_loaded,
                                                                        branch):
    """Two perturbations (0.2 H and 1.5 H) along the mode converge to the same buckled
    equilibrium of the perfect plate: a distinct solution, not the perturbation."""
    pb, _, b, _ = lightly_loaded
    mode = critical_mode(pb, b.x, b.load).mode
    other = switch_branch(pb, b.x, b.load, mode, amplitudes=[1.5 * pb.plate.H])
    assert branch.switch.found and other.found
    assert branch.switch.deflection > 0.1 * pb.plate.H
    # Newton tolerance 1e-9 of the residual: the two states agree far below the mode size
    assert abs(other.deflection - branch.switch.deflection) < 1e-6 * branch.switch.deflection
    assert np.abs(other.x - branch.switch.x).max() < 1e-6 * np.abs(branch.switch.x).max()


def test_pitchfork_of_the_branch_gives_the_eigenvalue_crossing(lightly_loaded, branch):
    """D0 = D0_b + b w^2 + c w^4 through the four smallest deflections: the nonlinear
    branch alone gives the buckling load that the tangent's eigenvalue crossing locates.
    Tolerance 5e-5: the crossing is located to 1e-5; the fit's truncation (the next term
    w^6 at w <= 0.3 H) moves the intercept by 6e-6 between three and four points."""
    _, _, _, d_crit = lightly_loaded
    d0_fit, b = branch.pitchfork(4)
    assert abs(d0_fit - d_crit) < 5e-5
    assert b > 0                           # supercritical: the deflection grows with D0
    w = [s[1] for s in branch.states()]
    assert np.all(np.diff(w) > 0)


def test_buckled_branch_is_stable_where_the_fundamental_is_not(lightly_loaded, branch):
    """Exchange of stability: the fundamental state at D0 = 0.8 has one negative
    eigenvalue in the model's own class (inertia), every buckled state none."""
    pb, _, b, _ = lightly_loaded
    from_fundamental = class_stability(pb, b.x, b.load, k=0)
    assert from_fundamental.results[0].n_negative == 1
    steps = [s for _, _, s in branch.states() if s is not None]
    assert len(steps) == 5
    assert [s.quantities["n_negative_own"] for s in steps] == [0] * 5


def test_bad_input(lightly_loaded, branch):
    pb, _, b, _ = lightly_loaded
    eighth = fe.gallery.keplinger_problem(elements=(2, 1, 2))
    with pytest.raises(ValueError, match="x2 symmetry plane"):
        midplane_deflection(eighth, eighth.initial_state(), (0.0, 0.0))
    with pytest.raises(ValueError, match="mid-plane deflection"):
        switch_branch(pb, b.x, b.load, np.zeros_like(b.x))
    with pytest.raises(ValueError, match="amplitudes"):
        switch_branch(pb, b.x, b.load, critical_mode(pb, b.x, b.load).mode,
                      amplitudes=[-1.0])
    with pytest.raises(ValueError, match="x must be"):
        midplane_deflection(pb, b.x[:-1], b.load)
    with pytest.raises(ValueError, match="n must be >= 3"):
        branch.pitchfork(2)


def test_post_buckling_command_writes_both_branches_and_resumes(tmp_path, capsys):
    """``skfem-dielectric post-buckling`` on the coarse quarter model up to D0 = 0.85: the
    summary's two buckling loads (eigenvalue crossing located to 1e-4, pitchfork of the
    branch) agree within that location tolerance plus the fit's 1e-5; a rerun computes
    nothing and leaves the files as they are."""
    args = ["post-buckling", "--alpha", "0.05", "--meshes", "10x2x5", "--D0-max", "0.85",
            "--out", str(tmp_path)]
    assert main(args) == 0
    rows = read_rows(tmp_path / "post-buckling-summary.csv")
    assert len(rows) == 1
    r = rows[0]
    assert abs(r["D0_b"] - 0.77867) < 1e-4       # the own class's crossing, located to 1e-4
    assert abs(r["D0_b_pitchfork"] - r["D0_b"]) < 2e-4
    assert r["b"] > 0 and r["max_n_negative_own"] == 0
    states = read_rows(tmp_path / "post-buckling.csv")
    buckled = [s for s in states if s["branch"] == "buckled"]
    assert len(buckled) == 6               # 4 back, the switch point, 1 forward
    assert all(s["deflection"] > 0.1 for s in buckled)
    assert all(s["deflection"] < 1e-7 for s in states if s["branch"] == "fundamental")
    assert (tmp_path / "post-buckling.png").stat().st_size > 10_000
    before = (tmp_path / "post-buckling.csv").read_bytes()
    capsys.readouterr()
    assert main(args) == 0
    assert "alpha = 0.05" not in capsys.readouterr().out      # nothing recomputed
    assert (tmp_path / "post-buckling.csv").read_bytes() == before


def test_post_buckling_command_bad_input(tmp_path, capsys):
    assert main(["post-buckling", "--meshes", "10x1x5", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "N2 must be even" in err and err.count("\n") == 1
    assert main(["post-buckling", "--alpha", "-1", "--out", str(tmp_path)]) == 2
    assert "--alpha" in capsys.readouterr().err

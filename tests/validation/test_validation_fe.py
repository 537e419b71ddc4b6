"""The harness with the real FE runner: interrupted sweeps resume to identical files."""

from __future__ import annotations

import filecmp
from dataclasses import replace

import numpy as np
import pytest

from validation import cases as vc
from skfem_dielectric.gallery.loads import keplinger_s
from validation.fe import (buckling_problem, build_problem, pardiso_installed, run_fe,
                           stability_columns, whole_plate_verdict)
from skfem_dielectric.models.plate.modes import lowest_physical
from validation.specs import LOCATION_TOL
from validation.records import StepRecord
from validation.sweep import run_case
from validation.table import is_breakdown, read_table


class Interrupted(Exception):
    """Stands for Ctrl-C in the middle of a ramp."""


class StopAfter:
    """The real FE runner, interrupted after ``k`` converged targets (picklable)."""

    def __init__(self, k: int):
        self.k, self.seen = k, 0

    def __call__(self, spec, start, state, on_step):
        def wrapped(i, rec, st):
            stop = on_step(i, rec, st)
            self.seen += 1
            if self.seen >= self.k:
                raise Interrupted
            return stop

        return run_fe(spec, start, state, wrapped)


def small_case():
    runs = (
        # 3D: pre-load in sub-steps, then charge; resumes from (x, load) of a target
        vc.RunSpec("equibiaxial", "Gent", "coupled", 1.5, (0.0, 1.0, 2.0, 3.0)),
        vc.RunSpec("uniaxial", "neo-Hookean", "coupled", keplinger_s(1.0, g=9.81), (0.0, 1.5, 3.0),
                   alpha=1.0, mesh=(("n1", 4), ("n2", 1), ("n3", 2)), record_fields=True,
                   record_maps=True),
        vc.RunSpec("uniaxial", "neo-Hookean", "membrane", keplinger_s(1.0, g=9.81),
                   (0.0, 1.0, 2.0, 3.0, 4.0), alpha=1.0, mesh=(("n1", 8), ("n2", 1), ("n3", 4)),
                   record_fields=True),
        # s = 0: the pre-load is the unloaded state itself (a single target)
        vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", 0.0, (0.0, 1.0, 2.0)),
    )
    return vc.Case("zs22", "fig:zs22", "test", "uniaxial", quick=runs, full=runs)


@pytest.mark.parametrize("k", [2, 6, 9])   # inside: 3D homogeneous, 3D Keplinger, membrane
def test_real_fe_resume_is_bit_identical(tmp_path, k):
    case = small_case()
    run_case(case, tmp_path / "full", runner=run_fe, progress=False)
    with pytest.raises(Interrupted):
        run_case(case, tmp_path / "part", runner=StopAfter(k), progress=False)
    n_part = len((tmp_path / "part" / "zs22.csv").read_text().splitlines()) - 1
    assert n_part == k                                   # rows written step by step
    run_case(case, tmp_path / "part", runner=run_fe, progress=False)
    for name in ("zs22.csv", "zs22_fields.csv"):
        assert filecmp.cmp(tmp_path / "full" / name, tmp_path / "part" / name, shallow=False)
    t = read_table(tmp_path / "full" / "zs22.csv")
    # one row per FE target of every run, steps 0, 1, ... in order
    for spec in case.quick:
        assert list(t["step"][t["run"] == spec.key]) == list(range(len(spec.D0)))
    # the homogeneous 3D plates against Eq. (loading_gent) (mixed formulation, Newton
    # tolerance 1e-11 relative): 1e-8
    sel = t["variant"] == "coupled"
    eq = sel & np.isin(t["s"], (0.0, 1.5))
    np.testing.assert_allclose(t["lam1_fe"][eq], t["lam1_analytic"][eq], rtol=1e-8)


def test_process_pool_matches_serial(tmp_path, monkeypatch):
    # two worker processes (--jobs 2) write the same bytes as one serial process: the
    # CSV keeps 12 digits and at most 12 decimals, so threaded-BLAS round-off stays out
    from validation.sweep import run_cases

    eq = vc.Case("nh-d-e", "nh-d-e", "test", "equibiaxial",
                 quick=(vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", 0.0, (0.0, 2.0, 4.0)),
                        vc.RunSpec("equibiaxial", "neo-Hookean", "membrane", 1.0, (0.0, 2.0))))
    monkeypatch.setitem(vc.CASES, "nh-d-e", eq)
    monkeypatch.setitem(vc.CASES, "zs22", small_case())
    names = ["nh-d-e", "zs22"]
    run_cases(names, tmp_path / "serial", quick=True, runner=run_fe, progress=False)
    res = run_cases(names, tmp_path / "pool", quick=True, jobs=2, runner=run_fe, progress=False)
    for n in names:
        assert filecmp.cmp(tmp_path / "serial" / f"{n}.csv", tmp_path / "pool" / f"{n}.csv",
                           shallow=False)
    # homogeneous 3D and membrane plates against Eq. (loading_gent): Newton tolerance
    assert res[0].max_rel_error < 1e-8


def test_maxwell_keplinger_against_coupled_and_resume(tmp_path):
    # the quick Keplinger plate (eighth model, 10 x 1 x 5 Q2), alpha = 1, D0 steps of 0.5
    # up to the breakdown: 3D fully coupled vs 3D Maxwell traction (electrostatic field)
    s = keplinger_s(1.0, g=9.81)
    mesh = vc._mesh(vc.QUICK_PLATE, "maxwell")
    runs = tuple(vc.RunSpec("uniaxial", "neo-Hookean", v, s, tuple(np.arange(0.0, 6.01, 0.5)),
                            alpha=1.0, mesh=mesh) for v in ("coupled", "maxwell"))
    case = vc.Case("uni-axial-ideal", "uni-axial-ideal", "test", "uniaxial", quick=runs,
                   full=runs)
    run_case(case, tmp_path / "full", runner=run_fe, progress=False)
    # interrupted inside the Maxwell ramp (coupled: 7 rows up to the breakdown), resumed:
    # the same bytes (SuperLU, deterministic)
    with pytest.raises(Interrupted):
        run_case(case, tmp_path / "part", runner=StopAfter(10), progress=False)
    run_case(case, tmp_path / "part", runner=run_fe, progress=False)
    assert filecmp.cmp(tmp_path / "full" / "uni-axial-ideal.csv",
                       tmp_path / "part" / "uni-axial-ideal.csv", shallow=False)
    t = read_table(tmp_path / "full" / "uni-axial-ideal.csv")
    c, m = (t["variant"] == "coupled"), (t["variant"] == "maxwell")
    # both ramps stop at the same step, the first one with P33 < -0.01 mu (measured D0 = 3,
    # as for the coupled plate in docs/validation.md)
    assert list(t["D0"][c]) == list(t["D0"][m]) == list(np.arange(0.0, 3.01, 0.5))
    assert t["breakdown"][c][-1] and t["breakdown"][m][-1]
    # the two couplings discretise the same equations (Div tau_m = 0); they differ only by
    # the discrete int Div P_m . v at the clamp corners: required agreement 0.1 % on lam1
    # and 5 % of mu on min P33 up to the breakdown (measured 5.8e-4 and 3.4e-4 mu)
    np.testing.assert_allclose(t["lam1_fe"][m], t["lam1_fe"][c], rtol=1e-3)
    np.testing.assert_allclose(t["min_P33_interior"][m], t["min_P33_interior"][c], atol=0.05)
    # pre-load: no charge, no Maxwell traction, the same elastic problem: Newton tolerance
    np.testing.assert_allclose(t["lam1_fe"][m][0], t["lam1_fe"][c][0], rtol=1e-8)
    # at the centre lam1 follows the homogeneous uni-axial curve Eq. (DEuniax) within 1 %
    # (the clamps act near the ends only; measured 2.5e-3 for the coupled plate)
    np.testing.assert_allclose(t["lam1_fe"][m], t["lam1_analytic"][m], rtol=1e-2)
    assert np.all(t["stable"][m] == None)        # noqa: E711 (non-symmetric: no verdict)


@pytest.mark.skipif(not pardiso_installed(), reason="needs PARDISO (the fast extra)")
def test_pardiso_columns_come_from_the_ramps_factors():
    # with PARDISO the clamped 3D plate's stability columns are read from the ramp's own
    # factorisations (validation.fe.stability_monitor): the counts of a fresh analysis of
    # each state, its lowest eigenvalue within the Lanczos tolerance 1e-6
    spec = vc.RunSpec("uniaxial", "neo-Hookean", "coupled", keplinger_s(1.0, g=9.81),
                      (0.0, 1.0, 2.0, 3.0), alpha=1.0, mesh=(("n1", 8), ("n2", 1), ("n3", 4)),
                      stop_at_breakdown=False)
    seen = []
    run_fe(spec, 0, None, lambda i, rec, st: seen.append((rec, st)) and False,
           linear_solver="pardiso")
    assert [rec.D0 for rec, _ in seen] == list(spec.D0)
    problem = build_problem(spec)
    for rec, st in seen:
        fresh = stability_columns(spec, problem, st["x"], st["load"])
        assert (rec.n_negative, rec.n_unstable) == (fresh["n_negative"], fresh["n_unstable"])
        # the column is the whole-plate verdict of the fresh analysis (an eighth model
        # without the whole plate's spectrum: unknown unless a physical mode is negative)
        own = StepRecord(rec.D0, rec.lam1, rec.lam3, rec.min_P33, stable=fresh["stable"])
        assert rec.stable == whole_plate_verdict(spec, problem, own)
        assert rec.lowest_eig == pytest.approx(fresh["lowest_eig"], rel=1e-6)


def test_a_target_the_ramp_cannot_reach_ends_the_run_with_its_reason():
    # D0 = 60 is far beyond what the clamped plate carries: the ramp gets part of the way
    # (sub-steps converge past D0 = 3), then fails after its cut-backs.  The furthest
    # converged sub-step is no target: the runner reports the three targets only and
    # returns the failure (the harness records it as a row), instead of raising.
    spec = vc.RunSpec("uniaxial", "neo-Hookean", "coupled", keplinger_s(1.0, g=9.81),
                      (0.0, 1.5, 3.0, 60.0), alpha=1.0, mesh=(("n1", 4), ("n2", 1), ("n3", 2)),
                      stop_at_breakdown=False)
    seen = []
    out = run_fe(spec, 0, None, lambda i, rec, st: seen.append((i, rec.D0)) and False)
    assert seen == [(0, 0.0), (1, 1.5), (2, 3.0)]
    assert not out.converged and "not reached" in out.reason
    # the failed attempt lies past the last target reached, towards the unreachable one
    assert 3.0 < out.failed_D0 < 60.0


def test_stable_column_never_true_on_a_buckled_state(tmp_path, monkeypatch):
    # the quick case's alpha = 1 run (10 x 1 x 5 eighth model; its whole-plate columns of
    # the grad-div form's state at every target), cut to the states around its buckling
    # load: that state's own (symmetric-class) tangent has no physical negative eigenvalue
    # on any of them, the whole plate's spectrum has one from D0 = 3 on (its lowest
    # physical eigenvalue 7.9e-4 at 2.5, -1.4e-3 at 3)
    quick = next(r for r in vc.CASES["uni-axial-ideal"].quick
                 if r.variant == "coupled" and r.alpha == 1.0 and r.buckling)
    spec = vc.RunSpec(quick.geometry, quick.model, quick.variant, quick.s, (0.0, 2.5, 3.0),
                      alpha=1.0, mesh=quick.mesh, buckling=True, stop_at_breakdown=False)
    case = vc.Case("uni-axial-ideal", "uni-axial-ideal", "test", "uniaxial", quick=(spec,),
                   full=(spec,))
    seen = []

    def runner(spec, start, state, on_step):
        return run_fe(spec, start, state,
                      lambda i, rec, st: seen.append((rec, st)) or on_step(i, rec, st),
                      linear_solver="superlu")

    run_case(case, tmp_path, quick=True, runner=runner, progress=False)
    t = read_table(tmp_path / "uni-axial-ideal.csv")
    ev, stable = t["physical_eig"], list(t["stable"])
    # the event-driven scan classifies only the modes that crossed zero: a physical one
    # first at D0 = 3, none before (the column is empty there)
    assert np.isnan(ev[:2]).all() and ev[2] < 0, ev
    problem = buckling_problem(spec)
    # reference: the full scan (every negative mode of every class classified) of the
    # same states: its lowest physical eigenvalue is positive at 2.5 and at 3 the one the
    # event scan found (same class, to the Lanczos tolerance)
    full = [lowest_physical(problem, st["x_stab"], st["load"]) for _, st in seen[1:]]
    assert full[0].eigenvalue > 0 and full[1].eigenvalue < 0
    assert ev[2] == pytest.approx(full[1].eigenvalue, rel=1e-6)
    assert t["physical_class"][2] == full[1].label.symmetry
    assert list(t["n_negative_plate"][1:]) == [f.n_negative for f in full]
    # the column is the whole plate's verdict: False exactly where a physical mode is negative
    assert stable == [True, True, False], stable
    # ... and the symmetric class alone would have said True everywhere (what the column
    # must not report): the rule is what makes the difference
    own = [stability_columns(spec, problem, st["x_stab"], st["load"])["stable"]
           for _, st in seen]
    assert own == [True] * len(ev)
    # the two ramps are two states: the plain one's J = 1 holds weakly only, the grad-div
    # one is pulled towards J = 1 near the clamps, so their vectors differ by far more than
    # the Newton tolerance (1e-9 relative)
    assert all(np.linalg.norm(st["x"] - st["x_stab"]) > 1e-6 * np.linalg.norm(st["x"])
               for _, st in seen)
    # the buckling load is located (to LOCATION_TOL) on the row of the first state past it,
    # inside the bracket 2.5 .. 3 of the two states; no other row holds one
    located = t["D0_b"]
    assert np.isnan(located[:2]).all() and 2.5 < located[2] < 3.0, located
    # a linear interpolation of the two rows' eigenvalues would put it at 2.68: the
    # eigenvalue is far from linear there, the located value is not that
    e25, e3 = full[0].eigenvalue, full[1].eigenvalue
    assert abs(located[2] - (2.5 + 0.5 * e25 / (e25 - e3))) > 10 * LOCATION_TOL
    # interrupted after the state before the crossing and resumed: both ramps continue
    # from the saved vectors and D0_b is located from the saved grad-div state, so the
    # file is the uninterrupted run's, byte for byte
    with pytest.raises(Interrupted):
        run_case(case, tmp_path / "part", quick=True, runner=StopAfter(2), progress=False)
    run_case(case, tmp_path / "part", quick=True, runner=run_fe, progress=False)
    assert filecmp.cmp(tmp_path / "uni-axial-ideal.csv", tmp_path / "part" /
                       "uni-axial-ideal.csv", shallow=False)


@pytest.mark.parametrize("variant, symmetry, own, plate, expected", [
    ("coupled", ("x1", "x2", "x3"), True, None, None),     # eighth model alone: unknown
    ("coupled", ("x1", "x2", "x3"), False, None, False),   # a physical negative: unstable
    ("coupled", ("x1", "x2", "x3"), True, (4, 1e-3), True),    # whole plate: none negative
    ("coupled", ("x1", "x2", "x3"), True, (4, -1e-3), False),  # whole plate: one negative
    ("coupled", ("x1", "x2", "x3"), True, (2, float("nan")), True),  # only flagged modes
    ("coupled", (), True, None, True),                     # no symmetry plane: every mode
    ("membrane", (), True, None, None),                    # no out-of-plane mode
    ("maxwell", ("x1", "x2", "x3"), None, None, None),     # no symmetric tangent
])
def test_whole_plate_verdict_rule(variant, symmetry, own, plate, expected):
    from types import SimpleNamespace

    spec = vc.RunSpec("uniaxial", "neo-Hookean", variant, keplinger_s(1.0, g=9.81), (0.0,), alpha=1.0)
    problem = SimpleNamespace(plate=SimpleNamespace(symmetry=symmetry))
    rec = StepRecord(0.0, 1.0, 1.0, 0.0, stable=own)
    if plate is not None:
        rec.n_negative_plate, rec.physical_eig = plate
    assert whole_plate_verdict(spec, problem, rec) is expected


def test_alpha_1_breaks_down_after_alpha_0_7_and_both_cases_agree(monkeypatch):
    # the quick run's 3D P33 markers (10 x 1 x 5 eighth model, plain state): the paper's
    # trend, a heavier weight takes more charge before P33 near the clamps turns
    # compressive (alpha = 0.7 at D0 = 2, alpha = 1 at 3), and the alpha = 1 run of
    # uni-axial-ideal (analysed for buckling) and of zs22 are the same state, row by row
    # (equal to rounding, 1e-12: one problem, one ramp)
    import validation.fe.runner as runner
    monkeypatch.setattr(runner, "plate_buckling_columns", lambda *a, **k: {})  # not tested
    uni = vc.CASES["uni-axial-ideal"].quick
    a07 = next(r for r in uni if r.variant == "coupled" and r.alpha == 0.7)
    a1 = next(r for r in uni if r.variant == "coupled" and r.alpha == 1.0)
    z1 = next(r for r in vc.CASES["zs22"].quick if r.variant == "coupled")
    assert a1.buckling and not z1.buckling
    cut = tuple(d for d in z1.D0 if d <= 3.0)

    def onset(spec):
        rows = []

        def on_step(i, rec, st):
            rows.append((rec.D0, rec.min_P33_interior, rec.lam1))
            return is_breakdown(spec, rec)
        run_fe(replace(spec, D0=cut), 0, None, on_step, linear_solver="superlu")
        return rows

    r07, r1, rz = onset(a07), onset(a1), onset(z1)
    assert r07[-1][0] == 2.0 and r1[-1][0] == 3.0 and rz[-1][0] == 3.0
    assert r1[-1][0] >= r07[-1][0]
    np.testing.assert_allclose(np.array(r1), np.array(rz), rtol=0, atol=1e-12)

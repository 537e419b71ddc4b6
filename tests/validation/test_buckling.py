"""First physical buckling load of a plate (skfem_dielectric.studies.buckling)."""

from __future__ import annotations

import numpy as np
import pytest

import analytic as an
import skfem_dielectric as fe
from skfem_dielectric.gallery.drivers import equibiaxial_problem, keplinger_problem
from skfem_dielectric.linalg.solver_base import back_substitution_count
from skfem_dielectric.models.plate.symmetry_classes import class_stability
from skfem_dielectric.models.plate.modes import (LowestPhysical, corner_radius, lowest_physical,
                                                physical_modes)
from skfem_dielectric.models.plate.scan import PlateScan
from skfem_dielectric.studies.buckling import buckling_load
from validation.cli import main

SIZE = (8.0, 1.0, 4.0)


def _states(pb, loads, start=np.zeros(2)):
    res = fe.ramp(pb, loads, x0=pb.initial_state(), start=start)
    assert res.converged
    return [(st.x, st.load) for st in res.steps]


def test_homogeneous_equibiaxial_plate_has_no_buckling_load():
    """Charge control with a dead load s = 1: the homogeneous thin plate never reaches the
    Stroh threshold (the paper's claim), so the scan of every symmetry class finds no
    physical negative eigenvalue -- through the same code path as the clamped plate."""
    pb = equibiaxial_problem(size=(20.0, 1.0, 20.0), elements=(4, 1, 4),
                             options=fe.PlateOptions(grad_div=10.0))
    D0 = np.array([2.0, 4.0, 6.0])
    states = _states(pb, [np.array([1.0, 0.0])] + [np.array([1.0, d]) for d in D0])
    out = buckling_load(pb, states)
    assert not out.found and np.isnan(out.D0_b) and "no negative physical" in out.reason
    # no negative eigenvalue of any kind on the whole plate (exact count, inertia)
    assert [r["n_negative"] for r in out.scan] == [0, 0, 0, 0]
    # the event-driven scan computes no mode where no count changes; the full scan's
    # lowest physical eigenvalue at the last state is positive, its counts the same
    assert np.isnan(out.eigenvalue) and all(r["back_substitutions"] == 0 for r in out.scan)
    full = buckling_load(pb, states, scan="full")
    assert not full.found and full.eigenvalue > 0
    assert [r["n_negative"] for r in full.scan] == [0, 0, 0, 0]
    # the analytic side: the loading curve stays below the thin-plate limit of the
    # Stroh analysis at every state (independent of the FE)
    lam = [pb.postprocess(x, ld)["lam1"] for x, ld in states[1:]]
    assert np.all(D0 < an.thin_limit_D0(np.array(lam), an.NeoHookean()))


@pytest.fixture(scope="module")
def end_compression():
    """The slender clamped plate 8 x 1 x 4 charged to D0 = 1 and compressed end to end:
    the eighth model's states along s = -0.02 ... -0.4 (2 x 1 x 2 elements: the mirror
    images of the full mesh 4 x 2 x 4 below)."""
    pb = keplinger_problem(size=SIZE, elements=(2, 1, 2), symmetry="eighth")
    loads = [np.array([s, 1.0]) for s in np.linspace(-0.02, -0.4, 5)]
    first = _states(pb, [np.array([-0.02, 1.0]) * t for t in (0.5, 1.0)])[-1]
    rest = fe.ramp(pb, loads[1:], x0=first[0], start=loads[0])
    assert rest.converged
    return pb, [first] + [(st.x, st.load) for st in rest.steps]


def test_buckling_load_is_the_full_plates_eigenvalue_crossing(end_compression):
    pb, states = end_compression
    out = buckling_load(pb, states, tol=1e-5)
    assert out.found and out.label.kind == "physical"
    # bending: antisymmetric through the thickness
    assert out.label.increments[2] == "antisymmetric"
    # reference: the full (unreduced) mesh of the same plate, its lowest eigenvalue
    # (dense, no symmetry classes, no classification) located by critical_load
    full = keplinger_problem(size=SIZE, elements=(4, 2, 4), symmetry="full")
    xa = _states(full, [np.array([-0.02, 1.0]) * t for t in (0.5, 1.0)])[-1][0]

    def lowest(x, load):
        return class_stability(full, x, load, k=1, method="dense").lowest(1)[0][0]

    ref = fe.critical_load(full, xa, np.array([-0.02, 1.0]), np.array([-0.4, 1.0]), lowest,
                           tol=1e-5)
    # both crossings are located to 1e-5 in s, and the classes' eigenvalues equal the full
    # mesh's to 1e-8 (tests/fe/test_symmetry_classes.py): agreement to twice the tolerance
    assert abs(out.load[0] - ref.load[0]) <= 2e-5
    assert out.load[1] == 1.0 and out.D0_b == 1.0


def test_event_scan_locates_the_full_scans_load_with_its_counts(end_compression):
    # the event-driven scan (counts at every state, modes where a count changes) and the
    # full scan (every negative mode classified at every state) see the same counts
    # (Sylvester, exact) and locate the same crossing: each to tol = 1e-5, trial states
    # solved alike, so they agree to twice the tolerance
    pb, states = end_compression
    ev = buckling_load(pb, states, tol=1e-5)
    full = buckling_load(pb, states, tol=1e-5, scan="full")
    assert ev.found and full.found
    assert [r["n_negative"] for r in ev.scan] == [r["n_negative"] for r in full.scan]
    assert abs(ev.load[0] - full.load[0]) <= 2e-5
    assert ev.label.symmetry == full.label.symmetry and ev.label.kind == "physical"
    # where no class's count changed, the event scan computed no mode
    for a, b in zip(ev.scan[:-1], ev.scan[1:]):
        if a["n_negative"] == b["n_negative"] == 0:
            assert b["back_substitutions"] == 0 and b["changed"] == ""
    with pytest.raises(ValueError, match="scan must be one of"):
        buckling_load(pb, states, scan="some")


def test_counting_a_state_is_analysing_it_without_modes(end_compression):
    """PlateScan.count at a state gives analyse's counts there (one factorisation per
    class, Sylvester: exact, no eigenpair computed), and the state after it is analysed
    alike from either: the same counts, physical count and classes of what crossed."""
    pb, states = end_compression
    i = next(k for k in range(1, len(states))
             if PlateScan(pb).analyse(*states[k]).n_physical > 0)
    a, b = PlateScan(pb), PlateScan(pb)
    ref = a.analyse(*states[i - 1])
    b0 = back_substitution_count()
    assert b.count(*states[i - 1]) == ref.counts
    assert back_substitution_count() == b0
    ra, rb = a.analyse(*states[i]), b.analyse(*states[i])
    assert ra.counts == rb.counts and ra.n_physical == rb.n_physical > 0
    assert [m.symmetry for m in ra.labels] == [m.symmetry for m in rb.labels]
    assert np.allclose([m.eigenvalue for m in ra.labels], [m.eigenvalue for m in rb.labels])


def test_the_trials_trace_the_indicator_through_zero_at_the_located_load(end_compression):
    """The trial states of the location (BucklingLoad.trials, drawn in buckling.png):
    they start at the last stable scanned state and the first unstable one, end at the
    located load, and the line through them crosses zero there, while the straight line
    between the two scanned states crosses elsewhere.  Reference for each trial's
    eigenvalue: the lowest physical mode of the whole plate at that state re-solved from
    the stable state (lowest_physical: every class, every negative mode classified)."""
    pb, states = end_compression
    out = buckling_load(pb, states, tol=1e-5)
    tr = out.trials
    s_scan = [float(ld[0]) for _, ld in states]
    k = next(i for i, v in enumerate(s_scan) if abs(v - tr[1]["s"]) <= 1e-12)
    assert tr[0]["s"] == pytest.approx(s_scan[k - 1], abs=1e-12)
    assert tr[0]["eigenvalue"] > 0 > tr[1]["eigenvalue"]
    assert tr[-1]["s"] == out.load[0] and tr[-1]["eigenvalue"] == out.eigenvalue
    assert {t["class"] for t in tr} == {out.label.symmetry}
    assert all(t["D0"] == 1.0 for t in tr)
    # the polyline through the trials (by load) crosses zero within tol of the located s
    pts = sorted((t["s"], t["eigenvalue"]) for t in tr)
    (j,) = [i for i in range(len(pts) - 1) if pts[i][1] * pts[i + 1][1] < 0]
    (s0, v0), (s1, v1) = pts[j], pts[j + 1]
    assert abs(s0 - v0 * (s1 - s0) / (v1 - v0) - out.load[0]) <= 1e-5
    # the straight line between the two scanned states (the full scan's lowest physical
    # eigenvalues there) misses it by more than ten times that
    full = buckling_load(pb, states, tol=1e-5, scan="full")
    (sa, va), (sb, vb) = [(r["s"], r["physical"]) for r in full.scan[k - 1:k + 1]]
    assert abs(sa - va * (sb - sa) / (vb - va) - out.load[0]) > 1e-4
    # each trial's eigenvalue is its state's lowest physical one (the same mode)
    for t in (tr[2], tr[-1]):
        res = fe.ramp(pb, [np.array([t["s"], 1.0])], x0=states[k - 1][0],
                      start=np.asarray(states[k - 1][1], float),
                      settings=fe.RampSettings(rtol=1e-10, atol=0.0))
        assert res.converged
        ref = lowest_physical(pb, res.x, np.array([t["s"], 1.0])).label
        assert ref.symmetry == t["class"]
        assert ref.eigenvalue == pytest.approx(t["eigenvalue"], rel=1e-4, abs=1e-9)


def test_class_stability_in_threads_is_the_serial_one(end_compression):
    # the classes are independent problems: analysed two at a time (SuperLU releases the
    # GIL) they give the serial result bit for bit, in the order of the classes
    pb, states = end_compression
    x, load = states[-1]
    spec = dict(k=0, all_negative=True, extra=2, method="superlu")
    one = class_stability(pb, x, load, threads=1, **spec)
    two = class_stability(pb, x, load, threads=2, **spec)
    assert [c.name for c in two.classes] == [c.name for c in one.classes]
    assert len(one.classes) == 8
    # the most compressed state has negative eigenvalues: the spectrum slicing runs
    assert one.n_negative >= 1
    for r1, r2 in zip(one.results, two.results):
        assert r1.n_negative == r2.n_negative
        assert np.array_equal(r1.eigenvalues, r2.eigenvalues)
        assert np.array_equal(r1.modes, r2.modes)
    with pytest.raises(ValueError, match="threads must be"):
        class_stability(pb, x, load, threads=0)


def test_lowest_physical_is_the_first_physical_mode_of_the_whole_plate(end_compression):
    pb, states = end_compression
    x, load = states[-1]
    low = lowest_physical(pb, x, load)
    # the whole plate's count is the sum of the classes' dense counts (Sylvester, exact)
    assert low.n_negative == class_stability(pb, x, load, k=0, method="dense").n_negative
    assert low.n_negative >= 1
    # the modes are classified in ascending order up to the first physical one, which
    # carries the indicator
    values = [m.eigenvalue for m in low.labels]
    assert values == sorted(values)
    assert low.labels[-1] is low.label and low.label.kind == "physical"
    assert all(m.kind != "physical" for m in low.labels[:-1])
    assert low.eigenvalue == low.label.eigenvalue < 0
    # without a physical mode among the computed ones the indicator is nan
    assert np.isnan(LowestPhysical(None, [], 0).eigenvalue)


def test_corner_radius_covers_the_corner_element():
    pb = keplinger_problem(size=(100.0, 1.0, 50.0), elements=(10, 1, 5), symmetry="eighth")
    # 5 x 5 mm elements: the corner element's in-plane diagonal, 5 sqrt(2) mm > 2 H
    assert corner_radius(pb) == pytest.approx(5 * np.sqrt(2), rel=1e-12)
    fine = keplinger_problem(size=(100.0, 1.0, 50.0), elements=(80, 1, 40), symmetry="eighth")
    # 0.625 mm elements: 2 H = 2 mm is the larger
    assert corner_radius(fine) == 2.0


def test_bad_input(end_compression):
    pb, states = end_compression
    with pytest.raises(ValueError, match="result must be a RampResult or a PlateProblem"):
        buckling_load(object())
    with pytest.raises(ValueError, match="states must be given"):
        buckling_load(pb)
    with pytest.raises(ValueError, match="states must hold"):
        buckling_load(pb, [])
    with pytest.raises(ValueError, match=r"states\[0\] must be a pair"):
        buckling_load(pb, [(states[0][0], 1.0)])
    with pytest.raises(ValueError, match="tol must be"):
        buckling_load(pb, states[:1], tol=0.0)
    with pytest.raises(ValueError, match="extra must be"):
        buckling_load(pb, states[:1], extra=0)
    with pytest.raises(ValueError, match="radius must be"):
        physical_modes(pb, *states[0], radius=-1.0)
    with pytest.raises(ValueError, match="problem must be a PlateProblem"):
        corner_radius(object())
    res = fe.ramp(fe.CrossSection(fe.section_mesh(4.0, 1.0, 2, 1), fe.NeoHookeanDielectric()),
                  [np.zeros(3)])
    with pytest.raises(ValueError, match="result must come from a plate driver"):
        buckling_load(res)


def test_cli_rejects_bad_options(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:      # argparse: usage error, exit code 2
        main(["buckling", "--meshes", "10x1", "--out", str(tmp_path)])
    assert exc.value.code == 2 and "N1xN2xN3" in capsys.readouterr().err
    assert main(["buckling", "--quick", "--D0-step", "0", "--out", str(tmp_path)]) == 2
    assert "--D0-step must be > 0" in capsys.readouterr().err
    assert main(["buckling", "--quick", "--alpha", "-1", "--out", str(tmp_path)]) == 2
    assert "--alpha must be > 0" in capsys.readouterr().err


@pytest.mark.slow
def test_validate_and_buckling_quick_report_the_same_D0_b(tmp_path):
    # one definition of D0_b: the quick validate run's alpha = 1 plate (its report.md and
    # summary.json) and `buckling --quick` locate the same crossing, each to LOCATION_TOL
    # (the final bracket's width): their states differ only within the Newton tolerance,
    # so the two located values differ by at most two brackets
    import json

    from validation.cases import CASES, Case
    from validation.specs import LOCATION_TOL
    from validation.report import write_report, write_summary
    from validation.results import folder_results
    from validation.store import read_rows
    from validation.sweep import run_case

    spec = next(r for r in CASES["uni-axial-ideal"].quick if r.buckling)
    case = Case("uni-axial-ideal", "uni-axial-ideal", "test", "uniaxial", quick=(spec,),
                full=(spec,))
    res = run_case(case, tmp_path / "v", quick=True, progress=False)
    D0_b = res.buckling_D0[spec.key]
    assert main(["buckling", "--quick", "--solver", "superlu", "--out",
                 str(tmp_path / "b")]) == 0
    study = float(read_rows(tmp_path / "b" / "buckling.csv")[0]["D0_b"])
    assert abs(D0_b - study) <= 2 * LOCATION_TOL, (D0_b, study)
    # ... and summary.json and report.md state the located value
    every = folder_results(tmp_path / "v", [res])
    write_summary(every, tmp_path / "v", quick=True)
    write_report(every, tmp_path / "v", quick=True)
    summary = json.loads((tmp_path / "v" / "summary.json").read_text())
    assert summary["cases"]["uni-axial-ideal"]["buckling_D0"][spec.key] == D0_b
    report = (tmp_path / "v" / "report.md").read_text()
    assert f"D0_b = {D0_b:.4f}" in report
    from validation.report import meaning_lines
    assert "\n".join(meaning_lines()) in report     # the three meanings and the located order


def test_the_study_figure_passes_through_zero_at_D0_b_and_names_the_forms(tmp_path,
                                                                          buckling_figure_rows):
    """buckling.png: the eigenvalue panel joins the scanned states and the location's trial
    states in D0 order, so its line crosses zero at the row's D0_b (the trials' closed
    form: eigenvalue = 0 at 2.9147), not where the straight line between the two scanned
    states would (2.857); the P33 panel names the grad-div stabilised form it draws and
    marks both forms' interior onsets (0.645 and the plain form's 2.52)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import validation.studies.buckling as bk

    row, scan, plain = buckling_figure_rows
    trials = [{"alpha": 1.0, "mesh": "10x1x5", "D0": d, "eigenvalue": v,
               "physical_class": "x1 S"}
              for d, v in ((2.5, 0.05), (3.0, -0.02), (2.93, -0.003), (2.91, 0.0008),
                           (2.9147, 0.0))]
    shown = {}
    real_save = bk.save_figure

    def keep(fig, *a, **k):
        shown["axes"] = fig.axes
        return real_save(fig, *a, **k)

    bk.save_figure = keep
    try:
        bk.buckling_figure([row], scan, tmp_path, tmp_path / "buckling.png", trials=trials,
                           plain=plain)
    finally:
        bk.save_figure = real_save
    eig, p33 = shown["axes"][:2]
    (line,) = [ln for ln in eig.lines if ln.get_label() == "10x1x5"]
    x, y = line.get_xdata(), line.get_ydata()
    np.testing.assert_array_equal(x, [2.5, 2.91, 2.9147, 2.93, 3.0])
    assert y[2] == 0.0 and y[1] > 0 > y[3]               # through zero at D0_b, no jump
    assert [ln.get_xdata()[0] for ln in eig.lines if ln.get_linestyle() == ":"] == [2.9147]
    assert "grad-div stabilised form" in p33.get_title()
    onsets = {ln.get_label(): ln.get_xdata()[0] for ln in p33.lines
              if (ln.get_gid() or "").startswith("onset-")}
    assert onsets == {"P33 onset (interior), grad-div stabilised form: 0.645": 0.645,
                      "P33 onset (interior), plain form: 2.520": 2.52}
    # the converged study beside the run's coarse mesh: D0_b on the zero line, the located
    # P33 onset on the criterion's line, in that order (the shipped tables' values)
    from validation.data.loads import converged_buckling_load, p33_onsets

    (diamond,) = [ln for ln in eig.lines if ln.get_gid() == "buckling-converged"]
    (bar,) = [ln for ln in p33.lines if ln.get_gid() == "p33-onset-located"]
    d0b = converged_buckling_load(1.0).D0_b
    onset = dict((a, d) for a, d, _ in p33_onsets())[1.0]
    assert diamond.get_xydata().tolist() == [[d0b, 0.0]]
    assert bar.get_xydata().tolist() == [[onset, -0.01]] and onset < d0b
    assert (tmp_path / "buckling.png").exists()
    plt.close("all")


@pytest.mark.slow
def test_event_scan_matches_the_full_scan_on_the_quick_alpha_1_run():
    """The alpha = 1 run of the main job's ``uni-axial-ideal`` (grad-div form, 10 x 1 x 5,
    D0 = 0 ... 4 by 0.5): the event-driven scan and the full-spectrum scan see the same
    counts at every state (Sylvester, exact) and locate D0_b within 1e-4 of each other
    (each located to 1e-4 by the same trial states); the crossing is the x2-antisymmetric
    class's (the plate bends), and the event scan computes no mode at a state where no
    count changed."""
    from validation.cases import CASES
    from validation.fe.model import BUCKLING_NEWTON
    from validation.specs import LOCATION_TOL
    from validation.fe.runner import grad_div_states

    pb, states = grad_div_states(next(r for r in CASES["uni-axial-ideal"].runs(True)
                                      if r.buckling))
    kw = dict(tol=LOCATION_TOL, linear_solver="superlu", settings=BUCKLING_NEWTON)
    ev = buckling_load(pb, states, **kw)
    full = buckling_load(pb, states, scan="full", **kw)
    assert ev.found and full.found
    assert [r["n_negative"] for r in ev.scan] == [r["n_negative"] for r in full.scan]
    assert abs(ev.D0_b - full.D0_b) <= LOCATION_TOL
    assert ev.label.symmetry == full.label.symmetry == "x1 S, x2 A, x3 S"
    for r in ev.scan[1:]:
        if not r["changed"]:
            assert r["back_substitutions"] == 0

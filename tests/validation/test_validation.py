"""Validation harness: CSV contract, errors, breakdown, resume, executors, no stray writes.

The FE solver is replaced here by :class:`FakeRunner`, a closed-form "solver" with a
known, state-dependent error, so the harness's bookkeeping can be checked exactly and
fast; the real FE runs are in tests/cli/test_cli.py and tests/validation/test_validation_fe.py.
"""

from __future__ import annotations

import filecmp
import json
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

from validation import cases as vc
from skfem_dielectric.gallery.loads import keplinger_s
from validation.fe import with_dead_load
from validation.records import RunOutcome, StepRecord
from validation.sweep import run_case, run_cases, validate
from validation.table import BREAKDOWN_TOL, csv_columns, read_table

CONTRACT = ["case", "model", "variant", "s", "D0", "lam1_fe", "lam1_analytic", "lam3_fe",
            "min_P33", "converged", "stable"]
PERTURB = 1e-7      # the fake solver's error per unit of accumulated D0


class Interrupted(Exception):
    """Stands for Ctrl-C / a killed process in the middle of a sweep."""


def exact_lam(geometry: str, s: float, D0: float) -> float:
    """neo-Hookean closed forms solved with numpy's polynomial roots (independent of analytic).

    Equi-biaxial: lam^6 - s lam^5 - (1 + D0^2) = 0 (Eq. loading_gent);
    uni-axial: lam1^3 - s lam1^2 - sqrt(1 + D0^2) = 0 (Eq. DEuniax).
    """
    if geometry == "equibiaxial":
        r = np.roots([1, -s, 0, 0, 0, 0, -(1 + D0**2)])
    else:
        r = np.roots([1, -s, 0, -np.sqrt(1 + D0**2)])
    r = r[np.abs(r.imag) < 1e-9].real
    return float(r[r > 0].max())


def p33_clamp(alpha: float, D0: float) -> float:
    """The fake's lateral stress near the clamps: compressive beyond D0 = 2.5 alpha."""
    return 0.05 * alpha - 0.02 * D0


class FakeRunner:
    """A runner whose answer depends on the carried state: a lost state changes the CSV."""

    def __init__(self, interrupt_after: int | None = None, fail_at: float | None = None):
        self.interrupt_after = interrupt_after
        self.fail_at = fail_at
        self.calls = 0            # converged targets reported in this process

    def __call__(self, spec, start, state, on_step):
        acc = 0.0 if state is None else float(state["acc"])
        if start > 0 and state is None:
            raise AssertionError("resume without state")
        for i in range(start, len(spec.D0)):
            D0 = spec.D0[i]
            if self.fail_at is not None and D0 >= self.fail_at:
                return RunOutcome(False, "Newton diverged (fake)", D0)
            acc += D0
            lam = exact_lam(spec.geometry, spec.s, D0) * (1 + PERTURB * acc)
            alpha = spec.alpha or 0.0
            fields = None
            if spec.record_fields:
                x1 = np.linspace(0, 0.05, 5)
                fields = {"kind": np.zeros(5), "x1": x1, "x3": np.zeros(5), "P33": p33_clamp(alpha, D0) * x1 / 0.05,
                          "lam1": np.full(5, lam), "lam3": np.full(5, 1 / np.sqrt(lam))}
            p33 = p33_clamp(alpha, D0) if spec.geometry == "uniaxial" else 0.0
            rec = StepRecord(D0=D0, lam1=lam, lam3=lam if spec.geometry == "equibiaxial"
                             else 1 / np.sqrt(lam), min_P33=p33, min_P33_clamp=p33 + 0.1,
                             stable=True, iterations=3, fields=fields)
            stop = on_step(i, rec, {"acc": np.array(acc)})
            self.calls += 1
            if self.interrupt_after is not None and self.calls >= self.interrupt_after:
                raise Interrupted
            if stop:
                break
        return RunOutcome(True)


def eq_case(n_s=2, n=4, name="nh-d-e"):
    runs = tuple(vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", s,
                            tuple(np.linspace(0, 4, n + 1))) for s in (0.8, 2.5)[:n_s])
    return vc.Case(name, name, "test", "equibiaxial", quick=runs, full=runs)


def uni_case(alphas=(0.3, 1.0), fields=False, name="uni-axial-ideal"):
    runs = tuple(vc.RunSpec("uniaxial", "neo-Hookean", v, keplinger_s(a, g=9.81),
                            tuple(np.linspace(0, 6, 13)), alpha=a, record_fields=fields)
                 for v in ("coupled", "maxwell") for a in alphas)
    return vc.Case(name, name, "test", "uniaxial", quick=runs, full=runs)


def test_keplinger_runs_get_the_dead_load_of_their_weight():
    # the cases give the Keplinger runs by alpha; the runner's dead load is
    # s = alpha m g/(mu A) = alpha 0.15 * 9.81 / (9833.07 * 50e-6) (paper Sec. 6 caption),
    # bit for bit that formula for the weights of Fig. uni-axial-ideal
    runs = vc.CASES["uni-axial-ideal"].quick
    assert {r.alpha for r in runs} == set(vc.ALPHAS) and all(r.s is None for r in runs)
    for r in runs:
        assert with_dead_load(r).s == r.alpha * 0.15 * 9.81 / (9833.07 * 50e-6)
    one = next(r for r in runs if r.alpha == 1.0)
    assert with_dead_load(one).s == pytest.approx(2.99296, abs=5e-6)   # 6 digits, paper
    homogeneous = vc.CASES["nh-d-e"].quick[0]
    assert with_dead_load(homogeneous) is homogeneous                  # s given: kept
    with pytest.raises(ValueError, match="s may be None only for a uniaxial run"):
        vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", None, (0.0,))


def test_csv_contract_and_error(tmp_path):
    case = eq_case()
    res = run_case(case, tmp_path, runner=FakeRunner(), progress=False)
    t = read_table(tmp_path / "nh-d-e.csv")
    header = (tmp_path / "nh-d-e.csv").read_text().splitlines()[0].split(",")
    assert set(CONTRACT) <= set(header) and "alpha" not in header
    assert header == csv_columns(case)
    assert len(t["D0"]) == 10 and res.n_steps == 10          # one row per FE step
    # lam1_analytic from analytic.equibiaxial_lam against numpy's polynomial roots;
    # both are root finders at machine precision, the CSV keeps 12 digits
    ref = [exact_lam("equibiaxial", s, d) for s, d in zip(t["s"], t["D0"])]
    np.testing.assert_allclose(t["lam1_analytic"], ref, rtol=1e-11)
    # the fake's error is PERTURB * (sum of D0 so far): max = 1e-7 * (0+1+2+3+4) = 1e-6;
    # the error is recomputed from 12-digit CSV values (lam < 3): absolute slack 1e-11
    assert res.max_rel_error == pytest.approx(PERTURB * 10, abs=1e-11)
    assert all(t["stable"]) and res.breakdown_D0 == {r.key: None for r in case.quick}


def test_breakdown_stops_ramp_and_is_reported(tmp_path):
    case = uni_case()
    res = run_case(case, tmp_path, runner=FakeRunner(), progress=False)
    t = read_table(tmp_path / "uni-axial-ideal.csv")
    assert "alpha" in t
    for spec in case.quick:
        # first D0 on the grid (step 0.5) with 0.05 alpha - 0.02 D0 < -BREAKDOWN_TOL
        D0 = np.array(spec.D0)
        expect = D0[np.argmax(0.05 * spec.alpha - 0.02 * D0 < -BREAKDOWN_TOL)]
        assert res.breakdown_D0[spec.key] == pytest.approx(expect)
        sel = t["run"] == spec.key
        assert t["D0"][sel].max() == pytest.approx(expect)     # the ramp ended there
    # lam1 of the uni-axial dead load: analytic.uniaxial_lam1 vs the cubic's root
    ref = [exact_lam("uniaxial", s, d) for s, d in zip(t["s"], t["D0"])]
    np.testing.assert_allclose(t["lam1_analytic"], ref, rtol=1e-11)


def test_solver_failure_row(tmp_path):
    case = eq_case(n_s=1)
    res = run_case(case, tmp_path, runner=FakeRunner(fail_at=2.5), progress=False)
    t = read_table(tmp_path / "nh-d-e.csv")
    conv = [bool(c) for c in t["converged"]]
    assert conv == [True, True, True, False]                  # D0 = 0, 1, 2 then 3 fails
    assert np.isnan(t["lam1_fe"][-1]) and t["D0"][-1] == 3.0
    assert "D0 = 3" in res.reasons[case.quick[0].key]
    # a rerun does not retry a finished (failed) ramp and leaves the file unchanged
    before = (tmp_path / "nh-d-e.csv").read_bytes()
    run_case(case, tmp_path, runner=FakeRunner(fail_at=2.5), progress=False)
    assert (tmp_path / "nh-d-e.csv").read_bytes() == before


@pytest.mark.parametrize("k", [1, 5, 9, 14])
def test_resume_gives_identical_files(tmp_path, k):
    case = uni_case(fields=True)
    full = tmp_path / "full"
    run_case(case, full, runner=FakeRunner(), progress=False)
    part = tmp_path / "part"
    with pytest.raises(Interrupted):
        run_case(case, part, runner=FakeRunner(interrupt_after=k), progress=False)
    rows_before = len((part / "uni-axial-ideal.csv").read_text().splitlines()) - 1
    assert rows_before == k                                    # written step by step
    again = FakeRunner()
    res = run_case(case, part, runner=again, progress=False)
    total = len((full / "uni-axial-ideal.csv").read_text().splitlines()) - 1
    assert again.calls == total - k and res.resumed_steps == k   # nothing recomputed
    for name in ("uni-axial-ideal.csv", "uni-axial-ideal_fields.csv"):
        assert filecmp.cmp(full / name, part / name, shallow=False), name


def test_resume_after_crash_between_row_and_state(tmp_path):
    # a row written but its state not saved (killed in between): the row is recomputed
    case = eq_case(n_s=1)
    with pytest.raises(Interrupted):
        run_case(case, tmp_path / "a", runner=FakeRunner(interrupt_after=3), progress=False)
    state = tmp_path / "a" / ".state" / "nh-d-e" / f"{case.quick[0].key}.npz"
    with np.load(state) as z:
        assert int(z["__step__"]) == 2
    with open(tmp_path / "a" / "nh-d-e.csv", "a") as fh:
        fh.write("nh-d-e,garbage,3\n")
    run_case(case, tmp_path / "a", runner=FakeRunner(), progress=False)
    run_case(case, tmp_path / "b", runner=FakeRunner(), progress=False)
    assert filecmp.cmp(tmp_path / "a" / "nh-d-e.csv", tmp_path / "b" / "nh-d-e.csv", shallow=False)


def test_second_writer_is_refused(tmp_path):
    fcntl = pytest.importorskip("fcntl")
    case = eq_case(n_s=1)
    lock = tmp_path / ".state" / "nh-d-e.lock"
    lock.parent.mkdir(parents=True)
    with open(lock, "w") as fh:                     # another process writing this case
        fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        fh.write("pid 4242: skfem-dielectric validate --out x\n")
        fh.flush()
        with pytest.raises(ValueError, match=r"being written by another process "
                                             r"\(pid 4242: skfem-dielectric validate"):
            run_case(case, tmp_path, runner=FakeRunner(), progress=False)
    assert not (tmp_path / "nh-d-e.csv").exists()    # the refused process wrote nothing
    res = run_case(case, tmp_path, runner=FakeRunner(), progress=False)   # lock released
    assert res.n_steps == 5


def test_force_recomputes(tmp_path):
    case = eq_case(n_s=1)
    run_case(case, tmp_path, runner=FakeRunner(), progress=False)
    again = FakeRunner()
    run_case(case, tmp_path, runner=again, progress=False)
    assert again.calls == 0                                    # complete: nothing to do
    run_case(case, tmp_path, runner=again, force=True, progress=False)
    assert again.calls == 5


def test_executors_give_the_same_files(tmp_path, monkeypatch):
    monkeypatch.setitem(vc.CASES, "nh-d-e", eq_case())
    monkeypatch.setitem(vc.CASES, "uni-axial-ideal", uni_case())
    names = ["nh-d-e", "uni-axial-ideal"]
    serial = run_cases(names, tmp_path / "serial", runner=FakeRunner(), progress=False)
    with ThreadPoolExecutor(2) as ex:
        threaded = run_cases(names, tmp_path / "thread", executor=ex, runner=FakeRunner(),
                             progress=False)
    for a, b in zip(serial, threaded):
        assert a.max_rel_error == b.max_rel_error and a.breakdown_D0 == b.breakdown_D0
    for n in names:
        assert filecmp.cmp(tmp_path / "serial" / f"{n}.csv", tmp_path / "thread" / f"{n}.csv",
                           shallow=False)


def test_process_pool(tmp_path, monkeypatch):
    # jobs=2: a process pool; the registry patch reaches the forked workers
    monkeypatch.setitem(vc.CASES, "nh-d-e", eq_case())
    res = run_cases(["nh-d-e"], tmp_path, jobs=2, runner=FakeRunner(), progress=False)
    assert res[0].max_rel_error == pytest.approx(PERTURB * 10, abs=1e-11)  # 12-digit CSV


def test_validate_writes_only_into_out(tmp_path, monkeypatch):
    import matplotlib
    import matplotlib.pyplot as plt

    matplotlib.use("Agg")
    names = ["gent-equi-biaxial", "uni-axial-ideal", "zs22"]
    monkeypatch.setitem(vc.CASES, names[0], eq_case(name=names[0]))
    monkeypatch.setitem(vc.CASES, names[1], uni_case())
    monkeypatch.setitem(vc.CASES, names[2], uni_case(alphas=(1.0,), fields=True, name=names[2]))

    def no_show(*a, **k):
        raise AssertionError("plt.show() called by library code")

    monkeypatch.setattr(plt, "show", no_show)
    cwd = tmp_path / "cwd"
    cwd.mkdir()
    monkeypatch.chdir(cwd)
    out = tmp_path / "out"
    validate(names, out, runner=FakeRunner(), progress=False)
    assert list(cwd.iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cwd", "out"]
    files = {p.name for p in out.iterdir()}
    for n in names:
        assert {f"{n}.csv", f"{n}.png", f"{n}.pdf"} <= files
    summary = json.loads((out / "summary.json").read_text())
    assert summary["cases"][names[0]]["max_rel_error"] == pytest.approx(PERTURB * 10, abs=1e-11)
    # breakdown of the fake: first D0 on the 0.5 grid with 0.05 a - 0.02 D0 < -0.01
    assert set(summary["cases"]["zs22"]["breakdown_D0"].values()) == {3.5}
    assert summary["cases"]["uni-axial-ideal"]["breakdown_D0_by_alpha"] == {
        v: {"0.3": 1.5, "1": 3.5} for v in ("coupled", "maxwell")}
    report = (out / "report.md").read_text()
    cases_table = report.split("\n\nBreakdown (")[0]
    assert cases_table.count("\n| ") == 5                       # header, rule, 3 cases
    assert "What \"breakdown\" means" in report                 # and the three meanings
    assert plt.get_fignums() == []                               # figures closed


def test_library_never_prints_or_shows():
    # static check: only the CLI prints; nothing calls plt.show()
    root = Path(__file__).resolve().parents[2] / "validation"
    for path in root.glob("*.py"):
        src = path.read_text()
        assert ".show(" not in src, path
        if path.name != "cli.py":
            assert "print(" not in src, path


def test_runner_reporting_a_step_twice_is_an_error(tmp_path):
    def twice(spec, start, state, on_step):
        on_step(0, StepRecord(0.0, 1.0, 1.0, 0.0), {})
        on_step(0, StepRecord(0.0, 1.0, 1.0, 0.0), {})
        return RunOutcome(True)

    with pytest.raises(RuntimeError, match="steps must come once each"):
        run_case(eq_case(n_s=1), tmp_path, runner=twice, progress=False)


def test_bad_input():
    with pytest.raises(ValueError, match="geometry"):
        vc.RunSpec("shear", "neo-Hookean", "coupled", 1.0, (0.0, 1.0))
    with pytest.raises(ValueError, match="D0"):
        vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", 1.0, (0.0, 2.0, 1.0))
    with pytest.raises(ValueError, match="case must be one of"):
        vc.get_case("nope")
    with pytest.raises(ValueError, match="jobs"):
        run_cases([], ".", jobs=0)


def test_progress_bar_on_a_terminal_step_lines_elsewhere():
    import io

    from validation.progress import Progress

    class TTY(io.StringIO):
        def isatty(self):
            return True

    quiet, tty = io.StringIO(), TTY()
    for stream in (quiet, tty):
        with Progress(4, "case", stream=stream) as bar:
            for _ in range(4):
                bar.update(note="D0=1")
    # not a terminal: no bar, a line per finished step at most every Progress.interval
    # seconds (here the first only: the four updates take far less than 5 s)
    assert "\r" not in quiet.getvalue() and Progress.interval == 5.0
    assert quiet.getvalue().splitlines()[0].startswith("skfem-dielectric: case: 1/4 D0=1 (")
    assert len(quiet.getvalue().splitlines()) == 1
    last = tty.getvalue().split("\r")[-1]
    assert last.split()[:3] == ["case", "[" + "#" * Progress.width + "]", "4/4"]
    assert tty.getvalue().endswith("\n")


def test_read_table_verdict_columns_are_bool_even_when_empty(tmp_path):
    # Without PARDISO no stability verdict is computed: an all-empty ``stable`` column must
    # still read as None (not NaN), so code comparing with None works on every machine.
    from validation.table import read_table

    p = tmp_path / "t.csv"
    p.write_text("D0,stable,converged\n0.5,,True\n1.0,,False\n")
    t = read_table(p)
    assert list(t["stable"]) == [None, None]
    assert list(t["converged"]) == [True, False]
    assert t["D0"].tolist() == [0.5, 1.0]


def test_buckling_load_is_the_located_value_of_its_row(tmp_path):
    # a run analysed for buckling: the summary's D0_b is the runner's located value on
    # the row of the first state past it (here 2.3, as a location of a nonlinear
    # eigenvalue gives), not an interpolation of the rows' eigenvalues (0.9 - 0.4 D0
    # interpolates to 2.25); a resumed run keeps it (the row is verified and kept)
    spec = vc.RunSpec("uniaxial", "neo-Hookean", "coupled", keplinger_s(1.0, g=9.81),
                      tuple(np.linspace(0, 4, 9)), alpha=1.0, buckling=True,
                      stop_at_breakdown=False)
    case = vc.Case("uni-axial-ideal", "uni-axial-ideal", "test", "uniaxial", quick=(spec,),
                   full=(spec,))
    assert csv_columns(case)[-1] == "D0_b"
    assert "D0_b" not in csv_columns(uni_case())      # only cases with such a run

    def runner(spec, start, state, on_step, interrupt_at=None):
        for i in range(start, len(spec.D0)):
            D0 = spec.D0[i]
            ev = 0.9 - 0.4 * D0
            rec = StepRecord(D0=D0, lam1=exact_lam("uniaxial", spec.s, D0), lam3=1.0,
                             min_P33=0.0, physical_eig=ev, n_negative_plate=0,
                             D0_b=2.3 if ev < 0 and 0.9 - 0.4 * spec.D0[i - 1] >= 0
                             else float("nan"))
            on_step(i, rec, {"x": np.zeros(1), "load": np.array([spec.s, D0])})
            if interrupt_at is not None and D0 >= interrupt_at:
                raise Interrupted
        return RunOutcome(True)

    with pytest.raises(Interrupted):
        run_case(case, tmp_path / "a", runner=lambda *a: runner(*a, interrupt_at=3.0),
                 progress=False)
    resumed = run_case(case, tmp_path / "a", runner=runner, progress=False)
    fresh = run_case(case, tmp_path / "b", runner=runner, progress=False)
    assert resumed.buckling_D0[spec.key] == fresh.buckling_D0[spec.key] == 2.3
    assert filecmp.cmp(tmp_path / "a" / "uni-axial-ideal.csv",
                       tmp_path / "b" / "uni-axial-ideal.csv", shallow=False)
    t = read_table(tmp_path / "b" / "uni-axial-ideal.csv")
    assert np.isfinite(t["D0_b"]).sum() == 1 and t["D0"][np.isfinite(t["D0_b"])][0] == 2.5


def test_report_links_every_figure_and_summary_names_files_in_its_folder(tmp_path,
                                                                          monkeypatch,
                                                                          capsys,
                                                                          fake_wrinkling):
    """report.md links every PNG the run wrote (the breakdown map of docs/breakdown.md
    too); every ``csv`` of summary.json is relative to the folder of summary.json; the
    FE runs of wrinkling-fe are the number ``skfem-dielectric list`` shows."""
    import re

    import matplotlib

    from validation.studies.extra_cases import EXTRA_CASES

    matplotlib.use("Agg")
    names = ["uni-axial-ideal", "nh-d-e"]
    monkeypatch.setitem(vc.CASES, names[0], uni_case(alphas=(1.0,)))
    monkeypatch.setitem(vc.CASES, names[1], eq_case(n_s=1))
    fake_wrinkling(monkeypatch)
    monkeypatch.chdir(tmp_path)
    out = Path("res")                          # relative: as the CLI's --out res
    validate(names + ["wrinkling-fe"], out, quick=True, runner=FakeRunner(), progress=False)
    pngs = sorted(p.name for p in out.glob("*.png"))
    assert pngs == ["breakdown-map.png", "nh-d-e.png", "uni-axial-ideal.png",
                    "wrinkling-fe.png"]
    report = (out / "report.md").read_text()
    linked = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", report)
    assert sorted(linked) == pngs
    assert all((out / f).is_file() for f in linked)
    summary = json.loads((out / "summary.json").read_text())["cases"]
    assert set(summary) == set(names) | {"wrinkling-fe"}
    for name, case in summary.items():
        assert not Path(case["csv"]).is_absolute(), case["csv"]
        assert (out / case["csv"]).is_file(), (name, case["csv"])
        assert (out / case["csv"]).resolve() == (tmp_path / "res" / f"{name}.csv").resolve()
    # one count of the FE runs: the quick grid has 10 points, 9 with a Stroh root
    n = EXTRA_CASES["wrinkling-fe"].count(True)
    assert summary["wrinkling-fe"]["n_runs"] == n == 9
    assert summary["wrinkling-fe"]["n_steps"] == 10
    assert f"| wrinkling-fe | Sec. 3 (Stroh) | {n} | 10 |" in report
    from validation.cli import main

    capsys.readouterr()
    assert main(["list"]) == 0
    (line,) = [ln for ln in capsys.readouterr().out.splitlines()
               if ln.startswith("wrinkling-fe ")]
    assert f" {n}/{EXTRA_CASES['wrinkling-fe'].count(False)} " in line
    # a later run of another case keeps the earlier cases' figures and paths
    validate(["nh-d-e"], out, quick=True, runner=FakeRunner(), progress=False)
    report = (out / "report.md").read_text()
    assert sorted(re.findall(r"!\[[^\]]*\]\(([^)]+)\)", report)) == pngs
    summary = json.loads((out / "summary.json").read_text())["cases"]
    assert all((out / c["csv"]).is_file() for c in summary.values())

"""Progress off a terminal: a flushed line per finished load step (at most one per
interval), the grad-div ramp's steps through the case's bar, and what a resumed case kept.

The counts the lines must show are derived here from the fake runner's layout (two
equi-biaxial runs of 13 targets, no breakdown, interrupted after ``k`` reported steps) or
from the case definition, not from the harness's own bookkeeping."""

from __future__ import annotations

import io
import os
import re
import subprocess
import sys
import threading

import pytest

from test_validation import FakeRunner, Interrupted, eq_case
from validation.cases import CASES
from validation.progress import Progress, report_step
from validation.sweep import run_case

_LINE = re.compile(r"^skfem-dielectric: (?P<desc>[\w-]+): (?P<k>\d+)/(?P<n>\d+) (?P<note>.*) "
                   r"\(\d+ s\)$")


class Log(io.StringIO):
    """A stream that is not a terminal and records, for every write, whether the text
    written so far was flushed before the next write."""

    def __init__(self, tty: bool = False):
        super().__init__()
        self.tty, self.unflushed, self.pending = tty, 0, False

    def isatty(self) -> bool:
        return self.tty

    def write(self, text):
        self.unflushed += self.pending
        self.pending = True
        return super().write(text)

    def flush(self):
        self.pending = False
        super().flush()


def test_a_line_per_load_step_off_a_terminal_flushed():
    log = Log()
    with Progress(3, "zs22", stream=log, interval=0) as bar:
        for D0 in (0.5, 1.0, 1.5):
            bar.update(note=f"alpha=1 D0={D0}")
    lines = log.getvalue().splitlines()
    got = [(m["desc"], int(m["k"]), int(m["n"]), m["note"]) for m in map(_LINE.match, lines)]
    assert got == [("zs22", k, 3, f"alpha=1 D0={D0}") for k, D0 in ((1, 0.5), (2, 1.0),
                                                                    (3, 1.5))]
    assert log.unflushed == 0 and not log.pending          # every line flushed at once


def test_at_most_one_line_per_interval_none_on_a_terminal_or_when_off():
    log = Log()
    with Progress(50, "figde", stream=log, interval=3600) as bar:
        for _ in range(50):
            bar.update(note="D0=1")
    assert len(log.getvalue().splitlines()) == 1            # the first step only
    for stream, enabled in ((Log(tty=True), None), (Log(), False)):
        with Progress(5, "figde", stream=stream, enabled=enabled, interval=0) as bar:
            bar.update(note="D0=1")
            report_step("grad-div D0=1")
        assert "skfem-dielectric" not in stream.getvalue()  # the bar, or nothing
    with pytest.raises(ValueError, match="interval"):
        Progress(1, interval=-1.0)


def test_report_step_reaches_the_bar_of_its_thread_only():
    outer, inner = Log(), Log()
    seen_elsewhere = []
    with Progress(2, "outer", stream=outer, interval=0):
        with Progress(2, "inner", stream=inner, interval=0):
            report_step("grad-div D0=0.5")
            t = threading.Thread(target=lambda: seen_elsewhere.append(report_step("x")))
            t.start()
            t.join()
        report_step("grad-div D0=1")
    report_step("no bar")
    assert [m["note"] for m in map(_LINE.match, inner.getvalue().splitlines())] == \
        ["grad-div D0=0.5"]
    assert [m["note"] for m in map(_LINE.match, outer.getvalue().splitlines())] == \
        ["grad-div D0=1"]


class ReportingRunner(FakeRunner):
    """The fake runner that, like the harness's runner for a run analysed for buckling,
    reports the steps of a ramp computed before its rows."""

    def __call__(self, spec, start, state, on_step):
        for D0 in spec.D0[start:]:
            report_step(f"{spec.key} D0={D0:.3g} (grad-div form)")
        return super().__call__(spec, start, state, on_step)


@pytest.mark.parametrize("k", [5, 13, 14, 25])
def test_a_resumed_case_says_how_many_steps_and_runs_it_kept(tmp_path, capsys, k):
    case = eq_case(n_s=2, n=12)                            # 2 runs of 13 targets
    n_runs, n_targets = len(case.quick), len(case.quick[0].D0)
    with pytest.raises(Interrupted):
        run_case(case, tmp_path, runner=ReportingRunner(interrupt_after=k))
    err = capsys.readouterr().err
    assert "resumed" not in err
    assert any("(grad-div form)" in ln for ln in err.splitlines())   # before any row
    run_case(case, tmp_path, runner=ReportingRunner())
    err = capsys.readouterr().err.splitlines()
    complete, continued = k // n_targets, int(k % n_targets > 0)
    assert err[0] == (f"skfem-dielectric: case {case.name}: resumed with {k} steps kept; "
                      f"runs: {complete} of {n_runs} complete, {continued} continued from its "
                      f"last saved step, {n_runs - complete - continued} from the start")
    steps = [m for m in map(_LINE.match, err) if m]
    assert 1 <= len(steps) <= 2 * (n_runs * n_targets - k)     # a row and a grad-div step
    assert all(int(m["n"]) == n_runs * n_targets - k for m in steps)
    run_case(case, tmp_path, runner=ReportingRunner(), progress=False)
    assert capsys.readouterr().err == ""                        # progress off: silent


def test_validate_off_a_terminal_prints_steps_and_what_a_rerun_kept(tmp_path):
    """The command line with its output piped: step and run lines as the case runs, and a
    rerun says it kept every step (the counts from the case definition)."""
    runs = CASES["figde"].quick
    total = sum(len(r.D0) for r in runs)
    argv = [sys.executable, "-m", "validation.cli", "validate", "--quick", "--case", "figde",
            "--out", str(tmp_path / "results")]
    env = dict(os.environ, MPLBACKEND="Agg")
    first = subprocess.run(argv, capture_output=True, text=True, env=env, timeout=600)
    assert first.returncode == 0, first.stderr
    lines = first.stderr.splitlines()
    steps = [m for m in map(_LINE.match, lines) if m]
    assert steps and all(m["desc"] == "figde" and int(m["n"]) == total for m in steps)
    assert len(steps) <= total
    assert [ln for ln in lines if re.match(r"skfem-dielectric: figde: run \d+/", ln)] and \
        len([ln for ln in lines if " run " in ln]) == len(runs)
    again = subprocess.run(argv, capture_output=True, text=True, env=env, timeout=600)
    assert again.returncode == 0, again.stderr
    assert (f"skfem-dielectric: case figde: resumed with {total} steps kept; runs: "
            f"{len(runs)} of {len(runs)} complete, 0 continued from its last saved step, "
            f"0 from the start") in again.stderr.splitlines()

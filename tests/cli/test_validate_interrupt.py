"""``validate --jobs N`` stopped by SIGTERM to the parent or Ctrl-C (SIGINT to the whole
process group, as a terminal sends it; docs/cli.md, exit codes): every worker stops, no
temporary file is left, one line on stderr, exit code 143 (130), and a rerun resumes to
the files of an uninterrupted run, byte for byte.

The cases are real FE ramps on the one-element equi-biaxial plate; the runner sleeps
after each saved step so that the signal arrives while both workers are mid-ramp.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

psutil = pytest.importorskip("psutil")

ROOT = Path(__file__).resolve().parents[2]
CASES = ("nh-d-e", "gent-d-e", "figde")
N_TARGETS = 8

#: three tiny cases in two workers; each worker prints its pid after every saved step
SCRIPT = textwrap.dedent("""
    import multiprocessing, os, sys, time
    # the patched cases and runner reach the workers by fork
    multiprocessing.set_start_method("fork", force=True)
    from validation import cases as vc
    import validation.sweep as sweep
    pause, unwind = float(sys.argv[2]), float(sys.argv[3])
    real = sweep.run_fe
    def runner(spec, start, state, on_step):
        def step(i, rec, st):
            stop = on_step(i, rec, st)
            print(f"worker {os.getpid()} saved step {i}", flush=True)
            try:
                time.sleep(pause)
            except KeyboardInterrupt:
                time.sleep(unwind)         # a case slow to unwind (a long C call)
                raise
            return stop
        return real(spec, start, state, step)
    sweep.run_fe = runner
    for name in %(cases)r:
        runs = (vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", 1.0,
                           tuple(0.25 * k for k in range(%(n)d))),)
        vc.CASES[name] = vc.Case(name, name, "test", "equibiaxial", quick=runs, full=runs)
    from validation.cli import main
    sys.exit(main(["validate", "--case", *%(cases)r, "--jobs", "2", "--no-progress",
                   "--solver", "superlu", "--out", sys.argv[1]]))
""") % {"cases": CASES, "n": N_TARGETS}


def _start(tmp, out, pause, unwind=0.0):
    script = tmp / "validate_slow.py"
    script.write_text(SCRIPT)
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.Popen([sys.executable, str(script), str(out), str(pause), str(unwind)],
                            env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)        # its own process group


def _run(tmp, out):
    p = _start(tmp, out, 0.0)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 0, err
    return err


def _csvs(out):
    return {c: (out / f"{c}.csv").read_bytes() for c in CASES}


def _left_over(out):
    """Processes still running whose command line names ``out`` (the workers are forks
    of the parent and carry its command line)."""
    found = []
    for q in psutil.process_iter(["cmdline", "status"]):
        cmd = q.info["cmdline"] or []
        if str(out) in cmd and q.info["status"] != psutil.STATUS_ZOMBIE:
            found.append(q.pid)
    return found


def _workers(p) -> set:
    """The pids of both workers, once each has saved a step."""
    workers, t_end = set(), time.monotonic() + 60
    while len(workers) < 2 and time.monotonic() < t_end:
        text = p.stdout.readline()
        if "saved step" in text:
            workers.add(int(text.split()[1]))
    assert len(workers) == 2
    return workers


def _alive(pid) -> bool:
    return psutil.pid_exists(pid) and psutil.Process(pid).status() != psutil.STATUS_ZOMBIE


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("ref")
    _run(tmp, tmp / "out")
    return _csvs(tmp / "out")


@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork (POSIX)")
@pytest.mark.parametrize("sig, group, code, line", [
    pytest.param(signal.SIGTERM, False, 143,
                 "terminated (SIGTERM); rerun the same command to resume", id="SIGTERM"),
    pytest.param(signal.SIGINT, True, 130, "interrupted; rerun the same command to resume",
                 id="ctrl-c", marks=pytest.mark.slow)])
def test_a_signal_stops_every_worker(sig, group, code, line, tmp_path, reference):
    out = tmp_path / "out"
    p = _start(tmp_path, out, 0.5)
    workers = _workers(p)
    if group:
        os.killpg(p.pid, sig)
    else:
        p.send_signal(sig)
    t0 = time.monotonic()
    _, err = p.communicate(timeout=60)
    # the workers sleep 0.5 s per step and have at least 6 steps to go, the third case
    # waits: a parent that waited for them would need 7 s
    assert time.monotonic() - t0 < 5.0
    assert p.returncode == code, err
    assert err.strip() == line
    assert not any(_alive(w) for w in workers)
    assert _left_over(out) == []
    assert not [f for f in out.rglob("*") if f.name.endswith(".tmp")]
    # stopped mid-ramp: each started case has fewer rows than targets, the third none
    done = [len((out / f"{c}.csv").read_text().splitlines()) - 1
            for c in CASES if (out / f"{c}.csv").exists()]
    assert len(done) == 2 and all(1 <= n < N_TARGETS for n in done), done
    # the rerun resumes (locks released) and ends with the uninterrupted run's files
    assert _run(tmp_path, out) == ""
    assert _csvs(out) == reference
    summary = json.loads((out / "summary.json").read_text())["cases"]
    assert sum(summary[c]["resumed_steps"] for c in CASES) == sum(done)


@pytest.mark.slow
@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork (POSIX)")
def test_a_second_sigterm_kills_workers_slow_to_unwind(tmp_path):
    # each worker takes 30 s to unwind its case: the first SIGTERM waits for them, the
    # second kills them at once
    out = tmp_path / "out"
    p = _start(tmp_path, out, 0.5, unwind=30.0)
    workers = _workers(p)
    p.send_signal(signal.SIGTERM)
    time.sleep(1.0)
    assert p.poll() is None and all(_alive(w) for w in workers)
    p.send_signal(signal.SIGTERM)
    t0 = time.monotonic()
    _, err = p.communicate(timeout=60)
    assert time.monotonic() - t0 < 5.0
    assert p.returncode == 143, err
    assert err.strip() == "terminated (SIGTERM); rerun the same command to resume"
    assert not any(_alive(w) for w in workers) and _left_over(out) == []

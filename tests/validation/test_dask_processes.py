"""``clamp-zone units --scheduler tcp://...`` against real ``dask scheduler`` and
``dask worker`` processes on 127.0.0.1: a worker killed mid-unit has its unit run again
on the other worker (no row lost or doubled); the scheduler killed mid-run ends the
command with one line and exit code 3, the finished rows kept, and a rerun resumes."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import pytest

pytest.importorskip("distributed", reason="the 'cluster' extra is not installed")

from distributed import Client  # noqa: E402

from validation.data.registry import load  # noqa: E402
from validation.data.key import UnitKey  # noqa: E402

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="needs SIGKILL")]

#: two of the smallest units (about 3 CPU s each)
TWO = ["--alpha", "1", "0.7", "--mesh", "6x1x3", "--grading", "0.5", "--D0-step", "1",
       "--solver", "superlu"]
ENV = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}


def _scheduler(tmp_path):
    info = tmp_path / "scheduler.json"
    proc = subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler",
                             "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                             "--scheduler-file", str(info)], env=ENV,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    t0 = time.monotonic()
    while not info.exists() or not info.read_text().strip():
        assert proc.poll() is None and time.monotonic() - t0 < 60, "no scheduler"
        time.sleep(0.1)
    time.sleep(0.2)
    return proc, json.loads(info.read_text())["address"]


def _worker(address):
    return subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address,
                             "--nthreads", "1", "--nworkers", "1", "--no-dashboard",
                             "--no-nanny"], env=ENV, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)


def _units(address, out):
    return subprocess.Popen([sys.executable, "-c", "import sys; from validation.cli import "
                             "main; sys.exit(main(sys.argv[1:]))", "clamp-zone", "units",
                             *TWO, "--out", str(out), "--scheduler", address], env=ENV,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _busy_worker(client, workers, t_max=120):
    """The worker process running a task, once one is."""
    pids = client.run(os.getpid)                   # {worker address: its pid}
    by_pid = {p.pid: p for p in workers}
    t0 = time.monotonic()
    while time.monotonic() - t0 < t_max:
        for w, keys in client.processing().items():
            if keys and pids.get(w) in by_pid:
                return by_pid[pids[w]]
        time.sleep(0.05)
    raise AssertionError("no worker ran a task")


def _stop(*procs):
    for p in procs:
        if p.poll() is None:
            p.kill()
        p.wait()


def test_a_worker_killed_mid_unit_loses_and_doubles_no_row(tmp_path):
    sched, address = _scheduler(tmp_path)
    workers = [_worker(address), _worker(address)]
    try:
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(2, timeout=60)
            run = _units(address, tmp_path / "run")
            victim = _busy_worker(client, workers)
            victim.send_signal(signal.SIGKILL)
            out, err = run.communicate(timeout=300)
        assert run.returncode == 0, err
        rows = load("units", tmp_path / "run")
        keys = [UnitKey.from_row(r) for r in rows]
        # both units, once each, each with a located D0_b and its mode file
        assert sorted(k.alpha for k in keys) == [0.7, 1.0]
        assert all(r["D0_b"] for r in rows)
        for k in keys:
            assert (tmp_path / "run" / "modes" / f"{k.stem}.npz").is_file()
        assert out.count("done on the cluster") == 2
    finally:
        _stop(*workers, sched)


def test_the_scheduler_killed_mid_run_is_one_line_exit_3_and_a_rerun_resumes(tmp_path):
    sched, address = _scheduler(tmp_path)
    workers = [_worker(address)]          # one worker: the units run one after the other
    out_dir = tmp_path / "run"
    try:
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(1, timeout=60)
            run = _units(address, out_dir)
            t0 = time.monotonic()
            table = out_dir / "clamp_units.csv"
            while not (table.exists() and len(load("units", out_dir)) == 1):
                assert run.poll() is None and time.monotonic() - t0 < 300
                time.sleep(0.05)
        sched.send_signal(signal.SIGKILL)
        out, err = run.communicate(timeout=300)
    finally:
        _stop(*workers, sched)
    if run.returncode == 0:               # the second unit ended before the kill landed
        pytest.skip("both units finished before the scheduler was killed")
    assert run.returncode == 3, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    assert "lost the dask scheduler after 1 of 2 unit(s)" in lines[0]
    assert address in lines[0]
    (row,) = load("units", out_dir)
    # the rerun, here without a cluster, keeps the finished unit and computes the other
    again = subprocess.run([sys.executable, "-c", "import sys; from validation.cli import "
                            "main; sys.exit(main(sys.argv[1:]))", "clamp-zone", "units",
                            *TWO, "--out", str(out_dir)], env=ENV, capture_output=True,
                           text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    assert f"{UnitKey.from_row(row)}: kept" in again.stdout
    assert sorted(r["alpha"] for r in load("units", out_dir)) == ["0.7", "1"]

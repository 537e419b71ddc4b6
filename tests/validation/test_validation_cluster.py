"""Sweeps on a dask.distributed cluster (the optional ``cluster`` extra).

A ``LocalCluster`` of two worker processes runs real FE cases through the
Executor-based sweep API and the ``validate --scheduler`` option; the CSVs must be
byte-identical to the serial run's.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from validation import cases as vc
from validation.cli import main
from validation.sweep import run_cases

NO_DASK = "dask.distributed is not installed (pip install -e '.[cluster]')"


def small_cases():
    """Real quick runs, cut down: five homogeneous ramps in two cases (a few seconds)."""
    nh, fig = vc.CASES["nh-d-e"], vc.CASES["figde"]
    return [vc.Case(nh.name, nh.figure, nh.title, nh.geometry, quick=nh.quick[:3],
                    full=nh.quick[:3]),
            vc.Case(fig.name, fig.figure, fig.title, fig.geometry, quick=fig.quick[:2],
                    full=fig.quick[:2])]


def test_local_cluster_gives_the_serial_bytes(tmp_path):
    distributed = pytest.importorskip("distributed", reason=NO_DASK)
    cases = small_cases()
    serial = run_cases(cases, tmp_path / "serial", quick=True, progress=False)
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        on_dask = run_cases(cases, tmp_path / "dask", quick=True,
                            executor=client.get_executor(), progress=False)
    assert [r.n_steps for r in on_dask] == [r.n_steps for r in serial] == [21, 14]
    for c in cases:
        a = (tmp_path / "serial" / f"{c.name}.csv").read_bytes()
        b = (tmp_path / "dask" / f"{c.name}.csv").read_bytes()
        assert a == b, c.name


@pytest.mark.slow
def test_validate_scheduler_local(tmp_path, capsys):
    """``validate --quick --case nh-d-e --scheduler local --jobs 2`` against the serial run."""
    pytest.importorskip("distributed", reason=NO_DASK)
    args = ["validate", "--quick", "--case", "nh-d-e", "figde", "--no-progress"]
    assert main(args + ["--out", str(tmp_path / "serial")]) == 0
    assert main(args + ["--out", str(tmp_path / "dask"), "--scheduler", "local",
                        "--jobs", "2"]) == 0
    for name in ("nh-d-e", "figde"):
        assert (tmp_path / "serial" / f"{name}.csv").read_bytes() == \
            (tmp_path / "dask" / f"{name}.csv").read_bytes()


def test_scheduler_without_dask_is_an_input_error(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "dask.distributed", None)     # import fails
    code = main(["validate", "--quick", "--case", "nh-d-e", "--out", str(tmp_path),
                 "--scheduler", "local"])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "--scheduler needs dask.distributed (pip install -e '.[cluster]')" in err
    assert not (tmp_path / "nh-d-e.csv").exists()


@pytest.mark.slow
def test_a_scheduler_that_goes_away_is_exit_3_naming_it(tmp_path, capsys):
    """A scheduler killed mid-run (after the first case's CSV appears): one line naming
    it, exit code 3, the rows written so far kept for the rerun."""
    import socket
    import subprocess
    import threading
    import time

    pytest.importorskip("distributed", reason=NO_DASK)
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    address = f"tcp://127.0.0.1:{port}"
    dask = [sys.executable, "-m", "distributed.cli.dask_"]
    sched = subprocess.Popen(dask[:-1] + ["distributed.cli.dask_scheduler", "--host",
                                           "127.0.0.1", "--port", str(port),
                                           "--no-dashboard"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    worker = subprocess.Popen(dask[:-1] + ["distributed.cli.dask_worker", address,
                                            "--nthreads", "1", "--no-dashboard"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def kill_when_written():
        for _ in range(600):
            if (tmp_path / "nh-d-e.csv").exists():
                break
            time.sleep(0.2)
        sched.kill()

    try:
        killer = threading.Thread(target=kill_when_written)
        killer.start()
        code = main(["validate", "--quick", "--case", "nh-d-e", "figde", "--no-progress",
                     "--solver", "superlu", "--scheduler", address, "--out", str(tmp_path)])
        killer.join()
    finally:
        for p in (sched, worker):
            p.kill()
            p.wait()
    err = capsys.readouterr().err
    assert code == 3 and len(err.strip().splitlines()) == 1, err
    assert f"cannot use {address}: the dask scheduler went away mid-run" in err
    assert (tmp_path / "nh-d-e.csv").exists()


@pytest.mark.slow
def test_sigterm_on_a_local_cluster_stops_and_resumes(tmp_path):
    """``validate --scheduler local --jobs 2`` sent SIGTERM once the first FE step of the
    Keplinger case is saved: exit 143 with the one line of docs/cli.md, no worker left, no
    temporary file; the rerun resumes (the locks released) to the serial run's bytes."""
    pytest.importorskip("distributed", reason=NO_DASK)
    psutil = pytest.importorskip("psutil")
    root = Path(__file__).resolve().parents[2]
    args = ["validate", "--quick", "--case", "uni-axial-ideal", "--no-progress",
            "--solver", "superlu"]
    assert main(args + ["--out", str(tmp_path / "serial")]) == 0
    out = tmp_path / "dask"
    cmd = [sys.executable, "-m", "validation.cli", *args, "--scheduler", "local", "--jobs",
           "2", "--out", str(out)]
    p = subprocess.Popen(cmd, env=dict(os.environ, PYTHONPATH=str(root)),
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    csv_file, t_end = out / "uni-axial-ideal.csv", time.monotonic() + 120
    while time.monotonic() < t_end and p.poll() is None and not (
            csv_file.exists() and len(csv_file.read_text().splitlines()) >= 3):
        time.sleep(0.05)
    children = psutil.Process(p.pid).children(recursive=True)
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 143, err
    assert err.strip() == "terminated (SIGTERM); rerun the same command to resume"
    gone, alive = psutil.wait_procs(children, timeout=15)
    assert not alive
    assert not [f for f in out.rglob("*") if f.name.endswith(".tmp")]
    rows = len(csv_file.read_text().splitlines())
    assert main(args + ["--out", str(out)]) == 0
    assert len((tmp_path / "serial" / "uni-axial-ideal.csv").read_text().splitlines()) > rows
    assert (out / "uni-axial-ideal.csv").read_bytes() == \
        (tmp_path / "serial" / "uni-axial-ideal.csv").read_bytes()

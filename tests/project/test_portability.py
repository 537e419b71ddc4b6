"""The package on systems without the POSIX-only modules (Windows), and the units of the
portable peak-memory reading (macOS reports bytes, Linux kilobytes).

The POSIX-only modules ``fcntl``, ``resource`` and ``termios`` are made unimportable in a
fresh interpreter (``sys.modules[name] = None`` makes ``import name`` raise
``ImportError``, as it does on Windows) before anything of the package is imported.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

#: the modules a Windows Python does not have
POSIX_ONLY = ("fcntl", "resource", "termios")

BLOCK = textwrap.dedent(f"""
    import sys
    for name in {POSIX_ONLY!r}:
        sys.modules.pop(name, None)
        sys.modules[name] = None
""")


def _run(code: str, *, cwd=None, timeout=600) -> subprocess.CompletedProcess:
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, "-c", BLOCK + textwrap.dedent(code)],
                          capture_output=True, text=True, timeout=timeout, cwd=cwd,
                          env=env)


def test_the_block_is_real():
    # the harness itself: each blocked module raises ImportError in the child
    out = _run("""
        bad = []
        for name in ("fcntl", "resource", "termios"):
            try:
                __import__(name)
            except ImportError:
                continue
            bad.append(name)
        print(bad)
    """)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


def test_every_module_imports_without_posix_modules():
    out = _run("""
        import importlib, pkgutil
        failed, count = [], 0
        for top in ("analytic", "skfem_dielectric", "validation"):
            pkg = importlib.import_module(top)
            for info in pkgutil.walk_packages(pkg.__path__, top + "."):
                count += 1
                try:
                    importlib.import_module(info.name)
                except Exception as exc:      # report every module, not the first
                    failed.append(f"{info.name}: {type(exc).__name__}: {exc}")
        print(count)
        print("\\n".join(failed))
    """)
    assert out.returncode == 0, out.stderr
    count, *failed = out.stdout.strip().splitlines()
    # every module file of the three packages was walked (the packages themselves are
    # not counted), and none failed
    root = Path(__file__).resolve().parents[2]
    files = [f for top in ("analytic", "skfem_dielectric", "validation")
             for f in (root / top).rglob("*.py")]
    assert int(count) == len(files) - 3
    assert failed == []


def test_cli_runs_without_posix_modules(tmp_path):
    out = _run(f"""
        from validation.cli import main
        try:
            main(["--help"])
        except SystemExit as exc:
            assert exc.code == 0, exc.code
        print("list", main(["list"]))
        print("validate", main(["validate", "--quick", "--case", "gent-equi-biaxial",
                                "--out", {str(tmp_path / "res")!r}, "--no-progress"]))
    """)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert "list 0" in lines and "validate 0" in lines, out.stdout + out.stderr
    assert (tmp_path / "res" / "gent-equi-biaxial.csv").stat().st_size > 1000


LOCK_HOLDER = """
    import sys, time
    from validation.store import FolderLock
    with FolderLock(sys.argv[1], "the test table"):
        print("held", flush=True)
        time.sleep(120)
"""


@pytest.mark.skipif(not hasattr(__import__("signal"), "SIGKILL"), reason="needs SIGKILL")
def test_lock_excludes_without_fcntl(tmp_path):
    # without fcntl (and not on Windows) the lock is the file's existence with the
    # holder's pid: a second process is refused while the first lives, and a killed
    # holder does not block the next run
    path = tmp_path / "t.lock"
    holder = subprocess.Popen(
        [sys.executable, "-c", BLOCK + textwrap.dedent(LOCK_HOLDER), str(path)],
        stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "held"
        second = _run(f"""
            from validation.store import FolderLock, LockedError
            try:
                with FolderLock({str(path)!r}, "the test table"):
                    print("acquired")
            except LockedError as exc:
                print("refused:", exc)
        """, timeout=60)
        assert second.returncode == 0, second.stderr
        assert second.stdout.startswith("refused: the test table is being written by "
                                        f"another process (pid {holder.pid}")
    finally:
        holder.kill()
        holder.wait()
    third = _run(f"""
        from validation.store import FolderLock
        with FolderLock({str(path)!r}, "the test table"):
            print("acquired")
    """, timeout=60)
    assert third.returncode == 0, third.stderr
    assert third.stdout.strip() == "acquired"


PEAK = """
    import numpy as np
    from validation.clamp_zone.costs import peak_bytes
    before = peak_bytes()
    a = np.ones(300 * 2**20 // 8)          # 300 MiB, every page touched
    print(before, peak_bytes(), a.nbytes)
"""


@pytest.mark.parametrize("blocked", [False, True], ids=["default", "without-resource"])
def test_peak_memory_against_a_known_allocation(blocked):
    """In a child of this (large) pytest process: ru_maxrss would start at the parent's
    peak (Linux keeps it across fork and exec), VmHWM at the child's own."""
    code = (BLOCK if blocked else "") + textwrap.dedent(PEAK)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    before, after, nbytes = (float(v) for v in out.stdout.split())
    # the peak grows by the allocation (the pages touched), within 5 % and the few MiB
    # numpy's temporaries may add
    assert 0.95 * nbytes <= after - before <= 1.05 * nbytes + 16 * 2**20


def test_peak_memory_units_per_system(monkeypatch):
    # ru_maxrss is kilobytes on Linux and bytes on macOS (getrusage(2) of each system)
    import types

    from validation.clamp_zone import costs

    fake = types.SimpleNamespace(RUSAGE_SELF=0, getrusage=lambda who: types.SimpleNamespace(
        ru_maxrss=3 * 2**20))
    monkeypatch.setattr(costs, "resource", fake)
    monkeypatch.setattr(costs, "_proc_peak", lambda: None)     # as on macOS: no /proc
    monkeypatch.setattr(costs.sys, "platform", "darwin")
    assert costs.peak_bytes() == 3 * 2**20
    assert costs.peak_GB() == 0.003
    monkeypatch.setattr(costs.sys, "platform", "linux")
    assert costs.peak_bytes() == 3 * 2**30
    assert costs.peak_GB() == 3.0

"""Benchmark: the whole validation job, ``skfem-dielectric validate``, case by case.

Runs the command in a child process into a fresh folder (``--out`` to keep it) and prints,
per case, its wall runtime (``summary.json``), FE runs, FE steps and Newton iterations (the
case CSV's ``iterations`` column: Newton and chord steps of the charge-ramp cases), the
verdict of the report; then the job's CPU seconds (user + system, the figure that does
not depend on other jobs), the total wall time, the child's peak resident memory and
the load average before and after (other jobs on the machine slow every CPU-bound step).

The README's main job is ``--quick`` with the default install (SuperLU); the full run is
measured with ``--solver pardiso`` (the ``fast`` extra).  Figures are drawn as in the
job itself.

Usage::

    python benchmarks/bench_validate.py --quick
    python benchmarks/bench_validate.py --solver pardiso [--case uni-axial-ideal zs22]
    python benchmarks/bench_validate.py --smoke    # --quick --case figde

``--smoke`` runs the same code path on the cheapest case of the quick job (``figde``,
SuperLU unless ``--solver`` says otherwise): a check that the script runs, its numbers
are not measurements.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def _iterations(path: Path) -> int | None:
    """Sum of the ``iterations`` column of a case CSV (``None`` without one)."""
    if not path.is_file():
        return None
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    if not rows or "iterations" not in rows[0]:
        return None
    return int(sum(float(r["iterations"]) for r in rows if r["iterations"] not in ("", "nan")))


def _verdicts(report: Path) -> dict[str, str]:
    """Case -> verdict from the table of ``report.md``."""
    out = {}
    if not report.is_file():
        return out
    for line in report.read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 8 and cells[0] not in ("case", "---"):
            out[cells[0]] = cells[6]
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the README's quick job")
    ap.add_argument("--solver", choices=("auto", "superlu", "pardiso"), default="superlu")
    ap.add_argument("--case", nargs="+", default=None, help="cases (default: all)")
    ap.add_argument("--out", default=None, help="output folder (default: a temporary one)")
    ap.add_argument("--smoke", action="store_true",
                    help="--quick with the cheapest case, figde, unless --case is given (a "
                         "check that the script runs, not a measurement)")
    args = ap.parse_args(argv)
    if args.smoke:
        args.quick, args.case = True, args.case or ["figde"]

    tmp = None
    if args.out is None:
        tmp = tempfile.TemporaryDirectory(prefix="bench-validate-")
        out = Path(tmp.name) / "results"
    else:
        out = Path(args.out)
    cmd = [sys.executable, "-m", "validation.cli", "validate", "--out", str(out),
           "--solver", args.solver, "--no-progress"]
    if args.quick:
        cmd.append("--quick")
    if args.case:
        cmd += ["--case", *args.case]
    print("command: python -m", " ".join(cmd[2:]))
    print(f"load average before: {os.getloadavg()[0]:.2f}", flush=True)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    child = resource.getrusage(resource.RUSAGE_CHILDREN)
    peak_mb, cpu = child.ru_maxrss / 1024, child.ru_utime + child.ru_stime
    if proc.returncode != 0:
        print(proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else "failed")
        print(f"exit code {proc.returncode}")
        return 1
    summary = json.loads((out / "summary.json").read_text())["cases"]
    verdicts = _verdicts(out / "report.md")
    print(f"{'case':18s} {'wall s':>10s} {'FE runs':>8s} {'FE steps':>9s} "
          f"{'iterations':>10s}  verdict")
    for name, c in summary.items():
        its = _iterations(out / f"{name}.csv")
        print(f"{name:18s} {float(c.get('runtime_s') or 0):10.1f} {c.get('n_runs', ''):>8} "
              f"{c.get('n_steps', ''):>9} {'' if its is None else its:>10}  "
              f"{verdicts.get(name, '?')}")
    print(f"CPU time {cpu:.1f} s (user + system of the job and its workers), wall time "
          f"{wall:.1f} s (with the interpreter start and the figures), peak RSS "
          f"{peak_mb:.0f} MB, load average after {os.getloadavg()[0]:.2f}")
    if tmp is not None:
        tmp.cleanup()
    return 0


if __name__ == "__main__":
    sys.exit(main())

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
    python benchmarks/bench_validate.py --quick --against OLD --repeat 2

``--against OLD`` runs the job with the packages of the source tree ``OLD`` (e.g. ``git
archive 13becd9 | tar -x -C OLD``) and of this tree in alternation (``--repeat`` times
each), prints each run's CPU and wall seconds with the load average, the medians and
their ratio, and compares the case CSVs of the two trees column by column: the largest
difference of every numeric column that differs (``D0_b``, the located buckling load,
among them).

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


def _columns(path: Path) -> dict[str, list[str]]:
    """Columns of a case CSV (cells as text)."""
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(r for r in fh if not r.startswith("#")))
    return {k: [r[k] for r in rows] for k in (rows[0] if rows else {})}


def _float(cell: str) -> float | None:
    try:
        return float(cell)
    except ValueError:
        return None


def compare_outputs(a: Path, b: Path) -> list[tuple[str, str, float]]:
    """``(csv, column, largest |difference|)`` of the numeric columns of the case CSVs of
    two output folders that differ (cells that are not numbers must be equal, or the
    column is reported with ``inf``)."""
    out = []
    for fa in sorted(a.glob("*.csv")):
        fb = b / fa.name
        if not fb.is_file():
            out.append((fa.name, "(missing)", float("inf")))
            continue
        ca, cb = _columns(fa), _columns(fb)
        for col in ca:
            va, vb = ca[col], cb.get(col)
            if vb is None or len(va) != len(vb):
                out.append((fa.name, col, float("inf")))
                continue
            worst = 0.0
            for x, y in zip(va, vb):
                fx, fy = _float(x), _float(y)
                if fx is None or fy is None:
                    worst = worst if x == y else float("inf")
                elif not (fx == fy or (fx != fx and fy != fy)):
                    worst = max(worst, abs(fx - fy))
            if worst > 0:
                out.append((fa.name, col, worst))
    return out


def against(args, cmd_tail: list[str]) -> int:
    """The job with this tree and with the tree ``args.against`` in alternation."""
    import statistics

    here = Path(__file__).resolve().parents[1]
    trees = {"this tree": here, "reference": Path(args.against).resolve()}
    runs: dict[str, list[tuple[float, float]]] = {k: [] for k in trees}
    with tempfile.TemporaryDirectory(prefix="bench-validate-") as tmp:
        for i in range(args.repeat):
            for name, tree in trees.items():
                out = Path(tmp) / f"{name.replace(' ', '-')}-{i}"
                env = dict(os.environ, PYTHONPATH=str(tree))
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                load0 = os.getloadavg()[0]
                t0 = time.perf_counter()
                proc = subprocess.run([sys.executable, "-m", "validation.cli", "validate",
                                       "--out", str(out)] + cmd_tail, cwd=tree, env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                      text=True)
                wall = time.perf_counter() - t0
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
                if proc.returncode != 0:
                    print(f"{name}: exit code {proc.returncode}: "
                          f"{proc.stderr.strip().splitlines()[-1:]}")
                    return 1
                runs[name].append((cpu, wall))
                print(f"  {name:>9}: CPU {cpu:6.1f} s, wall {wall:6.1f} s, load "
                      f"{load0:.2f} -> {os.getloadavg()[0]:.2f}", flush=True)
        med = {k: (statistics.median(c for c, _ in v), statistics.median(w for _, w in v))
               for k, v in runs.items()}
        for k, (c, w) in med.items():
            print(f"{k:>10}: median CPU {c:.1f} s, median wall {w:.1f} s")
        print(f"ratio (this tree / reference, medians): CPU "
              f"{med['this tree'][0] / med['reference'][0]:.3f}, wall "
              f"{med['this tree'][1] / med['reference'][1]:.3f}")
        diffs = compare_outputs(Path(tmp) / "this-tree-0", Path(tmp) / "reference-0")
        print(f"columns that differ between the trees: {len(diffs)}")
        for f, col, d in sorted(diffs, key=lambda t: -t[2])[:25]:
            print(f"  {f:28s} {col:24s} {d:.2e}")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the README's quick job")
    ap.add_argument("--solver", choices=("auto", "superlu", "pardiso"), default="superlu")
    ap.add_argument("--case", nargs="+", default=None, help="cases (default: all)")
    ap.add_argument("--out", default=None, help="output folder (default: a temporary one)")
    ap.add_argument("--smoke", action="store_true",
                    help="--quick with the cheapest case, figde, unless --case is given (a "
                         "check that the script runs, not a measurement)")
    ap.add_argument("--against", default=None, metavar="TREE",
                    help="also run the job with the packages of the source tree TREE, in "
                         "alternation, and compare times and CSVs")
    ap.add_argument("--repeat", type=int, default=2,
                    help="runs of each tree with --against (default: 2)")
    args = ap.parse_args(argv)
    if args.smoke:
        args.quick, args.case = True, args.case or ["figde"]
    if args.against:
        tail = ["--solver", args.solver, "--no-progress"] + (["--quick"] if args.quick else [])
        return against(args, tail + (["--case", *args.case] if args.case else []))

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

"""Benchmark: what the README's commands cost, written as the table ``docs/costs.md``.

The one place that states what the commands of the README cost: each command runs in a
child process (a fresh temporary folder as its working folder, so that its ``results/``
lands there; the test suite and the site build run in the checkout, as the README says)
and the script records its **CPU seconds** (user + system of the child and its worker
processes, the difference of ``resource.getrusage(RUSAGE_CHILDREN)`` around it: less
dependent on other jobs than the wall time, not independent of them), its **wall seconds** with the **load average** before
and after (other jobs slow every CPU-bound step), and its **peak memory** (the largest
resident set of the child or a worker, from ``os.wait4``).  Also counted: the tests that
``python -m pytest`` runs (``--collect-only``).

The table keeps a row per command with the date and the machine it was measured on;
measuring some commands (``--only``) rewrites their rows and keeps the others, so that a
cheap command can be re-measured without the hour of the full run.  The table is written
after each command: a run stopped midway keeps the rows it measured.  A command never
measured has a row that says so and how to measure it.  Every run but ``--smoke``
counts the tests again (a few CPU seconds).

Usage::

    python benchmarks/bench_costs.py                        # every command, about 1 CPU hour
    python benchmarks/bench_costs.py --only list curves     # those rows, the rest kept
    python benchmarks/bench_costs.py --smoke                # list, simulate --help; a temporary table

The README's install (``pip install -e .``) is not part of the measurement: run the script
in the virtual environment of the README's first command.  ``--smoke`` measures the two
cheapest commands and writes the table into a temporary folder (printed, then removed): a
check that the script runs, its numbers are not measurements.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import re
import resource
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TABLE = ROOT / "docs" / "costs.md"
#: the commands of the README in its order: key -> (command as the README writes it,
#: where it runs: ``"tmp"`` a fresh folder, ``"checkout"`` the repository), what it is
COMMANDS = {
    "main": ("skfem-dielectric validate --quick --out results", "tmp",
             "the main job, after the install of the README's first command"),
    "tests": ("python -m pytest", "checkout",
              "the test suite, after the install of the README's second command"),
    "site": ("sphinx-build -W -b html docs docs/_build/html", "checkout",
             "the site, every gallery example executed"),
    "list": ("skfem-dielectric list", "tmp", ""),
    "curves": ("skfem-dielectric curves --out results/curves", "tmp", ""),
    "full": ("skfem-dielectric validate --out results/full", "tmp", "fine meshes"),
    "simulate-help": ("skfem-dielectric simulate --help", "tmp", ""),
    "bench": ("skfem-dielectric bench", "tmp", ""),
    "buckling": ("skfem-dielectric buckling --quick --out results", "tmp", ""),
    "post-buckling": ("skfem-dielectric post-buckling --quick --out results", "tmp", ""),
    # the demos of docs/lecture.md, whose CPU column is these rows' (tests/docs/test_lecture.py)
    "lecture-curves": ("skfem-dielectric curves --out results/lecture/curves", "tmp",
                       "lecture demo 1"),
    "lecture-nh-d-e": ("skfem-dielectric validate --quick --case nh-d-e --out results/lecture",
                       "tmp", "lecture demo 2"),
    "lecture-voltage": ("skfem-dielectric validate --quick --case voltage-control --out "
                        "results/lecture", "tmp", "lecture demo 3"),
    "lecture-wrinkling": ("skfem-dielectric wrinkling-fe --quick --out results/lecture/wrinkling",
                          "tmp", "lecture demo 4"),
    "lecture-uniaxial": ("skfem-dielectric validate --quick --case uni-axial-ideal --out "
                         "results/lecture", "tmp", "lecture demo 5"),
    "lecture-modes": ("skfem-dielectric clamp-zone modes --out results/lecture", "tmp",
                      "lecture demo 6"),
    "lecture-tables": ("skfem-dielectric clamp-zone tables --breakdown", "tmp",
                       "lecture demo 6"),
}
SMOKE = ("list", "simulate-help")
HEADER = ("| command | CPU s | wall s | load average (before -> after) | peak memory | "
          "measured |")
NOT_MEASURED = "not measured"
_COUNT = re.compile(r"^(?P<run>\d+)(?:/(?P<all>\d+))? tests? collected", re.M)


def machine() -> str:
    """Cores, memory and the linear solver of ``--solver auto``: ``2 CPUs, 23.4 GB, SuperLU``."""
    mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 1e9
    try:
        import pypardiso  # noqa: F401
        solver = "PARDISO"
    except ImportError:
        solver = "SuperLU"
    return f"{os.cpu_count()} CPUs, {mem:.1f} GB, {solver}"


def cpu_model() -> str:
    """The processor's name (``/proc/cpuinfo``), else what :mod:`platform` says."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def argv_of(command: str) -> list[str]:
    """The command line of a README command with this interpreter's environment: its
    ``python`` and the console scripts beside it."""
    argv = command.split()
    bindir = Path(sys.executable).parent
    if argv[0] == "python":
        return [sys.executable, *argv[1:]]
    if (bindir / argv[0]).exists():
        return [str(bindir / argv[0]), *argv[1:]]
    return argv


def measure(command: str, cwd: Path) -> dict:
    """Run ``command`` in ``cwd``; CPU and wall seconds, load average, peak memory."""
    env = dict(os.environ, MPLBACKEND="Agg",
               PATH=str(Path(sys.executable).parent) + os.pathsep + os.environ.get("PATH", ""))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    load0 = os.getloadavg()[0]
    with tempfile.TemporaryFile() as err:          # a file: a pipe could fill and block
        t0 = time.perf_counter()
        proc = subprocess.Popen(argv_of(command), cwd=cwd, env=env,
                                stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)    # the child's own peak memory
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
        err.seek(0)
        stderr = err.read().decode(errors="replace")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"cpu": cpu, "wall": wall, "load": (load0, os.getloadavg()[0]),
            "peak_mb": usage.ru_maxrss / 1024, "exit": proc.returncode,
            "error": stderr.strip().splitlines()[-1] if stderr.strip() else ""}


def count_tests() -> tuple[int, int]:
    """Tests that ``python -m pytest`` runs and those it collects (the rest: ``-m slow``)."""
    out = subprocess.run([sys.executable, "-m", "pytest", "--collect-only", "-q"], cwd=ROOT,
                         capture_output=True, text=True).stdout
    m = _COUNT.search(out)
    if m is None:
        raise RuntimeError(f"no test count in the output of pytest --collect-only:\n{out[-500:]}")
    return int(m["run"]), int(m["all"] or m["run"])


def row(key: str, m: dict | None, when: str, where: str) -> str:
    """The table row of command ``key``: measured (``m``) or saying how to measure it."""
    command, _, what = COMMANDS[key]
    label = f"`{command}`" + (f" ({what})" if what else "")
    if m is None:
        return (f"| {label} | {NOT_MEASURED} | | | | `python benchmarks/bench_costs.py "
                f"--only {key}` |")
    if m["exit"] != 0:
        return f"| {label} | failed (exit code {m['exit']}) | | | | {when}, {where} |"
    return (f"| {label} | {m['cpu']:.1f} | {m['wall']:.1f} | {m['load'][0]:.2f} -> "
            f"{m['load'][1]:.2f} | {m['peak_mb']:.0f} MB | {when}, {where} |")


def old_rows(path: Path) -> dict[str, str]:
    """The rows of an existing table by command key (rows of unknown commands dropped)."""
    if not path.is_file():
        return {}
    by_label = {f"`{c}`": k for k, (c, _, _) in COMMANDS.items()}
    rows = {}
    for line in path.read_text().splitlines():
        first = line.strip().strip("|").split("|")[0].strip() if line.startswith("| `") else ""
        label = first.split(" (")[0]
        if label in by_label:
            rows[by_label[label]] = line
    return rows


def old_count(path: Path) -> str | None:
    """The test-count paragraph of an existing table, as one line."""
    if path.is_file():
        for para in path.read_text().split("\n\n"):
            if para.startswith("Tests: ") and "not counted" not in para:
                return " ".join(para.split())
    return None


def render(rows: dict[str, str], count: str | None, cpu: str) -> str:
    """The page ``docs/costs.md``: how it is made, the table, the test count."""
    lines = [
        "# What the commands cost",
        "",
        "<!-- generated by benchmarks/bench_costs.py: edit that script, not this page -->",
        "",
        *textwrap.wrap("The README's commands, each run in a child process by `python "
        "benchmarks/bench_costs.py` in the virtual environment of the README's install: "
        "**CPU seconds** are user + system time of the command and its worker processes "
        "(`getrusage(RUSAGE_CHILDREN)`): they depend on the load much less than wall "
        "seconds, but they do depend on it (on a 2-core machine whose hyper-threads share "
        "caches and memory bandwidth the same commands used 1.4 to 2.3 times the CPU seconds "
        "below at a load average of 5 to 7), so compare rows measured at a similar load; "
        "**wall seconds** come with the load average before and after (about "
        "1 per busy core: other jobs slow every CPU-bound step); **peak memory** is the "
        "largest resident set of the command or a worker.  Each row says when and on what "
        "machine (cores, memory, the linear solver of `--solver auto`: SuperLU without the "
        "`fast` extra) it was measured; the install itself is not included.", 92),
        "",
        *textwrap.wrap("Regenerate every row with `python benchmarks/bench_costs.py` (about an hour of CPU: "
        "the full `validate` and the test suite dominate) or some rows with `python "
        "benchmarks/bench_costs.py --only KEY ...` (KEY: "
        + ", ".join(f"`{k}`" for k in COMMANDS) + "); the other rows are kept.", 92),
        "",
        HEADER,
        "| --- | --- | --- | --- | --- | --- |",
        *(rows.get(k) or row(k, None, "", "") for k in COMMANDS),
        "",
        *textwrap.wrap(count or "Tests: not counted (every run of the script but `--smoke` "
                       "counts them).", 92),
        "",
        *textwrap.wrap(f"Processor of the last measurement: {cpu}.  Other measurements "
                       "(single ramps, solvers, the studies' cases): "
                       "[performance.md](performance.md).", 92),
        "",
    ]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="+", choices=list(COMMANDS), default=None,
                    help="measure these commands; keep the other rows of the table")
    ap.add_argument("--table", type=Path, default=TABLE,
                    help="the page to write (default docs/costs.md)")
    ap.add_argument("--smoke", action="store_true",
                    help="only 'list' and 'simulate --help', into a temporary table (a check "
                         "that the script runs, not a measurement)")
    args = ap.parse_args(argv)
    keys = list(SMOKE) if args.smoke else (args.only or list(COMMANDS))
    tmp = tempfile.TemporaryDirectory(prefix="bench-costs-")
    table = Path(tmp.name) / "costs.md" if args.smoke else args.table
    rows, count = old_rows(args.table), old_count(args.table)
    when = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")
    where = machine()
    print(f"machine: {where}; {cpu_model()}; cores {os.cpu_count()}")
    failed = 0
    for key in keys:
        command, place, _ = COMMANDS[key]
        cwd = ROOT if place == "checkout" else Path(tempfile.mkdtemp(dir=tmp.name))
        print(f"running {command} ...", flush=True)
        m = measure(command, cwd)
        rows[key] = row(key, m, when, where)
        failed += m["exit"] != 0
        print(f"{key:14s} CPU {m['cpu']:8.1f} s  wall {m['wall']:8.1f} s  load "
              f"{m['load'][0]:.2f} -> {m['load'][1]:.2f}  peak {m['peak_mb']:6.0f} MB  "
              f"exit {m['exit']}" + (f"  ({m['error']})" if m["exit"] else ""), flush=True)
        # each row as soon as it is measured: a run stopped later keeps it
        table.write_text(render(rows, count, cpu_model()))
    if not args.smoke:                              # a few CPU seconds
        run, collected = count_tests()
        count = (f"Tests: `python -m pytest` runs {run} tests; `python -m pytest -m slow` "
                 f"runs the other {collected - run} ({when}).")
        print(f"tests run {run}, collected {collected}")
    table.write_text(render(rows, count, cpu_model()))
    print(f"table: {table}")
    if args.smoke:
        print(table.read_text())
    tmp.cleanup()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

"""What ``skfem-dielectric check`` costs on large results files, and the refusal above the
bound.

Writes an ``nh-d-e.csv`` of exact rows (Eq. loading_gent, neo-Hookean, ``s = 0.5``) of
about each size asked for and checks it in a child process: rows, exit code, CPU seconds
(user + system of the child), wall seconds with the load average, and the child's peak
memory.  Then a (sparse) 50 MB file, above ``MAX_FILE_BYTES``: refused with one line and
exit code 2 before anything is read.

Usage::

    python benchmarks/bench_check_input.py [--mb 1 4 16]
    python benchmarks/bench_check_input.py --smoke      # 0.2 MB and the refusal
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import analytic as an
from validation.checker import MAX_FILE_BYTES

CHILD = ("import resource, sys\n"
         "from validation.cli import main\n"
         "rc = main(['check', sys.argv[1]])\n"
         "r = resource.getrusage(resource.RUSAGE_SELF)\n"
         "print(f'COST {r.ru_utime + r.ru_stime:.2f} {r.ru_maxrss / 1024:.0f}', "
         "file=sys.stderr)\n"
         "sys.exit(rc)\n")


def write_rows(path: Path, megabytes: float) -> int:
    """An exact ``nh-d-e`` file of about ``megabytes``; its number of rows."""
    D0 = np.linspace(0.0, 3.0, 2001)
    lam = an.equibiaxial_lam(D0, 0.5)
    block = "".join(f"nh-d-e,0.5,{d!r},{v!r}\n" for d, v in zip(D0.tolist(), lam.tolist()))
    n = max(1, int(megabytes * 1024**2 / len(block)))
    with open(path, "w") as fh:
        fh.write("case,s,D0,lam1\n")
        for _ in range(n):
            fh.write(block)
    return n * D0.size


def run(path: Path) -> tuple[int, float, float, float, str]:
    """``(exit code, CPU s, wall s, peak MB, last stderr line)`` of ``check path``."""
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-c", CHILD, str(path)], capture_output=True,
                       text=True)
    wall = time.perf_counter() - t0
    lines = r.stderr.strip().splitlines()
    cost = [ln for ln in lines if ln.startswith("COST ")]
    cpu, peak = (float(v) for v in cost[-1].split()[1:]) if cost else (float("nan"),) * 2
    other = [ln for ln in lines if not ln.startswith("COST ")]
    return r.returncode, cpu, wall, peak, (other[-1] if other else r.stdout.strip()
                                            .splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mb", type=float, nargs="+", default=[1.0, 4.0, 11.5])
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    sizes = [0.2] if a.smoke else a.mb
    print(f"bound MAX_FILE_BYTES = {MAX_FILE_BYTES / 1024**2:g} MB; {os.cpu_count()} CPUs")
    print(f"{'MB':>6} {'rows':>9} {'exit':>4} {'CPU s':>7} {'wall s':>7} {'peak MB':>8}  load "
          f"before -> after  last line")
    with tempfile.TemporaryDirectory() as tmp:
        for mb in sizes:
            f = Path(tmp) / "nh-d-e.csv"
            rows = write_rows(f, mb)
            load0 = os.getloadavg()[0]
            code, cpu, wall, peak, last = run(f)
            print(f"{f.stat().st_size / 1024**2:6.2f} {rows:9d} {code:4d} {cpu:7.2f} "
                  f"{wall:7.2f} {peak:8.0f}  {load0:.2f} -> {os.getloadavg()[0]:.2f}  "
                  f"{last[:90]}")
        big = Path(tmp) / "big.csv"
        with open(big, "wb") as fh:
            fh.write(b"case,s,D0,lam1\n")
            fh.truncate(50 * 1024**2)
        code, cpu, wall, peak, last = run(big)
        print(f"{50.0:6.2f} {'-':>9} {code:4d} {cpu:7.2f} {wall:7.2f} {peak:8.0f}  refused: "
              f"{last}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Benchmark: the Keplinger plate (alpha = 1, s = 2.993) through the charge ramp D0 = 0 -> 6.

Eighth model (symmetry planes x1 = 0, x2 = 0, x3 = 0), 40 x 20 in-plane Q2 elements, one Q2
layer through the half thickness; pre-load in 3 steps, then D0 = 1, 2, ..., 6.  For each
linear solver it prints DOFs, Newton iterations per step, assembly and solve seconds per
iteration, total wall time and peak memory.  Each solver runs in its own subprocess so that
the peak resident memory is its own.

Usage::

    python benchmarks/bench_fe_keplinger.py [--solver pardiso|superlu] [--n1 40 --n3 20]
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time


def run(solver: str, n1: int, n3: int, threads: int | None) -> dict:
    import numpy as np

    from skfem_dielectric.drivers import keplinger_plate

    t0 = time.perf_counter()
    res = keplinger_plate(1.0, D0=[1, 2, 3, 4, 5, 6], elements=(n1, 1, n3),
                          linear_solver=solver, threads=threads)
    wall = time.perf_counter() - t0
    prob = res.problem
    its = [st.iterations for st in res.steps]
    n_it = max(1, sum(its))
    asm = sum(st.assembly_seconds for st in res.steps)
    sol = sum(st.solve_seconds for st in res.steps)
    calls = prob.stats["assembly_calls"]
    return {
        "solver": solver, "dofs": int(prob.red.n), "elements": int(prob.nel),
        "converged": bool(res.converged), "reason": res.reason,
        "steps": [[float(v) for v in st.load] for st in res.steps],
        "iterations_per_step": its, "iterations": int(sum(its)),
        "assembly_calls": int(calls),
        "assembly_s_per_call": asm / max(1, calls),
        "assembly_s_per_iteration": asm / n_it, "solve_s_per_iteration": sol / n_it,
        "assembly_fraction": asm / max(1e-12, asm + sol),
        "wall_s": wall,
        "lam1_final": float(res.steps[-1]["lam1"]) if res.steps else float("nan"),
        "peak_rss_MB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
        "threads": prob.threads,
        "numpy": np.__version__,
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--solver", choices=["pardiso", "superlu"], default=None,
                    help="run one solver in this process (default: both, in subprocesses)")
    ap.add_argument("--n1", type=int, default=40)
    ap.add_argument("--n3", type=int, default=20)
    ap.add_argument("--threads", type=int, default=None, help="assembly threads")
    ap.add_argument("--json", action="store_true", help="print a JSON line (internal)")
    a = ap.parse_args(argv)
    if a.solver is not None:
        out = run(a.solver, a.n1, a.n3, a.threads)
        print(json.dumps(out) if a.json else out)
        return 0
    print("Keplinger plate, alpha = 1 (s = 2.993, g = 9.81), eighth model, "
          f"{a.n1} x {a.n3} in-plane Q2 elements, D0 = 0 -> 6")
    print("NOTE: 2-core machine shared with other jobs: timings are noisy.")
    for solver in ("pardiso", "superlu"):
        cmd = [sys.executable, __file__, "--solver", solver, "--n1", str(a.n1),
               "--n3", str(a.n3), "--json"]
        if a.threads is not None:
            cmd += ["--threads", str(a.threads)]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            print(f"{solver}: failed\n{p.stderr[-2000:]}")
            continue
        r = json.loads(p.stdout.strip().splitlines()[-1])
        print(f"\n[{solver}] DOFs {r['dofs']}  elements {r['elements']}  "
              f"converged {r['converged']} {r['reason']}")
        print(f"  Newton iterations per step {r['iterations_per_step']} "
              f"(total {r['iterations']}, assembly calls {r['assembly_calls']})")
        print(f"  assembly {r['assembly_s_per_iteration']:.3f} s/iteration "
              f"({r['assembly_s_per_call']:.3f} s/call), solve "
              f"{r['solve_s_per_iteration']:.3f} s/iteration, assembly share "
              f"{100 * r['assembly_fraction']:.0f} %")
        print(f"  total wall {r['wall_s']:.1f} s, peak RSS {r['peak_rss_MB']:.0f} MB, "
              f"lam1(D0=6) = {r['lam1_final']:.5f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

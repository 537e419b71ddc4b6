"""Benchmark: the Keplinger plate (alpha = 1, s = 2.993) through the charge ramp D0 = 0 -> 6.

Eighth model (symmetry planes x1 = 0, x2 = 0, x3 = 0), 40 x 20 in-plane Q2 elements, one Q2
layer through the half thickness; pre-load in 3 steps, then D0 = 1, 2, ..., 6.  For each
linear solver it prints DOFs, Newton iterations per step, assembly and solve seconds per
iteration (means over all calls, and medians), total wall time and peak memory.  Each solver
runs in its own subprocess so that the peak resident memory is its own.

On the 40 x 20 mesh the discrete plate loses stability near the clamp corner at D0 ~ 5.1
(an extra negative pivot of the tangent: the paper's breakdown, docs/fe.md), so D0 = 6 is
not reached.  With PARDISO the ramp stops at the first unstable step (its inertia is
known); ``--no-stop`` lets it spend its cut-backs trying to pass it instead.  SuperLU gives
no inertia and always runs until Newton fails.

Usage::

    python benchmarks/bench_fe_keplinger.py [--solver pardiso|superlu] [--n1 40 --n3 20]
                                            [--D0-max 6] [--no-stop]
    python benchmarks/bench_fe_keplinger.py --smoke    # SuperLU, 2 x 1, D0 = 1
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import json
import resource
import subprocess
import sys
import time
import warnings


def run(solver: str, n1: int, n3: int, threads: int | None, stop_unstable: bool,
        D0_max: int = 6) -> dict:
    import numpy as np

    from skfem_dielectric import PlateOptions, keplinger_plate
    from skfem_dielectric.gallery import KEPLINGER_SETTINGS

    t0 = time.perf_counter()
    wall_ok = [0.0]

    def on_step(step):
        if step.target_reached:
            wall_ok[0] = time.perf_counter() - t0

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = keplinger_plate(1.0, D0=list(range(1, D0_max + 1)), elements=(n1, 1, n3),
                              linear_solver=solver, options=PlateOptions(threads=threads),
                              on_step=on_step,
                              settings=replace(KEPLINGER_SETTINGS,
                                               stop_on_instability=stop_unstable))
    wall = time.perf_counter() - t0
    prob = res.problem
    its = [st.iterations for st in res.steps if st.target_reached]
    partial = [st for st in res.steps if not st.target_reached]
    asm_call = res.assembly_seconds / max(1, res.assembly_calls)
    sol_it = res.solve_seconds / max(1, res.iterations_total)
    asm_med = float(np.median(res.assembly_times)) if res.assembly_times else float("nan")
    sol_med = float(np.median(res.solve_times)) if res.solve_times else float("nan")
    return {
        "solver": solver, "dofs": int(prob.ndofs), "elements": int(prob.plate.mesh.nelements),
        "converged": bool(res.converged), "reason": res.reason,
        "failed_at": None if res.failed_at is None else [float(v) for v in res.failed_at],
        "D0_target_reached": max([float(st.load[1]) for st in res.steps if st.target_reached],
                                 default=float("nan")),
        "D0_furthest_substep": float(partial[0].load[1]) if partial else None,
        "iterations_per_step": its, "iterations_converged": int(sum(its)),
        "iterations_total": int(res.iterations_total),
        "assembly_calls": int(res.assembly_calls),
        "assembly_s_per_call": asm_call, "solve_s_per_iteration": sol_it,
        "assembly_fraction": asm_call / max(1e-12, asm_call + sol_it),
        "assembly_s_median": asm_med, "solve_s_median": sol_med,
        "assembly_fraction_median": asm_med / (asm_med + sol_med),
        "unstable_at": None if res.unstable_at is None else [float(v) for v in res.unstable_at],
        "wall_s": wall,
        "wall_to_last_target_s": wall_ok[0],
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
    ap.add_argument("--D0-max", type=int, default=6, help="last charge target (D0 = 1, 2, ...)")
    ap.add_argument("--threads", type=int, default=None, help="assembly threads")
    ap.add_argument("--json", action="store_true", help="print a JSON line (internal)")
    ap.add_argument("--no-stop", action="store_true",
                    help="do not stop at the first unstable step (PARDISO inertia); the ramp "
                         "then spends its cut-backs trying to pass the breakdown")
    ap.add_argument("--smoke", action="store_true",
                    help="the same code path with SuperLU only on 2 x 1 elements up to D0 = 1 "
                         "(a check that the script runs, not a measurement)")
    a = ap.parse_args(argv)
    solvers = ("pardiso", "superlu")
    if a.smoke:
        a.n1, a.n3, a.D0_max, solvers = 2, 1, 1, ("superlu",)
    if a.solver is not None:
        out = run(a.solver, a.n1, a.n3, a.threads, not a.no_stop, a.D0_max)
        print(json.dumps(out) if a.json else out)
        return 0
    print("Keplinger plate, alpha = 1 (s = 2.993, g = 9.81), eighth model, "
          f"{a.n1} x {a.n3} in-plane Q2 elements, D0 = 0 -> {a.D0_max}")
    print("NOTE: 2-core machine shared with other jobs: timings are noisy.")
    for solver in solvers:
        cmd = [sys.executable, __file__, "--solver", solver, "--n1", str(a.n1),
               "--n3", str(a.n3), "--D0-max", str(a.D0_max), "--json"]
        if a.threads is not None:
            cmd += ["--threads", str(a.threads)]
        if a.no_stop:
            cmd += ["--no-stop"]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            print(f"{solver}: failed\n{p.stderr[-2000:]}")
            continue
        r = json.loads(p.stdout.strip().splitlines()[-1])
        print(f"\n[{solver}] DOFs {r['dofs']}  elements {r['elements']}  "
              f"converged {r['converged']}  last D0 target reached {r['D0_target_reached']}"
              + (f", furthest converged sub-step D0 = {r['D0_furthest_substep']}"
                 if r["D0_furthest_substep"] is not None else ""))
        if r["unstable_at"] is not None:
            print(f"  stopped at the breakdown: tangent unstable (inertia) at D0 = "
                  f"{r['unstable_at'][1]:.4g}")
        elif not r["converged"]:
            print(f"  stopped: failed at load {r['failed_at']}: {r['reason'][:150]}")
        print(f"  Newton iterations per reached target {r['iterations_per_step']} "
              f"(sum {r['iterations_converged']}; all attempts {r['iterations_total']}, "
              f"assembly calls {r['assembly_calls']})")
        print(f"  assembly {r['assembly_s_per_call']:.3f} s/call, solve "
              f"{r['solve_s_per_iteration']:.3f} s/iteration -> assembly "
              f"{100 * r['assembly_fraction']:.0f} % of an iteration (means; medians "
              f"{r['assembly_s_median']:.3f} s and {r['solve_s_median']:.3f} s -> "
              f"{100 * r['assembly_fraction_median']:.0f} %)")
        print(f"  wall {r['wall_s']:.1f} s total, {r['wall_to_last_target_s']:.1f} s to the "
              f"last reached target; peak RSS {r['peak_rss_MB']:.0f} MB; "
              f"lam1 at the last step {r['lam1_final']:.5f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

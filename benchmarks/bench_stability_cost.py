"""Benchmark: what the stability analysis of every converged state adds to a Keplinger ramp.

The Keplinger plate (alpha = 1) on the quarter model (symmetry planes x1 = 0 and x3 = 0,
the full thickness: it can bend), 40 x 1 x 20 Q2 elements by default (one through the
thickness); pre-load in 3 steps, then D0 = 0.5, 1, ..., 5.  The same ramp runs three
times: plain; with ``StabilityMonitor(k=0)`` (the negative-eigenvalue count of every
converged state from the factorisation of its tangent, which then starts the next load
step as a chord matrix); with ``StabilityMonitor(k=5)`` (the count and the five lowest
eigenpairs).  It prints DOFs, Newton iterations, factorisations, assembly and solve
seconds, the wall and CPU time of each run and the extra share over the plain ramp, and
the peak memory.  ``--check`` also recomputes every state's count and lowest eigenvalue
independently (``tangent_stability`` on a fresh assembly, tolerance 1e-8) and prints the
largest differences.

Usage::

    python benchmarks/bench_stability_cost.py [--n1 40 --n2 1 --n3 20] [--solver pardiso|superlu]
                                              [--symmetry quarter] [--D0-max 5] [--check]
    python benchmarks/bench_stability_cost.py --smoke    # 2 x 1 x 1, D0 = 0.5, --check
"""

from __future__ import annotations

import argparse
import os
import resource
import time
import warnings

import numpy as np

from skfem_dielectric import StabilityMonitor, keplinger_plate
from skfem_dielectric.stability import tangent_stability


def run(a, monitor):
    """One ramp; returns (result, wall s, cpu s)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0, c0 = time.perf_counter(), time.process_time()
        res = keplinger_plate(1.0, D0=np.arange(0.5, a.D0_max + 1e-4, 0.5),
                              elements=(a.n1, a.n2, a.n3), symmetry=a.symmetry,
                              linear_solver=a.solver, state_analysis=monitor)
        return res, time.perf_counter() - t0, time.process_time() - c0


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n1", type=int, default=40)
    ap.add_argument("--n2", type=int, default=1)
    ap.add_argument("--n3", type=int, default=20)
    ap.add_argument("--symmetry", default="quarter")
    ap.add_argument("--solver", default="auto")
    ap.add_argument("--D0-max", type=float, default=5.0, help="last charge target (steps of 0.5)")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--smoke", action="store_true",
                    help="2 x 1 x 1 elements up to D0 = 0.5 with --check (a check that the "
                         "script runs, not a measurement)")
    a = ap.parse_args(argv)
    if a.smoke:
        a.n1, a.n2, a.n3, a.D0_max, a.check = 2, 1, 1, 0.5, True
    runs = {}
    for name, mon in (("plain", None), ("count", StabilityMonitor(k=0)),
                      ("count + 5 modes", StabilityMonitor(k=5))):
        res, wall, cpu = run(a, mon)
        runs[name] = (res, wall, cpu, mon)
        print(f"{name:16s} wall {wall:7.1f} s  cpu {cpu:7.1f} s  iterations "
              f"{res.iterations_total:4d}  factorisations {res.factorisations:4d}  assembly "
              f"{res.assembly_seconds:6.1f} s  solve {res.solve_seconds:6.1f} s  "
              f"converged {res.converged}", flush=True)
    res5, mon5 = runs["count + 5 modes"][0], runs["count + 5 modes"][3]
    pb = res5.problem
    print(f"Keplinger plate alpha = 1, {a.symmetry} model {a.n1} x {a.n2} x {a.n3}, "
          f"{pb.ndofs} DOFs, solver {a.solver}, load average {os.getloadavg()[0]:.1f}")
    print("  load (s, D0)        n_negative  five lowest eigenvalues")
    for step, (_, nn, _, ev) in zip(res5.steps, mon5.history):
        print(f"  ({step.load[0]:.4f}, {step.load[1]:4.2f})  {nn:10d}  "
              + " ".join(f"{v: .4e}" for v in ev))
    base = runs["plain"]
    for name in ("count", "count + 5 modes"):
        _, wall, cpu, _ = runs[name]
        print(f"{name}: +{100 * (wall / base[1] - 1):.0f} % wall, "
              f"+{100 * (cpu / base[2] - 1):.0f} % cpu over the plain ramp")
    if a.check:
        dn = de = 0.0
        for step, (_, nn, _, ev) in zip(res5.steps, mon5.history):
            K, _ = pb.assemble(step.x, step.load)
            ref = tangent_stability(pb, K, k=5, tol=1e-8)
            dn = max(dn, abs(ref.n_negative - nn))
            de = max(de, float(np.max(np.abs(ref.eigenvalues - ev)
                                      / np.maximum(np.abs(ref.eigenvalues), 1e-300))))
        print(f"check against tangent_stability: largest count difference {dn:.0f}, "
              f"largest relative eigenvalue difference {de:.1e}")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    print(f"peak resident memory {peak:.2f} GB")


if __name__ == "__main__":
    main()

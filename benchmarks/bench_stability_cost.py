"""Benchmark: what the stability analysis adds to a Keplinger ramp.

The Keplinger plate (alpha = 1) on the quarter model (symmetry planes x1 = 0 and x3 = 0,
the full thickness: it can bend), 40 x 1 x 20 Q2 elements by default (one through the
thickness); pre-load in 3 steps,
then D0 = 0.5, 1, ..., 5.  The ramp runs once; at every converged target the benchmark
times, on the same state, (a) the negative-eigenvalue count of the reduced stiffness
(assembly of the tangent at the state + one symmetric factorisation,
``tangent_stability(k=0)``) and (b) the count and the five lowest modes (``k=5``,
shift-invert Lanczos).  It prints DOFs, Newton iterations, the ramp's wall time per
target, the two stability times and their sums as a share of the ramp's time, and the
peak memory.  Optionally (``--classes``) it also times the count over every symmetry
class of the model (``class_stability``), which gives the full plate's count.

Usage::

    python benchmarks/bench_stability_cost.py [--n1 40 --n2 1 --n3 20] [--solver pardiso|superlu]
                                              [--symmetry quarter] [--classes]
"""

from __future__ import annotations

import argparse
import os
import resource
import time
import warnings

import numpy as np

from skfem_dielectric import class_stability, keplinger_plate, tangent_stability


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n1", type=int, default=40)
    ap.add_argument("--n2", type=int, default=1)
    ap.add_argument("--n3", type=int, default=20)
    ap.add_argument("--symmetry", default="quarter")
    ap.add_argument("--solver", default="auto")
    ap.add_argument("--classes", action="store_true")
    a = ap.parse_args(argv)
    n2 = a.n2
    targets = []
    stamps = [time.perf_counter()]
    stab = []

    def on_step(step):
        if not step.target_reached:
            return
        stamps.append(time.perf_counter())
        targets.append(step)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        res = keplinger_plate(1.0, D0=np.arange(0.5, 5.0001, 0.5), elements=(a.n1, n2, a.n3),
                              symmetry=a.symmetry, linear_solver=a.solver, on_step=on_step)
        ramp_wall = time.perf_counter() - t0
    print(f"ramp done in {ramp_wall:.1f} s; stability at each of {len(targets)} targets:",
          flush=True)
    pb = res.problem
    method = "pardiso" if a.solver in ("pardiso", "auto") else "superlu"
    for step in targets:
        t = time.perf_counter()
        K, _ = pb.assemble(step.x, step.load)
        st0 = tangent_stability(pb, K, k=0, method=method)
        t_count = time.perf_counter() - t
        t = time.perf_counter()
        K, _ = pb.assemble(step.x, step.load)
        st5 = tangent_stability(pb, K, k=5, method=method, tol=1e-6)
        t_modes = time.perf_counter() - t
        row = [step.load, step.iterations, st0.n_negative, st5.eigenvalues[0], t_count, t_modes]
        print(f"  target ({step.load[0]:.4f}, {step.load[1]:.2f}): count {t_count:.2f} s, "
              f"count + 5 modes {t_modes:.2f} s, n_negative {st0.n_negative}", flush=True)
        if a.classes:
            t = time.perf_counter()
            cs = class_stability(pb, step.x, step.load, k=0, method=method)
            row += [cs.n_negative, time.perf_counter() - t]
        stab.append(row)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    per = np.diff(stamps)
    print(f"Keplinger plate alpha = 1, {a.symmetry} model {a.n1} x {n2} x {a.n3}, "
          f"{pb.ndofs} DOFs, solver {method}, load average {os.getloadavg()[0]:.1f}")
    hdr = "  load (s, D0)          its  n_neg  lowest eig    ramp s   count s   5 modes s"
    print(hdr + ("   classes n_neg  s" if a.classes else ""))
    for (ld, its, nn, ev, tc, tm, *cl), tr in zip(stab, per):
        extra = f"   {cl[0]:5d}  {cl[1]:7.2f}" if cl else ""
        print(f"  ({ld[0]:.4f}, {ld[1]:5.2f})  {its:4d}  {nn:5d}  {ev: .4e}  {tr:8.2f}  "
              f"{tc:8.2f}  {tm:9.2f}{extra}")
    tc = sum(r[4] for r in stab)
    tm = sum(r[5] for r in stab)
    print(f"ramp {ramp_wall:.1f} s ({res.iterations_total} Newton iterations, "
          f"{len(targets)} targets); count at every target {tc:.1f} s = "
          f"{100 * tc / ramp_wall:.0f} %; count + 5 lowest modes {tm:.1f} s = "
          f"{100 * tm / ramp_wall:.0f} %" + (
              f"; every class {sum(r[7] for r in stab):.1f} s = "
              f"{100 * sum(r[7] for r in stab) / ramp_wall:.0f} %" if a.classes else ""))
    print(f"peak resident memory {peak:.2f} GB")


if __name__ == "__main__":
    main()

"""Benchmark: the fill and memory of PARDISO's factors of the clamp-zone plates, per ordering.

The plate of a clamp-zone unit (:func:`validation.clamp_zone.units.unit_problem`: the
eighth Keplinger plate graded towards the clamp, grad-div 10, Q2/Q1/Q2) is assembled at
its reference state under the dead load of ``--alpha`` (the pattern of every tangent of
its ramp) and its upper triangle handed to the package's symmetric PARDISO
(:class:`~skfem_dielectric.linalg.linear.PardisoSolver`) with each fill-reducing ordering
of ``--orderings``.  Per mesh and ordering it reports, from PARDISO itself: the entries of
the factors (``iparm(18)``), the peak memory of the analysis (``iparm(15)``), the
permanent memory (``iparm(16)``) and that of the factorisation and solve (``iparm(17)``),
their sum (what a kept factorisation holds), and the seconds of the analysis (phase 11)
and, unless ``--analysis-only``, of one factorisation (phase 22) and one solve (33), with
the process's peak resident memory (``VmHWM``).  Each mesh and ordering runs in its own
subprocess, so that its peak is its own.

Usage::

    python benchmarks/bench_factor_fill.py --meshes 30x1x24 50x2x36
    python benchmarks/bench_factor_fill.py --meshes 70x4x36 --analysis-only
    python benchmarks/bench_factor_fill.py --smoke          # 4x1x2, both orderings

Needs pypardiso (``pip install ".[fast]"``).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time

ORDERINGS = ("minimum-degree", "metis")


def _vmhwm_gb() -> float:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM"):
                return int(line.split()[1]) / 1024**2
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2


def measure(mesh: str, ordering: str, alpha: float, grading: float,
            analysis_only: bool) -> dict:
    """One mesh, one ordering, in this process."""
    import numpy as np

    from skfem_dielectric.linalg.linear import PardisoSolver
    from validation.clamp_zone.units import unit_problem
    from validation.data.key import parse_mesh

    t0 = time.process_time()
    pb, s = unit_problem(alpha, parse_mesh(mesh), grading=grading)
    K, _ = pb.assemble_upper(pb.initial_state(), np.array([s, 0.0]))
    t_assemble = time.process_time() - t0
    solver = PardisoSolver(ordering=ordering)
    A = solver._matrix(K)
    solver._ps.set_iparm(18, -1)                   # report the entries of the factors
    b = np.ones(A.shape[0])
    out = {"mesh": mesh, "ordering": ordering, "dofs": int(A.shape[0]),
           "matrix_entries": int(A.nnz), "assemble_cpu_s": round(t_assemble, 2)}
    t = time.process_time()
    solver._call(11, A, b)
    out["analysis_cpu_s"] = round(time.process_time() - t, 2)
    ip = solver._ps.iparm
    out.update(factor_entries=int(ip[17]), analysis_peak_GB=round(ip[14] / 1024**2, 3),
               permanent_GB=round(ip[15] / 1024**2, 3),
               factorisation_GB=round(ip[16] / 1024**2, 3))
    if not analysis_only:
        t = time.process_time()
        solver._call(22, A, b)
        out["factorise_cpu_s"] = round(time.process_time() - t, 2)
        ip = solver._ps.iparm
        out.update(factor_entries=int(ip[17]), factorisation_GB=round(ip[16] / 1024**2, 3),
                   negative=int(ip[22]))
        t = time.process_time()
        solver._call(33, A, b)
        out["solve_cpu_s"] = round(time.process_time() - t, 2)
    out["kept_GB"] = round(out["permanent_GB"] + out["factorisation_GB"], 3)
    out["VmHWM_GB"] = round(_vmhwm_gb(), 3)
    solver.discard()
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--meshes", nargs="+", default=["30x1x24", "50x2x36"])
    ap.add_argument("--orderings", nargs="+", default=list(ORDERINGS), choices=ORDERINGS)
    ap.add_argument("--alpha", type=float, default=1.5)
    ap.add_argument("--grading", type=float, default=0.1)
    ap.add_argument("--analysis-only", action="store_true")
    ap.add_argument("--smoke", action="store_true", help="4x1x2, both orderings")
    ap.add_argument("--one", help=argparse.SUPPRESS)      # MESH,ORDERING in this process
    a = ap.parse_args(argv)
    if a.one:
        mesh, ordering = a.one.split(",")
        print(json.dumps(measure(mesh, ordering, a.alpha, a.grading, a.analysis_only)))
        return 0
    if a.smoke:
        a.meshes = ["4x1x2"]
    load = os.getloadavg()[0]
    print(f"# alpha {a.alpha:g}, grading {a.grading:g}, load average {load:.2f}, "
          f"{time.strftime('%Y-%m-%d')}")
    cols = ("mesh", "ordering", "dofs", "factor_entries", "analysis_peak_GB", "kept_GB",
            "analysis_cpu_s", "factorise_cpu_s", "solve_cpu_s", "VmHWM_GB")
    print(",".join(cols))
    for mesh in a.meshes:
        for ordering in a.orderings:
            cmd = [sys.executable, __file__, "--one", f"{mesh},{ordering}",
                   "--alpha", str(a.alpha), "--grading", str(a.grading)]
            cmd += ["--analysis-only"] if a.analysis_only else []
            run = subprocess.run(cmd, capture_output=True, text=True,
                                 env={**os.environ, "OMP_NUM_THREADS": "1",
                                      "MKL_NUM_THREADS": "1"})
            if run.returncode:
                print(f"{mesh},{ordering},failed: {run.stderr.strip().splitlines()[-1]}")
                continue
            r = json.loads(run.stdout.strip().splitlines()[-1])
            print(",".join(str(r.get(c, "")) for c in cols), flush=True)
    print(f"# load average after {os.getloadavg()[0]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

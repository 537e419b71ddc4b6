"""Benchmark: membrane model of the Keplinger plate, charge ramp D0 = 0 -> 6.

Quarter plate, 40 x 20 biquadratic elements, alpha = 1 (s = 2.993), neo-Hookean.
Prints DOFs, Newton iterations per step, assembly and solve seconds, wall time.
Target: at most 5 s wall.

Usage::

    python benchmarks/bench_fe_membrane.py [superlu|pardiso|auto]    # default superlu
    python benchmarks/bench_fe_membrane.py --smoke    # 4 x 2, D0 = 0, 1
"""

import argparse
import time

import numpy as np

from skfem_dielectric import MembranePlate, NeoHookeanDielectric, keplinger_s, membrane_mesh
from skfem_dielectric.gallery import membrane_ramp


def main(solver: str = "superlu", n1: int = 40, n3: int = 20, D0_max: float = 6.0) -> None:
    """Ramp the quarter membrane on ``n1 x n3`` elements to ``D0_max`` and print the table."""
    t0 = time.perf_counter()
    pb = MembranePlate(membrane_mesh(100.0, 1.0, 50.0, n1, n3), NeoHookeanDielectric(1.0, 1.0),
                       loading="uniaxial")
    t_setup = time.perf_counter() - t0
    s = keplinger_s(1.0, g=9.81)
    D0 = np.arange(0.0, D0_max + 0.01, 1.0)
    res = membrane_ramp(pb, s, D0, linear_solver=solver)
    wall = time.perf_counter() - t0
    print(f"membrane Keplinger plate, solver={solver}, s={s:.4f}, {n1} x {n3} Q2 quarter")
    print(f"DOFs (reduced): {pb.ndofs}, setup {t_setup:.2f} s")
    print(f"{'D0':>5} {'lam1':>9} {'min_P33':>9} {'iters':>5} {'asm s':>7} {'solve s':>7}")
    for st in res.steps:
        print(f"{st.load[1]:5.2f} {st['lam1']:9.5f} {st['min_P33']:9.4f} {st.iterations:5d} "
              f"{st.assembly_seconds:7.3f} {st.solve_seconds:7.3f}")
    it = sum(st.iterations for st in res.steps)
    asm = sum(st.assembly_seconds for st in res.steps)
    sol = sum(st.solve_seconds for st in res.steps)
    print(f"total: {it} Newton iterations, assembly {asm:.2f} s, solve {sol:.2f} s, "
          f"wall {wall:.2f} s (target <= 5 s), converged={res.converged}")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("solver", nargs="?", default="superlu", choices=["superlu", "pardiso", "auto"])
    ap.add_argument("--smoke", action="store_true",
                    help="the same code path on 4 x 2 elements with D0 = 0, 1 (a check that "
                         "the script runs, not a measurement)")
    a = ap.parse_args()
    if a.smoke:
        main(a.solver, n1=4, n3=2, D0_max=1.0)
    else:
        main(a.solver)

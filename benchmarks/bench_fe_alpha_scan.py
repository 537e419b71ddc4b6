"""Keplinger plate for every weight fraction alpha: deviation from the uni-axial curve,
min P33 on the centre line / near the clamp, stability verdict, and where the ramp breaks.

Usage::

    python benchmarks/bench_fe_alpha_scan.py [--n1 20 --n3 10] [--dD0 0.5] [--alpha 1.0 ...]
    python benchmarks/bench_fe_alpha_scan.py --smoke    # alpha = 1, 2 x 1 x 1, D0 = 1

Prints one table per alpha.  Reference: Eq. (DEuniax), ``lam1^2 (lam1 - s) =
sqrt(1 + D0^2)`` (largest real root), and ``lam1 - lam1^-2 = s`` before charging.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings

import numpy as np


def lam1_uniaxial(D0: float, s: float) -> float:
    r = np.roots([1.0, -s, 0.0, -np.sqrt(1.0 + D0**2)])
    return float(max(r[np.abs(r.imag) < 1e-10].real))


def main(argv=None) -> int:
    from skfem_dielectric import keplinger_plate, keplinger_s

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n1", type=int, default=20)
    ap.add_argument("--n3", type=int, default=10)
    ap.add_argument("--dD0", type=float, default=0.5)
    ap.add_argument("--D0max", type=float, default=6.0)
    ap.add_argument("--alpha", type=float, nargs="*", default=[0.05, 0.3, 0.7, 1.0, 1.5])
    ap.add_argument("--solver", default="auto")
    ap.add_argument("--smoke", action="store_true",
                    help="alpha = 1 on 2 x 1 x 1 elements up to D0 = 1 (a check that the "
                         "script runs, not a measurement)")
    a = ap.parse_args(argv)
    if a.smoke:
        a.n1, a.n3, a.dD0, a.D0max, a.alpha = 2, 1, 1.0, 1.0, [1.0]
    D0 = np.arange(a.dD0, a.D0max + 1e-9, a.dD0)
    for alpha in a.alpha:
        s = keplinger_s(alpha, g=9.81)
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = keplinger_plate(alpha, D0=D0, elements=(a.n1, 1, a.n3),
                                  linear_solver=a.solver)
        print(f"\nalpha = {alpha}  s = {s:.4f}  mesh {a.n1} x 1 x {a.n3}  "
              f"({time.perf_counter() - t0:.0f} s)  converged = {res.converged}")
        if not res.converged:
            print(f"  breakdown: {res.reason[:160]}  failed at load {res.failed_at}")
        print("  s_step     D0    lam1_fe  lam1_hom    dev%   lam3_fe  min_P33 (x1)   "
              "min_P33_clamp  stable  its")
        for st in res.steps:
            s_step, d = float(st.load[0]), float(st.load[1])   # pre-load steps: s < s_final
            ref = lam1_uniaxial(d, s_step)
            print(f"  {s_step:6.3f}  {d:5.2f}  {st['lam1']:8.5f}  {ref:8.5f}  {100 * (st['lam1'] / ref - 1):+6.3f}"
                  f"  {st['lam3']:8.5f}  {st['min_P33']:+8.4f} ({st['x1_min_P33']:4.1f})"
                  f"  {st['min_P33_clamp']:+8.4f}     {str(st['stable']):5s}  {st.iterations}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Benchmark: finite-thickness wrinkling dispersion curves D0_crit(kh).

A dispersion curve is the critical D0 of an equi-biaxially stretched plate at
200 log-spaced values of kh in [1e-2, 1e2] (``analytic.critical_D0``: 64-point
scan in D0, then Illinois regula falsi to ~1e-14 relative, fully vectorised).
Target: under 1 s per curve. Prints the best of 3 wall times per
curve, the number of roots found and the end values against the thin/thick
limits.

Usage::

    python benchmarks/bench_wrinkling.py [--n 200] [--repeat 3]
    python benchmarks/bench_wrinkling.py --smoke    # 20 values of kh, once
"""

import argparse
import time

import numpy as np

from analytic import Gent, NeoHookean, critical_D0, thick_limit_D0, thin_limit_D0


def best_of(fun, repeat=3):
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200, help="values of kh per curve")
    ap.add_argument("--repeat", type=int, default=3, help="repetitions, best is kept")
    ap.add_argument("--smoke", action="store_true",
                    help="the same code path on 20 values of kh, one repetition (a check "
                         "that the script runs, not a measurement)")
    a = ap.parse_args(argv)
    if a.smoke:
        a.n, a.repeat = 20, 1
    kh = np.logspace(-2, 2, a.n)
    lam = 1.5
    print(f"dispersion curves: lam = {lam}, {kh.size} values of kh in [1e-2, 1e2]")
    print(f"{'model':>12} {'mode':>14} {'control':>8} {'seconds':>8} {'roots':>6} "
          f"{'D0(kh=0.01)':>12} {'thin':>9} {'D0(kh=100)':>11} {'thick':>9}")
    worst = 0.0
    for model in (NeoHookean(), Gent(Jm=97.2)):
        for mode in ("antisymmetric", "symmetric"):
            for control in ("charge", "voltage"):
                t, D = best_of(lambda: critical_D0(lam, kh, model, mode=mode, control=control),
                               a.repeat)
                worst = max(worst, t)
                print(f"{model.name:>12} {mode:>14} {control:>8} {t:8.3f} {np.isfinite(D).sum():6d} "
                      f"{D[0]:12.6f} {thin_limit_D0(lam, model):9.5f} {D[-1]:11.6f} "
                      f"{thick_limit_D0(lam, model, control=control):9.5f}")
    print(f"slowest curve: {worst:.3f} s (target < 1 s): {'OK' if worst < 1.0 else 'TOO SLOW'}")


if __name__ == "__main__":
    main()

"""Time 10^6 points of every analytic loading curve (target: each under 1 s).

Prints, per curve and model, the best wall time of R repetitions for N points, and
whether it is under 1 s per 10^6 points. Timings are machine dependent and noisy on a
loaded machine.

Usage::

    python benchmarks/bench_analytic.py [--n N] [--repeat R]
    python benchmarks/bench_analytic.py --smoke    # 1000 points, one repetition
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import analytic as an


def cases(n: int):
    lam = np.linspace(1.35, 4.0, n)  # s = 1 equi-biaxial branch starts at 1.285
    lam1 = np.linspace(1.5, 6.0, n)  # s = 1 uni-axial branch starts at 1.466
    D0 = np.linspace(0.0, 5.0, n)
    gent = an.Gent(97.2)
    for model, name in ((None, "neo-Hookean"), (gent, "Gent(97.2)")):
        yield f"equibiaxial_D0(lam; s=1)    {name}", lambda m=model: an.equibiaxial_D0(lam, 1.0, m)
        yield f"equibiaxial_E0(lam; s=1)    {name}", lambda m=model: an.equibiaxial_E0(lam, 1.0, m)
        yield f"equibiaxial_lam(D0; s=1)    {name}", lambda m=model: an.equibiaxial_lam(D0, 1.0, m)
        yield f"uniaxial_D0(lam1; s=1)      {name}", lambda m=model: an.uniaxial_D0(lam1, 1.0, m)
        yield f"uniaxial_E0(lam1; s=1)      {name}", lambda m=model: an.uniaxial_E0(lam1, 1.0, m)
        yield f"uniaxial_lam3(lam1; s=1)    {name}", lambda m=model: an.uniaxial_lam3(lam1, 1.0, m)
        yield f"uniaxial_lam1(D0; s=1)      {name}", lambda m=model: an.uniaxial_lam1(D0, 1.0, m)
        yield f"voltage_limit_D0(lam)       {name}", lambda m=model: an.voltage_limit_D0(lam, m)



def locus_cases(n: int):
    """The uni-axial det H* = 0 locus (a figure curve, not a loading curve): for non
    neo-Hookean models it is found by a ~60-point scan per point plus regula falsi."""
    lam1 = np.linspace(1.5, 6.0, n)
    for model, name in ((None, "neo-Hookean"), (an.Gent(97.2), "Gent(97.2)")):
        yield f"uniaxial_voltage_limit_D0   {name}", lambda m=model: an.uniaxial_voltage_limit_D0(lam1, m)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=10**6, help="points per curve (default 10^6)")
    parser.add_argument("--repeat", type=int, default=3, help="repetitions, best is kept")
    parser.add_argument("--smoke", action="store_true",
                        help="the same code path on 1000 points, one repetition (a check that "
                             "the script runs, not a measurement)")
    args = parser.parse_args(argv)
    if args.smoke:
        args.n, args.repeat = 1000, 1
    print(f"{'curve':45s} {'points':>9s} {'best s':>8s}  per 1e6 pts")
    runs = [(args.n, c) for c in cases(args.n)] + [(args.n // 10, c) for c in locus_cases(args.n // 10)]
    for n, (label, fun) in runs:
        best = np.inf
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            out = fun()
            best = min(best, time.perf_counter() - t0)
        per = best * 1e6 / n
        finite = np.count_nonzero(np.isfinite(np.asarray(out)))
        flag = "ok (< 1 s)" if per < 1.0 else "SLOW (>= 1 s)"
        print(f"{label:45s} {n:9d} {best:8.3f}  {per:6.3f} s  {flag}  [{finite} finite]")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Where and why Newton stops on the clamped Keplinger plate: the clamp/free-edge corner.

Usage::

    python benchmarks/bench_fe_corner_failure.py [--alpha 0.05] [--n1 40 --n3 20]
        [--grading 1] [--D0 1 1.5 2 ...] [--cutbacks 4 --max-iter 12] [--eig-from 1.5]
        [--solver pardiso|superlu|auto]
    python benchmarks/bench_fe_corner_failure.py --smoke    # 2 x 1 x 1, default solver

Ramps the eighth model (PARDISO by default) and prints per converged step: the centre stretch, the
inertia verdict, ``min det F`` and the ``S33/mu`` of largest magnitude at the quadrature
points with their positions (``skfem_dielectric.models.plate.failure.plate_failure_cause``), and
from ``--eig-from`` on the lowest eigenvalues of the reduced stiffness with, per mode, the
fraction of its displacement norm within two thicknesses of the clamp/free-edge corner
(``c``) and its overlap with the charge load vector (``f``, ``|w.q|/(|w||q|)``: a limit
point has a vanishing eigenvalue whose mode is not orthogonal to the load).  If the ramp
stops, the failed Newton attempt is replayed from the last converged state with its
residual history and the ``det F > 0`` step limits (``PlateProblem.max_step``) it met.

``--smoke`` runs the same code path on 2 x 1 x 1 elements with the default solver: one
charge step with the eigenvalues, then a jump to ``D0 = 8`` without cut-backs that Newton
cannot make, so that the replay runs too (a check that the script runs, not a
measurement).
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np


def main(argv=None) -> int:
    from skfem_dielectric import keplinger_s
    from skfem_dielectric.gallery.drivers import keplinger_problem, plate_admissible, run_ramp
    from skfem_dielectric.gallery.loads import preload_then_charge
    from skfem_dielectric.linalg.linear import get_linear_solver
    from skfem_dielectric.models.plate.failure import plate_failure_cause
    from skfem_dielectric.solvers.newton import NewtonSettings, newton
    from skfem_dielectric.solvers.ramp import RampSettings
    from skfem_dielectric.stability.analysis import tangent_stability

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--alpha", type=float, default=0.05)
    ap.add_argument("--n1", type=int, default=40)
    ap.add_argument("--n3", type=int, default=20)
    ap.add_argument("--grading", type=float, default=1.0)
    ap.add_argument("--D0", type=float, nargs="*",
                    default=[1.0, 1.5, 2.0, 2.0625, 2.125, 2.1875, 2.25, 2.5, 3.0])
    ap.add_argument("--cutbacks", type=int, default=4)
    ap.add_argument("--max-iter", type=int, default=12)
    ap.add_argument("--eig-from", type=float, default=np.inf)
    ap.add_argument("--k", type=int, default=3)
    ap.add_argument("--solver", choices=["pardiso", "superlu", "auto"], default="pardiso")
    ap.add_argument("--smoke", action="store_true",
                    help="2 x 1 x 1 elements, D0 = 1 (with the eigenvalues) and 8 (fails, "
                         "replayed), default solver (a check that the script runs, not a "
                         "measurement)")
    a = ap.parse_args(argv)
    if a.smoke:
        a.n1, a.n3, a.D0, a.cutbacks, a.max_iter = 2, 1, [1.0, 8.0], 0, 6
        a.eig_from, a.solver = 1.0, "auto"
    t0 = time.perf_counter()
    prob = keplinger_problem(elements=(a.n1, 1, a.n3), grading=a.grading)
    pm = prob.plate
    X = prob.b2.doflocs.T
    near = np.hypot(np.abs(X[:, 0]) - pm.L1 / 2, np.abs(X[:, 2]) - pm.L3 / 2) < 2 * pm.H

    def corner_fraction(w):
        u = prob.red.expand(w, np.zeros(prob.n_full))[:prob.n_u].reshape(-1, 3)
        e = (u * u).sum(axis=1)
        return float(e[near].sum() / e.sum())

    def report(st):
        c = plate_failure_cause(prob, st.x, st.load)
        line = (f"D0 = {st.load[1]:.5f}  it {st.iterations:2d}  lam1 {st['lam1']:.6f}  "
                f"stable {st['stable']}  min J {c['min_J']:.4f} at "
                f"{np.round(c['min_J_at'], 2)}  S33/mu {c['S33']:.3f} at "
                f"{np.round(c['S33_at'], 2)}")
        if st.load[1] >= a.eig_from:
            K, _ = prob.assemble(st.x, st.load)
            stb = tangent_stability(prob, K, k=a.k)
            q = prob.load_vector(st.x, st.load)[:, 1]
            overlap = [abs(w @ q) / (np.linalg.norm(q) * np.linalg.norm(w)) for w in stb.modes.T]
            line += f"  n_neg {stb.n_negative}  eig " + ", ".join(
                f"{v:.3e} (c {corner_fraction(w):.2f}, f {o:.1e})"
                for v, w, o in zip(stb.eigenvalues, stb.modes.T, overlap))
        print(line + f"  [{time.perf_counter() - t0:.0f} s]", flush=True)

    s = keplinger_s(a.alpha, g=9.81)
    print(f"alpha = {a.alpha} (s = {s:.4f}), eighth model {a.n1} x 1 x {a.n3}, "
          f"grading {a.grading}, cut-backs {a.cutbacks}, max_iter {a.max_iter}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = run_ramp(prob, preload_then_charge(s, a.D0, 3), linear_solver=a.solver,
                       on_step=lambda st: st.load[1] > 0 and report(st),
                       settings=RampSettings(atol=0.0, rtol=1e-9, max_cutbacks=a.cutbacks,
                                                    max_iter=a.max_iter))
    print("converged:", res.converged, "| reason:", res.reason)
    if res.failed_at is not None:
        lims = []

        def limit(xx, dd):
            lims.append(prob.max_step(xx, dd, res.failed_at))
            return lims[-1]

        nr = newton(lambda xx: prob.assemble(xx, res.failed_at), res.steps[-1].x,
                    residual=lambda xx: prob.residual(xx, res.failed_at),
                    linear_solver=get_linear_solver(a.solver),
                    settings=NewtonSettings(atol=0.0, rtol=1e-9, max_iter=a.max_iter),
                    scale=prob.residual_scale(res.failed_at),
                    step_limit=limit,
                    admissible=lambda xx: plate_admissible(prob, xx, res.failed_at))
        print(f"replay at D0 = {res.failed_at[1]:.5f}: {nr.reason or 'converged'}")
        print("  ||r||:", " ".join(f"{v:.2e}" for v in nr.residual_norms))
        print("  step limits:", " ".join(f"{v:.3g}" for v in lims))
        c = plate_failure_cause(prob, nr.x, res.failed_at)
        print(f"  last iterate: min J {c['min_J']:.4f}, S33/mu {c['S33']:.3f} at "
              f"{np.round(c['S33_at'], 2)}")
    print(f"wall {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

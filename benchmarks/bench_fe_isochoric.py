"""Centre stretch of the Keplinger plate with the volumetric treatments side by side.

Usage::

    python benchmarks/bench_fe_isochoric.py [--n1 20 --n3 10] [--kappa 1000] [--alpha 1.0]
        [--D0 0 1 2 3] [--solver pardiso]
    python benchmarks/bench_fe_isochoric.py --smoke    # 2 x 1 x 1, D0 = 0, 1

Prints ``lam1`` at the plate centre for the exactly incompressible mixed form (the
reference) and, at the finite ``kappa``, the isochoric (COMSOL) energy
``W(J^(-2/3) I1) + kappa (J-1)^2/2`` in the mixed form (``mixed-isochoric``) and
displacement-only (``isochoric``), the mixed form (``p (J-1) - p^2/(2 kappa)`` on
``W(I1) - mu ln J``) and the penalty ``W(I1) - mu ln J + kappa (J-1)^2/2``, and their
relative shifts from the reference.  The
last columns are the same shifts of the homogeneous uni-axial state (free x3 faces,
nominal stress ``s`` on x1, the charge ``D0``), solved with scipy from the energy per
reference volume ``W + U(J) + D0^2 lam2^2/(2J) - s lam1``.
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import warnings

import numpy as np
from scipy.optimize import brentq, root


def homogeneous(s: float, D0: float, kappa: float, form: str) -> float:
    """``lam1`` of the homogeneous uni-axial neo-Hookean state (mu = eps = 1)."""
    lam_inc = brentq(lambda L: L**2 * (L - s) - np.sqrt(1.0 + D0**2), 1.0, 20.0, xtol=1e-15)
    if form == "incompressible":
        return lam_inc

    def eqs(y):
        lam = np.exp(y)                       # log-stretches keep the iterates positive
        J, I1 = lam.prod(), (lam * lam).sum()
        f = D0**2 * lam[1] / (2.0 * lam[0] * lam[2])
        d_el = np.array([-f / lam[0], f / lam[1], -f / lam[2]])
        vol = kappa * (J - 1.0) * J / lam
        if form == "isochoric":
            j23 = J ** (-2.0 / 3.0)
            d_w = 0.5 * j23 * (2.0 * lam - (2.0 / 3.0) * I1 / lam)
        else:                                  # mu/2 (I1 - 3) - mu ln J
            d_w = lam - 1.0 / lam
        return (d_w + vol + d_el - np.array([s, 0.0, 0.0])) * lam

    lam3 = np.sqrt(np.sqrt(1.0 + D0**2) / lam_inc)
    sol = root(eqs, np.log([lam_inc, 1.0 / (lam_inc * lam3), lam3]), tol=1e-14)
    return float(np.exp(sol.x[0]))


def main(argv=None) -> int:
    from skfem_dielectric import PlateOptions, keplinger_plate, keplinger_s
    from skfem_dielectric.gallery import KEPLINGER_SETTINGS

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n1", type=int, default=20)
    ap.add_argument("--n3", type=int, default=10)
    ap.add_argument("--kappa", type=float, default=1000.0)
    ap.add_argument("--alpha", type=float, default=1.0)
    ap.add_argument("--D0", type=float, nargs="*", default=[0.0, 1.0, 2.0, 3.0])
    ap.add_argument("--solver", default="auto")
    ap.add_argument("--forms", nargs="*",
                    default=["mixed-isochoric", "isochoric", "mixed", "penalty"],
                    help="formulations with the finite kappa (the reference, the mixed form "
                         "with kappa = inf, is always run first)")
    ap.add_argument("--smoke", action="store_true",
                    help="every form on 2 x 1 x 1 elements at D0 = 0, 1 (a check that the "
                         "script runs, not a measurement)")
    a = ap.parse_args(argv)
    if a.smoke:
        a.n1, a.n3, a.D0 = 2, 1, [0.0, 1.0]
    s = keplinger_s(a.alpha, g=9.81)
    forms = [("mixed", float("inf"))] + [(f, a.kappa) for f in a.forms]
    lam = {}
    for form, kappa in forms:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            # a finite kappa needs more Newton iterations than the mixed form (the
            # volumetric stiffness dominates the tangent): the ramp's general budget
            res = keplinger_plate(a.alpha, a.D0, elements=(a.n1, 1, a.n3),
                                  options=PlateOptions(formulation=form, kappa=kappa),
                                  linear_solver=a.solver, preload_steps=6,
                                  settings=replace(KEPLINGER_SETTINGS, max_iter=30,
                                                   max_cutbacks=6))
        got = {round(float(st.load[1]), 12): st["lam1"] for st in res.steps
               if st.target_reached and st.load[0] == s}
        lam[form, kappa] = got
        print(f"# {form} kappa={kappa:g}: converged={res.converged} {res.reason}; lam1 "
              + " ".join(f"{v:.7f}" for v in got.values()), flush=True)
    print(f"alpha = {a.alpha} (s = {s:.4f}), mesh {a.n1} x 1 x {a.n3} (eighth), "
          f"kappa = {a.kappa:g} mu")
    print("D0     lam1_inc   " + "  ".join(f"shift({f})" for f, _ in forms[1:])
          + "  | homogeneous: penalty  isochoric")
    ref = lam["mixed", float("inf")]
    for D0 in a.D0:
        d = round(float(D0), 12)
        if d not in ref:
            continue
        sh = [lam[f, k].get(d, np.nan) / ref[d] - 1 for f, k in forms[1:]]
        h0 = homogeneous(s, D0, a.kappa, "incompressible")
        hp = homogeneous(s, D0, a.kappa, "penalty") / h0 - 1
        hi = homogeneous(s, D0, a.kappa, "isochoric") / h0 - 1
        print(f"{D0:<6g} {ref[d]:.6f}  " + "  ".join(f"{v:+.2e}" for v in sh)
              + f"  | {hp:+.2e}  {hi:+.2e}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

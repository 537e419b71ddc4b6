"""The clamp-zone wrinkle of the Keplinger plate against the homogeneous theory of its zone.

For each weight fraction ``alpha`` and eighth-model mesh: the study's plate (grad-div 10,
neo-Hookean, ``validation.studies.buckling``) is ramped in ``D0`` (steps of 0.25 and the
study's buckling load ``D0_b``, docs/validation.md); at ``D0_b`` the lowest physical mode of
the whole plate is computed, its energy centroid (mid-plane) and its number of half-waves
across the width.  At that reference point the local homogeneous state ``(lam1, lam3, D0)``
of every ramp state is handed to the closed forms (``validation.clamp_zone.local_theory``):
the perpendicular thin limit (Eq. thin-uni-axial, ``(x3, x2)`` plane), the flexural
``D0_c(kh)`` at the FE mode's ``kh`` and the thick (surface) limit (Eq. thick-plate23),
and the ramp ``D0`` at which each first fires is printed beside ``D0_b``.

Usage::

    python benchmarks/bench_clamp_wrinkle.py [--alpha 0.3 0.7 1 1.5] [--mesh 10x1x5 14x1x7]
    python benchmarks/bench_clamp_wrinkle.py --smoke    # alpha = 1 on 4 x 1 x 2

Prints two lines (the centroid and the most compressive clamp-side point) per alpha x mesh
and the CPU seconds of each.  ``--smoke`` runs the same code path for ``alpha = 1`` on
the 4 x 1 x 2 eighth model in steps of 0.5 up to the ``D0_b`` of the 10 x 1 x 5 mesh (a
check that the script runs; its numbers are not the study's).
"""

from __future__ import annotations

import argparse
import math
import time
import warnings

import numpy as np

#: D0_b of the buckling study (docs/validation.md, "The study"), per alpha and mesh
D0_B = {(0.3, "10x1x5"): 1.5607, (0.3, "14x1x7"): 1.4949, (0.3, "20x1x10"): 1.4707,
        (0.7, "10x1x5"): 2.5471, (0.7, "14x1x7"): 2.4807, (0.7, "20x1x10"): 2.4693,
        (1.0, "10x1x5"): 2.9147, (1.0, "14x1x7"): 2.8470, (1.0, "20x1x10"): 2.8406,
        (1.5, "10x1x5"): 4.2027, (1.5, "14x1x7"): 3.9908, (1.5, "20x1x10"): 4.4008}


def run(alpha: float, mesh: str, D0_max: float = 5.0, solver: str = "auto",
        D0_step: float = 0.25, D0_b: float | None = None) -> list[dict]:
    """One alpha x mesh: the mode at D0_b and the local criteria's onsets at two points.

    Parameters
    ----------
    alpha, mesh
        Weight fraction and eighth-model mesh (``"10x1x5"``).
    D0_max, D0_step
        The charge ramp: ``D0 = D0_step, 2 D0_step, ..., D0_max`` and ``D0_b``.
    solver
        Linear solver of the ramp.
    D0_b
        The reference charge; default the study's buckling load of ``alpha`` and ``mesh``
        (:data:`D0_B`).

    Returns
    -------
    list of dict
        The centroid's row and the most compressive clamp-side point's row.
    """
    import skfem_dielectric as fe
    from skfem_dielectric.models.plate.modes import lowest_physical
    from validation.fe.model import BUCKLING_GRAD_DIV
    from validation.clamp_zone.local_theory import energy_centroid, half_waves, local_state
    from validation.clamp_zone.units import UNIT_SETTINGS

    el = tuple(int(v) for v in mesh.split("x"))
    D0_b = D0_B[(alpha, mesh)] if D0_b is None else D0_b
    targets = np.unique(np.append(np.round(np.arange(D0_step, D0_max + 1e-9, D0_step), 10),
                                  D0_b))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = fe.keplinger_plate(alpha, D0=targets, elements=el, symmetry="eighth",
                                 options=fe.PlateOptions(grad_div=BUCKLING_GRAD_DIV),
                                 linear_solver=solver,
                                 settings=UNIT_SETTINGS)
    pb = res.problem
    states = [st for st in res.steps if float(np.asarray(st.load)[1]) > 0]
    D0 = np.array([float(np.asarray(st.load)[1]) for st in states])
    b = states[int(np.argmin(np.abs(D0 - D0_b)))]
    method = "pardiso" if solver == "pardiso" else "auto"
    lab = lowest_physical(pb, b.x, b.load, method=method).label
    point = energy_centroid(pb, b.x, b.load, lab.mode)
    n_half = half_waves(pb, lab.mode, lab.increments, point[0])
    # the clamp-side point of the centroid's X3 where sigma_33 is most compressive at D0_b
    line = [np.array([X1, 0.0, point[2]]) for X1 in np.linspace(30.0, pb.plate.L1 / 2, 81)]
    squeeze = min(line, key=lambda q: local_state(pb, b.x, b.load, q).sigma3)
    common = {"alpha": alpha, "mesh": mesh, "D0_b": D0_b, "class": lab.symmetry,
              "half_waves": n_half}
    return [dict(common, where="centroid", **_onsets(pb, states, D0, D0_b, point, n_half)),
            dict(common, where="compressive", **_onsets(pb, states, D0, D0_b, squeeze, n_half))]


def _onsets(pb, states, D0, D0_b, point, n_half) -> dict:
    """The local criteria along the ramp at one reference point."""
    import analytic as an
    from validation.clamp_zone.local_theory import first_firing, local_criteria, local_state

    H, L3 = pb.plate.H, pb.plate.L3
    model = an.NeoHookean()
    thin, fe_kh, thick, thin_par, kh_fe = [], [], [], [], []
    for st in states:
        ls = local_state(pb, st.x, st.load, point)
        c = local_criteria(ls, model, kh=np.array([0.01]))
        p = c.perpendicular
        # the FE mode's wavenumber x thickness in this state (deformed lengths)
        kh = 2 * math.pi * (H / (ls.lam1 * ls.lam3)) / (2 * L3 / n_half * ls.lam3)
        kh_fe.append(kh)
        D0c = float(an.critical_D0_biaxial(ls.lam1, ls.lam3, kh, model, "antisymmetric",
                                           "charge", "perpendicular"))
        fired = math.inf if p.eta < 1 else math.nan     # compressed thin plate: no root
        thin.append(ls.D0 - p.thin if np.isfinite(p.thin) else fired)
        fe_kh.append(ls.D0 - D0c if np.isfinite(D0c) else fired)
        thick.append(ls.D0 - p.thick)
        thin_par.append(ls.D0 - c.parallel.thin if np.isfinite(c.parallel.thin) else fired)
    i = int(np.argmin(np.abs(D0 - D0_b)))
    at_b = local_criteria(local_state(pb, states[i].x, states[i].load, point), model)
    s = at_b.state
    return {"X1": point[0], "X3": point[2], "lam1": s.lam1, "lam2": s.lam2, "lam3": s.lam3,
            "J": s.J, "D0_local": s.D0, "sigma3": s.sigma3, "thin_b": at_b.perpendicular.thin,
            "thick_b": at_b.perpendicular.thick, "kh_fe": kh_fe[i],
            "half_wave_mm": L3 / n_half * s.lam3, "kh_pref": at_b.perpendicular.kh_preferred,
            "thin": first_firing(D0, thin), "at_kh_fe": first_firing(D0, fe_kh),
            "thick": first_firing(D0, thick), "thin_parallel": first_firing(D0, thin_par)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--alpha", type=float, nargs="*", default=[0.3, 0.7, 1.0, 1.5])
    ap.add_argument("--mesh", nargs="*", default=["10x1x5", "14x1x7"])
    ap.add_argument("--solver", default="auto")
    ap.add_argument("--smoke", action="store_true",
                    help="alpha = 1 on the 4 x 1 x 2 mesh in D0 steps of 0.5 up to the D0_b of "
                         "10 x 1 x 5 (a check that the script runs, not a measurement)")
    a = ap.parse_args(argv)
    ramp = {}
    if a.smoke:
        a.alpha, a.mesh = [1.0], ["4x1x2"]
        D0_b = D0_B[(1.0, "10x1x5")]
        ramp = {"D0_step": 0.5, "D0_max": D0_b, "D0_b": D0_b}
    print("alpha  mesh      D0_b  n_half  point        X1    X3  lam1  lam2  lam3     J  D0_loc "
          " sig33  thin_b thick_b  kh_fe  half-wave/mm  kh_pref | fires at D0: thin  kh_fe  thick"
          "  thin-par.  CPU s")
    for mesh in a.mesh:
        for alpha in a.alpha:
            t0 = time.process_time()
            rows = run(alpha, mesh, solver=a.solver, **ramp)
            cpu = time.process_time() - t0
            for r in rows:
                print(f"{r['alpha']:5.2f}  {r['mesh']:7s} {r['D0_b']:6.4f}  {r['half_waves']:5d}  "
                      f"{r['where']:11s} {r['X1']:5.1f} {r['X3']:5.1f}  {r['lam1']:.3f} "
                      f"{r['lam2']:.3f} {r['lam3']:.3f} {r['J']:.3f}  {r['D0_local']:6.3f} "
                      f"{r['sigma3']:+6.3f}  {r['thin_b']:6.3f}  {r['thick_b']:6.3f}  "
                      f"{r['kh_fe']:5.3f}  {r['half_wave_mm']:11.2f}  {r['kh_pref']:7.2g} | "
                      f"{r['thin']:16.3f}  {r['at_kh_fe']:5.3f}  {r['thick']:5.3f}  "
                      f"{r['thin_parallel']:9.3f}  {cpu:5.1f}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

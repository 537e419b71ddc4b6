"""Run every gallery script ``docs/examples/ex*.py`` top to bottom and pin one number.

Like scikit-fem's tests/docs/test_examples.py: the examples are documentation, so they must
run; plotting sits under ``if __name__ == "__main__":`` and is executed too (Agg
backend, in a temporary working directory so that nothing lands in the repository).
"""

from __future__ import annotations

import runpy
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

EXAMPLES = sorted((Path(__file__).resolve().parents[2] / "docs" / "examples").glob("ex*.py"))


def _uniaxial_lam1(D0: float, s: float) -> float:
    """neo-Hookean uni-axial stretch: root of lam1^3 - s lam1^2 - sqrt(1 + D0^2) (DEuniax)."""
    r = np.roots([1.0, -s, 0.0, -np.sqrt(1.0 + D0**2)])
    return float(max(r[np.abs(r.imag) < 1e-12].real))


def _mooney_rivlin_lam(s: float, D0: float, c2: float) -> float:
    """Root of dPi/dlam of Pi = c1 (2 l^2 + l^-4 - 3) + c2 (l^4 + 2 l^-2 - 3)
    + D0^2 l^-4 / 2 - 2 s (l - 1), the derivative by complex step (exact to round-off)."""
    c1 = 0.5 - c2

    def energy(lam):
        return (c1 * (2 * lam**2 + lam**-4 - 3) + c2 * (lam**4 + 2 * lam**-2 - 3)
                + 0.5 * D0**2 * lam**-4 - 2 * s * (lam - 1))

    return brentq(lambda lam: energy(lam + 1e-30j).imag / 1e-30, 1.0, 5.0, xtol=1e-15,
                  rtol=1e-15)


def _uniaxial_E0_argmax(s: float) -> float:
    """``lam1`` where ``E0 = sqrt(lam1^4 (lam1 - s)^2 - 1) / (lam1^3 (lam1 - s))`` (Eq.
    DEuniax with ``lam3^2 = lam1 (lam1 - s)``) is maximal: root of its complex-step
    derivative, bracketed between the start of the curve and a far stretch."""
    def E0(l1):
        return np.sqrt(l1**4 * (l1 - s) ** 2 - 1) / (l1**3 * (l1 - s))

    start = _uniaxial_lam1(0.0, s)
    return brentq(lambda l1: E0(l1 + 1e-30j).imag / 1e-30, start * (1 + 1e-6), 10.0,
                  xtol=1e-15, rtol=1e-15)


def _thick_limit_nh(lam: float) -> float:
    """Positive root of Eq. (ideal-shortwave),
    D0^4 - (lam^6 + 3 lam^3 - 2) D0^2 - (lam^9 + lam^6 + 3 lam^3 - 1) = 0."""
    B = lam**6 + 3 * lam**3 - 2
    C = lam**9 + lam**6 + 3 * lam**3 - 1
    return float(np.sqrt((B + np.sqrt(B * B + 4 * C)) / 2))


def _equibiaxial_lam_nh(s: float, D0: float) -> float:
    """Largest real root of lam^6 - s lam^5 - 1 - D0^2 = 0, Eq. (loading_gent)."""
    return float(max(r.real for r in np.roots([1, -s, 0, 0, 0, 0, -1 - D0**2])
                     if abs(r.imag) < 1e-12))


def _plane_strain_state(s: float, D0: float, kappa: float) -> tuple[float, float]:
    """``(lam1, lam2)`` of the homogeneous plane-strain state (``lam3 = 1``) of ex13: the
    stationary point of the charge-controlled energy per reference volume (``mu = eps = 1``,
    ``F = diag(lam1, lam2, 1)``, ``D_L = -D0 e2``, so ``|F D_L|^2 / J = lam2 D0^2 / lam1``)
    ``(I1 - 3 - 2 ln J)/2 + kappa (ln J)^2/2 + lam2 D0^2/(2 lam1) - s lam1``; its
    derivatives by complex step (exact to round-off), ``lam2`` for a given ``lam1`` and
    then ``lam1`` by brentq."""
    def psi(l1, l2):
        lnJ = np.log(l1 * l2)
        return ((l1**2 + l2**2 - 2 - 2 * lnJ) / 2 + kappa * lnJ**2 / 2
                + l2 * D0**2 / (2 * l1) - s * l1)

    def lam2(l1):
        return brentq(lambda l2: psi(l1, l2 + 1e-30j).imag / 1e-30, 0.05, 5.0, xtol=1e-15,
                      rtol=1e-15)

    l1 = brentq(lambda l1: psi(l1 + 1e-30j, lam2(l1)).imag / 1e-30, 1.0, 5.0, xtol=1e-15,
                rtol=1e-15)
    return l1, lam2(l1)


_S_KEPLINGER = 0.150 * 9.81 / (9833.07 * 50e-6)

# name of the script -> (global variable, reference value, rtol, why this reference)
PINNED: dict[str, tuple[str, float, float, str]] = {
    "ex01_loading_curves": ("E0max_s0", np.sqrt(3.0) / 2 ** (4.0 / 3.0), 1e-9,
                            "literature: neo-Hookean s = 0 voltage-control maximum "
                            "sqrt(3)/2^(4/3) at lam = 2^(1/3)"),
    "ex02_wrinkling_map": ("thick_at_1", np.sqrt(1.0 + np.sqrt(5.0)), 1e-6,
                           "Eq. (ideal-shortwave) at lam = 1: D0^4 - 2 D0^2 - 4 = 0; lam = 1 "
                           "is a grid point, so only the root finder's tolerance remains"),
    "ex03_fe_plate": ("lam_final", _equibiaxial_lam_nh(1.5, 6.0), 1e-8,
                      "homogeneous 3D plate, s = 1.5, D0 = 6: Eq. (loading_gent) "
                      "lam^6 - s lam^5 - 1 - D0^2 = 0; mixed formulation, Newton tolerance"),
    "ex04_membrane": ("lam1_final", _uniaxial_lam1(6.0, _S_KEPLINGER), 1e-2,
                      "the clamped plate follows the homogeneous curve at its centre within "
                      "1 % (paper Sec. 6); measured deviation about 1e-4"),
    "ex05_new_model": ("lam_final", _mooney_rivlin_lam(1.0, 4.0, 0.1), 1e-10,
                       "stationary point of the Mooney-Rivlin energy Pi(lam) at s = 1, D0 = 4, "
                       "c2 = 0.1, from its complex-step derivative (independent of the "
                       "example's hand-derived residual); Newton tolerance 1e-13"),
    "ex06_hessian_loci": ("lam1_voltage_limit", _uniaxial_E0_argmax(1.0), 1e-10,
                          "sign change of the voltage-control Hessian block along the "
                          "uni-axial s = 1 path = maximum of the closed-form E0(lam1) "
                          "(complex-step derivative, brentq); both roots to ~1e-14"),
    "ex07_wrinkling_dispersion": ("D0_thick_side", _thick_limit_nh(2.0), 1e-9,
                                  "kh = 50 is deep in the thick-plate limit, Eq. "
                                  "(ideal-shortwave) solved as a quadratic in D0^2; the "
                                  "finite-thickness correction decays exponentially in kh "
                                  "(measured 8e-15), the rest is the root finder"),
    "ex08_keplinger_p33": ("lam1_D0_5", _uniaxial_lam1(5.0, _S_KEPLINGER), 1e-2,
                           "centre of the clamped plate on the homogeneous curve Eq. "
                           "(DEuniax) within 1 % (paper Sec. 6); measured 7e-4 on the "
                           "8 x 1 x 4 mesh"),
    "ex09_maxwell_vs_coupled": ("lam_maxwell_final", _equibiaxial_lam_nh(1.5, 6.0), 1e-8,
                                "homogeneous Maxwell-traction plate at s = 1.5, D0 = 6 on "
                                "Eq. (loading_gent); Newton tolerance 1e-11"),
    "ex10_snap_through": ("E0max_fe", np.sqrt(3.0) / 2 ** (4.0 / 3.0), 1e-9,
                          "literature: neo-Hookean s = 0 voltage-control maximum "
                          "sqrt(3)/2^(4/3); the FE limit point is located to |dE0/ds| <= "
                          "1e-9, second order in E0 at the maximum (measured 3e-11)"),
    "ex11_symmetry_classes": ("lowest_eig", lambda: _full_plate_lowest_eig(), 1e-8,
                              "the lowest eigenvalue of the whole clamped plate, computed on "
                              "the full (mirror-image) mesh without symmetry classes; the "
                              "classes split the same operator (measured equal to 1e-9)"),
    "ex12_post_buckling": ("D0_b_branch", lambda: _eighth_class_crossing(), 1e-4,
                           "the buckling load from the nonlinear branch alone (pitchfork "
                           "fit) against the eigenvalue crossing of the same bending class "
                           "x1 S, x2 A, x3 S on the eighth model (another model of the same "
                           "discrete problem), located to 1e-5; the fit's truncation about "
                           "1e-5 (measured difference 2e-6)"),
    "ex13_add_a_model": ("lam1_final", _plane_strain_state(0.5, 2.0, 100.0)[0], 1e-10,
                         "homogeneous plane-strain state of the compressible u-phi model at "
                         "s = 0.5, D0 = 2, kappa = 100: stationary point of its energy per "
                         "volume (complex-step derivatives, brentq); the state is exact in "
                         "the discrete space, Newton tolerance 1e-12"),
    "ex14_check_external_code": ("lam_s3_D06", _equibiaxial_lam_nh(3.0, 6.0), 1e-4,
                                 "the compressible plate (kappa = 1e5 mu) at s = 3, D0 = 6 on "
                                 "the incompressible Eq. (loading_gent): its penalty error, "
                                 "about 4 mu/kappa (measured 3.7e-5), is what the example "
                                 "checks with its tolerance 1e-4"),
    "ex15_lecture_breakdown": ("E0_max", np.sqrt(3.0) / 2 ** (4.0 / 3.0), 1e-10,
                               "literature: the neo-Hookean s = 0 voltage-control maximum "
                               "sqrt(3)/2^(4/3), found by a bounded search on the loading "
                               "curve (flat at the maximum: E0 to second order in the "
                               "search's 1e-12 in lam)"),
}


def _eighth_class_crossing() -> float:
    """D0 where the lowest eigenvalue of the class x1 S, x2 A, x3 S of the eighth model
    10 x 1 x 5 of the alpha = 0.05 Keplinger plate (grad-div 10) changes sign."""
    import skfem_dielectric as fe
    from skfem_dielectric.models.plate.symmetry_classes import class_stability

    res = fe.keplinger_plate(0.05, D0=[0.75, 0.8], elements=(10, 1, 5),
                             options=fe.PlateOptions(grad_div=10.0),
                             settings=replace(fe.gallery.KEPLINGER_SETTINGS, max_cutbacks=6,
                                              max_iter=25))
    pb, a, b = res.problem, res.steps[-2], res.steps[-1]

    def eig(x, ld):
        cs = class_stability(pb, x, ld, k=0, all_negative=True, extra=2,
                             only=["x1 S, x2 A, x3 S"])
        return float(cs.results[0].eigenvalues.min())

    crit = fe.critical_load(pb, a.x, a.load, b.load, eig, tol=1e-5,
                            settings=fe.RampSettings(rtol=1e-9, atol=0.0))
    return float(crit.load[1])


def _full_plate_lowest_eig() -> float:
    """Lowest eigenvalue of the reduced stiffness of the full 8 x 2 x 4 clamped plate at
    s = -0.4, D0 = 1 (the mirror image of the example's eighth model)."""
    import skfem_dielectric as fe
    from skfem_dielectric.gallery.drivers import keplinger_problem

    pb = keplinger_problem(size=(8.0, 1.0, 4.0), elements=(8, 2, 4), symmetry="full")
    tg = [np.array([-0.4, 1.0]) * t for t in np.linspace(0.25, 1.0, 4)]
    res = fe.ramp(pb, tg, x0=pb.initial_state(), start=np.zeros(2))
    K, _ = pb.assemble(res.x, tg[-1])
    return float(fe.stability.tangent_stability(pb, K, k=1, method="dense").eigenvalues[0])


def test_every_example_is_pinned():
    assert len(EXAMPLES) >= 9
    assert {p.stem for p in EXAMPLES} == set(PINNED)


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs(path, tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(plt, "show", lambda *a, **k: None)
    ns = runpy.run_path(str(path), run_name="__main__")
    plt.close("all")
    assert (tmp_path / f"{path.stem}.png").exists()     # the figure is saved, not only shown
    if path.stem == "ex05_new_model":
        # the contract's default load vector (central differences, h = 1e-6) against the
        # model's closed form: r is linear in s and quadratic in D0, so the difference is
        # exact up to round-off ~ 1e-16 |r| / h
        assert ns["dr_dload_fd"] == pytest.approx(ns["dr_dload"], rel=1e-8)
    if path.stem == "ex13_add_a_model":
        _check_add_a_model(ns)
    if path.stem == "ex09_maxwell_vs_coupled":
        assert ns["gap"] < 1e-9          # the two couplings agree on a homogeneous state
    if path.stem in PINNED:
        name, ref, rtol, _why = PINNED[path.stem]
        ref = ref() if callable(ref) else ref
        assert np.asarray(ns[name], dtype=float) == pytest.approx(ref, rel=rtol)


def _check_add_a_model(ns):
    """The tangent, the stability count and the Newton step of ex13 against references."""
    model, x, load = ns["model"], ns["result"].x, ns["loads"][-1]
    K, _ = model.assemble(x, load)
    d = np.random.default_rng(0).standard_normal(x.size)
    h = 1e-6
    fd = (model.residual(x + h * d, load) - model.residual(x - h * d, load)) / (2 * h)
    # central differences: truncation O(h^2) ~ 1e-12; round-off ~ 1e-16 ||r|| / h, measured
    # 2e-9 relative; a wrong term of the second variation is O(1) off
    assert np.linalg.norm(K @ d - fd) <= 1e-7 * np.linalg.norm(fd)
    # the second variation of an energy is symmetric to round-off (||K|| ~ 1e3)
    assert abs(K - K.T).max() <= 1e-12 * abs(K).max()
    # charge control of the homogeneous plate under tension is stable (paper Sec. 5): the
    # saddle-point tangent has exactly one negative eigenvalue per potential unknown
    # (Haynsworth inertia additivity, the phi-phi block is negative definite), none more
    assert ns["verdict"].inertia[1] == model.layout.blocks["phi"].size
    assert ns["verdict"].n_zero == 0
    # Newton alone to D0 = 2.25, against the same closed form as the pinned ramp value
    assert ns["sol"].converged
    assert ns["lam1_next"] == pytest.approx(_plane_strain_state(0.5, 2.25, 100.0)[0],
                                            rel=1e-10)


def test_add_a_model_tends_to_the_incompressible_curve():
    """ex13's model for kappa -> infinity: the plane-strain loading curve Eq. (t1t3) with
    lam3 = 1 (analytic.biaxial_stress), approached at first order in mu/kappa."""
    from analytic import biaxial_stress

    ns = runpy.run_path(str(EXAMPLES[0].parent / "ex13_add_a_model.py"))
    s, D0 = 0.5, 2.0
    lam_inc = brentq(lambda l1: biaxial_stress(l1, 1.0, D0)[0] - s, 1.0, 5.0, xtol=1e-15,
                     rtol=1e-15)
    stiff = ns["PlaneStrainDielectric"](kappa=1000.0, n1=1, n2=1)
    res = ns["ramp"](stiff, [np.array([s, 0.0]), np.array([s, 1.0]), np.array([s, D0])],
                     settings=ns["RampSettings"](atol=1e-12, rtol=1e-12))
    assert res.converged
    err_100 = ns["lam1_final"] - lam_inc
    err_1000 = float(res.column("lam1")[-1]) - lam_inc
    # the penalty error is c mu/kappa + O((mu/kappa)^2): ten times kappa, a tenth of the
    # error, up to the second-order term (relative size ~ 1/kappa = 1 %; measured 9.92)
    assert err_100 / err_1000 == pytest.approx(10.0, rel=0.03)

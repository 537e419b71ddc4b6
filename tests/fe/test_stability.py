"""Stability analysis: inertia counts, lowest modes, grad-div stabilisation, FE wrinkling.

References: dense eigenvalue counts of the same matrices (Sylvester's law makes the
inertia of a factorisation equal to the eigenvalue signs), central differences of the
residual for the tangent, the homogeneous closed forms, and the Stroh dispersion relation
of the analytic package (an independent implementation of the paper's Sec. 3).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import analytic as an
import skfem_dielectric as fe
from skfem_dielectric.linalg.inertia import tangent_inertia
from skfem_dielectric.stability.analysis import lowest_modes, metric_matrix, stability_analysis
from skfem_dielectric.studies.wrinkling_fe import section_critical_load, wrinkling_section

METHODS = ["superlu", "dense"] + (["pardiso"] if fe.linalg.pardiso_available() else [])


def _converged(pb, loads, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = fe.ramp(pb, loads, x0=pb.initial_state(),
                      settings=fe.RampSettings(atol=1e-10, rtol=1e-11), **kw)
    assert res.converged, res.reason
    return res


def _dense_negative(pb, x, load) -> int:
    K, _ = pb.assemble(x, load)
    ev = np.linalg.eigvalsh(K.toarray())
    return int(np.sum(ev < 0)) - pb.layout.n_multipliers


def test_count_equals_dense_eigenvalues_3d_quarter_plate():
    # the clamped quarter plate (full thickness) has clamp-corner modes after the pre-load
    # on a coarse mesh: counts of 0 and > 0 both occur along this ramp
    pb = fe.gallery.keplinger_problem(elements=(4, 1, 2), symmetry="quarter")
    s = fe.keplinger_s(1.0, g=9.81)
    loads = [np.array([s * k / 3, 0.0]) for k in (1, 2, 3)] + [np.array([s, 1.0])]
    res = _converged(pb, loads)
    counts = []
    for st in res.steps:
        ref = _dense_negative(pb, st.x, st.load)
        for method in METHODS:
            assert stability_analysis(pb, st.x, st.load, method=method).n_negative == ref
        counts.append(ref)
    assert min(counts) == 0 and max(counts) > 0


def test_count_equals_dense_eigenvalues_3d_voltage_control():
    # voltage control: the potential is prescribed on the electrodes, the count is over the
    # remaining potential unknowns; the equi-biaxial plate under E0 approaching its maximum
    # (0.5107 at s = 0.5, analytic.max_E0: beyond it there is no admissible equilibrium,
    # and a ramp without the plate's guards used to land on the inverted F11 = -0.97)
    E0_max = an.max_E0(0.5)[1]
    assert 0.510 < E0_max < 0.512
    pb = fe.gallery.equibiaxial_problem(elements=(2, 1, 2), symmetry="quarter",
                                        options=fe.PlateOptions(control="voltage"))
    res = _converged(pb, [np.array([0.5, 0.0]), np.array([0.5, 0.3]),
                          np.array([0.5, 0.98 * E0_max])])
    for st in res.steps:
        ref = _dense_negative(pb, st.x, st.load)
        for method in METHODS:
            assert stability_analysis(pb, st.x, st.load, method=method).n_negative == ref


@pytest.mark.parametrize("control", ["charge", "voltage"])
def test_count_equals_dense_eigenvalues_2d_section(control):
    # compressed section without stabilisation: spurious negative modes (count > 0)
    pb = fe.CrossSection(fe.section_mesh(4.0, 1.0, 6, 3), fe.NeoHookeanDielectric(),
                         control=control, lam1=0.7, lam3=0.7)
    res = _converged(pb, [np.array([0.0, 0.0, 0.5])])
    ref = _dense_negative(pb, res.x, res.steps[-1].load)
    assert ref > 0
    for method in METHODS:
        assert stability_analysis(pb, res.x, res.steps[-1].load, method=method).n_negative == ref


def test_lowest_modes_match_the_dense_pencil():
    pb = fe.CrossSection(fe.section_mesh(4.0, 1.0, 6, 3), fe.NeoHookeanDielectric(),
                         lam1=0.7, lam3=0.7)
    res = _converged(pb, [np.array([0.0, 0.0, 0.0])])
    K, _ = pb.assemble(res.x, (0, 0, 0))
    M = metric_matrix(pb)
    n_neg = stability_analysis(pb, res.x, (0, 0, 0), method="dense").n_negative
    vals, vecs = lowest_modes(K, M, 4, n_negative=n_neg)
    # dense reference: the d-block of K^-1 (d = displacement unknowns) is the inverse of
    # the reduced stiffness on the incompressible subspace (zero on its complement), so its
    # non-zero eigenvalues theta give the finite pencil eigenvalues 1/theta
    d = np.flatnonzero(M.diagonal() > 0)
    theta = np.linalg.eigvalsh(np.linalg.inv(K.toarray())[np.ix_(d, d)])
    theta = theta[np.abs(theta) > 1e-9 * np.abs(theta).max()]
    ref = np.sort(1.0 / theta)
    # the shift-invert Lanczos tolerance is 1e-12 relative in theta = 1/lambda
    assert vals == pytest.approx(ref[:4], rel=1e-8)
    r = K @ vecs - M @ vecs * vals      # the pencil residual of each mode
    assert np.abs(r).max() < 1e-8 * np.abs(K).max()


@pytest.mark.parametrize("aspect, spurious", [(0.25, False), (1.0, True), (4.0, True)])
def test_grad_div_removes_the_spurious_surface_modes(aspect, spurious):
    # equi-biaxial compression lam = 0.7 is above Biot's surface-instability stretch
    # 0.666 and the symmetric modes of finite plates (kh <= 5 have no root above 0.45):
    # the continuum is stable.  Q2/Q1 has mesh-scale surface modes with negative energy
    # there (the hydrostatic term p (F^-T : Grad v)^2 on modes that are divergence free
    # only against Q1; measured: 9 of them at dx/dy = 1, 2 at 4, none at 0.25 on this state);
    # gamma (J - 1)^2/2 removes them at every element aspect ratio.
    n2 = 4
    n1 = max(1, round((4.0 / 2) / (aspect * 0.5 / n2)))
    counts = {}
    for gd in (0.0, 10.0):
        pb = fe.CrossSection(fe.section_mesh(4.0, 1.0, n1, n2), fe.NeoHookeanDielectric(),
                             grad_div=gd, lam1=0.7, lam3=0.7)
        res = _converged(pb, [np.array([0.0, 0.0, 0.0])])
        counts[gd] = stability_analysis(pb, res.x, (0, 0, 0), method="superlu").n_negative
    assert (counts[0.0] > 0) == spurious and counts[10.0] == 0


def test_grad_div_leaves_homogeneous_states_and_keeps_the_tangent_consistent(
        assert_tangent_columns):
    s, D0 = 1.5, 3.0
    ref = fe.equibiaxial_plate(s, [D0], linear_solver="superlu").column("lam1")[-1]
    pb = fe.gallery.equibiaxial_problem(options=fe.PlateOptions(grad_div=10.0))
    res = fe.gallery.run_ramp(pb, fe.gallery.preload_then_charge(s, [D0], 4),
                              linear_solver="superlu",
                              settings=fe.RampSettings(atol=0.0, rtol=1e-11))
    # J = 1 exactly on the homogeneous state: the stabilisation changes nothing (Newton
    # tolerance 1e-11)
    assert res.column("lam1")[-1] == pytest.approx(ref, rel=1e-10)
    rng = np.random.default_rng(5)
    plate = fe.gallery.keplinger_problem(elements=(2, 1, 1), options=fe.PlateOptions(grad_div=7.0))
    for prob, load in ((plate, (1.0, 2.0)),
                       (fe.CrossSection(fe.section_mesh(20.0, 1.0, 2, 1),
                                        fe.GentDielectric(1.0, 1.0, 20.0), grad_div=7.0),
                        (1.0, 0.5, 2.0))):
        x = prob.initial_state() + 0.01 * rng.standard_normal(prob.ndofs)
        K, _ = prob.assemble(x, load)
        cols = rng.choice(prob.ndofs, 10, replace=False)
        assert_tangent_columns(prob.residual, K.toarray(), x, load, cols, floor=1.0)


def test_reported_stress_of_a_grad_div_model_is_the_plain_models():
    # the grad-div term is a device of the weak form, not of the material: at the same
    # state (F, p, G) the stabilised plate reports the plain plate's stress; the reference
    # is the plain model's response, the state a perturbed one with J != 1 (where the
    # term gamma (J - 1) J F^-T would be of order 7 * 0.01 mu), equal to rounding (1e-12 mu)
    rng = np.random.default_rng(3)
    plain = fe.gallery.keplinger_problem(elements=(2, 1, 1))
    stab = fe.gallery.keplinger_problem(elements=(2, 1, 1),
                                         options=fe.PlateOptions(grad_div=7.0))
    x = plain.initial_state() + 0.01 * rng.standard_normal(plain.ndofs)
    load = (1.0, 2.0)
    for (_, F, G, p), (_, F2, G2, p2) in zip(plain.quadrature_fields(x, load),
                                             stab.quadrature_fields(x, load)):
        ref, got = plain.stresses(F, G, p, load), stab.stresses(F2, G2, p2, load)
        assert np.abs(np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1))) - 1).max() > 1e-3
        for k in ("P1", "S", "sigma", "D"):
            np.testing.assert_allclose(got[k], ref[k], rtol=0, atol=1e-12)
    q_plain, q_stab = plain.postprocess(x, load), stab.postprocess(x, load)
    for k in ("min_P33", "min_P33_clamp", "min_P33_all", "P33_centre"):
        assert q_stab[k] == pytest.approx(q_plain[k], abs=1e-12)
    # the cross-section's reported P33 likewise
    sec = [fe.CrossSection(fe.section_mesh(20.0, 1.0, 2, 1), fe.GentDielectric(1.0, 1.0, 20.0),
                           grad_div=g) for g in (0.0, 7.0)]
    xs = sec[0].initial_state() + 0.01 * rng.standard_normal(sec[0].ndofs)
    assert sec[1].postprocess(xs, (1.0, 0.5, 2.0))["min_P33"] == pytest.approx(
        sec[0].postprocess(xs, (1.0, 0.5, 2.0))["min_P33"], abs=1e-12)


@pytest.mark.parametrize("lam, kh, mode, control, mesh", [
    (1.5, 2.0, "symmetric", "charge", (8, 4)),
    (1.5, 2.0, "symmetric", "voltage", (8, 4)),
    (1.2, 0.5, "antisymmetric", "charge", (8, 8)),
])
def test_fe_wrinkling_matches_the_stroh_dispersion_relation(lam, kh, mode, control, mesh):
    ref = an.critical_D0(lam, kh, mode=mode, control=control)
    ref_load = ref if control == "charge" else ref / lam**4     # E0 = D0 / lam^4
    pb = wrinkling_section(lam, kh, mode, control, n1=mesh[0], n2=mesh[1])
    r = section_critical_load(pb, mode, 0.95 * ref_load, 1.05 * ref_load)
    # coarse mesh: measured 1e-3 (charge), 6e-5 (voltage), 4e-5 (flexural); the harness'
    # quick tolerance is 3e-3
    assert abs(r.D0 / ref - 1) <= 3e-3
    if control == "voltage":    # homogeneous state: D0 = lam^4 E0 (Eq. (loading_gent))
        assert r.D0 == pytest.approx(lam**4 * r.load, rel=1e-8)


@pytest.mark.slow
def test_fe_wrinkling_converges_with_the_mesh():
    ref = an.critical_D0(1.5, 2.0, mode="symmetric", control="voltage")
    h, err = [], []
    for n1, n2 in ((4, 2), (8, 4), (16, 8)):
        pb = wrinkling_section(1.5, 2.0, "symmetric", "voltage", n1=n1, n2=n2)
        r = section_critical_load(pb, "symmetric", 0.9 * ref / 1.5**4, 1.1 * ref / 1.5**4)
        h.append(1.0 / n1)
        err.append(abs(r.D0 / ref - 1))
    rate = np.polyfit(np.log(h), np.log(err), 1)[0]
    print("errors", err, "rate", rate)
    # Q2 eigenvalue error: O(h^4) for a smooth mode (twice the order of the energy norm)
    assert rate > 3.0


def test_bad_input():
    pm = fe.plate_mesh(4.0, 1.0, 4.0, 1, 1, 1)
    mx = fe.PlateProblem(pm, fe.NeoHookeanDielectric(), coupling="maxwell")
    with pytest.raises(ValueError, match="not symmetric"):
        stability_analysis(mx, mx.initial_state(), (0.0, 0.0))
    pb = fe.PlateProblem(pm, fe.NeoHookeanDielectric())
    with pytest.raises(ValueError, match="k must be between"):
        stability_analysis(pb, pb.initial_state(), (0.0, 0.0), k=10**6)
    with pytest.raises(ValueError, match="not an equilibrium"):
        stability_analysis(pb, pb.initial_state(), (1.0, 2.0))
    with pytest.raises(ValueError, match="method"):
        tangent_inertia(pb.assemble(pb.initial_state(), (0, 0))[0], "lapack")

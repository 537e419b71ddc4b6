"""Material point laws: stresses vs finite differences of the energy, tangents vs finite
differences of the stresses, and the Maxwell-stress push-forward."""

import math

import numpy as np
import pytest

from skfem_dielectric.materials import (GentDielectric, IdealDielectric, NeoHookeanDielectric,
                                        ideal_dielectric_response)

rng = np.random.default_rng(0)
NPT = 4
F0 = np.eye(3)[:, :, None] + 0.3 * rng.standard_normal((3, 3, NPT))
G0 = rng.standard_normal((3, NPT))
P0 = rng.standard_normal(NPT)

MATERIALS = [NeoHookeanDielectric(mu=1.3, eps=0.7), GentDielectric(mu=1.3, eps=0.7, Jm=20.0),
             IdealDielectric(W=lambda I: 0.5 * (I - 3) + 0.01 * (I - 3) ** 2,
                             dW=lambda I: 0.5 + 0.02 * (I - 3), d2W=lambda I: 0.02 + 0 * I,
                             mu=1.0, eps=2.0)]
FORMS = [("mixed", math.inf), ("mixed", 50.0), ("penalty", 50.0), ("isochoric", 50.0),
         ("mixed-isochoric", 50.0), ("mixed-isochoric", math.inf), ("mixed-plain", math.inf)]


def flat(F, G, p):
    return np.concatenate([F.reshape(9, NPT), G, p[None]])


def unflat(y):
    return y[:9].reshape(3, 3, NPT), y[9:12], y[12]


@pytest.mark.parametrize("mat", MATERIALS)
@pytest.mark.parametrize("form,kappa", FORMS)
@pytest.mark.parametrize("stress_free", [False, True])
def test_derivatives_match_central_differences(mat, form, kappa, stress_free):
    y0 = flat(F0, G0, P0)
    resp = lambda y: ideal_dielectric_response(mat, *unflat(y), kappa=kappa, formulation=form,
                                               stress_free_reference=stress_free)
    r0 = resp(y0)
    grad = np.concatenate([r0.P.reshape(9, NPT), r0.D_L, r0.dpsi_dp[None]])
    hess = np.zeros((13, 13, NPT))
    hess[:9, :9] = r0.A_FF.reshape(9, 9, NPT)
    hess[:9, 9:12] = r0.A_FG.reshape(9, 3, NPT)
    hess[9:12, :9] = np.swapaxes(hess[:9, 9:12], 0, 1)
    hess[9:12, 9:12] = r0.A_GG
    hess[:9, 12] = hess[12, :9] = r0.A_Fp.reshape(9, NPT)
    hess[12, 12] = r0.A_pp
    h = 1e-6
    fd_g = np.zeros((13, NPT))
    fd_h = np.zeros((13, 13, NPT))
    for k in range(13):
        yp, ym = y0.copy(), y0.copy()
        yp[k] += h
        ym[k] -= h
        rp, rm = resp(yp), resp(ym)
        fd_g[k] = (rp.psi - rm.psi) / (2 * h)
        gp = np.concatenate([rp.P.reshape(9, NPT), rp.D_L, rp.dpsi_dp[None]])
        gm = np.concatenate([rm.P.reshape(9, NPT), rm.D_L, rm.dpsi_dp[None]])
        fd_h[:, k] = (gp - gm) / (2 * h)
    # central differences with h = 1e-6: truncation ~h^2 * |psi'''| ~ 1e-11, round-off
    # ~1e-16 * |psi| / h ~ 1e-10 (kappa = 50 terms are O(50)); relative 1e-7 is safe and
    # far below any missing-term error (O(1)).
    scale_g = np.abs(grad).max()
    assert np.abs(fd_g - grad).max() / scale_g < 1e-7
    scale_h = np.abs(hess).max()
    assert np.abs(fd_h - hess).max() / scale_h < 1e-7
    # the tangent is symmetric (it is a Hessian)
    assert np.abs(hess - np.swapaxes(hess, 0, 1)).max() / scale_h < 1e-13


@pytest.mark.parametrize("form,stress_free,log_term", [("mixed", False, False),
                                                       ("mixed", True, True),
                                                       ("mixed-plain", True, False)])
def test_cauchy_stress_is_elastic_plus_maxwell(form, stress_free, log_term):
    mat = NeoHookeanDielectric(mu=1.0, eps=2.5)
    r = ideal_dielectric_response(mat, F0, G0, P0, formulation=form,
                                  stress_free_reference=stress_free)
    J = np.linalg.det(np.moveaxis(F0, -1, 0))
    sigma = np.einsum("aK...,bK...->ab...", r.P, F0) / J
    Finv = np.linalg.inv(np.moveaxis(F0, -1, 0))
    E = -np.einsum("nMa,Mn->an", Finv, G0)          # E = -F^-T Grad phi
    b = np.einsum("aKn,bKn->abn", F0, F0)
    I = np.eye(3)[:, :, None]
    # -mu ln J adds -mu/J I (vanishes from the model when J = 1)
    # ("mixed-plain" has none: its reference pressure is p = -mu)
    p_eff = P0 - (mat.mu / J if log_term else 0.0)
    expected = (mat.mu * b / J + p_eff * I + mat.eps * (np.einsum("an,bn->abn", E, E)
                - 0.5 * np.einsum("an,an->n", E, E) * I))
    np.testing.assert_allclose(sigma, expected, atol=1e-12)
    # D = J^-1 F D_L = eps E  (ideal dielectric, exact also for J != 1)
    D = np.einsum("aKn,Kn->an", F0, r.D_L) / J
    np.testing.assert_allclose(D, mat.eps * E, atol=1e-12)


@pytest.mark.parametrize("kwargs,name", [({"mu": 0.0}, "mu"), ({"eps": -1.0}, "eps"),
                                         ({"mu": float("nan")}, "mu")])
def test_bad_parameters(kwargs, name):
    with pytest.raises(ValueError, match=name):
        NeoHookeanDielectric(**kwargs)
    with pytest.raises(ValueError, match="Jm"):
        GentDielectric(Jm=0.0)
    with pytest.raises(ValueError, match="formulation"):
        ideal_dielectric_response(NeoHookeanDielectric(), F0, G0, formulation="hybrid")


def test_inverse_and_cofactor_of_a_field_of_matrices_match_lapack():
    # the closed forms of skfem_dielectric.kinematics against numpy's LU inverse and
    # determinant on a (3, 3, 4, 5) field of well-conditioned matrices
    from skfem_dielectric.kinematics import cof3, det3, det_inv3, inv3

    rng = np.random.default_rng(3)
    F = np.eye(3)[:, :, None, None] + 0.3 * rng.standard_normal((3, 3, 4, 5))
    Fl = np.moveaxis(F, (0, 1), (-2, -1))
    ref_inv = np.moveaxis(np.linalg.inv(Fl), (-2, -1), (0, 1))
    ref_det = np.linalg.det(Fl)
    np.testing.assert_allclose(inv3(F), ref_inv, rtol=1e-12, atol=1e-13)
    J, Finv = det_inv3(F)
    np.testing.assert_allclose(J, ref_det, rtol=1e-12)
    np.testing.assert_allclose(det3(F), ref_det, rtol=1e-12)
    np.testing.assert_allclose(Finv, ref_inv, rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(cof3(F), ref_det * np.swapaxes(ref_inv, 0, 1),
                               rtol=1e-12, atol=1e-13)

"""Tests of the Maxwell-traction coupling (skfem_dielectric.maxwell)."""

import numpy as np
import pytest

from skfem_dielectric.maxwell import maxwell_stress, maxwell_traction

EPS = 0.8


def test_traction_is_minus_tau_m_cof_N_and_tangent_matches_fd():
    rng = np.random.default_rng(1)
    F = np.eye(3)[:, :, None, None] + 0.3 * rng.standard_normal((3, 3, 2, 5))
    N = rng.standard_normal((3, 2, 5))
    N /= np.linalg.norm(N, axis=0)
    t0, dt0 = maxwell_traction(F, N, 1.3, EPS)
    tau = maxwell_stress(F, 1.3, EPS)
    cof = np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))[None, None] * np.moveaxis(
        np.linalg.inv(np.moveaxis(F, (0, 1), (-2, -1))), (-1, -2), (0, 1))
    ref = -np.einsum("ij...,jk...,k...->i...", tau, cof, N)
    np.testing.assert_allclose(t0, ref, atol=1e-12)  # two routes to the same formula
    h = 1e-6
    fd = np.zeros_like(dt0)
    for k in range(3):
        for l in range(3):
            Fp, Fm = F.copy(), F.copy()
            Fp[k, l] += h
            Fm[k, l] -= h
            fd[:, k, l] = (maxwell_traction(Fp, N, 1.3, EPS)[0]
                           - maxwell_traction(Fm, N, 1.3, EPS)[0]) / (2 * h)
    # central differences: O(h^2) + O(1e-16/h) ~ 1e-10 relative
    assert np.abs(dt0 - fd).max() <= 1e-7 * np.abs(dt0).max()


@pytest.mark.parametrize("lam1, lam3", [(1.4, 1.4), (2.2, 0.9), (3.0, 1.1)])
def test_homogeneous_plate_reproduces_loading_curve(lam1, lam3):
    """Elastic neo-Hookean plate + Maxwell traction on all faces = fully coupled.

    On ``F = diag(lam1, lam2, lam3)``, the traction-free condition on the charged
    face (loaded by the Maxwell pressure) fixes the pressure, then the nominal
    lateral stresses follow ``t_a = mu (lam_a - lam2^2/lam_a) - lam2^2 D_L^2/(eps lam_a)``
    i.e. ``d omega*/d lam_a`` of Sec. 2.1 (Eqs. t1t3, loading_gent, uni-axial-loading).
    """
    mu, D_L = 1.7, 1.1
    lam2 = 1 / (lam1 * lam3)
    lams = np.array([lam1, lam2, lam3])
    F = np.diag(lams)
    tm = []
    for a in range(3):
        N = np.zeros(3)
        N[a] = 1.0
        t0, _ = maxwell_traction(F, N, -D_L, EPS)
        tm.append(t0[a] * lams[a])  # nominal -> Cauchy: t0 = tau n * (area stretch = 1/lam_a)
    # Cauchy: mu lam_a^2 - q = tm_a on every face (elastic part + the field's traction)
    q = mu * lam2**2 - tm[1]
    t1 = (mu * lam1**2 - q - tm[0]) / lam1
    t3 = (mu * lam3**2 - q - tm[2]) / lam3
    t1_ref = mu * (lam1 - lam2**2 / lam1) - lam2**2 * D_L**2 / (EPS * lam1)
    t3_ref = mu * (lam3 - lam2**2 / lam3) - lam2**2 * D_L**2 / (EPS * lam3)
    np.testing.assert_allclose([t1, t3], [t1_ref, t3_ref], rtol=1e-13)  # round-off only
    # the field alone pulls the lateral faces outwards and presses the charged ones
    assert tm[0] > 0 and tm[2] > 0 and tm[1] < 0
    if lam1 == lam3:
        s = t1 / mu
        D0 = D_L / np.sqrt(mu * EPS)
        np.testing.assert_allclose(np.sqrt(lam1**6 - 1 - lam1**5 * s), D0, rtol=1e-12)

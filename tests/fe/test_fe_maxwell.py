"""Tests of the Maxwell-traction coupling (skfem_dielectric.forms.maxwell_traction)."""

import numpy as np
import pytest

from skfem_dielectric.forms.maxwell_traction import (maxwell_stress, maxwell_traction,
                                                     maxwell_traction_field)

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


# --------------------------------------------------------------------------
# 2D cross-section with Maxwell traction (generalised plane strain, u-p-lam3)
# --------------------------------------------------------------------------
from scipy.optimize import brentq  # noqa: E402

from skfem_dielectric import CrossSection, section_mesh  # noqa: E402
from skfem_dielectric.gallery import cross_section_ramp  # noqa: E402
from skfem_dielectric.materials import GentDielectric, NeoHookeanDielectric  # noqa: E402


@pytest.mark.parametrize("field", ["electrostatic", "local"])
@pytest.mark.parametrize("s1, s3", [(1.5, 1.5), (0.8, 0.8), (2.993, 0.0), (0.8, 0.0)])
def test_cross_section_maxwell_matches_closed_form(s1, s3, field):
    mu = 1.3
    pb = CrossSection(section_mesh(4.0, 1.0, 3, 2), NeoHookeanDielectric(mu, EPS),
                      coupling="maxwell", field=field)
    res = cross_section_ramp(pb, s1, s3, [0.0, 2.0, 4.0, 6.0])
    assert res.converged
    for st in res.steps:
        D0 = st.load[2]
        if s3:  # Eq. (loading_gent), neo-Hookean
            lam = brentq(lambda l: l**6 - 1 - l**5 * s1 - D0**2, 1.0, 8.0, xtol=1e-15,
                         rtol=1e-14)
            lam1 = lam3 = lam
        else:  # Eq. (DEuniax) and lam3^2 = lam1 (lam1 - s)
            lo = brentq(lambda l: l - l**-2 - s1, 0.5, 20.0)
            lam1 = brentq(lambda l: l**4 * (l - s1) ** 2 - 1 - D0**2, lo - 1e-12, 20.0,
                          xtol=1e-15, rtol=1e-14)
            lam3 = np.sqrt(lam1 * (lam1 - s1))
        # the assumed field D = F D_L / J is exact on the homogeneous state, which is
        # exact in the discrete space: only the Newton tolerance (1e-10) remains
        assert abs(st["lam1"] / lam1 - 1) < 1e-8
        assert abs(st["lam3"] / lam3 - 1) < 1e-8
        # total P33 (elastic + Maxwell) = s3/lam3, as in the fully coupled model
        assert abs(st["min_P33"] - s3 / lam3) < 1e-8


@pytest.mark.parametrize("field", ["electrostatic", "local"])
def test_cross_section_maxwell_tangent_matches_finite_differences(field,
                                                                   assert_tangent_columns):
    pb = CrossSection(section_mesh(4.0, 1.0, 2, 2), GentDielectric(1.3, EPS, 20.0),
                      coupling="maxwell", field=field)
    rng = np.random.default_rng(7)
    x = pb.initial_state() + 0.01 * rng.standard_normal(pb.ndofs)
    load = (1.0, 0.5, 2.5)
    K, _ = pb.assemble(x, load)
    K = K.toarray()
    cols = list(rng.choice(pb.ndofs, 12, replace=False)) + [pb.ndofs - 1]
    assert_tangent_columns(pb.residual, K, x, load, cols, floor=1.0)
    # the follower load makes the tangent non-symmetric (it is not a potential load)
    assert np.abs(K - K.T).max() > 1e-6 * np.abs(K).max()


def test_cross_section_maxwell_bad_input():
    mesh, mat = section_mesh(20.0, 1.0, 1, 1), NeoHookeanDielectric(1.0, 1.0)
    with pytest.raises(ValueError, match="coupling"):
        CrossSection(mesh, mat, coupling="traction")
    with pytest.raises(ValueError, match="control"):
        CrossSection(mesh, mat, coupling="maxwell", control="voltage")
    with pytest.raises(ValueError, match="field"):
        CrossSection(mesh, mat, coupling="maxwell", field="remote")


# --------------------------------------------------------------------------
# 2D membrane with Maxwell traction
# --------------------------------------------------------------------------
from skfem_dielectric import MembranePlate, membrane_mesh  # noqa: E402
from skfem_dielectric.gallery import membrane_ramp  # noqa: E402


@pytest.mark.parametrize("loading, s", [("equibiaxial", 1.5), ("uniaxial-free", 2.993)])
def test_membrane_maxwell_matches_closed_form(loading, s):
    pb = MembranePlate(membrane_mesh(2.0, 0.05, 1.0, 3, 2), NeoHookeanDielectric(1.3, EPS),
                       loading=loading, coupling="maxwell")
    res = membrane_ramp(pb, s, [0.0, 2.0, 4.0, 6.0])
    assert res.converged
    for st in res.steps:
        D0 = st.load[1]
        if loading == "equibiaxial":
            lam = brentq(lambda l: l**6 - 1 - l**5 * s - D0**2, 1.0, 8.0, xtol=1e-15,
                         rtol=1e-14)
            lam1, lam3, P33 = lam, lam, s / lam
        else:
            lo = brentq(lambda l: l - l**-2 - s, 0.5, 20.0)
            lam1 = brentq(lambda l: l**4 * (l - s) ** 2 - 1 - D0**2, lo - 1e-12, 20.0,
                          xtol=1e-15, rtol=1e-14)
            lam3, P33 = np.sqrt(lam1 * (lam1 - s)), 0.0
        # exact homogeneous state (assumed field exact there): Newton tolerance only
        assert abs(st["lam1"] / lam1 - 1) < 1e-8
        assert abs(st["lam3"] / lam3 - 1) < 1e-8
        assert abs(st["min_P33"] - P33) < 1e-8  # total (elastic + Maxwell) P33


def test_membrane_maxwell_tangent_matches_finite_differences(assert_tangent_columns):
    pb = MembranePlate(membrane_mesh(2.0, 0.05, 1.0, 3, 2), GentDielectric(1.3, EPS, 20.0),
                       loading="uniaxial", coupling="maxwell")
    rng = np.random.default_rng(11)
    x = 0.01 * rng.standard_normal(pb.ndofs)
    load = (1.0, 3.0)
    K, _ = pb.assemble(x, load)
    K = K.toarray()
    cols = list(rng.choice(pb.ndofs - 1, 8, replace=False)) + [pb.ndofs - 1]
    assert_tangent_columns(pb.residual, K, x, load, cols)
    assert np.abs(K - K.T).max() > 1e-6 * np.abs(K).max()  # follower load: non-symmetric


def test_membrane_edge_traction_equals_3d_kernel():
    """The membrane's edge load is maxwell_traction on F = diag-block(F2, lam2)."""
    rng = np.random.default_rng(2)
    F2 = np.eye(2) + 0.2 * rng.standard_normal((2, 2))
    lam2 = 1 / np.linalg.det(F2)
    F3 = np.zeros((3, 3))
    F3[np.ix_([0, 2], [0, 2])] = F2
    F3[1, 1] = lam2
    N2 = np.array([0.6, 0.8])
    t0, _ = maxwell_traction(F3, np.array([N2[0], 0.0, N2[1]]), -1.7, EPS)
    ref = 1.7**2 * lam2**2 / (2 * EPS) * np.linalg.inv(F2).T @ N2
    np.testing.assert_allclose(t0[[0, 2]], ref, rtol=1e-13)  # same formula, round-off
    assert abs(t0[1]) < 1e-14


def test_field_traction_matches_tau_m_and_finite_differences():

    rng = np.random.default_rng(4)
    F = np.eye(3)[:, :, None] + 0.3 * rng.standard_normal((3, 3, 6))
    G = rng.standard_normal((3, 6))
    N = rng.standard_normal((3, 6))
    N /= np.linalg.norm(N, axis=0)
    t0, dF, dG = maxwell_traction_field(F, G, N, EPS)
    Ft = np.moveaxis(F, -1, 0)
    E = -np.linalg.solve(np.swapaxes(Ft, 1, 2), G.T[:, :, None])[..., 0]  # -F^-T G
    tau = EPS * (np.einsum("ni,nj->nij", E, E) - 0.5 * np.sum(E * E, 1)[:, None, None]
                 * np.eye(3))
    cofN = np.linalg.det(Ft)[:, None] * np.linalg.solve(np.swapaxes(Ft, 1, 2),
                                                         N.T[:, :, None])[..., 0]
    ref = -np.einsum("nij,nj->ni", tau, cofN).T
    np.testing.assert_allclose(t0, ref, atol=1e-12)  # definition, round-off only
    h = 1e-6
    for k in range(3):
        for l in range(3):
            Fp, Fm = F.copy(), F.copy()
            Fp[k, l] += h
            Fm[k, l] -= h
            fd = (maxwell_traction_field(Fp, G, N, EPS)[0]
                  - maxwell_traction_field(Fm, G, N, EPS)[0]) / (2 * h)
            # central differences: O(h^2) + round-off/h
            assert np.abs(fd - dF[:, k, l]).max() <= 1e-7 * np.abs(dF).max()
        Gp, Gm = G.copy(), G.copy()
        Gp[k] += h
        Gm[k] -= h
        fd = (maxwell_traction_field(F, Gp, N, EPS)[0]
              - maxwell_traction_field(F, Gm, N, EPS)[0]) / (2 * h)
        assert np.abs(fd - dG[:, k]).max() <= 1e-7 * np.abs(dG).max()

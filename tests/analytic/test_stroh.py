"""Electroelastic moduli and the Stroh matrix (paper Section 4, with its corrections)."""

import numpy as np
import pytest

from analytic import Gent, NeoHookean
from analytic.stroh import (
    electroelastic_moduli,
    stroh_coefficients,
    stroh_exponents,
    stroh_matrix,
)

MODELS = [NeoHookean(), Gent(Jm=97.2), Gent(Jm=10.0)]
STATES = [(1.3, 1.3, 0.8), (0.8, 0.8, 0.3), (1.6, 0.9, 1.2), (2.0, 2.0**-0.5, 2.5), (1.0, 1.0, 0.0)]


def _omega(F, EL, model):
    """Omega = W(I1) - I5/2 (Eq. modelE, mu = eps = 1) for an unconstrained F."""
    C = F.T @ F
    return float(model.W(np.trace(C))) - 0.5 * EL @ np.linalg.solve(C, EL)


def _fd_moduli(lam1, lam3, D0, model, h=1e-4):
    """Moduli by central finite differences of Omega, pushed forward with F."""
    lam2 = 1.0 / (lam1 * lam3)
    F = np.diag([lam1, lam2, lam3])
    EL = np.array([0.0, lam2**2 * D0, 0.0])  # E_L = F^T E, E2 = lam2 D0
    x0 = np.concatenate([F.ravel(), EL])  # 9 + 3 variables

    def f(x):
        return _omega(x[:9].reshape(3, 3), x[9:], model)

    H = np.zeros((12, 12))
    I = np.eye(12) * h
    for m in range(12):
        for n in range(m, 12):
            H[m, n] = H[n, m] = (
                f(x0 + I[m] + I[n]) - f(x0 + I[m] - I[n]) - f(x0 - I[m] + I[n]) + f(x0 - I[m] - I[n])
            ) / (4 * h * h)
    HFF = H[:9, :9].reshape(3, 3, 3, 3)  # d2/dF_ia dF_jb
    HFE = H[:9, 9:].reshape(3, 3, 3)  # d2/dF_ia dEL_b
    HEE = H[9:, 9:]
    A0 = np.einsum("pa,qb,iajb->piqj", F, F, HFF)
    AA0 = np.einsum("pa,kb,iab->pik", F, F, HFE)
    Ae0 = F @ HEE @ F.T
    return A0, AA0, Ae0


@pytest.mark.parametrize("model", MODELS[:2], ids=lambda m: m.name)
@pytest.mark.parametrize("state", STATES[:3])
def test_moduli_match_finite_differences_of_omega(model, state):
    A0, AA0, Ae0, _ = electroelastic_moduli(*state, model)
    A0f, AA0f, Ae0f = _fd_moduli(*state, model)
    # central differences with h = 1e-4: truncation ~h^2 * O(10) plus round-off
    # ~1e-16 * |Omega| / h^2 ~ 1e-8; moduli are O(1-10)
    assert np.max(np.abs(A0 - A0f)) < 2e-6
    assert np.max(np.abs(AA0 - AA0f)) < 2e-6
    assert np.max(np.abs(Ae0 - Ae0f)) < 2e-6


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
def test_equibiaxial_coefficients_match_gent_moduli(model):
    lam = np.array([0.7, 1.0, 1.4, 2.2])
    D0 = np.array([0.2, 0.0, 1.5, 3.0])
    a, b, c, d = stroh_coefficients(lam, lam, D0, model)
    I1 = 2 * lam**2 + lam**-4
    W1, W11 = model.dW(I1), model.d2W(I1)
    # Eq. (gent-moduli), exact algebra: agreement to rounding
    a_ref = 2 * lam**2 * W1 - lam**-4 * D0**2
    c_ref = 2 * lam**-4 * W1
    b_ref = 0.5 * (4 * (lam**-4 - lam**2) ** 2 * W11 + a_ref + c_ref)
    np.testing.assert_allclose(a, a_ref, rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(b, b_ref, rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(c, c_ref, rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(d, lam**-2 * D0, rtol=1e-13, atol=1e-13)


@pytest.mark.parametrize("model", MODELS[:2], ids=lambda m: m.name)
def test_paper_alternative_component_set_gives_same_combinations(model):
    """The printed set A0_1122 (with -E2^2), A0_1221 = 0, p = A0_2121 is an alternative."""
    lam1, lam3, D0 = 1.5, 0.8, 1.1
    A0, _, _, p = electroelastic_moduli(lam1, lam3, D0, model)
    lam2 = 1 / (lam1 * lam3)
    E2 = lam2 * D0
    W11 = model.d2W(lam1**2 + lam2**2 + lam3**2)
    # push-forward values (not the printed ones)
    assert A0[0, 0, 1, 1] == pytest.approx(4 * W11 * lam1**2 * lam2**2, rel=1e-13)
    assert A0[0, 1, 1, 0] == pytest.approx(-(E2**2), rel=1e-13)
    assert p == pytest.approx(A0[1, 0, 1, 0] - A0[1, 0, 0, 1], rel=1e-13)
    A1122_paper = 4 * W11 * lam1**2 * lam2**2 - E2**2
    two_b_paper = A0[0, 0, 0, 0] + A0[1, 1, 1, 1] - 2 * A1122_paper  # A0_1221 = 0 in the paper
    _, b, _, _ = stroh_coefficients(lam1, lam3, D0, model)
    assert b == pytest.approx(0.5 * two_b_paper, rel=1e-13)


@pytest.mark.parametrize("direction", ["parallel", "perpendicular"])
@pytest.mark.parametrize("model", MODELS[:2], ids=lambda m: m.name)
@pytest.mark.parametrize("state", STATES)
def test_stroh_eigenvectors_solve_full_incremental_equations(state, model, direction):
    """Independent check of N (and of the corrected Eq. con-eqns).

    Every eigenvector of N, as a plane wave exp(i(x_m + q x2)), is inserted into
    the full incremental equations written with all components of the
    push-forward moduli: incompressibility, div T0 = 0, div DL0 = 0, and the
    Stroh components Sigma21, Sigma22, Delta must equal T0_2m/i, T0_22/i, DL0_2/i.
    """
    A0, AA0, Ae0, p = electroelastic_moduli(*state, model)
    N = stroh_matrix(*state, model, direction)
    m = 0 if direction == "parallel" else 2
    qs, vecs = np.linalg.eig(N)
    for q, v in zip(qs, vecs.T):
        U1, U2, Phi, S21, S22, Dl = v
        u = np.zeros(3, complex)
        u[m], u[1] = U1, U2
        grad = np.zeros(3, complex)
        grad[m], grad[1] = 1j, 1j * q  # d/dx_m -> i, d/dx2 -> i q (k = 1)
        L = np.outer(u, grad)  # L_jq = u_j,q
        EL0 = -Phi * grad
        assert abs(np.trace(L)) < 1e-10
        T0_no_p = np.einsum("piqj,jq->pi", A0, L) + p * L + np.einsum("pik,k->pi", AA0, EL0)
        pdot = T0_no_p[1, 1] - 1j * S22  # from T0_22 = i Sigma22
        T0 = T0_no_p - pdot * np.eye(3)
        DL0 = -np.einsum("qjk,jq->k", AA0, L) - Ae0 @ EL0
        tol = 1e-10 * (1 + abs(q)) ** 3  # rounding in eig and in O(q^2) products
        assert abs(T0[1, m] - 1j * S21) < tol
        assert abs(DL0[1] - 1j * Dl) < tol
        div_T = grad @ T0  # (div T0)_i = d_p T0_pi
        assert abs(div_T[m]) < tol and abs(div_T[1]) < tol
        assert abs(grad @ DL0) < tol


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
def test_eigenvalues_and_paper_evalue(model):
    lam = 1.35
    D0 = 0.9
    N = stroh_matrix(lam, lam, D0, model)
    _, p2, p3 = stroh_exponents(lam, lam, D0, model)
    expected = np.array([1j, -1j, 1j * p2, -1j * p2, 1j * p3, -1j * p3])
    expected = expected[np.argsort(expected.imag)]
    got = np.linalg.eigvals(N)
    got = got[np.argsort(got.imag)]
    # eigenvalues of a 6x6 matrix with O(10) entries (neo-Hookean: i is a double
    # but non-defective eigenvalue), backward-stable eig: ~1e-14
    np.testing.assert_allclose(got, expected, atol=1e-10)
    # Eq. (evalue), printed form
    I1 = 2 * lam**2 + lam**-4
    r = model.d2W(I1) / model.dW(I1)
    p2_paper = (lam**3 + 1) / 2 * np.sqrt(1 + 2 * (lam - lam**-2) ** 2 * r) - (lam**3 - 1) / 2 * np.sqrt(
        1 + 2 * (lam + lam**-2) ** 2 * r
    )
    p3_paper = (lam**3 + 1) / 2 * np.sqrt(1 + 2 * (lam - lam**-2) ** 2 * r) + (lam**3 - 1) / 2 * np.sqrt(
        1 + 2 * (lam + lam**-2) ** 2 * r
    )
    assert complex(p2).real == pytest.approx(p2_paper, rel=1e-12)
    assert complex(p3).real == pytest.approx(p3_paper, rel=1e-12)


@pytest.mark.parametrize("direction", ["parallel", "perpendicular"])
def test_detN3_factorises(direction):
    state = (1.7, 0.75, 1.3)
    model = Gent(Jm=20.0)
    N = stroh_matrix(*state, model, direction)
    a, b, c, d = stroh_coefficients(*state, model, direction)
    detN3 = np.linalg.det(N[3:, :3])
    # Eq. (detN3), with the scaled -2(b + c) entry of N3
    assert detN3.real == pytest.approx(2 * (a - c) * (b + c + 2 * d**2) * (d**2 + c) / c, rel=1e-12)
    J = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])
    # Stroh symmetry J N = (J N)^T, exact by construction of the entries
    assert np.max(np.abs(J @ N - (J @ N).T)) == 0.0


def test_perpendicular_is_parallel_with_lam1_lam3_swapped():
    model = Gent(Jm=30.0)
    perp = stroh_coefficients(1.8, 0.7, 1.1, model, "perpendicular")
    par = stroh_coefficients(0.7, 1.8, 1.1, model, "parallel")
    np.testing.assert_allclose(perp, par, rtol=1e-14)


def test_bad_input():
    with pytest.raises(ValueError, match="lam1"):
        stroh_matrix(-1.0, 1.0, 0.0)
    with pytest.raises(ValueError, match="lam3"):
        stroh_matrix(1.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="D0"):
        stroh_matrix(1.0, 1.0, np.nan)
    with pytest.raises(ValueError, match="direction"):
        stroh_coefficients(1.0, 1.0, 0.0, direction="diagonal")
    with pytest.raises(ValueError, match="model"):
        stroh_matrix(1.0, 1.0, 0.0, model="gent")


@pytest.mark.parametrize("direction", ["parallel", "perpendicular"])
@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
def test_fast_coefficients_equal_push_forward(model, direction):
    """The reduced formulas used in the root finders equal the tensor route."""
    from analytic._stroh_core import coefficients_fast

    lam1 = np.array([0.7, 1.0, 1.6, 2.4])
    lam3 = np.array([0.9, 1.0, 0.8, 2.4**-0.5])
    D0 = np.array([0.1, 0.0, 1.3, 4.0])
    fast = coefficients_fast(lam1, lam3, D0, model, direction)
    full = stroh_coefficients(lam1, lam3, D0, model, direction)
    np.testing.assert_allclose(fast, full, rtol=1e-13, atol=1e-13)  # same algebra

"""Tests of the 2D incompressible dielectric membrane (skfem_dielectric.membrane)."""

import numpy as np
import pytest

from skfem_dielectric.membrane import membrane_kernel

MU, EPS, JM = 1.3, 0.7, 20.0


def _gent():
    W = lambda I1: -MU * JM / 2 * np.log(1 - (I1 - 3) / JM)
    dW = lambda I1: MU / 2 / (1 - (I1 - 3) / JM)
    d2W = lambda I1: MU / 2 / JM / (1 - (I1 - 3) / JM) ** 2
    return W, dW, d2W


def _nh():
    return (lambda I1: MU / 2 * (I1 - 3), lambda I1: MU / 2 + 0 * I1, lambda I1: 0 * I1)


@pytest.mark.parametrize("control", [dict(D_L=1.1), dict(E_L=0.8)])
def test_kernel_against_finite_differences(control):
    W, dW, d2W = _gent()
    rng = np.random.default_rng(0)
    F = np.eye(2)[:, :, None, None] + 0.3 * rng.standard_normal((2, 2, 3, 4))
    psi, P, A = membrane_kernel(F, W, dW, d2W, EPS, H=0.9, **control)
    h = 1e-6
    Pfd, Afd = np.zeros_like(P), np.zeros_like(A)
    for k in range(2):
        for l in range(2):
            Fp, Fm = F.copy(), F.copy()
            Fp[k, l] += h
            Fm[k, l] -= h
            a = membrane_kernel(Fp, W, dW, d2W, EPS, H=0.9, **control)
            b = membrane_kernel(Fm, W, dW, d2W, EPS, H=0.9, **control)
            Pfd[k, l] = (a[0] - b[0]) / (2 * h)
            Afd[:, :, k, l] = (a[1] - b[1]) / (2 * h)
    # central differences with h = 1e-6: truncation ~h^2, round-off ~1e-16/h -> 1e-9
    assert np.abs(P - Pfd).max() <= 1e-7 * np.abs(P).max()
    assert np.abs(A - Afd).max() <= 1e-7 * np.abs(A).max()
    # the membrane tangent is the Hessian of an energy: exactly symmetric
    assert np.abs(A - A.transpose(2, 3, 0, 1, 4, 5)).max() <= 1e-12 * np.abs(A).max()


@pytest.mark.parametrize("model", ["nh", "gent"])
def test_equibiaxial_kernel_gives_loading_curve(model):
    """s = P11/(mu H) on F = diag(lam, lam) satisfies Eq. (loading_gent)."""
    W, dW, d2W = _nh() if model == "nh" else _gent()
    lam = np.linspace(1.05, 2.5, 7)
    D0 = 1.3
    F = np.zeros((2, 2, lam.size))
    F[0, 0] = F[1, 1] = lam
    _, P, _ = membrane_kernel(F, W, dW, d2W, EPS, D_L=D0 * np.sqrt(MU * EPS), H=2.0)
    s = P[0, 0] / (MU * 2.0)
    jm = np.inf if model == "nh" else JM
    # closed form, Eq. (loading_gent) (written here as the independent reference)
    D0_ref = np.sqrt((lam**6 - 1) / (1 - (2 * lam**2 + lam**-4 - 3) / jm) - lam**5 * s)
    np.testing.assert_allclose(D0_ref, D0, rtol=1e-12)  # algebraic identity: round-off only


def test_voltage_control_equibiaxial():
    """Voltage control: s = lam - lam^-5 - lam^3 E0^2 (D0 = lam^4 E0 in Eq. loading_gent)."""
    W, dW, d2W = _nh()
    lam = np.linspace(1.05, 2.0, 5)
    E0 = 0.4
    F = np.zeros((2, 2, lam.size))
    F[0, 0] = F[1, 1] = lam
    _, P, _ = membrane_kernel(F, W, dW, d2W, EPS, E_L=E0 * np.sqrt(MU / EPS))
    s = P[0, 0] / MU
    np.testing.assert_allclose(np.sqrt(lam**6 - 1 - lam**5 * s), lam**4 * E0, rtol=1e-12)

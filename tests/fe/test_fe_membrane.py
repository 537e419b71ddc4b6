"""Tests of the 2D incompressible dielectric membrane (skfem_dielectric.models.membrane)."""

import numpy as np
import pytest

from skfem_dielectric.forms.membrane import membrane_kernel
from skfem_dielectric.materials import GentDielectric, NeoHookeanDielectric

MU, EPS, JM = 1.3, 0.7, 20.0


GENT = GentDielectric(mu=MU, eps=EPS, Jm=JM)
NH = NeoHookeanDielectric(mu=MU, eps=EPS)


@pytest.mark.parametrize("control", [dict(D_L=1.1), dict(E_L=0.8)])
def test_kernel_against_finite_differences(control):
    rng = np.random.default_rng(0)
    F = np.eye(2)[:, :, None, None] + 0.3 * rng.standard_normal((2, 2, 3, 4))
    psi, P, A = membrane_kernel(F, GENT, H=0.9, **control)
    h = 1e-6
    Pfd, Afd = np.zeros_like(P), np.zeros_like(A)
    for k in range(2):
        for l in range(2):
            Fp, Fm = F.copy(), F.copy()
            Fp[k, l] += h
            Fm[k, l] -= h
            a = membrane_kernel(Fp, GENT, H=0.9, **control)
            b = membrane_kernel(Fm, GENT, H=0.9, **control)
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
    mat = NH if model == "nh" else GENT
    lam = np.linspace(1.05, 2.5, 7)
    D0 = 1.3
    F = np.zeros((2, 2, lam.size))
    F[0, 0] = F[1, 1] = lam
    _, P, _ = membrane_kernel(F, mat, D_L=D0 * np.sqrt(MU * EPS), H=2.0)
    s = P[0, 0] / (MU * 2.0)
    jm = np.inf if model == "nh" else JM
    # closed form, Eq. (loading_gent) (written here as the independent reference)
    D0_ref = np.sqrt((lam**6 - 1) / (1 - (2 * lam**2 + lam**-4 - 3) / jm) - lam**5 * s)
    np.testing.assert_allclose(D0_ref, D0, rtol=1e-12)  # algebraic identity: round-off only


def test_voltage_control_equibiaxial():
    """Voltage control: s = lam - lam^-5 - lam^3 E0^2 (D0 = lam^4 E0 in Eq. loading_gent)."""
    lam = np.linspace(1.05, 2.0, 5)
    E0 = 0.4
    F = np.zeros((2, 2, lam.size))
    F[0, 0] = F[1, 1] = lam
    _, P, _ = membrane_kernel(F, NH, E_L=E0 * np.sqrt(MU / EPS))
    s = P[0, 0] / MU
    np.testing.assert_allclose(np.sqrt(lam**6 - 1 - lam**5 * s), lam**4 * E0, rtol=1e-12)


# --------------------------------------------------------------------------
# finite elements
# --------------------------------------------------------------------------
from scipy.optimize import brentq  # noqa: E402

from skfem_dielectric import MembranePlate, membrane_mesh, ramp  # noqa: E402
from skfem_dielectric.gallery import membrane_keplinger, membrane_ramp  # noqa: E402


def _equibiaxial_lam(D0, s, Jm=np.inf):
    """Invert Eq. (loading_gent) (independent reference, written in the test)."""
    f = lambda lam: (lam**6 - 1) / (1 - (2 * lam**2 + lam**-4 - 3) / Jm) - lam**5 * s - D0**2
    hi = 8.0 if np.isinf(Jm) else 3.0  # Jm = 20 locks at lam = 3.39
    return brentq(f, 1.0 if s >= 0 else 0.3, hi, xtol=1e-15, rtol=1e-14)


def _uniaxial_lam1(D0, s):
    """Invert Eq. (DEuniax)_1, D0 = sqrt(lam1^4 (lam1 - s)^2 - 1)."""
    f = lambda l1: l1**4 * (l1 - s) ** 2 - 1 - D0**2
    lo = brentq(lambda l1: l1 - l1**-2 - s, 0.5, 20)  # D0 = 0 root
    return brentq(f, lo - 1e-12, 20.0, xtol=1e-15, rtol=1e-14)


@pytest.mark.parametrize("s", [0.8, 1.5, 2.5])
@pytest.mark.parametrize("model", ["nh", "gent"])
def test_fe_equibiaxial_matches_closed_form(s, model):
    mat = NeoHookeanDielectric(MU, EPS) if model == "nh" else GentDielectric(MU, EPS, JM)
    pb = MembranePlate(membrane_mesh(2.0, 0.05, 1.0, 3, 2), mat, loading="equibiaxial")
    D0s = [0.0, 1.5, 3.0, 4.5, 6.0] if model == "nh" else [0.0, 1.0, 2.0]
    res = ramp(pb, [(s, d) for d in D0s])
    assert res.converged
    for st in res.steps:
        lam_ref = _equibiaxial_lam(st.load[1], s, np.inf if model == "nh" else JM)
        # homogeneous state is exact in Q2: only the Newton tolerance (1e-10) remains
        assert abs(st["lam1"] / lam_ref - 1) < 1e-8
        assert abs(st["lam3"] / lam_ref - 1) < 1e-8
        # P33 = s mu / lam (second Piola of the dead load s along x3)
        assert abs(st["min_P33"] - s / lam_ref) < 1e-8


def test_fe_equibiaxial_voltage_control():
    """Voltage control on the stable branch: s = lam - lam^-5 - lam^3 E0^2."""
    mat = NeoHookeanDielectric(MU, EPS)
    pb = MembranePlate(membrane_mesh(2.0, 0.05, 1.0, 2, 2), mat, loading="equibiaxial",
                       control="voltage")
    s = 1.0
    res = ramp(pb, [(s, e) for e in (0.0, 0.1, 0.2, 0.3)])
    assert res.converged
    for st in res.steps:
        E0, lam = st.load[1], st["lam1"]
        lam_ref = brentq(lambda l: l - l**-5 - l**3 * E0**2 - s, 1.0, lam + 0.3)
        assert abs(lam / lam_ref - 1) < 1e-8  # exact homogeneous state, Newton tolerance


@pytest.mark.parametrize("s", [0.8, 2.993])
def test_fe_uniaxial_matches_closed_form(s):
    mat = NeoHookeanDielectric(MU, EPS)
    pb = MembranePlate(membrane_mesh(2.0, 0.05, 1.0, 3, 2), mat, loading="uniaxial-free")
    res = ramp(pb, [(s, d) for d in (0.0, 2.0, 4.0, 6.0)])
    assert res.converged
    for st in res.steps:
        lam1 = _uniaxial_lam1(st.load[1], s)
        assert abs(st["lam1"] / lam1 - 1) < 1e-8  # exact homogeneous state
        # lam3^2 = lam1 (lam1 - s), Eq. (uni-axial-loading)
        assert abs(st["lam3"] / np.sqrt(lam1 * (lam1 - s)) - 1) < 1e-8
        assert abs(st["min_P33"]) < 1e-8  # free lateral edge: P33 = 0


def test_fe_tangent_matches_finite_differences_of_residual(assert_tangent_columns):
    """Assembled reduced tangent (incl. the shared clamp dof) vs central differences."""
    mat = GentDielectric(MU, EPS, JM)
    pb = MembranePlate(membrane_mesh(2.0, 0.05, 1.0, 3, 2), mat, loading="uniaxial")
    rng = np.random.default_rng(3)
    x = 0.01 * rng.standard_normal(pb.ndofs)
    load = (1.0, 2.0)
    K, r = pb.assemble(x, load)
    K = K.toarray()
    cols = list(rng.choice(pb.ndofs - 1, 6, replace=False)) + [pb.ndofs - 1]
    assert_tangent_columns(pb.residual, K, x, load, cols)
    # symmetric: the membrane tangent is a Hessian (tying dofs keeps it symmetric)
    assert np.abs(K - K.T).max() <= 1e-12 * np.abs(K).max()


@pytest.mark.parametrize("kw, name", [
    (dict(L1=-1.0), "L1"), (dict(H=0.0), "H"), (dict(n1=0), "n1"), (dict(n3=2.5), "n3"),
    (dict(L3=np.nan), "L3"),
])
def test_bad_mesh_input_raises(kw, name):
    size = {**dict(L1=2.0, H=0.05, L3=1.0, n1=1, n3=1), **kw}
    with pytest.raises(ValueError, match=name):
        membrane_mesh(**size)


@pytest.mark.parametrize("kw, name", [
    (dict(loading="biaxial"), "loading"), (dict(loading="clamped"), "loading"),
    (dict(control="current"), "control"),
])
def test_bad_input_raises(kw, name):
    with pytest.raises(ValueError, match=name):
        MembranePlate(membrane_mesh(2.0, 0.05, 1.0, 1, 1), NeoHookeanDielectric(MU, EPS), **kw)


def test_bad_loads_raise():

    mesh = membrane_mesh(2.0, 0.05, 1.0, 1, 1)
    pb = MembranePlate(mesh, NeoHookeanDielectric(MU, EPS))
    with pytest.raises(ValueError, match="s must be finite"):
        membrane_ramp(pb, np.nan, [0.0])
    with pytest.raises(ValueError, match="D0"):
        membrane_ramp(pb, 1.0, [0.0, np.inf])
    with pytest.raises(ValueError, match="D0"):
        membrane_ramp(pb, 1.0, [])
    with pytest.raises(ValueError, match="alpha"):
        membrane_keplinger(alpha=np.nan, n1=1, n3=1)
    with pytest.raises(ValueError, match="coupling"):
        MembranePlate(mesh, NeoHookeanDielectric(MU, EPS), coupling="both")
    with pytest.raises(ValueError, match="control"):
        MembranePlate(mesh, NeoHookeanDielectric(MU, EPS), coupling="maxwell",
                      control="voltage")

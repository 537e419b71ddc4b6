"""Tests of the 2D generalised-plane-strain cross-section
(skfem_dielectric.models.cross_section)."""

import numpy as np
import pytest
from scipy.optimize import brentq

from skfem_dielectric import CrossSection, section_mesh
from skfem_dielectric.gallery import cross_section_ramp
from skfem_dielectric.materials import GentDielectric, NeoHookeanDielectric

MU, EPS, JM = 1.3, 0.7, 20.0


def _equibiaxial_lam(D0, s, Jm=np.inf):
    """Invert Eq. (loading_gent) (independent reference, written in the test)."""
    f = lambda lam: (lam**6 - 1) / (1 - (2 * lam**2 + lam**-4 - 3) / Jm) - lam**5 * s - D0**2
    return brentq(f, 1.0, 8.0 if np.isinf(Jm) else 3.0, xtol=1e-15, rtol=1e-14)


def _uniaxial_lam1(D0, s):
    """Invert Eq. (DEuniax)_1, D0 = sqrt(lam1^4 (lam1 - s)^2 - 1)."""
    lo = brentq(lambda l1: l1 - l1**-2 - s, 0.5, 20)
    return brentq(lambda l1: l1**4 * (l1 - s) ** 2 - 1 - D0**2, lo - 1e-12, 20.0,
                  xtol=1e-15, rtol=1e-14)


@pytest.mark.parametrize("model, s", [("nh", 0.8), ("nh", 2.5), ("gent", 1.5)])
def test_equibiaxial_matches_closed_form(model, s):
    mat = NeoHookeanDielectric(MU, EPS) if model == "nh" else GentDielectric(MU, EPS, JM)
    pb = CrossSection(section_mesh(4.0, 1.0, 3, 2), mat)
    D0s = [0.0, 2.0, 4.0, 6.0] if model == "nh" else [0.0, 1.0, 2.0]
    res = cross_section_ramp(pb, s, s, D0s)
    assert res.converged
    for st in res.steps:
        lam = _equibiaxial_lam(st.load[2], s, np.inf if model == "nh" else JM)
        # homogeneous state is exact in Q2/Q1/Q2: Newton tolerance (1e-10) only
        assert abs(st["lam1"] / lam - 1) < 1e-8
        assert abs(st["lam3"] / lam - 1) < 1e-8
        assert abs(st["lam2"] * lam**2 - 1) < 1e-8  # exact incompressibility
        assert abs(st["D0"] - st.load[2]) < 1e-8  # D_L2 = -sigma_F everywhere
        assert abs(st["E0"] - st.load[2] / lam**4) < 1e-8  # D0 = lam^4 E0
        assert abs(st["min_P33"] - s / lam) < 1e-8  # second Piola of the dead load s


@pytest.mark.parametrize("s", [0.8, 2.993])
def test_uniaxial_matches_closed_form(s):
    pb = CrossSection(section_mesh(4.0, 1.0, 3, 2), NeoHookeanDielectric(MU, EPS))
    res = cross_section_ramp(pb, s, 0.0, [0.0, 2.0, 4.0, 6.0])
    assert res.converged
    for st in res.steps:
        lam1 = _uniaxial_lam1(st.load[2], s)
        assert abs(st["lam1"] / lam1 - 1) < 1e-8  # exact homogeneous state
        # lam3^2 = lam1 (lam1 - s), Eq. (uni-axial-loading)
        assert abs(st["lam3"] / np.sqrt(lam1 * (lam1 - s)) - 1) < 1e-8
        assert abs(st["min_P33"]) < 1e-8  # s3 = 0


def test_prescribed_lam3_matches_biaxial_closed_form():
    """lam3 fixed: t1 = d omega*/d lam1 of Sec. 2.1 with lam2 = 1/(lam1 lam3)."""
    lam3 = 1.2
    pb = CrossSection(section_mesh(4.0, 1.0, 3, 2), NeoHookeanDielectric(MU, EPS), lam3=lam3)
    s = 1.0
    res = cross_section_ramp(pb, s, 0.0, [0.0, 1.5, 3.0])
    assert res.converged
    for st in res.steps:
        D0, l1 = st.load[2], st["lam1"]
        # omega*/mu = (l1^2 + l3^2 + l1^-2 l3^-2 - 3)/2 + l1^-2 l3^-2 D0^2 / 2
        t1 = l1 - l1**-3 * lam3**-2 * (1 + D0**2)
        assert abs(t1 - s) < 1e-8  # Newton tolerance on an exact homogeneous state
        assert st["lam3"] == lam3


def test_voltage_control_equibiaxial():
    """E0 prescribed: s = lam - lam^-5 - lam^3 E0^2 (D0 = lam^4 E0 in Eq. loading_gent)."""
    pb = CrossSection(section_mesh(4.0, 1.0, 2, 1), NeoHookeanDielectric(MU, EPS),
                      control="voltage")
    s = 1.0
    res = cross_section_ramp(pb, s, s, [0.0, 0.1, 0.2, 0.3])
    assert res.converged
    for st in res.steps:
        E0, lam = st.load[2], st["lam1"]
        assert abs(lam - lam**-5 - lam**3 * E0**2 - s) < 1e-8
        assert abs(st["E0"] - E0) < 1e-8


def test_tangent_matches_finite_differences(assert_tangent_columns):
    pb = CrossSection(section_mesh(4.0, 1.0, 2, 2), GentDielectric(MU, EPS, JM))
    rng = np.random.default_rng(5)
    x = pb.initial_state() + 0.01 * rng.standard_normal(pb.ndofs)
    load = (1.0, 0.5, 2.0)
    K, _ = pb.assemble(x, load)
    K = K.toarray()
    cols = list(rng.choice(pb.ndofs, 10, replace=False)) + [pb.ndofs - 1]
    assert_tangent_columns(pb.residual, K, x, load, cols, floor=1.0)
    assert np.abs(K - K.T).max() <= 1e-12 * np.abs(K).max()  # symmetric saddle point


@pytest.mark.parametrize("kw, name", [
    (dict(L1=0.0), "L1"), (dict(H=-1.0), "H"), (dict(n2=0), "n2"),
    (dict(thickness="quarter"), "thickness"),
])
def test_bad_mesh_input_raises(kw, name):
    size = {**dict(L1=20.0, H=1.0, n1=1, n2=1), **kw}
    with pytest.raises(ValueError, match=name):
        section_mesh(**size)


@pytest.mark.parametrize("kw, name", [
    (dict(lam3=-1.0), "lam3"), (dict(lam1=0.0), "lam1"), (dict(control="current"), "control"),
    (dict(grad_div=-1.0), "grad_div"), (dict(phi_element=2), "phi_element"),
])
def test_bad_input_raises(kw, name):
    with pytest.raises(ValueError, match=name):
        CrossSection(section_mesh(20.0, 1.0, 1, 1), NeoHookeanDielectric(MU, EPS), **kw)


def test_bad_load_raises():
    pb = CrossSection(section_mesh(20.0, 1.0, 1, 1), NeoHookeanDielectric(MU, EPS))
    with pytest.raises(ValueError, match="D0"):
        cross_section_ramp(pb, 1.0, 1.0, [0.0, np.nan])
    with pytest.raises(ValueError, match="s1"):
        cross_section_ramp(pb, np.inf, 1.0, [0.0])

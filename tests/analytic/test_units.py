"""SI <-> dimensionless conversions (analytic.units) against hand-computed values and physics."""

from __future__ import annotations

import numpy as np
import pytest

import analytic as an
from analytic import units as u

MU, EPS = 9833.07, 4.7 * u.EPS0  # a VHB-like permittivity, only to have realistic magnitudes


def test_keplinger_constants_and_s():
    p = u.KEPLINGER_PLATE
    assert (p.length, p.width, p.thickness, p.mu) == (0.100, 0.050, 0.001, 9833.07)
    assert p.cross_section == pytest.approx(50e-6, rel=1e-15)  # A = 50 mm^2 (Sec. 6)
    assert u.KEPLINGER_MASS == 0.150
    # s = alpha m g/(mu A), by hand: 0.15 * 9.81 / (9833.07 * 5e-5) = 1.4715 / 0.4916535
    s = u.keplinger_s(np.array(u.KEPLINGER_ALPHAS), g=9.81)
    np.testing.assert_allclose(s, np.array([0.05, 0.3, 0.7, 1.0, 1.5]) * (1.4715 / 0.4916535), rtol=1e-14)
    assert float(u.keplinger_s(1.0, g=9.81)) == pytest.approx(2.9929615, abs=5e-8)  # long division
    # standard gravity gives a 0.03 % larger load: s scales linearly with g
    assert float(u.keplinger_s(1.0, g=9.80665) / u.keplinger_s(1.0, g=9.81)) == pytest.approx(9.80665 / 9.81,
                                                                                            rel=1e-15)


def test_g_must_be_given():
    with pytest.raises(TypeError):
        u.keplinger_s(1.0)  # g is keyword-only and required: no silent default


def test_round_trips():
    x = np.array([-2.0, 0.0, 1e-3, 3.7])
    np.testing.assert_allclose(u.D0_to_SI(u.D0_from_SI(x, MU, EPS), MU, EPS), x, rtol=1e-15)
    np.testing.assert_allclose(u.E0_to_SI(u.E0_from_SI(x, MU, EPS), MU, EPS), x, rtol=1e-15)
    np.testing.assert_allclose(u.s_to_SI(u.s_from_SI(x, MU), MU), x, rtol=1e-15)
    A, H = 5e-3, 1e-3
    np.testing.assert_allclose(u.D0_to_charge(u.charge_to_D0(x, A, MU, EPS), A, MU, EPS), x, rtol=1e-15)
    np.testing.assert_allclose(u.E0_to_voltage(u.voltage_to_E0(x, H, MU, EPS), H, MU, EPS), x, rtol=1e-15)


def test_scalings_make_the_ideal_dielectric_law_dimensionless():
    """D_L = eps lam^4 E_L (equi-biaxial ideal dielectric, Sec. 2.1) becomes D0 = lam^4 E0."""
    lam, E_L = 1.7, 2.3e6  # V/m
    D_L = EPS * lam**4 * E_L
    assert float(u.D0_from_SI(D_L, MU, EPS)) == pytest.approx(lam**4 * float(u.E0_from_SI(E_L, MU, EPS)),
                                                             rel=1e-14)


def test_SI_equilibrium_of_the_keplinger_plate():
    """A dimensional check through the analytic curve: Q on the faces of the plate at the
    neo-Hookean uni-axial state, converted back, gives the nominal force balance in SI."""
    p = u.KEPLINGER_PLATE
    s = float(u.keplinger_s(1.0, g=9.81))
    lam1 = 4.0
    D0 = float(an.uniaxial_D0(lam1, s))
    lam3 = float(an.uniaxial_lam3(lam1, s))
    Q = float(u.D0_to_charge(D0, p.face_area, p.mu, EPS))
    D_L = Q / p.face_area
    # nominal stress in SI, Eq. (t1t3) with neo-Hookean W = mu/2 (I1 - 3):
    t1 = p.mu * (lam1 - lam1**-3 * lam3**-2) - lam1**-3 * lam3**-2 * D_L**2 / EPS
    assert t1 * p.cross_section == pytest.approx(0.150 * 9.81, rel=1e-12)  # = m g


def test_plain_conversions_by_hand():
    assert float(u.D0_from_SI(3.0, mu=4.0, eps=9.0)) == 0.5
    assert float(u.E0_from_SI(2.0, mu=4.0, eps=9.0)) == 3.0
    assert float(u.charge_to_D0(6.0, face_area=2.0, mu=1.0, eps=9.0)) == 1.0
    assert float(u.voltage_to_E0(4.0, thickness=2.0, mu=4.0, eps=9.0)) == 3.0
    assert float(u.dead_load_s(1.0, g=10.0, area=2.0, mu=5.0)) == 1.0
    assert u.EPS0 == 8.8541878128e-12  # CODATA 2018


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: u.D0_from_SI(1.0, mu=0.0, eps=1.0), r"mu must be > 0 and finite, got 0\.0"),
        (lambda: u.E0_from_SI(1.0, mu=1.0, eps=-1.0), r"eps must be > 0 and finite, got -1\.0"),
        (lambda: u.s_from_SI(np.nan, mu=1.0), r"t must not be NaN"),
        (lambda: u.keplinger_s(-0.5, g=9.81), r"alpha must be finite and >= 0"),
        (lambda: u.keplinger_s(1.0, g=0.0), r"g must be > 0"),
        (lambda: u.dead_load_s(-1.0, g=9.81, area=1.0, mu=1.0), r"mass must be finite and >= 0"),
        (lambda: u.Plate(length=0.1, width=0.0, thickness=0.001, mu=1.0), r"width must be > 0"),
        (lambda: u.charge_to_D0(1.0, face_area=-1.0, mu=1.0, eps=1.0), r"face_area must be > 0"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()

"""Strain-energy models: derivatives against finite differences, limits, bad input."""

import numpy as np
import pytest

from analytic import Gent, NeoHookean, UserModel

I1 = np.linspace(3.0, 40.0, 11)


@pytest.mark.parametrize("model", [NeoHookean(), Gent(97.2), Gent(5.0)])
def test_derivatives_match_central_differences(model):
    # central differences: truncation O(h^2 W''') ~ 1e-12, rounding ~ eps*W/h ~ 1e-10
    I = np.linspace(3.0, min(40.0, 3.0 + 0.9 * model.I1_max() - 2.7), 9)
    h = 1e-5
    dW_fd = (model.W(I + h) - model.W(I - h)) / (2 * h)
    d2W_fd = (model.dW(I + h) - model.dW(I - h)) / (2 * h)
    np.testing.assert_allclose(model.dW(I), dW_fd, rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(model.d2W(I), d2W_fd, rtol=1e-7, atol=1e-9)


def test_gent_tends_to_neo_hookean():
    # W_Gent - W_nH = (I1-3)^2/(4 Jm) + O(Jm^-2): the gap must fall like 1/Jm
    gaps = [np.max(np.abs(Gent(Jm).W(I1) - NeoHookean().W(I1))) for Jm in (1e3, 1e4)]
    assert gaps[0] / gaps[1] == pytest.approx(10.0, rel=0.05)
    # Taylor series to third order; the remainder (I1-3)^4/(8 Jm^3) is < 3e-7 here
    x, Jm = I1 - 3, 1e4
    taylor = x / 2 + x**2 / (4 * Jm) + x**3 / (6 * Jm**2)
    assert np.max(np.abs(Gent(Jm).W(I1) - taylor)) < 3e-7


def test_reference_state_shear_modulus_is_one():
    # W'(3) = 1/2 means mu = 1 in the dimensionless units
    for m in (NeoHookean(), Gent(97.2)):
        assert float(m.dW(3.0)) == 0.5


@pytest.mark.parametrize("Jm", [0.0, -1.0, np.nan, np.inf])
def test_gent_rejects_bad_Jm(Jm):
    with pytest.raises(ValueError, match="Jm"):
        Gent(Jm)


def test_gent_rejects_I1_beyond_limit():
    with pytest.raises(ValueError, match="Gent limit"):
        Gent(10.0).W(13.5)


def test_user_model_matches_neo_hookean():
    m = UserModel(W=lambda I: 0.5 * (I - 3), dW=lambda I: 0.5 + 0 * I, d2W=lambda I: 0 * I)
    np.testing.assert_allclose(m.W(I1), NeoHookean().W(I1), rtol=0, atol=0)
    with pytest.raises(ValueError, match="callable"):
        UserModel(W=1.0, dW=lambda I: I, d2W=lambda I: I)

"""Homogeneous loading curves (analytic.homogeneous) against independent references.

References used: central finite differences of the energies omega*, omega
(analytic.hessian, built from W(I1) only, never from W'), the paper's printed
closed forms (Eqs. loading_gent, uni-axial-loading, DEuniax) typed in here, the
Jm -> inf limit of Gent, and round trips of the inverse functions.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

import analytic as an

# A user model that is neo-Hookean in disguise: forces the generic (root-finding)
# code paths, whose results must match the neo-Hookean closed forms.
NH_USER = an.UserModel(
    W=lambda I: 0.5 * (I - 3.0), dW=lambda I: 0.5 + 0.0 * I, d2W=lambda I: 0.0 * I, name="nh-user"
)
# A genuinely different stiffening user model, W = (I1-3)/2 + c (I1-3)^2.
QUAD = an.UserModel(
    W=lambda I: 0.5 * (I - 3.0) + 0.01 * (I - 3.0) ** 2,
    dW=lambda I: 0.5 + 0.02 * (I - 3.0),
    d2W=lambda I: 0.02 + 0.0 * I,
    name="quadratic",
)
GENT = an.Gent(97.2)
MODELS = [None, GENT, NH_USER, QUAD]
IDS = ["neo-Hookean", "Gent", "nh-user", "quadratic"]

# Central differences with h = 1e-6 on O(1) smooth energies: truncation h^2 f'''/6 ~ 1e-12,
# round-off eps |omega| / h ~ 1e-10 (|omega| up to ~1e2 here) -> 1e-7 relative is safe
# and still 5 orders below any formula error (wrong factor, wrong power).
H_FD = 1e-6
FD_RTOL = 1e-7


def d_dx(f, x, h=H_FD):
    return (f(x + h) - f(x - h)) / (2 * h)


# ----------------------------------------------------------------------------- equi-biaxial
@pytest.mark.parametrize("model", MODELS, ids=IDS)
@pytest.mark.parametrize("s", [-0.5, 0.0, 1.0, 2.3])
def test_equibiaxial_curve_is_equilibrium_fd(model, s):
    """s = (1/2) d omega*-hat/d lam and E0 = d omega*-hat/d D0 (Eq. s_general), by FD."""
    lam0 = float(an.equibiaxial_lam(0.0, s, model))
    lam = lam0 * np.linspace(1.01, 2.5, 13)
    D0 = an.equibiaxial_D0(lam, s, model)
    E0 = an.equibiaxial_E0(lam, s, model)
    assert np.all(np.isfinite(D0))
    s_fd = 0.5 * d_dx(lambda l: an.equibiaxial_omega_star(l, D0, model), lam)
    E_fd = d_dx(lambda d: an.equibiaxial_omega_star(lam, d, model), D0)
    scale = 1.0 + np.abs(s) + D0**2 / lam**5  # size of the terms that cancel in s
    np.testing.assert_allclose((s_fd - s) / scale, 0.0, atol=FD_RTOL)
    np.testing.assert_allclose(E_fd, E0, rtol=FD_RTOL)
    # the voltage-control form s(lam, E0) and the charge form s(lam, D0) give s back
    np.testing.assert_allclose(an.equibiaxial_s(lam, D0, model), s, atol=1e-12 * scale.max())
    np.testing.assert_allclose(an.equibiaxial_s_E0(lam, E0, model), s, atol=1e-12 * scale.max())


def test_equibiaxial_matches_printed_loading_gent():
    """Eq. (loading_gent) as printed, neo-Hookean and Gent (Jm = 97.2)."""
    lam = np.linspace(1.0, 5.0, 41)
    for s in (0.0, 1.0, 2.3, 3.0):
        with np.errstate(invalid="ignore"):
            nh = np.sqrt(lam**6 - 1 - lam**5 * s)
            Jm = 97.2
            gent = np.sqrt((lam**6 - 1) / (1 - (2 * lam**2 + lam**-4 - 3) / Jm) - lam**5 * s)
        # same algebra evaluated in a different order: a few ulps of lam^6 ~ 1e4
        np.testing.assert_allclose(an.equibiaxial_D0(lam, s), nh, rtol=1e-12, atol=1e-9)
        np.testing.assert_allclose(an.equibiaxial_D0(lam, s, an.Gent(97.2)), gent, rtol=1e-12, atol=1e-9)
        np.testing.assert_allclose(an.equibiaxial_E0(lam, s), nh / lam**4, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("model", MODELS, ids=IDS)
@pytest.mark.parametrize("s", [-2.0, 0.0, 1.0, 3.0])
def test_equibiaxial_lam_round_trip(model, s):
    D0 = np.array([0.0, 1e-3, 0.3, 1.0, 2.0, 5.0, 20.0])
    lam = an.equibiaxial_lam(D0, s, model)
    # the root finder stops at a few ulps; D0(lam) then matches to ~1e-12 relative
    np.testing.assert_allclose(an.equibiaxial_D0(lam, s, model), D0, rtol=1e-10, atol=1e-6)
    # and the forward-backward trip in lam
    lam_grid = lam[2:]
    back = an.equibiaxial_lam(an.equibiaxial_D0(lam_grid, s, model), s, model)
    np.testing.assert_allclose(back, lam_grid, rtol=1e-13)


def test_equibiaxial_lam_closed_form_at_s0():
    """Neo-Hookean s = 0: lam^6 = 1 + D0^2 exactly (Eq. loading_gent)."""
    D0 = np.linspace(0, 10, 101)
    np.testing.assert_allclose(an.equibiaxial_lam(D0, 0.0), (1 + D0**2) ** (1 / 6), rtol=4e-16 * 8)


def test_gent_tends_to_neo_hookean_with_rate_one_over_Jm():
    """Gent -> neo-Hookean as Jm -> inf; 1/(1 - x/Jm) = 1 + x/Jm + ... gives error ~ 1/Jm."""
    lam = np.linspace(1.4, 3.0, 30)  # s = 1 branch starts at lam = 1.285
    lam1 = np.linspace(1.8, 3.0, 30)  # and at lam1 = 1.466
    Jms = np.array([1e2, 1e3, 1e4, 1e5])
    err_eq = [np.max(np.abs(an.equibiaxial_D0(lam, 1.0, an.Gent(J)) - an.equibiaxial_D0(lam, 1.0))) for J in Jms]
    err_ua = [np.max(np.abs(an.uniaxial_D0(lam1, 1.0, an.Gent(J)) - an.uniaxial_D0(lam1, 1.0))) for J in Jms]
    err_inv = [np.max(np.abs(an.equibiaxial_lam(lam, 1.0, an.Gent(J)) - an.equibiaxial_lam(lam, 1.0))) for J in Jms]
    err_ua_inv = [np.max(np.abs(an.uniaxial_lam1(lam, 1.0, an.Gent(J)) - an.uniaxial_lam1(lam, 1.0))) for J in Jms]
    for err in (err_eq, err_ua, err_inv, err_ua_inv):
        rate = np.polyfit(np.log(Jms), np.log(err), 1)[0]
        assert rate == pytest.approx(-1.0, abs=0.05)  # first-order in 1/Jm, asymptotic regime
        # constant of the 1/Jm law settled: err * Jm agrees between the two largest Jm
        assert err[-1] * Jms[-1] == pytest.approx(err[-2] * Jms[-2], rel=0.02)


# ----------------------------------------------------------------------------- uni-axial
@pytest.mark.parametrize("model", MODELS, ids=IDS)
@pytest.mark.parametrize("s", [-0.5, 0.0, 0.5, 1.0, 3.0])
def test_uniaxial_curve_is_equilibrium_fd(model, s):
    """t1 = d omega*/d lam1 = s and t3 = d omega*/d lam3 = 0 (Eq. t1t3) by FD; E0 = d omega*/d D0."""
    l10 = float(an.uniaxial_lam1(0.0, s, model))
    lam1 = l10 * np.linspace(1.01, 2.0, 11)
    lam3 = an.uniaxial_lam3(lam1, s, model)
    D0 = an.uniaxial_D0(lam1, s, model)
    E0 = an.uniaxial_E0(lam1, s, model)
    assert np.all(np.isfinite(D0)) and np.all(np.isfinite(lam3))
    t1 = d_dx(lambda a: an.omega_star(a, lam3, D0, model), lam1)
    t3 = d_dx(lambda b: an.omega_star(lam1, b, D0, model), lam3)
    Ed = d_dx(lambda d: an.omega_star(lam1, lam3, d, model), D0)
    scale = 1.0 + lam1 + D0**2  # magnitude of the cancelling terms
    np.testing.assert_allclose((t1 - s) / scale, 0.0, atol=FD_RTOL)
    np.testing.assert_allclose(t3 / scale, 0.0, atol=FD_RTOL)
    np.testing.assert_allclose(Ed, E0, rtol=FD_RTOL)


@pytest.mark.parametrize("model", [None, NH_USER], ids=["closed-form", "generic-solver"])
def test_uniaxial_matches_printed_DEuniax(model):
    """Eqs. (uni-axial-loading) and (DEuniax) as printed, for neo-Hookean."""
    lam1 = np.linspace(1.05, 6.0, 60)
    for s in (0.0, 1.0, 2.0, 3.0, 4.0):
        with np.errstate(invalid="ignore", divide="ignore"):
            D0_p = np.sqrt(lam1**4 * (lam1 - s) ** 2 - 1)
            E0_p = np.sqrt(1 - lam1**-4 * (lam1 - s) ** -2.0) / lam1
        on = (lam1 > s) & np.isfinite(D0_p)
        D0 = an.uniaxial_D0(lam1, s, model)
        E0 = an.uniaxial_E0(lam1, s, model)
        l3 = an.uniaxial_lam3(lam1, s, model)
        assert np.array_equal(np.isfinite(D0), on)  # nan exactly off the branch
        # the generic solver converges to a few ulps of lam3^2; D0 ~ lam1^2 lam3^2 amplifies
        np.testing.assert_allclose(D0[on], D0_p[on], rtol=1e-12, atol=1e-6)
        np.testing.assert_allclose(E0[on], E0_p[on], rtol=1e-12, atol=1e-6)
        # Eq. (uni-axial-loading): s = lam1 - lam3^2/lam1, D0^2 = lam1^2 lam3^4 - 1,
        # E0^2 = lam1^-2 - lam1^-4 lam3^-4
        np.testing.assert_allclose(lam1[on] - l3[on] ** 2 / lam1[on], s, atol=1e-12 * lam1.max())
        np.testing.assert_allclose(D0[on] ** 2, lam1[on] ** 2 * l3[on] ** 4 - 1, rtol=1e-11, atol=1e-11)
        np.testing.assert_allclose(E0[on] ** 2, lam1[on] ** -2 - lam1[on] ** -4 * l3[on] ** -4, atol=1e-13)


def test_gent_uniaxial_closed_form_matches_generic_solver():
    """The Gent quadratic in lam3^2 against the root finder run on a user-model copy of
    Gent, up to the locking stretch (including the region where two states share lam1)."""
    Jm = 97.2
    gent_user = an.UserModel(
        W=lambda I: -0.5 * Jm * np.log(1 - (I - 3) / Jm),
        dW=lambda I: 0.5 / (1 - (I - 3) / Jm),
        d2W=lambda I: 0.5 / (Jm * (1 - (I - 3) / Jm) ** 2),
        name="gent-user", I1_limit=3 + Jm,
    )
    lam1 = np.linspace(0.6, 9.95, 400)[:, None]
    s = np.array([-1.0, 0.0, 0.5, 2.0, 6.0, 30.0, 47.0])[None, :]
    a = an.uniaxial_lam3(lam1, s, GENT)
    b = an.uniaxial_lam3(lam1, s, gent_user)
    assert np.array_equal(np.isnan(a), np.isnan(b))
    assert np.count_nonzero(np.isfinite(a)) > 1000
    # both converge to a few ulps of lam3^2; near the lock the roots are ill-conditioned
    np.testing.assert_allclose(a, b, rtol=1e-10)


def test_uniaxial_s0_is_equibiaxial():
    """With s = 0 both in-plane stresses vanish: the uni-axial state is the equi-biaxial one."""
    lam1 = np.linspace(1.0, 3.0, 21)
    for model in (None, GENT, QUAD):
        np.testing.assert_allclose(an.uniaxial_lam3(lam1, 0.0, model), lam1, rtol=1e-14)
        np.testing.assert_allclose(an.uniaxial_D0(lam1, 0.0, model), an.equibiaxial_D0(lam1, 0.0, model),
                                   rtol=1e-12, atol=1e-7)


@pytest.mark.parametrize("model", MODELS, ids=IDS)
@pytest.mark.parametrize("s", [-0.5, 0.0, 1.0, 2.99])
def test_uniaxial_lam1_round_trip(model, s):
    D0 = np.array([0.0, 0.2, 1.0, 3.0, 8.0])
    lam1 = an.uniaxial_lam1(D0, s, model)
    np.testing.assert_allclose(an.uniaxial_D0(lam1, s, model), D0, rtol=1e-9, atol=1e-6)
    back = an.uniaxial_lam1(an.uniaxial_D0(lam1[1:], s, model), s, model)
    np.testing.assert_allclose(back, lam1[1:], rtol=1e-12)


def test_uniaxial_lam1_neo_hookean_cubic():
    """Neo-Hookean: lam1^2 (lam1 - s) = sqrt(1 + D0^2) (Eq. DEuniax solved for lam1)."""
    D0 = np.linspace(0, 10, 41)[:, None]
    s = np.array([-1.0, 0.0, 1.0, 4.0])[None, :]
    lam1 = an.uniaxial_lam1(D0, s)
    assert lam1.shape == (41, 4)
    np.testing.assert_allclose(lam1**2 * (lam1 - s), np.broadcast_to(np.sqrt(1 + D0**2), (41, 4)),
                               rtol=1e-14)


@pytest.mark.parametrize("Jm", [20.0, 97.2])
def test_gent_uniaxial_lam1_round_trip(Jm):
    """uniaxial_D0(uniaxial_lam1(D0)) == D0 for Gent (the fast path: Newton in xi = 1/(2W'))."""
    g = an.Gent(Jm)
    eps = np.finfo(float).eps
    for s in (0.5, 1.0, 2.993, 5.0):
        # D0 >= 0.5: a lam1 exact to a few ulps gives D0 to (d ln D0/d ln lam1) x (a few eps);
        # that factor is <= 660 here (s = 5: lam1 hardly moves with D0), so <= 3e-13 < 1e-12
        D0 = np.linspace(0.5, 6.0, 56)
        lam1 = an.uniaxial_lam1(D0, s, g)
        np.testing.assert_allclose(an.uniaxial_D0(lam1, s, g), D0, rtol=1e-12, atol=0)
        # D0 -> 0 the map lam1 -> D0 = sqrt(G(lam1)) is infinitely steep at the branch start,
        # so no method can give 1e-12 relative there: the error budget is 4 ulps of lam1,
        # |D0_rt^2 - D0^2| <= 4 eps lam1 |dG/dlam1| (G = D0^2; one-sided FD slope, the branch
        # starts at lam1(0)); observed <= 1.2 ulp
        D0 = np.array([0.0, 1e-6, 1e-4, 1e-3, 1e-2, 0.1, 0.3])
        lam1 = an.uniaxial_lam1(D0, s, g)
        h = 1e-6 * lam1
        dG = (an.uniaxial_D0(lam1 + 2 * h, s, g) ** 2 - an.uniaxial_D0(lam1 + h, s, g) ** 2) / h
        assert np.all(dG > 0)  # D0 grows along the loading branch
        err = np.abs(an.uniaxial_D0(lam1, s, g) ** 2 - D0**2)
        assert np.all(err <= 4 * eps * lam1 * dG), (s, err / (eps * lam1 * dG))


def test_gent_uniaxial_lam1_matches_biaxial_newton():
    """The Gent fast path against the 2-D Newton solve of grad psi* = 0 with s3 = 0 (the
    previous implementation, still used for user models), including s <= 0, large D0 and the
    near-lock range where lam1(D0) turns back (Jm = 20, s = 10: lam1 beyond the equi-biaxial
    locking stretch 3.39)."""
    D0 = np.concatenate([np.linspace(0.0, 6.0, 61), [10.0, 20.0, 50.0]])[:, None]
    s = np.array([-2.0, -0.5, 0.0, 0.5, 1.0, 2.993, 5.0, 10.0])[None, :]
    for Jm in (5.0, 20.0, 97.2):
        g = an.Gent(Jm)
        new = an.uniaxial_lam1(D0, s, g)
        ref, _ = an.biaxial_stretches(s, 0.0, D0, g)
        assert new.shape == (64, 8) and np.all(np.isfinite(new)) and np.all(np.isfinite(ref))
        # both stop at ~1e-14 relative (Newton residual 1e-14 of the stress scale; here
        # observed <= 1e-14): 1e-12 leaves a factor 100 for the conditioning near the lock
        np.testing.assert_allclose(new, ref, rtol=1e-12)
    # there lam1(D0) is not monotone; the result is the equilibrium (matched above), which
    # uniaxial_D0 (one state per lam1) need not return: its D0 at lam1[1] is 1.38, not 2
    lam1 = an.uniaxial_lam1(np.array([0.0, 2.0, 6.0]), 10.0, an.Gent(20.0))  # 3.8596, 3.8620, 3.8499
    assert lam1[1] > lam1[0] and lam1[2] < lam1[1]


def test_gent_uniaxial_lam1_conventions():
    """Scalar in, scalar out; broadcasting; only D0^2 matters; D0 = s = 0 is the reference
    state; non-finite input raises like the other models."""
    out = an.uniaxial_lam1(2.0, 1.0, GENT)
    assert np.ndim(out) == 0
    assert an.uniaxial_lam1(0.0, 0.0, GENT) == 1.0  # Cardano at xi = 1: u = cbrt(1) exactly
    D0 = np.linspace(0, 5, 11)[:, None]
    s = np.array([-1.0, 0.0, 1.0])
    lam1 = an.uniaxial_lam1(D0, s, GENT)
    assert lam1.shape == (11, 3)
    for j, sj in enumerate(s):  # column j equals the scalar-s evaluation, bit for bit
        np.testing.assert_array_equal(lam1[:, j], an.uniaxial_lam1(D0[:, 0], sj, GENT))
    np.testing.assert_array_equal(an.uniaxial_lam1(-D0, s, GENT), lam1)
    with pytest.raises(ValueError, match=r"D0 must be finite"):
        an.uniaxial_lam1(np.inf, 1.0, GENT)
    with pytest.raises(ValueError, match=r"s must not be NaN"):
        an.uniaxial_lam1(1.0, np.nan, GENT)


# ----------------------------------------------------------------------------- biaxial
@pytest.mark.parametrize("model", MODELS, ids=IDS)
def test_biaxial_stretches_equilibrium(model):
    """General (s1, s3, D0): the stresses d omega*/d lam_i (FD) equal the loads."""
    s1 = np.array([0.0, 1.0, 2.0, -0.3, 0.5])
    s3 = np.array([0.0, 0.3, 1.5, 0.2, -0.2])
    D0 = np.array([0.5, 1.0, 2.0, 0.0, 3.0])
    l1, l3 = an.biaxial_stretches(s1, s3, D0, model)
    t1 = d_dx(lambda a: an.omega_star(a, l3, D0, model), l1)
    t3 = d_dx(lambda b: an.omega_star(l1, b, D0, model), l3)
    np.testing.assert_allclose(t1, s1, atol=FD_RTOL * 10)
    np.testing.assert_allclose(t3, s3, atol=FD_RTOL * 10)
    t1a, t3a = an.biaxial_stress(l1, l3, D0, model)
    np.testing.assert_allclose(t1a, s1, atol=1e-12)
    np.testing.assert_allclose(t3a, s3, atol=1e-12)


@pytest.mark.parametrize("model", [None, GENT, QUAD], ids=["neo-Hookean", "Gent", "quadratic"])
def test_biaxial_reduces_to_equibiaxial_and_uniaxial(model):
    D0 = np.linspace(0, 4, 9)
    l1, l3 = an.biaxial_stretches(1.5, 1.5, D0, model)
    lam = an.equibiaxial_lam(D0, 1.5, model)
    np.testing.assert_allclose(l1, lam, rtol=1e-12)
    np.testing.assert_allclose(l3, lam, rtol=1e-12)
    l1, l3 = an.biaxial_stretches(2.0, 0.0, D0, model)
    np.testing.assert_allclose(l3, an.uniaxial_lam3(l1, 2.0, model), rtol=1e-11)


def test_biaxial_E0_is_dDomega():
    l1, l3, D0 = 1.7, 0.8, np.array([0.1, 1.0, 3.0])
    np.testing.assert_allclose(an.biaxial_E0(l1, l3, D0),
                               d_dx(lambda d: an.omega_star(l1, l3, d), D0), rtol=FD_RTOL)


# ----------------------------------------------------------------------------- branches
def test_nan_off_branch():
    # equi-biaxial: below the purely mechanical stretch of s = 1 (D0^2 < 0)
    assert np.isnan(an.equibiaxial_D0(1.0, 1.0))
    assert np.isnan(an.equibiaxial_E0(1.0, 1.0, GENT))
    # uni-axial: lam1 <= s (lam3^2 <= 0), lam1 < 1 at s = 0 (D0^2 < 0)
    for model in (None, GENT, NH_USER):
        assert np.isnan(an.uniaxial_D0(1.5, 2.0, model))
        assert np.isnan(an.uniaxial_lam3(0.9, 0.0, model))
        assert np.isnan(an.uniaxial_E0(1.2, 1.0, model))
    # the mixed array keeps its finite entries
    out = an.uniaxial_D0(np.array([1.5, 3.0]), 2.0)
    assert np.isnan(out[0]) and out[1] == pytest.approx(np.sqrt(81 - 1))


def test_scalar_in_scalar_out_and_broadcasting():
    assert np.ndim(an.equibiaxial_D0(2.0, 1.0)) == 0
    lam = np.linspace(1.5, 3, 4)[:, None]
    s = np.array([0.0, 1.0, 2.0])
    out = an.equibiaxial_D0(lam, s, GENT)
    assert out.shape == (4, 3)
    for j, sj in enumerate(s):  # column j equals the scalar-s evaluation
        np.testing.assert_array_equal(out[:, j], an.equibiaxial_D0(lam[:, 0], sj, GENT))


# ----------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: an.equibiaxial_D0(0.0, 1.0), r"lam must be > 0.*0\.0"),
        (lambda: an.equibiaxial_D0(-1.0, 1.0), r"lam must be > 0.*-1\.0"),
        (lambda: an.equibiaxial_D0(np.nan, 1.0), r"lam must not be NaN"),
        (lambda: an.equibiaxial_D0(2.0, np.nan), r"s must not be NaN"),
        (lambda: an.equibiaxial_E0(8.0, 0.0, an.Gent(97.2)), r"lam = 8\.0 gives I1 = .*Gent limit"),
        (lambda: an.equibiaxial_D0(np.ones(3), np.ones(2)), r"incompatible shapes: lam\(3,\), s\(2,\)"),
        (lambda: an.equibiaxial_lam(np.inf, 1.0), r"D0 must be finite"),
        (lambda: an.equibiaxial_lam(1.0, np.ones(2), None) + an.equibiaxial_lam(np.ones(3), np.ones(2)),
         r"incompatible shapes"),
        (lambda: an.uniaxial_D0(0.0, 1.0), r"lam1 must be > 0"),
        (lambda: an.uniaxial_D0(2.0, np.inf), r"s must be finite"),
        (lambda: an.uniaxial_lam3(10.5, 1.0, an.Gent(97.2)), r"lam1 = 10\.5 gives I1 .*Gent limit"),
        (lambda: an.uniaxial_lam1("abc", 1.0), r"D0 must be a real number"),
        (lambda: an.biaxial_stretches(1.0, np.nan, 1.0), r"s3 must not be NaN"),
        (lambda: an.biaxial_stress(1.0, -2.0, 1.0), r"lam3 must be > 0.*-2\.0"),
        (lambda: an.equibiaxial_D0(2.0, 1.0, model="Gent"), r"model must be an analytic model"),
        (lambda: an.Gent(Jm=-1.0), r"Jm must be a finite number > 0, got -1\.0"),
    ],
)
def test_bad_input_raises_value_error(call, match):
    with pytest.raises(ValueError, match=match):
        call()


@pytest.mark.parametrize("maxiter", [0, -5, 2.5, True, "3", None])
def test_biaxial_stretches_rejects_a_maxiter_that_is_not_a_count(maxiter):
    with pytest.raises(ValueError, match=r"^maxiter must be an integer >= 1, got "
                       + re.escape(repr(maxiter)) + "$"):
        an.biaxial_stretches(1.0, 0.0, 2.0, maxiter=maxiter)


def test_biaxial_stretches_with_a_valid_maxiter_meets_the_closed_form():
    # numpy integers are counts too; Eq. (DEuniax) lam1^2 (lam1 - s) = sqrt(1 + D0^2) at
    # s = 1, D0 = 2 holds to round-off once Newton converged (tolerance 1e-14 |grad|)
    l1, _ = an.biaxial_stretches(1.0, 0.0, 2.0, maxiter=np.int64(50))
    assert abs(l1**2 * (l1 - 1.0) - np.sqrt(5.0)) < 1e-12

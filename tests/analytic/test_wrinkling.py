"""Wrinkling: thin/thick limits (paper Secs. 4-5) and the finite-thickness plate."""

import re

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.optimize import brentq

from analytic import (
    Gent,
    NeoHookean,
    critical_D0,
    critical_D0_biaxial,
    critical_point_on_path,
    dispersion_function,
    equibiaxial_D0,
    equibiaxial_lam,
    surface_impedance,
    surface_instability_stretch,
    thick_limit_D0,
    thick_limit_D0_numeric,
    thick_limit_D0_uniaxial,
    thin_limit_D0,
    thin_limit_D0_uniaxial,
    thin_plate_factors,
    uniaxial_D0,
    uniaxial_lam1,
    uniaxial_lam3,
    wrinkling_map,
)
from analytic.wrinkling import _expm3

NH = NeoHookean()
GENT = Gent(Jm=97.2)
MODELS = [NH, GENT]


def _biot_eta():
    """Real root of eta^3 + eta^2 + 3 eta - 1 = 0, i.e. (1 + eta^2)^2 = 4 eta (Biot)."""
    r = np.roots([1.0, 1.0, 3.0, -1.0])
    return float(r[np.abs(r.imag) < 1e-12].real[0])


# --------------------------------------------------------------------------- D0 = 0
def test_green_zerna_and_biot_surface_instability():
    eta = _biot_eta()
    lam_eq = surface_instability_stretch(NH, "equibiaxial")
    lam_uni = surface_instability_stretch(NH, "uniaxial")
    # eta = lam^3 (equi-biaxial), eta = lam1^(3/2) (uni-axial, lam2 = lam1^-1/2);
    # both are roots found by brentq to ~1e-15
    assert lam_eq == pytest.approx(eta ** (1 / 3), abs=1e-12)
    assert lam_uni == pytest.approx(eta ** (2 / 3), abs=1e-12)
    # literature values quoted with three decimals: 0.666 (Green-Zerna, paper
    # Sec. 4) and 0.444 (Biot, paper Sec. 5) -> half a unit of the last digit
    assert abs(lam_eq - 0.666) < 5e-4
    assert abs(lam_uni - 0.444) < 5e-4
    # the thick-plate limit starts from D0 = 0 there (nan just below)
    assert thick_limit_D0(lam_eq + 1e-6) < 1e-2
    assert np.isnan(thick_limit_D0(lam_eq - 1e-6))


@pytest.mark.parametrize("kh", [0.5, 2.0, 6.0, 12.0, 30.0])
@pytest.mark.parametrize("mode", ["antisymmetric", "symmetric"])
def test_elastic_plate_matches_classical_dispersion_relation(kh, mode):
    """D0 = 0: incompressible neo-Hookean plate, traction-free faces.

    With eta = lam_in/lam2 and H = kh/2 the classical relations (Biot; Ogden &
    Roxburgh 1993 form, re-derived here from the exponential solutions with
    exponents p = 1, eta) are
    flexural:     (1 + eta^2)^2 tanh(H)     = 4 eta tanh(eta H),
    extensional:  (1 + eta^2)^2 tanh(eta H) = 4 eta tanh(H)
    (the trivial root eta = 1 of both is spurious).
    """
    H = kh / 2
    if mode == "antisymmetric":
        classical = lambda e: (1 + e * e) ** 2 * np.tanh(H) - 4 * e * np.tanh(e * H)  # noqa: E731
    else:
        classical = lambda e: (1 + e * e) ** 2 * np.tanh(e * H) - 4 * e * np.tanh(H)  # noqa: E731

    def roots(f, x):
        v = f(x)
        i = np.flatnonzero(np.sign(v[:-1]) != np.sign(v[1:]))
        return np.array([brentq(f, x[j], x[j + 1], xtol=1e-15) for j in i])

    ref = roots(classical, np.linspace(0.02, 0.999, 3000)) ** (1 / 3)  # lam = eta^(1/3)
    num = roots(lambda l: dispersion_function(l, l, 0.0, kh, mode=mode), np.linspace(0.3, 0.999, 400))
    assert len(num) == len(ref)
    # both are brentq roots of smooth functions: agreement to ~1e-14
    np.testing.assert_allclose(num, ref, atol=1e-11)
    if mode == "antisymmetric":
        assert len(ref) == 1  # Euler-type flexural buckling exists for every kh


def test_elastic_plate_uniaxial_direction():
    """Same classical flexural relation with eta = lam1^(3/2) (lam3 = lam1^-1/2)."""
    kh, H = 3.0, 1.5
    classical = lambda e: (1 + e * e) ** 2 * np.tanh(H) - 4 * e * np.tanh(e * H)  # noqa: E731
    eta = brentq(classical, 0.3, 0.999, xtol=1e-15)
    lam1 = brentq(lambda l: dispersion_function(l, l**-0.5, 0.0, kh), 0.3, 0.999, xtol=1e-15)
    assert lam1 == pytest.approx(eta ** (2 / 3), abs=1e-11)


# --------------------------------------------------------------------------- thin limit
@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
def test_thin_limit_closed_forms(model):
    lam = np.array([0.8, 1.0, 1.3, 2.0, 3.0])
    D0 = thin_limit_D0(lam, model)
    I1 = 2 * lam**2 + lam**-4
    if isinstance(model, Gent):  # Eq. (antisym_thin), Gent
        ref = np.sqrt((lam**6 - 1) / (1 - (I1 - 3) / model.Jm) + 0j)
    else:  # Eq. (antisym_thin), neo-Hookean
        ref = np.sqrt(lam**6 - 1 + 0j)
    ref = np.where(np.abs(ref.imag) > 0, np.nan, ref.real)
    np.testing.assert_allclose(D0, ref, rtol=1e-13)  # same algebra, rounding only
    # a - c = 0 on it (Eq. detN3); the other two factors stay positive
    ok = np.isfinite(D0)
    f1, f2, f3 = thin_plate_factors(lam[ok], lam[ok], D0[ok], model)
    assert np.max(np.abs(f1)) < 1e-12 * np.max(lam) ** 2
    lam_g, D_g = np.meshgrid(np.linspace(0.5, 3, 30), np.linspace(0, 40, 30))
    _, f2, f3 = thin_plate_factors(lam_g, lam_g, D_g, model)
    assert np.all(f2 > 0) and np.all(f3 > 0)


def test_thin_limit_uniaxial_neo_hookean():
    lam1 = np.array([1.2, 1.5, 2.5])
    lam3 = np.array([0.95, 0.9, 0.7])
    # Eq. (thin-uni-axial): D0^2 = lam1^4 lam3^2 - 1
    np.testing.assert_allclose(thin_limit_D0_uniaxial(lam1, lam3), np.sqrt(lam1**4 * lam3**2 - 1), rtol=1e-13)
    # perpendicular: lam1 <-> lam3
    np.testing.assert_allclose(
        thin_limit_D0_uniaxial(lam1, lam3, direction="perpendicular"), np.sqrt(lam1**2 * lam3**4 - 1), rtol=1e-13
    )


# --------------------------------------------------------------------------- thick limit
def _shortwave_printed(lam, model):
    """Eqs. (short-wave) and (evalue) as printed, positive root in D0^2."""
    I1 = 2 * lam**2 + lam**-4
    W1, W11 = model.dW(I1), model.d2W(I1)
    r = W11 / W1
    sp = (lam**3 + 1) * np.sqrt(1 + 2 * (lam - lam**-2) ** 2 * r)  # p2 + p3
    B = 2 * W1 * (lam**3 * sp + 2 * (lam**3 - 1))
    C = 4 * W1**2 * (lam**3 * sp**2 - (lam**3 - 1) ** 2)
    return np.sqrt((B + np.sqrt(B**2 + 4 * C)) / 2)


@pytest.mark.parametrize("model", MODELS + [Gent(Jm=10.0)], ids=lambda m: f"{m.name}{getattr(m, 'Jm', '')}")
def test_thick_limit_closed_forms(model):
    lam = np.array([0.7, 1.0, 1.4, 2.0, 2.5])
    D0 = thick_limit_D0(lam, model)
    np.testing.assert_allclose(D0, _shortwave_printed(lam, model), rtol=1e-12)
    if model is NH:  # Eq. (ideal-shortwave), residual relative to its largest term
        x = D0**2
        res = x**2 - (lam**6 + 3 * lam**3 - 2) * x - (lam**9 + lam**6 + 3 * lam**3 - 1)
        assert np.max(np.abs(res) / (x**2 + lam**9)) < 1e-14


def test_thick_limit_uniaxial_neo_hookean_polynomials():
    lam1 = np.array([0.6, 1.0, 1.5, 2.5])
    lam3 = np.array([1.2, 1.0, 0.9, 0.7])
    x = thick_limit_D0_uniaxial(lam1, lam3, direction="parallel") ** 2
    a = lam1**4 * lam3**2
    res = x**2 - (a + 3 * lam1**2 * lam3 - 2) * x - (lam1**6 * lam3**3 + a + 3 * lam1**2 * lam3 - 1)
    assert np.max(np.abs(res) / (x**2 + a**1.5)) < 1e-14  # Eq. (thick-uni-axial)
    x = thick_limit_D0_uniaxial(lam1, lam3, direction="perpendicular") ** 2
    a = lam1**2 * lam3**4
    res = x**2 - (a + 3 * lam1 * lam3**2 - 2) * x - (lam1**3 * lam3**6 + a + 3 * lam1 * lam3**2 - 1)
    assert np.max(np.abs(res) / (x**2 + a**1.5)) < 1e-14  # Eq. (thick-plate23)


CASES = [  # (lam1, lam3, direction)
    (0.7, 0.7, "parallel"),
    (1.0, 1.0, "parallel"),  # neo-Hookean: N defective (p1 = p2 = p3 = 1) at D0 = 0
    (1.3, 1.3, "parallel"),
    (2.2, 2.2, "parallel"),
    (1.8, 1.8**-0.5, "parallel"),
    (1.8, 0.9, "perpendicular"),
    (0.6, 1.3, "parallel"),
]


@pytest.mark.parametrize("control", ["charge", "voltage"])
@pytest.mark.parametrize("model", MODELS + [Gent(Jm=10.0)], ids=lambda m: f"{m.name}{getattr(m, 'Jm', '')}")
def test_thick_limit_numeric_matches_closed_form(model, control):
    l1 = np.array([c[0] for c in CASES])
    l3 = np.array([c[1] for c in CASES])
    for direction in ("parallel", "perpendicular"):
        num = thick_limit_D0_numeric(l1, l3, model, direction, control)
        ref = thick_limit_D0_uniaxial(l1, l3, model, direction, control)
        assert np.array_equal(np.isnan(num), np.isnan(ref))
        ok = np.isfinite(ref)
        assert ok.sum() >= 5
        # bisection to ~1e-14 of a function computed to ~1e-14: issue asks 1e-10
        assert np.max(np.abs(num[ok] - ref[ok]) / np.maximum(1.0, ref[ok])) < 1e-10


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
@pytest.mark.parametrize("state", [(1.0, 1.0, 0.0), (1.0, 1.0, 0.6), (1.4, 1.4, 2.0), (0.8, 1.1, 0.4), (2.5, 0.7, 3.0)])
def test_impedance_hermitian_and_basis_independent(model, state):
    Y = surface_impedance(*state, model)
    Ys = surface_impedance(*state, model, method="schur")
    scale = np.max(np.abs(Y))
    # Stroh theory: i B A^-1 is Hermitian; both bases give it to rounding
    assert np.max(np.abs(Y - Y.conj().T)) < 1e-12 * scale
    assert np.max(np.abs(Ys - Ys.conj().T)) < 1e-12 * scale
    assert np.max(np.abs(Y - Ys)) < 1e-11 * scale


# --------------------------------------------------------------------------- finite thickness
@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
@pytest.mark.parametrize("lam", [1.2, 1.5, 2.0])
def test_critical_D0_thin_and_thick_limits(model, lam):
    thin, thick = thin_limit_D0(lam, model), thick_limit_D0(lam, model)
    kh = np.array([0.01, 0.02, 0.04, 0.08])
    err = critical_D0(lam, kh, model) - thin
    assert np.all(err > 0)
    rate = np.polyfit(np.log(kh), np.log(err), 1)[0]
    assert abs(rate - 2.0) < 0.05  # long-wave correction is O((kh)^2)
    assert err[0] < 2e-4 * thin
    # kh -> inf: corrections decay like exp(-kh min p) with min p = 1 here
    big = critical_D0(lam, np.array([40.0, np.inf]), model)
    np.testing.assert_allclose(big, thick, rtol=1e-10)
    sym = critical_D0(lam, np.array([40.0, np.inf]), model, mode="symmetric")
    np.testing.assert_allclose(sym, thick, rtol=1e-10)
    # in between for all kh: thin < antisymmetric < thick <= symmetric
    khs = np.logspace(-2, 1.5, 15)
    anti = critical_D0(lam, khs, model)
    # (relative 1e-12: at kh ~ 30 the two agree to rounding)
    assert np.all((anti > thin) & (anti < thick * (1 + 1e-12)))
    assert np.all(np.diff(anti) > 0)  # thicker plates need more charge
    sym = critical_D0(lam, khs, model, mode="symmetric")
    assert np.all(np.isnan(sym) | (sym > thick * (1 - 1e-12)))


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
def test_critical_D0_voltage_control_limits(model):
    lam = np.array([1.1, 1.6])
    thin = thin_limit_D0(lam, model)
    thick = thick_limit_D0(lam, model, control="voltage")
    np.testing.assert_allclose(critical_D0(lam, np.inf, model, control="voltage"), thick, rtol=1e-10)
    np.testing.assert_allclose(critical_D0(lam, 50.0, model, control="voltage"), thick, rtol=1e-10)
    # long waves: the same a = c as under charge control, O((kh)^2) away at kh = 0.01
    np.testing.assert_allclose(critical_D0(lam, 0.01, model, control="voltage"), thin, rtol=2e-4)
    # voltage control wrinkles thick plates earlier than charge control
    assert np.all(thick < thick_limit_D0(lam, model))


def test_critical_D0_vectorised_equals_pointwise():
    lam = np.array([[0.9], [1.25], [1.8]])
    kh = np.array([0.3, 3.0, 30.0])
    arr = critical_D0(lam, kh, GENT)
    assert arr.shape == (3, 3)
    for i in range(3):
        for j in range(3):
            one = critical_D0(float(lam[i, 0]), float(kh[j]), GENT)
            # same arithmetic on the same bracket: identical up to rounding
            assert arr[i, j] == pytest.approx(one, rel=1e-12, abs=1e-13, nan_ok=True)


def test_expm3_matches_scipy():
    rng = np.random.default_rng(3)
    A = rng.normal(size=(20, 3, 3)) * rng.uniform(0.01, 40, size=(20, 1, 1)) - 5 * np.eye(3)
    A = -A @ np.swapaxes(A, 1, 2) * 0.05  # stable (decaying) like M kh
    ref = expm(A)
    got = _expm3(A)
    # scaling and squaring, Taylor 12: ~1e-15 relative to the largest entry of exp(A)
    assert np.max(np.abs(got - ref)) < 1e-12 * max(1.0, np.max(np.abs(ref)))


# --------------------------------------------------------------------------- the paper's conclusion
S_EQUI = [0.05, 0.3, 0.8, 1.5, 2.5, 4.5]  # the paper's Fig. gent-equi-biaxial values and a small one


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
def test_no_wrinkling_on_equibiaxial_charge_controlled_loading_curves(model):
    """Fig. gent-equi-biaxial, shown rather than assumed: for s > 0 every point of
    every loading curve lies strictly below the critical D0 of every plate
    thickness (antisymmetric and symmetric modes, kh from 0.01 to inf)."""
    khs = np.concatenate([np.logspace(-2, 2, 10), [np.inf]])
    lams, D0s = [], []
    for s in S_EQUI:
        lam0 = equibiaxial_lam(0.0, s, model)  # start of the curve (D0 = 0)
        lam = lam0 + np.linspace(0.0, 1.5, 16)[1:]
        D0 = equibiaxial_D0(lam, s, model)
        assert np.all(np.isfinite(D0))
        # loading curve below both limits
        assert np.all(D0 < thin_limit_D0(lam, model))
        assert np.all(D0 < thick_limit_D0(lam, model))
        pc = critical_point_on_path(lam, D0, 0.05, model)
        assert np.isnan(pc[0]) and np.isnan(pc[1])
        lams.append(lam)
        D0s.append(D0)
    lam, D0 = np.concatenate(lams), np.concatenate(D0s)
    for mode in ("antisymmetric", "symmetric"):
        crit = critical_D0(lam[:, None], khs[None, :], model, mode=mode)
        # nan = no root below the search bound 2 (lam^3 + 2) sqrt(2 W') > D0
        assert np.all(np.isnan(crit) | (crit > D0[:, None]))
        if mode == "antisymmetric":
            assert np.all(np.isfinite(crit))
            # the binding thickness is kh -> 0: the margin is never below the
            # thin-limit margin (which is > 0 because D0^2 = thin^2 - lam^5 s)
            thin = thin_limit_D0(lam, model)
            assert np.all(crit - D0[:, None] >= (thin - D0)[:, None] * (1 - 1e-9))
    # control (the check can fail): the s = 0.3 curve scaled up by 10 % crosses
    # the thin-plate limit where 0.21 (lam^6 - 1) = 0.363 lam^5 (neo-Hookean)
    lam = equibiaxial_lam(0.0, 0.3, model) + np.linspace(0.0, 2.5, 251)[1:]
    D0 = 1.1 * equibiaxial_D0(lam, 0.3, model)
    lc, Dc = critical_point_on_path(lam, D0, 0.05, model)
    assert lam[0] < lc < lam[-1]
    assert Dc == pytest.approx(critical_D0(lc, 0.05, model), rel=1e-3)  # linear interpolation


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
def test_no_wrinkling_on_uniaxial_charge_controlled_loading_curves(model):
    """Fig. uni-axial-ideal: Keplinger plate s = alpha m g/(mu A), g = 9.81 m/s^2."""
    s_values = np.array([0.05, 0.3, 0.7, 1.0, 1.5]) * 0.150 * 9.81 / (9833.07 * 50e-6)
    for s in s_values:
        lam1 = uniaxial_lam1(0.0, s, model) + np.linspace(0.0, 2.0, 41)[1:]
        D0 = uniaxial_D0(lam1, s, model)
        lam3 = uniaxial_lam3(lam1, s, model)
        assert np.all(np.isfinite(D0)) and np.all(np.isfinite(lam3))
        assert np.all(D0 < thin_limit_D0_uniaxial(lam1, lam3, model, "parallel"))
        assert np.all(D0 < thick_limit_D0_uniaxial(lam1, lam3, model, "parallel"))
        assert np.all(D0 < thick_limit_D0_uniaxial(lam1, lam3, model, "perpendicular"))
        # perpendicular long waves are marginal for every s (t3 = 0 <=> a = c)
        np.testing.assert_allclose(
            thin_limit_D0_uniaxial(lam1, lam3, model, "perpendicular"), D0, rtol=1e-9, atol=1e-9
        )
        # finite thickness (beyond the paper): every plate is strictly stable, the
        # perpendicular flexural margin closing like (kh)^2 as kh -> 0
        sub = slice(None, None, 8)
        khs = np.array([0.01, 0.02, 1.0, 10.0, np.inf])
        for direction in ("parallel", "perpendicular"):
            crit = critical_D0_biaxial(lam1[sub, None], lam3[sub, None], khs[None, :], model,
                                       direction=direction)
            assert np.all(crit > D0[sub, None])
        gap = crit[:, :2] / D0[sub, None] - 1.0  # perpendicular, kh = 0.01 and 0.02
        assert np.all(gap[:, 0] < 1e-4)
        # O((kh)^2): doubling kh quadruples the gap while eta kh is small
        # (eta = lam1 lam3^2 = p2 p3 reaches ~100 at the far end of the heavy
        # paths, where kh = 0.02 is no longer a long wave): check eta kh < 0.25
        eta = lam1[sub] * lam3[sub] ** 2
        long = eta * 0.02 < 0.25
        assert long.sum() >= 1
        np.testing.assert_allclose(gap[long, 1] / gap[long, 0], 4.0, rtol=0.05)


def test_critical_point_on_path_against_root():
    lam = np.linspace(1.0, 1.8, 81)
    D0 = 1.05 * np.sqrt(lam**6 - 1)
    kh = 0.5
    lc, Dc = critical_point_on_path(lam, D0, kh)
    ref = brentq(lambda l: 1.05 * np.sqrt(l**6 - 1) - critical_D0(l, kh), lam[1], lam[-1], xtol=1e-13)
    # linear interpolation between path points 0.01 apart: error O(0.01^2) * curvature
    assert lc == pytest.approx(ref, abs=1e-3)
    assert Dc == pytest.approx(1.05 * np.sqrt(ref**6 - 1), rel=2e-3)


def test_wrinkling_map_region():
    lam = np.array([0.5, 0.8, 1.0, 1.5, 2.5])
    m = wrinkling_map(lam, GENT)
    thin, thick = thin_limit_D0(lam, GENT), thick_limit_D0(lam, GENT)
    assert np.isnan(m.lower[0]) and np.isnan(m.upper[0])  # below Green-Zerna
    assert m.lower[1] == 0.0 and m.upper[1] == thick[1]  # compression: thin plates wrinkle at D0 = 0
    np.testing.assert_array_equal(m.lower[3:], thin[3:])
    np.testing.assert_array_equal(m.upper[3:], thick[3:])


def test_bad_input():
    with pytest.raises(ValueError, match="lam"):
        thin_limit_D0(0.0)
    with pytest.raises(ValueError, match="lam"):
        thick_limit_D0(-1.0)
    with pytest.raises(ValueError, match="kh"):
        critical_D0(1.2, 0.0)
    with pytest.raises(ValueError, match="mode"):
        critical_D0(1.2, 1.0, mode="flexural")
    with pytest.raises(ValueError, match="control"):
        critical_D0(1.2, 1.0, control="current")
    with pytest.raises(ValueError, match="direction"):
        thick_limit_D0_uniaxial(1.2, 0.9, direction="x")
    with pytest.raises(ValueError, match="loading"):
        surface_instability_stretch(loading="shear")
    with pytest.raises(ValueError, match="model"):
        thin_limit_D0(1.2, "neo")


@pytest.mark.parametrize("control", ["charge", "voltage"])
@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
def test_finite_plate_against_transfer_matrix(model, control):
    """Independent of the projector / reflection machinery: the whole plate via the
    transfer matrix exp(K kh) (fine for moderate kh), whose determinant vanishes at
    the antisymmetric and the symmetric roots."""
    from analytic.stroh import stroh_coefficients
    from analytic.wrinkling import _real_K

    lam, kh = 1.3, 2.0
    rows = [3, 4, 5] if control == "charge" else [2, 3, 4]
    free = [i for i in range(6) if i not in rows]  # face data not prescribed

    def full_plate(D0):
        K = _real_K(*stroh_coefficients(lam, lam, D0, model))
        return np.linalg.det(expm(K * kh)[..., rows, :][..., free])  # batched over D0

    roots = []
    for mode in ("antisymmetric", "symmetric"):
        D = critical_D0(lam, kh, model, mode=mode, control=control)
        # the transfer-matrix determinant changes sign across each root
        h = 1e-6 * D
        assert full_plate(D - h) * full_plate(D + h) < 0
        roots.append(brentq(lambda x: float(full_plate(x)), D - h, D + h, xtol=1e-14))
        # exp(K kh) has entries ~exp(p3 kh) ~ 1e3: roots agree to ~1e-12
        assert roots[-1] == pytest.approx(D, rel=1e-10)
    # and no root of the whole plate below the smaller one (smallest-root claim)
    grid = np.linspace(0.0, 0.999 * min(roots), 60)
    vals = full_plate(grid)
    assert np.all(np.sign(vals) == np.sign(vals[0]))


def test_user_model_with_complex_exponents():
    """W'' < 0 makes p2, p3 a complex-conjugate pair (b0^2 < a0 c): the projector
    basis, the Schur basis and the closed form must still agree."""
    from analytic import UserModel, stroh_exponents

    m = UserModel(
        W=lambda I: 0.5 * (I - 3) - 0.05 * (I - 3) ** 2,
        dW=lambda I: 0.5 - 0.1 * (I - 3),
        d2W=lambda I: -0.1 + 0 * I,
        name="softening",
        I1_limit=5.0,
    )
    _, p2, p3 = stroh_exponents(1.2, 1.2, 0.3, m)
    assert abs(complex(p2).imag) > 0.1 and complex(p2) == pytest.approx(np.conj(complex(p3)))
    Y = surface_impedance(1.2, 1.2, 0.3, m)
    Ys = surface_impedance(1.2, 1.2, 0.3, m, method="schur")
    assert np.max(np.abs(Y - Ys)) < 1e-12 * np.max(np.abs(Y))  # rounding only
    assert thick_limit_D0_numeric(1.2, 1.2, m) == pytest.approx(thick_limit_D0(1.2, m), rel=1e-10)


def test_compressed_plate_semantics():
    """lam < 1: thin plates buckle without charge (no root in D0 -> nan), thick ones
    wrinkle at some D0 below the thick-plate limit. Reference for the first claim:
    the classical flexural relation puts the D0 = 0 buckling stretch of kh = 0.5
    at lam = 0.98709 > 0.9."""
    assert np.isnan(critical_D0(0.9, 0.5))
    assert np.isnan(thin_limit_D0(0.9))
    D = critical_D0(0.9, 10.0)
    assert 0.0 < D < thick_limit_D0(0.9)
    # and it is a genuine root of the dispersion relation (sign change within 1e-9)
    assert dispersion_function(0.9, 0.9, D * (1 - 1e-9), 10.0) * dispersion_function(0.9, 0.9, D * (1 + 1e-9), 10.0) < 0


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
def test_symmetric_long_waves_are_the_homogeneous_instability(model):
    """kh -> 0 symmetric modes are homogeneous plane-strain (u3 = 0) thickness
    changes. Under voltage control they appear where the Hessian of
    omega(lam1, lam3, E0) = W(I1) - lam1^2 lam3^2 E0^2 / 2 (Sec. 3) loses
    positivity in lam1 at fixed lam3 and E0 (neo-Hookean: D0^2 = lam^6 + 3);
    under charge control omega*_11 > 0 and there is no such root (second factor
    of Eq. detN3 > 0): the symmetric root recedes like 1/kh, far above the
    search bound at kh = 0.01."""
    lam = np.array([1.0, 1.5, 2.0])
    h = 1e-4

    def w(l1):
        return model.W(l1**2 + lam**2 + (l1 * lam) ** -2)

    w11 = (w(lam + h) - 2 * w(lam) + w(lam - h)) / h**2  # central FD, error ~1e-7
    D0_ref = lam**4 * np.sqrt(w11 / lam**2)  # omega_11 = w11 - lam3^2 E0^2 = 0
    if model is NH:
        np.testing.assert_allclose(D0_ref, np.sqrt(lam**6 + 3), rtol=1e-6)
    got = critical_D0(lam, 0.01, model, mode="symmetric", control="voltage")
    # O((kh)^2) = 1e-4 long-wave correction (observed 1e-6 .. 4e-6) plus FD error
    np.testing.assert_allclose(got, D0_ref, rtol=2e-5)
    assert np.all(np.isnan(critical_D0(lam, 0.01, model, mode="symmetric", control="charge")))


@pytest.mark.parametrize("lam", [1e6, 1e-4])
def test_critical_D0_names_its_own_lam_when_the_stretch_overflows(lam):
    # the computation runs in critical_D0_biaxial(lam1=lam, lam3=lam, ...); the message
    # names the argument the user passed
    with pytest.raises(ValueError, match=r"^lam must be of a size for which critical_D0 is "
                       r"representable in double precision \(a step of the computation "
                       r"overflows\), got " + re.escape(repr(lam)) + "$"):
        critical_D0(lam, 2.0)


def test_critical_D0_is_representable_over_the_documented_stretches():
    khs = [1e-3, 1.0, 1e3, 1e6, np.inf]
    # lam = 0.05 is far below the Green-Zerna stretch 0.666: the plate wrinkles without
    # charge at every kh, so there is no root (nan), and no step overflows
    assert all(np.isnan(critical_D0(0.05, kh)) for kh in khs)
    # lam = 10: short waves tend to Eq. (short-wave); the scan and regula falsi reach
    # ~1e-14 relative and exp(-p kh) at kh = 1e3 is far below round-off, 1e-9 allows for
    # the root finder's stopping rule on either side
    thick = thick_limit_D0(10.0)
    for kh in khs[2:]:
        assert abs(critical_D0(10.0, kh) - thick) <= 1e-9 * thick
    # long waves tend to Eq. (antisym_thin): the correction is O(kh^2), 1e-6 relative at
    # kh = 1e-3
    assert abs(critical_D0(10.0, 1e-3) - thin_limit_D0(10.0)) <= 1e-6 * thin_limit_D0(10.0)

"""Hessians, stability verdicts and voltage limits (analytic.hessian) against independent references.

References: second-order finite differences of the energies omega*, omega (built
from W only), the paper's printed neo-Hookean formulas (Sec. 3.1 and 5), the
Legendre-transform identities, the literature value E0max = sqrt(3)/2^(4/3) at
lam = 2^(1/3) (neo-Hookean, s = 0), and brute-force maxima of E0 on fine grids.
"""

from __future__ import annotations

import numpy as np
import pytest

import analytic as an

QUAD = an.UserModel(
    W=lambda I: 0.5 * (I - 3.0) + 0.01 * (I - 3.0) ** 2,
    dW=lambda I: 0.5 + 0.02 * (I - 3.0),
    d2W=lambda I: 0.02 + 0.0 * I,
    name="quadratic",
)
NH_USER = an.UserModel(
    W=lambda I: 0.5 * (I - 3.0), dW=lambda I: 0.5 + 0.0 * I, d2W=lambda I: 0.0 * I, name="nh-user"
)
GENT = an.Gent(97.2)
MODELS = [None, GENT, QUAD]
IDS = ["neo-Hookean", "Gent", "quadratic"]

# Second differences with h = 1e-4: truncation h^2 f''''/12 ~ 1e-9, round-off
# 4 eps |omega| / h^2 ~ 1e-7 for |omega| ~ 10 -> compare to 1e-5 of the entry scale.
H2 = 1e-4
FD2_TOL = 1e-5

PTS = [(1.3, 0.9, 0.7), (2.0, 1.5, 2.5), (0.8, 1.2, 0.3), (3.0, 2.0, 6.0)]


def fd_hessian(f, x, h=H2):
    """Full FD Hessian of a scalar function of an n-vector (central, 4-point mixed)."""
    n = len(x)
    Hm = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            ei, ej = np.eye(n)[i] * h, np.eye(n)[j] * h
            Hm[i, j] = (f(x + ei + ej) - f(x + ei - ej) - f(x - ei + ej) + f(x - ei - ej)) / (4 * h * h)
    return Hm


@pytest.mark.parametrize("model", MODELS, ids=IDS)
@pytest.mark.parametrize("pt", PTS)
def test_hessians_match_fd_of_energies(model, pt):
    x = np.array(pt)
    Hs = an.hessian_omega_star(*pt, model)
    Hfd = fd_hessian(lambda v: float(an.omega_star(v[0], v[1], v[2], model)), x)
    np.testing.assert_allclose(Hs, Hfd, atol=FD2_TOL * np.abs(Hs).max())
    E0 = pt[2] / (pt[0] * pt[1]) ** 2
    xe = np.array([pt[0], pt[1], E0])
    He = an.hessian_omega(*xe, model)
    Hfd = fd_hessian(lambda v: float(an.omega(v[0], v[1], v[2], model)), xe)
    np.testing.assert_allclose(He, Hfd, atol=FD2_TOL * np.abs(He).max())


@pytest.mark.parametrize("model", MODELS, ids=IDS)
@pytest.mark.parametrize("lam, D0", [(1.0, 1.0), (1.6, 2.0), (0.8, 0.4), (3.0, 9.0)])
def test_equibiaxial_hessians_match_fd(model, lam, D0):
    f = lambda v: float(an.equibiaxial_omega_star(v[0], v[1], model))  # noqa: E731
    x = np.array([lam, D0])
    Hfd = fd_hessian(f, x)
    Hs = an.equibiaxial_hessian_omega_star(lam, D0, model)
    np.testing.assert_allclose(Hs, Hfd, atol=FD2_TOL * np.abs(Hs).max())
    E0 = D0 / lam**4
    g = lambda v: float(an.equibiaxial_omega(v[0], v[1], model))  # noqa: E731
    x = np.array([lam, E0])
    Hfd = fd_hessian(g, x)
    He = an.equibiaxial_hessian_omega(lam, E0, model)
    np.testing.assert_allclose(He, Hfd, atol=FD2_TOL * np.abs(He).max())


def test_neo_hookean_printed_equibiaxial_formulas():
    """Sec. 3.1: omega*_ll, omega_ll, mixed terms and both determinants as printed."""
    lam = np.linspace(0.7, 3.0, 9)[:, None]
    D0 = np.linspace(0.0, 4.0, 5)[None, :]
    E0 = D0 / lam**4
    Hs = an.equibiaxial_hessian_omega_star(lam, D0)
    He = an.equibiaxial_hessian_omega(lam, E0)
    tol = dict(rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(Hs[..., 0, 0], 2 * (1 + 5 * lam**-6 + 5 * lam**-6 * D0**2), **tol)
    np.testing.assert_allclose(Hs[..., 0, 1], -4 * lam**-5 * D0, **tol)
    np.testing.assert_allclose(Hs[..., 1, 1], np.broadcast_to(lam**-4, Hs[..., 1, 1].shape), **tol)
    np.testing.assert_allclose(He[..., 0, 0], 2 * (1 + 5 * lam**-6 - 3 * lam**2 * E0**2), **tol)
    np.testing.assert_allclose(He[..., 0, 1], -4 * lam**3 * E0, **tol)
    np.testing.assert_allclose(np.linalg.det(Hs), 2 * lam**-10 * (lam**6 + 5 - 3 * D0**2), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(np.linalg.det(He), -2 * lam**4 * (1 + 5 * lam**-6 + 5 * lam**2 * E0**2),
                               rtol=1e-12)


@pytest.mark.parametrize("model", MODELS, ids=IDS)
def test_legendre_identities(model):
    """det H* = -omega_ll/omega_EE and det H = omega*_ll omega_EE (Sec. 3.1), and the 3x3
    analogues det H* = -det K/omega_EE, det H = det K* omega_EE (K, K*: mechanical blocks)."""
    lam = np.linspace(0.8, 2.5, 7)[:, None]
    D0 = np.linspace(0.0, 3.0, 4)[None, :]
    E0 = D0 / lam**4
    Hs = an.equibiaxial_hessian_omega_star(lam, D0, model)
    He = an.equibiaxial_hessian_omega(lam, E0, model)
    scale = np.abs(Hs[..., 0, 0] * Hs[..., 1, 1])  # size of the cancelling products
    np.testing.assert_allclose(np.linalg.det(Hs), -He[..., 0, 0] / He[..., 1, 1], atol=1e-13 * scale.max())
    scale = np.abs(He[..., 0, 0] * He[..., 1, 1]) + He[..., 0, 1] ** 2
    np.testing.assert_allclose(np.linalg.det(He), Hs[..., 0, 0] * He[..., 1, 1], atol=1e-13 * scale.max())
    l1 = np.array([1.2, 2.0, 0.9])
    l3 = np.array([0.8, 1.4, 1.1])
    D0 = np.array([0.5, 2.0, 1.0])
    E0 = D0 / (l1 * l3) ** 2
    Hs = an.hessian_omega_star(l1, l3, D0, model)
    He = an.hessian_omega(l1, l3, E0, model)
    detK = np.linalg.det(He[:, :2, :2])
    detKs = np.linalg.det(Hs[:, :2, :2])
    np.testing.assert_allclose(np.linalg.det(Hs), -detK / He[:, 2, 2], rtol=1e-11)
    np.testing.assert_allclose(np.linalg.det(He), detKs * He[:, 2, 2], rtol=1e-11)


def test_leading_minors_and_printed_charge_minor():
    """Sec. 5: det of the leading 2x2 minor of H* (neo-Hookean) and its equi-biaxial factorisation."""
    l1 = np.array([1.2, 2.0, 0.9, 3.0])
    l3 = np.array([0.8, 1.4, 1.1, 3.0])
    D0 = np.array([0.5, 2.0, 1.0, 4.0])
    q = 1 + D0**2
    m = an.leading_minors(an.hessian_omega_star(l1, l3, D0))
    printed = 1 + 3 * (l1 * l3) ** -4 * (l1**2 + l3**2) * q + 5 * (l1 * l3) ** -6 * q**2
    np.testing.assert_allclose(m[:, 1], printed, rtol=1e-13)
    lam = l1[-1]  # equi-biaxial point: [1 + 5 lam^-6 (1+D0^2)] [1 + lam^-6 (1+D0^2)]
    np.testing.assert_allclose(m[-1, 1], (1 + 5 * lam**-6 * q[-1]) * (1 + lam**-6 * q[-1]), rtol=1e-14)
    np.testing.assert_allclose(m[:, 0], an.hessian_omega_star(l1, l3, D0)[:, 0, 0], rtol=1e-15)
    np.testing.assert_allclose(m[:, 2], np.linalg.det(an.hessian_omega_star(l1, l3, D0)), rtol=1e-12)


# ----------------------------------------------------------------------------- voltage limits
@pytest.mark.parametrize("model", MODELS, ids=IDS)
def test_voltage_limit_is_det_H_star_zero(model):
    lam = np.linspace(0.8, 4.0, 17)
    D0 = an.voltage_limit_D0(lam, model)
    Hs = an.equibiaxial_hessian_omega_star(lam, D0, model)
    scale = Hs[:, 0, 0] * Hs[:, 1, 1]
    np.testing.assert_allclose(np.linalg.det(Hs) / scale, 0.0, atol=1e-13)
    np.testing.assert_allclose(an.voltage_limit_E0(lam, model), D0 / lam**4, rtol=1e-15)
    if model is None:  # Sec. 3.1 / Fig. nh-d-e: D0 = sqrt((lam^6+5)/3)
        np.testing.assert_allclose(D0, np.sqrt((lam**6 + 5) / 3), rtol=1e-14)
        np.testing.assert_allclose(an.voltage_limit_E0(lam), np.sqrt((lam**-2 + 5 * lam**-8) / 3), rtol=1e-14)


def test_literature_value_neo_hookean_s0():
    """E0max = sqrt(3)/2^(4/3) at lam = 2^(1/3) (neo-Hookean, s = 0), both loadings."""
    for loading in ("equibiaxial", "uniaxial"):
        lam, E0 = an.max_E0(0.0, loading=loading)
        assert lam == pytest.approx(2 ** (1 / 3), rel=1e-14)
        assert E0 == pytest.approx(np.sqrt(3) / 2 ** (4 / 3), rel=1e-14)


def _brute_max(f, x):
    y = f(x)
    d = np.diff(y)
    k = np.flatnonzero((d[:-1] > 0) & (d[1:] <= 0))
    return (x[k[0] + 1], y[k[0] + 1]) if k.size else (np.nan, np.nan)


@pytest.mark.parametrize("model", [None, GENT, QUAD, NH_USER], ids=IDS + ["nh-user"])
@pytest.mark.parametrize("loading", ["equibiaxial", "uniaxial"])
def test_max_E0_against_brute_force(model, loading):
    """The first maximum of E0 on a 5e4-point grid: spacing h ~ 1.2e-4 locates lam to 2h and
    E0 to E0'' h^2/2 ~ 1e-8 relative (1e-7 asserted)."""
    s = np.array([0.0, 1.0, 1.9])
    lam_m, E_m = an.max_E0(s, model, loading=loading)
    curve = an.equibiaxial_E0 if loading == "equibiaxial" else an.uniaxial_E0
    start = an.equibiaxial_lam if loading == "equibiaxial" else an.uniaxial_lam1
    for j, sj in enumerate(s):
        l0 = float(start(0.0, sj, model))
        top = 6.9 if model is GENT and loading == "equibiaxial" else l0 + 6.0  # Gent lock at 7.08
        x = np.linspace(l0 * (1 + 1e-9), top, 50001)
        lb, Eb = _brute_max(lambda v: curve(v, sj, model), x)
        assert lam_m[j] == pytest.approx(lb, abs=2 * (x[1] - x[0]))
        assert E_m[j] == pytest.approx(Eb, rel=1e-7)


def test_max_E0_neo_hookean_closed_forms():
    """Equi-biaxial: 2 lam^6 - 3 s lam^5 - 8 = 0; uni-axial: 4 lam1 - 3 s - lam1^4 (lam1-s)^3 = 0."""
    s = np.linspace(-1.0, 4.0, 11)
    lam, E0 = an.max_E0(s)
    # cancellation between terms of size 2 lam^6 ~ 1e4: compare to the term size
    np.testing.assert_allclose(2 * lam**6 - 3 * s * lam**5, 8.0, atol=1e-14 * np.max(2 * lam**6 + 3 * np.abs(s) * lam**5))
    np.testing.assert_allclose(E0, an.voltage_limit_E0(lam), rtol=1e-12)  # on the dashed curve
    lam1, E0 = an.max_E0(s, loading="uniaxial")
    np.testing.assert_allclose(4 * lam1 - 3 * s, lam1**4 * (lam1 - s) ** 3, rtol=1e-12)
    np.testing.assert_allclose(E0, an.uniaxial_voltage_limit_E0(lam1), rtol=1e-10)  # Fig. figde(b)


def test_gent_no_maximum_threshold():
    """Fig. gent-d-e: above s* the E0 curves have no maximum (brute force on each side)."""
    for loading, curve in (("equibiaxial", an.equibiaxial_E0), ("uniaxial", an.uniaxial_E0)):
        s_star = an.no_maximum_threshold(GENT, loading)
        hi = 6.9 if loading == "equibiaxial" else 9.9  # below the Gent locking stretch
        for ds, has_max in ((-0.01, True), (+0.01, False)):
            s = s_star + ds
            start = an.equibiaxial_lam if loading == "equibiaxial" else an.uniaxial_lam1
            x = np.linspace(float(start(0.0, s, GENT)) * (1 + 1e-9), hi, 50001)
            lb, _ = _brute_max(lambda v: curve(v, s, GENT), x)
            assert np.isfinite(lb) == has_max
            assert np.isfinite(an.max_E0(s, GENT, loading)[0]) == has_max
    # the paper's curves: s = 0, 1 have a maximum, s = 2.3 and 3 none (s = 2 almost touches)
    s_star = an.no_maximum_threshold(GENT)
    assert 2.0 < s_star < 2.3
    assert an.no_maximum_threshold(None) == np.inf


# ----------------------------------------------------------------------------- uni-axial locus
def test_uniaxial_printed_det_H_star_on_path_only():
    """Sec. 5: det H* = 4 lam1^-6 lam3^-6 (3 lam3^2 + lam1^2 - lam1^2 lam3^6) holds on the
    uni-axial path (D0^2 = lam1^2 lam3^4 - 1) and not for arbitrary (lam1, lam3, D0)."""
    printed = lambda a, b: 4 * a**-6 * b**-6 * (3 * b**2 + a**2 - a**2 * b**6)  # noqa: E731
    lam1 = np.linspace(2.6, 4.0, 11)  # on all three branches
    for s in (0.0, 1.0, 2.0):
        l3 = an.uniaxial_lam3(lam1, s)
        D0 = an.uniaxial_D0(lam1, s)
        det = np.linalg.det(an.hessian_omega_star(lam1, l3, D0))
        np.testing.assert_allclose(det, printed(lam1, l3), rtol=1e-10, atol=1e-13)
    det_off = np.linalg.det(an.hessian_omega_star(2.0, 1.0, 1.0))
    assert abs(det_off - printed(2.0, 1.0)) > 0.1 * abs(printed(2.0, 1.0))


@pytest.mark.parametrize("model", [None, NH_USER, GENT, QUAD], ids=["neo-Hookean", "nh-user", "Gent", "quadratic"])
def test_uniaxial_voltage_limit_locus(model):
    lam1 = np.linspace(1.1, 5.0, 14)
    l3 = an.uniaxial_voltage_limit_lam3(lam1, model)
    D0 = an.uniaxial_voltage_limit_D0(lam1, model)
    E0 = an.uniaxial_voltage_limit_E0(lam1, model)
    # it lies on a uni-axial path: t3 = 0 (by FD of omega*, independent of the solver)
    h = 1e-6
    t3 = (an.omega_star(lam1, l3 + h, D0, model) - an.omega_star(lam1, l3 - h, D0, model)) / (2 * h)
    np.testing.assert_allclose(t3, 0.0, atol=1e-7 * (1 + D0**2).max())
    # and det H* = 0 there
    Hs = an.hessian_omega_star(lam1, l3, D0, model)
    np.testing.assert_allclose(np.linalg.det(Hs) / np.abs(Hs[:, 0, 0] * Hs[:, 1, 1] * Hs[:, 2, 2]), 0.0,
                               atol=1e-10)
    np.testing.assert_allclose(E0, D0 / (lam1 * l3) ** 2, rtol=1e-14)
    if model is None or model is NH_USER:  # lam1^2 + 3 lam3^2 - lam1^2 lam3^6 = 0
        np.testing.assert_allclose(lam1**2 + 3 * l3**2 - lam1**2 * l3**6, 0.0, atol=1e-12 * lam1.max() ** 2)


# ----------------------------------------------------------------------------- verdicts
def test_verdicts_neo_hookean():
    """Charge control always stable (Secs. 3.1, 5); voltage control stable iff D0^2 < (lam^6+5)/3."""
    lam = np.linspace(0.6, 4.0, 35)[:, None]
    D0 = np.linspace(0.0, 40.0, 41)[None, :]
    assert np.all(an.equibiaxial_stability_verdict(lam, D0, control="charge"))
    v = an.equibiaxial_stability_verdict(lam, D0, control="voltage")
    np.testing.assert_array_equal(v, D0**2 < (lam**6 + 5) / 3)
    l3 = np.linspace(0.6, 3.0, 9)[None, :, None]
    assert np.all(an.stability_verdict(lam[..., None], l3, D0[:, None, :], control="charge"))


@pytest.mark.parametrize("model", [None, GENT], ids=["neo-Hookean", "Gent"])
def test_uniaxial_voltage_verdict_flips_at_E0_maximum(model):
    s = 1.0
    lam1_m, _ = an.max_E0(s, model, loading="uniaxial")
    lam1 = lam1_m * np.array([0.99, 1.01])
    l3 = an.uniaxial_lam3(lam1, s, model)
    D0 = an.uniaxial_D0(lam1, s, model)
    assert an.stability_verdict(lam1, l3, D0, model, control="voltage").tolist() == [True, False]
    assert an.stability_verdict(lam1, l3, D0, model, control="charge").tolist() == [True, True]


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: an.max_E0(1.0, loading="biaxial"), r"loading must be one of .*'biaxial'"),
        (lambda: an.no_maximum_threshold(GENT, loading="shear"), r"loading must be one of"),
        (lambda: an.stability_verdict(1.0, 1.0, 1.0, control="current"), r"control must be one of .*'current'"),
        (lambda: an.equibiaxial_stability_verdict(-1.0, 1.0), r"lam must be > 0"),
        (lambda: an.hessian_omega_star(1.0, 0.0, 1.0), r"lam3 must be > 0"),
        (lambda: an.hessian_omega(1.0, 1.0, np.nan), r"E0 must not be NaN"),
        (lambda: an.voltage_limit_D0(8.0, GENT), r"lam = 8\.0 gives I1"),
        (lambda: an.uniaxial_voltage_limit_D0(11.0, GENT), r"lam1 = 11\.0 gives I1"),
        (lambda: an.leading_minors(np.ones((2, 3))), r"H must have shape \(\.\.\., n, n\)"),
        (lambda: an.max_E0(np.nan), r"s must not be NaN"),
        (lambda: an.omega_star(np.ones(2), np.ones(3), 1.0), r"incompatible shapes"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()

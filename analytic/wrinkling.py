"""Wrinkling of charged dielectric plates: thin/thick limits and finite thickness.

Incremental (geometric) stability of Sections 4 and 5 of the paper, for any
``W(I1)`` model, built on :mod:`analytic.stroh`:

* thin-plate limit ``det N3 = 0`` (Eq. detN3) and its closed forms
  (Eq. antisym_thin), (Eq. thin-uni-axial);
* thick-plate (half-space) limit ``det(i B A^-1) = 0`` (Eq. detStroh), both
  numerically from a basis of the decaying invariant subspace of ``N`` and in
  closed form, Eqs. (short-wave), (evalue), (ideal-shortwave),
  (thick-uni-axial), (thick-plate23), generalised here to any ``W(I1)`` and any
  ``(lam1, lam3)``;
* beyond the paper: the exact dispersion relation of a plate of deformed
  thickness ``h`` with traction-free faces under charge control (``Delta = 0``
  on the faces) or voltage control (``Phi = 0``), split into antisymmetric
  (flexural) and symmetric (extensional) modes, and the critical ``D0`` as a
  function of ``(lam, kh)``.

Numerical method (finite thickness)
-----------------------------------
With ``G = diag(i, 1, 1, 1, i, i)`` the system ``eta' = i N eta`` becomes the real
system ``xi' = K xi``, ``K = G^-1 (i N) G``. The spectral projector onto the
decaying invariant subspace is ``P = (I - sign K)/2`` with
``sign K = K (K^2)^(-1/2)``; ``(K^2)^(-1/2)`` is the Hermite interpolation
polynomial of ``x^(-1/2)`` at the nodes ``1, p2^2, p3^2`` written with divided
differences that never cancel, so coincident exponents (neo-Hookean
``p2 = 1``, and ``lam = 1`` where all three coincide and ``N`` is defective)
need no special case; two Newton steps of the sign iteration polish it. The
subspace is represented as ``[I; Z]`` (``Z = B A^-1`` in real form), on which
``K`` acts as ``M = K_AA + K_AB Z`` with eigenvalues ``-1, -p2, -p3``.
Reflection ``x2 -> -x2`` maps decaying to growing solutions
(``T K T = -K``, ``T = diag(1, -1, -1, -1, 1, 1)``), so on the half plate
``0 <= k x2 <= kh/2`` the symmetric/antisymmetric split reduces the 6x6
determinant exactly to the 3x3 function::

    g(kh) = det( R (T V - sigma V exp(M kh)) ),   V = [I; Z],

``sigma = +1`` antisymmetric, ``-1`` symmetric, ``R`` the rows of the face
conditions. Only decaying exponentials occur, so nothing overflows for any
``kh``; ``g(inf)`` is the half-space condition.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import schur

from ._checks import as_array, broadcast, check_choice, check_finite, check_positive
from ._output import representable, scalar_or_array
from ._roots import brent, first_root_on_scan
from ._stroh_core import coefficients, coefficients_fast, exponents_from_coefficients, stroh_N
from .models import Model, as_model

__all__ = [
    "thin_plate_factors",
    "thin_limit_D0",
    "thin_limit_D0_uniaxial",
    "thick_limit_D0",
    "thick_limit_D0_uniaxial",
    "thick_limit_D0_numeric",
    "surface_impedance",
    "surface_instability_stretch",
    "dispersion_function",
    "critical_D0",
    "critical_D0_biaxial",
    "critical_point_on_path",
    "WrinklingMap",
    "wrinkling_map",
]

_DIRECTIONS = ("parallel", "perpendicular")
_MODES = ("antisymmetric", "symmetric")
_CONTROLS = ("charge", "voltage")
_T = np.array([1.0, -1.0, -1.0, -1.0, 1.0, 1.0])
_ROWS = {"charge": [3, 4, 5], "voltage": [2, 3, 4]}


# ---------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------
def _in_plane(lam1, lam3, direction):
    """``(lam_in, lam2)`` for the wrinkle plane."""
    lam2 = 1.0 / (lam1 * lam3)
    return (lam1 if direction == "parallel" else lam3), lam2


def _W_derivs(lam1, lam3, model):
    lam2 = 1.0 / (lam1 * lam3)
    I1 = lam1**2 + lam2**2 + lam3**2
    return model.dW(I1), model.d2W(I1)


def _sqrt_or_nan(x):
    x = np.asarray(x, dtype=float)
    out = np.full_like(x, np.nan)
    ok = x >= 0
    out[ok] = np.sqrt(x[ok])
    return out


# ---------------------------------------------------------------------------
# thin-plate limit
# ---------------------------------------------------------------------------
@representable
def thin_plate_factors(lam1, lam3, D0, model: Model | None = None, direction: str = "parallel"):
    """The three factors of ``det N3`` (Eq. detN3).

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (``> 0``).
    D0 : array_like
        Dimensionless electric displacement.
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    direction : {"parallel", "perpendicular"}
        Plane of the wrinkles.

    Returns
    -------
    antisymmetric, symmetric, third : ndarray
        ``a - c``, ``b + c + 2 d^2`` and ``d^2 + c``; ``det N3 =
        2 (a - c)(b + c + 2 d^2)(d^2 + c)/c`` (Eq. detN3 quotes the factors). The first vanishes
        on Eq. (antisym_thin); the other two are positive for every real state.

    Examples
    --------
    >>> from analytic.wrinkling import thin_plate_factors
    >>> [round(float(f), 12) for f in thin_plate_factors(1.0, 1.0, 0.0)]
    [0.0, 2.0, 1.0]
    """
    check_choice("direction", direction, _DIRECTIONS)
    a, b, c, d = coefficients(lam1, lam3, D0, model, direction)
    return scalar_or_array(a - c, b + c + 2.0 * d**2, d**2 + c)


@representable
def thin_limit_D0(lam, model: Model | None = None):
    """Thin-plate (long-wave) wrinkling limit of an equi-biaxially stretched plate.

    Parameters
    ----------
    lam : array_like
        Equi-biaxial stretch (``> 0``).
    model : Model, optional
        Strain-energy model; default neo-Hookean.

    Returns
    -------
    D0 : float or ndarray
        ``D0 = sqrt(2 W' (lam^6 - 1))``, the antisymmetric factor ``a = c`` of
        Eq. (detN3); ``nan`` for ``lam < 1`` (no real solution: the plate is in
        compression and long waves are unstable at every ``D0``).

    Notes
    -----
    Eq. (antisym_thin): ``sqrt(lam^6 - 1)`` (neo-Hookean) and
    ``sqrt((lam^6 - 1)/(1 - (2 lam^2 + lam^-4 - 3)/Jm))`` (Gent); it equals the
    ``s = 0`` loading curve (Eq. loading_gent). The symmetric and third factors
    of Eq. (detN3) have no real roots. Valid under charge and voltage control.

    Examples
    --------
    >>> from analytic import thin_limit_D0
    >>> round(thin_limit_D0(1.2), 10)
    1.4092494456
    """
    lam = check_positive("lam", lam)
    return thin_limit_D0_uniaxial(lam, lam, model, "parallel")


@representable
def thin_limit_D0_uniaxial(lam1, lam3, model: Model | None = None, direction: str = "parallel"):
    """Thin-plate limit ``a = c`` for general in-plane stretches ``(lam1, lam3)``.

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (``> 0``).
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    direction : {"parallel", "perpendicular"}
        Plane of the wrinkles.

    Returns
    -------
    D0 : float or ndarray
        ``D0 = sqrt(2 W' (eta^2 - 1))`` with ``eta = lam_in/lam2``
        (``lam_in = lam1`` parallel, ``lam3`` perpendicular); ``nan`` where
        ``eta < 1``.

    Notes
    -----
    Eq. (thin-uni-axial): ``D0^2 = lam1^4 lam3^2 - 1`` for neo-Hookean parallel
    wrinkles. For perpendicular wrinkles ``D0^2 = 2 W' (lam1^2 lam3^4 - 1)``
    coincides with the ``t3 = 0`` condition of the uni-axial loading curve for
    every ``s``, not only for ``s = 0``: perpendicular long waves are marginal on
    every uni-axial path.

    Examples
    --------
    >>> from analytic import thin_limit_D0_uniaxial
    >>> round(thin_limit_D0_uniaxial(1.5, 0.9), 10)
    1.7608591653
    """
    check_choice("direction", direction, _DIRECTIONS)
    model = as_model(model)
    lam1 = check_positive("lam1", lam1)
    lam3 = check_positive("lam3", lam3)
    lam1, lam3 = broadcast(lam1=lam1, lam3=lam3)
    lam_in, lam2 = _in_plane(lam1, lam3, direction)
    W1, _ = _W_derivs(lam1, lam3, model)
    return scalar_or_array(_sqrt_or_nan(2.0 * W1 * ((lam_in / lam2) ** 2 - 1.0)))


# ---------------------------------------------------------------------------
# thick-plate limit, closed forms
# ---------------------------------------------------------------------------
def _thick_coefficients(lam1, lam3, model, direction):
    """``(B, C, S, eta, W1)`` with ``D0^4 - B D0^2 - C = 0`` (Eq. short-wave)."""
    lam_in, lam2 = _in_plane(lam1, lam3, direction)
    W1, W11 = _W_derivs(lam1, lam3, model)
    eta = lam_in / lam2  # = p2 p3
    # (p2 + p3)^2 = 2 b0/c + 2 eta with 2 b0 = 4 W'' (lam_in^2 - lam2^2)^2 + 2 W'(lam_in^2 + lam2^2)
    two_b0_over_c = (4.0 * W11 * (lam_in**2 - lam2**2) ** 2 + 2.0 * W1 * (lam_in**2 + lam2**2)) / (
        2.0 * W1 * lam2**2
    )
    S = np.sqrt(two_b0_over_c + 2.0 * eta)  # p2 + p3
    B = 2.0 * W1 * (eta * S + 2.0 * eta - 2.0)
    C = 4.0 * W1**2 * (eta * (S**2 - eta) + 2.0 * eta - 1.0)
    return B, C, S, eta, W1


def _positive_root(B, C):
    """Positive root ``x`` of ``x^2 - B x - C = 0`` when ``C >= 0``, else nan."""
    disc = B * B + 4.0 * C
    x = np.where(C >= 0, 0.5 * (B + np.sqrt(np.maximum(disc, 0.0))), np.nan)
    # cancellation-free form when B < 0
    x = np.where((C >= 0) & (B < 0), 2.0 * C / (np.sqrt(np.maximum(disc, 0.0)) - B), x)
    return x


@representable
def thick_limit_D0_uniaxial(
    lam1, lam3, model: Model | None = None, direction: str = "parallel", control: str = "charge"
):
    """Thick-plate (surface) wrinkling limit for in-plane stretches ``(lam1, lam3)``.

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (``> 0``), e.g. ``lam3 = uniaxial_lam3(lam1, s)``.
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    direction : {"parallel", "perpendicular"}
        Wrinkles in the ``(x1, x2)`` plane (Eq. thick-uni-axial) or the
        ``(x3, x2)`` plane (Eq. thick-plate23).
    control : {"charge", "voltage"}
        Incremental electric condition on the face: ``Delta = 0`` (charge,
        the paper) or ``Phi = 0`` (voltage). Voltage control returns ``D0``
        (``E0 = D0 lam2^2``).

    Returns
    -------
    D0 : float or ndarray
        The critical ``D0 >= 0``; ``nan`` where the elastic half-space is
        already unstable at ``D0 = 0`` (``C < 0`` below, stretch below the
        Biot/Green–Zerna value) or strong ellipticity fails.

    Notes
    -----
    With ``eta = lam_in/lam2 = p2 p3``, ``S = p2 + p3`` (Eq. evalue,
    generalised: ``S^2 = (2b + d^2)/c + 2 eta``) the charge-control condition
    ``det(i B A^-1) = 0`` (Eq. detStroh) is, for every ``W(I1)``,
    ``D0^4 - B D0^2 - C = 0`` with ``B = 2W'(eta S + 2 eta - 2)`` and
    ``C = 4W'^2 (eta (S^2 - eta) + 2 eta - 1)``: Eq. (short-wave) in
    equi-biaxial stretch, Eqs. (thick-uni-axial) and (thick-plate23) for the
    neo-Hookean model (``S = 1 + eta``). Voltage control gives
    ``D0^2 = C/(2 W' S)``. Derived symbolically from the eigenvectors of ``N``
    and checked against :func:`thick_limit_D0_numeric`.

    Examples
    --------
    >>> from analytic import thick_limit_D0_uniaxial
    >>> round(thick_limit_D0_uniaxial(2.0, 2.0**-0.5), 10)
    4.0938235568
    """
    check_choice("direction", direction, _DIRECTIONS)
    check_choice("control", control, _CONTROLS)
    model = as_model(model)
    lam1 = check_positive("lam1", lam1)
    lam3 = check_positive("lam3", lam3)
    lam1, lam3 = broadcast(lam1=lam1, lam3=lam3)
    B, C, S, eta, W1 = _thick_coefficients(lam1, lam3, model, direction)
    if control == "charge":
        x = _positive_root(B, C)
    else:
        x = np.where(C >= 0, C / (2.0 * W1 * S), np.nan)
    return scalar_or_array(_sqrt_or_nan(x))


@representable
def thick_limit_D0(lam, model: Model | None = None, control: str = "charge"):
    """Thick-plate (surface) wrinkling limit of an equi-biaxially stretched plate.

    Parameters
    ----------
    lam : array_like
        Equi-biaxial stretch (``> 0``).
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    control : {"charge", "voltage"}
        Incremental electric face condition, see
        :func:`thick_limit_D0_uniaxial`. Default ``"charge"`` (the paper).

    Returns
    -------
    D0 : float or ndarray
        Positive root of Eq. (short-wave) (neo-Hookean: Eq. ideal-shortwave,
        ``D0^4 - (lam^6 + 3 lam^3 - 2) D0^2 - (lam^9 + lam^6 + 3 lam^3 - 1) = 0``);
        ``nan`` below the Green–Zerna stretch (``lam < 0.6661`` neo-Hookean),
        where the half-space wrinkles without charge.

    Notes
    -----
    Eqs. (short-wave) and (evalue) with ``W'``, ``W''`` of Eq. (W).

    Examples
    --------
    >>> from analytic import thick_limit_D0
    >>> round(thick_limit_D0(1.0), 12)  # sqrt(1 + sqrt(5))
    1.798907439948
    """
    lam = check_positive("lam", lam)
    return thick_limit_D0_uniaxial(lam, lam, model, "parallel", control)


@representable
def surface_instability_stretch(model: Model | None = None, loading: str = "equibiaxial") -> float:
    """Critical compressive stretch of the charge-free half-space (``D0 = 0``).

    Parameters
    ----------
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    loading : {"equibiaxial", "uniaxial"}
        Equi-biaxial compression ``lam1 = lam3 = lam`` (Green–Zerna) or
        uni-axial compression ``lam3 = lam1^(-1/2)`` (Biot; wrinkles along the
        load).

    Returns
    -------
    float
        The stretch (``lam`` or ``lam1``) where ``C = 0`` in Eq. (short-wave),
        i.e. Eq. (ideal-shortwave) / (thick-uni-axial) at ``D0 = 0``. For the
        neo-Hookean model ``eta^3 + eta^2 + 3 eta - 1 = 0`` with
        ``eta = lam^3`` (equi-biaxial, 0.66614) or ``eta = lam1^(3/2)``
        (uni-axial, 0.44375), the paper's 0.666 and Biot's 0.444. ``nan`` if
        the model locks (``I1 >= I1_max``) before the half-space wrinkles.

    Examples
    --------
    >>> from analytic import surface_instability_stretch
    >>> round(surface_instability_stretch(), 5), round(surface_instability_stretch(loading="uniaxial"), 5)
    (0.66614, 0.44375)
    """
    check_choice("loading", loading, ("equibiaxial", "uniaxial"))
    model = as_model(model)

    def C_of(lam):
        lam3 = lam if loading == "equibiaxial" else lam**-0.5
        return float(_thick_coefficients(np.asarray(lam), np.asarray(lam3), model, "parallel")[1])

    # march down from lam = 1 (C > 0: stable) inside the model's domain
    hi = 1.0 - 1e-9
    for lo in 0.999 * 0.97 ** np.arange(1, 200):
        lam3 = lo if loading == "equibiaxial" else lo**-0.5
        I1 = lo**2 + lam3**2 + (lo * lam3) ** -2
        if not I1 < model.I1_max():
            return np.nan
        if C_of(lo) <= 0:
            return float(brent(C_of, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=200))
        hi = lo
    return np.nan


# ---------------------------------------------------------------------------
# decaying subspace, impedance, dispersion relation
# ---------------------------------------------------------------------------
def _real_K(a, b, c, d):
    """Real Stroh system ``xi' = K xi``, ``K = G^-1 (i N) G``, ``G = diag(i,1,1,1,i,i)``."""
    K = np.zeros(np.shape(a) + (6, 6))
    K[..., 0, 1] = -1.0
    K[..., 0, 2] = d / c
    K[..., 0, 3] = 1.0 / c
    K[..., 1, 0] = 1.0
    K[..., 2, 0] = -2.0 * d
    K[..., 2, 5] = 1.0
    K[..., 3, 0] = 2.0 * (b + c) + 4.0 * d**2
    K[..., 3, 4] = 1.0
    K[..., 3, 5] = -2.0 * d
    K[..., 4, 1] = c - a
    K[..., 4, 3] = -1.0
    K[..., 5, 2] = d**2 / c + 1.0
    K[..., 5, 3] = d / c
    return K


def _decaying(a, b, c, d):
    """``(Z, M, K)``: decaying subspace ``[I; Z]`` of ``K`` and ``M = K_AA + K_AB Z``.

    ``nan`` where strong ellipticity fails (an exponent with ``Re p <= 0``).
    """
    K = _real_K(a, b, c, d)
    p2, p3 = exponents_from_coefficients(a, b, c, d)
    bad = (np.real(p2) <= 1e-12) | (np.real(p3) <= 1e-12) | ~np.isfinite(p2) | ~np.isfinite(p3)
    p2 = np.where(bad, 1.0, p2)
    p3 = np.where(bad, 1.0, p3)
    eye = np.eye(6)
    K2 = K @ K
    f01 = (-1.0 / (p2 * (1.0 + p2)))[..., None, None]
    f012 = ((1.0 + p2 + p3) / (p2 * p3 * (1.0 + p2) * (p2 + p3) * (1.0 + p3)))[..., None, None]
    K2m1 = K2 - eye
    S = eye + f01 * K2m1 + f012 * (K2m1 @ (K2 - (p2**2)[..., None, None] * eye))
    sgn = np.real(K @ S)
    sgn = np.where(bad[..., None, None], eye, sgn)
    for _ in range(2):  # Newton polish of the sign function
        sgn = 0.5 * (sgn + np.linalg.inv(sgn))
    P = 0.5 * (eye - sgn)
    P1, P2 = P[..., :3, :], P[..., 3:, :]
    P1t = np.swapaxes(P1, -1, -2)
    Z = np.swapaxes(np.linalg.solve(P1 @ P1t, (P2 @ P1t).swapaxes(-1, -2)), -1, -2)
    M = K[..., :3, :3] + K[..., :3, 3:] @ Z
    Z = np.where(bad[..., None, None], np.nan, Z)
    M = np.where(bad[..., None, None], np.nan, M)
    return Z, M, K


def _expm3(A):
    """Batched matrix exponential (scaling and squaring, Taylor degree 12)."""
    eye = np.eye(A.shape[-1])
    norm = np.abs(A).sum(axis=-1).max(axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(norm > 0.25, np.ceil(np.log2(np.where(norm > 0, norm, 1.0) / 0.25)), 0.0)
    s = np.nan_to_num(s, nan=0.0).astype(int)
    As = A / (2.0 ** s)[..., None, None]
    E = np.broadcast_to(eye, A.shape).copy()
    for k in range(12, 0, -1):
        E = eye + (As @ E) / k
    for j in range(int(s.max(initial=0))):
        E = np.where((j < s)[..., None, None], E @ E, E)
    return E


def _impedance_from_Z(Z):
    """Complex ``i B A^-1`` from the real-form ``Z`` (``eta = G xi``)."""
    gA = np.array([1j, 1.0, 1.0])
    gB = np.array([1.0, 1j, 1j])
    return 1j * gB[:, None] * Z / gA[None, :]


@representable
def surface_impedance(
    lam1, lam3, D0, model: Model | None = None, direction: str = "parallel", method: str = "projector"
):
    """Surface impedance ``i B A^-1`` of the charged half-space (Eq. detStroh).

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (``> 0``).
    D0 : array_like
        Dimensionless electric displacement.
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    direction : {"parallel", "perpendicular"}
        Plane of the wrinkles.
    method : {"projector", "schur"}
        ``"projector"`` (vectorised): spectral projector onto the decaying
        subspace (see module notes), robust where exponents coincide.
        ``"schur"`` (reference, loops over points): ordered complex Schur form
        of ``N`` with the ``Im q > 0`` eigenvalues first; its orthonormal
        basis ``[A; B]`` of the decaying subspace replaces the eigenvectors of
        Eq. (eigenvectors), which become parallel at ``lam = 1``.

    Returns
    -------
    ndarray, shape (..., 3, 3), complex
        ``i B A^-1``, Hermitian (Stroh theory), independent of the basis; ``nan``
        where strong ellipticity fails.

    Examples
    --------
    >>> import numpy as np
    >>> from analytic.wrinkling import surface_impedance
    >>> Y = surface_impedance(1.0, 1.0, 0.0)   # defective N: p1 = p2 = p3 = 1
    >>> bool(np.allclose(Y, Y.conj().T))
    True
    """
    check_choice("method", method, ("projector", "schur"))
    a, b, c, d = coefficients(lam1, lam3, D0, model, direction)
    if method == "projector":
        Z, _, _ = _decaying(a, b, c, d)
        return scalar_or_array(_impedance_from_Z(Z))
    N = stroh_N(a, b, c, d)
    flat = N.reshape(-1, 6, 6)
    out = np.empty((flat.shape[0], 3, 3), dtype=complex)
    for i, Ni in enumerate(flat):
        _, Q, sdim = schur(Ni, output="complex", sort=lambda z: z.imag > 0)
        if sdim != 3:
            out[i] = np.nan
            continue
        A, Bm = Q[:3, :3], Q[3:, :3]
        out[i] = 1j * np.linalg.solve(A.T, Bm.T).T
    return scalar_or_array(out.reshape(N.shape[:-2] + (3, 3)))


@representable
def dispersion_function(
    lam1,
    lam3,
    D0,
    kh,
    model: Model | None = None,
    mode: str = "antisymmetric",
    control: str = "charge",
    direction: str = "parallel",
):
    """Real dispersion function of a plate of deformed thickness ``h``.

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (``> 0``).
    D0 : array_like
        Dimensionless electric displacement.
    kh : array_like
        Wavenumber times *deformed* thickness, ``> 0``; ``inf`` gives the
        half-space (thick-plate) condition.
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    mode : {"antisymmetric", "symmetric"}
        Flexural (``u2`` even in ``x2``) or extensional (``u2`` odd) modes.
    control : {"charge", "voltage"}
        Faces traction free with ``Delta = 0`` (charge) or ``Phi = 0``
        (voltage).
    direction : {"parallel", "perpendicular"}
        Plane of the wrinkles.

    Returns
    -------
    ndarray
        ``g = det(R (T V - sigma V exp(M kh)))`` (module notes); wrinkles of
        wavenumber ``k`` exist where ``g = 0``. ``g`` is continuous in all
        arguments, has no spurious roots at coincident exponents and never
        overflows; its overall sign is not meaningful.

    Notes
    -----
    Beyond the paper (which treats the limits ``kh -> 0``, Eq. detN3, and
    ``kh -> inf``, Eq. detStroh). At ``D0 = 0`` it reduces to the classical
    incompressible elastic plate (for the neo-Hookean model
    ``(1 + eta^2)^2 tanh(kh/2) = 4 eta tanh(eta kh/2)`` (flexural) and
    ``(1 + eta^2)^2 tanh(eta kh/2) = 4 eta tanh(kh/2)`` (extensional),
    ``eta = lam_in/lam2``).

    Examples
    --------
    >>> from analytic.wrinkling import dispersion_function
    >>> g1 = dispersion_function(1.3, 1.3, 2.5, 2.0)
    >>> g2 = dispersion_function(1.3, 1.3, 3.0, 2.0)
    >>> bool(g1 * g2 < 0)   # a flexural root between D0 = 2.5 and 3.0
    True
    """
    check_choice("mode", mode, _MODES)
    check_choice("control", control, _CONTROLS)
    kh = as_array("kh", kh)
    if np.any(kh <= 0):
        raise ValueError(f"kh must be > 0, got {kh}")
    a, b, c, d = coefficients(lam1, lam3, D0, model, direction)
    a, b, c, d, kh = broadcast(a=a, b=b, c=c, d=d, kh=kh)
    Z, M, _ = _decaying(a, b, c, d)
    return scalar_or_array(_g_from(Z, M, kh, mode, control))


# ---------------------------------------------------------------------------
# thick limit, numerical
# ---------------------------------------------------------------------------
def _search_bound(lam1, lam3, model, direction):
    """Default upper end of the ``D0`` search, ``2 (eta + 2) sqrt(2 W')``."""
    lam_in, lam2 = _in_plane(lam1, lam3, direction)
    W1, _ = _W_derivs(lam1, lam3, model)
    return 2.0 * (lam_in / lam2 + 2.0) * np.sqrt(2.0 * W1)


@representable
def thick_limit_D0_numeric(
    lam1, lam3, model: Model | None = None, direction: str = "parallel", control: str = "charge"
):
    """Thick-plate limit from the decaying subspace of ``N`` (no closed form used).

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (``> 0``).
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    direction : {"parallel", "perpendicular"}
        Plane of the wrinkles.
    control : {"charge", "voltage"}
        ``det(i B A^-1) = 0`` (charge, Eq. detStroh) or the ``Phi = 0``
        analogue (voltage).

    Returns
    -------
    D0 : float or ndarray
        Smallest root ``D0`` in ``[0, 2 (eta + 2) sqrt(2 W')]`` of the
        half-space condition, by scan and regula falsi (relative accuracy
        ~1e-14); ``nan`` if there is none. Agrees with
        :func:`thick_limit_D0_uniaxial` (a test checks 1e-10).

    Examples
    --------
    >>> from analytic.wrinkling import thick_limit_D0_numeric
    >>> round(thick_limit_D0_numeric(1.0, 1.0), 10)
    1.7989074399
    """
    return critical_D0_biaxial(lam1, lam3, np.inf, model, "antisymmetric", control, direction)


# ---------------------------------------------------------------------------
# finite thickness
# ---------------------------------------------------------------------------
@representable
def critical_D0_biaxial(
    lam1,
    lam3,
    kh,
    model: Model | None = None,
    mode: str = "antisymmetric",
    control: str = "charge",
    direction: str = "parallel",
    D0_max=None,
):
    """Critical ``D0`` of a plate of finite thickness, general ``(lam1, lam3)``.

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (``> 0``).
    kh : array_like
        Wavenumber times deformed thickness (``> 0``, ``inf`` allowed).
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    mode : {"antisymmetric", "symmetric"}
        Flexural or extensional wrinkles.
    control : {"charge", "voltage"}
        Incremental face condition ``Delta = 0`` or ``Phi = 0``.
    direction : {"parallel", "perpendicular"}
        Plane of the wrinkles.
    D0_max : array_like, optional
        Upper end of the search; default ``2 (eta + 2) sqrt(2 W')``,
        ``eta = lam_in/lam2`` (about twice the thick-plate limit).

    Returns
    -------
    D0 : float or ndarray
        Smallest ``D0`` in ``[0, D0_max]`` where :func:`dispersion_function`
        vanishes (wrinkles of wavenumber ``k`` appear); ``nan`` if there is no
        root in the range — either no instability, or (``eta < 1``, thin
        plates) instability already at ``D0 = 0`` that charge does not remove.

    Notes
    -----
    64-interval scan then Illinois regula falsi (safeguarded by bisection), to
    ~1e-14 relative; vectorised; the bulk part (decaying
    subspace) is computed once per distinct stretch and ``D0``.
    """
    check_choice("mode", mode, _MODES)
    check_choice("control", control, _CONTROLS)
    check_choice("direction", direction, _DIRECTIONS)
    model = as_model(model)
    lam1 = check_positive("lam1", lam1)
    lam3 = check_positive("lam3", lam3)
    kh = as_array("kh", kh)
    if np.any(kh <= 0):
        raise ValueError(f"kh must be > 0, got {kh}")
    if D0_max is None:
        lam1, lam3, kh = broadcast(lam1=lam1, lam3=lam3, kh=kh)
        hi = _search_bound(lam1, lam3, model, direction)
    else:
        D0_max = check_positive("D0_max", D0_max)
        lam1, lam3, kh, hi = broadcast(lam1=lam1, lam3=lam3, kh=kh, D0_max=D0_max)
    shape = lam1.shape
    l1, l3, khf, hif = (np.ravel(x).astype(float) for x in (lam1, lam3, kh, hi))

    # scan: the bulk (decaying subspace) depends on (lam1, lam3, D0) only, so it
    # is computed once per distinct (lam1, lam3, hi) row and shared across kh
    key = np.stack([l1, l3, hif], axis=1)
    uniq, inv = np.unique(key, axis=0, return_inverse=True)
    inv = np.ravel(inv)

    def scan(t):
        Du = uniq[:, 2:3] * t[None, :]
        a, b, c, d = coefficients_fast(uniq[:, 0:1], uniq[:, 1:2], Du, model, direction)
        Z, M, _ = _decaying(a, b, c, d)
        return _g_from(Z[inv], M[inv], khf[:, None], mode, control)

    def gfun(idx, D0):
        a, b, c, d = coefficients_fast(l1[idx][:, None], l3[idx][:, None], D0, model, direction)
        Z, M, _ = _decaying(a, b, c, d)
        return _g_from(Z, M, khf[idx][:, None], mode, control)

    out = first_root_on_scan(scan, gfun, hif)
    return scalar_or_array(out.reshape(shape))


def _g_from(Z, M, kh, mode, control):
    rows = _ROWS[control]
    sigma = 1.0 if mode == "antisymmetric" else -1.0
    eye3 = np.eye(3)
    V = np.concatenate([np.broadcast_to(eye3, Z.shape), Z], axis=-2)[..., rows, :]
    TV = _T[rows][:, None] * V
    kh = np.broadcast_to(np.asarray(kh, dtype=float), Z.shape[:-2])
    finite = np.isfinite(kh)
    if finite.any():
        Mk = np.where(np.isfinite(M), M, 0.0) * np.where(finite, kh, 0.0)[..., None, None]
        E = np.where(finite[..., None, None], _expm3(Mk), 0.0)
        return np.linalg.det(TV - sigma * (V @ E))
    return np.linalg.det(TV)


@representable
def critical_D0(
    lam,
    kh,
    model: Model | None = None,
    mode: str = "antisymmetric",
    control: str = "charge",
    D0_max=None,
):
    """Critical ``D0`` for wrinkling of an equi-biaxially stretched plate of finite thickness.

    Parameters
    ----------
    lam : array_like
        Equi-biaxial stretch (``> 0``; Gent: below the locking stretch). The
        computation stays in double precision for ``0.05 <= lam <= 10`` at every
        ``kh`` (neo-Hookean; thickness stretch ``lam^-2`` from 400 down to 1/100),
        which holds every stretch an elastomer plate reaches; a stretch whose
        computation overflows raises ``ValueError`` naming ``lam``.
    kh : array_like
        Wavenumber ``k = 2 pi / wavelength`` times the *deformed* thickness
        ``h`` (``> 0``; ``inf`` gives the thick-plate limit).
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    mode : {"antisymmetric", "symmetric"}
        Flexural (``u2`` even through the thickness) or extensional modes.
    control : {"charge", "voltage"}
        Charge control (faces keep their charge: incremental ``Delta = 0``)
        or voltage control (incremental potential ``Phi = 0``). The homogeneous
        state is the same, so both return ``D0``; under voltage control the
        critical field is ``E0 = D0 / lam^4``.
    D0_max : array_like, optional
        Upper end of the search (default ``2 (lam^3 + 2) sqrt(2 W')``).

    Returns
    -------
    D0 : float or ndarray
        Smallest ``D0 >= 0`` at which the exact dispersion relation
        (:func:`dispersion_function`) has a root; ``nan`` if none in
        ``[0, D0_max]``: symmetric modes of thin plates have their root far
        above (it grows like ``1/kh``, e.g. 60 at ``lam = 1.5``, ``kh = 0.1``;
        pass a larger ``D0_max`` to find it); for ``lam < 1`` and small ``kh``
        the plate already wrinkles without charge and no root exists.

    Notes
    -----
    Beyond the paper. Tends to :func:`thin_limit_D0` (Eq. antisym_thin) as
    ``kh -> 0`` (antisymmetric modes) and to :func:`thick_limit_D0`
    (Eq. short-wave) as ``kh -> inf``. Uses Eq. (con-eqns) with its last relation
    corrected to ``D_L02 = 2 d u_{1,1} - phi_{,2}`` (printed ``phi_{,1}``; the printed
    Stroh matrix is consistent with ``phi_{,2}``). Numerically stable for every ``kh``
    (module notes).

    Examples
    --------
    >>> from analytic import critical_D0, thin_limit_D0, thick_limit_D0
    >>> lam = 1.5
    >>> bool(thin_limit_D0(lam) < critical_D0(lam, 1.0) < thick_limit_D0(lam))
    True
    """
    lam = check_positive("lam", lam)
    return critical_D0_biaxial(lam, lam, kh, model, mode, control, "parallel", D0_max)


@representable
def critical_point_on_path(
    lam,
    D0,
    kh,
    model: Model | None = None,
    mode: str = "antisymmetric",
    control: str = "charge",
):
    """First point of an equi-biaxial loading path where wrinkles of given ``kh`` appear.

    Parameters
    ----------
    lam, D0 : array_like, 1-D
        Points ``(lam_i, D0_i)`` along the path, in loading order (e.g.
        ``D0 = equibiaxial_D0(lam, s)``).
    kh : float
        Wavenumber times deformed thickness (``inf``: thick-plate limit).
    model, mode, control
        As in :func:`critical_D0`.

    Returns
    -------
    lam_c, D0_c : float
        Where ``D0 - critical_D0(lam, kh)`` first changes sign from negative to
        non-negative, by linear interpolation between path points; ``(nan,
        nan)`` if the path never reaches the critical ``D0`` (the paper's
        conclusion for every charge-controlled loading curve with ``s > 0``).

    Examples
    --------
    >>> import numpy as np
    >>> from analytic.wrinkling import critical_point_on_path
    >>> lam = np.linspace(1.0, 1.6, 61)
    >>> D0 = 1.02 * np.sqrt(lam**6 - 1)      # a path above the s = 0 curve
    >>> lc, Dc = critical_point_on_path(lam, D0, kh=0.05)
    >>> bool(1.0 < lc < 1.6)
    True
    """
    lam = check_positive("lam", lam)
    D0 = check_finite("D0", D0)
    if lam.ndim != 1 or D0.shape != lam.shape:
        raise ValueError(f"lam and D0 must be 1-D arrays of equal length, got {lam.shape} and {D0.shape}")
    kh = float(as_array("kh", kh))
    if not kh > 0:
        raise ValueError(f"kh must be > 0, got {kh}")
    crit = np.asarray(critical_D0(lam, kh, model, mode, control))
    margin = D0 - crit
    ok = np.isfinite(margin)
    hit = ok[1:] & ok[:-1] & (margin[:-1] < 0) & (margin[1:] >= 0)
    if ok[0] and margin[0] >= 0:
        return float(lam[0]), float(D0[0])
    if not hit.any():
        return np.nan, np.nan
    i = int(np.argmax(hit))
    t = margin[i] / (margin[i] - margin[i + 1])
    return float(lam[i] + t * (lam[i + 1] - lam[i])), float(D0[i] + t * (D0[i + 1] - D0[i]))


@dataclass(frozen=True)
class WrinklingMap:
    """Thin- and thick-plate limits over a range of equi-biaxial stretches.

    Attributes
    ----------
    lam : ndarray
        Stretches.
    thin, thick : ndarray
        :func:`thin_limit_D0` and :func:`thick_limit_D0` (``nan`` where none).
    lower, upper : ndarray
        Bounds of the shaded region where a plate of *some* thickness wrinkles
        but not every one: ``lower = min(thin, thick)`` (``0`` where the thin
        limit does not exist, ``lam < 1``), ``upper = max(thin, thick)``.
        Above ``upper`` every plate wrinkles; below ``lower`` none does.
    """

    lam: np.ndarray
    thin: np.ndarray
    thick: np.ndarray
    lower: np.ndarray
    upper: np.ndarray


@representable
def wrinkling_map(lam, model: Model | None = None, control: str = "charge") -> WrinklingMap:
    """Wrinkling region in the ``(lam, D0)`` plane between the thin and thick limits.

    Parameters
    ----------
    lam : array_like, 1-D
        Equi-biaxial stretches.
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    control : {"charge", "voltage"}
        Electric condition for the thick limit (the thin limit is the same).

    Returns
    -------
    WrinklingMap
        Curves for ``ax.fill_between(m.lam, m.lower, m.upper)`` (the paper's
        grey zone, Fig. gent-equi-biaxial).

    Notes
    -----
    The finite-thickness critical ``D0`` lies between the two limits
    (:func:`critical_D0`; checked in the tests).

    Examples
    --------
    >>> import numpy as np
    >>> from analytic.wrinkling import wrinkling_map
    >>> m = wrinkling_map(np.array([0.9, 1.5]))
    >>> [round(float(x), 4) for x in m.lower], [round(float(x), 4) for x in m.upper]
    ([0.0, 3.2234], [1.3617, 4.709])
    """
    lam = check_positive("lam", lam)
    thin = np.asarray(thin_limit_D0(lam, model), dtype=float)
    thick = np.asarray(thick_limit_D0(lam, model, control), dtype=float)
    thin_or0 = np.where(np.isnan(thin), 0.0, thin)
    lower = np.where(np.isnan(thick), np.nan, np.minimum(thin_or0, thick))
    upper = np.where(np.isnan(thick), np.nan, np.maximum(thin_or0, thick))
    return WrinklingMap(lam=lam, thin=thin, thick=thick, lower=lower, upper=upper)

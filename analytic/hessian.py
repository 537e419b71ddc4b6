"""Energies, Hessians and the Hessian stability criterion (paper Sections 3.1 and 5).

Dimensionless energies of the homogeneous biaxial plate (ideal dielectric,
Eqs. modelE, modelD; ``I1 = lam1^2 + lam3^2 + lam1^-2 lam3^-2``):

``omega*(lam1, lam3, D0) = W(I1) + lam1^-2 lam3^-2 D0^2 / 2``  (charge variable),
``omega(lam1, lam3, E0)  = W(I1) - lam1^2 lam3^2 E0^2 / 2``    (field variable),

linked by ``omega* = omega + D0 E0`` with ``D0 = lam1^2 lam3^2 E0`` (Eq.
omegaomegastar). The equi-biaxial energies ``omega*-hat(lam, D0)`` and
``omega-hat(lam, E0)`` set ``lam1 = lam3 = lam``.

Hessians: ``H*`` (of ``omega*`` in ``(lam1, lam3, D0)``) and ``H`` (of ``omega``
in ``(lam1, lam3, E0)``), Eq. (2nd-variation); 2x2 versions in ``(lam, D0)`` and
``(lam, E0)`` for equi-biaxial deformations (Sec. 3.1).

Verdicts (Eqs. sec-var-equi2, equiv): under **charge control** (``D0`` fixed)
the state is stable when the mechanical block of ``H*`` (the leading 2x2 minor,
or ``omega*-hat_{lam lam}`` equi-biaxially) is positive definite; under
**voltage control** (``E0`` fixed) when the mechanical block of ``H`` is, which
is equivalent to ``H*`` positive definite because ``omega*_{D0 D0} > 0`` and
``det H* = omega*_{D0 D0} det(mechanical block of H)``.
"""

from __future__ import annotations

import numpy as np

from ._checks import as_array, broadcast, check_choice, check_finite, check_positive
from ._loading import equibiaxial_limits, model_derivs, uniaxial_x, uniaxial_xlock
from ._output import representable, scalar_or_array
from ._roots import golden_section_max, illinois, rtsafe, scan_first_up
from .homogeneous import equibiaxial_lam, uniaxial_lam1
from .models import NeoHookean, as_model

__all__ = [
    "invariant_I1",
    "omega_star",
    "omega",
    "equibiaxial_omega_star",
    "equibiaxial_omega",
    "hessian_omega_star",
    "hessian_omega",
    "equibiaxial_hessian_omega_star",
    "equibiaxial_hessian_omega",
    "leading_minors",
    "stability_verdict",
    "equibiaxial_stability_verdict",
    "voltage_limit_D0",
    "voltage_limit_E0",
    "uniaxial_voltage_limit_lam3",
    "uniaxial_voltage_limit_D0",
    "uniaxial_voltage_limit_E0",
    "max_E0",
    "no_maximum_threshold",
]

_LOADINGS = ("equibiaxial", "uniaxial")
_CHUNK = 1 << 14  # rows per block in grid scans
_CONTROLS = ("charge", "voltage")


# ----------------------------------------------------------------------------
# energies
# ----------------------------------------------------------------------------
def _stretches(lam1, lam3, name, value):
    lam1 = check_positive("lam1", lam1)
    lam3 = check_positive("lam3", lam3)
    v = as_array(name, value)
    if np.any(~np.isfinite(v)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return broadcast(lam1=lam1, lam3=lam3, **{name: v})


@representable
def invariant_I1(lam1, lam3):
    """``I1 = lam1^2 + lam3^2 + lam1^-2 lam3^-2`` of the biaxial plate, Eq. (invariants1a).

    Examples
    --------
    >>> from analytic import invariant_I1
    >>> float(invariant_I1(1.0, 1.0))
    3.0
    """
    lam1 = check_positive("lam1", lam1)
    lam3 = check_positive("lam3", lam3)
    lam1, lam3 = broadcast(lam1=lam1, lam3=lam3)
    return scalar_or_array(lam1**2 + lam3**2 + 1.0 / (lam1 * lam3) ** 2)


@representable
def omega_star(lam1, lam3, D0, model=None):
    """Dimensionless energy ``omega*(lam1, lam3, D0) = W(I1) + lam1^-2 lam3^-2 D0^2/2``.

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (> 0).
    D0 : array_like
        Dimensionless Lagrangian charge ``D_L/sqrt(mu eps)``.
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Notes
    -----
    Sec. 2.1 ("omega* = w + lam1^-2 lam3^-2 D_L^2/(2 eps)") from Eq. (modelD),
    divided by ``mu``.

    Examples
    --------
    >>> from analytic import omega_star
    >>> float(omega_star(1.0, 1.0, 2.0))
    2.0
    """
    model = as_model(model)
    lam1, lam3, D0 = _stretches(lam1, lam3, "D0", D0)
    I1 = lam1**2 + lam3**2 + 1.0 / (lam1 * lam3) ** 2
    model_derivs(model, I1, "lam1", lam1)
    return scalar_or_array(model.W(I1) + 0.5 * D0**2 / (lam1 * lam3) ** 2)


@representable
def omega(lam1, lam3, E0, model=None):
    """Dimensionless energy ``omega(lam1, lam3, E0) = W(I1) - lam1^2 lam3^2 E0^2/2``.

    Notes
    -----
    Sec. 2.1 from Eq. (modelE), divided by ``mu``. Same parameters as
    :func:`omega_star` with the field ``E0 = E_L sqrt(eps/mu)`` instead of ``D0``.

    Examples
    --------
    >>> from analytic import omega
    >>> float(omega(1.0, 1.0, 2.0))
    -2.0
    """
    model = as_model(model)
    lam1, lam3, E0 = _stretches(lam1, lam3, "E0", E0)
    I1 = lam1**2 + lam3**2 + 1.0 / (lam1 * lam3) ** 2
    model_derivs(model, I1, "lam1", lam1)
    return scalar_or_array(model.W(I1) - 0.5 * E0**2 * (lam1 * lam3) ** 2)


@representable
def equibiaxial_omega_star(lam, D0, model=None):
    """Equi-biaxial ``omega*-hat(lam, D0) = W(2 lam^2 + lam^-4) + lam^-4 D0^2/2`` (Sec. 2.1).

    Examples
    --------
    >>> from analytic import equibiaxial_omega_star
    >>> float(equibiaxial_omega_star(1.0, 1.0))
    0.5
    """
    return omega_star(lam, lam, D0, model)


@representable
def equibiaxial_omega(lam, E0, model=None):
    """Equi-biaxial ``omega-hat(lam, E0) = W(2 lam^2 + lam^-4) - lam^4 E0^2/2`` (Sec. 2.1).

    Examples
    --------
    >>> from analytic import equibiaxial_omega
    >>> float(equibiaxial_omega(1.0, 1.0))
    -0.5
    """
    return omega(lam, lam, E0, model)


# ----------------------------------------------------------------------------
# Hessians
# ----------------------------------------------------------------------------
def _elastic(lam1, lam3, model, name="lam1"):
    """``W'' dI1 dI1 + W' d2I1`` entries (11, 13, 33) and ``I1``."""
    a, b = lam1, lam3
    ra, rb = 1.0 / a, 1.0 / b
    e = (ra * rb) ** 2
    I1 = a * a + b * b + e
    dW, d2W = model_derivs(model, I1, name, lam1)
    Ia, Ib = 2 * (a - e * ra), 2 * (b - e * rb)
    k11 = d2W * Ia * Ia + dW * (2 + 6 * e * ra * ra)
    k33 = d2W * Ib * Ib + dW * (2 + 6 * e * rb * rb)
    k13 = d2W * Ia * Ib + dW * 4 * e * ra * rb
    return k11, k13, k33


def _stack(rows):
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


@representable
def hessian_omega_star(lam1, lam3, D0, model=None):
    """3x3 Hessian ``H*`` of ``omega*`` in ``(lam1, lam3, D0)``.

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (> 0).
    D0 : array_like
        Dimensionless charge.
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Returns
    -------
    H : ndarray, shape ``(..., 3, 3)``
        ``[[w11, w13, w1D], [w13, w33, w3D], [w1D, w3D, wDD]]`` of ``omega*``.

    Notes
    -----
    Eq. (2nd-variation)_1 and the matrix that follows it. With
    ``e = lam1^-2 lam3^-2``: ``w1D = -2 D0 e/lam1``, ``w3D = -2 D0 e/lam3``,
    ``wDD = e``, and the electric parts of the mechanical block are
    ``3 D0^2 e/lam1^2``, ``2 D0^2 e/(lam1 lam3)``, ``3 D0^2 e/lam3^2``. For
    neo-Hookean the determinant of the mechanical block is the paper's
    ``1 + 3 lam1^-4 lam3^-4 (lam1^2 + lam3^2)(1 + D0^2) + 5 lam1^-6 lam3^-6 (1 + D0^2)^2``
    (Sec. 5).

    Examples
    --------
    >>> from analytic import hessian_omega_star
    >>> hessian_omega_star(1.0, 1.0, 0.0).tolist()
    [[4.0, 2.0, -0.0], [2.0, 4.0, -0.0], [-0.0, -0.0, 1.0]]
    """
    model = as_model(model)
    lam1, lam3, D0 = _stretches(lam1, lam3, "D0", D0)
    k11, k13, k33 = _elastic(lam1, lam3, model)
    ra, rb = 1.0 / lam1, 1.0 / lam3
    e, q = (ra * rb) ** 2, D0**2
    h11 = k11 + 3 * q * e * ra * ra
    h33 = k33 + 3 * q * e * rb * rb
    h13 = k13 + 2 * q * e * ra * rb
    h1D, h3D = -2 * D0 * e * ra, -2 * D0 * e * rb
    return scalar_or_array(_stack([[h11, h13, h1D], [h13, h33, h3D], [h1D, h3D, e]]))


@representable
def hessian_omega(lam1, lam3, E0, model=None):
    """3x3 Hessian ``H`` of ``omega`` in ``(lam1, lam3, E0)``.

    Returns an array of shape ``(..., 3, 3)``: ``[[w11, w13, w1E], [w13, w33,
    w3E], [w1E, w3E, wEE]]`` with ``w1E = -2 lam1 lam3^2 E0``,
    ``w3E = -2 lam1^2 lam3 E0``, ``wEE = -lam1^2 lam3^2`` and the electric parts
    ``-lam3^2 E0^2``, ``-2 lam1 lam3 E0^2``, ``-lam1^2 E0^2`` of the mechanical
    block. ``H`` is never positive definite (``wEE < 0``): it describes a saddle
    (Sec. 3.1).

    Notes
    -----
    Eq. (2nd-variation)_2 and the matrix that follows it.

    Examples
    --------
    >>> from analytic import hessian_omega
    >>> hessian_omega(1.0, 1.0, 0.0).tolist()
    [[4.0, 2.0, -0.0], [2.0, 4.0, -0.0], [-0.0, -0.0, -1.0]]
    """
    model = as_model(model)
    lam1, lam3, E0 = _stretches(lam1, lam3, "E0", E0)
    k11, k13, k33 = _elastic(lam1, lam3, model)
    q = E0**2
    h11 = k11 - lam3**2 * q
    h33 = k33 - lam1**2 * q
    h13 = k13 - 2 * lam1 * lam3 * q
    h1E, h3E = -2 * lam1 * lam3**2 * E0, -2 * lam1**2 * lam3 * E0
    return scalar_or_array(_stack([[h11, h13, h1E], [h13, h33, h3E], [h1E, h3E, -(lam1 * lam3) ** 2]]))


def _equi_elastic(lam, model):
    r = 1.0 / lam
    r4 = (r * r) ** 2
    I1 = 2 * lam * lam + r4
    dW, d2W = model_derivs(model, I1, "lam", lam)
    I1p, I1pp = 4 * (lam - r4 * r), 4 + 20 * r4 * r * r
    return d2W * I1p**2 + dW * I1pp, dW, d2W


@representable
def equibiaxial_hessian_omega_star(lam, D0, model=None):
    """2x2 equi-biaxial Hessian ``H*`` of ``omega*-hat`` in ``(lam, D0)``.

    Returns an array ``(..., 2, 2)``: ``[[w_ll, w_lD], [w_lD, w_DD]]`` with
    ``w_ll = W'' I1'^2 + W' I1'' + 10 lam^-6 D0^2``, ``w_lD = -4 lam^-5 D0``,
    ``w_DD = lam^-4`` (``I1 = 2 lam^2 + lam^-4``).

    Notes
    -----
    Sec. 3.1; neo-Hookean ``w_ll = 2 (1 + 5 lam^-6 + 5 lam^-6 D0^2)`` and
    ``det H* = 2 lam^-10 (lam^6 + 5 - 3 D0^2)``.

    Examples
    --------
    >>> import numpy as np
    >>> from analytic import equibiaxial_hessian_omega_star
    >>> H = equibiaxial_hessian_omega_star(1.0, 1.0)
    >>> H.tolist(), round(float(np.linalg.det(H)), 12)  # 2 (1 + 5 - 3)
    ([[22.0, -4.0], [-4.0, 1.0]], 6.0)
    """
    model = as_model(model)
    lam = check_positive("lam", lam)
    D0 = check_finite("D0", D0)
    lam, D0 = broadcast(lam=lam, D0=D0)
    m, _, _ = _equi_elastic(lam, model)
    r = 1.0 / lam
    r4 = (r * r) ** 2
    return scalar_or_array(_stack([[m + 10 * r4 * r * r * D0**2, -4 * r4 * r * D0], [-4 * r4 * r * D0, r4]]))


@representable
def equibiaxial_hessian_omega(lam, E0, model=None):
    """2x2 equi-biaxial Hessian ``H`` of ``omega-hat`` in ``(lam, E0)``.

    Returns ``[[w_ll, w_lE], [w_lE, w_EE]]`` with
    ``w_ll = W'' I1'^2 + W' I1'' - 6 lam^2 E0^2``, ``w_lE = -4 lam^3 E0``,
    ``w_EE = -lam^4``.

    Notes
    -----
    Sec. 3.1; neo-Hookean ``w_ll = 2 (1 + 5 lam^-6 - 3 lam^2 E0^2)`` and
    ``det H = -2 lam^4 (1 + 5 lam^-6 + 5 lam^2 E0^2)``.

    Examples
    --------
    >>> from analytic import equibiaxial_hessian_omega
    >>> equibiaxial_hessian_omega(1.0, 1.0).tolist()
    [[6.0, -4.0], [-4.0, -1.0]]
    """
    model = as_model(model)
    lam = check_positive("lam", lam)
    E0 = check_finite("E0", E0)
    lam, E0 = broadcast(lam=lam, E0=E0)
    m, _, _ = _equi_elastic(lam, model)
    return scalar_or_array(_stack([[m - 6 * lam**2 * E0**2, -4 * lam**3 * E0], [-4 * lam**3 * E0, -(lam**4)]]))


@representable
def leading_minors(H):
    """Leading principal minors of (stacks of) square matrices.

    Parameters
    ----------
    H : array_like, shape ``(..., n, n)``

    Returns
    -------
    minors : ndarray, shape ``(..., n)``
        ``det H[..., :k, :k]`` for ``k = 1..n``. By Sylvester's criterion ``H``
        is positive definite iff all are positive.

    Examples
    --------
    >>> from analytic import leading_minors
    >>> leading_minors([[2.0, 1.0], [1.0, 2.0]]).round(12).tolist()
    [2.0, 3.0]
    """
    H = as_array("H", H)
    if H.ndim < 2 or H.shape[-1] != H.shape[-2]:
        raise ValueError(f"H must have shape (..., n, n), got shape {H.shape}")
    n = H.shape[-1]
    return scalar_or_array(np.stack([np.linalg.det(H[..., :k, :k]) for k in range(1, n + 1)], axis=-1))


def _posdef2(h11, h12, h22):
    return (h11 > 0) & (h11 * h22 - h12 * h12 > 0)


@representable
def stability_verdict(lam1, lam3, D0, model=None, control: str = "charge"):
    """Hessian stability of the homogeneous biaxial state ``(lam1, lam3, D0)``.

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (> 0).
    D0 : array_like
        Dimensionless charge (the field is ``E0 = lam1^-2 lam3^-2 D0``).
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).
    control : {"charge", "voltage"}
        Electrical boundary condition.

    Returns
    -------
    stable : ndarray of bool
        Charge control: the leading 2x2 minor of ``H*`` is positive definite.
        Voltage control: the leading 2x2 minor of ``H`` (at the corresponding
        ``E0``) is positive definite, equivalently ``H*`` is.

    Notes
    -----
    Eq. (equiv) and the two inequalities after it (Sec. 5). For ``W' > 0``,
    ``W'' >= 0`` charge control is always stable (``omega*`` is convex in the
    stretches).

    Examples
    --------
    Neo-Hookean, uni-axial load ``s = 0`` at its ``E0`` maximum
    ``lam1 = lam3 = 2^(1/3)``, ``D0 = sqrt(3)``: charge control stable, voltage
    control just past its limit:

    >>> from analytic import stability_verdict
    >>> l = 2 ** (1 / 3)
    >>> bool(stability_verdict(l, l, 1.8, control="charge"))
    True
    >>> bool(stability_verdict(l, l, 1.8, control="voltage"))
    False
    """
    check_choice("control", control, _CONTROLS)
    if control == "charge":
        H = hessian_omega_star(lam1, lam3, D0, model)
    else:
        lam1, lam3, D0 = _stretches(lam1, lam3, "D0", D0)
        H = hessian_omega(lam1, lam3, D0 / (lam1 * lam3) ** 2, model)
    return scalar_or_array(_posdef2(H[..., 0, 0], H[..., 0, 1], H[..., 1, 1]))


@representable
def equibiaxial_stability_verdict(lam, D0, model=None, control: str = "charge"):
    """Hessian stability of the equi-biaxial state ``(lam, D0)`` against equi-biaxial perturbations.

    Returns ``omega*-hat_{lam lam} > 0`` under charge control and
    ``omega-hat_{lam lam} > 0`` (at ``E0 = lam^-4 D0``) under voltage control.

    Notes
    -----
    Eq. (sec-var-equi2) and the discussion after it (Sec. 3.1). Neo-Hookean:
    charge control is always stable; voltage control fails where
    ``D0^2 > (lam^6 + 5)/3`` (see :func:`voltage_limit_D0`).

    Examples
    --------
    >>> from analytic import equibiaxial_stability_verdict
    >>> bool(equibiaxial_stability_verdict(1.5, 3.0, control="voltage"))
    False
    >>> bool(equibiaxial_stability_verdict(1.5, 3.0, control="charge"))
    True
    """
    check_choice("control", control, _CONTROLS)
    if control == "charge":
        H = equibiaxial_hessian_omega_star(lam, D0, model)
    else:
        lam = check_positive("lam", lam)
        D0 = check_finite("D0", D0)
        lam, D0 = broadcast(lam=lam, D0=D0)
        H = equibiaxial_hessian_omega(lam, D0 / lam**4, model)
    return scalar_or_array(H[..., 0, 0] > 0)


# ----------------------------------------------------------------------------
# voltage-control limit loci
# ----------------------------------------------------------------------------
@representable
def voltage_limit_D0(lam, model=None):
    """Equi-biaxial locus ``det H* = 0``: the ``D0`` where voltage control becomes unstable.

    Parameters
    ----------
    lam : array_like
        Equi-biaxial stretch (> 0).
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Returns
    -------
    D0 : ndarray
        ``sqrt(lam^6 (W'' I1'^2 + W' I1'')/6)``; ``nan`` where negative.
        Independent of ``s``; its intersections with the loading curves are the
        maxima of ``E0``.

    Notes
    -----
    From the equi-biaxial ``det H* = 0`` (Sec. 3.1), equivalently
    ``omega-hat_{lam lam} = 0``; neo-Hookean ``D0 = sqrt((lam^6 + 5)/3)``
    (dashed curves of Figs. nh-d-e and gent-d-e).

    Examples
    --------
    >>> from analytic import voltage_limit_D0
    >>> float(voltage_limit_D0(1.0))  # sqrt(6/3)
    1.4142135623730951
    """
    model = as_model(model)
    lam = check_positive("lam", lam)
    m, _, _ = _equi_elastic(lam, model)
    D2 = lam**6 * m / 6.0
    with np.errstate(invalid="ignore"):
        return scalar_or_array(np.where(D2 >= 0, np.sqrt(np.abs(D2)), np.nan))


@representable
def voltage_limit_E0(lam, model=None):
    """Equi-biaxial voltage limit as a field: ``E0 = lam^-4`` :func:`voltage_limit_D0`.

    Neo-Hookean: ``E0 = sqrt((lam^-2 + 5 lam^-8)/3)`` (Sec. 3.1, dashed curve of
    Fig. nh-d-e(b)).

    Examples
    --------
    >>> from analytic import voltage_limit_E0
    >>> round(float(voltage_limit_E0(2 ** (1 / 3))), 12) == round(3**0.5 / 2 ** (4 / 3), 12)
    True
    """
    D0 = voltage_limit_D0(lam, model)
    lam = check_positive("lam", lam)
    return scalar_or_array(np.asarray(D0) / lam**4)


def _uniaxial_path_detK(lam1, x, model):
    """det of the mechanical block of ``H`` on the uni-axial path (``t3 = 0``), with its ``D0``.

    Flat arrays; ``x = lam3^2``. ``det H* = lam1^-2 lam3^-2 * detK``.
    """
    b = np.sqrt(x)
    I1 = lam1**2 + x + 1.0 / (lam1**2 * x)
    dW = model.dW(I1)
    D2 = 2 * dW * (lam1**2 * x**2 - 1.0)
    E2 = D2 / (lam1**4 * x**2)
    k11, k13, k33 = _elastic(lam1, b, model)
    h11 = k11 - x * E2
    h33 = k33 - lam1**2 * E2
    h13 = k13 - 2 * lam1 * b * E2
    return h11 * h33 - h13 * h13, D2


def _uniaxial_locus_x(lam1, model):
    """``x = lam3^2`` on the uni-axial ``det H* = 0`` locus (flat arrays)."""
    n = lam1.size
    if isinstance(model, NeoHookean):
        # lam1^2 x^3 - 3 x - lam1^2 = 0 (Sec. 5: lam1^2 + 3 lam3^2 - lam1^2 lam3^6 = 0),
        # one positive root, in (0, 1 + 3/lam1^2]
        def f(x, i):
            l2 = lam1[i] ** 2
            return l2 * x**3 - 3 * x - l2, 3 * l2 * x**2 - 3.0

        x = rtsafe(f, np.zeros(n), 1.0 + 3.0 / lam1**2, 1.0 + 3.0 / lam1**2)
        with np.errstate(invalid="ignore"):
            return np.where(lam1**2 * x**2 >= 1.0, x, np.nan)
    model_derivs(model, lam1**2 + 2.0 / lam1, "lam1", lam1)
    if n > _CHUNK:  # bound the memory of the scan grid (a loop over blocks, not points)
        return np.concatenate([_uniaxial_locus_x(lam1[k:k + _CHUNK], model) for k in range(0, n, _CHUNK)])
    x_lo = 1.0 / lam1
    x_top = uniaxial_xlock(lam1, model.I1_max())
    x_top = np.where(np.isfinite(x_top), x_top, 64.0 * (x_lo + 3.0 / lam1**2 + 1.0))
    t = np.concatenate([np.linspace(0.0, 0.97, 48), 1.0 - 0.03 * 2.0 ** -np.arange(1, 16)])
    xs = x_lo[:, None] + (x_top - x_lo)[:, None] * t[None, :]
    rows = np.repeat(lam1, t.size)
    # grid points that round onto the locking limit are skipped (nan: no sign change)
    inside = (rows**2 + xs.ravel() + 1.0 / (rows**2 * xs.ravel()) < model.I1_max())
    P = np.full(xs.size, np.nan)
    P[inside] = _uniaxial_path_detK(rows[inside], xs.ravel()[inside], model)[0]
    P = P.reshape(xs.shape)
    change = (P[:, :-1] > 0) & (P[:, 1:] <= 0)
    has = change.any(axis=1)
    k = np.argmax(change, axis=1)
    x = np.full(n, np.nan)
    r = np.flatnonzero(has)
    x[r] = illinois(lambda xv, i: _uniaxial_path_detK(lam1[r[i]], xv, model)[0],
                   xs[r, k[r]], xs[r, k[r] + 1])
    return x


def _locus_inputs(lam1, model):
    model = as_model(model)
    lam1 = check_positive("lam1", lam1)
    return lam1, model


@representable
def uniaxial_voltage_limit_lam3(lam1, model=None):
    """``lam3`` on the uni-axial voltage-control limit locus (``det H* = 0`` with ``t3 = 0``).

    Parameters
    ----------
    lam1 : array_like
        Stretch in the load direction (> 0).
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Returns
    -------
    lam3 : ndarray
        ``nan`` where the locus has no point with real ``D0``.

    Notes
    -----
    On the uni-axial path (``D0^2 = 2W'(lam1^2 lam3^4 - 1)`` from ``t3 = 0``)
    ``det H* = lam1^-2 lam3^-2 det K``, ``K`` the mechanical block of ``H``.
    Neo-Hookean: the paper's ``det H* = 4 lam1^-6 lam3^-6 (3 lam3^2 + lam1^2 -
    lam1^2 lam3^6)`` (Sec. 5), a cubic in ``lam3^2``. That printed formula holds
    on the loading path only (after substituting ``D0^2 = lam1^2 lam3^4 - 1``), not
    for arbitrary ``(lam1, lam3, D0)``. Other models: the first
    sign change of ``det K`` as ``D0`` grows from 0 at fixed ``lam1``
    (vectorised scan and Illinois regula falsi).

    Examples
    --------
    >>> from analytic import uniaxial_voltage_limit_lam3
    >>> round(float(uniaxial_voltage_limit_lam3(2 ** (1 / 3))), 12) == round(2 ** (1 / 3), 12)
    True
    """
    lam1, model = _locus_inputs(lam1, model)
    return scalar_or_array(np.sqrt(_uniaxial_locus_x(lam1.ravel(), model)).reshape(lam1.shape))


@representable
def uniaxial_voltage_limit_D0(lam1, model=None):
    """``D0`` on the uni-axial voltage-control limit locus (dashed curve of Fig. figde(a)).

    ``D0 = sqrt(2W'(lam1^2 lam3^4 - 1))`` with ``lam3`` from
    :func:`uniaxial_voltage_limit_lam3`; ``nan`` off the branch. Sec. 5.

    Examples
    --------
    >>> from analytic import uniaxial_voltage_limit_D0
    >>> round(float(uniaxial_voltage_limit_D0(2 ** (1 / 3))), 12) == round(3**0.5, 12)
    True
    """
    lam1, model = _locus_inputs(lam1, model)
    l1 = lam1.ravel()
    x = _uniaxial_locus_x(l1, model)
    D0 = np.full(l1.size, np.nan)
    g = np.isfinite(x)
    dW = model.dW(l1[g] ** 2 + x[g] + 1.0 / (l1[g] ** 2 * x[g]))
    D0[g] = np.sqrt(np.maximum(2 * dW * (l1[g] ** 2 * x[g] ** 2 - 1.0), 0.0))
    return scalar_or_array(D0.reshape(lam1.shape))


@representable
def uniaxial_voltage_limit_E0(lam1, model=None):
    """``E0`` on the uni-axial voltage-control limit locus (dashed curve of Fig. figde(b)).

    ``E0 = lam1^-2 lam3^-2 D0`` on :func:`uniaxial_voltage_limit_D0`. Sec. 5.

    Examples
    --------
    >>> from analytic import uniaxial_voltage_limit_E0
    >>> round(float(uniaxial_voltage_limit_E0(2 ** (1 / 3))), 12) == round(3**0.5 / 2 ** (4 / 3), 12)
    True
    """
    lam1, model = _locus_inputs(lam1, model)
    l1 = lam1.ravel()
    x = _uniaxial_locus_x(l1, model)
    D0 = np.asarray(uniaxial_voltage_limit_D0(l1, model))
    return scalar_or_array((D0 / (l1**2 * x)).reshape(lam1.shape))


# ----------------------------------------------------------------------------
# maxima of E0 along fixed-s curves
# ----------------------------------------------------------------------------
def _equi_F(lam, s, model):
    """``D0^2(curve) - D0^2(locus)`` on the equi-biaxial curve of load ``s``."""
    m, dW, _ = _equi_elastic(lam, model)
    return 2 * dW * (lam**6 - 1.0) - lam**5 * s - lam**6 * m / 6.0


@representable
def max_E0(s, model=None, loading: str = "equibiaxial"):
    """Maximum of ``E0`` along the loading curve of fixed dead load ``s``.

    Parameters
    ----------
    s : array_like
        Dimensionless dead load (equi-biaxial ``t/mu`` or uni-axial ``t1/mu``).
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).
    loading : {"equibiaxial", "uniaxial"}
        Loading curve (Eq. loading_gent or Eq. DEuniax).

    Returns
    -------
    lam, E0 : ndarray
        Stretch (``lam`` resp. ``lam1``) and field at the first maximum of ``E0``
        as ``D0`` grows from 0; ``(nan, nan)`` where ``E0`` has no maximum
        (Gent above :func:`no_maximum_threshold`).

    Notes
    -----
    A maximum of ``E0`` at fixed ``s`` is where voltage control loses
    stability: ``det H* = 0`` (Sec. 3.1; Sec. 5 for the uni-axial case,
    Fig. figde). Neo-Hookean equi-biaxial: the root of
    ``2 lam^6 - 3 s lam^5 - 8 = 0`` (curve meets ``D0^2 = (lam^6+5)/3``); for
    ``s = 0``, ``lam = 2^(1/3)`` and ``E0 = sqrt(3)/2^(4/3)``. Neo-Hookean
    uni-axial: root of ``4 lam1 - 3 s - lam1^4 (lam1 - s)^3 = 0``. Other
    models: first sign change on a 256-point scan from the ``D0 = 0`` state,
    refined by Illinois regula falsi.

    Examples
    --------
    >>> import numpy as np
    >>> from analytic import max_E0, Gent
    >>> lam, E0 = max_E0(0.0)
    >>> round(float(lam), 12) == round(2 ** (1 / 3), 12), round(float(E0), 12) == round(3**0.5 / 2 ** (4 / 3), 12)
    (True, True)
    >>> [bool(np.isnan(v)) for v in max_E0(3.0, Gent(97.2))]
    [True, True]
    """
    model = as_model(model)
    check_choice("loading", loading, _LOADINGS)
    s = check_finite("s", s)
    shape = s.shape
    sf = s.ravel()
    nh = isinstance(model, NeoHookean)
    if loading == "equibiaxial":
        lam0 = np.asarray(equibiaxial_lam(0.0 * sf, sf, model)).ravel()
        if nh:
            def f(x, i):
                return 2 * x**6 - 3 * sf[i] * x**5 - 8.0, 12 * x**5 - 15 * sf[i] * x**4

            hi = 1.5 * np.abs(sf) + 2.0
            lam = rtsafe(f, lam0, hi, hi)
        else:
            lo_lim, hi_lim = equibiaxial_limits(model)
            top = np.full(sf.size, hi_lim * (1 - 1e-9)) if np.isfinite(hi_lim) else 64.0 * lam0
            lam = scan_first_up(lambda x, i: _equi_F(x, sf[i], model), lam0, top)
        good = np.isfinite(lam)
        lg = np.where(good, lam, 1.0)
        _, dW, _ = _equi_elastic(lg, model)
        D2 = 2 * dW * (lg**6 - 1.0) - lg**5 * sf  # on the loading curve
        E0 = np.where(good, np.sqrt(np.abs(D2)) / lg**4, np.nan)
        return scalar_or_array(lam.reshape(shape), E0.reshape(shape))
    # uni-axial
    l10 = np.asarray(uniaxial_lam1(0.0 * sf, sf, model)).ravel()
    if nh:
        def G(x, i):
            u = x - sf[i]
            return 4 * x - 3 * sf[i] - x**4 * u**3, 4 - 4 * x**3 * u**3 - 3 * x**4 * u**2

        hi = np.maximum(sf, 0.0) + 2.0 + np.abs(sf)
        lam1 = rtsafe(G, hi, l10, hi)
    else:
        I1max = model.I1_max()
        if np.isfinite(I1max):
            # largest lam1 whose D0 = 0 state is admissible: lam1^2 + 2/lam1 < I1max
            cap = float(np.max(np.roots([1.0, 0.0, -I1max, 2.0]).real)) * (1 - 1e-9)
            top = np.full(sf.size, cap)
        else:
            top = 16.0 * l10 + 4.0

        def F(x, i):
            shp = x.shape
            xf, sv = x.ravel(), sf[np.broadcast_to(i, shp).ravel()]
            xx = uniaxial_x(xf, sv, model)
            out = np.full(xf.size, -np.inf)  # off the branch (lock reached): no maximum here
            g = np.isfinite(xx)
            out[g] = -_uniaxial_path_detK(xf[g], xx[g], model)[0]
            return out.reshape(shp)

        lam1 = scan_first_up(F, l10, top)
    lam1g = np.where(np.isfinite(lam1), lam1, 1.0)
    x = uniaxial_x(lam1g, sf, model)
    x = np.where(np.isfinite(lam1), x, np.nan)
    with np.errstate(invalid="ignore"):
        I1 = lam1g**2 + x + 1.0 / (lam1g**2 * x)
        dW = model.dW(np.where(np.isfinite(I1), I1, 3.0))
        E0 = np.sqrt(2 * dW * (lam1g**2 * x**2 - 1.0)) / (lam1g**2 * x)
    E0 = np.where(np.isfinite(lam1), E0, np.nan)
    return scalar_or_array(lam1.reshape(shape), E0.reshape(shape))


@representable
def no_maximum_threshold(model=None, loading: str = "equibiaxial") -> float:
    """Dead load ``s`` above which the fixed-``s`` curve has no maximum of ``E0``.

    Parameters
    ----------
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).
    loading : {"equibiaxial", "uniaxial"}

    Returns
    -------
    s_max : float
        ``max`` over the voltage-limit locus of the load ``s`` whose loading
        curve passes through it; ``inf`` for neo-Hookean (every curve has a
        maximum) and for models whose locus load keeps growing within the
        scanned range.

    Notes
    -----
    Fig. gent-d-e: "for the larger values of s there is no maximum". For
    ``Gent(97.2)`` the threshold is ``s = 2.052``: the ``s = 2`` curve nearly
    touches the locus (hence the paper's switch to ``s = 2.3``, which has no
    maximum). Along the
    locus ``det H* = 0`` the load of the curve through it first grows, then
    falls as Gent stiffening sets in; curves with larger ``s`` miss the locus.

    Examples
    --------
    >>> from analytic import no_maximum_threshold, Gent
    >>> round(no_maximum_threshold(Gent(97.2)), 4)
    2.052
    """
    model = as_model(model)
    check_choice("loading", loading, _LOADINGS)
    if isinstance(model, NeoHookean):
        return float("inf")
    I1max = model.I1_max()
    if loading == "equibiaxial":
        lo_lim, hi_lim = equibiaxial_limits(model)
        top = hi_lim * (1 - 1e-9) if np.isfinite(hi_lim) else 1e3

        def S(lam):
            m, dW, _ = _equi_elastic(lam, model)
            return (2 * dW * (lam**6 - 1.0) - lam**6 * m / 6.0) / lam**5

    else:
        top = float(np.max(np.roots([1.0, 0.0, -I1max, 2.0]).real)) * (1 - 1e-9) if np.isfinite(I1max) else 1e3

        def S(l1):
            x = _uniaxial_locus_x(l1, model)
            I1 = l1**2 + x + 1.0 / (l1**2 * x)
            with np.errstate(invalid="ignore"):
                val = 2 * model.dW(np.where(np.isfinite(I1), I1, 3.0)) * (l1 - x / l1)
            return np.where(np.isfinite(x), val, -np.inf)

    grid = 1.0 + (top - 1.0) * np.linspace(0.0, 1.0, 4001)[1:] ** 2
    vals = S(grid)
    k = int(np.argmax(vals))
    if k == grid.size - 1 and not np.isfinite(I1max):
        return float("inf")
    # golden-section refinement around the grid maximum (a scalar problem)
    a, b = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    fc, fd = golden_section_max(lambda x: S(np.array([x]))[0], a, b)
    return float(max(fc, fd, vals[k]))

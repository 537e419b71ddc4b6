"""Ideal-dielectric material laws evaluated pointwise (vectorised over quadrature points).

The total energy density (per reference volume) of the mixed, fully coupled formulation is

.. math::

    \\psi(F, p, G) = W(I_1) + p (J - 1) - \\frac{p^2}{2\\kappa}
                   - \\frac{\\varepsilon}{2} J\\, G \\cdot C^{-1} G,
    \\qquad G = \\mathrm{Grad}\\,\\phi = -E_L,

plus ``-mu0 ln J`` (``mu0 = 2 W'(3)``, see ``stress_free_reference`` of
:func:`ideal_dielectric_response`; it vanishes for ``J = 1``), i.e. the paper's
Eq. (modelE) ``Omega = W(I1) - eps/2 E_L.(C^-1 E_L)`` with the factor ``J``
that makes ``D = eps E`` hold exactly also where the discrete ``J`` differs from one (for
``J = 1`` it is Eq. (modelE) itself).  ``kappa = inf`` (default) is the exactly
incompressible mixed form.  The *penalty* form drops ``p`` and uses
``W + kappa (J - 1)^2 / 2`` instead (the paper's COMSOL choice, Sec. 6); its error is
``O(mu/kappa)``.  ``I1 = tr C`` is the full (not isochoric) invariant, as in the paper.

Derived quantities (``Finv = F^-1``, ``a = F^-T G = -E``, ``b = C^-1 G``):

* first Piola stress
  ``dpsi/dF = 2 W1 F + (p J - mu0) F^-T + eps J a (x) b - eps/2 J |a|^2 F^-T``
  (its push-forward ``J^-1 P F^T`` is ``2 W1 b_L + p I`` plus the Maxwell stress
  ``eps (E (x) E - |E|^2/2 I)``); the physical pressure is ``-p``;
* Lagrangian electric displacement ``D_L = dpsi/dG = -eps J C^-1 G`` (``= eps J C^-1 E_L``,
  so ``D = J^-1 F D_L = eps E``);
* the consistent second derivatives ``A_FF``, ``A_FG``, ``A_GG``, ``A_Fp``, ``A_pp``.

All arrays carry the tensor indices first and any number of trailing point axes, e.g.
``F`` of shape ``(3, 3, nel, nqp)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

__all__ = ["NeoHookeanDielectric", "GentDielectric", "IdealDielectric", "PointResponse",
           "ideal_dielectric_response"]


def _check_positive(name: str, value: float) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return v


def _check_int(name: str, value) -> int:
    if int(value) != value or int(value) < 1:
        raise ValueError(f"{name} must be a positive integer, got {value!r}")
    return int(value)


@dataclass(frozen=True)
class NeoHookeanDielectric:
    """Neo-Hookean ideal dielectric, ``W = mu/2 (I1 - 3)``, Eq. (gent)_1.

    Parameters
    ----------
    mu
        Shear modulus (> 0).
    eps
        Permittivity (> 0).
    """

    mu: float = 1.0
    eps: float = 1.0

    def __post_init__(self):
        _check_positive("mu", self.mu)
        _check_positive("eps", self.eps)

    def energy_derivatives(self, I1: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(W, dW/dI1, d2W/dI1^2)`` at ``I1``."""
        I1 = np.asarray(I1, dtype=float)
        return 0.5 * self.mu * (I1 - 3.0), np.full_like(I1, 0.5 * self.mu), np.zeros_like(I1)


@dataclass(frozen=True)
class GentDielectric:
    """Gent ideal dielectric, ``W = -mu Jm/2 ln(1 - (I1 - 3)/Jm)``, Eq. (gent)_2.

    Parameters
    ----------
    mu, eps
        Shear modulus and permittivity (> 0).
    Jm
        Stiffening parameter (> 0; the paper uses 97.2).

    Notes
    -----
    Beyond the locking limit ``I1 >= 3 + Jm`` the energy is undefined: the derivatives are
    ``nan`` there, which makes a Newton iteration fail (and the ramp cut back) instead of
    producing a wrong state.
    """

    mu: float = 1.0
    eps: float = 1.0
    Jm: float = 97.2

    def __post_init__(self):
        _check_positive("mu", self.mu)
        _check_positive("eps", self.eps)
        _check_positive("Jm", self.Jm)

    def energy_derivatives(self, I1: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(W, dW/dI1, d2W/dI1^2)`` at ``I1`` (``nan`` beyond the locking limit)."""
        I1 = np.asarray(I1, dtype=float)
        g = 1.0 - (I1 - 3.0) / self.Jm
        g = np.where(g > 0, g, np.nan)
        W = -0.5 * self.mu * self.Jm * np.log(g)
        W1 = 0.5 * self.mu / g
        W11 = 0.5 * self.mu / (self.Jm * g * g)
        return W, W1, W11


@dataclass(frozen=True)
class IdealDielectric:
    """Ideal dielectric with a user strain energy ``W(I1)``.

    Parameters
    ----------
    W, dW, d2W
        Vectorised callables ``W(I1)``, ``W'(I1)``, ``W''(I1)`` (``W`` in the same stress
        units as ``mu``).
    mu
        Shear modulus in the reference state (``mu = 2 W'(3)``), used only for scaling.
    eps
        Permittivity (> 0).
    """

    W: Callable[[np.ndarray], np.ndarray]
    dW: Callable[[np.ndarray], np.ndarray]
    d2W: Callable[[np.ndarray], np.ndarray]
    mu: float = 1.0
    eps: float = 1.0

    def __post_init__(self):
        _check_positive("mu", self.mu)
        _check_positive("eps", self.eps)
        for name in ("W", "dW", "d2W"):
            if not callable(getattr(self, name)):
                raise ValueError(f"{name} must be callable, got {getattr(self, name)!r}")

    def energy_derivatives(self, I1: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(W, dW/dI1, d2W/dI1^2)`` at ``I1``."""
        I1 = np.asarray(I1, dtype=float)
        return (np.broadcast_to(self.W(I1), I1.shape).astype(float),
                np.broadcast_to(self.dW(I1), I1.shape).astype(float),
                np.broadcast_to(self.d2W(I1), I1.shape).astype(float))


@dataclass
class PointResponse:
    """Energy density and its derivatives at points (tensor indices first).

    Attributes
    ----------
    psi
        Total energy density.
    P
        ``dpsi/dF`` (first Piola stress incl. pressure and electric part), ``(3, 3, ...)``.
    dpsi_dp
        ``J - 1 - p/kappa`` (mixed form; zero array for the penalty form).
    D_L
        ``dpsi/dG``, the Lagrangian electric displacement, ``(3, ...)``.
    A_FF, A_FG, A_GG, A_Fp
        Second derivatives ``d2psi/dF_aK dF_bL`` ``(3,3,3,3,...)``,
        ``d2psi/dF_aK dG_L`` ``(3,3,3,...)``, ``d2psi/dG_K dG_L`` ``(3,3,...)`` and
        ``d2psi/dF_aK dp = J Finv_Ka`` ``(3,3,...)``.
    A_pp
        ``-1/kappa`` (scalar).
    J
        ``det F``.
    """

    psi: np.ndarray
    P: np.ndarray
    dpsi_dp: np.ndarray
    D_L: np.ndarray
    A_FF: np.ndarray
    A_FG: np.ndarray
    A_GG: np.ndarray
    A_Fp: np.ndarray
    A_pp: float
    J: np.ndarray


def _det_inv(F: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Determinant and inverse of 3x3 matrices stored as ``F[a, K, ...]``."""
    a, b, c = F[0, 0], F[0, 1], F[0, 2]
    d, e, f = F[1, 0], F[1, 1], F[1, 2]
    g, h, i = F[2, 0], F[2, 1], F[2, 2]
    c00, c01, c02 = e * i - f * h, c * h - b * i, b * f - c * e
    c10, c11, c12 = f * g - d * i, a * i - c * g, c * d - a * f
    c20, c21, c22 = d * h - e * g, b * g - a * h, a * e - b * d
    J = a * c00 + b * c10 + c * c20
    inv = np.array([[c00, c01, c02], [c10, c11, c12], [c20, c21, c22]]) / J
    return J, inv


def ideal_dielectric_response(material, F: np.ndarray, G: np.ndarray,
                              p: np.ndarray | None = None, kappa: float = math.inf,
                              formulation: str = "mixed", need_tangent: bool = True,
                              stress_free_reference: bool = True) -> PointResponse:
    """Energy density, first derivatives and consistent tangent of the ideal dielectric.

    Parameters
    ----------
    material
        :class:`NeoHookeanDielectric`, :class:`GentDielectric` or :class:`IdealDielectric`.
    F
        Deformation gradient ``(3, 3, ...)``.
    G
        Referential potential gradient ``Grad phi = -E_L``, ``(3, ...)``.
    p
        Pressure-like multiplier (mixed form), shape ``(...)``; ignored for the penalty.
    kappa
        Bulk modulus; ``inf`` = exactly incompressible (mixed only).
    formulation
        ``"mixed"`` (``p (J-1) - p^2/(2 kappa)``) or ``"penalty"`` (``kappa (J-1)^2 / 2``).
    need_tangent
        If False only ``psi``, ``P``, ``dpsi_dp`` and ``D_L`` are computed (the tangent
        fields are empty arrays).
    stress_free_reference
        Add ``-mu0 ln J`` with ``mu0 = 2 W'(3)`` (default True).  It vanishes for
        ``J = 1``, so the incompressible model is unchanged, but it makes the reference
        state stress-free with ``p = 0`` instead of ``p = -mu``.  Without it the large
        hydrostatic pre-stress ``p (F^-T : Grad v)^2`` in the discrete tangent is only
        weakly controlled by the Q1 pressure space and makes discretely divergence-free
        modes at free corners unstable (observed: spurious negative eigenvalues and Newton
        stagnation on the clamped plate at ``s ~ 0.2``).  For the penalty form it gives the
        usual compressible neo-Hookean ``mu/2 (I1 - 3) - mu ln J + kappa (J-1)^2/2``.

    Returns
    -------
    PointResponse

    Notes
    -----
    Eq. (modelE) with ``I5 = E_L.(C^-1 E_L)``, multiplied by ``J`` (see the module
    docstring); the stresses are verified against finite differences of ``psi`` and the
    tangent against finite differences of the stresses in ``tests/test_fe_materials.py``.
    """
    if formulation not in ("mixed", "penalty"):
        raise ValueError(f"formulation must be 'mixed' or 'penalty', got {formulation!r}")
    kappa = float(kappa)
    if not kappa > 0:
        raise ValueError(f"kappa must be > 0, got {kappa}")
    if formulation == "penalty" and not math.isfinite(kappa):
        raise ValueError("kappa must be finite for the penalty formulation, got inf")
    eps = material.eps
    J, Finv = _det_inv(F)
    I1 = (F * F).sum(axis=(0, 1))
    W, W1, W11 = material.energy_derivatives(I1)
    a = (Finv * G[:, None]).sum(axis=0)                  # F^-T G
    bvec = (Finv * a[None]).sum(axis=1)                  # C^-1 G
    aa = (a * a).sum(axis=0)
    FinvT = np.swapaxes(Finv, 0, 1)                      # FinvT[a, K] = Finv[K, a]
    if formulation == "mixed":
        if p is None:
            p = np.zeros_like(J)
        pe = p
        vol = p * (J - 1.0) - (0.5 * p * p / kappa if math.isfinite(kappa) else 0.0)
        dpsi_dp = J - 1.0 - (p / kappa if math.isfinite(kappa) else 0.0)
        A_pp = -1.0 / kappa if math.isfinite(kappa) else 0.0
    else:
        pe = kappa * (J - 1.0)
        vol = 0.5 * kappa * (J - 1.0) ** 2
        dpsi_dp = np.zeros_like(J)
        A_pp = 0.0
    mu0 = 2.0 * float(material.energy_derivatives(np.array(3.0))[1]) if stress_free_reference \
        else 0.0
    with np.errstate(invalid="ignore", divide="ignore"):   # J <= 0 -> nan -> Newton rejects
        psi = W + vol - 0.5 * eps * J * aa - mu0 * np.log(J)
    P = (2.0 * W1 * F + (pe * J - 0.5 * eps * J * aa - mu0) * FinvT
         + eps * J * (a[:, None] * bvec[None]))
    D_L = -eps * J * bvec
    if not need_tangent:
        e = np.empty(0)
        return PointResponse(psi, P, dpsi_dp, D_L, e, e, e, e, A_pp, J)

    Cinv = (Finv[:, None] * Finv[None]).sum(axis=2)
    eJ = eps * J
    M = a[:, None] * bvec[None]                                    # a_a b_K

    def outer(X, Y):   # X_aK Y_bL
        return X[:, :, None, None] * Y[None, None]

    def cross(X, Y):   # X_aL Y_bK
        return X[:, None, None, :] * np.swapaxes(Y, 0, 1)[None, :, :, None]

    # coef = pressure + |a|^2 parts of P (their J- and Finv-derivatives)
    coef = pe * J - 0.5 * eJ * aa
    Y = coef * FinvT + eJ * M
    # outer terms: 4 W11 F F + coef FT FT + eJ (FT M + M FT) (+ kappa J^2 FT FT)
    A = outer(F, 4.0 * W11 * F) + outer(FinvT, Y + (kappa * J * J * FinvT
                                                    if formulation == "penalty" else 0.0))
    A += outer(M, eJ * FinvT)
    # cross terms: -coef Finv_La Finv_Kb - eJ (Finv_La a_b b_K + a_a b_L Finv_Kb)
    A -= cross(FinvT, Y - mu0 * FinvT)
    A -= cross(M, eJ * FinvT)
    # -eJ a_a a_b Cinv_KL
    A -= (eJ * a)[:, None, None, None] * a[None, None, :, None] * Cinv[None, :, None, :]
    # 2 W1 delta_ab delta_KL
    for i in range(3):
        for k in range(3):
            A[i, k, i, k] += 2.0 * W1
    A_FG = eJ * (np.swapaxes(Finv, 0, 1)[:, None, :] * bvec[None, :, None]   # Finv_La b_K
                 + a[:, None, None] * Cinv[None]                             # a_a Cinv_KL
                 - np.swapaxes(Finv, 0, 1)[:, :, None] * bvec[None, None, :])  # b_L Finv_Ka
    A_GG = -eps * J * Cinv
    A_Fp = J * FinvT if formulation == "mixed" else np.zeros_like(FinvT)
    return PointResponse(psi, P, dpsi_dp, D_L, A, A_FG, A_GG, A_Fp, A_pp, J)

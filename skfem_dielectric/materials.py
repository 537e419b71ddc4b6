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
The *isochoric* form (``formulation="isochoric"``, no ``p`` either) is COMSOL's nearly
incompressible hyperelastic law ``W(J^(-2/3) I1) + kappa (J - 1)^2 / 2``, and
``"mixed-isochoric"`` the same energy in the mixed form (``W(J^(-2/3) I1) + p (J - 1) -
p^2/(2 kappa)``: no volumetric locking of the displacement-only form); the strain energy
sees only the distortional invariant ``Ib1 = J^(-2/3) I1``, so the reference state is
stress free without the ``-mu0 ln J`` term and a state with ``J != 1`` has a different
stress than under the penalty form (docs/fe_variants.md compares the two).

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
from typing import Any, Callable

import numpy as np

from .checks import check_energy, check_positive
from .kinematics import det_inv3

__all__ = ["NeoHookeanDielectric", "GentDielectric", "IdealDielectric", "PointResponse",
           "FORMULATIONS", "MIXED_FORMULATIONS", "ideal_dielectric_response",
           "dielectric_response", "make_material"]


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
        check_positive("mu", self.mu)
        check_positive("eps", self.eps)

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
        check_positive("mu", self.mu)
        check_positive("eps", self.eps)
        check_positive("Jm", self.Jm)

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

    Raises
    ------
    ValueError
        A callable that fails, returns non-finite values or an array of another shape than
        ``I1`` on the probe ``I1 = 3 ... 4`` (:data:`skfem_dielectric.checks.ENERGY_PROBE`),
        or ``dW(3) != mu/2``.
    """

    W: Callable[[np.ndarray], np.ndarray]
    dW: Callable[[np.ndarray], np.ndarray]
    d2W: Callable[[np.ndarray], np.ndarray]
    mu: float = 1.0
    eps: float = 1.0

    def __post_init__(self):
        check_positive("mu", self.mu)
        check_positive("eps", self.eps)
        for name in ("W", "dW", "d2W"):
            if not callable(getattr(self, name)):
                raise ValueError(f"{name} must be callable, got {getattr(self, name)!r}")
        check_energy("IdealDielectric", {"W": self.W, "dW": self.dW, "d2W": self.d2W},
                     0.5 * float(self.mu))

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
        ``J - 1 - p/kappa`` (mixed form; zero array for the penalty and isochoric forms).
    D_L
        ``dpsi/dG``, the Lagrangian electric displacement, ``(3, ...)``.
    A_FF, A_FG, A_GG, A_Fp
        Second derivatives ``d2psi/dF_aK dF_bL`` ``(3,3,3,3,...)``,
        ``d2psi/dF_aK dG_L`` ``(3,3,3,...)``, ``d2psi/dG_K dG_L`` ``(3,3,...)`` and
        ``d2psi/dF_aK dp = J Finv_Ka`` ``(3,3,...)``.  (:func:`dielectric_response`, used
        by the assembly, returns them points-first, in the layouts it documents.)
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


#: the volumetric treatments: mixed u-p, penalty ``kappa (J-1)^2/2`` on ``W(I1)``,
#: COMSOL's isochoric ``W(J^(-2/3) I1) + kappa (J-1)^2/2``, and the mixed form without the
#: ``-mu0 ln J`` of the stress-free reference (``"mixed-plain"``)
FORMULATIONS = ("mixed", "penalty", "isochoric", "mixed-isochoric", "mixed-plain")
#: the formulations with the pressure-like unknown ``p``
MIXED_FORMULATIONS = ("mixed", "mixed-isochoric", "mixed-plain")


def _check_form(formulation: str, kappa: float) -> float:
    if formulation not in FORMULATIONS:
        raise ValueError(f"formulation must be one of {FORMULATIONS}, got {formulation!r}")
    kappa = float(kappa)
    if not kappa > 0:
        raise ValueError(f"kappa must be > 0, got {kappa}")
    if formulation not in MIXED_FORMULATIONS and not math.isfinite(kappa):
        raise ValueError(f"kappa must be finite for the {formulation} formulation, got inf")
    return kappa


def _strain_energy(material, F: np.ndarray, I1: np.ndarray, J: np.ndarray,
                   FinvT: np.ndarray, isochoric: bool):
    """``W``, and the strain-energy stress ``2 W1e F + c FinvT`` with the derivative
    ``T = dW1e/dF`` (``[b, L, ...]``) that its tangent needs.

    Full invariant: ``W(I1)``, ``W1e = W'``, ``c = 0``, ``T = 2 W'' F``.  Isochoric:
    ``W(Ib1)``, ``Ib1 = J^(-2/3) I1``, ``W1e = J^(-2/3) W'``, ``c = -2/3 W1e I1`` and
    ``T = W'' J^(-2/3) dIb1/dF - 2/3 W1e F^-T`` with
    ``dIb1/dF = 2 J^(-2/3) (F - I1/3 F^-T)``.
    """
    if not isochoric:
        W, W1, W11 = material.energy_derivatives(I1)
        return W, W1, 0.0, 2.0 * W11 * F
    with np.errstate(invalid="ignore", divide="ignore"):   # J <= 0 -> nan -> Newton rejects
        j23 = np.where(J > 0, np.cbrt(J) ** -2, np.nan)
    W, W1, W11 = material.energy_derivatives(j23 * I1)
    W1e = j23 * W1
    dIb = 2.0 * j23 * (F - (I1 / 3.0) * FinvT)
    return W, W1e, -2.0 / 3.0 * W1e * I1, W11 * j23 * dIb - (2.0 / 3.0) * W1e * FinvT


def _points_first(T: np.ndarray, s: np.ndarray | None, nt: int) -> np.ndarray:
    """Contiguous copy of ``T`` (``nt`` tensor axes first) with the point axes first,
    times the weights ``s`` (one pass)."""
    pts = T.shape[nt:]
    out = np.empty(pts + T.shape[:nt])
    src = np.moveaxis(T, tuple(range(nt)), tuple(range(-nt, 0)))
    if s is None:
        out[...] = src
    else:
        np.multiply(src, s.reshape(s.shape + (1,) * nt), out=out)
    return out


def dielectric_response(material, F: np.ndarray, G: np.ndarray, p: np.ndarray | None,
                        kappa: float, formulation: str, need_tangent: bool,
                        stress_free_reference: bool, weights: np.ndarray | None,
                        grad_div: float = 0.0) -> PointResponse:
    """Core of :func:`ideal_dielectric_response` in the assembly layout.

    Tensor-first ``F``, ``G``, ``psi``, ``P``,
    ``D_L``; the tangent (times ``weights``) in the assembly layout, point axes first:
    ``A_FF[..., K, a, b, L]``, ``A_FG[..., K, a, L]``, ``A_GG[..., K, L]``,
    ``A_Fp[..., K, a]``.

    The fourth-order tangent is two batched products of small matrices: the dyads
    ``X_aK Y_bL`` (``2 F (x) dW1e/dF``, i.e. ``4 W'' F F`` for the full invariant, the
    pressure / ``|a|^2`` terms, ``M F^-T``, and ``-eps J a a C^-1`` written as three dyads
    through ``C^-1 = F^-1 F^-T``) and the two crossed terms ``X_aL Y_bK``, plus
    ``2 W1e I`` (``W1e = W'``, or ``J^(-2/3) W'(Ib1)`` for the isochoric form, whose
    ``F^-T`` coefficient ``-2/3 W1e I1`` adds its own derivative to the first dyad).
    ``grad_div`` adds ``gamma (J - 1)^2 / 2`` to the mixed form (see
    :func:`ideal_dielectric_response`).
    """
    kappa = _check_form(formulation, kappa)
    eps = material.eps
    J, Finv = det_inv3(F)
    I1 = (F * F).sum(axis=(0, 1))
    a = (Finv * G[:, None]).sum(axis=0)                  # F^-T G
    bvec = (Finv * a[None]).sum(axis=1)                  # C^-1 G
    aa = (a * a).sum(axis=0)
    FinvT = np.swapaxes(Finv, 0, 1)                      # FinvT[a, K] = Finv[K, a]
    iso = formulation in ("isochoric", "mixed-isochoric")
    mixed = formulation in MIXED_FORMULATIONS
    W, W1, c_iso, T = _strain_energy(material, F, I1, J, FinvT, iso)
    finite_k = math.isfinite(kappa)
    if mixed:
        if p is None:
            p = np.zeros_like(J)
        pe = p
        vol = p * (J - 1.0) - (0.5 * p * p / kappa if finite_k else 0.0)
        if grad_div:
            pe = p + grad_div * (J - 1.0)
            vol = vol + 0.5 * grad_div * (J - 1.0) ** 2
        dpsi_dp = J - 1.0 - (p / kappa if finite_k else 0.0)
        A_pp = -1.0 / kappa if finite_k else 0.0
    else:
        pe = kappa * (J - 1.0)
        vol = 0.5 * kappa * (J - 1.0) ** 2
        dpsi_dp = np.zeros_like(J)
        A_pp = 0.0
    mu0 = 2.0 * float(material.energy_derivatives(np.array(3.0))[1]) \
        if stress_free_reference and not iso and formulation != "mixed-plain" else 0.0
    eJ = eps * J
    with np.errstate(invalid="ignore", divide="ignore"):   # J <= 0 -> nan -> Newton rejects
        psi = W + vol - 0.5 * eJ * aa - mu0 * np.log(J)
    coef = pe * J - 0.5 * eJ * aa
    M = a[:, None] * bvec[None]                                    # M[a, K] = a_a b_K
    P = 2.0 * W1 * F + (coef + c_iso - mu0) * FinvT + eJ * M
    D_L = -eJ * bvec
    if not need_tangent:
        e = np.empty(0)
        return PointResponse(psi, P, dpsi_dp, D_L, e, e, e, e, A_pp, J)

    shp = J.shape
    s = None if weights is None else np.broadcast_to(weights, shp)
    sw = 1.0 if s is None else s
    Y = coef * FinvT + eJ * M                                      # [b, L]
    # dyads X_aK Y_bL: X stored [m, K, a], Y stored [m, b, L]
    Xd = [Finv, np.swapaxes(M, 0, 1)]
    stiff = grad_div if mixed else kappa                         # d(pe)/dJ
    Y0 = Y + stiff * J * J * FinvT if stiff else Y
    if iso:     # d(c_iso)/dF = -2/3 (I1 T + 2 W1e F)
        Y0 = Y0 - (2.0 / 3.0) * (I1 * T + 2.0 * W1 * F)
    Yd = [Y0, eJ * FinvT]
    for m in range(3):     # -eJ a_a a_b Cinv_KL = sum_m (Finv_Km a_a)(-eJ a_b Finv_Lm)
        Xd.append(Finv[:, m][:, None] * a[None])
        Yd.append(-eJ * a[:, None] * Finv[:, m][None])
    if iso or np.any(T != 0.0):      # 2 F_aK dW1e/dF_bL
        Xd.append(np.swapaxes(F, 0, 1))
        Yd.append(2.0 * T)
    nm = len(Xd)
    X = _points_first(np.array(Xd).reshape((nm, 9) + shp), None, 2).swapaxes(-1, -2)
    Yw = _points_first(np.array(Yd).reshape((nm, 9) + shp), s, 2)
    A = (X @ Yw).reshape(shp + (3, 3, 3, 3))                        # [K, a, b, L]
    # crossed terms -(X_aL Y_bK): X stored [L, a], Y stored [b, K]; product [L, a, b, K]
    Xc = _points_first(np.array([Finv, bvec[:, None] * a[None]]).reshape((2, 9) + shp),
                       None, 2).swapaxes(-1, -2)
    Yc = _points_first(np.array([Y + (c_iso - mu0) * FinvT, eJ * FinvT]).reshape((2, 9) + shp),
                       s, 2)
    A -= np.swapaxes((Xc @ Yc).reshape(shp + (3, 3, 3, 3)), -4, -1)
    d = 2.0 * W1 * sw
    for i in range(3):
        for k in range(3):
            A[..., k, i, i, k] += d
    # A_FG[a,K,L] = eJ (Finv_La b_K + a_a Cinv_KL - b_L Finv_Ka), stored [K, a, L]
    Cinv = (Finv[:, None] * Finv[None]).sum(axis=2)
    A_FG = eJ * (bvec[:, None, None] * FinvT[None]
                 + a[None, :, None] * Cinv[:, None, :] - Finv[:, :, None] * bvec[None, None])
    A_GG = -eps * J * Cinv
    A_Fp = J * Finv if mixed else np.zeros_like(Finv)
    return PointResponse(psi, P, dpsi_dp, D_L, A, _points_first(A_FG, s, 3),
                         _points_first(A_GG, s, 2), _points_first(A_Fp, s, 2), A_pp, J)


def ideal_dielectric_response(material, F: np.ndarray, G: np.ndarray,
                              p: np.ndarray | None = None, kappa: float = math.inf,
                              formulation: str = "mixed", need_tangent: bool = True,
                              stress_free_reference: bool = True,
                              grad_div: float = 0.0) -> PointResponse:
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
        Pressure-like multiplier (mixed form), shape ``(...)``; ignored otherwise.
    kappa
        Bulk modulus; ``inf`` = exactly incompressible (mixed only).
    formulation
        ``"mixed"`` (``W(I1) + p (J-1) - p^2/(2 kappa)``), ``"penalty"``
        (``W(I1) + kappa (J-1)^2 / 2``), ``"isochoric"``
        (``W(J^(-2/3) I1) + kappa (J-1)^2 / 2``, COMSOL's nearly incompressible form) or
        ``"mixed-isochoric"`` (``W(J^(-2/3) I1) + p (J-1) - p^2/(2 kappa)``) or
        ``"mixed-plain"`` (``"mixed"`` without the ``-mu0 ln J`` of
        ``stress_free_reference``: the paper's ``W(I1) + p (J-1)``, reference pressure
        ``p = -mu``; the three mixed forms agree wherever ``J = 1``).
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
        Not used by the isochoric forms, whose reference state is stress free as it is,
        nor by ``"mixed-plain"``.
    grad_div
        ``gamma >= 0``: adds ``gamma (J - 1)^2 / 2`` to the mixed form (grad-div
        stabilisation).  It vanishes with its first derivative where ``J = 1``, so exact
        incompressible solutions (every homogeneous state) are unchanged, and adds
        ``gamma (F^-T : Grad v)^2`` to the tangent.  That term controls the modes that are
        divergence free only against the Q1 pressures, on which the hydrostatic part
        ``p (F^-T : Grad v)^2`` of the tangent acts: without it, where ``p`` is strongly
        negative (compressed or charged states with a free surface) such mesh-scale
        surface modes have negative energy below the continuum's onset.  ``gamma`` of a
        few ``mu`` plus ``|p|`` removes them (docs/stability.md).

    Returns
    -------
    PointResponse
        Tensor indices first (``A_FF[a, K, b, L, ...]`` etc.; the tangent fields are views
        of the points-first arrays the assembly uses).

    Notes
    -----
    Eq. (modelE) with ``I5 = E_L.(C^-1 E_L)``, multiplied by ``J`` (see the module
    docstring); the stresses are verified against finite differences of ``psi`` and the
    tangent against finite differences of the stresses in ``tests/fe/test_fe_materials.py``.
    """
    F = np.asarray(F, dtype=float)
    if not (math.isfinite(float(grad_div)) and grad_div >= 0):
        raise ValueError(f"grad_div must be a finite number >= 0, got {grad_div!r}")
    r = dielectric_response(material, F, np.asarray(G, dtype=float), p, kappa, formulation,
                            need_tangent, stress_free_reference, None, grad_div)
    if need_tangent:
        r.A_FF = np.moveaxis(r.A_FF, (-3, -4, -2, -1), (0, 1, 2, 3))
        r.A_FG = np.moveaxis(r.A_FG, (-2, -3, -1), (0, 1, 2))
        r.A_GG = np.moveaxis(r.A_GG, (-2, -1), (0, 1))
        r.A_Fp = np.moveaxis(r.A_Fp, (-1, -2), (0, 1))
    return r


def make_material(model: Any = "neo-Hookean", Jm: float = 97.2):
    """Dimensionless material (``mu = eps = 1``) from a model name or object.

    Parameters
    ----------
    model
        ``"neo-Hookean"``, ``"Gent"`` (with ``Jm``), or a material object
        (``NeoHookeanDielectric``, ``GentDielectric``, ``IdealDielectric``) used as is.
    Jm
        Gent stiffening parameter.
    """
    if isinstance(model, (NeoHookeanDielectric, GentDielectric, IdealDielectric)):
        return model
    if isinstance(model, str):
        key = model.lower().replace("-", "").replace("_", "").replace(" ", "")
        if key in ("neohookean", "nh"):
            return NeoHookeanDielectric(1.0, 1.0)
        if key == "gent":
            return GentDielectric(1.0, 1.0, Jm)
    raise ValueError(f"model must be 'neo-Hookean', 'Gent' or a material object, got {model!r}")

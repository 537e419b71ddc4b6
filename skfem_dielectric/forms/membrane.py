"""Membrane weak form of a thin incompressible dielectric plate (in-plane x1-x3).

The plate of reference thickness ``H`` is described by its mid-surface, with
coordinates ``(X1, X3)`` and in-plane displacement ``u = (u1, u3)``. Plane
stress holds through the thickness; exact incompressibility gives the thickness
stretch ``lam2 = 1/sqrt(det C) = 1/det F`` with ``F`` the 2x2 in-plane
deformation gradient and ``C = F^T F``. The energy per reference area is

* charge control (``D_L = sigma_F`` per reference area fixed, Eq. modelD)::

      psi = H [ W(I1) + lam2^2 D_L^2 / (2 eps) ],   I1 = tr C + lam2^2

* voltage control (``E_L = -V/H`` fixed, Eq. modelE)::

      psi = H [ W(I1) - (eps/2) lam2^-2 E_L^2 ]

so the model has the displacement as its only unknown, is exactly
incompressible and has a symmetric tangent. On an equi-biaxial state
``lam1 = lam3 = lam`` it reproduces Eq. (loading_gent); on a uni-axial state
Eq. (DEuniax).

This module holds the pointwise kernels -- energy, first Piola stress, tangent, and the
follower traction of the Maxwell coupling on the edges -- vectorised over trailing axes
``(..., nel, nqp)`` with the component axes first (scikit-fem convention ``F[i, j, ...]``).
The weak form is ``int_A P : Grad v dA = s int_{edges} mu H e . v dL`` (dead load), plus,
for the Maxwell coupling, the edge traction's virtual work.
"""

from __future__ import annotations

import numpy as np

from ..kinematics import det2, inv_t2

__all__ = ["membrane_kernel", "edge_maxwell_traction"]


def membrane_kernel(
    F: np.ndarray,
    material,
    D_L: float = 0.0,
    E_L: float | None = None,
    H: float = 1.0,
):
    """Energy, stress and tangent of the incompressible dielectric membrane.

    Parameters
    ----------
    F : ndarray, shape (2, 2, ...)
        In-plane deformation gradient ``dx_a/dX_b`` (components x1, x3).
    material : NeoHookeanDielectric, GentDielectric or IdealDielectric
        Gives ``W(I1)`` and its derivatives (``energy_derivatives``) and ``eps``.
    D_L : float or ndarray
        Lagrangian electric displacement through the thickness (the surface
        charge per reference area, charge control). Ignored when ``E_L`` is
        given.
    E_L : float or ndarray, optional
        Lagrangian electric field through the thickness (voltage control).
    H : float
        Reference thickness (multiplies everything: energy per reference area).

    Returns
    -------
    psi : ndarray, shape (...)
        Energy per reference area.
    P : ndarray, shape (2, 2, ...)
        ``dpsi/dF`` (membrane first Piola force per reference length).
    A : ndarray, shape (2, 2, 2, 2, ...)
        ``d2psi/dF dF`` (symmetric in the pairs ``(ij) <-> (kl)``).

    Notes
    -----
    With ``J = det F`` (so ``lam2 = 1/J``), ``I1 = |F|^2 + m(J)`` with
    ``m = J^-2`` and the electric part ``g(J) = D_L^2 J^-2 / (2 eps)`` (charge)
    or ``g(J) = -eps E_L^2 J^2 / 2`` (voltage). With ``G = F^-T``,
    ``dJ/dF = J G`` and ``d2J/dF_ij dF_kl = J (G_ij G_kl - G_il G_kj)``;
    the tangent of ``psi = W(I1) + g(J)`` follows by the chain rule.
    Equi-biaxial: ``s = lam - lam^-5 - lam^-5 D0^2``, Eq. (loading_gent).
    """
    F = np.asarray(F, dtype=float)
    eps = material.eps
    J = det2(F)
    G = inv_t2(F, J)
    m, m1, m2 = J**-2, -2.0 * J**-3, 6.0 * J**-4
    if E_L is None:
        a = np.asarray(D_L, dtype=float) ** 2 / (2.0 * eps)
        g, g1, g2 = a * J**-2, -2.0 * a * J**-3, 6.0 * a * J**-4
    else:
        b = eps * np.asarray(E_L, dtype=float) ** 2 / 2.0
        g, g1, g2 = -b * J**2, -2.0 * b * J, -2.0 * b * np.ones_like(J)
    I1 = np.einsum("ij...,ij...->...", F, F) + m
    w, w1, w2 = material.energy_derivatives(I1)
    dI1 = 2.0 * F + m1 * J * G
    psi = H * (w + g)
    P = H * (w1 * dI1 + g1 * J * G)
    GG = np.einsum("ij...,kl...->ijkl...", G, G)
    GGx = np.einsum("il...,kj...->ijkl...", G, G)
    eye = np.eye(2)
    II = np.einsum("ik,jl->ijkl", eye, eye).reshape((2, 2, 2, 2) + (1,) * J.ndim)
    d2I1 = 2.0 * II + m2 * J**2 * GG + m1 * J * (GG - GGx)
    A = H * (
        w2 * np.einsum("ij...,kl...->ijkl...", dI1, dI1)
        + w1 * d2I1
        + g2 * J**2 * GG
        + g1 * J * (GG - GGx)
    )
    return psi, P, A


def edge_maxwell_traction(F: np.ndarray, N: np.ndarray, c, need_tangent: bool = True):
    """Follower traction ``t = c J^-2 F^-T N`` on the membrane's edges and its F-derivative.

    Parameters
    ----------
    F : ndarray, shape (2, 2, ...)
        In-plane deformation gradient on the edge.
    N : ndarray, shape (2, ...)
        Outward unit normal of the reference edge.
    c : float or ndarray
        ``H sigma_F^2 / (2 eps)`` (times the quadrature weights).
    need_tangent : bool
        Whether ``dt/dF`` is needed.

    Returns
    -------
    t : ndarray, shape (2, ...)
        Force per reference length exerted by the field's lateral pull
        ``H sigma_F^2 lam2^2/(2 eps)`` (``lam2 = 1/J``).
    dt : ndarray, shape (2, 2, 2, ...) or None
        ``dt_i / dF_kl``.
    """
    J = det2(F)
    G = inv_t2(F, J)
    g = np.einsum("iM...,M...->i...", G, N)
    t = c * J**-2 * g
    if not need_tangent:
        return t, None
    dt = -c * J**-2 * (2.0 * np.einsum("kl...,i...->ikl...", G, g)
                       + np.einsum("il...,k...->ikl...", G, g))
    return t, dt

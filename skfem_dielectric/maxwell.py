"""Maxwell-traction coupling: an elastic problem loaded by the field's traction.

The second method of the paper's Sec. 6: instead of solving electrostatics, the
purely elastic incompressible problem is loaded on its deformed boundary by
the Maxwell stress ``tau_m = E (x) D - (E.D)/2 I``.

Field used
----------
The charges sprayed on the faces move with the material, ``N.D_L = -sigma_F``
per reference area (DESIGN.md §2). We take the Lagrangian displacement
uniform through the body, ``D_L = -sigma_F e2`` (the homogeneous solution):
it satisfies Gauss' law ``Div D_L = 0`` and the charge boundary condition
exactly. Its push-forward is

    D = F D_L / J,      E = D / eps,

so on a charged face ``D.n = D_L.N / a`` with ``a = J |F^-T N|`` the local
area stretch: the current surface charge is ``sigma_F / a``, directed along
the deformed thickness fibre ``F e2`` (normal to the faces up to transverse
shear, which is small in a thin plate).

Sign
----
There is no field outside the plate, so the force per current area that the
field exerts on the body is the jump ``(tau_m^out - tau_m^in) n = -tau_m n``
with ``tau_m`` evaluated inside. On a charged face (``n = e2``) this is the
compressive Maxwell pressure ``-(E D/2) n``; on a lateral face (``E . n = 0``)
it is the outward pull ``+(E D/2) n``. Both are needed: the faces' pressure
alone gives only half of the electric term of the loading curve; with the
lateral pull the homogeneous plate follows Eq. (loading_gent) exactly
(``tau_11 = mu(lam1^2 - lam2^2) - D^2/eps``, as in the fully coupled model).

The nominal traction (per reference area) is a follower load,

    t0 = -tau_m cof(F) N
       = -(1/eps) [ (D_L.N) F D_L / J - |F D_L|^2 / (2 J) F^-T N ],

and :func:`maxwell_traction` also returns its exact derivative with respect
to ``F`` for the consistent (non-symmetric) tangent.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "maxwell_traction",
    "maxwell_stress",
]


def _det3(F: np.ndarray) -> np.ndarray:
    return (
        F[0, 0] * (F[1, 1] * F[2, 2] - F[1, 2] * F[2, 1])
        - F[0, 1] * (F[1, 0] * F[2, 2] - F[1, 2] * F[2, 0])
        + F[0, 2] * (F[1, 0] * F[2, 1] - F[1, 1] * F[2, 0])
    )


def _cof3(F: np.ndarray) -> np.ndarray:
    """Cofactor ``J F^-T`` of a field of 3x3 matrices."""
    C = np.empty_like(F)
    C[0, 0] = F[1, 1] * F[2, 2] - F[1, 2] * F[2, 1]
    C[0, 1] = F[1, 2] * F[2, 0] - F[1, 0] * F[2, 2]
    C[0, 2] = F[1, 0] * F[2, 1] - F[1, 1] * F[2, 0]
    C[1, 0] = F[0, 2] * F[2, 1] - F[0, 1] * F[2, 2]
    C[1, 1] = F[0, 0] * F[2, 2] - F[0, 2] * F[2, 0]
    C[1, 2] = F[0, 1] * F[2, 0] - F[0, 0] * F[2, 1]
    C[2, 0] = F[0, 1] * F[1, 2] - F[0, 2] * F[1, 1]
    C[2, 1] = F[0, 2] * F[1, 0] - F[0, 0] * F[1, 2]
    C[2, 2] = F[0, 0] * F[1, 1] - F[0, 1] * F[1, 0]
    return C


def _lagrangian_D(D_L, shape) -> np.ndarray:
    D_L = np.asarray(D_L, dtype=float)
    if D_L.ndim == 0 or D_L.shape[0] != 3:
        # scalar: charge per reference area, field along e2 (thickness)
        out = np.zeros((3,) + tuple(shape))
        out[1] = D_L
        return out
    return np.broadcast_to(D_L.reshape(D_L.shape + (1,) * (len(shape) + 1 - D_L.ndim)),
                           (3,) + tuple(shape))


def maxwell_stress(F: np.ndarray, D_L, eps: float) -> np.ndarray:
    """Maxwell stress ``tau_m = E (x) D - (E.D)/2 I`` of the assumed field.

    Parameters
    ----------
    F : ndarray, shape (3, 3, ...)
        Deformation gradient.
    D_L : float or ndarray, shape (3, ...)
        Lagrangian electric displacement; a scalar means ``D_L e2``.
    eps : float
        Permittivity.

    Returns
    -------
    ndarray, shape (3, 3, ...)
        Cauchy Maxwell stress with ``D = F D_L / J``, ``E = D/eps``.
    """
    F = np.asarray(F, dtype=float)
    J = _det3(F)
    DL = _lagrangian_D(D_L, F.shape[2:])
    d = np.einsum("iM...,M...->i...", F, DL) / J
    dd = np.einsum("i...,i...->...", d, d)
    eye = np.eye(3).reshape((3, 3) + (1,) * J.ndim)
    return (np.einsum("i...,j...->ij...", d, d) - 0.5 * dd * eye) / eps


def maxwell_traction(F: np.ndarray, N: np.ndarray, D_L, eps: float):
    """Nominal Maxwell traction ``t0 = -tau_m cof(F) N`` and its F-derivative.

    Parameters
    ----------
    F : ndarray, shape (3, 3, ...)
        Deformation gradient at boundary points.
    N : ndarray, shape (3, ...)
        Outward unit normal of the reference boundary.
    D_L : float or ndarray, shape (3, ...)
        Lagrangian electric displacement (``-sigma_F`` for charge per
        reference area ``sigma_F``); a scalar means ``D_L e2``.
    eps : float
        Permittivity.

    Returns
    -------
    t0 : ndarray, shape (3, ...)
        Force per reference area exerted by the field on the body.
    dt0 : ndarray, shape (3, 3, 3, ...)
        ``dt0_i / dF_kL`` (the follower-load tangent; not symmetric).

    Notes
    -----
    ``t0 = -(1/eps)[(D_L.N) d/J - |d|^2/(2J) g]`` with ``d = F D_L`` and
    ``g = F^-T N``; ``dd_i/dF_kL = delta_ik D_L,L``, ``dJ/dF_kL = J G_kL`` and
    ``dg_i/dF_kL = -G_iL g_k`` (``G = F^-T``). See the module docstring for
    the field and the sign (paper Sec. 6, second method).
    """
    F = np.asarray(F, dtype=float)
    N = np.asarray(N, dtype=float)
    shape = F.shape[2:]
    J = _det3(F)
    G = _cof3(F) / J
    DL = _lagrangian_D(D_L, shape)
    d = np.einsum("iM...,M...->i...", F, DL)
    g = np.einsum("iM...,M...->i...", G, N)
    DN = np.einsum("M...,M...->...", DL, N)
    dd = np.einsum("i...,i...->...", d, d)
    t0 = -(DN / J * d - 0.5 * dd / J * g) / eps
    eye = np.eye(3).reshape((3, 3) + (1,) * J.ndim)
    da = (DN / J) * (
        np.einsum("ik...,L...->ikL...", eye, DL) - np.einsum("i...,kL...->ikL...", d, G)
    )
    db = (
        np.einsum("k...,L...,i...->ikL...", d, DL, g) / J
        - 0.5 * dd / J * np.einsum("kL...,i...->ikL...", G, g)
        - 0.5 * dd / J * np.einsum("iL...,k...->ikL...", G, g)
    )
    return t0, -(da - db) / eps

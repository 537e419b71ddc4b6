"""Kinematics of fields of small matrices, tensor indices first (``F[a, K, ...]``).

Every FE model builds its deformation gradients and their inverses here: 3x3 determinant,
inverse and cofactor, the 2x2 in-plane versions of the membrane, and the block-diagonal
``F`` of generalised plane strain (``F33 = lam3`` uniform).
"""

from __future__ import annotations

import numpy as np

__all__ = ["det_inv3", "det3", "cof3", "inv3", "det2", "inv_t2", "plane_strain_F",
           "pad3", "second_piola"]


def det_inv3(F: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
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


def det3(F: np.ndarray) -> np.ndarray:
    """``det F`` of a field of 3x3 matrices."""
    return (F[0, 0] * (F[1, 1] * F[2, 2] - F[1, 2] * F[2, 1])
            - F[0, 1] * (F[1, 0] * F[2, 2] - F[1, 2] * F[2, 0])
            + F[0, 2] * (F[1, 0] * F[2, 1] - F[1, 1] * F[2, 0]))


def cof3(F: np.ndarray) -> np.ndarray:
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


def inv3(F: np.ndarray) -> np.ndarray:
    """``F^-1`` of a field of 3x3 matrices (LAPACK, any trailing shape)."""
    return np.moveaxis(np.linalg.inv(np.moveaxis(F, (0, 1), (-2, -1))), (-2, -1), (0, 1))


def det2(F: np.ndarray) -> np.ndarray:
    """``det F`` of a field of 2x2 matrices."""
    return F[0, 0] * F[1, 1] - F[0, 1] * F[1, 0]


def inv_t2(F: np.ndarray, J: np.ndarray) -> np.ndarray:
    """``F^-T`` of a field of 2x2 matrices with determinant ``J``."""
    G = np.empty_like(F)
    G[0, 0] = F[1, 1] / J
    G[0, 1] = -F[1, 0] / J
    G[1, 0] = -F[0, 1] / J
    G[1, 1] = F[0, 0] / J
    return G


def plane_strain_F(gradu: np.ndarray, lam3) -> np.ndarray:
    """``F = [[1 + u1,1, u1,2, 0], [u2,1, 1 + u2,2, 0], [0, 0, lam3]]`` (generalised
    plane strain) from the in-plane displacement gradient ``gradu[i, j, ...]``."""
    F = np.zeros((3, 3) + gradu.shape[2:])
    F[:2, :2] = gradu
    F[0, 0] += 1.0
    F[1, 1] += 1.0
    F[2, 2] = lam3
    return F


def pad3(v: np.ndarray) -> np.ndarray:
    """In-plane vector field ``v[i, ...]`` (i = 1, 2) as a 3D field with zero third component."""
    out = np.zeros((3,) + v.shape[1:])
    out[:2] = v
    return out


def second_piola(F: np.ndarray, P: np.ndarray) -> np.ndarray:
    """Second Piola-Kirchhoff ``S = F^-1 P`` from the first Piola stress ``P[a, K, ...]``."""
    return np.einsum("Ka...,aL...->KL...", inv3(F), P)

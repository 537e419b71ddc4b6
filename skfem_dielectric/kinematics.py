"""Kinematics of fields of small matrices, tensor indices first (``F[a, K, ...]``).

Every FE model builds its deformation gradients and their inverses here: 3x3 determinant,
inverse and cofactor, the 2x2 in-plane versions of the membrane, and the block-diagonal
``F`` of generalised plane strain (``F33 = lam3`` uniform), and the largest step along a
segment of deformation gradients that keeps ``det F > 0`` (:func:`segment_det_limit`, the
step limit of the 3D plate's Newton solves; there the matrices are indexed last,
``F[n, a, K]``).
"""

from __future__ import annotations

import numpy as np

__all__ = ["det_inv3", "det3", "cof3", "inv3", "det2", "inv_t2", "plane_strain_F",
           "pad3", "second_piola", "segment_det_limit"]


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
    """``F^-1`` of a field of 3x3 matrices (any trailing shape), the adjugate over the
    determinant (:func:`det_inv3`; a third of the time of LAPACK's batched inverse on
    the transposed copy it needs)."""
    return det_inv3(F)[1]


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


def segment_det_limit(F0: np.ndarray, dF: np.ndarray, tol: float = 1e-8) -> float:
    """Largest ``alpha`` in ``(0, 1]`` with ``det(F0 + a dF) > tol det F0`` for all ``a`` in
    ``[0, alpha)`` at every point.

    Parameters
    ----------
    F0, dF
        Deformation gradients and their increments, shape ``(n, 3, 3)``; ``det F0 > 0``.
    tol
        Relative floor of the determinant.  A floor above zero also catches a segment that
        only *touches* ``det F = 0`` (a double root, e.g. two stretches passing through
        zero together, which turns the body inside out while ``det F`` keeps its sign).

    Returns
    -------
    float
        1.0 if the whole segment is admissible; 0.0 if ``det F0 <= 0`` somewhere.

    Notes
    -----
    ``det(F0 + a dF) = c0 + c1 a + c2 a^2 + c3 a^3`` with ``c0 = det F0``,
    ``c1 = cof F0 : dF``, ``c2 = cof dF : F0``, ``c3 = det dF``; between the critical
    points of the cubic it is monotone, so its first crossing of the floor is bracketed
    and found by bisection.
    """
    # tensor indices first (views): the coefficients by the closed forms of det3 and cof3
    F0 = np.moveaxis(np.asarray(F0, dtype=float).reshape(-1, 3, 3), 0, 2)
    dF = np.moveaxis(np.asarray(dF, dtype=float).reshape(-1, 3, 3), 0, 2)
    c0 = det3(F0)
    if not np.all(c0 > 0):
        return 0.0
    c1 = np.einsum("ijn,ijn->n", cof3(F0), dF)
    c2 = np.einsum("ijn,ijn->n", cof3(dF), F0)
    c3 = det3(dF)
    g0 = (1.0 - tol) * c0
    # on [0, 1] the cubic is at least g0 - |c1| - |c2| - |c3|: where that is positive the
    # point cannot cross the floor (most points of a Newton step), the others are analysed
    near = np.flatnonzero(np.abs(c1) + np.abs(c2) + np.abs(c3) >= g0)
    if near.size == 0:
        return 1.0
    c0, c1, c2, c3, g0 = c0[near], c1[near], c2[near], c3[near], g0[near]

    def g(a, i=slice(None)):
        return ((c3[i] * a + c2[i]) * a + c1[i]) * a + g0[i]

    # critical points: 3 c3 a^2 + 2 c2 a + c1 = 0 (or linear when c3 = 0)
    qa, qb, qc = 3.0 * c3, 2.0 * c2, c1
    disc = qb * qb - 4.0 * qa * qc
    sq = np.sqrt(np.maximum(disc, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        lin = np.where(qb != 0, -qc / qb, np.nan)
        r1 = np.where(qa != 0, (-qb - sq) / (2.0 * qa), lin)
        r2 = np.where(qa != 0, (-qb + sq) / (2.0 * qa), np.nan)
    r1 = np.where(disc >= 0, r1, np.nan)
    r2 = np.where(disc >= 0, r2, np.nan)
    cps = np.stack([np.zeros_like(c0), r1, r2, np.ones_like(c0)], axis=1)
    cps = np.where((cps > 0) & (cps < 1) | (cps == 0) | (cps == 1), cps, 1.0)
    cps = np.sort(cps, axis=1)
    gv = np.stack([g(cps[:, k]) for k in range(4)], axis=1)
    bad = gv <= 0
    hit = np.nonzero(bad.any(axis=1))[0]
    if hit.size == 0:
        return 1.0
    k = np.argmax(bad[hit], axis=1)
    lo, hi = cps[hit, k - 1], cps[hit, k]       # g(lo) > 0 >= g(hi), g monotone between
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        pos = g(mid, hit) > 0
        lo, hi = np.where(pos, mid, lo), np.where(pos, hi, mid)
    return float(max(lo.min(), 0.0))

"""Stroh coefficients, matrix and exponents from the scaled moduli (private).

Array kernels without input validation, shared by :mod:`analytic.stroh` and
:mod:`analytic.wrinkling` (hot loops of the wrinkling searches).
"""

from __future__ import annotations

import numpy as np

__all__ = ["coefficients_fast", "exponents_from_coefficients", "stroh_N"]


def coefficients_fast(lam1, lam3, D0, model, direction="parallel"):
    """``(a, b, c, d)`` by the reduced formulas (no validation; hot loops).

    Equal to :func:`analytic.stroh.stroh_coefficients` (checked in the tests):
    ``a = 2 W1 l^2 - E2^2``, ``c = 2 W1 lam2^2``,
    ``2b = 4 W11 (l^2 - lam2^2)^2 + a + c``, ``d = E2 = lam2 D0`` with ``l`` the
    in-plane stretch of the wrinkle plane.
    """
    lam2 = 1.0 / (lam1 * lam3)
    I1 = lam1**2 + lam2**2 + lam3**2
    W1, W11 = model.dW(I1), model.d2W(I1)
    lin = lam1 if direction == "parallel" else lam3
    E2 = lam2 * D0
    a = 2.0 * W1 * lin**2 - E2**2
    c = 2.0 * W1 * lam2**2
    b = 0.5 * (4.0 * W11 * (lin**2 - lam2**2) ** 2 + a + c)
    return a, b, c, E2 + 0.0 * a


def stroh_N(a, b, c, d):
    """Complex Stroh matrix (Eq. stroh-form) from scaled ``(a, b, c, d)``."""
    shape = np.shape(a)
    N = np.zeros(shape + (6, 6), dtype=complex)
    N[..., 0, 1] = -1.0
    N[..., 0, 2] = d / c
    N[..., 1, 0] = -1.0
    N[..., 2, 0] = 2.0 * d
    N[..., 0, 3] = 1.0 / c
    N[..., 2, 5] = -1.0
    N[..., 3, 0] = -2.0 * (b + c) - 4.0 * d**2
    N[..., 4, 1] = c - a
    N[..., 5, 2] = d**2 / c + 1.0
    # N1^T block
    N[..., 3, 4] = -1.0
    N[..., 4, 3] = -1.0
    N[..., 5, 3] = d / c
    N[..., 3, 5] = 2.0 * d
    return N


def exponents_from_coefficients(a, b, c, d):
    """Decay exponents ``p2, p3`` (complex, ``Re > 0``) of Eq. (evalue), general form."""
    a0 = a + d**2  # purely elastic a (charge-free)
    b0 = b + 0.5 * d**2
    disc = (b0 * b0 - a0 * c).astype(complex)
    sq = np.sqrt(disc)
    # larger root of c P^2 - 2 b0 P + a0 = 0 without cancellation
    big = np.where(np.real(b0) >= 0, (b0 + sq) / c, (b0 - sq) / c)
    small = (a0 / c) / big
    p_big = np.sqrt(big)
    p_small = np.sqrt(small)
    return p_small, p_big

"""Moduli, Stroh coefficients, matrix and exponents as numpy kernels (private).

Shared by :mod:`analytic.stroh` (whose public functions wrap them in the package's
return convention) and :mod:`analytic.wrinkling`. :func:`moduli` and
:func:`coefficients` validate their arguments; :func:`coefficients_fast`,
:func:`stroh_N` and :func:`exponents_from_coefficients` do not (hot loops of the
wrinkling searches).
"""

from __future__ import annotations

import numpy as np

from ._checks import broadcast, check_choice, check_finite, check_positive
from .models import as_model

__all__ = ["coefficients", "coefficients_fast", "exponents_from_coefficients", "moduli", "stroh_N"]

_DIRECTIONS = ("parallel", "perpendicular")


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


def _state(lam1, lam3, D0, model):
    """Validated, broadcast ``(lam1, lam2, lam3, D0, W1, W11)``."""
    model = as_model(model)
    lam1 = check_positive("lam1", lam1)
    lam3 = check_positive("lam3", lam3)
    D0 = check_finite("D0", D0)
    if np.any(~np.isfinite(D0)):
        raise ValueError(f"D0 must be finite, got {D0}")
    lam1, lam3, D0 = broadcast(lam1=lam1, lam3=lam3, D0=D0)
    lam2 = 1.0 / (lam1 * lam3)
    I1 = lam1**2 + lam2**2 + lam3**2
    return lam1, lam2, lam3, D0, model.dW(I1), model.d2W(I1)


def moduli(lam1, lam3, D0, model):
    """``(A0, AA0, Ae0, p)`` of :func:`analytic.stroh.electroelastic_moduli` (numpy results)."""
    lam1, lam2, lam3, D0, W1, W11 = _state(lam1, lam3, D0, model)
    shape = lam1.shape
    bdiag = np.stack([lam1**2, lam2**2, lam3**2], axis=-1)  # (..., 3)
    E2 = lam2 * D0
    E = np.zeros(shape + (3,))
    E[..., 1] = E2
    eye = np.eye(3)
    b = bdiag[..., :, None] * eye  # (..., 3, 3)
    W1e = W1[..., None, None, None, None]
    W11e = W11[..., None, None, None, None]
    A0 = (
        2.0 * W1e * np.einsum("ij,...pq->...piqj", eye, b)
        + 4.0 * W11e * np.einsum("...pi,...qj->...piqj", b, b)
        - np.einsum("iq,...p,...j->...piqj", eye, E, E)
        - np.einsum("jp,...i,...q->...piqj", eye, E, E)
        - np.einsum("pq,...i,...j->...piqj", eye, E, E)
    )
    AA0 = np.einsum("ik,...p->...pik", eye, E) + np.einsum("pk,...i->...pik", eye, E)
    Ae0 = -np.broadcast_to(eye, shape + (3, 3)).copy()
    p = 2.0 * W1 * lam2**2 + E2**2
    return A0, AA0, Ae0, p


def coefficients(lam1, lam3, D0, model, direction):
    """``(a, b, c, d)`` of :func:`analytic.stroh.stroh_coefficients` (numpy results, from :func:`moduli`)."""
    check_choice("direction", direction, _DIRECTIONS)
    A0, AA0, _, _ = moduli(lam1, lam3, D0, model)
    m = 0 if direction == "parallel" else 2
    n = 1
    a = A0[..., m, n, m, n]
    c = A0[..., n, m, n, m]
    b = 0.5 * (A0[..., m, m, m, m] + A0[..., n, n, n, n] - 2.0 * A0[..., m, m, n, n] - 2.0 * A0[..., m, n, n, m])
    d = AA0[..., m, n, m]
    return a, b, c, d

"""Incremental electroelastic moduli and the Stroh matrix of a charged plate.

Section 4 of the paper linearises the equations of an ideal dielectric
``Omega = W(I1) - eps I5/2`` (Eq. modelE) about a biaxially stretched plate
(stretches ``lam1``, ``lam2 = 1/(lam1 lam3)``, ``lam3``) carrying a uniform field
``E2`` through its thickness ``x2``. Everything here is dimensionless
(``mu = eps = 1``): the true field is ``E2 = lam2 D0``.

Moduli (push-forward of ``Omega``)::

    A0_piqj = 2 W1 delta_ij b_pq + 4 W11 b_pi b_qj
              - (delta_iq E_p E_j + delta_jp E_i E_q + delta_pq E_i E_j)
    AA0_pik = delta_ik E_p + delta_pk E_i          (paper's  A0_{pi|k})
    Ae0_ij  = -delta_ij                              (paper's sans-serif A0)
    p       = 2 W1 lam2^2 + E2^2                     (from t2 = 0)

so ``A0_1122 = 4 W11 lam1^2 lam2^2``, ``A0_1221 = A0_2112 = -E2^2`` and
``p = A0_2121 - A0_2112``. The paper's list in Section 4 is a self-consistent
*alternative* set (``A0_1122`` with ``-E2^2``, ``A0_1221 = 0``, ``p = A0_2121``);
both give the same combinations (Eq. gent-moduli)::

    a = A0_1212,   2b = A0_1111 + A0_2222 - 2 A0_1122 - 2 A0_1221,
    c = A0_2121,   d = AA0_121  (= E2)

and the same Stroh matrix ``N`` (Eq. stroh-form). ``N`` is built with the
corrected last relation of Eq. (con-eqns), ``D_L02 = 2 d u_{1,1} - phi_{,2}``
(printed ``phi_{,1}``), and the entry ``-2(b+c)`` of ``N3`` is read as the
scaled ``-2(b-bar + c-bar)``.

Wrinkles in the perpendicular ``(x3, x2)`` plane (Eq. perpendicular-vars) use the
same formulas with ``x1`` replaced by ``x3``, i.e. ``lam1`` and ``lam3`` swapped
in the in-plane role.
"""

from __future__ import annotations

import numpy as np

from ._output import representable, scalar_or_array
from ._stroh_core import coefficients, exponents_from_coefficients, moduli, stroh_N
from .models import Model

__all__ = [
    "electroelastic_moduli",
    "stroh_coefficients",
    "stroh_matrix",
    "stroh_exponents",
]

@representable
def electroelastic_moduli(lam1, lam3, D0, model: Model | None = None):
    """Push-forward electroelastic moduli of a biaxially stretched charged plate.

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane principal stretches (``> 0``); ``lam2 = 1/(lam1 lam3)``.
    D0 : array_like
        Dimensionless Lagrangian electric displacement ``D_L/sqrt(mu eps)``.
    model : Model, optional
        Strain-energy model ``W(I1)``; default :class:`~analytic.NeoHookean`.

    Returns
    -------
    A0 : ndarray, shape (..., 3, 3, 3, 3)
        Fourth-order moduli ``A0_piqj / mu``.
    AA0 : ndarray, shape (..., 3, 3, 3)
        Third-order moduli ``A0_{pi|k} / sqrt(mu eps)``.
    Ae0 : ndarray, shape (..., 3, 3)
        Second-order moduli ``A0_ij / eps`` (``= -I``).
    p : ndarray
        Lagrange multiplier ``p / mu = 2 W1 lam2^2 + E2^2`` (traction-free faces).

    Notes
    -----
    Push-forward of ``Omega = W(I1) - eps I5/2`` (Eq. modelE). The
    incremental constitutive law is ``T0_pi = A0_piqj u_{j,q} + p u_{p,i} - pdot
    delta_pi + AA0_pik EL0_k`` and ``DL0_k = -AA0_qjk u_{j,q} - Ae0_km EL0_m``.
    The paper's listed components (Section 4) are an alternative set; this
    function returns the true push-forward values (``A0_1221 = -E2^2``).

    Examples
    --------
    >>> from analytic.stroh import electroelastic_moduli
    >>> A0, AA0, Ae0, p = electroelastic_moduli(1.2, 1.2, 0.5)
    >>> round(float(A0[0, 1, 1, 0]), 12), round(float(p - A0[1, 0, 1, 0] + A0[1, 0, 0, 1]), 12)
    (-0.120563271605, 0.0)
    """
    return scalar_or_array(*moduli(lam1, lam3, D0, model))


@representable
def stroh_coefficients(lam1, lam3, D0, model: Model | None = None, direction: str = "parallel"):
    """Scaled moduli combinations ``(a, b, c, d)`` of Eq. (gent-moduli).

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (``> 0``).
    D0 : array_like
        Dimensionless electric displacement.
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    direction : {"parallel", "perpendicular"}
        ``"parallel"``: wrinkles in the ``(x1, x2)`` plane (along the load
        ``x1``); ``"perpendicular"``: in the ``(x3, x2)`` plane
        (Eq. perpendicular-vars).

    Returns
    -------
    a, b, c, d : ndarray
        ``a = A0_1212``, ``2b = A0_1111 + A0_2222 - 2A0_1122 - 2A0_1221``,
        ``c = A0_2121``, ``d = AA0_{12|1}`` (index 1 replaced by 3 for
        perpendicular wrinkles), all dimensionless (the paper's barred
        quantities).

    Notes
    -----
    Computed from the push-forward moduli of :func:`electroelastic_moduli`.
    In equi-biaxial stretch they reduce to Eq. (gent-moduli):
    ``a = 2 lam^2 W' - lam^-4 D0^2``, ``c = 2 lam^-4 W'``,
    ``2b = 4 (lam^-4 - lam^2)^2 W'' + a + c``, ``d = lam^-2 D0``.

    Examples
    --------
    >>> from analytic.stroh import stroh_coefficients
    >>> [round(float(x), 12) for x in stroh_coefficients(1.0, 1.0, 0.0)]
    [1.0, 1.0, 1.0, 0.0]
    """
    return scalar_or_array(*coefficients(lam1, lam3, D0, model, direction))


@representable
def stroh_matrix(lam1, lam3, D0, model: Model | None = None, direction: str = "parallel"):
    """The 6x6 Stroh matrix ``N`` of Eq. (stroh-form), ``eta' = i N eta``.

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (``> 0``); use ``lam1 = lam3 = lam`` for equi-biaxial.
    D0 : array_like
        Dimensionless electric displacement.
    model : Model, optional
        Strain-energy model; default neo-Hookean.
    direction : {"parallel", "perpendicular"}
        Plane of the wrinkles, see :func:`stroh_coefficients`.

    Returns
    -------
    N : ndarray, shape (..., 6, 6), complex
        ``N = [[N1, N2], [N3, N1^T]]`` acting on the Stroh vector
        ``eta = [U1, U2, Phi, Sigma21, Sigma22, Delta]`` (Eq. strohvector, with
        index 1 -> 3 for perpendicular wrinkles); a prime is ``d/d(k x2)``.

    Notes
    -----
    Uses the corrected Eq. (con-eqns), ``D_L02 = 2 d u_{1,1} - phi_{,2}``
    (printed ``phi_{,1}``), and ``N3_11 = -2(b + c) - 4 d^2`` in scaled quantities
    (the printed ``-2(b + c)`` means the barred, scaled ``b`` and ``c``). ``J N`` is
    symmetric with ``J = [[0, I], [I, 0]]``.

    Examples
    --------
    >>> import numpy as np
    >>> from analytic.stroh import stroh_matrix
    >>> N = stroh_matrix(1.1, 1.1, 0.3)
    >>> J = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])
    >>> bool(np.allclose(J @ N, (J @ N).T))
    True
    """
    return scalar_or_array(stroh_N(*coefficients(lam1, lam3, D0, model, direction)))


@representable
def stroh_exponents(lam1, lam3, D0, model: Model | None = None, direction: str = "parallel"):
    """Decay exponents ``(1, p2, p3)`` of the eigenvalues ``q = i p`` of ``N``.

    Parameters
    ----------
    lam1, lam3, D0, model, direction
        As in :func:`stroh_matrix`.

    Returns
    -------
    p1, p2, p3 : ndarray (complex)
        The eigenvalues of ``N`` are ``+-i p1``, ``+-i p2``, ``+-i p3``; those
        with ``Im q > 0`` (decay into ``x2 > 0``) are ``i p_j`` with
        ``Re p_j > 0``. ``p1 = 1`` is the electric exponent; ``p2``, ``p3`` (with
        ``|p2| <= |p3|``) are the purely elastic ones (independent of ``D0``).

    Notes
    -----
    The characteristic polynomial of ``N`` factorises as
    ``(q^2 + 1)(c q^4 + (2b + d^2) q^2 + a + d^2) / c`` (derived symbolically),
    so ``p2^2, p3^2`` are the roots of ``c P^2 - (2b + d^2) P + (a + d^2) = 0``.
    In equi-biaxial stretch this is Eq. (evalue), with ``p2 p3 = lam^3``; for
    the neo-Hookean model ``{p2, p3} = {1, lam^3}`` (the paper labels them so
    that ``p2 = 1``; here they are ordered by modulus). Strong ellipticity fails
    where ``Re p_j = 0``.

    Examples
    --------
    >>> from analytic.stroh import stroh_exponents
    >>> [round(complex(x).real, 12) for x in stroh_exponents(0.9, 0.9, 0.4)]
    [1.0, 0.729, 1.0]
    """
    p2, p3 = exponents_from_coefficients(*coefficients(lam1, lam3, D0, model, direction))
    return scalar_or_array(np.ones_like(p2), p2, p3)

"""Homogeneous loading curves of an ideal dielectric plate (paper Sections 2 and 5).

The plate is stretched by ``lam1`` (x1), ``lam3`` (x3) and thinned to
``lam2 = 1/(lam1 lam3)``; the faces carry the dimensionless Lagrangian charge
``D0`` (charge control) or field ``E0`` (voltage control), with
``D0 = lam1^2 lam3^2 E0`` for an ideal dielectric. Everything is dimensionless
(``mu = eps = 1``); ``s`` is a nominal traction divided by ``mu``.

With ``I1 = lam1^2 + lam3^2 + lam1^-2 lam3^-2`` and the total energy
``omega*(lam1, lam3, D0) = W(I1) + lam1^-2 lam3^-2 D0^2 / 2`` the nominal
stresses are, Eq. (t1t3),

``t1 = 2W'(I1) (lam1 - lam1^-3 lam3^-2) - lam1^-3 lam3^-2 D0^2``,
``t3 = 2W'(I1) (lam3 - lam1^-2 lam3^-3) - lam1^-2 lam3^-3 D0^2``.

Equi-biaxial (``lam1 = lam3 = lam``, ``t1 = t3 = s``), Eq. (loading_gent) for any
``W``: ``D0^2 = 2W'(I1) (lam^6 - 1) - lam^5 s``.

Uni-axial dead load (``t1 = s``, ``t3 = 0``): eliminating ``D0`` from ``t3 = 0``
gives ``D0^2 = 2W'(I1) (lam1^2 lam3^4 - 1)`` and then ``s = 2W'(I1) (lam1 -
lam3^2/lam1)``; for neo-Hookean (``2W' = 1``) these are Eqs.
(uni-axial-loading) and (DEuniax).

Branch conventions (all functions): ``D0 >= 0`` is returned; where the loading
curve has no real state (``D0^2 < 0``, or ``lam3^2 <= 0`` in the uni-axial case)
the result is ``nan``. Inputs that are invalid (``lam <= 0``, NaN, stretches
beyond the locking limit of a Gent model, incompatible shapes) raise
``ValueError``.
"""

from __future__ import annotations

import numpy as np

from ._checks import as_array, broadcast, check_count, check_finite, check_positive
from ._loading import equibiaxial_limits, model_derivs, sqrt_branch, uniaxial_x
from ._output import representable, scalar_or_array
from ._roots import expand_bracket, rtsafe
from .models import Gent, NeoHookean, as_model

__all__ = [
    "biaxial_stress",
    "biaxial_E0",
    "biaxial_stretches",
    "equibiaxial_D0",
    "equibiaxial_E0",
    "equibiaxial_lam",
    "equibiaxial_s",
    "equibiaxial_s_E0",
    "uniaxial_D0",
    "uniaxial_E0",
    "uniaxial_lam3",
    "uniaxial_lam1",
]

# ----------------------------------------------------------------------------
# private helpers
# ----------------------------------------------------------------------------
def _I1(lam1, lam3):
    return lam1 * lam1 + lam3 * lam3 + 1.0 / (lam1 * lam3) ** 2


# ----------------------------------------------------------------------------
# general biaxial state
# ----------------------------------------------------------------------------
@representable
def biaxial_stress(lam1, lam3, D0, model=None):
    """Nominal stresses ``(t1, t3)/mu`` of the homogeneous biaxial state.

    Parameters
    ----------
    lam1, lam3 : array_like
        In-plane stretches (> 0).
    D0 : array_like
        Dimensionless Lagrangian charge ``D_L/sqrt(mu eps)``.
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Returns
    -------
    t1, t3 : ndarray
        ``d omega*/d lam1`` and ``d omega*/d lam3``.

    Notes
    -----
    Eq. (t1t3) with ``omega* = W(I1) + lam1^-2 lam3^-2 D0^2/2`` (ideal
    dielectric, Eq. modelD, in the dimensionless form of Sec. 2):
    ``t1 = 2W'(lam1 - lam1^-3 lam3^-2) - lam1^-3 lam3^-2 D0^2`` and likewise
    for ``t3``.

    Examples
    --------
    >>> from analytic import biaxial_stress
    >>> [round(float(t), 12) for t in biaxial_stress(2.0, 1.0, 0.0)]
    [1.875, 0.75]
    """
    model = as_model(model)
    lam1 = check_positive("lam1", lam1)
    lam3 = check_positive("lam3", lam3)
    D0 = check_finite("D0", D0)
    lam1, lam3, D0 = broadcast(lam1=lam1, lam3=lam3, D0=D0)
    dW, _ = model_derivs(model, _I1(lam1, lam3), "lam1", lam1)
    e = lam1**-2 * lam3**-2
    t1 = 2 * dW * (lam1 - e / lam1) - e / lam1 * D0**2
    t3 = 2 * dW * (lam3 - e / lam3) - e / lam3 * D0**2
    return scalar_or_array(t1, t3)


@representable
def biaxial_E0(lam1, lam3, D0):
    """Lagrangian field ``E0 = d omega*/d D0 = lam1^-2 lam3^-2 D0`` (Eq. DLEL).

    Examples
    --------
    >>> from analytic import biaxial_E0
    >>> float(biaxial_E0(2.0, 0.5, 3.0))
    3.0
    """
    lam1 = check_positive("lam1", lam1)
    lam3 = check_positive("lam3", lam3)
    D0 = check_finite("D0", D0)
    lam1, lam3, D0 = broadcast(lam1=lam1, lam3=lam3, D0=D0)
    return scalar_or_array(D0 / (lam1**2 * lam3**2))


def _biaxial_core(s1, s3, q, model, start=None, maxiter=100):
    """Newton solve of ``grad psi* = 0`` on flat arrays (see :func:`biaxial_stretches`)."""
    I1max = model.I1_max()

    def residual(a, b, i):
        """Gradient of psi*, its Jacobian and a magnitude scale for the tolerance."""
        qa, ra, rb = q[i], 1.0 / a, 1.0 / b
        ea = (ra * rb) ** 2
        ea_a, ea_b = ea * ra, ea * rb
        I1 = a * a + b * b + ea
        dW, d2W = model.dW(I1), model.d2W(I1)
        Ia, Ib = 2 * (a - ea_a), 2 * (b - ea_b)
        g1 = dW * Ia - ea_a * qa - s1[i]
        g3 = dW * Ib - ea_b * qa - s3[i]
        K11 = d2W * Ia * Ia + dW * (2 + 6 * ea_a * ra) + 3 * qa * ea_a * ra
        K33 = d2W * Ib * Ib + dW * (2 + 6 * ea_b * rb) + 3 * qa * ea_b * rb
        K13 = d2W * Ia * Ib + (4 * dW + 2 * qa) * ea_a * rb
        scale = 2 * dW * (a + b + ea_a + ea_b) + qa * (ea_a + ea_b) + np.abs(s1[i]) + np.abs(s3[i])
        return g1, g3, K11, K13, K33, scale

    # start from the neo-Hookean equi-biaxial free-charge state, always admissible
    x0 = (1.0 + q) ** (1.0 / 6.0)
    if np.isfinite(I1max):
        lo, hi = equibiaxial_limits(model)
        x0 = np.minimum(x0, 1.0 + 0.5 * (hi - 1.0))
    a, b = x0.copy(), x0.copy()
    if start is not None:  # a better first guess where it is admissible
        sa, sb = start
        with np.errstate(invalid="ignore", divide="ignore"):
            good = np.isfinite(sa) & np.isfinite(sb) & (sa > 0) & (sb > 0)
            good &= _I1(np.where(good, sa, 1.0), np.where(good, sb, 1.0)) < 3.0 + 0.9 * (I1max - 3.0)
        a, b = np.where(good, sa, a), np.where(good, sb, b)
    n = a.size
    la, lb = np.full(n, np.nan), np.full(n, np.nan)
    active = np.arange(n)
    res = residual(a, b, active)
    for _ in range(maxiter):
        if active.size == 0:
            break
        g1, g3, K11, K13, K33, scale = res
        gg = g1**2 + g3**2
        conv = np.sqrt(gg) <= 1e-14 * scale
        la[active[conv]], lb[active[conv]] = a[conv], b[conv]
        keep = ~conv
        active, a, b = active[keep], a[keep], b[keep]
        g1, g3, K11, K13, K33, gg, scale = (v[keep] for v in (g1, g3, K11, K13, K33, gg, scale))
        if active.size == 0:
            break
        # Newton step; the merit |grad psi*|^2 decreases along it for any regular Jacobian
        det = K11 * K33 - K13**2
        with np.errstate(divide="ignore", invalid="ignore"):
            pa = -(K33 * g1 - K13 * g3) / det
            pb = -(-K13 * g1 + K11 * g3) / det
        t = np.ones(active.size)
        ok = np.zeros(active.size, dtype=bool)
        new = [np.full(active.size, np.nan) for _k in range(6)]
        todo = np.arange(active.size)
        for _ls in range(40):
            an, bn = a[todo] + t[todo] * pa[todo], b[todo] + t[todo] * pb[todo]
            feas = np.isfinite(an) & np.isfinite(bn) & (an > 0) & (bn > 0)
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                feas &= _I1(np.where(feas, an, 1.0), np.where(feas, bn, 1.0)) < I1max
            good = np.zeros(todo.size, dtype=bool)
            if np.any(feas):
                jf = todo[feas]
                r = residual(an[feas], bn[feas], active[jf])
                acc = r[0] ** 2 + r[1] ** 2 <= (1.0 - 1e-4 * t[jf]) * gg[jf]
                for k in range(6):
                    new[k][jf[acc]] = r[k][acc]
                good[np.flatnonzero(feas)[acc]] = True
            ok[todo[good]] = True
            todo = todo[~good]
            if todo.size == 0:
                break
            t[todo] *= 0.5
        # a failed line search means the point sits at its rounding floor (accept it if
        # the gradient is small) or there is no minimiser (leave nan)
        stuck = ~ok
        floor = stuck & (np.sqrt(gg) <= 1e-10 * scale)
        la[active[floor]], lb[active[floor]] = a[floor], b[floor]
        a, b = a + t * pa, b + t * pb
        active, a, b = active[ok], a[ok], b[ok]
        res = tuple(v[ok] for v in new)
    return la, lb


@representable
def biaxial_stretches(s1, s3, D0, model=None, *, maxiter: int = 100):
    """Stretches ``(lam1, lam3)`` of the plate under dead loads ``s1, s3`` and charge ``D0``.

    Parameters
    ----------
    s1, s3 : array_like
        Nominal tractions ``t1/mu``, ``t3/mu`` on the lateral faces.
    D0 : array_like
        Dimensionless charge (only ``D0^2`` matters).
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).
    maxiter : int
        Newton iterations allowed (an integer ``>= 1``).

    Returns
    -------
    lam1, lam3 : ndarray
        The equilibrium stretches; ``nan`` where none was found (no minimiser,
        e.g. a user model that softens too much, or not within ``maxiter`` iterations).

    Notes
    -----
    Under charge control the equilibrium minimises ``psi* = omega*(lam1, lam3,
    D0) - s1 lam1 - s3 lam3`` at fixed ``D0`` (Sec. 3.1, ``psi*`` without the
    ``D0 E0`` term). For ``W' > 0`` and ``W'' >= 0`` (neo-Hookean, Gent)
    ``omega*`` is strictly convex in ``(lam1, lam3)`` because ``I1`` and
    ``lam1^-2 lam3^-2`` are, so the equilibrium is unique and charge-controlled
    actuation is stable (Sec. 5). It is found by Newton's method with a
    backtracking line search on ``|grad psi*|^2``, vectorised over all points.

    Examples
    --------
    Uni-axial neo-Hookean dead load ``s = 1`` at ``D0 = 2``, against
    Eq. (DEuniax), ``lam1^2 (lam1 - s) = sqrt(1 + D0^2)``:

    >>> from analytic import biaxial_stretches
    >>> l1, l3 = biaxial_stretches(1.0, 0.0, 2.0)
    >>> round(float(l1**2 * (l1 - 1.0)), 12), round(float(l3**2 - l1 * (l1 - 1.0)), 12)
    (2.2360679775, 0.0)
    """
    maxiter = check_count("maxiter", maxiter)
    model = as_model(model)
    s1 = as_array("s1", s1)
    s3 = as_array("s3", s3)
    D0 = check_finite("D0", D0)
    for name, v in (("s1", s1), ("s3", s3), ("D0", D0)):
        if np.any(~np.isfinite(v)):
            raise ValueError(f"{name} must be finite, got {v!r}")
    s1, s3, D0 = broadcast(s1=s1, s3=s3, D0=D0)
    shape = s1.shape
    s1, s3, q = s1.ravel(), s3.ravel(), D0.ravel() ** 2
    la, lb = _biaxial_core(s1, s3, q, model, None, maxiter)
    return scalar_or_array(la.reshape(shape), lb.reshape(shape))


# ----------------------------------------------------------------------------
# equi-biaxial loading
# ----------------------------------------------------------------------------
@representable
def equibiaxial_s(lam, D0, model=None):
    """Equi-biaxial dead load ``s`` that holds stretch ``lam`` at charge ``D0``.

    Parameters
    ----------
    lam : array_like
        Equi-biaxial stretch (> 0).
    D0 : array_like
        Dimensionless charge.
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Returns
    -------
    s : ndarray
        ``(1/2) d omega*-hat/d lam = 2W'(I1)(lam - lam^-5) - lam^-5 D0^2``.

    Notes
    -----
    Eq. (s_general); neo-Hookean: ``s = lam - lam^-5 - lam^-5 D0^2`` (Sec. 3.1).

    Examples
    --------
    >>> from analytic import equibiaxial_s
    >>> float(equibiaxial_s(1.0, 0.0))
    0.0
    """
    model = as_model(model)
    lam = check_positive("lam", lam)
    D0 = check_finite("D0", D0)
    lam, D0 = broadcast(lam=lam, D0=D0)
    dW, _ = model_derivs(model, 2 * lam**2 + lam**-4, "lam", lam)
    return scalar_or_array(2 * dW * (lam - lam**-5) - lam**-5 * D0**2)


@representable
def equibiaxial_s_E0(lam, E0, model=None):
    """Equi-biaxial dead load ``s`` that holds stretch ``lam`` at field ``E0``.

    Returns ``(1/2) d omega-hat/d lam = 2W'(I1)(lam - lam^-5) - lam^3 E0^2``,
    Eq. (s_general) in the voltage-control form; neo-Hookean:
    ``s = lam - lam^-5 - lam^3 E0^2`` (Sec. 3.1).

    Examples
    --------
    >>> from analytic import equibiaxial_s, equibiaxial_s_E0
    >>> bool(abs(equibiaxial_s_E0(1.5, 0.3) - equibiaxial_s(1.5, 0.3 * 1.5**4)) < 1e-14)
    True
    """
    model = as_model(model)
    lam = check_positive("lam", lam)
    E0 = check_finite("E0", E0)
    lam, E0 = broadcast(lam=lam, E0=E0)
    dW, _ = model_derivs(model, 2 * lam**2 + lam**-4, "lam", lam)
    return scalar_or_array(2 * dW * (lam - lam**-5) - lam**3 * E0**2)


@representable
def equibiaxial_D0(lam, s=0.0, model=None):
    """Charge ``D0`` on the equi-biaxial loading curve of dead load ``s``.

    Parameters
    ----------
    lam : array_like
        Equi-biaxial stretch (> 0).
    s : array_like
        Dimensionless equi-biaxial nominal traction ``t/mu`` (broadcast with ``lam``).
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Returns
    -------
    D0 : ndarray
        ``sqrt(2W'(I1)(lam^6 - 1) - lam^5 s)`` with ``I1 = 2 lam^2 + lam^-4``;
        ``nan`` where the radicand is negative (no real state: the stretch is
        below the purely mechanical stretch of the dead load).

    Raises
    ------
    ValueError
        ``lam <= 0`` or NaN, ``s`` NaN or of incompatible shape, or ``I1``
        beyond the locking limit of the model.

    Notes
    -----
    Eq. (loading_gent): neo-Hookean ``D0 = sqrt(lam^6 - 1 - lam^5 s)``, Gent
    ``D0 = sqrt((lam^6 - 1)/(1 - (2 lam^2 + lam^-4 - 3)/Jm) - lam^5 s)``.

    Examples
    --------
    >>> from analytic import equibiaxial_D0, Gent
    >>> round(float(equibiaxial_D0(2.0 ** (1 / 6))), 12)  # neo-Hookean, s = 0: D0^2 = lam^6 - 1
    1.0
    >>> round(float(equibiaxial_D0(2.0, 1.0, Gent(97.2))), 6)
    5.870395
    """
    model = as_model(model)
    lam = check_positive("lam", lam)
    s = check_finite("s", s)
    lam, s = broadcast(lam=lam, s=s)
    if isinstance(model, NeoHookean):
        D2 = lam**6 - 1.0 - lam**5 * s
        scale = lam**6 + 1.0 + np.abs(lam**5 * s)
    else:
        dW, _ = model_derivs(model, 2 * lam**2 + lam**-4, "lam", lam)
        D2 = 2 * dW * (lam**6 - 1.0) - lam**5 * s
        scale = 2 * dW * (lam**6 + 1.0) + np.abs(lam**5 * s)
    return scalar_or_array(sqrt_branch(D2, scale))


@representable
def equibiaxial_E0(lam, s=0.0, model=None):
    """Field ``E0 = lam^-4 D0`` on the equi-biaxial loading curve of dead load ``s``.

    Same parameters, branch convention (``nan`` where ``D0`` is not real) and
    errors as :func:`equibiaxial_D0`.

    Notes
    -----
    Eq. (loading_gent) with ``E0 = d omega*-hat/d D0 = lam^-4 D0``, Eq. (s_general).

    Examples
    --------
    The neo-Hookean maximum of ``E0`` at ``s = 0`` (Fig. nh-d-e):

    >>> from analytic import equibiaxial_E0
    >>> round(float(equibiaxial_E0(2 ** (1 / 3))), 12) == round(3**0.5 / 2 ** (4 / 3), 12)
    True
    """
    D0 = equibiaxial_D0(lam, s, model)
    lam = np.broadcast_to(check_positive("lam", lam), np.shape(D0))
    return scalar_or_array(np.asarray(D0) / lam**4)


@representable
def equibiaxial_lam(D0, s=0.0, model=None):
    """Charge-controlled equi-biaxial stretch ``lam(D0; s)`` (inverse of :func:`equibiaxial_D0`).

    Parameters
    ----------
    D0 : array_like
        Dimensionless charge (finite; only ``D0^2`` matters).
    s : array_like
        Dimensionless equi-biaxial nominal traction.
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Returns
    -------
    lam : ndarray
        The root of ``s = 2W'(I1)(lam - lam^-5) - lam^-5 D0^2``. ``nan`` only if
        no root was found (cannot happen for neo-Hookean or Gent).

    Notes
    -----
    Inverse of Eq. (loading_gent). The right-hand side is ``(1/2) d omega*-hat
    /d lam`` and increases with ``lam`` (``omega*-hat_{lam lam} > 0`` for
    ``W' > 0``, ``W'' >= 0``), from ``-inf`` at ``lam -> 0`` (or the lower Gent
    lock) to ``+inf``: the root is unique. It is bracketed and refined by a
    vectorised safeguarded Newton method (neo-Hookean: the single positive root
    of ``lam^6 - s lam^5 - 1 - D0^2``).

    Examples
    --------
    >>> from analytic import equibiaxial_lam, equibiaxial_D0
    >>> lam = equibiaxial_lam(1.0)
    >>> round(float(lam**6), 12)
    2.0
    >>> round(float(equibiaxial_D0(equibiaxial_lam(3.0, 1.5), 1.5)), 12)
    3.0
    """
    model = as_model(model)
    D0, s = broadcast(D0=check_finite("D0", D0), s=check_finite("s", s))
    shape = D0.shape
    q, s = D0.ravel() ** 2, s.ravel()
    lo_lim, hi_lim = equibiaxial_limits(model)

    nh = isinstance(model, NeoHookean)
    cq = 1.0 + q

    def h(lam, i):
        r = 1.0 / lam
        r4 = (r * r) ** 2
        r5, r6 = r4 * r, r4 * r * r
        if nh:  # 2W' = 1, W'' = 0
            cr5 = cq[i] * r5
            return lam - cr5 - s[i], 1.0 + 5.0 * cr5 * r
        I1 = 2 * lam * lam + r4
        dW, d2W = model.dW(I1), model.d2W(I1)
        I1p, I1pp = 4 * (lam - r5), 4 + 20 * r6
        f = 0.5 * dW * I1p - r5 * q[i] - s[i]
        df = 0.5 * (d2W * I1p**2 + dW * I1pp) + 5 * r6 * q[i]
        return f, df

    if nh:  # explicit bracket: h(lo) <= 0 <= h(hi) with c = 1 + D0^2 (see Notes)
        c6 = (1.0 + q) ** (1.0 / 6.0)
        lo = ((1.0 + q) / (c6 + np.maximum(-s, 0.0))) ** 0.2
        hi = c6 + np.maximum(s, 0.0)
        lam = rtsafe(h, lo, hi, 0.5 * s + np.sqrt(0.25 * s**2 + c6**2))
        return scalar_or_array(lam.reshape(shape))
    if type(model) is Gent:
        # 2W' >= 1 (W'' >= 0, 2W'(3) = 1): h_Gent >= h_nH for lam >= 1 and <= for lam <= 1,
        # so the root lies between 1 and the explicit neo-Hookean bounds (see nh above)
        c6 = (1.0 + q) ** (1.0 / 6.0)
        up = -q - s <= 0  # h(1) <= 0: root at or above 1
        lo = np.where(up, 1.0, np.maximum(((1.0 + q) / (c6 + np.maximum(-s, 0.0))) ** 0.2,
                                           lo_lim * (1 + 1e-12)))
        hi = np.where(up, np.minimum(c6 + np.maximum(s, 0.0), hi_lim * (1 - 1e-12)), 1.0)
        # first guess: the neo-Hookean estimate used above (exact for nH at s = 0)
        lam = rtsafe(h, lo, hi, 0.5 * s + np.sqrt(0.25 * s**2 + c6**2))
        return scalar_or_array(lam.reshape(shape))
    one = np.ones(q.size)
    f1 = h(one, np.arange(q.size))[0]
    lo = np.where(f1 <= 0, one, np.nan)
    hi = np.where(f1 >= 0, one, np.nan)
    need_lo, need_hi = np.flatnonzero(np.isnan(lo)), np.flatnonzero(np.isnan(hi))
    lo[need_lo] = expand_bracket(lambda x, i: h(x, need_lo[i])[0], one[need_lo], lo_lim, -1)
    hi[need_hi] = expand_bracket(lambda x, i: h(x, need_hi[i])[0], one[need_hi], hi_lim, +1)
    ok = np.flatnonzero(np.isfinite(lo) & np.isfinite(hi))
    # first guess: exact for neo-Hookean at s = 0, an upper estimate for s > 0
    u2 = (1.0 + q[ok]) ** (1.0 / 3.0)
    x0 = 0.5 * s[ok] + np.sqrt(0.25 * s[ok] ** 2 + u2)
    lam = np.full(q.size, np.nan)
    lam[ok] = rtsafe(lambda x, i: h(x, ok[i]), lo[ok], hi[ok], x0)
    return scalar_or_array(lam.reshape(shape))


# ----------------------------------------------------------------------------
# uni-axial dead load (t3 = 0)
# ----------------------------------------------------------------------------
def _uniaxial_inputs(lam1, s, model):
    model = as_model(model)
    lam1 = check_positive("lam1", lam1)
    lam1, s = broadcast(lam1=lam1, s=check_finite("s", s))
    return lam1, s, model


@representable
def uniaxial_lam3(lam1, s=0.0, model=None):
    """Transverse stretch ``lam3`` on the uni-axial dead-load curve (``t3 = 0``, ``t1 = s``).

    Parameters
    ----------
    lam1 : array_like
        Stretch in the load direction (> 0).
    s : array_like
        Dimensionless dead load ``t1/mu`` (nominal, per reference cross-section).
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Returns
    -------
    lam3 : ndarray
        Solution of ``s = 2W'(I1)(lam1 - lam3^2/lam1)`` with
        ``lam1^2 lam3^4 >= 1`` (so that ``D0`` is real); ``nan`` where none
        exists (``lam1`` below the purely mechanical stretch of the load).

    Notes
    -----
    Eq. (uni-axial-loading)_1 generalised to any ``W``; neo-Hookean closed form
    ``lam3 = sqrt(lam1 (lam1 - s))``. Gent: multiplying by ``x (Jm + 3 - I1)``
    (``x = lam3^2``) turns the condition into the quadratic
    ``(Jm/lam1 - s) x^2 + (s (Jm + 3 - lam1^2) - Jm lam1) x - s/lam1^2 = 0``,
    solved in closed form. Other models: a vectorised safeguarded Newton method
    on ``[lam1^-1, lam1^2]`` (``s > 0``), with a scan where a locking limit cuts
    in. Within a few per cent of the Gent locking stretch two states can share
    ``lam1``; the smaller ``lam3`` (smaller ``D0``) is returned.

    Examples
    --------
    >>> from analytic import uniaxial_lam3, Gent
    >>> round(float(uniaxial_lam3(2.0, 1.0)), 12) == round(2.0**0.5, 12)
    True
    >>> round(float(uniaxial_lam3(2.0, 1.0, Gent(97.2))), 6)
    1.437208
    """
    lam1, s, model = _uniaxial_inputs(lam1, s, model)
    x = uniaxial_x(lam1.ravel(), s.ravel(), model).reshape(lam1.shape)
    return scalar_or_array(np.sqrt(x))


@representable
def uniaxial_D0(lam1, s=0.0, model=None):
    """Charge ``D0`` on the uni-axial dead-load curve of load ``s``.

    Parameters
    ----------
    lam1 : array_like
        Stretch in the load direction (> 0).
    s : array_like
        Dimensionless dead load ``t1/mu``.
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Returns
    -------
    D0 : ndarray
        ``sqrt(2W'(I1)(lam1^2 lam3^4 - 1))`` with ``lam3`` from
        :func:`uniaxial_lam3`; ``nan`` where there is no real state.

    Notes
    -----
    Eqs. (uni-axial-loading) and (DEuniax); neo-Hookean
    ``D0 = sqrt(lam1^4 (lam1 - s)^2 - 1)`` for ``lam1 > s``.

    Examples
    --------
    >>> from analytic import uniaxial_D0
    >>> float(uniaxial_D0(2.0, 1.0))  # sqrt(16 - 1)
    3.872983346207417
    """
    lam1, s, model = _uniaxial_inputs(lam1, s, model)
    l1, sf = lam1.ravel(), s.ravel()
    if isinstance(model, NeoHookean):
        D2 = l1**4 * (l1 - sf) ** 2 - 1.0
        D0 = np.where(l1 > sf, sqrt_branch(D2, D2 + 2.0), np.nan)
    else:
        x = uniaxial_x(l1, sf, model)
        good = np.isfinite(x)
        D0 = np.full(l1.size, np.nan)
        xg, lg = x[good], l1[good]
        dW = model.dW(lg**2 + xg + 1.0 / (lg**2 * xg))
        D0[good] = np.nan_to_num(sqrt_branch(2 * dW * (lg**2 * xg**2 - 1.0), 2 * dW * (lg**2 * xg**2 + 1.0)))
    return scalar_or_array(D0.reshape(lam1.shape))


@representable
def uniaxial_E0(lam1, s=0.0, model=None):
    """Field ``E0 = lam1^-2 lam3^-2 D0`` on the uni-axial dead-load curve of load ``s``.

    Same parameters and branch convention as :func:`uniaxial_D0`.

    Notes
    -----
    Eq. (DEuniax)_2; neo-Hookean ``E0 = lam1^-1 sqrt(1 - lam1^-4 (lam1 - s)^-2)``.

    Examples
    --------
    >>> from analytic import uniaxial_E0
    >>> round(float(uniaxial_E0(2.0, 1.0)), 12) == round(0.5 * (1 - 1 / 16) ** 0.5, 12)
    True
    """
    lam1, s, model = _uniaxial_inputs(lam1, s, model)
    l1, sf = lam1.ravel(), s.ravel()
    if isinstance(model, NeoHookean):
        with np.errstate(invalid="ignore", divide="ignore"):
            r = 1.0 - l1**-4 * (l1 - sf) ** -2.0
        E0 = np.where(l1 > sf, sqrt_branch(r, 2.0) / l1, np.nan)
    else:
        x = uniaxial_x(l1, sf, model)
        good = np.isfinite(x)
        E0 = np.full(l1.size, np.nan)
        xg, lg = x[good], l1[good]
        dW = model.dW(lg**2 + xg + 1.0 / (lg**2 * xg))
        E0[good] = np.nan_to_num(sqrt_branch(2 * dW * (lg**2 * xg**2 - 1.0), 2 * dW * (lg**2 * xg**2 + 1.0))) / (lg**2 * xg)
    return scalar_or_array(E0.reshape(lam1.shape))


def _uniaxial_cubic_root(c, sig):
    """Positive root ``l`` of ``l^2 (l - sig) = c`` (``c >= 1``), flat arrays.

    ``l^2 (l - sig)`` increases from ``0`` on ``l > max(sig, 0)``, so the root is unique.
    ``sig >= 0``: Cardano with ``m = sig/3``, ``l = m + u + m^2/u``,
    ``u = cbrt(m^3 + c/2 + sqrt((c/2)(c/2 + 2 m^3)))`` (all terms positive).
    ``sig < 0``: ``y = 1/l`` is the positive root of ``y^3 - 3P y - 2Q = 0`` with
    ``P = -sig/(3c)``, ``Q = 1/(2c)``: ``y = u + P/u``, ``u = cbrt(Q + sqrt(Q^2 - P^3))``,
    or where ``Q^2 < P^3`` (three real roots) the largest,
    ``y = 2 sqrt(P) cos(arccos(Q/P^(3/2))/3)`` (``cos`` in ``[1/2, 1]``): no cancellation
    either way, also for ``|sig| >> c`` where ``l ~ sqrt(c/|sig|)``.
    """
    m = sig / 3.0
    b = 0.5 * c
    u = np.cbrt(m * m * m + b + np.sqrt(b * (b + 2.0 * m * m * m)))
    l = m + u + m * m / u
    neg = sig < 0
    if np.any(neg):
        cn = c[neg]
        P, Q = -sig[neg] / (3.0 * cn), 0.5 / cn
        disc = Q * Q - P * P * P
        y = np.empty(cn.size)
        one = disc >= 0
        un = np.cbrt(Q[one] + np.sqrt(disc[one]))
        y[one] = un + P[one] / un
        Pt, Qt = P[~one], Q[~one]
        rP = np.sqrt(Pt)
        y[~one] = 2.0 * rP * np.cos(np.arccos(np.minimum(Qt / (Pt * rP), 1.0)) / 3.0)
        l[neg] = 1.0 / y
    return l


def _gent_xi_residual(xi, t, sb, Jm):
    """``R(xi)`` of :func:`_uniaxial_lam1_gent` and ``dR/dxi`` (``t = D0^2``, ``sb = s``)."""
    c = np.sqrt(1.0 + t * xi)
    sig = sb * xi
    l = _uniaxial_cubic_root(c, sig)
    ic, il = 1.0 / c, 1.0 / l
    w = (c + ic) * il
    f = l * l + w - 3.0 - Jm * (1.0 - xi)
    # d/dxi by implicit differentiation of the cubic: (3l^2 - 2 sig l) l' = c' + s l^2
    dc = 0.5 * t * ic
    dl = (dc + sb * l * l) / (l * (3.0 * l - 2.0 * sig))
    return f, (2.0 * l - w * il) * dl + (1.0 - ic * ic) * dc * il + Jm


def _uniaxial_lam1_gent(q, s, Jm, block=1 << 14, maxiter=100):
    """Gent ``lam1(D0; s)`` on flat arrays (``q = D0^2``); see :func:`uniaxial_lam1`.

    With ``xi = 1/(2W') = 1 - (I1 - 3)/Jm`` the uni-axial equations ``s = 2W'(lam1 -
    lam3^2/lam1)``, ``D0^2 = 2W'(lam1^2 lam3^4 - 1)`` are the neo-Hookean ones with
    loads ``s xi``, ``D0^2 xi``: ``lam1^2 (lam1 - s xi) = c = sqrt(1 + D0^2 xi)`` (a
    cubic) and ``lam3^2 = c/lam1``. What is left is the scalar equation
    ``R(xi) = I1(xi) - 3 - Jm (1 - xi) = 0`` with ``I1 = lam1^2 + (c + 1/c)/lam1``.
    ``R(0) = -Jm < 0 <= R(1) = I1_nH - 3``, every ``xi`` in ``[0, 1]`` gives a real
    state, and each root is an equilibrium, which is unique (``omega*`` is strictly
    convex on the convex set ``I1 < 3 + Jm``): ``[0, 1]`` brackets exactly one root.
    Safeguarded Newton (:func:`~analytic._roots.rtsafe`, bisection fallback) from the
    upper bound of ``xi`` (``xi = 1``, the neo-Hookean state, unless a bound below
    applies), bracket width checked every sweep, run in cache-sized blocks; the final
    ``lam1`` gets one Newton polish on the cubic.
    """
    n = q.size
    out = np.empty(n)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for k0 in range(0, n, block):
            t, sb = q[k0:k0 + block], s[k0:k0 + block]
            m = t.size
            # bounds on xi at the root (where I1 = 3 + Jm (1 - xi) < 3 + Jm), for huge D0 or
            # |s|: I1 >= lam1^2 + c/lam1 >= 3 (c/2)^(2/3) gives c <= cmax = 2 (1 + Jm/3)^(3/2),
            # i.e. D0^2 xi <= cmax^2 - 1; s > 0: I1 > lam1^2 > (s xi)^2; s < 0: lam1^2 |s| xi < c
            # and I1 >= (c + 1/c)/lam1 >= 2/lam1 give 4 |s| xi < cmax (3 + Jm)^2. At each
            # bound R >= Jm xi >= 0, so it is an upper end of the bracket and Newton's start
            cmax = 2.0 * (1.0 + Jm / 3.0) ** 1.5
            with np.errstate(divide="ignore"):
                hi = np.minimum(1.0, (cmax * cmax - 1.0) / t)
                hi = np.minimum(hi, np.where(sb > 0, np.sqrt(3.0 + Jm), 0.25 * cmax * (3.0 + Jm) ** 2) / np.abs(sb))
            xi = rtsafe(lambda x, i: _gent_xi_residual(x, t[i], sb[i], Jm), np.zeros(m), hi, hi,
                        maxiter=maxiter, start_on_bracket=True, width_every=1)
            c = np.sqrt(1.0 + t * xi)
            sig = sb * xi
            l = _uniaxial_cubic_root(c, sig)
            out[k0:k0 + block] = l - (l * l * (l - sig) - c) / (l * (3.0 * l - 2.0 * sig))
    return out


def _uniaxial_lam1_biaxial(D0, s, model, l1=None):
    """Generic ``lam1(D0; s)`` on flat arrays: Newton on ``grad psi* = 0`` with ``t3 = 0``
    (:func:`_biaxial_core`) from the neo-Hookean state ``l1`` (computed if not given)."""
    if l1 is None:
        l1 = _uniaxial_lam1_nh(np.sqrt(1.0 + D0**2), s)
    l3 = np.sqrt(l1 * (l1 - s))
    la, _ = _biaxial_core(s, 0.0 * s, D0**2, model, (l1, l3))
    return la


def _uniaxial_lam1_nh(c, s):
    """Neo-Hookean ``lam1``: root of ``l^2 (l - s) = c`` by safeguarded Newton (flat arrays)."""
    lo = np.maximum(s, 0.0)  # q(lo) = lo^2 (lo - s) - c < 0
    hi = lo + c ** (1.0 / 3.0) + np.abs(s)  # q(hi) > 0

    def q(l1, i):
        return l1**2 * (l1 - s[i]) - c[i], l1 * (3 * l1 - 2 * s[i])

    return rtsafe(q, lo, hi)


@representable
def uniaxial_lam1(D0, s=0.0, model=None):
    """Charge-controlled stretch ``lam1(D0; s)`` under a uni-axial dead load (inverse of :func:`uniaxial_D0`).

    Parameters
    ----------
    D0 : array_like
        Dimensionless charge (finite; only ``D0^2`` matters).
    s : array_like
        Dimensionless dead load ``t1/mu``.
    model : Model, optional
        Strain-energy model (default :class:`NeoHookean`).

    Returns
    -------
    lam1 : ndarray
        Stretch in the load direction; ``nan`` where no equilibrium was found.

    Notes
    -----
    Inverse of Eq. (DEuniax). Neo-Hookean: the single root ``lam1 > max(s, 0)``
    of ``lam1^2 (lam1 - s) = sqrt(1 + D0^2)``. Gent (Eqs. gent, W): with
    ``xi = 1/(2W') = 1 - (I1 - 3)/Jm`` the equations are the neo-Hookean ones with
    loads ``s xi`` and ``D0^2 xi``, so ``lam1^2 (lam1 - s xi) = sqrt(1 + D0^2 xi)``
    (solved by Cardano) and ``lam3^2 = sqrt(1 + D0^2 xi)/lam1``; ``xi`` is the single
    root in ``[0, 1]`` of ``I1(xi) = 3 + Jm (1 - xi)``, found by a vectorised
    safeguarded Newton method. Other models: the unique minimiser of ``omega* - s
    lam1`` with ``t3 = 0`` (:func:`biaxial_stretches` with ``s3 = 0``). The state is
    the charge-controlled equilibrium (unique). Beyond the Gent equi-biaxial locking
    stretch (large ``s``, small ``Jm``) two uni-axial states can share ``lam1`` and
    ``lam1(D0)`` turns back; there it may be the state that :func:`uniaxial_D0` (one
    state per ``lam1``) does not return.

    Examples
    --------
    >>> from analytic import uniaxial_lam1, uniaxial_D0, Gent
    >>> round(float(uniaxial_D0(uniaxial_lam1(2.5, 1.0), 1.0)), 12)
    2.5
    >>> round(float(uniaxial_D0(uniaxial_lam1(2.5, 1.0, Gent(97.2)), 1.0, Gent(97.2))), 12)
    2.5
    """
    model = as_model(model)
    D0, s = broadcast(D0=check_finite("D0", D0), s=check_finite("s", s))
    shape = D0.shape
    D0f, sf = D0.ravel(), s.ravel()
    if type(model) is Gent:
        return scalar_or_array(_uniaxial_lam1_gent(D0f**2, sf, model.Jm).reshape(shape))
    l1 = _uniaxial_lam1_nh(np.sqrt(1.0 + D0f**2), sf)
    if isinstance(model, NeoHookean):
        return scalar_or_array(l1.reshape(shape))
    return scalar_or_array(_uniaxial_lam1_biaxial(D0f, sf, model, l1).reshape(shape))

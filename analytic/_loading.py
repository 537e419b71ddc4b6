"""Pieces of the homogeneous loading curves shared by the analytic modules (private).

``model_derivs`` evaluates ``W'`` and ``W''`` with a check of the model's locking
limit; ``equibiaxial_limits`` and ``uniaxial_xlock`` are the stretches where that
limit is reached; ``sqrt_branch`` is the real branch ``D0 = sqrt(D0^2)`` of a loading
curve; ``uniaxial_x`` solves the uni-axial dead-load condition ``t3 = 0``,
``s = 2W'(I1)(lam1 - lam3^2/lam1)``, for ``x = lam3^2``.
"""

from __future__ import annotations

import numpy as np

from ._roots import expand_bracket, rtsafe
from .models import Gent, Model, NeoHookean

__all__ = ["equibiaxial_limits", "model_derivs", "sqrt_branch", "uniaxial_x", "uniaxial_xlock"]

_EPS = np.finfo(float).eps


def _first(value, mask):
    """A representative offending entry of ``value`` for error messages."""
    v = np.broadcast_to(np.asarray(value), np.shape(mask))
    return (v[mask].flat[0] if np.ndim(mask) else v).item()


def model_derivs(model: Model, I1: np.ndarray, name: str, value):
    """``(W', W'')`` at ``I1``; ``ValueError`` naming ``name`` beyond the model limit."""
    I1max = model.I1_max()
    bad = ~(I1 < I1max)
    if np.any(bad):
        raise ValueError(
            f"{name} = {_first(value, bad)!r} gives I1 = {_first(I1, bad)!r}, beyond the "
            f"{model.name} limit I1 < {I1max}"
        )
    return np.asarray(model.dW(I1), dtype=float), np.asarray(model.d2W(I1), dtype=float)


def sqrt_branch(D2, scale):
    """``sqrt(D2)``; values within rounding of 0 (``|D2| <= 16 eps scale``) give 0, others
    below 0 give ``nan`` (no real state)."""
    D2 = np.where(np.abs(D2) <= 16 * _EPS * scale, 0.0, D2)
    with np.errstate(invalid="ignore"):
        return np.where(D2 >= 0, np.sqrt(np.abs(D2)), np.nan)


def equibiaxial_limits(model: Model) -> tuple[float, float]:
    """Stretches ``(lam_lo, lam_hi)`` where ``I1 = 2 lam^2 + lam^-4`` reaches the model limit."""
    I1max = model.I1_max()
    if not np.isfinite(I1max):
        return 0.0, np.inf
    # 2 y^3 - I1max y^2 + 1 = 0 with y = lam^2: one root in (0, 1), one above 1
    r = np.roots([2.0, -I1max, 0.0, 1.0])
    r = np.sort(r[np.isreal(r)].real)
    r = r[r > 0]
    return float(np.sqrt(r[0])), float(np.sqrt(r[-1]))


def uniaxial_xlock(lam1, I1max):
    """Largest ``x = lam3^2`` with ``lam1^2 + x + 1/(lam1^2 x) <= I1max`` (``inf`` if none)."""
    if not np.isfinite(I1max):
        return np.full(np.shape(lam1), np.inf)
    c = I1max - lam1**2
    disc = c**2 - 4.0 / lam1**2
    with np.errstate(invalid="ignore"):
        return np.where(disc >= 0, 0.5 * (c + np.sqrt(np.maximum(disc, 0.0))), np.nan)


def _uniaxial_x_gent(lam1, s, Jm):
    """Gent closed form of ``x = lam3^2``: with ``2W' = Jm/(Jm + 3 - I1)`` the condition
    ``s = 2W'(lam1 - x/lam1)`` times ``x (Jm + 3 - I1)`` is the quadratic
    ``(Jm/lam1 - s) x^2 + (s (Jm + 3 - lam1^2) - Jm lam1) x - s/lam1^2 = 0``.
    Of its roots, those with ``D0^2 >= 0`` (``x >= 1/lam1``) and ``I1 < 3 + Jm`` are
    states; the smallest (smallest ``D0``) is returned, ``nan`` if none."""
    A = Jm / lam1 - s
    B = s * (Jm + 3.0 - lam1**2) - Jm * lam1
    C = -s / lam1**2
    with np.errstate(invalid="ignore", divide="ignore"):
        sq = np.sqrt(np.maximum(B * B - 4.0 * A * C, 0.0))
        qq = -0.5 * (B + np.where(B >= 0, sq, -sq))
        r1 = qq / A
        r2 = np.where(qq != 0, C / qq, -C / B)  # stable product form; A = 0: linear root
        r1 = np.where(A != 0, r1, np.nan)
    x_lo = 1.0 / lam1
    tol = 64 * _EPS * x_lo  # rounding of the D0 = 0 root
    best = np.full(lam1.shape, np.inf)
    for r in (r1, r2):
        r = np.where(np.abs(r - x_lo) <= tol, x_lo, r)
        with np.errstate(invalid="ignore", divide="ignore"):
            ok = np.isfinite(r) & (r >= x_lo) & (lam1**2 + r + 1.0 / (lam1**2 * r) < 3.0 + Jm)
        best = np.where(ok & (r < best), r, best)
    return np.where(np.isfinite(best), best, np.nan)


def uniaxial_x(lam1, s, model):
    """``x = lam3^2`` on the uni-axial branch (flat arrays in, flat array out)."""
    n = lam1.size
    x = np.full(n, np.nan)
    if isinstance(model, NeoHookean):
        xx = lam1 * (lam1 - s)
        good = (lam1 > s) & np.isfinite(sqrt_branch(lam1**2 * xx**2 - 1.0, 2.0))
        x[good] = xx[good]
        return x
    I1max = model.I1_max()
    x_lo = 1.0 / lam1  # D0 = 0
    model_derivs(model, lam1**2 + 2.0 / lam1, "lam1", lam1)  # D0 = 0 state must be admissible
    if type(model) is Gent:
        return _uniaxial_x_gent(lam1, s, model.Jm)
    x_lock = uniaxial_xlock(lam1, I1max)

    def g(xv, i):
        l1 = lam1[i]
        I1 = l1**2 + xv + 1.0 / (l1**2 * xv)
        dW, d2W = model.dW(I1), model.d2W(I1)
        f = 2 * dW * (l1 - xv / l1) - s[i]
        df = 2 * d2W * (1.0 - 1.0 / (l1**2 * xv**2)) * (l1 - xv / l1) - 2 * dW / l1
        return f, df

    idx = np.arange(n)
    f_lo = g(x_lo, idx)[0]
    # the D0 = 0 state itself: f(x_lo) = 0 up to rounding
    at_lo = np.abs(f_lo) <= 16 * _EPS * (np.abs(s) + lam1 * 2 * model.dW(lam1**2 + 2.0 / lam1))
    x[at_lo] = x_lo[at_lo]
    f_lo = np.where(at_lo, np.nan, f_lo)  # excluded from the brackets below
    pos = s > 0
    # first guess: the neo-Hookean x = lam1 (lam1 - s), corrected once for W'
    with np.errstate(invalid="ignore", divide="ignore"):
        x_nh = lam1 * (lam1 - s)
        I1g = lam1**2 + x_nh + 1.0 / (lam1**2 * x_nh)
        okg = (x_nh > 0) & (I1g < I1max)
        dWg = np.where(okg, model.dW(np.where(okg, I1g, 3.0)), 0.5)
        x0 = lam1 * (lam1 - s / (2 * dWg))
    # (a) s > 0 and the lock does not cut in: root in [x_lo, lam1^2], f(lam1^2) = -s < 0
    A = np.flatnonzero(pos & (lam1**2 > x_lo) & (x_lock > lam1**2) & (f_lo >= 0))
    if A.size:
        x[A] = rtsafe(lambda xv, i: g(xv, A[i]), lam1[A] ** 2, x_lo[A], x0[A])
    # (b) s <= 0: root at or beyond max(x_lo, lam1^2), where f decreases to -inf;
    #     f(lam1^2) = -s exactly (avoid evaluating the rounding of lam1 - lam1^2/lam1)
    start = np.maximum(x_lo, lam1**2)
    f_st = np.where(lam1**2 >= x_lo, -s, f_lo)
    B = np.flatnonzero(~pos & (f_st >= 0) & (start < x_lock) & ~at_lo)
    zero = B[s[B] == 0]
    x[zero] = start[zero]
    B = B[s[B] < 0]
    if B.size:
        hi = expand_bracket(lambda xv, i: g(xv, B[i])[0], start[B], x_lock[B], -1)
        okB = np.isfinite(hi)
        Bk = B[okB]
        x[Bk] = rtsafe(lambda xv, i: g(xv, Bk[i]), hi[okB], start[Bk], x0[Bk])
    # (c) s > 0 and the Gent lock cuts in before lam1^2: f -> +inf at the lock and f may
    #     dip below 0 and rise again; take the first sign change of a scan from x_lo
    #     (the state with the smallest D0), refined by safeguarded Newton
    C_all = np.flatnonzero(pos & np.isfinite(x_lock) & (x_lock <= lam1**2) & (x_lock > x_lo) & ~at_lo)
    for c0 in range(0, C_all.size, 1 << 16):  # blocks bound the memory of the scan grid
        C = C_all[c0:c0 + (1 << 16)]
        t = np.concatenate([np.linspace(0.0, 0.97, 30), 1.0 - 0.03 * 2.0 ** -np.arange(1, 16)])
        xs = x_lo[C, None] + (x_lock[C, None] - x_lo[C, None]) * t[None, :]
        rows = np.repeat(C, t.size)
        # grid points that round onto the locking limit are skipped (nan: no sign change)
        xr = xs.ravel()
        inside = lam1[rows] ** 2 + xr + 1.0 / (lam1[rows] ** 2 * xr) < I1max
        fs = np.full(xr.size, np.nan)
        fs[inside] = g(xr[inside], rows[inside])[0]
        fs = fs.reshape(xs.shape)
        f0, f1 = fs[:, :-1], fs[:, 1:]
        change = ((f0 >= 0) & (f1 < 0)) | ((f0 < 0) & (f1 >= 0))
        has = change.any(axis=1)
        k = np.argmax(change, axis=1)[has]
        Ck = C[has]
        r = np.arange(C.size)[has]
        left, right = xs[r, k], xs[r, k + 1]
        neg_left = fs[r, k] < 0
        a, b = np.where(neg_left, left, right), np.where(neg_left, right, left)
        x[Ck] = rtsafe(lambda xv, i: g(xv, Ck[i]), a, b)
    return x

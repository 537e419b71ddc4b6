"""Root finders of the analytic package (private).

Vectorised finders work on flat arrays of independent problems: each sweep
evaluates only the problems that have not converged yet (no Python loop over
points); ``fun(x, idx)`` receives the trial points ``x`` of the problems ``idx``
(integer indices into the original arrays). Scalar finders take a Python
function of one float.

* :func:`rtsafe` - safeguarded Newton with bisection fallback (needs ``f'``);
* :func:`illinois` - Illinois (modified regula falsi), derivative free;
* :func:`illinois_bisect` - Illinois with a bisection step whenever the bracket
  fails to shrink, absolute tolerance (used on scanned dispersion functions);
* :func:`expand_bracket` - geometric search for a point of a given sign;
* :func:`scan_first_up` - first ``F < 0 -> F >= 0`` change on a grid, then :func:`illinois`;
* :func:`first_root_on_scan` - first sign change of a scanned function, then
  :func:`illinois_bisect`;
* :func:`brent` - scalar Brent method (the iteration of ``scipy.optimize.brentq``);
* :func:`golden_section_max` - scalar golden-section search for a maximum.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "brent",
    "expand_bracket",
    "first_root_on_scan",
    "golden_section_max",
    "illinois",
    "illinois_bisect",
    "rtsafe",
    "scan_first_up",
]

_EPS = np.finfo(float).eps


def rtsafe(fun, a, b, x0=None, *, rtol=4 * _EPS, maxiter=200, start_on_bracket=False, width_every=4):
    """Vectorised safeguarded Newton method (bisection fallback) on brackets.

    Parameters
    ----------
    fun : callable
        ``fun(x, idx) -> (f, df)``: the function and its derivative at the points
        ``x`` of the problems ``idx``.
    a, b : array_like
        Brackets with ``f(a) <= 0 <= f(b)`` for every problem (``a`` may exceed ``b``).
    x0 : array_like, optional
        First guess, used where it is finite and strictly inside the bracket (or,
        with ``start_on_bracket``, on it); elsewhere the midpoint.
    rtol : float
        Relative bracket width at which a problem stops.
    maxiter : int
        Sweeps allowed; a problem still running then returns its last iterate.
    start_on_bracket : bool
        Also accept an ``x0`` equal to an end of the bracket.
    width_every : int
        The bracket width is checked every ``width_every``-th sweep (bisection needs
        ~50 sweeps anyway; ``1`` checks every sweep).

    Returns
    -------
    x : ndarray
        The roots, flat.

    Notes
    -----
    A Newton step is taken where it stays inside the closed bracket, else the
    bracket is bisected; every 16th sweep bisects to break a possible Newton cycle.
    A Newton step of relative size ``1e-9`` leaves an error of order ``1e-18``
    (quadratic convergence; ``f == 0`` gives step 0), so it stops the problem.
    """
    a = np.array(a, dtype=float).ravel()
    b = np.array(b, dtype=float).ravel()
    n = a.size
    out = np.full(n, np.nan)
    active = np.arange(n)
    x = 0.5 * (a + b)
    if x0 is not None:
        x0 = np.broadcast_to(np.asarray(x0, dtype=float).ravel(), x.shape)
        where = (x0 - a) * (x0 - b)
        inside = np.isfinite(x0) & ((where <= 0) if start_on_bracket else (where < 0))
        x = np.where(inside, x0, x)
    for it in range(maxiter):
        if active.size == 0:
            break
        f, df = fun(x, active)
        neg = f < 0
        a = np.where(neg, x, a)
        b = np.where(neg, b, x)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            step = f / df
        xn = x - step
        newton = (xn - a) * (xn - b) <= 0  # False for nan/inf
        if it % 16 == 15:
            newton[:] = False
        xn = np.where(newton, xn, 0.5 * (a + b))
        ax = np.abs(x)
        conv = newton & (np.abs(step) <= 1e-9 * ax)
        if it % width_every == width_every - 1:
            conv |= np.abs(b - a) <= rtol * ax
        if np.any(conv):
            out[active[conv]] = xn[conv]
            keep = ~conv
            active, x, a, b = active[keep], xn[keep], a[keep], b[keep]
        else:
            x = xn
    out[active] = x  # bracket has shrunk for maxiter sweeps: accept
    return out


def illinois(fun, a, b, maxiter=100):
    """Vectorised Illinois (modified regula falsi) root finder.

    Parameters
    ----------
    fun : callable
        ``fun(x, idx) -> f`` at the points ``x`` of the problems ``idx``.
    a, b : array_like
        Brackets with ``fun(a) > 0 >= fun(b)``.
    maxiter : int
        Sweeps allowed; a problem still running then returns its bracket midpoint.

    Returns
    -------
    x : ndarray
        The roots, flat.

    Notes
    -----
    Superlinear and derivative free; the bracket is kept, and the function value
    kept twice in a row at the same end is halved. A problem stops when its
    bracket is 4 ulps wide (relative), on an exact zero or on a non-finite value.
    """
    a, b = np.array(a, dtype=float), np.array(b, dtype=float)
    n = a.size
    out = np.full(n, np.nan)
    idx = np.arange(n)
    fa, fb = fun(a, idx), fun(b, idx)
    side = np.zeros(n)
    for _ in range(maxiter):
        if idx.size == 0:
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            c = b - fb * (b - a) / (fb - fa)
        bad = ~np.isfinite(c) | ((c - a) * (c - b) >= 0)
        c = np.where(bad, 0.5 * (a + b), c)
        fc = fun(c, idx)
        pos = fc > 0
        fa_new = np.where(pos, fc, np.where(side == -1, 0.5 * fa, fa))
        fb_new = np.where(pos, np.where(side == 1, 0.5 * fb, fb), fc)
        a, b = np.where(pos, c, a), np.where(pos, b, c)
        fa, fb = fa_new, fb_new
        side = np.where(pos, 1, -1)
        conv = (np.abs(b - a) <= 4 * _EPS * np.abs(c)) | (fc == 0) | ~np.isfinite(fc)
        out[idx[conv]] = c[conv]
        keep = ~conv
        idx, a, b, fa, fb, side = idx[keep], a[keep], b[keep], fa[keep], fb[keep], side[keep]
    out[idx] = 0.5 * (a + b)
    return out


def illinois_bisect(gfun, lo, up, glo, gup, tol, maxiter=100):
    """Vectorised Illinois regula falsi with a bisection safeguard, in place.

    Parameters
    ----------
    gfun : callable
        ``gfun(k, x) -> g`` at the points ``x`` of the problems ``k``.
    lo, up : ndarray
        Brackets ``lo < up`` with ``g(lo) g(up) <= 0``; overwritten.
    glo, gup : ndarray
        ``g`` at ``lo`` and ``up``; overwritten.
    tol : ndarray
        Absolute bracket width at which a problem stops.
    maxiter : int
        Sweeps allowed.

    Returns
    -------
    lo, up : ndarray
        The final brackets (``lo == up`` where an exact zero was hit; problems
        with ``g(lo) == 0`` on entry are not iterated).

    Notes
    -----
    Differs from :func:`illinois` in the safeguard: a bisection step is taken when
    the secant point leaves the bracket or the same end has been kept three times
    in a row, and the tolerance is absolute.
    """
    side = np.zeros(lo.size, dtype=int)
    active = (glo != 0) & (up - lo > tol)
    for _ in range(maxiter):
        if not active.any():
            break
        k = np.flatnonzero(active)
        width = up[k] - lo[k]
        with np.errstate(invalid="ignore", divide="ignore"):
            x = up[k] - gup[k] * width / (gup[k] - glo[k])
        bisect = ~np.isfinite(x) | (x <= lo[k]) | (x >= up[k]) | (np.abs(side[k]) >= 3)
        x = np.where(bisect, 0.5 * (lo[k] + up[k]), x)
        side[k] = np.where(bisect, 0, side[k])
        gx = gfun(k, x)
        left = np.sign(gx) * np.sign(glo[k]) <= 0  # root in [lo, x]
        # Illinois: halve the function value at the end that is kept
        up[k] = np.where(left, x, up[k])
        gup[k] = np.where(left, gx, np.where(side[k] < 0, 0.5 * gup[k], gup[k]))
        lo[k] = np.where(left, lo[k], x)
        glo[k] = np.where(left, np.where(side[k] > 0, 0.5 * glo[k], glo[k]), gx)
        side[k] = np.where(left, np.where(side[k] > 0, side[k] + 1, 1), np.where(side[k] < 0, side[k] - 1, -1))
        done = (up[k] - lo[k] <= tol[k]) | (gx == 0)
        hit0 = gx == 0
        lo[k] = np.where(hit0, x, lo[k])
        up[k] = np.where(hit0, x, up[k])
        active[k] = ~done
    return lo, up


def expand_bracket(fun_sign, start, limit, want, maxsteps=80):
    """Vectorised search from ``start`` toward ``limit`` for a point of a given sign.

    Parameters
    ----------
    fun_sign : callable
        ``fun_sign(x, idx) -> f`` at the points ``x`` of the problems ``idx``.
    start : array_like
        Starting points (``> 0``).
    limit : array_like
        Where the search stops (``inf``: unbounded).
    want : {+1, -1}
        The sign looked for.
    maxsteps : int
        Trial points per problem.

    Returns
    -------
    x : ndarray
        The first trial point with ``sign(f) == want``; ``nan`` where none. The
        trial points halve the distance to a finite ``limit`` (``limit + (start -
        limit) 2^-k``) or double ``start`` (``start 2^k``) when it is infinite.
    """
    start = np.asarray(start, dtype=float)
    limit = np.broadcast_to(np.asarray(limit, dtype=float), start.shape)
    found = np.full(start.shape, np.nan)
    active = np.arange(start.size)
    for k in range(1, maxsteps + 1):
        if active.size == 0:
            break
        lim, st = limit[active], start[active]
        fin = np.isfinite(lim)
        x = st * 2.0**k
        x[fin] = lim[fin] + (st[fin] - lim[fin]) * 2.0 ** (-k)
        f = fun_sign(x, active)
        hit = np.sign(f) == want
        found[active[hit]] = x[hit]
        active = active[~hit]
    return found


def scan_first_up(F, lo, hi, n=256):
    """First sign change ``F < 0 -> F >= 0`` on a grid from ``lo`` to ``hi``, refined.

    Parameters
    ----------
    F : callable
        ``F(x, rows) -> values`` on 2-D grids ``x`` whose row ``r`` belongs to problem ``rows[r]``.
    lo, hi : ndarray
        Ends of the scanned interval per problem (``F(lo) < 0`` is assumed).
    n : int
        Grid intervals.

    Returns
    -------
    x : ndarray
        The first crossing, refined by :func:`illinois`; ``nan`` where the grid has none.
    """
    t = np.linspace(0.0, 1.0, n + 1)[1:]
    grid = lo[:, None] + (hi - lo)[:, None] * t[None, :]
    Fv = F(grid, np.repeat(np.arange(lo.size), n).reshape(grid.shape))
    prev = np.concatenate([np.full((lo.size, 1), -1.0), Fv[:, :-1]], axis=1)
    change = (prev < 0) & (Fv >= 0)
    has = change.any(axis=1)
    k = np.argmax(change, axis=1)
    out = np.full(lo.size, np.nan)
    r = np.flatnonzero(has)
    a = np.where(k[r] > 0, grid[r, np.maximum(k[r] - 1, 0)], lo[r])
    b = grid[r, k[r]]
    out[r] = illinois(lambda x, i: -F(x, r[i]), a, b)
    return out


def first_root_on_scan(scan, gfun, hi, n_scan=64, rtol=1e-14):
    """Smallest root in ``[0, hi]`` of a function of ``D0``, per point (vectorised).

    Parameters
    ----------
    scan : callable
        ``scan(t)`` returns the function at ``D0 = hi * t`` for all points, shape
        ``(n, len(t))``.
    gfun : callable
        ``gfun(idx, D0)`` returns it for the points ``idx`` at ``D0`` of shape
        ``(len(idx), 1)``.
    hi : ndarray
        Upper ends of the search, shape ``(n,)``.
    n_scan : int
        Scan intervals.
    rtol : float
        Tolerance relative to ``max(hi, 1)``.

    Returns
    -------
    D0 : ndarray
        The first root, refined by :func:`illinois_bisect`; ``nan`` where the scan
        finds no sign change.
    """
    n = hi.shape[0]
    idx = np.arange(n)
    t = np.linspace(0.0, 1.0, n_scan + 1)
    D = hi[:, None] * t[None, :]
    g = scan(t)
    s = np.sign(g)
    change = (s[:, :-1] * s[:, 1:] <= 0) & np.isfinite(g[:, :-1]) & np.isfinite(g[:, 1:])
    has = change.any(axis=1)
    j = np.argmax(change, axis=1)
    out = np.full(n, np.nan)
    if not has.any():
        return out
    ii = idx[has]
    lo, up = D[ii, j[has]], D[ii, j[has] + 1]
    glo, gup = g[ii, j[has]], g[ii, j[has] + 1]
    exact = glo == 0
    tol = rtol * np.maximum(hi[ii], 1.0)
    lo, up = illinois_bisect(lambda k, x: gfun(ii[k], x[:, None])[:, 0], lo, up, glo, gup, tol)
    out[ii] = np.where(exact, D[ii, j[has]], 0.5 * (lo + up))
    return out


def brent(f, a, b, xtol, rtol, maxiter):
    """Scalar root of ``f`` in ``[a, b]`` by Brent's method.

    Parameters
    ----------
    f : callable
        ``f(x) -> float``, with ``f(a)`` and ``f(b)`` of opposite signs.
    a, b : float
        The bracket.
    xtol, rtol : float
        The root is returned once the bracket half-width is below
        ``(xtol + rtol |x|)/2``.
    maxiter : int
        Iterations allowed; ``RuntimeError`` beyond.

    Returns
    -------
    x : float

    Notes
    -----
    Brent (1973): inverse quadratic interpolation or secant steps while they are
    short, bisection otherwise. The iteration is the one of
    ``scipy.optimize.brentq`` step for step (same results, checked in the tests),
    written here so that ``import analytic`` does not load ``scipy.optimize``.
    """
    xpre, xcur = float(a), float(b)
    xblk = fblk = spre = scur = 0.0
    fpre, fcur = f(xpre), f(xcur)
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    if math.copysign(1.0, fpre) == math.copysign(1.0, fcur):
        raise ValueError(f"f(a) and f(b) must have different signs, got f({a}) = {fpre}, f({b}) = {fcur}")
    for _ in range(maxiter):
        if fpre != 0 and fcur != 0 and math.copysign(1.0, fpre) != math.copysign(1.0, fcur):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:  # secant
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:  # inverse quadratic interpolation
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre, scur = scur, stry  # short step accepted
            else:
                spre = scur = sbis
        else:
            spre = scur = sbis
        xpre, fpre = xcur, fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0 else -delta
        fcur = f(xcur)
    raise RuntimeError(f"brent: no convergence after {maxiter} iterations, value is {xcur}")


def golden_section_max(S, a, b, maxiter=80):
    """Scalar golden-section search for a maximum of ``S`` in ``[a, b]``.

    Parameters
    ----------
    S : callable
        ``S(x) -> float``, unimodal on ``[a, b]``.
    a, b : float
        The interval.
    maxiter : int
        Interval reductions (each by the golden ratio).

    Returns
    -------
    fc, fd : float
        ``S`` at the two interior points of the final interval (the caller takes
        the larger).
    """
    g = (np.sqrt(5.0) - 1.0) / 2.0
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = S(c), S(d)
    for _ in range(maxiter):
        if fc > fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = S(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = S(d)
    return fc, fd

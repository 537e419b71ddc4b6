"""The closed forms a loading row is scored with, and the diagnosis of a failing one.

:func:`lam1_closed` inverts Eq. (loading_gent) or Eq. (DEuniax) at a row's ``s`` and ``D0``;
:func:`hypotheses` lists the usual mix-ups of conventions (the sign of ``s``, ``D0`` per
current area, a strain or a percentage for a stretch, ``D0`` in physical units, ...) and
:func:`diagnose_loading` names the first under which every row would pass.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

import analytic as an
from analytic.units import keplinger_s

from ..cases import analytic_model
from ..specs import GENT_JM, KEPLINGER
from .contract import CheckInputError
from .scores import fmt_g

__all__ = ["Loading", "closed_form", "lam1_closed", "lam3_state", "lam1_errors",
           "hypotheses", "diagnose_loading"]

def closed_form(rows, fn, *arrays) -> np.ndarray:
    """``fn(*arrays)`` as a float array (one entry per row of ``rows``); a ``ValueError`` of
    the closed form (a value out of its range, e.g. one whose square overflows) becomes a
    :class:`CheckInputError` naming the first row it comes from."""
    try:
        with np.errstate(all="ignore"):
            return np.atleast_1d(np.asarray(fn(*arrays), dtype=float))
    except ValueError as exc:
        for i, row in enumerate(rows):
            try:
                with np.errstate(all="ignore"):
                    fn(*(a[i:i + 1] for a in arrays))
            except ValueError as one:
                raise CheckInputError(f"{row.where}: out of the range of the closed form "
                                      f"({' '.join(str(one).split())})") from None
        raise CheckInputError(f"{rows[0].where}: {' '.join(str(exc).split())}") from None


def lam1_closed(D0, s, model, loading, rows) -> np.ndarray:
    """Closed-form ``lam1`` per row: Eq. (loading_gent) inverted (``equibiaxial_lam``) or
    Eq. (DEuniax) inverted (``uniaxial_lam1``)."""
    out = np.full(D0.shape, np.nan)
    for m in set(model):
        for ld in set(loading):
            sel = (model == m) & (loading == ld)
            if not sel.any():
                continue
            am = analytic_model(m)
            f = an.equibiaxial_lam if ld == "equibiaxial" else an.uniaxial_lam1
            out[sel] = closed_form([r for r, k in zip(rows, sel) if k],
                               lambda d, s_: f(d, s_, am), D0[sel], s[sel])
    return out


def lam3_state(lam1, lam3, s, model, loading, rows) -> np.ndarray:
    """``lam3`` of each row: the file's where given, else ``lam1`` equi-biaxially and
    Eq. (uni-axial-loading) (``uniaxial_lam3(lam1, s)``) uni-axially."""
    out = lam3.copy()
    need = ~np.isfinite(out)
    out[need & (loading == "equibiaxial")] = lam1[need & (loading == "equibiaxial")]
    for m in set(model):
        sel = need & (loading != "equibiaxial") & (model == m)
        if sel.any():
            am = analytic_model(m)
            out[sel] = closed_form([r for r, k in zip(rows, sel) if k],
                               lambda l1, s_: an.uniaxial_lam3(l1, s_, am), lam1[sel], s[sel])
    return out


@dataclass
class Loading:
    """The columns of rows scored against a loading curve (one array entry per row)."""

    rows: list
    s: np.ndarray
    D0: np.ndarray
    lam1: np.ndarray
    lam3: np.ndarray
    model: np.ndarray
    loading: np.ndarray
    E0: np.ndarray              # the file's E0 where D0 came from it, else nan
    alpha: np.ndarray
    s_from_alpha: np.ndarray    # s of the Keplinger plate computed from alpha

    def replace(self, **kw) -> "Loading":
        d = dict(vars(self))
        d.update(kw)
        return Loading(**d)


def lam1_errors(p: Loading) -> tuple[np.ndarray, np.ndarray]:
    """The closed-form ``lam1`` of every row of ``p`` (:func:`lam1_closed`) and the relative
    error ``|lam1 - closed form| / closed form`` of the file's ``lam1`` (``nan`` where no
    closed form exists)."""
    ref = lam1_closed(p.D0, p.s, p.model, p.loading, p.rows)
    with np.errstate(all="ignore"):
        return ref, np.abs(p.lam1 - ref) / ref


def _D0_scale(p: Loading) -> float | None:
    """The one factor by which the file's ``D0`` (where it gives ``D0``) exceeds the
    ``D0`` of its stretches (Eq. (loading_gent) or Eq. (DEuniax) solved for ``D0``), when
    that factor is the same in every charged row within 1 % and far from 1 (a mix-up of
    units); else ``None``."""
    sel = ~np.isfinite(p.E0) & (p.D0 > 0)
    if not sel.any():
        return None
    implied = np.full(p.D0.shape, np.nan)
    with np.errstate(all="ignore"):
        for m in set(p.model[sel]):
            am = analytic_model(m)
            for ld in set(p.loading[sel]):
                k = sel & (p.model == m) & (p.loading == ld)
                f = an.equibiaxial_D0 if ld == "equibiaxial" else an.uniaxial_D0
                try:
                    implied[k] = f(p.lam1[k], p.s[k], am)
                except ValueError:
                    return None
        ratio = p.D0[sel] / implied[sel]
    ratio = ratio[np.isfinite(ratio) & (ratio > 0)]
    if not ratio.size:
        return None
    c = float(np.median(ratio))
    if 0.1 < c < 10 or np.max(np.abs(ratio / c - 1)) > 1e-2:
        return None
    return c


def hypotheses(p: Loading) -> list[tuple[str, Callable[[], Loading]]]:
    """Mix-ups of conventions that a failing loading measure is tried with: ``(what it
    would mean, the rows read that way)``."""
    lam3 = lam3_state(p.lam1, p.lam3, p.s, p.model, p.loading, p.rows)
    from_E0 = np.isfinite(p.E0)
    out = []
    if np.any(p.s != 0):
        out.append(("s has the opposite sign (the contract's s > 0 is a dead load that "
                    "stretches the plate)", lambda: p.replace(s=-p.s)))
        out.append(("s is the true traction, per current area of the loaded face (the "
                    "contract's s is nominal, per reference area: s = t_true/lam1)",
                    lambda: p.replace(s=p.s / p.lam1)))
    if np.any(~from_E0):
        out.append(("D0 is given per current area, the true D = D_L/(lam1 lam3) (the "
                    "contract's D0 is the charge per reference area: D0 = D lam1 lam3)",
                    lambda: p.replace(D0=np.where(from_E0, p.D0, p.D0 * p.lam1 * lam3))))
        out.append(("the D0 column holds E0 (the contract's D0 = lam1^2 lam3^2 E0, Eq. DLEL)",
                    lambda: p.replace(D0=np.where(from_E0, p.D0, p.D0 * (p.lam1 * lam3)**2))))
    if np.any(from_E0):
        out.append(("the E0 column holds D0 (the contract's E0 = D0/(lam1 lam3)^2)",
                    lambda: p.replace(D0=np.where(from_E0, p.E0, p.D0))))
        out.append(("E0 is the field in the deformed plate, voltage over the current "
                    "thickness (the contract's E0 is over the reference thickness)",
                    lambda: p.replace(D0=np.where(from_E0, p.E0 * p.lam1 * lam3, p.D0))))
    if np.any(np.isfinite(p.lam3)) and np.any(p.loading != "equibiaxial"):
        out.append(("lam1 and lam3 are swapped (lam1 is along the dead load, x1; lam3 across "
                    "the width, x3)",
                    lambda: p.replace(lam1=np.where(np.isfinite(p.lam3), p.lam3, p.lam1),
                                      lam3=np.where(np.isfinite(p.lam3), p.lam1, p.lam3))))
    if np.any(p.lam1 < 1):
        out.append(("the lam1 column holds the strain lam1 - 1 (the contract's lam1 is the "
                    "stretch, 1 + strain)", lambda: p.replace(lam1=p.lam1 + 1.0)))
    if np.any(p.lam1 > 2):
        out.append(("the lam1 column holds the strain in percent (the contract's lam1 is "
                    "the stretch, 1 + percent/100)",
                    lambda: p.replace(lam1=1.0 + p.lam1 / 100.0)))
    scale = _D0_scale(p)
    if scale is not None:
        out.append((f"D0 is in physical units, {scale:.4g} times the contract's in every row "
                    f"(D0 in C/m^2? the contract's D0 is dimensionless, D/sqrt(mu eps): "
                    f"divide by sqrt(mu eps) of your material)",
                    lambda: p.replace(D0=np.where(from_E0, p.D0, p.D0 / scale))))
    other = np.where(p.model == "Gent", "neo-Hookean", "Gent")
    names = " and ".join(sorted(set(p.model)))
    out.append((f"the rows are of the other model than the {names} they name (Gent has "
                f"Jm = {GENT_JM:g})", lambda: p.replace(model=other)))
    if np.any(p.s_from_alpha):
        out.append(("the alpha column holds s (the contract's alpha is the weight fraction, "
                    f"s = alpha m g/(mu A) = {float(keplinger_s(1.0, g=KEPLINGER['g'])):.5g} "
                    "alpha)",
                    lambda: p.replace(s=np.where(p.s_from_alpha, p.alpha, p.s))))
    return out


def diagnose_loading(p: Loading, tol: float, err_of=None) -> str:
    """The first mix-up of :func:`hypotheses` under which every row passes."""
    err_of = err_of or (lambda q: lam1_errors(q)[1])
    for what, read in hypotheses(p):
        try:
            with np.errstate(all="ignore"):
                err = err_of(read())
        except ValueError:              # read that way a row leaves the closed form's range
            continue
        err = np.where(np.isfinite(err), err, np.inf)
        if err.size and np.all(err <= tol):
            return (f"looks like {what}: read that way the largest error would be "
                    f"{fmt_g(float(err.max()))}")
    return ("no usual mix-up of conventions explains it (tried: the sign of s, s per "
            "current area, D0 per current area, E0 for D0, a strain or a percentage for the "
            "stretch, D0 in physical units, the other model)")

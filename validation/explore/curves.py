"""The curves of the ``explore`` page, computed from :mod:`analytic` alone.

Each panel of the page is a pure function of the page's parameters
(:class:`ExploreParameters`) returning plain arrays, so that the page, its static export, the
benchmark and the tests draw the same numbers.  No Bokeh here.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

import analytic as an
from analytic.units import keplinger_s

from ..data.loads import buckling_loads, newton_limits, p33_onsets
from ..cases import ALPHAS
from ..figures.common import (equibiaxial_curve, refine_start, uniaxial_curve,
                              wrinkling_zone_outline)
from ..figures.uniaxial_wrinkling import uniaxial_thick_limit_curve
from ..specs import GENT_JM, KEPLINGER

__all__ = ["ExploreParameters", "PAPER", "PAPER_S", "LAM_MAX", "LAM1_MAX", "D0_MAX", "E0_MAX",
           "KH", "equibiaxial_panel", "uniaxial_panel", "dispersion_panel", "clamped_reference"]

#: Right end of the stretch axis of the equi-biaxial panels (paper Figs. nh-d-e, gent-d-e).
LAM_MAX = 5.0
#: Right end of the stretch axis of the uni-axial panel (paper Fig. uni-axial-ideal).
LAM1_MAX = 6.0
#: Top of the ``D0`` axes (paper Figs. nh-d-e, gent-d-e) and of the ``E0`` axis.
D0_MAX = 8.0
E0_MAX = 0.8
#: Wavenumbers ``kh`` of the dispersion panel (deformed thickness ``h``).
KH = np.geomspace(0.02, 50.0, 60)
#: The paper's dead loads of the equi-biaxial figures per model (Figs. nh-d-e, gent-d-e).
PAPER_S = {"neo-Hookean": (0.0, 1.0, 2.0, 3.0), "Gent": (0.0, 1.0, 2.3, 3.0)}
_MODELS = ("neo-Hookean", "Gent")
_CONTROLS = ("charge", "voltage")
_N = 400                         # points per loading curve


@dataclass(frozen=True)
class ExploreParameters:
    """What the student sets on the page.

    Parameters
    ----------
    model : {"neo-Hookean", "Gent"}
        Strain energy, ``W = (I1 - 3)/2`` or Gent's ``-(Jm/2) ln(1 - (I1 - 3)/Jm)``.
    Jm : float
        Gent's locking parameter (``> 0``; the paper's 97.2); unused for neo-Hookean.
    control : {"charge", "voltage"}
        What the electrodes hold fixed: the charge ``D0`` or the voltage ``E0``.
    s : float
        Equi-biaxial dead load ``s = t/mu`` (Eq. loading_gent).
    alpha : float
        Weight fraction of the Keplinger plate (``> 0``); its uni-axial dead load is
        ``s = alpha m g/(mu A)`` (:func:`analytic.units.keplinger_s`).
    lam : float
        Equi-biaxial stretch of the dispersion panel (``> 0``).

    The checks run when a panel is computed (:meth:`analytic_model`, the panels), so that
    the page can hold a bad value and say what is wrong with it.
    """

    model: str = "neo-Hookean"
    Jm: float = GENT_JM
    control: str = "charge"
    s: float = 1.0
    alpha: float = 1.0
    lam: float = 2.0

    def analytic_model(self):
        """The :mod:`analytic` model: ``NeoHookean()`` or ``Gent(Jm)``; ``ValueError``
        naming ``model`` or ``Jm`` for a bad value."""
        if self.model not in _MODELS:
            raise ValueError(f"model must be one of {list(_MODELS)}, got {self.model!r}")
        if self.control not in _CONTROLS:
            raise ValueError(f"control must be one of {list(_CONTROLS)}, got {self.control!r}")
        return _model(self.model, float(self.Jm))


#: The parameters of the paper's figures: neo-Hookean, charge control, ``s = 1``
#: (Fig. nh-d-e), ``alpha = 1`` (Fig. uni-axial-ideal), ``lam = 2``.
PAPER = ExploreParameters()


@functools.lru_cache(maxsize=16)
def _model(name: str, Jm: float):
    return an.NeoHookean() if name == "neo-Hookean" else an.Gent(Jm=Jm)


def _finite(name: str, value) -> float:
    value = float(value)
    if not np.isfinite(value):
        raise ValueError(f"{name} must be a finite number, got {value}")
    return value


def _split(y, stable):
    """``(y where stable, y where not)`` with ``nan`` elsewhere; each part keeps the first
    point of the other at a change, so that the two lines join."""
    y = np.asarray(y, dtype=float)
    stable = np.asarray(stable, dtype=bool)
    change = np.r_[False, stable[1:] != stable[:-1]]
    a = np.where(stable | change, y, np.nan)
    b = np.where(~stable | change, y, np.nan)
    return a, b


def equibiaxial_panel(p: ExploreParameters) -> dict:
    """The equi-biaxial loading curves ``D0(lam)`` and ``E0(lam)`` at the dead load ``p.s``.

    Parameters
    ----------
    p : ExploreParameters

    Returns
    -------
    dict
        ``lam``, ``D0``, ``E0`` of the curve (Eq. loading_gent, ``E0 = D0/lam^4``);
        ``D0_stable``, ``D0_unstable``, ``E0_stable``, ``E0_unstable``: the same split by
        the stability of the state under ``p.control``
        (:func:`analytic.equibiaxial_stability_verdict`); ``locus_lam``, ``locus_D0``,
        ``locus_E0``: the voltage-control limit ``det H* = 0``
        (:func:`analytic.voltage_limit_D0`); ``max_lam``, ``max_E0``, ``max_D0``: the
        maximum of ``E0`` on the curve (:func:`analytic.max_E0`, ``nan`` if it has none);
        ``paper``: the paper's curves ``[(s, lam, D0, E0), ...]`` (:data:`PAPER_S`);
        ``notes``: sentences for the page (no maximum, wrinkled from the start).

    Notes
    -----
    Paper Figs. nh-d-e and gent-d-e (Sec. 3.1): the maxima of ``E0`` lie on the
    ``det H* = 0`` locus; under voltage control the states past the maximum are
    unstable, under charge control every state is stable for these models.
    """
    m = p.analytic_model()
    s = _finite("s", p.s)
    lam, D0 = equibiaxial_curve(s, m, _lam_top(p.model, float(p.Jm)), n=_N)
    E0 = D0 / lam**4
    stable = np.asarray(an.equibiaxial_stability_verdict(lam, D0, m, control=p.control),
                        dtype=bool) if lam.size else np.zeros(0, bool)
    D0s, D0u = _split(D0, stable)
    E0s, E0u = _split(E0, stable)
    locus_lam, locus_D0 = _locus(p.model, float(p.Jm))
    lm, E0m = an.max_E0(s, m)
    notes = []
    if not np.isfinite(lm):
        notes.append(f"s = {s:g}: E0 has no maximum on this curve (above s = "
                     f"{an.no_maximum_threshold(m):.4g} for {_name(p)}): voltage control "
                     "stays stable all along")
    if lam.size and lam[0] < 1.0:
        notes.append(f"s = {s:g} < 0: the plate is compressed at D0 = 0 (lam = "
                     f"{lam[0]:.4g} < 1); a thin plate wrinkles already without charge "
                     "(thin-plate limit, Eq. antisym_thin)")
    return dict(lam=lam, D0=D0, E0=E0, D0_stable=D0s, D0_unstable=D0u, E0_stable=E0s,
                E0_unstable=E0u, locus_lam=locus_lam, locus_D0=locus_D0,
                locus_E0=locus_D0 / locus_lam**4, max_lam=float(lm), max_E0=float(E0m),
                max_D0=float(lm**4 * E0m), paper=_paper_equibiaxial(p.model, float(p.Jm)),
                notes=notes)


def uniaxial_panel(p: ExploreParameters) -> dict:
    """The Keplinger plate's uni-axial loading curve ``D0(lam1)`` for the weight ``p.alpha``
    with the thin- and thick-plate wrinkling limits and the zone between them.

    Parameters
    ----------
    p : ExploreParameters

    Returns
    -------
    dict
        ``s`` (the dead load of ``p.alpha``), ``lam1``, ``D0`` of the curve (Eq. DEuniax);
        ``thin_lam1``, ``thin_D0``: the thin-plate limit (Eq. thin-uni-axial, the ``s = 0``
        curve); ``thick_lam1``, ``thick_D0``: the thick-plate limit (Eq. thick-uni-axial on
        the path); ``zone``: the outline ``(xs, ys)`` of the wrinkling zone or ``None``;
        ``paper``: the curves of the paper's weights ``[(alpha, s, lam1, D0), ...]``;
        ``reference``: the converged study of the clamped plate at this weight (the
        neo-Hookean plate of the package's data, the same layer as the figures':
        :func:`clamped_reference`); ``notes``.

    Notes
    -----
    Paper Fig. uni-axial-ideal (Sec. 5).
    """
    p.analytic_model()                  # its parameters checked (a ValueError naming them)
    alpha = _finite("alpha", p.alpha)
    if alpha <= 0:
        raise ValueError(f"alpha must be > 0, got {alpha:g}")
    s = float(keplinger_s(alpha, g=KEPLINGER["g"]))
    lam1, D0 = _uniaxial_curve(s, p.model, float(p.Jm))
    thin_lam1, thin_D0, thick_lam1, thick_D0, zone = _uniaxial_limits(p.model, float(p.Jm))
    notes = []
    if not lam1.size:
        notes.append(f"alpha = {alpha:g} (s = {s:.4g}): no uni-axial state up to "
                     f"lam1 = {_lam1_top(p.model, float(p.Jm)):.4g} ({_name(p)})")
    if not np.isfinite(thick_D0).any():
        notes.append(f"no thick-plate limit below the locking of {_name(p)}")
    reference = clamped_reference(alpha) if p.model == "neo-Hookean" else {}
    return dict(s=s, lam1=lam1, D0=D0, thin_lam1=thin_lam1, thin_D0=thin_D0,
                thick_lam1=thick_lam1, thick_D0=thick_D0, zone=zone,
                paper=_paper_uniaxial(p.model, float(p.Jm)), reference=reference,
                notes=notes)


def clamped_reference(alpha: float) -> dict:
    """The converged study of the clamped Keplinger plate at the weight ``alpha`` (matched
    to ``1e-9``), each value on the weight's homogeneous neo-Hookean curve: ``{role: (lam1,
    D0)}`` with the roles ``p33_onset`` (:func:`validation.data.loads.p33_onsets`),
    ``D0_b`` (:func:`validation.data.loads.buckling_loads`, converged only) and
    ``newton_limit`` (:func:`validation.data.loads.newton_limits`); a weight the study
    has not run has none.

    Parameters
    ----------
    alpha : float

    Returns
    -------
    dict
    """
    s = float(keplinger_s(alpha, g=KEPLINGER["g"]))
    m = an.NeoHookean()
    found = {}
    for role, rows in (("p33_onset", [(a, d) for a, d, _ in p33_onsets()]),
                       ("D0_b", [(e.alpha, e.D0_b) for e in buckling_loads()
                                 if e.converged]),
                       ("newton_limit", [(a, d) for a, d, _ in newton_limits()])):
        for a, d in rows:
            if abs(a - alpha) <= 1e-9 and np.isfinite(d):
                found[role] = (float(an.uniaxial_lam1(d, s, m)), float(d))
    return found


def dispersion_panel(p: ExploreParameters) -> dict:
    """The critical charge ``D0_c(kh)`` of the wrinkles of wavenumber ``k`` of a plate of
    deformed thickness ``h`` at the equi-biaxial stretch ``p.lam``, both mode families.

    Parameters
    ----------
    p : ExploreParameters

    Returns
    -------
    dict
        ``kh`` (:data:`KH`), ``antisymmetric`` and ``symmetric``: ``D0_c`` of the flexural
        and extensional modes under ``p.control`` (:func:`analytic.critical_D0`, ``nan``
        where no root); ``thin``, ``thick``: the ``kh -> 0`` limit (Eq. antisym_thin) and
        the ``kh -> inf`` limit (Eq. short-wave); ``notes``.

    Notes
    -----
    The exact dispersion relation of a plate of finite thickness (docs/wrinkling.md),
    which joins the paper's thin- and thick-plate limits (Sec. 4).
    """
    m = p.analytic_model()
    lam = _finite("lam", p.lam)
    if lam <= 0:
        raise ValueError(f"lam must be > 0, got {lam:g}")
    top = _lam_top(p.model, float(p.Jm))
    if p.model != "neo-Hookean" and lam >= top / 0.999:
        raise ValueError(f"lam must be below the locking stretch {top / 0.999:.4g} of "
                         f"{_name(p)}, got {lam:g}")
    anti = np.asarray(an.critical_D0(lam, KH, m, "antisymmetric", p.control), dtype=float)
    sym = np.asarray(an.critical_D0(lam, KH, m, "symmetric", p.control), dtype=float)
    thin = float(an.thin_limit_D0(lam, m))
    thick = float(an.thick_limit_D0(lam, m, control=p.control))
    notes = []
    if not np.isfinite(anti).any():
        notes.append(f"lam = {lam:g}: no flexural root up to D0 = "
                     f"{2 * (lam**3 + 2):.3g}: the compressed plate wrinkles without charge"
                     if lam < 1 else f"lam = {lam:g}: no flexural root")
    return dict(kh=KH, antisymmetric=anti, symmetric=sym, thin=thin, thick=thick, notes=notes)


def _name(p: ExploreParameters) -> str:
    return "neo-Hookean" if p.model == "neo-Hookean" else f"Gent, Jm = {float(p.Jm):g}"


# The parts that depend on the model only, computed once per model.
@functools.lru_cache(maxsize=16)
def _lam_top(model: str, Jm: float) -> float:
    """Right end of the equi-biaxial curves: :data:`LAM_MAX`, or just below Gent's locking
    stretch, ``2 lam^2 + lam^-4 = 3 + Jm``."""
    if model == "neo-Hookean":
        return LAM_MAX
    lock = max(np.roots([2.0, 0.0, -(3.0 + Jm), 0.0, 0.0, 0.0, 1.0]).real)
    return min(LAM_MAX, 0.999 * float(lock))


@functools.lru_cache(maxsize=16)
def _lam1_top(model: str, Jm: float) -> float:
    """Right end of the uni-axial curves: :data:`LAM1_MAX`, or just below the stretch where
    the least ``I1`` of a uni-axial state, ``lam1^2 + 2/lam1``, reaches Gent's ``3 + Jm``."""
    if model == "neo-Hookean":
        return LAM1_MAX
    lock = max(np.roots([1.0, 0.0, -(3.0 + Jm), 2.0]).real)
    return min(LAM1_MAX, 0.999 * float(lock))


@functools.lru_cache(maxsize=16)
def _locus(model: str, Jm: float):
    lam = np.linspace(1.0, _lam_top(model, Jm), _N)
    return lam, np.asarray(an.voltage_limit_D0(lam, _model(model, Jm)), dtype=float)


@functools.lru_cache(maxsize=16)
def _paper_equibiaxial(model: str, Jm: float):
    m = _model(model, Jm)
    out = []
    for s in PAPER_S[model]:
        lam, D0 = equibiaxial_curve(s, m, _lam_top(model, Jm), n=_N)
        out.append((s, lam, D0, D0 / lam**4))
    return tuple(out)


@functools.lru_cache(maxsize=16)
def _paper_uniaxial(model: str, Jm: float):
    _model(model, Jm)                   # its parameters checked
    out = []
    for a in ALPHAS:
        s = float(keplinger_s(a, g=KEPLINGER["g"]))
        lam1, D0 = _uniaxial_curve(s, model, Jm)
        out.append((a, s, lam1, D0))
    return tuple(out)


def _uniaxial_curve(s: float, model: str, Jm: float):
    """``(lam1, D0)`` of Eq. (DEuniax) up to the end of the axis; sampled at the stretch
    where ``D0`` is finite when the end of the axis has no state (Gent near locking)."""
    m = _model(model, Jm)
    top = _lam1_top(model, Jm)
    if model != "neo-Hookean":
        grid = np.linspace(top, 0.4, 200)
        D0 = np.asarray(an.uniaxial_D0(grid, s, m), dtype=float)
        if not np.isfinite(D0).any():
            return np.empty(0), np.empty(0)
        top = float(grid[np.argmax(np.isfinite(D0))])
    lam1, D0, _ = uniaxial_curve(s, m, top, n=_N)
    return lam1, D0


@functools.lru_cache(maxsize=16)
def _uniaxial_limits(model: str, Jm: float):
    m = _model(model, Jm)
    thin_lam1, thin_D0 = _uniaxial_curve(0.0, model, Jm)
    lam1 = np.linspace(0.4, _lam1_top(model, Jm), _N)
    try:
        lk, thick = refine_start(lam1, lambda x: uniaxial_thick_limit_curve(x, m))
    except ValueError:            # the bisection's bracket reaches the Gent locking
        lk, thick = lam1, np.full(lam1.shape, np.nan)
    zone = wrinkling_zone_outline(lk, thick, thin_lam1, thin_D0, D0_MAX)
    return thin_lam1, thin_D0, lk, thick, zone

"""Paper Fig. 4 (figde): the uni-axial loading curves ``D0(lam1)`` and ``E0(lam1)`` of
Eq. (DEuniax) with the ``det H* = 0`` locus of the voltage-control limit, with the FE dots
of the free uni-axial plate."""

from __future__ import annotations

import numpy as np

import analytic as an

from ..cases import analytic_model
from ..markers import VOLTAGE_LIMIT_LOCUS, line_style
from .common import colors, finish_loading_axes, loading_fe_dots, new_axes, uniaxial_curve

__all__ = ["uniaxial_voltage_locus", "plot_uniaxial_loading"]


# --------------------------------------------------------------------------- uni-axial
def uniaxial_voltage_locus(model="neo-Hookean", s=None):
    """Points ``(lam1, D0, E0)`` of the uni-axial ``det H* = 0`` locus.

    Traced through the maxima of ``E0`` along the fixed-``s`` loading curves,
    :func:`analytic.max_E0` with ``loading="uniaxial"`` (paper Fig. figde).
    """
    m = analytic_model(model)
    s = np.linspace(0.0, 6.0, 301) if s is None else np.asarray(s, dtype=float)
    lam1, E0 = (np.atleast_1d(np.asarray(a, dtype=float))
                for a in an.max_E0(s, m, loading="uniaxial"))
    ok = np.isfinite(lam1)
    D0 = np.asarray(an.uniaxial_D0(lam1[ok], s[ok], m), dtype=float)
    return lam1[ok], D0, E0[ok]


def plot_uniaxial_loading(model="neo-Hookean", s_values=(0, 1, 2, 3, 4), quantity="D0",
                          fe=None, ax=None, lam1_max=6.0, locus=True, palette=None):
    """Uni-axial dead-load curves ``D0(lam1)`` or ``E0(lam1)`` (paper Fig. figde, Eq. DEuniax).

    The dotted curve is the ``det H* = 0`` locus of :func:`uniaxial_voltage_locus`;
    FE dots at ``(lam1_fe, D0)`` or ``(lam1_fe, D0/(lam1_fe lam3_fe)^2)``. ``palette``
    (a superset of ``s_values``) fixes the colour of each ``s`` across panels.

    Returns
    -------
    matplotlib Axes
    """
    if quantity not in ("D0", "E0"):
        raise ValueError(f"quantity must be 'D0' or 'E0', got {quantity!r}")
    ax = new_axes(ax)
    m = analytic_model(model)
    for s, c in zip(s_values, colors(len(s_values), s_values, palette)):
        lam1, D0, E0 = uniaxial_curve(s, m, lam1_max)
        ax.plot(lam1, D0 if quantity == "D0" else E0, color=c, label=f"$s = {s:g}$")
        loading_fe_dots(ax, fe, s=s, model=model, quantity=quantity, color=c)
    if locus:
        l1, D0, E0 = uniaxial_voltage_locus(model)
        ax.plot(l1, D0 if quantity == "D0" else E0, label=r"$\det\mathcal{H}^* = 0$",
                **line_style(VOLTAGE_LIMIT_LOCUS))
    finish_loading_axes(ax, fe, quantity, r"$\lambda_1$", (0.5, lam1_max),
                        f"{model}, uni-axial dead load: ${quantity[0]}_0$ vs $\\lambda_1$")
    return ax

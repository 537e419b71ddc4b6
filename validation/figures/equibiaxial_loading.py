"""Paper Figs. 1 (nh-d-e) and 2 (gent-d-e): the equi-biaxial loading curves
``D0(lam)`` and ``E0(lam)`` of Eq. (loading_gent) for several dead loads ``s``, with the FE
dots of the homogeneous plates and the voltage-control limit."""

from __future__ import annotations

import numpy as np

import analytic as an

from ..cases import analytic_model
from ..markers import VOLTAGE_LIMIT_LOCUS, line_style
from .common import colors, equibiaxial_curve, finish_loading_axes, loading_fe_dots, new_axes

__all__ = ["plot_equibiaxial_loading"]


# --------------------------------------------------------------------------- equi-biaxial
def plot_equibiaxial_loading(model="neo-Hookean", s_values=(0, 1, 2, 3), quantity="D0",
                             fe=None, ax=None, lam_max=5.0, locus=True):
    """Equi-biaxial loading curves ``D0(lam)`` or ``E0(lam)`` at fixed ``s``.

    Paper Figs. nh-d-e and gent-d-e: Eq. (loading_gent) and ``E0 = lam^-4 D0``,
    with the dotted voltage-control limit locus ``det H* = 0`` (through the
    maxima of ``E0``; for neo-Hookean ``D0 = sqrt((lam^6 + 5)/3)``) and the
    maxima of ``E0`` from :func:`analytic.max_E0` marked.

    Parameters
    ----------
    model : {"neo-Hookean", "Gent"}
    s_values : sequence of float
    quantity : {"D0", "E0"}
    fe : dict, optional
        FE table; dots at ``(lam1_fe, D0)`` or ``(lam1_fe, E0_fe)`` with
        ``E0_fe = D0/(lam1_fe lam3_fe)^2``.
    ax : matplotlib Axes, optional
    lam_max : float
        Right end of the stretch axis (starts at 1).
    locus : bool
        Draw the voltage-control limit locus.

    Returns
    -------
    matplotlib Axes
    """
    if quantity not in ("D0", "E0"):
        raise ValueError(f"quantity must be 'D0' or 'E0', got {quantity!r}")
    ax = new_axes(ax)
    m = analytic_model(model)
    for s, c in zip(s_values, colors(len(s_values))):
        lam, D0 = equibiaxial_curve(s, m, lam_max)
        ax.plot(lam, D0 if quantity == "D0" else D0 / lam**4, color=c, label=f"$s = {s:g}$")
        loading_fe_dots(ax, fe, s=s, model=model, quantity=quantity, color=c)
    if locus:
        lam = np.linspace(1.0, lam_max, 800)
        D0l = np.asarray(an.voltage_limit_D0(lam, m), dtype=float)
        ax.plot(lam, D0l if quantity == "D0" else D0l / lam**4,
                label=r"$\det\mathcal{H}^* = 0$ (voltage control limit)",
                **line_style(VOLTAGE_LIMIT_LOCUS))
        lm, E0m = (np.atleast_1d(np.asarray(a, dtype=float))
                   for a in an.max_E0(np.asarray(s_values, dtype=float), m, loading="equibiaxial"))
        ok = np.isfinite(lm)
        ax.plot(lm[ok], (lm**4 * E0m)[ok] if quantity == "D0" else E0m[ok], "k^", ms=5,
                label=r"max of $E_0$ at fixed $s$")
    finish_loading_axes(ax, fe, quantity, r"$\lambda$", (1.0, lam_max),
                        f"{model}, equi-biaxial: ${quantity[0]}_0$ vs stretch")
    return ax

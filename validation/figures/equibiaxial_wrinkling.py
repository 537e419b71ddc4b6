"""Paper Fig. 3 (gent-equi-biaxial): the equi-biaxial loading curves with the thin- and
thick-plate wrinkling limits, neo-Hookean and Gent, with the FE dots."""

from __future__ import annotations

import numpy as np

import analytic as an

from ..cases import analytic_model
from ..markers import THIN_PLATE_LIMIT, line_style
from .common import (VARIANT_MARKER, colors, equibiaxial_curve, fe_dots, fe_rows, new_axes,
                     refine_start, variant_legend, wrinkling_zone)

__all__ = ["plot_equibiaxial_wrinkling"]


def plot_equibiaxial_wrinkling(model="neo-Hookean", s_values=(0, 0.8, 1.5, 2.5, 4.5), fe=None,
                               ax=None, D0max=8.0):
    """Loading curves with the thin/thick-plate wrinkling limits (paper Fig. gent-equi-biaxial).

    The grey zone lies between the thick-plate limit (dashed, Eq. ideal-shortwave
    for neo-Hookean, Eq. short-wave in general) and the thin-plate limit
    (Eq. antisym_thin, which coincides with the ``s = 0`` loading curve).

    Returns
    -------
    matplotlib Axes
    """
    ax = new_axes(ax)
    m = analytic_model(model)
    lam = np.linspace(0.5, 5.0, 2000)
    lk, thick = refine_start(lam, lambda x: an.thick_limit_D0(x, m))
    ln, thin = refine_start(lam, lambda x: an.thin_limit_D0(x, m))
    wrinkling_zone(ax, lk, thick, ln, thin, D0max)
    for s, c in zip(s_values, colors(len(s_values))):
        l, D0 = equibiaxial_curve(s, m, 5.0)
        ax.plot(l, D0, color=c, label=f"$s = {s:g}$")
        mask = fe_rows(fe, s=s, model=model)
        if mask is not None:
            for v in VARIANT_MARKER:
                fe_dots(ax, fe, fe["lam1_fe"], fe["D0"], mask & (fe["variant"] == v), v, c)
    ax.plot(ln, thin, label="thin-plate limit (= $s = 0$ curve)", **line_style(THIN_PLATE_LIMIT))
    ax.set_xlim(0.5, 5.0)
    ax.set_ylim(0, D0max)
    ax.set_xlabel(r"$\lambda$")
    ax.set_ylabel(r"$D_0$")
    handles, _ = ax.get_legend_handles_labels()
    ax.legend(handles=handles + variant_legend(ax, fe), fontsize=8, loc="lower right")
    ax.set_title(f"{model}, equi-biaxial: loading curves and wrinkling limits", fontsize=10)
    return ax

"""Paper Fig. 5 (uni-axial-ideal): the Keplinger plate's uni-axial loading curves for the
weight fractions ``alpha``, the thin- and thick-plate wrinkling limits, the FE dots of the
clamped plate, its ``P33`` breakdown and its buckling load."""

from __future__ import annotations

import numpy as np
from matplotlib.lines import Line2D

import analytic as an
from analytic.units import keplinger_s

from ..cases import ALPHAS, analytic_model
from ..specs import KEPLINGER
from .common import (BREAKDOWN_MARKER, BREAKDOWN_NAME, BUCKLING_NAME, MODEL_NAME,
                     VARIANT_MARKER, colors, new_axes, refine_start, uniaxial_curve,
                     variant_legend, wrinkling_zone)

__all__ = ["uniaxial_thick_limit_curve", "plot_uniaxial_wrinkling"]


def uniaxial_thick_limit_curve(lam1, model="neo-Hookean", direction="parallel"):
    """``D0`` of the thick-plate limit on the uni-axial path, per ``lam1``.

    Solves Eq. (thick-uni-axial) together with Eq. (uni-axial-loading)_2,
    ``D0^2 = lam1^2 lam3^4 - 1``, for ``lam3`` by vectorised bisection of
    ``thick_limit_D0_uniaxial(lam1, lam3) - sqrt(lam1^2 lam3^4 - 1)`` (paper
    Fig. uni-axial-ideal); ``nan`` where no root is bracketed.
    """
    m = analytic_model(model)
    lam1 = np.asarray(lam1, dtype=float)
    lo = lam1 ** -0.5 * (1 + 1e-12)       # D0 = 0 on the path
    hi = lo * 20.0

    def g(l3):
        th = np.asarray(an.thick_limit_D0_uniaxial(lam1, l3, m, direction=direction), dtype=float)
        path = np.sqrt(np.maximum(lam1**2 * l3**4 - 1.0, 0.0))
        return th - path

    glo, ghi = g(lo), g(hi)
    ok = np.isfinite(glo) & np.isfinite(ghi) & (np.sign(glo) != np.sign(ghi))
    a, b, ga = lo.copy(), hi.copy(), glo.copy()
    for _ in range(80):
        mid = 0.5 * (a + b)
        gm = g(mid)
        left = np.isfinite(gm) & (np.sign(gm) == np.sign(ga))
        a = np.where(left, mid, a)
        ga = np.where(left, gm, ga)
        b = np.where(left, b, mid)
    l3 = 0.5 * (a + b)
    D0 = np.sqrt(np.maximum(lam1**2 * l3**4 - 1.0, 0.0))
    return np.where(ok, D0, np.nan)


def plot_uniaxial_wrinkling(fe=None, alphas=ALPHAS, ax=None, D0max=7.0):
    """The Keplinger plate (paper Fig. uni-axial-ideal).

    Neo-Hookean loading curves Eq. (DEuniax) for ``s = alpha m g/(mu A)``, the
    thick-plate limit (dashed blue, Eq. thick-uni-axial), the thin-plate limit
    (dashed black, Eq. thin-uni-axial, the ``s = 0`` curve), the wrinkling zone
    between them, the FE dots of the clamped plate, per run a red open marker of the
    shape of its FE model around the dot of its "P33 breakdown" (:data:`BREAKDOWN_NAME`:
    the first step with ``P33/mu < -0.01`` near the clamps or that the solver could not
    reach), and a red cross at the "buckling load"
    ``D0_b`` (:data:`BUCKLING_NAME`) of the runs analysed with the whole plate's spectrum
    (the located zero crossing of the lowest physical eigenvalue, column ``D0_b``).
    The FE models are named by :data:`MODEL_NAME` in the legend.

    Returns
    -------
    matplotlib Axes
    """
    ax = new_axes(ax, figsize=(6.5, 4.8))
    m = analytic_model("neo-Hookean")
    lam1 = np.linspace(0.4, 6.0, 1500)
    ln, thin, _ = uniaxial_curve(0.0, m, 6.0)          # Eq. (thin-uni-axial) = s = 0
    lk, thick = refine_start(lam1, uniaxial_thick_limit_curve)
    wrinkling_zone(ax, lk, thick, ln, thin, D0max)
    ax.plot(ln, thin, "--", color="k", label="thin-plate limit ($s = 0$)")
    broken = set()
    buckled = []
    for a, c in zip(alphas, colors(len(alphas))):
        s = float(keplinger_s(a, g=KEPLINGER["g"]))   # the analytic curve's own load
        l1, D0c, _ = uniaxial_curve(s, m, 6.0)
        ax.plot(l1, D0c, color=c, label=rf"$\alpha = {a:g}$, $s = {s:.3g}$")
        if fe is None or not len(fe.get("run", [])):
            continue
        for v in VARIANT_MARKER:
            sel = np.isclose(fe["alpha"], a) & (fe["variant"] == v)
            if not sel.any():
                continue
            conv = np.array([bool(x) for x in fe["converged"][sel]])
            brk = np.array([bool(x) for x in fe["breakdown"][sel]])
            lam_fe, D0_fe = fe["lam1_fe"][sel], fe["D0"][sel]
            ax.plot(lam_fe[conv], D0_fe[conv], ls="none", color=c, **VARIANT_MARKER[v])
            if brk.any() or not conv.all():
                # the first compressive step, else the last converged one before the failure
                i = int(np.argmax(brk)) if brk.any() else max(int(np.argmin(conv)) - 1, 0)
                x = lam_fe[i] if np.isfinite(lam_fe[i]) else fe["lam1_analytic"][sel][i]
                ax.plot(x, D0_fe[i], ls="none", color="red", mfc="none", mew=1.6, zorder=5,
                        clip_on=False, **BREAKDOWN_MARKER.get(v, BREAKDOWN_MARKER["coupled"]))
                broken.add(v)
            located = fe["D0_b"][sel][np.isfinite(fe["D0_b"][sel])] if "D0_b" in fe \
                else np.zeros(0)
            if located.size:          # the stability-based breakdown: a red cross
                D0b = float(located[0])
                ok = conv & np.isfinite(lam_fe)
                ax.plot(np.interp(D0b, D0_fe[ok], lam_fe[ok]), D0b, ls="none", color="red",
                        marker="x", ms=11, mew=2.4, zorder=6, clip_on=False)
                buckled.append(f"{a:g}")
    ax.set_xlim(0.4, 6.0)
    ax.set_ylim(0, D0max)
    ax.set_xlabel(r"$\lambda_1$")
    ax.set_ylabel(r"$D_0$")
    handles, _ = ax.get_legend_handles_labels()
    crosses = [Line2D([], [], ls="none", color="red", mfc="none", mew=1.6,
                      label=f"{BREAKDOWN_NAME} ($P_{{33}}/\\mu < -0.01$), {MODEL_NAME[v]}",
                      **dict(BREAKDOWN_MARKER[v], ms=0.6 * BREAKDOWN_MARKER[v]["ms"]))
               for v in BREAKDOWN_MARKER if v in broken]
    if buckled:
        crosses.insert(0, Line2D([], [], ls="none", color="red", marker="x", ms=8, mew=2.2,
                                 label=f"{BUCKLING_NAME} (whole-plate spectrum), "
                                 + r"$\alpha = $" + ", ".join(buckled)))
    ax.legend(handles=handles + variant_legend(ax, fe) + crosses, fontsize=8,
              loc="center left", bbox_to_anchor=(1.01, 0.5))
    ax.set_title("Keplinger plate, uni-axial dead load (neo-Hookean)", fontsize=10)
    return ax

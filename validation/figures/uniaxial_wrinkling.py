"""Paper Fig. 5 (uni-axial-ideal): the Keplinger plate's uni-axial loading curves for the
weight fractions ``alpha``, the thin- and thick-plate wrinkling limits, the FE dots of the
clamped plate, its ``P33`` breakdown and its buckling load."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.lines import Line2D

import analytic as an
from analytic.units import keplinger_s

from ..buckling_data import buckling_loads
from ..cases import ALPHAS, analytic_model
from ..specs import KEPLINGER
from .common import (BREAKDOWN_MARKER, BREAKDOWN_NAME, BUCKLING_NAME, MODEL_NAME, NEWTON_NAME,
                     VARIANT_MARKER, colors, new_axes, refine_start, uniaxial_curve,
                     variant_legend, wrinkling_zone)

__all__ = ["uniaxial_thick_limit_curve", "RunMarks", "keplinger_run_marks", "plot_uniaxial_wrinkling"]


def uniaxial_thick_limit_curve(lam1, model="neo-Hookean", direction="parallel"):
    """``D0`` of the thick-plate limit on the uni-axial path, per ``lam1``.

    Solves Eq. (thick-uni-axial) together with the uni-axial path
    ``D0^2 = 2W'(I1) (lam1^2 lam3^4 - 1)`` (Eq. (uni-axial-loading)_2,
    ``D0^2 = lam1^2 lam3^4 - 1``, for neo-Hookean) for ``lam3`` by vectorised bisection of
    ``thick_limit_D0_uniaxial(lam1, lam3) - D0(path)`` (paper Fig. uni-axial-ideal);
    ``nan`` where no root is bracketed (for Gent the bracket stays below the locking).  ``model`` is a FE
    material name (:func:`~validation.cases.analytic_model`) or an :mod:`analytic` model.
    """
    m = analytic_model(model) if isinstance(model, str) else an.as_model(model)
    lam1 = np.asarray(lam1, dtype=float)
    lo = lam1 ** -0.5 * (1 + 1e-12)       # D0 = 0 on the path
    hi = lo * 20.0
    I1max = m.I1_max()
    if np.isfinite(I1max):                # Gent: the bracket stays below the locking I1
        b = I1max - lam1**2
        disc = b**2 - 4.0 / lam1**2       # I1 = lam1^2 + x + 1/(lam1^2 x) = I1max, x = lam3^2
        x_lock = np.where((b > 0) & (disc > 0), 0.5 * (b + np.sqrt(np.abs(disc))), 0.0)
        hi = np.where(x_lock > lo**2, np.minimum(hi, np.sqrt(x_lock) * (1 - 1e-9)), lo)

    def g(l3):
        th = np.asarray(an.thick_limit_D0_uniaxial(lam1, l3, m, direction=direction), dtype=float)
        I1 = lam1**2 + l3**2 + 1.0 / (lam1 * l3) ** 2
        path = np.sqrt(np.maximum(2 * m.dW(I1) * (lam1**2 * l3**4 - 1.0), 0.0))
        return th - path

    if np.isfinite(I1max):
        # the difference turns positive again near the locking: bracket its first sign
        # change on a geometric scan from the D0 = 0 state
        grid = lo * (hi / lo) ** np.linspace(0.0, 1.0, 48)[:, None]
        vals = np.array([g(row) for row in grid])
        change = np.sign(vals[1:]) != np.sign(vals[:1])
        k = np.where(change.any(axis=0), np.argmax(change, axis=0) + 1, grid.shape[0] - 1)
        hi = grid[k, np.arange(lam1.size)] if lam1.ndim else grid[k, 0]
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
    I1 = lam1**2 + l3**2 + 1.0 / (lam1 * l3) ** 2
    D0 = np.sqrt(np.maximum(2 * m.dW(I1) * (lam1**2 * l3**4 - 1.0), 0.0))
    return np.where(ok, D0, np.nan)


def _measured_loads(ax, alphas, m, D0max):
    """The converged buckling loads of :mod:`validation.buckling_data` (black diamonds with
    error bars) and the plain form's Newton limits (black triangles down), on each
    weight's homogeneous loading curve; returns their legend entries."""
    out = []
    conv, newton = [], []
    for e in buckling_loads():
        if not any(np.isclose(e.alpha, a) for a in alphas):
            continue
        s = float(keplinger_s(e.alpha, g=KEPLINGER["g"]))
        if e.converged:
            conv.append((float(an.uniaxial_lam1(e.D0_b, s, m)), e.D0_b, e.error))
        if np.isfinite(e.newton_limit) and e.newton_limit <= D0max:
            newton.append((float(an.uniaxial_lam1(e.newton_limit, s, m)), e.newton_limit))
    if conv:
        x, y, err = zip(*conv)
        ax.errorbar(x, y, yerr=err, fmt="D", color="k", ms=6, capsize=3, zorder=7,
                    gid="buckling-converged")
        out.append(Line2D([], [], ls="none", color="k", marker="D", ms=6,
                          label=f"{BUCKLING_NAME} $D_{{0b}}$, converged (error bar)"))
    if newton:
        ax.plot(*zip(*newton), ls="none", color="k", marker="v", ms=8, zorder=7,
                gid="newton-limit")
        out.append(Line2D([], [], ls="none", color="k", marker="v", ms=8,
                          label=f"{NEWTON_NAME}, plain form (20 x 1 x 10)"))
    return out


@dataclass(frozen=True)
class RunMarks:
    """What the Keplinger figure draws of one FE run (one ``alpha``, one variant).

    Attributes
    ----------
    dots : tuple of ndarray
        ``(lam1_fe, D0)`` of the converged rows.
    breakdown : tuple of float or None
        ``(lam1, D0)`` of the "P33 breakdown" (:data:`BREAKDOWN_NAME`): the first row with
        ``P33/mu < -0.01`` near the clamps, else the last converged row before a target
        the solver could not reach; ``None`` if the run has neither.
    buckling : tuple of float or None
        ``(lam1, D0_b)`` of the "buckling load" (:data:`BUCKLING_NAME`), the located zero
        crossing of the whole plate's lowest physical eigenvalue (column ``D0_b``);
        ``None`` if the run has no such crossing.
    """

    dots: tuple
    breakdown: tuple | None
    buckling: tuple | None


def keplinger_run_marks(fe, alpha: float, variant: str) -> RunMarks | None:
    """The dots, ``P33`` breakdown and buckling load of the run ``(alpha, variant)`` of a
    ``uni-axial-ideal`` table (paper Fig. uni-axial-ideal); ``None`` if the table has no
    such run."""
    if fe is None or not len(fe.get("run", [])):
        return None
    sel = np.isclose(fe["alpha"], alpha) & (fe["variant"] == variant)
    if not sel.any():
        return None
    conv = np.array([bool(x) for x in fe["converged"][sel]])
    brk = np.array([bool(x) for x in fe["breakdown"][sel]])
    lam_fe, D0_fe = fe["lam1_fe"][sel], fe["D0"][sel]
    breakdown = None
    if brk.any() or not conv.all():
        # the first compressive step, else the last converged one before the failure
        i = int(np.argmax(brk)) if brk.any() else max(int(np.argmin(conv)) - 1, 0)
        x = lam_fe[i] if np.isfinite(lam_fe[i]) else fe["lam1_analytic"][sel][i]
        breakdown = (x, D0_fe[i])
    located = fe["D0_b"][sel][np.isfinite(fe["D0_b"][sel])] if "D0_b" in fe else np.zeros(0)
    buckling = None
    if located.size:
        D0b = float(located[0])
        ok = conv & np.isfinite(lam_fe)
        buckling = (np.interp(D0b, D0_fe[ok], lam_fe[ok]), D0b)
    return RunMarks((lam_fe[conv], D0_fe[conv]), breakdown, buckling)


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
    With FE data, also the converged buckling load ``D0_b`` of each weight
    (:func:`validation.buckling_data.buckling_loads`, black diamond with its error bar)
    and the plain form's Newton limit (black triangle down), both on the weight's
    homogeneous curve (docs/breakdown.md).
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
            marks = keplinger_run_marks(fe, a, v)
            if marks is None:
                continue
            ax.plot(*marks.dots, ls="none", color=c, **VARIANT_MARKER[v])
            if marks.breakdown is not None:
                ax.plot(*marks.breakdown, ls="none", color="red", mfc="none", mew=1.6,
                        zorder=5, clip_on=False,
                        **BREAKDOWN_MARKER.get(v, BREAKDOWN_MARKER["coupled"]))
                broken.add(v)
            if marks.buckling is not None:       # the stability-based breakdown: a red cross
                ax.plot(*marks.buckling, ls="none", color="red", marker="x", ms=11, mew=2.4,
                        zorder=6, clip_on=False)
                buckled.append(f"{a:g}")
    drawn = _measured_loads(ax, alphas, m, D0max) if fe is not None and len(
        fe.get("run", [])) else []
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
                                 label=f"{BUCKLING_NAME} on this run's mesh, "
                                 + r"$\alpha = $" + ", ".join(buckled)))
    crosses += drawn
    ax.legend(handles=handles + variant_legend(ax, fe) + crosses, fontsize=8,
              loc="center left", bbox_to_anchor=(1.01, 0.5))
    ax.set_title("Keplinger plate, uni-axial dead load (neo-Hookean)", fontsize=10)
    return ax

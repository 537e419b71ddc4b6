"""Paper Fig. 5 (uni-axial-ideal): the Keplinger plate's uni-axial loading curves for the
weight fractions ``alpha``, the thin- and thick-plate wrinkling limits, the FE dots of the
clamped plate, its ``P33`` breakdown and its buckling load."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.lines import Line2D

import analytic as an
from analytic.units import keplinger_s

from ..data.loads import buckling_loads, newton_limit_bands, newton_limits, p33_onsets
from ..cases import ALPHAS, analytic_model
from ..specs import KEPLINGER
from ..markers import (AFTER_BREAKDOWN, CONVERGED_BUCKLING, NEWTON_BAND, NEWTON_BAND_LABEL,
                       NEWTON_LIMIT, NOT_CONVERGED_NOTE,
                       P33_BREAKDOWN, P33_ONSET_LOCATED, P33_SHAPES, RUN_BUCKLING,
                       THIN_PLATE_LIMIT, legend_style, line_style)
from .common import (MODEL_NAME, VARIANT_MARKER, colors, new_axes, refine_start, uniaxial_curve,
                     variant_legend, wrinkling_zone)

__all__ = ["uniaxial_thick_limit_curve", "RunMarks", "keplinger_run_marks", "plot_uniaxial_wrinkling",
           "reference_layer"]


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


def reference_layer(ax, alphas, D0max: float, model: str = "neo-Hookean") -> list:
    """Draw the converged clamped-plate study on ``ax``: per weight of ``alphas`` its
    located ``P33`` onset, converged ``D0_b`` and Newton limit (with the band over its
    meshes), each on the weight's homogeneous loading curve; see below.

    Parameters
    ----------
    ax : matplotlib Axes
        Axes of ``lam1`` against ``D0``.
    alphas : sequence of float
        The weights to draw (the study's other weights are left out).
    D0max : float
        The top of the axes; values above it are not drawn.
    model : str
        The analytic model of the homogeneous curves.

    Returns
    -------
    list of Line2D
        The legend entries of what was drawn.
    """
    return _measured_loads(ax, alphas, analytic_model(model), D0max)


def _measured_loads(ax, alphas, m, D0max):
    """The converged buckling loads of :mod:`validation.data.loads`
    (:data:`~validation.markers.CONVERGED_BUCKLING`, error bars hidden by the diamonds, as
    the legend says) and the plain form's Newton limits
    (:data:`~validation.markers.NEWTON_LIMIT`), on each weight's homogeneous loading curve;
    returns their legend entries, with a note for each weight whose load is not converged
    (no diamond)."""
    out = []
    conv, missing = [], []
    for e in buckling_loads():
        if not any(np.isclose(e.alpha, a) for a in alphas):
            continue
        s = float(keplinger_s(e.alpha, g=KEPLINGER["g"]))
        if e.converged:
            conv.append((float(an.uniaxial_lam1(e.D0_b, s, m)), e.D0_b, e.error))
        else:
            missing.append(f"{e.alpha:g}")

    if conv:
        x, y, err = zip(*conv)
        st = legend_style(CONVERGED_BUCKLING)
        ax.errorbar(x, y, yerr=err, fmt="none", color=st["color"], capsize=3,
                    zorder=st["zorder"], gid="buckling-converged")
        ax.plot(x, y, ls="none", gid="buckling-converged", **st)
        out.append(Line2D([], [], ls="none", **st,
                          label=f"{CONVERGED_BUCKLING.name} (error bar "
                                f"$\\leq {max(err):.2g}$, hidden by the diamond)"))
    for rows, marker, gid, what in ((p33_onsets(), P33_ONSET_LOCATED, "p33-onset-located",
                                     "interior, plain form; "),
                                    (newton_limits(), NEWTON_LIMIT, "newton-limit", "")):
        pts, meshes = [], set()
        for a, d, mesh in rows:          # each weight's value on its homogeneous curve
            if any(np.isclose(a, b) for b in alphas) and d <= D0max:
                s = float(keplinger_s(a, g=KEPLINGER["g"]))
                pts.append((float(an.uniaxial_lam1(d, s, m)), d))
                meshes.add(mesh)
        if pts:
            ax.plot(*zip(*pts), ls="none", gid=gid, **legend_style(marker))
            out.append(Line2D([], [], ls="none", **legend_style(marker),
                              label=f"{marker.name} ({what}{', '.join(sorted(meshes))})"))
    for i, (a, lo, hi, _) in enumerate(newton_limit_bands()):
        if hi > lo and any(np.isclose(a, b) for b in alphas) and lo <= D0max:
            s = float(keplinger_s(a, g=KEPLINGER["g"]))
            d = np.linspace(lo, min(hi, D0max), 40)
            ax.plot(an.uniaxial_lam1(d, s, m), d, **line_style(NEWTON_BAND))
            if not any(h.get_label() == NEWTON_BAND_LABEL for h in out):
                out.append(Line2D([], [], **line_style(NEWTON_BAND), label=NEWTON_BAND_LABEL))
    if missing and conv:
        out.append(Line2D([], [], ls="none", label=rf"$\alpha = {', '.join(missing)}$: "
                                                    f"{NOT_CONVERGED_NOTE}"))
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
        ``(lam1, D0_b)`` of the "buckling load of this run"
        (:data:`~validation.markers.RUN_BUCKLING`), the located zero crossing of the whole
        plate's lowest physical eigenvalue (column ``D0_b``); ``None`` if the run has no
        such crossing.
    after : tuple of ndarray
        ``(lam1_fe, D0)`` of the converged rows past a ``P33`` breakdown (a run that goes
        on for its spectrum, :data:`~validation.markers.AFTER_BREAKDOWN`): part of
        ``dots``; empty where the run stops at its breakdown.
    """

    dots: tuple
    breakdown: tuple | None
    buckling: tuple | None
    after: tuple = (np.zeros(0), np.zeros(0))


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
    past = np.zeros(conv.size, dtype=bool)
    if brk.any() or not conv.all():
        # the first compressive step, else the last converged one before the failure
        i = int(np.argmax(brk)) if brk.any() else max(int(np.argmin(conv)) - 1, 0)
        x = lam_fe[i] if np.isfinite(lam_fe[i]) else fe["lam1_analytic"][sel][i]
        breakdown = (x, D0_fe[i])
        past[i + 1:] = True
    located = fe["D0_b"][sel][np.isfinite(fe["D0_b"][sel])] if "D0_b" in fe else np.zeros(0)
    buckling = None
    if located.size:
        D0b = float(located[0])
        ok = conv & np.isfinite(lam_fe)
        buckling = (np.interp(D0b, D0_fe[ok], lam_fe[ok]), D0b)
    return RunMarks((lam_fe[conv], D0_fe[conv]), breakdown, buckling,
                    (lam_fe[conv & past], D0_fe[conv & past]))


def plot_uniaxial_wrinkling(fe=None, alphas=ALPHAS, ax=None, D0max=7.0):
    """The Keplinger plate (paper Fig. uni-axial-ideal).

    Neo-Hookean loading curves Eq. (DEuniax) for ``s = alpha m g/(mu A)``, the
    thick-plate limit (dashed blue, Eq. thick-uni-axial), the thin-plate limit
    (dashed black, Eq. thin-uni-axial, the ``s = 0`` curve), the wrinkling zone
    between them and the FE dots of the clamped plate.  The markers of the breakdown and
    stability results are those of :mod:`validation.markers`: per run its
    :data:`~validation.markers.P33_BREAKDOWN` (a red open marker of the shape of its FE
    model around the dot of the first step with ``P33/mu < -0.01`` near the clamps or
    that the solver could not reach), the dots of a run that goes on past it faded
    (:data:`~validation.markers.AFTER_BREAKDOWN`), and the
    :data:`~validation.markers.RUN_BUCKLING` (red cross, on top of every other marker) of
    the runs analysed with the whole plate's spectrum (column ``D0_b``).  With FE data,
    also the converged buckling load ``D0_b`` of each weight
    (:func:`validation.data.loads.buckling_loads`,
    :data:`~validation.markers.CONVERGED_BUCKLING`; a legend line names the weights
    without one) and the plain form's Newton limit
    (:data:`~validation.markers.NEWTON_LIMIT`), both on the weight's homogeneous curve
    (docs/breakdown.md).  The FE models are named by :data:`MODEL_NAME` in the legend.
    The ``lam1`` axis ends just past the last curve or dot below ``D0max``.

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
    ax.plot(ln, thin, label="thin-plate limit ($s = 0$)", **line_style(THIN_PLATE_LIMIT))
    broken, faded = set(), set()
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
            later = np.isin(marks.dots[1], marks.after[1])
            ax.plot(marks.dots[0][~later], marks.dots[1][~later], ls="none", color=c,
                    **VARIANT_MARKER[v])
            if later.any():
                ax.plot(*marks.after, ls="none", gid="after-breakdown",
                        **{**VARIANT_MARKER[v], **legend_style(AFTER_BREAKDOWN), "color": c})
                faded.add(v)
            if marks.breakdown is not None:
                ax.plot(*marks.breakdown, ls="none", clip_on=False, gid=f"p33-{v}",
                        **legend_style(P33_BREAKDOWN, P33_SHAPES.get(v, P33_SHAPES["coupled"])))
                broken.add(v)
            if marks.buckling is not None:
                ax.plot(*marks.buckling, ls="none", clip_on=False, gid="buckling-run",
                        **legend_style(RUN_BUCKLING))
                buckled.append(f"{a:g}")
    drawn = _measured_loads(ax, alphas, m, D0max) if fe is not None and len(
        fe.get("run", [])) else []
    ax.set_xlim(0.4, _right_end(ax, D0max))
    ax.set_ylim(0, D0max)
    ax.set_xlabel(r"$\lambda_1$")
    ax.set_ylabel(r"$D_0$")
    handles, _ = ax.get_legend_handles_labels()
    keys = [Line2D([], [], ls="none", label=f"{P33_BREAKDOWN.name} ($P_{{33}}/\\mu < -0.01$), "
                                            f"{MODEL_NAME[v]}",
                   **legend_style(P33_BREAKDOWN, dict(P33_SHAPES[v],
                                                      ms=0.6 * P33_SHAPES[v]["ms"])))
            for v in P33_SHAPES if v in broken]
    keys += [Line2D([], [], ls="none", label=f"{AFTER_BREAKDOWN.name}, {MODEL_NAME[v]}",
                    **{**VARIANT_MARKER[v], **legend_style(AFTER_BREAKDOWN)})
             for v in VARIANT_MARKER if v in faded]
    if buckled:
        keys.insert(0, Line2D([], [], ls="none", **legend_style(RUN_BUCKLING, ms=9, mew=2.2),
                              label=f"{RUN_BUCKLING.name}, " + r"$\alpha = $"
                              + ", ".join(buckled)))
    ax.legend(handles=handles + variant_legend(ax, fe) + keys + drawn, fontsize=8,
              loc="center left", bbox_to_anchor=(1.01, 0.5))
    ax.set_title("Keplinger plate, uni-axial dead load (neo-Hookean)", fontsize=10)
    return ax


def _right_end(ax, D0max: float, step: float = 0.25) -> float:
    """The right end of the ``lam1`` axis: the largest ``lam1`` of a line point with
    ``0 <= D0 <= D0max``, rounded up to ``step`` after a 2 % margin."""
    right = 1.0
    for line in ax.lines:
        xy = np.asarray(line.get_xydata(), dtype=float)
        if xy.size:
            ok = np.isfinite(xy).all(axis=1) & (xy[:, 1] >= 0) & (xy[:, 1] <= D0max)
            if ok.any():
                right = max(right, float(xy[ok, 0].max()))
    return float(np.ceil(1.02 * right / step) * step)

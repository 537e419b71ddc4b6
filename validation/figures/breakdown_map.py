"""The breakdown map of the Keplinger plate: the three meanings of "breakdown" per weight.

One panel with the weight fraction ``alpha`` across and ``D0`` up: the paper's ``P33``
criterion (Sec. 6, the red crosses of its Fig. 5), the converged loss of stability
``D0_b`` of the whole plate (:mod:`validation.data.loads`, with its error bar and the
value of each mesh), the charge where the Newton ramp stops, and the paper's homogeneous
wrinkling limits on each weight's loading path (Eqs. thin-uni-axial, thick-uni-axial).
Beside it, optionally, the critical mode of each weight: the top face's deflection over
the whole plate at ``D0_b``.  docs/breakdown.md reads the figure.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

import analytic as an
from analytic.units import keplinger_s

from ..data.loads import (buckling_loads, newton_limit_bands, newton_limits, p33_onsets,
                          voltage_limits)
from ..cases import ALPHAS, analytic_model
from ..specs import KEPLINGER
from ..markers import (CONVERGED_BUCKLING, LIMIT_POINT, MESH_BUCKLING, NEWTON_BAND,
                       NEWTON_BAND_LABEL, NEWTON_LIMIT, NOT_CONVERGED_NOTE,
                       P33_BREAKDOWN, P33_ONSET_LOCATED, P33_SHAPES, RUN_BUCKLING, RUN_NEWTON,
                       WRINKLING_NOT_REACHED, legend_style, line_style)
from .common import MODEL_NAME, add_caption

__all__ = ["homogeneous_wrinkling_D0", "plot_breakdown_map", "breakdown_map_figure"]

#: where the map's homogeneous wrinkling search ends (and the map's top)
MAP_D0_MAX = 8.0
#: how far left of its weight the map draws the load of each mesh (in alpha)
MESH_OFFSET = 0.025


def homogeneous_wrinkling_D0(alpha: float, model="neo-Hookean", D0_max: float = MAP_D0_MAX,
                             n: int = 1601) -> tuple[float, float]:
    """Where the homogeneous uni-axial loading path of weight ``alpha`` first reaches the
    paper's wrinkling limits.

    The path is Eq. (DEuniax) with ``s = alpha m g/(mu A)`` of the Keplinger plate
    (:func:`analytic.units.keplinger_s`), sampled on ``n`` values of ``D0`` in
    ``[0, D0_max]``; at each state the thin-plate limit Eq. (thin-uni-axial) and the
    thick-plate limit Eq. (thick-uni-axial) of wrinkles along the load
    (:func:`analytic.thin_limit_D0_uniaxial`, :func:`analytic.thick_limit_D0_uniaxial`)
    are compared with the state's ``D0``.

    Parameters
    ----------
    alpha : float
        Weight fraction, ``>= 0``.
    model : str or analytic model, optional
    D0_max : float, optional
        End of the search.
    n : int, optional
        Samples of the path.

    Returns
    -------
    thin, thick : float
        The first ``D0`` where the path's ``D0`` reaches each limit (linear between the
        samples); ``nan`` where it stays below it up to ``D0_max`` -- the paper's finding
        for every charge-controlled path with ``s > 0`` (docs/wrinkling.md).

    Raises
    ------
    ValueError
        ``alpha < 0``, ``D0_max <= 0`` or ``n < 2``.
    """
    if not alpha >= 0:
        raise ValueError(f"alpha must be >= 0, got {alpha}")
    if not D0_max > 0:
        raise ValueError(f"D0_max must be > 0, got {D0_max}")
    if int(n) != n or n < 2:
        raise ValueError(f"n must be an integer >= 2, got {n}")
    m = analytic_model(model) if isinstance(model, str) else model
    s = float(keplinger_s(alpha, g=KEPLINGER["g"]))
    D0 = np.linspace(0.0, D0_max, int(n))
    lam1 = np.asarray(an.uniaxial_lam1(D0, s, m), dtype=float)
    ok = np.isfinite(lam1)
    lam3 = np.full_like(lam1, np.nan)
    lam3[ok] = np.asarray(an.uniaxial_lam3(lam1[ok], s, m), dtype=float)
    ok &= np.isfinite(lam3)
    out = []
    for limit in (an.thin_limit_D0_uniaxial, an.thick_limit_D0_uniaxial):
        margin = np.full_like(D0, np.nan)
        margin[ok] = np.asarray(limit(lam1[ok], lam3[ok], m), dtype=float) - D0[ok]
        hit = np.flatnonzero(np.isfinite(margin) & (margin <= 0))
        if not hit.size:
            out.append(float("nan"))
            continue
        i = int(hit[0])
        if i == 0 or not np.isfinite(margin[i - 1]):
            out.append(float(D0[i]))
            continue
        out.append(float(D0[i - 1] + (D0[i] - D0[i - 1]) * margin[i - 1]
                         / (margin[i - 1] - margin[i])))
    return out[0], out[1]


def plot_breakdown_map(p33=None, run_buckling=None, run_newton=None, loads=None,
                       alphas=ALPHAS, run_mesh: str = "", ax=None, D0max: float = MAP_D0_MAX):
    """The breakdown map: ``D0`` of each meaning of "breakdown" against ``alpha``.

    Parameters
    ----------
    p33 : dict, optional
        ``{variant: {alpha: D0}}``: the first step of a run with ``P33/mu < -0.01`` near
        the clamps (the paper's criterion, Sec. 6; ``None`` values: none in the run), as
        :class:`validation.results.CaseResult` ``breakdown_D0_by_alpha`` holds it.
        :data:`~validation.markers.P33_BREAKDOWN` (red open markers of the run's model
        shape).
    run_buckling : dict, optional
        ``{alpha: D0_b}`` located by the run on its own mesh ``run_mesh``
        (:data:`~validation.markers.RUN_BUCKLING`, red crosses, on top of every other marker).
    run_newton : dict, optional
        ``{alpha: D0}``: the first target a run's Newton solver could not reach
        (:data:`~validation.markers.RUN_NEWTON`).
    loads : sequence of BucklingEntry, optional
        The measured buckling loads (default :func:`validation.data.loads.buckling_loads`):
        the converged ``D0_b`` with its error bar (:data:`~validation.markers.CONVERGED_BUCKLING`;
        the legend says that the bars hide behind the diamonds), the value of each mesh of
        the entry (:data:`~validation.markers.MESH_BUCKLING`: the three uniform meshes, or
        the two finest graded ones; a weight without a diamond gets a note
        in the figure, :data:`~validation.markers.NOT_CONVERGED_NOTE`) and the plain form's
        Newton limit (:func:`validation.data.loads.newton_limits`,
        :data:`~validation.markers.NEWTON_LIMIT`).  The located ``P33`` onsets of the
        clamp-zone study (:func:`validation.data.loads.p33_onsets`,
        :data:`~validation.markers.P33_ONSET_LOCATED`) are drawn with them: with the
        converged loads and the Newton limits they are the reference layer, in the order
        the charge meets them, beside which a run's own values show what its mesh gives.
        The same plate under voltage control snaps through at the charge of
        :func:`validation.data.loads.voltage_limits` (:data:`~validation.markers.LIMIT_POINT`,
        where two meshes agree).
    alphas : sequence of float, optional
        The weights of the homogeneous wrinkling limits (:func:`homogeneous_wrinkling_D0`):
        a blue line where a path reaches one, else a blue arrow at the top of the axes.
    run_mesh : str, optional
        The run's mesh, for the legend of its crosses.
    ax : matplotlib Axes, optional
    D0max : float, optional
        Top of the axes.

    Returns
    -------
    matplotlib Axes
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 4.8), layout="constrained")
    loads = buckling_loads() if loads is None else loads
    named = set()
    for e in loads:                                    # every mesh, converged or not
        label = None
        if e.source not in named:                      # one legend entry per source
            named.add(e.source)
            label = (f"{MESH_BUCKLING.name} (uniform {', '.join(e.meshes)})"
                     if e.source == "uniform" else
                     f"{MESH_BUCKLING.name} (the two finest graded meshes)")
        # a step left of the weight: the finest mesh's value is the diamond's, which would
        # hide it
        ax.plot([e.alpha - MESH_OFFSET] * len(e.D0_b_mesh), e.D0_b_mesh, ls="none",
                gid="buckling-mesh", label=label, **legend_style(MESH_BUCKLING))
    conv = [e for e in loads if e.converged]
    if conv:
        err = max(e.error for e in conv)
        st = legend_style(CONVERGED_BUCKLING)
        ax.errorbar([e.alpha for e in conv], [e.D0_b for e in conv],
                    yerr=[e.error for e in conv], fmt="-", lw=1.0, capsize=3,
                    gid="buckling-converged", color=st.pop("color"), **st,
                    label=f"{CONVERGED_BUCKLING.name} (error bar "
                          f"$\\leq {err:.2g}$, hidden by the diamond)")
    for e in loads:                                    # a weight without a diamond says why
        if not e.converged and len(e.D0_b_mesh):
            ax.annotate(f"$\\alpha = {e.alpha:g}$: {NOT_CONVERGED_NOTE}",
                        (e.alpha, max(e.D0_b_mesh)), xytext=(-6, 10),
                        textcoords="offset points", ha="right", fontsize=7, color="0.3",
                        gid="not-converged")
    bands = [(a, lo, hi, m) for a, lo, hi, m in newton_limit_bands() if hi > lo]
    for i, (a, lo, hi, _) in enumerate(bands):
        ax.plot([a, a], [lo, hi], **line_style(NEWTON_BAND),
                label=None if i else NEWTON_BAND_LABEL)
    volt = [(a, d, ", ".join(ms)) for a, d, ms in voltage_limits()]
    for pts, gid, label, marker in (
            (newton_limits(), "newton-limit", NEWTON_LIMIT.name + " ({})", NEWTON_LIMIT),
            (volt, "voltage-limit", LIMIT_POINT.name + " under voltage control: the charge "
                                    "at the centre, converged ({})", LIMIT_POINT),
            (p33_onsets(), "p33-onset-located",
             P33_ONSET_LOCATED.name + " (interior, plain form; {})", P33_ONSET_LOCATED)):
        if pts:                          # the reference layer: (alpha, D0, mesh) per weight
            meshes = ", ".join(sorted({m for _, _, m in pts}))
            ax.plot([a for a, _, _ in pts], [d for _, d, _ in pts], ls="none", gid=gid,
                    label=label.format(meshes), **legend_style(marker))
    for v, per in (p33 or {}).items():
        pts = [(float(a), d) for a, d in per.items() if d is not None]
        if pts:
            shape = dict(P33_SHAPES.get(v, P33_SHAPES["coupled"]))
            shape["ms"] = 0.6 * shape["ms"]
            ax.plot(*zip(*pts), ls="none", gid=f"p33-{v}",
                    label=f"{P33_BREAKDOWN.name} ($P_{{33}}/\\mu < -0.01$), "
                          f"{MODEL_NAME.get(v, v)}, this run (its meshes: the caption)",
                    **legend_style(P33_BREAKDOWN, shape))
    pts = [(float(a), d) for a, d in (run_buckling or {}).items() if d is not None]
    if pts:
        ax.plot(*zip(*pts), ls="none", gid="buckling-run",
                label=f"{RUN_BUCKLING.name} ({run_mesh or 'its mesh'})",
                **legend_style(RUN_BUCKLING))
    pts = [(float(a), d) for a, d in (run_newton or {}).items() if d is not None]
    if pts:
        ax.plot(*zip(*pts), ls="none", gid="newton-run", label=RUN_NEWTON.name,
                **legend_style(RUN_NEWTON))
    limits = np.array([homogeneous_wrinkling_D0(a, D0_max=D0max) for a in alphas])
    first = np.fmin(limits[:, 0], limits[:, 1]) if len(alphas) else np.zeros(0)
    reached = np.isfinite(first)
    if reached.any():
        ax.plot(np.asarray(alphas)[reached], first[reached], "--", color="tab:blue",
                marker="o", ms=4, gid="wrinkling-limit",
                label="homogeneous wrinkling limit (thin/thick plate)")
    if (~reached).any():
        ax.plot(np.asarray(alphas)[~reached], np.full((~reached).sum(), D0max), ls="none",
                clip_on=False, gid="wrinkling-not-reached",
                label=f"{WRINKLING_NOT_REACHED.name} up to $D_0 = {D0max:g}$",
                **legend_style(WRINKLING_NOT_REACHED))
    ax.set_xlim(0, max(alphas) * 1.08 if len(alphas) else 1.6)
    ax.set_ylim(0, D0max)
    ax.set_xlabel(r"weight fraction $\alpha$ ($s = 2.99\,\alpha$)")
    ax.set_ylabel(r"$D_0$")
    ax.set_title("What is the breakdown? Keplinger plate (neo-Hookean)", fontsize=10, pad=16)
    ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0))   # beside: hides no point
    return ax


def breakdown_map_figure(p33=None, run_buckling=None, run_newton=None, loads=None,
                         modes=None, run_mesh: str = "", caption: str = ""):
    """The breakdown map (:func:`plot_breakdown_map`) with the critical modes beside it.

    Parameters
    ----------
    p33, run_buckling, run_newton, loads, run_mesh
        As :func:`plot_breakdown_map`.
    modes : dict, optional
        ``{alpha: {"X1", "X3", "u2", "D0_b", "class", "mesh"}}``: the top face's
        deflection of the critical mode over the whole plate at that mesh's ``D0_b``
        (as ``skfem-dielectric buckling`` saves it in ``.modes/``), one panel per weight, scaled
        to a largest deflection of 1.  ``None``: the map alone.
    caption : str, optional
        The caption line under the figure.

    Returns
    -------
    matplotlib Figure
    """
    if not modes:
        fig, ax = plt.subplots(figsize=(11.0, 5.6), layout="constrained")
        plot_breakdown_map(p33, run_buckling, run_newton, loads, run_mesh=run_mesh, ax=ax)
    else:
        keys = sorted(modes)
        fig = plt.figure(figsize=(14.0, max(5.6, 1.9 * len(keys))), layout="constrained")
        left, right = fig.subfigures(1, 2, width_ratios=[1.25, 1.0])
        ax = left.subplots()
        plot_breakdown_map(p33, run_buckling, run_newton, loads, run_mesh=run_mesh, ax=ax)
        axes = right.subplots(len(keys), 1, sharex=True, squeeze=False)[:, 0]
        for a, axm in zip(keys, axes):
            d = modes[a]
            u2 = np.asarray(d["u2"], float)
            u2 = u2 / max(np.abs(u2).max(), 1e-300)
            t = axm.tricontourf(d["X1"], d["X3"], u2, 21, cmap="RdBu_r", vmin=-1, vmax=1)
            axm.set_aspect("equal")
            axm.set_ylabel("X3 (mm)", fontsize=8)
            axm.set_title(rf"$\alpha = {a:g}$: mode at $D_{{0b}} = {d['D0_b']:.3f}$ "
                          f"({d['mesh']}), {d['class']}", fontsize=8)
            axm.tick_params(labelsize=7)
        axes[-1].set_xlabel("X1 (mm)", fontsize=8)
        right.colorbar(t, ax=list(axes), shrink=0.6, label="top-face deflection u2 (scaled)")
    if caption:
        add_caption(fig, caption)
    return fig

"""Paper Fig. 7 (zs22): ``P33/mu`` along the centre line of the Keplinger plate for
increasing ``D0`` up to the breakdown, from the FE fields."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from .common import MODEL_NAME, new_axes

__all__ = ["plot_p33_profiles"]


def plot_p33_profiles(fields, fe=None, ax=None, variant="coupled"):
    """``P33/mu`` along the centre line in ``x1`` for increasing ``D0`` (Fig. zs22).

    Parameters
    ----------
    fields : dict
        Table with columns ``run, step, D0, x1`` (metres) and ``P33`` (over mu).
    fe : dict, optional
        The case's step table, to label the breakdown step.
    variant : str
        Which coupling variant to draw (runs whose key contains it).

    Returns
    -------
    matplotlib Axes
    """
    ax = new_axes(ax, figsize=(6.5, 4.5))
    runs = [r for r in dict.fromkeys(fields["run"]) if f"_{variant}_" in r]
    if not runs:
        raise ValueError(f"variant {variant!r} has no profiles in the table")
    sel_run = (fields["run"] == runs[0]) & (fields["kind"] == 0)
    steps = np.unique(fields["step"][sel_run])
    # a sequential map without white (no curve disappears on the background), up to orange
    cmap = plt.get_cmap("plasma")
    D0s = np.array([fields["D0"][sel_run & (fields["step"] == k)][0] for k in steps])
    norm = plt.Normalize(D0s.min(), max(D0s.max(), 1e-12) / 0.82)
    brk_step = None
    if fe is not None and len(fe.get("run", [])):
        sel = (fe["run"] == runs[0]) & np.array([bool(b) for b in fe["breakdown"]])
        if sel.any():
            brk_step = int(fe["step"][sel][0])
    for k, D0 in zip(steps, D0s):
        sel = sel_run & (fields["step"] == k)
        x1, y = fields["x1"][sel], fields["P33"][sel]
        if x1.min() >= 0.0:                       # quarter model: mirror about x1 = 0
            x1, y = np.r_[-x1, x1], np.r_[y, y]
        order = np.argsort(x1)
        x, y = 100 * x1[order], y[order]
        lw, ls = (2.2, "-") if k == brk_step else (1.2, "-")
        ax.plot(x, y, ls, lw=lw, color=cmap(norm(D0)),
                label=f"$D_0 = {D0:.3g}$" + (" (breakdown)" if k == brk_step else ""))
    ax.axhline(0.0, color="k", lw=0.8)
    # the clamp itself is a stress singularity in 3D: keep the interior readable
    ally = fields["P33"][sel_run]
    top, p95 = float(np.nanmax(ally)), float(np.nanpercentile(ally, 95))
    if top > 3 * max(p95, 1e-3):
        ax.set_ylim(top=1.3 * p95)
        ax.text(0.99, 0.02, f"clipped: $P_{{33}}/\\mu$ up to {top:.2g} at the clamps",
                transform=ax.transAxes, ha="right", va="bottom", fontsize=7)
    ax.set_xlabel(r"$X_1$ along the centre line (cm, reference)")
    ax.set_ylabel(r"$P_{33}/\mu$")
    ax.legend(fontsize=7, ncol=2, loc="upper center")
    ax.set_title(f"Keplinger plate, $\\alpha = 1$: lateral stress, {MODEL_NAME[variant]}",
                 fontsize=10)
    return ax

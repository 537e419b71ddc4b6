"""Paper Fig. 6 (lambda1-3): the stretch maps ``lam1``, ``lam3`` of the weighted Keplinger
plate before charging, from the FE fields."""

from __future__ import annotations

import matplotlib.pyplot as plt
import matplotlib.tri as mtri
import numpy as np
from matplotlib.ticker import MaxNLocator

from .common import new_axes

__all__ = ["plot_stretch_maps"]


# --------------------------------------------------------------------------- FE fields
def _mirror(x1, x3, v, length, width):
    """Quarter-model points mirrored to the full plate when they cover one quarter."""
    x1, x3, v = (np.asarray(a, dtype=float) for a in (x1, x3, v))
    if x1.min() >= -1e-12 * length and x1.max() <= 0.5 * length * (1 + 1e-9):
        x1, x3, v = np.r_[x1, -x1], np.r_[x3, x3], np.r_[v, v]
    if x3.min() >= -1e-12 * width and x3.max() <= 0.5 * width * (1 + 1e-9):
        x1, x3, v = np.r_[x1, x1], np.r_[x3, -x3], np.r_[v, v]
    return x1, x3, v


def plot_stretch_maps(fields, axes=None):
    """Maps of ``lam1`` and ``lam3`` over the weighted plate before charging (Fig. lambda1-3).

    Parameters
    ----------
    fields : dict
        Table with columns ``x1, x3`` (reference position in the mid-plane,
        metres, origin at the plate centre) and ``lam1, lam3`` at ``D0 = 0`` (the
        Keplinger plate under the full weight, ``alpha = 1``: 150 g).
    axes : pair of Axes, optional

    Returns
    -------
    pair of matplotlib Axes
    """
    axes = new_axes(axes, n=2, figsize=(8.0, 5.0))
    sel = (fields["step"] == fields["step"].min()) & (fields["kind"] == 1)
    L, W = 0.1, 0.05
    for ax, name, label in zip(axes, ("lam1", "lam3"),
                               (r"$\lambda_1$ (load direction)", r"$\lambda_3$ (width)")):
        x1, x3, v = _mirror(fields["x1"][sel], fields["x3"][sel], fields[name][sel], L, W)
        pts, idx = np.unique(np.c_[np.round(x1, 12), np.round(x3, 12)], axis=0, return_index=True)
        tri = mtri.Triangulation(100 * x3[idx], 100 * x1[idx])   # cm, x1 vertical like the paper
        # colour range from the 5th-99th percentiles: the clamp edges are singular
        lo, hi = np.percentile(v[idx], [5, 99])
        # round level boundaries, so that the colour bar reads 3.04, 3.06, ... not 3.0437
        levels = MaxNLocator(nbins=16).tick_values(lo, hi if hi > lo else lo + 1e-9)
        pc = ax.tricontourf(tri, v[idx], levels=levels, cmap="viridis", extend="both")
        cb = plt.colorbar(pc, ax=ax, label=label, ticks=MaxNLocator(nbins=8))
        cb.ax.tick_params(labelsize=8)
        ax.set_aspect("equal")
        ax.set_xlabel(r"$X_3$ (cm, reference)")
        ax.set_ylabel(r"$X_1$ (cm, reference)")
        ax.set_title(f"{label}, $D_0 = 0$, $\\alpha = 1$ (150 g)", fontsize=10)
    return axes

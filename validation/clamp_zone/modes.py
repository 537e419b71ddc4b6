"""The clamp-zone study's modes at ``D0_b``: the top face's deflection over the whole plate.

:func:`validation.clamp_zone.units.run_unit` writes one ``.npz`` per unit (named by :attr:`~validation.clamp_zone.key.UnitKey.stem`) (``X1``,
``X3`` in mm, ``u2`` the mode's deflection, ``D0_b``; each panel scales it to a largest
``|u2|`` of one);
:func:`clamp_modes_figure` draws a folder of them, one panel per unit (blue and red: the
two signs of the deflection; the clamps are the left and right edges).

``skfem-dielectric clamp-zone modes`` draws the modes of a run's ``--out``, or the
shipped ones.
"""

from __future__ import annotations

import errno
from pathlib import Path

import numpy as np

from ..figures.common import plt
from ..store import read_npz
from .key import UnitKey

__all__ = ["read_clamp_modes", "clamp_modes_figure"]


def read_clamp_modes(folder) -> list[dict]:
    """The modes of a folder, sorted by weight fraction and unknowns (``n1 n2 n3``).

    Parameters
    ----------
    folder : path-like
        Where :func:`validation.clamp_zone.units.run_unit` wrote them.

    Returns
    -------
    list of dict
        ``alpha``, ``mesh``, ``grading``, ``formulation``, ``D0_b`` and the arrays
        ``X1``, ``X3``, ``u2``.

    Raises
    ------
    ValueError
        ``folder`` is not a folder, or holds no mode.
    """
    folder = Path(folder)
    if not folder.is_dir():
        raise ValueError(f"folder must be a folder of modes, got {str(folder)!r}")
    out = []
    for f in sorted(folder.glob("*.npz")):
        try:
            key = UnitKey.parse(f.stem)
        except ValueError:
            continue
        z = read_npz(f)
        missing = [k for k in ("D0_b", "X1", "X3", "u2") if k not in z]
        if missing:
            raise OSError(errno.EINVAL, f"is not a clamp-zone mode (no {', '.join(missing)})",
                          str(f))
        out.append({"key": key, "alpha": key.alpha, "mesh": key.mesh_text,
                    "grading": key.grading, "formulation": key.formulation,
                    "D0_b": float(z["D0_b"]), "X1": z["X1"], "X3": z["X3"], "u2": z["u2"]})
    if not out:
        raise ValueError(f"folder {str(folder)!r} holds no mode (<alpha>_<mesh>_g<grading>_"
                         f"<formulation>.npz)")
    return sorted(out, key=lambda r: (r["alpha"], r["key"].elements, r["formulation"]))


def clamp_modes_figure(modes: list[dict]):
    """One panel per mode: ``u2`` on the top face (``X1`` along, ``X3`` across, mm).

    Parameters
    ----------
    modes : list of dict
        As :func:`read_clamp_modes` returns them.

    Returns
    -------
    matplotlib Figure
    """
    n = len(modes)
    cols = min(n, 3)
    rows = -(-n // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(max(4.2 * cols, 6.5), 1.9 * rows + 0.8),
                             layout="constrained", squeeze=False)
    for ax, m in zip(axes.flat, modes):
        u = m["u2"] / max(np.abs(m["u2"]).max(), 1e-300)
        tc = ax.tricontourf(m["X1"], m["X3"], u, levels=np.linspace(-1, 1, 21),
                            cmap="RdBu_r")
        ax.set_aspect("equal")
        ax.set_title(rf"$\alpha = {m['alpha']:g}$, {m['mesh']} g{m['grading']:g}"
                     + ("" if m["formulation"] == "mixed" else f" ({m['formulation']})")
                     + rf": $D_{{0b}} = {m['D0_b']:.4f}$", fontsize=8)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel(r"$X_1$ (mm)", fontsize=8)
    for ax in axes[:, 0]:
        ax.set_ylabel(r"$X_3$ (mm)", fontsize=8)
    fig.colorbar(tc, ax=axes, shrink=0.8, label=r"$u_2$ / max $|u_2|$ (top face)")
    fig.suptitle("Clamp-zone modes at the buckling load (whole plate, top face)", fontsize=10)
    return fig

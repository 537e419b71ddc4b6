"""The clamp-zone study's modes at ``D0_b``: the top face's deflection over the whole plate.

:func:`validation.clamp_zone.units.run_unit` writes one ``.npz`` per unit (named by :attr:`~validation.data.key.UnitKey.stem`) (``X1``,
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
from ..data.key import UnitKey

__all__ = ["read_clamp_modes", "clamp_modes_figure", "clamp_trace", "row_half_waves"]


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
    OSError
        A mode file without the mode's arrays, or one whose ``key`` is another unit's
        (a renamed file).
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
        if "key" in z and str(z["key"]) != f.stem:
            raise OSError(errno.EINVAL, f"holds the mode of the unit {str(z['key'])}, not "
                                        f"that of its name", str(f))
        out.append({"key": key, "alpha": key.alpha, "mesh": key.mesh_text,
                    "grading": key.grading, "formulation": key.formulation,
                    "D0_b": float(z["D0_b"]), "X1": z["X1"], "X3": z["X3"], "u2": z["u2"]})
    if not out:
        raise ValueError(f"folder {str(folder)!r} holds no mode (<alpha>_<mesh>_g<grading>_"
                         f"<formulation>.npz)")
    return sorted(out, key=lambda r: (r["alpha"], r["key"].elements, r["formulation"]))


def row_half_waves(x1, x3, u2, X1: float) -> tuple[float, np.ndarray, np.ndarray, int]:
    """The row of top-face vertices nearest ``X1`` and its half-waves across the width.

    Parameters
    ----------
    x1, x3, u2 : ndarray
        The top face's vertices and deflection over the whole plate (as
        :func:`~skfem_dielectric.models.plate.modes.top_deflection` gives them).
    X1 : float
        Reference ``X1``; the row of vertices nearest it is used.

    Returns
    -------
    X1 : float
        The row's ``X1``.
    X3, u2 : ndarray
        The row, sorted by ``X3``.
    half_waves : int
        Sign changes of ``u2`` along the row plus one (values below ``1e-6`` of the row's
        largest are skipped as nodes of the wave).
    """
    x1, x3, u2 = (np.asarray(a, float) for a in (x1, x3, u2))
    X1 = float(x1[np.argmin(np.abs(x1 - X1))])
    row = np.abs(x1 - X1) < 1e-9 * np.ptp(x1)
    order = np.argsort(x3[row])
    X3, u = x3[row][order], u2[row][order]
    nz = u[np.abs(u) > 1e-6 * np.abs(u).max()]
    return X1, X3, u, int(np.count_nonzero(np.diff(np.sign(nz)))) + 1


def clamp_trace(mode: dict) -> tuple[float, np.ndarray, np.ndarray, int]:
    """The mode's top-face deflection across the whole width at the clamp zone: the row of
    vertices at the ``X1`` of the largest ``|u2|``.

    Parameters
    ----------
    mode : dict
        As :func:`read_clamp_modes` returns it.

    Returns
    -------
    X1 : float
        The row's ``X1`` (mm).
    X3, u2 : ndarray
        The row, sorted by ``X3``; ``u2`` scaled to a largest ``|u2|`` of 1 on the plate.
    half_waves : int
        :func:`row_half_waves` of that row: the count of the ``half_waves`` column of the
        ``units`` table.
    """
    x1, u2 = np.asarray(mode["X1"], float), np.asarray(mode["u2"], float)
    X1, X3, u, n = row_half_waves(x1, mode["X3"], u2, x1[np.argmax(np.abs(u2))])
    return X1, X3, u / max(np.abs(u2).max(), 1e-300), n


def clamp_modes_figure(modes: list[dict], loads: dict | None = None):
    """One panel per mode: ``u2`` on the top face (``X1`` along, ``X3`` across, mm), and
    below it the trace across the width at the clamp zone (:func:`clamp_trace`) with its
    half-wave count.

    Parameters
    ----------
    modes : list of dict
        As :func:`read_clamp_modes` returns them.
    loads : dict, optional
        ``{alpha: (D0_b, error, meshes)}``: the converged load of each weight (the table's,
        :func:`~validation.data.clamp_zone.clamp_unit_load`), which the panel's title
        gives beside the mesh the mode was computed on; without it the title gives the
        mode's own ``D0_b``.

    Returns
    -------
    matplotlib Figure
    """
    loads = loads or {}
    n = len(modes)
    cols = min(n, 3)
    rows = -(-n // cols)
    fig, axes = plt.subplots(2 * rows, cols, figsize=(max(4.4 * cols, 6.5), 3.0 * rows + 0.8),
                             layout="constrained", squeeze=False,
                             gridspec_kw={"height_ratios": [2.2, 1.0] * rows})
    for i, m in enumerate(modes):
        ax, tr = axes[2 * (i // cols), i % cols], axes[2 * (i // cols) + 1, i % cols]
        u = m["u2"] / max(np.abs(m["u2"]).max(), 1e-300)
        tc = ax.tricontourf(m["X1"], m["X3"], u, levels=np.linspace(-1, 1, 21),
                            cmap="RdBu_r")
        X1, X3, trace, n_half = clamp_trace(m)
        ax.axvline(X1, color="0.35", lw=0.8, ls="-", gid="clamp-trace-row")
        ax.set_aspect("equal")
        form = "" if m["formulation"] == "mixed" else f" ({m['formulation']})"
        ref = loads.get(round(m["alpha"], 9))
        head = (rf"$\alpha = {m['alpha']:g}$: $D_{{0b}} = {ref[0]:.4f} \pm {ref[1]:.4f}$"
                if ref else rf"$\alpha = {m['alpha']:g}$: $D_{{0b}} = {m['D0_b']:.4f}$")
        ax.set_title(head + f"\nmode on {m['mesh']} g{m['grading']:g}{form}"
                     + (rf" (its $D_{{0b}}$ {m['D0_b']:.4f})" if ref else ""), fontsize=8)
        ax.tick_params(labelsize=7)
        ax.set_ylabel(r"$X_3$ (mm)", fontsize=8)
        tr.axhline(0, color="0.6", lw=0.5)
        tr.plot(X3, trace, "-", color="k", lw=0.9, marker=".", ms=2.5, gid="clamp-trace")
        tr.set_xlim(X3.min(), X3.max())
        tr.set_ylim(-1.05, 1.05)
        tr.set_title(f"across the width at $X_1$ = {X1:.1f} mm: {n_half} half-waves",
                     fontsize=8)
        tr.set_xlabel(r"$X_3$ (mm)", fontsize=8)
        tr.set_ylabel(r"$u_2$", fontsize=8)
        tr.tick_params(labelsize=7)
    for j in range(n, rows * cols):
        axes[2 * (j // cols), j % cols].set_visible(False)
        axes[2 * (j // cols) + 1, j % cols].set_visible(False)
    for ax in axes[0::2].flat:
        ax.set_xlabel(r"$X_1$ (mm)", fontsize=8)
    fig.colorbar(tc, ax=axes[0::2], shrink=0.8, label=r"$u_2$ / max $|u_2|$ (top face)")
    fig.suptitle("Clamp-zone modes at the buckling load (whole plate, top face)", fontsize=10)
    return fig

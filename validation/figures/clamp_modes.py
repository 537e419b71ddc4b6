"""The clamp-zone study's modes at ``D0_b``: the top face's deflection over the whole plate.

:func:`validation.studies.clamp_units.run_unit` writes one ``.npz`` per unit (``X1``,
``X3`` in mm, ``u2`` the mode's deflection, ``D0_b``; each panel scales it to a largest
``|u2|`` of one);
:func:`clamp_modes_figure` draws a folder of them, one panel per unit (blue and red: the
two signs of the deflection; the clamps are the left and right edges).

Usage::

    python -m validation.figures.clamp_modes [results/clamp-modes] [--out results]
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

import numpy as np

from .common import plt, save_figure

__all__ = ["read_clamp_modes", "clamp_modes_figure", "main"]

_NAME = re.compile(r"(?P<alpha>[0-9.e+-]+)_(?P<mesh>\d+x\d+x\d+)_g(?P<grading>[0-9.e+-]+)_"
                   r"(?P<formulation>[a-z-]+)$")


def read_clamp_modes(folder) -> list[dict]:
    """The modes of a folder, sorted by weight fraction and unknowns (``n1 n2 n3``).

    Parameters
    ----------
    folder : path-like
        Where :func:`~validation.studies.clamp_units.run_unit` wrote them.

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
        m = _NAME.match(f.stem)
        if m is None:
            continue
        with np.load(f) as z:
            out.append({"alpha": float(m["alpha"]), "mesh": m["mesh"],
                        "grading": float(m["grading"]), "formulation": m["formulation"],
                        "D0_b": float(z["D0_b"]), "X1": z["X1"], "X3": z["X3"],
                        "u2": z["u2"]})
    if not out:
        raise ValueError(f"folder {str(folder)!r} holds no mode (<alpha>_<mesh>_g<grading>_"
                         f"<formulation>.npz)")
    size = lambda r: int(np.prod([int(n) for n in r["mesh"].split("x")]))
    return sorted(out, key=lambda r: (r["alpha"], size(r), r["formulation"]))


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


def main(argv: list[str] | None = None) -> int:
    """Draw ``clamp-modes.png`` (and ``.pdf``) from a folder of modes.

    Parameters
    ----------
    argv : list of str, optional
        The folder (default ``results/clamp-modes``) and ``--out`` (default ``results``).

    Returns
    -------
    int
        0; a folder without modes exits with one line and code 2.
    """
    ap = argparse.ArgumentParser(prog="python -m validation.figures.clamp_modes",
                                 description=__doc__.splitlines()[0])
    ap.add_argument("folder", nargs="?", type=Path, default=Path("results") / "clamp-modes")
    ap.add_argument("--out", type=Path, default=Path("results"))
    a = ap.parse_args(argv)
    try:
        modes = read_clamp_modes(a.folder)
    except ValueError as exc:
        ap.error(str(exc))
    a.out.mkdir(parents=True, exist_ok=True)
    for p in save_figure(clamp_modes_figure(modes), a.out, "clamp-modes"):
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main())

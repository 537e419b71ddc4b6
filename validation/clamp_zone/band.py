"""The clamp edge in section: negative modes against the wavenumber along the clamp.

One panel per 3D state (weight fraction ``alpha``, charge ``D0``) of
the ``section`` table (:mod:`validation.clamp_zone.section`): the number of negative modes of the section next to
the clamp against ``k`` (``2 pi / k`` is the reference wavelength along ``X3``, mm), one line
per section mesh (edge elements ``h0``).  A physical edge instability is a band of ``k``
whose lower edge stays put as ``h0`` is halved; a band that recedes towards the largest
``k`` with each halving follows the mesh, not the plate.  A section whose base state has
inverted elements (``J_min <= 0``) is no state of the plate: its line is drawn grey and
dotted, and its counts decide nothing.  The shaded band is the reach of the 3D mesh
across the width: the wavenumbers it holds with at least
:data:`~validation.data.registry.MIN_ELEMENTS_PER_HALF_WAVE` elements per half-wave.

``skfem-dielectric clamp-zone band`` draws it (``--table``: :func:`band_table`).
"""

from __future__ import annotations

import numpy as np

from ..figures.common import plt
from ..specs import KEPLINGER
from ..data.registry import MIN_ELEMENTS_PER_HALF_WAVE

__all__ = ["band_onsets", "band_table", "mesh_reach", "edge_band_figure"]


def _state(r: dict) -> tuple:
    return (float(r["alpha"]), float(r["D0"]), str(r["mesh"]), float(r["grading"]),
            float(r["grad_div"]), str(r.get("pressure") or "Q1"))


def _grad_div_cell(gd: float, pressure: str) -> str:
    """The grad-div weight, with the section's pressure space where it is not Q1."""
    return f"{gd:g}" if pressure == "Q1" else f"{gd:g} ({pressure})"


def mesh_reach(mesh: str) -> float:
    """The largest ``k`` (1/mm) a 3D eighth-model mesh ``n1xn2xn3`` holds with
    :data:`~validation.data.registry.MIN_ELEMENTS_PER_HALF_WAVE` elements per half-wave
    across the half-width (``n3`` elements over ``W / 2``): ``pi / (m h3)``."""
    h3 = 1e3 * KEPLINGER["width"] / 2 / int(mesh.split("x")[2])
    return float(np.pi / (MIN_ELEMENTS_PER_HALF_WAVE * h3))


def _inverted(r: dict) -> bool:
    return r.get("J_min") not in (None, "") and float(r["J_min"]) <= 0


def _sweeps(rows: list[dict]) -> dict:
    """``{state: {h0: (sorted [(k, n_negative)], inverted)}}`` of the rows."""
    kn, inverted = {}, {}
    for r in rows:
        key = (_state(r), float(r["h0"]))
        kn.setdefault(key, []).append((float(r["k"]), int(r["n_negative"])))
        inverted[key] = inverted.get(key, False) or _inverted(r)
    out: dict = {}
    for (state, h0), pairs in kn.items():
        out.setdefault(state, {})[h0] = (sorted(pairs), inverted[(state, h0)])
    return out


def band_onsets(rows: list[dict]) -> dict:
    """The band's lower edge per state and section mesh.

    Parameters
    ----------
    rows : list of dict
        Rows of the ``section`` table (:func:`~validation.data.registry.load`).

    Returns
    -------
    dict
        ``{(alpha, D0, mesh, grading, grad_div, pressure): {h0: (k_onset, n_at_onset, k_max,
        inverted)}}``: the smallest ``k`` of the sweep with a negative mode (``None`` where
        there is none, with ``n_at_onset = 0``), the count there, the sweep's largest
        ``k``, and whether the section's base state has inverted elements (``J_min <= 0``,
        a row without ``J_min``: not inverted).
    """
    res: dict = {}
    for state, by_h in _sweeps(rows).items():
        res[state] = {}
        for h0, (kn, inverted) in by_h.items():
            neg = [(k, n) for k, n in kn if n > 0]
            k0, n0 = neg[0] if neg else (None, 0)
            res[state][h0] = (k0, n0, kn[-1][0], inverted)
    return res


def band_table(rows: list[dict]) -> str:
    """The band's lower edge as a Markdown table, a row per state (the docs show it
    verbatim): per section mesh ``h0`` (coarse to fine) the smallest ``k`` with a negative
    mode (``none`` up to the sweep's end, ``inverted`` where the base state has inverted
    elements), and the largest ``k`` the 3D mesh holds (:func:`mesh_reach`).

    Parameters
    ----------
    rows : list of dict
        Rows of the ``section`` table (:func:`~validation.data.registry.load`).

    Returns
    -------
    str
    """
    lines = ["| alpha | `D0` | 3D mesh | grad-div | `h0` (mm) | first `k` with a negative "
             "mode (1/mm) | `k` held by the 3D mesh |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for state, by_h in sorted(band_onsets(rows).items()):
        alpha, D0, mesh, grading, gd, pressure = state
        h0s = sorted(by_h, reverse=True)
        cells = []
        for h0 in h0s:
            k0, _, _, inverted = by_h[h0]
            cells.append("inverted" if inverted else "none" if k0 is None else f"{k0:.4g}")
        lines.append(f"| {alpha:g} | {D0:g} | {mesh} g{grading:g} | "
                     f"{_grad_div_cell(gd, pressure)} | "
                     f"{' / '.join(f'{h:g}' for h in h0s)} | {' / '.join(cells)} | "
                     f"{mesh_reach(mesh):.2f} |")
    return "\n".join(lines) + "\n"


def edge_band_figure(rows: list[dict]):
    """One panel per state: negative modes against ``k``, a line per ``h0``.

    Parameters
    ----------
    rows : list of dict
        Rows of the ``section`` table (:func:`~validation.data.registry.load`).

    Returns
    -------
    matplotlib Figure

    Raises
    ------
    ValueError
        No rows.
    """
    if not rows:
        raise ValueError("rows must hold at least one row of the section table, got none")
    sweeps = _sweeps(rows)
    states = sorted(sweeps)
    cols = min(len(states), 2)
    nrow = -(-len(states) // cols)
    fig, axes = plt.subplots(nrow, cols, figsize=(4.6 * cols, 2.6 * nrow + 0.6),
                             layout="constrained", squeeze=False, sharex=True)
    styles = ["-o", "--s", ":^", "-.v"]
    for ax, state in zip(axes.flat, states):
        by_h = sweeps[state]
        for i, h0 in enumerate(sorted(by_h, reverse=True)):
            kn, inverted = by_h[h0]
            k, n = np.array(kn).T
            if inverted:
                ax.plot(k, n, ":", color="0.6", lw=1.0,
                        label=rf"$h_0$ = {h0:g} mm: base inverted ($J_{{min}} \leq 0$)")
            else:
                ax.plot(k, n, styles[i % len(styles)], ms=3.5, lw=1.1,
                        label=rf"$h_0$ = {h0:g} mm")
        alpha, D0, mesh, grading, gd, pressure = state
        k_min = min(kn[0][0] for kn, _ in by_h.values())
        ax.axvspan(k_min, mesh_reach(mesh), color="0.9", zorder=0,
                   label=f"held by the 3D mesh {mesh}")
        ax.set_xscale("log")
        ax.set_title(rf"$\alpha = {alpha:g}$, $D_0 = {D0:g}$ (3D {mesh} g{grading:g}, "
                     rf"grad-div {gd:g}$\mu$"
                     + ("" if pressure == "Q1" else f", section pressure {pressure}") + ")",
                     fontsize=9)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=7, loc="upper left")
        ax.set_ylim(bottom=-0.3)
    for ax in list(axes.flat)[len(states):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel(r"$k$ (1/mm): wave $\cos kX_3$ along the clamp", fontsize=8)
    for ax in axes[:, 0]:
        ax.set_ylabel("negative modes of the section", fontsize=8)
    fig.suptitle("Clamp edge in section: negative modes against the wavenumber, "
                 "three section meshes", fontsize=10)
    return fig

"""The drawing shared by every figure: FE markers and model names, the FE rows and dots of a
tidy table, the sampled analytic loading curves, the caption line, panel tags and
:func:`save_figure`.

Every plotting function takes ``ax=None`` (or ``axes=None`` for two panels),
draws and returns the axes; nothing here shows or saves a figure except
:func:`save_figure`, which writes into a given folder (pyplot chooses its backend
at the first figure, so importing this module sets none).
FE data are the tidy tables of :func:`validation.table.read_table` (``None``
draws the analytic curves alone).

The names of the FE models in legends and caption lines (:data:`MODEL_NAME`), the
markers of the breakdown and stability results (:mod:`validation.markers`, whose names
:data:`BREAKDOWN_NAME`, :data:`BUCKLING_NAME`, :data:`NEWTON_NAME`, :data:`LIMIT_NAME` repeat)
and the caption line itself (:func:`run_caption`, :func:`add_caption`) are shared by
every figure of ``skfem-dielectric validate``, also those of ``voltage-control`` and
``wrinkling-fe``, so that one set of names stands in the figures and the docs.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D

import analytic as an

from ..markers import LIMIT_POINT, P33_BREAKDOWN, P33_SHAPES, THICK_PLATE_LIMIT, line_style

__all__ = [
    "PAPER_FIGURE", "MODEL_NAME", "BREAKDOWN_NAME", "BUCKLING_NAME", "NEWTON_NAME", "LIMIT_NAME",
    "VARIANT_MARKER", "BREAKDOWN_MARKER", "new_axes", "colors", "fe_rows", "fe_dots", "fe_E0", "loading_fe_dots",
    "variant_legend", "wrinkling_zone_outline", "wrinkling_zone", "finish_loading_axes", "refine_start", "equibiaxial_curve", "uniaxial_curve", "plate_mesh_text",
    "mesh_caption", "mesh_text", "run_caption", "add_caption", "shared_legend", "tag_panels",
    "save_figure",
]

#: The paper's figure numbers, in the order the paper shows them.
PAPER_FIGURE = {"nh-d-e": 1, "gent-d-e": 2, "gent-equi-biaxial": 3, "figde": 4,
                "uni-axial-ideal": 5, "lambda1-3": 6, "zs22": 7}

# Concentric markers of decreasing size, so that models on the same point stay visible:
# a large circle (3D coupled) holds a square (3D Maxwell), a triangle (membrane) and a
# small filled diamond (membrane, Maxwell).
VARIANT_MARKER = {"coupled": dict(marker="o", mfc="none", ms=12, mew=1.3),
                   "maxwell": dict(marker="s", mfc="none", ms=7.5, mew=1.2),
                   "membrane": dict(marker="^", mfc="none", ms=5.5, mew=1.1),
                   "membrane-maxwell": dict(marker="D", ms=3.4, mew=0.6)}
#: the shape of each FE model's ``P33 breakdown`` marker (:data:`validation.markers.P33_SHAPES`)
BREAKDOWN_MARKER = P33_SHAPES

#: The names of the FE models in every legend and caption line (docs/gallery.md and
#: docs/cli.md use the same): the keys are the ``variant`` values of the CSVs, plus
#: ``"section"``, the cross-section of ``wrinkling-fe``.  No name holds a comma, so that
#: a caption can list several.
MODEL_NAME = {"coupled": "3D fully coupled", "maxwell": "3D Maxwell traction",
              "membrane": "2D membrane", "membrane-maxwell": "2D membrane (local-field Maxwell)",
              "section": "2D cross-section"}
#: Legend name of the red open marker: the paper's criterion, the first step with
#: compressive ``P33`` near the clamps (:data:`validation.markers.P33_BREAKDOWN`).
BREAKDOWN_NAME = P33_BREAKDOWN.name
#: The quantity ``D0_b``, the zero crossing of the lowest physical eigenvalue of the whole
#: plate; each legend name of its markers starts with it
#: (:data:`validation.markers.RUN_BUCKLING`, ``CONVERGED_BUCKLING``, ``MESH_BUCKLING``).
BUCKLING_NAME = "buckling load"
#: The first charge target a Newton ramp cannot reach; each legend name of its markers starts
#: with it (:data:`validation.markers.NEWTON_LIMIT`, ``RUN_NEWTON``).
NEWTON_NAME = "Newton limit"
#: Legend name of the star of ``voltage-control`` (:data:`validation.markers.LIMIT_POINT`).
LIMIT_NAME = LIMIT_POINT.name


def new_axes(ax, n=1, figsize=None):
    """``ax`` if given, else ``n`` new axes side by side (5 x 4 inches each by default)."""
    if ax is not None:
        return ax
    fig, axes = plt.subplots(1, n, figsize=figsize or (5.0 * n, 4.0), layout="constrained")
    return axes


def colors(n, values=None, palette=None):
    """``n`` viridis colours; with ``palette``, the colour of each value of ``values``
    within the palette (so that one ``s`` has one colour in every panel)."""
    cmap = plt.get_cmap("viridis")
    if palette is None:
        return [cmap(x) for x in np.linspace(0.0, 0.85, n)]
    full = dict(zip(palette, colors(len(palette))))
    return [full[v] for v in values]


def fe_rows(fe, **match):
    """Boolean mask of FE rows matching the given column values (converged rows only)."""
    if fe is None or not len(fe.get("run", [])):
        return None
    mask = np.array([bool(c) for c in fe["converged"]])
    for k, v in match.items():
        col = fe[k]
        mask &= np.isclose(col, v) if col.dtype.kind == "f" else (col == v)
    return mask


def fe_dots(ax, fe, x, y, mask, variant, color, label=None):
    """FE dots ``(x, y)`` of the rows in ``mask`` with the marker of ``variant``
    (:data:`VARIANT_MARKER`); nothing if no row is selected."""
    if mask is None or not mask.any():
        return
    # not clipped: a dot on the frame (D0 = 0, or the top of the range) stays whole
    ax.plot(x[mask], y[mask], ls="none", color=color, label=label, clip_on=False, zorder=3,
            **VARIANT_MARKER[variant])


def fe_E0(fe):
    """FE ``E0 = D0/(lam1 lam3)^2`` of an ideal dielectric from the centre stretches."""
    return fe["D0"] / (fe["lam1_fe"] * fe["lam3_fe"]) ** 2


def loading_fe_dots(ax, fe, *, s, model, quantity, color):
    """The FE dots of one loading curve: ``(lam1_fe, D0)`` or ``(lam1_fe, E0_fe)`` of the
    converged rows with this ``s`` and ``model``, one marker per variant."""
    mask = fe_rows(fe, s=s, model=model)
    if mask is None:
        return
    y = fe["D0"] if quantity == "D0" else fe_E0(fe)
    for v in VARIANT_MARKER:
        fe_dots(ax, fe, fe["lam1_fe"], y, mask & (fe["variant"] == v), v, color)


def variant_legend(ax, fe):
    """Legend entries for the FE marker styles actually drawn."""
    if fe is None or not len(fe.get("run", [])):
        return []
    return [Line2D([], [], ls="none", color="k", label=MODEL_NAME[v], **VARIANT_MARKER[v])
            for v in VARIANT_MARKER if v in set(fe["variant"])]


def wrinkling_zone_outline(lk, thick, ln, thin, D0max):
    """The outline ``(xs, ys)`` of the wrinkling zone between the thick-plate limit
    ``(lk, thick)`` and the thin-plate limit ``(ln, thin)`` up to ``D0max`` (paper Figs.
    gent-equi-biaxial and uni-axial-ideal); ``None`` if either limit has no point there."""
    ok_k = np.isfinite(thick) & (thick <= D0max)
    ok_n = np.isfinite(thin) & (thin <= D0max)
    if not (ok_k.any() and ok_n.any()):
        return None
    return (np.concatenate([lk[ok_k], ln[ok_n][::-1]]),
            np.concatenate([thick[ok_k], thin[ok_n][::-1]]))


def wrinkling_zone(ax, lk, thick, ln, thin, D0max):
    """Shade the wrinkling zone (:func:`wrinkling_zone_outline`) and draw the thick-plate
    limit (paper Figs. gent-equi-biaxial and uni-axial-ideal)."""
    zone = wrinkling_zone_outline(lk, thick, ln, thin, D0max)
    if zone is not None:
        ax.fill(*zone, color="0.85", zorder=0, label="wrinkling zone")
    ax.plot(lk, thick, label="thick-plate limit", **line_style(THICK_PLATE_LIMIT))


def finish_loading_axes(ax, fe, quantity, xlabel, xlim, title):
    """Labels, limits (``D0`` up to 8, ``E0`` up to 0.8), the legend with the FE markers
    drawn (:func:`variant_legend`) and the title of a loading-curve panel."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"$D_0$" if quantity == "D0" else r"$E_0$")
    ax.set_xlim(*xlim)
    ax.set_ylim(0, 8.0 if quantity == "D0" else 0.8)
    handles, _ = ax.get_legend_handles_labels()
    ax.legend(handles=handles + variant_legend(ax, fe), fontsize=8,
              loc="lower right" if quantity == "D0" else "upper right")
    ax.set_title(title, fontsize=10)


def refine_start(x, f, n=80):
    """``(x, f(x))`` with extra points where a curve starts with a vertical tangent.

    Curves such as ``D0 = sqrt(lam^6 - 1)`` rise like a square root from their
    first real point; on a uniform grid they would seem to start above ``D0 = 0``.
    Points are added geometrically between the last ``nan`` and the first finite
    sample.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(f(x), dtype=float)
    ok = np.isfinite(y)
    if ok.any() and not ok[0]:
        i = int(np.argmax(ok))
        lo, hi = x[i - 1], x[i]
        for _ in range(60):                    # where the curve starts: bisect on finiteness
            mid = 0.5 * (lo + hi)
            if np.isfinite(np.asarray(f(np.array([mid])), dtype=float)[0]):
                hi = mid
            else:
                lo = mid
        xs = hi + (x[i] - hi) * np.r_[0.0, np.geomspace(1e-10, 1.0, n)]
        ys = np.asarray(f(xs), dtype=float)
        x, y = np.r_[x[:i], xs, x[i + 1:]], np.r_[y[:i], ys, y[i + 1:]]
    return x, y


def equibiaxial_curve(s, m, lam_max, n=1500):
    """``(lam, D0)`` of Eq. (loading_gent), sampled in ``D0`` (smooth from ``D0 = 0``)."""
    D0max = float(an.equibiaxial_D0(lam_max, s, m))
    if not np.isfinite(D0max):
        return np.empty(0), np.empty(0)
    D0 = D0max * np.linspace(0.0, 1.0, n) ** 2          # dense near D0 = 0, where E0 ~ D0
    return np.asarray(an.equibiaxial_lam(D0, s, m), dtype=float), D0


def uniaxial_curve(s, m, lam1_max, n=1500):
    """``(lam1, D0, E0)`` of Eq. (DEuniax), sampled in ``D0``."""
    D0max = float(an.uniaxial_D0(lam1_max, s, m))
    if not np.isfinite(D0max):
        return np.empty(0), np.empty(0), np.empty(0)
    D0 = D0max * np.linspace(0.0, 1.0, n) ** 2          # dense near D0 = 0, where E0 ~ D0
    lam1 = np.asarray(an.uniaxial_lam1(D0, s, m), dtype=float)
    return lam1, D0, np.asarray(an.uniaxial_E0(lam1, s, m), dtype=float)



def plate_mesh_text(variant: str, mesh: dict) -> str:
    """The mesh of a plate model in words, such as ``"10 x 1 x 5 elements (eighth of the
    plate)"``.

    Parameters
    ----------
    variant : str
        FE variant (``"membrane..."``: the quarter of the mid-plane, else the 3D eighth).
    mesh : dict
        Elements ``{"n1": ., "n2": ., "n3": .}`` of the symmetric model.

    Returns
    -------
    str
    """
    if (mesh.get("n1"), mesh.get("n2"), mesh.get("n3")) == (1, 1, 1):
        return "1 element (homogeneous state)"
    if variant.startswith("membrane"):
        return f"{mesh['n1']} x {mesh['n3']} elements (quarter plate)"
    return f"{mesh['n1']} x {mesh['n2']} x {mesh['n3']} elements (eighth of the plate)"


def mesh_caption(items) -> str:
    """The meshes part of a caption line from ``(model name, mesh text)`` pairs.

    Models on the same mesh are listed together, several meshes of the same models are
    joined by "and": ``"3D fully coupled, 3D Maxwell traction: 10 x 1 x 5 elements
    (eighth of the plate); 2D membrane: 20 x 10 elements (quarter plate)"``.

    Parameters
    ----------
    items : iterable of (str, str)

    Returns
    -------
    str
    """
    by_mesh: dict[str, list[str]] = {}
    for model, text in items:
        names = by_mesh.setdefault(text, [])
        if model not in names:
            names.append(model)
    by_models: dict[tuple, list[str]] = {}
    for text, names in by_mesh.items():
        by_models.setdefault(tuple(names), []).append(text)
    return "; ".join(f"{', '.join(names)}: {' and '.join(texts)}"
                     for names, texts in by_models.items())


def mesh_text(specs) -> str:
    """The meshes of the runs ``specs`` for a caption line, one entry per FE variant."""
    return mesh_caption((MODEL_NAME[r.variant], plate_mesh_text(r.variant, r.mesh_dict))
                        for r in specs)


def run_caption(head: str, quick: bool | None, meshes: str) -> str:
    """One caption line: what the figure compares with, quick or full run, the meshes.

    The line reads ``"<head>. Quick run; meshes: <meshes>."``.

    Parameters
    ----------
    head : str
        What the figure compares with, e.g. ``"Paper Fig. 5 (uni-axial-ideal)"``.
    quick : bool or None
        ``True``: quick run, ``False``: full run, ``None``: not known ("FE run").
    meshes : str
        The FE models and their meshes (:func:`mesh_caption`); empty: "unknown".

    Returns
    -------
    str
    """
    run = {True: "Quick run", False: "Full run", None: "FE run"}[quick]
    return f"{head}. {run}; meshes: {meshes or 'unknown'}."


def add_caption(fig, text: str):
    """Put the caption line ``text`` under the figure (small, grey), as every figure of
    ``skfem-dielectric validate`` has it.

    Returns
    -------
    matplotlib Text
    """
    return fig.supxlabel(text, fontsize=8, color="0.25")



def shared_legend(fig, axes):
    """Replace the panels' legends by one legend beside the figure (entries of all
    panels, each once)."""
    handles, labels = [], []
    for ax in axes:
        leg = ax.get_legend()
        for h, txt in zip(leg.legend_handles, leg.get_texts()):
            if txt.get_text() not in labels:
                handles.append(h)
                labels.append(txt.get_text())
        leg.remove()
    fig.legend(handles, labels, loc="outside right center", fontsize=8)


def tag_panels(axes):
    """``(a)``, ``(b)``, ... in front of the panel titles, off the data."""
    for ax, t in zip(axes, "abcdef"):
        ax.set_title(f"({t}) " + ax.get_title(), fontsize=10)


def save_figure(fig, folder, stem: str, dpi: int = 130, bbox_inches=None) -> list[Path]:
    """Write ``fig`` as ``folder/stem.png`` and ``.pdf`` (no timestamps) and close it.

    Parameters
    ----------
    fig : matplotlib Figure
    folder : path-like
    stem : str
        File name without suffix.
    dpi : int, optional
        Resolution of the PNG.
    bbox_inches : str, optional
        ``"tight"`` crops both files to what is drawn (figures without a layout engine).

    Returns
    -------
    list of Path
        The PNG and the PDF.
    """
    folder = Path(folder)
    paths = [folder / f"{stem}.png", folder / f"{stem}.pdf"]
    fig.savefig(paths[0], dpi=dpi, bbox_inches=bbox_inches, metadata={"Software": None})
    # the layout the PNG's draw computed (constrained layout: fractions of the figure,
    # text in points) serves the PDF as it is, instead of being solved a second time
    if fig.get_layout_engine() is not None:
        fig.set_layout_engine("none")
    fig.savefig(paths[1], bbox_inches=bbox_inches,
                metadata={"CreationDate": None, "Creator": None, "Producer": None})
    plt.close(fig)
    return paths

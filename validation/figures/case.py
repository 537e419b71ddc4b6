"""The figure of each validation case: the paper figure's panels (one module per figure
beside this one) and its caption line (paper figure, quick or full run, the FE meshes)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ..cases import get_case
from .common import (PAPER_FIGURE, VARIANT_MARKER, add_caption, mesh_text, run_caption,
                     shared_legend, tag_panels)
from .equibiaxial_loading import plot_equibiaxial_loading
from .equibiaxial_wrinkling import plot_equibiaxial_wrinkling
from .p33_profiles import plot_p33_profiles
from .stretch_maps import plot_stretch_maps
from .uniaxial_loading import plot_uniaxial_loading
from .uniaxial_wrinkling import plot_uniaxial_wrinkling

__all__ = ["figure_caption", "case_figure"]


def _run_setting(name, fe, fields):
    """``(quick, specs)``: which run setting produced the table (``None`` if unknown).

    A table belongs to the quick setting when each run and ``D0`` value is one of its
    targets (the full setting refines the quick steps); when both settings have the
    same targets (``lambda1-3``), the 3D centre line, ``2 n1 + 1`` points, decides.
    """
    if fe is None or not len(fe.get("run", [])):
        return None, ()
    case = get_case(name)
    fits = []
    for quick in (True, False):
        specs = {r.key: r for r in case.runs(quick)}
        if all(str(k) in specs and np.any(np.isclose(d, specs[str(k)].D0))
               for k, d in zip(fe["run"], fe["D0"])):
            fits.append(quick)
    if len(fits) > 1 and fields is not None and len(fields.get("run", [])):
        run = str(fields["run"][0])
        sel = (fields["run"] == run) & (fields["kind"] == 0) & (fields["step"] == fields["step"].min())
        npts = len(np.unique(fields["x1"][sel]))
        fits = [q for q in fits
                if 2 * {r.key: r for r in case.runs(q)}[run].mesh_dict["n1"] + 1 == npts] or fits
    if not fits:
        return None, ()
    keys = set(map(str, fe["run"]))
    return fits[0], tuple(r for r in case.runs(fits[0]) if r.key in keys)


def figure_caption(name: str, fe=None, fields=None) -> str:
    """One caption line: the paper's figure number, quick/full run and the FE meshes.

    Parameters
    ----------
    name : str
        Case name.
    fe, fields : dict, optional
        The case's tables (as for :func:`case_figure`).

    Returns
    -------
    str
    """
    case = get_case(name)
    head = f"Paper Fig. {PAPER_FIGURE[name]} ({case.figure.removeprefix('fig:')})"
    quick, specs = _run_setting(name, fe, fields)
    if fe is None or not len(fe.get("run", [])):
        if fields is None:
            return f"{head}. Analytic curves only (no FE run)."
        return f"{head}. FE fields."
    return run_caption(head, quick, mesh_text(specs))


def case_figure(name: str, fe=None, fields=None):
    """The figure of case ``name`` (analytic curves, plus FE data if given).

    Every figure carries a caption line (:func:`figure_caption`).

    Returns
    -------
    matplotlib Figure
    """
    fig = _case_figure(name, fe, fields)
    add_caption(fig, figure_caption(name, fe, fields))
    return fig


def _case_figure(name, fe, fields):
    if name in ("nh-d-e", "gent-d-e"):
        model, s_values = ("neo-Hookean", (0, 1, 2, 3)) if name == "nh-d-e" \
            else ("Gent", (0, 1, 2.3, 3))
        fig, axes = plt.subplots(1, 2, figsize=(12.5, 4.6), layout="constrained")
        plot_equibiaxial_loading(model, s_values, "D0", fe=fe, ax=axes[0])
        plot_equibiaxial_loading(model, s_values, "E0", fe=fe, ax=axes[1])
        shared_legend(fig, axes)
        tag_panels(axes)
        return fig
    if name == "gent-equi-biaxial":
        fig, axes = plt.subplots(1, 2, figsize=(13, 5.0), layout="constrained", sharey=True)
        for ax, model in zip(axes, ("neo-Hookean", "Gent")):
            plot_equibiaxial_wrinkling(model, fe=fe, ax=ax)
        shared_legend(fig, axes)             # clear of the s = 4.5 curve
        tag_panels(axes)
        return fig
    if name == "figde":
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), layout="constrained")
        palette = (0, 1, 2, 3, 4)
        plot_uniaxial_loading("neo-Hookean", palette, "D0", fe=fe, ax=axes[0])
        plot_uniaxial_loading("neo-Hookean", (0, 1, 2, 3), "E0", fe=fe, ax=axes[1],
                              palette=palette)
        for txt in axes[0].get_legend().get_texts():     # the paper's (b): s = 0 ... 3
            if txt.get_text() == "$s = 4$":
                txt.set_text("$s = 4$ ((a) only, as in the paper)")
        shared_legend(fig, axes)             # (a)'s legend covered the s = 3, 4 curves
        tag_panels(axes)
        return fig
    if name == "uni-axial-ideal":
        fig, ax = plt.subplots(figsize=(10, 5.4), layout="constrained")
        plot_uniaxial_wrinkling(fe=fe, ax=ax)
        return fig
    if name == "lambda1-3":
        if fields is None:
            raise ValueError("case 'lambda1-3' needs FE fields (run validate)")
        fig, axes = plt.subplots(1, 2, figsize=(9, 5.8), layout="constrained")
        plot_stretch_maps(fields, axes=axes)
        tag_panels(axes)
        return fig
    if name == "zs22":
        if fields is None:
            raise ValueError("case 'zs22' needs FE fields (run validate)")
        variants = [v for v in VARIANT_MARKER if any(f"_{v}_" in r for r in set(fields["run"]))]
        fig, axes = plt.subplots(1, len(variants), figsize=(5.6 * len(variants), 4.8),
                                 layout="constrained", squeeze=False, sharey=True)
        axes = axes.ravel()
        for ax, v in zip(axes, variants):
            plot_p33_profiles(fields, fe=fe, ax=ax, variant=v)
        lo = min(ax.get_ylim()[0] for ax in axes)
        hi = max(ax.get_ylim()[1] for ax in axes)
        for ax in axes:                       # one P33 scale for every model
            ax.set_ylim(lo, hi)
        tag_panels(axes)
        return fig
    raise ValueError(f"no figure for case {name!r}")

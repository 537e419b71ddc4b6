"""The paper's figures: analytic curves from :mod:`analytic` with the FE dots on top.

Every plotting function takes ``ax=None`` (or ``axes=None`` for two panels),
draws and returns the axes; nothing here shows or saves a figure except
:func:`save_figure`, which writes into a given folder (pyplot chooses its backend
at the first figure, so importing this module sets none).
FE data are the tidy tables of :func:`validation.sweep.read_table` (``None``
draws the analytic curves alone).

The names of the FE models and markers in legends and caption lines
(:data:`MODEL_NAME`, :data:`BREAKDOWN_NAME`, :data:`BUCKLING_NAME`, :data:`LIMIT_NAME`)
and the caption line itself (:func:`run_caption`, :func:`add_caption`) are shared by
every figure of ``skfem-dielectric validate``, also those of ``voltage-control`` and
``wrinkling-fe``, so that one set of names stands in the figures and the docs.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import matplotlib.tri as mtri
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.ticker import MaxNLocator

import analytic as an

from .cases import ALPHAS, analytic_model, get_case
from .fe import keplinger_s
from .records import buckling_crossing

__all__ = [
    "plot_equibiaxial_loading",
    "plot_equibiaxial_wrinkling",
    "plot_uniaxial_loading",
    "plot_uniaxial_wrinkling",
    "plot_stretch_maps",
    "plot_p33_profiles",
    "uniaxial_thick_limit_curve",
    "uniaxial_voltage_locus",
    "case_figure",
    "figure_caption",
    "run_caption",
    "mesh_caption",
    "plate_mesh_text",
    "add_caption",
    "tag_panels",
    "save_figure",
    "MODEL_NAME",
    "BREAKDOWN_NAME",
    "BUCKLING_NAME",
    "LIMIT_NAME",
]

#: The paper's figure numbers, in the order the paper shows them.
PAPER_FIGURE = {"nh-d-e": 1, "gent-d-e": 2, "gent-equi-biaxial": 3, "figde": 4,
                "uni-axial-ideal": 5, "lambda1-3": 6, "zs22": 7}

# Concentric markers of decreasing size, so that models on the same point stay visible:
# a large circle (3D coupled) holds a square (3D Maxwell), a triangle (membrane) and a
# small filled diamond (membrane, Maxwell).
_VARIANT_MARKER = {"coupled": dict(marker="o", mfc="none", ms=12, mew=1.3),
                   "maxwell": dict(marker="s", mfc="none", ms=7.5, mew=1.2),
                   "membrane": dict(marker="^", mfc="none", ms=5.5, mew=1.1),
                   "membrane-maxwell": dict(marker="D", ms=3.4, mew=0.6)}
_BREAKDOWN_MARKER = {"coupled": dict(marker="o", ms=19), "maxwell": dict(marker="s", ms=14),
                     "membrane": dict(marker="^", ms=12)}

#: The names of the FE models in every legend and caption line (docs/gallery.md and
#: docs/cli.md use the same): the keys are the ``variant`` values of the CSVs, plus
#: ``"section"``, the cross-section of ``wrinkling-fe``.  No name holds a comma, so that
#: a caption can list several.
MODEL_NAME = {"coupled": "3D fully coupled", "maxwell": "3D Maxwell traction",
              "membrane": "2D membrane", "membrane-maxwell": "2D membrane (local-field Maxwell)",
              "section": "2D cross-section"}
#: Legend name of the red open marker: the first step with compressive ``P33`` near the
#: clamps (``P33/mu < -0.01``) or that the solver could not reach.
BREAKDOWN_NAME = "P33 breakdown"
#: Legend name of the red cross: the zero crossing of the lowest physical eigenvalue of
#: the whole plate, ``D0_b``.
BUCKLING_NAME = "buckling load"
#: Legend name of the star of ``voltage-control``: the maximum of ``E0`` on a path.
LIMIT_NAME = "limit point (snap-through)"


def _new_axes(ax, n=1, figsize=None):
    if ax is not None:
        return ax
    fig, axes = plt.subplots(1, n, figsize=figsize or (5.0 * n, 4.0), layout="constrained")
    return axes


def _colors(n, values=None, palette=None):
    """``n`` viridis colours; with ``palette``, the colour of each value of ``values``
    within the palette (so that one ``s`` has one colour in every panel)."""
    cmap = plt.get_cmap("viridis")
    if palette is None:
        return [cmap(x) for x in np.linspace(0.0, 0.85, n)]
    full = dict(zip(palette, _colors(len(palette))))
    return [full[v] for v in values]


def _fe_rows(fe, **match):
    """Boolean mask of FE rows matching the given column values (converged rows only)."""
    if fe is None or not len(fe.get("run", [])):
        return None
    mask = np.array([bool(c) for c in fe["converged"]])
    for k, v in match.items():
        col = fe[k]
        mask &= np.isclose(col, v) if col.dtype.kind == "f" else (col == v)
    return mask


def _fe_dots(ax, fe, x, y, mask, variant, color, label=None):
    if mask is None or not mask.any():
        return
    # not clipped: a dot on the frame (D0 = 0, or the top of the range) stays whole
    ax.plot(x[mask], y[mask], ls="none", color=color, label=label, clip_on=False, zorder=3,
            **_VARIANT_MARKER[variant])


def _fe_E0(fe):
    """FE ``E0 = D0/(lam1 lam3)^2`` of an ideal dielectric from the centre stretches."""
    return fe["D0"] / (fe["lam1_fe"] * fe["lam3_fe"]) ** 2


def _variant_legend(ax, fe):
    """Legend entries for the FE marker styles actually drawn."""
    if fe is None or not len(fe.get("run", [])):
        return []
    return [Line2D([], [], ls="none", color="k", label=MODEL_NAME[v], **_VARIANT_MARKER[v])
            for v in _VARIANT_MARKER if v in set(fe["variant"])]


def _refine_start(x, f, n=80):
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


def _equibiaxial_curve(s, m, lam_max, n=1500):
    """``(lam, D0)`` of Eq. (loading_gent), sampled in ``D0`` (smooth from ``D0 = 0``)."""
    D0max = float(an.equibiaxial_D0(lam_max, s, m))
    if not np.isfinite(D0max):
        return np.empty(0), np.empty(0)
    D0 = D0max * np.linspace(0.0, 1.0, n) ** 2          # dense near D0 = 0, where E0 ~ D0
    return np.asarray(an.equibiaxial_lam(D0, s, m), dtype=float), D0


def _uniaxial_curve(s, m, lam1_max, n=1500):
    """``(lam1, D0, E0)`` of Eq. (DEuniax), sampled in ``D0``."""
    D0max = float(an.uniaxial_D0(lam1_max, s, m))
    if not np.isfinite(D0max):
        return np.empty(0), np.empty(0), np.empty(0)
    D0 = D0max * np.linspace(0.0, 1.0, n) ** 2          # dense near D0 = 0, where E0 ~ D0
    lam1 = np.asarray(an.uniaxial_lam1(D0, s, m), dtype=float)
    return lam1, D0, np.asarray(an.uniaxial_E0(lam1, s, m), dtype=float)


# --------------------------------------------------------------------------- equi-biaxial
def plot_equibiaxial_loading(model="neo-Hookean", s_values=(0, 1, 2, 3), quantity="D0",
                             fe=None, ax=None, lam_max=5.0, locus=True):
    """Equi-biaxial loading curves ``D0(lam)`` or ``E0(lam)`` at fixed ``s``.

    Paper Figs. nh-d-e and gent-d-e: Eq. (loading_gent) and ``E0 = lam^-4 D0``,
    with the dashed voltage-control limit locus ``det H* = 0`` (through the
    maxima of ``E0``; for neo-Hookean ``D0 = sqrt((lam^6 + 5)/3)``) and the
    maxima of ``E0`` from :func:`analytic.max_E0` marked.

    Parameters
    ----------
    model : {"neo-Hookean", "Gent"}
    s_values : sequence of float
    quantity : {"D0", "E0"}
    fe : dict, optional
        FE table; dots at ``(lam1_fe, D0)`` or ``(lam1_fe, E0_fe)`` with
        ``E0_fe = D0/(lam1_fe lam3_fe)^2``.
    ax : matplotlib Axes, optional
    lam_max : float
        Right end of the stretch axis (starts at 1).
    locus : bool
        Draw the voltage-control limit locus.

    Returns
    -------
    matplotlib Axes
    """
    if quantity not in ("D0", "E0"):
        raise ValueError(f"quantity must be 'D0' or 'E0', got {quantity!r}")
    ax = _new_axes(ax)
    m = analytic_model(model)
    for s, c in zip(s_values, _colors(len(s_values))):
        lam, D0 = _equibiaxial_curve(s, m, lam_max)
        ax.plot(lam, D0 if quantity == "D0" else D0 / lam**4, color=c, label=f"$s = {s:g}$")
        mask = _fe_rows(fe, s=s, model=model)
        if mask is not None:
            yfe = fe["D0"] if quantity == "D0" else _fe_E0(fe)
            for v in _VARIANT_MARKER:
                _fe_dots(ax, fe, fe["lam1_fe"], yfe, mask & (fe["variant"] == v), v, c)
    if locus:
        lam = np.linspace(1.0, lam_max, 800)
        D0l = np.asarray(an.voltage_limit_D0(lam, m), dtype=float)
        ax.plot(lam, D0l if quantity == "D0" else D0l / lam**4, "k--", lw=1.2,
                label=r"$\det\mathcal{H}^* = 0$ (voltage control limit)")
        lm, E0m = (np.atleast_1d(np.asarray(a, dtype=float))
                   for a in an.max_E0(np.asarray(s_values, dtype=float), m, loading="equibiaxial"))
        ok = np.isfinite(lm)
        ax.plot(lm[ok], (lm**4 * E0m)[ok] if quantity == "D0" else E0m[ok], "k^", ms=5,
                label=r"max of $E_0$ at fixed $s$")
    ax.set_xlabel(r"$\lambda$")
    ax.set_ylabel(r"$D_0$" if quantity == "D0" else r"$E_0$")
    ax.set_xlim(1.0, lam_max)
    ax.set_ylim(0, 8.0 if quantity == "D0" else 0.8)
    handles, _ = ax.get_legend_handles_labels()
    ax.legend(handles=handles + _variant_legend(ax, fe), fontsize=8,
              loc="lower right" if quantity == "D0" else "upper right")
    ax.set_title(f"{model}, equi-biaxial: ${quantity[0]}_0$ vs stretch", fontsize=10)
    return ax


def plot_equibiaxial_wrinkling(model="neo-Hookean", s_values=(0, 0.8, 1.5, 2.5, 4.5), fe=None,
                               ax=None, D0max=8.0):
    """Loading curves with the thin/thick-plate wrinkling limits (paper Fig. gent-equi-biaxial).

    The grey zone lies between the thick-plate limit (dashed, Eq. ideal-shortwave
    for neo-Hookean, Eq. short-wave in general) and the thin-plate limit
    (Eq. antisym_thin, which coincides with the ``s = 0`` loading curve).

    Returns
    -------
    matplotlib Axes
    """
    ax = _new_axes(ax)
    m = analytic_model(model)
    lam = np.linspace(0.5, 5.0, 2000)
    lk, thick = _refine_start(lam, lambda x: an.thick_limit_D0(x, m))
    ln, thin = _refine_start(lam, lambda x: an.thin_limit_D0(x, m))
    ok_k = np.isfinite(thick) & (thick <= D0max)
    ok_n = np.isfinite(thin) & (thin <= D0max)
    if ok_k.any() and ok_n.any():
        xs = np.concatenate([lk[ok_k], ln[ok_n][::-1]])
        ys = np.concatenate([thick[ok_k], thin[ok_n][::-1]])
        ax.fill(xs, ys, color="0.85", zorder=0, label="wrinkling zone")
    ax.plot(lk, thick, "--", color="tab:blue", label="thick-plate limit")
    for s, c in zip(s_values, _colors(len(s_values))):
        l, D0 = _equibiaxial_curve(s, m, 5.0)
        ax.plot(l, D0, color=c, label=f"$s = {s:g}$")
        mask = _fe_rows(fe, s=s, model=model)
        if mask is not None:
            for v in _VARIANT_MARKER:
                _fe_dots(ax, fe, fe["lam1_fe"], fe["D0"], mask & (fe["variant"] == v), v, c)
    ax.plot(ln, thin, ":", color="k", lw=1.5, label="thin-plate limit (= $s = 0$ curve)")
    ax.set_xlim(0.5, 5.0)
    ax.set_ylim(0, D0max)
    ax.set_xlabel(r"$\lambda$")
    ax.set_ylabel(r"$D_0$")
    handles, _ = ax.get_legend_handles_labels()
    ax.legend(handles=handles + _variant_legend(ax, fe), fontsize=8, loc="lower right")
    ax.set_title(f"{model}, equi-biaxial: loading curves and wrinkling limits", fontsize=10)
    return ax


# --------------------------------------------------------------------------- uni-axial
def uniaxial_voltage_locus(model="neo-Hookean", s=None):
    """Points ``(lam1, D0, E0)`` of the uni-axial ``det H* = 0`` locus.

    Traced through the maxima of ``E0`` along the fixed-``s`` loading curves,
    :func:`analytic.max_E0` with ``loading="uniaxial"`` (paper Fig. figde).
    """
    m = analytic_model(model)
    s = np.linspace(0.0, 6.0, 301) if s is None else np.asarray(s, dtype=float)
    lam1, E0 = (np.atleast_1d(np.asarray(a, dtype=float))
                for a in an.max_E0(s, m, loading="uniaxial"))
    ok = np.isfinite(lam1)
    D0 = np.asarray(an.uniaxial_D0(lam1[ok], s[ok], m), dtype=float)
    return lam1[ok], D0, E0[ok]


def plot_uniaxial_loading(model="neo-Hookean", s_values=(0, 1, 2, 3, 4), quantity="D0",
                          fe=None, ax=None, lam1_max=6.0, locus=True, palette=None):
    """Uni-axial dead-load curves ``D0(lam1)`` or ``E0(lam1)`` (paper Fig. figde, Eq. DEuniax).

    The dashed curve is the ``det H* = 0`` locus of :func:`uniaxial_voltage_locus`;
    FE dots at ``(lam1_fe, D0)`` or ``(lam1_fe, D0/(lam1_fe lam3_fe)^2)``. ``palette``
    (a superset of ``s_values``) fixes the colour of each ``s`` across panels.

    Returns
    -------
    matplotlib Axes
    """
    if quantity not in ("D0", "E0"):
        raise ValueError(f"quantity must be 'D0' or 'E0', got {quantity!r}")
    ax = _new_axes(ax)
    m = analytic_model(model)
    for s, c in zip(s_values, _colors(len(s_values), s_values, palette)):
        lam1, D0, E0 = _uniaxial_curve(s, m, lam1_max)
        ax.plot(lam1, D0 if quantity == "D0" else E0, color=c, label=f"$s = {s:g}$")
        mask = _fe_rows(fe, s=s, model=model)
        if mask is not None:
            yv = fe["D0"] if quantity == "D0" else _fe_E0(fe)
            for v in _VARIANT_MARKER:
                _fe_dots(ax, fe, fe["lam1_fe"], yv, mask & (fe["variant"] == v), v, c)
    if locus:
        l1, D0, E0 = uniaxial_voltage_locus(model)
        ax.plot(l1, D0 if quantity == "D0" else E0, "k--", lw=1.2,
                label=r"$\det\mathcal{H}^* = 0$")
    ax.set_xlabel(r"$\lambda_1$")
    ax.set_ylabel(r"$D_0$" if quantity == "D0" else r"$E_0$")
    ax.set_xlim(0.5, lam1_max)
    ax.set_ylim(0, 8.0 if quantity == "D0" else 0.8)
    handles, _ = ax.get_legend_handles_labels()
    ax.legend(handles=handles + _variant_legend(ax, fe), fontsize=8,
              loc="lower right" if quantity == "D0" else "upper right")
    ax.set_title(f"{model}, uni-axial dead load: ${quantity[0]}_0$ vs $\\lambda_1$", fontsize=10)
    return ax


def uniaxial_thick_limit_curve(lam1, model="neo-Hookean", direction="parallel"):
    """``D0`` of the thick-plate limit on the uni-axial path, per ``lam1``.

    Solves Eq. (thick-uni-axial) together with Eq. (uni-axial-loading)_2,
    ``D0^2 = lam1^2 lam3^4 - 1``, for ``lam3`` by vectorised bisection of
    ``thick_limit_D0_uniaxial(lam1, lam3) - sqrt(lam1^2 lam3^4 - 1)`` (paper
    Fig. uni-axial-ideal); ``nan`` where no root is bracketed.
    """
    m = analytic_model(model)
    lam1 = np.asarray(lam1, dtype=float)
    lo = lam1 ** -0.5 * (1 + 1e-12)       # D0 = 0 on the path
    hi = lo * 20.0

    def g(l3):
        th = np.asarray(an.thick_limit_D0_uniaxial(lam1, l3, m, direction=direction), dtype=float)
        path = np.sqrt(np.maximum(lam1**2 * l3**4 - 1.0, 0.0))
        return th - path

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
    D0 = np.sqrt(np.maximum(lam1**2 * l3**4 - 1.0, 0.0))
    return np.where(ok, D0, np.nan)


def plot_uniaxial_wrinkling(fe=None, alphas=ALPHAS, ax=None, D0max=7.0):
    """The Keplinger plate (paper Fig. uni-axial-ideal).

    Neo-Hookean loading curves Eq. (DEuniax) for ``s = alpha m g/(mu A)``, the
    thick-plate limit (dashed blue, Eq. thick-uni-axial), the thin-plate limit
    (dashed black, Eq. thin-uni-axial, the ``s = 0`` curve), the wrinkling zone
    between them, the FE dots of the clamped plate, per run a red open marker of the
    shape of its FE model around the dot of its "P33 breakdown" (:data:`BREAKDOWN_NAME`:
    the first step with ``P33/mu < -0.01`` near the clamps or that the solver could not
    reach), and a red cross at the "buckling load"
    ``D0_b`` (:data:`BUCKLING_NAME`) of the runs analysed with the whole plate's spectrum
    (the zero crossing of the lowest physical eigenvalue, column ``physical_eig``).
    The FE models are named by :data:`MODEL_NAME` in the legend.

    Returns
    -------
    matplotlib Axes
    """
    ax = _new_axes(ax, figsize=(6.5, 4.8))
    m = analytic_model("neo-Hookean")
    lam1 = np.linspace(0.4, 6.0, 1500)
    ln, thin, _ = _uniaxial_curve(0.0, m, 6.0)          # Eq. (thin-uni-axial) = s = 0
    lk, thick = _refine_start(lam1, uniaxial_thick_limit_curve)
    ok_k = np.isfinite(thick) & (thick <= D0max)
    ok_n = np.isfinite(thin) & (thin <= D0max)
    if ok_k.any() and ok_n.any():
        xs = np.concatenate([lk[ok_k], ln[ok_n][::-1]])
        ys = np.concatenate([thick[ok_k], thin[ok_n][::-1]])
        ax.fill(xs, ys, color="0.85", zorder=0, label="wrinkling zone")
    ax.plot(lk, thick, "--", color="tab:blue", label="thick-plate limit")
    ax.plot(ln, thin, "--", color="k", label="thin-plate limit ($s = 0$)")
    broken = set()
    buckled = []
    for a, c in zip(alphas, _colors(len(alphas))):
        s = keplinger_s(a)
        l1, D0c, _ = _uniaxial_curve(s, m, 6.0)
        ax.plot(l1, D0c, color=c, label=rf"$\alpha = {a:g}$, $s = {s:.3g}$")
        if fe is None or not len(fe.get("run", [])):
            continue
        for v in _VARIANT_MARKER:
            sel = np.isclose(fe["alpha"], a) & (fe["variant"] == v)
            if not sel.any():
                continue
            conv = np.array([bool(x) for x in fe["converged"][sel]])
            brk = np.array([bool(x) for x in fe["breakdown"][sel]])
            lam_fe, D0_fe = fe["lam1_fe"][sel], fe["D0"][sel]
            ax.plot(lam_fe[conv], D0_fe[conv], ls="none", color=c, **_VARIANT_MARKER[v])
            if brk.any() or not conv.all():
                # the first compressive step, else the last converged one before the failure
                i = int(np.argmax(brk)) if brk.any() else max(int(np.argmin(conv)) - 1, 0)
                x = lam_fe[i] if np.isfinite(lam_fe[i]) else fe["lam1_analytic"][sel][i]
                ax.plot(x, D0_fe[i], ls="none", color="red", mfc="none", mew=1.6, zorder=5,
                        clip_on=False, **_BREAKDOWN_MARKER.get(v, _BREAKDOWN_MARKER["coupled"]))
                broken.add(v)
            ev = fe["physical_eig"][sel] if "physical_eig" in fe else np.zeros(0)
            D0b = buckling_crossing(D0_fe, ev) if np.isfinite(ev).any() else None
            if D0b is not None:       # the stability-based breakdown: a red cross
                ok = conv & np.isfinite(lam_fe)
                ax.plot(np.interp(D0b, D0_fe[ok], lam_fe[ok]), D0b, ls="none", color="red",
                        marker="x", ms=11, mew=2.4, zorder=6, clip_on=False)
                buckled.append(f"{a:g}")
    ax.set_xlim(0.4, 6.0)
    ax.set_ylim(0, D0max)
    ax.set_xlabel(r"$\lambda_1$")
    ax.set_ylabel(r"$D_0$")
    handles, _ = ax.get_legend_handles_labels()
    crosses = [Line2D([], [], ls="none", color="red", mfc="none", mew=1.6,
                      label=f"{BREAKDOWN_NAME} ($P_{{33}}/\\mu < -0.01$), {MODEL_NAME[v]}",
                      **dict(_BREAKDOWN_MARKER[v], ms=0.6 * _BREAKDOWN_MARKER[v]["ms"]))
               for v in _BREAKDOWN_MARKER if v in broken]
    if buckled:
        crosses.insert(0, Line2D([], [], ls="none", color="red", marker="x", ms=8, mew=2.2,
                                 label=f"{BUCKLING_NAME} (whole-plate spectrum), "
                                 + r"$\alpha = $" + ", ".join(buckled)))
    ax.legend(handles=handles + _variant_legend(ax, fe) + crosses, fontsize=8,
              loc="center left", bbox_to_anchor=(1.01, 0.5))
    ax.set_title("Keplinger plate, uni-axial dead load (neo-Hookean)", fontsize=10)
    return ax


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
    axes = _new_axes(axes, n=2, figsize=(8.0, 5.0))
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
    ax = _new_axes(ax, figsize=(6.5, 4.5))
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


# --------------------------------------------------------------------------- per case
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


def _mesh_text(specs) -> str:
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
    return run_caption(head, quick, _mesh_text(specs))


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
        _shared_legend(fig, axes)
        tag_panels(axes)
        return fig
    if name == "gent-equi-biaxial":
        fig, axes = plt.subplots(1, 2, figsize=(13, 5.0), layout="constrained", sharey=True)
        for ax, model in zip(axes, ("neo-Hookean", "Gent")):
            plot_equibiaxial_wrinkling(model, fe=fe, ax=ax)
        _shared_legend(fig, axes)             # clear of the s = 4.5 curve
        tag_panels(axes)
        return fig
    if name == "figde":
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), layout="constrained")
        palette = (0, 1, 2, 3, 4)
        plot_uniaxial_loading("neo-Hookean", palette, "D0", fe=fe, ax=axes[0])
        plot_uniaxial_loading("neo-Hookean", (0, 1, 2, 3), "E0", fe=fe, ax=axes[1],
                              palette=palette)
        _shared_legend(fig, axes)             # (a)'s legend covered the s = 3, 4 curves
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
        variants = [v for v in _VARIANT_MARKER if any(f"_{v}_" in r for r in set(fields["run"]))]
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


def _shared_legend(fig, axes):
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
    fig.savefig(paths[1], bbox_inches=bbox_inches,
                metadata={"CreationDate": None, "Creator": None, "Producer": None})
    plt.close(fig)
    return paths

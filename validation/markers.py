"""One vocabulary for the markers of the breakdown and stability results.

Every figure that draws one of these quantities (paper Fig. 5 ``uni-axial-ideal``, the
breakdown map, the ``voltage-control`` figure) takes its marker, colour and legend name
from here, and the pages docs/breakdown.md, docs/gallery.md, docs/validation.md and
docs/cli.md describe each marker with the same words (:attr:`Marker.look`) next to the same
legend name (:attr:`Marker.name`; tests/validation/test_markers.py checks both).

The paper's own marker of its ``P33`` criterion is a red cross (its Fig. 5); our figures
draw that criterion as :data:`P33_BREAKDOWN` (a red open marker of the FE model's shape)
and keep the red cross for the buckling load the run locates itself
(:data:`RUN_BUCKLING`).  The pages quote the paper's marker only as
:data:`PAPER_P33_WORDS`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["Marker", "P33_BREAKDOWN", "P33_ONSET_LOCATED", "AFTER_BREAKDOWN", "RUN_BUCKLING", "CONVERGED_BUCKLING",
           "MESH_BUCKLING", "NEWTON_LIMIT", "RUN_NEWTON", "WRINKLING_NOT_REACHED",
           "STABLE_STATE", "UNSTABLE_STATE", "LIMIT_POINT", "SECTION_SYMMETRIC",
           "SECTION_ANTISYMMETRIC", "BEYOND_TOLERANCE", "VOCABULARY",
           "P33_SHAPES",
           "PAPER_P33_WORDS", "NOT_CONVERGED_NOTE", "BREAKDOWN_MEANINGS", "legend_style",
           "find_marker", "LineRole", "MODE_LINES", "VOLTAGE_LIMIT_LOCUS", "THIN_PLATE_LIMIT",
           "THICK_PLATE_LIMIT", "NEWTON_BAND", "NEWTON_BAND_LABEL", "SYMMETRIC_MODE", "ANTISYMMETRIC_MODE", "LINES", "line_style"]


@dataclass(frozen=True)
class Marker:
    """One reported quantity as the figures draw it.

    Attributes
    ----------
    name
        The legend name (a legend entry starts with it; the docs quote it in backticks).
    look
        The marker in words, as the docs describe it (e.g. ``"red cross"``).
    meaning
        What the marker marks, in one line.
    style
        Matplotlib ``Line2D`` keywords of the marker (``marker``, ``color``, ``mfc``,
        ``ms``, ``mew``, ``alpha``, ``zorder``); a ``marker`` of ``None`` takes the FE
        model's shape (:data:`P33_SHAPES`, or the model's own dot marker).
    """

    name: str
    look: str
    meaning: str
    style: dict = field(default_factory=dict)


#: Shape and size of the :data:`P33_BREAKDOWN` marker per FE variant: around the model's
#: own dot (validation.figures.common.VARIANT_MARKER), larger, so that the dot shows inside.
P33_SHAPES = {"coupled": dict(marker="o", ms=19), "maxwell": dict(marker="s", ms=14),
              "membrane": dict(marker="^", ms=12)}

P33_BREAKDOWN = Marker(
    "P33 breakdown", "red open marker",
    "the paper's criterion (Sec. 6): the first step with P33/mu < -0.01 on the centre line "
    "at least two thicknesses from the clamps, or a step the solver could not reach; "
    "circle, square or triangle: the FE model's shape",
    dict(marker=None, color="red", mfc="none", mew=1.6, zorder=5))
P33_ONSET_LOCATED = Marker(
    "P33 onset, located", "red bar",
    "the reference layer of the P33 criterion: the plain form's first charge with "
    "P33/mu < -0.01 in the interior, located to 1e-4 on the finest graded mesh of the "
    "clamp-zone study (validation/data/clamp_p33.csv), where the run's own P33 breakdown "
    "is the first step of its coarse grid",
    dict(marker="_", color="red", ms=16, mew=2.6, zorder=8))
AFTER_BREAKDOWN = Marker(
    "after the breakdown", "faded dot",
    "a state of a run that goes on past its P33 breakdown (the run analysed for buckling, "
    "alpha = 1): drawn faded, since the paper's ramp stops at the breakdown",
    dict(marker=None, color="0.45", mfc="none", alpha=0.35))
RUN_BUCKLING = Marker(
    "buckling load of this run", "red cross",
    "D0_b located by the run itself on its own (coarse) mesh: the zero crossing of the "
    "whole plate's lowest physical eigenvalue (column D0_b)",
    dict(marker="x", color="red", ms=13, mew=2.8, zorder=9))
CONVERGED_BUCKLING = Marker(
    "buckling load, converged", "black diamond",
    "D0_b where the meshes agree: the finest of the two finest graded meshes of the "
    "clamp-zone study (validation/data/clamp_units.csv), else the extrapolation of three "
    "uniform meshes (validation/data/buckling_loads.csv); its error bar (at most 0.012) is "
    "smaller than the diamond",
    dict(marker="D", color="k", ms=6, zorder=7))
MESH_BUCKLING = Marker(
    "buckling load on each mesh", "small grey dot",
    "D0_b on each mesh of the load (the two finest graded or the three uniform); where "
    "they scatter without a diamond the load is not converged",
    dict(marker=".", color="0.55", ms=5, zorder=2))
NEWTON_LIMIT = Marker(
    "Newton limit, plain form", "black triangle down",
    "where the plain form's Newton ramp stops on the finest mesh (the clamp/free-edge "
    "corner), long after D0_b",
    dict(marker="v", color="k", ms=8, zorder=7))
RUN_NEWTON = Marker(
    "Newton limit of this run", "red open triangle down",
    "the first charge target the run's own Newton solver could not reach",
    dict(marker="v", color="red", mfc="none", ms=8, mew=1.5, zorder=6))
WRINKLING_NOT_REACHED = Marker(
    "homogeneous wrinkling limit: not reached", "blue arrow",
    "the paper's homogeneous wrinkling limits (thin and thick plate) on the weight's path "
    "lie above the axes: never reached for s > 0",
    dict(marker=r"$\uparrow$", color="tab:blue", ms=14, zorder=6))
STABLE_STATE = Marker(
    "stable (voltage control)", "filled dot",
    "a point of a voltage-controlled path whose reduced stiffness is positive definite",
    dict(marker="o", color="k", ms=5))
UNSTABLE_STATE = Marker(
    "unstable (voltage control)", "open dot",
    "a point of a voltage-controlled path with a negative eigenvalue of its reduced "
    "stiffness (past a limit point)",
    dict(marker="o", color="k", mfc="none", ms=5))
LIMIT_POINT = Marker(
    "limit point (snap-through)", "red star",
    "the located maximum of E0 on a voltage-controlled path",
    dict(marker="*", color="crimson", ms=12, mec="k", mew=0.5, zorder=4))

SECTION_SYMMETRIC = Marker(
    "2D cross-section, symmetric", "open hexagon",
    "a critical point of the FE cross-section (one Fourier mode, sliding ends) whose mode is "
    "symmetric about the mid-plane (wrinkling-fe; the colour is the curve's)",
    dict(marker="h", color="k", mfc="none", ms=8))
SECTION_ANTISYMMETRIC = Marker(
    "2D cross-section, antisymmetric", "filled hexagon",
    "a critical point of the FE cross-section whose mode is antisymmetric about the "
    "mid-plane (wrinkling-fe; the colour is the curve's)",
    dict(marker="h", color="k", ms=6))
BEYOND_TOLERANCE = Marker(
    "beyond its tolerance", "orange X",
    "check: a row of the checked results beyond its tolerance (drawn above the others)",
    dict(marker="X", color="darkorange", mec="saddlebrown", ms=11, mew=0.8, zorder=10))

@dataclass(frozen=True)
class LineRole:
    """One curve as every figure and the explore page draw it: the same role, the same
    line (a figure gives its line the role's ``gid``, which the tests read back).

    Attributes
    ----------
    gid
        The ``gid`` of a matplotlib line of this role (and the explore page's glyph name).
    look
        The line in words.
    meaning
        What it is, in one line.
    style
        Matplotlib keywords (``ls``, ``color`` where the role fixes it, ``lw``).
    dash
        The explore page's (Bokeh) ``line_dash``.
    """

    gid: str
    look: str
    meaning: str
    style: dict = field(default_factory=dict)
    dash: str = "solid"


VOLTAGE_LIMIT_LOCUS = LineRole(
    "det-H-locus", "dotted black line",
    "the voltage-control limit det H* = 0 (Sec. 3.1): the maxima of E0 of the loading "
    "curves", dict(ls=":", color="k", lw=1.3), "dotted")
THIN_PLATE_LIMIT = LineRole(
    "thin-plate-limit", "dashed black line",
    "the thin-plate wrinkling limit (Eqs. thin-equi-biaxial, thin-uni-axial; kh -> 0)",
    dict(ls="--", color="k", lw=1.3), "dashed")
THICK_PLATE_LIMIT = LineRole(
    "thick-plate-limit", "dashed blue line",
    "the thick-plate (surface) wrinkling limit (Eqs. thick-equi-biaxial, thick-uni-axial; "
    "kh -> infinity)", dict(ls="--", color="tab:blue", lw=1.3), "dashed")
NEWTON_BAND = LineRole(
    "newton-band", "thick tan line",
    "the plain form's Newton limits of one weight over every mesh that has one (graded and "
    "uniform): a solver limit that moves with the mesh, from its lowest to its highest "
    "value (the black triangle is the breakdown table's mesh)",
    dict(ls="-", color="tan", lw=6, solid_capstyle="butt", zorder=1), "solid")
#: the legend entry of :data:`NEWTON_BAND`
NEWTON_BAND_LABEL = "Newton limit over its meshes (a solver limit that moves with the mesh)"
SYMMETRIC_MODE = LineRole(
    "symmetric-mode", "solid line",
    "a Stroh curve of wrinkles symmetric about the mid-plane (extensional); the colour is "
    "the curve's", dict(ls="-"), "solid")
ANTISYMMETRIC_MODE = LineRole(
    "antisymmetric-mode", "dash-dotted line",
    "a Stroh curve of wrinkles antisymmetric about the mid-plane (flexural); the colour is "
    "the curve's", dict(ls="-."), "dashdot")
#: Every line role; no two share a look.
LINES = (VOLTAGE_LIMIT_LOCUS, THIN_PLATE_LIMIT, THICK_PLATE_LIMIT, NEWTON_BAND,
         SYMMETRIC_MODE, ANTISYMMETRIC_MODE)
#: the Stroh curves' role by mode
MODE_LINES = {"symmetric": SYMMETRIC_MODE, "antisymmetric": ANTISYMMETRIC_MODE}


def line_style(role: LineRole, **extra) -> dict:
    """The matplotlib keywords of a line of ``role``: its style and ``gid``, updated by
    ``extra`` (e.g. the curve's colour where the role leaves it open).

    Examples
    --------
    >>> line_style(VOLTAGE_LIMIT_LOCUS)["ls"]
    ':'
    """
    return {**role.style, "gid": role.gid, **extra}


#: Every marker, in the order the docs' tables list them.
VOCABULARY = (P33_BREAKDOWN, P33_ONSET_LOCATED, AFTER_BREAKDOWN, RUN_BUCKLING, CONVERGED_BUCKLING,
              MESH_BUCKLING, NEWTON_LIMIT, RUN_NEWTON, WRINKLING_NOT_REACHED, STABLE_STATE,
              UNSTABLE_STATE, LIMIT_POINT, SECTION_SYMMETRIC, SECTION_ANTISYMMETRIC,
              BEYOND_TOLERANCE)

#: The three meanings of "breakdown", in the order the charge meets them, each in one
#: sentence that report.md, the README and docs/breakdown.md say in these words
#: (tests/docs/test_docs_data.py): ``(name, sentence)``.
BREAKDOWN_MEANINGS = (
    ("the P33 criterion", "the first charge at which P33/mu falls below -0.01 on the centre "
     "line at least two thicknesses from the clamps, where the paper's COMSOL runs stopped: "
     "a warning of the lateral compression next to the clamps, not an instability"),
    ("the buckling load D0_b", "the charge at which the whole plate's lowest physical "
     "eigenvalue crosses zero: the loss of stability, a wrinkle next to each clamp"),
    ("the Newton limit", "the charge at which the plain form's Newton ramp stops at the "
     "clamp/free-edge corner: a failure of the solver, after D0_b"),
)

#: How the pages name the paper's own marker of its P33 criterion (not one of ours).
PAPER_P33_WORDS = "the paper's red crosses"

#: The note of a weight whose buckling load is not converged (no diamond).
NOT_CONVERGED_NOTE = "no diamond: the three meshes disagree (not converged)"


def legend_style(marker: Marker, shape: dict | None = None, **extra) -> dict:
    """The ``Line2D`` keywords of ``marker`` (for a legend handle or a drawn point):
    its :attr:`~Marker.style` with the FE model's ``shape`` where the style leaves the
    shape open, updated by ``extra``.

    Examples
    --------
    >>> legend_style(RUN_BUCKLING)["marker"]
    'x'
    >>> legend_style(P33_BREAKDOWN, P33_SHAPES["maxwell"])["marker"]
    's'
    """
    out = {k: v for k, v in marker.style.items() if not (k == "marker" and v is None)}
    if marker.style.get("marker", "") is None:
        out.update(shape or {})
    out.update(extra)
    return out


def find_marker(label: str) -> Marker | None:
    """The vocabulary entry a legend label starts with (the longest name), else ``None``.

    Examples
    --------
    >>> find_marker("buckling load of this run (10 x 1 x 5)").look
    'red cross'
    >>> find_marker("wrinkling zone") is None
    True
    """
    hits = [m for m in VOCABULARY if label.startswith(m.name)]
    return max(hits, key=lambda m: len(m.name)) if hits else None

"""One marker vocabulary (validation.markers) in the figures and the docs.

The pages describe each marker in words (``Marker.look``, e.g. "red cross") and name it by
its legend name (``Marker.name``, e.g. `buckling load of this run`); the figures draw it
with ``Marker.style`` under a legend entry that starts with the name.  The tests read the
pages as the reader does (paragraph by paragraph, table row by table row) and the
legends as matplotlib holds them, so that a page calling the P33 breakdown a red cross,
or a legend drawing it with another marker, fails.
"""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import analytic as an  # noqa: E402
from analytic.units import keplinger_s  # noqa: E402
from validation.data.loads import buckling_loads, uniform_buckling_loads  # noqa: E402
from validation.figures import plot_breakdown_map, plot_uniaxial_wrinkling  # noqa: E402
from validation.markers import (AFTER_BREAKDOWN, CONVERGED_BUCKLING, LIMIT_POINT,  # noqa: E402
                                MESH_BUCKLING, NEWTON_LIMIT, NOT_CONVERGED_NOTE,
                                P33_BREAKDOWN, P33_ONSET_LOCATED, PAPER_P33_WORDS,
                                RUN_BUCKLING, RUN_NEWTON,
                                STABLE_STATE, UNSTABLE_STATE, VOCABULARY,
                                WRINKLING_NOT_REACHED, find_marker)
from validation.studies.voltage_control import VOLTAGE_COLUMNS, voltage_figure  # noqa: E402

DOCS = Path(__file__).resolve().parents[2] / "docs"
PAGES = ("breakdown.md", "gallery.md", "validation.md", "clamp-zone.md", "cli.md",
         "explore.md")


def _units(text: str) -> list[str]:
    """The page as a reader meets it: each table row, list item and paragraph (code
    blocks left out), with the paper's own marker (:data:`PAPER_P33_WORDS`) taken out."""
    out, cur, code = [], [], False
    for line in text.splitlines():
        s = line.strip()
        if s.startswith("```"):
            code = not code
            continue
        if code:
            continue
        if not s or s.startswith(("|", "* ", "- ", "#")) or re.match(r"\d+\. ", s):
            if cur:
                out.append(" ".join(cur))
            cur = []
        if s.startswith("|"):
            out.append(s)
        elif s:
            cur.append(s)
    if cur:
        out.append(" ".join(cur))
    return [re.sub(re.escape(PAPER_P33_WORDS), "", u, flags=re.I) for u in out]


def _look(marker) -> re.Pattern:
    """The marker's words, each word also in the plural ("red crosses")."""
    return re.compile(r"\b" + r"\s+".join(re.escape(w) + "(?:e?s)?" for w in marker.look.split())
                      + r"\b", re.I)


def _looks_in(unit: str):
    """The vocabulary entries whose marker words a unit uses (the longest words win where
    one entry's words hold another's)."""
    hits = [(m, mt.span()) for m in VOCABULARY for mt in _look(m).finditer(unit)]
    out = [m for m, (a, b) in hits
           if not any((a2 <= a and b <= b2) and (b2 - a2) > (b - a) for _, (a2, b2) in hits)]
    return list({m.name: m for m in out}.values())


def test_the_vocabulary_is_one_to_one():
    names = [m.name for m in VOCABULARY]
    looks = [m.look for m in VOCABULARY]
    assert len(set(names)) == len(names) and len(set(looks)) == len(looks)
    # the P33 criterion is not the cross: the cross is the run's own buckling load
    assert P33_BREAKDOWN.look == "red open marker" and RUN_BUCKLING.look == "red cross"
    for m in VOCABULARY:
        assert m.meaning and m.style.get("color") is not None


@pytest.mark.parametrize("page", PAGES)
def test_a_marker_described_on_a_page_is_named_by_its_legend_name(page):
    """Where a page describes a marker in words, the same paragraph or table row names
    it by its legend name (docs/validation.md once said the P33 breakdown "gets a red
    cross", the run's buckling load's marker)."""
    bad = []
    for unit in _units((DOCS / page).read_text()):
        for m in _looks_in(unit):
            if m.name not in unit:
                bad.append(f"{m.look!r} without {m.name!r}: {unit[:160]}")
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("page", PAGES)
def test_a_legend_name_quoted_on_a_page_comes_with_its_marker(page):
    """Where a page quotes a legend name (in backticks), the paragraph or table row
    describes its marker with the vocabulary's words, and no other entry's words stand
    for it there."""
    bad = []
    for unit in _units((DOCS / page).read_text()):
        for m in VOCABULARY:
            if f"`{m.name}`" in unit and not _look(m).search(unit):
                bad.append(f"{m.name!r} without {m.look!r}: {unit[:160]}")
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("page", ["breakdown.md", "gallery.md"])
def test_the_marker_tables_list_the_vocabulary(page):
    """The marker tables of breakdown.md (the breakdown map's markers) and gallery.md
    (every figure's): one row per marker, with its words and legend name."""
    rows = [u for u in _units((DOCS / page).read_text()) if u.startswith("|")]
    want = (VOCABULARY if page == "gallery.md" else
            (P33_BREAKDOWN, P33_ONSET_LOCATED, RUN_BUCKLING, CONVERGED_BUCKLING,
             MESH_BUCKLING, NEWTON_LIMIT, RUN_NEWTON, WRINKLING_NOT_REACHED))
    for m in want:
        assert any(f"`{m.name}`" in r and _look(m).search(r) for r in rows), m.name


def _legend(ax):
    """``(label, handle)`` of the axes' legend as drawn."""
    leg = ax.get_legend()
    return list(zip([t.get_text() for t in leg.get_texts()], leg.legend_handles))


def _same_marker(handle, marker):
    """The handle's marker has the vocabulary's shape, colour and face."""
    from matplotlib.colors import same_color

    st = marker.style
    if st.get("marker") is not None:
        assert handle.get_marker() == st["marker"]
    assert same_color(handle.get_color(), st["color"])
    if st.get("mfc") == "none":
        assert handle.get_markerfacecolor() == "none"
    elif marker is not AFTER_BREAKDOWN:
        assert handle.get_markerfacecolor() != "none"


def _fake_keplinger():
    """A uni-axial-ideal table: alpha = 1 (3D fully coupled) on the homogeneous curve up to
    D0 = 5 with its P33 breakdown at 3 and its own D0_b = 2.9147 (the quick run's), the
    Maxwell-traction run stopping at its breakdown 3, alpha = 0.3 stopping at 1.5."""
    cols = {k: [] for k in ("run", "alpha", "variant", "converged", "breakdown", "lam1_fe",
                            "lam1_analytic", "D0", "D0_b")}
    for a, var, stop in ((1.0, "coupled", 5.0), (1.0, "maxwell", 3.0), (0.3, "coupled", 1.5)):
        s = float(keplinger_s(a, g=9.81))
        brk = 1.5 if a == 0.3 else 3.0
        for d in np.arange(0.0, stop + 1e-9, 0.5):
            lam = float(an.uniaxial_lam1(d, s, an.NeoHookean()))
            for k, v in (("run", f"{a:g}_{var}"), ("alpha", a), ("variant", var),
                         ("converged", True), ("breakdown", bool(np.isclose(d, brk))),
                         ("lam1_fe", lam), ("lam1_analytic", lam), ("D0", d),
                         ("D0_b", 2.9147 if (var == "coupled" and a == 1 and d == 3.0)
                          else np.nan)):
                cols[k].append(v)
    return {k: np.array(v) for k, v in cols.items()}


def test_the_keplinger_figure_draws_the_vocabulary():
    fig, ax = plt.subplots()
    plot_uniaxial_wrinkling(fe=_fake_keplinger(), ax=ax)
    drawn = {}
    for label, h in _legend(ax):
        m = find_marker(label)
        if m is not None:
            _same_marker(h, m)
            drawn[m.name] = label
    assert set(drawn) == {P33_BREAKDOWN.name, AFTER_BREAKDOWN.name, RUN_BUCKLING.name,
                          CONVERGED_BUCKLING.name, NEWTON_LIMIT.name, P33_ONSET_LOCATED.name}
    # the error bars are at most the file's largest error, and the legend says so
    err = max(e.error for e in buckling_loads() if e.converged)
    assert f"{err:.2g}" in drawn[CONVERGED_BUCKLING.name]
    assert "hidden by the diamond" in drawn[CONVERGED_BUCKLING.name]
    # every weight has a converged load: no note of a missing diamond
    assert not any(NOT_CONVERGED_NOTE in lab for lab, _ in _legend(ax))
    # the dots past the breakdown (D0 = 3.5 ... 5 of alpha = 1) are the faded ones
    (after,) = [ln for ln in ax.lines if ln.get_gid() == "after-breakdown"]
    np.testing.assert_array_equal(after.get_ydata(), [3.5, 4.0, 4.5, 5.0])
    assert after.get_alpha() == AFTER_BREAKDOWN.style["alpha"]
    # the run's own D0_b: on its dots (lam1 of D0_b on the FE curve), above every marker
    (cross,) = [ln for ln in ax.lines if ln.get_gid() == "buckling-run"]
    s1 = float(keplinger_s(1.0, g=9.81))
    np.testing.assert_allclose(cross.get_xydata(), [[np.interp(
        2.9147, [2.5, 3.0], [an.uniaxial_lam1(d, s1, an.NeoHookean()) for d in (2.5, 3.0)]),
        2.9147]], rtol=1e-12)
    others = [a for a in ax.lines + ax.collections if a is not cross]
    assert cross.get_zorder() > max(a.get_zorder() for a in others)
    assert RUN_BUCKLING.style["ms"] > CONVERGED_BUCKLING.style["ms"]   # wider than the diamond
    plt.close(fig)


def test_the_keplinger_figure_notes_a_missing_diamond(monkeypatch):
    """With the uniform meshes' loads alone (alpha = 1.5 not converged) the legend says
    why alpha = 1.5 has no diamond."""
    import validation.figures.uniaxial_wrinkling as uw
    monkeypatch.setattr(uw, "buckling_loads", uniform_buckling_loads)
    fig, ax = plt.subplots()
    plot_uniaxial_wrinkling(fe=_fake_keplinger(), ax=ax)
    assert any(lab == rf"$\alpha = 1.5$: {NOT_CONVERGED_NOTE}" for lab, _ in _legend(ax))
    plt.close(fig)


def test_the_keplinger_axis_ends_at_the_data():
    """The lam1 axis ends just past the last curve point below D0 = 7 (alpha = 1.5 reaches
    D0 = 7 at lam1 = 4.80 on its homogeneous curve, docs/gallery.md), not at 6."""
    fig, ax = plt.subplots()
    plot_uniaxial_wrinkling(ax=ax)
    s = float(keplinger_s(1.5, g=9.81))
    right = float(an.uniaxial_lam1(7.0, s, an.NeoHookean()))
    assert right < ax.get_xlim()[1] <= 1.02 * right + 0.25
    plt.close(fig)


def test_the_breakdown_map_draws_the_vocabulary():
    fig, ax = plt.subplots()
    plot_breakdown_map(p33={"coupled": {0.05: 0.5, 1.0: 3.0}}, run_buckling={1.0: 2.9147},
                       run_newton={0.3: 5.5}, run_mesh="10 x 1 x 5", ax=ax)
    drawn = set()
    labels, handles = ax.get_legend_handles_labels()[::-1]
    for label, h in zip(labels, handles):
        m = find_marker(label)
        if m is None:
            continue
        h = getattr(h, "lines", [h])[0] or h        # an errorbar's data line
        _same_marker(h, m)
        drawn.add(m.name)
    assert drawn == {P33_BREAKDOWN.name, RUN_BUCKLING.name, CONVERGED_BUCKLING.name,
                     MESH_BUCKLING.name, NEWTON_LIMIT.name, RUN_NEWTON.name,
                     WRINKLING_NOT_REACHED.name, P33_ONSET_LOCATED.name,
                     LIMIT_POINT.name}
    # the voltage-controlled snap-through: a red star per weight with two agreeing meshes,
    # at the charge of the voltage table
    from validation.data.loads import voltage_limits

    (stars,) = [ln for ln in ax.lines if ln.get_gid() == "voltage-limit"]
    want = voltage_limits()
    assert want and list(stars.get_xdata()) == [a for a, _, _ in want]
    assert list(stars.get_ydata()) == [d for _, d, _ in want]
    # every weight has its diamond; with the uniform meshes' loads alone alpha = 1.5 has
    # none (three meshes that disagree), and a note in the figure says why
    assert not [t for t in ax.texts if t.get_gid() == "not-converged"]
    fig2, ax2 = plt.subplots()
    plot_breakdown_map(loads=uniform_buckling_loads(), ax=ax2)
    notes = [t for t in ax2.texts if t.get_gid() == "not-converged"]
    assert [t.get_text() for t in notes] == [rf"$\alpha = 1.5$: {NOT_CONVERGED_NOTE}"]
    plt.close(fig2)
    (cross,) = [ln for ln in ax.lines if ln.get_gid() == "buckling-run"]
    assert cross.get_zorder() > max(a.get_zorder() for a in ax.lines + ax.collections
                                    if a is not cross)
    plt.close(fig)


def _voltage_rows():
    """Two points of one equi-biaxial path: stable, then a limit point (unstable)."""
    col = {c: i for i, c in enumerate(VOLTAGE_COLUMNS)}
    rows = []
    for point, (E0, D0, stable, kind) in enumerate(((0.2, 0.25, True, "regular"),
                                                   (0.69, 1.8, False, "limit"))):
        r = [None] * len(VOLTAGE_COLUMNS)
        for k, v in dict(case="voltage-control", run="eq", point=point, model="neo-Hookean",
                         loading="equibiaxial", variant="coupled", s=0.0, alpha=None,
                         kind=kind, E0=E0, D0=D0, lam1_fe=1.0 + E0, stable=stable).items():
            if k in col:
                r[col[k]] = v
        rows.append(r)
    return rows


def test_the_voltage_control_figure_draws_the_vocabulary():
    """Two points of one equi-biaxial path: stable, then a limit point (unstable)."""
    ax = voltage_figure(_voltage_rows())
    drawn = set()
    for label, h in _legend(ax[0]):
        m = find_marker(label)
        if m is not None:
            _same_marker(h, m)
            drawn.add(m.name)
    assert drawn == {STABLE_STATE.name, UNSTABLE_STATE.name, LIMIT_POINT.name}
    plt.close(ax[0].figure)


_SHAPES = {"x": "cross", "X": "cross", "o": "circle", "s": "square", "^": "triangle up",
           "v": "triangle down", "D": "diamond", "d": "diamond", "h": "hexagon",
           "H": "hexagon", "P": "plus", "+": "plus", "*": "star", ".": "dot"}


def _look_of(h):
    """What a reader sees of a marker in a legend: shape, colour, filled or open, large or
    small (``None`` for a handle that is a line, a patch or a curve with points)."""
    from matplotlib.colors import to_hex

    h = getattr(h, "lines", [h])[0] or h
    if not hasattr(h, "get_marker") or h.get_marker() in (None, "None", "", " "):
        return None
    if h.get_linestyle() not in ("None", "", " "):
        return None        # a curve with its points: its colour names a series, not an event
    shape = _SHAPES.get(h.get_marker(), str(h.get_marker()))
    edge = h.get_markeredgecolor()
    colour = to_hex(edge if h.get_markerfacecolor() == "none" else h.get_markerfacecolor())
    return (shape, colour, h.get_markerfacecolor() == "none", h.get_markersize() >= 10)


def _meaning(label: str) -> str:
    m = find_marker(label)
    return m.name if m is not None else re.split(r" \(|, ", label)[0]


def test_one_look_one_meaning_across_every_figures_legend(tmp_path):
    """The legends of the Keplinger figure (with FE rows and as `curves` draws it), the
    breakdown map, the voltage-control figure, the FE wrinkling figure, a check figure
    with failing rows, the paper's loading figures and the clamp-edge band: a marker that looks the
    same (shape, colour, open or filled, large or small) means the same thing in all of
    them (the red cross is the run's buckling load, not a row beyond its tolerance; an
    open square is the Maxwell-traction plate, not an antisymmetric mode)."""
    from validation.check_report import check_figure
    from validation.checker import check
    from validation.studies.wrinkling import wrinkling_figure

    legends = []
    fig, ax = plt.subplots()
    plot_uniaxial_wrinkling(fe=_fake_keplinger(), ax=ax)
    legends += [("uni-axial-ideal", *lh) for lh in _legend(ax)]
    fig2, ax2 = plt.subplots()
    plot_breakdown_map(p33={"coupled": {0.05: 0.5, 1.0: 3.0}, "maxwell": {1.0: 3.0},
                            "membrane": {1.0: 3.5}},
                       run_buckling={1.0: 2.9147}, run_newton={0.3: 5.5},
                       run_mesh="10 x 1 x 5", ax=ax2)
    legends += [("breakdown map", *lh) for lh in _legend(ax2)]
    axv = voltage_figure(_voltage_rows())
    legends += [("voltage-control", *lh) for lh in _legend(axv[0])]
    rows = [["charge", mode, 1.5, kh, 4.0, 4.0, 0.0, "8x2", 0, 0, ""]
            for mode in ("symmetric", "antisymmetric") for kh in (0.5, 2.0)]
    elastic = [["antisymmetric", 1.0, 0.95, 0.95, 0.0, "8x4", ""]]
    axw = wrinkling_figure(rows, elastic=elastic, quick=True)
    for a in axw:
        if a.get_legend() is not None:
            legends += [("wrinkling-fe", *lh) for lh in _legend(a)]
    example = DOCS / "examples" / "ex14_external_nh-d-e.csv"
    result = check(example, tol=["lam1=1e-15"])
    assert not result.passed
    for case in result.cases:
        f = check_figure(case)
        for a in f.axes:
            if a.get_legend() is not None:
                legends += [(f"check {case.name}", *lh) for lh in _legend(a)]
    from validation.clamp_zone.band import edge_band_figure
    from validation.data.registry import load
    from validation.figures import case_figure

    figs = {name: case_figure(name) for name in ("nh-d-e", "gent-d-e", "gent-equi-biaxial",
                                                 "figde", "uni-axial-ideal")}
    figs["edge-band"] = edge_band_figure(load("section"))
    for name, f in figs.items():
        for leg in list(f.legends) + [a.get_legend() for a in f.axes if a.get_legend()]:
            legends += [(name, t.get_text(), h)
                        for t, h in zip(leg.get_texts(), leg.legend_handles)]
    assert len({w for w, _, _ in legends}) >= 10
    seen: dict = {}
    for where, label, h in legends:
        look = _look_of(h)
        if look is None:
            continue
        seen.setdefault(look, set()).add((_meaning(label), where))
    clash = {k: v for k, v in seen.items() if len({m for m, _ in v}) > 1}
    assert not clash, clash
    names = {m for v in seen.values() for m, _ in v}
    assert {RUN_BUCKLING.name, "beyond its tolerance", "2D cross-section, antisymmetric",
            "3D Maxwell traction"} <= names
    plt.close("all")


def _drawn(ax, gid: str) -> np.ndarray:
    """The ``(x, y)`` points of the axes' lines with ``gid`` (rows)."""
    pts = [np.asarray(ln.get_xydata(), float) for ln in ax.lines if ln.get_gid() == gid]
    return np.concatenate(pts) if pts else np.zeros((0, 2))


def _reference_order(ax, x_of_alpha):
    """The reference layer as drawn: per weight the located P33 onset, the converged D0_b
    and the Newton limit (y of the points whose x is the weight's, by ``x_of_alpha``);
    returns ``{alpha: (onset, D0_b, newton)}`` for the weights that have all three."""
    from validation.data.loads import buckling_loads as loads

    layers = [_drawn(ax, g) for g in ("p33-onset-located", "buckling-converged",
                                      "newton-limit")]
    out = {}
    for e in loads():
        x = x_of_alpha(e.alpha)
        ys = []
        for pts in layers:
            hit = pts[np.isclose(pts[:, 0], x, rtol=0, atol=1e-6)] if len(pts) else pts
            ys.append(float(hit[0, 1]) if len(hit) else None)
        if None not in ys:
            out[e.alpha] = tuple(ys)
    return out


def test_the_breakdown_map_draws_the_order_of_the_three_meanings():
    """From the reference layer the map draws (the shipped study, whatever the run): per
    weight the located P33 onset lies below the converged D0_b, which lies below the
    Newton limit -- the order "P33 onset, then D0_b, then the Newton limit" a reader must
    see.  The values drawn are the tables' (within their 6 printed digits)."""
    from validation.data.loads import newton_limits, p33_onsets

    fig, ax = plt.subplots()
    plot_breakdown_map(p33={"coupled": {1.0: 3.0}}, run_buckling={1.0: 2.9146},
                       run_mesh="10 x 1 x 5", ax=ax)
    order = _reference_order(ax, lambda a: a)
    assert set(order) == {0.3, 0.7, 1.0, 1.5}          # every weight with a P33 row
    for a, (onset, d0b, newton) in order.items():
        assert onset < d0b < newton, (a, onset, d0b, newton)
    assert {a: o for a, (o, _, _) in order.items()} == {a: d for a, d, _ in p33_onsets()}
    assert {a: n for a, (_, _, n) in order.items()} == {
        a: d for a, d, _ in newton_limits() if a in order}
    # the run's own P33 steps are labelled as this run's (the caption names its meshes,
    # one per model: the membrane's is not the 3D one's)
    labels = ax.get_legend_handles_labels()[1]
    assert any(lab.startswith(P33_BREAKDOWN.name) and lab.endswith(
        "3D fully coupled, this run (its meshes: the caption)") for lab in labels)
    plt.close(fig)


def test_the_keplinger_figure_draws_the_order_of_the_three_meanings():
    """The same order from uni-axial-ideal's reference layer, each point on its weight's
    homogeneous loading curve (x = lam1 of Eq. (DEuniax) at the point's D0)."""
    import analytic as an
    from analytic.units import keplinger_s

    fig, ax = plt.subplots()
    plot_uniaxial_wrinkling(fe=_fake_keplinger(), ax=ax)
    layers = [_drawn(ax, g) for g in ("p33-onset-located", "buckling-converged",
                                      "newton-limit")]
    m = an.NeoHookean()
    found = 0
    for a in (0.3, 0.7, 1.0, 1.5):
        s = float(keplinger_s(a, g=9.81))
        ys = []
        for pts in layers:
            on = [y for x, y in pts if np.isclose(float(an.uniaxial_lam1(y, s, m)), x,
                                                  rtol=1e-9)]
            ys.append(on[0] if on else None)
        if None in ys:
            continue
        found += 1
        assert ys[0] < ys[1] < ys[2], (a, ys)
    assert found == 4
    plt.close(fig)


# -- the lines: one role one look, by construction ------------------------------------------
_ROLE_WORDS = (  # a legend label that says a role must be drawn by the role's line
    (re.compile(r"det\s*\\?mathcal\{H\}|det H\*"), "det-H-locus"),
    (re.compile(r"^thin-plate limit"), "thin-plate-limit"),
    (re.compile(r"^thick-plate limit"), "thick-plate-limit"),
    (re.compile(r"^Stroh.*, symmetric$"), "symmetric-mode"),
    (re.compile(r"^Stroh.*, antisymmetric$"), "antisymmetric-mode"),
    (re.compile(r"^Newton limit over its meshes"), "newton-band"),
)


def _every_line_figure(tmp_path):
    """The axes of every figure the package draws with role lines: the seven cases'
    analytic figures, uni-axial-ideal with FE data, voltage-control, wrinkling-fe, the
    breakdown map, check's figures (a loading case and the clamped plate), buckling.png
    and post-buckling.png."""
    from validation.cases import CASES
    from validation.checker import check
    from validation.check_report import check_figure
    from validation.figures.case import case_figure
    from validation.studies.wrinkling import wrinkling_figure

    axes = []
    for name in CASES:
        try:
            axes += case_figure(name).axes
        except ValueError:                  # a case drawn from FE fields only
            continue
    fig, ax = plt.subplots()
    plot_uniaxial_wrinkling(fe=_fake_keplinger(), ax=ax)
    axes.append(ax)
    axes += list(voltage_figure(_voltage_rows()))
    rows = [["charge", mode, 1.5, kh, 4.0, 4.0, 0.0, "8x2", 0, 0, ""]
            for mode in ("symmetric", "antisymmetric") for kh in (0.5, 2.0)]
    axes += list(wrinkling_figure(rows, elastic=[["antisymmetric", 1.0, 0.95, 0.95, 0.0,
                                                   "8x4", ""]], quick=True))
    for case in check(DOCS / "examples" / "ex14_external_nh-d-e.csv").cases:
        axes += check_figure(case).axes
    axes += check_figure(_clamped_check(tmp_path).cases[0]).axes
    fig, ax = plt.subplots()
    plot_breakdown_map(p33={"coupled": {1.0: 3.0}}, run_buckling={1.0: 2.9146},
                       run_newton={0.3: 5.5}, run_mesh="10 x 1 x 5", ax=ax)
    axes.append(ax)
    axes += _study_figure_axes(tmp_path)
    return axes


def _clamped_check(tmp_path):
    """A check of clamped-plate rows: one state on the homogeneous curve and one D0_b
    beyond its tolerance."""
    from validation.checker import check

    s = float(keplinger_s(1.0, g=9.81))
    path = tmp_path / "clamped.csv"
    path.write_text("case,alpha,D0,lam1,D0_b\n"
                    f"uni-axial-ideal,1,1.0,{float(an.uniaxial_lam1(1.0, s)):.12g},2.9\n")
    return check(path)


def _study_figure_axes(tmp_path):
    """The axes of buckling.png and post-buckling.png drawn from a few rows."""
    import validation.studies.buckling as bk
    import validation.studies.postbuckling as pb

    from conftest import _buckling_figure_rows

    row, scan, plain = _buckling_figure_rows()
    summary = [{"alpha": 1.0, "model": m, "mesh": "10x1x5", "ndofs": n, "D0_b": 2.9}
               for m, n in (("3D", 900), ("membrane", 100))]
    rows = [{"alpha": 1.0, "mesh": "10x1x5", "model": m, "branch": b, "D0": d,
             "deflection": 0.1 * d, "lam1": 1.5 + 0.1 * d, "lam1_homogeneous": 1.5}
            for m in ("3D", "membrane") for b in ("buckled", "fundamental") for d in (3, 3.5)]
    figs = []
    for mod, draw in ((bk, lambda: bk.buckling_figure([row], scan, tmp_path,
                                                       tmp_path / "buckling.png",
                                                       plain=plain)),
                      (pb, lambda: pb.post_buckling_figure(summary, rows, tmp_path,
                                                           tmp_path / "post-buckling.png"))):
        real = mod.save_figure
        mod.save_figure = lambda fig, *a, **k: figs.append(fig)
        try:
            draw()
        finally:
            mod.save_figure = real
    return [ax for f in figs for ax in f.axes]


def _line_look(line) -> tuple:
    from matplotlib.colors import to_rgba

    return line.get_linestyle(), to_rgba(line.get_color())


def test_one_role_one_line_and_one_line_one_role_in_every_figure(tmp_path):
    """Every line of a role (det H* = 0, the thin- and thick-plate limits, the Newton band,
    the symmetric and antisymmetric Stroh curves) is drawn with its role's line in every
    figure, a label naming a role is never drawn without it, no two roles share a line,
    and no other line has a role's look (a dashed blue curve would read as the
    thick-plate limit; a dash-dotted one as an antisymmetric mode)."""
    from matplotlib.colors import to_rgba

    from validation.markers import LINES

    assert len({(r.style["ls"], r.style.get("color")) for r in LINES}) == len(LINES)
    by_gid = {r.gid: r for r in LINES}
    fixed = {(r.style["ls"], to_rgba(r.style["color"])): r.gid for r in LINES
             if "color" in r.style and r.style.get("lw", 1) < 3}
    seen, bad = {}, []
    for ax in _every_line_figure(tmp_path):
        for line in ax.lines:
            label, gid = str(line.get_label()), line.get_gid()
            if gid not in by_gid:
                look = _line_look(line)
                if look in fixed:
                    bad.append(f"{ax.get_title()!r}: {label!r} has the look of {fixed[look]}")
                if look[0] == "-.":
                    bad.append(f"{ax.get_title()!r}: {label!r} is dash-dotted, not a mode")
            for words, role in _ROLE_WORDS:
                if words.search(label) and gid != role:
                    bad.append(f"{ax.get_title()!r}: {label!r} drawn without the {role} line")
            if gid in by_gid:
                r = by_gid[gid]
                ls, color = _line_look(line)
                want = r.style["ls"]
                if {"--": "dashed", "-": "solid", ":": "dotted", "-.": "dashdot"}[want] != ls \
                        and want != ls:
                    bad.append(f"{ax.get_title()!r}: {gid} drawn {ls}, not {want}")
                if "color" in r.style and color != to_rgba(r.style["color"]):
                    bad.append(f"{ax.get_title()!r}: {gid} drawn in {color}")
                seen.setdefault(gid, set()).add(ls)
    assert not bad, "\n".join(bad)
    assert set(seen) == set(by_gid)                     # every role is drawn somewhere
    plt.close("all")


def test_the_explore_page_draws_the_roles_with_the_same_lines():
    pytest.importorskip("bokeh")
    from bokeh.document import Document
    from bokeh.models import GlyphRenderer, Line

    from validation.explore.app import build_page
    from validation.markers import (ANTISYMMETRIC_MODE, SYMMETRIC_MODE, THICK_PLATE_LIMIT,
                                    THIN_PLATE_LIMIT, VOLTAGE_LIMIT_LOCUS)

    doc = Document()
    build_page(doc)
    want = {"det H* = 0": VOLTAGE_LIMIT_LOCUS, THIN_PLATE_LIMIT.gid: THIN_PLATE_LIMIT,
            THICK_PLATE_LIMIT.gid: THICK_PLATE_LIMIT, "symmetric": SYMMETRIC_MODE,
            "antisymmetric": ANTISYMMETRIC_MODE}
    found = {}
    for r in doc.select({"type": GlyphRenderer}):
        if r.name in want and isinstance(r.glyph, Line):
            found.setdefault(r.name, []).append(r.glyph.line_dash)
    assert set(found) == set(want)
    for name, dashes in found.items():
        expect = Line(line_dash=want[name].dash).line_dash
        assert all(d == expect for d in dashes), (name, dashes, expect)


def test_the_explore_page_draws_the_reference_layer_in_order():
    """Panel (c) of the explore page at the paper's alpha = 1: the located P33 onset, the
    converged D0_b and the Newton limit of the shipped study, on the weight's curve, in
    the order the figures draw them, with the figures' legend names."""
    pytest.importorskip("bokeh")
    from bokeh.document import Document
    from bokeh.models import GlyphRenderer

    from validation.data.loads import converged_buckling_load, newton_limits, p33_onsets
    from validation.explore.app import build_page

    doc = Document()
    build_page(doc)
    got = {}
    for r in doc.select({"type": GlyphRenderer}):
        if r.name and r.name.startswith("reference-"):
            ys = list(r.data_source.data["y"])
            got[r.name.removeprefix("reference-")] = ys[0] if ys else None
    onset, d0b, newton = got["p33_onset"], got["D0_b"], got["newton_limit"]
    assert onset < d0b < newton
    assert onset == dict((a, d) for a, d, _ in p33_onsets())[1.0]
    assert d0b == converged_buckling_load(1.0).D0_b
    assert newton == dict((a, d) for a, d, _ in newton_limits())[1.0]


def test_the_newton_band_spans_every_mesh_with_a_limit():
    """The band of the breakdown map and of uni-axial-ideal runs, per weight, from the
    lowest to the highest Newton limit of the shipped rows that have one (read here from
    the CSV files themselves: the graded P33 rows and the finest uniform mesh), and the
    pages that list the markers describe it with its look and legend name."""
    import csv

    from validation.markers import NEWTON_BAND, NEWTON_BAND_LABEL

    data = Path(__file__).resolve().parents[2] / "validation" / "data"
    per: dict = {}
    with open(data / "clamp_p33.csv") as fh:
        for r in csv.DictReader(ln for ln in fh if not ln.startswith("#")):
            if r["newton_limit"]:
                per.setdefault(float(r["alpha"]), []).append(float(r["newton_limit"]))
    with open(data / "buckling_loads.csv") as fh:
        for r in csv.DictReader(ln for ln in fh if not ln.startswith("#")):
            col = [k for k in r if k.startswith("newton_limit_")][0]
            if r[col]:
                per.setdefault(float(r["alpha"]), []).append(float(r[col]))
    want = sorted((a, min(v), max(v)) for a, v in per.items() if max(v) > min(v))
    assert want == [(0.3, 2.5, 5.125)]                 # the one weight with two meshes
    fig, ax = plt.subplots()
    plot_breakdown_map(p33={"coupled": {1.0: 3.0}}, ax=ax)
    got = sorted((float(x[0]), float(min(y)), float(max(y))) for x, y in
                 ((ln.get_xdata(), ln.get_ydata()) for ln in ax.lines
                  if ln.get_gid() == NEWTON_BAND.gid))
    assert got == want
    fig, ax = plt.subplots()
    plot_uniaxial_wrinkling(fe=_fake_keplinger(), ax=ax)
    (band,) = [ln for ln in ax.lines if ln.get_gid() == NEWTON_BAND.gid]
    s = float(keplinger_s(0.3, g=9.81))
    y = band.get_ydata()
    assert (y.min(), y.max()) == (2.5, 5.125)
    np.testing.assert_allclose(band.get_xdata(), an.uniaxial_lam1(y, s, an.NeoHookean()),
                               rtol=1e-12)                      # on the weight's curve
    assert NEWTON_BAND_LABEL in [t.get_text() for t in ax.get_legend().get_texts()]
    name = NEWTON_BAND_LABEL.split(" (")[0]
    for page in ("breakdown.md", "gallery.md"):
        rows = [u for u in _units((DOCS / page).read_text()) if u.startswith("|")]
        assert any(f"`{name}`" in r and NEWTON_BAND.look in r for r in rows), page
    plt.close("all")


def test_check_draws_the_reference_layer_of_validate(tmp_path):
    """check's figure of clamped-plate rows draws the converged study as uni-axial-ideal
    does (the same points, drawn by the same function), and from its drawn layer the
    order P33 onset < D0_b < Newton limit holds for the checked weight."""
    from validation.check_report import check_figure

    (ax,) = check_figure(_clamped_check(tmp_path).cases[0]).axes
    fig, ref = plt.subplots()
    plot_uniaxial_wrinkling(fe=_fake_keplinger(), alphas=(1.0,), ax=ref, D0max=7.0)
    for gid in ("p33-onset-located", "buckling-converged", "newton-limit"):
        np.testing.assert_array_equal(_drawn(ax, gid), _drawn(ref, gid))
        assert len(_drawn(ax, gid)), gid
    s = float(keplinger_s(1.0, g=9.81))
    (diamond,) = [ln.get_xydata() for ln in ax.lines
                  if ln.get_gid() == "buckling-converged" and ln.get_marker() == "D"]
    onset, newton = (float(_drawn(ax, g)[0, 1]) for g in
                     ("p33-onset-located", "newton-limit"))
    d0b = float(diamond[0, 1])
    assert onset < d0b < newton
    assert d0b == buckling_loads()[[e.alpha for e in buckling_loads()].index(1.0)].D0_b
    assert float(diamond[0, 0]) == pytest.approx(
        float(an.uniaxial_lam1(d0b, s, an.NeoHookean())), rel=1e-12)
    plt.close("all")

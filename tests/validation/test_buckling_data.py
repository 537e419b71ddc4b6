"""The measured buckling loads (validation/data/buckling_loads.csv, the uniform meshes, and
validation/data/clamp_units.csv, the graded ones): the files, their loader, the Richardson
extrapolation behind the uniform file's extrapolated column, the docs table it feeds, and
the figures that draw the loads."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from validation.data.loads import (buckling_loads, buckling_provenance, converged_buckling_load, newton_limits, uniform_buckling_loads)
import validation.data.loads as bd
from validation.data.clamp_zone import clamp_unit_load
from validation.data.registry import load
from validation.studies.buckling import richardson

ROOT = Path(__file__).resolve().parents[2]
H = 1.0 / np.array([10.0, 14.0, 20.0])          # the study's meshes: ratios 1.4 and 1.43


@pytest.mark.parametrize("p", [1.0, 1.8, 3.0])
def test_richardson_recovers_a_power_law_on_unequal_ratios(p):
    # f(h) = a + b h^p on h = 1/10, 1/14, 1/20 (r1 = 1.4 != r2 = 1.43): the three-mesh
    # equation has the exact root p; the differences of the values (>= 1e-3) carry the
    # rounding of the values (1e-16) amplified by at most 1e3, so 1e-11 on a and 1e-9 on p
    a, b = 0.74, 3.2
    ext, err, order = richardson(H, a + b * H**p)
    assert abs(order - p) < 1e-9
    assert abs(ext - a) < 1e-11
    # the error estimate is the distance of the finest value from the limit: b h3^p
    assert err == pytest.approx(b * H[-1] ** p, rel=1e-9)


def test_richardson_equal_ratios_is_the_closed_form():
    # r1 = r2 = 2: p = log((v1 - v2)/(v2 - v3))/log 2 exactly (to rounding, 1e-12)
    h, v = np.array([0.4, 0.2, 0.1]), np.array([1.3, 1.1, 1.04])
    p = np.log(0.2 / 0.06) / np.log(2.0)
    ext, _, order = richardson(h, v)
    assert order == pytest.approx(p, rel=1e-12)
    assert ext == pytest.approx(1.04 - 0.06 / (2.0**p - 1), rel=1e-12)


def test_richardson_refuses_a_non_monotone_sequence_and_bad_meshes():
    ext, err, order = richardson(H, [4.2027, 3.9908, 4.4008])   # alpha = 1.5: no range
    assert np.isnan(ext) and np.isnan(order) and err == pytest.approx(0.41, abs=1e-12)
    with pytest.raises(ValueError, match="h must be positive and strictly descending"):
        richardson([0.1, 0.2, 0.05], [1.0, 2.0, 3.0])


def test_data_file_extrapolation_is_richardson_of_its_meshes():
    # the file's D0_b, error and order are richardson() of its three meshes, rounded to
    # the printed digits (4 decimals for loads and errors, 2 for the order)
    entries = uniform_buckling_loads()
    assert [e.alpha for e in entries] == [0.05, 0.3, 0.7, 1.0, 1.5]
    for e in entries:
        ext, err, order = richardson(H, e.D0_b_mesh)
        if e.converged:
            assert abs(ext - e.D0_b) <= 5e-5 + 1e-12
            assert abs(err - e.error) <= 5e-5 + 1e-12
            assert abs(order - e.order) <= 5e-3 + 1e-12
        else:
            assert np.isnan(ext) and np.isnan(e.D0_b)
    # alpha = 0.05 extrapolates to 0.744 (the finest mesh 0.7539, order 1.81)
    assert round(next(e for e in entries if e.alpha == 0.05).D0_b, 3) == 0.744


def test_a_weight_takes_the_graded_load_where_its_two_finest_meshes_agree():
    """buckling_loads() per weight: clamp_unit_load's verdict on the committed graded rows
    (the finest mesh's D0_b, error = the two finest meshes' difference but at least the
    location tolerance 1e-4, recomputed here from the rows), else the uniform file's entry
    unchanged."""
    uniform = {e.alpha: e for e in uniform_buckling_loads()}
    rows = load("units")
    for e in buckling_loads():
        mine = sorted((r for r in rows if r["D0_b"] and r["formulation"] == "mixed"
                       and float(r["alpha"]) == e.alpha), key=lambda r: int(r["dofs"]))
        try:
            clamp_unit_load(e.alpha)
        except ValueError:
            assert repr(e) == repr(uniform[e.alpha])        # nan-safe
            continue
        a, b = mine[-2:]
        assert e.source == "graded" and e.converged
        assert e.D0_b == float(b["D0_b"])
        assert e.error == pytest.approx(max(abs(float(b["D0_b"]) - float(a["D0_b"])), 1e-4),
                                        abs=1e-15)
        assert e.meshes == (f"{a['mesh']} g{a['grading']}", f"{b['mesh']} g{b['grading']}")
        assert float(a["elements_per_half_wave"]) >= 4
        if a["half_waves"] != b["half_waves"]:
            # the first crossings differ in class: a class located within 2e-4 of the
            # first on both meshes counts the same half-waves on both (class onsets)
            def near(r):
                mine = [q for q in load("onsets") if q["D0_c"] and (
                    q["alpha"], q["mesh"], q["grading"], q["formulation"]) == (
                    r["alpha"], r["mesh"], r["grading"], r["formulation"])]
                first = min(float(q["D0_c"]) for q in mine)
                assert abs(first - float(r["D0_b"])) <= 2e-4
                return {q["class"]: q["half_waves"] for q in mine
                        if float(q["D0_c"]) <= first + 2e-4}
            assert any(near(a).get(c) == n for c, n in near(b).items())
    # alpha = 1: the graded meshes resolve the clamp-zone wrinkle at 3.370, 0.53 above the
    # uniform meshes' extrapolation 2.840 (two elements per half-wave)
    g1 = converged_buckling_load(1.0)
    assert g1.source == "graded" and abs(g1.D0_b - 3.370) < 5e-4 and g1.error < 1e-3
    assert uniform[1.0].D0_b == 2.84


def test_provenance_names_command_meshes_solver_date_and_error():
    text = buckling_provenance()
    for word in ("command: skfem-dielectric buckling", "meshes:", "solver:", "date:",
                 "error estimate:"):
        assert word in text


def test_bad_alpha_names_the_alpha_and_the_converged_entries(monkeypatch):
    with pytest.raises(ValueError, match=r"alpha = 2 has no entry .*converged: alpha = "
                                         r"0\.05, 0\.3, 0\.7, 1, 1\.5"):
        converged_buckling_load(2.0)
    # the uniform meshes alone: alpha = 1.5 is not converged there
    monkeypatch.setattr(bd, "buckling_loads", uniform_buckling_loads)
    with pytest.raises(ValueError, match=r"alpha = 1\.5 has no converged buckling load.*"
                                         r"converged: alpha = 0\.05, 0\.3, 0\.7, 1; "
                                         r"not converged: alpha = 1\.5"):
        converged_buckling_load(1.5)


def _cell(x: float, digits: int) -> str:
    return f"{x:.{digits}f}"


def test_docs_table_agrees_with_the_data_file():
    text = (ROOT / "docs" / "validation.md").read_text()
    for e in uniform_buckling_loads():
        a = f"{e.alpha:g}"
        row = next(ln for ln in text.splitlines()
                   if ln.startswith(f"| {a} | ") and ln.count("|") == 10)
        cells = [c.strip() for c in row.strip("|").split("|")]
        assert cells[1:4] == [_cell(v, 4) for v in e.D0_b_mesh]
        if e.converged:
            assert cells[4] == (f"**{_cell(e.D0_b, 4)}** ({_cell(e.error, 4)}, "
                                f"{_cell(e.order, 2)})")
        else:
            assert cells[4] == "not converged"
        newton = cells[7]
        assert (newton == "none") == np.isnan(e.newton_limit)
        if not np.isnan(e.newton_limit):
            assert float(newton) == e.newton_limit


def _by_gid(ax, gid):
    return [ln for ln in ax.lines if ln.get_gid() == gid]


def test_breakdown_map_draws_each_meaning_where_the_data_put_it():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from validation.figures import plot_breakdown_map

    fig, ax = plt.subplots()
    p33 = {"coupled": {0.05: 0.5, 1.0: 3.0, 1.5: None}}
    plot_breakdown_map(p33=p33, run_buckling={1.0: 2.68}, run_newton={0.3: 5.5},
                       run_mesh="10 x 1 x 5", ax=ax)
    conv = [e for e in buckling_loads() if e.converged]
    # the converged loads: black diamonds at (alpha, D0_b), error bars of +- error
    (line,) = [ln for ln in _by_gid(ax, "buckling-converged") if ln.get_marker() == "D"]
    np.testing.assert_array_equal(line.get_xydata(), [[e.alpha, e.D0_b] for e in conv])
    (bars,) = [c for c in ax.collections if c.get_gid() == "buckling-converged"]
    half = [abs(s[1, 1] - s[0, 1]) / 2 for s in bars.get_segments()]
    np.testing.assert_allclose(half, [e.error for e in conv], rtol=0, atol=1e-12)   # rounding
    # each load's mesh values as dots (alpha = 1.5: its two graded meshes), a step left
    # of the weight so that the diamond (the finest mesh's value) does not hide them
    from validation.figures.breakdown_map import MESH_OFFSET

    dots = np.vstack([ln.get_xydata() for ln in _by_gid(ax, "buckling-mesh")])
    e15 = next(e for e in conv if e.alpha == 1.5)
    assert dots[np.isclose(dots[:, 0], 1.5 - MESH_OFFSET)][:, 1].tolist() == list(e15.D0_b_mesh)
    assert MESH_OFFSET >= 0.02                        # more than a diamond's half width
    # a weight without a converged load (the uniform meshes' alpha = 1.5): no diamond,
    # its three mesh values as dots
    fig2, ax2 = plt.subplots()
    plot_breakdown_map(loads=uniform_buckling_loads(), ax=ax2)
    (line2,) = [ln for ln in _by_gid(ax2, "buckling-converged") if ln.get_marker() == "D"]
    assert 1.5 not in line2.get_xdata()
    dots = np.vstack([ln.get_xydata() for ln in _by_gid(ax2, "buckling-mesh")])
    assert dots[np.isclose(dots[:, 0], 1.5 - MESH_OFFSET)][:, 1].tolist() == [
        4.2027, 3.9908, 4.4008]
    plt.close(fig2)
    # the P33 criterion as given (the None of alpha = 1.5 is not drawn), red open circles
    (p,) = _by_gid(ax, "p33-coupled")
    np.testing.assert_array_equal(p.get_xydata(), [[0.05, 0.5], [1.0, 3.0]])
    assert p.get_marker() == "o" and p.get_markerfacecolor() == "none"
    # the run's crosses and Newton limit, the loads' Newton limits: one per weight, the
    # graded mesh's of docs/breakdown.md's table where the weight has one (the one source
    # of both), else the uniform 20 x 1 x 10's
    np.testing.assert_array_equal(_by_gid(ax, "buckling-run")[0].get_xydata(), [[1.0, 2.68]])
    assert _by_gid(ax, "buckling-run")[0].get_marker() == "x"
    np.testing.assert_array_equal(_by_gid(ax, "newton-run")[0].get_xydata(), [[0.3, 5.5]])
    nl = [[a, d] for a, d, _ in newton_limits()]
    from validation.clamp_zone.tables import breakdown_numbers
    graded = [[r["alpha"], r["newton_limit"]] for r in breakdown_numbers()]
    assert nl == [[0.05, 3.91]] + graded                 # 0.05: the uniform 20 x 1 x 10's
    assert len({a for a, _ in nl}) == len(nl)
    np.testing.assert_array_equal(_by_gid(ax, "newton-limit")[0].get_xydata(), nl)
    # the homogeneous paths of s > 0 never reach the wrinkling limits (docs/wrinkling.md):
    # arrows at the top for every weight, no limit line
    assert not _by_gid(ax, "wrinkling-limit")
    np.testing.assert_array_equal(_by_gid(ax, "wrinkling-not-reached")[0].get_xdata(),
                                  [0.05, 0.3, 0.7, 1.0, 1.5])
    plt.close(fig)


def test_homogeneous_wrinkling_limit_on_the_paths():
    from validation.figures import homogeneous_wrinkling_D0

    # s = 0 (alpha = 0) is the thin-plate limit itself: reached at once; every s > 0 path
    # stays below both limits (docs/wrinkling.md: margin of the thin limit
    # D0^2 = thin^2 - lam^5 s > 0)
    assert homogeneous_wrinkling_D0(0.0)[0] == 0.0
    for a in (0.05, 1.0):
        assert all(np.isnan(homogeneous_wrinkling_D0(a)))
    with pytest.raises(ValueError, match="alpha must be >= 0, got -1"):
        homogeneous_wrinkling_D0(-1.0)



def test_fig5_draws_the_converged_loads_on_their_curves():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import analytic as an
    from analytic.units import keplinger_s
    from validation.figures import plot_uniaxial_wrinkling

    fe = {"run": np.array(["r"]), "alpha": np.array([1.0]), "variant": np.array(["coupled"]),
          "converged": np.array([True]), "breakdown": np.array([False]),
          "lam1_fe": np.array([3.2]), "lam1_analytic": np.array([3.2]), "D0": np.array([2.5])}
    fig, ax = plt.subplots()
    plot_uniaxial_wrinkling(fe=fe, ax=ax)
    conv = [e for e in buckling_loads() if e.converged]
    (line,) = [ln for ln in ax.lines if ln.get_gid() == "buckling-converged"
               and ln.get_marker() == "D"]
    # on the weight's homogeneous curve Eq. (DEuniax): lam1 = uniaxial_lam1(D0_b, s)
    want = [[an.uniaxial_lam1(e.D0_b, keplinger_s(e.alpha, g=9.81), an.NeoHookean()), e.D0_b]
            for e in conv]
    np.testing.assert_allclose(line.get_xydata(), want, rtol=1e-12)   # same closed form
    (nl,) = [ln for ln in ax.lines if ln.get_gid() == "newton-limit"]
    np.testing.assert_array_equal(nl.get_ydata(), [d for _, d, _ in newton_limits()])
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    err = max(e.error for e in conv)
    assert (f"buckling load, converged (error bar $\\leq {err:.2g}$, hidden by the diamond)"
            in labels)
    meshes = ", ".join(sorted({m for _, _, m in newton_limits()}))
    assert f"Newton limit, plain form ({meshes})" in labels and "20x1x10" in meshes
    plt.close(fig)


def test_the_clamp_study_tables_on_the_page_are_the_data_files():
    """docs/clamp-zone.md shows clamp_study_tables() verbatim (regenerate with
    skfem-dielectric clamp-zone tables), and the tables carry every located unit."""
    from validation.clamp_zone.tables import clamp_study_tables

    text = (ROOT / "docs" / "clamp-zone.md").read_text()
    a = "<!-- clamp-study-tables: generated by skfem-dielectric clamp-zone tables -->\n"
    b = "<!-- end clamp-study-tables -->"
    shown = text[text.index(a) + len(a):text.index(b)].strip("\n") + "\n"
    tables = clamp_study_tables()
    assert shown == tables
    located = [r for r in load("units") if r["D0_b"]]
    first = tables.split("\n\n")[0].splitlines()[2:]
    assert len(first) == len(located)
    for r, line in zip(sorted(located, key=lambda r: (float(r["alpha"]),
                                                      r["formulation"] != "mixed",
                                                      r["formulation"], int(r["dofs"]))), first):
        assert f"| {float(r['D0_b']):.4f} |" in line and r["mesh"] in line


def test_richardson_over_the_graded_family_of_alpha_1():
    """alpha = 1 on the family refined alike in both directions (graded 0.1, n3 = 1.2 n1:
    20x1x24, 30x1x36, 40x1x48): the three located loads converge monotonically and their
    Richardson limit (h = 1/n1) lies within the location tolerance 1e-4 of the finest and
    of clamp_unit_load(1) (docs/clamp-zone.md)."""
    rows = {r["mesh"]: float(r["D0_b"]) for r in load("units") if r["alpha"] == "1"
            and r["grading"] == "0.1" and r["formulation"] == "mixed" and r["D0_b"]}
    v = [rows[m] for m in ("20x1x24", "30x1x36", "40x1x48")]
    assert v[0] < v[1] < v[2]
    ext, err, order = richardson([1 / 20, 1 / 30, 1 / 40], v)
    assert abs(ext - v[2]) <= 1e-4 and err <= 1e-4
    assert abs(ext - clamp_unit_load(1.0)["D0_b"]) <= 1e-4

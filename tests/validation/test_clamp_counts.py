"""Negative-mode counts without eigenpairs (validation.clamp_zone.counts): the counts of
one ramp equal those of a clamp-zone unit's full scan, state by state; bad input is one
line."""

from __future__ import annotations

import pytest

from validation.clamp_zone.counts import CLASS_COLUMNS, COLUMNS, run_counts
from validation.data.clamp_zone import scan_states, unit_row
from validation.data.registry import load
from validation.data.key import UnitKey


@pytest.mark.slow
def test_the_counts_equal_the_units_full_scan():
    """alpha = 1, 10 x 1 x 24 graded 0.1: the unit's scan (every negative mode computed and
    classified) counted 38 negative modes at D0 = 2.5 and 100 at D0 = 3 (its
    ``scan_counts``); Sylvester's counts of one ramp give the same integers."""
    unit = unit_row(UnitKey(1.0, (10, 1, 24), 0.1))
    scanned = {d: n for d, n, _ in scan_states(unit)}
    rows = run_counts(UnitKey(1.0, (10, 1, 24), 0.1), [2.5, 3.0])
    assert [r["D0"] for r in rows] == [2.5, 3.0]
    for r in rows:
        assert r["n_negative"] == scanned[r["D0"]]
        assert r["n_negative"] == sum(r[c] for c in CLASS_COLUMNS)
        assert r["dofs"] == int(unit["dofs"])
    assert set(rows[0]) >= set(COLUMNS) - {"command"}


def test_the_committed_rows_count_the_whole_spectrum():
    """Every committed row: its class counts add up to its total, and the x2 A classes
    (bending) to its n_x2A."""
    rows = load("counts")
    assert rows
    for r in rows:
        counts = {c: int(r[c]) for c in CLASS_COLUMNS}
        assert sum(counts.values()) == int(r["n_negative"])
        assert sum(v for c, v in counts.items() if c[1] == "A") == int(r["n_x2A"])




def test_the_second_pressure_space_counts_one_pressure_per_element():
    """With ``pressure="P0"`` the plate has one pressure unknown per element instead of one
    per vertex: 4 x 1 x 6 has 24 elements and 5 * 2 * 7 = 70 vertices, so 46 unknowns
    fewer; its counts add up over the classes as the Taylor-Hood ones do."""
    q1 = run_counts(UnitKey(1.0, (4, 1, 6), 0.1), [2.5])
    p0 = run_counts(UnitKey(1.0, (4, 1, 6), 0.1), [2.5], pressure="P0")
    assert q1[0]["dofs"] - p0[0]["dofs"] == 70 - 24
    assert p0[0]["pressure"] == "P0" and q1[0]["pressure"] == "Q1"
    assert p0[0]["n_negative"] == sum(p0[0][c] for c in CLASS_COLUMNS)


def test_the_alpha_1_5_counts_on_the_page_are_the_table_s():
    """docs/breakdown.md states the alpha = 1.5 counts of four meshes: each sentence
    ``N1 x N2 x N3 has a, b and c negative modes at D0 = 4, 4.5 and 4.75`` equals the
    shipped rows (Q1, graded 0.1), and each of those rows is antisymmetric in x2."""
    import re
    from pathlib import Path

    page = (Path(__file__).resolve().parents[2] / "docs" / "breakdown.md").read_text()
    said = re.findall(r"(\d+) x (\d+) x (\d+) has (\d+), (\d+) and (\d+) negative modes at "
                      r"`D0` = 4, 4\.5 and 4\.75", " ".join(page.split()))
    assert len(said) == 4, said
    rows = {(r["mesh"], float(r["D0"])): r for r in load("counts")
            if r["alpha"] == "1.5" and r["pressure"] == "Q1" and r["grading"] == "0.1"}
    for n1, n2, n3, *counts in said:
        mesh = f"{n1}x{n2}x{n3}"
        for D0, n in zip((4.0, 4.5, 4.75), counts):
            r = rows[(mesh, D0)]
            assert int(r["n_negative"]) == int(n), (mesh, D0)
            assert int(r["n_x2A"]) == int(n), (mesh, D0)


def test_a_paused_ramp_resumes_to_the_same_counts(tmp_path):
    """A budget of a millisecond pauses the counts ramp after its first reached target,
    its state kept in the checkpoint; each call continues from there, and the counts of
    the paused-and-resumed ramp equal those of one uninterrupted ramp, state by state
    (the resumed ramp restarts on the same state, secant point and factors)."""
    from validation.clamp_zone.counts import CountsPaused
    from validation.clamp_zone.units import COUNT_PRELOAD_STEPS

    key = UnitKey(1.0, (4, 1, 6), 0.1)
    whole = run_counts(key, [1.0, 1.5])
    ck = tmp_path / "ck.npz"
    rows, pauses = [], 0

    def keep(r):                              # the caller's table: the rows as they come
        rows.append(r)

    while True:
        try:
            run_counts(key, [1.0, 1.5], skip={r["D0"] for r in rows}, checkpoint=ck,
                            budget=1e-3, on_row=keep)
            break
        except CountsPaused as exc:
            pauses += 1
            assert ck.is_file() and exc.checkpoint == ck
            assert pauses < 40
    # the pre-load's targets (COUNT_PRELOAD_STEPS = 6) and the charge targets 0.5, 1 and
    # 1.5: one pause per target but the last
    assert COUNT_PRELOAD_STEPS == 6 and pauses == 6 + 3 - 1
    assert not ck.exists()                     # a finished unit keeps no state
    assert [r["D0"] for r in rows] == [r["D0"] for r in whole] == [1.0, 1.5]
    for a, b in zip(rows, whole):
        assert {c: a[c] for c in CLASS_COLUMNS} == {c: b[c] for c in CLASS_COLUMNS}
        assert a["n_negative"] == b["n_negative"] and a["dofs"] == b["dofs"]


def test_a_budget_must_be_positive():
    with pytest.raises(ValueError, match="budget must be positive and finite, got 0"):
        run_counts(UnitKey(1.0, (2, 1, 2), 1.0), [1.0], budget=0)


def test_the_verdict_s_numbers_are_the_tables():
    """Every number of the verdicts of docs/breakdown.md on alpha = 1 and 1.5 that comes
    from a table is generated here from the shipped rows and found on the page: the
    section band's first wavenumbers (3 significant digits), the Q1 and P0 counts, the
    finest mesh's unknowns and the onset brackets of the thickness-refined meshes."""
    from pathlib import Path

    from validation.clamp_zone.band import band_onsets

    page = " ".join((Path(__file__).resolve().parents[2] / "docs" / "breakdown.md")
                    .read_text().split())
    bands = band_onsets(load("section"))

    def ks(alpha, D0, gd=10.0, pressure="Q1"):
        by_h = bands[(alpha, D0, "40x1x36", 0.1, gd, pressure)]
        return [f"{by_h[h][0]:.3g}" for h in sorted(by_h, reverse=True)]
    assert f"{', '.join(ks(1.0, 3.25)[:2])} and {ks(1.0, 3.25)[2]}/mm" in page
    assert f"{', '.join(ks(1.0, 2.5)[:2])} and {ks(1.0, 2.5)[2]}/mm at 2.5" in page
    assert f"stops receding ({ks(1.0, 3.25, gd=100.0)[-1]}/mm)" in page
    for D0 in (3.5, 4.0, 4.5):
        assert set(ks(1.5, D0)) == {"9.27"}
    assert set(ks(1.5, 3.5, pressure="P0")) == {"9.27"}
    assert "from 9.267/mm" in page

    counts = {(r["alpha"], r["mesh"], r["pressure"], float(r["D0"])): int(r["n_negative"])
              for r in load("counts") if r["grading"] == "0.1"}
    assert (f"20 x 1 x 24: {counts[('1', '20x1x24', 'Q1', 3.25)]} negative modes with Q1, "
            f"the corner quartet's {counts[('1', '20x1x24', 'P0', 3.25)]} with P0") in page
    q1 = [counts[("1.5", "30x1x36", "Q1", d)] for d in (4.0, 4.5)]
    p0 = [counts[("1.5", "30x1x36", "P0", d)] for d in (4.0, 4.5)]
    assert (f"30 x 1 x 36: {q1[0]} and {q1[1]} at `D0` = 4 and 4.5 with Q1, {p0[0]} and "
            f"{p0[1]} with P0") in page
    (dofs,) = {r["dofs"] for r in load("counts") if r["mesh"] == "70x4x36"}
    assert f"70 x 4 x 36, {int(dofs):,} unknowns: negative from between 4 and 4.5" in page

    def bracket(mesh):
        n = [counts[("1.5", mesh, "Q1", d)] for d in (4.0, 4.5, 4.75)]
        return "between 4 and 4.5" if n[0] == 0 < n[1] else \
            "between 4.5 and 4.75" if n[1] == 0 < n[2] else None
    assert f"50 x 2 x 36: {bracket('50x2x36')}; 70 x 2 x 36: {bracket('70x2x36')}" in page
    other = " ".join((Path(__file__).resolve().parents[2] / "docs" / "clamp-zone.md")
                     .read_text().split())
    n = [counts[("1.5", "70x4x36", "Q1", d)] for d in (4.0, 4.5, 4.75)]
    spaced = f"{int(dofs):,}".replace(",", " ")
    assert (f"70 x 4 x 36 ({spaced} unknowns) has {n[1]} and {n[2]} negative modes at "
            f"`D0` = 4.5 and 4.75") in other and n[0] == 0

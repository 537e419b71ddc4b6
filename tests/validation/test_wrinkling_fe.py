"""`skfem-dielectric wrinkling-fe`: FE bifurcations of the section against Stroh."""

from __future__ import annotations

import math

import analytic as an
from validation.cli import main
from validation.store import StudyStore
from validation.table import read_table
import validation.studies.wrinkling as wr
from validation.studies.wrinkling import ELASTIC_COLUMNS, WRINKLING_COLUMNS


def test_quick_grid_matches_the_dispersion_relation(tmp_path, capsys):
    assert main(["wrinkling-fe", "--quick", "--out", str(tmp_path)]) == 0
    t = read_table(tmp_path / "wrinkling-fe.csv")
    assert list(t) == WRINKLING_COLUMNS
    assert (tmp_path / "wrinkling-fe.png").stat().st_size > 10_000
    assert (tmp_path / "wrinkling-fe.pdf").stat().st_size > 10_000
    rows = 0
    for i in range(len(t["lam"])):
        if t["note"][i] == "no root of the dispersion relation":
            # the symmetric mode at kh = 0.5, lam = 1.5 under charge control has no root
            assert math.isnan(t["D0_stroh"][i]) and math.isnan(t["D0_fe"][i])
            continue
        rows += 1
        # quick grid: 8 Q2 elements per half-wave; the harness' quick tolerance is 3e-3
        # (measured <= 7e-5 on this grid)
        assert abs(t["D0_fe"][i] / t["D0_stroh"][i] - 1) <= 3e-3, (
            t["control"][i], t["mode"][i], t["kh"][i], t["note"][i])
        # the count is consistent with the layout (a negative count would mean that the
        # multiplier blocks carry fewer negative eigenvalues than unknowns), and there is no
        # spurious negative eigenvalue below the continuum's onset: at the lower bracket end
        # 0.95 D0_stroh the FE count may not exceed the Fourier modes n = 1..16 of the
        # section's classes that the Stroh analysis finds unstable there (validation side,
        # analytic.critical_D0); the mesh resolves those at best
        assert 0 <= t["n_negative_below"][i] <= t["n_stroh_below"][i], (
            t["control"][i], t["mode"][i], t["kh"][i])
        # and where 0.95 D0_stroh lies below the thick-plate limit every shorter wave is
        # stable too: an independent bound from the closed form
        lo = 0.95 * t["D0_stroh"][i]
        if t["control"][i] == "charge" and lo < an.thick_limit_D0(t["lam"][i]):
            assert t["n_negative_below"][i] == 0
    assert rows == 7
    # the uncharged plate in compression: the critical stretch of the flexural mode at
    # kh = 1 (Euler-like) and kh = 20 (near the thick-plate limit 0.666), against the
    # root of the dispersion relation; the 1e-3 (measured 1.3e-4, 1.4e-4)
    el = read_table(tmp_path / "wrinkling-fe-elastic.csv")
    assert list(el) == ELASTIC_COLUMNS
    assert list(el["kh"]) == [1.0, 20.0]
    for i in range(2):
        assert abs(el["lam_fe"][i] / el["lam_stroh"][i] - 1) <= 1e-3, el["kh"][i]
        assert 0.666 < el["lam_stroh"][i] < 1.0


def test_wrinkling_rows_resume_from_the_csv(tmp_path, monkeypatch):
    # the FE row is replaced by a cheap stand-in that records its calls: what is tested is
    # the bookkeeping (an interrupted run keeps its rows, a rerun computes only the rest)
    calls = []

    def fake_row(control, mode, lam, kh, n1):
        calls.append((control, mode, lam, kh))
        if kh == 2.0 and mode == "symmetric":         # no value: an empty cell
            return [control, mode, lam, kh, float("nan"), 1.0, float("nan"), f"{n1}x2",
                    0, 0, "no FE root"]
        return [control, mode, lam, kh, 1.0 + lam * kh / 7, 1.0, lam * kh / 7, f"{n1}x2",
                0, 0, ""]

    monkeypatch.setattr(wr, "_row", fake_row)
    path = tmp_path / "wrinkling-fe.csv"
    notes = []

    def rows():
        with StudyStore(tmp_path, "wrinkling-fe", {"quick": True, "n1": 8}, wr.TABLE,
                        plan=wr._grid_keys(True), note=notes.append) as store:
            return wr.wrinkling_rows(quick=True, store=store)

    first = rows()
    n = len(first)
    assert len(calls) == n == 8      # 2 controls x 2 modes x 1 lam x 2 kh
    text = path.read_text()
    lines = text.splitlines()
    assert len(lines) == n + 1       # header and every row
    assert "nan" not in text
    assert [r[4] for r in first if r[-1]] == [None, None]             # read back as empty
    # the cells written: 1 + lam kh / 7 with 10 significant digits
    assert [r[4] for r in first if not r[-1]] == [
        float(f"{1 + lam * kh / 7:.10g}") for _, m, lam, kh in wr._grid_keys(True)
        if not (kh == 2.0 and m == "symmetric")]
    t = read_table(path)
    assert [math.isnan(v) for v in t["D0_fe"]] == [note == "no FE root" for note in t["note"]]
    path.write_text("\n".join(lines[:-3]) + "\n")    # a run killed three rows early
    calls.clear()
    again = rows()
    assert len(calls) == 3 and again == first and notes == []
    assert path.read_text() == text
    path.write_text("control,mode,other\nx,y,z\n")   # another file: recomputed
    calls.clear()
    assert rows() == first and len(calls) == n
    assert notes == [f"{path} has other columns than {', '.join(wr.WRINKLING_COLUMNS)}; its "
                     f"results are discarded and recomputed (their rows kept in "
                     f"{path.name}.damaged)"]
    # the row of the other file is not lost: it is in the side file, after its line
    assert (path.parent / f"{path.name}.damaged").read_text().splitlines()[1:] == ["x,y,z"]


def test_the_mode_near_zero_is_the_mode_of_the_full_search():
    # the root searches take the mode's eigenvalue from the k eigenvalues nearest to zero
    # (one factorisation) and fall back to the full search; near the bifurcation both
    # must give the same eigenpair.  Section of the symmetric mode, lam = 1.5, kh = 2
    # (8 to 10 negative eigenvalues of other modes lie below it there, one at -6.5e-3 next
    # to its -1.1e-4), at 0.999 and 1.001 of its located critical charge.
    import numpy as np

    import skfem_dielectric as fe
    from skfem_dielectric.studies.wrinkling_fe import _mode_near_zero, section_mode_eigenvalue

    ref = float(an.critical_D0(1.5, 2.0, mode="symmetric"))
    pb = fe.studies.wrinkling_section(1.5, 2.0, "symmetric", "charge", n1=8, n2=9)
    crit = fe.studies.section_critical_load(pb, "symmetric", 0.95 * ref, 1.05 * ref)
    x = pb.initial_state()
    for f in (0.999, 1.001):
        load = np.array([0.0, 0.0, f * crit.load])
        res = fe.ramp(pb, [load], x0=x, start=np.zeros(3),
                      settings=fe.RampSettings(atol=1e-10, rtol=1e-11))
        x = res.x
        near = _mode_near_zero(pb, x, load, "symmetric")
        full, n_neg, _ = section_mode_eigenvalue(pb, x, load, "symmetric")
        # one eigenvalue of one matrix by two shift-invert Lanczos runs (ARPACK tol 1e-12
        # and 1e-10 on 1/(lambda - sigma)): equal to 1e-8 of the eigenvalue scale
        assert abs(near - full) <= 1e-8 * max(1.0, abs(full)), (f, near, full)
        # the sign changes across the located load, as the root search needs
        assert (near > 0) == (f < 1.0)
        assert n_neg >= 7


def test_caption_gives_the_run_and_the_mesh_range():
    rows = [["charge", "symmetric", 1.5, 2.0, 5.4, 5.4, 0.0, "8x30", 0, 0, ""],
            ["charge", "antisymmetric", 1.5, 0.5, 3.3, 3.3, 0.0, "8x2", 0, 0, ""]]
    text = wr.wrinkling_caption(rows, quick=True)
    assert text == ("Paper Sec. 3 (Stroh dispersion relation). Quick run; meshes: "
                    "2D cross-section: 8 x 2 to 8 x 30 elements (per half-wave x modelled "
                    "thickness).")
    assert wr.wrinkling_caption([], quick=None).endswith("FE run; meshes: unknown.")


def test_a_cut_last_row_is_recomputed_with_a_note_naming_the_file(tmp_path, monkeypatch,
                                                                  capsys, fake_wrinkling):
    """docs/cli.md (the result folder): a last row cut short (no line end) is dropped and
    recomputed, with one line on stderr naming the file, and a resumed run says how many
    rows it kept; validate --case wrinkling-fe and the wrinkling-fe command alike.  The FE
    rows are cheap stand-ins of the real ones."""
    import json

    calls = fake_wrinkling(monkeypatch)
    out = tmp_path / "res"
    argv = ["validate", "--quick", "--case", "wrinkling-fe", "--out", str(out),
            "--no-progress"]
    assert main(argv) == 0
    capsys.readouterr()
    path = out / "wrinkling-fe.csv"
    ref = path.read_bytes()
    assert len(calls) == 10
    path.write_bytes(ref[:-9])                        # the last row cut short
    calls.clear()
    assert main(argv) == 0
    err = capsys.readouterr().err
    note = (f"skfem-dielectric: {path}: its last row is incomplete (no line end); kept "
            f"aside in {path.name}.damaged")
    elastic = out / "wrinkling-fe-elastic.csv"
    assert err.splitlines() == [
        note, f"skfem-dielectric: {path}: kept 7 of 8 rows of an earlier run",
        f"skfem-dielectric: {elastic}: kept 2 of 2 rows of an earlier run"]
    assert calls == [("voltage", "antisymmetric", 1.5, 2.0)]    # only that row recomputed
    assert path.read_bytes() == ref
    summary = json.loads((out / "summary.json").read_text())["cases"]["wrinkling-fe"]
    assert summary["repairs"] == [note.removeprefix("skfem-dielectric: ")]
    assert summary["resumed_steps"] == 9
    # the command wrinkling-fe: the same note for its second CSV
    ref = elastic.read_bytes()
    elastic.write_bytes(ref[:-3])
    calls.clear()
    assert main(["wrinkling-fe", "--quick", "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert err.splitlines() == [f"skfem-dielectric: {elastic}: its last row is incomplete "
                                f"(no line end); kept aside in {elastic.name}.damaged",
                                f"skfem-dielectric: {path}: kept 8 of 8 rows of an earlier run",
                                f"skfem-dielectric: {elastic}: kept 1 of 2 rows of an earlier "
                                f"run"]
    assert calls == [("antisymmetric", 20.0)]
    assert elastic.read_bytes() == ref

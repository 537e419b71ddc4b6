"""``skfem-dielectric clamp-zone``: its tables cannot lose or double a row (a lock per
table, damaged rows named and recomputed, another table refused), inputs are refused
before anything is allocated, every bad value is one line and a documented exit code, and
units farmed to a dask LocalCluster give the serial run's rows."""

from __future__ import annotations

import math
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import validation.clamp_zone.cli as zone_cli
from validation.cli import main
from validation.data.registry import TABLES, load
from validation.data.key import UnitKey

ROOT = Path(__file__).resolve().parents[2]
#: the smallest unit: alpha = 1 on 6 x 1 x 3 graded 0.5, charge steps of 1 (about 3 CPU s)
SMALL = ["--alpha", "1", "--mesh", "6x1x3", "--grading", "0.5", "--D0-step", "1",
         "--solver", "superlu"]
#: the columns of a unit's row that are physics (no cost, date or command)
PHYSICS = ("alpha", "mesh", "grading", "formulation", "dofs", "D0_step", "D0_b", "class",
           "corner_share", "mesh_scale", "half_waves", "elements_per_half_wave",
           "J_min_clamp", "J_max_clamp", "n_flagged_b", "states", "scan_counts", "note")


def _exit(argv) -> int:
    """The exit code of the console script (argparse's errors exit from ``main``)."""
    try:
        return main(argv)
    except SystemExit as exc:
        return exc.code


def _units(out: Path, capsys, *extra) -> tuple[int, str, str]:
    code = main(["clamp-zone", "units", *SMALL, *extra, "--out", str(out)])
    got = capsys.readouterr()
    return code, got.out, got.err


@pytest.fixture(scope="module")
def small_run(tmp_path_factory):
    """One run of the smallest unit: its folder (the table and the mode)."""
    out = tmp_path_factory.mktemp("small") / "run"
    assert main(["clamp-zone", "units", *SMALL, "--out", str(out)]) == 0
    return out


def test_a_run_writes_the_row_and_the_mode_and_a_rerun_keeps_them(small_run, tmp_path, capsys):
    """The row's D0_b equals the mode file's; the table declares itself; a rerun of the
    same command leaves the table byte for byte and says 'kept'."""
    (row,) = load("units", small_run)
    key = UnitKey.from_row(row)
    with np.load(small_run / "modes" / f"{key.stem}.npz") as z:
        assert math.isclose(float(z["D0_b"]), float(row["D0_b"]), rel_tol=1e-5)
    text = (small_run / "clamp_units.csv").read_text()
    assert text.startswith("# clamp-zone table: units\n")
    out = tmp_path / "again"
    out.mkdir()
    (out / "clamp_units.csv").write_text(text)
    code, stdout, _ = _units(out, capsys)
    assert code == 0 and "alpha = 1 6x1x3 grading 0.5: kept" in stdout
    assert (out / "clamp_units.csv").read_text() == text


def test_a_second_writer_is_refused_naming_the_holder(tmp_path, capsys):
    """Another process holds the units table of --out: the run ends with exit 2 and one
    line naming that process, and the table is untouched."""
    out = tmp_path / "run"
    holder = subprocess.Popen(
        [sys.executable, "-c", textwrap.dedent(f"""
            import sys, time
            from validation.data.registry import TABLES
            from validation.store import TableWriter
            with TableWriter({str(out / 'clamp_units.csv')!r}, TABLES["units"]):
                print("held", flush=True)
                time.sleep(60)
        """)], cwd=ROOT, stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "held"
        code, _, err = _units(out, capsys)
        assert code == 2 and err.count("\n") == 1, err
        assert f"pid {holder.pid}" in err and "being written by another process" in err
        assert not (out / "clamp_units.csv").exists()
    finally:
        holder.kill()
        holder.wait()


@pytest.mark.parametrize("damage, why", [
    (lambda t: t.rstrip("\n"), "is incomplete (no line end)"),
    (lambda t: t.replace(",mixed,", ",mixed,extra,", 1), "has 25 cells, the header 24"),
    (lambda t: t.replace("\n1,6x1x3,0.5,mixed,854,1,", "\n1,6x1x3,0.5,mixed,854,one,"),
     "has 'one' in the number column 'D0_step'"),
])
def test_a_damaged_row_is_named_and_recomputed(small_run, tmp_path, capsys, damage, why):
    """A row cut short, with a cell too many or text in a number column: the run names
    the file and the line, leaves the row out and computes the unit again; the new row's
    physics equals the undamaged one's."""
    good = (small_run / "clamp_units.csv").read_text()
    out = tmp_path / "run"
    out.mkdir()
    bad = damage(good)
    assert bad != good
    (out / "clamp_units.csv").write_text(bad)
    code, stdout, _ = _units(out, capsys)
    assert code == 0
    line = len(good.splitlines())
    assert f"clamp_units.csv: line {line} {why}; left out" in stdout, stdout
    (new,) = load("units", out)
    (old,) = load("units", small_run)
    assert all(new[c] == old[c] for c in PHYSICS), [c for c in PHYSICS if new[c] != old[c]]


def test_a_repeated_key_is_one_row(small_run, tmp_path, capsys):
    """The same unit written twice (two runs that raced before the lock existed): the
    second row is named and left out, so a load is never one mesh compared with itself."""
    text = (small_run / "clamp_units.csv").read_text()
    out = tmp_path / "run"
    out.mkdir()
    (out / "clamp_units.csv").write_text(text + text.splitlines(keepends=True)[-1])
    code, stdout, _ = _units(out, capsys)
    assert code == 0 and "repeats the key 1, 6x1x3, 0.5, mixed; left out" in stdout
    assert "kept" in stdout and len(load("units", out)) == 1


@pytest.mark.parametrize("content", [
    "alpha,mesh,D0_b\n1,2x1x2,3\n",                                  # no declaration
    "# clamp-zone table: layer\nalpha,mesh\n",                       # another table
    "# clamp-zone table: units\nalpha,mesh,grading\n1,2x1x2,0.5\n",  # other columns
])
def test_another_table_is_refused_and_left_as_it_is(tmp_path, capsys, content):
    out = tmp_path / "run"
    out.mkdir()
    (out / "clamp_units.csv").write_text(content)
    code, _, err = _units(out, capsys)
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err
    assert "is not the clamp-zone units table" in err or "other columns" in err
    assert (out / "clamp_units.csv").read_text() == content


def test_a_mesh_too_large_is_refused_before_anything_is_allocated(tmp_path, capsys,
                                                                 monkeypatch):
    """100 x 10 x 100 (100,000 elements): one line naming --max-elements, exit 2, no plate
    built and nothing written; with the bound raised it is still refused, by its
    estimated memory (1.8 GB per 1000 elements: 180 GB) against the machine's; a mesh
    above the bound that fits in memory goes through to the (here replaced) runner."""
    from validation.clamp_zone.costs import estimated_GB

    def no_plate(*a, **k):
        raise AssertionError("a plate was built")

    monkeypatch.setattr(zone_cli, "run_unit", no_plate)
    out = tmp_path / "run"
    code = main(["clamp-zone", "units", "--alpha", "1", "--mesh", "100x10x100",
                 "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert "--mesh 100x10x100 has 100000 elements, more than --max-elements 5000" in err
    monkeypatch.setattr(zone_cli, "physical_GB", lambda: 24.0)
    code = main(["clamp-zone", "units", "--alpha", "1", "--mesh", "100x10x100",
                 "--max-elements", "100000", "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert estimated_GB(100_000) == pytest.approx(180.3)
    assert ("--mesh 100x10x100 needs about 180 GB of memory (100000 elements), more than "
            "this machine's 24 GB") in err
    assert not out.exists()
    calls = []
    monkeypatch.setattr(zone_cli, "run_unit", lambda *a, **k: calls.append(a) or {})
    with pytest.raises(Exception):
        main(["clamp-zone", "units", "--alpha", "1", "--mesh", "60x2x50",
              "--max-elements", "6000", "--out", str(out)])
    assert calls and calls[0][0].mesh == (60, 2, 50)           # the unit's key


BAD = {
    "units": [("--alpha", v) for v in ("-1", "0", "nan", "inf", "x")]
    + [("--mesh", v) for v in ("0x1x1", "6x1", "axbxc", "-2x1x1", "")]
    + [("--grading", v) for v in ("0", "-1", "nan", "1e9", "x")]
    + [("--D0-step", v) for v in ("0", "-1", "nan", "1e-9")]
    + [("--D0-max", v) for v in ("0", "-1", "nan", "inf")]
    + [("--formulation", "plain"), ("--solver", "mumps"), ("--out", ""),
       ("--max-elements", "0"), ("--jobs", "0"), ("--scheduler", ""),
       ("--scheduler", "udp://h:1")],
    "onsets": [("--alpha", "nan"), ("--mesh", "2x2"), ("--bracket", "2 1"),
               ("--bracket", "0 1"), ("--bracket", "1 nan")],
    "layer": [("--mesh", "1x1x1"), ("--grading", "inf")],
    "p33": [("--D0-step", "0"), ("--D0-max", "nan"), ("--alpha", "-0.5")],
    "flagged": [("--D0", "-1"), ("--D0", "nan"), ("--D0", "x")],
    "counts": [("--D0", "0"), ("--grad-div", "-1"), ("--grad-div", "nan"),
               ("--pressure", "P1")],
    "section": [("--D0", "inf"), ("--D0", "-1"), ("--h0", "0"), ("--h0", "6"), ("--k", "-1"),
                ("--length", "0"), ("--mesh", "40x1"), ("--mesh", "1000x10x100")],
    "voltage": [("--alpha", "inf"), ("--mesh", "4x1"), ("--grading", "0"), ("--jobs", "0"),
                ("--grad-div", "-1"), ("--grad-div", "nan"),
                ("--scheduler", "udp://h:1")],
    "tables": [("--from", "missing")],
    "band": [("--from", "missing")],
    "modes": [("--from", "missing")],
}
GOOD = {"units": ["--alpha", "1", "--mesh", "4x1x2"],
        "onsets": ["--alpha", "1", "--mesh", "4x1x2"],
        "layer": ["--alpha", "1", "--mesh", "4x1x2"],
        "p33": ["--alpha", "1", "--mesh", "4x1x2"],
        "flagged": ["--alpha", "1", "--mesh", "4x1x2", "--D0", "1"],
        "counts": ["--alpha", "1", "--mesh", "4x1x2", "--D0", "1"],
        "section": ["--alpha", "1", "--D0", "1"],
        "voltage": ["--alpha", "1", "--mesh", "4x1x2"],
        "tables": [], "band": [], "modes": []}


@pytest.mark.parametrize("command, option, value",
                         [(c, o, v) for c, items in BAD.items() for o, v in items])
def test_every_bad_value_is_one_line_and_exit_2(tmp_path, capsys, monkeypatch, command,
                                                option, value):
    """Each option of each subcommand with a bad value: one line on stderr, exit code 2,
    no traceback, nothing written and no runner called."""
    for name in ("run_unit", "run_onsets", "run_layer", "run_p33",
                 "run_flagged", "run_counts", "run_section", "run_voltage"):
        monkeypatch.setattr(zone_cli, name, lambda *a, **k: pytest.fail("a runner ran"))
    argv = list(GOOD[command])
    if option in argv:
        i = argv.index(option)
        del argv[i:i + 2]
    out = tmp_path / "run"
    has_out = command not in ("tables",)
    values = value.split(" ") if option == "--bracket" else [value]
    tail = ([] if option == "--out" or not has_out else ["--out", str(out)])
    if command in ("tables", "band", "modes") and option == "--from":
        values = [str(tmp_path / value)]
    code = _exit(["clamp-zone", command, *argv, option, *values, *tail])
    err = capsys.readouterr().err
    assert code == 2, (code, err)
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert not out.exists()


def test_an_out_that_is_a_file_is_exit_3(tmp_path, capsys):
    out = tmp_path / "file"
    out.write_text("x")
    code, _, err = _units(out, capsys)
    assert code == 3 and err.count("\n") == 1 and str(out) in err


def test_the_shipped_tables_are_written_from_a_checkout_only(tmp_path, monkeypatch):
    """--into-package names the shipped folder in a source checkout and is refused (a
    ValueError naming the install) where no pyproject.toml is beside the package."""
    assert zone_cli.package_data_dir() == ROOT / "validation" / "data"
    fake = tmp_path / "site-packages" / "validation" / "clamp_zone" / "cli.py"
    fake.parent.mkdir(parents=True)
    monkeypatch.setattr(zone_cli, "__file__", str(fake))
    with pytest.raises(ValueError, match="--into-package writes the shipped tables of a "
                                         "source checkout; this package is installed"):
        zone_cli.package_data_dir()


@pytest.mark.slow
def test_two_units_on_a_local_cluster_give_the_serial_rows(small_run, tmp_path, capsys):
    """alpha = 1 and 0.7 on the smallest mesh, on a LocalCluster of two workers: the same
    rows (every physics column, as written) as one after the other here, and the same
    modes to the eigensolver's tolerance (1e-8 of the largest deflection; the worker
    processes differ in the last digits of the iterative eigenvectors)."""
    pytest.importorskip("distributed", reason="the 'cluster' extra is not installed")
    two = ["--alpha", "1", "0.7", "--mesh", "6x1x3", "--grading", "0.5", "--D0-step", "1",
           "--solver", "superlu"]
    serial, farm = tmp_path / "serial", tmp_path / "farm"
    assert main(["clamp-zone", "units", *two, "--out", str(serial)]) == 0
    assert main(["clamp-zone", "units", *two, "--out", str(farm), "--scheduler", "local",
                 "--jobs", "2"]) == 0
    assert "done on the cluster" in capsys.readouterr().out
    key = lambda r: UnitKey.from_row(r)      # noqa: E731
    a = {key(r): r for r in load("units", serial)}
    b = {key(r): r for r in load("units", farm)}
    assert set(a) == set(b) and len(a) == 2
    for k in a:
        assert all(a[k][c] == b[k][c] for c in PHYSICS), k
        with np.load(serial / "modes" / f"{k.stem}.npz") as x, \
                np.load(farm / "modes" / f"{k.stem}.npz") as y:
            # the mode of the iterative eigensolver, to its tolerance in each process
            np.testing.assert_allclose(x["u2"], y["u2"], rtol=0,
                                       atol=1e-8 * np.abs(x["u2"]).max())
    assert TABLES["units"].key == ("alpha", "mesh", "grading", "formulation")


def test_the_shipped_modes_are_those_of_the_shipped_units(tmp_path, capsys):
    """Each shipped mode file (computed again by ``clamp-zone units`` on the smallest
    resolving meshes) has the D0_b of its unit's shipped row within twice the location
    tolerance, and ``clamp-zone modes`` draws them without a run (one panel each)."""
    from validation.data.registry import shipped_path
    from validation.specs import LOCATION_TOL
    from validation.clamp_zone.modes import read_clamp_modes

    modes = read_clamp_modes(shipped_path("units").parent / "modes")
    rows = {UnitKey.from_row(r): r for r in load("units")}
    assert {m["alpha"] for m in modes} == {0.05, 0.3, 0.7, 1.0, 1.5}
    for m in modes:
        assert abs(m["D0_b"] - float(rows[m["key"]]["D0_b"])) <= 2 * LOCATION_TOL, m["key"]
        assert m["u2"].shape == m["X1"].shape and np.abs(m["u2"]).max() > 0
    assert main(["clamp-zone", "modes", "--out", str(tmp_path)]) == 0
    assert (tmp_path / "clamp-modes.png").stat().st_size > 10_000


@pytest.mark.slow
def test_sigterm_keeps_the_finished_units_and_a_rerun_resumes(tmp_path):
    """SIGTERM after the first of two units: exit 143 with one line, the table holds the
    finished unit's complete row (and its mode), and the same command run again computes
    only the other unit."""
    import os
    import signal
    import time

    out = tmp_path / "run"
    argv = [sys.executable, "-c", "import sys; from validation.cli import main; "
            "sys.exit(main(sys.argv[1:]))", "clamp-zone", "units", "--alpha", "1", "0.7",
            "--mesh", "6x1x3", "--grading", "0.5", "--D0-step", "1", "--solver", "superlu",
            "--out", str(out)]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen(argv, cwd=tmp_path, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    table = out / "clamp_units.csv"
    t0 = time.monotonic()
    while not (table.exists() and len(load("units", out)) == 1):
        assert proc.poll() is None and time.monotonic() - t0 < 300
        time.sleep(0.05)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=120)
    if proc.returncode == 0:           # the second unit finished before the signal landed
        pytest.skip("both units finished before SIGTERM")
    assert proc.returncode == 143 and "rerun the same command to resume" in err
    (row,) = load("units", out)
    assert row["alpha"] == "1" and row["D0_b"]
    assert (out / "modes" / "1_6x1x3_g0.5_mixed.npz").is_file()
    again = subprocess.run(argv, cwd=tmp_path, env=env, capture_output=True, text=True,
                           timeout=300)
    assert again.returncode == 0, again.stderr
    assert "alpha = 1 6x1x3 grading 0.5: kept" in again.stdout
    assert sorted(r["alpha"] for r in load("units", out)) == ["0.7", "1"]


def test_the_modes_figure_titles_the_table_s_load_and_counts_its_half_waves(tmp_path,
                                                                            capsys):
    """clamp-modes.png: each panel's title gives the converged D0_b of the table (not the
    mode's mesh's), and the trace under it counts the half-waves of the units table's row
    for the mode's mesh; the pages' counts (6, 10, 12, 13) are those rows'."""
    import matplotlib.pyplot as plt

    from validation.data.clamp_zone import clamp_unit_load
    from validation.data.registry import shipped_path
    from validation.clamp_zone.modes import clamp_modes_figure, clamp_trace, read_clamp_modes

    modes = read_clamp_modes(shipped_path("units").parent / "modes")
    rows = {UnitKey.from_row(r): r for r in load("units")}
    counts = {}
    for m in modes:
        counts[m["alpha"]] = clamp_trace(m)[3]
        assert counts[m["alpha"]] == int(rows[m["key"]]["half_waves"]), m["key"]
    assert counts == {0.05: 6, 0.3: 10, 0.7: 12, 1.0: 13, 1.5: 15}
    loads = {a: (g["D0_b"], g["spread"], g["meshes"])
             for a in counts for g in [clamp_unit_load(a)]}
    fig = clamp_modes_figure(modes, loads)
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    for a, (d0b, _, _) in loads.items():
        assert any(t.startswith(rf"$\alpha = {a:g}$: $D_{{0b}} = {d0b:.4f}") for t in titles)
    for a, n in counts.items():
        assert sum(t.endswith(f": {n} half-waves") for t in titles) >= 1
    plt.close(fig)
    page = (ROOT / "docs" / "lecture.md").read_text()
    assert ("6, 10, 12, 13 and 15 for `alpha` = 0.05, 0.3, 0.7, 1 and 1.5"
            in " ".join(page.split()))


def test_counts_paused_by_budget_exit_4_and_a_rerun_finishes_them(tmp_path, capsys):
    """``counts --budget`` pauses the ramp after its first target past the budget: one
    line naming the charge and the state kept, exit code 4 (docs/cli.md); the same
    command run again continues until the table has the rows of one uninterrupted run."""
    argv = ["clamp-zone", "counts", "--alpha", "1", "--mesh", "4x1x6", "--grading", "0.1",
            "--D0", "1", "1.5", "--solver", "superlu"]
    assert main([*argv, "--out", str(tmp_path / "whole")]) == 0
    whole = load("counts", tmp_path / "whole")
    codes = []
    while not codes or codes[-1] == 4:
        codes.append(main([*argv, "--budget", "0.001", "--out", str(tmp_path / "paused")]))
        err = capsys.readouterr().err
        if codes[-1] == 4:
            (line,) = err.strip().splitlines()
            assert "paused at s = " in line and "counts" in line and "rerun" in line
        assert len(codes) < 20
    assert codes[-1] == 0 and codes.count(4) == len(codes) - 1 >= 2
    got = load("counts", tmp_path / "paused")
    cells = [c for c in TABLES["counts"].columns if c not in
             ("cpu_s", "count_cpu_s", "peak_GB", "factorisations", "date", "command")]
    assert [{c: r[c] for c in cells} for r in got] == [{c: r[c] for c in cells}
                                                       for r in whole]
    assert not list((tmp_path / "paused" / ".state" / "counts").glob("*.npz"))


def test_each_mode_file_carries_its_unit_s_key(tmp_path):
    """Every shipped mode holds its unit's key (the array ``key``, equal to its file's
    stem, written by ``write_mode``); a mode file renamed to another unit's name is refused
    in one line naming it (exit code 3 of the command)."""
    import shutil

    from validation.clamp_zone.modes import read_clamp_modes
    from validation.data.registry import shipped_path
    from validation.store.files import read_npz

    folder = shipped_path("units").parent / "modes"
    files = sorted(folder.glob("*.npz"))
    assert len(files) == 5
    for f in files:
        assert str(read_npz(f)["key"]) == f.stem
    (tmp_path / "modes").mkdir()
    shutil.copy(files[0], tmp_path / "modes" / f"{files[1].stem}.npz")
    with pytest.raises(OSError, match=f"holds the mode of the unit {files[0].stem}"):
        read_clamp_modes(tmp_path / "modes")
    assert _exit(["clamp-zone", "modes", "--from", str(tmp_path),
                  "--out", str(tmp_path / "fig")]) == 3


def test_an_inverted_section_row_is_computed_again_and_kept_aside(tmp_path, capsys):
    """A ``section`` row whose base state was inverted (``J_min <= 0``, accepted by an
    earlier solver without the ``J > 0`` guard) is computed again by a run of its state:
    the new row replaces it, the old one goes to the side file with the reason, and an
    inverted row of a state the run does not compute is left as it is."""
    from validation.data.spec import read_table

    argv = ["clamp-zone", "section", "--alpha", "1", "--mesh", "4x1x2", "--grading", "0.5",
            "--D0", "1", "--h0", "0.1", "--k", "1", "--solver", "superlu", "--out",
            str(tmp_path)]
    assert main(argv) == 0
    path = tmp_path / TABLES["section"].file
    (good,) = read_table(path, TABLES["section"])
    assert float(good["J_min"]) > 0
    other = {**good, "D0": "2", "J_min": "-0.3"}
    bad = {**good, "J_min": "-0.47", "n_negative": "-2"}
    cols = TABLES["section"].columns
    text = path.read_text().splitlines()
    body = [",".join(str(r[c]) for c in cols) for r in (bad, other)]
    path.write_text("\n".join(text[:-1] + body) + "\n")       # the good row swapped out
    capsys.readouterr()
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "1 row(s) in clamp_section.csv (1, 4x1x2, 0.5, " in out
    assert "has an inverted base state (J_min = -0.47); computed again" in out
    rows = read_table(path, TABLES["section"])
    assert sorted((r["D0"], float(r["J_min"]) > 0) for r in rows) == [("1", True),
                                                                       ("2", False)]
    assert [r["n_negative"] for r in rows if r["D0"] == "1"] == [good["n_negative"]]
    aside = path.with_name(path.name + ".damaged").read_text()
    assert "computed again with other settings" in aside and ",-0.47," in aside


def test_the_section_s_pressure_space_is_part_of_its_rows_key(tmp_path, capsys):
    """A table written before the ``pressure`` column reads with Q1;
    ``section --pressure P0`` of a state adds its rows beside the Q1 ones of the same
    state (the key holds the space), and the table is then written with the whole header,
    the older rows keeping Q1.  The P0 section has one pressure per element instead of one
    per vertex: ``(n1 + 1)(n2 + 1) - n1 n2 = n1 + n2 + 1`` unknowns fewer."""
    from validation.data.spec import read_table

    base = ["clamp-zone", "section", "--alpha", "1", "--mesh", "4x1x2", "--grading", "0.5",
            "--D0", "1", "--h0", "0.1", "--k", "1", "--solver", "superlu", "--out",
            str(tmp_path)]
    assert main(base) == 0
    path = tmp_path / TABLES["section"].file
    lines = path.read_text().splitlines()            # as a file of the earlier release
    header = lines.index(next(ln for ln in lines if ln.startswith("alpha,")))
    cols = lines[header].split(",")
    i = cols.index("pressure")
    old = [",".join(c for j, c in enumerate(ln.split(",")) if j != i)
           for ln in lines[header:]]
    path.write_text("\n".join(lines[:header] + old) + "\n")
    (q1,) = read_table(path, TABLES["section"])
    assert q1["pressure"] == "Q1"
    assert main([*base, "--pressure", "P0"]) == 0
    rows = read_table(path, TABLES["section"])
    assert sorted(r["pressure"] for r in rows) == ["P0", "Q1"]
    assert "pressure" in path.read_text().splitlines()[header].split(",")
    from skfem_dielectric.models.edge_section import edge_section_grids

    g1, g2 = edge_section_grids(50.0, 5.0, 1.0, 0.1)
    p0 = next(r for r in rows if r["pressure"] == "P0")
    assert int(q1["section_dofs"]) - int(p0["section_dofs"]) == len(g1) + len(g2) - 1


def test_the_section_of_the_dead_load_alone_is_the_limit_of_small_charges(tmp_path):
    """``section --D0 0``: the state at the pre-load's end (no charge step).  Its rows are
    the limit of a small charge's: the base state's F11 at the section's middle (5 digits)
    and the negative-mode count at every k agree with ``D0 = 1e-6``, both with the 3D
    plate's F11 from its own ramp."""
    from validation.data.spec import read_table

    base = ["clamp-zone", "section", "--alpha", "1.5", "--mesh", "4x1x2", "--grading",
            "0.5", "--h0", "0.1", "--k", "1", "20", "--solver", "superlu", "--out",
            str(tmp_path)]
    assert main([*base, "--D0", "0", "1e-6"]) == 0
    rows = read_table(tmp_path / TABLES["section"].file, TABLES["section"])
    by = {(float(r["D0"]), float(r["k"])): r for r in rows}
    assert sorted(by) == [(0.0, 1.0), (0.0, 20.0), (1e-6, 1.0), (1e-6, 20.0)]
    for k in (1.0, 20.0):
        zero, small = by[0.0, k], by[1e-6, k]
        assert float(zero["F11_section"]) == pytest.approx(float(small["F11_section"]),
                                                           abs=1e-5)
        assert float(zero["F11_3d"]) == pytest.approx(float(small["F11_3d"]), abs=1e-5)
        assert zero["n_negative"] == small["n_negative"]
        assert float(zero["F11_section"]) == pytest.approx(float(zero["F11_3d"]), rel=0.05)
        assert float(zero["J_min"]) > 0

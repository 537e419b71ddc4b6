"""The store's rules, for every command that writes into ``--out``: nothing the command
did not create is deleted (a folder, FIFO or device where a table goes stops the command,
exit 3, untouched); a damaged row is named with its file and line and kept aside in
``<table>.damaged``, never deleted; a rerun with other settings recomputes a row whose
result they change, and says so.  Property-based: random sequences of writes, kills,
damaged lines and reruns never lose a finished row or keep a stale one."""

from __future__ import annotations

import os

import pytest

from test_study_store import STUDIES, patch_fakes, run
from validation.cli import main
from validation.data.spec import TableSpec
from validation.store import StudyStore


@pytest.fixture
def fake(monkeypatch):
    """The studies' FE work replaced (:func:`test_study_store.patch_fakes`)."""
    return patch_fakes(monkeypatch)


@pytest.mark.parametrize("study", list(STUDIES))
def test_a_folder_named_as_a_table_is_left_and_the_command_exits_3(study, fake, tmp_path,
                                                                    capsys):
    """A user's folder in --out with the name of one of the study's CSVs, with a file in
    it: exit 3, one line naming it, the folder and its file untouched, nothing computed."""
    for name in STUDIES[study]["files"]:
        out = tmp_path / name.replace(".", "_")
        mine = out / name
        mine.mkdir(parents=True)
        (mine / "notes.txt").write_text("my notes")
        fake.clear()
        code, _, err = run(STUDIES[study]["argv"], out, capsys)
        assert code == 3 and err.count("\n") == 1 and "Traceback" not in err, err
        assert f"{mine}: is a folder, not a file of the {study} study" in err
        assert (mine / "notes.txt").read_text() == "my notes"
        assert fake == []


@pytest.mark.parametrize("case", ["voltage-control", "wrinkling-fe"])
def test_validate_leaves_a_folder_named_as_its_csv(case, tmp_path, capsys, monkeypatch):
    """The same rule through ``validate --case``: exit 3 (docs/cli.md, "a CSV is a
    folder"), the folder and what it holds kept."""
    out = tmp_path / "res"
    mine = out / f"{case}.csv"
    mine.mkdir(parents=True)
    (mine / "keep.txt").write_text("x")
    code = main(["validate", "--quick", "--case", case, "--out", str(out), "--no-progress"])
    err = capsys.readouterr().err
    assert code == 3, err
    assert f"{mine}: is a folder" in err
    assert (mine / "keep.txt").read_text() == "x"


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs mkfifo")
def test_a_fifo_or_a_device_is_named_for_what_it_is(tmp_path):
    from validation.store import regular_file

    fifo = tmp_path / "t.csv"
    os.mkfifo(fifo)
    with pytest.raises(OSError, match="is a FIFO, not the table") as exc:
        regular_file(fifo, "the table")
    assert exc.value.filename == str(fifo)
    if os.path.exists("/dev/zero"):
        link = tmp_path / "z.csv"
        link.symlink_to("/dev/zero")
        with pytest.raises(OSError, match="is a device, not the table"):
            regular_file(link, "the table")
    assert regular_file(tmp_path / "absent.csv") == tmp_path / "absent.csv"


def test_keep_aside_appends_and_names_each_line(tmp_path):
    from validation.store import keep_aside

    path = tmp_path / "t.csv"
    keep_aside(path, [(3, "1,2x1x1,x", "has 'x' in the number column 'D0_b'")])
    keep_aside(path, [(7, "2,2x1", "has 2 cells, the header 3")])
    lines = (tmp_path / "t.csv.damaged").read_text().splitlines()
    assert len(lines) == 4
    assert lines[0].startswith("# t.csv line 3 (") and lines[1] == "1,2x1x1,x"
    assert lines[2].endswith("): has 2 cells, the header 3") and lines[3] == "2,2x1"


def test_a_repeated_unit_row_is_kept_aside(tmp_path):
    t = TableSpec.plain("t.csv", ("alpha", "mesh", "D0_b"), ("alpha", "mesh"))
    (tmp_path / "t.csv").write_text("alpha,mesh,D0_b\n1,2x1x1,0.5\n1,2x1x1,0.75\n")
    (tmp_path / ".state").mkdir()
    (tmp_path / ".state" / "demo.json").write_text("{}")
    notes = []
    with StudyStore(tmp_path, "demo", {}, t, plan=[], note=notes.append) as st:
        assert st.rows() == [{"alpha": 1.0, "mesh": "2x1x1", "D0_b": 0.5}]
    assert notes == [f"{tmp_path / 't.csv'}: row 3 repeats the unit 1, 2x1x1; kept aside in "
                     f"t.csv.damaged"]
    assert (tmp_path / "t.csv.damaged").read_text().splitlines()[1] == "1,2x1x1,0.75"


# -- the clamp-zone tables ----------------------------------------------------------------
import validation.clamp_zone.cli as zone_cli  # noqa: E402
from validation.data.registry import TABLES, load  # noqa: E402


def _unit_row(alpha, mesh, *, D0_step=0.5, D0_b=3.25, note=""):
    """A units row as ``run_unit`` returns it (values, no mode): every column set."""
    row = {c: 1 for c in TABLES["units"].columns}
    row.update(alpha=alpha, mesh=mesh, grading=1.0, formulation="mixed", D0_step=D0_step,
               D0_b=D0_b, note=note, solver="superlu", date="2026-12-07", scan_counts="",
               **{"class": "x1 S, x2 A, x3 S"})
    row.pop("command")
    return row


@pytest.fixture
def fake_units(monkeypatch):
    """``run_unit`` replaced: D0_b = 3 alpha, or no crossing when D0_max < 3 alpha; the
    calls listed."""
    calls = []

    def run_unit(key, *, D0_step, D0_max, **kw):
        alpha, el = key.alpha, key.mesh
        calls.append((alpha, tuple(el), D0_step, D0_max))
        mesh = "x".join(map(str, el))
        if D0_max < 3 * alpha:
            return _unit_row(alpha, mesh, D0_step=D0_step, D0_b=float("nan"),
                             note=f"no physical crossing up to D0 = {D0_max:g}")
        return _unit_row(alpha, mesh, D0_step=D0_step, D0_b=3 * alpha)

    monkeypatch.setattr(zone_cli, "run_unit", run_unit)
    return calls


def _zone(argv, capsys):
    code = main(["clamp-zone", *argv])
    got = capsys.readouterr()
    return code, got.out, got.err


def test_a_damaged_row_of_a_unit_not_run_is_kept_aside_not_deleted(fake_units, tmp_path,
                                                                   capsys):
    """The table holds a damaged row of alpha = 0.7; a run of alpha = 1 rewrites the
    table: the damaged row goes, with its line, to clamp_units.csv.damaged, and the message
    says its unit is computed again only if the command runs it."""
    out = tmp_path / "run"
    assert _zone(["units", "--alpha", "0.7", "--mesh", "4x1x2", "--out", str(out)],
                 capsys)[0] == 0
    table = out / "clamp_units.csv"
    text = table.read_text()
    bad = text.replace(",4x1x2,1,mixed,1,0.5,", ",4x1x2,1,mixed,1,one,")
    assert bad != text
    table.write_text(bad)
    damaged_line = bad.splitlines()[-1]
    n = len(bad.splitlines())
    code, stdout, _ = _zone(["units", "--alpha", "1", "--mesh", "4x1x2", "--out", str(out)],
                            capsys)
    assert code == 0
    assert (f"{table}: line {n} has 'one' in the number column 'D0_step'; left out, moved "
            f"to clamp_units.csv.damaged when the table is next written; its unit is "
            f"computed again if this command runs it") in stdout
    assert [r["alpha"] for r in load("units", out)] == ["1"]
    aside = (out / "clamp_units.csv.damaged").read_text().splitlines()
    assert aside[0].startswith(f"# clamp_units.csv line {n} (") and aside[1] == damaged_line
    assert fake_units == [(0.7, (4, 1, 2), 0.5, 6.0), (1.0, (4, 1, 2), 0.5, 6.0)]


def test_a_rerun_with_other_charge_settings_recomputes_what_they_change(fake_units, tmp_path,
                                                                       capsys):
    """--D0-max 1 finds no crossing for alpha = 1 (D0_b = 3); the rerun with --D0-max 6
    recomputes it and finds D0_b = 3, the old row kept aside; another --D0-step
    recomputes; the same settings keep; a smaller --D0-max keeps a located D0_b."""
    out = tmp_path / "run"
    base = ["units", "--alpha", "1", "--mesh", "4x1x4", "--out", str(out)]
    assert _zone(base + ["--D0-max", "1"], capsys)[0] == 0
    (row,) = load("units", out)
    assert row["D0_b"] == "" and row["note"] == "no physical crossing up to D0 = 1"
    code, stdout, _ = _zone(base + ["--D0-max", "6"], capsys)
    assert code == 0
    assert ("alpha = 1 4x1x4 grading 1: its row in clamp_units.csv found no crossing up to "
            "D0 = 1, this run asks up to --D0-max 6; computed again") in stdout
    (row,) = load("units", out)
    assert float(row["D0_b"]) == 3.0
    assert "no physical crossing up to D0 = 1" in (out / "clamp_units.csv.damaged").read_text()
    code, stdout, _ = _zone(base + ["--D0-max", "6"], capsys)
    assert "alpha = 1 4x1x4 grading 1: kept" in stdout
    code, stdout, _ = _zone(base + ["--D0-max", "4"], capsys)
    assert "alpha = 1 4x1x4 grading 1: kept" in stdout
    code, stdout, _ = _zone(base + ["--D0-step", "0.25"], capsys)
    assert "was scanned with --D0-step 0.5, this run asks 0.25; computed again" in stdout
    (row,) = load("units", out)
    assert float(row["D0_step"]) == 0.25
    assert [c[2:] for c in fake_units] == [(0.5, 1.0), (0.5, 6.0), (0.25, 6.0)]


def test_a_p33_row_ramped_to_a_smaller_charge_is_recomputed(tmp_path, capsys, monkeypatch):
    calls = []

    def run_p33(key, *, D0_step, D0_max, **kw):
        alpha, el, grading = key.alpha, key.mesh, key.grading
        calls.append((D0_step, D0_max))
        row = {c: "" for c in TABLES["p33"].columns if c != "command"}
        row.update(alpha=alpha, mesh="x".join(map(str, el)), grading=grading, dofs=10,
                   D0_step=D0_step, D0_max=D0_max, newton_limit=5.5 if D0_max > 5.5
                   else float("nan"), cpu_s=1)
        return row

    monkeypatch.setattr(zone_cli, "run_p33", run_p33)
    out = tmp_path / "run"
    base = ["p33", "--alpha", "1", "--mesh", "4x1x2", "--out", str(out)]
    assert _zone(base + ["--D0-max", "2"], capsys)[0] == 0
    code, stdout, _ = _zone(base + ["--D0-max", "6"], capsys)
    assert ("ramped to D0 = 2 without a Newton limit, this run asks up to --D0-max 6; "
            "computed again") in stdout
    (row,) = load("p33", out)
    assert float(row["newton_limit"]) == 5.5 and calls == [(0.25, 2.0), (0.25, 6.0)]


def test_a_reading_command_names_each_damaged_row(tmp_path, capsys):
    """clamp-zone tables --from DIR and the shipped scaling: a damaged row is named on
    stderr with its file and line (the printed tables leave it out)."""
    from validation.data.registry import shipped_path

    src = tmp_path / "tables"
    src.mkdir()
    for name in TABLES:
        text = shipped_path(name).read_text()
        (src / TABLES[name].file).write_text(text)
    units = src / "clamp_units.csv"
    lines = units.read_text().splitlines(keepends=True)
    i = next(i for i, ln in enumerate(lines) if ln.startswith("1,"))
    lines[i] = lines[i].replace(",mixed,", ",mixed,extra,", 1)
    units.write_text("".join(lines))
    code, stdout, err = _zone(["tables", "--from", str(src)], capsys)
    assert code == 0 and stdout
    assert err.splitlines() == [f"skfem-dielectric clamp-zone: {units}: line {i + 1} has "
                                f"{len(TABLES['units'].columns) + 1} cells, the header "
                                f"{len(TABLES['units'].columns)}; left out of what is read"]


def test_an_empty_key_cell_is_a_damaged_row_named_with_its_line(fake_units, tmp_path,
                                                                capsys):
    out = tmp_path / "run"
    assert _zone(["units", "--alpha", "1", "--mesh", "4x1x2", "--out", str(out)],
                 capsys)[0] == 0
    table = out / "clamp_units.csv"
    text = table.read_text()
    table.write_text(text + text.splitlines(keepends=True)[-1].replace("1,4x1x2", ",4x1x3"))
    n = len(text.splitlines()) + 1
    code, stdout, err = _zone(["units", "--alpha", "0.7", "--mesh", "4x1x2", "--out",
                               str(out)], capsys)
    assert code == 0, err
    assert f"{table}: line {n} has an empty key cell 'alpha'; left out" in stdout


@pytest.mark.parametrize("argv, message", [
    (["flagged", "--alpha", "1", "--mesh", "4x1x2", "--D0", "1e9"],
     "--D0 must be at most 50"),
    (["counts", "--alpha", "1", "--mesh", "4x1x2", "--D0", "1e9"], "--D0 must be at most 50"),
    (["section", "--alpha", "1", "--D0", "1e9"], "--D0 must be at most 50"),
    (["onsets", "--alpha", "1", "--mesh", "4x1x2", "--bracket", "1e8", "1e9"],
     "--bracket must be at most 50"),
    (["units", "--alpha", "1", "--mesh", "4x1x2", "--D0-max", "1e9", "--D0-step", "1e7"],
     "--D0-max must be at most 50"),
    (["units", "--alpha", "0.3000001", "--mesh", "4x1x2"],
     "--alpha 0.3000001 has more digits than the tables keep (6 significant: 0.3)"),
    (["units", "--alpha", "1", "--grading", "0.12345678", "--mesh", "4x1x2"],
     "--grading 0.12345678 has more digits"),
    (["section", "--alpha", "1", "--D0", "1", "--h0", "1e-9"], "--h0 must be at least 0.01"),
    (["section", "--alpha", "1", "--D0", "1", "--length", "60"],
     "--length must be at most the eighth model's 50 mm, got 60"),
], ids=["flagged-D0", "counts-D0", "section-D0", "onsets-bracket", "units-D0-max",
        "units-alpha-digits", "units-grading-digits", "section-h0", "section-length"])
def test_sizes_are_bounded_before_anything_is_allocated(argv, message, tmp_path, capsys,
                                                        monkeypatch):
    for name in ("run_unit", "run_onsets", "run_layer", "run_p33",
                 "run_flagged", "run_counts", "run_section"):
        monkeypatch.setattr(zone_cli, name, lambda *a, **k: pytest.fail("a runner ran"))
    out = tmp_path / "run"
    code, _, err = _zone(argv + ["--out", str(out)], capsys)
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err, err
    assert message in err
    assert not out.exists()


@pytest.mark.parametrize("D0_b", ["-1", "1e9", "inf"])
def test_a_unit_whose_D0_b_is_not_a_charge_stops_layer_with_exit_3(D0_b, fake_units,
                                                                   tmp_path, capsys):
    out = tmp_path / "run"
    assert _zone(["units", "--alpha", "1", "--mesh", "4x1x2", "--out", str(out)],
                 capsys)[0] == 0
    table = out / "clamp_units.csv"
    table.write_text(table.read_text().replace(",0.5,3,", f",0.5,{D0_b},"))
    assert load("units", out)[0]["D0_b"] == D0_b
    code, _, err = _zone(["layer", "--alpha", "1", "--mesh", "4x1x2", "--out", str(out)],
                         capsys)
    assert code == 3 and err.count("\n") == 1, err
    assert (f"cannot use {table}: the row of the clamp-zone unit alpha = 1 4x1x2 grading 1 "
            f"has D0_b = {D0_b}, not a charge in (0, 50]") in err
    assert load("layer", out) == []


def test_a_table_that_is_a_folder_or_a_fifo_is_exit_3(fake_units, tmp_path, capsys):
    out = tmp_path / "run"
    (out / "clamp_units.csv").mkdir(parents=True)
    code, _, err = _zone(["units", "--alpha", "1", "--mesh", "4x1x2", "--out", str(out)],
                         capsys)
    assert code == 3 and err.count("\n") == 1, err
    assert "clamp_units.csv: is a folder, not the clamp-zone units table" in err
    if hasattr(os, "mkfifo"):
        other = tmp_path / "other"
        other.mkdir()
        os.mkfifo(other / "clamp_units.csv")
        code, _, err = _zone(["units", "--alpha", "1", "--mesh", "4x1x2", "--out",
                              str(other)], capsys)
        assert code == 3 and "is a FIFO, not the clamp-zone units table" in err, err
    assert fake_units == []


def test_a_mode_file_that_is_not_an_npz_is_named(tmp_path, capsys):
    src = tmp_path / "run"
    (src / "modes").mkdir(parents=True)
    bad = src / "modes" / "1_4x1x2_g1_mixed.npz"
    bad.write_bytes(b"\x80\x04not a zip")       # a pickle's first bytes, as reported
    code, _, err = _zone(["modes", "--from", str(src), "--out", str(tmp_path / "fig")],
                         capsys)
    assert code == 3 and err.count("\n") == 1, err
    assert f"cannot use {bad}: is not an .npz file of arrays (ValueError" in err


def test_a_full_disk_while_the_mode_is_written_names_the_file(tmp_path, capsys, monkeypatch):
    import errno

    import numpy as np

    import validation.store.files as files

    def full(fh, **arrays):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(files.np, "savez", full)
    with pytest.raises(OSError) as exc:
        files.write_npz_atomic(tmp_path / "m.npz", a=np.zeros(3))
    assert exc.value.filename == str(tmp_path / "m.npz") and exc.value.errno == errno.ENOSPC
    assert not list(tmp_path.iterdir())


def test_an_allocation_that_fails_is_one_line_and_exit_2(tmp_path, capsys, monkeypatch):
    def huge(*a, **k):
        raise MemoryError("Unable to allocate 149. GiB for an array with shape (2e10,)")

    monkeypatch.setattr(zone_cli, "run_unit", huge)
    code, _, err = _zone(["units", "--alpha", "1", "--mesh", "4x1x2", "--out",
                          str(tmp_path / "run")], capsys)
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err, err
    assert "not enough memory for this run (Unable to allocate 149. GiB" in err

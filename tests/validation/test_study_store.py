"""The result store of the studies ``buckling`` and ``post-buckling``
(:class:`validation.store.StudyStore`): resume, settings, damaged files, repeated values,
one writer, SIGTERM.

The FE work of a unit (one alpha x mesh) is replaced by a closed-form stand-in whose every
cell is known, so that each test checks the files against those numbers and runs in well
under a second; ``test_buckling_killed_at_random_moments`` (slow) kills the real command.
"""

from __future__ import annotations

import csv
import os
import random
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

import validation.store.rows as rows_module
import validation.studies.buckling as bk
import validation.studies.postbuckling as pb
from validation.cli import main
from validation.data.spec import TableSpec
from validation.store import DamagedFileError, LockedError, StudyStore, read_rows

ROOT = Path(__file__).resolve().parents[2]


def fake_buckling(calls):
    """Stand-ins of ``run_one``/``run_plain`` whose cells are closed forms of the inputs:
    ``D0_b = alpha N1 / 10 + D0_step``, one scan row per charge target with
    ``lowest = alpha D0``, three trial states at ``D0_b + d`` with ``eigenvalue = -d``."""

    def run_one(alpha, el, *, D0_step, D0_max, solver="auto", modes_dir=None):
        calls.append((alpha, tuple(el), D0_step, D0_max))
        mesh = bk._mesh_name(el)
        row = {c: 0.5 for c in bk.COLUMNS}
        row.update(alpha=alpha, mesh=mesh, D0_b=alpha * el[0] / 10 + D0_step,
                   **{"class": "x1 S, x2 S, x3 A"}, D0_max=D0_max, seconds=1.0)
        scan = [{**{c: 0.25 for c in bk.SCAN_COLUMNS}, "alpha": alpha, "mesh": mesh,
                 "D0": float(d), "lowest": alpha * float(d), "physical_class": "x1 S"}
                for d in bk.charge_targets(D0_step, D0_max)]
        trials = [{"alpha": alpha, "mesh": mesh, "D0": row["D0_b"] + d, "eigenvalue": -d,
                   "physical_class": "x1 S"} for d in (0.25, -0.125, 0.0)]
        return row, scan, trials

    def run_plain(alpha, el, *, D0_step, D0_max, solver="auto"):
        return {**{c: 0.125 for c in bk.PLAIN_COLUMNS}, "alpha": alpha,
                "mesh": bk._mesh_name(el), "newton_limit": D0_max, "seconds": 1.0}

    return run_one, run_plain


def fake_post(calls):
    """Stand-in of the post-buckling ``run_one``: ``D0_b = alpha + N1 / 100``, one state
    row per fundamental target with ``lam1 = 1 + D0``."""

    def run_one(alpha, el, *, D0_step, D0_max, D0_from=0.0, solver="auto",
                model="quarter", shapes_dir=None):
        calls.append((alpha, tuple(el), D0_step, D0_max))
        mesh = pb._mesh_name(el)
        summary = {**{c: 0.5 for c in pb.SUMMARY_COLUMNS}, "alpha": alpha, "mesh": mesh,
                   "model": model, "D0_b": alpha + el[0] / 100, "reason": "", "seconds": 1.0}
        states = [{**{c: 0.25 for c in pb.COLUMNS}, "alpha": alpha, "mesh": mesh,
                   "model": model, "branch": "fundamental", "D0": float(d),
                   "lam1": 1 + float(d)}
                  for d in pb.charge_targets(D0_step, D0_max, D0_from)]
        return summary, states

    return run_one


STUDIES = {
    "buckling": dict(module=bk, files=("buckling.csv", "buckling-scan.csv",
                                       "buckling-trials.csv", "buckling-plain.csv"),
                     argv=["buckling", "--alpha", "1", "0.5", "--meshes", "2x1x1", "3x1x1",
                           "--D0-step", "0.5", "--D0-max", "1", "--solver", "superlu"]),
    "post-buckling": dict(module=pb, files=("post-buckling-summary.csv", "post-buckling.csv"),
                          argv=["post-buckling", "--alpha", "0.05", "1", "--meshes", "2x2x1",
                                "4x2x2", "--D0-step", "0.5", "--D0-max", "1", "--solver",
                                "superlu"]),
}


@pytest.fixture
def fake(monkeypatch):
    """Patch both studies' FE work and figures; returns the list of computed units."""
    return patch_fakes(monkeypatch)


def patch_fakes(monkeypatch) -> list:
    """Patch both studies' FE work and figures (:func:`fake_buckling`, :func:`fake_post`);
    returns the list of computed units."""
    calls = []
    one, plain = fake_buckling(calls)
    monkeypatch.setattr(bk, "run_one", one)
    monkeypatch.setattr(bk, "run_plain", plain)
    monkeypatch.setattr(bk, "buckling_figure", lambda *a, **k: None)
    monkeypatch.setattr(pb, "run_one", fake_post(calls))
    monkeypatch.setattr(pb, "post_buckling_figure", lambda *a, **k: None)
    return calls


def run(argv, out, capsys):
    code = main(argv + ["--out", str(out)])
    o, err = capsys.readouterr()
    return code, o, err


def files_of(out, study):
    """The bytes of the study's files (``None``: not written, e.g. no trial states)."""
    return {f: (out / f).read_bytes() if (out / f).exists() else None
            for f in STUDIES[study]["files"]}


class _Killed(BaseException):
    """Stands for a kill: not an Exception, so nothing of the study catches it."""


@pytest.mark.parametrize("study", list(STUDIES))
def test_a_stop_at_any_write_resumes_to_the_uninterrupted_files(study, fake, tmp_path,
                                                                 capsys, monkeypatch):
    # the reference: the uninterrupted study, 4 units
    argv = STUDIES[study]["argv"]
    assert run(argv, tmp_path / "ref", capsys)[0] == 0
    ref = files_of(tmp_path / "ref", study)
    assert len(fake) == 4
    table = read_rows(tmp_path / "ref" / STUDIES[study]["files"][0])
    want = ([a * n / 10 + 0.5 for a in (1.0, 0.5) for n in (2, 3)] if study == "buckling"
            else [a + n / 100 for a in (0.05, 1.0) for n in (2, 4)])
    # the cells are the stand-in's closed form, written with 10 significant digits
    assert [r["D0_b"] for r in table] == pytest.approx(want, rel=1e-10, abs=0)
    n_writes = 4 * len(ref)
    real = rows_module.write_csv_atomic
    for k in range(n_writes):
        out = tmp_path / f"k{k}"
        count = [0]

        def stop_at_k(path, header, rows):
            count[0] += 1
            if count[0] == k + 1:
                if k % 2:                      # killed while writing the temporary file
                    Path(path).with_name(f".{Path(path).name}.{os.getpid()}.tmp"
                                         ).write_text("alpha,me")
                raise _Killed
            return real(path, header, rows)

        monkeypatch.setattr(rows_module, "write_csv_atomic", stop_at_k)
        with pytest.raises(_Killed):
            main(argv + ["--out", str(out)])
        monkeypatch.setattr(rows_module, "write_csv_atomic", real)
        capsys.readouterr()
        assert run(argv, out, capsys)[0] == 0
        assert files_of(out, study) == ref, f"stopped at write {k + 1}"
        assert not list(out.glob(".*.tmp"))


def test_a_half_written_last_row_is_recomputed(fake, tmp_path, capsys):
    # a table cut inside its last row (no line end), as an appending writer leaves it
    argv = STUDIES["buckling"]["argv"]
    assert run(argv, tmp_path, capsys)[0] == 0
    ref = files_of(tmp_path, "buckling")
    table = tmp_path / "buckling.csv"
    table.write_bytes(ref["buckling.csv"][:-7])
    fake.clear()
    code, _, err = run(argv, tmp_path, capsys)
    assert code == 0
    assert err.count("\n") == 4     # the cut row kept aside; its unit's scan, trial, plain rows
    assert (f"{table}: its last row is incomplete (no line end); kept aside in "
            f"buckling.csv.damaged") in err
    # the cut row is in the side file, named by its line, not lost
    cut = ref["buckling.csv"][:-7].decode().splitlines()
    aside = (tmp_path / "buckling.csv.damaged").read_text().splitlines()
    assert aside[0].startswith(f"# buckling.csv line {len(cut)} (")
    assert aside[0].endswith("): incomplete (no line end)") and aside[1:] == cut[-1:]
    assert fake == [(0.5, (3, 1, 1), 0.5, 1.0)]         # only that unit recomputed
    assert files_of(tmp_path, "buckling") == ref
    fake.clear()
    assert run(argv, tmp_path, capsys)[1:] == ("wrote " + f"{tmp_path / 'buckling.csv'}, "
                                               f"{tmp_path / 'buckling.png'} (and .pdf)\n", "")
    assert fake == []


def test_a_missing_value_is_an_empty_cell_and_said_in_words(tmp_path, capsys, monkeypatch):
    """docs/cli.md: ``P33_onset_<set>`` "empty if never", ``newton_limit`` "empty" when the
    ramp reached ``--D0-max``; the printed line says so, and a rerun reads the cells back."""
    calls = []
    one, plain = fake_buckling(calls)
    nan = float("nan")
    never = {f"P33_onset_{k}": nan for k in bk.P33_SETS}

    def one_without(*a, **k):
        row, scan, _ = one(*a, **k)
        row.update(never, D0_b=nan, newton_limit=nan, lowest_eig=nan, **{"class": ""})
        return row, scan, []

    monkeypatch.setattr(bk, "run_one", one_without)
    monkeypatch.setattr(bk, "run_plain", lambda *a, **k: {**plain(*a, **k), **never,
                                                          "newton_limit": nan})
    monkeypatch.setattr(bk, "buckling_figure", lambda *a, **k: None)
    argv = ["buckling", "--alpha", "1", "--meshes", "2x1x1", "--D0-step", "0.5",
            "--D0-max", "1", "--solver", "superlu"]
    code, o, err = run(argv, tmp_path, capsys)
    assert code == 0 and err == ""
    # the stand-in's plain row has D0_max = 0.125 (every cell of fake_buckling's run_plain)
    assert ("alpha = 1 2x1x1: no D0_b found; grad-div stabilised form: no P33 onset "
            "(interior) up to D0 = 1, no Newton limit up to D0 = 1; plain form: no P33 onset "
            "(interior) up to D0 = 0.125, no Newton limit up to D0 = 0.125; 1 s") in o
    assert "nan" not in o
    empty = ["D0_b", "lowest_eig", "newton_limit"] + list(never)
    for name in ("buckling.csv", "buckling-plain.csv"):
        with open(tmp_path / name, newline="") as fh:
            (row,) = list(csv.DictReader(fh))
        assert "nan" not in (tmp_path / name).read_text()
        assert all(row[c] == "" for c in empty if c in row), row
        assert all(v != v for c, v in read_rows(tmp_path / name)[0].items() if c in empty)
    ref = files_of(tmp_path, "buckling")
    calls.clear()
    code, o, err = run(argv, tmp_path, capsys)       # the rerun reads its own CSVs back
    assert code == 0 and err == "" and calls == []
    assert files_of(tmp_path, "buckling") == ref
    # a table of an earlier version with "nan" cells is read and rewritten with empty ones
    table = tmp_path / "buckling.csv"
    with open(table, newline="") as fh:
        lines = list(csv.reader(fh))
    lines[1] = ["nan" if c in empty else v for c, v in zip(lines[0], lines[1])]
    table.write_text("".join(",".join(r) + "\n" for r in lines))
    code, o, err = run(argv[:2] + ["1", "2"] + argv[3:], tmp_path, capsys)
    assert code == 0 and err == "" and len(calls) == 1          # alpha = 2 only
    assert "nan" not in table.read_text()
    assert table.read_text().splitlines()[1] == ref["buckling.csv"].decode().splitlines()[1]


def test_a_post_buckling_unit_without_a_branch_is_said_in_words(tmp_path, capsys,
                                                                 monkeypatch):
    nan = float("nan")
    none = dict(D0_b=nan, D0_b_pitchfork=nan, b=nan, D0_last=nan, deflection_last=nan,
                reason="no negative eigenvalue of the own class")
    one = fake_post([])
    monkeypatch.setattr(pb, "run_one", lambda *a, **k: ({**one(*a, **k)[0], **none},
                                                         one(*a, **k)[1]))
    monkeypatch.setattr(pb, "post_buckling_figure", lambda *a, **k: None)
    code, o, err = run(["post-buckling", "--alpha", "0.05", "--meshes", "2x2x1", "--D0-step",
                        "0.5", "--D0-max", "1", "--solver", "superlu"], tmp_path, capsys)
    assert code == 0 and err == ""
    assert ("alpha = 0.05 quarter 2x2x1: no D0_b found, none from the branch; no buckled "
            "state; 1 s (no negative eigenvalue of the own class)") in o
    with open(tmp_path / "post-buckling-summary.csv", newline="") as fh:
        (row,) = list(csv.DictReader(fh))
    assert all(row[c] == "" for c in none if c != "reason")


def test_a_damaged_row_is_exit_3_naming_the_file_and_row(fake, tmp_path, capsys):
    argv = STUDIES["buckling"]["argv"]
    assert run(argv, tmp_path, capsys)[0] == 0
    table = tmp_path / "buckling.csv"
    lines = table.read_text().splitlines(keepends=True)
    cells = lines[2].split(",")
    cells[2] = "3.30.5"                                 # D0_b of the second row
    lines[2] = ",".join(cells)
    table.write_text("".join(lines))
    code, _, err = run(argv, tmp_path, capsys)
    assert code == 3 and len(err.strip().splitlines()) == 1, err
    assert f"cannot use {table}: row 2 (line 3) has '3.30.5' in the number column 'D0_b'" in err
    with pytest.raises(DamagedFileError, match="row 2"):
        read_rows(table)


def test_changed_settings_are_recomputed_with_a_note(fake, tmp_path, capsys):
    argv = ["buckling", "--alpha", "1", "--meshes", "2x1x1", "--D0-step", "0.5",
            "--D0-max", "1", "--solver", "superlu"]
    assert run(argv, tmp_path, capsys)[0] == 0
    (tmp_path / "buckling.png").write_text("a figure of the old rows")
    (tmp_path / ".modes").mkdir()
    (tmp_path / ".modes" / "1_2x1x1.npz").write_text("old mode")
    fake.clear()
    code, _, err = run(argv[:-5] + ["0.25", "--D0-max", "1", "--solver", "superlu"],
                       tmp_path, capsys)
    assert code == 0
    assert len(err.strip().splitlines()) == 1
    assert "differ from these" in err and '"D0_step":0.25' in err
    assert "results are discarded and recomputed" in err
    assert fake == [(1.0, (2, 1, 1), 0.25, 1.0)]
    assert not (tmp_path / "buckling.png").exists() and not (tmp_path / ".modes").exists()
    # D0_b = alpha N1 / 10 + D0_step of the new step; four scan targets 0.25 ... 1
    assert read_rows(tmp_path / "buckling.csv")[0]["D0_b"] == pytest.approx(0.45, abs=1e-12)
    assert [r["D0"] for r in read_rows(tmp_path / "buckling-scan.csv")] == [0.25, 0.5, 0.75,
                                                                          1.0]


@pytest.mark.parametrize("study", list(STUDIES))
def test_repeated_values_are_computed_once(study, fake, tmp_path, capsys):
    argv = ([study, "--alpha", "1", "1.0", "--meshes", "2x2x1", "2x2x1", "--D0-step", "0.5",
             "--D0-max", "1", "--solver", "superlu"])
    assert run(argv, tmp_path, capsys)[0] == 0
    assert len(fake) == 1
    assert len(read_rows(tmp_path / STUDIES[study]["files"][0])) == 1
    # the detail file holds the one unit's rows: targets 0.5 and 1 (buckling), the
    # post-buckling ramp's 0.25 steps below its window and 0.5 from it
    n = len(read_rows(tmp_path / STUDIES[study]["files"][1]))
    assert n == (2 if study == "buckling" else len(pb.charge_targets(0.5, 1.0, 1.0)))


@pytest.mark.parametrize("study", list(STUDIES))
def test_too_many_targets_are_refused_before_any_work(study, fake, tmp_path, capsys):
    code, _, err = run([study, "--quick", "--D0-step", "1e-9"], tmp_path / "res", capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1
    # 1e-9 steps up to D0 = 1 (both --quick) are 1e9 targets, the bound is 1e5
    assert "--D0-step 1e-09 gives" in err and "more than 100000" in err
    assert fake == [] and not (tmp_path / "res").exists()


def test_a_second_writer_of_the_study_is_refused(tmp_path):
    t = TableSpec.plain("t.csv", ("alpha", "mesh", "D0_b"), ("alpha", "mesh"))
    with StudyStore(tmp_path, "demo", {}, t, plan=[(1.0, "2x1x1")]) as first:
        with pytest.raises(LockedError, match=f"pid {os.getpid()}"):
            with StudyStore(tmp_path, "demo", {}, t, plan=[(1.0, "2x1x1")]):
                pass
        first.commit({"alpha": 1.0, "mesh": "2x1x1", "D0_b": 0.5}, {})
    with StudyStore(tmp_path, "demo", {}, t, plan=[]) as again:      # released
        assert again.done((1.0, "2x1x1"))
        assert again.rows() == [{"alpha": 1.0, "mesh": "2x1x1", "D0_b": 0.5}]


def test_detail_rows_of_an_unfinished_unit_are_dropped(tmp_path):
    # a stop between the detail file and the table: the detail rows of unit 2 only
    t = TableSpec.plain("t.csv", ("alpha", "mesh", "D0_b"), ("alpha", "mesh"))
    d = TableSpec.plain("d.csv", ("alpha", "mesh", "D0"), ("alpha", "mesh"))
    (tmp_path / "t.csv").write_text("alpha,mesh,D0_b\n1,2x1x1,0.5\n")
    (tmp_path / "d.csv").write_text("alpha,mesh,D0\n1,2x1x1,0.5\n2,2x1x1,0.5\n2,2x1x1,1\n")
    (tmp_path / ".state").mkdir()
    (tmp_path / ".state" / "demo.json").write_text("{}")
    notes = []
    with StudyStore(tmp_path, "demo", {}, t, (d,), plan=[(1.0, "2x1x1"), (2.0, "2x1x1")],
                    note=notes.append) as st:
        assert notes == [f"{tmp_path / 'd.csv'}: 2 row(s) of 1 unfinished unit(s) dropped"]
        assert st.done((1.0, "2x1x1")) and not st.done((2.0, "2x1x1"))
        assert (tmp_path / "d.csv").read_text() == "alpha,mesh,D0\n1,2x1x1,0.5\n"


@pytest.mark.skipif(not hasattr(signal, "SIGTERM") or not os.path.isdir("/dev/shm"),
                    reason="needs SIGTERM and /dev/shm")
def test_sigterm_stops_like_ctrl_c(tmp_path):
    # the unit's work waits; SIGTERM arrives while the study holds its lock
    script = textwrap.dedent("""
        import os, sys, time
        from pathlib import Path
        import validation.studies.buckling as bk
        def slow(*a, **k):
            print("computing", flush=True)
            time.sleep(120)
        bk.run_one = slow
        # what Intel OpenMP registers when PARDISO is loaded
        Path(f"/dev/shm/__KMP_REGISTERED_LIB_{os.getpid()}_0").write_text("x")
        from validation.cli import main
        sys.exit(main(["buckling", "--alpha", "1", "--meshes", "2x1x1", "--solver",
                       "superlu", "--out", sys.argv[1]]))
    """)
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    p = subprocess.Popen([sys.executable, "-c", script, str(tmp_path)], env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline() == "computing\n"
    p.send_signal(signal.SIGTERM)
    out, err = p.communicate(timeout=60)
    assert p.returncode == 143, err
    assert err.strip() == "terminated (SIGTERM); rerun the same command to resume"
    assert not Path(f"/dev/shm/__KMP_REGISTERED_LIB_{p.pid}_0").exists()
    assert not list(tmp_path.glob(".*.tmp"))
    with StudyStore(tmp_path, "buckling", {"D0_max": 6.0, "D0_step": 0.25,
                                           "solver": "superlu"}, bk.TABLE,
                    plan=[]) as st:                     # the lock was released
        assert not st.done((1.0, "2x1x1"))


def _without_seconds(path):
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    i = rows[0].index("seconds") if "seconds" in rows[0] else None
    return [[c for j, c in enumerate(r) if j != i] for r in rows]


@pytest.mark.slow
def test_buckling_killed_at_random_moments(tmp_path):
    """The real command, killed (SIGKILL) five times at random moments and rerun, leaves
    the files of the uninterrupted run: byte for byte, the timing column aside."""
    argv = [sys.executable, "-m", "validation.cli", "buckling", "--alpha", "1", "0.5",
            "--meshes", "2x1x1", "--D0-step", "0.5", "--D0-max", "1", "--solver", "superlu"]
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    t0 = time.perf_counter()
    subprocess.run(argv + ["--out", str(tmp_path / "ref")], env=env, check=True,
                   capture_output=True)
    whole = time.perf_counter() - t0
    rng = random.Random(7)
    for _ in range(5):
        p = subprocess.Popen(argv + ["--out", str(tmp_path / "k")], env=env,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(rng.uniform(0.3, 1.0) * whole)
        p.kill()
        p.wait()
    subprocess.run(argv + ["--out", str(tmp_path / "k")], env=env, check=True,
                   capture_output=True)
    for f in ("buckling.csv", "buckling-plain.csv"):
        assert _without_seconds(tmp_path / "k" / f) == _without_seconds(tmp_path / "ref" / f)
    k, ref = files_of(tmp_path / "k", "buckling"), files_of(tmp_path / "ref", "buckling")
    assert ref["buckling-scan.csv"] is not None
    for f in ("buckling-scan.csv", "buckling-trials.csv"):     # trials: none on 2x1x1
        assert k[f] == ref[f]


def test_discarded_results_take_the_summary_with_them(tmp_path, capsys, monkeypatch):
    # one real ramp on the one-element equi-biaxial plate, then --force interrupted
    from validation import cases as vc
    import validation.sweep as sweep
    runs = (vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", 1.0, (0.0, 1.0)),)
    monkeypatch.setitem(vc.CASES, "nh-d-e", vc.Case("nh-d-e", "nh-d-e", "test",
                                                     "equibiaxial", quick=runs, full=runs))
    argv = ["validate", "--case", "nh-d-e", "--no-progress", "--solver", "superlu"]
    assert run(argv, tmp_path, capsys)[0] == 0
    assert (tmp_path / "summary.json").is_file() and (tmp_path / "report.md").is_file()

    def interrupted(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(sweep, "run_fe", interrupted)
    code, _, err = run(argv + ["--force"], tmp_path, capsys)
    assert code == 130 and "rerun the same command to resume" in err
    assert not (tmp_path / "summary.json").exists() and not (tmp_path / "report.md").exists()


def test_a_full_disk_names_the_file(fake, tmp_path, capsys, monkeypatch):
    import errno

    import validation.store.files as files_module

    def full(tmp, path, fh):
        # what fsync of a full disk raises: ENOSPC without a file name
        fh.close()
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(files_module, "_replace", full)
    code, _, err = run(STUDIES["buckling"]["argv"], tmp_path, capsys)
    assert code == 3 and len(err.strip().splitlines()) == 1, err
    assert f"cannot use {tmp_path / '.state' / 'buckling.json'}: No space left on device" in err
    assert not list(tmp_path.rglob(".*.tmp"))


@pytest.mark.parametrize("cmd", ["simulate", "bench"])
def test_too_many_steps_are_refused_before_any_work(cmd, tmp_path, capsys):
    out = ["--out", str(tmp_path / "res")] if cmd == "simulate" else []
    code = main([cmd, "--steps", "200000"] + out)
    err = capsys.readouterr().err
    # 200000 steps are 200001 targets, the bound is 1e5
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert "--steps gives 200001 targets up to" in err and "more than 100000" in err
    assert not (tmp_path / "res").exists()

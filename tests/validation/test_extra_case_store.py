"""The validate cases ``wrinkling-fe`` and ``voltage-control`` on the studies' store
(:class:`validation.store.StudyStore`, docs/cli.md "The result folder"): a stop at any
write resumes to the files of an uninterrupted run, a second writer is refused, a cut
last row is named in one line and recomputed, a resumed run says how many rows it kept,
``--force`` recomputes.

The FE work is replaced by stand-ins whose cells are closed forms (the wrinkling rows:
the Stroh value times ``1 + 1e-5``, conftest ``fake_wrinkling``; the voltage paths: five
points with the limit point ``lam1 = 1.25 (1 + 1e-9)`` against ``1.25``), and the figures
by empty files, so that every test runs in about a second.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from types import SimpleNamespace

import pytest

import validation.store.rows as rows_module
import validation.studies.voltage_control as vvc
import validation.studies.wrinkling as wr
from validation.cli import main
from validation.store import FolderLock

FILES = {"wrinkling-fe": ("wrinkling-fe.csv", "wrinkling-fe-elastic.csv"),
         "voltage-control": ("voltage-control.csv",)}
#: relative error of the stand-in limit points (12 significant digits keep it)
LIMIT_ERROR = 1e-9


def _figure(*args, **kwargs):
    return [SimpleNamespace(figure=None)]


def _save(fig, out, name):
    path = Path(out) / f"{name}.png"
    path.write_text("figure")
    return [path]


def fake_voltage(calls):
    """Stand-in of a voltage-controlled path: five points, the limit point the third."""

    def rows_of(r, quick):
        calls.append(vvc._run_key(r))
        rows = []
        for i in range(5):
            kind = "limit" if i == 2 else ("start" if i == 0 else "regular")
            branch = "limit" if i == 2 else ("rising" if i < 2 else "falling")
            lam = 1 + i / 8
            rows.append([vvc.VOLTAGE_CONTROL, vvc._run_key(r), i, r["model"], r["loading"],
                         "coupled", r["s"], r["alpha"], kind, branch, lam, lam / 10,
                         lam / 10, lam**4 / 10, int(i > 2), 0, i <= 2, True,
                         1.25 * (1 + LIMIT_ERROR), 0.125, 1.25, 0.125, 3,
                         "the path ended" if i == 4 else ""])
        return rows

    return rows_of


@pytest.fixture
def fake(monkeypatch, fake_wrinkling):
    """Both cases' FE work and figures replaced; returns the list of computed units."""
    calls = fake_wrinkling(monkeypatch)
    monkeypatch.setattr(vvc, "_rows_of", fake_voltage(calls))
    for module, figure in ((wr, "wrinkling_figure"), (vvc, "voltage_figure")):
        monkeypatch.setattr(module, figure, _figure)
        monkeypatch.setattr(module, "save_figure", _save)
    return calls


def argv(case, out, *extra):
    return ["validate", "--quick", "--case", case, "--out", str(out), "--no-progress",
            *extra]


def files_of(out, case):
    return {f: (out / f).read_bytes() for f in FILES[case]}


def summary_of(out, case):
    return json.loads((out / "summary.json").read_text())["cases"][case]


class _Killed(BaseException):
    """Stands for a kill: not an Exception, so nothing of the case catches it."""


@pytest.mark.parametrize("case", list(FILES))
def test_a_stop_at_any_write_resumes_to_the_uninterrupted_files(case, fake, tmp_path,
                                                                 capsys, monkeypatch):
    assert main(argv(case, tmp_path / "ref")) == 0
    ref = files_of(tmp_path / "ref", case)
    n_units = len(fake)
    # quick: 8 wrinkling grid points and 2 elastic ones; 2 voltage paths of 5 points
    assert n_units == (10 if case == "wrinkling-fe" else 2)
    if case == "voltage-control":
        # the limit points read back from the CSV: 12 significant digits keep 1e-9
        assert summary_of(tmp_path / "ref", case)["max_rel_error"] == pytest.approx(
            LIMIT_ERROR, rel=1e-3)
    # every unit is one write of the wrinkling tables, two of voltage-control (its points,
    # then its row of the resume table)
    n_writes = n_units * (1 if case == "wrinkling-fe" else 2)
    real = rows_module.write_csv_atomic
    for k in range(n_writes):
        out = tmp_path / f"k{k}"
        count = [0]

        def stop_at_k(path, header, rows):
            count[0] += 1
            if count[0] == k + 1:
                if k % 2:                      # killed while writing the temporary file
                    Path(path).with_name(f".{Path(path).name}.{os.getpid()}.tmp"
                                         ).write_text("run,mo")
                raise _Killed
            return real(path, header, rows)

        monkeypatch.setattr(rows_module, "write_csv_atomic", stop_at_k)
        with pytest.raises(_Killed):
            main(argv(case, out))
        monkeypatch.setattr(rows_module, "write_csv_atomic", real)
        capsys.readouterr()
        fake.clear()
        assert main(argv(case, out)) == 0
        err = capsys.readouterr().err
        # the units done before the stop are kept, and said so; the rest are computed once
        done = k if case == "wrinkling-fe" else k // 2
        assert len(fake) == n_units - done, f"stopped at write {k + 1}"
        assert summary_of(out, case)["resumed_steps"] == (done if case == "wrinkling-fe"
                                                          else 5 * done)
        if case == "voltage-control":
            # stopped between a path's points and its row of the resume table: the points
            # are dropped, with a line
            csv = out / "voltage-control.csv"
            assert err.splitlines() == (
                [f"skfem-dielectric: {csv}: 5 row(s) of 1 unfinished unit(s) dropped"] * (k % 2)
                + [f"skfem-dielectric: {csv}: kept {done} of 2 paths ({5 * done} rows) of an "
                   f"earlier run"] * bool(done))
        assert files_of(out, case) == ref, f"stopped at write {k + 1}"
        assert not list(out.rglob(".*.tmp"))


@pytest.mark.parametrize("case", list(FILES))
def test_a_second_writer_is_refused(case, fake, tmp_path, capsys):
    (tmp_path / ".state").mkdir()
    with FolderLock(tmp_path / ".state" / f"{case}.lock", "test"):
        code = main(argv(case, tmp_path))
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert f"being written by another process (pid {os.getpid()}:" in err
    assert fake == [] and sorted(p.name for p in tmp_path.iterdir()) == [".state"]


def test_a_cut_or_edited_voltage_path_is_recomputed_with_one_line(fake, tmp_path, capsys):
    assert main(argv("voltage-control", tmp_path)) == 0
    capsys.readouterr()
    path = tmp_path / "voltage-control.csv"
    ref = path.read_bytes()
    path.write_bytes(ref[:-5])                              # the last row cut short
    fake.clear()
    assert main(argv("voltage-control", tmp_path)) == 0
    err = capsys.readouterr().err
    note = (f"{path}: its last row is incomplete (no line end); kept aside in "
            f"{path.name}.damaged")
    assert err.splitlines() == [f"skfem-dielectric: {note}",
                                f"skfem-dielectric: {path}: kept 1 of 2 paths (5 rows) of an "
                                f"earlier run"]
    assert fake == ["uniaxial-free_nh_s1"]                 # the second path only
    assert path.read_bytes() == ref
    assert summary_of(tmp_path, "voltage-control")["repairs"] == [note]
    # a whole row deleted from the first path (line ends intact): that path is recomputed
    lines = ref.decode().splitlines(keepends=True)
    path.write_text("".join(lines[:2] + lines[3:]))
    fake.clear()
    assert main(argv("voltage-control", tmp_path)) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0] == (f"skfem-dielectric: {path}: the rows of 1 unit(s) are missing or extra "
                      f"(equibiaxial_nh_s1); recomputed")
    assert len(err) == 2 and fake == ["equibiaxial_nh_s1"]
    assert path.read_bytes() == ref


@pytest.mark.parametrize("case", list(FILES))
def test_force_recomputes_and_a_finished_run_is_kept(case, fake, tmp_path, capsys):
    assert main(argv(case, tmp_path)) == 0
    ref = files_of(tmp_path, case)
    n_units = len(fake)
    fake.clear()
    assert main(argv(case, tmp_path)) == 0              # all kept, nothing computed
    assert fake == [] and files_of(tmp_path, case) == ref
    assert "kept" in capsys.readouterr().err
    assert main(argv(case, tmp_path, "--force")) == 0
    assert len(fake) == n_units and files_of(tmp_path, case) == ref
    assert capsys.readouterr().err == ""

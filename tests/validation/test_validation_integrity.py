"""Integrity of a validation folder: concurrent writers, corrupted files, full summaries.

Every test compares bytes: after a refused second writer, or a rerun on a corrupted
folder, the CSVs must equal those of one uninterrupted run. The FE solver is the
closed-form :class:`FakeRunner` of tests/validation/test_validation.py (its answer depends on the
carried state, so a lost or wrong state changes the files), except in
:func:`test_real_fe_state_of_the_wrong_size`.
"""

from __future__ import annotations

import json
import multiprocessing as mp
import time
from pathlib import Path

import numpy as np
import pytest

from test_validation import FakeRunner, Interrupted, eq_case, uni_case
from validation import cases as vc
from validation.fe import run_fe
from validation.store import LockedError
from validation.sweep import run_case, validate
from validation.table import read_table

NAME = "uni-axial-ideal"
FILES = (f"{NAME}.csv", f"{NAME}_fields.csv")


def _files(out: Path) -> dict:
    return {n: (out / n).read_bytes() if (out / n).exists() else None for n in FILES}


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The files of one uninterrupted run of the uni-axial case with fields."""
    out = tmp_path_factory.mktemp("ref")
    run_case(uni_case(fields=True), out, runner=FakeRunner(), progress=False)
    files = _files(out)
    assert all(files.values())
    return files


def _lines(path: Path) -> list[str]:
    return path.read_text().splitlines(keepends=True)


def _state_files(out: Path, done: bool | None = None) -> list[Path]:
    found = []
    for p in sorted((out / ".state" / NAME).glob("*.npz")):
        with np.load(p) as z:
            if done is None or bool(z["__done__"]) == done:
                found.append(p)
    return found


def _cut_last_line(out):
    p = out / FILES[0]
    data = p.read_bytes()
    p.write_bytes(data[:-7])                        # a half-written last line


def _drop_last_field(out):
    p = out / FILES[0]
    lines = _lines(p)
    lines[-1] = lines[-1].rstrip("\n").rsplit(",", 1)[0] + "\n"
    p.write_text("".join(lines))


def _edit_middle_row(out):
    p = out / FILES[0]
    lines = _lines(p)
    i = len(lines) // 2
    cells = lines[i].split(",")
    j = cells.index(next(c for c in cells[8:] if any(ch.isdigit() for ch in c)))
    d = next(ch for ch in cells[j] if ch.isdigit())
    cells[j] = cells[j].replace(d, str((int(d) + 1) % 10), 1)     # one digit changed
    edited = ",".join(cells)
    assert edited != lines[i]
    lines[i] = edited
    p.write_text("".join(lines))


def _delete_rows(out):
    p = out / FILES[0]
    lines = _lines(p)
    del lines[3:5]
    p.write_text("".join(lines))


def _empty_csv(out):
    (out / FILES[0]).write_text("")


def _delete_csv(out):
    (out / FILES[0]).unlink()


def _edit_fields(out):
    p = out / FILES[1]
    lines = _lines(p)
    lines[2] = lines[2].replace("0", "1", 1)
    p.write_text("".join(lines))


def _truncate_state(out):
    p = _state_files(out)[0]
    data = p.read_bytes()
    p.write_bytes(data[: len(data) // 2])           # zipfile.BadZipFile on load


def _truncate_manifest(out):
    p = out / ".state" / NAME / "manifest.json"
    text = p.read_text()
    p.write_text(text[: len(text) // 2])


CORRUPTIONS = {
    "half-written last line": (_cut_last_line, f"{NAME}.csv"),
    "missing last field": (_drop_last_field, f"{NAME}.csv"),
    "edited middle row": (_edit_middle_row, "differ from those saved"),
    "deleted rows": (_delete_rows, f"{NAME}.csv"),
    "emptied csv": (_empty_csv, f"{NAME}.csv"),
    "deleted csv": (_delete_csv, f"{NAME}.csv"),
    "edited fields row": (_edit_fields, f"{NAME}_fields.csv"),
    "truncated state": (_truncate_state, "BadZipFile"),
    "truncated manifest": (_truncate_manifest, "manifest.json is unreadable"),
}


@pytest.mark.parametrize("interrupted", [False, True], ids=["complete", "interrupted"])
@pytest.mark.parametrize("kind", list(CORRUPTIONS))
def test_rerun_repairs_a_corrupted_folder(tmp_path, reference, capsys, kind, interrupted):
    corrupt, says = CORRUPTIONS[kind]
    case = uni_case(fields=True)
    if interrupted:
        with pytest.raises(Interrupted):        # two runs done, the third half-way
            run_case(case, tmp_path, runner=FakeRunner(interrupt_after=14), progress=False)
    else:
        run_case(case, tmp_path, runner=FakeRunner(), progress=False)
    capsys.readouterr()
    corrupt(tmp_path)
    res = run_case(case, tmp_path, runner=FakeRunner(), progress=False)
    err = capsys.readouterr().err
    assert _files(tmp_path) == reference, kind     # byte for byte an uninterrupted run
    assert says in err and "recomputed" in err, err
    assert res.repairs and all(ln.startswith("skfem-dielectric: ") for ln in err.splitlines())
    # and the repaired folder is trusted again: a third run has nothing to do or say
    again = FakeRunner()
    run_case(case, tmp_path, runner=again, progress=False)
    assert again.calls == 0 and capsys.readouterr().err == ""
    assert _files(tmp_path) == reference


def test_state_vector_of_the_wrong_size(tmp_path, reference, capsys):
    case = uni_case(fields=True)
    with pytest.raises(Interrupted):
        run_case(case, tmp_path, runner=FakeRunner(interrupt_after=14), progress=False)
    (path,) = _state_files(tmp_path, done=False)
    with np.load(path) as z:
        arrays = {k: z[k] for k in z.files}
    arrays["x_acc"] = np.zeros(3)                   # the fake's state is a scalar
    np.savez(path, **arrays)
    capsys.readouterr()
    run_case(case, tmp_path, runner=FakeRunner(), progress=False)
    assert "could not continue from the saved state" in capsys.readouterr().err
    assert _files(tmp_path) == reference


def test_real_fe_state_of_the_wrong_size(tmp_path, capsys):
    # the real runner on a one-element plate: a state vector that does not fit the mesh
    # (x of another mesh) made numpy fail to broadcast; now the run is recomputed
    runs = (vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", 1.0, (0.0, 1.0, 2.0, 3.0)),)
    case = vc.Case("nh-d-e", "nh-d-e", "test", "equibiaxial", quick=runs, full=runs)
    run_case(case, tmp_path / "ref", progress=False)

    def stop_after_two(spec, start, state, on_step):
        def cb(i, rec, st):
            on_step(i, rec, st)
            if i == 1:
                raise Interrupted
        return run_fe(spec, start, state, cb)

    with pytest.raises(Interrupted):
        run_case(case, tmp_path / "b", runner=stop_after_two, progress=False)
    path = tmp_path / "b" / ".state" / "nh-d-e" / f"{runs[0].key}.npz"
    with np.load(path) as z:
        arrays = {k: z[k] for k in z.files}
    arrays["x_x"] = np.r_[arrays["x_x"], np.zeros(7)]
    np.savez(path, **arrays)
    capsys.readouterr()
    run_case(case, tmp_path / "b", progress=False)
    assert "could not continue" in capsys.readouterr().err
    assert (tmp_path / "b" / "nh-d-e.csv").read_bytes() == \
        (tmp_path / "ref" / "nh-d-e.csv").read_bytes()


def test_state_of_other_settings_is_not_trusted(tmp_path, capsys):
    # a state saved for other targets of the same run (copied in, or an older layout)
    case = eq_case(n_s=1)
    run_case(case, tmp_path / "ref", runner=FakeRunner(), progress=False)
    other = eq_case(n_s=1, n=2)
    with pytest.raises(Interrupted):
        run_case(other, tmp_path / "b", runner=FakeRunner(interrupt_after=2), progress=False)
    with pytest.raises(Interrupted):
        run_case(case, tmp_path / "c", runner=FakeRunner(interrupt_after=2), progress=False)
    key = case.quick[0].key
    src = tmp_path / "b" / ".state" / "nh-d-e" / f"{key}.npz"
    (tmp_path / "c" / ".state" / "nh-d-e" / f"{key}.npz").write_bytes(src.read_bytes())
    capsys.readouterr()
    run_case(case, tmp_path / "c", runner=FakeRunner(), progress=False)
    assert "saved for other settings" in capsys.readouterr().err
    assert (tmp_path / "c" / "nh-d-e.csv").read_bytes() == \
        (tmp_path / "ref" / "nh-d-e.csv").read_bytes()


def test_rows_of_the_runs_come_back_in_order(tmp_path, reference):
    # a run recomputed after later runs were kept: the rewritten CSV is in case order
    case = uni_case(fields=True)
    run_case(case, tmp_path, runner=FakeRunner(), progress=False)
    first = case.quick[0].key
    (tmp_path / ".state" / NAME / f"{first}.npz").unlink()
    again = FakeRunner()
    run_case(case, tmp_path, runner=again, progress=False)
    t = read_table(tmp_path / FILES[0])
    assert again.calls == int(np.sum(t["run"] == first))      # only that run recomputed
    assert _files(tmp_path) == reference


# --------------------------------------------------------------------------- concurrency
class SlowRunner(FakeRunner):
    """The fake solver at 20 ms a step; sets ``started`` after its first step."""

    def __init__(self, started=None):
        super().__init__()
        self.started = started

    def __call__(self, spec, start, state, on_step):
        def slow(i, rec, st):
            stop = on_step(i, rec, st)
            if self.started is not None:
                self.started.set()
            time.sleep(0.02)
            return stop
        return super().__call__(spec, start, state, slow)


def two_settings():
    full = uni_case(fields=True)
    quick = tuple(vc.RunSpec(r.geometry, r.model, r.variant, r.s, r.D0[::4], alpha=r.alpha,
                             record_fields=True) for r in full.quick)
    return vc.Case(NAME, NAME, "test", "uniaxial", quick=quick, full=full.quick)


def _writer(out, quick, force, started, wait_for, queue):
    if wait_for is not None:
        wait_for.wait(30)
    try:
        run_case(two_settings(), out, quick=quick, force=force, runner=SlowRunner(started),
                 progress=False)
        queue.put(("ok", ""))
    except LockedError as exc:
        queue.put(("locked", str(exc)))


@pytest.mark.parametrize("second", ["same settings", "--force", "quick during full"])
def test_second_writer_during_a_run(tmp_path, reference, second):
    try:
        ctx = mp.get_context("fork")
    except ValueError:
        pytest.skip("needs the fork start method")
    started, q1, q2 = ctx.Event(), ctx.Queue(), ctx.Queue()
    first = ctx.Process(target=_writer, args=(tmp_path, False, False, started, None, q1))
    other = ctx.Process(target=_writer, args=(tmp_path, second == "quick during full",
                                              second == "--force", None, started, q2))
    first.start()
    other.start()
    r1, r2 = q1.get(timeout=60), q2.get(timeout=60)
    first.join(10)
    other.join(10)
    assert r1 == ("ok", "")
    assert r2[0] == "locked" and "being written by another process (pid " in r2[1], r2
    assert f"pid {first.pid}:" in r2[1]
    assert _files(tmp_path) == reference        # no duplicate, lost or mixed rows
    t = read_table(tmp_path / FILES[0])
    pairs = list(zip(t["run"], t["step"]))
    assert len(pairs) == len(set(pairs))
    again = FakeRunner()                        # the folder resumes as a finished run
    run_case(two_settings(), tmp_path, runner=again, progress=False)
    assert again.calls == 0 and _files(tmp_path) == reference


def test_lock_file_outlives_force(tmp_path):
    case = eq_case(n_s=1)
    run_case(case, tmp_path, runner=FakeRunner(), progress=False)
    lock = tmp_path / ".state" / "nh-d-e.lock"
    inode = lock.stat().st_ino
    run_case(case, tmp_path, runner=FakeRunner(), force=True, progress=False)
    run_case(eq_case(n_s=2), tmp_path, runner=FakeRunner(), progress=False)   # new manifest
    assert lock.stat().st_ino == inode          # one lock file for the life of the folder


# --------------------------------------------------------------------------- the summary
def test_summary_covers_cases_run_one_after_the_other(tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    monkeypatch.setitem(vc.CASES, "nh-d-e", eq_case())
    monkeypatch.setitem(vc.CASES, "gent-d-e", eq_case(n_s=1, name="gent-d-e"))
    both = tmp_path / "both"
    validate(["nh-d-e", "gent-d-e"], both, runner=FakeRunner(), progress=False)
    seq = tmp_path / "seq"
    validate(["nh-d-e"], seq, runner=FakeRunner(), progress=False)
    validate(["gent-d-e"], seq, runner=FakeRunner(), progress=False)
    s_both = json.loads((both / "summary.json").read_text())
    s_seq = json.loads((seq / "summary.json").read_text())
    assert sorted(s_seq["cases"]) == ["gent-d-e", "nh-d-e"]
    drop = {"runtime_s"}
    for name in ("nh-d-e", "gent-d-e"):
        a = {k: v for k, v in s_both["cases"][name].items() if k not in drop}
        b = {k: v for k, v in s_seq["cases"][name].items() if k not in drop}
        assert a == b, name
    assert s_seq["cases"]["nh-d-e"]["n_steps"] == 10 and s_seq["cases"]["gent-d-e"]["n_steps"] == 5
    # the first case keeps its runtime from the earlier summary
    first = json.loads(json.dumps(s_seq["cases"]["nh-d-e"]))
    assert first["runtime_s"] > 0
    report = (seq / "report.md").read_text()
    assert "| nh-d-e |" in report and "| gent-d-e |" in report
    assert report.count("\n| ") == 4              # header, rule, 2 cases

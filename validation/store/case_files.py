"""The files of a case in its output folder and the resume plan of its runs.

* :class:`CaseFiles` -- the two CSVs of a case (``<case>.csv``, ``<case>_fields.csv``):
  rows appended as the ramps go, rewritten atomically in the canonical order;
* :func:`case_manifest`, :func:`spec_sig` -- the settings of a case's runs, saved beside
  their states (a state of other settings is not trusted);
* :func:`resume_plan` -- what a rerun keeps: each run's rows must match the row count and
  checksum saved with its state (:mod:`.files`), else the run is recomputed.
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import Iterable

from ..specs import Case, RunSpec
from ..table import FIELD_KEYS, csv_columns
from .files import RowDigest, dumps, load_state, write_csv_atomic

__all__ = ["state_path", "case_manifest", "spec_sig", "append_csv_rows", "CaseFiles",
           "resume_plan"]


def state_path(state_dir: Path, spec: RunSpec) -> Path:
    """The resume state file of the run ``spec`` in the case's state folder."""
    return state_dir / f"{spec.key}.npz"


def _manifest_entry(r: RunSpec) -> list:
    return [r.key, list(r.D0), [list(m) for m in r.mesh], r.record_fields, r.record_maps,
            r.stop_at_breakdown] + (["buckling"] if r.buckling else [])


def case_manifest(case: Case, runs: tuple) -> dict:
    """The settings of the runs of ``case`` (key, targets, mesh, recording and stop flags),
    saved as ``.state/<case>/manifest.json``: a rerun with other settings starts afresh."""
    return {"case": case.name, "runs": [_manifest_entry(r) for r in runs]}


def spec_sig(spec: RunSpec) -> str:
    """The settings of one run as JSON, saved with its state (:func:`~.files.save_state`)."""
    return dumps(_manifest_entry(spec))


def _read_csv(path: Path) -> tuple[list[str] | None, list[list[str]], str]:
    """``(header, rows, problem)``; an unreadable file gives no rows and says why."""
    if not path.exists():
        return None, [], ""
    try:
        with open(path, newline="") as fh:
            rows = list(csv.reader(fh))
    except (csv.Error, UnicodeDecodeError) as exc:
        return None, [], f"{path} is unreadable ({exc})"
    return (rows[0], rows[1:], "") if rows else (None, [], "")


def _rows_by_run(rows, case_name: str, keys, ncols: int) -> tuple[dict, int]:
    """The complete rows of each run (in file order) and the number of other rows."""
    by, bad = {k: [] for k in keys}, 0
    for r in rows:
        if len(r) == ncols and r[0] == case_name and r[1] in by:
            by[r[1]].append(r)
        else:
            bad += 1
    return by, bad


def append_csv_rows(path: Path, header: list[str], rows: Iterable[list[str]]) -> None:
    """Append ``rows`` to the CSV ``path`` (``header`` first if the file is new), flushed."""
    new = not path.exists()
    with open(path, "a", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        if new:
            w.writerow(header)
        w.writerows(rows)
        fh.flush()


class CaseFiles:
    """The two CSVs of a case: rows appended as the ramps go, kept per run in memory.

    :meth:`rewrite` writes both files atomically in the canonical order (runs in the
    order of the case, steps in order), the order of an uninterrupted run.
    """

    def __init__(self, case: Case, runs: tuple, csv_path: Path, fields_path: Path):
        self.case, self.keys = case, [r.key for r in runs]
        self.csv_path, self.fields_path = csv_path, fields_path
        self.header, self.f_header = csv_columns(case), None
        self.rows = {k: [] for k in self.keys}
        self.frows = {k: [] for k in self.keys}

    def add(self, key: str, row: list[str]) -> None:
        self.rows[key].append(row)
        append_csv_rows(self.csv_path, self.header, [row])

    def add_fields(self, key: str, header: list[str], rows: list[list[str]]) -> None:
        if self.f_header is None:
            self.f_header = header
        self.frows[key] += rows
        append_csv_rows(self.fields_path, self.f_header, rows)

    def drop(self, key: str) -> None:
        self.rows[key], self.frows[key] = [], []
        self.rewrite()

    def rewrite(self) -> None:
        write_csv_atomic(self.csv_path, self.header, [r for k in self.keys for r in self.rows[k]])
        frows = [r for k in self.keys for r in self.frows[k]]
        if frows:
            write_csv_atomic(self.fields_path, self.f_header, frows)
        elif self.fields_path.exists():
            self.fields_path.unlink()



def _check_rows(st: dict, rows: list, frows: list, files: CaseFiles) -> str:
    """Why the rows of a run do not match its saved state (empty when they do)."""
    for name, have, n, sha in ((files.csv_path.name, rows, st["rows"], st["sha"]),
                               (files.fields_path.name, frows, st["frows"], st["fsha"])):
        if len(have) < n:
            return f"{name} holds {len(have)} of its {n} saved rows"
        if RowDigest.of(have[:n]).hexdigest() != sha:
            return f"its rows in {name} differ from those saved with its state"
    if not st["step"] + 1 <= st["rows"] <= st["step"] + 2:
        return f"its saved state counts {st['rows']} rows for step {st['step']}"
    return ""


def resume_plan(case, runs, files: CaseFiles, state_dir: Path, note) -> tuple[list, int]:
    """Read the CSVs and states of a case, keep what verifies.

    Parameters
    ----------
    case : Case
    runs : tuple of RunSpec
        The case's runs of this setting (quick or full).
    files : CaseFiles
        The case's CSVs; the rows kept are put into it.
    state_dir : Path
        ``.state/<case>/`` with a state file per run.
    note : callable
        ``note(message)``: what was repaired (a run recomputed, rows dropped).

    Returns
    -------
    plan : list of tuple
        ``(spec, start, state, rows, frows)`` of every run still to compute: its first
        target, the saved arrays to continue from (``None`` from the start) and the
        :class:`~.files.RowDigest` of its kept rows in the two CSVs.
    resumed : int
        The number of steps kept from earlier runs.
    """
    header, rows, why = _read_csv(files.csv_path)
    if why or (header is not None and header != files.header):
        note(why or f"{files.csv_path} has another header than {files.header}")
        rows = []
    by_run, bad = _rows_by_run(rows, case.name, files.keys, len(files.header))
    f_header, frows, fwhy = _read_csv(files.fields_path)
    if fwhy or (f_header is not None and f_header[:4] != FIELD_KEYS):
        note(fwhy or f"{files.fields_path} has another header")
        f_header, frows = None, []
    fby_run, fbad = _rows_by_run(frows, case.name, files.keys,
                                 len(f_header) if f_header else 0)
    for n, path in ((bad, files.csv_path), (fbad, files.fields_path)):
        if n:
            note(f"{path}: {n} incomplete or unreadable row(s) dropped")
    files.f_header = f_header
    plan, resumed = [], 0
    for spec in runs:
        path = state_path(state_dir, spec)
        st, why = load_state(path, spec_sig(spec))
        r, fr = by_run[spec.key], fby_run[spec.key]
        if st is not None:
            why = _check_rows(st, r, fr, files)
        if st is None or why:
            if why:
                note(f"run {spec.key} of case {case.name}: {why}; recomputed from the start")
            elif len(r) > 1:
                note(f"run {spec.key} of case {case.name}: {len(r)} rows without a saved "
                     f"state; recomputed from the start")
            if path.exists():
                path.unlink()
            plan.append((spec, 0, None, RowDigest(), RowDigest()))
            continue
        files.rows[spec.key], files.frows[spec.key] = r[:st["rows"]], fr[:st["frows"]]
        if st["done"] and (len(r) > st["rows"] or len(fr) > st["frows"]):
            note(f"run {spec.key} of case {case.name}: rows after its last saved step dropped")
        resumed += st["step"] + 1
        if not st["done"]:
            plan.append((spec, st["step"] + 1, st["state"], RowDigest.of(r[:st["rows"]]),
                         RowDigest.of(fr[:st["frows"]])))
    return plan, resumed


"""Run the FE ramps of a case, write its tidy CSV step by step, resume after interruption.

Data flow: for every :class:`~validation.cases.RunSpec` of a case a
*runner* (by default :func:`validation.fe.run_fe`, the real FE solver) ramps
``D0`` through the targets and calls back after each converged target. The
callback appends one CSV row to ``DIR/<case>.csv`` (and field rows to
``DIR/<case>_fields.csv``), then saves the FE state to
``DIR/.state/<case>/<run>.npz``. A rerun with the same ``DIR`` keeps the rows
up to the last saved state and resumes the ramp from it, so an interrupted
sweep produces the same files as an uninterrupted one; ``force=True`` starts
afresh.

The runner protocol (any callable, picklable for process pools)::

    runner(spec, start, state, on_step) -> RunOutcome

runs the targets ``spec.D0[start:]`` from ``state`` (``None`` when
``start == 0``) and calls ``on_step(index, record, state)`` after every
converged target with a :class:`StepRecord` and a ``dict`` of arrays that
lets it continue from there; ``on_step`` returns ``True`` to end the ramp
(breakdown reached).
"""

from __future__ import annotations

import csv
import errno
import json
import os
import shutil
import time
from concurrent.futures import Executor, ProcessPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterable

import numpy as np

import analytic as an

from .cases import CASES, Case, RunSpec, analytic_model, get_case
from .fe import run_fe
from .figures import case_figure, save_figure
from .progress import Progress, notice
from .records import StepRecord, buckling_crossing
from .report import write_report, write_summary
from .store import (FolderLock, RowDigest, dumps, load_state, save_state, write_csv_atomic,
                    write_text_atomic)
from .extra_cases import EXTRA_CASES

__all__ = [
    "CaseResult",
    "BREAKDOWN_TOL",
    "csv_columns",
    "run_case",
    "run_cases",
    "read_table",
    "validate",
    "make_figure",
    "folder_results",
]

#: The paper's breakdown: ``min P33/mu`` along the centre line (which runs into
#: the clamps), outside the clamps' boundary layer of width ``2H`` (column
#: ``min_P33_interior``), below ``-BREAKDOWN_TOL``. In the central zone ``P33`` is close
#: to its homogeneous value 0; on coarse meshes it scatters by a few 1e-3
#: around it, while at the breakdown it drops by about 0.2 within one
#: ``D0`` step of 0.5, so ``1e-2`` separates the two.
BREAKDOWN_TOL = 1e-2

_FMT = ".12g"   # 12 significant digits (and at most 12 decimals) in the CSV


@dataclass
class CaseResult:
    """Summary of one case, computed from its CSV (so identical after a resume)."""

    name: str
    figure: str
    csv: str
    n_runs: int
    n_steps: int
    max_rel_error: float | None
    max_rel_error_by_run: dict = field(default_factory=dict)
    breakdown_D0: dict = field(default_factory=dict)
    breakdown_D0_by_alpha: dict = field(default_factory=dict)
    buckling_D0: dict = field(default_factory=dict)
    buckling_D0_by_alpha: dict = field(default_factory=dict)
    reasons: dict = field(default_factory=dict)
    runtime_s: float = 0.0
    resumed_steps: int = 0
    quick: bool | None = None
    repairs: list = field(default_factory=list)


def csv_columns(case: Case) -> list[str]:
    """Columns of ``DIR/<case>.csv``.

    The run (``case``, ``run``, ``step``, ``model``, ``variant``, ``alpha`` for the
    uni-axial cases, ``s``), the load ``D0``, FE and analytic stretches at the plate
    centre, the ``P33/mu`` minima, the verdicts ``converged``, ``stable``, the stability
    counts ``n_negative`` (negative eigenvalues of the reduced stiffness), ``n_unstable``
    (those not classified as clamp-corner artefacts) and ``lowest_eig``, ``breakdown`` and
    the Newton ``iterations``; the uni-axial cases also the whole plate's spectrum of the
    runs that analyse it (``n_negative_plate``, ``physical_eig``, ``physical_class``, see
    :func:`validation.fe.plate_buckling_columns`; empty for the others).

    Parameters
    ----------
    case : Case

    Returns
    -------
    list of str
    """
    cols = ["case", "run", "step", "model", "variant"]
    if case.geometry == "uniaxial":
        cols.append("alpha")
    cols += ["s", "D0", "lam1_fe", "lam1_analytic", "lam3_fe", "lam3_analytic", "min_P33",
             "min_P33_interior", "min_P33_clamp", "converged", "stable", "n_negative",
             "n_unstable", "lowest_eig", "breakdown", "iterations"]
    if case.geometry == "uniaxial":
        cols += ["n_negative_plate", "physical_eig", "physical_class"]
    return cols


def _fmt(x) -> str:
    if x is None:
        return ""
    if isinstance(x, (bool, np.bool_)):
        return "True" if x else "False"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, str):
        return x
    x = float(x)
    if not np.isfinite(x):
        return ""
    # 12 significant digits and at most 12 decimals: round-off noise (P33 ~ 1e-15 on a
    # homogeneous plate, last bits of threaded BLAS sums) does not reach the file
    return format(round(x, 12) + 0.0, _FMT)


def _analytic(spec: RunSpec, D0: float) -> tuple[float, float]:
    """``(lam1, lam3)`` of the homogeneous theory: Eq. (loading_gent) or Eq. (DEuniax)."""
    model = analytic_model(spec.model)
    if spec.geometry == "equibiaxial":
        lam = float(an.equibiaxial_lam(D0, spec.s, model))
        return lam, lam
    lam1 = float(an.uniaxial_lam1(D0, spec.s, model))
    lam3 = float(an.uniaxial_lam3(lam1, spec.s, model)) if np.isfinite(lam1) else float("nan")
    return lam1, lam3


def _breakdown(spec: RunSpec, rec: StepRecord) -> bool:
    if spec.geometry != "uniaxial":
        return False
    p = rec.min_P33_interior if np.isfinite(rec.min_P33_interior) else rec.min_P33
    return bool(np.isfinite(p) and p < -BREAKDOWN_TOL)


def _row(case: Case, spec: RunSpec, index: int, rec: StepRecord | None, converged: bool,
         breakdown: bool, D0: float) -> list[str]:
    lam1_an, lam3_an = _analytic(spec, D0)
    vals = {"case": case.name, "run": spec.key, "step": index, "model": spec.model,
            "variant": spec.variant, "alpha": spec.alpha, "s": spec.s, "D0": D0,
            "lam1_fe": rec.lam1 if rec else None, "lam1_analytic": lam1_an,
            "lam3_fe": rec.lam3 if rec else None, "lam3_analytic": lam3_an,
            "min_P33": rec.min_P33 if rec else None,
            "min_P33_interior": rec.min_P33_interior if rec else None,
            "min_P33_clamp": rec.min_P33_clamp if rec else None,
            "converged": converged, "stable": rec.stable if rec else None,
            "n_negative": rec.n_negative if rec else None,
            "n_unstable": rec.n_unstable if rec else None,
            "lowest_eig": rec.lowest_eig if rec else None,
            "breakdown": breakdown, "iterations": rec.iterations if rec else None,
            "n_negative_plate": rec.n_negative_plate if rec else None,
            "physical_eig": rec.physical_eig if rec else None,
            "physical_class": rec.physical_class if rec else None}
    return [_fmt(vals[c]) for c in csv_columns(case)]



#: Verdict columns: always bool/None, also when every cell is empty (e.g. ``stable``
#: without PARDISO), so that a table's column types do not depend on its content.
_BOOL_COLUMNS = frozenset({"converged", "stable", "breakdown"})


def read_table(path) -> dict[str, np.ndarray]:
    """Read a tidy CSV written by the harness into columns.

    Numeric columns become float arrays (empty cells ``nan``), ``True``/``False``
    columns (and always ``converged``, ``stable``, ``breakdown``) become object arrays of
    bool/None, the others string arrays. Rows with another number of cells than the
    header (a line cut short by a crash) are left out.
    """
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    if not rows:
        return {}
    header = rows[0]
    body = [r for r in rows[1:] if len(r) == len(header)]   # a half-written line is no row
    table = {}
    for j, name in enumerate(header):
        col = [r[j] for r in body]
        if name in _BOOL_COLUMNS or (col and all(v in ("True", "False", "") for v in col)
                                     and any(col)):
            table[name] = np.array([None if v == "" else v == "True" for v in col], dtype=object)
            continue
        try:
            table[name] = np.array([float(v) if v != "" else np.nan for v in col], dtype=float)
        except ValueError:
            table[name] = np.array(col, dtype=str)
    return table


# --------------------------------------------------------------------------- files of a case
_FIELD_KEYS = ["case", "run", "step", "D0"]


def _state_path(state_dir: Path, spec: RunSpec) -> Path:
    return state_dir / f"{spec.key}.npz"


def _manifest_entry(r: RunSpec) -> list:
    return [r.key, list(r.D0), [list(m) for m in r.mesh], r.record_fields, r.record_maps,
            r.stop_at_breakdown] + (["buckling"] if r.buckling else [])


def _manifest(case: Case, runs: tuple) -> dict:
    return {"case": case.name, "runs": [_manifest_entry(r) for r in runs]}


def _spec_sig(spec: RunSpec) -> str:
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


def _append(path: Path, header: list[str], rows: Iterable[list[str]]) -> None:
    new = not path.exists()
    with open(path, "a", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        if new:
            w.writerow(header)
        w.writerows(rows)
        fh.flush()


class _CaseFiles:
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
        _append(self.csv_path, self.header, [row])

    def add_fields(self, key: str, header: list[str], rows: list[list[str]]) -> None:
        if self.f_header is None:
            self.f_header = header
        self.frows[key] += rows
        _append(self.fields_path, self.f_header, rows)

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


# --------------------------------------------------------------------------- one case
def run_case(case: Case | str, out, *, quick: bool = False, force: bool = False,
             runner: Callable | None = None, progress: bool | None = None) -> CaseResult:
    """Run (or resume) every FE ramp of ``case``, writing its CSV step by step.

    The case is locked (``flock`` on ``out/.state/<case>.lock``, a file that is never
    deleted) before anything is read or cleared; a second process writing the same
    case into the same folder gets :class:`~validation.store.LockedError`. A resume
    verifies before it trusts: each run's rows must match the row count and checksum
    saved with its state, and the state must belong to the run's settings; a run that
    fails a check is recomputed (from the start) and a line on stderr says so.

    Parameters
    ----------
    case : Case or str
        The case or its name.
    out : path-like
        Output folder; everything is written below it (``<case>.csv``,
        ``<case>_fields.csv``, ``.state/<case>/``, ``.state/<case>.lock``).
    quick : bool
        Coarse meshes and few steps.
    force : bool
        Discard earlier results and state of this case.
    runner : callable, optional
        The FE runner (module docstring); :func:`validation.fe.run_fe` by default.
    progress : bool, optional
        Progress bar on stderr; by default only on a terminal.

    Returns
    -------
    CaseResult
        Errors against the analytic curves, breakdown ``D0`` per run, runtime.

    Raises
    ------
    validation.store.LockedError
        Another process is writing this case into ``out`` (a ``ValueError``).
    OSError
        A file or folder below ``out`` cannot be created, read or written.
    """
    t0 = time.perf_counter()
    case = get_case(case) if isinstance(case, str) else case
    runner = run_fe if runner is None else runner
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    state_root = out / ".state"
    state_root.mkdir(exist_ok=True)
    csv_path = out / f"{case.name}.csv"
    fields_path = out / f"{case.name}_fields.csv"
    state_dir = state_root / case.name
    runs = case.runs(quick)
    manifest = _manifest(case, runs)
    man_path = state_dir / "manifest.json"
    notes: list[str] = []

    def note(msg: str) -> None:
        notes.append(msg)
        notice(msg)

    with FolderLock(state_root / f"{case.name}.lock", f"case {case.name!r} in {out}"):
        for p in (csv_path, fields_path, man_path):
            if p.exists() and not p.is_file():
                raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), str(p))
        if not force and man_path.exists():
            try:
                saved = json.loads(man_path.read_text())
            except (ValueError, UnicodeDecodeError) as exc:
                note(f"{man_path} is unreadable ({type(exc).__name__}); case {case.name} is "
                     f"recomputed")
                force = True
            else:
                if saved != manifest:
                    note(f"{man_path}: the saved runs of case {case.name} have other settings "
                         f"(quick/full, meshes or steps); the case is recomputed")
                    force = True
        elif not force and not man_path.exists() and (csv_path.exists()
                                                       or fields_path.exists()):
            note(f"{csv_path} has no saved state ({man_path} is missing); case {case.name} "
                 f"is recomputed")
            force = True                                            # rows without state
        if force:
            for p in (csv_path, fields_path):
                if p.exists():
                    p.unlink()
            if state_dir.is_dir():
                shutil.rmtree(state_dir)
        state_dir.mkdir(exist_ok=True)
        write_text_atomic(man_path, json.dumps(manifest))
        result = _run_locked(case, runs, csv_path, fields_path, state_dir, runner, progress,
                             note)
    result.runtime_s = round(time.perf_counter() - t0, 3)
    result.quick = bool(quick)
    result.repairs = notes
    return result


def _check_rows(st: dict, rows: list, frows: list, files: _CaseFiles) -> str:
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


def _plan(case, runs, files: _CaseFiles, state_dir: Path, note) -> tuple[list, int]:
    """Read the CSVs and states, keep what verifies; ``(plan, resumed steps)``."""
    header, rows, why = _read_csv(files.csv_path)
    if why or (header is not None and header != files.header):
        note(why or f"{files.csv_path} has another header than {files.header}")
        rows = []
    by_run, bad = _rows_by_run(rows, case.name, files.keys, len(files.header))
    f_header, frows, fwhy = _read_csv(files.fields_path)
    if fwhy or (f_header is not None and f_header[:4] != _FIELD_KEYS):
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
        path = _state_path(state_dir, spec)
        st, why = load_state(path, _spec_sig(spec))
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


def _run_locked(case, runs, csv_path, fields_path, state_dir, runner, progress,
                note) -> CaseResult:
    """Body of :func:`run_case` under the case lock: resume plan, ramps, summary."""
    files = _CaseFiles(case, runs, csv_path, fields_path)
    plan, resumed = _plan(case, runs, files, state_dir, note)
    files.rewrite()
    total = sum(len(spec.D0) - start for spec, start, *_ in plan)
    with Progress(total, case.name, enabled=progress) as bar:
        for i, (spec, start, state, rows, frows) in enumerate(plan):
            cpu, count = time.process_time(), bar.count
            try:
                _run_one(case, spec, start, state, runner, files, rows, frows, state_dir, bar)
            except _ResumeFailed as exc:
                note(f"run {spec.key} of case {case.name}: the runner could not continue from "
                     f"the saved state ({exc}); recomputed from the start")
                resumed -= start
                files.drop(spec.key)
                _run_one(case, spec, 0, None, runner, files, RowDigest(), RowDigest(),
                         state_dir, bar)
            bar.line(f"run {i + 1}/{len(plan)} {spec.key}: {bar.count - count} of "
                     f"{len(spec.D0) - start} targets, {time.process_time() - cpu:.1f} s CPU")
    files.rewrite()
    result = summarise_case(case, csv_path, n_runs=len(runs))
    result.resumed_steps = resumed
    return result


class _ResumeFailed(Exception):
    """The runner raised before reporting a step of a resumed ramp."""


def _run_one(case, spec, start, state, runner, files: _CaseFiles, rows: RowDigest,
             frows: RowDigest, state_dir: Path, bar) -> None:
    path = _state_path(state_dir, spec)
    sig = _spec_sig(spec)
    last = {"step": start - 1, "done": False}

    def save(step, st, done, reason=""):
        save_state(path, step=step, state=st, done=done, reason=reason, rows=rows, frows=frows,
                   spec=sig)
        last["done"] = done

    def on_step(index: int, rec: StepRecord, st: dict) -> bool:
        if index != last["step"] + 1:
            raise RuntimeError(f"runner reported step {index} of run {spec.key} after step "
                               f"{last['step']}; steps must come once each, in order")
        brk = _breakdown(spec, rec)
        row = _row(case, spec, index, rec, True, brk, spec.D0[index])
        files.add(spec.key, row)
        rows.add(row)
        if spec.record_fields and rec.fields:
            names = sorted(rec.fields)
            cols = [np.asarray(rec.fields[n], dtype=float).ravel() for n in names]
            frs = [[case.name, spec.key, str(index), _fmt(spec.D0[index])] + [_fmt(v) for v in vals]
                   for vals in zip(*cols)]
            files.add_fields(spec.key, _FIELD_KEYS + names, frs)
            for r in frs:
                frows.add(r)
        stop = brk and spec.stop_at_breakdown
        last_target = index == len(spec.D0) - 1
        save(index, None if (stop or last_target) else st, stop or last_target)
        last["step"] = index
        bar.update(note=f"{spec.key} D0={spec.D0[index]:.3g}")
        return stop

    if start >= len(spec.D0):
        return
    try:
        outcome = runner(spec, start, state, on_step)
    except Exception as exc:
        if start > 0 and last["step"] == start - 1:
            raise _ResumeFailed(f"{type(exc).__name__}: {exc}") from exc
        raise
    if last["done"]:
        return
    # the ramp ended early: record the failed target and the reason
    k = last["step"] + 1
    if not outcome.converged and k < len(spec.D0):
        row = _row(case, spec, k, None, False, spec.geometry == "uniaxial", spec.D0[k])
        files.add(spec.key, row)
        rows.add(row)
        save(last["step"], None, True, outcome.reason or "failed")
    else:
        save(last["step"], None, True)


def summarise_case(case: Case, csv_path: Path, n_runs: int) -> CaseResult:
    """Errors and breakdown points of a case, from its CSV."""
    res = CaseResult(name=case.name, figure=case.figure, csv=csv_path.name, n_runs=n_runs,
                     n_steps=0, max_rel_error=None)
    if not csv_path.exists():
        return res
    t = read_table(csv_path)
    if not t or not len(t["run"]):
        return res
    res.n_steps = len(t["run"])
    conv = np.array([bool(c) for c in t["converged"]])
    err = np.abs(t["lam1_fe"] - t["lam1_analytic"]) / t["lam1_analytic"]
    ok = conv & np.isfinite(err)
    if ok.any():
        res.max_rel_error = float(np.max(err[ok]))
    for key in map(str, dict.fromkeys(t["run"])):
        sel = t["run"] == key
        e = err[sel & ok]
        res.max_rel_error_by_run[key] = float(e.max()) if e.size else None
        brk = np.array([bool(b) for b in t["breakdown"][sel]])
        if brk.any():
            res.breakdown_D0[key] = float(t["D0"][sel][np.argmax(brk)])
        else:
            res.breakdown_D0[key] = None
        if "alpha" in t and np.isfinite(t["alpha"][sel][0]):
            variant = str(t["variant"][sel][0])
            res.breakdown_D0_by_alpha.setdefault(variant, {})[format(t["alpha"][sel][0], "g")] = \
                res.breakdown_D0[key]
        if "physical_eig" in t and np.isfinite(t["physical_eig"][sel]).any():
            res.buckling_D0[key] = buckling_crossing(t["D0"][sel], t["physical_eig"][sel])
            res.buckling_D0_by_alpha.setdefault(str(t["variant"][sel][0]), {})[
                format(t["alpha"][sel][0], "g")] = res.buckling_D0[key]
        fails = ~conv[sel]
        if fails.any():
            res.reasons[key] = f"no convergence at D0 = {t['D0'][sel][np.argmax(fails)]:g}"
    return res


# --------------------------------------------------------------------------- many cases
def run_cases(cases: Iterable[Case | str], out, *, quick: bool = False, force: bool = False,
              jobs: int = 1, executor: Executor | None = None, runner: Callable | None = None,
              progress: bool | None = None) -> list[CaseResult]:
    """Run several cases, in parallel through a :class:`concurrent.futures.Executor`.

    Parameters
    ----------
    cases : iterable of Case or str
        The cases.
    out : path-like
        Output folder.
    quick, force, runner
        As in :func:`run_case`.
    jobs : int
        Number of worker processes when no ``executor`` is given; ``1`` runs
        in this process.
    executor : Executor, optional
        Any executor (a process pool, a thread pool, a ``dask.distributed``
        client's executor); the caller owns and shuts it down.
    progress : bool, optional
        Progress bars (per step in-process, per case with an executor).

    Returns
    -------
    list of CaseResult
        In the order of ``cases``.
    """
    cases = [get_case(c) if isinstance(c, str) else c for c in cases]
    if jobs < 1:
        raise ValueError(f"jobs must be >= 1, got {jobs}")
    if executor is None and jobs == 1:
        return [run_case(c, out, quick=quick, force=force, runner=runner, progress=progress)
                for c in cases]
    own = executor is None
    ex = ProcessPoolExecutor(max_workers=jobs) if own else executor
    try:
        futures = [ex.submit(run_case, c, str(out), quick=quick, force=force, runner=runner,
                             progress=False) for c in cases]
        with Progress(len(futures), "cases", enabled=progress) as bar:
            results = []
            for c, f in zip(cases, futures):
                results.append(f.result())
                bar.update(note=c.name)
                bar.line(f"{c.name}: {results[-1].n_steps} FE steps, "
                         f"{results[-1].runtime_s:.1f} s")
        return results
    finally:
        if own:
            ex.shutdown()


def make_figure(case: Case | str, out) -> list[Path]:
    """Draw the figure of ``case`` from ``out/<case>.csv`` into ``out/<case>.png|pdf``."""
    case = get_case(case) if isinstance(case, str) else case
    out = Path(out)
    csv_path, fields_path = out / f"{case.name}.csv", out / f"{case.name}_fields.csv"
    fe = read_table(csv_path) if csv_path.exists() else None
    fields = read_table(fields_path) if fields_path.exists() else None
    return save_figure(case_figure(case.name, fe=fe, fields=fields), out, case.name)


def validate(cases: Iterable[Case | str] | None, out, *, quick: bool = False,
             force: bool = False, jobs: int = 1, executor: Executor | None = None,
             runner: Callable | None = None, progress: bool | None = None) -> list[CaseResult]:
    """The main job: run the cases, draw their figures, write ``summary.json`` and ``report.md``.

    Parameters
    ----------
    cases : iterable of Case or str, optional
        Default: every registered case.
    out : path-like
        Output folder (created); nothing is written elsewhere.
    quick, force, jobs, executor, runner, progress
        As in :func:`run_cases`.

    Returns
    -------
    list of CaseResult
    """
    cases = list(CASES) + list(EXTRA_CASES) if cases is None else list(cases)
    registered = [c for c in cases if c not in EXTRA_CASES]
    results = run_cases(registered, out, quick=quick, force=force, jobs=jobs,
                        executor=executor, runner=runner, progress=progress)
    for r in results:
        make_figure(r.name, out)
    for name in (c for c in cases if c in EXTRA_CASES):
        cpu = time.process_time()
        results.append(extra_case_result(name, out, quick=quick))
        Progress(1, name, enabled=progress).line(
            f"{results[-1].n_steps} FE points, {time.process_time() - cpu:.1f} s CPU")
    out = Path(out)
    (out / ".state").mkdir(parents=True, exist_ok=True)
    with FolderLock(out / ".state" / "summary.lock", f"the summary of {out}", wait=True):
        every = folder_results(out, results)
        write_summary(every, out, quick=quick)
        write_report(every, out, quick=quick)
    return results


def folder_results(out, results=()) -> list[CaseResult]:
    """The results of every case present in ``out``: ``results`` and, for the other cases
    with a CSV there, the summary computed from that CSV.

    Parameters
    ----------
    out : path-like
        Output folder of earlier :func:`validate` or :func:`run_case` calls.
    results : sequence of CaseResult
        Fresh results (they replace what the folder says about their cases).

    Returns
    -------
    list of CaseResult
        Registered cases in the order of :data:`~validation.cases.CASES`, then any
        other case of ``results``. Runtime and resumed steps of a case not in
        ``results`` come from the ``summary.json`` already in ``out`` (else 0).
    """
    out = Path(out)
    fresh = {r.name: r for r in results}
    try:
        prev = json.loads((out / "summary.json").read_text())["cases"]
        prev = prev if isinstance(prev, dict) else {}
    except (OSError, ValueError, KeyError, TypeError):
        prev = {}
    every = []
    for name, case in CASES.items():
        if name in fresh:
            every.append(fresh[name])
            continue
        csv_path = out / f"{name}.csv"
        if not csv_path.is_file():
            continue
        try:
            saved = json.loads((out / ".state" / name / "manifest.json").read_text())
        except (OSError, ValueError):
            saved = None
        quick = None if saved is None else saved == _manifest(case, case.runs(True))
        n_runs = len(saved["runs"]) if isinstance(saved, dict) and "runs" in saved \
            else len(case.runs(bool(quick)))
        try:
            r = summarise_case(case, csv_path, n_runs=n_runs)
        except (OSError, ValueError, csv.Error, UnicodeDecodeError):
            continue
        old = prev.get(name) if isinstance(prev.get(name), dict) else {}
        r.runtime_s = float(old.get("runtime_s", 0.0) or 0.0)
        r.resumed_steps = int(old.get("resumed_steps", 0) or 0)
        r.quick = old.get("quick") if isinstance(old.get("quick"), bool) else quick
        every.append(r)
    every += [r for r in results if r.name not in CASES]
    for name in EXTRA_CASES:
        old = prev.get(name)
        if name not in fresh and isinstance(old, dict) and (out / f"{name}.csv").is_file():
            try:
                every.append(CaseResult(**{k: old[k] for k in CaseResult.__dataclass_fields__
                                           if k in old}))
            except TypeError:
                pass
    return every


def extra_case_result(name: str, out, *, quick: bool = False) -> CaseResult:
    """Run the case ``name`` of :data:`~validation.extra_cases.EXTRA_CASES` (not a charge
    ramp: the continuation through the snap-through, the FE wrinkling against Stroh) into
    ``out`` and summarise it with its own error measure.  The case is locked like a
    registered one (``out/.state/<name>.lock``): a second process writing it is refused."""
    case = EXTRA_CASES[name]
    state_root = Path(out) / ".state"
    state_root.mkdir(parents=True, exist_ok=True)
    with FolderLock(state_root / f"{name}.lock", f"case {name!r} in {out}"):
        paths, summ = case.run(out, quick=quick)
    return CaseResult(name, case.figure, str(paths[0]), summ["n_runs"], summ["n_points"],
                      summ["max_rel_error"], max_rel_error_by_run=summ["max_rel_error_by_run"],
                      reasons=summ["reasons"], runtime_s=summ["runtime_s"], quick=quick)

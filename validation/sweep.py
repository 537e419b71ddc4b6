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
from .progress import Progress
from .records import StepRecord
from .report import write_report, write_summary

try:
    import fcntl
except ImportError:                   # pragma: no cover - Windows
    fcntl = None

__all__ = [
    "CaseResult",
    "BREAKDOWN_TOL",
    "csv_columns",
    "run_case",
    "run_cases",
    "read_table",
    "validate",
    "make_figure",
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
    reasons: dict = field(default_factory=dict)
    runtime_s: float = 0.0
    resumed_steps: int = 0


def csv_columns(case: Case) -> list[str]:
    """Columns of ``DIR/<case>.csv``.

    The run (``case``, ``run``, ``step``, ``model``, ``variant``, ``alpha`` for the
    uni-axial cases, ``s``), the load ``D0``, FE and analytic stretches at the plate
    centre, the ``P33/mu`` minima, the verdicts ``converged``, ``stable``,
    ``breakdown`` and the Newton ``iterations``.

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
             "min_P33_interior", "min_P33_clamp", "converged", "stable", "breakdown",
             "iterations"]
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
            "breakdown": breakdown, "iterations": rec.iterations if rec else None}
    return [_fmt(vals[c]) for c in csv_columns(case)]


#: Verdict columns: always bool/None, also when every cell is empty (e.g. ``stable``
#: without PARDISO), so that a table's column types do not depend on its content.
_BOOL_COLUMNS = frozenset({"converged", "stable", "breakdown"})


def read_table(path) -> dict[str, np.ndarray]:
    """Read a tidy CSV written by the harness into columns.

    Numeric columns become float arrays (empty cells ``nan``), ``True``/``False``
    columns (and always ``converged``, ``stable``, ``breakdown``) become object arrays of
    bool/None, the others string arrays.
    """
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    if not rows:
        return {}
    header, body = rows[0], rows[1:]
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


# --------------------------------------------------------------------------- state files
def _state_path(state_dir: Path, spec: RunSpec) -> Path:
    return state_dir / f"{spec.key}.npz"


def _save_state(path: Path, step: int, state: dict | None, done: bool, reason: str = "") -> None:
    arrays = {f"x_{k}": np.asarray(v) for k, v in (state or {}).items()}
    tmp = path.with_suffix(".tmp.npz")
    with open(tmp, "wb") as fh:
        np.savez(fh, __step__=step, __done__=done, __reason__=reason, **arrays)
    os.replace(tmp, path)


def _load_state(path: Path) -> dict | None:
    if not path.exists():
        return None
    try:
        with np.load(path, allow_pickle=False) as z:
            return {"step": int(z["__step__"]), "done": bool(z["__done__"]),
                    "reason": str(z["__reason__"]),
                    "state": {k[2:]: z[k] for k in z.files if k.startswith("x_")}}
    except (OSError, ValueError, KeyError):
        return None


def _manifest(case: Case, runs: tuple) -> dict:
    return {"case": case.name, "runs": [[r.key, list(r.D0), [list(m) for m in r.mesh],
                                         r.record_fields, r.record_maps, r.stop_at_breakdown]
                                        for r in runs]}


def _read_rows(path: Path) -> tuple[list[str] | None, list[list[str]]]:
    if not path.exists():
        return None, []
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    return (rows[0], rows[1:]) if rows else (None, [])


def _write_rows(path: Path, header: list[str] | None, rows: list[list[str]]) -> None:
    if header is None:
        if path.exists():
            path.unlink()
        return
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)


def _append(path: Path, header: list[str], rows: Iterable[list[str]]) -> None:
    new = not path.exists()
    with open(path, "a", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        if new:
            w.writerow(header)
        w.writerows(rows)
        fh.flush()


# --------------------------------------------------------------------------- one case
def run_case(case: Case | str, out, *, quick: bool = False, force: bool = False,
             runner: Callable | None = None, progress: bool | None = None) -> CaseResult:
    """Run (or resume) every FE ramp of ``case``, writing its CSV step by step.

    Parameters
    ----------
    case : Case or str
        The case or its name.
    out : path-like
        Output folder; everything is written below it (``<case>.csv``,
        ``<case>_fields.csv``, ``.state/<case>/``).
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
    """
    t0 = time.perf_counter()
    case = get_case(case) if isinstance(case, str) else case
    runner = run_fe if runner is None else runner
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    csv_path = out / f"{case.name}.csv"
    fields_path = out / f"{case.name}_fields.csv"
    state_dir = out / ".state" / case.name
    runs = case.runs(quick)
    manifest = _manifest(case, runs)
    man_path = state_dir / "manifest.json"
    if not force and man_path.exists():
        force = json.loads(man_path.read_text()) != manifest   # other settings: start afresh
    elif not force and not man_path.exists() and csv_path.exists():
        force = True                                            # rows without state
    if force:
        for p in (csv_path, fields_path):
            if p.exists():
                p.unlink()
        shutil.rmtree(state_dir, ignore_errors=True)
    state_dir.mkdir(parents=True, exist_ok=True)
    with _case_lock(state_dir, case.name):
        man_path.write_text(json.dumps(manifest))
        return _run_locked(case, runs, out, csv_path, fields_path, state_dir, runner, progress,
                           t0)


class _case_lock:
    """Exclusive lock on ``.state/<case>/lock`` while a process writes the case.

    Two processes writing the same case into the same folder would interleave
    rows; ``flock`` is released by the OS when a process dies, so a killed run
    never blocks its own resume. (No-op where ``fcntl`` is unavailable.)
    """

    def __init__(self, state_dir: Path, name: str):
        self.path, self.name, self.fh = state_dir / "lock", name, None

    def __enter__(self):
        if fcntl is None:             # pragma: no cover - Windows
            return self
        self.fh = open(self.path, "w")
        try:
            fcntl.flock(self.fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            self.fh.close()
            raise ValueError(f"case {self.name!r} is being written by another process into "
                             f"{self.path.parent.parent.parent}") from None
        return self

    def __exit__(self, *exc):
        if self.fh is not None:
            self.fh.close()          # releases the lock


def _run_locked(case, runs, out, csv_path, fields_path, state_dir, runner, progress,
                t0) -> CaseResult:
    """Body of :func:`run_case` under the case lock: resume plan, ramps, summary."""
    header = csv_columns(case)
    _, old_rows = _read_rows(csv_path)
    f_header, old_frows = _read_rows(fields_path)

    # Which runs are complete, where does the first incomplete one resume?
    plan, keep, resumed = [], set(), 0
    broken = False
    for spec in runs:
        path = _state_path(state_dir, spec)
        st = None if broken else _load_state(path)
        if st is None:
            broken = True
            if path.exists():
                path.unlink()
            plan.append((spec, 0, None))
            continue
        keep |= {(spec.key, str(i)) for i in range(st["step"] + 1)}
        resumed += st["step"] + 1
        if st["done"]:
            if st["reason"]:
                keep.add((spec.key, str(st["step"] + 1)))   # the failed-step row
            continue
        broken = True
        plan.append((spec, st["step"] + 1, st["state"]))
    rows = [r for r in old_rows if (r[1], r[2]) in keep]
    frows = [r for r in old_frows if (r[1], r[2]) in keep]
    _write_rows(csv_path, header if rows else None, rows)
    _write_rows(fields_path, f_header if frows else None, frows)

    total = sum(len(spec.D0) - start for spec, start, _ in plan)
    with Progress(total, case.name, enabled=progress) as bar:
        for spec, start, state in plan:
            _run_one(case, spec, start, state, runner, csv_path, fields_path, state_dir, bar)

    if not csv_path.exists():
        _write_rows(csv_path, header, [])        # a case without FE runs: header only
    result = summarise_case(case, csv_path, n_runs=len(runs))
    result.runtime_s = round(time.perf_counter() - t0, 3)
    result.resumed_steps = resumed
    return result


def _run_one(case, spec, start, state, runner, csv_path, fields_path, state_dir, bar) -> None:
    path = _state_path(state_dir, spec)
    header = csv_columns(case)
    last = {"step": start - 1}

    def on_step(index: int, rec: StepRecord, st: dict) -> bool:
        if index != last["step"] + 1:
            raise RuntimeError(f"runner reported step {index} of run {spec.key} after step "
                               f"{last['step']}; steps must come once each, in order")
        brk = _breakdown(spec, rec)
        _append(csv_path, header, [_row(case, spec, index, rec, True, brk, spec.D0[index])])
        if spec.record_fields and rec.fields:
            names = sorted(rec.fields)
            cols = [np.asarray(rec.fields[n], dtype=float).ravel() for n in names]
            frs = [[case.name, spec.key, str(index), _fmt(spec.D0[index])] + [_fmt(v) for v in vals]
                   for vals in zip(*cols)]
            _append(fields_path, ["case", "run", "step", "D0"] + names, frs)
        stop = brk and spec.stop_at_breakdown
        last_target = index == len(spec.D0) - 1
        _save_state(path, index, None if (stop or last_target) else st, done=stop or last_target,
                    reason="")
        last["step"] = index
        bar.update(note=f"{spec.key} D0={spec.D0[index]:.3g}")
        return stop

    if start >= len(spec.D0):
        return
    outcome = runner(spec, start, state, on_step)
    st = _load_state(path)
    if st is not None and st["done"]:
        return
    # the ramp ended early: record the failed target and the reason
    k = last["step"] + 1
    if not outcome.converged and k < len(spec.D0):
        _append(csv_path, header, [_row(case, spec, k, None, False, spec.geometry == "uniaxial",
                                        spec.D0[k])])
        _save_state(path, last["step"], None, done=True, reason=outcome.reason or "failed")
    else:
        _save_state(path, last["step"], None, done=True, reason="")


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
    cases = list(CASES) if cases is None else list(cases)
    results = run_cases(cases, out, quick=quick, force=force, jobs=jobs, executor=executor,
                        runner=runner, progress=progress)
    for r in results:
        make_figure(r.name, out)
    write_summary(results, out, quick=quick)
    write_report(results, out, quick=quick)
    return results

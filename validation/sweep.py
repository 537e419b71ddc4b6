"""Run the FE ramps of a case, write its tidy CSV step by step, resume after interruption.

Data flow: for every :class:`~validation.specs.RunSpec` of a case (its dead load set by
:func:`validation.fe.model.with_dead_load`) a
*runner* (by default :func:`validation.fe.run_fe`, the real FE solver) ramps
``D0`` through the targets and calls back after each converged target. The
callback appends one CSV row to ``DIR/<case>.csv`` (and field rows to
``DIR/<case>_fields.csv``), then saves the FE state to
``DIR/.state/<case>/<run>.npz``. A rerun with the same ``DIR`` keeps the rows
up to the last saved state and resumes the ramp from it, so an interrupted
sweep produces the same files as an uninterrupted one; ``force=True`` starts
afresh.  The rows are those of :mod:`validation.table`, the files, their checksums and
the resume plan those of :mod:`validation.store`.

The runner protocol (any callable, picklable for process pools)::

    runner(spec, start, state, on_step) -> RunOutcome

runs the targets ``spec.D0[start:]`` from ``state`` (``None`` when
``start == 0``) and calls ``on_step(index, record, state)`` after every
converged target with a :class:`StepRecord` and a ``dict`` of arrays that
lets it continue from there; ``on_step`` returns ``True`` to end the ramp
(breakdown reached).
"""

from __future__ import annotations

import errno
import json
import os
import signal
import shutil
import sys
import threading
import time
from concurrent.futures import Executor, ProcessPoolExecutor
from pathlib import Path
from typing import Callable, Iterable

import numpy as np

from .cases import CASES, Case, get_case
from .fe import run_fe, with_dead_load
from .figures import case_figure, plate_mesh_text, run_caption, save_figure
from .figures.common import mesh_text
from .figures.breakdown_map import breakdown_map_figure
from .progress import Progress, notice
from .records import StepRecord
from .report import CASE_FIGURES, write_report, write_summary
from .results import CaseResult, folder_results, summarise_case
from .store import (CaseFiles, FolderLock, RowDigest, case_manifest,
                    resume_plan, save_state, spec_sig, state_path, write_text_atomic)
from .table import FIELD_KEYS, case_row, format_cell, is_breakdown, read_table
from .studies.extra_cases import EXTRA_CASES

__all__ = ["run_case", "run_cases", "validate", "make_figure", "make_breakdown_map",
           "extra_case_result", "remove_openmp_registration"]


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
    runs = tuple(with_dead_load(r) for r in case.runs(quick))
    manifest = case_manifest(case, runs)
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
            _drop_summary(out)                  # it described the rows discarded here
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



#: the files of a folder that summarise every case in it (:func:`validate`)
SUMMARY_FILES = ("summary.json", "report.md")


def _drop_summary(out: Path) -> None:
    """Remove ``summary.json`` and ``report.md`` of ``out`` (under the summary's lock) when
    results are discarded: an interrupted recomputation leaves no summary of rows that no
    longer exist; the next :func:`validate` writes them anew."""
    if not any((out / name).exists() for name in SUMMARY_FILES):
        return
    with FolderLock(out / ".state" / "summary.lock", f"the summary of {out}", wait=True):
        for name in SUMMARY_FILES:
            if (out / name).is_file():
                (out / name).unlink()


def _run_locked(case, runs, csv_path, fields_path, state_dir, runner, progress,
                note) -> CaseResult:
    """Body of :func:`run_case` under the case lock: resume plan, ramps, summary."""
    files = CaseFiles(case, runs, csv_path, fields_path)
    plan, resumed = resume_plan(case, runs, files, state_dir, note)
    files.rewrite()
    if resumed and progress is not False:
        notice(_resumed_line(case.name, len(runs), [start for _, start, *_ in plan], resumed))
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


def _resumed_line(name: str, n_runs: int, starts: list[int], rows: int) -> str:
    """What a resumed case kept: its converged steps (one CSV row each) and runs (``starts``:
    the first target of each run still to compute, 0 for a run computed from the start).

    Examples
    --------
    >>> _resumed_line("zs22", 4, [1, 0], 14)
    'case zs22: resumed with 14 steps kept; runs: 2 of 4 complete, 1 continued from its last saved step, 1 from the start'
    """
    continued = sum(1 for s in starts if s > 0)
    return (f"case {name}: resumed with {rows} steps kept; runs: {n_runs - len(starts)} of "
            f"{n_runs} complete, {continued} continued from its last saved step, "
            f"{len(starts) - continued} from the start")


class _ResumeFailed(Exception):
    """The runner raised before reporting a step of a resumed ramp."""


def _run_one(case, spec, start, state, runner, files: CaseFiles, rows: RowDigest,
             frows: RowDigest, state_dir: Path, bar) -> None:
    path = state_path(state_dir, spec)
    sig = spec_sig(spec)
    last = {"step": start - 1, "done": False}

    def save(step, st, done, reason=""):
        save_state(path, step=step, state=st, done=done, reason=reason, rows=rows, frows=frows,
                   spec=sig)
        last["done"] = done

    def on_step(index: int, rec: StepRecord, st: dict) -> bool:
        if index != last["step"] + 1:
            raise RuntimeError(f"runner reported step {index} of run {spec.key} after step "
                               f"{last['step']}; steps must come once each, in order")
        brk = is_breakdown(spec, rec)
        row = case_row(case, spec, index, rec, True, brk, spec.D0[index])
        files.add(spec.key, row)
        rows.add(row)
        if spec.record_fields and rec.fields:
            names = sorted(rec.fields)
            cols = [np.asarray(rec.fields[n], dtype=float).ravel() for n in names]
            frs = [[case.name, spec.key, str(index), format_cell(spec.D0[index])] + [format_cell(v) for v in vals]
                   for vals in zip(*cols)]
            files.add_fields(spec.key, FIELD_KEYS + names, frs)
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
        row = case_row(case, spec, k, None, False, spec.geometry == "uniaxial", spec.D0[k])
        files.add(spec.key, row)
        rows.add(row)
        save(last["step"], None, True, outcome.reason or "failed")
    else:
        save(last["step"], None, True)



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
    ex = ProcessPoolExecutor(max_workers=jobs, initializer=_init_worker) if own else executor
    task = _run_case_in_worker if own else run_case
    try:
        futures = [ex.submit(task, c, str(out), quick=quick, force=force, runner=runner,
                             progress=False) for c in cases]
        with Progress(len(futures), "cases", enabled=progress) as bar:
            results = []
            for c, f in zip(cases, futures):
                results.append(f.result())
                bar.update(note=c.name)
                bar.line(f"{c.name}: {results[-1].n_steps} FE steps, "
                         f"{results[-1].runtime_s:.1f} s")
        return results
    except KeyboardInterrupt:               # Ctrl-C, or SIGTERM as the CLI raises it
        if own:
            _stop_workers(ex)
        raise
    finally:
        if own:
            ex.shutdown()


# --------------------------------------------------------------------------- workers
#: seconds a stopped worker has to unwind its case before it is killed
WORKER_GRACE_S = 60.0
#: whether this worker process is running a case (signals raise) or idle (signals exit)
_in_case = False


class _WorkerStopped(KeyboardInterrupt):
    """SIGTERM or SIGINT in a worker of :func:`run_cases`, raised in its main thread so that
    its case unwinds like Ctrl-C: lock released, temporary files removed."""


def _on_worker_signal(signum, frame):
    if _in_case:
        raise _WorkerStopped(signum)
    _exit_worker(signum)                # idle: nothing to release


def _init_worker() -> None:
    """Initializer of the worker processes: SIGTERM and SIGINT stop the case and the
    worker quietly (no traceback; the parent prints the one line)."""
    signal.signal(signal.SIGTERM, _on_worker_signal)
    signal.signal(signal.SIGINT, _on_worker_signal)


def _exit_worker(signum: int) -> None:
    """End this worker by ``signum`` with its default action (what the signal would have
    done without the handler), once its case has unwound."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    remove_openmp_registration()
    signal.signal(signum, signal.SIG_DFL)
    os.kill(os.getpid(), signum)


def _run_case_in_worker(*args, **kwargs) -> CaseResult:
    """:func:`run_case` in a worker process; a stopped case ends the worker (it takes no
    further case), after the case has unwound."""
    global _in_case
    try:
        _in_case = True
        return run_case(*args, **kwargs)
    except _WorkerStopped as exc:
        _in_case = False
        _exit_worker(exc.args[0])
    finally:
        _in_case = False


def _stop_workers(ex: ProcessPoolExecutor, grace: float = WORKER_GRACE_S) -> None:
    """Cancel the cases not started and stop every worker of ``ex`` (SIGTERM: each unwinds
    its case, then exits); wait for them, killing one that takes longer than ``grace``
    seconds.  A further SIGTERM or SIGINT meanwhile kills them at once (the clean-up
    itself goes on to its end)."""
    procs = list((getattr(ex, "_processes", None) or {}).values())
    signals = (signal.SIGTERM, signal.SIGINT)
    main = threading.current_thread() is threading.main_thread()
    before = [signal.getsignal(s) for s in signals] if main else []

    def kill_now(signum, frame):
        for p in procs:
            if p.is_alive():
                p.kill()

    for s in signals if main else ():
        signal.signal(s, kill_now)
    try:
        ex.shutdown(wait=False, cancel_futures=True)
        for p in procs:
            try:
                os.kill(p.pid, signal.SIGTERM)
            except ProcessLookupError:                  # gone already
                pass
        deadline = time.monotonic() + grace
        for p in procs:
            p.join(max(0.0, deadline - time.monotonic()))
            if p.is_alive():
                p.kill()
                p.join()
    finally:
        for s, handler in zip(signals, before):
            if handler is not None:
                signal.signal(s, handler)


def remove_openmp_registration(pid: int | None = None) -> None:
    """Remove Intel OpenMP's ``/dev/shm/__KMP_REGISTERED_LIB_<pid>_0`` of the process
    ``pid`` (default: this one; loaded with PARDISO for the inertia), which a process
    stopped by a signal leaves (Linux only: elsewhere there is no such file)."""
    if not sys.platform.startswith("linux"):
        return
    path = Path(f"/dev/shm/__KMP_REGISTERED_LIB_{pid or os.getpid()}_0")
    try:
        path.unlink()
    except OSError:
        pass


def make_figure(case: Case | str, out) -> list[Path]:
    """Draw the figure of ``case`` from ``out/<case>.csv`` into ``out/<case>.png|pdf``."""
    case = get_case(case) if isinstance(case, str) else case
    out = Path(out)
    csv_path, fields_path = out / f"{case.name}.csv", out / f"{case.name}_fields.csv"
    fe = read_table(csv_path) if csv_path.exists() else None
    fields = read_table(fields_path) if fields_path.exists() else None
    return save_figure(case_figure(case.name, fe=fe, fields=fields), out, case.name)


def make_breakdown_map(result: CaseResult, out, *, quick: bool = False) -> list[Path]:
    """Draw the breakdown map (docs/breakdown.md) into ``out/breakdown-map.png|pdf``.

    The run's ``P33`` breakdowns and buckling loads per weight come from ``result`` (the
    uni-axial-ideal case's summary), its Newton failures from its CSV, the converged
    buckling loads from :mod:`validation.data.loads`.  The map is drawn without the
    mode panels (docs/breakdown.md says how to draw them).
    """
    out = Path(out)
    t = read_table(out / result.csv)
    newton = {}
    for key in map(str, dict.fromkeys(t["run"]) if t else ()):
        sel = (t["run"] == key) & (t["variant"] == "coupled")
        fails = np.flatnonzero(~np.array([bool(c) for c in t["converged"][sel]], dtype=bool))
        if fails.size:
            newton[float(t["alpha"][sel][0])] = float(t["D0"][sel][fails[0]])
    buckled = {float(a): d for a, d in result.buckling_D0_by_alpha.get("coupled", {}).items()}
    specs = get_case(result.name).runs(quick)
    coupled = [r for r in specs if r.variant == "coupled"]
    mesh = (plate_mesh_text("coupled", coupled[0].mesh_dict).split(" elements")[0]
            if coupled else "")
    caption = run_caption("Breakdown map (paper Sec. 6 and Fig. 5)", quick,
                          mesh_text(specs))
    fig = breakdown_map_figure(p33={v: {float(a): d for a, d in per.items()}
                                    for v, per in result.breakdown_D0_by_alpha.items()},
                               run_buckling=buckled, run_newton=newton, run_mesh=mesh,
                               caption=caption)
    return save_figure(fig, out, "breakdown-map")


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
    for r in results:                   # the figures report.md links (CASE_FIGURES)
        if "breakdown-map" in dict(CASE_FIGURES.get(r.name, ())):
            make_breakdown_map(r, out, quick=quick)
    for name in (c for c in cases if c in EXTRA_CASES):
        cpu = time.process_time()
        results.append(extra_case_result(name, out, quick=quick, force=force))
        Progress(1, name, enabled=progress).line(
            f"{results[-1].n_steps} FE points, {time.process_time() - cpu:.1f} s CPU")
    out = Path(out)
    (out / ".state").mkdir(parents=True, exist_ok=True)
    with FolderLock(out / ".state" / "summary.lock", f"the summary of {out}", wait=True):
        every = folder_results(out, results)
        write_summary(every, out, quick=quick)
        write_report(every, out, quick=quick)
    return results


def extra_case_result(name: str, out, *, quick: bool = False,
                      force: bool = False) -> CaseResult:
    """Run (or resume) the case ``name`` of :data:`~validation.studies.extra_cases.EXTRA_CASES`
    (not a charge ramp: the continuation through the snap-through, the FE wrinkling
    against Stroh) into ``out`` and summarise it with its own error measure.  The case is
    locked like a registered one (``out/.state/<name>.lock``, held by its
    :class:`~validation.store.StudyStore`): a second process writing it is refused;
    ``force`` discards its earlier results."""
    case = EXTRA_CASES[name]
    paths, summ = case.run(out, quick=quick, force=force)
    # the CSV as every case names it: relative to the folder of summary.json
    csv_name = os.path.relpath(paths[0], out)
    return CaseResult(name, case.figure, csv_name, summ["n_runs"], summ["n_points"],
                      summ["max_rel_error"], max_rel_error_by_run=summ["max_rel_error_by_run"],
                      reasons=summ["reasons"], runtime_s=summ["runtime_s"], quick=quick,
                      resumed_steps=summ.get("resumed", 0),
                      repairs=list(summ.get("repairs", [])))

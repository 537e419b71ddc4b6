"""The ``skfem-dielectric`` command line: ``list | curves | simulate | validate | check |
bench | explore | wrinkling-fe | buckling | post-buckling | clamp-zone``.

Every subcommand has ``--help``. Only this module prints, and it writes files
only into the folder given by ``--out``.
"""

from __future__ import annotations

import argparse
import atexit
import csv
import functools
import logging
import os
import signal
import sys
import threading
import time
from concurrent.futures import CancelledError
import webbrowser
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from skfem_dielectric.fem import blas_thread_limit

from .cases import CASES
from .check_report import write_check_report
from .checker import CHECK_CASES, TOLERANCES, check
from .clamp_zone.cli import add_clamp_zone_command, cmd_clamp_zone
from .cluster import dask_executor as _dask_executor
from .fe import bench, run_fe, simulate
from .figures import case_figure, save_figure
from .specs import MODELS, VARIANTS
from .report import verdict_lines
from .store import write_text_atomic
from .sweep import remove_openmp_registration, validate
from .studies.commands import STUDY_COMMANDS, add_study_commands
from .studies.extra_cases import EXTRA_CASES
from .options import check_mesh, load_targets, out_dir, positive, solver_name
from .explore import INSTALL_HINT, export_html, load_results, make_server, require_bokeh

__all__ = ["main", "build_parser", "EXIT_CODES"]


def _version() -> str:
    try:
        return version("skfem-dielectric")
    except PackageNotFoundError:      # pragma: no cover - running from a source tree
        return "unknown"


#: Exit codes of :func:`main` (docs/cli.md).
EXIT_CODES = {
    0: "success",
    1: "validate: a case with FE runs produced no FE step; check: a case fails its "
       "tolerance",
    2: "bad input: an invalid option or value (the message names it), an option that does "
       "not apply to the chosen geometry, a missing optional dependency, or another "
       "process writing the same case into the same --out (the message names it)",
    3: "file system: a path below --out cannot be created, read or written (--out is a "
       "file or below a file, no permission, disk full, .state is a file, a CSV is a "
       "folder); the message names the path",
    130: "interrupted by Ctrl-C, SIGINT (rerun the same command to resume)",
    143: "terminated by SIGTERM (timeout, a scheduler, docker stop; rerun the same command "
         "to resume)",
}

SIM_HELP = ("Run one FE ramp (pre-load, then D0 = 0 -> --D0-max in --steps steps) and export "
            "the fields for ParaView plus a CSV of the steps. The exported mesh is the "
            "symmetric model in millimetres: in 3D one eighth of the plate (x1 >= 0, x2 >= 0, "
            "x3 >= 0; the Keplinger plate 100 x 1 x 50 mm gives 50 x 0.5 x 25 mm, the "
            "homogeneous equi-biaxial plate 4 x 1 x 4 gives 2 x 0.5 x 2), for the 2D "
            "membrane one quarter of the 100 x 50 mm mid-plane (x2 = 0). Fields are "
            "dimensionless (stresses over mu, D0 = D/sqrt(mu eps)). With --format vtu a "
            "<run>.pvd index lists the steps with D0 as the time value.")


class _Formatter(argparse.ArgumentDefaultsHelpFormatter):
    """Shows each option's default, except for options without one (``None``)."""

    def _get_help_string(self, action):
        if action.default is None or action.default is False:
            return action.help
        return super()._get_help_string(action)


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line on stderr (exit code 2)."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {' '.join(message.split())} "
                     f"(see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (exposed for the docs and the tests).

    Returns
    -------
    argparse.ArgumentParser
        Every subcommand shows its defaults in ``--help``; a parse error is one line
        on stderr and exit code 2.
    """
    p = _Parser(
        prog="skfem-dielectric", formatter_class=_Formatter,
        description="Charge-controlled soft dielectric plates: the paper's figures with "
                    "finite-element dots, closed-form curves and FE simulations.",
        epilog="exit codes: " + "; ".join(f"{k} {v}" for k, v in EXIT_CODES.items()))
    p.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", required=True,
                           parser_class=_Parser)

    def add(name, help, description):
        return sub.add_parser(name, help=help, description=description,
                              formatter_class=_Formatter)

    add("list", "list the validation cases (one per paper figure)",
        "List the validation cases, their paper figure and FE runs.")

    c = add("curves", "draw the analytic curves only (no FE)",
            "Draw the closed-form curves of the paper's figures, without FE dots, as PNG "
            "and PDF into --out.")
    c.add_argument("--case", nargs="+", choices=list(CASES), metavar="NAME",
                   help="cases to draw (default: those that need no FE fields)")
    c.add_argument("--out", required=True, type=out_dir, help="output folder")

    add_study_commands(add)
    add_clamp_zone_command(add)

    v = add("validate", "run FE sweeps, overlay them on the theory (main job)",
            "Run the FE ramps of the cases, write DIR/<case>.csv step by step, the figures "
            "(PNG, PDF), summary.json and report.md (covering every case in DIR). An "
            "interrupted run resumes when rerun with the same --out; a case is locked while "
            "a process writes it.")
    v.add_argument("--quick", action="store_true", help="coarse meshes and few D0 steps")
    v.add_argument("--case", nargs="+", choices=list(CASES) + list(EXTRA_CASES),
                   metavar="NAME",
                   help=f"cases to run (default: all of {', '.join(CASES)}, "
                        f"{', '.join(EXTRA_CASES)})")
    v.add_argument("--out", required=True, type=out_dir, help="output folder")
    v.add_argument("--jobs", type=int, default=1,
                   help="worker processes (a process pool, or the workers of "
                        "--scheduler local)")
    v.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run the cases on a dask.distributed cluster: the scheduler's "
                        "ADDRESS (e.g. tcp://10.0.0.1:8786) or 'local' for a LocalCluster "
                        "of --jobs worker processes; needs the 'cluster' extra "
                        "(pip install -e '.[cluster]')")
    v.add_argument("--force", action="store_true", help="recompute instead of resuming")
    v.add_argument("--solver", choices=["auto", "superlu", "pardiso"], default="auto",
                   help="linear solver of the FE ramps: auto (PARDISO if the 'fast' extra "
                        "is installed, else SuperLU), superlu (deterministic: a resumed run "
                        "repeats the uninterrupted one bit for bit) or pardiso (faster on "
                        "fine meshes, needs the 'fast' extra; multi-threaded, so the last "
                        "digits may differ between runs)")
    v.add_argument("--no-progress", action="store_true", help="no progress bars")

    k = add("check", "score another code's results CSVs against the closed forms",
            "Read the results CSVs of PATH (a folder, or one CSV) written in the results "
            "contract of validate (docs/check.md: per case the columns case, D0 or E0, s or "
            "alpha and the checked quantity, e.g. lam1), score each case against the closed "
            "forms (loading curves, Hessian verdicts, voltage limit points, the Stroh "
            "critical D0, the converged buckling load D0_b) and print a verdict per case; "
            "exit code 1 if a case fails. With --out, also <case>.png (their dots on our "
            "curves), check.md and check.json, written only after every file was read.")
    k.add_argument("path", metavar="PATH", help="folder of <case>.csv files, or one CSV")
    k.add_argument("--case", nargs="+", choices=list(CHECK_CASES), metavar="NAME",
                   help=f"cases to check (default: every case found; {', '.join(CHECK_CASES)})")
    k.add_argument("--tol", nargs="+", metavar="NAME=VALUE", default=None,
                   help="replace a tolerance (measures and defaults: "
                        + ", ".join(f"{n}={v:g}" for n, v in TOLERANCES.items()) + ")")
    k.add_argument("--out", type=out_dir, default=None,
                   help="report folder (not PATH): <case>.png, check.md, check.json")

    s = add("simulate", "run one FE ramp and export VTU/XDMF", SIM_HELP)
    s.add_argument("--geometry", choices=["equibiaxial", "uniaxial"], default="uniaxial",
                   help="homogeneous equi-biaxial plate or clamped Keplinger plate")
    s.add_argument("--model", choices=list(MODELS), default="neo-Hookean",
                   help="strain energy (Gent with Jm = 97.2)")
    s.add_argument("--variant", choices=list(VARIANTS), default="coupled",
                   help="3D fully coupled, 3D Maxwell traction, 2D membrane, or 2D membrane "
                        "with the local-field Maxwell traction")
    s.add_argument("--s", type=float, default=None,
                   help="dimensionless dead load, --geometry equibiaxial only (default 1)")
    s.add_argument("--alpha", type=float, default=None,
                   help="weight fraction of the Keplinger plate, --geometry uniaxial only "
                        "(default 1)")
    s.add_argument("--D0-max", dest="D0_max", type=float, default=4.0,
                   help="final charge target D0")
    s.add_argument("--steps", type=int, default=8, help="number of charge steps")
    s.add_argument("--mesh", type=int, nargs=3, metavar=("N1", "N2", "N3"), default=None,
                   help="elements of the symmetric model along length, thickness, width "
                        "(default 20 1 10; the membrane uses N1 and N3)")
    s.add_argument("--format", dest="fmt", choices=["vtu", "xdmf"], default="vtu",
                   help="one .vtu per step with a .pvd index, or one XDMF time series")
    s.add_argument("--out", required=True, type=out_dir, help="output folder")

    e = add("explore", "the paper's theory live in a browser (needs the 'explore' extra)",
            "Serve a page on 127.0.0.1 whose panels follow the model, Jm, control, s, alpha "
            "and lam widgets: equi-biaxial D0-lam and E0-lam with the det H* = 0 locus and "
            "the E0 maximum, the Keplinger plate's uni-axial curve with the wrinkling limits, "
            "the dispersion D0_c(kh) (docs/explore.md). " + INSTALL_HINT + ".")
    e.add_argument("--results", default=None, metavar="DIR",
                   help="a `validate` output folder: FE dots and P33/buckling markers on top")
    e.add_argument("--port", type=int, default=5006, help="TCP port on 127.0.0.1")
    e.add_argument("--no-browser", action="store_true", help="do not open a browser")
    e.add_argument("--export", default=None, metavar="FILE.html",
                   help="write the panels at the paper's parameters as one HTML file "
                        "(BokehJS inline) and exit, instead of serving")

    b = add("bench", "time one Keplinger ramp (DOFs, iterations, seconds)",
            "Time the Keplinger plate ramp on a given mesh and solver; prints the linear "
            "solver that was used (also what 'auto' chose).")
    b.add_argument("--mesh", type=int, nargs=3, metavar=("N1", "N2", "N3"), default=[20, 1, 10],
                   help="elements of the eighth model along length, thickness, width")
    b.add_argument("--alpha", type=float, default=1.0, help="weight fraction of the plate")
    b.add_argument("--D0-max", dest="D0_max", type=float, default=6.0,
                   help="final charge target D0")
    b.add_argument("--steps", type=int, default=6, help="number of charge steps")
    b.add_argument("--variant", choices=list(VARIANTS), default="coupled", help="FE variant")
    b.add_argument("--solver", choices=["auto", "superlu", "pardiso"], default="auto",
                   help="linear solver: superlu, pardiso or auto (PARDISO if pypardiso is "
                        "installed, else SuperLU)")
    return p


def _cmd_list(args) -> int:
    rows = [(c.name, c.figure, f"{len(c.quick)}/{len(c.full)}", c.title)
            for c in CASES.values()]
    rows += [(c.name, c.figure, f"{c.count(True)}/{c.count(False)}", c.title)
             for c in EXTRA_CASES.values()]
    head = ("case", "paper figure", "runs quick/full", "description")
    # every column as wide as its longest entry: nothing is cut, the columns stay aligned
    w = [max(len(r[i]) for r in rows + [head]) for i in range(3)]
    for r in [head] + rows:
        print("  ".join(f"{v:<{n}}" for v, n in zip(r, w)) + "  " + r[3])
    return 0


def _cmd_curves(args) -> int:
    names = args.case or ["nh-d-e", "gent-d-e", "gent-equi-biaxial", "figde", "uni-axial-ideal"]
    args.out.mkdir(parents=True, exist_ok=True)
    for name in names:
        if name in ("lambda1-3", "zs22"):
            print(f"{name}: FE fields only, run `skfem-dielectric validate --case {name}`")
            continue
        paths = save_figure(case_figure(name), args.out, name)
        print(f"{name}: " + ", ".join(str(p) for p in paths))
    return 0


def _validate_on_cluster(args, kw: dict) -> list:
    """:func:`~validation.sweep.validate` on the cluster of ``--scheduler``; a scheduler
    that goes away mid-run is an ``OSError`` naming it (exit code 3): the folder keeps
    what was saved and resumes when the command is rerun."""
    client, cluster = _dask_executor(args.scheduler, args.jobs)
    logs = [logging.getLogger(n) for n in ("distributed", "distributed.client")]
    levels = [log.level for log in logs]
    for log in logs:                   # the client's reconnect tracebacks: said below
        log.setLevel(logging.CRITICAL)
    try:
        return validate(args.case, args.out, executor=client.get_executor(), **kw)
    except (CancelledError, OSError, TimeoutError) as exc:
        if client.status == "running" and not isinstance(exc, CancelledError):
            raise                      # a file of --out, not the cluster
        raise OSError(None, f"the dask scheduler went away mid-run "
                            f"({type(exc).__name__}); rerun the same command to resume",
                      args.scheduler) from None
    finally:
        try:
            client.close(timeout=10)
            if cluster is not None:
                cluster.close(timeout=10)
        finally:
            for log, level in zip(logs, levels):
                log.setLevel(level)


def _cpu_seconds() -> float:
    """CPU seconds of this process and its finished worker processes (user + system)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def _cmd_validate(args) -> int:
    solver = solver_name(args.solver)
    if args.scheduler is not None and not args.scheduler.strip():
        raise ValueError("--scheduler must be a scheduler address or 'local', got ''")
    t0, cpu0 = time.perf_counter(), _cpu_seconds()
    runner = None if solver == "superlu" else functools.partial(run_fe, linear_solver=solver)
    kw = dict(quick=args.quick, force=args.force, runner=runner,
              progress=False if args.no_progress else None)
    if args.scheduler:
        results = _validate_on_cluster(args, kw)
        for r in results:                 # the workers' stderr may not reach this terminal
            for line in r.repairs:
                print(f"skfem-dielectric: {line}", file=sys.stderr)
    else:
        results = validate(args.case, args.out, jobs=args.jobs, **kw)
    for line in verdict_lines(results):
        print(line)
    print(f"report: {args.out / 'report.md'} (errors, breakdown and buckling loads, figures); "
          f"linear solver {solver}; {_cpu_seconds() - cpu0:.1f} s CPU, "
          f"{time.perf_counter() - t0:.1f} s wall")
    return 0 if all(r.n_steps or not r.n_runs for r in results) else 1


def _cmd_check(args) -> int:
    result = check(args.path, cases=args.case, tol=args.tol or [])
    paths = write_check_report(result, args.out) if args.out is not None else []
    for line in result.lines():
        print(line)
    for note in result.notes:
        print(f"note: {note}")
    if paths:
        print(f"report: {args.out / 'check.md'} (figures: "
              f"{', '.join(p.name for p in paths if p.suffix == '.png')})")
    return 0 if result.passed else 1


def _write_pvd(path: Path, files, times) -> Path:
    """A ParaView collection: each ``.vtu`` of ``files`` at the time value in ``times``."""
    items = "".join(f'    <DataSet timestep="{t}" group="" part="0" file="{f.name}"/>\n'
                    for f, t in zip(files, times))
    return write_text_atomic(path, '<?xml version="1.0"?>\n<VTKFile type="Collection" '
                                   'version="0.1" byte_order="LittleEndian">\n  <Collection>\n'
                                   f'{items}  </Collection>\n</VTKFile>\n')


def _cmd_simulate(args) -> int:
    if args.geometry != "uniaxial" and args.alpha is not None:
        raise ValueError(f"--alpha is the weight fraction of the Keplinger plate and applies to "
                         f"--geometry uniaxial only, got --alpha {args.alpha:g} with --geometry "
                         f"{args.geometry} (use --s for its dead load)")
    if args.geometry == "uniaxial" and args.s is not None:
        raise ValueError(f"--s applies to --geometry equibiaxial only (the Keplinger plate's "
                         f"load follows from --alpha), got --s {args.s:g} with --geometry "
                         f"uniaxial")
    positive("--steps", args.steps, integer=True)
    positive("--D0-max", args.D0_max)
    load_targets("--steps", 0.0, args.D0_max, num=args.steps + 1)     # bounded
    if args.alpha is not None:
        positive("--alpha", args.alpha)
    if args.s is not None:
        positive("--s", args.s, zero=True)
    check_mesh("--mesh", args.mesh)
    out = simulate(geometry=args.geometry, model=args.model, variant=args.variant, s=args.s,
                   alpha=args.alpha, D0_max=args.D0_max, steps=args.steps,
                   mesh=args.mesh, fmt=args.fmt, out=args.out)
    table = out[-1]
    with open(table, newline="") as fh:
        rows = list(csv.DictReader(fh))
    done = [r for r in rows if r["D0"] != ""]
    vtu = [p for p in out if p.suffix == ".vtu"]
    if vtu:
        out.insert(len(out) - 1, _write_pvd(table.with_name(table.name[:-len("_steps.csv")]
                                                            + ".pvd"),
                                            vtu, [r["D0"] for r in done]))
    for p in out:
        print(p)
    targets = [float(d) for d in load_targets("--steps", 0.0, args.D0_max,
                                              num=args.steps + 1)]
    failed = [r for r in rows if r["D0"] == ""]
    if failed:
        k = len(done)
        print(f"ramp stopped after step {k - 1} (D0 = {done[-1]['D0'] if done else '-'}): "
              f"the next target D0 = {targets[k]:g} was not reached: "
              f"{failed[0]['iterations'].removeprefix('stopped: ')}")
    else:
        print(f"ramp reached D0 = {targets[-1]:g} in {len(done) - 1} charge steps")
    return 0


def _cmd_explore(args) -> int:
    if args.export is not None and (not args.export.strip() or Path(args.export).is_dir()):
        raise ValueError(f"--export must name an HTML file to write, got {args.export!r}")
    require_bokeh()
    results = load_results(args.results)
    if args.export:
        print(export_html(args.export, results))
        return 0
    server = make_server(results, port=args.port)
    server.start()
    url = f"http://127.0.0.1:{args.port}/"
    print(f"explore: {url} (Ctrl-C stops the server)", flush=True)
    if not args.no_browser:
        webbrowser.open(url)
    try:
        server.io_loop.start()
    except KeyboardInterrupt:
        print("explore: stopped")
    return 0


def _cmd_bench(args) -> int:
    positive("--steps", args.steps, integer=True)
    positive("--D0-max", args.D0_max)
    load_targets("--steps", 0.0, args.D0_max, num=args.steps + 1)     # bounded
    positive("--alpha", args.alpha)
    check_mesh("--mesh", args.mesh)
    used = solver_name(args.solver)
    print(f"linear solver: {used}" + (" (chosen by 'auto': PARDISO if pypardiso is installed, "
                                      "else SuperLU)" if args.solver == "auto" else ""))
    for line in bench(mesh=tuple(args.mesh), alpha=args.alpha, D0_max=args.D0_max,
                      steps=args.steps, variant=args.variant, solver=used):
        print(line)
    return 0


def _one_line(text) -> str:
    return " ".join(str(text).split())


def _os_message(exc: OSError) -> str:
    paths = [str(p) for p in (exc.filename, exc.filename2) if p is not None]
    what = exc.strerror or type(exc).__name__
    if paths:
        return f"cannot use {' -> '.join(paths)}: {what}"
    return _one_line(exc) or what


class _Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread so that it unwinds like Ctrl-C: locks released,
    temporary files removed."""


def _on_sigterm(signum, frame):
    raise _Terminated()


def main(argv: list[str] | None = None) -> int:
    """Entry point of the console script; returns the exit code.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        One of :data:`EXIT_CODES`: 0 success, 1 a validation case produced no FE
        step (``validate``) or a checked case fails (``check``), 2 bad input (also:
        another process writes the same case), 3 a path cannot be created, read or
        written, 130 interrupted by SIGINT, 143 by SIGTERM (rerun the same command to
        resume). Every error is one line on stderr.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    cmd = {"list": _cmd_list, "curves": _cmd_curves, "validate": _cmd_validate,
           "check": _cmd_check, "simulate": _cmd_simulate, "bench": _cmd_bench,
           "explore": _cmd_explore,
           "clamp-zone": cmd_clamp_zone, **STUDY_COMMANDS}[args.command]
    args.argv = argv
    prefix = f"skfem-dielectric {args.command}: error:"
    atexit.unregister(remove_openmp_registration)      # once per process
    atexit.register(remove_openmp_registration, os.getpid())
    main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGTERM, _on_sigterm) if main_thread else None
    try:
        if getattr(args, "jobs", 1) < 1:
            raise ValueError(f"--jobs must be >= 1, got {args.jobs}")
        if "OPENBLAS_NUM_THREADS" in os.environ:    # the user's choice
            return cmd(args)
        # one OpenBLAS thread: SuperLU's and ARPACK's small BLAS calls spin the others
        # (docs/performance.md, "BLAS threads"); worker processes read the variable
        os.environ["OPENBLAS_NUM_THREADS"] = "1"
        try:
            with blas_thread_limit(1):
                return cmd(args)
        finally:
            del os.environ["OPENBLAS_NUM_THREADS"]
    except _Terminated:
        print("\nterminated (SIGTERM); rerun the same command to resume", file=sys.stderr)
        return 143
    except ValueError as exc:
        print(f"{prefix} {_one_line(exc)}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"{prefix} {_os_message(exc)}", file=sys.stderr)
        return 3
    except MemoryError as exc:      # an estimate that was too low: still one line
        what = _one_line(exc)[:160] or "an allocation failed"
        print(f"{prefix} not enough memory for this run ({what}); choose a smaller mesh",
              file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("\ninterrupted; rerun the same command to resume", file=sys.stderr)
        return 130
    finally:
        if main_thread:
            signal.signal(signal.SIGTERM, previous)


if __name__ == "__main__":      # pragma: no cover
    sys.exit(main())

"""The ``skfem-dielectric`` command line: ``list | curves | simulate | validate | bench |
wrinkling-fe | buckling | post-buckling``.

Every subcommand has ``--help``. Only this module prints, and it writes files
only into the folder given by ``--out``.
"""

from __future__ import annotations

import argparse
import csv
import functools
import math
import os
import sys
import time
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

import numpy as np

from .buckling import FULL as BUCKLING_FULL, QUICK as BUCKLING_QUICK, run_buckling
from .cases import CASES
from .fe import bench, pardiso_installed, run_fe, simulate
from .postbuckling import FULL as POST_FULL, QUICK as POST_QUICK, run_post_buckling
from .figures import case_figure, save_figure
from .wrinkling import run_wrinkling_fe
from .specs import MODELS, VARIANTS
from .report import verdict_lines
from .store import write_text_atomic
from .sweep import validate
from .extra_cases import EXTRA_CASES

__all__ = ["main", "build_parser", "EXIT_CODES"]


def _version() -> str:
    try:
        return version("skfem-dielectric")
    except PackageNotFoundError:      # pragma: no cover - running from a source tree
        return "unknown"


#: Exit codes of :func:`main` (docs/cli.md).
EXIT_CODES = {
    0: "success",
    1: "validate: a case with FE runs produced no FE step",
    2: "bad input: an invalid option or value (the message names it), an option that does "
       "not apply to the chosen geometry, a missing optional dependency, or another "
       "process writing the same case into the same --out (the message names it)",
    3: "file system: a path below --out cannot be created, read or written (--out is a "
       "file or below a file, no permission, disk full, .state is a file, a CSV is a "
       "folder); the message names the path",
    130: "interrupted (rerun the same command to resume)",
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


def _out_dir(text: str) -> Path:
    if not text.strip():
        raise argparse.ArgumentTypeError(f"must be a folder path, got {text!r}")
    return Path(text)


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
    c.add_argument("--out", required=True, type=_out_dir, help="output folder")

    w = add("wrinkling-fe", "FE wrinkling of a homogeneous plate against the Stroh analysis",
            "The critical charge of one Fourier mode of the cross-section with sliding ends "
            "(symmetric and antisymmetric, charge and voltage control) on a grid of lam and "
            "kh, against the finite-thickness dispersion relation: DIR/wrinkling-fe.csv and "
            "DIR/wrinkling-fe.png (full grid: several minutes).")
    w.add_argument("--quick", action="store_true", help="only lam = 1.5 and kh in {0.5, 2}")
    w.add_argument("--out", required=True, type=_out_dir, help="output folder")

    k = add("buckling", "first physical buckling load of the clamped plate per weight",
            "Ramp the clamped Keplinger plate (eighth model, grad-div 10) for each --alpha on "
            "each mesh, scan its states with the whole plate's spectrum (every symmetry "
            "class), locate the first physical buckling load D0_b to 1e-4 and compare it with "
            "the onsets of compressive P33 and the Newton limit: DIR/buckling.csv (one row "
            "per alpha x mesh, written as each is done; a rerun skips the rows present), "
            "DIR/buckling-scan.csv and DIR/buckling.png|pdf (redrawn after each row). "
            "Default: alpha = 1, 0.3, 1.5, 0.7, "
            "0.05 on 10x1x5, 20x1x10, 40x1x20, D0 step 0.25 (hours on 2 cores); --quick: "
            "alpha = 1 on 10x1x5 (the quick validate run's mesh), D0 step 0.5 (about a "
            "minute).")
    _study_arguments(k, "alpha = 1 on the coarse mesh 10x1x5",
                     "eighth-model meshes, e.g. 10x1x5 20x1x10", "charge step of the scan",
                     "last charge target", "auto",
                     "linear solver and inertia method (auto: PARDISO if installed)")

    pb = add("post-buckling", "follow the clamped plate onto its buckled branch",
             "Ramp the clamped Keplinger plate's quarter model (the whole thickness, "
             "grad-div 10) for each --alpha on each mesh, locate the buckling load D0_b of "
             "its own symmetry class, switch onto the buckled branch along the critical "
             "mode and follow it forward and back towards D0_b: DIR/post-buckling.csv (every "
             "state, both branches: mid-plane deflection, lam1 at the centre against the "
             "homogeneous closed form, stability counts), DIR/post-buckling-summary.csv "
             "(one row per alpha x mesh, written as each is done; a rerun skips the rows "
             "present) and DIR/post-buckling.png|pdf. Default: alpha = 0.05 and 1 on the "
             "quarter meshes 10x2x5, 14x2x7, 20x2x10 (about an hour on 2 cores); --quick: "
             "alpha = 0.05 on 10x2x5 up to D0 = 1 (about a minute).")
    _study_arguments(pb, "alpha = 0.05, one coarse mesh",
                     "quarter-model meshes with an even N2, e.g. 10x2x5 20x2x10",
                     "charge step of the scan and the branch (default 0.05)",
                     "last charge target (default: 1.5 for alpha = 0.05, 3.3 for alpha = 1; "
                     "see validation.postbuckling.WINDOW)", "auto",
                     "linear solver and inertia method (auto: PARDISO if installed)")
    pb.add_argument("--model", choices=["quarter", "x1"], default="quarter",
                    help="quarter: symmetry planes x1 = 0 and x3 = 0 (modes symmetric in x3); "
                         "x1: the plane x1 = 0 only, the whole width (modes of either "
                         "parity in x3; N3 then counts the whole width)")

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
    v.add_argument("--out", required=True, type=_out_dir, help="output folder")
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
    s.add_argument("--out", required=True, type=_out_dir, help="output folder")

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


def _positive(name: str, value, *, integer: bool = False, zero: bool = False) -> None:
    """``ValueError`` naming the option unless ``value`` is finite and > 0 (``zero``: >= 0)."""
    if math.isfinite(value) and (value >= 0 if zero else value > 0):
        return
    bound = ">= 0" if zero else (">= 1" if integer else "> 0")
    raise ValueError(f"{name} must be {bound}{'' if integer else ' and finite'}, got {value}")


def _check_mesh(name: str, mesh) -> None:
    if mesh is not None and any(n < 1 for n in mesh):
        raise ValueError(f"{name} must be three element counts >= 1, got "
                         f"{' '.join(map(str, mesh))}")


def _study_arguments(p, quick: str, meshes: str, step: str, top: str, solver: str,
                     solver_help: str) -> None:
    """The options shared by the ``buckling`` and ``post-buckling`` studies."""
    p.add_argument("--quick", action="store_true", help=quick)
    p.add_argument("--alpha", nargs="+", type=float, metavar="A", help="weight fractions")
    p.add_argument("--meshes", nargs="+", type=_mesh_triple, metavar="N1xN2xN3", help=meshes)
    p.add_argument("--D0-step", dest="D0_step", type=float, help=step)
    p.add_argument("--D0-max", dest="D0_max", type=float, help=top)
    p.add_argument("--solver", choices=["auto", "superlu", "pardiso"], default=solver,
                   help=solver_help)
    p.add_argument("--out", required=True, type=_out_dir, help="output folder")


def _study_options(args, quick: dict, full: dict) -> dict:
    """The study's settings: the ``--quick`` or default ones, overridden by the options
    given, each checked (``ValueError`` naming the option)."""
    opts = dict(quick if args.quick else full)
    for key in ("alpha", "meshes", "D0_step", "D0_max"):
        value = getattr(args, key)
        if value is not None:
            opts["alphas" if key == "alpha" else key] = value
    _positive("--D0-step", opts["D0_step"])
    if opts["D0_max"] is not None:
        _positive("--D0-max", opts["D0_max"])
    for a in opts["alphas"]:
        _positive("--alpha", a)
    args.solver = _solver(args.solver)
    return opts


def _mesh_triple(text: str) -> tuple[int, int, int]:
    """``"20x1x10"`` -> ``(20, 1, 10)`` (argparse type of ``--meshes``)."""
    try:
        el = tuple(int(v) for v in text.lower().split("x"))
    except ValueError:
        el = ()
    if len(el) != 3 or min(el) < 1:
        raise argparse.ArgumentTypeError(f"a mesh is N1xN2xN3 with counts >= 1, got {text!r}")
    return el


def _cmd_post_buckling(args) -> int:
    opts = _study_options(args, POST_QUICK, POST_FULL)
    for m in opts["meshes"]:
        if m[1] % 2:
            raise ValueError(f"--meshes: N2 must be even (nodes on the mid-plane), got "
                             f"{'x'.join(map(str, m))}")

    def show(row):
        print(f"alpha = {row['alpha']:g} {row['model']} {row['mesh']}: "
              f"D0_b = {row['D0_b']:.4f}, from the "
              f"branch {row['D0_b_pitchfork']:.4f}; deflection {row['deflection_last']:.3f} "
              f"mm at D0 = {row['D0_last']:.3g}; {row['seconds']:.0f} s"
              + (f" ({row['reason']})" if row["reason"] else ""), flush=True)

    run_post_buckling(args.out, **opts, solver=args.solver, model=args.model,
                      progress=show)
    print(f"wrote {args.out / 'post-buckling.csv'}, {args.out / 'post-buckling.png'} (and .pdf)")
    return 0


def _cmd_buckling(args) -> int:
    opts = _study_options(args, BUCKLING_QUICK, BUCKLING_FULL)

    def show(row):
        print(f"alpha = {row['alpha']:g} {row['mesh']}: D0_b = {row['D0_b']:.4f} "
              f"({row['class'] or 'none found'}), P33 onset (interior) "
              f"{row['P33_onset_interior']:.3f}, Newton limit {row['newton_limit']:.3f}, "
              f"{row['seconds']:.0f} s", flush=True)

    run_buckling(args.out, **opts, solver=args.solver, progress=show)
    print(f"wrote {args.out / 'buckling.csv'}, {args.out / 'buckling.png'} (and .pdf)")
    return 0


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


def _cmd_wrinkling(args) -> int:
    def show(row):
        err = "" if row[6] is None else f"  rel. error {row[6]:+.2e}"
        print(f"{row[0]:>7} {row[1]:>13} lam = {row[2]:g} kh = {row[3]:g}: "
              + (f"D0_fe = {row[4]:.6g}, D0_stroh = {row[5]:.6g}{err}" if row[4] is not None
                 else (row[10] or "no FE root")), flush=True)

    def show_elastic(row):
        print(f"{'D0 = 0':>7} {row[0]:>13} kh = {row[1]:g}: "
              + (f"lam_fe = {row[2]:.6g}, lam_stroh = {row[3]:.6g}  rel. error {row[4]:+.2e}"
                 if row[2] is not None else (row[6] or "no FE root")), flush=True)

    paths = run_wrinkling_fe(args.out, quick=args.quick, on_row=show, on_elastic_row=show_elastic)
    print("wrote " + ", ".join(str(p) for p in paths))
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


def _dask_executor(address: str, jobs: int):
    """``(client, cluster)`` of a dask.distributed scheduler ADDRESS or a LocalCluster."""
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise ValueError(f"--scheduler needs dask.distributed (pip install -e '.[cluster]'), "
                         f"got --scheduler {address} without it") from None
    if address == "local":
        cluster = LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        return Client(cluster), cluster
    try:
        return Client(address, timeout="20s"), None
    except ValueError as exc:
        raise ValueError(f"--scheduler must be a dask scheduler address (tcp://HOST:PORT) or "
                         f"'local', got {address!r} ({exc})") from None


def _solver(name: str) -> str:
    """The linear solver a command uses: ``auto`` is PARDISO when pypardiso (the ``fast``
    extra) is installed, else SuperLU; ``pardiso`` without it is a ``ValueError``."""
    if name == "pardiso" and not pardiso_installed():
        raise ValueError("--solver pardiso needs pypardiso (pip install -e '.[fast]'); "
                         "use --solver auto or superlu")
    if name == "auto":
        return "pardiso" if pardiso_installed() else "superlu"
    return name


def _cpu_seconds() -> float:
    """CPU seconds of this process and its finished worker processes (user + system)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def _cmd_validate(args) -> int:
    solver = _solver(args.solver)
    if args.scheduler is not None and not args.scheduler.strip():
        raise ValueError("--scheduler must be a scheduler address or 'local', got ''")
    t0, cpu0 = time.perf_counter(), _cpu_seconds()
    runner = None if solver == "superlu" else functools.partial(run_fe, linear_solver=solver)
    kw = dict(quick=args.quick, force=args.force, runner=runner,
              progress=False if args.no_progress else None)
    if args.scheduler:
        client, cluster = _dask_executor(args.scheduler, args.jobs)
        try:
            results = validate(args.case, args.out, executor=client.get_executor(), **kw)
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
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
    _positive("--steps", args.steps, integer=True)
    _positive("--D0-max", args.D0_max)
    if args.alpha is not None:
        _positive("--alpha", args.alpha)
    if args.s is not None:
        _positive("--s", args.s, zero=True)
    _check_mesh("--mesh", args.mesh)
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
    targets = [float(d) for d in np.linspace(0.0, args.D0_max, args.steps + 1)]
    failed = [r for r in rows if r["D0"] == ""]
    if failed:
        k = len(done)
        print(f"ramp stopped after step {k - 1} (D0 = {done[-1]['D0'] if done else '-'}): "
              f"the next target D0 = {targets[k]:g} was not reached: "
              f"{failed[0]['iterations'].removeprefix('stopped: ')}")
    else:
        print(f"ramp reached D0 = {targets[-1]:g} in {len(done) - 1} charge steps")
    return 0


def _cmd_bench(args) -> int:
    _positive("--steps", args.steps, integer=True)
    _positive("--D0-max", args.D0_max)
    _positive("--alpha", args.alpha)
    _check_mesh("--mesh", args.mesh)
    used = _solver(args.solver)
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
        step, 2 bad input (also: another process writes the same case), 3 a path
        cannot be created, read or written, 130 interrupted (rerun the same command
        to resume). Every error is one line on stderr.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    cmd = {"list": _cmd_list, "curves": _cmd_curves, "validate": _cmd_validate,
           "simulate": _cmd_simulate, "bench": _cmd_bench,
           "wrinkling-fe": _cmd_wrinkling, "buckling": _cmd_buckling,
           "post-buckling": _cmd_post_buckling}[args.command]
    prefix = f"skfem-dielectric {args.command}: error:"
    try:
        if getattr(args, "jobs", 1) < 1:
            raise ValueError(f"--jobs must be >= 1, got {args.jobs}")
        return cmd(args)
    except ValueError as exc:
        print(f"{prefix} {_one_line(exc)}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"{prefix} {_os_message(exc)}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("\ninterrupted; rerun the same command to resume", file=sys.stderr)
        return 130


if __name__ == "__main__":      # pragma: no cover
    sys.exit(main())

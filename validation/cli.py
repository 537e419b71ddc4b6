"""The ``skfem-dielectric`` command line: ``list | curves | simulate | validate | bench``.

Every subcommand has ``--help``. Only this module prints, and it writes files
only into the folder given by ``--out``.
"""

from __future__ import annotations

import argparse
import functools
import sys
import time
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from .cases import CASES
from .fe import bench, pardiso_installed, run_fe, simulate
from .figures import case_figure, save_figure
from .specs import MODELS, VARIANTS
from .sweep import validate

__all__ = ["main", "build_parser"]


def _version() -> str:
    try:
        return version("skfem-dielectric")
    except PackageNotFoundError:      # pragma: no cover - running from a source tree
        return "unknown"


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (exposed for the docs and the tests)."""
    p = argparse.ArgumentParser(
        prog="skfem-dielectric",
        description="Charge-controlled soft dielectric plates: the paper's figures with "
                    "finite-element dots, closed-form curves and FE simulations.")
    p.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", required=True)

    sub.add_parser("list", help="list the validation cases (one per paper figure)",
                   description="List the validation cases, their paper figure and FE runs.")

    c = sub.add_parser("curves", help="draw the analytic curves only (no FE)",
                       description="Draw the closed-form curves of the paper's figures, "
                                   "without FE dots, as PNG and PDF into --out.")
    c.add_argument("--case", nargs="+", choices=list(CASES), metavar="NAME",
                   help="cases to draw (default: those that need no FE fields)")
    c.add_argument("--out", required=True, type=Path, help="output folder")

    v = sub.add_parser("validate", help="run FE sweeps, overlay them on the theory (main job)",
                       description="Run the FE ramps of the cases, write DIR/<case>.csv step by "
                                   "step, the figures (PNG, PDF), summary.json and report.md. "
                                   "An interrupted run resumes when rerun with the same --out.")
    v.add_argument("--quick", action="store_true", help="coarse meshes and few D0 steps")
    v.add_argument("--case", nargs="+", choices=list(CASES), metavar="NAME",
                   help=f"cases to run (default: all of {', '.join(CASES)})")
    v.add_argument("--out", required=True, type=Path, help="output folder")
    v.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    v.add_argument("--force", action="store_true", help="recompute instead of resuming")
    v.add_argument("--solver", choices=["superlu", "pardiso"], default="superlu",
                   help="linear solver of the FE ramps: superlu (default, deterministic: a "
                        "resumed run repeats the uninterrupted one bit for bit) or pardiso "
                        "(faster on fine meshes, needs the 'fast' extra; multi-threaded, so "
                        "the last digits may differ between runs)")
    v.add_argument("--no-progress", action="store_true", help="no progress bars")

    s = sub.add_parser("simulate", help="run one FE ramp and export VTU/XDMF",
                       description="Run one FE ramp (pre-load, then D0 = 0 -> --D0-max) and "
                                   "export the fields for ParaView plus a CSV of the steps.")
    s.add_argument("--geometry", choices=["equibiaxial", "uniaxial"], default="uniaxial",
                   help="homogeneous equi-biaxial plate or clamped Keplinger plate")
    s.add_argument("--model", choices=list(MODELS), default="neo-Hookean")
    s.add_argument("--variant", choices=list(VARIANTS), default="coupled")
    s.add_argument("--s", type=float, default=None,
                   help="dimensionless dead load (equi-biaxial; default 1)")
    s.add_argument("--alpha", type=float, default=None,
                   help="weight fraction of the Keplinger plate (uni-axial; default 1)")
    s.add_argument("--D0-max", dest="D0_max", type=float, default=4.0, help="final D0")
    s.add_argument("--steps", type=int, default=8, help="number of charge steps")
    s.add_argument("--mesh", type=int, nargs=3, metavar=("N1", "N2", "N3"), default=None,
                   help="elements along length, thickness, width")
    s.add_argument("--format", dest="fmt", choices=["vtu", "xdmf"], default="vtu")
    s.add_argument("--out", required=True, type=Path, help="output folder")

    b = sub.add_parser("bench", help="time one Keplinger ramp (DOFs, iterations, seconds)",
                       description="Time the Keplinger plate ramp on a given mesh and solver.")
    b.add_argument("--mesh", type=int, nargs=3, metavar=("N1", "N2", "N3"), default=[20, 1, 10])
    b.add_argument("--alpha", type=float, default=1.0)
    b.add_argument("--D0-max", dest="D0_max", type=float, default=6.0)
    b.add_argument("--steps", type=int, default=6)
    b.add_argument("--variant", choices=list(VARIANTS), default="coupled")
    b.add_argument("--solver", default="auto", help="linear solver: superlu, pardiso or auto")
    return p


def _cmd_list(args) -> int:
    w = max(len(n) for n in CASES)
    print(f"{'case':<{w}}  {'paper figure':<18} {'runs quick/full':<16} description")
    for c in CASES.values():
        runs = f"{len(c.quick)}/{len(c.full)}"
        print(f"{c.name:<{w}}  {c.figure:<18} {runs:<16} {c.title}")
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


def _cmd_validate(args) -> int:
    if args.solver == "pardiso" and not pardiso_installed():
        raise ValueError("--solver pardiso needs pypardiso (pip install -e '.[fast]'), "
                         "got no pypardiso")
    t0 = time.perf_counter()
    runner = None if args.solver == "superlu" else functools.partial(run_fe,
                                                                     linear_solver=args.solver)
    results = validate(args.case, args.out, quick=args.quick, force=args.force, jobs=args.jobs,
                       runner=runner, progress=False if args.no_progress else None)
    print((args.out / "report.md").read_text(), end="")
    print(f"\nwall time {time.perf_counter() - t0:.1f} s; results in {args.out}")
    return 0 if all(r.n_steps or not r.n_runs for r in results) else 1


def _cmd_simulate(args) -> int:
    out = simulate(geometry=args.geometry, model=args.model, variant=args.variant, s=args.s,
                   alpha=args.alpha, D0_max=args.D0_max, steps=args.steps,
                   mesh=args.mesh, fmt=args.fmt, out=args.out)
    for p in out:
        print(p)
    return 0


def _cmd_bench(args) -> int:
    for line in bench(mesh=tuple(args.mesh), alpha=args.alpha, D0_max=args.D0_max,
                      steps=args.steps, variant=args.variant, solver=args.solver):
        print(line)
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the console script; returns the exit code.

    Exit codes: 0 success, 1 a validation case produced no FE step, 2 bad
    input, 130 interrupted (rerun the same command to resume).
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    cmd = {"list": _cmd_list, "curves": _cmd_curves, "validate": _cmd_validate,
           "simulate": _cmd_simulate, "bench": _cmd_bench}[args.command]
    try:
        if getattr(args, "jobs", 1) < 1:
            raise ValueError(f"--jobs must be >= 1, got {args.jobs}")
        return cmd(args)
    except ValueError as exc:
        print(f"skfem-dielectric {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("\ninterrupted; rerun the same command to resume", file=sys.stderr)
        return 130


if __name__ == "__main__":      # pragma: no cover
    sys.exit(main())

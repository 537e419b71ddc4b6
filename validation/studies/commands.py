"""The studies' commands of ``skfem-dielectric``: ``wrinkling-fe``, ``buckling`` and
``post-buckling``, their options and what they print.  Each command holds the lock
``--out/.state/<command>.lock`` (:func:`validation.store.command_lock`, taken by the
studies' :class:`validation.store.StudyStore`) while it writes, so that a second process
writing the same study into the same folder is refused.
"""

from __future__ import annotations

from ..options import mesh_triple, out_dir, positive, solver_name
from ..progress import notice
from .buckling import FULL as BUCKLING_FULL, GRAD_DIV_FORM, PLAIN_FORM, QUICK as BUCKLING_QUICK
from .buckling import run_buckling
from .buckling import charge_targets as buckling_targets
from .postbuckling import FULL as POST_FULL, QUICK as POST_QUICK, run_post_buckling
from .postbuckling import charge_targets as post_targets, study_window
from .wrinkling import run_wrinkling_fe

__all__ = ["add_study_commands", "STUDY_COMMANDS", "cmd_wrinkling", "cmd_buckling",
           "cmd_post_buckling", "buckling_line"]


def add_study_commands(add) -> None:
    """Add the parsers of ``wrinkling-fe``, ``buckling`` and ``post-buckling``.

    Parameters
    ----------
    add : callable
        ``add(name, help, description) -> ArgumentParser``, the sub-parser factory of
        :func:`validation.cli.build_parser`.
    """
    w = add("wrinkling-fe", "FE wrinkling of a homogeneous plate against the Stroh analysis",
            "The critical charge of one Fourier mode of the cross-section with sliding ends "
            "(symmetric and antisymmetric, charge and voltage control) on a grid of lam and "
            "kh, against the finite-thickness dispersion relation: DIR/wrinkling-fe.csv and "
            "DIR/wrinkling-fe.png (what each costs: docs/performance.md).")
    w.add_argument("--quick", action="store_true", help="only lam = 1.5 and kh in {0.5, 2}")
    w.add_argument("--out", required=True, type=out_dir, help="output folder")

    k = add("buckling", "first physical buckling load of the clamped plate per weight",
            "Ramp the clamped Keplinger plate (eighth model, grad-div 10) for each --alpha on "
            "each mesh, scan its states with the whole plate's spectrum (every symmetry "
            "class), locate the first physical buckling load D0_b to 1e-4 (as validate locates "
            "it) and compare it with "
            "the onsets of compressive P33 and the Newton limit: DIR/buckling.csv (one row "
            "per alpha x mesh, written as each is done; a rerun skips the rows present), "
            "DIR/buckling-scan.csv, DIR/buckling-trials.csv (the states the location solved), "
            "DIR/buckling-plain.csv (the plain form's P33 onsets) and "
            "DIR/buckling.png|pdf (redrawn after each row). "
            "Default: alpha = 1, 0.3, 1.5, 0.7, "
            "0.05 on 10x1x5, 20x1x10, 40x1x20, D0 step 0.25; --quick: alpha = 1 on 10x1x5 "
            "(the quick validate run's mesh), D0 step 0.5 (what each costs: "
            "docs/performance.md).")
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
             "quarter meshes 10x2x5, 14x2x7, 20x2x10; --quick: alpha = 0.05 on 10x2x5 up to "
             "D0 = 1 (what each costs: docs/performance.md).")
    _study_arguments(pb, "alpha = 0.05, one coarse mesh",
                     "quarter-model meshes with an even N2, e.g. 10x2x5 20x2x10",
                     "charge step of the scan and the branch (default 0.05)",
                     "last charge target (default: 1.5 for alpha = 0.05, 3.3 for alpha = 1; "
                     "see validation.studies.postbuckling.WINDOW)", "auto",
                     "linear solver and inertia method (auto: PARDISO if installed)")
    pb.add_argument("--model", choices=["quarter", "x1"], default="quarter",
                    help="quarter: symmetry planes x1 = 0 and x3 = 0 (modes symmetric in x3); "
                         "x1: the plane x1 = 0 only, the whole width (modes of either "
                         "parity in x3; N3 then counts the whole width)")


def _study_arguments(p, quick: str, meshes: str, step: str, top: str, solver: str,
                     solver_help: str) -> None:
    """The options shared by the ``buckling`` and ``post-buckling`` studies."""
    p.add_argument("--quick", action="store_true", help=quick)
    p.add_argument("--alpha", nargs="+", type=float, metavar="A", help="weight fractions")
    p.add_argument("--meshes", nargs="+", type=mesh_triple, metavar="N1xN2xN3", help=meshes)
    p.add_argument("--D0-step", dest="D0_step", type=float, help=step)
    p.add_argument("--D0-max", dest="D0_max", type=float, help=top)
    p.add_argument("--solver", choices=["auto", "superlu", "pardiso"], default=solver,
                   help=solver_help)
    p.add_argument("--out", required=True, type=out_dir, help="output folder")


def _study_options(args, quick: dict, full: dict) -> dict:
    """The study's settings: the ``--quick`` or default ones, overridden by the options
    given, each checked (``ValueError`` naming the option), repeated alphas and meshes
    given once."""
    opts = dict(quick if args.quick else full)
    for key in ("alpha", "meshes", "D0_step", "D0_max"):
        value = getattr(args, key)
        if value is not None:
            opts["alphas" if key == "alpha" else key] = value
    positive("--D0-step", opts["D0_step"])
    if opts["D0_max"] is not None:
        positive("--D0-max", opts["D0_max"])
    for a in opts["alphas"]:
        positive("--alpha", a)
    opts["alphas"] = tuple(dict.fromkeys(float(a) for a in opts["alphas"]))
    opts["meshes"] = tuple(dict.fromkeys(tuple(m) for m in opts["meshes"]))
    args.solver = solver_name(args.solver)
    return opts


def _given(value) -> bool:
    """Whether a row value is a number (an empty cell, ``None`` or ``nan``, is none)."""
    return value is not None and value == value


def _number(fmt: str, value, missing: str) -> str:
    """``fmt.format(value)``, or ``missing`` where the row has no value (an empty cell)."""
    return fmt.format(value) if _given(value) else missing


def buckling_line(row: dict, plain: dict | None = None) -> str:
    """The line ``skfem-dielectric buckling`` prints for a finished alpha x mesh: ``D0_b``
    from a row of ``buckling.csv``, then the interior ``P33`` onset and the Newton limit
    of each form, named: the grad-div stabilised form's states (the row, those analysed for
    buckling) and, with ``plain`` (its row of ``buckling-plain.csv``), the paper's plain
    form's.  A value a row does not have (an empty cell) is said in words: ``no D0_b
    found``, ``no P33 onset (interior) up to D0 = <D0_max>``, ``no Newton limit up to D0 =
    <D0_max>`` (every target converged).

    Examples
    --------
    >>> nan = float("nan")
    >>> buckling_line({"alpha": 1.0, "mesh": "10x1x5", "D0_b": 2.91472, "class": "AS",
    ...                "P33_onset_interior": 0.645, "newton_limit": nan, "D0_max": 5.0,
    ...                "seconds": 12.0},
    ...               {"P33_onset_interior": 2.52, "newton_limit": nan, "D0_max": 5.0})
    'alpha = 1 10x1x5: D0_b = 2.9147 (AS); grad-div stabilised form: P33 onset (interior) 0.645, no Newton limit up to D0 = 5; plain form: P33 onset (interior) 2.520, no Newton limit up to D0 = 5; 12 s'
    """
    def onsets(r: dict) -> str:
        top = f"up to D0 = {r['D0_max']:g}" if _given(r.get("D0_max")) else "at any target"
        return (_number("P33 onset (interior) {:.3f}", r["P33_onset_interior"],
                        f"no P33 onset (interior) {top}") + ", "
                + _number("Newton limit {:.3f}", r["newton_limit"], f"no Newton limit {top}"))

    return (f"alpha = {row['alpha']:g} {row['mesh']}: "
            + (f"D0_b = {row['D0_b']:.4f} ({row['class'] or 'none found'})"
               if _given(row["D0_b"]) else "no D0_b found")
            + f"; {GRAD_DIV_FORM}: {onsets(row)}"
            + (f"; {PLAIN_FORM}: {onsets(plain)}" if plain is not None else "")
            + f"; {row['seconds']:.0f} s")


def cmd_post_buckling(args) -> int:
    """``skfem-dielectric post-buckling``: :func:`~.postbuckling.run_post_buckling` with the
    options of ``args``, one line per finished alpha x mesh; returns the exit code 0."""
    opts = _study_options(args, POST_QUICK, POST_FULL)
    for m in opts["meshes"]:
        if m[1] % 2:
            raise ValueError(f"--meshes: N2 must be even (nodes on the mid-plane), got "
                             f"{'x'.join(map(str, m))}")
    for a in opts["alphas"]:                 # bounded before any work
        start, top = study_window(a, opts["D0_step"], opts["D0_max"])
        post_targets(opts["D0_step"], top, start)

    def show(row):
        last = (f"deflection {row['deflection_last']:.3f} mm at D0 = {row['D0_last']:.3g}"
                if _given(row["D0_last"]) else "no buckled state")
        print(f"alpha = {row['alpha']:g} {row['model']} {row['mesh']}: "
              + _number("D0_b = {:.4f}", row["D0_b"], "no D0_b found")
              + ", " + _number("from the branch {:.4f}", row["D0_b_pitchfork"],
                               "none from the branch")
              + f"; {last}; {row['seconds']:.0f} s"
              + (f" ({row['reason']})" if row["reason"] else ""), flush=True)

    run_post_buckling(args.out, **opts, solver=args.solver, model=args.model,
                      progress=show, note=notice)
    print(f"wrote {args.out / 'post-buckling.csv'}, {args.out / 'post-buckling.png'} (and .pdf)")
    return 0


def cmd_buckling(args) -> int:
    """``skfem-dielectric buckling``: :func:`~.buckling.run_buckling` with the options of
    ``args``, one line per finished alpha x mesh; returns the exit code 0."""
    opts = _study_options(args, BUCKLING_QUICK, BUCKLING_FULL)
    buckling_targets(opts["D0_step"], opts["D0_max"])          # bounded before any work

    def show(row, plain):
        print(buckling_line(row, plain), flush=True)

    run_buckling(args.out, **opts, solver=args.solver, progress=show, note=notice)
    print(f"wrote {args.out / 'buckling.csv'}, {args.out / 'buckling.png'} (and .pdf)")
    return 0


def cmd_wrinkling(args) -> int:
    """``skfem-dielectric wrinkling-fe``: :func:`~.wrinkling.run_wrinkling_fe`, one line
    per grid point; returns the exit code 0."""

    def show(row):
        err = "" if row[6] is None else f"  rel. error {row[6]:+.2e}"
        print(f"{row[0]:>7} {row[1]:>13} lam = {row[2]:g} kh = {row[3]:g}: "
              + (f"D0_fe = {row[4]:.6g}, D0_stroh = {row[5]:.6g}{err}" if row[4] is not None
                 else (row[10] or "no FE root")), flush=True)

    def show_elastic(row):
        print(f"{'D0 = 0':>7} {row[0]:>13} kh = {row[1]:g}: "
              + (f"lam_fe = {row[2]:.6g}, lam_stroh = {row[3]:.6g}  rel. error {row[4]:+.2e}"
                 if row[2] is not None else (row[6] or "no FE root")), flush=True)

    paths = run_wrinkling_fe(args.out, quick=args.quick, on_row=show,
                             on_elastic_row=show_elastic, note=notice, say=notice)
    print("wrote " + ", ".join(str(p) for p in paths))
    return 0


#: The handler of each study command: ``handler(args) -> exit code``.
STUDY_COMMANDS = {"wrinkling-fe": cmd_wrinkling, "buckling": cmd_buckling,
                  "post-buckling": cmd_post_buckling}

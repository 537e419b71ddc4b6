"""``skfem-dielectric clamp-zone SUBCOMMAND``: the clamp-zone study's one command.

Every subcommand that computes writes its table into ``--out`` (default
``results/clamp-zone``) under the table's lock, one unit's rows as soon as the unit is
done; a rerun skips the units there, so a killed run resumes.  Inputs are checked before
anything is allocated; every error is one line (the exit codes of ``skfem-dielectric``).
``--into-package`` writes into the shipped tables instead: a maintainer's step, from a
source checkout only.  ``units --scheduler local|ADDRESS`` farms the units to a
dask.distributed cluster; the rows are written by this process as units finish.
"""

from __future__ import annotations

import functools
import inspect
import logging
import math
import re
import shlex
import sys
from concurrent.futures import CancelledError
from pathlib import Path

from skfem_dielectric.fem import blas_thread_limit

from ..cluster import check_scheduler, dask_executor
from ..fe.model import BUCKLING_GRAD_DIV
from ..figures.common import save_figure
from ..options import out_dir, positive, solver_name
from ..store import TableWriter, aside_path
from .band import band_table, edge_band_figure
from .costs import estimated_GB, physical_GB
from .counts import CountsPaused, run_counts
from ..data.clamp_zone import clamp_unit_load
from ..data.registry import MAX_D0, TABLES, load, shipped_path, table_file
from ..specs import LOCATION_TOL
from .flagged import run_flagged
from ..data.key import FORMULATIONS, UnitKey, parse_mesh
from .layer import run_layer
from .modes import clamp_modes_figure, read_clamp_modes
from .onsets import run_onsets
from .p33 import run_p33
from .scaling import scaling_tables
from .section import DEFAULT_K, check_section_size, run_section
from .voltage import run_voltage
from ..data.spec import read_table
from .tables import breakdown_table, clamp_study_tables, voltage_table
from .units import run_unit, write_mode

__all__ = ["add_clamp_zone_command", "cmd_clamp_zone", "MAX_ELEMENTS", "DEFAULT_OUT",
           "package_data_dir"]

#: the largest eighth-model mesh (``n1 n2 n3`` elements) a run accepts without
#: ``--max-elements``: about 38 unknowns per element
MAX_ELEMENTS = 5000
#: exit code of ``counts`` paused by ``--budget`` (rerun the same command to continue)
EXIT_PAUSED = 4

#: where a run writes by default
DEFAULT_OUT = Path("results") / "clamp-zone"
#: the most charge steps a ramp of ``--D0-max / --D0-step`` may have
MAX_STEPS = 400

_HELP = ("the clamp-zone study: units, class onsets, the clamp layer, P33 onsets, flagged "
         "modes, counts, the edge section, tables, figures")


def package_data_dir() -> Path:
    """The shipped tables' folder, if this package runs from a source checkout.

    Raises
    ------
    ValueError
        The package is installed (no ``pyproject.toml`` beside it): the shipped tables are
        read-only there.
    """
    root = Path(__file__).resolve().parents[2]
    if not (root / "pyproject.toml").is_file() or not (root / "validation" / "data").is_dir():
        raise ValueError(f"--into-package writes the shipped tables of a source checkout; "
                         f"this package is installed at {root} (use --out)")
    return root / "validation" / "data"


# -- the options ------------------------------------------------------------------------
def _common(p, *, meshes: bool = True, mesh_default=None, grading: float = 1.0,
            formulation: bool = True) -> None:
    p.add_argument("--alpha", nargs="+", type=float, required=True, metavar="A",
                   help="weight fractions (> 0)")
    if meshes:
        p.add_argument("--mesh", nargs="+", required=True, metavar="N1xN2xN3",
                       help="eighth-model meshes")
    else:
        p.add_argument("--mesh", default=mesh_default, metavar="N1xN2xN3",
                       help="the 3D eighth-model mesh")
    p.add_argument("--grading", type=float, default=grading,
                   help="last / first element length along x1 (< 1: finer at the clamp)")
    if formulation:
        p.add_argument("--formulation", default="mixed", choices=FORMULATIONS,
                       help="how J = 1 is imposed")
    p.add_argument("--solver", choices=["auto", "superlu", "pardiso"], default="auto",
                   help="linear solver (auto: PARDISO if installed)")
    p.add_argument("--out", type=out_dir, default=DEFAULT_OUT,
                   help="folder of the tables (and modes) this run writes")
    p.add_argument("--into-package", action="store_true",
                   help="write into the shipped tables (a maintainer's step, from a source "
                        "checkout only)")
    p.add_argument("--max-elements", type=int, default=MAX_ELEMENTS,
                   help="largest mesh accepted, in elements n1 n2 n3 (a mesh whose "
                        "estimated peak memory, about 1.8 GB per 1000 elements, exceeds "
                        "this machine's is refused whatever this bound)")


def add_clamp_zone_command(add) -> None:
    """Add ``clamp-zone`` and its subcommands.

    Parameters
    ----------
    add : callable
        ``add(name, help, description) -> ArgumentParser``, the sub-parser factory of
        :func:`validation.cli.build_parser`.
    """
    z = add("clamp-zone", _HELP,
            "The clamp-zone study of the clamped Keplinger plate (docs/clamp-zone.md): a unit "
            "is one weight fraction on one graded eighth-model mesh. Each subcommand writes "
            "its table into --out (default results/clamp-zone), a unit's rows as it is "
            "done; a rerun resumes.")
    sub = z.add_subparsers(dest="clamp_command", metavar="SUBCOMMAND", required=True,
                           help="what to run or show (each has --help)")

    def new(name, help):
        return sub.add_parser(name, help=help, description=help[0].upper() + help[1:] + ".",
                              formatter_class=z.formatter_class)

    u = new("units", "locate the first physical buckling load D0_b of each unit, with its "
                     "mode (table units, modes/<unit>.npz)")
    _common(u)
    u.add_argument("--D0-step", dest="D0_step", type=float, default=0.5,
                   help="charge step of the scanned ramp")
    u.add_argument("--D0-max", dest="D0_max", type=float, default=6.0,
                   help="last charge target")
    u.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run the units on a dask.distributed cluster: a scheduler ADDRESS "
                        "(tcp://HOST:PORT) or 'local' for a LocalCluster of --jobs workers "
                        "(the 'cluster' extra)")
    u.add_argument("--jobs", type=int, default=2, help="workers of --scheduler local")

    o = new("onsets", "locate each symmetry class's crossing in a unit's bracket "
                      "(table onsets)")
    _common(o)
    o.add_argument("--classes", nargs="+", default=None, metavar="CLASS",
                   help="class names, e.g. 'x1 S, x2 A, x3 S' (default: every class with "
                        "a physical negative mode at the bracket's top)")
    o.add_argument("--bracket", nargs=2, type=float, metavar=("LO", "HI"), default=None,
                   help="the bracket instead of a unit's (no unit of the mesh needed)")

    la = new("layer", "J and volume ratios in the clamp layer at a unit's D0_b "
                      "(table layer)")
    _common(la)

    p = new("p33", "locate the plain form's P33 onsets and Newton limit (table p33)")
    _common(p, formulation=False)
    p.add_argument("--D0-step", dest="D0_step", type=float, default=0.25,
                   help="charge step of the ramp")
    p.add_argument("--D0-max", dest="D0_max", type=float, default=6.0,
                   help="last charge target")

    f = new("flagged", "every negative mode of the whole plate at one charge "
                       "(table flagged)")
    _common(f, formulation=False)
    f.add_argument("--D0", type=float, required=True, help="the charge")

    c = new("counts", "negative-mode counts per symmetry class at a few charges "
                      "(table counts)")
    _common(c)
    c.add_argument("--D0", nargs="+", type=float, required=True, help="the charges")
    c.add_argument("--grad-div", dest="grad_div", type=float, default=None,
                   help="grad-div weight (units of mu; default that of the units)")
    c.add_argument("--pressure", choices=["Q1", "P0"], default="Q1", help="pressure space")
    c.add_argument("--budget", type=float, default=None, metavar="SECONDS",
                   help="pause each unit's ramp after the first target past SECONDS (wall) "
                        "and exit with code 4; its state is kept under OUT/.state/counts/ "
                        "and a rerun of the same command continues it")

    v = new("voltage", "follow each unit's plate under voltage control through its first "
                       "limit point, with the first negative mode before it (table voltage)")
    _common(v)
    v.add_argument("--grad-div", dest="grad_div", type=float, default=None,
                   help="grad-div weight (units of mu; default that of the units; 0: the "
                        "plain mixed form)")
    v.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run the units on a dask.distributed cluster (as for units)")
    v.add_argument("--jobs", type=int, default=2, help="workers of --scheduler local")

    s = new("section", "the clamp edge in section against waves along the clamp "
                       "(table section)")
    _common(s, meshes=False, mesh_default="40x1x36", grading=0.1, formulation=False)
    s.add_argument("--D0", nargs="+", type=float, required=True,
                   help="the charges (0: the dead load alone)")
    s.add_argument("--grad-div", dest="grad_div", type=float, default=None,
                   help="grad-div weight (units of mu; default that of the units)")
    s.add_argument("--h0", nargs="+", type=float, default=[0.04, 0.02, 0.01],
                   help="edge element sizes of the section (mm)")
    s.add_argument("--pressure", choices=["Q1", "P0"], default="Q1",
                   help="the section's pressure space (the 3D ramp keeps Q1)")
    s.add_argument("--k", nargs="+", type=float, default=None,
                   help="wavenumbers along x3 (1/mm; default 25 from 2 pi/50 to 200)")
    s.add_argument("--length", type=float, default=5.0, help="the section's length (mm)")

    t = new("tables", "print the study's Markdown tables from its tables")
    t.add_argument("--breakdown", action="store_true",
                   help="only the three meanings of breakdown per weight (docs/breakdown.md)")
    t.add_argument("--voltage", action="store_true",
                   help="only the voltage table, a row per unit (docs/clamp-zone.md)")
    t.add_argument("--from", dest="source", type=out_dir, default=None, metavar="DIR",
                   help="a run's --out (default: the shipped tables)")

    w = new("scaling", "print the wavelength against the Cerda-Mahadevan scaling")
    w.add_argument("--no-membrane", action="store_true",
                   help="the wavelength table only (no membrane ramps)")

    b = new("band", "draw the clamp-edge band, edge-band.png|pdf (or print its table)")
    b.add_argument("--from", dest="source", type=out_dir, default=None, metavar="DIR",
                   help="a run's --out (default: the shipped section table)")
    b.add_argument("--table", action="store_true", help="print the band's table instead")
    b.add_argument("--out", type=out_dir, default=DEFAULT_OUT, help="figure folder")

    m = new("modes", "draw the modes at D0_b, clamp-modes.png|pdf")
    m.add_argument("--from", dest="source", type=out_dir, default=None, metavar="DIR",
                   help="a run's --out (default: the shipped modes)")
    m.add_argument("--out", type=out_dir, default=DEFAULT_OUT, help="figure folder")


# -- checks before anything is allocated -------------------------------------------------
def _finite(name: str, value, *, zero: bool = False) -> float:
    """``value`` as a float, checked by :func:`validation.options.positive`."""
    value = float(value)
    positive(name, value, zero=zero)
    return value


def _meshes(args, texts) -> list[tuple]:
    if args.max_elements < 1:
        raise ValueError(f"--max-elements must be >= 1, got {args.max_elements}")
    out = []
    for text in texts:
        try:
            el = parse_mesh(text)
        except ValueError as exc:
            raise ValueError(f"--mesh: {exc}") from None
        n = math.prod(el)
        need = estimated_GB(n)
        if n > args.max_elements:
            raise ValueError(f"--mesh {text} has {n} elements, more than --max-elements "
                             f"{args.max_elements} (about {need:.0f} GB); raise "
                             f"--max-elements to run it")
        have = physical_GB()
        if math.isfinite(have) and need > have:
            raise ValueError(f"--mesh {text} needs about {need:.0f} GB of memory ({n} "
                             f"elements), more than this machine's {have:.0f} GB")
        out.append(el)
    return list(dict.fromkeys(out))


def _charges(name: str, values) -> list[float]:
    return list(dict.fromkeys(_finite(name, v) for v in values))


def _charge_list(name: str, values, *, zero: bool = False) -> list[float]:
    """Charges (:func:`_charge`), each once, in the order given."""
    return list(dict.fromkeys(_charge(name, v, zero=zero) for v in values))


def _charge(name: str, value, *, zero: bool = False) -> float:
    """A charge: finite, > 0 (``>= 0`` if ``zero``) and at most :data:`MAX_D0`."""
    value = _finite(name, value, zero=zero)
    if value > MAX_D0:
        raise ValueError(f"{name} must be at most {MAX_D0:g} (the study's plates wrinkle or "
                         f"stop below D0 = 6), got {value:g}")
    return value


def _key_value(name: str, value: float) -> float:
    """``value``, refused if the tables' key (6 significant digits) would change it."""
    if float(f"{value:g}") != value:
        raise ValueError(f"{name} {value!r} has more digits than the tables keep (6 "
                         f"significant: {value:g}); give {value:g} or another value")
    return value


def _ramp(step: float, top: float) -> None:
    _finite("--D0-step", step)
    _charge("--D0-max", top)
    if top / step > MAX_STEPS:
        raise ValueError(f"--D0-max / --D0-step must be at most {MAX_STEPS} steps, got "
                         f"{top:g} / {step:g}")


def _settings(args) -> dict:
    """The checked options shared by the computing subcommands."""
    alphas = [_key_value("--alpha", a) for a in _charges("--alpha", args.alpha)]
    grading = _key_value("--grading", _finite("--grading", args.grading))
    if grading > 1e3:
        raise ValueError(f"--grading must be at most 1000, got {grading:g}")
    return {"alphas": alphas, "grading": grading, "solver": solver_name(args.solver)}


# -- the tasks: one unit of work each, run here or on a dask worker ------------------------
def _task(runner, key: UnitKey, *args, one_row: bool = False, stream: str | None = None,
          progress=None, emit=None, **options):
    """Run ``runner(key, *args, **options)`` (a runner of the study, which takes the unit's
    :class:`~validation.data.key.UnitKey`) with one BLAS thread: the task of one unit,
    here or on a dask worker (a ``functools.partial`` of it is picklable).  Returns its
    rows (``one_row``: the runner returns one row); ``progress`` goes to a runner that
    reports it, and ``emit(rows)`` to one that writes rows as it goes (``stream``: its
    ``on_row`` or ``on_rows``)."""
    if progress is not None and "progress" in inspect.signature(runner).parameters:
        options["progress"] = progress
    if stream is not None and emit is not None:
        options[stream] = (lambda r: emit([r])) if stream == "on_row" else emit
    with blas_thread_limit(1):
        out = runner(key, *args, **options)
    return [out] if one_row else out


# -- running the tasks ------------------------------------------------------------------
def _say(text: str) -> None:
    print(text, flush=True)


def _table_path(args, name: str) -> Path:
    folder = package_data_dir() if args.into_package else Path(args.out)
    if folder.exists() and not folder.is_dir():
        raise NotADirectoryError(20, "not a folder", str(folder))
    return folder / TABLES[name].file


def _command(argv) -> str:
    args = list(sys.argv[1:] if argv is None else argv)
    return "skfem-dielectric " + " ".join(shlex.quote(a) for a in args)


def _run(args, name: str, tasks, show, *, incremental: bool = False, files=None,
         stale=None, superseded=None) -> int:
    """Run ``tasks`` (``[(label, row_key, callable)]``) not yet in the table ``name``,
    writing each task's rows (with the run's command) as soon as they exist; ``files(row)``
    writes a row's own files first (a row in the table has them).  ``stale(row)``: why a
    row of the table does not hold for this run's settings (``""``: it holds); such a
    row's task runs again, and its new row replaces it (the old one kept aside).
    ``superseded(row)``: the same for the rows of tasks without a ``row_key`` (which skip
    the rows they find themselves): a new row with the key of such a row replaces it."""
    path = _table_path(args, name)
    command = _command(getattr(args, "argv", None))
    with TableWriter(path, TABLES[name], note=_say) as table:
        todo, replace = [], []
        said = {}
        for r in table.rows if superseded is not None else ():
            why = superseded(r)
            if why:
                replace.append(r)
                said.setdefault(why, []).append(TABLES[name].key_of(r))
        for why, keys in said.items():        # one line per reason, not per row
            _say(f"{len(keys)} row(s) in {path.name} ({', '.join(map(str, keys[0]))}"
                 f"{' ...' if len(keys) > 1 else ''}) {why}; computed again (the old rows "
                 f"kept in {aside_path(path).name})")
        for label, row_key, task in tasks:
            have = table.find(row_key) if row_key is not None else []
            why = next((w for w in map(stale, have) if w), "") if stale and have else ""
            if have and not why:
                _say(f"{label}: kept")
                continue
            if why:
                _say(f"{label}: its row in {path.name} {why}; computed again (the old row "
                     f"kept in {aside_path(path).name})")
                replace.extend(have)
            todo.append((label, task))

        def write(rows):
            for r in rows if files is not None else ():
                files(r)
            table.add([{**r, "command": command} for r in rows], replace=replace)
            for r in rows:
                show(r)

        scheduler = getattr(args, "scheduler", None)
        if scheduler:
            _on_cluster(args, todo, write)
        else:
            for label, task in todo:
                _say(f"{label}:")
                progress = lambda t: _say("  " + t)      # noqa: E731
                if incremental:
                    task(progress=progress, emit=write)
                else:
                    write(task(progress=progress))
    _say(f"wrote {path}")
    return 0


_NO_CROSSING = re.compile(r"no physical crossing up to D0 = (?P<top>[0-9.e+-]+)")


def _units_stale(D0_step: float, D0_max: float):
    """Why a ``units`` row does not hold for a run with these charge settings: another
    ``D0_step`` (the scan, so the crossing found, depends on it), or no crossing found up
    to a ``D0_max`` below this run's.  A located ``D0_b`` holds for any larger ``D0_max``;
    a ramp that stopped (its note) stops at the same charge."""
    def stale(row: dict) -> str:
        step = float(row["D0_step"] or "nan")
        if step != float(f"{D0_step:.6g}"):
            return f"was scanned with --D0-step {step:g}, this run asks {D0_step:g}"
        m = _NO_CROSSING.search(row.get("note") or "")
        if not row["D0_b"] and m and float(m["top"]) < D0_max:
            return (f"found no crossing up to D0 = {float(m['top']):g}, this run asks up to "
                    f"--D0-max {D0_max:g}")
        return ""
    return stale


def _p33_stale(D0_step: float, D0_max: float):
    """Why a ``p33`` row does not hold: another ``D0_step``, or a ``D0_max`` below this
    run's where the row found no Newton limit (the ramp reached its ``D0_max``)."""
    def stale(row: dict) -> str:
        step, top = (float(row[c] or "nan") for c in ("D0_step", "D0_max"))
        if step != float(f"{D0_step:.6g}"):
            return f"was computed with --D0-step {step:g}, this run asks {D0_step:g}"
        if not row["newton_limit"] and top < D0_max:
            return (f"ramped to D0 = {top:g} without a Newton limit, this run asks up to "
                    f"--D0-max {D0_max:g}")
        return ""
    return stale


def _on_cluster(args, todo, write) -> None:
    """The tasks on the dask cluster of ``--scheduler``; rows written here as they end.
    A worker that dies mid-task has its task run again on another (dask's rule); the loss
    of the scheduler ends the command with an :class:`OSError` (exit code 3, one line)
    after the rows of the finished tasks are written, and a rerun resumes."""
    client, cluster = dask_executor(args.scheduler, args.jobs)
    finished = 0
    # the client logs every reconnection attempt after a loss, a traceback each: the one
    # line below says it instead
    quiet = [logging.getLogger(n) for n in ("distributed.client", "distributed.core",
                                            "distributed.comm", "distributed.batched")]
    levels = [q.level for q in quiet]
    for q in quiet:
        q.setLevel(logging.CRITICAL)
    try:
        from distributed import as_completed
        from distributed.comm.core import CommClosedError
        futures = {client.submit(task, pure=False): label for label, task in todo}
        try:
            for fut in as_completed(futures):
                rows = fut.result()
                _say(f"{futures[fut]}: done on the cluster")
                write(rows)
                finished += 1
        except (CancelledError, CommClosedError, TimeoutError, OSError) as exc:
            if isinstance(exc, OSError) and exc.filename is not None:
                raise                   # a file of this process, not the cluster
            raise OSError(None, f"lost the dask scheduler after {finished} of {len(todo)} "
                                f"unit(s) ({type(exc).__name__}); their rows are kept, rerun "
                                f"the same command to resume", str(args.scheduler)) from None
    finally:
        try:
            client.close(timeout=5)
        except Exception:               # the scheduler is gone: nothing to close
            pass
        if cluster is not None:
            cluster.close()
        for q, level in zip(quiet, levels):
            q.setLevel(level)


def _cluster_options(args) -> None:
    """``--scheduler`` and ``--jobs`` checked before anything runs."""
    if args.scheduler is not None:
        check_scheduler(args.scheduler)
    if args.jobs < 1:
        raise ValueError(f"--jobs must be >= 1, got {args.jobs}")


def _cmd_units(args) -> int:
    _cluster_options(args)
    opts = _settings(args)
    _ramp(args.D0_step, args.D0_max)
    meshes = _meshes(args, args.mesh)
    modes = (package_data_dir() / "modes" if args.into_package else Path(args.out) / "modes")
    tasks = []
    for a in opts["alphas"]:
        for el in meshes:
            key = UnitKey(a, el, opts["grading"], args.formulation)
            tasks.append((str(key), dict(zip(TABLES["units"].key, key.cells)),
                          functools.partial(_task, run_unit, key, one_row=True,
                                            D0_step=args.D0_step, D0_max=args.D0_max,
                                            solver=opts["solver"])))

    def mode(r):           # before the row: a unit in the table has its mode
        if "mode" in r:
            write_mode(modes, UnitKey.from_row(r), r["mode"])

    def show(r):
        _say(f"  {UnitKey.from_row(r)}: D0_b {float(r['D0_b'] or 'nan'):.4f} "
             + (f"({r['note']}) " if r.get('note') else "")
             + f"{r.get('half_waves', '')} half-waves, {r['dofs']} DOFs, "
             f"{r['cpu_s']} CPU s, {r['peak_GB']} GB")
    return _run(args, "units", tasks, show, files=mode,
                stale=_units_stale(args.D0_step, args.D0_max))


def _cmd_voltage(args) -> int:
    _cluster_options(args)
    opts = _settings(args)
    grad_div = _grad_div(args)
    tasks = [(str(k), dict(zip(TABLES["voltage"].key, (*k.cells, grad_div))),
              functools.partial(_task, run_voltage, k, one_row=True, grad_div=grad_div,
                                solver=opts["solver"]))
             for k in (UnitKey(a, el, opts["grading"], args.formulation)
                       for a in opts["alphas"] for el in _meshes(args, args.mesh))]

    def show(r):
        _say(f"  {UnitKey.from_row(r)} grad-div {float(r['grad_div']):g}: E0 limit "
             f"{float(r['E0_limit'] or 'nan'):.5f} "
             + (f"({r['note']}) " if r.get("note") else "")
             + f"at D0 {float(r.get('D0_limit') or 'nan'):.4f}, "
             f"{float(r.get('ratio') or 'nan'):.4f} of max_E0; {r['dofs']} DOFs, "
             f"{r['cpu_s']} CPU s, {r['peak_GB']} GB")
    return _run(args, "voltage", tasks, show)


def _units_source(args):
    return None if args.into_package else Path(args.out)


def _cmd_onsets(args) -> int:
    opts = _settings(args)
    meshes = _meshes(args, args.mesh)
    bracket = None
    if args.bracket is not None:
        lo, hi = (_charge("--bracket", v) for v in args.bracket)
        if not lo < hi:
            raise ValueError(f"--bracket must be LO < HI, got {lo:g} {hi:g}")
        bracket = (lo, hi)
    path = _table_path(args, "onsets")
    have = read_table(path, TABLES["onsets"])
    tasks = []
    for a in opts["alphas"]:
        for el in meshes:
            key = UnitKey(a, el, opts["grading"], args.formulation)
            done = {r["class"] for r in have if UnitKey.from_row(r) == key}
            if args.classes is not None and set(args.classes) <= done:
                _say(f"{key}: kept")
                continue
            tasks.append((str(key), None, functools.partial(
                _task, run_onsets, key, stream="on_row", solver=opts["solver"],
                classes=args.classes, skip=done,
                units=_units_source(args), given=bracket)))
    return _run(args, "onsets", tasks, lambda r: None, incremental=True)


def _cmd_layer(args) -> int:
    opts = _settings(args)
    meshes = _meshes(args, args.mesh)
    if any(el[0] < 2 for el in meshes):
        raise ValueError("--mesh: the clamp layer needs n1 >= 2 (two element layers at the "
                         "clamp)")
    tasks = [(str(k), dict(zip(TABLES["layer"].key, k.cells)),
              functools.partial(_task, run_layer, k, one_row=True,
                                solver=opts["solver"], units=_units_source(args)))
             for k in (UnitKey(a, el, opts["grading"], args.formulation)
                       for a in opts["alphas"] for el in meshes)]

    def show(r):
        _say(f"  {UnitKey.from_row(r)} at D0 = {float(r['D0']):g}: first layer J "
             f"{float(r['J_first_min']):.4f}-{float(r['J_first_max']):.4f}, "
             f"{r['cpu_s']} CPU s")
    return _run(args, "layer", tasks, show)


def _cmd_p33(args) -> int:
    opts = _settings(args)
    _ramp(args.D0_step, args.D0_max)
    meshes = _meshes(args, args.mesh)
    tasks = [(str(k), {"alpha": k.alpha, "mesh": k.mesh_text, "grading": k.grading},
              functools.partial(_task, run_p33, k, one_row=True, D0_step=args.D0_step,
                                D0_max=args.D0_max, solver=opts["solver"]))
             for k in (UnitKey(a, el, opts["grading"]) for a in opts["alphas"]
                       for el in meshes)]

    def show(r):
        _say(f"  {UnitKey.from_row(r)}: P33 onsets " + ", ".join(
            f"{s} {r[f'P33_onset_{s}'] or 'none'}" for s in ("centre_line", "clamp",
                                                             "interior"))
             + f", Newton limit {r['newton_limit'] or 'none'}, {r['cpu_s']} CPU s")
    return _run(args, "p33", tasks, show, stale=_p33_stale(args.D0_step, args.D0_max))


def _cmd_flagged(args) -> int:
    opts = _settings(args)
    D0 = _charge("--D0", args.D0)
    meshes = _meshes(args, args.mesh)
    tasks = [(f"{k} D0 = {D0:g}", {"alpha": k.alpha, "mesh": k.mesh_text,
                                   "grading": k.grading, "D0": D0},
              functools.partial(_task, run_flagged, k, D0, solver=opts["solver"]))
             for k in (UnitKey(a, el, opts["grading"]) for a in opts["alphas"]
                       for el in meshes)]

    def show(r):
        _say(f"  {r['kind']} {r['class']} eigenvalue {r['eigenvalue']}")
    return _run(args, "flagged", tasks, show)


def _grad_div(args) -> float:
    return (BUCKLING_GRAD_DIV if args.grad_div is None
            else _finite("--grad-div", args.grad_div, zero=True))


def _cmd_counts(args) -> int:
    opts = _settings(args)
    D0 = _charge_list("--D0", args.D0)
    meshes = _meshes(args, args.mesh)
    grad_div = _grad_div(args)
    path = _table_path(args, "counts")
    have = read_table(path, TABLES["counts"])
    budget = args.budget
    if budget is not None and not (math.isfinite(budget) and budget > 0):
        raise ValueError(f"--budget must be positive and finite, got {budget!r}")
    states = Path(args.out) / ".state" / "counts"
    states.mkdir(parents=True, exist_ok=True)
    tasks = []
    for a in opts["alphas"]:
        for el in meshes:
            key = UnitKey(a, el, opts["grading"], args.formulation)
            done = {float(r["D0"]) for r in have if UnitKey.from_row(r) == key
                    and float(r["grad_div"]) == grad_div and r["pressure"] == args.pressure}
            if set(D0) <= done:
                _say(f"{key}: kept")
                continue
            state = states / f"{key.stem}_gd{grad_div:g}_{args.pressure}.npz"
            tasks.append((str(key), None, functools.partial(
                _task, run_counts, key, D0, stream="on_row", grad_div=grad_div,
                pressure=args.pressure, solver=opts["solver"], skip=done, checkpoint=state,
                budget=budget)))
    try:
        return _run(args, "counts", tasks, lambda r: None, incremental=True)
    except CountsPaused as exc:
        print(f"skfem-dielectric clamp-zone counts: {exc}; rerun the same command to "
              f"continue", file=sys.stderr)
        return EXIT_PAUSED


def _cmd_section(args) -> int:
    opts = _settings(args)
    D0 = _charge_list("--D0", args.D0, zero=True)
    (el,) = _meshes(args, [args.mesh])
    grad_div = _grad_div(args)
    length = _finite("--length", args.length)
    h0s = _charges("--h0", args.h0)
    check_section_size(length, h0s, names=("--length", "--h0"))
    if max(h0s) >= length:
        raise ValueError(f"--h0 must be below --length {length:g}, got {max(h0s):g}")
    ks = DEFAULT_K if args.k is None else _charges("--k", args.k)
    path = _table_path(args, "section")
    done = {TABLES["section"].key_of(r) for r in read_table(path, TABLES["section"])
            if not _section_inverted(r)}
    tasks = [(f"{UnitKey(a, el, opts['grading'])} D0 = {d:g}", None, functools.partial(
        _task, run_section, UnitKey(a, el, opts["grading"]), d, h0s, ks,
        stream="on_rows", grad_div=grad_div, length=length, solver=opts["solver"],
        done=done, pressure=args.pressure))
        for a in opts["alphas"] for d in D0]
    ours = {(UnitKey(a, el, opts["grading"]), float(f"{d:.6g}"), float(f"{h:.6g}"))
            for a in opts["alphas"] for d in D0 for h in h0s}

    def superseded(row: dict) -> str:      # an inverted row of a state this run computes
        try:
            mine = ((UnitKey.from_row(row), float(row["D0"]), float(row["h0"])) in ours
                    and float(row["grad_div"]) == grad_div
                    and float(row["length"]) == length and row["pressure"] == args.pressure)
        except (KeyError, ValueError):
            return ""
        return _section_inverted(row) if mine else ""

    return _run(args, "section", tasks, lambda r: None, incremental=True,
                superseded=superseded)


def _section_inverted(row: dict) -> str:
    """Why a ``section`` row does not hold: its base state was inverted somewhere
    (``J_min <= 0``: a state the section's solver now refuses); ``""`` if it holds."""
    try:
        j = float(row["J_min"])
    except (KeyError, TypeError, ValueError):
        return ""
    return f"has an inverted base state (J_min = {j:g})" if j <= 0 else ""


def _damaged_rows(source) -> None:
    """One line on stderr per damaged row of the study's tables in ``source`` (default:
    the shipped ones), which the printed tables leave out."""
    for name in TABLES:
        load(name, source, note=lambda msg: print(f"skfem-dielectric clamp-zone: {msg}",
                                                  file=sys.stderr))


def _cmd_tables(args) -> int:
    source = _source(args)
    _damaged_rows(source)
    sys.stdout.write(breakdown_table(source) if args.breakdown else
                     voltage_table(source) if args.voltage else clamp_study_tables(source))
    return 0


def _cmd_scaling(args) -> int:
    _damaged_rows(None)
    sys.stdout.write(scaling_tables(membrane=not args.no_membrane))
    return 0


def _source(args):
    if args.source is not None and not Path(args.source).is_dir():
        raise ValueError(f"--from must be a folder of the study's tables, got "
                         f"{str(args.source)!r}")
    return args.source


def _cmd_band(args) -> int:
    rows = load("section", _source(args))
    if args.table:
        sys.stdout.write(band_table(rows))
        return 0
    if not rows:
        raise ValueError(f"--from {args.source}: the section table has no rows")
    Path(args.out).mkdir(parents=True, exist_ok=True)
    for p in save_figure(edge_band_figure(rows), Path(args.out), "edge-band"):
        _say(str(p))
    return 0


def _cmd_modes(args) -> int:
    folder = (Path(args.source) / "modes" if _source(args) is not None
              else shipped_path("units").parent / "modes")
    modes = read_clamp_modes(folder)
    loads = {}
    for a in sorted({round(m["alpha"], 9) for m in modes}):
        try:
            g = clamp_unit_load(a, path=table_file("units", _source(args)),
                                classes_path=table_file("onsets", _source(args)))
        except ValueError:                  # no converged load: the mode's own D0_b
            continue
        loads[a] = (g["D0_b"], max(g["spread"], LOCATION_TOL), g["meshes"])
    Path(args.out).mkdir(parents=True, exist_ok=True)
    for p in save_figure(clamp_modes_figure(modes, loads), Path(args.out), "clamp-modes"):
        _say(str(p))
    return 0


_SUBCOMMANDS = {"units": _cmd_units, "onsets": _cmd_onsets, "layer": _cmd_layer,
                "p33": _cmd_p33, "flagged": _cmd_flagged, "counts": _cmd_counts,
                "section": _cmd_section, "voltage": _cmd_voltage, "tables": _cmd_tables,
                "scaling": _cmd_scaling, "band": _cmd_band, "modes": _cmd_modes}


def cmd_clamp_zone(args) -> int:
    """``skfem-dielectric clamp-zone``: the handler of ``args.clamp_command``; returns the
    exit code 0 (errors are raised: ``ValueError`` bad input, ``OSError`` a path)."""
    return _SUBCOMMANDS[args.clamp_command](args)


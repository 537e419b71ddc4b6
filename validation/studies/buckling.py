"""Buckling study of the clamped Keplinger plate: first physical buckling load per weight.

For each weight ``alpha`` and mesh the eighth model (grad-div 10, which lets Newton pass
the clamp/free-edge corner) is ramped in ``D0``; its states are scanned with the whole
plate's spectrum of their own tangent, the Hessian of the stabilised energy whose
equilibria they are (:func:`skfem_dielectric.studies.buckling.buckling_load`), and the first
physical buckling load ``D0_b`` located to ``1e-4``, as the ``validate`` harness locates
it on its run analysed for buckling (same form, tolerance and Newton settings;
docs/stability.md, "Which state each column is of").  Next to it: the onsets of compressive
``P33/mu < -BREAKDOWN_TOL`` (the paper's breakdown, Conroy Broderick, Righi, Destrade and
Ogden, "Stability analysis of charge-controlled soft dielectric plates", Int. J. Eng.
Sci., 2020, Sec. 6) on five sets of points, and where Newton stops.

Files (all in ``out``): ``buckling.csv`` (one row per alpha x mesh, written as each is
done, after its other rows; a rerun skips the rows present), ``buckling-scan.csv`` (every scanned state),
``buckling-trials.csv`` (the states the location of ``D0_b`` solved between two scanned
states, :attr:`~skfem_dielectric.studies.buckling.BucklingLoad.trials`),
``buckling-plain.csv`` (the same ramp without grad-div: its ``P33`` onsets and Newton
limit), ``.modes/<alpha>_<mesh>.npz`` (the critical mode's top-face deflection) and
``buckling.png``.  The ``P33`` columns of ``buckling.csv`` and ``buckling-scan.csv`` are
of the grad-div stabilised form's states, those of ``buckling-plain.csv`` of the paper's
plain form (docs/stability.md, "Which state each column is of"); the figure and the printed
line name which.
"""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.models.plate.modes import top_deflection
from skfem_dielectric.solvers import illinois
from skfem_dielectric.studies.buckling import buckling_load

from ..fe.model import BUCKLING_GRAD_DIV, BUCKLING_NEWTON
from ..specs import LOCATION_TOL
from ..figures import save_figure
from ..options import load_targets
from ..data.spec import TableSpec
from ..store import StudyStore, read_npz, write_npz_atomic
from ..data.loads import buckling_loads, p33_onsets
from ..markers import CONVERGED_BUCKLING, P33_ONSET_LOCATED, legend_style
from ..table import BREAKDOWN_TOL

__all__ = ["COLUMNS", "SCAN_COLUMNS", "TRIAL_COLUMNS", "PLAIN_COLUMNS", "P33_SETS",
           "p33_measures", "onset", "TABLE", "SCAN", "TRIALS", "PLAIN", "GRAD_DIV_FORM",
           "PLAIN_FORM",
           "charge_targets", "run_one", "run_plain", "run_buckling", "richardson", "buckling_figure"]

#: where min P33/mu is taken: centre line, clamp line (one element inside the clamp),
#: centre line outside the clamps' 2H layer, all quadrature points outside it, centre
P33_SETS = ("centre_line", "clamp", "interior", "whole_interior", "centre")
COLUMNS = (["alpha", "mesh", "D0_b", "class", "lowest_eig", "corner_share", "mesh_scale",
            "lam1_b", "n_negative_b", "first_negative_D0"]
           + [f"P33_onset_{k}" for k in P33_SETS]
           + ["newton_limit", "D0_max", "seconds"])
SCAN_COLUMNS = (["alpha", "mesh", "D0", "n_negative", "lowest", "physical", "physical_class",
                 "corner_share", "mesh_scale", "lam1"] + [f"P33_{k}" for k in P33_SETS])
#: the trial states of the location: D0, the followed physical mode's eigenvalue, its class
TRIAL_COLUMNS = ["alpha", "mesh", "D0", "eigenvalue", "physical_class"]
#: the names of the two forms whose states the study reports (figure, printed line)
GRAD_DIV_FORM = "grad-div stabilised form"
PLAIN_FORM = "plain form"
#: the same ramp without grad-div (the harness's form): its P33 onsets and Newton limit
PLAIN_COLUMNS = (["alpha", "mesh"] + [f"P33_onset_{k}" for k in P33_SETS]
                 + ["newton_limit", "D0_max", "seconds"])
#: ``--quick``: the mesh and step of the quick ``validate`` run's alpha = 1 plate, so that
#: both report the same D0_b
QUICK = {"alphas": (1.0,), "meshes": ((10, 1, 5),), "D0_step": 0.5,
         "D0_max": 5.0}
FULL = {"alphas": (1.0, 0.3, 1.5, 0.7, 0.05),
        "meshes": ((10, 1, 5), (20, 1, 10), (40, 1, 20)), "D0_step": 0.25, "D0_max": 6.0}


def p33_measures(problem, x, load, quantities) -> dict[str, float]:
    """``min P33/mu`` on each of :data:`P33_SETS` at a converged state of the plate."""
    pl = problem.plate
    edge = pl.L1 / 2 - 2 * pl.H + 1e-9
    c = quantities["centre_line"]
    inner = np.abs(c["x1"]) <= edge
    best = np.inf
    X = problem.b2.mapping.F(problem.b2.X)
    for sl, F, G, p in problem.quadrature_fields(x, load):
        S33 = problem.stresses(F, G, p, load)["S"][2, 2] / problem.material.mu
        keep = np.abs(X[0][sl]) <= edge
        if keep.any():
            best = min(best, float(S33[keep].min()))
    return {"centre_line": quantities["min_P33"], "clamp": quantities["min_P33_clamp"],
            "interior": float(np.min(c["P33"][inner])), "whole_interior": best,
            "centre": quantities["P33_centre"]}


def onset(D0, values, tol: float = BREAKDOWN_TOL) -> float:
    """First ``D0`` where ``values`` falls below ``-tol`` (linear between the states),
    ``nan`` if it never does, the first ``D0`` if it starts below."""
    D0, v = np.asarray(D0, float), np.asarray(values, float) + tol
    below = np.flatnonzero(v < 0)
    if not below.size:
        return float("nan")
    i = int(below[0])
    if i == 0:
        return float(D0[0])
    return float(D0[i - 1] + v[i - 1] * (D0[i] - D0[i - 1]) / (v[i - 1] - v[i]))


def _mesh_name(el) -> str:
    return "x".join(str(int(v)) for v in el)


def run_one(alpha: float, elements, *, D0_step: float, D0_max: float,
            solver: str = "auto", modes_dir: Path | None = None
            ) -> tuple[dict, list[dict], list[dict]]:
    """One alpha x mesh: ramp, P33 onsets, buckling load.  Returns the row, the scan and
    the trial states of the location (rows of :data:`TRIAL_COLUMNS`)."""
    t0 = time.time()
    D0 = charge_targets(D0_step, D0_max)
    res = fe.keplinger_plate(alpha, D0=D0, elements=tuple(elements), symmetry="eighth",
                             options=fe.PlateOptions(grad_div=BUCKLING_GRAD_DIV),
                             linear_solver=solver,
                             settings=replace(fe.gallery.KEPLINGER_SETTINGS, max_cutbacks=6,
                                              max_iter=25))
    newton = dict(linear_solver=solver, settings=BUCKLING_NEWTON)
    pb = res.problem
    charge = [st for st in res.steps if np.asarray(st.load)[1] > 0]
    states = [res.steps[len(res.steps) - len(charge) - 1]] + charge
    mesh = _mesh_name(elements)
    method = "pardiso" if solver == "pardiso" else "auto"
    bl = buckling_load(pb, [(st.x, st.load) for st in states], method=method,
                       tol=LOCATION_TOL, **newton)
    scan = []
    for st, row in zip(states, bl.scan):
        m = p33_measures(pb, st.x, st.load, st.quantities)
        scan.append({"alpha": alpha, "mesh": mesh, "D0": row["D0"],
                     "n_negative": row["n_negative"], "lowest": row["lowest"],
                     "physical": row["physical"], "physical_class": row["physical_class"],
                     "corner_share": row["corner_share"], "mesh_scale": row["mesh_scale"],
                     "lam1": st.quantities["lam1"], **{f"P33_{k}": m[k] for k in P33_SETS}})
    # P33 onsets over every converged state (not only the scanned ones)
    allm = [p33_measures(pb, st.x, st.load, st.quantities) for st in states[len(scan):]]
    allm = [{k: r[f"P33_{k}"] for k in P33_SETS} for r in scan] + allm
    d_all = [float(np.asarray(st.load)[1]) for st in states]
    first_neg = next((r["D0"] for r in bl.scan if r["n_negative"] > 0), float("nan"))
    lab = bl.label
    row = {"alpha": alpha, "mesh": mesh, "D0_b": bl.D0_b,
           "class": lab.symmetry if lab else "", "lowest_eig": bl.eigenvalue,
           "corner_share": lab.corner_share if lab else np.nan,
           "mesh_scale": lab.mesh_scale if lab else np.nan,
           "lam1_b": pb.postprocess(bl.x, bl.load)["lam1"] if bl.found else np.nan,
           "n_negative_b": (bl.scan[-1]["n_negative"] if bl.scan else 0),
           "first_negative_D0": first_neg,
           **{f"P33_onset_{k}": onset(d_all, [m[k] for m in allm]) for k in P33_SETS},
           "newton_limit": (float(np.asarray(res.steps[-1].load)[1]) if not res.converged
                            else np.nan),
           "D0_max": D0_max, "seconds": round(time.time() - t0, 1)}
    if modes_dir is not None and lab is not None:
        modes_dir.mkdir(parents=True, exist_ok=True)
        X1, X3, u2 = top_deflection(pb, lab.mode, lab.increments)
        write_npz_atomic(modes_dir / f"{alpha:g}_{mesh}.npz", X1=X1, X3=X3, u2=u2)
    trials = [{"alpha": alpha, "mesh": mesh, "D0": t["D0"], "eigenvalue": t["eigenvalue"],
               "physical_class": t["class"]} for t in bl.trials]
    return row, scan, trials


def run_plain(alpha: float, elements, *, D0_step: float, D0_max: float,
              solver: str = "auto") -> dict:
    """The plain form (``grad_div = 0``, as the validation harness ramps it) on the same
    targets: its ``P33`` onsets and where Newton stops (``nan``: all targets reached)."""
    t0 = time.time()
    D0 = charge_targets(D0_step, D0_max)
    res = fe.keplinger_plate(alpha, D0=D0, elements=tuple(elements), symmetry="eighth",
                             linear_solver=solver,
                             settings=replace(fe.gallery.KEPLINGER_SETTINGS, max_cutbacks=6,
                                              max_iter=25))
    pb = res.problem
    states = [st for st in res.steps if np.asarray(st.load)[1] > 0]
    ms = [p33_measures(pb, st.x, st.load, st.quantities) for st in states]
    d = [float(np.asarray(st.load)[1]) for st in states]
    return {"alpha": alpha, "mesh": _mesh_name(elements),
            **{f"P33_onset_{k}": onset(d, [m[k] for m in ms]) for k in P33_SETS},
            "newton_limit": (float(np.asarray(res.steps[-1].load)[1]) if not res.converged
                             else np.nan),
            "D0_max": D0_max, "seconds": round(time.time() - t0, 1)}


#: the files of the study (:class:`~validation.store.StudyStore`): the table last
TABLE = TableSpec.plain("buckling.csv", tuple(COLUMNS), ("alpha", "mesh"))
SCAN = TableSpec.plain("buckling-scan.csv", tuple(SCAN_COLUMNS), ("alpha", "mesh"))
TRIALS = TableSpec.plain("buckling-trials.csv", tuple(TRIAL_COLUMNS), ("alpha", "mesh"))
PLAIN = TableSpec.plain("buckling-plain.csv", tuple(PLAIN_COLUMNS), ("alpha", "mesh"))


def charge_targets(D0_step: float, D0_max: float) -> np.ndarray:
    """The charge targets of the ramp, multiples of ``D0_step`` up to ``D0_max`` (checked:
    ``ValueError`` naming ``--D0-step`` for more than
    :data:`~validation.options.MAX_TARGETS`)."""
    return load_targets("--D0-step", D0_step, D0_max, D0_step)


def run_buckling(out: Path, *, alphas, meshes, D0_step: float, D0_max: float,
                 solver: str = "auto", progress=None, note=None) -> list[dict]:
    """The study: every alpha x mesh not yet in ``out/buckling.csv``, then the figure.

    The study holds its lock and store (:class:`~validation.store.StudyStore`): one
    alpha x mesh is done when its row is in ``buckling.csv``, written after its scan and
    plain-form rows; a folder of another ``D0_step``, ``D0_max`` or ``solver`` is
    discarded and recomputed (``note(message)`` says so).  Repeated alphas and meshes
    are computed once.  ``progress(row, plain)`` is called with the table row and the
    plain form's row of each finished alpha x mesh.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    alphas = list(dict.fromkeys(float(a) for a in alphas))
    meshes = list(dict.fromkeys(tuple(int(n) for n in el) for el in meshes))
    charge_targets(D0_step, D0_max)
    footer = (f"skfem-dielectric buckling: eighth-model meshes "
              f"{', '.join(_mesh_name(el) for el in meshes)}, D0 step {D0_step:g} up to "
              f"{D0_max:g}, linear solver {solver}")
    settings = {"D0_step": float(D0_step), "D0_max": float(D0_max), "solver": solver}
    plan = [(a, _mesh_name(el)) for a in alphas for el in meshes]
    with StudyStore(out, "buckling", settings, TABLE, (SCAN, TRIALS, PLAIN), plan=plan,
                    derived=("buckling.png", "buckling.pdf", ".modes"), note=note) as store:

        def draw():
            buckling_figure(store.rows(), store.rows(SCAN.file), out / ".modes",
                            out / "buckling.png", footer=footer,
                            trials=store.rows(TRIALS.file), plain=store.rows(PLAIN.file))

        for alpha in alphas:
            for el in meshes:
                if store.done((alpha, _mesh_name(el))):
                    continue
                row, scan, trials = run_one(alpha, el, D0_step=D0_step, D0_max=D0_max,
                                            solver=solver, modes_dir=out / ".modes")
                plain = run_plain(alpha, el, D0_step=D0_step, D0_max=D0_max, solver=solver)
                store.commit(row, {SCAN.file: scan, TRIALS.file: trials, PLAIN.file: [plain]})
                draw()              # the figure follows the table: every finished row
                if progress is not None:
                    progress(row, plain)
        rows = store.rows()
        if rows:
            draw()
    return rows


def richardson(h, values) -> tuple[float, float, float]:
    """Richardson extrapolation of a value on three meshes with unequal refinement ratios.

    The three finest meshes (sizes ``h`` descending, ``h1 > h2 > h3``) are taken as
    ``v = v_inf + b h^p``.  With the ratios ``r1 = h1/h2``, ``r2 = h2/h3`` the observed
    order ``p`` solves the three-mesh equation

        (v1 - v2) / (v2 - v3) = r2^p (r1^p - 1) / (r2^p - 1),

    found by Illinois steps (:func:`skfem_dielectric.solvers.illinois`) on its logarithm;
    ``r1 = r2 = r`` gives the familiar ``p = log((v1 - v2)/(v2 - v3)) / log r``.  Then
    ``v_inf = v3 + (v3 - v2)/(r2^p - 1)``.

    Parameters
    ----------
    h, values : array_like
        Mesh sizes (descending) and the values on them; the last three are used.

    Returns
    -------
    extrapolated, error, order : float
        ``v_inf``, the error estimate ``|v_inf - v3|`` and ``p``.  ``nan`` (the error:
        ``|v3 - v2|``) where the sequence is not monotone or its differences shrink too
        slowly for any positive order (no asymptotic range).

    Raises
    ------
    ValueError
        ``h`` not strictly descending and positive, or ``h`` and ``values`` of different
        lengths.

    Notes
    -----
    Used for the converged buckling loads (docs/validation.md, "The study"; the meshes
    10 x 1 x 5, 14 x 1 x 7, 20 x 1 x 10 have ratios 1.4 and 1.43;
    ``validation/data/buckling_loads.csv``, :mod:`validation.data.loads`).
    """
    h, v = np.asarray(h, float), np.asarray(values, float)
    if h.shape != v.shape:
        raise ValueError(f"h and values must have the same length, got {h.size} and {v.size}")
    h, v = h[-3:], v[-3:]
    if v.size < 3 or not np.all(np.isfinite(v)):
        return float("nan"), float("nan"), float("nan")
    if not (np.all(h > 0) and np.all(np.diff(h) < 0)):
        raise ValueError(f"h must be positive and strictly descending, got {h.tolist()}")
    d1, d2 = v[1] - v[0], v[2] - v[1]
    if d1 == 0 or d2 / d1 <= 0:
        return float("nan"), abs(d2), float("nan")
    l1, l2 = np.log(h[0] / h[1]), np.log(h[1] / h[2])
    log_q = float(np.log(d1 / d2))

    def g(p):       # log q - log(r2^p (r1^p - 1)/(r2^p - 1)): > 0 below the order
        return log_q - (p * l2 + np.log(np.expm1(p * l1)) - np.log(np.expm1(p * l2)))

    lo, g_lo = 1e-12, log_q - float(np.log(l1 / l2))     # the limit p -> 0
    if g_lo <= 0:                       # differences shrink too slowly for any p > 0
        return float("nan"), abs(d2), float("nan")
    hi = 1.0
    while g(hi) > 0:
        hi *= 2
        if hi > 1e3:
            return float("nan"), abs(d2), float("nan")
    p, *_ = illinois(g, lo, g_lo, hi, g(hi), maxiter=200,
                     done=lambda a, b, c: abs(b - a) <= 4e-16 * max(1.0, abs(c)))
    ext = float(v[2] + d2 / np.expm1(p * l2))
    return ext, abs(ext - v[2]), float(p)


def buckling_figure(rows, scan, modes_dir: Path, path: Path, footer: str = "",
                    trials=(), plain=()) -> Path:
    """One row of panels per alpha, written to ``path`` (PNG) and beside it as PDF, with
    ``footer`` under the panels.

    * The lowest physical eigenvalue against ``D0`` per mesh, the states of the
      grad-div stabilised form: the scanned states where it was computed (dots) and the
      trial states of the location (``trials``, rows of :data:`TRIAL_COLUMNS`: crosses;
      the search starts at a scanned state and brackets with the next, and there the line
      takes the followed mode's value), joined in ``D0`` order, so that the line passes
      through zero at the located ``D0_b`` (dotted line); a straight line between two
      scanned states would not.
    * The ``P33`` minima against ``D0`` on the finest mesh, of the grad-div stabilised
      form's states (:data:`GRAD_DIV_FORM`, as the scan holds them), with the interior
      onset of both forms: the grad-div one and the paper's plain form's
      (:data:`PLAIN_FORM`, ``plain``: rows of ``buckling-plain.csv``).
    * The critical mode's deflection map.

    Beside each weight's own meshes the reference of the converged study (when it has the
    weight): the converged ``D0_b`` on the zero line of the eigenvalue panel and the
    located ``P33`` onset on the criterion's line of the ``P33`` panel
    (:mod:`validation.data.loads`, the markers of :mod:`validation.markers`).
    """
    alphas = sorted({r["alpha"] for r in rows})
    fig, axes = plt.subplots(len(alphas), 3, figsize=(14, 3.4 * len(alphas)), squeeze=False,
                             constrained_layout=True)
    for ax3, alpha in zip(axes, alphas):
        mine = [r for r in rows if r["alpha"] == alpha]
        meshes = sorted({r["mesh"] for r in mine}, key=lambda m: int(m.split("x")[0]))
        for k, m in enumerate(meshes):
            sc = [(s["D0"], s["physical"]) for s in scan
                  if s["alpha"] == alpha and s["mesh"] == m and np.isfinite(s["physical"])]
            tr = [(t["D0"], t["eigenvalue"]) for t in trials
                  if t["alpha"] == alpha and t["mesh"] == m and np.isfinite(t["eigenvalue"])]
            both = sorted(dict(sc + tr).items())   # at a scanned state, the trial's value
            line, = ax3[0].plot([p[0] for p in both], [p[1] for p in both], "-", lw=1.0,
                                label=m)
            c = line.get_color()
            if sc:
                ax3[0].plot(*zip(*sc), "o", ms=6, mfc="none", mew=1.2, color=c,
                            gid="scanned", zorder=4,
                            label="scanned states" if k == 0 else None)
            if tr:               # below the scanned states' rings: a shared end shows both
                ax3[0].plot(*zip(*tr), "x", ms=4, color=c, gid="trials", zorder=3,
                            label="trial states of the location" if k == 0 else None)
            b = next(r for r in mine if r["mesh"] == m)["D0_b"]
            if np.isfinite(b):
                ax3[0].axvline(b, ls=":", lw=0.8, color=c)
        ax3[0].axhline(0, color="k", lw=0.6)
        ref = next((e for e in buckling_loads() if e.converged
                    and np.isclose(e.alpha, alpha)), None)
        if ref is not None:      # the reference: where the resolving meshes cross
            ax3[0].plot([ref.D0_b], [0.0], ls="none", gid="buckling-converged",
                        label=f"{CONVERGED_BUCKLING.name}: {ref.D0_b:.4f}",
                        **legend_style(CONVERGED_BUCKLING))
        ax3[0].set(xlabel="D0", ylabel="lowest physical eigenvalue",
                   title=f"alpha = {alpha:g}: {GRAD_DIV_FORM} (dotted: D0_b)")
        ax3[0].legend(fontsize=7)
        fine = meshes[-1]
        sc = [s for s in scan if s["alpha"] == alpha and s["mesh"] == fine]
        for k in P33_SETS:
            ax3[1].plot([s["D0"] for s in sc], [s[f"P33_{k}"] for s in sc], ".-", label=k)
        ax3[1].axhline(-BREAKDOWN_TOL, color="red", lw=0.6, gid="p33-criterion")
        located = next((d for a, d, _ in p33_onsets() if np.isclose(a, alpha)), None)
        if located is not None:  # the reference: the onset on the resolving graded mesh
            ax3[1].plot([located], [-BREAKDOWN_TOL], ls="none", gid="p33-onset-located",
                        label=f"{P33_ONSET_LOCATED.name}: {located:.4f}",
                        **legend_style(P33_ONSET_LOCATED))
        r = next(r for r in mine if r["mesh"] == fine)
        pl = next((p for p in plain if p["alpha"] == alpha and p["mesh"] == fine), None)
        for form, onset_D0, ls in ((GRAD_DIV_FORM, r["P33_onset_interior"], "-"),
                                   (PLAIN_FORM, pl["P33_onset_interior"] if pl else np.nan,
                                    "--")):
            if np.isfinite(onset_D0):
                ax3[1].axvline(onset_D0, color="0.3", lw=0.9, ls=ls, gid=f"onset-{form}",
                               label=f"P33 onset (interior), {form}: {onset_D0:.3f}")
        ax3[1].set(xlabel="D0", ylabel="min P33/mu",
                   title=f"{fine}: P33 minima of the {GRAD_DIV_FORM}")
        ax3[1].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.22), ncol=2)
        f = modes_dir / f"{alpha:g}_{fine}.npz"
        if f.exists():
            d = read_npz(f)
            u2 = d["u2"] / max(np.abs(d["u2"]).max(), 1e-300)
            t = ax3[2].tricontourf(d["X1"], d["X3"], u2, 21, cmap="RdBu_r", vmin=-1, vmax=1)
            fig.colorbar(t, ax=ax3[2], shrink=0.8)
            ax3[2].set(aspect="equal", xlabel="X1 (mm)", ylabel="X3 (mm)",
                       title=f"mode at D0_b = {r['D0_b']:.4f}: {r['class']}")
        else:                                 # no crossing in the scanned range
            ax3[2].axis("off")
            ax3[2].text(0.5, 0.5, f"{fine}: no buckling load\nin the scanned range",
                        ha="center", va="center", transform=ax3[2].transAxes)
    if footer:
        fig.text(0.5, 0.0, footer, ha="center", va="top", fontsize=7, color="0.3")
    path = Path(path)
    save_figure(fig, path.parent, path.stem, dpi=110, bbox_inches="tight")
    return path

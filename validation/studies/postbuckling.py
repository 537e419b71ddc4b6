"""The clamped Keplinger plate past its buckling load: the post-buckled branch per weight.

For each weight ``alpha`` and mesh the *quarter* model (symmetry planes ``x1 = 0`` and
``x3 = 0``, the whole thickness: it can bend; grad-div 10 as in :mod:`validation.studies.buckling`)
is ramped in ``D0`` on its fundamental (symmetric) branch; the lowest physical eigenvalue of
its own class (:func:`skfem_dielectric.studies.postbuckling.critical_mode`) locates the buckling
load ``D0_b`` to ``1e-4``; at the first scanned state past it Newton is started from the
fundamental state plus the critical mode (branch switching on the perfect plate) and the
buckled branch is followed forward to ``D0_max`` and back towards ``D0_b``.  The
mid-plane deflection against ``D0`` gives ``D0_b`` a second time, from the nonlinear
branch alone (pitchfork fit ``D0 = D0_b + b w^2 + c w^4``), and ``lam1`` at the plate
centre is compared with the fundamental branch and with the homogeneous curve (Eq.
(DEuniax) of Conroy Broderick, Righi, Destrade and Ogden, "Stability analysis of
charge-controlled soft dielectric plates", Int. J. Eng. Sci., 2020).

Files (all in ``out``): ``post-buckling.csv`` (one row per state of both branches),
``post-buckling-summary.csv`` (one row per alpha x mesh, written as each is done, after
its states; a rerun skips the pairs present), ``.post-buckling/<alpha>_<mesh>.npz`` (the mid-plane deflection
of the last buckled state) and ``post-buckling.png``.
"""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import analytic as an
import skfem_dielectric as fe
from skfem_dielectric.models.plate.symmetry_classes import class_stability
from skfem_dielectric.solvers.critical import critical_load
from skfem_dielectric.studies.postbuckling import (critical_mode, midplane_deflection,
                                           midplane_nodes, post_buckled_branch)

from ..options import load_targets
from ..data.spec import TableSpec
from ..store import StudyStore, read_npz, write_npz_atomic
from ..fe.model import BUCKLING_GRAD_DIV
from ..figures import save_figure

__all__ = ["COLUMNS", "SUMMARY_COLUMNS", "QUICK", "FULL", "WINDOW", "MODELS", "TABLE", "STATES",
           "charge_targets", "study_window", "run_one", "run_post_buckling",
           "post_buckling_figure"]

COLUMNS = ("alpha", "mesh", "model", "branch", "D0", "deflection", "lam1", "lam1_fundamental",
           "lam1_homogeneous", "min_P33", "eigenvalue", "n_negative_own", "n_negative")
SUMMARY_COLUMNS = ("alpha", "s", "mesh", "model", "ndofs", "D0_b", "D0_b_pitchfork", "b", "switch_D0",
                   "switch_amplitude", "D0_last", "deflection_last", "lam1_last",
                   "lam1_fundamental_last", "lam1_homogeneous_last", "max_n_negative_own",
                   "min_eigenvalue_buckled",
                   "reason", "seconds")
#: models that can bend: name -> symmetry planes (axes); ``"x1"`` keeps the whole width,
#: for critical modes antisymmetric in ``x3`` as well
MODELS = {"quarter": (1, 3), "x1": (1,)}
#: backward targets: D0_b + f (D0_switch - D0_b)
BACK_FRACTIONS = (0.5, 0.25, 0.12, 0.06)
QUICK = {"alphas": (0.05,), "meshes": ((10, 2, 5),), "D0_step": 0.05, "D0_max": 1.0}
FULL = {"alphas": (0.05, 1.0), "meshes": ((10, 2, 5), (14, 2, 7), (20, 2, 10)),
        "D0_step": 0.05, "D0_max": None}
#: per weight: where the spectrum scan starts (below 0.9 of the buckling load of the
#: table in docs/validation.md) and where the branch ends by default
WINDOW = {0.05: (0.65, 1.5), 0.3: (1.3, 2.0), 0.7: (2.2, 3.0), 1.0: (2.55, 3.3)}


#: the files of the study (:class:`~validation.store.StudyStore`): the summary last
TABLE = TableSpec.plain("post-buckling-summary.csv", tuple(SUMMARY_COLUMNS), ("alpha", "mesh", "model"))
STATES = TableSpec.plain("post-buckling.csv", tuple(COLUMNS), ("alpha", "mesh", "model"))


def charge_targets(D0_step: float, D0_max: float, D0_from: float = 0.0) -> np.ndarray:
    """The fundamental ramp's targets: steps of 0.25 below ``D0_from``, then ``D0_step``
    up to ``D0_max`` (checked: ``ValueError`` naming ``--D0-step`` for more than
    :data:`~validation.options.MAX_TARGETS`)."""
    D0 = np.concatenate([load_targets("--D0-step", 0.25, D0_from - 2e-9, 0.25),
                         load_targets("--D0-step", D0_from, D0_max, D0_step)])
    return D0[D0 > 0]


def study_window(alpha: float, D0_step: float, D0_max: float | None) -> tuple[float, float]:
    """Where the spectrum scan of ``alpha`` starts and where its branch ends
    (:data:`WINDOW`; ``D0_max`` overrides the end)."""
    start, top = WINDOW.get(float(alpha), (D0_step, 1.5))
    top = top if D0_max is None else D0_max
    return min(start, top), top


def _mesh_name(el) -> str:
    return "x".join(str(int(n)) for n in el)


def _fundamental(alpha, elements, D0, solver, model):
    # each Newton solve starts from the last converged state (no secant): the last
    # correction is then tiny and the fundamental branch stays symmetric through the
    # thickness to round-off past the buckling load, where a secant start leaves a
    # deflection at the Newton tolerance in the direction that has just gone unstable;
    # double-precision factors for the same reason (the chord corrections of single-
    # precision ones bend the fundamental state by 2e-8 of the thickness)
    res = fe.keplinger_plate(alpha, D0=D0, elements=tuple(elements), symmetry=MODELS[model],
                             options=fe.PlateOptions(grad_div=BUCKLING_GRAD_DIV),
                             linear_solver=solver,
                             settings=replace(fe.gallery.KEPLINGER_SETTINGS, max_cutbacks=6,
                                              max_iter=25, predictor="none",
                                              factor_precision="double"))
    newton = dict(linear_solver=solver,
                  settings=fe.RampSettings(atol=0.0, rtol=1e-9, max_cutbacks=6, max_iter=25))
    return res, newton


def _locate(pb, states, method, newton):
    """First own-class crossing of the lowest physical eigenvalue along the states:
    ``(D0_b, index of the first state past it, eigenvalues)``; ``nan, None`` if none."""
    eig = []
    for i, st in enumerate(states):
        lab = critical_mode(pb, st.x, st.load, method=method)
        eig.append(lab.eigenvalue if lab is not None else np.nan)
        if i and eig[-1] < 0 < eig[-2]:
            a = states[i - 1]
            crit = critical_load(pb, a.x, a.load, st.load,
                                 lambda x, ld: critical_mode(pb, x, ld,
                                                             method=method).eigenvalue,
                                 tol=1e-4, **newton)
            return float(crit.load[1]), i, eig
    return float("nan"), None, eig


def _counts(pb, st, method) -> dict:
    """Negative eigenvalues of the own class and of all classes of a fundamental state
    (only where the spectrum is scanned, ``D0 >= D0_from``)."""
    cs = class_stability(pb, st.x, st.load, k=0, method=method)
    return {"n_negative_own": cs.results[0].n_negative, "n_negative": cs.n_negative}


def run_one(alpha: float, elements, *, D0_step: float, D0_max: float,
            D0_from: float = 0.0, solver: str = "auto", model: str = "quarter",
            shapes_dir: Path | None = None) -> tuple[dict, list[dict]]:
    """One alpha x mesh of ``model`` (:data:`MODELS`): fundamental ramp (steps of 0.25 up to ``D0_from``, then
    ``D0_step``; the spectrum from ``D0_from`` on), ``D0_b``, branch switch, the buckled
    branch forward to ``D0_max`` and back.  Returns the summary row and the state rows."""
    t0 = time.time()
    D0 = charge_targets(D0_step, D0_max, D0_from)
    if model not in MODELS:
        raise ValueError(f"model must be one of {tuple(MODELS)}, got {model!r}")
    res, newton = _fundamental(alpha, elements, D0, solver, model)
    pb = res.problem
    mesh = _mesh_name(elements)
    method = "pardiso" if solver == "pardiso" else "auto"
    charge = [st for st in res.steps
              if np.asarray(st.load)[1] >= max(D0_from, 1e-12) - 1e-9]
    s = float(np.asarray(charge[0].load)[0]) if charge else float("nan")
    material = an.NeoHookean()

    def homogeneous(d):
        return float(an.uniaxial_lam1(d, s, material))

    d_b, i_sw, eig = _locate(pb, charge, method, newton)
    rows = [{"alpha": alpha, "mesh": mesh, "model": model, "branch": "fundamental",
             "D0": float(st.load[1]),
             "deflection": midplane_deflection(pb, st.x, st.load),
             "lam1": st.quantities["lam1"], "lam1_fundamental": st.quantities["lam1"],
             "lam1_homogeneous": homogeneous(float(st.load[1])),
             "min_P33": st.quantities["min_P33"],
             "eigenvalue": eig[k] if k < len(eig) else np.nan,
             **_counts(pb, st, method)} for k, st in enumerate(charge)]
    summary = {"alpha": alpha, "s": s, "mesh": mesh, "model": model, "ndofs": pb.ndofs, "D0_b": d_b,
               "D0_b_pitchfork": np.nan, "b": np.nan, "switch_D0": np.nan,
               "switch_amplitude": np.nan, "D0_last": np.nan, "deflection_last": np.nan,
               "lam1_last": np.nan, "lam1_fundamental_last": np.nan,
               "lam1_homogeneous_last": np.nan, "max_n_negative_own": "",
               "min_eigenvalue_buckled": np.nan, "reason": ""}
    if i_sw is None:
        summary["reason"] = ("no physical negative eigenvalue of the own class up to "
                             f"D0 = {charge[-1].load[1] if charge else 0:g}"
                             + ("" if res.converged else f"; {res.reason}"))
        summary["seconds"] = round(time.time() - t0, 1)
        return summary, rows
    sw = charge[i_sw]
    d_sw = float(sw.load[1])
    back = [d_b + f * (d_sw - d_b) for f in BACK_FRACTIONS]
    fwd = [float(st.load[1]) for st in charge[i_sw + 1:]]
    br = post_buckled_branch(pb, sw.x, sw.load, fwd, back, method=method,
                             linear_solver=solver)
    summary.update(switch_D0=d_sw, switch_amplitude=br.switch.amplitude)
    if not br.switch.found:
        summary["reason"] = br.switch.reason
        summary["seconds"] = round(time.time() - t0, 1)
        return summary, rows
    fund = {round(float(st.load[1]), 10): st.quantities["lam1"] for st in charge}
    buckled = []
    for d, w, st in br.states():
        q = st.quantities if st is not None else None
        lab = (critical_mode(pb, st.x, st.load, method=method) if st is not None else None)
        buckled.append({"alpha": alpha, "mesh": mesh, "model": model, "branch": "buckled",
                        "D0": d,
                        "deflection": w,
                        "lam1": q["lam1"] if q else pb.postprocess(br.switch.x,
                                                                   sw.load)["lam1"],
                        "lam1_fundamental": fund.get(round(d, 10), np.nan),
                        "lam1_homogeneous": homogeneous(d),
                        "min_P33": q["min_P33"] if q else np.nan,
                        "eigenvalue": lab.eigenvalue if lab is not None else np.nan,
                        "n_negative_own": q["n_negative_own"] if q else "",
                        "n_negative": q["n_negative"] if q else ""})
    rows += buckled
    try:
        summary["D0_b_pitchfork"], summary["b"] = br.pitchfork(4)
    except ValueError as exc:
        summary["reason"] = str(exc)
    else:
        if summary["b"] <= 0 or abs(summary["D0_b_pitchfork"] - d_b) > 0.25 * (d_sw - d_b):
            summary["reason"] = (f"the branch reached does not bifurcate at D0_b = {d_b:.4f}: "
                                 f"its pitchfork fit gives {summary['D0_b_pitchfork']:.4f}, "
                                 f"b = {summary['b']:.3g} (another buckled branch, or a "
                                 f"subcritical bifurcation)")
    last = buckled[-1]
    summary.update(D0_last=last["D0"], deflection_last=last["deflection"],
                   lam1_last=last["lam1"], lam1_fundamental_last=last["lam1_fundamental"],
                   lam1_homogeneous_last=last["lam1_homogeneous"],
                   max_n_negative_own=max((r["n_negative_own"] for r in buckled
                                           if r["n_negative_own"] != ""), default=""),
                   min_eigenvalue_buckled=float(np.nanmin([r["eigenvalue"] for r in buckled])))
    reasons = [r.reason for r in (br.forward, br.backward) if r is not None and r.reason]
    if reasons:
        summary["reason"] = "; ".join([summary["reason"]] * bool(summary["reason"]) + reasons)
    if shapes_dir is not None:
        st = [t[2] for t in br.states() if t[2] is not None][-1]
        shapes_dir.mkdir(parents=True, exist_ok=True)
        X = pb.b2.doflocs
        mid = midplane_nodes(pb)
        u2 = pb.full(st.x, st.load)[1:pb.n_u:3][mid]
        write_npz_atomic(shapes_dir / f"{alpha:g}_{model}_{mesh}.npz", X1=X[0][mid], X3=X[2][mid], u2=u2,
                 D0=float(st.load[1]))
    summary["seconds"] = round(time.time() - t0, 1)
    return summary, rows


def run_post_buckling(out: Path, *, alphas, meshes, D0_step: float, D0_max: float | None,
                      solver: str = "auto", model: str = "quarter",
                      progress=None, note=None) -> list[dict]:
    """The study: every alpha x mesh not yet in ``out/post-buckling-summary.csv``, then
    the figure.  Each weight's spectrum scan starts at ``WINDOW[alpha][0]`` (``D0_step``
    for a weight not in it); ``D0_max=None`` ends it at ``WINDOW[alpha][1]`` (1.5).

    The study holds its lock and store (:class:`~validation.store.StudyStore`): one
    alpha x mesh x model is done when its summary row is written, after its states; a
    folder of another ``D0_step``, ``D0_max`` or ``solver`` is discarded and recomputed
    (``note(message)`` says so).  Repeated alphas and meshes are computed once."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    alphas = list(dict.fromkeys(float(a) for a in alphas))
    meshes = list(dict.fromkeys(tuple(int(n) for n in el) for el in meshes))
    for alpha in alphas:
        charge_targets(D0_step, *study_window(alpha, D0_step, D0_max)[::-1])
    footer = (f"skfem-dielectric post-buckling: {model} model, meshes "
              f"{', '.join(_mesh_name(el) for el in meshes)}, D0 step {D0_step:g}, "
              f"linear solver {solver}")
    settings = {"D0_step": float(D0_step),
                "D0_max": None if D0_max is None else float(D0_max), "solver": solver}
    plan = [(a, _mesh_name(el), model) for a in alphas for el in meshes]
    with StudyStore(out, "post-buckling", settings, TABLE, (STATES,), plan=plan,
                    derived=("post-buckling.png", "post-buckling.pdf", ".post-buckling"),
                    note=note) as store:
        for alpha in alphas:
            start, top = study_window(alpha, D0_step, D0_max)
            for el in meshes:
                if store.done((alpha, _mesh_name(el), model)):
                    continue
                summary, rows = run_one(alpha, el, D0_step=D0_step, D0_max=top,
                                        D0_from=start, solver=solver, model=model,
                                        shapes_dir=out / ".post-buckling")
                store.commit(summary, {STATES.file: rows})
                # the figure follows the table: a long study shows every finished row
                post_buckling_figure(store.rows(), store.rows(STATES.file),
                                     out / ".post-buckling", out / "post-buckling.png",
                                     footer=footer)
                if progress is not None:
                    progress(summary)
        summary = store.rows()
        if summary:
            post_buckling_figure(summary, store.rows(STATES.file), out / ".post-buckling",
                                 out / "post-buckling.png", footer=footer)
    return summary


def _unfold(z, model):
    """Mid-plane points and ``u2`` of a saved shape over the whole plate (mirror images
    through the model's symmetry planes; the state is symmetric in them)."""
    X1, X3, u2 = z["X1"], z["X3"], z["u2"]
    for ax in MODELS[model]:
        if ax == 1:
            X1, X3, u2 = np.concatenate([X1, -X1]), np.concatenate([X3, X3]), np.tile(u2, 2)
        else:
            X1, X3, u2 = np.concatenate([X1, X1]), np.concatenate([X3, -X3]), np.tile(u2, 2)
    return X1, X3, u2


def post_buckling_figure(summary, rows, shapes_dir: Path, path: Path,
                         footer: str = "") -> Path:
    """One row of panels per alpha: mid-plane deflection vs ``D0`` per model and mesh,
    ``lam1`` at the centre minus the homogeneous closed form (fundamental and buckled
    branches), the buckled shape of the largest model; written to ``path`` (PNG) and
    beside it as PDF, with ``footer`` under the panels."""
    alphas = sorted({r["alpha"] for r in summary})
    fig, axes = plt.subplots(len(alphas), 3, figsize=(14, 3.6 * len(alphas)),
                             squeeze=False, constrained_layout=True)
    for ax3, alpha in zip(axes, alphas):
        mine = sorted((r for r in summary if r["alpha"] == alpha),
                      key=lambda r: (r["model"], r["ndofs"]))
        for r in mine:
            key = (r["mesh"], r["model"])
            b = [q for q in rows if q["alpha"] == alpha and (q["mesh"], q["model"]) == key
                 and q["branch"] == "buckled"]
            f = [q for q in rows if q["alpha"] == alpha and (q["mesh"], q["model"]) == key
                 and q["branch"] == "fundamental"]
            name = f"{r['model']} {r['mesh']}"
            line, = ax3[0].plot([q["D0"] for q in b], [q["deflection"] for q in b], "o-",
                                ms=3, label=name)
            if np.isfinite(r["D0_b"]):
                ax3[0].axvline(r["D0_b"], ls=":", lw=0.8, color=line.get_color())
            ax3[1].plot([q["D0"] for q in b], [q["lam1"] - q["lam1_homogeneous"] for q in b],
                        "o-", ms=3, color=line.get_color(), label=f"buckled {name}")
            ax3[1].plot([q["D0"] for q in f], [q["lam1"] - q["lam1_homogeneous"] for q in f],
                        "s-", ms=3, mfc="none", lw=0.6, color=line.get_color(),
                        label=f"fundamental {name}")
        ax3[0].set(xlabel="D0", ylabel="mid-plane deflection max |u2| (mm)",
                   title=f"alpha = {alpha:g}: buckled branch (dotted: D0_b)")
        ax3[0].legend(fontsize=7)
        ax3[1].axhline(0, color="k", lw=0.6)
        ax3[1].set(xlabel="D0", ylabel="lam1 (FE, centre) - lam1 (homogeneous)",
                   title=f"alpha = {alpha:g}: centre stretch against Eq. (DEuniax)")
        ax3[1].legend(fontsize=6)
        big = max(mine, key=lambda r: r["ndofs"])
        npz = shapes_dir / f"{alpha:g}_{big['model']}_{big['mesh']}.npz"
        if npz.exists():
            z = read_npz(npz)
            X1, X3, u2 = _unfold(z, big["model"])
            lim = max(float(np.abs(u2).max()), 1e-300)
            t = ax3[2].tricontourf(X1, X3, u2, 21, cmap="RdBu_r", vmin=-lim, vmax=lim)
            fig.colorbar(t, ax=ax3[2], shrink=0.8, label="u2 (mm)")
            ax3[2].set(aspect="equal", xlabel="X1 (mm)", ylabel="X3 (mm)",
                       title=f"{big['model']} {big['mesh']}: mid-plane u2, "
                             f"D0 = {float(z['D0']):.3g}")
    if footer:
        fig.text(0.5, 0.0, footer, ha="center", va="top", fontsize=7, color="0.3")
    path = Path(path)
    save_figure(fig, path.parent, path.stem, dpi=110, bbox_inches="tight")
    return path

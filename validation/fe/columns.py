"""What a converged FE state adds to its row: the stability columns, the whole plate's
spectrum, the verdict on the whole plate, the centre line and the stretch maps.

* :func:`stability_columns` -- negative-eigenvalue count, its physical part and the
  lowest eigenvalue of a converged state (:func:`stability_monitor`: read from the ramp's
  own factorisations with PARDISO);
* :func:`plate_buckling_columns`, :func:`whole_plate_verdict` -- the whole plate's
  spectrum (of the grad-div form's state in a run analysed for buckling) and the
  ``stable`` column;
* :func:`membrane_stretch_maps` -- the membrane's deformation gradient at points;
* :func:`step_record` -- the :class:`~validation.records.StepRecord` of a converged target.
"""

from __future__ import annotations

import numpy as np

import skfem_dielectric as fe
import skfem_dielectric.models.plate.modes as fe_modes

from ..records import StepRecord
from ..specs import RunSpec
from .model import H, L1, is_membrane

__all__ = ["stability_columns", "stability_monitor", "plate_buckling_columns", "whole_plate_verdict", "membrane_stretch_maps", "step_record"]

#: grad-div stabilisation (units of mu) of the tangent of the homogeneous plates' stability
#: columns: it removes the spurious mesh-scale surface modes of Q2/Q1 and, J = 1 holding
#: exactly there, is the Hessian of the same state (docs/stability.md)
STABILITY_GRAD_DIV = 10.0
def stability_columns(spec: RunSpec, problem, x, load, analysis=None) -> dict:
    """Stability of a converged state: ``n_negative``, ``n_unstable``, ``lowest_eig`` and
    the verdict ``stable``.

    ``n_negative`` counts the negative eigenvalues of the reduced stiffness
    (:func:`skfem_dielectric.stability.tangent_stability`; of the model's own tangent, for the
    homogeneous equi-biaxial plate of the grad-div stabilised one,
    :data:`STABILITY_GRAD_DIV`, which has the same state), ``n_unstable`` those whose mode
    is classified physical (:func:`skfem_dielectric.models.plate.modes.classify_mode`: not at a
    clamp/free-edge corner, not mesh-scale), ``lowest_eig`` the lowest eigenvalue
    (Euclidean metric of the displacement unknowns); ``stable`` is ``n_unstable == 0``.
    All ``None`` for the Maxwell-traction variants (non-symmetric tangent).

    Parameters
    ----------
    spec : RunSpec
    problem
        The problem of :func:`build_problem`.
    x, load
        Converged reduced state and its load.
    analysis : StabilityResult, optional
        The analysis of this state's tangent by :func:`stability_monitor`'s monitor (the
        same numbers: the count exactly, the eigenvalues to its tolerance); computed here
        when not given.

    Returns
    -------
    dict
    """
    if not problem.symmetric:
        return {"stable": None, "n_negative": None, "n_unstable": None}
    if analysis is not None:
        st = analysis
    else:
        if not is_membrane(spec) and spec.geometry == "equibiaxial":
            K = problem.stabilised_tangent(x, load, STABILITY_GRAD_DIV)
        else:
            K = problem.assemble(x, load)[0]
        # lowest_eig to 1e-6 (a column of the table; the count is exact)
        st = fe.stability.tangent_stability(problem, K, k=1, method="auto", all_negative=True,
                                            tol=1e-6)
    artefacts = 0
    if not is_membrane(spec) and spec.geometry == "uniaxial" and st.n_negative:
        xf = problem.full(x, load)
        artefacts = sum(fe_modes.classify_mode(problem, xf, problem.red.expand(
            st.modes[:, j]))["kind"] != "physical" for j in range(st.n_negative))
    n_unstable = st.n_negative - artefacts
    return {"stable": bool(n_unstable == 0 and st.n_zero == 0), "n_negative": st.n_negative,
            "n_unstable": n_unstable, "lowest_eig": st.lowest_eig}


def stability_monitor(spec: RunSpec, problem, linear_solver="superlu"):
    """The :class:`skfem_dielectric.StabilityMonitor` that gives the ramp of ``spec`` its
    stability columns from the ramp's own factorisations, or ``None``.

    With PARDISO, for the clamped 3D plate (its columns analyse the ramp's own tangent; the
    homogeneous 3D plates' analyse the grad-div stabilised one, and the small membranes
    gain little): the ramp factorises the tangent of every converged target, the count is
    read from those factors and the lowest modes (one, and every negative one) come from
    back-substitutions on them or from a spectrum slicing that starts near the previous
    state's lowest eigenvalue; the next load step starts with a chord step on the same
    factors.  That changes the Newton path within its tolerance, and a resumed ramp
    (without those factors at its start) repeats the uninterrupted one only within it,
    which PARDISO's threads allow anyway; with SuperLU the ramp and the columns stay as
    they are, and a resumed run repeats the uninterrupted one bit for bit.  On the full
    alpha = 1.5 run (40 x 1 x 20, 19 rows) the columns are identical to 12 digits and the
    dots within 3e-10 (what it saves: docs/performance.md, "Measurements behind the code").

    Parameters
    ----------
    spec : RunSpec
    problem
        The problem of :func:`build_problem`.
    linear_solver : str
        The ramp's solver name.

    Returns
    -------
    StabilityMonitor or None
    """
    if linear_solver != "pardiso" or not problem.symmetric or is_membrane(spec) \
            or spec.geometry != "uniaxial":
        return None
    return fe.StabilityMonitor(k=1, tol=1e-6, all_negative=True)


def membrane_stretch_maps(problem, x) -> dict:
    """``lam1 = F11``, ``lam3 = F33`` of the membrane at its mesh vertices.

    Parameters
    ----------
    problem : MembranePlate
    x : ndarray
        Reduced state.

    Returns
    -------
    dict
        ``kind = 1``, the reference ``x1``, ``x3`` in metres, ``lam1``, ``lam3`` and
        ``P33 = nan``: rows of the fields table.
    """
    pts = problem.mesh.p
    # nudge boundary points inside so that the element finder locates them
    c = pts.mean(axis=1, keepdims=True)
    inner = pts + 1e-9 * (c - pts)
    G, dofs = fe.fem.point_gradients(problem.basis, inner)
    u = problem.T @ x
    F = np.einsum("pn,pijn->ijn", u[dofs], G) + np.eye(2)[:, :, None]
    return {"kind": np.ones(pts.shape[1]), "x1": pts[0] * 1e-3, "x3": pts[1] * 1e-3,
            "lam1": F[0, 0], "lam3": F[1, 1], "P33": np.full(pts.shape[1], np.nan)}


def _plate_stretch_maps(problem, x, load) -> dict:
    """``lam1 = |F e1|``, ``lam3 = |F e3|`` on a grid of the 3D plate's mid-plane."""
    g1, _, g3 = problem.plate.grids
    x1 = np.linspace(g1[0], g1[-1], 4 * (len(g1) - 1) + 1)
    x3 = np.linspace(g3[0], g3[-1], 4 * (len(g3) - 1) + 1)
    X1, X3 = (a.ravel() for a in np.meshgrid(x1, x3, indexing="ij"))
    tiny = 1e-9 * (g1[-1] - g1[0])
    pts = np.vstack([np.clip(X1, g1[0] + tiny, g1[-1] - tiny), np.full(X1.size, tiny),
                     np.clip(X3, g3[0] + tiny, g3[-1] - tiny)])
    F = problem.evaluate(x, load, pts)["F"]
    lam = np.linalg.norm(F, axis=0)
    return {"kind": np.ones(X1.size), "x1": X1 * 1e-3, "x3": X3 * 1e-3, "lam1": lam[0],
            "lam3": lam[2], "P33": np.full(X1.size, np.nan)}


def _centre_line(spec: RunSpec, problem, step) -> dict:
    """Centre-line profile in millimetres: ``x1``, ``P33/mu``, ``lam1``, ``lam3``."""
    if is_membrane(spec):
        return problem.centre_line(step.x, step.load)
    return step.quantities["centre_line"]


def _interior_min(x1_mm, P33) -> float:
    """Minimum of ``P33`` on the centre line at least ``2 H`` away from the clamps.

    The 3D clamp (``u2 = u3 = 0``) is a stress singularity whose boundary layer
    decays over about one thickness ``H``; at the clamp itself ``P33/mu`` reaches
    about 5 and dips next to it on fine meshes. The breakdown is judged outside
    this layer (``|x1| <= L1/2 - 2H``), where the paper's "P33 near the clamps"
    is resolved on every mesh.
    """
    x1 = np.abs(np.asarray(x1_mm, dtype=float))
    keep = x1 <= L1 / 2 - 2 * H + 1e-9
    return float(np.min(np.asarray(P33)[keep])) if keep.any() else float("nan")


def plate_buckling_columns(spec: RunSpec, scan, x, load) -> dict:
    """The whole plate's columns of a state of a run with ``spec.buckling``.

    ``scan`` is the run's :class:`~skfem_dielectric.models.plate.scan.PlateScan` of its
    grad-div form (:func:`~validation.fe.model.buckling_problem`) and ``x`` that form's own
    state at ``load``: the spectrum is of that state's own tangent, the Hessian of the
    energy whose equilibrium it is.  The scan counts the negative eigenvalues of every
    symmetry class of the eighth model at every state and classifies the modes that
    crossed zero since the previous state (where a class's count changed).  Columns:
    ``n_negative_plate`` (the whole plate's count), ``physical_eig`` and
    ``physical_class`` (the lowest mode classified physical *at this state* -- one that
    crossed zero here; empty where none did), ``stable`` (no negative mode labelled
    physical on the whole plate, labels carried along the path, and a non-singular
    tangent; the eighth model's own tangent is one of the classes).  Empty for other
    runs, and where the spectrum cannot be computed (a ``ValueError``, e.g. a class
    tangent too large to be counted without PARDISO).

    Parameters
    ----------
    spec : RunSpec
    scan : PlateScan
        The run's scan, its previous state the run's previous row.
    x, load
        The grad-div form's converged reduced state and the load.

    Returns
    -------
    dict
    """
    if not (spec.buckling and spec.geometry == "uniaxial" and not is_membrane(spec)):
        return {}
    try:
        row = scan.analyse(x, load)
    except ValueError:
        return {}
    phys = [m for m in row.labels if m.kind == "physical"]
    return {"n_negative_plate": row.n_negative,
            "physical_eig": phys[0].eigenvalue if phys else float("nan"),
            "physical_class": phys[0].symmetry if phys else "", "stable": row.stable}


def whole_plate_verdict(spec: RunSpec, problem, rec: StepRecord) -> bool | None:
    """The ``stable`` column: the verdict on the whole plate, never ``True`` on a model
    that cannot show the unstable mode.

    ``rec.stable`` arrives as the verdict of the model's own tangent
    (:func:`stability_columns`).  A symmetry-reduced 3D plate sees only the increments
    that keep its symmetry planes, a membrane no out-of-plane mode at all, so their
    ``True`` says nothing about the plate: the column is

    * ``False`` when a physical negative eigenvalue was found, on the model's own tangent
      (``n_unstable > 0``) or in the whole plate's spectrum over every symmetry class
      (``physical_eig < 0``);
    * ``True`` only when no physical negative eigenvalue was found by an analysis that can
      show every mode: the whole plate's spectrum (runs with ``n_negative_plate``) or the
      model's own tangent when the 3D model has no symmetry plane;
    * ``None`` (empty: unknown) otherwise, and for the non-symmetric Maxwell variants.

    Parameters
    ----------
    spec : RunSpec
    problem
        The problem of :func:`build_problem`.
    rec : StepRecord
        The state's record with the model's own verdict in ``stable`` and, for runs that
        analyse the whole plate, ``n_negative_plate`` and ``physical_eig``.

    Returns
    -------
    bool or None
    """
    own = rec.stable
    if own is None or own is False:
        return own
    if rec.n_negative_plate is not None:
        return not bool(np.isfinite(rec.physical_eig) and rec.physical_eig < 0)
    if not is_membrane(spec) and not tuple(problem.plate.symmetry):
        return own
    return None


def step_record(spec: RunSpec, problem, step, analysis=None) -> StepRecord:
    """The :class:`StepRecord` of a converged target of ``problem``, with the centre line if
    recorded; the whole plate's columns of a run analysed for buckling are not in it (they
    are of the grad-div form's state, :func:`plate_buckling_columns`, added by the
    runner)."""
    q = step.quantities
    rec = StepRecord(D0=float(np.asarray(step.load)[1]), lam1=q["lam1"], lam3=q["lam3"],
                     min_P33=q["min_P33"], min_P33_clamp=q.get("min_P33_clamp", np.nan),
                     iterations=step.iterations,
                     **stability_columns(spec, problem, step.x, step.load, analysis))
    rec.stable = whole_plate_verdict(spec, problem, rec)
    c = _centre_line(spec, problem, step)
    rec.min_P33_interior = _interior_min(c["x1"], c["P33"])
    if spec.record_fields:
        n = len(c["x1"])
        rec.fields = {"kind": np.zeros(n), "x1": np.asarray(c["x1"]) * 1e-3, "x3": np.zeros(n),
                      "P33": c["P33"], "lam1": c["lam1"], "lam3": c["lam3"]}
        if spec.record_maps and rec.D0 == 0.0:
            # stretch maps of the pre-loaded plate (kind 1) after the centre line (kind 0)
            maps = (membrane_stretch_maps(problem, step.x) if is_membrane(spec)
                    else _plate_stretch_maps(problem, step.x, step.load))
            rec.fields = {k: np.r_[rec.fields[k], maps[k]] for k in rec.fields}
    return rec

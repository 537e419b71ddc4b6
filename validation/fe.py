"""The harness's FE runner: a :class:`~validation.specs.RunSpec` solved with :mod:`skfem_dielectric`.

This is the only module of :mod:`validation` that imports :mod:`skfem_dielectric`. It
touches the FE package in a few small functions, one per job:

* :func:`build_problem` -- the FE problem of a spec (3D plate, 3D Maxwell-traction
  plate or 2D membrane);
* :func:`ramp_targets` and :func:`ramp_settings` -- the ramp's loads ``(s, D0)`` and
  its Newton tolerances, cut-back limit and linear solver;
* :func:`stability_columns` -- negative-eigenvalue count, its physical part and the
  lowest eigenvalue of a converged state (:func:`stability_monitor`: read from the ramp's
  own factorisations with PARDISO);
* :func:`membrane_stretch_maps` -- the membrane's deformation gradient at points;
* :func:`keplinger_s` -- the Keplinger plate's dead load.

:func:`run_fe` is the default runner of :func:`validation.sweep.run_case`: it ramps
the load (pre-load first, then the charge targets) with :func:`skfem_dielectric.solvers.ramp.ramp`
and reports each converged target as a :class:`~validation.records.StepRecord`. The
saved state is the ramp's reduced solution vector and its load, so a resumed ramp
continues bit for bit.

Geometry in SI-like units of millimetres (the Keplinger plate 100 x 50 x 1 mm)
with ``mu = eps = 1``: every reported quantity is dimensionless.
"""

from __future__ import annotations

import csv
import time
import warnings
from pathlib import Path

import meshio
import numpy as np

import skfem_dielectric as fe
import skfem_dielectric.models.plate.modes as fe_modes

from .records import RunOutcome, StepRecord
from .specs import GENT_JM, KEPLINGER, RunSpec

__all__ = [
    "keplinger_s",
    "build_problem",
    "ramp_targets",
    "ramp_settings",
    "stability_columns",
    "stability_monitor",
    "plate_buckling_columns",
    "membrane_stretch_maps",
    "pardiso_installed",
    "run_fe",
    "simulate",
    "bench",
]

L1, L3, H = 100.0, 50.0, 1.0     # mm
MEMBRANE_VARIANTS = ("membrane", "membrane-maxwell")
#: 3D pre-load sub-steps, as the drivers equibiaxial_plate (4) and keplinger_plate (3).
PRELOAD_STEPS = {"equibiaxial": 4, "uniaxial": 3}
#: 3D Newton tolerance relative to the external load: as equibiaxial_plate (1e-11) and
#: keplinger_plate (1e-9); the membrane keeps the tolerance of the plain ramp.
RTOL = {"equibiaxial": 1e-11, "uniaxial": 1e-9}
MEMBRANE_TOL = {"atol": 1e-10, "rtol": 1e-10}
#: Cut-backs per target and Newton iterations per attempt, every variant.
MAX_CUTBACKS, MAX_ITER = 6, 25
#: chord factor of the ramps' Newton solves (:func:`skfem_dielectric.solvers.newton.newton`): a
#: factorisation is reused while the residual contracts at least tenfold per step.  No
#: secant predictor: it depends on the state before the last one, so a resumed ramp would
#: not repeat the uninterrupted one bit for bit (and past the breakdown it can jump to
#: another branch of the clamped plate).  What it saves: docs/performance.md,
#: "Measurements behind the code"; the FE dots move within the Newton tolerance.
CHORD = 0.1


class _Stop(Exception):
    """Raised inside ``on_step`` to end a ramp at the breakdown."""


def keplinger_s(alpha: float) -> float:
    """Dimensionless dead load ``s = alpha m g/(mu A)`` of the Keplinger plate.

    :func:`skfem_dielectric.keplinger_s` with ``g = KEPLINGER["g"] = 9.81 m/s^2``
    (paper caption of Fig. uni-axial-ideal).

    Parameters
    ----------
    alpha : float
        Fraction of the 150 g weight, ``alpha >= 0``.

    Returns
    -------
    float

    Examples
    --------
    >>> round(keplinger_s(1.0), 5)
    2.99296
    """
    return fe.keplinger_s(alpha, g=KEPLINGER["g"])


def _is_membrane(spec: RunSpec) -> bool:
    return spec.variant in MEMBRANE_VARIANTS


# --------------------------------------------------------------------------- the FE model
def build_problem(spec: RunSpec):
    """The FE problem of ``spec``, a ramp problem of :mod:`skfem_dielectric`.

    The 3D plates are eighth models: of a 4 x 1 x 4 plate with one element per
    direction by default for the homogeneous equi-biaxial state (as
    :func:`skfem_dielectric.equibiaxial_plate`), of the 100 x 1 x 50 mm Keplinger plate
    (as :func:`skfem_dielectric.keplinger_plate`). The membrane is the quarter of the
    100 x 50 mm plate of thickness 1 mm.

    Parameters
    ----------
    spec : RunSpec

    Returns
    -------
    PlateProblem or MembranePlate
        For ``variant="maxwell"`` the plate with ``coupling="maxwell"`` and the field of
        the potential solved on the deformed body.
    """
    m = spec.mesh_dict
    if _is_membrane(spec):
        coupling = "maxwell" if spec.variant == "membrane-maxwell" else "full"
        # the geometry names are the models' loadings (the Keplinger plate is "uniaxial")
        return fe.MembranePlate(fe.membrane_mesh(L1, H, L3, m.get("n1", 1), m.get("n3", 1)),
                                fe.make_material(spec.model, Jm=GENT_JM),
                                loading=spec.geometry, coupling=coupling)
    el = (m.get("n1", 1), m.get("n2", 1), m.get("n3", 1))
    # the variant that discretises the fully coupled equations (docs/fe_variants.md)
    coupling = {"coupling": "maxwell", "field": "electrostatic"} \
        if spec.variant == "maxwell" else {}
    if spec.geometry == "equibiaxial":
        return fe.equibiaxial_problem(model=spec.model, Jm=GENT_JM, elements=el, **coupling)
    if spec.geometry == "uniaxial":
        # the run analysed for buckling is the grad-div form of the buckling study
        # (docs/validation.md): its tangent is the Hessian of its own state, and Newton
        # passes the clamp/free-edge corner
        return fe.keplinger_problem(model=spec.model, Jm=GENT_JM, size=(L1, H, L3),
                                    elements=el, grad_div=BUCKLING_GRAD_DIV if spec.buckling
                                    else 0.0, **coupling)
    raise ValueError(f"the 3D plate has no geometry {spec.geometry!r}")


def ramp_targets(spec: RunSpec) -> list:
    """The ramp's loads ``(s, D0)`` for ``spec``, the pre-load first.

    3D: the pre-load in equal steps ``(s k/n, 0)``, ``n`` from :data:`PRELOAD_STEPS`
    (a single ``(0, 0)`` target when ``s = 0``), then ``(s, D0)`` for the charge
    targets. Membrane: straight to ``(s, D0)`` for every target, as
    :func:`skfem_dielectric.membrane_ramp`.

    Parameters
    ----------
    spec : RunSpec

    Returns
    -------
    list of ndarray
    """
    if _is_membrane(spec):
        return [np.array([spec.s, d]) for d in spec.D0]
    n = PRELOAD_STEPS[spec.geometry] if spec.s > 0 else 1
    return fe.preload_then_charge(spec.s, spec.D0, n)


def ramp_settings(spec: RunSpec, linear_solver="superlu") -> dict:
    """Keyword arguments of :func:`skfem_dielectric.solvers.ramp.ramp` for ``spec``.

    Parameters
    ----------
    spec : RunSpec
    linear_solver : str
        Requested solver. The Maxwell-traction variants have a non-symmetric tangent
        (follower load), which the symmetric-indefinite PARDISO set-up (upper triangle
        only) cannot factorise: they get :func:`skfem_dielectric.nonsymmetric_solver`
        of it (SuperLU, or PARDISO as a general LU when PARDISO is asked for).

    Returns
    -------
    dict
        ``settings``: a :class:`skfem_dielectric.RampSettings` with ``atol``, ``rtol``
        (:data:`RTOL` with ``atol = 0`` in 3D, :data:`MEMBRANE_TOL` for the membrane),
        ``max_cutbacks``, ``max_iter`` and ``chord`` (:data:`CHORD`); and
        ``linear_solver``.
    """
    if "maxwell" in spec.variant:
        linear_solver = fe.nonsymmetric_solver(linear_solver)
    tol = MEMBRANE_TOL if _is_membrane(spec) else {"atol": 0.0, "rtol": RTOL[spec.geometry]}
    settings = fe.RampSettings(**tol, max_cutbacks=MAX_CUTBACKS, max_iter=MAX_ITER,
                               chord=CHORD)
    return {"settings": settings, "linear_solver": linear_solver}


def pardiso_installed() -> bool:
    """Whether PARDISO (pypardiso, the ``fast`` extra) can be used."""
    return fe.pardiso_available()


#: grad-div stabilisation (units of mu) of the tangent of the homogeneous plates' stability
#: columns: it removes the spurious mesh-scale surface modes of Q2/Q1 and, J = 1 holding
#: exactly there, is the Hessian of the same state (docs/stability.md)
STABILITY_GRAD_DIV = 10.0
#: grad-div stabilisation (units of mu) of the uni-axial runs analysed for buckling
#: (``RunSpec.buckling``), as in ``skfem-dielectric buckling``
BUCKLING_GRAD_DIV = 10.0
def stability_columns(spec: RunSpec, problem, x, load, analysis=None) -> dict:
    """Stability of a converged state: ``n_negative``, ``n_unstable``, ``lowest_eig`` and
    the verdict ``stable``.

    ``n_negative`` counts the negative eigenvalues of the reduced stiffness
    (:func:`skfem_dielectric.tangent_stability`; of the model's own tangent, for the
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
        if not _is_membrane(spec) and spec.geometry == "equibiaxial":
            K = problem.stabilised_tangent(x, load, STABILITY_GRAD_DIV)
        else:
            K = problem.assemble(x, load)[0]
        # lowest_eig to 1e-6 (a column of the table; the count is exact)
        st = fe.tangent_stability(problem, K, k=1, method="auto", all_negative=True,
                                  tol=1e-6)
    artefacts = 0
    if not _is_membrane(spec) and spec.geometry == "uniaxial" and st.n_negative:
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
    if linear_solver != "pardiso" or not problem.symmetric or _is_membrane(spec) \
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
    G, dofs = fe.point_gradients(problem.basis, inner)
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
    if _is_membrane(spec):
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


def plate_buckling_columns(spec: RunSpec, problem, x, load) -> dict:
    """The whole plate's spectrum at a state of a run with ``spec.buckling``:
    ``n_negative_plate`` (negative eigenvalues over every symmetry class of the eighth
    model), ``physical_eig`` (the lowest eigenvalue whose mode is classified physical,
    :func:`skfem_dielectric.models.plate.modes.lowest_physical`; ``nan`` if none of the computed
    ones is) and ``physical_class`` (its symmetry class).  Empty for other runs, and where
    the spectrum cannot be computed (a ``ValueError``, e.g. a class tangent too large to
    be counted without PARDISO)."""
    if not (spec.buckling and spec.geometry == "uniaxial" and not _is_membrane(spec)
            and problem.symmetric):
        return {}
    try:
        lowest = fe_modes.lowest_physical(problem, x, load)
    except ValueError:
        return {}
    return {"n_negative_plate": int(lowest.n_negative), "physical_eig": lowest.eigenvalue,
            "physical_class": lowest.label.symmetry if lowest.label is not None else ""}


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
    if not _is_membrane(spec) and not tuple(problem.plate.symmetry):
        return own
    return None


def _step_record(spec: RunSpec, problem, step, analysis=None) -> StepRecord:
    """The :class:`StepRecord` of a converged target, with the centre line if recorded."""
    q = step.quantities
    rec = StepRecord(D0=float(np.asarray(step.load)[1]), lam1=q["lam1"], lam3=q["lam3"],
                     min_P33=q["min_P33"], min_P33_clamp=q.get("min_P33_clamp", np.nan),
                     iterations=step.iterations,
                     **stability_columns(spec, problem, step.x, step.load, analysis),
                     **plate_buckling_columns(spec, problem, step.x, step.load))
    rec.stable = whole_plate_verdict(spec, problem, rec)
    c = _centre_line(spec, problem, step)
    rec.min_P33_interior = _interior_min(c["x1"], c["P33"])
    if spec.record_fields:
        n = len(c["x1"])
        rec.fields = {"kind": np.zeros(n), "x1": np.asarray(c["x1"]) * 1e-3, "x3": np.zeros(n),
                      "P33": c["P33"], "lam1": c["lam1"], "lam3": c["lam3"]}
        if spec.record_maps and rec.D0 == 0.0:
            # stretch maps of the pre-loaded plate (kind 1) after the centre line (kind 0)
            maps = (membrane_stretch_maps(problem, step.x) if _is_membrane(spec)
                    else _plate_stretch_maps(problem, step.x, step.load))
            rec.fields = {k: np.r_[rec.fields[k], maps[k]] for k in rec.fields}
    return rec


def _export(spec: RunSpec, problem, x, load):
    """meshio ``Mesh`` of a state: :func:`skfem_dielectric.step_mesh` in 3D (u, phi, p,
    P33, stretches); for the membrane the displacement ``(u1, 0, u3)``, ``lam1``, ``lam3``."""
    if not _is_membrane(spec):
        return fe.step_mesh(problem, x, load)
    u = problem.T @ x
    ud = u[problem.basis.nodal_dofs]                   # (2, nverts): u1, u3
    p = problem.mesh.p
    pts = np.c_[p[0], np.zeros(p.shape[1]), p[1]]     # (x1, x2 = 0, x3)
    disp = np.c_[ud[0], np.zeros(p.shape[1]), ud[1]]
    maps = membrane_stretch_maps(problem, x)
    return meshio.Mesh(pts, [("quad", problem.mesh.t[:4].T.copy())],
                       point_data={"displacement": disp, "lam1": maps["lam1"],
                                   "lam3": maps["lam3"]})


def _analysis(monitor, step, load):
    """The monitor's analysis of ``step`` (``None`` without a monitor, or where the ramp
    could not factorise the step's tangent and the monitor did not see it)."""
    if monitor is None or "state_analysis_error" in step.quantities or not monitor.history \
            or not np.array_equal(np.asarray(monitor.history[-1][0], dtype=float), load):
        return None
    return monitor.last


# --------------------------------------------------------------------------- the runner
def run_fe(spec, start, state, on_step, linear_solver="superlu"):
    """Run the FE ramp of ``spec`` from target ``start`` (runner protocol of :mod:`.sweep`).

    Parameters
    ----------
    spec : RunSpec
    start : int
        First target to compute; ``state`` holds ``x`` and ``load`` of target
        ``start - 1`` (``None`` when ``start == 0``).
    state : dict or None
    on_step : callable
        ``on_step(index, record, state) -> stop``.
    linear_solver : str
        Passed to the ramp; SuperLU (deterministic) by default, so that a
        resumed ramp repeats the uninterrupted one bit for bit.

    Returns
    -------
    RunOutcome
    """
    problem = build_problem(spec)
    targets = ramp_targets(spec)
    x0 = None if state is None else np.asarray(state["x"], dtype=float)
    start_load = None if state is None else np.asarray(state["load"], dtype=float)
    if start_load is not None:
        try:
            targets = fe.remaining_targets(targets, start_load)
        except ValueError:
            raise ValueError(f"saved load {start_load} is not a target of run {spec.key}"
                             ) from None

    monitor = stability_monitor(spec, problem, linear_solver)

    def cb(step):
        load = np.asarray(step.load, dtype=float)
        if load[0] != spec.s or not step.target_reached:
            # an intermediate pre-load step, or the furthest converged sub-step towards a
            # target the ramp failed to reach (the failed target is recorded as a row)
            return
        i = spec.D0.index(float(load[1]))
        if on_step(i, _step_record(spec, problem, step, _analysis(monitor, step, load)),
                   {"x": step.x, "load": load}):
            raise _Stop

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)   # the failure is recorded
            res = fe.ramp(problem, targets, x0=x0, start=start_load, on_step=cb,
                          state_analysis=monitor, **ramp_settings(spec, linear_solver),
                          **fe.newton_guards(problem))
    except _Stop:
        return RunOutcome(True)
    failed = None if res.failed_at is None else float(np.asarray(res.failed_at).ravel()[-1])
    return RunOutcome(bool(res.converged), res.reason, failed)


def _ramp_spec(geometry, model, variant, s, alpha, D0, mesh) -> RunSpec:
    """A :class:`RunSpec` that runs to its last target (no breakdown stop)."""
    return RunSpec(geometry, model, variant, float(s), tuple(D0), alpha=alpha,
                   mesh=(("n1", mesh[0]), ("n2", mesh[1]), ("n3", mesh[2])),
                   stop_at_breakdown=False)


def simulate(*, geometry="uniaxial", model="neo-Hookean", variant="coupled", s=None,
             alpha=None, D0_max=4.0, steps=8, mesh=None, fmt="vtu", out="."):
    """Run one FE ramp and export every converged step (``skfem-dielectric simulate``).

    Parameters
    ----------
    geometry : {"equibiaxial", "uniaxial", "uniaxial-free"}
    model : {"neo-Hookean", "Gent"}
    variant : {"coupled", "maxwell", "membrane"}
    s : float, optional
        Dead load; for ``"uniaxial"`` it is set from ``alpha`` (default 1).
    alpha : float, optional
        Weight fraction of the Keplinger plate.
    D0_max : float
        Last charge target.
    steps : int
        Number of charge steps after the pre-load.
    mesh : (n1, n2, n3), optional
        Element counts (default coarse).
    fmt : {"vtu", "xdmf"}
        One ``.vtu`` per step, or one XDMF time series.
    out : path-like
        Output folder (created).

    Returns
    -------
    list of Path
        The written files: the fields and ``steps.csv``.
    """
    if steps < 1:
        raise ValueError(f"steps must be >= 1, got {steps}")
    if not np.isfinite(D0_max) or D0_max <= 0:
        raise ValueError(f"D0_max must be > 0, got {D0_max}")
    if fmt not in ("vtu", "xdmf"):
        raise ValueError(f"fmt must be 'vtu' or 'xdmf', got {fmt!r}")
    if geometry == "uniaxial":
        alpha = 1.0 if alpha is None else alpha
        s = keplinger_s(alpha)
    else:
        s = 1.0 if s is None else s
    spec = _ramp_spec(geometry, model, variant, s, alpha, np.linspace(0, D0_max, steps + 1),
                      (20, 1, 10) if mesh is None else tuple(mesh))
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    problem = build_problem(spec)
    frames, rows = [], []

    def on_step(i, rec, st):
        frames.append(_export(spec, problem, st["x"], st["load"]))
        rows.append([i, spec.D0[i], rec.lam1, rec.lam3, rec.min_P33, rec.min_P33_clamp,
                     rec.iterations])
        return False

    outcome = run_fe(spec, 0, None, on_step)
    written = []
    stem = f"{spec.key}"
    if fmt == "vtu":
        for i, frame in enumerate(frames):
            path = out / f"{stem}_{i:03d}.vtu"
            meshio.write(path, frame)
            written.append(path)
    elif frames:
        path = out / f"{stem}.xdmf"
        with meshio.xdmf.TimeSeriesWriter(path, data_format="XML") as w:   # no h5py needed
            w.write_points_cells(frames[0].points, frames[0].cells)
            for i, frame in enumerate(frames):
                w.write_data(spec.D0[i], point_data=frame.point_data,
                             cell_data=frame.cell_data or None)
        written.append(path)
    table = out / f"{stem}_steps.csv"
    with open(table, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(["step", "D0", "lam1", "lam3", "min_P33", "min_P33_clamp", "iterations"])
        w.writerows(rows)
        if not outcome.converged:
            w.writerow([len(rows), "", "", "", "", "", f"stopped: {outcome.reason}"])
    return written + [table]


def bench(*, mesh=(20, 1, 10), alpha=1.0, D0_max=6.0, steps=6, variant="coupled",
          solver="auto"):
    """Time one Keplinger ramp; returns the lines of a small table (``skfem-dielectric bench``).

    Parameters
    ----------
    mesh : (n1, n2, n3)
    alpha : float
    D0_max : float
    steps : int
    variant : {"coupled", "maxwell", "membrane"}
    solver : str
        Linear solver name passed to the ramp.

    Returns
    -------
    list of str
    """
    if steps < 1:
        raise ValueError(f"steps must be >= 1, got {steps}")
    spec = _ramp_spec("uniaxial", "neo-Hookean", variant, keplinger_s(alpha), alpha,
                      np.linspace(0, D0_max, steps + 1), mesh)
    t_build = time.perf_counter()
    problem = build_problem(spec)
    t_build = time.perf_counter() - t_build
    lines = [f"Keplinger plate, alpha = {alpha:g} (s = {spec.s:.4g}), variant {variant}, "
             f"mesh {tuple(mesh)}, {problem.initial_state().size} unknowns, set-up {t_build:.2f} s",
             f"{'step':>4} {'D0':>6} {'lam1':>9} {'min_P33':>9} {'iters':>5} {'seconds':>8}"]
    t = [time.perf_counter()]

    def on_step(i, rec, st):
        now = time.perf_counter()
        lines.append(f"{i:4d} {rec.D0:6.2f} {rec.lam1:9.5f} {rec.min_P33:9.4f} "
                     f"{rec.iterations:5d} {now - t[-1]:8.2f}")
        t.append(now)
        return False

    outcome = run_fe(spec, 0, None, on_step, linear_solver=solver)
    lines.append(f"total {t[-1] - t[0]:.2f} s" + ("" if outcome.converged
                                                 else f"; stopped: {outcome.reason}"))
    return lines

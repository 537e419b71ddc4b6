"""High-level drivers: build a model, pre-load it, then ramp the charge (or voltage).

Every driver solves in dimensionless units: stresses in units of ``mu``, ``eps = 1``,
lengths as given (the Keplinger plate in mm), so ``s`` and ``D0`` (``E0``) are the paper's
dimensionless loads.  The 3D drivers are a *builder* (:func:`equibiaxial_problem`,
:func:`keplinger_problem`: the :class:`~skfem_dielectric.models.plate.problem.PlateProblem`) and a
ramp along :func:`~skfem_dielectric.gallery.loads.preload_then_charge` (:func:`run_ramp`); use the
builders to ramp a plate along a path of your own.  Builders and drivers take the plate's
model options (control, coupling, formulation, grad-div, threads, ...) as one
:class:`~skfem_dielectric.gallery.plates.PlateOptions` (``options=``) and how the load steps
are solved as one :class:`~skfem_dielectric.solvers.ramp.RampSettings` (``settings=``).  The
load of every step is the pair
``(s, D0)`` (``(s, E0)`` under voltage control).  Each step's ``quantities`` hold the
post-processed values of the model plus ``phase`` (``"preload"`` or ``"charge"``) and
``stable`` (inertia verdict with PARDISO, else ``None``).

Resuming: pass ``x0=step.x``, ``start=step.load``, ``back=step.back``,
``back2=step.back2`` and ``factors=step.factors`` of a saved step together with the *same*
arguments; targets up to and including ``start`` are skipped and the remaining steps are
bit-for-bit those of the uninterrupted run (deterministic linear solver).  ``factors`` is where the factors the next
step starts on come from (``keep_factors`` of the settings, as in :data:`KEPLINGER_SETTINGS`);
``None`` for settings without it.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, Callable, Sequence

import numpy as np

from ..checks import check_count, check_finite, check_positive
from ..fem.mesh import plate_mesh
from ..linalg.solver_base import LinearSolver
from ..materials import NeoHookeanDielectric, make_material
from ..models.cross_section import CrossSection
from ..models.membrane import MembranePlate, membrane_mesh
from ..models.plate.failure import StepLimitCounter, describe_failure, plate_failure_cause
from ..models.plate.problem import PlateProblem
from ..problem import Problem
from ..solvers.newton import check_settings
from ..solvers.ramp import RampResult, RampSettings, StepResult, check_callbacks, ramp
from .defaults import (EQUIBIAXIAL_PRELOAD_STEPS, EQUIBIAXIAL_RTOL, EQUIBIAXIAL_SIZE, GENT_JM,
                       KEPLINGER_ACCELERATION, KEPLINGER_CHORD, KEPLINGER_MAX_ITER,
                       KEPLINGER_PRELOAD_STEPS, KEPLINGER_RTOL, KEPLINGER_SIZE)
from .loads import charge_targets, keplinger_s, preload_then_charge, remaining_targets
from .plates import PlateOptions

__all__ = ["EQUIBIAXIAL_SETTINGS", "KEPLINGER_SETTINGS", "MAXWELL_KEPLINGER_SETTINGS",
           "plate_admissible", "equibiaxial_problem", "keplinger_problem",
           "run_ramp", "equibiaxial_plate", "keplinger_plate", "maxwell_equibiaxial",
           "maxwell_keplinger", "membrane_ramp", "membrane_keplinger", "cross_section_ramp"]

#: How :func:`equibiaxial_plate` solves its load steps: the homogeneous state converges to
#: round-off, so a tight ``rtol`` relative to the external load alone (``atol = 0``).
EQUIBIAXIAL_SETTINGS = RampSettings(atol=0.0, rtol=EQUIBIAXIAL_RTOL, max_cutbacks=6)
#: How :func:`keplinger_plate` solves its load steps: ``rtol`` relative to the external
#: load alone, factors kept while the (accelerated) chord steps halve the residual, each
#: solve started from the parabola through the last three states, a small Newton budget
#: (converged steps need <= 6 iterations on the 40 x 20 eighth model up to ``D0 = 5``, up
#: to 9 right before the breakdown; a low limit makes the attempts beyond it cheap).
KEPLINGER_SETTINGS = RampSettings(atol=0.0, rtol=KEPLINGER_RTOL, max_iter=KEPLINGER_MAX_ITER,
                                  max_cutbacks=4, chord=KEPLINGER_CHORD,
                                  acceleration=KEPLINGER_ACCELERATION, keep_factors=True,
                                  predictor="quadratic", factor_precision="single")
#: How :func:`maxwell_keplinger` solves its load steps: :data:`KEPLINGER_SETTINGS` with
#: the ramp's default Newton budget (6 cut-backs, 25 iterations).
MAXWELL_KEPLINGER_SETTINGS = replace(KEPLINGER_SETTINGS, max_iter=25, max_cutbacks=6)


def _phase(load) -> str:
    return "preload" if np.asarray(load)[1] == 0 else "charge"


def plate_admissible(problem: PlateProblem, x: np.ndarray, load) -> str:
    """Why the plate state ``x`` is inverted, or ``""`` if it is not
    (:meth:`~skfem_dielectric.models.plate.problem.PlateProblem.admissible`)."""
    return problem.admissible(x, load)


def _triple(name: str, value, check) -> tuple:
    """``value`` as a 3-tuple checked entry by entry (``size``: lengths, ``elements``: counts)."""
    try:
        items = tuple(value)
    except TypeError:
        items = ()
    if len(items) != 3:
        raise ValueError(f"{name} must be a triple (x1, x2, x3), got {value!r}")
    return tuple(check(f"{name}[{i}]", v) for i, v in enumerate(items))


def run_ramp(problem: Problem, targets: Sequence[Any], *,
             on_step: Callable[[StepResult], Any] | None = None,
             x0: np.ndarray | None = None, start: Any = None,
             back: tuple[np.ndarray, Any] | None = None,
             linear_solver: str | LinearSolver = "auto", extra: dict | None = None,
             **ramp_options) -> RampResult:
    """Ramp ``problem`` through ``targets``, resuming after ``start``, and tag the steps.

    Parameters
    ----------
    problem
        Any :class:`~skfem_dielectric.problem.Problem` whose loads are ``(s, D0)``-like
        pairs (the second component 0 marks the pre-load).
    targets
        The whole load path (e.g. :func:`~skfem_dielectric.gallery.loads.preload_then_charge`).
    on_step, x0, start, back
        Callback and resume state: with ``start`` (the load of a saved step, which must be
        one of ``targets``), ``x0`` (its state), ``factors`` (its ``StepResult.factors``,
        in ``ramp_options``) and ``back`` (its ``StepResult.back``, the
        predictor's second point; its third, ``back2``, in ``ramp_options``) the ramp
        continues after ``start``.
    linear_solver
        Name or instance (:func:`~skfem_dielectric.linalg.linear.get_linear_solver`).
    extra
        Quantities added to every step (e.g. ``alpha``); each step also gets ``phase``.
    **ramp_options
        ``settings`` (:class:`~skfem_dielectric.solvers.ramp.RampSettings`), ``factors``,
        ``stop``, ``state_analysis``, ``step_limit`` and ``admissible`` of
        :func:`~skfem_dielectric.solvers.ramp.ramp`.  For a
        :class:`~skfem_dielectric.models.plate.problem.PlateProblem` the last two default to
        ``step_limit=problem.max_step`` (``det F > 0`` along every Newton step) and
        ``admissible``: :func:`plate_admissible` (no converged inverted state).

    Returns
    -------
    RampResult
        With ``problem`` set (for evaluation and export of the stored states).  When
        Newton fails on a plate, ``failure`` holds
        :func:`~skfem_dielectric.models.plate.failure.plate_failure_cause` of the last converged
        state and how often the step limit shortened the Newton steps towards the failed target
        (``step_limited`` of ``newton_steps``, ``smallest_step_limit``), and ``reason``
        ends with that sentence (docs/validation.md, the corner failure).
    """
    check_callbacks({"on_step": on_step, **ramp_options})
    targets = list(targets)
    if start is not None:
        targets = remaining_targets(targets, start)
        if x0 is None:
            raise ValueError("start given without x0")
    extra = dict(extra or {})
    counter = None
    limit = ramp_options.get("step_limit") or problem.newton_guards().get("step_limit")
    if isinstance(problem, PlateProblem) and limit is not None:
        counter = ramp_options["step_limit"] = StepLimitCounter(limit)

    def hook(step: StepResult):
        step.quantities.update(extra)
        step.quantities["phase"] = _phase(step.load)
        if counter is not None and step.target_reached:
            counter.reset()
        if on_step is not None:
            on_step(step)

    out = ramp(problem, targets, x0=x0, start=start, back=back, on_step=hook,
               linear_solver=linear_solver, **ramp_options)
    out.problem = problem
    if out.failed_at is not None and out.steps and isinstance(problem, PlateProblem):
        out.failure = plate_failure_cause(problem, out.steps[-1].x, out.steps[-1].load)
        if counter is not None:
            out.failure.update(step_limited=counter.limited, newton_steps=counter.calls,
                               smallest_step_limit=counter.smallest)
        out.reason += "; " + describe_failure(out.failure)
    return out


def _charge_loads(s: float, D0: Sequence[float]) -> list[np.ndarray]:
    """The charge targets of a plate driver as loads, in ramp order: the pre-loaded state
    ``(s, 0)`` if ``D0`` holds a zero, then ``(s, D0_i)`` for the others
    (:attr:`~skfem_dielectric.solvers.ramp.RampResult.targets`)."""
    vals = np.atleast_1d(np.asarray(D0, dtype=float))
    zero = [np.array([s, 0.0])] if np.any(vals == 0.0) else []
    return zero + [np.array([s, v]) for v in vals if v != 0.0]


def equibiaxial_problem(*, model: Any = "neo-Hookean", Jm: float = GENT_JM,
                        size: tuple[float, float, float] = EQUIBIAXIAL_SIZE,
                        elements: tuple[int, int, int] = (1, 1, 1), symmetry: str = "eighth",
                        options: PlateOptions = PlateOptions()) -> PlateProblem:
    """The equi-biaxial dead-load plate (dimensionless ``mu = eps = 1``).

    Parameters
    ----------
    model, Jm
        ``"neo-Hookean"``, ``"Gent"`` (with ``Jm``) or a material object.
    size, elements, symmetry
        Full plate ``(L1, H, L3)``, elements of the model, symmetry (see
        :func:`~skfem_dielectric.fem.mesh.plate_mesh`).  The state is homogeneous, so one
        element suffices.
    options
        The model options (:class:`~skfem_dielectric.gallery.plates.PlateOptions`: control,
        coupling, formulation, ...).
    """
    check_settings("options", options, PlateOptions)
    pm = plate_mesh(*_triple("size", size, check_positive),
                    *_triple("elements", elements, check_count), symmetry=symmetry)
    return PlateProblem(pm, make_material(model, Jm), loading="equibiaxial",
                        **options.as_kwargs())


def keplinger_problem(*, model: Any = "neo-Hookean", Jm: float = GENT_JM,
                      size: tuple[float, float, float] = KEPLINGER_SIZE,
                      elements: tuple[int, int, int] = (40, 1, 20), symmetry: str = "eighth",
                      grading: float = 1.0,
                      options: PlateOptions = PlateOptions()) -> PlateProblem:
    """The clamped uni-axial Keplinger plate (dimensionless ``mu = eps = 1``, mm).

    A plate ``L1 x H x L3 = 100 x 1 x 50`` (mm) clamped on its short edges ``x1 = +-L1/2``;
    the clamps have ``u2 = u3 = 0``, the moving clamp translates rigidly in ``x1`` (one
    shared dof) under the resultant ``s mu A``.  With the default eighth model the symmetry
    planes ``x1 = 0`` (both clamps equivalent), ``x2 = 0`` (antisymmetric ``phi``) and
    ``x3 = 0`` are used.

    Parameters
    ----------
    model, Jm
        Material model.
    size, elements, symmetry, grading
        Plate ``(L1, H, L3)`` in mm, elements of the model ``(n1, n2, n3)``, symmetry and
        x1-grading towards the clamp (see :func:`~skfem_dielectric.fem.mesh.plate_mesh`).
    options
        The model options (:class:`~skfem_dielectric.gallery.plates.PlateOptions`: control,
        coupling, formulation, grad-div stabilisation, threads, ...).
    """
    check_settings("options", options, PlateOptions)
    pm = plate_mesh(*_triple("size", size, check_positive),
                    *_triple("elements", elements, check_count), symmetry=symmetry,
                    grading=grading)
    return PlateProblem(pm, make_material(model, Jm), loading="uniaxial",
                        **options.as_kwargs())


def equibiaxial_plate(s: float, D0: Sequence[float], *, model: Any = "neo-Hookean",
                      Jm: float = GENT_JM, size: tuple[float, float, float] = EQUIBIAXIAL_SIZE,
                      elements: tuple[int, int, int] = (1, 1, 1), symmetry: str = "eighth",
                      options: PlateOptions = PlateOptions(),
                      preload_steps: int = EQUIBIAXIAL_PRELOAD_STEPS, linear_solver: str = "auto",
                      on_step: Callable[[StepResult], Any] | None = None,
                      x0: np.ndarray | None = None, start: Any = None,
                      back: tuple[np.ndarray, Any] | None = None,
                      factors: tuple[np.ndarray, Any] | None = None,
                      settings: RampSettings = EQUIBIAXIAL_SETTINGS,
                      back2: tuple[np.ndarray, Any] | None = None) -> RampResult:
    """Equi-biaxial dead-load plate: pre-load ``s``, then the charge ramp ``D0``.

    Parameters
    ----------
    s
        Dimensionless nominal lateral traction ``t/mu`` on all lateral faces.
    D0
        Target values of the charge ramp (``D0 = sigma_F/sqrt(mu eps)``); under
        ``PlateOptions(control="voltage")`` they are ``E0`` values.
    model, Jm, size, elements, symmetry
        See :func:`equibiaxial_problem`.
    options
        The model options (:class:`~skfem_dielectric.gallery.plates.PlateOptions`).
    preload_steps
        Number of equal pre-load targets.
    linear_solver
        ``"auto"``, ``"superlu"`` or ``"pardiso"`` (for ``coupling="maxwell"`` PARDISO is
        its general LU).
    on_step, x0, start, back, back2, factors
        Callback and resume state, see the module docstring.
    settings
        How the load steps are solved (:class:`~skfem_dielectric.solvers.ramp.RampSettings`;
        default :data:`EQUIBIAXIAL_SETTINGS`: ``rtol = 1e-11`` relative to the external load
        norm, ``atol = 0``, 6 cut-backs).

    Returns
    -------
    RampResult
        ``steps[i].quantities["lam1"]`` is the stretch at the plate centre (equal to
        ``lam3``); compare with Eq. (loading_gent).
    """
    s = check_finite("s", s)
    check_settings("settings", settings, RampSettings)
    check_callbacks({"on_step": on_step})
    prob = equibiaxial_problem(model=model, Jm=Jm, size=size, elements=elements,
                               symmetry=symmetry, options=options)
    extra = {"model": type(prob.material).__name__}
    if options.coupling == "maxwell":
        extra["variant"] = f"maxwell-{options.field}"
    out = run_ramp(prob, preload_then_charge(s, D0, preload_steps), on_step=on_step, x0=x0,
                   start=start, back=back, back2=back2, factors=factors,
                   linear_solver=linear_solver, extra=extra, settings=settings)
    out.targets = _charge_loads(s, D0)
    return out


def keplinger_plate(alpha: float | None = 1.0, D0: Sequence[float] = (1, 2, 3, 4, 5, 6), *,
                    s: float | None = None, g: float = 9.81, m: float = 0.150,
                    mu: float = 9833.07, A: float = 50e-6, model: Any = "neo-Hookean",
                    Jm: float = GENT_JM, size: tuple[float, float, float] = KEPLINGER_SIZE,
                    elements: tuple[int, int, int] = (40, 1, 20), symmetry: str = "eighth",
                    grading: float = 1.0, options: PlateOptions = PlateOptions(),
                    preload_steps: int = KEPLINGER_PRELOAD_STEPS, linear_solver: str = "auto",
                    settings: RampSettings = KEPLINGER_SETTINGS,
                    state_analysis: Callable[..., dict] | None = None,
                    on_step: Callable[[StepResult], Any] | None = None,
                    x0: np.ndarray | None = None, start: Any = None,
                    back: tuple[np.ndarray, Any] | None = None,
                    factors: tuple[np.ndarray, Any] | None = None,
                    back2: tuple[np.ndarray, Any] | None = None) -> RampResult:
    """The uni-axial Keplinger plate: weight on a rigid clamp, then the charge ramp.

    Parameters
    ----------
    alpha
        Weight fraction; ``s = keplinger_s(alpha, g=g, m=m, mu=mu, A=A)`` unless ``s`` is
        given.
    D0
        Target values of the charge ramp (``E0`` values under voltage control).
    s
        Dimensionless dead load; overrides ``alpha``.
    g, m, mu, A
        Physical data for ``s`` (``g`` default 9.81 m/s^2).
    model, Jm, size, elements, symmetry, grading
        See :func:`keplinger_problem`.
    options
        The model options (:class:`~skfem_dielectric.gallery.plates.PlateOptions`);
        ``PlateOptions(grad_div=10.0)`` lets Newton pass the clamp/free-edge corner where
        the plain mixed form stalls on fine meshes (docs/validation.md, the corner failure).
    preload_steps
        Number of pre-load targets (the ramp cuts back automatically if needed).
    linear_solver
        Linear solver name.
    settings
        How the load steps are solved (:class:`~skfem_dielectric.solvers.ramp.RampSettings`;
        default :data:`KEPLINGER_SETTINGS`: ``rtol = 1e-9``, ``atol = 0``, 4 cut-backs, 12
        Newton iterations per attempt, factors kept across load steps, Anderson-accelerated
        chord steps at ``chord = 0.5``, each Newton solve started from the parabola
        through the last three converged states, ``predictor="quadratic"``).
        ``replace(KEPLINGER_SETTINGS, stop_on_instability=True)`` stops at the first step
        whose tangent inertia says unstable (PARDISO only): the discrete breakdown near the
        clamps; ``predictor="none"`` starts each solve from the last converged state.
    state_analysis
        Analysis of every converged state on the factorisation of its tangent, e.g.
        ``StabilityMonitor(k=5)`` (:mod:`skfem_dielectric.stability.monitor`); see
        :func:`~skfem_dielectric.solvers.ramp.ramp`.
    on_step, x0, start, back, back2, factors
        Callback and resume state (see the module docstring).

    Returns
    -------
    RampResult
        Per step: ``lam1``/``lam3`` at the plate centre (compare with Eq. (DEuniax)),
        ``min_P33`` on the x1 centre line, ``min_P33_clamp`` near the clamp, ``stable``,
        ``alpha``, ``phase`` and the Newton data.
    """
    if s is None:
        if alpha is None:
            raise ValueError("give alpha or s")
        s = keplinger_s(alpha, g=g, m=m, mu=mu, A=A)
    s = check_finite("s", s)
    check_settings("settings", settings, RampSettings)
    check_callbacks({"on_step": on_step, "state_analysis": state_analysis})
    prob = keplinger_problem(model=model, Jm=Jm, size=size, elements=elements,
                             symmetry=symmetry, grading=grading, options=options)
    extra = {"alpha": alpha if alpha is not None else float("nan"), "g": g}
    if options.coupling == "maxwell":
        extra["variant"] = f"maxwell-{options.field}"
    out = run_ramp(prob, preload_then_charge(s, D0, preload_steps), on_step=on_step, x0=x0,
                   start=start, back=back, back2=back2, factors=factors,
                   linear_solver=linear_solver, extra=extra, settings=settings,
                   state_analysis=state_analysis)
    out.targets = _charge_loads(s, D0)
    return out


def maxwell_equibiaxial(s: float, D0, *, field: str = "electrostatic",
                        options: PlateOptions = PlateOptions(), **driver_args) -> RampResult:
    """:func:`equibiaxial_plate` with ``coupling="maxwell"`` (charge control).

    Parameters
    ----------
    s, D0
        Dead load and charge targets, see :func:`equibiaxial_plate`.
    field
        ``"electrostatic"`` or ``"local"``
        (:class:`~skfem_dielectric.gallery.plates.PlateOptions`).
    options
        The other model options; their ``coupling`` and ``field`` are set here.
    **driver_args
        The other arguments of :func:`equibiaxial_plate`.

    Returns
    -------
    RampResult
        ``lam1`` at the centre follows Eq. (loading_gent) for either field.
    """
    check_settings("options", options, PlateOptions)
    return equibiaxial_plate(s, D0, options=replace(options, coupling="maxwell", field=field),
                             **driver_args)


def maxwell_keplinger(alpha: float | None = 1.0, D0=(1, 2, 3, 4, 5, 6), *,
                      field: str = "electrostatic",
                      options: PlateOptions = PlateOptions(),
                      settings: RampSettings = MAXWELL_KEPLINGER_SETTINGS,
                      **driver_args) -> RampResult:
    """:func:`keplinger_plate` with ``coupling="maxwell"`` (charge control), by default
    with the ramp's Newton budget (:data:`MAXWELL_KEPLINGER_SETTINGS`: 6 cut-backs, 25
    iterations).

    Parameters
    ----------
    alpha, D0
        Weight fraction and charge targets, see :func:`keplinger_plate`.
    field
        ``"electrostatic"`` or ``"local"``
        (:class:`~skfem_dielectric.gallery.plates.PlateOptions`).
    options
        The other model options; their ``coupling`` and ``field`` are set here.
    settings
        How the load steps are solved (default :data:`MAXWELL_KEPLINGER_SETTINGS`).
    **driver_args
        The other arguments of :func:`keplinger_plate`.

    Returns
    -------
    RampResult
        Per step ``lam1`` at the centre, ``min_P33`` (total stress) on the centre line,
        ``min_P33_clamp``, ``phase``, ``alpha``.
    """
    check_settings("options", options, PlateOptions)
    return keplinger_plate(alpha, D0, options=replace(options, coupling="maxwell", field=field),
                           settings=settings, **driver_args)


def membrane_ramp(problem: MembranePlate, s: float, D0, **ramp_options) -> RampResult:
    """Pre-load ``s`` then charge (or voltage) ramp ``D0`` on a membrane problem.

    Parameters
    ----------
    problem : MembranePlate
        The discretised membrane.
    s : float
        Dimensionless dead load (nominal stress over ``mu``).
    D0 : array_like
        Target values of ``D0`` (charge control) or ``E0`` (voltage control); the
        ramp goes from the unloaded state to ``(s, D0[0])`` (the pre-load when
        ``D0[0] = 0``), then through the others in order.
    **ramp_options
        Passed to :func:`skfem_dielectric.solvers.ramp.ramp` (``linear_solver``,
        ``on_step``, ``x0``/``start`` to resume, ``settings``, ...).

    Returns
    -------
    RampResult
        One :class:`StepResult` per target with the quantities of
        :meth:`MembranePlate.postprocess` (``lam1``, ``lam3``, ``min_P33``, ...);
        ``result.problem`` is ``problem`` (for :mod:`skfem_dielectric.export`).
    """
    s = check_finite("s", s)
    out = ramp(problem, [np.array([s, d]) for d in charge_targets(D0)], **ramp_options)
    out.problem = problem
    return out


def membrane_keplinger(alpha: float = 1.0, D0=np.arange(0.0, 6.01, 0.5), material=None,
                       n1: int = 40, n3: int = 20, L1: float = KEPLINGER_SIZE[0],
                       L3: float = KEPLINGER_SIZE[2], H: float = KEPLINGER_SIZE[1],
                       g: float = 9.81, **ramp_options) -> RampResult:
    """Membrane model of the clamped uni-axial Keplinger plate under charge control.

    Parameters
    ----------
    alpha : float
        Weight factor, ``s = keplinger_s(alpha, g=g)`` (``m = 150 g``,
        ``mu = 9833.07 Pa``, ``A = 50 mm^2``).
    D0 : array_like
        Charge targets after the pre-load (start with 0 to record it).
    material : optional
        Dielectric (default neo-Hookean, ``mu = eps = 1``: the results are
        dimensionless).
    n1, n3 : int
        Q2 elements along the half-length and half-width.
    L1, L3, H : float
        Plate size (default 100 x 50 x 1, mm).
    g : float
        Gravity used in ``s``.
    **ramp_options
        Passed to :func:`skfem_dielectric.solvers.ramp.ramp`.

    Returns
    -------
    RampResult
        Per step ``lam1`` (centre), ``lam3``, ``min_P33`` along the centre line,
        ``min_P33_clamp`` next to the clamp, ``lam1_mean``.
    """
    check_callbacks(ramp_options)
    material = NeoHookeanDielectric(1.0, 1.0) if material is None else material
    pb = MembranePlate(membrane_mesh(L1, H, L3, n1, n3), material, loading="uniaxial")
    return membrane_ramp(pb, keplinger_s(alpha, g=g), D0, **ramp_options)


def cross_section_ramp(problem: CrossSection, s1: float, s3: float, D0,
                       **ramp_options) -> RampResult:
    """Pre-load ``(s1, s3)`` then the charge (or voltage) ramp on a cross-section.

    Parameters
    ----------
    problem : CrossSection
        The discretised cross-section.
    s1, s3 : float
        Dimensionless nominal stresses along x1 and x3 (``s3`` is ignored when
        ``lam3`` is prescribed). Equi-biaxial: ``s1 = s3 = s``; uni-axial:
        ``s3 = 0``.
    D0 : array_like
        Targets of ``D0`` (or ``E0`` under voltage control).
    **ramp_options
        Passed to :func:`skfem_dielectric.solvers.ramp.ramp`.

    Returns
    -------
    RampResult
        Quantities of :meth:`CrossSection.postprocess` per step.
    """
    check_finite("s1", s1)
    check_finite("s3", s3)
    D0 = charge_targets(D0)
    out = ramp(problem, [np.array([s1, s3, d]) for d in D0], **ramp_options)
    out.problem = problem
    return out

"""High-level drivers: pre-load, then a charge (or voltage) ramp, returning a RampResult.

Both drivers solve in dimensionless units: stresses in units of ``mu``, ``eps = 1``,
lengths as given (the Keplinger plate in mm), so ``s`` and ``D0`` (``E0``) are the paper's
dimensionless loads.  The load of every step is the pair ``(s, D0)`` (``(s, E0)`` under
voltage control): first ``preload_steps`` targets ``(s k/n, 0)``, then ``(s, D0_i)`` for
the requested ``D0`` values.  Each step's ``quantities`` hold the post-processed values of
:meth:`skfem_dielectric.plate.PlateProblem.postprocess` plus ``phase`` (``"preload"`` or
``"charge"``) and ``stable`` (inertia verdict with PARDISO, else ``None``).

Resuming: pass ``x0=step.x`` and ``start=step.load`` of a saved step together with the
*same* arguments; targets up to and including ``start`` are skipped and the remaining steps
are bit-for-bit those of the uninterrupted run (deterministic linear solver).
"""

from __future__ import annotations

import math
from typing import Any, Callable, Sequence

import numpy as np

from .materials import GentDielectric, IdealDielectric, NeoHookeanDielectric
from .mesh import plate_mesh
from .newton import RampResult, StepResult, ramp
from .plate import PlateProblem

__all__ = ["equibiaxial_plate", "keplinger_plate", "keplinger_s", "make_material"]


def make_material(model: Any = "neo-Hookean", Jm: float = 97.2):
    """Dimensionless material (``mu = eps = 1``) from a model name or object.

    Parameters
    ----------
    model
        ``"neo-Hookean"``, ``"Gent"`` (with ``Jm``), or a material object
        (``NeoHookeanDielectric``, ``GentDielectric``, ``IdealDielectric``) used as is.
    Jm
        Gent stiffening parameter.
    """
    if isinstance(model, (NeoHookeanDielectric, GentDielectric, IdealDielectric)):
        return model
    if isinstance(model, str):
        key = model.lower().replace("-", "").replace("_", "").replace(" ", "")
        if key in ("neohookean", "nh"):
            return NeoHookeanDielectric(1.0, 1.0)
        if key == "gent":
            return GentDielectric(1.0, 1.0, Jm)
    raise ValueError(f"model must be 'neo-Hookean', 'Gent' or a material object, got {model!r}")


def _finite(name: str, value: float) -> float:
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def _targets(s: float, values: Sequence[float], preload_steps: int) -> list[np.ndarray]:
    if int(preload_steps) != preload_steps or preload_steps < 1:
        raise ValueError(f"preload_steps must be an integer >= 1, got {preload_steps!r}")
    vals = np.atleast_1d(np.asarray(values, dtype=float))
    if vals.ndim != 1 or not np.all(np.isfinite(vals)):
        raise ValueError(f"D0 must be a finite sequence, got {values!r}")
    t = [np.array([s * k / preload_steps, 0.0]) for k in range(1, int(preload_steps) + 1)]
    for v in vals:
        if v == 0.0:
            continue
        t.append(np.array([s, v]))
    return t


def _run(problem: PlateProblem, targets, *, on_step, x0, start, linear_solver, phase_of,
         extra: dict, **ramp_kw) -> RampResult:
    if start is not None:
        st = np.asarray(start, dtype=float)
        idx = [i for i, t in enumerate(targets) if np.allclose(t, st, rtol=0, atol=1e-14)]
        if not idx:
            raise ValueError(f"start {start!r} is not one of the ramp's loads")
        targets = targets[idx[0] + 1:]
        if x0 is None:
            raise ValueError("start given without x0")

    def hook(step: StepResult):
        step.quantities.update(extra)
        step.quantities["phase"] = phase_of(step.load)
        if on_step is not None:
            on_step(step)

    out = ramp(problem, targets, x0=x0, start=start, on_step=hook,
               linear_solver=linear_solver, **ramp_kw)
    out.problem = problem
    return out


def equibiaxial_plate(s: float, D0: Sequence[float], *, model: Any = "neo-Hookean",
                      Jm: float = 97.2, size: tuple[float, float, float] = (4.0, 1.0, 4.0),
                      elements: tuple[int, int, int] = (1, 1, 1), symmetry: str = "eighth",
                      preload_steps: int = 4, control: str = "charge",
                      formulation: str = "mixed", kappa: float = math.inf,
                      phi_element: str = "Q2", linear_solver: str = "auto",
                      on_step: Callable[[StepResult], Any] | None = None,
                      x0: np.ndarray | None = None, start: Any = None,
                      rtol: float = 1e-11, max_cutbacks: int = 6) -> RampResult:
    """Equi-biaxial dead-load plate: pre-load ``s``, then the charge ramp ``D0``.

    Parameters
    ----------
    s
        Dimensionless nominal lateral traction ``t/mu`` on all lateral faces.
    D0
        Target values of the charge ramp (``D0 = sigma_F/sqrt(mu eps)``); under
        ``control="voltage"`` they are ``E0`` values.
    model, Jm
        ``"neo-Hookean"``, ``"Gent"`` (with ``Jm``) or a material object.
    size, elements, symmetry
        Full plate ``(L1, H, L3)``, elements of the model, symmetry (see
        :func:`~skfem_dielectric.mesh.plate_mesh`).  The state is homogeneous, so one
        element suffices.
    preload_steps
        Number of equal pre-load targets.
    control, formulation, kappa, phi_element
        See :class:`~skfem_dielectric.plate.PlateProblem`.
    linear_solver
        ``"auto"``, ``"superlu"`` or ``"pardiso"``.
    on_step, x0, start
        Callback and resume state, see the module docstring.
    rtol, max_cutbacks
        Newton tolerance (relative to the external load norm) and cut-back limit.

    Returns
    -------
    RampResult
        ``steps[i].quantities["lam1"]`` is the stretch at the plate centre (equal to
        ``lam3``); compare with Eq. (loading_gent).
    """
    s = _finite("s", s)
    mat = make_material(model, Jm)
    L1, H, L3 = size
    pm = plate_mesh(L1, H, L3, *elements, symmetry=symmetry)
    prob = PlateProblem(pm, mat, loading="equibiaxial", control=control,
                        formulation=formulation, kappa=kappa, phi_element=phi_element)
    targets = _targets(s, D0, preload_steps)
    return _run(prob, targets, on_step=on_step, x0=x0, start=start, linear_solver=linear_solver,
                phase_of=lambda ld: "preload" if ld[1] == 0 else "charge",
                extra={"model": type(mat).__name__}, atol=0.0, rtol=rtol,
                max_cutbacks=max_cutbacks)


def keplinger_s(alpha: float, m: float = 0.150, g: float = 9.81, mu: float = 9833.07,
                A: float = 50e-6) -> float:
    """Dimensionless dead load ``s = alpha m g / (mu A)`` of the Keplinger plate (Sec. 5).

    Parameters
    ----------
    alpha
        Weight fraction (the paper uses 0.05, 0.3, 0.7, 1.0, 1.5).
    m, g, mu, A
        Mass [kg], gravity [m/s^2] (state it: 9.81 or 9.80665), shear modulus [Pa] and
        reference cross-section [m^2] (50 mm x 1 mm).

    Returns
    -------
    float
        ``s``; e.g. ``keplinger_s(1.0) = 2.993`` with ``g = 9.81``.
    """
    for name, v in (("m", m), ("g", g), ("mu", mu), ("A", A)):
        if not (math.isfinite(float(v)) and float(v) > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {v!r}")
    alpha = _finite("alpha", alpha)
    if alpha < 0:
        raise ValueError(f"alpha must be >= 0, got {alpha}")
    return alpha * m * g / (mu * A)


def keplinger_plate(alpha: float | None = 1.0, D0: Sequence[float] = (1, 2, 3, 4, 5, 6), *,
                    s: float | None = None, g: float = 9.81, m: float = 0.150,
                    mu: float = 9833.07, A: float = 50e-6, model: Any = "neo-Hookean",
                    Jm: float = 97.2, size: tuple[float, float, float] = (100.0, 1.0, 50.0),
                    elements: tuple[int, int, int] = (40, 1, 20), symmetry: str = "eighth",
                    grading: float = 1.0, preload_steps: int = 3, control: str = "charge",
                    formulation: str = "mixed", kappa: float = math.inf,
                    phi_element: str = "Q2", linear_solver: str = "auto",
                    on_step: Callable[[StepResult], Any] | None = None,
                    x0: np.ndarray | None = None, start: Any = None, rtol: float = 1e-9,
                    max_cutbacks: int = 4, max_iter: int = 12,
                    threads: int | None = None,
                    stop_on_instability: bool = False) -> RampResult:
    """The uni-axial Keplinger plate: weight on a rigid clamp, then the charge ramp.

    A plate ``L1 x H x L3 = 100 x 1 x 50`` (mm) clamped on its short edges ``x1 = +-L1/2``;
    the clamps have ``u2 = u3 = 0``, the moving clamp translates rigidly in ``x1`` (one
    shared dof) under the resultant ``s mu A``.  With the default eighth model the symmetry
    planes ``x1 = 0`` (both clamps equivalent), ``x2 = 0`` (antisymmetric ``phi``) and
    ``x3 = 0`` are used.

    Parameters
    ----------
    alpha
        Weight fraction; ``s = keplinger_s(alpha, m, g, mu, A)`` unless ``s`` is given.
    D0
        Target values of the charge ramp (``E0`` values under voltage control).
    s
        Dimensionless dead load; overrides ``alpha``.
    g, m, mu, A
        Physical data for ``s`` (``g`` default 9.81 m/s^2).
    model, Jm
        Material model (dimensionless, ``mu = eps = 1`` in the solve).
    size, elements, symmetry, grading
        Plate ``(L1, H, L3)`` in mm, elements of the model ``(n1, n2, n3)``, symmetry and
        x1-grading towards the clamp (see :func:`~skfem_dielectric.mesh.plate_mesh`).
    preload_steps
        Number of pre-load targets (the ramp cuts back automatically if needed).
    control, formulation, kappa, phi_element
        See :class:`~skfem_dielectric.plate.PlateProblem`.
    linear_solver, threads
        Linear solver name and assembly threads.
    on_step, x0, start
        Callback and resume state (see the module docstring).
    stop_on_instability
        Stop at the first step whose tangent inertia says unstable (PARDISO only; see
        :func:`~skfem_dielectric.newton.ramp`): the discrete breakdown near the clamps.
    rtol, max_cutbacks, max_iter
        Newton tolerance, cut-back limit and Newton iterations per attempt (converged
        steps need <= 6 on the 40 x 20 eighth model up to D0 = 5, up to 9 right before the
        breakdown; a low limit makes the attempts beyond the breakdown cheap).

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
        s = keplinger_s(alpha, m, g, mu, A)
    s = _finite("s", s)
    mat = make_material(model, Jm)
    L1, H, L3 = size
    pm = plate_mesh(L1, H, L3, *elements, symmetry=symmetry, grading=grading)
    prob = PlateProblem(pm, mat, loading="uniaxial", control=control, formulation=formulation,
                        kappa=kappa, phi_element=phi_element, threads=threads)
    targets = _targets(s, D0, preload_steps)
    return _run(prob, targets, on_step=on_step, x0=x0, start=start, linear_solver=linear_solver,
                phase_of=lambda ld: "preload" if ld[1] == 0 else "charge",
                extra={"alpha": alpha if alpha is not None else float("nan"), "g": g},
                atol=0.0, rtol=rtol, max_cutbacks=max_cutbacks, max_iter=max_iter,
                stop_on_instability=stop_on_instability)

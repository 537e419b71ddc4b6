"""Voltage control of the homogeneous plates through the snap-through (limit point).

Under voltage control at a fixed dead load ``s`` the field ``E0`` has a maximum along the
loading curve: there the Hessian ``H*`` of the voltage-controlled free energy becomes
singular (``det H* = 0``, Sec. 3.1; Sec. 5 and Fig. figde for the uni-axial load) and a
voltage ramp snaps through.  Under charge control the same states are stable: the
Hessian of the charge-controlled energy stays positive definite (the paper's central
result, Sec. 3).  :func:`voltage_snap_through` computes both by finite elements:

1. the voltage-controlled plate (``PlateProblem(control="voltage")``) is pre-loaded to
   ``(s, 0)`` and followed in ``E0`` by pseudo-arclength continuation
   (:func:`~skfem_dielectric.solvers.continuation.continuation`) through the maximum of ``E0``,
   which is located as a limit point (``dE0/ds = 0``);
2. at every point the negative-eigenvalue count of the voltage-controlled reduced
   stiffness is taken, and, for the *same* state read as a charge-controlled one
   (``D0 = |D_L| / sqrt(mu eps)`` of the state, the potential free on the faces), the
   count of the charge-controlled reduced stiffness.

Both counts are taken on the grad-div stabilised tangent (``grad_div``, units of ``mu``):
it removes the spurious mesh-scale surface modes of Q2/Q1 and, ``J = 1`` holding
exactly in a homogeneous state, is the Hessian of the same state (docs/stability.md).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..checks import check_choice, check_finite, check_positive
from ..fem.mesh import plate_mesh
from ..materials import make_material
from ..models.plate.problem import PlateProblem
from ..solvers.continuation import (ContinuationPoint, ContinuationResult, ContinuationSettings,
                                    continuation)
from ..solvers.newton import check_settings
from ..solvers.ramp import ramp
from ..stability.analysis import tangent_stability

__all__ = ["SNAP_THROUGH_SETTINGS", "homogeneous_plate", "SnapThrough", "voltage_snap_through"]

HOMOGENEOUS_LOADINGS = ("equibiaxial", "uniaxial-free")

#: How :func:`voltage_snap_through` steps along the path: arclength step 0.05, at most 150
#: steps (the stop criteria end the homogeneous paths well before), otherwise the defaults
#: of :class:`~skfem_dielectric.solvers.continuation.ContinuationSettings`.
SNAP_THROUGH_SETTINGS = ContinuationSettings(ds=0.05, max_steps=150)


def homogeneous_plate(loading: str = "equibiaxial", control: str = "voltage", *,
                      model: Any = "neo-Hookean", Jm: float = 97.2,
                      size: tuple[float, float, float] = (4.0, 1.0, 4.0),
                      elements: tuple[int, int, int] = (1, 1, 1), **options) -> PlateProblem:
    """An eighth of a plate under an equi-biaxial (``"equibiaxial"``) or uni-axial
    (``"uniaxial-free"``: traction on the ``x1`` faces, ``x3`` faces free) dead load.

    The state is homogeneous, so one element suffices (the mixed Q2/Q1 element
    reproduces it to solver tolerance).  ``options`` go to
    :class:`~skfem_dielectric.models.plate.problem.PlateProblem`.
    """
    check_choice("loading", loading, HOMOGENEOUS_LOADINGS)
    pm = plate_mesh(*size, *elements, symmetry="eighth")
    return PlateProblem(pm, make_material(model, Jm), loading=loading, control=control,
                        **options)


@dataclass
class SnapThrough:
    """The voltage-controlled path of a homogeneous plate and the counts along it.

    Attributes
    ----------
    path
        The continuation in ``E0`` at fixed ``s`` (every point, the limit points located).
    n_negative_voltage
        Negative eigenvalues of the voltage-controlled reduced stiffness per point.
    n_negative_charge
        The same for the charge-controlled stiffness at the same states (``None`` entries
        if not computed).
    D0
        ``D0`` of every state (the charge that holds it under charge control).
    charge_residual
        ``||r|| / residual_scale`` of each state in the charge-controlled problem (an
        equilibrium there to solver tolerance).
    s, loading
        Dead load and loading of the plate.
    wall_seconds
        Wall time of the continuation.
    """

    path: ContinuationResult
    n_negative_voltage: list[int | None]
    n_negative_charge: list[int | None]
    D0: np.ndarray
    charge_residual: np.ndarray
    s: float
    loading: str
    wall_seconds: float = 0.0

    @property
    def limit(self) -> ContinuationPoint | None:
        """The first located limit point (the maximum of ``E0``), ``None`` if none."""
        pts = self.path.limit_points
        return pts[0] if pts else None

    @property
    def lam1_max(self) -> float:
        """``lam1`` at the maximum of ``E0`` (``nan`` without a limit point)."""
        return float("nan") if self.limit is None else float(self.limit["lam1"])

    @property
    def E0_max(self) -> float:
        """The maximum of ``E0`` (``nan`` without a limit point)."""
        return float("nan") if self.limit is None else float(self.limit.t)


def _counter(problem: PlateProblem, grad_div: float):
    def count(x, load):
        return int(tangent_stability(problem, problem.stabilised_tangent(x, load, grad_div))
                   .n_negative)
    return count


def voltage_snap_through(s: float, *, loading: str = "equibiaxial",
                         model: Any = "neo-Hookean", Jm: float = 97.2,
                         grad_div: float = 10.0, lam_factor: float = 2.0,
                         E0_max: float = 10.0, charge: bool = True,
                         stop_after_limit: bool = False, coupling: str = "full",
                         settings: ContinuationSettings = SNAP_THROUGH_SETTINGS,
                         linear_solver: str = "superlu") -> SnapThrough:
    """Voltage-controlled path of the homogeneous plate at dead load ``s`` through the
    maximum of ``E0``, with the stability counts under voltage and charge control.

    Parameters
    ----------
    s
        Dimensionless dead load (equi-biaxial ``t/mu``, uni-axial ``t1/mu``).
    loading
        ``"equibiaxial"`` (Eq. loading_gent) or ``"uniaxial-free"`` (Eq. DEuniax).
    model, Jm
        ``"neo-Hookean"``, ``"Gent"`` (with ``Jm``) or a material object.
    grad_div
        Grad-div stabilisation of the counted tangents (units of ``mu``, > 0).
    lam_factor, E0_max
        The path ends when ``lam1`` exceeds ``lam_factor`` times its pre-loaded value,
        when ``E0`` falls below zero, or when ``E0 > E0_max``.
    charge
        Also count the charge-controlled stiffness at every state (full coupling).
    stop_after_limit
        End the path at the first point after the first limit point.
    coupling
        ``"full"`` or ``"maxwell"`` (the Maxwell traction of the solved field; its tangent
        is not symmetric, so no counts are taken).
    settings
        How the continuation steps (default :data:`SNAP_THROUGH_SETTINGS`; e.g.
        ``replace(SNAP_THROUGH_SETTINGS, ds=0.1)`` for a coarser path).
    linear_solver
        Solver of the continuation's bordered systems.

    Returns
    -------
    SnapThrough
        ``limit`` is ``None`` where ``E0`` grows monotonically (Gent above the threshold
        of ``analytic.no_maximum_threshold``).
    """
    s = check_finite("s", s)
    check_choice("loading", loading, HOMOGENEOUS_LOADINGS)
    grad_div = check_positive("grad_div", grad_div)
    lam_factor = check_positive("lam_factor", lam_factor)
    check_settings("settings", settings, ContinuationSettings)
    pb = homogeneous_plate(loading, "voltage", model=model, Jm=Jm, coupling=coupling)
    full = coupling == "full"
    pre = ramp(pb, [np.array([s, 0.0])])
    lam0 = pre.steps[-1]["lam1"] if pre.steps else 1.0

    def stop(p):
        # E0 starts increasing: a negative dE0/ds is the path past its first maximum
        return (p["lam1"] > lam_factor * lam0 or p.t < 0.0
                or (stop_after_limit and p.tangent_t < 0))

    path = continuation(pb, np.array([s, 0.0]), np.array([0.0, 1.0]),
                        x0=pre.x if pre.steps else None, t_max=E0_max, stop=stop,
                        settings=settings, count=_counter(pb, grad_div) if full else False,
                        linear_solver=linear_solver)
    n_c: list[int | None] = []
    D0, res = [], []
    cpb = homogeneous_plate(loading, "charge", model=model, Jm=Jm) if charge and full else None
    for p in path.points:
        D0.append(np.sign(p.t) * p["D0_centre"])
        if cpb is None:
            n_c.append(None)
            res.append(np.nan)
            continue
        xc = cpb.red.restrict(pb.full(p.x, p.load))
        ld = np.array([s, D0[-1]])
        res.append(float(np.linalg.norm(cpb.residual(xc, ld)) / cpb.residual_scale(ld)))
        n_c.append(_counter(cpb, grad_div)(xc, ld))
    return SnapThrough(path, [p.n_negative for p in path.points], n_c, np.array(D0),
                       np.array(res), s, loading, wall_seconds=path.wall_seconds)


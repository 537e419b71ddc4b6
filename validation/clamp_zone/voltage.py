"""The clamped plate under voltage control, unit by unit: where a unit's plate snaps through
when the voltage (``E0``) is prescribed instead of the charge.

A *voltage unit* is the plate of a clamp-zone unit (the same key: weight fraction, eighth
mesh, grading along ``x1``, formulation; neo-Hookean, ``g = 9.81``; grad-div 10 as the units
or another weight, ``0`` the plain mixed form) with the
potential difference prescribed: pre-loaded by its weight, then followed in ``E0`` at fixed
``s`` by pseudo-arclength continuation
(:func:`~skfem_dielectric.solvers.continuation.continuation`) through its first limit
point, located to ``|dE0/darc| <= 1e-9``.  Every point is scanned for the whole plate's
spectrum (:class:`~skfem_dielectric.models.plate.scan.PlateScan`: inertia counts per
symmetry class of the voltage-controlled stiffness, the modes that cross classified).  The
row holds

* the limit point: ``E0_limit``, ``D0_limit`` (the charge at the plate's centre there),
  ``lam1_limit`` (the stretch at the centre) and the range of ``J = det F`` over every
  quadrature point there (``J_min_limit``, ``J_max_limit``; the material is
  incompressible, so a discrete state far from ``J = 1`` is not the continuum's); beside
  it the homogeneous uni-axial limit :func:`analytic.max_E0` at the same ``s``
  (``max_E0``, ``lam1_max_E0``) and their ratio;
* ``E0_membrane``: the limit of the clamped membrane (:func:`membrane_voltage_limit`), an
  independent cross-check;
* the first point of the path with a physical negative mode (``E0_physical``, the charge
  at the centre there ``D0_physical``, and the mode's class) and the point before it
  (``E0_stable``, ``D0_stable``): the crossing lies between them (the path's steps, not
  located), to compare with the charge-controlled ``D0_b``; empty where none crosses
  before the limit;
* the first point of the path with a negative mode that the dead load alone does not have:
  its ``E0_first``, the mode's eigenvalue, class, kind (physical, clamp corner or mesh
  scale: :func:`~skfem_dielectric.models.plate.modes.classify_mode`), corner share, mesh
  scale and energy centroid ``X1, X2, X3`` with its element layer counted from the clamp
  (1: the element that touches it); empty where no mode crosses before the limit;
* the path's points and Newton iterations, the unknowns and the costs.

The rows go to the ``voltage`` table (:data:`~validation.data.registry.TABLES`);
``skfem-dielectric clamp-zone voltage`` runs the units not yet there (docs/clamp-zone.md).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

import analytic as an
import skfem_dielectric as fe
from skfem_dielectric.kinematics import det3
from skfem_dielectric.models.plate.scan import PlateScan

from ..data.key import UnitKey, mesh_text
from ..data.registry import TABLES
from ..fe.model import BUCKLING_GRAD_DIV
from .costs import Meter
from .local_theory import energy_centroid
from .units import UNIT_SETTINGS, charge_path, unit_problem, unit_ramp

__all__ = ["COLUMNS", "VOLTAGE_SETTINGS", "MEMBRANE_MESH", "run_voltage",
           "membrane_voltage_limit"]

#: the membrane mesh of :func:`membrane_voltage_limit` (Q2 elements on the quarter
#: mid-surface): its limit agrees with that of twice the elements to 1e-6
MEMBRANE_MESH = (20, 10)

#: the columns of a row, in order (the ``voltage`` table)
COLUMNS = TABLES["voltage"].columns

#: how a voltage unit's path is stepped: arclength steps of 0.05 (in the metric of the
#: displacements' mean and ``E0``), correctors with the units' Newton settings
VOLTAGE_SETTINGS = fe.ContinuationSettings(
    ds=0.05, max_steps=120, locate_tol=1e-9,
    corrector=fe.NewtonSettings(atol=UNIT_SETTINGS.atol, rtol=UNIT_SETTINGS.rtol,
                                max_iter=UNIT_SETTINGS.max_iter))


def membrane_voltage_limit(alpha: float, elements=MEMBRANE_MESH, *,
                           settings=VOLTAGE_SETTINGS) -> tuple[float, float]:
    """The voltage-controlled limit ``(E0, lam1)`` of the clamped membrane: the 2D model of
    the plate (:class:`~skfem_dielectric.models.membrane.MembranePlate`, plane stress, exact
    incompressibility, the rigid clamp of the Keplinger experiment, no through-thickness
    field), pre-loaded by the weight of ``alpha`` (``g = 9.81``), then followed in ``E0``
    through its first limit point; ``lam1`` at the centre.  A cross-check of the 3D
    units that shares none of their discretisation: a membrane has no clamp corner
    through the thickness and no out-of-plane mode.

    Parameters
    ----------
    alpha : float
        Weight fraction (``>= 0``).
    elements : tuple of int
        Q2 elements ``(n1, n3)`` on the quarter mid-surface (default :data:`MEMBRANE_MESH`).
    settings : ContinuationSettings
        How the path is stepped.

    Returns
    -------
    tuple of float
        ``(nan, nan)`` where the path stops before a limit point.

    Examples
    --------
    >>> E0, lam1 = membrane_voltage_limit(1.0)
    >>> round(E0, 4), round(lam1, 3)
    (0.2906, 3.354)
    """
    if not (math.isfinite(float(alpha)) and float(alpha) >= 0):
        raise ValueError(f"alpha must be non-negative and finite, got {alpha!r}")
    s = fe.gallery.keplinger_s(float(alpha), g=9.81)
    n1, n3 = (int(n) for n in elements)
    pb = fe.MembranePlate(fe.membrane_mesh(100.0, 1.0, 50.0, n1, n3),
                          fe.NeoHookeanDielectric(1.0, 1.0), loading="uniaxial",
                          control="voltage")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)     # a stopped path is data
        pre = fe.ramp(pb, charge_path(s, []))               # the units' pre-load steps
        if not pre.converged:
            return math.nan, math.nan
        path = fe.continuation(pb, np.array([s, 0.0]), np.array([0.0, 1.0]), x0=pre.x,
                               count=False, stop=lambda p: p.tangent_t < 0,
                               settings=settings)
    if not path.limit_points:
        return math.nan, math.nan
    lim = path.limit_points[0]
    return float(lim.t), float(lim["lam1"])


def run_voltage(key: UnitKey, *, grad_div: float = BUCKLING_GRAD_DIV, solver: str = "auto",
                settings=VOLTAGE_SETTINGS, progress=None) -> dict:
    """One voltage unit: the row of :data:`COLUMNS` (module docstring).

    Parameters
    ----------
    key : UnitKey
        The unit (:class:`~validation.data.key.UnitKey`): weight fraction, eighth-model
        mesh, grading along ``x1`` and formulation.
    grad_div
        The plate's grad-div weight (units of ``mu``; default that of the units,
        :data:`~validation.fe.model.BUCKLING_GRAD_DIV`; ``0``: the plain mixed form).
    solver
        Linear solver of the pre-load and the continuation's bordered systems.
    settings : ContinuationSettings
        How the path is stepped (default :data:`VOLTAGE_SETTINGS`).
    progress
        Optional ``progress(text)`` called once per point of the path.

    Returns
    -------
    dict
        The columns; ``E0_limit`` is ``nan`` and ``note`` says why where the path stopped
        before a limit point (the pre-load or a corrector failed, or the step budget).
    """
    meter = Meter()
    alpha, el = key.alpha, key.mesh
    if not (math.isfinite(float(grad_div)) and float(grad_div) >= 0):
        raise ValueError(f"grad_div must be non-negative and finite, got {grad_div!r}")
    pb, s = unit_problem(alpha, el, grading=key.grading, formulation=key.formulation,
                         grad_div=grad_div, control="voltage")
    row = {"alpha": alpha, "mesh": mesh_text(el), "grading": key.grading,
           "formulation": key.formulation, "grad_div": grad_div, "dofs": pb.ndofs, "s": s}
    lam_h, E0_h = (float(v) for v in an.max_E0(s, loading="uniaxial"))
    row.update(max_E0=E0_h, lam1_max_E0=lam_h)
    pre = unit_ramp(pb, charge_path(s, []), on_step=lambda step: None, solver=solver)
    if not pre.converged:
        row.update(E0_limit=math.nan, note=f"pre-load stopped at s = "
                                           f"{np.asarray(pre.failed_at)[0]:g}")
        row.update(meter.columns(solver))
        return row
    scan, scanned = PlateScan(pb), {}

    def count(x, load):
        r = scan.analyse(x, load)
        scanned[float(load[1])] = (r, x.copy(), np.asarray(load, float))
        if progress is not None:
            progress(f"E0 = {load[1]:.5f}: {r.n_negative} negative "
                     f"({r.n_physical} physical), {r.cpu:.1f} CPU s")
        return r.n_negative

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)     # a stopped path is data
        path = fe.continuation(pb, np.array([s, 0.0]), np.array([0.0, 1.0]), x0=pre.x,
                               count=count, stop=lambda p: p.tangent_t < 0,
                               settings=settings, linear_solver=solver)
    limits = path.limit_points
    row.update(points=len(path.points), iterations=path.iterations_total)
    if not limits:
        row.update(E0_limit=math.nan,
                   note=path.reason or f"no limit point in {len(path.points)} points")
        row.update(meter.columns(solver))
        return row
    lim = limits[0]
    J = np.concatenate([det3(F).ravel()
                        for _, F, _, _ in pb.quadrature_fields(lim.x, lim.load)])
    row.update(J_min_limit=float(J.min()), J_max_limit=float(J.max()))
    row.update(E0_limit=lim.t, D0_limit=lim["D0_centre"], lam1_limit=lim["lam1"],
               ratio=lim.t / E0_h, E0_membrane=membrane_voltage_limit(alpha)[0])
    # the scanned points in the path's order up to the limit point (the scan saw the
    # point past the limit before the located limit point)
    k = next(j for j, p in enumerate(path.points) if p is lim)
    before = [(p.t, *scanned[p.t]) for p in path.points[:k + 1] if p.t in scanned]
    start = before[0][1].n_negative
    first = next(((E0, r, x, load) for E0, r, x, load in before
                  if r.n_negative > start and r.labels), None)
    row["n_negative_start"] = start
    i = next((i for i, (E0, r, _, _) in enumerate(before) if r.n_physical > 0), None)
    if i is not None:
        E0, r, x, load = before[i]
        m = next((m for m in r.labels if m.kind == "physical"), None)
        row.update(E0_physical=E0, D0_physical=pb.postprocess(x, load)["D0_centre"],
                   physical_class=m.symmetry if m is not None else "")
        if i > 0:                   # the bracket's lower end: the point before it
            E0, _, x, load = before[i - 1]
            row.update(E0_stable=E0, D0_stable=pb.postprocess(x, load)["D0_centre"])
    if first is not None:
        E0, r, x, load = first
        m = r.labels[0]
        c = energy_centroid(pb, x, load, m.mode)
        g1 = pb.plate.grids[0]
        row.update(E0_first=E0, first_eigenvalue=m.eigenvalue, first_class=m.symmetry,
                   first_kind=m.kind, first_corner_share=m.corner_share,
                   first_mesh_scale=m.mesh_scale, first_X1=float(c[0]),
                   first_X2=float(c[1]), first_X3=float(c[2]),
                   first_layer=int(np.count_nonzero(g1 > c[0])))
    row.update(meter.columns(solver))
    return row

"""How incompressible the clamp layer is at the clamp-zone wrinkle's onset, per mesh.

The incompressible plate has ``J = det F = 1`` everywhere.  The mixed form imposes it
weakly, ``integral q (J - 1) dV = 0`` for every continuous ``Q1`` pressure test function
``q``: the discrete ``J`` at a point is not one, and next to the clamp -- where the clamped
face meets the free faces along a line, a singular edge of the incompressible solid -- it
departs from one by a few per cent in the first elements on every mesh.  What the
formulation constrains is the volume, and this study measures both at the located onset
``D0_b`` of a clamp-zone unit (the ``units`` table):

* ``J_first_min``, ``J_first_max``: the volume ratio (mean ``J``) of each element next to
  the clamp (the last element along ``x1``, every element across ``x2`` and ``x3``);
* ``J_second_min``, ``J_second_max``: the same for the second element layer;
* ``J_centre_min``, ``J_centre_max``: ``J`` at the mid-plane centres of the elements next
  to the clamp (the clamp-zone study's ``J_min_clamp``, ``J_max_clamp``);
* ``V_<d>mm``: the volume ratio of the clamp layer ``L - d < X1 < L`` (``d`` = 0.5, 1 and
  2 mm: half, one and two plate thicknesses), by the quadrature points inside it;
* ``V_plate``: the volume ratio of the whole model (the constant is a ``Q1`` test
  function: one to the Newton tolerance).

The rows go to the ``layer`` table, one per unit (``skfem-dielectric clamp-zone layer``);
a unit already there is skipped.
"""

from __future__ import annotations


import numpy as np

from .costs import Meter
from ..data.clamp_zone import unit_row
from ..data.registry import LAYER_WIDTHS, TABLES
from ..data.key import UnitKey, mesh_text
from .units import clamp_centre_J, ramp_to_charge, unit_problem

__all__ = ["COLUMNS", "LAYER_WIDTHS", "volume_ratios", "run_layer"]

#: the columns of a row, in order (the ``layer`` table)
COLUMNS = TABLES["layer"].columns


def volume_ratios(problem, x: np.ndarray, load) -> dict:
    """``J`` and volume ratios at the clamp of a plate state (the module docstring).

    Parameters
    ----------
    problem : PlateProblem
        The plate (mixed form: its ``form`` has the ``Q2`` displacement basis ``b2``).
    x : ndarray
        Reduced state vector of a converged step.
    load : tuple
        Its load ``(s, D0)``.

    Returns
    -------
    dict
        The ``J_first_*``, ``J_second_*``, ``V_<d>mm`` and ``V_plate`` columns; ``J`` is
        ``det(I + grad u)`` at the quadrature points, a volume ratio is
        ``integral J dX / integral dX`` over the set.
    """
    xf = problem.full(x, load)
    b2 = problem.form.b2
    u = xf[:problem.form.n_u].reshape(b2.N, 3)
    grad = np.array([b2.interpolate(u[:, i]).grad for i in range(3)])       # (i, j, e, q)
    F = grad + np.eye(3)[:, :, None, None]
    J = np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))                     # (e, q)
    w = np.asarray(b2.dx)
    X1 = np.asarray(b2.global_coordinates())[0]                             # (e, q)
    g1 = problem.plate.grids[0]
    centre = b2.mesh.p[0, b2.mesh.t].mean(axis=0)
    out = {}
    for k, name in ((1, "first"), (2, "second")):
        sel = (centre > g1[-k - 1]) & (centre < g1[-k])
        mean = (J[sel] * w[sel]).sum(axis=1) / w[sel].sum(axis=1)
        out[f"J_{name}_min"], out[f"J_{name}_max"] = float(mean.min()), float(mean.max())
    for d in LAYER_WIDTHS:
        m = X1 > g1[-1] - d
        out[f"V_{d:g}mm"] = float((J[m] * w[m]).sum() / w[m].sum())
    out["V_plate"] = float((J * w).sum() / w.sum())
    return out


def run_layer(key: UnitKey, *, solver: str = "auto", D0: float | None = None,
                    units=None) -> dict:
    """One unit: the charge ramp (steps of 0.5) to ``D0`` and the row of :data:`COLUMNS`.

    Parameters
    ----------
    key : UnitKey
        The unit (:class:`~validation.data.key.UnitKey`): weight fraction, eighth-model
        mesh, grading along ``x1`` and formulation (eighth model, grad-div 10).
    solver
        Linear solver of the ramp.
    D0
        The charge; ``None``: the unit's ``D0_b`` in the ``units`` table ``units`` (a file or
        folder) or else the shipped one (:func:`~validation.data.clamp_zone.unit_row`).

    Raises
    ------
    ValueError
        ``D0`` is ``None`` and the unit has no located ``D0_b``; the ramp stops first.
    """
    meter = Meter()
    alpha, elements, grading, formulation = key.alpha, key.mesh, key.grading, key.formulation
    el = tuple(int(n) for n in elements)
    if D0 is None:
        unit = unit_row(key, units)
        if not unit["D0_b"]:
            raise ValueError(f"the clamp-zone unit alpha = {alpha:g} {mesh_text(el)} has no "
                             f"located D0_b")
        D0 = float(unit["D0_b"])
    D0 = float(D0)
    pb, s = unit_problem(alpha, el, grading=grading, formulation=formulation)
    x, load = ramp_to_charge(pb, s, D0, solver=solver,
                             name=f"alpha = {alpha:g} {mesh_text(el)}")
    j_min, j_max = clamp_centre_J(pb, x, load)
    row = {"alpha": alpha, "mesh": mesh_text(el), "grading": grading,
           "formulation": formulation, "dofs": pb.ndofs, "D0": D0,
           **volume_ratios(pb, x, load), "J_centre_min": j_min, "J_centre_max": j_max,
           **meter.columns(solver)}
    return row

"""Where the whole plate's flagged negative modes sit at one state of a clamp-zone unit.

The scan of a unit (:mod:`validation.clamp_zone.units`) flags negative modes that are not
physical (:func:`~skfem_dielectric.models.plate.modes.classify_mode`: a clamp-corner or a
mesh-scale mode) and only counts them.  This study takes one state of a unit -- the plate
(eighth model, grad-div 10, graded along ``x1``), ramped in steps of 0.5 to ``D0`` --
analyses it from scratch (:meth:`~skfem_dielectric.models.plate.scan.PlateScan.analyse`:
every negative mode of every class computed and classified) and writes a row per negative
mode (one row of ``kind`` ``none`` where there is none): its eigenvalue, class, label
(``kind``, ``corner_share``, ``mesh_scale``) and the
energy centroid of its deflection (``X1``, ``X2``, ``X3``,
:func:`validation.clamp_zone.local_theory.energy_centroid`), with the unit's element layers
at the clamp (``layer``: 1 for the element next to the clamp, 2 the next, ...).

The rows go to the ``flagged`` table, one block per state (``alpha``, mesh, ``grading``,
``D0``), when the state is analysed (``skfem-dielectric clamp-zone flagged``); a state
already there is skipped.
"""

from __future__ import annotations

import datetime
import time

import numpy as np

from skfem_dielectric.models.plate.scan import PlateScan

from ..data.registry import TABLES
from ..data.key import UnitKey, mesh_text
from .units import ramp_to_charge, unit_problem
from .local_theory import energy_centroid

__all__ = ["COLUMNS", "run_flagged"]

#: the columns of a row, in order (the ``flagged`` table)
COLUMNS = TABLES["flagged"].columns


def run_flagged(key: UnitKey, D0: float, *, solver: str = "auto") -> list[dict]:
    """The rows of one state: every negative mode of the whole plate at ``D0``.

    Parameters
    ----------
    key : UnitKey
        The unit (:class:`~validation.data.key.UnitKey`): weight fraction, eighth-model
        mesh, grading along ``x1`` and formulation (eighth model, mixed form,
        grad-div 10; the formulation is not used).
    D0
        The charge of the state (reached in steps of 0.5).
    solver
        Linear solver of the ramp.

    Returns
    -------
    list of dict
        In increasing eigenvalue; a state without negative modes has one row of
        ``kind`` ``"none"`` (the mode columns empty).

    Raises
    ------
    ValueError
        The ramp stops before ``D0``.
    """
    alpha, grading, el = key.alpha, key.grading, key.mesh
    pb, s = unit_problem(alpha, el, grading=grading)
    x, load = ramp_to_charge(pb, s, D0, solver=solver,
                             name=f"alpha = {alpha:g} {mesh_text(el)}")
    t0 = time.process_time()
    row = PlateScan(pb).analyse(x, load)
    g1 = pb.plate.grids[0]
    out = []
    for m in row.labels:
        c = energy_centroid(pb, x, load, m.mode)
        layer = int(np.count_nonzero(g1 > c[0]))        # 1: inside the last element
        out.append({"alpha": alpha, "mesh": mesh_text(el), "grading": grading, "D0": D0,
                    "dofs": pb.ndofs, "eigenvalue": m.eigenvalue, "class": m.symmetry,
                    "kind": m.kind, "corner_share": m.corner_share,
                    "mesh_scale": m.mesh_scale, "X1": float(c[0]), "X2": float(c[1]),
                    "X3": float(c[2]), "layer": layer})
    if not out:                 # a state without negative modes: one row that says so
        out.append({"alpha": alpha, "mesh": mesh_text(el), "grading": grading, "D0": D0,
                    "dofs": pb.ndofs, "kind": "none"})
    cpu = round(time.process_time() - t0, 1)
    today = datetime.date.today().isoformat()
    for r in out:
        r.update(cpu_s=cpu, date=today)
    return out

"""The clamp edge resolved: the (X1, X2) section next to the clamp against waves along X3.

For a weight fraction ``alpha`` and a charge ``D0`` the clamped plate (eighth model,
neo-Hookean, ``g = 9.81``, graded along ``x1``) is ramped to ``D0`` on a 3D mesh; the
section ``[50 - length, 50] x [-H/2, H/2]`` at the plate's centre plane then solves its own
base state with elements of side ``h0`` at the two clamp edges, graded away from them
(the 3D state on the cut and on the clamp, ``F_33`` from it), by continuation along the 3D
ramp's converged states ``D0 = 0, 0.5, 1, ...``
(:func:`~skfem_dielectric.studies.section_base.continue_section_base`), and counts the negative eigenvalues of its energy
against ``cos kX3`` / ``sin kX3`` waves for each ``k`` of ``--k``
(:class:`~skfem_dielectric.models.edge_section.EdgeSection`).  A physical edge instability
is a band of ``k`` with negative modes whose edges converge as ``h0`` is halved; an
artefact of the discretisation is not.

A row per ``(state, h0, k)``:

* ``alpha``, ``mesh``, ``grading``, ``grad_div`` (units of ``mu``), ``D0``: the 3D state;
  ``length``, ``h0``: the section and its edge elements (mm, ``H = 1``); ``k``: the
  wavenumber per reference length along ``X3`` (``2 pi / k`` is the reference wavelength);
* ``section_dofs``; ``n_negative``: the negative modes at ``k``;
* ``base_iterations`` (Newton steps of the whole continuation); ``J_min``, ``J_max``: ``det F`` of the section's base state at its
  quadrature points (1 in the continuum); ``F11_section``, ``F11_3d``: ``F11`` at
  ``(50 - length / 2, 0)`` in the section and in the 3D state (the two agree where both
  resolve); ``J_min <= 0``: the discrete base state has inverted elements (at the singular
  edge), is no state of the plate, and its counts decide nothing;
* ``count_cpu_s`` (this ``k``), ``base_cpu_s`` (the section's base state), ``state_cpu_s``
  (the 3D ramp), ``peak_GB``, ``date``, ``command``.

The rows go to the ``section`` table as each section mesh is done
(``skfem-dielectric clamp-zone section``); a key already there is skipped.
"""

from __future__ import annotations

import datetime
import math
import time

import numpy as np

from skfem_dielectric.fem import blas_thread_limit
from skfem_dielectric.studies.section_base import continue_section_base
from skfem_dielectric.models.edge_section import (EdgeSection, edge_section_grids,
                                                  plate_fields)

from ..fe.model import BUCKLING_GRAD_DIV
from .costs import peak_GB
from ..data.registry import TABLES
from ..data.key import UnitKey, mesh_text
from .units import ramp_states, unit_problem

__all__ = ["COLUMNS", "DEFAULT_K", "run_section", "check_section_size", "MIN_H0",
           "PLATE_HALF_LENGTH"]

#: the eighth model's length along ``X1`` (mm): the section cannot be longer
PLATE_HALF_LENGTH = 50.0
#: the finest edge element of the section (mm): below it scikit-fem's facet-basis inverse
#: map (an absolute tolerance) fails at ``X1 = 50``
MIN_H0 = 0.01

#: from the plate's width (k = 2 pi / 50) to far past the 3D meshes' cut-off
DEFAULT_K = tuple(float(f"{k:.4g}") for k in np.geomspace(2 * math.pi / 50, 200.0, 25))
#: the columns of a row, in order (the ``section`` table)
COLUMNS = TABLES["section"].columns
_key = TABLES["section"].key_of


def check_section_size(length: float, h0s, *, names=("length", "h0")) -> None:
    """``ValueError`` naming ``names`` unless the section fits the eighth model
    (``length`` at most :data:`PLATE_HALF_LENGTH`) and its edge elements are at least
    :data:`MIN_H0` (``h0s``); the command line passes its option names."""
    if length > PLATE_HALF_LENGTH:
        raise ValueError(f"{names[0]} must be at most the eighth model's "
                         f"{PLATE_HALF_LENGTH:g} mm, got {length:g}")
    if min(h0s) < MIN_H0:
        raise ValueError(f"{names[1]} must be at least {MIN_H0:g} mm (finer edge elements "
                         f"fail in scikit-fem's facet-basis inverse map), got {min(h0s):g}")


def run_section(key: UnitKey, D0: float, h0s, ks=DEFAULT_K, *,
                     grad_div: float = BUCKLING_GRAD_DIV,
                     length: float = 5.0, solver: str = "auto", done=frozenset(),
                     on_rows=None, progress=None, pressure: str = "Q1") -> list[dict]:
    """The rows of :data:`COLUMNS` for one 3D state and every ``h0`` x ``k``.

    Parameters
    ----------
    key : UnitKey
        The unit (:class:`~validation.data.key.UnitKey`): weight fraction, eighth-model
        mesh, grading along ``x1`` and formulation (the formulation is not used).
    grad_div
        The plate's grad-div weight (:func:`~validation.clamp_zone.units.unit_problem`).
    pressure
        The section's pressure space, ``"Q1"`` or ``"P0"``
        (:data:`~skfem_dielectric.models.edge_section.PRESSURES`; the 3D ramp keeps Q1).
    D0
        The charge of the state (``>= 0``; ``0``: the dead load alone).
    h0s, ks
        Edge element sizes of the section (mm, positive) and wavenumbers (positive).
    length
        The section's length along ``X1`` (mm).
    solver
        Linear solver of the 3D ramp.
    done
        Keys (:data:`COLUMNS` up to ``k``, as written) not to compute again.
    on_rows, progress
        Optional ``on_rows(rows)`` after each ``h0`` (the caller writes them) and
        ``progress(text)``.

    Raises
    ------
    ValueError
        A negative ``D0``, a non-positive ``h0``, ``k`` or ``length``; the ramp stopping before
        ``D0``; the section's base state not converging.
    """
    alpha, elements, grading = key.alpha, key.mesh, key.grading
    if not (math.isfinite(float(D0)) and float(D0) >= 0):
        raise ValueError(f"D0 must be non-negative and finite, got {D0!r}")
    for name, vals in (("h0", h0s), ("k", ks), ("length", [length])):
        for v in vals:
            if not (math.isfinite(float(v)) and float(v) > 0):
                raise ValueError(f"{name} must be positive and finite, got {v!r}")
    check_section_size(length, h0s)
    el = tuple(int(n) for n in elements)
    base_row = {"alpha": alpha, "mesh": mesh_text(el), "grading": grading,
                "grad_div": grad_div, "pressure": pressure, "D0": float(D0), "length": length}
    todo = [(h, k) for h in h0s for k in ks
            if _key({**base_row, "h0": h, "k": k}) not in done]
    if not todo:
        return []
    t0 = time.process_time()
    pb, s = unit_problem(alpha, el, grading=grading, grad_div=grad_div)
    with blas_thread_limit(1):
        states = ramp_states(pb, s, D0, solver=solver,
                             name=f"alpha = {alpha:g} {mesh_text(el)}")
    path = [(d, plate_fields(pb, pb.full(x, load))) for d, x, load in states]
    fields = path[-1][1]
    state_cpu = time.process_time() - t0
    mid = (np.array([50.0 - length / 2]), np.array([0.0]))
    F11_3d = float(fields(*mid)["F"][0, 0, 0])
    rows = []
    for h0 in sorted(set(h0s), reverse=True):
        ks_h = [k for (h, k) in todo if h == h0]
        if not ks_h:
            continue
        t1 = time.process_time()
        g1, g2 = edge_section_grids(50.0, length, 1.0, h0)
        try:
            sb = continue_section_base(g1, g2, pb.material, path, grad_div=pb.grad_div,
                                       pressure=pressure)
            sec = EdgeSection(g1, g2, pb.material, sb.base, grad_div=pb.grad_div,
                              pressure=pressure)
        except Exception as exc:        # scikit-fem's inverse map raises a bare Exception
            if type(exc) is not Exception or "Newton iteration" not in str(exc):
                raise
            raise ValueError(f"h0 = {h0:g}: scikit-fem's facet-basis inverse map did not "
                             f"converge on the section (its tolerance is absolute); use a "
                             f"larger --h0") from None
        base_cpu = time.process_time() - t1
        F11_sec = float(sb.fields(*mid)["F"][0, 0, 0])
        out = []
        for k in ks_h:
            t2 = time.process_time()
            n = sec.count(k)
            out.append({**base_row, "h0": h0, "k": k, "section_dofs": int(sec.free.sum()),
                        "n_negative": n, "base_iterations": sb.iterations,
                        "J_min": round(float(sec.base_J.min()), 4),
                        "J_max": round(float(sec.base_J.max()), 4),
                        "F11_section": round(F11_sec, 5), "F11_3d": round(F11_3d, 5),
                        "count_cpu_s": round(time.process_time() - t2, 2),
                        "base_cpu_s": round(base_cpu, 1), "state_cpu_s": round(state_cpu, 1),
                        "peak_GB": peak_GB(),
                        "date": datetime.date.today().isoformat()})
        if progress is not None:
            neg = [f"{r['k']:g}:{r['n_negative']}" for r in out if r["n_negative"]]
            progress(f"h0 = {h0:g}: {out[0]['section_dofs']} unknowns, base in "
                     f"{sb.iterations} steps, negative at k = {' '.join(neg) or 'none'}")
        rows += out
        if on_rows is not None:
            on_rows(out)
    return rows

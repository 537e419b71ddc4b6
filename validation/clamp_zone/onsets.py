"""The first physical crossing of each symmetry class at the clamp-zone study's bracket.

Where the whole-plate scan of a unit (:mod:`validation.clamp_zone.units`) finds several
physical modes crossing between its last two states (the clamp-zone wrinkle of the heavier
weights: modes one half-wave apart across the width, in the two width classes, and their
mirror images about the plate's centre, in the two ``x1`` classes), the unit locates the
first of them only.  Which one is first can flip with the mesh while the load does not move;
this study locates each of them.

A *unit* is one weight fraction ``alpha`` on one mesh of the clamp-zone study (same plate,
grading, formulation and solver), with that unit's row in
the ``units`` table: its last two scanned states (``scan_counts``: the
largest charge below ``D0_b`` without and the smallest above it with a physical negative
mode) are the bracket ``lo, hi``.  The charge ramp goes to ``lo`` and ``hi`` (targets in
steps of the row's ``D0_step`` below ``lo``, not scanned), the classes are counted at ``lo``
(whose negative modes the unit's scan classified: none is physical;
:meth:`~skfem_dielectric.models.plate.scan.PlateScan.count`) and the whole plate is scanned
at ``hi`` (:class:`~skfem_dielectric.models.plate.scan.PlateScan`), and every class with a negative
physical mode at ``hi`` (or each class of ``--classes``; one not yet physical at ``hi`` is
followed in steps of ``hi - lo``, four at most) is located to ``1e-4`` in ``D0``
(:func:`~skfem_dielectric.studies.buckling.locate_buckling`, that class's indicator
alone).  A row per class:

* ``D0_c``: the located crossing of the class's lowest physical mode;
* ``half_waves``, ``elements_per_half_wave``, ``corner_share``, ``mesh_scale``: as the
  clamp-zone study's row, for this mode;
* ``lo``, ``hi``: the class's bracket; the unknowns; the factorisations, CPU seconds and
  peak memory of the unit's process up to that row (the ramp, the scans and the classes
  located before it in the same run included); solver, date, command, and a ``note`` where
  the location failed.

``--bracket LO HI`` gives the bracket instead, for a mesh without a unit (too large for a
unit's scan from ``D0 = 0``): the classes are located there just the same, but no scan
of that mesh says that no physical mode went negative below ``LO`` (the row's ``note``
says so; the coarser meshes' units are the evidence).

The rows go to the ``onsets`` table as each class is located
(``skfem-dielectric clamp-zone onsets``); a class already there is skipped.
"""

from __future__ import annotations

import math
import time

import numpy as np

from skfem_dielectric.models.plate.scan import PlateScan
from skfem_dielectric.studies.buckling import locate_buckling

from ..fe.model import BUCKLING_NEWTON
from .costs import Meter
from ..data.clamp_zone import scan_states, unit_row
from ..data.registry import MAX_D0, TABLES
from ..specs import LOCATION_TOL
from ..data.key import UnitKey, mesh_text
from .units import charge_path, unit_problem, unit_ramp
from .local_theory import energy_centroid, half_waves

__all__ = ["COLUMNS", "bracket", "run_onsets"]

#: the columns of a row, in order
COLUMNS = TABLES["onsets"].columns


def bracket(row: dict) -> tuple[float, float]:
    """``(lo, hi)`` of a clamp-zone unit's row: the largest scanned charge below ``D0_b``
    and the smallest above it (from ``scan_counts``).

    Parameters
    ----------
    row : dict
        A row of the ``units`` table with a located ``D0_b``.

    Raises
    ------
    ValueError
        The row has no ``D0_b`` or no scanned state on one side of it.
    """
    try:
        d0b = float(row.get("D0_b") or "nan")
    except ValueError:
        d0b = math.nan
    if not math.isfinite(d0b):
        raise ValueError(f"the unit alpha = {row.get('alpha')} {row.get('mesh')} has no "
                         f"located D0_b: no bracket")
    D0 = [d for d, _, _ in scan_states(row)]
    below, above = [d for d in D0 if d < d0b], [d for d in D0 if d > d0b]
    if not below or not above:
        raise ValueError(f"the unit alpha = {row.get('alpha')} {row.get('mesh')} has no "
                         f"scanned state on both sides of D0_b = {d0b:g}")
    if not 0 <= max(below) < min(above) <= MAX_D0:
        raise ValueError(f"the unit alpha = {row.get('alpha')} {row.get('mesh')} has a "
                         f"bracket ({max(below):g}, {min(above):g}) outside (0, {MAX_D0:g}]")
    return max(below), min(above)


def run_onsets(key: UnitKey, *, solver: str = "auto", classes=None,
                     skip=(), units=None, progress=None,
                     on_row=None, given=None) -> list[dict]:
    """One unit of the study: a row of :data:`COLUMNS` per located class.

    Parameters
    ----------
    key : UnitKey
        The unit (:class:`~validation.data.key.UnitKey`): weight fraction, eighth-model
        mesh, grading along ``x1`` and formulation (its row must be in ``units``).
    solver
        Linear solver of the ramp and the trial states.
    classes
        Names of the classes to locate (as the ``class`` column); ``None``: every class
        with a negative physical mode at ``hi``.
    skip
        Names of classes not to locate (already located).
    units
        A ``units`` table (file or folder) to look for the unit in before the shipped
        one (:func:`~validation.data.clamp_zone.unit_row`).
    progress
        Optional ``progress(text)``.
    on_row
        Optional ``on_row(row)`` called as each class is located (the caller writes it).
    given
        ``(lo, hi)`` instead of a unit's bracket: no unit of this mesh is needed, the ramp
        goes in steps of 0.5, and nothing says that no physical mode went negative below
        ``lo`` (the rows' ``note`` says so; a coarser unit's scan is the evidence).

    Returns
    -------
    list of dict

    Raises
    ------
    ValueError
        No such unit in ``units``; the unit's scan has a physical negative mode at
        ``lo``; a class of
        ``classes`` without a physical negative mode at ``hi``.
    """
    meter = Meter()
    alpha, elements, grading, formulation = key.alpha, key.mesh, key.grading, key.formulation
    say = progress or (lambda text: None)
    el = tuple(int(n) for n in elements)
    if given is None:
        unit = unit_row(key, units)
        lo, hi = bracket(unit)
        at_lo = {d: (n, p) for d, n, p in scan_states(unit)}
        if at_lo.get(lo, (0, 1))[1] != 0:
            raise ValueError(f"the unit alpha = {alpha:g} {mesh_text(el)} has physical "
                             f"negative modes at lo = {lo:g} ({at_lo.get(lo)})")
        step, note = float(unit["D0_step"]), ""
    else:
        lo, hi = (float(v) for v in given)
        if not (0 < lo < hi and math.isfinite(hi)):
            raise ValueError(f"bracket must be 0 < lo < hi, got {lo:g}, {hi:g}")
        step, note = 0.5, "bracket given: no unit of this mesh scanned below lo"
    pb, s = unit_problem(alpha, el, grading=grading, formulation=formulation)
    D0 = [d for d in np.round(np.arange(step, lo, step), 10) if d < lo - 1e-9] + [lo, hi]
    states = {}

    def on_step(st):
        load = np.asarray(st.load, dtype=float)
        if st.target_reached and load[0] == s:
            states[float(load[1])] = (st.x, load, st.back, st.factors, st.back2)

    def ramp(targets, start=None):
        res = unit_ramp(pb, targets, on_step=on_step, solver=solver, start=start)
        if not res.converged:
            raise ValueError(f"the ramp of alpha = {alpha:g} {mesh_text(el)} stopped at "
                             f"D0 = {np.asarray(res.failed_at)[-1]:g}")

    ramp(charge_path(s, D0))
    # lo has no physical negative mode (the unit's scan says so): its counts alone
    scan = PlateScan(pb)
    t1 = time.process_time()
    counts = scan.count(*states[lo][:2])
    say(f"D0 = {lo:g}: {sum(counts.values())} negative (counted), "
        f"{time.process_time() - t1:.1f} CPU s")
    # the lowest physical negative mode of each class and the first state that has it;
    # a class of ``classes`` not yet there is followed in steps of hi - lo (four at most)
    lowest, ends, end = {}, {}, hi
    for extra in range(5):
        row_at = scan.analyse(*states[end][:2])
        say(f"D0 = {end:g}: {sum(row_at.counts.values())} negative, {row_at.n_physical} "
            f"physical, {row_at.cpu:.1f} CPU s")
        for lab in row_at.labels:      # sorted by eigenvalue: the class's lowest first
            if lab.kind == "physical" and lab.eigenvalue < 0 and lab.symmetry not in lowest:
                lowest[lab.symmetry], ends[lab.symmetry] = lab, end
        if classes is None or set(classes) <= set(lowest) or extra == 4:
            break
        nxt = round(end + (hi - lo), 10)
        ramp([np.array([s, end]), np.array([s, nxt])], start=states[end])
        end = nxt
    if classes is None and not lowest:
        raise ValueError(f"alpha = {alpha:g} {mesh_text(el)}: no class has a physical "
                         f"negative mode at hi = {hi:g}")
    names = [c for c in (sorted(lowest) if classes is None else classes) if c not in skip]
    for name in names:
        if name not in lowest:
            raise ValueError(f"classes: {name!r} has no physical negative mode up to "
                             f"D0 = {end:g} (there: {sorted(lowest)})")
    method = "pardiso" if solver == "pardiso" else "auto"
    n3 = el[2] * (2 if 3 in pb.plate.symmetry else 1)
    rows = []
    for name in names:
        row = {"alpha": alpha, "mesh": mesh_text(el), "grading": grading,
               "formulation": formulation, "class": name, "dofs": pb.ndofs, "lo": lo,
               "hi": ends[name]}
        try:
            bl = locate_buckling(pb, states[lo][:2], states[ends[name]][:2], lowest[name],
                                 counts=None,
                                 method=method, tol=LOCATION_TOL, linear_solver=solver,
                                 settings=BUCKLING_NEWTON)
        except ValueError as exc:     # a result: the class's crossing not located
            row.update(D0_c=math.nan, note=f"not located: {exc}")
        else:
            lab = bl.label
            point = energy_centroid(pb, bl.x, bl.load, lab.mode)
            n_half = half_waves(pb, lab.mode, lab.increments, point[0])
            row.update(D0_c=float(bl.D0_b), half_waves=n_half,
                       elements_per_half_wave=n3 / n_half, corner_share=lab.corner_share,
                       mesh_scale=lab.mesh_scale)
            if lab.symmetry != name:
                row["note"] = f"located the crossing of {lab.symmetry} first"
        if note:
            row["note"] = "; ".join(v for v in (row.get("note", ""), note) if v)
        row.update(meter.columns(solver))
        say(f"{name}: D0_c {row['D0_c']:.5f}, {row.get('half_waves', '')} half-waves "
            f"{row.get('note', '')}")
        rows.append(row)
        if on_row is not None:
            on_row(row)
    return rows

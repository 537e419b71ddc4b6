"""The clamp-zone wrinkle, unit by unit: one weight fraction on one (graded) mesh per unit.

A *unit* is the buckling run of the clamped Keplinger plate (eighth model, grad-div 10,
neo-Hookean, ``g = 9.81``) for one weight fraction ``alpha`` on one mesh ``n1 x n2 x n3``
with a geometric grading along ``x1`` towards the clamp (``grading`` = last / first element
length, :func:`skfem_dielectric.fem.mesh.plate_mesh`): the charge ramp in steps of
``D0_step``; every state scanned for the whole plate
(:class:`~skfem_dielectric.models.plate.scan.PlateScan`, inertia counts per symmetry
class, modes where a count changes); the ramp stops at the first physical crossing, which
is located to ``1e-4`` (:func:`~skfem_dielectric.studies.buckling.locate_buckling`).  The
unit's row holds what the mesh says about the mode there:

* ``D0_b``, the mode's class, its share at the clamp corners and its mesh scale;
* ``half_waves``: sign changes of its top-face deflection across the whole width, at its
  energy centroid (:func:`validation.clamp_zone.local_theory.half_waves`), and
  ``elements_per_half_wave`` (the width's elements over the half-waves);
* ``J_min_clamp``, ``J_max_clamp``: ``J = det F`` at the mid-plane centres of the elements
  next to the clamp, at ``D0_b`` (an incompressible material has ``J = 1``; the discrete
  clamp layer departs from it where the mesh does not resolve it);
* ``n_flagged_b``: the negative eigenvalues of the whole plate that are not physical
  (clamp corner or mesh scale) at the last scanned state; ``scan_counts`` every scanned
  state as ``D0:negative/physical`` (in scan order, refined steps last);
* the unknowns, factorisations, CPU seconds, peak memory, solver, date and command, and a
  ``note`` where no ``D0_b`` was found (no crossing up to ``D0_max``, the ramp stopped, or a
  crossing between two states that the location could not follow).

The mode at ``D0_b`` (the top face's deflection over the whole plate) goes to
``--out``'s ``modes`` folder (one ``.npz`` per unit, :attr:`~validation.data.key.UnitKey.stem`);
``skfem-dielectric clamp-zone modes`` draws them.  The rows go to the ``units`` table
(:data:`~validation.data.registry.TABLES`); ``skfem-dielectric clamp-zone units`` runs the units not yet
there (docs/clamp-zone.md).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.models.plate.modes import top_deflection
from skfem_dielectric.models.plate.scan import PlateScan
from skfem_dielectric.studies.buckling import locate_buckling

from ..fe.model import BUCKLING_GRAD_DIV, BUCKLING_NEWTON
from ..store import write_npz_atomic
from .costs import Meter
from ..data.registry import TABLES
from ..specs import LOCATION_TOL
from ..data.key import UnitKey, mesh_text
from .local_theory import energy_centroid, half_waves, local_state

__all__ = ["COLUMNS", "UNIT_SETTINGS", "COUNT_PRELOAD_STEPS", "run_unit", "write_mode",
           "unit_problem", "charge_path", "unit_ramp", "ramp_states", "ramp_to_charge",
           "clamp_centre_J"]

#: the columns of a unit's row, in order (the ``units`` table)
COLUMNS = TABLES["units"].columns

#: Newton settings of a unit's ramps: the Keplinger plate's, with more cut-backs and
#: iterations (the graded clamp layer)
UNIT_SETTINGS = replace(fe.gallery.KEPLINGER_SETTINGS, max_cutbacks=6, max_iter=25)

#: Equal steps of the dead load before the charge in the ramp of the clamp-zone counts
#: (the units' other ramps take the Keplinger plate's three): with six the heaviest
#: weight (alpha = 1.5) converges without the cut-back and the damped Newton steps that
#: three cost (on 30 x 2 x 24: 19 factorisations against 46, docs/performance.md)
COUNT_PRELOAD_STEPS = 6


def unit_problem(alpha: float, elements, *, grading: float = 1.0,
                 formulation: str = "mixed", grad_div: float = BUCKLING_GRAD_DIV,
                 pressure: str = "Q1", control: str = "charge"):
    """The plate of a unit and its dead load: ``(problem, s)``.

    The clamped Keplinger plate, eighth model, graded along ``x1`` (``grading``), grad-div
    ``grad_div`` (default :data:`~validation.fe.model.BUCKLING_GRAD_DIV`), ``J = 1`` imposed
    as ``formulation`` with the pressure space ``pressure`` (``"Q1"`` or ``"P0"``),
    actuated by ``control`` (``"charge"``: the load is ``(s, D0)``; ``"voltage"``:
    ``(s, E0)``; :class:`~skfem_dielectric.gallery.plates.PlateOptions`); ``s`` of weight
    fraction ``alpha`` with ``g = 9.81``.
    """
    options = fe.PlateOptions(grad_div=grad_div, formulation=formulation, pressure=pressure,
                              control=control)
    pb = fe.gallery.keplinger_problem(elements=tuple(int(n) for n in elements),
                                      symmetry="eighth", grading=grading, options=options)
    return pb, fe.gallery.keplinger_s(alpha, g=9.81)


def charge_path(s: float, D0, preload_steps: int = fe.gallery.KEPLINGER_PRELOAD_STEPS
                ) -> list:
    """A unit's load path: the dead load ``s`` in ``preload_steps`` equal steps (the
    Keplinger plate's unless given), then the charges ``D0``
    (:func:`~skfem_dielectric.gallery.loads.preload_then_charge`)."""
    return fe.gallery.preload_then_charge(s, np.asarray(D0), preload_steps)


def unit_ramp(problem, targets, *, on_step, solver: str = "auto", start=None, **options):
    """A unit's ramp of ``problem`` through ``targets`` with :data:`UNIT_SETTINGS`, its
    ``RuntimeWarning`` silenced (the caller reports a ramp that stopped).

    ``start``: a converged state ``(x, load, back, factors, back2)`` of an earlier ramp of
    the same plate (its step's ``x``, ``load``, ``back``, ``factors`` and ``back2``) to
    continue from, bit for
    bit; ``options``: more options of :func:`~skfem_dielectric.gallery.drivers.run_ramp`
    (e.g. ``stop``).  Returns the :class:`~skfem_dielectric.solvers.ramp.RampResult`.
    """
    resume = {} if start is None else dict(x0=start[0], start=start[1], back=start[2],
                                           factors=start[3], back2=start[4])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return fe.gallery.run_ramp(problem, targets, on_step=on_step, linear_solver=solver,
                                   settings=UNIT_SETTINGS, **resume, **options)


def ramp_states(problem, s: float, D0: float, *, solver: str = "auto",
                name: str = "") -> list[tuple[float, np.ndarray, np.ndarray]]:
    """The converged states ``(D0_i, x, load)`` of a unit's ramp to the charge ``D0 >= 0``:
    the dead load ``s`` in the Keplinger pre-load steps (its end is ``D0_i = 0``), then the
    charge in steps of 0.5 and ``D0`` (:data:`UNIT_SETTINGS`), in the ramp's order.

    Raises
    ------
    ValueError
        The ramp stops before ``D0`` (the message names the ramp as ``name``).
    """
    D0 = float(D0)
    targets = ([d for d in np.round(np.arange(0.5, D0, 0.5), 10) if d < D0 - 1e-9]
               + ([D0] if D0 > 0 else []))         # D0 = 0: the pre-load's end
    states = {}

    def on_step(step):
        if step.target_reached and step.load[0] == s:
            states[float(step.load[1])] = (float(step.load[1]), step.x, step.load)

    res = unit_ramp(problem, charge_path(s, targets), on_step=on_step, solver=solver)
    if not res.converged or D0 not in states:
        raise ValueError(f"the ramp{' of ' + name if name else ''} stopped before "
                         f"D0 = {D0:g}")
    return [states[d] for d in sorted(states)]


def ramp_to_charge(problem, s: float, D0: float, *, solver: str = "auto", name: str = ""):
    """The converged state ``(x, load)`` at charge ``D0`` of a unit's plate: the last of
    :func:`ramp_states`.

    Raises
    ------
    ValueError
        The ramp stops before ``D0`` (the message names the ramp as ``name``).
    """
    _, x, load = ramp_states(problem, s, D0, solver=solver, name=name)[-1]
    return x, load


def clamp_centre_J(pb, x, load) -> tuple[float, float]:
    """Smallest and largest ``J`` at the mid-plane centres of the elements next to the
    clamp (eighth model: the last element along ``x1``, every element across ``x3``)."""
    g1, _, g3 = pb.plate.grids
    X1 = 0.5 * (g1[-1] + g1[-2])
    Js = [local_state(pb, x, load, np.array([X1, 0.0, 0.5 * (a + b)])).J
          for a, b in zip(g3[:-1], g3[1:])]
    return float(min(Js)), float(max(Js))


def run_unit(key: UnitKey, *, D0_step: float = 0.5, D0_max: float = 6.0,
             solver: str = "auto", progress=None, modes_dir: Path | None = None) -> dict:
    """One unit of the study: the row of :data:`COLUMNS` (module docstring).

    Parameters
    ----------
    key : UnitKey
        The unit: weight fraction, eighth-model mesh ``(n1, n2, n3)``, grading along
        ``x1`` (last / first element length, ``< 1``: finer at the clamp) and formulation
        (:class:`~validation.data.key.UnitKey`).
    D0_step, D0_max
        The charge targets ``D0_step, 2 D0_step, ..., D0_max``; the ramp stops at the
        first scanned state with a negative physical mode.  Where several physical modes
        crossed in one step, or the location cannot follow the crossing, that step is
        scanned again in four (at most twice: steps down to ``D0_step / 16``).
    solver
        Linear solver of the ramps and trial states.
    progress
        Optional ``progress(text)`` called once per scanned state.
    modes_dir
        Where to write the mode at ``D0_b`` (``<stem>.npz``, :attr:`~validation.data.key.UnitKey.stem`:
        the top face's deflection over the whole plate, ``X1``, ``X3``, ``u2``, as
        :func:`~skfem_dielectric.models.plate.modes.top_deflection`); ``None``: not written.

    Returns
    -------
    dict
        The columns; ``D0_b`` is ``nan`` (and the mode columns empty) when no physical mode
        crossed up to ``D0_max`` or the ramp stopped first.  Where it crossed, ``mode``
        holds the mode's arrays (``X1``, ``X3``, ``u2``, ``D0_b``) for :func:`write_mode`.
    """
    meter = Meter()
    alpha, el, grading, formulation = key.alpha, key.mesh, key.grading, key.formulation
    pb, s = unit_problem(alpha, el, grading=grading, formulation=formulation)
    track = {"prev": None, "before": None, "row": None, "cur": None, "states": 0,
             "counts": []}

    def on_step(step):
        load = np.asarray(step.load, dtype=float)
        if not step.target_reached or load[0] != s:
            return
        before = scan.state
        row = scan.analyse(step.x, load)
        track["states"] += 1
        track["counts"].append(f"{load[1]:g}:{row.n_negative}/{row.n_physical}")
        if progress is not None:
            progress(f"D0 = {load[1]:.4f}: {row.n_negative} negative, {row.n_physical} "
                     f"physical, {row.cpu:.1f} CPU s")
        if row.n_physical > 0 and track["prev"] is not None:
            track.update(before=before, row=row,
                         cur=(step.x, load, step.back, step.factors, step.back2), crossed=True)
            return
        track["prev"] = (step.x, load, step.back, step.factors, step.back2)

    def crossed(step):          # the ramp's stop predicate: the first physical crossing
        return track.pop("crossed", False)

    def ramp_to(targets, start=None):
        track["row"] = None
        res = unit_ramp(pb, targets, on_step=on_step, solver=solver, start=start,
                        stop=crossed)
        return "" if res.converged else \
            f"ramp stopped at D0 = {np.asarray(res.failed_at)[-1]:g}"

    # the charge ramp in steps of D0_step, scanned at every target, up to the first state
    # with a physical negative mode; then the located crossing.  A step in which several
    # physical modes crossed, or whose crossing the location cannot follow, is scanned
    # again in four steps (twice at most)
    scan = PlateScan(pb)
    D0 = np.round(np.arange(D0_step, D0_max + 1e-9, D0_step), 10)
    stopped = ramp_to(charge_path(s, D0))
    bl, step = None, D0_step
    method = "pardiso" if solver == "pardiso" else "auto"
    for refine in range(3):
        if track["row"] is None:
            break
        prev, cur, before, row = track["prev"], track["cur"], track["before"], track["row"]
        lo, hi = float(prev[1][1]), float(cur[1][1])
        try:
            if row.n_physical > 1 and refine < 2:
                raise ValueError(f"{row.n_physical} physical modes crossed at once")
            bl = locate_buckling(pb, prev[:2], cur[:2], row.new_physical, counts=before,
                                 method=method, tol=LOCATION_TOL, linear_solver=solver,
                                 settings=BUCKLING_NEWTON)
            break
        except ValueError as exc:   # a result: the crossing between lo and hi, unlocated
            stopped = f"physical crossing between D0 = {lo:g} and {hi:g} not located: {exc}"
            if refine == 2:
                break
            step /= 4.0
            scan = PlateScan(pb, state=before)
            fine = [np.array([s, d]) for d in np.round(lo + step * np.arange(0, 5), 10)]
            stopped = ramp_to(fine, start=prev) or stopped
    row = {"alpha": alpha, "mesh": mesh_text(el), "grading": grading,
           "formulation": formulation, "dofs": pb.ndofs, "D0_step": D0_step,
           "states": track["states"], "scan_counts": " ".join(track["counts"])}
    if bl is not None:
        stopped = ""
        lab = bl.label
        point = energy_centroid(pb, bl.x, bl.load, lab.mode)
        n_half = half_waves(pb, lab.mode, lab.increments, point[0])
        jmin, jmax = clamp_centre_J(pb, bl.x, bl.load)
        n3 = el[2] * (2 if 3 in pb.plate.symmetry else 1)
        row.update(D0_b=float(bl.D0_b), **{"class": lab.symmetry},
                   corner_share=lab.corner_share, mesh_scale=lab.mesh_scale,
                   half_waves=n_half, elements_per_half_wave=n3 / n_half,
                   J_min_clamp=jmin, J_max_clamp=jmax,
                   n_flagged_b=track["row"].n_negative - track["row"].n_physical)
        X1, X3, u2 = top_deflection(pb, lab.mode, lab.increments)
        row["mode"] = {"X1": X1, "X3": X3, "u2": u2, "D0_b": float(bl.D0_b)}
        if modes_dir is not None:
            write_mode(modes_dir, key, row["mode"])
    else:
        row.update(D0_b=math.nan, n_flagged_b=(track["row"].n_negative - track["row"].n_physical
                                                if track["row"] is not None else ""),
                   note=stopped or f"no physical crossing up to D0 = {D0_max:g}")
    row.update(meter.columns(solver))
    return row


def write_mode(folder, key: UnitKey, mode: dict) -> Path:
    """Write a unit's mode at ``D0_b`` (the ``mode`` of :func:`run_unit`'s row) atomically
    to ``folder/<stem>.npz`` (:attr:`~validation.data.key.UnitKey.stem`), with the unit's
    key in it (the array ``key``: the stem), so that a renamed file is caught; returns the
    path."""
    path = Path(folder) / f"{key.stem}.npz"
    path.parent.mkdir(parents=True, exist_ok=True)
    write_npz_atomic(path, key=np.array(key.stem), **mode)
    return path

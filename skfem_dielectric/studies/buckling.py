"""First physical buckling load of a plate along a load path.

The clamped plate of Conroy Broderick, Righi, Destrade and Ogden, "Stability analysis of
charge-controlled soft dielectric plates" (Int. J. Eng. Sci., 2020) "breaks down" once
``P33`` near the clamps turns compressive (Sec. 6); a symmetry-reduced model cannot show
the lateral buckling that follows.  Here the states of a ramp are scanned with the
spectrum of the *whole* plate (the union of the symmetry classes of a reduced model,
:func:`~skfem_dielectric.models.plate.symmetry_classes.class_stability`); the lowest
eigenvalue whose mode is physical
(:func:`~skfem_dielectric.models.plate.modes.lowest_physical`: neither at a clamp corner,
:func:`~skfem_dielectric.models.plate.modes.corner_radius`, nor at the mesh scale) is the
indicator whose zero crossing :func:`~skfem_dielectric.solvers.critical.critical_load`
locates.

The verdict of a single mesh is a flag, not a proof: a negative eigenvalue is physics
only if its onset converges under refinement (``validation.studies.buckling`` compares meshes).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Sequence

import numpy as np

from ..checks import check_count, check_nonnegative_int, check_positive
from ..models.plate.modes import (ModeLabel, classify_mode, corner_radius, lowest_physical,
                                  physical_modes)
from ..linalg.inertia import inertia_factors, reusable_factors
from ..models.plate.problem import PlateProblem
from ..models.plate.scan import PlateScan, ScanRow
from ..models.plate.symmetry_classes import (class_mode_full, class_stability, class_tangent,
                                             union_tangent)
from ..solvers.critical import CriticalLoad, critical_load
from ..solvers.ramp import RampResult
from ..stability.analysis import modes_near_zero

__all__ = ["BucklingLoad", "buckling_load", "locate_buckling", "SCANS"]

#: how :func:`buckling_load` scans the states: ``"events"`` (counts at every state, modes
#: where a class's count changes, :class:`~skfem_dielectric.models.plate.scan.PlateScan`)
#: or ``"full"`` (the lowest physical mode at every state,
#: :func:`~skfem_dielectric.models.plate.modes.lowest_physical`)
SCANS = ("events", "full")


@dataclass
class BucklingLoad:
    """The first physical buckling load on a load path.

    Attributes
    ----------
    D0_b
        Second load component (``D0``, or ``E0`` under voltage control) at the buckling
        load; ``nan`` if none was found on the scanned states.
    load
        The whole load ``(s, D0)`` there (``None`` if none found).
    eigenvalue
        The lowest physical eigenvalue there (about 0 when located), else the lowest
        physical eigenvalue at the last scanned state.
    label
        :class:`~skfem_dielectric.models.plate.modes.ModeLabel` of the critical mode (at
        ``load``), else ``None``.
    x
        State at ``load`` (reduced vector), else ``None``.
    scan
        One dict per scanned state: ``D0``, ``s``, ``n_negative`` (whole plate),
        ``lowest`` and ``lowest_class`` (lowest eigenvalue of any kind),
        ``n_flagged`` (negative modes below the lowest physical one, all flagged),
        ``physical``, ``physical_class``, ``corner_share``, ``mesh_scale`` (the lowest
        physical mode; ``nan`` and ``""`` if none among the computed).
    critical
        The :class:`~skfem_dielectric.solvers.critical.CriticalLoad` search, else ``None``.
    reason
        Why none was found (empty if found).
    trials
        The states the location solved, one dict per evaluation of the located crossing's
        indicator (the last :attr:`critical` search), in the order solved: ``s``, ``D0``,
        ``eigenvalue`` (of the followed physical mode; ``nan`` where none of its class's
        modes near zero was physical) and ``class`` (its symmetry class).  The first is the
        stable state the search starts from, the second the end of its bracket, the last
        the located load: with the scanned states they trace the indicator through zero at
        ``D0_b``, which a straight line between two scanned states does not.
    """

    D0_b: float
    load: Any
    eigenvalue: float
    label: ModeLabel | None
    x: np.ndarray | None
    scan: list[dict] = field(default_factory=list)
    critical: CriticalLoad | None = None
    reason: str = ""
    trials: list[dict] = field(default_factory=list)

    @property
    def found(self) -> bool:
        """A buckling load was located."""
        return bool(np.isfinite(self.D0_b))


def _trials(crit: CriticalLoad, load_a, load_b, name: str) -> list[dict]:
    """The evaluations of a :func:`critical_load` search on the path ``load_a -> load_b``
    as :attr:`BucklingLoad.trials` rows (``t`` back to the load)."""
    la, lb = np.asarray(load_a, dtype=float), np.asarray(load_b, dtype=float)
    out = []
    for t, v in crit.evaluations:
        s, d = (float(c) for c in la + t * (lb - la))
        out.append({"s": s, "D0": d, "eigenvalue": float(v) if np.isfinite(v) else np.nan,
                    "class": name})
    return out


def _scan_row(load, lowest) -> dict:
    s, d = (float(v) for v in np.asarray(load, dtype=float))
    phys, labels = lowest.label, lowest.labels
    return {"s": s, "D0": d, "n_negative": int(lowest.n_negative),
            "lowest": labels[0].eigenvalue if labels else np.nan,
            "lowest_class": labels[0].symmetry if labels else "",
            "n_flagged": sum(1 for m in labels if m.kind != "physical" and m.eigenvalue < 0),
            "physical": phys.eigenvalue if phys else np.nan,
            "physical_class": phys.symmetry if phys else "",
            "corner_share": phys.corner_share if phys else np.nan,
            "mesh_scale": phys.mesh_scale if phys else np.nan}


def _event_row(row: ScanRow) -> dict:
    """The scan row of an event-driven state: the counts at every state, the modes where
    they changed (``nan``/empty where none was computed or none is physical)."""
    s, d = (float(v) for v in row.load)
    phys = [m for m in row.labels if m.kind == "physical"]
    low = row.labels[0] if row.labels else None
    p = phys[0] if phys else None
    return {"s": s, "D0": d, "n_negative": row.n_negative,
            "lowest": low.eigenvalue if low else np.nan,
            "lowest_class": low.symmetry if low else "",
            "n_flagged": row.n_negative - row.n_physical,
            "physical": p.eigenvalue if p else np.nan,
            "physical_class": p.symmetry if p else "",
            "corner_share": p.corner_share if p else np.nan,
            "mesh_scale": p.mesh_scale if p else np.nan,
            "n_physical": row.n_physical, "changed": "; ".join(row.changed),
            "factorisations": row.factorisations,
            "back_substitutions": row.back_substitutions}


def buckling_load(result: RampResult | PlateProblem,
                  states: Sequence[tuple[np.ndarray, Any]] | None = None, *,
                  extra: int = 2, grad_div: float | None = None, method: str = "auto",
                  radius: float | None = None, tol: float = 1e-4, maxiter: int = 30,
                  scan: str = "events", **ramp_options) -> BucklingLoad:
    """Scan converged states for the first physical buckling load and locate it.

    Parameters
    ----------
    result
        A :class:`~skfem_dielectric.solvers.ramp.RampResult` of a plate driver (its ``problem``
        and ``steps`` are used), or a
        :class:`~skfem_dielectric.models.plate.problem.PlateProblem` with ``states``.
    states
        ``(x, load)`` pairs in load order (with a problem; ignored for a result).
    extra, grad_div, method, radius
        As :func:`~skfem_dielectric.models.plate.modes.physical_modes`.
    tol, maxiter
        Location of the zero crossing in the load
        (:func:`~skfem_dielectric.solvers.critical.critical_load`).
    scan
        ``"events"`` (default): one factorisation per symmetry class per state and its
        negative count; modes only where a class's count changes, to classify what
        crossed zero (:class:`~skfem_dielectric.models.plate.scan.PlateScan`); the first
        state with a negative mode labelled physical ends the scan.  ``"full"``: the
        lowest physical mode of the whole plate at every state
        (:func:`~skfem_dielectric.models.plate.modes.lowest_physical`), every negative
        mode classified -- the same load at many times the cost, for checking.
    **ramp_options
        Newton settings of the trial states (``linear_solver``, ``max_cutbacks``,
        ``rtol``, ...); the ramp adds the plate's own ``det F > 0`` guards
        (:meth:`~skfem_dielectric.problem.Problem.newton_guards`).

    Returns
    -------
    BucklingLoad
        ``found`` is ``False`` (``D0_b = nan``, ``reason`` says why) when no scanned
        state has a negative physical eigenvalue, or when the first state already has one.

    Notes
    -----
    The indicator is the lowest eigenvalue of the whole plate whose mode is classified
    physical; between the last state where it is positive and the first where it is
    negative the load is interpolated linearly and the crossing found by Illinois steps,
    each trial solved from the stable state.  The paper's breakdown criterion (Sec. 6,
    compressive ``P33`` near the clamps) is a stress criterion; this is the bifurcation
    of the discrete whole plate that it anticipates.

    Raises
    ------
    ValueError
        Bad ``result``/``states``, ``extra``, ``tol``, ``maxiter`` or ``radius``.
    """
    if isinstance(result, RampResult):
        problem = result.problem
        pairs = [(st.x, st.load) for st in result.steps]
        if not isinstance(problem, PlateProblem):
            raise ValueError("result must come from a plate driver (result.problem a "
                             f"PlateProblem), got {type(problem).__name__}")
    elif isinstance(result, PlateProblem):
        problem = result
        if states is None:
            raise ValueError("states must be given with a PlateProblem")
        pairs = list(states)
    else:
        raise ValueError(f"result must be a RampResult or a PlateProblem, got "
                         f"{type(result).__name__}")
    if not pairs:
        raise ValueError("states must hold at least one converged state")
    for i, pair in enumerate(pairs):
        if len(pair) != 2 or np.asarray(pair[1]).shape != (2,):
            raise ValueError(f"states[{i}] must be a pair (x, (s, D0)), got {pair!r:.80}")
    extra = check_count("extra", extra)
    tol = check_positive("tol", tol)
    maxiter = check_nonnegative_int("maxiter", maxiter)
    if radius is not None:
        radius = check_positive("radius", radius)
    if scan not in SCANS:
        raise ValueError(f"scan must be one of {SCANS}, got {scan!r}")
    opts = dict(extra=extra, grad_div=grad_div, method=method, radius=radius)
    if scan == "events":
        return _event_scan(problem, pairs, opts, tol, maxiter, ramp_options)
    scan: list[dict] = []
    prev = None
    for x, load in pairs:
        lowest = lowest_physical(problem, x, load, **opts)
        phys = lowest.label
        scan.append(_scan_row(load, lowest))
        if phys is not None and phys.eigenvalue < 0:
            if prev is None:
                return BucklingLoad(np.nan, None, phys.eigenvalue, phys, None, scan,
                                    reason="the first state already has a negative "
                                           "physical eigenvalue")
            return _locate(problem, prev, (x, load), phys, opts, scan, tol, maxiter,
                           ramp_options)
        if phys is not None:
            prev = (x, load)
    last = scan[-1]["physical"]
    return BucklingLoad(np.nan, None, last, None, None, scan,
                        reason=f"no negative physical eigenvalue up to "
                               f"D0 = {scan[-1]['D0']:g}")


def _event_scan(problem, pairs, opts, tol, maxiter, ramp_options) -> BucklingLoad:
    """:func:`buckling_load` with the event-driven scan."""
    scanner = PlateScan(problem, extra=opts["extra"], grad_div=opts["grad_div"],
                        method=opts["method"], radius=opts["radius"])
    rows: list[dict] = []
    prev = None
    for x, load in pairs:
        before = scanner.state
        row = scanner.analyse(x, load)
        rows.append(_event_row(row))
        if row.n_physical > 0:
            phys = row.new_physical
            if prev is None or phys is None:
                reason = ("the first state already has a negative physical eigenvalue"
                          if prev is None else "a negative physical mode whose crossing "
                          "was not seen (its class's count did not change)")
                return BucklingLoad(np.nan, None, phys.eigenvalue if phys else np.nan, phys,
                                    None, rows, reason=reason)
            bl = locate_buckling(problem, prev, (x, load), phys, counts=before, tol=tol,
                                 maxiter=maxiter, **opts, **ramp_options)
            bl.scan = rows
            return bl
        prev = (x, load)
    return BucklingLoad(np.nan, None, np.nan, None, None, rows,
                        reason=f"no negative physical eigenvalue up to D0 = {rows[-1]['D0']:g}")


def _most_like(problem, c, vals, vecs, order, ref, radius, xf):
    """Among the eigenpairs ``vals``, ``vecs`` of class ``c`` (visited in ``order``), the
    mode classified physical that overlaps most with ``ref`` (the unit displacement part
    of the followed mode): ``(eigenvalue, full mode, overlap)``, or ``None`` if none is
    physical."""
    n_u = ref.size
    best, out = -1.0, None
    for j in order:
        w = class_mode_full(c, vecs[:, j])
        ov = abs(ref @ w[:n_u]) / max(np.linalg.norm(w[:n_u]), 1e-300)
        if ov > best and classify_mode(problem, xf, w, radius=radius)["kind"] == "physical":
            best, out = ov, (float(vals[j]), w, float(ov))
    return out


#: overlap with the followed mode below which the physical modes nearest to zero are
#: taken not to hold it (it lies beyond them, past mesh-scale modes): more are computed
FOLLOW_OVERLAP = 0.5


def _near_zero_physical(problem, c, K, ref, radius, k0, xf):
    """Among the eigenpairs of class ``c`` nearest to zero, the physical mode most like
    ``ref``: ``(eigenvalue, mode, overlap)``, or ``None`` when none of up to 64 nearest is
    physical.  More eigenpairs are computed (doubling) while the best physical one
    overlaps less than :data:`FOLLOW_OVERLAP` with ``ref``: a physical mode that has just
    crossed can lie beyond mesh-scale modes nearer to zero, and another physical mode
    nearer to zero is not the one followed."""
    Kc = class_tangent(c, K)
    inertia, factors = inertia_factors(Kc, "auto", c.orders)
    usable = reusable_factors(factors, inertia)
    nd = int(np.count_nonzero(c.metric.diagonal() > 0))
    k = min(k0, nd - 1)
    while True:
        vals, vecs = modes_near_zero(Kc, c.metric, k, side="both", factors=usable, tol=1e-10)
        out = _most_like(problem, c, vals, vecs, np.argsort(np.abs(vals), kind="stable"),
                         ref, radius, xf)
        if out is not None and out[2] >= FOLLOW_OVERLAP or k >= min(64, nd - 1):
            return out
        k = min(2 * k, nd - 1)


def locate_buckling(problem: PlateProblem, a: tuple[np.ndarray, Any],
                    b: tuple[np.ndarray, Any], mode: ModeLabel, *, counts: dict | None = None,
                    extra: int = 2, grad_div: float | None = None, method: str = "auto",
                    radius: float | None = None, tol: float = 1e-4, maxiter: int = 30,
                    **ramp_options) -> BucklingLoad:
    """Locate the zero crossing of a physical mode between two states of a scan.

    The indicator is the eigenvalue of the mode of ``mode``'s symmetry class that is
    classified physical and overlaps most with ``mode``, among the eigenpairs of that
    class nearest to zero (:func:`~skfem_dielectric.stability.analysis.modes_near_zero`,
    on the factors that count the class: a mode near its crossing is among them), located
    by :func:`~skfem_dielectric.solvers.critical.critical_load` with every trial solved
    from the stable end of its bracket (``a`` or a later trial found stable).  At the
    located load every class is counted against ``counts`` (the scan's state at ``a``);
    a class whose new negative mode there is physical crossed first and is located in turn
    (each class once).

    Parameters
    ----------
    problem
        The plate of the scan.
    a, b
        ``(x, load)`` of the last state without and the first with the negative physical
        ``mode``.
    mode
        The :class:`~skfem_dielectric.models.plate.modes.ModeLabel` found at ``b``.
    counts
        :attr:`~skfem_dielectric.models.plate.scan.PlateScan.state` at ``a`` (``None``:
        the other classes are not checked).
    extra, grad_div, method, radius
        As :func:`buckling_load`.
    tol, maxiter
        As :func:`buckling_load`.
    **ramp_options
        Newton settings of the trial states, as :func:`buckling_load`.

    Returns
    -------
    BucklingLoad
        Without ``scan`` rows.

    Raises
    ------
    ValueError
        The indicator does not change sign between ``a`` and ``b``, or a trial state
        cannot be solved.
    """
    n_u = problem.n_u
    r = corner_radius(problem) if radius is None else check_positive("radius", radius)
    k0 = max(6, 2 * check_count("extra", extra) + 2)
    target, end, seen = mode, np.asarray(b[1], float), set()
    last: dict = {}
    while True:
        seen.add(target.symmetry)
        ref = target.mode[:n_u] / np.linalg.norm(target.mode[:n_u])

        def eig(x, load, ref=ref, name=target.symmetry):
            classes, K = union_tangent(problem, x, load, grad_div)
            c = next(c for c in classes if c.name == name)
            found = _near_zero_physical(problem, c, K, ref, r, k0, problem.full(x, load))
            if found is None:
                return np.inf
            last["mode"], last["class"] = found[1], c
            return found[0]

        crit = critical_load(problem, a[0], np.asarray(a[1], float), end, eig, tol=tol,
                             maxiter=maxiter, **ramp_options)
        earlier = None
        if counts is not None:
            scanner = PlateScan(problem, extra=extra, grad_div=grad_div, method=method,
                                radius=r, state=counts)
            row = scanner.analyse(crit.x, crit.load)
            earlier = next((m for m in row.labels if m.kind == "physical"
                            and m.eigenvalue < 0 and m.symmetry not in seen), None)
        if earlier is None:
            break
        target, end = earlier, np.asarray(crit.load, float)
    c = last["class"]                   # the located mode: the last trial's, at crit.x
    lab = classify_mode(problem, problem.full(crit.x, crit.load), last["mode"], radius=r)
    label = ModeLabel(float(crit.eigenvalue), c.name, dict(c.increments), lab["corner_share"],
                      lab["mesh_scale"], lab["kind"], last["mode"])
    return BucklingLoad(float(crit.load[1]), crit.load, crit.eigenvalue, label, crit.x, [],
                        crit, trials=_trials(crit, a[1], end, target.symmetry))


def _locate(problem, a, b, phys_b, opts, scan, tol, maxiter, ramp_options) -> BucklingLoad:
    """:func:`critical_load` of the physical mode found at ``b``, tracked back to ``a``.

    Taking the lowest physical mode over all classes at every trial would make the
    indicator jump where another mode's indicators cross a threshold; instead, among the
    modes of the critical class classified physical, the one that overlaps most with the
    physical mode at ``b`` is followed (one class per trial; a flagged mode that mixes
    with it is not followed).  The lowest physical mode at ``b`` need not be the first to
    cross (nearly degenerate classes cross in another order): if another class has a
    negative physical eigenvalue at the located load, its crossing is located between
    ``a`` and that load, until no class is negative there (each class once).
    """
    n_u = problem.n_u
    spec = dict(extra=opts["extra"], grad_div=opts["grad_div"], method=opts["method"])
    r = corner_radius(problem) if opts["radius"] is None else opts["radius"]
    target, end, seen = phys_b, np.asarray(b[1], float), set()
    while True:
        seen.add(target.symmetry)
        ref = target.mode[:n_u] / np.linalg.norm(target.mode[:n_u])

        def eig(x, load, ref=ref, cls=target.symmetry):
            # among the class's modes classified physical, the one most like the reference
            cs = class_stability(problem, x, load, k=0, all_negative=True, only=[cls],
                                 **spec)
            c, vals, vecs = cs.classes[0], cs.results[0].eigenvalues, cs.results[0].modes
            found = _most_like(problem, c, vals, vecs, range(vals.size), ref, r,
                               problem.full(x, load))
            return np.inf if found is None else found[0]

        crit = critical_load(problem, a[0], np.asarray(a[1], float), end, eig, tol=tol,
                             maxiter=maxiter, **ramp_options)
        labels, _ = physical_modes(problem, crit.x, crit.load, stop_at_physical=False, **opts)
        earlier = [m for m in labels if m.kind == "physical" and m.eigenvalue < 0
                   and m.symmetry not in seen]
        if not earlier:
            break
        target, end = earlier[0], np.asarray(crit.load, float)
    same = [m for m in labels if m.symmetry == target.symmetry]
    ov = [abs(ref @ m.mode[:n_u]) / np.linalg.norm(m.mode[:n_u]) for m in same]
    label = same[int(np.argmax(ov))] if same else None
    return BucklingLoad(float(crit.load[1]), crit.load, crit.eigenvalue, label, crit.x, scan,
                        crit, trials=_trials(crit, a[1], end, target.symmetry))

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
from ..gallery.drivers import newton_guards
from ..models.plate.modes import (ModeLabel, classify_mode, corner_radius, lowest_physical,
                                  physical_modes)
from ..models.plate.problem import PlateProblem
from ..models.plate.symmetry_classes import class_mode_full, class_stability
from ..solvers.critical import CriticalLoad, critical_load
from ..solvers.ramp import RampResult

__all__ = ["BucklingLoad", "buckling_load"]


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
    """

    D0_b: float
    load: Any
    eigenvalue: float
    label: ModeLabel | None
    x: np.ndarray | None
    scan: list[dict] = field(default_factory=list)
    critical: CriticalLoad | None = None
    reason: str = ""

    @property
    def found(self) -> bool:
        """A buckling load was located."""
        return bool(np.isfinite(self.D0_b))


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


def buckling_load(result: RampResult | PlateProblem,
                  states: Sequence[tuple[np.ndarray, Any]] | None = None, *,
                  extra: int = 2, grad_div: float | None = None, method: str = "auto",
                  radius: float | None = None, tol: float = 1e-4, maxiter: int = 30,
                  **ramp_options) -> BucklingLoad:
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
    **ramp_options
        Newton settings of the trial states (``linear_solver``, ``max_cutbacks``,
        ``rtol``, ...); the plate's ``det F > 0`` guards are added
        (:func:`~skfem_dielectric.gallery.drivers.newton_guards`).

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
    opts = dict(extra=extra, grad_div=grad_div, method=method, radius=radius)
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
    for key, value in newton_guards(problem).items():
        ramp_options.setdefault(key, value)
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
            xf = problem.full(x, load)
            best, value = -1.0, np.inf
            for j in range(vals.size):
                w = class_mode_full(c, vecs[:, j])
                ov = abs(ref @ w[:n_u]) / max(np.linalg.norm(w[:n_u]), 1e-300)
                if ov > best and classify_mode(problem, xf, w, radius=r)["kind"] == "physical":
                    best, value = ov, float(vals[j])
            return value

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
                        crit)

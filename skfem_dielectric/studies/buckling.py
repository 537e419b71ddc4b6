"""First physical buckling load of a plate along a load path.

The clamped plate of Conroy Broderick, Righi, Destrade and Ogden, "Stability analysis of
charge-controlled soft dielectric plates" (Int. J. Eng. Sci., 2020) "breaks down" once
``P33`` near the clamps turns compressive (Sec. 6); a symmetry-reduced model cannot show
the lateral buckling that follows.  Here the states of a ramp are scanned with the
spectrum of the *whole* plate (the union of the symmetry classes of a reduced model,
:func:`~skfem_dielectric.models.plate.symmetry_classes.class_stability`); the modes of each state
are
classified in ascending order (:func:`~skfem_dielectric.models.plate.modes.classify_mode`) and the
lowest eigenvalue whose mode is physical is the indicator whose zero crossing
:func:`~skfem_dielectric.solvers.critical.critical_load` locates.

The corner radius.  :func:`~skfem_dielectric.models.plate.modes.corner_elements` selects elements by
their centroid within ``2 H`` of a clamp/free-edge corner line.  On a mesh whose elements
are larger than ``2 H`` in the plane the element *at* the corner has its centroid farther
away than that and would not count (10 x 1 x 5 eighth model of the 100 x 1 x 50 plate:
96 % of a mode's energy in that element, corner share 0.00 with the default radius).
:func:`corner_radius` therefore takes at least the in-plane diagonal of the corner
element, so that the element touching the corner always belongs to the corner zone.

The verdict of a single mesh is a flag, not a proof: a negative eigenvalue is physics
only if its onset converges under refinement (``validation.studies.buckling`` compares meshes).
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any, Sequence

import numpy as np

from ..checks import check_count, check_nonnegative_int, check_positive
from ..gallery.drivers import newton_guards
from ..linalg.inertia import inertia_factors, reusable_factors
from ..linalg.linear import pardiso_available
from ..models.plate.modes import classify_mode
from ..models.plate.problem import PlateProblem
from ..models.plate.symmetry_classes import class_mode_full, class_tangent, union_tangent
from ..solvers.critical import CriticalLoad, critical_load
from ..solvers.ramp import RampResult
from ..stability.analysis import lowest_modes

__all__ = ["ModeLabel", "BucklingLoad", "corner_radius", "class_spectra", "physical_modes",
           "lowest_physical", "buckling_load"]

@dataclass
class ModeLabel:
    """One classified mode of the whole plate at a state.

    Attributes
    ----------
    eigenvalue
        Eigenvalue of the reduced stiffness (metric of the full plate's nodal displacements).
    symmetry
        Name of its symmetry class (e.g. ``"x1 S, x2 A, x3 S"``).
    increments
        The class's parities, axis -> ``"symmetric"`` / ``"antisymmetric"``.
    corner_share, mesh_scale, kind
        As :func:`~skfem_dielectric.models.plate.modes.classify_mode` (radius
        :func:`corner_radius`).
    mode
        Full dof vector of the mode.
    """

    eigenvalue: float
    symmetry: str
    increments: dict
    corner_share: float
    mesh_scale: float
    kind: str
    mode: np.ndarray = field(repr=False)


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
        :class:`ModeLabel` of the critical mode (at ``load``), else ``None``.
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


def corner_radius(problem: PlateProblem) -> float:
    """Radius of the clamp/free-edge corner zone: ``max(2 H, d)`` with ``d`` the in-plane
    diagonal of the element at the corner (module docstring)."""
    if not isinstance(problem, PlateProblem):
        raise ValueError(f"problem must be a PlateProblem, got {type(problem).__name__}")
    g1, _, g3 = problem.plate.grids
    d = float(np.hypot(g1[-1] - g1[-2], g3[-1] - g3[-2]))
    return max(2.0 * problem.plate.H, d)


def _spectra_threads(method: str) -> int:
    """Worker threads of :func:`class_spectra`: two (at most the cores) where SuperLU or a
    dense count factorises the classes (single-threaded, and they release the GIL:
    two classes at once use both cores), one where PARDISO does (its MKL threads already
    use them)."""
    uses_pardiso = method == "pardiso" or (method == "auto" and pardiso_available())
    return 1 if uses_pardiso else max(1, min(2, os.cpu_count() or 1))


def class_spectra(problem: PlateProblem, x: np.ndarray, load: Any, *, extra: int = 2,
                  grad_div: float | None = None, method: str = "auto",
                  only: Sequence[str] | None = None,
                  threads: int | None = None) -> list[tuple]:
    """Per symmetry class: every negative eigenpair and ``extra`` more above them.

    :func:`~skfem_dielectric.models.plate.symmetry_classes.class_stability` asks each class for the
    same number of modes; a class with many flagged negative modes then hides its lowest
    positive (physical) one.  Here each class gets its own count first (inertia), then
    ``n_negative + extra`` eigenpairs.

    Parameters
    ----------
    problem, x, load
        A symmetric-coupling plate and a state of it.
    extra
        Eigenpairs above the negative ones, per class.
    grad_div
        Grad-div stabilisation of the analysed tangent (units of ``mu``; default the
        model's own: the Hessian of the state's energy).
    method
        Inertia method.
    only
        Names of the classes to analyse (default all).
    threads
        Classes analysed at once (default two where SuperLU factorises, one with PARDISO,
        whose own threads use the cores).  The classes are independent: the result is
        the same bit for bit whatever the number.

    Returns
    -------
    list of (SymmetryClass, n_negative, eigenvalues, modes)
        Modes as vectors of the class's unknowns (unit in the class metric), in the order
        of the classes.
    """
    extra = check_count("extra", extra)
    threads = _spectra_threads(method) if threads is None else check_count("threads",
                                                                            threads)
    classes, K = union_tangent(problem, x, load, grad_div)

    def spectrum(c):
        Kc = class_tangent(c, K)
        inertia, factors = inertia_factors(Kc, method)
        n_neg = inertia[1] - c.layout.n_multipliers
        vals, vecs = lowest_modes(Kc, c.metric, n_neg + extra, max(n_neg, 0), tol=1e-10,
                                  factors=reusable_factors(factors, inertia, n_neg))
        del factors
        return c, n_neg, vals, vecs

    todo = [c for c in classes if only is None or c.name in only]
    if threads == 1 or len(todo) < 2:
        return [spectrum(c) for c in todo]
    with ThreadPoolExecutor(min(threads, len(todo))) as pool:
        return list(pool.map(spectrum, todo))


def physical_modes(problem: PlateProblem, x: np.ndarray, load: Any, *, extra: int = 2,
                   grad_div: float | None = None, method: str = "auto",
                   radius: float | None = None, stop_at_physical: bool = True,
                   only: Sequence[str] | None = None) -> tuple[list[ModeLabel], int]:
    """Classified modes of the whole plate at a state, ascending.

    Parameters
    ----------
    problem, x, load
        A symmetric-coupling plate and a converged state of it.
    extra, grad_div, method
        As :func:`class_spectra`.
    radius
        Corner radius (default :func:`corner_radius`).
    stop_at_physical
        Stop classifying after the first physical mode.
    only
        Names of the classes to analyse (default all, the whole plate).

    Returns
    -------
    labels : list of ModeLabel
        The classified modes, ascending.
    n_negative : int
        Negative eigenvalues of the whole plate's reduced stiffness (of the classes
        ``only``).
    """
    r = corner_radius(problem) if radius is None else check_positive("radius", radius)
    spectra = class_spectra(problem, x, load, extra=extra, grad_div=grad_div, method=method,
                            only=only)
    xf = problem.full(x, load)
    order = sorted((float(v), i, j) for i, (_, _, vals, _) in enumerate(spectra)
                   for j, v in enumerate(vals))
    out = []
    for v, i, j in order:
        c, _, _, vecs = spectra[i]
        w = class_mode_full(c, vecs[:, j])
        lab = classify_mode(problem, xf, w, symmetry=c.name, radius=r)
        out.append(ModeLabel(v, c.name, dict(c.increments), lab["corner_share"],
                             lab["mesh_scale"], lab["kind"], w))
        if stop_at_physical and lab["kind"] == "physical":
            break
    return out, sum(n for _, n, _, _ in spectra)


def lowest_physical(problem: PlateProblem, x: np.ndarray, load: Any,
                    **options) -> tuple[ModeLabel | None, list[ModeLabel], int]:
    """The lowest physical mode of the whole plate at a state.

    Returns
    -------
    physical : ModeLabel or None
        ``None`` if no computed mode is physical.
    labels : list of ModeLabel
        Every classified mode up to it (:func:`physical_modes`).
    n_negative : int
    """
    labels, n_neg = physical_modes(problem, x, load, **options)
    phys = [m for m in labels if m.kind == "physical"]
    return (phys[0] if phys else None), labels, n_neg


def _scan_row(load, phys, labels, n_neg) -> dict:
    s, d = (float(v) for v in np.asarray(load, dtype=float))
    return {"s": s, "D0": d, "n_negative": int(n_neg),
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
        As :func:`physical_modes`.
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
        phys, labels, n_neg = lowest_physical(problem, x, load, **opts)
        scan.append(_scan_row(load, phys, labels, n_neg))
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
            c, _, vals, vecs = class_spectra(problem, x, load, only=[cls], **spec)[0]
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

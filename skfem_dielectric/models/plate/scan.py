"""Event-driven scan of a plate's states along a load path: counts at every state, modes
only where a count changes.

Along a ramp the whole plate's spectrum (the union of the symmetry classes of a reduced
model, :mod:`~skfem_dielectric.models.plate.symmetry_classes`) changes its negative
count only where an eigenvalue crosses zero.  Sylvester's law gives that count per class
from one symmetric factorisation; eigenvectors are needed only to say *what* crossed --
a physical mode, a clamp-corner mode or a mesh-scale mode
(:func:`~skfem_dielectric.models.plate.modes.classify_mode`).  So at each state
:class:`PlateScan`

* factorises each class's tangent once and reads its negative count;
* where a class's count is unchanged from the previous state, computes nothing more:
  the negative modes of that class keep the labels they had;
* where it rises by ``m``, computes the ``m + extra`` eigenpairs nearest to zero on the
  same factors (:func:`~skfem_dielectric.stability.analysis.modes_near_zero`) and
  classifies the ``m`` negative ones nearest to zero -- the ones that have just crossed;
  where it falls by ``m``, the ``m`` positive ones nearest to zero, the ones that have
  crossed back;
* keeps, per class, how many of its negative modes are labelled physical.

The first physical buckling load lies between the last state without a physical negative
mode and the first with one (located by
:func:`~skfem_dielectric.studies.buckling.locate_buckling`).  At the first state scanned
(no previous counts) every negative mode of every class is classified.

Two events inside one step that cancel in one class's count (a mode crossing down while
another crosses back) are not seen; a step of the ramp small enough that counts change by
a few at a time keeps that unlikely, and the full-spectrum scan
(:func:`~skfem_dielectric.models.plate.modes.lowest_physical` at every state) remains
available to check it.
"""

from __future__ import annotations

import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...checks import check_count, check_positive
from ...linalg.inertia import inertia_factors, reusable_factors
from ...linalg.linear import pardiso_available
from ...linalg.solver_base import back_substitution_count, factorisation_count
from ...stability.analysis import lowest_modes, modes_near_zero
from .modes import ModeLabel, classify_mode, corner_radius
from .problem import PlateProblem
from .symmetry_classes import (class_mode_full, class_tangent, class_threads, class_upper,
                               symmetry_classes, union_tangent, union_upper)

__all__ = ["ScanRow", "PlateScan"]


@dataclass
class ScanRow:
    """One state of an event-driven scan (:class:`PlateScan`).

    Attributes
    ----------
    load
        ``(s, D0)`` of the state.
    counts
        Negative eigenvalues of each symmetry class's reduced stiffness (class name ->
        count).
    n_zero
        Zero pivots over all classes (a singular tangent).
    changed
        Names of the classes whose count differs from the previous state's (every class
        with a negative eigenvalue at the first state scanned).
    labels
        The modes classified at this state (those that crossed zero), ascending.
    n_physical
        Negative modes labelled physical, whole plate (carried from state to state).
    factorisations, back_substitutions, cpu
        What the state cost: sparse factorisations, Lanczos back-substitutions and CPU
        seconds of this process.
    """

    load: np.ndarray
    counts: dict[str, int]
    n_zero: int
    changed: list[str]
    labels: list[ModeLabel]
    n_physical: int
    factorisations: int = 0
    back_substitutions: int = 0
    cpu: float = 0.0

    @property
    def n_negative(self) -> int:
        """Negative eigenvalues of the whole plate's reduced stiffness."""
        return int(sum(self.counts.values()))

    @property
    def new_physical(self) -> ModeLabel | None:
        """The lowest negative mode classified at this state as physical, or ``None``."""
        phys = [m for m in self.labels if m.kind == "physical" and m.eigenvalue < 0]
        return phys[0] if phys else None

    @property
    def stable(self) -> bool:
        """No negative mode labelled physical and a non-singular tangent."""
        return self.n_physical == 0 and self.n_zero == 0


class PlateScan:
    """Scan the states of a plate along a load path, in load order (module docstring).

    Parameters
    ----------
    problem
        A symmetric-coupling :class:`~skfem_dielectric.models.plate.problem.PlateProblem`.
    extra
        Eigenpairs beyond the ones that crossed, per changed class (at least 1): Lanczos
        separates the wanted ones better with a few more.
    grad_div, method
        Grad-div stabilisation of the analysed tangent (units of ``mu``; default the
        model's own) and inertia method, as
        :func:`~skfem_dielectric.models.plate.symmetry_classes.class_stability`.
    radius
        Corner radius of the classification (default
        :func:`~skfem_dielectric.models.plate.modes.corner_radius`).
    tol
        ARPACK's relative tolerance of the eigenvalues.
    state
        The :attr:`state` of a scan to continue (its previous counts and physical
        labels), e.g. saved with a resumable ramp; ``None`` starts afresh.

    Raises
    ------
    ValueError
        A non-symmetric coupling, bad ``extra``/``radius``/``tol``, or a ``state`` that
        does not match the problem's classes.
    """

    def __init__(self, problem: PlateProblem, *, extra: int = 2, grad_div: float | None = None,
                 method: str = "auto", radius: float | None = None, tol: float = 1e-10,
                 state: dict | None = None) -> None:
        if not isinstance(problem, PlateProblem):
            raise ValueError(f"problem must be a PlateProblem, got {type(problem).__name__}")
        if not problem.symmetric:
            raise ValueError("the Maxwell coupling has no symmetric tangent: scan the fully "
                             "coupled model")
        self.problem = problem
        self.extra = check_count("extra", extra)
        self.grad_div, self.method = grad_div, method
        self.radius = corner_radius(problem) if radius is None else check_positive("radius",
                                                                                  radius)
        self.tol = check_positive("tol", tol)
        self.classes = symmetry_classes(problem)
        self.counts: dict[str, int] | None = None
        self.physical = {c.name: 0 for c in self.classes}
        #: the :class:`ScanRow` of the last state analysed
        self.last: ScanRow | None = None
        if state is not None:
            self._restore(state)

    # ------------------------------------------------------------------ resume
    @property
    def state(self) -> dict:
        """What a resumed scan needs, as arrays: ``{"counts": ..., "physical": ...}`` in
        the order of the classes (``counts`` is empty before the first state)."""
        names = [c.name for c in self.classes]
        counts = [] if self.counts is None else [self.counts[n] for n in names]
        return {"counts": np.array(counts, dtype=np.int64),
                "physical": np.array([self.physical[n] for n in names], dtype=np.int64)}

    def _restore(self, state: dict) -> None:
        names = [c.name for c in self.classes]
        counts = np.asarray(state.get("counts", []), dtype=np.int64).ravel()
        phys = np.asarray(state.get("physical", np.zeros(len(names))), dtype=np.int64).ravel()
        if counts.size not in (0, len(names)) or phys.size != len(names):
            raise ValueError(f"state must hold one count per symmetry class ({len(names)}), "
                             f"got counts of size {counts.size} and physical of size "
                             f"{phys.size}")
        self.counts = None if counts.size == 0 else dict(zip(names, map(int, counts)))
        self.physical = dict(zip(names, map(int, phys)))

    # ------------------------------------------------------------------ one state
    def _class_modes(self, c, K, prev: int | None):
        """Count of class ``c`` and, where it changed, the eigenpairs that crossed:
        ``(inertia, vals, vecs, side)`` with ``side`` -1 (new negative ones), +1 (ones
        that crossed back) or 0 (none computed)."""
        Kc = class_tangent(c, K)
        inertia, factors = inertia_factors(Kc, self.method, c.orders)
        n_neg = inertia[1] - c.layout.n_multipliers
        nd = int(np.count_nonzero(c.metric.diagonal() > 0))
        none = (inertia, np.zeros(0), np.zeros((Kc.shape[0], 0)), 0)
        usable = reusable_factors(factors, inertia)
        if prev is None:                 # first state: every negative one
            if n_neg <= 0:
                return none
            vals, vecs = lowest_modes(Kc, c.metric, min(n_neg, nd - 1), n_neg, tol=self.tol,
                                      factors=usable, orders=c.orders)
            return inertia, vals, vecs, -1
        delta = n_neg - prev
        if delta == 0:
            return none
        side = -1 if delta > 0 else 1
        need = abs(delta)
        # a mode that has just crossed lies near zero: the nearest ones on both sides first
        # (both ends of the shift-invert spectrum, cheap); a new negative one that went
        # deeper in one step than the soft positive ones next to zero is not among them:
        # then the negative ones nearest to zero (the far end, costlier)
        k = min(need + self.extra, nd - 1)
        vals, vecs = modes_near_zero(Kc, c.metric, k, side="both", factors=usable,
                                     tol=self.tol)
        on_side = np.flatnonzero(vals < 0) if side < 0 else np.flatnonzero(vals >= 0)
        if on_side.size < need and side < 0:
            vals, vecs = modes_near_zero(Kc, c.metric, min(need, n_neg, nd - 1),
                                         side="negative", factors=usable, tol=self.tol)
            on_side = np.flatnonzero(vals < 0)
        elif on_side.size < need:
            vals, vecs = modes_near_zero(Kc, c.metric, k, side="positive", factors=usable,
                                         tol=self.tol)
            on_side = np.flatnonzero(vals >= 0)
        # the ``need`` nearest to zero on that side are the ones that crossed
        near = np.sort(on_side[np.argsort(np.abs(vals[on_side]), kind="stable")][:need])
        return inertia, vals[near], vecs[:, near], side

    def count(self, x: np.ndarray, load: Any) -> dict[str, int]:
        """Count the negative eigenvalues of every class at a state, without eigenpairs,
        and take the state as the previous one of the next :meth:`analyse`.

        One factorisation per class and no eigenpair: for a state known to have no
        physical negative mode (an earlier scan of the same path said so), where
        :meth:`analyse` from scratch would compute every negative mode to classify it.
        The physical counts are set to zero.  Each class's factors are freed before the
        next class is factorised: the count holds one factorisation at a time.  With
        PARDISO the count holds only upper triangles: that of the union tangent, assembled
        directly (:func:`~skfem_dielectric.models.plate.symmetry_classes.union_upper`), and
        that of one class at a time
        (:func:`~skfem_dielectric.models.plate.symmetry_classes.class_upper`).

        Parameters
        ----------
        x, load
            A converged state of the problem (reduced vector, ``(s, D0)``).

        Returns
        -------
        dict
            Negative eigenvalues per class name.
        """
        upper = self.method == "pardiso" or (self.method == "auto" and pardiso_available())
        classes, K = (union_upper if upper else union_tangent)(self.problem, x, load,
                                                               self.grad_div)
        counts = {}
        for c in classes:
            Kc = class_upper(c, K) if upper else class_tangent(c, K)
            inertia, factors = inertia_factors(Kc, self.method, c.orders)
            del Kc
            if factors is not None and callable(getattr(factors, "discard", None)):
                factors.discard()        # not held while the next class is factorised
            del factors
            counts[c.name] = int(inertia[1] - c.layout.n_multipliers)
        self.counts = counts
        self.physical = {c.name: 0 for c in self.classes}
        return dict(counts)

    def analyse(self, x: np.ndarray, load: Any) -> ScanRow:
        """Count every class at the state ``(x, load)`` and classify what crossed zero
        since the previous state.

        Parameters
        ----------
        x, load
            A converged state of the problem (reduced vector, ``(s, D0)``), later on the
            path than the previous one analysed.

        Returns
        -------
        ScanRow
        """
        t0, f0, b0 = time.process_time(), factorisation_count(), back_substitution_count()
        problem = self.problem
        classes, K = union_tangent(problem, x, load, self.grad_div)
        prev = self.counts

        def work(c):
            return self._class_modes(c, K, None if prev is None else prev[c.name])

        threads = class_threads(self.method)
        if threads == 1:
            results = [work(c) for c in classes]
        else:
            with ThreadPoolExecutor(threads) as pool:
                results = list(pool.map(work, classes))
        xf = None
        labels, changed, counts, n_zero = [], [], {}, 0
        for c, (inertia, vals, vecs, side) in zip(classes, results):
            n_neg = inertia[1] - c.layout.n_multipliers
            counts[c.name] = int(n_neg)
            n_zero += int(inertia[2])
            if prev is None and n_neg > 0 or prev is not None and n_neg != prev[c.name]:
                changed.append(c.name)
            if not vals.size:
                continue
            xf = problem.full(x, load) if xf is None else xf
            n_phys = 0
            for j in range(vals.size):
                w = class_mode_full(c, vecs[:, j])
                lab = classify_mode(problem, xf, w, symmetry=c.name, radius=self.radius)
                labels.append(ModeLabel(float(vals[j]), c.name, dict(c.increments),
                                        lab["corner_share"], lab["mesh_scale"], lab["kind"], w))
                n_phys += lab["kind"] == "physical"
            if prev is None:
                self.physical[c.name] = n_phys
            else:
                self.physical[c.name] = max(0, self.physical[c.name] - side * n_phys)
        labels.sort(key=lambda m: m.eigenvalue)
        self.counts = counts
        self.last = ScanRow(np.asarray(load, dtype=float).copy(), counts, n_zero, changed,
                            labels, int(sum(self.physical.values())),
                            factorisation_count() - f0, back_substitution_count() - b0,
                            time.process_time() - t0)
        return self.last

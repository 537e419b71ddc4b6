"""Stability of a symmetric plate state by symmetry classes of its increments.

A plate model cut by the symmetry planes ``x_i = 0`` computes states that are symmetric
with respect to every plane; its own constraints admit only the *mirror-symmetric*
increments.  The full plate's increments are the direct sum of ``2^m`` classes (``m``
planes; per plane symmetric or antisymmetric,
:func:`~skfem_dielectric.models.plate.problem.plate_reduction`)
and its tangent is block diagonal in them.  So the negative-eigenvalue count of the full
plate is the sum of the classes' counts, and its spectrum the union of theirs, at the cost
of ``2^m`` factorisations of the reduced model's size: bending (``x2`` antisymmetric) and
sway modes that the reduced model itself cannot show.

The classes' tangents are assembled once per state on the *union* space (every dof free in
some class) and restricted by sparse prolongations ``K_c = P_c^T K P_c``.
"""

from __future__ import annotations

import weakref
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any, Sequence

import numpy as np
import scipy.sparse as sp

from ...checks import check_count
from ...fem.assembly import DofReduction
from ...fem.runtime import assembly_threads
from ...linalg.linear import pardiso_available
from ...linalg.symmetric import SymmetricUpper
from ...problem import Layout
from ...stability.analysis import StabilityResult, tangent_stability
from .problem import PlateProblem, increment_classes, plate_reduction

__all__ = ["SymmetryClass", "ClassStability", "symmetry_classes", "class_stability",
           "class_mode_full", "union_tangent", "union_upper", "class_tangent", "class_upper",
           "class_threads"]

#: per base problem: the union-space problem and its classes (built once)
_CACHE: "weakref.WeakKeyDictionary[PlateProblem, tuple]" = weakref.WeakKeyDictionary()


@dataclass
class SymmetryClass:
    """One symmetry class of the increments of a plate model.

    Attributes
    ----------
    increments
        Axis -> ``"symmetric"`` or ``"antisymmetric"``.
    red
        Its dof reduction (of the full dofs).
    layout
        Its :class:`~skfem_dielectric.problem.Layout` (multiplier blocks ``p``, ``phi``).
    P
        Prolongation from the class's unknowns to the union space's.
    metric
        Diagonal metric of its modes: on each displacement unknown the number of its
        mirror images in the full plate over ``2^m`` (1 inside, 1/2 on one plane, ...),
        zero on the multipliers -- so that the Euclidean norm of the full plate's nodal
        displacements restricts to it, and the classes' eigenvalues are the full plate's.
    orders
        The SuperLU elimination order of its tangents (``orders`` of
        :func:`~skfem_dielectric.linalg.inertia.inertia_factors`): filled at the first
        analysis that needs the constrained order, used by every later one of the same
        pattern (the tangents of all charged states have one pattern and one zero
        diagonal; the uncharged one lacks the electric coupling entries), so that each
        state's count costs one factorisation.
    """

    increments: dict[int, str]
    red: DofReduction
    layout: Layout
    P: sp.csr_matrix
    metric: sp.csr_matrix
    orders: list = field(default_factory=list, repr=False)

    @property
    def ndofs(self) -> int:
        """Number of unknowns of the class."""
        return self.red.n

    @property
    def name(self) -> str:
        """E.g. ``"x1 S, x2 A, x3 S"`` (S symmetric, A antisymmetric); ``"full"`` for a
        model without symmetry planes."""
        return ", ".join(f"x{ax} {v[0].upper()}"
                         for ax, v in sorted(self.increments.items())) or "full"


@dataclass
class ClassStability:
    """Stability of one state over the symmetry classes (every class, or those asked for:
    ``only`` of :func:`class_stability`).

    Attributes
    ----------
    classes, results
        The classes and, per class, its
        :class:`~skfem_dielectric.stability.analysis.StabilityResult`.
    """

    classes: list[SymmetryClass]
    results: list[StabilityResult] = field(default_factory=list)

    @property
    def n_negative(self) -> int:
        """Negative eigenvalues of the full plate's reduced stiffness (sum over the
        classes; of the classes analysed)."""
        return sum(r.n_negative for r in self.results)

    @property
    def n_zero(self) -> int:
        """Zero pivots, summed over the classes."""
        return sum(r.n_zero for r in self.results)

    @property
    def stable(self) -> bool:
        """Every class stable."""
        return all(r.stable for r in self.results)

    def lowest(self, k: int | None = None) -> list[tuple[float, str, int]]:
        """The computed eigenvalues of all classes, ascending, as ``(value, class name,
        index of the mode in that class's result)``; the first ``k`` (default all)."""
        out = [(float(v), c.name, j) for c, r in zip(self.classes, self.results)
               for j, v in enumerate(r.eigenvalues)]
        out.sort()
        return out if k is None else out[:k]


def _union(problem: PlateProblem):
    if problem not in _CACHE:
        opts = dict(problem.options, increments="union")
        union = PlateProblem(problem.plate, problem.material, **opts)
        fields = union.form.fields
        classes = []
        for inc in increment_classes(problem.plate.symmetry):
            red = plate_reduction(problem, inc)
            free = np.flatnonzero(red.index >= 0)
            rows, cols = union.red.index[free], red.index[free]
            pairs = np.unique(np.column_stack([rows, cols]), axis=0)
            P = sp.csr_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])),
                              shape=(union.red.n, red.n))
            layout = Layout.from_reduction(red, fields, ("p", "phi"))
            classes.append(SymmetryClass(inc, red, layout, P,
                                         _class_metric(problem, red, layout)))
        _CACHE[problem] = (union, classes)
    return _CACHE[problem]


def _class_metric(problem: PlateProblem, red: DofReduction, layout: Layout):
    """Mirror-image weights of the displacement unknowns (see :class:`SymmetryClass`)."""
    sym = problem.plate.symmetry
    X = problem.b2.doflocs
    on_planes = np.zeros(X.shape[1], dtype=int)
    for ax in sym:
        on_planes += np.abs(X[ax - 1]) < 1e-9 * problem.plate.L1
    n_u = problem.n_u
    free_u = np.flatnonzero(red.index[:n_u] >= 0)
    unknown = red.index[free_u]
    weight = np.zeros(red.n)
    weight[unknown] = 0.5 ** on_planes[free_u // 3]
    counts = np.bincount(unknown, minlength=red.n)
    # a tied unknown (the rigid clamp) is one unknown of the full plate per x1 face
    weight[counts > 1] = 2.0 ** ((1 in sym) - len(sym))
    for name in layout.multipliers:
        weight[layout.blocks[name]] = 0.0
    return sp.diags(weight).tocsr()


def symmetry_classes(problem: PlateProblem) -> list[SymmetryClass]:
    """The ``2^m`` symmetry classes of the increments of ``problem`` (``m`` symmetry
    planes; the all-symmetric class, the model's own, first)."""
    if not isinstance(problem, PlateProblem):
        raise ValueError(f"problem must be a PlateProblem, got {type(problem).__name__}")
    return _union(problem)[1]


def class_threads(method: str) -> int:
    """Worker threads of :func:`class_stability`: two (at most the cores) where SuperLU or a
    dense count factorises the classes (single-threaded, and they release the GIL: two
    classes at once use both cores), one where PARDISO does (its MKL threads already use
    them)."""
    uses_pardiso = method == "pardiso" or (method == "auto" and pardiso_available())
    return 1 if uses_pardiso else assembly_threads()


def class_stability(problem: PlateProblem, x: np.ndarray, load: Any, *, k: int = 1,
                    method: str = "auto", grad_div: float | None = None,
                    all_negative: bool = False, extra: int = 0, tol: float = 1e-10,
                    only: Sequence[str] | None = None,
                    threads: int | None = None) -> ClassStability:
    """Negative-eigenvalue count and lowest modes of every symmetry class at a state.

    The tangent of the full plate is block diagonal in the classes, so its count is the
    sum of theirs and its spectrum the union of theirs (module docstring).  Each class is
    counted by its own factorisation, which also serves its modes.

    Parameters
    ----------
    problem
        A symmetric-coupling :class:`~skfem_dielectric.models.plate.problem.PlateProblem` (its
        symmetry planes define the classes; a full plate has one class, itself).
    x, load
        A state of ``problem`` (reduced vector and load).
    k
        Lowest eigenpairs per class (0: counts only).
    method
        Inertia method (:func:`~skfem_dielectric.linalg.inertia.tangent_inertia`).
    grad_div
        Grad-div stabilisation of the analysed tangent in units of ``mu`` (default: the
        model's own,
        :meth:`~skfem_dielectric.models.plate.problem.PlateProblem.stabilised_tangent`).
    all_negative, extra, tol
        As in :func:`~skfem_dielectric.stability.analysis.tangent_stability`, per class:
        with ``all_negative`` each class gets its own number of modes, its negative ones
        and ``extra`` more (asking every class for the same ``k`` would let a class with
        many negative modes hide its lowest positive one).
    only
        Names of the classes to analyse (default all, the whole plate).
    threads
        Classes analysed at once (default two where SuperLU or a dense count factorises,
        one with PARDISO, whose own threads use the cores).  The classes are independent:
        the result is the same bit for bit whatever the number.

    Returns
    -------
    ClassStability
        The classes analysed (those named in ``only``, in the order of
        :func:`symmetry_classes`) and their results; modes are vectors of each class's
        unknowns (unit in the class metric), :func:`class_mode_full` expands them.

    Raises
    ------
    ValueError
        A non-symmetric (Maxwell) coupling, ``x`` of the wrong size, ``threads`` below 1,
        or a negative ``extra``.
    """
    threads = class_threads(method) if threads is None else check_count("threads", threads)
    classes, K = union_tangent(problem, x, load, grad_div)

    def analyse(c):
        return tangent_stability(c, class_tangent(c, K), k=k, method=method,
                                 all_negative=all_negative, extra=extra, tol=tol,
                                 metric=c.metric, orders=c.orders)

    todo = [c for c in classes if only is None or c.name in only]
    if threads == 1 or len(todo) < 2:
        return ClassStability(todo, [analyse(c) for c in todo])
    with ThreadPoolExecutor(min(threads, len(todo))) as pool:
        return ClassStability(todo, list(pool.map(analyse, todo)))


def union_tangent(problem: PlateProblem, x: np.ndarray, load: Any,
                  grad_div: float | None = None) -> tuple[list[SymmetryClass], sp.csr_matrix]:
    """The symmetry classes of ``problem`` and the tangent at ``(x, load)`` on their union
    space, which every class restricts (:func:`class_tangent`).

    Raises
    ------
    ValueError
        A non-symmetric (Maxwell) coupling, or ``x`` of the wrong size.
    """
    classes, union, xf, gd = _union_state(problem, x, load, grad_div)
    return classes, union.scatter.csr(union.form.assemble(xf, gd)[0])


def _union_state(problem: PlateProblem, x: np.ndarray, load: Any, grad_div: float | None):
    """The classes, the union-space problem, the full dof vector of ``(x, load)`` and the
    grad-div weight in stress units, checked (see :func:`union_tangent`)."""
    classes = symmetry_classes(problem)
    if not problem.symmetric:
        raise ValueError("the Maxwell coupling has no symmetric tangent: analyse the fully "
                         "coupled model")
    x = np.asarray(x, dtype=float)
    if x.shape != (problem.ndofs,):
        raise ValueError(f"x must have shape ({problem.ndofs},), got {x.shape}")
    gd = problem.grad_div if grad_div is None else float(grad_div)
    return classes, _union(problem)[0], problem.full(x, load), gd * problem.material.mu


def union_upper(problem: PlateProblem, x: np.ndarray, load: Any,
                grad_div: float | None = None) -> tuple[list[SymmetryClass], sp.csr_matrix]:
    """:func:`union_tangent` as its upper triangle (CSR, the diagonal included), assembled
    directly: half the memory of the whole union tangent, for the classes' upper
    triangles (:func:`class_upper`) that a count by PARDISO factorises.

    Raises
    ------
    ValueError
        As :func:`union_tangent`.
    """
    classes, union, xf, gd = _union_state(problem, x, load, grad_div)
    return classes, union.form.upper_scatter.csr(union.form.assemble(xf, gd, upper=True)[0])


def class_upper(c: SymmetryClass, U: sp.csr_matrix) -> SymmetricUpper:
    """The tangent of class ``c`` (:func:`class_tangent`) as its upper triangle, every
    diagonal entry stored, from the upper triangle ``U`` of the union tangent
    (:func:`union_upper`), without the whole matrix of either.

    With ``A = P_c^T U P_c`` (the submatrix ``U[s][:, s]`` where ``P_c`` selects), every
    pair of off-diagonal entries of ``P_c^T K P_c`` appears once in ``A``, above or below
    the diagonal, and is folded above it; the diagonal is ``2 diag(A) - P_c^T diag(U)``
    (a union entry between two tied unknowns counts twice, a diagonal one once).
    """
    sel = _selection(c.P)
    A = (U[sel][:, sel] if sel is not None else c.P.T @ U @ c.P).tocoo()
    n = A.shape[0]
    off = A.row != A.col
    i = np.arange(n)
    diag = 2.0 * A.diagonal() - c.P.T @ U.diagonal()
    Uc = sp.csr_matrix((np.concatenate([A.data[off], diag]),
                        (np.concatenate([np.minimum(A.row[off], A.col[off]), i]),
                         np.concatenate([np.maximum(A.row[off], A.col[off]), i]))),
                       shape=(n, n))
    Uc.sum_duplicates()
    return SymmetricUpper(Uc)


def class_tangent(c: SymmetryClass, K: sp.csr_matrix) -> sp.csr_matrix:
    """The tangent of class ``c``, ``P_c^T K P_c`` of the union-space tangent ``K``, with
    every diagonal entry stored.

    Where ``P_c`` selects (one union unknown per class unknown, each union unknown at most
    once: every class of the plates but the symmetric one, which ties the electrode's
    unknowns) this is the submatrix ``K[s][:, s]``, taken without the products'
    intermediate matrices; otherwise the products.
    """
    sel = _selection(c.P)
    if sel is None:
        return _with_diagonal((c.P.T @ K @ c.P).tocoo())
    Kc = sp.csr_matrix(K)[sel][:, sel]
    n = Kc.shape[0]
    rows = np.repeat(np.arange(n), np.diff(Kc.indptr))
    if np.count_nonzero(Kc.indices == rows) == n:      # every diagonal entry stored
        Kc.sort_indices()
        return Kc
    return _with_diagonal(Kc.tocoo())


def _selection(P: sp.csr_matrix) -> np.ndarray | None:
    """The union unknown of each class unknown where the prolongation ``P`` (of ones)
    only selects: one entry per column and per row; else ``None``."""
    Pc = sp.csc_matrix(P)
    if (np.any(np.diff(Pc.indptr) != 1) or np.any(Pc.data != 1.0)
            or np.unique(Pc.indices).size != Pc.indices.size):
        return None
    return Pc.indices.copy()


def _with_diagonal(K: sp.coo_matrix) -> sp.csr_matrix:
    """CSR with every diagonal entry stored (explicit zeros of the multiplier block:
    PARDISO reports a row without its diagonal as empty)."""
    n = K.shape[0]
    i = np.arange(n)
    return sp.csr_matrix((np.concatenate([K.data, np.zeros(n)]),
                          (np.concatenate([K.row, i]), np.concatenate([K.col, i]))),
                         shape=K.shape)


def class_mode_full(c: SymmetryClass, w: np.ndarray) -> np.ndarray:
    """Full dof vector of a mode ``w`` of class ``c`` (zeros on its fixed dofs)."""
    return c.red.expand(np.asarray(w, dtype=float))

"""Inertia of a symmetric (saddle-point) matrix from a symmetric factorisation.

Sylvester's law: ``P K P^T = L D L^T`` has as many positive, negative and zero pivots in
``D`` as ``K`` has eigenvalues of each sign.  The factorisation is MKL PARDISO's
(LDL^T, ``fast`` extra), or scipy's SuperLU in symmetric mode with diagonal pivots
(``diag_pivot_thresh = 0``; the row and column permutations are checked to be equal, so
that ``U = D L^T``), or, for small systems, a dense eigenvalue count.

:func:`symmetric_lu` keeps the SuperLU factors of such a count, so that the same
factorisation serves the solves of a shift-invert eigenvalue iteration
(:func:`~skfem_dielectric.stability.analysis.lowest_modes`); :class:`SymmetricFactors` hands them on
as a :class:`~skfem_dielectric.linalg.solver_base.LinearSolver` that has factorised ``K``.
"""

from __future__ import annotations

from typing import Callable

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import reverse_cuthill_mckee

from .linear import PardisoSolver, pardiso_available
from .solver_base import LinearSolver, splu

__all__ = ["INERTIA_METHODS", "DENSE_LIMIT", "tangent_inertia", "constrained_order",
           "counted_inertia", "symmetric_lu", "SymmetricFactors", "inertia_factors",
           "reusable_factors", "kept_order", "keep_order"]

INERTIA_METHODS = ("auto", "superlu", "pardiso", "dense")
#: systems up to this size may be counted densely
DENSE_LIMIT = 3000


def tangent_inertia(K: sp.spmatrix, method: str = "auto") -> tuple[int, int, int]:
    """Inertia ``(n_positive, n_negative, n_zero)`` of a symmetric sparse matrix.

    Parameters
    ----------
    K
        Symmetric (possibly indefinite, saddle-point) matrix.
    method
        ``"pardiso"`` (MKL, LDL^T), ``"superlu"`` (symmetric-mode LU with
        diagonal pivots, ``U = D L^T``), ``"dense"`` (eigenvalues; small systems) or
        ``"auto"`` (PARDISO if installed, else SuperLU).

    Returns
    -------
    tuple of int

    Raises
    ------
    ValueError
        Unknown ``method``, a non-square matrix, or a SuperLU factorisation that needed
        off-diagonal pivots (its diagonal then says nothing about the inertia).
    """
    if method not in INERTIA_METHODS:
        raise ValueError(f"method must be one of {INERTIA_METHODS}, got {method!r}")
    if K.shape[0] != K.shape[1]:
        raise ValueError(f"K must be square, got shape {K.shape}")
    n = K.shape[0]
    if method == "auto":
        method = "pardiso" if pardiso_available() else "superlu"
    if method == "dense":
        ev = np.linalg.eigvalsh(K.toarray())
        tol = n * np.finfo(float).eps * max(1.0, float(np.abs(ev).max()))
        return int(np.sum(ev > tol)), int(np.sum(ev < -tol)), int(np.sum(np.abs(ev) <= tol))
    if method == "pardiso":
        solver = PardisoSolver(matching=True)
        solver.solve(K, np.zeros(n))
        return solver.inertia
    return symmetric_lu(K)[0]


def symmetric_lu(K: sp.spmatrix, order: np.ndarray | None = None
                 ) -> tuple[tuple[int, int, int], Callable, np.ndarray | None]:
    """SuperLU of a symmetric matrix with diagonal pivots: its inertia and a solve with it.

    The factorisation of :func:`tangent_inertia` (method ``"superlu"``): minimum degree
    first; where that meets a zero pivot, the order of :func:`constrained_order`.

    Parameters
    ----------
    K
        Symmetric matrix.
    order
        A symmetric elimination order to use instead (the third return value of an
        earlier call for a matrix of the same pattern and zero diagonal, e.g. ``K - sigma
        M`` for another ``sigma``).

    Returns
    -------
    inertia : tuple of int
        ``(n_positive, n_negative, n_zero)``.
    solve : callable
        ``solve(b)`` returns ``K^-1 b`` for a vector ``b``.
    order : ndarray or None
        The constrained order if it was used, else ``None``.

    Raises
    ------
    ValueError
        Off-diagonal pivots in the order used last (the diagonal then says nothing).
    """
    lu = None
    if order is None:
        lu = splu(K, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                  options={"SymmetricMode": True})
        solve = lu.solve
    if lu is None or not np.array_equal(lu.perm_r, lu.perm_c):
        # a zero pivot: a multiplier (zero diagonal) eliminated before the displacements
        # it couples to; retry with an order that puts each such unknown after all its
        # neighbours (then its pivot is the Schur complement -b^T A^-1 b, non-zero)
        order = constrained_order(K) if order is None else np.asarray(order)
        lu = splu(sp.csc_matrix(K)[order][:, order], permc_spec="NATURAL",
                  diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        if not np.array_equal(lu.perm_r, lu.perm_c):
            raise ValueError("SuperLU needed off-diagonal pivots: no inertia from its "
                             "diagonal (use method='dense' or 'pardiso')")
        back = np.argsort(order)

        def solve(b, lu=lu):
            return lu.solve(np.asarray(b, dtype=float)[order])[back]
    d = lu.U.diagonal()
    return (int(np.sum(d > 0)), int(np.sum(d < 0)), int(np.sum(d == 0))), solve, order


def constrained_order(K: sp.spmatrix) -> np.ndarray:
    """A symmetric elimination order for a saddle-point matrix: reverse Cuthill-McKee
    (bandwidth), with every unknown of zero diagonal (a pressure-like multiplier) moved
    right after the last of its neighbours, so that it is eliminated after every unknown
    it couples to and its pivot is a Schur complement, not zero."""
    A = sp.csr_matrix(K, copy=True)
    A.eliminate_zeros()
    n = A.shape[0]
    pos = np.empty(n)
    pos[reverse_cuthill_mckee(A, symmetric_mode=True)] = np.arange(n)
    key = pos.copy()
    zero = np.flatnonzero((A.diagonal() == 0) & (np.diff(A.indptr) > 0))
    if zero.size:
        last = np.maximum.reduceat(pos[A.indices], A.indptr[:-1][np.diff(A.indptr) > 0])
        nonempty = np.flatnonzero(np.diff(A.indptr) > 0)
        full_last = np.full(n, -np.inf)
        full_last[nonempty] = last
        key[zero] = full_last[zero] + 0.5
    return np.argsort(key, kind="stable")


def counted_inertia(K: sp.spmatrix, method: str = "auto") -> tuple[int, int, int]:
    """:func:`tangent_inertia` with the fallback of the stability analyses: small systems
    (``n <= DENSE_LIMIT / 10`` without PARDISO) are counted densely, and where SuperLU
    meets a zero pivot (a multiplier eliminated before its displacements) systems up to
    :data:`DENSE_LIMIT` unknowns are counted densely instead.

    Raises
    ------
    ValueError
        As :func:`tangent_inertia`; for a larger system whose SuperLU factorisation needed
        off-diagonal pivots, one naming the remedy (the ``fast`` extra, PARDISO).
    """
    if method == "auto" and not pardiso_available() and K.shape[0] <= DENSE_LIMIT // 10:
        method = "dense"
    try:
        return tangent_inertia(K, method)
    except ValueError as exc:
        if not (method in ("auto", "superlu") and "off-diagonal pivots" in str(exc)):
            raise
        if K.shape[0] > DENSE_LIMIT:
            raise ValueError(f"{exc}; this tangent ({K.shape[0]} unknowns) is too large "
                             "to be counted densely: install the 'fast' extra (PARDISO)"
                             ) from None
        return tangent_inertia(K, "dense")


class SymmetricFactors(LinearSolver):
    """The SuperLU factors of a symmetric matrix from :func:`symmetric_lu`, as a solver that
    has factorised it: :meth:`resolve` solves with them, ``inertia`` is their count.

    Parameters
    ----------
    inertia
        ``(n_positive, n_negative, n_zero)`` of the factorised matrix.
    solve
        The solve of :func:`symmetric_lu`.
    """

    name = "superlu-symmetric"

    def __init__(self, inertia: tuple[int, int, int], solve: Callable):
        self.inertia = tuple(inertia)
        self._solve = solve

    def solve(self, K: sp.spmatrix, b: np.ndarray) -> np.ndarray:
        """Factorise ``K`` (:func:`symmetric_lu`) and return ``K^-1 b``."""
        self.inertia, self._solve, _ = symmetric_lu(K)
        return self._solve(b)

    def resolve(self, b: np.ndarray) -> np.ndarray:
        """Solve with the factors."""
        return self._solve(b)


def kept_order(orders: list | None, K: sp.spmatrix) -> np.ndarray | None:
    """The elimination order kept in ``orders`` (see :func:`inertia_factors`) if it was
    made for a matrix of ``K``'s pattern (same shape and number of stored entries), else
    the constrained order of ``K`` (:func:`constrained_order`; minimum degree met a zero
    pivot on the other pattern), or ``None`` when nothing is kept: an order made for a
    sparser pattern (e.g. the tangent at ``D0 = 0``, whose electric coupling entries
    vanish) can fill in badly on the full one."""
    if orders and orders[0][0] == (K.shape, K.nnz):
        return orders[0][1]
    if orders:      # minimum degree failed on the other pattern: the constrained order at once
        return constrained_order(K)
    return None


def keep_order(orders: list | None, K: sp.spmatrix, order: np.ndarray | None) -> None:
    """Keep ``order`` (made for ``K``) in ``orders`` for the next matrices of its pattern."""
    if orders is not None and order is not None:
        orders[:] = [((K.shape, K.nnz), order)]


def inertia_factors(K: sp.spmatrix, method: str = "auto", orders: list | None = None
                    ) -> tuple[tuple[int, int, int], LinearSolver | None]:
    """:func:`counted_inertia` of ``K`` and the sparse factorisation that counted it.

    ``orders`` (a list) keeps the SuperLU elimination order from one call to the next for
    matrices of one pattern and zero diagonal (e.g. the tangents of one symmetry class along
    a load path): it receives the constrained order where minimum degree met a zero pivot
    (:func:`symmetric_lu`); holding one made for ``K``'s pattern (:func:`kept_order`), that
    order is used at once, without the minimum-degree factorisation that would fail again.

    Returns
    -------
    inertia : tuple of int
    factors : LinearSolver or None
        A solver holding the factors of ``K`` (``resolve`` solves with them): a
        :class:`~skfem_dielectric.linalg.linear.PardisoSolver` or :class:`SymmetricFactors`;
        ``None`` where the count was dense.
    """
    if method not in INERTIA_METHODS:
        raise ValueError(f"method must be one of {INERTIA_METHODS}, got {method!r}")
    if method == "auto":
        if not pardiso_available() and K.shape[0] <= DENSE_LIMIT // 10:
            return counted_inertia(K, method), None
        method = "pardiso" if pardiso_available() else "superlu"
    if method == "pardiso":
        solver = PardisoSolver(matching=True)
        solver.solve(K, np.zeros(K.shape[0]))
        return solver.inertia, solver
    if method == "superlu":
        try:
            inertia, solve, order = symmetric_lu(K, kept_order(orders, K))
        except ValueError:
            return counted_inertia(K, method), None
        keep_order(orders, K, order)
        return inertia, SymmetricFactors(inertia, solve)
    return counted_inertia(K, method), None


def reusable_factors(factors: LinearSolver | None, inertia: tuple[int, int, int]
                     ) -> LinearSolver | None:
    """The factors of :func:`inertia_factors` to pass on as the shift-0 solver of
    :func:`~skfem_dielectric.stability.analysis.lowest_modes`, or ``None`` for a singular
    matrix.  They serve both of its parts: the negative eigenvalues (the algebraically
    smallest ``1/lambda``) and the lowest positive ones (the largest), so that the count
    and the modes of a state cost one factorisation."""
    if factors is None or inertia[2] != 0:
        return None
    return factors

"""The linear-solver interface and scipy's SuperLU (always available).

:class:`LinearSolver` documents what the Newton iterations, the ramps and the stability
analysis ask of a solver; :class:`SuperLUSolver` is the default implementation.  The
PARDISO solvers (``fast`` extra) and :func:`~skfem_dielectric.linalg.linear.get_linear_solver`
live in :mod:`skfem_dielectric.linalg.linear`.
"""

from __future__ import annotations

import threading

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .symmetric import SymmetricUpper

__all__ = ["LinearSolver", "SuperLUSolver", "whole_matrix", "splu", "factorisation_count",
           "count_factorisation", "back_substitution_count", "count_back_substitution"]


_FACTORISATIONS = [0]
_BACK_SUBSTITUTIONS = [0]
_COUNT_LOCK = threading.Lock()


def count_factorisation() -> None:
    """Add one to :func:`factorisation_count` (every sparse factorisation of the package
    calls it: :func:`splu`, the PARDISO solvers' numerical factorisation)."""
    with _COUNT_LOCK:
        _FACTORISATIONS[0] += 1


def factorisation_count() -> int:
    """Sparse factorisations (SuperLU and PARDISO) of this process so far, over all
    threads: the difference of two readings is what the code between them factorised,
    the measure of the cost of a stability analysis along a path (docs/performance.md)."""
    with _COUNT_LOCK:
        return _FACTORISATIONS[0]


def count_back_substitution(n: int = 1) -> None:
    """Add ``n`` to :func:`back_substitution_count` (the eigenvalue iterations of the
    stability analysis call it once per solve with a factorisation they hold)."""
    with _COUNT_LOCK:
        _BACK_SUBSTITUTIONS[0] += int(n)


def back_substitution_count() -> int:
    """Back-substitutions of the stability analysis's eigenvalue iterations (each Lanczos
    step applies the inverse of a factorised tangent once) in this process so far, over
    all threads: with :func:`factorisation_count`, the cost of a spectrum along a path."""
    with _COUNT_LOCK:
        return _BACK_SUBSTITUTIONS[0]


def splu(A: sp.spmatrix, **options):
    """:func:`scipy.sparse.linalg.splu` of ``A`` (CSC), counted in
    :func:`factorisation_count`; ``options`` are splu's."""
    count_factorisation()
    return spla.splu(sp.csc_matrix(A), **options)


#: precisions of a sparse factorisation (PARDISO's; SuperLU's are double)
PRECISIONS = ("double", "single")


class LinearSolver:
    """Interface of a sparse linear solver (documentation base class).

    Subclasses implement :meth:`solve`.  ``inertia`` is ``None`` or the tuple
    ``(n_positive, n_negative, n_zero)`` of the last factorised matrix.  ``reads_upper``:
    the solver reads only the upper triangle of a symmetric matrix, and takes it as a
    :class:`~skfem_dielectric.linalg.symmetric.SymmetricUpper` (every solver accepts one).
    """

    name = "base"
    inertia: tuple[int, int, int] | None = None
    reads_upper = False

    def solve(self, K: sp.spmatrix, b: np.ndarray) -> np.ndarray:  # pragma: no cover
        """Return ``x`` with ``K x = b``."""
        raise NotImplementedError

    def resolve(self, b: np.ndarray) -> np.ndarray | None:
        """Solve with the last factorised matrix (``None`` if not supported)."""
        return None

    def discard(self) -> None:
        """Free the last factorisation (a new matrix is factorised next): :meth:`resolve`
        returns ``None`` until the next :meth:`solve`."""

    def release(self) -> None:
        """Free all the memory the solver holds for its matrices (the factors and any
        analysis kept for the next matrix of the same pattern); the default is
        :meth:`discard`."""
        self.discard()

    def factor_inertia(self) -> tuple[int, int, int] | None:
        """Inertia ``(n_positive, n_negative, n_zero)`` of the last factorised matrix if
        the factors show it (``None`` otherwise)."""
        return self.inertia


class SuperLUSolver(LinearSolver):
    """scipy SuperLU direct solver.

    Parameters
    ----------
    permc_spec
        Column ordering passed to :func:`scipy.sparse.linalg.splu`; ``"MMD_AT_PLUS_A"``
        (minimum degree on the symmetric pattern, fastest on our saddle-point tangents) or
        ``"COLAMD"``, ``"MMD_ATA"``, ``"NATURAL"``.
    diag_pivot_thresh
        Threshold for partial pivoting; the default 0.1 prefers diagonal pivots, which keeps
        the fill of the symmetric ordering while remaining stable for saddle-point matrices.

    Notes
    -----
    SuperLU does not report the inertia; ``inertia`` stays ``None``.
    """

    name = "superlu"

    def __init__(self, permc_spec: str = "MMD_AT_PLUS_A", diag_pivot_thresh: float = 0.1):
        allowed = ("MMD_AT_PLUS_A", "COLAMD", "MMD_ATA", "NATURAL")
        if permc_spec not in allowed:
            raise ValueError(f"permc_spec must be one of {allowed}, got {permc_spec!r}")
        self.permc_spec = permc_spec
        self.diag_pivot_thresh = float(diag_pivot_thresh)
        self.inertia = None

    def solve(self, K: sp.spmatrix, b: np.ndarray) -> np.ndarray:
        """Factorise ``K`` (CSC copy) and solve ``K x = b``."""
        self._lu = None
        lu = splu(whole_matrix(K), permc_spec=self.permc_spec,
                  diag_pivot_thresh=self.diag_pivot_thresh, options={"SymmetricMode": True})
        self._lu = lu
        return lu.solve(np.asarray(b, dtype=float))

    def discard(self) -> None:
        """Free the LU factors."""
        self._lu = None

    def resolve(self, b: np.ndarray) -> np.ndarray | None:
        """Solve with the last LU factors."""
        lu = getattr(self, "_lu", None)
        return None if lu is None else lu.solve(np.asarray(b, dtype=float))

    def factor_inertia(self) -> tuple[int, int, int] | None:
        """Inertia of the last factorised (symmetric) matrix when SuperLU kept to
        diagonal pivots (equal row and column permutations, so ``U = D L^T`` and
        Sylvester's law gives the inertia from the signs of ``diag(U)``), else ``None``."""
        lu = getattr(self, "_lu", None)
        if lu is None or not np.array_equal(lu.perm_r, lu.perm_c):
            return None
        d = lu.U.diagonal()
        return int(np.sum(d > 0)), int(np.sum(d < 0)), int(np.sum(d == 0))


def whole_matrix(K):
    """``K`` as a sparse matrix (a :class:`~skfem_dielectric.linalg.symmetric.SymmetricUpper` as
    its whole matrix)."""
    return K.tocsr() if isinstance(K, SymmetricUpper) else K

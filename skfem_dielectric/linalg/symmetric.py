"""A symmetric sparse matrix held as its upper triangle.

The symmetric-indefinite PARDISO (:class:`~skfem_dielectric.linalg.linear.PardisoSolver`) reads
only the upper triangle of a tangent.  A problem that assembles that triangle directly
(:meth:`~skfem_dielectric.problem.Problem.assemble_upper`) hands it over as a
:class:`SymmetricUpper`: no full CSR matrix (data and pattern) and no selected copy of it
while the tangent is factorised.  The products that the iterative refinement needs are
``U x + U^T x - diag(U) x``; :meth:`SymmetricUpper.tocsr` gives the whole matrix for the
solvers that read it (SuperLU).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["SymmetricUpper", "same_memory", "same_pattern"]


class SymmetricUpper:
    """The symmetric matrix ``U + U^T - diag(U)`` of an upper-triangular CSR matrix ``U``.

    Parameters
    ----------
    upper
        Square sparse matrix with no entries below the diagonal (converted to CSR with
        sorted indices if it is not; such a CSR matrix is kept as it is, its arrays
        shared).

    Raises
    ------
    ValueError
        ``upper`` not sparse, not square, or with an entry below the diagonal.
    """

    def __init__(self, upper: sp.spmatrix):
        if not sp.issparse(upper) or upper.ndim != 2 or upper.shape[0] != upper.shape[1]:
            raise ValueError(f"upper must be a square sparse matrix, got "
                             f"{type(upper).__name__} of shape {getattr(upper, 'shape', None)}")
        U = upper if sp.isspmatrix_csr(upper) else sp.csr_matrix(upper)
        if not U.has_sorted_indices:
            U = U.sorted_indices()
        # sorted rows: the first entry of each row decides (no index array per entry)
        full = np.flatnonzero(np.diff(U.indptr))
        if np.any(U.indices[U.indptr[full]] < full):
            raise ValueError("upper must have no entries below the diagonal")
        self.upper = U
        self.shape = U.shape
        self.dtype = U.dtype
        self._diag: np.ndarray | None = None

    @classmethod
    def from_full(cls, K: sp.spmatrix) -> "SymmetricUpper":
        """The upper triangle of a symmetric matrix ``K``."""
        return cls(sp.triu(K, format="csr"))

    def diagonal(self) -> np.ndarray:
        """The diagonal (computed once; read off the first entry of each row where every
        row starts with its diagonal entry, once, as in the assembled tangents)."""
        if self._diag is None:
            U, n = self.upper, self.shape[0]
            first = U.indptr[:-1]
            i = np.arange(n)
            lead = (np.diff(U.indptr) > 0).all() and np.array_equal(U.indices[first], i)
            if lead:        # a second entry in the same column would be a duplicate
                more = np.flatnonzero(np.diff(U.indptr) > 1)
                lead = not np.any(U.indices[first[more] + 1] == more)
            self._diag = U.data[first].astype(float) if lead else U.diagonal()
        return self._diag

    def __matmul__(self, x: np.ndarray) -> np.ndarray:
        """``U x + U^T x - diag(U) x`` for a vector or a ``(n, k)`` array ``x``."""
        x = np.asarray(x)
        if x.shape[0] != self.shape[1]:
            raise ValueError(f"x must have {self.shape[1]} rows, got shape {x.shape}")
        U = self.upper
        d = self.diagonal()
        return U @ x + U.T @ x - (d * x if x.ndim == 1 else d[:, None] * x)

    dot = __matmul__

    def tocsr(self) -> sp.csr_matrix:
        """The whole symmetric matrix as CSR (sorted indices)."""
        U = self.upper
        K = (U + U.T - sp.diags(self.diagonal())).tocsr()
        K.sort_indices()
        return K


def same_memory(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether ``a`` and ``b`` view the same memory with the same layout (O(1)).

    Parameters
    ----------
    a, b
        Arrays.

    Returns
    -------
    bool
    """
    return (a.__array_interface__["data"][0] == b.__array_interface__["data"][0]
            and a.shape == b.shape and a.strides == b.strides and a.dtype == b.dtype)


def same_pattern(pattern: tuple[np.ndarray, np.ndarray], A: sp.csr_matrix) -> bool:
    """Whether the CSR matrix ``A`` has the sparsity pattern ``(indptr, indices)``.

    Parameters
    ----------
    pattern
        ``(indptr, indices)``; when read-only (the shared pattern of a
        :class:`~skfem_dielectric.fem.assembly.ScatterMap`), the same memory decides in O(1).
    A
        CSR matrix.

    Returns
    -------
    bool
    """
    indptr, indices = pattern
    if indptr.shape != A.indptr.shape or indices.shape != A.indices.shape:
        return False
    if (not indptr.flags.writeable and same_memory(indptr, A.indptr)
            and same_memory(indices, A.indices)):
        return True
    return bool(np.array_equal(indptr, A.indptr) and np.array_equal(indices, A.indices))

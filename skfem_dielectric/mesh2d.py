"""Helpers for the 2D models: batched assembly of displacement forms, point probes.

:class:`BatchedVectorForm` assembles the residual ``int P : Grad v`` and tangent
``int Grad v : A : Grad du`` of a hyperelastic-type energy on a vector basis
with array operations over all elements and quadrature points at once, with
the sparsity pattern and scatter map built once per basis.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["BatchedVectorForm", "point_gradients"]


class BatchedVectorForm:
    """Batched assembly on a scikit-fem vector basis.

    Parameters
    ----------
    basis : skfem.CellBasis
        Basis of an ``ElementVector`` (shape functions ``phi_a``, gradients
        ``Grad phi_a`` of shape ``(d, d)``).

    Notes
    -----
    ``grad(u)`` gives ``Grad u`` at the quadrature points, ``(d, d, nel, nqp)``;
    ``assemble(P, A)`` returns ``K_ab = sum_q A_ijkl G^a_ij G^b_kl dx`` (CSR)
    and ``r_a = sum_q P_ij G^a_ij dx``.
    """

    def __init__(self, basis):
        self.basis = basis
        self.G = np.array([basis.basis[a][0].grad for a in range(basis.Nbfun)])
        self.dofs = basis.element_dofs  # (nb, nel)
        self.dx = basis.dx
        self.N = basis.N
        nb, nel = self.dofs.shape
        rows = np.broadcast_to(self.dofs[:, None, :], (nb, nb, nel)).ravel()
        cols = np.broadcast_to(self.dofs[None, :, :], (nb, nb, nel)).ravel()
        key = rows.astype(np.int64) * self.N + cols
        ukey, self._pos = np.unique(key, return_inverse=True)
        self._indices = (ukey % self.N).astype(np.int32)
        self._indptr = np.searchsorted(ukey // self.N, np.arange(self.N + 1)).astype(np.int32)
        self._nnz = ukey.size

    def grad(self, u: np.ndarray) -> np.ndarray:
        """``Grad u`` at the quadrature points, shape ``(d, d, nel, nqp)``."""
        return np.einsum("ae,aijeq->ijeq", u[self.dofs], self.G, optimize=True)

    def assemble_vector(self, P: np.ndarray) -> np.ndarray:
        """``r_a = int P : Grad phi_a``."""
        re = np.einsum("ijeq,aijeq->ae", P * self.dx, self.G, optimize=True)
        return np.bincount(self.dofs.ravel(), weights=re.ravel(), minlength=self.N)

    def assemble_matrix(self, A: np.ndarray) -> sp.csr_matrix:
        """``K_ab = int Grad phi_a : A : Grad phi_b``."""
        AG = np.einsum("ijkleq,bkleq->ijbeq", A * self.dx, self.G, optimize=True)
        Ke = np.einsum("aijeq,ijbeq->abe", self.G, AG, optimize=True)
        data = np.bincount(self._pos, weights=Ke.ravel(), minlength=self._nnz)
        return sp.csr_matrix((data, self._indices, self._indptr), shape=(self.N, self.N))

    def assemble(self, P: np.ndarray, A: np.ndarray):
        """``(K, r)``, see :meth:`assemble_matrix` and :meth:`assemble_vector`."""
        return self.assemble_matrix(A), self.assemble_vector(P)


def point_gradients(basis, points: np.ndarray):
    """Shape-function gradients of a vector basis at physical points.

    Parameters
    ----------
    basis : skfem.CellBasis
        Vector basis.
    points : ndarray, shape (d, npts)
        Points inside the mesh.

    Returns
    -------
    G : ndarray, shape (nb, d, d, npts)
        ``Grad phi_a`` at each point (of the element that contains it).
    dofs : ndarray, shape (nb, npts)
        Global dofs of those shape functions.
    """
    mesh, mapping = basis.mesh, basis.mapping
    points = np.asarray(points, dtype=float)
    cells = mesh.element_finder(mapping=mapping)(*points)
    ref = mapping.invF(points[:, :, None], tind=cells)
    G = np.array([basis.elem.gbasis(mapping, ref, a, tind=cells)[0].grad[..., 0]
                  for a in range(basis.Nbfun)])
    return G, basis.element_dofs[:, cells]

"""Helpers for the 2D models: batched element arrays of displacement forms, point probes.

:class:`BatchedVectorForm` computes the element residuals ``int P : Grad v`` and
tangents ``int Grad v : A : Grad du`` of a hyperelastic-type energy on a vector
basis with array operations over all elements and quadrature points at once;
the scatter into the reduced sparse system is the shared
:class:`skfem_dielectric.fem.assembly.ScatterMap`.
"""

from __future__ import annotations

import numpy as np
import skfem as fe

__all__ = ["BatchedVectorForm", "point_gradients", "quarter_quad_mesh"]


class BatchedVectorForm:
    """Batched element arrays on a scikit-fem vector basis.

    Parameters
    ----------
    basis : skfem.CellBasis
        Basis of an ``ElementVector`` (shape functions ``phi_a``, gradients
        ``Grad phi_a`` of shape ``(d, d)``).

    Notes
    -----
    ``grad(u)`` gives ``Grad u`` at the quadrature points, ``(d, d, nel, nqp)``;
    ``element_vectors(P)`` the ``(nel, nb)`` array ``r_a = sum_q P_ij G^a_ij dx``
    and ``element_matrices(A)`` the ``(nel, nb, nb)`` array
    ``K_ab = sum_q A_ijkl G^a_ij G^b_kl dx``; they are scattered with
    :class:`skfem_dielectric.fem.assembly.ScatterMap` (the dof table is
    ``basis.element_dofs.T``), as in the 3D solver.
    """

    def __init__(self, basis):
        self.basis = basis
        self.G = np.array([basis.basis[a][0].grad for a in range(basis.Nbfun)])
        self.dofs = basis.element_dofs  # (nb, nel)
        self.dx = basis.dx

    def grad(self, u: np.ndarray) -> np.ndarray:
        """``Grad u`` at the quadrature points, shape ``(d, d, nel, nqp)``."""
        return np.einsum("ae,aijeq->ijeq", u[self.dofs], self.G, optimize=True)

    def element_vectors(self, P: np.ndarray) -> np.ndarray:
        """``r_a = int P : Grad phi_a`` per element, shape ``(nel, nb)``."""
        return np.einsum("ijeq,aijeq->ea", P * self.dx, self.G, optimize=True)

    def element_matrices(self, A: np.ndarray) -> np.ndarray:
        """``K_ab = int Grad phi_a : A : Grad phi_b`` per element, ``(nel, nb, nb)``."""
        AG = np.einsum("ijkleq,bkleq->ijbeq", A * self.dx, self.G, optimize=True)
        return np.einsum("aijeq,ijbeq->eab", self.G, AG, optimize=True)


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


def quarter_quad_mesh(a1: float, a2: float, n1: int, n2: int, names: tuple[str, str, str, str],
                      b2: float = 0.0):
    """Quadrilateral mesh of the quarter ``[0, a1] x [b2, a2]`` with named boundaries.

    Parameters
    ----------
    a1, a2 : float
        Half-lengths of the modelled rectangle (the symmetry planes are at 0).
    n1, n2 : int
        Elements along each side.
    names : 4 str
        Names of the sides ``x = 0``, ``y = b2``, ``x = a1``, ``y = a2``.
    b2 : float
        Lower end in ``y`` (0: the quarter; ``-a2``: the full height).

    Returns
    -------
    skfem.MeshQuad
    """
    tol = 1e-9 * max(a1, a2)
    mesh = fe.MeshQuad.init_tensor(np.linspace(0, a1, n1 + 1), np.linspace(b2, a2, n2 + 1))
    x0, y0, x1, y1 = names
    return mesh.with_boundaries({
        x0: lambda x: np.abs(x[0]) < tol,
        y0: lambda x: np.abs(x[1] - b2) < tol,
        x1: lambda x: np.abs(x[0] - a1) < tol,
        y1: lambda x: np.abs(x[1] - a2) < tol,
    })

"""The base state of a clamp-edge section, solved on the section's own mesh.

The 3D plate's meshes have elements of a few tenths of a millimetre at the clamp; the field
at the edge where the clamp meets a charged face is singular, so a base state read from them
(:func:`~skfem_dielectric.models.edge_section.plate_base`) is smooth where it should not be,
and is not an equilibrium of the section.  This module solves for the base state on the
section ``[X1_cut, X1_clamp] x [-H/2, H/2]`` itself, at the plate's centre plane ``X3 = 0``,
where the plate is symmetric in ``X3`` (``F_13 = F_31 = F_23 = F_32 = 0``,
``Grad phi . e3 = 0``):

* unknowns ``u1, u2, phi`` (continuous Q2) and ``p`` (continuous Q1), the plate's
  incompressible ``u``-``p``-``phi`` energy with its grad-div term
  (:func:`~skfem_dielectric.materials.ideal_dielectric_response`, Eq. (modelE));
* the out-of-plane stretch ``F_33 = lam3(X1, X2)`` taken from the 3D solution (it varies
  from 1 at the clamp to the plate's ``lam3`` away from it);
* ``u`` of the 3D solution on the clamp face (the clamp's rigid translation along
  ``X1``) and ``u`` and ``phi`` of the 3D solution on the cut; the
  charge ``sigma = D0 sqrt(mu eps)`` per reference area on the faces ``X2 = +-H/2``
  (``N . D_L = -sigma`` on the top face, ``+sigma`` on the bottom one).

Equilibrium is the stationarity of ``int psi dA + sigma (int_top phi - int_bottom phi)``
in ``(u1, u2, phi, p)`` (:class:`SectionBaseProblem`), reached by the package's Newton
with the plate's ``J > 0`` guards from the 3D solution
(:func:`~skfem_dielectric.studies.section_base.solve_section_base`) or, where that is too
far from the section's equilibrium at the edge, by continuation along the 3D ramp's states
(:func:`~skfem_dielectric.studies.section_base.continue_section_base`).  The
terms ``d P_i3 / d X3`` of the 3D equilibrium are left out (the plate's state varies along
``X3`` on the scale of its width), so away from the edge the section's state equals the 3D
one to within that and the 3D discretisation error.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementQuad0, ElementQuad1, ElementQuad2, FacetBasis, LinearForm, MeshQuad

from ..kinematics import segment_det_limit
from ..materials import ideal_dielectric_response
from ..problem import Layout, Problem

__all__ = ["SectionBase", "SectionBaseProblem", "pointwise_tangent", "PRESSURES",
           "pressure_element"]

#: in-plane entries of ``F`` (row-major ``3 i + J``), of ``Grad phi``, and ``p`` in the
#: 13 unknowns ``(F, Grad phi, p)`` of the pointwise tangent
_IN_PLANE = (0, 1, 3, 4, 9, 10, 12)


#: the section's pressure spaces: ``"Q1"`` continuous bilinear (Taylor-Hood with the Q2
#: displacement), ``"P0"`` one constant per element (Q2-P0)
PRESSURES = ("Q1", "P0")


def pressure_element(pressure: str):
    """The scikit-fem element of the pressure space ``pressure`` (:data:`PRESSURES`).

    Raises
    ------
    ValueError
        An unknown ``pressure``.
    """
    if pressure not in PRESSURES:
        raise ValueError(f"pressure must be one of {', '.join(PRESSURES)}, got {pressure!r}")
    return ElementQuad1() if pressure == "Q1" else ElementQuad0()


def _tensor_cells(mesh, X1, X2) -> np.ndarray:
    """The element of a tensor-product quadrilateral mesh that holds each point (a point
    on an element's side: either element), by bisection of the grid lines."""
    g1, g2 = np.unique(mesh.p[0]), np.unique(mesh.p[1])
    c = mesh.p[:, mesh.t].mean(axis=1)
    i = np.searchsorted(g1, c[0]) - 1
    j = np.searchsorted(g2, c[1]) - 1
    index = np.empty((g1.size - 1, g2.size - 1), dtype=np.int64)
    index[i, j] = np.arange(mesh.t.shape[1])
    pi = np.clip(np.searchsorted(g1, X1, side="right") - 1, 0, g1.size - 2)
    pj = np.clip(np.searchsorted(g2, X2, side="right") - 1, 0, g2.size - 2)
    return index[pi, pj]


def _affine_inverse(mp, cells, X1, X2) -> np.ndarray:
    """Reference coordinates ``(2, n, 1)`` of the points in their (rectangular, so affinely
    mapped) elements: the map from three corners, no Newton iteration (whose absolute
    tolerance fails on elements of 0.01 at coordinates of 50)."""
    def at(xi, eta):
        return mp.F(np.array([[xi], [eta]]), tind=cells)[:, :, 0]        # (2, n)
    o, a, b = at(0.0, 0.0), at(1.0, 0.0), at(0.0, 1.0)
    A = np.stack([a - o, b - o], axis=-1)                                 # (2, n, 2)
    d = np.vstack([X1, X2]) - o
    det = A[0, :, 0] * A[1, :, 1] - A[0, :, 1] * A[1, :, 0]
    xi = (A[1, :, 1] * d[0] - A[0, :, 1] * d[1]) / det
    eta = (A[0, :, 0] * d[1] - A[1, :, 0] * d[0]) / det
    return np.vstack([xi, eta])[:, :, None]


@dataclass
class SectionBase:
    """A solved base state of a section
    (:func:`~skfem_dielectric.studies.section_base.solve_section_base`).

    Attributes
    ----------
    x
        The unknowns ``(u1, u2, phi)`` (Q2 each) then ``p`` (Q1).
    iterations
        Newton iterations.
    residual
        The final residual norm relative to that of the 3D state on the section.
    """

    basis2: Basis
    basis1: Basis
    lam3: Callable
    x: np.ndarray
    iterations: int
    residual: float

    def fields(self, X1, X2) -> dict:
        """``u (2, n)``, ``phi``, ``p``, ``F (3, 3, n)`` and ``G = Grad phi (3, n)`` at the
        points ``(X1, X2)`` of the section."""
        X1, X2 = np.asarray(X1, dtype=float).ravel(), np.asarray(X2, dtype=float).ravel()
        b2, b1 = self.basis2, self.basis1
        n2 = b2.N
        mp = b2.mapping
        cells = _tensor_cells(b2.mesh, X1, X2)
        ref = _affine_inverse(mp, cells, X1, X2)
        n = X1.size
        vals = np.zeros((3, n))
        grads = np.zeros((3, 2, n))
        ed2 = b2.element_dofs[:, cells]
        for i in range(ed2.shape[0]):
            df = b2.elem.gbasis(mp, ref, i, tind=cells)[0]
            v, g = np.array(df)[:, 0], df.grad[:, :, 0]
            for f in range(3):
                c = self.x[f * n2 + ed2[i]]
                vals[f] += c * v
                grads[f] += c * g
        p = np.zeros(n)
        ed1 = b1.element_dofs[:, cells]
        for i in range(ed1.shape[0]):
            df = b1.elem.gbasis(mp, ref, i, tind=cells)[0]
            p += self.x[3 * n2 + ed1[i]] * np.array(df)[:, 0]
        F = np.zeros((3, 3, n))
        F[:2, :2] = grads[:2]
        F[0, 0] += 1.0
        F[1, 1] += 1.0
        F[2, 2] = self.lam3(X1, X2)
        G = np.vstack([grads[2], np.zeros((1, n))])
        return {"u": vals[:2], "phi": vals[2], "p": p, "F": F, "G": G}

    def base(self, X1, X2) -> tuple:
        """``(F, G, p)`` at the points: the ``base`` of
        :class:`~skfem_dielectric.models.edge_section.EdgeSection`."""
        f = self.fields(X1, X2)
        return f["F"], f["G"], f["p"]


def pointwise_tangent(r, npt: int) -> np.ndarray:
    """The 13 x 13 second derivatives of ``psi`` in ``(F, Grad phi, p)`` at each of the
    ``npt`` points of a response ``r`` of
    :func:`~skfem_dielectric.materials.ideal_dielectric_response`, shape ``(npt, 13, 13)``
    (``F`` row-major, ``3 i + J``, then ``Grad phi``, then ``p``)."""
    T = np.zeros((npt, 13, 13))
    T[:, :9, :9] = np.moveaxis(r.A_FF.reshape(9, 9, npt), -1, 0)
    T[:, :9, 9:12] = np.moveaxis(r.A_FG.reshape(9, 3, npt), -1, 0)
    T[:, 9:12, :9] = np.swapaxes(T[:, :9, 9:12], 1, 2)
    T[:, 9:12, 9:12] = np.moveaxis(r.A_GG.reshape(3, 3, npt), -1, 0)
    T[:, :9, 12] = np.moveaxis(r.A_Fp.reshape(9, npt), -1, 0)
    T[:, 12, :9] = T[:, :9, 12]
    T[:, 12, 12] = r.A_pp
    return T


class SectionBaseProblem(Problem):
    """The section's base-state equations at one 3D state (module docstring), as a
    :class:`~skfem_dielectric.problem.Problem`: the reduced unknowns are ``(u1, u2, phi,
    p)`` off the clamp and the cut, whose values (and ``F_33``) are the 3D state's.

    Its Newton guards are the plate's: ``J = det F > 0`` at every quadrature point along
    each step (:func:`~skfem_dielectric.kinematics.segment_det_limit`) and no converged
    state with ``J <= 0`` (:meth:`newton_guards`).  Solved by
    :func:`~skfem_dielectric.studies.section_base.solve_section_base`.

    Parameters
    ----------
    g1, g2
        Nodes along ``X1`` (the clamp at ``g1[-1]``, the cut at ``g1[0]``) and ``X2``
        (``-H/2 ... H/2``), e.g. :func:`~skfem_dielectric.models.edge_section.edge_section_grids`.
    material
        The plate's material.
    fields
        ``fields(X1, X2) -> dict`` with ``u``, ``phi``, ``p``, ``F`` of the 3D state
        (:func:`~skfem_dielectric.models.edge_section.plate_fields`): the first guess, the
        clamp's ``u``, the cut's ``u`` and ``phi``, and ``F_33``.
    D0
        The charge per reference area in units of ``sqrt(mu eps)``.
    guess
        ``guess(X1, X2) -> dict`` with ``u``, ``phi``, ``p``: the first guess inside the
        section (default ``fields``).
    grad_div
        The plate's grad-div weight, in units of ``mu``: that of the 3D state where
        ``fields`` says it (its attribute ``grad_div``,
        :func:`~skfem_dielectric.models.edge_section.plate_fields`), since the section
        takes its boundary data and ``F33`` from that state, whose discrete equilibrium
        holds the grad-div term (with another weight Newton does not converge even under
        the dead load alone).
    pressure
        The pressure space, ``"Q1"`` (continuous, Taylor-Hood) or ``"P0"`` (one constant
        per element), :data:`PRESSURES`.

    Raises
    ------
    ValueError
        ``grad_div`` other than the 3D state's.
    """

    def __init__(self, g1, g2, material, fields: Callable, D0: float, *,
                 guess: Callable | None = None, grad_div: float = 0.0, pressure: str = "Q1"):
        state = getattr(fields, "grad_div", None)
        if state is not None and float(grad_div) != float(state):
            raise ValueError(f"grad_div must be the 3D state's grad-div weight {state:g} (the "
                             f"section takes its boundary data and F33 from that state), "
                             f"got {grad_div!r}")
        mesh = MeshQuad.init_tensor(np.asarray(g1, float), np.asarray(g2, float))
        b2 = Basis(mesh, ElementQuad2(), intorder=4)
        b1 = Basis(mesh, pressure_element(pressure), intorder=4)
        n2, n1 = b2.N, b1.N
        ndofs = 3 * n2 + n1
        Xq = b2.mapping.F(b2.X)
        ne, nq = Xq.shape[1:]
        npt = ne * nq
        q3d = fields(Xq[0].ravel(), Xq[1].ravel())
        lam3_q = q3d["F"][2, 2].copy()

        def lam3(X1, X2):
            return fields(X1, X2)["F"][2, 2]

        # first guess and the cut's values: the 3D state at the dof locations
        xd = b2.doflocs
        d3 = fields(xd[0], xd[1])
        g2d = d3 if guess is None else guess(xd[0], xd[1])
        x = np.concatenate([g2d["u"][0], g2d["u"][1], g2d["phi"],
                            (fields if guess is None else guess)(*b1.doflocs)["p"]])
        clamp = np.flatnonzero(np.isclose(xd[0], g1[-1]))
        cut = np.flatnonzero(np.isclose(xd[0], g1[0]))
        fixed = np.concatenate([clamp, n2 + clamp, cut, n2 + cut, 2 * n2 + cut])
        for f, v in enumerate((d3["u"][0], d3["u"][1], d3["phi"])):   # boundary data: 3D's
            x[f * n2 + cut] = v[cut]
            if f < 2:
                x[f * n2 + clamp] = v[clamp]
        free = np.setdiff1d(np.arange(ndofs), fixed)

        # the charge on the faces: sigma (int_top phi - int_bottom phi)
        sigma = float(D0) * math.sqrt(material.mu * material.eps)
        face = np.zeros(ndofs)
        for where, sign in ((lambda X: np.isclose(X[1], g2[-1]), 1.0),
                            (lambda X: np.isclose(X[1], g2[0]), -1.0)):
            fb = FacetBasis(mesh, ElementQuad2(), facets=mesh.facets_satisfying(where), intorder=4)
            face[2 * n2:3 * n2] += sign * sigma * LinearForm(lambda v, w: v).assemble(fb)

        dN = np.moveaxis(np.stack([np.asarray(f[0].grad) for f in b2.basis], axis=-1), 0, 2)
        M = np.stack([np.asarray(f[0]) for f in b1.basis], axis=-1)                 # (e,q,4|1)
        nb = 27 + M.shape[-1]                     # the element's unknowns: u1, u2, phi, p
        B = np.zeros((ne, nq, 7, nb))             # rows: _IN_PLANE; columns: u1, u2, phi, p
        for a in range(2):
            for K in range(2):
                B[:, :, 2 * a + K, 9 * a:9 * a + 9] = dN[:, :, K]
        for K in range(2):
            B[:, :, 4 + K, 18:27] = dN[:, :, K]
        B[:, :, 6, 27:nb] = M
        edofs = np.concatenate([b2.element_dofs + f * n2 for f in range(3)]
                               + [b1.element_dofs + 3 * n2]).T                    # (e, nb)
        rows = np.repeat(edofs, nb, axis=1).ravel()
        cols = np.tile(edofs, (1, nb)).ravel()
        w = np.asarray(b2.dx).reshape(npt)
        idx = np.array(_IN_PLANE)

        self.mesh, self.b2, self.b1, self.material = mesh, b2, b1, material
        self.n2, self.ndofs_full, self.npt, self.ne, self.nq = n2, ndofs, npt, ne, nq
        self.lam3, self.lam3_q, self.x0, self.free = lam3, lam3_q, x, free
        self.face, self.B, self.edofs, self.rows, self.cols = face, B, edofs, rows, cols
        self.w, self.idx, self.grad_div = w, idx, float(grad_div)
        area = (g1[-1] - g1[0]) * (g2[-1] - g2[0])
        #: the residual's norm at the first guess
        self.residual0 = float(np.linalg.norm(self.evaluate(x, tangent=False)[0][free]))
        #: the residual's scale: the first residual, the charge's load, mu times the section
        self.scale = max(self.residual0, float(np.linalg.norm(face)), material.mu * area)

    @property
    def layout(self) -> Layout:
        return Layout.single(self.free.size)

    def initial_state(self) -> np.ndarray:
        """The first guess (``guess``, else the 3D state) at the reduced unknowns."""
        return self.x0[self.free].copy()

    def full(self, y: np.ndarray) -> np.ndarray:
        """All unknowns of the reduced ``y`` (the boundary data of the 3D state)."""
        out = self.x0.copy()
        out[self.free] = y
        return out

    def deformation(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``F`` (``(npt, 3, 3)``) and the seven in-plane gradients at the quadrature
        points of all unknowns ``x``."""
        npt = self.npt
        q = np.einsum("eqij,ej->eqi", self.B, x[self.edofs]).reshape(npt, 7)
        F = np.zeros((npt, 3, 3))
        F[:, 0, 0], F[:, 0, 1], F[:, 1, 0], F[:, 1, 1] = 1 + q[:, 0], q[:, 1], q[:, 2], 1 + q[:, 3]
        F[:, 2, 2] = self.lam3_q
        return F, q

    def evaluate(self, x: np.ndarray, tangent: bool = True):
        """Residual and (with ``tangent``) tangent of all unknowns ``x``."""
        npt, ne, nq, mat = self.npt, self.ne, self.nq, self.material
        F, q = self.deformation(x)
        G = np.vstack([q[:, 4], q[:, 5], np.zeros(npt)])
        r = ideal_dielectric_response(mat, np.moveaxis(F, 0, 2), G, q[:, 6],
                                      grad_div=self.grad_div * mat.mu)
        s = np.zeros((npt, 13))
        s[:, :9] = r.P.reshape(9, npt).T
        s[:, 9:12] = r.D_L.T
        s[:, 12] = r.dpsi_dp
        s = (s[:, self.idx] * self.w[:, None]).reshape(ne, nq, 7)
        R = np.bincount(self.edofs.ravel(), np.einsum("eqia,eqi->ea", self.B, s).ravel(),
                        minlength=self.ndofs_full) + self.face
        if not tangent:
            return R, None
        idx = self.idx
        T = (pointwise_tangent(r, npt)[:, idx][:, :, idx]
             * self.w[:, None, None]).reshape(ne, nq, 7, 7)
        Ke = np.einsum("eqia,eqij,eqjb->eab", self.B, T, self.B, optimize=True)
        K = sp.coo_matrix((Ke.ravel(), (self.rows, self.cols)),
                          shape=(self.ndofs_full, self.ndofs_full)).tocsr()
        return R, K

    def assemble(self, x: np.ndarray, load=None) -> tuple[sp.csr_matrix, np.ndarray]:
        R, K = self.evaluate(self.full(x))
        return K[self.free][:, self.free], R[self.free]

    def residual(self, x: np.ndarray, load=None) -> np.ndarray:
        return self.evaluate(self.full(x), tangent=False)[0][self.free]

    def residual_scale(self, load=None) -> float:
        return self.scale

    def jacobian(self, x: np.ndarray) -> np.ndarray:
        """``J = det F`` at the quadrature points of the reduced state ``x``."""
        return np.linalg.det(self.deformation(self.full(x))[0])

    def max_step(self, x: np.ndarray, dx: np.ndarray, load=None) -> float:
        """The largest fraction of the step ``dx`` from ``x`` with ``J > 0`` at every
        quadrature point along it (:func:`~skfem_dielectric.kinematics.segment_det_limit`)."""
        d = np.zeros(self.ndofs_full)
        d[self.free] = dx
        dF = self.deformation(d)[0]
        dF[:, 0, 0] -= 1.0                        # the increment of F: no identity, F33 fixed
        dF[:, 1, 1] -= 1.0
        dF[:, 2, 2] = 0.0
        return segment_det_limit(self.deformation(self.full(x))[0], dF)

    def admissible(self, x: np.ndarray, load=None) -> str:
        """Why the reduced state ``x`` is inverted (``J <= 0`` at a quadrature point), or
        ``""``."""
        J = self.jacobian(x)
        return "" if J.min() > 0 else (f"inverted section state: J = {J.min():.4g} at a "
                                       f"quadrature point (must be > 0)")

    def newton_guards(self) -> dict:
        """``step_limit``: :meth:`max_step`; ``admissible``: :meth:`admissible`."""
        return {"step_limit": self.max_step, "admissible": self.admissible}

    def base(self, x: np.ndarray, iterations: int, residual: float) -> SectionBase:
        """The :class:`SectionBase` of the reduced state ``x``."""
        return SectionBase(self.b2, self.b1, self.lam3, self.full(x), iterations, residual)



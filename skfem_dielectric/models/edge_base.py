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
in ``(u1, u2, phi, p)``, reached by Newton's method with backtracking from the 3D solution
(:func:`solve_section_base`) or, where that is too far from the section's equilibrium at
the edge, by continuation along the 3D ramp's states (:func:`continue_section_base`).  The
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
import scipy.sparse.linalg as spla
from skfem import Basis, ElementQuad1, ElementQuad2, FacetBasis, LinearForm, MeshQuad

from ..materials import ideal_dielectric_response

__all__ = ["SectionBase", "solve_section_base", "continue_section_base", "pointwise_tangent"]

#: in-plane entries of ``F`` (row-major ``3 i + J``), of ``Grad phi``, and ``p`` in the
#: 13 unknowns ``(F, Grad phi, p)`` of the pointwise tangent
_IN_PLANE = (0, 1, 3, 4, 9, 10, 12)


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
    """A solved base state of a section (:func:`solve_section_base`).

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


def solve_section_base(g1, g2, material, fields: Callable, D0: float, *,
                       guess: Callable | None = None, grad_div: float = 0.0,
                       tol: float = 1e-10, max_iter: int = 40) -> SectionBase:
    """Solve the section's base state (module docstring) from the 3D state ``fields``.

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
        section (default ``fields``); the solution on a coarser section
        (:meth:`SectionBase.fields`) is a better one where the edge is fine, since the 3D
        state is far from the section's equilibrium at the edge, where the 3D mesh cannot
        follow the singular field.
    grad_div
        The plate's grad-div weight, in units of ``mu``.
    tol, max_iter
        Newton stops when the residual norm is below ``tol`` times its scale (the largest
        of the first residual, the charge's load vector and ``mu`` times the section's
        area), or at the round-off floor below ``100 tol``; at most ``max_iter`` steps.

    Returns
    -------
    SectionBase

    Raises
    ------
    ValueError
        Newton does not converge within ``max_iter`` steps.
    """
    mesh = MeshQuad.init_tensor(np.asarray(g1, float), np.asarray(g2, float))
    b2 = Basis(mesh, ElementQuad2(), intorder=4)
    b1 = Basis(mesh, ElementQuad1(), intorder=4)
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
    M = np.stack([np.asarray(f[0]) for f in b1.basis], axis=-1)                   # (e,q,4)
    B = np.zeros((ne, nq, 7, 31))             # rows: _IN_PLANE; columns: u1, u2, phi, p
    for a in range(2):
        for K in range(2):
            B[:, :, 2 * a + K, 9 * a:9 * a + 9] = dN[:, :, K]
    for K in range(2):
        B[:, :, 4 + K, 18:27] = dN[:, :, K]
    B[:, :, 6, 27:31] = M
    edofs = np.concatenate([b2.element_dofs + f * n2 for f in range(3)]
                           + [b1.element_dofs + 3 * n2]).T                    # (e, 31)
    rows = np.repeat(edofs, 31, axis=1).ravel()
    cols = np.tile(edofs, (1, 31)).ravel()
    w = np.asarray(b2.dx).reshape(npt)
    idx = np.array(_IN_PLANE)

    def evaluate(x):
        e = x[edofs]                                                           # (e, 31)
        q = np.einsum("eqij,ej->eqi", B, e).reshape(npt, 7)
        F = np.zeros((3, 3, npt))
        F[0, 0], F[0, 1], F[1, 0], F[1, 1] = 1 + q[:, 0], q[:, 1], q[:, 2], 1 + q[:, 3]
        F[2, 2] = lam3_q
        G = np.vstack([q[:, 4], q[:, 5], np.zeros(npt)])
        r = ideal_dielectric_response(material, F, G, q[:, 6],
                                      grad_div=grad_div * material.mu)
        s = np.zeros((npt, 13))
        s[:, :9] = r.P.reshape(9, npt).T
        s[:, 9:12] = r.D_L.T
        s[:, 12] = r.dpsi_dp
        s = (s[:, idx] * w[:, None]).reshape(ne, nq, 7)
        R = np.bincount(edofs.ravel(), np.einsum("eqia,eqi->ea", B, s).ravel(),
                        minlength=ndofs) + face
        T = (pointwise_tangent(r, npt)[:, idx][:, :, idx] * w[:, None, None]).reshape(ne, nq, 7, 7)
        Ke = np.einsum("eqia,eqij,eqjb->eab", B, T, B, optimize=True)
        K = sp.coo_matrix((Ke.ravel(), (rows, cols)), shape=(ndofs, ndofs)).tocsr()
        return R, K

    R, K = evaluate(x)
    # the residual's scale: the first residual, the charge's load, mu times the section
    area = (g1[-1] - g1[0]) * (g2[-1] - g2[0])
    r0 = max(float(np.linalg.norm(R[free])), float(np.linalg.norm(face)), material.mu * area)
    rel = float(np.linalg.norm(R[free])) / r0
    if rel < tol:
        return SectionBase(b2, b1, lam3, x, 0, rel)
    for it in range(1, max_iter + 1):
        dx = spla.spsolve(K[free][:, free].tocsc(), -R[free])
        step = 1.0                          # backtracking on the residual norm
        for _ in range(12):
            trial = x.copy()
            trial[free] += step * dx
            Rt, Kt = evaluate(trial)
            rt = float(np.linalg.norm(Rt[free])) / r0
            if math.isfinite(rt) and rt < rel * (1 - 1e-4 * step):
                break
            step *= 0.5
        else:                               # no decrease along the Newton direction:
            if rel < 1e2 * tol:             # the round-off floor
                return SectionBase(b2, b1, lam3, x, it, rel)
            break
        x, R, K, rel = trial, Rt, Kt, rt
        if rel < tol:
            return SectionBase(b2, b1, lam3, x, it, rel)
    raise ValueError(f"the section's base state did not converge in max_iter = {max_iter} "
                     f"Newton steps (relative residual {rel:.2e})")


def _blend(fa: Callable, fb: Callable, t: float) -> Callable:
    """The fields ``(1 - t) fa + t fb`` (``u``, ``phi``, ``p``, ``F``)."""
    def fields(X1, X2):
        a, b = fa(X1, X2), fb(X1, X2)
        return {name: (1.0 - t) * a[name] + t * b[name] for name in ("u", "phi", "p", "F")}
    return fields


def _shifted(sb: SectionBase, old: Callable, new: Callable) -> Callable:
    """The guess ``sb + (new - old)``: the section's solution moved by the change of the
    3D state, so that the boundary data move with it."""
    def guess(X1, X2):
        f, a, b = sb.fields(X1, X2), old(X1, X2), new(X1, X2)
        return {"u": f["u"] + (b["u"][:2] - a["u"][:2]),
                "phi": f["phi"] + (b["phi"] - a["phi"]),
                "p": f["p"] + (b["p"] - a["p"])}
    return guess


def continue_section_base(g1, g2, material, path, *, grad_div: float = 0.0,
                          tol: float = 1e-10, max_iter: int = 40, max_halvings: int = 6,
                          progress: Callable | None = None) -> SectionBase:
    """Solve the section's base state along a path of 3D states, by continuation in the
    charge.

    The first state is solved from its own 3D fields (:func:`solve_section_base`); each
    next one from the last solution moved by the change of the 3D state, ``guess = x + (f_new
    - f_old)`` (so the clamp's and the cut's data move with it).  Between two states of the
    path the 3D fields and ``D0`` are interpolated linearly, and a step that does not
    converge is halved, at most ``max_halvings`` times.

    Parameters
    ----------
    g1, g2, material, grad_div, tol, max_iter
        As for :func:`solve_section_base`.
    path
        ``[(D0, fields), ...]`` in the order to follow (e.g. the 3D ramp's converged
        states, :func:`~skfem_dielectric.models.edge_section.plate_fields` of each); the
        result is the last one's base state.
    max_halvings
        The smallest step is ``2 ** -max_halvings`` of an interval of the path.
    progress
        Optional ``progress(text)`` after each state of the path.

    Returns
    -------
    SectionBase
        The base state at the path's last state; its ``iterations`` are the Newton steps
        of the whole path.

    Raises
    ------
    ValueError
        An empty path, or a step of the smallest size that does not converge (the message
        names the charge).
    """
    path = list(path)
    if not path:
        raise ValueError("path must hold at least one (D0, fields) state, got none")
    D0, f0 = path[0]
    sb = solve_section_base(g1, g2, material, f0, D0, grad_div=grad_div, tol=tol,
                            max_iter=max_iter)
    total = sb.iterations
    for (Da, fa), (Db, fb) in zip(path[:-1], path[1:]):
        t, dt = 0.0, 1.0
        while t < 1.0:
            t1 = min(1.0, t + dt)
            old, new = _blend(fa, fb, t), _blend(fa, fb, t1)
            try:
                sb = solve_section_base(g1, g2, material, new, (1 - t1) * Da + t1 * Db,
                                        guess=_shifted(sb, old, new), grad_div=grad_div,
                                        tol=tol, max_iter=max_iter)
            except ValueError:
                if dt <= 2.0 ** -max_halvings:
                    raise ValueError(f"the section's base state did not converge at D0 = "
                                     f"{(1 - t1) * Da + t1 * Db:.6g} with the smallest step "
                                     f"(max_halvings = {max_halvings})") from None
                dt /= 2
                continue
            total += sb.iterations
            t = t1
        if progress is not None:
            progress(f"D0 = {Db:g}: {total} Newton steps so far")
    sb.iterations = total
    return sb

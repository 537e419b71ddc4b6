"""Stability of the (X1, X2) section next to a clamp against waves along X3.

The clamped plate's short-wave modes at the clamp edge vary along the width X3 on a scale
that the 3D meshes resolve with a few elements at most.  This model takes the state of the
plate on its centre plane ``X3 = 0`` (a *base state*: ``F``, ``Grad phi``, ``p`` at each
point of the section) as given and asks whether perturbations of the form::

    du  = (a1(X1, X2) cos kX3,  a2(X1, X2) cos kX3,  a3(X1, X2) sin kX3)
    dp  = b(X1, X2) cos kX3,    dphi = c(X1, X2) cos kX3

lower the energy, for each wavenumber ``k`` (reference length per radian) on its own.  The
energy is the plate's: the incompressible ``u``-``p``-``phi`` density of
:mod:`skfem_dielectric.materials` (Eq. (modelE) times ``J``) with its grad-div term, whose
second variation at each point is the 13 x 13 matrix of second derivatives with respect to
``(F, Grad phi, p)`` (:func:`~skfem_dielectric.materials.ideal_dielectric_response`).
Averaged over a period in ``X3`` the products ``cos sin`` vanish and the second variation
splits into a *cosine group* (``dF_aK`` for ``a, K`` in-plane, ``dF_33 = k a3``,
``dG_1, dG_2``, ``dp``) and a *sine group* (``dF_3K = a3,K``, ``dF_a3 = -k a_a``,
``dG_3 = -k c``), with no coupling between them where the base state is even in ``X3``
(``F_13 = F_31 = F_23 = F_32 = G_3 = 0``, as on the plate's symmetry plane).  The charges
and dead loads are linear in the unknowns (charge control): they add nothing.

Discretisation: ``a1, a2, a3, c`` continuous Q2, ``b`` continuous Q1 (Taylor-Hood) or one
constant per element (Q2-P0, ``pressure="P0"``) on a
quadrilateral mesh of the section, graded geometrically towards the clamp face and towards
both faces of the plate so that the elements at the clamp edge are squares of side ``h0``
(:func:`edge_section_grids`).  The negative eigenvalues of the energy are counted by
Sylvester's law of inertia: the discrete operator is a saddle point with one negative
eigenvalue per pressure and per potential unknown, which are subtracted
(:meth:`EdgeSection.count`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementQuad2, MeshQuad

from ..checks import check_positive
from ..linalg.inertia import counted_inertia
from ..materials import ideal_dielectric_response
from .edge_base import PRESSURES, pointwise_tangent, pressure_element
from .plate import evaluate_fields

__all__ = ["EdgeSection", "edge_section_grids", "graded_spacing", "homogeneous_base",
           "plate_fields", "plate_base", "FIXED", "PRESSURES"]

#: a base state: ``base(X1, X2) -> (F (3, 3, n), G (3, n), p (n))`` at ``n`` points
FIXED = ("ends", "normal", "none")

BaseState = Callable[[np.ndarray, np.ndarray], tuple]



def graded_spacing(length: float, h0: float, growth: float, hmax: float) -> np.ndarray:
    """Increasing node offsets from 0 to ``length`` whose first interval is ``h0`` and
    each next one ``growth`` times the previous, at most ``hmax`` (a short last interval
    folded into the one before, so that the offsets end at ``length``).

    Raises
    ------
    ValueError
        A non-positive length or size, ``growth < 1``, or ``h0 > hmax``.
    """
    check_positive("length", length)
    check_positive("h0", h0)
    check_positive("hmax", hmax)
    if not (math.isfinite(growth) and growth >= 1.0):
        raise ValueError(f"growth must be >= 1, got {growth!r}")
    if h0 > hmax:
        raise ValueError(f"h0 must be <= hmax, got h0 = {h0:g}, hmax = {hmax:g}")
    t, h = [0.0], h0
    while t[-1] + h < length - 1e-12:
        t.append(t[-1] + h)
        h = min(h * growth, hmax)
    rest = length - t[-1]
    if rest < 0.5 * h and len(t) > 1:       # fold a short last interval into the one before
        t.pop()
    t.append(length)
    return np.array(t)


def edge_section_grids(x1_clamp: float = 50.0, length: float = 5.0, thickness: float = 1.0,
                       h0: float = 0.02, growth: float = 1.3,
                       hmax: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The nodes ``(g1, g2)`` of a section ``[x1_clamp - length, x1_clamp] x
    [-thickness/2, thickness/2]``, graded towards ``X1 = x1_clamp`` and towards both faces
    ``X2 = +-thickness/2`` with squares of side ``h0`` at the clamp edges.

    ``hmax`` (default ``thickness / 8``) caps the elements across the thickness; along
    ``X1`` they grow up to ``thickness / 2``.
    """
    check_positive("thickness", thickness)
    hmax = thickness / 8 if hmax is None else hmax
    g1 = x1_clamp - graded_spacing(length, h0, growth, max(thickness / 2, h0))[::-1]
    half = graded_spacing(thickness / 2, h0, growth, hmax)
    g2 = np.concatenate([-thickness / 2 + half[:-1], thickness / 2 - half[::-1]])
    return g1, np.unique(np.round(g2, 14))


def homogeneous_base(material, lam1: float, lam3: float, D0: float, *,
                     grad_div: float = 0.0) -> BaseState:
    """The homogeneous base state of stretches ``lam1``, ``lam3`` (``lam2 = 1/(lam1 lam3)``)
    carrying the charge ``D0`` per reference area with traction-free faces ``X2 = +-H/2``.

    ``G_2`` is set so that ``D_L2 = -D0 sqrt(mu eps)`` and ``p`` so that ``P_22 = 0``, both
    from the material's own response (``D_L`` is linear in ``G``, ``P`` in ``p``).
    """
    F = np.diag([lam1, 1.0 / (lam1 * lam3), lam3])[:, :, None]
    target = -D0 * math.sqrt(material.mu * material.eps)

    def resp(G2, p):
        return ideal_dielectric_response(material, F, np.array([[0.0], [G2], [0.0]]),
                                         np.array([p]), need_tangent=False,
                                         grad_div=grad_div)

    d1 = resp(1.0, 0.0).D_L[1, 0]
    G2 = target / d1
    P0, P1 = resp(G2, 0.0).P[1, 1, 0], resp(G2, 1.0).P[1, 1, 0]
    p = -P0 / (P1 - P0)
    G = np.array([0.0, G2, 0.0])

    def base(X1, X2):
        n = np.size(X1)
        return (np.repeat(F, n, axis=2), np.repeat(G[:, None], n, axis=1), np.full(n, p))

    return base


def plate_fields(problem, xf: np.ndarray, X3: float = 0.0) -> Callable:
    """The 3D plate's state (eighth model) on the plane ``X3`` as a function of the
    section's points: ``fields(X1, X2)`` returns the dict of
    :func:`~skfem_dielectric.models.plate.evaluate_fields` (``u``, ``phi``, ``p``, ``F``,
    ``G``) of the full dof vector ``xf`` (``problem.full(x, load)``), extended to
    ``X2 < 0`` by the plate's mirror symmetry about its mid-plane (``u2`` and ``phi`` odd
    in ``X2``: ``u(-X2) = M u``, ``F(-X2) = M F M``, ``Grad phi(-X2) = -M Grad phi``,
    ``p`` even, ``M = diag(1, -1, 1)``).  The function's attribute ``grad_div`` is the
    plate's grad-div weight (units of ``mu``), which the section's base state must take
    (:class:`~skfem_dielectric.models.edge_base.SectionBaseProblem`).

    Raises
    ------
    ValueError
        ``xf`` not of the problem's full length.
    """
    xf = np.asarray(xf, dtype=float)
    if xf.shape != (problem.n_full,):
        raise ValueError(f"xf must be a full dof vector of length {problem.n_full}, got "
                         f"shape {xf.shape}")
    M = np.array([1.0, -1.0, 1.0])

    def fields(X1, X2):
        X1, X2 = np.asarray(X1, dtype=float).ravel(), np.asarray(X2, dtype=float).ravel()
        pts = np.vstack([X1, np.abs(X2), np.full(X1.shape, float(X3))])
        for i, g in enumerate(problem.plate.grids):   # points on a face: a hair inside
            d = 1e-9 * (g[-1] - g[0])
            pts[i] = np.clip(pts[i], g[0] + d, g[-1] - d)
        f = evaluate_fields(problem, xf, pts)
        lower = X2 < 0
        f["u"][:, lower] *= M[:, None]
        f["phi"][lower] *= -1.0
        f["F"][:, :, lower] *= (M[:, None] * M[None, :])[:, :, None]
        f["G"][:, lower] *= -M[:, None]
        return f

    fields.grad_div = float(problem.grad_div)      # the weight its equilibrium holds
    return fields


def plate_base(problem, xf: np.ndarray, X3: float = 0.0) -> BaseState:
    """The base state ``(F, Grad phi, p)`` of :func:`plate_fields`: the 3D solution
    itself, which resolves the clamp edge no better than the 3D mesh does (the section's
    own base state: :func:`~skfem_dielectric.studies.section_base.solve_section_base`).

    Raises
    ------
    ValueError
        ``xf`` not of the problem's full length.
    """
    fields = plate_fields(problem, xf, X3)

    def base(X1, X2):
        f = fields(X1, X2)
        return f["F"], f["G"], f["p"]

    return base


@dataclass
class _Cache:
    T: np.ndarray            # (e, q, 13, 13) second derivatives times the weights
    N2: np.ndarray           # (e, q, 9) Q2 values
    dN2: np.ndarray          # (e, q, 2, 9) Q2 gradients
    N1: np.ndarray           # (e, q, 4) Q1 values


class EdgeSection:
    """The section's energy against waves ``cos kX3`` / ``sin kX3`` (module docstring).

    Parameters
    ----------
    g1, g2
        Nodes along ``X1`` and ``X2`` (:func:`edge_section_grids`).
    material
        The plate's material (``mu``, ``eps``).
    base
        The base state, ``base(X1, X2) -> (F, G, p)`` at arrays of points.
    grad_div
        The grad-div weight of the plate's energy (units of ``mu``).
    fixed
        ``"ends"``: ``a = 0`` on both ends ``X1 = g1[0]`` and ``X1 = g1[-1]`` (the clamp and
        the cut, which is far enough from the clamp for the edge's modes); ``"normal"``:
        only ``a1 = 0`` there (mirror planes: a strip of an unbounded plate, whose modes are
        ``cos(n pi X1 / length)``, ``n = 0`` being the plate's own); ``"none"``: no
        displacement fixed.
    pressure
        The pressure space (:data:`PRESSURES`): ``"Q1"`` (Taylor-Hood) or ``"P0"``.

    Raises
    ------
    ValueError
        Bad grids, a negative ``grad_div``, an unknown ``fixed`` or ``pressure``.
    """

    def __init__(self, g1, g2, material, base: BaseState, *, grad_div: float = 0.0,
                 fixed: str = "ends", pressure: str = "Q1") -> None:
        g1, g2 = np.asarray(g1, dtype=float), np.asarray(g2, dtype=float)
        for name, g in (("g1", g1), ("g2", g2)):
            if g.ndim != 1 or g.size < 2 or not np.all(np.diff(g) > 0):
                raise ValueError(f"{name} must be increasing nodes (at least 2)")
        if fixed not in FIXED:
            raise ValueError(f"fixed must be one of {', '.join(FIXED)}, got {fixed!r}")
        if not (math.isfinite(grad_div) and grad_div >= 0):
            raise ValueError(f"grad_div must be a finite number >= 0, got {grad_div!r}")
        self.mesh = MeshQuad.init_tensor(g1, g2)
        self.b2 = Basis(self.mesh, ElementQuad2(), intorder=4)
        self.b1 = Basis(self.mesh, pressure_element(pressure), intorder=4)
        self.pressure = pressure
        self.material, self.grad_div = material, float(grad_div)
        n2, n1 = self.b2.N, self.b1.N
        #: unknowns: a1, a2, a3, c (Q2 each), then b (the pressure space)
        self.n2, self.n1 = n2, n1
        self.ndofs = 4 * n2 + n1
        edofs2, edofs1 = self.b2.element_dofs, self.b1.element_dofs        # (9, e), (4|1, e)
        self.edofs = np.concatenate([edofs2 + f * n2 for f in range(4)]
                                    + [edofs1 + 4 * n2]).T                  # (e, 36 + 4|1)
        self.nb = self.edofs.shape[1]
        free = np.ones(self.ndofs, dtype=bool)
        if fixed != "none":
            x = self.b2.doflocs[0]
            ends = np.flatnonzero(np.isclose(x, g1[0]) | np.isclose(x, g1[-1]))
            for f in range(3 if fixed == "ends" else 1):
                free[ends + f * n2] = False
        self.free = free
        #: the unknowns that are multipliers of the saddle point: c and b
        self.n_multipliers = int(free[3 * n2:].sum())
        self._cache = self._points(base)

    # ------------------------------------------------------------------ base state
    def _points(self, base: BaseState) -> _Cache:
        b2, b1 = self.b2, self.b1
        X = b2.mapping.F(b2.X)                                    # (2, e, q)
        ne, nq = X.shape[1], X.shape[2]
        F, G, p = base(X[0].ravel(), X[1].ravel())
        r = ideal_dielectric_response(self.material, F, G, p,
                                      grad_div=self.grad_div * self.material.mu)
        npt = ne * nq
        T = pointwise_tangent(r, npt)
        T *= b2.dx.reshape(npt)[:, None, None]
        N2 = np.stack([np.asarray(f[0]) for f in b2.basis], axis=-1)          # (e,q,9)
        dN2 = np.stack([np.asarray(f[0].grad) for f in b2.basis], axis=-1)          # (2,e,q,9)
        N1 = np.stack([np.asarray(f[0]) for f in b1.basis], axis=-1)          # (e,q,4|1)
        self.base_F, self.base_J = F, r.J
        return _Cache(T.reshape(ne, nq, 13, 13), N2, np.moveaxis(dN2, 0, 2), N1)

    # ------------------------------------------------------------------ operator
    def matrix(self, k: float) -> sp.csr_matrix:
        """The second variation of the energy for the wavenumber ``k`` (free unknowns
        only), a symmetric sparse matrix.

        Raises
        ------
        ValueError
            ``k`` not positive and finite.
        """
        k = check_positive("k", k)
        c = self._cache
        ne, nq = c.N2.shape[:2]
        N, dN, M = c.N2, c.dN2, c.N1
        nb = self.nb
        Bc = np.zeros((ne, nq, 13, nb))
        Bs = np.zeros((ne, nq, 13, nb))
        s2 = [slice(9 * f, 9 * f + 9) for f in range(4)]           # a1, a2, a3, c
        # cosine group: dF_aK = a_a,K (a, K in-plane), dF_33 = k a3, dG_K = c,K, dp = b
        for a in range(2):
            for K in range(2):
                Bc[:, :, 3 * a + K, s2[a]] = dN[:, :, K]
        Bc[:, :, 8, s2[2]] = k * N
        for K in range(2):
            Bc[:, :, 9 + K, s2[3]] = dN[:, :, K]
        Bc[:, :, 12, 36:nb] = M
        # sine group: dF_3K = a3,K, dF_a3 = -k a_a, dG_3 = -k c
        for K in range(2):
            Bs[:, :, 6 + K, s2[2]] = dN[:, :, K]
        for a in range(2):
            Bs[:, :, 3 * a + 2, s2[a]] = -k * N
        Bs[:, :, 11, s2[3]] = -k * N
        Ke = (np.einsum("eqia,eqij,eqjb->eab", Bc, c.T, Bc, optimize=True)
              + np.einsum("eqia,eqij,eqjb->eab", Bs, c.T, Bs, optimize=True))
        Ke = 0.5 * (Ke + np.swapaxes(Ke, 1, 2))
        # the diagonal is stored (zero for the pressure unknowns): a symmetric
        # factorisation reads the upper triangle, which must have every row
        diag = np.arange(self.ndofs)
        rows = np.concatenate([np.repeat(self.edofs, nb, axis=1).ravel(), diag])
        cols = np.concatenate([np.tile(self.edofs, (1, nb)).ravel(), diag])
        data = np.concatenate([Ke.ravel(), np.zeros(self.ndofs)])
        K = sp.coo_matrix((data, (rows, cols)), shape=(self.ndofs,) * 2).tocsr()
        return K[self.free][:, self.free]

    def count(self, k: float, method: str = "auto") -> int:
        """The negative eigenvalues of the energy at wavenumber ``k``: Sylvester's count of
        :meth:`matrix` less one per multiplier (pressure and potential unknown)."""
        neg = counted_inertia(self.matrix(k), method)[1]
        return int(neg - self.n_multipliers)

"""2D membrane model of a thin incompressible dielectric plate (in-plane x1-x3).

The quarter of a rectangular plate, described by its mid-surface: plane stress through
the thickness, exact incompressibility (``lam2 = 1/det F``), the displacement as the only
unknown.  Weak form and kernels: :mod:`skfem_dielectric.forms.membrane`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import skfem as fe
from skfem.io.meshio import to_meshio

from ..checks import (check_choice, check_count, check_instance, check_material,
                      check_positive)
from ..fem.assembly import DofReduction, ScatterMap
from ..fem.mesh2d import BatchedVectorForm, point_gradients, quarter_quad_mesh
from ..forms.membrane import edge_maxwell_traction, membrane_kernel
from ..kinematics import det2, inv_t2
from ..problem import Layout, Problem

__all__ = ["MembranePlate", "MembraneMesh", "membrane_mesh", "CONTROLS", "COUPLINGS",
           "check_control_coupling"]

#: the loadings of :class:`~skfem_dielectric.models.plate.problem.PlateProblem`: the same
#: names for the same set-up
LOADINGS = ("equibiaxial", "uniaxial", "uniaxial-free", "none")
CONTROLS = ("charge", "voltage")
COUPLINGS = ("full", "maxwell")


def check_control_coupling(control: str, coupling: str) -> None:
    """Shared by the 2D models: known ``control``/``coupling``; Maxwell coupling needs charge."""
    check_choice("control", control, CONTROLS)
    check_choice("coupling", coupling, COUPLINGS)
    if coupling == "maxwell" and control != "charge":
        raise ValueError(f"coupling 'maxwell' needs control='charge', got {control!r}")


@dataclass(frozen=True)
class MembraneMesh:
    """The quarter mid-surface of a plate and its geometry.

    Attributes
    ----------
    mesh
        scikit-fem ``MeshQuad`` of ``[0, L1/2] x [0, L3/2]`` (coordinates ``(X1, X3)``) with
        the boundaries ``sym_x1`` (``X1 = 0``), ``sym_x3`` (``X3 = 0``), ``x1_plus``
        (``X1 = L1/2``, the loaded edge or clamp) and ``x3_plus`` (``X3 = L3/2``).
    L1, H, L3
        Full plate dimensions (length, thickness, width).
    n1, n3
        Elements along x1 and x3 on the quarter.
    """

    mesh: fe.MeshQuad
    L1: float
    H: float
    L3: float
    n1: int
    n3: int


def membrane_mesh(L1: float, H: float, L3: float, n1: int, n3: int) -> MembraneMesh:
    """Structured quadrilateral mesh of the quarter mid-surface of a plate
    ``L1 x H x L3``, the geometry of :class:`MembranePlate`.

    Parameters
    ----------
    L1, H, L3
        Full length (x1), thickness (x2) and width (x3) of the plate (> 0), in the order of
        :func:`~skfem_dielectric.fem.mesh.plate_mesh`.
    n1, n3
        Number of elements along x1 and x3 on the quarter (the in-plane counts of
        :func:`~skfem_dielectric.fem.mesh.plate_mesh`; a membrane has no elements through
        the thickness).

    Returns
    -------
    MembraneMesh

    Raises
    ------
    ValueError
        For non-positive sizes or counts, naming the parameter.

    Examples
    --------
    >>> m = membrane_mesh(100.0, 1.0, 50.0, 4, 2)
    >>> m.mesh.nelements, m.mesh.p[:, -1].tolist()
    (8, [50.0, 25.0])
    """
    L1, H, L3 = check_positive("L1", L1), check_positive("H", H), check_positive("L3", L3)
    n1, n3 = check_count("n1", n1), check_count("n3", n3)
    mesh = quarter_quad_mesh(L1 / 2, L3 / 2, n1, n3, ("sym_x1", "sym_x3", "x1_plus", "x3_plus"))
    return MembraneMesh(mesh=mesh, L1=L1, H=H, L3=L3, n1=n1, n3=n3)


class MembranePlate(Problem):
    """Quarter of a rectangular dielectric membrane, a :class:`~skfem_dielectric.problem.Problem`.

    The mid-surface ``[0, L1/2] x [0, L3/2]`` (x1 along the load, x3 across;
    ``X1 = 0`` and ``X3 = 0`` are the symmetry lines through the plate centre)
    is meshed with ``n1 x n3`` biquadratic quadrilaterals (Q2, 3x3 Gauss points by default).
    The load is the pair ``(s, D0)``: ``s`` the dimensionless nominal stress
    (force per reference cross-section ``H x width`` over ``mu``) and ``D0 =
    D_L/sqrt(mu eps)`` (charge control) or ``E0 = E_L sqrt(eps/mu)`` (voltage
    control).

    Constructed as every model of :mod:`skfem_dielectric.models` (docs/fe.md, "Constructing
    a model"): the mesh first, then the material, then keyword-only options, e.g.
    ``MembranePlate(membrane_mesh(100, 1, 50, 40, 20), NeoHookeanDielectric(),
    loading="uniaxial")``.

    Parameters
    ----------
    mesh : MembraneMesh
        The plate's geometry and mesh, from :func:`membrane_mesh` (sizes ``L1, H, L3``,
        element counts ``n1, n3``); kept as :attr:`plate`.
    material : NeoHookeanDielectric, GentDielectric or IdealDielectric
        Ideal-dielectric material (``mu``, ``eps``, ``W(I1)``).
    loading : {"equibiaxial", "uniaxial", "uniaxial-free", "none"}
        As for :class:`~skfem_dielectric.models.plate.problem.PlateProblem`:
        ``"equibiaxial"`` (default): dead traction ``s`` on the edges ``X1 = L1/2`` and
        ``X3 = L3/2``; ``"uniaxial"``: the Keplinger experiment, the edge ``X1 = L1/2`` is
        glued to a rigid clamp (``u3 = 0`` and one shared ``u1``) carrying the weight, i.e.
        the resultant force ``s mu H L3`` (full plate), the edge ``X3 = L3/2`` free;
        ``"uniaxial-free"``: dead traction ``s`` on ``X1 = L1/2``, free edge ``X3 = L3/2``;
        ``"none"``: no mechanical load.
    control : {"charge", "voltage"}
        Which electric quantity the load's second component prescribes.
    coupling : {"full", "maxwell"}
        ``"full"``: the charge-controlled energy of :func:`membrane_kernel`;
        ``"maxwell"`` (charge control only): the purely elastic membrane loaded
        by the Maxwell traction of :mod:`skfem_dielectric.forms.maxwell_traction` on its faces
        and edges, with the local field of the charge (see Notes).
    intorder : int
        Quadrature order (4: 3 x 3 Gauss points).

    Raises
    ------
    ValueError
        Naming the parameter and the value: a ``mesh`` that is no ``MembraneMesh``, a
        ``material`` that is no dielectric, unknown options, ``coupling="maxwell"`` under
        voltage control.

    Notes
    -----
    Energy per reference area: see :func:`membrane_kernel`.

    Maxwell coupling: with the field ``D = F D_L/J``, ``D_L = -sigma_F e2``,
    the faces carry the compressive traction ``sigma_F^2 lam2/(2 eps)`` per
    reference area, whose virtual work ``-sigma_F^2 H lam2 dlam2/(2 eps)`` is
    that of the energy ``H lam2^2 sigma_F^2/(4 eps)`` (half the fully coupled
    electric energy); the edges (``X1 = L1/2``, ``X3 = L3/2``; the clamp edge
    included, its x1-resultant is carried by the clamp) carry the follower
    traction ``H sigma_F^2 lam2^2/(2 eps) F^-T N`` per reference length, with
    its linearisation in the (then non-symmetric) tangent. On homogeneous
    states both couplings coincide; they differ where ``lam2`` varies.

    For the clamped plate (``loading="uniaxial"``), by symmetry about ``X1 = 0`` the upper (fixed) and lower (moving)
    clamps of the experiment have the same relative motion as the two clamps
    ``X1 = +-L1/2`` of this model.
    """

    def __init__(self, mesh: MembraneMesh, material, *, loading: str = "equibiaxial",
                 control: str = "charge", coupling: str = "full", intorder: int = 4):
        self.plate = check_instance("mesh", mesh, MembraneMesh, "membrane_mesh")
        self.material = check_material("material", material)
        check_choice("loading", loading, LOADINGS)
        check_control_coupling(control, coupling)
        intorder = check_count("intorder", intorder)
        self.coupling = coupling
        self.symmetric = coupling == "full"
        self.load_names = ("s", "D0") if control == "charge" else ("s", "E0")
        self.L1, self.L3, self.H = mesh.L1, mesh.L3, mesh.H
        self.n1, self.n3 = mesh.n1, mesh.n3
        self.loading, self.control = loading, control
        a1, a3 = self.L1 / 2, self.L3 / 2
        self.mesh = mesh = mesh.mesh
        elem = fe.ElementVector(fe.ElementQuad2())
        self.basis = fe.Basis(mesh, elem, intorder=intorder)
        self.form = BatchedVectorForm(self.basis)
        n = self.basis.N
        dofs = {k: self.basis.get_dofs(k) for k in ("sym_x1", "sym_x3", "x1_plus", "x3_plus")}
        fixed = [dofs["sym_x1"].nodal["u^1"], dofs["sym_x1"].facet["u^1"],
                 dofs["sym_x3"].nodal["u^2"], dofs["sym_x3"].facet["u^2"]]
        tied = np.empty(0, dtype=int)
        if loading == "uniaxial":
            fixed += [dofs["x1_plus"].nodal["u^2"], dofs["x1_plus"].facet["u^2"]]
            tied = np.unique(np.concatenate([dofs["x1_plus"].nodal["u^1"],
                                             dofs["x1_plus"].facet["u^1"]]))
        fixed = np.unique(np.concatenate(fixed))
        # shared machinery: dof reduction (fixed + tied clamp dofs) and scatter map
        self.red = DofReduction(n, fixed, [tied] if tied.size else None)
        self.scatter = ScatterMap(self.red.index[self.basis.element_dofs.T], self.red.n)
        self.tied_index = int(self.red.index[tied[0]]) if tied.size else None
        # external load for s = 1 (force per reference length mu H on the loaded edges)
        mu = material.mu
        f = np.zeros(n)
        if loading == "uniaxial":
            fred = np.zeros(self.red.n)
            fred[self.tied_index] = mu * self.H * a3  # resultant on the quarter: mu s H L3/2
        else:
            edges = (("x1_plus", 0), ("x3_plus", 1))
            for name, comp in edges[: {"equibiaxial": 2, "uniaxial-free": 1}.get(loading, 0)]:
                fb = fe.FacetBasis(mesh, elem, facets=mesh.boundaries[name],
                                   intorder=intorder)
                e = np.zeros(2)
                e[comp] = mu * self.H

                @fe.LinearForm
                def trac(v, w, e=e):
                    return e[0] * v[0] + e[1] * v[1]

                f += trac.assemble(fb)
            fred = self.red.reduce(f)
        self.f_unit = fred
        if coupling == "maxwell":
            facets = np.concatenate([mesh.boundaries["x1_plus"], mesh.boundaries["x3_plus"]])
            fbm = fe.FacetBasis(mesh, elem, facets=facets, intorder=intorder)
            nb = fbm.Nbfun
            self._mx = dict(
                V=np.array([np.asarray(fbm.basis[a][0]) for a in range(nb)]),
                G=np.array([fbm.basis[a][0].grad for a in range(nb)]),
                N=fbm.normals, dx=fbm.dx, dofs=fbm.element_dofs,
                scatter=ScatterMap(self.red.index[fbm.element_dofs.T], self.red.n))
        # probes: centre line X3 = 0 and the line next to the clamp X1 = 0.95 L1/2
        self.x_line = np.linspace(0.0, a1, 4 * self.n1 + 1)
        self.x_clamp = np.linspace(0.0, a3, 4 * self.n3 + 1)
        pts_c = np.vstack([self.x_line, np.zeros_like(self.x_line)])
        pts_k = np.vstack([np.full_like(self.x_clamp, 0.95 * a1), self.x_clamp])
        self._probe_line = point_gradients(self.basis, pts_c)
        self._probe_clamp = point_gradients(self.basis, pts_k)

    # -- Problem contract ----------------------------------------------------
    @property
    def layout(self) -> Layout:
        """One block ``u`` (the clamp unknown included), no multipliers."""
        return Layout.single(self.red.n)

    @property
    def T(self):
        """Sparse prolongation ``u_full = T x`` (all prescribed values are zero)."""
        idx = self.red.index
        rows = np.flatnonzero(idx >= 0)
        return sp.csr_matrix((np.ones(rows.size), (rows, idx[rows])),
                             shape=(idx.size, self.red.n))

    def initial_state(self) -> np.ndarray:
        """Zero displacement."""
        return np.zeros(self.ndofs)

    def full(self, x: np.ndarray, load=None) -> np.ndarray:
        """Full displacement vector (scikit-fem dof order) from reduced unknowns."""
        return self.red.expand(np.asarray(x, dtype=float))

    def _electric(self, load):
        s, e0 = np.asarray(load, dtype=float).reshape(2)
        mu, eps = self.material.mu, self.material.eps
        if self.control == "charge":
            return s, dict(D_L=e0 * np.sqrt(mu * eps))
        return s, dict(E_L=e0 * np.sqrt(mu / eps))

    def _edge_maxwell(self, u, sigma, need_tangent=True):
        """Follower traction ``c J^-2 F^-T N`` on the edges, ``c = H sigma^2/(2 eps)``;
        reduced ``(K, r)`` contributions (``K`` is ``None`` without the tangent)."""
        m = self._mx
        F = np.einsum("ae,aijeq->ijeq", u[m["dofs"]], m["G"], optimize=True)
        F = F + np.eye(2)[:, :, None, None]
        c = self.H * sigma**2 / (2.0 * self.material.eps) * m["dx"]
        t, dt = edge_maxwell_traction(F, m["N"], c, need_tangent)
        re = -np.einsum("ieq,aieq->ea", t, m["V"], optimize=True)
        r = m["scatter"].vector(re)
        if not need_tangent:
            return None, r
        Ke = -np.einsum("aieq,ikleq,bkleq->eab", m["V"], dt, m["G"], optimize=True)
        return m["scatter"].matrix(Ke), r

    def _kernel_options(self, load):
        s, el = self._electric(load)
        if self.coupling == "maxwell":
            # the faces' Maxwell pressure = half the fully coupled electric energy
            return s, dict(D_L=el["D_L"] / np.sqrt(2.0)), el["D_L"]
        return s, el, None

    def assemble(self, x: np.ndarray, load) -> tuple:
        """Reduced tangent and residual ``P^T (f_int(u) - s f_ext)``."""
        s, el, sigma = self._kernel_options(load)
        u = self.full(x)
        F = self.form.grad(u) + np.eye(2)[:, :, None, None]
        _, P, A = membrane_kernel(F, self.material, H=self.H, **el)
        K = self.scatter.matrix(self.form.element_matrices(A))
        r = self.scatter.vector(self.form.element_vectors(P))
        if sigma is not None:
            Km, rm = self._edge_maxwell(u, sigma)
            K, r = K + Km, r + rm
        return K, r - s * self.f_unit

    def residual(self, x: np.ndarray, load) -> np.ndarray:
        """Reduced residual only (line search)."""
        s, el, sigma = self._kernel_options(load)
        u = self.full(x)
        F = self.form.grad(u) + np.eye(2)[:, :, None, None]
        _, P, _ = membrane_kernel(F, self.material, H=self.H, **el)
        r = self.scatter.vector(self.form.element_vectors(P))
        if sigma is not None:
            r = r + self._edge_maxwell(u, sigma, need_tangent=False)[1]
        return r - s * self.f_unit

    def residual_scale(self, load) -> float:
        """Scale of the residual: ``mu H L1`` (a force)."""
        return self.material.mu * self.H * self.L1

    def _probe(self, u, probe, el):
        G, dofs = probe
        F = np.einsum("pn,pijn->ijn", u[dofs], G) + np.eye(2)[:, :, None]
        _, P, _ = membrane_kernel(F, self.material, H=self.H, **el)
        J = det2(F)
        Finv = np.swapaxes(inv_t2(F, J), 0, 1)
        S = np.einsum("iK...,Kj...->ij...", Finv, P / self.H)  # 2nd Piola = F^-1 P
        return F, S

    def centre_line(self, x: np.ndarray, load) -> dict:
        """Profiles along the centre line ``X3 = 0`` (centre to clamp).

        Returns
        -------
        dict
            ``x1`` (reference ``X1``), ``lam1 = F11``, ``lam3 = F33``, ``lam2``
            and ``P33`` (second Piola ``S33/mu``, total stress) at the points.
        """
        _, el = self._electric(load)
        F, S = self._probe(self.full(x), self._probe_line, el)
        return {"x1": self.x_line.copy(), "lam1": F[0, 0], "lam3": F[1, 1],
                "lam2": 1.0 / det2(F), "P33": S[1, 1] / self.material.mu}

    def step_mesh(self, x: np.ndarray, load):
        """meshio ``Mesh`` of a state (used by :mod:`skfem_dielectric.export`).

        Points are ``(X1, X3, 0)``; point data ``displacement`` ``(u1, u3, 0)``;
        cell data (element averages) ``P33``, ``P11`` (second Piola over ``mu``),
        ``lam1``, ``lam2``, ``lam3``.
        """
        _, el = self._electric(load)
        u = self.full(x)
        nv = self.mesh.p.shape[1]
        uv = u.reshape(-1, 2)[:nv]  # vector dofs interleaved, vertices first
        disp = np.column_stack([uv, np.zeros(nv)])
        F = self.form.grad(u) + np.eye(2)[:, :, None, None]
        _, P, _ = membrane_kernel(F, self.material, H=self.H, **el)
        J = det2(F)
        Finv = np.swapaxes(inv_t2(F, J), 0, 1)
        S = np.einsum("iK...,Kj...->ij...", Finv, P / self.H) / self.material.mu
        cell = {"P33": S[1, 1], "P11": S[0, 0], "lam1": F[0, 0], "lam2": 1.0 / J,
                "lam3": F[1, 1]}
        cell = {k: [v.mean(axis=-1)] for k, v in cell.items()}
        return to_meshio(self.mesh, point_data={"displacement": disp}, cell_data=cell,
                         encode_cell_data=False)

    def postprocess(self, x: np.ndarray, load) -> dict:
        """Stretches at the plate centre and ``P33`` along the lines.

        Returns ``lam1``, ``lam3``, ``lam2`` at the centre, ``lam1_mean``
        (clamp-to-clamp, ``loading="uniaxial"`` only, else ``nan``), ``min_P33`` (the
        minimum of the second Piola ``P33/mu`` along the centre line ``X3 = 0``)
        and ``x_min_P33`` (its ``X1``), and ``min_P33_clamp``/``x3_min_P33_clamp``
        along ``X1 = 0.95 L1/2`` next to the clamp.
        """
        _, el = self._electric(load)
        u = self.full(x)
        mu = self.material.mu
        F, S = self._probe(u, self._probe_line, el)
        Fk, Sk = self._probe(u, self._probe_clamp, el)
        P33 = S[1, 1] / mu
        P33k = Sk[1, 1] / mu
        i, k = int(np.argmin(P33)), int(np.argmin(P33k))
        out = {
            "lam1": float(F[0, 0, 0]),
            "lam3": float(F[1, 1, 0]),
            "lam2": float(1.0 / det2(F)[0]),
            "lam1_mean": (float(1.0 + x[self.tied_index] / (self.L1 / 2))
                          if self.tied_index is not None else float("nan")),
            "min_P33": float(P33[i]),
            "x_min_P33": float(self.x_line[i]),
            "min_P33_clamp": float(P33k[k]),
            "x3_min_P33_clamp": float(self.x_clamp[k]),
        }
        return out

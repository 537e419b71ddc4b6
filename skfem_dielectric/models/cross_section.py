"""2D cross-section (x1-x2) of the plate in generalised plane strain, fully coupled.

The plate's cross-section ``[-L1/2, L1/2] x [-H/2, H/2]`` (x1 length, x2
thickness = field direction) deforms in its plane while every fibre along x3
is stretched by the same uniform ``lam3``:

    F = [[F11, F12, 0], [F21, F22, 0], [0, 0, lam3]],   Grad phi = (phi_1, phi_2, 0).

``lam3`` is either prescribed or one extra global unknown set by the nominal
stress ``s3`` on the x3-faces (its equation is ``int T33 dA = s3 mu A``, the
resultant over the reference cross-section ``A``). The unknowns are the
displacement ``u`` (Q2), the pressure multiplier ``p`` (Q1, Taylor-Hood), the
potential ``phi`` (Q2) and ``lam3``: the mixed, exactly incompressible, fully
coupled formulation of the 3D solver (weak form:
:mod:`skfem_dielectric.forms.plane_strain`), which is the geometry of the paper's Stroh
wrinkling analysis (Sec. 3).

The model is the quarter ``[0, L1/2] x [0, H/2]``: ``u1 = 0`` on ``x1 = 0``,
``u2 = 0`` and ``phi = 0`` on ``x2 = 0`` (the potential is odd in x2, so this
fixes its constant without adding charge); the top face ``x2 = H/2`` carries
the surface charge ``sigma_F = D0 sqrt(mu eps)`` per reference area (charge
control, ``N.D_L = -sigma_F``, so ``D_L2 = -sigma_F``) or the potential
``phi = E0 sqrt(mu/eps) H/2`` (voltage control, ``E_L2 = -E0 sqrt(mu/eps)``,
the same orientation as the charged plate; as in the 3D solver); the end ``x1 = L1/2`` carries
the dead nominal traction ``s mu e1``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import skfem as fe
from skfem.io.meshio import to_meshio

from ..checks import (check_choice, check_count, check_instance, check_material,
                      check_nonnegative, check_positive)
from ..fem.assembly import DofReduction, ScatterMap
from ..fem.mesh2d import point_gradients, quarter_quad_mesh
from ..forms.maxwell_traction import maxwell_nominal_stress, maxwell_stress
from ..forms.plane_strain import PlaneStrainForm, cross_section_kernel
from ..kinematics import det3, plane_strain_F, second_piola
from ..problem import Layout, Problem
from .membrane import check_control_coupling

__all__ = ["CrossSection", "SectionMesh", "section_mesh"]

FIELDS = ("electrostatic", "local")
THICKNESSES = ("half", "full")
PHI_ELEMENTS = ("Q1", "Q2")


def _component_dofs(basis, boundary: str, comp: str) -> np.ndarray:
    """Dofs of one component (``"u^1"``, ``"u^2"``) of a vector basis on a boundary."""
    d = basis.get_dofs(boundary)
    return np.concatenate([d.nodal[comp], d.facet[comp]])


@dataclass(frozen=True)
class SectionMesh:
    """The modelled part of a plate's cross-section and its geometry.

    Attributes
    ----------
    mesh
        scikit-fem ``MeshQuad`` of ``[0, L1/2] x [0, H/2]`` (``thickness="half"``) or
        ``[0, L1/2] x [-H/2, H/2]`` (``"full"``), coordinates ``(X1, X2)``, with the
        boundaries ``sym_x1``, ``x1_plus``, ``top`` and ``sym_x2`` (half) or ``bottom``
        (full).
    L1, H
        Full length and thickness of the plate.
    n1, n2
        Elements along the half-length and the modelled thickness.
    thickness
        ``"half"`` or ``"full"``.
    """

    mesh: fe.MeshQuad
    L1: float
    H: float
    n1: int
    n2: int
    thickness: str


def section_mesh(L1: float, H: float, n1: int, n2: int,
                 thickness: str = "half") -> SectionMesh:
    """Structured quadrilateral mesh of a plate's cross-section, the geometry of
    :class:`CrossSection`.

    Parameters
    ----------
    L1, H
        Full length (x1) and thickness (x2) of the plate (> 0), in the order of
        :func:`~skfem_dielectric.fem.mesh.plate_mesh` (a plane-strain section has no
        width).
    n1, n2
        Number of elements along the half-length and the modelled thickness (the half
        thickness, or the whole one for ``thickness="full"``).
    thickness
        ``"half"`` (default): ``[0, H/2]``, the mid-plane ``x2 = 0`` a symmetry plane
        (``symmetry="half"`` of :func:`~skfem_dielectric.fem.mesh.plate_mesh`), which
        admits only modes symmetric about it (extensional).  ``"full"``: ``[-H/2, H/2]``,
        flexural (antisymmetric) modes too.

    Returns
    -------
    SectionMesh

    Raises
    ------
    ValueError
        For non-positive sizes or counts or an unknown ``thickness``, naming the parameter.

    Examples
    --------
    >>> m = section_mesh(20.0, 1.0, 8, 2, thickness="full")
    >>> m.mesh.nelements, sorted(m.mesh.boundaries)
    (16, ['bottom', 'sym_x1', 'top', 'x1_plus'])
    """
    L1, H = check_positive("L1", L1), check_positive("H", H)
    n1, n2 = check_count("n1", n1), check_count("n2", n2)
    check_choice("thickness", thickness, THICKNESSES)
    a1, a2 = L1 / 2, H / 2
    full = thickness == "full"
    mesh = quarter_quad_mesh(a1, a2, n1, n2,
                             ("sym_x1", "bottom" if full else "sym_x2", "x1_plus", "top"),
                             b2=-a2 if full else 0.0)
    return SectionMesh(mesh=mesh, L1=L1, H=H, n1=n1, n2=n2, thickness=thickness)


class CrossSection(Problem):
    """Cross-section in generalised plane strain, a :class:`~skfem_dielectric.problem.Problem`.

    Constructed as every model of :mod:`skfem_dielectric.models` (docs/fe.md, "Constructing
    a model"): the mesh first, then the material, then keyword-only options, e.g.
    ``CrossSection(section_mesh(20, 1, 8, 2), NeoHookeanDielectric(), lam3=1.2)``.

    Parameters
    ----------
    mesh : SectionMesh
        The plate's geometry and mesh, from :func:`section_mesh` (sizes ``L1, H``, element
        counts ``n1, n2``, ``thickness`` ``"half"`` or ``"full"``); kept as :attr:`plate`.
        ``"full"``: the bottom face carries the opposite charge (or potential), ``phi`` is
        pinned at the mid-plane centre under charge control and ``u2`` at ``X1 = L1/4`` (a
        node of the lowest modes of either class) against the rigid translation.
    material
        Ideal dielectric (``mu``, ``eps``, ``W(I1)``).
    control : {"charge", "voltage"}
        Meaning of the load's last component (``D0`` or ``E0``).
    coupling : {"full", "maxwell"}
        ``"full"``: the fully coupled energy in the volume. ``"maxwell"`` (charge
        control): elastic stress in the volume, the Maxwell traction
        ``-tau_m cof(F) N`` on the top face, the end ``x1 = L1/2`` and (in the
        ``lam3`` equation) the x3 faces, linearised in the non-symmetric
        tangent (:mod:`skfem_dielectric.forms.maxwell_traction`).
    field : {"electrostatic", "local"}
        Field in ``tau_m`` for the Maxwell coupling: from the potential solved
        on the deformed section (default), or the local thin-plate field
        ``D = F D_L/J`` without electrostatics (exact on homogeneous states
        only; see :class:`skfem_dielectric.models.plate.problem.PlateProblem`).
    phi_element : {"Q2", "Q1"}
        Interpolation of the potential (default ``"Q2"``, as for the plate).
    intorder : int
        Quadrature order (4: 3 x 3 Gauss points).
    grad_div : float
        Grad-div stabilisation ``gamma (J - 1)^2 / 2`` in units of ``mu``: removes the
        spurious mesh-scale surface modes from the stability analysis, leaves every
        homogeneous state unchanged (docs/stability.md).  Default 0.
    lam1 : float, optional
        Prescribed stretch along x1: the end ``x1 = L1/2`` slides on a rigid wall at
        ``u1 = (lam1 - 1) L1/2`` (no shear traction), so that the increments of a
        homogeneous state are Fourier modes ``sin, cos(pi X1/(L1/2))``; the load's ``s1``
        is then not used.
    lam3 : float, optional
        Prescribed out-of-plane stretch. If ``None`` (default), ``lam3`` is an
        unknown and the load's ``s3`` component prescribes the nominal stress.

    Raises
    ------
    ValueError
        Naming the parameter and the value: a ``mesh`` that is no ``SectionMesh``, a
        ``material`` that is no dielectric, unknown options, ``coupling="maxwell"`` under
        voltage control, non-positive ``lam1``/``lam3``, negative ``grad_div``.

    Notes
    -----
    The load is ``(s1, s3, D0)``: dimensionless nominal stresses along x1 and x3
    and the charge (or ``E0``). Equi-biaxial: ``s1 = s3 = s``; uni-axial:
    ``s3 = 0``. The homogeneous state is exact in the discrete space, so these
    reproduce Eqs. (loading_gent) and (DEuniax) to the Newton tolerance.
    """

    def __init__(self, mesh: SectionMesh, material, *, control: str = "charge",
                 coupling: str = "full", field: str = "electrostatic",
                 phi_element: str = "Q2", intorder: int = 4, grad_div: float = 0.0,
                 lam1: float | None = None, lam3: float | None = None):
        self.plate = check_instance("mesh", mesh, SectionMesh, "section_mesh")
        self.material = check_material("material", material)
        check_control_coupling(control, coupling)
        check_choice("field", field, FIELDS)
        check_choice("phi_element", phi_element, PHI_ELEMENTS)
        intorder = check_count("intorder", intorder)
        self.grad_div = check_nonnegative("grad_div", grad_div) * material.mu
        self.lam1_fixed = None if lam1 is None else check_positive("lam1", lam1)
        self.lam3_fixed = None if lam3 is None else check_positive("lam3", lam3)
        self.thickness = mesh.thickness
        self.coupling, self.field = coupling, field
        self.symmetric = coupling == "full"
        self.load_names = ("s1", "s3", "D0" if control == "charge" else "E0")
        self._local = coupling == "maxwell" and field == "local"
        self._elastic_volume = coupling == "maxwell" and field == "electrostatic"
        self.L1, self.H = mesh.L1, mesh.H
        self.n1, self.n2 = mesh.n1, mesh.n2
        self.control = control
        a1 = self.L1 / 2
        full = self.thickness == "full"
        self.mesh = mesh = mesh.mesh
        eu = fe.ElementVector(fe.ElementQuad2())
        ephi = fe.ElementQuad2() if phi_element == "Q2" else fe.ElementQuad1()
        self.bu = fe.Basis(mesh, eu, intorder=intorder)
        self.bp = fe.Basis(mesh, fe.ElementQuad1(), quadrature=self.bu.quadrature)
        self.bf = fe.Basis(mesh, ephi, quadrature=self.bu.quadrature)
        nu, npp, nf = self.bu.N, self.bp.N, self.bf.N
        self.offsets = (0, nu, nu + npp, nu + npp + nf)  # u, p, phi, lam3
        n_full = nu + npp + nf + 1
        self.n_full = n_full
        o_p, o_f, o_l = self.offsets[1:]
        # element dof table: u (18), p (4), phi (9), lam3 (1)
        nel = mesh.nelements
        edofs = np.vstack([self.bu.element_dofs, o_p + self.bp.element_dofs,
                           o_f + self.bf.element_dofs, np.full((1, nel), o_l)]).T
        self.nb = (self.bu.Nbfun, self.bp.Nbfun, self.bf.Nbfun)
        self._top_phi = o_f + self.bf.get_dofs("top").all()
        self._bottom_phi = o_f + self.bf.get_dofs("bottom").all() if full else np.zeros(0, int)
        self._end_u1 = _component_dofs(self.bu, "x1_plus", "u^1")
        fixed = _section_constraints(self, full, control)
        self.red = DofReduction(n_full, np.concatenate(fixed))
        self.scatter = ScatterMap(self.red.index[edofs], self.red.n)
        self._layout = Layout.from_reduction(
            self.red, {"u": slice(0, o_p), "p": slice(o_p, o_f), "phi": slice(o_f, o_l),
                       "lam3": slice(o_l, n_full)}, ("p", "phi"))
        fbm = fbf = None
        if coupling == "maxwell":
            # Maxwell traction on the charged face (top) and the lateral end (x1_plus)
            facets = np.concatenate([mesh.boundaries["top"], mesh.boundaries["x1_plus"]])
            fbm = fe.FacetBasis(mesh, eu, facets=facets, intorder=intorder)
            fbf = fe.FacetBasis(mesh, ephi, facets=facets, intorder=intorder)
            fdofs = np.vstack([fbm.element_dofs,
                               np.full((1, facets.size), o_l), o_f + fbf.element_dofs]).T
            self.scatter_m = ScatterMap(self.red.index[fdofs], self.red.n)
        self.form = PlaneStrainForm(self.bu, self.bp, self.bf, fbm, fbf)
        self.dx = self.bu.dx
        self.f_s1, self.f_s3, self.q_top = _section_loads(self, eu, ephi, intorder, full)
        self.x_line = np.linspace(0.0, a1, 4 * self.n1 + 1)
        self._probe_u, self._probe_phi, self._probe_p = _centre_line_probes(self)

    # -- Problem contract -------------------------------------------------------
    @property
    def layout(self) -> Layout:
        """Blocks ``u``, ``p``, ``phi`` and ``lam3`` (when unknown); ``p`` and ``phi``
        are the multiplier/potential blocks."""
        return self._layout

    def _prescribed(self, load) -> np.ndarray:
        s1, s3, e0 = load
        x = np.zeros(self.n_full)
        x[self.offsets[3]] = 1.0 if self.lam3_fixed is None else self.lam3_fixed
        if self.control == "voltage":
            E_L = e0 * math.sqrt(self.material.mu / self.material.eps)
            x[self._top_phi] = E_L * self.H / 2  # E_L2 = -phi_,2 = -E0 sqrt(mu/eps)
            x[self._bottom_phi] = -E_L * self.H / 2
        if self.lam1_fixed is not None:
            x[self._end_u1] = (self.lam1_fixed - 1.0) * self.L1 / 2
        return x

    def initial_state(self) -> np.ndarray:
        """Uncharged state: undeformed (``lam3 = 1`` when it is unknown), or with the
        prescribed ``lam1`` the homogeneous incompressible stretch ``u1 = (lam1 - 1) X1``,
        ``u2 = (1/(lam1 lam3) - 1) X2`` (a Newton start the prescribed end cannot fold)."""
        x = np.zeros(self.n_full)
        lam3 = 1.0 if self.lam3_fixed is None else self.lam3_fixed
        x[self.offsets[3]] = lam3
        if self.lam1_fixed is not None:
            X = self.bu.doflocs
            x[0:self.offsets[1]:2] = (self.lam1_fixed - 1.0) * X[0, 0::2]
            x[1:self.offsets[1]:2] = (1.0 / (self.lam1_fixed * lam3) - 1.0) * X[1, 1::2]
        return self.red.restrict(x)

    def split(self, x: np.ndarray, load=(0.0, 0.0, 0.0)):
        """Full fields ``(u, p, phi, lam3)`` from the reduced unknowns."""
        xf = self.red.expand(x, self._prescribed(self._load(load)))
        o = self.offsets
        return xf[: o[1]], xf[o[1]: o[2]], xf[o[2]: o[3]], float(xf[o[3]])

    def _load(self, load):
        load = np.asarray(load, dtype=float).reshape(-1)
        if load.size != 3:
            raise ValueError(f"load must be (s1, s3, D0), got {load}")
        return load

    def _fields(self, x, load):
        u, p, phi, lam3 = self.split(x, load)
        gu, pq, gf = self.form.fields(u, p, phi, (self.bu.element_dofs, self.bp.element_dofs,
                                                  self.bf.element_dofs))
        return gu, lam3, pq, gf

    def _rhs(self, load) -> np.ndarray:
        s1, s3, e0 = load
        r = s1 * self.f_s1
        if self.lam3_fixed is None:
            r = r + s3 * self.f_s3
        if self.control == "charge" and not self._local:
            sigma = e0 * math.sqrt(self.material.mu * self.material.eps)
            r = r - sigma * self.q_top  # weak form: int D_L.Grad w + int sigma_F w = 0
        return r

    def _sigma(self, load) -> float:
        return float(load[2]) * math.sqrt(self.material.mu * self.material.eps)

    def _volume(self, x, load, need_tangent=True):
        gu, lam3, pq, gf = self._fields(x, load)
        R = cross_section_kernel(self.material, gu, lam3, pq, gf, need_tangent=need_tangent,
                                 grad_div=self.grad_div)
        Rm = R
        if self._elastic_volume:  # the field acts through the boundary only
            Rm = cross_section_kernel(self.material, gu, lam3, pq, np.zeros_like(gf),
                                      need_tangent=need_tangent, grad_div=self.grad_div)
        return gu, lam3, gf, R, Rm

    def residual(self, x: np.ndarray, load) -> np.ndarray:
        """Reduced residual."""
        return self._system(x, load, need_tangent=False)[1]

    def _system(self, x, load, need_tangent):
        load = self._load(load)
        gu, lam3, gf, R, Rm = self._volume(x, load, need_tangent=need_tangent)
        form = self.form
        ve = form.vectors(R, Rm)
        Ke = form.matrices(R, Rm, self._elastic_volume) if need_tangent else None
        if self.coupling != "maxwell":
            K = self.scatter.matrix(Ke) if need_tangent else None
            return K, self.scatter.vector(ve) - self._rhs(load)
        u, _, phi, _ = self.split(x, load)
        re, Km, t3, dF3, dG3 = form.maxwell(u, phi, lam3, gu, gf, -self._sigma(load),
                                            self.material.eps, self._local, need_tangent)
        form.x3_face_terms(ve, Ke, t3, dF3, dG3)
        K = self.scatter.matrix(Ke) + self.scatter_m.matrix(Km) if need_tangent else None
        return K, self.scatter.vector(ve) + self.scatter_m.vector(re) - self._rhs(load)

    def assemble(self, x: np.ndarray, load):
        """Reduced tangent (symmetric saddle point for the full coupling) and residual."""
        return self._system(x, load, need_tangent=True)

    def residual_scale(self, load) -> float:
        """Scale of the residual: ``mu L1 H`` (a force per unit length in x3)."""
        return self.material.mu * self.L1 * self.H

    def step_mesh(self, x: np.ndarray, load):
        """meshio ``Mesh`` of a state (used by :mod:`skfem_dielectric.export`).

        Points ``(X1, X2, 0)``; point data ``displacement`` ``(u1, u2, 0)``,
        ``potential``, ``pressure``; cell data (element averages) ``P33``,
        ``P11`` (total second Piola over ``mu``, the physical stress: the grad-div
        term of a stabilised section is not part of it), ``lam1``, ``lam2``, ``lam3``.
        """
        load = self._load(load)
        u, p, phi, lam3 = self.split(x, load)
        nv = self.mesh.p.shape[1]
        disp = np.column_stack([u.reshape(-1, 2)[:nv], np.zeros(nv)])
        gu, lam3, pq, gf = self._fields(x, load)
        # the physical stress: without the grad-div term (a device of the weak form)
        P = cross_section_kernel(self.material, gu, lam3, pq, gf, need_tangent=False).P
        F = plane_strain_F(gu, lam3)
        if self._local:
            P = P + maxwell_nominal_stress(F, -self._sigma(load), self.material.eps)[1]
        S = second_piola(F, P) / self.material.mu
        cell = {"P33": S[2, 2], "P11": S[0, 0], "lam1": F[0, 0], "lam2": F[1, 1],
                "lam3": np.full_like(F[0, 0], lam3)}
        cell = {k: [v.mean(axis=-1)] for k, v in cell.items()}
        return to_meshio(self.mesh, point_data={"displacement": disp, "potential": phi[:nv],
                                                "pressure": p[:nv]},
                         cell_data=cell, encode_cell_data=False)

    def postprocess(self, x: np.ndarray, load) -> dict:
        """Stretches at the centre and ``P33`` along the centre line ``x2 = 0``.

        Returns ``lam1``, ``lam2`` at the centre (``x1 = x2 = 0``), ``lam3``,
        ``min_P33`` (min of the physical second Piola ``P33/mu`` along ``x2 = 0``: the
        grad-div term of a stabilised section is not part of it) and its
        ``x_min_P33``, and ``E0``/``D0`` at the centre (dimensionless ``-E_L2``
        and ``-D_L2``).
        """
        load = self._load(load)
        u, p, phi, lam3 = self.split(x, load)
        Gu, du = self._probe_u
        gu = np.einsum("pn,pijn->ijn", u[du], Gu)
        Gf, df = self._probe_phi
        gf = np.einsum("pn,pin->in", phi[df], Gf)
        Np, dp = self._probe_p
        pq = np.einsum("pn,pn->n", p[dp], Np)
        # the physical stress: without the grad-div term (a device of the weak form)
        R = cross_section_kernel(self.material, gu, lam3, pq, gf, need_tangent=False)
        mu, eps = self.material.mu, self.material.eps
        P33 = R.P[2, 2] / lam3 / mu  # second Piola S33 = P33 / lam3 (F block-diagonal)
        E0 = float(gf[1, 0] * math.sqrt(eps / mu))
        D0 = float(-R.D_L[1, 0] / math.sqrt(mu * eps))
        if self._local:
            # total stress = elastic + Maxwell stress of the assumed field D = F D_L / J
            F = plane_strain_F(gu, lam3)
            J = det3(F)
            tau_m = maxwell_stress(F, -self._sigma(load), eps)
            P33 = P33 + J * tau_m[2, 2] / lam3**2 / mu
            C22 = F[0, 1, 0] ** 2 + F[1, 1, 0] ** 2
            D0 = float(load[2])
            E0 = float(C22 * load[2] / J[0])  # -E_L2 = -(C D_L)_2/(J eps), dimensionless
        i = int(np.argmin(P33))
        return {
            "lam1": float(1.0 + gu[0, 0, 0]),
            "lam2": float(1.0 + gu[1, 1, 0]),
            "lam3": float(lam3),
            "min_P33": float(P33[i]),
            "x_min_P33": float(self.x_line[i]),
            "E0": E0,
            "D0": D0,
        }


def _section_constraints(pb, full: bool, control: str) -> list[np.ndarray]:
    """Fixed full dofs of a section: symmetry line, mid-plane or pins, electrodes, the
    sliding end, the potential of the local Maxwell field, a prescribed ``lam3``."""
    nu, o_f, o_l = pb.offsets[1], pb.offsets[2], pb.offsets[3]
    a1 = pb.L1 / 2
    fixed = [_component_dofs(pb.bu, "sym_x1", "u^1")]
    if full:
        ux = pb.bu.doflocs
        pin = np.flatnonzero(np.arange(nu) % 2 == 1)      # u2 dofs
        fixed.append(np.array([pin[np.argmin(np.hypot(ux[0, pin] - a1 / 2, ux[1, pin]))]]))
        if control == "charge":
            fx = pb.bf.doflocs
            fixed.append(np.array([o_f + int(np.argmin(np.hypot(fx[0], fx[1])))]))
    else:
        fixed += [_component_dofs(pb.bu, "sym_x2", "u^2"),
                  o_f + pb.bf.get_dofs("sym_x2").all()]
    if control == "voltage":
        fixed += [pb._top_phi, pb._bottom_phi]
    if pb.lam1_fixed is not None:
        fixed.append(pb._end_u1)
    if pb._local:  # purely elastic: no potential unknowns
        fixed.append(o_f + np.arange(o_l - o_f))
    if pb.lam3_fixed is not None:
        fixed.append(np.array([o_l]))
    return fixed


def _section_loads(pb, eu, ephi, intorder: int, full: bool):
    """Reduced unit loads: traction ``mu e1`` on ``x1_plus`` (per unit ``s1``), the ``s3``
    resultant, and ``int w dA`` on the top face minus the bottom (per unit charge)."""
    mesh, mu, n_full = pb.mesh, pb.material.mu, pb.n_full
    nu, o_f, o_l = pb.offsets[1], pb.offsets[2], pb.offsets[3]
    fb = fe.FacetBasis(mesh, eu, facets=mesh.boundaries["x1_plus"], intorder=intorder)
    ft = fe.FacetBasis(mesh, ephi, facets=mesh.boundaries["top"], intorder=intorder)
    f = np.zeros(n_full)
    f[:nu] = fe.LinearForm(lambda v, w: mu * v[0]).assemble(fb)
    f_s1 = pb.red.reduce(f)
    f = np.zeros(n_full)
    f[o_l] = mu * pb.L1 / 2 * pb.H / 2 * (2.0 if full else 1.0)  # s3 resultant
    f_s3 = pb.red.reduce(f)
    f = np.zeros(n_full)
    f[o_f:o_l] = fe.LinearForm(lambda v, w: v).assemble(ft)
    if full:   # the opposite charge on the bottom face
        fbot = fe.FacetBasis(mesh, ephi, facets=mesh.boundaries["bottom"], intorder=intorder)
        f[o_f:o_l] -= fe.LinearForm(lambda v, w: v).assemble(fbot)
    return f_s1, f_s3, pb.red.reduce(f)


def _centre_line_probes(pb):
    """Shape functions of ``u``, ``phi`` and ``p`` at the centre-line points."""
    pts = np.vstack([pb.x_line, np.zeros_like(pb.x_line)])
    cells = pb.mesh.element_finder(mapping=pb.bf.mapping)(*pts)
    ref = pb.bf.mapping.invF(pts[:, :, None], tind=cells)
    phi = (np.array([pb.bf.elem.gbasis(pb.bf.mapping, ref, a, tind=cells)[0].grad[..., 0]
                     for a in range(pb.nb[2])]), pb.bf.element_dofs[:, cells])
    p = (np.array([np.asarray(pb.bp.elem.gbasis(pb.bp.mapping, ref, a, tind=cells)[0])[..., 0]
                   for a in range(pb.nb[1])]), pb.bp.element_dofs[:, cells])
    return point_gradients(pb.bu, pts), phi, p

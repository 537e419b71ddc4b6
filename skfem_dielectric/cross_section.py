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
coupled formulation of the 3D solver (energy density and tangent from
:func:`skfem_dielectric.materials.ideal_dielectric_response`, embedded in 3D),
which is the geometry of the paper's Stroh wrinkling analysis (Sec. 3).

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

import numpy as np

from .materials import _check_int, _check_positive
from .membrane import _check_control_coupling, _D0_targets

__all__ = ["CrossSection", "cross_section_kernel", "cross_section_ramp"]

_FIELDS = ("electrostatic", "local")


def cross_section_kernel(material, gradu: np.ndarray, lam3, p: np.ndarray,
                         gradphi: np.ndarray, need_tangent: bool = True):
    """Energy derivatives of the generalised-plane-strain state at points.

    Parameters
    ----------
    material
        Ideal dielectric (:mod:`skfem_dielectric.materials`).
    gradu : ndarray, shape (2, 2, ...)
        In-plane displacement gradient.
    lam3 : float
        Uniform out-of-plane stretch.
    p : ndarray, shape (...)
        Pressure multiplier (the physical pressure is ``-p``).
    gradphi : ndarray, shape (2, ...)
        In-plane potential gradient (``E_L = -Grad phi``).
    need_tangent : bool
        Whether the second derivatives are needed.

    Returns
    -------
    PointResponse
        The 3D response of :func:`ideal_dielectric_response` at
        ``F = diag-block(I + gradu, lam3)``, ``G = (gradphi, 0)``; the in-plane
        blocks and the ``33`` entries are what the 2D model uses.
    """
    from .materials import ideal_dielectric_response

    shape = gradu.shape[2:]
    F = np.zeros((3, 3) + shape)
    F[:2, :2] = gradu
    F[0, 0] += 1.0
    F[1, 1] += 1.0
    F[2, 2] = lam3
    G = np.zeros((3,) + shape)
    G[:2] = gradphi
    return ideal_dielectric_response(material, F, G, p, need_tangent=need_tangent)


class CrossSection:
    """Quarter cross-section in generalised plane strain, a :class:`RampProblem`.

    Parameters
    ----------
    material
        Ideal dielectric (``mu``, ``eps``, ``W(I1)``).
    L1, H : float
        Reference length and thickness of the whole plate.
    n1, n2 : int
        Q2 elements along the half-length and the half-thickness.
    lam3 : float, optional
        Prescribed out-of-plane stretch. If ``None`` (default), ``lam3`` is an
        unknown and the load's ``s3`` component prescribes the nominal stress.
    control : {"charge", "voltage"}
        Meaning of the load's last component (``D0`` or ``E0``).
    coupling : {"full", "maxwell"}
        ``"full"``: the fully coupled energy in the volume. ``"maxwell"`` (charge
        control): elastic stress in the volume, the Maxwell traction
        ``-tau_m cof(F) N`` on the top face, the end ``x1 = L1/2`` and (in the
        ``lam3`` equation) the x3 faces, linearised in the non-symmetric
        tangent (:mod:`skfem_dielectric.maxwell`).
    field : {"electrostatic", "local"}
        Field in ``tau_m`` for the Maxwell coupling: from the potential solved
        on the deformed section (default), or the local thin-plate field
        ``D = F D_L/J`` without electrostatics (exact on homogeneous states
        only; see :class:`skfem_dielectric.maxwell.MaxwellPlate`).

    Notes
    -----
    The load is ``(s1, s3, D0)``: dimensionless nominal stresses along x1 and x3
    and the charge (or ``E0``). Equi-biaxial: ``s1 = s3 = s``; uni-axial:
    ``s3 = 0``. The homogeneous state is exact in the discrete space, so these
    reproduce Eqs. (loading_gent) and (DEuniax) to the Newton tolerance.
    """

    def __init__(self, material, L1: float = 20.0, H: float = 1.0, n1: int = 8,
                 n2: int = 2, lam3: float | None = None, control: str = "charge",
                 coupling: str = "full", field: str = "electrostatic"):
        import skfem as fe

        from .assembly import DofReduction, ScatterMap
        from .mesh2d import quarter_quad_mesh

        _check_control_coupling(control, coupling)
        if field not in _FIELDS:
            raise ValueError(f"field must be one of {_FIELDS}, got {field!r}")
        self.coupling, self.field = coupling, field
        self._local = coupling == "maxwell" and field == "local"
        self._elastic_volume = coupling == "maxwell" and field == "electrostatic"
        self.material = material
        self.L1, self.H = _check_positive("L1", L1), _check_positive("H", H)
        self.n1, self.n2 = _check_int("n1", n1), _check_int("n2", n2)
        self.lam3_fixed = None if lam3 is None else _check_positive("lam3", lam3)
        self.control = control
        a1, a2 = self.L1 / 2, self.H / 2
        mesh = quarter_quad_mesh(a1, a2, self.n1, self.n2, ("sym_x1", "sym_x2", "x1_plus", "top"))
        self.mesh = mesh
        eu = fe.ElementVector(fe.ElementQuad2())
        self.bu = fe.Basis(mesh, eu, intorder=4)
        self.bp = fe.Basis(mesh, fe.ElementQuad1(), quadrature=self.bu.quadrature)
        self.bf = fe.Basis(mesh, fe.ElementQuad2(), quadrature=self.bu.quadrature)
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
        du = {k: self.bu.get_dofs(k) for k in ("sym_x1", "sym_x2")}
        fixed = [du["sym_x1"].nodal["u^1"], du["sym_x1"].facet["u^1"],
                 du["sym_x2"].nodal["u^2"], du["sym_x2"].facet["u^2"],
                 o_f + self.bf.get_dofs("sym_x2").all()]
        self._top_phi = o_f + self.bf.get_dofs("top").all()
        if control == "voltage":
            fixed.append(self._top_phi)
        if self._local:  # purely elastic: no potential unknowns
            fixed.append(o_f + np.arange(nf))
        if self.lam3_fixed is not None:
            fixed.append(np.array([o_l]))
        self.red = DofReduction(n_full, np.concatenate(fixed))
        self.scatter = ScatterMap(self.red.index[edofs], self.red.n)
        if coupling == "maxwell":
            # Maxwell traction on the charged face (top) and the lateral end (x1_plus)
            facets = np.concatenate([mesh.boundaries["top"], mesh.boundaries["x1_plus"]])
            self.fbm = fe.FacetBasis(mesh, eu, facets=facets, intorder=4)
            self.Gm = np.array([self.fbm.basis[a][0].grad for a in range(self.nb[0])])
            self.Vm = np.array([np.asarray(self.fbm.basis[a][0]) for a in range(self.nb[0])])
            fbf = fe.FacetBasis(mesh, fe.ElementQuad2(), facets=facets, intorder=4)
            self.Gmf = np.array([fbf.basis[a][0].grad for a in range(self.nb[2])])
            self._fphi = fbf.element_dofs
            fdofs = np.vstack([self.fbm.element_dofs,
                               np.full((1, facets.size), o_l), o_f + fbf.element_dofs]).T
            self.scatter_m = ScatterMap(self.red.index[fdofs], self.red.n)
        # basis arrays at quadrature points
        self.Gu = np.array([self.bu.basis[a][0].grad for a in range(self.nb[0])])
        self.Np = np.array([np.asarray(self.bp.basis[a][0]) for a in range(self.nb[1])])
        self.Gf = np.array([self.bf.basis[a][0].grad for a in range(self.nb[2])])
        self.dx = self.bu.dx
        # unit loads: traction mu e1 on x1_plus, charge 1 on top
        mu = material.mu
        fb = fe.FacetBasis(mesh, eu, facets=mesh.boundaries["x1_plus"], intorder=4)
        ft = fe.FacetBasis(mesh, fe.ElementQuad2(), facets=mesh.boundaries["top"],
                           intorder=4)
        f = np.zeros(n_full)
        f[:nu] = fe.LinearForm(lambda v, w: mu * v[0]).assemble(fb)
        self.f_s1 = self.red.reduce(f)
        f = np.zeros(n_full)
        f[o_l] = mu * a1 * a2  # s3 resultant over the reference quarter section
        self.f_s3 = self.red.reduce(f)
        f = np.zeros(n_full)
        f[o_f:o_l] = fe.LinearForm(lambda v, w: v).assemble(ft)
        self.q_top = self.red.reduce(f)  # int w dA on the top face
        self.x_line = np.linspace(0.0, a1, 4 * self.n1 + 1)
        from .mesh2d import point_gradients

        pts = np.vstack([self.x_line, np.zeros_like(self.x_line)])
        self._probe_u = point_gradients(self.bu, pts)
        cells = mesh.element_finder(mapping=self.bf.mapping)(*pts)
        ref = self.bf.mapping.invF(pts[:, :, None], tind=cells)
        self._probe_phi = (np.array([self.bf.elem.gbasis(self.bf.mapping, ref, a, tind=cells)
                                     [0].grad[..., 0] for a in range(self.nb[2])]),
                           self.bf.element_dofs[:, cells])
        self._probe_p = (np.array([np.asarray(self.bp.elem.gbasis(self.bp.mapping, ref, a,
                                                                  tind=cells)[0])[..., 0]
                                   for a in range(self.nb[1])]),
                         self.bp.element_dofs[:, cells])

    # -- state ----------------------------------------------------------------
    @property
    def ndofs(self) -> int:
        """Number of reduced unknowns."""
        return self.red.n

    def _prescribed(self, load) -> np.ndarray:
        s1, s3, e0 = load
        x = np.zeros(self.n_full)
        x[self.offsets[3]] = 1.0 if self.lam3_fixed is None else self.lam3_fixed
        if self.control == "voltage":
            E_L = e0 * math.sqrt(self.material.mu / self.material.eps)
            x[self._top_phi] = E_L * self.H / 2  # E_L2 = -phi_,2 = -E0 sqrt(mu/eps)
        return x

    def initial_state(self) -> np.ndarray:
        """Undeformed, uncharged state (``lam3 = 1`` when it is unknown)."""
        x = np.zeros(self.n_full)
        x[self.offsets[3]] = 1.0 if self.lam3_fixed is None else self.lam3_fixed
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
        gu = np.einsum("ae,aijeq->ijeq", u[self.bu.element_dofs], self.Gu, optimize=True)
        pq = np.einsum("ae,aeq->eq", p[self.bp.element_dofs], self.Np, optimize=True)
        gf = np.einsum("ae,aieq->ieq", phi[self.bf.element_dofs], self.Gf, optimize=True)
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

    def _element_vectors(self, R, Rm=None) -> np.ndarray:
        """Element residuals; ``Rm`` (default ``R``) gives the stress of the u/lam3 rows."""
        Rm = R if Rm is None else Rm
        dx = self.dx
        ru = np.einsum("ijeq,aijeq->ea", Rm.P[:2, :2] * dx, self.Gu, optimize=True)
        rp = np.einsum("eq,aeq->ea", R.dpsi_dp * dx, self.Np, optimize=True)
        rf = np.einsum("ieq,aieq->ea", R.D_L[:2] * dx, self.Gf, optimize=True)
        rl = np.sum(Rm.P[2, 2] * dx, axis=1)[:, None]
        return np.concatenate([ru, rp, rf, rl], axis=1)

    def _sigma(self, load) -> float:
        return float(load[2]) * math.sqrt(self.material.mu * self.material.eps)

    def _maxwell(self, x, load, lam3, gu, gf, need_tangent=True):
        """Maxwell-traction terms: edges (top, x1_plus) and the x3 faces.

        Returns the edge element vectors/matrices over the facet dofs
        ``[u (18), lam3, phi (9)]`` and the x3-face traction ``t3`` with its
        derivatives (per reference area of the section)."""
        from .maxwell import maxwell_traction, maxwell_traction_field

        eps = self.material.eps
        D_L = -self._sigma(load)
        u, _, phi, _ = self.split(x, load)

        def F3(g):
            F = np.zeros((3, 3) + g.shape[2:])
            F[:2, :2] = g
            F[0, 0] += 1.0
            F[1, 1] += 1.0
            F[2, 2] = lam3
            return F

        def vec3(v):
            out = np.zeros((3,) + v.shape[1:])
            out[:2] = v
            return out

        gm = np.einsum("ae,aijeq->ijeq", u[self.fbm.element_dofs], self.Gm, optimize=True)
        N = vec3(np.asarray(self.fbm.normals))
        N3 = np.zeros((3,) + gu.shape[2:])
        N3[2] = 1.0
        if self._local:
            t0, dF = maxwell_traction(F3(gm), N, D_L, eps)
            t3, dF3 = maxwell_traction(F3(gu), N3, D_L, eps)
            dG = dG3 = None
        else:
            gmf = np.einsum("ae,aieq->ieq", phi[self._fphi], self.Gmf, optimize=True)
            t0, dF, dG = maxwell_traction_field(F3(gm), vec3(gmf), N, eps)
            t3, dF3, dG3 = maxwell_traction_field(F3(gu), vec3(gf), N3, eps)
        dx = self.fbm.dx
        nu, nf = self.nb[0], self.nb[2]
        m = nu + 1 + nf
        re = np.zeros((dx.shape[0], m))
        re[:, :nu] = -np.einsum("ieq,aieq->ea", t0[:2] * dx, self.Vm, optimize=True)
        Ke = None
        if need_tangent:
            Ke = np.zeros((dx.shape[0], m, m))
            Ke[:, :nu, :nu] = -np.einsum("aieq,ikleq,bkleq->eab", self.Vm, dF[:2, :2, :2] * dx,
                                         self.Gm, optimize=True)
            Ke[:, :nu, nu] = -np.einsum("aieq,ieq->ea", self.Vm, dF[:2, 2, 2] * dx,
                                        optimize=True)
            if dG is not None:
                Ke[:, :nu, nu + 1:] = -np.einsum("aieq,ileq,bleq->eab", self.Vm,
                                                 dG[:2, :2] * dx, self.Gmf, optimize=True)
        return re, Ke, t3, dF3, dG3

    def _volume(self, x, load, need_tangent=True):
        gu, lam3, pq, gf = self._fields(x, load)
        R = cross_section_kernel(self.material, gu, lam3, pq, gf, need_tangent=need_tangent)
        Rm = R
        if self._elastic_volume:  # the field acts through the boundary only
            Rm = cross_section_kernel(self.material, gu, lam3, pq, np.zeros_like(gf),
                                      need_tangent=need_tangent)
        return gu, lam3, gf, R, Rm

    def residual(self, x: np.ndarray, load) -> np.ndarray:
        """Reduced residual."""
        load = self._load(load)
        gu, lam3, gf, R, Rm = self._volume(x, load, need_tangent=False)
        ve = self._element_vectors(R, Rm)
        if self.coupling == "maxwell":
            re, _, t3, _, _ = self._maxwell(x, load, lam3, gu, gf, need_tangent=False)
            ve[:, -1] -= np.sum(t3[2] * self.dx, axis=1)
            return (self.scatter.vector(ve) + self.scatter_m.vector(re) - self._rhs(load))
        return self.scatter.vector(ve) - self._rhs(load)

    def assemble(self, x: np.ndarray, load):
        """Reduced symmetric (saddle-point) tangent and residual."""
        load = self._load(load)
        gu, lam3, gf, R, Rm = self._volume(x, load)
        dx = self.dx
        Gu, Np, Gf = self.Gu, self.Np, self.Gf
        nu, npp, nf = self.nb
        nel = dx.shape[0]
        m = nu + npp + nf + 1
        Ke = np.zeros((nel, m, m))
        iu, ip, jf, il = (slice(0, nu), slice(nu, nu + npp), slice(nu + npp, m - 1),
                          m - 1)
        AFF = Rm.A_FF * dx
        # u-u, u-lam3, lam3-lam3
        AG = np.einsum("ijkleq,bkleq->ijbeq", AFF[:2, :2, :2, :2], Gu, optimize=True)
        Ke[:, iu, iu] = np.einsum("aijeq,ijbeq->eab", Gu, AG, optimize=True)
        kul = np.einsum("ijeq,aijeq->ea", AFF[:2, :2, 2, 2], Gu, optimize=True)
        Ke[:, iu, il] = kul
        Ke[:, il, iu] = kul
        Ke[:, il, il] = np.sum(AFF[2, 2, 2, 2], axis=1)
        # u-phi, lam3-phi
        AFG = R.A_FG * dx
        kuf = np.einsum("aijeq,ijLeq,bLeq->eab", Gu, AFG[:2, :2, :2], Gf, optimize=True)
        if not self._elastic_volume:
            Ke[:, iu, jf] = kuf
        Ke[:, jf, iu] = np.swapaxes(kuf, 1, 2)
        klf = np.einsum("Leq,bLeq->eb", AFG[2, 2, :2], Gf, optimize=True)
        if not self._elastic_volume:
            Ke[:, il, jf] = klf
        Ke[:, jf, il] = klf
        # u-p, lam3-p
        AFp = R.A_Fp * dx
        kup = np.einsum("aijeq,ijeq,beq->eab", Gu, AFp[:2, :2], Np, optimize=True)
        Ke[:, iu, ip] = kup
        Ke[:, ip, iu] = np.swapaxes(kup, 1, 2)
        klp = np.einsum("eq,beq->eb", AFp[2, 2], Np, optimize=True)
        Ke[:, il, ip] = klp
        Ke[:, ip, il] = klp
        # phi-phi, p-p
        Ke[:, jf, jf] = np.einsum("aKeq,KLeq,bLeq->eab", Gf, R.A_GG[:2, :2] * dx, Gf,
                                  optimize=True)
        if R.A_pp != 0.0:
            Ke[:, ip, ip] = R.A_pp * np.einsum("aeq,beq,eq->eab", Np, Np, dx, optimize=True)
        ve = self._element_vectors(R, Rm)
        if self.coupling == "maxwell":
            re, Km, t3, dF3, dG3 = self._maxwell(x, load, lam3, gu, gf)
            ve[:, -1] -= np.sum(t3[2] * dx, axis=1)
            dT3 = dF3 * dx
            Ke[:, il, iu] -= np.einsum("kleq,bkleq->eb", dT3[2, :2, :2], Gu, optimize=True)
            Ke[:, il, il] -= np.sum(dT3[2, 2, 2], axis=1)
            if dG3 is not None:
                Ke[:, il, jf] -= np.einsum("leq,bleq->eb", dG3[2, :2] * dx, Gf, optimize=True)
            K = self.scatter.matrix(Ke) + self.scatter_m.matrix(Km)
            r = self.scatter.vector(ve) + self.scatter_m.vector(re) - self._rhs(load)
            return K, r
        K = self.scatter.matrix(Ke)
        r = self.scatter.vector(ve) - self._rhs(load)
        return K, r

    def residual_scale(self, load) -> float:
        """Scale of the residual: ``mu L1 H`` (a force per unit length in x3)."""
        return self.material.mu * self.L1 * self.H

    def step_mesh(self, x: np.ndarray, load):
        """meshio ``Mesh`` of a state (used by :mod:`skfem_dielectric.export`).

        Points ``(X1, X2, 0)``; point data ``displacement`` ``(u1, u2, 0)``,
        ``potential``, ``pressure``; cell data (element averages) ``P33``,
        ``P11`` (total second Piola over ``mu``), ``lam1``, ``lam2``, ``lam3``.
        """
        from skfem.io.meshio import to_meshio

        load = self._load(load)
        u, p, phi, lam3 = self.split(x, load)
        nv = self.mesh.p.shape[1]
        disp = np.column_stack([u.reshape(-1, 2)[:nv], np.zeros(nv)])
        gu, lam3, gf, R, _ = self._volume(x, load, need_tangent=False)
        F = np.zeros((3, 3) + gu.shape[2:])
        F[:2, :2] = gu
        F[0, 0] += 1.0
        F[1, 1] += 1.0
        F[2, 2] = lam3
        P = R.P
        if self._local:
            from .maxwell import maxwell_stress

            J = F[2, 2] * (F[0, 0] * F[1, 1] - F[0, 1] * F[1, 0])
            tau = maxwell_stress(F, -self._sigma(load), self.material.eps)
            Finv = np.moveaxis(np.linalg.inv(np.moveaxis(F, (0, 1), (-2, -1))), (-2, -1),
                               (0, 1))
            P = P + J * np.einsum("ab...,Kb...->aK...", tau, Finv)
        Finv = np.moveaxis(np.linalg.inv(np.moveaxis(F, (0, 1), (-2, -1))), (-2, -1), (0, 1))
        S = np.einsum("Ka...,aL...->KL...", Finv, P) / self.material.mu
        cell = {"P33": S[2, 2], "P11": S[0, 0], "lam1": F[0, 0], "lam2": F[1, 1],
                "lam3": np.full_like(F[0, 0], lam3)}
        cell = {k: [v.mean(axis=-1)] for k, v in cell.items()}
        return to_meshio(self.mesh, point_data={"displacement": disp, "potential": phi[:nv],
                                                "pressure": p[:nv]},
                         cell_data=cell, encode_cell_data=False)

    def postprocess(self, x: np.ndarray, load) -> dict:
        """Stretches at the centre and ``P33`` along the centre line ``x2 = 0``.

        Returns ``lam1``, ``lam2`` at the centre (``x1 = x2 = 0``), ``lam3``,
        ``min_P33`` (min of the second Piola ``P33/mu`` along ``x2 = 0``) and its
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
        R = cross_section_kernel(self.material, gu, lam3, pq, gf, need_tangent=False)
        mu, eps = self.material.mu, self.material.eps
        P33 = R.P[2, 2] / lam3 / mu  # second Piola S33 = P33 / lam3 (F block-diagonal)
        E0 = float(gf[1, 0] * math.sqrt(eps / mu))
        D0 = float(-R.D_L[1, 0] / math.sqrt(mu * eps))
        if self._local:
            # total stress = elastic + Maxwell stress of the assumed field D = F D_L / J
            from .maxwell import maxwell_stress

            F = np.zeros((3, 3) + gu.shape[2:])
            F[:2, :2] = gu
            F[0, 0] += 1.0
            F[1, 1] += 1.0
            F[2, 2] = lam3
            J = F[2, 2] * (F[0, 0] * F[1, 1] - F[0, 1] * F[1, 0])
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


def cross_section_ramp(problem: CrossSection, s1: float, s3: float, D0, **ramp_options):
    """Pre-load ``(s1, s3)`` then the charge (or voltage) ramp on a cross-section.

    Parameters
    ----------
    problem : CrossSection
        The discretised cross-section.
    s1, s3 : float
        Dimensionless nominal stresses along x1 and x3 (``s3`` is ignored when
        ``lam3`` is prescribed). Equi-biaxial: ``s1 = s3 = s``; uni-axial:
        ``s3 = 0``.
    D0 : array_like
        Targets of ``D0`` (or ``E0`` under voltage control).
    **ramp_options
        Passed to :func:`skfem_dielectric.newton.ramp`.

    Returns
    -------
    RampResult
        Quantities of :meth:`CrossSection.postprocess` per step.
    """
    from .newton import ramp

    for name, v in (("s1", s1), ("s3", s3)):
        if not math.isfinite(float(v)):
            raise ValueError(f"{name} must be finite, got {v}")
    D0 = _D0_targets(D0)
    out = ramp(problem, [np.array([s1, s3, d]) for d in D0], **ramp_options)
    out.problem = problem  # for skfem_dielectric.export
    return out

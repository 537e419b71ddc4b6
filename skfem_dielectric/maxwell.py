"""Maxwell-traction coupling: an elastic problem loaded by the field's traction.

The second method of the paper's Sec. 6: the purely elastic incompressible
problem (elastic stress only in the volume) is loaded on its deformed boundary
by the Maxwell stress ``tau_m = E (x) D - (E.D)/2 I``.

Fields
------
Two fields can enter ``tau_m`` (``MaxwellPlate(field=...)``):

* ``"electrostatic"`` (default): the potential is solved on the deformed body
  as in the fully coupled model and ``E = -F^-T Grad phi``, ``D = eps E``
  (:func:`maxwell_traction_field`). With this field ``Div tau_m = 0``, so the
  variant discretises the same equations as the fully coupled solver.
* ``"local"``: no electrostatics (:func:`maxwell_traction`), described next.
  Exact on homogeneous states, but not curl-free where ``lam2`` varies in the
  plane, so it misses the tangential field and the faces' shear traction that
  balance the gradient of the lateral pull: wrong near clamps
  (docs/fe_variants.md).

The charges sprayed on the faces move with the material, ``N.D_L = -sigma_F``
per reference area (DESIGN.md §2). The local field takes the Lagrangian
displacement uniform through the body, ``D_L = -sigma_F e2`` (the homogeneous solution):
it satisfies Gauss' law ``Div D_L = 0`` and the charge boundary condition
exactly. Its push-forward is

    D = F D_L / J,      E = D / eps,

so on a charged face ``D.n = D_L.N / a`` with ``a = J |F^-T N|`` the local
area stretch: the current surface charge is ``sigma_F / a``, directed along
the deformed thickness fibre ``F e2`` (normal to the faces up to transverse
shear, which is small in a thin plate).

Sign
----
There is no field outside the plate, so the force per current area that the
field exerts on the body is the jump ``(tau_m^out - tau_m^in) n = -tau_m n``
with ``tau_m`` evaluated inside. On a charged face (``n = e2``) this is the
compressive Maxwell pressure ``-(E D/2) n``; on a lateral face (``E . n = 0``)
it is the outward pull ``+(E D/2) n``. Both are needed: the faces' pressure
alone gives only half of the electric term of the loading curve; with the
lateral pull the homogeneous plate follows Eq. (loading_gent) exactly
(``tau_11 = mu(lam1^2 - lam2^2) - D^2/eps``, as in the fully coupled model).

The nominal traction (per reference area) is a follower load,

    t0 = -tau_m cof(F) N
       = -(1/eps) [ (D_L.N) F D_L / J - |F D_L|^2 / (2 J) F^-T N ],

and :func:`maxwell_traction` also returns its exact derivative with respect
to ``F`` for the consistent (non-symmetric) tangent.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "maxwell_traction",
    "maxwell_traction_field",
    "maxwell_stress",
    "MaxwellPlate",
    "PardisoLUSolver",
    "nonsymmetric_solver",
    "maxwell_equibiaxial",
    "maxwell_keplinger",
]


def _det3(F: np.ndarray) -> np.ndarray:
    return (
        F[0, 0] * (F[1, 1] * F[2, 2] - F[1, 2] * F[2, 1])
        - F[0, 1] * (F[1, 0] * F[2, 2] - F[1, 2] * F[2, 0])
        + F[0, 2] * (F[1, 0] * F[2, 1] - F[1, 1] * F[2, 0])
    )


def _cof3(F: np.ndarray) -> np.ndarray:
    """Cofactor ``J F^-T`` of a field of 3x3 matrices."""
    C = np.empty_like(F)
    C[0, 0] = F[1, 1] * F[2, 2] - F[1, 2] * F[2, 1]
    C[0, 1] = F[1, 2] * F[2, 0] - F[1, 0] * F[2, 2]
    C[0, 2] = F[1, 0] * F[2, 1] - F[1, 1] * F[2, 0]
    C[1, 0] = F[0, 2] * F[2, 1] - F[0, 1] * F[2, 2]
    C[1, 1] = F[0, 0] * F[2, 2] - F[0, 2] * F[2, 0]
    C[1, 2] = F[0, 1] * F[2, 0] - F[0, 0] * F[2, 1]
    C[2, 0] = F[0, 1] * F[1, 2] - F[0, 2] * F[1, 1]
    C[2, 1] = F[0, 2] * F[1, 0] - F[0, 0] * F[1, 2]
    C[2, 2] = F[0, 0] * F[1, 1] - F[0, 1] * F[1, 0]
    return C


def _lagrangian_D(D_L, shape) -> np.ndarray:
    D_L = np.asarray(D_L, dtype=float)
    if D_L.ndim == 0 or D_L.shape[0] != 3:
        # scalar: charge per reference area, field along e2 (thickness)
        out = np.zeros((3,) + tuple(shape))
        out[1] = D_L
        return out
    return np.broadcast_to(D_L.reshape(D_L.shape + (1,) * (len(shape) + 1 - D_L.ndim)),
                           (3,) + tuple(shape))


def maxwell_stress(F: np.ndarray, D_L, eps: float) -> np.ndarray:
    """Maxwell stress ``tau_m = E (x) D - (E.D)/2 I`` of the assumed field.

    Parameters
    ----------
    F : ndarray, shape (3, 3, ...)
        Deformation gradient.
    D_L : float or ndarray, shape (3, ...)
        Lagrangian electric displacement; a scalar means ``D_L e2``.
    eps : float
        Permittivity.

    Returns
    -------
    ndarray, shape (3, 3, ...)
        Cauchy Maxwell stress with ``D = F D_L / J``, ``E = D/eps``.
    """
    F = np.asarray(F, dtype=float)
    J = _det3(F)
    DL = _lagrangian_D(D_L, F.shape[2:])
    d = np.einsum("iM...,M...->i...", F, DL) / J
    dd = np.einsum("i...,i...->...", d, d)
    eye = np.eye(3).reshape((3, 3) + (1,) * J.ndim)
    return (np.einsum("i...,j...->ij...", d, d) - 0.5 * dd * eye) / eps


def maxwell_traction(F: np.ndarray, N: np.ndarray, D_L, eps: float):
    """Nominal Maxwell traction ``t0 = -tau_m cof(F) N`` and its F-derivative.

    Parameters
    ----------
    F : ndarray, shape (3, 3, ...)
        Deformation gradient at boundary points.
    N : ndarray, shape (3, ...)
        Outward unit normal of the reference boundary.
    D_L : float or ndarray, shape (3, ...)
        Lagrangian electric displacement (``-sigma_F`` for charge per
        reference area ``sigma_F``); a scalar means ``D_L e2``.
    eps : float
        Permittivity.

    Returns
    -------
    t0 : ndarray, shape (3, ...)
        Force per reference area exerted by the field on the body.
    dt0 : ndarray, shape (3, 3, 3, ...)
        ``dt0_i / dF_kL`` (the follower-load tangent; not symmetric).

    Notes
    -----
    ``t0 = -(1/eps)[(D_L.N) d/J - |d|^2/(2J) g]`` with ``d = F D_L`` and
    ``g = F^-T N``; ``dd_i/dF_kL = delta_ik D_L,L``, ``dJ/dF_kL = J G_kL`` and
    ``dg_i/dF_kL = -G_iL g_k`` (``G = F^-T``). See the module docstring for
    the field and the sign (paper Sec. 6, second method).
    """
    F = np.asarray(F, dtype=float)
    N = np.asarray(N, dtype=float)
    shape = F.shape[2:]
    J = _det3(F)
    G = _cof3(F) / J
    DL = _lagrangian_D(D_L, shape)
    d = np.einsum("iM...,M...->i...", F, DL)
    g = np.einsum("iM...,M...->i...", G, N)
    DN = np.einsum("M...,M...->...", DL, N)
    dd = np.einsum("i...,i...->...", d, d)
    t0 = -(DN / J * d - 0.5 * dd / J * g) / eps
    eye = np.eye(3).reshape((3, 3) + (1,) * J.ndim)
    da = (DN / J) * (
        np.einsum("ik...,L...->ikL...", eye, DL) - np.einsum("i...,kL...->ikL...", d, G)
    )
    db = (
        np.einsum("k...,L...,i...->ikL...", d, DL, g) / J
        - 0.5 * dd / J * np.einsum("kL...,i...->ikL...", G, g)
        - 0.5 * dd / J * np.einsum("iL...,k...->ikL...", G, g)
    )
    return t0, -(da - db) / eps


def maxwell_traction_field(F: np.ndarray, G: np.ndarray, N: np.ndarray, eps: float):
    """Nominal Maxwell traction of a computed field and its derivatives.

    Parameters
    ----------
    F : ndarray, shape (3, 3, ...)
        Deformation gradient at boundary points.
    G : ndarray, shape (3, ...)
        Referential potential gradient ``Grad phi = -E_L`` (from an
        electrostatic solution on the deformed body).
    N : ndarray, shape (3, ...)
        Outward unit normal of the reference boundary.
    eps : float
        Permittivity.

    Returns
    -------
    t0 : ndarray, shape (3, ...)
        ``-tau_m cof(F) N`` with ``E = -F^-T G``, ``D = eps E`` (force per
        reference area exerted by the field on the body; no field outside).
    dt0_dF : ndarray, shape (3, 3, 3, ...)
        ``dt0_i / dF_kL``.
    dt0_dG : ndarray, shape (3, 3, ...)
        ``dt0_i / dG_L``.

    Notes
    -----
    With ``a = F^-T G`` (``= -E``) and ``m = cof(F) N = J F^-T N``:
    ``t0 = -eps [a (a.m) - |a|^2 m / 2]``, ``da_i/dF_kL = -a_k Finv_Li``,
    ``da_i/dG_L = Finv_Li`` and ``dm_i/dF_kL = Finv_Lk m_i - m_k Finv_Li``.
    """
    F = np.asarray(F, dtype=float)
    J = _det3(F)
    FinvT = _cof3(F) / J           # FinvT[i, L] = Finv[L, i]
    a = np.einsum("iM...,M...->i...", FinvT, G)
    m = J * np.einsum("iM...,M...->i...", FinvT, N)
    am = np.einsum("i...,i...->...", a, m)
    aa = np.einsum("i...,i...->...", a, a)
    t0 = -eps * (a * am - 0.5 * aa * m)
    # derivatives of a, m
    da_F = -np.einsum("k...,iL...->ikL...", a, FinvT)
    dm_F = (np.einsum("kL...,i...->ikL...", FinvT, m)
            - np.einsum("k...,iL...->ikL...", m, FinvT))
    dam_F = (np.einsum("i...,ikL...->kL...", m, da_F)
             + np.einsum("i...,ikL...->kL...", a, dm_F))
    daa_F = 2.0 * np.einsum("i...,ikL...->kL...", a, da_F)
    dF = -eps * (da_F * am + np.einsum("i...,kL...->ikL...", a, dam_F)
                 - 0.5 * np.einsum("kL...,i...->ikL...", daa_F, m) - 0.5 * aa * dm_F)
    da_G = FinvT
    dam_G = np.einsum("i...,iL...->L...", m, da_G)
    daa_G = 2.0 * np.einsum("i...,iL...->L...", a, da_G)
    dG = -eps * (da_G * am + np.einsum("i...,L...->iL...", a, dam_G)
                 - 0.5 * np.einsum("L...,i...->iL...", daa_G, m))
    return t0, dF, dG


# --------------------------------------------------------------------------
# 3D plate with Maxwell-traction coupling
# --------------------------------------------------------------------------

_FIELDS = ("electrostatic", "local")
_LOADED_FACES = ("top", "bottom", "x1_plus", "x1_minus", "x3_plus", "x3_minus")


def nonsymmetric_solver(name="superlu"):
    """Linear solver suitable for the non-symmetric Maxwell-traction tangent.

    Parameters
    ----------
    name : {"superlu", "pardiso", "auto"} or LinearSolver
        ``"pardiso"``/``"auto"`` give :class:`PardisoLUSolver` (if ``pypardiso``
        is installed; ``"auto"`` falls back to SuperLU); an instance is
        returned unchanged.

    Returns
    -------
    LinearSolver
    """
    from .linear import get_linear_solver, pardiso_available

    if not isinstance(name, str):
        return name
    if name in ("pardiso", "auto") and pardiso_available():
        return PardisoLUSolver()
    if name == "pardiso":
        raise ValueError("linear solver 'pardiso' needs pypardiso")
    return get_linear_solver("superlu" if name == "auto" else name)


def _linear_solver_base():
    from .linear import LinearSolver

    return LinearSolver


def _plate_problem_class():
    from .plate import PlateProblem

    return PlateProblem


class PardisoLUSolver(_linear_solver_base()):
    """MKL PARDISO for the non-symmetric Maxwell-traction tangents (``mtype = 11``).

    The symmetric-indefinite PARDISO solver of :mod:`skfem_dielectric.linear`
    reads only the upper triangle, which is wrong for follower loads; this one
    factorises the whole matrix. Same interface (``solve(K, b)``).
    """

    name = "pardiso-lu"
    inertia = None

    def __init__(self):
        from .linear import new_pypardiso_solver  # optional dependency (`fast` extra)

        self._ps = new_pypardiso_solver(11)

    def solve(self, K, b):
        """Factorise ``K`` and solve ``K x = b``."""
        import scipy.sparse as sp

        A = sp.csr_matrix(K)
        A.sort_indices()
        self._ps.factorize(A)
        return np.ascontiguousarray(self._ps.solve(A, np.asarray(b, dtype=float)))


class MaxwellPlate(_plate_problem_class()):
    """3D plate, elastic in the volume, loaded by the Maxwell traction on its boundary.

    A :class:`skfem_dielectric.plate.PlateProblem` (same mesh, Taylor-Hood u-p
    discretisation, loads, clamp, post-processing, ramp) whose electric
    coupling is moved from the volume to the boundary: the volume carries only
    the elastic stress ``2 W1 F + p J F^-T``, and every non-symmetry face
    (``top``/``bottom``: the charged faces; ``x1_*``, ``x3_*``: the lateral
    faces and clamps) carries the follower traction ``t0 = -tau_m cof(F) N``,
    linearised in the (non-symmetric) tangent.

    Parameters
    ----------
    plate : PlateMesh
        Mesh (:func:`skfem_dielectric.mesh.plate_mesh`).
    material
        Ideal dielectric.
    field : {"electrostatic", "local"}
        Which field enters ``tau_m``. ``"electrostatic"`` (default): the
        potential is solved on the deformed body (``Div D_L = 0``, ``N.D_L =
        -sigma_F`` on the charged faces, as in the fully coupled model) and
        ``E = -F^-T Grad phi``, ``D = eps E``. ``"local"``: no electrostatics;
        the field is the local thin-plate one, ``D = F D_L / J`` with
        ``D_L = -sigma_F e2`` (current charge ``sigma_F`` over the local area
        stretch, along the deformed thickness fibre; see the module docstring).
    **options
        Passed to :class:`PlateProblem` (``loading``, ``phi_element``,
        ``intorder``, ``chunk``, ``threads``); the control is charge. Besides
        the loadings of :class:`PlateProblem`, ``loading="uniaxial-free"`` puts
        the dead load ``s`` on the x1 faces only (x3 faces free: the homogeneous
        uni-axial state of Eq. (DEuniax); needs the eighth/quarter model).

    Notes
    -----
    With the exact field ``Div tau_m = 0`` in the body, so the fully coupled
    equations ``int (P_el + P_m) : Grad v = f`` and these,
    ``int P_el : Grad v = f + int t0 . v dA``, coincide; discretely they differ
    by ``int Div P_m . v``, which vanishes on homogeneous states and is a
    discretisation error otherwise. The ``"local"`` field is not curl-free
    where ``lam2`` varies in the plane: it misses the tangential field
    ``E_1 ~ x2 d(E_2)/dx1`` whose shear traction on the faces balances the
    gradient of the lateral Maxwell pull, so it deviates from the fully
    coupled model near the clamps (measured in docs/fe_variants.md).
    Use :func:`nonsymmetric_solver` (the ramp's default SuperLU is fine;
    the symmetric PARDISO solver is not).
    """

    def __init__(self, plate, material, *, field: str = "electrostatic", **options):
        import skfem as fe

        from .assembly import DofReduction, ScatterMap

        if field not in _FIELDS:
            raise ValueError(f"field must be one of {_FIELDS}, got {field!r}")
        if options.get("control", "charge") != "charge":
            raise ValueError(f"MaxwellPlate needs control='charge', got {options['control']!r}")
        if options.get("formulation", "mixed") != "mixed":
            raise ValueError("MaxwellPlate needs formulation='mixed', got "
                             f"{options['formulation']!r}")
        options = {k: v for k, v in options.items() if k not in ("control", "formulation")}
        free_uniaxial = options.get("loading") == "uniaxial-free"
        if free_uniaxial:
            options["loading"] = "equibiaxial"
        super().__init__(plate, material, control="charge", formulation="mixed", **options)
        self.field = field
        m = plate.mesh
        if free_uniaxial:  # dead load on x1 faces only, x3 faces free
            self.loading = "uniaxial-free"
            self.f_s = np.zeros(self.n_full)
            for name in ("x1_plus", "x1_minus"):
                if name in m.boundaries:
                    fb = fe.FacetBasis(m, fe.ElementHex2(), facets=m.boundaries[name],
                                       intorder=options.get("intorder", 4))
                    v = fe.asm(fe.LinearForm(lambda v, w: v * w.n[0]), fb)
                    self.f_s[0: 3 * self.b2.N: 3] += material.mu * v
        if field == "local":  # purely elastic: every potential dof fixed at 0
            fixed = np.union1d(np.flatnonzero(self.red.index < 0),
                               np.arange(self.off_phi, self.n_full))
            tied = ([3 * self.b2.get_dofs("x1_plus").all()] if self.loading == "uniaxial"
                    else [])
            self.red = DofReduction(self.n_full, fixed, tied)
            self.scatter = ScatterMap(self.red.index[self.edofs], self.red.n)
            if hasattr(self, "_block_positions"):  # scatter positions cached by the core
                self._block_pos = self._block_positions()
                self._pos_cache = {}
        names = [n for n in _LOADED_FACES if n in m.boundaries]
        facets = np.concatenate([m.boundaries[n] for n in names])
        intorder = options.get("intorder", 4)
        fb2 = fe.FacetBasis(m, fe.ElementHex2(), facets=facets, intorder=intorder)
        fbf = fe.FacetBasis(m, self.bphi.elem, facets=facets, intorder=intorder)
        self._b = dict(
            V=np.array([np.asarray(f[0]) for f in fb2.basis]),          # (i, e, q)
            dN=np.array([f[0].grad for f in fb2.basis]),                # (i, K, e, q)
            dNf=np.array([f[0].grad for f in fbf.basis]),               # (k, K, e, q)
            N=np.asarray(fb2.normals), dx=np.asarray(fb2.dx))
        e2 = fb2.element_dofs.T
        eu = (3 * e2[:, :, None] + np.arange(3)).reshape(e2.shape[0], -1)
        ef = self.off_phi + fbf.element_dofs.T
        self._bdofs = np.concatenate([eu, ef], axis=1)
        self._bscatter = ScatterMap(self.red.index[self._bdofs], self.red.n)
        self._mu_b = eu.shape[1]
        self.loaded_faces = tuple(names)

    # -- volume: elastic stress only ------------------------------------------
    def _response(self, xf, sl, need_tangent=True):
        r, F, G, p = super()._response(xf, sl, need_tangent)
        if self.field == "electrostatic":
            r0 = self._point_response(F, np.zeros_like(G), p, sl, need_tangent)
            r.P = r0.P
            if need_tangent:
                r.A_FF = r0.A_FF
        return r, F, G, p

    # The volume u-rows do not depend on phi (their stress is elastic), while the phi-rows
    # keep D_L(F, Grad phi): zero the u-phi block of the core's flat block buffer, keep the
    # phi-u block.
    def _element_blocks(self, r, sl):
        buf = super()._element_blocks(r, sl)
        ne, o = sl.stop - sl.start, 0
        for name, n in self._block_sizes():
            if name == "uf":
                buf[o: o + ne * n] = 0.0
            o += ne * n
        return buf

    def external(self, load) -> np.ndarray:
        """Dead tractions; the charges only under the electrostatic field."""
        s, e = self._check_load(load)
        f = s * self.f_s
        if self.field == "electrostatic":
            f = f - e * self.q_D0
        return f

    # -- boundary: Maxwell traction -------------------------------------------
    def _sigma(self, load) -> float:
        return self._check_load(load)[1] * math.sqrt(self.material.mu * self.material.eps)

    def _boundary(self, x, load, need_tangent=True):
        b = self._b
        xf = self.full(x, load)
        ne = self._bdofs.shape[0]
        ue = xf[self._bdofs[:, : self._mu_b]].reshape(ne, -1, 3)
        F = np.einsum("eia,iKeq->aKeq", ue, b["dN"], optimize=True)
        F[0, 0] += 1.0
        F[1, 1] += 1.0
        F[2, 2] += 1.0
        eps = self.material.eps
        if self.field == "electrostatic":
            G = np.einsum("ek,kKeq->Keq", xf[self._bdofs[:, self._mu_b:]], b["dNf"],
                          optimize=True)
            t0, dF, dG = maxwell_traction_field(F, G, b["N"], eps)
        else:
            t0, dF = maxwell_traction(F, b["N"], -self._sigma(load), eps)
            dG = None
        dx = b["dx"]
        re = -np.einsum("aeq,ieq->eia", t0 * dx, b["V"], optimize=True).reshape(ne, -1)
        mf = self._bdofs.shape[1] - self._mu_b
        rb = self._bscatter.vector(np.concatenate([re, np.zeros((ne, mf))], axis=1))
        if not need_tangent:
            return None, rb
        m = self._bdofs.shape[1]
        Ke = np.zeros((ne, m, m))
        Kuu = -np.einsum("ieq,abLeq,jLeq->eiajb", b["V"], dF * dx, b["dN"], optimize=True)
        Ke[:, : self._mu_b, : self._mu_b] = Kuu.reshape(ne, self._mu_b, self._mu_b)
        if dG is not None:
            Kuf = -np.einsum("ieq,aLeq,kLeq->eiak", b["V"], dG * dx, b["dNf"], optimize=True)
            Ke[:, : self._mu_b, self._mu_b:] = Kuf.reshape(ne, self._mu_b, mf)
        return self._bscatter.matrix(Ke), rb

    def assemble(self, x, load):
        """Reduced (non-symmetric) tangent and residual."""
        K, r = super().assemble(x, load)
        Kb, rb = self._boundary(x, load)
        return (K + Kb).tocsr(), r + rb

    def residual(self, x, load):
        """Reduced residual (line search)."""
        return super().residual(x, load) + self._boundary(x, load, need_tangent=False)[1]

    # -- post-processing: total stress = elastic + Maxwell ----------------------
    def stresses(self, F, G, p):
        """As :meth:`PlateProblem.stresses`; for the local field the Maxwell stress
        of the assumed field ``D = F D_L/J`` is added (total stress)."""
        if self.field == "electrostatic":
            return super().stresses(F, G, p)
        out = super().stresses(F, np.zeros_like(G), p)
        sig = getattr(self, "_post_sigma", 0.0)
        tau = maxwell_stress(F, -sig, self.material.eps)
        J = out["J"]
        Finv = np.moveaxis(np.linalg.inv(np.moveaxis(F, (0, 1), (-2, -1))), (-2, -1), (0, 1))
        P_m = J * np.einsum("ab...,Kb...->aK...", tau, Finv)
        out["P1"] = out["P1"] + P_m
        out["S"] = out["S"] + np.einsum("Ka...,aL...->KL...", Finv, P_m)
        out["sigma"] = out["sigma"] + tau
        DL = np.zeros_like(G)
        DL[1] = -sig
        D = np.einsum("aK...,K...->a...", F, DL) / J
        out.update(D=D, E=D / self.material.eps, D_L=DL,
                   E_L=np.einsum("aK...,a...->K...", F, D / self.material.eps))
        return out

    def full(self, x, load):
        """Full dof vector; also records the charge of ``load`` for :meth:`stresses`
        (the local field depends on it; post-processing and export call ``full``
        first)."""
        self._post_sigma = self._sigma(load)
        return super().full(x, load)

    def postprocess(self, x, load):
        """:meth:`PlateProblem.postprocess` with the total (elastic + Maxwell) stress."""
        self._post_sigma = self._sigma(load)
        return super().postprocess(x, load)


def maxwell_equibiaxial(s: float, D0, *, field: str = "electrostatic",
                        model="neo-Hookean", Jm: float = 97.2,
                        size: tuple = (4.0, 1.0, 4.0), elements: tuple = (1, 1, 1),
                        symmetry: str = "eighth", preload_steps: int = 4,
                        phi_element: str = "Q2", linear_solver="auto", on_step=None,
                        x0=None, start=None, rtol: float = 1e-11, max_cutbacks: int = 6):
    """Equi-biaxial dead-load plate with Maxwell-traction coupling.

    The same arguments and ramp as
    :func:`skfem_dielectric.drivers.equibiaxial_plate` (charge control), on a
    :class:`MaxwellPlate` with the given ``field``. ``linear_solver`` is mapped
    through :func:`nonsymmetric_solver`.

    Returns
    -------
    RampResult
        ``lam1`` at the centre follows Eq. (loading_gent) for either field.
    """
    from .drivers import _finite, _run, _targets, make_material
    from .mesh import plate_mesh

    s = _finite("s", s)
    mat = make_material(model, Jm)
    pm = plate_mesh(*size, *elements, symmetry=symmetry)
    prob = MaxwellPlate(pm, mat, loading="equibiaxial", field=field, phi_element=phi_element)
    return _run(prob, _targets(s, D0, preload_steps), on_step=on_step, x0=x0, start=start,
                linear_solver=nonsymmetric_solver(linear_solver),
                phase_of=lambda ld: "preload" if ld[1] == 0 else "charge",
                extra={"model": type(mat).__name__, "variant": f"maxwell-{field}"},
                atol=0.0, rtol=rtol, max_cutbacks=max_cutbacks)


def maxwell_keplinger(alpha: float | None = 1.0, D0=(1, 2, 3, 4, 5, 6), *,
                      field: str = "electrostatic", s: float | None = None, g: float = 9.81,
                      model="neo-Hookean", Jm: float = 97.2, size: tuple = (100.0, 1.0, 50.0),
                      elements: tuple = (40, 1, 20), symmetry: str = "eighth",
                      grading: float = 1.0, preload_steps: int = 3, phi_element: str = "Q2",
                      linear_solver="auto", on_step=None, x0=None, start=None,
                      rtol: float = 1e-9, max_cutbacks: int = 6, threads=None):
    """The clamped uni-axial Keplinger plate with Maxwell-traction coupling.

    The same geometry, clamp, weight, pre-load and charge ramp as
    :func:`skfem_dielectric.drivers.keplinger_plate` (``s = alpha m g/(mu A)``,
    ``m = 150 g``, ``mu = 9833.07 Pa``, ``A = 50 mm^2``), on a
    :class:`MaxwellPlate` with the given ``field`` (``"electrostatic"`` or
    ``"local"``). ``linear_solver`` is mapped through
    :func:`nonsymmetric_solver`.

    Returns
    -------
    RampResult
        Per step ``lam1`` at the centre, ``min_P33`` (total stress) on the centre
        line, ``min_P33_clamp``, ``phase``, ``alpha``.
    """
    from .drivers import _finite, _run, _targets, keplinger_s, make_material
    from .mesh import plate_mesh

    if s is None:
        if alpha is None:
            raise ValueError("give alpha or s")
        s = keplinger_s(alpha, g=g)
    s = _finite("s", s)
    mat = make_material(model, Jm)
    pm = plate_mesh(*size, *elements, symmetry=symmetry, grading=grading)
    prob = MaxwellPlate(pm, mat, loading="uniaxial", field=field, phi_element=phi_element,
                        threads=threads)
    return _run(prob, _targets(s, D0, preload_steps), on_step=on_step, x0=x0, start=start,
                linear_solver=nonsymmetric_solver(linear_solver),
                phase_of=lambda ld: "preload" if ld[1] == 0 else "charge",
                extra={"alpha": alpha if alpha is not None else float("nan"), "g": g,
                       "variant": f"maxwell-{field}"},
                atol=0.0, rtol=rtol, max_cutbacks=max_cutbacks)

"""Maxwell-traction coupling: the field's traction on the deformed boundary, and its linearisation.

The second method of the paper's Sec. 6: the purely elastic incompressible
problem (elastic stress only in the volume) is loaded on its deformed boundary
by the Maxwell stress ``tau_m = E (x) D - (E.D)/2 I``.

Fields
------
Two fields can enter ``tau_m`` (``PlateProblem(coupling="maxwell", field=...)``):

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
per reference area (the charges are sprayed on and move
with the material). The local field takes the Lagrangian
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

import numpy as np
from skfem import ElementHex2, FacetBasis

from ..fem.assembly import ScatterMap
from ..kinematics import cof3, det3, inv3

__all__ = ["maxwell_stress", "maxwell_traction", "maxwell_traction_field",
           "maxwell_nominal_stress", "MaxwellBoundary"]

#: faces of a plate model that carry the Maxwell traction (every non-symmetry face)
LOADED_FACES = ("top", "bottom", "x1_plus", "x1_minus", "x3_plus", "x3_minus")


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
    J = det3(F)
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
    J = det3(F)
    G = cof3(F) / J
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
    J = det3(F)
    FinvT = cof3(F) / J           # FinvT[i, L] = Finv[L, i]
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


def maxwell_nominal_stress(F: np.ndarray, D_L, eps: float) -> tuple[np.ndarray, np.ndarray]:
    """Maxwell stress of the local field and its nominal (first Piola) form.

    Parameters
    ----------
    F : ndarray, shape (3, 3, ...)
        Deformation gradient.
    D_L : float or ndarray, shape (3, ...)
        Lagrangian electric displacement (a scalar means ``D_L e2``).
    eps : float
        Permittivity.

    Returns
    -------
    tau : ndarray, shape (3, 3, ...)
        Cauchy Maxwell stress (:func:`maxwell_stress`).
    P_m : ndarray, shape (3, 3, ...)
        ``J tau F^-T``, added to the elastic first Piola stress to give the total stress.
    """
    tau = maxwell_stress(F, D_L, eps)
    P_m = det3(F) * np.einsum("ab...,Kb...->aK...", tau, inv3(F))
    return tau, P_m


class MaxwellBoundary:
    """The Maxwell traction on the non-symmetry faces of a 3D plate model, linearised.

    Parameters
    ----------
    mesh
        scikit-fem ``MeshHex`` with the plate's named boundaries.
    phi_element
        scikit-fem element of the potential (for the electrostatic field).
    off_phi
        Offset of the potential in the full dof vector ``[u (node-major), p, phi]``.
    red
        The model's :class:`~skfem_dielectric.fem.assembly.DofReduction`.
    eps
        Permittivity.
    field : {"electrostatic", "local"}
        Field in ``tau_m``: ``E = -F^-T Grad phi`` of the solved potential, or the local
        field ``D = F D_L / J`` of the charge.
    intorder
        Quadrature order on the faces.

    Notes
    -----
    Residual contribution ``-int t0 . v dA`` (reference faces) with
    ``t0 = -tau_m cof(F) N``; its tangent (:func:`maxwell_traction_field`,
    :func:`maxwell_traction`) is not symmetric.
    """

    def __init__(self, mesh, phi_element, off_phi: int, red, eps: float, field: str,
                 intorder: int = 4):
        names = [n for n in LOADED_FACES if n in mesh.boundaries]
        facets = np.concatenate([mesh.boundaries[n] for n in names])
        fb2 = FacetBasis(mesh, ElementHex2(), facets=facets, intorder=intorder)
        fbf = FacetBasis(mesh, phi_element, facets=facets, intorder=intorder)
        self.V = np.array([np.asarray(f[0]) for f in fb2.basis])          # (i, e, q)
        self.dN = np.array([f[0].grad for f in fb2.basis])                # (i, K, e, q)
        self.dNf = np.array([f[0].grad for f in fbf.basis])               # (k, K, e, q)
        self.N, self.dx = np.asarray(fb2.normals), np.asarray(fb2.dx)
        e2 = fb2.element_dofs.T
        eu = (3 * e2[:, :, None] + np.arange(3)).reshape(e2.shape[0], -1)
        self.dofs = np.concatenate([eu, off_phi + fbf.element_dofs.T], axis=1)
        self.scatter = ScatterMap(red.index[self.dofs], red.n)
        self.m_u = eu.shape[1]
        self.eps, self.field = eps, field
        self.faces = tuple(names)

    def assemble(self, xf: np.ndarray, sigma: float, need_tangent: bool = True):
        """Reduced ``(K, r)`` of the traction at the full dof vector ``xf`` and the charge
        ``sigma`` per reference area (``K`` is ``None`` without the tangent)."""
        ne = self.dofs.shape[0]
        ue = xf[self.dofs[:, : self.m_u]].reshape(ne, -1, 3)
        F = np.einsum("eia,iKeq->aKeq", ue, self.dN, optimize=True)
        F[0, 0] += 1.0
        F[1, 1] += 1.0
        F[2, 2] += 1.0
        if self.field == "electrostatic":
            G = np.einsum("ek,kKeq->Keq", xf[self.dofs[:, self.m_u:]], self.dNf,
                          optimize=True)
            t0, dF, dG = maxwell_traction_field(F, G, self.N, self.eps)
        else:
            t0, dF = maxwell_traction(F, self.N, -sigma, self.eps)
            dG = None
        re = -np.einsum("aeq,ieq->eia", t0 * self.dx, self.V, optimize=True).reshape(ne, -1)
        mf = self.dofs.shape[1] - self.m_u
        rb = self.scatter.vector(np.concatenate([re, np.zeros((ne, mf))], axis=1))
        if not need_tangent:
            return None, rb
        m = self.dofs.shape[1]
        Ke = np.zeros((ne, m, m))
        Kuu = -np.einsum("ieq,abLeq,jLeq->eiajb", self.V, dF * self.dx, self.dN, optimize=True)
        Ke[:, : self.m_u, : self.m_u] = Kuu.reshape(ne, self.m_u, self.m_u)
        if dG is not None:
            Kuf = -np.einsum("ieq,aLeq,kLeq->eiak", self.V, dG * self.dx, self.dNf,
                             optimize=True)
            Ke[:, : self.m_u, self.m_u:] = Kuf.reshape(ne, self.m_u, mf)
        return self.scatter.matrix(Ke), rb

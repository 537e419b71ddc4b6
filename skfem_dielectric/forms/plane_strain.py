"""Generalised-plane-strain weak form of the cross-section (x1-x2), fully coupled or Maxwell.

Kinematics: every fibre along x3 is stretched by the same uniform ``lam3``::

    F = [[F11, F12, 0], [F21, F22, 0], [0, 0, lam3]],   Grad phi = (phi_1, phi_2, 0).

Unknowns ``u`` (Q2), ``p`` (Q1), ``phi`` (Q2) and the global ``lam3``.  With the energy
density ``psi(F, p, Grad phi)`` of :mod:`skfem_dielectric.materials` (embedded in 3D) the
weak form per unit length in x3 is::

    int_A P_ij v_i,j dA              = s1 mu int_{x1 = L1/2} v_1 dL          (u rows)
    int_A (J - 1 - p/kappa) q dA     = 0                                       (p rows)
    int_A D_L . Grad w dA            = -sigma_F int_top w dL                   (phi rows)
    int_A P_33 dA                    = s3 mu A                                 (lam3 row)

(the last is the x3 resultant of the nominal stress over the reference section ``A``).
Under the Maxwell coupling the u and lam3 rows carry the elastic stress only and the
Maxwell traction ``-tau_m cof(F) N`` acts on the top face, the end ``x1 = L1/2`` and, in
the lam3 row, on the x3 faces (:mod:`skfem_dielectric.forms.maxwell_traction`).
"""

from __future__ import annotations

import numpy as np

from ..kinematics import pad3, plane_strain_F
from ..materials import ideal_dielectric_response
from .maxwell_traction import maxwell_traction, maxwell_traction_field

__all__ = ["cross_section_kernel", "PlaneStrainForm"]


def cross_section_kernel(material, gradu: np.ndarray, lam3, p: np.ndarray,
                         gradphi: np.ndarray, need_tangent: bool = True,
                         grad_div: float = 0.0):
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
    grad_div : float
        Grad-div stabilisation ``gamma (J - 1)^2 / 2`` (``gamma`` in stress units).

    Returns
    -------
    PointResponse
        The 3D response of :func:`ideal_dielectric_response` at
        ``F = diag-block(I + gradu, lam3)``, ``G = (gradphi, 0)``; the in-plane
        blocks and the ``33`` entries are what the 2D model uses.
    """
    return ideal_dielectric_response(material, plane_strain_F(gradu, lam3), pad3(gradphi), p,
                                     need_tangent=need_tangent, grad_div=grad_div)


class PlaneStrainForm:
    """Element arrays of the cross-section: volume terms and Maxwell boundary terms.

    Parameters
    ----------
    bu, bp, bf
        scikit-fem bases of ``u`` (vector Q2), ``p`` (Q1) and ``phi`` (Q2), one quadrature.
    fbm, fbf
        Facet bases of ``u`` and ``phi`` on the Maxwell-loaded edges (``None`` for the full
        coupling).

    Notes
    -----
    Element dof order ``[u (18), p (4), phi (9), lam3]``; the Maxwell edge arrays use
    ``[u (18), lam3, phi (9)]``.
    """

    def __init__(self, bu, bp, bf, fbm=None, fbf=None):
        self.nb = (bu.Nbfun, bp.Nbfun, bf.Nbfun)
        self.Gu = np.array([bu.basis[a][0].grad for a in range(self.nb[0])])
        self.Np = np.array([np.asarray(bp.basis[a][0]) for a in range(self.nb[1])])
        self.Gf = np.array([bf.basis[a][0].grad for a in range(self.nb[2])])
        self.dx = bu.dx
        self.fbm = fbm
        if fbm is not None:
            self.Gm = np.array([fbm.basis[a][0].grad for a in range(self.nb[0])])
            self.Vm = np.array([np.asarray(fbm.basis[a][0]) for a in range(self.nb[0])])
            self.Gmf = np.array([fbf.basis[a][0].grad for a in range(self.nb[2])])
            self.fphi = fbf.element_dofs

    def fields(self, u, p, phi, edofs):
        """``Grad u``, ``p`` and ``Grad phi`` at the quadrature points (``edofs``: the
        element dofs of the three bases)."""
        du, dp, df = edofs
        gu = np.einsum("ae,aijeq->ijeq", u[du], self.Gu, optimize=True)
        pq = np.einsum("ae,aeq->eq", p[dp], self.Np, optimize=True)
        gf = np.einsum("ae,aieq->ieq", phi[df], self.Gf, optimize=True)
        return gu, pq, gf

    def vectors(self, R, Rm) -> np.ndarray:
        """Element residuals; ``Rm`` gives the stress of the u/lam3 rows."""
        dx = self.dx
        ru = np.einsum("ijeq,aijeq->ea", Rm.P[:2, :2] * dx, self.Gu, optimize=True)
        rp = np.einsum("eq,aeq->ea", R.dpsi_dp * dx, self.Np, optimize=True)
        rf = np.einsum("ieq,aieq->ea", R.D_L[:2] * dx, self.Gf, optimize=True)
        rl = np.sum(Rm.P[2, 2] * dx, axis=1)[:, None]
        return np.concatenate([ru, rp, rf, rl], axis=1)

    def matrices(self, R, Rm, elastic_volume: bool) -> np.ndarray:
        """Element tangents (``elastic_volume``: the u/lam3 rows do not depend on phi)."""
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
        if not elastic_volume:
            Ke[:, iu, jf] = kuf
        Ke[:, jf, iu] = np.swapaxes(kuf, 1, 2)
        klf = np.einsum("Leq,bLeq->eb", AFG[2, 2, :2], Gf, optimize=True)
        if not elastic_volume:
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
        return Ke

    def maxwell(self, u, phi, lam3, gu, gf, D_L, eps, local: bool, need_tangent=True):
        """Maxwell-traction terms: edges (top, x1_plus) and the x3 faces.

        Returns the edge element vectors/matrices over the facet dofs
        ``[u (18), lam3, phi (9)]`` and the x3-face traction ``t3`` with its
        derivatives (per reference area of the section)."""
        fbm = self.fbm
        gm = np.einsum("ae,aijeq->ijeq", u[fbm.element_dofs], self.Gm, optimize=True)
        N = pad3(np.asarray(fbm.normals))
        N3 = np.zeros((3,) + gu.shape[2:])
        N3[2] = 1.0
        if local:
            t0, dF = maxwell_traction(plane_strain_F(gm, lam3), N, D_L, eps)
            t3, dF3 = maxwell_traction(plane_strain_F(gu, lam3), N3, D_L, eps)
            dG = dG3 = None
        else:
            gmf = np.einsum("ae,aieq->ieq", phi[self.fphi], self.Gmf, optimize=True)
            t0, dF, dG = maxwell_traction_field(plane_strain_F(gm, lam3), pad3(gmf), N, eps)
            t3, dF3, dG3 = maxwell_traction_field(plane_strain_F(gu, lam3), pad3(gf), N3, eps)
        dx = fbm.dx
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

    def x3_face_terms(self, ve, Ke, t3, dF3, dG3):
        """Add the x3 faces' Maxwell traction to the lam3 row (in place)."""
        dx = self.dx
        nu, npp, nf = self.nb
        m = nu + npp + nf + 1
        iu, jf, il = slice(0, nu), slice(nu + npp, m - 1), m - 1
        ve[:, -1] -= np.sum(t3[2] * dx, axis=1)
        if Ke is None:
            return
        dT3 = dF3 * dx
        Ke[:, il, iu] -= np.einsum("kleq,bkleq->eb", dT3[2, :2, :2], self.Gu, optimize=True)
        Ke[:, il, il] -= np.sum(dT3[2, 2, 2], axis=1)
        if dG3 is not None:
            Ke[:, il, jf] -= np.einsum("leq,bleq->eb", dG3[2, :2] * dx, self.Gf, optimize=True)

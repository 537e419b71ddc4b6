"""The mixed u-p-phi weak form as plain scikit-fem integrands: the maths, slow and readable.

:class:`~skfem_dielectric.forms.mixed_upphi.MixedUPPhiForm` assembles the same form with
batched arrays, worker threads and precomputed scatter positions; this module writes it
as scikit-fem ``BilinearForm`` / ``LinearForm`` integrands over the material's strain
energy ``W(I1)`` (``material.energy_derivatives``) and nothing else, so that the fast
assembly can be checked against it (``tests/fe/test_fe_reference_form.py``: tangent and
residual to 1e-12 on small meshes).

Energy per reference volume (the paper's Eq. (modelE) times ``J``, with the
stress-free-reference term ``-mu0 ln J``, ``mu0 = 2 W'(3)``)::

    psi(F, p, G) = W(I1) + p (J - 1) - eps/2 J G.C^-1 G - mu0 ln J,
    F = I + Grad u,   G = Grad phi,   I1 = F:F,   J = det F.

With ``a = F^-T G`` and ``b = C^-1 G = F^-1 a`` the first derivatives are::

    P   = dpsi/dF = 2 W' F + c F^-T + eps J a (x) b,   c = p J - eps/2 J a.a - mu0
    D_L = dpsi/dG = -eps J b,                           dpsi/dp = J - 1,

and the weak form (internal forces; the loads belong to the model)::

    r_u(v)   = int_V P : Grad v dV
    r_p(q)   = int_V (J - 1) q dV
    r_phi(w) = int_V D_L . Grad w dV.

The tangent is the directional derivative of ``(P, J - 1, D_L)`` along
``(dF, dp, dG) = (Grad du, dp, Grad dphi)``, written term by term in
``ReferenceForm._increments``.  Only the ``"mixed"`` formulation with ``kappa = inf`` and no
grad-div term is written here (the default of the plate models).
"""

from __future__ import annotations

import numpy as np
from skfem import Basis, BilinearForm, ElementHex1, ElementHex2, ElementVector, LinearForm, asm
from skfem.helpers import ddot, det, dot, grad, inv, mul, transpose
from scipy.sparse import bmat

__all__ = ["ReferenceForm"]


def _mv(A, x):
    """Matrix times vector, tensor indices first."""
    return np.einsum("ij...,j...->i...", A, x)


def _outer(x, y):
    return np.einsum("i...,j...->ij...", x, y)


class ReferenceForm:
    """The mixed u-p-phi weak form of an ideal dielectric on a hexahedral mesh.

    Parameters
    ----------
    mesh : skfem.MeshHex
    material
        Any material of :mod:`skfem_dielectric.materials` (``eps`` and
        ``energy_derivatives(I1) -> (W, W', W'')``).
    intorder : int, optional
        Quadrature order (4: 27 Gauss points, as the fast assembly).

    Notes
    -----
    Unknowns in blocks ``[u, p, phi]``: ``u`` in ``ElementVector(ElementHex2)``, ``p`` in
    ``ElementHex1``, ``phi`` in ``ElementHex2`` (Taylor-Hood, potential Q2).
    """

    def __init__(self, mesh, material, intorder: int = 4):
        self.material = material
        self.ub = Basis(mesh, ElementVector(ElementHex2()), intorder=intorder)
        self.pb = Basis(mesh, ElementHex1(), intorder=intorder)
        self.fb = Basis(mesh, ElementHex2(), intorder=intorder)
        self.sizes = (self.ub.N, self.pb.N, self.fb.N)

    # ---------------------------------------------------------------- pointwise law
    def _state(self, w):
        """Everything the integrands need at the quadrature points of the state ``w``."""
        m = self.material
        F = grad(w["u"]) + np.eye(3)[:, :, None, None]
        G = grad(w["phi"])
        J, Finv = det(F), inv(F)
        FinvT = transpose(Finv)
        a = _mv(FinvT, G)                                  # F^-T G
        b = _mv(Finv, a)                                   # C^-1 G
        _, W1, W11 = m.energy_derivatives(ddot(F, F))
        mu0 = 2.0 * float(m.energy_derivatives(np.array(3.0))[1])
        c = w["p"] * J - 0.5 * m.eps * J * dot(a, a) - mu0
        return dict(F=F, G=G, J=J, Finv=Finv, FinvT=FinvT, a=a, b=b, W1=W1, W11=W11, c=c,
                    p=np.asarray(w["p"]), eps=m.eps)

    @staticmethod
    def _stresses(s):
        """``(P, dpsi/dp, D_L)``."""
        P = 2.0 * s["W1"] * s["F"] + s["c"] * s["FinvT"] + s["eps"] * s["J"] * _outer(s["a"],
                                                                                     s["b"])
        return P, s["J"] - 1.0, -s["eps"] * s["J"] * s["b"]

    @staticmethod
    def _increments(s, dF=0.0, dp=0.0, dG=0.0):
        """Directional derivatives ``(dP, dJ, dD_L)`` along ``(dF, dp, dG)``."""
        F, J, Finv, FinvT, a, b, eps = (s[k] for k in ("F", "J", "Finv", "FinvT", "a", "b",
                                                      "eps"))
        dF = np.broadcast_to(dF, F.shape)
        dG = np.broadcast_to(dG, a.shape)
        dJ = J * ddot(FinvT, dF)
        dFinvT = -mul(FinvT, mul(transpose(dF), FinvT))
        dFinv = -mul(Finv, mul(dF, Finv))
        da = _mv(dFinvT, s["G"]) + _mv(FinvT, dG)
        db = _mv(dFinv, a) + _mv(Finv, da)
        dc = dp * J + s["p"] * dJ - 0.5 * eps * (dJ * dot(a, a) + 2.0 * J * dot(a, da))
        dP = (2.0 * s["W1"] * dF + 4.0 * s["W11"] * ddot(F, dF) * F + dc * FinvT
              + s["c"] * dFinvT + eps * (dJ * _outer(a, b) + J * _outer(da, b)
                                         + J * _outer(a, db)))
        return dP, dJ, -eps * (dJ * b + J * db)

    # ---------------------------------------------------------------- assembly
    def fields(self, x):
        """The state ``x`` at the quadrature points.

        Parameters
        ----------
        x : ndarray
            Dofs in blocks ``[u, p, phi]`` of :attr:`sizes`.

        Returns
        -------
        dict of DiscreteField
            ``u``, ``p``, ``phi``: the ``w`` of the integrands.
        """
        nu, npr, _ = self.sizes
        return dict(u=self.ub.interpolate(x[:nu]), p=self.pb.interpolate(x[nu:nu + npr]),
                    phi=self.fb.interpolate(x[nu + npr:]))

    def residual(self, x):
        """Internal forces ``[r_u, r_p, r_phi]`` at ``x``.

        Parameters
        ----------
        x : ndarray
            Dofs in blocks ``[u, p, phi]``.

        Returns
        -------
        ndarray
        """
        w = self.fields(x)

        @LinearForm
        def r_u(v, w):
            return ddot(self._stresses(self._state(w))[0], grad(v))

        @LinearForm
        def r_p(q, w):
            return self._stresses(self._state(w))[1] * q

        @LinearForm
        def r_phi(t, w):
            return dot(self._stresses(self._state(w))[2], grad(t))

        return np.concatenate([asm(r_u, self.ub, **w), asm(r_p, self.pb, **w),
                               asm(r_phi, self.fb, **w)])

    def tangent(self, x):
        """The tangent ``d r / d x`` at ``x``.

        Parameters
        ----------
        x : ndarray
            Dofs in blocks ``[u, p, phi]``.

        Returns
        -------
        scipy.sparse.csr_matrix
            Blocks ``[[K_uu, K_up, K_uf], [K_pu, 0, 0], [K_fu, 0, K_ff]]``.
        """
        w = self.fields(x)
        bases = {"u": self.ub, "p": self.pb, "phi": self.fb}

        def increment(kind, trial):
            if kind == "u":
                return dict(dF=grad(trial))
            if kind == "p":
                return dict(dp=np.asarray(trial))
            return dict(dG=grad(trial))

        def test_part(kind, inc, test):
            dP, dJ, dD = inc
            if kind == "u":
                return ddot(dP, grad(test))
            if kind == "p":
                return dJ * test
            return dot(dD, grad(test))

        blocks = []
        for row in ("u", "p", "phi"):
            line = []
            for col in ("u", "p", "phi"):
                @BilinearForm
                def k(trial, test, w, row=row, col=col):
                    s = self._state(w)
                    return test_part(row, self._increments(s, **increment(col, trial)),
                                     test)
                line.append(asm(k, bases[col], bases[row], **w))
            blocks.append(line)
        return bmat(blocks, format="csr")

    def from_mixed_upphi(self, form) -> np.ndarray:
        """The dof map from a fast form: ``x_reference = x_fast[perm]``.

        Parameters
        ----------
        form : MixedUPPhiForm
            On the same mesh, potential Q2, mixed formulation.

        Returns
        -------
        ndarray of int
            ``perm``, a permutation of the full dofs of ``form``.
        """
        nu, npr, _ = self.sizes
        perm = np.empty(sum(self.sizes), dtype=np.int64)
        ed = form.edofs                                    # element dofs, local u order 3 i + c
        ref = np.concatenate([self.ub.element_dofs, nu + self.pb.element_dofs,
                              nu + npr + self.fb.element_dofs]).T
        perm[ref.ravel()] = ed.ravel()
        return perm

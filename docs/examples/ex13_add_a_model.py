r"""Adding a model: a plane-strain u-phi dielectric in plain scikit-fem forms
=========================================================================

A two-field model written from scratch on the :class:`skfem_dielectric.Problem` contract:
the displacement ``u`` and the electric potential ``phi`` of a compressible ideal
dielectric in plane strain (``lam3 = 1``), cross-section ``x1``-``x2`` with the field
across the thickness ``x2``.  The free energy per reference volume is

.. math::

    \psi(\mathbf F, \nabla\phi) = \frac{\mu}{2}\,(I_1 - 3 - 2\ln J)
        + \frac{\kappa}{2}\,(\ln J)^2
        - \frac{\varepsilon}{2}\, J\, |\mathbf F^{-T}\nabla\phi|^2 ,

(neo-Hookean with a volume penalty ``kappa``, ideal dielectric, ``E_L = -Grad phi``).
Its first variation is the weak form: the nominal stress
``P = d psi/d F`` tested with ``Grad v`` and the Lagrangian displacement
``D_L = d psi/d Grad phi = -eps J C^-1 Grad phi`` tested with ``Grad q``:

.. math::

    \int_A \mathbf P : \nabla\mathbf v + \mathbf D_L \cdot \nabla q \, dA
    + \int_{\rm top} \sigma_F\, q \, dL - s\,\mu \int_{x_1 = L_1/2} v_1 \, dL = 0 ,

with the charge ``sigma_F = D0 sqrt(mu eps)`` on the top face (charge control,
``N.D_L = -sigma_F``) and the dead traction ``s mu`` on the end.  The tangent is its
second variation, written out below.  The model is the quarter
``[0, L1/2] x [0, H/2]``: ``u1 = 0`` on ``x1 = 0``, ``u2 = phi = 0`` on the mid-plane.
The homogeneous state is exact in the discrete space; for ``kappa -> infinity`` it tends
to the incompressible plane-strain loading curve ``s = lam1 - lam1^-3 (1 + D0^2)``,
Eq. (t1t3) with ``lam3 = 1`` (:func:`analytic.biaxial_stress`).
"""

import numpy as np
import skfem as fe
from skfem.helpers import ddot, det, dot, grad, inv, mul, trace, transpose

from skfem_dielectric import (Layout, NewtonSettings, Problem, RampSettings, newton, ramp,
                              stability_analysis)
from skfem_dielectric.fem import DofReduction
from skfem_dielectric.fem.mesh2d import quarter_quad_mesh


def outer(a, b):
    """``a (x) b`` of two vectors at every quadrature point."""
    return np.einsum("i...,j...->ij...", a, b)


@fe.BilinearForm
def tangent_form(du, dphi, v, q, w):
    """Second variation of the energy: d^2 psi[(du, dphi), (v, q)]."""
    H, J, e, a, lnJ, mu, kappa, eps = w.H, w.J, w.e, w.a, w.lnJ, w.mu, w.kappa, w.eps
    dU, dV, dG, dQ = grad(du), grad(v), grad(dphi), grad(q)
    HdU, HdV = mul(H, dU), mul(H, dV)
    mech = (mu * ddot(dV, dU) + (mu - kappa * lnJ) * trace(mul(HdU, HdV))
            + kappa * trace(HdV) * trace(HdU))
    de = mul(transpose(H), dG - mul(transpose(dU), e))     # d(F^-T Grad phi)
    da = mul(H, de) - mul(HdU, a)                          # d(C^-1 Grad phi)
    first = dot(e, mul(dV, a)) - dot(e, e) / 2 * trace(HdV) - dot(a, dQ)
    elec = trace(HdU) * first + (dot(de, mul(dV, a)) + dot(e, mul(dV, da))
                                 - dot(e, de) * trace(HdV) + dot(e, e) / 2 * trace(mul(HdU, HdV))
                                 - dot(da, dQ))
    return mech + eps * J * elec


@fe.LinearForm
def residual_form(v, q, w):
    """First variation of the energy: P : Grad v + D_L . Grad q."""
    H, J, e, a, lnJ, F = w.H, w.J, w.e, w.a, w.lnJ, w.F
    Ht = transpose(H)
    P = (w.mu * (F - Ht) + w.kappa * lnJ * Ht
         + w.eps * J * (outer(e, a) - dot(e, e) / 2 * Ht))
    D_L = -w.eps * J * a
    return ddot(P, grad(v)) + dot(D_L, grad(q))


class PlaneStrainDielectric(Problem):
    """Quarter cross-section of a compressible dielectric plate in plane strain.

    Unknowns ``u`` (vector Q2) and ``phi`` (Q2); load ``(s, D0)``.  ``phi`` is the
    potential block: a stable state has exactly as many negative tangent eigenvalues
    as potential unknowns (:meth:`Problem.stability`).

    Parameters
    ----------
    mu, eps, kappa : float
        Shear modulus, permittivity and volume penalty (``kappa >> mu``: nearly
        incompressible).
    L1, H : float
        Length and thickness of the whole cross-section.
    n1, n2 : int
        Q2 elements along the half-length and the half-thickness.
    """

    load_names = ("s", "D0")

    def __init__(self, mu=1.0, eps=1.0, kappa=100.0, L1=4.0, H=1.0, n1=4, n2=2):
        for name, val in (("mu", mu), ("eps", eps), ("kappa", kappa), ("L1", L1), ("H", H)):
            if not val > 0:
                raise ValueError(f"{name} must be > 0, got {val!r}")
        for name, val in (("n1", n1), ("n2", n2)):
            if int(val) != val or val < 1:
                raise ValueError(f"{name} must be an integer >= 1, got {val!r}")
        self.mu, self.eps, self.kappa, self.L1, self.H = mu, eps, kappa, L1, H
        mesh = quarter_quad_mesh(L1 / 2, H / 2, n1, n2, ("sym_x1", "mid", "end", "top"))
        self.basis = fe.Basis(mesh, fe.ElementVector(fe.ElementQuad2()) * fe.ElementQuad2(),
                              intorder=4)
        # composite dof names: "u^1^1" = u1, "u^2^1" = u2, "u^2" = phi
        fixed = np.concatenate([self.basis.get_dofs("sym_x1").all("u^1^1"),
                                self.basis.get_dofs("mid").all(["u^2^1", "u^2"])])
        self.red = DofReduction(self.basis.N, fixed)
        self.free = self.red.index >= 0
        idx = self.red.index
        blocks = {name: np.sort(idx[d][idx[d] >= 0])
                  for name, d in zip(("u", "phi"), self.basis.split_indices())}
        self._layout = Layout(self.red.n, blocks, multipliers=("phi",))
        # probes: u1 at the end of the mid-plane, u2 at the top of the symmetry line
        X = self.basis.doflocs
        end_u1, top_u2 = (self.basis.get_dofs("end").all("u^1^1"),
                          self.basis.get_dofs("top").all("u^2^1"))
        self._probes = (end_u1[np.argmin(X[1, end_u1])], top_u2[np.argmin(X[0, top_u2])])
        # unit loads: traction mu e1 on the end, charge 1 on the top face
        end = fe.FacetBasis(mesh, self.basis.elem, facets=mesh.boundaries["end"], intorder=4)
        top = fe.FacetBasis(mesh, self.basis.elem, facets=mesh.boundaries["top"], intorder=4)
        self.f_s = fe.LinearForm(lambda v, q, w: mu * v[0]).assemble(end)[self.free]
        self.f_q = fe.LinearForm(lambda v, q, w: q).assemble(top)[self.free]

    @property
    def layout(self):
        return self._layout

    def initial_state(self):
        return np.zeros(self.red.n)

    def _state(self, x):
        """Fields of the state at the quadrature points, passed to the forms as ``w``."""
        uk, phik = self.basis.interpolate(self.red.expand(x))
        F = grad(uk) + np.eye(2)[:, :, None, None]
        H, J = inv(F), det(F)
        e = mul(transpose(H), grad(phik))
        return dict(F=F, H=H, J=J, e=e, a=mul(H, e), lnJ=np.log(J), mu=self.mu,
                    kappa=self.kappa, eps=self.eps)

    def _residual(self, w, load):
        s, D0 = load
        r = residual_form.assemble(self.basis, **w)[self.free]
        return r - s * self.f_s + D0 * np.sqrt(self.mu * self.eps) * self.f_q

    def residual(self, x, load):
        return self._residual(self._state(x), load)

    def assemble(self, x, load):
        w = self._state(x)
        K = tangent_form.assemble(self.basis, **w)[self.free][:, self.free]
        return K.tocsr(), self._residual(w, load)

    def residual_scale(self, load):
        return self.mu * self.L1 * self.H

    def postprocess(self, x, load):
        """Mean stretches ``lam1`` (mid-plane, centre to end) and ``lam2`` (thickness)."""
        xf = self.red.expand(x)
        i_end, i_top = self._probes
        return {"lam1": 1.0 + xf[i_end] / (self.L1 / 2), "lam2": 1.0 + xf[i_top] / (self.H / 2)}


model = PlaneStrainDielectric(kappa=100.0)
s = 0.5
loads = [np.array([s * k / 2, 0.0]) for k in (1, 2)]               # pre-stretch
loads += [np.array([s, D0]) for D0 in np.linspace(0.5, 2.0, 4)]     # then the charge
result = ramp(model, loads, settings=RampSettings(atol=1e-12, rtol=1e-12))
lam1_final = float(result.column("lam1")[-1])                       # (s, D0) = (0.5, 2)
lam2_final = float(result.column("lam2")[-1])
verdict = stability_analysis(model, result.x, loads[-1], k=2)

# one more load by Newton alone, from the last converged state
load_next = np.array([s, 2.25])
sol = newton(lambda x: model.assemble(x, load_next), result.x,
             residual=lambda x: model.residual(x, load_next),
             settings=NewtonSettings(atol=1e-12, rtol=1e-12),
             scale=model.residual_scale(load_next))
lam1_next = model.postprocess(sol.x, load_next)["lam1"]

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    from scipy.optimize import brentq

    from analytic import biaxial_stress

    D0 = np.array([ld[1] for ld in loads[1:]])
    lam_s = brentq(lambda lam1: biaxial_stress(lam1, 1.0, 0.0)[0] - s, 1.0, 3.0)  # D0 = 0
    grid = np.linspace(lam_s, 1.05 * lam1_final, 200)
    t1, _ = biaxial_stress(grid, 1.0, 0.0)          # t1(lam1, lam3 = 1, D0) is linear in D0^2
    t1_D, _ = biaxial_stress(grid, 1.0, 1.0)
    D0_curve = np.sqrt(np.maximum(0.0, (t1 - s) / (t1 - t1_D)))
    fig, ax = plt.subplots(figsize=(4.5, 3.5))
    ax.plot(D0_curve, grid, "k-", label="incompressible, Eq. (t1t3), lam3 = 1")
    ax.plot(D0, result.column("lam1")[1:], "o", mfc="none",
            label=f"u-phi FE, kappa = {model.kappa:g} mu")
    ax.set_xlabel("D0")
    ax.set_ylabel("lam1")
    ax.set_title(f"plane-strain dielectric, s = {s:g}")
    ax.legend(loc="upper left", fontsize="small")
    fig.tight_layout()
    fig.savefig("ex13_add_a_model.png", dpi=120)
    plt.show()

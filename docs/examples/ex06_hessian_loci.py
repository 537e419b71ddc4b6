r"""
Charge control versus voltage control: Hessian criteria and the voltage limit
=============================================================================

A homogeneous state of the plate (in-plane stretches ``lam1``, ``lam3``, charge ``D0``,
all dimensionless with ``mu = eps = 1``) is stable under **charge control** when the
free energy :math:`\omega^*(\lambda_1, \lambda_3, D_0)` has a positive definite Hessian in
the stretches at fixed charge, and under **voltage control** when
:math:`\omega(\lambda_1, \lambda_3, E_0) = \omega^* - D_0 E_0` (with
:math:`E_0 = \lambda_1^{-2}\lambda_3^{-2} D_0`) has one at fixed field (paper Sec. 5,
Eq. 2nd-variation and Eq. equiv). For the neo-Hookean solid the charge-controlled
plate is stable everywhere; the voltage-controlled one is lost where the field is
maximal along a dead-load curve, i.e. where :math:`\det \mathcal{H}^* = 0`.

Along the uni-axial dead-load path (``t3 = 0``, Eq. DEuniax)

.. math::

    \lambda_3^2 = \lambda_1(\lambda_1 - s), \qquad
    D_0 = \sqrt{\lambda_1^4 (\lambda_1 - s)^2 - 1}, \qquad
    E_0 = \frac{D_0}{\lambda_1^2 \lambda_3^2},

we follow both Hessians (:func:`analytic.hessian_omega_star`,
:func:`analytic.hessian_omega`) and locate where the determinant of the voltage-control
block changes sign. It coincides with the maximum of ``E0`` of
:func:`analytic.max_E0`; the equi-biaxial panel shows the same limit as the locus
``D0 = sqrt((lam^6 + 5)/3)`` (:func:`analytic.voltage_limit_D0`).
"""

import numpy as np
from scipy.optimize import brentq

import analytic as an

s = 1.0
lam1 = np.linspace(1.0, 4.0, 1201)
lam3 = an.uniaxial_lam3(lam1, s)
D0 = an.uniaxial_D0(lam1, s)
on = np.isfinite(D0)                       # the path starts where D0 = 0
lam1, lam3, D0 = lam1[on], lam3[on], D0[on]
E0 = D0 / (lam1 * lam3) ** 2


def block_det(H):
    """Determinant of the 2x2 stretch block of a 3x3 Hessian."""
    return H[..., 0, 0] * H[..., 1, 1] - H[..., 0, 1] ** 2


H_charge = an.hessian_omega_star(lam1, lam3, D0)          # fixed D0
H_voltage = an.hessian_omega(lam1, lam3, E0)              # fixed E0
min_eig_charge = np.linalg.eigvalsh(H_charge[:, :2, :2])[:, 0]
det_voltage = block_det(H_voltage)
assert np.all(min_eig_charge > 0)                         # charge control: stable all along


def det_voltage_at(l1):
    l3 = an.uniaxial_lam3(l1, s)
    return block_det(an.hessian_omega(l1, l3, an.uniaxial_D0(l1, s) / (l1 * l3) ** 2))


# voltage control is lost where the determinant changes sign
i = int(np.argmax(det_voltage < 0))
lam1_voltage_limit = brentq(det_voltage_at, lam1[i - 1], lam1[i], xtol=1e-14)
lam1_maxE0, E0_max = an.max_E0(s, loading="uniaxial")
print(f"uni-axial s = {s:g}: voltage control lost at lam1 = {lam1_voltage_limit:.10f}; "
      f"max of E0 at lam1 = {lam1_maxE0:.10f} (E0 = {E0_max:.6f})")

# equi-biaxial: loading curves, the det H* = 0 locus and the maxima of E0
s_values = [0.0, 0.5, 1.0, 2.0]
lam = np.linspace(1.0, 3.0, 600)
equi = {sv: an.equibiaxial_D0(lam, sv) for sv in s_values}
lam_max, E0_max_equi = an.max_E0(np.array(s_values))

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, (ax0, ax1, ax2) = plt.subplots(1, 3, figsize=(14, 4.2))
    for sv, c in zip(s_values, plt.cm.viridis(np.linspace(0, 0.85, len(s_values)))):
        ax0.plot(lam, equi[sv], color=c, label=f"s = {sv:g}")
    ax0.plot(lam, an.voltage_limit_D0(lam), "k--", label=r"$\det\mathcal{H}^*=0$")
    ax0.plot(lam_max, lam_max**4 * E0_max_equi, "k^", label="max of E0")
    ax0.set(xlabel=r"$\lambda$", ylabel=r"$D_0$", title="(a) equi-biaxial: voltage limit",
            xlim=(1, 3), ylim=(0, 8))
    ax0.legend(fontsize=8)

    ax1.plot(lam1, E0, "C0-")
    ax1.axvline(lam1_voltage_limit, color="k", ls=":", lw=1)
    ax1.plot(lam1_maxE0, E0_max, "k^", label="max of E0 (analytic.max_E0)")
    ax1.set(xlabel=r"$\lambda_1$", ylabel=r"$E_0$", title=f"(b) uni-axial, s = {s:g}")
    ax1.legend(fontsize=8, loc="lower right")

    ax2.plot(lam1, min_eig_charge, "C2-", label="charge: smallest eigenvalue of $H^*$")
    ax2.plot(lam1, det_voltage, "C3-", label=r"voltage: $\det$ of the stretch block of $H$")
    ax2.axhline(0.0, color="k", lw=0.8)
    ax2.axvline(lam1_voltage_limit, color="k", ls=":", lw=1, label="voltage limit")
    ax2.set(xlabel=r"$\lambda_1$", title="(c) Hessian criteria along (b)", ylim=(-2, 6))
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig("ex06_hessian_loci.png", dpi=120)
    plt.show()

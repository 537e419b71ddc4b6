r"""
Loading curves of a charge-controlled dielectric plate
======================================================

A plate of an ideal dielectric (neo-Hookean or Gent) is pre-stretched by a dead load
``s`` and then charged: ``D0`` is the Lagrangian charge, ``E0`` the Lagrangian field,
both dimensionless (``mu = eps = 1``).

Equi-biaxial load (paper Eq. loading_gent), for any ``W(I1)`` with ``I1 = 2 lam^2 + lam^-4``:

.. math::

    D_0^2 = 2W'(I_1)\,(\lambda^6 - 1) - \lambda^5 s, \qquad E_0 = \lambda^{-4} D_0 .

Uni-axial dead load (``t3 = 0``; Eqs. uni-axial-loading and DEuniax, neo-Hookean):

.. math::

    \lambda_3^2 = \lambda_1(\lambda_1 - s), \qquad
    D_0 = \sqrt{\lambda_1^4(\lambda_1 - s)^2 - 1} .

Under voltage control the state is lost where ``E0`` is maximal along a fixed-``s``
curve, which is where ``det H* = 0``; for neo-Hookean the locus is
``D0 = sqrt((lam^6 + 5)/3)`` and at ``s = 0`` the maximum is
``E0 = sqrt(3)/2^(4/3)`` at ``lam = 2^(1/3)``. Under charge control the Hessian of
``omega*`` stays positive definite: the charged plate is stable all along.
For Gent (``Jm = 97.2``) curves with ``s`` above about 2.05 have no maximum.
"""

import numpy as np

import analytic as an

gent = an.Gent(Jm=97.2)
s_values = [0.0, 1.0, 2.3, 3.0]
lam = np.linspace(1.0, 5.0, 500)     # covers every maximum of E0 below

# equi-biaxial curves, neo-Hookean and Gent (nan below the mechanical stretch of s)
curves = {
    (name, s): (an.equibiaxial_D0(lam, s, model), an.equibiaxial_E0(lam, s, model))
    for name, model in (("neo-Hookean", None), ("Gent", gent))
    for s in s_values
}

# maxima of E0 (voltage-control limit) and the Gent threshold above which there is none
lam_max, E0_max = an.max_E0(np.array(s_values))
lam_max_gent, E0_max_gent = an.max_E0(np.array(s_values), gent)
s_star = an.no_maximum_threshold(gent)
E0max_s0 = float(E0_max[0])  # literature: sqrt(3)/2^(4/3) = 0.6874
print(f"neo-Hookean s=0: E0max = {E0max_s0:.6f} at lam = {lam_max[0]:.6f}")
print(f"Gent: no maximum of E0 for s > {s_star:.4f}")

# charge control stays stable along the whole s = 1 curve (Hessian criterion)
D0_1 = an.equibiaxial_D0(lam, 1.0)
on = np.isfinite(D0_1)
assert np.all(an.equibiaxial_stability_verdict(lam[on], D0_1[on], control="charge"))

# uni-axial dead load
lam1 = np.linspace(1.0, 6.0, 400)
uni = {s: (an.uniaxial_D0(lam1, s), an.uniaxial_E0(lam1, s)) for s in (0.0, 1.0, 2.0, 3.0)}
lam1_max, E0_max_uni = an.max_E0(np.array([0.0, 1.0, 2.0, 3.0]), loading="uniaxial")

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    for (name, s), (D0, E0) in curves.items():
        style = "-" if name == "neo-Hookean" else "--"
        axes[0].plot(lam, D0, style, label=f"{name}, s={s}")
        axes[1].plot(lam, E0, style)
    axes[0].plot(lam, an.voltage_limit_D0(lam), "k:", label="det H* = 0 (nH)")
    axes[1].plot(lam, an.voltage_limit_E0(lam), "k:")
    axes[1].plot(lam_max, E0_max, "ko", label="max of E0 (nH)")
    axes[1].plot(lam_max_gent, E0_max_gent, "ks", mfc="none", ms=8, label="max of E0 (Gent)")
    for s, (D0, E0) in uni.items():
        axes[2].plot(lam1, E0, label=f"s={s}")
    axes[2].plot(lam1, an.uniaxial_voltage_limit_E0(lam1), "k:", label="det H* = 0")
    axes[2].plot(lam1_max, E0_max_uni, "ko", label="max of E0")
    axes[0].set(xlabel="lam", ylabel="D0", title="equi-biaxial, charge")
    axes[1].set(xlabel="lam", ylabel="E0", title="equi-biaxial, field", ylim=(0, 0.8))
    axes[2].set(xlabel="lam1", ylabel="E0", title="uni-axial dead load (nH)", ylim=(0, 0.8))
    axes[0].set_xlim(1.0, 5.0)
    axes[1].set_xlim(1.0, 5.0)
    axes[0].legend(fontsize=7, ncol=2)
    axes[1].legend(fontsize=7)
    axes[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig("ex01_loading_curves.png", dpi=120)
    plt.show()

"""Membrane model of the Keplinger plate under charge control
==============================================================

A thin incompressible dielectric plate (100 x 50 x 1 mm, neo-Hookean) hangs from
a fixed clamp and carries a weight on a rigid lower clamp, ``s = alpha m g/(mu A)``
with ``alpha = 1`` (``s = 2.993``). Charges sprayed on its faces (``D0 = D_L /
sqrt(mu eps)`` per reference area) make it expand.

The 2D membrane model (:class:`skfem_dielectric.MembranePlate`) keeps
only the in-plane displacement ``(u1, u3)``: with ``F`` the 2x2 in-plane
deformation gradient, exact incompressibility gives the thickness stretch
``lam2 = 1/det F`` and the energy per reference area is

.. math::

    \\psi = H \\left[ W(I_1) + \\frac{\\lambda_2^2 D_L^2}{2\\varepsilon} \\right],
    \\qquad I_1 = \\operatorname{tr}(F^T F) + \\lambda_2^2 .

Far from the clamps the plate follows the homogeneous uni-axial curve of the
paper, Eq. (DEuniax), ``D0 = sqrt(lam1^4 (lam1 - s)^2 - 1)``; near the clamps
the lateral stress ``P33`` turns compressive as the charge grows, the paper's
breakdown indicator (Sec. 6).
"""

import numpy as np

from skfem_dielectric import MembranePlate, NeoHookeanDielectric, keplinger_s, membrane_mesh
from skfem_dielectric.gallery import membrane_ramp

s = keplinger_s(alpha=1.0, g=9.81)  # 2.993
# the 100 x 1 x 50 mm plate, 16 x 8 elements on the quarter; "uniaxial": the clamped plate
plate = MembranePlate(membrane_mesh(100.0, 1.0, 50.0, 16, 8),
                      NeoHookeanDielectric(mu=1.0, eps=1.0), loading="uniaxial")
D0 = np.arange(0.0, 6.01, 1.0)
result = membrane_ramp(plate, s, D0)

lam1 = result.column("lam1")  # stretch at the plate centre
min_P33 = result.column("min_P33")  # min of P33/mu along the centre line
# homogeneous uni-axial loading curve, Eq. (DEuniax), at the FE stretches
D0_homogeneous = np.sqrt(lam1**4 * (lam1 - s) ** 2 - 1)
lam1_final = float(lam1[-1])

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.5))
    # the curve starts at D0 = 0 (lam1 = largest root of lam1^3 - s lam1^2 - 1 = 0), so it
    # is sampled from there: no flat piece where D0^2 < 0
    lam_start = max(r.real for r in np.roots([1.0, -s, 0.0, -1.0]) if abs(r.imag) < 1e-12)
    lam = lam_start + (lam1.max() * 1.01 - lam_start) * np.linspace(0.0, 1.0, 400) ** 2
    ax1.plot(lam, np.sqrt(np.maximum(lam**4 * (lam - s) ** 2 - 1, 0.0)), "k-",
             label="homogeneous, Eq. (DEuniax)")
    ax1.plot(lam1, D0, "^", mfc="none", label="membrane FE, plate centre")
    ax1.set_xlabel(r"$\lambda_1$")
    ax1.set_ylabel(r"$D_0$")
    ax1.legend()
    for st in result.steps:
        line = plate.centre_line(st.x, st.load)
        ax2.plot(line["x1"], line["P33"], label=f"$D_0$ = {st.load[1]:.0f}")
    ax2.axhline(0.0, color="k", lw=0.5)
    ax2.set_xlabel(r"$X_1$ (mm, centre to clamp)")
    ax2.set_ylabel(r"$P_{33}/\mu$ on the centre line")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig("ex04_membrane.png", dpi=120)
    plt.show()

"""Fully coupled 3D finite elements: equi-biaxial and clamped (Keplinger) plates
================================================================================

The 3D u-p-phi model of :mod:`skfem_dielectric.models.plate.problem` discretises an incompressible
ideal-dielectric plate with Taylor-Hood Q2/Q1 hexahedra (displacement ``u`` Q2, pressure
``p`` Q1) and a Q2 electric potential ``phi``; the total energy

.. math::

    \\Pi = \\int_V \\Big[ W(I_1) + p (J - 1) - \\frac{\\varepsilon}{2} J\\,
    \\mathrm{Grad}\\,\\phi \\cdot C^{-1} \\mathrm{Grad}\\,\\phi \\Big] dV
    - \\int t_A \\cdot u \\, dA + \\int \\sigma_F \\phi \\, dA

is stationary (min over ``u``, max over ``phi``) with ``sigma_F`` the sprayed charge per
reference area (``D0 = sigma_F / sqrt(mu eps)``).

1. Equi-biaxial dead load ``s = 1.5``: the state is homogeneous, so a single element
   reproduces the paper's loading curve Eq. (loading_gent),
   ``D0 = sqrt(lam^6 - 1 - lam^5 s)``, to round-off.
2. The Keplinger plate (100 x 1 x 50 mm, weight ``s = 2.993`` on a rigid clamp, eighth
   model): its centre follows the uni-axial curve Eq. (DEuniax) while the lateral stress
   ``P33`` near the clamp turns compressive under charge (the paper's Fig. zs22).
"""

import numpy as np

from skfem_dielectric import equibiaxial_plate, keplinger_plate

# --- 1. equi-biaxial plate, one Q2 element (eighth model) -------------------------
s = 1.5
D0 = np.arange(1.0, 6.01, 1.0)
equi = equibiaxial_plate(s, D0, linear_solver="superlu")
charge = [st for st in equi.steps if st["phase"] == "charge"]
lam = np.array([st["lam1"] for st in charge])
D0_closed_form = np.sqrt(lam**6 - 1 - lam**5 * s)          # Eq. (loading_gent)
lam_final = float(lam[-1])                                  # stretch at D0 = 6
max_error = float(np.abs(D0_closed_form - D0).max())

# --- 2. clamped Keplinger plate, coarse mesh ------------------------------------------
kep = keplinger_plate(1.0, D0=[1, 2, 3, 4], elements=(6, 1, 3), linear_solver="superlu")
s_kep = kep.steps[-1]["s"]
# the pre-load steps carry part of the weight (s < s_kep): they lie on other curves, so
# only the fully loaded state (the last pre-load step, D0 = 0) and the charge steps are drawn
on_curve = [st for st in kep.steps if np.isclose(st.load[0], s_kep)]
lam1 = np.array([st["lam1"] for st in on_curve])
D0_kep = np.array([st.load[1] for st in on_curve])
lam1_final = float(lam1[-1])

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    # each curve from its D0 = 0 stretch (largest real root), denser near the vertical start
    def start(coeffs):
        return max(r.real for r in np.roots(coeffs) if abs(r.imag) < 1e-12)

    u = np.linspace(0.0, 1.0, 300) ** 2
    L = start([1, -s, 0, 0, 0, 0, -1]) + (2.3 - start([1, -s, 0, 0, 0, 0, -1])) * u
    ax1.plot(L, np.sqrt(np.maximum(L**6 - 1 - L**5 * s, 0)), "k-",
             label="Eq. (loading_gent), s = 1.5")
    ax1.plot(lam, D0, "o", mfc="none", label="FE equi-biaxial (1 element)")
    L1 = start([1, -s_kep, 0, -1]) + (3.4 - start([1, -s_kep, 0, -1])) * u
    ax1.plot(L1, np.sqrt(np.maximum(L1**4 * (L1 - s_kep) ** 2 - 1, 0)), "b-",
             label=f"Eq. (DEuniax), s = {s_kep:.3f}")
    ax1.plot(lam1, D0_kep, "bs", mfc="none", label="FE Keplinger plate, centre")
    ax1.set_xlabel("stretch")
    ax1.set_ylabel("D0")
    ax1.legend()
    for st in on_curve:
        c = st["centre_line"]
        ax2.plot(c["x1"] / 10.0, c["P33"], label=f"D0 = {st.load[1]:g}")
    ax2.axhline(0.0, color="k", lw=0.5)
    ax2.set_xlabel("x1 [cm] (centre -> clamp)")
    ax2.set_ylabel("P33 / mu on the centre line")
    ax2.legend()
    fig.tight_layout()
    fig.savefig("ex03_fe_plate.png", dpi=120)
    plt.show()
    print(f"equi-biaxial: max |D0_FE - D0_closed_form| = {max_error:.2e}; "
          f"Keplinger centre lam1(D0=4) = {lam1_final:.5f}")

r"""
Maxwell-traction coupling versus the fully coupled model on a homogeneous plate
===============================================================================

Two ways to put the electric field into a finite-element model of a dielectric plate:

* **fully coupled** (``PlateProblem(coupling="full")``): the total energy of the ideal
  dielectric :math:`W(I_1) - \frac{\varepsilon}{2} J\, \mathrm{Grad}\,\phi \cdot C^{-1}
  \mathrm{Grad}\,\phi` is stationary in the displacement, pressure and potential;
* **Maxwell traction** (``PlateProblem(coupling="maxwell")``): a purely elastic plate
  loaded on its deformed boundary by the jump of the Maxwell stress,
  :math:`t_0 = -\tau_m \,\mathrm{cof}(F) N` with
  :math:`\tau_m = (E \otimes D) - \frac{1}{2}(E\cdot D) I`, the field solved on the
  deformed body (``field="electrostatic"``) or taken as the charge over the local area
  stretch (``field="local"``).

For a homogeneous equi-biaxial state with dead load ``s`` both must give the loading
curve of the paper, Eq. (loading_gent), for the neo-Hookean solid
:math:`\lambda^6 - s\lambda^5 - 1 - D_0^2 = 0`. The faces' Maxwell pressure alone gives
only half of the electric term; the outward pull on the lateral faces supplies the
other half. One element of the eighth model suffices (the state is homogeneous).
"""

import numpy as np

from skfem_dielectric import equibiaxial_plate
from skfem_dielectric.gallery import maxwell_equibiaxial

s = 1.5
D0 = np.arange(1.0, 6.01, 1.0)
runs = {
    "fully coupled": equibiaxial_plate(s, D0),
    "Maxwell, electrostatic field": maxwell_equibiaxial(s, D0, field="electrostatic"),
    "Maxwell, local field": maxwell_equibiaxial(s, D0, field="local"),
}
lam = {name: np.array([st["lam1"] for st in r.steps if st["phase"] == "charge"])
       for name, r in runs.items()}
lam_maxwell_final = float(lam["Maxwell, electrostatic field"][-1])   # (s, D0) = (1.5, 6)
gap = max(float(np.max(np.abs(lam[name] - lam["fully coupled"]))) for name in lam)
print("lam at D0 = 6: " + ", ".join(f"{k}: {v[-1]:.12f}" for k, v in lam.items()))
print(f"largest |lam_maxwell - lam_coupled| over the ramp: {gap:.1e}")

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10.5, 4))
    lam_start = max(r.real for r in np.roots([1, -s, 0, 0, 0, 0, -1]) if abs(r.imag) < 1e-12)
    L = lam_start + (2.3 - lam_start) * np.linspace(0.0, 1.0, 300) ** 2
    ax1.plot(L, np.sqrt(np.maximum(L**6 - 1 - s * L**5, 0.0)), "k-",
             label=f"Eq. (loading_gent), s = {s:g}")
    styles = {"fully coupled": dict(marker="o", ms=9),
              "Maxwell, electrostatic field": dict(marker="s", ms=6),
              "Maxwell, local field": dict(marker="x", ms=6, mew=1.5)}
    for name, st in styles.items():
        ax1.plot(lam[name], D0, ls="none", mfc="none", label=name, **st)
    ax1.set(xlabel=r"$\lambda$", ylabel=r"$D_0$", title="(a) loading curve")
    ax1.legend(fontsize=8, loc="upper left")
    for name, st in styles.items():
        D0_fe = np.sqrt(lam[name] ** 6 - 1 - s * lam[name] ** 5)
        ax2.semilogy(D0, np.abs(D0_fe - D0) + 1e-16, ls="-", mfc="none", label=name, **st)
    ax2.set(xlabel=r"$D_0$", ylabel=r"$|D_0(\lambda_{FE}) - D_0|$",
            title="(b) distance to the closed form (round-off level)")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig("ex09_maxwell_vs_coupled.png", dpi=120)
    plt.show()

r"""
The Keplinger plate: lateral stress along the centre line as the charge grows
=============================================================================

The plate of Keplinger et al. (100 x 1 x 50 mm, neo-Hookean, ``mu = 9833.07 Pa``) hangs
from a fixed clamp and carries a weight of 150 g on a rigid lower clamp, so the nominal
load is ``s = alpha m g / (mu A)`` (``A`` = 50 mm^2, ``g = 9.81`` m/s^2; ``alpha = 1``
gives ``s = 2.993``). Charge ``D0 = D_L / sqrt(mu eps)`` per reference area is then
sprayed on its faces (paper Sec. 6, Figs. uni-axial-ideal and zs22).

The 3D fully coupled u-p-phi model (Taylor-Hood Q2/Q1, potential Q2; one eighth of
the plate by symmetry, a coarse 8 x 1 x 4 mesh here) is ramped through the weight and
then the charge. Far from the clamps the plate is in the homogeneous uni-axial state
of Eq. (DEuniax),

.. math::

    D_0 = \sqrt{\lambda_1^4 (\lambda_1 - s)^2 - 1}, \qquad P_{33} = 0 ,

while the clamps hold ``lam3 = 1``. Along the centre line ``x3 = 0`` (mid-thickness,
from the centre to the clamp) the lateral second Piola-Kirchhoff stress ``P33/mu``
starts tensile near the clamp and turns compressive as ``D0`` grows: the paper's
indicator of the breakdown of the actuator (wrinkles near the clamps). On this coarse
mesh the centre-line minimum sits in the element next to the clamp; the validation
harness judges the breakdown two thicknesses away from the clamps, on finer meshes
(``skfem-dielectric validate``).
"""

import numpy as np

from skfem_dielectric import keplinger_plate, keplinger_s

s = keplinger_s(1.0, g=9.81)
D0_targets = [1.0, 2.0, 3.0, 4.0, 5.0]
kep = keplinger_plate(1.0, D0=D0_targets, elements=(8, 1, 4))
loaded = [st for st in kep.steps if np.isclose(st.load[0], s)]   # full weight, D0 >= 0
D0 = np.array([st.load[1] for st in loaded])
lam1 = np.array([st["lam1"] for st in loaded])           # stretch at the plate centre
min_P33 = np.array([st["min_P33"] for st in loaded])     # min of P33/mu on the centre line
lam1_D0_5 = float(lam1[-1])
# first charge where the centre line is compressive
D0_compressive = float(D0[np.argmax(min_P33 < -0.01)]) if np.any(min_P33 < -0.01) else None
print(f"s = {s:.4f}; lam1 at the centre for D0 = 0..5: {np.round(lam1, 5)}")
print(f"min P33/mu on the centre line: {np.round(min_P33, 4)}; compressive from "
      f"D0 = {D0_compressive}")

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    lam_start = max(r.real for r in np.roots([1.0, -s, 0.0, -1.0]) if abs(r.imag) < 1e-12)
    L = lam_start + (3.5 - lam_start) * np.linspace(0.0, 1.0, 300) ** 2
    ax1.plot(L, np.sqrt(np.maximum(L**4 * (L - s) ** 2 - 1.0, 0.0)), "k-",
             label=f"Eq. (DEuniax), s = {s:.3f}")
    ax1.plot(lam1, D0, "o", mfc="none", ms=7, label="FE 3D fully coupled, plate centre")
    ax1.set(xlabel=r"$\lambda_1$", ylabel=r"$D_0$", title="(a) stretch at the centre")
    ax1.legend(fontsize=8, loc="upper left")

    cmap = plt.get_cmap("plasma")
    for st, c in zip(loaded, cmap(np.linspace(0.0, 0.85, len(loaded)))):
        line = st["centre_line"]
        ax2.plot(line["x1"] / 10.0, line["P33"], "-", color=c, marker=".",
                 label=f"$D_0$ = {st.load[1]:g}")
    ax2.axhline(0.0, color="k", lw=0.8)
    ax2.set(xlabel=r"$X_1$ (cm, reference, centre $\to$ clamp)", ylabel=r"$P_{33}/\mu$",
            title="(b) lateral stress on the centre line", ylim=(-2.0, 1.5))
    ax2.legend(fontsize=8, loc="lower left", ncol=2)
    fig.tight_layout()
    fig.savefig("ex08_keplinger_p33.png", dpi=120)
    plt.show()

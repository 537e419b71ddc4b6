"""A new model on the problem contract: a Mooney-Rivlin dielectric plate
=======================================================================

Every FE model of ``skfem_dielectric`` is a :class:`skfem_dielectric.Problem`: it says
how many unknowns it has (``layout``), where it starts (``initial_state``) and returns
its tangent and residual (``assemble``).  The Newton solver, the load ramp with
cut-back and resume, the stability verdict and the export then work on it unchanged.

Here the new model is a homogeneous plate of a Mooney-Rivlin-like ideal dielectric,
``W(I1, I2) = c1 (I1 - 3) + c2 (I2 - 3)`` with ``2 (c1 + c2) = mu = 1``, under an
equi-biaxial dead load ``s`` and charge control ``D0`` (dimensionless, ``eps = 1``).
With ``lam1 = lam3 = lam`` and ``lam2 = lam^-2`` the energy per reference volume is

.. math::

    \\Pi(\\lambda) = c_1 (2\\lambda^2 + \\lambda^{-4} - 3)
                   + c_2 (\\lambda^4 + 2\\lambda^{-2} - 3)
                   + \\frac{D_0^2}{2} \\lambda^{-4} - 2 s (\\lambda - 1),

whose stationarity ``r = dPi/dlam = 0`` is the loading curve.  For ``c2 = 0`` it is the
paper's Eq. (loading_gent) for the neo-Hookean solid, ``s = lam - lam^-5 (1 + D0^2)``.
The model has one unknown, ``x = lam - 1``; it is the smallest possible model, but it
plugs into the same contract as the 3D plate.
"""

import numpy as np
import scipy.sparse as sp

from skfem_dielectric import Layout, Problem, RampSettings, ramp


class MooneyRivlinPlate(Problem):
    """Homogeneous equi-biaxial Mooney-Rivlin dielectric plate, unknown ``lam - 1``."""

    load_names = ("s", "D0")
    layout = Layout.single(1, "lam")

    def __init__(self, c2: float = 0.1):
        if not 0.0 <= c2 < 0.5:
            raise ValueError(f"c2 must be in [0, 0.5) (so that c1 = 1/2 - c2 > 0), got {c2!r}")
        self.c1, self.c2 = 0.5 - c2, c2

    def initial_state(self):
        return np.zeros(1)

    def assemble(self, x, load):
        s, D0 = load
        lam = 1.0 + x[0]
        c1, c2 = self.c1, self.c2
        r = (c1 * (4 * lam - 4 * lam**-5) + c2 * (4 * lam**3 - 4 * lam**-3)
             - 2 * D0**2 * lam**-5 - 2 * s)
        k = c1 * (4 + 20 * lam**-6) + c2 * (12 * lam**2 + 12 * lam**-4) + 10 * D0**2 * lam**-6
        return sp.csr_matrix([[k]]), np.array([r])

    def residual_scale(self, load):
        return 1.0

    def load_vector(self, x, load, h=1e-6):
        lam = 1.0 + x[0]
        return np.array([[-2.0, -4.0 * load[1] * lam**-5]])

    def postprocess(self, x, load):
        return {"lam": 1.0 + x[0]}


plate = MooneyRivlinPlate(c2=0.1)
s = 1.0
loads = [np.array([s * k / 4, 0.0]) for k in range(1, 5)]      # pre-load in 4 steps
loads += [np.array([s, D0]) for D0 in np.arange(0.5, 4.01, 0.5)]  # then the charge
result = ramp(plate, loads, settings=RampSettings(atol=1e-13, rtol=0.0))
lam = result.column("lam")
lam_final = float(lam[-1])          # (s, D0) = (1, 4)
# the contract's default load vector (central differences) equals the closed form here
dr_dload = plate.load_vector(result.x, loads[-1])
dr_dload_fd = Problem.load_vector(plate, result.x, loads[-1])

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    D0 = np.array([ld[1] for ld in loads])
    fig, ax = plt.subplots(figsize=(4.5, 3.5))
    grid = np.linspace(1.0, lam.max() * 1.05, 200)
    c1, c2 = plate.c1, plate.c2
    # the loading curve solved for D0 (no FE): the same equation written for D0(lam)
    D0_curve = np.sqrt(np.maximum(0.0, (c1 * (4 * grid - 4 * grid**-5)
                                        + c2 * (4 * grid**3 - 4 * grid**-3) - 2 * s)
                                  * grid**5 / 2))
    ax.plot(D0_curve, grid, "k-", label="loading curve, c2 = 0.1")
    ax.plot(D0[4:], lam[4:], "o", mfc="none", label="ramp (Problem contract)")
    ax.set_xlabel("D0")
    ax.set_ylabel("lam")
    ax.set_title(f"Mooney-Rivlin plate, s = {s:g}")
    ax.legend()
    fig.tight_layout()
    fig.savefig("ex05_new_model.png", dpi=120)
    plt.show()

r"""
Snap-through under voltage control, none under charge control
==============================================================

The paper's central contrast, computed by finite elements.  A homogeneous neo-Hookean
plate without dead load (``s = 0``, dimensionless ``mu = eps = 1``) stretched
equi-biaxially by ``lam`` follows the loading curve (Eq. loading_gent)

.. math::

    D_0^2 = \lambda^6 - 1, \qquad E_0 = \lambda^{-4} D_0 .

The field ``E0`` (the voltage) has a maximum, :math:`E_0 = \sqrt{3}/2^{4/3}` at
:math:`\lambda = 2^{1/3}`, where :math:`\det \mathcal{H}^* = 0` (Sec. 3.1): a voltage
ramp cannot go beyond it and snaps through.  The charge ``D0`` grows monotonically
along the whole curve, and under charge control every state is stable.

A voltage ramp (:func:`skfem_dielectric.solvers.ramp.ramp`) stops at the maximum.  Pseudo-arclength
continuation (:func:`skfem_dielectric.solvers.continuation.continuation`, used by
:func:`skfem_dielectric.studies.voltage_snap_through`) makes ``E0`` an unknown and passes it:
the path turns back in ``E0`` while ``lam`` keeps growing.  At every state the number
of negative eigenvalues of the reduced stiffness is counted twice
(:func:`skfem_dielectric.stability.tangent_stability`): with the potential prescribed on
the faces (voltage control) and, for the *same* state, with the charge prescribed.  The first
jumps from zero at the limit point; the second stays zero.
"""

import math
from dataclasses import replace

import numpy as np

import skfem_dielectric as fe

coarse = replace(fe.studies.SNAP_THROUGH_SETTINGS, ds=0.1)     # arclength step 0.1
st = fe.studies.voltage_snap_through(0.0, loading="equibiaxial", lam_factor=1.6,
                                     settings=coarse)
path = st.path
lam = path.column("lam1")
E0 = path.column("t")
n_voltage = np.array(st.n_negative_voltage)
n_charge = np.array(st.n_negative_charge)
E0max_fe, lam_max_fe = st.E0_max, st.lam1_max
k = path.points.index(st.limit)

assert np.all(n_voltage[:k] == 0) and np.all(n_voltage[k + 1:] > 0)
assert np.all(n_charge == 0)

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    lam_c = np.linspace(1.0, lam.max(), 300)
    ax1.plot(lam_c, np.sqrt(lam_c ** 6 - 1) / lam_c ** 4, "k-", lw=1,
             label="Eq. (loading_gent), s = 0")
    stable = n_voltage == 0
    ax1.plot(lam[stable], E0[stable], "o", color="C0", label="FE, stable under voltage")
    ax1.plot(lam[~stable], E0[~stable], "o", mfc="none", color="C3",
             label="FE, unstable under voltage")
    ax1.plot(lam_max_fe, E0max_fe, "*", ms=14, color="gold", mec="k",
             label=f"limit point E0 = {E0max_fe:.6f}")
    ax1.axhline(math.sqrt(3) / 2 ** (4 / 3), color="grey", ls=":", lw=1)
    ax1.set_xlabel("lam")
    ax1.set_ylabel("E0 (voltage)")
    ax1.legend(fontsize=8)
    arc = path.column("arclength")
    # each count is that of a computed state (markers), held until the next one
    ax2.plot(arc, n_voltage, "o-", drawstyle="steps-pre", color="C3",
             label="voltage control")
    ax2.plot(arc, n_charge, "s--", drawstyle="steps-pre", color="C0", mfc="none",
             label="charge control, the same states")
    ax2.axvline(arc[k], color="gold", lw=2, label="limit point")
    ax2.set_xlabel("arclength along the path")
    ax2.set_ylabel("negative eigenvalues of the reduced stiffness")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig("ex10_snap_through.png", dpi=120)
    plt.show()
    print(f"limit point: E0 = {E0max_fe:.12f} (sqrt(3)/2^(4/3) = "
          f"{math.sqrt(3) / 2 ** (4 / 3):.12f}), lam = {lam_max_fe:.10f}")

"""The isochoric nearly incompressible energy ``W(J^(-2/3) I1) + kappa (J-1)^2/2`` on the 3D
plate against its own homogeneous equi-biaxial state.

Reference: the stationarity of the energy per reference volume of a homogeneous plate
``F = diag(lam1, lam2, lam3)`` under the dead lateral traction ``s`` (units of mu) and the
charge ``D0`` per reference area,

    Pi = W(Ib1) + kappa/2 (J - 1)^2 + D0^2 lam2^2 / (2 J) - s (lam1 + lam3),
    Ib1 = J^(-2/3) (lam1^2 + lam2^2 + lam3^2),   J = lam1 lam2 lam3

(the charge-controlled Legendre transform ``D_L.C D_L / (2 eps J)`` of the paper's
Eq. (modelE), ``mu = eps = 1``), written out by hand here and solved with scipy: it shares
no code with the FE material law.
"""

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq, root

from skfem_dielectric.gallery import EQUIBIAXIAL_SETTINGS, PlateOptions, equibiaxial_plate

JM = 97.2


def dW(Ib, model):
    """``W'(I)`` of neo-Hookean ``(I - 3)/2`` and Gent ``-Jm/2 ln(1 - (I - 3)/Jm)``."""
    return 0.5 if model == "neo-Hookean" else 0.5 / (1.0 - (Ib - 3.0) / JM)


def stationarity(lam, s, D0, kappa, model):
    """``dPi/dlam_i`` of the homogeneous state (module docstring)."""
    lam = np.asarray(lam, dtype=float)
    J = lam.prod()
    I1 = (lam * lam).sum()
    j23 = J ** (-2.0 / 3.0)
    dIb = j23 * (2.0 * lam - (2.0 / 3.0) * I1 / lam)
    f = D0**2 * lam[1] / (2.0 * lam[0] * lam[2])          # D0^2 lam2^2 / (2 J)
    d_el = np.array([-f / lam[0], f / lam[1], -f / lam[2]])
    return (dW(j23 * I1, model) * dIb + kappa * (J - 1.0) * J / lam + d_el
            - s * np.array([1.0, 0.0, 1.0]))


def incompressible_lam(s, D0, model):
    """Equi-biaxial stretch of the incompressible plate, Eq. (loading_gent)."""
    if model == "neo-Hookean":
        f = lambda L: L**6 - 1 - L**5 * s - D0**2
    else:
        f = lambda L: (L**6 - 1) / (1 - (2 * L**2 + L**-4 - 3) / JM) - L**5 * s - D0**2
    return brentq(f, 1.0, 5.0, xtol=1e-15, rtol=1e-15)


def isochoric_state(s, D0, kappa, model):
    """``(lam1, lam2, lam3)`` of the compressible homogeneous state, from the
    incompressible one as the initial guess."""
    lam0 = incompressible_lam(s, D0, model)
    sol = root(stationarity, [lam0, lam0**-2, lam0], args=(s, D0, kappa, model),
               method="hybr", tol=1e-15)
    # (hybr reports that 1e-15 cannot be improved on; what counts is the residual:) the
    # residual of the hand-written equations is at round-off (kappa J^2 ~ 1e2)
    assert np.abs(stationarity(sol.x, s, D0, kappa, model)).max() < 1e-11
    return sol.x


@pytest.mark.parametrize("model,formulation", [("neo-Hookean", "isochoric"),
                                               ("Gent", "isochoric"),
                                               ("neo-Hookean", "mixed-isochoric")])
def test_isochoric_equibiaxial_matches_its_closed_form(model, formulation):
    # the mixed form's p (J - 1) - p^2/(2 kappa) is stationary in p at p = kappa (J - 1),
    # where it equals kappa (J - 1)^2 / 2: both formulations have the same state
    s, kappa, D0 = 1.5, 100.0, [1.0, 3.0]
    res = equibiaxial_plate(s, D0, model=model,
                            options=PlateOptions(formulation=formulation, kappa=kappa),
                            preload_steps=4, linear_solver="superlu",
                            settings=replace(EQUIBIAXIAL_SETTINGS, rtol=1e-12))
    assert res.converged, res.reason
    for st in res.steps[-2:]:
        ref = isochoric_state(st.load[0], st.load[1], kappa, model)
        got = np.array([st["lam1"], st["lam2"], st["lam3"]])
        # the homogeneous state lies in the Q2 space of the one-element model, so the FE
        # state is exact up to the Newton tolerance (rtol 1e-12 on the residual): 1e-10
        assert np.abs(got / ref - 1).max() < 1e-10
        # and it is not the incompressible state: the compressibility at kappa = 100 mu
        # moves the stretch by O(mu/kappa), far above the tolerance above
        lam_inc = incompressible_lam(st.load[0], st.load[1], model)
        assert abs(st["lam1"] / lam_inc - 1) > 1e-4


def test_isochoric_needs_a_finite_kappa():
    with pytest.raises(ValueError, match="kappa"):
        equibiaxial_plate(1.0, [1.0], options=PlateOptions(formulation="isochoric", kappa=math.inf))

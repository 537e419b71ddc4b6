r"""
Check another code: a compressible plate, its energy minimised with scipy
=========================================================================

``skfem-dielectric check`` scores results written by *another* code against the closed
forms of the paper (docs/check.md).  The "other code" here is twenty lines of scipy that
reach the homogeneous equi-biaxial plate of Fig. nh-d-e by a different route from
Eq. (loading_gent): a **compressible** neo-Hookean dielectric with bulk modulus
:math:`\kappa`, whose energy per reference volume

.. math::

   \Pi(\lambda, \lambda_2) = \frac{\mu}{2}\left(J^{-2/3} I_1 - 3\right)
   + \frac{\kappa}{2}(J - 1)^2 + \frac{D_0^2 \lambda_2}{2 \lambda^2}
   - 2 s (\lambda - 1), \qquad J = \lambda^2 \lambda_2,\; I_1 = 2\lambda^2 + \lambda_2^2

(charge form :math:`D_L \cdot C D_L / (2 \varepsilon J)` with :math:`D_L = D_0 e_2`, dead
load :math:`s` on both lateral faces) is minimised directly with ``scipy.optimize``
(BFGS in the log-stretches, warm-started along the charge ramp).  The penalty
:math:`\kappa` replaces the constraint :math:`J = 1`, so the stretches carry a penalty
error of order :math:`\mu/\kappa` -- the code's own error, which it estimates itself by
solving again with :math:`2\kappa` (Richardson: the error of the first solution is twice
the difference).  With :math:`\kappa = 10^5 \mu` the estimate is :math:`4 \cdot 10^{-5}`,
so the code's results are checked with ``--tol lam1=1e-4``: 2.5 times its own estimate,
room for the :math:`O(\kappa^{-2})` remainder.  With the default tolerance ``1e-6`` of a
homogeneous state the same file fails, as it should: the penalty error is real.

The script writes ``ex14_external_nh-d-e.csv`` (20 rows; a copy is committed beside it)
and checks it with :func:`validation.check`; the figure shows its dots on our curves.
"""

import csv

import numpy as np
from scipy.optimize import minimize

import validation

KAPPA = 1e5                  # bulk modulus over mu: the penalty on J = 1
S_VALUES = (0.0, 1.0, 2.0, 3.0)
D0_VALUES = (0.0, 1.5, 3.0, 4.5, 6.0)
CSV = "ex14_external_nh-d-e.csv"


def energy(x, D0, s, kappa):
    """Pi and its gradient in the log-stretches x = (ln lam, ln lam2)."""
    lam, lam2 = np.exp(x)
    J1 = np.expm1(2 * x[0] + x[1])                     # J - 1, accurate near J = 1
    J = 1.0 + J1
    I1 = 2 * lam**2 + lam2**2
    c = J ** (-2 / 3)
    Pi = (0.5 * (c * I1 - 3) + 0.5 * kappa * J1**2 + 0.5 * D0**2 * lam2 / lam**2
          - 2 * s * (lam - 1))
    dlam = (c * (2 * lam - 2 * I1 / (3 * lam)) + 2 * kappa * J1 * J / lam
            - D0**2 * lam2 / lam**3 - 2 * s)
    dlam2 = c * (lam2 - I1 / (3 * lam2)) + kappa * J1 * J / lam2 + 0.5 * D0**2 / lam**2
    return Pi, np.array([lam * dlam, lam2 * dlam2])


def solve(kappa):
    """``{(s, D0): (lam, lam2)}``: the minimiser of Pi along each charge ramp."""
    out = {}
    for s in S_VALUES:
        x = np.zeros(2)
        for D0 in D0_VALUES:
            r = minimize(energy, x, args=(D0, s, kappa), jac=True, method="BFGS",
                         options={"gtol": 1e-10})
            # BFGS ends when Pi stops decreasing in double precision; judge the state by
            # its gradient instead (an error of ~1e-9 in lam at most)
            assert np.abs(r.jac).max() < 1e-6, (s, D0, r.message)
            x = r.x
            out[s, D0] = tuple(np.exp(x))
    return out


states, states_2k = solve(KAPPA), solve(2 * KAPPA)
penalty_error = max(2 * abs(states[k][0] / states_2k[k][0] - 1) for k in states)
TOL = 1e-4
assert penalty_error < TOL / 2

with open(CSV, "w", newline="") as fh:
    fh.write("# a compressible neo-Hookean plate (kappa = 1e5 mu), energy minimised with "
             "scipy BFGS\n")
    fh.write(f"# penalty error estimate (Richardson in 1/kappa): {penalty_error:.1e}\n")
    w = csv.writer(fh, lineterminator="\n")
    w.writerow(["case", "model", "s", "D0", "lam1", "lam3", "J"])
    for (s, D0), (lam, lam2) in states.items():
        w.writerow(["nh-d-e", "neo-Hookean", f"{s:g}", f"{D0:g}", f"{lam:.10g}",
                    f"{lam:.10g}", f"{lam * lam * lam2:.10g}"])

result = validation.check(CSV, tol={"lam1": TOL})
strict = validation.check(CSV)                   # the default tolerance of a homogeneous state
lam_s3_D06 = states[3.0, 6.0][0]                # pinned by tests/docs/test_examples.py
print(f"own penalty error estimate {penalty_error:.2e}; check with lam1 <= {TOL:g}:")
print(result.table())
print(f"with the default tolerance: {'pass' if strict.passed else 'fail'} "
      f"({strict.worst.error:.2e} > {strict.worst.tol:g})")

if __name__ == "__main__":
    from validation.check_report import check_figure

    fig = check_figure(result["nh-d-e"])
    fig.savefig("ex14_check_external_code.png", dpi=90)

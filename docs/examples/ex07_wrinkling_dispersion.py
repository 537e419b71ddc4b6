r"""
Wrinkling of a plate of finite thickness: critical charge versus wavenumber
===========================================================================

A plate stretched equi-biaxially to ``lam`` carries the charge ``D0``. A small wrinkle
of wavenumber ``k`` (deformed thickness ``h``) is possible when the exact dispersion
relation of the plate has a root (Stroh formalism, paper Sec. 4, with the corrected
Eq. con-eqns); :func:`analytic.critical_D0` returns the smallest such ``D0`` for the
flexural (antisymmetric) and the extensional (symmetric) modes. Its two ends are the
paper's closed forms:

* thin plate, ``kh -> 0`` (Eq. antisym_thin): the ``s = 0`` loading curve
  :math:`D_0^2 = \lambda^6 - 1` (neo-Hookean);
* thick plate, ``kh -> inf`` (Eqs. short-wave, ideal-shortwave), neo-Hookean:

.. math::

    D_0^4 - (\lambda^6 + 3\lambda^3 - 2)\, D_0^2 - (\lambda^9 + \lambda^6 + 3\lambda^3 - 1) = 0 .

Under charge control a pre-stretched plate (``s > 0``) lies below the thin limit, hence
below every finite-thickness curve: it does not wrinkle (example 2).
"""

import numpy as np

import analytic as an

kh = np.geomspace(0.02, 50.0, 120)
lams = [1.5, 2.0, 3.0]
antisym = {lam: an.critical_D0(lam, kh, mode="antisymmetric") for lam in lams}
sym = {lam: an.critical_D0(lam, kh, mode="symmetric") for lam in lams}
thin = {lam: an.thin_limit_D0(lam) for lam in lams}
thick = {lam: an.thick_limit_D0(lam) for lam in lams}

D0_thick_side = float(an.critical_D0(2.0, 50.0))        # lam = 2, kh = 50: thick limit
D0_thin_side = float(an.critical_D0(2.0, 0.02))         # lam = 2, kh = 0.02: thin limit
print(f"lam = 2: critical D0 = {D0_thin_side:.6f} at kh = 0.02 (thin limit "
      f"{thin[2.0]:.6f}), {D0_thick_side:.10f} at kh = 50 (thick limit {thick[2.0]:.10f})")

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for lam, c in zip(lams, ("tab:blue", "tab:orange", "tab:green")):
        ax.plot(kh, antisym[lam], "-", color=c, label=f"flexural, $\\lambda$ = {lam:g}")
        ax.plot(kh, sym[lam], "--", color=c, label=f"extensional, $\\lambda$ = {lam:g}")
        ax.axhline(thin[lam], color=c, lw=0.8, ls=":")
        ax.axhline(thick[lam], color=c, lw=0.8, ls="-.")
    ax.plot([], [], "k:", lw=0.8, label="thin limit (Eq. antisym_thin)")
    ax.plot([], [], "k-.", lw=0.8, label="thick limit (Eq. ideal-shortwave)")
    ax.set_xscale("log")
    ax.set(xlabel="$kh$", ylabel="critical $D_0$", ylim=(0, 40),
           title="critical charge of a neo-Hookean plate")
    ax.legend(fontsize=7, ncol=2, loc="upper right")
    fig.tight_layout()
    fig.savefig("ex07_wrinkling_dispersion.png", dpi=120)
    plt.show()

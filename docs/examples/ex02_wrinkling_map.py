r"""
Wrinkling map of an equi-biaxially stretched, charge-controlled plate
=====================================================================

Paper Section 4, Fig. gent-equi-biaxial. A plate stretched to ``lam`` in both
in-plane directions and carrying the charge ``D0`` can wrinkle with wavenumber
``k`` when the dispersion relation of the plate (deformed thickness ``h``) has a
root. Its two limits bound the grey zone of the paper:

* thin plate, ``kh -> 0`` (Eq. antisym_thin): ``a = c``, i.e.
  ``D0^2 = 2 W'(I1) (lam^6 - 1)`` -- the ``s = 0`` loading curve;
* thick plate, ``kh -> inf`` (Eqs. short-wave, evalue):
  ``D0^4 - 2W'[lam^3 (p2+p3) + 2(lam^3-1)] D0^2
  - 4W'^2 [lam^3 (p2+p3)^2 - (lam^3-1)^2] = 0``
  (neo-Hookean: ``D0^4 - (lam^6+3lam^3-2) D0^2 - (lam^9+lam^6+3lam^3-1) = 0``).

Between them lies the exact finite-thickness critical ``D0(lam, kh)`` (beyond
the paper; dotted curves). The loading curves
``D0^2 = 2W'(lam^6 - 1) - lam^5 s`` (Eq. loading_gent) with pre-stress
``s > 0`` stay below the thin limit, hence below every critical curve: no
wrinkling under charge control.
"""

import numpy as np

from analytic import Gent, NeoHookean, critical_D0, equibiaxial_D0, wrinkling_map

model = NeoHookean()
lam = np.linspace(0.6, 6.0, 541)
region = wrinkling_map(lam, model)

# finite thickness: critical D0 for three plate thicknesses (flexural mode)
kh_values = [0.5, 2.0, 6.0]
lam_fin = np.linspace(1.0, 6.0, 26)
finite = {kh: critical_D0(lam_fin, kh, model) for kh in kh_values}

# loading curves of Fig. gent-equi-biaxial
s_values = [0.0, 0.8, 1.5, 2.5, 4.5]
curves = {s: equibiaxial_D0(lam, s, model) for s in s_values}

# largest ratio loading-curve D0 / thin limit over all s > 0 curves (< 1: no wrinkling)
above = lam > 1.0
worst_ratio = max(np.nanmax(curves[s][above] / region.thin[above]) for s in s_values if s > 0)
# thick limit at lam = 1 is sqrt(1 + sqrt(5)) for the neo-Hookean model
thick_at_1 = float(np.interp(1.0, lam, region.thick))

gent = wrinkling_map(lam, Gent(Jm=97.2))

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    # (a) the paper's axes (linear D0); (b) D0 over the thin-plate limit, where the thin
    # wrinkling zone between the two limits has a visible width at every stretch
    fig, (ax, axr) = plt.subplots(1, 2, figsize=(11, 4.5))
    ax.fill_between(region.lam, region.lower, region.upper, color="0.75", label="wrinkling zone")
    ax.plot(lam, region.thick, "k--", label="thick-plate limit")
    ax.plot(lam, gent.thick, ":", color="tab:red", label="thick limit, Gent $J_m=97.2$")
    for i, kh in enumerate(kh_values):
        label = "finite plate, kh = " + ", ".join(f"{k:g}" for k in kh_values) if i == 0 else None
        ax.plot(lam_fin, finite[kh], ":", color="tab:blue", lw=1, label=label)
    for s in s_values:
        ax.plot(lam, curves[s], "-", lw=1.2, label=f"s = {s:g}")
    ax.set(xlabel=r"$\lambda$", ylabel=r"$D_0$", xlim=(0.6, 4.0), ylim=(0, 12),
           title="(a) loading curves and wrinkling limits")
    ax.legend(fontsize=7, loc="lower right")

    ok = region.thin > 0
    thin = np.where(ok, region.thin, np.nan)
    axr.fill_between(lam[ok], 1.0, (region.thick / thin)[ok], color="0.75",
                     label="wrinkling zone")
    for kh in kh_values:
        thin_fin = np.interp(lam_fin, lam, thin)
        axr.plot(lam_fin, finite[kh] / thin_fin, "o-", ms=3, lw=1, label=f"finite plate, kh = {kh:g}")
    for s in s_values[1:]:
        axr.plot(lam, curves[s] / thin, "-", lw=1.2, label=f"loading curve s = {s:g}")
    axr.axhline(1.0, color="k", lw=0.8)
    axr.set(xlabel=r"$\lambda$", ylabel=r"$D_0 / D_0^{\mathrm{thin}}$", xlim=(1.0, 6.0),
            ylim=(0.0, 1.35),
            title=f"(b) over the thin limit; s > 0 curves stay below: max {worst_ratio:.3f}")
    axr.legend(fontsize=7, loc="lower right", ncol=2)
    fig.tight_layout()
    fig.savefig("ex02_wrinkling_map.png", dpi=120)
    plt.show()

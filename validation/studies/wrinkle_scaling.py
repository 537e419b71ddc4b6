"""The clamp-zone wrinkle's wavelength against the Cerda-Mahadevan scaling.

A sheet stretched between two clamps wrinkles where the clamps stop its lateral
contraction; the wavelength comes from the bending stiffness against the tension along the
wrinkles over the sheet's length (Cerda & Mahadevan, Phys. Rev. Lett. 90, 074302, 2003):

.. math::

    \\lambda_w \\propto (t L)^{1/2} \\gamma^{-1/4},

``t`` the thickness, ``L`` the length, ``gamma`` the tensile strain -- not from the local
homogeneous state (whose only length is the thickness: ``lambda_w ∝ t``).  For each weight
with a converged clamp-zone load (:func:`validation.buckling_data.clamp_unit_load`) this
module compares the measured wavelength -- the reference width over the half-wave pairs
of the mode, ``2 W / n`` -- with both, on the homogeneous uni-axial state at ``D0_b``
(Eq. (DEuniax): ``t = H lam2``, ``L = L0 lam1``, ``gamma = lam1 - 1``).  The scaling
holds where ``lambda_w / ((t L)^{1/2} gamma^{-1/4})`` is the same for every weight.

Usage::

    python -m validation.studies.wrinkle_scaling
"""

from __future__ import annotations

import math
import sys

import analytic as an
from analytic.units import keplinger_s

from ..buckling_data import clamp_unit_load
from ..specs import KEPLINGER

__all__ = ["wrinkle_scaling", "main"]


def wrinkle_scaling(alphas=(0.3, 0.7, 1.0, 1.5)) -> list[dict]:
    """The measured wavelength and the two scalings per weight with a converged load.

    Parameters
    ----------
    alphas : sequence of float
        Weights to try (default: those whose mode is the clamp-zone wrinkle); those
        without a converged clamp-zone load are left out.

    Returns
    -------
    list of dict
        Per weight: ``alpha``, ``D0_b``, ``half_waves``, ``wavelength_mm`` (``2 W / n``),
        ``lam1``, ``t_mm``, ``L_mm``, ``gamma``, ``cm_mm`` (``(t L)^{1/2} gamma^{-1/4}``),
        ``ratio_cm`` (wavelength over ``cm_mm``) and ``ratio_t`` (wavelength over ``t``).
    """
    W, L0, H = (1e3 * KEPLINGER[k] for k in ("width", "length", "thickness"))
    model = an.NeoHookean()
    out = []
    for a in alphas:
        try:
            g = clamp_unit_load(a)
        except ValueError:
            continue
        s = float(keplinger_s(a, g=KEPLINGER["g"]))
        lam1 = float(an.uniaxial_lam1(g["D0_b"], s, model))
        lam3 = float(an.uniaxial_lam3(lam1, s, model))
        t, L, gamma = H / (lam1 * lam3), L0 * lam1, lam1 - 1.0
        wl = 2.0 * W / g["half_waves"]
        cm = math.sqrt(t * L) * gamma ** -0.25
        out.append({"alpha": a, "D0_b": g["D0_b"], "half_waves": g["half_waves"],
                    "wavelength_mm": wl, "lam1": lam1, "t_mm": t, "L_mm": L,
                    "gamma": gamma, "cm_mm": cm, "ratio_cm": wl / cm, "ratio_t": wl / t})
    return out


def main(argv=None) -> int:
    """Print the table of :func:`wrinkle_scaling` (Markdown).

    Returns
    -------
    int
        0.
    """
    rows = wrinkle_scaling()
    print("| alpha | D0_b | half-waves | wavelength 2W/n (mm) | lam1 | t (mm) | L (mm) | "
          "gamma | (t L)^1/2 gamma^-1/4 (mm) | wavelength / CM | wavelength / t |")
    print("| --- " * 11 + "|")
    for r in rows:
        print(f"| {r['alpha']:g} | {r['D0_b']:.4f} | {r['half_waves']} | "
              f"{r['wavelength_mm']:.2f} | {r['lam1']:.3f} | {r['t_mm']:.3f} | "
              f"{r['L_mm']:.1f} | {r['gamma']:.3f} | {r['cm_mm']:.2f} | "
              f"{r['ratio_cm']:.3f} | {r['ratio_t']:.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

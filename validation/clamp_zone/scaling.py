"""The clamp-zone wrinkle's wavelength against the Cerda-Mahadevan scaling.

A sheet stretched between two clamps wrinkles where the clamps stop its lateral
contraction; the wavelength comes from the bending stiffness against the tension along the
wrinkles over the sheet's length (Cerda & Mahadevan, Phys. Rev. Lett. 90, 074302, 2003):

.. math::

    \\lambda_w \\propto (t L)^{1/2} \\gamma^{-1/4},

``t`` the thickness, ``L`` the length, ``gamma`` the tensile strain -- not from the local
homogeneous state (whose only length is the thickness: ``lambda_w ∝ t``).  For each weight
with a converged clamp-zone load (:func:`validation.data.clamp_zone.clamp_unit_load`) this
module compares the measured wavelength -- the reference width over the half-wave pairs
of the mode, ``2 W / n`` -- with both, on the homogeneous uni-axial state at ``D0_b``
(Eq. (DEuniax): ``t = H lam2``, ``L = L0 lam1``, ``gamma = lam1 - 1``).  The data are
consistent with the scaling where ``lambda_w / ((t L)^{1/2} gamma^{-1/4})`` is the same for
every weight; a few weights with an integer half-wave count cannot fix its exponent (and
``t L = H L0 / lam3`` hardly changes along these states).

:func:`compressive_zone` gives the plane-stress compressive zone of the membrane model at
``D0_b`` (where the lateral stress ``S33/mu`` -- the paper's ``P33`` -- is negative).

``skfem-dielectric clamp-zone scaling`` prints both tables (:func:`scaling_tables`).
"""

from __future__ import annotations

import math

import numpy as np

import analytic as an
import skfem_dielectric as fe
from analytic.units import keplinger_s

from ..data.clamp_zone import clamp_unit_load
from ..specs import KEPLINGER

__all__ = ["wrinkle_scaling", "compressive_zone", "scaling_tables"]

#: lateral stress ``S33/mu`` below which a point counts as compressed (the breakdown flag
#: of the harness, ``validation.table.BREAKDOWN_TOL``)
COMPRESSED = -1e-2


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


def compressive_zone(alpha: float, D0_b: float, *, n1: int = 80, n3: int = 40,
                     D0_step: float = 0.125) -> dict:
    """The plane-stress compressive zone of the membrane model at ``D0_b``.

    The membrane plate (:func:`skfem_dielectric.gallery.membrane_keplinger`, ``n1 x n3`` Q2
    elements on the quarter, charge in steps of ``D0_step`` to ``D0_b``): the lateral
    second Piola stress ``S33/mu`` (the paper's ``P33``) along the centre line and over
    the plate.

    Parameters
    ----------
    alpha, D0_b
        Weight fraction and the charge of the state.
    n1, n3, D0_step
        Mesh of the quarter and charge step.

    Returns
    -------
    dict
        ``P33_centre`` (``X1 = 0``), ``P33_min`` (over the element centres) with its
        ``X1_min``, ``X3_min`` (mm), ``extent_mm``: the length from the clamp along the
        centre line over which ``S33/mu <`` :data:`COMPRESSED`, ``area_fraction``: the
        share of the plate's elements below it, ``D0_compressed``: the first charge step
        at which the centre line outside the clamps' 2H layer falls below it.
    """
    D0 = np.append(np.arange(0.0, D0_b - 1e-9, D0_step), D0_b)
    res = fe.gallery.membrane_keplinger(alpha, D0=D0, n1=n1, n3=n3)
    if not res.converged:
        raise ValueError(f"the membrane ramp of alpha = {alpha:g} stopped before "
                         f"D0_b = {D0_b:g}: {res.reason}")
    pb = res.problem
    L = 1e3 * KEPLINGER["length"] / 2
    first = math.nan
    for st in res.steps:
        if st.load[1] > 0 and not math.isfinite(first):
            c = pb.centre_line(st.x, st.load)
            if c["P33"][np.abs(c["x1"]) <= L - 2e3 * KEPLINGER["thickness"]].min() < COMPRESSED:
                first = float(st.load[1])
    st = res.steps[-1]
    c = pb.centre_line(st.x, st.load)
    m = pb.step_mesh(st.x, st.load)
    P33 = np.asarray(m.cell_data["P33"][0])
    centres = m.points[m.cells[0].data].mean(axis=1)
    k = int(np.argmin(P33))
    comp = np.abs(c["x1"][c["P33"] < COMPRESSED])
    return {"P33_centre": float(c["P33"][np.argmin(np.abs(c["x1"]))]),
            "P33_min": float(P33[k]), "X1_min": float(abs(centres[k, 0])),
            "X3_min": float(abs(centres[k, 1])),
            "extent_mm": float(L - comp.min()) if comp.size else 0.0,
            "area_fraction": float(np.mean(P33 < COMPRESSED)), "D0_compressed": first}


def scaling_tables(membrane: bool = True) -> str:
    """The tables of :func:`wrinkle_scaling` and :func:`compressive_zone`, as Markdown.

    Parameters
    ----------
    membrane : bool
        Also the compressive zone's table (the membrane ramps take about 10 CPU seconds
        per weight); ``False``: the wavelength table only.

    Returns
    -------
    str
    """
    rows = wrinkle_scaling()
    out = ["| alpha | D0_b | half-waves | wavelength 2W/n (mm) | lam1 | t (mm) | L (mm) | "
           "gamma | (t L)^1/2 gamma^-1/4 (mm) | wavelength / CM | wavelength / t |",
           "| --- " * 11 + "|"]
    for r in rows:
        out.append(f"| {r['alpha']:g} | {r['D0_b']:.4f} | {r['half_waves']} | "
                   f"{r['wavelength_mm']:.2f} | {r['lam1']:.3f} | {r['t_mm']:.3f} | "
                   f"{r['L_mm']:.1f} | {r['gamma']:.3f} | {r['cm_mm']:.2f} | "
                   f"{r['ratio_cm']:.3f} | {r['ratio_t']:.1f} |")
    if membrane:
        out += ["", "| alpha | D0_b | membrane S33/mu at the centre | min S33/mu (X1, X3 mm) | "
                "compressed length from the clamp on the centre line (mm) | compressed area | "
                "centre line compressed from D0 |", "| --- " * 7 + "|"]
        for r in rows:
            z = compressive_zone(r["alpha"], r["D0_b"])
            out.append(f"| {r['alpha']:g} | {r['D0_b']:.4f} | {z['P33_centre']:+.4f} | "
                       f"{z['P33_min']:+.4f} ({z['X1_min']:.1f}, {z['X3_min']:.1f}) | "
                       f"{z['extent_mm']:.1f} | {z['area_fraction']:.2f} | "
                       f"{z['D0_compressed']:g} |")
    return "\n".join(out) + "\n"

r"""
The lecture in one notebook: charge against voltage control, and what breaks the clamped plate
==============================================================================================

The companion of the lecture page (docs/lecture.md), downloadable as a Jupyter notebook
from the gallery.  Two parts.

**The homogeneous plate.**  Under equi-biaxial stretch ``lam`` and no dead load, the
loading curve of Eq. (loading_gent) is :math:`D_0 = \sqrt{\lambda^6 - 1}` (neo-Hookean).
Under voltage control the field :math:`E_0 = D_0/\lambda^4` has a maximum, the
voltage-control limit :math:`\det\mathcal{H}^* = 0` (Sec. 3.1): the plate snaps through
there.  Under charge control :math:`D_0` grows without a maximum: no snap-through.  Here
the maximum is found on the curve by a bounded scalar search and compared with the
literature value :math:`E_0^{max} = \sqrt{3}/2^{4/3}` at :math:`\lambda = 2^{1/3}`.

**The clamped Keplinger plate.**  What stops it is not the homogeneous theory (which
predicts no wrinkling for a loaded plate) but the clamps.  "Breakdown" means three things,
met in this order as the charge grows: the ``P33`` criterion (the paper's), the buckling
load ``D0_b`` (a wrinkle next to each clamp) and the Newton limit (a solver failure).  The
numbers come from the study shipped with the package, located to ``1e-4`` on meshes graded
towards the clamp (``validation.clamp_zone.tables.breakdown_numbers``); the map draws them.
"""

import numpy as np
from scipy.optimize import minimize_scalar

import analytic as an
from validation.clamp_zone.tables import breakdown_numbers

# -- part 1: the homogeneous plate under the two controls
res = minimize_scalar(lambda lam: -an.equibiaxial_D0(lam, 0.0) / lam**4, bounds=(1.0, 3.0),
                      method="bounded", options={"xatol": 1e-12})
lam_max, E0_max = float(res.x), float(-res.fun)
lam = np.linspace(1.0, 3.0, 400)
D0 = an.equibiaxial_D0(lam, 0.0)
print(f"voltage control: largest E0 = {E0_max:.8f} at lam = {lam_max:.6f}")
print(f"charge control: D0 increases along the whole curve: {bool(np.all(np.diff(D0) > 0))}")

# -- part 2: the clamped plate, the three meanings of breakdown per weight
rows = breakdown_numbers()
for n in rows:
    print(f"alpha = {n['alpha']:g}: P33 onset {n['interior']:.4f} < D0_b {n['D0_b']:.4f} "
          f"+- {n['error']:.4f} < Newton limit {n['newton_limit']:g}")
ordered = all(n["interior"] < n["D0_b"] < n["newton_limit"] for n in rows)
print("the order holds for every weight:", ordered)

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    from validation.figures import plot_breakdown_map

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 4.8), layout="constrained")
    ax1.plot(lam, D0 / lam**4, "k-", label="$E_0 = D_0/\\lambda^4$ on the curve $s = 0$")
    ax1.plot(lam_max, E0_max, "^k", ms=9, label="voltage-control limit (snap-through)")
    ax1.set(xlabel=r"$\lambda$", ylabel=r"$E_0$", title="(a) voltage control has a maximum")
    ax1.legend(fontsize=8)
    plot_breakdown_map(ax=ax2)
    ax2.set_title("(b) the clamped plate: P33 onset, D0_b, Newton limit", fontsize=10,
                  pad=16)
    fig.savefig("ex15_lecture_breakdown.png", dpi=110)
    plt.show()

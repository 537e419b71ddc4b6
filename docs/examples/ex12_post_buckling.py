r"""
The clamped plate past its buckling load: switching onto the buckled branch
===========================================================================

The lightly loaded Keplinger plate (:math:`\alpha = 0.05`) buckles laterally at
:math:`D_0 \approx 0.78` on this coarse mesh: the lowest physical eigenvalue of its
quarter model (symmetry planes :math:`x_1 = 0`, :math:`x_3 = 0`, the whole thickness, so
that it can bend) changes sign.  A load-controlled Newton from the fundamental state stays
on the now unstable symmetric branch; started from the fundamental state plus the
critical mode (:func:`skfem_dielectric.studies.postbuckling.switch_branch`) it converges to the
buckled equilibrium of the perfect plate, which the ramp then follows forward and back
towards the buckling load (:func:`skfem_dielectric.studies.postbuckling.post_buckled_branch`).

Near a symmetric bifurcation the load is even in the deflection amplitude :math:`w`,
:math:`D_0 = D_{0b} + b w^2 + c w^4`: the branch alone gives the buckling load again,
independently of the eigenvalues
(:meth:`~skfem_dielectric.studies.postbuckling.PostBuckledBranch.pitchfork`).
"""

from dataclasses import replace

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.studies.postbuckling import critical_mode, midplane_nodes, post_buckled_branch

res = fe.keplinger_plate(0.05, D0=[0.75, 0.8], elements=(10, 2, 5), symmetry="quarter",
                         options=fe.PlateOptions(grad_div=10.0),
                         settings=replace(fe.gallery.KEPLINGER_SETTINGS, max_cutbacks=6,
                                          max_iter=25))
pb, before, after = res.problem, res.steps[-2], res.steps[-1]
for st in (before, after):
    print(f"fundamental D0 = {st.load[1]:.2f}: lowest physical eigenvalue "
          f"{critical_mode(pb, st.x, st.load).eigenvalue: .3e}")

br = post_buckled_branch(pb, after.x, after.load, forward=[0.9, 1.0, 1.1, 1.2],
                         backward=[0.79, 0.785, 0.782, 0.78], stability=False)
print(f"switched with a = {br.switch.amplitude:g} mm: deflection {br.switch.deflection:.3f} mm")
for d, w, _ in br.states():
    print(f"  D0 = {d:.4f}: mid-plane deflection {w:.4f} mm")
D0_b_branch, b = br.pitchfork(4)
print(f"buckling load from the branch: D0_b = {D0_b_branch:.5f} (b = {b:.4f}: supercritical)")

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    d, w = np.array([(s[0], s[1]) for s in br.states()]).T
    ww = np.linspace(0.0, w.max(), 100)
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 3.8), constrained_layout=True)
    ax.plot(d, w, "o", label="FE buckled branch (quarter 10 x 2 x 5)")
    ax.plot(D0_b_branch + b * ww**2, ww, "-", lw=0.8, label="D0 = D0_b + b w^2 (4-point fit)")
    ax.plot([0.7, D0_b_branch], [0, 0], "k-", lw=2, label="fundamental branch, stable")
    ax.plot([D0_b_branch, 1.2], [0, 0], "k--", lw=1, label="fundamental branch, unstable")
    ax.axvline(D0_b_branch, ls=":", color="k")
    ax.set(xlabel="D0", ylabel="mid-plane deflection w (mm)", xlim=(0.7, 1.22),
           title="alpha = 0.05: pitchfork at D0_b")
    ax.legend(fontsize=8)
    last = [s for s in br.states() if s[2] is not None][-1][2]
    X = pb.b2.doflocs
    mid = midplane_nodes(pb)
    u2 = pb.full(last.x, last.load)[1:pb.n_u:3][mid]
    X1 = np.concatenate([X[0][mid], -X[0][mid], X[0][mid], -X[0][mid]])
    X3 = np.concatenate([X[2][mid], X[2][mid], -X[2][mid], -X[2][mid]])
    t = ax2.tricontourf(X1, X3, np.tile(u2, 4), 21, cmap="RdBu_r")
    fig.colorbar(t, ax=ax2, shrink=0.8, label="u2 (mm)")
    ax2.set(aspect="equal", xlabel="X1 (mm)", ylabel="X3 (mm)",
            title=f"mid-plane deflection at D0 = {last.load[1]:.2f}")
    fig.savefig("ex12_post_buckling.png", dpi=120)
    plt.show()

r"""
Buckling modes of a clamped plate from its eighth: symmetry classes
===================================================================

An eighth model (symmetry planes :math:`x_1 = 0`, :math:`x_2 = 0`, :math:`x_3 = 0`) only
admits increments that are mirror-symmetric with respect to every plane: it cannot bend.
Switching each plane between symmetric and antisymmetric conditions
(:func:`skfem_dielectric.models.plate.problem.plate_reduction`) gives the eight classes of
increments of the whole plate; the tangent of the whole plate is block diagonal in them, so
:func:`skfem_dielectric.models.class_stability` returns the whole plate's negative-eigenvalue
count and lowest modes at the cost of eight factorisations of the eighth model's size.

Here a slender clamped plate (8 x 1 x 4 thicknesses) is compressed end to end past its
Euler load (``s = -0.4``) and charged (``D0 = 1``).  The eighth model's own class is
stable; four classes have one negative eigenvalue each, all antisymmetric through the
thickness (bending).  The maps show the top-face deflection of their modes over the whole
plate, unfolded by each class's parities
(:func:`skfem_dielectric.models.plate.modes.top_deflection`);
:func:`skfem_dielectric.models.plate.modes.classify_mode` says where their energy sits.
"""

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.gallery.drivers import keplinger_problem
from skfem_dielectric.models.plate.modes import top_deflection
from skfem_dielectric.models.plate.symmetry_classes import class_mode_full

pb = keplinger_problem(size=(8.0, 1.0, 4.0), elements=(4, 1, 2), symmetry="eighth")
targets = [np.array([-0.4, 1.0]) * t for t in np.linspace(0.25, 1.0, 4)]
res = fe.ramp(pb, targets, x0=pb.initial_state(), start=np.zeros(2))
cs = fe.models.class_stability(pb, res.x, targets[-1], k=1)
xf = pb.full(res.x, targets[-1])
modes = []
for c, r in zip(cs.classes, cs.results):
    w = class_mode_full(c, r.modes[:, 0])
    lab = fe.models.classify_mode(pb, xf, w, symmetry=c.name)
    modes.append((float(r.eigenvalues[0]), c, w, lab))
    print(f"{c.name}: {r.n_negative} negative, lowest {r.eigenvalues[0]: .5e}, "
          f"corner share {lab['corner_share']:.2f}, mesh scale {lab['mesh_scale']:.2f}, "
          f"{lab['kind']}")
lowest_eig = cs.lowest(1)[0][0]
print(f"whole plate: {cs.n_negative} negative eigenvalues, lowest {lowest_eig:.8e}")

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    unstable = sorted(m for m in modes if m[0] < 0)[:4]
    fig, axes = plt.subplots(2, 2, figsize=(10, 5.6), constrained_layout=True)
    for ax, (ev, c, w, lab) in zip(axes.ravel(), unstable):
        X1, X3, u2 = top_deflection(pb, w, c.increments)
        t = ax.tricontourf(X1, X3, u2 / np.abs(u2).max(), 21, cmap="RdBu_r", vmin=-1, vmax=1)
        ax.set(aspect="equal", xlabel="X1", ylabel="X3",
               title=f"{c.name}: eigenvalue {ev:.3e} ({lab['kind']})")
    fig.colorbar(t, ax=axes, shrink=0.8, label="top-face u2 (scaled)")
    fig.suptitle("Unstable modes of a clamped plate under end compression s = -0.4, D0 = 1 "
                 "(clamps at X1 = +-4)", fontsize=10)
    fig.savefig("ex11_symmetry_classes.png", dpi=120)
    plt.show()

"""The whole plate's spectrum along a path costs one factorisation per symmetry class
per state, and gives the eigenvalues of the spectrum slicing on fresh factorisations."""

import numpy as np

from skfem_dielectric import keplinger_plate
from skfem_dielectric.linalg.solver_base import factorisation_count
from skfem_dielectric.models.plate.symmetry_classes import (class_stability, class_tangent,
                                                            union_tangent)
from skfem_dielectric.stability.analysis import lowest_modes


def test_class_spectra_one_factorisation_per_class_and_state():
    # the 10 x 1 x 5 eighth model has negative (corner) eigenvalues from D0 = 3 on
    res = keplinger_plate(1.0, D0=[3.0, 4.0], elements=(10, 1, 5), linear_solver="superlu")
    problem = res.problem
    counts = []
    for st in res.steps[-2:]:
        c0 = factorisation_count()
        cs = class_stability(problem, st.x, st.load, k=0, all_negative=True, extra=2,
                             method="superlu")
        counts.append((factorisation_count() - c0) / len(cs.classes))
        assert cs.n_negative > 0          # the negative part is exercised
        classes, K = union_tangent(problem, st.x, st.load)
        for c, r in zip(cs.classes, cs.results):
            # reference: no factors handed on, so the negative part is sliced on
            # shifted factorisations of its own (the independent path)
            vals, _ = lowest_modes(class_tangent(c, K), c.metric, r.eigenvalues.size,
                                   r.n_negative, tol=1e-10)
            # both solve the same eigenproblem to ARPACK's tolerance 1e-10 on 1/lambda;
            # 1e-8 relative to the largest computed |lambda| leaves rounding of the two
            # factorisations a margin of 100
            scale = float(np.max(np.abs(vals)))
            np.testing.assert_allclose(r.eigenvalues, vals, rtol=0, atol=1e-8 * scale)
    # the count's factorisation serves the negative and the positive modes; the
    # constrained order is kept from the first state, so no minimum-degree attempt fails
    assert np.mean(counts) <= 1.5, counts
    assert counts[-1] == 1.0, counts

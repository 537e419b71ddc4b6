"""Critical load on a load path (skfem_dielectric.solvers.critical)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp

from skfem_dielectric import Layout, Problem
from skfem_dielectric.solvers.critical import brent, critical_load, illinois


class Branch(Problem):
    """E = (x2 - t)^2/2 + x1^2 (2 - x2^2)/2 + x1^4/4: the branch x1 = 0, x2 = t has the
    stiffness diag(2 - t^2, 1), which loses positive definiteness at t = sqrt(2)."""

    layout = Layout.single(2)

    def initial_state(self):
        return np.zeros(2)

    def assemble(self, x, load):
        x1, x2 = x
        t = float(load)
        r = np.array([x1 * (2 - x2**2) + x1**3, (x2 - t) - x1**2 * x2])
        K = np.array([[2 - x2**2 + 3 * x1**2, -2 * x1 * x2], [-2 * x1 * x2, 1 - x1**2]])
        return sp.csr_matrix(K), r


def lowest(pb):
    return lambda x, load: float(np.linalg.eigvalsh(pb.assemble(x, load)[0].toarray())[0])


def test_locates_the_closed_form_critical_load():
    pb = Branch()
    x_a = np.array([0.0, 0.5])
    out = critical_load(pb, x_a, 0.5, 2.0, lowest(pb), tol=1e-4)
    # the located load is within the requested tolerance of sqrt(2) (the closed form)
    assert abs(out.load - math.sqrt(2.0)) <= 1e-4
    assert out.bracket[1] - out.bracket[0] <= 1e-4 / 1.5 + 1e-15
    assert np.allclose(out.x, [0.0, out.load])
    # the Illinois steps converge superlinearly: a handful of trial states
    assert len(out.evaluations) <= 10


def test_vector_loads_and_bad_input():
    pb = Branch()

    class Pair(Branch):
        def assemble(self, x, load):
            return Branch.assemble(self, x, float(np.asarray(load)[1]))

    pp = Pair()
    out = critical_load(pp, np.array([0.0, 0.5]), (0.0, 0.5), (0.0, 2.0), lowest(pp),
                        tol=1e-6)
    assert abs(out.load[1] - math.sqrt(2.0)) <= 1e-6 and out.load[0] == 0.0
    with pytest.raises(ValueError, match="does not change sign"):
        critical_load(pb, np.array([0.0, 0.5]), 0.5, 1.2, lowest(pb))
    with pytest.raises(ValueError, match="tol must be"):
        critical_load(pb, np.array([0.0, 0.5]), 0.5, 2.0, lowest(pb), tol=0.0)
    with pytest.raises(ValueError, match="eig must be callable"):
        critical_load(pb, np.array([0.0, 0.5]), 0.5, 2.0, None)
    with pytest.raises(ValueError, match="must differ"):
        critical_load(pb, np.array([0.0, 0.5]), 0.5, 0.5, lowest(pb))
    with pytest.raises(ValueError, match="problem must be"):
        critical_load(object(), np.zeros(2), 0.5, 2.0, lowest(pb))


@pytest.mark.parametrize("xtol", [1e-4, 1e-8, 1e-12])
def test_brent_closes_the_bracket_with_fewer_evaluations_than_illinois(xtol):
    # g(t) = cos t - t (positive at 0, negative at 1), root 0.739085133215160641655 (the
    # Dottie number); the final bracket holds it and is no wider than asked; Brent needs at
    # most as many evaluations as Illinois for the same width, and a curved g (the
    # eigenvalue of a plate near its crossing bends like this) takes it fewer
    root = 0.739085133215160641655
    for g in (lambda t: math.cos(t) - t, lambda t: math.cos(3 * t) - t / 3 - 0.5):
        f0, f1 = g(0.0), g(1.0)
        c, fc, a, b, it = brent(g, 0.0, f0, 1.0, f1, xtol=xtol, maxiter=100)
        assert g(a) > 0 > g(b) and abs(b - a) <= xtol and fc == g(c)
        _, _, ia, ib, it_ill = illinois(g, 0.0, f0, 1.0, f1, maxiter=100,
                                        done=lambda a, b, c: abs(b - a) <= xtol)
        assert it <= it_ill
        assert min(a, b) <= max(ia, ib) and min(ia, ib) <= max(a, b)   # same root
    c, _, a, b, _ = brent(lambda t: math.cos(t) - t, 0.0, 1.0, 1.0, math.cos(1) - 1,
                          xtol=xtol, maxiter=100)
    assert min(a, b) <= root <= max(a, b)

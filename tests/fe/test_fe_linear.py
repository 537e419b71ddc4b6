"""PARDISO solvers share the located MKL library but not their factorisations."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from skfem_dielectric.linalg.linear import (PardisoLUSolver, PardisoSolver, new_pypardiso_solver,
                                     pardiso_available)

pytestmark = pytest.mark.skipif(not pardiso_available(), reason="needs pypardiso")


def saddle(n: int, m: int, seed: int) -> sp.csr_matrix:
    """Symmetric indefinite saddle-point matrix [[A, B^T], [B, -C]] (like the u-p tangent;
    a small C keeps the diagonal in the stored upper triangle)."""
    rng = np.random.default_rng(seed)
    A = sp.random(n, n, density=0.2, random_state=rng)
    A = A @ A.T + n * sp.identity(n)
    B = sp.random(m, n, density=0.3, random_state=rng) + sp.eye(m, n)
    return sp.bmat([[A, B.T], [B, -1e-3 * sp.identity(m)]], format="csr")


def test_two_symmetric_solvers_keep_their_own_factorisation():
    K1, K2 = saddle(40, 10, 1), saddle(70, 20, 2)          # different sizes and patterns
    b1, b2 = np.arange(50.0), np.cos(np.arange(90.0))
    s1, s2 = PardisoSolver(), PardisoSolver()
    x1 = s1.solve(K1, b1)
    x2 = s2.solve(K2, b2)                                   # factorised after s1
    # reference: scipy's SuperLU; both systems are well conditioned (cond < 1e4), so
    # the two direct solvers agree to ~1e-12 relative
    r1, r2 = spla.spsolve(K1.tocsc(), b1), spla.spsolve(K2.tocsc(), b2)
    np.testing.assert_allclose(x1, r1, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(x2, r2, rtol=1e-9, atol=1e-12)
    # s1's factors survive s2's factorisation: a new right-hand side with the old factors
    c1 = np.sin(np.arange(50.0))
    np.testing.assert_allclose(s1.resolve(c1), spla.spsolve(K1.tocsc(), c1), rtol=1e-9,
                               atol=1e-12)
    # inertia is per solver: n positive (A block), m negative (Schur complement)
    assert s1.inertia == (40, 10, 0) and s2.inertia == (70, 20, 0)


def test_two_nonsymmetric_pypardiso_solvers_are_independent():
    rng = np.random.default_rng(3)
    mats = [sp.random(n, n, density=0.1, random_state=rng) + n * sp.identity(n)
            for n in (30, 45)]
    mats = [sp.csr_matrix(M) for M in mats]
    solvers = [new_pypardiso_solver(11) for _ in mats]
    for ps, M in zip(solvers, mats):
        ps.factorize(M)
    assert solvers[0].pt is not solvers[1].pt and solvers[0].pt.any()
    for ps, M in zip(solvers, mats):                        # phase 33 with the stored factors
        b = np.linspace(-1.0, 1.0, M.shape[0])
        # diagonally dominant non-symmetric matrices: LU agrees with SuperLU to round-off
        np.testing.assert_allclose(ps.solve(M, b), spla.spsolve(M.tocsc(), b), rtol=1e-10,
                                   atol=1e-13)


def test_pardiso_lu_keeps_its_analysis_and_solves_again_with_its_factors(monkeypatch):
    rng = np.random.default_rng(4)
    n = 60
    P = sp.random(n, n, density=0.1, random_state=rng) + n * sp.identity(n)
    K1 = sp.csr_matrix(P)
    K1.sort_indices()
    K2 = K1.copy()
    K2.data = K2.data * (1.0 + 0.3 * rng.standard_normal(K2.nnz))   # same pattern
    solver = PardisoLUSolver()
    phases = []
    call = solver._call
    monkeypatch.setattr(solver, "_call", lambda ph, A, b: phases.append(ph) or call(ph, A, b))
    b = np.linspace(-1.0, 1.0, n)
    # non-symmetric, diagonally dominant (cond < 10): LU agrees with SuperLU to round-off
    for K in (K1, K2):
        np.testing.assert_allclose(solver.solve(K, b), spla.spsolve(K.tocsc(), b),
                                   rtol=1e-10, atol=1e-13)
    # one symbolic analysis (phase 11) for the two matrices of one pattern
    assert phases.count(11) == 1 and phases.count(22) == 2
    # a chord step: the last factors solve a new right-hand side without factorising
    c = np.cos(np.arange(n, dtype=float))
    np.testing.assert_allclose(solver.resolve(c), spla.spsolve(K2.tocsc(), c), rtol=1e-10,
                               atol=1e-13)
    assert phases.count(22) == 2 and solver.inertia is None
    solver.discard()
    assert solver.resolve(c) is None


@pytest.mark.skipif(not pardiso_available(), reason="needs pypardiso")
def test_pardiso_reuses_the_upper_triangle_of_a_shared_pattern(monkeypatch):
    from skfem_dielectric.fem.assembly import ScatterMap

    # 1-D chain of 2-node elements with element matrices [[2, -1], [-1, 2]] + diag shift:
    # SPD tridiagonal, solved exactly; the second matrix shares the read-only pattern
    n = 200
    dofs = np.c_[np.arange(n - 1), np.arange(1, n)]
    sc = ScatterMap(dofs, n)
    Ke = np.broadcast_to(np.array([[2.0, -1.0], [-1.0, 2.0]]), (n - 1, 2, 2))
    solver = PardisoSolver()
    b = np.ones(n)
    uppers = []
    for scale in (1.0, 3.0):
        K = sc.matrix(scale * Ke)
        x = solver.solve(K, b)
        np.testing.assert_allclose(K @ x, b, rtol=1e-12)
        uppers.append(solver._ucache[2])
        # from the second matrix on the pattern is recognised by its memory (O(1)), not by
        # comparing its contents
        monkeypatch.setattr(np, "array_equal", lambda *a, **k: pytest.fail("compared"))
    assert solver._ucache[4] and uppers[0] is uppers[1]


def test_pardiso_overwrites_the_upper_triangle_in_place():
    from skfem_dielectric.fem.assembly import ScatterMap
    from skfem_dielectric.linalg.linear import _compress_into

    # blocks of the copy: across block boundaries, as a[keep]
    rng = np.random.default_rng(4)
    a, keep = rng.standard_normal(1000), rng.random(1000) < 0.4
    out = np.empty(int(keep.sum()))
    _compress_into(keep, a, out, block=64)
    assert np.array_equal(out, a[keep])
    # a new tangent of the same pattern: the upper triangle's data array is refilled (the
    # zero-based pattern is what PARDISO reads), and the solve is that of the new matrix
    n = 150
    dofs = np.c_[np.arange(n - 1), np.arange(1, n)]
    sc = ScatterMap(dofs, n)
    Ke = np.broadcast_to(np.array([[2.0, -1.0], [-1.0, 2.0]]), (n - 1, 2, 2))
    solver = PardisoSolver()
    b = np.linspace(1.0, 2.0, n)
    x1 = solver.solve(sc.matrix(Ke), b)
    U = solver._ucache[2]
    data = U.data
    K2 = sc.matrix(2.5 * Ke)
    x2 = solver.solve(K2, b)
    assert solver._ucache[2].data is data and U.indptr[0] == 0
    np.testing.assert_allclose(K2 @ x2, b, rtol=1e-12)
    np.testing.assert_allclose(x2, x1 / 2.5, rtol=1e-12)


@pytest.mark.parametrize("ordering", ["auto", "minimum-degree", "metis", "parallel-metis"])
def test_pardiso_orderings_give_the_same_solution_and_inertia(ordering):
    K, b = saddle(60, 15, 6), np.linspace(-1.0, 1.0, 75)
    s = PardisoSolver(ordering=ordering)
    np.testing.assert_allclose(s.solve(K, b), spla.spsolve(K.tocsc(), b), rtol=1e-9,
                               atol=1e-12)
    assert s.inertia == (60, 15, 0)
    with pytest.raises(ValueError, match="ordering"):
        PardisoSolver(ordering="amd")


def test_pardiso_auto_orders_by_the_size_of_the_system(monkeypatch):
    """``ordering="auto"`` analyses a system below METIS_MIN_UNKNOWNS by minimum degree and
    one at or above it by METIS (iparm(2) as PARDISO received it: 0 and 2), and the solve
    and inertia are those of either ordering."""
    import skfem_dielectric.linalg.linear as lin

    K, b = saddle(60, 15, 6), np.linspace(-1.0, 1.0, 75)
    s = PardisoSolver()
    assert s.ordering == "auto"
    s.solve(K, b)
    assert s.chosen_ordering == "minimum-degree" and s._ps.iparm[1] == 0
    monkeypatch.setattr(lin, "METIS_MIN_UNKNOWNS", 75)
    t = PardisoSolver()
    x = t.solve(K, b)
    assert t.chosen_ordering == "metis" and t._ps.iparm[1] == 2
    np.testing.assert_allclose(x, spla.spsolve(K.tocsc(), b), rtol=1e-9, atol=1e-12)
    assert t.inertia == (60, 15, 0)


def test_pardiso_refines_with_the_matrix_passed():
    # the refinement steps are done with the residual of K (PARDISO's own refinement,
    # whose work array is as large as the matrix, is off): the residual is at round-off
    K, b = saddle(80, 30, 8), np.cos(np.arange(110.0))
    s = PardisoSolver()
    assert s._ps.iparm[7] == 0
    x = s.solve(K, b)
    assert np.linalg.norm(K @ x - b) <= 1e-13 * np.linalg.norm(b)
    x0 = PardisoSolver(refine=0).solve(K, b)
    assert np.linalg.norm(K @ x - b) <= np.linalg.norm(K @ x0 - b)


def test_pardiso_factorises_a_given_upper_triangle():
    # a SymmetricUpper is handed to PARDISO as it is (no selection, no cache), its
    # read-only pattern recognised by its memory; the refinement's products are those of
    # the whole matrix
    from skfem_dielectric.linalg.symmetric import SymmetricUpper

    K, b = saddle(80, 30, 9), np.sin(np.arange(110.0))
    T = sp.triu(K, format="csr")
    T.indptr.flags.writeable = T.indices.flags.writeable = False
    s = PardisoSolver()
    x = s.solve(SymmetricUpper(T), b)
    assert s._ucache is None and s._pattern[0] is T.indptr and s.inertia == (80, 30, 0)
    assert np.linalg.norm(K @ x - b) <= 1e-13 * np.linalg.norm(b)
    T2 = sp.csr_matrix((2.0 * T.data, T.indices, T.indptr), shape=T.shape)
    x2 = s.solve(SymmetricUpper(T2), b)             # the same analysis, new factors
    np.testing.assert_allclose(x2, x / 2.0, rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(s.resolve(b), x2, rtol=1e-10, atol=1e-14)


def zero_diagonal(n: int, seed: int) -> sp.csr_matrix:
    """Symmetric indefinite matrix with half its diagonal zero (stored explicitly): 1x1
    diagonal pivots alone must perturb some of them."""
    rng = np.random.default_rng(seed)
    A = sp.random(n, n, density=0.1, random_state=seed, format="csr")
    A = (A + A.T).tolil()
    A.setdiag(np.r_[np.zeros(n // 2), rng.uniform(-1.0, 1.0, n - n // 2)])
    A = A.tocsr()
    A.sort_indices()
    return A


@pytest.mark.parametrize("seed", [0, 1])
def test_a_perturbed_1x1_pivot_is_refactorised_with_bunch_kaufman(seed):
    # the default 1x1 pivots perturb pivots of this matrix: the solver factorises it again
    # with Bunch-Kaufman pivoting (its own analysis) and solves, counts and back-
    # substitutes with those factors; the reference is numpy's dense solve and eigenvalues
    K = zero_diagonal(40, seed)
    b = np.sin(np.arange(40.0))
    dense = K.toarray()
    ev = np.linalg.eigvalsh(dense)
    s = PardisoSolver()
    x = s.solve(K, b)
    assert s.fallbacks == 1
    np.testing.assert_allclose(x, np.linalg.solve(dense, b), rtol=1e-9, atol=1e-9)
    assert s.inertia == (int((ev > 0).sum()), int((ev < 0).sum()), 0)
    np.testing.assert_allclose(s.resolve(2.0 * b), 2.0 * x, rtol=1e-9, atol=1e-9)
    # a matrix without a perturbed pivot goes back to the 1x1 factors
    K2, b2 = saddle(30, 10, 3), np.cos(np.arange(40.0))
    x2 = s.solve(K2, b2)
    assert s.fallbacks == 1 and s.perturbed_pivots() == 0
    np.testing.assert_allclose(s.resolve(b2), x2, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(x2, spla.spsolve(K2.tocsc(), b2), rtol=1e-9, atol=1e-12)
    # the fallback freed the first handle's analysis: the same matrix again is analysed
    # and falls back again, with the same solution
    x3 = s.solve(K, b)
    assert s.fallbacks == 2
    np.testing.assert_allclose(x3, np.linalg.solve(dense, b), rtol=1e-9, atol=1e-9)


def test_a_released_solver_analyses_again_and_solves_as_before():
    # release frees the factors and the analysis: resolve has nothing to solve with, and
    # the next solve (same pattern, then another) matches scipy's LU
    K, b = saddle(30, 10, 3), np.cos(np.arange(40.0))
    s = PardisoSolver()
    x = s.solve(K, b)
    s.release()
    assert s.resolve(b) is None
    x2 = s.solve(K, b)
    np.testing.assert_allclose(x2, spla.spsolve(K.tocsc(), b), rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(x2, x, rtol=1e-12, atol=1e-14)
    assert s.inertia == (30, 10, 0)
    K3 = zero_diagonal(40, 0)
    s.release()
    x3 = s.solve(K3, b)
    np.testing.assert_allclose(x3, np.linalg.solve(K3.toarray(), b), rtol=1e-9, atol=1e-9)
    s.release()
    s.release()                                 # twice: nothing left to free
    assert s.resolve(b) is None


def test_single_precision_factors_solve_to_double_accuracy_with_the_same_inertia():
    # factors in single precision: a solve refines in double to the default 1e-13 (against
    # scipy's LU of the double matrix), the inertia is that of the double factors (and of
    # numpy's eigenvalues), a resolve with the single factors alone is accurate to
    # single precision times the condition (here below 1e-4) but not to double
    K, b = saddle(60, 20, 4), np.sin(np.arange(80.0) + 0.3)
    exact = spla.spsolve(K.tocsc(), b)
    ev = np.linalg.eigvalsh(K.toarray())
    single, double = PardisoSolver(precision="single"), PardisoSolver()
    assert single.precision == "single" and single.refine == 1 and double.refine == 2
    x1 = single.solve(K, b)                 # one refinement step by default
    assert np.linalg.norm(K @ x1 - b) <= 1e-9 * np.linalg.norm(b)
    single.refine = 3
    x = single.solve(K, b)
    double.solve(K, b)
    assert np.linalg.norm(K @ x - b) <= 1e-13 * np.linalg.norm(b)
    np.testing.assert_allclose(x, exact, rtol=1e-11, atol=1e-13)
    assert single.inertia == double.inertia == (int((ev > 0).sum()), int((ev < 0).sum()), 0)
    y = single.resolve(b)
    err = np.linalg.norm(y - exact) / np.linalg.norm(exact)
    assert 1e-12 < err < 1e-4
    # a perturbed pivot, which single precision does not recover from (the solution of
    # the perturbed factors refined is wrong by orders of magnitude here), falls back to
    # Bunch-Kaufman in double precision
    Z = zero_diagonal(40, 1)
    bz = np.cos(np.arange(40.0))
    xz = single.solve(Z, bz)
    assert single.fallbacks == 1 and single._robust.precision == "double"
    np.testing.assert_allclose(xz, np.linalg.solve(Z.toarray(), bz), rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("bad", ["half", "float32", None])
def test_a_precision_not_offered_is_refused_by_name(bad):
    from skfem_dielectric.linalg.linear import get_linear_solver
    with pytest.raises(ValueError, match="precision"):
        PardisoSolver(precision=bad)
    with pytest.raises(ValueError, match="precision"):
        get_linear_solver("superlu", precision=bad)


def test_single_precision_refines_as_far_as_the_condition_allows_then_falls_back():
    # condition 1e5: single-precision factors refined reach 2e-12 in three steps; 3e7: the
    # refinement stalls near 1.5e-4 (kept: a Newton iteration judges its correction by the
    # next residual); 1e9: it is useless (about 1, above SINGLE_RESIDUAL) and the solver
    # factorises the matrix again in double precision.  Reference: numpy's dense solve
    from skfem_dielectric.linalg.linear import SINGLE_RESIDUAL
    rng = np.random.default_rng(5)
    for top, falls, lo, hi in ((5.0, 0, 0.0, 1e-11), (7.5, 0, 1e-6, 1e-3),
                               (9.0, 1, 0.0, 1e-7)):
        Q, _ = np.linalg.qr(rng.standard_normal((30, 30)))
        d = np.logspace(0, -top, 30) * np.where(np.arange(30) % 3 == 0, -1.0, 1.0)
        A = Q @ np.diag(d) @ Q.T
        A = sp.csr_matrix((A + A.T) / 2)
        b = np.ones(30)
        s = PardisoSolver(precision="single", refine=3)
        x = s.solve(A, b)
        assert s.fallbacks == falls
        rel = np.linalg.norm(A @ x - b) / np.linalg.norm(b)
        assert lo <= rel <= hi and rel <= SINGLE_RESIDUAL
        assert s.last_residual == pytest.approx(rel, rel=1e-6, abs=1e-16)
        ref = np.linalg.solve(A.toarray(), b)
        assert np.linalg.norm(x - ref) <= 10.0 ** (top - 7.0) * np.linalg.norm(ref)
        assert s.inertia == (20, 10, 0)

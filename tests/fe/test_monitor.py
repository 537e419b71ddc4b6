"""Stability of every converged ramp state on the ramp's own factorisation.

References: dense eigenvalues of the same tangents (the count by Sylvester's law; the
lowest pencil eigenvalues from the inverse of the dense tangent, as in test_stability.py),
the states of the same ramp without the analysis (Newton tolerance), and a dense inertia
for the SuperLU factors.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import skfem_dielectric as fe
from skfem_dielectric.linalg.linear import get_linear_solver
from skfem_dielectric.linalg.solver_base import SuperLUSolver
from skfem_dielectric.linalg.inertia import constrained_order, tangent_inertia
from skfem_dielectric.stability.analysis import lowest_modes, metric_matrix

SOLVERS = ["superlu"] + (["pardiso"] if fe.linalg.pardiso_available() else [])


def _pencil_eigenvalues(pb, K):
    """Finite eigenvalues of ``K w = lambda M w`` from the dense inverse (ascending)."""
    d = np.flatnonzero(metric_matrix(pb).diagonal() > 0)
    theta = np.linalg.eigvalsh(np.linalg.inv(K.toarray())[np.ix_(d, d)])
    theta = theta[np.abs(theta) > 1e-9 * np.abs(theta).max()]
    return np.sort(1.0 / theta)


def _quarter_ramp(solver, state_analysis=None):
    # the clamped quarter plate (full thickness, 4 x 1 x 2): clamp-corner modes make the
    # count 0 after the first pre-load step and > 0 later, so both branches of the modes
    # (shift 0 on the ramp's factors; spectrum slicing) are exercised
    pb = fe.gallery.keplinger_problem(elements=(4, 1, 2), symmetry="quarter")
    s = fe.keplinger_s(1.0, g=9.81)
    loads = [np.array([s * k / 3, 0.0]) for k in (1, 2, 3)] + [np.array([s, 1.0]),
                                                               np.array([s, 2.0])]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = fe.ramp(pb, loads, settings=fe.RampSettings(atol=1e-10, rtol=1e-11, chord=0.1),
                      linear_solver=solver, state_analysis=state_analysis)
    assert res.converged, res.reason
    return pb, res


@pytest.mark.parametrize("solver", SOLVERS)
def test_monitor_counts_and_modes_equal_the_dense_spectrum(solver):
    mon = fe.StabilityMonitor(k=6, tol=1e-12)
    pb, res = _quarter_ramp(solver, mon)
    plain = _quarter_ramp(solver)[1]
    counts = []
    for st, st0, (load, n_neg, n_zero, ev) in zip(res.steps, plain.steps, mon.history):
        K, _ = pb.assemble(st.x, st.load)
        dense = tangent_inertia(K, "dense")
        ref = _pencil_eigenvalues(pb, K)
        # the count is exact (Sylvester): the inertia of the ramp's factors
        assert st["n_negative"] == n_neg == dense[1] - pb.layout.n_multipliers
        assert st.inertia is None or tuple(st.inertia) == dense
        # Lanczos tolerance 1e-12 relative in theta = 1/(lambda - sigma); the dense
        # inverse of a tangent with condition ~1e8 is good to ~1e-8 relative
        assert ev == pytest.approx(ref[:6], rel=1e-7, abs=1e-12)
        assert st["lowest_eig"] == pytest.approx(ref[0], rel=1e-7)
        # the factorisation only starts the next Newton solve: the same states within the
        # Newton tolerance (1e-11 relative to the load scale)
        assert np.abs(st.x - st0.x).max() <= 1e-8 * max(1.0, np.abs(st0.x).max())
        counts.append(n_neg)
    assert min(counts) == 0 and max(counts) > 0
    # the state's factorisation replaces the next step's first one (at most one more per
    # target, and with chord steps usually none)
    assert res.factorisations <= plain.factorisations + len(res.steps)


@pytest.mark.parametrize("solver", SOLVERS)
def test_monitor_all_negative_gives_every_negative_mode(solver):
    # k = 0 with all_negative: one mode per negative eigenvalue (none without), equal to the
    # dense spectrum (as tangent_stability(all_negative=True), the harness's columns)
    mon = fe.StabilityMonitor(k=0, tol=1e-12, all_negative=True)
    pb, res = _quarter_ramp(solver, mon)
    for st, (load, n_neg, n_zero, ev) in zip(res.steps, mon.history):
        ref = _pencil_eigenvalues(pb, pb.assemble(st.x, st.load)[0])
        assert ev.size == n_neg
        assert ev == pytest.approx(ref[:n_neg], rel=1e-7, abs=1e-12)
    assert min(h[1] for h in mon.history) == 0 and max(h[1] for h in mon.history) > 0


def test_all_negative_with_extra_gives_the_next_modes_too():
    # all_negative with extra = 2: every negative mode and the two above it (the request
    # per symmetry class of the plate's buckling scan), equal to the dense spectrum
    pb, res = _quarter_ramp("superlu")
    signs = set()
    for st in res.steps:
        K, _ = pb.assemble(st.x, st.load)
        out = fe.stability.tangent_stability(pb, K, all_negative=True, extra=2, tol=1e-12)
        ref = _pencil_eigenvalues(pb, K)
        assert out.eigenvalues.size == out.n_negative + 2
        # Lanczos tolerance 1e-12 relative in theta; the dense inverse of a tangent with
        # condition ~1e8 is good to ~1e-8 relative
        assert out.eigenvalues == pytest.approx(ref[:out.n_negative + 2], rel=1e-7,
                                                abs=1e-12)
        signs.add(out.n_negative > 0)
    assert signs == {False, True}
    with pytest.raises(ValueError, match="extra must be an integer >= 0"):
        fe.stability.tangent_stability(pb, K, all_negative=True, extra=-1)


def test_reuse_factors_starts_with_a_chord_step():
    pb = fe.gallery.keplinger_problem(elements=(4, 1, 2))
    s = fe.keplinger_s(1.0, g=9.81)
    a, b = np.array([s, 0.0]), np.array([s, 0.5])
    x_a = fe.ramp(pb, [a / 2, a], settings=fe.RampSettings(atol=1e-10, rtol=1e-11)).x
    ref = fe.newton(lambda x: pb.assemble(x, b), x_a,
                    settings=fe.NewtonSettings(atol=1e-10, rtol=1e-11),
                    scale=pb.residual_scale(b))
    solver = get_linear_solver("superlu")
    K, _ = pb.assemble(x_a, a)
    solver.solve(K, np.zeros(pb.ndofs))
    nr = fe.newton(lambda x: pb.assemble(x, b), x_a, residual=lambda x: pb.residual(x, b),
                   linear_solver=solver,
                   settings=fe.NewtonSettings(atol=1e-10, rtol=1e-11, chord=0.1),
                   scale=pb.residual_scale(b), reuse_factors=True)
    assert nr.converged and ref.converged
    assert nr.chord_steps >= 1 and nr.factorisations < ref.factorisations
    # both converge to the same state within the Newton tolerance
    assert np.abs(nr.x - ref.x).max() <= 1e-8 * np.abs(ref.x).max()


def test_superlu_factor_inertia_is_the_dense_inertia():
    rng = np.random.default_rng(2)
    A = rng.standard_normal((30, 30))
    A = A @ A.T + 30 * np.eye(30) - 40 * np.diag(rng.random(30) < 0.3)
    B = rng.standard_normal((5, 30))
    K = sp.csr_matrix(np.block([[A, B.T], [B, -np.eye(5)]]))
    sol = SuperLUSolver()
    assert sol.factor_inertia() is None          # nothing factorised yet
    sol.solve(K, np.ones(35))
    # this matrix keeps to diagonal pivots (equal row and column permutations), so
    # U = D L^T and the signs of diag(U) are the eigenvalue signs (30 positive, 5 negative)
    assert sol.factor_inertia() == tangent_inertia(K, "dense") == (30, 5, 0)


def test_monitor_bad_input():
    with pytest.raises(ValueError, match="k"):
        fe.StabilityMonitor(k=-1)
    with pytest.raises(ValueError, match="tol"):
        fe.StabilityMonitor(tol=0.0)
    pb = fe.gallery.keplinger_problem(elements=(2, 1, 1),
                                      options=fe.PlateOptions(coupling="maxwell"))
    with pytest.raises(ValueError, match="not symmetric"):
        fe.StabilityMonitor()(pb, pb.initial_state(), (0.0, 0.0), None, None)
    pb = fe.gallery.keplinger_problem(elements=(2, 1, 1))
    K, _ = pb.assemble(pb.initial_state(), (0.0, 0.0))
    with pytest.raises(ValueError, match="sigma_start, sigma_growth, shift_solver, v0"):
        fe.stability.tangent_stability(pb, K, k=1, sigma0=1.0)
    with pytest.raises(ValueError, match="state_analysis"):
        fe.ramp(pb, [(0.1, 0.0)], state_analysis=3)


def test_constrained_order_gives_the_inertia_where_minimum_degree_fails():
    # a saddle-point matrix [[A, B^T], [B, 0]] (A indefinite, B a sparse coupling): a
    # minimum-degree order may eliminate a zero-diagonal unknown first (SuperLU then needs
    # an off-diagonal pivot); the constrained order puts each after its neighbours
    rng = np.random.default_rng(7)
    n, m = 80, 12
    A = sp.random(n, n, density=0.08, random_state=rng)
    A = (A + A.T + sp.diags(rng.uniform(-1.0, 3.0, n))).tocsr()
    B = sp.random(m, n, density=0.1, random_state=rng) + sp.eye(m, n)
    K = sp.bmat([[A, B.T], [B, None]]).tocsr()
    order = constrained_order(K)
    where = np.empty(K.shape[0], int)
    where[order] = np.arange(K.shape[0])
    for i in range(n, n + m):     # every multiplier after all its neighbours
        nb = K.indices[K.indptr[i]:K.indptr[i + 1]]
        assert where[i] > where[nb].max()
    lu = spla.splu(sp.csc_matrix(K)[order][:, order], permc_spec="NATURAL",
                   diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    assert np.array_equal(lu.perm_r, lu.perm_c)
    d = lu.U.diagonal()
    # Sylvester: the signs of the pivots are the dense eigenvalue signs
    assert (int(np.sum(d > 0)), int(np.sum(d < 0)), 0) == tangent_inertia(K, "dense")
    assert tangent_inertia(K, "superlu") == tangent_inertia(K, "dense")


def test_lowest_modes_with_a_negative_eigenvalue_just_below_zero():
    # a negative eigenvalue between the default shift (-1e-8 max|K|) and zero is found by
    # both parts of the spectrum (slicing and the shift just below zero); it must be
    # counted once and the k lowest returned (a diagonal pencil: the reference is exact)
    lam = np.linspace(0.1, 10.0, 200)
    lam[0] = -1e-10
    K = sp.diags(lam).tocsr()
    M = sp.identity(200, format="csr")
    vals, vecs = lowest_modes(K, M, 5, n_negative=1, tol=1e-12)
    assert vals.shape == (5,) and vecs.shape == (200, 5)
    # ARPACK's tolerance 1e-12 relative in theta = 1/(lambda - sigma)
    assert vals == pytest.approx(np.sort(lam)[:5], rel=1e-9, abs=1e-14)

"""The scatter map against an independent scipy COO assembly."""

import numpy as np
import pytest
import scipy.sparse as sp

from skfem_dielectric.fem.assembly import DofReduction, ScatterMap
from skfem_dielectric.fem.runtime import blas_threads, single_threaded_blas


def _connectivity(rng, nel=3000, m=20, n_full=4000):
    dofs = rng.integers(0, n_full, size=(nel, m))
    red = DofReduction(n_full, fixed=rng.choice(n_full, 50, replace=False),
                       tied=[np.arange(10, 20)])
    return red.index[dofs], red.n


def test_scatter_matches_coo_assembly():
    rng = np.random.default_rng(3)
    dofs, n = _connectivity(rng)
    Ke = rng.standard_normal(dofs.shape + (dofs.shape[1],))
    sc = ScatterMap(dofs, n)
    K = sc.matrix(Ke)
    # reference: COO with the eliminated (-1) rows/columns dropped, duplicates summed
    r = np.broadcast_to(dofs[:, :, None], Ke.shape)
    c = np.broadcast_to(dofs[:, None, :], Ke.shape)
    ok = (r >= 0) & (c >= 0)
    ref = sp.coo_matrix((Ke[ok], (r[ok], c[ok])), shape=(n, n)).tocsr()
    # summation order differs: round-off only
    assert abs(K - ref).max() <= 1e-12 * abs(ref).max()
    assert K.nnz == ref.nnz and K.has_sorted_indices
    # the returned matrices share the read-only pattern
    K2 = sc.csr(np.zeros(sc.nnz))
    assert np.shares_memory(K2.indices, K.indices) and not K.indices.flags.writeable


def test_block_positions_equal_plain_binary_search():
    # > 2^20 queries: the sorted-query path; the reference is np.searchsorted itself
    rng = np.random.default_rng(4)
    dofs, n = _connectivity(rng, nel=2000, m=30)
    sc = ScatterMap(dofs, n)
    rows = dofs[:, :, None, None]
    cols = dofs[:, None, None, :]
    pos = sc.positions(rows, np.broadcast_to(cols, (dofs.shape[0], 1, 2, 30)))
    assert pos.size > 2**20
    keys = np.where((rows >= 0) & (cols >= 0), rows * n + cols, -1)
    keys = np.broadcast_to(keys, pos.shape)
    ref = np.where(keys >= 0, np.searchsorted(sc._ukeys, keys), sc.nnz)
    assert np.array_equal(pos, ref)
    np.testing.assert_array_equal(sc.pos, sc.positions(dofs[:, :, None], dofs[:, None, :]))


def test_block_outside_the_pattern_is_an_error():
    sc = ScatterMap(np.array([[0, 1], [1, 2]]), 3)
    with pytest.raises(ValueError, match="outside the sparsity pattern"):
        sc.positions(np.array([0]), np.array([2]))


def test_shared_pattern_is_protected_and_copies_are_free():
    sc = ScatterMap(np.array([[0, 1], [1, 2]]), 3)
    K = sc.matrix(np.ones((2, 2, 2)))
    with pytest.raises(ValueError):
        K.eliminate_zeros()                  # would rewrite the pattern of every matrix
    K2 = K.copy()
    K2.data[:] = 0.0
    K2.eliminate_zeros()
    assert K2.nnz == 0 and K.nnz == 7        # 3x3 tridiagonal pattern untouched


def test_compact_scatter_map_gives_the_same_positions():
    rng = np.random.default_rng(3)
    dofs = rng.integers(-1, 40, size=(30, 6))
    sc = ScatterMap(dofs, 40)
    before = sc.positions(dofs[:, :, None], dofs[:, None, :])
    sc.compact()
    # rebuilt from indptr/indices: the same positions as from the kept keys
    np.testing.assert_array_equal(sc.positions(dofs[:, :, None], dofs[:, None, :]), before)


def test_single_threaded_blas_restores_the_thread_count():
    n = blas_threads()
    if n is None:
        pytest.skip("numpy does not use a bundled OpenBLAS here")
    with single_threaded_blas():
        assert blas_threads() == 1
    assert blas_threads() == n


def test_blas_thread_limit_reaches_scipys_openblas_and_restores_it():
    # scipy's bundled OpenBLAS (SuperLU, ARPACK) and numpy's: at most n threads inside,
    # the counts before restored after; the command line leaves no variable behind
    import os

    from skfem_dielectric.fem.runtime import _every_openblas, blas_thread_limit
    from validation.cli import main

    libs = _every_openblas()
    if not libs:
        pytest.skip("no bundled OpenBLAS here")
    before = [get() for get, _ in libs]
    with blas_thread_limit(1):
        assert [get() for get, _ in libs] == [1] * len(libs)
    assert [get() for get, _ in libs] == before
    with pytest.raises(ValueError, match="n must be an integer >= 1, got 0"):
        with blas_thread_limit(0):
            pass
    had = os.environ.pop("OPENBLAS_NUM_THREADS", None)
    try:
        assert main(["list"]) == 0
        assert "OPENBLAS_NUM_THREADS" not in os.environ
        assert [get() for get, _ in libs] == before
    finally:
        if had is not None:
            os.environ["OPENBLAS_NUM_THREADS"] = had


def test_ordered_sum_adds_the_chunks_in_order_whatever_the_threads():
    # chunks handed to the threads in reverse order still add in chunk order: the result
    # is the sequential sum bit for bit (and np.bincount's to round-off)
    from concurrent.futures import ThreadPoolExecutor

    from skfem_dielectric.fem.assembly import OrderedSum

    rng = np.random.default_rng(5)
    chunks = [(rng.integers(0, 101, 5000).astype(np.int32), rng.standard_normal(5000))
              for _ in range(6)]
    seq = OrderedSum(101)
    for k, (p, v) in enumerate(chunks):
        seq.add(k, p, v)
    par = OrderedSum(101)
    order = list(enumerate(chunks))
    with ThreadPoolExecutor(6) as pool:   # all waiting at once: no deadlock
        list(pool.map(lambda kc: par.add(kc[0], *kc[1]), order[::-1]))
    assert np.array_equal(seq.data, par.data)
    ref = sum(np.bincount(p, weights=v, minlength=101) for p, v in chunks)
    np.testing.assert_allclose(par.data, ref, rtol=1e-12, atol=1e-12)
    # a failed chunk passes its turn on (pos None): the later ones are still added
    skip = OrderedSum(101)
    skip.add(0, None, None)
    skip.add(1, *chunks[1])
    np.testing.assert_allclose(skip.data, np.bincount(chunks[1][0], weights=chunks[1][1],
                                                      minlength=101), rtol=1e-12, atol=1e-12)


def test_trim_heap_is_harmless():
    from skfem_dielectric.fem.runtime import trim_heap

    a = np.ones(1 << 22)
    del a
    assert trim_heap() in (True, False)
    assert trim_heap() in (True, False)        # found once, callable again
    # a small system's temporaries are not trimmed (the next allocations would fault the
    # memory in again): nothing is handed back below the threshold
    from skfem_dielectric.fem.runtime import TRIM_MIN_UNKNOWNS
    assert trim_heap(TRIM_MIN_UNKNOWNS - 1) is False


def _scatter_case(star: bool, seed: int):
    """Element dofs (reduced, eliminated ones -1) and two block pairs: 500 random 12-dof
    elements on 4000 dofs, or with ``star`` dof 0 coupled to 70 000 others (a row that
    does not fit 16-bit offsets)."""
    rng = np.random.default_rng(seed)
    if star:
        n_full = 70_001
        dofs = np.c_[np.zeros(n_full - 1, int), np.arange(1, n_full)]
    else:
        n_full = 4000
        dofs = rng.integers(0, n_full, size=(500, 12))
    red = DofReduction(n_full, fixed=rng.choice(np.arange(1, n_full), 40, replace=False),
                       tied=[np.arange(10, 20)])
    d = red.index[dofs]
    blocks = [(d[:, :, None], d[:, None, :]), (d[:, :1, None], d[:, None, 1:])]
    return rng, red, d, blocks


@pytest.mark.parametrize("star", [False, True])
def test_block_scatter_adds_as_the_positions(star):
    # 16-bit offsets in the rows (or, with a row of more than 65 535 entries, the 32-bit
    # positions) against np.bincount of ScatterMap.positions, eliminated dofs included
    from skfem_dielectric.fem.assembly import BlockScatter

    rng, red, d, blocks = _scatter_case(star, 11)
    sc = ScatterMap(d, red.n)
    bs = BlockScatter(sc, blocks)
    pos = np.concatenate([sc.positions(r, c).ravel() for r, c in blocks]).astype(np.int64)
    assert bs.size == pos.size and np.array_equal(bs.positions(), pos)
    vals = rng.standard_normal(pos.size)
    ref = np.bincount(pos, weights=vals, minlength=sc.nnz + 1)[:sc.nnz]
    out = np.zeros(sc.nnz + 1)
    bs.add_into(out, vals.copy())
    np.testing.assert_allclose(out[:sc.nnz], ref, rtol=1e-12, atol=1e-12)
    per = 4 if star else 2           # bytes per entry: 32-bit positions, or offsets
    assert bs.nbytes < (per + 0.6) * pos.size


@pytest.mark.parametrize("star", [False, True])
def test_upper_triangle_in_the_spare_layout(star):
    # the upper ScatterMap's blocks scattered through BlockScatter's spare layout (the
    # entries below the diagonal and the eliminated columns into each row's spare slot),
    # compacted in place: the upper triangle of the whole matrix, bit for bit (the same
    # entries added in the same order)
    from skfem_dielectric.fem.assembly import BlockScatter, drop_spare_slots

    rng, red, d, blocks = _scatter_case(star, 12)
    full, up = ScatterMap(d, red.n), ScatterMap(d, red.n, upper=True)
    vals = rng.standard_normal(sum(np.broadcast(r, c).size for r, c in blocks))
    whole = np.zeros(full.nnz + 1)
    BlockScatter(full, blocks).add_into(whole, vals.copy())
    K = full.csr(whole[:full.nnz])
    bs = BlockScatter(up, blocks, spare=True)
    assert not bs._drop.size and bs.size == vals.size
    data = np.zeros(up.nnz + up.n + 1)
    bs.add_into(data, vals.copy())
    U = up.csr(drop_spare_slots(data, up.indptr, block=97))
    T = sp.triu(K, format="csr")
    assert np.array_equal(U.indptr, T.indptr) and np.array_equal(U.indices, T.indices)
    assert np.array_equal(U.data, T.data)
    with pytest.raises(ValueError, match="data must have"):
        drop_spare_slots(np.zeros(up.nnz), up.indptr)


def test_symmetric_upper_products_and_whole_matrix():
    from skfem_dielectric.linalg.solver_base import SuperLUSolver
    from skfem_dielectric.linalg.symmetric import SymmetricUpper

    rng = np.random.default_rng(13)
    A = sp.random(60, 60, density=0.1, random_state=rng)
    K = (A + A.T + 60 * sp.identity(60)).tocsr()
    S = SymmetricUpper.from_full(K)
    x, X = rng.standard_normal(60), rng.standard_normal((60, 3))
    np.testing.assert_allclose(S @ x, K @ x, rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(S.dot(X), K @ X, rtol=1e-13, atol=1e-13)
    assert abs(S.tocsr() - K).max() == 0.0 and S.tocsr().has_sorted_indices
    # the solvers that read the whole matrix take it from the triangle
    b = np.arange(60.0)
    np.testing.assert_allclose(SuperLUSolver().solve(S, b), SuperLUSolver().solve(K, b),
                               rtol=1e-12)
    with pytest.raises(ValueError, match="below the diagonal"):
        SymmetricUpper(K)
    with pytest.raises(ValueError, match="square sparse"):
        SymmetricUpper(np.eye(3))
    with pytest.raises(ValueError, match="x must have 60 rows"):
        S @ np.ones(5)


def test_symmetric_upper_diagonal_with_missing_or_repeated_diagonal_entries():
    # the diagonal read off the rows' first entries must equal scipy's (which sums
    # duplicates and gives 0 where a row has no diagonal entry); the reference is the
    # dense matrix's diagonal
    from skfem_dielectric.linalg.symmetric import SymmetricUpper

    full = sp.csr_matrix(np.triu(np.arange(1.0, 17.0).reshape(4, 4)))
    gap = sp.csr_matrix(np.triu(np.arange(1.0, 17.0).reshape(4, 4)) - np.diag([0, 6, 0, 0]))
    cols = [0, 0, 1, 2, 2, 3]           # rows 0, 0, 1, 1, 2, 3: (0, 0) stored twice, 1 + 2
    dup = sp.csr_matrix((np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]), np.array(cols),
                         np.array([0, 2, 4, 5, 6])), shape=(4, 4))
    dup.has_sorted_indices = True
    for U, diag in ((full, [1.0, 6.0, 11.0, 16.0]), (gap, [1.0, 0.0, 11.0, 16.0]),
                    (dup, [3.0, 3.0, 5.0, 6.0])):
        assert np.array_equal(SymmetricUpper(U).diagonal(), diag)
        assert np.array_equal(diag, U.toarray().diagonal())


def test_setup_cache_keeps_the_newest_entries():
    from skfem_dielectric.fem.runtime import SetupCache

    c = SetupCache(2)
    for k in "abc":
        assert c.put(k, k.upper()) == k.upper()
    # at most two entries, the oldest ("a") dropped first
    assert [c.get(k) for k in "abc"] == [None, "B", "C"]

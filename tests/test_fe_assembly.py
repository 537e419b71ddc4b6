"""The scatter map against an independent scipy COO assembly."""

import numpy as np
import pytest
import scipy.sparse as sp

from skfem_dielectric.assembly import (DofReduction, ScatterMap, blas_threads,
                                       single_threaded_blas)


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


def test_ordered_sum_adds_the_chunks_in_order_whatever_the_threads():
    # chunks handed to the threads in reverse order still add in chunk order: the result
    # is the sequential sum bit for bit (and np.bincount's to round-off)
    from concurrent.futures import ThreadPoolExecutor

    from skfem_dielectric.assembly import OrderedSum

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
    from skfem_dielectric.assembly import trim_heap

    a = np.ones(1 << 22)
    del a
    assert trim_heap() in (True, False)
    assert trim_heap() in (True, False)        # found once, callable again


@pytest.mark.parametrize("star", [False, True])
def test_block_scatter_adds_as_the_positions(star):
    # 16-bit offsets in the rows (or, with a row of more than 65 535 entries, the 32-bit
    # positions) against np.bincount of ScatterMap.positions, eliminated dofs included
    from skfem_dielectric.assembly import BlockScatter

    rng = np.random.default_rng(11)
    if star:      # dof 0 coupled to 70 000 others: its row does not fit 16-bit offsets
        n_full = 70_001
        dofs = np.c_[np.zeros(n_full - 1, int), np.arange(1, n_full)]
    else:
        n_full = 4000
        dofs = rng.integers(0, n_full, size=(500, 12))
    red = DofReduction(n_full, fixed=rng.choice(np.arange(1, n_full), 40, replace=False),
                       tied=[np.arange(10, 20)])
    d = red.index[dofs]
    sc = ScatterMap(d, red.n)
    blocks = [(d[:, :, None], d[:, None, :]), (d[:, :1, None], d[:, None, 1:])]
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

"""Fast assembly machinery: dof reduction and a precomputed COO -> CSR scatter map.

The FE models compute element matrices for all elements at once (batched numpy over
elements and quadrature points) and scatter them into a CSR matrix whose sparsity pattern
and scatter positions are computed once per mesh (:class:`ScatterMap`).  Dirichlet
conditions and tied dofs (e.g. a rigid clamp whose nodes share one displacement) are
handled by a :class:`DofReduction`: every full dof maps to one reduced unknown, or to ``-1``
if it is prescribed.  Scattering element contributions through the reduced map directly
gives ``P^T K P`` and ``P^T r`` of the prolongation ``x_full = P x_red + x_prescribed``
without forming ``P``.

These classes are problem-agnostic and shared by all FE models of the package; where the
assembly runs (threads, BLAS threads, the heap, the set-up cache) is
:mod:`~skfem_dielectric.fem.runtime`.
"""

from __future__ import annotations

import threading

import numpy as np
import scipy.sparse as sp

__all__ = ["BlockScatter", "DofReduction", "OrderedSum", "ScatterMap", "drop_spare_slots"]


class DofReduction:
    """Map from full dofs to reduced unknowns (prescribed dofs -> ``-1``).

    Parameters
    ----------
    n_full
        Number of full dofs.
    fixed
        Indices of prescribed dofs (their values come from ``x_prescribed``).
    tied
        List of index arrays; the dofs of each array share one reduced unknown.

    Attributes
    ----------
    index
        ``index[i]`` = reduced unknown of full dof ``i`` or ``-1``.
    n
        Number of reduced unknowns.
    """

    def __init__(self, n_full: int, fixed: np.ndarray | None = None,
                 tied: list[np.ndarray] | None = None):
        fixed = np.unique(np.asarray([] if fixed is None else fixed, dtype=np.int64))
        tied = [np.unique(np.asarray(t, dtype=np.int64)) for t in (tied or [])]
        label = np.arange(n_full, dtype=np.int64)
        for t in tied:
            if np.intersect1d(t, fixed).size:
                raise ValueError("tied dofs must not be prescribed")
            label[t] = t[0]
        free = np.ones(n_full, dtype=bool)
        free[fixed] = False
        reps = np.unique(label[free])
        index = np.full(n_full, -1, dtype=np.int64)
        pos = np.searchsorted(reps, label[free])
        index[free] = pos
        self.index = index
        self.n = int(reps.size)
        self.n_full = int(n_full)
        self.fixed = fixed
        self._free = free
        self._rep_of = reps  # full index representing each reduced unknown

    def expand(self, x_red: np.ndarray, x_prescribed: np.ndarray | None = None) -> np.ndarray:
        """Full vector ``P x_red + x_prescribed`` (prescribed values taken on fixed dofs)."""
        x = np.zeros(self.n_full) if x_prescribed is None else np.array(x_prescribed, float)
        x[self._free] = x_red[self.index[self._free]]
        return x

    def restrict(self, x_full: np.ndarray) -> np.ndarray:
        """Reduced vector taking, for each unknown, the value of its representative dof."""
        return np.asarray(x_full, dtype=float)[self._rep_of].copy()

    def reduce(self, r_full: np.ndarray) -> np.ndarray:
        """``P^T r_full``: sums over tied dofs, drops prescribed ones."""
        return np.bincount(self.index[self._free], weights=r_full[self._free],
                           minlength=self.n)


class ScatterMap:
    """Precomputed scatter of square element matrices into a reduced CSR matrix.

    Parameters
    ----------
    dofs
        ``(nel, m)`` reduced unknown of each element-local dof (``-1`` = eliminated).
    n
        Number of reduced unknowns.
    upper
        Keep only the upper triangle (column >= row, the diagonal included): the entries
        below the diagonal count as eliminated (the storage a symmetric solver reads).

    Notes
    -----
    The pattern is built once by sorting the row-major keys; afterwards :meth:`matrix` is
    one ``np.bincount`` over all element entries.  Repeated indices (tied
    dofs) are summed, as the reduction requires.
    """

    def __init__(self, dofs: np.ndarray, n: int, upper: bool = False):
        dofs = np.asarray(dofs, dtype=np.int64)
        self.dofs = dofs
        self.n = int(n)
        self.upper = bool(upper)
        nel, m = dofs.shape
        # sorted unique row-major keys of the valid (row, col) pairs: np.sort + a diff,
        # faster than np.unique (docs/performance.md)
        keys = self._keys(dofs[:, :, None], dofs[:, None, :]).ravel()
        keys = np.sort(keys[keys >= 0])
        ukeys = keys[np.r_[True, keys[1:] != keys[:-1]]] if keys.size else keys
        self.nnz = int(ukeys.size)
        self._ukeys: np.ndarray | None = ukeys
        self._dtype = np.int32 if self.nnz < 2**31 - 1 else np.int64
        self._pos = None
        r = ukeys // self.n
        self.indices = (ukeys % self.n).astype(np.int32)
        self.indptr = np.concatenate([[0], np.cumsum(np.bincount(r, minlength=self.n))]
                                     ).astype(np.int32)
        self._vmask = dofs >= 0
        # shared by every matrix :meth:`csr` returns (no copy per Newton iteration);
        # read-only so that no caller can corrupt the pattern of the others
        self.indices.flags.writeable = False
        self.indptr.flags.writeable = False

    def compact(self) -> None:
        """Release the sorted keys of the pattern (8 bytes per nonzero) once the scatter
        positions are known; :meth:`positions` rebuilds them from ``indptr`` and
        ``indices`` when it is called again."""
        self._ukeys = None

    def _sorted_keys(self) -> np.ndarray:
        """Sorted row-major keys of the pattern (rebuilt after :meth:`compact`)."""
        if self._ukeys is None:
            rows = np.repeat(np.arange(self.n, dtype=np.int64), np.diff(self.indptr))
            self._ukeys = rows * self.n + self.indices
        return self._ukeys

    def _keys(self, rows, cols) -> np.ndarray:
        """Row-major keys ``row * n + col`` of broadcast index arrays, ``-1`` where either
        index is eliminated (or, for ``upper``, below the diagonal)."""
        rows, cols = np.broadcast_arrays(np.asarray(rows, np.int64), np.asarray(cols, np.int64))
        keep = (rows >= 0) & (cols >= rows) if self.upper else (rows >= 0) & (cols >= 0)
        return np.where(keep, rows * self.n + cols, -1)

    @property
    def pos(self) -> np.ndarray:
        """``(nel, m, m)`` scatter positions of dense element matrices (computed on first
        use; models that scatter element blocks through :meth:`positions` never need it)."""
        if self._pos is None:
            d = self.dofs
            self._pos = self.positions(d[:, :, None], d[:, None, :])
        return self._pos

    def positions(self, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """Scatter positions of an element block of any layout.

        ``rows`` and ``cols`` are broadcastable arrays of reduced indices (``-1`` =
        eliminated) whose broadcast shape is the block's layout, e.g. ``(nel, 27, 3, 3, 27)``
        for a displacement block stored as ``(i, a, b, j)``.  The entries must belong to the
        pattern.  Eliminated entries get the dummy position ``nnz``.  Use with
        :meth:`block_data`.
        """
        keys = self._keys(rows, cols)
        valid = keys >= 0
        pos = self._search(keys)
        pos[~valid] = self.nnz
        if np.any(valid) and (self.nnz == 0 or np.any(
                valid & (self._sorted_keys()[np.minimum(pos, self.nnz - 1)] != keys))):
            raise ValueError("block entries outside the sparsity pattern")
        return pos.astype(self._dtype)

    def _search(self, keys: np.ndarray) -> np.ndarray:
        """``np.searchsorted(self._ukeys, keys)``, through sorted queries when the key and
        the query index fit in 63 bits together (a merge instead of one binary search per
        key into the large key array: docs/performance.md)."""
        flat = keys.ravel()
        nbits = max(1, int(flat.size - 1).bit_length())
        top = int(self.n) * int(self.n)
        ukeys = self._sorted_keys()
        if flat.size < 2**20 or top.bit_length() + nbits > 62:
            return np.searchsorted(ukeys, keys)
        code = (np.maximum(flat, 0) << nbits) | np.arange(flat.size, dtype=np.int64)
        code.sort()
        order = code & ((1 << nbits) - 1)
        out = np.empty(flat.size, dtype=np.int64)
        out[order] = np.searchsorted(ukeys, code >> nbits)
        return out.reshape(keys.shape)

    def block_data(self, blocks: list[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
        """CSR data of ``sum`` over ``(positions, values)`` pairs of equal shapes."""
        out = np.zeros(self.nnz + 1)
        for pos, val in blocks:
            out += np.bincount(pos.ravel(), weights=np.asarray(val, float).ravel(),
                               minlength=self.nnz + 1)
        return out[: self.nnz]

    def data(self, Ke: np.ndarray, elements: slice | np.ndarray | None = None) -> np.ndarray:
        """CSR data array of ``sum_e Ke[e]`` (optionally only the given ``elements``,
        ``Ke`` then holds those elements' matrices)."""
        pos = self.pos if elements is None else self.pos[elements]
        return np.bincount(pos.ravel(), weights=np.asarray(Ke, float).ravel(),
                           minlength=self.nnz + 1)[: self.nnz]

    def csr(self, data: np.ndarray) -> sp.csr_matrix:
        """CSR matrix with the precomputed pattern and the given data.

        The matrices share the pattern arrays ``indices``/``indptr`` (read-only, sorted);
        each owns its ``data``.  Arithmetic, slicing, conversion and ``data`` updates work
        as usual; in-place *structural* changes (``eliminate_zeros``) raise ``ValueError``
        (read-only) — call them on ``K.copy()``."""
        K = sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))
        K.has_sorted_indices = True
        return K

    def matrix(self, Ke: np.ndarray) -> sp.csr_matrix:
        """Assemble all element matrices ``Ke`` of shape ``(nel, m, m)``."""
        return self.csr(self.data(Ke))

    def vector(self, re: np.ndarray) -> np.ndarray:
        """Assemble element vectors ``re`` of shape ``(nel, m)``."""
        return np.bincount(self.dofs[self._vmask], weights=np.asarray(re, float)[self._vmask],
                           minlength=self.n)


class OrderedSum:
    """One CSR data array that numbered element chunks add into, in chunk order.

    Worker threads compute the element blocks of their chunks in parallel; each then
    waits for its turn and adds its entries (``np.add.at`` through the chunk's 32-bit
    scatter positions, no conversion and no temporary), so that every entry is summed in
    the same order in every run and whatever the threads.  Replaces a partial sum of
    ``nnz`` entries per chunk (sizes: docs/performance.md).

    Parameters
    ----------
    size
        Length of the data array (``nnz + 1``: the last entry collects the eliminated
        entries' dummy position).
    vector_size
        Length of a vector summed the same way (the internal forces; one vector per
        chunk kept until the end grew with the number of chunks).
    """

    def __init__(self, size: int, vector_size: int = 0):
        self.data = np.zeros(int(size))
        self.vector = np.zeros(int(vector_size))
        self._cond = threading.Condition()
        self._next = 0

    def add(self, k: int, pos, values: np.ndarray | None, vpos: np.ndarray | None = None,
            vvalues: np.ndarray | None = None) -> None:
        """Add chunk ``k``'s ``values`` at ``pos`` (positions, or a :class:`BlockScatter`)
        and ``vvalues`` at ``vpos`` of the vector once chunks ``0 .. k-1`` are in;
        ``pos=None`` only passes the turn on (a chunk whose computation failed)."""
        with self._cond:
            self._cond.wait_for(lambda: self._next == k)
            try:
                if isinstance(pos, BlockScatter):
                    pos.add_into(self.data, values)
                elif pos is not None:
                    np.add.at(self.data, pos, values)
                if pos is not None and vpos is not None:
                    np.add.at(self.vector, vpos, vvalues)
            finally:
                self._next += 1
                self._cond.notify_all()


class BlockScatter:
    """Scatter positions of a chunk's element blocks, stored as 16-bit offsets in rows.

    An entry in row ``R`` of the pattern lands at ``indptr[R] + offset``; the offsets fit
    in 16 bits while every row has fewer than 65 535 entries (up to ~600 for the Q2/Q1/Q2
    plate), half the memory of 32-bit positions (docs/performance.md); the row
    starts are gathered block by block from the rows of the element (one per 81 entries of
    the u-u block).  Otherwise the 32-bit positions are kept.

    Parameters
    ----------
    scatter
        The :class:`ScatterMap` (before :meth:`ScatterMap.compact`, or rebuilding its
        keys).
    blocks
        ``(rows, cols)`` pairs of broadcastable reduced indices (``-1`` = eliminated), one
        per block, in the order of the chunk's flat value buffer.
    spare
        Scatter into the *spare layout*: row ``R`` of the pattern followed by one spare
        slot (entries ``indptr[R] + R ... indptr[R + 1] + R``, ``nnz + n + 1`` in all), which
        collects the row's entries outside the pattern (eliminated columns, and the
        entries below the diagonal of an ``upper`` map: half of every element block, which
        would otherwise need a list of their places); :func:`drop_spare_slots` turns the
        data into CSR data.

    Notes
    -----
    An eliminated row goes to the dummy entry at the end (``nnz``, or ``nnz + n`` in the
    spare layout).  Without ``spare``, an eliminated column in a kept row gets offset 0
    and its value is set to zero before the scatter, which leaves every sum as it is.
    """

    def __init__(self, scatter: ScatterMap, blocks: list[tuple[np.ndarray, np.ndarray]],
                 spare: bool = False):
        self.nnz = scatter.nnz
        self.spare = bool(spare)
        ip = scatter.indptr
        self._indptr = ip + np.arange(ip.size, dtype=ip.dtype) if spare else ip
        wide = scatter.n and int(np.diff(ip).max()) + self.spare >= 0xFFFF
        self._parts, drop, o = [], [], 0
        for rows, cols in blocks:
            pos = scatter.positions(rows, cols)
            r = np.broadcast_to(np.asarray(rows), pos.shape)
            cut = (pos == self.nnz) & (r >= 0)
            if spare:        # shift by the spare slots before; outside the pattern: the row's
                pos = pos + np.where(r >= 0, r, scatter.n)
                pos[cut] = self._indptr[r[cut] + 1] - 1
            if wide:
                self._parts.append((None, pos.ravel()))
            else:
                off = pos - self._indptr[r]
                if not spare:
                    off[cut] = 0
                    drop.append(o + np.flatnonzero(cut.ravel()))
                self._parts.append((np.asarray(rows, dtype=np.int32), off.astype(np.uint16)))
            o += pos.size
        self.size = o
        self._drop = np.concatenate(drop).astype(np.intp) if drop else np.zeros(0, np.intp)

    def _block_positions(self, rows, off) -> np.ndarray:
        return off if rows is None else (self._indptr[rows] + off).ravel()

    def positions(self) -> np.ndarray:
        """Flat 64-bit positions (``nnz`` for every eliminated entry; in the spare layout
        the positions there, a row's spare slot for the entries outside the pattern)."""
        pos = np.concatenate([self._block_positions(r, o).astype(np.int64)
                              for r, o in self._parts])
        pos[self._drop] = self.nnz
        return pos

    def add_into(self, data: np.ndarray, values: np.ndarray) -> None:
        """``data[pos] += values`` entry by entry (``np.add.at``); zeroes the entries of
        eliminated columns in ``values``."""
        values[self._drop] = 0.0
        o = 0
        for rows, off in self._parts:
            n = off.size
            np.add.at(data, self._block_positions(rows, off), values[o:o + n])
            o += n

    @property
    def nbytes(self) -> int:
        """Bytes held (offsets or positions, the rows of the blocks, the dropped entries)."""
        return self._drop.nbytes + sum(o.nbytes + (0 if r is None else r.nbytes)
                                       for r, o in self._parts)


def drop_spare_slots(data: np.ndarray, indptr: np.ndarray, block: int = 1 << 20) -> np.ndarray:
    """CSR data from data in the spare layout of :class:`BlockScatter` (every row followed
    by one spare slot), moved in place.

    Parameters
    ----------
    data
        ``nnz + n + 1`` entries (or more) in the spare layout of the pattern ``indptr``.
    indptr
        Row starts of the pattern (``n + 1`` entries).
    block
        Entries moved per step (the temporary copy of one group of rows).

    Returns
    -------
    numpy.ndarray
        The first ``nnz`` entries of ``data`` (a view), the rows without their spare slots.
    """
    n = indptr.size - 1
    if data.size < int(indptr[-1]) + n:
        raise ValueError(f"data must have at least nnz + n = {int(indptr[-1]) + n} entries "
                         f"in the spare layout, got {data.size}")
    r0 = 0
    while r0 < n:
        r1 = int(np.searchsorted(indptr, int(indptr[r0]) + block, side="right"))
        r1 = min(n, max(r1, r0 + 1))
        a, b = int(indptr[r0]), int(indptr[r1])
        src = data[a + r0: b + r1]
        keep = np.ones(src.size, dtype=bool)
        keep[indptr[r0 + 1: r1 + 1] + np.arange(r0, r1) - (a + r0)] = False
        data[a:b] = src[keep]         # a copy: the rows move left, over their old places
        r0 = r1
    return data[: int(indptr[-1])]

"""Sparse linear solvers for the Newton iterations.

A linear solver is any object with a method ``solve(K, b) -> x`` for a square sparse matrix
``K`` (CSR, symmetric, possibly indefinite: the mixed and coupled tangents are saddle-point
matrices) and a dense right-hand side ``b``.  Solvers may keep state between calls (for
instance the symbolic factorisation of a fixed sparsity pattern) and expose the
*inertia* of the last factorised matrix, which the stability check uses.

Two implementations:

``SuperLUSolver``
    scipy's SuperLU (``scipy.sparse.linalg.splu``) with a fill-reducing column ordering
    (``permc_spec``, default ``"MMD_AT_PLUS_A"`` which suits the structurally symmetric
    pattern).  No extra dependency.
``PardisoLUSolver``
    MKL PARDISO as a general (non-symmetric) LU, for the tangents of follower loads
    (Maxwell-traction coupling); it reports no inertia.
``PardisoSolver``
    MKL PARDISO through ``pypardiso`` (the ``fast`` extra), used as a real symmetric
    indefinite solver (``mtype=-2``, upper triangle only) with the symbolic analysis done
    once per sparsity pattern and reused for all later numerical factorisations.  PARDISO
    reports the matrix inertia, used by the stability verdict.  The MKL library is located
    once per process (:func:`new_pypardiso_solver`); each solver keeps its own PARDISO
    handle and factorisation.

Use :func:`get_linear_solver` to obtain one by name.
"""

from __future__ import annotations

import copy
import ctypes
import os

import numpy as np
import scipy.sparse as sp

from ..fem.runtime import trim_heap
from .solver_base import (PRECISIONS, LinearSolver, SuperLUSolver, count_factorisation,
                          whole_matrix)
from .symmetric import SymmetricUpper, same_memory, same_pattern

__all__ = ["PardisoSolver", "PardisoLUSolver", "get_linear_solver", "nonsymmetric_solver",
           "pardiso_available", "new_pypardiso_solver"]


def _compress_into(keep: np.ndarray, a: np.ndarray, out: np.ndarray,
                   block: int = 1 << 20) -> None:
    """``out[:] = a[keep]`` block by block (``np.compress`` of the whole array makes a
    temporary 64-bit index of every kept entry: docs/performance.md)."""
    o = 0
    for i in range(0, a.size, block):
        m = keep[i:i + block]
        k = int(np.count_nonzero(m))
        np.compress(m, a[i:i + block], out=out[o:o + k])
        o += k


def _quiet_mkl_threads() -> None:
    """Let MKL's OpenMP threads sleep as soon as a PARDISO call returns.

    They otherwise spin for ``KMP_BLOCKTIME`` (default 200 ms) after every parallel region
    and kept both cores busy during the next (numpy-threaded) assembly, slowing it
    (docs/performance.md).  The variable is read when the OpenMP
    runtime starts, so this runs before ``pypardiso`` is imported; a value the user set
    wins.
    """
    os.environ.setdefault("KMP_BLOCKTIME", "0")


def pardiso_available() -> bool:
    """True if ``pypardiso`` (MKL PARDISO) can be imported."""
    _quiet_mkl_threads()
    try:
        import pypardiso  # noqa: F401
    except Exception:  # pragma: no cover - depends on the environment
        return False
    return True


def new_pypardiso_solver(mtype: int = 11):
    """A fresh ``pypardiso.PyPardisoSolver`` without repeating the library search.

    ``PyPardisoSolver()`` looks for the MKL runtime each time it is constructed (a
    recursive glob under ``sys.prefix``, slow beside a solve: docs/performance.md);
    ``import pypardiso`` already does
    so once for its module-level solver. The new solver shares that solver's loaded
    library function but gets its own PARDISO handle ``pt``, ``iparm``, ``perm``,
    matrix type and stored matrix, so solvers with different matrices keep separate
    factorisations.

    Parameters
    ----------
    mtype
        PARDISO matrix type (11: real non-symmetric, -2: real symmetric indefinite).

    Returns
    -------
    pypardiso.PyPardisoSolver
    """
    _quiet_mkl_threads()
    import pypardiso  # lazy: optional dependency
    from pypardiso.scipy_aliases import pypardiso_solver as loaded

    if not all(hasattr(loaded, a) for a in ("libmkl", "_mkl_pardiso", "_pt_type", "pt",
                                            "iparm", "perm", "factorized_A")):
        return pypardiso.PyPardisoSolver(mtype=mtype)   # unknown layout: the slow way
    ps = copy.copy(loaded)               # shares only the ctypes library handles
    ps.pt = np.zeros(64, dtype=loaded._pt_type[1])   # as PyPardisoSolver.__init__
    ps.iparm = np.zeros(64, dtype=np.int32)
    ps.perm = np.zeros(0, dtype=np.int32)
    ps.mtype = int(mtype)
    ps.phase = 13
    ps.msglvl = False
    ps.factorized_A = sp.csr_matrix((0, 0))
    ps._solve_transposed = False
    return ps


_ORDERINGS = {"minimum-degree": 0, "metis": 2, "parallel-metis": 3}   # PARDISO iparm(2)
#: with ``ordering="auto"``, systems of at least this many unknowns are ordered by nested
#: dissection (METIS), smaller ones by minimum degree: the crossover of the factors' fill
#: on the clamp-zone plates (docs/performance.md, "The ordering of the factors")
METIS_MIN_UNKNOWNS = 100_000
#: relative residual beyond which a solve with single-precision factors, refined, is
#: useless and the matrix is factorised again in double precision (the robust fallback)
SINGLE_RESIDUAL = 1e-3


class PardisoSolver(LinearSolver):
    """MKL PARDISO (via ``pypardiso``), real symmetric indefinite, analysis reused.

    The symbolic analysis (ordering, phase 11) is done the first time a sparsity pattern is
    seen and reused while ``K.indptr``/``K.indices`` stay the same; each call then only
    runs the numerical factorisation (phase 22) and the solve (phase 33).  The matrix must be
    symmetric; only its upper triangle is passed to PARDISO.

    Parameters
    ----------
    refine
        Maximum number of iterative-refinement steps (default 2; 1 with single-precision
        factors, see ``precision``); refinement recovers the accuracy
        lost by pivot perturbation on saddle-point matrices.  A step is taken while the
        relative residual ``||b - K x|| / ||b||`` exceeds ``refine_tol`` (a solve that
        is already there, as on the plates, whose factorisations perturb no pivot, costs
        one product and no second solve).  The steps are done here, with the residual of
        the matrix passed to :meth:`solve` and a solve with the factors each, not by
        PARDISO (``iparm(8) = 0``), whose own refinement allocated a work array of the
        size of the factorised matrix in every solve (docs/performance.md).
    refine_tol
        Relative residual below which no refinement step is taken (default ``1e-13``).
    ordering
        Fill-reducing ordering (``iparm(2)``): ``"auto"`` (default: ``"metis"`` for a
        system of at least :data:`METIS_MIN_UNKNOWNS` unknowns, else
        ``"minimum-degree"``; the one used is :attr:`chosen_ordering`),
        ``"minimum-degree"`` (on the 40 x 1 x 20 Keplinger plate, nearly a 2-D problem,
        13.2 M entries in the factors against 15.5 M for METIS), ``"metis"`` (nested
        dissection: half the entries of minimum degree on the 359,283 unknowns of the
        70 x 4 x 36 clamp-zone plate) or ``"parallel-metis"``; the fill per ordering:
        docs/performance.md.
    precision
        Precision of the factors: ``"double"`` (default) or ``"single"`` (PARDISO
        ``iparm(28) = 1``: the matrix is factorised in single precision, in about half
        the time and with 0.7 times the memory of the factors); :meth:`solve` refines its
        solution in double precision with the matrix while that lowers the residual, up
        to ``refine_tol`` and ``refine`` steps (a solve of relative residual ``1e-6`` or
        so, then ``1e-10``, ``1e-13`` where the condition number is below about ``1e6``;
        on worse conditioned matrices the refinement stalls higher:
        :attr:`last_residual`).  One step by default: a Newton iteration needs no more
        (on the Keplinger ramp one step gave 165 iterations and 20 factorisations, three
        steps 176 and 21); ``refine=3`` for a solve to about ``1e-13``.  A
        matrix whose single-precision factorisation perturbed a pivot, or whose refined
        solution stays above :data:`SINGLE_RESIDUAL`, is factorised again in double
        precision (the fallback below).  :meth:`resolve` solves with the
        single-precision factors alone (an approximate correction, as the chord steps use
        it).  For the Newton solves of a ramp, whose next residual judges each
        correction: the states converge to the same tolerance.  A stability analysis or a
        count needs double-precision factors (its shifted solves and its inertia).
    matching
        Weighted matching in the analysis (``iparm(13) = 1``; default ``False``): an
        analysis about three times as long (0.87 against 0.29 s on a tangent of the
        40 x 1 x 20 Keplinger plate), for an inertia that stays exact nearer a singular
        matrix: the counts of negative eigenvalues
        (:func:`~skfem_dielectric.linalg.inertia.counted_inertia`,
        :func:`~skfem_dielectric.linalg.inertia.inertia_factors`, the shifted
        factorisations of the stability analyses) use it.  Without it the count of a
        Q2-P0 strip's tangent near its first negative charge flips within a band of
        4e-8 of the charge (not monotone in it); with it, as with SuperLU's, it does not.

    Notes
    -----
    After each factorisation ``inertia = (n_positive, n_negative, n_zero)`` is read from
    PARDISO ``iparm(22)``, ``iparm(23)`` (Sylvester inertia of the factorised matrix).  The
    results may differ in the last bits between runs because MKL is multi-threaded.

    Pivoting: after the symmetric scaling of the analysis, without weighted matching
    unless ``matching`` (``iparm(13)``), the factorisation takes 1x1 diagonal pivots
    (``iparm(21) = 0``); a matrix whose factorisation had to perturb a pivot
    (``iparm(14) > 0``) is factorised again at once with weighted matching and
    Bunch-Kaufman 1x1 and 2x2 pivoting (``iparm(13) = iparm(21) = 1``) by a second solver
    with its own analysis (neither can change between an analysis and its
    factorisations; the first one's factors and analysis are freed before it), whose
    factors then serve :meth:`resolve` and the inertia; :attr:`fallbacks` counts them.
    On every converged state of the Keplinger ramps (eighth and full plate, up to
    ``D0 = 6.5``) the 1x1 and Bunch-Kaufman pivots give the same inertia and residuals and
    no perturbed pivot, and so do the factorisations with and without the matching
    (40 x 1 x 20, eighth and full plate, ``D0 = 0.5 ... 5.5``); the 1x1 pivots factorise
    in 0.7 times the time, and without the matching the
    analysis takes a third of the time and a factorisation 0.9 of it (docs/performance.md).
    """

    name = "pardiso"
    reads_upper = True
    _mtype = -2                      # real symmetric indefinite
    _pivoting = {10: 8, 21: 0}       # pivot perturbation 1e-8, 1x1 diagonal pivots
    _fallback = {13: 1, 21: 1}       # after a perturbed pivot: matching, Bunch-Kaufman

    def __init__(self, refine: int | None = None, ordering: str = "auto",
                 refine_tol: float = 1e-13, precision: str = "double",
                 matching: bool = False):
        if ordering not in (*_ORDERINGS, "auto"):
            raise ValueError(f"ordering must be one of {('auto', *_ORDERINGS)}, "
                             f"got {ordering!r}")
        if precision not in PRECISIONS:
            raise ValueError(f"precision must be one of {PRECISIONS}, got {precision!r}")
        self._ps = new_pypardiso_solver(mtype=self._mtype)   # library located once
        p = self._ps
        p.set_iparm(1, 1)    # use the iparm values below
        p.set_iparm(2, _ORDERINGS.get(ordering, 0))
        p.set_iparm(8, 0)    # no refinement inside PARDISO (see ``refine``)
        p.set_iparm(11, 1)   # (symmetric) scaling
        #: weighted matching in the analysis (``iparm(13)``)
        self.matching = bool(matching)
        p.set_iparm(13, int(self.matching))   # the fallback below always matches
        for i, v in self._pivoting.items():
            p.set_iparm(i, v)
        # zero-based index arrays: PARDISO reads the upper triangle's own indptr/indices
        # (no one-based copy; pypardiso's generic call adds one to them, so only where the
        # call below is used)
        self._direct = hasattr(p, "_mkl_pardiso")
        if self._direct:
            p.set_iparm(35, 1)
        #: precision of the factors, ``"double"`` or ``"single"``
        self.precision = precision
        self._single = precision == "single"
        if self._single:
            if not self._direct:
                raise ValueError("precision='single' needs the direct PARDISO call, which "
                                 "this pypardiso's layout does not offer")
            p.set_iparm(28, 1)
        self._a32: np.ndarray | None = None   # the single-precision values PARDISO reads
        self._pattern: tuple[np.ndarray, np.ndarray] | None = None
        self._ucache = None
        self.refine = int((1 if self._single else 2) if refine is None else refine)
        self.refine_tol = float(refine_tol)
        self.ordering = ordering
        #: the ordering of the last analysis (``ordering``, or what ``"auto"`` chose)
        self.chosen_ordering: str | None = None
        self._robust: PardisoSolver | None = None   # Bunch-Kaufman, for perturbed pivots
        self._active: PardisoSolver | None = None   # it holds the last factors
        self._last = None
        #: factorisations redone with Bunch-Kaufman pivoting after a perturbed 1x1 pivot
        #: (or a single-precision solve above :data:`SINGLE_RESIDUAL`)
        self.fallbacks = 0
        #: relative residual ``||b - K x|| / ||b||`` of the last :meth:`solve` (0 where
        #: ``refine = 0``: none computed)
        self.last_residual = 0.0
        self.inertia = None

    def _call(self, phase: int, A: sp.csr_matrix, b: np.ndarray) -> np.ndarray:
        """One PARDISO call with the zero-based int32 ``indptr``/``indices`` of ``A`` as
        they are (pypardiso would make one-based copies on every call: docs/performance.md);
        the heap is trimmed after a factorisation or a
        solve (:func:`~skfem_dielectric.fem.runtime.trim_heap`: their work arrays)."""
        ps = self._ps
        ps.set_phase(phase)
        if not self._direct:
            x = ps._call_pardiso(A, b)
        else:
            x = self._call_direct(phase, A, b)
        if phase in (22, 33):
            trim_heap(A.shape[0])
        return x

    def _call_direct(self, phase: int, A: sp.csr_matrix, b: np.ndarray) -> np.ndarray:
        ps = self._ps
        if self._single:
            # the values in single precision where the phase reads them (the analysis
            # scales with them), the right-hand side and the solution always
            if phase in (11, 22) or self._a32 is None or self._a32.size != A.data.size:
                self._a32 = A.data.astype(np.float32)
            a = self._a32
            fp = ctypes.POINTER(ctypes.c_float)
            b = b.astype(np.float32)
        else:
            a, fp = A.data, ctypes.POINTER(ctypes.c_double)
        x = np.zeros_like(b)
        err = ctypes.c_int32(0)
        i32 = ctypes.POINTER(ctypes.c_int32)
        ps._mkl_pardiso(ps.pt.ctypes.data_as(ctypes.POINTER(ps._pt_type[0])),
                        ctypes.byref(ctypes.c_int32(1)), ctypes.byref(ctypes.c_int32(1)),
                        ctypes.byref(ctypes.c_int32(ps.mtype)),
                        ctypes.byref(ctypes.c_int32(phase)),
                        ctypes.byref(ctypes.c_int32(A.shape[0])), a.ctypes.data_as(fp),
                        A.indptr.ctypes.data_as(i32), A.indices.ctypes.data_as(i32),
                        ps.perm.ctypes.data_as(i32),
                        ctypes.byref(ctypes.c_int32(1 if b.ndim == 1 else b.shape[1])),
                        ps.iparm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(0)),
                        b.ctypes.data_as(fp), x.ctypes.data_as(fp), ctypes.byref(err))
        if err.value != 0:
            raise RuntimeError(f"PARDISO error {err.value} in phase {phase}")
        return x.astype(np.float64) if self._single else x

    def _upper(self, K: sp.spmatrix) -> sp.csr_matrix:
        """Upper triangle of ``K`` (that of a :class:`SymmetricUpper` as it is, with int32
        indices); the selection is cached for a repeated CSR pattern, whose upper
        triangle's data are then overwritten in place (no second array while the old one
        is still referenced)."""
        if isinstance(K, SymmetricUpper):
            U = K.upper
            if U.indptr.dtype != np.int32 or U.indices.dtype != np.int32:
                U = sp.csr_matrix((U.data, U.indices.astype(np.int32),
                                   U.indptr.astype(np.int32)), shape=U.shape)
                U.has_sorted_indices = True
            return U
        K = sp.csr_matrix(K)
        c = self._ucache
        if (c is not None and c[0].shape == K.indptr.shape and c[1].shape == K.indices.shape
                and ((c[4] and same_memory(c[0], K.indptr) and same_memory(c[1], K.indices))
                     or (np.array_equal(c[0], K.indptr) and np.array_equal(c[1], K.indices)))):
            U = c[2]
            _compress_into(c[3], K.data, U.data)
            return U
        K.sort_indices()
        n = K.shape[0]
        rows = np.repeat(np.arange(n, dtype=np.int32), np.diff(K.indptr))
        keep = K.indices >= rows              # a mask: 1 byte per nonzero, not 8
        counts = np.bincount(rows[keep], minlength=n)
        del rows
        indptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int32)
        U = sp.csr_matrix((K.data[keep].astype(np.float64), K.indices[keep].astype(np.int32),
                           indptr), shape=K.shape)
        U.has_sorted_indices = True
        if U.indptr.dtype != np.int32 or U.indices.dtype != np.int32:   # PARDISO's int32
            U.indptr, U.indices = U.indptr.astype(np.int32), U.indices.astype(np.int32)
        U.indptr.flags.writeable = U.indices.flags.writeable = False   # the solver's own
        # a read-only pattern (shared by the matrices of a ScatterMap) is recognised by its
        # memory, in O(1); otherwise keep a copy and compare the contents
        shared = not (K.indptr.flags.writeable or K.indices.flags.writeable)
        self._ucache = ((K.indptr, K.indices) if shared else (K.indptr.copy(), K.indices.copy())
                        ) + (U, keep, shared)
        return U

    def _matrix(self, K: sp.spmatrix) -> sp.csr_matrix:
        """The CSR matrix PARDISO reads: the upper triangle (:meth:`_upper`)."""
        return self._upper(K)

    def _read_inertia(self, n: int) -> tuple[int, int, int] | None:
        """Sylvester inertia of the last factorisation, from ``iparm(22)``, ``iparm(23)``."""
        npos, nneg = int(self._ps.iparm[21]), int(self._ps.iparm[22])
        return npos, nneg, n - npos - nneg

    def solve(self, K: sp.spmatrix, b: np.ndarray) -> np.ndarray:
        """Factorise ``K`` (analysis reused for an unchanged pattern) and solve ``K x = b``."""
        U = self._matrix(K)
        b = np.asfortranarray(np.asarray(b, dtype=np.float64))
        if np.any(np.diff(U.indptr) == 0):
            raise ValueError("matrix is singular: it has an empty row")
        same = self._pattern is not None and same_pattern(self._pattern, U)
        if not same:
            self._free_analysis()     # the old pattern's analysis and factors
            self.chosen_ordering = self._ordering_for(U.shape[0])
            self._ps.set_iparm(2, _ORDERINGS[self.chosen_ordering])
            self._call(11, U, b)
            # a read-only pattern (that of a ScatterMap, or the solver's own selection) is
            # recognised by its memory; otherwise keep a copy to compare with
            self._pattern = ((U.indptr, U.indices) if not (U.indptr.flags.writeable
                                                           or U.indices.flags.writeable)
                             else (U.indptr.copy(), U.indices.copy()))
        if self._robust is not None:
            self._robust.discard()      # its factors were of an earlier matrix
        self._active = None
        self._call(22, U, b)
        count_factorisation()
        if self._fallback and int(self._ps.iparm[13]) > 0:
            return self._fall_back(K, b)
        self.inertia = self._read_inertia(K.shape[0])
        x = self._call(33, U, b)
        self._last = U
        x, self.last_residual = self._refined(K, b, x)
        if self._single and self._fallback and not self.last_residual <= SINGLE_RESIDUAL:
            return self._fall_back(K, b)   # single precision did not reach it
        return np.ascontiguousarray(x)

    def _fall_back(self, K: sp.spmatrix, b: np.ndarray) -> np.ndarray:
        """Factorise ``K`` again with the robust solver (Bunch-Kaufman pivoting and weighted
        matching, double precision), which needs its own analysis (a second PARDISO
        handle): this handle's factors and analysis are freed first (not held beside the
        second's)."""
        self._free_analysis()
        self._last = None
        robust = self._robust_solver()
        x = robust.solve(K, b)
        self._active, self.inertia = robust, robust.inertia
        self.last_residual = robust.last_residual
        self.fallbacks += 1
        return x

    def _ordering_for(self, n: int) -> str:
        """The ordering of an analysis of ``n`` unknowns."""
        if self.ordering != "auto":
            return self.ordering
        return "metis" if n >= METIS_MIN_UNKNOWNS else "minimum-degree"

    def perturbed_pivots(self) -> int:
        """Pivots the last factorisation perturbed (PARDISO ``iparm(14)``; that of the
        Bunch-Kaufman factorisation where the 1x1 pivots perturbed one)."""
        if self._active is not None:
            return self._active.perturbed_pivots()
        return int(self._ps.iparm[13])

    def _robust_solver(self) -> "PardisoSolver":
        """The solver with Bunch-Kaufman pivoting that factorises the matrices whose 1x1
        pivots were perturbed (made on first use; its analysis is kept)."""
        if self._robust is None:
            robust = PardisoSolver(refine=self.refine, ordering=self.ordering,
                                   refine_tol=self.refine_tol)
            for i, v in self._fallback.items():
                robust._ps.set_iparm(i, v)
            robust._fallback = {}
            self._robust = robust
        return self._robust

    def _refined(self, K: sp.csr_matrix, b: np.ndarray, x: np.ndarray
                 ) -> tuple[np.ndarray, float]:
        """Up to ``refine`` steps ``x += K^-1 (b - K x)`` with the factors, while the
        relative residual exceeds ``refine_tol`` and they lower it; the solution and its
        relative residual (0 without refinement, which computes none)."""
        if self.refine <= 0:
            return x, 0.0
        bn = float(np.linalg.norm(b))
        r = b - K @ x
        rn = float(np.linalg.norm(r))
        floor = max(self.refine_tol, 4.0 * np.finfo(float).eps) * bn
        for _ in range(self.refine):
            if not rn > floor:
                break
            xt = x + self._call(33, self._last, np.asfortranarray(r))
            rt = b - K @ xt
            rtn = float(np.linalg.norm(rt))
            if not rtn < rn:
                break
            x, r, rn = xt, rt, rtn
        return x, (rn / bn if bn > 0 else 0.0)

    def discard(self) -> None:
        """Free the numerical factorisation (PARDISO phase 0: a part of the factors'
        memory, docs/performance.md; the analysis is kept) and the matrix it
        belongs to, so that they are not held while the next tangent is assembled and
        factorised; :meth:`resolve` returns ``None`` until the next :meth:`solve`."""
        if self._active is not None:
            self._active.discard()
            self._active = None
        U = getattr(self, "_last", None)
        if U is None:
            return
        self._last = None
        self._call(0, U, np.zeros(U.shape[0]))
        trim_heap(U.shape[0])

    def release(self) -> None:
        """Free the factorisation and the analysis (PARDISO phase -1: all of the
        solver's memory): the next :meth:`solve` analyses its matrix again.  For a solver
        that waits while other large systems are factorised (a ramp's, during the counts
        of a state)."""
        self.discard()
        if self._robust is not None:
            self._robust.release()
        if self._free_analysis():
            trim_heap()

    def _free_analysis(self) -> bool:
        """PARDISO phase -1 (the analysis and any factors) where an analysis is held;
        whether one was."""
        if self._pattern is None:
            return False
        self._call(-1, sp.identity(1, format="csr"), np.zeros(1))
        self._pattern = None
        return True

    def resolve(self, b: np.ndarray) -> np.ndarray | None:
        """Solve with the last numerical factorisation (PARDISO phase 33), without
        iterative refinement: the callers (chord steps, the monotonicity test of
        :func:`~skfem_dielectric.solvers.newton.newton`) use the old factors for an approximate
        correction, which refinement against the old matrix does not improve."""
        if self._active is not None:
            return self._active.resolve(b)
        U = getattr(self, "_last", None)
        if U is None:
            return None
        b = np.asfortranarray(np.asarray(b, dtype=np.float64))
        return np.ascontiguousarray(self._call(33, U, b))

    def __del__(self):  # pragma: no cover - cleanup
        try:
            self._free_analysis()
        except Exception:
            pass


class PardisoLUSolver(PardisoSolver):
    """MKL PARDISO for non-symmetric tangents (``mtype = 11``, the whole matrix).

    The symmetric-indefinite :class:`PardisoSolver` reads only the upper triangle, which is
    wrong for the follower loads of the Maxwell-traction coupling; this one factorises the
    whole matrix (LU with PARDISO's defaults for non-symmetric matrices: pivot perturbation
    ``1e-13``, scaling and weighted matching).  Like :class:`PardisoSolver` it keeps the
    symbolic analysis while the sparsity pattern stays the same, solves again with the last
    factors (:meth:`~PardisoSolver.resolve`, the chord steps of
    :func:`~skfem_dielectric.solvers.newton.newton`), frees them on
    :meth:`~PardisoSolver.discard` and refines the solution with the matrix.  It reports no
    inertia (a non-symmetric matrix has no stability verdict).

    Parameters
    ----------
    refine
        Maximum iterative-refinement steps per solve (see :class:`PardisoSolver`).
    ordering
        Fill-reducing ordering, as for :class:`PardisoSolver`.
    """

    name = "pardiso-lu"
    reads_upper = False
    _mtype = 11                      # real non-symmetric
    _pivoting = {10: 13}             # pivot perturbation 1e-13 (the non-symmetric default)
    _fallback: dict = {}

    def _matrix(self, K: sp.spmatrix) -> sp.csr_matrix:
        """The whole matrix as CSR with sorted int32 indices (``K``'s own arrays where
        they already are)."""
        A = sp.csr_matrix(whole_matrix(K))
        if A.indptr.dtype != np.int32 or A.indices.dtype != np.int32 \
                or not A.has_sorted_indices:
            A = sp.csr_matrix((A.data.copy(), A.indices.astype(np.int32),
                               A.indptr.astype(np.int32)), shape=A.shape)
            A.sort_indices()
        return A

    def _read_inertia(self, n: int) -> None:
        return None


def get_linear_solver(name: str | LinearSolver = "auto", *, symmetric: bool = True,
                      precision: str = "double", **options) -> LinearSolver:
    """Return a linear solver by name.

    Parameters
    ----------
    name
        ``"superlu"`` (scipy, always available), ``"pardiso"`` (needs ``pypardiso``) or
        ``"auto"`` (PARDISO if importable, else SuperLU).  A :class:`LinearSolver`
        instance, or any object with ``solve(K, b)`` (and optionally ``resolve(b)`` and
        ``inertia``), is returned unchanged.
    symmetric
        Whether the matrices are symmetric; for ``symmetric=False`` PARDISO is the
        general LU :class:`PardisoLUSolver` (see :func:`nonsymmetric_solver`).
    precision
        Precision of PARDISO's factors, ``"double"`` or ``"single"``
        (:class:`PardisoSolver`); SuperLU factorises in double precision whatever it is.
    **options
        Passed to the solver's constructor.

    Returns
    -------
    LinearSolver
    """
    if precision not in PRECISIONS:
        raise ValueError(f"precision must be one of {PRECISIONS}, got {precision!r}")
    if isinstance(name, LinearSolver) or (not isinstance(name, str)
                                          and callable(getattr(name, "solve", None))):
        return name                     # an instance (duck-typed: ``solve(K, b)``)
    if name == "auto":
        name = "pardiso" if pardiso_available() else "superlu"
    if name == "pardiso" and not symmetric and pardiso_available():
        return PardisoLUSolver(precision=precision, **options)
    if name == "superlu":
        return SuperLUSolver(**options)
    if name == "pardiso":
        if not pardiso_available():
            raise ValueError("linear solver 'pardiso' needs pypardiso (pip install "
                             "'skfem-dielectric[fast]')")
        return PardisoSolver(precision=precision, **options)
    raise ValueError(f"linear_solver must be a linear solver name ('auto', 'superlu', "
                     f"'pardiso') or a solver instance, got {name!r}")


def nonsymmetric_solver(name: str | LinearSolver = "superlu") -> LinearSolver:
    """Linear solver for non-symmetric tangents (Maxwell-traction coupling).

    Parameters
    ----------
    name
        ``"pardiso"``/``"auto"`` give :class:`PardisoLUSolver` (if ``pypardiso`` is
        installed; ``"auto"`` falls back to SuperLU), ``"superlu"`` SuperLU; an instance is
        returned unchanged.

    Returns
    -------
    LinearSolver
    """
    return get_linear_solver(name, symmetric=False)

"""Stability of an FE equilibrium: negative-eigenvalue count and lowest modes.

The tangent of a charge-controlled, incompressible model is a symmetric saddle-point
matrix ``K = [[K_uu, K_um], [K_mu, K_mm]]`` whose multiplier block (the pressure ``p``,
enforcing ``J = 1``, and the potential ``phi``, at which the energy is maximal) carries
``n_m`` negative eigenvalues by construction.  By Haynsworth's inertia additivity the
*reduced stiffness* -- the mechanical stiffness on the discretely incompressible subspace
with the potential condensed out -- has

    n_negative = n_neg(K) - n_m          (n_m = problem.layout.n_multipliers)

negative eigenvalues, and the equilibrium is stable iff ``n_negative = 0`` and ``K`` is
non-singular.  Under voltage control the potential on the electrodes is prescribed and
the same count applies to the remaining potential unknowns; the reduced operator is the
voltage-controlled stiffness.

The inertia ``n_neg(K)`` comes from a symmetric factorisation ``P K P^T = L D L^T``
(Sylvester's law): MKL PARDISO (``fast`` extra) or, with the default install, scipy's
SuperLU in symmetric mode with diagonal pivoting (``diag_pivot_thresh = 0``; the row and
column permutations are checked to be equal, so that ``U = D L^T``), or a dense
eigenvalue count for small systems.

The lowest modes are eigenpairs of the pencil ``K w = lambda M w`` with ``M`` the identity
on the displacement-like unknowns and zero on the multipliers (the stated metric: the
Euclidean norm of the nodal displacements).  Its finite eigenvalues are those of the
reduced stiffness in that metric; they are found by shift-invert Lanczos on the
saddle-point factorisation.  Their signs, and so the count, do not depend on the metric.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..linalg.inertia import (DENSE_LIMIT, counted_inertia, inertia_factors, reusable_factors,
                              keep_order, kept_order, symmetric_lu, tangent_inertia)
from ..linalg.linear import PardisoSolver, pardiso_available
from ..linalg.solver_base import LinearSolver, count_back_substitution, splu
from ..problem import Problem

__all__ = ["StabilityResult", "stability_analysis", "tangent_stability", "metric_matrix",
           "lowest_modes", "modes_near_zero"]


def metric_matrix(problem: Problem) -> sp.csr_matrix:
    """The metric ``M`` of the modes: identity on the unknowns of the displacement-like
    blocks (every block that is not a multiplier), zero on the multiplier blocks."""
    lay = problem.layout
    diag = np.ones(lay.n)
    for name in lay.multipliers:
        diag[lay.blocks[name]] = 0.0
    return sp.diags(diag).tocsr()


def _pencil_solve(Ks: sp.spmatrix, use_pardiso: bool, solver: PardisoSolver | None = None):
    """A solve with ``Ks`` factorised: PARDISO (``solver`` keeps its analysis) or SuperLU."""
    if use_pardiso:
        solver = solver if solver is not None else PardisoSolver(matching=True)
        solver.solve(Ks, np.zeros(Ks.shape[0]))
        return solver.resolve
    return splu(Ks, permc_spec="MMD_AT_PLUS_A").solve


def _below(Ks: sp.spmatrix, n_m: int, use_pardiso: bool, solver: PardisoSolver | None = None,
           orders: list | None = None) -> tuple[int, Any]:
    """Eigenvalues of the pencil below the shift of ``Ks = K - sigma M`` (its negative
    pivots less the ``n_m`` multipliers') and a solve with ``Ks`` where the factorisation
    that counted them gives one (else ``None``).  ``orders`` (a list) keeps the SuperLU
    elimination order of the first shift for the next ones (same pattern, same zero
    diagonal)."""
    n = Ks.shape[0]
    if use_pardiso:         # the factors that give the inertia serve the solves
        ps = solver if solver is not None else PardisoSolver(matching=True)
        ps.solve(Ks, np.zeros(n))
        return ps.inertia[1] - n_m, ps.resolve
    if n <= DENSE_LIMIT // 10:
        return tangent_inertia(Ks, "dense")[1] - n_m, None
    orders = [] if orders is None else orders
    try:
        inertia, solve, order = symmetric_lu(Ks, kept_order(orders, Ks))
    except ValueError:      # SuperLU without diagonal pivots
        if not pardiso_available():
            return 0, None  # keep this shift
        return tangent_inertia(Ks, "pardiso")[1] - n_m, None
    keep_order(orders, Ks, order)
    return inertia[1] - n_m, solve


def _eig_near(solve, sigma: float, d: np.ndarray, sq: np.ndarray, n: int, m: int,
              which: str, tol: float, v0: np.ndarray | None, ncv: int | None = None):
    """``m`` eigenpairs of ``C = M^1/2 P (K - sigma M)^-1 P M^1/2`` (``solve`` applies the
    inverse; ``which`` as ARPACK's, on ``theta = 1/(lambda - sigma)``): ascending
    ``lambda`` and the full modes, unit ``M``-norm."""
    nd = d.size

    def solve_d(v):
        b = np.zeros(n)
        b[d] = sq * v
        count_back_substitution()
        return solve(b)

    op = spla.LinearOperator((nd, nd), matvec=lambda v: sq * solve_d(v)[d], dtype=float)
    m = min(m, nd - 1)
    if nd <= 2 * m + 20:         # ARPACK needs ncv < n: small systems densely
        C = np.column_stack([op.matvec(e) for e in np.eye(nd)])
        theta, V = np.linalg.eigh(0.5 * (C + C.T))
        key = {"LM": -np.abs(theta), "LA": -theta, "SA": theta}[which]
        keep = np.argsort(key, kind="stable")[:m]
        theta, V = theta[keep], V[:, keep]
    else:
        # a fixed start vector: ARPACK's default is random, and so would be which of
        # nearly equal eigenvalues it returns first
        start = (np.random.default_rng(0).standard_normal(nd) if v0 is None or
                 np.shape(v0) != (nd,) else np.asarray(v0, dtype=float))
        # Lanczos basis 2m + 1, at least 8 (ARPACK's default 20 costs 22 back-
        # substitutions for one well-separated eigenvalue; 8: 10, same eigenvalue)
        theta, V = spla.eigsh(op, m, which=which, tol=tol, v0=start,
                              ncv=min(nd - 1, max(2 * m + 1, 8) if ncv is None else
                                      max(ncv, m + 2)))
    vals = sigma + 1.0 / theta
    order = np.argsort(vals)
    vecs = np.column_stack([solve_d(V[:, j]) * theta[j] for j in order]) if m else \
        np.zeros((n, 0))
    if m:
        vecs /= np.sqrt(np.sum((sq[:, None] * vecs[d]) ** 2, axis=0))
    return vals[order], vecs


#: smallest Lanczos basis of :func:`modes_near_zero` and of the negative eigenpairs that
#: :func:`lowest_modes` takes on the factors of ``K``
NEAR_ZERO_NCV = 20

#: at most this many negative eigenvalues are taken on the factors of ``K`` itself
#: (:func:`lowest_modes`); more are sliced, where Lanczos needs fewer vectors at once
ZERO_SHIFT_LIMIT = 64


def _negative_at_zero(solve, d: np.ndarray, sq: np.ndarray, n: int, n_neg: int, tol: float,
                      v0: np.ndarray | None):
    """The ``n_neg`` negative eigenpairs of the pencil on the factors of ``K`` (``solve``):
    the algebraically smallest ``theta = 1/lambda`` of the shift-invert operator at 0.
    ``None`` unless Lanczos converges to exactly ``n_neg`` negative ones (the inertia's
    count), each apart from the multipliers' ``theta = 0`` by more than rounding."""
    try:
        vals, vecs = _eig_near(solve, 0.0, d, sq, n, n_neg, "SA", tol, v0,
                               ncv=max(2 * n_neg + 1, NEAR_ZERO_NCV))
    except spla.ArpackNoConvergence:
        return None
    theta_max = float(np.max(np.abs(1.0 / vals))) if vals.size else 0.0
    ok = (vals < 0) & np.isfinite(vals) & (np.abs(1.0 / vals) > 1e-10 * theta_max)
    if vals.size != n_neg or not np.all(ok):
        return None
    return vals, vecs


def lowest_modes(K: sp.spmatrix, M: sp.spmatrix, k: int, n_negative: int = 0,
                 sigma: float | None = None, tol: float = 1e-12, *,
                 factors: LinearSolver | None = None, sigma_start: float | None = None,
                 sigma_growth: float = 2.0, shift_solver: PardisoSolver | None = None,
                 v0: np.ndarray | None = None, orders: list | None = None):
    """The ``k`` lowest finite eigenpairs of the pencil ``K w = lambda M w``.

    ``M`` is diagonal, positive on the displacement-like unknowns (index set ``d``) and
    zero on the multipliers.  Shift-invert Lanczos (ARPACK, standard mode) on the
    symmetric operator ``C = M^1/2 P (K - sigma M)^-1 P M^1/2`` restricted to ``d`` (``P``
    the projection on ``d``): its eigenvalues are ``theta = 1/(lambda - sigma)`` for the
    finite ``lambda`` (the multiplier directions give ``theta = 0``), its eigenvectors the
    ``d``-parts of the modes scaled by ``M^1/2``.

    With a given ``sigma`` the ``k`` eigenvalues nearest to it are returned.  Otherwise the
    spectrum is taken in two parts, each where Lanczos separates it well:

    * the non-negative eigenvalues at the shift 0 (``factors``, a solver that holds the
      factorisation of ``K`` itself, serves it without a new factorisation; else ``K`` is
      factorised, with a shift just below zero when it is singular), as the largest
      positive ``theta``: the soft modes nearest to zero come first;
    * the ``n_negative`` negative ones (known from the inertia): where ``factors`` are
      given (and at most :data:`ZERO_SHIFT_LIMIT` are negative), on those same factors as
      the algebraically smallest ``theta = 1/lambda`` (the negative ``theta`` lie apart
      from the positive ones and from the multipliers' ``theta = 0``), kept when Lanczos
      returns exactly ``n_negative`` of them, the count of Sylvester's law; otherwise by
      spectrum slicing: the
      shift moves down by decades (from ``sigma_start`` by factors of ``sigma_growth``
      when given, e.g. 1.5 times the previous state's lowest eigenvalue) until the inertia of
      ``K - sigma M`` shows no eigenvalue below it; the interval between the last two
      shifts is then halved geometrically (systems of more than ``DENSE_LIMIT // 10``
      unknowns) until their ratio is at most 2 (Lanczos
      separates the negative ones best with the shift near the lowest), and the ones
      nearest to the shift are the lowest; the number asked for grows until all the
      negative ones wanted are found.  Without PARDISO the SuperLU factors that counted
      at the last shift (:func:`~skfem_dielectric.linalg.inertia.symmetric_lu`) serve its solves.

    ``shift_solver``, a :class:`~skfem_dielectric.linalg.linear.PardisoSolver`, factorises the
    shifted matrices with its symbolic analysis kept from call to call; ``v0`` (length
    ``nd``: the displacement-like unknowns scaled by ``M^1/2``, e.g. the previous lowest
    mode) starts the Lanczos iteration of the negative part (of the other where there is
    none).  ``orders`` (a list, see
    :func:`~skfem_dielectric.linalg.inertia.inertia_factors`) keeps the SuperLU elimination
    order of the shifted matrices from call to call.  ``tol`` is ARPACK's relative
    tolerance on ``theta``.

    Returns
    -------
    vals : ndarray, shape (k,)
        Ascending eigenvalues.
    vecs : ndarray, shape (n, k)
        Modes (all unknowns, multipliers included), unit ``M``-norm.
    """
    n = K.shape[0]
    md = M.diagonal()
    d = np.flatnonzero(md > 0)
    sq = np.sqrt(md[d])
    nd = d.size
    if not 1 <= k <= nd - 1:
        raise ValueError(f"k must be between 1 and {nd - 1} (the finite eigenvalues of "
                         f"this system less one), got {k}")
    # K - sigma M on K's own pattern: a sparse subtraction would drop the explicit zeros of
    # the multiplier diagonal, which PARDISO needs
    K0 = sp.csr_matrix(K, copy=True)
    K0.sort_indices()
    rows = np.repeat(np.arange(n), np.diff(K0.indptr))
    on_diag = np.flatnonzero(K0.indices == rows)

    def shifted(sig):
        if on_diag.size < n:                        # a pattern without diagonal
            return sp.csr_matrix(K) - sig * sp.csr_matrix(M)
        Ks = K0.copy()
        Ks.data[on_diag] -= sig * md[rows[on_diag]]
        return Ks

    use_pardiso = pardiso_available() and n > DENSE_LIMIT    # symmetric LDL^T
    if sigma is not None:
        return _eig_near(_pencil_solve(shifted(sigma), use_pardiso, shift_solver), sigma,
                         d, sq, n, k, "LM", tol, v0)
    tiny = -1e-8 * float(abs(K).max())
    parts = []
    n_neg = max(0, int(n_negative))
    solve_k = None          # a solve with K itself, from the factors given
    if factors is not None and factors.resolve(np.zeros(n)) is not None:
        solve_k = factors.resolve
    neg = (_negative_at_zero(solve_k, d, sq, n, n_neg, tol, v0)
           if n_neg and solve_k is not None and n_neg <= ZERO_SHIFT_LIMIT else None)
    if neg is not None:     # every negative one, ascending: the lowest first
        parts.append((neg[0][:k], neg[1][:, :k]))
    elif n_neg:
        sig, grow, hi = tiny, 10.0, None
        orders = [] if orders is None else orders
        if sigma_start is not None and sigma_start < sig:
            sig, grow = float(sigma_start), float(sigma_growth)
        for _ in range(40):
            # spectrum slicing: the shift below the lowest eigenvalue (no eigenvalue under
            # it: n_neg(K - sigma M) = n - nd, the multipliers' count); a shift near zero
            # would return every soft positive mode nearer to zero than the negative ones
            below, solve = _below(shifted(sig), n - nd, use_pardiso, shift_solver, orders)
            if below <= 0:
                break
            hi, sig = sig, sig * grow
        # the lowest eigenvalue lies between sig and hi: halve that interval (geometrically)
        # until sig is at most twice it, where Lanczos separates the negative ones best
        # (sparse factorisations; a small system's dense count costs more than it saves)
        while hi is not None and sig / hi > 2.0 and n > DENSE_LIMIT // 10:
            mid = -np.sqrt(sig * hi)
            below, s_mid = _below(shifted(mid), n - nd, use_pardiso, shift_solver, orders)
            if below > 0:
                hi = mid
                solve = None if use_pardiso else solve    # one solver, its factors replaced
            else:
                sig, solve = mid, s_mid
        if solve is None:
            solve = _pencil_solve(shifted(sig), use_pardiso, shift_solver)
        # the ``want`` eigenvalues nearest the shift below them all are the lowest (asking
        # for more would add soft positive ones, clustered at theta ~ 1/|sigma|, which
        # Lanczos converges to slowly)
        want = min(k, n_neg)
        m = want
        while True:
            vals, vecs = _eig_near(solve, sig, d, sq, n, m, "LM", tol, v0)
            neg = vals < 0
            if np.sum(neg) >= want or m >= nd - 1:
                parts.append((vals[neg][:want], vecs[:, neg][:, :want]))
                break
            m *= 2
    if n_neg < k:
        sig0, solve0 = 0.0, solve_k
        if solve0 is None:
            sig0 = tiny
            solve0 = _pencil_solve(shifted(sig0), use_pardiso, shift_solver)
        # the ones below zero belong to the negative part (a shift just below zero can
        # return a negative eigenvalue above it): ask for more until enough remain
        need = k - sum(p[0].size for p in parts)
        m = need
        while True:
            vals, vecs = _eig_near(solve0, sig0, d, sq, n, m, "LA", tol,
                                   None if n_neg else v0)
            keep = np.flatnonzero(vals >= 0) if n_neg else np.arange(vals.size)
            if keep.size >= need or m >= nd - 1:
                keep = keep[:need]
                parts.append((vals[keep], vecs[:, keep]))
                break
            m = min(nd - 1, m + need - keep.size + 2)
    vals = np.concatenate([p[0] for p in parts])
    vecs = np.column_stack([p[1] for p in parts])
    order = np.argsort(vals)[:k]
    return vals[order], vecs[:, order]


#: ARPACK's ``which`` of the shift-invert operator at 0 for the eigenvalues nearest to
#: zero on one side (``theta = 1/lambda``: the negative ones nearest to zero have the most
#: negative ``theta``, the positive ones the largest) or on both
_SIDES = {"negative": "SA", "positive": "LA", "both": "LM"}


def modes_near_zero(K: sp.spmatrix, M: sp.spmatrix, k: int, *, side: str = "both",
                    factors: LinearSolver | None = None, tol: float = 1e-10,
                    v0: np.ndarray | None = None):
    """The ``k`` finite eigenpairs of the pencil ``K w = lambda M w`` nearest to zero: of
    either sign, or on one side of zero.

    Shift-invert Lanczos at the shift 0 (``theta = 1/lambda``: the largest ``|theta|``
    for ``side="both"``, the most negative ``theta`` for the negative eigenvalues nearest
    to zero, the largest for the positive ones -- each an end of the spectrum of the
    operator, where Lanczos converges fastest), on the
    factors of ``K`` itself where ``factors`` holds them (e.g. the factorisation that
    counted its inertia, :func:`~skfem_dielectric.linalg.inertia.inertia_factors`): then
    the modes cost back-substitutions only, no factorisation.  Without usable factors
    (none given, or a singular ``K``) ``K`` is factorised with a shift just below zero.
    This is what an eigenvalue that has just crossed zero needs -- it is among the
    nearest to zero -- whereas :func:`lowest_modes` has to reach the most negative ones
    first, past every other negative eigenvalue.

    Parameters
    ----------
    K, M
        As :func:`lowest_modes` (``M`` diagonal, zero on the multipliers).
    k
        Number of eigenpairs, ``1 <= k <= nd - 1`` (``nd`` displacement-like unknowns);
        with ``side="negative"`` at most the number of negative eigenvalues (past them
        Lanczos would have to resolve the cluster of ``theta`` near 0).
    side
        ``"both"``, ``"negative"`` or ``"positive"``.
    factors
        A solver holding the factorisation of ``K`` (its ``resolve`` solves with it).
    tol
        ARPACK's relative tolerance on ``theta``.
    v0
        Lanczos start vector (length ``nd``), default a fixed random one.

    Returns
    -------
    vals : ndarray, shape (k,)
        Ascending eigenvalues.
    vecs : ndarray, shape (n, k)
        Modes (all unknowns), unit ``M``-norm.

    Raises
    ------
    ValueError
        ``k`` out of range or an unknown ``side``.
    """
    if side not in _SIDES:
        raise ValueError(f"side must be one of {sorted(_SIDES)}, got {side!r}")
    n = K.shape[0]
    md = M.diagonal()
    d = np.flatnonzero(md > 0)
    nd = d.size
    if int(k) != k or not 1 <= k <= nd - 1:
        raise ValueError(f"k must be an integer between 1 and {nd - 1} (the finite "
                         f"eigenvalues of this system less one), got {k!r}")
    if factors is not None and factors.resolve(np.zeros(n)) is not None:
        solve, sigma = factors.resolve, 0.0
    else:                       # a shift just below zero: K itself may be singular
        sigma = -1e-8 * float(abs(K).max())
        solve = _pencil_solve(K - sigma * M, pardiso_available() and n > DENSE_LIMIT)
    # a Lanczos basis of at least 20: the eigenvalues near zero come in clusters (pairs of
    # mesh-scale modes), which a basis of 2k + 1 resolves only after many restarts (on the
    # quick alpha = 1 scan 2.4 times the back-substitutions, same eigenpairs)
    return _eig_near(solve, sigma, d, np.sqrt(md[d]), n, int(k), _SIDES[side], tol, v0,
                     ncv=max(2 * int(k) + 1, NEAR_ZERO_NCV))


@dataclass
class StabilityResult:
    """Stability of one equilibrium (see the module docstring).

    Attributes
    ----------
    n_negative
        Negative eigenvalues of the reduced stiffness (``n_neg(K) - n_multipliers``).
    n_zero
        Zero pivots of the tangent (a singular tangent: a bifurcation or limit point).
    inertia
        ``(n_pos, n_neg, n_zero)`` of the saddle-point tangent.
    n_multipliers
        Multiplier and potential unknowns of the problem's layout.
    eigenvalues, modes
        The ``k`` lowest eigenpairs of the reduced stiffness (ascending; ``M``-orthonormal
        reduced vectors, columns), empty for ``k = 0``.
    labels
        Per mode, the classification (``problem``-specific; see
        :mod:`skfem_dielectric.models.plate.modes`), empty unless asked for.
    """

    n_negative: int
    n_zero: int
    inertia: tuple[int, int, int]
    n_multipliers: int
    eigenvalues: np.ndarray = field(default_factory=lambda: np.zeros(0))
    modes: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    labels: list[dict[str, Any]] = field(default_factory=list)

    @property
    def stable(self) -> bool:
        """``n_negative == 0`` and a non-singular tangent."""
        return self.n_negative == 0 and self.n_zero == 0

    @property
    def lowest_eig(self) -> float:
        """Lowest eigenvalue of the reduced stiffness (``nan`` without modes)."""
        return float(self.eigenvalues[0]) if self.eigenvalues.size else float("nan")


def stability_analysis(problem: Problem, x: np.ndarray, load: Any, *, k: int = 0,
                       method: str = "auto", rtol: float = 1e-6) -> StabilityResult:
    """Negative-eigenvalue count and ``k`` lowest modes of the reduced stiffness at an
    equilibrium ``(x, load)`` of a symmetric problem.

    Parameters
    ----------
    problem
        A :class:`~skfem_dielectric.problem.Problem` with a symmetric tangent.
    x, load
        A converged state (``StepResult.x``, ``StepResult.load``).
    k
        Number of lowest eigenpairs (0: only the count).
    method
        Inertia method of :func:`~skfem_dielectric.linalg.inertia.tangent_inertia`.
    rtol
        The state must satisfy ``||r|| <= rtol * residual_scale(load)`` (an equilibrium).

    Returns
    -------
    StabilityResult

    Raises
    ------
    ValueError
        A non-symmetric tangent (Maxwell-traction coupling: its inertia is no stability
        statement), ``k`` larger than the system, or a state that is not an equilibrium.
    """
    if not isinstance(problem, Problem):
        raise ValueError(f"problem must be a skfem_dielectric.Problem, got "
                         f"{type(problem).__name__}")
    if not problem.symmetric:
        raise ValueError(f"the tangent of {type(problem).__name__} is not symmetric "
                         "(follower loads of the Maxwell coupling): its eigenvalues are no "
                         "stability statement; analyse the fully coupled model")
    x = np.asarray(x, dtype=float)
    if x.shape != (problem.ndofs,):
        raise ValueError(f"x must have shape ({problem.ndofs},), got {x.shape}")
    K, r = problem.assemble(x, load)
    scale = problem.residual_scale(load) or 1.0
    rn = float(np.linalg.norm(r))
    if not rn <= rtol * scale:
        raise ValueError(f"the state is not an equilibrium: ||r|| = {rn:.3e} > "
                         f"rtol * scale = {rtol * scale:.3e} (use a converged StepResult)")
    return tangent_stability(problem, K, k=k, method=method)


def tangent_stability(problem: Problem, K: sp.spmatrix, *, k: int = 0,
                      method: str = "auto", all_negative: bool = False, extra: int = 0,
                      tol: float = 1e-12, metric: sp.spmatrix | None = None,
                      factors: LinearSolver | None = None, **reuse: Any
                      ) -> StabilityResult:
    """:func:`stability_analysis` of a given tangent ``K`` of ``problem`` (no equilibrium
    check): e.g. the grad-div stabilised tangent at a state of the unstabilised model.

    Parameters
    ----------
    problem
        Gives the layout (multiplier blocks, metric).
    K
        Symmetric reduced tangent in that layout.
    k, method
        As in :func:`stability_analysis`.
    all_negative
        Return at least as many modes as negative eigenvalues, and ``extra`` more
        (``k = max(k, n_negative + extra)``): the count is known only after the
        factorisation, so a caller cannot ask for "every negative mode and the next ones"
        through ``k``.
    extra
        Modes above the negative ones with ``all_negative`` (ignored without it).
    tol
        Relative tolerance of the eigenvalues (:func:`lowest_modes`).
    metric
        Diagonal metric ``M`` of the modes (default :func:`metric_matrix`; positive on
        the displacement-like unknowns, zero on the multipliers).
    factors
        A linear solver that has just factorised ``K`` (e.g. the ramp's, see
        ``state_analysis`` of :func:`~skfem_dielectric.solvers.ramp.ramp`): its inertia is the
        count where the factors show it (no new factorisation), and its back-substitutions
        serve the modes of a state without negative eigenvalues.
    **reuse
        ``sigma_start``, ``sigma_growth``, ``shift_solver``, ``v0``, ``orders`` of
        :func:`lowest_modes` (``orders`` also serves the count's own factorisation,
        :func:`~skfem_dielectric.linalg.inertia.inertia_factors`).

    Returns
    -------
    StabilityResult
    """
    if int(k) != k or k < 0:
        raise ValueError(f"k must be an integer >= 0, got {k!r}")
    if int(extra) != extra or extra < 0:
        raise ValueError(f"extra must be an integer >= 0, got {extra!r}")
    if K.shape != (problem.ndofs, problem.ndofs):
        raise ValueError(f"K must have shape ({problem.ndofs}, {problem.ndofs}), got {K.shape}")
    unknown = set(reuse) - {"sigma_start", "sigma_growth", "shift_solver", "v0", "orders"}
    if unknown:
        raise ValueError(f"unknown keyword arguments {sorted(unknown)} (allowed: "
                         "sigma_start, sigma_growth, shift_solver, v0, orders)")
    inertia = factors.factor_inertia() if factors is not None else None
    n_m = problem.layout.n_multipliers
    if inertia is None and factors is None and (k or all_negative):
        # the factorisation that counts also serves the shift-0 solves of the modes
        inertia, own = inertia_factors(K, method, reuse.get("orders"))
        factors = reusable_factors(own, inertia)
        del own
    elif inertia is None:
        inertia = counted_inertia(K, method)
    out = StabilityResult(inertia[1] - n_m, inertia[2], tuple(inertia), n_m)
    if all_negative:
        k = max(int(k), out.n_negative + int(extra))
    if k:
        M = metric_matrix(problem) if metric is None else metric
        out.eigenvalues, out.modes = lowest_modes(
            K, M, int(k), max(0, out.n_negative), tol=tol,
            factors=factors if out.n_zero == 0 else None, **reuse)
    return out

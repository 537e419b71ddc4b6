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

from .linear import PardisoSolver, pardiso_available
from .problem import Problem

__all__ = ["tangent_inertia", "StabilityResult", "stability_analysis", "tangent_stability",
           "metric_matrix", "lowest_modes"]

INERTIA_METHODS = ("auto", "superlu", "pardiso", "dense")
#: systems up to this size may be counted densely
DENSE_LIMIT = 3000


def tangent_inertia(K: sp.spmatrix, method: str = "auto") -> tuple[int, int, int]:
    """Inertia ``(n_positive, n_negative, n_zero)`` of a symmetric sparse matrix.

    Parameters
    ----------
    K
        Symmetric (possibly indefinite, saddle-point) matrix.
    method
        ``"pardiso"`` (MKL, Bunch-Kaufman LDL^T), ``"superlu"`` (symmetric-mode LU with
        diagonal pivots, ``U = D L^T``), ``"dense"`` (eigenvalues; small systems) or
        ``"auto"`` (PARDISO if installed, else SuperLU).

    Returns
    -------
    tuple of int

    Raises
    ------
    ValueError
        Unknown ``method``, a non-square matrix, or a SuperLU factorisation that needed
        off-diagonal pivots (its diagonal then says nothing about the inertia).
    """
    if method not in INERTIA_METHODS:
        raise ValueError(f"method must be one of {INERTIA_METHODS}, got {method!r}")
    if K.shape[0] != K.shape[1]:
        raise ValueError(f"K must be square, got shape {K.shape}")
    n = K.shape[0]
    if method == "auto":
        method = "pardiso" if pardiso_available() else "superlu"
    if method == "dense":
        ev = np.linalg.eigvalsh(K.toarray())
        tol = n * np.finfo(float).eps * max(1.0, float(np.abs(ev).max()))
        return int(np.sum(ev > tol)), int(np.sum(ev < -tol)), int(np.sum(np.abs(ev) <= tol))
    if method == "pardiso":
        solver = PardisoSolver()
        solver.solve(K, np.zeros(n))
        return solver.inertia
    lu = spla.splu(sp.csc_matrix(K), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                   options={"SymmetricMode": True})
    if not np.array_equal(lu.perm_r, lu.perm_c):
        raise ValueError("SuperLU needed off-diagonal pivots: no inertia from its diagonal "
                         "(use method='dense' or 'pardiso')")
    d = lu.U.diagonal()
    return int(np.sum(d > 0)), int(np.sum(d < 0)), int(np.sum(d == 0))


def metric_matrix(problem: Problem) -> sp.csr_matrix:
    """The metric ``M`` of the modes: identity on the unknowns of the displacement-like
    blocks (every block that is not a multiplier), zero on the multiplier blocks."""
    lay = problem.layout
    diag = np.ones(lay.n)
    for name in lay.multipliers:
        diag[lay.blocks[name]] = 0.0
    return sp.diags(diag).tocsr()


def lowest_modes(K: sp.spmatrix, M: sp.spmatrix, k: int, n_negative: int = 0,
                 sigma: float | None = None, tol: float = 1e-12):
    """The ``k`` lowest finite eigenpairs of the pencil ``K w = lambda M w``.

    ``M`` is diagonal, positive on the displacement-like unknowns (index set ``d``) and
    zero on the multipliers.  Shift-invert Lanczos (ARPACK, standard mode) on the
    symmetric operator ``C = M^1/2 P (K - sigma M)^-1 P M^1/2`` restricted to ``d`` (``P``
    the projection on ``d``): its eigenvalues are ``theta = 1/(lambda - sigma)`` for the
    finite ``lambda`` (the multiplier directions give ``theta = 0``), its eigenvectors the
    ``d``-parts of the modes scaled by ``M^1/2``.  ``sigma`` defaults to just below zero (scaled to ``K``);
    with ``n_negative > 0`` (known from the inertia) the shift first moves down by decades
    until the inertia of ``K - sigma M`` shows no eigenvalue below it (spectrum slicing), so
    that the eigenvalues nearest to it are the lowest; where that cannot be shown, the
    number of eigenpairs asked for grows until all ``n_negative`` negative eigenvalues are
    among them, so that the returned ones are the lowest.
    ``tol`` is ARPACK's relative tolerance on ``theta``.

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
    pardiso = None           # PARDISO's factors of the current shift, once computed
    below_all = False        # no eigenvalue below the shift: the nearest ones are the lowest
    if sigma is None:
        sigma = -1e-8 * float(abs(K).max())
        if n_negative > 0:
            # spectrum slicing: move the shift below the lowest eigenvalue (no eigenvalue
            # under it: n_neg(K - sigma M) = n - nd, the multipliers' count), so that the
            # negative eigenvalues are the ones nearest to it and come first -- a shift near
            # zero would first return every soft positive mode closer to zero than them
            for _ in range(16):
                if use_pardiso:     # the factors that give the inertia serve the solves
                    pardiso = PardisoSolver()
                    pardiso.solve(shifted(sigma), np.zeros(n))
                    below = pardiso.inertia[1] - (n - nd)
                else:
                    try:
                        below = tangent_inertia(shifted(sigma), "auto" if n > DENSE_LIMIT
                                                // 10 else "dense")[1] - (n - nd)
                    except ValueError:   # SuperLU without diagonal pivots: keep this shift
                        break
                if below <= 0:
                    below_all = True
                    break
                sigma *= 10.0
                pardiso = None
    Ks = shifted(sigma)
    if use_pardiso:                                 # factorised once per shift
        if pardiso is None:
            pardiso = PardisoSolver()
            pardiso.solve(Ks, np.zeros(n))
        solve = pardiso.resolve
    else:
        solve = spla.splu(sp.csc_matrix(Ks), permc_spec="MMD_AT_PLUS_A").solve

    def solve_d(v):
        b = np.zeros(n)
        b[d] = sq * v
        return solve(b)

    op = spla.LinearOperator((nd, nd), matvec=lambda v: sq * solve_d(v)[d], dtype=float)
    want = k if below_all else k + max(0, n_negative)
    while True:
        m = min(want, nd - 1)
        if nd <= 2 * m + 20:     # ARPACK needs ncv < n: small systems densely
            C = np.column_stack([op.matvec(e) for e in np.eye(nd)])
            theta, V = np.linalg.eigh(0.5 * (C + C.T))
            keep = np.argsort(-np.abs(theta))[:m]
            theta, V = theta[keep], V[:, keep]
        else:
            # a fixed start vector: ARPACK's default is random, and so would be which of
            # nearly equal eigenvalues it returns first
            v0 = np.random.default_rng(0).standard_normal(nd)
            theta, V = spla.eigsh(op, m, which="LM", tol=tol, v0=v0)
        vals = sigma + 1.0 / theta
        order = np.argsort(vals)
        vals, V, theta = vals[order], V[:, order], theta[order]
        if below_all or np.sum(vals < 0) >= n_negative or m == nd - 1:
            vecs = np.column_stack([solve_d(V[:, j]) * theta[j] for j in range(k)])
            vecs /= np.sqrt(np.sum(md[d, None] * vecs[d] ** 2, axis=0))
            return vals[:k], vecs
        want *= 2


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
        :mod:`skfem_dielectric.modes`), empty unless asked for.
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
        Inertia method of :func:`tangent_inertia`.
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
                      method: str = "auto", all_negative: bool = False,
                      tol: float = 1e-12, metric: sp.spmatrix | None = None
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
        Return at least as many modes as negative eigenvalues (``k = max(k, n_negative)``).
    tol
        Relative tolerance of the eigenvalues (:func:`lowest_modes`).
    metric
        Diagonal metric ``M`` of the modes (default :func:`metric_matrix`; positive on
        the displacement-like unknowns, zero on the multipliers).

    Returns
    -------
    StabilityResult
    """
    if int(k) != k or k < 0:
        raise ValueError(f"k must be an integer >= 0, got {k!r}")
    if K.shape != (problem.ndofs, problem.ndofs):
        raise ValueError(f"K must have shape ({problem.ndofs}, {problem.ndofs}), got {K.shape}")
    if method == "auto" and not pardiso_available() and K.shape[0] <= DENSE_LIMIT // 10:
        method = "dense"
    try:
        inertia = tangent_inertia(K, method)
    except ValueError as exc:
        # SuperLU met a zero pivot (a multiplier eliminated before its displacements);
        # small systems are counted densely instead, large ones need PARDISO
        if not (method in ("auto", "superlu") and "off-diagonal pivots" in str(exc)):
            raise
        if K.shape[0] > DENSE_LIMIT:
            raise ValueError(f"{exc}; this tangent ({K.shape[0]} unknowns) is too large "
                             "to be counted densely: install the 'fast' extra (PARDISO)"
                             ) from None
        inertia = tangent_inertia(K, "dense")
    n_m = problem.layout.n_multipliers
    out = StabilityResult(inertia[1] - n_m, inertia[2], tuple(inertia), n_m)
    if all_negative:
        k = max(int(k), out.n_negative)
    if k:
        M = metric_matrix(problem) if metric is None else metric
        out.eigenvalues, out.modes = lowest_modes(K, M, int(k), max(0, out.n_negative),
                                                  tol=tol)
    return out

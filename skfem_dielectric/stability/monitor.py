"""Stability of every converged state of a ramp, on the factorisation the ramp makes anyway.

A :class:`StabilityMonitor` is the ``state_analysis`` of
:func:`~skfem_dielectric.solvers.ramp.ramp` (and of the drivers, e.g.
``keplinger_plate(..., state_analysis=StabilityMonitor(k=5))``).  The ramp assembles and
factorises the tangent of each converged state and starts the next load step with a chord
step on those factors (``reuse_factors`` of :func:`~skfem_dielectric.solvers.newton.newton`), so
that factorisation replaces the one the next Newton solve would have made.  On it the
monitor reads

* the negative-eigenvalue count of the reduced stiffness, ``n_neg(K) - n_multipliers``
  (the inertia of the factors: PARDISO, or SuperLU when it kept to diagonal pivots; else
  one extra symmetric factorisation, :func:`~skfem_dielectric.linalg.inertia.tangent_inertia`);
* with ``k > 0`` the ``k`` lowest eigenpairs
  (:func:`~skfem_dielectric.stability.analysis.lowest_modes`,
  metric of :func:`~skfem_dielectric.stability.analysis.metric_matrix`): for a state without
  negative eigenvalues by Lanczos back-substitutions on the same factors (shift 0); with
  negative ones by spectrum slicing that starts at 1.5 times the previous state's lowest
  eigenvalue, on one PARDISO solver whose symbolic analysis is kept, and Lanczos started
  from the previous lowest mode.

Its numbers are those of :func:`~skfem_dielectric.stability.analysis.tangent_stability` on the same
tangent (the count exactly, the eigenvalues to the Lanczos tolerance ``tol``).
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from ..checks import check_nonnegative_int, check_positive
from ..linalg.inertia import DENSE_LIMIT
from ..linalg.linear import PardisoSolver, pardiso_available
from ..linalg.solver_base import LinearSolver
from ..problem import Problem
from .analysis import StabilityResult, metric_matrix, tangent_stability

__all__ = ["StabilityMonitor"]


class StabilityMonitor:
    """Negative-eigenvalue count and ``k`` lowest modes of every converged ramp state.

    Parameters
    ----------
    k
        Number of lowest eigenpairs per state (0: only the count).
    tol
        Relative Lanczos tolerance of the eigenvalues.
    method
        Inertia method where the ramp's factors do not show the inertia (see
        :func:`~skfem_dielectric.linalg.inertia.tangent_inertia`).
    all_negative
        At least as many eigenpairs as negative eigenvalues (``max(k, n_negative)``, as
        :func:`~skfem_dielectric.stability.analysis.tangent_stability`), e.g. to classify every
        unstable mode.

    Attributes
    ----------
    history
        One ``(load, n_negative, n_zero, eigenvalues)`` tuple per analysed state.
    last
        The :class:`~skfem_dielectric.stability.analysis.StabilityResult` of the last state (with
        its modes).
    seconds
        Wall time of each analysis (the factorisation of the tangent is the ramp's).

    Raises
    ------
    ValueError
        ``k`` not a non-negative integer, ``tol`` not positive; when called, a problem
        whose tangent is not symmetric.

    Examples
    --------
    >>> from skfem_dielectric import keplinger_plate
    >>> from skfem_dielectric.stability.monitor import StabilityMonitor
    >>> mon = StabilityMonitor(k=1)
    >>> res = keplinger_plate(1.0, D0=[1.0], elements=(4, 1, 2), state_analysis=mon)
    >>> res.steps[-1]["n_negative"]
    0
    """

    def __init__(self, k: int = 0, *, tol: float = 1e-6, method: str = "auto",
                 all_negative: bool = False):
        self.k = check_nonnegative_int("k", k)
        self.tol = check_positive("tol", tol)
        self.method = method
        self.all_negative = bool(all_negative)
        self.history: list[tuple[Any, int, int, np.ndarray]] = []
        self.last: StabilityResult | None = None
        self.seconds: list[float] = []
        self._shift: PardisoSolver | None = None
        self._metric = None

    def __call__(self, problem: Problem, x: np.ndarray, load: Any, K, solver: LinearSolver
                 ) -> dict[str, Any]:
        """Analyse the converged state ``(x, load)`` whose tangent ``K`` ``solver`` has just
        factorised; returns ``n_negative``, ``n_zero``, ``lowest_eig`` (``nan`` for
        ``k = 0``) for the step's quantities."""
        if not problem.symmetric:
            raise ValueError(f"the tangent of {type(problem).__name__} is not symmetric "
                             "(follower loads of the Maxwell coupling): its eigenvalues are "
                             "no stability statement")
        t0 = time.perf_counter()
        reuse: dict[str, Any] = {}
        if self.k or self.all_negative:
            if self._metric is None or self._metric[0] is not problem:
                M = metric_matrix(problem)
                md = M.diagonal()
                d = np.flatnonzero(md > 0)
                self._metric = (problem, M, d, np.sqrt(md[d]))
                self._shift = (PardisoSolver(matching=True) if pardiso_available()
                               and problem.ndofs > DENSE_LIMIT else None)
            _, M, d, sq = self._metric
            prev = self.last
            if prev is not None and prev.eigenvalues.size and prev.modes.shape[0] == K.shape[0]:
                low = float(prev.eigenvalues[0])
                if low < 0:     # the trend of the last two states, never above the last
                    trend = [h[3][0] for h in self.history[-2:] if h[3].size]
                    guess = min(low, 2 * low - trend[0]) if len(trend) == 2 else low
                    reuse["sigma_start"], reuse["sigma_growth"] = 1.5 * guess, 2.0
                elif low > 0:   # an onset: negative ones just crossed zero
                    reuse["sigma_start"], reuse["sigma_growth"] = -10.0 * low, 10.0
                reuse["v0"] = sq * prev.modes[d, 0]
            reuse["shift_solver"] = self._shift
        st = tangent_stability(problem, K, k=self.k, method=self.method, tol=self.tol,
                               factors=solver, all_negative=self.all_negative,
                               metric=M if self.k or self.all_negative else None, **reuse)
        self.last = st
        self.history.append((load, st.n_negative, st.n_zero, st.eigenvalues.copy()))
        self.seconds.append(time.perf_counter() - t0)
        return {"n_negative": st.n_negative, "n_zero": st.n_zero,
                "lowest_eig": st.lowest_eig}

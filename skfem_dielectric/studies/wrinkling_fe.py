"""FE wrinkling of a homogeneous plate: the bifurcation of one Fourier mode of the section.

A homogeneous equi-biaxially stretched plate (``lam1 = lam3 = lam``, charge ``D0`` or
voltage ``E0``) is modelled by its cross-section (:class:`~skfem_dielectric.CrossSection`,
generalised plane strain) of half-length ``a`` with *sliding ends*: ``u1 = 0`` on
``X1 = 0`` and ``u1 = (lam - 1) a`` on ``X1 = a``, no shear traction.  The increments of
the homogeneous state are then the Fourier modes ``u2 ~ cos(n pi X1/a)``, of wavenumber
``k_n = n pi/(lam a)`` in the deformed plate and ``k_n h = n pi/(lam^3 a)`` with the
deformed thickness ``h = lam^-2 H``.  The half-length is chosen so that ``n = 1`` has the
requested ``kh``.  Symmetric (extensional) modes live on the half thickness (``u2 = phi = 0``
on the mid-plane), antisymmetric (flexural) ones on the full thickness, told apart by the
parity of ``u2`` in ``X2``.

:func:`section_mode_eigenvalue` gives the eigenvalue of the reduced stiffness
(:mod:`skfem_dielectric.stability.analysis`) that belongs to the mode ``n = 1`` of the requested
class; :func:`section_critical_load` finds where it vanishes by Brent's
iterations on the load -- the FE counterpart of the Stroh dispersion relation
of the paper's Sec. 3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..checks import check_choice, check_positive
from ..materials import NeoHookeanDielectric
from ..models.cross_section import CrossSection, section_mesh
from ..solvers.critical import brent
from ..solvers.ramp import RampSettings, ramp
from ..stability.analysis import lowest_modes, metric_matrix, tangent_stability

__all__ = ["wrinkling_section", "section_mode_eigenvalue", "section_critical_load",
           "SectionBifurcation", "section_critical_stretch"]

MODES = ("symmetric", "antisymmetric")
CONTROLS = ("charge", "voltage")
#: linear solver of the sections' Newton solves: PARDISO where installed.  SuperLU's
#: threshold pivoting fills the long thin sections' factors badly (8 x 102 elements,
#: 10 970 unknowns: 11.9 M entries; the cost against PARDISO: docs/performance.md); the
#: critical loads are located to 1e-6, far above the last bits that PARDISO's threads move.
SOLVER = "auto"
#: Newton settings of the sections' solves: the states converge to round-off.
SETTINGS = RampSettings(atol=1e-10, rtol=1e-11)


def wrinkling_section(lam: float, kh: float, mode: str = "symmetric",
                      control: str = "charge", *, material=None, n1: int = 8,
                      n2: int = 4, grad_div: float = 10.0) -> CrossSection:
    """The cross-section whose mode ``n = 1`` has the wavenumber ``kh``.

    Parameters
    ----------
    lam
        Equi-biaxial stretch (prescribed: ``lam1`` by the sliding end, ``lam3``).
    kh
        Wavenumber times the deformed thickness of the mode ``n = 1``.
    mode
        ``"symmetric"`` (half thickness) or ``"antisymmetric"`` (full thickness).
    control
        ``"charge"`` or ``"voltage"``.
    material
        Ideal dielectric (default neo-Hookean, ``mu = eps = 1``).
    n1, n2
        Q2 elements along the half-length and across the modelled thickness.
    grad_div
        Grad-div stabilisation in units of ``mu`` (default 10: no spurious mesh-scale
        surface modes; docs/stability.md).
    """
    lam, kh = check_positive("lam", lam), check_positive("kh", kh)
    check_choice("mode", mode, MODES)
    check_choice("control", control, CONTROLS)
    a = math.pi / (lam**3 * kh)
    mesh = section_mesh(2 * a, 1.0, n1, n2, "half" if mode == "symmetric" else "full")
    return CrossSection(mesh, material or NeoHookeanDielectric(), control=control,
                        grad_div=grad_div, lam1=lam, lam3=lam)


def _top_profile(pb: CrossSection, w: np.ndarray):
    """``X1`` and ``u2`` of a mode on the top face, and its parity in ``X2``."""
    full = pb.red.expand(w, np.zeros(pb.n_full))
    u = full[: pb.offsets[1]].reshape(-1, 2)
    X = pb.bu.doflocs[:, ::2]
    top = np.flatnonzero(np.abs(X[1] - X[1].max()) < 1e-9)
    top = top[np.argsort(X[0, top])]
    parity = 1.0
    if pb.thickness == "full":      # u2(X1, -X2) = parity * u2(X1, X2)
        bot = np.flatnonzero(np.abs(X[1] - X[1].min()) < 1e-9)
        bot = bot[np.argsort(X[0, bot])]
        num = float(np.dot(u[top, 1], u[bot, 1]))
        parity = num / max(float(np.dot(u[top, 1], u[top, 1])), 1e-300)
    return X[0, top], u[top, 1], parity


def fourier_index(x: np.ndarray, f: np.ndarray, a: float, n_max: int = 12) -> int:
    """The ``n`` of the dominant ``cos(n pi x/a)`` in the profile ``f(x)`` on ``[0, a]``."""
    w = np.zeros_like(x)                     # trapezoid weights
    dx = np.diff(x)
    w[:-1] += dx / 2
    w[1:] += dx / 2
    c = [abs(np.dot(w * f, np.cos(n * np.pi * x / a))) for n in range(n_max + 1)]
    return int(np.argmax(c))


def section_mode_eigenvalue(pb: CrossSection, x: np.ndarray, load, mode: str,
                            n: int = 1, k: int = 8, method: str = "auto"):
    """Eigenvalue of the reduced stiffness at ``(x, load)`` whose mode is ``cos(n pi X1/a)``
    of class ``mode``, and the count of negative eigenvalues.

    Returns
    -------
    eig : float
        ``nan`` if no such mode is among the ``k`` (growing up to 64) lowest.
    n_negative : int
    w : ndarray or None
        The mode (reduced vector).
    """
    want = check_choice("mode", mode, MODES)
    K, _ = pb.assemble(x, load)
    n_neg = tangent_stability(pb, K, method=method).n_negative
    M = metric_matrix(pb)
    n_finite = int(M.diagonal().sum())
    while True:
        kk = min(k + max(0, n_neg), n_finite - 2)
        vals, vecs = lowest_modes(K, M, kk, max(0, n_neg))
        j = _first_mode(pb, vals, vecs, want, n)
        if j is not None:
            return float(vals[j]), n_neg, vecs[:, j]
        if k >= 64 or kk == n_finite - 2:
            return float("nan"), n_neg, None
        k *= 2


def _first_mode(pb: CrossSection, vals: np.ndarray, vecs: np.ndarray, mode: str,
                n: int) -> int | None:
    """Index of the lowest of the eigenpairs ``(vals, vecs)`` whose mode is
    ``cos(n pi X1/a)`` of class ``mode`` (``None`` if none is)."""
    a = pb.L1 / 2
    for j in np.argsort(vals, kind="stable"):
        xs, u2, parity = _top_profile(pb, vecs[:, j])
        cls = "symmetric" if (pb.thickness == "half" or parity < 0) else "antisymmetric"
        if cls == mode and fourier_index(xs, u2, a) == n:
            return int(j)
    return None


def _mode_near_zero(pb: CrossSection, x: np.ndarray, load, mode: str, n: int = 1,
                    k: int = 8) -> float:
    """Eigenvalue of the mode ``cos(n pi X1/a)`` of class ``mode`` among the ``k``
    eigenvalues of the reduced stiffness nearest to zero (one factorisation at the shift
    0, no count, no spectrum slicing), ``nan`` if it is not among them.

    Near a bifurcation the sought eigenvalue is itself near zero, so this finds the same
    eigenpair as :func:`section_mode_eigenvalue` (the lowest mode of index ``n`` and the
    class: an overtone of the same index is stiffer) at a fraction of its cost; the root
    searches call it first and fall back to :func:`section_mode_eigenvalue`
    (:func:`_tracked_eigenvalue`)."""
    K, _ = pb.assemble(x, load)
    M = metric_matrix(pb)
    k = min(k, int(M.diagonal().sum()) - 2)
    vals, vecs = lowest_modes(K, M, k, sigma=0.0)
    j = _first_mode(pb, vals, vecs, mode, n)
    return float("nan") if j is None else float(vals[j])


def _tracked_eigenvalue(pb: CrossSection, x: np.ndarray, load, mode: str,
                        count: bool = False) -> tuple[float, int | None]:
    """The eigenvalue of the mode ``n = 1`` of class ``mode`` for a root search:
    :func:`_mode_near_zero`, else (or with ``count``, which needs the inertia)
    :func:`section_mode_eigenvalue`; with the count of negative eigenvalues where that
    was computed (``None`` otherwise).  ``nan`` if neither finds the mode."""
    if not count:
        eig = _mode_near_zero(pb, x, load, mode)
        if math.isfinite(eig):
            return eig, None
    eig, n_neg, _ = section_mode_eigenvalue(pb, x, load, mode)
    return eig, n_neg


@dataclass
class SectionBifurcation:
    """Critical load of one mode of a wrinkling section.

    Attributes
    ----------
    load
        Critical ``D0`` (charge) or ``E0`` (voltage).
    D0
        ``|D_L|/sqrt(mu eps)`` of the critical state (FE post-processing).
    iterations
        Secant iterations.
    n_negative_below
        Negative eigenvalues of the reduced stiffness at the lower bracket end (the
        stable side; spurious modes would show here).
    """

    load: float
    D0: float
    iterations: int
    n_negative_below: int


def section_critical_load(pb: CrossSection, mode: str, lo: float, hi: float, *,
                          tol: float = 1e-6, maxiter: int = 60) -> SectionBifurcation:
    """Load at which the mode ``n = 1`` of class ``mode`` loses stability.

    Brent iterations (inverse quadratic interpolation, bisection) on the load between
    ``lo`` (mode stable) and ``hi`` (mode unstable), each state solved by Newton from the
    previous one.

    Raises
    ------
    ValueError
        If ``[lo, hi]`` does not bracket a sign change of the mode's eigenvalue.
    """
    check_choice("mode", mode, MODES)
    state = {"x": pb.initial_state(), "load": np.zeros(3)}
    base = {}
    phi = np.arange(pb.ndofs)[pb.layout.blocks["phi"]]

    def solve(v):
        # a homogeneous initial guess for every state: the state at a small load (its
        # potential hardly departs from homogeneity at the charged or electroded face) with
        # the potential scaled to the load; Newton keeps a homogeneous iterate homogeneous,
        # so it cannot drift onto a bifurcated branch of the modes that are already unstable
        # (short waves beyond the thick-plate limit).  A step from the unloaded plate puts
        # the whole jump of the potential into the face elements and can end on such a
        # branch (voltage control, lam = 2).
        if not base:
            v0 = lo / 64
            res = ramp(pb, [np.array([0.0, 0.0, v0])], x0=pb.initial_state(),
                       start=np.zeros(3), settings=SETTINGS, linear_solver=SOLVER)
            if not res.converged:
                raise ValueError(f"no equilibrium at load {v0}: {res.reason}")
            base.update(x=res.x, v=v0)
        x0 = base["x"].copy()
        x0[phi] *= v / base["v"]
        tgt = np.array([0.0, 0.0, v])
        res = ramp(pb, [tgt], x0=x0, start=np.array([0.0, 0.0, base["v"]]), settings=SETTINGS,
                   linear_solver=SOLVER)
        if not res.converged:
            raise ValueError(f"no equilibrium at load {v}: {res.reason}")
        state.update(x=res.x, load=tgt)
        return res

    def g(v, count=False):
        solve(v)
        eig, n_neg = _tracked_eigenvalue(pb, state["x"], state["load"], mode, count)
        if not math.isfinite(eig):
            raise ValueError(f"no {mode} mode n = 1 among the 64 lowest modes at load {v}")
        return eig, n_neg

    fa, nneg_lo = g(lo, count=True)
    fb, _ = g(hi)
    if not (fa > 0 > fb):
        raise ValueError(f"[{lo}, {hi}] does not bracket the bifurcation of the {mode} "
                         f"mode: eigenvalues {fa:.3e}, {fb:.3e}")
    c, _, _, _, it = brent(lambda v: g(v)[0], lo, fa, hi, fb, maxiter=maxiter,
                           xtol=lambda c: tol * max(1.0, abs(c)))
    res = solve(c)
    return SectionBifurcation(float(c), float(res.steps[-1]["D0"]), it, int(nneg_lo))


def section_critical_stretch(kh: float, mode: str, lo: float, hi: float, *, n1: int = 8,
                             n2: int = 8, material=None, grad_div: float = 10.0,
                             tol: float = 1e-8, maxiter: int = 60) -> tuple[float, int]:
    """Critical equi-biaxial stretch of the purely elastic plate (``D0 = 0``) for the mode
    ``n = 1`` of wavenumber ``kh`` (deformed thickness) and class ``mode``.

    The compressed plate (``lam < 1``) buckles where the mode's eigenvalue vanishes: for
    every trial stretch the section of :func:`wrinkling_section` (``n1 x n2`` elements,
    the same for every trial, so that the eigenvalue is a smooth function of ``lam``) is
    solved uncharged and its mode's eigenvalue computed; Brent iterations on ``lam``
    between ``lo`` (unstable, more compressed) and ``hi`` (stable).

    Returns
    -------
    lam : float
        The critical stretch (to ``tol``).
    iterations : int

    Raises
    ------
    ValueError
        If ``[lo, hi]`` does not bracket a sign change of the eigenvalue.
    """
    check_choice("mode", mode, MODES)
    kh = check_positive("kh", kh)

    def g(lam):
        pb = wrinkling_section(lam, kh, mode, "charge", material=material, n1=n1, n2=n2,
                               grad_div=grad_div)
        res = ramp(pb, [np.zeros(3)], x0=pb.initial_state(), start=np.zeros(3),
                   settings=SETTINGS, linear_solver=SOLVER)
        if not res.converged:
            raise ValueError(f"no equilibrium at lam = {lam}: {res.reason}")
        eig = _tracked_eigenvalue(pb, res.x, np.zeros(3), mode)[0]
        if not math.isfinite(eig):
            raise ValueError(f"no {mode} mode n = 1 among the 64 lowest modes at lam = {lam}")
        return eig

    fa, fb = g(hi), g(lo)
    if not (fa > 0 > fb):
        raise ValueError(f"[{lo}, {hi}] does not bracket the buckling of the {mode} mode: "
                         f"eigenvalues {fb:.3e} at {lo}, {fa:.3e} at {hi}")
    c, _, _, _, it = brent(g, hi, fa, lo, fb, maxiter=maxiter, xtol=tol)
    return float(c), it

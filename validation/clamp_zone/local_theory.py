"""The paper's homogeneous wrinkling theory evaluated at one point of an FE plate state.

The FE plate is inhomogeneous; the closed forms of :mod:`analytic.wrinkling` are for a
homogeneous plate with traction-free charged faces.  Here the local state at a reference
point is read off the FE state and handed to the closed forms, so that a wrinkle the FE
finds in one zone (e.g. next to the clamps of the Keplinger plate) can be compared with
what the homogeneous theory predicts for the state of that zone.

The local homogeneous state is ``(lam1, lam3, D0)``: the in-plane principal stretches of
``C = F^T F`` and the charge per reference area.  The criteria depend on the charge only
through the true field ``d = |D| / sqrt(mu eps)`` (``= E2 = lam2 D0`` in the homogeneous
state, the Stroh coefficient ``d`` of Eq. (gent-moduli)), and they take
``lam2 = 1/(lam1 lam3)``.  The local ``D0`` is therefore ``d lam1 lam3``: it gives the
analytic state the FE's true field exactly, whatever the FE's ``J - 1``.  ``|D_L|`` (the
FE's Lagrangian charge density) is kept beside it for comparison.

The finite elements (this module's FE side) and the closed forms (``analytic``) meet only
here; ``analytic`` itself knows nothing of the FE package.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

import analytic as an
from skfem_dielectric.models.plate.modes import element_energies, top_deflection
from skfem_dielectric.models.plate.post import evaluate_fields

from .modes import row_half_waves

__all__ = ["LocalState", "local_state", "energy_centroid", "half_waves",
           "DirectionCriteria", "LocalCriteria", "local_criteria", "KH_GRID",
           "first_firing"]

#: wavenumber x deformed thickness of the finite-thickness dispersion ``D0_c(kh)``
KH_GRID = np.logspace(-2, 2, 41)


@dataclass(frozen=True)
class LocalState:
    """The local homogeneous state of an FE plate state at one reference point.

    Attributes
    ----------
    point : ndarray, shape (3,)
        Reference point (mm).
    lam1, lam3 : float
        In-plane principal stretches (eigenvalues of the in-plane block of ``C = F^T F``);
        ``lam1`` is the one whose axis is nearer ``X1`` (the load).
    lam2 : float
        Thickness stretch ``|F e2|``.
    theta : float
        Angle (rad) of the ``lam1`` axis from ``X1`` in the ``(X1, X3)`` plane.
    J : float
        ``det F`` (1 up to the Newton tolerance of the mixed form).
    d : float
        True field ``|D| / sqrt(mu eps)`` (``= E2``).
    D0 : float
        The charge the criteria take, ``d lam1 lam3`` (module notes).
    D_L : float
        ``|D_L| / sqrt(mu eps)``, the FE's Lagrangian charge density.
    sigma1, sigma3 : float
        FE Cauchy stresses ``(sigma_11 - sigma_22) / mu`` and ``(sigma_33 - sigma_22) / mu``
        along the principal axes: the in-plane stresses of a plate with traction-free
        faces, ``a - c`` of Eq. (gent-moduli) in the homogeneous theory.
    """

    point: np.ndarray
    lam1: float
    lam2: float
    lam3: float
    theta: float
    J: float
    d: float
    D0: float
    D_L: float
    sigma1: float
    sigma3: float


def local_state(problem, x: np.ndarray, load, point) -> LocalState:
    """Local homogeneous state of a plate state at a reference point.

    Parameters
    ----------
    problem : PlateProblem
        The FE plate.
    x : ndarray
        Reduced state vector of a converged step.
    load : tuple
        Its load ``(s, D0)``.
    point : array_like, shape (3,)
        Reference point inside the modelled part of the plate.

    Returns
    -------
    LocalState

    Notes
    -----
    ``F`` at the point from :func:`~skfem_dielectric.models.plate.post.evaluate_fields`;
    the true displacement ``D = F D_L / J`` and the Cauchy stress from
    ``problem.stresses`` (the paper's Eqs. (const-rels1), (modelE)).
    """
    point = np.asarray(point, dtype=float)
    if point.shape != (3,) or not np.all(np.isfinite(point)):
        raise ValueError(f"point must be 3 finite coordinates, got {point}")
    xf = problem.full(x, load)
    fld = evaluate_fields(problem, xf, point[:, None])
    F = fld["F"][:, :, 0]
    st = problem.stresses(fld["F"], fld["G"], fld["p"], load)
    mu, eps = problem.material.mu, problem.material.eps
    C = F.T @ F
    plane = np.ix_([0, 2], [0, 2])
    w, v = np.linalg.eigh(C[plane])
    k1 = int(np.argmax(np.abs(v[0])))           # the axis nearer X1
    n1 = v[:, k1] * np.sign(v[0, k1])
    n3 = np.array([-n1[1], n1[0]])
    lam1, lam3 = math.sqrt(w[k1]), math.sqrt(w[1 - k1])
    sig = st["sigma"][:, :, 0] / mu
    # Cauchy stress along the deformed images of the principal axes
    a1 = F[:, [0, 2]] @ n1
    a3 = F[:, [0, 2]] @ n3
    a1, a3 = a1 / np.linalg.norm(a1), a3 / np.linalg.norm(a3)
    s22 = sig[1, 1]
    d = float(np.linalg.norm(st["D"][:, 0]) / math.sqrt(mu * eps))
    return LocalState(point=point, lam1=lam1, lam2=float(np.linalg.norm(F[:, 1])),
                      lam3=lam3, theta=float(math.atan2(n1[1], n1[0])),
                      J=float(np.linalg.det(F)), d=d, D0=d * lam1 * lam3,
                      D_L=float(np.linalg.norm(st["D_L"][:, 0]) / math.sqrt(mu * eps)),
                      sigma1=float(a1 @ sig @ a1 - s22), sigma3=float(a3 @ sig @ a3 - s22))


def energy_centroid(problem, x: np.ndarray, load, w_full: np.ndarray) -> np.ndarray:
    """Reference point where a mode's second-variation energy is centred, on the mid-plane.

    Parameters
    ----------
    problem : PlateProblem
        The FE plate.
    x, load
        The state the mode belongs to.
    w_full : ndarray
        Full dof vector of the mode (e.g. ``ModeLabel.mode``).

    Returns
    -------
    ndarray, shape (3,)
        ``(X1, 0, X3)``: the element centres weighted by ``|e_K|``, the element energies of
        :func:`~skfem_dielectric.models.plate.modes.element_energies`; ``X2 = 0`` because
        the homogeneous plate theory's state is uniform through the thickness.
    """
    e = np.abs(element_energies(problem, problem.full(x, load), w_full))
    m = problem.plate.mesh
    centres = m.p[:, m.t].mean(axis=1)
    c = centres @ e / e.sum()
    return np.array([c[0], 0.0, c[2]])


def half_waves(problem, w_full: np.ndarray, increments: dict, X1: float) -> int:
    """Half-waves of a mode's top-face deflection across the whole width at ``X1``.

    Parameters
    ----------
    problem : PlateProblem
        The FE plate.
    w_full : ndarray
        Full dof vector of the mode.
    increments : dict
        The mode's class parities (``ModeLabel.increments``), to unfold it across ``X3 = 0``.
    X1 : float
        Reference ``X1``; the row of top-face vertices nearest it is used.

    Returns
    -------
    int
        :func:`~validation.clamp_zone.modes.row_half_waves` of the mode's top face: sign
        changes of ``u2`` along ``X3`` plus one.
    """
    return row_half_waves(*top_deflection(problem, w_full, increments), X1)[3]


@dataclass(frozen=True)
class DirectionCriteria:
    """The homogeneous criteria for wrinkles along one in-plane principal axis.

    Attributes
    ----------
    direction : str
        ``"parallel"`` (wave vector along the ``lam1`` axis) or ``"perpendicular"``
        (along the ``lam3`` axis, Eq. (perpendicular-vars)).
    eta : float
        ``lam_in / lam2`` (``lam_in`` the stretch along the wave vector).
    sigma : float
        The homogeneous in-plane stress ``a - c`` (Eq. gent-moduli) along the wave vector.
    thin : float
        Thin-plate limit ``D0`` (Eq. thin-uni-axial); ``nan`` where ``eta < 1``: the thin
        plate is in compression and wrinkles at every ``D0``.
    thick : float
        Thick-plate (surface) limit ``D0`` under charge control (Eqs. short-wave,
        thick-uni-axial, thick-plate23); ``nan`` below the surface-instability stretch.
    kh : ndarray
        Wavenumber x deformed thickness of the dispersion curves (:data:`KH_GRID`).
    antisymmetric, symmetric : ndarray
        ``D0_c(kh)`` of the flexural and extensional families (``nan``: no root).
    kh_preferred, D0_preferred : float
        Where the flexural ``D0_c(kh)`` is smallest on the grid and its value.
    """

    direction: str
    eta: float
    sigma: float
    thin: float
    thick: float
    kh: np.ndarray
    antisymmetric: np.ndarray
    symmetric: np.ndarray
    kh_preferred: float
    D0_preferred: float


@dataclass(frozen=True)
class LocalCriteria:
    """The local state and the homogeneous criteria in its two principal directions.

    Attributes
    ----------
    state : LocalState
        The local homogeneous state the criteria are evaluated for.
    parallel, perpendicular : DirectionCriteria
        Wrinkles with the wave vector along the ``lam1`` axis (the load) and along the
        ``lam3`` axis (across the width).
    """

    state: LocalState
    parallel: DirectionCriteria
    perpendicular: DirectionCriteria


def local_criteria(state: LocalState, model: an.Model | None = None,
                   kh: np.ndarray | None = None) -> LocalCriteria:
    """The paper's wrinkling criteria for the homogeneous plate of a local state.

    Parameters
    ----------
    state : LocalState
        From :func:`local_state`.
    model : analytic.Model, optional
        The strain energy (default neo-Hookean), the FE material's counterpart.
    kh : ndarray, optional
        Wavenumbers x deformed thickness of the dispersion curves (default
        :data:`KH_GRID`).

    Returns
    -------
    LocalCriteria

    Raises
    ------
    ValueError
        If ``state`` is not a :class:`LocalState`.

    Notes
    -----
    Sections 4-5 of the paper for general in-plane stretches ``(lam1, lam3)``: thin limit
    Eq. (thin-uni-axial) (:func:`analytic.thin_limit_D0_uniaxial`), thick limit
    Eq. (detStroh) in the closed forms (thick-uni-axial), (thick-plate23)
    (:func:`analytic.thick_limit_D0_uniaxial`), and the finite-thickness dispersion of
    :func:`analytic.critical_D0_biaxial` (flexural and extensional); charge control.
    """
    if not isinstance(state, LocalState):
        raise ValueError(f"state must be a LocalState, got {type(state).__name__}")
    model = an.NeoHookean() if model is None else model
    kh = KH_GRID if kh is None else np.asarray(kh, dtype=float)
    l1, l3 = state.lam1, state.lam3
    lam2 = 1.0 / (l1 * l3)
    out = {}
    for direction in ("parallel", "perpendicular"):
        anti = np.asarray(an.critical_D0_biaxial(l1, l3, kh, model, "antisymmetric",
                                                 "charge", direction), dtype=float)
        sym = np.asarray(an.critical_D0_biaxial(l1, l3, kh, model, "symmetric",
                                                "charge", direction), dtype=float)
        ok = np.isfinite(anti)
        j = int(np.nanargmin(anti)) if ok.any() else -1
        fac = an.thin_plate_factors(l1, l3, state.D0, model, direction)
        out[direction] = DirectionCriteria(
            direction=direction, eta=(l1 if direction == "parallel" else l3) / lam2,
            sigma=float(fac[0]),
            thin=float(an.thin_limit_D0_uniaxial(l1, l3, model, direction)),
            thick=float(an.thick_limit_D0_uniaxial(l1, l3, model, direction, "charge")),
            kh=kh, antisymmetric=anti, symmetric=sym,
            kh_preferred=float(kh[j]) if j >= 0 else math.nan,
            D0_preferred=float(anti[j]) if j >= 0 else math.nan)
    return LocalCriteria(state=state, **out)


def first_firing(D0, margin) -> float:
    """First ramp ``D0`` where a criterion's ``margin = D0_local - D0_c`` reaches zero.

    Parameters
    ----------
    D0 : array_like
        The ramp's charge at each state (the FE load), increasing.
    margin : array_like
        ``D0_local - D0_c`` at each state; ``+inf`` where the criterion has already fired
        without a root (e.g. ``eta < 1`` for the thin limit), ``nan`` where it has no value.

    Returns
    -------
    float
        Linear interpolation between the last state below zero and the first with a
        non-negative margin (that state's ``D0`` when its margin is ``+inf`` or the one
        before it is ``nan``); the first ``D0`` if the margin starts non-negative; ``nan``
        if it never fires.

    Examples
    --------
    >>> from validation.clamp_zone.local_theory import first_firing
    >>> first_firing([1.0, 2.0, 3.0], [-1.0, -0.5, 0.5])
    2.5
    """
    D0, m = np.asarray(D0, dtype=float), np.asarray(margin, dtype=float)
    if D0.shape != m.shape or D0.ndim != 1:
        raise ValueError(f"D0 and margin must be 1-D of equal length, got {D0.shape}, {m.shape}")
    hit = np.flatnonzero(m >= 0)
    if not hit.size:
        return math.nan
    i = int(hit[0])
    if i == 0 or not (np.isfinite(m[i]) and np.isfinite(m[i - 1])):
        return float(D0[i])
    return float(D0[i - 1] - m[i - 1] * (D0[i] - D0[i - 1]) / (m[i] - m[i - 1]))

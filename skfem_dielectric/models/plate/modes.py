"""Classification of the modes of a plate's reduced stiffness.

A negative eigenvalue is physics only when its mode is: the indicators below say where a
mode of :func:`~skfem_dielectric.stability.tangent_stability` (or of a symmetry class,
:func:`~skfem_dielectric.models.plate.symmetry_classes.class_stability`) sits and at which
scale it varies; :func:`lowest_physical` is the lowest mode of the whole plate that sits
neither at a clamp corner nor at the mesh scale.

``energy_share``
    the share of the mode's second-variation energy in a set of elements.  The element
    energies ``e_K = w_K . (d r_K / d eps)(x + eps w)`` (central differences of the element
    internal forces along the mode) add up to ``w . K w``; the share is
    ``sum_{K in R} |e_K| / sum_K |e_K|``.
``corner_share``
    that share within a radius (default two thicknesses) of the lines where a clamp face
    meets a free edge -- where the clamped plate's discrete field is singular.
``mesh_scale``
    ``max_i sqrt(int h_i^2 |d_i w|^2 / int |w|^2) / pi`` over the directions ``i`` (``h_i``
    the element size): about ``2 h / l`` for a wave of half-length ``l``, so 1 for a mode
    that changes sign from element to element (checkerboard) and below 0.25 for a mode
    resolved by four or more elements per half-wave.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Sequence

import meshio
import numpy as np
from skfem import Functional

from ...checks import check_count, check_positive
from .problem import PlateProblem
from .symmetry_classes import class_mode_full, class_stability

__all__ = ["element_energies", "energy_share", "corner_elements", "corner_share",
           "mesh_scale", "classify_mode", "mode_mesh", "write_mode_vtu", "top_deflection",
           "ModeLabel", "LowestPhysical", "corner_radius", "physical_modes",
           "lowest_physical", "MESH_SCALE_LIMIT", "CORNER_LIMIT"]

#: a mode with a larger mesh-scale indicator is under-resolved (fewer than two elements
#: per half-wave): a discretisation artefact until a finer mesh shows otherwise
MESH_SCALE_LIMIT = 0.5
#: a mode with a larger corner share sits at a clamp/free-edge corner
CORNER_LIMIT = 0.5


def _check(problem, w_full):
    if not isinstance(problem, PlateProblem):
        raise ValueError(f"problem must be a PlateProblem, got {type(problem).__name__}")
    w_full = np.asarray(w_full, dtype=float)
    if w_full.shape != (problem.n_full,):
        raise ValueError(f"w_full must be a full dof vector of shape ({problem.n_full},), "
                         f"got {w_full.shape}")
    return w_full


def element_energies(problem: PlateProblem, xf: np.ndarray, w_full: np.ndarray,
                     h: float = 1e-6) -> np.ndarray:
    """Second-variation energy of the mode ``w_full`` per element at the full state ``xf``.

    Central differences of the element internal forces along the mode (step ``h`` relative
    to the mode's largest entry); their sum is ``w . K w`` to ``O(h^2)``.
    """
    w_full = _check(problem, w_full)
    f = problem.form
    eps = h / max(float(np.abs(w_full).max()), 1e-300)
    dr = (f.element_residuals(xf + eps * w_full) - f.element_residuals(xf - eps * w_full))
    return np.sum(w_full[f.edofs] * dr, axis=1) / (2 * eps)


def energy_share(energies: np.ndarray, elements: np.ndarray) -> float:
    """``sum |e_K|`` over ``elements`` (indices or a mask) over the total."""
    a = np.abs(np.asarray(energies, dtype=float))
    return float(a[elements].sum() / max(a.sum(), 1e-300))


def corner_elements(problem: PlateProblem, radius: float | None = None) -> np.ndarray:
    """Mask of the elements whose centroid lies within ``radius`` (default ``2 H``) of a
    line where a clamp face (``x1 = +-L1/2``) meets a free edge (``x3 = +-L3/2``);
    all ``False`` unless the plate is clamped (loading ``"uniaxial"``)."""
    pl = problem.plate
    m = pl.mesh
    c = m.p[:, m.t].mean(axis=1)
    if problem.loading != "uniaxial":
        return np.zeros(c.shape[1], dtype=bool)
    r = 2 * pl.H if radius is None else float(radius)
    d = np.hypot(np.abs(c[0]) - pl.L1 / 2, np.abs(c[2]) - pl.L3 / 2)
    return d <= r


def corner_share(problem: PlateProblem, xf: np.ndarray, w_full: np.ndarray,
                 radius: float | None = None) -> float:
    """Share of the mode's energy within ``radius`` of the clamp/free-edge corners."""
    return energy_share(element_energies(problem, xf, w_full),
                        corner_elements(problem, radius))


def mesh_scale(problem: PlateProblem, w_full: np.ndarray) -> float:
    """The mesh-scale indicator of the displacement of a mode (module docstring)."""
    w_full = _check(problem, w_full)
    b = problem.b2
    m = problem.plate.mesh
    ext = m.p[:, m.t].max(axis=1) - m.p[:, m.t].min(axis=1)         # (3, nel)
    num = np.zeros(3)
    den = 0.0
    for comp in range(3):
        u = b.interpolate(w_full[comp:problem.n_u:3])
        for i in range(3):
            num[i] += Functional(lambda w, i=i: w["h"] ** 2 * w["u"].grad[i] ** 2).assemble(
                b, u=u, h=np.broadcast_to(ext[i][:, None], b.dx.shape))
        den += Functional(lambda w: w["u"] ** 2).assemble(b, u=u)
    return float(np.sqrt(num.max() / max(den, 1e-300)) / np.pi)


def classify_mode(problem: PlateProblem, xf: np.ndarray, w_full: np.ndarray, *,
                  symmetry: str = "", radius: float | None = None) -> dict[str, Any]:
    """Indicators and verdict of one mode.

    Parameters
    ----------
    problem
        The plate whose dofs ``w_full`` and ``xf`` are (full vectors).
    xf
        Full state vector (``problem.full(x, load)``).
    w_full
        Full mode vector (e.g. ``problem.red.expand(w)`` or
        :func:`~skfem_dielectric.models.plate.symmetry_classes.class_mode_full`).
    symmetry
        Name of the mode's symmetry class (recorded).
    radius
        Corner radius (default two thicknesses).

    Returns
    -------
    dict
        ``corner_share``, ``mesh_scale``, ``symmetry`` and ``kind``: ``"mesh-scale"``
        (``mesh_scale > MESH_SCALE_LIMIT``), ``"corner"`` (``corner_share >
        CORNER_LIMIT``) or ``"physical"``.
    """
    cs = corner_share(problem, xf, w_full, radius)
    ms = mesh_scale(problem, w_full)
    kind = ("mesh-scale" if ms > MESH_SCALE_LIMIT else
            "corner" if cs > CORNER_LIMIT else "physical")
    return {"corner_share": cs, "mesh_scale": ms, "symmetry": symmetry, "kind": kind}


def mode_mesh(problem: PlateProblem, x: np.ndarray, load: Any, w_full: np.ndarray):
    """meshio ``Mesh`` of a state with one of its modes (reference coordinates).

    The state's data of :meth:`~skfem_dielectric.models.plate.problem.PlateProblem.step_mesh` plus
    point data ``mode_displacement`` (vector, the mode's unit-norm displacement),
    ``mode_potential`` and cell data ``mode_energy`` (:func:`element_energies`).
    """
    w_full = _check(problem, w_full)
    mesh = problem.step_mesh(x, load)
    nv = problem.plate.mesh.p.shape[1]
    mesh.point_data["mode_displacement"] = w_full[: problem.n_u].reshape(-1, 3)[:nv]
    mesh.point_data["mode_potential"] = w_full[problem.off_phi:][:nv]
    mesh.cell_data["mode_energy"] = [element_energies(problem, problem.full(x, load),
                                                      w_full)]
    return mesh


def write_mode_vtu(path: str | Path, problem: PlateProblem, x: np.ndarray, load: Any,
                   w_full: np.ndarray) -> Path:
    """Write :func:`mode_mesh` to ``path`` (``.vtu``) and return the path."""
    path = Path(path)
    if path.suffix != ".vtu":
        raise ValueError(f"path must end in .vtu, got {str(path)!r}")
    meshio.write(path, mode_mesh(problem, x, load, w_full))
    return path


def top_deflection(problem: PlateProblem, w_full: np.ndarray,
                   increments: dict[int, str] | None = None):
    """Out-of-plane displacement ``u2`` of a mode on the top face, unfolded to the whole
    plate through the symmetry planes ``x1 = 0`` and ``x3 = 0`` by the parity of the
    mode's class (``u2`` is even across a plane for a symmetric class, odd for an
    antisymmetric one; default: the model's own, symmetric).

    Returns
    -------
    X1, X3, u2 : ndarray
        Reference coordinates and values at the top-face vertices of the whole plate.
    """
    w_full = _check(problem, w_full)
    pl = problem.plate
    m = pl.mesh
    top = np.flatnonzero(np.abs(m.p[1] - m.p[1].max()) < 1e-9 * pl.H)
    X1, X3, u2 = m.p[0, top], m.p[2, top], w_full[3 * top + 1]
    inc = increments or {ax: "symmetric" for ax in pl.symmetry}
    for ax, row in ((1, 0), (3, 2)):
        if ax in pl.symmetry:
            keep = (X1 if row == 0 else X3) > 1e-12 * pl.L1
            sign = 1.0 if inc[ax] == "symmetric" else -1.0
            if row == 0:
                X1, X3, u2 = (np.concatenate([X1, -X1[keep]]), np.concatenate([X3, X3[keep]]),
                              np.concatenate([u2, sign * u2[keep]]))
            else:
                X1, X3, u2 = (np.concatenate([X1, X1[keep]]), np.concatenate([X3, -X3[keep]]),
                              np.concatenate([u2, sign * u2[keep]]))
    return X1, X3, u2


@dataclass
class ModeLabel:
    """One classified mode of the whole plate at a state.

    Attributes
    ----------
    eigenvalue
        Eigenvalue of the reduced stiffness (metric of the full plate's nodal displacements).
    symmetry
        Name of its symmetry class (e.g. ``"x1 S, x2 A, x3 S"``).
    increments
        The class's parities, axis -> ``"symmetric"`` / ``"antisymmetric"``.
    corner_share, mesh_scale, kind
        As :func:`classify_mode` (radius :func:`corner_radius`).
    mode
        Full dof vector of the mode.
    """

    eigenvalue: float
    symmetry: str
    increments: dict
    corner_share: float
    mesh_scale: float
    kind: str
    mode: np.ndarray = field(repr=False)


@dataclass
class LowestPhysical:
    """The lowest physical mode of the whole plate at a state (:func:`lowest_physical`).

    Attributes
    ----------
    label
        Its :class:`ModeLabel`; ``None`` if no computed mode is physical.
    labels
        Every classified mode up to it, ascending (:func:`physical_modes`).
    n_negative
        Negative eigenvalues of the whole plate's reduced stiffness (of the classes
        analysed).
    """

    label: ModeLabel | None
    labels: list[ModeLabel]
    n_negative: int

    @property
    def eigenvalue(self) -> float:
        """The lowest physical eigenvalue (``nan`` if no computed mode is physical): the
        indicator of :func:`~skfem_dielectric.solvers.critical.critical_load` for a plate."""
        return self.label.eigenvalue if self.label is not None else float("nan")


def corner_radius(problem: PlateProblem) -> float:
    """Radius of the clamp/free-edge corner zone: ``max(2 H, d)`` with ``d`` the in-plane
    diagonal of the element at the corner.

    :func:`corner_elements` selects elements by their centroid within the radius of a
    corner line.  On a mesh whose elements are larger than ``2 H`` in the plane the
    element *at* the corner has its centroid farther away than that and would not count
    (10 x 1 x 5 eighth model of the 100 x 1 x 50 plate: 96 % of a mode's energy in that
    element, corner share 0.00 with the radius ``2 H``); with at least the diagonal, the
    element touching the corner always belongs to the corner zone.
    """
    if not isinstance(problem, PlateProblem):
        raise ValueError(f"problem must be a PlateProblem, got {type(problem).__name__}")
    g1, _, g3 = problem.plate.grids
    d = float(np.hypot(g1[-1] - g1[-2], g3[-1] - g3[-2]))
    return max(2.0 * problem.plate.H, d)


def physical_modes(problem: PlateProblem, x: np.ndarray, load: Any, *, extra: int = 2,
                   grad_div: float | None = None, method: str = "auto",
                   radius: float | None = None, stop_at_physical: bool = True,
                   only: Sequence[str] | None = None) -> tuple[list[ModeLabel], int]:
    """Classified modes of the whole plate at a state, ascending.

    Every negative eigenpair of each symmetry class and ``extra`` more above them
    (:func:`~skfem_dielectric.models.plate.symmetry_classes.class_stability` with
    ``all_negative``) are classified (:func:`classify_mode`) in ascending order of the
    eigenvalue over all classes.

    Parameters
    ----------
    problem, x, load
        A symmetric-coupling plate and a converged state of it.
    extra
        Eigenpairs above the negative ones, per class (at least 1).
    grad_div, method
        Grad-div stabilisation of the analysed tangent (units of ``mu``; default the
        model's own: the Hessian of the state's energy) and inertia method, as
        :func:`~skfem_dielectric.models.plate.symmetry_classes.class_stability`.
    radius
        Corner radius (default :func:`corner_radius`).
    stop_at_physical
        Stop classifying after the first physical mode.
    only
        Names of the classes to analyse (default all, the whole plate).

    Returns
    -------
    labels : list of ModeLabel
        The classified modes, ascending.
    n_negative : int
        Negative eigenvalues of the whole plate's reduced stiffness (of the classes
        ``only``).
    """
    extra = check_count("extra", extra)
    r = corner_radius(problem) if radius is None else check_positive("radius", radius)
    cs = class_stability(problem, x, load, k=0, grad_div=grad_div, method=method,
                         all_negative=True, extra=extra, only=only)
    xf = problem.full(x, load)
    order = sorted((float(v), i, j) for i, res in enumerate(cs.results)
                   for j, v in enumerate(res.eigenvalues))
    out = []
    for v, i, j in order:
        c = cs.classes[i]
        w = class_mode_full(c, cs.results[i].modes[:, j])
        lab = classify_mode(problem, xf, w, symmetry=c.name, radius=r)
        out.append(ModeLabel(v, c.name, dict(c.increments), lab["corner_share"],
                             lab["mesh_scale"], lab["kind"], w))
        if stop_at_physical and lab["kind"] == "physical":
            break
    return out, cs.n_negative


def lowest_physical(problem: PlateProblem, x: np.ndarray, load: Any, *, extra: int = 2,
                    grad_div: float | None = None, method: str = "auto",
                    radius: float | None = None,
                    only: Sequence[str] | None = None) -> LowestPhysical:
    """The lowest mode of the whole plate at a state whose energy is neither at a clamp
    corner nor at the mesh scale.

    A negative eigenvalue of the discrete plate is physics only when its mode is
    (module docstring); the lowest physical eigenvalue is therefore the indicator whose
    zero crossing is the first buckling load
    (:func:`~skfem_dielectric.solvers.critical.critical_load`), the discrete counterpart of
    the bifurcation that the paper's breakdown criterion (Sec. 6, compressive ``P33`` near
    the clamps) anticipates.

    Parameters
    ----------
    problem, x, load, extra, grad_div, method, radius, only
        As :func:`physical_modes`.

    Returns
    -------
    LowestPhysical
        ``label`` is ``None`` (``eigenvalue`` ``nan``) if no computed mode is physical.
    """
    labels, n_neg = physical_modes(problem, x, load, extra=extra, grad_div=grad_div,
                                   method=method, radius=radius, only=only)
    phys = [m for m in labels if m.kind == "physical"]
    return LowestPhysical(phys[0] if phys else None, labels, n_neg)

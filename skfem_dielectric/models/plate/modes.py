"""Classification of the modes of a plate's reduced stiffness.

A negative eigenvalue is physics only when its mode is: the indicators below say where a
mode of :func:`~skfem_dielectric.tangent_stability` (or of a symmetry class,
:func:`~skfem_dielectric.class_stability`) sits and at which scale it varies.

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

from pathlib import Path
from typing import Any

import meshio
import numpy as np
from skfem import Functional

from .problem import PlateProblem
from .symmetry_classes import class_mode_full, class_stability

__all__ = ["element_energies", "energy_share", "corner_elements", "corner_share",
           "mesh_scale", "classify_mode", "lowest_physical_eigenvalue", "mode_mesh",
           "write_mode_vtu", "top_deflection",
           "MESH_SCALE_LIMIT", "CORNER_LIMIT"]

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


def lowest_physical_eigenvalue(problem: PlateProblem, x: np.ndarray, load: Any, *,
                               k: int = 4, grad_div: float | None = None,
                               radius: float | None = None) -> tuple[float, dict]:
    """The lowest eigenvalue over every symmetry class whose mode is classified
    ``"physical"`` (:func:`classify_mode`), and that mode's labels.

    The ``k`` lowest modes of each class (at least all negative ones) are classified in
    ascending order.  If none of them is physical, the largest computed eigenvalue is
    returned (a lower bound of the lowest physical one) with ``kind = "none found"``.
    The indicator of :func:`~skfem_dielectric.solvers.critical.critical_load` for a plate.
    """
    cs = class_stability(problem, x, load, k=k, grad_div=grad_div, all_negative=True)
    xf = problem.full(x, load)
    names = [c.name for c in cs.classes]
    vals = cs.lowest()
    for v, name, j in vals:
        i = names.index(name)
        w = class_mode_full(cs.classes[i], cs.results[i].modes[:, j])
        lab = classify_mode(problem, xf, w, symmetry=name, radius=radius)
        if lab["kind"] == "physical":
            return float(v), lab
    return float(vals[-1][0]), {"kind": "none found", "symmetry": ""}

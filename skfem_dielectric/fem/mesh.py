"""Hexahedral plate meshes with named boundaries and symmetry options.

Axes follow the paper: ``x1`` length (load direction), ``x2`` thickness (field direction),
``x3`` width.  The full plate occupies ``[-L1/2, L1/2] x [-H/2, H/2] x [-L3/2, L3/2]``; each
symmetry plane used cuts the model at ``x_i = 0`` and keeps the positive half.

Boundary names (present when the corresponding face exists):

========== ==================================================================
``top``     ``x2 = +H/2`` (charged / electrode face)
``bottom``  ``x2 = -H/2`` (absent with the ``x2`` symmetry plane)
``x1_plus``  ``x1 = +L1/2`` (lateral face or clamp face)
``x1_minus`` ``x1 = -L1/2`` (absent with the ``x1`` symmetry plane)
``x3_plus``  ``x3 = +L3/2`` (lateral face or free edge)
``x3_minus`` ``x3 = -L3/2`` (absent with the ``x3`` symmetry plane)
``sym_x1``, ``sym_x2``, ``sym_x3``  the symmetry planes ``x_i = 0`` that are used
========== ==================================================================
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np
from skfem import MeshHex

from ..checks import check_count, check_positive

__all__ = ["PlateMesh", "plate_mesh", "SYMMETRIES"]

#: named symmetry choices -> axes (1, 2, 3) whose ``x_i = 0`` plane is a symmetry plane
SYMMETRIES = {"full": (), "half": (2,), "quarter": (1, 3), "eighth": (1, 2, 3)}


@dataclass(frozen=True)
class PlateMesh:
    """A hexahedral plate mesh and its geometry.

    Attributes
    ----------
    mesh
        scikit-fem ``MeshHex`` (trilinear geometry) with named boundaries.
    L1, H, L3
        Full plate dimensions (length, thickness, width).
    symmetry
        Axes whose ``x_i = 0`` plane is a symmetry plane of the model.
    grids
        The three 1-D node coordinate arrays of the tensor-product mesh.
    """

    mesh: MeshHex
    L1: float
    H: float
    L3: float
    symmetry: tuple[int, ...]
    grids: tuple[np.ndarray, np.ndarray, np.ndarray]

    @property
    def fraction(self) -> float:
        """Volume fraction of the full plate that the model represents (1, 1/2, ..., 1/8)."""
        return 0.5 ** len(self.symmetry)

    @property
    def boundary_names(self) -> tuple[str, ...]:
        """Names of the boundaries of the model."""
        return tuple(self.mesh.boundaries.keys())

    def facets(self, name: str) -> np.ndarray:
        """Facet indices of the boundary ``name``.

        Raises
        ------
        ValueError
            If the model has no boundary of that name.
        """
        if name not in self.mesh.boundaries:
            raise ValueError(f"unknown boundary {name!r}; this model has "
                             f"{self.boundary_names}")
        return self.mesh.boundaries[name]


def plate_mesh(L1: float, H: float, L3: float, n1: int, n2: int, n3: int,
               symmetry: str | Sequence[int] = "eighth",
               grading: float = 1.0) -> PlateMesh:
    """Structured hexahedral mesh of a plate, layered through the thickness.

    Parameters
    ----------
    L1, H, L3
        Full length (x1), thickness (x2) and width (x3) of the plate (> 0, any unit).
    n1, n2, n3
        Number of elements of the *model* along x1, x2, x3 (after symmetry cuts).
    symmetry
        ``"full"``, ``"half"`` (x2 plane), ``"quarter"`` (x1 and x3 planes) or
        ``"eighth"`` (all three), or a tuple of axes among ``(1, 2, 3)``.
    grading
        Ratio of the last to the first element length along x1 (geometric grading towards
        ``x1 = +L1/2``, e.g. to refine near a clamp); 1 = uniform.

    Returns
    -------
    PlateMesh

    Raises
    ------
    ValueError
        For non-positive sizes, counts or grading, or an unknown symmetry.
    """
    L1, H, L3 = check_positive("L1", L1), check_positive("H", H), check_positive("L3", L3)
    n1, n2, n3 = check_count("n1", n1), check_count("n2", n2), check_count("n3", n3)
    grading = check_positive("grading", grading)
    if isinstance(symmetry, str):
        if symmetry not in SYMMETRIES:
            raise ValueError(f"symmetry must be one of {tuple(SYMMETRIES)} or a tuple of axes, "
                             f"got {symmetry!r}")
        axes = SYMMETRIES[symmetry]
    else:
        try:
            axes = tuple(sorted(set(symmetry)))
        except TypeError:
            axes = (None,)
        if any(isinstance(a, bool) or a not in (1, 2, 3) for a in axes):
            raise ValueError(f"symmetry must be a name or a tuple of axes among (1, 2, 3), "
                             f"got {symmetry!r}")
        axes = tuple(int(a) for a in axes)

    def grid(L, n, ax, grade=1.0):
        lo = 0.0 if ax in axes else -L / 2
        hi = L / 2
        if grade == 1.0 or n == 1:
            return np.linspace(lo, hi, n + 1)
        q = grade ** (1.0 / (n - 1))
        w = q ** np.arange(n)
        return lo + (hi - lo) * np.concatenate([[0.0], np.cumsum(w) / w.sum()])

    g1, g2, g3 = grid(L1, n1, 1, grading), grid(H, n2, 2), grid(L3, n3, 3)
    m = MeshHex.init_tensor(g1, g2, g3)
    tol = 1e-9 * min(L1, H, L3)
    faces = {
        "top": lambda x: np.abs(x[1] - H / 2) < tol,
        "x1_plus": lambda x: np.abs(x[0] - L1 / 2) < tol,
        "x3_plus": lambda x: np.abs(x[2] - L3 / 2) < tol,
    }
    if 2 in axes:
        faces["sym_x2"] = lambda x: np.abs(x[1]) < tol
    else:
        faces["bottom"] = lambda x: np.abs(x[1] + H / 2) < tol
    if 1 in axes:
        faces["sym_x1"] = lambda x: np.abs(x[0]) < tol
    else:
        faces["x1_minus"] = lambda x: np.abs(x[0] + L1 / 2) < tol
    if 3 in axes:
        faces["sym_x3"] = lambda x: np.abs(x[2]) < tol
    else:
        faces["x3_minus"] = lambda x: np.abs(x[2] + L3 / 2) < tol
    m = m.with_boundaries(faces)
    return PlateMesh(mesh=m, L1=L1, H=H, L3=L3, symmetry=axes, grids=(g1, g2, g3))

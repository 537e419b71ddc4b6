"""The problem contract: what every FE model provides to Newton, the ramp and export.

A *problem* is a discretised model whose unknowns have been reduced (Dirichlet conditions
eliminated, tied dofs such as a rigid clamp merged into one unknown).  The machinery of
the package -- :func:`~skfem_dielectric.solvers.newton.newton`,
:func:`~skfem_dielectric.solvers.ramp.ramp`, :mod:`~skfem_dielectric.export` -- and the
stability and continuation analyses work on any subclass of :class:`Problem`; they never
look inside a model.

What a model implements (abstract):

``layout``
    a :class:`Layout`: the number of reduced unknowns, the reduced indices of each field
    block (``"u"``, ``"p"``, ``"phi"``, ``"lam3"``, ...), and which blocks are
    constraint multipliers or potentials (``"p"``, ``"phi"``: the directions in which
    the energy is maximised, not minimised).
``initial_state()``
    the reduced vector of the unloaded state.
``assemble(x, load) -> (K, r)``
    reduced sparse tangent ``dr/dx`` (CSR) and residual ``r``.

What it may override (the defaults are correct, sometimes slower):

``assemble_upper(x, load)``
    the symmetric tangent as its upper triangle (what the symmetric PARDISO reads);
    default: the triangle of :meth:`Problem.assemble`'s tangent.
``residual(x, load)``
    the residual alone (line search); default ``assemble(x, load)[1]``.
``residual_scale(load)``
    the scale of the relative Newton tolerance (typically the norm of the external load
    vector); default ``None``: relative to the first residual of each solve.
``load_vector(x, load)``
    ``dr/dload``, shape ``(n, n_load)``, the load direction of arc-length continuation;
    default: central differences of :meth:`Problem.residual`, exact to round-off where
    the load enters linearly (dead loads, charges).
``postprocess(x, load) -> dict``
    quantities of a converged state stored in each ramp step; default ``{}``.
``step_mesh(x, load) -> meshio.Mesh``
    the state for ParaView (:mod:`skfem_dielectric.export`); default raises.
``stability(inertia)``
    the stability verdict from the inertia of the reduced tangent; default: stable iff
    the tangent has exactly as many negative eigenvalues as the multiplier and potential
    unknowns and no zero eigenvalue (Haynsworth inertia additivity for a saddle-point
    matrix whose multiplier blocks are definite), ``None`` for a non-symmetric tangent
    or an unknown inertia.

Attributes every problem sets: ``load_names`` (names of the load components, e.g.
``("s", "D0")``) and ``symmetric`` (whether the tangent is symmetric: the ramp then uses
a symmetric solver; a follower load makes it non-symmetric).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp

from .fem.assembly import DofReduction
from .linalg.symmetric import SymmetricUpper

__all__ = ["Layout", "Problem"]


@dataclass(frozen=True)
class Layout:
    """Reduced unknowns of a problem, by field block.

    Attributes
    ----------
    n
        Number of reduced unknowns.
    blocks
        Field name -> sorted reduced indices of that field (e.g. ``"u"``, ``"p"``,
        ``"phi"``, ``"lam3"``); every unknown belongs to exactly one block.
    multipliers
        Names of the blocks that are constraint multipliers or potentials (the energy is
        stationary-maximal there: ``"p"`` enforces ``J = 1``, ``"phi"`` is the potential
        of the charge-controlled energy).  Their count is the number of negative
        eigenvalues a stable saddle-point tangent has.
    """

    n: int
    blocks: dict[str, np.ndarray] = field(default_factory=dict)
    multipliers: tuple[str, ...] = ()

    def __post_init__(self):
        unknown = [b for b in self.multipliers if b not in self.blocks]
        if unknown:
            raise ValueError(f"multipliers must name blocks of {sorted(self.blocks)}, "
                             f"got {unknown}")

    @classmethod
    def from_reduction(cls, red: DofReduction, fields: dict[str, slice],
                       multipliers: tuple[str, ...] = ()) -> "Layout":
        """Layout of a :class:`~skfem_dielectric.fem.assembly.DofReduction` whose full dofs
        are grouped in contiguous ranges ``fields`` (name -> slice of full dofs)."""
        blocks = {}
        for name, sl in fields.items():
            idx = red.index[sl]
            blocks[name] = np.unique(idx[idx >= 0])
        return cls(red.n, blocks, tuple(m for m in multipliers if m in blocks))

    @classmethod
    def single(cls, n: int, name: str = "u") -> "Layout":
        """All ``n`` unknowns in one block ``name`` without multipliers."""
        return cls(int(n), {name: np.arange(int(n))})

    @property
    def n_multipliers(self) -> int:
        """Number of multiplier and potential unknowns."""
        return int(sum(self.blocks[b].size for b in self.multipliers))


class Problem(ABC):
    """Base class of every FE model (see the module docstring for the contract)."""

    #: names of the load components
    load_names: tuple[str, ...] = ("load",)
    #: whether :meth:`assemble` returns a symmetric tangent
    symmetric: bool = True

    @property
    @abstractmethod
    def layout(self) -> Layout:
        """The reduced unknowns by field block (:class:`Layout`)."""

    @abstractmethod
    def initial_state(self) -> np.ndarray:
        """Reduced vector of the unloaded state."""

    @abstractmethod
    def assemble(self, x: np.ndarray, load: Any) -> tuple[sp.csr_matrix, np.ndarray]:
        """Reduced tangent and residual at the reduced state ``x`` and ``load``."""

    @property
    def ndofs(self) -> int:
        """Number of reduced unknowns."""
        return self.layout.n

    def assemble_upper(self, x: np.ndarray, load: Any) -> tuple[SymmetricUpper, np.ndarray]:
        """The symmetric tangent as its upper triangle
        (:class:`~skfem_dielectric.linalg.symmetric.SymmetricUpper`) and the residual, for a
        solver that reads only that triangle (the ramp's Newton iterations with the
        symmetric PARDISO); default: from :meth:`assemble`.  Models override it to
        assemble the triangle directly."""
        K, r = self.assemble(x, load)
        return SymmetricUpper.from_full(K), r

    def residual(self, x: np.ndarray, load: Any) -> np.ndarray:
        """Reduced residual (default: from :meth:`assemble`)."""
        return self.assemble(x, load)[1]

    def residual_scale(self, load: Any) -> float | None:
        """Scale of the relative Newton tolerance (``None``: the first residual)."""
        return None

    def load_vector(self, x: np.ndarray, load: Any, h: float = 1e-6) -> np.ndarray:
        """``d residual / d load`` at ``(x, load)``, shape ``(n, n_load)``.

        The default differentiates :meth:`residual` by central differences of step
        ``h (1 + |load_k|)`` per component: exact to round-off where the load enters
        linearly, ``O(h^2)`` otherwise.  Models override it with the closed form.
        """
        ld = np.atleast_1d(np.asarray(load, dtype=float))
        cols = []
        for k in range(ld.size):
            dk = h * (1.0 + abs(ld[k]))
            lp, lm = ld.copy(), ld.copy()
            lp[k] += dk
            lm[k] -= dk
            shape = np.shape(load)
            cols.append((self.residual(x, lp.reshape(shape)) - self.residual(x, lm.reshape(shape)))
                        / (2.0 * dk))
        return np.stack(cols, axis=1)

    def postprocess(self, x: np.ndarray, load: Any) -> dict[str, Any]:
        """Quantities of a converged state (default: none)."""
        return {}

    def step_mesh(self, x: np.ndarray, load: Any):
        """meshio ``Mesh`` of a state (for :mod:`skfem_dielectric.export`)."""
        raise ValueError(f"{type(self).__name__} does not export meshes (step_mesh)")

    def newton_guards(self) -> dict[str, Any]:
        """Ramp options that keep Newton's iterates admissible states of the model:
        ``step_limit(x, dx, load) -> alpha_max`` and ``admissible(x, load) -> reason`` of
        :func:`~skfem_dielectric.solvers.ramp.ramp`; none (``{}``) by default.  The drivers
        pass them to every ramp of the model."""
        return {}

    def stability(self, inertia: tuple[int, int, int] | None) -> bool | None:
        """Stability verdict from the inertia ``(n_pos, n_neg, n_zero)`` of the reduced
        tangent: ``True`` iff it has exactly ``layout.n_multipliers`` negative and no zero
        eigenvalues; ``None`` if the inertia is unknown or the tangent is not symmetric."""
        if inertia is None or not self.symmetric:
            return None
        _, nneg, nzero = inertia
        return bool(nneg == self.layout.n_multipliers and nzero == 0)

"""What the harness runs: :class:`RunSpec` (one FE ramp) and :class:`Case` (one figure).

Plain data with their argument checks, and the plate and material data that the FE
side (:mod:`validation.fe`) and the analytic side (:mod:`validation.cases`) share.

Keplinger plate (paper Sec. 6): 100 mm x 50 mm x 1 mm, ``mu = 9833.07 Pa``,
``m = 150 g``, ``A = 50 mm^2`` and ``g = 9.81 m/s^2``, so
``s = alpha m g / (mu A) = 2.99296 alpha``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

#: the tolerance in ``D0`` to which every located load (``D0_b``, ``D0_c``, a ``P33``
#: onset) is found: the least error of a graded load, whatever its meshes' spread
LOCATION_TOL = 1e-4

__all__ = ["KEPLINGER", "ALPHAS", "GENT_JM", "MODELS", "VARIANTS", "GEOMETRIES", "RunSpec",
           "Case"]

#: Keplinger et al. plate and weight, SI units; ``g`` stated explicitly.
KEPLINGER = {"length": 0.100, "width": 0.050, "thickness": 0.001, "mu": 9833.07,
             "mass": 0.150, "area": 50e-6, "g": 9.81}
#: Weight fractions of the paper's Fig. uni-axial-ideal.
ALPHAS = (0.05, 0.3, 0.7, 1.0, 1.5)
#: Stiffening parameter of the Gent model, FE and analytic alike.
GENT_JM = 97.2

#: Strain energies, FE variants and loadings a :class:`RunSpec` may name.
MODELS = ("neo-Hookean", "Gent")
VARIANTS = ("coupled", "maxwell", "membrane", "membrane-maxwell")
GEOMETRIES = ("equibiaxial", "uniaxial", "uniaxial-free")


@dataclass(frozen=True)
class RunSpec:
    """One FE ramp: a pre-load followed by charge targets.

    Parameters
    ----------
    geometry : {"equibiaxial", "uniaxial", "uniaxial-free"}
        Homogeneous equi-biaxial dead-load plate, the clamped Keplinger
        plate carrying a weight, or a homogeneous uni-axial dead load (free
        lateral edges, no clamps).
    model : {"neo-Hookean", "Gent"}
        Strain energy (Gent with ``Jm = GENT_JM = 97.2``).
    variant : {"coupled", "maxwell", "membrane", "membrane-maxwell"}
        3D fully coupled ``u-p-phi`` solver, 3D Maxwell-traction variant (field
        of the potential solved on the deformed body), or
        the 2D membrane model (in-plane, exact incompressibility) with the
        electric energy in the total energy (``"membrane"``) or with the
        Maxwell traction of the local field as a follower load
        (``"membrane-maxwell"``; exact on homogeneous states only).
    s : float or None
        Dimensionless dead load (equi-biaxial traction, or weight/(mu A)).  ``None`` for
        a Keplinger run given by its weight fraction ``alpha``: the FE runner sets it,
        :func:`validation.fe.model.with_dead_load` (the FE package's dead load, so that
        the cases need no finite elements).
    D0 : tuple of float
        Charge targets, increasing, the first one ``0`` (the pre-load).
    alpha : float or None
        Weight fraction (uni-axial runs only).
    mesh : tuple of (str, int)
        Mesh divisions ``(("n1", .), ("n2", .), ("n3", .))`` along length,
        thickness and width.
    record_fields : bool
        Also store the centre-line profile (``P33``, stretches) of every step.
    record_maps : bool
        Also store the mid-plane stretch maps of the pre-loaded plate (``D0 = 0``).
    stop_at_breakdown : bool
        End the ramp at the first step where ``P33`` near the clamps turns
        compressive (the paper's breakdown), as the paper's COMSOL runs did.
    buckling : bool
        Also analyse every converged state of the clamped plate with the whole plate's
        spectrum (every symmetry class of the eighth model,
        scanned event by event, :class:`skfem_dielectric.models.plate.scan.PlateScan`): the columns
        ``n_negative_plate``, ``physical_eig``, ``physical_class`` and ``stable``, and
        ``D0_b``, the stability-based breakdown where that eigenvalue crosses zero,
        located to ``1e-4`` (:func:`skfem_dielectric.studies.buckling.buckling_load`, as
        the study ``buckling``).  Those columns are of the grad-div form
        (``grad_div = 10``, :func:`validation.fe.model.buckling_problem`) ramped to the
        same loads, so that the analysed tangent is the Hessian of its own state; every
        other column is of the plain form, as in every other run (docs/stability.md,
        "Which state each column is of").
    """

    geometry: str
    model: str
    variant: str
    s: float | None
    D0: tuple
    alpha: float | None = None
    mesh: tuple = (("n1", 1), ("n2", 1), ("n3", 1))
    record_fields: bool = False
    record_maps: bool = False
    stop_at_breakdown: bool = True
    buckling: bool = False

    def __post_init__(self):
        if self.geometry not in GEOMETRIES:
            raise ValueError(f"geometry must be one of {GEOMETRIES}, got {self.geometry!r}")
        if self.model not in MODELS:
            raise ValueError(f"model must be one of {MODELS}, got {self.model!r}")
        if self.variant not in VARIANTS:
            raise ValueError(f"variant must be one of {VARIANTS}, got {self.variant!r}")
        if self.s is None:
            if self.geometry != "uniaxial" or self.alpha is None:
                raise ValueError(f"s may be None only for a uniaxial run given by its alpha, "
                                 f"got geometry {self.geometry!r} and alpha {self.alpha!r}")
        elif not np.isfinite(self.s) or self.s < 0:
            raise ValueError(f"s must be >= 0 and finite, got {self.s!r}")
        D0 = np.asarray(self.D0, dtype=float)
        if D0.ndim != 1 or D0.size < 1 or np.any(~np.isfinite(D0)) or np.any(D0 < 0) \
                or np.any(np.diff(D0) <= 0):
            raise ValueError(f"D0 must be a non-empty increasing sequence >= 0, got {self.D0!r}")
        object.__setattr__(self, "D0", tuple(float(d) for d in D0))

    @property
    def key(self) -> str:
        """Stable identifier, used for state files and the CSV ``run`` column."""
        parts = [self.geometry, "nh" if self.model == "neo-Hookean" else "gent", self.variant]
        parts.append(f"a{self.alpha:g}" if self.alpha is not None else f"s{self.s:g}")
        return "_".join(parts)

    @property
    def mesh_dict(self) -> dict:
        """The mesh divisions as a ``dict`` (``{"n1": ., "n2": ., "n3": .}``)."""
        return dict(self.mesh)


@dataclass(frozen=True)
class Case:
    """A paper figure and the FE ramps overlaid on it.

    Attributes
    ----------
    name : str
        CLI name, e.g. ``"uni-axial-ideal"``.
    figure : str
        The paper's figure label.
    title : str
        One-line description.
    geometry : str
        ``"equibiaxial"`` or ``"uniaxial"`` (decides the CSV columns).
    quick, full : tuple of RunSpec
        The FE ramps of a quick and of a full run.
    """

    name: str
    figure: str
    title: str
    geometry: str
    quick: tuple = field(default=())
    full: tuple = field(default=())

    def runs(self, quick: bool = False) -> tuple:
        """The FE ramps of this case."""
        return self.quick if quick else self.full

"""The validation cases: one per figure of the paper.

A :class:`Case` names a paper figure and lists the FE ramps (:class:`RunSpec`)
whose dots are drawn over its analytic curves. Each ramp is a mechanical
pre-load (the first target, ``D0 = 0``) followed by a charge ramp through the
listed ``D0`` targets. ``quick`` runs use coarse meshes and few charge steps
(the README's main job), full runs the paper's resolution.

Keplinger plate (paper Sec. 6, DESIGN.md §2): 100 mm x 50 mm x 1 mm,
``mu = 9833.07 Pa``, ``m = 150 g``, ``A = 50 mm^2`` and ``g = 9.81 m/s^2``, so
``s = alpha m g / (mu A) = 2.99296 alpha``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

import analytic as an

__all__ = [
    "KEPLINGER",
    "ALPHAS",
    "RunSpec",
    "Case",
    "CASES",
    "get_case",
    "analytic_model",
    "keplinger_s",
    "FE_VARIANTS",
    "KEPLINGER_VARIANTS",
]

#: Keplinger et al. plate and weight, SI units; ``g`` stated explicitly.
KEPLINGER = {"length": 0.100, "width": 0.050, "thickness": 0.001, "mu": 9833.07,
             "mass": 0.150, "area": 50e-6, "g": 9.81}
#: Weight fractions of the paper's Fig. uni-axial-ideal.
ALPHAS = (0.05, 0.3, 0.7, 1.0, 1.5)

MODELS = ("neo-Hookean", "Gent")
VARIANTS = ("coupled", "maxwell", "membrane", "membrane-maxwell")
GEOMETRIES = ("equibiaxial", "uniaxial", "uniaxial-free")


def keplinger_s(alpha):
    """Dimensionless dead load ``s = alpha m g/(mu A)`` of the Keplinger plate.

    Parameters
    ----------
    alpha : float or array_like
        Fraction of the 150 g weight, ``alpha > 0``.

    Returns
    -------
    float or ndarray
        ``s`` with ``g = 9.81 m/s^2`` (paper caption of Fig. uni-axial-ideal).

    Examples
    --------
    >>> round(keplinger_s(1.0), 5)
    2.99296
    """
    a = np.asarray(alpha, dtype=float)
    if np.any(~np.isfinite(a)) or np.any(a < 0):
        raise ValueError(f"alpha must be >= 0 and finite, got {alpha!r}")
    k = KEPLINGER
    s = a * k["mass"] * k["g"] / (k["mu"] * k["area"])
    return float(s) if s.ndim == 0 else s


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
        Strain energy (Gent with ``Jm = 97.2``).
    variant : {"coupled", "maxwell", "membrane", "membrane-maxwell"}
        3D fully coupled ``u-p-phi`` solver, 3D Maxwell-traction variant (field
        of the potential solved on the deformed body), or
        the 2D membrane model (in-plane, exact incompressibility) with the
        electric energy in the total energy (``"membrane"``) or with the
        Maxwell traction of the local field as a follower load
        (``"membrane-maxwell"``; exact on homogeneous states only).
    s : float
        Dimensionless dead load (equi-biaxial traction, or weight/(mu A)).
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
    """

    geometry: str
    model: str
    variant: str
    s: float
    D0: tuple
    alpha: float | None = None
    mesh: tuple = (("n1", 1), ("n2", 1), ("n3", 1))
    record_fields: bool = False
    record_maps: bool = False
    stop_at_breakdown: bool = True

    def __post_init__(self):
        if self.geometry not in GEOMETRIES:
            raise ValueError(f"geometry must be one of {GEOMETRIES}, got {self.geometry!r}")
        if self.model not in MODELS:
            raise ValueError(f"model must be one of {MODELS}, got {self.model!r}")
        if self.variant not in VARIANTS:
            raise ValueError(f"variant must be one of {VARIANTS}, got {self.variant!r}")
        if not np.isfinite(self.s) or self.s < 0:
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


def _steps(D0max: float, n: int) -> tuple:
    return tuple(float(d) for d in np.linspace(0.0, D0max, n + 1))


#: FE variants drawn on the homogeneous cases (3D fully coupled, 2D membrane with
#: energy coupling and with the local-field Maxwell traction, which is exact on
#: homogeneous states). The 3D model has no free uni-axial loading, so Fig. figde gets
#: membrane dots only.
FE_VARIANTS = ("coupled", "membrane", "membrane-maxwell")
#: FE variants of the clamped Keplinger plate: 3D fully coupled, 3D Maxwell traction
#: (field of the potential solved on the deformed body) and the energy-coupled membrane.
#: The local-field membrane Maxwell variant is left out: its field (charge over the local
#: area stretch) is exact only on homogeneous states and 1-4 % off near the clamps
#: (docs/validation.md).
KEPLINGER_VARIANTS = ("coupled", "maxwell", "membrane")
HOMOGENEOUS_MESH = (("n1", 1), ("n2", 1), ("n3", 1))
#: Keplinger meshes (elements of the symmetric model: eighth in 3D, quarter in 2D)
QUICK_PLATE = {"coupled": (("n1", 10), ("n2", 1), ("n3", 5)),
               "membrane": (("n1", 20), ("n2", 1), ("n3", 10))}
FULL_PLATE = {"coupled": (("n1", 40), ("n2", 1), ("n3", 20)),
              "membrane": (("n1", 40), ("n2", 1), ("n3", 20))}


def _mesh(table, variant):
    return table["coupled" if variant in ("coupled", "maxwell") else "membrane"]


def _homogeneous(geometry, models, s_values, D0max, n, variants=FE_VARIANTS):
    if geometry == "uniaxial-free":
        variants = tuple(v for v in variants if v.startswith("membrane"))
    return tuple(RunSpec(geometry, m, v, float(s), _steps(D0max, n), mesh=HOMOGENEOUS_MESH)
                 for m in models for v in variants for s in s_values)


def _keplinger(alphas, D0max, n, meshes, variants=KEPLINGER_VARIANTS, record_fields=False,
               record_maps=False):
    return tuple(RunSpec("uniaxial", "neo-Hookean", v, keplinger_s(a), _steps(D0max, n), alpha=a,
                         mesh=_mesh(meshes, v), record_fields=record_fields,
                         record_maps=record_maps)
                 for v in variants for a in alphas)


CASES: dict[str, Case] = {c.name: c for c in (
    Case("nh-d-e", "nh-d-e",
         "neo-Hookean equi-biaxial D0-lam and E0-lam curves, s = 0,1,2,3, voltage-control limit",
         "equibiaxial",
         quick=_homogeneous("equibiaxial", ["neo-Hookean"], (0, 1, 2, 3), 6.0, 6),
         full=_homogeneous("equibiaxial", ["neo-Hookean"], (0, 1, 2, 3), 6.0, 24)),
    Case("gent-d-e", "gent-d-e",
         "Gent equi-biaxial D0-lam and E0-lam curves, s = 0,1,2.3,3, voltage-control limit",
         "equibiaxial",
         quick=_homogeneous("equibiaxial", ["Gent"], (0, 1, 2.3, 3), 6.0, 6),
         full=_homogeneous("equibiaxial", ["Gent"], (0, 1, 2.3, 3), 6.0, 24)),
    Case("gent-equi-biaxial", "gent-equi-biaxial",
         "equi-biaxial loading curves s = 0..4.5 with thin/thick wrinkling limits",
         "equibiaxial",
         quick=_homogeneous("equibiaxial", MODELS, (0.8, 1.5, 2.5, 4.5), 8.0, 4,
                            variants=("coupled", "maxwell") + FE_VARIANTS[1:]),
         full=_homogeneous("equibiaxial", MODELS, (0.8, 1.5, 2.5, 4.5), 8.0, 16,
                           variants=("coupled", "maxwell") + FE_VARIANTS[1:])),
    Case("figde", "figde",
         "neo-Hookean uni-axial D0-lam1 and E0-lam1 curves with the det H* = 0 locus",
         "uniaxial",
         quick=_homogeneous("uniaxial-free", ["neo-Hookean"], (0, 1, 2, 3, 4), 6.0, 6),
         full=_homogeneous("uniaxial-free", ["neo-Hookean"], (0, 1, 2, 3, 4), 6.0, 24)),
    Case("uni-axial-ideal", "uni-axial-ideal",
         "Keplinger plate: uni-axial loading curves, wrinkling limits, FE dots, breakdown",
         "uniaxial",
         quick=_keplinger(ALPHAS, 6.0, 12, QUICK_PLATE),
         full=_keplinger(ALPHAS, 6.0, 24, FULL_PLATE)),
    Case("lambda1-3", "fig:lambda1-3",
         "stretch maps lam1, lam3 of the weighted Keplinger plate before charging",
         "uniaxial",
         quick=_keplinger((1.0,), 0.0, 0, {"coupled": (("n1", 20), ("n2", 1), ("n3", 10))},
                          variants=("coupled",), record_fields=True, record_maps=True),
         full=_keplinger((1.0,), 0.0, 0, FULL_PLATE, variants=("coupled",), record_fields=True,
                         record_maps=True)),
    Case("zs22", "fig:zs22",
         "P33/mu along the centre line for increasing D0 up to the breakdown (alpha = 1)",
         "uniaxial",
         quick=_keplinger((1.0,), 6.0, 12, QUICK_PLATE, record_fields=True),
         full=_keplinger((1.0,), 6.0, 24, FULL_PLATE, record_fields=True)),
)}


def get_case(name: str) -> Case:
    """The registered case called ``name``; ``ValueError`` listing the names otherwise."""
    try:
        return CASES[name]
    except KeyError:
        raise ValueError(f"case must be one of {list(CASES)}, got {name!r}") from None


def analytic_model(name: str):
    """The :mod:`analytic` model object of a FE material name.

    Parameters
    ----------
    name : {"neo-Hookean", "Gent"}
        ``"Gent"`` has ``Jm = 97.2``, as the FE material.

    Returns
    -------
    analytic.NeoHookean or analytic.Gent
    """
    if name == "neo-Hookean":
        return an.NeoHookean()
    if name == "Gent":
        return an.Gent(Jm=97.2)
    raise ValueError(f"model must be 'neo-Hookean' or 'Gent', got {name!r}")

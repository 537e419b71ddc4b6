"""The validation cases: one per figure of the paper.

A :class:`~validation.specs.Case` names a paper figure and lists the FE ramps
(:class:`~validation.specs.RunSpec`) whose dots are drawn over its analytic curves.
Each ramp is a mechanical pre-load (the first target, ``D0 = 0``) followed by a
charge ramp through the listed ``D0`` targets. ``quick`` runs use coarse meshes and
few charge steps (the README's main job), full runs the paper's resolution.

The Keplinger runs are given by their weight fraction ``alpha`` (``s=None``): the FE
runner sets their dead load, the FE package's ``s = alpha m g/(mu A)`` with ``g = 9.81``
(:func:`validation.fe.model.with_dead_load`), so that this module imports no finite
elements; the analytic side of every case is the :mod:`analytic` model of
:func:`analytic_model`.
"""

from __future__ import annotations

import numpy as np

import analytic as an

from .specs import ALPHAS, GENT_JM, KEPLINGER, MODELS, Case, RunSpec

__all__ = [
    "KEPLINGER",
    "ALPHAS",
    "RunSpec",
    "Case",
    "CASES",
    "get_case",
    "analytic_model",
    "FE_VARIANTS",
    "KEPLINGER_VARIANTS",
]


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
               record_maps=False, buckling=()):
    def targets(v, a):
        D0 = _steps(D0max, n)
        # the run that finds the buckling load goes past the P33 breakdown, to
        # BUCKLING_D0_MAX (beyond its D0_b; the later spectra, with ever more flagged clamp
        # modes to classify, cost the most)
        return tuple(d for d in D0 if d <= BUCKLING_D0_MAX) if a in buckling and \
            v == "coupled" else D0

    return tuple(RunSpec("uniaxial", "neo-Hookean", v, None, targets(v, a), alpha=a,
                         mesh=_mesh(meshes, v), record_fields=record_fields,
                         record_maps=record_maps, buckling=v == "coupled" and a in buckling,
                         stop_at_breakdown=not (v == "coupled" and a in buckling))
                 for v in variants for a in alphas)


#: weights whose 3D runs of the quick case also get the whole plate's spectrum at every
#: state (the stability-based breakdown D0_b; on the full run's 40 x 1 x 20 plate it
#: costs far more per state, so the full run leaves it to ``skfem-dielectric buckling``;
#: the costs: docs/performance.md)
BUCKLING_ALPHAS = (1.0,)
#: last charge target of those runs
BUCKLING_D0_MAX = 4.0


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
         quick=_keplinger(ALPHAS, 6.0, 12, QUICK_PLATE, buckling=BUCKLING_ALPHAS),
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
        ``"Gent"`` has ``Jm = GENT_JM`` (97.2), as the FE material.

    Returns
    -------
    analytic.NeoHookean or analytic.Gent
    """
    if name == "neo-Hookean":
        return an.NeoHookean()
    if name == "Gent":
        return an.Gent(Jm=GENT_JM)
    raise ValueError(f"model must be 'neo-Hookean' or 'Gent', got {name!r}")

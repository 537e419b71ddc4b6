"""The default settings of the paper's plates, named once: the drivers take them as their
defaults, and the validation harness imports them instead of repeating them.

Lengths in millimetres, stresses in units of ``mu`` (``mu = eps = 1``).
"""

from __future__ import annotations

__all__ = ["GENT_JM", "EQUIBIAXIAL_SIZE", "KEPLINGER_SIZE", "EQUIBIAXIAL_PRELOAD_STEPS",
           "KEPLINGER_PRELOAD_STEPS", "EQUIBIAXIAL_RTOL", "KEPLINGER_RTOL", "KEPLINGER_CHORD",
           "KEPLINGER_ACCELERATION", "KEPLINGER_MAX_ITER"]

#: Stiffening parameter ``Jm`` of the Gent model (the paper's figures).
GENT_JM = 97.2
#: ``(L1, H, L3)`` of the homogeneous equi-biaxial plate: any size has the same state.
EQUIBIAXIAL_SIZE = (4.0, 1.0, 4.0)
#: ``(L1, H, L3)`` of the clamped Keplinger plate, 100 mm x 1 mm x 50 mm (paper Sec. 6).
KEPLINGER_SIZE = (100.0, 1.0, 50.0)
#: Equal pre-load targets before the charge ramp of the equi-biaxial plate.
EQUIBIAXIAL_PRELOAD_STEPS = 4
#: Pre-load targets of the Keplinger plate (the ramp cuts back by itself if needed).
KEPLINGER_PRELOAD_STEPS = 3
#: Newton tolerance of the equi-biaxial plate, relative to the external load (``atol = 0``).
EQUIBIAXIAL_RTOL = 1e-11
#: Newton tolerance of the Keplinger plate, relative to the external load (``atol = 0``).
KEPLINGER_RTOL = 1e-9
#: Chord factor of the Keplinger ramp's Newton solves: a factorisation is reused, within a
#: load step and across load steps, while the residual contracts by at least this factor
#: per step (:func:`~skfem_dielectric.solvers.newton.newton`).
KEPLINGER_CHORD = 0.5
#: Depth of the Anderson acceleration of the Keplinger ramp's chord steps.
KEPLINGER_ACCELERATION = 5
#: Newton iterations (chord steps included) per attempt of a Keplinger load step.
KEPLINGER_MAX_ITER = 12

"""The paper's plates ready to run: builders and drivers of the equibiaxial and Keplinger
plates and of the membrane and cross-section models with their default settings (the
drivers' :class:`~skfem_dielectric.solvers.ramp.RampSettings` are public constants)
(:mod:`~skfem_dielectric.gallery.drivers`), their load paths, a pre-load followed by the
charge targets (:mod:`~skfem_dielectric.gallery.loads`), the model options they forward to
the plate, one :class:`PlateOptions` (:mod:`~skfem_dielectric.gallery.plates`), and the
default values of the plates, named once (:mod:`~skfem_dielectric.gallery.defaults`).
"""

from .drivers import (EQUIBIAXIAL_SETTINGS, KEPLINGER_SETTINGS, MAXWELL_KEPLINGER_SETTINGS,
                      plate_admissible, equibiaxial_problem,
                      keplinger_problem, run_ramp, equibiaxial_plate, keplinger_plate,
                      maxwell_equibiaxial, maxwell_keplinger, membrane_ramp,
                      membrane_keplinger, cross_section_ramp)
from .defaults import (EQUIBIAXIAL_PRELOAD_STEPS, EQUIBIAXIAL_RTOL, EQUIBIAXIAL_SIZE, GENT_JM,
                       KEPLINGER_ACCELERATION, KEPLINGER_CHORD, KEPLINGER_MAX_ITER,
                       KEPLINGER_PRELOAD_STEPS, KEPLINGER_RTOL, KEPLINGER_SIZE)
from .loads import keplinger_s, charge_targets, preload_then_charge, remaining_targets
from .plates import PlateOptions

__all__ = [
    "EQUIBIAXIAL_SETTINGS", "KEPLINGER_SETTINGS", "MAXWELL_KEPLINGER_SETTINGS",
    "plate_admissible", "equibiaxial_problem", "keplinger_problem",
    "run_ramp", "equibiaxial_plate", "keplinger_plate", "maxwell_equibiaxial",
    "maxwell_keplinger", "membrane_ramp", "membrane_keplinger", "cross_section_ramp",
    "keplinger_s", "charge_targets", "preload_then_charge", "remaining_targets",
    "PlateOptions",
    "GENT_JM", "EQUIBIAXIAL_SIZE", "KEPLINGER_SIZE", "EQUIBIAXIAL_PRELOAD_STEPS",
    "KEPLINGER_PRELOAD_STEPS", "EQUIBIAXIAL_RTOL", "KEPLINGER_RTOL", "KEPLINGER_CHORD",
    "KEPLINGER_ACCELERATION", "KEPLINGER_MAX_ITER",
]

"""The 3D clamped plate: the mixed u-p-phi (or penalty) model with optional Maxwell-traction
coupling (:mod:`~skfem_dielectric.models.plate.problem`), its stresses, fields and export
meshes (:mod:`~skfem_dielectric.models.plate.post`), the eight symmetry classes of
increments of the eighth model (:mod:`~skfem_dielectric.models.plate.symmetry_classes`), the
classification of its modes by where their energy sits
(:mod:`~skfem_dielectric.models.plate.modes`), and the diagnosis of a failed ramp step
(:mod:`~skfem_dielectric.models.plate.failure`).
"""

from .problem import PlateProblem, plate_reduction, increment_classes
from .post import (evaluate_fields, plate_stresses, centre_line_points, clamp_line_points,
                   plate_quantities, plate_step_mesh)
from .symmetry_classes import (SymmetryClass, ClassStability, symmetry_classes,
                               class_stability, class_mode_full, union_tangent,
                               class_tangent)
from .modes import (element_energies, energy_share, corner_elements, corner_share,
                    mesh_scale, classify_mode, mode_mesh, write_mode_vtu, top_deflection,
                    ModeLabel, LowestPhysical, corner_radius, physical_modes,
                    lowest_physical, MESH_SCALE_LIMIT, CORNER_LIMIT)
from .failure import StepLimitCounter, plate_failure_cause, describe_failure

__all__ = [
    "PlateProblem", "plate_reduction", "increment_classes", "evaluate_fields",
    "plate_stresses", "centre_line_points", "clamp_line_points", "plate_quantities",
    "plate_step_mesh", "SymmetryClass", "ClassStability", "symmetry_classes",
    "class_stability", "class_mode_full", "union_tangent", "class_tangent",
    "element_energies", "energy_share", "corner_elements", "corner_share", "mesh_scale",
    "classify_mode", "mode_mesh", "write_mode_vtu", "top_deflection", "ModeLabel",
    "LowestPhysical", "corner_radius", "physical_modes", "lowest_physical",
    "MESH_SCALE_LIMIT", "CORNER_LIMIT", "StepLimitCounter",
    "plate_failure_cause", "describe_failure",
]

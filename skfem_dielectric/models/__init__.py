"""The FE models, each a :class:`~skfem_dielectric.problem.Problem`: the 2D incompressible
membrane (:mod:`~skfem_dielectric.models.membrane`), the 2D generalised-plane-strain
cross-section (:mod:`~skfem_dielectric.models.cross_section`), and the 3D plate with its
post-processing, symmetry classes, mode classification and failure diagnosis
(:mod:`skfem_dielectric.models.plate`). A model knows its weak form and its unknowns, not
how it is solved: it imports neither :mod:`skfem_dielectric.solvers` nor the studies.
"""

from .membrane import MembraneMesh, MembranePlate, check_control_coupling, membrane_mesh
from .cross_section import CrossSection, SectionMesh, section_mesh
from .plate import (PlateProblem, plate_reduction, increment_classes, evaluate_fields,
                    plate_stresses, centre_line_points, clamp_line_points, plate_quantities,
                    plate_step_mesh, SymmetryClass, ClassStability, symmetry_classes,
                    class_stability, class_mode_full, union_tangent, class_tangent,
                    element_energies, energy_share, corner_elements, corner_share,
                    mesh_scale, classify_mode, mode_mesh, write_mode_vtu, top_deflection,
                    ModeLabel, LowestPhysical, corner_radius, physical_modes,
                    lowest_physical, MESH_SCALE_LIMIT, CORNER_LIMIT,
                    StepLimitCounter, plate_failure_cause, describe_failure)

__all__ = [
    "MembranePlate", "MembraneMesh", "membrane_mesh", "check_control_coupling",
    "CrossSection", "SectionMesh", "section_mesh", "PlateProblem",
    "plate_reduction", "increment_classes", "evaluate_fields", "plate_stresses",
    "centre_line_points", "clamp_line_points", "plate_quantities", "plate_step_mesh",
    "SymmetryClass", "ClassStability", "symmetry_classes", "class_stability",
    "class_mode_full", "union_tangent", "class_tangent", "element_energies", "energy_share",
    "corner_elements", "corner_share", "mesh_scale", "classify_mode",
    "mode_mesh", "write_mode_vtu", "top_deflection", "ModeLabel", "LowestPhysical",
    "corner_radius", "physical_modes", "lowest_physical",
    "MESH_SCALE_LIMIT", "CORNER_LIMIT", "StepLimitCounter", "plate_failure_cause",
    "describe_failure",
]

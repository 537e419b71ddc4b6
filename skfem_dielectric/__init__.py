"""scikit-fem finite elements for charge-controlled soft dielectric plates.

Every model is a :class:`Problem` (module :mod:`skfem_dielectric.problem`): the Newton
solver, the load ramp and the export work on any of them.  Models: :class:`PlateProblem`
(3D, fully coupled or Maxwell-traction coupling), :class:`MembranePlate` (2D membrane),
:class:`CrossSection` (2D generalised plane strain).

The subpackages, bottom up (docs/architecture.md): :mod:`skfem_dielectric.fem`
(discretisation machinery), :mod:`skfem_dielectric.forms` (weak forms),
:mod:`skfem_dielectric.linalg` (linear solvers, symmetric storage, inertia),
:mod:`skfem_dielectric.stability` (stability of a converged state),
:mod:`skfem_dielectric.models` (the FE models) and :mod:`skfem_dielectric.solvers`
(Newton, ramp, continuation, critical load) side by side, :mod:`skfem_dielectric.gallery`
(the paper's plates and load paths) and :mod:`skfem_dielectric.studies` (the paper's
analyses).  The names below are re-exported from them.
"""

from . import fem, forms, gallery, linalg, models, solvers, stability, studies
from .export import step_mesh, write_vtu_series, write_xdmf
from .fem import DofReduction, PlateMesh, ScatterMap, plate_mesh, point_gradients
from .forms.maxwell_traction import maxwell_stress, maxwell_traction, maxwell_traction_field
from .forms.membrane import membrane_kernel
from .forms.plane_strain import cross_section_kernel
from .gallery import (charge_targets, cross_section_ramp, equibiaxial_plate,
                      equibiaxial_problem, keplinger_plate, keplinger_problem, keplinger_s,
                      maxwell_equibiaxial, maxwell_keplinger, membrane_keplinger, membrane_ramp,
                      newton_guards, plate_admissible, preload_then_charge, remaining_targets,
                      run_ramp)
from .kinematics import segment_det_limit
from .linalg import (LinearSolver, PardisoLUSolver, PardisoSolver, SuperLUSolver,
                     get_linear_solver, nonsymmetric_solver, pardiso_available, tangent_inertia)
from .materials import (GentDielectric, IdealDielectric, NeoHookeanDielectric, PointResponse,
                        ideal_dielectric_response, make_material)
from .models import (ClassStability, CrossSection, MembraneMesh, MembranePlate, PlateProblem,
                     SectionMesh, class_stability, classify_mode, lowest_physical,
                     membrane_mesh, mode_mesh, section_mesh, symmetry_classes, write_mode_vtu)
from .problem import Layout, Problem
from .solvers import (ContinuationEvent, ContinuationPoint, ContinuationResult, CriticalLoad,
                      NewtonResult, NewtonSettings, RampResult, RampSettings, StepResult,
                      continuation, critical_load, newton, ramp)
from .stability import StabilityMonitor, StabilityResult, stability_analysis, tangent_stability
from .studies import (SnapThrough, homogeneous_plate, section_critical_load,
                      section_critical_stretch, voltage_snap_through, wrinkling_section)

__all__ = [
    # the contract and the machinery
    "Problem", "Layout", "newton", "NewtonSettings", "NewtonResult", "segment_det_limit",
    "ramp", "RampSettings", "RampResult",
    "StepResult", "continuation", "ContinuationResult", "ContinuationPoint", "ContinuationEvent",
    "LinearSolver", "SuperLUSolver", "PardisoSolver", "PardisoLUSolver", "get_linear_solver",
    "nonsymmetric_solver", "pardiso_available", "DofReduction", "ScatterMap",
    # materials and meshes
    "NeoHookeanDielectric", "GentDielectric", "IdealDielectric", "PointResponse",
    "ideal_dielectric_response", "make_material", "PlateMesh", "plate_mesh",
    "point_gradients",
    # models and their point kernels
    "PlateProblem", "MembranePlate", "CrossSection", "MembraneMesh", "membrane_mesh",
    "SectionMesh", "section_mesh", "membrane_kernel",
    "cross_section_kernel", "maxwell_stress", "maxwell_traction", "maxwell_traction_field",
    # loads and drivers
    "keplinger_s", "charge_targets", "preload_then_charge", "remaining_targets",
    "equibiaxial_problem", "keplinger_problem", "plate_admissible", "newton_guards", "run_ramp",
    "equibiaxial_plate",
    "keplinger_plate", "maxwell_equibiaxial", "maxwell_keplinger", "membrane_ramp",
    "membrane_keplinger", "cross_section_ramp",
    # stability
    "StabilityResult", "StabilityMonitor", "stability_analysis", "tangent_stability", "tangent_inertia",
    "ClassStability", "class_stability", "symmetry_classes", "classify_mode", "mode_mesh",
    "write_mode_vtu", "lowest_physical", "CriticalLoad", "critical_load",
    "wrinkling_section", "section_critical_load", "section_critical_stretch",
    # voltage control through the snap-through
    "homogeneous_plate", "voltage_snap_through", "SnapThrough",
    # export
    "step_mesh", "write_vtu_series", "write_xdmf",
]

"""scikit-fem finite elements for charge-controlled soft dielectric plates.

Every model is a :class:`Problem` (module :mod:`skfem_dielectric.problem`): the Newton
solver, the load ramp and the export work on any of them.  Models: :class:`PlateProblem`
(3D, fully coupled or Maxwell-traction coupling), :class:`MembranePlate` (2D membrane),
:class:`CrossSection` (2D generalised plane strain).  Weak forms: :mod:`skfem_dielectric.forms`.
"""

from .assembly import DofReduction, ScatterMap
from .continuation import (ContinuationEvent, ContinuationPoint, ContinuationResult,
                           continuation)
from .critical import CriticalLoad, critical_load
from .cross_section import CrossSection
from .drivers import (cross_section_ramp, equibiaxial_plate, equibiaxial_problem,
                      keplinger_plate, keplinger_problem, maxwell_equibiaxial,
                      maxwell_keplinger, membrane_keplinger, membrane_ramp, newton_guards,
                      plate_admissible, run_ramp)
from .export import step_mesh, write_vtu_series, write_xdmf
from .forms.maxwell_traction import maxwell_stress, maxwell_traction, maxwell_traction_field
from .forms.membrane import membrane_kernel
from .forms.plane_strain import cross_section_kernel
from .kinematics import segment_det_limit
from .linear import (LinearSolver, PardisoLUSolver, PardisoSolver, SuperLUSolver,
                     get_linear_solver, nonsymmetric_solver, pardiso_available)
from .loads import charge_targets, keplinger_s, preload_then_charge, remaining_targets
from .materials import (GentDielectric, IdealDielectric, NeoHookeanDielectric, PointResponse,
                        ideal_dielectric_response, make_material)
from .membrane import MembranePlate
from .mesh import PlateMesh, plate_mesh
from .mesh2d import point_gradients
from .monitor import StabilityMonitor
from .modes import classify_mode, lowest_physical_eigenvalue, mode_mesh, write_mode_vtu
from .newton import NewtonResult, newton
from .plate import PlateProblem
from .problem import Layout, Problem
from .ramp import RampResult, StepResult, ramp
from .snap_through import SnapThrough, homogeneous_plate, voltage_snap_through
from .stability import StabilityResult, stability_analysis, tangent_inertia, tangent_stability
from .symmetry_classes import ClassStability, class_stability, symmetry_classes
from .wrinkling_fe import section_critical_load, section_critical_stretch, wrinkling_section

__all__ = [
    # the contract and the machinery
    "Problem", "Layout", "newton", "NewtonResult", "segment_det_limit", "ramp", "RampResult",
    "StepResult", "continuation", "ContinuationResult", "ContinuationPoint", "ContinuationEvent",
    "LinearSolver", "SuperLUSolver", "PardisoSolver", "PardisoLUSolver", "get_linear_solver",
    "nonsymmetric_solver", "pardiso_available", "DofReduction", "ScatterMap",
    # materials and meshes
    "NeoHookeanDielectric", "GentDielectric", "IdealDielectric", "PointResponse",
    "ideal_dielectric_response", "make_material", "PlateMesh", "plate_mesh",
    "point_gradients",
    # models and their point kernels
    "PlateProblem", "MembranePlate", "CrossSection", "membrane_kernel",
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
    "write_mode_vtu", "lowest_physical_eigenvalue", "CriticalLoad", "critical_load",
    "wrinkling_section", "section_critical_load", "section_critical_stretch",
    # voltage control through the snap-through
    "homogeneous_plate", "voltage_snap_through", "SnapThrough",
    # export
    "step_mesh", "write_vtu_series", "write_xdmf",
]

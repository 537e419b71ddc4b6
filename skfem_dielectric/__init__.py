"""scikit-fem finite elements for charge-controlled soft dielectric plates.

The top level holds the names a user of the paper's plates needs:

- the contract every model implements: :class:`Problem`, :class:`Layout`;
- the models and their meshes: :class:`PlateProblem` (3D, fully coupled or
  Maxwell-traction coupling) with :func:`plate_mesh`, :class:`MembranePlate` (2D membrane)
  with :func:`membrane_mesh`, :class:`CrossSection` (2D generalised plane strain) with
  :func:`section_mesh`;
- the ideal-dielectric materials: :class:`NeoHookeanDielectric`, :class:`GentDielectric`,
  :class:`IdealDielectric`, :func:`make_material`;
- the model-agnostic solvers: :func:`newton`, :func:`ramp`, :func:`continuation`,
  :func:`critical_load`, their settings and results;
- the stability of a converged state: :func:`stability_analysis`, :class:`StabilityResult`,
  :class:`StabilityMonitor`;
- the paper's plates: :func:`equibiaxial_plate`, :func:`keplinger_plate`,
  :func:`keplinger_s`, and their model options :class:`PlateOptions`;
- :func:`get_linear_solver`, and the export :func:`write_vtu_series`, :func:`write_xdmf`.

Everything else is reached through its subpackage, bottom up (docs/architecture.md):
:mod:`skfem_dielectric.fem` (discretisation machinery: dof reduction, scatter maps,
meshes), :mod:`skfem_dielectric.forms` (weak forms, one module per form),
:mod:`skfem_dielectric.linalg` (linear solvers, symmetric storage, inertia),
:mod:`skfem_dielectric.stability` (stability of a converged state),
:mod:`skfem_dielectric.models` (the FE models, the plate's symmetry classes and modes) and
:mod:`skfem_dielectric.solvers` (Newton, ramp, continuation, critical load) side by side,
:mod:`skfem_dielectric.gallery` (the paper's plates, drivers and load paths, e.g.
``gallery.run_ramp``) and :mod:`skfem_dielectric.studies` (the paper's analyses: buckling,
post-buckling, snap-through, FE wrinkling).  The flat modules :mod:`skfem_dielectric.materials`,
:mod:`skfem_dielectric.kinematics` and :mod:`skfem_dielectric.export` hold the pointwise
laws, the small-matrix kinematics and the whole export.
"""

from . import fem, forms, gallery, linalg, models, solvers, stability, studies
from .export import write_vtu_series, write_xdmf
from .fem import plate_mesh
from .gallery import PlateOptions, equibiaxial_plate, keplinger_plate, keplinger_s
from .linalg import get_linear_solver
from .materials import GentDielectric, IdealDielectric, NeoHookeanDielectric, make_material
from .models import CrossSection, MembranePlate, PlateProblem, membrane_mesh, section_mesh
from .problem import Layout, Problem
from .solvers import (ContinuationResult, ContinuationSettings, NewtonResult, NewtonSettings,
                      RampResult, RampSettings, StepResult, continuation, critical_load, newton,
                      ramp)
from .stability import StabilityMonitor, StabilityResult, stability_analysis

__all__ = [
    # the contract
    "Problem", "Layout",
    # models and their meshes
    "PlateProblem", "MembranePlate", "CrossSection", "plate_mesh", "membrane_mesh",
    "section_mesh",
    # materials
    "NeoHookeanDielectric", "GentDielectric", "IdealDielectric", "make_material",
    # solvers
    "newton", "ramp", "continuation", "NewtonSettings", "RampSettings", "ContinuationSettings",
    "NewtonResult", "RampResult", "StepResult", "ContinuationResult", "critical_load",
    # stability
    "stability_analysis", "StabilityResult", "StabilityMonitor",
    # the paper's plates
    "equibiaxial_plate", "keplinger_plate", "keplinger_s", "PlateOptions",
    # linear solver and export
    "get_linear_solver", "write_vtu_series", "write_xdmf",
]

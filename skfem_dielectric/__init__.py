"""scikit-fem finite elements for charge-controlled soft dielectric plates."""

__all__: list[str] = []

# --- FE core (helper C): generic Newton / ramp machinery and linear solvers ---
from .linear import LinearSolver, PardisoSolver, SuperLUSolver, get_linear_solver  # noqa: E402
from .newton import NewtonResult, RampResult, StepResult, newton, ramp  # noqa: E402

__all__ += ["LinearSolver", "SuperLUSolver", "PardisoSolver", "get_linear_solver",
            "NewtonResult", "StepResult", "RampResult", "newton", "ramp"]
from .materials import GentDielectric, IdealDielectric, NeoHookeanDielectric  # noqa: E402
from .mesh import PlateMesh, plate_mesh  # noqa: E402
from .assembly import DofReduction, ScatterMap  # noqa: E402
from .plate import PlateProblem  # noqa: E402
from .drivers import equibiaxial_plate, keplinger_plate, keplinger_s  # noqa: E402

__all__ += ["NeoHookeanDielectric", "GentDielectric", "IdealDielectric", "PlateMesh",
            "plate_mesh", "DofReduction", "ScatterMap", "PlateProblem", "equibiaxial_plate",
            "keplinger_plate", "keplinger_s"]
from .export import step_mesh, write_vtu_series, write_xdmf  # noqa: E402

__all__ += ["step_mesh", "write_vtu_series", "write_xdmf"]

# --- FE variants (helper D): 2D membrane ---
from .membrane import MembranePlate, membrane_kernel, membrane_keplinger, membrane_ramp  # noqa: E402,E501

__all__ += ["MembranePlate", "membrane_kernel", "membrane_ramp", "membrane_keplinger"]

# --- FE variants (helper D): Maxwell-traction coupling, 2D cross-section ---
from .maxwell import MaxwellPlate, maxwell_equibiaxial, maxwell_keplinger, nonsymmetric_solver  # noqa: E402,E501
from .cross_section import CrossSection, cross_section_ramp  # noqa: E402

__all__ += ["MaxwellPlate", "maxwell_equibiaxial", "maxwell_keplinger", "nonsymmetric_solver",
            "CrossSection", "cross_section_ramp"]

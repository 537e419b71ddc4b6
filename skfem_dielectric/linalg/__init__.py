"""Linear algebra of the tangents: the linear-solver interface and SuperLU
(:mod:`~skfem_dielectric.linalg.solver_base`), the PARDISO solvers and the choice by name
(:mod:`~skfem_dielectric.linalg.linear`), the upper-triangle storage of a symmetric tangent
(:mod:`~skfem_dielectric.linalg.symmetric`), and the inertia (signature) of a symmetric
matrix by symmetric factorisations (:mod:`~skfem_dielectric.linalg.inertia`).
"""

from .solver_base import LinearSolver, SuperLUSolver, whole_matrix
from .symmetric import SymmetricUpper, same_memory, same_pattern
from .linear import (PardisoSolver, PardisoLUSolver, get_linear_solver, nonsymmetric_solver,
                     pardiso_available, new_pypardiso_solver)
from .inertia import (INERTIA_METHODS, DENSE_LIMIT, tangent_inertia, constrained_order,
                      counted_inertia, symmetric_lu, SymmetricFactors, inertia_factors,
                      reusable_factors)

__all__ = [
    "LinearSolver", "SuperLUSolver", "whole_matrix", "SymmetricUpper", "same_memory",
    "same_pattern", "PardisoSolver", "PardisoLUSolver", "get_linear_solver",
    "nonsymmetric_solver", "pardiso_available", "new_pypardiso_solver", "INERTIA_METHODS",
    "DENSE_LIMIT", "tangent_inertia", "constrained_order", "counted_inertia",
    "symmetric_lu", "SymmetricFactors", "inertia_factors", "reusable_factors",
]

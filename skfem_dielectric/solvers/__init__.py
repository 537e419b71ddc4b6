"""Model-agnostic solvers of the equilibrium equations of any
:class:`~skfem_dielectric.problem.Problem`: Newton's method with a backtracking line search
(:mod:`~skfem_dielectric.solvers.newton`), the load ramp with step cut-back
(:mod:`~skfem_dielectric.solvers.ramp`), pseudo-arclength continuation through limit points
(:mod:`~skfem_dielectric.solvers.continuation`), and the location of a critical load along a
load path (:mod:`~skfem_dielectric.solvers.critical`).
"""

from .newton import NewtonResult, newton
from .ramp import StepResult, RampResult, ramp
from .continuation import (ContinuationPoint, ContinuationEvent, ContinuationResult,
                           continuation)
from .critical import CriticalLoad, critical_load, illinois

__all__ = [
    "NewtonResult", "newton", "StepResult", "RampResult", "ramp", "ContinuationPoint",
    "ContinuationEvent", "ContinuationResult", "continuation", "CriticalLoad",
    "critical_load", "illinois",
]

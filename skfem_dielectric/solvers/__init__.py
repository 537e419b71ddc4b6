"""Model-agnostic solvers of the equilibrium equations of any
:class:`~skfem_dielectric.problem.Problem`: Newton's method with a backtracking line search
(:mod:`~skfem_dielectric.solvers.newton`), the load ramp with step cut-back
(:mod:`~skfem_dielectric.solvers.ramp`), pseudo-arclength continuation through limit points
(:mod:`~skfem_dielectric.solvers.continuation`), and the location of a critical load along a
load path (:mod:`~skfem_dielectric.solvers.critical`).  How Newton iterates is one
:class:`NewtonSettings`; how a ramp solves its load steps is one :class:`RampSettings`; how a
continuation steps along its path is one :class:`ContinuationSettings`.
"""

from .newton import NewtonSettings, NewtonResult, newton
from .ramp import RampSettings, StepResult, RampResult, ramp
from .continuation import (ContinuationSettings, ContinuationPoint, ContinuationEvent,
                           ContinuationResult, continuation)
from .critical import CriticalLoad, critical_load, illinois

__all__ = [
    "NewtonSettings", "NewtonResult", "newton", "RampSettings", "StepResult", "RampResult",
    "ramp", "ContinuationSettings", "ContinuationPoint", "ContinuationEvent", "ContinuationResult", "continuation",
    "CriticalLoad", "critical_load", "illinois",
]

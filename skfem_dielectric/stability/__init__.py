"""Model-agnostic stability of a converged state: the inertia and the lowest eigenpairs of the
tangent in the metric of the unknowns (:mod:`~skfem_dielectric.stability.analysis`), and the
monitor that records them for every converged state of a ramp
(:mod:`~skfem_dielectric.stability.monitor`).
"""

from .analysis import (StabilityResult, stability_analysis, tangent_stability, metric_matrix,
                       lowest_modes, modes_near_zero)
from .monitor import StabilityMonitor

__all__ = [
    "StabilityResult", "stability_analysis", "tangent_stability", "metric_matrix",
    "lowest_modes", "modes_near_zero", "StabilityMonitor",
]

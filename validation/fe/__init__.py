"""The FE side of the harness, the only part of :mod:`validation` besides the studies that
imports :mod:`skfem_dielectric`: the problem of a run and its ramp settings
(:mod:`.model`), the columns a converged state adds to its row (:mod:`.columns`), the
runner of :func:`validation.sweep.run_case` (:mod:`.runner`) and the single ramps of
``simulate`` and ``bench`` (:mod:`.simulate`).
"""

from .columns import (membrane_stretch_maps, plate_buckling_columns, stability_columns,
                      stability_monitor, step_record, whole_plate_verdict)
from .model import (buckling_problem, build_problem, is_membrane, pardiso_installed,
                    ramp_settings, ramp_targets, with_dead_load)
from .runner import run_fe
from .simulate import bench, export_mesh, simulate

__all__ = [
    "with_dead_load", "is_membrane", "build_problem", "buckling_problem", "ramp_targets", "ramp_settings",
    "pardiso_installed", "stability_columns", "stability_monitor", "plate_buckling_columns",
    "whole_plate_verdict", "membrane_stretch_maps", "step_record", "run_fe", "export_mesh",
    "simulate", "bench",
]

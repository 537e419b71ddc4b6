"""The analyses of the paper, each a model, a solver and the stability put together: the first
physical buckling load of the clamped plate (:mod:`~skfem_dielectric.studies.buckling`), the
post-buckled branch (:mod:`~skfem_dielectric.studies.postbuckling`), the voltage-controlled
snap-through of a homogeneous plate (:mod:`~skfem_dielectric.studies.snap_through`), the
FE wrinkling of the cross-section (:mod:`~skfem_dielectric.studies.wrinkling_fe`), and the
base state of a clamp-edge section (:mod:`~skfem_dielectric.studies.section_base`).
"""

from .buckling import BucklingLoad, buckling_load
from .postbuckling import (midplane_nodes, midplane_deflection, critical_mode, BranchSwitch,
                           switch_branch, follow_branch, PostBuckledBranch,
                           post_buckled_branch)
from .section_base import continue_section_base, solve_section_base
from .snap_through import (SNAP_THROUGH_SETTINGS, homogeneous_plate, SnapThrough,
                           voltage_snap_through)
from .wrinkling_fe import (wrinkling_section, section_mode_eigenvalue,
                           section_critical_load, SectionBifurcation,
                           section_critical_stretch)

__all__ = [
    "BucklingLoad", "buckling_load", "midplane_nodes", "midplane_deflection",
    "critical_mode", "BranchSwitch", "switch_branch", "follow_branch", "PostBuckledBranch",
    "post_buckled_branch", "SNAP_THROUGH_SETTINGS", "homogeneous_plate", "SnapThrough", "voltage_snap_through",
    "wrinkling_section", "section_mode_eigenvalue", "section_critical_load",
    "SectionBifurcation", "section_critical_stretch", "solve_section_base",
    "continue_section_base",
]

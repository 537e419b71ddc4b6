"""The paper's studies beyond the charge ramps of the cases, each with its table, figure
and command: the buckling load of the clamped plate (:mod:`~validation.studies.buckling`), its post-buckled
branch (:mod:`~validation.studies.postbuckling`), the FE wrinkling of the cross-section against Stroh
(:mod:`~validation.studies.wrinkling`), the voltage-controlled snap-through (:mod:`~validation.studies.voltage_control`); the
two of them that ``validate`` runs as cases (:mod:`~validation.studies.extra_cases`) and the commands
``wrinkling-fe``, ``buckling``, ``post-buckling`` (:mod:`~validation.studies.commands`).
"""

from .buckling import run_buckling
from .commands import STUDY_COMMANDS, add_study_commands
from .extra_cases import EXTRA_CASES, ExtraCase
from .postbuckling import run_post_buckling
from .voltage_control import run_voltage_control
from .wrinkling import run_wrinkling_fe

__all__ = ["run_buckling", "run_post_buckling", "run_wrinkling_fe", "run_voltage_control",
           "EXTRA_CASES", "ExtraCase", "STUDY_COMMANDS", "add_study_commands"]

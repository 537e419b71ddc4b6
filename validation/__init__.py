"""FE-versus-analytic validation: the paper's figures with FE dots, and the CLI.

The paper: Conroy Broderick, Righi, Destrade, Ogden, "Stability analysis of
charge-controlled soft dielectric plates", Int. J. Eng. Sci., 2020.

The main job is :func:`validate` (``skfem-dielectric validate``): it runs the FE
ramps of every :data:`CASES` entry (one per figure of the paper), writes tidy
CSVs step by step (resumable), draws the figures and writes ``summary.json``
and ``report.md``.
"""

from .clash import PackageClash, check_packages

check_packages()       # before anything imports analytic / skfem_dielectric

from .cases import CASES, get_case  # noqa: E402
from .fe import keplinger_s
from .records import RunOutcome, StepRecord
from .specs import ALPHAS, KEPLINGER, Case, RunSpec
from .results import CaseResult
from .sweep import make_figure, run_case, run_cases, validate
from .table import BREAKDOWN_TOL, read_table

__all__ = [
    "ALPHAS", "CASES", "KEPLINGER", "Case", "RunSpec", "get_case", "keplinger_s",
    "BREAKDOWN_TOL", "CaseResult", "RunOutcome", "StepRecord", "make_figure", "read_table",
    "run_case", "run_cases", "validate", "PackageClash", "check_packages",
]

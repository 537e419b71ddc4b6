"""FE-versus-analytic validation: the paper's figures with FE dots, and the CLI.

The paper: Conroy Broderick, Righi, Destrade, Ogden, "Stability analysis of
charge-controlled soft dielectric plates", Int. J. Eng. Sci., 2020.

The main job is :func:`validation.sweep.validate` (``skfem-dielectric validate``): it runs
the FE ramps of every :data:`CASES` entry (one per figure of the paper), writes tidy
CSVs step by step (resumable), draws the figures and writes ``summary.json``
and ``report.md``.  This namespace holds what describes the cases and reads their tables
and imports no finite elements (:mod:`validation.specs`, :mod:`validation.cases`,
:mod:`validation.records`, :mod:`validation.table`), and :func:`check`, which scores
another code's results CSVs against the closed forms (:mod:`validation.checker`); the FE
runner (:mod:`validation.fe`), the harness (:mod:`validation.sweep`), the figures, the
studies and the CLI are imported from their modules (docs/architecture.md).
"""

from .clash import PackageClash, check_packages

check_packages()       # before anything imports analytic / skfem_dielectric

from .cases import CASES, get_case  # noqa: E402
from .checker import CheckResult, check  # noqa: E402
from .records import RunOutcome, StepRecord  # noqa: E402
from .specs import ALPHAS, KEPLINGER, Case, RunSpec  # noqa: E402
from .table import BREAKDOWN_TOL, read_table  # noqa: E402

__all__ = [
    "ALPHAS", "CASES", "KEPLINGER", "Case", "RunSpec", "get_case", "BREAKDOWN_TOL",
    "RunOutcome", "StepRecord", "read_table", "PackageClash", "check_packages",
    "check", "CheckResult",
]

"""Score another code's results against the closed forms: ``skfem-dielectric check``.

A solver written elsewhere (FEniCS, COMSOL, Abaqus, a script) writes its results in the
results contract of ``skfem-dielectric validate`` (docs/theory.md, "The results contract";
the columns each case needs: docs/check.md) and :func:`check` scores every case it finds
against the closed forms of :mod:`analytic` and the measured buckling loads of
:mod:`validation.data.loads`:

* the loading curves of the homogeneous plates, equi-biaxial (Eq. loading_gent) and
  uni-axial (Eq. DEuniax), neo-Hookean and Gent: the relative error of ``lam1`` at the
  row's ``s`` and ``D0`` (``D0 = lam1^2 lam3^2 E0`` from ``E0``, Eq. DLEL);
* the Hessian verdicts (Eq. equiv and the inequalities after it) where a row says
  ``stable``, and the voltage limit points (``max_E0``, the ``det H* = 0`` locus, Sec. 3.1
  and Sec. 5) of ``voltage-control``;
* the critical ``D0`` of the finite-thickness dispersion relation (Sec. 4, beyond the
  paper: :func:`analytic.critical_D0`) of ``wrinkling-fe``;
* the clamped Keplinger plate (Sec. 6): ``lam1`` at the centre within 1 % of the
  homogeneous curve, and ``D0_b`` against the converged buckling load with its error bar.

Each case gets one :class:`Measure` per quantity it has: the error of the worst row, its
tolerance (:data:`TOLERANCES`), where that row is (file and line) and a verdict; a failing
measure also says which common mix-up of conventions would explain it (the sign of ``s``,
``D0`` per current area, ...).  Reading loads neither finite elements nor matplotlib; the
figures and the report files are :mod:`validation.check_report`.
"""

from __future__ import annotations

from pathlib import Path

from .contract import (CHECK_CASES, MAX_FILE_BYTES, MAX_TOTAL_BYTES, TOLERANCE_SOURCES,
                       TOLERANCES, CheckInputError, parse_tolerances)
from .onsets import check_voltage, check_wrinkling
from .reading import gather, read_csv_rows
from .rules import check_clamped, check_loading
from .scores import CaseCheck, CheckResult, Measure

__all__ = ["CHECK_CASES", "TOLERANCES", "TOLERANCE_SOURCES", "MAX_FILE_BYTES",
           "MAX_TOTAL_BYTES", "CheckInputError", "Measure", "CaseCheck", "CheckResult",
           "check", "parse_tolerances", "read_csv_rows"]

CHECKERS = {"equibiaxial": check_loading, "uniaxial-free": check_loading,
             "clamped": check_clamped, "voltage": check_voltage,
             "wrinkling": check_wrinkling}


def check(path, cases=None, *, tol=None) -> CheckResult:
    """Score the results CSVs in ``path`` against the closed forms.

    Implements the comparisons of the module docstring: Eq. (loading_gent) and
    Eq. (DEuniax) for the loading curves, Eq. (equiv) for the ``stable`` verdicts,
    ``analytic.max_E0`` (``det H* = 0``, Sec. 3.1 and Sec. 5) for the voltage limit points,
    the dispersion relation of Sec. 4 for the critical ``D0``, and the converged buckling
    load of the Keplinger plate (Sec. 6).

    Parameters
    ----------
    path : path-like
        A folder of ``<case>.csv`` files in the results contract (docs/check.md), or one
        such file.  Every ``*.csv`` of the folder is read (the contract's field samples
        and study tables are named and skipped).
    cases : str or iterable of str, optional
        Only these cases (default: every case found).
    tol : dict or iterable of str, optional
        Replaced tolerances, ``{"lam1": 1e-4}`` or ``["lam1=1e-4"]``
        (:func:`parse_tolerances`; default :data:`TOLERANCES`).

    Returns
    -------
    CheckResult
        ``.passed``, ``.worst``, ``.table()``, one :class:`CaseCheck` per case.

    Raises
    ------
    CheckInputError
        A file that cannot be scored (a ``ValueError``; the message names the file, the
        line and the column).
    OSError
        ``path`` does not exist or a file cannot be read.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "nh-d-e.csv").write_text("case,s,D0,lam1\\nnh-d-e,0,0,1\\n"
    ...                                        "nh-d-e,0,1,1.122462048309373\\n")
    >>> result = check(folder)
    >>> result.passed, result["nh-d-e"].measures[0].n
    (True, 2)
    """
    if isinstance(cases, str):
        cases = [cases]
    if cases is not None:
        cases = list(dict.fromkeys(cases))
        for c in cases:
            if c not in CHECK_CASES:
                raise CheckInputError(f"unknown case {c!r} (cases: {', '.join(CHECK_CASES)})")
    tolerances = parse_tolerances(tol if tol is not None else [])
    path = Path(path)
    found, notes = gather(path, cases)
    checked = tuple(CHECKERS[CHECK_CASES[name][0]](name, found[name], tolerances)
                    for name in CHECK_CASES if name in found)
    notes += [f"{c.name}: {n}" for c in checked for n in c.notes]
    return CheckResult(str(path), checked, tuple(notes), tolerances)

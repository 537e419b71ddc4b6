"""The scores ``check`` reports: a :class:`Measure` per quantity, a :class:`CaseCheck` per
case, the :class:`CheckResult` of a folder, and their lines and tables.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Measure", "CaseCheck", "CheckResult", "make_measure", "measures_table",
           "file_names", "rows_text", "fmt_g"]

# --------------------------------------------------------------------------- measures
@dataclass(frozen=True)
class Measure:
    """The score of one quantity of one case.

    Attributes
    ----------
    case, name : str
        The case and the measure (a key of :data:`TOLERANCES`).
    what : str
        The error measure in words, with the equation it compares with.
    n : int
        Rows (or points) scored.
    error, tol : float
        The error of the worst row and its tolerance (the worst row is the one with the
        largest error relative to its tolerance).
    where : str
        File and line of the worst row.
    detail : str
        The worst row's values against the closed form.
    n_failed : int
        Rows beyond their tolerance.
    diagnosis : str
        For a failing measure: the mix-up of conventions that would explain it, or that
        none of the usual ones does.
    """

    case: str
    name: str
    what: str
    n: int
    error: float
    tol: float
    where: str
    detail: str
    n_failed: int = 0
    diagnosis: str = ""

    @property
    def passed(self) -> bool:
        """Every row within its tolerance."""
        return self.n_failed == 0

    @property
    def ratio(self) -> float:
        """Error over tolerance of the worst row (``inf`` for a failure at tolerance 0)."""
        if self.tol > 0:
            return self.error / self.tol
        return 0.0 if self.error <= 0 else math.inf

    def error_text(self) -> str:
        """The error as printed: ``"1.23e-05"``, or ``"2 of 40 disagree"`` for a verdict
        column (``stable``, ``stable_charge``)."""
        if self.name.startswith("stable"):
            return f"{self.n_failed} of {self.n} disagree"
        return fmt_g(self.error)

    def line(self) -> str:
        """One line: the measure, its worst error, tolerance and row, the verdict."""
        verdict = "pass" if self.passed else "FAIL"
        return (f"{self.name}: {verdict} ({self.what}: {self.error_text()}, tolerance "
                f"{self.tol:g}, {self.n} rows; worst {self.where}: {self.detail})")


def rows_text(n: int) -> str:
    """``"1 row"`` or ``"n rows"``."""
    return f"{n} row" if n == 1 else f"{n} rows"


def fmt_g(x: float) -> str:
    """``x`` in the two-digit scientific form of the report (``inf`` for a non-finite
    value)."""
    return "inf" if not math.isfinite(x) else format(x, ".2e")


def make_measure(case, name, what, rows, err, tol, details, diagnose=None) -> Measure:
    """A :class:`Measure` from per-row errors ``err`` and tolerances ``tol`` (arrays, an
    error ``nan`` counts as ``inf``); ``details(i)`` describes row ``i``; ``diagnose()`` is
    called for a failing measure."""
    err = np.where(np.isfinite(err), err, np.inf)
    tol = np.broadcast_to(np.asarray(tol, dtype=float), err.shape)
    failed = err > tol
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(tol > 0, err / np.where(tol > 0, tol, 1.0),
                         np.where(err > 0, np.inf, 0.0))
    i = int(np.argmax(ratio))
    diagnosis = diagnose() if failed.any() and diagnose is not None else ""
    return Measure(case, name, what, int(err.size), float(err[i]), float(tol[i]),
                   rows[i].where, details(i), int(failed.sum()), diagnosis)


# --------------------------------------------------------------------------- the cases
@dataclass(frozen=True)
class CaseCheck:
    """The check of one case.

    Attributes
    ----------
    name : str
        The case.
    files : tuple of str
        The files its rows came from.
    measures : tuple of Measure
        One per quantity scored.
    notes : tuple of str
        Rows that were not scored, and why.
    points : dict
        Their values and per-row verdicts, for the figure
        (:func:`validation.check_report.check_figure`).
    """

    name: str
    files: tuple
    measures: tuple
    notes: tuple = ()
    points: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def passed(self) -> bool:
        """Every measure passes."""
        return all(m.passed for m in self.measures)

    @property
    def worst(self) -> Measure:
        """The measure with the largest error relative to its tolerance."""
        return max(self.measures, key=lambda m: m.ratio)

    def line(self) -> str:
        """One line: the case's verdict and its measures' worst errors."""
        parts = [f"{m.name} {m.error_text()} <= {m.tol:g}" if m.passed else
                 f"{m.name} {m.error_text()} > {m.tol:g} at {m.where}" for m in self.measures]
        return f"{self.name}: {'pass' if self.passed else 'FAIL'} ({'; '.join(parts)})"

    def table(self) -> str:
        """The measures as a Markdown table (one row each)."""
        return measures_table([self])


def measures_table(cases) -> str:
    """A Markdown table of every measure of ``cases``: rows, error, tolerance, worst row and
    verdict."""
    lines = ["| case | measure | rows | error | tolerance | worst row | verdict |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for c in cases:
        for m in c.measures:
            lines.append(f"| {c.name} | {m.name} | {m.n} | {m.error_text()} | {m.tol:g} | {m.where}: "
                         f"{m.detail} | {'pass' if m.passed else '**FAIL**'} |")
    return "\n".join(lines)


@dataclass(frozen=True)
class CheckResult:
    """The check of every case found: ``result.passed``, ``result.worst``,
    ``result.table()``, ``result["nh-d-e"]``.

    Attributes
    ----------
    path : str
        The folder (or file) checked.
    cases : tuple of CaseCheck
        In the order of :data:`CHECK_CASES`.
    notes : tuple of str
        Files that were not scored, and why.
    tolerances : dict
        The tolerances used (:data:`TOLERANCES` with the replaced ones).
    """

    path: str
    cases: tuple
    notes: tuple = ()
    tolerances: dict = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        """Every case passes."""
        return all(c.passed for c in self.cases)

    @property
    def worst(self) -> Measure:
        """The measure, over every case, with the largest error relative to its tolerance
        (the first failure to look at; for a pass, the closest call)."""
        return max((c.worst for c in self.cases), key=lambda m: m.ratio)

    def __getitem__(self, name: str) -> CaseCheck:
        for c in self.cases:
            if c.name == name:
                return c
        raise KeyError(f"no case {name!r} in this check (cases: "
                       f"{', '.join(c.name for c in self.cases)})")

    def __iter__(self):
        return iter(self.cases)

    def __len__(self) -> int:
        return len(self.cases)

    def table(self) -> str:
        """Every measure of every case as a Markdown table."""
        return measures_table(self.cases)

    def lines(self) -> list[str]:
        """What ``skfem-dielectric check`` prints: a line per case, for a failing measure
        a line with its worst row and one with the diagnosis, then the tally."""
        out = []
        for c in self.cases:
            out.append(c.line())
            for m in c.measures:
                if not m.passed:
                    out.append(f"  {m.name}: {m.n_failed} of {m.n} rows beyond {m.tol:g}; "
                               f"worst {m.where}: {m.detail}")
                    out.append(f"  {m.name}: {m.diagnosis}")
        n = sum(c.passed for c in self.cases)
        out.append(f"check: {n} of {len(self.cases)} cases pass")
        return out


def file_names(tables) -> tuple:
    """The names of the files that ``tables`` were read from, each once, in reading order."""
    return tuple(dict.fromkeys(rs[0].file for _, rs in tables))

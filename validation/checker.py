"""Score another code's results against the closed forms: ``skfem-dielectric check``.

A solver written elsewhere (FEniCS, COMSOL, Abaqus, a script) writes its results in the
results contract of ``skfem-dielectric validate`` (docs/theory.md, "The results contract";
the columns each case needs: docs/check.md) and :func:`check` scores every case it finds
against the closed forms of :mod:`analytic` and the measured buckling loads of
:mod:`validation.buckling_data`:

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

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

import analytic as an
from analytic.units import keplinger_s

from .buckling_data import BUCKLING_LOADS_FILE, buckling_loads, uniform_buckling_loads
from .cases import analytic_model
from .specs import GENT_JM, KEPLINGER

__all__ = ["CHECK_CASES", "TOLERANCES", "TOLERANCE_SOURCES", "CheckInputError", "Measure",
           "CaseCheck", "CheckResult", "check", "parse_tolerances", "read_csv_rows"]

#: The cases :func:`check` scores: ``{case: (kind, model)}``.  ``kind`` says which closed
#: forms apply (``"equibiaxial"``, ``"uniaxial-free"``: homogeneous loading curves;
#: ``"clamped"``: the Keplinger plate; ``"voltage"``: paths under voltage control;
#: ``"wrinkling"``: the dispersion relation); ``model`` is the strain energy a file
#: without a ``model`` column is read with (``None``: the column is required).
CHECK_CASES = {
    "nh-d-e": ("equibiaxial", "neo-Hookean"),
    "gent-d-e": ("equibiaxial", "Gent"),
    "gent-equi-biaxial": ("equibiaxial", None),
    "figde": ("uniaxial-free", "neo-Hookean"),
    "uni-axial-ideal": ("clamped", "neo-Hookean"),
    "lambda1-3": ("clamped", "neo-Hookean"),
    "zs22": ("clamped", "neo-Hookean"),
    "voltage-control": ("voltage", None),
    "wrinkling-fe": ("wrinkling", "neo-Hookean"),
}

#: Default tolerances of the measures (``--tol NAME=VALUE`` replaces one; docs/check.md
#: says where each comes from, :data:`TOLERANCE_SOURCES` in one line each).
TOLERANCES = {
    "lam1": 1e-6,
    "lam1_clamped": 1e-2,
    "lam1_limit": 1e-4,
    "E0_limit": 1e-6,
    "stable": 0.0,
    "D0_crit": 1e-3,
    "D0_b": 0.0,
}

TOLERANCE_SOURCES = {
    "lam1": "a homogeneous state is exact in any conforming discretisation: what remains is "
            "the solver tolerance and the digits of the file (validate itself holds 1e-8)",
    "lam1_clamped": "the centre of the clamped plate follows the homogeneous curve within "
                    "1 % (paper Sec. 6; validate's tolerance)",
    "lam1_limit": "the limit point located on a path of E0 flat to second order: 1e-4 in "
                  "lam1 (validate's voltage-control target)",
    "E0_limit": "the maximum of E0 itself, 1e-6 (validate's voltage-control target)",
    "stable": "the Hessian verdict is exact away from the det H* = 0 locus: no row may "
              "disagree (rows within the lam1_limit tolerance of the limit point excluded)",
    "D0_crit": "validate's FE cross-section with 8 elements per half-wave reaches 1e-3",
    "D0_b": "the converged buckling load's error bar (validation/data/buckling_loads.csv) "
            "plus the file's D0_b_error, or this absolute value",
}

#: contract files that are read by nothing here: ``{file name or suffix: why}``
_NOT_SCORED = {
    "_fields.csv": "field samples along the centre line (no closed form)",
    "wrinkling-fe-elastic.csv": "the uncharged plate's critical stretch (not scored)",
    "buckling.csv": "a study table of skfem-dielectric buckling (not scored)",
    "buckling-scan.csv": "a study table of skfem-dielectric buckling (not scored)",
    "buckling-trials.csv": "a study table of skfem-dielectric buckling (not scored)",
    "buckling-plain.csv": "a study table of skfem-dielectric buckling (not scored)",
    "post-buckling.csv": "a study table of skfem-dielectric post-buckling (not scored)",
    "post-buckling-summary.csv": "a study table of skfem-dielectric post-buckling (not "
                                 "scored)",
}

#: accepted names of a quantity, the contract's first
_ALIASES = {"lam1": ("lam1_fe", "lam1"), "lam3": ("lam3_fe", "lam3"),
            "D0_crit": ("D0_fe", "D0")}
_MODELS = {"neo-hookean": "neo-Hookean", "neohookean": "neo-Hookean", "nh": "neo-Hookean",
           "gent": "Gent"}
_LOADINGS = ("equibiaxial", "uniaxial-free", "uniaxial")
_TRUE = {"true": True, "1": True, "yes": True, "false": False, "0": False, "no": False}


class CheckInputError(ValueError):
    """A results file that cannot be scored; the message is one line naming the file (and
    the line and column where there is one)."""


# --------------------------------------------------------------------------- reading
@dataclass(frozen=True)
class _Row:
    """One data row: its file, its line in the file and its cells by column name."""

    file: str
    line: int
    cells: dict

    @property
    def where(self) -> str:
        return f"{self.file} line {self.line}"


def read_csv_rows(path) -> tuple[list[str], list]:
    """The header and data rows of a results CSV.

    Lines starting with ``#`` (comments, anywhere) and blank lines are skipped; the first
    other line is the header (names stripped of blanks); every row must have as many
    cells as the header.

    Parameters
    ----------
    path : path-like

    Returns
    -------
    header : list of str
    rows : list
        Rows with ``.file``, ``.line`` (1-based line number in the file) and ``.cells``
        (column name -> stripped text).

    Raises
    ------
    CheckInputError
        Not UTF-8 text, no header, a column named twice, a row with another number of
        cells than the header, or no data row.
    OSError
        The file cannot be read.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError:
        raise CheckInputError(f"{path.name}: not a text file (UTF-8); the results contract "
                              f"is a comma-separated text file (docs/check.md)") from None
    header, rows = None, []
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        cells = [c.strip() for c in next(csv.reader([line]))]
        if header is None:
            header = cells
            dup = sorted({c for c in header if header.count(c) > 1})
            if dup:
                raise CheckInputError(f"{path.name} line {number}: column {dup[0]!r} appears "
                                      f"more than once in the header")
            continue
        if len(cells) != len(header):
            raise CheckInputError(f"{path.name} line {number}: {len(cells)} cells, the header "
                                  f"has {len(header)} columns")
        rows.append(_Row(path.name, number, dict(zip(header, cells))))
    if header is None:
        raise CheckInputError(f"{path.name}: no header line (only comments or blank lines)")
    if not rows:
        raise CheckInputError(f"{path.name}: a header but no data row")
    return header, rows


def _column(header, quantity: str) -> str | None:
    """The column of ``quantity`` in ``header`` (its aliases, the contract's name first)."""
    for name in _ALIASES.get(quantity, (quantity,)):
        if name in header:
            return name
    return None


def _number(row: _Row, col: str | None, *, required: bool = True) -> float | None:
    """The number in column ``col`` of ``row``; ``None`` for an empty cell (``required``:
    an error instead); text, NaN and infinities are errors naming the cell."""
    if col is None:
        return None
    text = row.cells.get(col, "")
    if text == "":
        if required:
            raise CheckInputError(f"{row.where}, column {col}: empty, and the row needs it "
                                  f"(leave a row out, or set converged to False, for a value "
                                  f"that is not available)")
        return None
    try:
        x = float(text)
    except ValueError:
        raise CheckInputError(f"{row.where}, column {col}: {text!r} is not a number") from None
    if not math.isfinite(x):
        raise CheckInputError(f"{row.where}, column {col}: {text} (leave the cell empty for "
                              f"'not available', and set converged to False on a row the "
                              f"solver did not reach)")
    return x


def _flag(row: _Row, col: str | None) -> bool | None:
    if col is None or row.cells.get(col, "") == "":
        return None
    text = row.cells[col].lower()
    if text not in _TRUE:
        raise CheckInputError(f"{row.where}, column {col}: {row.cells[col]!r} is not True or "
                              f"False")
    return _TRUE[text]


def _model(row: _Row, header, case: str) -> str:
    default = CHECK_CASES[case][1]
    if "model" not in header or row.cells["model"] == "":
        if default is None:
            raise CheckInputError(f"{row.where}: case {case} needs the column model "
                                  f"(neo-Hookean or Gent, Jm = {GENT_JM:g})")
        return default
    name = _MODELS.get(row.cells["model"].lower().replace(" ", ""))
    if name is None:
        raise CheckInputError(f"{row.where}, column model: {row.cells['model']!r} is neither "
                              f"neo-Hookean nor Gent")
    return name


def _text(row: _Row, col: str, choices, default=None) -> str:
    value = row.cells.get(col, "")
    if value == "" and default is not None:
        return default
    if value not in choices:
        raise CheckInputError(f"{row.where}, column {col}: {value!r} is not one of "
                              f"{', '.join(choices)}")
    return value


def _not_scored(name: str) -> str | None:
    for key, why in _NOT_SCORED.items():
        if name == key or (key.startswith("_") and name.endswith(key)):
            return why
    return None


def _files(path: Path) -> list[Path]:
    if path.is_dir():
        files = sorted(p for p in path.iterdir() if p.suffix.lower() == ".csv" and p.is_file())
        if not files:
            raise CheckInputError(f"{path} holds no CSV file (the results contract: one "
                                  f"<case>.csv per case, docs/check.md)")
        return files
    if not path.exists():
        raise FileNotFoundError(2, "No such file or directory", str(path))
    return [path]


def _gather(path: Path, cases) -> tuple[dict, list[str]]:
    """``({case: [(header, rows)]}, notes)`` of every results file below ``path``."""
    found: dict[str, list] = {}
    notes, seen = [], []
    for f in _files(path):
        why = _not_scored(f.name)
        if why is not None and f != path:
            notes.append(f"{f.name}: {why}")
            continue
        header, rows = read_csv_rows(f)
        if "case" in header:
            by_case: dict[str, list] = {}
            for r in rows:
                name = r.cells["case"]
                if name not in CHECK_CASES:
                    raise CheckInputError(f"{r.where}, column case: unknown case {name!r} "
                                          f"(cases: {', '.join(CHECK_CASES)})")
                by_case.setdefault(name, []).append(r)
        elif f.stem in CHECK_CASES:
            by_case = {f.stem: rows}
        else:
            hint = ""
            if len(header) == 1 and any(sep in header[0] for sep in ";\t"):
                hint = " (separated by semicolons or tabs? the contract is comma-separated)"
            raise CheckInputError(
                f"{f.name}: not a results CSV of the contract: no column 'case' and "
                f"{f.stem!r} is no case name{hint}; columns: {', '.join(header)[:200]} "
                f"(docs/check.md)")
        for name, rs in by_case.items():
            seen.append(name)
            if cases is None or name in cases:
                found.setdefault(name, []).append((header, rs))
    if cases is not None:
        missing = [c for c in cases if c not in found]
        if missing:
            raise CheckInputError(f"{path}: no rows of case {missing[0]} (cases found: "
                                  f"{', '.join(dict.fromkeys(seen)) or 'none'})")
    if not found:
        raise CheckInputError(f"{path}: no results CSV of a case (only {len(notes)} files "
                              f"that are not scored)")
    return found, notes


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
        return _g(self.error)

    def line(self) -> str:
        """One line: the measure, its worst error, tolerance and row, the verdict."""
        verdict = "pass" if self.passed else "FAIL"
        return (f"{self.name}: {verdict} ({self.what}: {self.error_text()}, tolerance "
                f"{self.tol:g}, {self.n} rows; worst {self.where}: {self.detail})")


def _rows(n: int) -> str:
    return f"{n} row" if n == 1 else f"{n} rows"


def _g(x: float) -> str:
    return "inf" if not math.isfinite(x) else format(x, ".2e")


def _measure(case, name, what, rows, err, tol, details, diagnose=None) -> Measure:
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


def _closed(rows, fn, *arrays) -> np.ndarray:
    """``fn(*arrays)`` as a float array (one entry per row of ``rows``); a ``ValueError`` of
    the closed form (a value out of its range, e.g. one whose square overflows) becomes a
    :class:`CheckInputError` naming the first row it comes from."""
    try:
        with np.errstate(all="ignore"):
            return np.atleast_1d(np.asarray(fn(*arrays), dtype=float))
    except ValueError as exc:
        for i, row in enumerate(rows):
            try:
                with np.errstate(all="ignore"):
                    fn(*(a[i:i + 1] for a in arrays))
            except ValueError as one:
                raise CheckInputError(f"{row.where}: out of the range of the closed form "
                                      f"({' '.join(str(one).split())})") from None
        raise CheckInputError(f"{rows[0].where}: {' '.join(str(exc).split())}") from None


def _lam1_closed(D0, s, model, loading, rows) -> np.ndarray:
    """Closed-form ``lam1`` per row: Eq. (loading_gent) inverted (``equibiaxial_lam``) or
    Eq. (DEuniax) inverted (``uniaxial_lam1``)."""
    out = np.full(D0.shape, np.nan)
    for m in set(model):
        for ld in set(loading):
            sel = (model == m) & (loading == ld)
            if not sel.any():
                continue
            am = analytic_model(m)
            f = an.equibiaxial_lam if ld == "equibiaxial" else an.uniaxial_lam1
            out[sel] = _closed([r for r, k in zip(rows, sel) if k],
                               lambda d, s_: f(d, s_, am), D0[sel], s[sel])
    return out


def _lam3_state(lam1, lam3, s, model, loading, rows) -> np.ndarray:
    """``lam3`` of each row: the file's where given, else ``lam1`` equi-biaxially and
    Eq. (uni-axial-loading) (``uniaxial_lam3(lam1, s)``) uni-axially."""
    out = lam3.copy()
    need = ~np.isfinite(out)
    out[need & (loading == "equibiaxial")] = lam1[need & (loading == "equibiaxial")]
    for m in set(model):
        sel = need & (loading != "equibiaxial") & (model == m)
        if sel.any():
            am = analytic_model(m)
            out[sel] = _closed([r for r, k in zip(rows, sel) if k],
                               lambda l1, s_: an.uniaxial_lam3(l1, s_, am), lam1[sel], s[sel])
    return out


@dataclass
class _Loading:
    """The columns of rows scored against a loading curve (one array entry per row)."""

    rows: list
    s: np.ndarray
    D0: np.ndarray
    lam1: np.ndarray
    lam3: np.ndarray
    model: np.ndarray
    loading: np.ndarray
    E0: np.ndarray              # the file's E0 where D0 came from it, else nan
    alpha: np.ndarray
    s_from_alpha: np.ndarray    # s of the Keplinger plate computed from alpha

    def replace(self, **kw) -> "_Loading":
        d = dict(vars(self))
        d.update(kw)
        return _Loading(**d)


def _lam1_errors(p: _Loading) -> tuple[np.ndarray, np.ndarray]:
    ref = _lam1_closed(p.D0, p.s, p.model, p.loading, p.rows)
    with np.errstate(all="ignore"):
        return ref, np.abs(p.lam1 - ref) / ref


def _hypotheses(p: _Loading) -> list[tuple[str, Callable[[], _Loading]]]:
    """Mix-ups of conventions that a failing loading measure is tried with: ``(what it
    would mean, the rows read that way)``."""
    lam3 = _lam3_state(p.lam1, p.lam3, p.s, p.model, p.loading, p.rows)
    from_E0 = np.isfinite(p.E0)
    out = []
    if np.any(p.s != 0):
        out.append(("s has the opposite sign (the contract's s > 0 is a dead load that "
                    "stretches the plate)", lambda: p.replace(s=-p.s)))
        out.append(("s is the true traction, per current area of the loaded face (the "
                    "contract's s is nominal, per reference area: s = t_true/lam1)",
                    lambda: p.replace(s=p.s / p.lam1)))
    if np.any(~from_E0):
        out.append(("D0 is given per current area, the true D = D_L/(lam1 lam3) (the "
                    "contract's D0 is the charge per reference area: D0 = D lam1 lam3)",
                    lambda: p.replace(D0=np.where(from_E0, p.D0, p.D0 * p.lam1 * lam3))))
        out.append(("the D0 column holds E0 (the contract's D0 = lam1^2 lam3^2 E0, Eq. DLEL)",
                    lambda: p.replace(D0=np.where(from_E0, p.D0, p.D0 * (p.lam1 * lam3)**2))))
    if np.any(from_E0):
        out.append(("the E0 column holds D0 (the contract's E0 = D0/(lam1 lam3)^2)",
                    lambda: p.replace(D0=np.where(from_E0, p.E0, p.D0))))
        out.append(("E0 is the field in the deformed plate, voltage over the current "
                    "thickness (the contract's E0 is over the reference thickness)",
                    lambda: p.replace(D0=np.where(from_E0, p.E0 * p.lam1 * lam3, p.D0))))
    if np.any(np.isfinite(p.lam3)) and np.any(p.loading != "equibiaxial"):
        out.append(("lam1 and lam3 are swapped (lam1 is along the dead load, x1; lam3 across "
                    "the width, x3)",
                    lambda: p.replace(lam1=np.where(np.isfinite(p.lam3), p.lam3, p.lam1),
                                      lam3=np.where(np.isfinite(p.lam3), p.lam1, p.lam3))))
    other = np.where(p.model == "Gent", "neo-Hookean", "Gent")
    names = " and ".join(sorted(set(p.model)))
    out.append((f"the rows are of the other model than the {names} they name (Gent has "
                f"Jm = {GENT_JM:g})", lambda: p.replace(model=other)))
    if np.any(p.s_from_alpha):
        out.append(("the alpha column holds s (the contract's alpha is the weight fraction, "
                    f"s = alpha m g/(mu A) = {float(keplinger_s(1.0, g=KEPLINGER['g'])):.5g} "
                    "alpha)",
                    lambda: p.replace(s=np.where(p.s_from_alpha, p.alpha, p.s))))
    return out


def _diagnose(p: _Loading, tol: float, err_of=None) -> str:
    """The first mix-up of :func:`_hypotheses` under which every row passes."""
    err_of = err_of or (lambda q: _lam1_errors(q)[1])
    for what, read in _hypotheses(p):
        try:
            with np.errstate(all="ignore"):
                err = err_of(read())
        except ValueError:              # read that way a row leaves the closed form's range
            continue
        err = np.where(np.isfinite(err), err, np.inf)
        if err.size and np.all(err <= tol):
            return (f"looks like {what}: read that way the largest error would be "
                    f"{_g(float(err.max()))}")
    return ("no usual mix-up of conventions explains it (tried: the sign of s, s per "
            "current area, D0 per current area, E0 for D0, the other model)")


def _loading_measure(case, p: _Loading, name: str, tol: float, eq: str) -> Measure:
    ref, err = _lam1_errors(p)

    def details(i):
        load = f"s = {p.s[i]:.6g}" + (f" (alpha = {p.alpha[i]:g})"
                                      if np.isfinite(p.alpha[i]) else "")
        src = f"E0 = {p.E0[i]:.6g}, " if np.isfinite(p.E0[i]) else ""
        return (f"{p.model[i]}, {load}, {src}D0 = {p.D0[i]:.6g}: lam1 = {p.lam1[i]:.10g}, "
                f"closed form {ref[i]:.10g}")

    return _measure(case, name, f"relative error of lam1 against {eq}", p.rows, err, tol,
                    details, lambda: _diagnose(p, tol))


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
        return _table([self])


def _table(cases) -> str:
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
        return _table(self.cases)

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


def _loading_rows(case, tables, kind) -> tuple[_Loading | None, list]:
    """The rows of a loading case (homogeneous or clamped) as :class:`_Loading`, and the
    notes."""
    rows, vals, notes = [], [], []
    skipped_conv, skipped_empty = 0, 0
    for header, rs in tables:
        c_lam1, c_lam3 = _column(header, "lam1"), _column(header, "lam3")
        if kind != "clamped" and "s" not in header:
            raise CheckInputError(f"{rs[0].file}: column s missing (case {case} needs case, "
                                  f"s, D0 or E0, lam1; docs/check.md)")
        if kind == "clamped" and "s" not in header and "alpha" not in header:
            raise CheckInputError(f"{rs[0].file}: columns s and alpha missing (case {case} "
                                  f"needs s or alpha; docs/check.md)")
        if c_lam1 is None and not (kind == "clamped" and "D0_b" in header):
            raise CheckInputError(f"{rs[0].file}: column lam1 missing (case {case} needs "
                                  f"lam1_fe or lam1, the stretch at the plate centre)")
        if c_lam1 is not None and "D0" not in header and "E0" not in header:
            raise CheckInputError(f"{rs[0].file}: columns D0 and E0 missing (case {case} "
                                  f"needs the charge D0 or the field E0)")
        for r in rs:
            if _flag(r, "converged" if "converged" in header else None) is False:
                skipped_conv += 1
                continue
            lam1 = _number(r, c_lam1, required=False)
            if lam1 is None:
                skipped_empty += 1
                continue
            if lam1 <= 0:
                raise CheckInputError(f"{r.where}, column {c_lam1}: {lam1:g} is not a stretch "
                                      f"(> 0)")
            lam3 = _number(r, c_lam3, required=False)
            model = _model(r, header, case)
            alpha = _number(r, "alpha" if "alpha" in header else None, required=False)
            s = _number(r, "s" if "s" in header else None, required=alpha is None)
            from_alpha = s is None
            if from_alpha:
                if alpha < 0:
                    raise CheckInputError(f"{r.where}, column alpha: {alpha:g} < 0")
                s = float(keplinger_s(alpha, g=KEPLINGER["g"]))
            if "D0" in header and r.cells["D0"] != "":
                D0, E0 = _number(r, "D0"), np.nan
            else:                  # D0 = lam1^2 lam3^2 E0 below, once lam3 is known
                D0, E0 = np.nan, _number(r, "E0" if "E0" in header else "D0")
            rows.append(r)
            vals.append((s, D0, lam1, np.nan if lam3 is None else lam3, model, E0,
                         np.nan if alpha is None else alpha, from_alpha))
    if skipped_conv:
        notes.append(f"{_rows(skipped_conv)} with converged = False not scored")
    if skipped_empty:
        notes.append(f"{_rows(skipped_empty)} without lam1 not scored")
    if not rows:
        return None, notes
    s, D0, lam1, lam3, model, E0, alpha, from_alpha = (np.array(v) for v in zip(*vals))
    s, D0, lam1, lam3, E0, alpha = (np.asarray(a, dtype=float)
                                    for a in (s, D0, lam1, lam3, E0, alpha))
    loading = np.full(len(rows), "equibiaxial" if kind == "equibiaxial" else "uniaxial")
    p = _Loading(rows, s, D0, lam1, lam3, model.astype(str), loading, E0, alpha,
                 from_alpha.astype(bool))
    if np.any(np.isfinite(E0)):                       # D0 = lam1^2 lam3^2 E0 (Eq. DLEL)
        l3 = _lam3_state(p.lam1, p.lam3, p.s, p.model, p.loading, p.rows)
        with np.errstate(all="ignore"):
            p = p.replace(D0=np.where(np.isfinite(E0), E0 * (p.lam1 * l3) ** 2, p.D0))
    return p, notes


def _stable_measure(case, rows, lam1, lam3, D0, model, control, theirs, exclude=None,
                    name="stable"):
    """Rows whose ``stable`` disagrees with the Hessian verdict, Eq. (equiv)
    (:func:`analytic.stability_verdict`)."""
    ours = np.zeros(len(rows), dtype=bool)
    for m in set(model):
        sel = model == m
        am = analytic_model(m)
        ours[sel] = _closed([r for r, k in zip(rows, sel) if k],
                            lambda a, b, c: an.stability_verdict(a, b, c, am, control=control),
                            lam1[sel], lam3[sel], D0[sel]) > 0.5
    keep = np.ones(len(rows), dtype=bool) if exclude is None else ~exclude
    idx = np.flatnonzero(keep)
    if not idx.size:
        return None
    err = (ours[idx] != theirs[idx]).astype(float)

    def details(i):
        j = idx[i]
        return (f"lam1 = {lam1[j]:.6g}, D0 = {D0[j]:.6g}: {name} = {bool(theirs[j])}, the "
                f"Hessian ({control} control) says {bool(ours[j])}")

    return _measure(case, name, f"rows whose {name} disagrees with the Hessian verdict "
                    f"under {control} control, Eq. (equiv)", [rows[j] for j in idx], err,
                    0.0, details, lambda: "the verdict differs from the sign of the Hessian's "
                    "leading 2x2 minor (docs/theory.md, Stability)")


def _stability_rows(case, tables, p: _Loading):
    """``stable`` of the rows of ``p`` (``None`` where the file says nothing)."""
    by_row = {}
    for header, rs in tables:
        if "stable" in header:
            for r in rs:
                by_row[(r.file, r.line)] = _flag(r, "stable")
    return np.array([by_row.get((r.file, r.line)) for r in p.rows], dtype=object)


def _check_loading(case, tables, tol) -> CaseCheck:
    kind = CHECK_CASES[case][0]
    p, notes = _loading_rows(case, tables, kind)
    if p is None:
        raise CheckInputError(f"case {case}: no row to score in "
                              f"{', '.join(sorted({h[1][0].file for h in tables}))}")
    eq = "Eq. (loading_gent)" if kind == "equibiaxial" else "Eq. (DEuniax)"
    measures = [_loading_measure(case, p, "lam1", tol["lam1"], eq)]
    stable = _stability_rows(case, tables, p)
    given = np.array([v is not None for v in stable])
    if given.any():
        lam3 = _lam3_state(p.lam1, p.lam3, p.s, p.model, p.loading, p.rows)
        sel = np.flatnonzero(given)
        m = _stable_measure(case, [p.rows[i] for i in sel], p.lam1[sel], lam3[sel],
                            p.D0[sel], p.model[sel], "charge",
                            np.array([bool(v) for v in stable[sel]]))
        measures.append(m)
    _, err = _lam1_errors(p)
    points = dict(kind=kind, s=p.s, D0=p.D0, lam1=p.lam1, model=p.model,
                  lam3=_lam3_state(p.lam1, p.lam3, p.s, p.model, p.loading, p.rows),
                  ok=err <= tol["lam1"])
    return CaseCheck(case, _file_names(tables), tuple(measures), tuple(notes), points)


def _check_clamped(case, tables, tol) -> CaseCheck:
    p, notes = _loading_rows(case, tables, "clamped")
    measures, points = [], {"kind": "clamped"}
    if p is not None:
        measures.append(_loading_measure(case, p, "lam1_clamped", tol["lam1_clamped"],
                                         "the homogeneous curve, Eq. (DEuniax)"))
        _, err = _lam1_errors(p)
        alpha = np.where(np.isfinite(p.alpha), p.alpha,
                         p.s / float(keplinger_s(1.0, g=KEPLINGER["g"])))
        points.update(s=p.s, D0=p.D0, lam1=p.lam1, alpha=alpha, ok=err <= tol["lam1_clamped"])
    m, bpoints, bnotes = _buckling_measure(case, tables, tol)
    notes += bnotes
    if m is not None:
        measures.append(m)
        points["buckling"] = bpoints
    if not measures:
        raise CheckInputError(f"case {case}: no row to score (lam1 with D0, or D0_b) in "
                              f"{', '.join(_file_names(tables))}")
    return CaseCheck(case, _file_names(tables), tuple(measures), tuple(notes), points)


def _alpha_of(r, header) -> float:
    alpha = _number(r, "alpha" if "alpha" in header else None, required=False)
    if alpha is not None:
        return alpha
    s = _number(r, "s" if "s" in header else None)
    return s / float(keplinger_s(1.0, g=KEPLINGER["g"]))


def _buckling_measure(case, tables, tol):
    """``D0_b`` per weight against the converged load of
    :func:`validation.buckling_data.buckling_loads` (Sec. 6; docs/validation.md: the graded
    meshes' load where they agree, else the uniform meshes' extrapolation)."""
    entries, uniform = buckling_loads(), uniform_buckling_loads()
    found = {}                    # (alpha, run) -> (row, D0_b, own error)
    for header, rs in tables:
        if "D0_b" not in header:
            continue
        if "s" not in header and "alpha" not in header:
            raise CheckInputError(f"{rs[0].file}: column alpha (or s) missing: D0_b is "
                                  f"checked per weight fraction alpha")
        for r in rs:
            D0b = _number(r, "D0_b", required=False)
            if D0b is None:
                continue
            alpha = _alpha_of(r, header)
            key = (round(alpha, 9), r.cells.get("run", ""), r.cells.get("variant", ""))
            if key not in found:
                u = _number(r, "D0_b_error" if "D0_b_error" in header else None,
                            required=False)
                found[key] = (r, D0b, u, alpha)
    notes, rows, err, tols, info = [], [], [], [], []
    for (a, _, _), (r, D0b, u, alpha) in found.items():
        e = next((e for e in entries if math.isclose(e.alpha, alpha, rel_tol=1e-6,
                                                     abs_tol=1e-9)), None)
        if e is None or not e.converged:
            why = "no entry" if e is None else "no converged load (its meshes disagree)"
            notes.append(f"{r.where}: D0_b of alpha = {alpha:g} not scored: {why} in "
                         f"validation/{BUCKLING_LOADS_FILE}")
            continue
        extra = u if u is not None else tol["D0_b"]
        rows.append(r)
        err.append(abs(D0b - e.D0_b))
        tols.append(e.error + extra)
        info.append((alpha, D0b, e, u))
    if not rows:
        return None, [], notes

    def details(i):
        alpha, D0b, e, u = info[i]
        mine = f" ± {u:g}" if u is not None else ""
        return (f"alpha = {alpha:g}: D0_b = {D0b:.6g}{mine}, converged {e.D0_b:.4f} ± "
                f"{e.error:.4f}")

    def diagnose():
        out = []
        for (alpha, D0b, e, u), er, t in zip(info, err, tols):
            if er <= t:
                continue
            meshes = ", ".join(f"{m}: {v:.4f}" for m, v in zip(e.meshes, e.D0_b_mesh))
            # our meshes that are not converged: the entry's own, and the uniform ones
            # where the graded meshes replaced them
            cands = list(zip(e.meshes, e.D0_b_mesh)) + [
                (f"uniform {m}", v) for u in uniform if u.source != e.source
                and math.isclose(u.alpha, alpha, rel_tol=1e-6, abs_tol=1e-9)
                for m, v in zip(u.meshes, u.D0_b_mesh) if math.isfinite(v)]
            near = min(cands, key=lambda mv: abs(mv[1] - D0b))
            side = "above" if D0b > e.D0_b else "below"
            text = (f"alpha = {alpha:g}: {D0b:.4f} is {side} the converged load (our eighth "
                    f"models: {meshes})")
            if abs(near[1] - D0b) <= 0.1 * abs(D0b - e.D0_b):
                text += (f"; it is the load of our {near[0]} mesh: a mesh that is not "
                         f"converged (refine, or state its error in a D0_b_error column)")
            out.append(text)
        return "; ".join(out)

    m = _measure(case, "D0_b", "|D0_b - D0_b converged| (buckling load, Sec. 6)", rows,
                 np.array(err), np.array(tols), details, diagnose)
    points = [(alpha, D0b, ok) for (alpha, D0b, _, _), ok in
              zip(info, np.array(err) <= np.array(tols))]
    return m, points, notes


def _check_voltage(case, tables, tol) -> CaseCheck:
    """Paths under voltage control: ``lam1`` at each point against the loading curve,
    ``stable`` and ``stable_charge`` against the Hessian, the limit points against
    :func:`analytic.max_E0`."""
    rows, vals, notes = [], [], []
    limits = {}
    clamped = 0
    skipped = 0
    for header, rs in tables:
        for col in ("loading", "s", "lam1"):
            if _column(header, col) is None:
                raise CheckInputError(f"{rs[0].file}: column {col} missing (case {case} "
                                      f"needs case, loading, s, E0 or D0, lam1; "
                                      f"docs/check.md)")
        if "D0" not in header and "E0" not in header:
            raise CheckInputError(f"{rs[0].file}: columns D0 and E0 missing")
        c_lam1 = _column(header, "lam1")
        for r in rs:
            loading = _text(r, "loading", _LOADINGS)
            if loading == "uniaxial":
                clamped += 1
                continue
            lam1 = _number(r, c_lam1, required=False)
            if lam1 is None:
                skipped += 1
                continue
            model = _model(r, header, case)
            s = _number(r, "s")
            D0 = _number(r, "D0", required=False) if "D0" in header else None
            E0 = _number(r, "E0", required=D0 is None) if "E0" in header else None
            run = r.cells.get("run") or f"{loading} {model} s={s:g}"
            kind = r.cells.get("kind", "")
            rows.append(r)
            vals.append((s, np.nan if D0 is None else D0, lam1, model, loading,
                         np.nan if E0 is None else E0, _flag(r, "stable" if "stable" in
                                                             header else None),
                         _flag(r, "stable_charge" if "stable_charge" in header else None)))
            if kind == "limit":
                limits[run] = (r, lam1, E0 if E0 is not None else np.nan, s, model, loading)
            elif run not in limits and "lam1_max_fe" in header and \
                    r.cells.get("lam1_max_fe", "") != "":
                limits[run] = (r, _number(r, "lam1_max_fe"),
                               _number(r, "E0_max_fe" if "E0_max_fe" in header else None,
                                       required=False) or np.nan, s, model, loading)
    if clamped:
        notes.append(f"{_rows(clamped)} of the clamped plate (loading uniaxial) not scored: "
                     f"the closed forms are of homogeneous plates")
    if skipped:
        notes.append(f"{_rows(skipped)} without lam1 not scored")
    if not rows:
        raise CheckInputError(f"case {case}: no row of a homogeneous plate to score in "
                              f"{', '.join(_file_names(tables))}")
    s, D0, lam1, model, loading, E0, stable, stable_charge = (list(v) for v in zip(*vals))
    s, D0, lam1, E0 = (np.asarray(a, dtype=float) for a in (s, D0, lam1, E0))
    model, loading = np.array(model, dtype=str), np.array(loading, dtype=str)
    ld = np.where(loading == "equibiaxial", "equibiaxial", "uniaxial")
    p = _Loading(rows, s, D0, lam1, np.full(len(rows), np.nan), model, ld,
                 np.where(np.isfinite(D0), np.nan, E0), np.full(len(rows), np.nan),
                 np.zeros(len(rows), dtype=bool))
    lam3 = _lam3_state(p.lam1, p.lam3, p.s, p.model, p.loading, p.rows)
    with np.errstate(all="ignore"):
        p = p.replace(D0=np.where(np.isfinite(D0), D0, E0 * (lam1 * lam3) ** 2))
    measures = [_loading_measure(case, p, "lam1", tol["lam1"],
                                 "the loading curve, Eq. (loading_gent) or Eq. (DEuniax)")]
    # the limit point of each row's path, and the rows within tolerance of it
    lim_lam = np.full(len(rows), np.nan)
    for m_ in set(model):
        for l_ in set(ld):
            sel = (model == m_) & (ld == l_)
            if sel.any():
                am = analytic_model(m_)
                lim_lam[sel] = _closed([r for r, k in zip(rows, sel) if k],
                                       lambda s_: an.max_E0(s_, am, loading=l_)[0], s[sel])
    with np.errstate(invalid="ignore"):
        marginal = np.abs(lam1 / lim_lam - 1) <= tol["lam1_limit"]
    marginal |= np.array([r.cells.get("kind", "") == "limit" for r in rows])
    for name, flags, control in (("stable", stable, "voltage"),
                                 ("stable_charge", stable_charge, "charge")):
        given = np.array([f is not None for f in flags])
        if not given.any():
            continue
        sel = np.flatnonzero(given)
        m = _stable_measure(case, [rows[i] for i in sel], lam1[sel], lam3[sel],
                            p.D0[sel], model[sel], control,
                            np.array([bool(flags[i]) for i in sel]),
                            exclude=marginal[sel] if control == "voltage" else None, name=name)
        if m is not None:
            measures.append(m)
    lim_points = []
    if limits:
        lrows, lerr, Eerr, linfo = [], [], [], []
        for run, (r, l1, e0, s_, m_, l_) in limits.items():
            lam_ref, E0_ref = (float(v[0]) for v in _closed(
                [r], lambda x: np.array(an.max_E0(x, analytic_model(m_), loading=(
                    "equibiaxial" if l_ == "equibiaxial" else "uniaxial"))), np.array([s_])))
            lrows.append(r)
            lerr.append(abs(l1 / lam_ref - 1) if math.isfinite(lam_ref) else math.inf)
            Eerr.append(abs(e0 / E0_ref - 1) if math.isfinite(E0_ref) and math.isfinite(e0)
                        else (math.inf if not math.isfinite(E0_ref) else math.nan))
            linfo.append((run, l1, e0, lam_ref, E0_ref, s_, m_, l_))

        def ldetail(key):
            def details(i):
                run, l1, e0, lam_ref, E0_ref, s_, m_, l_ = linfo[i]
                if not math.isfinite(lam_ref):
                    return (f"{run}: a limit point, but E0 has no maximum at s = {s_:g} "
                            f"({m_}, analytic.max_E0)")
                return (f"{run}: lam1 = {l1:.10g}, E0 = {e0:.10g}; max_E0: lam1 = "
                        f"{lam_ref:.10g}, E0 = {E0_ref:.10g}")
            return details

        lerr_a = np.array(lerr)
        measures.append(_measure(case, "lam1_limit", "relative error of lam1 at the limit "
                                 "point against analytic.max_E0 (det H* = 0)", lrows, lerr_a,
                                 tol["lam1_limit"], ldetail("lam1")))
        E = np.array(Eerr)
        if np.any(np.isfinite(E) | np.isinf(E)):
            keep = ~np.isnan(E)
            measures.append(_measure(case, "E0_limit", "relative error of the maximum of E0 "
                                     "against analytic.max_E0", [lrows[i] for i in
                                                                  np.flatnonzero(keep)],
                                     E[keep], tol["E0_limit"],
                                     lambda i: ldetail("E0")(int(np.flatnonzero(keep)[i]))))
        lim_points = [("equibiaxial" if l_ == "equibiaxial" else "uniaxial", m_, s_, l1, e0,
                       lerr_a[i] <= tol["lam1_limit"])
                      for i, (run, l1, e0, lam_ref, E0_ref, s_, m_, l_) in enumerate(linfo)]
    _, err = _lam1_errors(p)
    points = dict(kind="voltage", s=s, D0=p.D0, lam1=lam1, lam3=lam3, model=model,
                  loading=ld, ok=err <= tol["lam1"], limits=lim_points)
    return CaseCheck(case, _file_names(tables), tuple(measures), tuple(notes), points)


def _check_wrinkling(case, tables, tol) -> CaseCheck:
    """The critical ``D0`` of each row against :func:`analytic.critical_D0` (the exact
    dispersion relation of the finite plate, Sec. 4; ``D0 = lam^4 E0`` under voltage
    control)."""
    rows, vals, notes, skipped = [], [], [], 0
    for header, rs in tables:
        col = _column(header, "D0_crit")
        for need in ("mode", "lam", "kh"):
            if need not in header:
                raise CheckInputError(f"{rs[0].file}: column {need} missing (case {case} needs "
                                      f"mode, lam, kh, D0_fe; control optional)")
        if col is None:
            raise CheckInputError(f"{rs[0].file}: column D0_fe missing (the critical D0)")
        for r in rs:
            D0 = _number(r, col, required=False)
            if D0 is None:
                skipped += 1
                continue
            control = _text(r, "control", ("charge", "voltage"), default="charge")
            mode = _text(r, "mode", ("antisymmetric", "symmetric"))
            lam, kh = _number(r, "lam"), _number(r, "kh")
            if lam <= 0 or kh <= 0:
                raise CheckInputError(f"{r.where}: lam and kh must be > 0, got lam = {lam:g}, "
                                      f"kh = {kh:g}")
            rows.append(r)
            vals.append((control, mode, lam, kh, D0, _model(r, header, case)))
    if skipped:
        notes.append(f"{_rows(skipped)} without a critical D0 not scored")
    if not rows:
        raise CheckInputError(f"case {case}: no row with a critical D0 in "
                              f"{', '.join(_file_names(tables))}")
    control, mode, lam, kh, D0, model = (np.array(v) for v in zip(*vals))
    lam, kh, D0 = (np.asarray(a, dtype=float) for a in (lam, kh, D0))

    def reference(lam_, kh_, mode_):
        ref = np.full(lam_.shape, np.nan)
        for c in set(control):
            for md in set(mode_):
                for mo in set(model):
                    sel = (control == c) & (mode_ == md) & (model == mo)
                    if sel.any():
                        am = analytic_model(mo)
                        ref[sel] = _closed(
                            [r for r, k in zip(rows, sel) if k],
                            lambda a, b: an.critical_D0(a, b, am, mode=md, control=c),
                            lam_[sel], kh_[sel])
        return ref

    ref = reference(lam, kh, mode)
    with np.errstate(all="ignore"):
        err = np.abs(D0 - ref) / ref

    def details(i):
        stroh = f"{ref[i]:.8g}" if np.isfinite(ref[i]) else "no root of the dispersion relation"
        return (f"{control[i]} control, {mode[i]}, lam = {lam[i]:g}, kh = {kh[i]:g}: critical "
                f"D0 = {D0[i]:.8g}, Stroh {stroh}")

    def diagnose():
        t = tol["D0_crit"]
        tries = [("kh is per reference thickness (the contract's kh is per deformed "
                  "thickness, h = lam^-2 H)", lambda: np.abs(D0 - reference(
                      lam, kh * lam**-2, mode)) / reference(lam, kh * lam**-2, mode))]
        if np.any(control == "voltage"):
            tries.append(("the voltage-control rows give E0 (the contract's critical D0 = "
                          "lam^4 E0)", lambda: np.abs(np.where(control == "voltage",
                                                               D0 * lam**4, D0) - ref) / ref))
        other = np.where(mode == "symmetric", "antisymmetric", "symmetric")
        tries.append(("the modes are swapped (antisymmetric: flexural, u2 even through the "
                      "thickness)", lambda: np.abs(D0 - reference(lam, kh, other))
                      / reference(lam, kh, other)))
        for what, e in tries:
            try:
                with np.errstate(all="ignore"):
                    ee = e()
            except ValueError:
                continue
            if np.all(np.isfinite(ee) & (ee <= t)):
                return f"looks like {what}: read that way the largest error would be " \
                       f"{_g(float(ee.max()))}"
        return "no usual mix-up explains it (tried: kh per reference thickness, E0 for D0, " \
               "the modes swapped)"

    m = _measure(case, "D0_crit", "relative error of the critical D0 against the dispersion "
                 "relation (analytic.critical_D0)", rows, err, tol["D0_crit"], details,
                 diagnose)
    points = dict(kind="wrinkling", control=control, mode=mode, lam=lam, kh=kh, D0=D0,
                  ok=np.nan_to_num(err, nan=np.inf) <= tol["D0_crit"])
    return CaseCheck(case, _file_names(tables), (m,), tuple(notes), points)


def _file_names(tables) -> tuple:
    return tuple(dict.fromkeys(rs[0].file for _, rs in tables))


_CHECKERS = {"equibiaxial": _check_loading, "uniaxial-free": _check_loading,
             "clamped": _check_clamped, "voltage": _check_voltage,
             "wrinkling": _check_wrinkling}


def parse_tolerances(items) -> dict:
    """Tolerances from ``NAME=VALUE`` texts (``--tol``).

    Parameters
    ----------
    items : iterable of str or dict
        ``["lam1=1e-4", ...]``, or a ``dict`` ``{name: value}``.

    Returns
    -------
    dict
        :data:`TOLERANCES` with the given ones replaced.

    Raises
    ------
    ValueError
        An unknown name, a text without ``=``, a value that is no number ``>= 0``.
    """
    tol = dict(TOLERANCES)
    pairs = items.items() if isinstance(items, dict) else []
    if not isinstance(items, dict):
        pairs = []
        for text in items or ():
            name, sep, value = str(text).partition("=")
            if not sep:
                raise ValueError(f"--tol must be NAME=VALUE (names: {', '.join(TOLERANCES)}), "
                                 f"got {text!r}")
            pairs.append((name.strip(), value.strip()))
    for name, value in pairs:
        if name not in TOLERANCES:
            raise ValueError(f"--tol: unknown measure {name!r} (measures: "
                             f"{', '.join(TOLERANCES)})")
        try:
            v = float(value)
        except (TypeError, ValueError):
            v = math.nan
        if not (math.isfinite(v) and v >= 0):
            raise ValueError(f"--tol {name} must be a number >= 0, got {value!r}")
        tol[name] = v
    return tol


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
    found, notes = _gather(path, cases)
    checked = tuple(_CHECKERS[CHECK_CASES[name][0]](name, found[name], tolerances)
                    for name in CHECK_CASES if name in found)
    notes += [f"{c.name}: {n}" for c in checked for n in c.notes]
    return CheckResult(str(path), checked, tuple(notes), tolerances)


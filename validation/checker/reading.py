"""Reading a results folder for ``check``: the files, their rows and cells, one line per
mistake.

Every file is a regular file of at most :data:`~validation.checker.contract.MAX_FILE_BYTES`
(a folder at most :data:`~validation.checker.contract.MAX_TOTAL_BYTES`), read line by
line; every cell is read by :func:`row_number`, :func:`row_flag`, :func:`row_model` or
:func:`row_text`, which raise :class:`~validation.checker.contract.CheckInputError` naming
the file, line and column.
"""

from __future__ import annotations

import csv
import math
import stat
from dataclasses import dataclass
from pathlib import Path

from ..specs import GENT_JM
from .contract import CHECK_CASES, MAX_FILE_BYTES, MAX_TOTAL_BYTES, CheckInputError

__all__ = ["Row", "read_csv_rows", "header_column", "row_number", "row_flag", "row_model",
           "row_text", "not_scored", "results_files", "gather", "ALIASES", "LOADINGS",
           "NOT_SCORED"]

#: contract files that are read by nothing here: ``{file name or suffix: why}``
NOT_SCORED = {
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
ALIASES = {"lam1": ("lam1_fe", "lam1"), "lam3": ("lam3_fe", "lam3"),
            "D0_crit": ("D0_fe", "D0")}
MODEL_NAMES = {"neo-hookean": "neo-Hookean", "neohookean": "neo-Hookean", "nh": "neo-Hookean",
           "gent": "Gent"}
LOADINGS = ("equibiaxial", "uniaxial-free", "uniaxial")
TRUE_TEXT = {"true": True, "1": True, "yes": True, "false": False, "0": False, "no": False}



# --------------------------------------------------------------------------- reading
@dataclass(frozen=True)
class Row:
    """One data row: its file, its line in the file and its cells by column name."""

    file: str
    line: int
    cells: dict

    @property
    def where(self) -> str:
        return f"{self.file} line {self.line}"



#: the longest line ``check`` reads (characters): a longer one is not a results row
MAX_LINE_CHARS = 100_000


def _regular_size(path: Path) -> int:
    """The size of ``path`` in bytes; a :class:`CheckInputError` for anything that is not
    a regular file (a device, a pipe, a socket), a ``FileNotFoundError`` for nothing."""
    st = path.stat()                      # follows a symlink; OSError if missing
    if not stat.S_ISREG(st.st_mode):
        raise CheckInputError(f"{path}: not a regular file (a device, pipe or socket?); "
                              f"check reads results CSVs")
    return st.st_size


def _lines(fh, path: Path):
    """The lines of ``fh`` without their ends, each at most :data:`MAX_LINE_CHARS` long
    (read in pieces: a file without a line end is not read whole)."""
    while True:
        line = fh.readline(MAX_LINE_CHARS + 1)
        if not line:
            return
        if len(line) > MAX_LINE_CHARS and not line.endswith(("\n", "\r")):
            raise CheckInputError(f"{path.name}: a line longer than {MAX_LINE_CHARS:,} "
                                  f"characters: not a results CSV (docs/check.md)")
        yield line.rstrip("\r\n")


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
    size = _regular_size(path)
    if size > MAX_FILE_BYTES:
        raise CheckInputError(f"{path.name}: {size / 1024**2:.1f} MB, above the "
                              f"{MAX_FILE_BYTES // 1024**2} MB that check reads from one "
                              f"file (docs/check.md); split it by case")
    header, rows = None, []
    try:
        with open(path, encoding="utf-8-sig", newline="") as fh:
            lines = enumerate(_lines(fh, path), start=1)
            for number, line in lines:
                if not line.strip() or line.lstrip().startswith("#"):
                    continue
                try:
                    cells = [c.strip() for c in next(csv.reader([line]))]
                except csv.Error as exc:
                    raise CheckInputError(f"{path.name} line {number}: not a CSV line "
                                          f"({exc})") from None
                if header is None:
                    header = cells
                    dup = sorted({c for c in header if header.count(c) > 1})
                    if dup:
                        raise CheckInputError(f"{path.name} line {number}: column {dup[0]!r} "
                                              f"appears more than once in the header")
                    continue
                if len(cells) != len(header):
                    raise CheckInputError(f"{path.name} line {number}: {len(cells)} cells, "
                                          f"the header has {len(header)} columns")
                rows.append(Row(path.name, number, dict(zip(header, cells))))
    except UnicodeDecodeError:
        raise CheckInputError(f"{path.name}: not a text file (UTF-8); the results contract "
                              f"is a comma-separated text file (docs/check.md)") from None
    if header is None:
        raise CheckInputError(f"{path.name}: no header line (only comments or blank lines)")
    if not rows:
        raise CheckInputError(f"{path.name}: a header but no data row")
    return header, rows


def header_column(header, quantity: str) -> str | None:
    """The column of ``quantity`` in ``header`` (its aliases, the contract's name first)."""
    for name in ALIASES.get(quantity, (quantity,)):
        if name in header:
            return name
    return None


def row_number(row: Row, col: str | None, *, required: bool = True) -> float | None:
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


def row_flag(row: Row, col: str | None) -> bool | None:
    """The True/False cell of ``row`` in column ``col`` (``None`` for no column or an empty
    cell); any other text is a :class:`CheckInputError` naming the row and column."""
    if col is None or row.cells.get(col, "") == "":
        return None
    text = row.cells[col].lower()
    if text not in TRUE_TEXT:
        raise CheckInputError(f"{row.where}, column {col}: {row.cells[col]!r} is not True or "
                              f"False")
    return TRUE_TEXT[text]


def row_model(row: Row, header, case: str) -> str:
    """The canonical model name of ``row`` (``neo-Hookean`` or ``Gent``), or the default of
    ``case`` when the file has no ``model`` column; an unknown name or a missing one where
    the case has no default is a :class:`CheckInputError`."""
    default = CHECK_CASES[case][1]
    if "model" not in header or row.cells["model"] == "":
        if default is None:
            raise CheckInputError(f"{row.where}: case {case} needs the column model "
                                  f"(neo-Hookean or Gent, Jm = {GENT_JM:g})")
        return default
    name = MODEL_NAMES.get(row.cells["model"].lower().replace(" ", ""))
    if name is None:
        raise CheckInputError(f"{row.where}, column model: {row.cells['model']!r} is neither "
                              f"neo-Hookean nor Gent")
    return name


def row_text(row: Row, col: str, choices, default=None) -> str:
    """The cell of ``row`` in column ``col``, which must be one of ``choices`` (``default``
    for an empty cell when given); anything else is a :class:`CheckInputError`."""
    value = row.cells.get(col, "")
    if value == "" and default is not None:
        return default
    if value not in choices:
        raise CheckInputError(f"{row.where}, column {col}: {value!r} is not one of "
                              f"{', '.join(choices)}")
    return value


def not_scored(name: str) -> str | None:
    """Why the contract file ``name`` is read by no rule of ``check`` (an entry of
    :data:`NOT_SCORED`, matched by name or by suffix), or ``None`` for a scored file."""
    for key, why in NOT_SCORED.items():
        if name == key or (key.startswith("_") and name.endswith(key)):
            return why
    return None


def results_files(path: Path) -> list[Path]:
    """The CSV files of a folder (regular files only, by name), or ``[path]`` for a file;
    a folder holding more than :data:`MAX_TOTAL_BYTES` of them is refused."""
    if path.is_dir():
        files = sorted(p for p in path.iterdir() if p.suffix.lower() == ".csv" and p.is_file())
        if not files:
            raise CheckInputError(f"{path} holds no CSV file (the results contract: one "
                                  f"<case>.csv per case, docs/check.md)")
        total = sum(_regular_size(f) for f in files if not_scored(f.name) is None)
        if total > MAX_TOTAL_BYTES:
            raise CheckInputError(f"{path}: {len(files)} CSV files of {total / 1024**2:.1f} MB, "
                                  f"above the {MAX_TOTAL_BYTES // 1024**2} MB that check reads "
                                  f"from one folder (docs/check.md); check it in parts")
        return files
    if not path.exists():
        raise FileNotFoundError(2, "No such file or directory", str(path))
    return [path]


def gather(path: Path, cases) -> tuple[dict, list[str]]:
    """``({case: [(header, rows)]}, notes)`` of every results file below ``path``."""
    found: dict[str, list] = {}
    notes, seen = [], []
    for f in results_files(path):
        why = not_scored(f.name)
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

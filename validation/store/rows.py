"""The row files of the studies (``buckling``, ``post-buckling``, ``wrinkling-fe``,
``voltage-control``) and the lock of a command that writes a folder.

* :class:`StudyStore` -- the files of one study: a table with one row per unit of work
  (an alpha x mesh), written last, and detail files with the unit's other rows; every
  file is rewritten atomically in the order of an uninterrupted run, so that a resumed
  study leaves the same files as one that was never interrupted;
* :func:`read_rows` -- a study CSV back as dicts, a damaged row named
  (:class:`DamagedFileError`);
* :class:`KeyedRows` -- a CSV resumed by the keys of its rows (``wrinkling-fe``);
* :func:`command_lock` -- the lock of a command that writes a folder.
"""

from __future__ import annotations

import csv
import io
import json
import math
import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .files import FolderLock, dumps, write_csv_atomic, write_text_atomic

__all__ = ["read_rows", "KeyedRows", "command_lock", "DamagedFileError", "RowFile",
           "StudyStore", "TEXT_COLUMNS"]

#: the columns of the study CSVs that hold text; every other cell is a number
TEXT_COLUMNS = frozenset({"mesh", "class", "physical_class", "branch", "reason", "model",
                          "control", "mode", "note", "case", "run", "loading", "variant",
                          "kind", "stable", "stable_charge"})


def command_lock(out, name: str, what: str) -> FolderLock:
    """The :class:`~.files.FolderLock` ``out/.state/<name>.lock`` (folders created) that a
    command holds while it writes ``what`` into ``out``: a second process writing the same
    into the same folder gets :class:`~.files.LockedError`.

    Parameters
    ----------
    out : path-like
        The output folder.
    name : str
        The lock's name (a case or a command).
    what : str
        What the lock protects, for the message (``"case 'nh-d-e' in out"``).

    Returns
    -------
    FolderLock
    """
    state_root = Path(out) / ".state"
    state_root.mkdir(parents=True, exist_ok=True)
    return FolderLock(state_root / f"{name}.lock", what)


class DamagedFileError(OSError):
    """A complete row of a study CSV that cannot be read back (exit code 3 of the CLI):
    ``filename`` is the file, the message names the row (its line number) and why."""

    def __init__(self, path, line: int, why: str):
        where = f"row {line - 1} (line {line}) " if line > 1 else ""
        super().__init__(None, f"{where}{why}", str(path))


def _text(v) -> str:
    """The cell of a row value: ``""`` for ``None`` and ``nan`` (no value), floats with 10
    significant digits."""
    if v is None:
        return ""
    if isinstance(v, (float, np.floating)):
        return "" if math.isnan(v) else f"{float(v):.10g}"
    return str(v)


def _cells(columns, cells: list[str]) -> list[str]:
    """``cells`` of a row read back, a ``nan`` in a number column as the empty cell that
    :func:`_text` now writes for it (files of earlier versions)."""
    return ["" if c not in TEXT_COLUMNS and t.strip().lower() == "nan" else t
            for c, t in zip(columns, cells)]


def _value(path, line: int, column: str, text: str):
    if column in TEXT_COLUMNS:
        return text
    if text == "":
        return float("nan")
    try:
        return float(text)
    except ValueError:
        raise DamagedFileError(path, line, f"has {text!r} in the number column "
                               f"{column!r}") from None


def _parse(path: Path, text: str) -> tuple[list[str] | None, list[tuple[int, list[str]]], bool]:
    """``(header, [(line, cells)], cut)`` of a CSV's text; ``cut``: its last line had no
    line end (a write cut short) and was left out."""
    cut = bool(text) and not text.endswith("\n")
    if cut:
        text = text[:text.rfind("\n") + 1]
    try:
        rows = list(csv.reader(io.StringIO(text, newline="")))
    except csv.Error as exc:
        raise DamagedFileError(path, 0, f"is not CSV ({exc})") from None
    if not rows:
        return None, [], cut
    return rows[0], [(i + 2, r) for i, r in enumerate(rows[1:])], cut


def _read_text(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8") if path.exists() else ""
    except UnicodeDecodeError as exc:
        raise DamagedFileError(path, 0, f"is not text ({exc.reason})") from None


def read_rows(path: Path) -> list[dict]:
    """The rows of a study CSV (:class:`StudyStore`) as dicts: numbers as floats (an empty
    cell as ``nan``), the :data:`TEXT_COLUMNS` as written; ``[]`` if there is no file.

    Raises
    ------
    DamagedFileError
        A row with another number of cells than the header, or a number column holding
        something else (the file and the row named).
    """
    path = Path(path)
    header, rows, _ = _parse(path, _read_text(path))
    out = []
    for line, r in rows:
        if len(r) != len(header):
            raise DamagedFileError(path, line, f"has {len(r)} cells, the header {len(header)}")
        out.append({c: _value(path, line, c, t) for c, t in zip(header, r)})
    return out


@dataclass(frozen=True)
class RowFile:
    """One CSV of a study: its file name in ``out``, its columns and the columns that key
    a row to its unit of work (e.g. ``("alpha", "mesh")``)."""

    name: str
    columns: tuple
    key: tuple

    def key_of(self, row) -> tuple:
        """The key of ``row`` (a dict of values or the list of its cells) as text."""
        if isinstance(row, dict):
            return tuple(_text(row[c]) for c in self.key)
        return tuple(row[self.columns.index(c)] for c in self.key)


class StudyStore:
    """The files of one study in ``out``, held under its lock: resumed unit by unit.

    A unit of work (one alpha x mesh) ends with one row of the ``table`` and any number
    of rows in each of the ``details`` files.  :meth:`commit` rewrites the detail files,
    then the table, each atomically, all in the order of ``plan`` (keys of earlier runs
    not in ``plan`` first, as found): the table is the record of what is done, and
    rows of the detail files whose unit is not in it (an interrupted commit) are dropped
    when the store is opened.  So a study interrupted at any moment and rerun leaves
    the files of an uninterrupted run (timing columns aside).

    Parameters
    ----------
    out : path-like
        The output folder (created).
    name : str
        The study's name: its lock ``.state/<name>.lock`` and settings ``.state/<name>.json``.
    settings : dict
        What the results depend on besides their keys (e.g. the charge step); a folder
        whose saved settings differ is discarded, with a note, and recomputed.
    table : RowFile
        One row per unit, written last.
    details : tuple of RowFile
        The units' other rows.
    derived : tuple of str
        Files and folders in ``out`` drawn from the rows (figures, mode shapes): removed
        with the rows when these are discarded.
    note : callable
        ``note(message)``: one line for each repair (rows dropped, results discarded).
    counts : dict, optional
        ``{detail file name: table column}``: the table column that holds how many rows
        the unit has in that detail file; a unit with another number of rows there (a
        file cut short or edited) is dropped and recomputed, with a note.
    force : bool
        Discard the results present (and the ``derived`` files) without reading them.

    Raises
    ------
    DamagedFileError
        On opening: a complete row that cannot be read back (names the file and row).
    LockedError
        On opening: another process writes this study into ``out``.

    Examples
    --------
    >>> import tempfile
    >>> out = tempfile.mkdtemp()
    >>> t = RowFile("t.csv", ("alpha", "mesh", "D0_b"), ("alpha", "mesh"))
    >>> d = RowFile("d.csv", ("alpha", "mesh", "D0"), ("alpha", "mesh"))
    >>> with StudyStore(out, "demo", {"D0_step": 0.5}, t, (d,), plan=[(1.0, "2x1x1")],
    ...                 note=print) as st:
    ...     st.commit({"alpha": 1.0, "mesh": "2x1x1", "D0_b": 0.25},
    ...               {"d.csv": [{"alpha": 1.0, "mesh": "2x1x1", "D0": 0.5}]})
    ...     st.done((1.0, "2x1x1"))
    True
    >>> notes = []
    >>> with StudyStore(out, "demo", {"D0_step": 0.25}, t, (d,), plan=[],
    ...                 note=notes.append) as st:
    ...     st.done((1.0, "2x1x1"))
    False
    >>> "results are discarded and recomputed" in notes[0]
    True
    """

    def __init__(self, out, name: str, settings: dict, table: RowFile,
                 details: tuple = (), *, plan, derived: tuple = (), note=None,
                 counts: dict | None = None, force: bool = False):
        self.out, self.name, self.settings = Path(out), name, settings
        self.counts, self.force = dict(counts or {}), force
        self.table, self.details, self.derived = table, tuple(details), tuple(derived)
        self.plan = [tuple(_text(v) for v in k) for k in plan]
        self.note = note or (lambda msg: None)
        self._lock = None

    # -- opening ---------------------------------------------------------------------
    def __enter__(self) -> "StudyStore":
        self._lock = command_lock(self.out, self.name, f"the {self.name} study in {self.out}")
        self._lock.__enter__()
        try:
            self._open()
        except BaseException:
            self._lock.__exit__(None, None, None)
            raise
        return self

    def __exit__(self, *exc) -> None:
        self._lock.__exit__(*exc)

    def _files(self):
        return (self.table,) + self.details

    def _open(self) -> None:
        for f in self._files():                     # temporaries of a killed write
            path = self.out / f.name
            for tmp in path.parent.glob(f".{path.name}.*.tmp"):
                tmp.unlink()
        man = self.out / ".state" / f"{self.name}.json"
        want = json.loads(dumps(self.settings))
        present = [f.name for f in self._files() if (self.out / f.name).exists()]
        why = ""
        if self.force:
            self._discard()
        elif man.exists():
            try:
                saved = json.loads(man.read_text())
            except (ValueError, UnicodeDecodeError):
                saved, why = None, f"{man} is unreadable"
            if saved is not None and saved != want:
                why = (f"the settings of {', '.join(present) or 'its results'} in {self.out} "
                       f"({dumps(saved)}) differ from these ({dumps(want)})")
        elif present:
            why = f"{', '.join(present)} in {self.out} have no saved settings ({man})"
        if not why and not self.force:
            why = self._read()
        if why:
            if present:
                self.note(f"{why}; its results are discarded and recomputed")
            self._discard()
        write_text_atomic(man, dumps(self.settings))

    def _read(self) -> str:
        """Read the files into memory; why they are discarded as a whole (empty: kept)."""
        self.cells: dict[str, dict[tuple, list]] = {}
        self.order: list[tuple] = []
        repaired, cut_files = False, set()
        for f in self._files():
            path = self.out / f.name
            header, rows, cut = _parse(path, _read_text(path))
            if header is not None and header != list(f.columns):
                return f"{path} has other columns than {', '.join(f.columns)}"
            if cut:
                self.note(f"{path}: its last row is incomplete (no line end); dropped")
                repaired = True
                cut_files.add(f.name)
            by: dict[tuple, list] = {}
            for line, r in rows:
                if len(r) != len(f.columns):
                    raise DamagedFileError(path, line, f"has {len(r)} cells, the header "
                                           f"{len(f.columns)}")
                for c, t in zip(f.columns, r):
                    _value(path, line, c, t)
                r = _cells(f.columns, r)
                k = f.key_of(r)
                if f is self.table and k in by:
                    self.note(f"{path}: row {line} repeats the unit {', '.join(k)}; dropped")
                    repaired = True
                    continue
                by.setdefault(k, []).append(r)
                if f is self.table:
                    self.order.append(k)
            self.cells[f.name] = by
        table, recounted = self.cells[self.table.name], set()
        for name, column in self.counts.items():    # units missing rows of a detail file
            i = self.table.columns.index(column)
            short = [k for k in self.order
                     if _value(self.out / self.table.name, 0, column, table[k][0][i])
                     != len(self.cells[name].get(k, []))]
            if short:
                if name not in cut_files:       # the cut row's note says it
                    self.note(f"{self.out / name}: the rows of {len(short)} unit(s) are "
                              f"missing or extra ({'; '.join(', '.join(k) for k in short)}); "
                              f"recomputed")
                for k in short:
                    del table[k]
                recounted.update(short)
                self.order = [k for k in self.order if k in table]
                repaired = True
        done = set(self.order)
        for f in self.details:
            extra = [k for k in self.cells[f.name] if k not in done]
            if extra:
                rows = {k: self.cells[f.name].pop(k) for k in extra}
                unfinished = [k for k in extra if k not in recounted]   # others: noted
                if unfinished and f.name not in cut_files:
                    self.note(f"{self.out / f.name}: "
                              f"{sum(len(rows[k]) for k in unfinished)} row(s) of "
                              f"{len(unfinished)} unfinished unit(s) dropped")
                repaired = True
        if repaired:
            self._write()
        return ""

    def _discard(self) -> None:
        for name in [f.name for f in self._files()] + list(self.derived):
            p = self.out / name
            if p.is_dir() and not p.is_symlink():
                shutil.rmtree(p)
            elif p.exists() or p.is_symlink():
                p.unlink()
        self.cells = {f.name: {} for f in self._files()}
        self.order = []

    # -- use -------------------------------------------------------------------------
    def kept(self) -> int:
        """How many units of ``plan`` are in the table (kept from an earlier run)."""
        return sum(k in self.cells[self.table.name] for k in self.plan)

    def done(self, key) -> bool:
        """Whether the unit ``key`` (values of the table's key columns) is in the table."""
        return tuple(_text(v) for v in key) in self.cells[self.table.name]

    def _keys(self) -> list[tuple]:
        planned = set(self.plan)
        have = self.cells[self.table.name]
        return ([k for k in self.order if k not in planned]
                + [k for k in self.plan if k in have])

    def _write(self) -> None:
        keys = self._keys()
        for f in self.details + (self.table,):          # the table last: it commits
            by = self.cells[f.name]
            rows = [r for k in keys for r in by.get(k, [])]
            if rows or (self.out / f.name).exists():
                write_csv_atomic(self.out / f.name, list(f.columns), rows)

    def commit(self, row: dict, details: dict) -> None:
        """Record one finished unit: its table ``row`` and its rows in each detail file
        (``{file name: [dict, ...]}``), all files rewritten (the table last)."""
        k = self.table.key_of(row)
        for f in self.details:
            self.cells[f.name][k] = [[_text(r[c]) for c in f.columns]
                                     for r in details.get(f.name, [])]
        if k not in self.cells[self.table.name]:
            self.order.append(k)
        self.cells[self.table.name][k] = [[_text(row[c]) for c in self.table.columns]]
        self._write()

    def rows(self, name: str | None = None) -> list[dict]:
        """The rows of the table (or of the detail file ``name``) as dicts, in file order."""
        path = self.out / (name or self.table.name)
        return read_rows(path)


def _cell(text: str):
    """A CSV cell back as the row value: ``None`` (empty), a float, or the text."""
    if text == "":
        return None
    try:
        return float(text)
    except ValueError:
        return text


class KeyedRows:
    """Rows of one CSV, kept by key (the first ``nkey`` cells as written), rewritten
    atomically after every new row.  Rows of an existing file with the same header are
    reused (a ``nan`` cell of an earlier version as an empty one); a last row cut short
    (no line end) and rows with another number of cells are dropped, to be recomputed,
    and a file with other columns is ignored (and replaced), each with a ``note``.

    Parameters
    ----------
    path : Path or None
        The CSV (``None``: rows kept in memory only).
    columns : list of str
        Its header.
    nkey : int
        The first ``nkey`` cells of a row are its key.
    fmt : callable
        ``fmt(value) -> str``, the text of a cell.
    note : callable, optional
        ``note(message)``: one line naming the file for each repair (the messages of
        :class:`StudyStore`).

    Examples
    --------
    >>> import tempfile
    >>> path = Path(tempfile.mkdtemp()) / "rows.csv"
    >>> _ = path.write_text("kh,D0\\n0.5,1.25\\n2,3.")         # the last row cut short
    >>> rows = KeyedRows(path, ["kh", "D0"], 1, str, note=print)  # doctest: +ELLIPSIS
    /.../rows.csv: its last row is incomplete (no line end); dropped
    >>> rows.get((0.5,), lambda: [0.5, 9.0]), rows.get((2,), lambda: [2, 3.5])
    ([0.5, 1.25], [2.0, 3.5])
    """

    def __init__(self, path: Path | None, columns: list[str], nkey: int, fmt, note=None):
        self.path, self.columns, self.nkey, self.fmt = path, columns, nkey, fmt
        self.note = note or (lambda msg: None)
        self.known: dict[tuple, list[str]] = {}
        if path is not None and path.is_file():
            self.known = self._read(Path(path))
        self.rows: list[list[str]] = []

    def _read(self, path: Path) -> dict[tuple, list[str]]:
        try:
            header, rows, cut = _parse(path, _read_text(path))
        except DamagedFileError as exc:
            self.note(f"{path}: {exc.strerror}; its rows are recomputed")
            return {}
        if header is None:
            return {}
        if header != self.columns:
            self.note(f"{path} has other columns than {', '.join(self.columns)}; its rows "
                      f"are recomputed")
            return {}
        if cut:
            self.note(f"{path}: its last row is incomplete (no line end); dropped")
        known = {}
        for line, r in rows:
            if len(r) != len(self.columns):
                self.note(f"{path}: row {line - 1} (line {line}) has {len(r)} cells, the "
                          f"header {len(self.columns)}; dropped")
                continue
            known[tuple(r[:self.nkey])] = ["" if c.strip().lower() == "nan" else c
                                           for c in r]     # no value: an empty cell
        return known

    def get(self, key: tuple, compute) -> list:
        """The row of ``key`` (cells formatted as the CSV's): reused, or computed and
        written."""
        k = tuple(self.fmt(v) for v in key)
        row = self.known.get(k)
        if row is None:
            row = [self.fmt(v) for v in compute()]
            self.known[k] = row
            self.rows.append(row)
            if self.path is not None:
                write_csv_atomic(self.path, self.columns, self.rows)
        else:
            self.rows.append(row)
        return [_cell(c) for c in row]

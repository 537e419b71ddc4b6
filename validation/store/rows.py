"""The row files of the studies (``buckling``, ``post-buckling``, ``wrinkling-fe``,
``voltage-control``) and the lock of a command that writes a folder.

* :class:`StudyStore` -- the files of one study: a table with one row per unit of work
  (an alpha x mesh), written last, and detail files with the unit's other rows; every
  file is rewritten atomically in the order of an uninterrupted run, so that a resumed
  study leaves the same files as one that was never interrupted;
* :func:`read_rows` -- a study CSV back as dicts, a damaged row named
  (:class:`DamagedFileError`);
* :func:`command_lock` -- the lock of a command that writes a folder.
"""

from __future__ import annotations

import csv
import io
import json
import shutil
from pathlib import Path

from ..data.spec import TEXT_COLUMNS, TableSpec
from .files import (FolderLock, aside_path, csv_line, dumps, keep_aside, regular_file,
                    write_csv_atomic, write_text_atomic)

__all__ = ["read_rows", "command_lock", "DamagedFileError", "StudyStore"]


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


class LockedWriter:
    """What every writer of a folder's rows does on entering and leaving: take its
    :func:`command_lock` (``_lock_args()``: the folder, the lock's name and what it
    protects), then open its files (``_open()``), releasing the lock if that fails; the
    lock is released on leaving.  :class:`StudyStore` and
    :class:`~.tables.TableWriter` are the two."""

    _lock = None

    def _lock_args(self) -> tuple:
        raise NotImplementedError

    def _open(self) -> None:
        raise NotImplementedError

    def __enter__(self):
        self._lock = command_lock(*self._lock_args())
        self._lock.__enter__()
        try:
            self._open()
        except BaseException:
            self._lock.__exit__(None, None, None)
            raise
        return self

    def __exit__(self, *exc) -> None:
        self._lock.__exit__(*exc)


class DamagedFileError(OSError):
    """A complete row of a study CSV that cannot be read back (exit code 3 of the CLI):
    ``filename`` is the file, the message names the row (its line number) and why."""

    def __init__(self, path, line: int, why: str):
        where = f"row {line - 1} (line {line}) " if line > 1 else ""
        super().__init__(None, f"{where}{why}", str(path))


def _cells(spec: TableSpec, cells: list[str]) -> list[str]:
    """``cells`` of a row read back, a ``nan`` in a number column as the empty cell that
    :meth:`TableSpec.cell` now writes for it (files of earlier versions)."""
    return ["" if c not in spec.text and t.strip().lower() == "nan" else t
            for c, t in zip(spec.columns, cells)]


def _value(path, line: int, column: str, text: str, text_columns=TEXT_COLUMNS):
    if column in text_columns:
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


class StudyStore(LockedWriter):
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
        whose saved settings differ is discarded, with a note, and recomputed, its rows
        first kept aside in ``<file>.damaged`` (:func:`~.files.keep_aside`).
    table : TableSpec
        One row per unit, written last (a plain CSV: :meth:`TableSpec.plain`).
    details : tuple of TableSpec
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
    >>> t = TableSpec.plain("t.csv", ("alpha", "mesh", "D0_b"), ("alpha", "mesh"))
    >>> d = TableSpec.plain("d.csv", ("alpha", "mesh", "D0"), ("alpha", "mesh"))
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

    def __init__(self, out, name: str, settings: dict, table: TableSpec,
                 details: tuple = (), *, plan, derived: tuple = (), note=None,
                 counts: dict | None = None, force: bool = False):
        self.out, self.name, self.settings = Path(out), name, settings
        self.counts, self.force = dict(counts or {}), force
        self.table, self.details, self.derived = table, tuple(details), tuple(derived)
        self.plan = [self._key(k) for k in plan]
        self.note = note or (lambda msg: None)
        self._lock = None

    # -- opening ---------------------------------------------------------------------
    def _key(self, values) -> tuple:
        """The key of a unit given by the values of the table's key columns."""
        return self.table.key_of(dict(zip(self.table.key, values)))

    def _lock_args(self) -> tuple:
        return self.out, self.name, f"the {self.name} study in {self.out}"

    def _files(self):
        return (self.table,) + self.details

    def _owned(self) -> list[Path]:
        """The files this study writes in ``out`` (its CSVs, its derived files); each must
        be a regular file or absent, else the study stops before touching anything."""
        names = [f.file for f in self._files()] + [d for d in self.derived
                                                    if Path(d).suffix]
        return [regular_file(self.out / n, f"a file of the {self.name} study")
                for n in names]

    def _open(self) -> None:
        self._owned()
        for f in self._files():                     # temporaries of a killed write
            path = self.out / f.file
            for tmp in path.parent.glob(f".{path.name}.*.tmp"):
                tmp.unlink()
        man = self.out / ".state" / f"{self.name}.json"
        want = json.loads(dumps(self.settings))
        present = [f.file for f in self._files() if (self.out / f.file).exists()]
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
                kept = self._keep_aside_all(why)
                self.note(f"{why}; its results are discarded and recomputed"
                          + (f" (their rows kept in {', '.join(kept)})" if kept else ""))
            self._discard()
        write_text_atomic(man, dumps(self.settings))

    def _read(self) -> str:
        """Read the files into memory; why they are discarded as a whole (empty: kept).

        A finished row left out (cut short, repeated, of a unit whose rows are
        incomplete) is kept aside (:func:`~.files.keep_aside`) before the file is
        rewritten; the detail rows of a unit not in the table (a commit stopped between
        its writes) are not a result and are dropped."""
        self.cells: dict[str, dict[tuple, list]] = {}
        self.order: list[tuple] = []
        repaired, cut_files = False, set()
        aside: dict[str, list] = {}
        lines: dict[str, dict[tuple, list[int]]] = {}
        for f in self._files():
            path = self.out / f.file
            text = _read_text(path)
            header, rows, cut = _parse(path, text)
            if header is not None and header != list(f.columns):
                return f"{path} has other columns than {', '.join(f.columns)}"
            if cut:
                line = text.count("\n") + 1
                self.note(f"{path}: its last row is incomplete (no line end); kept aside "
                          f"in {aside_path(path).name}")
                aside.setdefault(f.file, []).append(
                    (line, text[text.rfind("\n") + 1:], "incomplete (no line end)"))
                repaired = True
                cut_files.add(f.file)
            by: dict[tuple, list] = {}
            at: dict[tuple, list[int]] = {}
            for line, r in rows:
                if len(r) != len(f.columns):
                    raise DamagedFileError(path, line, f"has {len(r)} cells, the header "
                                           f"{len(f.columns)}")
                for c, t in zip(f.columns, r):
                    _value(path, line, c, t, f.text)
                r = _cells(f, r)
                k = f.key_of(r)
                if f is self.table and k in by:
                    self.note(f"{path}: row {line} repeats the unit {', '.join(k)}; kept "
                              f"aside in {aside_path(path).name}")
                    aside.setdefault(f.file, []).append(
                        (line, csv_line(r).rstrip("\n"), "repeats the unit"))
                    repaired = True
                    continue
                by.setdefault(k, []).append(r)
                at.setdefault(k, []).append(line)
                if f is self.table:
                    self.order.append(k)
            self.cells[f.file] = by
            lines[f.file] = at

        def put_aside(name, k, why):
            aside.setdefault(name, []).extend(
                (n, csv_line(r).rstrip("\n"), why)
                for n, r in zip(lines[name].get(k, []), self.cells[name].get(k, [])))

        table, recounted = self.cells[self.table.file], set()
        for name, column in self.counts.items():    # units missing rows of a detail file
            i = self.table.columns.index(column)
            short = [k for k in self.order
                     if _value(self.out / self.table.file, 0, column, table[k][0][i],
                            self.table.text)
                     != len(self.cells[name].get(k, []))]
            if short:
                if name not in cut_files:       # the cut row's note says it
                    self.note(f"{self.out / name}: the rows of {len(short)} unit(s) are "
                              f"missing or extra ({'; '.join(', '.join(k) for k in short)}); "
                              f"recomputed")
                for k in short:
                    put_aside(self.table.file, k, f"its unit has another number of rows "
                                                  f"in {name} than {column}")
                    del table[k]
                recounted.update(short)
                self.order = [k for k in self.order if k in table]
                repaired = True
        done = set(self.order)
        for f in self.details:
            extra = [k for k in self.cells[f.file] if k not in done]
            if extra:        # an interrupted commit: not a result (the table row is)
                for k in recounted.intersection(extra):
                    put_aside(f.file, k, "a row of a unit whose rows are incomplete")
                rows = {k: self.cells[f.file].pop(k) for k in extra}
                unfinished = [k for k in extra if k not in recounted]   # others: noted
                if unfinished and f.file not in cut_files:
                    self.note(f"{self.out / f.file}: "
                              f"{sum(len(rows[k]) for k in unfinished)} row(s) of "
                              f"{len(unfinished)} unfinished unit(s) dropped")
                repaired = True
        if repaired:
            for name, items in aside.items():   # before the rows leave their file
                keep_aside(self.out / name, items)
            self._write()
        return ""

    def _keep_aside_all(self, why: str) -> list[str]:
        """Every row of the study's CSVs, kept aside (:func:`~.files.keep_aside`) before
        they are discarded for ``why`` (other settings, an unreadable file); the names of
        the side files written."""
        kept = []
        for f in self._files():
            path = self.out / f.file
            if not path.exists():
                continue
            text = path.read_text(encoding="utf-8", errors="replace")
            rows = [(i + 1, ln, why) for i, ln in enumerate(text.splitlines()) if i > 0 and ln]
            if rows:
                kept.append(keep_aside(path, rows).name)
        return kept

    def _discard(self) -> None:
        """Remove the study's files (checked regular by :meth:`_owned`) and its derived
        folders (``.modes``: folders this study makes, named with a leading dot)."""
        for p in self._owned():
            if p.exists() or p.is_symlink():
                p.unlink()
        for name in self.derived:
            p = self.out / name
            if not Path(name).suffix and p.is_dir() and not p.is_symlink():
                shutil.rmtree(p)
        self.cells = {f.file: {} for f in self._files()}
        self.order = []

    # -- use -------------------------------------------------------------------------
    def kept(self) -> int:
        """How many units of ``plan`` are in the table (kept from an earlier run)."""
        return sum(k in self.cells[self.table.file] for k in self.plan)

    def done(self, key) -> bool:
        """Whether the unit ``key`` (values of the table's key columns) is in the table."""
        return self._key(key) in self.cells[self.table.file]

    def _keys(self) -> list[tuple]:
        planned = set(self.plan)
        have = self.cells[self.table.file]
        return ([k for k in self.order if k not in planned]
                + [k for k in self.plan if k in have])

    def _write(self) -> None:
        keys = self._keys()
        for f in self.details + (self.table,):          # the table last: it commits
            by = self.cells[f.file]
            rows = [r for k in keys for r in by.get(k, [])]
            if rows or (self.out / f.file).exists():
                write_csv_atomic(self.out / f.file, list(f.columns), rows)

    def commit(self, row: dict, details: dict) -> None:
        """Record one finished unit: its table ``row`` and its rows in each detail file
        (``{file name: [dict, ...]}``), all files rewritten (the table last)."""
        k = self.table.key_of(row)
        for f in self.details:
            self.cells[f.file][k] = [[f.cell(r[c]) for c in f.columns]
                                     for r in details.get(f.file, [])]
        if k not in self.cells[self.table.file]:
            self.order.append(k)
        self.cells[self.table.file][k] = [[self.table.cell(row[c]) for c in self.table.columns]]
        self._write()

    def rows(self, name: str | None = None) -> list[dict]:
        """The rows of the table (or of the detail file ``name``: its :attr:`TableSpec.file`)
        as dicts, in file order."""
        path = self.out / (name or self.table.file)
        return read_rows(path)

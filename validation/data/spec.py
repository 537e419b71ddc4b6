"""What a measured table holds (:class:`TableSpec`: a clamp-zone table, or a study's plain
CSV by :meth:`TableSpec.plain`) and reading a clamp-zone table back with its damaged rows
named (:func:`read_table`); :mod:`validation.store.tables` writes one under its lock.

A clamp-zone table is a CSV whose first line declares which of the study's tables it is
(``# clamp-zone table: <name>``), then ``#`` lines saying what it holds, the header and
one row per unit (or per state, or per class: :attr:`TableSpec.key`).  A file that does
not declare the same table, or whose header has other columns, is another table and is
never rewritten.  A row that cannot be read back (cut short by a kill, another number of
cells, text in a number column, an empty key cell) or that repeats a key is named in a
note (file and line) and left out; the writer keeps it aside in ``<table>.damaged`` before
the table is rewritten, and its unit is computed again if the command runs it; the file
is rewritten atomically (temporary file, ``fsync``, ``os.replace``) with each new unit's
rows, under a lock that refuses a second writer and names the holder.
"""

from __future__ import annotations

import csv
import errno
import math
import stat
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["TableSpec", "ForeignTableError", "read_table", "DECLARATION", "TEXT_COLUMNS"]

#: the columns of the studies' plain CSVs that hold text (:meth:`TableSpec.plain`); every
#: other cell is a number
TEXT_COLUMNS = frozenset({"mesh", "class", "physical_class", "branch", "reason", "model",
                          "control", "mode", "note", "case", "run", "loading", "variant",
                          "kind", "stable", "stable_charge"})

#: the first line of every table of the study: ``DECLARATION.format(name=...)``
DECLARATION = "# clamp-zone table: {name}"


class ForeignTableError(ValueError):
    """A file that is not the table asked for (exit code 2 of the CLI); the message names
    it and what it is."""


@dataclass(frozen=True)
class TableSpec:
    """One measured table: its file, its columns, the columns that key a row to its unit
    of work, and how it is written.

    Two kinds share it: the clamp-zone study's declared tables (:data:`~validation.data.
    registry.TABLES`: a declaration line and ``#`` lines, floats to 6 digits, written by
    :class:`~validation.store.tables.TableWriter`) and the other studies' plain CSVs
    (:meth:`plain`: the header first, floats to 10 digits, written with their detail files
    by :class:`~validation.store.rows.StudyStore`).

    Attributes
    ----------
    name
        The table's name (``"units"``), declared in its first line and used by
        :func:`validation.data.registry.load`.
    file
        Its file name, in ``--out`` and among the shipped data (``"clamp_units.csv"``).
    columns
        Its header.
    key
        The columns that name a row's unit of work: one row per key, unless ``multi``.
    about
        The ``#`` lines after the declaration (what the columns mean, who writes them).
    text
        The columns that hold text; every other cell is a number or empty.
    multi
        Several rows share a key (written together: the negative modes of one state).
    added
        Columns added to the table after its first release, each with the value the rows
        of a file written before it take (pairs: ``(("pressure", "Q1"),)``): such a file
        is read with that value, and its next write has the whole header.
    declared
        The file begins with :attr:`declaration` and the :attr:`about` lines (else with
        its header).
    digits
        Significant digits of a float cell.
    former
        The file's name in earlier releases (``"edge_counts.csv"``), read in a folder that
        has no file of the present name; the table's writer renames it (kept for one
        release: :data:`~validation.data.registry.FORMER_UNTIL`).

    Examples
    --------
    >>> t = TableSpec.plain("buckling.csv", ("alpha", "mesh", "D0_b"), ("alpha", "mesh"))
    >>> t.name, t.key_of({"alpha": 1, "mesh": "2x1x1", "D0_b": 0.5})
    ('buckling', ('1', '2x1x1'))
    >>> t.cell(2 / 3), TableSpec("demo", "demo.csv", ("x",), ("x",), "").cell(2 / 3)
    ('0.6666666667', '0.666667')
    """

    name: str
    file: str
    columns: tuple
    key: tuple
    about: str
    text: frozenset = frozenset({"mesh", "formulation", "class", "solver", "date",
                                 "scan_counts", "note", "command", "pressure", "kind",
                                 "first_class", "first_kind", "physical_class"})
    multi: bool = False
    added: tuple = ()
    declared: bool = True
    digits: int = 6
    former: str = ""

    @classmethod
    def plain(cls, file: str, columns, key, *, text=TEXT_COLUMNS) -> "TableSpec":
        """A study's plain CSV ``file`` (its name: the file's stem): the header first, no
        declaration, floats to 10 digits, text in the columns ``text``."""
        return cls(Path(file).stem, file, tuple(columns), tuple(key), "",
                   text=frozenset(text), declared=False, digits=10)

    @property
    def declaration(self) -> str:
        """The table's first line."""
        return DECLARATION.format(name=self.name)

    def cell(self, v) -> str:
        """A row value as its cell: ``None`` and ``nan`` as the empty cell, floats to
        :attr:`digits` significant digits, anything else as ``str``."""
        if v is None:
            return ""
        if isinstance(v, (float, np.floating)):
            return "" if math.isnan(v) else f"{float(v):.{self.digits}g}"
        return str(v)

    def key_of(self, row) -> tuple:
        """The key of ``row`` (a dict of text or numbers, or the list of a row's cells) as
        text: numbers to 10 digits, an empty cell as empty."""
        if not isinstance(row, dict):
            row = dict(zip(self.columns, row))
        return tuple(str(row[c]) if c in self.text else _key_number(row[c])
                     for c in self.key)


def _key_number(v) -> str:
    if isinstance(v, str) and v.strip() == "":
        return ""
    v = float(v)
    return "" if math.isnan(v) else f"{v:.10g}"


def _bad_cell(spec: TableSpec, row: dict) -> str:
    for c in spec.key:
        if row[c].strip() == "":
            return f"has an empty key cell {c!r}"
    for c in spec.columns:
        t = row[c]
        if c in spec.text or t == "":
            continue
        try:
            float(t)
        except ValueError:
            return f"has {t!r} in the number column {c!r}"
    return ""


def read_table(path, spec: TableSpec, *, note=None, on_damaged=None) -> list[dict]:
    """The rows of a table, as dicts of the cells' text; ``[]`` if there is no file.

    Parameters
    ----------
    path : path-like
        The CSV.
    spec : TableSpec
        The table it must be.
    note : callable, optional
        ``note(message)``: one line for each row left out (cut short, another number of
        cells, text in a number column, an empty key cell, a repeated key), naming the file
        and the line.
    on_damaged : callable, optional
        ``on_damaged(line number, text, why)`` for each row left out, instead of ``note``
        (the writer keeps them aside: :class:`~validation.store.tables.TableWriter`).

    Raises
    ------
    OSError
        ``path`` is a folder, a FIFO or a device (exit code 3 of the CLI).
    ForeignTableError
        ``path`` does not declare ``spec``'s table, or has other columns.
    """
    path = Path(path)
    note = note or (lambda msg: None)
    if on_damaged is None:
        def on_damaged(line, text, why):
            note(f"{path}: line {line} {why}; left out of what is read")
    try:
        mode = path.stat().st_mode
    except FileNotFoundError:
        return []
    if not stat.S_ISREG(mode):
        kind = "a folder" if stat.S_ISDIR(mode) else "not a regular file"
        raise OSError(errno.EINVAL, f"is {kind}, not the clamp-zone {spec.name} table; it "
                      f"is left as it is (choose another --out or move it)", str(path))
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise ForeignTableError(f"{path} is not text, not the clamp-zone {spec.name} "
                                f"table") from None
    if not text:
        return []
    first = text.split("\n", 1)[0].strip()
    if first != spec.declaration:
        what = (f"it declares {first.lstrip('# ')!r}" if first.startswith(DECLARATION[:20])
                else "it declares no clamp-zone table")
        raise ForeignTableError(f"{path} is not the clamp-zone {spec.name} table ({what}); "
                                f"choose another --out")
    lines = text.split("\n")
    cut = not text.endswith("\n")
    body = [(i + 1, ln) for i, ln in enumerate(lines[:-1] if not cut else lines)
            if ln and not ln.startswith("#")]
    if cut and body:
        on_damaged(*body[-1], "is incomplete (no line end)")
        body = body[:-1]
    if not body:
        return []
    header = next(csv.reader([body[0][1]]))
    old = dict(spec.added)              # a file written before the added columns
    if tuple(header) != tuple(c for c in spec.columns if c not in old):
        old = {}
    if not old and tuple(header) != tuple(spec.columns):
        raise ForeignTableError(f"{path} has other columns than the clamp-zone {spec.name} "
                                f"table ({len(header)} against {len(spec.columns)}); choose "
                                f"another --out")
    out, seen = [], set()
    for line, ln in body[1:]:
        cells = next(csv.reader([ln]), [])
        why = ""
        if len(cells) != len(header):
            why = f"has {len(cells)} cells, the header {len(header)}"
        else:
            row = {**old, **dict(zip(header, cells))}
            row = {c: row[c] for c in spec.columns}
            why = _bad_cell(spec, row)
            if not why and not spec.multi:
                k = spec.key_of(row)
                if k in seen:
                    why = "repeats the key " + ", ".join(k)
                seen.add(k)
        if why:
            on_damaged(line, ln, why)
            continue
        out.append(row)
    return out

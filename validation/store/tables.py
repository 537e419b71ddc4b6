"""Writing a measured table under its lock (:class:`TableWriter`): a second writer is
refused and named, damaged rows are kept aside and recomputed, every write is atomic
(temporary file, ``fsync``, ``os.replace``).  What a table holds and how it is read back:
:mod:`validation.data.spec`; the tables: :data:`validation.data.registry.TABLES`.
"""

from __future__ import annotations

import csv
import io
import os
from pathlib import Path

from ..data.spec import TableSpec, read_table
from .files import aside_path, csv_line, keep_aside, regular_file, write_text_atomic
from .rows import LockedWriter

__all__ = ["TableWriter"]


class TableWriter(LockedWriter):
    """A table held for writing: its lock taken, its rows read back.

    Parameters
    ----------
    path : path-like
        The CSV (its folder is created).
    spec : TableSpec
        The table.
    note : callable, optional
        ``note(message)`` for each row left out (:func:`read_table`).

    Raises
    ------
    LockedError
        On entering: another process writes this table (a ``ValueError``, the message
        names its pid and command line).
    ForeignTableError
        On entering: ``path`` is another table.

    Examples
    --------
    >>> import tempfile
    >>> spec = TableSpec("demo", "demo.csv", ("alpha", "mesh", "D0_b"), ("alpha", "mesh"),
    ...                  "# a demonstration\\n")
    >>> path = Path(tempfile.mkdtemp()) / "demo.csv"
    >>> with TableWriter(path, spec) as t:
    ...     t.add([{"alpha": 1.0, "mesh": "2x1x1", "D0_b": 3.14159265}])
    ...     t.done({"alpha": "1", "mesh": "2x1x1"})
    True
    >>> print(path.read_text(), end="")
    # clamp-zone table: demo
    # a demonstration
    alpha,mesh,D0_b
    1,2x1x1,3.14159
    """

    def __init__(self, path, spec: TableSpec, *, note=None):
        if not spec.declared:
            raise ValueError(f"spec must be a declared table (a plain CSV is written by "
                             f"StudyStore), got {spec.file!r}")
        self.path, self.spec, self.note = Path(path), spec, note
        self._lock = None
        self.rows: list[dict] = []
        self.damaged: list[tuple] = []

    def _lock_args(self) -> tuple:
        return (self.path.parent, self.path.name,
                f"the clamp-zone {self.spec.name} table {self.path}")

    def _open(self) -> None:
        for tmp in self.path.parent.glob(f".{self.path.name}.*.tmp"):     # a killed write
            tmp.unlink()
        regular_file(self.path, f"the clamp-zone {self.spec.name} table")
        former = self.path.with_name(self.spec.former) if self.spec.former else None
        if former is not None and not self.path.exists() and former.is_file():
            read_table(former, self.spec)           # another table is refused, untouched
            os.replace(former, self.path)
            if self.note is not None:
                self.note(f"{former} renamed {self.path.name}, the table's file from "
                          f"this release on")
        self.damaged = []
        self.rows = read_table(self.path, self.spec, on_damaged=self._damaged)

    def _damaged(self, line: int, text: str, why: str) -> None:
        """A row :func:`read_table` leaves out: named now, kept aside at the next write."""
        if self.note is not None:
            self.note(f"{self.path}: line {line} {why}; left out, moved to "
                      f"{aside_path(self.path).name} when the table is next written; its "
                      f"unit is computed again if this command runs it")
        self.damaged.append((line, text, why))

    def done(self, row: dict) -> bool:
        """Whether the table holds a row with the key of ``row``."""
        return bool(self.find(row))

    def find(self, row: dict) -> list[dict]:
        """The rows of the table with the key of ``row``."""
        k = self.spec.key_of(row)
        return [r for r in self.rows if self.spec.key_of(r) == k]

    def add(self, rows, *, replace=()) -> None:
        """Append ``rows`` (dicts; each value as :meth:`TableSpec.cell` writes it) and
        rewrite the table atomically.  The rows read back as damaged are first kept aside
        (:func:`validation.store.keep_aside`), once; so are the rows of ``replace`` (rows
        of this table computed with other settings) that have the key of a new row: the
        new row replaces them."""
        new = [{c: self.spec.cell(r.get(c, "")) for c in self.spec.columns} for r in rows]
        keys = {self.spec.key_of(r) for r in new} if replace else set()
        old = [r for r in self.rows if any(r is x for x in replace)
               and self.spec.key_of(r) in keys]
        if self.damaged or old:
            keep_aside(self.path, self.damaged + [
                (None, csv_line([r[c] for c in self.spec.columns]).rstrip("\n"),
                 "computed again with other settings") for r in old])
            self.damaged = []
        self.rows = [r for r in self.rows if not any(r is x for x in old)] + new
        buf = io.StringIO()
        w = csv.DictWriter(buf, self.spec.columns, lineterminator="\n")
        w.writeheader()
        w.writerows(self.rows)
        write_text_atomic(self.path, self.spec.declaration + "\n" + self.spec.about
                          + buf.getvalue())

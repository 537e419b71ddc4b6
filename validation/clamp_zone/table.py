"""Writing a table of the clamp-zone study under its lock (:class:`TableWriter`): a second
writer is refused and named, damaged rows are left out and recomputed, every write is
atomic (temporary file, ``fsync``, ``os.replace``).  What a table holds and how it is read
back: :mod:`validation.clamp_zone.spec`.
"""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np

from ..store import command_lock, write_text_atomic
from .spec import TableSpec, read_table

__all__ = ["TableWriter"]


def _cell(v) -> str:
    """A row value as its cell: floats to 6 digits, ``nan`` and ``None`` as empty."""
    if v is None:
        return ""
    if isinstance(v, (float, np.floating)):
        return "" if not math.isfinite(v) else f"{float(v):.6g}"
    return str(v)



class TableWriter:
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
        self.path, self.spec, self.note = Path(path), spec, note
        self._lock = None
        self.rows: list[dict] = []

    def __enter__(self) -> "TableWriter":
        self._lock = command_lock(self.path.parent, self.path.name,
                                  f"the clamp-zone {self.spec.name} table {self.path}")
        self._lock.__enter__()
        try:
            for tmp in self.path.parent.glob(f".{self.path.name}.*.tmp"):   # a killed write
                tmp.unlink()
            self.rows = read_table(self.path, self.spec, note=self.note)
        except BaseException:
            self._lock.__exit__(None, None, None)
            raise
        return self

    def __exit__(self, *exc) -> None:
        self._lock.__exit__(*exc)

    def done(self, row: dict) -> bool:
        """Whether the table holds a row with the key of ``row``."""
        k = self.spec.key_of(row)
        return any(self.spec.key_of(r) == k for r in self.rows)

    def add(self, rows) -> None:
        """Append ``rows`` (dicts; floats to 6 digits, ``nan`` as an empty cell) and
        rewrite the table atomically."""
        self.rows = self.rows + [{c: _cell(r.get(c, "")) for c in self.spec.columns}
                                 for r in rows]
        buf = io.StringIO()
        w = csv.DictWriter(buf, self.spec.columns, lineterminator="\n")
        w.writeheader()
        w.writerows(self.rows)
        write_text_atomic(self.path, self.spec.declaration + "\n" + self.spec.about
                          + buf.getvalue())

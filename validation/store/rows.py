"""The row files of the studies (``buckling``, ``post-buckling``, ``wrinkling-fe``): a CSV
resumed by the keys of its rows, so that a rerun into the same folder computes only the
missing rows, and the lock of the command that writes the folder."""

from __future__ import annotations

import csv
from pathlib import Path

from .files import FolderLock, write_csv_atomic

__all__ = ["read_rows", "append_rows", "KeyedRows", "command_lock"]


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


def read_rows(path: Path) -> list[dict]:
    """Rows of a CSV written by :func:`append_rows` (numbers as floats; the text
    columns ``mesh``, ``class``, ``physical_class``, ``branch``, ``reason``, ``model``
    as written)."""
    if not path.exists():
        return []
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k, v in r.items():
            if k not in ("mesh", "class", "physical_class", "branch", "reason", "model"):
                r[k] = float(v) if v not in ("", None) else float("nan")
    return rows


def append_rows(path: Path, columns, rows) -> None:
    """Append ``rows`` (dicts) to the CSV ``path``, writing its header first if new."""
    new = not path.exists()
    with open(path, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        if new:
            w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in r.items()})


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
    reused; a file with other columns is ignored (and replaced).

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
    """

    def __init__(self, path: Path | None, columns: list[str], nkey: int, fmt):
        self.path, self.columns, self.nkey, self.fmt = path, columns, nkey, fmt
        self.known: dict[tuple, list[str]] = {}
        if path is not None and path.is_file():
            with open(path, newline="") as fh:
                lines = list(csv.reader(fh))
            if lines and lines[0] == columns:
                self.known = {tuple(r[:nkey]): r for r in lines[1:] if len(r) == len(columns)}
        self.rows: list[list[str]] = []

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

"""Files of a validation folder that must survive crashes and concurrent writers.

* :class:`FolderLock` -- an exclusive lock on a lock file that is never deleted (on
  POSIX), so that ``--force`` or a change of settings cannot make a second process lock a
  fresh file while the first one still writes; the holder's pid and command line are
  written into the file, so that a refused process can name it.
* :func:`write_text_atomic`, :func:`write_csv_atomic`, :func:`write_npz_atomic` -- a temporary file in the same
  folder, ``fsync``, then :func:`os.replace`: a reader (or a crash) sees the old or
  the new file, never half of one.
* :class:`RowDigest` -- row count and SHA-256 checksum of the CSV rows of one run.
* :func:`save_state`, :func:`load_state` -- the resume state of one run: the last
  saved step, the arrays that continue the ramp, the row count and checksum of the
  run's rows in the CSVs, and the run's settings.
"""

from __future__ import annotations

import csv
import datetime
import errno
import hashlib
import io
import json
import os
import shlex
import stat
import sys
import warnings
import zipfile
from pathlib import Path

import numpy as np

with warnings.catch_warnings():       # where there is neither fcntl nor Windows' locking,
    warnings.simplefilter("ignore")   # filelock warns that it locks by existence
    import filelock

__all__ = ["LockedError", "FolderLock", "write_text_atomic", "write_csv_atomic",
           "write_npz_atomic", "csv_line", "regular_file", "aside_path", "keep_aside", "read_npz",
           "RowDigest", "save_state", "load_state", "dumps", "STATE_VERSION", "save_point",
           "saved_point", "RESUME_POINTS", "save_points", "saved_points"]

#: Layout version of the state files; a state of another layout is not trusted.
STATE_VERSION = 2


class LockedError(ValueError):
    """Another process holds the lock; the message names it (pid, command line)."""


def _command() -> str:
    argv = list(sys.argv) or ["python"]
    argv[0] = os.path.basename(argv[0]) or "python"
    return " ".join(shlex.quote(a) for a in argv)


class FolderLock:
    """Exclusive lock on ``path`` while a process writes (:mod:`filelock`: ``flock`` on
    POSIX, ``LockFileEx`` on Windows).

    Parameters
    ----------
    path : path-like
        The lock file.
    what : str
        What the lock protects, for the message of :class:`LockedError`.
    wait : bool
        Block until the lock is free instead of raising :class:`LockedError`.

    Notes
    -----
    The operating system releases the lock when its process dies, so a killed run never
    blocks its own resume. On POSIX the file stays after release (a second process
    cannot lock a fresh file while the first still writes) and holds the holder's pid and
    command line, which a refused process names. Where neither ``fcntl`` nor Windows'
    locking exists, the lock is the file's existence, written with the holder's pid and
    broken when that process is gone.
    """

    def __init__(self, path, what: str, *, wait: bool = False):
        self.path, self.what, self.wait, self._lock = Path(path), what, wait, None

    def holder(self) -> str:
        """Pid and command line of the process that holds (or last held) the lock."""
        try:
            text = self.path.read_text(errors="replace").strip()
        except OSError:
            text = ""
        first = text.splitlines()[0] if text else ""
        if first.isdigit():                 # the existence lock's own record: its pid
            first = f"pid {first}"
        return first or "pid unknown"

    def __enter__(self) -> "FolderLock":
        lock = filelock.FileLock(str(self.path), timeout=-1 if self.wait else 0,
                                 thread_local=False)
        try:
            lock.acquire()
        except filelock.Timeout:
            raise LockedError(f"{self.what} is being written by another process "
                              f"({self.holder()}); wait for it to end or choose another "
                              f"--out") from None
        self._lock = lock
        if isinstance(lock, filelock.UnixFileLock):
            # the holder's name, in the locked file itself (kept after release)
            try:
                fd = os.open(self.path, os.O_WRONLY)
                try:
                    os.ftruncate(fd, 0)
                    os.write(fd, f"pid {os.getpid()}: {_command()}\n".encode())
                finally:
                    os.close(fd)
            except OSError:
                pass
        return self

    def __exit__(self, *exc) -> None:
        if self._lock is not None:
            self._lock.release()
            self._lock = None


def _tmp_path(path: Path) -> Path:
    return path.with_name(f".{path.name}.{os.getpid()}.tmp")


def _replace(tmp: Path, path: Path, fh) -> None:
    fh.flush()
    os.fsync(fh.fileno())
    fh.close()
    os.replace(tmp, path)


def write_text_atomic(path, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (temporary file, ``fsync``, ``os.replace``);
    line ends are written as given (no newline translation)."""
    return _write_atomic(path, lambda fh: fh.write(text), "w")


def _write_atomic(path, write, mode: str) -> Path:
    """``write(fh)`` into a temporary file opened with ``mode`` next to ``path``, then
    ``fsync`` and ``os.replace``; an error names ``path`` (a full disk names no file),
    and the temporary file never stays."""
    path = Path(path)
    tmp = _tmp_path(path)
    try:
        fh = open(tmp, mode, **({"newline": ""} if "b" not in mode else {}))
        write(fh)
        _replace(tmp, path, fh)
    except OSError as exc:
        if exc.filename is None:          # a full disk names no file: name the one written
            raise OSError(exc.errno, exc.strerror or str(exc), str(path)) from exc
        raise
    finally:
        if tmp.exists():
            tmp.unlink()
    return path


def read_npz(path) -> dict:
    """The arrays of an ``.npz`` file the package wrote, loaded (no pickles); an
    :class:`OSError` naming ``path`` (exit code 3 of the CLI) if it is not one.

    Parameters
    ----------
    path : path-like
        The file.

    Returns
    -------
    dict
        ``{name: array}``.
    """
    path = regular_file(path, "an .npz file")
    try:
        with np.load(path, allow_pickle=False) as z:
            return {k: np.array(z[k]) for k in z.files}
    except FileNotFoundError:
        raise
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as exc:
        raise OSError(errno.EINVAL, f"is not an .npz file of arrays ({type(exc).__name__}: "
                      f"{' '.join(str(exc).split())[:120]})", str(path)) from None


def regular_file(path, what: str = "file") -> Path:
    """``path`` if it is a regular file or does not exist; an :class:`OSError` naming it
    (exit code 3 of the CLI) if it is a folder, a FIFO, a device or another special file,
    which no command of the package reads, rewrites or deletes.

    Parameters
    ----------
    path : path-like
        The path a command is about to read, rewrite or delete.
    what : str
        What the command expects there, for the message (``"the units table"``).
    """
    path = Path(path)
    try:
        mode = os.stat(path).st_mode        # a link counts as what it points to
    except FileNotFoundError:
        return path
    if stat.S_ISREG(mode):
        return path
    kind = ("a folder" if stat.S_ISDIR(mode) else "a FIFO" if stat.S_ISFIFO(mode)
            else "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode)
            else "a socket" if stat.S_ISSOCK(mode) else "not a regular file")
    raise OSError(errno.EEXIST, f"is {kind}, not {what}; it is left as it is (choose "
                  f"another --out or move it)", str(path))


def aside_path(path) -> Path:
    """Where :func:`keep_aside` keeps the damaged lines of ``path``: ``<path>.damaged``."""
    path = Path(path)
    return path.with_name(path.name + ".damaged")


def keep_aside(path, lines) -> Path:
    """Append the damaged ``lines`` of the file ``path`` to :func:`aside_path` (rewritten
    atomically), each after a ``#`` line with its line number, why it is damaged and
    when, before the rows are left out of ``path``: a row a command cannot read is never
    deleted.

    Parameters
    ----------
    path : path-like
        The file the lines come from.
    lines : iterable of (int or None, str, str)
        ``(line number, the line's text, why it is kept aside)``; ``None``: a row that
        was read, not a line of the file as it is now.

    Returns
    -------
    Path
        The side file.
    """
    aside = regular_file(aside_path(path), "the damaged rows of a table")
    old = aside.read_text(encoding="utf-8", errors="replace") if aside.exists() else ""
    stamp = datetime.datetime.now().isoformat(timespec="seconds")
    new = "".join(f"# {Path(path).name}{'' if n is None else f' line {n}'} ({stamp}): "
                  f"{why}\n{text}\n" for n, text, why in lines)
    if new:
        write_text_atomic(aside, old + new)
    return aside


def write_csv_atomic(path, header: list[str], rows) -> Path:
    """Write a CSV (``header`` then ``rows``, ``\\n`` line ends) atomically."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return write_text_atomic(path, buf.getvalue())


def write_npz_atomic(path, **arrays) -> Path:
    """Write ``arrays`` as an ``.npz`` file atomically (temporary file, ``fsync``,
    ``os.replace``): a killed write leaves no half file; an error names ``path``."""
    return _write_atomic(path, lambda fh: np.savez(fh, **arrays), "wb")


def csv_line(row) -> str:
    """The text of one CSV row as the harness writes it (with its ``\\n``)."""
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerow(row)
    return buf.getvalue()


class RowDigest:
    """Row count and SHA-256 of the CSV rows of one run, in order.

    Examples
    --------
    >>> d = RowDigest()
    >>> d.add(["a", "1"]); d.add(["a", "2"])
    >>> d.count, RowDigest.of([["a", "1"], ["a", "2"]]).hexdigest() == d.hexdigest()
    (2, True)
    """

    def __init__(self):
        self._h, self.count = hashlib.sha256(), 0

    def add(self, row) -> None:
        """Account for one more row."""
        self._h.update(csv_line(row).encode())
        self.count += 1

    def hexdigest(self) -> str:
        """The checksum of the rows so far."""
        return self._h.hexdigest()

    @classmethod
    def of(cls, rows) -> "RowDigest":
        """The digest of ``rows``."""
        d = cls()
        for r in rows:
            d.add(r)
        return d


def save_point(saved: dict, point, name: str, prefix: str = "") -> None:
    """Add a state ``point = (x, load)`` of a ramp to the arrays ``saved`` of a resume
    state, as ``x_<prefix><name>`` and ``load_<prefix><name>``: the predictor's second or
    third point (``name="back"``, ``StepResult.back``; ``"back2"``,
    ``StepResult.back2``) or where the factors the next step
    starts on were made (``name="factors"``, ``StepResult.factors``); nothing for
    ``None``."""
    if point is not None:
        saved[f"x_{prefix}{name}"] = point[0]
        saved[f"load_{prefix}{name}"] = np.asarray(point[1], dtype=float)


#: The states a ramp resumes on besides its last one (``StepResult`` attributes and
#: :func:`~skfem_dielectric.solvers.ramp.ramp` arguments of the same names)
RESUME_POINTS = ("back", "back2", "factors")


def save_points(saved: dict, step, prefix: str = "") -> None:
    """:func:`save_point` of each of a ramp step's :data:`RESUME_POINTS` (nothing for a
    ``step`` of ``None``)."""
    for name in RESUME_POINTS:
        save_point(saved, None if step is None else getattr(step, name), name, prefix)


def saved_points(saved, prefix: str = "") -> dict:
    """The :data:`RESUME_POINTS` that :func:`save_points` added to ``saved``, by name
    (``None`` where there is none): the keyword arguments of a resumed ramp."""
    return {name: saved_point(saved, name, prefix) for name in RESUME_POINTS}


def saved_point(saved, name: str, prefix: str = "") -> tuple | None:
    """The state ``(x, load)`` that :func:`save_point` added to ``saved`` (a dict of arrays
    or an opened ``.npz``), or ``None`` if there is none."""
    if saved is None or f"x_{prefix}{name}" not in saved:
        return None
    return (np.asarray(saved[f"x_{prefix}{name}"], dtype=float),
            np.asarray(saved[f"load_{prefix}{name}"], dtype=float))


def save_state(path, *, step: int, state: dict | None, done: bool, reason: str,
               rows: RowDigest, frows: RowDigest, spec: str) -> None:
    """Save the resume state of one run atomically.

    Parameters
    ----------
    path : path-like
        The ``.npz`` file.
    step : int
        Last converged step (``-1``: none).
    state : dict or None
        Arrays that continue the ramp from ``step`` (``None`` for a finished run).
    done : bool
        The run is finished (last target, breakdown or solver failure).
    reason : str
        Why a finished run stopped early (empty otherwise).
    rows, frows : RowDigest
        The run's rows so far in the case CSV and in the fields CSV.
    spec : str
        The run's settings (JSON); a state saved for other settings is not trusted.
    """
    arrays = {f"x_{k}": np.asarray(v) for k, v in (state or {}).items()}
    write_npz_atomic(path, __version__=STATE_VERSION, __step__=step, __done__=done,
                     __reason__=reason, __rows__=rows.count, __sha__=rows.hexdigest(),
                     __frows__=frows.count, __fsha__=frows.hexdigest(), __spec__=spec,
                     **arrays)


def load_state(path, spec: str) -> tuple[dict | None, str]:
    """The saved state of one run, or ``None`` and why it cannot be trusted.

    Parameters
    ----------
    path : path-like
        The ``.npz`` file.
    spec : str
        The run's settings (JSON) as passed to :func:`save_state`.

    Returns
    -------
    state : dict or None
        ``step``, ``done``, ``reason``, ``rows``, ``sha``, ``frows``, ``fsha`` and the
        arrays ``state``; ``None`` when the file is missing or not trustworthy.
    why : str
        Empty when ``state`` is usable or the file does not exist.
    """
    path = Path(path)
    if not path.exists():
        return None, ""
    try:
        with np.load(path, allow_pickle=False) as z:
            if "__version__" not in z.files or int(z["__version__"]) != STATE_VERSION:
                return None, f"{path} was written by another version of the harness"
            if str(z["__spec__"]) != spec:
                return None, f"{path} was saved for other settings of this run"
            st = {"step": int(z["__step__"]), "done": bool(z["__done__"]),
                  "reason": str(z["__reason__"]), "rows": int(z["__rows__"]),
                  "sha": str(z["__sha__"]), "frows": int(z["__frows__"]),
                  "fsha": str(z["__fsha__"]),
                  "state": {k[2:]: np.array(z[k]) for k in z.files if k.startswith("x_")}}
    except IsADirectoryError:
        raise
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as exc:
        return None, f"{path} is unreadable ({type(exc).__name__}: {exc})"
    if st["step"] < -1 or st["rows"] < 0 or st["frows"] < 0:
        return None, f"{path} holds an impossible step or row count"
    return st, ""


def dumps(obj) -> str:
    """Compact, key-sorted JSON (the form compared and stored)."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"))

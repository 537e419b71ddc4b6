"""Progress on stderr (no dependency): a bar on a terminal; elsewhere (logs, pipes, CI)
lines, flushed: at most one per finished load step (and one every :attr:`Progress.interval`
seconds at most) and one per finished run; nothing when switched off.

A runner that computes load steps before it reports its first row (the grad-div ramp of a
run analysed for buckling) reports them with :func:`report_step` through the bar of the
case being run."""

from __future__ import annotations

import contextvars
import math
import sys
import time
from typing import TextIO

__all__ = ["Progress", "notice", "report_step"]

#: the bar of the unit of work running in this thread (:meth:`Progress.__enter__`)
_ACTIVE: contextvars.ContextVar["Progress | None"] = contextvars.ContextVar(
    "skfem_dielectric_progress", default=None)


class Progress:
    """Text progress bar ``desc [#####.....] 5/10 12.3s  note``.

    Parameters
    ----------
    total : int
        Number of units of work.
    desc : str
        Label printed before the bar.
    stream : file-like, optional
        Where to draw; ``sys.stderr`` by default.
    enabled : bool, optional
        ``True``: the bar; ``False``: nothing at all; ``None`` (default): the bar when
        ``stream`` is a terminal, else lines: those of :meth:`line` (one per finished run)
        and of :meth:`step` (a finished load step), so that a log shows progress without
        carriage returns.
    interval : float, optional
        Least seconds between two lines of :meth:`step` (default :attr:`interval`, 5 s;
        0: a line for every load step).

    Examples
    --------
    >>> import io
    >>> buf = io.StringIO()
    >>> with Progress(2, "demo", stream=buf, enabled=True) as bar:
    ...     bar.update(note="D0=1")
    ...     bar.update()
    >>> buf.getvalue().split(chr(13))[-1].split()[:3]
    ['demo', '[########################]', '2/2']
    """

    width = 24
    #: least seconds between two lines of :meth:`step` off a terminal
    interval = 5.0

    def __init__(self, total: int, desc: str = "", *, stream: TextIO | None = None,
                 enabled: bool | None = None, interval: float | None = None) -> None:
        if total < 0:
            raise ValueError(f"total must be >= 0, got {total}")
        if interval is not None:
            if not (isinstance(interval, (int, float)) and interval >= 0):
                raise ValueError(f"interval must be a number >= 0, got {interval!r}")
            self.interval = float(interval)
        self.total = int(total)
        self.desc = desc
        self.stream = sys.stderr if stream is None else stream
        isatty = getattr(self.stream, "isatty", None)
        tty = bool(isatty and isatty())
        #: draw the bar; write the lines of :meth:`line` instead when not on a terminal
        self.enabled = tty if enabled is None else bool(enabled)
        self.lines = enabled is None and not tty
        self.count = 0
        self._t0 = time.perf_counter()
        self._last_len = 0
        self._last_step = -math.inf
        self._token = None

    def update(self, n: int = 1, note: str = "") -> None:
        """Advance by ``n`` units (finished load steps) and redraw with an optional short
        ``note``; off a terminal, the line of :meth:`step`."""
        self.count = min(self.total, self.count + n)
        self._draw(note)
        self.step(note)

    def step(self, note: str) -> None:
        """Off a terminal, one line ``skfem-dielectric: desc: count/total note (t s)`` for a
        finished load step, unless the last one is less than :attr:`interval` seconds old
        (nothing on a terminal, where the bar shows it, or when progress is off).

        Examples
        --------
        >>> import io
        >>> buf = io.StringIO()
        >>> bar = Progress(4, "zs22", stream=buf, interval=0)
        >>> bar.update(note="alpha=1 D0=0.5"); bar.step("alpha=1 grad-div D0=1")
        >>> [ln.split(" (")[0] for ln in buf.getvalue().splitlines()]
        ['skfem-dielectric: zs22: 1/4 alpha=1 D0=0.5', 'skfem-dielectric: zs22: 1/4 alpha=1 grad-div D0=1']
        """
        if not self.lines:
            return
        now = time.perf_counter()
        if now - self._last_step < self.interval:
            return
        self._last_step = now
        head = f"{self.desc}: " if self.desc else ""
        notice(f"{head}{self.count}/{self.total} {note} ({now - self._t0:.0f} s)", self.stream)

    def line(self, message: str) -> None:
        """One line ``skfem-dielectric: desc: message`` when not on a terminal (the bar,
        when drawn, shows the same progress; nothing when progress is off).

        Examples
        --------
        >>> import io
        >>> buf = io.StringIO()
        >>> Progress(3, "nh-d-e", stream=buf).line("run a: 3 steps")
        >>> buf.getvalue()
        'skfem-dielectric: nh-d-e: run a: 3 steps\\n'
        """
        if self.lines:
            notice(f"{self.desc}: {message}" if self.desc else message, self.stream)

    def _draw(self, note: str = "") -> None:
        if not self.enabled:
            return
        frac = self.count / self.total if self.total else 1.0
        filled = int(round(frac * self.width))
        bar = "#" * filled + "." * (self.width - filled)
        elapsed = time.perf_counter() - self._t0
        line = f"{self.desc} [{bar}] {self.count}/{self.total} {elapsed:5.1f}s {note}".rstrip()
        pad = " " * max(0, self._last_len - len(line))
        self.stream.write("\r" + line + pad)
        self.stream.flush()
        self._last_len = len(line)

    def close(self) -> None:
        """Finish the line (only if anything was drawn)."""
        if self.enabled and self._last_len:
            self.stream.write("\n")
            self.stream.flush()
        self._last_len = 0

    def __enter__(self) -> "Progress":
        self._token = _ACTIVE.set(self)
        self._draw()
        return self

    def __exit__(self, *exc) -> None:
        if self._token is not None:
            _ACTIVE.reset(self._token)
            self._token = None
        self.close()


def report_step(note: str) -> None:
    """A finished load step of work that has no row yet, as :meth:`Progress.step` of the
    bar running in this thread (nothing without one, or on a terminal).

    Examples
    --------
    >>> import io
    >>> buf = io.StringIO()
    >>> with Progress(2, "zs22", stream=buf, interval=0):
    ...     report_step("alpha=1 grad-div D0=0.5")
    >>> buf.getvalue().split(" (")[0]
    'skfem-dielectric: zs22: 0/2 alpha=1 grad-div D0=0.5'
    >>> report_step("no bar: nothing")
    """
    bar = _ACTIVE.get()
    if bar is not None:
        bar.step(note)


def notice(message: str, stream: TextIO | None = None) -> None:
    """Write a one-line message (e.g. what a resume repaired) to ``stream`` (``sys.stderr``).

    Examples
    --------
    >>> import io
    >>> buf = io.StringIO()
    >>> notice("run x: recomputed", stream=buf)
    >>> buf.getvalue()
    'skfem-dielectric: run x: recomputed\\n'
    """
    stream = sys.stderr if stream is None else stream
    stream.write("skfem-dielectric: " + " ".join(message.split()) + "\n")
    stream.flush()

"""Progress on stderr (no dependency): a bar on a terminal, one line per finished run
elsewhere (logs, pipes, CI), nothing when switched off."""

from __future__ import annotations

import sys
import time
from typing import TextIO

__all__ = ["Progress", "notice"]


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
        ``stream`` is a terminal, else only the lines of :meth:`line` (one per finished
        run), so that a log shows progress without carriage returns.

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

    def __init__(self, total: int, desc: str = "", *, stream: TextIO | None = None,
                 enabled: bool | None = None) -> None:
        if total < 0:
            raise ValueError(f"total must be >= 0, got {total}")
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

    def update(self, n: int = 1, note: str = "") -> None:
        """Advance by ``n`` units and redraw with an optional short ``note``."""
        self.count = min(self.total, self.count + n)
        self._draw(note)

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
        self._draw()
        return self

    def __exit__(self, *exc) -> None:
        self.close()


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

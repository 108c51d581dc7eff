"""A progress line on stderr for runs long enough to wonder about.

Shown only when stderr is a terminal (never in CI logs, pipes, editors or tests) and only
once the run has lasted ``DELAY_SECONDS``: a pre-commit run over a few files finishes
before anything would flicker. Redrawn at most every ``REFRESH_SECONDS``, on one line
(``\\r``), and erased when the run ends so that the summary line starts clean.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Mapping
from typing import TextIO

DELAY_SECONDS = 1.0
REFRESH_SECONDS = 0.1
_ERASE_LINE = "\r\x1b[K"


def wanted(stream: TextIO, environ: Mapping[str, str]) -> bool:
    """Whether a progress line may be drawn on ``stream`` at all."""
    try:
        terminal = stream.isatty()
    except (AttributeError, ValueError):  # a closed or unusual stream
        terminal = False
    return terminal and environ.get("TERM") != "dumb"


class ProgressBar:
    """Call it with (done, total) as often as you like; it decides when to draw."""

    def __init__(
        self,
        stream: TextIO,
        enabled: bool,
        clock: Callable[[], float] = time.monotonic,
        width: int | None = None,
    ) -> None:
        self._stream = stream
        self._enabled = enabled
        self._clock = clock
        self._width = width
        self._started = clock()
        self._drawn_at: float | None = None

    @property
    def shown(self) -> bool:
        return self._drawn_at is not None

    def __call__(self, done: int, total: int) -> None:
        if not self._enabled:
            return
        now = self._clock()
        if now - self._started < DELAY_SECONDS:
            return
        if self._drawn_at is not None and now - self._drawn_at < REFRESH_SECONDS:
            return
        self._drawn_at = now
        self._stream.write("\r" + self.line(done, total, now - self._started) + "\x1b[K")
        self._stream.flush()

    def close(self) -> None:
        """Erase the line, if one was drawn."""
        if self._drawn_at is not None:
            self._stream.write(_ERASE_LINE)
            self._stream.flush()
            self._drawn_at = None

    def line(self, done: int, total: int, elapsed: float) -> str:
        counts = f" {done}/{total} files  {elapsed:.0f} s"
        room = self._columns() - len("roslint-names []") - len(counts)
        if room < 10:
            return f"roslint-names{counts}"
        filled = room * done // total if total else room
        return f"roslint-names [{'#' * filled}{'.' * (room - filled)}]{counts}"

    def _columns(self) -> int:
        if self._width is not None:
            return self._width
        try:
            return os.get_terminal_size(self._stream.fileno()).columns - 1
        except (AttributeError, OSError, ValueError):
            return 79

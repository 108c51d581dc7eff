"""Run a hypothesis property for a few examples, or for a time budget, and count inputs.

Without ``ROSLINT_FUZZ_MINUTES`` each fuzz test runs ``QUICK_EXAMPLES`` inputs (a few
seconds for all of them, as part of the normal suite) and a failure is shrunk and reported
by hypothesis as usual. With it, the minutes are shared among the fuzz tests selected, and
each runs rounds of hypothesis until its share is spent; a failing input is then recorded
(its bytes saved under ``ROSLINT_FUZZ_CRASHES``, default ``$TMPDIR/roslint-fuzz-crashes``,
one file per distinct failure, with its traceback) and the run goes on, so one bug does
not hide the next; the test fails at the end, listing them. Before each input of a long
run its bytes are written to ``TARGET-current.bin`` there: if a parser kills the process
(a segfault is no exception), that file holds the input that did it.

An input still running after ``ROSLINT_FUZZ_HANG_SECONDS`` (default 30) is a failure too
(``HangError``, raised by an alarm); one stuck in C code, which the alarm cannot
interrupt, ends the process after twice that, with faulthandler's traceback of it.
"""

from __future__ import annotations

import faulthandler
import hashlib
import os
import signal
import tempfile
import threading
import time
import traceback
from collections import Counter
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import TypeVar

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

MINUTES_VARIABLE = "ROSLINT_FUZZ_MINUTES"
CRASHES_VARIABLE = "ROSLINT_FUZZ_CRASHES"
HANG_VARIABLE = "ROSLINT_FUZZ_HANG_SECONDS"
QUICK_EXAMPLES = 20
ROUND_EXAMPLES = 200  # examples per hypothesis run in a long session
MAX_SAVED_PER_FAILURE = 3

T = TypeVar("T")


class FuzzUsageError(Exception):
    pass


class HangError(Exception):
    """An input the code under test has not finished with in time."""


def minutes() -> float | None:
    """The session's fuzzing budget in minutes, or None for a quick run."""
    text = os.environ.get(MINUTES_VARIABLE, "").strip()
    if not text:
        return None
    try:
        value = float(text)
    except ValueError:
        raise FuzzUsageError(f"{MINUTES_VARIABLE}={text!r} is not a number of minutes") from None
    if value <= 0:
        raise FuzzUsageError(f"{MINUTES_VARIABLE} must be more than 0")
    return value


@dataclass
class Failure:
    signature: str  # exception type and where it was raised
    message: str
    count: int = 0
    saved: list[Path] = field(default_factory=list)


@dataclass
class Stats:
    """What one fuzz test did: shown in the terminal summary (see ``conftest``)."""

    target: str
    inputs: int = 0
    seconds: float = 0.0
    kinds: Counter[str] = field(default_factory=Counter)
    failures: dict[str, Failure] = field(default_factory=dict)


STATS: list[Stats] = []
SELECTED = [0]  # fuzz tests selected in this session; set by conftest at collection


def share_seconds() -> float | None:
    total = minutes()
    if total is None:
        return None
    return total * 60 / max(SELECTED[0], 1)


def hang_seconds() -> float:
    text = os.environ.get(HANG_VARIABLE, "").strip()
    try:
        return float(text) if text else 30.0
    except ValueError:
        raise FuzzUsageError(f"{HANG_VARIABLE}={text!r} is not a number of seconds") from None


@contextmanager
def watchdog(seconds: float) -> Iterator[None]:
    """Raise ``HangError`` in the body after ``seconds``; end the process after twice that."""
    if (
        not hasattr(signal, "setitimer")
        or threading.current_thread() is not threading.main_thread()
    ):
        yield
        return

    def expire(signum: int, frame: object) -> None:
        raise HangError(f"no result after {seconds:g} s: it hangs")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    faulthandler.dump_traceback_later(2 * seconds, exit=True)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        faulthandler.cancel_dump_traceback_later()
        signal.signal(signal.SIGALRM, previous)


def crash_directory() -> Path:
    default = Path(tempfile.gettempdir()) / "roslint-fuzz-crashes"
    return Path(os.environ.get(CRASHES_VARIABLE) or default)


def fuzz(
    target: str,
    strategy: st.SearchStrategy[T],
    check: Callable[[T], None],
    *,
    data_of: Callable[[T], bytes],
    kind_of: Callable[[T], str],
    describe: Callable[[T], str] = repr,
) -> Stats:
    """Check ``check(sample)`` on samples of ``strategy``, quickly or for a time budget."""
    stats = Stats(target)
    STATS.append(stats)
    budget = share_seconds()
    started = time.monotonic()
    deadline = None if budget is None else started + budget
    keep_going = budget is not None
    hang = hang_seconds()
    crashes = crash_directory()
    current = crashes / f"{_file_stem(target)}-current.bin"
    if keep_going:
        crashes.mkdir(parents=True, exist_ok=True)

    @settings(
        max_examples=QUICK_EXAMPLES if budget is None else ROUND_EXAMPLES,
        deadline=None,
        database=None if keep_going else settings.default.database,
        suppress_health_check=list(HealthCheck),
        print_blob=True,
    )
    @given(strategy)
    def run(sample: T) -> None:
        if deadline is not None and time.monotonic() >= deadline:
            return  # the rest of this round: nothing to do
        stats.inputs += 1
        stats.kinds[kind_of(sample)] += 1
        if not keep_going:
            with watchdog(hang):
                check(sample)
            return
        data = data_of(sample)
        current.write_bytes(data)
        try:
            with watchdog(hang):
                check(sample)
        except Exception as error:
            _record(stats, crashes, error, data, describe(sample))

    try:
        while True:
            run()
            if deadline is None or time.monotonic() >= deadline:
                break
    finally:
        stats.seconds = time.monotonic() - started
    return stats


def _record(stats: Stats, crashes: Path, error: Exception, data: bytes, description: str) -> None:
    frames = traceback.extract_tb(error.__traceback__)
    if isinstance(error, HangError):
        frames = frames[:-1]  # where the alarm interrupted the code, not the alarm itself
    where = f"{frames[-1].filename}:{frames[-1].lineno}" if frames else "?"
    signature = f"{type(error).__name__} at {where}"
    message = f"{type(error).__name__}: {error}"[:2000]
    failure = stats.failures.setdefault(signature, Failure(signature, message))
    failure.count += 1
    if len(failure.saved) >= MAX_SAVED_PER_FAILURE:
        return
    digest = hashlib.sha1(data).hexdigest()[:12]
    path = crashes / f"{_file_stem(stats.target)}-{digest}.bin"
    if path in failure.saved:  # hypothesis tried the same input again
        return
    path.write_bytes(data)
    details = "".join(traceback.format_exception(error))
    path.with_suffix(".txt").write_text(f"{description}\n\n{details}", encoding="utf-8")
    failure.saved.append(path)


def _file_stem(target: str) -> str:
    return "".join(char if char.isalnum() or char in "._-" else "_" for char in target)


def report_failures(stats: Stats) -> str | None:
    """The failures of a long run, for the test to fail with; None when there were none."""
    if not stats.failures:
        return None
    lines = [f"{stats.target}: {len(stats.failures)} distinct failures in {stats.inputs} inputs"]
    for failure in stats.failures.values():
        lines.append(f"- {failure.count}x {failure.signature}: {failure.message[:300]}")
        lines.extend(f"    saved: {path}" for path in failure.saved)
    return "\n".join(lines)

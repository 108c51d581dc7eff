"""Worker processes for extraction, started only when there is enough work for them.

``Dispatcher`` takes items one at a time (the engine hands over files as it reads them) and
hands back results as they are ready, in any order. Workers cost tens of milliseconds to
start and every item they take is pickled across a pipe, so:

- with one job, or while fewer than ``min_items`` items have arrived, nothing is started;
  a run that ends below that (the one-file pre-commit case, a re-run where nearly
  everything came from the cache) does its work in-process at ``finish``;
- a small run on a many-core machine gets one worker per ``ITEMS_PER_WORKER`` items;
- items travel in chunks (a few files or a few hundred KiB) to keep messages few;
- at most a few chunks per worker are in flight, so the bytes of files waiting to be
  extracted stay bounded however large the workspace is.

``concurrent.futures`` and ``multiprocessing`` are imported only when workers start.
"""

from __future__ import annotations

import gc
import os
import signal
import sys
from collections.abc import Callable, Iterator
from types import TracebackType
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from .collection import THRESHOLDS

if TYPE_CHECKING:
    from concurrent.futures import Future, ProcessPoolExecutor

Item = TypeVar("Item")
Result = TypeVar("Result")

MIN_ITEMS = 20
ITEMS_PER_WORKER = 10  # fewer expected items per worker: fewer workers (forks cost too)
CHUNK_ITEMS = 8
CHUNK_BYTES = 256 * 1024
CHUNKS_PER_WORKER = 3


def available_cores() -> int:
    """Cores this process may run on (affinity and cpusets count, not the machine's)."""
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return os.cpu_count() or 1


def worker_count(jobs: int) -> int:
    """``--jobs``: 0 means every available core."""
    return available_cores() if jobs == 0 else jobs


class Dispatcher(Generic[Item, Result]):
    """Runs ``work`` over chunks of items, in worker processes when that pays off."""

    def __init__(
        self,
        work: Callable[[list[Item]], list[Result]],
        jobs: int,
        min_items: int | None = None,
        expected_items: int | None = None,
    ) -> None:
        self._work = work
        self._workers = worker_count(jobs)
        if expected_items is not None:
            self._workers = min(self._workers, max(1, expected_items // ITEMS_PER_WORKER))
        self._min_items = MIN_ITEMS if min_items is None else min_items
        self._pending: list[Item] = []
        self._pending_bytes = 0
        self._executor: ProcessPoolExecutor | None = None
        self._inflight: set[Future[list[Result]]] = set()

    @property
    def workers(self) -> int:
        """How many worker processes were started (0: everything ran in-process)."""
        return self._workers if self._executor is not None else 0

    def put(self, item: Item, size: int) -> list[Result]:
        """Take one item of ``size`` bytes; return the results that are ready, if any."""
        if self._workers < 2:
            return self._work([item])  # one job: no queue, no bytes held
        self._pending.append(item)
        self._pending_bytes += size
        if self._executor is None:
            if len(self._pending) < self._min_items:
                return []
            self._start()
        if len(self._pending) >= CHUNK_ITEMS or self._pending_bytes >= CHUNK_BYTES:
            self._submit()
        return self._collect(block=len(self._inflight) >= self._workers * CHUNKS_PER_WORKER)

    def finish(self) -> Iterator[Result]:
        """The results of every item taken and not yet returned."""
        if self._executor is None:
            if self._pending:
                pending, self._pending = self._pending, []
                yield from self._work(pending)
            return
        if self._pending:
            self._submit()
        while self._inflight:
            yield from self._collect(block=True)

    def close(self) -> None:
        if self._executor is not None:
            self._executor.shutdown(wait=True, cancel_futures=True)
            self._executor = None

    def __enter__(self) -> Dispatcher[Item, Result]:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self.close()

    def _start(self) -> None:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        # fork on Linux: a worker starts in milliseconds with the modules already loaded,
        # and the engine has not imported any parser yet (workers import their own on
        # first use). Elsewhere the platform's default (spawn on macOS and Windows).
        context = multiprocessing.get_context("fork") if sys.platform == "linux" else None
        self._executor = ProcessPoolExecutor(
            max_workers=self._workers,
            mp_context=context,
            initializer=_initialize,
            initargs=(self._work,),
        )

    def _submit(self) -> None:
        assert self._executor is not None
        chunk, self._pending, self._pending_bytes = self._pending, [], 0
        self._inflight.add(self._executor.submit(_run, chunk))

    def _collect(self, block: bool) -> list[Result]:
        from concurrent.futures import FIRST_COMPLETED, wait

        if block:
            done, _ = wait(self._inflight, return_when=FIRST_COMPLETED)
        else:
            done = {future for future in self._inflight if future.done()}
        self._inflight -= done
        # result() re-raises a worker's exception here, as in-process work would.
        return [result for future in done for result in future.result()]


# The work function, installed once per worker rather than pickled with every chunk.
_WORK: Callable[[list[Any]], list[Any]] | None = None


def _initialize(work: Callable[[list[Any]], list[Any]]) -> None:
    global _WORK  # noqa: PLW0603 - the worker's one piece of state
    _WORK = work
    gc.set_threshold(*THRESHOLDS)  # inherited when forked, not when spawned
    # Ctrl-C reaches the whole process group; the main process alone decides what to do
    # (cancel and shut down), so workers do not each print a KeyboardInterrupt traceback.
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _run(chunk: list[Any]) -> list[Any]:
    assert _WORK is not None, "worker used before its initializer ran"
    return _WORK(chunk)

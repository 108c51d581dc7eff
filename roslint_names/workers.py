"""Worker processes for extraction, started only when there is enough work for them; and
the time budget every item's work has, in a worker or in this process.

``Dispatcher`` takes items one at a time (the engine hands over files as it reads them) and
hands back results as they are ready, in any order. Workers cost tens of milliseconds to
start and every item they take is pickled across a pipe, so:

- with one job, or while fewer than ``min_items`` items have arrived, nothing is started;
  a run that ends below that (the one-file pre-commit case, a re-run where nearly
  everything came from the cache) does its work in-process at ``finish``;
- a small run on a many-core machine gets one worker per ``ITEMS_PER_WORKER`` items;
- items travel in chunks (up to a few dozen files or a few hundred KiB) to keep messages
  few: each costs the main process's threads a pickling, a send, a result received and
  unpickled (at 8 files a chunk, a quarter second of a cold run's serial part on realws);
  a run of few items sends smaller ones, so that every worker still gets several;
- at most a few chunks per worker are in flight, so the bytes of files waiting to be
  extracted stay bounded however large the workspace is.

No item hangs a run. The work itself keeps to ``BUDGET_SECONDS`` per item where Python
code is slow (``time_limit``: an alarm signal, in whichever process works, on its main
thread); a signal cannot stop a long native call (a parser's), so a worker still busy
with one item ``KILL_GRACE`` past the budget is killed, that item handed to ``give_up``,
the items of the chunks it took down sent again to fresh workers. A worker that dies on
its own (a parser's segfault) is found the same way. Workers die with the main process,
even by ``kill -9`` (the parent death signal, or a watching thread), and never hold its
standard output: ``check | cat`` ends when the main process does.

``concurrent.futures`` and ``multiprocessing`` are imported only when workers start.
"""

from __future__ import annotations

import contextlib
import gc
import os
import pickle
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from types import FrameType, TracebackType
from typing import TYPE_CHECKING, Any, Generic, TypeVar, cast

from .collection import THRESHOLDS
from .model import dumps

if TYPE_CHECKING:
    from concurrent.futures import Future, ProcessPoolExecutor
    from multiprocessing.sharedctypes import SynchronizedArray

Item = TypeVar("Item")
Result = TypeVar("Result")

MIN_ITEMS = 20
ITEMS_PER_WORKER = 10  # fewer expected items per worker: fewer workers (forks cost too)
CHUNK_ITEMS = 32  # at most; fewer where the expected items would give a worker few chunks
CHUNKS_EACH = 8  # the chunks a worker should get at least, where there are items enough
CHUNK_BYTES = 256 * 1024
CHUNKS_PER_WORKER = 3
# A batch the caller waits for whole (``Dispatcher.batch``): at least this many chunks a
# worker, so that one slow chunk does not hold the batch while the others idle.
BATCH_CHUNKS_EACH = 2

# Seconds one item's work may take; read at each use, so tests can lower it. Far above
# what a file written by hand needs: realws's 4,294 files past the prefilters took 9.7 s
# together (bench/latest-results.json), and a generated node of 8,000 publishers
# (590 KB) takes 3.7 s.
BUDGET_SECONDS = 10.0
# How long past the budget a worker may stay on one item before it is killed: the alarm
# should have stopped it at the budget, unless native code (a parser) holds it.
KILL_GRACE = 0.5  # of the budget
_POLL_SECONDS = 0.5  # how often the main process looks for a worker past its time
# How long the main process waits for the workers' slots' lock, which a worker holds
# only to write its slot: held longer, its holder died with it.
_SLOTS_LOCK_SECONDS = 1.0
_WATCH_PARENT_SECONDS = 0.5  # without a parent death signal: how often a worker looks


def available_cores() -> int:
    """Cores this process may run on (affinity and cpusets count, not the machine's)."""
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return os.cpu_count() or 1


def worker_count(jobs: int) -> int:
    """``--jobs``: 0 means every available core."""
    return available_cores() if jobs == 0 else jobs


def budget_seconds() -> float:
    return BUDGET_SECONDS


class OutOfTime(BaseException):
    """An item's work ran past its budget. A ``BaseException``, as ``KeyboardInterrupt``
    is: no ``except Exception`` in an extractor may swallow it."""


@contextmanager
def time_limit(seconds: float) -> Iterator[None]:
    """Raise ``OutOfTime`` in the block once it has run ``seconds``.

    An alarm signal, so only on the main thread of a platform that has one (elsewhere the
    block runs unlimited: the language server's threads, Windows); and only between
    Python bytecodes: a native call is interrupted when it returns. A timer already
    armed (a test runner's) is set again, less the time spent here, when the block ends.
    """
    if (
        not hasattr(signal, "setitimer")
        or threading.current_thread() is not threading.main_thread()
    ):
        yield
        return

    def expired(signum: int, frame: FrameType | None) -> None:
        raise OutOfTime

    previous = signal.signal(signal.SIGALRM, expired)
    started = time.monotonic()
    earlier, interval = signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
        if earlier > 0:
            left = max(earlier - (time.monotonic() - started), 0.001)
            signal.setitimer(signal.ITIMER_REAL, left, interval)


@dataclass(frozen=True)
class Stopped:
    """Why an item's work was stopped: it ran past ``budget`` seconds, or (``budget``
    None) the worker process died on it twice, or (``unreceived``) its result, sent
    alone, could not be unpickled here."""

    budget: float | None
    unreceived: bool = False

    def __str__(self) -> str:
        if self.unreceived:
            return "its facts could not be received from the worker process"
        if self.budget is None:
            return "the worker process extracting it died, twice"
        return f"gave up after {self.budget:g} s"


GiveUp = Callable[[Item, Stopped], Result]  # an item whose work was stopped, and why


class Dispatcher(Generic[Item, Result]):
    """Runs ``work`` over chunks of items, in worker processes when that pays off.

    ``give_up``: the result of an item whose worker was killed past its budget, or died
    while on it; without it, such a death is an error, as it was before budgets."""

    def __init__(
        self,
        work: Callable[[Iterable[Item]], list[Result]],
        jobs: int,
        min_items: int | None = None,
        expected_items: int | None = None,
        *,
        give_up: GiveUp[Item, Result] | None = None,
    ) -> None:
        self._work = work
        self._give_up = give_up
        self._workers = worker_count(jobs)
        self._chunk_items = CHUNK_ITEMS
        self._expected = expected_items
        if expected_items is not None:
            self._workers = min(self._workers, max(1, expected_items // ITEMS_PER_WORKER))
            spread = expected_items // (self._workers * CHUNKS_EACH)
            self._chunk_items = max(1, min(CHUNK_ITEMS, spread))
        self._min_items = MIN_ITEMS if min_items is None else min_items
        self._pending: list[tuple[int, Item]] = []
        self._pending_bytes = 0
        self._numbered = 0
        self._executor: ProcessPoolExecutor | None = None
        self._slots: SynchronizedArray[float] | None = None
        self._inflight: dict[Future[bytes], list[tuple[int, Item]]] = {}
        self._stopped: dict[int, Stopped] = {}  # items killed past their budget: why
        self._strikes: dict[int, int] = {}  # items busy when a worker died unexplained
        self._started = False  # since the last close
        self._next_overdue_check = 0.0  # ``time.monotonic``: a put looks no sooner

    @property
    def parallel(self) -> bool:
        """Whether the items go to worker processes (once there are enough of them)."""
        return self._workers >= 2

    @property
    def workers(self) -> int:
        """How many worker processes were started (0: everything ran in-process)."""
        return self._workers if self._started else 0

    def put(self, item: Item, size: int) -> list[Result]:
        """Take one item of ``size`` bytes; return the results that are ready, if any."""
        if self._workers < 2:
            return self._work([item])  # one job: no queue, no bytes held
        self._pending.append((self._numbered, item))
        self._numbered += 1
        self._pending_bytes += size
        if self._executor is None:
            if len(self._pending) < self._min_items:
                return []
            self._start()
        if len(self._pending) < self._chunk_limit() and self._pending_bytes < CHUNK_BYTES:
            # Asked only as a chunk goes out: after every item, looking at each future in
            # flight (its lock taken) was 0.44 s of a cold run's main process at 8 copies.
            return []
        self._submit()
        return self._collect(block=len(self._inflight) >= self._workers * CHUNKS_PER_WORKER)

    def _chunk_limit(self) -> int:
        """``_chunk_items``, less as the expected items run out: the last chunks of a
        stream give each worker two at least, so that the workers finish together rather
        than all but one waiting on a last chunk of 32 files (guided self-scheduling)."""
        if self._expected is None or self._numbered > self._expected:
            return self._chunk_items
        return self._spread(self._expected - self._numbered + len(self._pending))

    @contextmanager
    def batch(self, items: int) -> Iterator[None]:
        """The next ``items`` puts are chunked so that every worker gets some: a batch the
        caller then waits for whole (``finish``; a depth of the launch trees,
        ``gather.Specialiser``), or items each slow to work on (the largest files, handed
        out first: ``gather.Gatherer``). Chunks sized for the stream of a whole workspace
        (32 items) left 8 of 16 workers idle on a depth of 229 launch files, and every
        worker but one on the deepest depths."""
        kept = self._chunk_items
        self._chunk_items = self._spread(items)
        try:
            yield
        finally:
            self._chunk_items = kept

    def _spread(self, items: int) -> int:
        """Chunks of ``items`` that give every worker ``BATCH_CHUNKS_EACH`` at least (the
        count rounded up), no larger than ``_chunk_items``."""
        return max(1, min(self._chunk_items, -(-items // (self._workers * BATCH_CHUNKS_EACH))))

    def here(self, items: Iterable[Item]) -> list[Result]:
        """The results of ``items``, worked on in this process."""
        return self._work(items)

    def finish(self) -> Iterator[Result]:
        """The results of every item taken and not yet returned."""
        if self._executor is None:
            if self._pending:
                pending, self._pending = self._pending, []
                yield from self._work([item for _, item in pending])
            return
        if self._pending:
            self._submit()
        while self._inflight:
            yield from self._collect(block=True)

    def close(self) -> None:
        """Shut the workers down: at once, killing them, if work is still in flight (an
        error or Ctrl-C left it): one stuck in a parser would never return."""
        self._started = False
        if self._executor is None:
            return
        if self._inflight:
            self._kill_workers()
        self._executor.shutdown(wait=True, cancel_futures=True)
        self._executor = None
        self._slots = None
        self._inflight.clear()

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
        context = (
            multiprocessing.get_context("fork")
            if sys.platform == "linux"
            else multiprocessing.get_context()
        )
        # Per worker: its pid, the number of the item it is on (-1: none), since when.
        self._slots = context.Array("d", [0.0, -1.0, 0.0] * self._workers)
        self._executor = ProcessPoolExecutor(
            max_workers=self._workers,
            mp_context=context,
            initializer=_initialize,
            initargs=(self._work, self._slots, os.getpid()),
        )
        self._started = True

    def _submit(self) -> None:
        chunk, self._pending, self._pending_bytes = self._pending, [], 0
        self._send(chunk)

    def _send(self, chunk: list[tuple[int, Item]]) -> None:
        assert self._executor is not None
        self._inflight[self._executor.submit(_run, chunk)] = chunk

    def _collect(self, block: bool) -> list[Result]:
        from concurrent.futures import FIRST_COMPLETED, wait
        from concurrent.futures.process import BrokenProcessPool

        while True:
            if block:
                done, _ = wait(self._inflight, timeout=_POLL_SECONDS, return_when=FIRST_COMPLETED)
            else:
                # Asked after every item put: ``wait`` installs a waiter on each future in
                # flight and takes its lock twice: 0.25 s of a cold run's 3 s serial part.
                done = {future for future in self._inflight if future.done()}
            results: list[Result] = []
            broken = False
            for future in done:
                error = future.exception()
                if isinstance(error, BrokenProcessPool):
                    broken = True
                    continue  # sent again by ``_recover``, less what stopped it
                chunk = self._inflight.pop(future)
                if error is not None:
                    raise error  # a worker's exception, as in-process work would raise it
                received = _unpickled(future.result())
                results.extend(self._unreceived(chunk) if received is None else received)
                for number, _ in chunk:
                    self._strikes.pop(number, None)
            if broken:
                results.extend(self._recover())
            elif block or time.monotonic() >= self._next_overdue_check:
                self._kill_overdue()
            if results or not block or not self._inflight:
                return results

    def _kill_overdue(self) -> None:
        """Kill each worker that has been on one item for longer than the budget allows;
        the pool then breaks, and ``_recover`` picks up. Only when an item can be given up."""
        if self._give_up is None:
            return
        budget = budget_seconds()
        deadline = budget * (1 + KILL_GRACE)
        now = time.monotonic()
        self._next_overdue_check = now + _POLL_SECONDS
        for pid, number, since in self._busy():
            if now - since > deadline:
                self._stopped[number] = Stopped(budget)
                _kill(pid)

    def _busy(self) -> list[tuple[int, int, float]]:
        """Each busy worker: its pid, its item's number, since when. A worker killed while
        it held the slots' lock (one the pool terminated as another died) never releases
        it: past ``_SLOTS_LOCK_SECONDS`` the slots are read without it (no live worker
        writes them then: its death broke the pool), where waiting hung the run."""
        if self._slots is None:
            return []
        lock = self._slots.get_lock()
        if lock.acquire(timeout=_SLOTS_LOCK_SECONDS):
            try:
                values = self._slots[:]
            finally:
                lock.release()
        else:
            values = cast(list[float], self._slots.get_obj()[:])  # c_double reads as float
        return [
            (int(values[i]), int(values[i + 1]), values[i + 2])
            for i in range(0, len(values), 3)
            if values[i] > 0 and values[i + 1] >= 0
        ]

    def _recover(self) -> list[Result]:
        """The pool broke: a worker was killed past its budget, or died. Keep what the
        other chunks returned, give up on the items that stopped it, send the rest again
        to a fresh pool. An item that was busy when a worker died for no known reason
        is sent again once; if a worker dies on it again, it is given up."""
        from concurrent.futures import wait

        busy = [number for _, number, _ in self._busy()]
        wait(self._inflight)  # the pool fails every future it still held
        results: list[Result] = []
        again: list[tuple[int, Item]] = []
        for future, chunk in list(self._inflight.items()):
            received = None if future.exception() is not None else _unpickled(future.result())
            if received is None:
                again.extend(chunk)
            else:
                results.extend(received)
        self._inflight.clear()
        if not any(number in self._stopped for number in busy):
            for number in busy:  # no kill of ours: one of them crashed its worker
                self._strikes[number] = self._strikes.get(number, 0) + 1
        assert self._executor is not None
        self._executor.shutdown(wait=True)
        self._executor, self._slots = None, None  # their pids are no longer ours to kill
        retry: list[tuple[int, Item]] = []
        for number, item in again:
            why = self._stopped.pop(number, None)
            if why is None and self._strikes.get(number, 0) >= 2:
                why = Stopped(None)
            if why is None:
                retry.append((number, item))
            elif self._give_up is None:
                raise RuntimeError(f"a worker process was stopped: {why}")
            else:
                self._strikes.pop(number, None)
                results.append(self._give_up(item, why))
        if retry:
            self._start()
            # Items a worker died on go alone, so that a second death names its item.
            suspects = [entry for entry in retry if entry[0] in self._strikes]
            for entry in suspects:
                self._send([entry])
            rest = [entry for entry in retry if entry[0] not in self._strikes]
            for start in range(0, len(rest), self._chunk_items):
                self._send(rest[start : start + self._chunk_items])
        return results

    def _unreceived(self, chunk: list[tuple[int, Item]]) -> list[Result]:
        """A chunk whose results could not be unpickled here (``_unpickled``): each item
        sent again alone, and an item alone given up. Left to the pool's own unpickling,
        such a result broke the pool with no worker busy, and every chunk it held was
        sent again, for ever."""
        if len(chunk) > 1:
            for entry in chunk:
                self._send([entry])
            return []
        if self._give_up is None:
            raise RuntimeError("a worker's results could not be received")
        return [self._give_up(chunk[0][1], Stopped(None, unreceived=True))]

    def _kill_workers(self) -> None:
        for pid, _, _ in self._busy():
            _kill(pid)


def _kill(pid: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):  # gone already
        os.kill(pid, signal.SIGKILL)


# The work function and this worker's slot, installed once per worker rather than
# pickled with every chunk.
_WORK: Callable[[Iterable[Any]], list[Any]] | None = None
_SLOTS: SynchronizedArray[float] | None = None
_SLOT = -1


def _initialize(
    work: Callable[[Iterable[Any]], list[Any]], slots: SynchronizedArray[float], parent: int
) -> None:
    global _WORK, _SLOTS, _SLOT  # noqa: PLW0603 - the worker's one piece of state
    _die_with(parent)
    _WORK, _SLOTS = work, slots
    with slots.get_lock():
        _SLOT = next(i for i in range(0, len(slots), 3) if slots[i] == 0)
        slots[_SLOT] = os.getpid()
    gc.set_threshold(*THRESHOLDS)  # inherited when forked, not when spawned
    gc.enable()  # forked while the main process has its collector off (``collection``)
    # Ctrl-C reaches the whole process group; the main process alone decides what to do
    # (cancel and shut down), so workers do not each print a KeyboardInterrupt traceback.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # Results travel back through the pool's pipe; a worker has nothing to print. Holding
    # the main process's standard output would keep ``check | cat`` waiting for it, and
    # a forked worker's copy of unflushed output would be written a second time at exit.
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.close(devnull)


def _die_with(parent: int) -> None:
    """End this worker when ``parent`` ends, however it ends (``kill -9`` included).

    Linux: the kernel sends SIGKILL when the process that forked this one dies (checked
    once more after asking: the parent may have died before). Strictly, when the forking
    *thread* ends: the pool is started, and shut down, by the one thread that runs the
    dispatcher. Elsewhere, a thread that watches the parent's pid."""
    if sys.platform == "linux" and _parent_death_signal(signal.SIGKILL):
        if os.getppid() != parent:
            os._exit(1)
        return

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(_WATCH_PARENT_SECONDS)
        os._exit(1)

    threading.Thread(target=watch, name="watch-parent", daemon=True).start()


def _parent_death_signal(signum: int) -> bool:
    """``prctl(PR_SET_PDEATHSIG, signum)``; False where it cannot be had."""
    import ctypes
    import ctypes.util

    pr_set_pdeathsig = 1
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        return int(libc.prctl(pr_set_pdeathsig, signum, 0, 0, 0)) == 0
    except (OSError, AttributeError):
        return False


def _unpickled(blob: bytes) -> list[Any] | None:
    """A chunk's results as its worker pickled them (``_run``); None where they cannot
    be unpickled here."""
    try:
        return list(pickle.loads(blob))
    except Exception:
        return None


def _run(chunk: list[tuple[int, Any]]) -> bytes:
    """The chunk's results, pickled here: the main process unpickles them itself
    (``_unpickled``), where a failure names the chunk (``Dispatcher._unreceived``)."""
    assert _WORK is not None, "worker used before its initializer ran"
    return dumps(_WORK(_marked(chunk)))


def _marked(chunk: list[tuple[int, Any]]) -> Iterator[Any]:
    """The chunk's items, each marked in this worker's slot as it is taken, so that the
    main process sees which item a worker is on and since when."""
    assert _SLOTS is not None
    try:
        for number, item in chunk:
            with _SLOTS.get_lock():
                _SLOTS[_SLOT + 2] = time.monotonic()
                _SLOTS[_SLOT + 1] = number
            yield item
    finally:
        with _SLOTS.get_lock():
            _SLOTS[_SLOT + 1] = -1

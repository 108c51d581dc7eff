#!/usr/bin/env python3
"""How a first run's extraction spreads over N workers: a model, for fewer cores than N.

    python bench/schedule.py WORKSPACE [--workers 2,4,8,16]

Extracts every file of WORKSPACE in this one process (the CLI with ``--jobs 1
--no-cache``, each file's extraction timed), then hands the files out as
``workers.Dispatcher`` does: chunks of up to ``CHUNK_ITEMS`` files, smaller as the files
run out (``Dispatcher._chunk_limit``), the heaviest files first in chunks spread over
every worker (``gather.Gatherer._heaviest_first``, ``Dispatcher.batch``), each chunk to
the first worker free. It prints when the last worker would be done, against the total
over N (no schedule does better) and against the same files handed out in their order
in chunks of 32 to the end (the dispatcher before those two).

What it leaves out: the messages (a fixed ``MESSAGE_SECONDS`` a chunk), the main
process (its serial part is ``run.py``'s to measure), the launch files extracted again
under their includers' arguments, and that cores share caches and clocks (on a 16-core
machine a first run took 38 s of CPU where one core took 24 s: ``latest-cores.json``).
The times are this machine's, so compare the columns, not the seconds.
"""

from __future__ import annotations

import argparse
import contextlib
import heapq
import os
import sys
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from roslint_names import cli, gather, workers
from roslint_names.model import Language

MESSAGE_SECONDS = 0.002


@dataclass(frozen=True)
class Timed:
    seconds: float
    language: Language
    size: int


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("workspace", type=Path)
    parser.add_argument("--workers", default="2,4,8,16", help="worker counts, comma-separated")
    options = parser.parse_args(argv)
    counts = [int(count) for count in options.workers.split(",")]
    files = timed_extraction(options.workspace.resolve())
    total = sum(file.seconds for file in files)
    print(f"{len(files)} files extracted in {total:.2f} s in one process")
    print(f"{'workers':>8}{'ideal s':>10}{'in order s':>12}{'now s':>8}")
    heavy, rest = gather.heaviest_first([f.language for f in files], [f.size for f in files])
    for count in counts:
        # The dispatcher before: no items expected (chunks of 32 to the end), in order.
        before = finished(files, chunks(range(len(files)), count, expected=None), count)
        now = finished(files, chunks(rest, count, expected=len(files), heavy=heavy), count)
        print(f"{count:>8}{total / count:>10.2f}{before:>12.2f}{now:>8.2f}")
    return 0


def timed_extraction(workspace: Path) -> list[Timed]:
    """Each file's extraction time, language and size, in the order of the run's files."""
    found: dict[int, Timed] = {}
    real = gather._extract_within_budget

    def timed(job: gather._Job, data: bytes) -> object:
        started = time.perf_counter()
        facts = real(job, data)
        if not job.arguments:  # a specialisation is no file of the stream
            found[job.index] = Timed(time.perf_counter() - started, job.language, len(data))
        return facts

    gather._extract_within_budget = timed  # type: ignore[assignment]
    arguments = ["check", "--exit-zero", "--no-cache", "--jobs", "1", "--format", "json", "."]
    previous = Path.cwd()
    try:
        os.chdir(workspace)
        with (
            open(os.devnull, "w") as nowhere,  # the CLI writes to the streams' buffers
            contextlib.redirect_stdout(nowhere),
            contextlib.redirect_stderr(nowhere),
        ):
            cli.main(arguments)
    finally:
        os.chdir(previous)
        gather._extract_within_budget = real
    missing = Timed(0.0, Language.CPP, 0)  # a file the extractors never saw
    return [found.get(index, missing) for index in range(max(found, default=-1) + 1)]


class _Chunking(workers.Dispatcher[int, None]):
    """The real dispatcher, its chunks recorded rather than sent."""

    def __init__(self, count: int, expected: int | None) -> None:
        super().__init__(lambda items: [], count, min_items=1, expected_items=expected)
        self.chunks: list[list[int]] = []

    def _start(self) -> None:
        self._executor = object()  # type: ignore[assignment] # no pool: nothing is sent
        self._started = True

    def _send(self, chunk: list[tuple[int, int]]) -> None:
        self.chunks.append([item for _, item in chunk])

    def _collect(self, block: bool) -> list[None]:
        return []


def chunks(
    order: Iterable[int], count: int, *, expected: int | None, heavy: Sequence[int] = ()
) -> list[list[int]]:
    """The chunks ``workers.Dispatcher`` makes for ``count`` workers of ``heavy`` (as
    ``gather.Gatherer`` hands them out, ``Dispatcher.batch``), then ``order``."""
    dispatcher = _Chunking(count, expected)
    with dispatcher.batch(len(heavy)):
        for index in heavy:
            dispatcher.put(index, 0)
    for index in order:
        dispatcher.put(index, 0)
    list(dispatcher.finish())
    return dispatcher.chunks


def finished(files: Sequence[Timed], made: Sequence[Sequence[int]], count: int) -> float:
    """When the last of ``count`` workers is done, each chunk of ``made`` going to the
    first free."""
    free = [(0.0, worker) for worker in range(count)]
    last = 0.0
    for chunk in made:
        start, worker = heapq.heappop(free)
        done = start + MESSAGE_SECONDS + sum(files[index].seconds for index in chunk)
        last = max(last, done)
        heapq.heappush(free, (done, worker))
    return last


if __name__ == "__main__":
    sys.exit(main())

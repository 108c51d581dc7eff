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
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from roslint_names import cli, gather, workers

MESSAGE_SECONDS = 0.002


@dataclass(frozen=True)
class Timed:
    seconds: float
    weight: int  # ``gather.Gatherer._heaviest_first``'s: bytes, a Python file's counted more


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
    for count in counts:
        before = finished(files, in_order(len(files)), count, heavy=0, guided=False)
        order, heavy = heaviest_first(files)
        now = finished(files, order, count, heavy=heavy, guided=True)
        print(f"{count:>8}{total / count:>10.2f}{before:>12.2f}{now:>8.2f}")
    return 0


def timed_extraction(workspace: Path) -> list[Timed]:
    """Each file's extraction time and weight, in the order of the run's files."""
    found: dict[int, Timed] = {}
    real = gather._extract_within_budget

    def timed(job: gather._Job, data: bytes) -> object:
        started = time.perf_counter()
        facts = real(job, data)
        if not job.arguments:  # a specialisation is no file of the stream
            parsed = job.language in gather._PYTHON_PARSED
            weight = len(data) * gather.PYTHON_WEIGHT if parsed else len(data)
            found[job.index] = Timed(time.perf_counter() - started, weight)
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
    return [found.get(index, Timed(0.0, 0)) for index in range(max(found, default=-1) + 1)]


def in_order(count: int) -> list[int]:
    return list(range(count))


def heaviest_first(files: Sequence[Timed]) -> tuple[list[int], int]:
    heavy = sorted(
        (index for index, file in enumerate(files) if file.weight >= gather.HEAVY_WEIGHT),
        key=lambda index: (-files[index].weight, index),
    )
    chosen = set(heavy)
    return heavy + [index for index in range(len(files)) if index not in chosen], len(heavy)


def chunks(order: Sequence[int], count: int, *, heavy: int, guided: bool) -> list[list[int]]:
    """The chunks ``workers.Dispatcher`` makes of ``order`` for ``count`` workers."""
    most = max(1, min(workers.CHUNK_ITEMS, len(order) // (count * workers.CHUNKS_EACH)))
    spread = count * workers.BATCH_CHUNKS_EACH
    made: list[list[int]] = []
    start = 0
    while start < len(order):
        if start < heavy:
            end = min(start + max(1, min(most, -(-heavy // spread))), heavy)
        else:
            left = len(order) - start
            limit = max(1, min(most, -(-left // spread))) if guided else most
            end = min(start + limit, len(order))
        made.append(list(order[start:end]))
        start = end
    return made


def finished(
    files: Sequence[Timed], order: Sequence[int], count: int, *, heavy: int, guided: bool
) -> float:
    """When the last of ``count`` workers is done, each chunk going to the first free."""
    free = [(0.0, worker) for worker in range(count)]
    last = 0.0
    for chunk in chunks(order, count, heavy=heavy, guided=guided):
        start, worker = heapq.heappop(free)
        done = start + MESSAGE_SECONDS + sum(files[index].seconds for index in chunk)
        last = max(last, done)
        heapq.heappush(free, (done, worker))
    return last


if __name__ == "__main__":
    sys.exit(main())

"""How often Python's cycle collector runs during a run: rarely.

A run allocates millions of short-lived objects (parse trees and their walks) while it
keeps every file's facts. At CPython's default thresholds (700, 10, 10) the collector
walks the kept facts again and again: on realws that was a fifth of a cold run (28.4 s,
against 22.9 s with ``THRESHOLDS``; peak memory 164 MB against 198 MB). Cycles are still
collected, only some hundred times less often. The CLI sets them for its run and worker
processes for their lives; the previous thresholds come back when the run ends, so a
program that calls the engine keeps its own.

While one file is extracted the collector does not run at all (``no_collections``): its
parse tree is acyclic and goes, by reference counting, when the file is done, so a
collection in between only walks the tree it cannot free. On realws, with
``THRESHOLDS``, that walking was still 5.7 s of a 48 s cold run.
"""

from __future__ import annotations

import gc
from collections.abc import Iterator
from contextlib import contextmanager

THRESHOLDS = (50_000, 20, 100)


@contextmanager
def no_collections() -> Iterator[None]:
    """No cyclic collection inside: the collector's state (on or off) comes back after.

    Threads may nest it (the language server extracts in two): whichever saw it on puts
    it back on, so it is never left off."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


@contextmanager
def rare_collections() -> Iterator[None]:
    previous = gc.get_threshold()
    gc.set_threshold(*THRESHOLDS)
    try:
        yield
    finally:
        gc.set_threshold(*previous)

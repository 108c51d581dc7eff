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
``THRESHOLDS``, that walking was still 5.7 s of a 48 s cold run. Nor while the engine
gathers every file's facts and builds the graph: what it makes lives until the run
ends, and holds no cycle; at 8 copies of realws the collector's passes over the facts
unpickled from the cache were 2.0 s of a 14 s re-run after one edit. Only turned back
on, the collector would walk all of that at its next young collection: it goes to the
oldest generation first (``kept_for_the_run``). Worker processes, forked meanwhile,
turn the collector back on for their lives. The same holds from the start: the walk's
files (``discover``) and the statuses a re-run is keyed by (``run_inputs``) live as long
as the run; at 8 copies of realws the young collections over them were 0.09 s of a 1.1 s
re-run with nothing changed.
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
def kept_for_the_run() -> Iterator[None]:
    """No cyclic collection inside, and what is made inside goes to the oldest generation
    after: it lives as long as the run, and left young, the first collection after would
    walk it all, and the next one again (turning the collector back on would only move
    the cost). Where objects are frozen already (a caller's own ``gc.freeze``), they and
    what is made inside stay where they are: unfreezing them is no library's business."""
    enabled = gc.isenabled()
    frozen = gc.get_freeze_count()
    gc.disable()
    try:
        yield
    finally:
        if not frozen:
            gc.freeze()  # every object, young ones too, out of the young generations...
            gc.unfreeze()  # ...and into the oldest, which a run's few collections never reach
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

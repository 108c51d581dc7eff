"""Each file's content digest, remembered with its status, so that keying a re-run does
not mean reading every file (see ``ContentDigests``)."""

from __future__ import annotations

import hashlib
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from .cache import DIGESTS, BuiltinsUnpickler, FactsCache
from .journal import Journaled
from .reading import (
    BINARY,
    UNTAKEN,
    Read,
    Status,
    Taken,
    Untaken,
    status_of,
    taken,
    too_large,
)

KEPT = 128  # digest files: a base and a journal per recently linted workspace
_FORMAT = 1


@dataclass
class ContentDigests:
    """The content digest of every file of a workspace, remembered with its status.

    A re-run must key every file by its content, and reading and hashing them all is most
    of what is left of a re-run once its result is stored. As git's index does, a file
    whose status (size, modification and change times, inode) is what it was when its
    digest was taken is not read again. A file written in the same clock tick as that
    status was taken could have changed without its status showing it (git's "racily
    clean" files): a digest is trusted only for a file last modified more than two
    seconds before its status was recorded, the others are read again.

    ``summary`` answers for one file; ``save`` keeps what was learned, atomically, in one
    base and journal per workspace (``journal``; the ``KEPT`` most recently saved files
    are kept). A wrong digest would serve a stale result: the status test and the racy
    window are what rule it out.
    """

    path: Path
    cache: FactsCache
    _known: dict[str, tuple[Status, str, bool]] = field(default_factory=dict)
    _seen: dict[str, tuple[Status, str, bool]] = field(default_factory=dict)
    # The status of each file this run keyed, as taken before its bytes were read.
    statuses: dict[str, Status | None] = field(default_factory=dict)
    _loaded: bool = False
    _present: bool = False  # the file exists (damaged or not)
    _carried: bool = False  # ``carry``
    _kept: Journaled = field(init=False)

    def __post_init__(self) -> None:
        self._kept = Journaled(self.cache, self.path, KEPT, BuiltinsUnpickler, _FORMAT)

    @classmethod
    def of(cls, cache: FactsCache, root: Path) -> ContentDigests:
        """The digests ``cache`` remembers for the files under ``root``."""
        name = hashlib.blake2b(os.fsencode(root), digest_size=8).hexdigest()
        return cls(cache.directory / DIGESTS / name, cache)

    def remembered(self) -> bool:
        """Whether an earlier run of this workspace left its digests, even none (files
        all modified just then): else no stored result of it can exist."""
        self._remembered()
        return self._present

    def carry(self) -> None:
        """This run's files are the last run's, and those whose status is as it was then
        are keyed as they were (``unchanged.Keying``): their digests stand unread, and
        the others changed. So nothing remembered is loaded: ``summary`` reads each file
        it is asked about, and ``save`` journals what it learned over what was kept."""
        self._carried = True

    def summary(
        self, path: str | Path, max_size: int, status: Status | Untaken | None = UNTAKEN
    ) -> tuple[str | None, str, str | None]:
        """The file's content digest, else why it cannot be read; and why it is skipped
        (as ``read_file`` says it for the same file). ``status``: the file's, where the
        caller took it already (``UNTAKEN``: take it here)."""
        name = os.fspath(path)
        signature = status_of(path) if isinstance(status, Untaken) else status
        self.statuses[name] = signature
        if signature is not None:
            if signature[0] > max_size:
                return None, "", too_large(signature[0], max_size)
            known = None if self._carried else self._remembered().get(name)
            if known is not None and known[0] == signature:
                self._seen[name] = known
                return (None, "", BINARY) if known[2] else (known[1], "", None)
        found, _ = taken(path, max_size, signature)
        self.record(name, found)
        return found.content, found.error, found.skip

    def summaries(
        self, paths: Sequence[str], max_size: int, statuses: Sequence[Status | Untaken | None]
    ) -> list[tuple[str | None, str, str | None]]:
        """``summary`` of each of ``paths`` with its status: those whose digest is
        remembered under the status they have, nearly all of a re-run's, answered here in
        one loop (a call each cost 0.1 s of a re-run at 77,000 files)."""
        remembered, seen, taken = self._remembered(), self._seen, self.statuses
        found: list[tuple[str | None, str, str | None]] = []
        for path, status in zip(paths, statuses, strict=True):
            known = remembered.get(path)
            if (
                known is None
                or known[0] != status
                or known[2]  # binary: ``summary`` says so
                or status is None
                or isinstance(status, Untaken)
                or status[0] > max_size
            ):
                found.append(self.summary(path, max_size, status))
            else:
                taken[path] = status
                seen[path] = known
                found.append((known[1], "", None))
        return found

    def record(self, name: str, found: Taken) -> None:
        """Remember what reading the file at ``name`` found (``reading.taken``), here or
        in the worker process that read it."""
        status, content = found.status, found.content
        self.statuses[name] = status
        if status is not None and not found.racy and (content is not None or found.skip == BINARY):
            self._seen[name] = (status, content or "", content is None)

    def read(self, path: str | Path, max_size: int) -> tuple[Read, str | None]:
        """``read_file``, and the content digest of what it read, remembered for the next
        run."""
        found, data = taken(path, max_size)
        self.record(os.fspath(path), found)
        return (data, found.error, found.skip), found.content

    def _remembered(self) -> dict[str, tuple[Status, str, bool]]:
        if not self._loaded:
            self._known, self._loaded = self._load(), True
        return self._known

    def save(self) -> None:
        """Keep the digests of the files this run saw (only those: deleted files go): those
        that changed, as a journal (``journal``); where the run carried the rest
        (``carry``), those it learned, over the rest as kept."""
        if self._carried:
            if self._kept.extend((self._seen,)):
                return
            self._kept.save(({**self._remembered(), **self._seen},))
            return
        self._remembered()
        self._kept.save((self._seen,))

    def _load(self) -> dict[str, tuple[Status, str, bool]]:
        loaded = self._kept.load(1)  # None: absent, unreadable or damaged: all read again
        self._present = loaded is not None or self.path.exists()
        return {} if loaded is None else loaded[0]

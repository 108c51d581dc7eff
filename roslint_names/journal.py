"""The cache's large bookkeeping dicts (each file's digest, each directory's listing) kept as
a base file and a journal of what changed since the base was written: a run that changed a
few of 77,000 entries writes those, not all of them (0.1 s each for the digests and the
listings at 8 copies of the benchmark's workspace, after an edit).

Every entry holds the status it was taken with, which its reader compares with the status
now: an entry older or newer than the others is never wrong, only missed and taken again.
So a journal is read only over the base it was written for (each base has a random token,
which its journals name), a base or a journal evicted alone loses entries, never changes
one, and a crash between writing a new base and removing the old journal leaves a journal
that names another base. A removed entry is journaled as None. The journal grows until it
holds a quarter as many entries as the whole, then the whole is written as a new base.
Both files are written atomically through the facts cache and read with the caller's
unpickler; one that cannot be read is none.
"""

from __future__ import annotations

import contextlib
import os
import pickle
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import IO, Any

from .cache import FactsCache
from .reading import open_regular

# The dicts kept, in the order the caller gives them (the listings keep three).
Sections = tuple[dict[Any, Any], ...]

_ABSENT = object()
_PROTOCOL = pickle.HIGHEST_PROTOCOL
_JOURNAL_SHARE = 4  # the whole is written again once the journal holds 1/4 of its entries


class Journaled:
    """The sections of one bookkeeping file, as last saved, and saving them again."""

    def __init__(
        self,
        cache: FactsCache,
        path: Path,
        kept: int,
        unpickler: Callable[[IO[bytes]], pickle.Unpickler],
        version: int,
    ) -> None:
        self._cache = cache
        self._path = path
        self._journal_path = path.with_name(f"{path.name}-journal")
        self._kept = kept
        self._unpickler = unpickler
        self._version = version
        self._token: str | None = None  # the base's, once one was read
        self._loaded: Sections | None = None
        self._journaled: Sections = ()

    def load(self, count: int) -> Sections | None:
        """The ``count`` sections as last saved; None where there is no base to read."""
        base = self._read(self._path, count)
        if base is None:
            return None
        token, sections = base
        journal = self._read(self._journal_path, count)
        if journal is not None and journal[0] == token:
            self._journaled = journal[1]
            for section, changes in zip(sections, self._journaled, strict=True):
                for key, value in changes.items():
                    if value is None:
                        section.pop(key, None)
                    else:
                        section[key] = value
        self._token, self._loaded = token, sections
        return sections

    def save(self, sections: Sections) -> None:
        """Keep ``sections``: the journal of what differs from the sections loaded, or the
        whole where none were, or where that journal would be too long. Nothing when
        nothing differs. ``sections`` must not be the dicts ``load`` gave."""
        loaded = self._loaded
        if loaded is None or self._token is None or len(loaded) != len(sections):
            self._write_base(sections)
            return
        changes = tuple(_changes(old, new) for old, new in zip(loaded, sections, strict=True))
        if not any(changes):
            return
        journal = tuple(
            {**before, **now}
            for before, now in zip(self._journaled or [{}] * len(sections), changes, strict=True)
        )
        if sum(map(len, journal)) * _JOURNAL_SHARE > sum(map(len, sections)):
            self._write_base(sections)
            return
        blob = pickle.dumps((self._version, self._token, journal), _PROTOCOL)
        self._cache.write_newest(self._journal_path, blob, self._kept)

    def _write_base(self, sections: Sections) -> None:
        token = os.urandom(8).hex()
        whole = (self._version, token, sections)  # pickled into the file, not held first
        self._cache.write_newest(
            self._path, partial(pickle.dump, whole, protocol=_PROTOCOL), self._kept
        )
        with contextlib.suppress(OSError):  # none; else left naming a base that is gone
            self._journal_path.unlink()

    def _read(self, path: Path, count: int) -> tuple[str, Sections] | None:
        try:
            with open_regular(path) as stream:
                loaded = self._unpickler(stream).load()
        except Exception:  # absent, unreadable or damaged
            return None
        if not (isinstance(loaded, tuple) and len(loaded) == 3 and loaded[0] == self._version):
            return None
        _, token, sections = loaded
        if not (isinstance(token, str) and isinstance(sections, tuple) and len(sections) == count):
            return None
        if not all(isinstance(section, dict) for section in sections):
            return None
        return token, sections


def _changes(old: dict[Any, Any], new: dict[Any, Any]) -> dict[Any, Any]:
    """What makes ``old`` into ``new``: each entry added or changed, None for each removed."""
    changed = {key: value for key, value in new.items() if old.get(key, _ABSENT) != value}
    changed.update(dict.fromkeys(old.keys() - new.keys()))
    return changed

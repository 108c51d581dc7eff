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
Each file starts with a head that gives the base's token and its count of entries, so
that a run which knows every entry it did not learn stands journals what it learned
without loading the base (``extend``: ``digests`` after an edit, 81,000 entries not
loaded nor compared at 8 copies). Both files are written atomically through the facts
cache and read with the caller's unpickler; one that cannot be read is none.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import struct
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

from .cache import FactsCache
from .reading import open_regular

# The dicts kept, in the order the caller gives them (the listings keep three).
Sections = tuple[dict[Any, Any], ...]

_ABSENT = object()
_PROTOCOL = pickle.HIGHEST_PROTOCOL
_JOURNAL_SHARE = 4  # the whole is written again once the journal holds 1/4 of its entries
# Each file's head, before the pickled sections: a mark, the caller's version, the base's
# token, and the count of entries the file holds: what ``extend`` reads of the base.
_HEAD = struct.Struct("<8sH16sQ")
_MARK = b"rnjourna"
_TOKEN_BYTES = 16


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
        self._write_journal(self._token, journal)

    def extend(self, additions: Sections) -> bool:
        """Journal ``additions`` (entries added or changed, none removed) over the base as
        it was last saved, without loading it: what a run that knows every other entry
        stands saves (``digests``: the files of the last run whose status is as kept).
        False, writing nothing, where there is no base, or the journal would grow past
        its share: the caller loads and saves."""
        if not any(additions):
            return True
        head = self._head(self._path)
        if head is None:
            return False
        token, entries = head
        journal = self._read(self._journal_path, len(additions))
        before = journal[1] if journal is not None and journal[0] == token else None
        merged = tuple(
            {**earlier, **now}
            for earlier, now in zip(before or [{}] * len(additions), additions, strict=True)
        )
        if sum(map(len, merged)) * _JOURNAL_SHARE > entries:
            return False
        self._write_journal(token, merged)
        return True

    def _write_journal(self, token: str, journal: Sections) -> None:
        head = _HEAD.pack(_MARK, self._version, token.encode("ascii"), sum(map(len, journal)))
        blob = head + pickle.dumps(journal, _PROTOCOL)
        self._cache.write_newest(self._journal_path, blob, self._kept)

    def _write_base(self, sections: Sections) -> None:
        token = os.urandom(_TOKEN_BYTES // 2).hex()
        head = _HEAD.pack(_MARK, self._version, token.encode("ascii"), sum(map(len, sections)))

        def write(stream: IO[bytes]) -> None:
            stream.write(head)
            pickle.dump(sections, stream, protocol=_PROTOCOL)  # into the file, not held first

        self._cache.write_newest(self._path, write, self._kept)
        with contextlib.suppress(OSError):  # none; else left naming a base that is gone
            self._journal_path.unlink()

    def _head(self, path: Path) -> tuple[str, int] | None:
        """The token of the file at ``path`` and the count of entries it holds, if it is
        one of this version."""
        try:
            with open_regular(path) as stream:
                return self._token_of(stream.read(_HEAD.size))
        except OSError:
            return None

    def _token_of(self, head: bytes) -> tuple[str, int] | None:
        if len(head) != _HEAD.size:
            return None
        mark, version, token, entries = _HEAD.unpack(head)
        if mark != _MARK or version != self._version or not token.isascii():
            return None
        return token.decode("ascii"), entries

    def _read(self, path: Path, count: int) -> tuple[str, Sections] | None:
        try:
            with open_regular(path) as stream:
                head = self._token_of(stream.read(_HEAD.size))
                if head is None:
                    return None
                sections = self._unpickler(stream).load()
        except Exception:  # absent, unreadable or damaged
            return None
        if not (isinstance(sections, tuple) and len(sections) == count):
            return None
        if not all(isinstance(section, dict) for section in sections):
            return None
        return head[0], sections


def _changes(old: dict[Any, Any], new: dict[Any, Any]) -> dict[Any, Any]:
    """What makes ``old`` into ``new``: each entry added or changed, None for each removed."""
    changed = {key: value for key, value in new.items() if old.get(key, _ABSENT) != value}
    changed.update(dict.fromkeys(old.keys() - new.keys()))
    return changed

"""The last run's key, kept with the status of everything it was made from: a re-run that
finds every one of them as it was has that key without keying a file.

``run_inputs`` keys a run by each file's content digest (read from ``digests`` where the
file's status is unchanged) and by what the packages say of it, which costs some
microseconds a file: 0.7 s at 77,000 files, with the plugin names read from every
manifest first. Yet when nothing changed, each of those steps gives what it gave last
time. So the key is kept here with:

- the identity of what is not a file's content: the code and settings fingerprints, the
  files checked and all the others, where they are and how they are shown, how many are
  reported, the fallback generation and the environment's Python 2 choice;
- the status of each checked file and each ``.srv`` file, taken before its bytes were
  read (``ContentDigests.statuses``);
- the status of each ``package.xml`` looked for (none where there was none) and of each
  plugin description, taken before reading (``PackageGenerations.statuses``): a manifest
  added, removed or edited shows there, while the directories it is looked for in
  (a home directory, ``/tmp``) may change for other reasons all they like.

A re-run whose identity and statuses are all equal is keyed by the kept key. A status
taken within ``reading.RACY_NANOSECONDS`` of a change is never kept
(an edit in the same clock tick would not show: git's "racily clean" files); such a run
keeps nothing, and the next is keyed file by file. The file is builtins only, read with
an unpickler that resolves no class; one that cannot be read is no key.
"""

from __future__ import annotations

import hashlib
import os
import pickle
import time
from collections.abc import Mapping, Sequence
from pathlib import Path

from .cache import BuiltinsUnpickler, FactsCache
from .reading import Status, is_racy, open_regular, status_of

KEYS = "keys"  # their directory in the facts cache: one file per workspace
KEPT = 64
_FORMAT = 1


class KeptKey:
    """The key kept for one workspace, and what it was made from."""

    def __init__(self, cache: FactsCache, root: Path) -> None:
        name = hashlib.blake2b(os.fsencode(root), digest_size=8).hexdigest()
        self._path = cache.directory / KEYS / name
        self._cache = cache
        self.started = time.time_ns()  # before any status of this run is taken

    def key(self, identity: str, statuses: Sequence[Status | None]) -> str | None:
        """The kept key, if it was kept for ``identity`` and every status it was kept with
        is the status now (``statuses``: the files', in the order they were kept)."""
        kept = self._load()
        if kept is None:
            return None
        kept_identity, key, file_statuses, package_paths, package_statuses = kept
        if kept_identity != identity or list(statuses) != file_statuses:
            return None
        if [status_of(path) for path in package_paths] != package_statuses:
            return None
        return key

    def keep(
        self,
        identity: str,
        key: str,
        file_statuses: Sequence[Status | None],
        package_statuses: Mapping[str, Status | None],
    ) -> None:
        """Keep ``key`` with what it was made from, unless a status is too recent to say
        that nothing changed after it was taken."""
        statuses = [*file_statuses, *package_statuses.values()]
        if any(s is not None and is_racy(s[1], s[2], self.started) for s in statuses):
            return
        paths = tuple(package_statuses)
        kept = (_FORMAT, identity, key, list(file_statuses), paths, list(package_statuses.values()))
        self._cache.write_newest(self._path, pickle.dumps(kept, pickle.HIGHEST_PROTOCOL), KEPT)

    def _load(self) -> _Kept | None:
        try:
            with open_regular(self._path) as stream:
                loaded = BuiltinsUnpickler(stream).load()
        except Exception:  # absent, unreadable or damaged: the run is keyed file by file
            return None
        if not (isinstance(loaded, tuple) and len(loaded) == 6 and loaded[0] == _FORMAT):
            return None
        _, identity, key, file_statuses, paths, package_statuses = loaded
        shapes = (str, str, list, tuple, list)
        if not all(map(isinstance, loaded[1:], shapes)):
            return None
        return identity, key, file_statuses, paths, package_statuses


# identity, key, file statuses, package paths, their statuses
_Kept = tuple[str, str, list[Status | None], tuple[str, ...], list[Status | None]]

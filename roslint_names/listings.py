"""What the walk found in each directory, kept with the directory's status, so that a
re-run lists again only the directories that changed (git's "untracked cache").

Adding, removing or renaming an entry changes its directory's modification time; editing a
file does not, and need not: the walk only asks which files there are and what their names
say. What else a directory's verdict depends on is checked each time: its ``.gitignore``
(whose edit leaves the directory's time alone) by its own status, the ones above the
named directory likewise, the ``exclude`` patterns by the file the listings are kept in
(one per named directory and patterns), and every symbolic link by following it again
(its target may change without its directory). A file whose content says its language
(``discover._Sniff``) is kept with its own status and asked again when that changed.

A status taken within ``reading.RACY_NANOSECONDS`` of a change is not trusted (git's
"racily clean" entries): a change in the same clock tick would not show. Such a
directory is listed again the next time; such a ``.gitignore`` makes its subtree walked
whole.

The listings are kept as a base and a journal of the directories listed again since
(``journal``), pickled builtins and ``Listed`` only, read with an unpickler that resolves
no other class, and written atomically through the facts cache; one that cannot be read
is an empty one (everything listed again), never an error.
"""

from __future__ import annotations

import hashlib
import os
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NamedTuple

from .cache import BuiltinsUnpickler, FactsCache, code_fingerprint
from .journal import Journaled
from .reading import Status, is_racy, status_from

LISTINGS = "listings"  # their directory in the facts cache, one file per named directory
KEPT = 128  # listing files: a base and a journal per named directory and patterns
_FORMAT = 4
_ANCESTORS = "ancestors"  # the one key of the section that keeps them

DirectoryStatus = tuple[int, int, int]  # mtime_ns, ctime_ns, inode
FileStatus = Status  # a file's, as ``reading.status_of`` takes it


class Listed(NamedTuple):
    """One directory as the walk left it."""

    status: DirectoryStatus | None  # None: taken too soon after a change to be trusted
    gitignore: FileStatus | None  # its ``.gitignore``'s, None when it has none
    gitignore_valid: bool  # that file was read and said nothing (``discover._IgnoreRules``)
    stop: bool  # it holds an ignore marker: nothing below it is walked
    directories: tuple[str, ...]  # the subdirectories walked, by name
    files: tuple[tuple[str, str], ...]  # the files selected: name, what the name says
    links: tuple[tuple[str, str], ...]  # the links selected: followed again each time
    # An entry named ``package.xml`` (in any case), of any kind, ignored or not: where there
    # is none, no package lookup takes the status of one (``generation.PackageGenerations``).
    manifest: bool


class Listings:
    """The kept listings of one named directory's walk, and the new ones it makes."""

    def __init__(self, path: Path, cache: FactsCache) -> None:
        self.path = path
        self._kept = Journaled(cache, path, KEPT, _ListingsUnpickler, _FORMAT)
        self.started = time.time_ns()  # before any status is taken
        self.walked = 0  # directories the walk entered (``discover._Walker``)
        # Files whose content was asked what it says (``sniffed``), and those of them whose
        # status was too recent to vouch for what it said.
        self._sniffs = 0
        self._unsure: list[str] = []
        self._known: dict[str, Listed] = {}
        self._known_ancestors: tuple[tuple[str, FileStatus | None], ...] | None = None
        self._known_sniffed: dict[str, tuple[FileStatus, str]] = {}
        self._listed: dict[str, Listed] = {}
        self._ancestors: tuple[tuple[str, FileStatus | None], ...] = ()
        self._sniffed: dict[str, tuple[FileStatus, str]] = {}
        self._load()

    @classmethod
    def of(
        cls, cache: FactsCache, top: str, exclude: Sequence[str], exclude_root: Path
    ) -> Listings:
        """The listings kept in ``cache`` for ``top`` walked under ``exclude`` by this
        code (the facts cache's directory is named by the extractors' code only: a walk
        that selects other files must not replay what an older one kept)."""
        return cls(cls.path_of(cache, top, exclude, exclude_root), cache)

    @staticmethod
    def path_of(cache: FactsCache, top: str, exclude: Sequence[str], exclude_root: Path) -> Path:
        """Where ``of`` keeps them."""
        identity = "\0".join([code_fingerprint(), top, os.fspath(exclude_root), *exclude])
        name = hashlib.blake2b(os.fsencode(identity), digest_size=8).hexdigest()
        return cache.directory / LISTINGS / name

    def whole(
        self,
    ) -> (
        tuple[
            tuple[tuple[str, FileStatus | None], ...],
            dict[str, Listed],
            list[tuple[str, FileStatus | None]],
        ]
        | None
    ):
        """What this walk stood on, where it may be taken whole (``walks``): the
        ``.gitignore`` files above it, every directory it entered, listed or replayed,
        with the status it was taken with (None: too recent to vouch for it), none holding
        a link followed, and every file whose content said its language, with its status
        (None alike). None where a ``.gitignore`` above it had a status too recent, or a
        directory was not kept (its ``.gitignore``'s status was)."""
        listed = self._listed
        if self.walked != len(listed) or self._sniffs != len(self._sniffed) + len(self._unsure):
            return None
        if any(status is None and os.path.lexists(path) for path, status in self._ancestors):
            return None
        if any(listing.links for listing in listed.values()):
            return None
        sniffed: list[tuple[str, FileStatus | None]] = [
            (path, status) for path, (status, _) in self._sniffed.items()
        ]
        sniffed.extend((path, None) for path in self._unsure)
        return self._ancestors, listed, sniffed

    def trusts_ancestors(self, gitignores: Sequence[str]) -> bool:
        """Record the status of the ``.gitignore`` files above the named directory; whether
        they are as they were (else no listing below is trusted)."""
        self._ancestors = tuple((path, self.file_status(path)) for path in gitignores)
        return self._known_ancestors == self._ancestors and all(
            status is not None or not os.path.lexists(path) for path, status in self._ancestors
        )

    def unchanged(self, directory: str, status: DirectoryStatus | None) -> Listed | None:
        """The kept listing of ``directory`` if its status is the one it was kept with."""
        kept = self._known.get(directory)
        return kept if kept is not None and status is not None and kept.status == status else None

    def previous(self, directory: str) -> Listed | None:
        return self._known.get(directory)

    def keep(self, directory: str, listed: Listed) -> None:
        self._listed[directory] = listed

    def directory_status(self, directory: str) -> DirectoryStatus | None:
        """The status of ``directory``, None when it cannot be taken or is too recent."""
        found = self._trusted(directory)
        return None if found is None else (found.st_mtime_ns, found.st_ctime_ns, found.st_ino)

    def file_status(self, path: str) -> FileStatus | None:
        """The status of the file at ``path``, None when it cannot be taken or is too
        recent."""
        found = self._trusted(path)
        return None if found is None else status_from(found)

    def _trusted(self, path: str) -> os.stat_result | None:
        try:
            found = os.stat(path)
        except OSError:
            return None
        return None if is_racy(found.st_mtime_ns, found.st_ctime_ns, self.started) else found

    def sniffed(self, path: str) -> tuple[FileStatus | None, str | None]:
        """The file's status, and what its content said when it had that status."""
        self._sniffs += 1
        status = self.file_status(path)
        if status is None:
            self._unsure.append(path)
        kept = self._known_sniffed.get(path)
        if status is not None and kept is not None and kept[0] == status:
            self._sniffed[path] = kept
            return status, kept[1]
        return status, None

    def keep_sniffed(self, path: str, status: FileStatus | None, said: str) -> None:
        if status is not None:
            self._sniffed[path] = (status, said)

    def save(self) -> None:
        """Keep what this walk listed (only that: a deleted directory goes), if it differs:
        the listings that changed, as a journal (``journal``)."""
        self._kept.save(({_ANCESTORS: self._ancestors}, self._listed, self._sniffed))

    def _load(self) -> None:
        loaded = self._kept.load(3)
        if loaded is None:  # absent, unreadable, damaged or of another shape: list again
            return
        ancestors, self._known, self._known_sniffed = loaded
        self._known_ancestors = ancestors.get(_ANCESTORS)


class _ListingsUnpickler(BuiltinsUnpickler):
    """Builtins and ``Listed`` only."""

    def find_class(self, module: str, name: str) -> Any:
        if (module, name) == (__name__, "Listed"):
            return Listed
        return super().find_class(module, name)

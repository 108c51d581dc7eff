"""A named directory's last walk kept whole: a re-run that finds every status the walk
stood on as it was takes the files it found without walking.

The listings (``listings``) spare a re-run the listing of directories that did not
change, yet it still replays each of them, and decides each file again (77,000 at 8
copies of the benchmark's workspace: 0.55 s a run, with loading and saving them). When
nothing changed, every answer is the last one. So a walk that needed no warning and
followed no symbolic link (``Listings.whole``) is kept with the statuses it stood on: of
every directory walked (an entry added, removed or renamed changes its directory's), of
each ``.gitignore`` in them and above the named directory (an edit of one leaves its
directory alone), and of each file whose content said its language
(``discover._Sniff``). A run that takes each of them again and finds it equal takes the
files as they were found, shown as they were shown (the current directory is kept too),
and the directories that hold no ``package.xml``. A status too recent to vouch for what
it saw (``reading.is_racy``) is kept as none. Up to ``MOST_CHANGED`` directories of
another status (or none) are looked at again: the walk is taken where they hold the
entries it chose and no other it could (a file saved by a rename, or checked out anew,
changes its directory's status, not what a walk finds); a sniffed file of another status
is asked again what its content says. Anything else walks, and keeps what it found for
the next run.

The file is kept beside the listings, builtins only, read with an unpickler that resolves
no class, written atomically through the facts cache; one that cannot be read is none.
"""

from __future__ import annotations

import os
import pickle
from collections.abc import Callable, Sequence
from functools import partial
from pathlib import Path
from typing import NamedTuple

from .cache import BuiltinsUnpickler, FactsCache
from .listings import KEPT, DirectoryStatus, FileStatus, Listings
from .reading import open_regular, status_of

_FORMAT = 1
# Directories whose status changed since the kept walk that are looked at again, at most:
# beyond, the named directory is walked.
MOST_CHANGED = 16
_SUFFIX = ".walked"
_PROTOCOL = pickle.HIGHEST_PROTOCOL
# A file found: where it is, how it is shown, its language (``Language``'s value).
Found = tuple[str, str, str]


class Taken(NamedTuple):
    """What a kept walk found, and where to walk again."""

    found: list[Found]
    without_manifest: list[str]  # the directories it found no ``package.xml`` in
    # Directories that hold other entries than the walk chose now (none below another):
    # walked again, what the kept walk found below them left out.
    again: list[str]
    gitignores: list[str]  # the ``.gitignore`` files in the directories it walked


class Walk(NamedTuple):
    """How a walk chooses (``discover``'s), for what a kept walk stood on that changed."""

    may_choose: Callable[[str], bool]  # a file of a name, or chooses otherwise for it
    passed_over: Callable[[str], bool]  # never enters a directory of a name
    said: Callable[[str], str]  # a file's language by its name and content ("": none)


def taken(
    listings_path: Path,
    prefix: str,
    gitignores_above: Sequence[str],
    walk: Walk,
) -> Taken | None:
    """The files the kept walk found and the directories it found without a
    ``package.xml``, if every status it stood on is as it was, the ``.gitignore`` files
    above the named directory the same ones, and the current directory ``prefix``. A few
    directories whose status changed are looked at again (``_same_entries``: a file
    replaced changes its directory's status, not what the walk finds), and a file whose
    content said its language is asked again where its status changed, both as ``walk``
    chooses."""
    kept = _read(listings_path.with_name(listings_path.name + _SUFFIX))
    if kept is None:
        return None
    (kept_prefix, ancestors, directories, statuses, files_stood_on, without, found) = kept
    if kept_prefix != prefix or [path for path, _ in ancestors] != list(gitignores_above):
        return None
    for path, status in ancestors:
        if status_of(path) != status:
            return None
    changed: list[str] = []
    for directory, kept_status in zip(directories, statuses, strict=True):
        try:
            now = os.stat(directory)
        except OSError:
            return None
        if kept_status is None or (now.st_mtime_ns, now.st_ctime_ns, now.st_ino) != kept_status:
            changed.append(directory)  # or its status was too recent to vouch for it
            if len(changed) > MOST_CHANGED:
                return None
    languages: dict[str, str] | None = None
    for path, status in files_stood_on:
        if status is not None and status_of(path) == status:
            continue
        if os.path.basename(path) == ".gitignore":
            return None  # what it ignores may have changed: walked
        if languages is None:
            languages = {location: language for location, _, language in found}
        if walk.said(path) != languages.get(path, ""):
            return None
    again: list[str] = []
    if changed:
        bases = [directory.rstrip(os.sep) + os.sep for directory in changed]
        entered = _names_in(bases, directories)
        chosen = _names_in(
            bases, [*(path for path, _, _ in found), *(path for path, _ in files_stood_on)]
        )
        again = [
            directory
            for directory, base in zip(changed, bases, strict=True)
            if not _same_entries(directory, entered[base], chosen[base], walk)
        ]
    gitignores = [path for path, _ in files_stood_on if os.path.basename(path) == ".gitignore"]
    return Taken(found, without, _topmost(again), gitignores)


def _topmost(directories: list[str]) -> list[str]:
    """``directories`` less those below another of them."""
    ordered = sorted(directories)
    return [
        directory
        for index, directory in enumerate(ordered)
        if not any(directory.startswith(other.rstrip(os.sep) + os.sep) for other in ordered[:index])
    ]


def _names_in(bases: Sequence[str], paths: Sequence[str]) -> dict[str, set[str]]:
    """The names of the entries among ``paths`` right in each directory of ``bases``
    (each ending in a separator), by base: one pass over the paths, where a pass for
    each directory looked at again cost a re-run 0.013 s per directory at 8 copies of the
    benchmark's workspace (109,000 paths), up to ``MOST_CHANGED`` of them."""
    below: dict[str, set[str]] = {base: set() for base in bases}
    for path in paths:
        cut = path.rfind(os.sep) + 1
        names = below.get(path[:cut])
        if names is not None:
            names.add(path[cut:])
    return below


def _same_entries(directory: str, entered: set[str], files: set[str], walk: Walk) -> bool:
    """Whether ``directory`` holds the subdirectories the kept walk entered (``entered``,
    by name) and the files it chose (or asked the content of, or whose ``.gitignore`` it
    read) in it (``files``), of the same kinds, and no other entry the walk could enter
    or choose: then a walk finds in it what the kept one found (the files' own statuses
    are checked apart). Takes the sets, and empties them."""
    try:
        entries = list(os.scandir(directory))
    except OSError:
        return False
    for entry in entries:
        name = entry.name
        if entry.is_symlink():
            if name in entered or name in files or walk.may_choose(name):
                return False
        elif entry.is_dir():
            if name not in entered and not walk.passed_over(name):
                return False  # one the walk enters, or one an ignore rule passes over
            entered.discard(name)
        elif name in files and entry.is_file():
            files.discard(name)
        elif name in files or walk.may_choose(name):
            return False  # a file the walk may choose, or one an ignore rule passes over
    return not entered and not files


def keep(cache: FactsCache, listings: Listings, prefix: str, found: list[Found]) -> None:
    """Keep the walk ``listings`` made, which found ``found``, if it may be taken whole
    (``Listings.whole``)."""
    whole = listings.whole()
    if whole is None:
        return
    ancestors, listed, sniffed = whole
    directories = tuple(listed)
    statuses = tuple(listing.status for listing in listed.values())
    gitignores = [
        (os.path.join(directory, ".gitignore"), listing.gitignore)
        for directory, listing in listed.items()
        if listing.gitignore is not None
    ]
    stood_on = (*gitignores, *sniffed)
    without = [directory for directory, listing in listed.items() if not listing.manifest]
    kept = (_FORMAT, prefix, ancestors, directories, statuses, stood_on, without, found)
    path = listings.path.with_name(listings.path.name + _SUFFIX)
    cache.write_newest(path, partial(pickle.dump, kept, protocol=_PROTOCOL), KEPT)


def _read(
    path: Path,
) -> (
    tuple[
        str,
        tuple[tuple[str, FileStatus | None], ...],
        tuple[str, ...],
        tuple[DirectoryStatus | None, ...],
        tuple[tuple[str, FileStatus | None], ...],
        list[str],
        list[Found],
    ]
    | None
):
    try:
        with open_regular(path) as stream:
            loaded = BuiltinsUnpickler(stream).load()
    except Exception:  # absent, unreadable or damaged: the directory is walked
        return None
    if not (isinstance(loaded, tuple) and len(loaded) == 8 and loaded[0] == _FORMAT):
        return None
    _, prefix, ancestors, directories, statuses, stood_on, without, found = loaded
    shapes = ((prefix, str), (ancestors, tuple), (directories, tuple), (statuses, tuple))
    more = ((stood_on, tuple), (without, list), (found, list))
    if not all(isinstance(value, kind) for value, kind in (*shapes, *more)):
        return None
    if len(directories) != len(statuses):
        return None
    return prefix, ancestors, directories, statuses, stood_on, without, found

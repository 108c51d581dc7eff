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

What a directory looked at again, or a file asked again, vouches for is kept too
(``refresh``): its status now, where the walk takes it as it was and the status is not too
recent. Beside the walk, in a small file of its own naming the walk it amends (a token
each kept walk draws): a run after a file saved by a rename then finds its directory as
kept, where it looked at it again in every run until ``MOST_CHANGED`` such directories
made it walk the whole tree (at 8 copies of the benchmark's workspace, with ten such
directories, 0.05 s of every run's discovery, and a whole walk 1.0 to 1.3 s); rewriting
the walk's 20 MB for each would cost more than it saves.

Both files are kept beside the listings, builtins only, read with an unpickler that
resolves no class, written atomically through the facts cache; one that cannot be read
is none.
"""

from __future__ import annotations

import os
import pickle
import time
from collections.abc import Callable, Sequence
from functools import partial
from pathlib import Path
from typing import NamedTuple

from .cache import BuiltinsUnpickler, FactsCache
from .listings import KEPT, DirectoryStatus, FileStatus, Listings
from .reading import is_racy, open_regular, status_of

_FORMAT = 2
# Directories whose status changed since the kept walk that are looked at again, at most:
# beyond, the named directory is walked.
MOST_CHANGED = 16
_SUFFIX = ".walked"
_AMENDED_SUFFIX = ".walked-statuses"  # what the walk stood on, vouched for since (``refresh``)
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
    # The statuses of directories and files it stood on that changed since it was kept
    # while what they vouch for did not (the amendments kept, with this run's), for
    # ``refresh``; None where this run vouched for none anew.
    amended: Amended | None = None


class Amended(NamedTuple):
    """Statuses a kept walk stood on, as later runs found them vouching for the same."""

    token: str  # the kept walk's (``keep``): an amendment of another walk is none
    directories: dict[str, DirectoryStatus]
    files: dict[str, FileStatus]


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
    started = time.time_ns()  # before any status is taken: what is too recent after it
    kept = _read(listings_path.with_name(listings_path.name + _SUFFIX))
    if kept is None:
        return None
    (token, kept_prefix, ancestors, directories, statuses, files_stood_on, without, found) = kept
    if kept_prefix != prefix or [path for path, _ in ancestors] != list(gitignores_above):
        return None
    for path, status in ancestors:
        if status_of(path) != status:
            return None
    amended = _read_amended(_amended_path(listings_path), token)
    if amended.directories:
        statuses = tuple(
            amended.directories.get(d, s) for d, s in zip(directories, statuses, strict=True)
        )
    if amended.files:
        files_stood_on = tuple((path, amended.files.get(path, s)) for path, s in files_stood_on)
    changed: list[str] = []
    vouching: dict[str, DirectoryStatus] = {}  # the changed ones' statuses, where not too recent
    for directory, kept_status in zip(directories, statuses, strict=True):
        try:
            now = os.stat(directory)
        except OSError:
            return None
        seen = (now.st_mtime_ns, now.st_ctime_ns, now.st_ino)
        if kept_status is None or seen != kept_status:
            changed.append(directory)  # or its status was too recent to vouch for it
            if len(changed) > MOST_CHANGED:
                return None
            if not is_racy(now.st_mtime_ns, now.st_ctime_ns, started):
                vouching[directory] = seen
    languages: dict[str, str] | None = None
    asked: dict[str, FileStatus] = {}  # files asked again that say the same, by status now
    for path, status in files_stood_on:
        now_status = status_of(path)
        if status is not None and now_status == status:
            continue
        if os.path.basename(path) == ".gitignore":
            return None  # what it ignores may have changed: walked
        if languages is None:
            languages = {location: language for location, _, language in found}
        if walk.said(path) != languages.get(path, ""):
            return None
        if now_status is not None and not is_racy(now_status[1], now_status[2], started):
            asked[path] = now_status
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
    for directory in again:
        vouching.pop(directory, None)  # what it holds now is walked, not what was kept
    news = None
    if vouching or asked:
        news = Amended(token, {**amended.directories, **vouching}, {**amended.files, **asked})
    return Taken(found, without, _topmost(again), gitignores, news)


def refresh(cache: FactsCache, listings_path: Path, amended: Amended) -> None:
    """Keep the statuses a run found the kept walk at ``listings_path`` standing on
    (``Taken.amended``), so that the next run takes them as the walk's."""
    kept = (_FORMAT, amended.token, amended.directories, amended.files)
    cache.write_newest(
        _amended_path(listings_path), partial(pickle.dump, kept, protocol=_PROTOCOL), KEPT
    )


def _amended_path(listings_path: Path) -> Path:
    return listings_path.with_name(listings_path.name + _AMENDED_SUFFIX)


def _read_amended(path: Path, token: str) -> Amended:
    """The amendments kept for the walk of ``token``; none where they are another walk's,
    or cannot be read."""
    none = Amended(token, {}, {})
    try:
        with open_regular(path) as stream:
            loaded = BuiltinsUnpickler(stream).load()
    except Exception:  # absent, unreadable or damaged: the walk as it was kept
        return none
    if not (isinstance(loaded, tuple) and len(loaded) == 4 and loaded[:2] == (_FORMAT, token)):
        return none
    _, _, directories, files = loaded
    if not (isinstance(directories, dict) and isinstance(files, dict)):
        return none
    if not all(_is_status(status, 3) for status in directories.values()):
        return none
    if not all(_is_status(status, 4) for status in files.values()):
        return none
    return Amended(token, directories, files)


def _is_status(value: object, fields: int) -> bool:
    return (
        isinstance(value, tuple)
        and len(value) == fields
        and all(isinstance(number, int) for number in value)
    )


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
    # Drawn anew for each walk kept: the amendments of an earlier one (``refresh``) are
    # none of this one's.
    token = os.urandom(8).hex()
    kept = (_FORMAT, token, prefix, ancestors, directories, statuses, stood_on, without, found)
    path = listings.path.with_name(listings.path.name + _SUFFIX)
    cache.write_newest(path, partial(pickle.dump, kept, protocol=_PROTOCOL), KEPT)


def _read(
    path: Path,
) -> (
    tuple[
        str,
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
    if not (isinstance(loaded, tuple) and len(loaded) == 9 and loaded[0] == _FORMAT):
        return None
    _, token, prefix, ancestors, directories, statuses, stood_on, without, found = loaded
    shapes = ((token, str), (prefix, str), (ancestors, tuple), (directories, tuple))
    more = ((statuses, tuple), (stood_on, tuple), (without, list), (found, list))
    if not all(isinstance(value, kind) for value, kind in (*shapes, *more)):
        return None
    if len(directories) != len(statuses):
        return None
    return token, prefix, ancestors, directories, statuses, stood_on, without, found

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
taken within ``reading.RACY_NANOSECONDS`` of a change is never kept (an edit in the same
clock tick would not show: git's "racily clean" files): such a file is kept as changed,
and a manifest so taken is kept by the digest of what the run read in it
(``PackageGenerations.manifests``: its name, build type, dependencies and plugin
descriptions), which the next run compares with what it says then (``manifest_digest``:
one file read, where a manifest edited just before a run made the next run look every
package up again, 0.8 s at 8 copies of the benchmark's workspace). A manifest of
another status is compared so too: a version released or a maintainer changed is as
kept. The file is builtins only, read with an unpickler that resolves no class;
one that cannot be read is no key.

A re-run that edited some files is keyed file by file, yet most of that work gives what it
gave last time too: so the kept key comes with what it was made of (``Keying``), which a
run of the same identity takes up when every package status is as kept: the packages'
lookups (``PackageGenerations.lookups``: which package each directory is in, read from no
manifest again), each file's facts key, for the files whose status is as kept, and the
run's place (``RunInputs.place_key``) when no ``.srv`` file changed. At 77,000 files that
spares a run after an edit 0.6 s (every manifest read, 0.25 s; every file's facts key and
the place hashed, 0.3 s) for 0.1 s (the package statuses taken again, what was kept loaded).
A package.xml that says something else, there then and now, is read again and taken up
where only its dependencies changed (``Keying.reread``): the place is hashed anew.
"""

from __future__ import annotations

import hashlib
import io
import os
import pickle
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import IO, TYPE_CHECKING, NamedTuple

from .cache import BuiltinsUnpickler, FactsCache
from .generation import is_package_manifest
from .reading import Status, Statuses, is_racy, open_regular, racy_from, status_of

if TYPE_CHECKING:
    from .generation import KeptLookups

KEYS = "keys"  # their directory in the facts cache: one file per workspace, and its files
KEPT = 64
# 6: the files' statuses packed (``reading.Statuses``), in this machine's byte order; 7:
# what the key is made of pickled after the rest, not inside it (``keep``)
_FORMAT = f"7 {sys.byteorder}"
_FILES_FORMAT = 1
MOST_SHIFTED = 64  # checked files added or removed past which a run is keyed file by file
_PROTOCOL = pickle.HIGHEST_PROTOCOL


@dataclass(frozen=True)
class Keying:
    """What an earlier run of the same identity was keyed from and by."""

    file_statuses: Statuses  # as ``KeptKey.keep`` stores them
    package_statuses: dict[str, Status | None]
    tags: list[str]  # the facts key of each checked file, or why it has none ("": unknown)
    place_key: str | None  # None: an earlier run over other files (``KeptKey.keying``)
    lookups: KeptLookups
    shape_key: str | None = None  # ``RunInputs.shape_key``, with the place
    # The package.xml files that say something else now: the lookups are taken up with
    # what they say (``PackageGenerations.restore``), the place hashed anew.
    reread: tuple[str, ...] = ()


class KeptKey:
    """The key kept for one workspace, and what it was made from."""

    def __init__(
        self,
        cache: FactsCache,
        root: Path,
        package_status: Callable[[str], Status | None] = status_of,
        manifest_digest: Callable[[str], str | None] = lambda path: None,
    ) -> None:
        name = hashlib.blake2b(os.fsencode(root), digest_size=8).hexdigest()
        self._path = cache.directory / KEYS / name
        self._cache = cache
        # A package.xml's or plugin description's status now, as the lookups take it
        # (``PackageGenerations.status``).
        self._package_status = package_status
        # The digest of a package.xml's or plugin description's text now, as the lookups
        # take it (``generation.manifest_digest``); None where it cannot be read.
        self._manifest_digest = manifest_digest
        # Once the kept packages stand: each manifest kept by its digest (its status was
        # too recent), with its status now.
        self._verified: dict[str, Status] = {}
        self.started = time.time_ns()  # before any status of this run is taken
        self._files_path = self._path.with_name(f"{name}.files")  # ``keep``'s ``files``
        self._kept: _Kept | None = None
        self._loaded = False
        self._kept_identity: str | None = None  # of what was kept, once loaded
        self._packages_stand: bool | None = None  # once asked: their statuses are as kept
        self._differing: list[tuple[str, Status | str | None]] = []  # those not, as kept

    def key(self, identity: str, statuses: Statuses) -> str | None:
        """The kept key, if it was kept for ``identity`` and every status it was kept with
        is the status now (``statuses``: the files', in the order they were kept)."""
        kept = self._load()
        if kept is None or kept.identity != identity or statuses != kept.file_statuses:
            return None
        return kept.key if self._packages_as_kept(kept) else None

    def keying(
        self,
        identity: str,
        shape: str | None = None,
        files: Callable[[], Sequence[str]] = list,
        checked: int = 0,
    ) -> Keying | None:
        """What the kept key was made of, if it was kept for ``identity`` and every package
        status it was kept with is the status now (its files' statuses may differ); or,
        kept for the same ``shape`` (the identity but for which files are checked) over
        other checked files, renumbered to this run's (``_renumbered``). Asked last: what
        was kept is let go (30 MB at 77,000 files), ``Keying`` holds what is still
        needed. ``files``: the status files now (``RunInputs._status_files``), the first
        ``checked`` of them checked, each of those as where it is, how it is shown and its
        language (a facts key holds the last two)."""
        kept = self._load()
        self._kept = None
        if kept is None:
            return None
        reread: tuple[str, ...] = ()
        if not self._packages_as_kept(kept):
            found = self._rereadable(kept)
            if found is None:
                return None
            reread = found
        same = kept.identity == identity
        if not same and (shape is None or kept.shape != shape):
            return None
        try:
            tags, lookups, shape_key = BuiltinsUnpickler(io.BytesIO(kept.made_of)).load()
            # A manifest as kept by what it says (``_packages_as_kept``), or read again:
            # its status now is what the lookups are taken up with.
            now = {path: self._package_status(path) for path in reread}
            now.update(self._verified)
            package_statuses = {
                path: now[path] if path in now or isinstance(status, str) else status
                for path, status in zip(kept.package_paths, kept.package_statuses, strict=True)
            }
        except Exception:  # damaged: keyed file by file
            return None
        if not isinstance(tags, list) or not isinstance(shape_key, str | None):
            return None
        keying = Keying(
            kept.file_statuses, package_statuses, tags, kept.place_key, lookups, shape_key, reread
        )
        return keying if same else self._renumbered(keying, kept.identity, files(), checked)

    def _renumbered(
        self, keying: Keying, identity: str, files: Sequence[str], checked: int
    ) -> Keying | None:
        """``keying``, kept for ``identity``, over this run's status files: each checked
        file the kept run had takes its status and facts key, an added one has none (so
        it is read), the run's place is hashed anew. None where the ``.srv`` files differ,
        more than ``MOST_SHIFTED`` checked files do, or an added file is in a directory
        the kept lookups never saw (a package there would be one they never read)."""
        kept_files = self._kept_files(identity)
        if kept_files is None:
            return None
        locations, kept_checked = kept_files
        statuses = keying.file_statuses
        if len(statuses) != len(locations) or locations[kept_checked:] != list(files[checked:]):
            return None
        at = {where: index for index, where in enumerate(locations[:kept_checked])}
        previous = [at.get(where, -1) for where in files[:checked]]
        added = [files[index].partition("\0")[0] for index, then in enumerate(previous) if then < 0]
        removed = kept_checked - (checked - len(added))
        try:
            directories = keying.lookups[1]
        except (TypeError, IndexError):
            return None
        if (
            len(added) + removed > MOST_SHIFTED
            or len(keying.tags) != kept_checked
            or any(os.path.dirname(path) not in directories for path in added)
        ):
            return None
        return Keying(
            statuses.taking([*previous, *range(kept_checked, len(statuses))]),
            keying.package_statuses,
            [keying.tags[then] if then >= 0 else "" for then in previous],
            None,
            keying.lookups,
            reread=keying.reread,
        )

    def _kept_files(self, identity: str) -> tuple[Sequence[str], int] | None:
        """The status files of the run kept for ``identity`` and how many it checked."""
        try:
            with open_regular(self._files_path) as stream:
                loaded = BuiltinsUnpickler(stream).load()
        except Exception:  # absent, unreadable or damaged
            return None
        if not (isinstance(loaded, tuple) and len(loaded) == 4 and loaded[0] == _FILES_FORMAT):
            return None
        _, kept_identity, locations, checked = loaded
        if (
            kept_identity != identity
            or not isinstance(locations, list)
            or not all(isinstance(where, str) for where in locations)
            or not isinstance(checked, int)
            or not 0 <= checked <= len(locations)
        ):
            return None
        return locations, checked

    def keep(
        self,
        identity: str,
        key: str,
        file_statuses: Statuses,
        package_statuses: Mapping[str, Status | None],
        keying: tuple[Sequence[str], str, KeptLookups, str | None],
        *,
        manifests: Mapping[str, str] | None = None,
        shape: str | None = None,
        files: Callable[[], Sequence[str]] = list,
        checked: int = 0,
    ) -> None:
        """Keep ``key`` with what it was made from (``keying``: each file's facts key, the
        place, the packages' lookups and the place's shape). A file whose status is too
        recent to say that nothing changed after it was taken is kept as changed (False:
        no status is); a manifest's, by the digest of what the run read in it
        (``manifests``: path -> digest), or nothing is kept where it has none; every
        manifest's digest is kept beside its status (``_package_as_kept``). ``shape``:
        the identity but for which files are checked, where a run of that shape over
        other files may take this one up (``keying``); the status files (``files``, as
        ``keying`` takes them) are then kept beside, written only when the identity
        changed (a file added or removed: 10 MB at 81,000 files)."""
        manifests = manifests or {}
        kept_statuses: list[Status | str | None] = []
        for path, status in package_statuses.items():
            if status is not None and self._racy(status):
                if path not in manifests:
                    return
                kept_statuses.append(manifests[path])
            else:
                kept_statuses.append(status)
        digests = [manifests.get(path) for path in package_statuses]
        if shape is not None and (
            self._kept_identity != identity or not self._files_path.is_file()
        ):
            listed = (_FILES_FORMAT, identity, list(files()), checked)
            self._cache.write_newest(
                self._files_path, partial(pickle.dump, listed, protocol=_PROTOCOL), KEPT
            )
        # ``_racy`` of each, without a call each
        trusted = file_statuses.changed_from(racy_from(self.started)).to_bytes()
        tags, place_key, lookups, shape_key = keying
        paths = tuple(package_statuses)
        kept = (_FORMAT, identity, key, trusted, paths, kept_statuses, digests, place_key, shape)
        made_of = (list(tags), lookups, shape_key)

        # Pickled into the file, what the key is made of after the rest (``_read``): 12 MB
        # at 81,000 files, pickled into bytes first, then into the file, was 13 to 19 MB
        # more at the peak of a run that patched the graph.
        def write(stream: IO[bytes]) -> None:
            pickle.dump(kept, stream, protocol=_PROTOCOL)
            pickle.dump(made_of, stream, protocol=_PROTOCOL)

        self._cache.write_newest(self._path, write, KEPT)

    def _racy(self, status: Status) -> bool:
        return is_racy(status[1], status[2], self.started)

    def _packages_as_kept(self, kept: _Kept) -> bool:
        if self._packages_stand is None:
            self._differing = [
                (path, status)
                for path, status, digest in zip(
                    kept.package_paths, kept.package_statuses, kept.package_digests, strict=True
                )
                if not self._package_as_kept(path, status, digest)
            ]
            self._packages_stand = not self._differing
        return self._packages_stand

    def _rereadable(self, kept: _Kept) -> tuple[str, ...] | None:
        """The manifests not as kept (``_packages_as_kept``), where each is a package.xml
        there then and now: an edit of a package's dependencies, which the lookups take
        up (``PackageGenerations.restore``); None for any other change."""
        found: list[str] = []
        for path, status in self._differing:
            if not is_package_manifest(path) or status is None:
                return None
            if self._package_status(path) is None:
                return None
            found.append(path)
        return tuple(found)

    def _package_as_kept(self, path: str, kept: Status | str | None, digest: str | None) -> bool:
        """Whether a manifest looked for is as kept: the same status, or one that says
        what it said (``digest``, or ``kept`` where the status was too recent to keep):
        a manifest of another version, maintainer or description is read, not every
        manifest and file of the run keyed again (1 s at 8 copies)."""
        now = self._package_status(path)
        if not isinstance(kept, str):
            if now == kept:
                return True
            kept = digest
        if now is None or kept is None or self._manifest_digest(path) != kept:
            return False
        self._verified[path] = now
        return True

    def _load(self) -> _Kept | None:
        if not self._loaded:
            self._kept, self._loaded = self._read(), True
            self._kept_identity = None if self._kept is None else self._kept.identity
        return self._kept

    def _read(self) -> _Kept | None:
        try:
            with open_regular(self._path) as stream:
                loaded = BuiltinsUnpickler(stream).load()
                made_of = stream.read()  # the pickle after it (``keep``), read when taken up
        except Exception:  # absent, unreadable or damaged: the run is keyed file by file
            return None
        if not (isinstance(loaded, tuple) and len(loaded) == 9 and loaded[0] == _FORMAT):
            return None
        shapes: tuple[type | tuple[type, ...], ...] = (
            str,
            str,
            bytes,
            tuple,
            list,
            list,
            str,
            (str, type(None)),
        )
        if not all(map(isinstance, loaded[1:], shapes)):
            return None
        statuses = Statuses.from_bytes(loaded[3])
        if statuses is None:
            return None
        _, identity, key, _, paths, package_statuses, digests, place_key, shape = loaded
        kept = _Kept(
            identity, key, statuses, paths, package_statuses, digests, place_key, made_of, shape
        )
        if not len(kept.package_paths) == len(kept.package_statuses) == len(kept.package_digests):
            return None
        return kept


class _Kept(NamedTuple):
    identity: str
    key: str
    file_statuses: Statuses
    package_paths: tuple[str, ...]
    package_statuses: list[Status | str | None]  # a digest where the status was too recent
    package_digests: list[str | None]  # what each says (``PackageGenerations.manifests``)
    place_key: str
    made_of: bytes  # the pickled tags and lookups: read only by a run that takes them up
    shape: str | None  # ``KeptKey.keep``'s

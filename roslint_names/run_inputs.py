"""What a run's result depends on, as one key; and each file's facts key on the way.

A run's result is a function of: every linted file's bytes (through its facts key, which
also holds its path, language and generations), those of a per-file run's context (the
graph rules read them, and RN202 the names their launch files wire: an edited launch file
is a fresh run, while the code's facts stay cached), where each file is (per-file ignores are
relative paths), which files are reported, the files read without being linted (a
``.srv`` file's name is a service type, its text a ROS 1 service's definition; every
package.xml read), the settings, and the code of the tool and of every rule. The one
input from the environment, ``ROS_PYTHON_VERSION`` (``config.ros1_python2``), is in the
facts key of each file it applies to.
``RunInputs`` keys a run by all of that, so that ``FactsCache.load_run`` can serve the
result of an earlier run over the same inputs.

Files are keyed through the workspace's ``ContentDigests``. When an earlier run of the
workspace left them, the whole run is keyed before any file is extracted
(``key_first``): most files are then not read, only looked at. Otherwise no stored
result can match, and the run is keyed from the reads it makes anyway (``read``, then
``key_last``). A file whose bytes differ between the two (edited during the run) marks
the inputs as changed: that result is then nobody's key and is not kept.
"""

from __future__ import annotations

import hashlib
import os
from array import array
from collections.abc import Sequence
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

from .config import Settings, settings_fingerprint
from .digests import ContentDigests
from .discover import SourceFile
from .generation import PackageGenerations, manifest_digest, reads_python2
from .model import Generation, Language
from .reading import (
    MAX_DEFINITION_BYTES,
    UNTAKEN,
    Read,
    Status,
    Statuses,
    Taken,
    Untaken,
    content_digest,
    read_file,
    statuses_of,
)
from .registry import Registry
from .unchanged import KeptKey, Keying

if TYPE_CHECKING:
    from .cache import FactsCache

_SKIPPED, _UNREADABLE = "skipped: ", "unreadable: "  # tags of files that have no facts key
# The tag of a file an earlier run did not have, in its replay renumbered (``shifts``)
ADDED = "added: not in the earlier run"


def is_facts_key(tag: str) -> bool:
    """Whether a checked file's tag (``RunInputs.tags``) is a facts key, not why it has none."""
    return not tag.startswith((_SKIPPED, _UNREADABLE, ADDED))


class RunInputs:
    def __init__(
        self,
        cache: FactsCache,
        checked: Sequence[SourceFile],
        everything: Sequence[SourceFile],
        *,
        reported: int,
        settings: Settings,
        registry: Registry,
        packages: PackageGenerations,
        fallback: Generation,
        ros1_python2: bool,
        named: Sequence[SourceFile],
    ) -> None:
        self._cache = cache
        self._checked = checked
        self._everything = everything
        # Whose packages the plugin names are read from (a per-file run's whole workspace,
        # where ``everything`` keeps only what wires names): a package added there is a
        # plugin added, which only its files show.
        self._named = named
        self._reported = reported
        self._settings = settings
        self._registry = registry
        self._packages = packages
        self._fallback = fallback
        self._ros1_python2 = ros1_python2  # the environment's part (``config.ros1_python2``)
        root = _common_directory(checked)
        # First: every status of the run is taken after.
        self._kept = KeptKey(cache, root, packages.status, manifest_digest)
        self._digests = ContentDigests.of(cache, root)
        # Per checked file: its facts key, or why it has none ("" until it is known).
        self._tags: list[str] = [""] * len(checked)
        self._contents: list[str | None] = []  # per checked file: its digest, as keyed first
        self._keyed_first = False
        self._statuses = Statuses()  # of ``_status_files``, as first taken
        self.changed = False  # a file read differs from what the run was keyed by
        self.place_key: str | None = None  # once keyed: ``_place``
        # A run that reports every file it checks, keyed by ``_place``: its place but for
        # which files it checks and what its packages depend on (``shifts``: an earlier
        # run of that shape is this one but for some files added or removed, and
        # dependencies: ``graph_patch.Shift``).
        self.shape_key: str | None = None
        self._keying: Keying | None = None  # an earlier run's, taken up (``unchanged``)
        self._carried = False  # keyed from it (``_carry``)

    def unchanged_key(self) -> str | None:
        """The key an earlier run kept, when nothing it was made from changed since
        (``unchanged``): no file is keyed. The statuses taken are those ``key_first``
        goes on with, when it must; and what the kept key was made of, where the packages
        are as they were, is taken up (``unchanged.Keying``): the packages' lookups now,
        the files' facts keys and the place when ``key_first`` asks."""
        self._statuses = statuses_of(self._status_files)
        key = self._kept.key(self._identity, self._statuses)
        if key is None:
            keying = self._kept.keying(
                self._identity, self._shape, self._where_files, len(self._checked)
            )
            if (
                keying is not None
                and len(keying.tags) == len(self._checked)
                and len(keying.file_statuses) == len(self._statuses)
                and self._packages.restore(keying.lookups, keying.package_statuses, keying.reread)
            ):
                self._keying = keying
        return key

    def sizes(self) -> list[int] | None:
        """Each checked file's size as the run's statuses took it (``unchanged_key``; 0
        where it has none); None before they were taken."""
        if len(self._statuses) < len(self._checked):
            return None
        return self._statuses.sizes()

    def key_first(self) -> str | None:
        """The run's key before anything is extracted, when an earlier run of this
        workspace left its keying or its digests (only then can a stored result match)."""
        keying = self._keying
        if keying is not None:
            self._carry(keying)
        elif not self._digests.remembered():
            return None
        else:
            checked = len(self._checked)
            # A run's own statuses are none kept as changed (no False among them).
            taken = cast(Sequence[Status | Untaken | None], self._statuses)
            if not taken:
                taken = [UNTAKEN] * checked
            paths = [source.location for source in self._checked]
            maximum = self._settings.max_file_size
            summaries = self._digests.summaries(paths, maximum, taken[:checked])
            self._tags = [
                self._tag(source, *summary)
                for source, summary in zip(self._checked, summaries, strict=True)
            ]
            self._contents = [content for content, _, _ in summaries]
        self._keyed_first = True
        key = self._key()
        self._keying = None  # in the tags and the place now: its statuses (17 MB) go
        return key

    def _carry(self, keying: Keying) -> None:
        """Key the run from what the last run of the same files was keyed by: a file whose
        status is as kept has the facts key it had, unread; the others are read
        (``ContentDigests.carry``: no digest of the others is loaded)."""
        self._digests.carry()
        self._carried = True
        checked, maximum = len(self._checked), self._settings.max_file_size
        self._tags = list(keying.tags)
        self._contents = [None] * checked
        # The ``.srv`` files' statuses follow the checked files' (``_kept_place``).
        statuses = self._statuses
        for index in statuses.unvouched(keying.file_statuses, checked):
            status = statuses[index]
            if isinstance(status, bool):
                continue  # a run's own statuses hold none kept as changed
            source = self._checked[index]
            summary = self._digests.summary(source.location, maximum, status)
            self._tags[index] = self._tag(source, *summary)
            self._contents[index] = summary[0]

    def known_key(self, index: int) -> str | None:
        """The facts key of checked file ``index`` as ``key_first`` found it, if any."""
        if not self._keyed_first:
            return None
        tag = self._tags[index]
        return tag if is_facts_key(tag) else None

    def facts_key(self, index: int) -> str | None:
        """The facts key of checked file ``index`` once it is known (keyed first, or
        read), None before that and for a file that has none."""
        tag = self._tags[index]
        return tag if is_facts_key(tag) else None

    @property
    def keyed_first(self) -> bool:
        """Whether ``key_first`` keyed the run: else each file is keyed as it is read."""
        return self._keyed_first

    def record(self, index: int, source: SourceFile, taken: Taken, key: str | None) -> None:
        """Key a file another process read (``gather``, for a run not keyed first), as
        ``read`` keys one it reads: ``taken`` is what that process found, ``key`` the facts
        key it made of it (``_tag``'s, from the same package lookup), if any."""
        assert not self._keyed_first
        self._digests.record(source.location, taken)
        if key is None:
            key = self._tag(source, taken.content, taken.error, taken.skip)
        self._tags[index] = key

    def read(self, index: int, source: SourceFile) -> tuple[Read, str | None, str | None]:
        """The file's bytes (as ``read_file`` gives them), its facts key and its content
        digest."""
        maximum = self._settings.max_file_size
        if self._keyed_first:
            read, content = read_file(source.location, maximum), None
        else:
            read, content = self._digests.read(source.location, maximum)
        data, read_error, skip = read
        if data is not None and content is None:
            content = content_digest(data)
        if self._keyed_first and content is not None and content == self._contents[index]:
            tag = self._tags[index]  # the same bytes as keyed: the same key, not made again
        else:
            tag = self._tag(source, content, read_error, skip)
        if self._keyed_first:
            self.changed |= tag != self._tags[index]
        self._tags[index] = tag
        return read, None if data is None else tag, content

    def key_last(self) -> str | None:
        """The run's key once every file was read: for a run not keyed first."""
        return None if self._keyed_first else self._key()

    def finish(self, kept_key: str | None = None) -> None:
        """Save the digests; and keep ``kept_key`` (the key of the result the run kept) with
        what it was made from, for ``unchanged_key``."""
        self._digests.save()
        if kept_key is None or self.changed:
            return
        taken = self._digests.statuses  # of the files this run keyed
        files = self._status_files
        if self.place_key is None:
            return
        if self._carried:  # the statuses the run was keyed by, less those taken again
            again = {index: taken[path] for index, path in enumerate(files) if path in taken}
            file_statuses = self._statuses.replaced(again)
        elif all(path in taken for path in files):
            file_statuses = Statuses.of(taken[path] for path in files)
        else:
            return
        keying = (self._tags, self.place_key, self._packages.lookups(), self.shape_key)
        self._kept.keep(
            self._identity,
            kept_key,
            file_statuses,
            self._packages.statuses,
            keying,
            manifests=self._packages.manifests,
            shape=self._shape,
            files=self._where_files,
            checked=len(self._checked),
        )

    # Both below are asked at the start of the run and again at its end: made once.
    @cached_property
    def _status_files(self) -> list[str]:
        """The files whose bytes the key holds: those checked, and the ``.srv`` files."""
        service_files = [
            source.location
            for source in self._everything
            if source.language is Language.SERVICE_DEFINITION
        ]
        return [source.location for source in self._checked] + service_files

    @cached_property
    def _identity(self) -> str:
        """All the key holds besides the bytes of files and what the packages say."""
        digest = hashlib.blake2b(digest_size=20)
        python2 = self._ros1_python2
        head = f"{self._fingerprints}\0{self._reported}\0{self._fallback.value}\0{python2}\0"
        digest.update(_text_bytes(head))
        _hash_columns(digest, self._everything)
        # The files checked and those named are most often the workspace's own objects
        # (the CLI's are all of it): hashed as where they are in it, not joined again
        # (0.07 s at 77,000 files). Equal objects that are not the same are hashed as
        # columns: another identity for the same files, a kept key missed, never one
        # wrongly found.
        place = {id(source): position for position, source in enumerate(self._everything)}
        for sources in (self._checked, self._named):
            positions = [place.get(id(source), -1) for source in sources]
            if -1 in positions:
                digest.update(b"columns\0")
                _hash_columns(digest, sources)
            else:
                digest.update(f"positions {len(positions)}\0".encode())
                digest.update(array("q", positions).tobytes())
        return digest.hexdigest()

    def _where_files(self) -> list[str]:
        """The status files as a run of another identity matches them (``KeptKey``): each
        checked file as where it is, how it is shown and its language (its facts key
        holds the last two), then the ``.srv`` files' paths."""
        checked = len(self._checked)
        return [*self._wheres, *self._status_files[checked:]]

    @cached_property
    def _wheres(self) -> list[str]:
        """Each checked file as where it is, how it is shown and its language: for the
        place and for the status files a run of another identity matches (made once)."""
        return [_where(source) for source in self._checked]

    @cached_property
    def _shape(self) -> str | None:
        """The identity but for which files are checked, for a run that reports every
        file it checks and names every file of its workspace (the CLI's over a workspace):
        a run of the same shape over some other files takes up this one's keying
        (``KeptKey.keying``). None for other runs."""
        if self._reported != len(self._checked) or len(self._named) != len(self._everything):
            return None
        python2 = self._ros1_python2
        head = f"shape\0{self._fingerprints}\0{self._fallback.value}\0{python2}\0"
        return hashlib.blake2b(_text_bytes(head), digest_size=20).hexdigest()

    @cached_property
    def _fingerprints(self) -> str:
        """The code's and the settings' fingerprints (made once: 8 ms each time)."""
        from .cache import code_fingerprint

        modules = {
            function.__module__
            for rule in self._registry.rules
            for function in (rule.check, rule.check_workspace)
            if function is not None
        }
        return f"{code_fingerprint(modules)}\0{settings_fingerprint(self._settings)}"

    def _tag(
        self, source: SourceFile, content: str | None, read_error: str, skip: str | None
    ) -> str:
        if skip is not None:
            return _SKIPPED + skip
        if content is None:
            return _UNREADABLE + read_error
        package = self._packages.for_file(source.location)
        python2 = reads_python2(source.language, package, self._fallback, self._ros1_python2)
        return self._cache.key_of_digest(
            content, source.display, source.language, package, self._fallback, python2=python2
        )

    @property
    def tags(self) -> tuple[str, ...]:
        """Per checked file, its facts key or why it has none, once keyed (``_key``)."""
        return tuple(self._tags)

    def _key(self) -> str:
        """The run's key: its place (``place_key``) and each checked file's facts key."""
        self.place_key = self._kept_place() or self._place()
        # The checked files as the place and the keying saw them, made again only where
        # the key is kept over other files (``finish``): not held through the run (20 MB
        # at 81,000 files, under the graph's patch, the peak of a run that added a file).
        self.__dict__.pop("_wheres", None)
        digest = hashlib.blake2b(digest_size=20)
        digest.update(f"{self.place_key}\0".encode())
        digest.update(_text_bytes("\0".join(self._tags)))
        return digest.hexdigest()

    def _kept_place(self) -> str | None:
        """The kept place, when no ``.srv`` file changed since and no manifest says
        something else (the packages did not, or their keying would not have been taken
        up). The run is carried (``_carry``): the ``.srv`` files' digests stand as kept,
        none is read (1,024 files at 8 copies)."""
        keying, checked = self._keying, len(self._checked)
        if keying is None or keying.reread:
            return None
        if self._statuses[checked:] != keying.file_statuses[checked:]:
            return None
        self.shape_key = keying.shape_key
        return keying.place_key  # None for an earlier run over other files

    def _place(self) -> str:
        """All the run's key holds but the checked files' facts keys: which files, where,
        reported how, under which tool and settings, and what the packages and the
        service definitions say (``same_facts`` keys a run by it and the facts apart)."""
        digest = hashlib.blake2b(digest_size=20)
        fingerprints = self._fingerprints
        digest.update(_text_bytes(f"{fingerprints}\0{self._reported}\0"))
        # The bytes of one line per file, hashed in one update: the same digest as an
        # update per line, without 77,000 calls.
        wheres = self._wheres
        digest.update(_text_bytes("\n".join(wheres) + "\n" if wheres else ""))
        linted = {source.location for source in self._checked}
        lines: list[str] = []
        # Every manifest a run reads read now; where the lookups are an earlier run's over
        # the same directories (``unchanged``), they read none.
        look_up = not self._packages.restored
        for source in self._everything:
            if look_up:
                self._packages.for_file(source.location)
            if source.location not in linted:
                lines.append(f"{_where(source)}\n")
            if source.language is Language.SERVICE_DEFINITION:  # RN403 reads its text too
                content = self._digests.summary(source.location, MAX_DEFINITION_BYTES)[0]
                lines.append(f"{content}\n")
        rest = _text_bytes("".join(lines))
        manifests = _text_bytes(
            "".join(
                f"{manifest}\0{content}\n"  # path, digest
                for manifest, content in sorted(self._packages.manifests.items())
            )
        )
        digest.update(rest)
        digest.update(manifests)
        if self._reported == len(self._checked):
            # What the manifests say but for the dependencies: a run whose packages
            # depend on others patches the graph of the last run of its shape.
            shape = hashlib.blake2b(digest_size=20)
            shape.update(_text_bytes(f"{fingerprints}\0shape\0"))
            shape.update(rest)
            shape.update(self._packages.layout())
            self.shape_key = shape.hexdigest()
        return digest.hexdigest()


def _hash_columns(digest: Any, sources: Sequence[SourceFile]) -> None:
    """Where each of ``sources`` is, how it is shown and its language, into ``digest``:
    column by column, one join each, not one formatted line per file."""
    digest.update(_text_bytes("\0".join([source.location for source in sources])))
    digest.update(_text_bytes("\0".join([source.display for source in sources])))
    digest.update("\0".join([source.language for source in sources]).encode())
    digest.update(b"\1")


def _where(source: SourceFile) -> str:
    return f"{source.location}\0{source.display}\0{source.language.value}"


def _text_bytes(text: str) -> bytes:
    return text.encode("utf-8", errors="surrogatepass")


def _common_directory(sources: Sequence[SourceFile]) -> Path:
    """The deepest directory holding every source: what the run's digests are kept for."""
    # ``os.path.commonpath`` splits every path: too slow for every file of a re-run. The
    # common string prefix of the paths, cut after its last separator, is the same
    # directory ("a/b-c/x" and "a/b/y" share "a/", not "a/b"): a file name holds no
    # separator, so what ends in one and starts every path starts every directory.
    paths = [source.location for source in sources]
    prefix = os.path.commonprefix(paths)  # noqa: RUF071 - by character, on purpose
    return Path(prefix[: prefix.rfind(os.sep) + 1] or os.sep)

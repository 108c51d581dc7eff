"""Ways of getting facts: the cache, extraction in this process or in workers, and the
launch files extracted again under their includers' arguments.

``Gatherer`` hands every file's facts to the engine as they arrive, by the cheapest way
there is: a file of the rest of the workspace whose facts the cache holds under the key
its remembered digest gives is not even read; a file read is looked up under its
content's key; the rest is extracted, in worker processes when there are enough files to
pay for them (``workers``), which store what they extract. Arrival order depends on the
workers; nothing downstream may depend on it. ``Specialiser`` does the same for a launch
file under the arguments an including file hands it, for the workspace graph.

Extractor modules are imported on first use, in whichever process extracts: a run over
launch files never imports libcst or tree-sitter.
"""

from __future__ import annotations

import importlib
from collections import deque
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property
from types import ModuleType
from typing import TYPE_CHECKING, Protocol

from . import workers
from .collection import no_collections
from .discover import SourceFile
from .extract import EXTRACTOR_MODULES
from .generation import DEFAULT_GENERATION, PackageGenerations, reads_python2
from .model import Diagnostic, FileFacts, Generation, Language, LaunchArguments, ParseError, Span
from .reading import BINARY, Taken, content_digest, read_file, read_regular, taken
from .run_inputs import RunInputs
from .suppress import Suppression, may_hold_suppression
from .wiring import wired_by
from .workers import Dispatcher

if TYPE_CHECKING:
    from .cache import FactsCache  # imported by the caller that wants a cache

Extract = Callable[[str, bytes, "Generation | None", Generation], FileFacts]

# Launch files an including file can hand arguments to (see ``workspace.launch_tree``).
SPECIALISABLE = frozenset({Language.LAUNCH_XML, Language.LAUNCH_YAML, Language.PYTHON})
# Files handed out first (``Gatherer._heaviest_first``): their bytes, a Python file's
# counted this many times, at least this many.
PYTHON_WEIGHT = 8
HEAVY_WEIGHT = 128 * 1024
_PYTHON_PARSED = frozenset({Language.PYTHON, Language.LAUNCH_PYTHON})


def extractor_for(language: Language) -> Extract:
    extract: Extract = _extractor_module(language).extract
    return extract


def _extractor_module(language: Language) -> ModuleType:
    return importlib.import_module(f"roslint_names.extract.{EXTRACTOR_MODULES[language]}")


class _ExtractWithArguments(Protocol):
    """A launch extractor's ``extract``: also takes the arguments an includer hands over."""

    def __call__(
        self,
        path: str,
        data: bytes,
        package_generation: Generation | None,
        fallback_generation: Generation,
        *,
        arguments: LaunchArguments,
    ) -> FileFacts: ...


class _ExtractPython(Protocol):
    """The Python extractor's ``extract``: also told that the file may be Python 2."""

    def __call__(
        self,
        path: str,
        data: bytes,
        package_generation: Generation | None,
        fallback_generation: Generation,
        *,
        arguments: LaunchArguments,
        python2: bool,
    ) -> FileFacts: ...


class Specialiser:
    """An included launch file's facts under the arguments its includer hands it: the
    same extraction, with those arguments, through the same cache."""

    def __init__(
        self,
        sources: Sequence[SourceFile],
        packages: PackageGenerations,
        fallback: Generation,
        cache: FactsCache | None,
        max_file_size: int,
        *,
        dispatcher: Dispatcher[_Item, Extracted],
        ros1_python2: bool,
    ) -> None:
        self._given = sources
        self._packages = packages
        self._fallback = fallback
        self._ros1_python2 = ros1_python2
        self._cache = cache
        self._max_file_size = max_file_size
        self._dispatcher = dispatcher
        self._memo: dict[tuple[str, LaunchArguments], FileFacts | None] = {}
        self._files: dict[str, tuple[bytes | None, str]] = {}
        # Extracted ahead of the walk, while the rest of the workspace was (``ahead``):
        # each taken up as the walk asks for it, as if extracted then.
        self._ahead: dict[tuple[str, LaunchArguments], FileFacts | None] = {}
        self._ahead_files: dict[str, tuple[bytes | None, str]] = {}
        self._sent: dict[int, tuple[tuple[str, LaunchArguments], _Item]] = {}  # by number
        self._flying: set[tuple[str, LaunchArguments]] = set()  # those sent, not back
        self._numbered_ahead = 0

    @cached_property
    def _sources(self) -> dict[str, SourceFile]:
        # Made when first asked: a launch patch whose trees hand no arguments asks none
        # (77,000 files at 8 copies of realws).
        return {source.display: source for source in self._given}

    @property
    def specialised(self) -> frozenset[str]:
        """The display paths of the files read to be extracted again so far."""
        return frozenset(self._files)

    def forget(self, display: str) -> None:
        """The file changed: its specialisations are to be made again when asked."""
        self._files.pop(display, None)
        self._memo = {key: facts for key, facts in self._memo.items() if key[0] != display}

    def __call__(self, display: str, arguments: LaunchArguments) -> FileFacts | None:
        key = (display, arguments)
        if key not in self._memo:
            self.prepare([key])
        return self._memo[key]

    def prepare(self, wanted: Sequence[tuple[str, LaunchArguments]]) -> None:
        """Extract every specialisation of ``wanted`` not known yet: from the cache, else
        through the dispatcher (in workers when it has them), all handed over together."""
        asked: list[tuple[tuple[str, LaunchArguments], _Item]] = []
        unknown = [
            key
            for key in dict.fromkeys(wanted)
            if key not in self._memo and not self._taken_up(key)
        ]
        with self._dispatcher.batch(len(unknown)):
            for key in unknown:
                found = self._job(len(asked), *key)
                if isinstance(found, tuple):
                    asked.append((key, found))
                    self._take(asked, self._dispatcher.put(found, len(found[1].data)))
                else:
                    self._memo[key] = found
            self._take(asked, self._dispatcher.finish())

    def ahead(self, wanted: Sequence[tuple[str, LaunchArguments]], first: int) -> list[Extracted]:
        """Send the specialisations of ``wanted`` not known yet to be extracted while the
        walk is not there yet, numbered from ``first`` on (past the run's files: whose
        results are told apart by the number, ``sent``); the dispatcher's results that
        came back meanwhile, of any item. None is taken for a file the walk reads
        (``specialised``) until the walk asks for it (``prepare``)."""
        results: list[Extracted] = []
        for key in dict.fromkeys(wanted):
            if key in self._memo or key in self._ahead or key in self._flying:
                continue
            found = self._job(first + self._numbered_ahead, *key, ahead=True)
            if isinstance(found, tuple):
                self._numbered_ahead += 1
                self._sent[found[0].index] = (key, found)
                self._flying.add(key)
                results.extend(self._dispatcher.put(found, len(found[1].data)))
            else:
                self._ahead[key] = found
        return results

    def sent(self, number: int) -> bool:
        """Whether ``number`` is an item ``ahead`` sent whose result is not back."""
        return number in self._sent

    def back(self, result: Extracted) -> None:
        """The result of an item ``ahead`` sent."""
        key, item = self._sent.pop(result[0])
        self._flying.discard(key)
        self._ahead[key] = _as_read(result, item, self._dispatcher)[1]

    def known_ahead(self, display: str, arguments: LaunchArguments) -> FileFacts | None:
        """What ``ahead`` extracted (None where it has not, or the file is none)."""
        key = (display, arguments)
        return self._ahead[key] if key in self._ahead else self._memo.get(key)

    @property
    def flying(self) -> int:
        """How many items ``ahead`` sent are not back."""
        return len(self._sent)

    def _taken_up(self, key: tuple[str, LaunchArguments]) -> bool:
        """Whether ``key`` was extracted ahead: then it is known, its file read, as if the
        walk had asked for it now."""
        if key not in self._ahead:
            return False
        self._memo[key] = self._ahead.pop(key)
        if key[0] in self._ahead_files:
            self._files.setdefault(key[0], self._ahead_files[key[0]])
        return True

    def _take(
        self, asked: list[tuple[tuple[str, LaunchArguments], _Item]], results: Iterable[Extracted]
    ) -> None:
        for result in results:
            key, item = asked[result[0]]
            self._memo[key] = _as_read(result, item, self._dispatcher)[1]

    def _job(
        self, index: int, display: str, arguments: LaunchArguments, *, ahead: bool = False
    ) -> FileFacts | tuple[_Job, OnDisk, str | None] | None:
        """The cached facts (None: nothing to specialise), or the work to extract them."""
        source = self._sources.get(display)
        if source is None or source.language not in SPECIALISABLE:
            return None
        data, content = self._read(source, self._ahead_files if ahead else self._files)
        if data is None:
            return None
        package = self._packages.for_file(source.location)
        python2 = reads_python2(source.language, package, self._fallback, self._ros1_python2)
        cache_key = None
        if self._cache is not None:
            # The arguments are part of what the facts depend on: key them with the path.
            keyed = f"{display}\0{arguments!r}"
            cache_key = self._cache.key_of_digest(
                content, keyed, source.language, package, self._fallback, python2=python2
            )
            found = self._cache.load(cache_key, display)
            if found is not None:
                return found
        job = _Job(index, display, source.language, package, self._fallback, arguments, python2)
        return job, OnDisk(source.location, data, content), cache_key

    def _read(
        self, source: SourceFile, files: dict[str, tuple[bytes | None, str]]
    ) -> tuple[bytes | None, str]:
        """A launch file's bytes and content digest, read once however many argument
        sets it is specialised under (up to 19 on realws), kept in ``files``."""
        if source.display not in files:
            known = self._files.get(source.display) or self._ahead_files.get(source.display)
            if known is None:
                data, _, _ = read_file(source.location, self._max_file_size)
                known = data, "" if data is None else content_digest(data)
            files[source.display] = known
        return files[source.display]


@dataclass(frozen=True)
class _Job:
    """What an extractor needs besides the bytes; small, so cheap to send to a worker."""

    index: int
    display: str
    language: Language
    package_generation: Generation | None
    fallback_generation: Generation
    arguments: LaunchArguments = ()  # a launch file specialised under its includer's
    python2: bool = False  # a Python file that may be Python 2 (``reads_python2``)
    checked: bool = False  # a reported file: the per-file rules judge it where it is extracted


class OnDisk:
    """A file's bytes as the main process read them, sent to a worker process as where
    they are: the worker reads them again, from the page cache. Piped, every byte of the
    workspace went through the main process, a fifth of its part of a cold run (pickled,
    then written to the pipe in 64 KB pieces). The worker gets None where the file no
    longer holds those bytes (edited since): the main process extracts its own then.
    ``digest``: the bytes' content digest where the main process made it already (keying
    the file): hashing every file twice was a tenth of a cold run's serial part."""

    __slots__ = ("data", "digest", "path")

    def __init__(self, path: str, data: bytes, digest: str | None = None) -> None:
        self.path = path
        self.data = data
        self.digest = digest

    def __reduce__(self) -> tuple[Callable[[str, int, str], bytes | None], tuple[str, int, str]]:
        digest = content_digest(self.data) if self.digest is None else self.digest
        return _read_again, (self.path, len(self.data), digest)


def _as_read(result: Extracted, item: _Item, dispatcher: Dispatcher[_Item, Extracted]) -> Extracted:
    """``result``; where the worker found the file edited since the main process read it,
    the extraction of the bytes as read, here."""
    edited = result[1] is None and result[3] is None
    return dispatcher.here([item])[0] if edited else result


def _read_again(path: str, size: int, digest: str) -> bytes | None:
    """In the worker: the bytes at ``path`` if they are still the ``size`` bytes of
    ``digest`` the main process read, else None."""
    try:
        data, _ = read_regular(path, size)
    except OSError:
        return None
    if data is None:  # larger now
        return None
    return data if len(data) == size and content_digest(data) == digest else None


class Unread:
    """A file the worker reads itself, keyed by what it finds (``reading.taken``): in a
    run where no file's facts can be found by its content (the cache holds none, or there
    is none) the main process reads no file to look it up, and each is read once, where
    it is extracted. Reading and hashing every file was a tenth of a cold run's main
    process."""

    __slots__ = ("max_size", "path")

    def __init__(self, path: str, max_size: int) -> None:
        self.path = path
        self.max_size = max_size

    def __reduce__(self) -> tuple[type[Unread], tuple[str, int]]:
        return Unread, (self.path, self.max_size)


# A job, the file's bytes (or where they are, or that the worker is to read them), and
# the key its facts are cached under.
_Item = tuple[_Job, "bytes | OnDisk | Unread | None", str | None]
# What the per-file rules found in a file (``checks.FileChecks``): diagnostics and the
# file's suppressions; None where its verdict waits for the whole run.
Verdict = tuple[list[Diagnostic], list[Suppression]]
Checker = Callable[[FileFacts, bytes], "Verdict | None"]
# A file's index, its facts, and the per-file rules' verdict when it was judged with them;
# for a file the worker read (``Unread``), what reading it found, its bytes where the
# main process needs them (a verdict it makes, a launch file's wiring), else None, and
# the key its facts were stored under (the main process keys the run by it). Facts
# None: the worker found the file edited since the main process read it (``OnDisk``),
# and the main process extracts the bytes it read (``Dispatcher.here``); or the file the
# worker read is one no extractor reads (too large, not text, unreadable).
Read = tuple[Taken, "bytes | None", str | None]
Extracted = tuple[int, "FileFacts | None", "Verdict | None", "Read | None"]


def extract_batch(
    cache: FactsCache | None, batch: Iterable[_Item], checker: Checker | None = None
) -> list[Extracted]:
    """Extract and store facts, and judge a reported file with the per-file rules right
    there (``checker``): the work of a worker process, or of the main one, which then only
    gathers the verdicts.

    Module-level so that worker processes can run it; extractor modules are imported on
    first use, in whichever process extracts. Each file has ``workers.BUDGET_SECONDS``:
    a file past it is one RN001, stored like any facts (``gave_up``).
    """
    results: list[Extracted] = []
    for job, payload, sent_key in batch:
        found: Taken | None = None
        key = sent_key
        if isinstance(payload, Unread):
            found, data = taken(payload.path, payload.max_size)
            if data is None:  # too large, not text, unreadable: the main process says so
                results.append((job.index, None, None, (found, None, None)))
                continue
            key = _key_of(cache, job, found)
        else:
            data = payload.data if isinstance(payload, OnDisk) else payload
        if data is None:  # edited since the main process read it
            results.append((job.index, None, None, None))
            continue
        facts = _extract_within_budget(job, data)
        if may_hold_suppression(data):
            facts = replace(facts, suppression_marker=True)
        if cache is not None and key is not None:
            cache.store(key, facts)
        verdict = checker(facts, data) if checker is not None and job.checked else None
        read = None
        if found is not None:
            needed = (job.checked and verdict is None) or bool(wired_by(facts))
            read = (found, data if needed else None, key)
        results.append((job.index, facts, verdict, read))
    if cache is not None:
        cache.flush()  # a worker process has no "end of run": every batch ends its writes
    return results


def _key_of(cache: FactsCache | None, job: _Job, found: Taken) -> str | None:
    """The key the facts of a file a worker read are stored under: the one the main
    process keys the file by (``RunInputs.record``)."""
    if cache is None or found.content is None:
        return None
    return cache.key_of_digest(
        found.content,
        job.display,
        job.language,
        job.package_generation,
        job.fallback_generation,
        python2=job.python2,
    )


def _extract_within_budget(job: _Job, data: bytes) -> FileFacts:
    generations = (job.package_generation, job.fallback_generation)
    budget = workers.budget_seconds()
    try:
        with workers.time_limit(budget), no_collections():  # a parse tree is freed when done
            if job.python2:  # only the Python extractor reads Python 2
                python: _ExtractPython = _extractor_module(job.language).extract
                return python(
                    job.display, data, *generations, arguments=job.arguments, python2=True
                )
            if job.arguments:
                specialise: _ExtractWithArguments = _extractor_module(job.language).extract
                return specialise(job.display, data, *generations, arguments=job.arguments)
            return extractor_for(job.language)(job.display, data, *generations)
    except workers.OutOfTime:
        return gave_up_facts(job.display, job.language, data, workers.Stopped(budget))


def extract_file(
    language: Language,
    display: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
    *,
    ros1_python2: bool = False,
) -> FileFacts:
    """One file's facts, within the time budget, in this process: for a caller that
    extracts one file at a time (``--fix`` checking its edit, the language server).

    The budget holds on the main thread only (``workers.time_limit``); a file whose
    shape is known to keep a parser busy is refused before parsing, in any thread."""
    python2 = reads_python2(language, package_generation, fallback_generation, ros1_python2)
    job = _Job(0, display, language, package_generation, fallback_generation, (), python2)
    return _extract_within_budget(job, data)


def gave_up(cache: FactsCache | None, item: _Item, why: workers.Stopped) -> Extracted:
    """The result of a file whose worker was stopped (``Dispatcher``'s ``give_up``):
    one RN001, stored like any facts. A give-up is a property of the content under this
    version of the tool (the cache key has both), so the next run does not wait again;
    ``--no-cache`` tries anew."""
    job, payload, key = item
    read: Read | None = None
    if isinstance(payload, Unread):  # read here, as its worker read it
        found, unread = taken(payload.path, payload.max_size)
        if unread is None:
            return job.index, None, None, (found, None, None)
        key = _key_of(cache, job, found)
        data, read = unread, (found, unread, key)
    else:
        data = payload.data if isinstance(payload, OnDisk) else payload or b""
    facts = gave_up_facts(job.display, job.language, data, why)
    if cache is not None and key is not None:
        cache.store(key, facts)
    return job.index, facts, None, read


def gave_up_facts(display: str, language: Language, data: bytes, why: workers.Stopped) -> FileFacts:
    """One RN001 at the file's start: ``why`` the extraction stopped, and the shape that
    makes a parser slow, when the file has one."""
    shape = _slow_shape(language, data)
    if shape is None:
        shape = (
            "a parser crashed on it; please report it with the file"
            if why.budget is None
            else "its extraction takes longer than any file written by hand needs"
        )
    return FileFacts(
        path=display,
        language=language,
        generation=DEFAULT_GENERATION,
        parse_errors=(ParseError(f"{why}: {shape}", Span(1, 1, 1, 2)),),
    )


_NOTABLE_CHAIN = 100  # operators; the longest in 2,400 modules of real Python is 24


def _slow_shape(language: Language, data: bytes) -> str | None:
    if language not in (Language.PYTHON, Language.LAUNCH_PYTHON):
        return None
    from .extract.python.shape import longest_chain

    chain = longest_chain(data.decode("utf-8", errors="replace"), _NOTABLE_CHAIN)
    return None if chain is None else chain.describe()


def unreadable(source: SourceFile, reason: str) -> FileFacts:
    return _file_error(source, f"cannot read file: {reason}")


def not_text(source: SourceFile) -> FileFacts:
    return _file_error(
        source,
        "not a text file: a NUL byte in the first 8,000 bytes and no UTF-16 or UTF-32 "
        "byte order mark; save it as UTF-8",
    )


def _file_error(source: SourceFile, message: str) -> FileFacts:
    """The facts of a file whose content was never read: one RN001 at its start."""
    return FileFacts(
        path=source.display,
        language=source.language,
        generation=DEFAULT_GENERATION,
        parse_errors=(ParseError(message, Span(1, 1, 1, 1)),),
    )


def heaviest_first(
    languages: Sequence[Language], sizes: Sequence[int]
) -> tuple[list[int], list[int]]:
    """Of files of these ``languages`` and ``sizes`` (in bytes), the indices of those
    whose extraction may take long, the largest first (``Gatherer._heaviest_first``);
    then the rest, in order."""
    weights: dict[int, int] = {}
    for index, (language, size) in enumerate(zip(languages, sizes, strict=False)):
        weight = size * PYTHON_WEIGHT if language in _PYTHON_PARSED else size
        if weight >= HEAVY_WEIGHT:
            weights[index] = weight
    heavy = sorted(weights, key=lambda index: (-weights[index], index))
    return heavy, [index for index in range(len(languages)) if index not in weights]


class Ahead(Protocol):
    """What extracts work ahead of the walk while the files are gathered
    (``speculation.Speculation``): told the facts of each file of ``languages`` (handed
    out first), it sends items numbered past the run's files (``sent``) and takes their
    results (``back``), each time returning the dispatcher's results that came back
    meanwhile; it sends nothing once ``stop`` is called."""

    languages: frozenset[Language]

    def saw(self, facts: FileFacts) -> list[Extracted]: ...

    def sent(self, number: int) -> bool: ...

    def back(self, result: Extracted) -> list[Extracted]: ...

    def stop(self) -> None: ...


@dataclass
class Gatherer:
    """Every file of ``files`` as ``(index, facts, bytes)``, in the order facts arrive.

    The bytes are None for a file that was not read (its facts came from the cache by its
    remembered digest: the rest of the workspace, and reported files holding no
    suppression), and empty for a file that could not be. Files from ``reported`` on
    are the rest of the workspace: only their facts matter. Counts of what came from
    where, and the files skipped (too large), are kept for the run's summary.
    """

    files: Sequence[SourceFile]
    reported: int
    cache: FactsCache | None
    inputs: RunInputs | None
    dispatcher: Dispatcher[_Item, Extracted]
    packages: PackageGenerations
    fallback: Generation
    ros1_python2: bool  # ``config.ros1_python2``
    max_file_size: int
    # Work done ahead of the walk with the facts of some files, in a first run (where
    # every file is extracted: ``_read_where_extracted``)
    ahead: Ahead | None = None
    extracted: int = 0
    cached: int = 0
    # The worker processes started by the time files were extracted (a patch's
    # specialisations may start some after: those extracted none of the files)
    workers: int = 0
    _skipped: dict[int, tuple[str, str]] = field(default_factory=dict)  # by file index
    _extracting: dict[int, _Item] = field(default_factory=dict)  # sent to extraction
    _unread: bool | None = None  # once asked: workers read the files (``Unread``)

    @property
    def skipped(self) -> list[tuple[str, str]]:
        """The files skipped (display path, why), in the order of ``files``."""
        return [self._skipped[index] for index in sorted(self._skipped)]

    def facts(
        self, indices: Iterable[int] | None = None
    ) -> Iterator[tuple[int, FileFacts, bytes | None, Verdict | None]]:
        """Those of the files at ``indices`` of ``files``, or of all of them, the heaviest
        first (``_heaviest_first``) in chunks that spread them over every worker."""
        extracted = self.extracted
        if self.ahead is not None and (indices is not None or not self._read_where_extracted()):
            self.ahead = None  # no extraction of every file for its work to go beside
        if indices is None:
            heavy, rest = self._heaviest_first()
            if self.ahead is not None:  # the files it wants first, then the rest
                wanted = self.ahead.languages
                rest = [i for i in rest if self.files[i].language in wanted] + [
                    i for i in rest if self.files[i].language not in wanted
                ]
            with self.dispatcher.batch(len(heavy)):
                yield from self._told(self._each(heavy))
            yield from self._told(self._each(rest))
        else:
            yield from self._told(self._each(indices))
        if self.ahead is not None:
            self.ahead.stop()  # what it sent still comes back, through ``finish``
        yield from self._told(self._arrived(self.dispatcher.finish()))
        if self.extracted > extracted:
            self.workers = max(self.workers, self.dispatcher.workers)

    def _told(
        self, gathered: Iterable[tuple[int, FileFacts, bytes | None, Verdict | None]]
    ) -> Iterator[tuple[int, FileFacts, bytes | None, Verdict | None]]:
        """``gathered``, the facts of each file of the languages ``ahead`` wants told to
        it (by the file's language, as the files were handed out)."""
        for found in gathered:
            yield found
            if self.ahead is not None and self.files[found[0]].language in self.ahead.languages:
                yield from self._told(self._arrived(self.ahead.saw(found[1])))

    def _each(
        self, indices: Iterable[int]
    ) -> Iterator[tuple[int, FileFacts, bytes | None, Verdict | None]]:
        for index in indices:
            source = self.files[index]
            known = self._known(index, source)
            if known is not None and (index >= self.reported or not known[1].suppression_marker):
                self.cached += 1
                yield index, known[1], None, None
                continue
            if known is None and self._read_where_extracted():
                unread = Unread(source.location, self.max_file_size)
                item: _Item = (self._job(index, source), unread, None)
                self._extracting[index] = item
                yield from self._arrived(self.dispatcher.put(item, 0))
                continue
            key: str | None = None
            content: str | None = None  # the bytes' digest, where keying them made it
            if self.inputs is not None:
                (data, read_error, skip), key, content = self.inputs.read(index, source)
            else:
                data, read_error, skip = read_file(source.location, self.max_file_size)
            if data is None:
                yield self._not_extracted(index, source, read_error, skip)
            else:
                if known is not None and key == known[0]:  # loaded above: the same bytes
                    self.cached += 1
                    stored: FileFacts | None = known[1]
                else:
                    stored = self._stored(key, source)
                if stored is not None:
                    yield index, stored, data, None
                    continue
                self.extracted += 1
                on_disk = OnDisk(source.location, data, content)
                item = self._extracting[index] = (self._job(index, source), on_disk, key)
                yield from self._arrived(self.dispatcher.put(item, len(data)))

    def _heaviest_first(self) -> tuple[list[int], list[int]]:
        """The indices of the files whose extraction may take long (by size, a Python
        file's bytes counted ``PYTHON_WEIGHT`` times: libcst parses a byte ten times
        slower than tree-sitter), the largest first; then the rest, in order. Handed out
        last, one such file held the end of a first run: rclpy's ``test_node.py`` (115 KB,
        0.42 s on one core), 32nd from the end of realws's files, came 0.52 s after every
        other on 16 cores. Only in a first run (``_read_where_extracted``: every file is
        extracted) whose statuses were taken (a cache)."""
        sizes = None if self.inputs is None else self.inputs.sizes()
        if sizes is None or not self._read_where_extracted():
            return [], list(range(len(self.files)))
        return heaviest_first([source.language for source in self.files], sizes)

    def _read_where_extracted(self) -> bool:
        """Whether each file is read by the worker that extracts it (``Unread``): where no
        file's facts can be found by its content, for a run keyed as it reads."""
        if self._unread is None:
            keyed_first = self.inputs is not None and self.inputs.keyed_first
            self._unread = not keyed_first and (self.cache is None or not self.cache.holds_facts())
        return self._unread

    def _job(self, index: int, source: SourceFile) -> _Job:
        package = self.packages.for_file(source.location)
        python2 = reads_python2(source.language, package, self.fallback, self.ros1_python2)
        return _Job(
            index,
            source.display,
            source.language,
            package,
            self.fallback,
            (),
            python2,
            checked=index < self.reported,
        )

    def _not_extracted(
        self, index: int, source: SourceFile, error: str, skip: str | None
    ) -> tuple[int, FileFacts, bytes | None, Verdict | None]:
        """A file whose bytes no extractor reads (``read_file``'s ``error`` or ``skip``)."""
        if skip == BINARY:  # a source that is not text is a finding, never a pass
            return index, not_text(source), b"", None
        if skip is not None:
            self._skipped[index] = (source.display, skip)
            return index, FileFacts(source.display, source.language, self.fallback), b"", None
        return index, unreadable(source, error), b"", None

    def _known(self, index: int, source: SourceFile) -> tuple[str, FileFacts] | None:
        """The facts cached under the key the file's remembered digest gives, and that key.

        A file of the rest of the workspace is only its facts, and a reported file
        holding no suppression is only its facts until it has a finding: such a file is
        not read (yet)."""
        key = None if self.inputs is None else self.inputs.known_key(index)
        if key is None or self.cache is None:
            return None
        facts = self.cache.load(key, source.display)
        return None if facts is None else (key, facts)

    def _stored(self, key: str | None, source: SourceFile) -> FileFacts | None:
        if key is None or self.cache is None:
            return None
        facts = self.cache.load(key, source.display)
        if facts is not None:
            self.cached += 1
        return facts

    def _arrived(
        self, results: Iterable[Extracted]
    ) -> Iterator[tuple[int, FileFacts, bytes | None, Verdict | None]]:
        for first in results:  # as they come: ``finish`` waits for each chunk in turn
            waiting = deque([first])
            while waiting:
                result = waiting.popleft()
                if self.ahead is not None and self.ahead.sent(result[0]):
                    waiting.extend(self.ahead.back(result))  # and what it sent next
                    continue
                item = self._extracting.pop(result[0])
                index, facts, verdict, read = _as_read(result, item, self.dispatcher)
                if read is not None:
                    yield self._read_there(index, facts, verdict, read)
                    continue
                assert facts is not None and isinstance(item[1], OnDisk)
                yield index, facts, item[1].data, verdict

    def _read_there(
        self,
        index: int,
        facts: FileFacts | None,
        verdict: Verdict | None,
        read: Read,
    ) -> tuple[int, FileFacts, bytes | None, Verdict | None]:
        """A file its worker read (``Unread``): keyed as the worker keyed what it found,
        and what the main process makes of it where it read no bytes to extract, as for
        one it reads."""
        found, data, key = read
        source = self.files[index]
        if self.inputs is not None:
            self.inputs.record(index, source, found, key)
        if facts is None:
            return self._not_extracted(index, source, found.error, found.skip)
        self.extracted += 1
        return index, facts, data, verdict

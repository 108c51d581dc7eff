"""Run the pipeline over discovered files: extract facts, apply rules, then suppressions.

Extractor modules are imported on first use, so a run over launch files never imports
libcst or tree-sitter, and a run over one C++ file never imports lxml. Facts come from the
facts cache (``cache``) when a file is unchanged, and are extracted in worker processes
(``workers``) when there are enough files to pay for them; diagnostics never depend on
either.
"""

from __future__ import annotations

import importlib
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Protocol

from .config import Settings, enabled_codes, ignored_for_path, test_code_codes
from .discover import SourceFile, classify
from .fixing import located
from .generation import PackageGenerations, service_types
from .lines import split_lines
from .model import (
    Diagnostic,
    FileFacts,
    Finding,
    Fix,
    Generation,
    Kind,
    Language,
    LaunchArguments,
    ParseError,
    RelatedLocation,
    Span,
)
from .reading import BINARY, bom_encoding, content_digest, read_file
from .registry import Registry
from .rule import Rule, RuleContext, WorkspaceFinding
from .run_inputs import RunInputs
from .suppress import Suppression, find_suppressions, is_our_code
from .test_code import is_test_code
from .types import parse_type
from .workers import Dispatcher
from .workspace.build import build
from .workspace.graph import Graph
from .workspace.index import Package

if TYPE_CHECKING:
    from .cache import FactsCache  # imported by the caller that wants a cache

Extract = Callable[[str, bytes, "Generation | None", Generation], FileFacts]

EXTRACTOR_MODULES: dict[Language, str] = {
    Language.CPP: "cpp.extract",
    Language.PYTHON: "python.extract",
    Language.LAUNCH_XML: "launch.xml_launch",
    Language.LAUNCH_YAML: "launch.yaml_launch",
    Language.URDF: "launch.urdf",
    Language.CMAKE: "build.cmake",
    Language.SETUP_PY: "build.setup_py",
    Language.SETUP_CFG: "build.setup_py",
}
# Launch files an including file can hand arguments to (see ``workspace.launch_tree``).
SPECIALISABLE = frozenset({Language.LAUNCH_XML, Language.LAUNCH_YAML, Language.PYTHON})
DEFAULT_GENERATION = Generation.ROS2
UNUSED_SUPPRESSION = "RN002"
INVALID_SUPPRESSION = "RN003"


@dataclass(frozen=True)
class LintResult:
    diagnostics: tuple[Diagnostic, ...]  # sorted; suppressed ones flagged, not dropped
    files_checked: int
    files_extracted: int = 0  # parsed (or prefiltered) this run
    files_cached: int = 0  # facts served by the cache
    workers: int = 0  # worker processes started; 0 when everything ran in-process
    graph: Graph | None = None  # the workspace graph, when a graph rule or the caller wants it
    skipped: tuple[tuple[str, str], ...] = ()  # (display path, why): too large or binary
    reused: bool = False  # the stored result of an earlier run over the same inputs
    # Every file's facts, the rest of the workspace's too, when they were kept for the graph
    # or the caller (``want_facts``); never those of a stored result.
    facts: tuple[FileFacts, ...] = ()


Progress = Callable[[int, int], None]  # (files done, files in total)


@dataclass(frozen=True)
class RunOptions:
    """How a run goes about it, never what it reports: the output is the same for all."""

    jobs: int = 1  # worker processes for extraction; 0: every core; 1: none
    cache: FactsCache | None = None
    progress: Progress | None = None


def lintable(sources: Iterable[SourceFile]) -> list[SourceFile]:
    return [source for source in sources if source.language in EXTRACTOR_MODULES]


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


def lint(
    sources: Sequence[SourceFile],
    settings: Settings,
    registry: Registry,
    run: RunOptions = RunOptions(),  # frozen: sharing the default is safe
    *,
    context: Sequence[SourceFile] = (),
    want_graph: bool = False,
    want_facts: bool = False,
) -> LintResult:
    """Diagnostics of every lintable source; the same bytes whatever the ``run`` options.

    With a cache, the run is first keyed by its inputs (``run_inputs``): a run over the
    same inputs as a recent one returns that run's result. Otherwise each file is read
    once, here (a file of the rest of the workspace not at all when its facts are
    cached). Its facts come from the cache when its key is there; otherwise the file goes
    to extraction, in-process or in worker processes (see ``workers``), which store what
    they extract. Rules and suppressions run here, in the main process, as facts arrive,
    in whatever order; every file's diagnostics are kept in its own slot and joined in
    discovery order before the final sort, so the order in which workers finish never
    shows in the output.

    ``context`` files (the rest of the workspace of a per-file run) are extracted for the
    graph rules only: nothing is reported in them. Once every file is in, the graph rules
    run over the workspace graph and report into the files of ``sources``.

    ``want_graph`` returns the graph; ``want_facts`` every file's facts (``renames``
    searches them), without the graph when no graph rule needs it.
    """
    enabled = enabled_codes(settings, registry)
    test_rules = test_code_codes(settings, registry)
    graph_rules = [r for r in registry.rules if r.check_workspace and r.code in enabled]
    packages = PackageGenerations()
    fallback = settings.ros or DEFAULT_GENERATION
    cache, progress = run.cache, run.progress
    checked = lintable(sources)
    reported = len(checked)
    keep_facts = bool(graph_rules) or want_graph or want_facts
    # A stored result has neither the graph nor the facts.
    fresh = want_graph or want_facts
    if keep_facts:
        given = {source.path for source in checked}
        checked += [source for source in lintable(context) if source.path not in given]
    else:
        context = ()
    per_file: list[list[Diagnostic]] = [[] for _ in range(reported)]
    suppressions_of: dict[int, list[Suppression]] = {}
    all_facts: list[FileFacts | None] = [None] * len(checked)
    extracting: dict[int, bytes] = {}  # files sent to extraction: their bytes, to check them
    # RN204 compares a service's name with every service type of the run (of the file's own
    # generation), known only once every file is extracted: files that serve or call a typed
    # service wait for that list; the others (nearly all) are checked as their facts arrive.
    run_service_types = set(service_types([*sources, *context], packages))
    waiting: list[tuple[int, FileFacts, bytes]] = []
    done = 0

    def check(index: int, facts: FileFacts, data: bytes) -> None:
        nonlocal done
        if keep_facts:
            all_facts[index] = facts
        types = typed_services(facts)
        run_service_types.update((facts.generation, spelling) for spelling in types)
        if index < reported:
            if types:
                waiting.append((index, facts, data))
            else:
                check_now(index, facts, data, frozenset())
        done += 1
        if progress is not None:
            progress(done, len(checked))

    def check_now(index: int, facts: FileFacts, data: bytes, known: frozenset[str]) -> None:
        text = decode_for_display(data)
        per_file[index], found = check_file(
            facts,
            text,
            settings,
            registry,
            enabled,
            known_service_types=known,
            test_rules=test_rules,
        )
        if found:
            suppressions_of[index] = found

    def check_extracted(results: Iterable[tuple[int, FileFacts]]) -> None:
        for index, facts in results:
            check(index, facts, extracting.pop(index))

    # A run over the same inputs as a recent one (nothing edited since) is its result again.
    inputs: RunInputs | None = None
    run_key: str | None = None
    if cache is not None and checked:
        inputs = RunInputs(
            cache,
            checked,
            [*sources, *context],
            reported=reported,
            settings=settings,
            registry=registry,
            packages=packages,
            fallback=fallback,
        )
        run_key = None if fresh else inputs.key_first()
        stored = None if run_key is None else _stored_result(cache.load_run(run_key), len(checked))
        if stored is not None:
            inputs.finish()
            return stored
    if cache is not None:
        cache.writable()  # create the directory now, not racing in every worker
    extracted = cached = 0
    skipped: list[tuple[str, str]] = []
    extract = partial(extract_batch, cache)
    with Dispatcher(extract, run.jobs, expected_items=len(checked)) as dispatcher:
        for index, source in enumerate(checked):
            # A file of the rest of the workspace is only its facts: when they are cached
            # under the key its digest gave, it is not read at all.
            cached_key = None if inputs is None or index < reported else inputs.known_key(index)
            if cached_key is not None and cache is not None:
                facts = cache.load(cached_key, source.display)
                if facts is not None:
                    cached += 1
                    check(index, facts, b"")
                    continue
            key: str | None = None
            if inputs is not None:
                (data, read_error, skip), key = inputs.read(index, source)
            else:
                data, read_error, skip = read_file(source.path, settings.max_file_size)
            if skip == BINARY:  # a source that is not text is a finding, never a pass
                check(index, _not_text(source), b"")
                continue
            if skip is not None:
                skipped.append((source.display, skip))
                check(index, FileFacts(source.display, source.language, fallback), b"")
                continue
            if data is None:
                check(index, _unreadable(source, read_error), b"")
                continue
            package = packages.for_file(source.path)
            job = _Job(index, source.display, source.language, package, fallback)
            if cache is not None and key is not None:
                facts = cache.load(key, source.display)
                if facts is not None:
                    cached += 1
                    check(index, facts, data)
                    continue
            extracted += 1
            extracting[index] = data
            check_extracted(dispatcher.put((job, data, key), len(data)))
        check_extracted(dispatcher.finish())
        workers = dispatcher.workers  # that extracted the files (specialisations may start some)
        if inputs is not None and not fresh and run_key is None:
            run_key = inputs.key_last()
        for index, facts, data in waiting:
            known = frozenset(
                spelling
                for generation, spelling in run_service_types
                if generation in (facts.generation, None)
            )
            check_now(index, facts, data, known)
        graph: Graph | None = None
        if graph_rules or want_graph:
            known_facts = [facts for facts in all_facts if facts is not None]
            # Launch files extracted again under their includers' arguments go through the
            # same workers, a depth of the launch trees at a time.
            specialise = Specialiser(
                checked, packages, fallback, cache, settings.max_file_size, dispatcher=dispatcher
            )
            graph = build(
                known_facts,
                workspace_packages([*sources, *context], packages),
                specialise,
                specialise.prepare,
            )
            report_graph(
                graph,
                graph_rules,
                reported=checked[:reported],
                facts=known_facts,
                per_file=per_file,
                suppressions_of=suppressions_of,
                settings=settings,
                registry=registry,
            )
    diagnostics = [diagnostic for found in per_file for diagnostic in found]
    diagnostics.sort(key=Diagnostic.sort_key)
    skipped_paths = {path for path, _ in skipped}
    checked_count = sum(1 for source in checked[:reported] if source.display not in skipped_paths)
    if cache is not None:
        cache.finish()  # the graph's specialised facts are still buffered
    if inputs is not None:
        if run_key is not None and not inputs.changed:
            assert cache is not None
            cache.store_run(run_key, (tuple(diagnostics), checked_count, tuple(skipped)))
        inputs.finish()
    return LintResult(
        tuple(diagnostics),
        checked_count,
        extracted,
        cached,
        workers,
        graph,
        tuple(skipped),
        facts=tuple(facts for facts in all_facts if facts is not None),
    )


def _stored_result(value: object, files: int) -> LintResult | None:
    """A result ``store_run`` kept, if ``value`` is one (anything else: a miss)."""
    match value:
        case (tuple() as diagnostics, int() as checked, tuple() as skipped) if all(
            isinstance(diagnostic, Diagnostic) for diagnostic in diagnostics
        ) and all(
            isinstance(item, tuple) and all(isinstance(part, str) for part in item)
            for item in skipped
        ):
            return LintResult(diagnostics, checked, 0, files, 0, None, skipped, reused=True)
    return None


def workspace_packages(
    sources: Sequence[SourceFile], packages: PackageGenerations
) -> list[Package]:
    """Every package holding a file of the run, by name and display directory."""
    found: dict[Path, Package] = {}
    for source in sources:
        name = packages.package_name(source.path)
        directory = packages.package_directory(source.path)
        if name is None or directory is None or directory in found:
            continue
        relative = source.path.relative_to(directory).as_posix()
        display = source.display[: -len(relative)].rstrip("/")
        found[directory] = Package(name, display, packages.package_depends(source.path))
    return list(found.values())


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
        dispatcher: Dispatcher[_Item, tuple[int, FileFacts]],
    ) -> None:
        self._sources = {source.display: source for source in sources}
        self._packages = packages
        self._fallback = fallback
        self._cache = cache
        self._max_file_size = max_file_size
        self._dispatcher = dispatcher
        self._memo: dict[tuple[str, LaunchArguments], FileFacts | None] = {}
        self._files: dict[str, tuple[bytes | None, str]] = {}

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
        asked: list[tuple[str, LaunchArguments]] = []
        for key in dict.fromkeys(wanted):
            if key in self._memo:
                continue
            found = self._job(len(asked), *key)
            if isinstance(found, tuple):
                asked.append(key)
                self._take(asked, self._dispatcher.put(found, len(found[1])))
            else:
                self._memo[key] = found
        self._take(asked, self._dispatcher.finish())

    def _take(
        self, asked: list[tuple[str, LaunchArguments]], results: Iterable[tuple[int, FileFacts]]
    ) -> None:
        for index, facts in results:
            self._memo[asked[index]] = facts

    def _job(
        self, index: int, display: str, arguments: LaunchArguments
    ) -> FileFacts | _Item | None:
        """The cached facts (None: nothing to specialise), or the work to extract them."""
        source = self._sources.get(display)
        if source is None or source.language not in SPECIALISABLE:
            return None
        data, content = self._read(source)
        if data is None:
            return None
        package = self._packages.for_file(source.path)
        cache_key = None
        if self._cache is not None:
            # The arguments are part of what the facts depend on: key them with the path.
            keyed = f"{display}\0{arguments!r}"
            cache_key = self._cache.key_of_digest(
                content, keyed, source.language, package, self._fallback
            )
            found = self._cache.load(cache_key, display)
            if found is not None:
                return found
        job = _Job(index, display, source.language, package, self._fallback, arguments)
        return job, data, cache_key

    def _read(self, source: SourceFile) -> tuple[bytes | None, str]:
        """A launch file's bytes and content digest, read once however many argument
        sets it is specialised under (up to 19 on realws)."""
        if source.display not in self._files:
            data, _, _ = read_file(source.path, self._max_file_size)
            self._files[source.display] = data, "" if data is None else content_digest(data)
        return self._files[source.display]


def report_graph(
    graph: Graph,
    rules: Sequence[Rule],
    *,
    reported: Sequence[SourceFile],
    facts: Sequence[FileFacts],
    per_file: list[list[Diagnostic]],
    suppressions_of: dict[int, list[Suppression]],
    settings: Settings,
    registry: Registry,
    texts: Mapping[str, str] | None = None,
) -> None:
    """Graph rules' findings, each into its file's slot with that file's suppressions;
    findings in files outside ``reported`` (a per-file run's context) are dropped.
    ``texts``: files' content by display path where it is not the file's on disk (an
    editor's unsaved buffer)."""
    slots = {source.display: index for index, source in enumerate(reported)}
    test_rules = test_code_codes(settings, registry)
    facts_of = {f.path: f for f in facts}
    found: dict[int, list[tuple[Rule, WorkspaceFinding]]] = {}
    for rule in rules:
        assert rule.check_workspace is not None
        for item in rule.check_workspace(graph, _context(rule, settings, frozenset())):
            index = slots.get(item.path)
            if index is not None:
                found.setdefault(index, []).append((rule, item))
    for index, items in sorted(found.items()):
        source = reported[index]
        file_facts = facts_of[source.display]
        relative = _relative_to_root(source.display, settings)
        ignored = ignored_for_path(settings, relative, registry)
        if texts is not None and source.display in texts:
            text = texts[source.display]
        else:
            data, _, _ = read_file(source.path, settings.max_file_size)
            text = decode_for_display(data or b"")
        to_diagnostic = _DiagnosticFactory(file_facts, settings, text)
        judging = _TestCodeFilter(file_facts, text, relative, settings, test_rules)
        fresh = [
            to_diagnostic(rule, item.finding.span, item.finding.message, item.finding.related)
            for rule, item in items
            if rule.code not in ignored and not (judging.spared(rule.code) and judging.is_test())
        ]
        suppressions = suppressions_of.get(index, [])
        fresh, used = _apply_suppressions(fresh, suppressions, registry)
        per_file[index] = [d for d in per_file[index] if not _now_used(d, used)] + fresh


def _now_used(diagnostic: Diagnostic, used: set[tuple[Suppression, str]]) -> bool:
    """An RN002 'silences nothing' on a suppression a graph finding turned out to use."""
    return diagnostic.code == UNUSED_SUPPRESSION and any(
        suppression.span == diagnostic.span
        and diagnostic.message.startswith(f"suppression of {code} ")
        for suppression, code in used
    )


@dataclass(frozen=True)
class _Job:
    """What an extractor needs besides the bytes; small, so cheap to send to a worker."""

    index: int
    display: str
    language: Language
    package_generation: Generation | None
    fallback_generation: Generation
    arguments: LaunchArguments = ()  # a launch file specialised under its includer's


# A job, the file's bytes, and the key its facts are cached under.
_Item = tuple[_Job, bytes, str | None]


def extract_batch(cache: FactsCache | None, batch: list[_Item]) -> list[tuple[int, FileFacts]]:
    """Extract and store facts: the work of a worker process, or of the main one.

    Module-level so that worker processes can run it; extractor modules are imported on
    first use, in whichever process extracts.
    """
    results: list[tuple[int, FileFacts]] = []
    for job, data, key in batch:
        generations = (job.package_generation, job.fallback_generation)
        if job.arguments:
            specialise: _ExtractWithArguments = _extractor_module(job.language).extract
            facts = specialise(job.display, data, *generations, arguments=job.arguments)
        else:
            facts = extractor_for(job.language)(job.display, data, *generations)
        if cache is not None and key is not None:
            cache.store(key, facts)
        results.append((job.index, facts))
    if cache is not None:
        cache.flush()  # a worker process has no "end of run": every batch ends its writes
    return results


def check_file(
    facts: FileFacts,
    text: str,
    settings: Settings,
    registry: Registry,
    enabled: frozenset[str],
    *,
    known_service_types: frozenset[str] = frozenset(),
    test_rules: frozenset[str] | None = None,
) -> tuple[list[Diagnostic], list[Suppression]]:
    """Every diagnostic of one file: rule findings, then suppression bookkeeping; and the
    file's suppressions, for the graph rules' findings still to come.

    ``test_rules``: the rules that judge test code (``test_code_codes``), when the caller
    has them already."""
    relative = _relative_to_root(facts.path, settings)
    active = enabled - ignored_for_path(settings, relative, registry)
    to_diagnostic = _DiagnosticFactory(facts, settings, text)
    diagnostics = [
        to_diagnostic(rule, finding.span, finding.message, finding.related, finding.fix)
        for rule in registry.rules
        if rule.code in active and rule.check is not None
        for finding in _run(rule, facts, settings, known_service_types)
    ]
    suppressions = find_suppressions(text, facts.language)
    # Whether the file is test code is asked only when the answer can change something.
    if test_rules is None:
        test_rules = test_code_codes(settings, registry)
    judging = _TestCodeFilter(facts, text, relative, settings, test_rules)
    if suppressions or any(judging.spared(d.code) for d in diagnostics):
        enabled = judging.rules(enabled)
        active = judging.rules(active)
        diagnostics = [d for d in diagnostics if d.code in active]
    diagnostics, used = _apply_suppressions(diagnostics, suppressions, registry)
    unused_rule = registry.by_code_or_name(UNUSED_SUPPRESSION)
    invalid_rule = registry.by_code_or_name(INVALID_SUPPRESSION)
    for suppression in suppressions:
        for key in suppression.keys:
            rule = registry.by_code_or_name(key)
            if rule is None and is_our_code(key) and invalid_rule and invalid_rule.code in active:
                message = f"suppression names unknown rule '{key}'; see `roslint-names rules`"
                diagnostics.append(to_diagnostic(invalid_rule, suppression.span, message))
            elif (
                rule is not None
                and rule.code in enabled
                and (suppression, rule.code) not in used
                and unused_rule
                and unused_rule.code in active
            ):
                message = f"suppression of {rule.code} ({rule.name}) silences nothing here"
                diagnostics.append(to_diagnostic(unused_rule, suppression.span, message))
    return diagnostics, list(suppressions)


class _TestCodeFilter:
    """The rules that judge one file: all the run's, or in test code those that
    ``[test-code]`` selects (``test_code``). The file is classified on first need."""

    def __init__(
        self,
        facts: FileFacts,
        text: str,
        relative: str,
        settings: Settings,
        judging: frozenset[str],
    ) -> None:
        self._facts, self._text, self._relative = facts, text, relative
        self._settings = settings
        self._judging = judging
        self._test: bool | None = None

    def spared(self, code: str) -> bool:
        """Whether a finding of ``code`` is dropped if the file is test code."""
        return code not in self._judging

    def is_test(self) -> bool:
        if self._test is None:
            self._test = is_test_code(
                self._relative, self._facts.language, self._text, self._settings
            )
        return self._test

    def rules(self, codes: frozenset[str]) -> frozenset[str]:
        return codes & self._judging if self.is_test() else codes


def recheck(
    path: Path,
    display: str,
    data: bytes,
    *,
    settings: Settings,
    registry: Registry,
    packages: PackageGenerations,
) -> tuple[int, set[tuple[str, int]]]:
    """One file's parse errors and per-file findings ``(code, line)`` for ``data`` as its
    content: what ``--fix`` asks of a file before it writes it."""
    language = classify(path)
    if language is None or language not in EXTRACTOR_MODULES:
        return 0, set()
    fallback = settings.ros or DEFAULT_GENERATION
    facts = extractor_for(language)(display, data, packages.for_file(path), fallback)
    enabled = enabled_codes(settings, registry)
    found, _ = check_file(facts, decode_for_display(data), settings, registry, enabled)
    return len(facts.parse_errors), {(d.code, d.span.line) for d in found if not d.suppressed}


def _run(
    rule: Rule, facts: FileFacts, settings: Settings, known_service_types: frozenset[str]
) -> Iterable[Finding]:
    assert rule.check is not None
    return rule.check(facts, _context(rule, settings, known_service_types))


def _context(rule: Rule, settings: Settings, known_service_types: frozenset[str]) -> RuleContext:
    options = {**rule.options, **settings.rule_options.get(rule.code, {})}
    return RuleContext(
        max_depth=settings.max_depth,
        options=options,
        policies=settings.policies,
        known_service_types=known_service_types,
    )


def typed_services(facts: FileFacts) -> set[str]:
    """``package/Name`` of every service type the file serves or calls."""
    return {
        str(parsed)
        for use in facts.names
        if use.kind is Kind.SERVICE
        and use.type_name
        and (parsed := parse_type(use.type_name)) is not None
        and parsed.package is not None
    }


def _apply_suppressions(
    diagnostics: list[Diagnostic], suppressions: Sequence[Suppression], registry: Registry
) -> tuple[list[Diagnostic], set[tuple[Suppression, str]]]:
    used: set[tuple[Suppression, str]] = set()
    result: list[Diagnostic] = []
    for diagnostic in diagnostics:
        silenced = False
        for suppression in suppressions:
            if diagnostic.span.line not in suppression.lines:
                continue
            for key in suppression.keys:
                rule = registry.by_code_or_name(key)
                if rule is not None and rule.code == diagnostic.code:
                    used.add((suppression, rule.code))
                    silenced = True
        result.append(replace(diagnostic, suppressed=True) if silenced else diagnostic)
    return result, used


class _DiagnosticFactory:
    """Binds findings of one file to its path, severities and source lines.

    The lines are split on the first diagnostic only: most files have none.
    """

    def __init__(self, facts: FileFacts, settings: Settings, text: str) -> None:
        self.facts = facts
        self.settings = settings
        self._text = text
        self._lines: list[str] | None = None

    def __call__(
        self,
        rule: Rule,
        span: Span,
        message: str,
        related: tuple[RelatedLocation, ...] = (),
        fix: Fix | None = None,
    ) -> Diagnostic:
        if self._lines is None:
            self._lines = split_lines(self._text)
        severity = self.settings.severity.get(rule.code) or rule.severity_for(self.facts.generation)
        in_file = 0 < span.line <= len(self._lines)
        source_line = self._lines[span.line - 1] if in_file else None
        return Diagnostic(
            path=self.facts.path,
            span=span,
            code=rule.code,
            rule_name=rule.name,
            severity=severity,
            message=message,
            related=related,
            source_line=source_line,
            edit=None if fix is None or fix.tokens else located(fix, span, source_line),
            renaming=fix if fix is not None and fix.tokens else None,
        )


def _unreadable(source: SourceFile, reason: str) -> FileFacts:
    return _file_error(source, f"cannot read file: {reason}")


def _not_text(source: SourceFile) -> FileFacts:
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


def decode_for_display(data: bytes) -> str:
    """Text for suppression scanning and source excerpts; never fails."""
    return data.decode(bom_encoding(data) or "utf-8", errors="replace")


def _relative_to_root(display: str, settings: Settings) -> str:
    """Where per-file ignores look: the file's path below the root, else its absolute
    path. String operations, not ``Path.relative_to``: this runs for every file."""
    absolute = display if os.path.isabs(display) else os.path.join(os.getcwd(), display)
    root = os.path.join(os.fspath(settings.root), "")
    relative = absolute[len(root) :] if absolute.startswith(root) else absolute
    return relative.replace(os.sep, "/") if os.sep != "/" else relative

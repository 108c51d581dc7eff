"""The pipeline from discovered files to diagnostics (``lint``), and one file's checks.

Facts come from ``gather`` (the cache, extraction in this process or in workers); the
per-file rules, suppressions and the test-code policy run here (``check_file``), then
the workspace graph and the graph rules. Diagnostics never depend on how facts came.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Callable, Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from functools import cache, lru_cache, partial
from pathlib import Path
from typing import TYPE_CHECKING, NamedTuple

from . import clean_files, same_facts, shifts
from .collection import kept_for_the_run
from .config import Settings, enabled_codes, ignored_for_path, ros1_python2, test_code_codes
from .decisions import one_per_decision
from .discover import SourceFile, classify, display_path_text
from .editing.fixing import located
from .gather import (
    DEFAULT_GENERATION,
    EXTRACTOR_MODULES,
    Gatherer,
    Specialiser,
    Verdict,
    extract_batch,
    extract_file,
    gave_up,
)
from .generation import (
    PackageGenerations,
    service_types,
    visible_service_types,
    workspace_plugin_names,
)
from .lines import split_lines
from .model import (
    Answer,
    Decision,
    Diagnostic,
    FileFacts,
    Finding,
    Fix,
    Generation,
    Kind,
    Language,
    RelatedLocation,
    Span,
)
from .moves import Moves, UnplacedError, moved_finding
from .reading import decode_for_display, read_file
from .registry import Registry
from .rule import Rule, RuleContext, WorkspaceFinding
from .run_inputs import ADDED, RunInputs, is_facts_key
from .same_facts import KeptGraph, KeptLaunch, Replay, RunWide
from .speculation import Speculation
from .suppress import Suppression, find_suppressions, is_our_code
from .symbols import PackageConstants, uses_constants
from .templates import holds_placeholder, is_template
from .test_code import is_example_code, is_test_code
from .types import parse_type
from .wiring import WIRING_SOURCES, awaits_wiring, wired_by
from .workers import Dispatcher
from .workspace.build import _TestFiles, build_parts
from .workspace.built import BuiltSources
from .workspace.graph import Graph
from .workspace.index import (
    CODE_LANGUAGES,
    Package,
    PackageFiles,
    WorkspaceIndex,
    companions,
    named_once,
)
from .workspace.interfaces import service_definitions
from .workspace.launch_parts import CodeParameterParts, LaunchParts
from .workspace.launch_patch import LazyFacts, launch_edit, launch_patched, parameter_edit
from .workspace.launch_tree import LAUNCH_LANGUAGES
from .workspace.parameter_patch import parameters_patched
from .workspace.patch import (
    NOT_CODE_FIELDS,
    Moved,
    edits_of,
    for_patching,
    moved_code_parameters,
    parameter_part,
    same_places,
    with_parameters,
)
from .workspace.patch import patched as patch_graph
from .workspace.program_patch import ProgramsAnew, program_edit, programs_anew

if TYPE_CHECKING:
    from .cache import FactsCache  # imported by the caller that wants a cache

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
    # Reported C++ sources no build file compiles, whose findings about names were
    # dropped (``workspace.built``): ``--verbose`` names them.
    unbuilt: tuple[str, ...] = ()
    # Reported C++ sources built only into tests rostest starts, whose findings about the
    # node name they hand ``ros::init`` were dropped: ``--verbose`` names them too.
    rostest_named: tuple[str, ...] = ()


Progress = Callable[[int, int], None]  # (files done, files in total)
_Contexts = Mapping[str, RuleContext]  # a context per per-file rule, by code


@dataclass(frozen=True)
class RunOptions:
    """How a run goes about it, never what it reports: the output is the same for all."""

    jobs: int = 1  # worker processes for extraction; 0: every core; 1: none
    cache: FactsCache | None = None
    progress: Progress | None = None
    # The directories the walk listed with no package.xml (``discover``): none is looked for.
    without_manifest: frozenset[str] = frozenset()


def lintable(sources: Iterable[SourceFile]) -> list[SourceFile]:
    return [source for source in sources if source.language in EXTRACTOR_MODULES]


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

    The pipeline: (1) a run over the same inputs as a recent one is that run's stored
    result (``run_inputs``); otherwise (2) every file's facts are gathered, from the cache
    or by extraction in workers (``gather``), and (3) each file is checked by the per-file
    rules as its facts arrive, in whatever order; (4) the workspace graph is built once
    every file is in and the graph rules report into the files of ``sources``; (5) the
    diagnostics are joined in discovery order, each decision reported once
    (``decisions``), sorted, and the result stored for (1).
    Arrival order never shows in the output.

    ``context`` files (the rest of the workspace of a per-file run) are gathered for the
    graph rules, and their launch files for the absolute names they wire (``wiring``,
    which RN202 reads): nothing is reported in them. ``want_graph`` returns the graph;
    ``want_facts`` every file's facts (``renames`` searches them), without the graph when
    no graph rule needs it.
    """
    # What a run keeps (the files found, their statuses, their facts, the graph) holds no
    # cycle: the collector does not walk it again and again (``collection``).
    with kept_for_the_run():
        whole = None if want_graph or want_facts else _whole_workspace(sources, context, run)
        if whole is not None and _graph_rules_on(settings, registry):
            workspace, focus = whole
            return _lint(
                workspace,
                settings,
                registry,
                run,
                context=(),
                want_graph=False,
                want_facts=False,
                focus=focus,
            )
        return _lint(
            sources,
            settings,
            registry,
            run,
            context=context,
            want_graph=want_graph,
            want_facts=want_facts,
        )


def _graph_rules_on(settings: Settings, registry: Registry) -> bool:
    enabled = enabled_codes(settings, registry)
    return any(rule.check_workspace and rule.code in enabled for rule in registry.rules)


def _whole_workspace(
    sources: Sequence[SourceFile], context: Sequence[SourceFile], run: RunOptions
) -> tuple[Sequence[SourceFile], frozenset[str]] | None:
    """The workspace of a run over some of its files (pre-commit's, which names the files
    staged) that is run whole and reported in those files only, where a cache keeps what
    it finds: its graph, its replay and its keys are then the whole workspace's, which the
    next such run takes up (``same_facts``, ``workspace.patch``) whatever files it names,
    as a run over the workspace does; run over the files named, each new set of them
    built the graph again (13 s at 8 copies of the benchmark's workspace). None where a
    file named is not one of the workspace's as its walk found it (ignored by git, say,
    or under another path): that run keeps its own way. With the display paths of the
    files it reports in."""
    if run.cache is None or not context:
        return None
    found = {(source.location, source.display) for source in context}
    named = lintable(sources)
    if all((source.location, source.display) in found for source in named):
        return context, frozenset(source.display for source in named)
    return None


def _lint(
    sources: Sequence[SourceFile],
    settings: Settings,
    registry: Registry,
    run: RunOptions,
    *,
    context: Sequence[SourceFile],
    want_graph: bool,
    want_facts: bool,
    focus: frozenset[str] | None = None,
) -> LintResult:
    """``lint``; with ``focus``, the run over the whole workspace reported in the files of
    those display paths alone, as a run over them with the rest as context reports
    (``_whole_workspace``): the decisions are made among their findings, their stored
    result kept under a key of its own."""
    enabled = enabled_codes(settings, registry)
    graph_rules = [r for r in registry.rules if r.check_workspace and r.code in enabled]
    rule_of = {rule.code: rule for rule in graph_rules}
    packages = PackageGenerations(run.without_manifest)
    # What the run's packages depend on, once they are all looked up (once keyed).
    depends = lru_cache(maxsize=1)(packages.depends_digest)
    fallback = settings.ros or DEFAULT_GENERATION
    python2 = ros1_python2(settings)
    cache = run.cache
    wiring = any(rule.reads_wiring and rule.code in enabled for rule in registry.rules)
    keep_facts = bool(graph_rules) or want_graph or want_facts
    files = lintable(sources)
    reported = len(files)
    named = [*sources, *context]  # whose packages' plugins the rules know (``plugins``)
    if not keep_facts and wiring:
        # Only what may wire names: parsing every C++ file of the workspace would be the
        # whole cost of a one-file run, for nothing.
        context = [source for source in context if source.language in WIRING_SOURCES]
    if keep_facts or wiring:
        given = {source.location for source in files}
        files += [source for source in lintable(context) if source.location not in given]
    else:
        context = ()
    workspace = [*sources, *context]
    packages_now = partial(workspace_packages, workspace, packages)  # the graph's packages

    # (1) A stored result has neither the graph nor the facts: not for a caller wanting them.
    inputs: RunInputs | None = None
    run_key: str | None = None
    fresh = want_graph or want_facts
    if cache is not None and files:
        inputs = RunInputs(
            cache,
            files,
            workspace,
            reported=reported,
            settings=settings,
            registry=registry,
            packages=packages,
            fallback=fallback,
            ros1_python2=python2,
            named=named,
        )
        # Nothing changed since a run that kept its key: its result, no file keyed. (A
        # focused run keeps no such key: it is the whole run's.)
        remembered = None if fresh else inputs.unchanged_key()
        if remembered is not None and focus is None:
            stored = _stored_result(cache.load_run(remembered), len(files))
            if stored is not None:
                return stored
    # Read from the manifests of the whole workspace (``plugins``) before the run is keyed,
    # which then covers every description they export (and after the inputs were made:
    # what the packages are seen to be is taken after they started, ``unchanged``); or
    # the last run's, where the inputs took up its packages' lookups (the same files, their
    # manifests as they were).
    if packages.restored:
        plugin_names = frozenset(packages.plugin_names)
    else:
        plugin_names = workspace_plugin_names(named, packages)
    if inputs is not None:
        assert cache is not None
        run_key = None if fresh else inputs.key_first()
        stored_at = None if run_key is None else _focused(run_key, focus)
        stored = (
            None if stored_at is None else _stored_result(cache.load_run(stored_at), len(files))
        )
        if stored is not None:
            inputs.finish(kept_key=run_key if focus is None else None)
            return stored
    if cache is not None:
        cache.writable()  # create the directory now, not racing in every worker
    # The files the per-file rules found nothing in last time, under the same rules,
    # settings, plugin names and packages (``clean_files``): checked again only if edited.
    clean_key: str | None = None
    clean: frozenset[bytes] = frozenset()
    verdicts: dict[bytes, clean_files.Verdict] = {}
    if cache is not None and inputs is not None:
        clean_key = clean_files.memo_key(
            settings, registry, enabled, plugin_names, packages.manifests.keys()
        )
        clean, verdicts = clean_files.loaded(cache.load_checks(clean_key))
    known_inputs = inputs

    def entry_of(index: int) -> bytes | None:
        key = None if known_inputs is None else known_inputs.facts_key(index)
        return None if key is None else clean_files.entry(files[index].display, key)

    # A file the per-file rules can judge alone is judged where it is extracted, in the
    # workers: the main process only gathers the verdicts (issue 30's serial part).
    judge = FileChecks(
        settings,
        registry,
        enabled,
        test_code_codes(settings, registry),
        rule_contexts(registry, settings, plugin_names=plugin_names),
        wiring,
    )
    checks = _FileChecks(
        files=len(files),
        reported=reported,
        judge=judge,
        service_types=set(service_types(workspace, packages)),
        plugin_names=plugin_names,
        keep_facts=keep_facts,
        progress=run.progress,
        package_of=lambda index: package_display(files[index], packages),
        visible_of=lambda index: packages.visible_packages(files[index].path),
        read=lambda index: read_file(files[index].path, settings.max_file_size)[0] or b"",
        clean=clean,
        verdicts=verdicts,
        entry_of=entry_of,
    )
    graph: Graph | None = None
    launch_parts: LaunchParts | None = None  # each launch tree's part of it
    code_parts: CodeParameterParts | None = None  # what its nodes' parameters came from
    built_with: list[Package] = []  # the packages the graph was built with

    # A run over the files of a run that built the graph, whose facts are the same, takes
    # its graph findings (``same_facts``); any run that builds the graph keeps them.
    def replay_key() -> str | None:
        """Where this run's replay is kept, once the run is keyed (first: an earlier
        run left its digests; else last), for a run that keeps what it finds."""
        if not graph_rules or fresh or clean_key is None or inputs is None:
            return None
        return None if inputs.place_key is None else same_facts.key(inputs.place_key, clean_key)

    kept_at = replay_key()
    raw_replay = None if kept_at is None or cache is None else cache.load_replay(kept_at)
    last_replay = same_facts.loaded(raw_replay, len(files), reported)
    # Where the graph a patch starts from is kept: under the replay's key, or the key of
    # the run whose replay this one's files were renumbered from (``shifts``).
    graph_place: _GraphPlace | None = None if kept_at is None else _GraphPlace(kept_at)
    shifted: _Shift | None = None
    if last_replay is None and kept_at is not None and not context:
        assert cache is not None and inputs is not None and clean_key is not None
        shifted = _shifted(cache, inputs, clean_key, files, depends())
        if shifted is not None:
            last_replay = shifted.replay
            graph_place = _GraphPlace(shifted.replay_at, shifted.renumbering)
    graph_found: Mapping[int, tuple[tuple[str, Finding], ...]] = {}
    specialised: frozenset[str] = frozenset()
    extract = partial(extract_batch, cache, checker=judge)
    # A file whose worker is killed past its time budget is one RN001 (``gave_up``).
    give_up = partial(gave_up, cache)
    with Dispatcher(extract, run.jobs, expected_items=len(files), give_up=give_up) as dispatcher:
        # Launch files extracted again under their includers' arguments (a build's, a
        # launch patch's) go through the same workers, a depth of the trees at a time.
        specialiser = partial(
            Specialiser,
            files,
            packages,
            fallback,
            cache,
            settings.max_file_size,
            dispatcher=dispatcher,
            ros1_python2=python2,
        )
        # A run that builds the graph, over workers, walks its launch trees' depths
        # while the files are extracted (``speculation``).
        ahead: Speculation | None = None
        if last_replay is None and (graph_rules or want_graph) and dispatcher.parallel:
            launch_files = sum(source.language in Speculation.languages for source in files)
            ahead = Speculation(
                specialiser(),
                packages_now,
                launch_files=launch_files,
                first=len(files),
            )
        # (2) and (3)
        gathered = Gatherer(
            files=files,
            reported=reported,
            cache=cache,
            inputs=inputs,
            dispatcher=dispatcher,
            packages=packages,
            fallback=fallback,
            ros1_python2=python2,
            max_file_size=settings.max_file_size,
            ahead=ahead,
        )
        patch = None
        if cache is not None and inputs is not None and graph_place is not None:
            assert clean_key is not None
            patch = _GraphPatch(
                gathered,
                checks,
                inputs,
                cache,
                graph_place,
                graph_rules,
                settings,
                specialiser,
                elsewhere=partial(_base_place, cache, inputs, clean_key, files),
                depends=depends,
                packages=packages_now,
                may_rebase=not context,
            )
        replayed = _take_facts(
            gathered,
            checks,
            last_replay,
            inputs,
            rules=rule_of,
            patch=patch,
            stands=shifted is None or shifted.stands,
        )
        workers = dispatcher.workers  # that extracted the files (specialisations may start some)
        if inputs is not None and not fresh and run_key is None:
            run_key = inputs.key_last()
        if replayed is not None:
            checks.resume(
                replayed.replay,
                replayed.edited,
                {files[index].display for index in replayed.edited},
            )
        checks.finish()
        if replayed is not None:
            graph_found, specialised = replayed.replay.graph, replayed.replay.specialised
            if patch is not None and patch.rebased is not None:  # kept as a build's
                graph, launch_parts, code_parts, built_with = patch.rebased
            _report_replayed(
                replayed,
                files=files,
                checks=checks,
                rules=rule_of,
                settings=settings,
                registry=registry,
            )
        # (4) The graph, and what each launch tree gave it (kept for a launch patch).
        elif graph_rules or want_graph:
            known_facts = checks.facts()
            if ahead is None:
                specialise, built_with = specialiser(), packages_now()
            else:
                specialise, built_with = ahead.specialiser, list(ahead.packages())
            graph, launch_parts, code_parts = build_parts(
                known_facts, built_with, specialise, specialise.prepare
            )
            reported_graph = report_graph(
                graph,
                graph_rules,
                reported=files[:reported],
                facts=known_facts,
                per_file=checks.per_file,
                suppressions_of=checks.suppressions_of,
                settings=settings,
                registry=registry,
            )
            graph_found = {
                index: tuple((rule.code, item.finding) for rule, item in items)
                for index, items in reported_graph.items()
            }
            specialised = specialise.specialised

    # (5)
    displays = [source.display for source in files[:reported]]
    unbuilt_at, named_at = checks.spare(displays, None if replayed is None else replayed.edited)
    if replayed is not None:
        skipped = replayed.replay.skipped
        unbuilt_at = _with_edited(replayed.replay.unbuilt, unbuilt_at, replayed.edited)
        named_at = _with_edited(replayed.replay.rostest_named, named_at, replayed.edited)
    else:
        skipped = tuple(gathered.skipped)
    shown = [focus is None or display in focus for display in displays]  # reported in
    unbuilt = [displays[index] for index in unbuilt_at if shown[index]]
    rostest_named = [displays[index] for index in named_at if shown[index]]
    # What a run whose facts are these takes (``same_facts``).
    kept_replay = None
    kept_at = replay_key()
    if kept_at is not None and inputs is not None:
        kept_replay = Replay(
            inputs.tags,
            reported,
            {index: tuple(found) for index, found in enumerate(checks.per_file) if found},
            graph_found,
            specialised,
            checks.run_wide(),
            skipped,
            tuple(unbuilt_at),
            tuple(named_at),
        )
    per_file = one_per_decision(
        [found if shown[index] else [] for index, found in enumerate(checks.per_file)]
    )
    diagnostics = sorted(
        (diagnostic for found in per_file for diagnostic in found), key=Diagnostic.sort_key
    )
    skipped_paths = {path for path, _ in skipped}
    checked_count = sum(
        1
        for index, source in enumerate(files[:reported])
        if shown[index] and source.display not in skipped_paths
    )
    if cache is not None:
        cache.finish()  # the graph's specialised facts are still buffered
    kept_key = None
    if inputs is not None:
        if run_key is not None and not inputs.changed:
            assert cache is not None
            kept_key = run_key if focus is None else None
            kept = (
                tuple(diagnostics),
                checked_count,
                tuple(skipped),
                tuple(unbuilt),
                tuple(rostest_named),
            )
            cache.store_run(_focused(run_key, focus), kept)
            if kept_replay is not None and kept_at is not None:
                cache.store_replay(kept_at, kept_replay.stored())
                _keep_base(
                    cache,
                    inputs,
                    clean_key,
                    kept_at,
                    files=files,
                    reported=reported,
                    depends=depends(),
                )
                # A graph this run's files were renumbered to, not built: where it is (as
                # the patch found it, where one ran).
                moved = None
                renumbered = shifted is not None or (patch is not None and patch.elsewhere_used)
                if graph is None and renumbered and graph_place is not None:
                    patched_from = None if patch is None else patch.graph_from
                    moved = patched_from or graph_place.resolved(cache, files)
                if moved is not None and moved.renumbering is not None:
                    move = shifts.GraphMove(moved.key, moved.renumbering)
                    cache.store_graph_move(kept_at, move.stored())
                # What a later run over the workspace patches (``workspace.patch``); not
                # a run over some files with the rest as context (one that names a file
                # its workspace's walk does not find), whose set is seldom run again.
                if graph is not None and not context:
                    kept_graph = KeptGraph(
                        inputs.tags,
                        for_patching(graph),
                        graph_found,
                        tuple(built_with),
                        depends(),
                    )
                    cache.store_graph(kept_at, kept_graph.stored())
                    if launch_parts is not None:
                        kept_launch = KeptLaunch(inputs.tags, parameter_part(graph), launch_parts)
                        cache.store_launch_parts(kept_at, kept_launch.stored())
                    if code_parts is not None:
                        kept_code = same_facts.KeptCode(inputs.tags, code_parts)
                        cache.store_code_parameters(kept_at, kept_code.stored())
        if clean_key is not None and not inputs.changed:
            assert cache is not None
            # A run over some files (pre-commit's), or one that checked only its edited
            # files (``same_facts``), adds to the set of the whole workspace's run; a run
            # over the workspace replaces it, forgetting files since edited.
            partial_run = bool(context) or replayed is not None
            found = clean | checks.clean_now if partial_run else checks.clean_now
            judged = verdicts | checks.verdicts_now if partial_run else checks.verdicts_now
            if found != clean or judged != verdicts:
                cache.store_checks(clean_key, clean_files.stored(found, judged))
        inputs.finish(kept_key)
    return LintResult(
        tuple(diagnostics),
        checked_count,
        gathered.extracted,
        len(files) - gathered.extracted if replayed is not None else gathered.cached,
        workers,
        graph,
        tuple(skipped),
        facts=tuple(checks.facts()),
        unbuilt=tuple(unbuilt),
        rostest_named=tuple(rostest_named),
    )


@dataclass
class _FileChecks:
    """The per-file rules over each file's facts as they arrive; what the graph rules
    then need: the diagnostics in one slot per reported file (joined in discovery order,
    so arrival order never shows), each file's suppressions, and every file's facts.

    RN204 compares a service's name with every service type of the run (of the file's own
    generation), RN202 an absolute name with those the launch files of the run wire
    (``wiring``), and a C++ name held in another file's constant gets its value from the
    headers of the run (``symbols``), all known only once every file is in: files that
    serve or call a typed service, hand an endpoint an absolute name, or use such a
    constant, wait for ``finish``; the others, nearly all, are checked as they arrive.
    """

    files: int
    reported: int
    judge: FileChecks  # the per-file rules, their settings and contexts, as workers run them
    service_types: set[tuple[Generation | None, str]]
    plugin_names: frozenset[str]  # ``plugins``: the workspace's pluginlib plugin names
    keep_facts: bool
    progress: Progress | None
    package_of: Callable[[int], str | None]  # the display directory of a file's package
    visible_of: Callable[[int], frozenset[str] | None]  # its package and dependencies (RN204)
    read: Callable[[int], bytes]  # a file's bytes, for one the gathering did not read
    # Files found clean by the same checks before (``clean_files``), the verdicts of the
    # others, and each file's entry in those once its facts key is known.
    clean: frozenset[bytes] = frozenset()
    verdicts: Mapping[bytes, clean_files.Verdict] = field(default_factory=dict)
    entry_of: Callable[[int], bytes | None] = lambda index: None
    per_file: list[list[Diagnostic]] = field(init=False)
    clean_now: set[bytes] = field(default_factory=set)
    verdicts_now: dict[bytes, clean_files.Verdict] = field(default_factory=dict)
    suppressions_of: dict[int, list[Suppression]] = field(default_factory=dict)
    _all_facts: list[FileFacts | None] = field(init=False)
    _waiting: list[tuple[int, FileFacts, bytes | None]] = field(default_factory=list)
    _unresolved: list[int] = field(default_factory=list)  # files only the graph reads
    _constants: PackageConstants = field(default_factory=PackageConstants)
    _wired: set[str] = field(default_factory=set)  # absolute names launch files remap to
    _rejected: dict[str, set[str]] = field(default_factory=dict)  # package: fixture names
    _built: BuiltSources = field(default_factory=BuiltSources)
    _lookups: shifts.Lookups = field(default_factory=shifts.Lookups)  # ``RunWide``'s
    _done: int = 0

    def __post_init__(self) -> None:
        self.per_file = [[] for _ in range(self.reported)]
        self._all_facts = [None] * self.files

    def take(
        self, index: int, facts: FileFacts, data: bytes | None, verdict: Verdict | None = None
    ) -> None:
        """One file's facts as they arrive; ``verdict``: the per-file rules' findings where
        the worker that extracted it judged it already (``FileChecks``)."""
        if self.keep_facts:
            self._all_facts[index] = facts
        types = typed_services(facts)
        self.service_types.update((facts.generation, spelling) for spelling in types)
        self._constants.add(facts)
        if self.judge.wiring:
            self._wired.update(
                launch_wiring(facts, partial(self._bytes, index, data), self.judge.settings)
            )
        if facts.rejected_fixtures and (package := self.package_of(index)) is not None:
            self._rejected.setdefault(package, set()).update(facts.rejected_fixtures)
        if facts.compiled is not None or facts.included_sources:
            self._built.add(facts, self.package_of(index))
        if facts.launch_nodes or facts.includes or facts.parameter_loads or facts.executables:
            self._lookups.add(facts)
        symbols = uses_constants(facts)
        if index < self.reported:
            if waits_for_the_run(facts, self.judge.wiring):
                self._waiting.append((index, facts, data))
            elif verdict is not None:
                self._judged(index, *verdict)
            else:
                self._check_unless_clean(index, facts, data, self.judge.contexts)
        elif symbols and self.keep_facts:
            self._unresolved.append(index)
        self._done += 1
        if self.progress is not None:
            self.progress(self._done, self.files)

    def _check_unless_clean(
        self,
        index: int,
        facts: FileFacts,
        data: bytes | None,
        contexts: _Contexts,
        wired: bytes = b"",
    ) -> None:
        """Check a file whose verdict depends on nothing but itself, the run's settings
        and (``wired``: their digest) the names the launch files wire; one judged before
        under the same has that verdict now."""
        entry = self.entry_of(index)
        if entry is not None and wired:
            entry = clean_files.under(entry, wired)
        if entry is None:
            self._check(index, facts, data, contexts)
        elif entry in self.clean:
            self.clean_now.add(entry)
        elif (known := self.verdicts.get(entry)) is not None:
            self._keep(index, list(known[0]), list(known[1]))
            self.verdicts_now[entry] = known
        else:
            self._remember(entry, *self._check(index, facts, data, contexts))

    def _judged(
        self, index: int, diagnostics: list[Diagnostic], suppressions: list[Suppression]
    ) -> None:
        """A verdict made elsewhere (``FileChecks``), kept as ``_check`` keeps its own."""
        self._keep(index, diagnostics, suppressions)
        entry = self.entry_of(index)
        if entry is not None:
            self._remember(entry, diagnostics, suppressions)

    def _remember(
        self, entry: bytes, diagnostics: list[Diagnostic], suppressions: list[Suppression]
    ) -> None:
        """A file's verdict for the next run (``clean_files``), as the rules made it."""
        if diagnostics or suppressions:
            self.verdicts_now[entry] = (tuple(diagnostics), tuple(suppressions))
        else:
            self.clean_now.add(entry)

    def _bytes(self, index: int, data: bytes | None) -> bytes:
        return self.read(index) if data is None else data

    def spare(
        self, displays: Sequence[str], only: Sequence[int] | None
    ) -> tuple[list[int], list[int]]:
        """Drop the findings the workspace says do not hold in their files (below), in
        the reported files at ``only`` (None: in all); the files judged unbuilt and those
        judged named by rostest (their indices), for ``--verbose``. ``displays``: the
        reported files' display paths. After the fixtures, unbuilt sources and names
        rostest replaces are spared: a finding in one must not stand for the others."""
        indices = range(len(self.per_file)) if only is None else sorted(only)
        indices = [index for index in indices if index < self.reported]
        if self._rejected:
            self._spare(displays, indices, lambda _: True, self._is_rejected)
        unbuilt = self._spare(displays, indices, _not_linter_code, self._built.unbuilt)
        named = self._spare(displays, indices, rostest_replaces, self._built.started_by_rostest)
        return unbuilt, named

    def _spare(
        self,
        displays: Sequence[str],
        indices: Iterable[int],
        spared: Callable[[Diagnostic], bool],
        applies: Callable[[str, str | None], bool],
    ) -> list[int]:
        """Drop the ``spared`` findings of each file at ``indices`` the workspace says
        they do not hold for (``applies``, asked only of a file holding some); the files
        it did that to (their indices). The rules: a file its package's tests load
        expecting it to be refused (``extract.python.fixtures``: its mistakes are the
        test's point); a C++ source no build file of its package compiles
        (``workspace.built``: it never runs; the linter's own findings, RN0xx, stay); the
        node name a C++ source hands ``ros::init`` where only rostest starts what it is
        built into (roslaunch names the node, ``rostest_replaces``)."""
        changed: list[int] = []
        for index in indices:
            found = self.per_file[index]
            kept = [diagnostic for diagnostic in found if not spared(diagnostic)]
            if len(kept) != len(found) and applies(displays[index], self.package_of(index)):
                self.per_file[index] = kept
                changed.append(index)
        return changed

    def _is_rejected(self, display: str, package: str | None) -> bool:
        name = display.rpartition("/")[2]
        return package is not None and name in self._rejected.get(package, ())

    def finish(self) -> None:
        """Check the files that waited for the run's service types, wiring and constants."""
        for index in self._unresolved:
            facts = self._all_facts[index]
            if facts is not None:
                self._all_facts[index] = self._constants.resolve(facts, self.package_of(index))
        wired = frozenset(self._wired)
        contexts = self._contexts_with(wired)
        wired_digest = clean_files.digest(wired)
        # The contexts of the files that compare with service types, by their generation
        # and the packages they see, with their digest: few distinct ones in a run.
        typed: dict[tuple[Generation, frozenset[str] | None], tuple[_Contexts, bytes]] = {}
        for index, extracted, data in self._waiting:
            facts = self._constants.resolve(extracted, self.package_of(index))
            if self.keep_facts:
                self._all_facts[index] = facts
            if typed_services(facts):
                context, digest = self._typed(typed, facts.generation, index, wired, wired_digest)
            else:  # it waited for the wiring or constants
                context, digest = contexts, wired_digest
            if uses_constants(extracted):
                self._check(index, facts, data, context)  # other files' constants: always
            else:  # clean under the same service types and wiring stays clean
                self._check_unless_clean(index, facts, data, context, digest)
        self._waiting.clear()
        self._unresolved.clear()

    def _contexts_with(
        self, wired: frozenset[str], known: frozenset[str] = frozenset()
    ) -> _Contexts:
        judge = self.judge
        return rule_contexts(judge.registry, judge.settings, known, wired, self.plugin_names)

    def _typed(
        self,
        memo: dict[tuple[Generation, frozenset[str] | None], tuple[_Contexts, bytes]],
        generation: Generation,
        index: int,
        wired: frozenset[str],
        wired_digest: bytes,
    ) -> tuple[_Contexts, bytes]:
        """The contexts of file ``index``, which compares with the service types it can
        see (RN204), and the digest of those types with the wiring's."""
        key = (generation, self.visible_of(index))
        found = memo.get(key)
        if found is None:
            known = visible_service_types(service_types_of(self.service_types, generation), key[1])
            digest = clean_files.under(clean_files.digest(known), wired_digest)
            found = memo[key] = (self._contexts_with(wired, known), digest)
        return found

    def run_wide(self) -> RunWide:
        """What the run gathered from every file's facts, for a run whose facts are the
        same (``same_facts``)."""
        return RunWide(
            frozenset(self.service_types),
            frozenset(self._wired),
            self._built.given(),
            {package: frozenset(names) for package, names in self._rejected.items()},
            frozenset(self._lookups.names),
            {name: frozenset(by) for name, by in self._lookups.naming.items()},
            dict(self._lookups.named),
        )

    def resume(self, replay: Replay, edited: Sequence[int], paths: Collection[str]) -> None:
        """Take a run's replay (``same_facts``) for every file but the ``edited`` ones
        (``paths``: their display paths), which were taken as any: their stored
        findings, and what the run gathered from every file's facts (the edited files'
        share of it as it is now). Before ``finish``: an edited file may wait for the
        run."""
        mine = set(edited)
        for index, found in replay.found.items():
            if index not in mine:
                self.per_file[index] = list(found)
        run_wide = replay.run_wide
        self.service_types.update(run_wide.service_types)
        self._wired.update(run_wide.wired)
        # The files taken by this run are in as they are now (a build file may compile
        # other sources: ``program_patch``), the others as the replay's run had them.
        self._built = built_as_taken(run_wide, self._built.given(), paths)
        self._rejected = {package: set(names) for package, names in run_wide.rejected.items()}
        self._lookups.update(run_wide.looked_up, run_wide.naming, run_wide.named_sources)

    def know_constants(self, facts: Iterable[FileFacts]) -> None:
        """The constants and includes of files the run does not take (a replay's, a
        patch's: the headers of the package of a file it checks again), for ``finish``
        to resolve the names of the files it takes."""
        for found in facts:
            self._constants.add(found)

    def facts_of(self, index: int) -> FileFacts | None:
        """File ``index``'s facts, when they were kept and it arrived."""
        return self._all_facts[index]

    def facts(self) -> list[FileFacts]:
        """Every file's facts, in discovery order (when they were kept)."""
        return [facts for facts in self._all_facts if facts is not None]

    def _check(
        self,
        index: int,
        facts: FileFacts,
        data: bytes | None,
        contexts: _Contexts,
    ) -> Verdict:
        """``data`` None: the file was not read, as it holds no suppression; its text is
        needed only for findings (their lines, fixes, whether it is test code). The
        verdict, as the rules made it."""
        text = "" if data is None else decode_for_display(data)
        diagnostics, found = self._check_text(facts, text, contexts)
        if data is None and diagnostics:
            diagnostics, found = self._check_text(
                facts, decode_for_display(self.read(index)), contexts
            )
        self._keep(index, diagnostics, found)
        return diagnostics, found

    def _keep(
        self, index: int, diagnostics: list[Diagnostic], suppressions: list[Suppression]
    ) -> None:
        if diagnostics:
            # Asked only of files with findings: proposals group answers by package.
            package = self.package_of(index)
            diagnostics = [replace(diagnostic, package=package) for diagnostic in diagnostics]
        self.per_file[index] = diagnostics
        if suppressions:
            self.suppressions_of[index] = suppressions

    def _check_text(self, facts: FileFacts, text: str, contexts: _Contexts) -> Verdict:
        return self.judge.check_text(facts, text, contexts)


class _Shift(NamedTuple):
    """A run over the files of an earlier run, some added or removed (``shifts``): where
    that run's replay is kept, how the files map, and the replay renumbered; whether it
    may stand as it is (each removed file said nothing), else only a patch of the
    graph may take it (a launch file removed: ``_GraphPatch``)."""

    replay_at: str
    renumbering: shifts.Renumbering
    replay: Replay
    stands: bool


def _shifted(
    cache: FactsCache,
    inputs: RunInputs,
    clean_key: str,
    files: Sequence[SourceFile],
    depends: str,
) -> _Shift | None:
    """The replay of the last run of this run's shape (``shifts.Base``), renumbered to its
    files; it stands where its packages depended on what they do now (``depends``) and
    each file it had and this run has not says nothing and is found by no name (its
    findings go with it), each added file asked the same once its facts are known
    (``_replay_moved``); else only a patch of the graph may take it."""
    found = _base_of(cache, inputs, clean_key, files)
    if found is None:
        return None
    base, renumbering = found
    earlier = same_facts.loaded(
        cache.load_replay(base.replay_at), len(base.displays), base.reported
    )
    if earlier is None:
        return None
    stands = base.depends == depends
    if stands and renumbering.removed:
        found_by = earlier.run_wide.lookups()
        gone = (_facts_by_tag(cache, earlier.tags[at], path) for at, path in renumbering.removed)
        stands = all(facts is not None and found_by.adds_nothing(facts) for facts in gone)
    replay = earlier.renumbered(renumbering, len(files))
    return _Shift(base.replay_at, renumbering, replay, stands)


def _facts_by_tag(cache: FactsCache, tag: str, display: str) -> FileFacts | None:
    """The facts of the file shown as ``display`` under ``tag`` (``RunInputs.tags``), None
    where the tag is no facts key or they are not kept."""
    return cache.load(tag, display) if is_facts_key(tag) else None


def _base_of(
    cache: FactsCache, inputs: RunInputs, clean_key: str, files: Sequence[SourceFile]
) -> tuple[shifts.Base, shifts.Renumbering] | None:
    """The last run of this run's shape that kept a replay (``shifts.Base``), and how this
    run's files map to its; None where there is none, or the files differ too much."""
    shape = inputs.shape_key
    if shape is None:
        return None
    base = shifts.loaded_base(
        cache.load_base(same_facts.key(shape, clean_key)), cache.load_file_list
    )
    if base is None:
        return None
    displays = [source.display for source in files]
    renumbering = shifts.renumbering(base.displays, base.reported, displays)
    return None if renumbering is None else (base, renumbering)


def _base_place(
    cache: FactsCache, inputs: RunInputs, clean_key: str, files: Sequence[SourceFile]
) -> _GraphPlace | None:
    """Where the graph of the last run of this run's shape is (``_GraphPatch.elsewhere``)."""
    found = _base_of(cache, inputs, clean_key, files)
    return None if found is None else _GraphPlace(found[0].replay_at, found[1])


def _keep_base(
    cache: FactsCache,
    inputs: RunInputs,
    clean_key: str | None,
    kept_at: str,
    *,
    files: Sequence[SourceFile],
    reported: int,
    depends: str,
) -> None:
    """Keep the run that kept its replay at ``kept_at`` as the last of its shape: its
    files, where no run over them kept them yet (or what was kept does not read back),
    and the pointer to them, with what its packages depend on (``depends``)."""
    if inputs.shape_key is None or clean_key is None:
        return
    at = same_facts.key(inputs.shape_key, clean_key)
    listed = cache.holds_file_list(kept_at)
    if listed and cache.load_base(at) == shifts.pointer(kept_at, reported, len(files), depends):
        return  # most runs: the last run's, as it is (its display paths not made)
    displays = tuple(source.display for source in files)
    base = shifts.Base(kept_at, displays, reported, depends)
    if not listed or shifts.loaded_base(base.pointer(), cache.load_file_list) != base:
        cache.store_file_list(kept_at, base.listed())
    cache.store_base(at, base.pointer())


@dataclass(frozen=True)
class _GraphPlace:
    """Where the graph a patch starts from is kept (``key``), and how this run's files
    map to that run's (None: they are its files)."""

    key: str
    renumbering: shifts.Renumbering | None = None

    def resolved(self, cache: FactsCache, files: Sequence[SourceFile]) -> _GraphPlace | None:
        """Where a build kept the graph: ``key``, or where the run kept under it says
        (``shifts.GraphMove``), the renumberings joined (``files``: this run's); None
        where neither is."""
        if cache.holds_graph(self.key):
            return self
        move = shifts.loaded_move(cache.load_graph_move(self.key))
        if move is None:
            return None
        renumbering = move.renumbering
        if self.renumbering is not None:
            displays = [source.display for source in files]
            renumbering = self.renumbering.after(renumbering, displays)
        return _GraphPlace(move.graph_at, renumbering)

    def graph(self, cache: FactsCache, files: int, reported: int) -> KeptGraph | None:
        """The kept graph over ``files`` checked files, ``reported`` of them reported
        (renumbered to them); None where it is not kept or does not read back."""
        if self.renumbering is None:
            return same_facts.loaded_graph(cache.load_graph(self.key), files, reported)
        renumbering = self.renumbering
        if len(renumbering.previous) != files:
            return None
        built = same_facts.loaded_graph(
            cache.load_graph(self.key), renumbering.before, renumbering.reported_before
        )
        return None if built is None else built.renumbered(renumbering, reported)


class _Replayed(NamedTuple):
    """A run that took a replay: the files edited since (and those whose graph findings a
    patched graph changed), and the replay with their places where they are now (with
    the patched graph's findings)."""

    edited: list[int]
    replay: Replay


def _take_facts(
    gathered: Gatherer,
    checks: _FileChecks,
    replay: Replay | None,
    inputs: RunInputs | None,
    *,
    rules: Mapping[str, Rule],
    patch: Callable[[Replay, Sequence[_Arrived]], _Replayed | None] | None = None,
    stands: bool = True,
) -> _Replayed | None:
    """Hand every file's facts to ``checks``, as they arrive; or, where the run can take
    ``replay`` (``same_facts``), only those of the files edited since: then those files,
    and the replay with their places where they are now; or, where ``patch`` patches the
    replay's graph (``workspace.patch``), what it gives. The edited files come first
    either way: whether the replay stands is their facts' question (and ``stands``:
    False where only a patch may take it, ``_Shift``)."""
    edited = None if replay is None or inputs is None else replay.edited(inputs.tags)
    if replay is None or edited is None or inputs is None or gathered.cache is None:
        for index, facts, data, verdict in gathered.facts():
            checks.take(index, facts, data, verdict)
        return None
    arrived = list(gathered.facts(edited))
    for index, facts, data, verdict in arrived:
        checks.take(index, facts, data, verdict)
    cache = gathered.cache
    moved = (
        _replay_moved(replay, arrived, inputs, files=gathered.files, cache=cache, rules=rules)
        if stands
        else None
    )
    if moved is not None:
        # Every file's facts are what the result stands on, loaded or not: kept by the
        # pack's rewrite (``FactsCache.stand_on``).
        cache.stand_on(tag for tag in inputs.tags if is_facts_key(tag))
        return _Replayed(edited, moved)
    patched = None if patch is None else patch(replay, arrived)
    if patched is not None:
        cache.stand_on(tag for tag in inputs.tags if is_facts_key(tag))
        return patched
    others = set(edited)
    rest = (index for index in range(len(gathered.files)) if index not in others)
    for index, facts, data, verdict in gathered.facts(rest):
        checks.take(index, facts, data, verdict)
    return None


_Arrived = tuple[int, FileFacts, "bytes | None", "Verdict | None"]


# Files edited since the last build past which a patch keeps what it patched as the
# graph the next runs patch, as a build does: each run patches every edit since that
# build again (at 8 copies of the benchmark's workspace, a parameter declared in one
# more C++ file before each run: 2.07 s after the first, 4.02 s after the thirtieth),
# and keeping the patched graph and its parts costs a run what a build's keeping does
# (0.4 to 0.5 s there). Kept past 8 such files, the runs of that sequence took 2.2 to
# 3.4 s.
REBASE_EDITS = 8


class _Rebased(NamedTuple):
    """What a patch keeps as a build keeps it: the whole graph, the launch and code
    parameter parts a build of the files as they are would leave, and the packages."""

    graph: Graph
    launch: LaunchParts
    code: CodeParameterParts
    packages: list[Package]


@dataclass
class _GraphPatch:
    """A run whose edits change only what some nodes' code declares (``workspace.patch``)
    or what some launch trees start or hand their nodes (``workspace.launch_patch``: launch
    and parameter files), or what some packages depend on (their manifests): the graph
    the last build kept, patched with every edit since (the facts it was built from are
    loaded, so kept in the pack), and the graph rules run over it; the files whose graph
    findings that changed, and those of a package depending on others, are taken and
    reported again with the edited ones, every other file's findings are the replay's.
    A build keeps its graph; a patch keeps what it patched, as a build keeps it, only
    where it applied many edits since (``REBASE_EDITS``): pickling a graph and its parts
    (0.4 to 0.5 s at 81,000 files) would cost each patched run more than patching it
    again, and every edit since the last build is patched again by each run."""

    gathered: Gatherer
    checks: _FileChecks
    inputs: RunInputs
    cache: FactsCache
    place: _GraphPlace  # where the last build's graph is kept, by the replay's
    rules: Sequence[Rule]
    settings: Settings
    # Launch files under their includers' arguments, for the trees walked again
    specialiser: Callable[[], Specialiser]
    # Where the graph of the last run of this run's shape is, where ``place`` no longer
    # leads to one (a run over these files long ago, whose graph was since forgotten)
    elsewhere: Callable[[], _GraphPlace | None] = lambda: None
    # What the run's packages depend on (``PackageGenerations.depends_digest``), and the
    # packages (``workspace_packages``): a graph built where some depended on others is
    # patched with them as they are (``_depending_anew``).
    depends: Callable[[], str] = lambda: ""
    packages: Callable[[], list[Package]] = list
    # Whether the run keeps what a build keeps (a run over the workspace, not one with
    # the rest of it as context): where the patch applied many edits, what it patched
    # is kept as the next runs' graph (``rebased``).
    may_rebase: bool = False
    elsewhere_used: bool = False
    graph_from: _GraphPlace | None = None  # where the graph it patched is, resolved
    rebased: _Rebased | None = None

    def __call__(self, replay: Replay, arrived: Sequence[_Arrived]) -> _Replayed | None:
        """The replay patched from the graph kept where it was made; where that holds
        none, or one the edits since cannot patch, from the graph of the last run of
        this run's shape (``elsewhere``): a replay found by the run's files may be of a
        run long ago (a file removed and brought back), whose graph is older than the
        last build's."""
        files = self.gathered.files
        place = self.place.resolved(self.cache, files)
        stored = None if place is None else place.graph(self.cache, len(files), replay.reported)
        found = (
            None if place is None or stored is None else self._from(replay, arrived, place, stored)
        )
        if found is not None:
            return found
        other = self.elsewhere()
        last = None if other is None else other.resolved(self.cache, files)
        if last is None or (place is not None and last.key == place.key):
            return None
        stored = last.graph(self.cache, len(files), replay.reported)
        self.elsewhere_used = True
        return None if stored is None else self._from(replay, arrived, last, stored)

    def _from(
        self, replay: Replay, arrived: Sequence[_Arrived], place: _GraphPlace, stored: KeptGraph
    ) -> _Replayed | None:
        """The replay patched from the graph ``stored`` at ``place``; None where the
        edits since cannot be."""
        files = self.gathered.files
        self.graph_from = place
        codes = {rule.code for rule in self.rules}
        if not same_facts.codes_of(replay.graph, stored.found) <= codes:
            return None
        built_from, graph = stored.tags, stored.graph
        packages: Sequence[Package] = stored.packages
        depending: frozenset[str] = frozenset()  # packages depending on others since
        if stored.depends != self.depends():
            anew = _depending_anew(stored.packages, self.packages())
            if anew is None:
                return None
            packages, depending = anew
        arrived_facts = {index: facts for index, facts, _, _ in arrived}
        loaded: dict[int, FileFacts | None] = {}
        raw: dict[int, FileFacts] = {}  # those of ``loaded`` whose names were resolved, as stored
        # Files the build did not have, or had and the run has not, say nothing and are
        # found by no name, the edited files' names too (``shifts``): then the build's
        # graph is theirs.
        found_by = replay.run_wide.lookups()
        for edited in arrived_facts.values():
            found_by.add(edited)

        def launch_files() -> list[str]:
            return [source.display for source in files if source.language in LAUNCH_LANGUAGES]

        # Launch files added or removed that nothing includes: trees that come or go.
        # Parameter files added or removed: the trees that read a launch file naming a
        # file of that name are walked again (and the trees handed a removed one), as
        # ``find_in_package`` may find another file by that name now.
        new_files: set[str] = set()
        removed_trees: list[str] = []
        naming: set[str] = set()  # launch files that name a parameter file added or removed
        # Code files the build had that the run has not, as they were: their packages'
        # programs are made again (``program_patch``).
        removed_code: dict[str, FileFacts] = {}
        for display, tag in stored.gone:
            gone = _facts_by_tag(self.cache, tag, display)
            if gone is not None and _new_code(gone, found_by, frozenset()):
                removed_code[display] = gone
                continue
            came = None if gone is None else _came_or_went(gone, found_by, launch_files)
            if came is None:
                return None
            naming |= came[1]
            if came[0] != _SAYS_NOTHING:
                removed_trees.append(display)

        slots = {source.display: index for index, source in enumerate(files)}
        # Which package holds each file (the build's packages), for a patch that asks.
        package_files = lru_cache(maxsize=1)(
            lambda: PackageFiles([source.display for source in files], packages)
        )

        def stored_facts(index: int) -> FileFacts | None:
            """A file's facts as extracted (the edited files' of this run)."""
            if index in arrived_facts:
                return arrived_facts[index]
            # By index: ``RunInputs.tags`` copies every file's key (0.08 s a patch).
            tag = self.inputs.facts_key(index)
            return None if tag is None else self.cache.load(tag, files[index].display)

        # The files taking another file's constant are resolved as the run resolves them
        # (``resolved``): as the build resolved them, where an edit changed what a file
        # includes (``resolved_alike``, below).
        def facts_at(index: int) -> FileFacts | None:
            if index in loaded:  # (an edited file's, resolved: below)
                return loaded[index]
            if index in arrived_facts:
                return arrived_facts[index]
            known = stored_facts(index)
            if known is not None and uses_constants(known):
                raw[index] = known
                known = resolved(known, index)
            loaded[index] = known
            return known

        @cache
        def code_below(directory: str) -> tuple[tuple[str, FileFacts], ...] | None:
            """Every C++ file below a package's directory (display path) with its facts,
            as ``symbols.PackageConstants`` reads them; None where one has no facts. Each
            directory's once: the tables then and now, and the checks, read the same."""
            code: list[tuple[str, FileFacts]] = []
            for path in package_files().below(directory):
                if files[slots[path]].language is not Language.CPP:
                    continue
                found = stored_facts(slots[path])
                if found is None:
                    return None
                code.append((path, found))
            return tuple(code)

        @cache
        def constants_of(directory: str) -> PackageConstants | None:
            """The constants of the C++ files below a package's directory now."""
            code = code_below(directory)
            if code is None:
                return None
            table = PackageConstants()
            for _, found in code:
                table.add(found)
            return table

        def resolved(known: FileFacts, index: int) -> FileFacts | None:
            """``known`` with its symbols resolved by its package's headers (``symbols``),
            from every C++ file below the package's directory; None where one of them
            has no facts."""
            package = self.checks.package_of(index)
            if package is None:
                return known  # the run resolves nothing there either
            table = constants_of(package)
            return None if table is None else table.resolve(known, package)

        @cache
        def constants_then(directory: str) -> PackageConstants | None:
            """The constants of the C++ files below a package's directory at the build:
            those edited since as they were (``then_of``, once every edit is known),
            those removed since too."""
            code = code_below(directory)
            if code is None:
                return None
            table = PackageConstants()
            for path, found in code:
                table.add(then_of.get(path, found))
            for path, found in removed_code.items():
                if path.startswith(f"{directory}/" if directory else ""):
                    table.add(found)
            return table

        def resolved_alike(including: Iterable[str]) -> bool:
            """Whether every file taking another file's constant, of a package holding a
            file whose includes changed (``including``), resolves its names as the build
            did, from the C++ files then (``constants_then``): an include added or taken
            out seldom changes which header defines a constant, and where it does, its
            names may change (the graph is built)."""
            for display in including:
                for package in package_files().enclosing(display):
                    at = package.directory
                    code, now, then = code_below(at), constants_of(at), constants_then(at)
                    if code is None or now is None or then is None:
                        return False
                    for path, found in code:
                        if not uses_constants(found):
                            continue
                        if package_files().package_of(path) != package:
                            continue  # resolved in its own package's, below this one
                        if now.resolve(found, at) != then.resolve(found, at):
                            return False
            return True

        changed: list[tuple[str, FileFacts, FileFacts]] = []
        taking: list[tuple[int, str, FileFacts]] = []  # code taking a constant: its facts then
        tree_edits: list[str] = []
        # Build files that build other programs now (as they were at the build), and code
        # files added: their packages' programs are made again (``program_patch``).
        building: dict[str, FileFacts] = {}
        added_code: list[str] = []
        pairs = zip(self.inputs.tags, built_from, strict=True)
        for index, (now, then) in enumerate(pairs):
            if now == then:
                continue
            display = files[index].display
            if display in replay.specialised:
                return None  # the graph read its bytes under an includer's arguments
            if then == ADDED:
                added = facts_at(index) if is_facts_key(now) else None
                if added is not None and _new_code(added, found_by, replay.run_wide.service_types):
                    added_code.append(display)  # its package's programs made again
                    new_files.add(display)
                    continue
                came = None if added is None else _came_or_went(added, found_by, launch_files)
                if came is None:
                    return None
                naming |= came[1]
                if came[0] == _A_TREE:
                    tree_edits.append(display)
                if came[0] != _SAYS_NOTHING:
                    new_files.add(display)
                continue
            before = _facts_by_tag(self.cache, then, display)
            facts = facts_at(index) if is_facts_key(now) else None
            if before is None or facts is None:
                return None
            # A launch or parameter file whose facts are where they were (a comment at the
            # end) changes no tree; else the trees that read it are walked again.
            if program_edit(before, facts):
                building[display] = before  # its package's programs made again
                continue
            if uses_constants(before) or uses_constants(raw.get(index, facts)):
                taking.append((index, display, before))  # resolved once every edit is known
                continue
            moved_only = same_places(before, facts)
            if (launch_edit(before, facts) or parameter_edit(before, facts)) and not moved_only:
                if not _patchable(before, facts, wiring_kept=True):
                    return None
                tree_edits.append(display)
            elif _patchable(before, facts, wiring_kept=moved_only):
                changed.append((display, before, facts))
            else:
                return None
        then_of: dict[str, FileFacts] = {display: then for display, then, _ in changed}
        then_of.update((display, before) for _, display, before in taking)
        for display in added_code:
            added = facts_at(slots[display])
            if added is not None:
                then_of[display] = _empty(added)
        # A code file taking another file's constant, edited: its facts then and now with
        # their names resolved from its package's headers then and now, as the build and
        # the run resolve them, compared as any edit's; its own check, at the run's end,
        # resolves them from those headers (``_FileChecks.know_constants``).
        for index, display, before in taking:
            directory = self.checks.package_of(index)
            now_raw = raw.get(index, arrived_facts.get(index))
            if now_raw is None or files[index].language is not Language.CPP:
                return None
            if directory is None:
                before_then, now_resolved = before, now_raw  # the run resolves none either
            else:
                table_then, table_now = constants_then(directory), constants_of(directory)
                headers = code_below(directory)
                if table_then is None or table_now is None or headers is None:
                    return None
                before_then = table_then.resolve(before, directory)
                now_resolved = table_now.resolve(now_raw, directory)
                if index in arrived_facts:
                    self.checks.know_constants(found for _, found in headers)
            loaded[index] = now_resolved
            if not _patchable(before_then, now_resolved, resolved=True):
                return None
            changed.append((display, before_then, now_resolved))
        including = [
            display for display, then, now in changed if then.cpp_includes != now.cpp_includes
        ]
        for display in added_code:  # a header added may define what a file takes
            if files[slots[display]].language is Language.CPP:
                including.append(display)
        for display, gone in removed_code.items():  # and one removed may have
            if gone.language is Language.CPP:
                including.append(display)
        if including and not resolved_alike(including):
            return None
        naming -= {*tree_edits, *removed_trees}
        walk = [*tree_edits, *sorted(naming)]  # the launch files whose trees are walked again
        declaring: set[str] = set()  # code files whose parameters changed
        renamed: set[str] = set()  # and those whose node name did (``patch.name_edit``)
        edits = edits_of(changed, declaring, renamed)
        if edits is None:
            return None

        def facts_of(display: str) -> FileFacts | None:
            at = slots.get(display)
            return None if at is None else facts_at(at)

        # The build's whole graph (its parameters kept apart, ``same_facts.KeptLaunch``)
        # for a patch that walks trees or gathers parameters again, or that keeps what it
        # patched as the graph later runs patch (``REBASE_EDITS``).
        kept: KeptLaunch | None = None
        known: set[str] = set()  # the files the build had facts of (a skipped one has none)
        # Some nodes' parameters gathered again
        gathering = bool(declaring or depending or building or added_code or removed_code)
        since = len(changed) + len(tree_edits) + len(removed_trees) + len(new_files)
        since += len(building) + len(removed_code)
        rebasing = self.may_rebase and since + len(depending) >= REBASE_EDITS
        if walk or removed_trees or gathering or rebasing:
            kept = same_facts.loaded_launch(
                self.cache.load_launch_parts(place.key), stored.built_from
            )
            whole = None if kept is None else with_parameters(graph, kept.parameters)
            if kept is None or whole is None:
                return None
            graph = whole
            if depending:  # which nodes can meet (``Graph.can_meet``)
                graph = replace(graph, companions=companions(named_once(packages)))
            known = {
                files[index].display for index, tag in enumerate(stored.tags) if is_facts_key(tag)
            }
            known |= new_files
        launch_parts = None if kept is None else kept.parts  # as a build would leave them
        programs: ProgramsAnew | None = None
        if building or added_code or removed_code:
            assert kept is not None
            # What the build files compiled at the last run, where one builds other
            # programs now (no file added or removed changes it), and now.
            compiled = _compiled(replay.run_wide, arrived, self.checks.package_of, bool(building))
            at_now = WorkspaceIndex.restored(
                LazyFacts(known, facts_of), packages, kept.parts.executables
            )
            owners = [
                package_files().package_of(path) for path in (*building, *added_code, *removed_code)
            ]
            if None in owners:
                return None
            programs = programs_anew(
                kept.parts.programs,
                kept.parts.executables,
                kept.parts.unbuilt,
                index=at_now,
                packages=sorted(
                    {owner for owner in owners if owner is not None}, key=_by_directory
                ),
                language_of=lambda path: files[slots[path]].language,
                then=building,
                added=added_code,
                removed=removed_code.keys(),
                compiled=compiled[1],
                compiled_then=compiled[0],
                is_test=_TestFiles(at_now, {}),
                named_elsewhere=lambda path, own: (
                    not found_by.builders(path) <= {shifts.digest(builder) for builder in own}
                ),
            )
            if programs is None:
                return None
        specialised = replay.specialised
        if walk or removed_trees or renamed or programs is not None:
            assert kept is not None
            if not naming <= known:
                return None  # a launch file naming one that has no facts now
            walked = self._walked(
                graph,
                parts=kept.parts,
                packages=packages,
                edited=walk,
                removed=removed_trees,
                code=renamed,
                known=known,
                facts_of=facts_of,
                programs=programs,
            )
            if walked is None:
                return None
            # A file an edited include hands arguments to now is read under them: an
            # edit of it is never replayed nor patched (the check above). One no longer
            # read so stays in the set: its edits build, as they would have.
            graph, launch_parts = walked[0]
            specialised = specialised | walked[1]
        patched: Graph | None = patch_graph(
            graph,
            edits,
            facts_of,
            package_files,
            declaring=bool(declaring),
        )
        code_parts: CodeParameterParts | None = None
        if patched is not None and (gathering or rebasing):
            assert launch_parts is not None
            kept_code = same_facts.loaded_code(
                self.cache.load_code_parameters(place.key), stored.built_from
            )
            if kept_code is None:
                return None
            code_parts = kept_code.parts
            if gathering:
                code_edits = {
                    display: (before, now) for display, before, now in changed if display in edits
                }
                for display in added_code:
                    added = facts_at(slots[display])
                    assert added is not None  # (``_new_code``)
                    code_edits[display] = (_empty(added), added)
                for display, gone in removed_code.items():
                    code_edits[display] = (gone, _empty(gone))
                gathered = parameters_patched(
                    patched,
                    launch_parts,
                    code_parts,
                    code_edits,
                    facts=LazyFacts(known, facts_of),
                    packages=packages,
                    depending=depending,
                    programs=programs,
                    added=added_code,
                    removed=removed_code.keys(),
                )
                if gathered is None:
                    return None
                patched, launch_parts, code_parts = gathered
            else:  # the nodes' parameters moved with their code (``patched``)
                moved = moved_code_parameters(launch_parts.parameters, edits)
                launch_parts = None if moved is None else replace(launch_parts, parameters=moved)
        if patched is None:
            return None
        # A rule that reads no name the patch changed has the built graph's findings, the
        # places of the edited files moved (only places can have: its parameter uses');
        # none where launch trees were walked again.
        kept_codes, kept_found = (
            (frozenset(), {})
            if walk or removed_trees or gathering
            else _kept_findings(stored.found, edits, self.rules, files)
        )
        fresh = [rule for rule in self.rules if rule.code not in kept_codes]
        by_rule: dict[int, dict[str, list[Finding]]] = {}
        for path, items in graph_findings(patched, fresh, self.settings).items():
            at = slots.get(path)
            if at is not None and at < replay.reported:
                for rule, item in items:
                    by_rule.setdefault(at, {}).setdefault(rule.code, []).append(item.finding)
        for index, built in kept_found.items():
            for code, finding in built:
                by_rule.setdefault(index, {}).setdefault(code, []).append(finding)
        # In the rules' order, as ``graph_findings`` lists them.
        found = {
            index: tuple((rule.code, f) for rule in self.rules for f in codes.get(rule.code, ()))
            for index, codes in by_rule.items()
        }
        again = set(arrived_facts) | {
            index
            for index in found.keys() | replay.graph.keys()
            if found.get(index, ()) != replay.graph.get(index, ())
        }
        # The files of a package depending on others are compared with the service types
        # of those (RN204: ``_FileChecks._typed``): checked again.
        for package in packages:
            if package.name in depending:
                again.update(
                    at
                    for display in package_files().below(package.directory)
                    if (at := slots[display]) < replay.reported
                )
        # A source rostest alone starts now, or starts no more, is judged again
        # (``_FileChecks.spare``).
        if programs is not None:
            again.update(
                at for display in programs.rostest_anew if (at := slots[display]) < replay.reported
            )
        rest = list(self.gathered.facts(sorted(again - arrived_facts.keys())))
        # A file taking another file's constant is checked with its names resolved from
        # its package's headers (``_FileChecks.finish``): the run took few of them.
        resolving = {
            directory
            for index, facts, _, _ in rest
            if uses_constants(facts) and (directory := self.checks.package_of(index)) is not None
        }
        for directory in sorted(resolving):
            headers = code_below(directory)
            if headers is None:
                return None
            self.checks.know_constants(found for _, found in headers)
        for index, facts, data, verdict in rest:
            self.checks.take(index, facts, data, verdict)
        if rebasing and launch_parts is not None and code_parts is not None:
            self.rebased = _Rebased(patched, launch_parts, code_parts, list(packages))
        return _Replayed(sorted(again), replace(replay, graph=found, specialised=specialised))

    def _walked(
        self,
        whole: Graph,
        *,
        parts: LaunchParts,
        packages: Sequence[Package],
        edited: Sequence[str],
        removed: Sequence[str],
        code: Collection[str],
        known: set[str],
        facts_of: Callable[[str], FileFacts | None],
        programs: ProgramsAnew | None,
    ) -> tuple[tuple[Graph, LaunchParts], frozenset[str]] | None:
        """The build's whole graph with the trees that read an ``edited`` launch or
        parameter file walked again (``workspace.launch_patch``), and those of the
        ``removed`` launch files gone, over every file the build had facts of and the
        added launch files (``known``), with the launch parts a build would leave; and
        the files the walk extracted again under an includer's arguments; None where it
        cannot be."""
        specialise = self.specialiser()
        found = launch_patched(
            whole,
            parts,
            edited,
            facts=LazyFacts(known, facts_of),
            packages=packages,
            specialise=specialise,
            prepare=specialise.prepare,
            removed=removed,
            code=code,
            programs=programs,
        )
        return None if found is None else (found, specialise.specialised)


def _depending_anew(
    built: Sequence[Package], now: Sequence[Package]
) -> tuple[list[Package], frozenset[str]] | None:
    """The packages as they are ``now`` in the build's order (``built``), and the names
    of those that depend on others than at the build; None where they differ in anything
    else (the graph is built)."""
    by_directory = {package.directory: package for package in now}
    if len(by_directory) != len(now) or by_directory.keys() != {p.directory for p in built}:
        return None
    found: list[Package] = []
    depending: set[str] = set()
    for package in built:
        anew = by_directory[package.directory]
        if replace(anew, depends=package.depends) != package:
            return None
        if anew.depends != package.depends:
            depending.add(package.name)
        found.append(anew)
    return found, frozenset(depending)


_SAYS_NOTHING, _A_TREE, _SETTINGS = "says nothing", "a tree", "settings"


def _came_or_went(
    facts: FileFacts, found_by: shifts.Lookups, launch_files: Callable[[], list[str]]
) -> tuple[str, set[str]] | None:
    """What a file added or removed since the build (``shifts``) asks of its graph, and
    the launch files whose trees are walked again for it: nothing, where it says nothing
    and is found by no name; a tree of its own (``_a_tree_alone``); a parameter file's
    settings, the trees of the launch files naming a file of its name walked again (of
    ``launch_files``, the run's); None where the graph must be built."""
    if found_by.adds_nothing(facts):
        return _SAYS_NOTHING, set()
    if facts.language is Language.PARAMETERS:
        naming = found_by.naming_of(facts.path.rpartition("/")[2], launch_files())
        return None if naming is None else (_SETTINGS, naming)
    return (_A_TREE, set()) if _a_tree_alone(facts, found_by) else None


def _new_code(
    facts: FileFacts,
    found_by: shifts.Lookups,
    service_types: Collection[tuple[Generation | None, str]],
) -> bool:
    """Whether a file added or removed since the build (``shifts``) is code whose
    package's programs may be made again for it (``program_patch``): code that says
    something or is found by a name, holds none of the facts launch, build and parameter
    files hold, takes no other file's constant, wires no name, names no source it
    includes, and serves or calls services only of ``service_types`` (the run's, for a
    file added; none, for one removed: another file's checks compare with those)."""
    if facts.language not in CODE_LANGUAGES or found_by.adds_nothing(facts):
        return False
    types = {(facts.generation, spelling) for spelling in typed_services(facts)}
    return (
        not any(getattr(facts, field) for field in NOT_CODE_FIELDS)
        and not facts.included_sources
        and not facts.rejected_fixtures
        and not wired_by(facts)
        and not uses_constants(facts)
        and types <= set(service_types)
    )


def _empty(facts: FileFacts) -> FileFacts:
    """The facts of an empty file where ``facts``' is: what a file added had before."""
    return FileFacts(facts.path, facts.language, facts.generation)


def built_as_taken(
    run_wide: RunWide, taken: Iterable[tuple[FileFacts, str | None]], paths: Collection[str]
) -> BuiltSources:
    """What the build files compile: as the replay's run had them (``run_wide``), but
    for the files this run took (``paths``), as they are now (``taken``: those of them
    that compile or include sources, with their packages' directories)."""
    built = BuiltSources()
    for facts, package in run_wide.built:
        if facts.path not in paths:
            built.add(facts, package)
    for facts, package in taken:
        built.add(facts, package)
    return built


def _compiled(
    run_wide: RunWide,
    arrived: Sequence[_Arrived],
    package_of: Callable[[int], str | None],
    then_too: bool,
) -> tuple[BuiltSources | None, BuiltSources]:
    """What the build files compiled at the last run (its ``RunWide``; ``then_too``:
    else None), and now: with the files edited since (``arrived``) as they are."""
    then = None
    if then_too:
        then = BuiltSources()
        for facts, package in run_wide.built:
            then.add(facts, package)
    taken = [
        (facts, package_of(index))
        for index, facts, _, _ in arrived
        if facts.compiled is not None or facts.included_sources
    ]
    return then, built_as_taken(run_wide, taken, {facts.path for _, facts, _, _ in arrived})


def _by_directory(package: Package) -> str:
    return package.directory


def _a_tree_alone(facts: FileFacts, found_by: shifts.Lookups) -> bool:
    """Whether a launch file added or removed (``shifts``) changes the graph only by a
    tree of its own: nothing includes it (no launch file finds a file of its name), and
    its facts hold nothing else the graph or the run's end reads (``launch_edit`` and
    ``_patchable`` from or to the facts of an empty file)."""
    empty = _empty(facts)
    return (
        not found_by.finds(facts.path)
        and launch_edit(empty, facts)
        and _patchable(empty, facts, wiring_kept=True)
    )


def _kept_findings(
    found: same_facts.GraphFound,
    edits: Mapping[str, Moved],
    rules: Sequence[Rule],
    files: Sequence[SourceFile],
) -> tuple[frozenset[str], dict[int, list[tuple[str, Finding]]]]:
    """The rules whose findings a patch keeps (``Rule.reads_code_names``) and those
    findings, from the built graph's (``found``), with the edited files' places where they
    are now; none where one of those places is no longer known."""
    kept = frozenset(rule.code for rule in rules if not rule.reads_code_names)
    moving = [move for display, spans in edits.items() if not (move := Moves(display, spans)).still]
    try:
        return kept, {
            index: [
                (code, moved_finding(finding, files[index].display, moving))
                for code, finding in items
                if code in kept
            ]
            for index, items in found.items()
        }
    except UnplacedError:
        return frozenset(), {}


def _patchable(
    before: FileFacts, now: FileFacts, *, wiring_kept: bool = False, resolved: bool = False
) -> bool:
    """Whether what the run gathers from every file's facts (``RunWide``) and the checks
    of other files read is the same before and after an edit, and the file's facts are
    its own (no constant of another file in them; ``resolved``: the constants' values in
    them, as the build and the run resolve them). ``wiring_kept``: a launch file may
    wire names (RN202's), the same before and after; code may wire none."""
    wiring = (
        wired_by(before) == wired_by(now)
        if wiring_kept
        else not (wired_by(before) or wired_by(now))
    )
    return (
        typed_services(before) == typed_services(now)
        and wiring
        and (resolved or not (uses_constants(before) or uses_constants(now)))
    )


def _with_edited(
    kept: Sequence[int], edited_now: Sequence[int], edited: Sequence[int]
) -> list[int]:
    """A replay's files judged so (unbuilt, named by rostest; their indices), with the
    edited files' judgements of this run in place of theirs, in discovery order."""
    return sorted((set(kept) - set(edited)) | set(edited_now))


def _replay_moved(
    replay: Replay,
    arrived: Sequence[tuple[int, FileFacts, bytes | None, Verdict | None]],
    inputs: RunInputs,
    *,
    files: Sequence[SourceFile],
    cache: FactsCache,
    rules: Mapping[str, Rule],
) -> Replay | None:
    """``replay`` with the edited files' places where they are now, where the run may
    take it: each edited file (``arrived``) has a facts key and leaves it true
    (``Replay.moves``), and the rules of its graph findings are the run's (``rules``, by
    code); else None."""
    if not same_facts.codes_of(replay.graph) <= rules.keys():
        return None
    moves: list[Moves] = []
    found_by: shifts.Lookups | None = None  # made for a file the replay's run did not have
    for index, facts, _, _ in arrived:
        old = replay.tags[index]
        if inputs.facts_key(index) is None:
            return None
        if old == ADDED:  # (``shifts``)
            found_by = found_by or replay.run_wide.lookups()
            if not found_by.adds_nothing(facts):
                return None
            continue
        if not is_facts_key(old):
            return None
        display = files[index].display
        move = replay.moves(display, cache.load(old, display), facts)
        if move is None:
            return None
        moves.append(move)
    return replay.moved(moves, [source.display for source in files[: replay.reported]])


def _report_replayed(
    replayed: _Replayed,
    *,
    files: Sequence[SourceFile],
    checks: _FileChecks,
    rules: Mapping[str, Rule],
    settings: Settings,
    registry: Registry,
) -> None:
    """The graph rules' findings of the replay in each edited reported file, made into
    diagnostics under its new text and suppressions (``report_graph``'s part per file)."""
    for index in replayed.edited:
        stored = replayed.replay.graph.get(index, ())
        facts = checks.facts_of(index)
        if not stored or facts is None:
            continue
        source = files[index]
        items = [
            (rules[code], WorkspaceFinding(source.display, finding)) for code, finding in stored
        ]
        checks.per_file[index] = file_graph_findings(
            items,
            source,
            facts,
            checks.per_file[index],
            suppressions=checks.suppressions_of.get(index, []),
            settings=settings,
            registry=registry,
        )


def waits_for_the_run(facts: FileFacts, wiring: bool) -> bool:
    """Whether a file's per-file verdict needs what only the whole run knows: the service
    types it compares with (RN204), another file's constants, or (``wiring``: a rule
    reads it) the names the launch files wire (RN202)."""
    return bool(typed_services(facts)) or uses_constants(facts) or (wiring and awaits_wiring(facts))


@dataclass(frozen=True)
class FileChecks:
    """The per-file rules of a run as a worker process runs them on a file it has just
    extracted (``gather.extract_batch``): a file whose verdict needs nothing but itself and
    the run's settings is judged there, so the main process only gathers verdicts; None
    for the others (``waits_for_the_run``), which the main process judges at the end.
    Everything here is plain data and module-level functions: it travels to the workers."""

    settings: Settings
    registry: Registry
    enabled: frozenset[str]
    test_rules: frozenset[str]
    contexts: _Contexts
    wiring: bool

    def __call__(self, facts: FileFacts, data: bytes) -> Verdict | None:
        if waits_for_the_run(facts, self.wiring):
            return None
        return self.check_text(facts, decode_for_display(data), self.contexts)

    def check_text(self, facts: FileFacts, text: str, contexts: _Contexts) -> Verdict:
        """One file's verdict under ``contexts`` (the run's, or those of a file that waited
        for the service types or the wiring)."""
        return check_file(
            facts,
            text,
            self.settings,
            self.registry,
            self.enabled,
            test_rules=self.test_rules,
            contexts=contexts,
        )


def launch_wiring(
    facts: FileFacts, data: Callable[[], bytes | str], settings: Settings
) -> frozenset[str]:
    """The absolute names a launch file wires (``wiring``), unless it is test code: a
    test's launch file wires the harness it needs (ros_comm's ``transform.test`` remaps to
    ``/num2``), not the system's interfaces. ``data``: the file's content, read only for
    a file that wires some."""
    wired = wired_by(facts)
    if not wired:
        return wired
    relative = relative_to_root(facts.path, settings)
    if os.path.isabs(relative) and not os.path.isabs(facts.path):
        # A per-file run's context lies outside the root (the named files' directory):
        # its directories are those below the working directory, as displayed, not those
        # above the workspace (``~/test_ws/src/...`` is no test).
        relative = facts.path
    return frozenset() if is_test_code(relative, facts.language, data(), settings) else wired


def is_linter_code(code: str) -> bool:
    """RN0xx: the linter's own findings (parse errors, suppressions), about the text."""
    return code.startswith("RN0")


def _not_linter_code(diagnostic: Diagnostic) -> bool:
    return not is_linter_code(diagnostic.code)


# The API the C++ extractor names on the node name handed to roscpp (extract/cpp/sites.py;
# not imported: the engine does not import the C++ parser).
_ROS_INIT_API = "ros::init"


def rostest_replaces(diagnostic: Diagnostic) -> bool:
    """Whether the finding judges the node name a ROS 1 program hands ``ros::init``,
    which a program rostest starts never takes: roslaunch passes every node it starts
    ``__name:=<name>``, a ``<test>``'s ``name`` or else its ``test-name``
    (``create_local_process_args``, ``XmlLoader._node_tag``), and roscpp's
    ``ThisNode::init`` takes that remapping in place of the name before it checks it."""
    decision = diagnostic.decision
    return (
        decision is not None
        and not is_linter_code(diagnostic.code)
        and decision.kind is Kind.NODE
        and decision.api == _ROS_INIT_API
        and decision.generation is Generation.ROS1
    )


def _focused(run_key: str, focus: frozenset[str] | None) -> str:
    """Where the result of a run whose key is ``run_key`` is kept: for a run reported in
    the files of ``focus`` only (``_lint``), a key of its own."""
    if focus is None:
        return run_key
    digest = hashlib.blake2b(f"{run_key}\0focus\0".encode(), digest_size=20)
    digest.update("\0".join(sorted(focus)).encode("utf-8", errors="surrogatepass"))
    return digest.hexdigest()


def _stored_result(value: object, files: int) -> LintResult | None:
    """A result ``store_run`` kept, if ``value`` is one (anything else: a miss)."""
    match value:
        case (
            tuple() as diagnostics,
            int() as checked,
            tuple() as skipped,
            tuple() as unbuilt,
            tuple() as rostest_named,
        ) if (
            all(isinstance(diagnostic, Diagnostic) for diagnostic in diagnostics)
            and all(
                isinstance(item, tuple) and all(isinstance(part, str) for part in item)
                for item in skipped
            )
            and all(isinstance(path, str) for path in (*unbuilt, *rostest_named))
        ):
            return LintResult(
                diagnostics,
                checked,
                0,
                files,
                0,
                None,
                skipped,
                reused=True,
                unbuilt=unbuilt,
                rostest_named=rostest_named,
            )
    return None


def workspace_packages(
    sources: Sequence[SourceFile], packages: PackageGenerations
) -> list[Package]:
    """Every package holding a file of the run, by name and display directory."""
    found: dict[str, Package] = {}
    services = service_definitions(sources, packages)  # its ROS 1 .srv files (RN403)
    for source in sources:
        # Strings, not paths: this runs for every file of the workspace (a ``Path`` for
        # each of 77,000 files cost 0.4 s).
        root = packages.package_root(source.location)
        if root is None or root in found:
            continue  # the display directory is worked out once per package, not per file
        name = packages.package_name(source.location)
        if name is None:
            continue
        found[root] = Package(
            name,
            _display_directory(source, root),
            packages.package_depends(source.location),
            services.get(root, ()),
            packages.for_file(source.location),
        )
    return list(found.values())


def package_display(source: SourceFile, packages: PackageGenerations) -> str | None:
    """The display directory of the package holding ``source`` ("" for the run's root)."""
    root = packages.package_root(source.location)
    return None if root is None else _display_directory(source, root)


def _display_directory(source: SourceFile, root: str) -> str:
    """The display directory of ``root``, a directory above ``source``: its display path
    less the part below ``root``, as displays show it (a byte that is not UTF-8 is four
    characters there)."""
    relative = display_path_text(source.location[len(root) :].lstrip(os.sep))
    return source.display[: -len(relative)].rstrip("/")


# The graph rules' findings in the reported files, by the file's index among them.
GraphFindings = dict[int, list[tuple[Rule, WorkspaceFinding]]]


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
) -> GraphFindings:
    """Graph rules' findings, each into its file's slot with that file's suppressions;
    findings in files outside ``reported`` (a per-file run's context) are dropped.
    ``texts``: files' content by display path where it is not the file's on disk (an
    editor's unsaved buffer). The findings, as the rules made them."""
    slots = {source.display: index for index, source in enumerate(reported)}
    found: GraphFindings = {
        slots[path]: items
        for path, items in graph_findings(graph, rules, settings).items()
        if path in slots
    }
    facts_of = {f.path: f for f in facts}
    for index, items in sorted(found.items()):
        source = reported[index]
        per_file[index] = file_graph_findings(
            items,
            source,
            facts_of[source.display],
            per_file[index],
            suppressions=suppressions_of.get(index, []),
            settings=settings,
            registry=registry,
            text=None if texts is None else texts.get(source.display),
        )
    return found


def graph_findings(
    graph: Graph, rules: Sequence[Rule], settings: Settings
) -> dict[str, list[tuple[Rule, WorkspaceFinding]]]:
    """Every graph rule's findings, by the display path of the file each is in."""
    found: dict[str, list[tuple[Rule, WorkspaceFinding]]] = {}
    for rule in rules:
        assert rule.check_workspace is not None
        for item in rule.check_workspace(graph, _context(rule, settings, frozenset())):
            found.setdefault(item.path, []).append((rule, item))
    return found


def file_graph_findings(
    items: Sequence[tuple[Rule, WorkspaceFinding]],
    source: SourceFile,
    file_facts: FileFacts,
    found: list[Diagnostic],
    *,
    suppressions: list[Suppression],
    settings: Settings,
    registry: Registry,
    text: str | None = None,
) -> list[Diagnostic]:
    """One file's diagnostics, ``found`` by the per-file rules, with the graph rules'
    findings in it (``items``) under its suppressions: an RN002 for a suppression one of
    them uses is dropped. ``text``: the file's content, when not the file's on disk."""
    ignored = _per_file_ignored(source.display, settings, registry)
    if text is None:
        data, _, _ = read_file(source.location, settings.max_file_size)
        text = decode_for_display(data or b"")
    to_diagnostic = _DiagnosticFactory(file_facts, settings, text)
    judging = _TestCodeFilter(file_facts, text, settings, test_code_codes(settings, registry))
    fresh = [
        to_diagnostic(
            rule,
            item.finding.span,
            item.finding.message,
            item.finding.related,
            answer=item.finding.answer,
            decision=item.finding.decision,
        )
        for rule, item in items
        if rule.code not in ignored
        and not ((judging.spared(rule.code) or item.finding.deployment_only) and judging.is_test())
    ]
    fresh, used = _apply_suppressions(fresh, suppressions, registry)
    return [d for d in found if not _now_used(d, used)] + fresh


def _now_used(diagnostic: Diagnostic, used: set[tuple[Suppression, str]]) -> bool:
    """An RN002 'silences nothing' on a suppression a graph finding turned out to use."""
    return diagnostic.code == UNUSED_SUPPRESSION and any(
        suppression.span == diagnostic.span
        and diagnostic.message.startswith(f"suppression of {code} ")
        for suppression, code in used
    )


def check_file(
    facts: FileFacts,
    text: str,
    settings: Settings,
    registry: Registry,
    enabled: frozenset[str],
    *,
    known_service_types: frozenset[str] = frozenset(),
    wired_names: frozenset[str] = frozenset(),
    plugin_names: frozenset[str] = frozenset(),
    test_rules: frozenset[str] | None = None,
    contexts: Mapping[str, RuleContext] | None = None,
) -> tuple[list[Diagnostic], list[Suppression]]:
    """Every diagnostic of one file: rule findings, then suppression bookkeeping; and the
    file's suppressions, for the graph rules' findings still to come.

    ``test_rules``: the rules that judge test code (``test_code_codes``), when the caller
    has them already; ``wired_names``: the absolute names the workspace's launch files wire;
    ``contexts``: each rule's context (``rule_contexts``) for these settings, service types
    and wiring, when the caller checks many files with the same."""
    active = enabled - _per_file_ignored(facts.path, settings, registry)
    if contexts is None:
        contexts = rule_contexts(registry, settings, known_service_types, wired_names, plugin_names)
    to_diagnostic = _DiagnosticFactory(facts, settings, text)
    # Whether the file is test code is asked only when the answer can change something.
    if test_rules is None:
        test_rules = test_code_codes(settings, registry)
    judging = _TestCodeFilter(facts, text, settings, test_rules)
    diagnostics = [
        to_diagnostic(
            rule,
            finding.span,
            finding.message,
            finding.related,
            finding.fix,
            answer=finding.answer,
            decision=finding.decision,
        )
        for rule in registry.rules
        if rule.code in active and rule.check is not None
        for finding in rule.check(facts, contexts[rule.code])
        if not (finding.deployment_only and judging.is_test())
    ]
    suppressions = find_suppressions(text, facts.language)
    if diagnostics and is_template(relative_to_root(facts.path, settings)):
        diagnostics = [
            d for d in diagnostics if d.source_line is None or not holds_placeholder(d.source_line)
        ]
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
        self, facts: FileFacts, text: str, settings: Settings, judging: frozenset[str]
    ) -> None:
        self._facts, self._text = facts, text
        self._settings = settings
        self._judging = judging
        self._test: bool | None = None

    def spared(self, code: str) -> bool:
        """Whether a finding of ``code`` is dropped if the file is test code."""
        return code not in self._judging

    def is_test(self) -> bool:
        if self._test is None:
            relative = relative_to_root(self._facts.path, self._settings)
            self._test = is_test_code(
                relative, self._facts.language, self._text, self._settings
            ) or is_example_code(relative, self._settings)
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
    package = packages.for_file(path)
    python2 = ros1_python2(settings)
    facts = extract_file(language, display, data, package, fallback, ros1_python2=python2)
    enabled = enabled_codes(settings, registry)
    found, _ = check_file(facts, decode_for_display(data), settings, registry, enabled)
    return len(facts.parse_errors), {(d.code, d.span.line) for d in found if not d.suppressed}


def rule_contexts(
    registry: Registry,
    settings: Settings,
    known_service_types: frozenset[str] = frozenset(),
    wired_names: frozenset[str] = frozenset(),
    plugin_names: frozenset[str] = frozenset(),
) -> dict[str, RuleContext]:
    """Each per-file rule's context: the same for every file of a run that has the same
    service types to compare with (nearly all: none). The wiring goes to the rules that
    read it only."""
    return {
        rule.code: _context(
            rule,
            settings,
            known_service_types,
            wired_names if rule.reads_wiring else frozenset(),
            plugin_names,
        )
        for rule in registry.rules
        if rule.check is not None
    }


def _context(
    rule: Rule,
    settings: Settings,
    known_service_types: frozenset[str],
    wired_names: frozenset[str] = frozenset(),
    plugin_names: frozenset[str] = frozenset(),
) -> RuleContext:
    options = {**rule.options, **settings.rule_options.get(rule.code, {})}
    return RuleContext(
        max_depth=settings.max_depth,
        options=options,
        policies=settings.policies,
        known_service_types=known_service_types,
        wired_names=wired_names,
        plugin_names=plugin_names,
    )


def service_types_of(
    types: Iterable[tuple[Generation | None, str]], generation: Generation
) -> frozenset[str]:
    """The service types a file of ``generation`` is compared with (RN204): its
    generation's and those of packages that build for both."""
    return frozenset(spelling for owner, spelling in types if owner in (generation, None))


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
        *,
        answer: Answer | None = None,
        decision: Decision | None = None,
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
            answer=answer,
            decision=decision,
        )


def _per_file_ignored(display: str, settings: Settings, registry: Registry) -> frozenset[str]:
    """The codes ``per-file-ignores`` turns off in one file. The file's path below the
    root is worked out only when some are configured: for every file of realws (8,949) it
    took 36 ms, 2% of a re-run from cached facts."""
    if not settings.per_file_ignores:
        return frozenset()
    return ignored_for_path(settings, relative_to_root(display, settings), registry)


def relative_to_root(display: str, settings: Settings) -> str:
    """Where per-file ignores look: the file's path below the root, else its absolute
    path. String operations, not ``Path.relative_to``: with per-file-ignores configured
    this runs for every file."""
    absolute = display if os.path.isabs(display) else os.path.join(os.getcwd(), display)
    root = os.path.join(os.fspath(settings.root), "")
    relative = absolute[len(root) :] if absolute.startswith(root) else absolute
    return relative.replace(os.sep, "/") if os.sep != "/" else relative

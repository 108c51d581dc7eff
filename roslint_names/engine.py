"""The pipeline from discovered files to diagnostics (``lint``).

Facts come from ``gather`` (the cache, extraction in this process or in workers); each
file is checked as its facts arrive (``run_checks``, ``checks``), then the workspace
graph is built, or the last one's findings replayed or its graph patched
(``graph_patch``), and the graph rules run. Diagnostics never depend on how facts came.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache, partial
from typing import TYPE_CHECKING

from .collection import kept_for_the_run
from .config import Settings, enabled_codes, ros1_python2, test_code_codes
from .discover import SourceFile, display_path_text
from .extract import EXTRACTOR_MODULES
from .generation import (
    DEFAULT_GENERATION,
    PackageGenerations,
    service_types,
    workspace_plugin_names,
)
from .model import Diagnostic, FileFacts, Finding
from .reading import read_file
from .registry import Registry
from .run_inputs import RunInputs, is_facts_key
from .wiring import WIRING_SOURCES
from .workspace.index import Package
from .workspace.interfaces import service_definitions

if TYPE_CHECKING:
    from .cache import FactsCache  # imported by the caller that wants a cache
    from .graph_patch import Shift
    from .run_checks import Progress
    from .workspace.graph import Graph
    from .workspace.launch_parts import CodeParameterParts, LaunchParts


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


def _besides(context: list[SourceFile], files: Sequence[SourceFile]) -> list[SourceFile]:
    """The files of ``context`` that are none of ``files``, in order."""
    given = {source.location for source in files}
    return [source for source in context if source.location not in given]


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
        files += _besides(lintable(context), files)
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
    # Past a stored result the run extracts, checks, and builds or patches the graph: the
    # modules that do so are imported here, not with this one, which a re-run of unchanged
    # files (its stored result) then never imports.
    from . import clean_files, same_facts, shifts
    from .checks import FileChecks, report_graph, rule_contexts
    from .decisions import one_per_decision
    from .gather import Gatherer, Specialiser, extract_batch, gave_up
    from .graph_patch import (
        GraphPatch,
        GraphPlace,
        base_place,
        keep_base,
        report_replayed,
        shifted_replay,
        take_facts,
        with_edited,
    )
    from .run_checks import RunChecks
    from .same_facts import KeptGraph, KeptLaunch, Replay
    from .speculation import Speculation
    from .workers import Dispatcher
    from .workspace.build import build_parts
    from .workspace.patch import for_patching, kept_parts

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
    checks = RunChecks(
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
    # Not bound to a name: what the replay is loaded from (8 MB at 81,000 files) would be
    # held to the end of the run, through the stores of a rebased graph (its peak).
    last_replay = same_facts.loaded(
        None if kept_at is None or cache is None else cache.load_replay(kept_at),
        len(files),
        reported,
    )
    # Where the graph a patch starts from is kept: under the replay's key, or the key of
    # the run whose replay this one's files were renumbered from (``shifts``).
    graph_place: GraphPlace | None = None if kept_at is None else GraphPlace(kept_at)
    shifted: Shift | None = None
    if last_replay is None and kept_at is not None and not context:
        assert cache is not None and inputs is not None and clean_key is not None
        shifted = shifted_replay(cache, inputs, clean_key, files, depends())
        if shifted is not None:
            last_replay = shifted.replay
            graph_place = GraphPlace(shifted.replay_at, shifted.renumbering)
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
            patch = GraphPatch(
                gathered,
                checks,
                inputs,
                cache,
                graph_place,
                graph_rules,
                settings,
                specialiser,
                elsewhere=partial(base_place, cache, inputs, clean_key, files),
                depends=depends,
                packages=packages_now,
                may_rebase=not context,
            )
        replayed = take_facts(
            gathered,
            checks,
            last_replay,
            inputs,
            rules=rule_of,
            patch=patch,
            stands=shifted is None or shifted.stands,
        )
        workers = gathered.workers  # that extracted the files
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
            report_replayed(
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
        unbuilt_at = with_edited(replayed.replay.unbuilt, unbuilt_at, replayed.edited)
        named_at = with_edited(replayed.replay.rostest_named, named_at, replayed.edited)
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
            checks.typed_files(),
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
        if inputs is not None:
            # Every checked file's facts are what the result stands on, loaded or not,
            # extracted here or by a worker: kept where a pack is rewritten.
            cache.stand_on(tag for tag in inputs.tags if is_facts_key(tag))
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
                keep_base(
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
                        kept_launch = KeptLaunch(inputs.tags, *kept_parts(graph, launch_parts))
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

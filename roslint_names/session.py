"""A workspace kept in memory between checks: what the language server lints against.

A command-line run reads the workspace, reports and ends; an editor asks again after
every keystroke. The session loads the workspace once (through the facts cache, so a
warm one costs little) and keeps every file's facts. Checking an open document is then
two steps of very different cost:

- ``check``: the document's own text extracted and judged by the per-file rules, with the
  graph findings it had at the last ``check_graph``: milliseconds, what an editor
  shows while the user types;
- ``check_graph``: the workspace graph built again over the facts in memory (the edited
  documents' included) and the graph rules run for the open documents: about a second on
  a workspace of ten thousand files, run once typing pauses.

A document above ``max-file-size`` is what ``check`` skips on disk: ``skip_reason`` says
so without copying its text, and ``skip`` leaves it with no facts. A session is not
thread-safe: one thread at a time calls it (the language server's session worker).
"""

from __future__ import annotations

import gc
import os
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

from .cache import FactsCache
from .checks import (
    check_file,
    file_graph_findings,
    graph_findings,
    is_linter_code,
    launch_wiring,
    rostest_replaces,
    service_types_of,
    typed_services,
)
from .config import Settings, enabled_codes, ros1_python2, test_code_codes
from .decisions import one_per_decision
from .discover import SourceFile, classify, discover, display_path
from .engine import RunOptions, lint, lintable, package_display, workspace_packages
from .extract import EXTRACTOR_MODULES
from .gather import (
    Specialiser,
    extract_batch,
    extract_file,
)
from .generation import (
    DEFAULT_GENERATION,
    PackageGenerations,
    service_types,
    visible_service_types,
    workspace_plugin_names,
)
from .model import Diagnostic, FileFacts, Generation
from .moves import Moves, UnplacedError, moved_finding, moved_spans
from .reading import read_file, too_large
from .registry import Registry
from .rule import Rule, WorkspaceFinding
from .suppress import Suppression
from .symbols import PackageConstants, uses_constants
from .workers import Dispatcher
from .workspace.build import build
from .workspace.built import BuiltSources
from .workspace.graph import Graph
from .workspace.index import Package, PackageFiles
from .workspace.memory import GraphMemory
from .workspace.patch import edits_of
from .workspace.patch import patched as patch_graph


@dataclass(frozen=True)
class _Checked:
    """An open document's per-file diagnostics and suppressions, for its graph findings."""

    source: SourceFile
    text: str
    diagnostics: list[Diagnostic]
    suppressions: list[Suppression]


class Session:
    """The facts of one workspace, and the documents the editor has open in it."""

    def __init__(
        self,
        root: Path,
        settings: Settings,
        registry: Registry,
        cache: FactsCache | None,
        *,
        jobs: int = 1,
    ) -> None:
        self.root = root
        self._settings = settings
        self._registry = registry
        self._cache = cache
        self._jobs = jobs
        self._enabled = enabled_codes(settings, registry)
        self._test_rules = test_code_codes(settings, registry)
        self._graph_codes = {
            rule.code
            for rule in registry.rules
            if rule.check_workspace is not None and rule.code in self._enabled
        }
        self._packages = PackageGenerations()
        self._fallback = settings.ros or DEFAULT_GENERATION
        self._ros1_python2 = ros1_python2(settings)
        self._sources: dict[str, SourceFile] = {}
        self._facts: dict[str, FileFacts] = {}
        self._service_types: set[tuple[Generation | None, str]] = set()
        self._plugin_names: frozenset[str] = frozenset()  # ``plugins``
        # The absolute names each launch file wires (RN202), for the files that wire some.
        self._wired_of: dict[str, frozenset[str]] = {}
        self._open: dict[str, _Checked] = {}
        self._graph_found: dict[str, list[Diagnostic]] = {}
        # Per document, its own findings the graph's answer: an RN002 "silences nothing"
        # on a suppression one of its graph findings uses (``report_graph``).
        self._graph_answered: dict[str, list[Diagnostic]] = {}
        # Kept from one graph build to the next: the packages, and the launch files'
        # specialisations under their includers' arguments (made again for a file only
        # when it changes). One job: the session extracts in its own process.
        self._dispatcher: Dispatcher[Any, Any] = Dispatcher(partial(extract_batch, cache), 1)
        self._specialiser: Specialiser | None = None
        self._workspace_packages: list[Package] = []
        self._built: BuiltSources | None = None  # made again when a build file changes
        # The last graph build's pieces: the next takes back what an edit cannot reach.
        self._graph_memory = GraphMemory()
        # The last graph, the facts it was built from, the files its build extracted
        # again under an includer's arguments, and its rules' findings by file: edits
        # that leave every file's names as they were, wherever they now are (a comment,
        # a body that names nothing, a line above them), leave the findings standing,
        # their places moved (``_moved_items``: then the findings are of later facts,
        # ``_graph_basis``, than the graph object, ``_graph_made_from``); an edit of a
        # node's endpoints patches the graph (``_patched_graph``).
        self._last_graph: Graph | None = None
        self._graph_made_from: dict[str, FileFacts] = {}
        self._graph_basis: dict[str, FileFacts] = {}
        self._graph_specialised: frozenset[str] = frozenset()
        # The last ``_changed_since``: its basis, facts and specialised files, and answer
        self._changed: tuple[Any, ...] | None = None
        self._graph_items: dict[str, list[tuple[Rule, WorkspaceFinding]]] = {}

    def load(self) -> None:
        """Read the workspace: every file's facts, from the cache where it has them."""
        sources = discover(
            [self.root], self._settings.exclude, self._settings.root, self.root, cache=self._cache
        )
        self._sources = {source.display: source for source in sources}
        self._last_graph = None  # the workspace read again: nothing of a graph stands
        result = lint(
            lintable(sources),
            self._settings,
            self._registry,
            RunOptions(jobs=self._jobs, cache=self._cache),
            want_facts=True,
        )
        self._facts = {facts.path: facts for facts in result.facts}
        for diagnostic in result.diagnostics:
            if diagnostic.code in self._graph_codes:
                self._graph_found.setdefault(diagnostic.path, []).append(diagnostic)
        self._service_types = set(service_types(sources, self._packages))
        self._plugin_names = workspace_plugin_names(sources, self._packages)
        self._workspace_packages = workspace_packages(sources, self._packages)
        self._specialiser = Specialiser(
            sources,
            self._packages,
            self._fallback,
            self._cache,
            self._settings.max_file_size,
            dispatcher=self._dispatcher,
            ros1_python2=self._ros1_python2,
        )
        for facts in self._facts.values():
            self._service_types.update((facts.generation, t) for t in typed_services(facts))
            self._note_wiring(facts, partial(self._disk_bytes, facts.path))
        # The workspace's facts live as long as the session, and hold no cycle: out of
        # the collector's sight, whose full passes over them (millions of objects on a
        # large workspace) made one graph refresh in three take 2 s longer.
        gc.freeze()

    def display(self, path: Path) -> str:
        return display_path(path, self.root)

    def check(self, path: Path, text: str) -> list[Diagnostic] | None:
        """The document's diagnostics for ``text``: its per-file findings, and its graph
        findings as the last ``check_graph`` left them. None for a file no rule reads."""
        language = classify(path)
        if language is None or language not in EXTRACTOR_MODULES:
            return None
        display = self.display(path)
        source = self._sources.get(display) or SourceFile(os.fspath(path), display, language)
        self._sources[display] = source
        # A lone surrogate (JSON can carry one) becomes one replacement character: one code
        # point for one, so that the columns of the findings stay the document's.
        data = text.encode("utf-8", errors="replace")
        # Within the time budget where it can hold (the main thread), and a file shaped to
        # keep a parser busy is refused before it is parsed, in any thread.
        facts = extract_file(
            language,
            display,
            data,
            self._packages.for_file(path),
            self._fallback,
            ros1_python2=self._ros1_python2,
        )
        if uses_constants(facts):
            constants = PackageConstants()
            for other in self._facts.values():
                constants.add(other)
            facts = constants.resolve(facts, package_display(source, self._packages))
        previous = self._facts.get(display)
        self._facts[display] = facts
        if _builds(facts) or (previous is not None and _builds(previous)):
            self._built = None
        if self._specialiser is not None:
            self._specialiser.forget(display)
        self._service_types.update((facts.generation, t) for t in typed_services(facts))
        self._note_wiring(facts, lambda: text)
        known = visible_service_types(
            service_types_of(self._service_types, facts.generation),
            self._packages.visible_packages(path),
        )
        found, suppressions = check_file(
            facts,
            text,
            self._settings,
            self._registry,
            self._enabled,
            known_service_types=known,
            wired_names=frozenset().union(*self._wired_of.values()),
            plugin_names=self._plugin_names,
            test_rules=self._test_rules,
        )
        # One document at a time: its own places of a decision are one finding, as a
        # run reports them; a place whose producer is another file stays where it is.
        (found,) = one_per_decision([found])
        self._open[display] = _Checked(source, text, found, suppressions)
        return self._with_graph(display)

    def skip_reason(self, text: str) -> str | None:
        """Why a document of ``text`` is not checked (above ``max-file-size``, as ``check``
        skips such a file on disk), or None. Counts its UTF-8 bytes without encoding it
        whole: the text may be tens of megabytes."""
        maximum = self._settings.max_file_size
        if len(text) <= maximum and text.isascii():
            return None
        size = len(text) if text.isascii() else _utf8_size(text)
        return too_large(size, maximum) if size > maximum else None

    def skip(self, path: Path) -> None:
        """The document is not checked: no facts, no diagnostics, until it is again."""
        display = self.display(path)
        self._open.pop(display, None)
        self._graph_found.pop(display, None)
        self._graph_answered.pop(display, None)
        if display in self._facts:
            self._facts[display] = FileFacts(display, self._facts[display].language, self._fallback)
        self._wired_of.pop(display, None)
        if self._specialiser is not None:
            self._specialiser.forget(display)

    def close(self, path: Path) -> None:
        """The editor closed the document: its facts are the file's on disk again."""
        display = self.display(path)
        self._open.pop(display, None)
        self._graph_found.pop(display, None)
        self._graph_answered.pop(display, None)
        source = self._sources.get(display)
        data, _, skip = read_file(path, self._settings.max_file_size)
        if source is None or data is None or skip is not None:
            self._facts.pop(display, None)
            self._wired_of.pop(display, None)
            return
        self.check(path, data.decode("utf-8", errors="replace"))
        self._open.pop(display, None)

    def check_graph(self) -> dict[str, list[Diagnostic]]:
        """Every open document's diagnostics with its graph findings made anew."""
        job = self.graph_job()
        return self.apply_graph(job, job.build())

    def graph_job(self) -> GraphJob:
        """What a graph build needs, as it is now: the build itself may run in another
        thread (``GraphJob.build``) while documents keep changing here."""
        return GraphJob(self, dict(self._facts), dict(self._open))

    def apply_graph(self, job: GraphJob, graph: Graph | None) -> dict[str, list[Diagnostic]]:
        """The graph rules' findings for the documents open when ``job`` was made, kept
        for the later ``check`` of each; every open document's diagnostics."""
        if graph is not None:
            for checked in job.opened.values():
                display = checked.source.display
                if display not in self._open:
                    continue
                found = file_graph_findings(
                    self._graph_items.get(display, []),
                    checked.source,
                    job.facts[display],
                    list(checked.diagnostics),
                    suppressions=checked.suppressions,
                    settings=self._settings,
                    registry=self._registry,
                    text=checked.text,
                )
                self._graph_found[display] = [d for d in found if d.code in self._graph_codes]
                self._graph_answered[display] = [d for d in checked.diagnostics if d not in found]
        return {display: self._with_graph(display) for display in self._open}

    def _build_graph(self, job: GraphJob) -> Graph | None:
        specialise = self._specialiser
        if not self._graph_codes or not job.opened or specialise is None:
            return None
        rules = [rule for rule in self._registry.rules if rule.code in self._graph_codes]
        if self._last_graph is not None:
            items = self._moved_items(job.facts)
            if items is not None:
                self._graph_items, self._graph_basis = items, job.facts
                return self._last_graph
            patched = self._patched_graph(job.facts)
            if patched is not None:
                self._graph_items = self._patched_items(patched, rules, job.facts)
                self._last_graph, self._graph_basis = patched, job.facts
                self._graph_made_from = job.facts
                return patched
        graph = build(
            job.facts.values(),
            self._workspace_packages,
            specialise,
            specialise.prepare,
            self._graph_memory,
        )
        if self._graph_memory.moved:
            gc.freeze()  # what a whole build leaves the memory lives long too (``load``)
        self._graph_items = graph_findings(graph, rules, self._settings)
        self._last_graph, self._graph_basis = graph, job.facts
        self._graph_made_from = job.facts
        self._graph_specialised = specialise.specialised
        return graph

    def _moved_items(
        self, facts: dict[str, FileFacts]
    ) -> dict[str, list[tuple[Rule, WorkspaceFinding]]] | None:
        """The last graph's findings as the graph of ``facts`` has them, where it is that
        graph but for places: the same files, each with the facts the graph was built from
        but for their spans (``moves``: the findings' places in those files are moved) and
        the suppression marker, none of those that differ read again by the build (a
        launch file extracted under an includer's arguments); else None."""
        changed = self._changed_since(self._graph_basis, facts)
        if changed is None:
            return None
        moving: list[Moves] = []
        for display, then, now in changed:
            spans = moved_spans(then, now)
            if spans is None:
                return None
            move = Moves(display, spans)
            if not move.still:
                moving.append(move)
        if not moving:
            return self._graph_items
        try:
            return {
                path: [
                    (rule, WorkspaceFinding(path, moved_finding(item.finding, path, moving)))
                    for rule, item in items
                ]
                for path, items in self._graph_items.items()
            }
        except UnplacedError:
            return None

    def _patched_graph(self, facts: dict[str, FileFacts]) -> Graph | None:
        """The last graph with the nodes of edited code resolved again
        (``workspace.patch``), where every file whose facts differ from those it was made
        from is code whose edit changed its endpoints alone, or has the same facts in the
        same places, none of them read again by the build (``_moved_items``); else None.
        The graph memory is left as the last build left it: the next build compares with
        what that build was made from."""
        # Against the facts the graph object is of: a move since (``_moved_items``) moved
        # its findings, not its places.
        graph = self._last_graph
        changed = self._changed_since(self._graph_made_from, facts)
        edits = None if changed is None else edits_of(changed)
        if graph is None or edits is None:
            return None
        return patch_graph(
            graph,
            edits,
            facts.get,
            lambda: PackageFiles(facts.keys(), self._workspace_packages),
        )

    def _patched_items(
        self, graph: Graph, rules: list[Rule], facts: dict[str, FileFacts]
    ) -> dict[str, list[tuple[Rule, WorkspaceFinding]]]:
        """The graph rules' findings on the patched ``graph`` of ``facts``: a rule that
        reads no code's names (``Rule.reads_code_names``) has the last graph's, the
        places of the edited files moved, as the CLI keeps them after such a patch
        (``graph_patch._kept_findings``); the others find anew. All find anew where a
        place is no longer known."""
        changed = self._changed_since(self._graph_basis, facts)  # the findings' facts
        edits = None if changed is None else edits_of(changed)
        kept = {rule.code for rule in rules if not rule.reads_code_names}
        if edits is None or not kept:
            return graph_findings(graph, rules, self._settings)
        moving = [move for path, spans in edits.items() if not (move := Moves(path, spans)).still]
        try:
            taken = {
                path: [
                    (rule, WorkspaceFinding(path, moved_finding(item.finding, path, moving)))
                    for rule, item in items
                    if rule.code in kept
                ]
                for path, items in self._graph_items.items()
            }
        except UnplacedError:
            return graph_findings(graph, rules, self._settings)
        fresh = graph_findings(
            graph, [rule for rule in rules if rule.code not in kept], self._settings
        )
        # Each file's findings in the rules' order, as ``graph_findings`` lists them
        order = {rule.code: position for position, rule in enumerate(rules)}
        found: dict[str, list[tuple[Rule, WorkspaceFinding]]] = {}
        for path in [*fresh, *(path for path in taken if path not in fresh)]:
            items = fresh.get(path, []) + taken.get(path, [])
            if items:
                found[path] = sorted(items, key=lambda pair: order[pair[0].code])
        return found

    def _changed_since(
        self, basis: dict[str, FileFacts], facts: dict[str, FileFacts]
    ) -> list[tuple[str, FileFacts, FileFacts]] | None:
        """Each file whose facts are not those of ``basis``: its display path, its facts
        then and now; None where the files are not the same, or one of them was
        extracted again by the last build under an includer's arguments (its bytes, not
        only its facts, made the graph)."""
        known, specialised = self._changed, self._graph_specialised
        if known is not None and all(
            one is other for one, other in zip(known, (basis, facts, specialised), strict=False)
        ):
            answer: list[tuple[str, FileFacts, FileFacts]] | None = known[3]
            return answer  # asked by ``_moved_items``, then ``_patched_graph``
        changed: list[tuple[str, FileFacts, FileFacts]] | None = None
        if facts.keys() == basis.keys():
            changed = [
                (display, then, now)
                for display, now in facts.items()
                if (then := basis[display]) is not now
            ]
            if any(display in self._graph_specialised for display, _, _ in changed):
                changed = None
        self._changed = (basis, facts, specialised, changed)
        return changed

    def _note_wiring(self, facts: FileFacts, data: Callable[[], bytes | str]) -> None:
        """Keep what a launch file wires, as its facts are now (an edit may drop it).
        A code document's findings change with it at its next check."""
        wired = launch_wiring(facts, data, self._settings)
        if wired:
            self._wired_of[facts.path] = wired
        else:
            self._wired_of.pop(facts.path, None)

    def _disk_bytes(self, display: str) -> bytes:
        source = self._sources.get(display)
        data = None if source is None else read_file(source.path, self._settings.max_file_size)[0]
        return data or b""

    def _with_graph(self, display: str) -> list[Diagnostic]:
        checked = self._open[display]
        answered = self._graph_answered.get(display, [])
        own = [d for d in checked.diagnostics if d not in answered]
        found = own + self._graph_found.get(display, [])
        if found:
            built = self._built_sources()
            package = package_display(checked.source, self._packages)
            if built.unbuilt(display, package):
                found = [diagnostic for diagnostic in found if is_linter_code(diagnostic.code)]
            elif any(map(rostest_replaces, found)) and built.started_by_rostest(display, package):
                found = [diagnostic for diagnostic in found if not rostest_replaces(diagnostic)]
        return sorted(found, key=Diagnostic.sort_key)

    def _built_sources(self) -> BuiltSources:
        """What the workspace's build files compile, as a run judges it (``built``)."""
        if self._built is None:
            self._built = BuiltSources()
            for facts in self._facts.values():
                if _builds(facts):
                    package = self._sources.get(facts.path)
                    where = None if package is None else package_display(package, self._packages)
                    self._built.add(facts, where)
        return self._built


def _builds(facts: FileFacts) -> bool:
    """Whether a file's facts say what is compiled (``BuiltSources.add``)."""
    return facts.compiled is not None or bool(facts.included_sources)


def _utf8_size(text: str, chunk: int = 1 << 20) -> int:
    """The length of ``text`` in UTF-8, encoded a megabyte at a time."""
    return sum(
        len(text[start : start + chunk].encode("utf-8", errors="replace"))
        for start in range(0, len(text), chunk)
    )


@dataclass(frozen=True)
class GraphJob:
    """A snapshot of the session for one graph build."""

    session: Session
    facts: dict[str, FileFacts]  # display path -> facts
    opened: dict[str, _Checked]

    def build(self) -> Graph | None:
        """The workspace graph of the snapshot; None when no graph rule is enabled."""
        return self.session._build_graph(self)

"""One file's checks: the per-file rules over its facts and text, its suppressions and the
test-code policy (``check_file``, ``FileChecks`` as a worker runs them), and the graph
rules' findings made into a file's diagnostics (``report_graph``)."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

from .config import Settings, enabled_codes, ignored_for_path, ros1_python2, test_code_codes
from .discover import SourceFile, classify
from .editing.fixing import located
from .extract import EXTRACTOR_MODULES
from .gather import Verdict, extract_file
from .generation import DEFAULT_GENERATION, PackageGenerations
from .lines import split_lines
from .model import (
    Answer,
    Decision,
    Diagnostic,
    FileFacts,
    Fix,
    Generation,
    Kind,
    RelatedLocation,
    Span,
)
from .reading import decode_for_display, read_file
from .registry import Registry
from .rule import Rule, RuleContext, WorkspaceFinding
from .suppress import Suppression, find_suppressions, is_our_code
from .symbols import uses_constants
from .templates import holds_placeholder, is_template
from .test_code import is_example_code, is_test_code
from .types import parse_type
from .wiring import awaits_wiring, wired_by

if TYPE_CHECKING:
    from .workspace.graph import Graph  # the caller built it


UNUSED_SUPPRESSION = "RN002"
INVALID_SUPPRESSION = "RN003"


Contexts = Mapping[str, RuleContext]  # a context per per-file rule, by code


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
    contexts: Contexts
    wiring: bool

    def __call__(self, facts: FileFacts, data: bytes) -> Verdict | None:
        if waits_for_the_run(facts, self.wiring):
            return None
        return self.check_text(facts, decode_for_display(data), self.contexts)

    def check_text(self, facts: FileFacts, text: str, contexts: Contexts) -> Verdict:
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


def not_linter_code(diagnostic: Diagnostic) -> bool:
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


def typed_uses(facts: FileFacts) -> set[tuple[Generation | None, str]]:
    """The service types the file serves or calls, as the run's set holds them: with the
    file's generation (``typed_services``)."""
    return {(facts.generation, spelling) for spelling in typed_services(facts)}


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

"""The contract between the engine and a rule.

A rule is a module in ``roslint_names/rules/`` (or a plugin) that exposes one ``Rule`` value
through the ``roslint_names.rules`` entry-point group. Its ``check`` is pure: facts of one
file, the settings that concern it and what the engine gathered of the rest of the run
(``RuleContext``) in, findings out. A graph rule's ``check_workspace``
is pure too: the workspace's resolved graph in, findings in any of its files out.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field

from .model import FileFacts, Finding, Generation, Kind, Severity
from .workspace.graph import Graph

OptionValue = bool | int | str | tuple[str, ...]


@dataclass(frozen=True)
class NamingPolicy:
    """A project's pattern for the names of one kind (RN206)."""

    kind: Kind
    pattern: str  # the configured regular expression, full-match semantics
    description: str  # what the user wrote it as, for messages


@dataclass(frozen=True)
class RuleContext:
    """What a rule may know besides the facts: settings, never the file system."""

    max_depth: int = 4
    options: Mapping[str, OptionValue] = field(default_factory=dict)
    policies: tuple[NamingPolicy, ...] = ()
    # Service types of the run beyond the file's own: every .srv file found and every type
    # another file serves or calls, as "package/Name" (RN204).
    known_service_types: frozenset[str] = frozenset()
    # The absolute names the workspace's launch files remap nodes to (``wiring``), given
    # to a rule that asks for them (``Rule.reads_wiring``); empty for the others.
    wired_names: frozenset[str] = frozenset()
    # The names pluginlib gives the plugins the workspace's packages export (``plugins``):
    # a namespace spelled so is a plugin's class name, not the writer's choice (RN203).
    plugin_names: frozenset[str] = frozenset()


Check = Callable[[FileFacts, RuleContext], Iterable[Finding]]


@dataclass(frozen=True)
class WorkspaceFinding:
    """A graph rule's finding and the file it belongs to (a display path of the run)."""

    path: str
    finding: Finding


WorkspaceCheck = Callable[[Graph, RuleContext], Iterable[WorkspaceFinding]]


@dataclass(frozen=True)
class Rule:
    code: str  # RNxxx, stable forever
    name: str  # kebab-case slug
    summary: str  # one line
    severity: Severity  # default severity (on ROS 2 when the two differ)
    check: Check | None  # None: reported by the engine itself (suppression bookkeeping)
    ros1_severity: Severity | None = None  # when ROS 1 tolerates what ROS 2 rejects
    enabled_by_default: bool = True
    options: Mapping[str, OptionValue] = field(default_factory=dict)  # name -> default
    # Why a configured option value is refused, or None: checked when the configuration
    # is read (after its type, which the default's gives), so that a bad value ends the
    # run naming its key instead of silencing nothing.
    option_error: Callable[[str, OptionValue], str | None] | None = None
    check_workspace: WorkspaceCheck | None = None  # graph rules: the whole workspace at once
    # Whether the rule judges test code by default (``test_code``): a rule whose findings
    # make a test fail or pass for the wrong reason does (an illegal name, an init order,
    # a type mismatch); a style rule does not (a CamelCase fixture, an absolute name in an
    # integration test harm no one). ``[test-code]`` in the config changes the selection.
    judges_test_code: bool = True
    # Whether ``check`` reads ``RuleContext.wired_names``: a run over some files then
    # gathers the launch files of the rest of their workspace, so that its answer is the
    # whole workspace's.
    reads_wiring: bool = False
    # Whether ``check`` reads ``RuleContext.plugin_names``: a run over some files then
    # reads the package.xml files of the rest of their workspace (not their sources).
    reads_plugins: bool = False
    # Whether ``check_workspace`` reads what a node's code names: its endpoints, the names
    # it uses (``NodeInstance.uses``), its package's literals (``Graph.mentions``). One that
    # reads none keeps its findings where an edit changed only those (``workspace.patch``).
    # One that does is run over the patched graph, which holds no parameter declarations,
    # settings or files (``patch.for_patching``): it may not read those.
    reads_code_names: bool = True

    def severity_for(self, generation: Generation) -> Severity:
        if generation is Generation.ROS1 and self.ros1_severity is not None:
            return self.ros1_severity
        return self.severity

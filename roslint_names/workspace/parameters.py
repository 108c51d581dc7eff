"""A node's parameters as its code shows them: what it declares, what it reads, and whether
that is the whole story.

The code looked at is wider than the node's own sources: a declaration may sit in another
file of the same executable or library (the class's constructor, a header, a
``parameter_handler.cpp``), or in a base class. So the node's *code* is every non-test code
file of the packages of its sources, plus the files defining the base classes (followed
through the workspace) of the classes in those files. Looking wider only adds
declarations, and causes of doubt, so it can only make a node's set more cautious.

The set is incomplete, for one or more ``Incomplete`` causes, when names may be declared,
read or accepted that no code of the workspace spells: names built at run time, undeclared
parameters allowed, declarations from overrides, plugins (but for those of the node's own
package: ``ParameterSets._own_plugins``), generated parameter code,
dynamic_reconfigure, a base class the workspace does not hold, a ROS 1 search up the
namespaces (``searchParam``), or code not (all) in the workspace. The causes are kept
apart: a rule that judges reads of undeclared names asks only whether the *declarations*
are all known (``declarations_complete``).

A ROS 1 dynamic_reconfigure server reads every parameter of its config from its node
handle's namespace, private by default (dynamic_reconfigure's ``server.h``,
``Server::init`` and the generated ``__fromServer__``; ``server.py``, ``Server.__init__``);
the config's names are its ``.cfg`` file's (``extract.build.reconfigure``, after
``parameter_generator_catkin.py``'s ``ParameterGenerator.add`` and ``generate``). A node
whose code serves ``pkg::NameConfig`` reads those names, written as its other reads are
(relative to the handle), and is no longer incomplete for dynamic_reconfigure when every
config its code serves is a ``.cfg`` of the workspace whose names are all known.

Every ROS 2 node also holds what its client library declares for it: ``use_sim_time``
(rclcpp's ``TimeSource::NodeState::attachNode`` in ``rclcpp/src/rclcpp/time_source.cpp``,
rclpy's ``TimeSource.attach_node`` in ``rclpy/time_source.py``) and
``start_type_description_service`` (rclcpp's ``NodeTypeDescriptions`` in
``node_interfaces/node_type_descriptions.cpp``, rclpy's ``TypeDescriptionService``), and
the ``qos_overrides.`` parameters rclcpp declares for a publisher or subscription that
allows QoS overrides (``rclcpp/detail/qos_parameters.hpp``).

A ROS 2 node whose code holds a filters library chain (``filters::FilterChain<T>``,
``MultiChannelFilterChain<T>``) declares what the chain does: ros/filters' (ros2)
``impl::load_chain_config`` (``include/filters/filter_chain.hpp``) declares ``filterN.name``
and ``filterN.type`` under the prefix ``configure`` is given, for N from 1 until one is
unset, and each filter it loads declares its own ``filterN.params.*``
(``FilterBase::getParamImpl``, ``filter_base.hpp``). The prefix is not read: a name with
such a part at any depth counts as declared, and the node's other names stay judged
(laser_filters' ``scan_to_scan_filter_chain`` reads ``tf_message_filter_target_frame``
without declaring it).
"""

from __future__ import annotations

import posixpath
import re
from collections.abc import Callable, Iterable, Sequence
from copy import copy
from dataclasses import dataclass, field, replace
from enum import Enum
from functools import cache
from typing import Any

from roslint_names.model import (
    ENDPOINT_ROLES,
    EventKind,
    FileFacts,
    Generation,
    Kind,
    Language,
    NameUse,
    ParameterAccess,
    ParameterTrait,
    ReconfigureConfig,
    Role,
)
from roslint_names.workspace.built import BUILD_FIELDS, TRANSLATION_UNITS
from roslint_names.workspace.graph import Location
from roslint_names.workspace.index import CODE_LANGUAGES, Package, WorkspaceIndex
from roslint_names.workspace.memory import GraphMemory, Reads

LIBRARY_DECLARED = frozenset({"use_sim_time", "start_type_description_service"})
LIBRARY_PREFIXES = ("qos_overrides.",)
DECLARATIONS = frozenset({ParameterAccess.DECLARE})
READS = frozenset(
    {
        ParameterAccess.READ,
        ParameterAccess.READ_QUIETLY,
        ParameterAccess.CHECK,
    }
)


class Incomplete(str, Enum):
    """Why a node's parameter set may miss names; the note counts nodes by these."""

    NO_CODE = "no-code"  # none of the node's code is in the workspace
    LIBRARY = "library"  # code no program or component is known to run alone
    RUN_TIME_DECLARATION = "run-time-declaration"  # declares names built at run time
    RUN_TIME_READ = "run-time-read"  # reads names built at run time
    ALLOW_UNDECLARED = "allow-undeclared"  # allow_undeclared_parameters
    FROM_OVERRIDES = "from-overrides"  # automatically_declare_parameters_from_overrides
    PLUGINS = "plugins"  # loads pluginlib plugins, which declare on the node
    GENERATED = "generated"  # generate_parameter_library declares them
    DYNAMIC_RECONFIGURE = "dynamic-reconfigure"  # a .cfg file's parameters (ROS 1)
    BASE_CLASS = "base-class"  # derives from a class the workspace does not hold
    SEARCH = "search"  # ROS 1 searchParam of a run-time name: found up the namespaces


_TRAIT_CAUSES = {
    ParameterTrait.ALLOW_UNDECLARED: Incomplete.ALLOW_UNDECLARED,
    ParameterTrait.FROM_OVERRIDES: Incomplete.FROM_OVERRIDES,
    ParameterTrait.PLUGINS: Incomplete.PLUGINS,
    ParameterTrait.GENERATED: Incomplete.GENERATED,
    ParameterTrait.DYNAMIC_RECONFIGURE: Incomplete.DYNAMIC_RECONFIGURE,
}
# Client-library base classes: they declare only what LIBRARY_DECLARED says. Spelled
# unqualified (``Node`` under a using), they count only where the workspace defines no
# class of that name.
_ROOT_BASES = frozenset(
    {
        "rclcpp::Node",
        "rclcpp_lifecycle::LifecycleNode",
        "rclpy.node.Node",
        "rclpy.lifecycle.Node",
        "rclpy.lifecycle.LifecycleNode",
    }
)
_UNQUALIFIED_ROOTS = frozenset({"Node", "LifecycleNode"})


@dataclass(frozen=True, order=True)
class ParameterUse:
    """A parameter name the node's own sources use, where, and how."""

    name: str
    access: ParameterAccess
    location: Location
    api: str


@dataclass(frozen=True)
class NodeParameters:
    """What a node's code declares and reads (static names, sorted), the ends of names it
    declares or reads under a run-time prefix (``.max_vel_x``), the prefixes it reads
    everything below, and why the set may be incomplete (empty: it is complete).

    ``uses`` are the static parameter uses of the node's own sources, for the rules to
    point at; the names are the whole code's.
    """

    declared: tuple[str, ...] = ()
    read: tuple[str, ...] = ()
    declared_suffixes: tuple[str, ...] = ()
    read_suffixes: tuple[str, ...] = ()
    read_prefixes: tuple[str, ...] = ()
    incomplete: tuple[Incomplete, ...] = ()
    uses: tuple[ParameterUse, ...] = ()
    # Parameter-shaped strings the node's code holds beyond the names read for
    # (``FileFacts.unexplained_literals``): names it may declare some way the linter does
    # not know.
    literals: tuple[str, ...] = ()
    # Constants of other packages the code declares parameters by, whose values the
    # workspace does not hold (``bond::msg::Constants::DISABLE_HEARTBEAT_TIMEOUT_PARAM``).
    declared_constants: tuple[str, ...] = ()
    # The dynamic_reconfigure ``.cfg`` files whose parameters the code's servers read
    # (their names are in ``read``).
    reconfigure: tuple[str, ...] = ()
    # The code holds a filters library chain (ROS 2): it declares ``filterN.name``,
    # ``filterN.type`` and ``filterN.params.*`` under some prefix (module docstring).
    filter_chain: bool = False
    # A class of the code derives from one the workspace does not define (but a client
    # library's node and harmless library classes), or from one of another package whose
    # code followed for the node declares endpoints: code that runs in the node and uses
    # names of its own (autoware's ground filters subscribe ``input`` through
    # ``pointcloud_preprocessor::Filter``). Made from what decides which code is followed
    # (bases, includes: a gathering edit) and whether a file declares endpoints (an edit
    # that flips it makes its package's programs again, and gathers the code spanning it:
    # ``parameter_patch``).
    derives_elsewhere: bool = False

    @property
    def complete(self) -> bool:
        return not self.incomplete

    @property
    def declarations_complete(self) -> bool:
        """Whether every name the node may declare is known: only run-time *reads* are
        allowed to be unknown."""
        return all(cause is Incomplete.RUN_TIME_READ for cause in self.incomplete)

    def declares(self, name: str) -> bool:
        """Whether the code (or its client library, or a filter chain it holds) may
        declare ``name``."""
        if self.filter_chain and _FILTER_CHAIN_NAME.search(name):
            return True
        return declared_by(name, self.declared, self.declared_suffixes)

    def may_declare(self, name: str) -> bool:
        """Whether the code may declare ``name`` some way the linter cannot see through:
        a string it holds that no known API takes, or a constant of another package whose
        name shares a word with it (a constant is named for what it holds:
        ``DISABLE_HEARTBEAT_TIMEOUT_PARAM`` may hold ``bond_disable_heartbeat_timeout``,
        hardly ``max_vel_x``)."""
        if name in self.literals:
            return True
        words = _words(name)
        return any(
            words & _words(constant.rpartition("::")[2]) for constant in self.declared_constants
        )


# The parameters of a node whose code the workspace does not hold
NO_CODE = NodeParameters(incomplete=(Incomplete.NO_CODE,))
# What a filters library chain declares on its node (module docstring), under any prefix
_FILTER_CHAIN_NAME = re.compile(r"(?:^|\.)filter[1-9][0-9]*\.(?:name$|type$|params\.)")


def declared_by(name: str, names: Iterable[str], suffixes: Iterable[str]) -> bool:
    """``name`` among ``names``, or ending with a suffix (an empty run-time prefix may
    leave the suffix alone), or one the client library declares."""
    if name in LIBRARY_DECLARED or name.startswith(LIBRARY_PREFIXES):
        return True
    return name in names or any(name.endswith(suffix) for suffix in suffixes)


@dataclass(frozen=True)
class WorkspaceDeclarations:
    """Every parameter the workspace's ROS 2 code declares, statically or by its end: a
    name declared nowhere in the workspace cannot have been declared by a helper of it.

    ``mentioned``: what else the workspace's code may take a parameter by, on a node it
    is handed: the static names its ROS 1 code reads, and the parameter-shaped strings of
    any code that no API the linter knows takes (``FileFacts.unexplained_literals``); of
    ROS 1 code without their ``~`` and slashes."""

    names: frozenset[str] = frozenset()
    suffixes: frozenset[str] = frozenset()
    mentioned: frozenset[str] = frozenset()

    def declares(self, name: str) -> bool:
        return declared_by(name, self.names, self.suffixes)

    def mentions(self, name: str) -> bool:
        return self.declares(name) or name in self.mentioned


@dataclass(frozen=True)
class TableLookups:
    """What ``ParameterTables`` looks up, made from every file's facts: what a parameter
    patch keeps of a build (``workspace.parameter_patch``), which follows an edit of a
    file's classes through ``with_classes``."""

    classes: dict[str, list[str]]  # class name -> files defining it
    # base class name -> (file, base as written) of each class derived from it
    derived: dict[str, list[tuple[str, str]]]
    # (package directory, C++ file name) -> its paths in that package
    by_name: dict[tuple[str, str], list[str]]
    programs: set[str]  # sources of every program and component
    # ``NameConfig`` -> (package, path) of each .cfg generating it
    configs: dict[str, list[tuple[str | None, str]]]
    # class name -> every code file (test and unbuilt code too) deriving from a class of
    # that name, but for the client libraries' nodes (``_ROOT_BASES``, never looked up):
    # the files whose nodes' code may be another where the classes of that name change
    # (``ParameterSets._defined``). Read by a patch only.
    deriving: dict[str, list[str]]
    # class name -> every code file loading plugins of a base of that name: whose nodes'
    # plugins may be others where the classes of that name or derived from one change
    # (``ParameterSets._own_plugins``). Read by a patch only.
    loading: dict[str, list[str]]

    def add_classes(self, path: str, facts: FileFacts, *, excluded: bool) -> None:
        """What a code file's classes add (``ParameterTables.of``: files in path order)."""
        for name, entries in _FOLLOWED:
            lookup: dict[str, list[Any]] = getattr(self, name)
            for key, entry in entries(path, facts, excluded):
                lookup.setdefault(key, []).append(entry)

    def with_classes(
        self,
        edited: Iterable[tuple[str, FileFacts, FileFacts]],
        excluded: Callable[[str], bool],
    ) -> tuple[TableLookups, set[str]]:
        """These lookups (made from the files' facts before) with each edited code file's
        classes and plugin loaders as they are now (display path, facts before and now),
        where ``ParameterTables.of`` puts them; and the files whose nodes' parameters the
        changed entries may change besides the edited ones: those deriving from a class
        of a name whose classes changed, or loading plugins of such a base or of one
        whose derived classes changed (``deriving``, ``loading``)."""
        lookups = {name: dict(getattr(self, name)) for name, _ in _FOLLOWED}
        changed: dict[str, set[str]] = {name: set() for name, _ in _FOLLOWED}
        for path, before, now in edited:
            left_out = excluded(path)
            for name, entries in _FOLLOWED:
                old, new = entries(path, before, left_out), entries(path, now, left_out)
                changed[name] |= _replace_entries(lookups[name], path, old, new)
        defined, bases = changed["classes"], changed["derived"]
        reached = {path for key in defined for path in self.deriving.get(key, ())}
        reached.update(path for key in defined | bases for path in self.loading.get(key, ()))
        found = replace(
            self,
            classes=lookups["classes"],
            derived=lookups["derived"],
            deriving=lookups["deriving"],
            loading=lookups["loading"],
        )
        return found, reached


def _defined_classes(path: str, facts: FileFacts, excluded: bool) -> list[tuple[str, Any]]:
    """``TableLookups.classes``' entries of a file: (class name, its path)."""
    return [] if excluded else [(name, path) for name, _ in facts.class_bases]


def _derived_classes(path: str, facts: FileFacts, excluded: bool) -> list[tuple[str, Any]]:
    """``TableLookups.derived``' entries of a file: (base class name, (its path, the base
    as written))."""
    if excluded:
        return []
    return [(_class_name(base), (path, base)) for _, bases in facts.class_bases for base in bases]


def _bases_looked_up(path: str, facts: FileFacts, _: bool) -> list[tuple[str, Any]]:
    """``TableLookups.deriving``' entries of a file: the name of each base of its classes
    that the parameter sets look up, with its path."""
    written = {base for _, bases in facts.class_bases for base in bases}
    return [(name, path) for name in sorted({_class_name(base) for base in written - _ROOT_BASES})]


def _loaded(path: str, facts: FileFacts, _: bool) -> list[tuple[str, Any]]:
    """``TableLookups.loading``' entries of a file: the name of each base of the plugins
    it loads, with its path."""
    return [(name, path) for name in sorted({_class_name(b) for b in facts.plugin_loaders if b})]


# Each lookup of classes (a field of ``TableLookups``) and the entries a file of code
# makes in it (from its path, facts and whether the tables leave it out).
_FOLLOWED: tuple[tuple[str, Callable[[str, FileFacts, bool], list[tuple[str, Any]]]], ...] = (
    ("classes", _defined_classes),
    ("derived", _derived_classes),
    ("deriving", _bases_looked_up),
    ("loading", _loaded),
)


def _path_of(entry: str | tuple[str, str]) -> str:
    """The file of an entry of a lookup of classes: itself, or its first item."""
    return entry if isinstance(entry, str) else entry[0]


def _replace_entries(
    table: dict[str, list[Any]],
    path: str,
    old: list[tuple[str, Any]],
    new: list[tuple[str, Any]],
) -> set[str]:
    """``table`` (a copy: its lists are replaced, never changed) with ``path``'s entries
    ``old`` (key, entry) put out and ``new`` put in among the other files' in path
    order; the keys whose entries changed."""
    changed: set[str] = set()
    for key in sorted({key for key, _ in (*old, *new)}):
        listed = table.get(key, [])
        kept = [entry for entry in listed if _path_of(entry) != path]
        at = next((i for i, entry in enumerate(kept) if _path_of(entry) > path), len(kept))
        kept[at:at] = [entry for found, entry in new if found == key]
        if kept == listed:
            continue
        changed.add(key)
        if kept:
            table[key] = kept
        else:
            del table[key]
    return changed


@dataclass
class DeclarationCounts:
    """How many code files add each name, suffix and mention to ``WorkspaceDeclarations``
    (``file_declarations``' three sets): the workspace's declarations follow an edit of
    one file without the others' facts (``workspace.parameter_patch``)."""

    # Dicts, not ``Counter``s: a kept graph's unpickler builds no other class.
    names: dict[str, int] = field(default_factory=dict)
    suffixes: dict[str, int] = field(default_factory=dict)
    mentioned: dict[str, int] = field(default_factory=dict)

    def add(self, declared: tuple[frozenset[str], ...], times: int = 1) -> None:
        """One file's declarations (``file_declarations``) added; taken away for -1."""
        for counts, found in zip(
            (self.names, self.suffixes, self.mentioned), declared, strict=True
        ):
            for name in found:
                count = counts[name] = counts.get(name, 0) + times
                if not count:
                    del counts[name]  # as counts made anew hold it: none

    def declarations(self) -> WorkspaceDeclarations:
        return WorkspaceDeclarations(
            *(
                frozenset(name for name, count in counter.items() if count > 0)
                for counter in (self.names, self.suffixes, self.mentioned)
            )
        )


class ParameterTables:
    """Where the parameter sets look classes, headers, programs and configs up: made from
    ``FIELDS`` of every file's facts, where files are and which are ``excluded`` (tests,
    sources no build compiles), and kept by a memory while none of that changes."""

    # What the tables are made from in every file's facts, besides the classes, which
    # a memory's next build takes in through ``with_classes``.
    FIELDS = ("language", "reconfigure", "executables", *BUILD_FIELDS)

    def __init__(self, lookups: TableLookups, excluded: Callable[[str], bool]) -> None:
        self.lookups = lookups
        # Asked about the same files for every node: each answer once.
        self.excluded = cache(excluded)
        self.classes = lookups.classes
        self.derived = lookups.derived
        self.by_name = lookups.by_name
        self.programs = lookups.programs
        self.configs = lookups.configs
        # What is looked up in these alone, each once.
        self.included: dict[tuple[str, str], list[str]] = {}
        self.implementations: dict[str, list[str]] = {}
        self.defined: dict[tuple[str, str], list[str]] = {}

    def with_classes(
        self, edited: Iterable[tuple[str, FileFacts, FileFacts]]
    ) -> tuple[ParameterTables, set[str]]:
        """These tables with the edited files' classes as they are now, and the other files
        whose nodes' parameters that may change (``TableLookups.with_classes``). What was
        looked up of no class is kept, the answers on excluded files with it (a
        language server's memory takes this up edit after edit: wrapped anew each time,
        ``excluded`` would nest one cache per edit)."""
        lookups, reached = self.lookups.with_classes(edited, self.excluded)
        tables = copy(self)
        tables.lookups, tables.classes, tables.derived = lookups, lookups.classes, lookups.derived
        tables.defined = {}  # which of the classes of a name a file means
        return tables, reached

    @classmethod
    def of(cls, index: WorkspaceIndex, excluded: Callable[[str], bool]) -> ParameterTables:
        """The tables of every file of ``index``."""
        lookups = TableLookups({}, {}, {}, set(), {}, {}, {})
        tables = cls(lookups, excluded)
        for path, facts in sorted(index.facts.items()):
            if facts.reconfigure is not None and facts.reconfigure.name is not None:
                package = facts.reconfigure.package or _package_name(index, path)
                tables.configs.setdefault(f"{facts.reconfigure.name}Config", []).append(
                    (package, path)
                )
            if facts.language not in CODE_LANGUAGES:
                continue
            left_out = tables.excluded(path)
            lookups.add_classes(path, facts, excluded=left_out)
            if left_out:
                continue
            if facts.language is Language.CPP:
                key = (package_directory(index, path), posixpath.basename(path))
                tables.by_name.setdefault(key, []).append(path)
        for sources in index.built_sources().values():
            tables.programs.update(sources)
        tables.programs.update(index.plugin_sources())
        return tables


class ParameterSets:
    """Computes each node's ``NodeParameters`` over one run's index, memoised by sources
    (across builds, in ``memory``, each with the files it was made from)."""

    def __init__(
        self,
        index: WorkspaceIndex,
        tables: ParameterTables,
        memory: GraphMemory | None = None,
    ) -> None:
        self._index = index
        self._tables = tables
        self._excluded = tables.excluded
        self._memory = memory = GraphMemory(keeps=False) if memory is None else memory
        # Made from the tables too: forgotten with them (and, where a file's classes
        # change, the pieces that read a file deriving from them: ``build``).
        fields = ParameterTables.FIELDS
        self._memo = memory.reads("parameters", fields)  # sources -> their parameters
        self._reached_memo = memory.reads("reached", fields)  # path -> what it includes
        self._package_memo = memory.reads("package declarations", fields)
        self._declared_memo = memory.reads("declarations")  # path -> what it declares
        self._classes = tables.classes
        self._derived = tables.derived
        self._by_name = tables.by_name
        self._programs = tables.programs
        self._configs = tables.configs
        self._included_memo = tables.included
        self._implementations_memo = tables.implementations
        self._names_memo: dict[str, tuple[_Names, frozenset[Incomplete]] | None] = {}
        self._defined_memo = tables.defined
        # The packages each node's code (sources -> parameters, ``of``) was gathered from,
        # "" for a file of none: an edit of another package's code changes none of it
        # (``workspace.parameter_patch``). Those this set computed, not a memory's.
        self.spans: dict[tuple[str, ...], frozenset[str]] = {}
        # How many code files declare each name, suffix and mention of the workspace's
        # declarations (``declarations``), made with them.
        self.counts: DeclarationCounts | None = None

    @property
    def lookups(self) -> TableLookups:
        return self._tables.lookups

    def declarations(self) -> WorkspaceDeclarations:
        """What the workspace's code declares; the last build's where no changed file's
        declarations differ (a launch file's edit: 0.07 s of 77,000 files)."""
        return self._memory.piece(
            "workspace declarations", (_code_declarations,), self._declarations
        )

    def _declarations(self) -> WorkspaceDeclarations:
        counts = DeclarationCounts()
        for path, facts in self._index.facts.items():
            if facts.language not in CODE_LANGUAGES:
                continue
            kept = self._declared_memo.get(path)
            if kept is None:
                kept = (file_declarations(facts), self._memory.read((path,)))
                if self._memory.keeps:  # else asked once a build: no memo
                    self._declared_memo[path] = kept
            if any(kept[0]):  # most files declare nothing: 40,000 calls saved at 8 copies
                counts.add(kept[0])
        self.counts = counts
        return counts.declarations()

    def of(self, sources: Sequence[str]) -> NodeParameters:
        key = tuple(sources)
        found = self._memo.get(key)
        if found is None:
            found = self._memo[key] = self._compute(key)
        parameters: NodeParameters = found[0]
        return parameters

    def _compute(self, sources: tuple[str, ...]) -> tuple[NodeParameters, Reads]:
        """The node's parameters, and the files and packages they are made from."""
        if not sources:
            return NO_CODE, self._memory.read()
        causes: set[Incomplete] = set()
        if not any(self._is_program(path) for path in sources):
            causes.add(Incomplete.LIBRARY)
        own, unknown_base, bases = self._own_code(sources)
        if unknown_base:
            causes.add(Incomplete.BASE_CLASS)
        names = _Names()
        for path in own:
            found = self._file_names(path)
            if found is not None:
                names.join(found[0])
                causes |= found[1]
        if Incomplete.PLUGINS in causes and self._own_plugins(own, sources):
            causes.discard(Incomplete.PLUGINS)  # their declarations are the package's
        configs: set[str] = set()
        if Incomplete.DYNAMIC_RECONFIGURE in causes:
            configs, known = self._served(own)
            for path in configs:
                names.read.update(name for name, _ in self._config_of(path).parameters)
            if known:
                causes.discard(Incomplete.DYNAMIC_RECONFIGURE)
        # The rest of the packages' code (a library the program links, a helper): its
        # declarations may be the node's too. Only declarations: what it reads, or leaves
        # open, is another node's business.
        packages = sorted({p.name for path in sources if (p := self._index.package_of(path))})
        # The base classes' code of other packages: where they are defined and the files
        # of the same stem that implement them (``Filter::Filter`` in ``filter.cpp``).
        beyond = [
            found
            for path in bases
            if (owner := self._index.package_of(path)) is not None and owner.name not in packages
            for found in (path, *self._implementations(path))
        ]
        elsewhere = unknown_base or any(has_endpoints(self._index.facts[path]) for path in beyond)
        self.spans[sources] = frozenset(
            (p.name if (p := self._index.package_of(path)) else "") for path in (*sources, *bases)
        ) | frozenset(packages)
        for package in packages:
            declared, suffixes = self._package_declarations(package)
            names.declared |= declared
            names.declared_suffixes |= suffixes
        uses = tuple(
            sorted(
                ParameterUse(use.value, use.access, Location(path, use.span), use.api)
                for path in sources
                for use in _parameter_uses(self._index.facts[path])
                if not use.dynamic and use.access is not None
            )
        )
        read = self._memory.read(tuple({*sources, *own, *configs, *beyond}), tuple(packages))
        return NodeParameters(
            declared=tuple(sorted(names.declared)),
            read=tuple(sorted(names.read)),
            declared_suffixes=tuple(sorted(names.declared_suffixes)),
            read_suffixes=tuple(sorted(names.read_suffixes)),
            read_prefixes=tuple(sorted(names.read_prefixes)),
            incomplete=tuple(cause for cause in Incomplete if cause in causes),
            uses=uses,
            literals=tuple(sorted(names.literals)),
            declared_constants=tuple(sorted(names.constants)),
            reconfigure=tuple(sorted(configs)),
            filter_chain=names.filter_chain,
            derives_elsewhere=elsewhere,
        ), read

    def _file_names(self, path: str) -> tuple[_Names, frozenset[Incomplete]] | None:
        """What one file adds to the names and causes of each node whose code holds it
        (None: nothing, as most headers): made once a build, however many nodes hold it
        (234,000 files of nodes' code at 8 copies of the benchmark's workspace)."""
        if path in self._names_memo:
            return self._names_memo[path]
        facts = self._index.facts[path]
        traits = facts.parameter_traits
        causes = {_TRAIT_CAUSES[trait] for trait in traits if trait in _TRAIT_CAUSES}
        names = _Names()
        names.add(facts, causes)
        # ROS 1's chain reads the list under the name it is given: a string the code
        # holds, which counts as read (``literals``).
        if ParameterTrait.FILTER_CHAIN in traits and facts.generation is not Generation.ROS1:
            names.filter_chain = True
        names.literals.update(facts.unexplained_literals)
        found = None if names.empty and not causes else (names, frozenset(causes))
        self._names_memo[path] = found
        return found

    def _own_plugins(self, own: Iterable[str], sources: Sequence[str]) -> bool:
        """Whether every plugin the code may load is a class of the node's own packages,
        whose declarations count as the node's already (``_package_declarations``): each
        loader names a base class of the node's packages (or of a library vendored inside
        one), and the workspace's classes derived from it, one at least, are all there.
        nav2_amcl's ``ClassLoader<nav2_amcl::MotionModel>`` loads nav2_amcl's motion
        models; slam_toolbox's ``ClassLoader<karto::ScanSolver>`` (``lib/karto_sdk``) its
        Ceres solver. A base of another package (nav2_core's ``Controller``,
        opennav_docking_core's ``ChargingDock``) is an extension point for plugins of any
        package, installed ones among them: the node stays unjudged."""
        bases = {base for path in own for base in self._index.facts[path].plugin_loaders}
        if not bases or "" in bases:
            return False  # plugins whose base the code does not show
        packages = [p for path in sources if (p := self._index.package_of(path))]
        names = {package.name for package in packages}
        for base in bases:
            derived = self._implementations_of(base)
            if (
                not derived
                or not self._defined_within(base, packages)
                or any(
                    (p := self._index.package_of(path)) is None or p.name not in names
                    for path in derived
                )
            ):
                return False
        return True

    def _defined_within(self, base: str, packages: Sequence[Package]) -> bool:
        """Whether a file defining the class ``base`` is in one of ``packages`` or in a
        package inside one's directory."""
        directories = {package.directory for package in packages}
        for path in self._classes.get(_class_name(base), []):
            defining = self._index.package_of(path)
            if defining is not None and any(
                _within(defining.directory, directory) for directory in directories
            ):
                return True
        return False

    def _implementations_of(self, base: str) -> list[str]:
        """The files of the workspace's classes derived from ``base`` as a loader names
        it. Two spellings of one qualified name must agree; a base written without its
        namespace in a package that defines a class of that name itself is that class
        (nav2_mppi_controller's ``MotionModel`` is not nav2_amcl's)."""
        name = _class_name(base)
        found: list[str] = []
        for path, written in self._derived.get(name, []):
            if "::" in written and "::" in base:
                if written.lstrip(":") == base.lstrip(":"):
                    found.append(path)
                continue
            package = self._index.package_of(path)
            defines_own = package is not None and any(
                self._index.package_of(defining) == package
                for defining in self._classes.get(name, [])
            )
            if "::" in written or "::" not in base or not defines_own:
                found.append(path)
        return found

    def _served(self, own: Iterable[str]) -> tuple[set[str], bool]:
        """The ``.cfg`` files of the configs the code serves, and whether they are all
        it serves, each known whole: every file that shows a server names its config,
        and each config is one ``.cfg`` of the workspace with no name left open."""
        found: set[str] = set()
        known = True
        for path in own:
            facts = self._index.facts[path]
            if ParameterTrait.DYNAMIC_RECONFIGURE not in facts.parameter_traits:
                continue
            known = known and bool(facts.reconfigure_servers)
            for written in facts.reconfigure_servers:
                config = self._config(written, path)
                if config is None:
                    known = False
                    continue
                found.add(config)
                known = known and self._config_of(config).complete
        return found, known and bool(found)

    def _config(self, written: str, user: str) -> str | None:
        """The ``.cfg`` generating the config ``written`` (``pkg::NameConfig``, or
        ``NameConfig`` in the package's own namespace) that ``user`` serves."""
        package, _, name = written.rpartition("::")
        candidates = self._configs.get(name, [])
        if package:
            candidates = [entry for entry in candidates if entry[0] == package]
        elif len(candidates) > 1:
            own = _package_name(self._index, user)
            candidates = [entry for entry in candidates if entry[0] == own]
        return candidates[0][1] if len(candidates) == 1 else None

    def _config_of(self, path: str) -> ReconfigureConfig:
        config = self._index.facts[path].reconfigure
        assert config is not None  # only paths of configs are kept
        return config

    def _is_program(self, path: str) -> bool:
        return path in self._programs or _starts_runtime(self._index, path)

    def _own_code(self, sources: tuple[str, ...]) -> tuple[list[str], bool, set[str]]:
        """The node's code: its sources, what they include of their own package (with the
        file of the same stem that implements an included header), and the files of the
        base classes their classes derive from, followed alike; whether one of those
        classes, or of their bases, derives from a class the workspace does not define;
        and the files of those base classes (what a file includes is of its package: the
        node's code is of its sources' packages and theirs). In a base class's files only
        that class's bases are followed: the other classes there (a QoS helper beside
        nav2's LifecycleNode) are not the node's."""
        index = self._index
        excluded = self._excluded
        # path -> the classes of it whose bases are followed; None: all of them
        files: dict[str, set[str] | None] = dict.fromkeys(sources)
        pending: list[tuple[str, set[str] | None]] = [(path, None) for path in sources]
        unknown = False
        defining: set[str] = set()  # the files of the base classes followed

        def add(path: str, classes: set[str] | None) -> None:
            # Known first: a node's code is reached again and again (a million times for
            # 4,600 nodes at 8 copies of the benchmark's workspace), and what is known
            # was not excluded (or is a source, whose bases are all followed already).
            known = files.get(path, _UNKNOWN)
            if known is _UNKNOWN:
                if excluded(path):
                    return
            elif known is None or (classes is not None and classes <= known):
                return
            elif classes is not None:
                classes = classes | known
            files[path] = classes
            pending.append((path, classes))

        while pending:
            path, classes = pending.pop()
            facts = index.facts[path]
            if classes is None:
                for found in self._reached(path):
                    if files.get(found, _UNKNOWN) is not None:  # else followed whole
                        add(found, None)
            else:
                nested: set[str] = set()
                for found in self._reached(path):
                    if found not in files:  # else ``nested`` adds nothing to it
                        add(found, nested)
            for name, bases in facts.class_bases:
                if classes is not None and name not in classes:
                    continue
                for base in bases:
                    defined = self._defined(base, path)
                    if defined is None:
                        unknown = unknown or not _harmless(base)
                        continue
                    base_name = _class_name(base)
                    defining.update(defined)
                    for found in defined:
                        add(found, {base_name})
        return list(files), unknown, defining

    def _reached(self, path: str) -> list[str]:
        """The headers ``path`` includes of its package, each followed by the files that
        implement it; once per file, however many nodes' code holds it."""
        kept = self._reached_memo.get(path)
        if kept is None:
            found = [
                reached
                for include in self._index.facts[path].cpp_includes
                for header in self._included(include, path)
                for reached in (header, *self._implementations(header))
            ]
            kept = self._reached_memo[path] = (found, self._memory.read((path,)))
        reached_files: list[str] = kept[0]
        return reached_files

    def _included(self, include: str, includer: str) -> list[str]:
        """The files of the includer's package an ``#include`` may mean: ``include``
        beside the includer, or below any directory of the package."""
        package = self._index.package_of(includer)
        if package is None:
            return []
        candidates = self._by_name.get((package.directory, posixpath.basename(include)))
        if not candidates:
            return []  # most includes: another package's header, or the library's
        directory = posixpath.dirname(includer)
        key = (include, directory)
        found = self._included_memo.get(key)
        if found is None:
            beside = posixpath.normpath(posixpath.join(directory, include))
            suffix = f"/{include}"
            found = [
                path
                for path in candidates
                if (path == beside or path.endswith(suffix)) and self._holds(path)
            ]
            self._included_memo[key] = found
        return found

    def _implementations(self, header: str) -> list[str]:
        """The translation units of the header's package named after it
        (``controller_server.hpp`` -> ``controller_server.cpp``)."""
        if header.lower().endswith(TRANSLATION_UNITS):
            return []  # an included source is its own implementation
        found = self._implementations_memo.get(header)
        if found is None:
            directory = package_directory(self._index, header)
            stem = posixpath.basename(header).rpartition(".")[0]
            found = self._implementations_memo[header] = [
                path
                for extension in TRANSLATION_UNITS
                for path in self._by_name.get((directory, stem + extension), [])
                if self._holds(path)
            ]
        return found

    def _holds(self, path: str) -> bool:
        """Whether ``path``, which the tables name, is a file of the run. A patch's tables
        are those of the build it patches, with the code files it adds or removes; a
        file that says nothing (``shifts.says_nothing``: a library source with no ROS
        code) may have gone since without a patch, while the last run's findings stood,
        and the tables still name it (moveit2's ``message_checks.cpp`` moved: the next
        patch that gathered parameters stopped on it with a ``KeyError``). It says
        nothing, so a build of the files as they are, which does not have it, gathers
        the same parameters without it."""
        return path in self._index.facts

    def _package_declarations(self, package: str) -> tuple[set[str], set[str]]:
        """The names (and ends of names) the package's code declares, tests aside."""
        kept = self._package_memo.get(package)
        if kept is None:
            names = _Names()
            for path in self._index.files_of(package):
                facts = self._index.facts[path]
                if facts.language in CODE_LANGUAGES and not self._excluded(path):
                    names.add_declarations(facts)
            found = (names.declared, names.declared_suffixes)
            kept = self._package_memo[package] = (found, self._memory.read(packages=(package,)))
        declarations: tuple[set[str], set[str]] = kept[0]
        return declarations

    def _defined(self, base: str, user: str) -> list[str] | None:
        """The files defining a base class that ``user`` derives from (none for a client
        library's), None when the workspace does not define it. Where packages define
        classes of one name, those of the user's package, else of the packages it
        depends on, are the ones meant: a class name is no workspace-wide key."""
        if base in _ROOT_BASES:
            return []
        name = _class_name(base)
        defined = self._classes.get(name)
        if not defined:
            return [] if base in _UNQUALIFIED_ROOTS else None
        if len(defined) == 1:
            return defined
        package = self._index.package_of(user)
        key = (name, "" if package is None else package.directory)
        found = self._defined_memo.get(key)
        if found is None:
            found = self._defined_memo[key] = _nearest(self._index, defined, package)
        return found


class _Names:
    """The names a node's code files declare and read, gathered file by file."""

    def __init__(self) -> None:
        self.declared: set[str] = set()
        self.read: set[str] = set()
        self.declared_suffixes: set[str] = set()
        self.read_suffixes: set[str] = set()
        self.read_prefixes: set[str] = set()
        self.literals: set[str] = set()
        self.constants: set[str] = set()
        self.filter_chain = False  # ``NodeParameters.filter_chain``

    def _sets(self) -> tuple[set[str], ...]:
        return (
            self.declared,
            self.read,
            self.declared_suffixes,
            self.read_suffixes,
            self.read_prefixes,
            self.literals,
            self.constants,
        )

    @property
    def empty(self) -> bool:
        return not self.filter_chain and not any(self._sets())

    def join(self, other: _Names) -> None:
        """Add what ``other`` gathered. Each set by name, not through ``_sets``: called
        96,000 times a build at 8 copies of the benchmark's workspace, where two tuples and
        a zip each time cost a tenth of the names' part."""
        self.declared |= other.declared
        self.read |= other.read
        self.declared_suffixes |= other.declared_suffixes
        self.read_suffixes |= other.read_suffixes
        self.read_prefixes |= other.read_prefixes
        self.literals |= other.literals
        self.constants |= other.constants
        self.filter_chain = self.filter_chain or other.filter_chain

    def add_declarations(self, facts: FileFacts) -> None:
        for use in _parameter_uses(facts):
            if use.access is ParameterAccess.DECLARE and not use.dynamic:
                self.declared.add(use.value)
            elif use.access is ParameterAccess.DECLARE and use.suffix:
                self.declared_suffixes.add(use.suffix)

    def add(self, facts: FileFacts, causes: set[Incomplete]) -> None:
        for use in _parameter_uses(facts):
            access = use.access
            if use.api in _SEARCHES and use.dynamic:
                causes.add(Incomplete.SEARCH)
            if access is ParameterAccess.READ_PREFIX:
                if use.dynamic:
                    causes.add(Incomplete.RUN_TIME_READ)
                else:
                    self.read_prefixes.add(use.value)
                continue
            if access in DECLARATIONS:
                names, suffixes, cause = (
                    self.declared,
                    self.declared_suffixes,
                    Incomplete.RUN_TIME_DECLARATION,
                )
            elif access in READS:
                names, suffixes, cause = self.read, self.read_suffixes, Incomplete.RUN_TIME_READ
            else:
                continue
            if not use.dynamic:
                names.add(use.value)
            elif use.suffix:
                suffixes.add(use.suffix)
            elif access in DECLARATIONS and _constant(use.symbol):
                self.constants.add(use.symbol or "")
            else:
                causes.add(cause)


# ROS 1 searches: the name found (in the node's namespace or any above it) is read next,
# by whatever key the search returns. A search for a static name reads that name at some
# level, which the ROS 1 comparison (namespaces aside) counts as a read of it; a search for
# a name built at run time may read anything.
_SEARCHES = frozenset({"ros::NodeHandle::searchParam", "ros::param::search", "rospy.search_param"})


def _code_declarations(facts: FileFacts) -> tuple[frozenset[str], ...] | None:
    """What a file adds to ``WorkspaceDeclarations``: None for a file of no code."""
    return file_declarations(facts) if facts.language in CODE_LANGUAGES else None


def file_declarations(facts: FileFacts) -> tuple[frozenset[str], ...]:
    """What one code file adds to ``WorkspaceDeclarations``: names, suffixes, mentions.
    Frozen: a memory keeps one for every code file, and most are the one empty set."""
    names: set[str] = set()
    suffixes: set[str] = set()
    mentioned: set[str] = set(facts.unexplained_literals)
    if facts.generation is not Generation.ROS2:
        mentioned.update(
            _bare(name)
            for name in (
                *facts.unexplained_literals,
                *(
                    use.value
                    for use in _parameter_uses(facts)
                    if use.access in READS and not use.dynamic
                ),
            )
        )
        return frozenset(names), frozenset(suffixes), frozenset(mentioned)
    for use in _parameter_uses(facts):
        if use.access is not ParameterAccess.DECLARE:
            continue
        if not use.dynamic:
            names.add(use.value)
        elif use.suffix:
            suffixes.add(use.suffix)
    return frozenset(names), frozenset(suffixes), frozenset(mentioned)


def _nearest(index: WorkspaceIndex, paths: list[str], package: Package | None) -> list[str]:
    """Of ``paths``, those in ``package``, else in the packages it depends on, else all.

    Where packages of one name are several (a ROS 1 and a ROS 2 checkout of geometry2, a
    fork beside its upstream: colcon and catkin refuse to build such a workspace, yet its
    files are linted), the copies of the package's own generation nearest to it in the
    tree are the ones meant; copies alike in both are all kept."""
    if package is None:
        return paths
    owners = [(path, index.package_of(path)) for path in paths]
    own = [path for path, owner in owners if owner == package]
    if own:
        return own
    depended = [
        (path, owner)
        for path, owner in owners
        if owner is not None and owner.name in package.depends
    ]
    if not depended:
        return paths
    closeness = {owner.directory: _closeness(owner, package) for _, owner in depended}
    best: dict[str, tuple[bool, int]] = {}
    for _, owner in depended:
        best[owner.name] = max(best.get(owner.name, (False, -1)), closeness[owner.directory])
    return [path for path, owner in depended if closeness[owner.directory] == best[owner.name]]


def _closeness(owner: Package, user: Package) -> tuple[bool, int]:
    """How near a package is to the package using it: whether it can be of the user's
    generation, then how many directories their paths share."""
    generations = {owner.generation, user.generation}
    shared = 0
    for one, other in zip(owner.directory.split("/"), user.directory.split("/"), strict=False):
        if one != other:
            break
        shared += 1
    return None in generations or len(generations) == 1, shared


def package_directory(index: WorkspaceIndex, path: str) -> str:
    """The directory of the package holding ``path``; the file's own outside packages."""
    package = index.package_of(path)
    return posixpath.dirname(path) if package is None else package.directory


def _within(directory: str, outer: str) -> bool:
    return not outer or directory == outer or directory.startswith(f"{outer}/")


def _class_name(written: str) -> str:
    """A class name as written (``nav2_amcl::MotionModel``, ``rclpy.node.Node``), without
    its namespaces."""
    return written.replace(".", "::").rpartition("::")[2]


def _bare(name: str) -> str:
    """A ROS 1 name without its private '~' and its slashes at either end."""
    return name.lstrip("~").strip("/")


def _constant(symbol: str | None) -> bool:
    """A name the file does not declare, spelled as a constant is (``kTopic``,
    ``Constants::DISABLE_HEARTBEAT_TIMEOUT_PARAM``): not a loop's variable."""
    last = (symbol or "").rpartition("::")[2]
    return bool(re.fullmatch(r"[A-Z][A-Z0-9_]*|k[A-Z]\w*", last))


# Words a constant's name adds to what it holds.
_CONSTANT_WORDS = frozenset({"k", "param", "params", "parameter", "parameters", "name", "key"})


def _words(name: str) -> frozenset[str]:
    """The lowercase words of an identifier or a parameter name: ``kMaxVelX``,
    ``MAX_VEL_X`` and ``max_vel.x`` all give ``max``, ``vel``, ``x``."""
    spaced = re.sub(r"([a-z0-9])([A-Z])", r"\1 \2", name)
    words = re.split(r"[^A-Za-z0-9]+", spaced.lower())
    return frozenset(word for word in words if word and word not in _CONSTANT_WORDS)


class _Reached(Enum):
    NOT_YET = 0  # a file ``_own_code`` has not reached


_UNKNOWN = _Reached.NOT_YET


def _parameter_uses(facts: FileFacts) -> Iterable[NameUse]:
    return (
        use
        for use in facts.names
        if use.kind is Kind.PARAMETER and use.role is Role.PARAMETER and use.access is not None
    )


def _package_name(index: WorkspaceIndex, path: str) -> str | None:
    package = index.package_of(path)
    return None if package is None else package.name


def _starts_runtime(index: WorkspaceIndex, path: str) -> bool:
    """A file that initialises the client library is a program's main: ``rclcpp::init``,
    ``rclpy.init``, ``ros::init``, ``rospy.init_node``."""
    return any(event.kind is EventKind.INIT for event in index.facts[path].events)


# Bases from libraries that hold no ROS node: a class deriving from one declares nothing
# (a behaviour tree node of BehaviorTree.CPP, an rviz panel, a Qt widget...).
_HARMLESS_BASES = re.compile(
    r"(?:::)?(?:std|boost|Eigen|testing|Ogre|pybind11|BT|rviz_common)(?:::|\.)"
    r"|rclcpp::(?!Node$)"  # a QoS profile, an executor: rclcpp's classes besides the node
    r"|Q[A-Z]\w*$"  # Qt
    r"|(?:object|Exception|Enum|IntEnum|Thread|threading\.Thread|unittest\.TestCase)$"
    r"|\w*(?:Error|Exception)$"
)


def has_endpoints(facts: FileFacts) -> bool:
    """Whether a file declares endpoints: a program of code no launch file starts is one
    that does (``build._programs``), and an edit that flips it makes its package's
    programs again (``patch.edits_of``)."""
    return any(use.role in ENDPOINT_ROLES for use in facts.names)


def _harmless(base: str) -> bool:
    return bool(_HARMLESS_BASES.match(base))

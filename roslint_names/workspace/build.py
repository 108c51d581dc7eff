"""Build the graph: launched nodes and code no launch file starts, their names resolved.

Every endpoint the code of a node declares is resolved in the node's namespace, with its
node name for private names, by the rules of its generation (``names.resolve``), then
renamed by the node's remaps. Each file's facts are visited a bounded number of times
(once per node instance that runs it), and resources are grouped by resolved name, never
compared pairwise, so building costs about the sum of the extractions.
"""

from __future__ import annotations

import operator
import posixpath
import re
from bisect import bisect_left
from collections.abc import Callable, Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass
from itertools import pairwise
from typing import Any, Generic, TypeVar

from roslint_names.model import (
    ENDPOINT_ROLES,
    FileFacts,
    Generation,
    Kind,
    Language,
    NameUse,
    ParameterBlock,
    Role,
    replaced,
)
from roslint_names.names import NameResolutionError, resolve
from roslint_names.test_code import is_test_directory
from roslint_names.types import parse_type
from roslint_names.workspace.built import BUILD_FIELDS, unbuilt_sources
from roslint_names.workspace.graph import (
    EdgeKind,
    Endpoint,
    Graph,
    Location,
    NodeInstance,
    NodeRemap,
    ParameterFileUse,
    ParameterSetting,
    Reach,
    UnnamedReceiver,
)
from roslint_names.workspace.index import CODE_LANGUAGES, Package, WorkspaceIndex
from roslint_names.workspace.launch_parts import (
    CodeParameterParts,
    LaunchParts,
    Programs,
    TreePart,
    Unnamed,
)
from roslint_names.workspace.launch_tree import Launched, LaunchTrees, Prepare, Specialise
from roslint_names.workspace.memory import Field, GraphMemory, Reads
from roslint_names.workspace.parameter_files import ros1_names, ros2_names
from roslint_names.workspace.parameter_settings import (
    file_settings,
    group_settings,
    launch_settings,
    ordered,
)
from roslint_names.workspace.parameters import (
    NodeParameters,
    ParameterSets,
    ParameterTables,
    has_endpoints,
)

_EDGES = {
    Role.PUBLISH: EdgeKind.PUBLISH,
    Role.SUBSCRIBE: EdgeKind.SUBSCRIBE,
    Role.SERVE: EdgeKind.SERVE,
    Role.CALL: EdgeKind.CALL,
    Role.ACTION_SERVE: EdgeKind.ACTION_SERVE,
    Role.ACTION_CALL: EdgeKind.ACTION_CALL,
}
_RESOURCE_KINDS = frozenset({Kind.TOPIC, Kind.SERVICE, Kind.ACTION})
# Names a node's code uses that a remap can rename: graph resources and, in ROS 1, params
# (roscpp's ``names::resolve`` remaps every name it resolves, ``NodeHandle::getParam``'s
# key too). rcl remaps topic and service names and the node's name and namespace only
# (``rcl_remap_topic_name``, ``rcl_remap_service_name``, ``rcl_remap_node_name``,
# ``rcl_remap_node_namespace`` in ``rcl/src/rcl/remap.c``): a ROS 2 parameter is no name a
# remap can rename, and one built at run time hides none of them.
_REMAPPABLE_KINDS = {
    Generation.ROS1: frozenset({Kind.TOPIC, Kind.SERVICE, Kind.ACTION, Kind.PARAMETER}),
    Generation.ROS2: frozenset({Kind.TOPIC, Kind.SERVICE, Kind.ACTION}),
}
_REMAPPABLE_ROLES = ENDPOINT_ROLES | {Role.PARAMETER}
_TEST_DIRECTORIES = frozenset({"test", "tests", "testing"})


@dataclass(frozen=True)
class _Instance:
    """What resolution needs to know about one running node."""

    name: str  # base name
    namespace: str  # fully qualified
    generation: Generation


def build(
    facts: Iterable[FileFacts],
    packages: Sequence[Package],
    specialise: Specialise,
    prepare: Prepare | None = None,
    memory: GraphMemory | None = None,
) -> Graph:
    """The workspace graph; ``prepare`` is told each depth's specialisations first.
    ``memory``: what the last build of this workspace left (``memory.GraphMemory``): the
    pieces nothing changed under are taken from it, and this build's are left in it."""
    return _build(facts, packages, specialise, prepare, memory)[0]


def build_parts(
    facts: Iterable[FileFacts],
    packages: Sequence[Package],
    specialise: Specialise,
    prepare: Prepare | None = None,
) -> tuple[Graph, LaunchParts, CodeParameterParts]:
    """``build``'s graph, each launch tree's part of it and what its nodes' parameters
    were gathered from (``launch_parts``): what the CLI keeps for a launch or parameter
    patch. The language server, which keeps a memory instead, builds without them."""
    graph, parts = _build(facts, packages, specialise, prepare, None)
    launch, code = parts()
    return graph, launch, code


def _build(
    facts: Iterable[FileFacts],
    packages: Sequence[Package],
    specialise: Specialise,
    prepare: Prepare | None,
    memory: GraphMemory | None,
) -> tuple[Graph, Callable[[], tuple[LaunchParts, CodeParameterParts]]]:
    memory = GraphMemory(keeps=False) if memory is None else memory
    index = memory.begin({f.path: f for f in facts}, packages)
    tests = _TestFiles(index, memory.piece("test files", (), dict))
    nodes: list[NodeInstance] = []
    endpoints: list[Endpoint] = []
    # Code no build file compiles never runs: it joins no node (``built``).
    unbuilt = memory.piece("unbuilt", BUILD_FIELDS, lambda: unbuilt_sources(index))
    launched_sources: set[str] = set(unbuilt)
    trees = LaunchTrees(index, specialise, prepare, memory)
    # Keyed by the tree and the node's place in it, not by the launched node: hashing
    # one hashes all it holds. A tree walked again starts nodes that are new objects.
    started = memory.reads("launched")
    # What each tree's nodes gave the last build, by root (``_TreeLaunches``)
    by_tree: dict[str, _TreeLaunches] = memory.piece("tree launches", _TREE_FIELDS, dict)
    # Each tree's code and parameter files handed to nodes of unknown name
    tree_sources: dict[str, set[str]] = {}
    tree_unnamed: dict[str, list[Unnamed]] = {}
    tree_started: dict[str, set[tuple[str, str]]] = {}
    for root, launched_nodes in trees.launched_by_root():
        made = by_tree.get(root)
        if made is None or not made.stands(launched_nodes, unbuilt, started):
            made = by_tree[root] = _TreeLaunches.of(
                root,
                launched_nodes,
                unbuilt=unbuilt,
                started=started,
                instance_of=lambda launched, sources: _launched_instance(
                    index, tests, launched, sources, trees
                ),
                sources_of=lambda launched: launched_sources_of(index, launched, unbuilt),
            )
        if made.places:
            launched_sources.update(made.sources)
            tree_sources[root] = set(made.sources)
            tree_started[root] = set(made.started)
            nodes.extend(made.nodes)
            endpoints.extend(made.endpoints)
            tree_unnamed[root] = list(made.unnamed)
    for gone in by_tree.keys() - trees.roots():
        del by_tree[gone]  # a root no more: what it held goes with it
    unlaunched = memory.reads("unlaunched")
    programs = memory.piece(
        "programs", _PROGRAM_FIELDS, lambda: _programs(index, tests, _code_files(index))
    )
    flipped = [
        path for path, old, new in memory.edits() if has_endpoints(old) != has_endpoints(new)
    ]
    if flipped:  # the last build's programs, but for code that started or stopped declaring
        programs = programs.anew(
            executables=index.executables(),
            facts=index.facts,
            flipped=flipped,
            is_test=tests,
            language_of=lambda path: index.facts[path].language,
        )
        memory.replace_piece("programs", programs)
    for sources in programs.unlaunched(launched_sources):
        if sources not in unlaunched:
            unlaunched[sources] = (_unlaunched_instance(index, sources), Reads(sources))
        node, found_endpoints = unlaunched[sources][0]
        nodes.append(node)
        endpoints.extend(found_endpoints)
    # parameter file -> the code (and generation) of each node of unknown name it is
    # handed to
    unnamed = receivers_by_file(pair for pairs in tree_unnamed.values() for pair in pairs)
    rooted_loads = _group_loads(index, trees)
    loads = [use for _, use in rooted_loads]
    blocks = {path: index.facts[path].parameter_blocks for path in linked_files(nodes, loads)}
    tables = memory.piece(
        "parameter tables",
        ParameterTables.FIELDS,
        lambda: ParameterTables.of(index, lambda path: path in unbuilt or tests(path)),
    )
    classes = [
        (path, old, new)
        for path, old, new in memory.edits()
        if (old.class_bases, old.plugin_loaders) != (new.class_bases, new.plugin_loaders)
    ]
    if classes:  # the last build's tables, but for the edited files' classes
        tables, reached = tables.with_classes(classes)
        memory.replace_piece("parameter tables", tables)
        memory.forget(reached)
    parameters = ParameterSets(index, tables, memory)
    finished = _Finished(memory.piece("finished nodes", (), dict))
    nodes = [
        finished(
            node,
            parameters.of(node.sources),
            _with_group_loads(node, rooted_loads, blocks),
        )
        for node in nodes
    ]
    finished.forget_the_rest()

    def parts() -> tuple[LaunchParts, CodeParameterParts]:
        tree_loads: dict[str, list[ParameterFileUse]] = {}
        for root, use in rooted_loads:
            tree_loads.setdefault(root, []).append(use)
        code = sorted(
            {node.sources for node in nodes}
            | {sources for receivers in unnamed.values() for _, sources in receivers}
        )
        assert parameters.counts is not None  # the graph's declarations were made
        launch = LaunchParts(
            tuple(trees.roots()),
            {
                root: TreePart(
                    trees.visited(root),
                    tuple(sorted(tree_sources.get(root, ()))),
                    tuple(tree_unnamed.get(root, ())),
                    tuple(tree_loads.get(root, ())),
                    tuple(sorted(tree_started.get(root, ()))),
                )
                for root in trees.roots()
            },
            trees.includers(),
            frozenset(unbuilt),
            index.executables(),
            programs,
            {sources: parameters.of(sources) for sources in code},
        )
        spans = {sources: parameters.spans.get(sources, frozenset()) for sources in code}
        return launch, CodeParameterParts(parameters.lookups, spans, parameters.counts)

    graph = Graph(
        _sorting(memory, "sorted nodes", NodeInstance.sort_key)(nodes),
        _sorting(memory, "sorted endpoints", Endpoint.sort_key)(endpoints),
        index.companions(),
        mentions(index, nodes),
        index.service_definitions(),
        blocks,
        tuple(sorted(set(loads))),
        unnamed_receivers(unnamed, parameters.of),
        parameter_declarations=parameters.declarations(),
    )
    return graph, parts


_T = TypeVar("_T")
_NO_KEY = object()


def _sorting(
    memory: GraphMemory, name: str, key: Callable[[_T], Any]
) -> Callable[[Iterable[_T]], tuple[_T, ...]]:
    """``_unique`` by ``key``, through the memory's ``_Sorting`` where it keeps pieces for
    a next build."""
    if not memory.keeps:
        return lambda items: _unique(items, key)
    sorting: _Sorting[_T] = memory.piece(name, (), lambda: _Sorting(key))
    return sorting


def _unique(items: Iterable[_T], key: Callable[[_T], Any]) -> tuple[_T, ...]:
    """``items`` sorted by ``key``, each once. Equal items have equal keys: only the
    items of one key are compared, and none is hashed (hashing a node hashes all it
    holds, 17,000 nodes a build). Items of one key but not equal keep their order."""
    return _Sorted.of(list(items), key).items


@dataclass(frozen=True)
class _Sorted(Generic[_T]):
    """What ``_unique`` makes of a list: the items sorted and each once, with their keys;
    and the keys that more than one item of the list has (those only are compared)."""

    items: tuple[_T, ...]
    keys: list[Any]
    shared: set[Any]

    @classmethod
    def of(cls, listed: list[_T], key: Callable[[_T], Any]) -> _Sorted[_T]:
        found: list[_T] = []
        found_keys: list[Any] = []
        shared: set[Any] = set()
        run: list[_T] = []  # the items found of the current key
        last: object = _NO_KEY
        # Each key made once; a tie goes to the order of arrival, never to the items.
        keyed = sorted((key(item), position) for position, item in enumerate(listed))
        for current, position in keyed:
            item = listed[position]
            if current != last:
                run = []
                last = current
            else:
                shared.add(current)
            if item not in run:
                run.append(item)
                found.append(item)
                found_keys.append(current)
        return cls(tuple(found), found_keys, shared)


class _Sorting(Generic[_T]):
    """``_unique`` of one list of each build (its nodes, its endpoints), taken from the
    last build's where few items are new: a launch file's edit makes its trees' nodes
    again, and sorting 17,000 nodes and 13,000 endpoints anew cost 0.13 s of the
    language server's 1 s after it. The result is ``_unique``'s: where an item new or
    gone shares its key with another item, or the items kept came in another order
    (which orders the items of one key), the list is sorted anew."""

    def __init__(self, key: Callable[[_T], Any]) -> None:
        self._key = key
        self._listed: list[_T] = []  # the last list: holding it keeps its items' ids theirs
        self._positions: dict[int, int] = {}  # id of an item of it -> where
        self._sorted: _Sorted[_T] | None = None

    def __call__(self, items: Iterable[_T]) -> tuple[_T, ...]:
        listed = list(items)
        found = self._updated(listed) or _Sorted.of(listed, self._key)
        self._listed, self._sorted = listed, found
        self._positions = {id(item): position for position, item in enumerate(listed)}
        return found.items

    def _updated(self, listed: list[_T]) -> _Sorted[_T] | None:
        last = self._sorted
        if last is None:
            return None
        added: list[_T] = []
        kept: set[int] = set()
        previous = -1
        for item in listed:
            position = self._positions.get(id(item), -1)
            if position < 0:
                added.append(item)
            elif position <= previous:
                return None  # the kept items in another order
            else:
                kept.add(position)
                previous = position
        gone = {id(item) for position, item in enumerate(self._listed) if position not in kept}
        if len(added) + len(gone) > len(listed) // 8:
            return None
        items, keys = [], []
        for item, key in zip(last.items, last.keys, strict=True):
            if id(item) in gone:
                if key in last.shared:
                    return None  # an item of its key may have been left out for it
            else:
                items.append(item)
                keys.append(key)
        fresh = sorted((self._key(item), index) for index, item in enumerate(added))
        if any(one == other for (one, _), (other, _) in pairwise(fresh)):
            return None  # two new items of one key
        for key, index in fresh:
            at = bisect_left(keys, key)
            if at < len(keys) and keys[at] == key:
                return None
            items.insert(at, added[index])
            keys.insert(at, key)
        return _Sorted(tuple(items), keys, last.shared)


@dataclass(frozen=True, eq=False)
class _TreeLaunches:
    """What one tree's nodes gave a build: their places (root, then the node's place in
    the tree) and the instances made for them (``memory.reads("launched")``'s entries),
    the code they run, the programs they name, and their nodes, endpoints and parameter
    files handed to nodes of unknown name. A build whose tree starts the same nodes
    (the walk's tuple, kept while the memory keeps the tree), whose code no build file
    compiles is the same, and whose instances are those kept takes them up as they are:
    asking each of 15,000 launched nodes again what code it runs was a tenth of a
    language server's graph refresh at 8 copies of the benchmark's workspace."""

    launched: tuple[Launched, ...]
    unbuilt: frozenset[str]
    places: tuple[tuple[str, int], ...]
    kept: tuple[object, ...]  # the instances' entries, by place
    sources: frozenset[str]
    started: frozenset[tuple[str, str]]
    nodes: tuple[NodeInstance, ...]
    endpoints: tuple[Endpoint, ...]
    unnamed: tuple[Unnamed, ...]

    def stands(
        self,
        launched: tuple[Launched, ...],
        unbuilt: frozenset[str],
        started: Mapping[tuple[str, int], object],
    ) -> bool:
        return (
            launched is self.launched
            and unbuilt is self.unbuilt
            and all(map(operator.is_, map(started.get, self.places), self.kept))
        )

    @classmethod
    def of(
        cls,
        root: str,
        launched_nodes: tuple[Launched, ...],
        *,
        unbuilt: frozenset[str],
        started: dict[Any, tuple[Any, Reads]],
        instance_of: Callable[[Launched, tuple[str, ...]], tuple[_Started, Reads]],
        sources_of: Callable[[Launched], tuple[str, ...]],
    ) -> _TreeLaunches:
        """The tree's nodes' part, each instance the one kept where it was made of the
        same launched node and code (``started``), else made (``instance_of``)."""
        places = tuple((root, position) for position in range(len(launched_nodes)))
        kept_entries: list[tuple[Any, Reads]] = []
        sources_found: set[str] = set()
        programs: set[tuple[str, str]] = set()
        nodes: list[NodeInstance] = []
        endpoints: list[Endpoint] = []
        unnamed: list[Unnamed] = []
        for place, launched in zip(places, launched_nodes, strict=True):
            sources = sources_of(launched)
            sources_found.update(sources)
            programs.add(started_program(launched))
            kept = started.get(place)
            if kept is None or kept[0][0] is not launched or kept[0][1] != sources:
                instance, read = instance_of(launched, sources)
                kept = started[place] = ((launched, sources, instance), read)
            kept_entries.append(kept)
            instance = kept[0][2]
            if instance.node is not None:
                nodes.append(instance.node)
                endpoints.extend(instance.endpoints)
            unnamed.extend(instance.unnamed)
        return cls(
            launched_nodes,
            unbuilt,
            places,
            tuple(kept_entries),
            frozenset(sources_found),
            frozenset(programs),
            tuple(nodes),
            tuple(endpoints),
            tuple(unnamed),
        )


# What the code a launched node runs is found by (``WorkspaceIndex.sources_of``) besides
# where files are and the code no build file compiles (``_TreeLaunches.stands``)
_TREE_FIELDS: tuple[Field, ...] = ("executables", "language")


@dataclass(frozen=True)
class _Started:
    """What one launched node makes: its instance and endpoints, or (a node of unknown
    name) for each parameter file it is handed, its generation and code."""

    node: NodeInstance | None = None
    endpoints: tuple[Endpoint, ...] = ()
    unnamed: tuple[tuple[str, tuple[Generation, tuple[str, ...]]], ...] = ()


class _Finished:
    """A node with its code's parameters and every parameter its launch sets. The last
    build's node where it is made from the same objects: a memory keeps nodes, their
    parameters and settings while nothing they are made from changes, and a node made
    again is 17,000 copies a build."""

    def __init__(self, known: dict[int, tuple[NodeInstance, NodeInstance]]) -> None:
        # id of a node as built -> (that node, finished): holding the node keeps its id
        # its own while the entry lives.
        self._known = known
        self._used: set[int] = set()

    def __call__(
        self,
        node: NodeInstance,
        parameters: NodeParameters,
        settings: tuple[ParameterSetting, ...],
    ) -> NodeInstance:
        self._used.add(id(node))
        kept = self._known.get(id(node))
        if (
            kept is not None
            and kept[0] is node
            and kept[1].code_parameters is parameters
            and kept[1].parameter_settings == settings
        ):
            return kept[1]
        finished = with_code_parameters(node, parameters, parameter_settings=settings)
        self._known[id(node)] = (node, finished)
        return finished

    def forget_the_rest(self) -> None:
        """Forget the nodes this build did not finish: gone, or built again."""
        for key in [key for key in self._known if key not in self._used]:
            del self._known[key]


def with_code_parameters(
    node: NodeInstance, parameters: NodeParameters, **changes: object
) -> NodeInstance:
    """``node`` with its code's parameters (and ``changes``), and what they say of code
    that runs in it from elsewhere (``NodeInstance.derives_elsewhere``, which the graph
    keeps where it keeps no parameters)."""
    return replaced(
        node,
        code_parameters=parameters,
        derives_elsewhere=parameters.derives_elsewhere,
        **changes,
    )


class _TestFiles:
    """Whether a file is test code (``_is_test``), each file asked once; the answers
    depend on where files are only, and a memory keeps them while nothing moves."""

    def __init__(self, index: WorkspaceIndex, known: dict[str, bool]) -> None:
        self._index = index
        self._known = known

    def __call__(self, path: str) -> bool:
        found = self._known.get(path)
        if found is None:
            found = self._known[path] = _is_test(self._index, path)
        return found


def mentions(
    index: WorkspaceIndex,
    nodes: Iterable[NodeInstance],
    known: Mapping[str, frozenset[str]] | None = None,
) -> dict[str, frozenset[str]]:
    """The string literals of every code file (headers too) of each package whose node
    has remaps of its own; ``known``'s where it has them (``launch_patch``: no code
    changed since the build that made them)."""
    packages = {node.package for node in nodes if node.package and any(r.own for r in node.remaps)}
    known = known or {}
    return {
        package: known[package]
        if package in known
        else package_literals(index.facts[path] for path in index.files_of(package))
        for package in sorted(packages)
    }


def linked_files(nodes: Iterable[NodeInstance], loads: Iterable[ParameterFileUse]) -> list[str]:
    """The parameter files handed to ``nodes`` or loaded by ``loads``, sorted: those whose
    blocks ``Graph.parameter_files`` holds."""
    linked = {use.path for node in nodes for use in node.parameter_files}
    linked.update(use.path for use in loads)
    return sorted(linked)


def receivers_by_file(
    unnamed: Iterable[Unnamed],
) -> dict[str, set[tuple[Generation, tuple[str, ...]]]]:
    """Each parameter file handed to a node of unknown name, with the generation and code
    of each such node (``TreePart.unnamed``'s pairs, of one tree or many), once each."""
    receivers: dict[str, set[tuple[Generation, tuple[str, ...]]]] = {}
    for path, receiver in unnamed:
        receivers.setdefault(path, set()).add(receiver)
    return receivers


def unnamed_receivers(
    unnamed: Mapping[str, Iterable[tuple[Generation, tuple[str, ...]]]],
    parameters_of: Callable[[tuple[str, ...]], NodeParameters],
) -> dict[str, tuple[UnnamedReceiver, ...]]:
    """``Graph.unnamed_parameter_files``: for each parameter file (``unnamed``) the
    generation and code of each node of unknown name it is handed to, with that code's
    parameters."""
    return {
        path: tuple(
            UnnamedReceiver(generation, parameters_of(sources))
            for generation, sources in sorted(set(receivers))
        )
        for path, receivers in sorted(unnamed.items())
    }


def package_literals(code: Iterable[FileFacts]) -> frozenset[str]:
    """The literals of a package's files, as ``Graph.mentions`` keeps them (``mentions``,
    and ``patch`` for an edited package)."""
    return frozenset(literal for facts in code for literal in facts.literals)


# ---------------------------------------------------------------------------------------
# Instances


def launched_sources_of(
    index: WorkspaceIndex, launched: Launched, unbuilt: Collection[str]
) -> tuple[str, ...]:
    """The code a launched node runs: its executable's sources that some build compiles
    (code no build file compiles never runs: ``built``)."""
    found = index.sources_of(launched.node.package, launched.node.executable)
    return tuple(path for path in found if path not in unbuilt)


def started_program(launched: Launched) -> tuple[str, str]:
    """The package and executable (or component plugin) a launched node names
    (``TreePart.started``), "" for either where it names none."""
    return (launched.node.package or "", launched.node.executable or "")


def _code(index: WorkspaceIndex, sources: Iterable[str]) -> list[FileFacts]:
    return [index.facts[path] for path in sources]


def _launched_instance(
    index: WorkspaceIndex,
    tests: _TestFiles,
    launched: Launched,
    sources: tuple[str, ...],
    trees: LaunchTrees,
) -> tuple[_Started, Reads]:
    """The node a launch tree starts, and the files it is made from."""
    read = {*sources, launched.path}
    code = _code(index, sources)
    launch_facts = index.facts.get(launched.path)
    generation = _generation(code, launch_facts)
    name = None if launched.node.dynamic_name else launched.node.name or _code_node_name(code)
    if name is None:  # the launch file names it, but not statically, or its code does not
        receiver = (generation, sources)
        unnamed = []
        for load in launched.node.parameter_files:
            path = _parameter_file(index, trees, launched.path, load.package, load.path, read=read)
            if path is not None:
                unnamed.append((path, receiver))
        return _Started(unnamed=tuple(unnamed)), Reads(tuple(read))
    instance = _Instance(name, launched.namespace, generation)
    full_name = _full_name(instance)
    packages = {launched.node.package} | {
        _package_name(index, path) for path in (launched.root, *(s.path for s in launched.sites))
    }
    reach = Reach(
        generation,
        _is_test_launch(tests, launched.root),
        tuple(sorted(p for p in packages if p)),
    )
    remaps = [
        NodeRemap(
            _resolve_quietly(remap.source, instance) or remap.source,
            _resolve_quietly(remap.target, instance) or remap.target,
            remap.span,
            remap.target_span,
            path=path,
            own=own,
            written_target=remap.target,
        )
        for remap, path, own in launched.remaps
    ]
    names = _resolve_code(code, instance, remaps, launched.root, reach)
    composable = "::" in (launched.node.executable or "")  # a component's plugin class
    files, file_set = _parameter_files(
        index, trees, launched, full_name, read, generation=generation, composable=composable
    )
    settings = launch_settings(
        launched.node, launched.path, full_name, generation, launched.conditional
    )
    node = NodeInstance(
        name=full_name,
        generation=generation,
        package=launched.node.package,
        executable=launched.node.executable,
        root=launched.root,
        launched_at=launched.sites,
        sources=sources,
        remaps=tuple(remaps),
        launch_namespaces=launched.site_namespaces,
        uses=names.uses,
        uses_complete=names.complete and bool(sources),
        uses_relative=names.relative,
        parameters=names.parameters,
        conditional=launched.conditional,
        named_at_launch=launched.node.name is not None,
        test=launched.node.test,
        stand_in=not reach.isolated and _all_test_code(index, tests, sources),
        reach=reach,
        parameter_files=files,
        composable=composable,
        parameter_settings=ordered([*settings, *file_set]),
    )
    return _Started(node, tuple(names.endpoints)), Reads(tuple(read))


def _parameter_file(
    index: WorkspaceIndex,
    trees: LaunchTrees,
    path: str,
    package: str | None,
    relative: str | None,
    *,
    read: set[str] | None = None,
) -> str | None:
    """The parameter file of the workspace a launch file names, if it holds one; the
    file found joins ``read``."""
    found = trees.located(path, package, relative)
    if found is not None and read is not None:
        read.add(found)
    facts = None if found is None else index.facts.get(found)
    return found if facts is not None and facts.language is Language.PARAMETERS else None


def _parameter_files(
    index: WorkspaceIndex,
    trees: LaunchTrees,
    launched: Launched,
    full_name: str,
    read: set[str],
    *,
    generation: Generation,
    composable: bool,
) -> tuple[tuple[ParameterFileUse, ...], list[ParameterSetting]]:
    """The parameter files the launch hands the node, with the names each sets on it,
    and each of those names with where its file writes it.

    ROS 1 loads a file inside ``<node>`` under the node's private namespace. A composable
    node the launch file names not gets only a file's ``/**`` entry from launch_ros
    (``workspace.parameters``)."""
    found: list[ParameterFileUse] = []
    settings: list[ParameterSetting] = []
    for load in launched.node.parameter_files:
        path = _parameter_file(index, trees, launched.path, load.package, load.path, read=read)
        if path is None:
            continue
        blocks = index.facts[path].parameter_blocks
        site = Location(launched.path, load.span)
        conditional = launched.conditional or load.conditional
        matched = full_name if launched.node.name is not None or not composable else ""
        if generation is Generation.ROS1:
            namespace = (
                load.namespace
                if load.namespace.startswith("/")
                else f"{full_name}/{load.namespace}".rstrip("/")
            )
            names = ros1_names(blocks, namespace)
            use = ParameterFileUse(path, site, namespace, names, conditional)
        else:
            names = ros2_names(blocks, matched, composable=composable)
            use = ParameterFileUse(path, site, "", names, conditional)
        found.append(use)
        settings.extend(
            file_settings(
                blocks,
                use,
                full_name,
                generation=generation,
                matched=matched,
                composable=composable,
            )
        )
    return tuple(found), settings


def _group_loads(index: WorkspaceIndex, trees: LaunchTrees) -> list[tuple[str, ParameterFileUse]]:
    """ROS 1 ``<rosparam load>`` outside nodes, each with the names it sets and the root
    of the launch tree that loads it."""
    found: list[tuple[str, ParameterFileUse]] = []
    for loaded in trees.loaded():
        load = loaded.load
        path = _parameter_file(index, trees, loaded.path, load.package, load.path)
        if path is None:
            continue
        names = ros1_names(index.facts[path].parameter_blocks, loaded.namespace)
        site = Location(loaded.path, load.span)
        use = ParameterFileUse(path, site, loaded.namespace, names, loaded.conditional)
        found.append((loaded.root, use))
    return found


def _with_group_loads(
    node: NodeInstance,
    loads: Sequence[tuple[str, ParameterFileUse]],
    blocks: dict[str, tuple[ParameterBlock, ...]],
) -> tuple[ParameterSetting, ...]:
    """The node's settings and, ROS 1, what its tree's group-level loads put in its
    private namespace."""
    if node.generation is not Generation.ROS1 or not node.root or not loads:
        return node.parameter_settings
    found = group_settings(node.name, node.root, loads, blocks)
    return ordered([*node.parameter_settings, *found])


def _code_files(index: WorkspaceIndex) -> list[str]:
    """The display paths of the index's code files, sorted."""
    return sorted(path for path, facts in index.facts.items() if facts.language in CODE_LANGUAGES)


def _programs(index: WorkspaceIndex, tests: _TestFiles, code: Sequence[str]) -> Programs:
    """What the code no launch file starts is made of (``Programs.unlaunched``), whatever
    is launched. ``code``: the index's code files, sorted (``_code_files``)."""
    built = tuple(sources for _, sources in sorted(index.built_sources().items()))
    built_files = {path for sources in built for path in sources}
    return Programs(
        tuple(tuple(sources) for sources in built),
        frozenset(path for path in built_files if tests(path)),
        frozenset(path for path in built_files if has_endpoints(index.facts[path])),
        tuple(path for path in code if has_endpoints(index.facts[path]) and not tests(path)),
    )


def _unlaunched_instance(
    index: WorkspaceIndex, sources: tuple[str, ...]
) -> tuple[NodeInstance, tuple[Endpoint, ...]]:
    code = _code(index, sources)
    name = _code_node_name(code) or _stem(sources[0])
    instance = _Instance(name, "/", _generation(code, None))
    full_name = _full_name(instance)
    package = index.package_of(sources[0])
    reach = Reach(instance.generation, False, () if package is None else (package.name,))
    names = _resolve_code(code, instance, [], "", reach)
    node = NodeInstance(
        name=full_name,
        generation=instance.generation,
        package=None if package is None else package.name,
        executable=None,
        root="",
        launched_at=(),
        sources=sources,
        uses=names.uses,
        uses_complete=names.complete,
        uses_relative=names.relative,
        parameters=names.parameters,
        reach=reach,
    )
    return node, tuple(names.endpoints)


def _package_name(index: WorkspaceIndex, path: str) -> str | None:
    package = index.package_of(path)
    return None if package is None else package.name


def _code_node_name(code: Sequence[FileFacts]) -> str | None:
    """The one static node name the code gives itself (``ros::init``, ``Node("x")``)."""
    found = {
        use.value
        for facts in code
        for use in facts.names
        if use.role is Role.NODE_NAME and not use.dynamic and use.value
    }
    return found.pop() if len(found) == 1 else None


def _generation(code: Sequence[FileFacts], launch: FileFacts | None) -> Generation:
    generations = {facts.generation for facts in code}
    if len(generations) == 1:
        return generations.pop()
    return launch.generation if launch is not None else Generation.ROS2


def _full_name(instance: _Instance) -> str:
    return f"{instance.namespace.rstrip('/')}/{instance.name}"


def _stem(path: str) -> str:
    return posixpath.basename(path).split(".", 1)[0]


def _is_test(index: WorkspaceIndex, path: str) -> bool:
    """Under a test directory of its package, or in a test package (``nav2_system_tests``,
    ``test_rospy``). Only the package's own directories count: a workspace checked out
    as ``~/test_ws`` or ``/ci/tests/`` is not a test."""
    package = index.package_of(path)
    if package is None:
        return False
    name = posixpath.basename(package.directory)
    return (
        _is_test_package(package.name)
        or _is_test_package(name)
        or any(part in _TEST_DIRECTORIES for part in _folders_inside(package, path))
    )


def _folders_inside(package: Package, path: str) -> list[str]:
    """The folders between the package's directory and the file ``path``."""
    inside = path[len(package.directory) :].lstrip("/") if package.directory else path
    return inside.split("/")[:-1]


def _all_test_code(index: WorkspaceIndex, tests: _TestFiles, sources: Sequence[str]) -> bool:
    """Whether every source is test code or test support code of its package, by the
    folders inside the package (``test_nodes/``, ``testing/``) or the package's name."""
    return bool(sources) and all(_is_test_support(index, tests, path) for path in sources)


def _is_test_support(index: WorkspaceIndex, tests: _TestFiles, path: str) -> bool:
    package = index.package_of(path)
    return package is not None and (
        tests(path) or any(is_test_directory(folder) for folder in _folders_inside(package, path))
    )


def _is_test_package(name: str) -> bool:
    return name.startswith("test_") or name.endswith(("_test", "_tests"))


def _is_test_launch(tests: _TestFiles, path: str) -> bool:
    """rostest's ``.test`` files, launch tests named for pytest (``test_*.py``), and any
    launch file of a test package or under a test directory of its package."""
    name = posixpath.basename(path)
    return name.endswith(".test") or name.startswith("test_") or tests(path)


# What ``_programs`` reads of each file besides where it is: the build's programs and
# which files are code. Which of those declare endpoints too, followed edit by edit
# (``Programs.anew``).
_PROGRAM_FIELDS: tuple[Field, ...] = ("executables", "language")


# ---------------------------------------------------------------------------------------
# Resolution


@dataclass(frozen=True)
class _CodeNames:
    """What a node's code uses: its endpoints after remapping; every remappable name
    before remapping, resolved (``uses``), and as written where its namespace is unknown
    (``relative``); whether those are all known; and, in ROS 2, its static parameter
    names, which no remap renames."""

    endpoints: list[Endpoint]
    uses: tuple[str, ...]
    relative: tuple[str, ...]
    complete: bool
    parameters: tuple[str, ...]


def _resolve_code(
    code: Sequence[FileFacts],
    instance: _Instance,
    remaps: Sequence[NodeRemap],
    root: str,
    reach: Reach,
) -> _CodeNames:
    endpoints: list[Endpoint] = []
    uses: set[str] = set()
    relative: set[str] = set()
    parameters: set[str] = set()
    complete = True
    remappable = _REMAPPABLE_KINDS[instance.generation]
    for facts in code:
        for use in facts.names:
            if use.kind is Kind.PARAMETER and use.kind not in remappable:
                if not use.dynamic:
                    parameters.add(use.value)
                continue
            if use.kind not in remappable or use.role not in _REMAPPABLE_ROLES:
                continue
            resolved, certain = _resolve_use(use, facts.language, instance)
            if resolved is None:
                # An illegal name is still a known one (RN101/RN102 report it): the remap
                # of its spelling is no less used. It joins no endpoint: rcl refuses it.
                spelled = None if use.dynamic else _spelled_out(use.value, instance)
                if spelled is None:
                    complete = False
                else:
                    uses.add(spelled)
                continue
            uses.add(resolved)
            if not certain:
                relative.add(use.value)
            edge = _EDGES.get(use.role)
            if edge is None or use.kind not in _RESOURCE_KINDS:
                continue
            endpoints.append(
                Endpoint(
                    resource=_remapped(resolved, remaps, instance.generation),
                    resource_kind=use.kind,
                    edge=edge,
                    node=_full_name(instance),
                    root=root,
                    type_name=_canonical_type(use.type_name),
                    location=Location(facts.path, use.span),
                    written=use.value,
                    reach=reach,
                    certain=certain,
                )
            )
    return _CodeNames(
        endpoints,
        tuple(sorted(uses)),
        tuple(sorted(relative)),
        complete,
        tuple(sorted(parameters)),
    )


def _resolve_use(use: NameUse, language: Language, instance: _Instance) -> tuple[str | None, bool]:
    """The fully qualified name of a use, and whether it is certain.

    A ROS 1 C++ name goes through a NodeHandle: ``""`` is the node's namespace, ``"~"`` its
    private one, a relative or absolute namespace nests; ``None`` (a handle the file does
    not show, e.g. a constructor parameter) is resolved in the node's namespace, uncertain.
    ROS 2 and Python names resolve against the node itself.
    """
    if use.dynamic:
        return None, False
    namespace = instance.namespace
    certain = True
    if instance.generation is Generation.ROS1 and language is Language.CPP:
        handle = use.namespace
        if handle is None:
            certain = use.value.startswith(("/", "~"))
        elif handle == "~":
            namespace = _full_name(instance)
        elif handle:
            try:
                namespace = resolve(handle, Generation.ROS1, instance.namespace, instance.name)
            except NameResolutionError:
                return None, False
    resolved = _resolve_quietly(use.value, _Instance(instance.name, namespace, instance.generation))
    return resolved, certain and resolved is not None


def _spelled_out(name: str, instance: _Instance) -> str | None:
    """An illegal name resolved by its spelling, as a remap rule would be matched against
    it: ``status/`` in ``/robot`` is ``/robot/status``; None when the spelling leaves
    nothing to match (an empty name, a substitution)."""
    body = re.sub(r"/+", "/", name).rstrip("/")
    if not body or "{" in body:
        return None
    namespace = instance.namespace.rstrip("/")
    if body.startswith("~"):
        return f"{namespace}/{instance.name}/{body[1:].lstrip('/')}".rstrip("/")
    if body.startswith("/"):
        return body
    return f"{namespace}/{body}"


def _resolve_quietly(name: str, instance: _Instance) -> str | None:
    try:
        return resolve(name, instance.generation, instance.namespace, instance.name)
    except NameResolutionError:
        return None


def _remapped(name: str, remaps: Sequence[NodeRemap], generation: Generation) -> str:
    """roscpp keeps the last remap of a name (the node's own come after its group's); rcl
    applies the first matching rule."""
    matching = [remap.target for remap in remaps if remap.source == name]
    if not matching:
        return name
    return matching[-1] if generation is Generation.ROS1 else matching[0]


def _canonical_type(spelling: str | None) -> str | None:
    parsed = None if spelling is None else parse_type(spelling)
    return None if parsed is None else str(parsed)

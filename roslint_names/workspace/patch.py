"""The last graph with the nodes of edited code files resolved again (issue 30).

An edit of a node's code that adds, renames or removes a topic, a service or an action
changes that node's endpoints and nothing else the graph is made of: which nodes run,
where and under which names comes from launch files, build files and manifests; what a
node's code declares as parameters from its parameter uses. Building the whole graph
again for it loads every file's facts (1.5 s at 77,000 files) and walks every launch
tree (3 s); the nodes that run the edited file are the only ones whose endpoints
change, and each is resolved from its code and what the graph keeps of it (its
namespace, name, remaps, launch tree and reach) by the function the build resolves it
with (``build._resolve_code``).

``code_edit`` says whether an edit is of that kind: a file of code, no launch or build
file, whose facts are those it had but for the endpoints its code declares, its
name-shaped literals and the places of the rest (``moves.moved_spans`` of the facts
without those). ``patched`` then gives the graph a build would: the nodes running the
file with their endpoints and names resolved again and their parameter uses where they
are now. A graph it cannot patch exactly (two nodes of one name in one tree running the
edited file, a node whose namespace the graph does not show, a parameter use no fact
places, a file of a package whose literals it keeps without facts) is None: the caller
builds. ``tests/test_graph_patch.py`` compares patched graphs with built ones.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Mapping
from dataclasses import replace
from typing import TypeVar, cast

from roslint_names.model import ENDPOINT_ROLES, FileFacts, Language, Role, Span, replaced
from roslint_names.moves import UnplacedError, moved_spans
from roslint_names.workspace.build import (
    _Instance,
    _resolve_code,
    _unique,
    package_literals,
)
from roslint_names.workspace.graph import Endpoint, Graph, Location, NodeInstance
from roslint_names.workspace.index import CODE_LANGUAGES, PackageFiles
from roslint_names.workspace.launch_parts import LaunchParts, ParameterPart
from roslint_names.workspace.parameters import NodeParameters, ParameterUse, has_endpoints

_T = TypeVar("_T")

# What a file holds that the graph takes from launch files, build files, parameter files
# and dynamic_reconfigure configs: an edit of any of it is built (the launch trees, the
# executables, the parameter settings change).
NOT_CODE_FIELDS = (
    "launch_nodes",
    "includes",
    "executables",
    "compiled",
    "parameter_blocks",
    "parameter_loads",
    "reconfigure",
)

Moved = dict[Span, Span]  # a file's old spans, each where it is now

# Build files: the graph takes from them which programs a package builds of which
# sources, and which sources are compiled (``WorkspaceIndex``, ``built``), none of their
# places.
_BUILD_LANGUAGES = frozenset({Language.CMAKE, Language.SETUP_PY, Language.SETUP_CFG})


def code_edit(before: FileFacts, now: FileFacts) -> Moved | None:
    """Where an edit of a code file moved what the graph keeps of it besides its
    endpoints, when the edit changed nothing else the graph reads: the endpoints its code
    declares and its literals may differ, every other fact only in its place; else None.
    Whether the file starts a node at all may not change (a program of code no launch
    file starts is one that declares endpoints: ``build._unlaunched_programs``)."""
    if before.language not in CODE_LANGUAGES or now.language is not before.language:
        return None
    if any(getattr(facts, field) for facts in (before, now) for field in NOT_CODE_FIELDS):
        return None
    if has_endpoints(before) != has_endpoints(now):
        return None
    return moved_spans(_without_endpoints(before), _without_endpoints(now))


def declaration_edit(before: FileFacts, now: FileFacts) -> Moved | None:
    """``code_edit``'s moves for an edit that may also change the parameters the code
    declares and reads (its parameter uses, the parameter-shaped strings it holds), which
    ``workspace.parameter_patch`` follows; None where something else changed."""
    return code_edit(_without_uses(before), _without_uses(now))


def name_edit(before: FileFacts, now: FileFacts) -> Moved | None:
    """``declaration_edit``'s moves for an edit that may also change the node name the
    code gives itself (``ros::init``, ``Node("x")``): the launch trees that start the file
    and its programs of their own are then made again (``workspace.launch_patch``, its
    ``code``), the rest as for a declaration edit; None where something else changed."""
    return declaration_edit(_without_node_names(before), _without_node_names(now))


def gathering_edit(before: FileFacts, now: FileFacts) -> tuple[Moved, bool] | None:
    """``name_edit``'s moves for an edit that may also change what the parameters of
    its nodes' code are gathered through (``_without_gathering``), which
    ``workspace.parameter_patch`` follows, and whether the node name the code gives
    itself changed too; None where something else changed."""
    bare_before, bare_now = _without_gathering(before), _without_gathering(now)
    moves = declaration_edit(bare_before, bare_now)
    if moves is not None:
        return moves, False
    moves = name_edit(bare_before, bare_now)
    return None if moves is None else (moves, True)


def _without_gathering(facts: FileFacts) -> FileFacts:
    """``facts`` less what decides which code its nodes' parameters are gathered from
    and how (``parameters.ParameterSets``: its classes' bases, what it includes, the
    plugins and configs it loads, what leaves its names open), which the graph reads
    nowhere else (but for the constants a file's names take through includes, which
    ``graph_patch._Constants.anew`` minds)."""
    return replace(
        facts,
        class_bases=(),
        cpp_includes=(),
        parameter_traits=(),
        plugin_loaders=(),
        reconfigure_servers=(),
    )


def _without_node_names(facts: FileFacts) -> FileFacts:
    kept = tuple(use for use in facts.names if use.role is not Role.NODE_NAME)
    return replace(facts, names=kept)


def build_moves(before: FileFacts, now: FileFacts) -> Moved | None:
    """Where an edit of a build file moved its facts, when it changed nothing else (a
    dependency found above its targets): the graph keeps no place of a build file, so
    no node changes; None where the file builds something else now, or is no build
    file."""
    if before.language not in _BUILD_LANGUAGES or now.language is not before.language:
        return None
    return moved_spans(before, now)


def _without_uses(facts: FileFacts) -> FileFacts:
    kept = tuple(use for use in facts.names if use.role is not Role.PARAMETER)
    return replace(facts, names=kept, unexplained_literals=())


def edits_of(
    changed: Iterable[tuple[str, FileFacts, FileFacts]],
    declaring: set[str] | None = None,
    naming: set[str] | None = None,
    flipping: set[str] | None = None,
) -> dict[str, Moved] | None:
    """``patched``'s edits for the files whose facts changed since the graph was made
    (display path, facts then and now): each a ``code_edit``, or the same facts in the same
    places (nothing of the graph to patch) or a build file's moved (``build_moves``);
    None where one is neither. With ``declaring``, a ``gathering_edit`` is one too (a
    ``declaration_edit`` among them), its file added to ``declaring``; one that also
    changed the node name the code gives itself (a ``name_edit``) only with ``naming``,
    the file added to both. With ``flipping``, code that starts or stops declaring
    endpoints is an edit too, its file added to ``flipping``: the caller makes its
    package's programs again (a program of code no launch file starts is one that
    declares endpoints: ``launch_parts.Programs``)."""
    edits: dict[str, Moved] = {}
    for display, facts_then, facts_now in changed:
        then, now = facts_then, facts_now
        if (
            flipping is not None
            and then.language in CODE_LANGUAGES
            and has_endpoints(then) != has_endpoints(now)
        ):
            flipping.add(display)  # compared as code_edit compares, its endpoints aside
            then, now = _without_endpoints(then), _without_endpoints(now)
        moves = code_edit(then, now)
        if moves is None:
            moves = build_moves(then, now)
        if moves is None and declaring is not None:
            gathering = gathering_edit(then, now)
            if gathering is not None and (naming is not None or not gathering[1]):
                moves, renames = gathering
                declaring.add(display)
                if renames and naming is not None:
                    naming.add(display)
        if moves is not None:
            edits[display] = moves
        elif not same_places(then, now):
            return None  # a launch, build or parameter file changed: the graph is built
    return edits


def same_places(before: FileFacts, now: FileFacts) -> bool:
    """The same facts, every one where it was (``moves``: but for what no graph reads)."""
    spans = moved_spans(before, now)
    return spans is not None and all(old == new for old, new in spans.items())


def for_patching(graph: Graph) -> Graph:
    """``graph`` less what neither ``patched`` nor a rule run over a patched graph reads
    (``Rule.reads_code_names``): what nodes declare and read as parameters, the settings
    and files launch hands them, which only the rules whose built findings a patch keeps
    read. What the CLI keeps of a build (``same_facts.KeptGraph``): a third of its bytes,
    loaded by every run that patches it. Equal names, and equal reaches, are one object
    each (``_One``): each file's facts brought its own (a package's name, once per node
    of it; a node's name, once more in each of its endpoints): 117,000 of the 391,000
    objects pickled at 8 copies of the benchmark's workspace, whose pickler's memo, past
    349,000, doubles to 16 MB (the peak of a run that keeps a rebased graph), and loaded
    by every patched run."""
    one = _One()
    nodes = tuple(
        replaced(
            node,
            name=one(node.name),
            package=one(node.package),
            executable=one(node.executable),
            root=one(node.root),
            sources=one(node.sources),
            launch_namespaces=one(node.launch_namespaces),
            uses=one(node.uses),
            uses_relative=one(node.uses_relative),
            parameters=one(node.parameters),
            code_parameters=None,
            parameter_settings=(),
            parameter_files=(),
            reach=one(node.reach),
        )
        for node in graph.nodes
    )
    endpoints = tuple(
        replaced(
            endpoint,
            resource=one(endpoint.resource),
            node=one(endpoint.node),
            root=one(endpoint.root),
            type_name=one(endpoint.type_name),
            location=Location(one(endpoint.location.path), endpoint.location.span),
            written=one(endpoint.written),
            reach=one(endpoint.reach),
        )
        for endpoint in graph.endpoints
    )
    return replace(
        graph,
        nodes=nodes,
        endpoints=endpoints,
        parameter_files={},
        parameter_loads=(),
        unnamed_parameter_files={},
        parameter_declarations=None,
    )


class _One:
    """The first of the equal values it was handed, for each value it is handed."""

    def __init__(self) -> None:
        self._first: dict[object, object] = {}

    def __call__(self, value: _T) -> _T:
        return cast(_T, self._first.setdefault(value, value))


def parameter_part(graph: Graph) -> ParameterPart:
    """What ``for_patching`` leaves out of ``graph``: with ``with_parameters``, the whole
    graph again (``same_facts.KeptLaunch``: a launch patch runs every rule)."""
    return ParameterPart(
        tuple(
            (node.code_parameters, node.parameter_settings, node.parameter_files)
            for node in graph.nodes
        ),
        graph.parameter_files,
        graph.parameter_loads,
        graph.unnamed_parameter_files,
        graph.parameter_declarations,
    )


def kept_parts(graph: Graph, parts: LaunchParts) -> tuple[ParameterPart, LaunchParts]:
    """``parameter_part(graph)`` and ``parts`` as the CLI keeps them beside the graph
    (``same_facts.KeptLaunch``), equal names one object each, as ``for_patching`` keeps
    the graph's: what nodes' code declares, reads and holds as literals, the names the
    launch files set, the programs each tree starts (108,000 copies among the 308,000
    objects at 8 copies of the benchmark's workspace)."""
    one = _One()
    shared: dict[int, NodeParameters] = {}  # by id: the graph and ``parts`` share them

    def names(values: tuple[str, ...]) -> tuple[str, ...]:
        return tuple(one(value) for value in values)

    def code(parameters: NodeParameters) -> NodeParameters:
        found = shared.get(id(parameters))
        if found is None:
            found = shared[id(parameters)] = replace(
                parameters,
                declared=names(parameters.declared),
                read=names(parameters.read),
                declared_suffixes=names(parameters.declared_suffixes),
                literals=names(parameters.literals),
            )
        return found

    part = parameter_part(graph)
    nodes = tuple(
        (
            None if parameters is None else code(parameters),
            tuple(replaced(setting, name=one(setting.name)) for setting in settings),
            files,
        )
        for parameters, settings, files in part.nodes
    )
    trees = {
        root: replaced(tree, started=tuple(one((one(p), one(e))) for p, e in tree.started))
        for root, tree in parts.trees.items()
    }
    by_code = {sources: code(parameters) for sources, parameters in parts.parameters.items()}
    return replace(part, nodes=nodes), replace(parts, trees=trees, parameters=by_code)


def with_parameters(graph: Graph, part: ParameterPart) -> Graph | None:
    """``graph`` (``for_patching``'s) with what ``parameter_part`` took from it; None
    where the part is of another graph (another count of nodes)."""
    if len(part.nodes) != len(graph.nodes):
        return None
    nodes = tuple(
        replaced(node, code_parameters=code, parameter_settings=settings, parameter_files=files)
        for node, (code, settings, files) in zip(graph.nodes, part.nodes, strict=True)
    )
    return replace(
        graph,
        nodes=nodes,
        parameter_files=part.parameter_files,
        parameter_loads=part.parameter_loads,
        unnamed_parameter_files=part.unnamed_parameter_files,
        parameter_declarations=part.parameter_declarations,
    )


def _without_endpoints(facts: FileFacts) -> FileFacts:
    kept = tuple(use for use in facts.names if use.role not in ENDPOINT_ROLES)
    return replace(facts, names=kept, literals=())


def patched(
    graph: Graph,
    edits: Mapping[str, Moved],
    facts_of: Callable[[str], FileFacts | None],
    packages: Callable[[], PackageFiles],
    *,
    declaring: bool = False,
) -> Graph | None:
    """``graph`` with every node whose code holds an edited file (``edits``: display
    path -> ``code_edit``'s moves) resolved again from its code as it is now, and the
    literals of each package holding one gathered again where the graph keeps them
    (``Graph.mentions``); None where that cannot be done exactly (module docstring).
    ``facts_of``: a file's facts by display path, the edited files' new ones, None where
    unknown; ``packages``: which package holds each file of the run, asked only where
    the graph keeps some package's literals. ``declaring``: some edit changed what code
    declares (``declaration_edit``): the nodes' static parameter names follow it, and
    their code's parameters are left as they were, for ``workspace.parameter_patch``
    to make again."""
    try:
        mentions = _mentions(graph, edits, facts_of, packages)
        found = _patched(graph, edits, facts_of, declaring=declaring)
    except UnplacedError:
        return None
    return None if found is None or mentions is None else replace(found, mentions=mentions)


def _mentions(
    graph: Graph,
    edits: Mapping[str, Moved],
    facts_of: Callable[[str], FileFacts | None],
    packages: Callable[[], PackageFiles],
) -> Mapping[str, frozenset[str]] | None:
    """The graph's literals of each package (``build.mentions``), those of the packages
    holding an edited file gathered again."""
    if not graph.mentions:
        return graph.mentions
    owners = packages()
    edited = {package.name for path in edits if (package := owners.package_of(path))}
    mentions = dict(graph.mentions)
    for name in edited & mentions.keys():
        code = [facts_of(path) for path in owners.files_of(name)]
        known = [facts for facts in code if facts is not None]
        if len(known) != len(code):
            return None
        mentions[name] = package_literals(known)
    return mentions


def _patched(
    graph: Graph,
    edits: Mapping[str, Moved],
    facts_of: Callable[[str], FileFacts | None],
    *,
    declaring: bool,
) -> Graph | None:
    touched = _touched(graph, edits.keys())
    if not touched:
        return graph
    renewed: dict[int, NodeInstance] = {}
    fresh: list[Endpoint] = []
    for node in touched:
        instance = _instance_of(node)
        code = [facts for path in node.sources if (facts := facts_of(path)) is not None]
        if instance is None or len(code) != len(node.sources):
            return None
        names = _resolve_code(code, instance, node.remaps, node.root, node.reach)
        if names.parameters != node.parameters and not declaring:
            return None
        renewed[id(node)] = replaced(
            node,
            uses=names.uses,
            uses_complete=names.complete,
            uses_relative=names.relative,
            parameters=names.parameters,
            code_parameters=node.code_parameters
            if node.code_parameters is None or declaring
            else _moved_parameters(node.code_parameters, edits),
        )
        fresh.extend(names.endpoints)
    gone = {(node.name, node.root, path) for node in touched for path in node.sources}
    endpoints = [e for e in graph.endpoints if (e.node, e.root, e.location.path) not in gone]
    receivers = (
        graph.unnamed_parameter_files
        if declaring
        else {
            path: tuple(
                replace(receiver, parameters=_moved_parameters(receiver.parameters, edits))
                for receiver in kept
            )
            for path, kept in graph.unnamed_parameter_files.items()
        }
    )
    return replace(
        graph,
        nodes=_unique((renewed.get(id(node), node) for node in graph.nodes), NodeInstance.sort_key),
        endpoints=_unique([*endpoints, *fresh], Endpoint.sort_key),
        unnamed_parameter_files=receivers,
    )


def _touched(graph: Graph, edited: Collection[str]) -> list[NodeInstance]:
    """The nodes running an edited file, and their namesakes that share code with one:
    an endpoint is its node's by the node's name and tree and by the code it is in, so
    two nodes of one name in one tree running one file (a launch file included twice
    under one namespace) cannot be told apart: both are resolved again, their endpoints
    in that code all made anew."""
    edited_set = set(edited)
    namesakes: dict[tuple[str, str], list[NodeInstance]] = {}
    for node in graph.nodes:
        namesakes.setdefault((node.name, node.root), []).append(node)
    touched = {id(node): node for node in graph.nodes if not edited_set.isdisjoint(node.sources)}
    waiting = list(touched.values())
    while waiting:
        node = waiting.pop()
        for other in namesakes[node.name, node.root]:
            if id(other) not in touched and not set(other.sources).isdisjoint(node.sources):
                touched[id(other)] = other
                waiting.append(other)
    return [node for node in graph.nodes if id(node) in touched]


def _instance_of(node: NodeInstance) -> _Instance | None:
    """What resolution knew of the node when it was built: its namespace is the one in
    force after its last launch site (root for code no launch file starts), its name what
    follows it in its full name."""
    if bool(node.launched_at) != bool(node.launch_namespaces):
        return None
    namespace = node.launch_namespaces[-1] if node.launched_at else "/"
    prefix = f"{namespace.rstrip('/')}/"
    name = node.name[len(prefix) :]
    if not node.name.startswith(prefix) or not name or "/" in name:
        return None
    return _Instance(name, namespace, node.generation)


def moved_code_parameters(
    parameters: Mapping[tuple[str, ...], NodeParameters], edits: Mapping[str, Moved]
) -> dict[tuple[str, ...], NodeParameters] | None:
    """Each node's code parameters (``LaunchParts.parameters``) with each use in an edited
    file where it is now, as ``patched`` moves the graph's nodes' (where no parameter is
    gathered again); None where one has no new place."""
    try:
        return {sources: _moved_parameters(found, edits) for sources, found in parameters.items()}
    except UnplacedError:
        return None


def _moved_parameters(parameters: NodeParameters, edits: Mapping[str, Moved]) -> NodeParameters:
    """``parameters`` with each use in an edited file where it is now; an
    ``UnplacedError`` where one has no new place."""
    if all(use.location.path not in edits for use in parameters.uses):
        return parameters
    return replace(
        parameters, uses=tuple(sorted(_moved_use(use, edits) for use in parameters.uses))
    )


def _moved_use(use: ParameterUse, edits: Mapping[str, Moved]) -> ParameterUse:
    moves = edits.get(use.location.path)
    if moves is None:
        return use
    span = moves.get(use.location.span)
    if span is None:
        raise UnplacedError(use.location.path)
    return replace(use, location=Location(use.location.path, span))

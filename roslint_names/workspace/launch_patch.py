"""The last graph with the launch trees an edited launch file is in walked again (issue 30).

A node added to a launch file, renamed, remapped, moved into a group or taken out, or
an include added, changed or taken out, changes what the trees that read that file
start (and which launch files are roots), and nothing else the graph is made of: the
code each node runs and what it declares come from code and build files, the other
trees from their own files. Building the whole graph again for it loads every
file's facts (1.5 s at 77,000 files) and walks every tree (3 s); ``launch_patched``
walks only the trees that read an edited file (``LaunchParts``: what each tree of the
last build read and gave), by the build's own functions, over an index that loads a
file's facts only when the walk asks for them, and puts their nodes, endpoints, loads
and parameter files in place of the old.

``launch_edit`` says whether an edit is of that kind: a launch file that keeps its
language and generation and holds nothing else the graph reads (build, parameter or
code facts, literals). An edit of a parameter file that changes only the names it sets
and where (``parameter_edit``) is one too: the trees whose nodes or group-level loads
are handed it are walked again, and its blocks are the graph's from its new facts.
A file an edited include names now, or named before, is a root where nothing includes
it any more (``LaunchParts.includers``). Code a tree starts now is no program of its
own any more, and code no tree starts any more is one again (``Programs.unlaunched``).
A patch is refused (None, the caller builds) where a node runs code whose parameters
the build did not make (code that ran as no node, or as a program of other sources),
but where a package's programs were made again (``program_patch``: the parameter patch
gathers those), or where a file it needs has no facts to load. It gives the launch
parts a build would leave too (the roots, each tree's part, the includers), which a run
that keeps what it patched keeps (``graph_patch.REBASE_EDITS``).
``tests/test_launch_patch.py`` compares patched graphs and parts with built ones.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterator, Mapping, Sequence
from dataclasses import replace

from roslint_names.model import FileFacts, Language
from roslint_names.workspace.build import (
    _group_loads,
    _launched_instance,
    _TestFiles,
    _unique,
    _unlaunched_instance,
    _with_group_loads,
    launched_sources_of,
    linked_files,
    mentions,
    receivers_by_file,
    started_program,
    unnamed_receivers,
    with_code_parameters,
)
from roslint_names.workspace.graph import (
    Endpoint,
    Graph,
    NodeInstance,
    ParameterFileUse,
)
from roslint_names.workspace.index import Package, WorkspaceIndex
from roslint_names.workspace.launch_parts import LaunchParts, TreePart, Unnamed
from roslint_names.workspace.launch_tree import (
    LAUNCH_LANGUAGES,
    LaunchTrees,
    Prepare,
    Specialise,
)
from roslint_names.workspace.parameters import (
    NO_CODE,
    NodeParameters,
    ParameterTables,
    has_endpoints,
)
from roslint_names.workspace.program_patch import ProgramsAnew

# What a launch file's facts may not change for its trees alone to be walked again: what
# the executables, the sources no build compiles, the parameter tables, the code no
# launch file starts and the packages' literals are made from.
_OTHER_FIELDS = (*ParameterTables.FIELDS, "literals", "parameter_blocks")


class UnknownFactsError(Exception):
    """A file whose facts the patch needs and cannot load (``LazyFacts``)."""


class LazyFacts(Mapping[str, FileFacts]):
    """Every file of a run by display path, each file's facts loaded when first asked
    for (``load``: None where it cannot be, which raises ``UnknownFactsError``)."""

    def __init__(self, paths: Collection[str], load: Callable[[str], FileFacts | None]) -> None:
        self._paths = paths  # a set: asked whether it holds a path, seldom walked
        self._load = load
        self._loaded: dict[str, FileFacts] = {}
        # Sorted when first walked, once: 0.04 to 0.09 s at 8 copies of the benchmark's
        # workspace (81,000 paths), and a patch walks them for each index it makes.
        self._order: list[str] | None = None

    def __getitem__(self, path: str) -> FileFacts:
        found = self._loaded.get(path)
        if found is None:
            if path not in self._paths:
                raise KeyError(path)
            found = self._load(path)
            if found is None:
                raise UnknownFactsError(path)
            self._loaded[path] = found
        return found

    def __contains__(self, path: object) -> bool:
        return path in self._paths

    def __iter__(self) -> Iterator[str]:
        if self._order is None:
            self._order = sorted(self._paths)
        return iter(self._order)

    def __len__(self) -> int:
        return len(self._paths)


def launch_edit(before: FileFacts, now: FileFacts) -> bool:
    """Whether an edit of a launch file changes the graph only through the trees that
    read it (module docstring)."""
    if before.language not in LAUNCH_LANGUAGES or now.language is not before.language:
        return False
    if now.generation is not before.generation or has_endpoints(before) != has_endpoints(now):
        return False
    return all(getattr(before, field) == getattr(now, field) for field in _OTHER_FIELDS)


def parameter_edit(before: FileFacts, now: FileFacts) -> bool:
    """Whether an edit of a parameter file changes only what it sets (its blocks, the
    names of its ROS 2 keys, whether it parses): the graph then changes only through the
    trees whose nodes or group loads are handed it, walked again as for a launch edit."""
    if before.language is not Language.PARAMETERS or now.language is not Language.PARAMETERS:
        return False
    return _without_settings(before) == _without_settings(now)


def _without_settings(facts: FileFacts) -> FileFacts:
    return replace(facts, names=(), parameter_blocks=(), parse_errors=())


def launch_patched(
    graph: Graph,
    parts: LaunchParts,
    edited: Collection[str],
    *,
    facts: Mapping[str, FileFacts],
    packages: Sequence[Package],
    specialise: Specialise,
    prepare: Prepare | None = None,
    removed: Collection[str] = (),
    code: Collection[str] = (),
    programs: ProgramsAnew | None = None,
) -> tuple[Graph, LaunchParts] | None:
    """``graph`` (a build's, whole: ``parts`` is what the same build left) with the trees
    that read one of the ``edited`` files (launch files, ``launch_edit``; parameter files,
    ``parameter_edit``) walked again over ``facts`` (every file of the run: a
    ``LazyFacts``), and the parts a build of the files as they are would leave (but for
    the parameters of the nodes' code, ``parameter_patch``'s); None where that cannot be
    done exactly (module docstring).
    ``removed``: launch and parameter files the run has not (``shifts``): a removed
    launch file's tree goes, and the trees that read or are handed one are walked
    again; an edited launch file the build had not is a root where nothing includes it,
    as any. ``code``: code files whose node name changed (``patch.name_edit``): the trees
    that start them are walked again, and their programs of their own made again.
    ``programs``: the programs of some packages made again (``program_patch``): the
    trees that start a node of one are walked again, and the programs of their own made
    of the code as it is now."""
    edited = frozenset(edited) | frozenset(removed)
    renamed = frozenset(code)
    anew = parts
    if programs is not None:
        anew = replace(
            parts,
            unbuilt=programs.unbuilt,
            executables=programs.executables,
            programs=programs.programs,
        )
    index = WorkspaceIndex.restored(facts, packages, anew.executables)
    try:
        roots, includers = _roots(
            parts, edited, LaunchTrees(index, specialise, roots=[]), frozenset(removed)
        )
        gone = set(parts.roots) - set(roots)
        handed = _handed(graph, parts, edited)
        walked = [
            root
            for root in roots
            if root not in parts.trees
            or root in handed
            or not edited.isdisjoint(parts.trees[root].visited)
            or not renamed.isdisjoint(parts.trees[root].sources)
            or (programs is not None and programs.starts(parts.trees[root]))
        ]
        if not walked and not gone and not renamed and programs is None:
            return graph, replace(parts, includers=includers)
        trees = LaunchTrees(index, specialise, prepare, roots=walked)
        found = _patched(
            graph,
            parts,
            roots,
            gone,
            trees,
            edited=edited,
            renamed=renamed,
            anew=anew,
            programs=programs,
        )
        if found is None:
            return None
        patched, walked_parts = found
        kept = {
            root: walked_parts[root] if root in walked_parts else parts.trees[root]
            for root in roots
        }
        return patched, replace(anew, roots=tuple(roots), trees=kept, includers=includers)
    except UnknownFactsError:
        return None


def _roots(
    parts: LaunchParts, edited: frozenset[str], trees: LaunchTrees, removed: frozenset[str]
) -> tuple[list[str], dict[str, tuple[str, ...]]]:
    """The roots after the edits: a file an edited include names now, or named before,
    and an edited file itself, is a root where it is a launch file no launch file
    includes (``LaunchTrees``); a ``removed`` file is none. And the includers after
    them, as ``LaunchTrees.includers`` gives them."""
    includers = {target: set(paths) - edited for target, paths in parts.includers.items()}
    for path in sorted(edited - removed):
        facts = trees.index.facts[path]
        if not trees.is_launch_file(path):
            continue
        for include in facts.includes:
            target = trees.target(path, include)
            if target is not None:
                includers.setdefault(target, set()).add(path)
    changed = {
        target
        for target in includers.keys() | parts.includers.keys()
        if includers.get(target, set()) != set(parts.includers.get(target, ()))
    }
    roots = set(parts.roots) - changed - removed
    roots.update(
        target
        for target in changed | (edited - removed)
        if not includers.get(target) and trees.is_launch_file(target)
    )
    found = {target: tuple(sorted(paths)) for target, paths in sorted(includers.items()) if paths}
    return sorted(roots), found


def _handed(graph: Graph, parts: LaunchParts, edited: frozenset[str]) -> set[str]:
    """The roots of the trees that hand one of the ``edited`` files to a node (named or
    not) or load it at group level: where a parameter file's edit reaches."""
    found = {
        node.root
        for node in graph.nodes
        if node.root and any(use.path in edited for use in node.parameter_files)
    }
    found.update(
        root
        for root, part in parts.trees.items()
        if any(use.path in edited for use in part.loads)
        or any(path in edited for path, _ in part.unnamed)
    )
    return found


def _patched(
    graph: Graph,
    parts: LaunchParts,
    roots: list[str],
    gone_roots: set[str],
    trees: LaunchTrees,
    *,
    edited: frozenset[str],
    renamed: frozenset[str] = frozenset(),
    anew: LaunchParts,
    programs: ProgramsAnew | None = None,
) -> tuple[Graph, dict[str, TreePart]] | None:
    """``launch_patched``'s graph, and the part of each tree walked again; ``anew``:
    ``parts`` with the programs as they are now (``programs``' where it is given)."""
    index = trees.index
    walked = trees.roots()
    tests = _TestFiles(index, {})
    nodes: list[NodeInstance] = []
    endpoints: list[Endpoint] = []
    sources_of: dict[str, set[str]] = {root: set() for root in walked}
    unnamed_of: dict[str, list[Unnamed]] = {root: [] for root in walked}
    started_of: dict[str, set[tuple[str, str]]] = {root: set() for root in walked}
    for launched in trees.launched():
        sources = launched_sources_of(index, launched, anew.unbuilt)
        sources_of[launched.root].update(sources)
        started_of[launched.root].add(started_program(launched))
        started, _ = _launched_instance(index, tests, launched, sources, trees)
        if started.node is not None:
            nodes.append(started.node)
            endpoints.extend(started.endpoints)
        unnamed_of[launched.root].extend(started.unnamed)
    # Code a launch file starts no more is a program of its own again, and code started
    # now is one no more.
    was = set(parts.programs.unlaunched(_launched(parts, parts.roots, {})))
    now = anew.programs.unlaunched(_launched(anew, roots, sources_of))
    # Those that run on, of code whose node name changed, are made again.
    stopped = (was - set(now)) | {sources for sources in now if not renamed.isdisjoint(sources)}
    for sources in now:
        if sources not in was or sources in stopped:  # sets: every program looked up
            node, own_endpoints = _unlaunched_instance(index, sources)
            nodes.append(node)
            endpoints.extend(own_endpoints)
    loads_of: dict[str, list[ParameterFileUse]] = {root: [] for root in walked}
    for root, use in _group_loads(index, trees):
        loads_of[root].append(use)
    rooted = [
        (root, use)
        for root in roots
        for use in (loads_of[root] if root in loads_of else parts.trees[root].loads)
    ]
    loads = tuple(sorted({use for _, use in rooted}))
    gone = set(walked) | gone_roots
    kept = [
        node
        for node in graph.nodes
        if node.root not in gone and not (not node.root and node.sources in stopped)
    ]
    # A program's endpoints are in its own code, its sources no other program's.
    stopped_at = {
        (node.name, path)
        for node in graph.nodes
        if not node.root and node.sources in stopped
        for path in node.sources
    }
    blocks = {
        path: graph.parameter_files[path]
        if path in graph.parameter_files and path not in edited
        else index.facts[path].parameter_blocks
        for path in linked_files((*kept, *nodes), loads)
    }
    # The code of a program made anew has no parameters in the build's parts: gathered
    # by the parameter patch (``parameter_patch``), which the caller runs then.
    parameters = _Parameters(parts.parameters, later=programs is not None)
    finished = [
        with_code_parameters(
            node,
            parameters.of(node.sources),
            parameter_settings=_with_group_loads(node, rooted, blocks),
        )
        for node in nodes
    ]
    receivers = receivers_by_file(
        unnamed
        for root in roots
        for unnamed in (unnamed_of[root] if root in unnamed_of else parts.trees[root].unnamed)
    )
    # A receiver of code made anew is handed its parameters by the parameter patch too.
    unnamed = unnamed_receivers(receivers, parameters.of)
    if parameters.missing:
        return None
    all_nodes = _unique([*kept, *finished], NodeInstance.sort_key)
    walked_parts = {
        root: TreePart(
            trees.visited(root),
            tuple(sorted(sources_of[root])),
            tuple(unnamed_of[root]),
            tuple(loads_of[root]),
            tuple(sorted(started_of[root])),
        )
        for root in walked
    }
    patched = replace(
        graph,
        nodes=all_nodes,
        endpoints=_unique(
            [
                *(
                    e
                    for e in graph.endpoints
                    if e.root not in gone
                    and (e.root or (e.node, e.location.path) not in stopped_at)
                ),
                *endpoints,
            ],
            Endpoint.sort_key,
        ),
        mentions=mentions(index, all_nodes, _literals_kept(graph, programs)),
        parameter_files=blocks,
        parameter_loads=loads,
        unnamed_parameter_files=unnamed,
    )
    return patched, walked_parts


def _launched(parts: LaunchParts, roots: Sequence[str], walked: Mapping[str, set[str]]) -> set[str]:
    """The code the trees of ``roots`` start, and the sources no build compiles
    (``build``'s ``launched_sources``), the trees in ``walked`` starting what it says."""
    found = set(parts.unbuilt)
    for root in roots:
        found.update(walked[root] if root in walked else parts.trees[root].sources)
    return found


def _literals_kept(graph: Graph, programs: ProgramsAnew | None) -> Mapping[str, frozenset[str]]:
    """The literals of the packages the graph keeps (``Graph.mentions``) but for those
    whose programs were made again (``programs``: code added or removed), read again."""
    if programs is None:
        return graph.mentions
    return {
        package: literals
        for package, literals in graph.mentions.items()
        if package not in programs.packages
    }


class _Parameters:
    """The build's parameters of each node's code; ``missing`` where one was not made,
    but for ``later``, where code the build had no node of is gathered later (each such
    code in ``later``, its parameters NO_CODE until then)."""

    def __init__(
        self, known: Mapping[tuple[str, ...], NodeParameters], *, later: bool = False
    ) -> None:
        self._known = known
        self._gathered_later = later
        self.missing = False
        self.later: set[tuple[str, ...]] = set()

    def of(self, sources: tuple[str, ...]) -> NodeParameters:
        if not sources:
            return NO_CODE
        found = self._known.get(sources)
        if found is None:
            if self._gathered_later:
                self.later.add(sources)
            else:
                self.missing = True
            return NO_CODE
        return found

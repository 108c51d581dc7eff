"""The last graph with the parameters of edited code gathered again (issue 30).

A parameter declared, read, renamed or taken out in a node's code changes what that
code declares and reads (``NodeParameters``, ``ParameterSets``), what the workspace's code
declares (``WorkspaceDeclarations``) and, ROS 2, the node's static parameter names; where
nodes run and what their endpoints are is the code patch's (``workspace.patch``, which
re-resolves the nodes running an edited file, their parameter names with them). Building
the whole graph again for it loads every file's facts and walks every tree (9-11 s at 8
copies of the benchmark's workspace); the parameters of a node's code are gathered from
its sources' packages and those of the base classes it derives from
(``ParameterSets._own_code``: what a file includes is of its own package), so only the
nodes whose code spans an edited file's package are gathered again, by the build's own
``ParameterSets``, over the lookups the build made from every file's facts
(``CodeParameterParts``) and an index that loads a file's facts when asked.

An edit may change what the parameters are gathered through as well
(``patch.gathering_edit``): what a file includes stays in its package; a class of it
added, taken out or given other bases changes the lookups of classes by name, which
follow it (``TableLookups.with_classes``), and the code of the nodes whose files derive
from a class of that name, or load plugins of such a base, may span other packages now:
those nodes are gathered again too (``TableLookups.deriving``, ``loading``). The growth
benchmark's ``edit_class`` (a class deriving from ``rclcpp::Node`` appended to a node's
source) is such an edit.

A package's dependencies changed change which of the classes of one name its code means
(``ParameterSets._defined``: those of the packages it depends on): the nodes whose code
spans that package are gathered again too. A package's programs made again
(``program_patch``: a node added or taken out) change which files are programs' sources
and which C++ files are looked up by name: the code spanning it, and the code no node
ran at the build, is gathered again, and the code no node runs any more is dropped.

``parameters_patched`` gives the graph a build would, over facts whose names take
other files' constants as the run resolves them (``graph_patch.GraphPatch``: those that
resolve otherwise than at the build are edits, ``_Constants.anew``), a node of unknown
name handed a parameter file with what its code may take of it as gathered now (the
graph keeps those parameters without the code they are of: the trees' parts say which);
None (the caller builds) where a file's facts cannot be loaded. It gives the parts a
build would leave too (each node's code parameters, the lookups, spans and counts),
which a run that keeps what it patched keeps (``graph_patch.REBASE_EDITS``).
``tests/test_parameter_patch.py`` compares patched graphs and parts with built ones.
"""

from __future__ import annotations

import posixpath
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import replace

from roslint_names.model import FileFacts, Language
from roslint_names.workspace.build import (
    _TestFiles,
    receivers_by_file,
    unnamed_receivers,
    with_code_parameters,
)
from roslint_names.workspace.graph import Graph, UnnamedReceiver
from roslint_names.workspace.index import CODE_LANGUAGES, Package, WorkspaceIndex
from roslint_names.workspace.launch_parts import CodeParameterParts, LaunchParts
from roslint_names.workspace.launch_patch import UnknownFactsError
from roslint_names.workspace.parameters import (
    DeclarationCounts,
    NodeParameters,
    ParameterSets,
    ParameterTables,
    file_declarations,
    package_directory,
)
from roslint_names.workspace.program_patch import ProgramsAnew


def parameters_patched(
    graph: Graph,
    parts: LaunchParts,
    code: CodeParameterParts,
    edited: Mapping[str, tuple[FileFacts, FileFacts]],
    *,
    facts: Mapping[str, FileFacts],
    packages: Sequence[Package],
    depending: Collection[str] = (),
    programs: ProgramsAnew | None = None,
    added: Collection[str] = (),
    removed: Collection[str] = (),
) -> tuple[Graph, LaunchParts, CodeParameterParts] | None:
    """``graph`` (a build's, whole, patched since: ``parts`` and ``code`` are what the
    same build left) with the parameters of every node's code that spans the package of
    an ``edited`` code file (display path -> its facts then and now) or one of the
    ``depending`` packages (names: those that depend on others than at the build, as
    ``packages`` say now) gathered again over ``facts`` (every file of the run: a
    ``launch_patch.LazyFacts``), and the workspace's declarations with the edited files'
    own; with the parts a build of the files as they are would leave (the parameters
    of each node's code, the lookups, spans and counts); None where that cannot be done
    exactly (module docstring). ``programs``: the programs of some packages made again
    (``program_patch``; ``parts`` are the launch patch's, with them): the code spanning
    those packages, and the code no node ran at the build, is gathered too; ``added``:
    the edited code files the build had not (their facts then empty), ``removed``: those
    the run has not (their facts now empty)."""
    index = WorkspaceIndex.restored(facts, packages, parts.executables)
    tests = _TestFiles(index, {})

    def excluded(path: str) -> bool:
        return path in parts.unbuilt or tests(path)

    lookups, dependent = code.lookups.with_classes(
        ((path, before, now) for path, (before, now) in edited.items()), excluded
    )
    changed_programs: Collection[str] = ()
    if programs is not None:
        lookups = replace(
            lookups,
            programs=programs.program_sources(),
            by_name=_by_name(lookups.by_name, index, added, removed, excluded),
        )
        changed_programs = programs.sources
    sets = ParameterSets(index, ParameterTables(lookups, excluded))
    reached = {
        (package.name if (package := index.package_of(path)) else "")
        for path in (*edited, *dependent, *changed_programs)
    }
    reached.update(depending)
    removed_set = frozenset(removed)
    spanning = [
        sources
        for sources, spans in code.spans.items()
        if not spans.isdisjoint(reached) and removed_set.isdisjoint(sources)  # (none runs it)
    ]
    running: set[tuple[str, ...]] | None = None  # the code a node runs, programs made anew
    if programs is not None:  # and the code the build had no node of (nor receiver)
        received = (sources for part in parts.trees.values() for _, (_, sources) in part.unnamed)
        running = {node.sources for node in graph.nodes}.union(received)
        spanning.extend(sorted(sources for sources in running if sources not in code.spans))
    if not spanning:
        fresh = {}
    else:
        try:
            fresh = {sources: sets.of(sources) for sources in spanning}
        except UnknownFactsError:  # a file the patch cannot load: the graph is built
            return None
    nodes = tuple(
        with_code_parameters(node, fresh[node.sources])
        if node.sources in fresh and node.code_parameters is not None
        else node
        for node in graph.nodes
    )
    counts = _declarations(code.counts, edited)
    spans = {**code.spans, **{sources: sets.spans.get(sources, frozenset()) for sources in fresh}}
    parameters = {**parts.parameters, **fresh}
    if running is not None:  # code no node runs any more: a build gathers none of it
        parameters = {sources: found for sources, found in parameters.items() if sources in running}
        spans = {sources: found for sources, found in spans.items() if sources in running}
    receivers = graph.unnamed_parameter_files
    if fresh or programs is not None:
        # A node of unknown name handed a parameter file keeps its code's parameters
        # (``UnnamedReceiver``), not which code they are of: the trees' parts say that.
        found = _receivers(parts, parameters)
        if found is None:
            return None
        receivers = found
    return (
        replace(
            graph,
            nodes=nodes,
            parameter_declarations=counts.declarations(),
            unnamed_parameter_files=receivers,
        ),
        replace(parts, parameters=parameters),
        CodeParameterParts(lookups, spans, counts),
    )


def _receivers(
    parts: LaunchParts, parameters: Mapping[tuple[str, ...], NodeParameters]
) -> dict[str, tuple[UnnamedReceiver, ...]] | None:
    """``Graph.unnamed_parameter_files`` as a build makes it (``unnamed_receivers``):
    each parameter file handed to a node of unknown name, with the parameters of that
    node's code as ``parameters`` (the code's, by its sources) say; None where they say
    none of a receiver's code."""
    handed = receivers_by_file(
        unnamed for root in parts.roots for unnamed in parts.trees[root].unnamed
    )
    if any(sources not in parameters for found in handed.values() for _, sources in found):
        return None
    return unnamed_receivers(handed, parameters.__getitem__)


def _by_name(
    by_name: Mapping[tuple[str, str], list[str]],
    index: WorkspaceIndex,
    added: Collection[str],
    removed: Collection[str],
    excluded: Callable[[str], bool],
) -> dict[tuple[str, str], list[str]]:
    """``TableLookups.by_name`` with the C++ files added that no build leaves out, each
    where ``ParameterTables.of`` puts it (in path order), and without those removed."""
    found = dict(by_name)
    for path in removed:
        key = (package_directory(index, path), posixpath.basename(path))
        kept = [other for other in found.get(key, ()) if other != path]
        if kept:
            found[key] = kept
        else:
            found.pop(key, None)
    for path in sorted(added):
        if index.facts[path].language is not Language.CPP or excluded(path):
            continue
        key = (package_directory(index, path), posixpath.basename(path))
        found[key] = sorted([*found.get(key, ()), path])
    return found


def _declarations(
    counts: DeclarationCounts, edited: Mapping[str, tuple[FileFacts, FileFacts]]
) -> DeclarationCounts:
    """``counts`` (the build's) with each edited code file's declarations as they are now."""
    found = DeclarationCounts(dict(counts.names), dict(counts.suffixes), dict(counts.mentioned))
    for before, now in edited.values():
        for facts, times in ((before, -1), (now, 1)):
            if facts.language in CODE_LANGUAGES:
                found.add(file_declarations(facts), times)
    return found

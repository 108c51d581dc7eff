"""What a graph build leaves for a launch patch: each launch tree's part of the graph;
and for a parameter patch: what the parameters of nodes' code were gathered from.

A build walks every root launch file's tree (``launch_tree``); ``workspace.launch_patch``
walks again only the trees an edited launch file is in, and needs, for every other tree,
what the build took from it besides its nodes and endpoints (which carry their root):
the code its nodes run, the parameter files handed to nodes of unknown name, the ROS 1
group-level loads. ``build.build_parts`` makes these beside the graph; the CLI keeps
them with the graph it keeps (``same_facts.KeptLaunch``).
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass

from roslint_names.model import Compact, FileFacts, Generation, Language, ParameterBlock
from roslint_names.workspace.graph import (
    ParameterFileUse,
    ParameterSetting,
    UnnamedReceiver,
)
from roslint_names.workspace.index import CODE_LANGUAGES, Executables
from roslint_names.workspace.parameters import (
    DeclarationCounts,
    NodeParameters,
    TableLookups,
    WorkspaceDeclarations,
    has_endpoints,
)

# A parameter file handed to a node of unknown name: (file, the node's generation, code)
Unnamed = tuple[str, tuple[Generation, tuple[str, ...]]]


@dataclass(frozen=True, slots=True)
class TreePart(Compact):
    """What one root's tree gave the build besides its nodes and endpoints."""

    visited: tuple[str, ...]  # the files its walk read, sorted (``LaunchTrees.visited``)
    sources: tuple[str, ...]  # the code of every node it starts, named or not, sorted
    unnamed: tuple[Unnamed, ...]  # in the order the walk met them
    loads: tuple[ParameterFileUse, ...]  # group-level ``<rosparam load>``, in order
    # The package and executable (or plugin) of every node it starts, sorted, whatever
    # code they found: the trees a package's programs made anew are walked again
    # (``workspace.program_patch``).
    started: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True, slots=True)
class Programs(Compact):
    """The code a build groups into programs of their own where no launch file starts it
    (``unlaunched``): every built program's sources (by package and executable, sorted),
    those of them that are test code and those that declare endpoints; and, sorted, the
    code files that declare endpoints and are no test code (a program of each, where no
    built program holds it)."""

    built: tuple[tuple[str, ...], ...]
    tests: frozenset[str]
    with_endpoints: frozenset[str]
    single: tuple[str, ...]

    def unlaunched(self, launched: Collection[str]) -> list[tuple[str, ...]]:
        """Code no launch file starts (``launched``: what some tree starts, and the
        sources no build compiles), one program per executable, else per file; tests are
        left out: they build throwaway graphs on purpose."""
        grouped: list[tuple[str, ...]] = []
        seen = set(launched)
        for sources in self.built:
            fresh = tuple(path for path in sources if path not in seen and path not in self.tests)
            seen.update(sources)
            if fresh and any(path in self.with_endpoints for path in fresh):
                grouped.append(fresh)
        grouped.extend((path,) for path in self.single if path not in seen)
        return grouped

    def anew(
        self,
        *,
        executables: Executables,
        facts: Mapping[str, FileFacts],
        added: Collection[str] = (),
        removed: Collection[str] = (),
        flipped: Collection[str] = (),
        is_test: Callable[[str], bool],
        language_of: Callable[[str], Language],
    ) -> Programs:
        """What ``build._programs`` makes of the files now, from these programs: over the
        programs ``executables`` makes, a file that was a program's source keeps whether
        it declares endpoints, but for the code added since (``added``), and that which
        started or stopped declaring them (``flipped``); another's is read from its
        facts. ``removed``: code the run no longer has."""
        lists = tuple(sources for _, sources in executables.programs)
        if lists == self.built:  # the same programs: one tuple of them, kept and shared
            lists = self.built
        sources = {path for listed in lists for path in listed}
        before = {path for listed in self.built for path in listed} - set(added) - set(flipped)
        with_endpoints = {
            path
            for path in sources
            if (path in self.with_endpoints if path in before else has_endpoints(facts[path]))
        }
        single = set(self.single) - set(removed) - set(flipped)
        single.update(
            path
            for path in (*added, *flipped)
            if language_of(path) in CODE_LANGUAGES
            and has_endpoints(facts[path])
            and not is_test(path)
        )
        return Programs(
            lists,
            frozenset(path for path in sources if is_test(path)),
            frozenset(with_endpoints),
            tuple(sorted(single)),
        )


@dataclass(frozen=True, slots=True)
class LaunchParts(Compact):
    """Every tree's part, with what the build knew of the workspace's code and
    programs: the sources no build compiles (they join no node), the executables, what
    the code no launch file starts is made of, and the parameters of each node's code
    (``ParameterSets.of``, by its sources: what a launch file starts changes none of
    them)."""

    roots: tuple[str, ...]  # in the build's order
    trees: Mapping[str, TreePart]
    # Each file a launch file's include names -> those launch files (``LaunchTrees``)
    includers: Mapping[str, tuple[str, ...]]
    unbuilt: frozenset[str]
    executables: Executables
    programs: Programs
    parameters: Mapping[tuple[str, ...], NodeParameters]


# What a node holds of parameters: its code's, the settings and files its launch hands it
NodeParameterPart = tuple[
    NodeParameters | None, tuple[ParameterSetting, ...], tuple[ParameterFileUse, ...]
]


@dataclass(frozen=True, slots=True)
class ParameterPart(Compact):
    """What ``patch.for_patching`` leaves out of a graph (``patch.parameter_part``): each
    node's parameters in the graph's order of nodes, and the graph's own."""

    nodes: tuple[NodeParameterPart, ...]
    parameter_files: Mapping[str, tuple[ParameterBlock, ...]]
    parameter_loads: tuple[ParameterFileUse, ...]
    unnamed_parameter_files: Mapping[str, tuple[UnnamedReceiver, ...]]
    parameter_declarations: WorkspaceDeclarations | None


@dataclass(frozen=True, slots=True)
class CodeParameterParts(Compact):
    """What a build leaves for a patch of what code declares (``workspace.parameter_patch``):
    the parameter tables' lookups (made from every file's facts; an edit of a file's
    classes is followed by ``TableLookups.with_classes``), the packages each node's code
    (by its sources, as ``LaunchParts.parameters``)
    was gathered from, and how many code files declare each name of the workspace's
    declarations. Kept apart from the launch parts (``same_facts.KeptLaunch``): 6 MB at
    8 copies of the benchmark's workspace, which a launch patch need not load."""

    lookups: TableLookups
    spans: Mapping[tuple[str, ...], frozenset[str]]
    counts: DeclarationCounts

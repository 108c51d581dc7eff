"""Launch trees: every node a root launch file starts, through its includes.

A root is a launch file no other launch file of the workspace includes. Each include is
followed into the file it names (``$(find pkg)``, ``FindPackageShare``, ``$(dirname)``...),
with the namespace pushed at the include prefixed to the included file's relative
namespaces, the group-level remaps in force carried in, and the statically known
arguments handed over: an included file that receives arguments is extracted again with
them (``Specialise``), exactly as the launch system would evaluate it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

from roslint_names.model import (
    FileFacts,
    Generation,
    Language,
    LaunchArguments,
    LaunchInclude,
    LaunchNode,
    ParameterLoad,
    Remap,
)
from roslint_names.names import join_namespace
from roslint_names.workspace.graph import Location
from roslint_names.workspace.index import WorkspaceIndex, join, parent
from roslint_names.workspace.memory import GraphMemory, Reads

LAUNCH_LANGUAGES = frozenset({Language.LAUNCH_XML, Language.LAUNCH_YAML, Language.LAUNCH_PYTHON})
MAX_INCLUDE_DEPTH = 16  # deeper than any real bringup; stops include cycles and blow-ups

# (display path, arguments) -> the file's facts extracted with those arguments, or None
Specialise = Callable[[str, LaunchArguments], "FileFacts | None"]
# Every (display path, arguments) one depth of the trees asks ``Specialise`` for, handed
# over before it asks: the specialisations of a depth can then be extracted together (in
# worker processes), and the walk's own calls find them done.
Prepare = Callable[[Sequence[tuple[str, LaunchArguments]]], None]


@dataclass(frozen=True)
class Launched:
    """One ``LaunchNode`` as a launch tree starts it."""

    root: str  # the root launch file
    node: LaunchNode
    path: str  # the file that holds the <node>
    namespace: str  # fully qualified, includes' namespaces applied
    remaps: tuple[tuple[Remap, str, bool], ...]  # (remap, file it is written in, own)
    sites: tuple[Location, ...]  # includes from the root, then the node
    site_namespaces: tuple[str, ...]  # namespace in force after each site
    conditional: bool  # the node, or an include on its way, may not run


@dataclass(frozen=True)
class Loaded:
    """A ROS 1 ``<rosparam command="load" file>`` outside nodes, as a tree runs it."""

    root: str
    load: ParameterLoad
    path: str  # the launch file that holds it
    namespace: str  # fully qualified, includes' namespaces applied
    conditional: bool


@dataclass(frozen=True)
class _Frame:
    """Where the walk is: the file, and what its includers give it."""

    path: str
    arguments: LaunchArguments
    namespace: str  # prefix for the file's relative namespaces
    remaps: tuple[tuple[Remap, str], ...]
    sites: tuple[Location, ...]
    site_namespaces: tuple[str, ...]
    visiting: frozenset[str]
    conditional: bool = False


@dataclass(frozen=True)
class _Tree:
    """What one root's tree starts and loads, and the facts its walk had from
    ``Specialise`` (a file under its includer's arguments), by path and arguments."""

    launched: tuple[Launched, ...]
    loaded: tuple[Loaded, ...]
    specialised: tuple[tuple[str, LaunchArguments, FileFacts | None], ...] = ()


@dataclass
class _Read:
    """What a walk reads: the files, and what ``Specialise`` gave for each file it asked
    under arguments (a file's own facts may be equal after an edit that changes what it
    starts under them: a node in a group its default arguments turn off)."""

    paths: set[str]
    specialised: dict[tuple[str, LaunchArguments], FileFacts | None]


class LaunchTrees:
    def __init__(
        self,
        index: WorkspaceIndex,
        specialise: Specialise,
        prepare: Prepare | None = None,
        memory: GraphMemory | None = None,
        *,
        roots: Sequence[str] | None = None,
    ) -> None:
        """``memory``: what the last build left (``memory.GraphMemory``): a tree whose
        files did not change is not walked again, and the launch files and the roots are
        the last build's where no changed file differs in what they are made from.
        ``roots``: the trees to walk, where they are known (``workspace.launch_patch``
        walks those an edit reaches); else every root of the workspace."""
        memory = GraphMemory(keeps=False) if memory is None else memory
        self.index = index
        self.specialise = specialise
        self.prepare = prepare
        self._trees = memory.reads("launch trees")
        self.launch_files: list[str] = []  # those a walk of every root starts from
        # Each launch file some launch file's include names -> those launch files, sorted
        self._includers: dict[str, tuple[str, ...]] = {}
        if roots is None:
            self.launch_files = memory.piece(
                "launch files", _LAUNCH_FILE_FIELDS, self._launch_files
            )
            self._includers = memory.piece(
                "launch includers", (*_LAUNCH_FILE_FIELDS, _include_targets), self._find_includers
            )
            roots = [path for path in self.launch_files if path not in self._includers]
        self._roots: list[str] = list(roots)

    def _launch_files(self) -> list[str]:
        return sorted(
            path
            for path, facts in self.index.facts.items()
            if facts.language in LAUNCH_LANGUAGES and runs(self.index, facts)
        )

    def target(self, path: str, include: LaunchInclude) -> str | None:
        """The display path of the file an include names, when the workspace holds it."""
        return self.located(path, include.package, include.path)

    def located(self, path: str, package: str | None, relative: str | None) -> str | None:
        """The display path of the file that the launch file ``path`` names by
        ``package`` and ``relative`` (``LaunchInclude``, ``ParameterLoad``)."""
        if relative is None:
            return None
        if package is not None:
            return self.index.find_in_package(package, relative)
        if relative.startswith("/"):
            return None  # an absolute path outside the run's display paths
        candidate = join(parent(path), relative)
        return candidate if candidate in self.index.facts else None

    def roots(self) -> list[str]:
        return self._roots

    def includers(self) -> dict[str, tuple[str, ...]]:
        """Each file an include of a launch file names, and those launch files: a root
        is a launch file no other includes (``launch_patch`` follows an edited include)."""
        return self._includers

    def _find_includers(self) -> dict[str, tuple[str, ...]]:
        found: dict[str, set[str]] = {}
        for path in self.launch_files:
            for include in self.index.facts[path].includes:
                target = self.target(path, include)
                if target is not None:
                    found.setdefault(target, set()).add(path)
        return {target: tuple(sorted(paths)) for target, paths in sorted(found.items())}

    def is_launch_file(self, path: str) -> bool:
        """Whether ``path`` is a launch file a tool runs: a root where nothing includes it."""
        facts = self.index.facts.get(path)
        return facts is not None and facts.language in LAUNCH_LANGUAGES and runs(self.index, facts)

    def launched(self) -> Iterator[Launched]:
        for _, launched in self.launched_by_root():
            yield from launched

    def launched_by_root(self) -> Iterator[tuple[str, tuple[Launched, ...]]]:
        """Each root and the nodes its tree starts, in order: the same tuple while the
        memory keeps the tree."""
        roots = self.roots()
        for root in roots:  # a kept tree whose specialised files now read otherwise
            kept = self._trees.get(root)
            if kept is not None and not self._same_specialised(kept[0]):
                del self._trees[root]
        if self.prepare is not None:
            walked = [_start(root) for root in roots if root not in self._trees]
            self._prepare_depths(self.prepare, walked)
        for root in roots:
            yield root, self._tree(root).launched

    def loaded(self) -> Iterator[Loaded]:
        """Every group-level ``<rosparam load>`` the trees run."""
        for root in self.roots():
            yield from self._tree(root).loaded

    def _tree(self, root: str) -> _Tree:
        kept = self._trees.get(root)
        if kept is None:
            read = _Read(set(), {})
            launched = tuple(self._walk(root, _start(root), read))
            loaded = tuple(self._loads(root, _start(root), read))
            specialised = tuple(
                (path, arguments, facts) for (path, arguments), facts in read.specialised.items()
            )
            tree = _Tree(launched, loaded, specialised)
            kept = self._trees[root] = (tree, Reads(tuple(read.paths)))
        found: _Tree = kept[0]
        return found

    def visited(self, root: str) -> tuple[str, ...]:
        """The files the tree of ``root`` read (its own, those it includes, whether they
        run or not), sorted: the trees an edit of one of them reaches."""
        self._tree(root)
        return tuple(sorted(self._trees[root][1].paths))

    def _same_specialised(self, tree: _Tree) -> bool:
        """Whether ``Specialise`` gives what it gave ``tree``'s walk (the same object while
        the file is unchanged: a memo hit)."""
        return all(
            (now := self.specialise(path, arguments)) is facts or now == facts
            for path, arguments, facts in tree.specialised
        )

    def _loads(self, root: str, frame: _Frame, read: _Read) -> Iterator[Loaded]:
        facts = self._facts(frame.path, frame.arguments, read)
        if facts is None:
            return
        for load in facts.parameter_loads:
            namespace = _nest(frame.namespace, load.namespace, load.anchored)
            if namespace is not None:
                conditional = frame.conditional or load.conditional
                yield Loaded(root, load, frame.path, namespace, conditional)
        for inner in self._included(frame, facts):
            yield from self._loads(root, inner, read)

    def _prepare_depths(self, prepare: Prepare, frames: list[_Frame]) -> None:
        """Walk the trees depth by depth, handing each depth's specialisations to
        ``prepare`` before asking for them; the walk proper then visits the same frames
        depth first (the order its launched nodes come in)."""
        for wanted in self._depths(frames):
            prepare(wanted)

    def depths(self) -> Iterator[list[tuple[str, LaunchArguments]]]:
        """Each depth of every tree's specialisations, as ``launched`` asks ``prepare``
        for them: the next depth is made once ``specialise`` gives those of the last (a
        run extracting them while the rest of the workspace is, ``speculation.Speculation``)."""
        return self._depths([_start(root) for root in self.roots()])

    def _depths(self, frames: list[_Frame]) -> Iterator[list[tuple[str, LaunchArguments]]]:
        while frames:
            wanted = dict.fromkeys((frame.path, frame.arguments) for frame in frames)
            # A file's specialisations side by side: a worker that parses it for one
            # extracts it under the next arguments from the same parse.
            specialised = [(path, arguments) for path, arguments in wanted if arguments]
            yield sorted(specialised, key=lambda pair: pair[0])
            frames = [
                inner
                for frame in frames
                if (facts := self._facts(frame.path, frame.arguments)) is not None
                for inner in self._included(frame, facts)
            ]

    def _walk(self, root: str, frame: _Frame, read: _Read) -> Iterator[Launched]:
        facts = self._facts(frame.path, frame.arguments, read)
        if facts is None:
            return
        for node in facts.launch_nodes:
            launched = self._node(root, frame, node)
            if launched is not None:
                yield launched
        for inner in self._included(frame, facts):
            yield from self._walk(root, inner, read)

    def _included(self, frame: _Frame, facts: FileFacts) -> Iterator[_Frame]:
        """The frames of the files ``frame``'s file includes that the walk follows."""
        if len(frame.sites) >= MAX_INCLUDE_DEPTH:
            return
        for include in facts.includes:
            target = self.target(frame.path, include)
            if target is None or target in frame.visiting:
                continue
            namespace = _nest(frame.namespace, include.namespace, include.anchored)
            if namespace is None:
                continue  # a namespace we cannot know: no guess about what runs where
            site = Location(frame.path, include.span)
            inner = _Frame(
                path=target,
                arguments=include.arguments,
                namespace=namespace,
                remaps=frame.remaps + tuple((remap, frame.path) for remap in include.remaps),
                sites=(*frame.sites, site),
                site_namespaces=(*frame.site_namespaces, namespace),
                visiting=frame.visiting | {target},
                conditional=frame.conditional or include.conditional,
            )
            yield inner

    def _facts(
        self, path: str, arguments: LaunchArguments, read: _Read | None = None
    ) -> FileFacts | None:
        if read is not None:
            read.paths.add(path)
        facts = self.index.facts.get(path)
        if facts is None or not runs(self.index, facts):
            return None  # included, it stops ros2 launch there: it starts nothing
        if not arguments:
            return facts
        specialised = self.specialise(path, arguments)
        if read is not None:
            read.specialised[(path, arguments)] = specialised
        return specialised

    def _node(self, root: str, frame: _Frame, node: LaunchNode) -> Launched | None:
        namespace = _nest(frame.namespace, node.namespace, node.anchored)
        if namespace is None:
            return None
        own_from = len(node.remaps) - node.own_remaps
        remaps = tuple((remap, path, False) for remap, path in frame.remaps) + tuple(
            (remap, frame.path, index >= own_from) for index, remap in enumerate(node.remaps)
        )
        site = Location(frame.path, node.span)
        return Launched(
            root=root,
            node=node,
            path=frame.path,
            namespace=namespace,
            remaps=remaps,
            sites=(*frame.sites, site),
            site_namespaces=(*frame.site_namespaces, namespace),
            conditional=frame.conditional or node.conditional,
        )


# What decides whether a file is a launch file a tool runs (``runs``), besides where it is
_LAUNCH_FILE_FIELDS = ("language", "generation")


def _include_targets(facts: FileFacts) -> tuple[tuple[str | None, str | None], ...]:
    """What a launch file's includes name: all ``LaunchTrees.roots`` reads of them."""
    return tuple((include.package, include.path) for include in facts.includes)


def _start(root: str) -> _Frame:
    return _Frame(root, (), "/", (), (), (), frozenset({root}))


def runs(index: WorkspaceIndex, facts: FileFacts) -> bool:
    """Whether a launch tool can run the launch file: not a roslaunch (ROS 1) file left in
    a ROS 2 package, as moveit2's ``generate_state_database.launch``.

    ros2 launch does read a ``.launch`` file (launch_xml's ``Parser.get_file_extensions``:
    ``launch.xml``, ``xml``, ``launch``), but what makes a file ROS 1 to the extractor
    (``evidence.launch_xml_evidence``) stops it: launch_ros's ``Node.parse`` reads
    ``entity.get_attr('exec')``, not optional, so ``<node type=...>`` raises, and an
    action's unread ``type`` attribute fails ``assert_entity_completely_parsed``
    (launch's ``frontend/expose.py``); ``$(arg)`` and ``$(find)`` are no substitutions
    it knows (``instantiate_substitution``: 'Unknown substitution'). And roslaunch has
    no program of the package to start: no ROS 1 build (catkin) makes an ament package's
    programs, rclcpp code at that. Its nodes would join the graph bound to the ROS 2
    code of the package's executables."""
    if facts.language is not Language.LAUNCH_XML or facts.generation is not Generation.ROS1:
        return True
    package = index.package_of(facts.path)
    return package is None or package.generation is not Generation.ROS2


def _nest(prefix: str, namespace: str, anchored: bool) -> str | None:
    """A file's namespace (rooted at "/") inside the namespace its includer pushed."""
    if not namespace:
        return None  # dynamic
    if anchored or prefix == "/":
        return namespace
    # join_namespace takes a generation it does not use: both nest alike.
    return join_namespace(prefix, namespace.lstrip("/"), Generation.ROS2)

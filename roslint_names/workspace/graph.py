"""The static computation graph: node instances and the endpoints they declare.

Values only, built by ``workspace.build`` from the facts of every file; the graph rules
(RN401-RN404) and the ``graph`` command's renderers read it. Everything is sorted, so two
runs over one tree give equal graphs.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from enum import Enum
from typing import TYPE_CHECKING, Protocol

from roslint_names.model import Compact, Generation, Kind, ParameterBlock, Remap, Span
from roslint_names.workspace.interfaces import ServiceDefinition

if TYPE_CHECKING:  # parameters.py builds on Location: no import cycle at run time
    from roslint_names.workspace.parameters import NodeParameters, WorkspaceDeclarations


@dataclass(frozen=True, order=True, slots=True)
class Location(Compact):
    """A place in a file of the run: a display path and a span."""

    path: str
    span: Span


class EdgeKind(str, Enum):
    """What a node does with a topic, service or action."""

    PUBLISH = "publish"
    SUBSCRIBE = "subscribe"
    SERVE = "serve"
    CALL = "call"
    ACTION_SERVE = "action-serve"
    ACTION_CALL = "action-call"


@dataclass(frozen=True, order=True, slots=True)
class Reach(Compact):
    """What decides which other nodes a node can exchange messages with.

    Two nodes can meet when one launch tree starts both, or when nothing keeps them apart
    and the workspace says their packages run together (``Graph.can_meet``). A tree a test
    starts (rostest's ``.test``, a ``test_*`` launch test, a file under ``test/``) is
    ``isolated``: rostest gives each its own master and launch tests their own domain.
    ``packages`` are the node's code's package and the packages of the launch files that
    start it.
    """

    generation: Generation
    isolated: bool = False
    packages: tuple[str, ...] = ()


class Placed(Protocol):
    """A node or an endpoint: something with a launch tree and a reach."""

    @property
    def root(self) -> str: ...

    @property
    def reach(self) -> Reach: ...


@dataclass(frozen=True, order=True, slots=True)
class NodeRemap(Remap):
    """A remap applied to one node: both sides fully qualified, where it is written, the
    target as written there (RN201 judges what the node's namespace makes of it), and
    whether it is the node's own (RN404 judges only those: a group's remap is meant for
    whichever of its nodes uses the name)."""

    path: str = ""
    own: bool = False
    written_target: str = ""


@dataclass(frozen=True, order=True, slots=True)
class ParameterFileUse(Compact):
    """A parameter file of the workspace that a launch file hands a node, or (ROS 1)
    loads into a namespace.

    ``path`` is the file's display path; ``site`` the reference in the launch file
    (``parameters=[...]``'s item, ``<param from>``, ``<rosparam file>``). ``namespace``
    (ROS 1) is where its names are loaded, fully qualified. ``names`` are the parameters
    it sets there: ROS 2, those of its node keys that match the node
    (``workspace.parameters``), as the node names them; ROS 1, fully qualified.
    """

    path: str
    site: Location
    namespace: str = ""
    names: tuple[str, ...] = ()
    conditional: bool = False


class SettingSource(str, Enum):
    """How a launch sets a parameter on a node."""

    LAUNCH = "launch"  # the node's <param>, its parameters={...}, -p or _name:= on its line
    FILE = "file"  # a parameter file handed to the node or (ROS 1) loaded into its namespace


@dataclass(frozen=True, slots=True)
class ParameterSetting(Compact):
    """A parameter a launch sets on a node: its name as the node reads it (ROS 2: dotted;
    ROS 1: relative to the node's private namespace when below it, else fully
    qualified), where the name is written (the ``<param name>``, dictionary key or
    command-line key; a parameter file's key), and for a file the node key it is under
    (ROS 2) and where the launch hands the file over."""

    name: str
    location: Location
    source: SettingSource
    key: str | None = None
    site: Location | None = None
    conditional: bool = False

    def sort_key(self) -> tuple[str, Location, str]:
        return (self.name, self.location, self.source.value)


@dataclass(frozen=True, slots=True)
class NodeInstance(Compact):
    """One node as it runs: launched by a launch tree, or code no launch file starts.

    ``name`` is fully qualified (``/robot1/driver``). ``launched_at`` is the chain of launch
    sites that start it, outermost include first and the ``<node>`` itself last; empty for
    code no launch file starts (resolved in the root namespace with its own node name).
    ``root`` is the display path of the launch file the tree starts from ("" when not
    launched). ``sources`` are the display paths of the code it runs, empty when that code
    is not in the workspace.
    """

    name: str
    generation: Generation
    package: str | None
    executable: str | None
    root: str
    launched_at: tuple[Location, ...]
    sources: tuple[str, ...]
    remaps: tuple[NodeRemap, ...] = ()
    # The namespace in force after each launch site of ``launched_at`` (RN201 blames the
    # site that pushes a name over the depth limit).
    launch_namespaces: tuple[str, ...] = ()
    # Every name the node's code uses, fully qualified but before remapping (RN404), and
    # whether that list is complete (false when some name is dynamic). Names used through
    # a handle whose namespace the code does not show are in ``uses_relative`` as written:
    # they may sit in any namespace.
    uses: tuple[str, ...] = ()
    uses_complete: bool = False
    uses_relative: tuple[str, ...] = ()
    # ROS 2 only: the parameter names the code shows statically. No remap renames one
    # (rcl remaps topics, services, the node's name and namespace), so they are no
    # ``uses``; they show that the linter sees the node's code (RN404).
    parameters: tuple[str, ...] = ()
    # What the node's code declares and reads, and whether that is all (RN407).
    code_parameters: NodeParameters | None = None
    # ``code_parameters.derives_elsewhere``, kept where the graph keeps no parameters
    # (``patch.for_patching``): code runs in the node whose names it does not show (RN404).
    derives_elsewhere: bool = False
    conditional: bool = False  # started under a condition the linter cannot decide
    named_at_launch: bool = False  # the launch file gives its name, not its code
    # The parameter files the launch hands it (ROS 1: loads into its private namespace).
    parameter_files: tuple[ParameterFileUse, ...] = ()
    composable: bool = False  # a component loaded into a container (launch_ros matches)
    # Every parameter the launch sets on it, by name then place.
    parameter_settings: tuple[ParameterSetting, ...] = ()
    test: bool = False  # a rostest ``<test>``: run alone, after the nodes are up
    # Its code is test code (``rospy/test_nodes/talker.py``) though no test starts it: a
    # test's stand-in that an example or a showcase of launch syntax borrows.
    stand_in: bool = False
    reach: Reach = Reach(Generation.ROS2)

    def sort_key(self) -> tuple[str, str, tuple[Location, ...], tuple[str, ...]]:
        return (self.name, self.root, self.launched_at, self.sources)


@dataclass(frozen=True, slots=True)
class Endpoint(Compact):
    """A node publishing, subscribing, serving or calling one resolved name.

    ``resource`` is fully qualified, after the node's namespace and remaps. ``type_name``
    is canonical (``std_msgs/String``; ``String`` when the code omits the package), None
    when unknown. ``location`` is the name in the code; ``written`` is the name as the code
    wrote it.
    """

    resource: str
    resource_kind: Kind  # TOPIC, SERVICE or ACTION
    edge: EdgeKind
    node: str  # NodeInstance.name
    root: str  # NodeInstance.root: endpoints of one launch tree meet each other
    type_name: str | None
    location: Location
    written: str
    reach: Reach = Reach(Generation.ROS2)  # the node's
    # False when the code uses the name through a handle whose namespace it does not show
    # (``NodeHandle nh("~/" + name)``): ``resource`` is then a guess, in the node's
    # namespace. The graph shows it; the rules do not judge it.
    certain: bool = True

    def sort_key(self) -> tuple[str, str, str, str, str, Location, str]:
        return (
            self.resource,
            self.resource_kind.value,
            self.edge.value,
            self.node,
            self.root,
            self.location,
            self.type_name or "",
        )


@dataclass(frozen=True, slots=True)
class UnnamedReceiver(Compact):
    """A node of unknown name a parameter file is handed to: any key may be its, but it
    keeps only what its code may take."""

    generation: Generation
    parameters: NodeParameters


@dataclass(frozen=True, slots=True)
class Graph(Compact):
    nodes: tuple[NodeInstance, ...]
    endpoints: tuple[Endpoint, ...]
    # package -> the packages it is meant to run with (``WorkspaceIndex.companions``)
    companions: Mapping[str, frozenset[str]] = field(default_factory=dict)
    # package -> name-shaped string literals of its code, for the packages of nodes with
    # remaps of their own: evidence of names used through APIs the linter does not know
    mentions: Mapping[str, frozenset[str]] = field(default_factory=dict)
    # ``package/Name`` -> the definition of a ROS 1 service type (RN403 compares ROS 1
    # services by it, as roscpp and rospy do by its md5sum)
    service_definitions: Mapping[str, ServiceDefinition] = field(default_factory=dict)
    # display path -> the blocks of each parameter file a launch file hands a node or loads
    parameter_files: Mapping[str, tuple[ParameterBlock, ...]] = field(default_factory=dict)
    # ROS 1 ``<rosparam command="load" file>`` outside any node, with its namespace
    parameter_loads: tuple[ParameterFileUse, ...] = ()
    # Parameter files handed to a launched node whose name the linter does not know
    # (``$(anon x)``, an argument, a name its code does not show): which of their keys
    # that node reads is unknown; what its code may take is known as far as its code is.
    unnamed_parameter_files: Mapping[str, tuple[UnnamedReceiver, ...]] = field(default_factory=dict)
    # Every parameter the workspace's ROS 2 code declares (RN407: a name declared nowhere
    # cannot have been declared by a helper the linter does not follow)
    parameter_declarations: WorkspaceDeclarations | None = None

    def can_meet(self, one: Placed, other: Placed) -> bool:
        """Whether two nodes (or their endpoints) can be in one ROS graph at run time.

        A workspace holds many systems never run together (tutorials, demos, tests of other
        packages): a name shared by two of them is no conflict. One launch tree is one
        system; a test's tree meets nothing else; ROS 1 and ROS 2 never meet; otherwise
        the packages decide, and code outside any package meets only such code.
        """
        if one.reach.generation is not other.reach.generation:
            return False
        if one.root and one.root == other.root:
            return True
        if one.reach.isolated or other.reach.isolated:
            return False
        mine, theirs = one.reach.packages, other.reach.packages
        if not mine or not theirs:
            return not mine and not theirs
        return any(
            package in self.companions.get(own, (own,)) for own in mine for package in theirs
        )

    def resources(self, kind: Kind) -> list[str]:
        """Every resolved name of one kind, sorted."""
        return sorted({e.resource for e in self.endpoints if e.resource_kind is kind})


def launched_by(graph: Graph, launch_files: frozenset[str]) -> Graph:
    """The part of ``graph`` that the launch files (display paths) start: the node
    instances whose launch chain (its first site is in the tree's root) passes through one
    of them, a file included by another drawn as its includers launch it, and those
    nodes' endpoints."""
    nodes = tuple(
        node for node in graph.nodes if any(site.path in launch_files for site in node.launched_at)
    )
    kept = {(node.name, node.root) for node in nodes}
    endpoints = tuple(e for e in graph.endpoints if (e.node, e.root) in kept)
    return replace(graph, nodes=nodes, endpoints=endpoints)

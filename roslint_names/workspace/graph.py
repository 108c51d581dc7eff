"""The static computation graph: node instances and the endpoints they declare.

Values only, built by ``workspace.build`` from the facts of every file; the graph rules
(RN401-RN404) and the ``graph`` command's renderers read it. Everything is sorted, so two
runs over one tree give equal graphs.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from roslint_names.model import Generation, Kind, Remap, Span


@dataclass(frozen=True, order=True)
class Location:
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


@dataclass(frozen=True, order=True)
class NodeRemap(Remap):
    """A remap applied to one node: both sides fully qualified, where it is written, and
    whether it is the node's own (RN404 judges only those: a group's remap is meant for
    whichever of its nodes uses the name)."""

    path: str = ""
    own: bool = False


@dataclass(frozen=True)
class NodeInstance:
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
    conditional: bool = False  # started under a condition the linter cannot decide

    def sort_key(self) -> tuple[str, str, tuple[Location, ...], tuple[str, ...]]:
        return (self.name, self.root, self.launched_at, self.sources)


@dataclass(frozen=True)
class Endpoint:
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


@dataclass(frozen=True)
class Graph:
    nodes: tuple[NodeInstance, ...]
    endpoints: tuple[Endpoint, ...]

    def resources(self, kind: Kind) -> list[str]:
        """Every resolved name of one kind, sorted."""
        return sorted({e.resource for e in self.endpoints if e.resource_kind is kind})

"""The graph as the drawing renderers (DOT, Mermaid) see it: shapes with ids, collapsed arrows.

Both drawings need the same decisions, made once here so that they cannot drift apart:

* One shape per node instance, keyed by ``(name, root)``: two launch trees may each start a
  ``/talker``, and those are two processes, not one. A node that endpoints name but the
  graph does not list still gets a shape, so that no arrow points at nothing.
* One shape per resource, keyed by ``(kind, name)``. Its types are the distinct known types
  its endpoints declare; more than one means they disagree.
* Ids are a letter and an index in sorted order (``n0`` nodes, ``t0`` topics, ``s0``
  services, ``a0`` actions): ROS names hold ``/``, ``~`` and ``{}``, which neither format
  accepts in an id, and sorted indices make the output the same for the same graph.
* A node lists the parameters the launch sets on it (``NodeInstance.parameter_settings``),
  ``MAX_PARAMETERS`` at most, then how many more: a drawing stays readable with
  navigation2's hundred-odd parameters per server; the JSON output has them all.
* Arrows follow the data: publisher -> topic -> subscriber, client -> service -> server,
  action client -> action -> action server. Endpoints with the same node, resource and edge
  kind collapse to one arrow that keeps all their locations.
* Where the graph holds more than one launch tree, each tree's nodes are drawn in a box
  labelled with its launch file (``Drawing.clusters``): a package's alternative launch
  files (rplidar_ros' fourteen ``/rplidarNode``) are then alternatives side by side, not
  one crowd. Nodes no launch file starts stay outside every box, and so do the topics,
  which the trees may share.
"""

from __future__ import annotations

import unicodedata
from collections import defaultdict
from collections.abc import Iterable
from dataclasses import dataclass

from ..model import Kind
from ..workspace.graph import EdgeKind, Endpoint, Graph, Location, NodeInstance

# The edge kinds whose data flows from the node to the resource; the others flow back.
_OUTGOING = frozenset({EdgeKind.PUBLISH, EdgeKind.CALL, EdgeKind.ACTION_CALL})
_KIND_ORDER = (Kind.TOPIC, Kind.SERVICE, Kind.ACTION)
_PREFIX = {Kind.TOPIC: "t", Kind.SERVICE: "s", Kind.ACTION: "a"}
_EXTRA_PREFIX = "r"  # a resource kind the graph should not hold; drawn rather than dropped
MISMATCH_NOTE = "(types disagree)"
MAX_PARAMETERS = 5  # parameter lines in a node's label before "and K more"


@dataclass(frozen=True)
class NodeShape:
    ident: str
    name: str
    root: str
    instance: NodeInstance | None  # None: named by endpoints only

    @property
    def lines(self) -> tuple[str, ...]:
        """The label, one entry per line, unescaped: the name, ``package/executable``,
        and the parameters the launch sets on it."""
        what = _package_executable(self.instance)
        head = (self.name, what) if what else (self.name,)
        return head + parameter_lines(self.instance)


@dataclass(frozen=True)
class ResourceShape:
    ident: str
    kind: Kind
    name: str
    types: tuple[str, ...]  # distinct known types, sorted; empty when none is known

    @property
    def mismatch(self) -> bool:
        return len(self.types) > 1

    @property
    def lines(self) -> tuple[str, ...]:
        note = (MISMATCH_NOTE,) if self.mismatch else ()
        return (self.name, *self.types, *note)


@dataclass(frozen=True)
class Arrow:
    tail: str  # shape id the data leaves
    head: str  # shape id the data reaches
    edge: EdgeKind
    endpoints: tuple[Endpoint, ...]  # every endpoint collapsed into it, by location

    @property
    def label(self) -> str:
        return edge_label(self.edge)


@dataclass(frozen=True)
class Drawing:
    nodes: tuple[NodeShape, ...]
    resources: tuple[ResourceShape, ...]
    arrows: tuple[Arrow, ...]

    def clusters(self) -> tuple[tuple[str, tuple[NodeShape, ...]], ...]:
        """(launch file, its nodes) for each launch tree, in path order, when there are
        several; empty when there is at most one tree to draw."""
        roots: dict[str, list[NodeShape]] = defaultdict(list)
        for node in self.nodes:
            if node.root:
                roots[node.root].append(node)
        if len(roots) < 2:
            return ()
        return tuple((root, tuple(roots[root])) for root in sorted(roots))

    def unclustered(self) -> tuple[NodeShape, ...]:
        """The nodes drawn outside every box: all of them when there are no boxes."""
        if not self.clusters():
            return self.nodes
        return tuple(node for node in self.nodes if not node.root)


def layout(graph: Graph) -> Drawing:
    nodes = _node_shapes(graph)
    resources = _resource_shapes(graph.endpoints)
    return Drawing(nodes, resources, _arrows(graph.endpoints, nodes, resources))


def edge_label(edge: EdgeKind) -> str:
    """``action call`` rather than ``action-call``: a Mermaid edge text reads ``-`` as a link."""
    return edge.value.replace("-", " ")


def where(location: Location) -> str:
    """``path:line:column``, the form editors and terminals turn into a link."""
    return f"{location.path}:{location.span.line}:{location.span.column}"


def one_line(text: str) -> str:
    """``text`` with every line break and control character made a space.

    Comments in both formats end at a line break, so a path or name holding one would
    otherwise end the comment early and leave the rest to the parser.
    """
    return "".join(" " if unicodedata.category(c) in {"Cc", "Zl", "Zp"} else c for c in text)


def node_summary(shape: NodeShape) -> str:
    """Where a node comes from, for a comment or tooltip: launch chain, else its sources;
    and the files that set its parameters."""
    instance = shape.instance
    if instance is None:
        return "not in the graph's node list"
    parts = []
    if instance.launched_at:
        parts.append("launched at " + " > ".join(where(loc) for loc in instance.launched_at))
    else:
        parts.append("not launched")
    if instance.sources:
        parts.append("sources " + ", ".join(instance.sources))
    files = sorted({setting.location.path for setting in instance.parameter_settings})
    if files:
        parts.append("parameters from " + ", ".join(files))
    return "; ".join(parts)


def parameter_lines(instance: NodeInstance | None) -> tuple[str, ...]:
    """``param NAME`` for each parameter the launch sets on the node, by name, at most
    ``MAX_PARAMETERS``, then ``and K more parameters``."""
    if instance is None:
        return ()
    names = sorted({setting.name for setting in instance.parameter_settings})
    shown = tuple(f"param {name}" for name in names[:MAX_PARAMETERS])
    more = len(names) - len(shown)
    return shown + ((f"and {more} more parameter{'s' if more > 1 else ''}",) if more else ())


def endpoint_summary(endpoint: Endpoint) -> str:
    """One endpoint for a comment: where it is and the name as the code wrote it."""
    return f"{where(endpoint.location)} written {endpoint.written!r}"


def _package_executable(instance: NodeInstance | None) -> str:
    if instance is None or (instance.package is None and instance.executable is None):
        return ""
    return f"{instance.package or '?'}/{instance.executable or '?'}"


def _node_shapes(graph: Graph) -> tuple[NodeShape, ...]:
    instances: dict[tuple[str, str], NodeInstance] = {}
    for instance in graph.nodes:
        instances.setdefault((instance.name, instance.root), instance)
    keys = set(instances) | {(e.node, e.root) for e in graph.endpoints}
    return tuple(
        NodeShape(f"n{index}", name, root, instances.get((name, root)))
        for index, (name, root) in enumerate(sorted(keys))
    )


def _kind_rank(kind: Kind) -> int:
    return _KIND_ORDER.index(kind) if kind in _KIND_ORDER else len(_KIND_ORDER)


def _resource_shapes(endpoints: Iterable[Endpoint]) -> tuple[ResourceShape, ...]:
    types: dict[tuple[Kind, str], set[str]] = defaultdict(set)
    for endpoint in endpoints:
        known = types[(endpoint.resource_kind, endpoint.resource)]
        if endpoint.type_name is not None:
            known.add(endpoint.type_name)
    ordered = sorted(types, key=lambda key: (_kind_rank(key[0]), key[0].value, key[1]))
    counters: dict[str, int] = defaultdict(int)
    shapes = []
    for kind, name in ordered:
        prefix = _PREFIX.get(kind, _EXTRA_PREFIX)
        shapes.append(
            ResourceShape(
                f"{prefix}{counters[prefix]}", kind, name, tuple(sorted(types[kind, name]))
            )
        )
        counters[prefix] += 1
    return tuple(shapes)


def endpoint_order(endpoint: Endpoint) -> tuple[str, int, int, int, int, str, str]:
    """A total order on endpoints that never compares None with a string."""
    span = endpoint.location.span
    return (
        endpoint.location.path,
        span.line,
        span.column,
        span.end_line,
        span.end_column,
        endpoint.written,
        endpoint.type_name or "",
    )


def _arrows(
    endpoints: Iterable[Endpoint],
    nodes: tuple[NodeShape, ...],
    resources: tuple[ResourceShape, ...],
) -> tuple[Arrow, ...]:
    node_index = {(shape.name, shape.root): index for index, shape in enumerate(nodes)}
    resource_index = {(shape.kind, shape.name): index for index, shape in enumerate(resources)}
    groups: dict[tuple[int, int, EdgeKind], list[Endpoint]] = defaultdict(list)
    for endpoint in endpoints:
        node = node_index[(endpoint.node, endpoint.root)]
        resource = resource_index[(endpoint.resource_kind, endpoint.resource)]
        groups[(node, resource, endpoint.edge)].append(endpoint)
    arrows = []
    for node, resource, edge in sorted(groups, key=lambda key: (key[0], key[1], key[2].value)):
        ends = (nodes[node].ident, resources[resource].ident)
        tail, head = ends if edge in _OUTGOING else ends[::-1]
        collapsed = tuple(sorted(groups[(node, resource, edge)], key=endpoint_order))
        arrows.append(Arrow(tail, head, edge, collapsed))
    return tuple(arrows)

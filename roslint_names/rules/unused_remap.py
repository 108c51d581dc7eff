"""RN404 unused-remap: a node's remap whose ``from`` its code never uses.

A remap that matches nothing is silently ignored: usually the name was misspelled
(``<remap from="cmd_vel" .../>`` for a node that publishes ``cmd_vel_out``), changed in
the code later, or written relative when the code uses a private name. Only a node's own
remaps are judged (a group's remap is meant for whichever of its nodes uses the name),
only when the node's code is in the workspace and every name it uses that a remap could
rename is known statically: in ROS 2 not its parameters, which rcl never remaps (a remap
of one is reported, saying so).
A remap of a name's parent or child counts as used: actions and image_transport derive
sub-topics (``move_base/goal``, ``image/compressed``) from the name the code gives; so does
a ``camera_info`` beside a topic the node uses (image_transport's camera publishers). So does
a remap of a name the client library uses for the node (``/tf``, ``/tf_static``,
``/clock``...): no code of the node spells it. And so does a name that a string literal of
the node's package spells (a header, a wrapper the linter does not know): that is evidence
the code uses it somehow.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator

from ..model import Severity
from ..rule import Rule, RuleContext, WorkspaceFinding
from ..workspace.graph import Graph, Location, NodeInstance, NodeRemap
from .graph_common import finding
from .hard_coded_absolute_name import GLOBAL_BY_DESIGN

_MAX_LISTED = 5


# Names the client libraries use on the node's behalf (tf listeners, the clock, logging,
# parameter events): remapping them is the classic multi-robot pattern, never unused.
_LIBRARY_NAMES = frozenset(name.rpartition("/")[2] for name in GLOBAL_BY_DESIGN)


def _used(remap: NodeRemap, node: NodeInstance, mentions: frozenset[str]) -> bool:
    source = remap.source.rstrip("/")
    if source.rpartition("/")[2] in _LIBRARY_NAMES:
        return True
    if any(
        use == source or use.startswith(source + "/") or source.startswith(use + "/")
        for use in node.uses
    ):
        return True
    # Through a handle whose namespace the code does not show, a name may sit anywhere.
    if any(f"/{written.strip('/~')}/" in f"{source}/" for written in node.uses_relative):
        return True
    if _parameter_named(source, node) is not None:
        return False  # the literal that spells it is the parameter's name: rcl remaps none
    # A name-shaped literal of the package's code, passed to an API we do not know,
    # resolves to the name when it is the name, a private or relative ending of it.
    if source in mentions or any(
        spelled in mentions
        for tail in _endings(source)
        for spelled in (tail, f"~{tail}", f"~/{tail}")
    ):
        return True
    return _camera_info_beside(source, node, mentions)


def _camera_info_beside(source: str, node: NodeInstance, mentions: frozenset[str]) -> bool:
    """image_transport's camera publishers and subscribers derive ``camera_info`` beside
    the image topic (``image_raw`` -> ``camera_info``): a remap of it is used when the node
    uses, or its package spells, a topic in the same namespace (image_pipeline's
    image_publisher hands ``"image_raw"`` to ``create_camera_publisher``)."""
    namespace, _, last = source.rpartition("/")
    if last != "camera_info":
        return False
    if any(use.rpartition("/")[0] == namespace for use in node.uses if use != source):
        return True
    node_namespace = node.name.rpartition("/")[0]
    relative = (m for m in mentions if m and m[0] not in "/~" and "/" not in m)
    return namespace == node_namespace and any(m != last for m in relative)


def _endings(name: str) -> list[str]:
    """Every ending of a name in whole tokens: ``/a/b/c`` gives ``c``, ``b/c``, ``a/b/c``."""
    tokens = name.strip("/").split("/")
    return ["/".join(tokens[start:]) for start in range(len(tokens))]


def check_workspace(graph: Graph, context: RuleContext) -> Iterator[WorkspaceFinding]:
    del context
    verdicts: dict[Location, list[tuple[bool, NodeRemap, NodeInstance]]] = defaultdict(list)
    for node in graph.nodes:
        if not node.uses_complete or node.derives_elsewhere or "::" in (node.executable or ""):
            # Code we cannot see all of: a remap may rename what we miss. A base class of
            # another package's code may use the name (autoware's ground filters
            # subscribe ``input`` through ``pointcloud_preprocessor::Filter``). A
            # component plugin's names are spread over its library (autoware's
            # planners), which the build files do not tie to the class.
            continue
        if not node.uses and not node.parameters:
            continue  # code that shows no name at all: it uses APIs we do not know
        for remap in node.remaps:
            if remap.own:
                location = Location(remap.path, remap.span)
                mentions = graph.mentions.get(node.package or "", frozenset())
                verdicts[location].append((_used(remap, node, mentions), remap, node))
    for location, seen in sorted(verdicts.items()):
        if any(used for used, _, _ in seen):
            continue  # used by one start of the node: the remap does its job there
        _, remap, node = seen[0]
        parameter = _parameter_named(remap.source, node)
        if parameter is not None:
            message = (
                f"remap from '{remap.source}' renames nothing: '{parameter}' is a parameter "
                f"of node '{node.name}' ({', '.join(node.sources)}), and ROS 2 remaps "
                "topic and service names, never parameters; set the parameter instead"
            )
        else:
            message = (
                f"remap from '{remap.source}' renames nothing: node '{node.name}' "
                f"({', '.join(node.sources)}) never uses that name{_what_it_uses(node)}"
            )
        related = [
            (endpoint.location, f"{endpoint.resource_kind.value} '{endpoint.written}'")
            for endpoint in graph.endpoints
            if endpoint.node == node.name and endpoint.root == node.root
        ]
        yield finding(location, message, related)


def _parameter_named(source: str, node: NodeInstance) -> str | None:
    """The ROS 2 parameter of the node a remap's ``from`` names (a ROS 1 habit:
    ``<remap from="~output_folder" .../>``), if any: rcl never remaps one."""
    namespace = node.name.rpartition("/")[0]
    written = source.lstrip("~").strip("/")  # a name rcl refuses is kept as written
    for parameter in node.parameters:
        path = parameter.strip("~/").replace(".", "/")
        if path and path in (written, *_tails(source, node.name, namespace)):
            return parameter
    return None


def _tails(source: str, *namespaces: str) -> list[str]:
    """What is left of ``source`` below each of ``namespaces`` it is in."""
    return [source[len(ns) + 1 :] for ns in namespaces if source.startswith(f"{ns}/")]


def _what_it_uses(node: NodeInstance) -> str:
    if not node.uses:
        return ""  # its names go through APIs the linter does not know; they are not listed
    listed = ", ".join(f"'{use}'" for use in node.uses[:_MAX_LISTED])
    more = f" and {len(node.uses) - _MAX_LISTED} more" if len(node.uses) > _MAX_LISTED else ""
    return f"; it uses {listed}{more}"


RULE = Rule(
    code="RN404",
    name="unused-remap",
    summary="A node's remap whose from name the node's code never uses",
    severity=Severity.WARNING,
    check=None,
    check_workspace=check_workspace,
)

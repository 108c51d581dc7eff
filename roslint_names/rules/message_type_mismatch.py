"""RN403 message-type-mismatch: one resolved topic, service or action, two types.

A publisher and a subscriber of one topic with different message types never exchange a
message (ROS 1 refuses the connection on the md5sum, ROS 2 on the type name), and nothing
fails loudly. Only endpoints that can be in one ROS graph are compared (``Graph.can_meet``:
one launch tree, or packages meant to run together), and only names the linter knows.
Types are compared in one canonical spelling (``std_msgs::msg::String``, ``std_msgs/String``
and ``std_msgs.msg.String`` are one type); a type the code names without its package
matches any package's type of that name. ROS 1 services are compared by their definition,
as roscpp and rospy compare the md5sum of it (``workspace.interfaces``): two names of one
definition connect, and a type whose definition the workspace does not hold is no mismatch.

Code that uses one name with two types on one side (two publishers, one chosen at run time)
leaves only those endpoints out: its other endpoints, and the other side of that name, are
compared like any other.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator, Mapping

from ..model import Generation, Kind, Severity
from ..rule import Rule, RuleContext, WorkspaceFinding
from ..workspace.graph import EdgeKind, Endpoint, Graph, Location
from ..workspace.interfaces import ServiceDefinition
from .graph_common import finding, where


def _comparable(endpoint: Endpoint) -> bool:
    """A type we can hold against another, on a name we know.

    Not one the code names without its package: in C++ that is nearly always an alias or
    a template parameter (``using Action = nav2_msgs::action::FollowPath``, ``ActionT``)
    declared where we do not look.
    """
    return endpoint.certain and endpoint.type_name is not None and "/" in endpoint.type_name


def _alternatives(endpoints: list[Endpoint]) -> set[tuple[str, str, str, EdgeKind]]:
    """(root, node, file, side) of code that uses the name with two types on one side
    itself: code that picks one at run time (``TwistStamped`` on Jazzy, ``Twist``
    before), not a mismatch. Only those endpoints are ambiguous: a subscriber of the same
    code, or a publisher with another type than its own subscriber of the name (the
    publisher never reaches it), is certain."""
    types: dict[tuple[str, str, str, EdgeKind], set[str]] = defaultdict(set)
    for endpoint in endpoints:
        types[_code_of(endpoint)].add(endpoint.type_name or "")
    return {code for code, found in types.items() if len(found) > 1}


def _code_of(endpoint: Endpoint) -> tuple[str, str, str, EdgeKind]:
    return (endpoint.root, endpoint.node, endpoint.location.path, endpoint.edge)


def _same_type(one: str, other: str) -> bool:
    if one == other:
        return True
    if "/" in one and "/" in other:
        return False
    return one.rpartition("/")[2] == other.rpartition("/")[2]


# ROS 1 types that connect to any type: their md5sum is "*", which roscpp's publisher
# accepts (``Publication::validateHeader`` in ``clients/roscpp/src/libros/publication.cpp``):
# topic_tools' ``ShapeShifter`` (``MD5Sum<ShapeShifter>`` in ``shape_shifter.h``) and
# rospy's ``AnyMsg`` (``_md5sum = TOPIC_ANYTYPE`` in ``clients/rospy/src/rospy/msg.py``).
_ANY_TYPE_ROS1 = frozenset({"topic_tools/ShapeShifter", "rospy/AnyMsg"})


class _Types:
    """Whether two endpoints' types connect: by name, and a ROS 1 service's by its
    definition (roscpp's ``ServiceClientLink::handleHeader`` and rospy's
    ``service_connection_handler`` refuse a client whose md5sum differs, whatever the
    type is called)."""

    def __init__(self, definitions: Mapping[str, ServiceDefinition]) -> None:
        self._definitions = definitions

    def compatible(self, one: Endpoint, other: Endpoint) -> bool:
        mine, theirs = one.type_name or "", other.type_name or ""
        if mine == theirs:
            return True
        if one.reach.generation is Generation.ROS1 and _ANY_TYPE_ROS1 & {mine, theirs}:
            return True
        if _ros1_service(one) and _ros1_service(other):
            known = self._definitions.get(mine), self._definitions.get(theirs)
            if known[0] is None or known[1] is None:
                return True  # a definition the workspace does not hold: nothing is known
            return known[0].same_md5(known[1]) is not False
        return _same_type(mine, theirs)

    def incompatible(self, endpoints: list[Endpoint]) -> dict[int, list[Endpoint]]:
        """The endpoints of one name whose types do not connect to all of the others', by
        ``id``, each with the endpoints it does not connect to; empty where every two
        connect. Compared a type against a type (the types of one name and generation
        are few), not an endpoint against an endpoint."""
        kinds: dict[tuple[str, Generation], list[Endpoint]] = {}
        for endpoint in endpoints:
            kinds.setdefault((endpoint.type_name or "", endpoint.reach.generation), []).append(
                endpoint
            )
        found: dict[int, list[Endpoint]] = {}
        for mine in kinds.values():
            others = [
                other
                for theirs in kinds.values()
                if not self.compatible(mine[0], theirs[0])
                for other in theirs
            ]
            if others:
                found.update((id(endpoint), others) for endpoint in mine)
        return found


def _ros1_service(endpoint: Endpoint) -> bool:
    return endpoint.reach.generation is Generation.ROS1 and endpoint.resource_kind is Kind.SERVICE


_OPPOSITE = {
    EdgeKind.PUBLISH: EdgeKind.SUBSCRIBE,
    EdgeKind.SUBSCRIBE: EdgeKind.PUBLISH,
    EdgeKind.SERVE: EdgeKind.CALL,
    EdgeKind.CALL: EdgeKind.SERVE,
    EdgeKind.ACTION_SERVE: EdgeKind.ACTION_CALL,
    EdgeKind.ACTION_CALL: EdgeKind.ACTION_SERVE,
}


def _facing(one: Endpoint, other: Endpoint) -> bool:
    """Endpoints whose types must agree: the two sides of a name (a publisher and a
    subscriber), or one side twice in one launch tree (two publishers a subscriber must
    choose between). Two programs no launch file starts that both publish ``output``
    (perception_pcl's bag and PCD tools) are not known to run together: that relative
    name is what each is remapped by when started by hand."""
    return _OPPOSITE[one.edge] is other.edge or (bool(one.root) and one.root == other.root)


_DONE = {
    EdgeKind.PUBLISH: "published",
    EdgeKind.SUBSCRIBE: "subscribed",
    EdgeKind.SERVE: "served",
    EdgeKind.CALL: "called",
    EdgeKind.ACTION_SERVE: "served",
    EdgeKind.ACTION_CALL: "called",
}


_WHY = {
    False: "the two never connect",
    True: "their definitions differ, and a server refuses a client whose md5sum is not its own",
}


def check_workspace(graph: Graph, context: RuleContext) -> Iterator[WorkspaceFinding]:
    del context
    types = _Types(graph.service_definitions)
    by_resource: dict[tuple[Kind, str], list[Endpoint]] = defaultdict(list)
    for endpoint in graph.endpoints:
        if _comparable(endpoint):
            by_resource[(endpoint.resource_kind, endpoint.resource)].append(endpoint)
    reported: set[Location] = set()
    for (kind, resource), found in sorted(by_resource.items()):
        switching = _alternatives(found)
        endpoints = [e for e in found if _code_of(e) not in switching]
        incompatible = types.incompatible(endpoints)
        if not incompatible:
            continue
        for endpoint in sorted(endpoints, key=Endpoint.sort_key):
            mine = endpoint.type_name or ""
            conflicting = sorted(
                {
                    other
                    for other in incompatible.get(id(endpoint), ())
                    if _facing(endpoint, other) and graph.can_meet(endpoint, other)
                },
                key=lambda o: (o.location, o.edge.value),
            )
            # One finding per place in the code, not one per namespace it is launched in.
            if not conflicting or endpoint.location in reported:
                continue
            reported.add(endpoint.location)
            first = conflicting[0]
            more = f" and {len(conflicting) - 1} more" if len(conflicting) > 1 else ""
            message = (
                f"{kind.value} '{resource}' is {_DONE[endpoint.edge]} here as '{mine}' but "
                f"{_DONE[first.edge]} as '{first.type_name}' at {where(first.location)}{more}; "
                f"{_WHY[_ros1_service(endpoint)]}"
            )
            related = [
                (o.location, f"{_DONE[o.edge]} as '{o.type_name}' by {o.node}") for o in conflicting
            ]
            yield finding(endpoint.location, message, related)


RULE = Rule(
    code="RN403",
    name="message-type-mismatch",
    summary="Endpoints of one resolved topic, service or action with different types",
    severity=Severity.ERROR,
    check=None,
    check_workspace=check_workspace,
)

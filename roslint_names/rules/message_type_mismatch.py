"""RN403 message-type-mismatch: one resolved topic, service or action, two types.

A publisher and a subscriber of one topic with different message types never exchange a
message (ROS 1 refuses the connection on the md5sum, ROS 2 on the type name), and nothing
fails loudly. Only endpoints that can be in one ROS graph are compared (``Graph.can_meet``:
one launch tree, or packages meant to run together), and only names the linter knows.
Types are compared in one canonical spelling (``std_msgs::msg::String``, ``std_msgs/String``
and ``std_msgs.msg.String`` are one type); a type the code names without its package
matches any package's type of that name.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator

from ..model import Generation, Kind, Severity
from ..rule import Rule, RuleContext, WorkspaceFinding
from ..workspace.graph import EdgeKind, Endpoint, Graph, Location
from .graph_common import finding, where


def _comparable(endpoint: Endpoint) -> bool:
    """A type we can hold against another, on a name we know.

    Not one the code names without its package: in C++ that is nearly always an alias or
    a template parameter (``using Action = nav2_msgs::action::FollowPath``, ``ActionT``)
    declared where we do not look. Not a ROS 1 service: rosservice connects on the md5 of
    the definition alone, and tutorials serve one definition under two names
    (``roscpp_tutorials/TwoInts``, ``rospy_tutorials/AddTwoInts``).
    """
    if not endpoint.certain or endpoint.type_name is None or "/" not in endpoint.type_name:
        return False
    ros1 = endpoint.reach.generation is Generation.ROS1
    return not (ros1 and endpoint.resource_kind is Kind.SERVICE)


def _alternatives(endpoints: list[Endpoint]) -> set[tuple[str, str, str]]:
    """(root, node, file) of code that uses the name with two types itself: code that
    picks one at run time (``TwistStamped`` on Jazzy, ``Twist`` before), not a mismatch."""
    types: dict[tuple[str, str, str], set[str]] = defaultdict(set)
    for endpoint in endpoints:
        types[_code_of(endpoint)].add(endpoint.type_name or "")
    return {code for code, found in types.items() if len(found) > 1}


def _code_of(endpoint: Endpoint) -> tuple[str, str, str]:
    return (endpoint.root, endpoint.node, endpoint.location.path)


def _compatible(one: str, other: str) -> bool:
    if one == other:
        return True
    if "/" in one and "/" in other:
        return False
    return one.rpartition("/")[2] == other.rpartition("/")[2]


def _mismatches(endpoints: list[Endpoint]) -> bool:
    types = sorted({e.type_name for e in endpoints if e.type_name})
    return any(not _compatible(a, b) for i, a in enumerate(types) for b in types[i + 1 :])


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


def check_workspace(graph: Graph, context: RuleContext) -> Iterator[WorkspaceFinding]:
    del context
    by_resource: dict[tuple[Kind, str], list[Endpoint]] = defaultdict(list)
    for endpoint in graph.endpoints:
        if _comparable(endpoint):
            by_resource[(endpoint.resource_kind, endpoint.resource)].append(endpoint)
    reported: set[Location] = set()
    for (kind, resource), found in sorted(by_resource.items()):
        switching = _alternatives(found)
        endpoints = [e for e in found if _code_of(e) not in switching]
        if not _mismatches(endpoints):
            continue
        for endpoint in sorted(endpoints, key=Endpoint.sort_key):
            mine = endpoint.type_name or ""
            conflicting = sorted(
                {
                    other
                    for other in endpoints
                    if other.type_name
                    and not _compatible(other.type_name, mine)
                    and _facing(endpoint, other)
                    and graph.can_meet(endpoint, other)
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
                "the two never connect"
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

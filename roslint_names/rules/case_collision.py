"""RN401 case-collision: resolved names equal ignoring case but not equal.

``/cmd_vel`` published in C++ and ``/Cmd_Vel`` subscribed in Python never meet: ROS names
are case-sensitive. Names are compared after resolution (namespaces, private names,
remaps), grouped by their lower-case form, between nodes that can meet (``Graph.can_meet``),
so two robots whose identical names sit in different namespaces never collide. A
collision that comes from the namespaces (one code launched under ``robot1`` and
``Robot1``) is blamed on the launch sites, not the code.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from collections.abc import Iterator

from ..model import Severity
from ..rule import Rule, RuleContext, WorkspaceFinding
from ..workspace.graph import Graph, Location, Placed
from .graph_common import finding, instances, launch_site, where

# (what, resolved name) -> places that use it, each with the node (or endpoint) using it.
# Lists: a place twice only compares twice, and hashing a node hashes all it holds.
_Uses = dict[tuple[str, str], list[tuple[Location, Placed]]]


def _colliding(graph: Graph) -> set[str]:
    """The lower-case forms shared by two resolved names (of endpoints the rule judges,
    and of launched nodes): the only names ``_uses`` must place. Most of a workspace's
    tens of thousands are alone in their case."""
    names = {endpoint.resource for endpoint in graph.endpoints if endpoint.certain}
    names.update(node.name for node in graph.nodes if node.launched_at)
    spellings = Counter(name.lower() for name in names)
    return {lower for lower, count in spellings.items() if count > 1}


def _uses(graph: Graph) -> _Uses:
    colliding = _colliding(graph)
    spellings: _Uses = defaultdict(list)
    if not colliding:
        return spellings
    nodes = instances(graph)
    by_code: dict[Location, set[str]] = defaultdict(set)
    for endpoint in graph.endpoints:
        if endpoint.resource.lower() in colliding:  # what _spelled_twice compares
            by_code[endpoint.location].add(endpoint.resource)
    for endpoint in graph.endpoints:
        if not endpoint.certain or endpoint.resource.lower() not in colliding:
            continue  # placed in the node's namespace by guess, or alone in its case
        location = endpoint.location
        node = nodes.get((endpoint.root, endpoint.node))
        # One code location under two spellings: the namespaces differ in case.
        site = None if node is None else launch_site(node)
        if site is not None and _spelled_twice(by_code[location], endpoint.resource):
            location = site
        spellings[(endpoint.resource_kind.value, endpoint.resource)].append((location, endpoint))
    for node in graph.nodes:
        site = launch_site(node)
        if site is not None and node.name.lower() in colliding:
            spellings[("node", node.name)].append((site, node))
    return spellings


def _spelled_twice(resources: set[str], resource: str) -> bool:
    lower = resource.lower()
    return any(other != resource and other.lower() == lower for other in resources)


def check_workspace(graph: Graph, context: RuleContext) -> Iterator[WorkspaceFinding]:
    del context
    groups: dict[str, list[tuple[str, str]]] = defaultdict(list)
    uses = _uses(graph)
    for key in sorted(uses):
        groups[key[1].lower()].append(key)
    for keys in groups.values():
        if len({name for _, name in keys}) < 2:
            continue
        for what, name in keys:
            # Every place, each with the places (and spellings) its node can meet.
            meeting: dict[Location, set[tuple[Location, str, str]]] = defaultdict(set)
            for location, user in uses[(what, name)]:
                for other_what, other_name in keys:
                    if other_name == name:
                        continue
                    meeting[location].update(
                        (other, other_what, other_name)
                        for other, other_user in uses[(other_what, other_name)]
                        if graph.can_meet(user, other_user)
                    )
            for location, others in sorted(meeting.items()):
                if not others:
                    continue
                first_other, _, first_name = min(others)
                also = f" and {len(others) - 1} more" if len(others) > 1 else ""
                message = (
                    f"{what} '{name}' differs only in case from '{first_name}' "
                    f"at {where(first_other)}{also}; ROS names are case-sensitive, "
                    f"so the two never meet"
                )
                related = [(other, f"{w} '{n}'") for other, w, n in others]
                yield finding(location, message, related)


RULE = Rule(
    code="RN401",
    name="case-collision",
    summary="Two resolved names of the workspace equal ignoring case but not equal",
    severity=Severity.WARNING,
    check=None,
    check_workspace=check_workspace,
    judges_test_code=False,
)

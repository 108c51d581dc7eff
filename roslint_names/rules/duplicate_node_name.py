"""RN402 duplicate-node-name: one launch tree starts one fully qualified node name twice.

roslaunch refuses to start a file with two nodes of one name; in ROS 2 both run, and
parameters, services and logging then reach one of them at random. Counted over the whole
tree a root launch file starts, includes followed, after every namespace is applied: the
same file included twice in two ``<group ns>`` is two robots, not a duplicate.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator

from ..model import Severity
from ..rule import Rule, RuleContext, WorkspaceFinding
from ..workspace.graph import Graph, Location, NodeInstance
from .graph_common import finding, where


def _blame(node: NodeInstance, other: NodeInstance) -> Location:
    """The outermost launch site where the two starts part ways: two includes of one file
    are blamed at the includes, two ``<node>`` tags of one file at the tags."""
    for mine, theirs in zip(node.launched_at, other.launched_at, strict=False):
        if mine != theirs:
            return mine
    return node.launched_at[-1]


def check_workspace(graph: Graph, context: RuleContext) -> Iterator[WorkspaceFinding]:
    del context
    started: dict[tuple[str, str], list[NodeInstance]] = defaultdict(list)
    for node in graph.nodes:
        if node.launched_at:
            started[(node.root, node.name)].append(node)
    reported: set[Location] = set()
    for (root, name), nodes in sorted(started.items()):
        if len(nodes) < 2:
            continue
        for node in nodes:
            others = [other for other in nodes if other is not node]
            location = _blame(node, others[0])
            if location in reported:
                continue  # an included file's duplicate, seen from another root already
            reported.add(location)
            related = [
                (_blame(other, node), f"node '{name}' also started here") for other in others
            ]
            times = "twice" if len(nodes) == 2 else f"{len(nodes)} times"
            message = (
                f"node '{name}' is started {times} when {root} is launched "
                f"(also at {where(related[0][0])}); node names must be unique"
            )
            yield finding(location, message, related)


RULE = Rule(
    code="RN402",
    name="duplicate-node-name",
    summary="One launch tree starts two nodes with the same fully qualified name",
    severity=Severity.ERROR,
    check=None,
    check_workspace=check_workspace,
)

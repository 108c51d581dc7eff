"""RN402 duplicate-node-name: one launch tree starts one fully qualified node name twice.

roslaunch refuses to start a file with two nodes of one name; in ROS 2 both run, and
parameters, services and logging then reach one of them at random. Counted over the whole
tree a root launch file starts, includes followed, after every namespace is applied: the
same file included twice in two ``<group ns>`` is two robots, not a duplicate. Two rostest
``<test>``s of one name are not either: rostest runs them one after the other.
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
        # Two starts under conditions we cannot decide are usually alternatives (composed
        # or standalone, simulation or hardware): only unconditional starts count.
        if node.launched_at and not node.conditional:
            started[(node.root, node.name)].append(node)
    # One finding per launch site: a copied include duplicates every node it starts. The
    # first start of a name is the one the others copy: each copy is reported, where its
    # name or namespace is changed, and the first is named beside it (one decision each).
    at: dict[Location, dict[str, list[Location]]] = defaultdict(dict)
    roots: dict[Location, str] = {}
    twice = [(key, nodes) for key, nodes in started.items() if len(nodes) > 1]
    for (root, name), nodes in sorted(twice):
        for node in nodes:
            # rostest runs its <test>s one at a time: two of one name never meet.
            others = [o for o in nodes if o is not node and not (o.test and node.test)]
            if not others:
                continue
            location = _blame(node, others[0])
            earlier = [_blame(other, node) for other in others]
            if min(earlier) > location:
                continue  # the first start: reported beside its copies
            roots.setdefault(location, root)
            at[location].setdefault(name, earlier)
    for location, names in sorted(at.items()):
        related = sorted({(o, "also started here") for others in names.values() for o in others})
        listed = _listed(sorted(names))
        verb = "is" if len(names) == 1 else "are"
        message = (
            f"{listed} {verb} started twice when {roots[location]} is launched "
            f"(also at {where(related[0][0])}); node names must be unique"
        )
        yield finding(location, message, related)


def _listed(names: list[str]) -> str:
    quoted = [f"'{name}'" for name in names]
    if len(quoted) == 1:
        return f"node {quoted[0]}"
    return f"nodes {', '.join(quoted[:-1])} and {quoted[-1]}"


RULE = Rule(
    code="RN402",
    name="duplicate-node-name",
    summary="One launch tree starts two nodes with the same fully qualified name",
    severity=Severity.ERROR,
    check=None,
    check_workspace=check_workspace,
    reads_code_names=False,
)

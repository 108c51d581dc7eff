"""RN201 name-too-deep: a graph name with more than ``max-depth`` tokens.

Deep names are hard to type, to remap and to read in rqt_graph; a name that is already
deep in a file ends deeper still once launch files push namespaces on it. Parameters are
left out: their nesting mirrors the configuration structure (``controller.gains.p``).
"""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Kind, Severity
from ..names import depth, is_valid
from ..rule import Rule, RuleContext, WorkspaceFinding
from ..workspace.graph import Endpoint, Graph, Location, NodeInstance
from .common import GRAPH_KINDS, chosen_here, label, static_uses
from .graph_common import finding, instances


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    for use in static_uses(facts):
        if use.kind not in GRAPH_KINDS or not chosen_here(use, facts):
            continue  # a remap's source, a subscriber's topic: spelled where chosen
        if not is_valid(use.value, use.kind, facts.generation):
            continue  # RN101 reports it; one problem, one finding
        levels = depth(use.value, use.kind)
        if levels > context.max_depth:
            yield Finding(
                use.span,
                f"{label(use)} '{use.value}' has {levels} levels; "
                f"the limit is {context.max_depth} (max-depth)",
            )


def check_workspace(graph: Graph, context: RuleContext) -> Iterator[WorkspaceFinding]:
    """Names that only grow too deep once launched: blamed on the launch site (a ``<node>``
    or an include) whose namespace pushes them over the limit."""
    nodes = instances(graph)
    reported: set[tuple[Location, str]] = set()
    for endpoint in graph.endpoints:
        node = nodes.get((endpoint.root, endpoint.node))
        if node is None or not node.launched_at:
            continue
        levels = depth(endpoint.resource, endpoint.resource_kind)
        own = _own_depth(endpoint)
        if levels <= context.max_depth or own > context.max_depth:
            continue  # fine, or too deep in the code already (reported there)
        site = _pushing_site(node, own, context.max_depth)
        if (site, endpoint.resource) in reported:
            continue
        reported.add((site, endpoint.resource))
        message = (
            f"{endpoint.resource_kind.value} '{endpoint.written}' of node '{node.name}' "
            f"resolves to '{endpoint.resource}' once launched here: {levels} levels; "
            f"the limit is {context.max_depth} (max-depth)"
        )
        yield finding(site, message, [(endpoint.location, f"'{endpoint.written}' in the code")])


def _own_depth(endpoint: Endpoint) -> int:
    """Levels the name has in the code alone: a private name counts the node's own."""
    written = endpoint.written
    if written.startswith("/"):
        return depth(written, endpoint.resource_kind)
    bare = written.lstrip("~").lstrip("/")
    extra = 1 if written.startswith("~") else 0
    return (depth(bare, endpoint.resource_kind) if bare else 0) + extra


def _pushing_site(node: NodeInstance, own: int, limit: int) -> Location:
    for site, namespace in zip(node.launched_at, node.launch_namespaces, strict=False):
        if depth(namespace, Kind.NAMESPACE) + own > limit:
            return site
    return node.launched_at[-1]


RULE = Rule(
    code="RN201",
    name="name-too-deep",
    summary="A name with more than max-depth tokens (default 4)",
    severity=Severity.WARNING,
    check=check,
    check_workspace=check_workspace,
    judges_test_code=False,
)

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
from ..workspace.graph import Graph, Location, NodeInstance, NodeRemap
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
    """Names that only grow too deep once launched: blamed on the remap that names them
    (its target resolves in the node's namespace), else on the launch site (a ``<node>`` or
    an include) whose namespace pushes them over the limit."""
    limit = context.max_depth
    # remap -> node name -> the first launch of that node (trees including one file twice
    # start the same node twice)
    deep_remaps: dict[Location, dict[str, tuple[NodeInstance, NodeRemap]]] = {}
    remapped: set[tuple[str, str, str]] = set()  # (root, node, target): judged at the remap
    for instance in graph.nodes:
        for remap in instance.remaps:
            remapped.add((instance.root, instance.name, remap.target))
            if _pushed_too_deep(instance, remap, limit):
                launches = deep_remaps.setdefault(Location(remap.path, remap.span), {})
                launches.setdefault(instance.name, (instance, remap))
    for location, launches in sorted(deep_remaps.items()):
        yield _deep_remap_finding(location, sorted(launches.values(), key=_by_name), limit)
    reported: set[tuple[Location, str]] = set()
    nodes = instances(graph)
    for endpoint in graph.endpoints:
        node = nodes.get((endpoint.root, endpoint.node))
        if node is None or not node.launched_at:
            continue
        if (node.root, node.name, endpoint.resource) in remapped:
            continue  # the remap chose the name, and is judged above
        levels = depth(endpoint.resource, endpoint.resource_kind)
        own = _own_depth(endpoint.written, endpoint.resource_kind)
        if levels <= limit or own > limit:
            continue  # fine, or too deep in the code already (reported there)
        site = _pushing_site(node, own, limit)
        if (site, endpoint.resource) in reported:
            continue
        reported.add((site, endpoint.resource))
        message = (
            f"{endpoint.resource_kind.value} '{endpoint.written}' of node '{node.name}' "
            f"resolves to '{endpoint.resource}' once launched here: {levels} levels; "
            f"the limit is {limit} (max-depth)"
        )
        yield finding(site, message, [(endpoint.location, f"'{endpoint.written}' in the code")])


def _pushed_too_deep(node: NodeInstance, remap: NodeRemap, limit: int) -> bool:
    """A remap target within the limit as written, past it in the node's namespace."""
    if not node.launched_at or not is_valid(remap.target, Kind.TOPIC, node.generation):
        return False
    own = _own_depth(remap.written_target, Kind.TOPIC)
    return own <= limit < depth(remap.target, Kind.TOPIC)


def _deep_remap_finding(
    location: Location, launches: list[tuple[NodeInstance, NodeRemap]], limit: int
) -> WorkspaceFinding:
    """One finding per remap, however many launches (robots, cameras) repeat it."""
    node, remap = launches[0]
    more = len(launches) - 1
    message = (
        f"remap target '{remap.written_target}' of node '{node.name}' resolves to "
        f"'{remap.target}' in the node's namespace: {depth(remap.target, Kind.TOPIC)} "
        f"levels; the limit is {limit} (max-depth)"
        + (f" (and in {more} more launch{'es' if more > 1 else ''})" if more else "")
    )
    own = _own_depth(remap.written_target, Kind.TOPIC)
    sites = [
        (_pushing_site(n, own, limit), "the launch site that pushes the namespace")
        for n, _ in launches
    ]
    return finding(location, message, sites)


def _by_name(launch: tuple[NodeInstance, NodeRemap]) -> str:
    return launch[0].name


def _own_depth(written: str, kind: Kind) -> int:
    """Levels the name has where it is written: a private name counts the node's own."""
    if written.startswith("/"):
        return depth(written, kind)
    bare = written.lstrip("~").lstrip("/")
    extra = 1 if written.startswith("~") else 0
    return (depth(bare, kind) if bare else 0) + extra


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

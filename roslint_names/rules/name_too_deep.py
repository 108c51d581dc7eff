"""RN201 name-too-deep: a graph name with more than ``max-depth`` tokens.

Deep names are hard to type, to remap and to read in rqt_graph; a name that is already
deep in a file ends deeper still once launch files push namespaces on it. Parameters are
left out: their nesting mirrors the configuration structure (``controller.gains.p``).

Only the levels a writer chose count (``common.chosen_depth``: not ROS 2's hidden tokens,
not a transport plugin's subtopic), and each decision is reported once, where the edit
goes: one finding per launch site that pushes a node's names past the limit, listing them;
a topic wired from a publisher's remap to subscribers' remaps at the publisher's, listing
theirs; a remap's finding at its target (``to``).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from enum import Enum

from ..model import Answer, FileFacts, Finding, Generation, Kind, Role, Severity, Span
from ..names import depth, is_valid
from ..rule import Rule, RuleContext, WorkspaceFinding
from ..workspace.graph import (
    EdgeKind,
    Endpoint,
    Graph,
    Location,
    NodeInstance,
    NodeRemap,
    Placed,
)
from .common import (
    GRAPH_KINDS,
    TRANSPORT_SUFFIXES,
    chosen_depth,
    chosen_here,
    decision,
    in_code,
    label,
    static_uses,
)
from .graph_common import finding, instances


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    deferred = _deferred_to_graph(facts)
    for use in static_uses(facts):
        if use.kind not in GRAPH_KINDS or not chosen_here(use, facts):
            continue  # a remap's source, a subscriber's topic: spelled where chosen
        if use.role is Role.REMAP_TO and use.span in deferred:
            continue  # a subscriber's remap: judged with its publisher (check_workspace)
        if not is_valid(use.value, use.kind, facts.generation):
            continue  # RN101 reports it; one problem, one finding
        levels = chosen_depth(use.value, use.kind, facts.generation)
        if levels > context.max_depth:
            message = _too_deep(label(use), use.value, levels, context.max_depth)
            # In code a name is one decision wherever it is written; in a launch file each
            # remap or namespace is its file's own choice (the graph judges their wiring).
            chosen = decision(use, facts) if in_code(use, facts) else None
            yield Finding(use.span, message, answer=_depth(levels), decision=chosen)


def _depth(levels: int) -> Answer:
    """The setting that would allow ``levels``: what ``conventions`` proposes."""
    return Answer("max-depth", str(levels))


def _too_deep(what: str, value: str, levels: int, limit: int) -> str:
    return f"{what} '{value}' has {levels} levels; the limit is {limit} (max-depth)"


def _deferred_to_graph(facts: FileFacts) -> set[Span]:
    """The targets of the input remaps of nodes the graph will hold (a static name and
    namespace): whether a publisher in the workspace chose the name is known only there."""
    return {
        remap.target_span
        for node in facts.launch_nodes
        if node.name is not None and not node.dynamic_name and node.namespace
        for remap in node.remaps[len(node.remaps) - node.own_remaps :]
        if remap.target_span is not None
        and _spelled_at(remap.target_span, remap.target)
        and _conventional_side(remap.source) is Side.CONSUMER
    }


def _spelled_at(span: Span, value: str) -> bool:
    """Whether ``span`` spells ``value`` itself (maybe quoted), not an argument that the
    including file gives: there the edit would go into the includer, not here."""
    width = span.end_column - span.column
    return span.line == span.end_line and width in (len(value), len(value) + 2)


class Side(Enum):
    """Which end of a topic a remap renames: the node that produces it, or one using it."""

    PRODUCER = "producer"
    CONSUMER = "consumer"
    UNKNOWN = "unknown"


_CONVENTIONAL_SIDES = {"input": Side.CONSUMER, "output": Side.PRODUCER}
_PRODUCING = frozenset({EdgeKind.PUBLISH, EdgeKind.SERVE, EdgeKind.ACTION_SERVE})
_CONSUMING = frozenset({EdgeKind.SUBSCRIBE, EdgeKind.CALL, EdgeKind.ACTION_CALL})


def _conventional_side(source: str) -> Side:
    """The side a remap's source names by convention: Autoware's ``~/input/*`` and
    ``~/output/*`` (its coding guidelines, "Topic namespaces"), pcl_ros' ``input`` and
    ``output``. ``source`` as written, or resolved: the token after the node's name."""
    first = source.lstrip("~").lstrip("/").split("/", 1)[0]
    return _CONVENTIONAL_SIDES.get(first, Side.UNKNOWN)


@dataclass(frozen=True)
class _Launch:
    """One node launch a remap applies to, with the side of the topic it renames."""

    node: NodeInstance
    remap: NodeRemap
    side: Side


def check_workspace(graph: Graph, context: RuleContext) -> Iterator[WorkspaceFinding]:
    """Names that only grow too deep once launched: blamed on the remap that names them
    (its target resolves in the node's namespace), else on the launch site (a ``<node>`` or
    an include) whose namespace pushes them over the limit, one finding per site. A
    subscriber's remap of a name a publisher of the workspace produces is left to the
    publisher's finding, which lists it."""
    limit = context.max_depth
    looked_up = _LookedUp(graph)
    # remap location -> node name -> the first launch of that node (trees including one
    # file twice start the same node twice)
    deep_remaps: dict[Location, dict[str, _Launch]] = {}
    wired: dict[str, set[Location]] = {}  # resource -> subscribers' remaps left out
    remapped: set[tuple[str, str, str]] = set()  # (root, node, target): judged at the remap
    for instance in graph.nodes:
        for remap in instance.remaps:
            remapped.add((instance.root, instance.name, remap.target))
            if not _judged_here(instance, remap, limit):
                continue
            side = looked_up.side(instance, remap)
            location = Location(remap.path, remap.target_span or remap.span)
            if side is Side.CONSUMER and looked_up.produced(instance, remap.target):
                wired.setdefault(remap.target, set()).add(location)
                continue
            launches = deep_remaps.setdefault(location, {})
            launches.setdefault(instance.name, _Launch(instance, remap, side))
    transports, merged = _transport_remaps(deep_remaps)
    for location, launches in sorted(deep_remaps.items()):
        if location in merged:
            continue  # an image transport's subtopic of a remap reported beside it
        ordered = sorted(launches.values(), key=_by_name)
        if _deep_only_by_instance(ordered, limit):
            continue  # one copy per robot: the robot's namespace is no level of the name
        yield _deep_remap_finding(location, ordered, limit, wired, transports.get(location, []))
    yield from _pushed_endpoints(graph, remapped, limit, wired)


def _deep_only_by_instance(launches: list[_Launch], limit: int) -> bool:
    """Whether a remap launched for several copies of a node is too deep only by the levels
    in which the copies' targets differ: husky's ``multi_husky_playpen.launch`` includes one
    spawn file for ``husky_alpha``, ``husky_beta`` and ``husky_gamma``. Such a level is each
    robot's namespace, the separation RN202 asks for, not a level anyone chose for the
    name; one copy alone gives no such evidence."""
    if len(launches) < 2:
        return False
    targets = [launch.remap.target.strip("/").split("/") for launch in launches]
    if len({len(levels) for levels in targets}) != 1:
        return False
    differing = sum(1 for level in zip(*targets, strict=True) if len(set(level)) > 1)
    return differing > 0 and all(
        chosen_depth(launch.remap.target, Kind.TOPIC, launch.node.generation) - differing <= limit
        for launch in launches
    )


def _transport_remaps(
    deep_remaps: dict[Location, dict[str, _Launch]],
) -> tuple[dict[Location, list[Location]], set[Location]]:
    """The remaps of a transport's subtopic (``debug/rois/compressed``) of a node whose
    base topic (``debug/rois``) another remap makes too deep: one decision, reported at
    the base's remap. Returns base remap -> its subtopics' remaps, and the latter."""
    bases = {
        (node, launch.remap.target): location
        for location, launches in deep_remaps.items()
        for node, launch in launches.items()
    }
    transports: dict[Location, list[Location]] = {}
    merged: set[Location] = set()
    for location, launches in deep_remaps.items():
        found = {
            bases.get((node, _transport_base(launch.remap.target)))
            for node, launch in launches.items()
        }
        if len(found) == 1 and (base := found.pop()) is not None and base != location:
            transports.setdefault(base, []).append(location)
            merged.add(location)
    return transports, merged


def _transport_base(topic: str) -> str:
    base, _, last = topic.rpartition("/")
    return base if base and last in TRANSPORT_SUFFIXES else ""


class _LookedUp:
    """The graph's endpoints by resource and its nodes' remaps by target, indexed when
    first asked: the rule asks about the few remaps past the limit, not about the
    tens of thousands of a workspace's endpoints and remaps."""

    def __init__(self, graph: Graph) -> None:
        self._graph = graph
        self._endpoints: dict[str, list[Endpoint]] | None = None
        self._remaps: dict[str, list[tuple[NodeInstance, NodeRemap]]] | None = None

    def endpoints_of(self, resource: str) -> list[Endpoint]:
        if self._endpoints is None:
            self._endpoints = {}
            for endpoint in self._graph.endpoints:
                self._endpoints.setdefault(endpoint.resource, []).append(endpoint)
        return self._endpoints.get(resource, [])

    def remaps_to(self, resource: str) -> list[tuple[NodeInstance, NodeRemap]]:
        if self._remaps is None:
            self._remaps = {}
            for node in self._graph.nodes:
                for remap in node.remaps:
                    self._remaps.setdefault(remap.target, []).append((node, remap))
        return self._remaps.get(resource, [])

    def side(self, node: NodeInstance, remap: NodeRemap) -> Side:
        """The side the node's code uses the remap's target on, else the side its source
        names by convention."""
        used = {
            endpoint.edge
            for endpoint in self.endpoints_of(remap.target)
            if endpoint.node == node.name and endpoint.root == node.root
        }
        if used & _PRODUCING:
            return Side.PRODUCER
        if used & _CONSUMING:
            return Side.CONSUMER
        return _conventional_side(_after_node(remap.source, node.name))

    def produced(self, node: NodeInstance, resource: str) -> bool:
        """Whether something the node can meet produces ``resource``: code that publishes
        or serves it, or a node whose publishing remap names it."""
        producers: list[Placed] = [
            endpoint
            for endpoint in self.endpoints_of(resource)
            if endpoint.certain and endpoint.edge in _PRODUCING
        ]
        producers += [
            other
            for other, remap in self.remaps_to(resource)
            if self.side(other, remap) is Side.PRODUCER
        ]
        return any(self._graph.can_meet(node, other) for other in producers)


def _after_node(source: str, node: str) -> str:
    """A resolved remap source without its node's name or namespace."""
    for prefix in (f"{node}/", f"{node.rpartition('/')[0]}/"):
        if source.startswith(prefix):
            return source[len(prefix) :]
    return source


def _judged_here(node: NodeInstance, remap: NodeRemap, limit: int) -> bool:
    """A remap target past the limit in the node's namespace, which the file rule left
    to the graph: pushed there by the namespace, or a subscriber's input remap."""
    if not node.launched_at or not is_valid(remap.target, Kind.TOPIC, node.generation):
        return False
    levels = chosen_depth(remap.target, Kind.TOPIC, node.generation)
    if levels <= limit:
        return False
    own = _own_depth(remap.written_target, Kind.TOPIC, node.generation)
    if own <= limit:
        return True  # pushed too deep by the namespace
    # the file rule's deferred remaps (``_deferred_to_graph``)
    return (
        node.named_at_launch
        and remap.own
        and remap.target_span is not None
        and _spelled_at(remap.target_span, remap.written_target)
        and _conventional_side(_after_node(remap.source, node.name)) is Side.CONSUMER
    )


def _deep_remap_finding(
    location: Location,
    launches: list[_Launch],
    limit: int,
    wired: dict[str, set[Location]],
    transports: list[Location],
) -> WorkspaceFinding:
    """One finding per remap, however many launches (robots, cameras) repeat it."""
    first = launches[0]
    node, remap = first.node, first.remap
    more = len(launches) - 1
    levels = chosen_depth(remap.target, Kind.TOPIC, node.generation)
    own = _own_depth(remap.written_target, Kind.TOPIC, node.generation)
    if own > limit:
        message = _too_deep("remap target", remap.written_target, levels, limit)
    else:
        message = (
            f"remap target '{remap.written_target}' of node '{node.name}' resolves to "
            f"'{remap.target}' in the node's namespace: {levels} "
            f"levels; the limit is {limit} (max-depth)"
        )
    message += f" (and in {more} more launch{'es' if more > 1 else ''})" if more else ""
    others: list[tuple[Location, str]] = []
    if own <= limit:
        others += [
            (_pushing_site(launch.node, own, limit), "the launch site that pushes the namespace")
            for launch in launches
        ]
    subscribers = sorted(wired.get(remap.target, set())) if first.side is Side.PRODUCER else []
    others += [(other, "a subscriber's remap of this name") for other in subscribers]
    if subscribers:
        message += f"; {len(subscribers)} subscriber remap(s) use it too"
    others += [(other, "its image transport's subtopic, as deep") for other in transports]
    return finding(location, message, others, _depth(levels))


def _pushed_endpoints(
    graph: Graph,
    remapped: set[tuple[str, str, str]],
    limit: int,
    wired: dict[str, set[Location]],
) -> Iterator[WorkspaceFinding]:
    """The code's names a launch site's namespace pushes past the limit: one finding per
    site, listing them (a ``<node>`` whose namespace makes ten ``~/debug/*`` topics too
    deep is one decision)."""
    nodes: dict[tuple[str, str], NodeInstance] | None = None
    pushed: dict[Location, dict[str, tuple[Endpoint, NodeInstance, int]]] = {}
    for endpoint in graph.endpoints:
        if _within(endpoint.resource, limit):
            continue
        if nodes is None:
            nodes = instances(graph)
        node = nodes.get((endpoint.root, endpoint.node))
        if node is None or not node.launched_at:
            continue
        if (node.root, node.name, endpoint.resource) in remapped:
            continue  # the remap chose the name, and is judged above
        generation = endpoint.reach.generation
        levels = chosen_depth(endpoint.resource, endpoint.resource_kind, generation)
        own = _own_depth(endpoint.written, endpoint.resource_kind, generation)
        if levels <= limit or own > limit:
            continue  # fine, or too deep in the code already (reported there)
        site = _pushing_site(node, own, limit)
        pushed.setdefault(site, {}).setdefault(endpoint.resource, (endpoint, node, levels))
    for site, names in sorted(pushed.items()):
        yield _pushed_finding(site, [names[r] for r in sorted(names)], limit, wired)


def _pushed_finding(
    site: Location,
    names: list[tuple[Endpoint, NodeInstance, int]],
    limit: int,
    wired: dict[str, set[Location]],
) -> WorkspaceFinding:
    others = [(endpoint.location, f"'{endpoint.written}' in the code") for endpoint, _, _ in names]
    others += [
        (subscriber, "a subscriber's remap of this name")
        for endpoint, _, _ in names
        for subscriber in sorted(wired.get(endpoint.resource, set()))
    ]
    endpoint, node, levels = names[0]
    if len(names) == 1:
        message = (
            f"{endpoint.resource_kind.value} '{endpoint.written}' of node '{node.name}' "
            f"resolves to '{endpoint.resource}' once launched here: {levels} levels; "
            f"the limit is {limit} (max-depth)"
        )
        return finding(site, message, others, _depth(levels))
    shown = ", ".join(f"'{e.resource}' ({n})" for e, _, n in names[:_LISTED])
    rest = len(names) - _LISTED
    node_names = sorted({n.name for _, n, _ in names})
    message = (
        f"{len(names)} names of node{'s' if len(node_names) > 1 else ''} "
        f"{', '.join(repr(n) for n in node_names)} resolve past the limit of {limit} "
        f"levels (max-depth) once launched here: {shown}"
        + (f" and {rest} more" if rest > 0 else "")
    )
    return finding(site, message, others, _depth(max(n for _, _, n in names)))


_LISTED = 3  # names a pushed finding's message spells out; its related locations list all


def _by_name(launch: _Launch) -> str:
    return launch.node.name


def _within(resource: str, limit: int) -> bool:
    """Whether a fully qualified name has at most ``limit`` levels by its separators
    alone: no more tokens than separators after the leading one (``names.tokens``), and
    ``chosen_depth`` counts no more than the tokens. Most names are: they need no
    tokenising."""
    return resource.startswith("/") and resource.count("/") <= limit


def _own_depth(written: str, kind: Kind, generation: Generation) -> int:
    """Levels the name has where it is written: a private name counts the node's own."""
    if written.startswith("/"):
        return chosen_depth(written, kind, generation)
    bare = written.lstrip("~").lstrip("/")
    extra = 1 if written.startswith("~") else 0
    return (chosen_depth(bare, kind, generation) if bare else 0) + extra


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

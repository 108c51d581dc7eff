"""Helpers the graph rules share: where to blame a graph fact, and how to say where."""

from __future__ import annotations

from collections.abc import Iterable

from ..model import Answer, Finding, RelatedLocation
from ..rule import WorkspaceFinding
from ..workspace.graph import Graph, Location, NodeInstance

MAX_RELATED = 20  # a finding lists at most this many other places; the message counts all


def where(location: Location) -> str:
    return f"{location.path}:{location.span.line}:{location.span.column}"


def instances(graph: Graph) -> dict[tuple[str, str], NodeInstance]:
    """(root, node name) -> the node; the first one when a tree starts a name twice."""
    found: dict[tuple[str, str], NodeInstance] = {}
    for node in graph.nodes:
        found.setdefault((node.root, node.name), node)
    return found


def launch_site(node: NodeInstance) -> Location | None:
    """Where the node is started: its ``<node>`` (or ``Node(...)``) in a launch file."""
    return node.launched_at[-1] if node.launched_at else None


def finding(
    location: Location,
    message: str,
    others: Iterable[tuple[Location, str]],
    answer: Answer | None = None,
) -> WorkspaceFinding:
    """A finding at ``location`` pointing at every other place involved."""
    related = tuple(
        RelatedLocation(other.path, other.span, note)
        for other, note in sorted(set(others))[:MAX_RELATED]
        if other != location
    )
    return WorkspaceFinding(location.path, Finding(location.span, message, related, answer=answer))

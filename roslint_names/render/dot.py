"""The ``graph`` command's Graphviz DOT output (``--format dot``).

Render it with ``dot -Tsvg graph.dot -o graph.svg``. Nodes are ellipses labelled with their
fully qualified name and ``package/executable``; topics are boxes, services hexagons and
actions parallelograms, labelled with their resolved name and type. A resource whose
endpoints disagree on the type lists every type, notes ``(types disagree)`` and is drawn in
red.

Arrows follow the data: publisher -> topic -> subscriber, client -> service -> server,
action client -> action -> action server. Each arrow is labelled with its edge kind
(``publish``, ``subscribe``, ``call``, ``serve``, ``action call``, ``action serve``); topic
arrows are solid, service arrows dashed, action arrows bold. Endpoints with the same node,
resource and edge kind share one arrow.

Where several launch trees are drawn, each one's nodes sit in a dashed ``cluster_N``
subgraph labelled with its launch file.

Source locations ride along as ``tooltip`` attributes (``src/talker.cpp:12:5``, shown when
hovering in an SVG) and as ``//`` comments above each statement. Ids are ``n0``, ``t0``,
``s0``, ``a0`` in sorted order, so the same graph always gives the same bytes.
"""

from __future__ import annotations

from collections.abc import Iterable

from ..model import Kind
from ..workspace.graph import EdgeKind, Graph
from .view import (
    Arrow,
    NodeShape,
    ResourceShape,
    endpoint_summary,
    layout,
    node_summary,
    one_line,
    where,
)

_INDENT = "  "
_SHAPES = {Kind.TOPIC: "box", Kind.SERVICE: "hexagon", Kind.ACTION: "parallelogram"}
_STYLES = {
    EdgeKind.PUBLISH: "solid",
    EdgeKind.SUBSCRIBE: "solid",
    EdgeKind.CALL: "dashed",
    EdgeKind.SERVE: "dashed",
    EdgeKind.ACTION_CALL: "bold",
    EdgeKind.ACTION_SERVE: "bold",
}
_MISMATCH_COLOR = "red"
_HEADER = (
    "// roslint-names graph: nodes are ellipses, topics boxes, services hexagons,",
    "// actions parallelograms. Arrows follow the data: publisher -> topic -> subscriber,",
    "// client -> service -> server, action client -> action -> action server.",
    "digraph ros {",
    f"{_INDENT}rankdir=LR;",
    f'{_INDENT}node [fontname="Helvetica"];',
    f'{_INDENT}edge [fontname="Helvetica", fontsize=10];',
)


def render(graph: Graph) -> str:
    drawing = layout(graph)
    lines = list(_HEADER)
    for node in drawing.unclustered():
        lines.extend(_node(node))
    for index, (root, nodes) in enumerate(drawing.clusters()):
        lines.append(f"{_INDENT}subgraph cluster_{index} {{")
        lines.append(f"{_INDENT * 2}label={quote(root)};")
        lines.append(f"{_INDENT * 2}style=dashed;")
        lines.extend(_INDENT + line for node in nodes for line in _node(node))
        lines.append(f"{_INDENT}}}")
    for resource in drawing.resources:
        lines.extend(_resource(resource))
    for arrow in drawing.arrows:
        lines.extend(_arrow(arrow))
    lines.append("}")
    return "\n".join(lines) + "\n"


def quote(text: str) -> str:
    """``text`` as a DOT double-quoted string, read back by Graphviz as the same text.

    A backslash is doubled because Graphviz reads ``\\n``, ``\\l``, ``\\N`` and friends in
    labels and tooltips as escapes; a line break becomes ``\\n`` (a centred line break),
    and other control characters, which no label means, become spaces.
    """
    lines = text.split("\n")
    escaped = [one_line(line).replace("\\", "\\\\").replace('"', '\\"') for line in lines]
    return '"' + "\\n".join(escaped) + '"'


def _attributes(pairs: Iterable[tuple[str, str]]) -> str:
    return "[" + ", ".join(f"{key}={value}" for key, value in pairs) + "]"


def _comment(text: str) -> str:
    return f"{_INDENT}// {one_line(text)}"


def _node(node: NodeShape) -> list[str]:
    summary = node_summary(node)
    attributes = [
        ("shape", "ellipse"),
        ("label", quote("\n".join(node.lines))),
        ("tooltip", quote(summary)),
    ]
    return [
        _comment(f"{node.name}: {summary}"),
        f"{_INDENT}{node.ident} {_attributes(attributes)};",
    ]


def _resource(resource: ResourceShape) -> list[str]:
    attributes = [
        ("shape", _SHAPES.get(resource.kind, "box")),
        ("label", quote("\n".join(resource.lines))),
        ("tooltip", quote(f"{resource.kind.value} {resource.name}")),
    ]
    if resource.mismatch:
        attributes += [("color", _MISMATCH_COLOR), ("fontcolor", _MISMATCH_COLOR)]
    return [f"{_INDENT}{resource.ident} {_attributes(attributes)};"]


def _arrow(arrow: Arrow) -> list[str]:
    comments = [_comment(f"{arrow.label}: {endpoint_summary(e)}") for e in arrow.endpoints]
    tooltip = "\n".join(where(e.location) for e in arrow.endpoints)
    attributes = [
        ("label", quote(arrow.label)),
        ("style", _STYLES[arrow.edge]),
        ("tooltip", quote(tooltip)),
    ]
    return [*comments, f"{_INDENT}{arrow.tail} -> {arrow.head} {_attributes(attributes)};"]

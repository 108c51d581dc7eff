"""The ``graph`` command's Mermaid output (``--format mermaid``), for GitHub markdown.

Paste it into a ```` ```mermaid ```` block. It is a ``flowchart LR`` in the subset of the
syntax GitHub renders: nodes are stadiums (``n0(["..."])``) labelled with their fully
qualified name and ``package/executable``; topics are rectangles (``t0["..."]``), services
hexagons (``s0{{"..."}}``) and actions parallelograms (``a0[/"..."/]``), labelled with their
resolved name and type. A resource whose endpoints disagree on the type lists every type,
notes ``(types disagree)`` and gets the red ``mismatch`` class.

Arrows follow the data: publisher -> topic -> subscriber, client -> service -> server,
action client -> action -> action server; topic arrows are solid (``-->``), service arrows
dotted (``-.->``), action arrows thick (``==>``), each labelled with its edge kind.
Endpoints with the same node, resource and edge kind share one arrow.

Where several launch trees are drawn, each one's nodes sit in a ``subgraph cN["file"]``
block labelled with its launch file.

Mermaid on GitHub takes no free-form attributes and no click handlers, so source locations
are ``%%`` comments on their own line above each node and arrow. Labels are always quoted,
and every character Mermaid reads as syntax even inside quotes is written as an entity code
(``#quot;``, ``#91;``); line breaks within a label are ``<br>``.
"""

from __future__ import annotations

from ..model import Kind
from ..workspace.graph import EdgeKind, Graph
from .view import Arrow, NodeShape, ResourceShape, endpoint_summary, layout, node_summary, one_line

_INDENT = "    "
# Opening and closing brackets around a quoted label, per shape.
_NODE_SHAPE = ("([", "])")
_RESOURCE_SHAPES = {
    Kind.TOPIC: ("[", "]"),
    Kind.SERVICE: ("{{", "}}"),
    Kind.ACTION: ("[/", "/]"),
}
_LINKS = {
    EdgeKind.PUBLISH: "-->",
    EdgeKind.SUBSCRIBE: "-->",
    EdgeKind.CALL: "-.->",
    EdgeKind.SERVE: "-.->",
    EdgeKind.ACTION_CALL: "==>",
    EdgeKind.ACTION_SERVE: "==>",
}
_MISMATCH_CLASS = "mismatch"
# Characters written as entity codes inside a quoted label: the quote itself; ``#`` and
# ``;``, which spell entity codes; the shape brackets and ``|``, which Mermaid's lexer
# matches even inside quotes on some versions; ``<``, ``>`` and ``&``, which the HTML label
# would read as markup; and the backtick, which opens a markdown string.
_ENTITIES = {
    '"': "#quot;",
    "#": "#35;",
    ";": "#59;",
    "[": "#91;",
    "]": "#93;",
    "(": "#40;",
    ")": "#41;",
    "{": "#123;",
    "}": "#125;",
    "|": "#124;",
    "<": "#lt;",
    ">": "#gt;",
    "&": "#amp;",
    "`": "#96;",
}
# A comment starting ``%%{`` is a directive, and some Mermaid versions choke on braces
# anywhere in a comment; codes keep the text readable without them.
_COMMENT_ENTITIES = {"{": "#123;", "}": "#125;"}
_HEADER = (
    "flowchart LR",
    f"{_INDENT}%% roslint-names graph: nodes are stadiums, topics rectangles, services",
    f"{_INDENT}%% hexagons, actions parallelograms. Arrows follow the data: publisher -> topic",
    f"{_INDENT}%% -> subscriber, client -> service -> server, action client -> action -> server.",
)


def render(graph: Graph) -> str:
    drawing = layout(graph)
    lines = list(_HEADER)
    for node in drawing.unclustered():
        lines.extend(_node(node))
    for index, (root, nodes) in enumerate(drawing.clusters()):
        lines.append(f"{_INDENT}subgraph c{index}[{_label((root,))}]")
        lines.extend(_INDENT + line for node in nodes for line in _node(node))
        lines.append(f"{_INDENT}end")
    for resource in drawing.resources:
        lines.append(
            _shape(resource.ident, _RESOURCE_SHAPES.get(resource.kind, ("[", "]")), resource.lines)
        )
    for arrow in drawing.arrows:
        lines.extend(_arrow(arrow))
    lines.extend(_mismatch_class(drawing.resources))
    return "\n".join(lines) + "\n"


def escape(text: str) -> str:
    """``text`` for inside a quoted Mermaid label: syntax characters as entity codes.

    Control characters become entity codes too (a raw line break would end the statement);
    any other character, ASCII or not, is kept as it is.
    """
    return "".join(_ENTITIES.get(c) or _control(c) or c for c in text)


def _control(character: str) -> str:
    return f"#{ord(character)};" if one_line(character) != character else ""


def _label(lines: tuple[str, ...]) -> str:
    return '"' + "<br>".join(escape(line) for line in lines) + '"'


def _comment(text: str) -> str:
    flat = one_line(text)
    return f"{_INDENT}%% " + "".join(_COMMENT_ENTITIES.get(c, c) for c in flat)


def _shape(ident: str, brackets: tuple[str, str], lines: tuple[str, ...]) -> str:
    opening, closing = brackets
    return f"{_INDENT}{ident}{opening}{_label(lines)}{closing}"


def _node(node: NodeShape) -> list[str]:
    return [
        _comment(f"{node.name}: {node_summary(node)}"),
        _shape(node.ident, _NODE_SHAPE, node.lines),
    ]


def _arrow(arrow: Arrow) -> list[str]:
    comments = [_comment(f"{arrow.label}: {endpoint_summary(e)}") for e in arrow.endpoints]
    link = f"{arrow.tail} {_LINKS[arrow.edge]}|{arrow.label}| {arrow.head}"
    return [*comments, _INDENT + link]


def _mismatch_class(resources: tuple[ResourceShape, ...]) -> list[str]:
    marked = [resource.ident for resource in resources if resource.mismatch]
    if not marked:
        return []
    return [
        f"{_INDENT}classDef {_MISMATCH_CLASS} stroke:red,color:red",
        f"{_INDENT}class {','.join(marked)} {_MISMATCH_CLASS}",
    ]

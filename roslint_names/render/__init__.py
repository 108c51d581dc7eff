"""Renderers for the ``graph`` command: a :class:`~roslint_names.workspace.graph.Graph` in,
one string out.

Each format lives in its own module (``dot``, ``mermaid``, ``json``) as ``render(graph)``: a
pure function that writes nothing, reads no clock and returns the whole document, each line
ending in ``\\n``. The same graph always gives the same bytes.

Direction convention, shared by the drawings: arrows follow the data. A publisher points at
its topic and the topic at each subscriber; a client points at its service and the service
at its server (the request travels that way); an action client points at its action and the
action at its server (the goal travels that way). So ``a -> /x -> b`` always reads "a sends
on /x, b receives".
"""

from __future__ import annotations

from collections.abc import Callable

from ..workspace.graph import Graph
from . import dot, json, mermaid

__all__ = ["FORMATS", "RENDERERS", "render"]

RENDERERS: dict[str, Callable[[Graph], str]] = {
    "dot": dot.render,
    "mermaid": mermaid.render,
    "json": json.render,
}
FORMATS = tuple(RENDERERS)


def render(fmt: str, graph: Graph) -> str:
    """``graph`` in format ``fmt``, one of :data:`FORMATS`."""
    renderer = RENDERERS.get(fmt)
    if renderer is None:
        raise ValueError(f"unknown graph format {fmt!r}; choose one of {', '.join(FORMATS)}")
    return renderer(graph)

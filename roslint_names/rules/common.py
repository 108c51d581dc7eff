"""Helpers shared by the rules: which uses a rule looks at, and how a name is described."""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Kind, Language, NameUse, Role

GRAPH_KINDS = frozenset({Kind.NODE, Kind.NAMESPACE, Kind.TOPIC, Kind.SERVICE, Kind.ACTION})
_LAUNCH_LANGUAGES = frozenset({Language.LAUNCH_XML, Language.LAUNCH_YAML, Language.URDF})

_LABELS = {
    Kind.NODE: "node name",
    Kind.NAMESPACE: "namespace",
    Kind.TOPIC: "topic",
    Kind.SERVICE: "service",
    Kind.ACTION: "action",
    Kind.PARAMETER: "parameter",
    Kind.FRAME: "frame id",
}


def static_uses(facts: FileFacts) -> Iterator[NameUse]:
    """The uses whose value is known; dynamic names are never judged."""
    return (use for use in facts.names if not use.dynamic)


def chosen_here(use: NameUse, facts: FileFacts) -> bool:
    """Whether the author of this file chose the name, so a style finding is actionable.

    A launch file's ``<param name>`` and ``<remap from>`` spell names the node's code
    defines (gmapping's ``maxUrange``): the launch author cannot rename them, so style
    rules leave them alone. The same names in code are definitions and are judged.
    """
    if facts.language in _LAUNCH_LANGUAGES:
        return use.role not in (Role.PARAMETER, Role.REMAP_FROM)
    return True


def label(use: NameUse) -> str:
    if use.role is Role.REMAP_FROM:
        return "remapped name"
    if use.role is Role.REMAP_TO:
        return "remap target"
    return _LABELS[use.kind]

"""Launch-file helpers that need no parser: namespaces, node paths, frame parameters.

Shared by the launch XML/YAML walkers and the launch.py walker. Kept apart from
``launch_xml`` so that linting Python never imports lxml.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from roslint_names.extract.launch.substitution import Value
from roslint_names.model import Kind, Role


def join_namespace(parent: str | None, child: Value) -> str | None:
    """roslaunch's ``ns_join`` and launch_ros's ``prefix_namespace``: an absolute child
    replaces the parent, a relative one is appended. "/" is the root; None is unknown."""
    if child.dynamic or child.text.startswith("~"):
        return None
    if child.text.startswith("/"):
        return child.text.rstrip("/") or "/"
    if parent is None:
        return None
    if not child.text:
        return parent
    return f"{parent.rstrip('/')}/{child.text}".rstrip("/") or "/"


def node_path(namespace: str | None, name: str | None) -> str | None:
    if namespace is None or name is None:
        return None
    return f"{namespace.rstrip('/')}/{name}"


_FRAME_TOKEN = re.compile(r"(?:^|_)frame(?:_id)?$")


def is_frame_parameter(name: str) -> bool:
    """``frame_id``, ``frame``, ``*_frame``, ``*_frame_id``: values that are tf2 frame ids."""
    return bool(_FRAME_TOKEN.search(re.split(r"[/.~]", name)[-1]))


@dataclass(frozen=True)
class Fact:
    """The kind of a name and what the launch file does with it."""

    kind: Kind
    role: Role


NODE = Fact(Kind.NODE, Role.NODE_NAME)
NAMESPACE = Fact(Kind.NAMESPACE, Role.NAMESPACE)
REMAP_FROM = Fact(Kind.TOPIC, Role.REMAP_FROM)
REMAP_TO = Fact(Kind.TOPIC, Role.REMAP_TO)
PARAMETER = Fact(Kind.PARAMETER, Role.PARAMETER)
FRAME = Fact(Kind.FRAME, Role.FRAME)

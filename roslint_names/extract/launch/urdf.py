"""URDF and XACRO robot descriptions: link names and the names gazebo plugins use.

``<link name>`` is a tf frame. Gazebo plugins (anywhere under ``<gazebo>`` or
``<plugin>``) name their node's namespace, topics, services and frames: gazebo_ros 2 in a
``<ros>`` block (``<namespace>``, ``<remapping>from:=to</remapping>``, the older
``<argument>`` command line) and ``snake_case_frame`` elements; gazebo_ros 1 in camelCase
elements (``<robotNamespace>``, ``<commandTopic>``, ``<serviceName>``, ``<odometryFrame>``).

XACRO elements are not robot elements: ``xacro:property`` and ``xacro:arg`` supply
``${name}`` and ``$(arg name)`` values, ``xacro:if``/``xacro:unless`` with a static value
prune their body, and a macro body is walked once with its parameters unknown (a
``${prefix}`` in it is dynamic: each call gives it another value).
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

from lxml import etree

from roslint_names.extract import evidence
from roslint_names.extract.launch import xmlsafe
from roslint_names.extract.launch.substitution import (
    ARG,
    PROPERTY,
    Bindings,
    Condition,
    Declaration,
    Dialect,
    Located,
    Meaning,
    Value,
    meaning,
    ros2_assignments,
    strip_node_prefix,
)
from roslint_names.model import (
    FileFacts,
    Generation,
    Kind,
    Language,
    NameUse,
    ParseError,
    Role,
    Span,
)

XACRO_NAMESPACES = frozenset(
    {"http://www.ros.org/wiki/xacro", "http://ros.org/wiki/xacro", "http://wiki.ros.org/xacro"}
)


@dataclass(frozen=True)
class _Plugin:
    """Being inside ``<gazebo>``/``<plugin>``; ``namespace`` is the plugin's own, if static."""

    namespace: str | None = None


def _elements(element: etree._Element) -> Iterator[etree._Element]:
    return (child for child in element if isinstance(child.tag, str))


def _local(element: etree._Element) -> str:
    return etree.QName(element).localname


def _is_xacro(element: etree._Element) -> bool:
    return etree.QName(element).namespace in XACRO_NAMESPACES


# gazebo_ros 1 names topics, services and frames in camelCase, gazebo_ros 2 frames in
# snake_case: commandTopic, imageTopicName, serviceName, odometryFrame, robot_base_frame.
_TOPIC_TAG = re.compile(r"topicName|\w+Topic|\w+TopicName")
_SERVICE_TAG = re.compile(r"serviceName|\w+ServiceName")
_FRAME_TAG = re.compile(r"frameName|frame_name|\w+Frame|\w+FrameName|\w+_frame")


def _plugin_tag_kind(tag: str) -> tuple[Kind, Role] | None:
    if tag == "robotNamespace":
        return Kind.NAMESPACE, Role.NAMESPACE
    if _TOPIC_TAG.fullmatch(tag):
        return Kind.TOPIC, Role.OTHER
    if _SERVICE_TAG.fullmatch(tag):
        return Kind.SERVICE, Role.OTHER
    if _FRAME_TAG.fullmatch(tag):
        return Kind.FRAME, Role.FRAME
    return None


def _macro_parameters(declared: str) -> list[str]:
    """``prefix parent *origin **content radius:=0.1 reflect:=^|1`` -> the names."""
    return [word.lstrip("*").partition(":=")[0] for word in declared.split()]


def _condition(element: etree._Element) -> Condition | None:
    """``<xacro:if value>`` / ``<xacro:unless value>`` as a condition on its body."""
    value = element.get("value")
    if value is None or _local(element) not in ("if", "unless"):
        return None
    return Condition(value, None) if _local(element) == "if" else Condition(None, value)


def _declare(
    element: etree._Element, bindings: Bindings, conditions: tuple[Condition, ...]
) -> None:
    """Collect ``xacro:arg`` and ``xacro:property`` below ``element``, outside macros."""
    for child in _elements(element):
        if not _is_xacro(child):
            _declare(child, bindings, conditions)
            continue
        tag, name = _local(child), child.get("name")
        if tag in ("arg", "property") and name is not None:
            raw = child.get("value", child.get("default"))  # a block property has neither
            space = ARG if tag == "arg" else PROPERTY
            bindings.declare(space, name, Declaration(raw, conditions))
        elif tag != "macro":
            condition = _condition(child)
            _declare(child, bindings, (*conditions, condition) if condition else conditions)


class _Robot:
    """Walks a robot description and collects its names."""

    def __init__(self, document: xmlsafe.XmlDocument) -> None:
        self.document = document
        self.names: list[NameUse] = []

    def value(self, located: Located, bindings: Bindings) -> Value:
        if located.opaque:
            return Value(located.text, dynamic=True)
        return bindings.substitute(located.text)

    def emit(
        self,
        located: Located,
        value: Value,
        *,
        kind: Kind,
        role: Role,
        api: str,
        namespace: str | None = None,
    ) -> None:
        self.names.append(
            NameUse(
                kind=kind,
                value=value.text,
                span=located.span,
                role=role,
                api=api,
                dynamic=value.dynamic,
                namespace=namespace,
            )
        )

    def visit(self, element: etree._Element, bindings: Bindings, plugin: _Plugin | None) -> None:
        tag = _local(element)
        if _is_xacro(element):
            self.xacro(element, bindings, plugin)
        elif tag == "link" and plugin is None:
            self.link(element, bindings)
        elif tag in ("gazebo", "plugin"):
            inner = plugin or _Plugin()
            if tag == "plugin":
                inner = _Plugin(self.plugin_namespace(element, bindings))
            self.children(element, bindings, inner)
        elif plugin is not None and tag == "ros":
            self.ros_block(element, bindings, plugin)
        elif plugin is not None and not any(True for _ in _elements(element)):
            self.plugin_text(element, bindings, plugin)
        else:
            self.children(element, bindings, plugin)

    def children(self, element: etree._Element, bindings: Bindings, plugin: _Plugin | None) -> None:
        for child in _elements(element):
            self.visit(child, bindings, plugin)

    def xacro(self, element: etree._Element, bindings: Bindings, plugin: _Plugin | None) -> None:
        tag = _local(element)
        if tag == "macro":
            inner = bindings.child(_macro_parameters(element.get("params", "")))
            _declare(element, inner, ())
            self.children(element, inner, plugin)
        elif tag not in ("property", "arg", "include"):  # declarations were collected first
            condition = _condition(element)
            if condition is None or bindings.allows([condition]):
                self.children(element, bindings, plugin)

    def link(self, element: etree._Element, bindings: Bindings) -> None:
        located = self.document.attribute(element, "name")
        if located is not None:
            value = self.value(located, bindings)
            self.emit(located, value, kind=Kind.FRAME, role=Role.FRAME, api="<link name>")
        self.children(element, bindings, None)

    def plugin_namespace(self, element: etree._Element, bindings: Bindings) -> str | None:
        """The plugin node's namespace: ``<ros><namespace>`` or ``<robotNamespace>``."""
        for child in _elements(element):
            tag = _local(child)
            holder = child if tag == "robotNamespace" else None
            if tag == "ros":
                holder = next((c for c in _elements(child) if _local(c) == "namespace"), None)
            located = None if holder is None else self.document.text(holder)
            if located is not None:
                value = self.value(located, bindings)
                if value.dynamic or value.text.startswith("~"):
                    return None
                return "/" + value.text.strip("/") if value.text.strip("/") else "/"
        return None

    def plugin_text(self, element: etree._Element, bindings: Bindings, plugin: _Plugin) -> None:
        """A camelCase or snake_case plugin element whose text is a name."""
        tag = _local(element)
        kind_role = _plugin_tag_kind(tag)
        located = self.document.text(element) if kind_role else None
        if kind_role is None or located is None:
            return
        kind, role = kind_role
        namespace = plugin.namespace if kind in (Kind.TOPIC, Kind.SERVICE) else None
        value = self.value(located, bindings)
        self.emit(located, value, kind=kind, role=role, api=f"<{tag}>", namespace=namespace)

    def ros_block(self, element: etree._Element, bindings: Bindings, plugin: _Plugin) -> None:
        """gazebo_ros 2: ``<namespace>``, ``<remapping>``, ``<argument>``, ``<parameter>``."""
        for child in _elements(element):
            tag = _local(child)
            if tag == "parameter":
                located = self.document.attribute(child, "name")
                if located is not None:
                    value = self.value(located, bindings)
                    api = "<ros><parameter name>"
                    self.emit(located, value, kind=Kind.PARAMETER, role=Role.PARAMETER, api=api)
                continue
            located = self.document.text(child)
            if located is None:
                continue
            if tag == "namespace":
                value = self.value(located, bindings)
                api = "<ros><namespace>"
                self.emit(located, value, kind=Kind.NAMESPACE, role=Role.NAMESPACE, api=api)
            elif tag in ("remapping", "argument"):
                self.command_line(located, bindings, plugin, f"<ros><{tag}>")

    def command_line(self, located: Located, bindings: Bindings, plugin: _Plugin, api: str) -> None:
        """``from:=to``, ``__ns:=/x``, ``--ros-args -r a:=b``: every name on the line."""
        if located.opaque:
            return  # an entity reference hides the line: nothing on it is known
        for assignment in ros2_assignments(located, all_ros_args=False, bare=True):
            key = strip_node_prefix(assignment.key) if assignment.flag == "-r" else assignment.key
            sides = {
                "key": (key, self.value(key, bindings)),
                "value": (assignment.value, self.value(assignment.value, bindings)),
            }
            what = meaning(assignment.flag, sides["key"][1].text, Dialect.ROS2)
            for side, kind, role in _ASSIGNMENT_NAMES.get(what, ()) if what else ():
                at, value = sides[side]
                namespace = plugin.namespace if kind in (Kind.TOPIC, Kind.NODE) else None
                self.emit(at, value, kind=kind, role=role, api=api, namespace=namespace)


# Which side of ``key:=value`` holds which name.
_ASSIGNMENT_NAMES: dict[Meaning, tuple[tuple[str, Kind, Role], ...]] = {
    Meaning.NAMESPACE: (("value", Kind.NAMESPACE, Role.NAMESPACE),),
    Meaning.NODE: (("value", Kind.NODE, Role.NODE_NAME),),
    Meaning.REMAP: (("key", Kind.TOPIC, Role.REMAP_FROM), ("value", Kind.TOPIC, Role.REMAP_TO)),
    Meaning.PARAMETER: (("key", Kind.PARAMETER, Role.PARAMETER),),
}


def extract(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
) -> FileFacts:
    """Frames, namespaces and plugin names of a URDF or XACRO file."""
    document = xmlsafe.parse(data)
    if isinstance(document, ParseError):
        generation = evidence.decide(package_generation, None, None, fallback_generation)
        return FileFacts(path, Language.URDF, generation, parse_errors=(document,))
    found = evidence.urdf_evidence(document.root)
    generation = evidence.decide(package_generation, found, None, fallback_generation)
    bindings = Bindings(Dialect.XACRO)
    robot = _Robot(document)
    try:
        _declare(document.root, bindings, ())
        robot.visit(document.root, bindings, None)
    except RecursionError:
        error = ParseError("robot description nested too deeply to analyse", Span(1, 1, 1, 2))
        return FileFacts(path, Language.URDF, generation, parse_errors=(error,))
    names = sorted(robot.names, key=lambda use: (use.span.line, use.span.column))
    return FileFacts(path, Language.URDF, generation, names=tuple(names))

"""Which ROS generation a launch file or robot description was written for.

The nearest package.xml decides when there is one (the caller passes it in); otherwise the
file's own markers, which are unambiguous in practice: no ROS 2 launch file has
``<node type=...>`` or ``$(arg x)``, no ROS 1 one has ``exec=`` or ``<let>``. When the
markers disagree (a file half-ported), the side with more distinct markers wins and a tie
decides nothing.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING

from roslint_names.model import Generation

if TYPE_CHECKING:  # the XML extractors that call in here have lxml loaded; Python does not
    from lxml import etree

_ROS1_EXTENSIONS = (".launch", ".test")
_ROS2_SUFFIXES = (".launch.xml", "_launch.xml", ".launch.yaml", "_launch.yaml", ".launch.yml")


def extension_generation(path: str) -> Generation | None:
    """``.launch``/``.test`` are roslaunch files; ``.launch.xml``/``.launch.yaml`` ROS 2."""
    name = path.replace("\\", "/").rpartition("/")[2].lower()
    if name.endswith(_ROS1_EXTENSIONS):
        return Generation.ROS1
    if name.endswith(_ROS2_SUFFIXES):
        return Generation.ROS2
    return None


def decide(
    package: Generation | None,
    evidence: Generation | None,
    default: Generation | None,
    fallback: Generation,
) -> Generation:
    """The package wins, then the file's evidence, then its extension, then the config."""
    for candidate in (package, evidence, default):
        if candidate is not None:
            return candidate
    return fallback


def _vote(ros1: Iterable[str], ros2: Iterable[str]) -> Generation | None:
    ros1_count, ros2_count = len(set(ros1)), len(set(ros2))
    if ros1_count > ros2_count:
        return Generation.ROS1
    if ros2_count > ros1_count:
        return Generation.ROS2
    return None


def _elements(root: etree._Element) -> Iterator[etree._Element]:
    return (element for element in root.iter() if isinstance(element.tag, str))


def _local(element: etree._Element) -> str:
    from lxml import etree

    return etree.QName(element).localname


_ROS1_SUBSTITUTIONS = {"$(arg ": "$(arg", "$(find ": "$(find"}
_ROS2_SUBSTITUTIONS = {"$(var ": "$(var", "$(find-pkg-share ": "$(find-pkg-share"}
_ROS2_LAUNCH_TAGS = frozenset({"let", "push-ros-namespace", "push_ros_namespace"})


def launch_xml_evidence(root: etree._Element) -> Generation | None:
    """ROS 1: ``<node type=>``, ``$(arg``, ``$(find``. ROS 2: ``exec=``, ``<let>``,
    ``$(var``, ``$(find-pkg-share``, ``<push-ros-namespace>``."""
    ros1: list[str] = []
    ros2: list[str] = []
    for element in _elements(root):
        tag = _local(element)
        if tag == "node" and element.get("type") is not None:
            ros1.append("type=")
        if element.get("exec") is not None:
            ros2.append("exec=")
        if tag in _ROS2_LAUNCH_TAGS:
            ros2.append(tag.replace("_", "-"))
        for value in element.attrib.values():
            ros1.extend(marker for text, marker in _ROS1_SUBSTITUTIONS.items() if text in value)
            ros2.extend(marker for text, marker in _ROS2_SUBSTITUTIONS.items() if text in value)
    return _vote(ros1, ros2)


_ROS1_PLUGIN_TAG = re.compile(r"robotNamespace|topicName|\w+Topic(?:Name)?")


def urdf_evidence(root: etree._Element) -> Generation | None:
    """ROS 2: a ``<ros>`` block in a gazebo plugin. ROS 1: ``<robotNamespace>``,
    ``<topicName>``, ``<*Topic>`` (gazebo_ros 2 renamed them all)."""
    ros1: list[str] = []
    ros2: list[str] = []
    for element in _elements(root):
        tag = _local(element)
        parent = element.getparent()
        if tag == "ros" and parent is not None and _local(parent) == "plugin":
            ros2.append("<ros>")
        elif _ROS1_PLUGIN_TAG.fullmatch(tag) and _inside_plugin(element):
            ros1.append(tag if tag == "robotNamespace" else "topic")
    return _vote(ros1, ros2)


def _inside_plugin(element: etree._Element) -> bool:
    return any(_local(ancestor) in ("plugin", "gazebo") for ancestor in element.iterancestors())

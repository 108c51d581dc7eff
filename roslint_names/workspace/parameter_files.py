"""Which parameters a parameter file sets on a node, as the runtimes decide it.

ROS 2: a file handed to a node (``--params-file``) is read by rcl into one entry per node
key (rcl_yaml_param_parser ``parse.c``: ``parse_key``, ``find_node``); the client library
then keeps the entries whose key matches the node's fully qualified name
(rclcpp ``parameter_map.cpp``, ``parameter_map_from`` and ``is_node_name_matched``;
rclpy ``src/rclpy/node.cpp``, ``_populate_node_parameters_from_rcl_params``, the same
code): the key gets a leading '/' when it has none, every ``/*`` becomes ``(/\\w+)`` (so
``/**`` becomes ``(/\\w+)*``), and the result must match the whole name
(``std::regex_match``). A key ``*`` is thus ``/*``: one token, a node in the root
namespace only.

A composable node is not started with ``--params-file``: launch_ros reads the file itself
and keeps only the ``**`` entry and the entry of the node's ``namespace/name`` exactly,
leading '/' stripped, and nothing at all when the launch file gives the node no name
(launch_ros ``utilities/to_parameters_list.py``, ``to_parameters_list`` and
``__normalize_parameters_dict``; ``actions/load_composable_nodes.py``,
``get_composable_node_load_request``).

ROS 1: ``<rosparam command="load" file ns>`` sets every leaf of the file under the
namespace, its keys joined with '/' (roslaunch ``loader.py``, ``Loader.load_rosparam``
and ``Loader.add_param``).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from functools import lru_cache

from roslint_names.model import ParameterBlock


def key_matches(key: str, full_name: str, *, composable: bool = False) -> bool:
    """Whether a ROS 2 parameter file's node ``key`` applies to the node ``full_name``
    (``/ns/node``); ``composable``: a composable node, which launch_ros matches."""
    if composable:
        plain = key.lstrip("/")
        return plain == "**" or plain == full_name.lstrip("/")
    pattern = _pattern(key)
    return pattern is not None and pattern.fullmatch(full_name) is not None


@lru_cache(maxsize=1024)
def _pattern(key: str) -> re.Pattern[str] | None:
    """rclcpp's regular expression for ``key``; None where std::regex would refuse it."""
    absolute = key if key.startswith("/") else f"/{key}"
    text = absolute.replace("/*", r"(/\w+)")
    try:
        return re.compile(text, re.ASCII)
    except re.error:
        return None


def is_wildcard(key: str) -> bool:
    return "*" in key


def ros2_names(
    blocks: Iterable[ParameterBlock], full_name: str, *, composable: bool = False
) -> tuple[str, ...]:
    """The parameter names the file sets on the node ``full_name``."""
    return tuple(
        sorted(
            {
                name
                for block in blocks
                if block.key is not None
                and key_matches(block.key, full_name, composable=composable)
                for name, _ in block.parameters
            }
        )
    )


def ros1_names(blocks: Iterable[ParameterBlock], namespace: str) -> tuple[str, ...]:
    """The fully qualified names a ROS 1 file sets when loaded under ``namespace``."""
    base = namespace.rstrip("/")
    return tuple(
        sorted(
            {
                f"{base}/{name.strip('/')}"
                for block in blocks
                if block.key is None
                for name, _ in block.parameters
            }
        )
    )

"""Python: rospy and rclpy nodes, and ROS 2 Python launch files.

Discovery hands every ``.py`` file here. Most Python in a ROS workspace holds no ROS name
(setup.py, tools, libraries), so a cheap regex over the raw bytes decides first whether
the file imports a ROS module or defines a launch description; a file that does neither
yields empty facts without being decoded or parsed, and without libcst even being
imported (``python_source`` and the extractors import it, and are imported only here,
after the prefilter).

A file is a launch file (``Language.LAUNCH_PYTHON``) when its name says so
(``*.launch.py``, ``*_launch.py``), when it defines ``generate_launch_description`` (or
launch_testing's ``generate_test_description``), or when it builds launch_ros actions
without being rospy or rclpy code (a helper module returning ``Node`` actions): its
remaps and parameters then spell names chosen elsewhere, as in launch XML.
"""

from __future__ import annotations

import re
from dataclasses import replace

from roslint_names.model import (
    FileFacts,
    Generation,
    Language,
    LaunchArguments,
    ParseError,
    Span,
)
from roslint_names.reading import WIDE_ENCODINGS, bom_encoding

from .fixtures import rejected_fixtures

# A ROS import (rospy, rclpy, actionlib, tf/tf2, launch_ros, message_filters, any
# *_msgs/*_srvs package) or a launch description. ``import os, rospy`` counts too.
_ROS_MODULE = (
    rb"(?:rospy|rclpy|actionlib\w*|tf2?(?:_\w+)?|launch_ros|message_filters|\w+_(?:msgs|srvs))"
)
# Two searches, not one regex of three alternatives: the description's, which may start
# anywhere and not only at a line, made that one three times slower over real files.
_ROS_IMPORT = re.compile(
    rb"^(?:\xef\xbb\xbf)?[ \t]*(?:from[ \t]+" + _ROS_MODULE + rb"\b"
    rb"|import[ \t]+[^\n#]*?\b" + _ROS_MODULE + rb"\b)",
    re.MULTILINE,
)
_DESCRIPTION = re.compile(rb"\bgenerate_(?:launch|test)_description\b")
_LAUNCH_SUFFIXES = (".launch.py", "_launch.py")


def may_hold_names(data: bytes) -> bool:
    """The prefilter: False when the file cannot hold a ROS name we extract."""
    return _ROS_IMPORT.search(data) is not None or (
        b"_description" in data and _DESCRIPTION.search(data) is not None
    )


def is_launch_path(path: str) -> bool:
    name = path.replace("\\", "/").rpartition("/")[2].lower()
    return name.endswith(_LAUNCH_SUFFIXES)


def extract(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
    *,
    arguments: LaunchArguments = (),
    python2: bool = False,
) -> FileFacts:
    """Names, events, launch nodes and includes of a Python file; never raises on any bytes.

    ``arguments`` are launch configurations set before a launch file's description runs:
    what an including file hands over, winning over ``DeclareLaunchArgument`` defaults.
    Code that is not a launch file has no use for them. ``python2``: the file may be
    Python 2 (``generation.reads_python2``), which is then read, not refused.
    """
    facts = _extract(
        path, data, package_generation, fallback_generation, arguments=arguments, python2=python2
    )
    fixtures = rejected_fixtures(data)
    return replace(facts, rejected_fixtures=fixtures) if fixtures else facts


def _extract(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
    *,
    arguments: LaunchArguments,
    python2: bool,
) -> FileFacts:
    launch_path = is_launch_path(path)
    wide = bom_encoding(data)
    if wide in WIDE_ENCODINGS:  # the prefilter cannot read it, and neither can CPython
        language = Language.LAUNCH_PYTHON if launch_path else Language.PYTHON
        message = (
            f"Python source is {wide.upper()} (byte order mark); CPython reads only UTF-8 "
            "or a PEP 263 8-bit encoding: save it as UTF-8"
        )
        error = ParseError(message, Span(1, 1, 1, 2))
        return FileFacts(
            path, language, package_generation or fallback_generation, parse_errors=(error,)
        )
    if not may_hold_names(data):
        language = Language.LAUNCH_PYTHON if launch_path else Language.PYTHON
        return FileFacts(path, language, package_generation or fallback_generation)
    from roslint_names.extract.python.parsed import extract_parsed

    return extract_parsed(
        path,
        data,
        package_generation,
        fallback_generation,
        launch_path,
        arguments=arguments,
        python2=python2,
    )

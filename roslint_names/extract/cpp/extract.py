"""C++: roscpp and rclcpp names, and the init/handle order RN301 checks.

The file is decoded (UTF-8, with or without BOM, or UTF-16 or UTF-32 with a BOM), skipped when it
holds no ROS marker at all (most C++ of a robot workspace is algorithms and drivers), and
parsed once with tree-sitter-cpp. tree-sitter always yields a tree; macros and templates
it cannot follow become ERROR nodes, which are not parse errors to report: the sites
around them are still read. See ``cpp_source`` for how sites are found without walking
the whole tree, and ``cpp_sites`` for which names each API takes.

The generation is the package's when known, else the file's includes (``ros/``,
``actionlib/``, ``tf/`` for ROS 1; ``rclcpp*/`` for ROS 2), else its qualified names
(``ros::`` versus ``rclcpp::``), else the fallback.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

import tree_sitter
import tree_sitter_cpp
from tree_sitter import Node

from roslint_names.model import (
    FileFacts,
    Generation,
    Language,
    NameUse,
    ParseError,
    RuntimeEvent,
    Span,
)
from roslint_names.reading import bom_encoding

from ..literals import name_literals, unexplained_literals
from ..parameter_traits import (
    cpp_class_bases,
    parameter_traits,
    plugin_loaders,
    reconfigure_servers,
)
from .apis import CALL_WORDS, CONSTRUCTED_TYPES, FRAME_FIELDS
from .constants import header_constants, included_paths, included_sources, is_header
from .events import INIT_WORDS, handle_event, init_event
from .expected import ExpectedFailures
from .handles import Handles
from .objects import (
    NODE_BASES,
    Classes,
    Construction,
    constructions_named_by,
    member_constructions,
)
from .sites import Sites
from .source import Source, word_pattern
from .tf_roles import tf_roles
from .types import Types
from .values import Declarations, Folder

_PARSER = tree_sitter.Parser(tree_sitter.Language(tree_sitter_cpp.language()))

# A file without any of these cannot hold a site this extractor reads: each is the word a
# site is found by, then (when the word alone says too little) what must follow it. About
# half of the C++ files of a ROS workspace include rclcpp or ros/ and still name nothing.
_POINTER_TYPEDEF = rb"\b(?!::(?:SharedPtr|WeakPtr|ConstSharedPtr|UniquePtr)\b)"
# get_parameter_or, get_parameters; not get_parameters_by_prefix
_PARAMETER_METHOD = rb"(?:_or|_if_not_declared|s)?\b"
MARKERS: dict[str, bytes | None] = {
    "ros::init": None,
    "rclcpp::init": None,
    "::service::": None,  # ros::service::call
    "param::": None,  # ros::param::get
    "NodeHandle": None,
    "Node": rb"\s*\(",  # `: Node("talker")`
    "rclcpp::Node": _POINTER_TYPEDEF,
    "LifecycleNode": _POINTER_TYPEDEF,
    **dict.fromkeys(("advertise", "subscribe", "serviceClient"), None),
    **dict.fromkeys(("SubscribeOptions", "AdvertiseOptions"), None),
    **dict.fromkeys(("getParam", "setParam", "hasParam", "deleteParam", "searchParam"), None),
    "param": rb"\s*[<(]",  # nh.param(...), nh.param<T>(...)
    **dict.fromkeys(f"create_{what}" for what in ("publisher", "subscription", "service")),
    **dict.fromkeys(f"create_{what}" for what in ("client", "server", "generic", "action")),
    **{
        f"{verb}_parameter": _PARAMETER_METHOD
        for verb in ("declare", "get", "has", "undeclare", "describe")
    },
    "rclcpp::Parameter": rb"\b",
    "auto_declare": rb"\b",  # ros2_control's controllers
    "getOrDeclareParameter": rb"\s*[<(]",  # Autoware's (get_or_declare_parameter: above)
    "frame_id": rb"\s*=[^=]",  # frame_id = "map", not frame_id == "map"
    **dict.fromkeys(("lookupTransform", "canTransform", "waitForTransform"), None),
    **dict.fromkeys(f"transform{what}" for what in ("Pose", "Point", "Vector", "Quaternion")),
    "StampedTransform": None,
    "Stamped": rb"\s*<",  # tf::Stamped<tf::Pose>
    **dict.fromkeys(("ActionServer", "ActionClient", "ServiceClient", "ServiceServer"), None),
    "message_filters": None,
    "Subscriber": rb"\s*<",  # message_filters::Subscriber<T>
}
# Most C++ files hold no marker, and a regular expression of alternatives scans them
# slowly (re tries the alternatives at nearly every offset): bytes.find is some twenty
# times faster. So each marker is looked for on its own, and only in files holding a part
# it shares with others; few files hold any part.
_MARKER_PARTS = tuple(
    b"Node ubscribe ::init create_ dvertise aram ervice ransform Action frame_id Stamped"
    b" message_filters auto_declare".split()
)
_Marker = tuple[bytes, "re.Pattern[bytes] | None"]  # its word, what must follow it


def _markers_by_part(markers: dict[str, bytes | None]) -> dict[bytes, list[_Marker]]:
    by_part: dict[bytes, list[_Marker]] = {part: [] for part in _MARKER_PARTS}
    for word, follows in markers.items():
        encoded = word.encode("ascii")
        part = next((part for part in _MARKER_PARTS if part in encoded), None)
        if part is None:
            raise ValueError(f"the marker {word} holds none of _MARKER_PARTS")
        by_part[part].append((encoded, None if follows is None else re.compile(follows)))
    return by_part


_MARKERS_BY_PART = _markers_by_part(MARKERS)


def has_ros_marker(data: bytes) -> bool:
    """Whether the bytes hold a marker followed by what must follow it."""
    return any(
        part in data and any(_follows(data, word, context) for word, context in markers)
        for part, markers in _MARKERS_BY_PART.items()
    )


def _follows(data: bytes, word: bytes, context: re.Pattern[bytes] | None) -> bool:
    if context is None:
        return word in data
    position = data.find(word)
    while position >= 0:
        if context.match(data, position + len(word)):
            return True
        position = data.find(word, position + 1)
    return False


def _unexplained(text: bytes, names: Sequence[NameUse]) -> tuple[str, ...]:
    """The literals the sites do not account for, in a file that may name parameters."""
    if b"aram" in text or b"declare" in text:
        return unexplained_literals(text, names)
    return ()


_ROS1_INCLUDE = re.compile(rb'#[ \t]*include[ \t]*[<"](?:ros|actionlib|tf|nodelet)/')
_ROS2_INCLUDE = re.compile(rb'#[ \t]*include[ \t]*[<"]rclcpp(?:_action|_lifecycle|_components)?/')
_ROS1_CODE = re.compile(rb"ros::(?:NodeHandle|init|Publisher|Subscriber|Rate|spin)\b")
_ROS2_CODE = re.compile(rb"rclcpp(?:_action|_lifecycle)?::")
_UTF8_BOM = b"\xef\xbb\xbf"


def extract(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
) -> FileFacts:
    """Names and runtime events of one C++ source or header."""
    text, error = decode(data)
    header = is_header(path)
    constants = header_constants(text) if header else ()
    if not has_ros_marker(text):
        generation = package_generation or fallback_generation
        return FileFacts(
            path,
            Language.CPP,
            generation,
            parse_errors=_errors(error),
            constants=constants,
            cpp_includes=included_paths(text) if header else (),
            included_sources=included_sources(text),
            # A header may hold a node's base class and what it does; a source with no
            # ROS marker is no node's (but a helper's caller need name no ROS API:
            # ``declare(node, "rate")``).
            parameter_traits=parameter_traits(text),
            plugin_loaders=plugin_loaders(text),
            reconfigure_servers=reconfigure_servers(text, python=False),
            class_bases=cpp_class_bases(text) if header else (),
            unexplained_literals=_unexplained(text, ()),
        )
    generation = package_generation or file_generation(text) or fallback_generation
    source = Source(text, _PARSER.parse(text))
    names, events = facts_of(source)
    return FileFacts(
        path=path,
        language=Language.CPP,
        generation=generation,
        names=tuple(sorted(names, key=lambda use: (use.span, use.kind.value, use.role.value))),
        events=tuple(sorted(events, key=lambda event: (event.scope, event.order))),
        parse_errors=_errors(error),
        literals=name_literals(text),
        parameter_traits=parameter_traits(text),
        plugin_loaders=plugin_loaders(text),
        reconfigure_servers=reconfigure_servers(text, python=False),
        class_bases=cpp_class_bases(text),
        unexplained_literals=_unexplained(text, names),
        constants=constants,
        # Every parsed file's: its node's parameters may be declared in what it includes.
        cpp_includes=included_paths(text),
        tf_roles=tf_roles(source),
        included_sources=included_sources(text),
    )


def facts_of(source: Source) -> tuple[list[NameUse], list[RuntimeEvent]]:
    """Every name and runtime event of a parsed file."""
    anchors = source.words(_ANCHORS, _ANCHOR_PARTS)  # every site's word, in order
    folder = Folder(source, Declarations(source))
    classes = Classes(source)
    constructions = _constructions(source, classes, anchors)
    handles = Handles(source, folder, classes, constructions)
    sites = Sites(source, folder, classes, handles, Types(source))
    events: list[RuntimeEvent] = []
    for construction in constructions:
        sites.construction(construction)
        events.extend(_present(handle_event(source, classes, construction)))
    for word, node in anchors:
        if word in INIT_WORDS:
            events.extend(_present(init_event(source, node)))
        if word in FRAME_FIELDS:
            sites.frame_field(word, node)
        elif word in NODE_BASES:
            sites.base_initializer(word, node)
        elif word in CALL_WORDS:
            sites.call(word, node)
    names, events = list(dict.fromkeys(sites.names)), list(dict.fromkeys(events))
    expected = ExpectedFailures(source)
    return (
        [use for use in names if not expected.holds(use.span)],
        [event for event in events if not expected.holds(event.span)],
    )


def _constructions(
    source: Source, classes: Classes, anchors: list[tuple[str, Node]]
) -> list[Construction]:
    """What the file builds, members built by its constructors included."""
    words = [node for word, node in anchors if word in CONSTRUCTED_TYPES]
    for name in sorted(classes.nodes.keys() | classes.holders):
        words.extend(source.occurrences(name))
    found = [c for word in words for c in constructions_named_by(source, word)]
    return found + member_constructions(source, found)


def _present(event: RuntimeEvent | None) -> list[RuntimeEvent]:
    return [] if event is None else [event]


_ANCHOR_WORDS = CALL_WORDS | FRAME_FIELDS | INIT_WORDS | CONSTRUCTED_TYPES
_ANCHORS = word_pattern(_ANCHOR_WORDS)
# What Source.words finds the anchor words by: each holds one of these parts, which few
# other identifiers hold.
_ANCHOR_PARTS = tuple(
    b"Node aram ervice create_ Action Stamped Transform transform ubscribe dvertise frame_id"
    b" init ForMessage _for_message auto_declare".split()
)
if unfound := [w for w in _ANCHOR_WORDS if not any(p in w.encode() for p in _ANCHOR_PARTS)]:
    raise ValueError(f"anchor words holding none of _ANCHOR_PARTS: {unfound}")


# ---------------------------------------------------------------------------------------
# Decoding and generation


def decode(data: bytes) -> tuple[bytes, ParseError | None]:
    """UTF-8 bytes to parse, and the decoding problem to report, if any.

    Undecodable bytes become U+FFFD exactly as the engine's display text does, so spans
    agree with the lines shown next to findings; the rest of the file is still read.
    """
    encoding = bom_encoding(data) or "utf-8"
    if encoding == "utf-8-sig":
        data, encoding = data[len(_UTF8_BOM) :], "utf-8"  # the display text drops it too
    try:
        text = data.decode(encoding)
    except UnicodeDecodeError as problem:
        replaced = data.decode(encoding, errors="replace").encode("utf-8")
        return replaced, _decode_error(data, problem)
    return (data if encoding == "utf-8" else text.encode("utf-8")), None


def _decode_error(data: bytes, problem: UnicodeDecodeError) -> ParseError:
    before = data[: problem.start].decode(problem.encoding, errors="replace").lstrip("\ufeff")
    line = before.count("\n") + 1
    column = len(before) - (before.rfind("\n") + 1) + 1
    return ParseError(
        f"not valid {problem.encoding.upper()}: byte 0x{data[problem.start]:02x} "
        f"at offset {problem.start}",
        Span(line, column, line, column + 1),
    )


def _errors(error: ParseError | None) -> tuple[ParseError, ...]:
    return () if error is None else (error,)


def file_generation(text: bytes) -> Generation | None:
    """The generation the file's includes (else its qualified names) say, if they agree."""
    for ros1, ros2 in ((_ROS1_INCLUDE, _ROS2_INCLUDE), (_ROS1_CODE, _ROS2_CODE)):
        one, two = bool(ros1.search(text)), bool(ros2.search(text))
        if one != two:
            return Generation.ROS1 if one else Generation.ROS2
        if one and two:
            return None  # a bridge between the generations: the fallback decides
    return None

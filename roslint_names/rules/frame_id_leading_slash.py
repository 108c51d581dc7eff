"""RN205 frame-id-leading-slash: a frame id starting with '/' where tf2 refuses it.

tf2 treats the slash differently by use (``tf2/src/buffer_core.cpp`` in ros/geometry2
noetic-devel and ros2/geometry2 rolling):

- ``BufferCore::setTransform`` (ROS 1) and ``BufferCore::setTransformImpl`` (ROS 2) strip
  one leading '/' from a received transform's ``frame_id`` and ``child_frame_id``: a frame
  only *broadcast* with a slash is stored without it, and every lookup of ``world`` finds
  ``/world``'s transform. tf2_ros's own ``StaticTransformBroadcasterNode`` defaults its
  ``frame_id``/``child_frame_id`` parameters to ``"/frame"``/``"/child"``.
- ``BufferCore::validateFrameId``, which ``lookupTransform``, ``canTransform`` (and so
  ``waitForTransform``, ``tf2_ros::Buffer::transform`` and the message filters) call on
  every frame they are given, refuses a leading '/': ``lookupTransform`` throws
  ``tf2::InvalidArgumentException``, ``canTransform`` returns false.

So a frame only broadcast is not reported (nothing breaks): one a launch file gives a
static transform broadcaster, as parameters or as static_transform_publisher's arguments,
and every frame of code that names a broadcaster and nothing else that could use a frame.
Every other use (a lookup's argument, a message header whose frame someone transforms, a
node's frame parameter, a URDF link) is.
"""

from __future__ import annotations

from collections.abc import Iterator

from ..model import (
    FileFacts,
    Finding,
    Generation,
    Kind,
    LaunchNode,
    NameUse,
    Role,
    Severity,
    Span,
    TfRole,
)
from ..rule import Rule, RuleContext
from .common import fix_hint, grammar_problems, suggested_fix

# tf2_ros's static transform broadcaster, as a launch file starts it: the component, and
# the program that runs it (ros2/geometry2 tf2_ros/src/static_transform_broadcaster_node.cpp
# turns its frame_id/child_frame_id parameters into the broadcast transform's frames), and
# ROS 1 tf's and tf2_ros's static_transform_publisher. Every frame it is given is broadcast.
_STATIC_BROADCASTERS = frozenset(
    {
        ("tf2_ros", "static_transform_publisher"),
        ("tf2_ros", "tf2_ros::StaticTransformBroadcasterNode"),
        ("tf", "static_transform_publisher"),
    }
)
# Frames only sent, by the API the extractors name them with: ROS 1 Python tf's
# TransformBroadcaster.sendTransform(translation, rotation, time, child, parent), the
# header and child frames of a C++ message handed to sendTransform in the function that
# sets them (extract/cpp/apis.py's SENT_FRAME_FIELD), and the two frames a launch file
# gives static_transform_publisher as arguments (extract/launch/static_transform.py's
# FRAME_API and CHILD_FRAME_API). tf2's setTransform strips the slash on the receiving
# side.
_BROADCAST_APIS = frozenset(
    {
        "tf sendTransform",
        "sendTransform frame_id",
        "sendTransform child_frame_id",
        "static_transform_publisher frame_id",
        "static_transform_publisher child_frame_id",
    }
)
# Endpoints that send a message or get one back: a frame of the file may be stamped on it.
_SENDING_ROLES = frozenset(
    {Role.PUBLISH, Role.SERVE, Role.CALL, Role.ACTION_SERVE, Role.ACTION_CALL}
)
# Lookups, by the API the extractors name (C++ call names, Python "tf <method>").
_LOOKUP_WORDS = ("lookup", "canTransform", "can_transform", "waitForTransform", "transform")


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    # tf2 in ROS 2 refuses the frame: dropping the slash cannot break what works. ROS 1's
    # tf (not tf2) kept '/map' and 'map' apart under tf_prefix: there it is not certain.
    safe = facts.generation is Generation.ROS2
    broadcast = _broadcast_only(facts)
    for use, problem in grammar_problems(facts, RULE.code):
        if use.span in broadcast:
            continue
        message = f"frame id '{use.value}' starts with '/': {_what_fails(use)}{fix_hint(problem)}"
        yield Finding(use.span, message, fix=suggested_fix(use, problem, safe=safe))


def _what_fails(use: NameUse) -> str:
    """What tf2 does with the frame at this use, from BufferCore::validateFrameId."""
    if use.api.startswith("tf ") or any(word in use.api for word in _LOOKUP_WORDS):
        if "can" in use.api.lower():
            return "canTransform returns false for it (tf2 BufferCore::validateFrameId)"
        return "tf2's lookups throw InvalidArgumentException for it (BufferCore::validateFrameId)"
    if "frame_id" in use.api and "parameters" not in use.api:
        return "a message stamped with it cannot be transformed (tf2 BufferCore::validateFrameId)"
    # A frame parameter (or its default): what the node does with it is not known here.
    # Looked up or stamped on a message it fails; only broadcast, tf2 strips the slash.
    return "a lookup of it, or of a message stamped with it, fails (tf2 validateFrameId)"


def _broadcast_only(facts: FileFacts) -> frozenset[Span]:
    """The spans of frames only broadcast: those a launch file gives a static transform
    broadcaster (as parameters or arguments), ROS 1 Python tf's ``sendTransform``
    frames, and every frame of code that only broadcasts."""
    if _only_broadcasts(facts):
        return frozenset(use.span for use in facts.names if use.kind is Kind.FRAME)
    found = {use.span for use in facts.names if use.api in _BROADCAST_APIS}
    if not facts.launch_nodes:
        return frozenset(found)
    nodes = sorted(facts.launch_nodes, key=lambda node: node.span)
    for use in facts.names:
        if use.kind is Kind.FRAME and _is_broadcaster(_node_before(nodes, use.span)):
            found.add(use.span)
    return frozenset(found)


def _only_broadcasts(facts: FileFacts) -> bool:
    """Code whose frames can only reach a tf broadcaster: it names a broadcaster, no tf
    buffer, listener or lookup (``FileFacts.tf_roles``), and no endpoint that sends a
    message (which might carry a frame in its header) or takes one back. tf2_ros's own
    ``StaticTransformBroadcasterNode`` (ros2/geometry2 ``static_transform_broadcaster_node
    .cpp``) declares its ``frame_id`` and ``child_frame_id`` parameters with the defaults
    ``"/frame"`` and ``"/child"`` and sends them through a ``StaticTransformBroadcaster``:
    tf2's setTransformImpl strips them."""
    if facts.tf_roles != (TfRole.BROADCAST,):
        return False
    return not any(use.role in _SENDING_ROLES for use in facts.names)


def _node_before(nodes: list[LaunchNode], span: Span) -> LaunchNode | None:
    """The launch node whose attributes come last before ``span``: the one a parameter or
    argument there is given to (a node's parameters follow its package, name or plugin)."""
    before = None
    for node in nodes:
        if node.span >= span:
            break
        before = node
    return before


def _is_broadcaster(node: LaunchNode | None) -> bool:
    return node is not None and (node.package, node.executable) in _STATIC_BROADCASTERS


RULE = Rule(
    code="RN205",
    name="frame-id-leading-slash",
    summary="A tf frame id starting with '/' where tf2 refuses it (lookups, headers, parameters)",
    severity=Severity.ERROR,
    ros1_severity=Severity.WARNING,
    check=check,
)

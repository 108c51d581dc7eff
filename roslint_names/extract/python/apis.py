"""The rospy, actionlib, rclpy and tf APIs that take a ROS name, and where they take it.

A table row says which argument holds the name (by position and keyword), which holds the
message, service or action type, which holds a parameter's default, and what RN301 sees
in the call (an init, or a construction that needs one).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import libcst as cst

from roslint_names.extract.launch.common import is_frame_parameter
from roslint_names.model import EventKind, Kind, ParameterAccess, Role


@dataclass(frozen=True)
class Arg:
    """Where an argument is: its position (None: keyword only) and keyword names."""

    position: int | None
    keywords: tuple[str, ...]


def arg(spec: str) -> Arg:
    """``"1:topic"``: second positional or ``topic=``; ``":namespace"``: keyword only."""
    position, _, keywords = spec.partition(":")
    return Arg(int(position) if position else None, tuple(keywords.split("|")))


@dataclass(frozen=True)
class Use:
    """What a name is and who took it: the fields a ``NameUse`` shares across sites."""

    kind: Kind
    role: Role
    api: str  # for messages: "rospy.Publisher"
    access: ParameterAccess | None = None  # a parameter's: ``PARAMETER_ACCESS`` by default


@dataclass(frozen=True)
class Api:
    """One API that takes a name: which argument holds it, and what RN301 sees."""

    api: str
    use: Use | None  # None: no name (rclpy.init)
    name: Arg | None = None
    type: Arg | None = None
    default: Arg | None = None  # a parameter's default or value (frame ids)
    event: EventKind | None = None
    private_only: bool = False  # a HANDLE only when the name is private (``~name``)


class _Needs(Enum):
    """What RN301 sees in a table row (see ``ROSPY`` for rospy's two cases)."""

    INIT = "init"
    HANDLE = "handle"
    PRIVATE = "private"  # a HANDLE when the name is ``~private``


_Row = tuple[str, str, Kind | None, Role, str | None, str | None, str | None, _Needs | None]
_HANDLE, _INIT, _PRIVATE = _Needs.HANDLE, _Needs.INIT, _Needs.PRIVATE
_NODE, _NAME = Kind.NODE, Role.NODE_NAME
_PARAM, _TOPIC, _SERVICE, _ACTION = Kind.PARAMETER, Kind.TOPIC, Kind.SERVICE, Kind.ACTION


def _table(*rows: _Row) -> dict[str, Api]:
    """Rows of (key, api, kind, role, name, type, default, event); specs as for ``arg``."""
    table: dict[str, Api] = {}
    for key, api, kind, role, name, type_, default, event in rows:
        table[key] = Api(
            api,
            None if kind is None else Use(kind, role, api),
            None if name is None else arg(name),
            None if type_ is None else arg(type_),
            None if default is None else arg(default),
            None if event is None else EventKind.INIT if event is _INIT else EventKind.HANDLE,
            event is _PRIVATE,
        )
    return table


# rospy re-exports everything at its top level (``rospy.topics.Publisher`` is
# ``rospy.Publisher``), so its APIs are keyed by their last component; so are actionlib's.
#
# RN301 and rospy: rospy *allows* topics before init_node (topics.py: "we allow topics and
# services to be initialized before the node") and registers them when init_node runs,
# except a ~private topic, which raises ValueError; actionlib's servers and clients are
# topics. Before init_node, names.resolve_name knows neither the node's remappings nor its
# name: a service or service proxy ignores a launch file's <remap> (services are remapped
# often, so they always need init_node first), and get_param("~x") silently reads
# /unnamed/x (parameters are rarely remapped: only ~private ones need it).
# fmt: off
ROSPY = _table(
    ("init_node", "rospy.init_node", _NODE, _NAME, "0:name", None, None, _INIT),
    ("Publisher", "rospy.Publisher", _TOPIC, Role.PUBLISH, "0:name", "1:data_class", None,
     _PRIVATE),
    ("Subscriber", "rospy.Subscriber", _TOPIC, Role.SUBSCRIBE, "0:name", "1:data_class", None,
     _PRIVATE),
    ("Service", "rospy.Service", _SERVICE, Role.SERVE, "0:name", "1:service_class", None,
     _HANDLE),
    ("ServiceProxy", "rospy.ServiceProxy", _SERVICE, Role.CALL, "0:name", "1:service_class",
     None, _HANDLE),
    ("wait_for_message", "rospy.wait_for_message", _TOPIC, Role.SUBSCRIBE, "0:topic",
     "1:topic_type", None, _PRIVATE),
    ("wait_for_service", "rospy.wait_for_service", _SERVICE, Role.CALL, "0:service", None,
     None, None),
    ("get_param", "rospy.get_param", _PARAM, Role.PARAMETER, "0:param_name", None, "1:default",
     _PRIVATE),
    ("get_param_cached", "rospy.get_param_cached", _PARAM, Role.PARAMETER, "0:param_name",
     None, "1:default", None),
    ("set_param", "rospy.set_param", _PARAM, Role.PARAMETER, "0:param_name", None,
     "1:param_value", None),
    ("has_param", "rospy.has_param", _PARAM, Role.PARAMETER, "0:param_name", None, None, None),
    ("delete_param", "rospy.delete_param", _PARAM, Role.PARAMETER, "0:param_name", None, None,
     None),
    ("search_param", "rospy.search_param", _PARAM, Role.PARAMETER, "0:param_name", None, None,
     None),
)
ACTIONLIB = _table(
    ("SimpleActionServer", "actionlib.SimpleActionServer", _ACTION, Role.ACTION_SERVE,
     "0:name", "1:ActionSpec", None, _PRIVATE),
    ("SimpleActionClient", "actionlib.SimpleActionClient", _ACTION, Role.ACTION_CALL, "0:ns",
     "1:ActionSpec", None, _PRIVATE),
    ("ActionServer", "actionlib.ActionServer", _ACTION, Role.ACTION_SERVE, "0:ns",
     "1:ActionSpec", None, _PRIVATE),
    ("ActionClient", "actionlib.ActionClient", _ACTION, Role.ACTION_CALL, "0:ns",
     "1:ActionSpec", None, _PRIVATE),
)
# rclpy callables by qualified name: its modules do not re-export one another.
RCLPY = _table(
    ("rclpy.init", "rclpy.init", None, Role.OTHER, None, None, None, _INIT),
    ("rclpy.create_node", "rclpy.create_node", _NODE, _NAME, "0:node_name", None, None,
     _HANDLE),
    ("rclpy.node.Node", "rclpy.node.Node", _NODE, _NAME, "0:node_name", None, None, _HANDLE),
    ("rclpy.lifecycle.Node", "rclpy.lifecycle.Node", _NODE, _NAME, "0:node_name", None, None,
     _HANDLE),
    ("rclpy.lifecycle.LifecycleNode", "rclpy.lifecycle.LifecycleNode", _NODE, _NAME,
     "0:node_name", None, None, _HANDLE),
    ("rclpy.action.ActionServer", "rclpy.action.ActionServer", _ACTION, Role.ACTION_SERVE,
     "2:action_name", "1:action_type", None, None),
    ("rclpy.action.ActionClient", "rclpy.action.ActionClient", _ACTION, Role.ACTION_CALL,
     "2:action_name", "1:action_type", None, None),
    ("rclpy.parameter.Parameter", "rclpy.parameter.Parameter", _PARAM, Role.PARAMETER,
     "0:name", None, "2:value", None),
    ("rclpy.wait_for_message.wait_for_message", "rclpy.wait_for_message.wait_for_message",
     _TOPIC, Role.SUBSCRIBE, "2:topic", "0:msg_type", None, None),
)
# message_filters.Subscriber: rospy's arguments in ROS 1, (node, type, topic) in ROS 2.
MESSAGE_FILTERS = {
    "ros1": _table(
        ("message_filters.Subscriber", "message_filters.Subscriber", _TOPIC, Role.SUBSCRIBE,
         "0:name", "1:data_class", None, _PRIVATE),
    ),
    "ros2": _table(
        ("message_filters.Subscriber", "message_filters.Subscriber", _TOPIC, Role.SUBSCRIBE,
         "2:topic", "1:msg_type", None, None),
    ),
}
# rclpy.node.Node's methods, matched on any receiver in rclpy code.
RCLPY_METHODS = _table(
    ("create_publisher", "rclpy.node.Node.create_publisher", _TOPIC, Role.PUBLISH, "1:topic",
     "0:msg_type", None, None),
    ("create_subscription", "rclpy.node.Node.create_subscription", _TOPIC, Role.SUBSCRIBE,
     "1:topic", "0:msg_type", None, None),
    ("create_service", "rclpy.node.Node.create_service", _SERVICE, Role.SERVE, "1:srv_name",
     "0:srv_type", None, None),
    ("create_client", "rclpy.node.Node.create_client", _SERVICE, Role.CALL, "1:srv_name",
     "0:srv_type", None, None),
    ("declare_parameter", "rclpy.node.Node.declare_parameter", _PARAM, Role.PARAMETER,
     "0:name", None, "1:value", None),
    ("get_parameter", "rclpy.node.Node.get_parameter", _PARAM, Role.PARAMETER, "0:name", None,
     None, None),
    ("get_parameter_or", "rclpy.node.Node.get_parameter_or", _PARAM, Role.PARAMETER, "0:name",
     None, None, None),
    ("has_parameter", "rclpy.node.Node.has_parameter", _PARAM, Role.PARAMETER, "0:name", None,
     None, None),
    ("undeclare_parameter", "rclpy.node.Node.undeclare_parameter", _PARAM, Role.PARAMETER,
     "0:name", None, None, None),
    ("describe_parameter", "rclpy.node.Node.describe_parameter", _PARAM, Role.PARAMETER,
     "0:name", None, None, None),
    ("get_parameters_by_prefix", "rclpy.node.Node.get_parameters_by_prefix", _PARAM,
     Role.PARAMETER, "0:prefix", None, None, None),
)
# fmt: on
RCLPY_ALIASES = {
    "rclpy.action.server.ActionServer": "rclpy.action.ActionServer",
    "rclpy.action.client.ActionClient": "rclpy.action.ActionClient",
    "rclpy.lifecycle.node.LifecycleNode": "rclpy.lifecycle.LifecycleNode",
    "rclpy.Parameter": "rclpy.parameter.Parameter",
}
NODE_CLASSES = frozenset(
    {
        "rclpy.node.Node",
        "rclpy.lifecycle.Node",
        "rclpy.lifecycle.LifecycleNode",
        "rclpy.lifecycle.node.LifecycleNode",
    }
)
NODE_FACTORIES = frozenset({"rclpy.create_node", *NODE_CLASSES})
GET_PARAMETERS = "rclpy.node.Node.get_parameters"
DECLARE_PARAMETERS = "rclpy.node.Node.declare_parameters"

# What each API does with a parameter (rclpy/node.py: ``Node.get_parameter``,
# ``get_parameters`` and ``describe_parameter`` raise ParameterNotDeclaredException for an
# undeclared name unless undeclared parameters are allowed; ``get_parameter_or`` returns
# the alternative). rospy has no declarations: every access reads or writes the server.
_D, _R, _Q = ParameterAccess.DECLARE, ParameterAccess.READ, ParameterAccess.READ_QUIETLY
_C, _W, _P = ParameterAccess.CHECK, ParameterAccess.WRITE, ParameterAccess.READ_PREFIX
PARAMETER_ACCESS: dict[str, ParameterAccess] = {
    "rospy.get_param": _R,
    "rospy.get_param_cached": _R,
    "rospy.set_param": _W,
    "rospy.has_param": _C,
    "rospy.delete_param": _W,
    "rospy.search_param": _C,
    "rclpy.node.Node.declare_parameter": _D,
    DECLARE_PARAMETERS: _D,
    "rclpy.node.Node.get_parameter": _R,
    GET_PARAMETERS: _R,
    "rclpy.node.Node.get_parameter_or": _Q,
    "rclpy.node.Node.get_parameters_by_prefix": _P,
    "rclpy.node.Node.has_parameter": _C,
    "rclpy.node.Node.undeclare_parameter": _W,
    "rclpy.node.Node.describe_parameter": _R,
}

# tf and tf2 lookups: the arguments holding frame ids.
_TARGET, _SOURCE = arg("0:target_frame"), arg("1:source_frame")
_FULL = (_TARGET, arg("2:source_frame"), arg("4:fixed_frame"))
TF_METHODS: dict[str, tuple[Arg, ...]] = {
    "lookup_transform": (_TARGET, _SOURCE),
    "can_transform": (_TARGET, _SOURCE),
    "wait_for_transform_async": (_TARGET, _SOURCE),
    "lookup_transform_async": (_TARGET, _SOURCE),
    "lookup_transform_full": _FULL,
    "can_transform_full": _FULL,
    "lookup_transform_full_async": _FULL,
    "lookupTransform": (_TARGET, _SOURCE),
    "canTransform": (_TARGET, _SOURCE),
    "waitForTransform": (_TARGET, _SOURCE),
    "lookupTransformFull": _FULL,
    "canTransformFull": _FULL,
    "waitForTransformFull": _FULL,
    "transformPoint": (_TARGET,),
    "transformPose": (_TARGET,),
    "transformVector3": (_TARGET,),
    "transformQuaternion": (_TARGET,),
}
# ROS 1 tf.TransformBroadcaster.sendTransform(translation, rotation, time, child, parent).
SEND_TRANSFORM = (arg("3:child"), arg("4:parent"))


def is_frame_field(name: str) -> bool:
    """``frame_id``, ``child_frame_id``, ``*_frame_id``, ``*_frame``: attributes and keyword
    arguments holding a tf frame id. A bare ``frame`` is too often a camera image."""
    return name != "frame" and is_frame_parameter(name)


def argument(call: cst.Call, where: Arg) -> cst.BaseExpression | None:
    """The expression passed for an argument; None when absent or hidden by ``*args``."""
    for item in call.args:
        if item.keyword is not None and item.keyword.value in where.keywords:
            return item.value
    if where.position is None:
        return None
    positional = 0
    for item in call.args:
        if item.keyword is not None or item.star == "**":
            continue
        if item.star == "*":
            return None  # positions after *args are unknown
        if positional == where.position:
            return item.value
        positional += 1
    return None


def positional_count(call: cst.Call) -> int:
    return sum(1 for item in call.args if item.keyword is None and not item.star)

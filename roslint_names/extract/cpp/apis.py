"""The roscpp and rclcpp APIs that take names: which argument, of which kind and role.

Tables only; ``cpp_sites`` reads the calls. ``api`` strings name the API in messages.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from roslint_names.model import Kind, ParameterAccess, Role


@dataclass(frozen=True)
class Endpoint:
    kind: Kind
    role: Role
    api: str


ENDPOINTS = {
    "advertise": Endpoint(Kind.TOPIC, Role.PUBLISH, "ros::NodeHandle::advertise"),
    "serviceClient": Endpoint(Kind.SERVICE, Role.CALL, "ros::NodeHandle::serviceClient"),
    "create_publisher": Endpoint(Kind.TOPIC, Role.PUBLISH, "rclcpp::Node::create_publisher"),
    "create_subscription": Endpoint(
        Kind.TOPIC, Role.SUBSCRIBE, "rclcpp::Node::create_subscription"
    ),
    "create_service": Endpoint(Kind.SERVICE, Role.SERVE, "rclcpp::Node::create_service"),
    "create_client": Endpoint(Kind.SERVICE, Role.CALL, "rclcpp::Node::create_client"),
    "create_generic_publisher": Endpoint(
        Kind.TOPIC, Role.PUBLISH, "rclcpp::Node::create_generic_publisher"
    ),
    "create_generic_subscription": Endpoint(
        Kind.TOPIC, Role.SUBSCRIBE, "rclcpp::Node::create_generic_subscription"
    ),
    # image_transport: a camera publisher is an image topic and its camera_info beside it
    "advertiseCamera": Endpoint(
        Kind.TOPIC, Role.PUBLISH, "image_transport::ImageTransport::advertiseCamera"
    ),
    "subscribeCamera": Endpoint(
        Kind.TOPIC, Role.SUBSCRIBE, "image_transport::ImageTransport::subscribeCamera"
    ),
    "create_camera_publisher": Endpoint(
        Kind.TOPIC, Role.PUBLISH, "image_transport::create_camera_publisher"
    ),
    "create_camera_subscription": Endpoint(
        Kind.TOPIC, Role.SUBSCRIBE, "image_transport::create_camera_subscription"
    ),
    # nav2::LifecycleNode's wrappers around rclcpp_action
    "create_action_server": Endpoint(
        Kind.ACTION, Role.ACTION_SERVE, "nav2::LifecycleNode::create_action_server"
    ),
    "create_action_client": Endpoint(
        Kind.ACTION, Role.ACTION_CALL, "nav2::LifecycleNode::create_action_client"
    ),
}
CAMERA_ENDPOINTS = frozenset(
    {"advertiseCamera", "subscribeCamera", "create_camera_publisher", "create_camera_subscription"}
)
ACTION_FUNCTIONS = {
    "create_server": Endpoint(Kind.ACTION, Role.ACTION_SERVE, "rclcpp_action::create_server"),
    "create_client": Endpoint(Kind.ACTION, Role.ACTION_CALL, "rclcpp_action::create_client"),
}
SERVICE_FUNCTIONS = frozenset({"call", "waitForService", "exists"})  # ros::service::
# One message, waited for: (namespace, argument holding the topic, api) per function; a
# member function of the same name (moveit's SynchronizedStringParameter) is not it.
WAIT_FOR_MESSAGE = {
    "waitForMessage": ("topic", 0, "ros::topic::waitForMessage"),  # (topic[, nh][, timeout])
    "wait_for_message": ("rclcpp", 2, "rclcpp::wait_for_message"),  # (msg, node, topic, ...)
}


_DECLARE, _READ = ParameterAccess.DECLARE, ParameterAccess.READ
_QUIETLY = ParameterAccess.READ_QUIETLY
_CHECK, _WRITE = ParameterAccess.CHECK, ParameterAccess.WRITE


@dataclass(frozen=True)
class ParameterSite:
    name: int  # the argument holding the parameter's name
    value: int | None  # the argument holding its default or new value
    api: str
    access: ParameterAccess | None  # None: no access of the node's (``rclcpp::Parameter``)
    minimum: int = 1  # the fewest arguments the call takes (the value's form may vary)
    # From this many arguments on, a read that throws becomes one that does not: rclcpp's
    # ``Node::get_parameter(name)`` calls ``NodeParameters::get_parameter(name)``, which
    # throws ``ParameterNotDeclaredException``; ``get_parameter(name, value)`` calls
    # ``NodeParameters::get_parameter(name, parameter)``, which returns false
    # (rclcpp/src/rclcpp/node_interfaces/node_parameters.cpp).
    quiet_from: int | None = None


# roscpp NodeHandle methods; `param` takes its default last: (name, var, default) or
# (name, default).
ROS1_PARAMETERS = {
    "param": ParameterSite(0, -1, "ros::NodeHandle::param", _READ, minimum=2),
    "getParam": ParameterSite(0, None, "ros::NodeHandle::getParam", _READ),
    "getParamCached": ParameterSite(0, None, "ros::NodeHandle::getParamCached", _READ),
    "setParam": ParameterSite(0, 1, "ros::NodeHandle::setParam", _WRITE),
    "hasParam": ParameterSite(0, None, "ros::NodeHandle::hasParam", _CHECK),
    "deleteParam": ParameterSite(0, None, "ros::NodeHandle::deleteParam", _WRITE),
    "searchParam": ParameterSite(0, None, "ros::NodeHandle::searchParam", _CHECK),
}
# ros::param:: free functions
ROS1_PARAMETER_FUNCTIONS = {
    "param": ParameterSite(0, -1, "ros::param::param", _READ, minimum=2),
    "get": ParameterSite(0, None, "ros::param::get", _READ),
    "getCached": ParameterSite(0, None, "ros::param::getCached", _READ),
    "set": ParameterSite(0, 1, "ros::param::set", _WRITE),
    "has": ParameterSite(0, None, "ros::param::has", _CHECK),
    "del": ParameterSite(0, None, "ros::param::del", _WRITE),
    "search": ParameterSite(0, None, "ros::param::search", _CHECK),
}
ROS2_PARAMETERS = {
    "declare_parameter": ParameterSite(0, 1, "rclcpp::Node::declare_parameter", _DECLARE),
    "get_parameter": ParameterSite(0, None, "rclcpp::Node::get_parameter", _READ, quiet_from=2),
    "get_parameter_or": ParameterSite(0, 2, "rclcpp::Node::get_parameter_or", _QUIETLY),
    "has_parameter": ParameterSite(0, None, "rclcpp::Node::has_parameter", _CHECK),
    "undeclare_parameter": ParameterSite(0, None, "rclcpp::Node::undeclare_parameter", _WRITE),
    # rclcpp's Node::describe_parameter throws ParameterNotDeclaredException (node.cpp)
    "describe_parameter": ParameterSite(0, None, "rclcpp::Node::describe_parameter", _READ),
    # nav2_util's free function: (node, name, default)
    "declare_parameter_if_not_declared": ParameterSite(
        1, 2, "nav2_util::declare_parameter_if_not_declared", _DECLARE, minimum=2
    ),
    # ros2_control's ControllerInterfaceBase::auto_declare(name, default): declares the
    # parameter unless it is (controller_interface_base.hpp)
    "auto_declare": ParameterSite(
        0, 1, "controller_interface::ControllerInterfaceBase::auto_declare", _DECLARE, minimum=2
    ),
    # Autoware's free function (node, name): the node's value of the parameter, which it
    # declares unless the node has it (autoware_utils, include/autoware_utils/ros/
    # parameter.hpp; autoware_universe_utils' getOrDeclareParameter before it, 815 and 1
    # calls in autoware.universe)
    "get_or_declare_parameter": ParameterSite(
        1, None, "autoware_utils::get_or_declare_parameter", _DECLARE, minimum=2
    ),
    "getOrDeclareParameter": ParameterSite(
        1, None, "autoware::universe_utils::getOrDeclareParameter", _DECLARE, minimum=2
    ),
}
# nav2's declare_or_get_parameter: a member (name, default) of nav2::LifecycleNode, or free
# (node, name[, default]) and (logger, parameters interface, name, default) in
# nav2_ros_common's node_utils.hpp; each declares the name unless it is.
DECLARE_OR_GET = "declare_or_get_parameter"
DECLARE_OR_GET_API = "nav2::declare_or_get_parameter"
# nav2's get_plugin_type_param(node, plugin): declares ``plugin + ".plugin"`` (node_utils.hpp)
PLUGIN_TYPE = "get_plugin_type_param"
PLUGIN_TYPE_API = "nav2::get_plugin_type_param"
PLUGIN_TYPE_SUFFIX = ".plugin"
# rclcpp's Node::declare_parameters(namespace, map) declares ``namespace.key`` for each key
# of the map, Node::get_parameters(names) reads each name (throwing as get_parameter does),
# Node::get_parameters(prefix, map) every parameter below ``prefix.`` (node_impl.hpp).
DECLARE_PARAMETERS = "declare_parameters"
DECLARE_PARAMETERS_API = "rclcpp::Node::declare_parameters"
GET_PARAMETERS = "get_parameters"
GET_PARAMETERS_API = "rclcpp::Node::get_parameters"
PARAMETER_LISTS = frozenset({DECLARE_OR_GET, PLUGIN_TYPE, DECLARE_PARAMETERS, GET_PARAMETERS})
# tf and tf2: every string argument of these is a frame id.
FRAME_FUNCTIONS = frozenset(
    {
        "lookupTransform",
        "canTransform",
        "waitForTransform",
        "transformPose",
        "transformPoint",
        "transformVector",
        "transformQuaternion",
        "transformPointCloud",
    }
)
FRAME_FIELDS = frozenset({"frame_id", "child_frame_id"})
# The API a header or child frame field is named with when the message it is set on is
# handed to a tf broadcaster's ``sendTransform`` in the same function (``t.header.frame_id =
# "odom"; broadcaster.sendTransform(t)``): a transform broadcast, whose slash tf2 strips.
SENT_FRAME_FIELD = {word: f"sendTransform {word}" for word in FRAME_FIELDS}
# (argument indexes holding frames) per constructed tf type
FRAME_CONSTRUCTIONS = {"StampedTransform": (2, 3), "Stamped": (2,)}
ACTIONLIB = {"SimpleActionServer": Role.ACTION_SERVE, "ActionServer": Role.ACTION_SERVE}
ACTIONLIB |= {"SimpleActionClient": Role.ACTION_CALL, "ActionClient": Role.ACTION_CALL}
ACTIONLIB_QUALIFIERS = frozenset({"actionlib", "nav2_util", "nav2", ""})
SERVICE_WRAPPERS = {"ServiceClient": Role.CALL, "ServiceServer": Role.SERVE}  # nav2
# roscpp's option objects take the name first, in the static ``create<M>(topic, queue, cb,
# tracked, queue_ptr)`` and the member ``init<M>(topic, queue, cb)`` alike (roscpp's
# subscribe_options.h, advertise_options.h, advertise_service_options.h); the handle's
# one-argument ``subscribe(ops)``, ``advertise(ops)``, ``advertiseService(ops)`` then uses it.
OPTIONS = {
    "SubscribeOptions": Endpoint(Kind.TOPIC, Role.SUBSCRIBE, "ros::SubscribeOptions"),
    "AdvertiseOptions": Endpoint(Kind.TOPIC, Role.PUBLISH, "ros::AdvertiseOptions"),
    "AdvertiseServiceOptions": Endpoint(Kind.SERVICE, Role.SERVE, "ros::AdvertiseServiceOptions"),
}
OPTIONS_METHODS = frozenset({"create", "init"})
OPTIONS_USERS = frozenset({"subscribe", "advertise", "advertiseService"})

CALL_WORDS = frozenset(
    {
        *ENDPOINTS,
        *ACTION_FUNCTIONS,
        *ROS1_PARAMETERS,
        *ROS2_PARAMETERS,
        *PARAMETER_LISTS,
        *FRAME_FUNCTIONS,
        "subscribe",
        "advertiseService",
        "init",
        "service",  # ros::service::call
        *WAIT_FOR_MESSAGE,
        "create_sub_node",
        *OPTIONS,
        # `param` (above) also anchors ros::param::get
    }
)
CONSTRUCTED_TYPES = frozenset(
    {
        "NodeHandle",
        "Node",
        "LifecycleNode",
        "Subscriber",
        "Parameter",
        *ACTIONLIB,
        *SERVICE_WRAPPERS,
        *FRAME_CONSTRUCTIONS,
    }
)

_FRAME_PARAMETER = re.compile(r"(?:^|_)frame(?:_id)?$")
_TOPIC_PARAMETER = re.compile(r"(?:^|_)topic(?:_name)?$")
_SERVICE_PARAMETER = re.compile(r"(?:^|_)service(?:_name)?$")
_ACTION_PARAMETER = re.compile(r"(?:^|_)action(?:_name|_server|_server_name)?$")
MAX_FRAME_ARGUMENTS = 6  # past these, tf's calls take times, durations and outputs


def value_fact(parameter: str) -> tuple[Kind, Role] | None:
    """What a parameter's string value is, judged by the parameter's name.

    ``*frame``/``*frame_id`` hold frame ids; ``*topic``/``*topic_name``, ``*service``,
    ``*action`` hold graph names, recorded as parameter defaults (never RN202: a default
    is the recommended fix). Other parameters hold anything.
    """
    last = re.split(r"[/.~]", parameter)[-1]
    if _FRAME_PARAMETER.search(last):
        return Kind.FRAME, Role.FRAME
    for pattern, kind in (
        (_TOPIC_PARAMETER, Kind.TOPIC),
        (_SERVICE_PARAMETER, Kind.SERVICE),
        (_ACTION_PARAMETER, Kind.ACTION),
    ):
        if pattern.search(last):
            return kind, Role.PARAMETER_DEFAULT
    return None

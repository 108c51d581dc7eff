"""Helpers shared by the rules: which uses a rule looks at, and how a name is described."""

from __future__ import annotations

import re
from collections.abc import Iterator

from ..model import Decision, FileFacts, Fix, Generation, Kind, Language, NameUse, Role
from ..names import Problem, check_name, tokens

GRAPH_KINDS = frozenset({Kind.NODE, Kind.NAMESPACE, Kind.TOPIC, Kind.SERVICE, Kind.ACTION})
_LAUNCH_LANGUAGES = frozenset(
    {Language.LAUNCH_XML, Language.LAUNCH_YAML, Language.LAUNCH_PYTHON, Language.URDF}
)
CODE_LANGUAGES = frozenset({Language.CPP, Language.PYTHON})
# The APIs of node code, as the Python extractor names them (``rclpy.node.Node.
# create_publisher``); a launch description's are its actions' (``Node(remappings=)``).
_CODE_APIS = ("rclpy.", "rospy.", "actionlib.", "message_filters.")

# The last token of an image or point cloud transport's topic: its plugin's name, which
# SimplePublisherPlugin::getTopicToAdvertise appends to the base topic (image_transport
# and point_cloud_transport, `simple_publisher_plugin.hpp`); the plugins' getTransportName
# in image_transport_plugins and point_cloud_transport_plugins.
TRANSPORT_SUFFIXES = frozenset({"compressed", "compressedDepth", "theora", "zstd", "draco", "zlib"})
# ROS 2 hides a name with a token that starts with '_' (rclpy's
# `topic_or_service_is_hidden`): a library's own services (rclcpp_components'
# `~/_container/load_node`) and actions' `_action/...` sub-names.
HIDDEN_PREFIX = "_"

_TYPE_SPELLING = re.compile(r"[A-Z][A-Za-z0-9]*[a-z][A-Za-z0-9]*")
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


def grammar_problems(facts: FileFacts, code: str) -> Iterator[tuple[NameUse, Problem]]:
    """Each known name the grammar faults under ``code``, with the grammar's verdict.

    The grammar gives one problem per name under its most specific code, so the rules
    that report grammar problems (RN101, RN102, RN205) never report one name twice.
    """
    for use in static_uses(facts):
        problem = check_name(use.value, use.kind, facts.generation)
        if problem is not None and problem.code == code:
            yield use, problem


def fix_hint(problem: Problem) -> str:
    return f"; use '{problem.suggestion}'" if problem.suggestion else ""


def suggested_fix(use: NameUse, problem: Problem, *, safe: bool) -> Fix | None:
    """The grammar's suggestion as a fix of ``use``, when it has one."""
    if problem.suggestion is None or problem.suggestion == use.value:
        return None
    return Fix(use.value, problem.suggestion, safe)


# Uses of a name another node chooses: the publisher chooses a topic, the server a service
# or action; a subscriber or client spells it as they did (navigation2's waypoint follower
# calls robot_localization's `fromLL`).
_USING_ROLES = frozenset({Role.SUBSCRIBE, Role.CALL, Role.ACTION_CALL})
# ROS 2 parameter APIs that use a parameter declared elsewhere (a `declare_parameter`, or a
# parameter file under `automatically_declare_parameters_from_overrides`): only a
# declaration chooses its name. ROS 1 has no declarations: reading one chooses it.
_ROS2_PARAMETER_USES = frozenset(
    {
        "rclcpp::Node::get_parameter",
        "rclcpp::Node::get_parameter_or",
        "rclcpp::Node::has_parameter",
        "rclcpp::Node::undeclare_parameter",
        "rclcpp::Node::describe_parameter",
        "rclpy.node.Node.get_parameter",
        "rclpy.node.Node.get_parameter_or",
        "rclpy.node.Node.has_parameter",
        "rclpy.node.Node.undeclare_parameter",
        "rclpy.node.Node.describe_parameter",
        "rclpy.parameter.Parameter",
    }
)


def chosen_here(use: NameUse, facts: FileFacts) -> bool:
    """Whether the author of this file chose the name, so a style finding (RN201, RN203,
    RN204, RN206) is actionable.

    A name is judged for style where it is chosen and left alone where it is only used:

    - a launch file's ``<param name>`` and ``<remap from>`` spell names the node's code
      defines (gmapping's ``maxUrange``): the launch author cannot rename them;
    - a subscriber, service client or action client uses the name its publisher or
      server chose, often in another package (robot_localization's ``fromLL``);
    - in ROS 2, reading, describing or setting a parameter uses the name its declaration
      chose;
    - a parameter file sets the names the node's code declares or reads, as a launch
      file's ``<param name>`` does: it spells them, and cannot rename them alone.

    Node names, namespaces, publishers, servers, parameter declarations (and every ROS 1
    parameter access) are where names are chosen, and are judged.
    """
    if facts.language is Language.PARAMETERS:
        return use.role is not Role.PARAMETER
    if facts.language in _LAUNCH_LANGUAGES and not in_code(use, facts):
        return use.role not in (Role.PARAMETER, Role.REMAP_FROM)
    if use.role in _USING_ROLES:
        return False
    return not (facts.generation is Generation.ROS2 and use.api in _ROS2_PARAMETER_USES)


def in_code(use: NameUse, facts: FileFacts) -> bool:
    """Whether ``use`` is in node code, not in a launch description. A Python launch file
    can hold both: launch_testing's ``generate_test_description`` sits beside the rclpy
    nodes and subscriptions of the test itself (universal_robots'
    ``ur_robot_driver/test/urscript_interface.py``)."""
    if facts.language in CODE_LANGUAGES:
        return True
    return facts.language is Language.LAUNCH_PYTHON and use.api.startswith(_CODE_APIS)


def spelled_as_type(use: NameUse) -> bool:
    """A service whose last token is spelled like an interface type (``SetBool``).

    RN204 reports it; RN203 leaves that token alone, so the name gets one finding.
    """
    if use.kind is not Kind.SERVICE or use.role not in (Role.SERVE, Role.CALL):
        return False
    last = use.value.rstrip("/").rsplit("/", 1)[-1]
    return bool(_TYPE_SPELLING.fullmatch(last))


def chosen_depth(name: str, kind: Kind, generation: Generation) -> int:
    """The levels of ``name`` its writer chose (RN201).

    A transport plugin's last token (``image/compressed``) is the plugin's, not the
    writer's. In ROS 2 a hidden token and all after it are a library's: rclcpp_components
    serves ``~/_container/load_node`` under whatever name the launch file gives the
    container, and hidden names are out of ``ros2 topic list`` and ``rqt_graph`` anyway.
    """
    chosen = tokens(name, kind)
    if kind is Kind.TOPIC and len(chosen) > 1 and chosen[-1] in TRANSPORT_SUFFIXES:
        chosen = chosen[:-1]
    if generation is Generation.ROS2:
        hidden = [i for i, token in enumerate(chosen) if token.startswith(HIDDEN_PREFIX)]
        if hidden:
            chosen = chosen[: hidden[0]]
    return len(chosen)


# The hidden level under which rcl_action names an action's services and topics.
_ACTION_LEVEL = "/_action/"

# Where a name starts: a publisher, a service server, an action server.
_PRODUCING_ROLES = frozenset({Role.PUBLISH, Role.SERVE, Role.ACTION_SERVE})


def decision(use: NameUse, facts: FileFacts, *, prefix: str | None = None) -> Decision:
    """The name ``use`` writes as one decision (``decisions``), or with ``prefix`` the
    absolute start a name built at run time shares with others.

    A parameter belongs to its node, as does a private ``~`` name: the same spelling in
    another file is most often another node's, so its scope is the file. Every other name
    (a topic, a service, a node name, a frame) is the workspace's.

    In ROS 2 an action's services and topics are its name and a hidden ``_action`` level
    (rcl_action ``rcl_action_get_cancel_service_name``: ``<action>/_action/cancel_goal``):
    a client that writes one of them spells the action's name, one decision with it."""
    own = use.kind is Kind.PARAMETER or use.value.startswith("~")
    kind, name = use.kind, use.value if prefix is None else prefix
    if prefix is None and facts.generation is Generation.ROS2 and _ACTION_LEVEL in name:
        kind, name = Kind.ACTION, name.partition(_ACTION_LEVEL)[0]
    return Decision(
        kind=kind,
        name=name,
        generation=facts.generation,
        prefix=prefix is not None,
        scope=facts.path if own and prefix is None else "",
        producer=use.role in _PRODUCING_ROLES,
        api=use.api,
    )


def label(use: NameUse) -> str:
    if use.role is Role.REMAP_FROM:
        return "remapped name"
    if use.role is Role.REMAP_TO:
        return "remap target"
    return _LABELS[use.kind]

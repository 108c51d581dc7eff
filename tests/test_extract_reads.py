"""What real code writes (issue 27, cause 6): names the extractors read through option
objects, absolute prefixes joined at run time, values followed through lambdas, repeated
assignments, members and constants, and remapping arguments of one node."""

from __future__ import annotations

from pathlib import Path

from roslint_names.extract.cpp import extract as cpp
from roslint_names.extract.python import extract as python
from roslint_names.model import FileFacts, Generation, Kind, NameUse, Role

FIXTURES = Path(__file__).parent / "fixtures"
ROS1, ROS2 = Generation.ROS1, Generation.ROS2
TOPIC, SERVICE = Kind.TOPIC, Kind.SERVICE
ENDPOINTS = frozenset({Role.PUBLISH, Role.SUBSCRIBE, Role.SERVE, Role.CALL})


def cpp_fixture(name: str) -> FileFacts:
    return cpp.extract(name, (FIXTURES / "cpp" / name).read_bytes(), None, ROS2)


def python_fixture(name: str) -> FileFacts:
    return python.extract(name, (FIXTURES / "python" / name).read_bytes(), None, ROS2)


def known(facts: FileFacts) -> list[NameUse]:
    return [use for use in facts.names if not use.dynamic]


# ---------------------------------------------------------------------------------------
# roscpp's option objects


def test_roscpp_option_objects_name_their_endpoints() -> None:
    facts = cpp_fixture("cloud_relay_options.cpp")
    found = [
        (u.kind, u.role, u.value, u.type_name, u.namespace, u.api, u.span.line)
        for u in known(facts)
    ]
    assert found == [
        (
            TOPIC,
            Role.SUBSCRIBE,
            "/velodyne_points",
            "sensor_msgs::PointCloud2",
            "",
            "ros::SubscribeOptions::create",
            17,
        ),
        # advertised through the private handle: the name is under ~
        (
            TOPIC,
            Role.PUBLISH,
            "status",
            "std_msgs::String",
            "~",
            "ros::AdvertiseOptions::create",
            23,
        ),
        (
            TOPIC,
            Role.SUBSCRIBE,
            "/planning/mode",
            "std_msgs::String",
            "",
            "ros::SubscribeOptions::init",
            29,
        ),
        (
            SERVICE,
            Role.SERVE,
            "reset",
            "std_srvs::Trigger",
            "~",
            "ros::AdvertiseServiceOptions::create",
            34,
        ),
    ]
    # `nh_.subscribe(ops)` hands over the object: no unknown name is made of `ops`
    assert [u.value for u in facts.names if u.dynamic] == []


# ---------------------------------------------------------------------------------------
# An absolute literal joined at run time


def prefixes(facts: FileFacts) -> list[tuple[int, str | None]]:
    """(line, certain absolute start) of the endpoint names built at run time."""
    return [(u.span.line, u.absolute_prefix) for u in facts.names if u.dynamic]


def test_cpp_absolute_prefix_joined_at_run_time_is_kept() -> None:
    facts = cpp_fixture("planning_factor_interface.hpp")
    assert prefixes(facts) == [
        (23, "/planning/planning_factors/"),
        (25, "/planning/debug/"),  # through a constant initialised with the sum
        (27, None),  # "~/debug/" + name: relative, nothing certain about its anchor
    ]


def test_python_absolute_prefix_joined_at_run_time_is_kept() -> None:
    facts = python_fixture("planning_debug_relay.py")
    assert prefixes(facts) == [
        (12, "/planning/planning_factors/"),
        (14, "/planning/debug/"),
        (15, "/planning/"),
        (17, "/planning/status/"),
        (19, None),
    ]


def test_a_known_prefix_leaves_the_name_unjudged_by_the_grammar() -> None:
    """The unknown rest may be anything: the use stays dynamic, so no rule that reads
    ``static_uses`` (every grammar rule) sees it."""
    facts = python_fixture("planning_debug_relay.py")
    [factors] = [u for u in facts.names if u.absolute_prefix == "/planning/planning_factors/"]
    assert factors.dynamic
    assert factors.value == '"/planning/planning_factors/" + module_name'


# ---------------------------------------------------------------------------------------
# Values followed: lambda captures, repeated assignments, members, constant sums


def static_endpoints(facts: FileFacts) -> list[tuple[int, Role, str]]:
    return [(u.span.line, u.role, u.value) for u in known(facts) if u.role in ENDPOINTS]


def test_cpp_constants_members_and_lambda_captures_are_followed() -> None:
    facts = cpp_fixture("teleop_mux.cpp")
    assert static_endpoints(facts) == [
        (22, Role.PUBLISH, "mux_status"),  # this->kStatusTopic
        (24, Role.PUBLISH, "/robot/cmd_vel"),  # std::string(kRobotNs) + "/cmd_vel"
        (26, Role.SUBSCRIBE, "joy/cmd_vel"),  # kJoyNs + "/cmd_vel"
        (33, Role.SUBSCRIBE, "cmd_vel_override"),  # [this, override_topic]
        (39, Role.PUBLISH, "heartbeat"),  # [=]
        (53, Role.PUBLISH, "mux_status"),  # mux.kStatusTopic
    ]
    assert [u.value for u in facts.names if u.dynamic] == []


CAPTURED_BY_REFERENCE_CPP = """\
#include <rclcpp/rclcpp.hpp>
void start(rclcpp::Node::SharedPtr node)
{
  std::string topic = "scan";
  auto reconfigure = [&topic](const std::string & name) { topic = name; };
  auto later = [node, topic]() { node->create_subscription<Scan>(topic, 10, cb); };
}
"""


def test_cpp_a_local_captured_by_reference_may_change() -> None:
    facts = cpp.extract("src/start.cpp", CAPTURED_BY_REFERENCE_CPP.encode(), ROS2, ROS2)
    assert [(u.value, u.dynamic) for u in facts.names] == [("topic", True)]


def test_python_local_assigned_twice_is_read_at_its_last_assignment() -> None:
    facts = python_fixture("battery_monitor.py")
    assert static_endpoints(facts) == [
        (12, Role.PUBLISH, "battery_state"),
        (14, Role.PUBLISH, "/battery_alarm"),
    ]
    # after a branch that may assign it, the value is not certain
    assert [(u.span.line, u.value) for u in facts.names if u.dynamic] == [(18, "topic")]


# ---------------------------------------------------------------------------------------
# Remapping arguments rename the node they are given to


def test_a_remapping_argument_renames_only_the_node_it_configures() -> None:
    facts = cpp_fixture("fleet_bringup.cpp")
    names = [
        (u.span.line, u.kind, u.value, u.dynamic)
        for u in facts.names
        if u.role in (Role.NODE_NAME, Role.NAMESPACE)
    ]
    assert names == [
        (16, Kind.NODE, "base_driver", False),
        (16, Kind.NAMESPACE, "ignored", True),  # __ns:=/robot1 in its options
        (20, Kind.NODE, "_", True),  # __node:= through the vector its options take
        (20, Kind.NAMESPACE, "robot2", False),
        # no remapping reaches the monitor: its names are judged (the trailing slash)
        (22, Kind.NODE, "fleet_monitor", False),
        (22, Kind.NAMESPACE, "fleet/", False),
    ]


PLANNING_PIPELINE_CPP = """\
#include <rclcpp/rclcpp.hpp>
namespace
{
const std::string UNDEFINED = "<undefined>";
const std::string PLANNING_SCENE_MONITOR_NS = "planning_scene_monitor_options.";
}  // namespace

bool MoveItPlanningPipeline::initialize(const std::shared_ptr<rclcpp::Node>& node)
{
  node->declare_parameter<std::string>(PLANNING_SCENE_MONITOR_NS + "joint_state_topic", UNDEFINED);
  node->declare_parameter<std::string>(PLANNING_SCENE_MONITOR_NS + "scene_topic", "scene");
  return true;
}
"""


def test_a_constant_sum_names_a_parameter_whose_placeholder_default_is_no_topic() -> None:
    """moveit's hybrid planner: the parameter name is two constants; "<undefined>" is the
    default that means "not set", not a topic someone chose."""
    facts = cpp.extract("src/pipeline.cpp", PLANNING_PIPELINE_CPP.encode(), ROS2, ROS2)
    assert [(u.kind, u.value) for u in known(facts)] == [
        (Kind.PARAMETER, "planning_scene_monitor_options.joint_state_topic"),
        (Kind.PARAMETER, "planning_scene_monitor_options.scene_topic"),
        (TOPIC, "scene"),
    ]

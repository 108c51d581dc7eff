"""C++ extractor: roscpp and rclcpp name sites, constants, spans, and handles before init."""

from __future__ import annotations

import signal
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from roslint_names.extract.cpp import extract as cpp
from roslint_names.extract.cpp import source as cpp_source
from roslint_names.model import (
    EventKind,
    FileFacts,
    Generation,
    Kind,
    Language,
    NameUse,
    Role,
    RuntimeEvent,
    Span,
)

FIXTURES = Path(__file__).parent / "fixtures" / "cpp"
ROS1, ROS2 = Generation.ROS1, Generation.ROS2
TOPIC, SERVICE, ACTION, NODE = Kind.TOPIC, Kind.SERVICE, Kind.ACTION, Kind.NODE
PARAMETER, FRAME, NAMESPACE = Kind.PARAMETER, Kind.FRAME, Kind.NAMESPACE


def extract(text: str | bytes, package: Generation | None = None) -> FileFacts:
    data = text.encode("utf-8") if isinstance(text, str) else text
    return cpp.extract("src/node.cpp", data, package, ROS2)


def fixture(name: str) -> FileFacts:
    return cpp.extract(name, (FIXTURES / name).read_bytes(), None, ROS2)


def uses(facts: FileFacts) -> list[tuple[Kind, Role, str, str | None]]:
    """(kind, role, value, type) of the statically known names, in source order."""
    return [(u.kind, u.role, u.value, u.type_name) for u in facts.names if not u.dynamic]


def dynamic(facts: FileFacts) -> list[tuple[Kind, str]]:
    return [(u.kind, u.value) for u in facts.names if u.dynamic]


def use(facts: FileFacts, value: str) -> NameUse:
    [found] = [u for u in facts.names if u.value == value]
    return found


def events(facts: FileFacts) -> list[tuple[EventKind, str, int, bool]]:
    """(kind, api, line, static storage) in source order."""
    ordered = sorted(facts.events, key=lambda event: (event.span.line, event.span.column))
    return [(e.kind, e.api, e.span.line, e.static_storage) for e in ordered]


def scopes(facts: FileFacts) -> dict[int, str]:
    return {event.span.line: event.scope for event in facts.events}


INIT, HANDLE = EventKind.INIT, EventKind.HANDLE


# ---------------------------------------------------------------------------------------
# roscpp


def test_talker() -> None:
    facts = fixture("talker.cpp")
    assert facts.language is Language.CPP
    assert facts.generation is ROS1
    assert uses(facts) == [
        (NODE, Role.NODE_NAME, "talker", None),
        (TOPIC, Role.PUBLISH, "chatter", "std_msgs::String"),
    ]
    assert use(facts, "chatter").api == "ros::NodeHandle::advertise"
    assert events(facts) == [(INIT, "ros::init", 11, False), (HANDLE, "ros::NodeHandle", 12, False)]


def test_subscriber_types_come_from_function_and_method_callbacks() -> None:
    facts = fixture("listener.cpp")
    assert uses(facts) == [
        (TOPIC, Role.SUBSCRIBE, "scan", "sensor_msgs::LaserScan"),  # &ScanListener::scanCallback
        (TOPIC, Role.SUBSCRIBE, "scan_filtered", "sensor_msgs::LaserScan"),  # boost::bind
        (NODE, Role.NODE_NAME, "listener", None),
        (TOPIC, Role.SUBSCRIBE, "chatter", "std_msgs::String"),  # chatterCallback
    ]


def test_service_types_come_from_request_parameters() -> None:
    facts = fixture("add_two_ints_server.cpp")
    assert uses(facts) == [
        (NODE, Role.NODE_NAME, "add_two_ints_server", None),
        (SERVICE, Role.SERVE, "add_two_ints", "beginner_tutorials::AddTwoInts"),
        (SERVICE, Role.SERVE, "enable", "std_srvs::SetBool"),  # std_srvs::SetBoolRequest&
    ]


def test_service_client_wait_and_call() -> None:
    facts = fixture("add_two_ints_client.cpp")
    assert uses(facts) == [
        (NODE, Role.NODE_NAME, "add_two_ints_client", None),
        (SERVICE, Role.CALL, "add_two_ints", None),
        (SERVICE, Role.CALL, "add_two_ints", "beginner_tutorials::AddTwoInts"),
        (SERVICE, Role.CALL, "/global_add_two_ints", "beginner_tutorials::AddTwoInts"),
    ]
    assert [u.api for u in facts.names][1:] == [
        "ros::service::waitForService",
        "ros::NodeHandle::serviceClient",
        "ros::service::call",
    ]


def test_actionlib_server_and_client() -> None:
    facts = fixture("fibonacci_action.cpp")
    fibonacci = "actionlib_tutorials::FibonacciAction"
    assert uses(facts) == [
        (ACTION, Role.ACTION_SERVE, "progress", fibonacci),  # server_(nh_, "progress", false)
        (NODE, Role.NODE_NAME, "fibonacci", None),
        (ACTION, Role.ACTION_CALL, "fibonacci", fibonacci),
    ]
    assert dynamic(facts) == [(ACTION, "name")]  # as_(nh_, name, ...): the constructor's argument


def test_tf_frames() -> None:
    facts = fixture("turtle_tf.cpp")
    frames = [(u.value, u.api) for u in facts.names if u.kind is FRAME]
    assert frames == [
        ("world", "tf::StampedTransform"),
        ("world", "tf::StampedTransform"),
        ("carrot1", "tf::StampedTransform"),
        ("base_link", "ros::NodeHandle::param"),  # the default of a *_frame parameter
        ("/turtle2", "waitForTransform"),
        ("/turtle1", "waitForTransform"),
        ("/turtle2", "lookupTransform"),
        ("/turtle1", "lookupTransform"),
        ("world", "frame_id"),
    ]
    assert use(facts, "/odom").role is Role.PARAMETER_DEFAULT  # the default of odom_topic


def test_parameters_and_private_handle_namespace() -> None:
    facts = fixture("turtle_tf.cpp")
    parameters = [(u.value, u.namespace) for u in facts.names if u.kind is PARAMETER]
    assert parameters == [("base_frame", "~"), ("odom_topic", "~")]


# ---------------------------------------------------------------------------------------
# rclcpp


def test_rclcpp_component() -> None:
    facts = fixture("minimal_component.cpp")
    assert facts.generation is ROS2
    navigate = "nav2_msgs::action::NavigateToPose"  # through `using NavigateToPose = ...`
    assert uses(facts) == [
        (NODE, Role.NODE_NAME, "base_controller", None),
        (NAMESPACE, Role.NAMESPACE, "mobile_base", None),
        (PARAMETER, Role.PARAMETER, "max_speed", None),
        (PARAMETER, Role.PARAMETER, "base_frame_id", None),
        (FRAME, Role.FRAME, "base_footprint", None),
        (TOPIC, Role.PUBLISH, "cmd_vel", "geometry_msgs::msg::Twist"),
        (TOPIC, Role.SUBSCRIBE, "scan", "sensor_msgs::msg::LaserScan"),
        (SERVICE, Role.SERVE, "reset_odometry", "std_srvs::srv::Trigger"),
        (SERVICE, Role.CALL, "add_two_ints", "example_interfaces::srv::AddTwoInts"),
        (ACTION, Role.ACTION_SERVE, "navigate_to_pose", navigate),
        (ACTION, Role.ACTION_CALL, "/navigate_to_pose", navigate),
    ]
    assert use(facts, "cmd_vel").api == "rclcpp::Node::create_publisher"
    assert use(facts, "navigate_to_pose").api == "rclcpp_action::create_server"


def test_types_brought_in_by_using_declarations_are_resolved() -> None:
    facts = extract(
        """#include <rclcpp/rclcpp.hpp>
#include <std_srvs/srv/set_bool.hpp>
#include <std_srvs/srv/trigger.hpp>

using std_srvs::srv::SetBool;
using namespace std_srvs::srv;  // brings in Trigger, but names no type itself

class Relay : public rclcpp::Node
{
public:
  Relay() : rclcpp::Node("relay")
  {
    enable_ = create_service<SetBool>("enable", nullptr);
    reset_ = create_service<Trigger>("reset", nullptr);
  }

private:
  rclcpp::Service<SetBool>::SharedPtr enable_;
  rclcpp::Service<Trigger>::SharedPtr reset_;
};
"""
    )
    assert use(facts, "enable").type_name == "std_srvs::srv::SetBool"
    assert use(facts, "reset").type_name == "Trigger"


def test_lifecycle_node() -> None:
    facts = fixture("lifecycle_talker.cpp")
    assert uses(facts) == [
        (TOPIC, Role.PUBLISH, "lifecycle_chatter", "std_msgs::msg::String"),
        (PARAMETER, Role.PARAMETER, "publish_period_ms", None),
        (NODE, Role.NODE_NAME, "camera_driver", None),
        (NAMESPACE, Role.NAMESPACE, "front", None),
    ]
    assert dynamic(facts) == [(NODE, "node_name")]  # LifecycleNode(node_name, options)
    assert events(facts) == [
        (INIT, "rclcpp::init", 43, False),
        (HANDLE, "LifecycleTalker (an rclcpp_lifecycle::LifecycleNode)", 45, False),
    ]


@pytest.mark.parametrize(
    "call",
    [
        'node->create_publisher<std_msgs::msg::String>("chatter", 10)',
        'node_->create_publisher<std_msgs::msg::String>("chatter", 10)',
        'this->create_publisher<std_msgs::msg::String>("chatter", 10)',
        'create_publisher<std_msgs::msg::String>("chatter", 10)',
        'rclcpp::create_publisher<std_msgs::msg::String>(node, "chatter", 10)',
    ],
)
def test_rclcpp_publisher_forms(call: str) -> None:
    facts = extract(f"#include <rclcpp/rclcpp.hpp>\nvoid f() {{ auto p = {call}; }}\n")
    assert uses(facts) == [(TOPIC, Role.PUBLISH, "chatter", "std_msgs::msg::String")]


def test_node_names_and_namespaces() -> None:
    facts = extract(
        "#include <rclcpp/rclcpp.hpp>\n"
        "int main(int argc, char** argv) {\n"
        "  rclcpp::init(argc, argv);\n"
        '  auto a = std::make_shared<rclcpp::Node>("a", "left");\n'
        '  auto b = rclcpp::Node::make_shared("b");\n'
        '  rclcpp::Node c("c", rclcpp::NodeOptions());\n'
        '  a->create_publisher<std_msgs::msg::String>("status", 10);\n'
        "}\n"
    )
    assert uses(facts) == [
        (NODE, Role.NODE_NAME, "a", None),
        (NAMESPACE, Role.NAMESPACE, "left", None),
        (NODE, Role.NODE_NAME, "b", None),
        (NODE, Role.NODE_NAME, "c", None),
        (TOPIC, Role.PUBLISH, "status", "std_msgs::msg::String"),
    ]
    assert use(facts, "status").namespace == "left"


def test_parameters_through_parameter_objects_and_nav2_helpers() -> None:
    facts = extract(
        "#include <rclcpp/rclcpp.hpp>\n"
        "void configure(rclcpp::Node::SharedPtr node) {\n"
        '  node->set_parameter(rclcpp::Parameter("global_frame", "map"));\n'
        "  nav2_util::declare_parameter_if_not_declared(\n"
        '    node, "scan_topic", rclcpp::ParameterValue("scan"));\n'
        '  node->get_parameter_or("use_sim_time", sim, false);\n'
        "}\n"
    )
    assert uses(facts) == [
        (PARAMETER, Role.PARAMETER, "global_frame", None),
        (FRAME, Role.FRAME, "map", None),
        (PARAMETER, Role.PARAMETER, "scan_topic", None),
        (TOPIC, Role.PARAMETER_DEFAULT, "scan", None),
        (PARAMETER, Role.PARAMETER, "use_sim_time", None),
    ]


def test_message_filters_subscriber() -> None:
    facts = extract(
        "#include <ros/ros.h>\n"
        "void f(ros::NodeHandle& nh) {\n"
        '  message_filters::Subscriber<sensor_msgs::Image> image(nh, "image", 1);\n'
        "  message_filters::Subscriber<sensor_msgs::CameraInfo> info;\n"
        '  info.subscribe(nh, "camera_info", 1);\n'
        "}\n"
    )
    assert uses(facts) == [
        (TOPIC, Role.SUBSCRIBE, "image", "sensor_msgs::Image"),
        (TOPIC, Role.SUBSCRIBE, "camera_info", None),
    ]


def test_a_subscribe_of_one_argument_names_no_topic() -> None:
    """autoware_pointcloud_preprocessor's filter.cpp, reduced: its own
    ``Filter::subscribe(filter_name)`` was read as a topic named ``""`` (an RN101
    error); roscpp's and message_filters' subscribe take two arguments or more."""
    facts = extract(
        "#include <rclcpp/rclcpp.hpp>\n"
        "#include <message_filters/subscriber.h>\n"
        "class Filter : public rclcpp::Node {\n"
        "  void subscribe() {\n"
        '    std::string filter_name = "";\n'
        "    subscribe(filter_name);\n"
        "  }\n"
        "  void subscribe(const std::string & filter_name) {\n"
        '    sub_input_filter_.subscribe(this, "input", rmw_qos_profile_sensor_data);\n'
        "    sub_input_filter_.subscribe();\n"
        "  }\n"
        "  message_filters::Subscriber<sensor_msgs::msg::PointCloud2> sub_input_filter_;\n"
        "};\n"
    )
    assert [(kind, role, value) for kind, role, value, _ in uses(facts)] == [
        (TOPIC, Role.SUBSCRIBE, "input"),
    ]


# ---------------------------------------------------------------------------------------
# Handle namespaces


def test_handle_namespaces_reach_the_names_used_through_them() -> None:
    facts = extract(
        "#include <ros/ros.h>\n"
        "class Arm {\n"
        '  Arm() : private_nh_("~") {\n'
        '    private_nh_.param("rate", rate_, 10.0);\n'
        '    ros::NodeHandle arm_nh(nh_, "arm");\n'
        '    arm_nh.advertise<std_msgs::Float64>("command", 1);\n'
        '    ros::NodeHandle("~").getParam("gain", gain_);\n'
        '    nh_.subscribe("joint_states", 1, &Arm::cb, this);\n'
        "  }\n"
        "  ros::NodeHandle nh_, private_nh_;\n"
        "};\n"
        "void Nodelet::onInit() {\n"
        "  ros::NodeHandle& pnh = getPrivateNodeHandle();\n"
        '  pnh.param("frame", frame_, std::string("laser"));\n'
        "}\n"
    )
    assert [(u.value, u.namespace) for u in facts.names] == [
        ("rate", "~"),
        ("arm", ""),  # a default-constructed handle is in the node's own namespace
        ("command", "arm"),
        ("gain", "~"),
        ("joint_states", ""),
        ("frame", "~"),
        ("laser", "~"),
    ]
    assert use(facts, "arm").kind is NAMESPACE


def test_private_namespace_is_not_judged_as_a_name() -> None:
    # ROS 1 code left in a ROS 2 package must not make "~" an illegal ROS 2 namespace.
    facts = extract('void f() { ros::NodeHandle pnh("~"); ros::NodeHandle ph_{"~"}; }', ROS2)
    assert facts.names == ()


# ---------------------------------------------------------------------------------------
# Parameter defaults


@pytest.mark.parametrize(
    ("call", "expected"),
    [
        ('nh.param<std::string>("cmd_topic", t, "/cmd_vel")', (TOPIC, Role.PARAMETER_DEFAULT)),
        ('nh.param("scan_topic_name", std::string("scan"))', (TOPIC, Role.PARAMETER_DEFAULT)),
        (
            'nh.param<std::string>("map_service", s, "static_map")',
            (SERVICE, Role.PARAMETER_DEFAULT),
        ),
        ('nh.param<std::string>("action_name", a, "move_base")', (ACTION, Role.PARAMETER_DEFAULT)),
        ('nh.param<std::string>("global_frame", f, "/map")', (FRAME, Role.FRAME)),
        ('nh.setParam("base_frame_id", "base_link")', (FRAME, Role.FRAME)),
        ('ros::param::param<std::string>("~odom_frame", f, "odom")', (FRAME, Role.FRAME)),
    ],
)
def test_parameter_defaults_that_name_something(call: str, expected: tuple[Kind, Role]) -> None:
    facts = extract(f"#include <ros/ros.h>\nvoid f(ros::NodeHandle& nh) {{ {call}; }}\n")
    [parameter, default] = facts.names
    assert parameter.kind is PARAMETER
    assert (default.kind, default.role) == expected


@pytest.mark.parametrize(
    "call",
    [
        'nh.param<std::string>("robot_name", n, "turtle1")',  # not a graph name
        'nh.param<std::string>("odom_topic", t, "")',  # empty: "disabled"
        'nh.param<std::string>("sources_topic", t, "scan bump")',  # a list
        'nh.param<std::string>("topic_prefix", t, "robot/")',  # joined later
        'nh.param<std::string>("topic", t, prefix + "/odom")',  # dynamic
    ],
)
def test_parameter_defaults_that_are_not_names(call: str) -> None:
    facts = extract(f"#include <ros/ros.h>\nvoid f(ros::NodeHandle& nh) {{ {call}; }}\n")
    assert [u.kind for u in facts.names] == [PARAMETER]


def test_parameter_default_is_never_a_hard_coded_absolute_name(lint_text: Any) -> None:
    source = (
        "#include <ros/ros.h>\n"
        "int main(int argc, char** argv) {\n"
        '  ros::init(argc, argv, "driver");\n'
        '  ros::NodeHandle pnh("~");\n'
        "  std::string topic;\n"
        '  pnh.param<std::string>("cmd_topic", topic, "/cmd_vel");\n'
        "  ros::NodeHandle nh;\n"
        "  nh.advertise<geometry_msgs::Twist>(topic, 1);\n"
        "}\n"
    )
    assert lint_text(source, "src/driver/src/driver.cpp", 1) == []


# ---------------------------------------------------------------------------------------
# Constants and dynamic names


def test_constants_are_folded() -> None:
    facts = fixture("constants.cpp")
    assert [u.value for u in facts.names if not u.dynamic] == [
        "cmd_vel",  # const std::string at namespace scope
        "odom",  # constexpr char[]
        "imu/data",  # constexpr const char* of adjacent literals
        "state",  # static member defined after the class
        "map",  # static constexpr std::string_view member
        "robot_status",  # #define of adjacent literals
        "diagnostics_agg",  # local const
        "laser/scan",  # adjacent literals at the call
        "mutable",  # a local std::string nothing changes: as certain as a constant
        "wrapped",  # std::string("wrapped")
    ]


def test_names_built_at_run_time_are_dynamic() -> None:
    facts = fixture("constants.cpp")
    assert [u.value for u in facts.names if u.dynamic] == [
        "kPrefix + suffix",
        '"sensors/" + suffix',
        'suffix.empty() ? "a" : "b"',
        'ros::names::append("ns/",suffix)',
        "kMutable",  # const char* reassigned in rename()
    ]


def test_literals_joined_with_a_suffix_are_not_reported(lint_text: Any) -> None:
    source = (FIXTURES / "constants.cpp").read_text(encoding="utf-8")
    assert lint_text(source, "src/driver/src/driver.cpp", 2) == []


def test_local_constant_shadows_and_is_scoped_to_its_function() -> None:
    facts = extract(
        "#include <ros/ros.h>\n"
        'const std::string kTopic = "global";\n'
        "void a(ros::NodeHandle& nh) {\n"
        '  const std::string kTopic = "local";\n'
        "  nh.advertise<std_msgs::Empty>(kTopic, 1);\n"
        "}\n"
        "void b(ros::NodeHandle& nh) { nh.advertise<std_msgs::Empty>(kTopic, 1); }\n"
        "void c(ros::NodeHandle& nh, const std::string& kTopic) {\n"
        "  nh.advertise<std_msgs::Empty>(kTopic, 1);\n"
        "}\n"
    )
    assert [(u.value, u.dynamic) for u in facts.names] == [
        ("local", False),
        ("global", False),
        ("kTopic", True),  # the parameter shadows the constant
    ]


def test_class_constant_defined_in_a_namespace_qualified_definition() -> None:
    # moveit: `static const std::string DISPLAY_PATH_TOPIC;` in the header's class,
    # `const std::string planning_pipeline::PlanningPipeline::DISPLAY_PATH_TOPIC = "..."`.
    facts = extract(
        "#include <ros/ros.h>\n"
        "class Pipeline { static const std::string TOPIC; void run(); };\n"
        'const std::string planning::Pipeline::TOPIC = "display_planned_path";\n'
        "void Pipeline::run() { nh_.advertise<moveit_msgs::DisplayTrajectory>(TOPIC, 10); }\n"
    )
    assert uses(facts) == [
        (TOPIC, Role.PUBLISH, "display_planned_path", "moveit_msgs::DisplayTrajectory")
    ]


def test_constant_set_in_a_constructor_is_not_folded() -> None:
    facts = extract(
        "#include <ros/ros.h>\n"
        "class A {\n"
        '  const std::string topic_ = "default";\n'
        '  A(ros::NodeHandle& nh) : topic_("other") { nh.advertise<std_msgs::Empty>(topic_, 1); }\n'
        "};\n"
    )
    assert dynamic(facts) == [(TOPIC, "topic_")]


def test_escapes_in_literals() -> None:
    # As in C++, a hex escape takes every hex digit that follows: "\x2Fb" is one character.
    facts = extract('#include <ros/ros.h>\nvoid f() { a.advertise<T>("a\\057b\\x2F" "c", 1); }\n')
    assert uses(facts) == [(TOPIC, Role.PUBLISH, "a/b/c", "T")]


# ---------------------------------------------------------------------------------------
# Spans


def test_span_of_a_literal_in_a_multi_line_call() -> None:
    facts = extract(
        "#include <rclcpp/rclcpp.hpp>\n"
        "void f() {\n"
        "  auto sub = node->create_subscription<std_msgs::msg::String>(\n"
        '      "chatter",\n'
        "      10, callback);\n"
        "}\n"
    )
    assert use(facts, "chatter").span == Span(4, 7, 4, 16)


def test_columns_count_code_points_after_non_ascii_text() -> None:
    facts = extract(
        '#include <ros/ros.h>\nvoid f() { /* vélocité → */ nh.advertise<T>("cmd_vel", 1); }\n'
    )
    line = '/* vélocité → */ nh.advertise<T>("cmd_vel", 1); }'
    column = len("void f() { ") + line.index('"') + 1
    assert use(facts, "cmd_vel").span == Span(2, column, 2, column + len('"cmd_vel"'))


def test_spans_with_crlf_line_endings() -> None:
    text = '#include <ros/ros.h>\r\nint main() {\r\n  nh.advertise<T>("chatter", 1);\r\n}\r\n'
    assert use(extract(text), "chatter").span == Span(3, 19, 3, 28)


def test_span_of_a_folded_constant_is_the_identifier_at_the_call() -> None:
    facts = extract(
        '#include <ros/ros.h>\nconst std::string kTopic = "chatter";\n'
        "void f() { nh.advertise<T>(kTopic, 1); }\n"
    )
    assert use(facts, "chatter").span == Span(3, 28, 3, 34)


def test_span_of_adjacent_literals_covers_them_all() -> None:
    facts = extract('#include <ros/ros.h>\nvoid f() { nh.advertise<T>("a"\n  "b", 1); }\n')
    assert use(facts, "ab").span == Span(2, 28, 3, 6)


def test_comments_between_adjacent_literals_are_not_part_of_the_name() -> None:
    """Universal_Robots' trajectory_until_node splits an action name over three lines;
    --add-noqa puts a NOLINT after the first piece."""
    facts = extract(
        "#include <rclcpp_action/rclcpp_action.hpp>\n"
        "void f() { auto c = rclcpp_action::create_client<A>(this,\n"
        '  "/motion_controller/"  // NOLINT(RN202)\n'
        '  "follow_joint_" /* why */ "trajectory"); }\n'
    )
    assert not use(facts, "/motion_controller/follow_joint_trajectory").dynamic


def test_decoding_with_bom_and_utf16() -> None:
    text = '#include <ros/ros.h>\nvoid f() { nh.advertise<T>("chatter", 1); }\n'
    for data in (b"\xef\xbb\xbf" + text.encode(), text.encode("utf-16")):
        facts = extract(data)
        assert facts.parse_errors == ()
        assert use(facts, "chatter").span == Span(2, 28, 2, 37)


def test_undecodable_bytes_are_one_parse_error_and_the_rest_is_read() -> None:
    data = b'#include <ros/ros.h>\n// caf\xe9\nvoid f() { nh.advertise<T>("chatter", 1); }\n'
    facts = extract(data)
    [error] = facts.parse_errors
    assert error.span.line == 2
    assert uses(facts) == [(TOPIC, Role.PUBLISH, "chatter", "T")]


# ---------------------------------------------------------------------------------------
# RN301 events


def test_handles_before_init() -> None:
    facts = fixture("handles_before_init.cpp")
    nh, relay = "ros::NodeHandle", "Relay (holds a ros::NodeHandle)"
    assert events(facts) == [
        (HANDLE, nh, 5, True),  # ros::NodeHandle g_nh;
        (HANDLE, nh, 22, True),  # ros::NodeHandle Relay::shared_nh_("shared");
        (HANDLE, relay, 23, True),  # Relay g_relay;
        (HANDLE, nh, 27, False),  # a function-local static: built when spinOnce first runs
        (HANDLE, nh, 33, False),  # early("~"), before ros::init
        (INIT, "ros::init", 35, False),
        (HANDLE, nh, 36, False),  # new ros::NodeHandle()
        (HANDLE, nh, 37, False),
        (HANDLE, relay, 38, False),
    ]
    assert scopes(facts)[27] == "spinOnce@25"
    assert scopes(facts)[33] == scopes(facts)[35] == "main@31"
    assert (
        next(e for e in facts.events if e.span.line == 33).order
        < next(e for e in facts.events if e.span.line == 35).order
    )


def test_nodes_before_init() -> None:
    facts = fixture("nodes_before_init.cpp")
    assert events(facts) == [
        (HANDLE, "rclcpp::Node", 12, True),  # auto g_node = rclcpp::Node::make_shared(...)
        (HANDLE, "rclcpp::Node", 16, False),
        (HANDLE, "Talker (an rclcpp::Node)", 17, False),
        (INIT, "rclcpp::init", 18, False),
        (HANDLE, "rclcpp::Node", 19, False),
        (HANDLE, "rclcpp::Node", 20, False),  # in a lambda: its own scope
        (HANDLE, "Talker (an rclcpp::Node)", 21, False),
    ]
    assert scopes(facts)[20].startswith("lambda@20")


def test_rn301_on_real_shapes(lint_text: Any) -> None:
    codes = lint_text(
        (FIXTURES / "handles_before_init.cpp").read_text(encoding="utf-8"), "src/a/src/a.cpp", 1
    )
    assert codes == ["RN301"] * 4
    codes = lint_text(
        (FIXTURES / "nodes_before_init.cpp").read_text(encoding="utf-8"), "src/b/src/b.cpp", 2
    )
    assert codes == ["RN301"] * 3


def test_a_default_argument_is_built_by_the_caller_not_before_main() -> None:
    # moveit's `OMPLInterface(..., const ros::NodeHandle& nh = ros::NodeHandle("~"));`
    facts = extract(
        "#include <ros/ros.h>\n"
        'class A { A(const ros::NodeHandle& nh = ros::NodeHandle("~")); };\n'
        'void f(const ros::NodeHandle& nh = ros::NodeHandle("~"));\n'
    )
    assert facts.events == ()


def test_a_member_is_built_with_its_object() -> None:
    facts = extract(
        "#include <ros/ros.h>\n"
        'class A { ros::NodeHandle nh_; ros::NodeHandle pnh_{"~"}; ros::NodeHandle* p_; };\n'
    )
    assert facts.events == ()


def test_statements_of_macro_defined_functions_are_not_static() -> None:
    # gtest's TEST_F(Suite, name) { ... } parses as a block outside any function.
    facts = extract(
        "#include <rclcpp/rclcpp.hpp>\n"
        "MOCKING(a, >)\n"
        "TEST_F(TestNode, construct) {\n"
        '  auto node = std::make_shared<rclcpp::Node>("node", "ns");\n'
        "}\n"
        'TEST(A, b) { EXPECT_NO_THROW(std::make_shared<rclcpp::Node>("n").reset()); }\n'
    )
    assert [event.static_storage for event in facts.events] == [False, False]


def test_pointers_references_and_declarations_build_nothing() -> None:
    facts = extract(
        "#include <ros/ros.h>\n"
        "ros::NodeHandle* g_nh;\n"
        "ros::NodeHandlePtr g_ptr;\n"
        "extern ros::NodeHandle g_other;\n"
        "std::shared_ptr<rclcpp::Node> g_node;\n"
        "rclcpp::Node::SharedPtr g_shared;\n"
        "class A { static ros::NodeHandle s_nh; };\n"
        "ros::NodeHandle make_handle();\n"
        "void f(ros::NodeHandle& nh, ros::NodeHandle copy);\n"
    )
    assert facts.events == ()


def test_init_events() -> None:
    facts = extract(
        "#include <ros/ros.h>\n"
        "int main(int argc, char** argv) {\n"
        '  ros::init(argc, argv, "a", ros::init_options::AnonymousName);\n'
        "  rclcpp::init(argc, argv);\n"
        "  init(argc, argv);\n"
        "}\n"
    )
    assert events(facts) == [(INIT, "ros::init", 3, False), (INIT, "rclcpp::init", 4, False)]
    assert use(facts, "a").kind is NODE


# ---------------------------------------------------------------------------------------
# False positives found on real code


def test_node_renamed_by_node_remap_arguments_is_dynamic() -> None:
    # moveit and nav2 build helper nodes named "_" and rename them with __node:=.
    facts = extract(
        "#include <rclcpp/rclcpp.hpp>\n"
        "void f() {\n"
        '  args.push_back("__node:=" + name + "_private");\n'
        '  pnode_ = std::make_shared<rclcpp::Node>("_", "ns", options.arguments(args));\n'
        "}\n"
    )
    assert dynamic(facts) == [(NODE, "_")]
    assert uses(facts) == [(NAMESPACE, Role.NAMESPACE, "ns", None)]


def test_a_remap_in_a_command_line_renames_that_process_not_this_node() -> None:
    """A test that starts the node under test with `ros2 run ... -r __node:=...` through a
    shell: the remap is that process's; the test's own node keeps the name it is given
    (cause 3 of the recall issue: the string turned off every node name of the file)."""
    facts = extract(
        "#include <gtest/gtest.h>\n"
        "#include <rclcpp/rclcpp.hpp>\n"
        "TEST(Talker, RenamedTalkerPublishes) {\n"
        '  std::system("ros2 run demo_nodes_cpp talker --ros-args -r __node:=talker2 '
        '-r __ns:=/robot1 &");\n'
        '  auto node = std::make_shared<rclcpp::Node>("chatter listener", "robot1");\n'
        "}\n"
    )
    assert dynamic(facts) == []
    assert [(u.kind, u.value) for u in facts.names] == [
        (NODE, "chatter listener"),
        (NAMESPACE, "robot1"),
    ]


def test_clearing_a_frame_id_names_no_frame() -> None:
    facts = extract('#include <ros/ros.h>\nvoid f() { msg.header.frame_id = ""; }\n')
    assert facts.names == ()


def test_frames_only_from_frame_fields_assigned() -> None:
    facts = extract(
        "#include <ros/ros.h>\n"
        "void f() {\n"
        '  msg.header.frame_id = "map";\n'
        '  t->child_frame_id = "base_link";\n'
        '  if (msg.header.frame_id == "odom") {}\n'
        '  frame_id = "local";\n'
        "}\n"
    )
    assert [u.value for u in facts.names] == ["map", "base_link"]


def test_base_initializer_of_a_constructor_whose_class_is_in_a_header() -> None:
    facts = extract(
        '#include "talker.hpp"\n#include <rclcpp/rclcpp.hpp>\n'
        'Talker::Talker() : Node("talker") {}\n'
    )
    assert uses(facts) == [(NODE, Role.NODE_NAME, "talker", None)]


def test_base_initializer_of_a_graph_node_is_no_ros_node() -> None:
    facts = extract(
        "#include <ros/ros.h>\n"
        "struct Node { explicit Node(const char* label); };\n"
        'struct Waypoint : Node { Waypoint() : Node("start") {} };\n'
        'Goal::Goal() : Node("goal") {}\n'
    )
    assert facts.names == ()


def test_unrelated_node_types_are_not_rclcpp_nodes() -> None:
    facts = extract(
        "#include <rclcpp/rclcpp.hpp>\n"
        'YAML::Node config = YAML::LoadFile("robot.yaml");\n'
        'struct Node { Node(const char* name); }; Node root("root");\n'
    )
    assert facts.names == () and facts.events == ()


# ---------------------------------------------------------------------------------------
# Generation, prefilter, robustness


@pytest.mark.parametrize(
    ("include", "expected"),
    [
        ("#include <ros/ros.h>", ROS1),
        ('#include "actionlib/client/simple_action_client.h"', ROS1),
        ("#include <tf/transform_listener.h>", ROS1),
        ("#include <rclcpp/rclcpp.hpp>", ROS2),
        ('#include "rclcpp_lifecycle/lifecycle_node.hpp"', ROS2),
        ("#include <ros/ros.h>\n#include <rclcpp/rclcpp.hpp>", ROS1),  # a bridge: fallback
        ("#include <tf2_ros/buffer.h>\nvoid f(ros::NodeHandle& nh);", ROS1),
    ],
)
def test_generation_from_includes(include: str, expected: Generation) -> None:
    data = f'{include}\nvoid f() {{ msg.header.frame_id = "map"; }}\n'.encode()
    assert cpp.extract("a.cpp", data, None, ROS1).generation is expected


def test_package_generation_wins() -> None:
    data = b'#include <ros/ros.h>\nvoid f() { msg.header.frame_id = "map"; }\n'
    assert cpp.extract("a.cpp", data, ROS2, ROS1).generation is ROS2


def test_files_without_ros_markers_are_not_parsed(monkeypatch: pytest.MonkeyPatch) -> None:
    def fail(data: bytes) -> None:
        raise AssertionError("parsed a file without any ROS marker")

    monkeypatch.setattr(cpp, "_PARSER", type("Parser", (), {"parse": staticmethod(fail)}))
    facts = cpp.extract("a.cpp", b'int main() { puts("/cmd_vel"); }\n', None, ROS1)
    assert facts == FileFacts("a.cpp", Language.CPP, ROS1)


def test_syntax_errors_are_not_parse_errors() -> None:
    facts = extract(
        "#include <ros/ros.h>\n"
        "#define DECLARE(x) x\n"
        "DECLARE(class) Broken { int x = ; };\n"
        'void f() { nh.advertise<T>("chatter", 1) }\n'
    )
    assert facts.parse_errors == ()
    assert [u.value for u in facts.names] == ["chatter"]


def test_deeply_nested_code_is_read_and_stays_in_its_function() -> None:
    depth = 3 * cpp_source.MAX_CLIMB
    body = "{" * depth + 'ros::NodeHandle nh; nh.advertise<T>("deep", 1);' + "}" * depth
    facts = extract(f"#include <ros/ros.h>\nvoid f() {body}\n")
    assert [u.value for u in facts.names] == ["deep"]
    assert [event.static_storage for event in facts.events] == [False]


@settings(max_examples=300, deadline=None)
@given(st.binary(max_size=400))
def test_random_bytes_never_raise(data: bytes) -> None:
    cpp.extract("a.cpp", b"#include <ros/ros.h>\n" + data, None, ROS1)


@settings(max_examples=200, deadline=None)
@given(
    name=st.sampled_from(sorted(path.name for path in FIXTURES.glob("*.cpp"))),
    cut=st.floats(min_value=0, max_value=1),
    junk=st.binary(max_size=20),
)
def test_truncated_real_files_never_raise(name: str, cut: float, junk: bytes) -> None:
    data = (FIXTURES / name).read_bytes()
    cpp.extract(name, data[: int(len(data) * cut)] + junk, None, ROS2)


def test_events_are_values() -> None:
    facts = fixture("handles_before_init.cpp")
    assert all(isinstance(event, RuntimeEvent) for event in facts.events)
    assert len(set(facts.events)) == len(facts.events)


@pytest.mark.parametrize("escape", ["\\ud800", "\\udc80", "\\U0000dfff", "\\xd800"])
def test_surrogate_escape_stands_for_a_replacement_character(escape: str) -> None:
    """A surrogate is no character (C++ rejects ``\\ud800``): like an escape above U+10FFFF
    it stands for U+FFFD, which every report can print (a lone surrogate made the CLI exit
    2 with a UnicodeEncodeError); the name stays illegal."""
    facts = extract(
        "#include <ros/ros.h>\n"
        f'int main(int c, char** v) {{ ros::init(c, v, "talker"); ros::NodeHandle nh;\n'
        f'  nh.advertise<std_msgs::String>("chat{escape}ter", 1); }}\n'
    )
    assert uses(facts)[1:] == [(TOPIC, Role.PUBLISH, "chat\ufffdter", "std_msgs::String")]


class _StillRunningError(Exception):
    pass


def _hang_guard(signum: int, frame: object) -> None:
    raise _StillRunningError("still extracting after a minute: the extractor hangs")


@pytest.mark.skipif(not hasattr(signal, "SIGALRM"), reason="needs SIGALRM")
def test_member_written_without_its_type_does_not_hang() -> None:
    """``nh_ = ros::NodeHandle();`` in a class body (its type forgotten) is a member that
    tree-sitter names with a MISSING, empty identifier; looking for the occurrences of ""
    looped forever (found by atheris). The alarm turns a hang into a failure."""
    previous = signal.signal(signal.SIGALRM, _hang_guard)
    signal.alarm(60)
    try:
        facts = extract("#include <ros/ros.h>\nclass Relay {\n  nh_ = ros::NodeHandle();\n};\n")
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    assert facts.parse_errors == ()


# ---------------------------------------------------------------------------------------
# API forms with a model now (recall issue, cause 4)

CAMERA_DRIVER_ROS1 = """#include <ros/ros.h>
#include <image_transport/image_transport.h>
#include <sensor_msgs/LaserScan.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "stereo_driver");
  ros::NodeHandle nh;
  image_transport::ImageTransport it(nh);
  image_transport::CameraPublisher left = it.advertiseCamera("/stereo/left/image_raw", 1);
  image_transport::CameraSubscriber sync = it.subscribeCamera("sync/image", 1, &onSync);
  // Wait for the laser before starting: the calibration needs one scan.
  auto scan = ros::topic::waitForMessage<sensor_msgs::LaserScan>("/base_scan", nh);
  ros::spin();
}
"""
CAMERA_DRIVER_ROS2 = """#include <rclcpp/rclcpp.hpp>
#include <image_transport/image_transport.hpp>
#include <sensor_msgs/msg/laser_scan.hpp>

class StereoDriver : public rclcpp::Node
{
public:
  StereoDriver() : Node("stereo_driver")
  {
    left_ = image_transport::create_camera_publisher(this, "left/image_raw");
    sync_ = image_transport::create_camera_subscription(this, "sync/image", cb, "raw");
    sensor_msgs::msg::LaserScan scan;
    rclcpp::wait_for_message(scan, shared_from_this(), "/base_scan", std::chrono::seconds(5));
  }
};
"""


def test_camera_publishers_subscribers_and_waiting_for_one_message() -> None:
    ros1 = extract(CAMERA_DRIVER_ROS1, Generation.ROS1)
    assert [u for u in uses(ros1) if u[0] is TOPIC] == [
        (TOPIC, Role.PUBLISH, "/stereo/left/image_raw", None),
        (TOPIC, Role.SUBSCRIBE, "sync/image", None),
        (TOPIC, Role.SUBSCRIBE, "/base_scan", "sensor_msgs::LaserScan"),
    ]
    ros2 = extract(CAMERA_DRIVER_ROS2)
    assert [u for u in uses(ros2) if u[0] is TOPIC] == [
        (TOPIC, Role.PUBLISH, "left/image_raw", None),
        (TOPIC, Role.SUBSCRIBE, "sync/image", None),
        (TOPIC, Role.SUBSCRIBE, "/base_scan", None),
    ]


# rclcpp's overloads taking node interfaces, as rclcpp's own TimeSource and NodeLogging
# call them, and a sub-node's namespace (recall issue, cause 4).
NODE_INTERFACES = """#include <rclcpp/rclcpp.hpp>
#include <rosgraph_msgs/msg/clock.hpp>
#include <std_srvs/srv/trigger.hpp>

void attach(
  rclcpp::node_interfaces::NodeBaseInterface::SharedPtr node_base,
  rclcpp::node_interfaces::NodeGraphInterface::SharedPtr node_graph,
  rclcpp::node_interfaces::NodeServicesInterface::SharedPtr node_services,
  rclcpp::node_interfaces::NodeParametersInterface::SharedPtr node_parameters,
  rclcpp::node_interfaces::NodeTopicsInterface::SharedPtr node_topics)
{
  auto clock = rclcpp::create_subscription<rosgraph_msgs::msg::Clock>(
    node_parameters, node_topics, "/clock", rclcpp::ClockQoS(), on_clock);
  auto reset = rclcpp::create_client<std_srvs::srv::Trigger>(
    node_base, node_graph, node_services, "reset odometry", rclcpp::ServicesQoS(), nullptr);
}

class Driver : public rclcpp::Node
{
public:
  Driver() : Node("driver")
  {
    auto sensors = create_sub_node("Sensors");
    auto pub = rclcpp::create_publisher<rosgraph_msgs::msg::Clock>(this, "tick", 10);
  }
};
"""


def test_node_interface_overloads_and_sub_nodes() -> None:
    facts = extract(NODE_INTERFACES)
    assert [(u[0], u[1], u[2]) for u in uses(facts)] == [
        (TOPIC, Role.SUBSCRIBE, "/clock"),
        (SERVICE, Role.CALL, "reset odometry"),
        (NODE, Role.NODE_NAME, "driver"),
        (NAMESPACE, Role.NAMESPACE, "Sensors"),
        (TOPIC, Role.PUBLISH, "tick"),
    ]
    assert dynamic(facts) == []


# Names held in variables: followed where the value is certain, dynamic where it is not.

LASER_FILTER_CPP = """\
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <std_srvs/Empty.h>

class LaserFilter
{
public:
  LaserFilter() : scan_topic_("scan"), nh_("~")
  {
    filtered_topic_ = "/scan_filtered";
    reset_service_ = "reset";
    nh_.param("input", input_topic_, std::string("raw_scan"));  // written by the server
  }

  void start()
  {
    sub_ = nh_.subscribe(scan_topic_, 10, &LaserFilter::onScan, this);
    pub_ = nh_.advertise<sensor_msgs::LaserScan>(filtered_topic_, 10);
    raw_sub_ = nh_.subscribe(input_topic_, 10, &LaserFilter::onScan, this);
    ROS_INFO("serving %s", reset_service_.c_str());
    server_ = nh_.advertiseService(reset_service_, &LaserFilter::onReset, this);
  }

private:
  void onScan(const sensor_msgs::LaserScan::ConstPtr& scan) { pub_.publish(*scan); }
  bool onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) { return true; }

  ros::NodeHandle nh_;
  std::string scan_topic_;
  std::string filtered_topic_;
  std::string reset_service_;
  std::string input_topic_;
  ros::Subscriber sub_, raw_sub_;
  ros::Publisher pub_;
  ros::ServiceServer server_;
};

int main(int argc, char** argv)
{
  ros::init(argc, argv, "laser_filter");
  ros::NodeHandle nh;
  std::string status = "status";
  status = "/diagnostics/status";
  ros::Publisher status_pub = nh.advertise<std_msgs::String>(status, 1);
  std::string mode = "mode";
  if (argc > 1) {
    mode = argv[1];
  }
  ros::Publisher mode_pub = nh.advertise<std_msgs::String>(mode, 1);
  std::string odom = "odom";
  for (int i = 0; i < 2; ++i) {
    ros::Publisher odom_pub = nh.advertise<std_msgs::String>(odom, 1);
    odom = "odom_" + std::to_string(i);
  }
  std::string cmd = "cmd_vel";
  cmd += "_raw";
  ros::Subscriber cmd_sub = nh.subscribe(cmd, 1, &onCommand);
  std::string same = "heartbeat";
  if (argc > 2) {
    same = "heartbeat";
  }
  ros::Publisher heartbeat_pub = nh.advertise<std_msgs::String>(same, 1);
  LaserFilter filter;
  filter.start();
  ros::spin();
}
"""


def test_locals_and_members_whose_value_is_certain_are_followed() -> None:
    facts = extract(LASER_FILTER_CPP, ROS1)
    assert uses(facts) == [
        (PARAMETER, Role.PARAMETER, "input", None),
        (TOPIC, Role.SUBSCRIBE, "scan", "sensor_msgs::LaserScan"),
        (TOPIC, Role.PUBLISH, "/scan_filtered", "sensor_msgs::LaserScan"),
        (SERVICE, Role.SERVE, "reset", "std_srvs::Empty"),
        (NODE, Role.NODE_NAME, "laser_filter", None),
        (TOPIC, Role.PUBLISH, "/diagnostics/status", "std_msgs::String"),
        (TOPIC, Role.PUBLISH, "heartbeat", "std_msgs::String"),
    ]
    # nh_.param() writes input_topic_; mode is set on one path only; odom changes on the
    # loop's next turn; cmd is appended to.
    assert [value for kind, value in dynamic(facts) if kind is TOPIC] == [
        "input_topic_",
        "mode",
        "odom",
        "cmd",
    ]


IMU_DRIVER_CPP = """\
#include "imu_driver/imu_driver.hpp"

namespace imu_driver
{
ImuDriver::ImuDriver(const rclcpp::NodeOptions& options) : rclcpp::Node("imu_driver", options)
{
  data_topic_ = "/imu/data";
  frame_ = declare_parameter("frame_id", "imu_link");
}

void ImuDriver::start()
{
  publisher_ = create_publisher<sensor_msgs::msg::Imu>(data_topic_, 10);
  for (const auto& topic_name : extra_topics_) {
    extra_.push_back(create_publisher<sensor_msgs::msg::Imu>(topic_name, 10));
  }
}
}  // namespace imu_driver
"""


def test_a_member_declared_in_the_header_and_set_in_the_constructor_is_followed() -> None:
    facts = extract(IMU_DRIVER_CPP, ROS2)
    assert (TOPIC, Role.PUBLISH, "/imu/data", "sensor_msgs::msg::Imu") in uses(facts)
    assert dynamic(facts) == [(TOPIC, "topic_name")]


# A ROS 1 laser merger, shaped like ira_laser_tools' laserscan_multi_merger: each scan
# topic is kept in a list as well as subscribed to.
SCAN_MERGER = """#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>

#include <string>
#include <utility>
#include <vector>

class ScanMerger
{
public:
  explicit ScanMerger(ros::NodeHandle & nh)
  {
    std::string front = "scan_front";
    std::string rear = "scan_rear";
    topics_.push_back(front);
    topics_.emplace_back(rear);
    front_sub_ = nh.subscribe(front, 10, &ScanMerger::onScan, this);
    rear_sub_ = nh.subscribe(rear, 10, &ScanMerger::onScan, this);
    std::string moved = "scan_moved";
    topics_.push_back(std::move(moved));
    moved_sub_ = nh.subscribe(moved, 10, &ScanMerger::onScan, this);
  }

private:
  void onScan(const sensor_msgs::LaserScan::ConstPtr & scan) {}
  std::vector<std::string> topics_;
  ros::Subscriber front_sub_, rear_sub_, moved_sub_;
};
"""


def test_a_string_copied_into_a_container_keeps_its_value() -> None:
    """push_back and emplace_back copy the name: it was taken as written, so dynamic,
    which silenced RN404 for the node. Moved from, it is unknown indeed."""
    facts = extract(SCAN_MERGER)
    assert [(u.value, u.dynamic) for u in facts.names if u.role is Role.SUBSCRIBE] == [
        ("scan_front", False),
        ("scan_rear", False),
        ("moved", True),
    ]


@pytest.mark.parametrize(
    ("code", "roles"),
    [
        # a TransformStamped's `transform` field is no call of tf2_ros::Buffer::transform
        (
            "tf2_ros::StaticTransformBroadcaster b(node);\n"
            "void f() { t.transform.rotation.w = 1.0; b.sendTransform(t); }\n",
            ("broadcast",),
        ),
        (
            "tf::TransformBroadcaster br;\ntf::TransformListener listener;\n",
            ("broadcast", "listen"),
        ),
        ('void f() { auto p = buffer_->transform(pose, "map"); }\n', ("listen",)),
        ("void f() { tf_->lookupTransform(a, b, t); }\n", ("listen",)),
        # only in a comment or a string: not code
        ('// a TransformBroadcaster\nconst char * s = "TransformListener";\n', ()),
    ],
)
def test_what_the_code_does_with_tf(code: str, roles: tuple[str, ...]) -> None:
    facts = extract("int main(int c, char ** v) { rclcpp::init(c, v); }\n" + code)
    assert [role.value for role in facts.tf_roles] == list(roles)

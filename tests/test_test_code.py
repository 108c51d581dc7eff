"""Test code is judged for what breaks a test, not for style (``test_code``, ``[test-code]``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from conftest import write, write_package

from roslint_names.config import Settings
from roslint_names.model import Language
from roslint_names.test_code import is_example_code, is_test_code

# An rclcpp gtest as ament packages write them: a CamelCase fixture node, an absolute
# topic the node under test publishes in the root namespace, and one name that really
# breaks the test (a space: rclcpp throws InvalidTopicNameError at create_publisher).
GTEST = """#include <gtest/gtest.h>

#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

class TestTalker : public ::testing::Test
{
protected:
  static void SetUpTestCase() { rclcpp::init(0, nullptr); }
  static void TearDownTestCase() { rclcpp::shutdown(); }
};

TEST_F(TestTalker, publishes_chatter)
{
  auto node = std::make_shared<rclcpp::Node>("TalkerTestNode");
  auto sub = node->create_subscription<std_msgs::msg::String>(
    "/chatter", 10, [](std_msgs::msg::String::ConstSharedPtr) {});
  auto pub = node->create_publisher<std_msgs::msg::String>("talker status", 10);
  EXPECT_EQ(1u, node->count_subscribers("/chatter"));
}
"""

# A rostest file: the fixture's node names are the test author's business.
ROSTEST = """<launch>
  <node pkg="robot_base" type="base_driver" name="baseDriver"/>
  <test test-name="base_driver_hztest" pkg="rostest" type="hztest" name="hzTest">
    <param name="topic" value="/odom"/>
    <param name="hz" value="50.0"/>
  </test>
</launch>
"""


def _workspace(root: Path) -> None:
    write_package(root / "talker", 2, "talker")
    write(root, "talker/test/test_talker.cpp", GTEST)
    write_package(root / "robot_base", 1, "robot_base")
    write(root, "robot_base/launch/hztest.test", ROSTEST)


def _codes_by_path(result: Any) -> list[tuple[str, str]]:
    return [(finding["path"], finding["code"]) for finding in result.findings()]


def test_test_code_is_judged_by_the_rules_that_break_tests(run_cli: Any, tmp_path: Path) -> None:
    _workspace(tmp_path)
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    # RN203 (TalkerTestNode, baseDriver, hzTest) and RN202 (/chatter) are style in a test.
    assert _codes_by_path(result) == [("talker/test/test_talker.cpp", "RN101")]


def test_the_same_code_outside_tests_is_judged_in_full(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "talker", 2, "talker")
    write(tmp_path, "talker/src/talker_check.cpp", GTEST.replace("<gtest/gtest.h>", "<cstdio>"))
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    assert sorted(code for _, code in _codes_by_path(result)) == ["RN101", "RN202", "RN203"]


@pytest.mark.parametrize(
    ("config", "expected"),
    [
        # Every rule of the run judges test code too.
        (
            '[test-code]\nselect = ["ALL"]\n',
            [
                ("robot_base/launch/hztest.test", "RN203"),
                ("robot_base/launch/hztest.test", "RN203"),
                ("talker/test/test_talker.cpp", "RN203"),
                ("talker/test/test_talker.cpp", "RN202"),
                ("talker/test/test_talker.cpp", "RN101"),
            ],
        ),
        (
            '[test-code]\nextend-select = ["RN202"]\n',
            [("talker/test/test_talker.cpp", "RN202"), ("talker/test/test_talker.cpp", "RN101")],
        ),
        ('[test-code]\nignore = ["illegal-name"]\n', []),
        # A rule the run does not check is not brought back by [test-code].
        ('ignore = ["RN101"]\n[test-code]\nselect = ["ALL"]\n', None),
    ],
)
def test_test_code_selection_is_configurable(
    run_cli: Any, tmp_path: Path, config: str, expected: list[tuple[str, str]] | None
) -> None:
    _workspace(tmp_path)
    write(tmp_path, "roslint-names.toml", config)
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    found = _codes_by_path(result)
    if expected is None:
        assert "RN101" not in [code for _, code in found]
        assert ("talker/test/test_talker.cpp", "RN203") in found
    else:
        assert found == expected


def test_configured_paths_are_test_code(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "talker", 2, "talker")
    source = GTEST.replace("<gtest/gtest.h>", "<cstdio>")
    write(tmp_path, "talker/integration/talker_check.cpp", source)
    write(tmp_path, "roslint-names.toml", '[test-code]\npaths = ["integration/"]\n')
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    assert _codes_by_path(result) == [("talker/integration/talker_check.cpp", "RN101")]


def test_a_suppression_of_a_rule_off_in_tests_is_not_unused(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "talker", 2, "talker")
    source = GTEST.replace('"/chatter", 10,', '"/chatter", 10,  // NOLINT(RN202)')
    write(tmp_path, "talker/test/test_talker.cpp", source)
    result = run_cli(["check", "--format", "json", "--extend-select", "RN002", "."], tmp_path)
    assert _codes_by_path(result) == [("talker/test/test_talker.cpp", "RN101")]


def test_graph_rules_spare_test_code_for_style(run_cli: Any, tmp_path: Path) -> None:
    """RN401 is style: a test's '/Chatter' does not collide with the package's '/chatter'."""
    write_package(tmp_path / "talker", 1, "talker")
    node = """#include <ros/ros.h>
#include <std_msgs/String.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "talker");
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<std_msgs::String>("/chatter", 10);
  ros::spin();
}
"""
    write(tmp_path, "talker/src/talker.cpp", node)
    test = """#!/usr/bin/env python
import unittest

import rospy
import rostest
from std_msgs.msg import String


class TalkerTest(unittest.TestCase):
    def test_hears_talker(self):
        rospy.init_node("talker_test")
        msg = rospy.wait_for_message("/Chatter", String, timeout=5.0)
        self.assertTrue(msg.data)


if __name__ == "__main__":
    rostest.rosrun("talker", "talker_test", TalkerTest)
"""
    write(tmp_path, "talker/scripts/talker_check.py", test)
    write(tmp_path, "roslint-names.toml", 'extend-select = ["RN401"]\n')
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    assert [code for _, code in _codes_by_path(result)].count("RN401") == 1
    assert all(path == "talker/src/talker.cpp" for path, _ in _codes_by_path(result))


# rplidar_ros's launch/test_rplidar.launch: what its README tells users to launch to try
# the driver with a client; no <test> in it.
RPLIDAR_TRY = """<!--
  Used for visualising rplidar in action.

  It requires rplidar.launch.
 -->
<launch>
  <include file="$(find rplidar_ros)/launch/rplidar.launch" />

  <node name="rplidarNodeClient"    pkg="rplidar_ros"  type="rplidarNodeClient" output="screen">
  </node>
</launch>
"""


def test_a_launch_file_named_test_but_holding_no_test_is_judged_in_full(
    run_cli: Any, tmp_path: Path
) -> None:
    """Its node name's style (RN203, not judged in tests) was passed over before."""
    write_package(tmp_path / "rplidar_ros", 1, "rplidar_ros")
    write(tmp_path, "rplidar_ros/launch/test_rplidar.launch", RPLIDAR_TRY)
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    found = [(f["path"], f["line"], f["code"]) for f in result.findings()]
    assert found == [("rplidar_ros/launch/test_rplidar.launch", 9, "RN203")]


@pytest.mark.parametrize(
    ("path", "language", "content", "expected"),
    [
        ("nav2_smoother/test/test_smoother_server.cpp", Language.CPP, "", True),
        ("rclpy/tests/conftest.py", Language.PYTHON, "", True),
        ("test_tf2/src/speed_test.cpp", Language.CPP, "", True),  # a test package
        ("nav2_system_tests/src/planning/planner_tester.cpp", Language.CPP, "", True),
        ("geometry2/tf2/src/buffer_core_test.cpp", Language.CPP, "", True),
        ("rospy_tutorials/scripts/test_on_shutdown.py", Language.PYTHON, "", True),
        ("robot/launch/hztest.test", Language.LAUNCH_XML, "", True),
        ("moveit_servo/launch/servo_integration.test.py", Language.LAUNCH_PYTHON, "", True),
        ("talker/src/talker.cpp", Language.CPP, '#include "gtest/gtest.h"\n', True),
        ("talker/scripts/check.py", Language.PYTHON, "import unittest\n", True),
        ("talker/scripts/check.py", Language.PYTHON, "from launch_testing import x\n", True),
        ("bringup/launch/all.launch", Language.LAUNCH_XML, '<launch><test name="t"/>', True),
        # Test support: code that exists for tests (before, judged in full).
        ("autoware_test_utils/src/topic_snapshot_saver.cpp", Language.CPP, "", True),
        ("hardware_interface_testing/src/mock.cpp", Language.CPP, "", True),
        ("autoware/testing/autoware_testing/src/fake.cpp", Language.CPP, "", True),
        (
            "ros2_controllers_test_nodes/ros2_controllers_test_nodes/publisher.py",
            Language.PYTHON,
            "",
            True,
        ),
        # Not tests: names that only contain "test".
        ("robot/src/testimonial_viewer.cpp", Language.CPP, "", False),
        ("attestation/src/signer.cpp", Language.CPP, "", False),
        ("robot/src/latest_scan.cpp", Language.CPP, "", False),
        ("robot/scripts/contest.py", Language.PYTHON, "# unittest-like\n", False),
        ("robot/launch/robot.launch", Language.LAUNCH_XML, "<launch><node/></launch>", False),
        # Launch files named for what a user tries, holding no test (rplidar_ros's).
        ("rplidar_ros/launch/test_rplidar.launch", Language.LAUNCH_XML, RPLIDAR_TRY, False),
        ("camera/launch/test_camera.launch.py", Language.LAUNCH_PYTHON, "import launch\n", False),
        ("camera/launch/test_camera.launch.yaml", Language.LAUNCH_YAML, "launch: []\n", False),
        # ... and the same names with a test in them.
        (
            "rplidar_ros/launch/test_rplidar.launch",
            Language.LAUNCH_XML,
            RPLIDAR_TRY.replace("</launch>", '<test test-name="scan" pkg="r" type="t"/></launch>'),
            True,
        ),
        (
            "camera/launch/test_camera.launch.py",
            Language.LAUNCH_PYTHON,
            "import launch_testing\n",
            True,
        ),
    ],
)
def test_test_code_conventions(
    tmp_path: Path, path: str, language: Language, content: str, expected: bool
) -> None:
    assert is_test_code(path, language, content, Settings(root=tmp_path)) is expected


# rclcpp's test/rclcpp/test_node.cpp and test_publisher.cpp, reduced: names the test passes
# to check that rclcpp refuses them, and one it means to work but misspells.
EXPECTED_FAILURES_CPP = """#include <gtest/gtest.h>

#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "rclcpp/exceptions.hpp"
#include "std_msgs/msg/string.hpp"

TEST(TestNode, construction_before_init_throws)
{
  EXPECT_THROW(rclcpp::Node("early_node"), rclcpp::exceptions::RCLError);
}

class TestPublisher : public ::testing::Test
{
protected:
  static void SetUpTestCase() { rclcpp::init(0, nullptr); }
};

TEST_F(TestPublisher, invalid_names)
{
  auto node = std::make_shared<rclcpp::Node>("my_node", "/ns");
  EXPECT_THROW(
    std::make_shared<rclcpp::Node>("invalid_node?", "/ns"),
    rclcpp::exceptions::InvalidNodeNameError);
  ASSERT_THROW(
    {
      auto publisher = node->create_publisher<std_msgs::msg::String>("invalid_topic?", 10);
    }, rclcpp::exceptions::InvalidTopicNameError);
  RCLCPP_EXPECT_THROW_EQ(
    node->create_publisher<std_msgs::msg::String>("", 10),
    std::invalid_argument("topic name must not be empty"));
  EXPECT_ANY_THROW(node->create_subscription<std_msgs::msg::String>(
    "7up", 10, [](std_msgs::msg::String::ConstSharedPtr) {}));
  ASSERT_DEATH(node->create_publisher<std_msgs::msg::String>("bad topic", 10), "");
  try {
    auto client = node->create_client<std_srvs::srv::Empty>("bad-service");
    FAIL() << "create_client accepted 'bad-service'";
  } catch (const rclcpp::exceptions::InvalidServiceNameError &) {
  }
  tf2::BufferCore buffer;
  EXPECT_FALSE(buffer.canTransform("", "base_link", tf2::TimePointZero));
  EXPECT_NO_THROW(node->create_publisher<std_msgs::msg::String>("status-out", 10));
  auto chatter = node->create_publisher<std_msgs::msg::String>("chatter out", 10);
}
"""

# ros_comm's test_rospy, reduced: the same two idioms in Python.
EXPECTED_FAILURES_PY = """import unittest

import rospy


class TestRospyClient(unittest.TestCase):
    def test_init_node(self):
        try:
            rospy.init_node('ns/node')
        except ValueError:
            pass
        else:
            self.fail("init_node accepted 'ns/node'")
        try: rospy.get_param('non-existent'); self.fail("get_param succeeded")
        except KeyError: pass
        self.assertFalse(rospy.has_param('non-existent'))
        with self.assertRaises(ValueError):
            rospy.Publisher('bad topic', String, queue_size=1)
        rospy.Subscriber('chatter in', String, self.callback)

    def test_init_node_empty_name(self):
        failed = True
        try:
            rospy.init_node('')
        except ValueError:
            failed = False
        self.failIf(failed, "init_node allowed an empty name")

    def test_rate(self):
        # rostest's hztest: a handler that fails the test says the tried call must work.
        try:
            rospy.Subscriber('rate in', String, self.callback)
        except rospy.ROSException as e:
            self.fail('cannot subscribe: %s' % e)

    def connect(self):
        try:
            rospy.Subscriber('odom in', Odometry, self.callback)
        except rospy.ROSException:
            rospy.logwarn('no odometry')
"""


def test_names_a_test_expects_to_fail_are_never_reported(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "talker", 2, "talker")
    write(tmp_path, "talker/test/test_publisher.cpp", EXPECTED_FAILURES_CPP)
    write_package(tmp_path / "test_rospy", 1, "test_rospy")
    write(tmp_path, "test_rospy/test/test_rospy_client.py", EXPECTED_FAILURES_PY)
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    found = [(f["path"], f["line"], f["code"]) for f in result.findings()]
    assert found == [
        ("talker/test/test_publisher.cpp", 43, "RN101"),  # status-out: meant to work
        ("talker/test/test_publisher.cpp", 44, "RN101"),  # chatter out
        ("test_rospy/test/test_rospy_client.py", 19, "RN101"),  # chatter in
        ("test_rospy/test/test_rospy_client.py", 32, "RN101"),  # rate in: must work
        ("test_rospy/test/test_rospy_client.py", 38, "RN101"),  # odom in: not a test
    ]


# tf2's test_tf2/test/buffer_core_test.cpp (ros/geometry2 and ros2/geometry2), reduced: the
# fields set just before an EXPECT_FALSE that takes the message are its deliberately
# invalid input; the same fields before a call that must succeed are judged.
PREPARED_FAILURES_CPP = """#include <gtest/gtest.h>
#include <geometry_msgs/msg/transform_stamped.hpp>
#include <tf2/buffer_core.h>

TEST(BufferCore_setTransform, NoInsertWithNoParentID)
{
  tf2::BufferCore mBC;
  geometry_msgs::msg::TransformStamped tranStamped;
  tranStamped.header.stamp = tf2_ros::toMsg(tf2::timeFromSec(10.0));
  tranStamped.child_frame_id = "some_frame";
  tranStamped.header.frame_id = "";
  EXPECT_FALSE(mBC.setTransform(tranStamped, "authority"));

  // only a slash, which setTransform strips to nothing
  tranStamped.header.frame_id = "/";
  EXPECT_FALSE(mBC.setTransform(tranStamped, "authority"));
}

TEST(BufferCore_lookupTransform, LeadingSlash)
{
  tf2::BufferCore mBC;
  geometry_msgs::msg::TransformStamped other;
  geometry_msgs::msg::TransformStamped tranStamped;
  tranStamped.header.frame_id = "/odom";
  other.child_frame_id = "/base_link";
  EXPECT_FALSE(mBC.setTransform(tranStamped, "authority"));
  tranStamped.child_frame_id = "/laser";
  mBC.clear();
  EXPECT_TRUE(mBC.setTransform(tranStamped, "authority"));
}
"""


def test_fields_set_for_a_call_a_test_expects_to_fail_are_never_reported(
    run_cli: Any, tmp_path: Path
) -> None:
    write_package(tmp_path / "test_tf2", 2, "test_tf2")
    write(tmp_path, "test_tf2/test/buffer_core_test.cpp", PREPARED_FAILURES_CPP)
    result = run_cli(["check", "--format", "json", "--select", "RN205", "."], tmp_path)
    # other.child_frame_id: the macro does not take `other`; "/laser": a statement that
    # sets no field stands between it and the macro.
    assert [f["line"] for f in result.findings()] == [25, 27]


# A launch_testing test as universal_robots writes them (ur_robot_driver/test/
# urscript_interface.py): the launch description and the test's own rclpy node in one file.
LAUNCH_TEST = """import unittest

import launch_testing
import pytest
import rclpy
from launch import LaunchDescription
from launch_ros.actions import Node
from rclpy.action import ActionClient
from std_msgs.msg import String
from ur_msgs.action import ExecuteScript
from ur_msgs.msg import IOStates


@pytest.mark.launch_test
def generate_test_description():
    driver = Node(package="ur_robot_driver", executable="urscript_interface")
    return LaunchDescription([driver, launch_testing.actions.ReadyToTest()])


class URScriptInterfaceTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rclpy.init()
        cls.node = rclpy.node.Node("urscript_interface_test")

    def test_set_io(self):
        publisher = self.node.create_publisher(String, "/urscript_interface/script_command", 1)
        client = ActionClient(self.node, ExecuteScript, "/urscript_interface/execute_script")
        states = self.node.create_subscription(
            IOStates, "/io_and_status_controller/io_states", lambda msg: None, 1
        )
"""


def test_a_launch_test_s_own_code_is_judged_as_code(run_cli: Any, tmp_path: Path) -> None:
    """The file is a launch description and Python code at once: its publisher, client
    and subscription are endpoints RN202 judges (once test code is selected for it), and
    a subscription uses a name, it does not choose one."""
    write_package(tmp_path / "ur_robot_driver", 2, "ur_robot_driver")
    write(tmp_path, "ur_robot_driver/test/urscript_interface.py", LAUNCH_TEST)
    write(tmp_path, "roslint-names.toml", '[test-code]\nextend-select = ["RN202", "RN203"]\n')
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    # Every endpoint name of the file is absolute: one decision (``decisions``), at the
    # publisher, with the action client and the subscription related.
    assert [
        (f["line"], f["code"], [place["line"] for place in f["related"]]) for f in result.findings()
    ] == [(27, "RN202", [28, 30])]


# ros2/demos' composition/src/client_component.cpp, reduced: the node name the tutorial
# prints, and one name that breaks the demo (a space: rclcpp throws InvalidTopicNameError).
DEMO_COMPONENT = """#include <memory>

#include "example_interfaces/srv/add_two_ints.hpp"
#include "rclcpp/rclcpp.hpp"

namespace composition
{

class Client : public rclcpp::Node
{
public:
  explicit Client(const rclcpp::NodeOptions & options)
  : Node("Client", options)
  {
    client_ = create_client<example_interfaces::srv::AddTwoInts>("add_two_ints");
    status_ = create_publisher<std_msgs::msg::String>("client status", 10);
  }
};

}  // namespace composition
"""

# Universal_Robots_ROS2_Driver's ur_robot_driver/examples/move_until_example.py, reduced: an
# example script that talks to the driver launched in the root namespace.
EXAMPLE_SCRIPT = """import rclpy
from rclpy.action import ActionClient
from rclpy.node import Node
from ur_msgs.action import TrajectoryUntil


class MoveUntilExample(Node):
    def __init__(self):
        super().__init__("move_until_example")
        self._client = ActionClient(self, TrajectoryUntil, "/trajectory_until_node/execute")


def main():
    rclpy.init()
    rclpy.spin(MoveUntilExample())
"""


def test_example_code_is_judged_as_test_code(run_cli: Any, tmp_path: Path) -> None:
    """Before, 'Client' (RN203) and the absolute action (RN202) were reported."""
    write_package(tmp_path / "demos" / "composition", 2, "composition")
    write(tmp_path, "demos/composition/src/client_component.cpp", DEMO_COMPONENT)
    write_package(tmp_path / "ur_robot_driver", 2, "ur_robot_driver")
    write(tmp_path, "ur_robot_driver/examples/move_until_example.py", EXAMPLE_SCRIPT)
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    assert [(f["path"], f["line"], f["code"]) for f in result.findings()] == [
        ("demos/composition/src/client_component.cpp", 16, "RN101"),
    ]


def test_a_run_inside_a_clone_of_an_example_repository_is_example_code(
    run_cli: Any, tmp_path: Path
) -> None:
    """`cd demos && roslint-names check .`: no folder below the root says 'demo'."""
    root = tmp_path / "demos"
    write_package(root / "composition", 2, "composition")
    write(root, "composition/src/client_component.cpp", DEMO_COMPONENT)
    result = run_cli(["check", "--format", "json", "."], root)
    assert [f["code"] for f in result.findings()] == ["RN101"]


def test_the_same_code_in_a_product_package_is_judged_in_full(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "robot_control", 2, "robot_control")
    write(tmp_path, "robot_control/src/client_component.cpp", DEMO_COMPONENT)
    write(tmp_path, "robot_control/scripts/move_until.py", EXAMPLE_SCRIPT)
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    assert sorted(f["code"] for f in result.findings()) == ["RN101", "RN202", "RN203"]


@pytest.mark.parametrize(
    ("path", "expected"),
    [
        ("ur_robot_driver/examples/move_until_example.py", True),
        ("demo_nodes_cpp/src/topics/talker.cpp", True),
        ("quality_of_service_demo/rclcpp/src/message_lost_listener.cpp", True),
        ("rospy_tutorials/006_parameters/param_talker.py", True),
        ("example_7/reference_generator/send_trajectory.cpp", True),
        ("ros2_control_demos/example_1/hardware/rrbot.cpp", True),
        ("examples_rclcpp_minimal_publisher/member_function.cpp", True),
        ("nav2_simple_commander/nav2_simple_commander/example_nav_to_pose.py", True),
        ("moveit_servo/demos/servo_keyboard_input.cpp", True),
        # Names that only contain the words.
        ("robot/src/demodulator.cpp", False),
        ("robot/src/counterexample_check.cpp", False),
        ("autoware_sample_rate_limiter/src/node.cpp", False),
        ("robot/launch/bringup.launch", False),
    ],
)
def test_example_code_conventions(tmp_path: Path, path: str, expected: bool) -> None:
    assert is_example_code(path, Settings(root=tmp_path / "ws")) is expected


# ros_comm's test_rospy/test/rostest/test_service_order.py, reduced: the test that rospy
# lets a service be declared before init_node (#530), and a private one, which lands
# under /unnamed where the test will never find it.
SERVICE_ORDER_PY = """\
import sys
import unittest

import rospy
import rostest
from test_rospy.srv import EmptyReqSrv, EmptyReqSrvResponse


def handle(req):
    return EmptyReqSrvResponse(123456)


def service_before():
    s = rospy.Service('service_order_before', EmptyReqSrv, handle)
    rospy.init_node('service_before')
    rospy.spin()


def private_before():
    s = rospy.Service('~private_order_before', EmptyReqSrv, handle)
    rospy.init_node('private_before')
    rospy.spin()


class TestServiceOrder(unittest.TestCase):
    def test_before(self):
        rospy.wait_for_service('service_order_before', 10.0)


if __name__ == '__main__':
    if '--before' in sys.argv:
        service_before()
    else:
        rostest.run('test_rospy', 'rospy_service_decl_order', TestServiceOrder, sys.argv)
"""


def test_a_service_before_init_in_a_test_is_judged_only_where_it_breaks_the_test(
    run_cli: Any, tmp_path: Path
) -> None:
    """Before, both services were RN301 findings; made before init_node, the first works
    in the root namespace the test runs it in, and only launch remaps would miss it."""
    write_package(tmp_path / "test_rospy", 1, "test_rospy")
    write(tmp_path, "test_rospy/test/rostest/test_service_order.py", SERVICE_ORDER_PY)
    result = run_cli(["check", "--format", "json", "--select", "RN301", "."], tmp_path)
    assert [(f["line"], f["code"]) for f in result.findings()] == [(20, "RN301")]
    # Outside tests, the same code misses the launch file's remaps: reported.
    node = SERVICE_ORDER_PY.partition("\n\nclass ")[0].replace("import rostest\n", "")
    node = node.replace("import unittest\n", "")
    write_package(tmp_path / "order_services", 1, "order_services")
    write(tmp_path, "order_services/nodes/service_order.py", node)
    result = run_cli(["check", "--format", "json", "--select", "RN301", "."], tmp_path)
    assert [(f["path"], f["line"]) for f in result.findings()] == [
        ("order_services/nodes/service_order.py", 12),
        ("order_services/nodes/service_order.py", 18),
        ("test_rospy/test/rostest/test_service_order.py", 20),
    ]


def test_a_run_over_a_file_judges_it_as_the_run_over_the_workspace_does(
    run_cli: Any, tmp_path: Path
) -> None:
    """pre-commit names the files staged. Without a config file, their run took their own
    folder as its root, above which no folder was looked at: ros2/demos' client, named
    alone, was no example code, and its absolute action (RN202) and node name (RN203)
    were reported where the run over the workspace reports neither."""
    write_package(tmp_path / "src" / "demos" / "composition", 2, "composition")
    write(tmp_path, "src/demos/composition/src/client_component.cpp", DEMO_COMPONENT)
    workspace = run_cli(["check", "--format", "json", "--no-cache", "."], tmp_path)
    named = run_cli(
        [
            "check",
            "--format",
            "json",
            "--no-cache",
            "src/demos/composition/src/client_component.cpp",
        ],
        tmp_path,
    )
    assert [f["code"] for f in named.findings()] == [f["code"] for f in workspace.findings()]
    assert [f["code"] for f in named.findings()] == ["RN101"]

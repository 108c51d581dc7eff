"""One decision, one finding: a name written at many places is reported once.

Each test writes a workspace shaped like the real one the findings came from
(ros2/examples' wait_set, MoveIt's RViz plugin and servo demos, amcl, gazebo_ros_pkgs'
harness plugin, MoveIt 2's MoveItCpp tests) and runs the real CLI over it.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from conftest import AMENT_PACKAGE, CATKIN_PACKAGE, Run, write

from roslint_names.config import load_settings
from roslint_names.registry import load_registry
from roslint_names.session import Session


def check(run_cli: Any, root: Path, *arguments: str) -> Run:
    result: Run = run_cli(["check", "--format", "json", *arguments], root)
    assert result.exit_code in (0, 1), result.stderr
    return result


def places(finding: dict[str, Any]) -> list[tuple[str, int]]:
    """Where a finding is, then the other places it stands for."""
    return [(place["path"], place["line"]) for place in (finding, *finding["related"])]


# ---------------------------------------------------------------------------------------
# ros2/examples, rclcpp/wait_set: two programs publish topicA, topicB and topicC

WAIT_SET_CMAKE = """\
cmake_minimum_required(VERSION 3.5)
project(rclcpp_wait_set)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(std_msgs REQUIRED)
include_directories(include)
add_executable(wait_set_random_order src/wait_set_random_order.cpp)
ament_target_dependencies(wait_set_random_order rclcpp std_msgs)
add_executable(wait_set_topics_and_timer src/wait_set_topics_and_timer.cpp)
ament_target_dependencies(wait_set_topics_and_timer rclcpp std_msgs)
install(TARGETS wait_set_random_order wait_set_topics_and_timer DESTINATION lib/${PROJECT_NAME})
ament_package()
"""
RANDOM_TALKER_HPP = """\
#ifndef WAIT_SET__RANDOM_TALKER_HPP_
#define WAIT_SET__RANDOM_TALKER_HPP_

#include <functional>
#include <vector>

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

class RandomTalker : public rclcpp::Node
{
public:
  RandomTalker()
  : Node("random_talker"),
    pub1_(this->create_publisher<std_msgs::msg::String>("topicA", 10)),
    pub2_(this->create_publisher<std_msgs::msg::String>("topicB", 10)),
    pub3_(this->create_publisher<std_msgs::msg::String>("topicC", 10))
  {
  }

private:
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr pub1_;
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr pub2_;
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr pub3_;
};

#endif  // WAIT_SET__RANDOM_TALKER_HPP_
"""
RANDOM_LISTENER_HPP = """\
#ifndef WAIT_SET__RANDOM_LISTENER_HPP_
#define WAIT_SET__RANDOM_LISTENER_HPP_

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

class RandomListener : public rclcpp::Node
{
public:
  RandomListener()
  : Node("random_listener")
  {
    auto print_msg = [this](std_msgs::msg::String::ConstSharedPtr msg) {
        RCLCPP_INFO(this->get_logger(), "I heard: '%s'", msg->data.c_str());
      };
    sub1_ = this->create_subscription<std_msgs::msg::String>("topicA", 10, print_msg);
    sub2_ = this->create_subscription<std_msgs::msg::String>("topicB", 10, print_msg);
    sub3_ = this->create_subscription<std_msgs::msg::String>("topicC", 10, print_msg);
  }

private:
  rclcpp::Subscription<std_msgs::msg::String>::SharedPtr sub1_, sub2_, sub3_;
};

#endif  // WAIT_SET__RANDOM_LISTENER_HPP_
"""
WAIT_SET_RANDOM_ORDER_CPP = """\
#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "wait_set/random_listener.hpp"
#include "wait_set/random_talker.hpp"

int main(int argc, char * argv[])
{
  rclcpp::init(argc, argv);
  auto talker = std::make_shared<RandomTalker>();
  auto listener = std::make_shared<RandomListener>();
  rclcpp::executors::SingleThreadedExecutor executor;
  executor.add_node(talker);
  executor.add_node(listener);
  executor.spin();
  rclcpp::shutdown();
  return 0;
}
"""
WAIT_SET_TOPICS_AND_TIMER_CPP = """\
#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

int main(int argc, char * argv[])
{
  rclcpp::init(argc, argv);

  auto node = std::make_shared<rclcpp::Node>("wait_set_listener");
  auto do_nothing = [](std_msgs::msg::String::UniquePtr) {assert(false);};

  auto sub1 = node->create_subscription<std_msgs::msg::String>("topicA", 1, do_nothing);
  auto sub2 = node->create_subscription<std_msgs::msg::String>("topicB", 1, do_nothing);
  auto sub3 = node->create_subscription<std_msgs::msg::String>("topicC", 1, do_nothing);

  const auto pub1 =
    node->create_publisher<std_msgs::msg::String>("topicA", 1);
  const auto pub2 =
    node->create_publisher<std_msgs::msg::String>("topicB", 1);
  const auto pub3 =
    node->create_publisher<std_msgs::msg::String>("topicC", 1);

  rclcpp::WaitSet wait_set({{sub1}, {sub2}, {sub3}});
  wait_set.wait(std::chrono::seconds(1));
  rclcpp::shutdown();
  return 0;
}
"""


def wait_set_workspace(root: Path) -> None:
    package = "src/io_tools/rclcpp/wait_set"
    write(root, f"{package}/package.xml", AMENT_PACKAGE.format(name="rclcpp_wait_set"))
    write(root, f"{package}/CMakeLists.txt", WAIT_SET_CMAKE)
    write(root, f"{package}/include/wait_set/random_talker.hpp", RANDOM_TALKER_HPP)
    write(root, f"{package}/include/wait_set/random_listener.hpp", RANDOM_LISTENER_HPP)
    write(root, f"{package}/src/wait_set_random_order.cpp", WAIT_SET_RANDOM_ORDER_CPP)
    write(root, f"{package}/src/wait_set_topics_and_timer.cpp", WAIT_SET_TOPICS_AND_TIMER_CPP)


TALKER = "src/io_tools/rclcpp/wait_set/include/wait_set/random_talker.hpp"
TOPICS_AND_TIMER = "src/io_tools/rclcpp/wait_set/src/wait_set_topics_and_timer.cpp"


def test_a_topic_two_programs_publish_is_one_finding(run_cli: Any, tmp_path: Path) -> None:
    """`topicA` is spelled by two publishers (and subscribers, which RN203 leaves to the
    publisher): three names, three findings, each naming the other program's place."""
    wait_set_workspace(tmp_path)
    found = check(run_cli, tmp_path, "--select", "RN203", ".").findings()
    assert [places(f) for f in found] == [
        [(TALKER, 15), (TOPICS_AND_TIMER, 18)],
        [(TALKER, 16), (TOPICS_AND_TIMER, 20)],
        [(TALKER, 17), (TOPICS_AND_TIMER, 22)],
    ]
    assert found[0]["message"] == (
        "topic 'topicA' is not lower snake_case ('topicA'); use 'topic_a' "
        "(also written at 1 other place)"
    )
    assert found[0]["related"][0]["message"] == (
        "topic 'topicA' also written here (rclcpp::Node::create_publisher)"
    )
    text = run_cli(["check", "--select", "RN203", "."], tmp_path).stdout.splitlines()
    assert f"{TOPICS_AND_TIMER}:18:51: note: topic 'topicA' also written here " in (text[1] + " ")


def test_the_rename_of_the_one_finding_renames_every_place(run_cli: Any, tmp_path: Path) -> None:
    wait_set_workspace(tmp_path)
    found = check(run_cli, tmp_path, "--select", "RN203", "--unsafe-fixes", ".").findings()
    assert len(found) == 3
    renamed = sorted((other["path"], other["line"]) for other in found[0]["fix"]["also"])
    assert renamed == [
        ("src/io_tools/rclcpp/wait_set/include/wait_set/random_listener.hpp", 16),
        (TOPICS_AND_TIMER, 13),
        (TOPICS_AND_TIMER, 18),
    ]
    fixed = run_cli(["check", "--select", "RN203", "--fix", "--unsafe-fixes", "."], tmp_path)
    assert "fixed 3 findings in 3 files" in fixed.stderr
    source = (tmp_path / TOPICS_AND_TIMER).read_text(encoding="utf-8")
    assert "topicA" not in source and source.count('"topic_a"') == 2
    assert check(run_cli, tmp_path, "--select", "RN203", ".").findings() == []


def test_findings_are_the_same_bytes_whatever_the_jobs(run_cli: Any, tmp_path: Path) -> None:
    wait_set_workspace(tmp_path)
    runs = [
        run_cli(["check", "--no-cache", "--format", "sarif", "-j", jobs, "."], tmp_path).stdout
        for jobs in ("1", "4", "1")
    ]
    assert runs[0] == runs[1] == runs[2]
    results = json.loads(runs[0])["runs"][0]["results"]
    assert [len(result.get("relatedLocations", [])) for result in results] == [1, 1, 1]


def test_a_run_over_one_file_reports_its_own_places(run_cli: Any, tmp_path: Path) -> None:
    """pre-commit passes the changed file; the publisher in the rest of the workspace is
    context, with no findings to join: the file's own finding stays (``decisions``)."""
    wait_set_workspace(tmp_path)
    found = check(run_cli, tmp_path, "--select", "RN203", TOPICS_AND_TIMER).findings()
    assert [places(f) for f in found] == [
        [(TOPICS_AND_TIMER, 18)],
        [(TOPICS_AND_TIMER, 20)],
        [(TOPICS_AND_TIMER, 22)],
    ]


# ---------------------------------------------------------------------------------------
# MoveIt's RViz plugin (ROS 1): the plugin subscribes to /rviz/moveit/plan, moveitjoy
# publishes it; the object recognition client is built in two files from one constant.

VISUALIZATION = "src/moveit/moveit_ros/visualization"
FRAME_H = f"{VISUALIZATION}/motion_planning_rviz_plugin/include/moveit/motion_planning_rviz_plugin/motion_planning_frame.h"  # noqa: E501
FRAME_CPP = f"{VISUALIZATION}/motion_planning_rviz_plugin/src/motion_planning_frame.cpp"
MANIPULATION_CPP = (
    f"{VISUALIZATION}/motion_planning_rviz_plugin/src/motion_planning_frame_manipulation.cpp"
)
MOVEITJOY_PY = f"{VISUALIZATION}/src/moveit_ros_visualization/moveitjoy_module.py"

MOTION_PLANNING_FRAME_H = """\
#pragma once

#include <actionlib/client/simple_action_client.h>
#include <object_recognition_msgs/ObjectRecognitionAction.h>
#include <ros/ros.h>

namespace moveit_rviz_plugin
{
const std::string OBJECT_RECOGNITION_ACTION = "/recognize_objects";

class MotionPlanningFrame
{
public:
  MotionPlanningFrame();
  void enable(bool enable);
  void triggerObjectDetection();

private:
  void remotePlanCallback(const std_msgs::EmptyConstPtr& msg);
  std::unique_ptr<actionlib::SimpleActionClient<object_recognition_msgs::ObjectRecognitionAction>>
      object_recognition_client_;
  ros::Subscriber plan_subscriber_;
};
}  // namespace moveit_rviz_plugin
"""
MOTION_PLANNING_FRAME_CPP = """\
#include <moveit/motion_planning_rviz_plugin/motion_planning_frame.h>
#include <std_msgs/Empty.h>

namespace moveit_rviz_plugin
{
MotionPlanningFrame::MotionPlanningFrame()
{
  object_recognition_client_ =
      std::make_unique<actionlib::SimpleActionClient<object_recognition_msgs::ObjectRecognitionAction>>(
          OBJECT_RECOGNITION_ACTION, false);
}

void MotionPlanningFrame::enable(bool enable)
{
  if (enable)
  {
    ros::NodeHandle nh;
    plan_subscriber_ = nh.subscribe("/rviz/moveit/plan", 1,
                                    &MotionPlanningFrame::remotePlanCallback, this);
  }
}
}  // namespace moveit_rviz_plugin
"""
MOTION_PLANNING_FRAME_MANIPULATION_CPP = """\
#include <moveit/motion_planning_rviz_plugin/motion_planning_frame.h>

namespace moveit_rviz_plugin
{
void MotionPlanningFrame::triggerObjectDetection()
{
  if (!object_recognition_client_)
  {
    object_recognition_client_ =
        std::make_unique<actionlib::SimpleActionClient<object_recognition_msgs::ObjectRecognitionAction>>(
            OBJECT_RECOGNITION_ACTION, false);
  }
}
}  // namespace moveit_rviz_plugin
"""
MOVEITJOY_MODULE_PY = """\
import rospy
from std_msgs.msg import Empty


class MoveitJoy:
    def __init__(self):
        rospy.init_node("moveit_joy")
        self.plan_pub = rospy.Publisher("/rviz/moveit/plan", Empty, queue_size=5)

    def plan(self):
        self.plan_pub.publish(Empty())
"""


def moveit_workspace(root: Path) -> None:
    write(
        root, f"{VISUALIZATION}/package.xml", CATKIN_PACKAGE.format(name="moveit_ros_visualization")
    )
    write(root, FRAME_H, MOTION_PLANNING_FRAME_H)
    write(root, FRAME_CPP, MOTION_PLANNING_FRAME_CPP)
    write(root, MANIPULATION_CPP, MOTION_PLANNING_FRAME_MANIPULATION_CPP)
    write(root, MOVEITJOY_PY, MOVEITJOY_MODULE_PY)


def test_a_topic_is_reported_at_its_publisher(run_cli: Any, tmp_path: Path) -> None:
    """The plugin's subscriber comes first in path order; the decision is moveitjoy's,
    which publishes the topic, and its fix is the subscriber's too."""
    moveit_workspace(tmp_path)
    found = check(run_cli, tmp_path, "--select", "RN202", "--unsafe-fixes", ".").findings()
    topic = [f for f in found if "/rviz/moveit/plan" in f["message"]]
    assert [places(f) for f in topic] == [[(MOVEITJOY_PY, 8), (FRAME_CPP, 18)]]
    fix = topic[0]["fix"]
    assert (fix["line"], fix["replacement"], fix["safe"]) == (8, "rviz/moveit/plan", False)
    assert [(o["path"], o["line"], o["replacement"]) for o in fix["also"]] == [
        (FRAME_CPP, 18, "rviz/moveit/plan")
    ]
    fixed = run_cli(["check", "--select", "RN202", "--fix", "--unsafe-fixes", "."], tmp_path)
    assert "roslint-names: wrote" in fixed.stderr, fixed.stderr
    for path in (MOVEITJOY_PY, FRAME_CPP):
        text = (tmp_path / path).read_text(encoding="utf-8")
        assert '"rviz/moveit/plan"' in text and '"/rviz/moveit/plan"' not in text


def test_one_action_client_built_in_two_files_is_one_finding(run_cli: Any, tmp_path: Path) -> None:
    moveit_workspace(tmp_path)
    found = check(run_cli, tmp_path, "--select", "RN202", ".").findings()
    action = [f for f in found if "/recognize_objects" in f["message"]]
    assert [places(f) for f in action] == [[(FRAME_CPP, 10), (MANIPULATION_CPP, 11)]]
    assert action[0]["message"].endswith("(also written at 1 other place)")


# ---------------------------------------------------------------------------------------
# MoveIt 2's servo: a Python teleop and a C++ keyboard demo publish one absolute topic,
# the demo through a constant of its own, which no edit of the literal reaches.

TELEOP_PY = """\
import rclpy
from geometry_msgs.msg import TwistStamped
from rclpy.node import Node
from sensor_msgs.msg import Joy


class TeleopDevice(Node):
    def __init__(self, node_name="teleop_node"):
        super().__init__(node_name=node_name)
        self.joy_subscriber = self.create_subscription(Joy, "joy", self.publish_command, 10)
        self.twist_publisher = self.create_publisher(
            TwistStamped, "/servo_node/delta_twist_cmds", 10
        )

    def publish_command(self, data):
        pass


def main():
    rclpy.init()
    rclpy.spin(TeleopDevice())
"""
SERVO_KEYBOARD_INPUT_CPP = """\
#include <geometry_msgs/msg/twist_stamped.hpp>
#include <rclcpp/rclcpp.hpp>

namespace
{
const std::string TWIST_TOPIC = "/servo_node/delta_twist_cmds";
const size_t ROS_QUEUE_SIZE = 10;
}  // namespace

class KeyboardServo
{
public:
  KeyboardServo() : nh_{ std::make_shared<rclcpp::Node>("servo_keyboard_input") }
  {
    twist_pub_ = nh_->create_publisher<geometry_msgs::msg::TwistStamped>(TWIST_TOPIC,
                                                                         ROS_QUEUE_SIZE);
  }

private:
  rclcpp::Node::SharedPtr nh_;
  rclcpp::Publisher<geometry_msgs::msg::TwistStamped>::SharedPtr twist_pub_;
};
"""
TELEOP = "src/moveit2/moveit_py/moveit/servo_client/teleop.py"
KEYBOARD = "src/moveit2/moveit_ros/moveit_servo/tools/servo_keyboard_input.cpp"


def test_a_decision_one_place_cannot_be_edited_at_has_no_fix(run_cli: Any, tmp_path: Path) -> None:
    """Made relative in teleop.py alone, the topic would leave the keyboard demo's under
    a namespace: the fix is every place or none."""
    write(tmp_path, "src/moveit2/moveit_py/package.xml", AMENT_PACKAGE.format(name="moveit_py"))
    write(tmp_path, TELEOP, TELEOP_PY)
    servo = "src/moveit2/moveit_ros/moveit_servo"
    write(tmp_path, f"{servo}/package.xml", AMENT_PACKAGE.format(name="moveit_servo"))
    write(tmp_path, KEYBOARD, SERVO_KEYBOARD_INPUT_CPP)
    found = check(run_cli, tmp_path, "--select", "RN202", "--unsafe-fixes", ".").findings()
    assert [places(f) for f in found] == [[(TELEOP, 12), (KEYBOARD, 15)]]
    assert found[0]["fix"] is None
    # Alone, teleop.py's place has its fix, as before.
    alone = check(run_cli, tmp_path, "--select", "RN202", "--unsafe-fixes", TELEOP).findings()
    assert alone[0]["fix"]["replacement"] == "servo_node/delta_twist_cmds"


# ---------------------------------------------------------------------------------------
# amcl (ROS 1): one parameter read twice; another node's parameter of the same name

AMCL_NODE_CPP = """\
#include <ros/ros.h>

class AmclNode
{
public:
  AmclNode();

private:
  ros::NodeHandle private_nh_;
  bool do_beamskip_;
  double beam_skip_distance_, beam_skip_threshold_, beam_skip_error_threshold_;
};

AmclNode::AmclNode() : private_nh_("~")
{
  private_nh_.param("do_beamskip", do_beamskip_, false);
  private_nh_.param("beam_skip_distance", beam_skip_distance_, 0.5);
  private_nh_.param("beam_skip_threshold", beam_skip_threshold_, 0.3);
  if (private_nh_.hasParam("beam_skip_error_threshold_"))
  {
    private_nh_.param("beam_skip_error_threshold_", beam_skip_error_threshold_);
  }
  else
  {
    beam_skip_error_threshold_ = 0.9;
  }
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "amcl");
  AmclNode node;
  ros::spin();
  return 0;
}
"""
LOCALIZER_CPP = """\
#include <ros/ros.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "beam_localizer");
  ros::NodeHandle private_nh("~");
  double threshold;
  private_nh.param("beam_skip_error_threshold_", threshold, 0.9);
  ros::spin();
  return 0;
}
"""
AMCL = "src/navigation/amcl/src/amcl_node.cpp"
LOCALIZER = "src/beam_localizer/src/beam_localizer.cpp"


def amcl_workspace(root: Path) -> None:
    write(root, "src/navigation/amcl/package.xml", CATKIN_PACKAGE.format(name="amcl"))
    write(root, AMCL, AMCL_NODE_CPP)


def test_a_parameter_read_twice_is_one_finding(run_cli: Any, tmp_path: Path) -> None:
    amcl_workspace(tmp_path)
    found = check(run_cli, tmp_path, "--select", "RN203", "--unsafe-fixes", ".").findings()
    assert [places(f) for f in found] == [[(AMCL, 19), (AMCL, 21)]]
    fix = found[0]["fix"]
    assert [(o["path"], o["line"]) for o in fix["also"]] == [(AMCL, 21)]


def test_another_nodes_parameter_of_that_name_is_its_own(run_cli: Any, tmp_path: Path) -> None:
    """A parameter belongs to its node: another program's is another decision."""
    amcl_workspace(tmp_path)
    write(tmp_path, "src/beam_localizer/package.xml", CATKIN_PACKAGE.format(name="beam_localizer"))
    write(tmp_path, LOCALIZER, LOCALIZER_CPP)
    found = check(run_cli, tmp_path, "--select", "RN203", ".").findings()
    assert [places(f) for f in found] == [[(LOCALIZER, 8)], [(AMCL, 19), (AMCL, 21)]]


def test_the_language_server_joins_a_documents_own_places(tmp_path: Path) -> None:
    amcl_workspace(tmp_path)
    registry = load_registry()
    session = Session(tmp_path, load_settings(None, tmp_path, registry), registry, None)
    session.load()
    found = session.check(tmp_path / AMCL, AMCL_NODE_CPP)
    assert found is not None
    assert [(d.code, d.span.line, [r.span.line for r in d.related]) for d in found] == [
        ("RN203", 19, [21])
    ]


# ---------------------------------------------------------------------------------------
# Suppressions: a place's comment is used; a kept finding's silences the decision


def test_a_suppression_at_another_place_is_used_and_keeps_its_own(
    run_cli: Any, tmp_path: Path
) -> None:
    """The second read says why it keeps the spelling: no RN002 says it silences nothing,
    the first read still reports the name, and the rename is held back."""
    source = AMCL_NODE_CPP.replace(
        "beam_skip_error_threshold_);\n",
        "beam_skip_error_threshold_);  // NOLINT(RN203) documented on the wiki\n",
    )
    write(tmp_path, "src/navigation/amcl/package.xml", CATKIN_PACKAGE.format(name="amcl"))
    write(tmp_path, AMCL, source)
    arguments = ("--extend-select", "RN002", "--unsafe-fixes", ".")
    found = check(run_cli, tmp_path, *arguments).findings()
    assert [(f["code"], places(f), f["fix"]) for f in found] == [("RN203", [(AMCL, 19)], None)]
    everything = check(run_cli, tmp_path, "--include-suppressed", ".")
    assert "RN002" not in everything.stdout


def test_a_suppressed_kept_finding_silences_every_place(run_cli: Any, tmp_path: Path) -> None:
    source = AMCL_NODE_CPP.replace(
        'hasParam("beam_skip_error_threshold_"))',
        'hasParam("beam_skip_error_threshold_"))  // NOLINT(RN203) documented on the wiki',
    )
    write(tmp_path, "src/navigation/amcl/package.xml", CATKIN_PACKAGE.format(name="amcl"))
    write(tmp_path, AMCL, source)
    result = check(run_cli, tmp_path, "--extend-select", "RN002", ".")
    assert (result.exit_code, result.findings()) == (0, [])


def test_add_noqa_writes_one_comment_for_the_decision(run_cli: Any, tmp_path: Path) -> None:
    wait_set_workspace(tmp_path)
    added = run_cli(["check", "--select", "RN203", "--add-noqa", "."], tmp_path)
    assert "added 3 suppression comments in 1 files" in added.stderr
    assert "NOLINT" not in (tmp_path / TOPICS_AND_TIMER).read_text(encoding="utf-8")
    again = check(run_cli, tmp_path, "--select", "RN203", "--extend-select", "RN002", ".")
    assert (again.exit_code, again.findings()) == (0, [])


# ---------------------------------------------------------------------------------------
# gazebo_ros_pkgs' harness plugin (ROS 1): two topics built from the absolute "/"

HARNESS_CPP = """\
#include <gazebo_plugins/gazebo_ros_harness.h>
#include <std_msgs/Bool.h>
#include <std_msgs/Float32.h>

namespace gazebo
{
void GazeboRosHarness::Load(physics::ModelPtr _parent, sdf::ElementPtr _sdf)
{
  HarnessPlugin::Load(_parent, _sdf);
  this->rosnode_ = new ros::NodeHandle(this->robotNamespace_);

  ros::SubscribeOptions so = ros::SubscribeOptions::create<std_msgs::Float32>(
      "/" + _parent->GetName() + "/harness/velocity", 1,
    boost::bind(&GazeboRosHarness::OnVelocity, this, _1),
    ros::VoidPtr(), &this->queue_);
  this->velocitySub_ = this->rosnode_->subscribe(so);

  so = ros::SubscribeOptions::create<std_msgs::Bool>(
    "/" + _parent->GetName() + "/harness/detach", 1,
    boost::bind(&GazeboRosHarness::OnDetach, this, _1),
    ros::VoidPtr(), &this->queue_);
  this->detachSub_ = this->rosnode_->subscribe(so);
}
}  // namespace gazebo
"""


def test_names_built_from_one_absolute_prefix_are_one_finding(run_cli: Any, tmp_path: Path) -> None:
    plugins = "src/gazebo_ros_pkgs/gazebo_plugins"
    write(tmp_path, f"{plugins}/package.xml", CATKIN_PACKAGE.format(name="gazebo_plugins"))
    write(tmp_path, f"{plugins}/src/gazebo_ros_harness.cpp", HARNESS_CPP)
    found = check(run_cli, tmp_path, "--select", "RN202", ".").findings()
    harness = f"{plugins}/src/gazebo_ros_harness.cpp"
    assert [places(f) for f in found] == [[(harness, 13), (harness, 19)]]
    assert found[0]["related"][0]["message"] == (
        "a topic built from '/' also written here (ros::SubscribeOptions::create)"
    )


# ---------------------------------------------------------------------------------------
# MoveIt 2's MoveItCpp tests: one illegal node name in two test files; and the baseline

MOVEIT_CPP_TEST_CPP = """\
#include <gtest/gtest.h>
#include <rclcpp/rclcpp.hpp>

class MoveItCppTest : public ::testing::Test
{
public:
  void SetUp() override
  {
    rclcpp::NodeOptions node_options;
    node_options.automatically_declare_parameters_from_overrides(true);
    node_ = rclcpp::Node::make_shared("/moveit_cpp_test", node_options);
  }

protected:
  rclcpp::Node::SharedPtr node_;
};

TEST_F(MoveItCppTest, GetCurrentStateTest)
{
  EXPECT_NE(node_, nullptr);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  rclcpp::init(argc, argv);
  int result = RUN_ALL_TESTS();
  rclcpp::shutdown();
  return result;
}
"""
PLANNING_TEST = "src/moveit2/moveit_ros/planning/moveit_cpp/test/moveit_cpp_test.cpp"
INTERFACE_TEST = "src/moveit2/moveit_ros/planning_interface/test/moveit_cpp_test.cpp"


def moveit_cpp_tests(root: Path) -> None:
    for package, name in (
        ("src/moveit2/moveit_ros/planning", "moveit_ros_planning"),
        ("src/moveit2/moveit_ros/planning_interface", "moveit_ros_planning_interface"),
    ):
        write(root, f"{package}/package.xml", AMENT_PACKAGE.format(name=name))
    write(root, PLANNING_TEST, MOVEIT_CPP_TEST_CPP)
    write(root, INTERFACE_TEST, MOVEIT_CPP_TEST_CPP)


def test_an_illegal_node_name_in_two_tests_is_one_finding(run_cli: Any, tmp_path: Path) -> None:
    moveit_cpp_tests(tmp_path)
    found = check(run_cli, tmp_path, "--select", "RN101", ".").findings()
    assert [places(f) for f in found] == [[(PLANNING_TEST, 11), (INTERFACE_TEST, 11)]]


def test_a_baseline_knows_a_decision_by_every_place(run_cli: Any, tmp_path: Path) -> None:
    """Recorded by each place; a third copy of the name makes the finding new again."""
    moveit_cpp_tests(tmp_path)
    written = run_cli(["check", "--write-baseline", "baseline.json", "."], tmp_path)
    assert "wrote 1 findings to baseline.json" in written.stderr
    entries = json.loads((tmp_path / "baseline.json").read_text(encoding="utf-8"))["findings"]
    assert sorted(entry["path"] for entry in entries) == [PLANNING_TEST, INTERFACE_TEST]
    known = check(run_cli, tmp_path, "--baseline", "baseline.json", "--verbose", ".")
    assert (known.exit_code, known.findings()) == (0, [])
    assert "no longer found" not in known.stderr
    third = "src/moveit2/moveit_ros/planning/moveit_cpp/test/moveit_cpp_copy_test.cpp"
    write(tmp_path, third, MOVEIT_CPP_TEST_CPP)
    grown = check(run_cli, tmp_path, "--baseline", "baseline.json", ".")
    assert [places(f) for f in grown.findings()] == [
        [(third, 11), (PLANNING_TEST, 11), (INTERFACE_TEST, 11)]
    ]


# ---------------------------------------------------------------------------------------
# Universal_Robots_ROS2_Driver's motion primitives example: an action client and a client of
# the same action's cancel service, both absolute: one name, the action's.

MOTION_PRIMITIVES_PY = """\
import rclpy
from action_msgs.srv import CancelGoal
from rclpy.action import ActionClient
from rclpy.node import Node
from control_msgs.action import ExecuteMotionPrimitiveSequence


class MotionPrimitiveExecutor(Node):
    def __init__(self):
        super().__init__("motion_primitive_executor")
        self._client = ActionClient(
            self,
            ExecuteMotionPrimitiveSequence,
            "/motion_primitive_forward_controller/motion_sequence",
        )
        self._cancel_client = self.create_client(
            CancelGoal, "/motion_primitive_forward_controller/motion_sequence/_action/cancel_goal"
        )


def main():
    rclpy.init()
    rclpy.spin(MotionPrimitiveExecutor())
"""
MOTION_PRIMITIVES = "src/ur_robot_driver/scripts/send_dummy_motion_primitives.py"


def test_an_actions_cancel_service_is_the_actions_decision(run_cli: Any, tmp_path: Path) -> None:
    """rcl_action names the cancel service ``<action>/_action/cancel_goal``: writing it
    absolute is the action's absolute name again, one decision with the action client."""
    package = AMENT_PACKAGE.format(name="ur_robot_driver")
    write(tmp_path, "src/ur_robot_driver/package.xml", package)
    write(tmp_path, MOTION_PRIMITIVES, MOTION_PRIMITIVES_PY)
    found = check(run_cli, tmp_path, "--select", "RN202", ".").findings()
    assert [places(f) for f in found] == [[(MOTION_PRIMITIVES, 14), (MOTION_PRIMITIVES, 17)]]
    assert "absolute action" in found[0]["message"]


# ---------------------------------------------------------------------------------------
# MoveIt's moveit_joy (ROS 1), reduced: every name it writes is absolute, one of them a
# topic the RViz plugin subscribes to as well; its end-effector topics come from the SRDF.

JOY_MODULE_PY = """\
import rospy
from geometry_msgs.msg import PoseStamped
from sensor_msgs.msg import Joy
from std_msgs.msg import Empty


class MoveitJoy:
    def __init__(self):
        self.plan_pub = rospy.Publisher("/rviz/moveit/plan", Empty, queue_size=5)
        self.joy_pose_pub = rospy.Publisher("/joy_pose", PoseStamped, queue_size=1)
        self.sub = rospy.Subscriber("/joy", Joy, self.joyCB, queue_size=1)

    def updatePoseTopic(self, topics, index):
        self.pose_pub = rospy.Publisher(topics[index], PoseStamped, queue_size=5)

    def joyCB(self, msg):
        pass


if __name__ == "__main__":
    rospy.init_node("moveit_joy")
    MoveitJoy()
    rospy.spin()
"""
PLAN_FRAME_CPP = """\
#include <ros/ros.h>
#include <std_msgs/Empty.h>

class MotionPlanningFrame
{
public:
  MotionPlanningFrame()
  {
    plan_subscriber_ = nh_.subscribe("/rviz/moveit/plan", 1, &MotionPlanningFrame::plan, this);
    status_pub_ = nh_.advertise<std_msgs::Empty>("planning_status", 1);
  }

private:
  void plan(const std_msgs::EmptyConstPtr& msg) {}
  ros::NodeHandle nh_;
  ros::Subscriber plan_subscriber_;
  ros::Publisher status_pub_;
};
"""
JOY_MODULE = "src/moveit/moveit_ros/visualization/src/moveit_ros_visualization/moveitjoy_module.py"
PLAN_FRAME = "src/moveit/moveit_ros/visualization/motion_planning_rviz_plugin/src/frame.cpp"


def test_a_file_that_writes_every_name_absolute_is_one_decision(
    run_cli: Any, tmp_path: Path
) -> None:
    """Before, moveit_joy's three names were three findings: the file binds its node to the
    root namespace, one choice. The plugin's subscription is the same topic (kept at the
    publisher); the plugin itself, which writes a relative name, is no such design."""
    visualization = "src/moveit/moveit_ros/visualization"
    write(tmp_path, f"{visualization}/package.xml", CATKIN_PACKAGE.format(name="visualization"))
    write(tmp_path, JOY_MODULE, JOY_MODULE_PY)
    write(tmp_path, PLAN_FRAME, PLAN_FRAME_CPP)
    found = check(run_cli, tmp_path, "--select", "RN202", "--unsafe-fixes", ".").findings()
    assert [places(f) for f in found] == [
        [(JOY_MODULE, 9), (PLAN_FRAME, 9), (JOY_MODULE, 10), (JOY_MODULE, 11)]
    ]
    assert "every endpoint name of this file is absolute, 2 more" in found[0]["message"]
    notes = [place["message"] for place in found[0]["related"]]
    assert notes[1:] == ["absolute topic '/joy_pose' here too", "absolute topic '/joy' here too"]
    # One fix for the whole decision: every place made relative, or none.
    fix = found[0]["fix"]
    assert sorted((o["path"], o["line"]) for o in fix["also"]) == [
        (PLAN_FRAME, 9),
        (JOY_MODULE, 10),
        (JOY_MODULE, 11),
    ]


def test_a_file_with_one_relative_name_is_judged_name_by_name(run_cli: Any, tmp_path: Path) -> None:
    visualization = "src/moveit/moveit_ros/visualization"
    write(tmp_path, f"{visualization}/package.xml", CATKIN_PACKAGE.format(name="visualization"))
    write(tmp_path, JOY_MODULE, JOY_MODULE_PY.replace('"/joy"', '"joy"'))
    found = check(run_cli, tmp_path, "--select", "RN202", ".").findings()
    assert [places(f) for f in found] == [[(JOY_MODULE, 9)], [(JOY_MODULE, 10)]]

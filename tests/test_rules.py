"""Rules on realistic launch snippets, one behaviour per test, pyflakes style."""

from __future__ import annotations

from typing import Any

from conftest import write, write_package

ROS1_CAMERA = """<launch>
  <group ns="camera">
    <node name="depth_republisher" pkg="image_transport" type="republish"
          args="compressedDepth raw">
      <remap from="in" to="depth/image_raw"/>
      <remap from="out" to="depth/image_raw/compressedDepth"/>
    </node>
  </group>
</launch>
"""


def test_image_transport_suffix_is_not_a_style_problem(lint_text: Any) -> None:
    # image_transport names its subtopics after the transport plugin (`compressedDepth`);
    # the launch author cannot choose another spelling.
    assert lint_text(ROS1_CAMERA, "camera.launch", 1) == []


def test_camel_case_elsewhere_is_still_reported(lint_text: Any) -> None:
    source = ROS1_CAMERA.replace("depth/image_raw/compressedDepth", "depth/compressedDepth/raw")
    assert lint_text(source, "camera.launch", 1) == ["RN203"]


def test_launch_param_and_remap_source_names_are_not_judged_for_style(lint_text: Any) -> None:
    source = """<launch>
  <node name="slam_gmapping" pkg="gmapping" type="slam_gmapping">
    <param name="maxUrange" value="6.0"/>
    <remap from="scanTopic" to="base_scan"/>
  </node>
</launch>
"""
    assert lint_text(source, "gmapping.launch", 1) == []


def test_dynamic_names_are_skipped_not_guessed(lint_text: Any) -> None:
    source = """<launch>
  <arg name="robot_name"/>
  <group ns="$(arg robot_name)">
    <node name="$(anon driver)" pkg="robot_base" type="driver_node">
      <remap from="cmd_vel" to="$(env ROBOT_PREFIX)/cmd_vel"/>
    </node>
  </group>
</launch>
"""
    assert lint_text(source, "robot.launch", 1) == []


def test_arg_defaults_are_substituted(lint_text: Any) -> None:
    source = """<launch>
  <arg name="robot_name" default="Robot-1"/>
  <group ns="$(arg robot_name)">
    <node name="driver" pkg="robot_base" type="driver_node"/>
  </group>
</launch>
"""
    assert lint_text(source, "robot.launch", 1) == ["RN101"]


def test_illegal_name_is_reported_once_under_its_most_specific_code(lint_text: Any) -> None:
    source = (
        '<launch>\n  <node pkg="a" exec="b" name="Base-Driver" namespace="Robot1/"/>\n</launch>\n'
    )
    assert lint_text(source, "robot.launch.xml", 2) == ["RN101", "RN102"]


def test_max_depth_option(lint_text: Any) -> None:
    source = '<launch>\n  <remap from="scan" to="a/b/c/d/e"/>\n</launch>\n'
    assert lint_text(source, "deep.launch", 1) == ["RN201"]
    assert lint_text(source, "deep.launch", 1, "--max-depth", "5") == []


def test_ros1_frame_leading_slash_is_a_warning_ros2_an_error(run_cli: Any, tmp_path: Any) -> None:
    launch = """<launch>
  <node pkg="robot_localization" exec="ekf_node" name="ekf">
    <param name="frame_id" value="/map"/>
  </node>
</launch>
"""
    write(tmp_path, "ros2/launch/a.launch.xml", launch)
    write_package(tmp_path / "ros2", 2)
    write(
        tmp_path,
        "ros1/launch/a.launch",
        launch.replace('exec="ekf_node"', 'type="ekf_localization_node"'),
    )
    write_package(tmp_path / "ros1", 1)
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    assert [(f["path"], f["code"], f["severity"]) for f in result.findings()] == [
        ("ros1/launch/a.launch", "RN205", "warning"),
        ("ros2/launch/a.launch.xml", "RN205", "error"),
    ]


SRV_SERVER = """#include <rclcpp/rclcpp.hpp>
#include <std_srvs/srv/trigger.hpp>

class Dock : public rclcpp::Node
{
public:
  Dock() : Node("dock")
  {
    service_ = create_service<std_srvs::srv::Trigger>(
      "start_docking",
      [](const std::shared_ptr<std_srvs::srv::Trigger::Request>,
         std::shared_ptr<std_srvs::srv::Trigger::Response> response) { response->success = true; });
  }

private:
  rclcpp::Service<std_srvs::srv::Trigger>::SharedPtr service_;
};
"""


def test_rn204_sees_the_workspace_srv_files(run_cli: Any, tmp_path: Any) -> None:
    write(tmp_path, "src/dock/src/dock.cpp", SRV_SERVER)
    write_package(tmp_path / "src" / "dock", 2, name="dock")
    result = run_cli(["check", "--format", "json", "src"], tmp_path)
    assert result.codes() == []
    write(tmp_path, "src/docking_msgs/srv/StartDocking.srv", "---\nbool success\n")
    write_package(tmp_path / "src" / "docking_msgs", 2, name="docking_msgs")
    # Only once dock depends on docking_msgs can its service be named after that type.
    manifest = tmp_path / "src" / "dock" / "package.xml"
    manifest.write_text(
        manifest.read_text(encoding="utf-8").replace(
            "</license>", "</license>\n  <depend>docking_msgs</depend>"
        ),
        encoding="utf-8",
    )
    result = run_cli(["check", "--format", "json", "src"], tmp_path)
    assert [(f["code"], f["path"]) for f in result.findings()] == [
        ("RN204", "src/dock/src/dock.cpp")
    ]
    assert "named after docking_msgs/StartDocking" in result.findings()[0]["message"]


ROS1_TUTORIAL = """#include <ros/ros.h>
#include <roscpp_tutorials/TwoInts.h>

bool add(roscpp_tutorials::TwoInts::Request& req, roscpp_tutorials::TwoInts::Response& res)
{
  res.sum = req.a + req.b;
  return true;
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "add_two_ints_server");
  ros::NodeHandle n;
  ros::ServiceServer service = n.advertiseService("add_two_ints", add);
  ros::spin();
  return 0;
}
"""
ROS2_CLIENT = """import rclpy
from example_interfaces.srv import AddTwoInts


def main():
    rclpy.init()
    node = rclpy.create_node("add_two_ints_client")
    client = node.create_client(AddTwoInts, "add_two_ints")
    rclpy.spin(node)
"""


def test_rn204_run_types_stay_within_their_generation(run_cli: Any, tmp_path: Any) -> None:
    # Found over ros_tutorials + rclpy in one run: a ROS 2 file's AddTwoInts was held
    # against roscpp's ROS 1 tutorial, whose add_two_ints serves roscpp_tutorials/TwoInts.
    write(tmp_path, "ros1/add_two_ints_server.cpp", ROS1_TUTORIAL)
    write_package(tmp_path / "ros1", 1, name="roscpp_tutorials")
    write(tmp_path, "ros2/add_two_ints_client.py", ROS2_CLIENT)
    write_package(tmp_path / "ros2", 2, name="demo_nodes_py")
    write(tmp_path, "ros1_msgs/srv/EmptySrv.srv", "---\n")
    write_package(tmp_path / "ros1_msgs", 1, name="test_rospy")
    assert run_cli(["check", "--format", "json", "."], tmp_path).codes() == []


# navigation2's waypoint follower, reduced: it calls robot_localization's `fromLL` (a name
# robot_localization chose), reads the parameters of a plugin whose id the parameter file
# chose, declares its own parameters, and serves its own service.
WAYPOINT_FOLLOWER = """#include <memory>
#include <string>

#include "rclcpp/rclcpp.hpp"
#include "robot_localization/srv/from_ll.hpp"
#include "nav_msgs/msg/odometry.hpp"
#include "std_srvs/srv/trigger.hpp"

class WaypointFollower : public rclcpp::Node
{
public:
  WaypointFollower() : Node("waypoint_follower")
  {
    declare_parameter("loop_rate", 20);
    declare_parameter("SmoothPath.w_smooth", 0.3);
    declare_parameter("DECLARED", 1.0);
    double lookahead = get_parameter("FollowPath.lookaheadDist").as_double();
    from_ll_client_ = create_client<robot_localization::srv::FromLL>("fromLL");
    odom_sub_ = create_subscription<nav_msgs::msg::Odometry>(
      "odomFiltered", 10, [](nav_msgs::msg::Odometry::ConstSharedPtr) {});
    stop_service_ = create_service<std_srvs::srv::Trigger>(
      "SERVED", [](const std::shared_ptr<std_srvs::srv::Trigger::Request>,
                    std::shared_ptr<std_srvs::srv::Trigger::Response>) {});
  }

private:
  rclcpp::Client<robot_localization::srv::FromLL>::SharedPtr from_ll_client_;
  rclcpp::Subscription<nav_msgs::msg::Odometry>::SharedPtr odom_sub_;
  rclcpp::Service<std_srvs::srv::Trigger>::SharedPtr stop_service_;
};
"""


def test_style_rules_judge_names_where_they_are_chosen(lint_text: Any) -> None:
    """A client, a subscriber and a ROS 2 parameter read use names chosen elsewhere; a
    parameter's plugin-id prefix is chosen in the parameter file."""
    source = WAYPOINT_FOLLOWER.replace("DECLARED", "max_retries").replace("SERVED", "stop")
    assert lint_text(source, "src/waypoint_follower.cpp", 2) == []


def test_style_rules_still_judge_what_the_file_chooses(lint_text: Any) -> None:
    source = WAYPOINT_FOLLOWER.replace("DECLARED", "SmoothPath.wCurve")
    source = source.replace("SERVED", "StopFollowing")
    assert lint_text(source, "src/waypoint_follower.cpp", 2) == ["RN203", "RN204"]


def test_a_client_of_a_service_spelled_as_a_type_is_not_told_to_rename_it(
    lint_text: Any,
) -> None:
    source = """import rospy
from gazebo_msgs.srv import SetModelState

rospy.init_node("teleporter")
rospy.wait_for_service("/gazebo/SetModelState")
set_state = rospy.ServiceProxy("/gazebo/SetModelState", SetModelState)
"""
    # RN202 (absolute) still applies: the client wrote the absolute form itself, twice,
    # which is one decision (``decisions``).
    assert lint_text(source, "scripts/teleporter.py", 1) == ["RN202"]


# A teleop bringup: the keyboard branch is off unless `keyboard:=true` is passed, so a run
# under the defaults never starts it; its mistakes still wait there for the first user who
# turns it on.
TELEOP_ROS1 = """<launch>
  <arg name="keyboard" default="false"/>
  <arg name="joy_dev" default="/dev/input/js0"/>

  <node pkg="joy" type="joy_node" name="joy_node">
    <param name="dev" value="$(arg joy_dev)"/>
  </node>

  <group if="$(arg keyboard)">
    <node pkg="teleop_twist_keyboard" type="teleop_twist_keyboard.py" name="teleopTwistKb"/>
    <group ns="drive//kb_teleop">
      <node pkg="teleop_twist_keyboard" type="teleop_twist_keyboard.py" name="kb teleop"/>
    </group>
  </group>
  <node pkg="joy" type="joy_node" name="joy_node" if="$(arg keyboard)">
    <remap from="joy" to="kb/joy"/>
  </node>
</launch>
"""

TELEOP_ROS2_XML = """<launch>
  <arg name="keyboard" default="false"/>
  <node pkg="joy" exec="joy_node" name="joy_node"/>
  <group if="$(var keyboard)">
    <push-ros-namespace namespace="drive//kb_teleop"/>
    <node pkg="teleop_twist_keyboard" exec="teleop_twist_keyboard" name="teleopTwistKb"/>
    <node pkg="teleop_twist_keyboard" exec="teleop_twist_keyboard" name="kb teleop"/>
  </group>
</launch>
"""

TELEOP_ROS2_YAML = """launch:
- arg: {name: keyboard, default: 'false'}
- node: {pkg: joy, exec: joy_node, name: joy_node}
- group:
    if: $(var keyboard)
    children:
    - push-ros-namespace: {namespace: drive//kb_teleop}
    - node: {pkg: teleop_twist_keyboard, exec: teleop_twist_keyboard, name: teleopTwistKb}
    - node: {pkg: teleop_twist_keyboard, exec: teleop_twist_keyboard, name: kb teleop}
"""

TELEOP_ROS2_PY = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node, PushRosNamespace


def generate_launch_description():
    keyboard = LaunchConfiguration('use_keyboard')
    return LaunchDescription([
        DeclareLaunchArgument('use_keyboard', default_value='false'),
        Node(package='joy', executable='joy_node', name='joy_node'),
        GroupAction(
            condition=IfCondition(keyboard),
            actions=[
                PushRosNamespace('drive//kb_teleop'),
                Node(package='teleop_twist_keyboard', executable='teleop_twist_keyboard',
                     name='teleopTwistKb'),
            ],
        ),
        Node(package='teleop_twist_keyboard', executable='teleop_twist_keyboard',
             name='kb teleop', condition=IfCondition(keyboard)),
    ])
"""


def test_every_branch_of_a_launch_file_is_checked(lint_text: Any) -> None:
    # teleopTwistKb (RN203), drive//kb_teleop and 'kb teleop' (RN101), each in a branch
    # the defaults turn off.
    assert sorted(lint_text(TELEOP_ROS1, "launch/teleop.launch", 1)) == [
        "RN101",
        "RN101",
        "RN203",
    ]
    for source, file in (
        (TELEOP_ROS2_XML, "launch/teleop.launch.xml"),
        (TELEOP_ROS2_YAML, "launch/teleop.launch.yaml"),
        (TELEOP_ROS2_PY, "launch/teleop.launch.py"),
    ):
        assert sorted(lint_text(source, file, 2)) == ["RN101", "RN101", "RN203"], file


def test_graph_rules_see_only_the_branches_the_defaults_start(lint_text: Any) -> None:
    """Both joy_node starts are one node twice only with keyboard:=true; under the
    defaults the second is off, so RN402 stays quiet, and so does RN404 for its remap."""
    fixed = TELEOP_ROS1.replace('name="teleopTwistKb"', 'name="teleop_twist_kb"')
    fixed = fixed.replace('ns="drive//kb_teleop"', 'ns="drive/kb_teleop"')
    fixed = fixed.replace('name="kb teleop"', 'name="kb_teleop"')
    assert lint_text(fixed, "launch/teleop.launch", 1) == []
    on = fixed.replace(
        '<arg name="keyboard" default="false"/>', '<arg name="keyboard" default="true"/>'
    )
    assert lint_text(on, "launch/teleop.launch", 1) == ["RN402"]  # at the second start


def test_a_deep_name_is_reported_where_it_is_published(lint_text: Any) -> None:
    """RN201 is style too: the camera driver chose the depth, its subscriber cannot."""
    source = """import rclpy
from rclpy.node import Node
from sensor_msgs.msg import CompressedImage


class LaneDetector(Node):
    def __init__(self):
        super().__init__("lane_detector")
        self.create_subscription(
            CompressedImage, "sensing/camera/front/image/compressed", self.on_image, 1
        )
        self.debug = self.create_publisher(CompressedImage, "lanes/debug/front/overlay/image", 1)
"""
    assert lint_text(source, "lane_detector/detector.py", 2) == ["RN201"]

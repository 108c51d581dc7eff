"""Rule claims that hold against the ROS source (issue 27, cause 3): RN205 by use, RN204
within the file's dependencies, RN101 on a child NodeHandle's joined name, and empty
parameter defaults that mean "unset"."""

from __future__ import annotations

from typing import Any

from conftest import write, write_package

# moveit2's moveit_servo/launch/demo_joint_jog.launch.py, reduced: the static broadcaster
# is given '/world' and '/panda_link0', which tf2's setTransformImpl strips; the servo node
# is given a planning frame it looks transforms up with.
SERVO_LAUNCH = """import launch
import launch_ros
from launch_ros.actions import ComposableNodeContainer


def generate_launch_description():
    container = ComposableNodeContainer(
        name="moveit_servo_demo_container",
        namespace="/",
        package="rclcpp_components",
        executable="component_container_mt",
        composable_node_descriptions=[
            launch_ros.descriptions.ComposableNode(
                package="tf2_ros",
                plugin="tf2_ros::StaticTransformBroadcasterNode",
                name="static_tf2_broadcaster",
                parameters=[{"child_frame_id": "/panda_link0", "frame_id": "/world"}],
            ),
        ],
        output="screen",
    )
    servo_node = launch_ros.actions.Node(
        package="moveit_servo",
        executable="demo_joint_jog",
        parameters=[{"planning_frame": "/panda_link0"}],
        output="screen",
    )
    return launch.LaunchDescription([container, servo_node])
"""


def test_rn205_leaves_a_static_broadcasters_frames_alone(run_cli: Any, tmp_path: Any) -> None:
    write(tmp_path, "src/moveit_servo/launch/demo_joint_jog.launch.py", SERVO_LAUNCH)
    write_package(tmp_path / "src" / "moveit_servo", 2, name="moveit_servo")
    result = run_cli(["check", "--format", "json", "--select", "RN205", "src"], tmp_path)
    found = [(f["line"], f["message"]) for f in result.findings()]
    # Only the servo's planning frame: the node looks transforms up with it.
    assert [line for line, _ in found] == [25]
    assert "a lookup of it, or of a message stamped with it, fails" in found[0][1]
    assert result.exit_code == 1


ROS2_STATIC_XML = """<launch>
  <node pkg="tf2_ros" exec="static_transform_publisher" name="world_to_map">
    <param name="frame_id" value="/world"/>
    <param name="child_frame_id" value="/map"/>
  </node>
  <node pkg="robot_localization" exec="ekf_node" name="ekf_filter_node">
    <param name="world_frame" value="/odom"/>
    <param name="frame_id" value="/odom"/>
  </node>
</launch>
"""


def test_rn205_xml_broadcaster_frames_pass_other_nodes_frames_do_not(
    run_cli: Any, tmp_path: Any
) -> None:
    write(tmp_path, "launch/tf.launch.xml", ROS2_STATIC_XML)
    write_package(tmp_path, 2)
    result = run_cli(["check", "--format", "json", "--select", "RN205", "."], tmp_path)
    assert [(f["line"], f["severity"]) for f in result.findings()] == [
        (7, "error"),
        (8, "error"),
    ]


LOOKUP_NODE = """#include <rclcpp/rclcpp.hpp>
#include <sensor_msgs/msg/laser_scan.hpp>
#include <tf2_ros/buffer.h>

class ScanMonitor : public rclcpp::Node
{
public:
  ScanMonitor() : Node("scan_monitor"), buffer_(get_clock()) {}

  void check()
  {
    if (buffer_.canTransform("/map", "base_link", tf2::TimePointZero)) {
      auto t = buffer_.lookupTransform("/map", "base_link", tf2::TimePointZero);
    }
    sensor_msgs::msg::LaserScan scan;
    scan.header.frame_id = "/laser";
  }

private:
  tf2_ros::Buffer buffer_;
};
"""


def test_rn205_says_what_fails_at_each_use(run_cli: Any, tmp_path: Any) -> None:
    write(tmp_path, "src/monitor/src/scan_monitor.cpp", LOOKUP_NODE)
    write_package(tmp_path / "src" / "monitor", 2, name="monitor")
    result = run_cli(["check", "--format", "json", "--select", "RN205", "src"], tmp_path)
    messages = {f["line"]: f["message"] for f in result.findings()}
    assert sorted(messages) == [12, 13, 16]
    assert "canTransform returns false" in messages[12]
    assert "throw InvalidArgumentException" in messages[13]
    assert "a message stamped with it cannot be transformed" in messages[16]


ROS1_TF_BROADCASTER = """#!/usr/bin/env python
import rospy
import tf

if __name__ == "__main__":
    rospy.init_node("turtle_tf_broadcaster")
    broadcaster = tf.TransformBroadcaster()
    rate = rospy.Rate(10.0)
    while not rospy.is_shutdown():
        broadcaster.sendTransform((0.0, 2.0, 0.0), (0.0, 0.0, 0.0, 1.0),
                                  rospy.Time.now(), "/carrot1", "/turtle1")
        rate.sleep()
"""


def test_rn205_leaves_ros1_tf_send_transform_alone(run_cli: Any, tmp_path: Any) -> None:
    write(tmp_path, "src/turtle_tf/nodes/fixed_tf_broadcaster.py", ROS1_TF_BROADCASTER)
    write_package(tmp_path / "src" / "turtle_tf", 1, name="turtle_tf")
    result = run_cli(["check", "--format", "json", "--select", "RN205", "src"], tmp_path)
    assert result.findings() == []
    assert result.exit_code == 0


# autoware.core's behavior_velocity_planner node, reduced: it serves its plugin loader with
# autoware_internal_debug_msgs/String; the sibling motion_velocity_planner package defines
# LoadPlugin.srv, which the behavior planner's package.xml does not depend on.
PLUGIN_LOADER = """#include <rclcpp/rclcpp.hpp>
#include <autoware_internal_debug_msgs/srv/string.hpp>

class BehaviorVelocityPlannerNode : public rclcpp::Node
{
public:
  explicit BehaviorVelocityPlannerNode(const rclcpp::NodeOptions & node_options)
  : Node("behavior_velocity_planner_node", node_options)
  {
    srv_load_plugin_ = create_service<autoware_internal_debug_msgs::srv::String>(
      "~/service/load_plugin",
      [](const autoware_internal_debug_msgs::srv::String::Request::SharedPtr,
         autoware_internal_debug_msgs::srv::String::Response::SharedPtr) {});
  }

private:
  rclcpp::Service<autoware_internal_debug_msgs::srv::String>::SharedPtr srv_load_plugin_;
};
"""
PLANNER_PACKAGE = """<?xml version="1.0"?>
<package format="3">
  <name>{name}</name>
  <version>0.1.0</version>
  <description>The planner</description>
  <maintainer email="dev@example.com">Dev</maintainer>
  <license>Apache License 2.0</license>
  <buildtool_depend>ament_cmake_auto</buildtool_depend>
  <depend>autoware_internal_debug_msgs</depend>
  <depend>rclcpp</depend>{extra}
  <export><build_type>ament_cmake</build_type></export>
</package>
"""


def _plugin_workspace(tmp_path: Any, extra: str) -> None:
    planner = tmp_path / "planning" / "autoware_behavior_velocity_planner"
    write(planner, "src/node.cpp", PLUGIN_LOADER)
    write(
        planner,
        "package.xml",
        PLANNER_PACKAGE.format(name="autoware_behavior_velocity_planner", extra=extra),
    )
    sibling = tmp_path / "planning" / "autoware_motion_velocity_planner"
    write(sibling, "srv/LoadPlugin.srv", "string plugin_name\n---\n")
    write_package(sibling, 2, name="autoware_motion_velocity_planner")


def test_rn204_ignores_a_sibling_packages_srv_the_file_does_not_depend_on(
    run_cli: Any, tmp_path: Any
) -> None:
    _plugin_workspace(tmp_path, "")
    result = run_cli(["check", "--format", "json", "--select", "RN204", "planning"], tmp_path)
    assert result.findings() == []
    assert result.exit_code == 0


def test_rn204_compares_with_the_srv_of_a_dependency(run_cli: Any, tmp_path: Any) -> None:
    _plugin_workspace(tmp_path, "\n  <exec_depend>autoware_motion_velocity_planner</exec_depend>")
    result = run_cli(["check", "--format", "json", "--select", "RN204", "planning"], tmp_path)
    assert [f["code"] for f in result.findings()] == ["RN204"]
    assert (
        "named after autoware_motion_velocity_planner/LoadPlugin"
        in (result.findings()[0]["message"])
    )


def test_rn204_language_server_keeps_to_the_dependencies_too(tmp_path: Any) -> None:
    from roslint_names.config import load_settings
    from roslint_names.registry import load_registry
    from roslint_names.session import Session

    _plugin_workspace(tmp_path, "")
    registry = load_registry()
    session = Session(tmp_path, load_settings(None, tmp_path, registry), registry, None)
    session.load()
    path = tmp_path / "planning/autoware_behavior_velocity_planner/src/node.cpp"
    found = session.check(path, PLUGIN_LOADER) or []
    assert [d.code for d in found if d.code == "RN204"] == []


# ros_comm's test_roscpp/test/src/handles.cpp (nodeHandleNames), reduced: roscpp accepts
# the child handle "2" (it resolves "/internal_ns/2"); a child with a '-' throws whatever
# its parent (the test's own "illegal_name!!!" is in a try that reaches FAIL(): an expected
# failure, never reported, so another child stands for it here).
ROSCPP_HANDLES = """#include <gtest/gtest.h>
#include <ros/ros.h>

TEST(RoscppHandles, nodeHandleNames)
{
  ros::NodeHandle n2("internal_ns");
  EXPECT_STREQ(n2.resolveName("blah").c_str(), "/internal_ns/blah");

  ros::NodeHandle n3(n2, "2");
  EXPECT_STREQ(n3.resolveName("blah").c_str(), "/internal_ns/2/blah");
}

void makeArm(const ros::NodeHandle& parent)
{
  ros::NodeHandle joint(parent, "6dof");
  ros::NodeHandle gripper(parent, "gripper-left");
  ros::NodeHandle top("6dof");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_handles");
  return RUN_ALL_TESTS();
}
"""


def test_rn101_judges_a_child_handle_by_its_joined_name(run_cli: Any, tmp_path: Any) -> None:
    write(tmp_path, "src/handles_demo/src/handles.cpp", ROSCPP_HANDLES)
    write_package(tmp_path / "src" / "handles_demo", 1, name="handles_demo")
    result = run_cli(["check", "--format", "json", "--select", "RN101", "src"], tmp_path)
    found = [(f["line"], f["message"]) for f in result.findings()]
    # "2" and "6dof" under a parent (known or not) resolve to '/<ns>/2', '/<ns>/6dof':
    # legal. "gripper-left" is illegal in any join; "6dof" alone is a name roscpp's
    # NodeHandle(ns) validates by itself (names::validate: first character a letter).
    assert [line for line, _ in found] == [16, 17]
    assert found[0][1].startswith("namespace 'gripper-left' contains '-' at index 7")
    assert found[1][1].startswith("namespace '6dof' starts with a digit ('6') at index 0")


# velodyne_pointcloud/launch/transform_nodelet.launch (ROS 1): fixed_frame and
# target_frame default to "", which the transform nodelet reads as "use the sensor frame".
VELODYNE_TRANSFORM = """<!-- run velodyne_pointcloud/TransformNodelet in a nodelet manager -->
<launch>
  <arg name="model" default="" />
  <arg name="fixed_frame" default="" />
  <arg name="target_frame" default="" />
  <arg name="manager" default="velodyne_nodelet_manager" />
  <node pkg="nodelet" type="nodelet" name="$(arg manager)_transform"
        args="load velodyne_pointcloud/TransformNodelet $(arg manager)" >
    <param name="model" value="$(arg model)"/>
    <param name="fixed_frame" value="$(arg fixed_frame)"/>
    <param name="target_frame" value="$(arg target_frame)"/>
  </node>
</launch>
"""
EMPTY_LOOKUP = """#include <rclcpp/rclcpp.hpp>
#include <tf2_ros/buffer.h>

class Projector : public rclcpp::Node
{
public:
  Projector() : Node("projector"), buffer_(get_clock()) {}

  void project()
  {
    auto t = buffer_.lookupTransform("", "velodyne", tf2::TimePointZero);
  }

private:
  tf2_ros::Buffer buffer_;
};
"""


def test_rn101_an_empty_frame_parameter_is_unset_not_illegal(run_cli: Any, tmp_path: Any) -> None:
    write(tmp_path, "velodyne_pointcloud/launch/transform_nodelet.launch", VELODYNE_TRANSFORM)
    write_package(tmp_path / "velodyne_pointcloud", 1, name="velodyne_pointcloud")
    ros2_params = VELODYNE_TRANSFORM.replace('type="nodelet"', 'exec="velodyne_transform_node"')
    write(tmp_path, "ros2_driver/launch/transform.launch.xml", ros2_params)
    write_package(tmp_path / "ros2_driver", 2, name="ros2_driver")
    result = run_cli(["check", "--format", "json", "--select", "RN101", "."], tmp_path)
    assert result.findings() == []
    assert result.exit_code == 0


def test_rn101_an_empty_frame_handed_to_tf2_is_still_reported(run_cli: Any, tmp_path: Any) -> None:
    write(tmp_path, "src/projector/src/projector.cpp", EMPTY_LOOKUP)
    write_package(tmp_path / "src" / "projector", 2, name="projector")
    result = run_cli(["check", "--format", "json", "--select", "RN101", "src"], tmp_path)
    assert [(f["line"], f["code"]) for f in result.findings()] == [(11, "RN101")]
    assert "must not be empty" in result.findings()[0]["message"]


# ros2/geometry2's tf2_ros/src/static_transform_broadcaster_node.cpp, reduced: the frame
# parameters' defaults are only ever sent through a StaticTransformBroadcaster.
STATIC_BROADCASTER_NODE = """#include <memory>
#include <string>

#include "tf2_ros/static_transform_broadcaster_node.hpp"
#include "rclcpp/rclcpp.hpp"

namespace tf2_ros
{
StaticTransformBroadcasterNode::StaticTransformBroadcasterNode(const rclcpp::NodeOptions & options)
: rclcpp::Node("static_transform_publisher", options)
{
  geometry_msgs::msg::TransformStamped tf_msg;
  tf_msg.header.stamp = this->now();
  tf_msg.transform.translation.x = this->declare_parameter("translation.x", 0.0);
  tf_msg.transform.rotation.w = this->declare_parameter("rotation.w", 1.0);
  tf_msg.header.frame_id =
    this->declare_parameter("frame_id", std::string("/frame"));
  tf_msg.child_frame_id =
    this->declare_parameter("child_frame_id", std::string("/child"));
  broadcaster_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>(this);
  broadcaster_->sendTransform(tf_msg);
}
}  // namespace tf2_ros
"""

# An odometry node: the same broadcast, and an odometry message stamped with the frame.
ODOMETRY_NODE = """#include <memory>
#include <string>

#include "nav_msgs/msg/odometry.hpp"
#include "rclcpp/rclcpp.hpp"
#include "tf2_ros/transform_broadcaster.h"

class Odometry : public rclcpp::Node
{
public:
  Odometry()
  : Node("odometry")
  {
    frame_id_ = declare_parameter("odom_frame", std::string("/odom"));
    publisher_ = create_publisher<nav_msgs::msg::Odometry>("odom", 10);
    broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>(*this);
  }

private:
  std::string frame_id_;
  rclcpp::Publisher<nav_msgs::msg::Odometry>::SharedPtr publisher_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> broadcaster_;
};
"""

# A follower: broadcasts its carrot, and looks the leader up in a tf2 buffer.
FOLLOWER_NODE = """#include <memory>
#include <string>

#include "rclcpp/rclcpp.hpp"
#include "tf2_ros/buffer.h"
#include "tf2_ros/transform_broadcaster.h"
#include "tf2_ros/transform_listener.h"

class Follower : public rclcpp::Node
{
public:
  Follower()
  : Node("follower"), buffer_(get_clock()), listener_(buffer_), broadcaster_(this)
  {
    carrot_ = declare_parameter("carrot_frame", std::string("/carrot"));
  }

private:
  std::string carrot_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
  tf2_ros::TransformBroadcaster broadcaster_;
};
"""


def test_rn205_leaves_the_frames_of_code_that_only_broadcasts_alone(
    run_cli: Any, tmp_path: Any
) -> None:
    write(
        tmp_path, "src/tf2_ros/src/static_transform_broadcaster_node.cpp", STATIC_BROADCASTER_NODE
    )
    write(tmp_path, "src/robot_base/src/odometry.cpp", ODOMETRY_NODE)
    write(tmp_path, "src/robot_base/src/follower.cpp", FOLLOWER_NODE)
    write_package(tmp_path / "src" / "tf2_ros", 2, name="tf2_ros")
    write_package(tmp_path / "src" / "robot_base", 2, name="robot_base")
    result = run_cli(["check", "--format", "json", "--select", "RN205", "src"], tmp_path)
    assert [(f["path"], f["line"]) for f in result.findings()] == [
        ("src/robot_base/src/follower.cpp", 15),
        ("src/robot_base/src/odometry.cpp", 14),
    ]


# slam_toolbox's merge_maps_kinematic.cpp, reduced: a node that publishes maps and
# broadcasts where each submap sits, the transforms filled field by field.
MAP_MERGER_NODE = """#include <memory>
#include <string>

#include "geometry_msgs/msg/transform_stamped.hpp"
#include "nav_msgs/msg/occupancy_grid.hpp"
#include "rclcpp/rclcpp.hpp"
#include "tf2_ros/transform_broadcaster.h"

class MergeMaps : public rclcpp::Node
{
public:
  MergeMaps()
  : Node("map_merging")
  {
    map_pub_ = create_publisher<nav_msgs::msg::OccupancyGrid>("map", 1);
    broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>(*this);
  }

  void addSubmap(int id)
  {
    geometry_msgs::msg::TransformStamped msg;
    msg.child_frame_id = "/map_" + std::to_string(id);
    msg.header.frame_id = "/map";
    msg.header.stamp = now();
    broadcaster_->sendTransform(msg);
  }

  void publishMap(nav_msgs::msg::OccupancyGrid & grid)
  {
    grid.header.frame_id = "/map";
    map_pub_->publish(grid);
  }

private:
  rclcpp::Publisher<nav_msgs::msg::OccupancyGrid>::SharedPtr map_pub_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> broadcaster_;
};
"""


def test_rn205_leaves_a_transform_handed_to_send_transform_alone(
    run_cli: Any, tmp_path: Any
) -> None:
    """tf2 strips the slash of a transform it stores (``BufferCore::setTransformImpl``):
    the frames set on the message the function hands to ``sendTransform`` work; the same
    frame stamped on a published map does not (rviz looks the header's frame up)."""
    write(tmp_path, "src/map_merging/src/merge_maps.cpp", MAP_MERGER_NODE)
    write_package(tmp_path / "src" / "map_merging", 2, name="map_merging")
    result = run_cli(["check", "--format", "json", "--select", "RN205", "src"], tmp_path)
    assert [(f["path"], f["line"]) for f in result.findings()] == [
        ("src/map_merging/src/merge_maps.cpp", 30),
    ]

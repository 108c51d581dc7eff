"""The workspace model end to end: launch trees, executables, resolution, graph rules.

Each test writes a small but realistic workspace (packages with package.xml, build
files, launch files and nodes) and runs the real CLI over it.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

from conftest import AMENT_PACKAGE, CATKIN_PACKAGE, write

# ---------------------------------------------------------------------------------------
# A ROS 1 workspace: one base launch file for a robot, included per robot


SMOOTHER_CPP = """\
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

class VelocitySmoother
{
public:
  VelocitySmoother()
  {
    ros::NodeHandle nh;
    raw_sub_ = nh.subscribe("cmd_vel", 10, &VelocitySmoother::onCommand, this);
    smooth_pub_ = nh.advertise<geometry_msgs::Twist>("cmd_vel_smooth", 10);
  }

private:
  void onCommand(const geometry_msgs::Twist::ConstPtr& msg) { smooth_pub_.publish(*msg); }
  ros::Subscriber raw_sub_;
  ros::Publisher smooth_pub_;
};

int main(int argc, char** argv)
{
  ros::init(argc, argv, "velocity_smoother");
  VelocitySmoother smoother;
  ros::spin();
  return 0;
}
"""

BATTERY_CPP = """\
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "battery_monitor");
  ros::NodeHandle nh;
  ros::Publisher low_pub = nh.advertise<sensor_msgs::BatteryState>("battery/low", 1, true);
  ros::spin();
  return 0;
}
"""

ALARM_PY = """\
#!/usr/bin/env python
import rospy
from std_msgs.msg import Bool


def on_low(msg):
    rospy.logwarn("battery low: %s", msg.data)


def main():
    rospy.init_node("low_battery_alarm")
    rospy.Subscriber("battery/low", Bool, on_low)
    rospy.spin()


if __name__ == "__main__":
    main()
"""

CMAKE_ROS1 = """\
cmake_minimum_required(VERSION 3.0.2)
project(turtle_base)
find_package(catkin REQUIRED COMPONENTS roscpp geometry_msgs sensor_msgs)
catkin_package()
include_directories(${catkin_INCLUDE_DIRS})

add_executable(velocity_smoother src/velocity_smoother.cpp)
target_link_libraries(velocity_smoother ${catkin_LIBRARIES})

add_executable(${PROJECT_NAME}_battery src/battery_monitor.cpp)
target_link_libraries(${PROJECT_NAME}_battery ${catkin_LIBRARIES})

catkin_install_python(PROGRAMS scripts/low_battery_alarm.py
  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
"""

BASE_LAUNCH = """\
<launch>
  <arg name="smoother_name" default="velocity_smoother"/>
  <node name="$(arg smoother_name)" pkg="turtle_base" type="velocity_smoother"/>
  <node name="battery_monitor" pkg="turtle_base" type="turtle_base_battery"/>
</launch>
"""


def ros1_workspace(root: Path) -> None:
    write(root, "src/turtle_base/package.xml", CATKIN_PACKAGE.format(name="turtle_base"))
    write(root, "src/turtle_base/CMakeLists.txt", CMAKE_ROS1)
    write(root, "src/turtle_base/src/velocity_smoother.cpp", SMOOTHER_CPP)
    write(root, "src/turtle_base/src/battery_monitor.cpp", BATTERY_CPP)
    write(root, "src/turtle_base/scripts/low_battery_alarm.py", ALARM_PY)
    write(root, "src/turtle_base/launch/base.launch", BASE_LAUNCH)


def graph_of(run_cli: Any, root: Path, *paths: str) -> dict[str, Any]:
    result = run_cli(["graph", "--format", "json", *(paths or ["."])], root)
    assert result.exit_code == 0, result.stderr
    graph: dict[str, Any] = json.loads(result.stdout)
    return graph


def node_names(graph: dict[str, Any]) -> list[str]:
    return sorted(node["name"] for node in graph["nodes"])


def findings(
    run_cli: Any, root: Path, *arguments: str, select: str = "RN4"
) -> list[dict[str, Any]]:
    result = run_cli(["check", "--format", "json", "--select", select, *arguments], root)
    assert result.exit_code in (0, 1), result.stderr
    found: list[dict[str, Any]] = result.findings()
    return found


def test_the_same_file_included_for_two_robots_is_neither_a_collision_nor_a_duplicate(
    run_cli: Any, tmp_path: Path
) -> None:
    ros1_workspace(tmp_path)
    write(
        tmp_path,
        "src/turtle_base/launch/robots.launch",
        "<launch>\n"
        '  <include file="$(find turtle_base)/launch/base.launch" ns="robot1"/>\n'
        '  <include file="$(find turtle_base)/launch/base.launch" ns="robot2"/>\n'
        "</launch>\n",
    )
    graph = graph_of(run_cli, tmp_path)
    launched = [n["name"] for n in graph["nodes"] if n["launched_at"]]
    assert sorted(launched) == [
        "/robot1/battery_monitor",
        "/robot1/velocity_smoother",
        "/robot2/battery_monitor",
        "/robot2/velocity_smoother",
    ]
    topics = {topic["name"] for topic in graph["topics"]}
    assert {"/robot1/cmd_vel", "/robot2/cmd_vel_smooth", "/robot2/battery/low"} <= topics
    assert [f["code"] for f in findings(run_cli, tmp_path, ".")] == []


def test_a_copied_include_starts_the_same_nodes_twice(run_cli: Any, tmp_path: Path) -> None:
    ros1_workspace(tmp_path)
    write(
        tmp_path,
        "src/turtle_base/launch/robots.launch",
        "<launch>\n"
        '  <include file="$(find turtle_base)/launch/base.launch" ns="robot1"/>\n'
        '  <include file="$(find turtle_base)/launch/base.launch" ns="robot1"/>\n'
        "</launch>\n",
    )
    found = findings(run_cli, tmp_path, ".")
    # Once, at the copy, the include copied named beside it: one namespace to change.
    assert [(f["code"], f["path"], f["line"]) for f in found] == [
        ("RN402", "src/turtle_base/launch/robots.launch", 3),
    ]
    assert [related["line"] for related in found[0]["related"]] == [2]


def test_two_node_tags_with_one_name_in_one_group(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "src/bringup/package.xml", CATKIN_PACKAGE.format(name="bringup"))
    write(
        tmp_path,
        "src/bringup/launch/sensors.launch",
        "<launch>\n"
        '  <group ns="front">\n'
        '    <node name="lidar" pkg="urg_node" type="urg_node"/>\n'
        "  </group>\n"
        '  <node name="lidar" pkg="urg_node" type="urg_node" ns="front"/>\n'
        '  <node name="lidar" pkg="urg_node" type="urg_node" ns="rear"/>\n'
        "</launch>\n",
    )
    found = findings(run_cli, tmp_path, ".")
    assert [(f["code"], f["line"]) for f in found] == [("RN402", 5)]  # the second start
    assert "'/front/lidar'" in found[0]["message"]
    assert [related["line"] for related in found[0]["related"]] == [3]


# launch_ros' test_track_node_names.py, reduced: each test function launches its own
# description, so the two nodes named /my_namespace/my_node never run together.
TRACK_NODE_NAMES = """import asyncio

from launch import LaunchDescription, LaunchService
from launch_ros.actions import Node

TEST_NODE_NAME = 'my_node'
TEST_NODE_NAMESPACE = '/my_namespace'


def _launch(launch_description):
    ls = LaunchService()
    ls.include_launch_description(launch_description)
    loop = asyncio.get_event_loop()
    loop.run_until_complete(asyncio.wait_for(ls.run_async(), 5))
    return ls.context


def test_launch_node_with_name():
    node = Node(package='demo_nodes_py', executable='listener_qos',
                name=TEST_NODE_NAME, namespace=TEST_NODE_NAMESPACE)
    _launch(LaunchDescription([node]))


def test_launch_node_with_name_twice():
    node = Node(package='demo_nodes_py', executable='listener_qos',
                name=TEST_NODE_NAME, namespace=TEST_NODE_NAMESPACE)
    _launch(LaunchDescription([node]))
"""


def test_descriptions_built_apart_are_not_one_launch(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "src/launch_checks/package.xml", AMENT_PACKAGE.format(name="launch_checks"))
    write(tmp_path, "src/launch_checks/launch_checks/track_node_names.py", TRACK_NODE_NAMES)
    assert findings(run_cli, tmp_path, ".") == []
    # The same two nodes in one description are twins.
    one_launch = TRACK_NODE_NAMES + (
        "\n\ndef generate_launch_description():\n"
        "    return LaunchDescription([\n"
        "        Node(package='demo_nodes_py', executable='listener_qos',\n"
        "             name=TEST_NODE_NAME, namespace=TEST_NODE_NAMESPACE),\n"
        "        Node(package='demo_nodes_py', executable='talker',\n"
        "             name=TEST_NODE_NAME, namespace=TEST_NODE_NAMESPACE),\n"
        "    ])\n"
    )
    write(tmp_path, "src/launch_checks/launch/twins.launch.py", one_launch)
    assert [f["code"] for f in findings(run_cli, tmp_path, ".")] == ["RN402"]


def test_arguments_handed_to_an_include_rename_its_nodes(run_cli: Any, tmp_path: Path) -> None:
    ros1_workspace(tmp_path)
    write(
        tmp_path,
        "src/turtle_base/launch/robots.launch",
        "<launch>\n"
        '  <include file="$(find turtle_base)/launch/base.launch" ns="robot1">\n'
        '    <arg name="smoother_name" value="smoother"/>\n'
        "  </include>\n"
        "</launch>\n",
    )
    graph = graph_of(run_cli, tmp_path)
    assert "/robot1/smoother" in node_names(graph)
    assert "/robot1/velocity_smoother" not in node_names(graph)


def test_a_group_remap_reaches_the_included_nodes_and_is_not_judged_unused(
    run_cli: Any, tmp_path: Path
) -> None:
    ros1_workspace(tmp_path)
    write(
        tmp_path,
        "src/turtle_base/launch/robots.launch",
        "<launch>\n"
        '  <group ns="robot1">\n'
        '    <remap from="cmd_vel" to="mux/cmd_vel"/>\n'
        '    <include file="$(find turtle_base)/launch/base.launch"/>\n'
        "  </group>\n"
        "</launch>\n",
    )
    graph = graph_of(run_cli, tmp_path)
    subscribed = {
        edge["resource"]
        for edge in graph["edges"]
        if edge["node"] == "/robot1/velocity_smoother" and edge["edge"] == "subscribe"
    }
    assert subscribed == {"/robot1/mux/cmd_vel"}
    assert findings(run_cli, tmp_path, ".") == []


def test_types_that_disagree_on_one_resolved_topic(run_cli: Any, tmp_path: Path) -> None:
    ros1_workspace(tmp_path)
    write(
        tmp_path,
        "src/turtle_base/launch/robot.launch",
        "<launch>\n"
        '  <group ns="robot1">\n'
        '    <include file="$(find turtle_base)/launch/base.launch"/>\n'
        '    <node name="alarm" pkg="turtle_base" type="low_battery_alarm.py"/>\n'
        "  </group>\n"
        "</launch>\n",
    )
    found = findings(run_cli, tmp_path, ".")
    assert {(f["code"], f["path"]) for f in found} == {
        ("RN403", "src/turtle_base/src/battery_monitor.cpp"),
        ("RN403", "src/turtle_base/scripts/low_battery_alarm.py"),
    }
    message = next(f["message"] for f in found if f["path"].endswith(".py"))
    assert "'/robot1/battery/low'" in message
    assert "'std_msgs/Bool'" in message and "'sensor_msgs/BatteryState'" in message


def test_a_node_remap_its_code_never_uses(run_cli: Any, tmp_path: Path) -> None:
    ros1_workspace(tmp_path)
    write(
        tmp_path,
        "src/turtle_base/launch/smoother.launch",
        "<launch>\n"
        '  <node name="velocity_smoother" pkg="turtle_base" type="velocity_smoother">\n'
        '    <remap from="cmd_vel_raw" to="teleop/cmd_vel"/>\n'
        '    <remap from="cmd_vel_smooth" to="mobile_base/cmd_vel"/>\n'
        "  </node>\n"
        "</launch>\n",
    )
    # (the unlaunched alarm and battery monitor disagree on /battery/low: RN403, not here)
    found = findings(run_cli, tmp_path, ".", select="RN404")
    assert [(f["code"], f["line"]) for f in found] == [("RN404", 3)]
    assert "'/cmd_vel_raw'" in found[0]["message"]
    assert "'/cmd_vel'" in found[0]["message"]  # what the node does use


def test_an_illegal_name_is_a_known_use_ros1(run_cli: Any, tmp_path: Path) -> None:
    """RN101 reports 'cmd_vel-smooth'; it is still a name the node uses, so the other
    names are all known and the dead remap is found."""
    ros1_workspace(tmp_path)
    smoother = SMOOTHER_CPP.replace('"cmd_vel_smooth"', '"cmd_vel-smooth"')
    write(tmp_path, "src/turtle_base/src/velocity_smoother.cpp", smoother)
    write(
        tmp_path,
        "src/turtle_base/launch/smoother.launch",
        "<launch>\n"
        '  <node name="velocity_smoother" pkg="turtle_base" type="velocity_smoother">\n'
        '    <remap from="cmd_vel_raw" to="teleop/cmd_vel"/>\n'
        "  </node>\n"
        "</launch>\n",
    )
    found = findings(run_cli, tmp_path, ".", select="RN404")
    assert [(f["code"], f["path"], f["line"]) for f in found] == [
        ("RN404", "src/turtle_base/launch/smoother.launch", 3)
    ]
    assert "'/cmd_vel-smooth'" in found[0]["message"]  # among the names it does use


STATUS_NODE_CPP = """\
#include <memory>

#include "geometry_msgs/msg/twist.hpp"
#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

class BaseStatus : public rclcpp::Node
{
public:
  BaseStatus() : Node("base_status")
  {
    status_pub_ = create_publisher<std_msgs::msg::String>("status/", 10);
    cmd_sub_ = create_subscription<geometry_msgs::msg::Twist>(
      "cmd_vel", 10, [](geometry_msgs::msg::Twist::ConstSharedPtr) {});
  }

private:
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr status_pub_;
  rclcpp::Subscription<geometry_msgs::msg::Twist>::SharedPtr cmd_sub_;
};

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<BaseStatus>());
  rclcpp::shutdown();
}
"""


def test_an_illegal_name_is_a_known_use_ros2(run_cli: Any, tmp_path: Path) -> None:
    """'status/' fails in rcl (RN102), but the node's names are known: the 'odom' remap
    renames nothing, the 'status' one matches the name as spelled."""
    write(tmp_path, "src/base_status/package.xml", AMENT_PACKAGE.format(name="base_status"))
    write(
        tmp_path,
        "src/base_status/CMakeLists.txt",
        "cmake_minimum_required(VERSION 3.8)\nproject(base_status)\n"
        "find_package(ament_cmake REQUIRED)\nfind_package(rclcpp REQUIRED)\n"
        "add_executable(base_status src/base_status.cpp)\nament_package()\n",
    )
    write(tmp_path, "src/base_status/src/base_status.cpp", STATUS_NODE_CPP)
    write(
        tmp_path,
        "src/base_status/launch/base.launch.xml",
        "<launch>\n"
        '  <node pkg="base_status" exec="base_status" name="base_status">\n'
        '    <remap from="odom" to="/robot/odom"/>\n'
        '    <remap from="status" to="/robot/status"/>\n'
        "  </node>\n"
        "</launch>\n",
    )
    found = findings(run_cli, tmp_path, ".", select="RN404")
    assert [(f["code"], f["path"], f["line"]) for f in found] == [
        ("RN404", "src/base_status/launch/base.launch.xml", 3)
    ]


# image_pipeline's image_publisher, reduced: image_transport derives camera_info beside the
# image topic it is handed, a name no code of the node spells.
IMAGE_PUBLISHER_CPP = """\
#include <string>

#include "image_transport/image_transport.hpp"
#include "rclcpp/rclcpp.hpp"

class ImagePublisher : public rclcpp::Node
{
public:
  ImagePublisher() : rclcpp::Node("image_publisher")
  {
    auto node_base = this->get_node_base_interface();
    std::string topic_name = node_base->resolve_topic_or_service_name("image_raw", false);
    pub_ = image_transport::create_camera_publisher(this, topic_name);
    camera_info_url_ = declare_parameter("camera_info_url", std::string(""));
    frame_id_ = declare_parameter("frame_id", std::string("camera"));
    timer_ = create_wall_timer(std::chrono::milliseconds(100), [] {});
  }

private:
  image_transport::CameraPublisher pub_;
  std::string camera_info_url_;
  std::string frame_id_;
  rclcpp::TimerBase::SharedPtr timer_;
};
"""


def test_camera_info_beside_an_image_topic_is_a_used_remap(run_cli: Any, tmp_path: Path) -> None:
    package = "src/image_publisher"
    write(tmp_path, f"{package}/package.xml", AMENT_PACKAGE.format(name="image_publisher"))
    write(
        tmp_path,
        f"{package}/CMakeLists.txt",
        "cmake_minimum_required(VERSION 3.8)\nproject(image_publisher)\n"
        "find_package(ament_cmake REQUIRED)\n"
        "add_executable(image_publisher_node src/image_publisher.cpp)\nament_package()\n",
    )
    write(tmp_path, f"{package}/src/image_publisher.cpp", IMAGE_PUBLISHER_CPP)
    write(
        tmp_path,
        f"{package}/launch/image_publisher.launch.py",
        "import launch\nimport launch_ros.actions\n\n\n"
        "def generate_launch_description():\n"
        "    return launch.LaunchDescription([\n"
        "        launch_ros.actions.Node(\n"
        "            package='image_publisher', executable='image_publisher_node',\n"
        "            remappings=[('image_raw', '/camera/image_raw'),\n"
        "                        ('camera_info', '/camera/camera_info'),\n"
        "                        ('camera_inf', '/camera/info')]),\n"
        "    ])\n",
    )
    found = findings(run_cli, tmp_path, ".", select="RN404")
    assert [(f["line"], f["message"].split(" renames")[0]) for f in found] == [
        (11, "remap from '/camera_inf'")
    ]


def test_a_per_file_run_sees_the_workspace_but_reports_only_its_files(
    run_cli: Any, tmp_path: Path
) -> None:
    ros1_workspace(tmp_path)
    write(
        tmp_path,
        "src/turtle_base/launch/robot.launch",
        "<launch>\n"
        '  <include file="$(find turtle_base)/launch/base.launch"/>\n'
        '  <node name="alarm" pkg="turtle_base" type="low_battery_alarm.py"/>\n'
        "</launch>\n",
    )
    alarm = "src/turtle_base/scripts/low_battery_alarm.py"
    found = findings(run_cli, tmp_path, alarm)
    assert [(f["code"], f["path"]) for f in found] == [("RN403", alarm)]
    assert found[0]["related"][0]["path"] == "src/turtle_base/src/battery_monitor.cpp"


def test_a_graph_finding_is_suppressed_like_any_other(run_cli: Any, tmp_path: Path) -> None:
    ros1_workspace(tmp_path)
    write(
        tmp_path,
        "src/turtle_base/launch/smoother.launch",
        "<launch>\n"
        '  <node name="velocity_smoother" pkg="turtle_base" type="velocity_smoother">\n'
        "    <!-- roslint-names: ignore RN404 (the next release renames the topic) -->\n"
        '    <remap from="cmd_vel_raw" to="teleop/cmd_vel"/>\n'
        "  </node>\n"
        "</launch>\n",
    )
    result = run_cli(["check", "--format", "json", "--select", "RN404,RN002", "."], tmp_path)
    assert result.exit_code == 0, result.stdout
    assert result.codes() == []


# ---------------------------------------------------------------------------------------
# ROS 2: Python launch with GroupAction + PushRosNamespace, setup.py console_scripts

REPORTER_PY = """\
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import BatteryState


class BatteryReporter(Node):
    def __init__(self):
        super().__init__("battery_reporter")
        self.state_pub = self.create_publisher(BatteryState, "battery_state", 10)


def main():
    rclpy.init()
    rclpy.spin(BatteryReporter())
"""

SETUP_PY = """\
from setuptools import setup

package_name = "fleet_nodes"

setup(
    name=package_name,
    version="0.1.0",
    packages=[package_name],
    entry_points={
        "console_scripts": [
            f"battery_reporter = {package_name}.battery_reporter:main",
        ],
    },
)
"""

ROBOT_LAUNCH_PY = """\
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package="fleet_nodes", executable="battery_reporter", name="battery"),
    ])
"""

FLEET_LAUNCH_PY = """\
from launch import LaunchDescription
from launch.actions import GroupAction, IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import PathJoinSubstitution
from launch_ros.actions import PushRosNamespace
from launch_ros.substitutions import FindPackageShare


def robot(namespace):
    return GroupAction([
        PushRosNamespace(namespace),
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource(
                PathJoinSubstitution([FindPackageShare("fleet_nodes"), "launch", "robot.launch.py"])
            )
        ),
    ])


def generate_launch_description():
    return LaunchDescription([robot("robot1"), robot("robot2")])
"""


def ros2_workspace(root: Path) -> None:
    write(root, "src/fleet_nodes/package.xml", AMENT_PACKAGE.format(name="fleet_nodes"))
    write(root, "src/fleet_nodes/setup.py", SETUP_PY)
    write(root, "src/fleet_nodes/fleet_nodes/__init__.py", "")
    write(root, "src/fleet_nodes/fleet_nodes/battery_reporter.py", REPORTER_PY)
    write(root, "src/fleet_nodes/launch/robot.launch.py", ROBOT_LAUNCH_PY)


def test_push_ros_namespace_inside_group_action_reaches_the_included_nodes(
    run_cli: Any, tmp_path: Path
) -> None:
    ros2_workspace(tmp_path)
    write(
        tmp_path,
        "src/fleet_nodes/launch/fleet.launch.py",
        FLEET_LAUNCH_PY.replace('robot("robot1"), robot("robot2")', 'robot("robot1")'),
    )
    graph = graph_of(run_cli, tmp_path)
    assert node_names(graph) == ["/robot1/battery"]
    (node,) = graph["nodes"]
    assert node["sources"] == ["src/fleet_nodes/fleet_nodes/battery_reporter.py"]
    assert [t["name"] for t in graph["topics"]] == ["/robot1/battery_state"]


def test_ros2_case_collision_between_cpp_and_python(run_cli: Any, tmp_path: Path) -> None:
    ros2_workspace(tmp_path)
    write(
        tmp_path,
        "src/fleet_nodes/src/dashboard.cpp",
        "#include <rclcpp/rclcpp.hpp>\n"
        "#include <sensor_msgs/msg/battery_state.hpp>\n"
        "class Dashboard : public rclcpp::Node {\n"
        " public:\n"
        '  Dashboard() : Node("dashboard") {\n'
        "    sub_ = create_subscription<sensor_msgs::msg::BatteryState>(\n"
        '        "Battery_State", 10, [](sensor_msgs::msg::BatteryState::SharedPtr) {});\n'
        "  }\n"
        "  rclcpp::Subscription<sensor_msgs::msg::BatteryState>::SharedPtr sub_;\n"
        "};\n",
    )
    found = findings(run_cli, tmp_path, ".")
    assert {(f["code"], f["path"]) for f in found} == {
        ("RN401", "src/fleet_nodes/fleet_nodes/battery_reporter.py"),
        ("RN401", "src/fleet_nodes/src/dashboard.cpp"),
    }
    for finding in found:
        assert len(finding["related"]) == 1


def test_a_name_pushed_too_deep_by_the_launch_file_is_blamed_on_the_launch_site(
    run_cli: Any, tmp_path: Path
) -> None:
    ros2_workspace(tmp_path)
    write(
        tmp_path,
        "src/fleet_nodes/launch/fleet.launch.py",
        FLEET_LAUNCH_PY.replace(
            'robot("robot1"), robot("robot2")', 'robot("site_a/warehouse/level_2/robot1")'
        ),
    )
    result = run_cli(["check", "--format", "json", "--select", "RN201", "."], tmp_path)
    found = result.findings()
    assert [(f["code"], f["path"]) for f in found] == [
        ("RN201", "src/fleet_nodes/launch/fleet.launch.py")
    ]
    assert "'/site_a/warehouse/level_2/robot1/battery_state'" in found[0]["message"]


def test_the_example_workspace_graph_renders_with_graphviz(run_cli: Any) -> None:
    import shutil
    import subprocess

    import pytest

    if shutil.which("dot") is None:
        pytest.skip("Graphviz `dot` is not installed (.ci/run installs it)")
    examples = Path(__file__).resolve().parent.parent / "examples"
    result = run_cli(["graph", "--format", "dot", "."], examples)
    assert result.exit_code == 0, result.stderr
    rendered = subprocess.run(
        ["dot", "-Tsvg"], input=result.stdout, capture_output=True, text=True, check=False
    )
    assert rendered.returncode == 0, rendered.stderr
    assert rendered.stderr == ""
    assert "/robot1/" in rendered.stdout


# ---------------------------------------------------------------------------------------
# False positives found on navigation2, turtlebot3 and ros_tutorials (each failed first)


def test_nodes_under_undecided_conditions_are_alternatives_not_duplicates(
    run_cli: Any, tmp_path: Path
) -> None:
    # nav2's launch files start map_server composed or standalone, on a run-time argument.
    write(tmp_path, "src/bringup/package.xml", CATKIN_PACKAGE.format(name="bringup"))
    write(
        tmp_path,
        "src/bringup/launch/map.launch",
        "<launch>\n"
        '  <node name="map_server" pkg="map_server" type="map_server"'
        ' if="$(optenv USE_COMPOSITION false)"/>\n'
        '  <node name="map_server" pkg="map_server" type="map_server"'
        ' unless="$(optenv USE_COMPOSITION false)"/>\n'
        "</launch>\n",
    )
    assert findings(run_cli, tmp_path, ".") == []


def test_aliases_and_run_time_choices_of_one_node_are_not_type_mismatches(
    run_cli: Any, tmp_path: Path
) -> None:
    write(tmp_path, "src/teleop/package.xml", AMENT_PACKAGE.format(name="teleop"))
    # turtlebot3's teleop publishes TwistStamped or Twist depending on ROS_DISTRO.
    write(
        tmp_path,
        "src/teleop/teleop/keyboard.py",
        "import os\n"
        "import rclpy\n"
        "from geometry_msgs.msg import Twist, TwistStamped\n\n\n"
        "def main():\n"
        "    rclpy.init()\n"
        '    node = rclpy.create_node("teleop_keyboard")\n'
        '    if os.environ["ROS_DISTRO"] == "humble":\n'
        '        pub = node.create_publisher(Twist, "cmd_vel", 10)\n'
        "    else:\n"
        '        pub = node.create_publisher(TwistStamped, "cmd_vel", 10)\n',
    )
    write(
        tmp_path,
        "src/teleop/teleop/patrol.py",
        "import rclpy\n"
        "from geometry_msgs.msg import Twist\n\n\n"
        "def main():\n"
        "    rclpy.init()\n"
        '    node = rclpy.create_node("patrol")\n'
        '    node.create_publisher(Twist, "cmd_vel", 10)\n',
    )
    # nav2's servers name their action type through an alias declared in a header.
    write(
        tmp_path,
        "src/teleop/src/follow_server.cpp",
        "#include <rclcpp/rclcpp.hpp>\n"
        "#include <rclcpp_action/rclcpp_action.hpp>\n"
        "class FollowServer : public rclcpp::Node {\n"
        " public:\n"
        '  FollowServer() : Node("follow_server") {\n'
        '    server_ = rclcpp_action::create_server<Action>(this, "follow_path",\n'
        "        nullptr, nullptr, nullptr);\n"
        "  }\n"
        "  rclcpp_action::Server<Action>::SharedPtr server_;\n"
        "};\n",
    )
    write(
        tmp_path,
        "src/teleop/teleop/commander.py",
        "import rclpy\n"
        "from nav2_msgs.action import FollowPath\n"
        "from rclpy.action import ActionClient\n\n\n"
        "def main():\n"
        "    rclpy.init()\n"
        '    node = rclpy.create_node("commander")\n'
        '    ActionClient(node, FollowPath, "follow_path")\n',
    )
    assert findings(run_cli, tmp_path, ".", select="RN403") == []


def test_remapping_tf_is_never_an_unused_remap(run_cli: Any, tmp_path: Path) -> None:
    # The multi-robot pattern of every nav2 launch file: the tf listener uses /tf.
    ros2_workspace(tmp_path)
    write(
        tmp_path,
        "src/fleet_nodes/launch/robot.launch.py",
        ROBOT_LAUNCH_PY.replace(
            'name="battery")',
            'name="battery", remappings=[("/tf", "tf"), ("/tf_static", "tf_static")])',
        ),
    )
    assert findings(run_cli, tmp_path, ".", select="RN404") == []


def test_verbose_counts_the_workspace_files_a_per_file_run_reads(
    run_cli: Any, tmp_path: Path, private_cache: Path
) -> None:
    # Found by hand: "5 of 1 files from the cache" in a per-file run.
    ros1_workspace(tmp_path)
    launch = "src/turtle_base/launch/base.launch"
    run_cli(["check", launch], tmp_path)
    result = run_cli(["check", "--verbose", launch], tmp_path)
    assert "a run over the same 5 files: its result reused" in result.stderr  # 4 + CMake
    for runs in private_cache.glob("facts-v*/runs"):
        shutil.rmtree(runs)  # the next run builds its result from the cached facts
    result = run_cli(["check", "--verbose", launch], tmp_path)
    assert "; 5 of 5 files from the cache, 0 extracted" in result.stderr


SENSORS_LAUNCH = """\
<launch>
  <arg name="robot" default="site_a/hall_b/robot1"/>
  <group ns="$(arg robot)">
    <node name="front_lidar" pkg="sick_scan" type="sick_generic_caller">
      <remap from="scan" to="sensors/front/scan"/>
    </node>
    <node name="velocity_smoother" pkg="turtle_base" type="velocity_smoother">
      <remap from="cmd_vel_smooth" to="base/smoothed/cmd_vel"/>
      <remap from="cmd_vel" to="teleop_cmd_vel"/>
    </node>
  </group>
</launch>
"""


def test_a_remap_target_pushed_too_deep_by_the_namespace_is_reported_at_the_remap(
    run_cli: Any, tmp_path: Path
) -> None:
    """The lidar driver's code is not in the workspace: only its remap says the name. The
    smoother's code is: its topic is reported once, at the remap that made it deep. The
    level each robot's copy differs in (robot1, robot2) is not counted: six levels, five
    judged."""
    ros1_workspace(tmp_path)
    write(tmp_path, "src/robot_bringup/package.xml", CATKIN_PACKAGE.format(name="robot_bringup"))
    write(tmp_path, "src/robot_bringup/launch/sensors.launch", SENSORS_LAUNCH)
    write(
        tmp_path,
        "src/robot_bringup/launch/fleet.launch",
        "<launch>\n"
        '  <include file="$(find robot_bringup)/launch/sensors.launch"/>\n'
        '  <include file="$(find robot_bringup)/launch/sensors.launch">\n'
        '    <arg name="robot" value="site_a/hall_b/robot2"/>\n'
        "  </include>\n"
        "</launch>\n",
    )
    found = findings(run_cli, tmp_path, ".", select="RN201")
    assert [(f["path"], f["line"]) for f in found] == [
        ("src/robot_bringup/launch/sensors.launch", 5),
        ("src/robot_bringup/launch/sensors.launch", 8),
    ]
    assert "'/site_a/hall_b/robot1/sensors/front/scan'" in found[0]["message"]
    assert "'/site_a/hall_b/robot1/base/smoothed/cmd_vel'" in found[1]["message"]
    assert all(f["message"].endswith("(and in 1 more launch)") for f in found)  # robot2

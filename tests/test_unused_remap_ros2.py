"""RN404 and ROS 2 parameters (issue 27, cause 7).

rcl remaps topic and service names and the node's name and namespace, never parameters:
a ROS 2 parameter name built at run time hides no remap, and a remap of a parameter
renames nothing. In ROS 1 remaps do apply to parameters.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import AMENT_PACKAGE, CATKIN_PACKAGE, write


def findings(run_cli: Any, root: Path) -> list[dict[str, Any]]:
    result = run_cli(["check", "--format", "json", "--select", "RN404", "."], root)
    assert result.exit_code in (0, 1), result.stderr
    found: list[dict[str, Any]] = result.findings()
    return found


def places(found: list[dict[str, Any]]) -> list[tuple[str, int]]:
    return sorted((f["path"], f["line"]) for f in found)


# nav2's planner server pattern, reduced: each plugin's parameters are declared under the
# plugin's name, known only at run time.
PLANNER_SERVER_CPP = """\
#include <string>
#include <vector>

#include "nav_msgs/msg/path.hpp"
#include "rclcpp/rclcpp.hpp"

class PlannerServer : public rclcpp::Node
{
public:
  PlannerServer() : rclcpp::Node("planner_server")
  {
    declare_parameter("planner_plugins", std::vector<std::string>{"GridBased"});
    for (const auto & id : get_parameter("planner_plugins").as_string_array()) {
      declare_parameter(id + ".plugin", std::string("nav2_navfn_planner::NavfnPlanner"));
    }
    plan_publisher_ = create_publisher<nav_msgs::msg::Path>("plan", 1);
  }

private:
  rclcpp::Publisher<nav_msgs::msg::Path>::SharedPtr plan_publisher_;
};
"""

PLANNER_LAUNCH_PY = """\
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(
            package='nav2_planner',
            executable='planner_server',
            name='planner_server',
            remappings=[('/tf', 'tf'), ('plans', 'global_plan')],
        ),
    ])
"""


def planner_workspace(root: Path) -> str:
    package = "src/nav2_planner"
    write(root, f"{package}/package.xml", AMENT_PACKAGE.format(name="nav2_planner"))
    write(
        root,
        f"{package}/CMakeLists.txt",
        "cmake_minimum_required(VERSION 3.5)\nproject(nav2_planner)\n"
        "find_package(ament_cmake REQUIRED)\n"
        "add_executable(planner_server src/planner_server.cpp)\nament_package()\n",
    )
    write(root, f"{package}/src/planner_server.cpp", PLANNER_SERVER_CPP)
    launch = f"{package}/launch/planner.launch.py"
    write(root, launch, PLANNER_LAUNCH_PY)
    return launch


def test_a_dynamic_ros2_parameter_name_does_not_silence_unused_remaps(
    run_cli: Any, tmp_path: Path
) -> None:
    launch = planner_workspace(tmp_path)
    found = findings(run_cli, tmp_path)
    assert places(found) == [(launch, 11)]
    assert "remap from '/plans' renames nothing" in found[0]["message"]
    assert "'/plan'" in found[0]["message"]  # what it does use


def test_a_ros2_remap_of_a_parameter_says_that_rcl_never_remaps_parameters(
    run_cli: Any, tmp_path: Path
) -> None:
    # moveit2's generate_state_database.launch, a ROS 1 habit kept for ROS 2 code.
    launch = planner_workspace(tmp_path)
    write(
        tmp_path,
        launch,
        PLANNER_LAUNCH_PY.replace("('plans', 'global_plan')", "('~/planner_plugins', 'plugins')"),
    )
    found = findings(run_cli, tmp_path)
    assert places(found) == [(launch, 11)]
    assert "'planner_plugins' is a parameter of node '/planner_server'" in found[0]["message"]
    assert "never parameters" in found[0]["message"]


def test_a_dynamic_ros1_parameter_name_still_silences_the_node(
    run_cli: Any, tmp_path: Path
) -> None:
    # roscpp remaps parameter names too (names::resolve): one we cannot read may be the
    # remap's ``from``.
    package = "src/robot_driver"
    write(tmp_path, f"{package}/package.xml", CATKIN_PACKAGE.format(name="robot_driver"))
    write(
        tmp_path,
        f"{package}/src/driver.cpp",
        "#include <ros/ros.h>\n#include <std_msgs/Float64.h>\n\n"
        "int main(int argc, char** argv)\n{\n"
        '  ros::init(argc, argv, "driver");\n  ros::NodeHandle nh("~");\n'
        '  std::string joint = argc > 1 ? argv[1] : "wheel";\n  double gain = 1.0;\n'
        '  nh.getParam(joint + "/gain", gain);\n'
        '  ros::Publisher pub = nh.advertise<std_msgs::Float64>("effort", 1);\n'
        "  ros::spin();\n}\n",
    )
    write(
        tmp_path,
        f"{package}/launch/driver.launch",
        '<launch>\n  <node name="driver" pkg="robot_driver" type="driver">\n'
        '    <remap from="~left/gain" to="/gains/left"/>\n  </node>\n</launch>\n',
    )
    assert findings(run_cli, tmp_path) == []

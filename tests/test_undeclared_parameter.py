"""RN407 and a node's parameter set (issue 28, part 2 and the third rule).

A ROS 2 node holds only the parameters it declares: rclcpp's get_parameter(name) throws
ParameterNotDeclaredException for another one, rclpy's raises it, and the quiet reads
(get_parameter(name, value), get_parameter_or) return their default for ever. The rule
reports such a read only where the node's declarations are all known.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from conftest import AMENT_PACKAGE, CATKIN_PACKAGE, ament_package, findings_of, line_places, write


def findings(run_cli: Any, root: Path) -> list[dict[str, Any]]:
    return findings_of(run_cli, root, "RN407")


places = line_places


package = ament_package


DRIVER_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(wheel_driver)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(std_msgs REQUIRED)
add_executable(wheel_driver src/main.cpp src/wheel_driver.cpp src/wheel_driver_timer.cpp)
ament_target_dependencies(wheel_driver rclcpp std_msgs)
install(TARGETS wheel_driver DESTINATION lib/${PROJECT_NAME})
ament_package()
"""

DRIVER_HPP = """\
#pragma once
#include <string>

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/float64.hpp"

namespace wheel_driver
{
class WheelDriver : public rclcpp::Node
{
public:
  explicit WheelDriver(const rclcpp::NodeOptions & options = rclcpp::NodeOptions());

private:
  void on_timer();
  double rate_{10.0};
  std::string port_;
  rclcpp::Publisher<std_msgs::msg::Float64>::SharedPtr speed_publisher_;
  rclcpp::TimerBase::SharedPtr timer_;
};
}  // namespace wheel_driver
"""

DRIVER_CPP = """\
#include "wheel_driver/wheel_driver.hpp"

namespace wheel_driver
{
WheelDriver::WheelDriver(const rclcpp::NodeOptions & options)
: rclcpp::Node("wheel_driver", options)
{
  declare_parameter("rate", 10.0);
  declare_parameter("port", "/dev/ttyUSB0");
  speed_publisher_ = create_publisher<std_msgs::msg::Float64>("wheel_speed", 10);
}
}  // namespace wheel_driver
"""

# A method in another file of the same executable reads what the constructor declares,
# and one more parameter nobody declares.
DRIVER_TIMER_CPP = """\
#include "wheel_driver/wheel_driver.hpp"

namespace wheel_driver
{
void WheelDriver::on_timer()
{
  rate_ = get_parameter("rate").as_double();
  port_ = get_parameter("port").as_string();
  double gain = get_parameter("gain").as_double();
  double trim = 0.0;
  get_parameter("trim", trim);
  speed_publisher_->publish(std_msgs::msg::Float64().set__data(rate_ * gain + trim));
}
}  // namespace wheel_driver
"""

DRIVER_MAIN = """\
#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "wheel_driver/wheel_driver.hpp"

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<wheel_driver::WheelDriver>());
  rclcpp::shutdown();
  return 0;
}
"""


def wheel_driver(root: Path, main: str = DRIVER_MAIN, timer: str = DRIVER_TIMER_CPP) -> Path:
    directory = package(root, "wheel_driver", DRIVER_CMAKE)
    write(directory, "include/wheel_driver/wheel_driver.hpp", DRIVER_HPP)
    write(directory, "src/wheel_driver.cpp", DRIVER_CPP)
    write(directory, "src/wheel_driver_timer.cpp", timer)
    write(directory, "src/main.cpp", main)
    return directory


def test_reads_of_undeclared_parameters_in_another_file_of_the_executable(
    run_cli: Any, tmp_path: Path
) -> None:
    """'rate' and 'port' are declared by the constructor in wheel_driver.cpp: fine.
    'gain' throws, 'trim' (get_parameter(name, value)) returns false for ever."""
    wheel_driver(tmp_path)
    found = findings(run_cli, tmp_path)
    timer = "src/wheel_driver/src/wheel_driver_timer.cpp"
    assert places(found) == [(timer, 9), (timer, 11)]
    gain, trim = sorted(found, key=lambda f: f["line"])
    assert "parameter 'gain'" in gain["message"]
    # No launch file starts it: the node is named only where a launch file names it (a
    # library linked into several programs would otherwise name the wrong one).
    assert "never declared by any code of its node:" in gain["message"]
    assert "throws ParameterNotDeclaredException" in gain["message"]
    assert gain["severity"] == "error"
    assert "returns false every time" in trim["message"]


def test_a_node_allowing_undeclared_parameters_is_not_judged(run_cli: Any, tmp_path: Path) -> None:
    main = DRIVER_MAIN.replace(
        "std::make_shared<wheel_driver::WheelDriver>()",
        "std::make_shared<wheel_driver::WheelDriver>(\n"
        "    rclcpp::NodeOptions().allow_undeclared_parameters(true))",
    )
    wheel_driver(tmp_path, main=main)
    assert findings(run_cli, tmp_path) == []


def test_declarations_from_overrides_leave_the_node_unjudged(run_cli: Any, tmp_path: Path) -> None:
    main = DRIVER_MAIN.replace(
        "std::make_shared<wheel_driver::WheelDriver>()",
        "std::make_shared<wheel_driver::WheelDriver>(\n"
        "    rclcpp::NodeOptions().automatically_declare_parameters_from_overrides(true))",
    )
    wheel_driver(tmp_path, main=main)
    assert findings(run_cli, tmp_path) == []


def test_a_name_declared_at_run_time_may_be_any(run_cli: Any, tmp_path: Path) -> None:
    timer = DRIVER_TIMER_CPP.replace(
        '  rate_ = get_parameter("rate").as_double();\n',
        "  for (const auto & name : extra_) {\n    declare_parameter(name, 0.0);\n  }\n"
        '  rate_ = get_parameter("rate").as_double();\n',
    ).replace("void on_timer();", "void on_timer();")
    wheel_driver(tmp_path, timer=timer)
    assert findings(run_cli, tmp_path) == []


def test_a_project_helper_that_declares_is_not_understood_so_not_judged(
    run_cli: Any, tmp_path: Path
) -> None:
    """``declare_double(node, "gain")``: the linter does not know the helper, but it sees
    the string it is given, and doubts."""
    timer = DRIVER_TIMER_CPP.replace(
        "void WheelDriver::on_timer()\n{\n",
        "void WheelDriver::on_timer()\n{\n"
        '  utils::declare_double(this, "gain");\n'
        '  utils::declare_double(this, "trim");\n',
    )
    wheel_driver(tmp_path, timer=timer)
    assert findings(run_cli, tmp_path) == []


def test_a_parameter_client_asks_another_node(run_cli: Any, tmp_path: Path) -> None:
    timer = DRIVER_TIMER_CPP.replace(
        '  double gain = get_parameter("gain").as_double();\n',
        '  auto client = std::make_shared<rclcpp::SyncParametersClient>(this, "motor");\n'
        '  double gain = client->get_parameter<double>("gain", 1.0);\n',
    )
    wheel_driver(tmp_path, timer=timer)
    assert places(findings(run_cli, tmp_path)) == [
        ("src/wheel_driver/src/wheel_driver_timer.cpp", 12)  # 'trim' only
    ]


def test_a_base_class_outside_the_workspace_may_declare(run_cli: Any, tmp_path: Path) -> None:
    """nav2_util::LifecycleNode (not in this workspace) declares parameters of its own."""
    directory = wheel_driver(tmp_path)
    write(
        directory,
        "include/wheel_driver/wheel_driver.hpp",
        DRIVER_HPP.replace("public rclcpp::Node", "public nav2_util::LifecycleNode"),
    )
    assert findings(run_cli, tmp_path) == []


NAV2_CONTROLLER_CPP = """\
#include <memory>
#include <string>

#include "geometry_msgs/msg/twist.hpp"
#include "nav2_util/node_utils.hpp"
#include "rclcpp/rclcpp.hpp"

class FollowPathServer : public rclcpp::Node
{
public:
  FollowPathServer()
  : rclcpp::Node("follow_path_server")
  {
    const std::string plugin_name = "FollowPath";
    configure(plugin_name);
    nav2_util::declare_parameter_if_not_declared(
      this, "controller_frequency", rclcpp::ParameterValue(20.0));
    frequency_ = get_parameter("controller_frequency").as_double();
    get_parameter("FollowPath.max_vel_x", max_vel_x_);
    publisher_ = create_publisher<geometry_msgs::msg::Twist>("cmd_vel", 1);
  }

private:
  void configure(const std::string & plugin_name_)
  {
    nav2_util::declare_parameter_if_not_declared(
      this, plugin_name_ + ".max_vel_x", rclcpp::ParameterValue(0.26));
  }

  double frequency_{20.0};
  double max_vel_x_{0.26};
  rclcpp::Publisher<geometry_msgs::msg::Twist>::SharedPtr publisher_;
};

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<FollowPathServer>());
  rclcpp::shutdown();
  return 0;
}
"""


def test_nav2_declarations_and_plugin_prefixes(run_cli: Any, tmp_path: Path) -> None:
    """``declare_parameter_if_not_declared`` declares; ``plugin_name_ + ".max_vel_x"``
    declares every ``*.max_vel_x``, so ``FollowPath.max_vel_x`` is declared."""
    directory = package(tmp_path, "follow_path")
    write(directory, "src/follow_path_server.cpp", NAV2_CONTROLLER_CPP)
    assert findings(run_cli, tmp_path) == []
    undeclared = NAV2_CONTROLLER_CPP.replace('"FollowPath.max_vel_x"', '"FollowPath.max_speed"')
    write(directory, "src/follow_path_server.cpp", undeclared)
    assert places(findings(run_cli, tmp_path)) == [
        ("src/follow_path/src/follow_path_server.cpp", 19)
    ]


RCLPY_NODE = """\
import rclpy
from rclpy.node import Node
from std_msgs.msg import Float64


class BatteryReporter(Node):

    def __init__(self):
        super().__init__('battery_reporter'{options})
        self.declare_parameter('capacity', 20.0)
        self.capacity = self.get_parameter('capacity').value
        self.threshold = self.get_parameter('threshold').value
        self.publisher = self.create_publisher(Float64, 'battery_level', 10)


def main():
    rclpy.init()
    rclpy.spin(BatteryReporter())


if __name__ == '__main__':
    main()
"""


def test_rclpy_node(run_cli: Any, tmp_path: Path) -> None:
    directory = package(tmp_path, "battery_reporter")
    path = "battery_reporter/battery_reporter.py"
    write(directory, path, RCLPY_NODE.format(options=""))
    found = findings(run_cli, tmp_path)
    assert places(found) == [(f"src/battery_reporter/{path}", 12)]
    assert "get_parameter raises ParameterNotDeclaredException" in found[0]["message"]
    allowing = ", allow_undeclared_parameters=True"
    write(directory, path, RCLPY_NODE.format(options=allowing))
    assert findings(run_cli, tmp_path) == []
    declared = RCLPY_NODE.format(options="").replace(
        "self.declare_parameter('capacity', 20.0)",
        "self.declare_parameters('', [('capacity', 20.0), ('threshold', 0.2)])",
    )
    write(directory, path, declared)
    assert findings(run_cli, tmp_path) == []


def test_library_code_no_program_runs_is_not_judged(run_cli: Any, tmp_path: Path) -> None:
    """A file no build target compiles into a program or component, with no main: its
    node is whatever code hands it one."""
    directory = package(tmp_path, "odometry_tools")
    write(
        directory,
        "src/odometry_filter.cpp",
        '#include "rclcpp/rclcpp.hpp"\n'
        "void OdometryFilter::configure(rclcpp::Node::SharedPtr node)\n{\n"
        '  alpha_ = node->get_parameter("alpha").as_double();\n'
        '  publisher_ = node->create_publisher<nav_msgs::msg::Odometry>("odom_filtered", 1);\n'
        "}\n",
    )
    assert findings(run_cli, tmp_path) == []


def test_graph_json_shows_each_node_parameters(run_cli: Any, tmp_path: Path) -> None:
    wheel_driver(tmp_path)
    result = run_cli(["graph", "--format", "json", "."], tmp_path)
    assert result.exit_code == 0, result.stderr
    (node,) = json.loads(result.stdout)["nodes"]
    assert node["code_parameters"] == {
        "declared": ["port", "rate"],
        "read": ["gain", "port", "rate", "trim"],
        "declared_under_prefix": [],
        "read_under_prefix": [],
        "read_below": [],
        "reconfigure": [],
        "complete": True,
        "incomplete": [],
    }
    main = DRIVER_MAIN.replace(
        "rclcpp::init(argc, argv);",
        "rclcpp::init(argc, argv);\n  rclcpp::NodeOptions().allow_undeclared_parameters(true);",
    )
    write(tmp_path, "src/wheel_driver/src/main.cpp", main)
    result = run_cli(["graph", "--format", "json", "--no-cache", "."], tmp_path)
    (node,) = json.loads(result.stdout)["nodes"]
    assert node["code_parameters"]["complete"] is False
    assert node["code_parameters"]["incomplete"] == ["allow-undeclared"]


def test_a_constant_of_another_package_may_declare_only_what_it_is_named_for(
    run_cli: Any, tmp_path: Path
) -> None:
    """nav2's LifecycleNode declares bond's DISABLE_HEARTBEAT_TIMEOUT_PARAM, whose value
    the workspace does not hold: a read of a name sharing a word with it is doubted, one
    of an unrelated name is not."""
    ctor = DRIVER_CPP.replace(
        '  declare_parameter("rate", 10.0);\n',
        '  declare_parameter("rate", 10.0);\n'
        "  declare_parameter(bond::msg::Constants::DISABLE_HEARTBEAT_TIMEOUT_PARAM, true);\n",
    )
    timer = DRIVER_TIMER_CPP.replace(
        '  double trim = 0.0;\n  get_parameter("trim", trim);\n',
        '  double trim = get_parameter("heartbeat_timeout").as_double();\n',
    )
    directory = wheel_driver(tmp_path, timer=timer)
    write(directory, "src/wheel_driver.cpp", ctor)
    assert places(findings(run_cli, tmp_path)) == [
        ("src/wheel_driver/src/wheel_driver_timer.cpp", 9)  # 'gain'
    ]


def test_a_base_class_the_workspace_holds_is_followed(run_cli: Any, tmp_path: Path) -> None:
    """An rclpy node deriving from a base class of another package of the workspace: what
    the base does is the node's (here it allows undeclared parameters), and the base's own
    base, rclpy's Node, declares nothing more."""
    base = package(tmp_path, "robot_common")
    base_node = (
        "from rclpy.node import Node\n\n\n"
        "class RobotNode(Node):\n\n"
        "    def __init__(self, name):\n"
        "        super().__init__(name{options})\n"
    )
    write(base, "robot_common/base_node.py", base_node.format(options=""))
    directory = package(tmp_path, "battery_reporter")
    node = (
        RCLPY_NODE.format(options="")
        .replace("from rclpy.node import Node", "from robot_common.base_node import RobotNode")
        .replace("(Node)", "(RobotNode)")
    )
    path = "battery_reporter/battery_reporter.py"
    write(directory, path, node)
    assert places(findings(run_cli, tmp_path)) == [(f"src/battery_reporter/{path}", 12)]
    allowing = ", allow_undeclared_parameters=True"
    write(base, "robot_common/base_node.py", base_node.format(options=allowing))
    assert findings(run_cli, tmp_path) == []


BASE_NODE = (
    "from rclpy.node import Node\n\n\n"
    "class RobotNode(Node):\n\n"
    "    def __init__(self, name):\n"
    "        super().__init__(name{options})\n"
)
ALLOWING = ", allow_undeclared_parameters=True"


def _robot_common(directory: Path, template: str, options: str) -> None:
    write(directory, "package.xml", template.format(name="robot_common"))
    write(directory, "robot_common/base_node.py", BASE_NODE.format(options=options))


def _reporter_on_robot_common(directory: Path) -> str:
    """battery_reporter, deriving from robot_common's ``RobotNode``: its source's path."""
    manifest = AMENT_PACKAGE.format(name="battery_reporter").replace(
        "</license>", "</license>\n  <exec_depend>robot_common</exec_depend>"
    )
    write(directory, "package.xml", manifest)
    node = (
        RCLPY_NODE.format(options="")
        .replace("from rclpy.node import Node", "from robot_common.base_node import RobotNode")
        .replace("(Node)", "(RobotNode)")
    )
    write(directory, "battery_reporter/battery_reporter.py", node)
    shown = directory.relative_to(directory.parents[2]).as_posix()
    return f"{shown}/battery_reporter/battery_reporter.py"


def test_of_two_copies_of_a_base_package_the_one_beside_the_node_is_followed(
    run_cli: Any, tmp_path: Path
) -> None:
    """A fork of robot_common beside the node, its upstream elsewhere (colcon refuses the
    workspace, yet it is linted): the node derives from the fork's class, which does not
    allow undeclared parameters, not from both copies at once."""
    fork, upstream = tmp_path / "src" / "fork", tmp_path / "src" / "upstream"
    _robot_common(fork / "robot_common", AMENT_PACKAGE, "")
    _robot_common(upstream / "robot_common", AMENT_PACKAGE, ALLOWING)
    path = _reporter_on_robot_common(fork / "battery_reporter")
    assert path == "src/fork/battery_reporter/battery_reporter/battery_reporter.py"
    assert places(findings(run_cli, tmp_path)) == [(path, 12)]
    _robot_common(fork / "robot_common", AMENT_PACKAGE, ALLOWING)
    _robot_common(upstream / "robot_common", AMENT_PACKAGE, "")
    assert findings(run_cli, tmp_path) == []


def test_of_two_copies_of_a_base_package_the_one_of_the_nodes_generation_is_followed(
    run_cli: Any, tmp_path: Path
) -> None:
    """A ROS 1 checkout of robot_common beside the ROS 2 node and a ROS 2 one elsewhere:
    a ROS 2 package builds against the ROS 2 one, however far."""
    near, far = tmp_path / "src" / "robot", tmp_path / "src" / "robot_ros2"
    _robot_common(near / "robot_common", CATKIN_PACKAGE, ALLOWING)
    _robot_common(far / "robot_common", AMENT_PACKAGE, "")
    path = _reporter_on_robot_common(near / "battery_reporter")
    assert places(findings(run_cli, tmp_path)) == [(path, 12)]


DRIVER_LAUNCH_PY = """\
from launch import LaunchDescription
from launch.substitutions import PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    params = PathJoinSubstitution([FindPackageShare("wheel_driver"), "config", "driver.yaml"])
    return LaunchDescription([
        Node(
            package="wheel_driver",
            executable="wheel_driver",
            name="wheel_driver",
            parameters=[params, {"trim": 0.05}],
        ),
    ])
"""


def test_sarif_points_at_the_file_and_launch_that_set_the_undeclared_name(
    run_cli: Any, tmp_path: Path
) -> None:
    """The file key and the inline value the launch gives 'gain' and 'trim' are never
    read: SARIF carries them, and where the file is handed over, as related locations."""
    directory = wheel_driver(tmp_path)
    write(directory, "launch/driver.launch.py", DRIVER_LAUNCH_PY)
    write(directory, "config/driver.yaml", "wheel_driver:\n  ros__parameters:\n    gain: 2.0\n")
    result = run_cli(["check", "--format", "sarif", "--select", "RN407", "."], tmp_path)
    assert result.exit_code == 1, result.stderr
    results = json.loads(result.stdout)["runs"][0]["results"]
    related = {
        result["message"]["text"].split("'")[1]: [
            (
                location["physicalLocation"]["artifactLocation"]["uri"],
                location["physicalLocation"]["region"]["startLine"],
                location["message"]["text"],
            )
            for location in result["relatedLocations"]
        ]
        for result in results
    }
    launch = "src/wheel_driver/launch/driver.launch.py"
    started = (launch, 13, "node '/wheel_driver' is started here")
    assert related["gain"] == [
        (
            "src/wheel_driver/config/driver.yaml",
            3,
            "this file sets 'gain' on node '/wheel_driver' here; undeclared, it is never read",
        ),
        started,
        (launch, 14, "the file is handed to node '/wheel_driver' here"),
    ]
    assert related["trim"] == [
        started,
        (
            launch,
            14,
            "the launch file sets 'trim' on node '/wheel_driver' here; undeclared, "
            "it is never read",
        ),
    ]


# ros/geometry2 (ROS 1) and ros2/geometry2 both hold a package tf2_ros whose build makes a
# buffer_server: in one checkout of both, the two programs were joined into one node, ROS
# 2 by the launch's vote, and roscpp's NodeHandle::param read as rclcpp's, which throws.

ROS1_BUFFER_SERVER = """\
#include <ros/ros.h>
#include <std_msgs/String.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "tf_buffer");
  ros::NodeHandle nh;
  double buffer_size;
  nh.param("buffer_size", buffer_size, 120.0);
  bool publish_frame_service;
  nh.param("publish_frame_service", publish_frame_service, false);
  ros::Publisher status = nh.advertise<std_msgs::String>("buffer_status", 1);
  ros::spin();
  return 0;
}
"""

ROS1_BUFFER_CMAKE = """\
cmake_minimum_required(VERSION 3.0.2)
project(tf2_ros)
find_package(catkin REQUIRED COMPONENTS roscpp)
catkin_package()
add_executable(${PROJECT_NAME}_buffer_server src/buffer_server_main.cpp)
set_target_properties(${PROJECT_NAME}_buffer_server PROPERTIES OUTPUT_NAME buffer_server)
"""

ROS2_BUFFER_SERVER = """\
#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("tf_buffer");
  double buffer_size = node->declare_parameter("buffer_size", 120.0);
  (void)buffer_size;
  auto status = node->create_publisher<std_msgs::msg::String>("buffer_status", 1);
  rclcpp::spin(node);
  return 0;
}
"""

ROS2_BUFFER_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(tf2_ros)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
add_executable(buffer_server src/buffer_server_main.cpp)
ament_target_dependencies(buffer_server rclcpp)
ament_package()
"""


def test_two_packages_of_one_name_are_two_programs(run_cli: Any, tmp_path: Path) -> None:
    ros1 = tmp_path / "src" / "geometry2" / "tf2_ros"
    write(ros1, "package.xml", CATKIN_PACKAGE.format(name="tf2_ros"))
    write(ros1, "CMakeLists.txt", ROS1_BUFFER_CMAKE)
    write(ros1, "src/buffer_server_main.cpp", ROS1_BUFFER_SERVER)
    ros2 = tmp_path / "src" / "geometry2_ros2" / "tf2_ros"
    write(ros2, "package.xml", AMENT_PACKAGE.format(name="tf2_ros"))
    write(ros2, "CMakeLists.txt", ROS2_BUFFER_CMAKE)
    write(ros2, "src/buffer_server_main.cpp", ROS2_BUFFER_SERVER)
    assert findings(run_cli, tmp_path) == []

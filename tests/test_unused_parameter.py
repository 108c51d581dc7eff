"""RN406: a parameter set on a node under a name its code never declares (ROS 2) or
reads (ROS 1) (issue 28, the second rule).

ROS 2 keeps a parameter override only when the node declares its name (rclcpp's
NodeParameters, rclpy's Node): a parameter file entry, a launch ``<param>`` or an inline
``parameters=[{...}]`` key the node never declares is dropped in silence. ROS 1 keeps it on
the parameter server, where nothing reads it. The rule speaks only where the node's code
shows every name it may take.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import CATKIN_PACKAGE, ament_package, findings_of, line_places, write


def findings(run_cli: Any, root: Path) -> list[dict[str, Any]]:
    return findings_of(run_cli, root, "RN406")


places = line_places


ament = ament_package


# ---------------------------------------------------------------------------------------
# A nav2-style controller server: the node declares its own parameters, and a controller
# class of the same package declares its own under the name the node gives it
# ("FollowPath"), known only at run time.

CONTROLLER_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(path_controller)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(geometry_msgs REQUIRED)
add_executable(controller_server src/main.cpp src/controller_server.cpp src/follow_path.cpp)
ament_target_dependencies(controller_server rclcpp geometry_msgs)
install(TARGETS controller_server DESTINATION lib/${PROJECT_NAME})
install(DIRECTORY config launch DESTINATION share/${PROJECT_NAME})
ament_package()
"""

CONTROLLER_HPP = """\
#pragma once
#include <memory>
#include <string>

#include "geometry_msgs/msg/twist.hpp"
#include "rclcpp/rclcpp.hpp"
#include "path_controller/follow_path.hpp"

namespace path_controller
{
class ControllerServer : public rclcpp::Node
{
public:
  explicit ControllerServer(const rclcpp::NodeOptions & options = rclcpp::NodeOptions());

private:
  double controller_frequency_;
  FollowPath follow_path_;
  rclcpp::Publisher<geometry_msgs::msg::Twist>::SharedPtr cmd_vel_publisher_;
};
}  // namespace path_controller
"""

CONTROLLER_CPP = """\
#include "path_controller/controller_server.hpp"

namespace path_controller
{
ControllerServer::ControllerServer(const rclcpp::NodeOptions & options)
: rclcpp::Node("controller_server", options)
{
  controller_frequency_ = declare_parameter("controller_frequency", 20.0);
  follow_path_.configure(this, "FollowPath");
  cmd_vel_publisher_ = create_publisher<geometry_msgs::msg::Twist>("cmd_vel", 10);
}
}  // namespace path_controller
"""

FOLLOW_PATH_HPP = """\
#pragma once
#include <string>

#include "rclcpp/rclcpp.hpp"

namespace path_controller
{
class FollowPath
{
public:
  void configure(rclcpp::Node * node, const std::string & name);

private:
  std::string name_;
  double max_vel_x_{0.26};
  double max_vel_theta_{1.0};
};
}  // namespace path_controller
"""

FOLLOW_PATH_CPP = """\
#include "path_controller/follow_path.hpp"

namespace path_controller
{
void FollowPath::configure(rclcpp::Node * node, const std::string & name)
{
  name_ = name;
  max_vel_x_ = node->declare_parameter(name_ + ".max_vel_x", 0.26);
  max_vel_theta_ = node->declare_parameter(name_ + ".max_vel_theta", 1.0);
}
}  // namespace path_controller
"""

CONTROLLER_MAIN = """\
#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "path_controller/controller_server.hpp"

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<path_controller::ControllerServer>({options}));
  rclcpp::shutdown();
  return 0;
}
"""

CONTROLLER_PARAMS = """\
/**:
  ros__parameters:
    use_sim_time: true
controller_server:
  ros__parameters:
    controller_frequency: 20.0
    FollowPath:
      max_vel_x: 0.26
      max_vel_theta: 1.0
"""

CONTROLLER_LAUNCH = """\
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    params = os.path.join(
        get_package_share_directory('path_controller'), 'config', 'controller.yaml')
    return LaunchDescription([
        Node(
            package='path_controller',
            executable='controller_server',
            name='controller_server',
            output='screen',
            parameters=[params, {{'use_sim_time': True{extra}}}],
        ),
    ])
"""


def path_controller(
    root: Path,
    params: str = CONTROLLER_PARAMS,
    options: str = "",
    extra: str = "",
) -> Path:
    directory = ament(root, "path_controller", CONTROLLER_CMAKE)
    write(directory, "include/path_controller/controller_server.hpp", CONTROLLER_HPP)
    write(directory, "include/path_controller/follow_path.hpp", FOLLOW_PATH_HPP)
    write(directory, "src/controller_server.cpp", CONTROLLER_CPP)
    write(directory, "src/follow_path.cpp", FOLLOW_PATH_CPP)
    write(directory, "src/main.cpp", CONTROLLER_MAIN.replace("{options}", options))
    write(directory, "config/controller.yaml", params)
    write(directory, "launch/controller.launch.py", CONTROLLER_LAUNCH.format(extra=extra))
    return directory


PARAMS = "src/path_controller/config/controller.yaml"


def test_names_the_code_declares_under_a_plugin_prefix_are_fine(
    run_cli: Any, tmp_path: Path
) -> None:
    """``FollowPath.max_vel_x`` is declared as ``name_ + ".max_vel_x"``; ``use_sim_time``
    (the ``/**`` key and the inline dict) is declared by rclcpp itself."""
    path_controller(tmp_path)
    assert findings(run_cli, tmp_path) == []


def test_a_misspelled_plugin_parameter_in_the_file(run_cli: Any, tmp_path: Path) -> None:
    params = CONTROLLER_PARAMS.replace("max_vel_x: 0.26", "max_speed_x: 0.26")
    path_controller(tmp_path, params)
    (found,) = findings(run_cli, tmp_path)
    assert (found["path"], found["line"], found["column"]) == (PARAMS, 8, 7)
    assert found["message"] == (
        "parameter 'FollowPath.max_speed_x' is set under node key 'controller_server' for "
        "node '/controller_server', but its code never declares it: a ROS 2 node keeps no "
        "parameter it does not declare, so the setting is dropped; did you mean "
        "'FollowPath.max_vel_x'?"
    )
    related = {(r["path"], r["message"]) for r in found["related"]}
    launch = "src/path_controller/launch/controller.launch.py"
    assert (launch, "node '/controller_server' is started here") in related
    assert (launch, "the file is handed to node '/controller_server' here") in related
    code = "the code of node '/controller_server' declares parameters here"
    assert ("src/path_controller/src/controller_server.cpp", code) in related


def test_a_name_the_node_declares_another_way_in_an_inline_dict(
    run_cli: Any, tmp_path: Path
) -> None:
    path_controller(tmp_path, extra=", 'controller_frequncy': 10.0")
    (found,) = findings(run_cli, tmp_path)
    assert (found["path"], found["line"]) == ("src/path_controller/launch/controller.launch.py", 17)
    assert found["message"].endswith("did you mean 'controller_frequency'?")


def test_a_node_that_allows_undeclared_parameters_is_not_judged(
    run_cli: Any, tmp_path: Path
) -> None:
    params = CONTROLLER_PARAMS.replace("max_vel_x: 0.26", "max_speed_x: 0.26")
    options = "rclcpp::NodeOptions().allow_undeclared_parameters(true)"
    path_controller(tmp_path, params, options=options)
    assert findings(run_cli, tmp_path) == []
    options = "rclcpp::NodeOptions().automatically_declare_parameters_from_overrides(true)"
    path_controller(tmp_path, params, options=options)
    assert findings(run_cli, tmp_path) == []


def test_a_node_that_loads_plugins_is_not_judged(run_cli: Any, tmp_path: Path) -> None:
    """A plugin pluginlib loads declares on the node it is given: its names are unknown."""
    params = CONTROLLER_PARAMS.replace("max_vel_x: 0.26", "max_speed_x: 0.26")
    directory = path_controller(tmp_path, params)
    loading = CONTROLLER_CPP.replace(
        '  follow_path_.configure(this, "FollowPath");\n',
        '  follow_path_.configure(this, "FollowPath");\n'
        '  plugin_ = loader_.createSharedInstance("dwb_core::DWBLocalPlanner");\n',
    )
    write(directory, "src/controller_server.cpp", loading)
    assert findings(run_cli, tmp_path) == []


def test_wildcard_keys_report_once_for_every_node_they_reach(run_cli: Any, tmp_path: Path) -> None:
    """A ``/**`` entry reaches every node given the file: reported only when none of them
    declares it, once, naming them all."""
    params = CONTROLLER_PARAMS.replace(
        "    use_sim_time: true\n", "    use_sim_time: true\n    transform_tolerence: 0.2\n"
    )
    directory = path_controller(tmp_path, params)
    twice = CONTROLLER_LAUNCH.replace(
        "        ),\n    ])",
        "        ),\n"
        "        Node(\n"
        "            package='path_controller',\n"
        "            executable='controller_server',\n"
        "            name='docking_controller',\n"
        "            parameters=[params],\n"
        "        ),\n"
        "    ])",
    ).format(extra="")
    write(directory, "launch/controller.launch.py", twice)
    (found,) = findings(run_cli, tmp_path)
    assert (found["path"], found["line"]) == (PARAMS, 4)
    assert (
        "for every node it applies to ('/controller_server', '/docking_controller'), but none "
        "of their code declares it"
    ) in found["message"]
    # One of them declares it: the entry is for that one.
    declaring = CONTROLLER_CPP.replace(
        '  follow_path_.configure(this, "FollowPath");\n',
        '  follow_path_.configure(this, "FollowPath");\n'
        '  declare_parameter("transform_tolerence", 0.1);\n',
    )
    write(directory, "src/controller_server.cpp", declaring)
    assert findings(run_cli, tmp_path) == []


# ---------------------------------------------------------------------------------------
# Code of another package may declare on the node (opennav_following builds
# opennav_docking's Controller): a name declared anywhere in the workspace is left alone.

DOCKING_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(docking_control)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
add_library(docking_control SHARED src/docking_control.cpp)
ament_target_dependencies(docking_control rclcpp)
ament_package()
"""

DOCKING_CPP = """\
#include <string>

#include "rclcpp/rclcpp.hpp"

namespace docking_control
{
void configure_docking(rclcpp::Node * node)
{
  node->declare_parameter("docking.approach_speed", 0.1);
}
}  // namespace docking_control
"""


def test_a_name_another_package_declares_is_left_alone(run_cli: Any, tmp_path: Path) -> None:
    params = CONTROLLER_PARAMS + "    docking:\n      approach_speed: 0.05\n"
    path_controller(tmp_path, params)
    (found,) = findings(run_cli, tmp_path)
    assert found["message"].startswith("parameter 'docking.approach_speed'")
    docking = ament(tmp_path, "docking_control", DOCKING_CMAKE)
    write(docking, "src/docking_control.cpp", DOCKING_CPP)
    assert findings(run_cli, tmp_path) == []


# ---------------------------------------------------------------------------------------
# A trailing underscore copied from a member (robot_localization's navsat_transform once
# declared ``broadcast_utm_transform_as_parent_frame_``), rclpy and a ROS 2 XML launch.

NAVSAT_NODE = """\
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import NavSatFix


class NavSatBridge(Node):

    def __init__(self):
        super().__init__('navsat_bridge')
        self.broadcast_utm = self.declare_parameter(
            'broadcast_utm_transform_as_parent_frame_', False).value
        self.frequency = self.declare_parameter('frequency', 30.0).value
        self.subscription = self.create_subscription(NavSatFix, 'gps/fix', self.on_fix, 10)

    def on_fix(self, message):
        pass


def main():
    rclpy.init()
    rclpy.spin(NavSatBridge())


if __name__ == '__main__':
    main()
"""

NAVSAT_LAUNCH = """\
<launch>
  <node pkg="navsat_bridge" exec="navsat_bridge" name="navsat_bridge">
    <param name="frequency" value="30.0"/>
    <param name="broadcast_utm_transform_as_parent_frame" value="true"/>
  </node>
</launch>
"""


def test_a_trailing_underscore_in_the_code(run_cli: Any, tmp_path: Path) -> None:
    directory = ament(tmp_path, "navsat_bridge")
    write(directory, "navsat_bridge/navsat_bridge.py", NAVSAT_NODE)
    write(directory, "launch/navsat.launch.xml", NAVSAT_LAUNCH)
    (found,) = findings(run_cli, tmp_path)
    assert (found["path"], found["line"], found["column"]) == (
        "src/navsat_bridge/launch/navsat.launch.xml",
        4,
        18,
    )
    assert found["message"].endswith("did you mean 'broadcast_utm_transform_as_parent_frame_'?")
    related = {(r["path"], r["line"], r["message"]) for r in found["related"]}
    assert (
        "src/navsat_bridge/navsat_bridge/navsat_bridge.py",
        11,
        "'broadcast_utm_transform_as_parent_frame_' is declared here",
    ) in related


# ---------------------------------------------------------------------------------------
# ROS 1: nothing is declared; the names the code reads are what it takes.

ROS1_CMAKE = """\
cmake_minimum_required(VERSION 3.0.2)
project(odom_publisher)
find_package(catkin REQUIRED COMPONENTS roscpp nav_msgs)
catkin_package()
include_directories(${catkin_INCLUDE_DIRS})
add_executable(odom_publisher src/odom_publisher.cpp)
target_link_libraries(odom_publisher ${catkin_LIBRARIES})
"""

ROS1_NODE = """\
#include <string>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

int main(int argc, char ** argv)
{
  ros::init(argc, argv, "odom_publisher");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  double rate;
  std::string frame_id;
  pnh.param("rate", rate, 50.0);
  pnh.param<std::string>("frame_id", frame_id, "odom");
  ros::Publisher publisher = nh.advertise<nav_msgs::Odometry>("odom", 10);
  ros::Rate loop(rate);
  while (ros::ok()) {
    nav_msgs::Odometry odometry;
    odometry.header.frame_id = frame_id;
    publisher.publish(odometry);
    loop.sleep();
  }
  return 0;
}
"""

ROS1_LAUNCH = """\
<launch>
  <group ns="robot1">
    <node pkg="odom_publisher" type="odom_publisher" name="odom_publisher">
      <param name="Rate" value="20.0"/>
      <rosparam command="load" file="$(find odom_publisher)/config/odom.yaml"/>
    </node>
  </group>
</launch>
"""

ROS1_PARAMS = """\
frame_id: odom
child_frame: base_link
"""


def odom_publisher(root: Path, node: str = ROS1_NODE) -> Path:
    directory = root / "src" / "odom_publisher"
    write(directory, "package.xml", CATKIN_PACKAGE.format(name="odom_publisher"))
    write(directory, "CMakeLists.txt", ROS1_CMAKE)
    write(directory, "src/odom_publisher.cpp", node)
    write(directory, "launch/odom.launch", ROS1_LAUNCH)
    write(directory, "config/odom.yaml", ROS1_PARAMS)
    return directory


def test_ros1_names_no_code_reads(run_cli: Any, tmp_path: Path) -> None:
    """``<param name="Rate">`` while the node reads ``~rate``; the file loaded into the
    node sets ``~child_frame``, which nothing reads."""
    odom_publisher(tmp_path)
    found = findings(run_cli, tmp_path)
    assert places(found) == [
        ("src/odom_publisher/config/odom.yaml", 2),
        ("src/odom_publisher/launch/odom.launch", 4),
    ]
    by_path = {f["path"]: f["message"] for f in found}
    assert by_path["src/odom_publisher/launch/odom.launch"] == (
        "parameter 'Rate' is set by the launch file for node '/robot1/odom_publisher', but "
        "its code never reads it: it stays on the parameter server, unread; did you mean "
        "'rate'?"
    )
    assert by_path["src/odom_publisher/config/odom.yaml"].startswith(
        "parameter 'child_frame' is loaded from this file for node '/robot1/odom_publisher'"
    )


def test_ros1_reads_through_any_handle_and_whole_dictionaries(run_cli: Any, tmp_path: Path) -> None:
    """Names are compared without their namespaces: a read through the public handle, or
    of the whole private namespace, counts."""
    reading = ROS1_NODE.replace(
        '  pnh.param("rate", rate, 50.0);\n',
        '  pnh.param("rate", rate, 50.0);\n'
        '  nh.param("Rate", rate, rate);\n'
        "  XmlRpc::XmlRpcValue everything;\n"
        '  pnh.getParam("child_frame", everything);\n',
    )
    odom_publisher(tmp_path, reading)
    assert findings(run_cli, tmp_path) == []


def test_ros1_a_search_reads_the_name_it_searches(run_cli: Any, tmp_path: Path) -> None:
    """``searchParam("child_frame", key)`` finds ``child_frame`` in the node's namespace or
    one above it (roscpp's ``NodeHandle::searchParam``, rospy's ``search_param``): a read of
    that name at some level. ``Rate`` is still read by nothing."""
    searching = ROS1_NODE.replace(
        '  pnh.param("rate", rate, 50.0);\n',
        '  pnh.param("rate", rate, 50.0);\n'
        "  std::string key;\n"
        '  if (pnh.searchParam("child_frame", key)) {}\n',
    )
    odom_publisher(tmp_path, searching)
    assert places(findings(run_cli, tmp_path)) == [("src/odom_publisher/launch/odom.launch", 4)]


def test_ros1_run_time_searches_or_reads_leave_the_node_unjudged(
    run_cli: Any, tmp_path: Path
) -> None:
    searching = ROS1_NODE.replace(
        '  pnh.param("rate", rate, 50.0);\n',
        '  pnh.param("rate", rate, 50.0);\n'
        "  std::string key;\n"
        "  if (nh.searchParam(std::string(argv[1]), key)) {}\n",
    )
    directory = odom_publisher(tmp_path, searching)
    assert findings(run_cli, tmp_path) == []
    built = ROS1_NODE.replace(
        '  pnh.param("rate", rate, 50.0);\n',
        '  pnh.param("rate", rate, 50.0);\n'
        '  for (const auto & axis : {std::string("x"), std::string("y")}) {\n'
        "    double limit;\n"
        "    pnh.getParam(axis, limit);\n"
        "  }\n",
    )
    write(directory, "src/odom_publisher.cpp", built)
    assert findings(run_cli, tmp_path) == []


def test_did_you_mean() -> None:
    from roslint_names.rules.spelling import nearest

    assert nearest("max_speed_x", ["max_vel_x", "controller_frequency"]) == "max_vel_x"
    assert nearest("jerk_wieght", ["jerk_weight", "over_v_weight"]) == "jerk_weight"
    assert nearest("Rate", ["rate", "frame_id"]) == "rate"
    assert nearest("yaml_file_name", ["yaml_filename", "topic_name"]) == "yaml_filename"
    assert nearest("delta_yaw_threshold", ["resample.delta_yaw_threshold"]) == (
        "resample.delta_yaw_threshold"
    )
    assert nearest("controller.simulation_step", ["controller.simulation_time_step"]) == (
        "controller.simulation_time_step"  # navigation2's nav2_params.yaml
    )
    assert nearest("max_vel", ["vel"]) is None  # one word left is no slip
    assert nearest("x", ["y"]) is None  # too short for a slip
    assert nearest("mid_vel_y", ["max_vel_x", "min_vel_x"]) is None  # two as near: no guess


# rostest's hztest reads its parameters inside a test's try/except, a part of test code
# the extractor sets aside (an expected failure): the strings it holds still count.

RATE_TEST_NODE = """\
#!/usr/bin/env python
import unittest

import rospy
import rostest
from std_msgs.msg import String


class RateTest(unittest.TestCase):
    def __init__(self, *args):
        super(RateTest, self).__init__(*args)
        rospy.init_node('rate_test')

    def test_rate(self):
        try:
            rate = float(rospy.get_param('~rate'))
        except KeyError as e:
            self.fail('rate_test needs ~rate: %s' % e)
        tolerance = 0.0
        if rate != 0.0:
            try:
                tolerance = float(rospy.get_param('~tolerance'))
            except KeyError as e:
                self.fail('rate_test needs ~tolerance: %s' % e)
        rospy.Subscriber('chatter', String, lambda message: None)
        self.assertGreaterEqual(tolerance, 0.0)


if __name__ == '__main__':
    rostest.rosrun('rate_check', 'rate_test', RateTest)
"""

RATE_TEST = """\
<launch>
  <node pkg="rostopic" type="rostopic" name="publisher"
        args="pub -r 10 chatter std_msgs/String hello"/>
  <test test-name="chatter_rate" pkg="rate_check" type="rate_test" name="rate_test">
    <param name="rate" value="10.0"/>
    <param name="tolerance" value="0.5"/>
  </test>
</launch>
"""


def test_ros1_reads_a_test_expects_to_fail_still_count(run_cli: Any, tmp_path: Path) -> None:
    directory = tmp_path / "src" / "rate_check"
    write(directory, "package.xml", CATKIN_PACKAGE.format(name="rate_check"))
    write(directory, "nodes/rate_test", RATE_TEST_NODE)
    write(directory, "test/chatter_rate.test", RATE_TEST)
    assert findings(run_cli, tmp_path) == []
    misspelled = RATE_TEST.replace('name="tolerance"', 'name="tolerence"')
    write(directory, "test/chatter_rate.test", misspelled)
    assert places(findings(run_cli, tmp_path)) == [("src/rate_check/test/chatter_rate.test", 6)]


def test_a_test_without_a_name_runs_as_its_test_name(run_cli: Any, tmp_path: Path) -> None:
    """MoveIt's pilz integration tests: roslaunch names a <test> without a name after its
    test-name (``XmlLoader._node_tag``); before, the message named the node by the name
    the code hands ``rospy.init_node``, a node that never runs."""
    directory = tmp_path / "src" / "rate_check"
    write(directory, "package.xml", CATKIN_PACKAGE.format(name="rate_check"))
    write(directory, "nodes/rate_test", RATE_TEST_NODE)
    unnamed = RATE_TEST.replace(' name="rate_test"', "").replace('"tolerance"', '"tolerence"')
    write(directory, "test/chatter_rate.test", unnamed)
    found = findings(run_cli, tmp_path)
    assert places(found) == [("src/rate_check/test/chatter_rate.test", 6)]
    assert "for node '/chatter_rate'" in found[0]["message"]


def test_one_stale_setting_copied_into_several_launch_files_is_one_finding(
    run_cli: Any, tmp_path: Path
) -> None:
    """autoware's map_projection_loader tests: four launch files set the same parameter
    the node no longer declares. One decision (drop it), reported once with the copies
    related."""
    directory = path_controller(tmp_path, extra=", 'controller_frequncy': 10.0")
    launch = CONTROLLER_LAUNCH.format(extra=", 'controller_frequncy': 10.0")
    write(directory, "launch/controller_sim.launch.py", launch)
    (found,) = findings(run_cli, tmp_path)
    assert (found["path"], found["line"]) == ("src/path_controller/launch/controller.launch.py", 17)
    assert found["message"].endswith("(also written at 1 other place)")
    copies = [r for r in found["related"] if r["path"].endswith("controller_sim.launch.py")]
    assert any(r["line"] == 17 for r in copies)


# roslaunch's resources/example.launch: a showcase of launch syntax that starts rospy's
# test_nodes/talker.py, a test's stand-in, and sets it a made-up ``talker_param``.

STAND_IN_TALKER = """\
#!/usr/bin/env python
import rospy
from std_msgs.msg import String


def talker():
    pub = rospy.Publisher('chatter', String, queue_size=10)
    rospy.init_node('talker', anonymous=True)
    rate = rospy.Rate(rospy.get_param('~rate', 10))
    while not rospy.is_shutdown():
        pub.publish(String('hello world %s' % rospy.get_time()))
        rate.sleep()


if __name__ == '__main__':
    talker()
"""

SYNTAX_SHOWCASE = """\
<launch>
  <group ns="wg">
    <remap from="chatter" to="hello"/>
    <node name="talker1" pkg="rospy" type="talker.py">
      <env name="ENV_EXAMPLE" value="example value" />
      <!-- params within node tags are equivalent to ~params. -->
      <param name="talker_param" value="a value" />
    </node>
  </group>
</launch>
"""


def stand_in_talker(root: Path, launch_path: str) -> Path:
    rospy = root / "src" / "rospy"
    write(rospy, "package.xml", CATKIN_PACKAGE.format(name="rospy"))
    write(rospy, "test_nodes/talker.py", STAND_IN_TALKER)
    (rospy / "test_nodes" / "talker.py").chmod(0o755)
    roslaunch = root / "src" / "roslaunch"
    write(roslaunch, "package.xml", CATKIN_PACKAGE.format(name="roslaunch"))
    write(roslaunch, launch_path, SYNTAX_SHOWCASE)
    return roslaunch


def test_an_example_setting_a_test_stand_in_a_made_up_name_is_left_alone(
    run_cli: Any, tmp_path: Path
) -> None:
    stand_in_talker(tmp_path, "resources/example.launch")
    assert findings(run_cli, tmp_path) == []


def test_a_deployed_launch_setting_a_test_stand_in_an_unread_name_is_reported(
    run_cli: Any, tmp_path: Path
) -> None:
    """The same launch file outside example code: whoever deploys the stand-in sets a
    parameter it never reads."""
    stand_in_talker(tmp_path, "launch/chatter.launch")
    assert places(findings(run_cli, tmp_path)) == [("src/roslaunch/launch/chatter.launch", 7)]


def test_ros1_yaml_inside_a_rosparam_sets_the_node_s_parameters(
    run_cli: Any, tmp_path: Path
) -> None:
    """husky's gmapping.launch writes the node's parameters as YAML inside ``<rosparam>``
    (roslaunch ``_rosparam_tag`` loads the text with ``yaml.safe_load``): each leaf is a
    ``~`` parameter, below ``ns`` when given, at its key's place in the launch file."""
    directory = odom_publisher(tmp_path)
    inline = ROS1_LAUNCH.replace(
        '      <param name="Rate" value="20.0"/>\n',
        "      <rosparam>\n"
        "        rate: 20.0\n"
        "        frame_idd: odom\n"
        "      </rosparam>\n"
        '      <rosparam ns="limits">\n'
        "        max_vel: 1.0\n"
        "      </rosparam>\n",
    )
    write(directory, "launch/odom.launch", inline)
    found = findings(run_cli, tmp_path)
    assert places(found) == [
        ("src/odom_publisher/config/odom.yaml", 2),
        ("src/odom_publisher/launch/odom.launch", 6),
        ("src/odom_publisher/launch/odom.launch", 9),
    ]
    by_line = {f["line"]: f for f in found}
    assert by_line[6]["column"] == 9
    assert (
        "'frame_idd'" in by_line[6]["message"]
        and "did you mean 'frame_id'" in by_line[6]["message"]
    )
    assert "'limits/max_vel'" in by_line[9]["message"]


# autoware_perception_online_evaluator, reduced: every parameter is declared through
# autoware_utils' get_or_declare_parameter, some under a prefix a lambda is handed.
EVALUATOR_CMAKE = """\
cmake_minimum_required(VERSION 3.14)
project(perception_online_evaluator)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(autoware_utils REQUIRED)
add_executable(perception_online_evaluator_node src/perception_online_evaluator_node.cpp)
ament_target_dependencies(perception_online_evaluator_node rclcpp autoware_utils)
install(TARGETS perception_online_evaluator_node DESTINATION lib/${PROJECT_NAME})
install(DIRECTORY param launch DESTINATION share/${PROJECT_NAME})
ament_package()
"""

EVALUATOR_CPP = """\
#include <autoware_utils/ros/parameter.hpp>
#include <rclcpp/rclcpp.hpp>

#include <memory>
#include <string>

class PerceptionOnlineEvaluatorNode : public rclcpp::Node
{
public:
  explicit PerceptionOnlineEvaluatorNode(const rclcpp::NodeOptions & options)
  : Node("perception_online_evaluator", options)
  {
    using autoware_utils::get_or_declare_parameter;
    window_ = get_or_declare_parameter<int>(*this, "smoothing_window_size");
    const auto check = [&](std::string && ns) {
      return get_or_declare_parameter<bool>(*this, ns + "check_lateral_deviation");
    };
    const std::string ns = "target_object.";
    car_ = check(ns + "car.");
    bus_ = check(ns + "bus.");
  }

private:
  int window_;
  bool car_;
  bool bus_;
};

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<PerceptionOnlineEvaluatorNode>(rclcpp::NodeOptions{}));
  rclcpp::shutdown();
}
"""

EVALUATOR_PARAMS = """\
/**:
  ros__parameters:
    smoothing_window_size: 11
    smoothing_windw: 3
    target_object:
      car:
        check_lateral_deviation: true
      bus:
        check_lateral_deviation: false
"""

EVALUATOR_LAUNCH = """\
<launch>
  <node pkg="perception_online_evaluator" exec="perception_online_evaluator_node"
        name="perception_online_evaluator">
    <param from="$(find-pkg-share perception_online_evaluator)/param/evaluator.param.yaml"/>
  </node>
</launch>
"""


def test_autoware_s_get_or_declare_parameter_declares(run_cli: Any, tmp_path: Path) -> None:
    """autoware.universe calls it 815 times; unknown, a node declaring through it alone
    declared nothing, and every key of its file was reported (58 in
    perception_online_evaluator.defaults.yaml). A misspelt key still is."""
    directory = ament_package(tmp_path, "perception_online_evaluator", EVALUATOR_CMAKE)
    write(directory, "src/perception_online_evaluator_node.cpp", EVALUATOR_CPP)
    write(directory, "param/evaluator.param.yaml", EVALUATOR_PARAMS)
    write(directory, "launch/evaluator.launch.xml", EVALUATOR_LAUNCH)
    found = findings_of(run_cli, tmp_path, "RN406")
    assert [(f["path"], f["line"]) for f in found] == [
        ("src/perception_online_evaluator/param/evaluator.param.yaml", 4),
    ]

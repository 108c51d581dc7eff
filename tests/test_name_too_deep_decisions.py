"""RN201 counts only the levels a writer chose, and reports each decision once.

Each test writes a small ROS workspace shaped like the real ones the findings came from
(Autoware's planning and traffic light launch files, a component container of its own)
and runs the real CLI over it.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import AMENT_PACKAGE, CATKIN_PACKAGE, write


def deep_findings(run_cli: Any, root: Path) -> list[dict[str, Any]]:
    result = run_cli(["check", "--format", "json", "--select", "RN201", "."], root)
    assert result.exit_code in (0, 1), result.stderr
    found: list[dict[str, Any]] = result.findings()
    return found


def column_of(text: str, line: int, needle: str) -> int:
    """The 1-based column of ``needle`` on ``line`` of ``text``."""
    return text.splitlines()[line - 1].index(needle) + 1


# ---------------------------------------------------------------------------------------
# Names nobody chose: a container's hidden services, a transport's subtopic

CONTAINER_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(sensing_containers)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(rclcpp_components REQUIRED)
find_package(composition_interfaces REQUIRED)
find_package(diagnostic_msgs REQUIRED)

add_executable(camera_container src/camera_container.cpp)
ament_target_dependencies(camera_container rclcpp rclcpp_components composition_interfaces
  diagnostic_msgs)
install(TARGETS camera_container DESTINATION lib/${PROJECT_NAME})
ament_package()
"""

# A container of its own that keeps rclcpp_components' service names
# (component_manager.cpp), so that `ros2 component load` still finds it.
CONTAINER_CPP = """\
#include <composition_interfaces/srv/list_nodes.hpp>
#include <composition_interfaces/srv/load_node.hpp>
#include <composition_interfaces/srv/unload_node.hpp>
#include <diagnostic_msgs/msg/diagnostic_status.hpp>
#include <rclcpp/rclcpp.hpp>

using composition_interfaces::srv::ListNodes;
using composition_interfaces::srv::LoadNode;
using composition_interfaces::srv::UnloadNode;

class CameraContainer : public rclcpp::Node
{
public:
  CameraContainer() : Node("camera_container")
  {
    load_srv_ = create_service<LoadNode>(
      "~/_container/load_node",
      [](const LoadNode::Request::SharedPtr, LoadNode::Response::SharedPtr) {});
    unload_srv_ = create_service<UnloadNode>(
      "~/_container/unload_node",
      [](const UnloadNode::Request::SharedPtr, UnloadNode::Response::SharedPtr) {});
    list_srv_ = create_service<ListNodes>(
      "~/_container/list_nodes",
      [](const ListNodes::Request::SharedPtr, ListNodes::Response::SharedPtr) {});
    status_pub_ = create_publisher<diagnostic_msgs::msg::DiagnosticStatus>("~/status", 10);
  }

private:
  rclcpp::Service<LoadNode>::SharedPtr load_srv_;
  rclcpp::Service<UnloadNode>::SharedPtr unload_srv_;
  rclcpp::Service<ListNodes>::SharedPtr list_srv_;
  rclcpp::Publisher<diagnostic_msgs::msg::DiagnosticStatus>::SharedPtr status_pub_;
};

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<CameraContainer>());
  rclcpp::shutdown();
  return 0;
}
"""

CONTAINER_LAUNCH = """\
<launch>
  <node pkg="sensing_containers" exec="camera_container" name="container"
        namespace="sensing/camera/front"/>
</launch>
"""


def test_a_containers_hidden_services_are_not_levels_of_the_launch_files_name(
    run_cli: Any, tmp_path: Path
) -> None:
    """`/sensing/camera/front/container/_container/load_node`: the launch file chose four
    levels, rclcpp_components the hidden rest. Its `~/status` is the node's own level."""
    write(
        tmp_path,
        "src/sensing_containers/package.xml",
        AMENT_PACKAGE.format(name="sensing_containers"),
    )
    write(tmp_path, "src/sensing_containers/CMakeLists.txt", CONTAINER_CMAKE)
    write(tmp_path, "src/sensing_containers/src/camera_container.cpp", CONTAINER_CPP)
    write(tmp_path, "src/sensing_containers/launch/camera.launch.xml", CONTAINER_LAUNCH)
    found = deep_findings(run_cli, tmp_path)
    assert [(f["path"], f["line"]) for f in found] == [
        ("src/sensing_containers/launch/camera.launch.xml", 2)
    ]
    assert "'/sensing/camera/front/container/status'" in found[0]["message"]
    assert "_container" not in found[0]["message"]


ROI_VISUALIZER_LAUNCH = """\
<launch>
  <node pkg="autoware_traffic_light_visualization" exec="traffic_light_visualization_node"
        name="traffic_light_roi_visualizer">
    <remap from="~/input/image" to="/sensing/camera/front/image_raw"/>
    <remap from="~/output/image" to="/perception/traffic_light/debug/rois"/>
    <remap from="~/output/image/compressed" to="/perception/traffic_light/debug/rois/compressed"/>
    <remap from="~/output/image/compressedDepth"
           to="/perception/traffic_light/debug/rois/compressedDepth"/>
    <remap from="~/output/image/theora" to="/perception/traffic_light/debug/rois/theora"/>
  </node>
</launch>
"""


def test_an_image_transports_subtopic_is_not_a_level_of_the_writers_name(
    lint_text: Any,
) -> None:
    """image_transport's plugins publish `<base>/compressed`, `/compressedDepth`,
    `/theora`: the writer chose the four levels of `/perception/traffic_light/debug/rois`."""
    assert lint_text(ROI_VISUALIZER_LAUNCH, "launch/roi_visualizer.launch.xml", 2) == []
    deeper = ROI_VISUALIZER_LAUNCH.replace("/debug/rois", "/debug/rois/front")
    assert lint_text(deeper, "launch/roi_visualizer.launch.xml", 2) == ["RN201"] * 4


# ---------------------------------------------------------------------------------------
# One decision, one finding: the launch site that pushes ten names past the limit

SMOOTHER_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(velocity_smoother)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(autoware_planning_msgs REQUIRED)

add_executable(velocity_smoother_node src/node.cpp)
ament_target_dependencies(velocity_smoother_node rclcpp autoware_planning_msgs)
install(TARGETS velocity_smoother_node DESTINATION lib/${PROJECT_NAME})
ament_package()
"""

SMOOTHER_NODE_CPP = """\
#include <autoware_planning_msgs/msg/trajectory.hpp>
#include <rclcpp/rclcpp.hpp>

using autoware_planning_msgs::msg::Trajectory;

class VelocitySmootherNode : public rclcpp::Node
{
public:
  VelocitySmootherNode() : Node("velocity_smoother")
  {
    pub_trajectory_ = create_publisher<Trajectory>("~/output/trajectory", 1);
    debug_raw_ = create_publisher<Trajectory>("~/debug/trajectory_raw", 1);
    debug_lateral_ = create_publisher<Trajectory>("~/debug/trajectory_lateral_acc_filtered", 1);
    debug_steering_ = create_publisher<Trajectory>("~/debug/trajectory_steering_rate_limited", 1);
    debug_resampled_ = create_publisher<Trajectory>("~/debug/trajectory_time_resampled", 1);
    debug_forward_ = create_publisher<Trajectory>("~/debug/forward_filtered_trajectory", 1);
  }

private:
  rclcpp::Publisher<Trajectory>::SharedPtr pub_trajectory_;
  rclcpp::Publisher<Trajectory>::SharedPtr debug_raw_;
  rclcpp::Publisher<Trajectory>::SharedPtr debug_lateral_;
  rclcpp::Publisher<Trajectory>::SharedPtr debug_steering_;
  rclcpp::Publisher<Trajectory>::SharedPtr debug_resampled_;
  rclcpp::Publisher<Trajectory>::SharedPtr debug_forward_;
};

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<VelocitySmootherNode>());
  rclcpp::shutdown();
  return 0;
}
"""

PLANNING_LAUNCH = """\
<launch>
  <group>
    <push-ros-namespace namespace="planning"/>
    <node pkg="velocity_smoother" exec="velocity_smoother_node" name="velocity_smoother"
          namespace="scenario_planning">
      <remap from="~/output/trajectory" to="/planning/scenario_planning/trajectory"/>
    </node>
  </group>
</launch>
"""


def smoother_workspace(root: Path) -> None:
    write(root, "src/velocity_smoother/package.xml", AMENT_PACKAGE.format(name="velocity_smoother"))
    write(root, "src/velocity_smoother/CMakeLists.txt", SMOOTHER_CMAKE)
    write(root, "src/velocity_smoother/src/node.cpp", SMOOTHER_NODE_CPP)
    write(root, "src/planning_launch/package.xml", AMENT_PACKAGE.format(name="planning_launch"))
    write(root, "src/planning_launch/launch/planning.launch.xml", PLANNING_LAUNCH)


def test_a_node_whose_namespace_pushes_five_debug_topics_too_deep_is_one_finding(
    run_cli: Any, tmp_path: Path
) -> None:
    smoother_workspace(tmp_path)
    found = deep_findings(run_cli, tmp_path)
    assert [(f["path"], f["line"]) for f in found] == [
        ("src/planning_launch/launch/planning.launch.xml", 4)
    ]
    message = found[0]["message"]
    assert message.startswith("5 names of node '/planning/scenario_planning/velocity_smoother'")
    assert "'/planning/scenario_planning/velocity_smoother/debug/forward_filtered_trajectory'" in (
        message
    )
    assert message.endswith("and 2 more")
    related = found[0]["related"]
    assert [(r["path"], r["line"]) for r in related] == [
        ("src/velocity_smoother/src/node.cpp", line) for line in (12, 13, 14, 15, 16)
    ]


# ---------------------------------------------------------------------------------------
# A topic wired from a publisher's remap to a subscriber's: reported at the publisher

MOTION_PLANNING_LAUNCH = """\
<launch>
  <group>
    <push-ros-namespace namespace="planning/scenario_planning/lane_driving/motion_planning"/>
    <node pkg="autoware_path_optimizer" exec="path_optimizer_node" name="path_optimizer">
      <remap from="~/input/path" to="path_smoother/path"/>
      <remap from="~/input/odometry" to="/localization/kinematic_state"/>
      <remap from="~/output/path" to="path_optimizer/trajectory"/>
    </node>
    <node pkg="autoware_motion_velocity_planner" exec="motion_velocity_planner_node"
          name="motion_velocity_planner">
      <remap from="~/input/trajectory" to="path_optimizer/trajectory"/>
      <remap from="~/input/vector_map" to="/map/vector_map"/>
      <remap from="~/output/trajectory" to="motion_velocity_planner/trajectory"/>
    </node>
  </group>
  <node pkg="autoware_velocity_smoother" exec="velocity_smoother_node" name="velocity_smoother"
        namespace="planning/scenario_planning">
    <remap from="~/input/trajectory"
           to="/planning/scenario_planning/lane_driving/motion_planning/motion_velocity_planner/trajectory"/>
    <remap from="~/output/trajectory" to="/planning/scenario_planning/trajectory"/>
  </node>
</launch>
"""


def test_a_topic_wired_from_an_output_remap_to_input_remaps_is_reported_at_the_output(
    run_cli: Any, tmp_path: Path
) -> None:
    """Autoware's nodes name their ends `~/input/*` and `~/output/*` (its coding
    guidelines): the subscriber's remap, relative or absolute, repeats the publisher's
    decision and is listed with it. `path_smoother/path` has no publisher here: its
    subscriber's remap is where it is chosen."""
    write(tmp_path, "src/planning_launch/package.xml", AMENT_PACKAGE.format(name="planning_launch"))
    path = "src/planning_launch/launch/motion_planning.launch.xml"
    write(tmp_path, path, MOTION_PLANNING_LAUNCH)
    found = deep_findings(run_cli, tmp_path)
    assert [(f["line"], f["column"]) for f in found] == [
        (5, column_of(MOTION_PLANNING_LAUNCH, 5, "path_smoother/path")),
        (7, column_of(MOTION_PLANNING_LAUNCH, 7, "path_optimizer/trajectory")),
        (13, column_of(MOTION_PLANNING_LAUNCH, 13, "motion_velocity_planner/trajectory")),
    ]
    assert [(r["line"], r["message"]) for r in found[1]["related"]] == [
        (4, "the launch site that pushes the namespace"),
        (11, "a subscriber's remap of this name"),
    ]
    assert [r["line"] for r in found[2]["related"] if "subscriber" in r["message"]] == [19]
    assert found[2]["message"].endswith("1 subscriber remap(s) use it too")


SMOOTHER_ROS1_CPP = """\
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "velocity_smoother");
  ros::NodeHandle nh;
  ros::Publisher smooth_pub = nh.advertise<geometry_msgs::Twist>("cmd_vel_smooth", 10);
  ros::spin();
  return 0;
}
"""

BASE_DRIVER_ROS1_CPP = """\
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

void onCommand(const geometry_msgs::Twist::ConstPtr& msg) {}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "base_driver");
  ros::NodeHandle nh;
  ros::Subscriber cmd_sub = nh.subscribe("cmd_vel", 10, onCommand);
  ros::spin();
  return 0;
}
"""

TURTLE_CMAKE = """\
cmake_minimum_required(VERSION 3.0.2)
project(turtle_base)
find_package(catkin REQUIRED COMPONENTS roscpp geometry_msgs)
catkin_package()
include_directories(${catkin_INCLUDE_DIRS})

add_executable(velocity_smoother src/velocity_smoother.cpp)
target_link_libraries(velocity_smoother ${catkin_LIBRARIES})
add_executable(base_driver src/base_driver.cpp)
target_link_libraries(base_driver ${catkin_LIBRARIES})
"""

BASE_LAUNCH = """\
<launch>
  <group ns="site_a/robot1">
    <node name="velocity_smoother" pkg="turtle_base" type="velocity_smoother">
      <remap from="cmd_vel_smooth" to="base/smoothed/cmd_vel"/>
    </node>
    <node name="base_driver" pkg="turtle_base" type="base_driver">
      <remap from="cmd_vel" to="base/smoothed/cmd_vel"/>
    </node>
  </group>
</launch>
"""


def test_the_nodes_code_says_which_remap_is_the_publishers(run_cli: Any, tmp_path: Path) -> None:
    """No naming convention here: the smoother's code publishes `cmd_vel_smooth`, the
    driver's subscribes `cmd_vel`, both remapped to one topic."""
    write(tmp_path, "src/turtle_base/package.xml", CATKIN_PACKAGE.format(name="turtle_base"))
    write(tmp_path, "src/turtle_base/CMakeLists.txt", TURTLE_CMAKE)
    write(tmp_path, "src/turtle_base/src/velocity_smoother.cpp", SMOOTHER_ROS1_CPP)
    write(tmp_path, "src/turtle_base/src/base_driver.cpp", BASE_DRIVER_ROS1_CPP)
    write(tmp_path, "src/turtle_base/launch/base.launch", BASE_LAUNCH)
    found = deep_findings(run_cli, tmp_path)
    assert [(f["line"], f["column"]) for f in found] == [
        (4, column_of(BASE_LAUNCH, 4, "base/smoothed/cmd_vel"))
    ]
    assert "'/site_a/robot1/base/smoothed/cmd_vel'" in found[0]["message"]
    assert [r["line"] for r in found[0]["related"] if "subscriber" in r["message"]] == [7]


def test_hidden_tokens_are_ros2s_and_a_transport_is_the_last_token_only() -> None:
    from roslint_names.model import Generation, Kind
    from roslint_names.rules.common import chosen_depth

    ros1, ros2 = Generation.ROS1, Generation.ROS2
    assert chosen_depth("/a/b/node/_container/load_node", Kind.SERVICE, ros2) == 3
    # ROS 1 hides nothing: rostopic and rqt_graph list `_`-prefixed names as any other
    assert chosen_depth("/a/b/node/_container/load_node", Kind.SERVICE, ros1) == 5
    assert chosen_depth("/camera/image_raw/compressed", Kind.TOPIC, ros1) == 2
    assert chosen_depth("/points/draco", Kind.TOPIC, ros2) == 1
    assert chosen_depth("/compressed", Kind.TOPIC, ros2) == 1  # a name of its own
    assert chosen_depth("/camera/compressed/image", Kind.TOPIC, ros2) == 3
    assert chosen_depth("/camera/image/compressed", Kind.SERVICE, ros2) == 3


MOTION_PLANNING_LAUNCH_PY = """\
from launch import LaunchDescription
from launch.actions import GroupAction
from launch_ros.actions import Node, PushRosNamespace


def generate_launch_description():
    return LaunchDescription([
        GroupAction([
            PushRosNamespace("planning/scenario_planning/lane_driving/motion_planning"),
            Node(
                package="autoware_path_optimizer",
                executable="path_optimizer_node",
                name="path_optimizer",
                remappings=[("~/output/path", "path_optimizer/trajectory")],
            ),
            Node(
                package="autoware_motion_velocity_planner",
                executable="motion_velocity_planner_node",
                name="motion_velocity_planner",
                remappings=[("~/input/trajectory", "path_optimizer/trajectory")],
            ),
        ]),
    ])
"""


def test_a_python_launch_files_wired_topic_is_reported_at_the_publishers_target(
    run_cli: Any, tmp_path: Path
) -> None:
    write(tmp_path, "src/planning_launch/package.xml", AMENT_PACKAGE.format(name="planning_launch"))
    write(
        tmp_path, "src/planning_launch/launch/motion_planning.launch.py", MOTION_PLANNING_LAUNCH_PY
    )
    found = deep_findings(run_cli, tmp_path)
    target = '"path_optimizer/trajectory"'
    assert [(f["line"], f["column"]) for f in found] == [
        (14, column_of(MOTION_PLANNING_LAUNCH_PY, 14, target))
    ]
    assert [
        (r["line"], r["column"]) for r in found[0]["related"] if "subscriber" in r["message"]
    ] == [(20, column_of(MOTION_PLANNING_LAUNCH_PY, 20, target))]


def test_an_input_remap_of_a_node_named_by_its_code_is_reported_once(
    run_cli: Any, tmp_path: Path
) -> None:
    """The file rule judges the remap of a node the launch file does not name (it cannot
    tell whether the graph will know the node); the graph rule leaves it alone."""
    smoother_workspace(tmp_path)
    launch = (
        "<launch>\n"
        '  <node pkg="velocity_smoother" exec="velocity_smoother_node">\n'
        '    <remap from="~/input/trajectory"\n'
        '           to="/planning/scenario_planning/lane_driving/motion_planning/trajectory"/>\n'
        "  </node>\n"
        "</launch>\n"
    )
    write(tmp_path, "src/planning_launch/launch/planning.launch.xml", launch)
    found = deep_findings(run_cli, tmp_path)
    assert [(f["line"], f["message"]) for f in found] == [
        (
            4,
            "remap target '/planning/scenario_planning/lane_driving/motion_planning/trajectory'"
            " has 5 levels; the limit is 4 (max-depth)",
        )
    ]


# ---------------------------------------------------------------------------------------
# One copy per robot: husky's multi-robot playpen, reduced

REALSENSE_LAUNCH = """\
<launch>
  <node pkg="pointcloud_to_laserscan" type="pointcloud_to_laserscan_node"
        name="realsense_to_laserscan">
    <remap from="cloud_in" to="realsense/depth/color/points"/>
    <remap from="scan" to="realsense/scan"/>
  </node>
</launch>
"""
SPAWN_LAUNCH = """\
<launch>
  <arg name="robot_namespace" default="/"/>
  <group ns="$(arg robot_namespace)">
    <include file="$(find husky_gazebo)/launch/realsense.launch"/>
  </group>
</launch>
"""
PLAYPEN_LAUNCH = """\
<launch>
  <include file="$(find husky_gazebo)/launch/spawn_husky.launch">
    <arg name="robot_namespace" value="husky_alpha"/>
  </include>
  <include file="$(find husky_gazebo)/launch/spawn_husky.launch">
    <arg name="robot_namespace" value="husky_beta"/>
  </include>
</launch>
"""


def husky_workspace(root: Path, playpen: str) -> None:
    package = root / "src" / "husky_gazebo"
    write(package, "package.xml", CATKIN_PACKAGE.format(name="husky_gazebo"))
    write(package, "launch/realsense.launch", REALSENSE_LAUNCH)
    write(package, "launch/spawn_husky.launch", SPAWN_LAUNCH)
    write(package, "launch/multi_husky_playpen.launch", playpen)


def test_a_level_each_robots_copy_differs_in_is_not_counted(run_cli: Any, tmp_path: Path) -> None:
    """Before, '/husky_alpha/realsense/depth/color/points' was 5 levels: the robot's own
    namespace, the separation RN202 asks for, counted against the name."""
    husky_workspace(tmp_path, PLAYPEN_LAUNCH)
    assert deep_findings(run_cli, tmp_path) == []


def test_one_namespaced_copy_gives_no_such_evidence(run_cli: Any, tmp_path: Path) -> None:
    one_robot = PLAYPEN_LAUNCH.split("  <include", 2)
    husky_workspace(tmp_path, "<launch>\n  <include" + one_robot[1] + "</launch>\n")
    (found,) = deep_findings(run_cli, tmp_path)
    assert "resolves to '/husky_alpha/realsense/depth/color/points'" in found["message"]

"""RN406 on nodes that load pluginlib plugins, and on files also handed to a node whose
name is unknown (issue 28).

A node that loads plugins may be given any name a plugin declares on it, so it was never
judged. Where its plugins are its own (nav2_amcl's motion models, slam_toolbox's Ceres
solver: a base class of the node's package, every implementation in it), their
declarations are the package's and the node is judged whole; where the base class is
another package's extension point (nav2_core's ``Controller``, opennav_docking_core's
``ChargingDock``), plugins may come from anywhere, and only the groups the node's own code
declares names in (opennav_docking's ``controller.``) are judged.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import ament_package, findings_of, write

LOCALIZER_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(pose_localizer)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(pluginlib REQUIRED)
find_package(geometry_msgs REQUIRED)
add_library(motion_models SHARED src/motion_model/differential_motion_model.cpp)
ament_target_dependencies(motion_models pluginlib)
pluginlib_export_plugin_description_file(pose_localizer plugins.xml)
add_executable(localizer src/main.cpp src/localizer.cpp)
ament_target_dependencies(localizer rclcpp pluginlib geometry_msgs)
install(TARGETS localizer motion_models DESTINATION lib/${PROJECT_NAME})
install(DIRECTORY config launch DESTINATION share/${PROJECT_NAME})
ament_package()
"""

MOTION_MODEL_HPP = """\
#pragma once

namespace {namespace}
{{
class MotionModel
{{
public:
  virtual ~MotionModel() = default;
  virtual void initialize(double alpha1, double alpha2) = 0;
}};
}}  // namespace {namespace}
"""

DIFFERENTIAL_HPP = """\
#pragma once
#include "{header}"

namespace pose_localizer
{{
class DifferentialMotionModel : public {base}
{{
public:
  void initialize(double alpha1, double alpha2) override;

private:
  double alpha1_{{0.2}};
  double alpha2_{{0.2}};
}};
}}  // namespace pose_localizer
"""

DIFFERENTIAL_CPP = """\
#include "pose_localizer/motion_model/differential_motion_model.hpp"

#include <pluginlib/class_list_macros.hpp>

namespace pose_localizer
{{
void DifferentialMotionModel::initialize(double alpha1, double alpha2)
{{
  alpha1_ = alpha1;
  alpha2_ = alpha2;
}}
}}  // namespace pose_localizer

PLUGINLIB_EXPORT_CLASS(pose_localizer::DifferentialMotionModel, {base})
"""

LOCALIZER_HPP = """\
#pragma once
#include <memory>
#include <string>

#include "geometry_msgs/msg/pose_stamped.hpp"
#include "pluginlib/class_loader.hpp"
#include "rclcpp/rclcpp.hpp"
#include "{header}"

namespace pose_localizer
{{
class Localizer : public rclcpp::Node
{{
public:
  explicit Localizer(const rclcpp::NodeOptions & options = rclcpp::NodeOptions());

private:
  double laser_max_range_;
  double controller_gain_;
  std::string robot_model_type_;
  pluginlib::ClassLoader<{base}> plugin_loader_{{"{base_package}", "{base}"}};
  std::shared_ptr<{base}> motion_model_;
  rclcpp::Publisher<geometry_msgs::msg::PoseStamped>::SharedPtr pose_publisher_;
}};
}}  // namespace pose_localizer
"""

LOCALIZER_CPP = """\
#include "pose_localizer/localizer.hpp"

namespace pose_localizer
{
Localizer::Localizer(const rclcpp::NodeOptions & options)
: rclcpp::Node("localizer", options)
{
  laser_max_range_ = declare_parameter("laser_max_range", 100.0);
  controller_gain_ = declare_parameter("controller.gain", 1.0);
  robot_model_type_ = declare_parameter(
    "robot_model_type", std::string("pose_localizer::DifferentialMotionModel"));
  motion_model_ = plugin_loader_.createSharedInstance(robot_model_type_);
  motion_model_->initialize(0.2, 0.2);
  pose_publisher_ = create_publisher<geometry_msgs::msg::PoseStamped>("pose", 10);
}
}  // namespace pose_localizer
"""

LOCALIZER_MAIN = """\
#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "pose_localizer/localizer.hpp"

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<pose_localizer::Localizer>());
  rclcpp::shutdown();
  return 0;
}
"""

LOCALIZER_PARAMS = """\
localizer:
  ros__parameters:
    laser_max_rang: 100.0
    robot_model_type: "pose_localizer::DifferentialMotionModel"
    controller:
      gian: 1.0
"""

LOCALIZER_LAUNCH = """\
<launch>
  <node pkg="pose_localizer" exec="localizer" name="localizer">
    <param from="$(find-pkg-share pose_localizer)/config/localizer.yaml"/>
  </node>
</launch>
"""

PLUGINS_XML = """\
<library path="motion_models">
  <class type="pose_localizer::DifferentialMotionModel" base_class_type="{base}">
    <description>A differential drive's motion model.</description>
  </class>
</library>
"""

PARAMS = "src/pose_localizer/config/localizer.yaml"


def localizer(root: Path, *, core: bool) -> Path:
    """The localizer and its motion model plugin; with ``core``, the plugins' base class
    is another package's (an extension point), else the localizer's own."""
    namespace = "localizer_core" if core else "pose_localizer"
    header = f"{namespace}/motion_model.hpp"
    base = f"{namespace}::MotionModel"
    directory = ament_package(root, "pose_localizer", LOCALIZER_CMAKE)
    home = ament_package(root, "localizer_core") if core else directory
    write(home, f"include/{header}", MOTION_MODEL_HPP.format(namespace=namespace))
    values = {"header": header, "base": base, "base_package": namespace}
    write(
        directory,
        "include/pose_localizer/motion_model/differential_motion_model.hpp",
        DIFFERENTIAL_HPP.format(**values),
    )
    write(
        directory,
        "src/motion_model/differential_motion_model.cpp",
        DIFFERENTIAL_CPP.format(**values),
    )
    write(directory, "include/pose_localizer/localizer.hpp", LOCALIZER_HPP.format(**values))
    write(directory, "src/localizer.cpp", LOCALIZER_CPP)
    write(directory, "src/main.cpp", LOCALIZER_MAIN)
    write(directory, "plugins.xml", PLUGINS_XML.format(base=base))
    write(directory, "config/localizer.yaml", LOCALIZER_PARAMS)
    write(directory, "launch/localizer.launch.xml", LOCALIZER_LAUNCH)
    return directory


def found_names(run_cli: Any, root: Path) -> list[tuple[str, int, str]]:
    found = findings_of(run_cli, root, "RN406")
    return sorted((f["path"], f["line"], f["message"].split("'")[1]) for f in found)


def test_a_node_whose_plugins_are_its_own_is_judged_whole(run_cli: Any, tmp_path: Path) -> None:
    localizer(tmp_path, core=False)
    assert found_names(run_cli, tmp_path) == [
        (PARAMS, 3, "laser_max_rang"),
        (PARAMS, 6, "controller.gian"),
    ]


def test_plugins_of_another_package_s_base_leave_only_the_node_s_own_groups_judged(
    run_cli: Any, tmp_path: Path
) -> None:
    """A plugin of ``localizer_core::MotionModel`` may come from any package, installed
    ones among them, and declare any top-level name: ``laser_max_rang`` is left alone.
    ``controller.`` is a group the node's own code declares in."""
    localizer(tmp_path, core=True)
    assert found_names(run_cli, tmp_path) == [(PARAMS, 6, "controller.gian")]


def test_a_plugin_of_another_package_leaves_the_node_unjudged(run_cli: Any, tmp_path: Path) -> None:
    """An implementation in another package of the workspace: the plugins are not all
    the node's package's, so their names are not all in its declarations."""
    directory = localizer(tmp_path, core=False)
    other = ament_package(tmp_path, "omni_models")
    write(
        other,
        "include/omni_models/omni_motion_model.hpp",
        DIFFERENTIAL_HPP.format(
            header="pose_localizer/motion_model.hpp", base="pose_localizer::MotionModel"
        ).replace("DifferentialMotionModel", "OmniMotionModel"),
    )
    assert (directory / "config/localizer.yaml").is_file()
    assert found_names(run_cli, tmp_path) == [(PARAMS, 6, "controller.gian")]


# nav2's slam_launch.py starts map_saver_server without a name and hands it the same
# nav2_params.yaml as every other server: any key of the file may be that node's, but it
# keeps only what its code may declare.

UNNAMED_LAUNCH = """\
from launch import LaunchDescription
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare
from launch.substitutions import PathJoinSubstitution


def generate_launch_description():
    params = PathJoinSubstitution([FindPackageShare('pose_localizer'), 'config', 'localizer.yaml'])
    return LaunchDescription([
        Node(package='pose_localizer', executable='{executable}', parameters=[params]),
    ])
"""

SAVER_CPP = """\
#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

int main(int argc, char ** argv)
{{
  rclcpp::init(argc, argv);
  auto node = std::make_shared<rclcpp::Node>(
    std::string(argc > 1 ? argv[1] : "map_saver"), rclcpp::NodeOptions(){options});
  auto saved = node->create_publisher<std_msgs::msg::String>("saved", 10);
  node->declare_parameter("save_map_timeout", 2.0);
  rclcpp::spin(node);
  return 0;
}}
"""


def test_a_node_of_unknown_name_keeps_only_what_its_code_takes(
    run_cli: Any, tmp_path: Path
) -> None:
    directory = localizer(tmp_path, core=False)
    write(directory, "src/map_saver.cpp", SAVER_CPP.format(options=""))
    cmake = LOCALIZER_CMAKE.replace(
        "install(TARGETS",
        "add_executable(map_saver src/map_saver.cpp)\n"
        "ament_target_dependencies(map_saver rclcpp std_msgs)\ninstall(TARGETS",
    )
    write(directory, "CMakeLists.txt", cmake)
    write(directory, "launch/saver.launch.py", UNNAMED_LAUNCH.format(executable="map_saver"))
    assert found_names(run_cli, tmp_path) == [
        (PARAMS, 3, "laser_max_rang"),
        (PARAMS, 6, "controller.gian"),
    ]
    # A saver that takes any parameter (allow_undeclared_parameters) may be the one the
    # file's names are for: they are left alone.
    allowing = SAVER_CPP.format(options=".allow_undeclared_parameters(true)")
    write(directory, "src/map_saver.cpp", allowing)
    assert found_names(run_cli, tmp_path) == []


# laser_filters' scan_to_scan_filter_chain (ros2 branch), reduced: a filters library chain
# declares each filterN.name and filterN.type, its filters their filterN.params.*
# (ros/filters include/filters/filter_chain.hpp, load_chain_config; filter_base.hpp,
# FilterBase::getParamImpl); the node's own reads are its own.

CHAIN_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(scan_filtering)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(filters REQUIRED)
find_package(sensor_msgs REQUIRED)
add_executable(scan_to_scan_filter_chain src/scan_to_scan_filter_chain.cpp)
ament_target_dependencies(scan_to_scan_filter_chain rclcpp filters sensor_msgs)
install(TARGETS scan_to_scan_filter_chain DESTINATION lib/${PROJECT_NAME})
install(DIRECTORY config launch DESTINATION share/${PROJECT_NAME})
ament_package()
"""

CHAIN_CPP = """\
#include <memory>
#include <string>

#include "filters/filter_chain.hpp"
#include "rclcpp/rclcpp.hpp"
#include "sensor_msgs/msg/laser_scan.hpp"

class ScanToScanFilterChain
{
public:
  explicit ScanToScanFilterChain(rclcpp::Node::SharedPtr node)
  : node_(node), filter_chain_("sensor_msgs::msg::LaserScan")
  {
    filter_chain_.configure(
      "", node_->get_node_logging_interface(), node_->get_node_parameters_interface());
    node_->declare_parameter("output_frame", std::string("laser"));
    node_->get_parameter_or("tf_message_filter_tolerance", tolerance_, 0.03);
    output_ = node_->create_publisher<sensor_msgs::msg::LaserScan>("scan_filtered", 10);
  }

private:
  rclcpp::Node::SharedPtr node_;
  filters::FilterChain<sensor_msgs::msg::LaserScan> filter_chain_;
  rclcpp::Publisher<sensor_msgs::msg::LaserScan>::SharedPtr output_;
  double tolerance_;
};

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("scan_to_scan_filter_chain");
  ScanToScanFilterChain chain(node);
  rclcpp::spin(node);
  return 0;
}
"""

CHAIN_PARAMS = """\
scan_to_scan_filter_chain:
  ros__parameters:
    output_frmae: laser_filtered
    filter1:
      name: angle
      type: laser_filters/LaserScanAngularBoundsFilter
      params:
        lower_angle: -1.52
        upper_angle: 1.52
"""

CHAIN_LAUNCH = """\
<launch>
  <node pkg="scan_filtering" exec="scan_to_scan_filter_chain"
        name="scan_to_scan_filter_chain">
    <param from="$(find-pkg-share scan_filtering)/config/angular_filter.yaml"/>
  </node>
</launch>
"""


def test_a_filter_chain_declares_its_filters_and_nothing_else(run_cli: Any, tmp_path: Path) -> None:
    """Every ``filter1.`` entry is the chain's, as its 52 entries in laser_filters'
    examples are (each was reported); a misspelt name of the node's own is still
    reported, and so is its read of a name nothing declares."""
    directory = ament_package(tmp_path, "scan_filtering", CHAIN_CMAKE)
    write(directory, "src/scan_to_scan_filter_chain.cpp", CHAIN_CPP)
    write(directory, "config/angular_filter.yaml", CHAIN_PARAMS)
    write(directory, "launch/filter.launch.xml", CHAIN_LAUNCH)
    params = "src/scan_filtering/config/angular_filter.yaml"
    assert found_names(run_cli, tmp_path) == [(params, 3, "output_frmae")]
    undeclared = findings_of(run_cli, tmp_path, "RN407")
    assert [(f["path"], f["line"]) for f in undeclared] == [
        ("src/scan_filtering/src/scan_to_scan_filter_chain.cpp", 17),
    ]

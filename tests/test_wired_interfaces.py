"""RN202 and a system's own global interfaces: an absolute name the workspace's launch
files remap a node to is chosen where the system is assembled, and code that writes it is
left alone; a name no launch file wires that way is still reported, whichever files a run
names. The workspace is autoware.core, reduced: autoware_motion_utils' vehicle state
checker subscribes to ``/localization/kinematic_state``, which the pure pursuit controller's
launch file wires its odometry input to."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from conftest import AMENT_PACKAGE, CATKIN_PACKAGE, write

from roslint_names.config import load_settings
from roslint_names.registry import load_registry
from roslint_names.session import Session

CHECKER = "src/autoware_motion_utils/src/vehicle/vehicle_state_checker.cpp"
LAUNCH = "src/autoware_simple_pure_pursuit/launch/simple_pure_pursuit.launch.xml"

CHECKER_CPP = """\
// Copyright 2022 TIER IV, Inc.
#include "autoware/motion_utils/vehicle/vehicle_state_checker.hpp"

#include <rclcpp/rclcpp.hpp>

#include <autoware_planning_msgs/msg/trajectory.hpp>
#include <nav_msgs/msg/odometry.hpp>

namespace autoware::motion_utils
{
using autoware_planning_msgs::msg::Trajectory;
using nav_msgs::msg::Odometry;

VehicleStopChecker::VehicleStopChecker(rclcpp::Node * node)
: VehicleStopCheckerBase(node, velocity_buffer_time_sec)
{
  using std::placeholders::_1;

  sub_odom_ = node->create_subscription<Odometry>(
    "/localization/kinematic_state", rclcpp::QoS(1),
    std::bind(&VehicleStopChecker::onOdom, this, _1));
}

VehicleArrivalChecker::VehicleArrivalChecker(rclcpp::Node * node) : VehicleStopChecker(node)
{
  using std::placeholders::_1;

  sub_trajectory_ = node->create_subscription<Trajectory>(
    "/planning/scenario_planning/trajectory", rclcpp::QoS(1),
    std::bind(&VehicleArrivalChecker::onTrajectory, this, _1));
}
}  // namespace autoware::motion_utils
"""
ODOMETRY_LINE = 20  # "/localization/kinematic_state"
TRAJECTORY_LINE = 29  # "/planning/scenario_planning/trajectory", which nothing wires here

CMAKE = """\
cmake_minimum_required(VERSION 3.14)
project(autoware_motion_utils)
find_package(autoware_cmake REQUIRED)
autoware_package()
ament_auto_add_library(autoware_motion_utils SHARED
  src/vehicle/vehicle_state_checker.cpp
)
ament_auto_package()
"""

PURE_PURSUIT_LAUNCH = """\
<launch>
  <arg name="vehicle_info_param_file"
    default="$(find-pkg-share autoware_vehicle_info_utils)/config/vehicle_info.param.yaml"/>

  <node pkg="autoware_simple_pure_pursuit" exec="autoware_simple_pure_pursuit_exe"
    name="simple_pure_pursuit" output="screen">
    <param from="$(var vehicle_info_param_file)"/>
    <remap from="~/input/odometry" to="/localization/kinematic_state"/>
    <remap from="~/output/control_command" to="/control/trajectory_follower/control_cmd"/>
  </node>
</launch>
"""


def autoware_workspace(root: Path, launch: str | None = PURE_PURSUIT_LAUNCH) -> Path:
    """The checker's package and, with ``launch``, the controller's."""
    package = root / "src" / "autoware_motion_utils"
    write(package, "package.xml", AMENT_PACKAGE.format(name="autoware_motion_utils"))
    write(package, "CMakeLists.txt", CMAKE)
    write(root, CHECKER, CHECKER_CPP)
    if launch is not None:
        controller = root / "src" / "autoware_simple_pure_pursuit"
        write(controller, "package.xml", AMENT_PACKAGE.format(name="autoware_simple_pure_pursuit"))
        write(root, LAUNCH, launch)
    return root


def absolute_names(run_cli: Any, root: Path, *arguments: str) -> list[tuple[str, int]]:
    """The places of the RN202 findings: a file that writes only absolute names is one
    finding, its other names related (``decisions``)."""
    result = run_cli(["check", "--format", "json", *arguments], root)
    assert result.exit_code in (0, 1), result.stderr
    return [
        (place["path"], place["line"])
        for f in result.findings()
        if f["code"] == "RN202"
        for place in (f, *f["related"])
    ]


# Whole workspace, the .cpp alone (its workspace gathered as context), each with the
# default rules (graph rules on) and with RN202 alone (no graph rule wants the context).
RUNS = [
    pytest.param(("src",), id="workspace"),
    pytest.param((CHECKER,), id="one-file"),
    pytest.param(("--select", "RN202", "src"), id="workspace-rn202-only"),
    pytest.param(("--select", "RN202", CHECKER), id="one-file-rn202-only"),
]


@pytest.mark.parametrize("arguments", RUNS)
def test_a_name_a_launch_file_remaps_a_node_to_is_left_alone(
    run_cli: Any, tmp_path: Path, arguments: tuple[str, ...]
) -> None:
    root = autoware_workspace(tmp_path)
    # The trajectory topic is wired by no launch file of this workspace: still reported.
    assert absolute_names(run_cli, root, *arguments) == [(CHECKER, TRAJECTORY_LINE)]


@pytest.mark.parametrize("arguments", RUNS)
def test_without_the_launch_file_the_name_is_reported(
    run_cli: Any, tmp_path: Path, arguments: tuple[str, ...]
) -> None:
    root = autoware_workspace(tmp_path, launch=None)
    found = absolute_names(run_cli, root, *arguments)
    assert found == [(CHECKER, ODOMETRY_LINE), (CHECKER, TRAJECTORY_LINE)]


# What a launch file may write of the name without wiring a node to it.
NOT_WIRING = {
    # UR's ur_control.launch.py: trajectory_until_node hard-codes the absolute
    # /motion_controller/follow_joint_trajectory, and the launch file moves it away.
    "remap-source": '<remap from="/localization/kinematic_state" to="~/input/odometry"/>',
    # A string handed to a node, which may or may not use it as a name.
    "parameter-value": '<param name="odometry_topic" value="/localization/kinematic_state"/>',
    # A relative target the node's namespace would resolve to it, were it in the root.
    "relative-target": '<remap from="~/input/odometry" to="localization/kinematic_state"/>',
}


@pytest.mark.parametrize("line", NOT_WIRING.values(), ids=NOT_WIRING.keys())
def test_a_launch_file_that_only_mentions_the_name_wires_nothing(
    run_cli: Any, tmp_path: Path, line: str
) -> None:
    launch = PURE_PURSUIT_LAUNCH.replace(
        '<remap from="~/input/odometry" to="/localization/kinematic_state"/>', line
    )
    root = autoware_workspace(tmp_path, launch)
    found = absolute_names(run_cli, root, "src")
    assert found == [(CHECKER, ODOMETRY_LINE), (CHECKER, TRAJECTORY_LINE)]


@pytest.mark.parametrize("arguments", RUNS)
def test_a_test_launch_file_wires_a_harness_not_the_system(
    run_cli: Any, tmp_path: Path, arguments: tuple[str, ...]
) -> None:
    root = autoware_workspace(tmp_path, launch=None)
    controller = root / "src" / "autoware_simple_pure_pursuit"
    write(controller, "package.xml", AMENT_PACKAGE.format(name="autoware_simple_pure_pursuit"))
    write(controller, "test/simple_pure_pursuit_test.launch.xml", PURE_PURSUIT_LAUNCH)
    found = absolute_names(run_cli, root, *arguments)
    assert found == [(CHECKER, ODOMETRY_LINE), (CHECKER, TRAJECTORY_LINE)]


FACTOR_INTERFACE = (
    "src/autoware_planning_factor_interface/include/autoware/planning_factor_interface/"
    "planning_factor_interface.hpp"
)
FACTOR_INTERFACE_HPP = """\
#ifndef AUTOWARE__PLANNING_FACTOR_INTERFACE__PLANNING_FACTOR_INTERFACE_HPP_
#define AUTOWARE__PLANNING_FACTOR_INTERFACE__PLANNING_FACTOR_INTERFACE_HPP_

#include <rclcpp/rclcpp.hpp>

#include <autoware_internal_planning_msgs/msg/planning_factor_array.hpp>

#include <string>

namespace autoware::planning_factor_interface
{
using autoware_internal_planning_msgs::msg::PlanningFactorArray;

class PlanningFactorInterface
{
public:
  PlanningFactorInterface(rclcpp::Node * node, const std::string & name)
  : name_{name},
    pub_factors_{
      node->create_publisher<PlanningFactorArray>("/planning/planning_factors/" + name, 1)},
    clock_{node->get_clock()}
  {
  }

private:
  std::string name_;
  rclcpp::Publisher<PlanningFactorArray>::SharedPtr pub_factors_;
  rclcpp::Clock::SharedPtr clock_;
};
}  // namespace autoware::planning_factor_interface

#endif  // AUTOWARE__PLANNING_FACTOR_INTERFACE__PLANNING_FACTOR_INTERFACE_HPP_
"""
ADAPI_LAUNCH = """\
<launch>
  <node pkg="autoware_default_adapi" exec="planning_factor_relay" name="planning_factor_relay">
    <remap from="~/input/factors" to="{target}"/>
  </node>
</launch>
"""


@pytest.mark.parametrize(
    ("target", "reported"),
    [
        ("/planning/planning_factors/obstacle_stop", False),
        ("/planning/velocity_factors/obstacle_stop", True),
        # A remap to the tree itself is no name the prefix starts.
        ("/planning/planning_factors", True),
    ],
)
def test_a_prefix_is_left_alone_when_a_wired_name_starts_with_it(
    run_cli: Any, tmp_path: Path, target: str, reported: bool
) -> None:
    package = tmp_path / "src" / "autoware_planning_factor_interface"
    write(package, "package.xml", AMENT_PACKAGE.format(name="autoware_planning_factor_interface"))
    write(tmp_path, FACTOR_INTERFACE, FACTOR_INTERFACE_HPP)
    adapi = tmp_path / "src" / "autoware_default_adapi"
    write(adapi, "package.xml", AMENT_PACKAGE.format(name="autoware_default_adapi"))
    write(adapi, "launch/adapi.launch.xml", ADAPI_LAUNCH.format(target=target))
    found = absolute_names(run_cli, tmp_path, FACTOR_INTERFACE)
    assert found == ([(FACTOR_INTERFACE, 20)] if reported else [])


HARNESS_CPP = """\
#include <gazebo/common/Plugin.hh>
#include <ros/ros.h>
#include <std_msgs/Float32.h>

namespace gazebo
{
void GazeboRosHarness::Load(physics::ModelPtr _parent, sdf::ElementPtr _sdf)
{
  this->rosnode_ = new ros::NodeHandle(this->robotNamespace_);
  ros::SubscribeOptions so = ros::SubscribeOptions::create<std_msgs::Float32>(
      "/" + _parent->GetName() + "/harness/velocity", 1,
    boost::bind(&GazeboRosHarness::OnVelocity, this, _1),
    ros::VoidPtr(), &this->queue_);
  this->velocitySub_ = this->rosnode_->subscribe(so);
}
}  // namespace gazebo
"""
HARNESS_LAUNCH = """\
<launch>
  <node name="teleop" pkg="teleop_twist_keyboard" type="teleop_twist_keyboard.py">
    <remap from="cmd_vel" to="/box/harness/velocity"/>
  </node>
</launch>
"""


def test_a_bare_slash_prefix_says_nothing_of_the_interface(run_cli: Any, tmp_path: Path) -> None:
    # gazebo_ros_pkgs' gazebo_ros_harness.cpp: "/" + the model's name; any absolute remap
    # target starts with "/", and that says nothing of which name the plugin uses.
    package = tmp_path / "src" / "gazebo_plugins"
    write(package, "package.xml", CATKIN_PACKAGE.format(name="gazebo_plugins"))
    write(package, "src/gazebo_ros_harness.cpp", HARNESS_CPP)
    write(package, "launch/harness.launch", HARNESS_LAUNCH)
    found = absolute_names(run_cli, tmp_path, "src")
    assert found == [("src/gazebo_plugins/src/gazebo_ros_harness.cpp", 11)]


def test_a_one_file_run_follows_the_launch_files_through_the_run_cache(
    run_cli: Any, tmp_path: Path, extractions: list[str]
) -> None:
    root = autoware_workspace(tmp_path)

    def check() -> Any:
        arguments = ["check", "--verbose", "--format", "json", "--select", "RN202", CHECKER]
        return run_cli(arguments, root)

    assert [f["line"] for f in check().findings()] == [TRAJECTORY_LINE]
    assert "its result reused" in check().stderr
    # The launch file's wiring changes; the checker's bytes, and so its facts, do not.
    launch = root / LAUNCH
    launch.write_text(launch.read_text().replace("/localization/kinematic_state", "odometry"))
    extractions.clear()
    after = check()
    assert "its result reused" not in after.stderr
    assert [(f["line"], len(f["related"])) for f in after.findings()] == [(ODOMETRY_LINE, 1)]
    assert extractions == [LAUNCH]


def test_an_editor_session_follows_the_launch_files(tmp_path: Path) -> None:
    root = autoware_workspace(tmp_path)
    registry = load_registry()
    session = Session(root, load_settings(None, root, registry), registry, None)
    session.load()

    def absolute() -> list[int]:
        found = session.check(root / CHECKER, CHECKER_CPP) or []
        return [
            line
            for d in found
            if d.code == "RN202"
            for line in (d.span.line, *(r.span.line for r in d.related))
        ]

    assert absolute() == [TRAJECTORY_LINE]
    unwired = PURE_PURSUIT_LAUNCH.replace("/localization/kinematic_state", "odometry")
    session.check(root / LAUNCH, unwired)
    assert absolute() == [ODOMETRY_LINE, TRAJECTORY_LINE]
    session.close(root / LAUNCH)  # back to the file on disk, which wires it
    assert absolute() == [TRAJECTORY_LINE]


# autoware.core's planning launch, reduced: three nodes' outputs wired into /planning/...,
# which makes /planning a tree the system lays out.
PLANNING_LAUNCH = """\
<launch>
  <node pkg="autoware_path_generator" exec="path_generator_node" name="path_generator">
    <remap from="~/output/path" to="/planning/scenario_planning/lane_driving/path"/>
  </node>
  <node pkg="autoware_velocity_smoother" exec="velocity_smoother_node" name="velocity_smoother">
    <remap from="~/input/trajectory" to="/planning/scenario_planning/scenario_selector/trajectory"/>
    <remap from="~/output/trajectory" to="/planning/scenario_planning/smoother/trajectory"/>
  </node>
</launch>
"""
PLANNING_LAUNCH_FILE = "src/autoware_core_planning/launch/autoware_core_planning.launch.xml"


@pytest.mark.parametrize(
    ("wired", "expected"),
    [
        # Three wired names under /planning: the checker's trajectory is a branch of it.
        (3, []),
        # Two say nothing of a tree: the name is reported, as before.
        (2, [(CHECKER, TRAJECTORY_LINE)]),
    ],
)
def test_a_name_under_a_tree_the_launch_files_lay_out_is_left_alone(
    run_cli: Any, tmp_path: Path, wired: int, expected: list[tuple[str, int]]
) -> None:
    root = autoware_workspace(tmp_path)
    planning = root / "src" / "autoware_core_planning"
    write(planning, "package.xml", AMENT_PACKAGE.format(name="autoware_core_planning"))
    launch = PLANNING_LAUNCH
    if wired == 2:
        launch = launch.replace(
            '    <remap from="~/input/trajectory" '
            'to="/planning/scenario_planning/scenario_selector/trajectory"/>\n',
            "",
        )
    write(root, PLANNING_LAUNCH_FILE, launch)
    assert absolute_names(run_cli, root) == expected
    assert absolute_names(run_cli, root, CHECKER) == expected

"""Templates a generator fills in: their placeholders are not findings, the rest is
judged as any file (``templates``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import write, write_package

from roslint_names.templates import holds_placeholder, is_template

# The MoveIt Setup Assistant's moveit_config_pkg_template/launch/gazebo.launch (MoveIt 1),
# reduced: a placeholder where an attribute goes, one inside a name, and a node name the
# template itself gets wrong (copied into every generated package as it is).
GAZEBO_TEMPLATE = """<?xml version="1.0"?>
<launch>
  <!-- Gazebo options -->
  <arg name="gazebo_gui" default="true" doc="Start Gazebo GUI"/>
  <arg name="paused" default="false" doc="Start Gazebo paused"/>
  <arg name="initial_joint_positions" default="[GAZEBO_INITIAL_JOINTS]"/>

  <include file="$(find gazebo_ros)/launch/empty_world.launch" pass_all_args="true">
    <arg name="paused" value="true"/>
  </include>

  <!-- Set the robot urdf on the parameter server -->
  <param name="robot_description" [GAZEBO_URDF_LOAD_ATTRIBUTE] />
</launch>
"""
CONTROLLERS_TEMPLATE = """<?xml version="1.0"?>
<launch>
  <rosparam file="$(find [GENERATED_PACKAGE_NAME])/config/ros_controllers.yaml" command="load"/>
  <node name="[ROBOT_NAME]_controller_spawner" pkg="controller_manager" type="spawner"/>
  <node name="joint-state-publisher" pkg="joint_state_publisher" type="joint_state_publisher"/>
</launch>
"""


def test_placeholders_in_a_template_folder_are_not_findings(run_cli: Any, tmp_path: Path) -> None:
    """Before, the gazebo template was one RN001 (the XML does not parse at the
    placeholder) and the spawner's name an RN101 for its '['."""
    template = "moveit_setup_assistant/templates/moveit_config_pkg_template/launch"
    write_package(tmp_path / "moveit_setup_assistant", 1, "moveit_setup_assistant")
    write(tmp_path, f"{template}/gazebo.launch", GAZEBO_TEMPLATE)
    write(tmp_path, f"{template}/ros_controllers.launch", CONTROLLERS_TEMPLATE)
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    found = [(f["path"], f["line"], f["code"]) for f in result.findings()]
    # The template's own mistake stays: every generated package would copy it.
    assert found == [(f"{template}/ros_controllers.launch", 5, "RN101")]


def test_the_same_lines_outside_a_template_folder_are_findings(
    run_cli: Any, tmp_path: Path
) -> None:
    write_package(tmp_path / "robot_moveit_config", 1, "robot_moveit_config")
    write(tmp_path, "robot_moveit_config/launch/gazebo.launch", GAZEBO_TEMPLATE)
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    assert [(f["line"], f["code"]) for f in result.findings()] == [(13, "RN001")]


def test_template_folders_and_placeholders() -> None:
    assert is_template("moveit_setup_assistant/templates/pkg/launch/demo.launch")
    assert is_template("ikfast_kinematics_plugin/templates/x.launch")
    assert is_template("my_pkg/launch_template/robot.launch")
    assert not is_template("robot_bringup/launch/templates.launch")  # a file, not a folder
    assert not is_template("robot_bringup/launch/robot.launch")
    text = 'a="[ROBOT_NAME]"\nb="@PROJECT_NAME@"\nc="{{ robot }}"\nd="[0, 1]"\ne="$(arg x)"\n'
    holding = {n for n, line in enumerate(text.splitlines(), start=1) if holds_placeholder(line)}
    assert holding == {1, 2, 3}

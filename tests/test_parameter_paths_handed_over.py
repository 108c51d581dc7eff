"""Parameter files named by the including launch file (issue 28).

Autoware's bringup names every node's parameter file in ``autoware_launch`` and hands the
path down: ``tier4_control_component.launch.xml`` passes ``<arg
name="shift_decider_param_path" value="$(find-pkg-share autoware_launch)/config/...">`` to
``control.launch.xml``, whose node reads ``<param from="$(var shift_decider_param_path)"/>``.
The value is not a static string (``find-pkg-share`` is the machine's install path), but
which package's file it is, the launch file says: the include hands that over
(``model.InPackage``), and the included file locates the file as if it had written the
path itself. Before, 182 of autoware_launch's 215 parameter-file references were unknown.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import CATKIN_PACKAGE, ament_package, findings_of, line_places, write
from test_unused_parameter import odom_publisher, path_controller

CONTROLLER_XML = """\
<launch>
  <arg name="controller_param_path"
       default="$(find-pkg-share path_controller)/config/controller.yaml"/>
  <arg name="namespace" default=""/>
  <node pkg="path_controller" exec="controller_server" name="controller_server"
        namespace="$(var namespace)">
    <param from="$(var controller_param_path)"/>
  </node>
</launch>
"""

BRINGUP_XML = """\
<launch>
  <arg name="config_dir" default="$(find-pkg-share robot_bringup)/config"/>
  <include file="$(find-pkg-share path_controller)/launch/controller.launch.xml">
    <arg name="namespace" value="robot1"/>
    <arg name="controller_param_path" value="$(var config_dir)/controller/controller.param.yaml"/>
  </include>
</launch>
"""

BRINGUP_PARAMS = """\
/**:
  ros__parameters:
    controller_frequency: 20.0
    FollowPath:
      max_vel_x: 0.26
      max_vel_theta: 1.0
"""


def bringup(root: Path, params: str = BRINGUP_PARAMS) -> Path:
    controller = path_controller(root)
    write(controller, "launch/controller.launch.xml", CONTROLLER_XML)
    directory = ament_package(root, "robot_bringup")
    write(directory, "launch/bringup.launch.xml", BRINGUP_XML)
    write(directory, "config/controller/controller.param.yaml", params)
    return directory


BRINGUP_PARAMETERS = "src/robot_bringup/config/controller/controller.param.yaml"


def test_a_file_the_includer_names_is_read_for_the_node(run_cli: Any, tmp_path: Path) -> None:
    bringup(tmp_path)
    assert findings_of(run_cli, tmp_path, "RN406") == []
    bringup(tmp_path, BRINGUP_PARAMS.replace("max_vel_x", "max_vel_X"))
    (found,) = findings_of(run_cli, tmp_path, "RN406")
    assert (found["path"], found["line"]) == (BRINGUP_PARAMETERS, 5)
    assert "for node '/robot1/controller_server'" in found["message"]
    assert "did you mean 'FollowPath.max_vel_x'?" in found["message"]
    sites = {(r["path"], r["line"]) for r in found["related"]}
    assert ("src/path_controller/launch/controller.launch.xml", 7) in sites


def test_the_same_stale_name_in_two_copies_is_one_finding(run_cli: Any, tmp_path: Path) -> None:
    """Two copies of one file for two instances of one program (the package's own config
    for ``/controller_server``, the bringup's for ``/robot1/controller_server``): one
    decision about that program's parameter, reported once with the other copy related."""
    controller = path_controller(tmp_path)
    write(controller, "launch/controller.launch.xml", CONTROLLER_XML)
    stale = BRINGUP_PARAMS.replace("controller_frequency", "controller_frequncy")
    write(controller, "config/controller.yaml", stale)
    directory = ament_package(tmp_path, "robot_bringup")
    write(directory, "launch/bringup.launch.xml", BRINGUP_XML)
    write(directory, "config/controller/controller.param.yaml", stale)
    (found,) = findings_of(run_cli, tmp_path, "RN406")
    assert found["message"].endswith("(also written at 1 other place)")
    places = {(found["path"], found["line"])} | {
        (r["path"], r["line"]) for r in found["related"] if "also written" in r["message"]
    }
    assert places == {(BRINGUP_PARAMETERS, 3), ("src/path_controller/config/controller.yaml", 3)}


def test_a_relative_path_of_the_includer_is_not_handed_over(run_cli: Any, tmp_path: Path) -> None:
    """``$(dirname)`` is the including file's directory: the included file lives elsewhere,
    so the path means nothing there and the node's parameters stay unknown (no guess)."""
    directory = bringup(tmp_path, BRINGUP_PARAMS.replace("max_vel_x", "max_vel_X"))
    relative = BRINGUP_XML.replace(
        "$(var config_dir)/controller/controller.param.yaml",
        "$(dirname)/../config/controller/controller.param.yaml",
    )
    write(directory, "launch/bringup.launch.xml", relative)
    assert findings_of(run_cli, tmp_path, "RN406") == []


# ROS 1: ``<arg name="config" default="$(find pkg)/config/a.yaml"/>`` handed to an
# included file's ``<rosparam command="load" file="$(arg config)"/>`` inside its node.

ODOM_LAUNCH = """\
<launch>
  <arg name="config" default="$(find odom_publisher)/config/odom.yaml"/>
  <node pkg="odom_publisher" type="odom_publisher" name="odom_publisher">
    <rosparam command="load" file="$(arg config)"/>
  </node>
</launch>
"""

ROBOT_LAUNCH = """\
<launch>
  <arg name="robot_config" default="$(find robot_bringup)/config/odom.yaml"/>
  <group ns="robot1">
    <include file="$(find odom_publisher)/launch/odom.launch">
      <arg name="config" value="$(arg robot_config)"/>
    </include>
  </group>
</launch>
"""


def test_ros1_a_rosparam_file_the_includer_names(run_cli: Any, tmp_path: Path) -> None:
    """The odometry node of ``test_unused_parameter`` (it reads ``~rate`` and
    ``~frame_id``), launched by a file that loads the configuration its includer names."""
    odom = odom_publisher(tmp_path)
    write(odom, "launch/odom.launch", ODOM_LAUNCH)
    write(odom, "config/odom.yaml", "rate: 50.0\nframe_id: odom\n")
    robot = tmp_path / "src" / "robot_bringup"
    write(robot, "package.xml", CATKIN_PACKAGE.format(name="robot_bringup"))
    write(robot, "launch/robot.launch", ROBOT_LAUNCH)
    write(robot, "config/odom.yaml", "rate: 100.0\nframe_idd: odom\n")
    found = findings_of(run_cli, tmp_path, "RN406")
    assert line_places(found) == [("src/robot_bringup/config/odom.yaml", 2)]
    assert "for node '/robot1/odom_publisher'" in found[0]["message"]


# Python: nav2_bringup's bringup_launch.py declares ``params_file`` with a default in its
# package and hands it to navigation_launch.py, whose nodes take ``parameters=[params]``.

BRINGUP_PY = """\
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration
from launch_ros.substitutions import FindPackageShare
from launch.substitutions import PathJoinSubstitution


def generate_launch_description():
    bringup_dir = get_package_share_directory('robot_bringup')
    params_file = LaunchConfiguration('params_file')
    return LaunchDescription([
        DeclareLaunchArgument(
            'params_file',
            default_value=os.path.join(
                bringup_dir, 'config', 'controller', 'controller.param.yaml'),
        ),
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource(
                PathJoinSubstitution(
                    [FindPackageShare('path_controller'), 'launch', 'controller_py.launch.py'])
            ),
            launch_arguments={'params_file': params_file, 'namespace': 'robot1'}.items(),
        ),
    ])
"""

CONTROLLER_PY = """\
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    params_file = LaunchConfiguration('params_file')
    return LaunchDescription([
        DeclareLaunchArgument('params_file'),
        DeclareLaunchArgument('namespace', default_value=''),
        Node(
            package='path_controller',
            executable='controller_server',
            name='controller_server',
            namespace=LaunchConfiguration('namespace'),
            parameters=[params_file],
        ),
    ])
"""


def test_python_a_path_the_includer_declares_and_hands_over(run_cli: Any, tmp_path: Path) -> None:
    controller = path_controller(tmp_path)
    write(controller, "launch/controller_py.launch.py", CONTROLLER_PY)
    directory = ament_package(tmp_path, "robot_bringup")
    write(directory, "launch/bringup.launch.py", BRINGUP_PY)
    write(directory, "config/controller/controller.param.yaml", BRINGUP_PARAMS)
    assert findings_of(run_cli, tmp_path, "RN406") == []
    misspelled = BRINGUP_PARAMS.replace("max_vel_theta", "max_vel_theta_")
    write(directory, "config/controller/controller.param.yaml", misspelled)
    (found,) = findings_of(run_cli, tmp_path, "RN406")
    assert (found["path"], found["line"]) == (BRINGUP_PARAMETERS, 6)
    assert "for node '/robot1/controller_server'" in found["message"]

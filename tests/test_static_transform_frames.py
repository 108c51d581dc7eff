"""The frames a launch file gives static_transform_publisher as arguments: read by each
program's own rules (``extract/launch/static_transform.py``), quiet for RN205 (tf2 strips
a broadcast frame's slash), visible to the rules that judge every chosen frame (RN206)."""

from __future__ import annotations

from typing import Any

import pytest
from conftest import write, write_package

from roslint_names.extract.launch import static_transform, xml_launch, yaml_launch
from roslint_names.extract.launch.static_transform import CHILD_FRAME_API, FRAME_API, Program
from roslint_names.extract.python.extract import extract as extract_python
from roslint_names.model import FileFacts, Generation, Kind, Span
from roslint_names.rules import frame_id_leading_slash

# -- each program's command line ----------------------------------------------------------


def frame_words(which: Program, line: str) -> list[tuple[str, str]]:
    words = line.split()
    return [(words[f.index], f.api) for f in static_transform.frames(which, words)]


BOTH = [("/map", FRAME_API), ("/odom", CHILD_FRAME_API)]


@pytest.mark.parametrize(
    ("which", "line", "expected"),
    [
        # ROS 1 tf: x y z yaw pitch roll frame child period, or with a quaternion
        (Program.TF, "0 0 0 0 0 0 /map /odom 100", BOTH),
        (Program.TF, "0 0 0 0 0 0 1 /map /odom 100", BOTH),
        (Program.TF, "0 0 0 0 0 0 /map /odom", []),  # argc 9: tf prints its usage
        (Program.TF, "0 0 0 0 0 0 /map /odom 100 __name:=x tf:=tf_old", BOTH),
        # ROS 1 tf2_ros: no period
        (Program.TF2_ROS1, "0 0 0 0 0 0 /map /odom", BOTH),
        (Program.TF2_ROS1, "0 0 0 0 0 0 1 /map /odom", BOTH),
        (Program.TF2_ROS1, "0 0 0 0 0 0 /map /odom 100 extra", []),
        # ROS 2 tf2_ros: flags, in any order, or the deprecated positional forms
        (Program.TF2_ROS2, "--x 1 --frame-id /map --child-frame-id /odom", BOTH),
        (Program.TF2_ROS2, "--child-frame-id /odom --yaw 1.57 --frame-id /map", BOTH),
        (Program.TF2_ROS2, "0 0 0 0 0 0 /map /odom", BOTH),
        (Program.TF2_ROS2, "0 0 0 0 0 0 1 /map /odom", BOTH),
        (Program.TF2_ROS2, "--roll 1 0 0 0 0 0 0 /map /odom", BOTH),  # Euler flags may mix
        (Program.TF2_ROS2, "--frame-id /map --ros-args -r __node:=tf --", []),  # no child
        (Program.TF2_ROS2, "--frame-id /map --child-frame-id /odom --ros-args -p a:=b", BOTH),
        (Program.TF2_ROS2, "--x 1 0 0 0 0 0 0 /map /odom", []),  # old and new style
        (Program.TF2_ROS2, "--frame-id=/map --child-frame-id=/odom", []),  # no '=' form
        (Program.TF2_ROS2, "--frame-id /map --child-frame-id /odom --help", []),
        (Program.TF2_ROS2, "--frame-id /map --child-frame-id", []),  # a flag without value
    ],
)
def test_each_program_reads_its_frames_its_own_way(
    which: Program, line: str, expected: list[tuple[str, str]]
) -> None:
    assert frame_words(which, line) == expected


def test_which_program_a_launch_node_runs() -> None:
    assert static_transform.program("tf", "static_transform_publisher", True) is Program.TF
    assert static_transform.program("tf", "static_transform_publisher", False) is None
    name = "static_transform_publisher"
    assert static_transform.program("tf2_ros", name, True) is Program.TF2_ROS1
    assert static_transform.program("tf2_ros", name, False) is Program.TF2_ROS2
    assert static_transform.program("tf2_ros", "buffer_server", False) is None


def test_rn205_knows_the_apis_the_extractors_give_these_frames() -> None:
    assert {FRAME_API, CHILD_FRAME_API} <= frame_id_leading_slash._BROADCAST_APIS


# -- launch files --------------------------------------------------------------------------


def frames(facts: FileFacts) -> list[tuple[str, Span, str, bool]]:
    return [
        (use.value, use.span, use.api, use.dynamic) for use in facts.names if use.kind is Kind.FRAME
    ]


# ros-planning/navigation's clear_costmap_recovery/test/clear_tests.launch and
# gazebo_ros_pkgs' multi_robot_scenario.launch, together: tf's form with a period, an
# argument's default, and an argument that holds several words.
ROS1_LAUNCH = """<launch>
  <arg name="robot" default="r1"/>
  <arg name="pose" default="0 0 0 0 0 0"/>
  <node name="static_tf" pkg="tf" type="static_transform_publisher"
        args="0 0 0 0 0 0 /map /base_link 100" />
  <node args="$(arg pose) /$(arg robot)/odom $(arg robot)/base_footprint 50"
        pkg="tf" type="static_transform_publisher" name="base_to_odom_$(arg robot)"/>
  <node pkg="tf2_ros" type="static_transform_publisher" name="laser"
        args="0.1 0 0.2 0 0 0 1 base_link $(arg laser_frame)"/>
  <node pkg="tf2_ros" type="static_transform_publisher" name="quoted"
        args="0 0 0 0 0 0 '/map' odom"/>
</launch>
"""


def test_ros1_launch_args_frames() -> None:
    facts = xml_launch.extract(
        "test/clear_tests.launch", ROS1_LAUNCH.encode(), None, Generation.ROS1
    )
    assert frames(facts) == [
        ("/map", Span(5, 27, 5, 31), FRAME_API, False),
        ("/base_link", Span(5, 32, 5, 42), CHILD_FRAME_API, False),
        # the words of $(arg pose) come first; the frames follow at their own places
        ("/r1/odom", Span(6, 27, 6, 45), FRAME_API, False),
        ("r1/base_footprint", Span(6, 46, 6, 73), CHILD_FRAME_API, False),
        ("base_link", Span(9, 33, 9, 42), FRAME_API, False),
        # an argument with no default: a frame, but not a known one
        ("$(arg laser_frame)", Span(9, 43, 9, 61), CHILD_FRAME_API, True),
        # quotes, which roslaunch's shlex would pair up: not read
    ]


ROS2_XML = """<launch>
  <node pkg="tf2_ros" exec="static_transform_publisher" name="map_to_odom"
        args="--x 0.5 --frame-id /map --child-frame-id $(var odom_frame)
              --ros-args --log-level warn"/>
  <node pkg="tf2_ros" exec="static_transform_publisher" args="0 0 0 0 0 0 /odom base_footprint"/>
</launch>
"""


def test_ros2_launch_xml_args_frames() -> None:
    facts = xml_launch.extract("launch/tf.launch.xml", ROS2_XML.encode(), None, Generation.ROS2)
    assert frames(facts) == [
        ("/map", Span(3, 34, 3, 38), FRAME_API, False),
        ("$(var odom_frame)", Span(3, 56, 3, 73), CHILD_FRAME_API, True),
        ("/odom", Span(5, 75, 5, 80), FRAME_API, False),
        ("base_footprint", Span(5, 81, 5, 95), CHILD_FRAME_API, False),
    ]


ROS2_YAML = """launch:
- arg: {name: child, default: base_link}
- node:
    pkg: tf2_ros
    exec: static_transform_publisher
    args: --frame-id /odom --child-frame-id $(var child)
"""


def test_ros2_launch_yaml_args_frames() -> None:
    facts = yaml_launch.extract("launch/tf.launch.yaml", ROS2_YAML.encode(), None, Generation.ROS2)
    assert frames(facts) == [
        ("/odom", Span(6, 22, 6, 27), FRAME_API, False),
        ("base_link", Span(6, 45, 6, 57), CHILD_FRAME_API, False),
    ]


# navigation2's nav2_bringup/launch/tb4_loopback_simulation_launch.py (flags) and an older
# bringup's positional form, with a frame from a declared launch argument.
PYTHON_LAUNCH = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    base_frame = LaunchConfiguration('base_frame')
    static_tf = Node(
        package='tf2_ros',
        executable='static_transform_publisher',
        arguments=[
            '--x', '0.0', '--y', '0.0', '--z', '0.0',
            '--frame-id', base_frame, '--child-frame-id', '/base_link'],
    )
    legacy_tf = Node(
        arguments=['0', '0', '0', '0', '0', '0', '/map', LaunchConfiguration('odom')],
        package='tf2_ros',
        executable='static_transform_publisher',
        name='map_to_odom',
    )
    whole = Node(
        package='tf2_ros',
        executable='static_transform_publisher',
        arguments='0 0 0 0 0 0 /map /odom',
    )
    return LaunchDescription([
        DeclareLaunchArgument('base_frame', default_value='/base_footprint'),
        static_tf,
        legacy_tf,
        whole,
    ])
"""


def test_python_launch_arguments_frames() -> None:
    facts = extract_python("launch/tf.launch.py", PYTHON_LAUNCH.encode(), None, Generation.ROS2)
    assert frames(facts) == [
        ("/base_footprint", Span(14, 27, 14, 37), FRAME_API, False),
        ("/base_link", Span(14, 59, 14, 71), CHILD_FRAME_API, False),
        ("/map", Span(17, 50, 17, 56), FRAME_API, False),
        ("LaunchConfiguration('odom')", Span(17, 58, 17, 85), CHILD_FRAME_API, True),
        # `arguments='...'`: launch_ros adds the string's characters one by one
    ]


# -- what the rules make of them ------------------------------------------------------------

BRINGUP_XML = """<launch>
  <node pkg="tf2_ros" exec="static_transform_publisher" name="map_to_odom"
        args="--frame-id /map --child-frame-id /odom"/>
  <node pkg="tf2_ros" exec="static_transform_publisher" name="odom_to_base"
        args="0 0 0 0 0 0 /odom base-link"/>
  <node pkg="robot_localization" exec="ekf_node" name="ekf_filter_node">
    <param name="world_frame" value="/odom"/>
  </node>
</launch>
"""


def test_rn205_leaves_the_frames_of_args_alone(run_cli: Any, tmp_path: Any) -> None:
    write(tmp_path, "src/robot_bringup/launch/bringup.launch.xml", BRINGUP_XML)
    write_package(tmp_path / "src" / "robot_bringup", 2)
    result = run_cli(["check", "--format", "json", "--select", "RN205", "src"], tmp_path)
    # Only the EKF's world frame: the node looks transforms up with it.
    assert [f["line"] for f in result.findings()] == [7]


def test_a_frame_naming_policy_sees_the_frames_of_args(run_cli: Any, tmp_path: Any) -> None:
    write(tmp_path, "src/robot_bringup/launch/bringup.launch.xml", BRINGUP_XML)
    write_package(tmp_path / "src" / "robot_bringup", 2)
    write(tmp_path, "roslint-names.toml", "[naming]\nframe = '[a-z][a-z0-9_]*'\n")
    result = run_cli(["check", "--format", "json", "--select", "RN206", "src"], tmp_path)
    assert [(f["line"], f["column"], f["message"]) for f in result.findings()] == [
        (
            5,
            33,
            "frame id 'base-link' does not match the project's frame naming policy "
            "'[a-z][a-z0-9_]*'",
        ),
    ]

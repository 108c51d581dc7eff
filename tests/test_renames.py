"""RN203's fix: a rename offered only with every use of the name in the workspace."""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Any

from conftest import Run, write, write_package
from lxml import etree

from roslint_names.editing import fixing
from roslint_names.editing.files import Snapshot
from roslint_names.model import Diagnostic, Edit, Severity, Span

# A ROS 1 SLAM node as gmapping writes it: camelCase private parameters, read in two places.
SLAM_CPP = """#include <ros/ros.h>

class SlamNode
{
public:
  SlamNode() : private_nh_("~")
  {
    // The search window of the scan matcher.
    if (!private_nh_.getParam("minimumScore", minimum_score_))
      minimum_score_ = 0.0;
    private_nh_.param("kernelSize", kernel_size_, 1);
  }

private:
  ros::NodeHandle private_nh_;
  double minimum_score_;
  int kernel_size_;
};

int main(int argc, char** argv)
{
  ros::init(argc, argv, "slam_node");
  SlamNode node;
  ros::spin();
}
"""
# The bringup of another package tunes it.
BRINGUP_LAUNCH = """<launch>
  <arg name="scan_topic" default="base_scan"/>
  <!-- Tuned on the PR2's Hokuyo. -->
  <node pkg="slam" type="slam_node" name="slam">
    <remap from="scan" to="$(arg scan_topic)"/>
    <param name="minimumScore" value="50"/>
    <param name="kernelSize" value="1"/>
  </node>
</launch>
"""
# dynamic_reconfigure declares the same parameter: no extractor reads a .cfg.
SLAM_CFG = """#!/usr/bin/env python
from dynamic_reconfigure.parameter_generator_catkin import ParameterGenerator, int_t

gen = ParameterGenerator()
gen.add("kernelSize", int_t, 0, "search window of the scan matcher", 1, 0, 10)
exit(gen.generate("slam", "slam_node", "Slam"))
"""


def _slam_workspace(root: Path) -> None:
    write_package(root / "src/slam", 1, "slam")
    write(root, "src/slam/src/slam_node.cpp", SLAM_CPP)
    write_package(root / "src/robot_bringup", 1, "robot_bringup")
    write(root, "src/robot_bringup/launch/slam.launch", BRINGUP_LAUNCH)


def _check(run_cli: Any, root: Path, *arguments: str) -> Run:
    result: Run = run_cli(
        ["check", "--format", "json", "--unsafe-fixes", "--select", "RN203", *arguments, "."],
        root,
    )
    assert result.exit_code in (0, 1), result.stderr
    return result


def _fixes(result: Run) -> dict[str, Any]:
    return {f["message"].split("'")[1]: f["fix"] for f in result.findings()}


def test_a_rename_is_offered_with_every_use_of_the_name_in_the_workspace(
    run_cli: Any, tmp_path: Path
) -> None:
    _slam_workspace(tmp_path)
    fixes = _fixes(_check(run_cli, tmp_path))
    assert fixes["minimumScore"] == {
        "safe": False,
        "line": 9,
        "column": 32,
        "end_line": 9,
        "end_column": 44,
        "replacement": "minimum_score",
        "also": [
            {
                "path": "src/robot_bringup/launch/slam.launch",
                "line": 6,
                "column": 18,
                "end_line": 6,
                "end_column": 30,
                "replacement": "minimum_score",
            }
        ],
    }
    assert fixes["kernelSize"]["also"][0]["path"] == "src/robot_bringup/launch/slam.launch"

    # Without --unsafe-fixes a report does not search the workspace for renames.
    plain = run_cli(["check", "--format", "json", "--select", "RN203", "."], tmp_path)
    assert [f["fix"] for f in plain.findings()] == [None, None]

    # The text report marks only safe fixes; a rename is never one.
    text = run_cli(["check", "--select", "RN203", "."], tmp_path)
    assert not [line for line in text.stdout.splitlines() if line.endswith("[*]")]
    assert "fixed 0 findings" in run_cli(["check", "--fix", "."], tmp_path).stderr

    fixed = _check(run_cli, tmp_path, "--fix")
    assert "fixed 2 findings in 2 files" in fixed.stderr
    assert fixed.findings() == []
    launch = tmp_path / "src/robot_bringup/launch/slam.launch"
    assert launch.read_text(encoding="utf-8") == BRINGUP_LAUNCH.replace(
        '"minimumScore"', '"minimum_score"'
    ).replace('"kernelSize"', '"kernel_size"')
    etree.parse(str(launch))  # still well formed
    source = (tmp_path / "src/slam/src/slam_node.cpp").read_text(encoding="utf-8")
    assert source == SLAM_CPP.replace('"minimumScore"', '"minimum_score"').replace(
        '"kernelSize"', '"kernel_size"'
    )
    again = run_cli(["check", "--fix", "--unsafe-fixes", "."], tmp_path)
    assert "fixed 0 findings in 0 files" in again.stderr


def test_a_use_no_extractor_reads_keeps_the_rename_from_being_offered(
    run_cli: Any, tmp_path: Path
) -> None:
    """The .cfg would still declare `kernelSize`: renaming the code's would split them."""
    _slam_workspace(tmp_path)
    write(tmp_path, "src/slam/cfg/Slam.cfg", SLAM_CFG)
    fixes = _fixes(_check(run_cli, tmp_path))
    assert fixes["kernelSize"] is None
    assert fixes["minimumScore"] is not None  # the other name is not held back

    # Nor a name-shaped string of code that is no name the linter knows: a helper's key.
    write(
        tmp_path,
        "src/robot_bringup/scripts/tune.py",
        'import dynamic_reconfigure.client\n\nKEY = "minimumScore"\n',
    )
    fixes = _fixes(_check(run_cli, tmp_path))
    assert fixes == {"minimumScore": None, "kernelSize": None}

    # Identifiers, comments and documentation are no names: they hold nothing back.
    write(tmp_path, "src/slam/README.md", "Set `minimumScore` and `kernelSize` to tune.\n")
    (tmp_path / "src/slam/cfg/Slam.cfg").unlink()
    (tmp_path / "src/robot_bringup/scripts/tune.py").unlink()
    source = SLAM_CPP.replace("double minimum_score_;", "double minimumScore; // minimumScore")
    write(tmp_path, "src/slam/src/slam_node.cpp", source)
    fixes = _fixes(_check(run_cli, tmp_path))
    assert fixes["minimumScore"] is not None and fixes["kernelSize"] is not None


def test_a_suppressed_use_keeps_its_spelling_everywhere(run_cli: Any, tmp_path: Path) -> None:
    _slam_workspace(tmp_path)
    source = SLAM_CPP.replace(
        'private_nh_.param("kernelSize", kernel_size_, 1);',
        'private_nh_.param("kernelSize", kernel_size_, 1);  // NOLINT(RN203) the wiki spells it',
    ).replace(
        "    private_nh_.param",
        '    private_nh_.getParam("kernelSize", kernel_size_);\n    private_nh_.param',
    )
    write(tmp_path, "src/slam/src/slam_node.cpp", source)
    result = _check(run_cli, tmp_path)
    assert [(f["line"], f["fix"]) for f in result.findings() if "kernelSize" in f["message"]] == [
        (11, None)
    ]


# A ROS 2 component, started by a Python launch file and by an XML one of another package:
# the node name is spelled in three files and two languages.
IMU_FILTER_CPP = """#include <rclcpp/rclcpp.hpp>
#include <sensor_msgs/msg/imu.hpp>

namespace imu_tools
{
class ImuFilter : public rclcpp::Node
{
public:
  explicit ImuFilter(const rclcpp::NodeOptions & options)
  : Node("ImuFilter", options)
  {
    pub_ = create_publisher<sensor_msgs::msg::Imu>("imu/filtered", 10);
  }

private:
  rclcpp::Publisher<sensor_msgs::msg::Imu>::SharedPtr pub_;
};
}  // namespace imu_tools
"""
IMU_LAUNCH_PY = """from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(
            package='imu_tools',
            executable='imu_filter',
            name='ImuFilter',
            remappings=[('imu/filtered', 'imu/data')],
        ),
    ])
"""
ROBOT_LAUNCH_XML = """<launch>
  <node pkg="imu_tools" exec="imu_filter" name="ImuFilter" namespace="front"/>
</launch>
"""


def test_a_node_name_is_renamed_across_languages(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "src/imu_tools", 2, "imu_tools")
    write(tmp_path, "src/imu_tools/src/imu_filter.cpp", IMU_FILTER_CPP)
    write(tmp_path, "src/imu_tools/launch/imu.launch.py", IMU_LAUNCH_PY)
    write_package(tmp_path / "src/robot", 2, "robot")
    write(tmp_path, "src/robot/launch/robot.launch.xml", ROBOT_LAUNCH_XML)
    found = _check(run_cli, tmp_path).findings()
    # One name, one decision: one finding, whose rename reaches the other two files.
    assert [(f["path"], len(f["fix"]["also"])) for f in found] == [
        ("src/imu_tools/launch/imu.launch.py", 2)
    ]
    assert sorted(other["path"] for other in found[0]["fix"]["also"]) == [
        "src/imu_tools/src/imu_filter.cpp",
        "src/robot/launch/robot.launch.xml",
    ]
    fixed = _check(run_cli, tmp_path, "--fix")
    assert "fixed 1 finding in 3 files" in fixed.stderr
    assert fixed.findings() == []
    launch = (tmp_path / "src/imu_tools/launch/imu.launch.py").read_text(encoding="utf-8")
    assert launch == IMU_LAUNCH_PY.replace("'ImuFilter'", "'imu_filter'")
    ast.parse(launch)
    source = (tmp_path / "src/imu_tools/src/imu_filter.cpp").read_text(encoding="utf-8")
    assert source == IMU_FILTER_CPP.replace('Node("ImuFilter"', 'Node("imu_filter"')


def test_a_node_another_one_calls_by_name_is_not_renamed(run_cli: Any, tmp_path: Path) -> None:
    """ros2/demos' use_logger_service.py: the test node is handed the served node's name."""
    write_package(tmp_path / "src/chatter", 2, "chatter")
    write(
        tmp_path,
        "src/chatter/chatter/use_logger_service.py",
        """import rclpy
from rclpy.node import Node


class LoggerServiceNode(Node):
    def __init__(self):
        super().__init__('LoggerServiceNode', enable_logger_service=True)


class TestNode(Node):
    def __init__(self, remote_node_name):
        super().__init__('test_node')
        self.client = self.create_client(GetLoggerLevels, remote_node_name + '/get_logger_levels')


def main():
    rclpy.init()
    server = LoggerServiceNode()
    client = TestNode('LoggerServiceNode')
""",
    )
    assert _fixes(_check(run_cli, tmp_path)) == {"LoggerServiceNode": None}


def _diagnostic(path: str, line: int, text: str, *also: Edit) -> Diagnostic:
    span = Span(line, 1, line, 4)
    return Diagnostic(
        path,
        span,
        "RN203",
        "not-snake-case",
        Severity.WARNING,
        "m",
        edit=Edit(span, text, False),
        also=also,
    )


def test_a_fix_is_all_its_edits_or_none(tmp_path: Path) -> None:
    """A rename whose edit in one file is refused is not made in the others either."""
    (tmp_path / "a.launch").write_text("abc\n", encoding="utf-8")
    (tmp_path / "b.launch").write_text("abc\nxyz\n", encoding="utf-8")
    rename = _diagnostic("a.launch", 1, "ABC", Edit(Span(1, 1, 1, 4), "ABC", False, "b.launch"))
    alone = _diagnostic("b.launch", 2, "XYZ")

    def verify(path: str, data: bytes) -> tuple[int, set[tuple[str, int]]]:
        return (1 if path == "b.launch" and b"ABC" in data else 0), set()

    planned = fixing.plan(
        [rename, alone], unsafe=True, snapshot=Snapshot(tmp_path, [tmp_path]), verify=verify
    )
    assert planned.changes == (("b.launch", "abc\nxyz\n", "abc\nXYZ\n"),)
    assert planned.fixed == 1
    assert planned.refused == (("b.launch", "renames not applied: it would no longer parse"),)

    # Two fixes writing one span with different text: only the first is made.
    other = _diagnostic("b.launch", 1, "Abc")
    planned = fixing.plan(
        [rename, other],
        unsafe=True,
        snapshot=Snapshot(tmp_path, [tmp_path]),
        verify=lambda p, d: (0, set()),
    )
    assert [(path, after) for path, _, after in planned.changes] == [
        ("a.launch", "ABC\n"),
        ("b.launch", "ABC\nxyz\n"),
    ]

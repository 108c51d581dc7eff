"""Adopting the linter on an existing codebase: the baseline and the changed-lines gate."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from conftest import Run, write, write_package

# A ROS 1 bringup as a team has it when it adopts the linter: two findings to live with.
LEGACY_LAUNCH = """<launch>
  <node name="base-driver" pkg="robot_base" type="driver_node"/>
  <group ns="laser">
    <node name="laser-filter" pkg="laser_filters" type="scan_to_scan_filter_chain"/>
  </group>
</launch>
"""
SMOOTHER_CPP = """#include <ros/ros.h>
#include <geometry_msgs/Twist.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "velocity_smoother");
  ros::NodeHandle nh;
  ros::Publisher out = nh.advertise<geometry_msgs::Twist>("/mobile_base/cmd_vel", 10);
  ros::spin();
}
"""


def _workspace(root: Path) -> None:
    write_package(root / "src/robot_bringup", 1, "robot_bringup")
    write(root, "src/robot_bringup/launch/robot.launch", LEGACY_LAUNCH)
    write(root, "src/robot_bringup/src/velocity_smoother.cpp", SMOOTHER_CPP)


def _check(run_cli: Any, root: Path, *arguments: str) -> Run:
    result: Run = run_cli(["check", "--format", "json", *arguments, "."], root)
    assert result.exit_code in (0, 1), result.stderr
    return result


def _found(result: Run) -> list[tuple[str, int, str]]:
    return [(f["path"], f["line"], f["code"]) for f in result.findings()]


# ---------------------------------------------------------------------------------------
# Baseline


def test_a_baseline_lets_known_findings_through_and_catches_new_ones(
    run_cli: Any, tmp_path: Path
) -> None:
    _workspace(tmp_path)
    written = run_cli(["check", "--write-baseline", "baseline.json", "."], tmp_path)
    assert written.exit_code == 0
    assert "wrote 3 findings to baseline.json" in written.stderr
    clean = _check(run_cli, tmp_path, "--baseline", "baseline.json")
    assert (clean.exit_code, clean.findings()) == (0, [])
    assert "no new problems (3 more in the baseline)" in clean.stderr

    # Twenty lines above every finding move them; they stay known. A new node is new.
    launch = tmp_path / "src/robot_bringup/launch/robot.launch"
    comments = "".join(f"  <!-- tuning note {i} -->\n" for i in range(20))
    text = LEGACY_LAUNCH.replace("<launch>\n", "<launch>\n" + comments)
    text = text.replace(
        "</launch>", '  <node name="imu-driver" pkg="imu" type="imu_node"/>\n</launch>'
    )
    launch.write_text(text, encoding="utf-8")
    source = tmp_path / "src/robot_bringup/src/velocity_smoother.cpp"
    source.write_text("// Smooths teleop commands.\n" * 20 + SMOOTHER_CPP, encoding="utf-8")
    shifted = _check(run_cli, tmp_path, "--baseline", "baseline.json")
    assert shifted.exit_code == 1
    assert _found(shifted) == [("src/robot_bringup/launch/robot.launch", 26, "RN101")]


def test_an_edited_line_or_a_second_copy_is_new(run_cli: Any, tmp_path: Path) -> None:
    _workspace(tmp_path)
    run_cli(["check", "--write-baseline", "baseline.json", "."], tmp_path)
    launch = tmp_path / "src/robot_bringup/launch/robot.launch"
    text = LEGACY_LAUNCH.replace("base-driver", "base-driver-v2")  # the finding's line edited
    copy = '  <group ns="laser_rear">\n' + text.splitlines()[3] + "\n  </group>\n"
    text = text.replace("</launch>", copy + "</launch>")  # the same line again
    launch.write_text(text, encoding="utf-8")
    result = _check(run_cli, tmp_path, "--baseline", "baseline.json")
    # The copy is one decision with the known line (the node name 'laser-filter'): that
    # finding is new again, and names the copy.
    assert _found(result) == [
        ("src/robot_bringup/launch/robot.launch", 2, "RN101"),
        ("src/robot_bringup/launch/robot.launch", 4, "RN101"),
    ]
    assert [r["line"] for r in result.findings()[1]["related"]] == [7]


def test_stale_entries_are_named_with_verbose_and_dropped_when_rewritten(
    run_cli: Any, tmp_path: Path
) -> None:
    _workspace(tmp_path)
    baseline = tmp_path / "baseline.json"
    run_cli(["check", "--write-baseline", "baseline.json", "."], tmp_path)
    before = baseline.read_text(encoding="utf-8")
    launch = tmp_path / "src/robot_bringup/launch/robot.launch"
    launch.write_text(LEGACY_LAUNCH.replace("base-driver", "base_driver"), encoding="utf-8")
    result = _check(run_cli, tmp_path, "--baseline", "baseline.json", "--verbose")
    assert result.findings() == []
    assert (
        "baseline baseline.json: no longer found: src/robot_bringup/launch/robot.launch: "
        "RN101 'base-driver'"
    ) in result.stderr
    run_cli(["check", "--write-baseline", "baseline.json", "."], tmp_path)
    after = json.loads(baseline.read_text(encoding="utf-8"))["findings"]
    assert [entry["name"] for entry in after] == ["laser-filter", '"/mobile_base/cmd_vel"']
    assert len(json.loads(before)["findings"]) == 3


def test_the_baseline_file_is_stable_and_has_no_line_numbers(run_cli: Any, tmp_path: Path) -> None:
    _workspace(tmp_path)
    run_cli(["check", "--write-baseline", "one.json", "."], tmp_path)
    source = tmp_path / "src/robot_bringup/src/velocity_smoother.cpp"
    source.write_text("\n\n" + SMOOTHER_CPP, encoding="utf-8")
    run_cli(["check", "--write-baseline", "two.json", "."], tmp_path)
    one = (tmp_path / "one.json").read_text(encoding="utf-8")
    assert one == (tmp_path / "two.json").read_text(encoding="utf-8")
    document = json.loads(one)
    assert document["roslint-names-baseline"] == 1
    assert document["findings"][0] == {
        "path": "src/robot_bringup/launch/robot.launch",
        "code": "RN101",
        "name": "base-driver",
        "fingerprint": document["findings"][0]["fingerprint"],
    }


def test_sarif_marks_the_baseline_state(run_cli: Any, tmp_path: Path) -> None:
    _workspace(tmp_path)
    run_cli(["check", "--write-baseline", "baseline.json", "."], tmp_path)
    launch = tmp_path / "src/robot_bringup/launch/robot.launch"
    launch.write_text(
        LEGACY_LAUNCH.replace("</launch>", '<node name="imu-driver" pkg="i" type="i"/></launch>'),
        encoding="utf-8",
    )
    result = run_cli(["check", "--format", "sarif", "--baseline", "baseline.json", "."], tmp_path)
    results = json.loads(result.stdout)["runs"][0]["results"]
    states = sorted((r["baselineState"], r["ruleId"]) for r in results)
    assert states == [
        ("new", "RN101"),
        ("unchanged", "RN101"),
        ("unchanged", "RN101"),
        (
            "unchanged",
            "RN202",
        ),
    ]
    without = run_cli(["check", "--format", "sarif", "."], tmp_path)
    assert all("baselineState" not in r for r in json.loads(without.stdout)["runs"][0]["results"])


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (None, "baseline.json: cannot read baseline"),
        ("{not json", "baseline.json: not a roslint-names baseline"),
        ('{"findings": []}', "baseline.json: not a roslint-names baseline (format 1)"),
        (
            '{"roslint-names-baseline": 1, "findings": [{"path": 3}]}',
            "baseline.json: findings[0]: needs the strings path, code, name, fingerprint",
        ),
    ],
)
def test_a_bad_baseline_file_is_a_usage_error_naming_it(
    run_cli: Any, tmp_path: Path, content: str | None, message: str
) -> None:
    _workspace(tmp_path)
    if content is not None:
        write(tmp_path, "baseline.json", content)
    result = run_cli(["check", "--baseline", "baseline.json", "."], tmp_path)
    assert result.exit_code == 2
    assert message in result.stderr
    assert "Traceback" not in result.stderr


# ---------------------------------------------------------------------------------------
# Changed lines


def git(root: Path, *arguments: str) -> None:
    subprocess.run(
        ["git", "-c", "user.name=t", "-c", "user.email=t@example.com", *arguments],
        cwd=root,
        check=True,
        capture_output=True,
    )


POSE_PUBLISHER = """#include <ros/ros.h>
#include <geometry_msgs/PoseStamped.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "fleet_monitor");
  ros::NodeHandle nh;
  ros::Publisher pose = nh.advertise<geometry_msgs::PoseStamped>("/robot_pose", 10);
  ros::spin();
}
"""
POSE_RECORDER = """#!/usr/bin/env python
import rospy
from geometry_msgs.msg import PoseStamped

rospy.init_node("pose_recorder")
rospy.Subscriber("/Robot_Pose", PoseStamped, print)
rospy.spin()
"""


def test_changed_since_reports_only_what_the_change_brought_in(
    run_cli: Any, tmp_path: Path
) -> None:
    _workspace(tmp_path)
    write(tmp_path, "src/robot_bringup/src/fleet_monitor.cpp", POSE_PUBLISHER)
    git(tmp_path, "init", "-q")
    git(tmp_path, "add", "-A")
    git(tmp_path, "commit", "-qm", "the robot as it was")
    # The pull request: a node added to the launch file (committed), a script (not yet
    # tracked) that spells the monitor's topic in another case.
    launch = tmp_path / "src/robot_bringup/launch/robot.launch"
    launch.write_text(
        LEGACY_LAUNCH.replace(
            "</launch>", '  <node name="imu-driver" pkg="i" type="i"/>\n</launch>'
        ),
        encoding="utf-8",
    )
    git(tmp_path, "commit", "-qam", "an IMU")
    write(tmp_path, "src/robot_bringup/scripts/pose_recorder", POSE_RECORDER)
    everything = _check(run_cli, tmp_path)
    assert len(everything.findings()) == 8
    gated = _check(run_cli, tmp_path, "--changed-since", "HEAD~1")
    recorder = [
        ("src/robot_bringup/scripts/pose_recorder", 6, "RN202"),
        ("src/robot_bringup/scripts/pose_recorder", 6, "RN401"),
        # the other side of the case collision, in the unchanged file: related to a new line
        ("src/robot_bringup/src/fleet_monitor.cpp", 8, "RN401"),
    ]
    assert _found(gated) == [("src/robot_bringup/launch/robot.launch", 6, "RN101"), *recorder]
    assert _found(_check(run_cli, tmp_path, "--changed-since", "HEAD")) == recorder


@pytest.mark.skipif(sys.platform == "darwin", reason="macOS file names must be UTF-8")
def test_changed_since_keeps_a_new_error_in_a_file_whose_name_is_not_utf8(
    run_cli: Any, tmp_path: Path
) -> None:
    """A launch file named in Latin-1 (``caf\xe9.launch``, from an old system): git quotes
    its name in the diff, and prints it raw for an untracked file; both must still match
    the file the run reports, or its new error is filtered out and the gate passes."""
    write_package(tmp_path / "src/robot_bringup", 1)
    committed = os.fsdecode(os.fsencode(tmp_path) + b"/src/robot_bringup/launch/caf\xe9.launch")
    write(tmp_path, committed, LEGACY_LAUNCH)
    git(tmp_path, "init", "-q")
    git(tmp_path, "add", "-A")
    git(tmp_path, "commit", "-qm", "the robot as it was")
    Path(committed).write_text(
        LEGACY_LAUNCH.replace(
            "</launch>", '  <node name="imu-driver" pkg="i" type="i"/>\n</launch>'
        ),
        encoding="utf-8",
    )
    untracked = os.fsdecode(os.fsencode(tmp_path) + b"/src/robot_bringup/launch/gr\xfcn.launch")
    write(
        tmp_path, untracked, '<launch>\n  <node name="gps-driver" pkg="g" type="g"/>\n</launch>\n'
    )
    gated = _check(run_cli, tmp_path, "--changed-since", "HEAD")
    assert [(path, code) for path, _, code in _found(gated)] == [
        ("src/robot_bringup/launch/caf\\xe9.launch", "RN101"),
        ("src/robot_bringup/launch/gr\\xfcn.launch", "RN101"),
    ]


@pytest.mark.parametrize(
    ("init", "message"),
    [
        (True, "--changed-since: 'no-such-branch' is not a commit git knows here"),
        (False, "--changed-since: fatal: not a git repository"),
    ],
)
def test_changed_since_errors_say_what_is_wrong(
    run_cli: Any, tmp_path: Path, init: bool, message: str
) -> None:
    _workspace(tmp_path)
    if init:
        git(tmp_path, "init", "-q")
        git(tmp_path, "add", "-A")
        git(tmp_path, "commit", "-qm", "x")
    result = run_cli(["check", "--changed-since", "no-such-branch", "."], tmp_path)
    assert result.exit_code == 2
    assert message in result.stderr


# ---------------------------------------------------------------------------------------
# Suppressions added for every current finding

NOQA_CPP = """#include <ros/ros.h>  // NOLINT(build/include_order)
#include <geometry_msgs/Twist.h>

#define ADVERTISE(nh, topic) \\
  nh.advertise<geometry_msgs::Twist>(topic, 10)

int main(int argc, char** argv)
{
  ros::init(argc, argv, "velocity_smoother");
  ros::NodeHandle nh;
  ros::Publisher out = nh.advertise<geometry_msgs::Twist>("/mobile_base/cmd_vel", 10);
  ros::Publisher raw = nh.advertise<geometry_msgs::Twist>("/raw", 10);  // NOLINT(runtime/int)
  ros::Publisher level = nh.advertise<geometry_msgs::Twist>("level", 10);
  ros::spin();
}
"""
NOQA_PY = """#!/usr/bin/env python
import rospy
from geometry_msgs.msg import Twist

rospy.init_node("teleop")
pub = rospy.Publisher("/cmd_vel", Twist, queue_size=1)  # noqa: E501
alt = rospy.Publisher("/cmd_vel_alt", \\
                      Twist, queue_size=1)
status = rospy.Publisher("status", Twist, queue_size=1)
"""
NOQA_LAUNCH = """<launch>
  <node name="base-driver" pkg="robot_base" type="driver_node"/>
  <node pkg="laser_filters"
        name="laser-filter"
        type="scan_to_scan_filter_chain">
    <remap from="scan" to="base_scan"/>
  </node>
  <node name="imu-driver" ns="Imu" pkg="imu" type="imu_node"/> <!-- roslint-names: ignore RN203 -->
</launch>
"""
NOQA_YAML = """launch:
- node: {pkg: teleop_twist_joy, exec: teleop_node, name: teleop-joy}
"""


def test_add_noqa_writes_each_language_s_comment_and_merges_existing_ones(
    run_cli: Any, tmp_path: Path
) -> None:
    write_package(tmp_path / "src/base", 1, "base")
    write(tmp_path, "src/base/src/smoother.cpp", NOQA_CPP)
    write(tmp_path, "src/base/scripts/teleop", NOQA_PY)
    write(tmp_path, "src/base/launch/base.launch", NOQA_LAUNCH)
    write_package(tmp_path / "src/joy", 2, "joy")
    write(tmp_path, "src/joy/launch/joy.launch.yaml", NOQA_YAML)
    added = run_cli(["check", "--add-noqa", "."], tmp_path)
    assert "added 7 suppression comments in 4 files" in added.stderr
    # The continued line has no room for a comment: named, and still a finding.
    assert "src/base/scripts/teleop:7: not suppressed: the line ends inside" in added.stderr
    assert added.exit_code == 1

    cpp = (tmp_path / "src/base/src/smoother.cpp").read_text(encoding="utf-8").splitlines()
    # Both lines are too long for the comment after them (80 columns): on the line before.
    assert cpp[10:14] == [
        "  // roslint-names: ignore RN202",
        '  ros::Publisher out = nh.advertise<geometry_msgs::Twist>("/mobile_base/cmd_vel", 10);',
        "  // roslint-names: ignore RN202",
        '  ros::Publisher raw = nh.advertise<geometry_msgs::Twist>("/raw", 10);  '
        "// NOLINT(runtime/int)",
    ]
    python = (tmp_path / "src/base/scripts/teleop").read_text(encoding="utf-8").splitlines()
    assert python[4].endswith('rospy.init_node("teleop")')
    assert python[5].endswith("  # noqa: E501, RN202")
    launch = (tmp_path / "src/base/launch/base.launch").read_text(encoding="utf-8").splitlines()
    assert launch[1].endswith("/> <!-- roslint-names: ignore RN101 -->")
    # Inside a start tag over several lines: alone before the tag, which it covers whole.
    assert launch[2] == "  <!-- roslint-names: ignore RN101 -->"
    assert launch[8] == (
        '  <node name="imu-driver" ns="Imu" pkg="imu" type="imu_node"/> '
        "<!-- roslint-names: ignore RN203, RN101 -->"
    )
    yaml = (tmp_path / "src/joy/launch/joy.launch.yaml").read_text(encoding="utf-8")
    assert yaml.splitlines()[1].endswith("}  # roslint-names: ignore RN101")

    after = _check(run_cli, tmp_path, "--extend-select", "RN002")
    assert _found(after) == [("src/base/scripts/teleop", 7, "RN202")]
    again = run_cli(["check", "--add-noqa", "."], tmp_path)
    assert "added 0 suppression comments in 0 files" in again.stderr


# ---------------------------------------------------------------------------------------
# Fixes

FIX_CPP = """#include <rclcpp/rclcpp.hpp>
#include <geometry_msgs/msg/transform_stamped.hpp>

class OdomBroadcaster : public rclcpp::Node
{
public:
  OdomBroadcaster() : Node("odom_broadcaster")
  {
    msg_.header.frame_id = "/odom";  // tf2 refuses it
    msg_.child_frame_id = "base_link";
    status_ = create_publisher<std_msgs::msg::String>("status/", 10);
  }

private:
  geometry_msgs::msg::TransformStamped msg_;
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr status_;
};
"""
FIX_LAUNCH = """<launch>
  <node pkg="robot_localization" exec="ekf_node" name="ekf" namespace="localization/">
    <param name="world_frame" value="/map"/>
    <remap from="~odom" to="odometry/filtered"/>
    <remap from="imu" to="imu/data"/> <!-- roslint-names: ignore RN102 -->
  </node>
</launch>
"""
FIX_ROS1_LAUNCH = """<launch>
  <node pkg="robot_localization" type="ekf_localization_node" name="ekf">
    <param name="map_frame" value="/map"/>
  </node>
</launch>
"""


def _fix_workspace(root: Path) -> None:
    write_package(root / "src/odom", 2, "odom")
    write(root, "src/odom/src/odom_broadcaster.cpp", FIX_CPP)
    write(root, "src/odom/launch/ekf.launch.xml", FIX_LAUNCH)
    write_package(root / "src/legacy", 1, "legacy")
    write(root, "src/legacy/launch/ekf.launch", FIX_ROS1_LAUNCH)


def test_safe_fixes_are_marked_shown_as_a_diff_and_applied(run_cli: Any, tmp_path: Path) -> None:
    _fix_workspace(tmp_path)
    text = run_cli(["check", "."], tmp_path)
    fixable = [line for line in text.stdout.splitlines() if line.endswith("[*]")]
    assert len(fixable) == 5  # /odom, status/, localization/, /map, ~odom (ROS 2 only)

    diff = run_cli(["check", "--diff", "."], tmp_path)
    assert diff.exit_code == 1
    assert '-    msg_.header.frame_id = "/odom";  // tf2 refuses it' in diff.stdout
    assert '+    msg_.header.frame_id = "odom";  // tf2 refuses it' in diff.stdout
    assert '+    <remap from="~/odom" to="odometry/filtered"/>' in diff.stdout
    assert (tmp_path / "src/odom/src/odom_broadcaster.cpp").read_text(encoding="utf-8") == FIX_CPP

    fixed = run_cli(["check", "--fix", "--format", "json", "."], tmp_path)
    assert "fixed 5 findings in 2 files" in fixed.stderr
    # What is left: the ROS 1 frame (tf, not tf2, may tell '/map' from 'map').
    assert [(f["path"], f["code"], f["fix"]["safe"]) for f in fixed.findings()] == [
        ("src/legacy/launch/ekf.launch", "RN205", False)
    ]
    launch = (tmp_path / "src/odom/launch/ekf.launch.xml").read_text(encoding="utf-8")
    assert launch == (
        FIX_LAUNCH.replace('"localization/"', '"localization"')
        .replace('"/map"', '"map"')
        .replace('"~odom"', '"~/odom"')
    )  # and nothing else: the comment and the layout stay as they were
    again = run_cli(["check", "--fix", "."], tmp_path)
    assert "fixed 0 findings in 0 files" in again.stderr

    unsafe = run_cli(["check", "--fix", "--unsafe-fixes", "."], tmp_path)
    assert "fixed 1 finding in 1 file" in unsafe.stderr
    assert unsafe.exit_code == 0
    legacy = (tmp_path / "src/legacy/launch/ekf.launch").read_text(encoding="utf-8")
    assert '<param name="map_frame" value="map"/>' in legacy


def test_a_suppressed_or_baselined_finding_is_not_fixed(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "src/odom", 2, "odom")
    source = FIX_CPP.replace("// tf2 refuses it", "// NOLINT(RN205)")
    write(tmp_path, "src/odom/src/odom_broadcaster.cpp", source)
    run_cli(["check", "--write-baseline", "baseline.json", "."], tmp_path)
    result = run_cli(["check", "--fix", "--baseline", "baseline.json", "."], tmp_path)
    assert "fixed 0 findings in 0 files" in result.stderr
    assert (tmp_path / "src/odom/src/odom_broadcaster.cpp").read_text(encoding="utf-8") == source


def test_unsafe_fixes_need_asking_for(run_cli: Any, tmp_path: Path) -> None:
    """An absolute name made relative resolves elsewhere under a namespace; a renamed node
    or topic must be renamed wherever else it is used: neither is applied by --fix alone."""
    _workspace(tmp_path)
    text = run_cli(["check", "."], tmp_path)
    assert not [line for line in text.stdout.splitlines() if line.endswith("[*]")]
    assert "fixed 0 findings in 0 files" in run_cli(["check", "--fix", "."], tmp_path).stderr
    diff = run_cli(["check", "--diff", "--unsafe-fixes", "."], tmp_path)
    assert '+  <node name="base_driver" pkg="robot_base" type="driver_node"/>' in diff.stdout
    assert '("mobile_base/cmd_vel", 10);' in diff.stdout
    fixed = run_cli(["check", "--fix", "--unsafe-fixes", "--format", "json", "."], tmp_path)
    assert "fixed 3 findings in 2 files" in fixed.stderr
    assert fixed.findings() == []


def test_edits_count_lines_as_the_parsers_do(run_cli: Any, tmp_path: Path) -> None:
    """A form feed (old C++ sources separate sections with one) is no line break for
    tree-sitter: fixes and comments must land on the finding's line all the same."""
    write_package(tmp_path / "src/odom", 2, "odom")
    source = FIX_CPP.replace("class OdomBroadcaster", "// Section 2\x0c\nclass OdomBroadcaster")
    write(tmp_path, "src/odom/src/odom_broadcaster.cpp", source)
    run_cli(["check", "--fix", "."], tmp_path)
    fixed = (tmp_path / "src/odom/src/odom_broadcaster.cpp").read_text(encoding="utf-8")
    assert fixed == source.replace('"/odom"', '"odom"').replace('"status/"', '"status"')
    write(tmp_path, "src/odom/src/odom_broadcaster.cpp", source)
    run_cli(["check", "--add-noqa", "."], tmp_path)
    noqa = (tmp_path / "src/odom/src/odom_broadcaster.cpp").read_text(encoding="utf-8")
    # Appended, the comment would pass 80 columns: alone on the line before.
    assert (
        '    // roslint-names: ignore RN205\n    msg_.header.frame_id = "/odom";  // tf2 refuses it'
        in noqa
    )


def test_a_byte_order_mark_survives_a_fix_and_shifts_nothing(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "src/odom", 2, "odom")
    launch = tmp_path / "src/odom/launch/tf.launch.xml"
    launch.parent.mkdir(parents=True)
    one_line = (
        '<launch><node pkg="tf2_ros" exec="static_transform_publisher" namespace="tf/"/></launch>\n'
    )
    launch.write_bytes(b"\xef\xbb\xbf" + one_line.encode("utf-8"))
    run_cli(["check", "--fix", "."], tmp_path)
    assert launch.read_bytes() == b"\xef\xbb\xbf" + one_line.replace('"tf/"', '"tf"').encode()

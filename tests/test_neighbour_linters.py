"""What ``--add-noqa`` writes passes the linters beside us, run for real.

cpplint (and the copy ament_cpplint ships, which ``ament_lint_auto`` runs in every ROS 2
C++ package's ``colcon test``) reports any category it does not know inside
``NOLINT(...)`` (``readability/nolint``): a suppression in that form turned the ROS style
gate red. ruff reports codes it does not know in ``# noqa`` (RUF102) unless
``lint.external`` names them, as the README says.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

from conftest import write, write_package

# A roscpp node in Google style, clean for cpplint as it stands: a name whose line has
# room for the comment, one whose line has not, and one that is fine.
NODE_CPP = """\
// Copyright 2024 Robot Co.

#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

using geometry_msgs::Twist;

int main(int argc, char** argv) {
  ros::init(argc, argv, "velocity_smoother");
  ros::NodeHandle nh;
  auto out = nh.advertise<Twist>("/cmd", 1);
  ros::Publisher raw =
      nh.advertise<Twist>("/mobile_base/commands/velocity", 10);
  ros::Publisher status = nh.advertise<Twist>("status", 10);
  ros::spin();
  return 0;
}
"""

# The same node as an older roslint-names left it: its codes inside NOLINT comments,
# beside cpplint's own.
OLD_FORMS_CPP = """\
// Copyright 2024 Robot Co.

#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

using geometry_msgs::Twist;

int main(int argc, char** argv) {
  ros::init(argc, argv, "velocity_smoother");
  ros::NodeHandle nh;
  auto out = nh.advertise<Twist>("/cmd", 1);  // NOLINT(RN202)
  auto odom = nh.advertise<Twist>("/odom", 1);  // NOLINT(runtime/int, RN202)
  // NOLINTNEXTLINE(RN202)
  ros::Publisher raw = nh.advertise<Twist>("/raw", 10);
  ros::Publisher status = nh.advertise<Twist>("status", 10);
  ros::spin();
  return 0;
}
"""


def cpplint(path: Path, *options: str) -> list[str]:
    done = subprocess.run(
        [sys.executable, "-m", "cpplint", "--quiet", *options, str(path)],
        capture_output=True,
        text=True,
        check=False,
    )
    return [line for line in done.stderr.splitlines() if line.strip()]


def test_cpplint_accepts_what_add_noqa_writes(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "src/base", 1, "base")
    node = write(tmp_path, "src/base/src/smoother.cpp", NODE_CPP)
    assert cpplint(node) == []
    added = run_cli(["check", "--add-noqa", "."], tmp_path)
    assert "added 2 suppression comments in 1 files" in added.stderr
    text = node.read_text(encoding="utf-8")
    assert 'auto out = nh.advertise<Twist>("/cmd", 1);  // roslint-names: ignore RN202\n' in text
    assert "  // roslint-names: ignore RN202\n  ros::Publisher raw =\n" in text
    # Google's 80 columns, and ament_cpplint's 100 (ament_cmake_cpplint's default).
    assert cpplint(node) == []
    assert cpplint(node, "--linelength=100") == []
    assert run_cli(["check", "--extend-select", "RN002", "."], tmp_path).exit_code == 0


def test_add_noqa_moves_our_codes_out_of_nolint(run_cli: Any, tmp_path: Path) -> None:
    """Before, cpplint reported each code of ours as an unknown NOLINT category."""
    write_package(tmp_path / "src/base", 1, "base")
    node = write(tmp_path, "src/base/src/smoother.cpp", OLD_FORMS_CPP)
    complaints = cpplint(node)
    assert len(complaints) == 3
    assert all("Unknown NOLINT error category: RN202" in line for line in complaints)
    # The old forms still suppress: nothing to report, nothing unused.
    assert run_cli(["check", "--extend-select", "RN002", "."], tmp_path).exit_code == 0
    run_cli(["check", "--add-noqa", "."], tmp_path)
    lines = node.read_text(encoding="utf-8").splitlines()
    assert lines[10:16] == [
        '  auto out = nh.advertise<Twist>("/cmd", 1);  // roslint-names: ignore RN202',
        "  // roslint-names: ignore RN202",  # no room after cpplint's own comment
        '  auto odom = nh.advertise<Twist>("/odom", 1);  // NOLINT(runtime/int)',
        "  // roslint-names: ignore RN202",  # the NOLINTNEXTLINE, in its place
        '  ros::Publisher raw = nh.advertise<Twist>("/raw", 10);',
        '  ros::Publisher status = nh.advertise<Twist>("status", 10);',
    ]
    assert cpplint(node) == []
    assert run_cli(["check", "--extend-select", "RN002", "."], tmp_path).exit_code == 0


TELEOP_PY = """\
import rospy
from geometry_msgs.msg import Twist


def main():
    rospy.init_node("teleop")
    pub = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
    status = rospy.Publisher("status", Twist, queue_size=1)
    rospy.spin()
"""


def test_ruff_accepts_the_python_form_with_the_documented_setting(
    run_cli: Any, tmp_path: Path
) -> None:
    write_package(tmp_path / "src/teleop", 1, "teleop")
    script = write(tmp_path, "src/teleop/src/teleop/teleop.py", TELEOP_PY)
    run_cli(["check", "--add-noqa", "."], tmp_path)
    assert "# noqa: RN202" in script.read_text(encoding="utf-8")

    def ruff(*options: str) -> subprocess.CompletedProcess[str]:
        command = [sys.executable, "-m", "ruff", "check", "--isolated", "--no-cache"]
        command += ["--select", "RUF100,RUF102", *options, str(script)]
        return subprocess.run(command, capture_output=True, text=True, check=False)

    assert "RUF102" in ruff().stdout  # what a user without the setting sees
    documented = ruff("--config", 'lint.external = ["RN"]')
    assert documented.returncode == 0, documented.stdout

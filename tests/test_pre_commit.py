"""The pre-commit hook, for real: a throwaway repository uses this one as a hook repository.

The hook repository is a snapshot of this checkout's working tree (tracked and untracked
files alike), committed into a temporary git repository, so the test checks the code as
it is now rather than the last commit.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SNAPSHOT_IGNORE = shutil.ignore_patterns(
    ".git",
    ".venv",
    "venv",
    "*.egg-info",
    "__pycache__",
    ".mypy_cache",
    ".ruff_cache",
    ".pytest_cache",
    ".hypothesis",
    "build",
    "dist",
)
BAD_LAUNCH = """<launch>
  <node name="base-driver" pkg="robot_base" type="driver_node"/>
</launch>
"""
GOOD_LAUNCH = BAD_LAUNCH.replace("base-driver", "base_driver")
# A catkin node installed without a suffix (catkin_install_python(PROGRAMS scripts/teleop)),
# and a rostest file: neither has a suffix pre-commit's file types know.
BAD_SCRIPT = """#!/usr/bin/env python
import rospy
from geometry_msgs.msg import Twist

rospy.init_node("teleop-keyboard")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=1)
rospy.spin()
"""
BAD_ROSTEST = """<launch>
  <node name="base_driver" pkg="robot_base" type="driver_node"/>
  <test test-name="odom_hz" pkg="rostest" type="hztest" name="odom hz"/>
</launch>
"""


def git(cwd: Path, *arguments: str) -> None:
    subprocess.run(["git", *arguments], cwd=cwd, check=True, capture_output=True)


def commit_all(repository: Path) -> str:
    git(repository, "add", "-A")
    git(repository, "-c", "user.name=t", "-c", "user.email=t@example.com", "commit", "-qm", "x")
    head = subprocess.run(
        ["git", "rev-parse", "HEAD"], cwd=repository, check=True, capture_output=True, text=True
    )
    return head.stdout.strip()


def test_hook_fails_on_a_bad_launch_file_and_passes_once_fixed(tmp_path: Path) -> None:
    hook_repository = tmp_path / "hook"
    shutil.copytree(ROOT, hook_repository, ignore=SNAPSHOT_IGNORE)
    git(hook_repository, "init", "-q")
    revision = commit_all(hook_repository)

    project = tmp_path / "project"
    launch = project / "src" / "robot_bringup" / "launch" / "robot.launch"
    launch.parent.mkdir(parents=True)
    launch.write_text(BAD_LAUNCH, encoding="utf-8")
    script = project / "src" / "robot_bringup" / "scripts" / "teleop"
    script.parent.mkdir()
    script.write_text(BAD_SCRIPT, encoding="utf-8")  # not executable: no `python` tag either
    rostest = project / "src" / "robot_bringup" / "test" / "odom.test"
    rostest.parent.mkdir()
    rostest.write_text(BAD_ROSTEST, encoding="utf-8")
    (project / "LICENSE").write_text("BSD 3-Clause License\n", encoding="utf-8")
    (project / ".pre-commit-config.yaml").write_text(
        f"repos:\n- repo: {hook_repository}\n  rev: {revision}\n  hooks:\n  - id: roslint-names\n",
        encoding="utf-8",
    )
    git(project, "init", "-q")
    commit_all(project)

    environment = {**os.environ, "PRE_COMMIT_HOME": str(tmp_path / "cache")}
    environment.pop("VIRTUAL_ENV", None)

    def pre_commit(*arguments: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, "-m", "pre_commit", *arguments, "--all-files", "--color", "never"],
            cwd=project,
            env=environment,
            capture_output=True,
            text=True,
            check=False,
            timeout=600,
        )

    failed = pre_commit("run")
    assert failed.returncode == 1, failed.stdout + failed.stderr
    assert "src/robot_bringup/launch/robot.launch:2:15: error: node name 'base-driver'" in (
        failed.stdout
    )
    assert "RN101 illegal-name" in failed.stdout
    assert "src/robot_bringup/scripts/teleop:5:17: error: node name 'teleop-keyboard'" in (
        failed.stdout
    )
    assert "src/robot_bringup/test/odom.test:3:63: error: node name 'odom hz'" in failed.stdout

    # What the README offers to try the hook before adding it: `pre-commit try-repo` with a
    # clone, run from the project (before, untested).
    tried = pre_commit("try-repo", str(hook_repository), "roslint-names")
    assert tried.returncode == 1, tried.stdout + tried.stderr
    assert "node name 'base-driver'" in tried.stdout

    launch.write_text(GOOD_LAUNCH, encoding="utf-8")
    script.write_text(BAD_SCRIPT.replace("teleop-keyboard", "teleop_keyboard"), encoding="utf-8")
    rostest.write_text(BAD_ROSTEST.replace("odom hz", "odom_hz"), encoding="utf-8")
    commit_all(project)
    passed = pre_commit("run")
    assert passed.returncode == 0, passed.stdout + passed.stderr
    assert "Passed" in passed.stdout

"""No input hangs a run: FIFOs in the tree, on the command line or as the configuration,
and a naming policy that would backtrack for minutes.

Each case runs the real CLI in a subprocess with a timeout, so that a regression fails
the test instead of hanging the suite.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from conftest import write, write_package

from roslint_names.reading import Read, read_file, too_large

pytestmark = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs (POSIX)")

ROOT = Path(__file__).resolve().parents[1]
TIMEOUT = 20  # seconds; every case here takes well under one
BRINGUP_LAUNCH = """\
<launch>
  <arg name="robot_name" default="turtlebot"/>
  <node pkg="turtlebot3_bringup" type="turtlebot3_core" name="base-driver" output="screen">
    <remap from="cmd_vel" to="/mobile_base/commands/velocity"/>
  </node>
</launch>
"""
BASE_DRIVER = "node name 'base-driver' contains '-' at index 4 (ROS 1); use 'base_driver'"


def roslint(cwd: Path, *arguments: str) -> tuple[int, str, str, float]:
    """``roslint-names check --no-cache ARGUMENTS`` in ``cwd``: exit code, stdout, stderr
    and seconds taken. This worktree's package first on the path."""
    path = os.pathsep.join(filter(None, (str(ROOT), os.environ.get("PYTHONPATH"))))
    started = time.monotonic()
    process = subprocess.run(
        [sys.executable, "-m", "roslint_names.cli", "check", "--no-cache", *arguments],
        cwd=cwd,
        env={**os.environ, "PYTHONPATH": path},
        capture_output=True,
        text=True,
        timeout=TIMEOUT,
        check=False,
    )
    return process.returncode, process.stdout, process.stderr, time.monotonic() - started


def bringup_package(root: Path) -> Path:
    """A ROS 1 package ``src/robot_bringup`` with one launch file; its directory."""
    package = root / "src" / "robot_bringup"
    write_package(package, 1)
    write(package, "launch/bringup.launch", BRINGUP_LAUNCH)
    return package


def test_fifo_named_gitignore_in_the_tree_does_not_block_the_walk(tmp_path: Path) -> None:
    """Opening the FIFO waited for a writer forever: the run never ended."""
    package = bringup_package(tmp_path)
    os.mkfifo(package / ".gitignore")
    code, stdout, stderr, _ = roslint(tmp_path, "--format", "json", "src")
    assert code == 1, stderr
    findings = json.loads(stdout)["findings"]
    assert [(f["path"], f["code"], f["message"]) for f in findings] == [
        ("src/robot_bringup/launch/bringup.launch", "RN101", BASE_DRIVER)
    ]
    assert stderr.splitlines()[0] == (
        "roslint-names: warning: cannot read src/robot_bringup/.gitignore: "
        "not a regular file (a FIFO); its patterns are not applied"
    )


def test_fifo_in_the_rest_of_the_workspace_of_a_pre_commit_run_is_said(tmp_path: Path) -> None:
    """A run over one file (pre-commit's) walks the rest of its workspace for the graph
    rules: what that walk passes over is said too, once, since the graph does not see it."""
    bringup_package(tmp_path)
    other = tmp_path / "src" / "robot_description"
    write_package(other, 1, "robot_description")
    os.mkfifo(other / ".gitignore")
    code, _, stderr, _ = roslint(tmp_path, "src/robot_bringup/launch/bringup.launch")
    assert code == 1, stderr
    warning = (
        "roslint-names: warning: cannot read src/robot_description/.gitignore: "
        "not a regular file (a FIFO); its patterns are not applied"
    )
    assert stderr.splitlines().count(warning) == 1


def test_fifo_named_on_the_command_line_is_an_error_naming_it(tmp_path: Path) -> None:
    """A FIFO named like a launch file was opened to be read: the run never ended."""
    package = bringup_package(tmp_path)
    os.mkfifo(package / "launch" / "robot.launch")
    code, stdout, stderr, _ = roslint(tmp_path, "src/robot_bringup/launch/robot.launch")
    assert code == 2
    assert stdout == ""
    assert stderr == (
        "roslint-names: error: src/robot_bringup/launch/robot.launch: not a regular file (a FIFO)\n"
    )


def test_fifo_without_a_suffix_named_on_the_command_line_is_an_error(tmp_path: Path) -> None:
    """A name without a suffix is sniffed for a Python shebang: that read blocked too."""
    package = bringup_package(tmp_path)
    os.mkfifo(package / "talker")
    code, _, stderr, _ = roslint(package, "talker", "launch/bringup.launch")
    assert code == 2
    assert stderr == "roslint-names: error: talker: not a regular file (a FIFO)\n"


def test_fifo_as_config_is_an_error_naming_it(tmp_path: Path) -> None:
    bringup_package(tmp_path)
    os.mkfifo(tmp_path / "ci.toml")
    code, _, stderr, _ = roslint(tmp_path, "--config", "ci.toml", "src")
    assert code == 2
    assert stderr == (
        "roslint-names: error: ci.toml: cannot read config file: not a regular file (a FIFO)\n"
    )


def test_fifo_found_as_the_nearest_config_is_an_error_naming_it(tmp_path: Path) -> None:
    """Passed over, it would have let a parent's configuration apply in silence."""
    bringup_package(tmp_path)
    os.mkfifo(tmp_path / "roslint-names.toml")
    code, _, stderr, _ = roslint(tmp_path, "src")
    assert code == 2
    assert stderr == (
        f"roslint-names: error: {tmp_path / 'roslint-names.toml'}: cannot read config file: "
        "not a regular file (a FIFO)\n"
    )


def test_nested_quantifier_policy_is_refused_at_load_time(tmp_path: Path) -> None:
    """'(a+)+$' against a 35-character node name backtracked for minutes."""
    write(tmp_path, "roslint-names.toml", '[naming]\nnode = "(a+)+$"\n')
    launch = BRINGUP_LAUNCH.replace("base-driver", "a" * 34 + "_")
    write(tmp_path, "launch/bringup.launch", launch)
    code, stdout, stderr, seconds = roslint(tmp_path, ".")
    assert code == 2
    assert stdout == ""
    assert stderr.startswith(
        f"roslint-names: error: {tmp_path / 'roslint-names.toml'}: naming.node.regex: "
        "'(a+)+$' repeats a part that can match the same text in more than one way"
    )
    assert seconds < 5  # the interpreter's start included; the check itself takes ms


def test_read_file_refuses_a_fifo_without_waiting_on_it(tmp_path: Path) -> None:
    """The reader every file of a run goes through: it waited for a writer forever."""
    fifo = tmp_path / "talker.py"
    os.mkfifo(fifo)
    results: list[Read] = []
    reader = threading.Thread(target=lambda: results.append(read_file(fifo, 1 << 20)))
    reader.daemon = True
    reader.start()
    reader.join(timeout=TIMEOUT)
    if reader.is_alive():  # a writer's open lets the blocked reader go
        os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
        reader.join(timeout=TIMEOUT)
    assert results == [(None, "not a regular file (a FIFO)", None)]


@pytest.mark.parametrize("size", [0, 1, 3 * (1 << 16) + 5])
def test_read_file_reads_every_byte_of_a_file_within_the_limit(tmp_path: Path, size: int) -> None:
    """An empty file, one byte, and more than one read's worth: read whole, as written."""
    written = bytes(ord("a") + index % 26 for index in range(size))
    launch = tmp_path / "bringup.launch"
    launch.write_bytes(written)
    assert read_file(launch, size) == (written, "", None)


def test_read_file_reads_no_byte_of_a_file_past_the_limit(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    launch = tmp_path / "bringup.launch"
    launch.write_bytes(b"<launch/>\n" * 100)

    def read(descriptor: int, length: int) -> bytes:
        raise AssertionError("read past the limit")

    monkeypatch.setattr(os, "read", read)
    assert read_file(launch, 999) == (None, "", too_large(1000, 999))

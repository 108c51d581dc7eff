"""The command line: subcommands, exit codes, shorthand, output files, validate."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from conftest import write, write_package

from roslint_names import __version__, cli
from roslint_names.cli import rules_table
from roslint_names.registry import load_registry

BAD_LAUNCH = """<launch>
  <arg name="robot" default="robot1"/>
  <group ns="$(arg robot)">
    <node name="base-driver" pkg="robot_base" type="driver_node">
      <remap from="cmd_vel" to="cmd_vel/"/>
    </node>
  </group>
</launch>
"""


def test_text_output_is_gcc_style_and_summary_goes_to_stderr(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path, 1)
    write(tmp_path, "launch/robot.launch", BAD_LAUNCH)
    result = run_cli(["launch"], tmp_path)  # shorthand for `check launch`
    assert result.exit_code == 1
    assert result.stdout.splitlines() == [
        "launch/robot.launch:4:17: error: node name 'base-driver' contains '-' at index 4"
        " (ROS 1); use 'base_driver' [RN101 illegal-name]",
        "launch/robot.launch:5:33: warning: remap target 'cmd_vel/' ends with '/'"
        " (ROS 1 strips it); use 'cmd_vel' [RN102 trailing-slash] [*]",
    ]
    assert "2 problems" in result.stderr
    assert "1 file" in result.stderr


def test_exit_zero_and_clean_exit(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "robot.launch", BAD_LAUNCH)
    assert run_cli(["check", "--exit-zero", "robot.launch"], tmp_path).exit_code == 0
    write(tmp_path, "robot.launch", BAD_LAUNCH.replace("-", "_").replace("cmd_vel/", "cmd_vel"))
    clean = run_cli(["check", "robot.launch"], tmp_path)
    assert (clean.exit_code, clean.stdout) == (0, "")


def test_output_file_and_statistics(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "robot.launch", BAD_LAUNCH)
    result = run_cli(["check", "--format", "json", "-o", "report.json", "."], tmp_path)
    assert result.exit_code == 1 and result.stdout == ""
    report = json.loads((tmp_path / "report.json").read_text(encoding="utf-8"))
    assert [finding["code"] for finding in report["findings"]] == ["RN101", "RN102"]
    stats = run_cli(["check", "--statistics", "."], tmp_path)
    assert "RN101" in stats.stdout and "illegal-name" in stats.stdout


def test_select_ignore_and_unknown_selector(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "robot.launch", BAD_LAUNCH)
    only = run_cli(["check", "--format", "json", "--select", "trailing-slash", "."], tmp_path)
    assert only.codes() == ["RN102"]
    ignored = run_cli(["check", "--format", "json", "--ignore", "RN1", "."], tmp_path)
    assert (ignored.exit_code, ignored.codes()) == (0, [])
    unknown = run_cli(["check", "--select", "RN9", "."], tmp_path)
    assert unknown.exit_code == 2 and "'RN9' matches no rule" in unknown.stderr


def test_ros_option_decides_only_when_nothing_else_does(run_cli: Any, tmp_path: Path) -> None:
    # No package.xml and no tag only one generation has: only --ros can tell.
    write(tmp_path, "remaps.xml", '<launch>\n  <remap from="scan" to="base_scan/"/>\n</launch>\n')

    def severities(*options: str) -> list[tuple[str, str]]:
        result = run_cli(["check", "--format", "json", *options, "."], tmp_path)
        return [(finding["code"], finding["severity"]) for finding in result.findings()]

    assert severities("--ros", "2") == [("RN102", "error")]
    assert severities("--ros", "1") == [("RN102", "warning")]
    assert severities() == [("RN102", "error")]  # auto: ROS 2
    write_package(tmp_path, 2)
    assert severities("--ros", "1") == [("RN102", "error")]  # the package.xml decides


def test_show_source_points_at_the_name(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "robot.launch", BAD_LAUNCH)
    lines = run_cli(["check", "--show-source", "--select", "RN101", "."], tmp_path).stdout
    assert lines.splitlines()[1:3] == [
        '        <node name="base-driver" pkg="robot_base" type="driver_node">',
        "                    ^~~~~~~~~~~",
    ]


@pytest.mark.parametrize("options", [["--jobs", "2"], ["-j", "0"], ["--no-cache"]])
def test_cache_and_jobs_options_leave_output_unchanged(
    run_cli: Any, tmp_path: Path, options: list[str]
) -> None:
    write(tmp_path, "robot.launch", BAD_LAUNCH)
    plain = run_cli(["check", "."], tmp_path)
    assert run_cli(["check", *options, "."], tmp_path) == plain


def test_negative_jobs_is_a_usage_error(run_cli: Any, tmp_path: Path) -> None:
    result = run_cli(["check", "--jobs", "-1", "."], tmp_path)
    assert result.exit_code == 2 and "--jobs" in result.stderr


def test_missing_path_exits_2(run_cli: Any, tmp_path: Path) -> None:
    result = run_cli(["check", "does/not/exist.launch"], tmp_path)
    assert result.exit_code == 2
    assert "does/not/exist.launch: no such file or directory" in result.stderr


def test_malformed_file_is_one_rn001_and_the_run_goes_on(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "a_broken.launch", "<launch><node name='x'></launch>")
    write(tmp_path, "b_bad.launch", BAD_LAUNCH)
    write(tmp_path, "c_bytes.launch", "")
    (tmp_path / "c_bytes.launch").write_bytes(b"\xff\xfe\x00<\x00l\x00\xd8\x00")
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    assert result.exit_code == 1
    assert [(f["path"], f["code"]) for f in result.findings()] == [
        ("a_broken.launch", "RN001"),
        ("b_bad.launch", "RN101"),
        ("b_bad.launch", "RN102"),
        ("c_bytes.launch", "RN001"),
    ]


def test_two_runs_give_identical_bytes(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "robot.launch", BAD_LAUNCH)
    for output_format in ("text", "json", "sarif", "github"):
        first = run_cli(["check", "--format", output_format, "."], tmp_path).stdout
        second = run_cli(["check", "--format", output_format, "."], tmp_path).stdout
        assert first == second and first


def test_rule_and_rules_commands(run_cli: Any, tmp_path: Path) -> None:
    page = run_cli(["rule", "trailing-slash"], tmp_path)
    assert page.exit_code == 0 and page.stdout.startswith("# RN102 trailing-slash")
    assert run_cli(["rule", "rn102"], tmp_path).stdout == page.stdout
    missing = run_cli(["rule", "RN999"], tmp_path)
    assert missing.exit_code == 2 and "RN999" in missing.stderr
    listing = run_cli(["rules"], tmp_path)
    assert "| RN102 | trailing-slash | error (ROS 1: warning) |" in listing.stdout
    assert "| RN002 | unused-suppression | warning, off by default |" in listing.stdout


def test_version(run_cli: Any, tmp_path: Path) -> None:
    assert run_cli(["--version"], tmp_path).stdout.strip() == f"roslint-names {__version__}"


def test_validate_json_keeps_input_order_and_reports_index(run_cli: Any, tmp_path: Path) -> None:
    result = run_cli(
        ["validate", "--ros", "2", "--kind", "topic", "--format", "json", "cmd_vel", "a-b", "~a"],
        tmp_path,
    )
    records = [json.loads(line) for line in result.stdout.splitlines()]
    assert result.exit_code == 1
    assert [record["name"] for record in records] == ["cmd_vel", "a-b", "~a"]
    assert records[0] == {
        "name": "cmd_vel",
        "kind": "topic",
        "ros": 2,
        "valid": True,
        "code": None,
        "reason": None,
        "index": None,
    }
    assert (records[1]["valid"], records[1]["code"], records[1]["index"]) == (False, "RN101", 1)
    assert records[2]["valid"] is False


def test_validate_reads_stdin_exactly_as_written(tmp_path: Path) -> None:
    process = subprocess.run(
        [sys.executable, "-m", "roslint_names.cli", "validate", "--format", "json", "-"],
        input=b" cmd_vel\ncmd_vel \r\nodom\n",
        capture_output=True,
        check=False,
    )
    records = [json.loads(line) for line in process.stdout.decode().splitlines()]
    assert [record["name"] for record in records] == [" cmd_vel", "cmd_vel ", "odom"]
    assert [record["valid"] for record in records] == [False, False, True]
    assert records[0]["index"] == 0 and records[1]["index"] == 7
    assert process.returncode == 1


@pytest.mark.parametrize("ros", ["1", "2"])
def test_validate_exit_zero_when_all_valid(run_cli: Any, tmp_path: Path, ros: str) -> None:
    assert run_cli(["validate", "--ros", ros, "/robot1/cmd_vel"], tmp_path).exit_code == 0


def test_readme_rule_table_is_current() -> None:
    readme = (Path(__file__).parents[1] / "README.md").read_text(encoding="utf-8")
    assert rules_table(load_registry()) in readme, "regenerate with `roslint-names rules`"


def test_no_traceback_on_internal_error(run_cli: Any, tmp_path: Path, monkeypatch: Any) -> None:
    def explode(*arguments: object, **keywords: object) -> None:
        raise RuntimeError("boom")

    monkeypatch.setattr(cli, "lint", explode)
    write(tmp_path, "robot.launch", BAD_LAUNCH)
    result = run_cli(["check", "."], tmp_path)
    assert result.exit_code == 2
    assert "internal error: RuntimeError: boom" in result.stderr


def test_non_utf8_file_name_is_reported_readably(run_cli: Any, tmp_path: Path) -> None:
    # Found by hand: a Latin-1 file name crashed every reporter with UnicodeEncodeError.
    (tmp_path / os.fsdecode(b"caf\xe9.launch")).write_text(BAD_LAUNCH, encoding="utf-8")
    text = run_cli(["check", "."], tmp_path)
    assert text.stdout.startswith("caf\\xe9.launch:4:17: error: node name 'base-driver'")
    github = run_cli(["check", "--format", "github", "."], tmp_path)
    assert "file=caf\\xe9.launch," in github.stdout
    findings = run_cli(["check", "--format", "json", "."], tmp_path).findings()
    assert {finding["path"] for finding in findings} == {"caf\\xe9.launch"}
    sarif = json.loads(run_cli(["check", "--format", "sarif", "."], tmp_path).stdout)
    location = sarif["runs"][0]["results"][0]["locations"][0]["physicalLocation"]
    assert location["artifactLocation"]["uri"] == "caf%5Cxe9.launch"


def test_python_m_runs_the_command_line(tmp_path: Path) -> None:
    """Before, ``python -m roslint_names`` said the package cannot be executed."""
    write_package(tmp_path / "robot", 1, "robot")
    launch = '<launch><node name="a-b" pkg="p" type="t"/></launch>\n'
    write(tmp_path, "robot/launch/robot.launch", launch)
    done = subprocess.run(
        [sys.executable, "-m", "roslint_names", "--no-cache", "."],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 1, done.stderr
    assert "robot/launch/robot.launch:1:" in done.stdout
    assert "[RN101 illegal-name]" in done.stdout


def test_the_command_ends_without_taking_its_objects_apart(tmp_path: Path) -> None:
    """``cli.entry`` (the ``roslint-names`` script, ``python -m roslint_names``) ends the
    process once ``main`` returns: no exit handler, no collection of what the run kept
    (1.0 s of a 10 s run at 8 copies of realws). The report is whole (its last line, a
    file's report and the summary on stderr), the exit code ``main``'s, and a reader
    gone before the end is exit 2 without a traceback, as within ``main``."""
    write_package(tmp_path / "robot", 1, "robot")
    launch = '<launch><node name="a-b" pkg="p" type="t"/></launch>\n'
    write(tmp_path, "robot/launch/robot.launch", launch)
    script = (
        "import atexit, sys\n"
        "atexit.register(lambda: print('torn down', file=sys.stderr))\n"
        "from roslint_names.cli import entry\n"
        "entry()\n"
    )
    for arguments, code in (
        (["--no-cache", "."], 1),
        (["--no-cache", "--format", "json", "-o", "report.json", "."], 1),
        (["--no-cache", "--ignore", "RN101", "."], 0),
    ):
        done = subprocess.run(
            [sys.executable, "-c", script, *arguments],
            cwd=tmp_path,
            capture_output=True,
            text=True,
            check=False,
        )
        assert done.returncode == code, done.stderr
        assert "torn down" not in done.stderr
    assert json.loads((tmp_path / "report.json").read_text())["findings"][0]["code"] == "RN101"
    text = subprocess.run(
        [sys.executable, "-c", script, "--no-cache", "."],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=False,
    )
    assert text.stdout.endswith("; use 'a_b' [RN101 illegal-name]\n")
    assert text.stderr.startswith("Found 1 problem (1 error) in 1 file")
    # A reader that closes the pipe at once: the flush at the end meets it.
    reader, writer = os.pipe()
    os.close(reader)
    with os.fdopen(writer, "w") as closed:
        gone = subprocess.run(
            [sys.executable, "-c", script, "--no-cache", "."],
            cwd=tmp_path,
            stdout=closed,
            stderr=subprocess.PIPE,
            text=True,
            check=False,
        )
    assert gone.returncode == 2
    assert "Traceback" not in gone.stderr


# A roscpp node whose every finding has only an unsafe fix: a rename (RN203) and an
# absolute name made relative (RN202).
SMOOTHER_CPP = """\
#include <ros/ros.h>
#include <geometry_msgs/Twist.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "velocitySmoother");
  ros::NodeHandle nh;
  ros::Publisher out = nh.advertise<geometry_msgs::Twist>("/cmd_vel", 10);
  ros::spin();
}
"""


def test_fix_and_diff_say_what_needs_unsafe_fixes(run_cli: Any, tmp_path: Path) -> None:
    """Before, --diff printed nothing and --fix said 'fixed 0 findings' with exit 0."""
    write_package(tmp_path / "base", 1, "base")
    node = write(tmp_path, "base/src/smoother.cpp", SMOOTHER_CPP)
    diff = run_cli(["check", "--diff", "."], tmp_path)
    assert diff.stdout == ""
    assert "roslint-names: no fix to show" in diff.stderr
    assert "roslint-names: 2 more fixes with --unsafe-fixes" in diff.stderr
    fixed = run_cli(["check", "--fix", "."], tmp_path)
    assert "roslint-names: fixed 0 findings in 0 files" in fixed.stderr
    assert "roslint-names: 2 more fixes with --unsafe-fixes" in fixed.stderr
    assert fixed.exit_code == 1
    assert node.read_text(encoding="utf-8") == SMOOTHER_CPP
    both = run_cli(["check", "--diff", "--unsafe-fixes", "."], tmp_path)
    assert '+  ros::init(argc, argv, "velocity_smoother");' in both.stdout
    assert "--unsafe-fixes:" not in both.stderr


def test_a_rename_held_back_is_named_with_its_reason(run_cli: Any, tmp_path: Path) -> None:
    """Before, the rename was dropped without a word."""
    write_package(tmp_path / "base", 1, "base")
    write(tmp_path, "base/src/smoother.cpp", SMOOTHER_CPP)
    kept = SMOOTHER_CPP.replace(
        '"velocitySmoother");', '"velocitySmoother");  // roslint-names: ignore RN203'
    )
    write(tmp_path, "base/src/smoother_main.cpp", kept)
    diff = run_cli(["check", "--diff", "--unsafe-fixes", "--select", "RN203", "."], tmp_path)
    assert diff.stdout == ""
    assert (
        "roslint-names: base/src/smoother.cpp:6: RN203 rename not offered, "
        "'velocitySmoother': a suppression keeps it at base/src/smoother_main.cpp:6"
    ) in diff.stderr


def test_verbose_says_what_became_of_each_file_named(run_cli: Any, tmp_path: Path) -> None:
    """Before, --verbose said only where the cache was: a file with no finding could have
    been checked in full, judged as test code, or never parsed."""
    write_package(tmp_path / "base", 1, "base")
    write(tmp_path, "base/src/smoother.cpp", SMOOTHER_CPP)
    write(tmp_path, "base/src/filter_math.cpp", "double lowpass(double x) { return x; }\n")
    write(tmp_path, "base/test/test_smoother.cpp", "#include <gtest/gtest.h>\n" + SMOOTHER_CPP)
    write(tmp_path, "base/examples/smoother_demo.cpp", SMOOTHER_CPP)
    write(tmp_path, "base/scripts/plot.py", "import matplotlib\n")
    named = [
        "base/examples/smoother_demo.cpp",
        "base/scripts/plot.py",
        "base/src/filter_math.cpp",
        "base/src/smoother.cpp",
        "base/test/test_smoother.cpp",
    ]
    result = run_cli(["check", "--verbose", "--no-cache", *named], tmp_path)
    said = [line for line in result.stderr.splitlines() if line.startswith("roslint-names: base")]
    assert sorted(said) == [
        "roslint-names: base/examples/smoother_demo.cpp: example code: judged by the "
        "[test-code] rules only",
        "roslint-names: base/scripts/plot.py: not parsed: it imports no ROS client library "
        "and holds no launch description",
        "roslint-names: base/src/filter_math.cpp: not parsed: it names no roscpp or rclcpp API",
        "roslint-names: base/src/smoother.cpp: checked",
        "roslint-names: base/test/test_smoother.cpp: test code: judged by the [test-code] "
        "rules only",
    ]
    # Named files the run does not check say why.
    write(tmp_path, "roslint-names.toml", 'exclude = ["base/src/legacy.cpp"]\n')
    write(tmp_path, "base/src/legacy.cpp", SMOOTHER_CPP)
    write(tmp_path, "base/NOTES.txt", "velocitySmoother is renamed in 2.0\n")
    named = ["base/src/legacy.cpp", "base/NOTES.txt", "base/package.xml"]
    result = run_cli(["check", "--verbose", "--no-cache", *named], tmp_path)
    said = [line for line in result.stderr.splitlines() if line.startswith("roslint-names: base")]
    assert said == [
        "roslint-names: base/NOTES.txt: not checked: no kind of file the linter reads",
        "roslint-names: base/package.xml: not checked: read only for what it says of its package",
        "roslint-names: base/src/legacy.cpp: not checked: the configuration's exclude covers it",
    ]
    # A directory's files are not listed one by one (each would be read again).
    whole = run_cli(["check", "--verbose", "--no-cache", "."], tmp_path)
    assert ": checked" not in whole.stderr

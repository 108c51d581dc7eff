"""The JUnit report: what colcon test-result, Jenkins and GitLab read."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest
import report_sample as sample
from conftest import write, write_package
from lxml import etree

from roslint_names.model import Diagnostic, Span
from roslint_names.report import render

# The Jenkins xunit plugin's schema (MIT, Gregory Boissinot), as pytest ships it in its
# source distribution to check its own --junitxml output: testing/example_scripts/.
SCHEMA = etree.XMLSchema(etree.parse(str(Path(__file__).parent / "fixtures/schemas/junit-10.xsd")))

BAD_LAUNCH = """<launch>
  <group ns="robot1">
    <node name="base-driver" pkg="robot_base" type="driver_node">
      <remap from="cmd_vel" to="/Cmd_vel"/>
    </node>
  </group>
</launch>
"""
CLEAN_NODE = """#!/usr/bin/env python
import rospy
from std_msgs.msg import String

rospy.init_node("talker")
pub = rospy.Publisher("chatter", String, queue_size=10)
"""


def junit(diagnostics: tuple[Diagnostic, ...], files: tuple[str, ...] = ()) -> Any:
    text = render("junit", diagnostics, sample.RULES, sample.context(files=files))
    return etree.fromstring(text.encode("utf-8"))


def test_a_workspace_run_validates_and_counts_testcases(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "src/robot_bringup", 1)
    write(tmp_path, "src/robot_bringup/launch/robot.launch", BAD_LAUNCH)
    write(tmp_path, "src/robot_bringup/launch/broken.launch", "<launch><node name='a'></launch>\n")
    write(tmp_path, "src/robot_bringup/scripts/talker.py", CLEAN_NODE)
    result = run_cli(["check", "--format", "junit", "."], tmp_path)
    assert result.exit_code == 1
    suite = etree.fromstring(result.stdout.encode("utf-8"))
    SCHEMA.assertValid(suite)
    assert dict(suite.attrib) == {
        "name": "roslint_names",
        "tests": "3",
        "failures": "1",
        "errors": "1",
        "skipped": "0",
    }
    cases = {case.get("name"): case for case in suite.iter("testcase")}
    assert sorted(cases) == [
        "src/robot_bringup/launch/broken.launch",
        "src/robot_bringup/launch/robot.launch",
        "src/robot_bringup/scripts/talker.py",
    ]
    assert len(cases["src/robot_bringup/scripts/talker.py"]) == 0  # a clean file passes
    (error,) = cases["src/robot_bringup/launch/broken.launch"]
    assert (error.tag, error.get("type")) == ("error", "RN001")
    failures = cases["src/robot_bringup/launch/robot.launch"]
    assert [(f.tag, f.get("type")) for f in failures] == [
        ("failure", "RN101"),
        ("failure", "RN203"),
    ]
    assert failures[0].get("message").startswith("3:17: node name 'base-driver'")
    assert failures[0].text.startswith("src/robot_bringup/launch/robot.launch:3:17: error: ")


def test_same_findings_same_bytes(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "src/robot_bringup", 1)
    write(tmp_path, "src/robot_bringup/launch/robot.launch", BAD_LAUNCH)
    first = run_cli(["check", "--format", "junit", "--no-cache", "."], tmp_path).stdout
    again = run_cli(["check", "--format", "junit", "."], tmp_path).stdout
    assert first == again
    assert "time" not in first and "timestamp" not in first


@pytest.mark.parametrize(
    "message",
    [
        "node name 'a\x01b' has an illegal character",
        'related <tags> & "quotes" in ]]> a message',
        "a line break\nin the message",
    ],
)
def test_any_message_gives_valid_xml(message: str) -> None:
    diagnostic = replace(sample.RN101, message=message)
    suite = junit((diagnostic,))
    SCHEMA.assertValid(suite)
    (failure,) = suite.iter("failure")
    assert "\n" not in failure.get("message")
    assert "\x01" not in failure.text


def test_no_files_and_no_findings_is_an_empty_passing_suite() -> None:
    suite = junit(())
    SCHEMA.assertValid(suite)
    assert (suite.get("tests"), suite.get("failures"), len(suite)) == ("0", "0", 0)


def test_suppressed_findings_are_not_failures() -> None:
    quiet = replace(sample.RN101, suppressed=True, span=Span(1, 1, 1, 2))
    suite = junit((quiet,), files=(quiet.path,))
    assert (suite.get("tests"), suite.get("failures")) == ("1", "0")

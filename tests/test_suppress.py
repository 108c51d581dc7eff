"""Suppression comments in each language's own form."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from roslint_names.model import Language
from roslint_names.suppress import find_suppressions


def keys_and_lines(text: str, language: Language) -> list[tuple[tuple[str, ...], list[int]]]:
    return [(found.keys, sorted(found.lines)) for found in find_suppressions(text, language)]


def test_cpp_nolint_and_nolintnextline() -> None:
    text = (
        'pub = nh.advertise<Twist>("/cmd_vel", 1);  // NOLINT(RN202)\n'
        "// NOLINTNEXTLINE(hard-coded-absolute-name, build/include)\n"
        'sub = nh.subscribe("/odom", 1, cb);\n'
        "int x;  // NOLINT\n"
    )
    assert keys_and_lines(text, Language.CPP) == [
        (("RN202",), [1]),
        (("hard-coded-absolute-name", "build/include"), [3]),
    ]


def test_python_noqa_keeps_other_tools_codes_apart() -> None:
    text = 'rospy.Publisher("/cmd_vel", Twist)  # noqa: E501, RN202\nx = 1  # noqa\n'
    assert keys_and_lines(text, Language.PYTHON) == [(("E501", "RN202"), [1])]


def test_xml_comment_covers_its_line_and_the_next() -> None:
    text = '<launch>\n  <!-- roslint-names: ignore RN101, RN203 -->\n  <node name="a-b"/>\n'
    assert keys_and_lines(text, Language.LAUNCH_XML) == [(("RN101", "RN203"), [2, 3])]


def test_yaml_comment() -> None:
    text = "launch:\n# roslint-names: ignore RN203\n- node: {pkg: a, exec: b, name: Foo}\n"
    assert keys_and_lines(text, Language.LAUNCH_YAML) == [(("RN203",), [2, 3])]


LAUNCH = """<launch>
  <!-- roslint-names: ignore illegal-name -->
  <node name="base-driver" pkg="robot_base" type="driver_node"/>
  <node name="arm-driver" pkg="robot_arm" type="driver_node"/> <!-- roslint-names: ignore RN101 -->
  <node name="gripper-driver" pkg="robot_arm" type="gripper_node"/>
  <!-- roslint-names: ignore RN999 -->
  <node name="camera" pkg="usb_cam" type="usb_cam_node"/> <!-- roslint-names: ignore RN101 -->
</launch>
"""


def test_engine_applies_suppressions(lint_text: Any) -> None:
    codes = lint_text(LAUNCH, "robot.launch", 1, "--extend-select", "RN002")
    assert codes == ["RN101", "RN003", "RN002"]


def test_suppressed_findings_are_in_sarif_only_on_request(run_cli: Any, tmp_path: Path) -> None:
    (tmp_path / "robot.launch").write_text(LAUNCH, encoding="utf-8")
    plain = json.loads(run_cli(["check", "--format", "sarif", "robot.launch"], tmp_path).stdout)
    full = json.loads(
        run_cli(
            ["check", "--format", "sarif", "--include-suppressed", "robot.launch"], tmp_path
        ).stdout
    )
    plain_results = plain["runs"][0]["results"]
    full_results = full["runs"][0]["results"]
    assert len(full_results) == len(plain_results) + 2
    assert sum("suppressions" in result for result in full_results) == 2


def test_lines_are_counted_as_parsers_count_them() -> None:
    # Found in review: str.splitlines() also breaks at form feed and \x1c-\x1e, so a
    # suppression after such a character sat on the wrong line.
    text = "// page one\x0c still line one\nros::Publisher p;  // NOLINT(RN202)\n"
    assert keys_and_lines(text, Language.CPP) == [(("RN202",), [2])]

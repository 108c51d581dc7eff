"""The GitLab Code Quality report: the fields GitLab requires, fingerprints that last."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from conftest import write, write_package
from jsonschema import Draft7Validator

# GitLab's "Code Quality report format" (docs/ci/testing/code_quality.md): a JSON array of
# Code Climate issues, each with these fields; GitLab ignores the rest.
CODE_QUALITY_SCHEMA = {
    "type": "array",
    "items": {
        "type": "object",
        "required": ["description", "check_name", "fingerprint", "severity", "location"],
        "properties": {
            "type": {"const": "issue"},
            "description": {"type": "string", "minLength": 1},
            "check_name": {"type": "string", "minLength": 1},
            "fingerprint": {"type": "string", "minLength": 1},
            "severity": {"enum": ["info", "minor", "major", "critical", "blocker"]},
            "location": {
                "type": "object",
                "required": ["path", "lines"],
                "properties": {
                    "path": {"type": "string", "pattern": "^[^/]"},  # relative to the project
                    "lines": {
                        "type": "object",
                        "required": ["begin"],
                        "properties": {"begin": {"type": "integer", "minimum": 1}},
                    },
                },
            },
        },
    },
}
VALIDATOR = Draft7Validator(CODE_QUALITY_SCHEMA)

TELEOP_LAUNCH = """<launch>
  <group ns="robot1">
    <node name="teleop-joy" pkg="joy" type="joy_node"/>
    <node name="teleop-twist" pkg="teleop_twist_joy" type="teleop_node">
      <remap from="cmd_vel" to="/cmd_vel"/>
    </node>
  </group>
</launch>
"""


def _report(run_cli: Any, root: Path) -> list[dict[str, Any]]:
    result = run_cli(["check", "--format", "gitlab", "."], root)
    assert result.exit_code == 1, result.stderr
    issues: list[dict[str, Any]] = json.loads(result.stdout)
    errors = [error.message for error in VALIDATOR.iter_errors(issues)]
    assert not errors, errors
    return issues


def test_each_finding_is_an_issue_gitlab_accepts(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "src/teleop", 1, "teleop")
    write(tmp_path, "src/teleop/launch/teleop.launch", TELEOP_LAUNCH)
    issues = _report(run_cli, tmp_path)
    assert [
        (i["check_name"], i["severity"], i["location"]["path"], i["location"]["lines"]["begin"])
        for i in issues
    ] == [
        ("RN101 illegal-name", "major", "src/teleop/launch/teleop.launch", 3),
        ("RN101 illegal-name", "major", "src/teleop/launch/teleop.launch", 4),
    ]
    assert issues[0]["description"].startswith("RN101 node name 'teleop-joy'")
    assert len({issue["fingerprint"] for issue in issues}) == 2


def test_fingerprints_survive_lines_inserted_above(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "src/teleop", 1, "teleop")
    write(tmp_path, "src/teleop/launch/teleop.launch", TELEOP_LAUNCH)
    before = _report(run_cli, tmp_path)
    notes = "".join(f"  <!-- tuned on robot {i} -->\n" for i in range(20))
    shifted = TELEOP_LAUNCH.replace("<launch>\n", "<launch>\n" + notes)
    write(tmp_path, "src/teleop/launch/teleop.launch", shifted)
    after = _report(run_cli, tmp_path)
    assert [i["location"]["lines"]["begin"] for i in after] == [23, 24]
    assert [i["fingerprint"] for i in after] == [i["fingerprint"] for i in before]


def test_a_clean_run_is_an_empty_array(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "src/teleop", 1, "teleop")
    write(
        tmp_path,
        "src/teleop/launch/teleop.launch",
        '<launch><node name="joy" pkg="joy" type="joy_node"/></launch>\n',
    )
    result = run_cli(["check", "--format", "gitlab", "."], tmp_path)
    assert (result.exit_code, json.loads(result.stdout)) == (0, [])

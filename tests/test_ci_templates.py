"""The CI templates: the GitHub composite action and the GitLab CI job, their scripts run."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import yaml
from conftest import write, write_package
from jsonschema import Draft7Validator
from lxml import etree
from test_report_gitlab import CODE_QUALITY_SCHEMA
from test_report_sarif import SCHEMA as SARIF_SCHEMA

REPOSITORY = Path(__file__).resolve().parents[1]
JUNIT = etree.XMLSchema(etree.parse(str(Path(__file__).parent / "fixtures/schemas/junit-10.xsd")))

TELEOP_LAUNCH = """<launch>
  <node name="teleop-joy" pkg="joy" type="joy_node"/>
</launch>
"""


def _workspace(root: Path) -> Path:
    write_package(root / "src/teleop", 1, "teleop")
    write(root, "src/teleop/launch/teleop.launch", TELEOP_LAUNCH)
    return root


def _environment(root: Path, **variables: str) -> dict[str, str]:
    path = os.pathsep.join((str(Path(sys.executable).parent), os.environ["PATH"]))
    return {**os.environ, "PATH": path, "XDG_CACHE_HOME": str(root / ".cache"), **variables}


def _bash(script: str, cwd: Path, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    # As GitHub runs a `shell: bash` step: bash --noprofile --norc -eo pipefail
    return subprocess.run(
        ["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", script],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        check=False,
        timeout=300,
    )


def _action() -> dict[str, Any]:
    loaded: dict[str, Any] = yaml.safe_load((REPOSITORY / "action.yml").read_text())
    return loaded


def _step(action: dict[str, Any], name: str) -> dict[str, Any]:
    return next(step for step in action["runs"]["steps"] if step.get("name") == name)


def _check_step(
    root: Path, scratch: Path, args: str, changed_since: str, cache_dir: str = ""
) -> tuple[dict[str, str], str]:
    """The action's check step run as GitHub would, in ``root``: the outputs it set and
    the annotations it printed."""
    written, stdout, _ = _check_step_run(root, scratch, args, changed_since, cache_dir)
    return written, stdout


def _check_step_run(
    root: Path, scratch: Path, args: str, changed_since: str, cache_dir: str = ""
) -> tuple[dict[str, str], str, str]:
    outputs = scratch / "github_output"
    outputs.unlink(missing_ok=True)
    env = _environment(
        root,
        PATHS=".",
        ARGS=args,
        CHANGED_SINCE=changed_since,
        CACHE_DIR=cache_dir,
        RUNNER_TEMP=str(scratch),
        GITHUB_OUTPUT=str(outputs),
    )
    ran = _bash(_step(_action(), "Check ROS names")["run"], root, env)
    assert ran.returncode == 0, ran.stderr
    written = dict(line.split("=", 1) for line in outputs.read_text().splitlines())
    return written, ran.stdout, ran.stderr


def test_the_action_annotates_writes_sarif_and_reports_the_exit_code(tmp_path: Path) -> None:
    action = _action()
    assert action["runs"]["using"] == "composite"
    assert {"paths", "version", "args", "changed-since", "upload-sarif"} <= set(action["inputs"])
    upload = _step(action, "Upload to code scanning")
    assert upload["uses"].startswith("github/codeql-action/upload-sarif@")

    root = _workspace(tmp_path / "ws")
    written, annotations = _check_step(root, tmp_path, args="--select RN1", changed_since="")
    assert annotations.startswith("::error file=src/teleop/launch/teleop.launch,line=2,")
    assert written == {"sarif-file": str(tmp_path / "roslint-names.sarif"), "exit-code": "1"}
    sarif = json.loads((tmp_path / "roslint-names.sarif").read_text())
    assert [r["ruleId"] for r in sarif["runs"][0]["results"]] == ["RN101"]

    gate = _step(action, "Gate")["run"]
    for code, fail, expected in (
        ("1", "true", 1),
        ("1", "false", 0),
        ("0", "true", 0),
        ("2", "false", 2),
    ):
        result = _bash(gate, root, _environment(root, CODE=code, FAIL_ON_FINDINGS=fail))
        assert result.returncode == expected, (code, fail)

    # Last: the SARIF the action uploads is valid against the official schema.
    schema = json.loads(SARIF_SCHEMA.read_text(encoding="utf-8"))
    assert not list(Draft7Validator(schema).iter_errors(sarif))


def test_the_action_gates_a_pull_request_on_its_changes(tmp_path: Path) -> None:
    root = _workspace(tmp_path / "ws")
    git = ["git", "-c", "user.name=ci", "-c", "user.email=ci@example.com"]
    for command in (["init", "-q"], ["add", "."], ["commit", "-qm", "base"]):
        subprocess.run([*git, *command], cwd=root, check=True, capture_output=True)
    written, annotations = _check_step(root, tmp_path, args="", changed_since="HEAD")
    assert (written["exit-code"], annotations) == (
        "0",
        "",
    )  # the old finding is not the pull request's


def test_the_gitlab_job_writes_code_quality_and_junit_reports(tmp_path: Path) -> None:
    template = yaml.safe_load(
        (REPOSITORY / "integrations/gitlab/roslint-names.gitlab-ci.yml").read_text()
    )
    job = template["roslint-names"]
    reports = job["artifacts"]["reports"]
    assert job["artifacts"]["when"] == "always"
    root = _workspace(tmp_path / "ws")
    env = _environment(root, **job["variables"])
    results = [
        _bash(line, root, env).returncode for line in job["script"] if not line.startswith("pip ")
    ]
    assert results == [0, 0, 1]  # the reports always, then the gate fails on the finding
    # The facts cache where GitLab's cache keeps it, inside the project; not linted.
    assert job["cache"]["paths"] == [f"{job['variables']['ROSLINT_NAMES_CACHE']}/"]
    assert list((root / job["variables"]["ROSLINT_NAMES_CACHE"]).glob("facts-v*"))
    issues = json.loads((root / reports["codequality"]).read_text())
    assert not list(Draft7Validator(CODE_QUALITY_SCHEMA).iter_errors(issues))
    assert [issue["check_name"] for issue in issues] == ["RN101 illegal-name"]
    suite = etree.parse(str(root / reports["junit"])).getroot()
    JUNIT.assertValid(suite)
    assert suite.get("failures") == "1"


def test_the_action_installs_the_ref_it_was_used_at(tmp_path: Path) -> None:
    """Before, the action installed `roslint-names` from PyPI, where no release exists yet;
    now its own checkout (``github.action_path``), unless a release is asked for."""
    shim = tmp_path / "bin"
    shim.mkdir()
    (shim / "python").write_text('#!/bin/sh\necho "$@"\n')
    (shim / "python").chmod(0o755)
    step = _step(_action(), "Install roslint-names")
    env = {**os.environ, "PATH": f"{shim}{os.pathsep}{os.environ['PATH']}"}
    own = _bash(step["run"], tmp_path, {**env, "VERSION": "", "ACTION_PATH": str(REPOSITORY)})
    assert own.stdout.split() == ["-m", "pip", "install", "--quiet", str(REPOSITORY)]
    assert step["env"]["ACTION_PATH"] == "${{ github.action_path }}"
    release = _bash(step["run"], tmp_path, {**env, "VERSION": "0.2.0", "ACTION_PATH": "/a"})
    assert release.stdout.split()[-1] == "roslint-names==0.2.0"


TELEOP_NODE = """#!/usr/bin/env python
import rospy
from sensor_msgs.msg import Joy


def main():
    rospy.init_node('teleop')
    rospy.Subscriber('joy', Joy, lambda message: None)
    rospy.spin()


if __name__ == '__main__':
    main()
"""


def test_the_action_keeps_the_facts_cache_between_runs(tmp_path: Path) -> None:
    """The action's steps twice, as two workflow runs: the cache-key step, the check step
    with the directory ``actions/cache`` saved after the first run and restored before the
    second (copied away and back), one file changed in between. The second run extracts
    that file alone, and prints what a run without any cache prints."""
    action = _action()
    restore = _step(action, "Restore the facts cache")
    assert restore["uses"].startswith("actions/cache@")
    assert restore["with"]["key"].endswith("${{ github.sha }}")
    root = _workspace(tmp_path / "ws")
    for index in range(5):
        write(root, f"src/teleop/scripts/teleop_{index}.py", TELEOP_NODE)
    key_outputs = tmp_path / "key_output"
    env = _environment(
        root, RUNNER_OS="Linux", RUNNER_TEMP=str(tmp_path), GITHUB_OUTPUT=str(key_outputs)
    )
    keyed = _bash(_step(action, "Facts cache key")["run"], root, env)
    assert keyed.returncode == 0, keyed.stderr
    key = dict(line.split("=", 1) for line in key_outputs.read_text().splitlines())
    assert key["prefix"].startswith("roslint-names-Linux-") and key["prefix"].endswith("-")
    directory = Path(key["dir"])

    _check_step_run(root, tmp_path, "--verbose", "", str(directory))
    saved = tmp_path / "saved"
    shutil.move(str(directory), saved)  # the job ends: actions/cache saves the directory
    node = root / "src/teleop/scripts/teleop_0.py"
    node.write_text(TELEOP_NODE.replace("'joy'", "'joy stick'"), encoding="utf-8")
    shutil.copytree(saved, directory)  # the next job: actions/cache restores it
    _, annotations, log = _check_step_run(root, tmp_path, "--verbose", "", str(directory))
    assert "1 extracted" in log, log
    _, expected, _ = _check_step_run(root, tmp_path, "--no-cache", "", "")
    assert annotations == expected
    assert "teleop_0.py" in annotations

"""The release: the tag is checked against the package's version and the changelog before
anything is built, and the workflow publishes what it checked."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import yaml

from roslint_names import __version__

ROOT = Path(__file__).resolve().parents[1]
CHECK = ROOT / ".ci" / "release_check.py"


def release_check(*arguments: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, str(CHECK), *arguments], capture_output=True, text=True, check=False
    )


def test_the_package_s_version_is_releasable_with_its_changelog_section() -> None:
    assert release_check(f"v{__version__}").returncode == 0
    notes = release_check(f"v{__version__}", "--notes")
    assert notes.returncode == 0
    assert "RN202" in notes.stdout
    assert "## [" not in notes.stdout  # its own section only


def test_a_tag_that_is_not_the_version_stops_the_release() -> None:
    wrong = release_check("v99.0.0")
    assert wrong.returncode == 1
    assert f"is not the package's version ({__version__})" in wrong.stderr
    assert release_check("0.1.0").returncode == 2


def test_the_workflow_checks_tests_builds_and_publishes_by_trusted_publishing() -> None:
    workflow: dict[Any, Any] = yaml.safe_load((ROOT / ".github/workflows/release.yml").read_text())
    # PyYAML reads the key `on` as True.
    assert workflow[True] == {"push": {"tags": ["v*"]}}
    build = workflow["jobs"]["build"]["steps"]
    runs = "\n".join(step.get("run", "") for step in build)
    assert runs.index("release_check.py") < runs.index(".ci/run") < runs.index("python -m build")
    assert "twine check --strict dist/*" in runs
    publish = workflow["jobs"]["publish"]
    assert publish["needs"] == "build"
    assert publish["permissions"] == {"id-token": "write"}
    assert publish["steps"][-1]["uses"] == "pypa/gh-action-pypi-publish@release/v1"
    assert workflow["jobs"]["github-release"]["needs"] == "publish"

"""A run after an edit checks again, with the per-file rules, only the files that can have
changed (``clean_files``, issue 30); its output is byte for byte a fresh run's, over a
sequence of edits that add, move and remove findings, suppressions, packages and
settings."""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from roslint_names import checks
from tests.conftest import AMENT_PACKAGE, CATKIN_PACKAGE, write
from tests.test_run_cache import CMAKE, DRIVER

TELEOP = """#!/usr/bin/env python
import rospy
from geometry_msgs.msg import Twist


def main():
    rospy.init_node('teleop')
    publisher = rospy.Publisher('cmd_vel', Twist, queue_size=1)
    rospy.spin()


if __name__ == '__main__':
    main()
"""

LAUNCH = """<launch>
  <group ns="robot1">
    <node pkg="robot_base" type="base_driver" name="base_driver"/>
    <node pkg="robot_base" type="teleop.py" name="teleop"/>
  </group>
</launch>
"""


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    root = tmp_path / "ws"
    package = root / "src" / "robot_base"
    write(package, "package.xml", CATKIN_PACKAGE.format(name="robot_base"))
    write(package, "CMakeLists.txt", CMAKE)
    write(package, "src/driver.cpp", DRIVER)
    write(package, "scripts/teleop.py", TELEOP)
    write(package, "launch/base.launch", LAUNCH)
    return root


@pytest.fixture
def checked_files(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[str]]:
    """The display paths the per-file rules check, run by run (cleared by the caller)."""
    seen: list[str] = []
    original = checks.check_file

    def counting(facts: Any, *arguments: Any, **keywords: Any) -> Any:
        seen.append(facts.path)
        return original(facts, *arguments, **keywords)

    monkeypatch.setattr(checks, "check_file", counting)
    yield seen


def outputs(
    run_cli: Any, root: Path, cache: Path, checked: list[str] | None = None
) -> tuple[str, str]:
    """A cached run's JSON and a fresh run's; ``checked``: the files the cached run
    checked, kept (the fresh run checks them all)."""
    arguments = ["check", "--format", "json", "--jobs", "1", "--exit-zero"]
    cached = run_cli([*arguments, "--cache-dir", str(cache), "."], root)
    seen = list(checked or [])
    fresh = run_cli([*arguments, "--no-cache", "."], root)
    if checked is not None:
        checked[:] = seen
    assert cached.exit_code == fresh.exit_code == 0, cached.stderr
    return cached.stdout, fresh.stdout


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text(encoding="utf-8")
    assert old in text
    path.write_text(text.replace(old, new), encoding="utf-8")
    stamp = path.stat().st_mtime + 2  # another time than the digests remember
    os.utime(path, (stamp, stamp))


def test_a_rerun_after_an_edit_checks_only_the_edited_file(
    run_cli: Any, workspace: Path, tmp_path: Path, checked_files: list[str]
) -> None:
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    checked_files.clear()
    driver = workspace / "src/robot_base/src/driver.cpp"
    edit(driver, "ros::spin();", "ros::spin();  // spin until shutdown")
    arguments = ["check", "--format", "json", "--jobs", "1", "--exit-zero"]
    run_cli([*arguments, "--cache-dir", str(cache), "."], workspace)
    assert checked_files == ["src/robot_base/src/driver.cpp"]


# Each step: (file below the package, text before, text after); the cached run after it
# must print what a fresh run prints.
STEPS: list[tuple[str, str, str]] = [
    # A clean file gets a finding, then loses it.
    ("scripts/teleop.py", "'cmd_vel'", "'cmd vel'"),
    ("scripts/teleop.py", "'cmd vel'", "'cmd_vel'"),
    # A finding and its suppression.
    ("src/driver.cpp", '"/odom"', '"/Odom"'),
    ("src/driver.cpp", '"/Odom", 10);', '"/Odom", 10);  // NOLINT(RN203)'),
    ("src/driver.cpp", "  // NOLINT(RN203)", ""),
    # A node renamed in the launch file, and the launch file's own finding.
    ("launch/base.launch", 'name="teleop"', 'name="tele-op"'),
    ("launch/base.launch", 'name="tele-op"', 'name="teleop"'),
]


def test_a_sequence_of_edits_gives_what_a_fresh_run_gives(
    run_cli: Any, workspace: Path, tmp_path: Path
) -> None:
    cache = tmp_path / "cache"
    package = workspace / "src/robot_base"
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    for relative, old, new in STEPS:
        edit(package / relative, old, new)
        cached, fresh = outputs(run_cli, workspace, cache)
        assert cached == fresh, (relative, old, new)


def test_what_decides_a_clean_file_s_verdict_besides_itself_keys_the_set(
    run_cli: Any, workspace: Path, tmp_path: Path, checked_files: list[str]
) -> None:
    """The settings, and the package layout (a folder that becomes a package of examples
    makes its files example code), are in the key: a change there checks every file."""
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    write(workspace, "roslint-names.toml", "[rules.RN202]\nextend-allow = ['/odom']\n")
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    checked_files.clear()
    examples = workspace / "src/robot_base/examples"
    write(examples, "package.xml", AMENT_PACKAGE.format(name="robot_examples"))
    write(examples, "talker.py", TELEOP.replace("'cmd_vel'", "'/cmd_vel'"))
    cached, fresh = outputs(run_cli, workspace, cache, checked_files)
    assert cached == fresh
    assert "src/robot_base/src/driver.cpp" in checked_files


def test_a_run_over_some_files_keeps_the_rest_of_the_set(
    run_cli: Any, workspace: Path, tmp_path: Path, checked_files: list[str]
) -> None:
    """pre-commit checks the files it is given: what it judges joins the set, and the
    workspace's other verdicts stay in it for the next whole run. (The settings' root is
    the configuration's folder for both runs; without a configuration a run over one
    file is rooted at its folder, which decides other verdicts: another key.)"""
    write(workspace, "roslint-names.toml", "max-depth = 4\n")
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    teleop = workspace / "src/robot_base/scripts/teleop.py"
    edit(teleop, "queue_size=1", "queue_size=10")
    arguments = ["check", "--format", "json", "--jobs", "1", "--exit-zero", "--cache-dir"]
    run_cli([*arguments, str(cache), "src/robot_base/scripts/teleop.py"], workspace)
    checked_files.clear()
    cached = run_cli([*arguments, str(cache), "."], workspace)
    assert checked_files == []  # driver.cpp's finding is remembered with its verdict
    assert cached.stdout == run_cli([*arguments[:-1], "--no-cache", "."], workspace).stdout


def test_a_damaged_or_foreign_set_is_ignored(
    run_cli: Any, workspace: Path, tmp_path: Path, checked_files: list[str]
) -> None:
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    (stored,) = cache.glob("facts-v*/checks/*")
    stored.write_bytes(stored.read_bytes()[:-3])  # torn
    for kept in cache.glob("facts-v*/graphs/*"):  # else the edit patches the last graph
        kept.unlink()
    teleop = workspace / "src/robot_base/scripts/teleop.py"
    edit(teleop, "'cmd_vel'", "'cmd vel'")
    checked_files.clear()
    cached, fresh = outputs(run_cli, workspace, cache, checked_files)
    assert cached == fresh
    assert "src/robot_base/launch/base.launch" in checked_files  # nothing was known


def skipped_until(
    run_cli: Any,
    workspace: Path,
    cache: Path,
    checked: list[str],
    *,
    watched: str,
    change: Callable[[], object],
) -> str:
    """``watched`` is not checked again after an edit elsewhere, and is after ``change``;
    both runs print what a fresh run prints. The last cached run's JSON."""
    outputs(run_cli, workspace, cache)
    driver = workspace / "src/robot_base/src/driver.cpp"
    edit(driver, "ros::spin();", "ros::spin();  // until shutdown")
    checked.clear()
    cached, fresh = outputs(run_cli, workspace, cache, checked)
    assert cached == fresh
    assert watched not in checked
    change()
    checked.clear()
    cached, fresh = outputs(run_cli, workspace, cache, checked)
    assert cached == fresh
    assert watched in checked
    return cached


MONITOR = """#!/usr/bin/env python
import rospy
from geometry_msgs.msg import Twist


def main():
    rospy.init_node('cmd_monitor')
    rospy.Subscriber('/base/cmd_vel', Twist, lambda message: None)
    rospy.spin()


if __name__ == '__main__':
    main()
"""


def test_a_file_waiting_for_the_wiring_is_clean_under_the_same_wiring(
    run_cli: Any, workspace: Path, tmp_path: Path, checked_files: list[str]
) -> None:
    """``/base/cmd_vel`` is what the launch file wires ``cmd_vel`` to: no RN202 while it
    does. The monitor is skipped while the wiring stays; a launch file that stops wiring
    the name has it checked again, and reported."""
    package = workspace / "src/robot_base"
    write(package, "scripts/cmd_monitor.py", MONITOR)
    launch = package / "launch/base.launch"
    edit(
        launch,
        'name="teleop"/>',
        'name="teleop">\n      <remap from="cmd_vel" to="/base/cmd_vel"/>\n    </node>',
    )
    cached = skipped_until(
        run_cli,
        workspace,
        tmp_path / "cache",
        checked_files,
        watched="src/robot_base/scripts/cmd_monitor.py",
        change=lambda: edit(launch, 'to="/base/cmd_vel"', 'to="/base/cmd_vel_safe"'),
    )
    assert '"path": "src/robot_base/scripts/cmd_monitor.py"' in cached


SERVICE = "---\nbool success\nstring message\n"

CHARGER = """#!/usr/bin/env python
import rospy
from std_srvs.srv import Trigger, TriggerResponse


def main():
    rospy.init_node('charger')
    rospy.Service('start_charging', Trigger, lambda request: TriggerResponse(success=True))
    rospy.spin()


if __name__ == '__main__':
    main()
"""


def test_a_file_waiting_for_the_service_types_is_clean_under_the_same_types(
    run_cli: Any, workspace: Path, tmp_path: Path, checked_files: list[str]
) -> None:
    """RN204 compares ``start_charging`` (served with ``Trigger``) with the service types
    the package can use: skipped while they stay; a ``StartCharging.srv`` added to the
    package makes the name another type's, and the file is checked again."""
    package = workspace / "src/robot_base"
    write(package, "scripts/charger.py", CHARGER)
    cached = skipped_until(
        run_cli,
        workspace,
        tmp_path / "cache",
        checked_files,
        watched="src/robot_base/scripts/charger.py",
        change=lambda: write(
            package, "srv/StartCharging.srv", "---\nbool success\nstring message\n"
        ),
    )
    assert '"code": "RN204"' in cached


def test_a_file_with_findings_or_a_suppression_keeps_its_verdict_until_edited(
    run_cli: Any, workspace: Path, tmp_path: Path, checked_files: list[str]
) -> None:
    """1,576 files with findings were checked again by every run after an edit at 8
    copies of the benchmark's workspace: their verdicts are remembered as clean files
    are, suppressions and RN002 included, and given back as a fresh check makes them."""
    package = workspace / "src/robot_base"
    edit(package / "src/driver.cpp", '"/odom"', '"/Odom"')  # RN203: a finding
    edit(package / "scripts/teleop.py", "queue_size=1)", "queue_size=1)  # noqa: RN202")
    arguments = ["check", "--format", "json", "--jobs", "1", "--extend-select", "RN002"]
    cache = tmp_path / "cache"
    first = run_cli([*arguments, "--cache-dir", str(cache), "."], workspace)
    assert {"RN203", "RN002"} <= {item["code"] for item in json.loads(first.stdout)["findings"]}
    edit(package / "launch/base.launch", 'name="teleop"', 'name="teleop_node"')
    checked_files.clear()
    cached = run_cli([*arguments, "--cache-dir", str(cache), "."], workspace)
    assert checked_files == ["src/robot_base/launch/base.launch"]
    assert cached.stdout == run_cli([*arguments, "--no-cache", "."], workspace).stdout
    edit(package / "src/driver.cpp", '"/Odom"', '"/odom"')
    checked_files.clear()
    cached = run_cli([*arguments, "--cache-dir", str(cache), "."], workspace)
    assert checked_files == ["src/robot_base/src/driver.cpp"]
    assert cached.stdout == run_cli([*arguments, "--no-cache", "."], workspace).stdout


def test_kept_verdicts_of_another_shape_are_nothing() -> None:
    """An older cache's set alone, or a verdict holding anything but findings and
    suppressions as ``stored`` writes them, is no verdict: every file is checked."""
    from roslint_names import clean_files
    from roslint_names.model import Diagnostic, Severity, Span
    from roslint_names.suppress import Suppression

    finding = Diagnostic(
        "a.cpp", Span(1, 1, 1, 2), "RN203", "not-snake-case", Severity.WARNING, "m"
    )
    suppression = Suppression(("RN202",), frozenset({3, 4}), Span(3, 10, 3, 30))
    kept = clean_files.stored([b"clean"], {b"judged": ((finding,), (suppression,))})
    assert clean_files.loaded(kept) == (
        frozenset({b"clean"}),
        {b"judged": ((finding,), (suppression,))},
    )
    nothing: tuple[frozenset[bytes], dict[bytes, Any]] = (frozenset(), {})
    assert clean_files.loaded(frozenset({b"clean"})) == nothing
    assert clean_files.loaded((frozenset({b"clean"}), {b"judged": (("text",), ())})) == nothing
    assert clean_files.loaded((frozenset(), {b"judged": ((finding,), (("RN202",),))})) == nothing
    assert clean_files.loaded((frozenset(), {"judged": ((finding,), ())})) == nothing


def test_a_dependency_added_checks_only_the_files_that_compare_with_service_types(
    run_cli: Any, workspace: Path, tmp_path: Path, checked_files: list[str]
) -> None:
    """What a package.xml says reaches a kept verdict only through its files' generation
    (their facts keys) and the service types a file compares with (its entry's digest):
    a dependency added made every file of the workspace checked again (2.8 s at 8
    copies). Now the files that serve or call a service are; and ``charger.py`` sees
    ``StartCharging`` in the package it now depends on (RN204), as a fresh run does."""
    package = workspace / "src/robot_base"
    write(package, "scripts/charger.py", CHARGER)
    messages = workspace / "src/charging_msgs"
    write(messages, "package.xml", CATKIN_PACKAGE.format(name="charging_msgs"))
    write(messages, "srv/StartCharging.srv", "---\nbool success\nstring message\n")
    cache = tmp_path / "cache"
    before, _ = outputs(run_cli, workspace, cache)
    assert '"code": "RN204"' not in before
    checked_files.clear()
    edit(
        package / "package.xml",
        "<buildtool_depend>catkin</buildtool_depend>",
        "<buildtool_depend>catkin</buildtool_depend>\n  <depend>charging_msgs</depend>",
    )
    cached, fresh = outputs(run_cli, workspace, cache, checked_files)
    assert cached == fresh and '"code": "RN204"' in cached
    # Twice: checked without its text first, then with it, for its finding's line.
    assert set(checked_files) == {"src/robot_base/scripts/charger.py"}

"""Whole-run results: a re-run over unchanged inputs is the stored result, any change to an
input is a fresh run, and damage or a race never yields a wrong result."""

from __future__ import annotations

import io
import os
import pickle
import shutil
import sys
import time
import types
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from roslint_names import cache as cache_module
from roslint_names import checks, engine, generation, reading, run_inputs
from roslint_names import digests as digests_module
from roslint_names.config import Settings, settings_fingerprint
from roslint_names.digests import ContentDigests
from roslint_names.discover import SourceFile
from roslint_names.generation import PackageGenerations
from roslint_names.model import Severity
from tests.conftest import AMENT_PACKAGE, CATKIN_PACKAGE, write

DRIVER = """#include <ros/ros.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>

void onTwist(const geometry_msgs::Twist::ConstPtr& twist) {}

int main(int argc, char** argv) {
  ros::init(argc, argv, "base_driver");
  ros::NodeHandle nh;
  ros::Subscriber twist = nh.subscribe("cmd_vel", 10, onTwist);
  ros::Publisher odometry = nh.advertise<nav_msgs::Odometry>("/odom", 10);
  ros::spin();
  return 0;
}
"""

LAUNCH = """<launch>
  <group ns="robot1">
    <node pkg="robot_base" type="base_driver" name="base_driver">
      <remap from="Cmd_Vel" to="teleop/cmd_vel"/>
    </node>
  </group>
</launch>
"""

CMAKE = """cmake_minimum_required(VERSION 3.0.2)
project(robot_base)
find_package(catkin REQUIRED COMPONENTS roscpp)
catkin_package()
add_executable(base_driver src/driver.cpp)
"""


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    root = tmp_path / "ws"
    package = root / "src" / "robot_base"
    write(package, "package.xml", CATKIN_PACKAGE.format(name="robot_base"))
    write(package, "CMakeLists.txt", CMAKE)
    write(package, "src/driver.cpp", DRIVER)
    write(package, "launch/base.launch", LAUNCH)
    return root


@pytest.fixture
def check(run_cli: Any, workspace: Path) -> Callable[..., Any]:
    """`check --verbose --format json --jobs 1` over ``workspace`` (or a directory below)."""

    def run(*options: str, cwd: Path = workspace) -> Any:
        arguments = ["check", "--verbose", "--format", "json", "--jobs", "1", *options, "."]
        return run_cli(arguments, cwd)

    return run


def reused(result: Any) -> bool:
    return "its result reused" in result.stderr


def stored_runs(cache: Path) -> list[Path]:
    return sorted(path for path in cache.glob("facts-v*/runs/*") if not path.name.startswith("."))


def test_a_rerun_over_unchanged_files_is_the_stored_result(
    check: Callable[..., Any], extractions: list[str], private_cache: Path
) -> None:
    cold = check()
    assert not reused(cold) and len(extractions) == 3  # package.xml is read, not extracted
    assert sorted(cold.codes()) == ["RN202", "RN404"]
    extractions.clear()
    warm = check()
    assert reused(warm) and extractions == []
    assert (warm.stdout, warm.exit_code) == (cold.stdout, cold.exit_code)
    assert len(stored_runs(private_cache)) == 1


@pytest.mark.usefixtures("old_tree")
def test_a_rerun_looks_for_no_manifest_where_the_walk_found_none(
    check: Callable[..., Any], workspace: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """In the directories the walk listed, a package.xml is looked for only where the
    listing holds one (``driver.cpp``'s lookup passes through ``src/``)."""
    age_all(workspace)
    check()
    looked_for: list[str] = []
    real = os.stat

    def counted(path: Any, *arguments: Any, **options: Any) -> os.stat_result:
        if os.fspath(path).endswith("package.xml"):
            looked_for.append(os.fspath(path))
        return real(path, *arguments, **options)

    monkeypatch.setattr(os, "stat", counted)
    assert reused(check())
    inside = [path for path in looked_for if path.startswith(f"{workspace}{os.sep}")]
    assert inside == [os.fspath(workspace / "src/robot_base/package.xml")]


def _edit_code(workspace: Path) -> None:
    driver = workspace / "src/robot_base/src/driver.cpp"
    driver.write_text(driver.read_text().replace('"cmd_vel"', '"Cmd_Vel"'))


def _add_file(workspace: Path) -> None:
    write(workspace, "src/robot_base/launch/two.launch", LAUNCH.replace("robot1", "robot2"))


def _delete_file(workspace: Path) -> None:
    (workspace / "src/robot_base/launch/base.launch").unlink()


def _package_depends(workspace: Path) -> None:
    # Read by the graph rules only: no file's facts change, the manifest's text does.
    manifest = workspace / "src/robot_base/package.xml"
    text = manifest.read_text().replace("</package>", "<depend>roscpp</depend>\n</package>")
    manifest.write_text(text)


def _package_generation(workspace: Path) -> None:
    manifest = workspace / "src/robot_base/package.xml"
    manifest.write_text(manifest.read_text().replace("catkin", "ament_cmake"))


def _nested_package(workspace: Path) -> None:
    # A directory the walk listed with no package.xml gets one: its launch file is now
    # of another package, of another generation.
    write(workspace, "src/robot_base/launch/package.xml", AMENT_PACKAGE.format(name="bringup"))


def _build_file(workspace: Path) -> None:
    # No file's facts but the CMakeLists.txt's change; with the target gone, driver.cpp
    # is compiled by nothing, and its findings go (``workspace.built``).
    build = workspace / "src/robot_base/CMakeLists.txt"
    build.write_text(build.read_text().replace("add_executable", "# add_executable"))


def _config(workspace: Path) -> None:
    write(workspace, "roslint-names.toml", 'ignore = ["RN202"]\n')


def _per_file_ignore(workspace: Path) -> None:
    write(workspace, "roslint-names.toml", '[per-file-ignores]\n"**/base.launch" = ["RN404"]\n')


def _service_definition(workspace: Path) -> None:
    # A .srv file is read by name only: its name is a service type of the run.
    write(workspace, "src/robot_base/srv/CmdVel.srv", "---\nbool ok\n")


# Changes to what a run's result is made from (the first one keeps the file's size).
_CHANGES = (
    _edit_code,
    _add_file,
    _delete_file,
    _package_depends,
    _package_generation,
    _nested_package,
    _build_file,
    _config,
)


@pytest.mark.parametrize("change", [*_CHANGES, _per_file_ignore, _service_definition])
def test_a_changed_input_is_a_fresh_run(
    check: Callable[..., Any], workspace: Path, change: Callable[[Path], None]
) -> None:
    check()
    assert reused(check())
    change(workspace)
    after = check()
    assert not reused(after)
    fresh = check("--no-cache")
    assert (after.stdout, after.exit_code) == (fresh.stdout, fresh.exit_code)
    assert reused(check())


def test_a_command_line_option_is_part_of_the_key(check: Callable[..., Any]) -> None:
    everything = check()
    fewer = check("--ignore", "RN202")
    assert not reused(fewer) and fewer.codes() == ["RN404"]
    assert reused(again := check()) and again.stdout == everything.stdout


def test_the_same_bytes_in_another_place_are_another_run(
    run_cli: Any, tmp_path: Path, private_cache: Path
) -> None:
    # Same display paths, same bytes; per-file-ignores (relative to the config) tell the
    # two directories apart, so the result of one is not the result of the other.
    root = tmp_path / "robots"
    write(root, "roslint-names.toml", '[per-file-ignores]\n"one/**" = ["RN202"]\n')
    for robot in ("one", "two"):
        write(root, f"{robot}/package.xml", CATKIN_PACKAGE.format(name="robot_base"))
        write(root, f"{robot}/src/driver.cpp", DRIVER)
    arguments = ["check", "--format", "json", "--verbose", "."]
    one = run_cli(arguments, root / "one")
    two = run_cli(arguments, root / "two")
    assert not reused(two)
    assert (one.codes(), two.codes()) == ([], ["RN202"])


def test_a_file_changed_while_the_run_reads_it_is_not_kept(
    check: Callable[..., Any],
    workspace: Path,
    monkeypatch: pytest.MonkeyPatch,
    private_cache: Path,
) -> None:
    # A run of a workspace with digests is keyed by a first pass (through the digests)
    # and extracted from what its second pass reads: when they differ, the result is
    # nobody's key. (A file that may hold a suppression is read; the others are not,
    # their cached facts are those of the keyed bytes.)
    launch = workspace / "src/robot_base/launch/base.launch"
    launch.write_text("<!-- checked by roslint-names in CI -->\n" + launch.read_text())
    check()
    [first] = stored_runs(private_cache)
    _edit_code(workspace)  # so that the next run is not the stored one
    real = run_inputs.read_file

    def edited_meanwhile(path: Path, max_size: int) -> Any:
        data, error, skip = real(path, max_size)
        if path.name == "base.launch" and data is not None:
            data = data.replace(b"Cmd_Vel", b"cmd_vel")
        return data, error, skip

    monkeypatch.setattr(run_inputs, "read_file", edited_meanwhile)
    check()
    assert stored_runs(private_cache) == [first]
    monkeypatch.setattr(run_inputs, "read_file", real)
    check()
    assert len(stored_runs(private_cache)) == 2


def test_a_damaged_result_is_ignored_and_rewritten(
    check: Callable[..., Any], private_cache: Path
) -> None:
    good = check()
    [entry] = stored_runs(private_cache)
    blob = entry.read_bytes()
    for damage in (blob[: len(blob) // 2], b"", b"garbage", blob[:-1] + bytes([blob[-1] ^ 1])):
        entry.write_bytes(damage)
        again = check()
        assert not reused(again) and again.stdout == good.stdout
        # The same result again (its objects may share other references: other bytes).
        assert cache_module._decode(entry.read_bytes()) == cache_module._decode(blob)


def test_a_stored_value_that_is_not_a_result_is_a_miss(
    check: Callable[..., Any], private_cache: Path
) -> None:
    good = check()
    [entry] = stored_runs(private_cache)
    # Well-formed, checksummed, of fact classes only, but not a run's result.
    with entry.open("wb") as stream:
        cache_module._encoded((("not a diagnostic",), 1, ()))(stream)
    again = check()
    assert not reused(again) and again.stdout == good.stdout


def test_only_the_most_recently_used_results_are_kept(
    check: Callable[..., Any], monkeypatch: pytest.MonkeyPatch, private_cache: Path
) -> None:
    monkeypatch.setattr(cache_module, "RUNS_KEPT", 2)

    def later(*options: str) -> Any:
        time.sleep(0.05)  # file times tick with the kernel's coarse clock, not per call
        return check(*options)

    later("--ignore", "RN202")
    later("--ignore", "RN404")
    assert reused(later("--ignore", "RN202"))  # now the most recently used of the two
    later("--ignore", "RN203")
    assert len(stored_runs(private_cache)) == 2
    assert reused(check("--ignore", "RN202"))
    assert not reused(check("--ignore", "RN404"))


def test_the_graph_command_neither_reads_nor_writes_results(
    run_cli: Any, workspace: Path, private_cache: Path
) -> None:
    run_cli(["graph", "."], workspace)
    assert stored_runs(private_cache) == []


def test_a_plugin_rules_module_is_in_the_code_fingerprint(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    source = write(tmp_path, "site_rules.py", "CODE = 1\n")
    module = types.ModuleType("site_rules")
    module.__file__ = str(source)
    monkeypatch.setitem(sys.modules, "site_rules", module)
    monkeypatch.setattr(cache_module, "_CODE_FINGERPRINTS", {})
    before = cache_module.code_fingerprint(["site_rules"])
    assert before != cache_module.code_fingerprint()
    source.write_text("CODE = 2\n")
    monkeypatch.setattr(cache_module, "_CODE_FINGERPRINTS", {})
    assert cache_module.code_fingerprint(["site_rules"]) != before


def test_settings_fingerprint_is_the_same_for_equal_settings(tmp_path: Path) -> None:
    one = Settings(root=tmp_path, severity={"RN101": Severity.ERROR, "RN105": Severity.WARNING})
    other = Settings(root=tmp_path, severity={"RN105": Severity.WARNING, "RN101": Severity.ERROR})
    changed = Settings(root=tmp_path, severity={"RN105": Severity.ERROR, "RN101": Severity.ERROR})
    assert settings_fingerprint(one) == settings_fingerprint(other)
    assert settings_fingerprint(one) != settings_fingerprint(changed)
    moved = Settings(root=tmp_path / "elsewhere", severity=dict(one.severity))
    assert settings_fingerprint(one) != settings_fingerprint(moved)


def test_forgetting_results_falls_back_to_the_replay_then_to_the_facts(
    check: Callable[..., Any], extractions: list[str], private_cache: Path
) -> None:
    cold = check()
    # The stored result, then with it the replay of the same facts.
    for forgotten in (("runs",), ("runs", "replays")):
        for kept in (path for kind in forgotten for path in private_cache.glob(f"facts-v*/{kind}")):
            shutil.rmtree(kept)
        extractions.clear()
        warm = check()
        assert not reused(warm) and extractions == [] and warm.stdout == cold.stdout


def counting_reads(monkeypatch: pytest.MonkeyPatch, module: Any) -> list[str]:
    """The names of the files ``module`` reads through ``read_file`` from now on."""
    seen: list[str] = []
    real = module.read_file

    def counting(path: str | Path, max_size: int) -> Any:
        seen.append(os.path.basename(path))
        return real(path, max_size)

    monkeypatch.setattr(module, "read_file", counting)
    return seen


@pytest.fixture
def reads(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The files read to be keyed (``reading.taken``): by the digests (those whose status
    changed), or where they are extracted (all of a first run, with ``--jobs 1`` in this
    process)."""
    return counting_reads(monkeypatch, reading)


def age(workspace: Path, seconds: float = 60) -> None:
    """Every file last modified ``seconds`` ago: past the racy window of the digests."""
    past = time.time() - seconds
    for path in workspace.rglob("*"):
        if path.is_file():
            os.utime(path, (past, past))


@pytest.mark.usefixtures("old_tree")
def test_a_rerun_reads_no_file_whose_status_is_unchanged(
    check: Callable[..., Any], workspace: Path, reads: list[str]
) -> None:
    age(workspace)
    check()
    assert sorted(reads) == ["CMakeLists.txt", "base.launch", "driver.cpp"]
    reads.clear()
    assert reused(check()) and reads == []


@pytest.mark.usefixtures("old_tree")
def test_an_edit_that_keeps_size_and_time_is_still_seen(
    check: Callable[..., Any], workspace: Path, reads: list[str]
) -> None:
    # Same length, modification time put back: the change time still moves.
    age(workspace)
    cold = check()
    launch = workspace / "src/robot_base/launch/base.launch"
    before = launch.stat()
    launch.write_text(launch.read_text().replace("Cmd_Vel", "cmd_vel"))
    os.utime(launch, ns=(before.st_atime_ns, before.st_mtime_ns))
    reads.clear()
    after = check()
    assert reads == ["base.launch"] and not reused(after)
    assert after.codes() != cold.codes()


def test_a_file_modified_just_now_is_read_again_next_time(
    check: Callable[..., Any],
    workspace: Path,
    reads: list[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Written in the same clock tick as its status could be taken: its status proves
    # nothing about its bytes yet (git's "racily clean" files). The window shortened, and
    # the tree left past it before the one file is touched.
    monkeypatch.setattr(reading, "RACY_NANOSECONDS", 300_000_000)
    time.sleep(0.4)
    (workspace / "src/robot_base/src/driver.cpp").touch()
    check()
    reads.clear()
    assert reused(check()) and reads == ["driver.cpp"]


@pytest.mark.usefixtures("old_tree")
def test_the_digests_of_many_files_are_what_each_file_s_digest_is(
    workspace: Path, tmp_path: Path
) -> None:
    """``summaries`` answers in one loop what ``summary`` answers file by file: a digest
    remembered under the status the file has, the digest of a file edited since, a file
    now too large, one that is not text, one gone, one whose status was not taken."""
    package = workspace / "src/robot_base"
    binary = write(package, "launch/blob.launch", "<launch>\0</launch>\n")
    large = write(package, "launch/large.launch", "<launch/>\n")
    paths = [
        os.fspath(path)
        for path in (
            package / "src/driver.cpp",
            package / "launch/base.launch",
            binary,
            large,
            package / "launch/gone.launch",
            package / "CMakeLists.txt",
        )
    ]
    cache = cache_module.FactsCache(tmp_path / "cache")
    first = digests_module.ContentDigests.of(cache, workspace)
    for path in paths:
        first.summary(path, 1 << 20)
    first.save()
    (package / "src/driver.cpp").write_text(DRIVER.replace("cmd_vel", "Cmd_Vel"))
    large.write_text("<launch>\n" + "<!-- padding -->\n" * 100 + "</launch>\n")
    statuses: list[Any] = [reading.status_of(path) for path in paths]
    statuses[-1] = reading.UNTAKEN
    one_by_one = digests_module.ContentDigests.of(cache, workspace)
    expected = [
        one_by_one.summary(path, 1_000, status)
        for path, status in zip(paths, statuses, strict=True)
    ]
    together = digests_module.ContentDigests.of(cache, workspace)
    assert together.summaries(paths, 1_000, statuses) == expected
    assert together.statuses == one_by_one.statuses
    assert together._seen == one_by_one._seen
    assert [skip for _, _, skip in expected][2:5] == [
        reading.BINARY,
        reading.too_large(statuses[3][0], 1_000),
        None,
    ]


def test_damaged_digests_are_ignored(
    check: Callable[..., Any], workspace: Path, reads: list[str], private_cache: Path
) -> None:
    age(workspace)
    good = check()
    [digests] = private_cache.glob("facts-v*/digests/*")
    digests.write_bytes(digests.read_bytes()[:20])
    reads.clear()
    again = check()
    assert reused(again) and again.stdout == good.stdout and len(reads) == 3


def test_digests_that_name_anything_but_builtins_are_never_unpickled(
    check: Callable[..., Any], workspace: Path, reads: list[str], private_cache: Path
) -> None:
    age(workspace)
    check()
    [digests] = private_cache.glob("facts-v*/digests/*")
    digests.write_bytes(pickle.dumps({"x": os.getcwd}))
    reads.clear()
    assert reused(check()) and len(reads) == 3


def test_the_first_run_of_a_workspace_reads_each_file_once(
    check: Callable[..., Any], monkeypatch: pytest.MonkeyPatch, reads: list[str]
) -> None:
    # No digests yet, so no stored result can match: the run is keyed as it reads.
    direct = counting_reads(monkeypatch, engine)
    direct_graph = counting_reads(monkeypatch, checks)  # a graph finding's source line
    check()
    assert sorted(reads) == ["CMakeLists.txt", "base.launch", "driver.cpp"]
    assert direct == [] and direct_graph == ["base.launch"]  # again, for its graph finding
    assert reused(check())


def test_only_the_digests_of_the_most_recent_workspaces_are_kept(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, private_cache: Path
) -> None:
    monkeypatch.setattr(digests_module, "KEPT", 2)
    for robot in ("one", "two", "three"):
        root = tmp_path / robot
        write(root, "package.xml", CATKIN_PACKAGE.format(name="robot_base"))
        write(root, "src/driver.cpp", DRIVER)
        time.sleep(0.05)  # file times tick with the kernel's coarse clock
        run_cli(["check", "."], root)
    assert len(list(private_cache.glob("facts-v*/digests/*"))) == 2


def test_a_rerun_from_the_facts_reads_only_the_files_with_findings_or_suppressions(
    check: Callable[..., Any],
    workspace: Path,
    monkeypatch: pytest.MonkeyPatch,
    private_cache: Path,
) -> None:
    write(
        workspace, "src/robot_base/launch/quiet.launch", "<launch>\n  <arg name='x'/>\n</launch>\n"
    )
    write(
        workspace,
        "src/robot_base/launch/noted.launch",
        '<launch>\n  <node name="helper" pkg="robot_base" type="helper"/>'
        "  <!-- roslint-names: ignore RN404 -->\n</launch>\n",
    )
    # No name at all, but a suppression that silences nothing: RN002 needs its text.
    write(
        workspace, "src/robot_base/src/util.cpp", "int helper() { return 1; }  // NOLINT(RN202)\n"
    )
    cold = check("--extend-select", "RN002")
    assert "RN002" in cold.codes()
    # The next run starts from the facts: no stored result, no replay of the same facts.
    for kept in (*private_cache.glob("facts-v*/runs"), *private_cache.glob("facts-v*/replays")):
        shutil.rmtree(kept)
    read: list[str] = []

    def recording(real: Callable[..., Any]) -> Callable[..., Any]:
        def read_file(path: str | Path, max_size: int) -> Any:
            read.append(os.path.basename(path))
            return real(path, max_size)

        return read_file

    monkeypatch.setattr(run_inputs, "read_file", recording(run_inputs.read_file))
    monkeypatch.setattr(engine, "read_file", recording(engine.read_file))
    monkeypatch.setattr(checks, "read_file", recording(checks.read_file))
    again = check("--extend-select", "RN002")
    assert not reused(again) and again.stdout == cold.stdout
    # driver.cpp has findings, remembered with their lines (``clean_files``): not read;
    # base.launch is read for the names it wires (RN202), noted.launch and util.cpp for
    # their suppressions; quiet.launch, CMakeLists.txt and package.xml are only facts.
    assert sorted(set(read)) == ["base.launch", "noted.launch", "util.cpp"]


# A run whose every input has the status it had is keyed by the key the last run kept
# (``unchanged``). Times are set back to one fixed instant, before and after each change,
# so that only what the change cannot hide (size, change time, inode) can show it.
_INSTANT = 1_700_000_000


def age_all(root: Path, changed_since: int = 0) -> None:
    """Every file and directory under ``root`` (changed since ``changed_since``, in
    nanoseconds: setting a time changes the change time, which would show elsewhere) last
    modified at one fixed instant."""
    for directory, _, files in os.walk(root):
        for path in [directory, *(os.path.join(directory, name) for name in files)]:
            if os.lstat(path).st_ctime_ns >= changed_since:
                os.utime(path, (_INSTANT, _INSTANT), follow_symlinks=False)


@pytest.fixture
def keyed(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """One entry per run keyed file by file (``RunInputs.key_first``)."""
    calls: list[int] = []
    real = run_inputs.RunInputs.key_first

    def counted(self: run_inputs.RunInputs) -> str | None:
        calls.append(1)
        return real(self)

    monkeypatch.setattr(run_inputs.RunInputs, "key_first", counted)
    return calls


def _service_edited(workspace: Path) -> None:
    write(workspace, "src/robot_base/srv/CmdVel.srv", "---\nbool ok\nstring why\n")


def changed_after_a_kept_key(
    run: Callable[[], Any], root: Path, keyed: list[int], change: Callable[[], object]
) -> Any:
    """Run twice (the second keyed by the key the first kept), make ``change`` with the
    times it moves set back, and run again: that run, which the kept key must not key."""
    age_all(root)
    run()
    keyed.clear()
    assert reused(run()) and keyed == []
    before = time.time_ns()
    time.sleep(0.05)  # change times tick with the kernel's coarse clock
    change()
    age_all(root, before)
    after = run()
    assert keyed == [1]
    return after


@pytest.mark.parametrize("change", [*_CHANGES, _service_edited])
@pytest.mark.usefixtures("old_tree")
def test_a_run_keyed_by_statuses_sees_every_change(
    check: Callable[..., Any],
    workspace: Path,
    keyed: list[int],
    change: Callable[[Path], None],
) -> None:
    write(workspace, "src/robot_base/srv/CmdVel.srv", "---\nbool ok\n")
    age_all(workspace)
    cold = check()
    keyed.clear()
    warm = check()
    assert reused(warm) and keyed == [] and warm.stdout == cold.stdout
    before = time.time_ns()
    time.sleep(0.05)  # change times tick with the kernel's coarse clock
    change(workspace)
    age_all(workspace, before)
    after = check()
    assert keyed == [1]
    fresh = check("--no-cache")
    assert (after.stdout, after.exit_code) == (fresh.stdout, fresh.exit_code)
    keyed.clear()
    assert reused(check()) and keyed == []


@pytest.mark.usefixtures("old_tree")
def test_a_package_xml_above_the_linted_directory_is_seen(
    run_cli: Any, tmp_path: Path, keyed: list[int]
) -> None:
    """A manifest that appears between a file and its package, above the directory the
    run was given: no file of the run shows it, the directory's status does."""
    package = tmp_path / "ws/src/robot_base"
    write(package, "package.xml", CATKIN_PACKAGE.format(name="robot_base"))
    write(package, "nodes/src/driver.cpp", DRIVER)
    linted = package / "nodes/src"
    arguments = ["check", "--verbose", "--format", "json", "--jobs", "1", "."]
    after = changed_after_a_kept_key(
        lambda: run_cli(arguments, linted),
        tmp_path / "ws",
        keyed,
        lambda: write(package, "nodes/package.xml", AMENT_PACKAGE.format(name="robot_nodes")),
    )
    assert after.stdout == run_cli([*arguments, "--no-cache"], linted).stdout


@pytest.fixture
def rekeyed(monkeypatch: pytest.MonkeyPatch) -> tuple[list[str], list[str]]:
    """The files given a facts key from their digest, and the manifests looked for."""
    files: list[str] = []
    manifests: list[str] = []
    key_of_digest = cache_module.FactsCache.key_of_digest
    is_manifest = PackageGenerations._is_manifest

    def keyed_file(
        self: cache_module.FactsCache, content: str, path: str, *rest: Any, **options: Any
    ) -> str:
        files.append(Path(path).name)
        return key_of_digest(self, content, path, *rest, **options)

    def looked_for(self: PackageGenerations, directory: str, manifest: str) -> bool:
        manifests.append(manifest)
        return is_manifest(self, directory, manifest)

    monkeypatch.setattr(cache_module.FactsCache, "key_of_digest", keyed_file)
    monkeypatch.setattr(PackageGenerations, "_is_manifest", looked_for)
    return files, manifests


def edited_after_a_run(
    check: Callable[..., Any],
    workspace: Path,
    rekeyed: tuple[list[str], list[str]],
    *changes: Callable[[Path], object],
) -> Any:
    """Run, make ``changes`` with the times they move set back, and run again: that run,
    ``rekeyed`` holding what it alone keyed and looked for."""
    age_all(workspace)
    check()
    for seen in rekeyed:
        seen.clear()
    before = time.time_ns()
    time.sleep(0.05)  # change times tick with the kernel's coarse clock
    for change in changes:
        change(workspace)
    age_all(workspace, before)
    return check()


@pytest.mark.usefixtures("old_tree")
def test_the_run_after_an_edit_keys_the_edited_file_alone(
    check: Callable[..., Any],
    workspace: Path,
    keyed: list[int],
    rekeyed: tuple[list[str], list[str]],
) -> None:
    """It takes up what the last run's key was made of (``unchanged.Keying``): no
    package.xml is looked for again, each other file keeps its facts key; and prints what
    a run with no cache prints."""
    after = edited_after_a_run(check, workspace, rekeyed, _edit_code)
    files, manifests = rekeyed
    assert keyed == [1, 1] and files == ["driver.cpp"] and manifests == []
    assert after.stdout == check("--no-cache").stdout
    keyed.clear()
    assert reused(check()) and keyed == []  # and it kept its own key


@pytest.mark.usefixtures("old_tree")
def test_runs_after_edits_load_no_digest_and_journal_those_they_read(
    check: Callable[..., Any],
    workspace: Path,
    rekeyed: tuple[list[str], list[str]],
    reads: list[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A run keyed from the last run's keying (the same files) loads no file's digest
    (0.2 s of it at 8 copies of the benchmark's workspace) and journals the digests of
    the files it read over those kept; so does a run over a file more in a directory the
    last run looked up (the keying renumbered: ``KeptKey.keying``), which keys only the
    new file; a run keyed from the digests after them (a file in a new directory: no
    keying) finds every other file's digest as it is, and reads only the new file."""
    loads: list[int] = []
    load = ContentDigests._load

    def counted(self: ContentDigests) -> Any:
        loads.append(1)
        return load(self)

    monkeypatch.setattr(ContentDigests, "_load", counted)

    def after(change: Callable[[Path], object]) -> Any:
        loads.clear()
        reads.clear()
        rekeyed[0].clear()
        before = time.time_ns()
        time.sleep(0.05)  # change times tick with the kernel's coarse clock
        change(workspace)
        age_all(workspace, before)
        return check()

    for module in range(12):  # more files than the edits change 1/4 of (``journal``)
        for name in ("util.cpp", "util.hpp"):
            write(workspace, f"src/robot_base/src/module{module}/{name}", "int helper();\n")
    # A ``.srv`` file's digest is carried as the checked files' are, not read again.
    write(workspace, "src/robot_base/srv/CmdVel.srv", "---\nbool ok\n")
    age_all(workspace)
    check()
    first = after(_edit_code)
    assert loads == [] and rekeyed[0] == ["driver.cpp"] and reads == ["driver.cpp"]
    assert first.stdout == check("--no-cache").stdout
    second = after(_edit_launch)
    assert loads == [] and rekeyed[0] == ["base.launch"]
    assert second.stdout == check("--no-cache").stdout
    added = after(_add_file)
    # Its place is hashed anew, with the ``.srv`` files' digests (read: none is loaded).
    assert loads == [] and rekeyed[0] == ["two.launch"]
    assert reads == ["two.launch", "CmdVel.srv"]
    assert added.stdout == check("--no-cache").stdout
    elsewhere = after(_add_file_in_a_new_directory)
    assert loads == [1] and reads == ["three.launch"]
    assert elsewhere.stdout == check("--no-cache").stdout


@pytest.mark.parametrize("damage", ["not a pickle", "another run's", "not paths"])
@pytest.mark.usefixtures("old_tree")
def test_a_file_added_after_damaged_kept_files_keys_every_file(
    check: Callable[..., Any],
    workspace: Path,
    private_cache: Path,
    rekeyed: tuple[list[str], list[str]],
    damage: str,
) -> None:
    """The kept key's status files (``KeptKey.keying``, renumbered by them) unreadable, of
    another run or not paths: the run is keyed file by file, as before any was kept."""

    def damaged(_: Path) -> None:
        (files,) = private_cache.glob("facts-v*/keys/*.files")
        form, identity, wheres, checked = pickle.loads(files.read_bytes())
        files.write_bytes(
            {
                "not a pickle": b"not a pickle",
                "another run's": pickle.dumps((form, "another", wheres, checked)),
                "not paths": pickle.dumps((form, identity, [[where] for where in wheres], checked)),
            }[damage]
        )

    after = edited_after_a_run(check, workspace, rekeyed, damaged, _add_file)
    assert len(rekeyed[0]) == 4  # every file, the new one among them
    assert after.stdout == check("--no-cache").stdout


def _add_file_in_a_new_directory(workspace: Path) -> None:
    launch = LAUNCH.replace("robot1", "robot3")
    write(workspace, "src/robot_base/launch/more/three.launch", launch)


def _edit_launch(workspace: Path) -> None:
    launch = workspace / "src/robot_base/launch/base.launch"
    launch.write_text(launch.read_text().replace("</launch>", "<!-- tuned -->\n</launch>"))


@pytest.mark.parametrize("change", [_package_depends, _package_generation, _service_edited])
@pytest.mark.usefixtures("old_tree")
def test_a_changed_manifest_or_service_is_read_again_after_an_edit(
    check: Callable[..., Any],
    workspace: Path,
    rekeyed: tuple[list[str], list[str]],
    change: Callable[[Path], None],
) -> None:
    """What the packages say is taken up where every manifest says what it said but for
    its dependencies (a manifest depending on others is read again, no package looked
    up); the run's place only where every manifest and ``.srv`` file is as it was."""
    write(workspace, "src/robot_base/srv/CmdVel.srv", "---\nbool ok\n")
    after = edited_after_a_run(check, workspace, rekeyed, _edit_code, change)
    files, manifests = rekeyed
    if change is _package_generation:
        assert manifests and len(files) == 3  # every file keyed again
    else:
        assert (manifests, files) == ([], ["driver.cpp"])
    assert after.stdout == check("--no-cache").stdout


@pytest.mark.parametrize(
    "made_of",
    [
        b"not a pickle",
        pickle.dumps((["one tag"], None)),  # the wrong number of tags, no lookups
        pickle.dumps((["a", "b", "c"], ([("robot_base", 7, (), "/")], {"/": 3}, {}, []))),
        pickle.dumps((types.SimpleNamespace(), None)),  # a class: refused
    ],
)
@pytest.mark.usefixtures("old_tree")
def test_a_damaged_kept_keying_keys_every_file(
    check: Callable[..., Any],
    workspace: Path,
    private_cache: Path,
    rekeyed: tuple[list[str], list[str]],
    made_of: bytes,
) -> None:
    def damaged(_: Path) -> None:
        (kept,) = [
            path for path in private_cache.glob("facts-v*/keys/*") if path.suffix != ".files"
        ]
        data = kept.read_bytes()
        stream = io.BytesIO(data)
        header = pickle.load(stream)  # what the key is made of follows it (``KeptKey.keep``)
        assert len(header) == 9 and isinstance(header[-2], str)
        kept.write_bytes(data[: stream.tell()] + made_of)

    after = edited_after_a_run(check, workspace, rekeyed, damaged, _edit_code)
    files, _ = rekeyed
    assert after.exit_code == 1 and len(files) == 3
    assert after.stdout == check("--no-cache").stdout


@pytest.mark.usefixtures("old_tree")
def test_an_edit_journals_the_digests_and_listings_it_changed(
    check: Callable[..., Any], workspace: Path, private_cache: Path
) -> None:
    """The digests and the listings of 77,000 files are not written whole for the few an
    edit changed (``journal``): their bases stay as they were."""
    for module in range(12):  # more files and directories than an edit changes 1/4 of
        for name in ("util.cpp", "util.hpp"):
            write(workspace, f"src/robot_base/src/module{module}/{name}", "int helper();\n")
    age_all(workspace)
    check()
    kept = sorted(private_cache.glob("facts-v*/[dl][ii][gs]*/*"))
    bases = [path for path in kept if path.suffix != ".walked"]  # the walk whole: ``walks``
    assert [path.parent.name for path in bases] == ["digests", "listings"]
    written = [path.read_bytes() for path in bases]
    before = time.time_ns()
    time.sleep(0.05)
    _edit_code(workspace)
    _add_file(workspace)
    age_all(workspace, before)
    after = check()
    assert [path.read_bytes() for path in bases] == written
    # The digests journaled; the listings not even read: the walk was taken whole, the
    # directories that hold another file walked again (``walks``).
    journaled = [
        path.parent.name for path in bases if path.with_name(f"{path.name}-journal").exists()
    ]
    assert journaled == ["digests"]
    assert after.stdout == check("--no-cache").stdout
    again = check()
    assert reused(again) and again.stdout == after.stdout


def _package_released(workspace: Path) -> None:
    manifest = workspace / "src/robot_base/package.xml"
    manifest.write_text(manifest.read_text().replace("0.1.0", "0.2.0").replace("Dev<", "Ops<"))


@pytest.mark.usefixtures("old_tree")
def test_a_manifest_that_says_what_it_said_is_as_kept(
    check: Callable[..., Any],
    workspace: Path,
    keyed: list[int],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A release (another version, maintainer): the run reads that manifest and takes
    the kept key, no file keyed, no package looked up; the run after it, the same."""
    read: list[str] = []
    digest = generation.manifest_digest

    def reading(path: str) -> str | None:
        read.append(Path(path).name)
        return digest(path)

    monkeypatch.setattr(run_inputs, "manifest_digest", reading)
    age_all(workspace)
    cold = check()
    keyed.clear()
    before = time.time_ns()
    time.sleep(0.05)  # change times tick with the kernel's coarse clock
    _package_released(workspace)
    age_all(workspace, before)
    after = check()
    assert reused(after) and keyed == [] and read == ["package.xml"]
    assert after.stdout == cold.stdout == check("--no-cache").stdout
    keyed.clear()
    assert reused(check()) and keyed == []


@pytest.fixture
def run_just_after(
    check: Callable[..., Any],
    workspace: Path,
    rekeyed: tuple[list[str], list[str]],
    monkeypatch: pytest.MonkeyPatch,
) -> Callable[[Callable[[Path], None]], None]:
    """A run just after an edit (the edited file's status within the racy window);
    ``rekeyed`` cleared after it."""

    def run(edit: Callable[[Path], None]) -> None:
        monkeypatch.setattr(reading, "RACY_NANOSECONDS", 1_000_000_000)
        age_all(workspace)
        time.sleep(1.1)  # every status but the edited file's past the racy window
        edit(workspace)
        check()
        for seen in rekeyed:
            seen.clear()

    return run


def test_a_file_edited_within_the_racy_window_is_kept_as_changed(
    check: Callable[..., Any],
    keyed: list[int],
    rekeyed: tuple[list[str], list[str]],
    run_just_after: Callable[[Callable[[Path], None]], None],
) -> None:
    """A run just after an edit keeps its key with that file as changed (its status may
    hide a later edit): the next run keys that file again, and only it."""
    run_just_after(_edit_code)
    files, manifests = rekeyed
    keyed.clear()
    again = check()
    assert reused(again) and keyed == [1] and files == ["driver.cpp"] and manifests == []


def test_a_manifest_edited_just_before_a_run_is_kept_by_its_text(
    check: Callable[..., Any],
    workspace: Path,
    keyed: list[int],
    rekeyed: tuple[list[str], list[str]],
    run_just_after: Callable[[Callable[[Path], None]], None],
) -> None:
    """Its status may hide a later edit, so the key is kept with the digest of the text
    the run read, which the next run compares with the text now: the stored result, or
    after an edit of code the last run's keying (no manifest looked for again), as for
    any other run."""
    run_just_after(_package_depends)
    again = check()
    assert reused(again) and keyed == [1]  # the first run's alone
    _edit_code(workspace)
    after = check()
    files, manifests = rekeyed
    assert files == ["driver.cpp"] and manifests == []
    assert after.stdout == check("--no-cache").stdout


def test_a_manifest_kept_by_its_text_and_edited_again_is_read_again(
    check: Callable[..., Any],
    workspace: Path,
    rekeyed: tuple[list[str], list[str]],
    run_just_after: Callable[[Callable[[Path], None]], None],
) -> None:
    """A dependency added just before a run, then another: not the result of the run
    before; the kept lookups are taken up with that manifest read again, no package
    looked up, no file keyed again."""
    run_just_after(_package_depends)
    manifest = workspace / "src/robot_base/package.xml"
    manifest.write_text(manifest.read_text().replace("roscpp", "rospy"))
    after = check()
    assert rekeyed == ([], [])
    assert not reused(after) and after.stdout == check("--no-cache").stdout


def test_a_verbose_rerun_over_a_directory_makes_no_path_of_its_files(
    check: Callable[..., Any], monkeypatch: pytest.MonkeyPatch
) -> None:
    """``--verbose`` says the fate of each file named on the command line; a directory's
    files are none of them, and a ``Path`` for each of 77,000 cost 0.35 s of a re-run."""
    check()
    made: list[str] = []
    real = SourceFile.path

    def path(self: SourceFile) -> Path:
        made.append(self.location)
        return real.func(self)

    monkeypatch.setattr(SourceFile, "path", property(path))
    assert reused(check()) and made == []


def test_a_status_taken_just_after_a_change_keeps_no_key(
    check: Callable[..., Any], workspace: Path, keyed: list[int]
) -> None:
    """An edit in the same clock tick as the status was taken would not show in it."""
    age_all(workspace)
    _edit_code(workspace)  # modified now: within the racy window
    check()
    keyed.clear()
    assert reused(check()) and keyed == [1]  # keyed file by file: no key was kept


@pytest.mark.usefixtures("old_tree")
def test_the_same_files_shown_from_elsewhere_are_not_the_kept_key(
    run_cli: Any, workspace: Path, keyed: list[int]
) -> None:
    """Run from the workspace, then from its parent: the same files with the same
    statuses, shown under other paths (``ws/src/...``)."""
    arguments = ["check", "--verbose", "--format", "json", "--jobs", "1"]
    age_all(workspace)
    run_cli([*arguments, "."], workspace)
    keyed.clear()
    above = run_cli([*arguments, "ws"], workspace.parent)
    assert keyed == [1]
    assert above.stdout == run_cli([*arguments, "--no-cache", "ws"], workspace.parent).stdout
    assert '"ws/src/robot_base/launch/base.launch"' in above.stdout


@pytest.mark.usefixtures("old_tree")
def test_a_manifest_link_to_nothing_that_becomes_a_file_is_seen(
    run_cli: Any, workspace: Path, keyed: list[int]
) -> None:
    """A package.xml generated by a configure step, linked from the package: until then a
    link to nothing. Its target appears elsewhere; the package's directory keeps its
    times, the link's own status is what shows it."""
    package = workspace / "src/robot_base"
    (package / "package.xml").unlink()
    # Where the lookup stops meanwhile (a directory above, such as /tmp, changes all the
    # time: its status is never kept).
    write(workspace, "package.xml", CATKIN_PACKAGE.format(name="robot_tools"))
    (workspace / "generated").mkdir()
    os.symlink("../../generated/robot_base.xml", package / "package.xml")
    linted = package / "src"
    arguments = ["check", "--verbose", "--format", "json", "--jobs", "1", "."]
    after = changed_after_a_kept_key(
        lambda: run_cli(arguments, linted),
        workspace,
        keyed,
        lambda: write(
            workspace, "generated/robot_base.xml", AMENT_PACKAGE.format(name="robot_base")
        ),
    )
    assert after.stdout == run_cli([*arguments, "--no-cache"], linted).stdout


def test_a_manifest_that_cannot_be_reached_keeps_its_status(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A package.xml behind a directory the user may not search: not read, and its status
    (none) kept, so that the day it can be reached shows."""
    package = tmp_path / "robot_base"
    write(package, "package.xml", CATKIN_PACKAGE.format(name="robot_base"))
    driver = write(package, "src/driver.cpp", DRIVER)
    manifest = os.fspath(package / "package.xml")
    real = os.stat

    def refused(path: Any, *arguments: Any, **options: Any) -> os.stat_result:
        if os.fspath(path) == manifest:
            raise PermissionError(13, "Permission denied", manifest)
        return real(path, *arguments, **options)

    monkeypatch.setattr(os, "stat", refused)
    packages = PackageGenerations()
    assert packages.package_name(driver) is None
    assert manifest in packages.statuses and packages.statuses[manifest] is None


@pytest.mark.usefixtures("old_tree")
def test_a_package_added_to_the_workspace_of_a_run_over_one_file_is_seen(
    run_cli: Any, workspace: Path, keyed: list[int]
) -> None:
    """Pre-commit's run over one file, with no graph rule: the plugin names still come
    from every package of its workspace, and a package that exports one is new."""
    arguments = ["check", "--verbose", "--format", "json", "--select", "RN203", "--jobs", "1"]
    driver = "src/robot_base/src/driver.cpp"
    age_all(workspace)
    run_cli([*arguments, driver], workspace)
    keyed.clear()
    assert reused(run_cli([*arguments, driver], workspace)) and keyed == []
    before = time.time_ns()
    time.sleep(0.05)  # change times tick with the kernel's coarse clock
    plugins = workspace / "src/nav_plugins"
    export = '  <export><nav_core plugin="${prefix}/planners.xml"/></export>\n</package>'
    write(
        plugins,
        "package.xml",
        CATKIN_PACKAGE.format(name="nav_plugins").replace("</package>", export),
    )
    write(plugins, "planners.xml", PLANNERS)
    age_all(workspace, before)
    after = run_cli([*arguments, driver], workspace)
    assert keyed == [1]
    assert after.stdout == run_cli([*arguments, "--no-cache", driver], workspace).stdout


PLANNERS = """<library path="lib/libnav_plugins">
  <class name="nav_plugins/FastPlanner" type="nav_plugins::FastPlanner"
         base_class_type="nav_core::BaseLocalPlanner"/>
</library>
"""

MODE_SERVER = """#include <ros/ros.h>
#include <robot_base/SetMode.h>

bool onSetMode(robot_base::SetMode::Request& req, robot_base::SetMode::Response& res) {
  return true;
}

int main(int argc, char** argv) {
  ros::init(argc, argv, "mode_server");
  ros::NodeHandle nh;
  ros::ServiceServer server = nh.advertiseService("set_mode", onSetMode);
  ros::spin();
}
"""
MODE_CLIENT = MODE_SERVER.replace("SetMode.h", "SetModeAlt.h").replace(
    'ros::ServiceServer server = nh.advertiseService("set_mode", onSetMode);',
    'ros::ServiceClient client = nh.serviceClient<robot_base::SetModeAlt>("set_mode");',
)


MODES_LAUNCH = """<launch>
  <node pkg="robot_base" type="mode_server" name="mode_server"/>
  <node pkg="robot_base" type="mode_client" name="mode_client"/>
</launch>
"""


def _definition(field: str) -> str:
    """A service definition past a ``max-file-size`` of 2,048 bytes: the definitions are
    read whole (up to 1 MiB) however large the files linted may be."""
    documentation = "".join(
        f"# Line {i} of what operators read about the modes.\n" for i in range(50)
    )
    return f"{documentation}{field} mode\n---\nbool success\n"


def test_a_service_definition_past_the_file_size_limit_is_keyed_by_its_bytes(
    check: Callable[..., Any], workspace: Path
) -> None:
    package = workspace / "src/robot_base"
    build = CMAKE + "add_executable(mode_server src/mode_server.cpp)\n"
    write(package, "CMakeLists.txt", build + "add_executable(mode_client src/mode_client.cpp)\n")
    write(package, "launch/modes.launch", MODES_LAUNCH)
    write(package, "src/mode_server.cpp", MODE_SERVER)
    write(package, "src/mode_client.cpp", MODE_CLIENT)
    write(package, "srv/SetMode.srv", _definition("uint8"))
    alternative = write(package, "srv/SetModeAlt.srv", _definition("uint8"))
    write(workspace, "roslint-names.toml", "max-file-size = 2048\n")
    assert alternative.stat().st_size > 2048
    assert "RN403" not in check().codes()
    alternative.write_text(_definition("int8 "))  # another type, the same size
    after = check()
    assert "RN403" in after.codes()
    assert (after.stdout, after.exit_code) == (
        check("--no-cache").stdout,
        check("--no-cache").exit_code,
    )


def test_times_set_back_just_now_keep_no_key(
    check: Callable[..., Any], workspace: Path, keyed: list[int]
) -> None:
    """Modification times set back (``cp -p``, ``rsync -t``): the change time says the
    files were written just now, and is what the racy window is measured on."""
    age_all(workspace)
    check()
    keyed.clear()
    assert reused(check()) and keyed == [1]


@pytest.mark.usefixtures("old_tree")
def test_a_directory_above_that_changes_for_other_reasons_keeps_the_key(
    check: Callable[..., Any], workspace: Path, keyed: list[int]
) -> None:
    """A file outside any package is looked up to the root, through the home directory
    or ``/tmp``, which change all the time: only a package.xml appearing there matters."""
    write(workspace, "tools/record_bag.py", "import rospy\nrospy.init_node('Recorder')\n")
    age_all(workspace)
    cold = check()
    keyed.clear()
    write(workspace.parent, "notes.txt", "written beside the workspace\n")
    warm = check()
    assert reused(warm) and keyed == [] and warm.stdout == cold.stdout
    write(workspace.parent, "package.xml", CATKIN_PACKAGE.format(name="everything"))
    after = check()
    assert keyed == [1]
    assert after.stdout == check("--no-cache").stdout


def test_the_identity_tells_apart_which_files_are_checked_and_named(tmp_path: Path) -> None:
    """The files checked and named are hashed as where they are among the workspace's when
    they are its own objects, as their columns otherwise: any other choice of files is
    another identity, and the same choice the same."""
    from roslint_names.discover import SourceFile
    from roslint_names.model import Generation, Language
    from roslint_names.registry import load_registry

    names = ["a/package.xml", "a/launch/a.launch", "a/src/a.cpp", "b/src/b.cpp"]
    files = [SourceFile(str(tmp_path / name), name, Language.CPP) for name in names]

    def identity(checked: list[int], named: list[int], copies: bool = False) -> str:
        pick = [
            SourceFile(files[i].location, files[i].display, files[i].language)
            if copies
            else files[i]
            for i in checked
        ]
        inputs = run_inputs.RunInputs(
            cache_module.FactsCache(tmp_path / "cache"),
            pick,
            files,
            reported=len(pick),
            settings=Settings(root=tmp_path),
            registry=load_registry(),
            packages=PackageGenerations(),
            fallback=Generation.ROS1,
            ros1_python2=False,
            named=[files[i] for i in named],
        )
        return inputs._identity

    whole = identity([1, 2, 3], [0, 1, 2, 3])
    assert identity([1, 2, 3], [0, 1, 2, 3]) == whole
    others = {
        identity([1, 2], [0, 1, 2, 3]),
        identity([2, 1, 3], [0, 1, 2, 3]),
        identity([1, 2, 3], [0, 1, 2]),
        identity([0, 1, 2, 3], [0, 1, 2, 3]),
        identity([1, 2, 3], [0, 1, 2, 3], copies=True),  # columns, not positions
    }
    assert len(others) == 5 and whole not in others
    assert identity([1, 2], [0, 1, 2], copies=True) == identity([1, 2], [0, 1, 2], copies=True)


def _statuses_workspace(root: Path, count: int) -> list[str]:
    """``count`` source files of a package, and one path that is none."""
    package = root / "src" / "probe"
    write(package, "package.xml", AMENT_PACKAGE.format(name="probe"))
    paths = [
        str(write(package, f"src/node_{index}.cpp", f"// node {index}\nint main() {{}}\n"))
        for index in range(count)
    ]
    return [*paths, str(package / "src" / "absent.cpp")]


def test_packed_statuses_are_the_statuses_of_each_file(tmp_path: Path) -> None:
    """``reading.Statuses``: each file's ``status_of`` (None where it has none), sliced,
    taken by index, replaced and written as bytes and read again unchanged."""
    paths = _statuses_workspace(tmp_path, 600)
    statuses = reading.statuses_of(paths)
    expected = [reading.status_of(path) for path in paths]
    assert list(statuses) == expected and len(statuses) == len(paths)
    assert [statuses[index] for index in (0, 599, 600, -1)] == [
        expected[0],
        expected[599],
        None,
        None,
    ]
    assert list(statuses[598:]) == expected[598:] and statuses[598:] == statuses[598:601]
    assert statuses.sizes() == [0 if status is None else status[0] for status in expected]
    assert list(statuses.taking([600, 3, -1])) == [None, expected[3], None]
    assert list(statuses.replaced({3: None, 600: (1, 2, 3, 4)})) == [
        *expected[:3],
        None,
        *expected[4:600],
        (1, 2, 3, 4),
    ]
    assert reading.Statuses.from_bytes(statuses.to_bytes()) == statuses
    assert reading.Statuses.from_bytes(statuses.to_bytes()[:-1]) is None
    assert reading.Statuses.of(expected) == statuses


def test_packed_statuses_name_the_files_a_run_keys_again(tmp_path: Path) -> None:
    """``Statuses.unvouched``: those of another status than kept (one edited in a block of
    files otherwise as kept, one kept as changed) and those without one, even where a
    whole block is as kept; and only the first ``count``. ``changed_from``: a status too
    recent is kept as changed, nothing else."""
    paths = _statuses_workspace(tmp_path, 600)
    kept = reading.statuses_of(paths)
    time.sleep(0.05)  # past the clock tick the files were written in
    edited = Path(paths[300])
    os.utime(edited, ns=(0, 1_000_000_000))  # another modification time, the same bytes
    now = reading.statuses_of(paths)
    assert list(now.unvouched(kept, len(paths))) == [300, 600]
    assert list(now.unvouched(kept, 300)) == []
    status = now[300]
    assert isinstance(status, tuple)
    changed = now.changed_from(status[2])  # its change time: later than every write
    assert [index for index, found in enumerate(changed) if found is False] == [300]
    assert changed[299] == now[299] and changed[600] is None
    assert list(now.unvouched(changed, len(paths))) == [300, 600]
    assert now.changed_from(time.time_ns() + 10**9) == now

"""What the tool writes into the user's tree: atomic, only onto the bytes an edit was
computed from, every file of a change or none (``editing.files``), tried with the faults
that broke files before: kills, full disks, files edited or read-only, links, two runs."""

from __future__ import annotations

import errno
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from conftest import write, write_package

from roslint_names.editing import files
from roslint_names.editing.files import Change, Snapshot, WriteError, replace_all

TALKER = """#include <chrono>
#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

using namespace std::chrono_literals;

class Talker : public rclcpp::Node
{
public:
  Talker() : Node("talker")
  {
    publisher_ = create_publisher<std_msgs::msg::String>("robotStatus", 10);
    timer_ = create_wall_timer(500ms, [this]() {
      std_msgs::msg::String message;
      message.data = "ok";
      publisher_->publish(message);
    });
  }

private:
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr publisher_;
  rclcpp::TimerBase::SharedPtr timer_;
};

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<Talker>());
  rclcpp::shutdown();
  return 0;
}
"""
LISTENER = """#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/string.hpp"

class Listener : public rclcpp::Node
{
public:
  Listener() : Node("listener")
  {
    subscription_ = create_subscription<std_msgs::msg::String>(
      "robotStatus", 10,
      [this](const std_msgs::msg::String & message) {
        RCLCPP_INFO(get_logger(), "status: %s", message.data.c_str());
      });
  }

private:
  rclcpp::Subscription<std_msgs::msg::String>::SharedPtr subscription_;
};

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<Listener>());
  rclcpp::shutdown();
  return 0;
}
"""
# A ROS 2 launch file with one safe fix (the namespace's trailing slash, RN102).
EKF_LAUNCH = """<launch>
  <arg name="use_sim_time" default="false"/>
  <node pkg="robot_localization" exec="ekf_node" name="ekf_filter_node" namespace="localization/">
    <param name="frequency" value="30.0"/>
    <param name="two_d_mode" value="true"/>
    <param name="use_sim_time" value="$(var use_sim_time)"/>
    <param from="$(find-pkg-share robot_bringup)/config/ekf.yaml"/>
    <remap from="odometry/filtered" to="odom/filtered"/>
  </node>
</launch>
"""
EKF_FIXED = EKF_LAUNCH.replace('namespace="localization/"', 'namespace="localization"')


def _talker_and_listener(root: Path) -> tuple[Path, Path]:
    write_package(root / "src/chatter", 2, "chatter")
    return (
        write(root, "src/chatter/src/talker.cpp", TALKER),
        write(root, "src/chatter/src/listener.cpp", LISTENER),
    )


def _launch_files(root: Path, count: int, padding: int = 0) -> list[Path]:
    write_package(root / "src/robot_bringup", 2)
    comment = "<!-- " + "x" * max(0, padding - 9) + " -->\n" if padding else ""
    text = EKF_LAUNCH.replace("</launch>\n", comment + "</launch>\n")
    return [
        write(root, f"src/robot_bringup/launch/ekf_{n:03}.launch.xml", text) for n in range(count)
    ]


def _snapshot_of(root: Path, *paths: Path) -> tuple[Snapshot, list[str]]:
    snapshot = Snapshot(root, [root])
    displays = [path.relative_to(root).as_posix() for path in paths]
    snapshot.remember(displays)
    return snapshot, displays


def _changes(root: Path, paths: list[Path]) -> list[Change]:
    return [
        Change(
            path.relative_to(root).as_posix(), path.read_bytes(), path.read_bytes() + b"<!--x-->"
        )
        for path in paths
    ]


def _temporaries(root: Path) -> list[Path]:
    return [path for path in root.rglob("*") if path.name.endswith(files.TEMPORARY_SUFFIX)]


# ---------------------------------------------------------------------------------------
# The write path itself


@pytest.mark.parametrize(
    ("fault", "expected", "message"),
    [
        # A replace refused: the error names the file and says nothing changed.
        (OSError(errno.EIO, "Input/output error"), WriteError, "input/output error: nothing"),
        # Ctrl-C between two replaces: the first file is put back too.
        (KeyboardInterrupt(), KeyboardInterrupt, None),
    ],
)
def test_a_fault_between_replaces_puts_back_the_files_already_replaced(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    fault: BaseException,
    expected: type[BaseException],
    message: str | None,
) -> None:
    paths = _launch_files(tmp_path, 3)
    before = [path.read_bytes() for path in paths]
    real_replace = os.replace
    calls = []

    def replace_failing_second(source: Any, target: Any) -> None:
        calls.append(target)
        if len(calls) == 2:
            raise fault
        real_replace(source, target)

    monkeypatch.setattr(os, "replace", replace_failing_second)
    with pytest.raises(expected, match=message):
        replace_all(_changes(tmp_path, paths), cwd=tmp_path, roots=[tmp_path])
    assert [path.read_bytes() for path in paths] == before
    assert _temporaries(tmp_path) == []


@pytest.mark.parametrize(
    ("fault", "expected", "message"),
    [
        # A full disk: the error names the file and says nothing changed.
        (
            OSError(errno.ENOSPC, "No space left on device"),
            WriteError,
            "no space left on device writing src/robot_bringup/launch/ekf_001.launch.xml: "
            "nothing was changed",
        ),
        # Ctrl-C: the temporaries already written are removed too.
        (KeyboardInterrupt(), KeyboardInterrupt, ""),
    ],
)
def test_a_fault_on_the_second_of_three_temporaries_changes_none(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    fault: BaseException,
    expected: type[BaseException],
    message: str,
) -> None:
    paths = _launch_files(tmp_path, 3)
    before = [path.read_bytes() for path in paths]
    real_fsync = os.fsync
    calls = []

    def fsync_failing_at_second(descriptor: int) -> None:
        calls.append(descriptor)
        if len(calls) == 2:
            raise fault
        real_fsync(descriptor)

    monkeypatch.setattr(os, "fsync", fsync_failing_at_second)
    with pytest.raises(expected) as raised:
        replace_all(_changes(tmp_path, paths), cwd=tmp_path, roots=[tmp_path])
    assert str(raised.value) == message
    assert [path.read_bytes() for path in paths] == before
    assert _temporaries(tmp_path) == []


def test_a_file_changed_since_it_was_read_is_left_alone(tmp_path: Path) -> None:
    (path,) = _launch_files(tmp_path, 1)
    snapshot, (display,) = _snapshot_of(tmp_path, path)
    data, why = snapshot.for_edit(display)
    assert data is not None and why == ""
    edited = EKF_LAUNCH.replace("30", "50")  # an editor saves while the run goes on
    path.write_text(edited, encoding="utf-8")
    with pytest.raises(WriteError, match="changed since it was read; run again"):
        snapshot.replace_all([Change(display, data, EKF_FIXED.encode())])
    assert path.read_text(encoding="utf-8") == edited
    # Read again, the edit is refused before it is computed.
    assert snapshot.for_edit(display) == (None, "changed since it was read; run again")


def test_the_mode_of_a_file_is_kept(tmp_path: Path) -> None:
    (path,) = _launch_files(tmp_path, 1)
    path.chmod(0o640)
    snapshot, (display,) = _snapshot_of(tmp_path, path)
    snapshot.replace_all([Change(display, path.read_bytes(), EKF_FIXED.encode())])
    assert path.read_text(encoding="utf-8") == EKF_FIXED
    assert path.stat().st_mode & 0o777 == 0o640


def test_a_run_holding_a_file_makes_another_wait_then_give_up(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    fcntl = pytest.importorskip("fcntl")
    (path,) = _launch_files(tmp_path, 1)
    monkeypatch.setattr(files, "LOCK_WAIT_SECONDS", 0.3)
    with open(path, "rb") as held:
        fcntl.flock(held.fileno(), fcntl.LOCK_EX)
        started = time.monotonic()
        with pytest.raises(WriteError, match="another run is writing it; nothing was changed"):
            replace_all(_changes(tmp_path, [path]), cwd=tmp_path, roots=[tmp_path])
        assert time.monotonic() - started < 5
    assert path.read_text(encoding="utf-8") == EKF_LAUNCH


def test_a_link_to_a_file_outside_the_linted_paths_is_never_written(tmp_path: Path) -> None:
    outside = write(tmp_path / "elsewhere", "ekf.launch.xml", EKF_LAUNCH)
    root = tmp_path / "ws"
    write_package(root / "src/robot_bringup", 2)
    link = root / "src/robot_bringup/launch/ekf.launch.xml"
    link.parent.mkdir(parents=True)
    link.symlink_to(outside)
    snapshot, (display,) = _snapshot_of(root, link)
    data, why = snapshot.for_edit(display)
    assert data is None and why == f"it is a link to {outside}, outside the linted paths"
    with pytest.raises(WriteError, match="outside the linted paths; nothing was changed"):
        replace_all([Change(display, EKF_LAUNCH.encode(), b"")], cwd=root, roots=[root])
    assert outside.read_text(encoding="utf-8") == EKF_LAUNCH


def test_a_link_inside_the_linted_paths_is_written_through_and_stays_a_link(
    tmp_path: Path,
) -> None:
    (target,) = _launch_files(tmp_path, 1)
    link = tmp_path / "src/robot_bringup/launch/default.launch.xml"
    link.symlink_to(target.name)
    snapshot, (display,) = _snapshot_of(tmp_path, link)
    snapshot.replace_all([Change(display, EKF_LAUNCH.encode(), EKF_FIXED.encode())])
    assert link.is_symlink()
    assert target.read_text(encoding="utf-8") == EKF_FIXED


def test_a_report_is_written_whole_and_through_a_link(tmp_path: Path) -> None:
    report = tmp_path / "results/roslint.sarif"
    files.write_new(report, b"{}\n", "the report")
    assert report.read_bytes() == b"{}\n"
    link = tmp_path / "latest.sarif"
    link.symlink_to(report)
    files.write_new(link, b'{"runs": []}\n', "the report")
    assert link.is_symlink() and report.read_bytes() == b'{"runs": []}\n'
    with pytest.raises(WriteError, match=r"cannot write the report .*: it is a directory"):
        files.write_new(tmp_path / "results", b"{}", "the report")


# ---------------------------------------------------------------------------------------
# Through the command line


def test_a_rename_with_one_read_only_file_changes_nothing(run_cli: Any, tmp_path: Path) -> None:
    talker, listener = _talker_and_listener(tmp_path)
    listener.chmod(0o444)
    result = run_cli(["check", "--no-cache", "--fix", "--unsafe-fixes", "."], tmp_path)
    assert (
        "roslint-names: src/chatter/src/listener.cpp: renames not applied: "
        "permission denied (the file is read-only)"
    ) in result.stderr
    assert "fixed 0 findings in 0 files" in result.stderr
    assert talker.read_text(encoding="utf-8") == TALKER
    assert listener.read_text(encoding="utf-8") == LISTENER
    assert result.exit_code == 1  # the finding is still there


def test_a_rename_writes_both_ends_and_names_the_files(run_cli: Any, tmp_path: Path) -> None:
    talker, listener = _talker_and_listener(tmp_path)
    result = run_cli(["check", "--no-cache", "--fix", "--unsafe-fixes", "."], tmp_path)
    assert "roslint-names: wrote src/chatter/src/listener.cpp" in result.stderr
    assert "roslint-names: wrote src/chatter/src/talker.cpp" in result.stderr
    assert talker.read_text(encoding="utf-8") == TALKER.replace("robotStatus", "robot_status")
    assert listener.read_text(encoding="utf-8") == LISTENER.replace("robotStatus", "robot_status")
    assert result.exit_code == 0


def test_a_file_saved_by_the_editor_during_the_run_is_not_spliced(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The run reads the file, the editor saves it with a line added above the finding,
    then the fix would be made: the old spans are never spliced into the new bytes."""
    from roslint_names import cli

    (path,) = _launch_files(tmp_path, 1)
    saved = "<!-- the robot's localization -->\n" + EKF_LAUNCH
    real_lint = cli.lint

    def lint_then_editor_saves(*arguments: Any, **keywords: Any) -> Any:
        result = real_lint(*arguments, **keywords)
        path.write_text(saved, encoding="utf-8")
        return result

    monkeypatch.setattr(cli, "lint", lint_then_editor_saves)
    result = run_cli(["check", "--no-cache", "--fix", "."], tmp_path)
    assert (
        "roslint-names: src/robot_bringup/launch/ekf_000.launch.xml: fixes not applied: "
        "changed since it was read; run again"
    ) in result.stderr
    assert "fixed 0 findings in 0 files" in result.stderr
    assert path.read_text(encoding="utf-8") == saved


def test_a_fix_through_a_link_out_of_the_tree_says_so(run_cli: Any, tmp_path: Path) -> None:
    outside = write(tmp_path / "vendor", "ekf.launch.xml", EKF_LAUNCH)
    root = tmp_path / "ws"
    write_package(root / "src/robot_bringup", 2)
    (root / "src/robot_bringup/launch").mkdir(parents=True)
    (root / "src/robot_bringup/launch/ekf.launch.xml").symlink_to(outside)
    result = run_cli(["check", "--no-cache", "--fix", "."], root)
    assert (
        f"src/robot_bringup/launch/ekf.launch.xml: fixes not applied: it is a link to {outside}, "
        "outside the linted paths"
    ) in result.stderr
    assert outside.read_text(encoding="utf-8") == EKF_LAUNCH


def test_a_baseline_that_is_a_fifo_is_refused_at_once(tmp_path: Path) -> None:
    _launch_files(tmp_path, 1)
    os.mkfifo(tmp_path / "baseline.json")
    result = _cli_subprocess(["check", "--no-cache", "--baseline", "baseline.json", "."], tmp_path)
    assert result.returncode == 2
    assert "baseline.json: cannot read baseline: not a regular file (a FIFO)" in result.stderr


def test_a_report_that_cannot_be_written_names_it_without_internal_error(
    run_cli: Any, tmp_path: Path
) -> None:
    _launch_files(tmp_path, 1)
    (tmp_path / "report.json").mkdir()
    result = run_cli(
        ["check", "--no-cache", "--format", "json", "-o", "report.json", "."], tmp_path
    )
    assert result.exit_code == 2
    assert "cannot write the report report.json: it is a directory" in result.stderr
    assert "internal error" not in result.stderr


def _cli_subprocess(
    arguments: list[str], cwd: Path, timeout: float = 60
) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "roslint_names.cli", *arguments],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=timeout,
        env=_environment(),
        check=False,
    )


def _environment() -> dict[str, str]:
    source = str(Path(__file__).resolve().parents[1])
    path = os.environ.get("PYTHONPATH")
    return {**os.environ, "PYTHONPATH": source + (os.pathsep + path if path else "")}


def test_two_fix_runs_at_once_leave_every_file_whole_and_consistent(tmp_path: Path) -> None:
    """Both runs rename the talker's and the listener's topic: whichever writes second
    finds the files changed and writes nothing; never a torn literal or half a rename."""
    talker, listener = _talker_and_listener(tmp_path)
    _launch_files(tmp_path, 30)
    command = [sys.executable, "-m", "roslint_names.cli", "check", "--no-cache", "--fix"]
    runs = [
        subprocess.Popen(
            [*command, "--unsafe-fixes", "."],
            cwd=tmp_path,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env=_environment(),
        )
        for _ in range(2)
    ]
    outputs = [run.communicate(timeout=120) for run in runs]
    for run, (_, errors) in zip(runs, outputs, strict=True):
        assert run.returncode in (0, 1, 2), errors
        assert "internal error" not in errors
    renamed = TALKER.replace("robotStatus", "robot_status")
    assert talker.read_text(encoding="utf-8") == renamed
    assert listener.read_text(encoding="utf-8") == LISTENER.replace("robotStatus", "robot_status")
    for path in (tmp_path / "src/robot_bringup/launch").iterdir():
        assert path.read_text(encoding="utf-8") == EKF_FIXED


@pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="kill -9 is POSIX")
def test_kill_9_during_fix_never_leaves_a_torn_file(tmp_path: Path) -> None:
    """Hundreds of 32 KB launch files fixed by a run killed with SIGKILL at random
    moments: every file is always the old text or the fixed one, never short."""
    paths = _launch_files(tmp_path, 300, padding=32 * 1024)
    old = paths[0].read_bytes()
    new = old.replace(b'namespace="localization/"', b'namespace="localization"')
    command = [sys.executable, "-m", "roslint_names.cli", "check", "--no-cache", "--fix", "-j1"]
    started = time.monotonic()
    subprocess.run(
        [*command, "--diff", "."],
        cwd=tmp_path,
        env=_environment(),
        timeout=120,
        capture_output=True,
        check=False,
    )
    duration = time.monotonic() - started  # a run's length, to kill within it
    chooser = random.Random(26)
    for _ in range(6):
        run = subprocess.Popen(
            [*command, "."],
            cwd=tmp_path,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            env=_environment(),
        )
        time.sleep(chooser.uniform(0.3, 1.2) * duration)
        run.kill()
        run.wait(timeout=30)
        contents = {path.read_bytes() for path in paths}
        assert contents <= {old, new}, "a file is neither the old text nor the fixed one"
        for leftover in _temporaries(tmp_path):
            leftover.unlink()  # a kill may leave the next file's temporary: never a source
        for path in paths:
            path.write_bytes(old)  # the next kill finds every file to fix again

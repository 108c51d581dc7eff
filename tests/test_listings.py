"""The walk's kept listings (``listings``): a re-run lists again only the directories that
changed, and finds what a walk without them finds after every kind of change, including
those that leave a directory's status alone (a ``.gitignore`` or a sniffed file edited in
place, a link's target removed)."""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from pathlib import Path

import pytest
from conftest import CATKIN_PACKAGE, write

from roslint_names import discover as discover_module
from roslint_names import listings as listings_module
from roslint_names import walks
from roslint_names.cache import FactsCache
from roslint_names.discover import discover
from roslint_names.listings import LISTINGS
from roslint_names.model import Language

TALKER = """#include <ros/ros.h>
#include <std_msgs/String.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "talker");
  ros::NodeHandle nh;
  ros::Publisher chatter = nh.advertise<std_msgs::String>("chatter", 10);
  ros::spin();
}
"""
BRINGUP = """<launch>
  <arg name="robot" default="robot1"/>
  <group ns="$(arg robot)">
    <node pkg="chatter" type="talker" name="talker">
      <remap from="chatter" to="speech"/>
    </node>
  </group>
</launch>
"""
RELAY = "#!/usr/bin/env python3\nimport rospy\nrospy.init_node('relay')\n"


@pytest.fixture(autouse=True)
def walked_each_time(monkeypatch: pytest.MonkeyPatch) -> None:
    """No walk taken whole (``walks``, its own tests): these test what a walk lists."""
    monkeypatch.setattr(walks, "taken", lambda *_: None)


@pytest.fixture
def workspace(tmp_path: Path, old_tree: None) -> Path:
    """A catkin workspace as ``catkin_init_workspace`` leaves it (``src/CMakeLists.txt`` a
    link to catkin's top-level file), one repository with its ``.gitignore``, two
    packages, a script without a suffix and an XML file whose root decides."""
    return chatter_workspace(tmp_path / "ws", linked_toplevel=True)


def chatter_workspace(root: Path, *, linked_toplevel: bool) -> Path:
    """The ``workspace`` at ``root``; its ``src/CMakeLists.txt`` a file of its own
    unless ``linked_toplevel``."""
    toplevel = "cmake_minimum_required(VERSION 3.0.2)\n"
    if linked_toplevel:
        write(root, "catkin/toplevel.cmake", toplevel)
        (root / "src").mkdir(parents=True)
        os.symlink(root / "catkin/toplevel.cmake", root / "src/CMakeLists.txt")
    else:
        write(root, "src/CMakeLists.txt", toplevel)
    repository = root / "src/chatter_ros"
    (repository / ".git").mkdir(parents=True)
    write(repository, ".gitignore", "*.orig\n")
    write(repository, "chatter/package.xml", CATKIN_PACKAGE.format(name="chatter"))
    write(repository, "chatter/CMakeLists.txt", "add_executable(talker src/talker.cpp)\n")
    write(repository, "chatter/src/talker.cpp", TALKER)
    write(repository, "chatter/scripts/relay", RELAY)
    write(repository, "chatter/launch/nodes.xml", BRINGUP)
    write(repository, "bringup/package.xml", CATKIN_PACKAGE.format(name="bringup"))
    write(repository, "bringup/launch/robot.launch", BRINGUP)
    _age(root)
    return root


def _age(root: Path) -> None:
    """Every file and directory under ``root`` last modified a minute ago: past the racy
    window, as a tree is between two commits."""
    past = time.time() - 60
    for directory, _, files in os.walk(root):
        for name in files:
            path = os.path.join(directory, name)
            if not os.path.islink(path):
                os.utime(path, (past, past))
        os.utime(directory, (past, past))


def _aged(path: Path) -> None:
    """``path`` edited in place, its time set back (its change time is still new)."""
    past = time.time() - 30
    os.utime(path, (past, past))


def _found(root: Path, cache: FactsCache | None) -> list[tuple[str, Language]]:
    warnings: list[str] = []
    sources = discover([root], [], root, root, warnings, cache=cache)
    return [(source.display, source.language) for source in sources]


@pytest.fixture
def listed(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The directories the walk lists (``os.scandir``), in order."""
    calls: list[str] = []
    real = discover_module._listing

    def counted(directory: str) -> list[os.DirEntry[str]]:
        calls.append(directory)
        return real(directory)

    monkeypatch.setattr(discover_module, "_listing", counted)
    return calls


def test_an_unchanged_tree_is_not_listed_again(
    workspace: Path, tmp_path: Path, listed: list[str]
) -> None:
    cache = FactsCache(tmp_path / "cache")
    first = _found(workspace, cache)
    assert len(listed) == 10
    assert ("src/CMakeLists.txt", Language.CMAKE) in first
    assert ("src/chatter_ros/chatter/scripts/relay", Language.PYTHON) in first
    assert ("src/chatter_ros/chatter/launch/nodes.xml", Language.LAUNCH_XML) in first
    listed.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first
    assert listed == []
    assert len(list((cache.directory / LISTINGS).iterdir())) == 1


def test_a_tree_changed_just_now_is_listed_again(tmp_path: Path, listed: list[str]) -> None:
    """Within the racy window a status may hide a change made in the same clock tick."""
    root = tmp_path / "ws"
    write(root, "src/chatter/package.xml", CATKIN_PACKAGE.format(name="chatter"))
    write(root, "src/chatter/src/talker.cpp", TALKER)
    cache = FactsCache(tmp_path / "cache")
    first = _found(root, cache)
    count = len(listed)
    assert _found(root, FactsCache(tmp_path / "cache")) == first
    assert len(listed) == 2 * count


def _remove_link_target(root: Path) -> None:
    (root / "catkin/toplevel.cmake").unlink()


def _rewritten(path: Path, text: str) -> None:
    """``path`` edited in place to ``text``, its time set back: its directory's stays."""
    path.write_text(text, encoding="utf-8")
    _aged(path)


def _ignore_by_gitignore(root: Path) -> None:
    _rewritten(root / "src/chatter_ros/.gitignore", "*.orig\nbringup/\n")


def _ignore_above(root: Path) -> None:
    _rewritten(root / "src/chatter_ros/.gitignore", "*.orig\nlaunch/\n")


def _script_no_longer_python(root: Path) -> None:
    _rewritten(
        root / "src/chatter_ros/chatter/scripts/relay", "#!/bin/bash\nrosrun chatter talker\n"
    )


def _xml_no_longer_launch(root: Path) -> None:
    _rewritten(
        root / "src/chatter_ros/chatter/launch/nodes.xml", BRINGUP.replace("launch>", "robot>")
    )


def _marker(root: Path) -> None:
    write(root, "src/chatter_ros/bringup/CATKIN_IGNORE", "")


def _added(root: Path) -> None:
    write(root, "src/chatter_ros/bringup/launch/sim.launch", BRINGUP)


def _removed(root: Path) -> None:
    (root / "src/chatter_ros/chatter/src/talker.cpp").unlink()


def _renamed(root: Path) -> None:
    os.rename(root / "src/chatter_ros/bringup", root / "src/chatter_ros/robot_bringup")


def _replaced_by_directory(root: Path) -> None:
    relay = root / "src/chatter_ros/chatter/scripts/relay"
    relay.unlink()
    write(relay.parent, "relay/talker.py", RELAY)


# Every kind of change but a link's (``_remove_link_target``).
CHANGES = (
    _ignore_by_gitignore,
    _ignore_above,
    _script_no_longer_python,
    _xml_no_longer_launch,
    _marker,
    _added,
    _removed,
    _renamed,
    _replaced_by_directory,
)


@pytest.mark.parametrize("change", [_remove_link_target, *CHANGES])
def test_a_re_run_finds_what_a_fresh_walk_finds(
    workspace: Path, tmp_path: Path, change: Callable[[Path], None]
) -> None:
    before = _found(workspace, FactsCache(tmp_path / "cache"))
    change(workspace)
    # Twice: right after the change (within the racy window of what it touched) and once
    # all of it is old, as the listings kept the first time say it.
    for _ in range(2):
        after = _found(workspace, FactsCache(tmp_path / "cache"))
        assert after == _found(workspace, None)
        assert after != before
        _age(workspace)


def test_a_gitignore_above_the_named_directory_is_checked(workspace: Path, tmp_path: Path) -> None:
    gitignore_above_is_checked(workspace, tmp_path / "cache", runs_before=1)


def gitignore_above_is_checked(workspace: Path, cache: Path, runs_before: int) -> None:
    """A package of ``workspace`` named, run ``runs_before`` times with the cache at
    ``cache``, then the repository's ``.gitignore`` above it edited in place."""
    package = workspace / "src/chatter_ros/chatter"
    for _ in range(runs_before):
        first = _found(package, FactsCache(cache))
        assert ("launch/nodes.xml", Language.LAUNCH_XML) in first
    _ignore_above(workspace)
    after = _found(package, FactsCache(cache))
    assert after == _found(package, None)
    assert ("launch/nodes.xml", Language.LAUNCH_XML) not in after


def test_a_damaged_listings_file_is_listed_again(workspace: Path, tmp_path: Path) -> None:
    cache = FactsCache(tmp_path / "cache")
    first = _found(workspace, cache)
    (kept,) = (cache.directory / LISTINGS).iterdir()
    kept.write_bytes(b"\x80\x05not a pickle")
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first
    kept.write_bytes(b"\x80\x05cos\nsystem\n.")  # a global no listing holds
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first


def test_another_walk_code_lists_again(
    workspace: Path, tmp_path: Path, listed: list[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """The facts cache's directory is named by the extractors' code only: a checkout whose
    walk selects other files must not replay what an older walk kept."""
    _found(workspace, FactsCache(tmp_path / "cache"))
    listed.clear()
    monkeypatch.setattr(listings_module, "code_fingerprint", lambda: "another checkout")
    _found(workspace, FactsCache(tmp_path / "cache"))
    assert len(listed) == 10


def test_files_shown_alike_come_out_in_one_order(tmp_path: Path, old_tree: None) -> None:
    """A Latin-1 file name (shown with its byte escaped) beside a link whose name spells
    that escape: the same display path, whose order the walk must not decide (a replayed
    directory yields its files before its links)."""
    root = tmp_path / "ws"
    launch = root / "bringup" / "launch"
    write(root, "robots/real.launch", BRINGUP)
    write(launch, os.fsdecode(b"caf\xe9.launch"), BRINGUP)
    os.symlink("../../robots/real.launch", launch / "caf\\xe9.launch")
    _age(root)

    def locations(cache: FactsCache | None) -> list[str]:
        sources = discover([root / "bringup"], [], root, root, [], cache=cache)
        return [source.location for source in sources]

    fresh = locations(None)
    assert len(fresh) == 2 and len({os.path.basename(path) for path in fresh}) == 2
    assert locations(FactsCache(tmp_path / "cache")) == fresh
    assert locations(FactsCache(tmp_path / "cache")) == fresh  # replayed


def test_times_set_back_just_now_are_not_trusted(tmp_path: Path, listed: list[str]) -> None:
    """``cp -p``, ``rsync -t`` and ``tar`` set modification times back; the change time
    still says the directory was written just now, and a file system that keeps whole
    seconds would hide a second change within the same one."""
    root = tmp_path / "ws"
    write(root, "src/chatter/package.xml", CATKIN_PACKAGE.format(name="chatter"))
    write(root, "src/chatter/src/talker.cpp", TALKER)
    _age(root)
    first = _found(root, FactsCache(tmp_path / "cache"))
    count = len(listed)
    assert _found(root, FactsCache(tmp_path / "cache")) == first
    assert len(listed) == 2 * count


@pytest.fixture
def compiled(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """How many ``.gitignore`` pattern sets the walk compiles (pathspec's ``from_lines``)."""
    import pathspec

    calls: list[int] = []
    real = pathspec.GitIgnoreSpec.from_lines

    def counted(lines: list[str]) -> pathspec.GitIgnoreSpec:
        calls.append(len(lines))
        return real(lines)

    monkeypatch.setattr(pathspec.GitIgnoreSpec, "from_lines", counted)
    return calls


def test_a_replayed_walk_compiles_a_gitignore_only_to_list_below_it(
    workspace: Path, tmp_path: Path, compiled: list[int]
) -> None:
    """300 ``.gitignore`` files cost 0.1 s to compile at 8 copies of the benchmark's
    workspace, for a re-run that matches nothing against them; a directory added below
    one is matched against its patterns all the same."""
    gitignore = workspace / "src/chatter_ros/.gitignore"
    gitignore.write_text("*.orig\n*.bak.launch\n", encoding="utf-8")
    _age(workspace)
    first = _found(workspace, FactsCache(tmp_path / "cache"))
    assert compiled == [2]
    compiled.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first
    assert compiled == []
    write(workspace, "src/chatter_ros/bringup/config/sim.launch", BRINGUP)
    write(workspace, "src/chatter_ros/bringup/config/sim.bak.launch", BRINGUP)
    _age(workspace)
    after = _found(workspace, FactsCache(tmp_path / "cache"))
    assert compiled == [2]
    assert after == _found(workspace, None)
    assert ("src/chatter_ros/bringup/config/sim.launch", Language.LAUNCH_XML) in after
    assert ("src/chatter_ros/bringup/config/sim.bak.launch", Language.LAUNCH_XML) not in after


def test_a_replayed_walk_says_what_an_invalid_gitignore_pattern_is(
    workspace: Path, tmp_path: Path
) -> None:
    gitignore = workspace / "src/chatter_ros/.gitignore"
    gitignore.write_text("*.orig\n!\n", encoding="utf-8")
    _age(workspace)
    said = ["src/chatter_ros/.gitignore:2: invalid pattern '!' not applied: git does not accept it"]
    for _ in range(2):  # listed, then replayed
        warnings: list[str] = []
        discover([workspace], [], workspace, workspace, warnings, cache=FactsCache(tmp_path / "c"))
        assert warnings == said


def test_patterns_compiled_late_leave_an_invalid_one_out() -> None:
    """A ``.gitignore`` edited between its status and its read: what git applies, no error
    (the next walk sees the new status and says what is invalid)."""
    spec = discover_module._Spec(["!", "*.bak.launch"], compiled=False)
    assert spec.match_file("launch/sim.bak.launch")
    assert not spec.match_file("launch/sim.launch")
    with pytest.raises(ValueError):
        discover_module._Spec(["!", "*.bak.launch"])


def test_the_directories_without_a_manifest_are_those_the_walk_saw_none_in(
    workspace: Path, tmp_path: Path
) -> None:
    """Listed or replayed alike; a package.xml counts ignored, as a link to nothing, and
    in another case (which a file system ignoring case opens as one)."""
    repository = workspace / "src/chatter_ros"
    write(repository, ".gitignore", "*.orig\nhidden/package.xml\n")
    write(repository, "hidden/package.xml", CATKIN_PACKAGE.format(name="hidden"))
    write(repository, "hidden/launch/robot.launch", BRINGUP)
    (repository / "linked").mkdir()
    os.symlink("nowhere.xml", repository / "linked/package.xml")
    write(repository, "shouting/PACKAGE.XML", CATKIN_PACKAGE.format(name="shouting"))
    write(repository, "shouting/src/node.cpp", TALKER)
    _age(workspace)
    cache = FactsCache(tmp_path / "cache")
    walks = []
    for kept in (None, cache, cache):  # no listings, then listed, then replayed
        without: set[str] = set()
        discover([workspace], [], workspace, workspace, [], cache=kept, without_manifest=without)
        walks.append(without)
    assert walks[0] == walks[1] == walks[2]
    manifests = {
        os.fspath(repository / name) for name in ("chatter", "bringup", "linked", "hidden")
    }
    assert manifests.isdisjoint(walks[0])
    assert os.fspath(repository / "shouting") not in walks[0]
    assert os.fspath(repository / "chatter/src") in walks[0]
    assert os.fspath(repository / "shouting/src") in walks[0]
    assert os.fspath(repository / "hidden/launch") in walks[0]

"""A named directory's last walk kept whole (``walks``): a re-run that finds every status
it stood on as it was takes its files without walking, and any change that could change
what a walk finds makes it walk: the tree of ``test_listings`` without its link."""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

import pytest
from conftest import CATKIN_PACKAGE, write

from roslint_names import discover as discover_module
from roslint_names import reading, walks
from roslint_names.cache import FactsCache
from roslint_names.discover import discover
from roslint_names.listings import LISTINGS, FileStatus, Listings
from roslint_names.model import Language
from tests.test_listings import (
    BRINGUP,
    CHANGES,
    RELAY,
    TALKER,
    _age,
    chatter_workspace,
    gitignore_above_is_checked,
)

Found = list[tuple[str, Language]]


@pytest.fixture
def workspace(tmp_path: Path, old_tree: None) -> Path:
    """``test_listings``' workspace without its link (a walk that follows one is walked
    again each time)."""
    return chatter_workspace(tmp_path / "ws", linked_toplevel=False)


@pytest.fixture
def walked(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The directories the walk enters, listed or replayed, in order."""
    calls: list[str] = []
    real = discover_module._Walker.walk

    def counted(self: discover_module._Walker[object], top: str, **options: bool) -> None:
        calls.append(top)
        real(self, top, **options)

    monkeypatch.setattr(discover_module._Walker, "walk", counted)
    return calls


def _found(
    root: Path, cache: FactsCache | None, cwd: Path | None = None, warnings: list[str] | None = None
) -> Found:
    sources = discover([root], [], root, cwd or root, warnings, cache=cache)
    return [(source.display, source.language) for source in sources]


def _kept_walks(cache: FactsCache) -> list[Path]:
    return sorted((cache.directory / LISTINGS).glob("*.walked"))


def test_an_unchanged_tree_is_taken_whole(
    workspace: Path, tmp_path: Path, walked: list[str]
) -> None:
    cache = FactsCache(tmp_path / "cache")
    without: set[str] = set()
    first = discover([workspace], [], workspace, workspace, cache=cache, without_manifest=without)
    assert len(walked) == 9 and len(_kept_walks(cache)) == 1
    walked.clear()
    again: set[str] = set()
    taken = discover(
        [workspace],
        [],
        workspace,
        workspace,
        cache=FactsCache(tmp_path / "cache"),
        without_manifest=again,
    )
    assert walked == []  # not a directory entered
    assert taken == first and again == without
    assert os.path.join(workspace, "src") in again
    assert [(source.display, source.language) for source in taken] == _found(workspace, None)


@pytest.mark.parametrize("change", CHANGES)
def test_a_change_is_walked(
    workspace: Path, tmp_path: Path, walked: list[str], change: Callable[[Path], None]
) -> None:
    before = _found(workspace, FactsCache(tmp_path / "cache"))
    _found(workspace, FactsCache(tmp_path / "cache"))  # taken whole
    change(workspace)
    # Twice: right after the change and once all of it is old, as the kept walk says it.
    for aged in (False, True):
        if aged:
            _age(workspace)
        fresh = _found(workspace, None)
        walked.clear()
        after = _found(workspace, FactsCache(tmp_path / "cache"))
        assert after == fresh != before
        assert walked  # the change is walked (listed or replayed), not taken whole
    walked.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == after
    assert walked == []  # and kept what it found: taken whole again


def test_a_gitignore_above_the_named_directory_is_checked(workspace: Path, tmp_path: Path) -> None:
    gitignore_above_is_checked(workspace, tmp_path / "cache", runs_before=2)  # then whole


def test_another_current_directory_shows_the_files_anew(workspace: Path, tmp_path: Path) -> None:
    inside = workspace / "src"
    for cwd in (workspace, inside, workspace, inside):
        shown = _found(workspace, FactsCache(tmp_path / "cache"), cwd)
        assert shown == _found(workspace, None, cwd)


def test_a_walk_that_warned_or_followed_a_link_is_not_kept(workspace: Path, tmp_path: Path) -> None:
    """A warning is said by every run; a link's target may change without its
    directory."""
    os.mkfifo(workspace / "src/chatter_ros/bringup/launch/pipe.launch")
    _age(workspace)
    cache = FactsCache(tmp_path / "cache")
    warned: list[str] = []
    first = _found(workspace, cache, warnings=warned)
    assert any("pipe.launch" in line for line in warned)
    assert _kept_walks(cache) == []
    again: list[str] = []
    assert _found(workspace, FactsCache(tmp_path / "cache"), warnings=again) == first
    assert again == warned
    (workspace / "src/chatter_ros/bringup/launch/pipe.launch").unlink()
    target = workspace / "tools/talker.launch"
    write(target.parent, target.name, BRINGUP)
    os.symlink(target, workspace / "src/chatter_ros/bringup/launch/talker.launch")
    _age(workspace)
    linked = _found(workspace, FactsCache(tmp_path / "cache"))
    assert ("src/chatter_ros/bringup/launch/talker.launch", Language.LAUNCH_XML) in linked
    assert _kept_walks(cache) == []
    target.unlink()  # its directory's status is as it was
    assert _found(workspace, FactsCache(tmp_path / "cache")) == _found(workspace, None)


def test_a_tree_changed_just_now_is_looked_at_again(tmp_path: Path, walked: list[str]) -> None:
    """Within the racy window a status may hide a change made in the same clock tick: the
    walk is kept without it, and each such directory's entries are looked at again."""
    root = tmp_path / "ws"
    write(root, "src/chatter/package.xml", CATKIN_PACKAGE.format(name="chatter"))
    write(root, "src/chatter/src/talker.cpp", TALKER)
    cache = FactsCache(tmp_path / "cache")
    first = _found(root, cache)
    assert len(_kept_walks(cache)) == 1
    walked.clear()
    assert _found(root, FactsCache(tmp_path / "cache")) == first
    assert walked == []
    write(root, "src/chatter/src/listener.cpp", TALKER)  # within the same tick, maybe
    fresh = _found(root, None)
    assert _found(root, FactsCache(tmp_path / "cache")) == fresh != first


@pytest.mark.parametrize(
    "damage", [b"\x80\x05not a pickle", b"\x80\x05cos\nsystem\n.", b"\x80\x05K\x01."]
)
def test_a_damaged_kept_walk_is_walked(
    workspace: Path, tmp_path: Path, walked: list[str], damage: bytes
) -> None:
    cache = FactsCache(tmp_path / "cache")
    first = _found(workspace, cache)
    (kept,) = _kept_walks(cache)
    kept.write_bytes(damage)
    walked.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first
    assert walked


def test_a_walk_that_warned_of_a_gitignore_warns_again(workspace: Path, tmp_path: Path) -> None:
    gitignore = workspace / "src/chatter_ros/.gitignore"
    gitignore.write_text("*.orig\n!\n", encoding="utf-8")
    _age(workspace)
    said = ["src/chatter_ros/.gitignore:2: invalid pattern '!' not applied: git does not accept it"]
    for _ in range(3):  # listed, then replayed, not taken whole
        warnings: list[str] = []
        _found(workspace, FactsCache(tmp_path / "cache"), warnings=warnings)
        assert warnings == said


def test_a_walk_that_could_not_trust_a_gitignore_s_status_is_not_kept(
    workspace: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A ``.gitignore`` whose status is too recent to vouch for it leaves its directory's
    listing unkept: the walk is not whole."""
    real = Listings.file_status

    def file_status(self: Listings, path: str) -> FileStatus | None:
        return None if os.path.basename(path) == ".gitignore" else real(self, path)

    monkeypatch.setattr(Listings, "file_status", file_status)
    cache = FactsCache(tmp_path / "cache")
    assert _found(workspace, cache) == _found(workspace, None)
    assert _kept_walks(cache) == []


def test_a_sniffed_file_whose_status_changed_is_asked_again(
    workspace: Path, tmp_path: Path, walked: list[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Its status too recent to vouch for what it said, or another now: what its content
    says is asked again, and the walk taken whole where it says the same."""
    real = Listings.file_status

    def file_status(self: Listings, path: str) -> FileStatus | None:
        return None if os.path.basename(path) == "relay" else real(self, path)

    with monkeypatch.context() as patched:
        patched.setattr(Listings, "file_status", file_status)
        first = _found(workspace, FactsCache(tmp_path / "cache"))
    relay = workspace / "src/chatter_ros/chatter/scripts/relay"
    relay.write_text(RELAY + "rospy.spin()\n", encoding="utf-8")  # still Python
    asked: list[str] = []
    said = discover_module._WALK.said

    def counted(path: str) -> str:
        asked.append(path)
        return said(path)

    monkeypatch.setattr(discover_module, "_WALK", discover_module._WALK._replace(said=counted))
    walked.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first
    assert walked == [] and asked == [os.fspath(relay)]
    # What it says now kept with its status: not asked again.
    asked.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first
    assert walked == [] and asked == []
    relay.write_text("#!/bin/bash\nrosrun chatter talker\n", encoding="utf-8")
    fresh = _found(workspace, None)
    assert _found(workspace, FactsCache(tmp_path / "cache")) == fresh != first


def _replaced(path: Path) -> None:
    """``path`` written anew (an editor saving by a rename, git checking it out): its
    directory's status changes, not what a walk finds there."""
    text = path.read_bytes()
    path.unlink()
    path.write_bytes(text + b"\n")


@pytest.fixture
def looked(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The directories of a kept walk looked at again (``walks._same_entries``)."""
    calls: list[str] = []
    real = walks._same_entries

    def counted(directory: str, entered: set[str], files: set[str], walk: walks.Walk) -> bool:
        calls.append(directory)
        return real(directory, entered, files, walk)

    monkeypatch.setattr(walks, "_same_entries", counted)
    return calls


def test_a_file_replaced_is_taken_whole_with_its_directory_looked_at_once(
    workspace: Path,
    tmp_path: Path,
    walked: list[str],
    looked: list[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    first = _found(workspace, FactsCache(tmp_path / "cache"))
    source = workspace / "src/chatter_ros/chatter/src"
    _replaced(source / "talker.cpp")
    write(source, "NOTES.md", "Not a file the walk chooses.\n")
    (source / "__pycache__").mkdir()  # a directory no walk enters
    assert _found(workspace, None) == first
    walked.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first
    assert walked == [] and looked == [os.fspath(source)]
    # What it found there vouched for by the directory's status now, kept: the next run
    # finds the walk as it stood, looking at nothing again.
    looked.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first
    assert walked == [] and looked == []
    monkeypatch.setattr(walks, "MOST_CHANGED", 0)  # past the directories looked at again
    _replaced(source / "talker.cpp")
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first
    assert walked


def test_a_directory_changed_just_now_is_looked_at_until_its_status_vouches(
    workspace: Path, tmp_path: Path, looked: list[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A status taken within the racy window is not kept for the walk: what the directory
    holds may change again in the same clock tick."""
    first = _found(workspace, FactsCache(tmp_path / "cache"))
    source = workspace / "src/chatter_ros/chatter/src"
    _replaced(source / "talker.cpp")
    monkeypatch.setattr(reading, "RACY_NANOSECONDS", 3600 * 10**9)
    for _ in range(2):
        looked.clear()
        assert _found(workspace, FactsCache(tmp_path / "cache")) == first
        assert looked == [os.fspath(source)]
    monkeypatch.setattr(reading, "RACY_NANOSECONDS", 0)  # past it
    for directories in ([os.fspath(source)], []):
        looked.clear()
        assert _found(workspace, FactsCache(tmp_path / "cache")) == first
        assert looked == directories


@pytest.mark.parametrize(
    "damage", [None, b"\x80\x05not a pickle", b"\x80\x05cos\nsystem\n.", b"\x80\x05K\x01."]
)
def test_statuses_kept_for_another_walk_or_damaged_are_none(
    workspace: Path, tmp_path: Path, looked: list[str], damage: bytes | None
) -> None:
    """None (``damage``): those kept for the walk before, which a walk of the whole tree
    replaced (a ``.gitignore`` edited). Taken for the new walk, the status they kept of a
    directory changed since would have it looked at again in every run."""
    cache = FactsCache(tmp_path / "cache")
    first = _found(workspace, cache)
    source = workspace / "src/chatter_ros/chatter/src"
    _replaced(source / "talker.cpp")
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first  # and kept its status
    (amended,) = (cache.directory / LISTINGS).glob("*.walked-statuses")
    _replaced(source / "talker.cpp")
    gitignore = workspace / "src/chatter_ros/.gitignore"
    gitignore.write_text(gitignore.read_text(encoding="utf-8") + "*.rej\n", encoding="utf-8")
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first  # walked, kept anew
    if damage is not None:
        amended.write_bytes(damage)
    looked.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == first
    assert looked == []


@pytest.mark.parametrize(
    "entry",
    [
        "helper.cpp",  # a file the walk chooses
        "relay",  # no suffix: its content decides
        ".gitignore",  # ignores what it names
        "COLCON_IGNORE",  # ignores everything below
        "nested/",  # a directory it enters, or an ignore rule passes over
        "talker.cpp",  # a chosen file gone
        "link.launch@",  # a link: followed each time
    ],
)
def test_a_directory_that_holds_other_entries_is_walked(
    workspace: Path, tmp_path: Path, walked: list[str], entry: str
) -> None:
    _found(workspace, FactsCache(tmp_path / "cache"))
    source = workspace / "src/chatter_ros/chatter/src"
    if entry == "talker.cpp":
        (source / entry).unlink()
    elif entry.endswith("/"):
        write(source / entry, "a.cpp", TALKER)
    elif entry.endswith("@"):
        os.symlink(workspace / "src/chatter_ros/bringup/launch/robot.launch", source / entry[:-1])
    else:
        write(source, entry, "#!/usr/bin/env python3\n" if entry == "relay" else "*.cpp\n")
    fresh = _found(workspace, None)
    walked.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == fresh
    assert walked


def test_only_the_directories_that_hold_other_entries_are_walked_again(
    workspace: Path, tmp_path: Path, walked: list[str]
) -> None:
    """Under the ignore rules the kept walk read above them: the repository's
    ``.gitignore`` ignores ``skip_*.cpp`` in a directory walked again."""
    gitignore = workspace / "src/chatter_ros/.gitignore"
    gitignore.write_text("*.orig\nskip_*.cpp\n", encoding="utf-8")
    _age(workspace)
    first = _found(workspace, FactsCache(tmp_path / "cache"))
    source = workspace / "src/chatter_ros/chatter/src"
    write(source, "listener.cpp", TALKER)
    write(source, "skip_me.cpp", TALKER)
    write(source / "nested", "probe.cpp", TALKER)
    (workspace / "src/chatter_ros/bringup/launch/robot.launch").unlink()
    fresh = _found(workspace, None)
    assert ("src/chatter_ros/chatter/src/listener.cpp", Language.CPP) in fresh
    assert ("src/chatter_ros/chatter/src/nested/probe.cpp", Language.CPP) in fresh
    assert not any("skip_me" in shown for shown, _ in fresh)
    walked.clear()
    assert _found(workspace, FactsCache(tmp_path / "cache")) == fresh != first
    launch = os.path.join(workspace, "src/chatter_ros/bringup/launch")
    assert sorted(walked) == sorted([launch, os.fspath(source), os.fspath(source / "nested")])

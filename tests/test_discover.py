"""File discovery: classification, .gitignore, exclude, ROS ignore markers, generations."""

from __future__ import annotations

import errno
import os
import re
from pathlib import Path
from typing import Any

import pytest
from conftest import write
from hypothesis import given, settings
from hypothesis import strategies as st

from roslint_names.discover import DiscoveryError, classify, discover
from roslint_names.generation import PackageGenerations, package_xml_generation, service_types
from roslint_names.model import Generation, Language


@pytest.mark.parametrize(
    ("name", "text", "language"),
    [
        ("robot.launch", "", Language.LAUNCH_XML),
        ("talker_listener.test", "", Language.LAUNCH_XML),
        ("bringup.launch.xml", "", Language.LAUNCH_XML),
        ("bringup_launch.xml", "", Language.LAUNCH_XML),
        ("bringup.launch.yaml", "", Language.LAUNCH_YAML),
        ("robot.urdf", "", Language.URDF),
        ("robot.urdf.xacro", "", Language.URDF),
        ("talker.cpp", "", Language.CPP),
        ("talker.hpp", "", Language.CPP),
        ("talker.py", "", Language.PYTHON),
        ("package.xml", "<package/>", Language.PACKAGE_XML),
        ("nodes.xml", '<?xml version="1.0"?>\n<!-- c -->\n<launch/>', Language.LAUNCH_XML),
        ("model.xml", "<robot name='r'/>", Language.URDF),
        ("plugins.xml", "<library path='x'/>", None),
        ("bringup.yaml", "# launch\nlaunch:\n- node: {pkg: a, exec: b}\n", Language.LAUNCH_YAML),
        ("params.yaml", "amcl:\n  ros__parameters:\n    use_sim_time: true\n", Language.PARAMETERS),
        # Any YAML may be a parameter file: its content and package decide (extraction).
        ("costmap.yaml", "robot_radius: 0.2\n", Language.PARAMETERS),
        ("CMakeLists.txt", "", Language.CMAKE),
        ("setup.py", "from setuptools import setup\n", Language.SETUP_PY),
        ("setup.cfg", "[options.entry_points]\n", Language.SETUP_CFG),
        ("notes.txt", "", None),
        # A ROS script installed without a suffix: Python by its shebang, nothing else is.
        ("map_hash_generator", "#!/usr/bin/env python3\nimport rclpy\n", Language.PYTHON),
        ("talker", "#!/usr/bin/python\nimport rospy\n", Language.PYTHON),
        ("relay", "#!/usr/bin/env -S python3 -u\n", Language.PYTHON),
        ("setup_env", "#!/bin/bash\nsource /opt/ros/noetic/setup.bash\n", None),
        ("LICENSE", "BSD 3-Clause License\n", None),
        (".gitignore", "build/\n", None),
    ],
)
def test_classify(tmp_path: Path, name: str, text: str, language: Language | None) -> None:
    assert classify(write(tmp_path, name, text)) is language


def test_walk_honours_gitignore_exclude_and_ros_markers(tmp_path: Path) -> None:
    (tmp_path / ".git").mkdir()
    write(tmp_path, ".gitignore", "generated/\n*.bak.launch\n")
    write(tmp_path, "src/bringup/launch/robot.launch", "<launch/>")
    write(tmp_path, "src/bringup/launch/old.bak.launch", "<launch/>")
    write(tmp_path, "src/bringup/generated/robot.launch", "<launch/>")
    write(tmp_path, "src/vendor/.gitignore", "!*.bak.launch\nskip.launch\n")
    write(tmp_path, "src/vendor/skip.launch", "<launch/>")
    write(tmp_path, "src/vendor/keep.launch", "<launch/>")
    write(tmp_path, "src/third_party/x.launch", "<launch/>")
    write(tmp_path, "src/disabled/COLCON_IGNORE", "")
    write(tmp_path, "src/disabled/robot.launch", "<launch/>")
    write(tmp_path, "install/COLCON_IGNORE", "")
    write(tmp_path, "install/share/bringup/launch/robot.launch", "<launch/>")
    found = discover([Path("src")], ["src/third_party/"], tmp_path, tmp_path)
    assert [source.display for source in found] == [
        "src/bringup/launch/robot.launch",
        "src/vendor/keep.launch",
    ]


def test_explicit_files_skip_gitignore_but_not_exclude(tmp_path: Path) -> None:
    write(tmp_path, ".gitignore", "*.launch\n")
    write(tmp_path, "a.launch", "<launch/>")
    write(tmp_path, "b.launch", "<launch/>")
    found = discover([Path("a.launch"), Path("b.launch")], ["b.launch"], tmp_path, tmp_path)
    assert [source.display for source in found] == ["a.launch"]


def test_missing_path_is_an_error_naming_it(tmp_path: Path) -> None:
    with pytest.raises(DiscoveryError, match="no_such_dir"):
        discover([Path("no_such_dir")], [], tmp_path, tmp_path)


def test_symlink_loops_are_not_followed(tmp_path: Path) -> None:
    write(tmp_path, "pkg/robot.launch", "<launch/>")
    os.symlink(tmp_path, tmp_path / "pkg" / "loop")
    found = discover([tmp_path], [], tmp_path, tmp_path)
    assert [source.display for source in found] == ["pkg/robot.launch"]


@pytest.mark.parametrize(
    ("manifest", "generation"),
    [
        ("<buildtool_depend>catkin</buildtool_depend>", Generation.ROS1),
        ("<buildtool_depend>ament_cmake</buildtool_depend>", Generation.ROS2),
        ("<export><build_type>ament_python</build_type></export>", Generation.ROS2),
        ("<!-- <buildtool_depend>catkin</buildtool_depend> -->", None),
        (
            '<buildtool_depend condition="$ROS_VERSION == 1">catkin</buildtool_depend>\n'
            '<buildtool_depend condition="$ROS_VERSION == 2">ament_cmake</buildtool_depend>',
            None,
        ),
    ],
)
def test_package_xml_generation(manifest: str, generation: Generation | None) -> None:
    text = f'<?xml version="1.0"?>\n<package format="3"><name>p</name>{manifest}</package>'
    assert package_xml_generation(text) is generation


def test_nearest_package_xml_decides(tmp_path: Path) -> None:
    write(tmp_path, "src/ros1_pkg/package.xml", "<buildtool_depend>catkin</buildtool_depend>")
    write(tmp_path, "src/ros2_pkg/package.xml", "<buildtool_depend>ament_cmake</buildtool_depend>")
    generations = PackageGenerations()
    assert generations.for_file(tmp_path / "src/ros1_pkg/launch/a.launch") is Generation.ROS1
    assert generations.for_file(tmp_path / "src/ros2_pkg/launch/a.launch.xml") is Generation.ROS2
    assert generations.for_file(tmp_path / "src/a.launch") is None


def test_service_definitions_are_found_with_their_package(tmp_path: Path) -> None:
    write(tmp_path, "src/docking_msgs/package.xml", "<package><name>docking_msgs</name></package>")
    write(tmp_path, "src/docking_msgs/srv/StartDocking.srv", "---\nbool success\n")
    write(tmp_path, "src/docking_msgs/srv/README.md", "")
    found = discover([Path("src")], [], tmp_path, tmp_path)
    assert [(source.display, source.language) for source in found] == [
        ("src/docking_msgs/package.xml", Language.PACKAGE_XML),  # the workspace model's
        ("src/docking_msgs/srv/StartDocking.srv", Language.SERVICE_DEFINITION),
    ]
    assert service_types(found, PackageGenerations()) == frozenset(
        {(None, "docking_msgs/StartDocking")}  # that package.xml names no build tool
    )


GITIGNORES = [
    ["*.launch", "!keep.launch"],
    ["build/", "/install", "log/**", "!log/keep/"],
    ["**/generated/*.py", "docs/**/*.xacro", "a?b[0-9].urdf"],
    ["*", "!*/", "!*.launch"],  # the "ignore all but" idiom
    ["\\!important.launch", "#comment", "", "foo\\ bar.launch "],
    ["*/"],  # every directory: pathspec searches "/" anywhere in the path
    ["**/", "!keep.launch"],
]
PATHS = [
    "keep.launch",
    "robot.launch",
    "pkg/launch/keep.launch",
    "build/",
    "build/x.cpp",
    "src/build/x.cpp",
    "install/setup.py",
    "src/install/setup.py",
    "log/latest/x.launch",
    "log/keep/",
    "src/generated/msg.py",
    "generated/x.py",
    "docs/a/b/robot.xacro",
    "axb1.urdf",
    "pkg/",
    "!important.launch",
    "foo bar.launch",
]


@pytest.mark.parametrize("lines", GITIGNORES)
def test_the_one_regex_per_gitignore_agrees_with_pathspec(lines: list[str]) -> None:
    import pathspec

    from roslint_names.discover import _Spec

    exact = pathspec.GitIgnoreSpec.from_lines(lines)
    ours = _Spec(lines)
    for path in PATHS:
        assert ours.match_file(path) == exact.match_file(path), path


_PIECES = st.sampled_from(["build", "log", "src", "keep", "a", "x.launch", "y.py", "gen"])
_PATTERN = st.builds(
    "".join,
    st.lists(
        st.sampled_from(["", "!", "/", "**/", "*", "*.launch", "build/", "log/**", "a?", "src/"])
        | _PIECES,
        min_size=1,
        max_size=4,
    ),
)
_PATH = st.builds(
    lambda parts, directory: "/".join(parts) + ("/" if directory else ""),
    st.lists(_PIECES, min_size=1, max_size=4),
    st.booleans(),
)


@settings(max_examples=300, deadline=None)
@given(st.lists(_PATTERN, min_size=1, max_size=5), st.lists(_PATH, min_size=1, max_size=8))
def test_the_one_regex_per_gitignore_agrees_with_pathspec_on_any_patterns(
    lines: list[str], paths: list[str]
) -> None:
    """With "!" patterns or without (where a match of the one regex is the answer, no
    pattern asked on its own), whatever the patterns and paths."""
    import pathspec

    from roslint_names.discover import _Spec

    try:
        exact = pathspec.GitIgnoreSpec.from_lines(lines)
    except (ValueError, re.error):
        return  # an invalid pattern: ``_Spec`` leaves such lines out (tested apart)
    ours = _Spec(lines)
    for path in paths:
        assert ours.match_file(path) == exact.match_file(path), (lines, path)


def test_extension_less_scripts_are_found_by_shebang_walked_or_named(tmp_path: Path) -> None:
    write(tmp_path, "src/teleop/scripts/teleop_keyboard", "#!/usr/bin/env python\nimport rospy\n")
    write(tmp_path, "src/teleop/scripts/setup_udev", "#!/bin/sh\necho udev\n")
    write(tmp_path, "src/teleop/Makefile", "all:\n\ttrue\n")
    walked = discover([Path(".")], (), tmp_path, tmp_path)
    assert [(s.display, s.language) for s in walked] == [
        ("src/teleop/scripts/teleop_keyboard", Language.PYTHON)
    ]
    named = [Path("src/teleop/scripts/teleop_keyboard"), Path("src/teleop/Makefile")]
    assert [s.display for s in discover(named, (), tmp_path, tmp_path)] == [
        "src/teleop/scripts/teleop_keyboard"
    ]


# ---------------------------------------------------------------------------------------
# Nothing passed over in silence: what the walk cannot read or will not open is said.

TELEOP_LAUNCH = """\
<launch>
  <node pkg="teleop_twist_keyboard" type="teleop_twist_keyboard.py" name="teleop"/>
</launch>
"""


def refuse_to_list(monkeypatch: pytest.MonkeyPatch, refused: Path) -> None:
    """``os.scandir`` of ``refused`` fails as a directory of mode 000 does for a user
    (root reads it all the same, and the suite runs as root)."""
    listing = os.scandir

    def scandir(path: str) -> Any:
        if os.fspath(path) == os.fspath(refused):
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), os.fspath(path))
        return listing(path)

    monkeypatch.setattr(os, "scandir", scandir)


def test_unreadable_directory_in_the_walk_is_a_warning(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """It was passed over without a word, and its launch files with it."""
    write(tmp_path, "src/teleop/launch/teleop.launch", TELEOP_LAUNCH)
    write(tmp_path, "src/secret/launch/robot.launch", TELEOP_LAUNCH)
    refuse_to_list(monkeypatch, tmp_path / "src" / "secret")
    warnings: list[str] = []
    found = discover([Path("src")], (), tmp_path, tmp_path, warnings)
    assert [source.display for source in found] == ["src/teleop/launch/teleop.launch"]
    assert warnings == [f"cannot read directory src/secret: {os.strerror(errno.EACCES)}"]


def test_unreadable_directory_named_is_an_error(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    write(tmp_path, "src/secret/launch/robot.launch", TELEOP_LAUNCH)
    refuse_to_list(monkeypatch, tmp_path / "src" / "secret")
    message = f"src/secret: cannot read directory: {os.strerror(errno.EACCES)}"
    with pytest.raises(DiscoveryError, match=re.escape(message)):
        discover([Path("src/secret")], (), tmp_path, tmp_path, [])


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs (POSIX)")
def test_fifo_named_like_a_source_in_the_tree_is_a_warning_never_opened(tmp_path: Path) -> None:
    write(tmp_path, "src/teleop/launch/teleop.launch", TELEOP_LAUNCH)
    os.mkfifo(tmp_path / "src" / "teleop" / "launch" / "pipe.launch")
    os.mkfifo(tmp_path / "src" / "teleop" / "ignored.launch")
    write(tmp_path, "src/teleop/.gitignore", "ignored.launch\n")
    warnings: list[str] = []
    found = discover([Path("src")], (), tmp_path, tmp_path, warnings)
    assert [source.display for source in found] == ["src/teleop/launch/teleop.launch"]
    assert warnings == ["skipped src/teleop/launch/pipe.launch: not a regular file (a FIFO)"]


def test_named_paths_that_yield_no_file_are_said(tmp_path: Path) -> None:
    """A link loop and an empty directory both said 'All checks passed: 0 files'."""
    (tmp_path / "empty").mkdir()
    os.symlink("loop_b", tmp_path / "loop_a")
    os.symlink("loop_a", tmp_path / "loop_b")
    write(tmp_path, "README.md", "# teleop\n")  # not lintable, and not a failure: quiet
    warnings: list[str] = []
    named = [Path("empty"), Path("loop_a"), Path("README.md")]
    assert discover(named, (), tmp_path, tmp_path, warnings) == []
    assert warnings == [
        "empty: no file to lint in this directory",
        f"loop_a: not linted: {os.strerror(errno.ELOOP)}",
    ]


def test_invalid_gitignore_patterns_are_said_and_the_others_kept(tmp_path: Path) -> None:
    """A '!' alone or a range such as '[z-a]' stopped the run with an internal error."""
    write(tmp_path, "src/teleop/.gitignore", "build/\n!\n[z-a].launch\n*.bak.launch\n")
    write(tmp_path, "src/teleop/launch/teleop.launch", TELEOP_LAUNCH)
    write(tmp_path, "src/teleop/launch/teleop.bak.launch", TELEOP_LAUNCH)
    write(tmp_path, "src/teleop/build/teleop.launch", TELEOP_LAUNCH)
    warnings: list[str] = []
    found = discover([Path("src")], (), tmp_path, tmp_path, warnings)
    assert [source.display for source in found] == ["src/teleop/launch/teleop.launch"]
    assert warnings == [
        "src/teleop/.gitignore:2: invalid pattern '!' not applied: git does not accept it",
        "src/teleop/.gitignore:3: invalid pattern '[z-a].launch' not applied: "
        "bad character range z-a",
    ]


def test_a_path_s_parent_is_the_one_dirname_gives() -> None:
    """The package lookup's own parent of a path (``rpartition``, not ``dirname``: a
    quarter of the lookup at 81,000 files) agrees with ``os.path.dirname`` everywhere."""
    from roslint_names.generation import _parent

    paths = ["/ws/src/robot/src/driver.cpp", "/ws", "/", "", "robot", "src/robot"]
    paths += ["src//robot", "//ws", "/ws/src/", "src/robot//", "///", "launch/"]
    for path in paths:
        assert _parent(path) == os.path.dirname(path), path

"""Which files are test code, by the ROS ecosystem's own conventions.

Test code is judged for what breaks a test, not for style (``Rule.judges_test_code``,
``[test-code]`` in the config). A file is test code when its path says so:

- a folder named ``test`` or ``tests`` (ament and catkin put tests there), or a test
  package's folder (``test_*``, ``*_tests``: ``test_rclcpp``, ``nav2_system_tests``), or
  one of test support code (``testing``, ``*_testing``, ``*_test_utils``,
  ``*_test_nodes``: Autoware's ``testing/autoware_test_utils``, ros2_control's
  ``hardware_interface_testing``, ros2_controllers' ``ros2_controllers_test_nodes``),
  which exists for tests;
- a test file's name: ``test_*``, ``*_test``, ``*_tests`` or ``test`` before the first dot
  (``test_node.py``, ``buffer_core_test.cpp``), a rostest ``.test`` file, a launch_testing
  ``*.test.py``; but not for a launch file, which is test code by its content alone:
  ``test_rplidar.launch`` is what rplidar's users launch to try the driver, and holds no
  ``<test>``;
- a pattern of ``[test-code] paths``;

or when its content does: a gtest, gmock or Catch2 include in C++; an import of pytest,
unittest, launch_testing, rostest or rosunit, or a ``generate_test_description`` in Python;
a rostest ``<test>`` element in a launch file.

Example code is judged as test code is (``is_example_code``): it shows how to use an API
and runs alone, in the root namespace, so its names are what a reader copies, not a
system's interfaces. ros2/demos' ``Client`` node or an ``examples/`` script's absolute
action name are the example's choice; an illegal name still breaks it and is reported.
"""

from __future__ import annotations

import functools
import re
from pathlib import Path

from .config import Settings
from .model import Language

_TEST_DIRECTORY = re.compile(
    r"tests?|test_.+|.+_tests|(?:.+_)?testing|.+_test_(?:utils?|tools|helpers|nodes)",
    re.IGNORECASE,
)
_TEST_STEM = re.compile(r"tests?|test_.+|.+_tests?", re.IGNORECASE)
# A folder, package or file whose name starts or ends with one of these words holds
# examples: ``examples/``, ``demo_nodes_cpp``, ``quality_of_service_demo``,
# ``rospy_tutorials``, ``example_7``, ``ros2_control_demos``, ``example_nav_to_pose.py``.
_EXAMPLE_WORD = r"(?:examples?|demos?|tutorials?|samples?)"
_EXAMPLE_NAME = re.compile(rf"{_EXAMPLE_WORD}(?:[-_+].*)?|.*[-_+]{_EXAMPLE_WORD}", re.IGNORECASE)
_CONTENT = {
    Language.CPP: re.compile(rb'^[ \t]*#[ \t]*include[ \t]*[<"](?:gtest|gmock|catch2)/', re.M),
    Language.PYTHON: re.compile(
        rb"^[ \t]*(?:import|from)[ \t]+(?:pytest|unittest|launch_testing|rostest|rosunit)\b"
        rb"|^[ \t]*def[ \t]+generate_test_description\b",
        re.M,
    ),
    Language.LAUNCH_XML: re.compile(rb"<test[\s>/]"),
}
_CONTENT[Language.LAUNCH_PYTHON] = _CONTENT[Language.PYTHON]
# Launch files are often named for what they let a user try (``test_rplidar.launch``,
# ``test_camera.launch.py``): their name does not make them tests, a ``<test>`` or a
# launch_testing import does.
_NAMED_FOR_USE = frozenset({Language.LAUNCH_XML, Language.LAUNCH_YAML, Language.LAUNCH_PYTHON})


def is_test_code(
    relative_path: str, language: Language, data: bytes | str, settings: Settings
) -> bool:
    """Whether the file at ``relative_path`` (below the settings' root, '/'-separated) with
    these contents is test code."""
    *directories, name = relative_path.split("/")
    if any(is_test_directory(directory) for directory in directories):
        return True
    stem, *suffixes = name.split(".")
    if "test" in (suffix.lower() for suffix in suffixes):
        return True
    if _TEST_STEM.fullmatch(stem) and language not in _NAMED_FOR_USE:
        return True
    if settings.test_code.paths and _configured(relative_path, settings.test_code.paths):
        return True
    pattern = _CONTENT.get(language)
    if pattern is None:
        return False
    content = data.encode("utf-8", "surrogateescape") if isinstance(data, str) else data
    return pattern.search(content) is not None


def is_test_directory(name: str) -> bool:
    """Whether a folder called ``name`` holds tests or test support code."""
    return _TEST_DIRECTORY.fullmatch(name) is not None


def is_example_code(relative_path: str, settings: Settings) -> bool:
    """Whether the file at ``relative_path`` (below the settings' root, '/'-separated) is
    example, demo or tutorial code: by its own name without suffixes, or the name of a
    folder it is in, up to the workspace's source space.

    The folders that count are the file's package's (its own folder among them) and those
    between the package and the ``src`` folder that holds it, a repository's (``src/demos/
    composition``: a package of ros2/demos), or the root's where the run starts inside a
    repository (``cd demos``). Above the source space the folders are a workspace's,
    whatever it is called: the examples workspace bundled with this linter holds products.
    """
    path = Path(relative_path)
    if _EXAMPLE_NAME.fullmatch(path.name.split(".")[0]):
        return True
    if not path.is_absolute():
        path = settings.root / path
    folder, in_package = path.parent, False
    while True:
        if in_package and folder.name == "src":
            return False
        in_package = in_package or _is_package(folder)
        if _EXAMPLE_NAME.fullmatch(folder.name):
            return True
        if folder in (settings.root, folder.parent):
            return False
        folder = folder.parent


@functools.lru_cache(maxsize=4096)
def _is_package(folder: Path) -> bool:
    return (folder / "package.xml").is_file()


def _configured(relative_path: str, patterns: tuple[str, ...]) -> bool:
    import pathspec  # only runs that configure test-code paths pay for it

    spec = pathspec.GitIgnoreSpec.from_lines(patterns)
    return bool(spec.match_file(relative_path))

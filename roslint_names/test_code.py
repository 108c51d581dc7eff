"""Which files are test code, by the ROS ecosystem's own conventions.

Test code is judged for what breaks a test, not for style (``Rule.judges_test_code``,
``[test-code]`` in the config). A file is test code when its path says so:

- a folder named ``test`` or ``tests`` (ament and catkin put tests there), or a test
  package's folder (``test_*``, ``*_tests``: ``test_rclcpp``, ``nav2_system_tests``);
- a test file's name: ``test_*``, ``*_test``, ``*_tests`` or ``test`` before the first dot
  (``test_node.py``, ``buffer_core_test.cpp``), a rostest ``.test`` file, a launch_testing
  ``*.test.py``; but not for a launch file, which is test code by its content alone:
  ``test_rplidar.launch`` is what rplidar's users launch to try the driver, and holds no
  ``<test>``;
- a pattern of ``[test-code] paths``;

or when its content does: a gtest, gmock or Catch2 include in C++; an import of pytest,
unittest, launch_testing, rostest or rosunit, or a ``generate_test_description`` in Python;
a rostest ``<test>`` element in a launch file.
"""

from __future__ import annotations

import re

from .config import Settings
from .model import Language

_TEST_DIRECTORY = re.compile(r"tests?|test_.+|.+_tests", re.IGNORECASE)
_TEST_STEM = re.compile(r"tests?|test_.+|.+_tests?", re.IGNORECASE)
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
    if any(_TEST_DIRECTORY.fullmatch(directory) for directory in directories):
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


def _configured(relative_path: str, patterns: tuple[str, ...]) -> bool:
    import pathspec  # only runs that configure test-code paths pay for it

    spec = pathspec.GitIgnoreSpec.from_lines(patterns)
    return bool(spec.match_file(relative_path))

"""What became of each file a run was asked to check, for ``--verbose``.

A file can be checked in full, judged as test or example code (only the rules that
``[test-code]`` selects), or read by a byte prefilter and found to hold no ROS API the
extractors read (never parsed: most C++ of a workspace is algorithms and drivers). Without
saying so, a file with no finding is indistinguishable from one that was never looked at.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from pathlib import Path

from .checks import relative_to_root
from .config import Settings
from .discover import SourceFile, classify
from .extract import EXTRACTOR_MODULES
from .model import Language
from .reading import read_file
from .test_code import is_example_code, is_test_code


def fates(sources: Iterable[SourceFile], settings: Settings) -> Iterator[tuple[str, str]]:
    """(display path, fate) of each source, in the order given."""
    for source in sources:
        data, _, skipped = read_file(source.path, settings.max_file_size)
        if data is None or skipped:
            continue  # said already, with its reason (``LintResult.skipped``)
        yield source.display, _fate(source, data, settings)


def _fate(source: SourceFile, data: bytes, settings: Settings) -> str:
    if source.language is Language.CPP:
        from .extract.cpp.extract import decode, has_ros_marker

        if not has_ros_marker(decode(data)[0]):
            return "not parsed: it names no roscpp or rclcpp API"
    elif source.language is Language.PYTHON:
        from .extract.python.extract import may_hold_names

        if not may_hold_names(data):
            return "not parsed: it imports no ROS client library and holds no launch description"
    relative = relative_to_root(source.display, settings)
    if is_test_code(relative, source.language, data, settings):
        return "test code: judged by the [test-code] rules only"
    if is_example_code(relative, settings):
        return "example code: judged by the [test-code] rules only"
    return "checked"


def unchecked(path: Path) -> str:
    """Why a file named on the command line is not among the files the run checks."""
    language = classify(path)
    if language is None:
        return "not checked: no kind of file the linter reads"
    if language not in EXTRACTOR_MODULES:
        return "not checked: read only for what it says of its package"
    return "not checked: the configuration's exclude covers it"

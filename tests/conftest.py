"""Shared test helpers: run the real CLI in-process and read what it printed."""

from __future__ import annotations

import json
import os
import shutil
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

import pytest

from roslint_names import gather, reading
from roslint_names.cli import main
from roslint_names.discover import discover
from roslint_names.engine import RunOptions, lint, lintable, workspace_packages
from roslint_names.gather import Specialiser, extract_batch
from roslint_names.generation import DEFAULT_GENERATION, PackageGenerations
from roslint_names.model import Generation, Language
from roslint_names.workers import Dispatcher
from roslint_names.workspace.build import build_parts
from roslint_names.workspace.index import Package

CATKIN_PACKAGE = """<?xml version="1.0"?>
<package format="2">
  <name>{name}</name>
  <version>0.1.0</version>
  <description>Test package</description>
  <maintainer email="dev@example.com">Dev</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
</package>
"""

AMENT_PACKAGE = """<?xml version="1.0"?>
<package format="3">
  <name>{name}</name>
  <version>0.1.0</version>
  <description>Test package</description>
  <maintainer email="dev@example.com">Dev</maintainer>
  <license>Apache-2.0</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <export><build_type>ament_cmake</build_type></export>
</package>
"""


@dataclass(frozen=True)
class Run:
    exit_code: int
    stdout: str
    stderr: str

    def findings(self) -> list[dict[str, Any]]:
        findings: list[dict[str, Any]] = json.loads(self.stdout)["findings"]
        return findings

    def codes(self) -> list[str]:
        return [finding["code"] for finding in self.findings()]


@contextmanager
def chdir(path: Path) -> Iterator[None]:
    previous = Path.cwd()
    os.chdir(path)
    try:
        yield
    finally:
        os.chdir(previous)


@pytest.fixture
def old_tree(monkeypatch: pytest.MonkeyPatch) -> None:
    """Statuses trusted as soon as they are taken, as for a tree left past the racy window
    (``reading.RACY_NANOSECONDS``, which its own tests keep): a test can set a file's
    modification time back, never its change time."""
    monkeypatch.setattr(reading, "RACY_NANOSECONDS", 0)


@pytest.fixture(autouse=True)
def private_cache(
    tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch
) -> Path:
    """Every test gets its own facts cache, outside the tree it lints.

    The suite never writes to the user's cache, and no test sees another's entries.
    Subprocesses (the pre-commit test) inherit the variable.
    """
    directory = tmp_path_factory.mktemp("xdg-cache")
    monkeypatch.setenv("XDG_CACHE_HOME", str(directory))
    return directory / "roslint-names"


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    """The suite runs alike in a sourced ROS environment: ``ROS_PYTHON_VERSION`` decides
    whether a ROS 1 package's Python 2 is read (``config.ros1_python2``)."""
    for variable in ("ROS_PYTHON_VERSION", "ROS_VERSION"):
        monkeypatch.delenv(variable, raising=False)


@pytest.fixture
def run_cli(capsys: pytest.CaptureFixture[str]) -> Any:
    def run(arguments: Sequence[str], cwd: Path) -> Run:
        with chdir(cwd):
            try:
                exit_code = main(list(arguments))
            except SystemExit as stop:
                exit_code = int(stop.code or 0)
        captured = capsys.readouterr()
        return Run(exit_code, captured.out, captured.err)

    return run


def write(root: Path, relative: str, text: str) -> Path:
    path = root / relative
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def ament_package(root: Path, name: str, cmake: str | None = None) -> Path:
    """``src/<name>``: an ament package, with ``cmake`` as its CMakeLists.txt if given."""
    directory = root / "src" / name
    write(directory, "package.xml", AMENT_PACKAGE.format(name=name))
    if cmake is not None:
        write(directory, "CMakeLists.txt", cmake)
    return directory


def findings_of(run_cli: Any, root: Path, code: str) -> list[dict[str, Any]]:
    """The JSON findings of one rule over the workspace at ``root``."""
    result = run_cli(["check", "--format", "json", "--select", code, "."], root)
    assert result.exit_code in (0, 1), result.stderr
    found: list[dict[str, Any]] = result.findings()
    return found


def line_places(found: list[dict[str, Any]]) -> list[tuple[str, int]]:
    return sorted((f["path"], f["line"]) for f in found)


def write_package(root: Path, ros: int, name: str = "robot_bringup") -> Path:
    template = CATKIN_PACKAGE if ros == 1 else AMENT_PACKAGE
    return write(root, "package.xml", template.format(name=name))


@pytest.fixture
def lint_text(run_cli: Any, tmp_path: Path) -> Any:
    """`lint_text(source, file="robot.launch", ros=1)` -> codes found, like pyflakes' harness."""

    def lint(source: str, file: str, ros: int | None = None, *options: str) -> list[str]:
        if ros is not None:
            write_package(tmp_path, ros)
        write(tmp_path, file, source)
        result: Run = run_cli(["check", "--format", "json", *options, file], tmp_path)
        assert result.exit_code in (0, 1), result.stderr
        return result.codes()

    return lint


@pytest.fixture
def extractions(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The paths the engine extracted, in order (in-process runs only)."""
    seen: list[str] = []
    real = gather.extractor_for

    def counting(language: Language) -> gather.Extract:
        extract = real(language)

        def wrapper(
            path: str, data: bytes, package: Generation | None, fallback: Generation
        ) -> Any:
            seen.append(path)
            return extract(path, data, package, fallback)

        return wrapper

    monkeypatch.setattr(gather, "extractor_for", counting)
    return seen


def code_units(text: str, encoding: str) -> int:
    """How many code units of ``encoding`` (an LSP position encoding) ``text`` takes: how
    a client counts columns."""
    if encoding == "utf-32":
        return len(text)
    if encoding == "utf-16":
        return len(text.encode("utf-16-le")) // 2
    return len(text.encode("utf-8"))


class ExampleCopy:
    """The example workspace copied to ``root``, with its settings: what the tests that
    edit it step by step and compare the graph a patch gives with a build's start from."""

    EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

    def __init__(self, root: Path) -> None:
        from roslint_names.config import load_settings
        from roslint_names.registry import load_registry

        shutil.copytree(self.EXAMPLES, root)
        self.root = root
        self.registry = load_registry()
        self.settings = load_settings(None, root, self.registry)
        # Of the last ``built_parts``: what a patch of that build is handed.
        self.packages: list[Package] = []
        self.specialiser: Specialiser | None = None

    def edit(self, relative: str, old: str, new: str) -> None:
        """``old`` replaced by ``new`` once in the file; ``new`` appended where ``old`` is
        empty."""
        path = self.root / relative
        text = path.read_text(encoding="utf-8")
        assert old in text, f"{old!r} is not in {relative}"
        path.write_text(text.replace(old, new, 1) if old else text + new, encoding="utf-8")

    def add(self, files: Mapping[str, str]) -> None:
        """Files the examples do not hold, by path below the root."""
        for relative, text in files.items():
            (self.root / relative).parent.mkdir(parents=True, exist_ok=True)
            (self.root / relative).write_text(text, encoding="utf-8")

    def built_parts(self) -> Any:
        """The workspace as it is now, built as the CLI builds it (``build_parts``): the
        graph (asserted equal to ``lint``'s), the launch parts, the code parameter parts,
        every file's facts by display path; and, kept on the copy for a patch of that
        build, its packages and the specialiser of its launch files."""
        root = self.root
        sources = lintable(discover([root], (), root, root))
        result = lint(sources, self.settings, self.registry, RunOptions(), want_graph=True)
        self.packages = workspace_packages(sources, PackageGenerations())
        self.specialiser = Specialiser(
            sources,
            PackageGenerations(),
            DEFAULT_GENERATION,
            None,
            self.settings.max_file_size,
            dispatcher=Dispatcher(partial(extract_batch, None), 1),
            ros1_python2=False,
        )
        graph, parts, code = build_parts(
            result.facts, self.packages, self.specialiser, self.specialiser.prepare
        )
        assert graph == result.graph
        return graph, parts, code, {facts.path: facts for facts in result.facts}


def assert_patched(steps: Sequence[tuple[str, Any, Any]], step: int) -> None:
    """A step of an edit sequence (the file edited, the graph built after it, the graph
    patched) was patched, into the built graph."""
    relative, built, patch = steps[step]
    assert patch is not None, f"step {step} ({relative}) was not patched"
    assert patch == built, f"step {step} ({relative})"

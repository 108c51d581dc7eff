"""C++ sources that no build file of their package compiles: code that never runs.

A ROS 1 nodelet left in a ported package (moveit2's ``depth_self_filter_nodelet.cpp``,
its ``add_library`` commented out with ``TODO: Port to ROS2``), a test whose
``ament_add_gtest`` is commented out: their names reach no running graph, and a finding
in them asks for an edit no user of the package would ever see. Whether a file is built
is a question about other files, the package's ``CMakeLists.txt`` and ``.cmake`` files,
so it is decided here, over the run's facts, and never stored with the file's own.

A translation unit (``.cpp``, ``.cc``, ``.cxx``, ``.c++``; never a header, which builds
include without naming) is unbuilt only when all of this holds:

* its package's ``CMakeLists.txt`` is in the run, and no build file of the run names it
  as a target's source (``CompiledSources.paths``, any package's: ``../common/a.cpp``);
* no C++ file of the run includes a source of its name (``#include "solver.cpp"``);
* nothing its package's build files leave open may be it: no pattern matches it (the
  unknown parts of a source, ``file(GLOB)``'s variable, a file that did not lex: ``*``),
  no word of a command the linter does not know names its path, a directory above it,
  its name or its stem, and every ``add_subdirectory`` and ``include`` of the package
  names a build file the run holds.

A ``.cmake`` file is run by the file that includes it, in that file's directory: its
relative paths are read from its own directory and from every directory of the package
that holds a ``CMakeLists.txt``. A setup.py building extension modules compiles anything.
"""

from __future__ import annotations

import posixpath
from dataclasses import dataclass, field
from fnmatch import fnmatchcase

from roslint_names.model import CompiledSources, FileFacts, Language
from roslint_names.workspace.index import WorkspaceIndex, join, parent

TRANSLATION_UNITS = (".cpp", ".cc", ".cxx", ".c++")
_CMAKE_LISTS = "CMakeLists.txt"


@dataclass(frozen=True)
class _BuildFile:
    path: str  # display path
    compiled: CompiledSources
    module: bool  # a .cmake file, run in its includer's directory


@dataclass
class BuiltSources:
    """What the run's build files compile, gathered file by file (``add``)."""

    _by_package: dict[str, list[_BuildFile]] = field(default_factory=dict)
    _compiled: set[str] = field(default_factory=set)  # display paths some target names
    _build_files: set[str] = field(default_factory=set)  # display paths of build files
    _included: set[str] = field(default_factory=set)  # names of included sources

    def add(self, facts: FileFacts, package: str | None) -> None:
        """One file's facts; ``package`` the display directory of its package."""
        self._included.update(facts.included_sources)
        compiled = facts.compiled
        if compiled is None:
            return
        self._build_files.add(facts.path)
        directory = parent(facts.path)
        self._compiled.update(join(directory, path) for path in compiled.paths)
        if package is None:
            return
        module = facts.path.endswith(".cmake")
        self._by_package.setdefault(package, []).append(_BuildFile(facts.path, compiled, module))

    def unbuilt(self, path: str, package: str | None) -> bool:
        """Whether the C++ file at display path ``path`` is certainly compiled by nothing."""
        if package is None or join(package, _CMAKE_LISTS) not in self._build_files:
            return False  # no CMake build, or the run holds only part of it
        if not path.lower().endswith(TRANSLATION_UNITS):
            return False
        if path in self._compiled or posixpath.basename(path) in self._included:
            return False
        build_files = self._by_package[package]
        lists = [parent(f.path) for f in build_files if f.path.endswith(_CMAKE_LISTS)]
        inside = path[len(package) :].lstrip("/") if package else path
        for build_file in build_files:
            bases = [parent(build_file.path)] + (lists if build_file.module else [])
            if any(self._may_compile(build_file.compiled, base, path, inside) for base in bases):
                return False
        return True

    def _may_compile(self, compiled: CompiledSources, base: str, path: str, inside: str) -> bool:
        """Whether what one build file leaves open, read from ``base``, may be ``path``
        (``inside``: the same, relative to its package's directory)."""
        for pattern in compiled.patterns:
            if pattern.startswith("*"):  # an unknown start: any directory of the package
                if fnmatchcase(inside, pattern) or fnmatchcase(path, pattern):
                    return True
            elif fnmatchcase(path, join(base, pattern)):
                return True
        if any(_names(join(base, word), path) for word in compiled.words):
            return True
        for directory in compiled.subdirectories:
            below = join(base, directory)
            if join(below, _CMAKE_LISTS) not in self._build_files and path.startswith(below + "/"):
                return True  # a subdirectory whose CMakeLists.txt the run does not hold
        return any(join(base, included) not in self._build_files for included in compiled.includes)


def _names(word: str, path: str) -> bool:
    """Whether a word (joined with its build file's directory) may name the file at
    ``path``: by its path, a directory above it, its name, or its stem (a macro of
    another package may make ``src/talker.cpp`` of ``talker``)."""
    name = posixpath.basename(path)
    return (
        path == word
        or path.startswith(word + "/")
        or posixpath.basename(word) in (name, name.rpartition(".")[0])
    )


def unbuilt_sources(index: WorkspaceIndex) -> frozenset[str]:
    """The display paths of the workspace's C++ sources no build file compiles."""
    built = BuiltSources()
    directories: dict[str, str | None] = {}
    for path, facts in index.facts.items():
        package = index.package_of(path)
        directories[path] = None if package is None else package.directory
        if facts.compiled is not None or facts.included_sources:
            built.add(facts, directories[path])
    return frozenset(
        path
        for path, facts in index.facts.items()
        if facts.language is Language.CPP and built.unbuilt(path, directories[path])
    )

"""C++ sources that no build file of their package compiles: code that never runs; and
those compiled only into test executables that rostest starts, and so names.

A ROS 1 nodelet left in a ported package (moveit2's ``depth_self_filter_nodelet.cpp``,
its ``add_library`` commented out with ``TODO: Port to ROS2``), a test whose
``ament_add_gtest`` is commented out, or whose directory's ``add_subdirectory`` is
(moveit2's ``planning_interface/test``): their names reach no running graph, and a
finding in them asks for an edit no user of the package would ever see. Whether a file is
built is a question about other files, the package's ``CMakeLists.txt`` and ``.cmake``
files, so it is decided here, over the run's facts, and never stored with the file's own.

CMake reads a package's root ``CMakeLists.txt``, and another only where a file it reads
runs it: ``add_subdirectory`` of its directory, ``include`` of it. A ``CMakeLists.txt``
nothing reached names that way builds nothing, and what it compiles does not count. What
a reached file leaves open may run one too: a pattern that may match it (an unknown
subdirectory, a file that did not lex: ``*``), a word of a command the linter does not
know that names its directory or one above. ``.cmake`` files count as read whatever
includes them (``include(Name)`` finds one through ``CMAKE_MODULE_PATH``, which is not
followed), as does a setup.py.

A translation unit (``.cpp``, ``.cc``, ``.cxx``, ``.c++``; never a header, which builds
include without naming) is unbuilt only when all of this holds:

* its package's ``CMakeLists.txt`` is in the run, and no build file CMake reads names it
  as a target's source (``CompiledSources.paths``, any package's: ``../common/a.cpp``);
* no C++ file of the run includes a source of its name (``#include "solver.cpp"``);
* nothing the package's build files that CMake reads leave open may be it: no pattern
  matches it (the unknown parts of a source, ``file(GLOB)``'s variable, a file that did
  not lex: ``*``), no word of a command the linter does not know names its path, a
  directory above it, its name or its stem, and every ``add_subdirectory`` and
  ``include`` of those files names a build file the run holds.

It is started only by rostest when the same holds but for ``add_rostest_gtest`` (or
``add_rostest_gmock``) naming it (``CompiledSources.rostest``): the executable is then a
test that rostest starts from its .test file, and roslaunch names every node it starts.

A ``.cmake`` file is run by the file that includes it, in that file's directory: its
relative paths are read from its own directory and from every directory of the package
that holds a ``CMakeLists.txt`` CMake reads. A setup.py building extension modules
compiles anything.
"""

from __future__ import annotations

import posixpath
from collections.abc import Iterable
from dataclasses import dataclass, field
from fnmatch import fnmatchcase
from functools import cached_property, lru_cache

from roslint_names.model import CompiledSources, FileFacts, Language
from roslint_names.workspace.index import WorkspaceIndex, join, parent

TRANSLATION_UNITS = (".cpp", ".cc", ".cxx", ".c++")
# What ``unbuilt_sources`` reads of each file's facts (besides where the file is).
BUILD_FIELDS = ("language", "compiled", "included_sources")
_CMAKE_LISTS = "CMakeLists.txt"


@dataclass(frozen=True)
class _BuildFile:
    path: str  # display path
    compiled: CompiledSources
    module: bool  # a .cmake file, run in its includer's directory
    package: str | None  # the display directory of its package

    @property
    def lists(self) -> bool:
        """A ``CMakeLists.txt``: read only where the package's build reaches it."""
        return posixpath.basename(self.path) == _CMAKE_LISTS

    @cached_property
    def named(self) -> _Named:
        """The display paths its targets name."""
        directory = parent(self.path)
        return _Named(
            frozenset(join(directory, path) for path in self.compiled.paths),
            frozenset(join(directory, path) for path in self.compiled.rostest),
        )


@dataclass(frozen=True)
class _Named:
    """The display paths the targets of build files name."""

    targets: frozenset[str]  # by any target but rostest's
    rostest: frozenset[str]  # by a test executable only rostest starts


@dataclass
class BuiltSources:
    """What the run's build files compile, gathered file by file (``add``), indexed when
    first asked: a run after an edit takes what the last run gathered (5,208 build files
    at 8 copies of the benchmark's workspace, 0.05 s to index) and most often asks
    nothing of it."""

    _by_package: dict[str, list[_BuildFile]] = field(default_factory=dict)
    _outside: list[_BuildFile] = field(default_factory=list)  # of no package: all count
    _build_files: set[str] = field(default_factory=set)  # display paths of build files
    _included: set[str] = field(default_factory=set)  # names of included sources
    # The build files whose targets name a file, by its display path
    _naming_file: dict[str, list[_BuildFile]] = field(default_factory=dict)
    # Worked out on the first question after an ``add``: per package, the build files
    # CMake reads (and their paths); per file asked about, whether they name it.
    _reached: dict[str, tuple[_BuildFile, ...]] = field(default_factory=dict)
    _reached_paths: dict[str, frozenset[str]] = field(default_factory=dict)
    _naming: dict[str, tuple[bool, bool]] = field(default_factory=dict)
    # Per package: what its build files, each read from its directories, leave open.
    _openings: dict[str, tuple[_Opening, ...]] = field(default_factory=dict)
    _cmake_built: dict[str, bool] = field(default_factory=dict)  # its root CMakeLists.txt held
    # What was added, only the fields read: the same answers, remade in a later run.
    _given: list[tuple[FileFacts, str | None]] = field(default_factory=list)
    _indexed: int = 0  # how many of ``_given`` are in the fields above

    @classmethod
    def of(cls, given: Iterable[tuple[FileFacts, str | None]]) -> BuiltSources:
        """What ``given`` (of an earlier ``given``, with its packages) compiles."""
        built = cls()
        built._given.extend(given)
        return built

    def add(self, facts: FileFacts, package: str | None) -> None:
        """One file's facts; ``package`` the display directory of its package."""
        read = FileFacts(
            facts.path,
            facts.language,
            facts.generation,
            compiled=facts.compiled,
            included_sources=facts.included_sources,
        )
        self._given.append((read, package))

    def given(self) -> tuple[tuple[FileFacts, str | None], ...]:
        """What was added, as ``add`` reads it: adding it again gives the same answers."""
        return tuple(self._given)

    def _index(self) -> None:
        """Take what was added since the last question into the fields questions read."""
        if self._indexed == len(self._given):
            return
        self._reached.clear()
        self._reached_paths.clear()
        self._naming.clear()
        self._openings.clear()
        self._cmake_built.clear()
        for facts, package in self._given[self._indexed :]:
            self._included.update(facts.included_sources)
            compiled = facts.compiled
            if compiled is None:
                continue
            self._build_files.add(facts.path)
            build_file = _BuildFile(facts.path, compiled, facts.path.endswith(".cmake"), package)
            if package is None:
                self._outside.append(build_file)
            else:
                self._by_package.setdefault(package, []).append(build_file)
            named = build_file.named
            for path in named.targets | named.rostest:
                self._naming_file.setdefault(path, []).append(build_file)
        self._indexed = len(self._given)

    def unbuilt(self, path: str, package: str | None) -> bool:
        """Whether the C++ file at display path ``path`` is certainly compiled by nothing."""
        self._index()
        if package is None or not self._whole_story(path, package):
            return False
        return not self._named(path)[1] and not self._compiled_otherwise(path, package)

    def started_by_rostest(self, path: str, package: str | None) -> bool:
        """Whether the C++ file at display path ``path`` is certainly compiled into test
        executables that only rostest starts, and into nothing else."""
        self._index()
        if package is None or not self._whole_story(path, package):
            return False
        return self._named(path)[1] and not self._compiled_otherwise(path, package)

    def _whole_story(self, path: str, package: str) -> bool:
        """Whether the run holds what builds the file, a translation unit (a build names
        no header, it includes them): its package's CMake build, from its root."""
        built = self._cmake_built.get(package)
        if built is None:  # asked for each source of the package: joined once
            built = self._cmake_built[package] = join(package, _CMAKE_LISTS) in self._build_files
        if not built:
            return False  # no CMake build, or the run holds only part of it
        return path.lower().endswith(TRANSLATION_UNITS)

    def _compiled_otherwise(self, path: str, package: str) -> bool:
        """Whether anything but a rostest test executable may compile the file."""
        if self._named(path)[0] or posixpath.basename(path) in self._included:
            return True
        inside = path[len(package) :].lstrip("/") if package else path
        return any(opening.may_be(path, inside) for opening in self._openings_of(package))

    def _openings_of(self, package: str) -> tuple[_Opening, ...]:
        """What each build file of the package that CMake reads leaves open, read from
        its own directory (and, for a ``.cmake`` file, from every directory of a
        ``CMakeLists.txt`` read): made once per package, asked for each of its sources."""
        if package not in self._openings:
            build_files = self._reached_files(package)
            lists = [parent(f.path) for f in build_files if f.lists]
            self._openings[package] = tuple(
                _Opening.of(build_file.compiled, base, self._build_files)
                for build_file in build_files
                for base in [parent(build_file.path)] + (lists if build_file.module else [])
            )
        return self._openings[package]

    def _named(self, path: str) -> tuple[bool, bool]:
        """Whether a target of a build file CMake reads names the file at display path
        ``path``, and whether a test executable only rostest starts does. Only the build
        files naming it are asked whether CMake reads them: a patch asks about one
        package's files, and the packages of those alone are reached
        (``_reached_files``), not every package of the workspace (0.12 s at 8 copies of
        the benchmark's workspace); and each source of a build about the few that name
        it, not about every build file above it and every one naming files outside its
        directory (390,000 questions for 22,000 sources at 8 copies: ``unbuilt_sources``
        took 0.65-0.82 s there, 0.33-0.60 s since)."""
        found = self._naming.get(path)
        if found is None:
            targets = rostest = False
            for build_file in self._naming_file.get(path, ()):
                if self._reads(build_file):
                    named = build_file.named
                    targets = targets or path in named.targets
                    rostest = rostest or path in named.rostest
            found = self._naming[path] = (targets, rostest)
        return found

    def _reads(self, build_file: _BuildFile) -> bool:
        """Whether CMake reads a build file (every one of no package does)."""
        package = build_file.package
        if package is None:
            return True
        reached = self._reached_paths.get(package)
        if reached is None:
            reached = frozenset(f.path for f in self._reached_files(package))
            self._reached_paths[package] = reached
        return build_file.path in reached

    def _reached_files(self, package: str) -> tuple[_BuildFile, ...]:
        """The package's build files that its build reads: the ``CMakeLists.txt`` files
        its root one reaches, every other build file (module docstring)."""
        if package not in self._reached:
            files = self._by_package.get(package, [])
            lists = {f.path: f for f in files if f.lists}
            others = tuple(f for f in files if not f.lists)
            modules = [f for f in others if f.module]
            root = join(package, _CMAKE_LISTS)
            reached = {root: lists[root]} if root in lists else {}
            grown = True
            while grown:  # until no reached file runs one more
                grown = False
                directories = [parent(path) for path in reached]
                for runner in [*reached.values(), *modules]:
                    bases = [parent(runner.path)] + (directories if runner.module else [])
                    for path, candidate in lists.items():
                        if path not in reached and any(
                            _may_run(runner.compiled, base, path, package) for base in bases
                        ):
                            reached[path] = candidate
                            grown = True
            self._reached[package] = (*reached.values(), *others)
        return self._reached[package]


@dataclass(frozen=True)
class _Naming:
    """What the patterns and words of one build file, read from ``base``, may name: as
    sets a path is looked up in, not words each path is compared with (a build file's
    words are asked about every C++ source of its package)."""

    patterns: tuple[str, ...]  # as written
    base: str
    words: frozenset[str]  # joined with ``base``
    word_names: frozenset[str]  # their last parts

    def names(self, path: str, inside: str) -> bool:
        """Whether a pattern or word may name ``path`` (``inside``: the same, relative to
        its package's directory). A word names a file by its path, a directory above
        it, its name or its stem (a macro of another package may make
        ``src/talker.cpp`` of ``talker``)."""
        if self.words:
            name = posixpath.basename(path)
            if name in self.word_names or name.rpartition(".")[0] in self.word_names:
                return True
            directory = path
            while "/" in directory:  # the word is the path, or a directory above it
                if directory in self.words:
                    return True
                directory = directory.rpartition("/")[0]
            if directory in self.words:
                return True
        for pattern in self.patterns:
            if pattern.startswith("*"):  # an unknown start: any directory of the package
                if fnmatchcase(inside, pattern) or fnmatchcase(path, pattern):
                    return True
            elif fnmatchcase(path, join(self.base, pattern)):
                return True
        return False


@lru_cache(maxsize=4096)
def _naming(compiled: CompiledSources, base: str) -> _Naming:
    words = [join(base, relative) for relative in compiled.words]
    return _Naming(
        compiled.patterns,
        base,
        frozenset(words),
        frozenset(posixpath.basename(word) for word in words),
    )


@dataclass(frozen=True)
class _Opening:
    """What one build file, read from one directory, leaves open: the sources it may
    compile besides those its targets name."""

    anything: bool  # an ``include`` of a build file the run does not hold: it may compile any
    # ``add_subdirectory`` directories whose CMakeLists.txt the run does not hold, each + "/"
    unknown_directories: tuple[str, ...]
    naming: _Naming

    @classmethod
    def of(cls, compiled: CompiledSources, base: str, build_files: set[str]) -> _Opening:
        unknown = tuple(
            below + "/"
            for directory in compiled.subdirectories
            if join(below := join(base, directory), _CMAKE_LISTS) not in build_files
        )
        return cls(
            any(join(base, included) not in build_files for included in compiled.includes),
            unknown,
            _naming(compiled, base),
        )

    def may_be(self, path: str, inside: str) -> bool:
        """Whether it may compile ``path`` (``inside``: the same, relative to its
        package's directory): the directories and files it runs that the run does not
        hold, then its patterns and words."""
        if self.anything or path.startswith(self.unknown_directories):
            return True
        return self.naming.names(path, inside)


def _may_run(compiled: CompiledSources, base: str, lists: str, package: str) -> bool:
    """Whether one build file, read from ``base``, may run the ``CMakeLists.txt`` at
    display path ``lists`` of ``package``: it adds its directory, includes it, or leaves
    open what may."""
    directory = parent(lists)
    inside = lists[len(package) :].lstrip("/") if package else lists
    return (
        any(join(base, subdirectory) == directory for subdirectory in compiled.subdirectories)
        or any(join(base, included) == lists for included in compiled.includes)
        or _naming(compiled, base).names(lists, inside)
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

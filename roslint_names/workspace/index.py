"""Where things are: packages by name, the package of a file, executables' source files.

Paths here are the display paths of the run ('/'-separated strings as reports show them),
so the index needs nothing but the facts and the list of package manifests.
"""

from __future__ import annotations

import copy
import posixpath
from bisect import bisect_left
from collections import Counter
from collections.abc import Callable, Collection, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass

from roslint_names.model import ExecutableKind, FileFacts, Generation, Language
from roslint_names.workspace.interfaces import WELL_KNOWN, ServiceDefinition

CODE_LANGUAGES = frozenset({Language.CPP, Language.PYTHON})


@dataclass(frozen=True)
class Package:
    name: str
    directory: str  # display path of the directory holding package.xml; "" for "."
    depends: frozenset[str] = frozenset()  # package names its package.xml depends on
    # (name, definition) of each of its ROS 1 ``.srv`` files (``interfaces``), by name
    services: tuple[tuple[str, ServiceDefinition], ...] = ()
    # What its package.xml builds for (``generation``); None for both, or unknown.
    generation: Generation | None = None


def _stem(path: str) -> str:
    """A path's base name less its last suffix ("" for a name without one)."""
    return posixpath.basename(path).rpartition(".")[0]


def parent(path: str) -> str:
    """``posixpath.dirname`` of a display path, without its checks of the argument's
    type: the graph asks it of every file of the workspace, some several times (125,000
    calls building the graph at 8 copies of the benchmark's workspace)."""
    cut = path.rfind("/") + 1
    head = path[:cut]
    if head and head != "/" * len(head):
        head = head.rstrip("/")
    return head


def join(directory: str, relative: str) -> str:
    """``directory/relative`` normalised; '..' is kept only above the run's root."""
    joined = posixpath.normpath(posixpath.join(directory, relative) if directory else relative)
    return "" if joined == "." else joined


@dataclass(frozen=True)
class Executables:
    """What the build files make: each program's sources by (package, executable), each
    component plugin's by class name (``WorkspaceIndex.sources_of``)."""

    programs: tuple[tuple[tuple[str, str], tuple[str, ...]], ...]
    plugins: tuple[tuple[str, tuple[str, ...]], ...]


def named_once(packages: Iterable[Package]) -> dict[str, Package]:
    """The packages by name, but for a name two directories claim (a ROS 1 and a ROS 2
    copy): no package we can find things in, as colcon and catkin refuse such a
    workspace, and which copy a launch file means is unknown."""
    listed = list(packages)
    claims = Counter(package.name for package in listed)
    return {package.name: package for package in listed if claims[package.name] == 1}


def companions(packages: Mapping[str, Package]) -> dict[str, frozenset[str]]:
    """package -> the workspace packages (``named_once``) it is meant to run with:
    itself, those it depends on, those depending on it, and those sharing a dependent
    with it (the packages a metapackage or a bringup package gathers)."""
    known = set(packages)
    found: dict[str, set[str]] = {name: {name} for name in known}
    for name, package in packages.items():
        gathered = (package.depends & known) | {name}
        for one in gathered:
            found[one] |= gathered
    return {name: frozenset(together) for name, together in found.items()}


class PackageFiles:
    """Which package holds each file of a run (the package of the nearest directory above
    it holding a manifest), and the files of each package name."""

    def __init__(self, paths: Collection[str], packages: Sequence[Package]) -> None:
        self._paths = paths
        self._package_by_directory = {p.directory: p for p in packages}
        self._package_of: dict[str, Package | None] = {}
        self._package_of_path: dict[str, Package | None] = {}
        self._files_by_package: dict[str, list[str]] = {}  # each made when first asked
        # A package's files by their base name, and by that name less its suffix (made
        # when first asked): where a launch file's executable is no build file's target,
        # its package's files were scanned for each node started of it.
        self._by_name: dict[str, dict[str, list[str]]] = {}
        self._by_stem: dict[str, dict[str, list[str]]] = {}
        self._sorted_paths: list[str] | None = None
        self._directories: dict[str, list[str]] = {}  # name -> directories of that name
        for package in packages:
            self._directories.setdefault(package.name, []).append(package.directory)

    def package_of(self, path: str) -> Package | None:
        # Memoised by path too: the graph asks about the same files hundreds of thousands
        # of times (a node's code, followed through its includes).
        try:
            return self._package_of_path[path]
        except KeyError:
            package = self._package_of_path[path] = self._package_of_directory(parent(path))
            return package

    def enclosing(self, path: str) -> list[Package]:
        """Every package whose directory holds ``path``, the nearest first."""
        found: list[Package] = []
        package = self.package_of(path)
        while package is not None:
            found.append(package)
            up = parent(package.directory)
            if not package.directory or up == package.directory:
                break
            package = self._package_of_directory(up)
        return found

    def _package_of_directory(self, directory: str) -> Package | None:
        # Memoised: every file of the workspace is asked about, several times each.
        if directory in self._package_of:
            return self._package_of[directory]
        package = self._package_by_directory.get(directory)
        if package is None and directory and directory not in ("/", "."):
            up = parent(directory)
            package = None if up == directory else self._package_of_directory(up)
        self._package_of[directory] = package
        return package

    def files_of(self, package: str) -> list[str]:
        """The files, sorted, of every package of that name. Only the paths below its
        directories are asked about: a patch asks for a few packages of 80,000 files
        (``workspace.parameter_patch``), and asking about every file costs 0.2 s."""
        found = self._files_by_package.get(package)
        if found is None:
            held: set[str] = set()
            for directory in self._directories.get(package, []):
                for path in self.below(directory):
                    owner = self.package_of(path)
                    if owner is not None and owner.name == package:
                        held.add(path)
            found = self._files_by_package[package] = sorted(held)
        return found

    def named(self, package: str, name: str) -> list[str]:
        """The package's files (``files_of``) whose base name is ``name``, sorted."""
        return self._grouped(self._by_name, package, posixpath.basename).get(name, [])

    def stemmed(self, package: str, stem: str) -> list[str]:
        """The package's files whose base name less its last suffix is ``stem``, sorted."""
        return self._grouped(self._by_stem, package, _stem).get(stem, [])

    def _grouped(
        self,
        groups: dict[str, dict[str, list[str]]],
        package: str,
        key: Callable[[str], str],
    ) -> dict[str, list[str]]:
        """The package's files by ``key`` of their path, made once into ``groups``."""
        found = groups.get(package)
        if found is None:
            found = groups[package] = {}
            for path in self.files_of(package):
                found.setdefault(key(path), []).append(path)
        return found

    def below(self, directory: str) -> Iterator[str]:
        """The paths below ``directory`` ("" for the run's root), sorted, those of the
        packages inside it too."""
        if self._sorted_paths is None:
            self._sorted_paths = sorted(self._paths)
        paths = self._sorted_paths
        prefix = directory.rstrip("/") + "/" if directory else ""
        # By position, not over a slice: a slice copies the rest of the list.
        at = bisect_left(paths, prefix)
        while at < len(paths) and paths[at].startswith(prefix):
            yield paths[at]
            at += 1


class WorkspaceIndex(PackageFiles):
    """Packages, files and executables of one run."""

    def __init__(self, facts: Iterable[FileFacts], packages: Sequence[Package]) -> None:
        self._placed({f.path: f for f in facts}, packages)
        self._programs: dict[tuple[str, str], list[str]] = {}
        self._plugins: dict[str, list[str]] = {}
        self._index_executables()

    def _placed(self, facts: Mapping[str, FileFacts], packages: Sequence[Package]) -> None:
        self.facts: Mapping[str, FileFacts] = facts
        self.packages: dict[str, Package] = named_once(packages)
        PackageFiles.__init__(self, facts.keys(), packages)

    @classmethod
    def restored(
        cls,
        facts: Mapping[str, FileFacts],
        packages: Sequence[Package],
        executables: Executables,
    ) -> WorkspaceIndex:
        """The index of a build whose executables (``executables``) are known, over
        ``facts`` (every file of the run, each looked at only when asked for: a launch
        patch reads a few files of 77,000, ``workspace.launch_patch``)."""
        index = cls.__new__(cls)
        index._placed(facts, packages)
        index._programs = {key: list(sources) for key, sources in executables.programs}
        index._plugins = {name: list(sources) for name, sources in executables.plugins}
        return index

    def executables(self) -> Executables:
        """The programs and plugins the build files make, as ``restored`` takes them."""
        return Executables(
            tuple((key, tuple(sources)) for key, sources in sorted(self._programs.items())),
            tuple((name, tuple(sources)) for name, sources in sorted(self._plugins.items())),
        )

    def with_facts(self, facts: Mapping[str, FileFacts]) -> WorkspaceIndex:
        """This index over new facts of the same files, whose executables and languages
        are unchanged (``memory.GraphMemory``): where things are stays as it was."""
        updated = copy.copy(self)
        updated.facts = facts
        return updated

    # -- packages -----------------------------------------------------------------------

    def companions(self) -> dict[str, frozenset[str]]:
        """``companions`` of the index's packages."""
        return companions(self.packages)

    def service_definitions(self) -> dict[str, ServiceDefinition]:
        """``package/Name`` -> definition of every ROS 1 service type of the workspace's
        packages, and of the well-known ones it does not hold."""
        found = dict(WELL_KNOWN)
        for package in self.packages.values():
            found.update((f"{package.name}/{name}", known) for name, known in package.services)
        return found

    def find_in_package(self, package: str, relative: str) -> str | None:
        """A package file by its path in the package; else by its path in the *installed*
        share directory, which CMake ``install(DIRECTORY ...)`` and setup.py ``data_files``
        often flatten (``launch/a.launch.py`` installed from ``launch/robot/a.launch.py``):
        the package's only file with that name."""
        found = self.packages.get(package)
        if found is None:
            return None
        exact = join(found.directory, relative)
        if exact in self.facts:
            return exact
        candidates = self.named(package, posixpath.basename(relative))
        return candidates[0] if len(candidates) == 1 else None

    # -- executables --------------------------------------------------------------------

    def sources_of(self, package: str | None, executable: str | None) -> tuple[str, ...]:
        """The code a launch ``<node pkg type|exec>`` or ``plugin`` runs, as far as the
        workspace holds it: the build files' targets, else (rosrun's rule) the package's
        scripts of that name, else its one source file of that stem."""
        if executable is None:
            return ()
        if "::" in executable:
            return tuple(self._plugins.get(executable, ()))
        if package not in self.packages:
            return ()
        built = self._programs.get((package, executable))
        if built:
            return tuple(built)
        # Sorted, as the package's files are: the name's and the name with ``.py``'s.
        named = [
            path
            for path in sorted(
                {*self.named(package, executable), *self.named(package, f"{executable}.py")}
            )
            if self.facts[path].language in CODE_LANGUAGES
        ]
        if named:
            return tuple(named)
        # A target the build files hide (made by a function of a .cmake module the
        # workspace does not hold, or named by a variable the file does not set): the
        # package's one code file named after it, if any.
        stems = [
            path
            for path in self.stemmed(package, executable)
            if self.facts[path].language in CODE_LANGUAGES
        ]
        return tuple(stems) if len(stems) == 1 else ()

    def built_sources(self) -> dict[tuple[str, str], list[str]]:
        """(package, executable) -> sources, for grouping code no launch file starts."""
        return dict(self._programs)

    def plugin_sources(self) -> set[str]:
        """The sources of every component plugin the build files register."""
        return {path for sources in self._plugins.values() for path in sources}

    def _index_executables(self) -> None:
        self._programs, self._plugins = self.made_by(
            sorted(self.facts.items()), self.facts.__contains__
        )

    def made_by(
        self, files: Iterable[tuple[str, FileFacts]], exists: Callable[[str], bool]
    ) -> tuple[dict[tuple[str, str], list[str]], dict[str, list[str]]]:
        """The programs and plugins ``files`` make (display path and facts, in path
        order), of their sources those that ``exists`` says are files of the run."""
        programs: dict[tuple[str, str], list[str]] = {}
        plugins: dict[str, list[str]] = {}
        for path, facts in files:
            if not facts.executables:
                continue
            package = self.package_of(path)
            directory = parent(path)
            for executable in facts.executables:
                sources = _existing(directory, executable.sources, exists)
                if not sources:
                    continue
                if executable.kind is ExecutableKind.PLUGIN:
                    plugins.setdefault(executable.name, []).extend(sources)
                elif package is not None:
                    # Two packages of one name (ros/geometry2's and ros2/geometry2's
                    # tf2_ros both build a buffer_server) are two programs, not one: a
                    # copy is keyed by its directory, which no launch file names.
                    owner = package.name if package.name in self.packages else package.directory
                    key = (owner, executable.name)
                    programs.setdefault(key, []).extend(sources)
        return programs, plugins


def _existing(directory: str, relatives: Iterable[str], exists: Callable[[str], bool]) -> list[str]:
    """Sources that are files of the run (``exists``); a console_scripts module ``a/b.py``
    may be a package, ``a/b/__init__.py``."""
    found: list[str] = []
    for relative in relatives:
        path = join(directory, relative)
        if exists(path):
            found.append(path)
        elif path.endswith(".py"):
            package_init = path[: -len(".py")] + "/__init__.py"
            if exists(package_init):
                found.append(package_init)
    return found

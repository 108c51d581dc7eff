"""The programs of some packages made again, for a patch of the last graph (issue 30).

A node added to a package is a source file added and an executable that compiles it
added to the package's build file (``add_executable(probe src/probe.cpp)``, a
``console_scripts`` entry); a source may be added to a target, a file added that a
launch file finds by its name (rosrun's rule, ``WorkspaceIndex.sources_of``), code may
start or stop declaring endpoints (code no launch file starts is a program of its own
where it declares some: ``launch_parts.Programs``). What such
edits change of what a build takes from every file is the package's own: which
programs its build files make of which sources (``WorkspaceIndex.executables``, and the
plugin names they register), which of its C++ sources no build compiles
(``workspace.built``), and what the code no launch file starts is made of
(``launch_parts.Programs``). Building the whole graph again for it loads every file's
facts and walks every tree (7.8 to 9.7 s at 8 copies of the benchmark's workspace).

``programs_anew`` makes those three as a build of the files as they are makes them,
from the build's and the package's files then and now; the trees that start a node of
such a package or plugin (``LaunchParts``' ``TreePart.started``, whatever code it found)
are then walked again (``launch_patch``), and the parameters of the code spanning the
package gathered again (``parameter_patch``). It is None (the caller builds) where the
edit may reach past the package: a build file naming a source outside its package
otherwise than at the build, a file added or removed that a build file of a package
not given names (``GraphPatch`` gives such packages too), a
program or plugin of that name made by another package's build files too, a C++ file
of the package that was there at the build built or not otherwise now (the parameter
tables leave out code no build compiles).
``tests/test_program_patch.py`` compares patched graphs and parts with built ones.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TypeVar

from roslint_names.model import FileFacts, Language
from roslint_names.moves import moved_spans
from roslint_names.workspace.built import BuiltSources
from roslint_names.workspace.index import (
    Executables,
    Package,
    WorkspaceIndex,
    join,
    parent,
)
from roslint_names.workspace.launch_parts import Programs, TreePart
from roslint_names.workspace.patch import same_places

BUILD_LANGUAGES = frozenset({Language.CMAKE, Language.SETUP_PY, Language.SETUP_CFG})


def program_edit(before: FileFacts, now: FileFacts) -> bool:
    """Whether an edit of a build file changed what it builds (its executables, the
    sources it compiles) and nothing else."""
    if before.language not in BUILD_LANGUAGES or now.language is not before.language:
        return False
    if moved_spans(before, now) is not None:
        return False  # the same, perhaps elsewhere: ``patch.build_moves``
    return same_places(_without_programs(before), _without_programs(now))


def _without_programs(facts: FileFacts) -> FileFacts:
    return replace(facts, executables=(), compiled=None)


_Made = tuple[dict[tuple[str, str], list[str]], dict[str, list[str]]]


@dataclass(frozen=True)
class ProgramsAnew:
    """What a build of the files as they are takes from the build files and code of
    some packages, the rest as the last build took it."""

    executables: Executables
    unbuilt: frozenset[str]  # the workspace's C++ sources no build compiles
    programs: Programs
    packages: frozenset[str]  # the names of the packages whose programs were made again
    plugins: frozenset[str]  # the plugin names whose sources changed
    # The files that are a program's or a plugin's source now and were not, or were and
    # are not (``ParameterTables``' ``programs``).
    sources: frozenset[str]
    # The packages' C++ sources that only rostest starts now and did not, or did and
    # does not (``workspace.built``: the node name they give is spared then).
    rostest_anew: frozenset[str] = frozenset()

    def starts(self, part: TreePart) -> bool:
        """Whether a tree starts a node of one of those packages or plugins: whatever
        code it found at the build, it may find other code now."""
        return any(
            package in self.packages or executable in self.plugins
            for package, executable in part.started
        )

    def program_sources(self) -> set[str]:
        """The sources of every program and plugin (``ParameterTables.of``'s)."""
        found = {path for _, sources in self.executables.programs for path in sources}
        found.update(path for _, sources in self.executables.plugins for path in sources)
        return found


def programs_anew(
    built: Programs,
    executables: Executables,
    unbuilt: frozenset[str],
    *,
    index: WorkspaceIndex,
    packages: Sequence[Package],
    language_of: Callable[[str], Language],
    then: Mapping[str, FileFacts],
    added: Collection[str],
    removed: Collection[str] = (),
    flipped: Collection[str] = (),
    compiled: BuiltSources,
    compiled_then: BuiltSources | None = None,
    is_test: Callable[[str], bool],
    named_elsewhere: Callable[[str, Collection[str]], bool],
) -> ProgramsAnew | None:
    """The executables, unbuilt sources and programs a build would make of the files as
    they are (``index``: over every file of the run now, its facts loaded when asked),
    from the last build's (``built``, ``executables``, ``unbuilt``) with those of the
    ``packages`` made again: their build files as they were at the build (``then``: the
    edited ones, by display path; the others as they are), the code files the build had
    not (``added``), those it had that the run has not (``removed``) and those that
    started or stopped declaring endpoints since (``flipped``), what the run's
    build files compile now (``compiled``) and at the last run (``compiled_then``; None
    where no build file changed) and which
    files are test code (``is_test``); None where that may reach past those packages
    (module docstring): ``named_elsewhere`` says whether a build file other than those
    given names a file as a source (another package's program would change)."""
    files = {package.directory: _files_of(index, package) for package in packages}
    build_files = sorted(
        path for held in files.values() for path in held if language_of(path) in BUILD_LANGUAGES
    )
    facts = index.facts
    if any(_names_elsewhere(then[path], facts[path], path, index) for path in then):
        return None
    if any(named_elsewhere(path, build_files) for path in (*added, *removed)):
        return None
    old = index.made_by(
        ((path, then.get(path) or facts[path]) for path in build_files),
        lambda path: (path in facts and path not in added) or path in removed,
    )
    new = index.made_by(((path, facts[path]) for path in build_files), facts.__contains__)
    programs = _merged(dict(executables.programs), old[0], new[0])
    plugins = _merged(dict(executables.plugins), old[1], new[1])
    if programs is None or plugins is None:
        return None
    found = Executables(
        tuple((key, tuple(sources)) for key, sources in sorted(programs.items())),
        tuple((name, tuple(sources)) for name, sources in sorted(plugins.items())),
    )
    code = [
        (path, package)
        for package in packages
        for path in files[package.directory]
        if language_of(path) is Language.CPP
    ]
    unbuilt_now = {path for path, package in code if compiled.unbuilt(path, package.directory)}
    if any((path in unbuilt) != (path in unbuilt_now) for path, _ in code if path not in added):
        return None
    own = {path for path, _ in code}
    rostest_anew = (
        frozenset()
        if compiled_then is None
        else frozenset(
            path
            for path, package in code
            if path not in added
            and compiled.started_by_rostest(path, package.directory)
            != compiled_then.started_by_rostest(path, package.directory)
        )
    )
    return ProgramsAnew(
        found,
        frozenset((unbuilt - own - set(removed)) | unbuilt_now),
        built.anew(
            executables=found,
            facts=facts,
            added=added,
            removed=removed,
            flipped=flipped,
            is_test=is_test,
            language_of=language_of,
        ),
        frozenset(package.name for package in packages),
        frozenset(
            name for name in old[1].keys() | new[1].keys() if old[1].get(name) != new[1].get(name)
        ),
        frozenset(_sources(old) ^ _sources(new)),
        rostest_anew,
    )


def _files_of(index: WorkspaceIndex, package: Package) -> list[str]:
    """The files of ``package`` (not of a package inside its directory), sorted."""
    return [path for path in index.below(package.directory) if index.package_of(path) == package]


def _names_elsewhere(then: FileFacts, now: FileFacts, path: str, index: WorkspaceIndex) -> bool:
    """Whether a build file's targets name a source outside its package otherwise now
    than at the build: whether that source is built is another package's question."""
    package = index.package_of(path)
    if package is None:
        return True
    directory = parent(path)
    inside = package.directory + "/" if package.directory else ""
    changed = _named(then, directory) ^ _named(now, directory)
    return any(not named.startswith(inside) for named in changed)


def _named(facts: FileFacts, directory: str) -> set[str]:
    """The sources a build file's targets name, by display path."""
    compiled = facts.compiled
    if compiled is None:
        return set()
    return {join(directory, relative) for relative in (*compiled.paths, *compiled.rostest)}


_Key = TypeVar("_Key")


def _merged(
    built: Mapping[_Key, Sequence[str]],
    old: Mapping[_Key, list[str]],
    new: Mapping[_Key, list[str]],
) -> dict[_Key, Sequence[str]] | None:
    """The build's programs (or plugins) with the packages' own as they make them now
    (``new``) in place of those they made at the build (``old``); None where another
    package's build files make one of those keys too."""
    merged = dict(built)
    for key, sources in old.items():
        if tuple(merged.pop(key, ())) != tuple(sources):
            return None
    for key, sources in new.items():
        if key in merged:
            return None
        merged[key] = sources
    return merged


def _sources(made: _Made) -> set[str]:
    programs, plugins = made
    return {path for sources in (*programs.values(), *plugins.values()) for path in sources}

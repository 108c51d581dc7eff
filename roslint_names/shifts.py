"""A run over the files of an earlier run, some added or removed: that run's replay and
kept graph, their files renumbered.

A file added or removed (a header, a Python module, a launch file) changes the run's
file list, so its place key (``RunInputs.place_key``): no replay or graph is kept under
it, and every such run built the graph (7.7 s at 81,000 files, issue 30). Yet most
files' facts are empty for the graph: code with no name, no class, no include the build
reads. Such a file changes nothing the graph or the run's end is made of, but where it
is, and that matters in a few known ways only (``WorkspaceIndex``):

- a build file's executable may name it as a source (``_existing`` keeps only sources
  the run holds);
- a launch file's node runs it by its name or stem where no build file makes that
  executable, and an include or a parameter file is found by its name where the path
  does not hold it (``sources_of``, ``find_in_package``).

``Lookups`` keeps both (``RunWide``'s, gathered since the last build: one that no longer
holds costs a build, never a result). A file that says nothing and is found by none of
them (``Lookups.adds_nothing``) can come or go without a graph of its own: the replay of
the last run of the same shape (its place but for the file list: ``Base``, by
``RunInputs.shape_key``) stands, its files renumbered (``Renumbering``): an added file
is an edited one whose facts before were nothing (``run_inputs.ADDED``), a removed one
is gone with its findings. Other files added or removed are the graph patch's to judge
(``graph_patch._came_or_went``: a launch file nothing includes is a tree of its own, a
parameter file has the trees naming a file of its name walked again). A graph kept by a
build is found through the same renumbering (``GraphMove``: the run that renumbered
keeps where the graph is and how its files map), and a patch over it asks the same of
every file added since the build, and of every file the build had and the run has not.

A run's shape leaves out what its packages depend on too (``RunInputs.shape_key``): a
dependency added to a manifest changes which packages run together and which service
types a file can use, nothing else. The base keeps what its packages depended on
(``Base.depends``); where they depended on others, its replay stands only through a
patch of the graph with the packages as they are now (``graph_patch.GraphPatch``).
"""

from __future__ import annotations

import hashlib
import posixpath
from array import array
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field

from .model import FileFacts, InPackage, Language, replaced
from .workspace.index import join

_SAYING_NOTHING = (Language.CPP, Language.PYTHON)


def says_nothing(facts: FileFacts) -> bool:
    """Whether a file's facts give the graph and the run's end nothing: code whose facts
    are those of an empty file but for its parse errors and suppression marker (which
    only its own checks read)."""
    if facts.language not in _SAYING_NOTHING:
        return False
    bare = replaced(facts, parse_errors=(), suppression_marker=False)
    return bare == FileFacts(facts.path, facts.language, facts.generation)


def digest(display: str) -> int:
    """A display path as ``RunWide`` keeps it: 8 bytes, not 70 characters (every run after
    an edit loads and keeps 7,000 of them at 8 copies). Two paths of one digest make a
    file found by name that is not: a build, never a wrong result."""
    data = display.encode("utf-8", errors="surrogatepass")
    return int.from_bytes(hashlib.blake2b(data, digest_size=8).digest(), "little")


SEVERAL = -1  # no digest: a source more than one build file names (``Lookups.named``)

PARAMETER_NAMES = (".yaml", ".yml")  # the names ``RunWide.naming`` keeps who looks up


@dataclass
class Lookups:
    """Where a run finds files by name (``RunWide``'s): the names launch files run,
    include, load and hand on, those of parameter files with who looks them up (digests
    of their display paths), and the sources build files' executables name (digests)."""

    names: set[str] = field(default_factory=set)
    naming: dict[str, set[int]] = field(default_factory=dict)
    # source -> the build file naming it (digests), ``SEVERAL`` where more than one does
    named: dict[int, int] = field(default_factory=dict)

    def add(self, facts: FileFacts) -> None:
        """What a file's facts look up: a launch file's executables and the names of the
        files it includes, loads and hands on (an argument's value may be a file the
        included one loads); a build file's executables' sources."""
        paths: list[str | None] = [load.path for load in facts.parameter_loads]
        for node in facts.launch_nodes:
            if node.executable:
                self.names.add(node.executable)
            paths += [load.path for load in node.parameter_files]
        for include in facts.includes:
            paths.append(include.path)
            for _, value in include.arguments:
                paths.append(value.path if isinstance(value, InPackage) else value)
        for path in paths:
            name = posixpath.basename(path) if path else ""
            if name:
                self.names.add(name)
                if name.endswith(PARAMETER_NAMES):
                    self.naming.setdefault(name, set()).add(digest(facts.path))
        directory = posixpath.dirname(facts.path)
        builder = digest(facts.path)
        for executable in facts.executables:
            for source in executable.sources:
                self._name(digest(join(directory, source)), builder)

    def _name(self, source: int, builder: int) -> None:
        """One more build file naming a source: one int each, not a set (7,000 sources
        at 8 copies of the benchmark's workspace, kept by every run's replay)."""
        known = self.named.setdefault(source, builder)
        if known != builder:
            self.named[source] = SEVERAL

    def update(
        self,
        names: Iterable[str],
        naming: Mapping[str, Iterable[int]],
        named: Mapping[int, int],
    ) -> None:
        """What an earlier run found (``RunWide``'s), with what this one finds."""
        self.names.update(names)
        for name, by in naming.items():
            self.naming.setdefault(name, set()).update(by)
        for source, builder in named.items():
            self._name(source, builder)

    def finds(self, display: str) -> bool:
        """Whether a launch file finds the file by its name or stem, or a build file's
        executable names it as a source."""
        name = posixpath.basename(display)
        if name in self.names or name.rpartition(".")[0] in self.names:
            return True
        return bool(self.builders(display))

    def builders(self, display: str) -> set[int]:
        """The build files (digests of their display paths) whose executables name the
        file as a source; ``SEVERAL`` among them where more than one names it."""
        sources = [digest(display)]
        # A console_scripts module ``a/b.py`` may be the package ``a/b/__init__.py``.
        if posixpath.basename(display) == "__init__.py":
            sources.append(digest(f"{posixpath.dirname(display)}.py"))
        return {self.named[source] for source in sources if source in self.named}

    def adds_nothing(self, facts: FileFacts) -> bool:
        """Whether a file may come or go without a graph of its own: it says nothing and
        is found by no name."""
        return says_nothing(facts) and not self.finds(facts.path)

    def naming_of(self, name: str, displays: Iterable[str]) -> set[str] | None:
        """Those of ``displays`` that look up a parameter file of this name (None for a
        name whose lookers are not kept)."""
        if not name.endswith(PARAMETER_NAMES):
            return None
        by = self.naming.get(name, set())
        return {display for display in displays if digest(display) in by} if by else set()


@dataclass(frozen=True)
class Renumbering:
    """How the files of a run map to those of an earlier run over nearly the same list:
    per file of the run, its index in the earlier run (-1: added); the earlier run's
    file and reported counts; and the earlier run's files the run has not, (index,
    display path)."""

    previous: tuple[int, ...]
    before: int
    reported_before: int
    removed: tuple[tuple[int, str], ...]

    def then_of(self, reported: int) -> dict[int, int]:
        """Earlier reported index -> reported index now, for the files of both."""
        return {
            then: now
            for now, then in enumerate(self.previous[:reported])
            if 0 <= then < self.reported_before
        }

    def after(self, earlier: Renumbering, displays: Sequence[str]) -> Renumbering:
        """This renumbering of the files ``earlier`` renumbered: from its earlier run to
        this one's run, whose files are ``displays``. A file ``earlier`` removed that
        this run has again is the earlier run's file (its facts then and now compared as
        any edited file's)."""
        removed = dict(earlier.removed)
        again = {display: first for first, display in earlier.removed}
        previous = []
        for index, then in enumerate(self.previous):
            if then >= 0:
                previous.append(earlier.previous[then])
            elif (first := again.get(displays[index])) is not None:
                previous.append(first)
                del removed[first]
            else:
                previous.append(-1)
        for then, display in self.removed:
            first = earlier.previous[then]
            if first >= 0:
                removed[first] = display
        return Renumbering(
            tuple(previous),
            earlier.before,
            earlier.reported_before,
            tuple(sorted(removed.items())),
        )

    def stored(self) -> tuple[object, ...]:
        return (
            array("i", self.previous).tobytes(),
            self.before,
            self.reported_before,
            self.removed,
        )


MOST_CHANGED = 64  # files added and removed in one renumbering: past it, a build pays


def renumbering(
    before: Sequence[str], reported_before: int, now: Sequence[str]
) -> Renumbering | None:
    """How the files ``now`` (display paths, in the run's order) map to ``before``; None
    where a path is twice in either, or more than ``MOST_CHANGED`` files differ."""
    at = {display: index for index, display in enumerate(before)}
    if len(at) != len(before) or len(set(now)) != len(now):
        return None
    previous = tuple(at.get(display, -1) for display in now)
    kept = {index for index in previous if index >= 0}
    removed = tuple((index, display) for index, display in enumerate(before) if index not in kept)
    if previous.count(-1) + len(removed) > MOST_CHANGED:
        return None
    return Renumbering(previous, len(before), reported_before, removed)


def loaded_renumbering(value: object) -> Renumbering | None:
    if not isinstance(value, tuple) or len(value) != 4:
        return None
    previous_bytes, before, reported_before, removed = value
    if not (
        isinstance(previous_bytes, bytes)
        and len(previous_bytes) % array("i").itemsize == 0
        and isinstance(before, int)
        and isinstance(reported_before, int)
        and 0 <= reported_before <= before
        and isinstance(removed, tuple)
    ):
        return None
    previous = tuple(array("i", previous_bytes))
    if not all(-1 <= index < before for index in previous):
        return None
    try:
        gone = tuple((int(index), str(display)) for index, display in removed)
    except (TypeError, ValueError):
        return None
    if not all(0 <= index < before for index, _ in gone):
        return None
    return Renumbering(previous, before, reported_before, gone)


_BASE_FORMAT = "base 3"
_LIST_FORMAT = "file list 1"


@dataclass(frozen=True)
class Base:
    """The last run of a shape (``RunInputs.shape_key``) that kept a replay: where (its
    replay's key), and its files (display paths) with how many it reported. Kept as a
    pointer, rewritten by every such run (``pointer``), and the files, written once per
    replay key (``listed``: 81,000 paths)."""

    replay_at: str
    displays: tuple[str, ...]
    reported: int
    # What its packages depended on (``PackageGenerations.depends_digest``): a run of
    # its shape may depend on others (``RunInputs.shape_key``), then its replay stands
    # only through a patch of the graph (``graph_patch.GraphPatch``).
    depends: str = ""

    def pointer(self) -> tuple[object, ...]:
        return pointer(self.replay_at, self.reported, len(self.displays), self.depends)

    def listed(self) -> tuple[object, ...]:
        return (_LIST_FORMAT, self.displays)


def pointer(replay_at: str, reported: int, files: int, depends: str) -> tuple[object, ...]:
    """``Base.pointer`` of a run's ``files``, without its display paths: what every run
    that keeps a replay compares with the kept one."""
    return (_BASE_FORMAT, replay_at, reported, files, depends)


def loaded_base(pointer: object, listed: Callable[[str], object]) -> Base | None:
    """The base a stored ``pointer`` gives, its files read by ``listed`` (by the
    pointer's replay key); None for anything else."""
    if not isinstance(pointer, tuple) or len(pointer) != 5 or pointer[0] != _BASE_FORMAT:
        return None
    _, replay_at, reported, count, depends = pointer
    if not (isinstance(replay_at, str) and isinstance(reported, int) and isinstance(depends, str)):
        return None
    found = listed(replay_at)
    if not isinstance(found, tuple) or len(found) != 2 or found[0] != _LIST_FORMAT:
        return None
    displays = found[1]
    if not (
        isinstance(displays, tuple)
        and len(displays) == count
        and 0 <= reported <= count
        and all(isinstance(display, str) for display in displays)
    ):
        return None
    return Base(replay_at, displays, reported, depends)


_MOVE_FORMAT = "graph move 1"


@dataclass(frozen=True)
class GraphMove:
    """Where the graph a run patches is kept (a build's replay key), and how the run's
    files map to that build's: kept by a run that renumbered, under its own key."""

    graph_at: str
    renumbering: Renumbering

    def stored(self) -> tuple[object, ...]:
        return (_MOVE_FORMAT, self.graph_at, self.renumbering.stored())


def loaded_move(value: object) -> GraphMove | None:
    if not isinstance(value, tuple) or len(value) != 3 or value[0] != _MOVE_FORMAT:
        return None
    _, graph_at, stored = value
    found = loaded_renumbering(stored)
    if not isinstance(graph_at, str) or found is None:
        return None
    return GraphMove(graph_at, found)

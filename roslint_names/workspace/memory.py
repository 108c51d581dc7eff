"""What one graph build keeps for the next in the same process.

The language server builds the graph again each time typing pauses (``session``); an
edit changes the facts of one file among tens of thousands, and building everything
again cost 6 s on a 77,000-file workspace. A ``GraphMemory`` handed to every build of one
workspace keeps each piece of the last build with what it was made from, and the next
build takes a piece back only where none of that changed: the result is the graph a
build without memory makes (``tests/test_graph_memory.py`` compares them after every
edit of a sequence that adds, renames and deletes launch files, nodes and remaps).

What changed is decided per file: facts that are not the same object and not equal
(``begin``). A file added or removed, or a package's manifest changed, changes where
things are (the package of a file, which file a launch file includes, which sources an
executable has): nothing is taken back then. Otherwise each piece says what it was
made from:

- a piece made from one field of every file's facts (the index's executables, the build
  files' compiled sources), or from what a function makes of each file's facts (what
  its code declares as parameters), is taken back when no changed file's field or view
  differs (``same``); the lookups of classes the parameter sets follow take the changed
  files' classes in, and the pieces of the files deriving from a class of a changed
  name are forgotten (``build``, ``ParameterTables.with_classes``);
- a piece made from some files (a node instance from its launch file, its code and its
  parameter files; a launch tree from the files it visits; a node's parameters from its
  code, the headers and base classes followed, its packages' code) is taken back when
  none of them changed: each is indexed by what it read as it is stored (``_Pieces``),
  and an edit forgets the pieces its files and their packages were read by.

A fresh memory remembers nothing: every build goes through the same code, and a build
without one (the CLI's) is the first build of a fresh memory that keeps nothing for a
next one (``keeps=False``: its pieces record no reads).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

from roslint_names.model import FileFacts
from roslint_names.workspace.index import Package, WorkspaceIndex

T = TypeVar("T")
# What a piece is made from in each file's facts: a field, or what a function makes of them
Field = str | Callable[[FileFacts], object]


@dataclass(frozen=True)
class Reads:
    """The files a piece was made from, and the packages whose every file it read.
    Tuples: a memory holds tens of thousands, and only ever asks whether one changed."""

    paths: tuple[str, ...] = ()
    packages: tuple[str, ...] = ()


NOTHING = Reads()  # what a piece of a memory that keeps nothing says it read


class GraphMemory:
    """The pieces of the last build of one workspace (module docstring).

    ``keeps``: False for a build no other follows (the CLI's): its pieces need not say
    what they read (a node's parameters alone read 40 MB of paths at 8 copies)."""

    def __init__(self, *, keeps: bool = True) -> None:
        self.keeps = keeps
        self._facts: Mapping[str, FileFacts] = {}
        self._packages: tuple[Package, ...] | None = None
        self._pairs: list[tuple[FileFacts, FileFacts]] = []
        self.moved = True  # a file added or removed, or a package changed: nothing is kept
        self.changed: frozenset[str] = frozenset()  # files whose facts differ
        self.changed_packages: frozenset[str] = frozenset()  # the packages holding them
        self._index: WorkspaceIndex | None = None
        self._pieces: dict[str, tuple[tuple[Field, ...], Any]] = {}  # name: (fields, value)
        # Pieces made from some files, by what they are for: value and what it read; and
        # the fields of every file's facts each kind is made from besides.
        self._reads: dict[str, _Pieces] = {}
        self._reads_fields: dict[str, tuple[Field, ...]] = {}
        # Which pieces read each file and each package, so that an edit forgets those
        # without asking the 100,000 pieces of a 77,000-file workspace (0.07 s a build).
        # Entries of pieces since forgotten or made again stay until the index is made
        # anew: each is checked against the piece its key holds now.
        self._readers: dict[str, list[tuple[str, Any]]] = {}
        self._package_readers: dict[str, list[tuple[str, Any]]] = {}
        self._indexed = 0  # entries in the two
        self._indexed_when_made = 0

    def begin(self, facts: Mapping[str, FileFacts], packages: Sequence[Package]) -> WorkspaceIndex:
        """Compare ``facts`` (display path -> facts) with the last build's; the index of
        this build."""
        packages = tuple(packages)
        before = self._facts
        self.moved = (
            self._index is None
            or packages != self._packages
            or len(before) != len(facts)
            or before.keys() != facts.keys()
        )
        if self.moved:
            self._pairs = []
            self.changed = frozenset()
            self._pieces.clear()
            self._reads.clear()
            self._index_reads()
        else:
            self._pairs = [
                (old, new)
                for path, new in facts.items()
                if (old := before[path]) is not new and old != new
            ]
            self.changed = frozenset(new.path for _, new in self._pairs)
        self._facts = dict(facts)
        self._packages = packages
        if self._index is not None and not self.moved and self.same("executables", "language"):
            self._index = self._index.with_facts(self._facts)
        else:
            self._index = WorkspaceIndex(self._facts.values(), packages)
        self.changed_packages = frozenset(
            package.name for path in self.changed if (package := self._index.package_of(path))
        )
        # Forgotten now, not when next asked for: a piece a build does not ask for must
        # not outlive a change to what it was made from.
        for name, (fields, _) in list(self._pieces.items()):
            if not self.same(*fields):
                del self._pieces[name]
        for kind, kept in self._reads.items():
            if not self.same(*self._reads_fields[kind]):
                kept.clear()
        self._forget_readers(self._readers, self.changed, _paths_read)
        self._forget_readers(self._package_readers, self.changed_packages, _packages_read)
        if not self._indexed_when_made:
            self._indexed_when_made = self._indexed  # the first build's entries: all live
        elif self._indexed > 2 * self._indexed_when_made + 50_000:
            self._index_reads()  # mostly entries of pieces gone
        return self._index

    def _forget_readers(
        self,
        readers: dict[str, list[tuple[str, Any]]],
        changed: frozenset[str],
        what: Callable[[Reads], tuple[str, ...]],
    ) -> None:
        """Forget every piece that read one of ``changed`` (files or packages)."""
        for name in changed:
            found = readers.pop(name, [])
            self._indexed -= len(found)
            for kind, key in found:
                kept = self._reads.get(kind)
                piece = None if kept is None else kept.get(key)
                if kept is not None and piece is not None and name in what(piece[1]):
                    del kept[key]  # else one made since, of other files

    def _index_reads(self) -> None:
        """Index every piece kept by what it read, anew."""
        self._readers, self._package_readers, self._indexed = {}, {}, 0
        for kind, kept in self._reads.items():
            for key, (_, read) in kept.items():
                self.indexed(kind, key, read)
        self._indexed_when_made = self._indexed

    def indexed(self, kind: str, key: Any, read: Reads) -> None:
        """Note that the piece ``key`` of ``kind`` read ``read`` (``_Pieces``)."""
        entry = (kind, key)  # one for all it read: 350,000 entries at 77,000 files
        for path in read.paths:
            self._readers.setdefault(path, []).append(entry)
        for package in read.packages:
            self._package_readers.setdefault(package, []).append(entry)
        self._indexed += len(read.paths) + len(read.packages)

    def edits(self) -> list[tuple[str, FileFacts, FileFacts]]:
        """Each changed file's display path and facts before and now (``begin``)."""
        return [(new.path, old, new) for old, new in self._pairs]

    def forget(self, paths: Iterable[str]) -> None:
        """Forget every piece that read one of ``paths``, as ``begin`` forgets those that
        read a changed file: a build that learns of other files its change reaches
        (``parameters.ParameterTables.with_classes``)."""
        self._forget_readers(self._readers, frozenset(paths), _paths_read)

    def replace_piece(self, name: str, value: Any) -> None:
        """The piece ``name`` made anew from the last build's, for the next build."""
        self._pieces[name] = (self._pieces[name][0], value)

    def same(self, *fields: Field) -> bool:
        """Whether every changed file's facts agree on ``fields`` before and after."""
        return not self.moved and all(
            _viewed(old, field) == _viewed(new, field)
            for old, new in self._pairs
            for field in fields
        )

    def piece(self, name: str, fields: tuple[Field, ...], make: Callable[[], T]) -> T:
        """The last build's piece ``name`` where no changed file differs in ``fields``
        (what it is made from), else made again."""
        if name in self._pieces:
            found: T = self._pieces[name][1]
            return found
        made = make()
        self._pieces[name] = (fields, made)
        return made

    def read(self, paths: tuple[str, ...] = (), packages: tuple[str, ...] = ()) -> Reads:
        """What a piece was made from, as this memory keeps it: nothing, where it keeps
        nothing for a next build."""
        return Reads(paths, packages) if self.keeps else NOTHING

    def reads(self, kind: str, fields: tuple[Field, ...] = ()) -> dict[Any, tuple[Any, Reads]]:
        """The pieces of one kind made from some files each (and from ``fields`` of every
        file's facts), those still valid (``begin`` forgot the others): the map a build
        takes from and adds to."""
        self._reads_fields[kind] = fields
        kept = self._reads.get(kind)
        if kept is None:
            kept = self._reads[kind] = _Pieces(self, kind)
        return kept


class _Pieces(dict[Any, tuple[Any, Reads]]):
    """The pieces of one kind, each indexed by what it read as it is stored (the build's
    code stores them as into any map). A memory that keeps nothing indexes nothing."""

    def __init__(self, memory: GraphMemory, kind: str) -> None:
        super().__init__()
        self._memory = memory
        self._kind = kind

    def __setitem__(self, key: Any, value: tuple[Any, Reads]) -> None:
        super().__setitem__(key, value)
        if self._memory.keeps:
            self._memory.indexed(self._kind, key, value[1])


def _paths_read(read: Reads) -> tuple[str, ...]:
    return read.paths


def _packages_read(read: Reads) -> tuple[str, ...]:
    return read.packages


def _viewed(facts: FileFacts, field: Field) -> object:
    return getattr(facts, field) if isinstance(field, str) else field(facts)

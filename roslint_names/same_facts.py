"""A run whose files' facts are those of the last run: its graph findings, without the graph.

Most edits leave a file's facts as they were, or move them: a comment, a function body
that names nothing ROS reads, a line above the file's names. The workspace graph is made
of facts only, so no node, launch tree or parameter changes, and no graph rule finds
anything new; yet loading every file's facts and building the graph again was 4.5 s of
the 8.7 s an edit cost at 77,000 files (issue 30).

After a run that built the graph, ``Replay`` keeps what the end of the run needs besides
it: each checked file's facts key, every reported file's findings once the graph rules
added theirs and the workspace spared some (``run_checks.RunChecks.spare``: with the files
so judged), the graph rules' own findings per file, and what the run gathered from every
file's facts (``RunWide``: the service types, the names the launch files wire, the build
files' compiled sources, the fixtures tests load expecting them refused). It is keyed by
all the run's key holds but the facts keys (``RunInputs``'s place key) and by the
per-file checks' key (``clean_files.memo_key``: settings, rules, plugin names, where
the manifests are; the place key holds what they say).

A later run with that key whose facts keys differ for some files (``edited``) takes it
when each of those files (``moves``):

- has the facts stored under its old key, but for their spans (``moves.moved_spans``:
  then every place the replay keeps in the file is put where it is now, and a place no
  fact gives refuses the replay) and for whether its bytes hold a suppression marker
  (which files a run reads, never what the graph is made of; the edited file is read and
  checked anew); a build file's places may move too: ``RunWide.built`` keeps what it
  compiles, no place;
- takes no value from another file's constant (``symbols.uses_constants``): those are
  not kept;
- wires no name (``wiring.wired_by``): whether its wiring counts depends on its text
  (``checks.launch_wiring``);
- was not extracted again under an includer's arguments by the last graph build
  (``specialised``): that reads its bytes, not its facts.

Its edited files are then checked by the per-file rules, the graph rules' findings in
them made into diagnostics again under their new text and suppressions, and every other
file's findings are the stored ones (their places in the edited files moved); the rest
of the run is the same code. A file added or removed renumbers the replay of the last
run of the same shape (``shifts``), and a manifest depending on other packages takes it
through a patch of the graph; anything else (settings changed, a package renamed) is a
run like any other, which keeps a new replay.
``tests/test_same_facts.py`` compares every run of a sequence of edits with a run from
an empty cache.
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace

from .model import CompiledSources, Diagnostic, FileFacts, Finding, Generation
from .moves import Moves, UnplacedError, moved_diagnostic, moved_finding, moved_spans
from .run_inputs import ADDED
from .shifts import Lookups, Renumbering
from .symbols import uses_constants
from .wiring import wired_by
from .workspace.graph import Graph
from .workspace.index import Package
from .workspace.launch_parts import CodeParameterParts, LaunchParts, ParameterPart

Built = tuple[tuple[FileFacts, "str | None"], ...]  # ``BuiltSources.given``


@dataclass(frozen=True)
class RunWide:
    """What a run gathers from every file's facts for the checks at its end
    (``run_checks.RunChecks``)."""

    service_types: frozenset[tuple[Generation | None, str]]
    wired: frozenset[str]  # absolute names the launch files wire
    built: Built  # the build files' compiled sources, and the sources C++ files include
    rejected: Mapping[str, frozenset[str]]  # package: the fixture names its tests refuse
    # Where the run finds a file by its name (``shifts.Lookups``): the names launch files
    # run and include, load and hand on files by; for a parameter file's name, who does
    # (digests of their display paths); the sources build files' executables name
    # (digests). Gathered over every run since the last build: one that no longer holds
    # makes a file found by name that is not, a build or a walk more, never a wrong result.
    looked_up: frozenset[str] = frozenset()
    naming: Mapping[str, frozenset[int]] = field(default_factory=dict)
    named_sources: Mapping[int, int] = field(default_factory=dict)  # source: build file
    # How many files serve or call a service of each type (``typed_services``), which
    # tells a patch whether an edit changes the set other files' RN204 compares with;
    # None where that is not known (a file removed since whose facts are gone).
    typed_uses: Mapping[tuple[Generation | None, str], int] | None = None

    def lookups(self) -> Lookups:
        found = Lookups()
        found.update(self.looked_up, self.naming, self.named_sources)
        return found


@dataclass(frozen=True)
class Replay:
    """What a run that built the graph leaves for a run whose facts are the same."""

    tags: tuple[str, ...]  # each checked file's facts key, or why it has none
    reported: int
    # Per reported file with any (its index): its findings, and the graph rules' findings
    # in it, as (rule code, finding).
    found: Mapping[int, tuple[Diagnostic, ...]]
    graph: Mapping[int, tuple[tuple[str, Finding], ...]]
    specialised: frozenset[str]  # display paths the graph build extracted again
    run_wide: RunWide
    skipped: tuple[tuple[str, str], ...]  # files too large, and why
    # The reported files (indices) whose findings were spared as unbuilt, and as named
    # by rostest.
    unbuilt: tuple[int, ...] = ()
    rostest_named: tuple[int, ...] = ()
    # The reported files (indices) that serve or call a typed service: checked again by a
    # patch that changes the set of types they compare with (RN204).
    typed: tuple[int, ...] = ()

    def edited(self, tags: Sequence[str]) -> list[int] | None:
        """The checked files whose facts keys differ from the replay's, none where nothing
        differs (a run reported in other files than the replay's: ``engine._lint``'s
        ``focus``); None where the run is not over the same files (its place key tells
        that: a guard)."""
        if len(tags) != len(self.tags):
            return None
        pairs = enumerate(zip(tags, self.tags, strict=True))
        return [index for index, (now, then) in pairs if now != then]

    def moves(self, display: str, before: FileFacts | None, now: FileFacts) -> Moves | None:
        """How an edited file's places moved, where it leaves the replay true (module
        docstring); None where it does not. ``before``: its facts under its old key, if
        still cached."""
        if (
            before is None
            or uses_constants(now)
            or wired_by(now)
            or display in self.specialised
            or (spans := moved_spans(before, now)) is None
        ):
            return None
        return Moves(display, spans)

    def moved(self, moves: Sequence[Moves], displays: Sequence[str]) -> Replay | None:
        """The replay with every place it keeps in the edited files where it is now;
        None where one has no known new place (``moves.UnplacedError``). ``displays``: the
        reported files' display paths."""
        moving = [move for move in moves if not move.still]
        if not moving:
            return self
        edited = {move.display for move in moving}
        try:
            graph = {
                index: tuple(
                    (code, moved_finding(finding, displays[index], moving))
                    for code, finding in items
                )
                for index, items in self.graph.items()
            }
            found = {
                index: found
                if displays[index] in edited
                else tuple(moved_diagnostic(diagnostic, moving) for diagnostic in found)
                for index, found in self.found.items()
            }
        except UnplacedError:
            return None
        return replace(self, graph=graph, found=found)

    def stored(self) -> tuple[object, ...]:
        """As the cache keeps it: model values and builtins only."""
        wide = self.run_wide
        return (
            _FORMAT,
            self.tags,
            self.reported,
            tuple(sorted(self.found.items())),
            tuple(sorted(self.graph.items())),
            tuple(sorted(self.specialised)),
            tuple(sorted(wide.service_types, key=_by_text)),
            tuple(sorted(wide.wired)),
            wide.built,
            tuple(
                sorted((package, tuple(sorted(names))) for package, names in wide.rejected.items())
            ),
            self.skipped,
            self.unbuilt,
            self.rostest_named,
            self.typed,
            tuple(sorted(wide.looked_up)),
            tuple(sorted((name, tuple(sorted(by))) for name, by in wide.naming.items())),
            tuple(sorted(wide.named_sources.items())),
            None
            if wide.typed_uses is None
            else tuple(sorted(wide.typed_uses.items(), key=lambda item: _by_text(item[0]))),
        )

    def renumbered(self, renumbering: Renumbering, reported: int) -> Replay:
        """This replay of an earlier run over the files of a run renumbered from it
        (``shifts``), ``reported`` of them reported: an added file's tag is ``ADDED``,
        a removed file's findings go with it."""
        then_of = renumbering.then_of(reported)
        return Replay(
            tuple(ADDED if then < 0 else self.tags[then] for then in renumbering.previous),
            reported,
            {then_of[index]: found for index, found in self.found.items() if index in then_of},
            {then_of[index]: found for index, found in self.graph.items() if index in then_of},
            self.specialised,
            self.run_wide,
            self.skipped,
            tuple(sorted(then_of[index] for index in self.unbuilt if index in then_of)),
            tuple(sorted(then_of[index] for index in self.rostest_named if index in then_of)),
            tuple(sorted(then_of[index] for index in self.typed if index in then_of)),
        )


_FORMAT = "replay 7"
_FIELDS = 18  # of ``stored``


def key(place_key: str, checks_key: str) -> str:
    """Where a run's replay is kept: its place and its per-file checks' key."""
    return hashlib.blake2b(f"{place_key}\0{checks_key}".encode(), digest_size=20).hexdigest()


def loaded(value: object, files: int, reported: int) -> Replay | None:
    """A stored replay for a run of ``files`` checked files, ``reported`` of them
    reported; None for anything else (absent, damaged, another shape)."""
    if not isinstance(value, tuple) or len(value) != _FIELDS:
        return None
    form, tags, kept_reported, found, graph, specialised, types, wired = value[:8]
    built, rejected, skipped, unbuilt, rostest_named, typed = value[8:14]
    looked_up, naming, named, uses = value[14:]
    if form != _FORMAT or kept_reported != reported or not _strings(tags) or len(tags) != files:
        return None
    try:
        found_map = {int(index): tuple(items) for index, items in found}
        graph_map = {
            int(index): tuple((str(code), finding) for code, finding in items)
            for index, items in graph
        }
        rejected_map = {str(package): frozenset(names) for package, names in rejected}
        built_pairs = tuple((facts, package) for facts, package in built)
        skipped_pairs = tuple((str(path), str(why)) for path, why in skipped)
        type_pairs = frozenset((generation, str(spelling)) for generation, spelling in types)
        naming_map = {str(name): frozenset(by) for name, by in naming}
        named_map = {source: builder for source, builder in named}
        uses_map = (
            None
            if uses is None
            else {(generation, str(spelling)): count for (generation, spelling), count in uses}
        )
    except (TypeError, ValueError):
        return None
    if not (
        all(0 <= index < reported for index in found_map)
        and all(0 <= index < reported for index in graph_map)
        and all(isinstance(d, Diagnostic) for items in found_map.values() for d in items)
        and all(_strings(tuple(names)) for names in rejected_map.values())
        and all(isinstance(f, Finding) for items in graph_map.values() for _, f in items)
        and all(
            isinstance(facts, FileFacts)
            and isinstance(facts.compiled, CompiledSources | None)
            and isinstance(package, str | None)
            for facts, package in built_pairs
        )
        and _strings(specialised)
        and _strings(wired)
        and _strings(looked_up)
        and all(_ints(tuple(by)) for by in naming_map.values())
        and _ints(tuple(named_map))
        and _ints(tuple(named_map.values()))
        and _indices(unbuilt, reported)
        and _indices(rostest_named, reported)
        and _indices(typed, reported)
        and all(isinstance(generation, Generation | None) for generation, _ in type_pairs)
        and (
            uses_map is None
            or all(
                isinstance(generation, Generation | None) and isinstance(count, int) and count > 0
                for (generation, _), count in uses_map.items()
            )
        )
    ):
        return None
    return Replay(
        tuple(tags),
        reported,
        found_map,
        graph_map,
        frozenset(specialised),
        RunWide(
            type_pairs,
            frozenset(wired),
            built_pairs,
            rejected_map,
            frozenset(looked_up),
            naming_map,
            named_map,
            uses_map,
        ),
        skipped_pairs,
        unbuilt,
        rostest_named,
        typed,
    )


_GRAPH_FORMAT = "graph 4"

# The graph rules' findings per reported file (its index), as ``Replay.graph`` holds them.
GraphFound = Mapping[int, tuple[tuple[str, Finding], ...]]


def codes_of(*found: GraphFound) -> set[str]:
    """The rules that made some of these graph findings: a run takes them only where it
    runs every one of those rules."""
    return {code for each in found for items in each.values() for code, _ in items}


@dataclass(frozen=True)
class KeptGraph:
    """The graph a run built, the facts keys it was built from, and its rules' findings
    (``workspace.patch``: a rule that reads no name the patch changes keeps them)."""

    tags: tuple[str, ...]
    graph: Graph
    found: GraphFound
    # The workspace's packages as the build had them: the same where the graph can be
    # patched (no manifest or ``.srv`` file changed) but for what they depend on, which
    # ``depends`` says (``PackageGenerations.depends_digest``); gathered from every file
    # else.
    packages: tuple[Package, ...]
    depends: str
    # A graph built over an earlier file list, renumbered (``shifts.GraphMove``): the
    # facts keys as the build had them (what its launch and code parts are named by), and
    # the files it had that the run has not, (display path, facts key).
    built_tags: tuple[str, ...] | None = None
    gone: tuple[tuple[str, str], ...] = ()

    @property
    def built_from(self) -> tuple[str, ...]:
        """The facts keys the graph was built from, in the build's file order."""
        return self.tags if self.built_tags is None else self.built_tags

    def stored(self) -> tuple[object, ...]:
        assert self.built_tags is None, "a renumbered graph is kept where it was built"
        found = tuple(sorted(self.found.items()))
        return (_GRAPH_FORMAT, self.tags, self.graph, found, self.packages, self.depends)

    def renumbered(self, renumbering: Renumbering, reported: int) -> KeptGraph:
        """This graph over the files of a run renumbered from its build's (``shifts``),
        ``reported`` of them reported: an added file's tag is ``ADDED``."""
        then_of = renumbering.then_of(reported)
        return KeptGraph(
            tuple(ADDED if then < 0 else self.tags[then] for then in renumbering.previous),
            self.graph,
            {then_of[index]: found for index, found in self.found.items() if index in then_of},
            self.packages,
            self.depends,
            self.tags,
            tuple((display, self.tags[index]) for index, display in renumbering.removed),
        )


def loaded_graph(value: object, files: int, reported: int) -> KeptGraph | None:
    """A kept graph of a run over ``files`` checked files, ``reported`` of them reported;
    None for anything else."""
    if not isinstance(value, tuple) or len(value) != 6:
        return None
    form, tags, graph, found, packages, depends = value
    if form != _GRAPH_FORMAT or not _strings(tags) or len(tags) != files:
        return None
    if not isinstance(depends, str):
        return None
    if not (isinstance(packages, tuple) and all(isinstance(p, Package) for p in packages)):
        return None
    try:
        found_map = {
            int(index): tuple((str(code), finding) for code, finding in items)
            for index, items in found
        }
    except (TypeError, ValueError):
        return None
    if not (
        isinstance(graph, Graph)
        and all(0 <= index < reported for index in found_map)
        and all(isinstance(f, Finding) for items in found_map.values() for _, f in items)
    ):
        return None
    return KeptGraph(tags, graph, found_map, packages, depends)


_LAUNCH_FORMAT = "launch parts 3"


@dataclass(frozen=True)
class KeptLaunch:
    """What ``KeptGraph``'s graph leaves out (``patch.parameter_part``), with the facts
    keys the graph was built from and each launch tree's part of it
    (``workspace.launch_patch``): with the kept graph, the whole graph of the build."""

    tags: tuple[str, ...]
    parameters: ParameterPart
    parts: LaunchParts

    def stored(self) -> tuple[object, ...]:
        return (_LAUNCH_FORMAT, _tags_digest(self.tags), self.parameters, self.parts)


def loaded_launch(value: object, tags: tuple[str, ...]) -> KeptLaunch | None:
    """A kept launch part built from the facts keys ``tags`` (the kept graph's); None for
    anything else."""
    found = _of_build(value, _LAUNCH_FORMAT, tags, 2)
    if found is None:
        return None
    parameters, parts = found
    if not (isinstance(parameters, ParameterPart) and isinstance(parts, LaunchParts)):
        return None
    return KeptLaunch(tags, parameters, parts)


_CODE_FORMAT = "code parameters 2"


@dataclass(frozen=True)
class KeptCode:
    """What the kept graph's nodes' parameters were gathered from
    (``launch_parts.CodeParameterParts``), with the facts keys the graph was built from."""

    tags: tuple[str, ...]
    parts: CodeParameterParts

    def stored(self) -> tuple[object, ...]:
        return (_CODE_FORMAT, _tags_digest(self.tags), self.parts)


def loaded_code(value: object, tags: tuple[str, ...]) -> KeptCode | None:
    """A kept ``KeptCode`` of the build from the facts keys ``tags``; None for anything
    else."""
    found = _of_build(value, _CODE_FORMAT, tags, 1)
    if found is None or not isinstance(found[0], CodeParameterParts):
        return None
    return KeptCode(tags, found[0])


def _of_build(
    value: object, form: str, tags: tuple[str, ...], items: int
) -> tuple[object, ...] | None:
    """The ``items`` values a kept entry of ``form`` holds after its format and the digest
    of the facts keys it was built from (``KeptLaunch.stored``, ``KeptCode.stored``),
    where those are ``form``'s and ``tags``'; else None."""
    if not isinstance(value, tuple) or len(value) != 2 + items:
        return None
    if value[0] != form or value[1] != _tags_digest(tags):
        return None
    return value[2:]


def _tags_digest(tags: Sequence[str]) -> str:
    """The facts keys of a build, as a launch part names them (the kept graph holds them
    whole: 3.5 MB at 77,000 files)."""
    return hashlib.blake2b("\0".join(tags).encode(), digest_size=16).hexdigest()


def _by_text(service_type: tuple[Generation | None, str]) -> tuple[str, str]:
    generation, spelling = service_type
    return ("" if generation is None else str(generation.value), spelling)


def _indices(value: object, reported: int) -> bool:
    return isinstance(value, tuple) and all(
        isinstance(item, int) and 0 <= item < reported for item in value
    )


def _ints(value: object) -> bool:
    return isinstance(value, tuple) and all(isinstance(item, int) for item in value)


def _strings(value: object) -> bool:
    return isinstance(value, tuple) and all(isinstance(item, str) for item in value)

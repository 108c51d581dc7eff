"""A run that takes the last run's graph findings (``same_facts``: its replay), or patches
the graph the last build kept (``GraphPatch``: ``workspace.patch``, ``launch_patch``,
``parameter_patch``, ``program_patch``) instead of building it; and where that graph and
the last run of the same shape are kept (``shifts``)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Collection, Iterable, Mapping, Sequence
from dataclasses import InitVar, dataclass, field, replace
from functools import lru_cache
from typing import TYPE_CHECKING, NamedTuple

from . import same_facts, shifts
from .checks import file_graph_findings, graph_findings, typed_services, typed_uses
from .config import Settings
from .discover import SourceFile
from .gather import Gatherer, Specialiser, Verdict
from .model import FileFacts, Finding, Generation, Language
from .moves import Moves, UnplacedError, moved_finding
from .registry import Registry
from .rule import Rule, WorkspaceFinding
from .run_checks import RunChecks, built_as_taken
from .run_inputs import ADDED, RunInputs, is_facts_key
from .same_facts import KeptGraph, KeptLaunch, Replay, RunWide
from .symbols import PackageConstants, uses_constants
from .wiring import wired_by
from .workspace.build import _TestFiles
from .workspace.built import BuiltSources
from .workspace.graph import Graph
from .workspace.index import (
    CODE_LANGUAGES,
    Package,
    PackageFiles,
    WorkspaceIndex,
    companions,
    named_once,
)
from .workspace.launch_parts import CodeParameterParts, LaunchParts
from .workspace.launch_patch import LazyFacts, launch_edit, launch_patched, parameter_edit
from .workspace.launch_tree import LAUNCH_LANGUAGES
from .workspace.parameter_patch import parameters_patched
from .workspace.patch import (
    NOT_CODE_FIELDS,
    Moved,
    edits_of,
    moved_code_parameters,
    same_places,
    with_parameters,
)
from .workspace.patch import patched as patch_graph
from .workspace.program_patch import (
    BUILD_LANGUAGES,
    ProgramsAnew,
    program_edit,
    programs_anew,
)

if TYPE_CHECKING:
    from .cache import FactsCache  # imported by the caller that wants a cache


class Shift(NamedTuple):
    """A run over the files of an earlier run, some added or removed (``shifts``): where
    that run's replay is kept, how the files map, and the replay renumbered; whether it
    may stand as it is (each removed file said nothing), else only a patch of the
    graph may take it (a launch file removed: ``GraphPatch``)."""

    replay_at: str
    renumbering: shifts.Renumbering
    replay: Replay
    stands: bool


def shifted_replay(
    cache: FactsCache,
    inputs: RunInputs,
    clean_key: str,
    files: Sequence[SourceFile],
    depends: str,
) -> Shift | None:
    """The replay of the last run of this run's shape (``shifts.Base``), renumbered to its
    files; it stands where its packages depended on what they do now (``depends``) and
    each file it had and this run has not says nothing and is found by no name (its
    findings go with it), each added file asked the same once its facts are known
    (``_replay_moved``); else only a patch of the graph may take it."""
    found = _base_of(cache, inputs, clean_key, files)
    if found is None:
        return None
    base, renumbering = found
    earlier = same_facts.loaded(
        cache.load_replay(base.replay_at), len(base.displays), base.reported
    )
    if earlier is None:
        return None
    stands = base.depends == depends
    gone = [_facts_by_tag(cache, earlier.tags[at], path) for at, path in renumbering.removed]
    if stands and gone:
        found_by = earlier.run_wide.lookups()
        stands = all(facts is not None and found_by.adds_nothing(facts) for facts in gone)
    replay = earlier.renumbered(renumbering, len(files))
    uses = _typed_uses_without(earlier.run_wide.typed_uses, gone)
    if uses != earlier.run_wide.typed_uses:
        replay = replace(replay, run_wide=replace(replay.run_wide, typed_uses=uses))
    return Shift(base.replay_at, renumbering, replay, stands)


def _typed_uses_without(
    uses: Mapping[tuple[Generation | None, str], int] | None,
    gone: Iterable[FileFacts | None],
    came: Iterable[FileFacts] = (),
) -> Mapping[tuple[Generation | None, str], int] | None:
    """A run's ``RunWide.typed_uses`` less the files removed or edited since (``gone``:
    their facts then) and with those added or edited (``came``: their facts now); None
    where one's facts are not kept, or a count falls below 0. A type whose last user
    went stays, counted 0: the set of types the other files' RN204 compared with at
    that run is the one a patch compares the set after its edits with, to check them
    again where it changed (``GraphPatch._from``'s ``types_changed``)."""
    if uses is None:
        return None
    counts = Counter(uses)
    for facts in gone:
        if facts is None:
            return None
        counts.subtract(typed_uses(facts))
    for facts in came:
        counts.update(typed_uses(facts))
    return None if any(count < 0 for count in counts.values()) else dict(counts)


def _facts_by_tag(cache: FactsCache, tag: str, display: str) -> FileFacts | None:
    """The facts of the file shown as ``display`` under ``tag`` (``RunInputs.tags``), None
    where the tag is no facts key or they are not kept."""
    return cache.load(tag, display) if is_facts_key(tag) else None


def _base_of(
    cache: FactsCache, inputs: RunInputs, clean_key: str, files: Sequence[SourceFile]
) -> tuple[shifts.Base, shifts.Renumbering] | None:
    """The last run of this run's shape that kept a replay (``shifts.Base``), and how this
    run's files map to its; None where there is none, or the files differ too much."""
    shape = inputs.shape_key
    if shape is None:
        return None
    base = shifts.loaded_base(
        cache.load_base(same_facts.key(shape, clean_key)), cache.load_file_list
    )
    if base is None:
        return None
    displays = [source.display for source in files]
    renumbering = shifts.renumbering(base.displays, base.reported, displays)
    return None if renumbering is None else (base, renumbering)


def base_place(
    cache: FactsCache, inputs: RunInputs, clean_key: str, files: Sequence[SourceFile]
) -> GraphPlace | None:
    """Where the graph of the last run of this run's shape is (``GraphPatch.elsewhere``)."""
    found = _base_of(cache, inputs, clean_key, files)
    return None if found is None else GraphPlace(found[0].replay_at, found[1])


def keep_base(
    cache: FactsCache,
    inputs: RunInputs,
    clean_key: str | None,
    kept_at: str,
    *,
    files: Sequence[SourceFile],
    reported: int,
    depends: str,
) -> None:
    """Keep the run that kept its replay at ``kept_at`` as the last of its shape: its
    files, where no run over them kept them yet (or what was kept does not read back),
    and the pointer to them, with what its packages depend on (``depends``)."""
    if inputs.shape_key is None or clean_key is None:
        return
    at = same_facts.key(inputs.shape_key, clean_key)
    listed = cache.holds_file_list(kept_at)
    if listed and cache.load_base(at) == shifts.pointer(kept_at, reported, len(files), depends):
        return  # most runs: the last run's, as it is (its display paths not made)
    displays = tuple(source.display for source in files)
    base = shifts.Base(kept_at, displays, reported, depends)
    if not listed or shifts.loaded_base(base.pointer(), cache.load_file_list) != base:
        cache.store_file_list(kept_at, base.listed())
    cache.store_base(at, base.pointer())


@dataclass(frozen=True)
class GraphPlace:
    """Where the graph a patch starts from is kept (``key``), and how this run's files
    map to that run's (None: they are its files)."""

    key: str
    renumbering: shifts.Renumbering | None = None

    def resolved(self, cache: FactsCache, files: Sequence[SourceFile]) -> GraphPlace | None:
        """Where a build kept the graph: ``key``, or where the run kept under it says
        (``shifts.GraphMove``), the renumberings joined (``files``: this run's); None
        where neither is."""
        if cache.holds_graph(self.key):
            return self
        move = shifts.loaded_move(cache.load_graph_move(self.key))
        if move is None:
            return None
        renumbering = move.renumbering
        if self.renumbering is not None:
            displays = [source.display for source in files]
            renumbering = self.renumbering.after(renumbering, displays)
        return GraphPlace(move.graph_at, renumbering)

    def graph(self, cache: FactsCache, files: int, reported: int) -> KeptGraph | None:
        """The kept graph over ``files`` checked files, ``reported`` of them reported
        (renumbered to them); None where it is not kept or does not read back."""
        if self.renumbering is None:
            return same_facts.loaded_graph(cache.load_graph(self.key), files, reported)
        renumbering = self.renumbering
        if len(renumbering.previous) != files:
            return None
        built = same_facts.loaded_graph(
            cache.load_graph(self.key), renumbering.before, renumbering.reported_before
        )
        return None if built is None else built.renumbered(renumbering, reported)


class Replayed(NamedTuple):
    """A run that took a replay: the files edited since (and those whose graph findings a
    patched graph changed), and the replay with their places where they are now (with
    the patched graph's findings)."""

    edited: list[int]
    replay: Replay


def take_facts(
    gathered: Gatherer,
    checks: RunChecks,
    replay: Replay | None,
    inputs: RunInputs | None,
    *,
    rules: Mapping[str, Rule],
    patch: Callable[[Replay, Sequence[_Arrived]], Replayed | None] | None = None,
    stands: bool = True,
) -> Replayed | None:
    """Hand every file's facts to ``checks``, as they arrive; or, where the run can take
    ``replay`` (``same_facts``), only those of the files edited since: then those files,
    and the replay with their places where they are now; or, where ``patch`` patches the
    replay's graph (``workspace.patch``), what it gives. The edited files come first
    either way: whether the replay stands is their facts' question (and ``stands``:
    False where only a patch may take it, ``Shift``)."""
    edited = None if replay is None or inputs is None else replay.edited(inputs.tags)
    if replay is None or edited is None or inputs is None or gathered.cache is None:
        for index, facts, data, verdict in gathered.facts():
            checks.take(index, facts, data, verdict)
        return None
    arrived = list(gathered.facts(edited))
    for index, facts, data, verdict in arrived:
        checks.take(index, facts, data, verdict)
    cache = gathered.cache
    moved = (
        _replay_moved(replay, arrived, inputs, files=gathered.files, cache=cache, rules=rules)
        if stands
        else None
    )
    if moved is not None:
        return Replayed(edited, moved)
    patched = None if patch is None else patch(replay, arrived)
    if patched is not None:
        return patched
    others = set(edited)
    rest = (index for index in range(len(gathered.files)) if index not in others)
    for index, facts, data, verdict in gathered.facts(rest):
        checks.take(index, facts, data, verdict)
    return None


_Arrived = tuple[int, FileFacts, "bytes | None", "Verdict | None"]


# Files edited since the last build past which a patch keeps what it patched as the
# graph the next runs patch, as a build does: each run patches every edit since that
# build again (at 8 copies of the benchmark's workspace, a parameter declared in one
# more C++ file before each run: 2.07 s after the first, 4.02 s after the thirtieth),
# and keeping the patched graph and its parts costs a run what a build's keeping does
# (0.4 to 0.5 s there). Kept past 8 such files, the runs of that sequence took 2.2 to
# 3.4 s.
REBASE_EDITS = 8


class _Rebased(NamedTuple):
    """What a patch keeps as a build keeps it: the whole graph, the launch and code
    parameter parts a build of the files as they are would leave, and the packages."""

    graph: Graph
    launch: LaunchParts
    code: CodeParameterParts
    packages: list[Package]


@dataclass
class GraphPatch:
    """A run whose edits change only what some nodes' code declares (``workspace.patch``)
    or what some launch trees start or hand their nodes (``workspace.launch_patch``: launch
    and parameter files), or what some packages depend on (their manifests): the graph
    the last build kept, patched with every edit since (the facts it was built from are
    loaded, so kept in the pack), and the graph rules run over it; the files whose graph
    findings that changed, and those of a package depending on others, are taken and
    reported again with the edited ones, every other file's findings are the replay's.
    A build keeps its graph; a patch keeps what it patched, as a build keeps it, only
    where it applied many edits since (``REBASE_EDITS``): pickling a graph and its parts
    (0.4 to 0.5 s at 81,000 files) would cost each patched run more than patching it
    again, and every edit since the last build is patched again by each run."""

    gathered: Gatherer
    checks: RunChecks
    inputs: RunInputs
    cache: FactsCache
    place: GraphPlace  # where the last build's graph is kept, by the replay's
    rules: Sequence[Rule]
    settings: Settings
    # Launch files under their includers' arguments, for the trees walked again
    specialiser: Callable[[], Specialiser]
    # Where the graph of the last run of this run's shape is, where ``place`` no longer
    # leads to one (a run over these files long ago, whose graph was since forgotten)
    elsewhere: Callable[[], GraphPlace | None] = lambda: None
    # What the run's packages depend on (``PackageGenerations.depends_digest``), and the
    # packages (``workspace_packages``): a graph built where some depended on others is
    # patched with them as they are (``_depending_anew``).
    depends: Callable[[], str] = lambda: ""
    packages: Callable[[], list[Package]] = list
    # Whether the run keeps what a build keeps (a run over the workspace, not one with
    # the rest of it as context): where the patch applied many edits, what it patched
    # is kept as the next runs' graph (``rebased``).
    may_rebase: bool = False
    elsewhere_used: bool = False
    graph_from: GraphPlace | None = None  # where the graph it patched is, resolved
    rebased: _Rebased | None = None
    # Package directories whose C++ files the checks know (``_know_headers``)
    _headers_known: set[str] = field(default_factory=set)

    def __call__(self, replay: Replay, arrived: Sequence[_Arrived]) -> Replayed | None:
        """The replay patched from the graph kept where it was made; where that holds
        none, or one the edits since cannot patch, from the graph of the last run of
        this run's shape (``elsewhere``): a replay found by the run's files may be of a
        run long ago (a file removed and brought back), whose graph is older than the
        last build's."""
        files = self.gathered.files
        place = self.place.resolved(self.cache, files)
        stored = None if place is None else place.graph(self.cache, len(files), replay.reported)
        found = (
            None if place is None or stored is None else self._from(replay, arrived, place, stored)
        )
        if found is not None:
            return found
        other = self.elsewhere()
        last = None if other is None else other.resolved(self.cache, files)
        if last is None or (place is not None and last.key == place.key):
            return None
        stored = last.graph(self.cache, len(files), replay.reported)
        self.elsewhere_used = True
        return None if stored is None else self._from(replay, arrived, last, stored)

    def _from(
        self, replay: Replay, arrived: Sequence[_Arrived], place: GraphPlace, stored: KeptGraph
    ) -> Replayed | None:
        """The replay patched from the graph ``stored`` at ``place``; None where the
        edits since cannot be."""
        files = self.gathered.files
        self.graph_from = place
        codes = {rule.code for rule in self.rules}
        if not same_facts.codes_of(replay.graph, stored.found) <= codes:
            return None
        graph = stored.graph
        packages: Sequence[Package] = stored.packages
        depending: frozenset[str] = frozenset()  # packages depending on others since
        if stored.depends != self.depends():
            anew = _depending_anew(stored.packages, self.packages())
            if anew is None:
                return None
            packages, depending = anew
        arrived_facts = {index: facts for index, facts, _, _ in arrived}
        # Files the build did not have, or had and the run has not, say nothing and are
        # found by no name, the edited files' names too (``shifts``): then the build's
        # graph is theirs.
        found_by = replay.run_wide.lookups()
        for edited in arrived_facts.values():
            found_by.add(edited)
        # Code may serve or call services of other types, where the run knows how many
        # files use each type after the edits since the replay's run; where that set of
        # types changed, every file comparing with it is checked again (RN204).
        typed_uses = self._typed_uses_after(replay, arrived)
        typed = typed_uses is not None
        if not typed and 0 in (replay.run_wide.typed_uses or {}).values():
            return None  # a type's last user removed: only its counts tell what changed
        types_changed = (
            typed_uses is not None
            and typed_uses.keys() != (replay.run_wide.typed_uses or {}).keys()
        )

        slots = {source.display: index for index, source in enumerate(files)}
        # Which package holds each file (the build's packages), for a patch that asks.
        package_files = lru_cache(maxsize=1)(
            lambda: PackageFiles([source.display for source in files], packages)
        )
        kinds = _Sorted()
        facts = _RunFacts(
            files,
            slots,
            arrived_facts,
            self.inputs.facts_key,
            self.cache,
            self.checks.package_of,
            package_files,
            kinds.removed_code,
        )
        if not self._sort(kinds, replay, stored, facts, found_by=found_by, typed=typed):
            return None
        kinds.naming -= {*kinds.tree_edits, *kinds.removed_trees}
        # The launch files whose trees are walked again
        walk = [*kinds.tree_edits, *sorted(kinds.naming)]
        declaring: set[str] = set()  # code files whose parameters changed
        renamed: set[str] = set()  # and those whose node name did (``patch.name_edit``)
        # Code that started or stopped declaring endpoints: its package's programs are
        # made again (code no launch file starts is a program where it declares some).
        flipping: set[str] = set()
        edits = edits_of(kinds.changed, declaring, renamed, flipping)
        if edits is None:
            return None

        # The build's whole graph (its parameters kept apart, ``same_facts.KeptLaunch``)
        # for a patch that walks trees or gathers parameters again, or that keeps what it
        # patched as the graph later runs patch (``REBASE_EDITS``).
        kept: KeptLaunch | None = None
        known: set[str] = set()  # the files the build had facts of (a skipped one has none)
        # Some packages' programs made again, some nodes' parameters gathered again
        remade = bool(kinds.building or kinds.added_code or kinds.removed_code or flipping)
        gathering = bool(declaring or depending or remade)
        since = (
            len(kinds.changed)
            + len(kinds.tree_edits)
            + len(kinds.removed_trees)
            + len(kinds.new_files)
        )
        since += len(kinds.building) + len(kinds.removed_code)
        # A file taking a constant that resolves otherwise than at the build is checked
        # again by this run, not by the next ones, which check again only what they
        # edit: what it patched is kept as a build keeps it, so that the graph each
        # replay is patched from resolves every such file as the replay's run did (and
        # has every file taking one that was added: ``_Constants.anew`` asks the build's).
        taking_anew = bool(kinds.retaking or kinds.taking_added)
        if taking_anew and not self.may_rebase:
            return None
        rebasing = self.may_rebase and (since + len(depending) >= REBASE_EDITS or taking_anew)
        if walk or kinds.removed_trees or gathering or rebasing:
            kept = same_facts.loaded_launch(
                self.cache.load_launch_parts(place.key), stored.built_from
            )
            whole = None if kept is None else with_parameters(graph, kept.parameters)
            if kept is None or whole is None:
                return None
            graph = whole
            if depending:  # which nodes can meet (``Graph.can_meet``)
                graph = replace(graph, companions=companions(named_once(packages)))
            known = {
                files[index].display for index, tag in enumerate(stored.tags) if is_facts_key(tag)
            }
            known |= kinds.new_files
        # Their facts, for the programs made, the trees walked and the parameters gathered
        # again: one mapping, whose order is sorted and whose facts are loaded once.
        known_facts = LazyFacts(known, facts.of)
        launch_parts = None if kept is None else kept.parts  # as a build would leave them
        programs: ProgramsAnew | None = None
        if remade:
            assert kept is not None
            # What the build files compiled at the last run, where one builds other
            # programs now (no file added or removed changes it), and now.
            compiled = _compiled(
                replay.run_wide, arrived, self.checks.package_of, bool(kinds.building)
            )
            at_now = WorkspaceIndex.restored(known_facts, packages, kept.parts.executables)
            # A code file added or removed that another package's build file names: that
            # package's programs are made again too.
            builders = self._builders(found_by, [*kinds.added_code, *kinds.removed_code])
            if builders is None:
                return None
            edited_programs = (*kinds.building, *kinds.added_code, *kinds.removed_code)
            owners = [
                package_files().package_of(path)
                for path in (*edited_programs, *flipping, *builders)
            ]
            if None in owners:
                return None
            programs = programs_anew(
                kept.parts.programs,
                kept.parts.executables,
                kept.parts.unbuilt,
                index=at_now,
                packages=sorted(
                    {owner for owner in owners if owner is not None}, key=_by_directory
                ),
                language_of=lambda path: files[slots[path]].language,
                then=kinds.building,
                added=kinds.added_code,
                removed=kinds.removed_code.keys(),
                flipped=flipping,
                compiled=compiled[1],
                compiled_then=compiled[0],
                is_test=_TestFiles(at_now, {}),
                named_elsewhere=lambda path, own: (
                    not found_by.builders(path) <= {shifts.digest(builder) for builder in own}
                ),
            )
            if programs is None:
                return None
        specialised = replay.specialised
        if walk or kinds.removed_trees or renamed or programs is not None:
            assert kept is not None
            if not kinds.naming <= known:
                return None  # a launch file naming one that has no facts now
            walked = self._walked(
                graph,
                parts=kept.parts,
                packages=packages,
                edited=walk,
                removed=kinds.removed_trees,
                code=renamed,
                facts=known_facts,
                programs=programs,
            )
            if walked is None:
                return None
            # A file an edited include hands arguments to now is read under them: an
            # edit of it is never replayed nor patched (the check above). One no longer
            # read so stays in the set: its edits build, as they would have.
            graph, launch_parts = walked[0]
            specialised = specialised | walked[1]
        patched: Graph | None = patch_graph(
            graph,
            edits,
            facts.of,
            package_files,
            declaring=bool(declaring),
        )
        code_parts: CodeParameterParts | None = None
        if patched is not None and (gathering or rebasing):
            assert launch_parts is not None
            kept_code = same_facts.loaded_code(
                self.cache.load_code_parameters(place.key), stored.built_from
            )
            if kept_code is None:
                return None
            code_parts = kept_code.parts
            if gathering:
                code_edits = {
                    display: (before, now)
                    for display, before, now in kinds.changed
                    if display in edits
                }
                for display in kinds.added_code:
                    added = facts.at(slots[display])
                    assert added is not None  # (``_new_code``)
                    code_edits[display] = (_empty(added), added)
                for display, gone in kinds.removed_code.items():
                    code_edits[display] = (gone, _empty(gone))
                gathered = parameters_patched(
                    patched,
                    launch_parts,
                    code_parts,
                    code_edits,
                    facts=known_facts,
                    packages=packages,
                    depending=depending,
                    programs=programs,
                    added=kinds.added_code,
                    removed=kinds.removed_code.keys(),
                )
                if gathered is None:
                    return None
                patched, launch_parts, code_parts = gathered
            else:  # the nodes' parameters moved with their code (``patched``)
                moved = moved_code_parameters(launch_parts.parameters, edits)
                launch_parts = None if moved is None else replace(launch_parts, parameters=moved)
        if patched is None:
            return None
        # A rule that reads no name the patch changed has the built graph's findings, the
        # places of the edited files moved (only places can have: its parameter uses');
        # none where launch trees were walked again.
        kept_codes, kept_found = (
            (frozenset(), {})
            if walk or kinds.removed_trees or gathering
            else _kept_findings(stored.found, edits, self.rules, files)
        )
        found = self._graph_found(patched, slots, replay.reported, kept_codes, kept_found)
        again = set(arrived_facts) | {
            index
            for index in found.keys() | replay.graph.keys()
            if found.get(index, ()) != replay.graph.get(index, ())
        }
        # The files of a package depending on others are compared with the service types
        # of those (RN204: ``RunChecks._typed``): checked again.
        for package in packages:
            if package.name in depending:
                again.update(
                    at
                    for display in package_files().below(package.directory)
                    if (at := slots[display]) < replay.reported
                )
        # A source rostest alone starts now, or starts no more, is judged again
        # (``RunChecks.spare``).
        if programs is not None:
            again.update(
                at for display in programs.rostest_anew if (at := slots[display]) < replay.reported
            )
        # A file taking a constant whose value changed is checked again under it.
        again.update(taker for taker in kinds.retaking if taker < replay.reported)
        # So is every file comparing with the service types the files use, where that
        # set changed (a type new to the run, or the last use of one gone).
        if types_changed:
            again.update(replay.typed)
        if not self._check_again(sorted(again - arrived_facts.keys()), facts.constants):
            return None
        if rebasing and launch_parts is not None and code_parts is not None:
            self.rebased = _Rebased(patched, launch_parts, code_parts, list(packages))
        run_wide = replay.run_wide if not typed else replace(replay.run_wide, typed_uses=typed_uses)
        patched_replay = replace(replay, graph=found, specialised=specialised, run_wide=run_wide)
        return Replayed(sorted(again), patched_replay)

    def _sort(
        self,
        kinds: _Sorted,
        replay: Replay,
        stored: KeptGraph,
        facts: _RunFacts,
        *,
        found_by: shifts.Lookups,
        typed: bool,
    ) -> bool:
        """Sort the files edited, added and removed since the build (``stored``: its tags
        and the files it had that the run has not) into ``kinds``, by what the patch
        does with each; False where one cannot be patched. ``found_by``: what finds a
        file by its name; ``typed``: the run counts the files using each service type."""
        files = self.gathered.files
        built_from = stored.tags
        constants = facts.constants  # each package's, then and now

        def launch_files() -> list[str]:
            return [source.display for source in files if source.language in LAUNCH_LANGUAGES]

        # Code files removed that take another file's constant: resolved below
        removed_taking: list[str] = []
        # The service types code added may use, and code removed (None: any, counted).
        types_added = None if typed else replay.run_wide.service_types
        types_removed: frozenset[tuple[Generation | None, str]] | None = (
            None if typed else frozenset()
        )
        for display, tag in stored.gone:
            gone = _facts_by_tag(self.cache, tag, display)
            if gone is not None and _new_code(gone, found_by, types_removed, resolved=True):
                kinds.removed_code[display] = gone
                if uses_constants(gone):
                    removed_taking.append(display)
                continue
            came = None if gone is None else _came_or_went(gone, found_by, launch_files)
            if came is None:
                return False
            kinds.naming |= came[1]
            if came[0] != _SAYS_NOTHING:
                kinds.removed_trees.append(display)

        taking: list[tuple[int, str, FileFacts]] = []  # code taking a constant: its facts then
        pairs = zip(self.inputs.tags, built_from, strict=True)
        for index, (now, then) in enumerate(pairs):
            if now == then:
                continue
            display = files[index].display
            # Read under an includer's arguments by the graph (its bytes, not its facts)
            specialised = display in replay.specialised
            if then == ADDED and specialised:
                return False
            if then == ADDED:
                added = facts.at(index) if is_facts_key(now) else None
                # Code taking another file's constant: resolved as the run resolves it,
                # from its package's C++ files now (its own check too).
                if added is not None and uses_constants(added):
                    home = self.checks.package_of(index)
                    added = constants.resolved(added, home)
                    if added is None or not self._know_headers(home, constants):
                        return False
                    facts.loaded[index] = added
                    kinds.taking_added.add(index)
                if added is not None and _new_code(added, found_by, types_added, resolved=True):
                    kinds.added_code.append(display)  # its package's programs made again
                    kinds.new_files.add(display)
                    continue
                came = None if added is None else _came_or_went(added, found_by, launch_files)
                if came is None:
                    return False
                kinds.naming |= came[1]
                if came[0] == _A_TREE:
                    kinds.tree_edits.append(display)
                if came[0] != _SAYS_NOTHING:
                    kinds.new_files.add(display)
                continue
            before = _facts_by_tag(self.cache, then, display)
            found = facts.at(index) if is_facts_key(now) else None
            if before is None or found is None:
                return False
            if specialised:
                # The trees that read it are walked again, which read it so again: where
                # its facts moved too, the places the graph keeps of it are of that read.
                if not (launch_edit(before, found) or parameter_edit(before, found)):
                    return False
                if not _patchable(before, found, wiring_kept=True):
                    return False
                kinds.tree_edits.append(display)
                continue
            # A launch or parameter file whose facts are where they were (a comment at the
            # end) changes no tree; else the trees that read it are walked again.
            if program_edit(before, found):
                kinds.building[display] = before  # its package's programs made again
                continue
            if uses_constants(before) or uses_constants(facts.raw.get(index, found)):
                taking.append((index, display, before))  # resolved once every edit is known
                continue
            moved_only = same_places(before, found)
            if (launch_edit(before, found) or parameter_edit(before, found)) and not moved_only:
                if not _patchable(before, found, wiring_kept=True):
                    return False
                kinds.tree_edits.append(display)
            elif _patchable(before, found, wiring_kept=moved_only, typed=typed):
                kinds.changed.append((display, before, found))
            else:
                return False
        then_of = constants.then_of  # the edited files' facts at the build
        then_of.update((display, then) for display, then, _ in kinds.changed)
        then_of.update((display, before) for _, display, before in taking)
        for display in kinds.added_code:
            added = facts.at(facts.slots[display])
            if added is not None:
                then_of[display] = _empty(added)
        # A code file taking another file's constant, removed: as the build resolved it,
        # from its package's C++ files then.
        for display in removed_taking:
            owner = facts.package_files().package_of(display)
            if owner is not None:
                table = constants.then(owner.directory)
                if table is None:
                    return False
                kinds.removed_code[display] = table.resolve(
                    kinds.removed_code[display], owner.directory
                )
        # A code file taking another file's constant, edited: its facts then and now with
        # their names resolved from its package's headers then and now, as the build and
        # the run resolve them, compared as any edit's; its own check, at the run's end,
        # resolves them from those headers (``RunChecks.know_constants``).
        for index, display, before in taking:
            directory = self.checks.package_of(index)
            now_raw = facts.raw.get(index, facts.arrived.get(index))
            if now_raw is None or files[index].language is not Language.CPP:
                return False
            if directory is None:
                before_then, now_resolved = before, now_raw  # the run resolves none either
            else:
                table_then, table_now = (
                    constants.then(directory),
                    constants.now(directory),
                )
                if table_then is None or table_now is None:
                    return False
                before_then = table_then.resolve(before, directory)
                now_resolved = table_now.resolve(now_raw, directory)
                if index in facts.arrived and not self._know_headers(directory, constants):
                    return False
            facts.loaded[index] = now_resolved
            if not _patchable(before_then, now_resolved, resolved=True, typed=typed):
                return False
            kinds.changed.append((display, before_then, now_resolved))
        # What the files taking a constant resolve may change where a file of their
        # package changed what it includes or the constants it defines, or came or went.
        reaching = [
            display
            for display, then, now in kinds.changed
            if then.cpp_includes != now.cpp_includes or then.constants != now.constants
        ]
        for display in kinds.added_code:  # a header added may define what a file takes
            if files[facts.slots[display]].language is Language.CPP:
                reaching.append(display)
        for display, gone in kinds.removed_code.items():  # and one removed may have
            if gone.language is Language.CPP:
                reaching.append(display)
        # The graph reads a header's constants only through the names of the files
        # taking them: those whose names resolve otherwise now are edits of their own
        # (their facts then and now resolved), checked again (``retaking``).
        if reaching:
            known_now = {display for display, _, _ in kinds.changed} | set(kinds.added_code)
            takers = constants.anew(reaching, known_now)
            if takers is None:
                return False
            for taker, names_then, names_now in takers:
                if not _patchable(names_then, names_now, resolved=True, typed=typed):
                    return False
                kinds.changed.append((files[taker].display, names_then, names_now))
                kinds.retaking.add(taker)
            kinds.changed = [
                (display, replace(then, constants=now.constants), now)
                for display, then, now in kinds.changed
            ]
        return True

    def _builders(self, found_by: shifts.Lookups, code: Sequence[str]) -> list[str] | None:
        """The build files (display paths) whose executables name one of the ``code``
        files as a source (``shifts.Lookups.builders``); None where a file is named by
        more than one, or by a build file the run has not."""
        named = [builder for path in code for builder in found_by.builders(path)]
        if not named:
            return []
        if shifts.SEVERAL in named:
            return None
        by_digest = {
            shifts.digest(source.display): source.display
            for source in self.gathered.files
            if source.language in BUILD_LANGUAGES
        }
        found = [by_digest.get(builder) for builder in named]
        return None if None in found else sorted({path for path in found if path is not None})

    def _graph_found(
        self,
        patched: Graph,
        slots: Mapping[str, int],
        reported: int,
        kept_codes: frozenset[str],
        kept_found: Mapping[int, list[tuple[str, Finding]]],
    ) -> dict[int, tuple[tuple[str, Finding], ...]]:
        """The graph rules' findings in each reported file (its index, of ``reported``):
        the patched graph's, but for the rules of ``kept_codes``, whose built findings
        (``kept_found``) stand; in the rules' order, as ``graph_findings`` lists them."""
        fresh = [rule for rule in self.rules if rule.code not in kept_codes]
        by_rule: dict[int, dict[str, list[Finding]]] = {}
        for path, items in graph_findings(patched, fresh, self.settings).items():
            at = slots.get(path)
            if at is not None and at < reported:
                for rule, item in items:
                    by_rule.setdefault(at, {}).setdefault(rule.code, []).append(item.finding)
        for index, built in kept_found.items():
            for code, finding in built:
                by_rule.setdefault(index, {}).setdefault(code, []).append(finding)
        return {
            index: tuple((rule.code, f) for rule in self.rules for f in codes.get(rule.code, ()))
            for index, codes in by_rule.items()
        }

    def _check_again(self, again: Sequence[int], constants: _Constants) -> bool:
        """Hand the files at ``again`` (none edited) to the checks, a file taking another
        file's constant with its package's headers known to them (``RunChecks.finish``
        resolves its names from those: the run took few of them); False where a C++ file
        of such a package has no facts."""
        rest = list(self.gathered.facts(again))
        resolving = {
            directory
            for index, facts, _, _ in rest
            if uses_constants(facts) and (directory := self.checks.package_of(index)) is not None
        }
        if not all(self._know_headers(directory, constants) for directory in sorted(resolving)):
            return False
        for index, facts, data, verdict in rest:
            self.checks.take(index, facts, data, verdict)
        return True

    def _know_headers(self, directory: str | None, constants: _Constants) -> bool:
        """Make the C++ files below a package's directory known to the checks, once, which
        resolve the names of the files taking another file's constant that the run checks
        from them (``RunChecks.know_constants``); False where one of them has no facts."""
        if directory is None or directory in self._headers_known:
            return True
        headers = constants.code_below(directory)
        if headers is None:
            return False
        self.checks.know_constants(found for _, found in headers)
        self._headers_known.add(directory)
        return True

    def _typed_uses_after(
        self, replay: Replay, arrived: Sequence[_Arrived]
    ) -> dict[tuple[Generation | None, str], int] | None:
        """How many files serve or call a service of each type after the edits since the
        replay's run (``arrived``: each file's facts then under its tag there, an added
        one's none); None where the replay's counts or a file's facts then are not known."""
        then = replay.run_wide.typed_uses
        if then is None:
            return None
        files = self.gathered.files
        before = (
            _facts_by_tag(self.cache, replay.tags[index], files[index].display)
            for index, _, _, _ in arrived
            if replay.tags[index] != ADDED
        )
        counts = _typed_uses_without(then, before, (facts for _, facts, _, _ in arrived))
        return None if counts is None else {key: n for key, n in counts.items() if n > 0}

    def _walked(
        self,
        whole: Graph,
        *,
        parts: LaunchParts,
        packages: Sequence[Package],
        edited: Sequence[str],
        removed: Sequence[str],
        code: Collection[str],
        facts: LazyFacts,
        programs: ProgramsAnew | None,
    ) -> tuple[tuple[Graph, LaunchParts], frozenset[str]] | None:
        """The build's whole graph with the trees that read an ``edited`` launch or
        parameter file walked again (``workspace.launch_patch``), and those of the
        ``removed`` launch files gone, over every file the build had facts of and the
        added launch files (``facts``), with the launch parts a build would leave; and
        the files the walk extracted again under an includer's arguments; None where it
        cannot be."""
        specialise = self.specialiser()
        found = launch_patched(
            whole,
            parts,
            edited,
            facts=facts,
            packages=packages,
            specialise=specialise,
            prepare=specialise.prepare,
            removed=removed,
            code=code,
            programs=programs,
        )
        return None if found is None else (found, specialise.specialised)


@dataclass
class _Sorted:
    """The files edited, added and removed since the build, by what a patch does with
    each (``GraphPatch._sort``)."""

    # Files whose facts changed (``patch.edits_of``), with their facts then and now: a
    # file taking another file's constant resolved as the build and the run resolve it,
    # those resolving otherwise now than at the build among them (``retaking``).
    changed: list[tuple[str, FileFacts, FileFacts]] = field(default_factory=list)
    tree_edits: list[str] = field(default_factory=list)  # whose trees are walked again
    # Launch files added or removed that nothing includes: trees that come or go.
    # Parameter files added or removed: the trees that read a launch file naming a file
    # of that name are walked again (and the trees handed a removed one), as
    # ``find_in_package`` may find another file by that name now (``naming``).
    removed_trees: list[str] = field(default_factory=list)
    new_files: set[str] = field(default_factory=set)  # files added that say something
    naming: set[str] = field(default_factory=set)
    # Build files that build other programs now (as they were at the build), code files
    # added, and those the build had that the run has not (as they were): their
    # packages' programs are made again (``program_patch``).
    building: dict[str, FileFacts] = field(default_factory=dict)
    added_code: list[str] = field(default_factory=list)
    removed_code: dict[str, FileFacts] = field(default_factory=dict)
    retaking: set[int] = field(default_factory=set)  # checked again by the run
    taking_added: set[int] = field(default_factory=set)  # code taking a constant, added


@dataclass
class _RunFacts:
    """Each file's facts as a patch reads them: an edited file's as the run extracted
    it, another's loaded from the cache when asked; a file taking another file's
    constant resolved as the run resolves it (``_Constants.resolved``), or, edited,
    as ``GraphPatch._sort`` resolved it."""

    files: Sequence[SourceFile]
    slots: Mapping[str, int]  # each file's index by display path
    arrived: Mapping[int, FileFacts]  # the edited files' facts, by index
    key_of: Callable[[int], str | None]  # a file's facts key (``RunInputs.facts_key``)
    cache: FactsCache
    package_of: Callable[[int], str | None]  # a file's package directory (``RunChecks``)
    package_files: Callable[[], PackageFiles]  # which package holds each file
    removed: InitVar[Mapping[str, FileFacts]]  # code files the build had, the run has not
    loaded: dict[int, FileFacts | None] = field(default_factory=dict)
    raw: dict[int, FileFacts] = field(default_factory=dict)  # of ``loaded``, as extracted
    _extracted: dict[int, FileFacts | None] = field(default_factory=dict)  # ``stored``'s
    # The constants of each package's C++ files at the build and now
    constants: _Constants = field(init=False)

    def __post_init__(self, removed: Mapping[str, FileFacts]) -> None:
        self.constants = _Constants(
            self.files, self.slots, self.package_files, self.stored, removed
        )

    def stored(self, index: int) -> FileFacts | None:
        """A file's facts as extracted (the edited files' of this run), loaded once: the
        constants of a package read every C++ file below it, and its parameters read the
        same files again (each unpickled twice before: 3 MB more at edit_constant's peak
        at 8 copies)."""
        if index in self.arrived:
            return self.arrived[index]
        if index in self._extracted:
            return self._extracted[index]
        # By index: ``RunInputs.tags`` copies every file's key (0.08 s a patch).
        tag = self.key_of(index)
        found = None if tag is None else self.cache.load(tag, self.files[index].display)
        self._extracted[index] = found
        return found

    def at(self, index: int) -> FileFacts | None:
        """A file's facts, resolved where it takes another file's constant."""
        if index in self.loaded:  # (an edited file's, resolved: ``GraphPatch._sort``)
            return self.loaded[index]
        if index in self.arrived:
            return self.arrived[index]
        known = self.stored(index)
        if known is not None and uses_constants(known):
            self.raw[index] = known
            known = self.constants.resolved(known, self.package_of(index))
        self.loaded[index] = known
        return known

    def of(self, display: str) -> FileFacts | None:
        """A file's facts by display path (``at``); None for a file the run has not."""
        at = self.slots.get(display)
        return None if at is None else self.at(at)


@dataclass
class _Constants:
    """The constants the C++ files of each package define at the build and now, by which a
    patch resolves the names of the files taking one as the build and the run do
    (``symbols``): from every C++ file below the package's directory, each directory's
    files read once (the tables then and now, and the checks, read the same)."""

    files: Sequence[SourceFile]
    slots: Mapping[str, int]  # each file's index by display path
    package_files: Callable[[], PackageFiles]  # which package holds each file
    stored_facts: Callable[[int], FileFacts | None]  # a file's facts as extracted
    removed: Mapping[str, FileFacts]  # code files the build had and the run has not
    # The edited files' facts at the build, by display path (once every edit is known)
    then_of: dict[str, FileFacts] = field(default_factory=dict)
    _below: dict[str, tuple[tuple[str, FileFacts], ...] | None] = field(default_factory=dict)
    _now: dict[str, PackageConstants | None] = field(default_factory=dict)
    _then: dict[str, PackageConstants | None] = field(default_factory=dict)

    def code_below(self, directory: str) -> tuple[tuple[str, FileFacts], ...] | None:
        """Every C++ file below a package's directory (display path) with its facts, as
        ``symbols.PackageConstants`` reads them; None where one has no facts."""
        if directory not in self._below:
            self._below[directory] = self._read_below(directory)
        return self._below[directory]

    def _read_below(self, directory: str) -> tuple[tuple[str, FileFacts], ...] | None:
        code: list[tuple[str, FileFacts]] = []
        for path in self.package_files().below(directory):
            at = self.slots[path]
            if self.files[at].language is not Language.CPP:
                continue
            found = self.stored_facts(at)
            if found is None:
                return None
            code.append((path, found))
        return tuple(code)

    def now(self, directory: str) -> PackageConstants | None:
        """The constants of the C++ files below a package's directory now."""
        if directory not in self._now:
            code = self.code_below(directory)
            self._now[directory] = None if code is None else _table(found for _, found in code)
        return self._now[directory]

    def then(self, directory: str) -> PackageConstants | None:
        """The constants of the C++ files below a package's directory at the build: those
        edited since as they were (``then_of``), those removed since too."""
        if directory not in self._then:
            code = self.code_below(directory)
            prefix = f"{directory}/" if directory else ""
            gone = (found for path, found in self.removed.items() if path.startswith(prefix))
            self._then[directory] = (
                None
                if code is None
                else _table([*(self.then_of.get(path, found) for path, found in code), *gone])
            )
        return self._then[directory]

    def resolved(self, facts: FileFacts, directory: str | None) -> FileFacts | None:
        """``facts`` with its symbols resolved by the headers of its package (display
        directory; None: the run resolves nothing there either) as they are now; None
        where a C++ file of it has no facts."""
        if directory is None:
            return facts
        table = self.now(directory)
        return None if table is None else table.resolve(facts, directory)

    def anew(
        self, reaching: Iterable[str], edited: Collection[str]
    ) -> list[tuple[int, FileFacts, FileFacts]] | None:
        """The files taking another file's constant, of a package holding a file that may
        change what they take (``reaching``: its includes or constants changed, or it
        came or went), not edited themselves (``edited``), whose names resolve otherwise
        now than at the build: each one's index and facts resolved then and now; None
        where a C++ file of those packages has no facts."""
        found: dict[int, tuple[int, FileFacts, FileFacts]] = {}
        package_files = self.package_files()
        for display in reaching:
            for package in package_files.enclosing(display):
                at = package.directory
                code, now, then = self.code_below(at), self.now(at), self.then(at)
                if code is None or now is None or then is None:
                    return None
                for path, taker in code:
                    if not uses_constants(taker) or path in edited:
                        continue
                    if package_files.package_of(path) != package:
                        continue  # resolved in its own package's, below this one
                    before, after = then.resolve(taker, at), now.resolve(taker, at)
                    if before != after:
                        found[self.slots[path]] = (self.slots[path], before, after)
        return [found[index] for index in sorted(found)]


def _table(facts: Iterable[FileFacts]) -> PackageConstants:
    table = PackageConstants()
    for found in facts:
        table.add(found)
    return table


def _depending_anew(
    built: Sequence[Package], now: Sequence[Package]
) -> tuple[list[Package], frozenset[str]] | None:
    """The packages as they are ``now`` in the build's order (``built``), and the names
    of those that depend on others than at the build; None where they differ in anything
    else (the graph is built)."""
    by_directory = {package.directory: package for package in now}
    if len(by_directory) != len(now) or by_directory.keys() != {p.directory for p in built}:
        return None
    found: list[Package] = []
    depending: set[str] = set()
    for package in built:
        anew = by_directory[package.directory]
        if replace(anew, depends=package.depends) != package:
            return None
        if anew.depends != package.depends:
            depending.add(package.name)
        found.append(anew)
    return found, frozenset(depending)


_SAYS_NOTHING, _A_TREE, _SETTINGS = "says nothing", "a tree", "settings"


def _came_or_went(
    facts: FileFacts, found_by: shifts.Lookups, launch_files: Callable[[], list[str]]
) -> tuple[str, set[str]] | None:
    """What a file added or removed since the build (``shifts``) asks of its graph, and
    the launch files whose trees are walked again for it: nothing, where it says nothing
    and is found by no name; a tree of its own (``_a_tree_alone``); a parameter file's
    settings, the trees of the launch files naming a file of its name walked again (of
    ``launch_files``, the run's); None where the graph must be built."""
    if found_by.adds_nothing(facts):
        return _SAYS_NOTHING, set()
    if facts.language is Language.PARAMETERS:
        naming = found_by.naming_of(facts.path.rpartition("/")[2], launch_files())
        return None if naming is None else (_SETTINGS, naming)
    return (_A_TREE, set()) if _a_tree_alone(facts, found_by) else None


def _new_code(
    facts: FileFacts,
    found_by: shifts.Lookups,
    service_types: Collection[tuple[Generation | None, str]] | None,
    *,
    resolved: bool = False,
) -> bool:
    """Whether a file added or removed since the build (``shifts``) is code whose
    package's programs may be made again for it (``program_patch``): code that says
    something or is found by a name, holds none of the facts launch, build and parameter
    files hold, takes no other file's constant (unless ``resolved``: its names are
    resolved as the build or the run resolves them), wires no name, names no source
    it includes, and serves or calls services only of ``service_types`` (the run's, for
    a file added; none, for one removed: another file's checks compare with those;
    None: of any, where the run counts the files that use each type)."""
    if facts.language not in CODE_LANGUAGES or found_by.adds_nothing(facts):
        return False
    types = typed_uses(facts)
    return (
        not any(getattr(facts, field) for field in NOT_CODE_FIELDS)
        and not facts.included_sources
        and not facts.rejected_fixtures
        and not wired_by(facts)
        and (resolved or not uses_constants(facts))
        and (service_types is None or types <= set(service_types))
    )


def _empty(facts: FileFacts) -> FileFacts:
    """The facts of an empty file where ``facts``' is: what a file added had before."""
    return FileFacts(facts.path, facts.language, facts.generation)


def _compiled(
    run_wide: RunWide,
    arrived: Sequence[_Arrived],
    package_of: Callable[[int], str | None],
    then_too: bool,
) -> tuple[BuiltSources | None, BuiltSources]:
    """What the build files compiled at the last run (its ``RunWide``; ``then_too``:
    else None), and now: with the files edited since (``arrived``) as they are."""
    then = BuiltSources.of(run_wide.built) if then_too else None
    taken = [
        (facts, package_of(index))
        for index, facts, _, _ in arrived
        if facts.compiled is not None or facts.included_sources
    ]
    return then, built_as_taken(run_wide, taken, {facts.path for _, facts, _, _ in arrived})


def _by_directory(package: Package) -> str:
    return package.directory


def _a_tree_alone(facts: FileFacts, found_by: shifts.Lookups) -> bool:
    """Whether a launch file added or removed (``shifts``) changes the graph only by a
    tree of its own: nothing includes it (no launch file finds a file of its name), and
    its facts hold nothing else the graph or the run's end reads (``launch_edit`` and
    ``_patchable`` from or to the facts of an empty file)."""
    empty = _empty(facts)
    return (
        not found_by.finds(facts.path)
        and launch_edit(empty, facts)
        and _patchable(empty, facts, wiring_kept=True)
    )


def _kept_findings(
    found: same_facts.GraphFound,
    edits: Mapping[str, Moved],
    rules: Sequence[Rule],
    files: Sequence[SourceFile],
) -> tuple[frozenset[str], dict[int, list[tuple[str, Finding]]]]:
    """The rules whose findings a patch keeps (``Rule.reads_code_names``) and those
    findings, from the built graph's (``found``), with the edited files' places where they
    are now; none where one of those places is no longer known."""
    kept = frozenset(rule.code for rule in rules if not rule.reads_code_names)
    moving = [move for display, spans in edits.items() if not (move := Moves(display, spans)).still]
    try:
        return kept, {
            index: [
                (code, moved_finding(finding, files[index].display, moving))
                for code, finding in items
                if code in kept
            ]
            for index, items in found.items()
        }
    except UnplacedError:
        return frozenset(), {}


def _patchable(
    before: FileFacts,
    now: FileFacts,
    *,
    wiring_kept: bool = False,
    resolved: bool = False,
    typed: bool = False,
) -> bool:
    """Whether what the run gathers from every file's facts (``RunWide``) and the checks
    of other files read is the same before and after an edit, and the file's facts are
    its own (no constant of another file in them; ``resolved``: the constants' values in
    them, as the build and the run resolve them). ``wiring_kept``: a launch file may
    wire names (RN202's), the same before and after; code may wire none. ``typed``: the
    services' types may differ, the run counting the files that use each type (and
    checking again those comparing with them where that set changes:
    ``GraphPatch._typed_uses_after``)."""
    wiring = (
        wired_by(before) == wired_by(now)
        if wiring_kept
        else not (wired_by(before) or wired_by(now))
    )
    return (
        (typed or typed_services(before) == typed_services(now))
        and wiring
        and (resolved or not (uses_constants(before) or uses_constants(now)))
    )


def with_edited(kept: Sequence[int], edited_now: Sequence[int], edited: Sequence[int]) -> list[int]:
    """A replay's files judged so (unbuilt, named by rostest; their indices), with the
    edited files' judgements of this run in place of theirs, in discovery order."""
    return sorted((set(kept) - set(edited)) | set(edited_now))


def _replay_moved(
    replay: Replay,
    arrived: Sequence[tuple[int, FileFacts, bytes | None, Verdict | None]],
    inputs: RunInputs,
    *,
    files: Sequence[SourceFile],
    cache: FactsCache,
    rules: Mapping[str, Rule],
) -> Replay | None:
    """``replay`` with the edited files' places where they are now, where the run may
    take it: each edited file (``arrived``) has a facts key and leaves it true
    (``Replay.moves``), and the rules of its graph findings are the run's (``rules``, by
    code); else None."""
    if not same_facts.codes_of(replay.graph) <= rules.keys():
        return None
    moves: list[Moves] = []
    found_by: shifts.Lookups | None = None  # made for a file the replay's run did not have
    for index, facts, _, _ in arrived:
        old = replay.tags[index]
        if inputs.facts_key(index) is None:
            return None
        if old == ADDED:  # (``shifts``)
            found_by = found_by or replay.run_wide.lookups()
            if not found_by.adds_nothing(facts):
                return None
            continue
        if not is_facts_key(old):
            return None
        display = files[index].display
        move = replay.moves(display, cache.load(old, display), facts)
        if move is None:
            return None
        moves.append(move)
    return replay.moved(moves, [source.display for source in files[: replay.reported]])


def report_replayed(
    replayed: Replayed,
    *,
    files: Sequence[SourceFile],
    checks: RunChecks,
    rules: Mapping[str, Rule],
    settings: Settings,
    registry: Registry,
) -> None:
    """The graph rules' findings of the replay in each edited reported file, made into
    diagnostics under its new text and suppressions (``report_graph``'s part per file)."""
    for index in replayed.edited:
        stored = replayed.replay.graph.get(index, ())
        facts = checks.facts_of(index)
        if not stored or facts is None:
            continue
        source = files[index]
        items = [
            (rules[code], WorkspaceFinding(source.display, finding)) for code, finding in stored
        ]
        checks.per_file[index] = file_graph_findings(
            items,
            source,
            facts,
            checks.per_file[index],
            suppressions=checks.suppressions_of.get(index, []),
            settings=settings,
            registry=registry,
        )

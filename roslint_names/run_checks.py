"""The per-file checks of a run (``RunChecks``): each file's facts taken as they arrive,
checked there or, where its verdict needs what only the whole run knows (service types,
wired names, other files' constants), at the run's end; what the graph rules and a
later run's replay then need."""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from functools import partial

from . import clean_files, shifts
from .checks import (
    Contexts,
    FileChecks,
    launch_wiring,
    not_linter_code,
    rostest_replaces,
    rule_contexts,
    service_types_of,
    typed_services,
    typed_uses,
    waits_for_the_run,
)
from .gather import Verdict
from .generation import visible_service_types
from .model import Diagnostic, FileFacts, Generation
from .reading import decode_for_display
from .same_facts import Replay, RunWide
from .suppress import Suppression
from .symbols import PackageConstants, uses_constants
from .workspace.built import BuiltSources

Progress = Callable[[int, int], None]  # (files done, files in total)


@dataclass
class RunChecks:
    """The per-file rules over each file's facts as they arrive; what the graph rules
    then need: the diagnostics in one slot per reported file (joined in discovery order,
    so arrival order never shows), each file's suppressions, and every file's facts.

    RN204 compares a service's name with every service type of the run (of the file's own
    generation), RN202 an absolute name with those the launch files of the run wire
    (``wiring``), and a C++ name held in another file's constant gets its value from the
    headers of the run (``symbols``), all known only once every file is in: files that
    serve or call a typed service, hand an endpoint an absolute name, or use such a
    constant, wait for ``finish``; the others, nearly all, are checked as they arrive.
    """

    files: int
    reported: int
    judge: FileChecks  # the per-file rules, their settings and contexts, as workers run them
    service_types: set[tuple[Generation | None, str]]
    plugin_names: frozenset[str]  # ``plugins``: the workspace's pluginlib plugin names
    keep_facts: bool
    progress: Progress | None
    package_of: Callable[[int], str | None]  # the display directory of a file's package
    visible_of: Callable[[int], frozenset[str] | None]  # its package and dependencies (RN204)
    read: Callable[[int], bytes]  # a file's bytes, for one the gathering did not read
    # Files found clean by the same checks before (``clean_files``), the verdicts of the
    # others, and each file's entry in those once its facts key is known.
    clean: frozenset[bytes] = frozenset()
    verdicts: Mapping[bytes, clean_files.Verdict] = field(default_factory=dict)
    entry_of: Callable[[int], bytes | None] = lambda index: None
    per_file: list[list[Diagnostic]] = field(init=False)
    clean_now: set[bytes] = field(default_factory=set)
    verdicts_now: dict[bytes, clean_files.Verdict] = field(default_factory=dict)
    suppressions_of: dict[int, list[Suppression]] = field(default_factory=dict)
    _all_facts: list[FileFacts | None] = field(init=False)
    _waiting: list[tuple[int, FileFacts, bytes | None]] = field(default_factory=list)
    _unresolved: list[int] = field(default_factory=list)  # files only the graph reads
    _constants: PackageConstants = field(default_factory=PackageConstants)
    _wired: set[str] = field(default_factory=set)  # absolute names launch files remap to
    _rejected: dict[str, set[str]] = field(default_factory=dict)  # package: fixture names
    _built: BuiltSources = field(default_factory=BuiltSources)
    _lookups: shifts.Lookups = field(default_factory=shifts.Lookups)  # ``RunWide``'s
    # How many files serve or call a service of each type (``RunWide.typed_uses``)
    _typed_uses: Counter[tuple[Generation | None, str]] | None = field(default_factory=Counter)
    _typed_files: set[int] = field(default_factory=set)  # reported, serving or calling one
    _done: int = 0

    def __post_init__(self) -> None:
        self.per_file = [[] for _ in range(self.reported)]
        self._all_facts = [None] * self.files

    def take(
        self, index: int, facts: FileFacts, data: bytes | None, verdict: Verdict | None = None
    ) -> None:
        """One file's facts as they arrive; ``verdict``: the per-file rules' findings where
        the worker that extracted it judged it already (``FileChecks``)."""
        if self.keep_facts:
            self._all_facts[index] = facts
        uses = typed_uses(facts)
        self.service_types.update(uses)
        if uses and self._typed_uses is not None:
            self._typed_uses.update(uses)
        if uses and index < self.reported:
            self._typed_files.add(index)
        self._constants.add(facts)
        if self.judge.wiring:
            self._wired.update(
                launch_wiring(facts, partial(self._bytes, index, data), self.judge.settings)
            )
        if facts.rejected_fixtures and (package := self.package_of(index)) is not None:
            self._rejected.setdefault(package, set()).update(facts.rejected_fixtures)
        if facts.compiled is not None or facts.included_sources:
            self._built.add(facts, self.package_of(index))
        if facts.launch_nodes or facts.includes or facts.parameter_loads or facts.executables:
            self._lookups.add(facts)
        symbols = uses_constants(facts)
        if index < self.reported:
            if waits_for_the_run(facts, self.judge.wiring):
                self._waiting.append((index, facts, data))
            elif verdict is not None:
                self._judged(index, *verdict)
            else:
                self._check_unless_clean(index, facts, data, self.judge.contexts)
        elif symbols and self.keep_facts:
            self._unresolved.append(index)
        self._done += 1
        if self.progress is not None:
            self.progress(self._done, self.files)

    def _check_unless_clean(
        self,
        index: int,
        facts: FileFacts,
        data: bytes | None,
        contexts: Contexts,
        wired: bytes = b"",
    ) -> None:
        """Check a file whose verdict depends on nothing but itself, the run's settings
        and (``wired``: their digest) the names the launch files wire; one judged before
        under the same has that verdict now."""
        entry = self.entry_of(index)
        if entry is not None and wired:
            entry = clean_files.under(entry, wired)
        if entry is None:
            self._check(index, facts, data, contexts)
        elif entry in self.clean:
            self.clean_now.add(entry)
        elif (known := self.verdicts.get(entry)) is not None:
            self._keep(index, list(known[0]), list(known[1]))
            self.verdicts_now[entry] = known
        else:
            self._remember(entry, *self._check(index, facts, data, contexts))

    def _judged(
        self, index: int, diagnostics: list[Diagnostic], suppressions: list[Suppression]
    ) -> None:
        """A verdict made elsewhere (``FileChecks``), kept as ``_check`` keeps its own."""
        self._keep(index, diagnostics, suppressions)
        entry = self.entry_of(index)
        if entry is not None:
            self._remember(entry, diagnostics, suppressions)

    def _remember(
        self, entry: bytes, diagnostics: list[Diagnostic], suppressions: list[Suppression]
    ) -> None:
        """A file's verdict for the next run (``clean_files``), as the rules made it."""
        if diagnostics or suppressions:
            self.verdicts_now[entry] = (tuple(diagnostics), tuple(suppressions))
        else:
            self.clean_now.add(entry)

    def _bytes(self, index: int, data: bytes | None) -> bytes:
        return self.read(index) if data is None else data

    def spare(
        self, displays: Sequence[str], only: Sequence[int] | None
    ) -> tuple[list[int], list[int]]:
        """Drop the findings the workspace says do not hold in their files (below), in
        the reported files at ``only`` (None: in all); the files judged unbuilt and those
        judged named by rostest (their indices), for ``--verbose``. ``displays``: the
        reported files' display paths. After the fixtures, unbuilt sources and names
        rostest replaces are spared: a finding in one must not stand for the others."""
        indices = range(len(self.per_file)) if only is None else sorted(only)
        indices = [index for index in indices if index < self.reported]
        if self._rejected:
            self._spare(displays, indices, lambda _: True, self._is_rejected)
        unbuilt = self._spare(displays, indices, not_linter_code, self._built.unbuilt)
        named = self._spare(displays, indices, rostest_replaces, self._built.started_by_rostest)
        return unbuilt, named

    def _spare(
        self,
        displays: Sequence[str],
        indices: Iterable[int],
        spared: Callable[[Diagnostic], bool],
        applies: Callable[[str, str | None], bool],
    ) -> list[int]:
        """Drop the ``spared`` findings of each file at ``indices`` the workspace says
        they do not hold for (``applies``, asked only of a file holding some); the files
        it did that to (their indices). The rules: a file its package's tests load
        expecting it to be refused (``extract.python.fixtures``: its mistakes are the
        test's point); a C++ source no build file of its package compiles
        (``workspace.built``: it never runs; the linter's own findings, RN0xx, stay); the
        node name a C++ source hands ``ros::init`` where only rostest starts what it is
        built into (roslaunch names the node, ``rostest_replaces``)."""
        changed: list[int] = []
        for index in indices:
            found = self.per_file[index]
            kept = [diagnostic for diagnostic in found if not spared(diagnostic)]
            if len(kept) != len(found) and applies(displays[index], self.package_of(index)):
                self.per_file[index] = kept
                changed.append(index)
        return changed

    def _is_rejected(self, display: str, package: str | None) -> bool:
        name = display.rpartition("/")[2]
        return package is not None and name in self._rejected.get(package, ())

    def finish(self) -> None:
        """Check the files that waited for the run's service types, wiring and constants."""
        for index in self._unresolved:
            facts = self._all_facts[index]
            if facts is not None:
                self._all_facts[index] = self._constants.resolve(facts, self.package_of(index))
        wired = frozenset(self._wired)
        contexts = self._contexts_with(wired)
        wired_digest = clean_files.digest(wired)
        # The contexts of the files that compare with service types, by their generation
        # and the packages they see, with their digest: few distinct ones in a run.
        typed: dict[tuple[Generation, frozenset[str] | None], tuple[Contexts, bytes]] = {}
        for index, extracted, data in self._waiting:
            facts = self._constants.resolve(extracted, self.package_of(index))
            if self.keep_facts:
                self._all_facts[index] = facts
            if typed_services(facts):
                context, digest = self._typed(typed, facts.generation, index, wired, wired_digest)
            else:  # it waited for the wiring or constants
                context, digest = contexts, wired_digest
            if uses_constants(extracted):
                self._check(index, facts, data, context)  # other files' constants: always
            else:  # clean under the same service types and wiring stays clean
                self._check_unless_clean(index, facts, data, context, digest)
        self._waiting.clear()
        self._unresolved.clear()

    def _contexts_with(
        self, wired: frozenset[str], known: frozenset[str] = frozenset()
    ) -> Contexts:
        judge = self.judge
        return rule_contexts(judge.registry, judge.settings, known, wired, self.plugin_names)

    def _typed(
        self,
        memo: dict[tuple[Generation, frozenset[str] | None], tuple[Contexts, bytes]],
        generation: Generation,
        index: int,
        wired: frozenset[str],
        wired_digest: bytes,
    ) -> tuple[Contexts, bytes]:
        """The contexts of file ``index``, which compares with the service types it can
        see (RN204), and the digest of those types with the wiring's."""
        key = (generation, self.visible_of(index))
        found = memo.get(key)
        if found is None:
            known = visible_service_types(service_types_of(self.service_types, generation), key[1])
            digest = clean_files.under(clean_files.digest(known), wired_digest)
            found = memo[key] = (self._contexts_with(wired, known), digest)
        return found

    def run_wide(self) -> RunWide:
        """What the run gathered from every file's facts, for a run whose facts are the
        same (``same_facts``)."""
        return RunWide(
            frozenset(self.service_types),
            frozenset(self._wired),
            self._built.given(),
            {package: frozenset(names) for package, names in self._rejected.items()},
            frozenset(self._lookups.names),
            {name: frozenset(by) for name, by in self._lookups.naming.items()},
            dict(self._lookups.named),
            None if self._typed_uses is None else dict(+self._typed_uses),
        )

    def resume(self, replay: Replay, edited: Sequence[int], paths: Collection[str]) -> None:
        """Take a run's replay (``same_facts``) for every file but the ``edited`` ones
        (``paths``: their display paths), which were taken as any: their stored
        findings, and what the run gathered from every file's facts (the edited files'
        share of it as it is now). Before ``finish``: an edited file may wait for the
        run."""
        mine = set(edited)
        for index, found in replay.found.items():
            if index not in mine:
                self.per_file[index] = list(found)
        run_wide = replay.run_wide
        # The types the files use as they are now, where the replay counts them (a patch
        # may have changed that set: ``GraphPatch._typed_uses_after``); the run's own
        # ``.srv`` files' are in already.
        uses = run_wide.typed_uses
        self.service_types.update(run_wide.service_types if uses is None else uses)
        self._typed_files |= set(replay.typed) - mine
        self._wired.update(run_wide.wired)
        # The files taken by this run are in as they are now (a build file may compile
        # other sources: ``program_patch``), the others as the replay's run had them.
        self._built = built_as_taken(run_wide, self._built.given(), paths)
        self._rejected = {package: set(names) for package, names in run_wide.rejected.items()}
        self._lookups.update(run_wide.looked_up, run_wide.naming, run_wide.named_sources)
        # The replay's counts are of the files as they are now (a patch that changed
        # them gives them so): the files taken were counted again by ``take``.
        self._typed_uses = None if uses is None else Counter(uses)

    def typed_files(self) -> tuple[int, ...]:
        """The reported files that serve or call a typed service (``Replay.typed``)."""
        return tuple(sorted(self._typed_files))

    def know_constants(self, facts: Iterable[FileFacts]) -> None:
        """The constants and includes of files the run does not take (a replay's, a
        patch's: the headers of the package of a file it checks again), for ``finish``
        to resolve the names of the files it takes."""
        for found in facts:
            self._constants.add(found)

    def facts_of(self, index: int) -> FileFacts | None:
        """File ``index``'s facts, when they were kept and it arrived."""
        return self._all_facts[index]

    def facts(self) -> list[FileFacts]:
        """Every file's facts, in discovery order (when they were kept)."""
        return [facts for facts in self._all_facts if facts is not None]

    def _check(
        self,
        index: int,
        facts: FileFacts,
        data: bytes | None,
        contexts: Contexts,
    ) -> Verdict:
        """``data`` None: the file was not read, as it holds no suppression; its text is
        needed only for findings (their lines, fixes, whether it is test code). The
        verdict, as the rules made it."""
        text = "" if data is None else decode_for_display(data)
        diagnostics, found = self._check_text(facts, text, contexts)
        if data is None and diagnostics:
            diagnostics, found = self._check_text(
                facts, decode_for_display(self.read(index)), contexts
            )
        self._keep(index, diagnostics, found)
        return diagnostics, found

    def _keep(
        self, index: int, diagnostics: list[Diagnostic], suppressions: list[Suppression]
    ) -> None:
        if diagnostics:
            # Asked only of files with findings: proposals group answers by package.
            package = self.package_of(index)
            diagnostics = [replace(diagnostic, package=package) for diagnostic in diagnostics]
        self.per_file[index] = diagnostics
        if suppressions:
            self.suppressions_of[index] = suppressions

    def _check_text(self, facts: FileFacts, text: str, contexts: Contexts) -> Verdict:
        return self.judge.check_text(facts, text, contexts)


def built_as_taken(
    run_wide: RunWide, taken: Iterable[tuple[FileFacts, str | None]], paths: Collection[str]
) -> BuiltSources:
    """What the build files compile: as the replay's run had them (``run_wide``), but
    for the files this run took (``paths``), as they are now (``taken``: those of them
    that compile or include sources, with their packages' directories)."""
    built = BuiltSources.of(given for given in run_wide.built if given[0].path not in paths)
    for facts, package in taken:
        built.add(facts, package)
    return built

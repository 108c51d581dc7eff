"""Command line: arguments in, exit code out.

Exit 0 clean, 1 findings, 2 usage, configuration or internal error.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, NoReturn, TextIO

from . import __version__
from .cache import FactsCache
from .cache import default_directory as default_cache_directory
from .catalog import load_doc, rule_meta
from .collection import rare_collections
from .config import (
    Overrides,
    Settings,
    apply_overrides,
    enabled_codes,
    load_settings,
)
from .conventions import propose
from .conventions import render as render_proposals
from .discover import (
    SourceFile,
    classify,
    discover,
    display_path,
    text_files,
    workspace_root,
)
from .engine import LintResult, RunOptions, lint, lintable
from .errors import UserError
from .generation import PackageGenerations
from .model import Diagnostic, FileFacts, Generation, Kind, Language
from .names import Problem, check_name
from .progress import ProgressBar
from .progress import wanted as progress_wanted
from .registry import Registry, load_registry
from .report import FORMATS, ReportContext, render, statistics, summary
from .report.base import plural
from .workspace.graph import launched_by

if TYPE_CHECKING:
    # The editing modules are imported by the options that edit, read a baseline or
    # compare with git: a plain check (a re-run of unchanged files) never needs them.
    from .editing import fixing
    from .editing.files import Snapshot

EXIT_CLEAN = 0
EXIT_FINDINGS = 1
EXIT_ERROR = 2
COMMANDS = ("check", "graph", "validate", "rule", "rules", "server")


class UsageError(UserError):
    pass


def entry() -> NoReturn:
    """The ``roslint-names`` command and ``python -m roslint_names``: ``main``, then the
    process ends without taking its objects apart one by one.

    A run that built the graph leaves every file's facts and the graph to the collector
    (some of them in cycles): at 8 copies of realws, 1.9 million objects whose collection
    at interpreter exit cost 1.0 s after the report was out, a tenth of the run. What
    the run writes into the cache and the user's tree is written and closed before
    ``main`` returns (``cache.finish``, ``editing.files``); the worker processes are
    joined by then (``workers.Dispatcher``); output streams are flushed here. mypy ends
    its runs so (``mypy.util.hard_exit``). A caller of ``main`` (the tests, a program
    embedding the linter) gets the exit code back as before; an error exit
    (``SystemExit``) goes the usual way."""
    code = main()
    for stream in (sys.stdout, sys.stderr):
        try:
            if not stream.closed:  # the language server's stdout, closed at the client's exit
                stream.flush()
        except BrokenPipeError:  # the reader went away after the report (`... | head`)
            code = EXIT_ERROR
    os._exit(code)


def main(argv: Sequence[str] | None = None) -> int:
    arguments = list(sys.argv[1:] if argv is None else argv)
    if not arguments or arguments[0] not in (*COMMANDS, "-h", "--help", "--version"):
        arguments.insert(0, "check")  # `roslint-names PATH...` is `roslint-names check PATH...`
    parser = _parser()
    options = parser.parse_args(arguments)
    try:
        with rare_collections():
            return int(options.run(options))
    except UserError as error:  # settings, arguments or files the user can mend
        _fail(str(error))
    except KeyboardInterrupt:
        _fail("interrupted")
    except BrokenPipeError:
        # The reader went away (`roslint-names ... | head`); that is not our error.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_ERROR
    except Exception as error:  # never a traceback for the user, but always a way to report it
        if os.environ.get("ROSLINT_NAMES_DEBUG"):
            raise
        _fail(
            f"internal error: {type(error).__name__}: {error}\n"
            "Please report it with the file that caused it; "
            "set ROSLINT_NAMES_DEBUG=1 for the traceback."
        )


def _fail(message: str) -> NoReturn:
    print(f"roslint-names: error: {message}", file=sys.stderr)
    raise SystemExit(EXIT_ERROR)


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="roslint-names",
        description="Static linter for ROS graph-resource names.",
        epilog="`roslint-names PATH...` is short for `roslint-names check PATH...`.",
    )
    parser.add_argument("--version", action="version", version=f"roslint-names {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    _add_check(commands.add_parser("check", help="lint files and directories (the default)"))
    _add_graph(commands.add_parser("graph", help="print the workspace's computation graph"))
    _add_validate(commands.add_parser("validate", help="judge names by the ROS grammar alone"))
    rule = commands.add_parser("rule", help="print one rule's catalog page")
    rule.add_argument("rule", metavar="CODE|SLUG")
    rule.set_defaults(run=_run_rule)
    rules = commands.add_parser("rules", help="list every rule")
    rules.set_defaults(run=_run_rules)
    server = commands.add_parser("server", help="speak the Language Server Protocol on stdio")
    server.set_defaults(run=_run_server)
    return parser


def _add_check(check: argparse.ArgumentParser) -> None:
    check.add_argument("paths", nargs="*", type=Path, default=[Path(".")], metavar="PATH")
    check.add_argument("--format", choices=FORMATS, default="text")
    check.add_argument("--output", "-o", type=Path, help="write the report to FILE")
    check.add_argument("--config", type=Path, help="use this config file, not the nearest one")
    check.add_argument("--select", type=_codes, help="check only these codes, prefixes or slugs")
    check.add_argument("--extend-select", type=_codes, default=(), help="check these as well")
    check.add_argument("--ignore", type=_codes, default=(), help="do not check these")
    check.add_argument(
        "--extend-exclude",
        action="append",
        default=[],
        metavar="PATTERN",
        help="skip files matching this gitignore pattern too (repeatable)",
    )
    check.add_argument("--ros", choices=("1", "2", "auto"), help="generation when undecided")
    check.add_argument("--max-depth", type=int, help="deepest allowed name (RN201)")
    check.add_argument("--exit-zero", action="store_true", help="exit 0 even with findings")
    check.add_argument("--statistics", action="store_true", help="print counts per rule")
    check.add_argument("--show-source", action="store_true", help="show the source line")
    check.add_argument(
        "--include-suppressed",
        action="store_true",
        help="SARIF: include suppressed results, marked with `suppressions`",
    )
    check.add_argument(
        "--baseline",
        type=Path,
        metavar="FILE",
        help="report only findings not recorded in FILE (see --write-baseline)",
    )
    check.add_argument(
        "--write-baseline",
        type=Path,
        metavar="FILE",
        help="record the current findings in FILE and exit 0",
    )
    check.add_argument(
        "--fix",
        action="store_true",
        help="apply the safe fixes ([*] in the report), then report what is left",
    )
    check.add_argument(
        "--diff",
        action="store_true",
        help="print the fixes --fix would make as a unified diff; write nothing",
    )
    check.add_argument(
        "--unsafe-fixes",
        action="store_true",
        help="with --fix or --diff: also the fixes that may change what the system does",
    )
    check.add_argument(
        "--add-noqa",
        action="store_true",
        help="write a suppression comment for every current finding, in its file's form",
    )
    check.add_argument(
        "--changed-since",
        metavar="REV",
        help="report only findings on lines added or modified since git revision REV",
    )
    check.add_argument(
        "--no-cache", action="store_true", help="do not read or write the facts cache"
    )
    check.add_argument(
        "--cache-dir",
        type=Path,
        metavar="DIR",
        help="keep the facts cache here (default: $XDG_CACHE_HOME/roslint-names "
        "or ~/.cache/roslint-names)",
    )
    check.add_argument(
        "--jobs", "-j", type=_jobs, default=0, help="worker processes (0: all cores)"
    )
    check.add_argument(
        "--verbose",
        "-v",
        action="store_true",
        help="say on stderr where the cache is, what it served and how many workers ran",
    )
    check.set_defaults(run=_run_check)


def _add_graph(graph: argparse.ArgumentParser) -> None:
    graph.add_argument("paths", nargs="*", type=Path, default=[Path(".")], metavar="PATH")
    graph.add_argument("--format", choices=("dot", "mermaid", "json"), default="dot")
    graph.add_argument("--output", "-o", type=Path, help="write the graph to FILE")
    graph.add_argument("--config", type=Path, help="use this config file, not the nearest one")
    graph.add_argument("--ros", choices=("1", "2", "auto"), help="generation when undecided")
    graph.add_argument(
        "--no-cache", action="store_true", help="do not read or write the facts cache"
    )
    graph.add_argument("--cache-dir", type=Path, metavar="DIR", help="keep the facts cache here")
    graph.add_argument(
        "--jobs", "-j", type=_jobs, default=0, help="worker processes (0: all cores)"
    )
    graph.set_defaults(run=_run_graph)


def _add_validate(validate: argparse.ArgumentParser) -> None:
    validate.add_argument("names", nargs="+", metavar="NAME", help="names, or - for stdin")
    validate.add_argument("--ros", choices=("1", "2"), default="2")
    validate.add_argument("--kind", choices=[kind.value for kind in Kind], default="topic")
    validate.add_argument("--format", choices=("text", "json"), default="text")
    validate.set_defaults(run=_run_validate)


def _codes(text: str) -> tuple[str, ...]:
    return tuple(code.strip() for code in text.split(",") if code.strip())


def _jobs(text: str) -> int:
    try:
        jobs = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if jobs < 0:
        raise argparse.ArgumentTypeError("must be 0 (all cores) or more")
    return jobs


def _run_check(options: argparse.Namespace) -> int:
    # Started now, so "the run lasts more than a second" counts discovery too.
    bar = ProgressBar(sys.stderr, enabled=progress_wanted(sys.stderr, os.environ))
    overrides = Overrides(
        ros=_generation(options.ros),
        select=options.select,
        extend_select=options.extend_select,
        ignore=options.ignore,
        max_depth=options.max_depth,
        extend_exclude=tuple(options.extend_exclude),
    )
    cache = _facts_cache(options)
    registry, settings, sources, workspace, without_manifest = _prepare(options, overrides, cache)
    cwd = Path.cwd()
    # Renames are offered when unsafe fixes are asked for: they need every file's facts
    # and a search of the workspace's text (``renames``), which a warm run must not pay
    # for; kept from the start when no cache can give them again.
    renaming = options.unsafe_fixes
    writing = options.fix or options.diff or options.add_noqa
    snapshot: Snapshot | None = None
    if writing or renaming:
        from .editing.files import Snapshot

        snapshot = Snapshot(cwd, _linted_roots(options.paths, cwd, renaming=renaming))
    if writing:
        assert snapshot is not None
        # The bytes the edits will be computed from, as the run reads them first: a file
        # edited while the run goes on is then refused, never spliced.
        snapshot.remember(source.display for source in lintable(sources))
        if renaming:
            snapshot.remember(source.display for source in lintable(workspace))
    try:
        run = RunOptions(
            jobs=options.jobs, cache=cache, progress=bar, without_manifest=without_manifest
        )
        want_facts = renaming and cache is None
        result = lint(sources, settings, registry, run, context=workspace, want_facts=want_facts)
        diagnostics: Sequence[Diagnostic] = result.diagnostics
        if renaming and any(diagnostic.renaming for diagnostic in diagnostics):
            assert snapshot is not None
            facts = (
                result.facts
                or lint(sources, settings, registry, run, context=workspace, want_facts=True).facts
            )
            diagnostics = _resolve_renames(snapshot, settings, diagnostics, facts)
    finally:
        bar.close()  # erased before the report and the summary are written
    if options.verbose:
        _print_run_details(result, cache, options.cache_dir or default_cache_directory())
        from .fates import fates, unchecked  # what became of each file: --verbose only

        # Of the files named one by one: a directory's thousands of files would cost a
        # read each, and the question is "why does my file show nothing?".
        named = {(cwd / path).absolute() for path in options.paths if (cwd / path).is_file()}
        # Not a ``Path`` for each of a named directory's files: 0.35 s at 77,000 of them.
        linted = [source for source in lintable(sources) if source.path in named] if named else []
        for display, fate in fates(linted, settings):
            print(f"roslint-names: {display}: {fate}", file=sys.stderr)
        for path in sorted(named - {source.path for source in linted}):
            print(f"roslint-names: {display_path(path, cwd)}: {unchecked(path)}", file=sys.stderr)
    if options.changed_since is not None:
        from .editing.changes import changed_lines, gate

        diagnostics = gate(diagnostics, changed_lines(options.changed_since, cwd), cwd)
    if options.write_baseline is not None:
        from .editing import baseline

        count = baseline.write(options.write_baseline, diagnostics, cwd)
        print(f"roslint-names: wrote {count} findings to {options.write_baseline}", file=sys.stderr)
        return EXIT_CLEAN
    if options.baseline is not None:
        diagnostics = _apply_baseline(options, diagnostics, cwd)
    if options.add_noqa:
        assert snapshot is not None
        return _add_noqa(diagnostics, snapshot)
    if options.fix or options.diff:
        from .editing import fixing

        assert snapshot is not None
        fixed = fixing.plan(
            diagnostics,
            unsafe=options.unsafe_fixes,
            snapshot=snapshot,
            verify=_verifier(settings, registry, cwd),
        )
        for path, why in fixed.refused:
            print(f"roslint-names: {path}: {why}", file=sys.stderr)
        if options.diff:
            _write(fixed.diff(), options.output)
            if not fixed.writes:
                print("roslint-names: no fix to show", file=sys.stderr)
            _say_what_was_not_fixed(diagnostics, options.unsafe_fixes)
            return EXIT_FINDINGS if fixed.writes else EXIT_CLEAN
        fixing.write(fixed, snapshot)
        for change in fixed.writes:
            print(f"roslint-names: wrote {change.display}", file=sys.stderr)
        made = f"{plural(fixed.fixed, 'finding')} in {plural(len(fixed.writes), 'file')}"
        print(f"roslint-names: fixed {made}", file=sys.stderr)
        _say_what_was_not_fixed(diagnostics, options.unsafe_fixes)
        # What is left, as a run after the fixes reports it.
        return int(_run_check(argparse.Namespace(**{**vars(options), "fix": False})))
    metas = [rule_meta(rule) for rule in registry.rules]
    enabled = enabled_codes(settings, registry)
    output_is_terminal = options.output is None and sys.stdout.isatty()
    context = ReportContext(
        tool_version=__version__,
        root=cwd,
        show_source=options.show_source,
        color=output_is_terminal and "NO_COLOR" not in os.environ,
        include_suppressed=options.include_suppressed,
        baseline=options.baseline is not None,
        files=_checked_files(sources, result),
    )
    proposals = propose(diagnostics)
    if options.statistics:
        report = statistics(diagnostics, metas)
        if proposals:
            report += "\n" + render_proposals(proposals)
    else:
        report = render(
            options.format,
            diagnostics,
            [meta for meta in metas if meta.code in enabled],
            context,
        )
    _write(report, options.output)
    print(summary(diagnostics, result.files_checked), file=sys.stderr)
    if proposals and not options.statistics and settings.source is None:
        # A project that has stated nothing yet: say which findings are one decision.
        print(render_proposals(proposals), end="", file=sys.stderr)
    has_findings = any(not d.suppressed and not d.baselined for d in diagnostics)
    return EXIT_FINDINGS if has_findings and not options.exit_zero else EXIT_CLEAN


def _checked_files(sources: Sequence[SourceFile], result: LintResult) -> tuple[str, ...]:
    """The display paths of the files the run checked (what ``files_checked`` counts)."""
    skipped = {path for path, _ in result.skipped}
    return tuple(source.display for source in lintable(sources) if source.display not in skipped)


def _linted_roots(paths: Sequence[Path], cwd: Path, *, renaming: bool) -> list[Path]:
    """Where a fix may write: the paths named and, for a rename, the workspace of each
    file named (a rename reaches every use of the name in it)."""
    absolute = [(cwd / path).absolute() for path in paths]
    if not renaming:
        return absolute
    return sorted(
        {
            path if path.is_dir() else workspace_root(path) or path
            for path in absolute
            if path.exists()
        }
    )


def _say_what_was_not_fixed(diagnostics: Sequence[Diagnostic], unsafe: bool) -> None:
    """After --fix or --diff: the fixes left for --unsafe-fixes, and each rename held back
    with its reason (ruff's "N hidden fixes can be enabled with --unsafe-fixes")."""
    reported = [d for d in diagnostics if not d.suppressed and not d.baselined]
    if not unsafe:
        waiting = sum(
            1
            for d in reported
            if d.renaming is not None or (d.edit is not None and not d.edit.safe)
        )
        if waiting:
            print(
                f"roslint-names: {waiting} more {'fix' if waiting == 1 else 'fixes'} with "
                "--unsafe-fixes: they change a name the running system uses (review them "
                "with --diff --unsafe-fixes)",
                file=sys.stderr,
            )
    for diagnostic in reported:
        if diagnostic.held_back:
            where = f"{diagnostic.path}:{diagnostic.span.line}"
            print(
                f"roslint-names: {where}: {diagnostic.code} rename not offered, "
                f"{diagnostic.held_back}",
                file=sys.stderr,
            )


def _resolve_renames(
    snapshot: Snapshot,
    settings: Settings,
    diagnostics: Sequence[Diagnostic],
    facts: Sequence[FileFacts],
) -> list[Diagnostic]:
    """The diagnostics with each rename offered or dropped, after a search of the
    workspaces the snapshot may write in (the directories named, the workspace of each
    file named)."""
    from .editing import renames

    cwd = snapshot.cwd
    files = text_files(list(snapshot.roots), settings.exclude, settings.root, cwd)

    def read(display: str) -> bytes | None:
        data, _ = snapshot.read(display)
        if data is not None and len(data) > settings.max_file_size:
            return None  # as ``read_file`` has it: too large to be searched
        return data

    displays = [display_path(file, cwd) for file in files]
    return renames.resolve(diagnostics, facts, displays, read)


def _verifier(settings: Settings, registry: Registry, cwd: Path) -> fixing.Verify:
    """Re-reads a fixed file: its parse errors and its per-file findings (code, line)."""
    from .checks import recheck  # a check run that writes no fix never needs it

    packages = PackageGenerations()

    def verify(path: str, data: bytes) -> tuple[int, set[tuple[str, int]]]:
        return recheck(
            cwd / path, path, data, settings=settings, registry=registry, packages=packages
        )

    return verify


def _add_noqa(diagnostics: Sequence[Diagnostic], snapshot: Snapshot) -> int:
    """Write a suppression for every reported diagnostic; 1 when some could not be."""
    from .editing.noqa import add_noqa

    languages = {d.path: classify(snapshot.cwd / d.path) for d in diagnostics}
    outcome = add_noqa(diagnostics, languages, snapshot)
    snapshot.replace_all(outcome.writes)
    print(
        f"roslint-names: added {outcome.added} suppression comments in {outcome.files} files",
        file=sys.stderr,
    )
    for path, line, why in outcome.left:
        print(f"roslint-names: {path}:{line}: not suppressed: {why}", file=sys.stderr)
    return EXIT_FINDINGS if outcome.left else EXIT_CLEAN


def _apply_baseline(
    options: argparse.Namespace, diagnostics: Sequence[Diagnostic], cwd: Path
) -> Sequence[Diagnostic]:
    """The diagnostics with those the baseline holds marked; ``--verbose`` names the
    entries that matched nothing (fixed since, or their line edited)."""
    from .editing import baseline

    path: Path = options.baseline
    applied = baseline.apply(diagnostics, baseline.load(path), path.absolute().parent, cwd)
    if options.verbose:
        for entry in applied.stale:
            print(
                f"roslint-names: baseline {path}: no longer found: {entry.path}: "
                f"{entry.code} '{entry.name}' (--write-baseline drops it)",
                file=sys.stderr,
            )
    return applied.diagnostics


def _generation(option: str | None) -> Generation | None:
    return None if option in (None, "auto") else Generation(int(option))


def _prepare(
    options: argparse.Namespace,
    overrides: Overrides,
    cache: FactsCache | None,
    *,
    for_graph: bool = False,
) -> tuple[Registry, Settings, list[SourceFile], list[SourceFile], frozenset[str]]:
    """The rules, the settings, the files named and the rest of their workspace (their
    walks' listings kept in ``cache``), and the directories the walks found no
    package.xml in."""
    registry = load_registry()
    cwd = Path.cwd()
    start = config_search_start(options.paths, cwd)
    settings = apply_overrides(load_settings(options.config, start, registry), overrides, registry)
    if settings.source is None and _files_below(options.paths, cwd):
        # No config file: a run over files here (pre-commit's) judges them from where
        # `roslint-names check .` here does (``test_code.is_example_code`` looks up the
        # folders to the root), not from their own folder.
        settings = replace(settings, root=cwd.resolve())
    warnings: list[str] = []  # what the walks passed over: said, never skipped in silence
    without_manifest: set[str] = set()

    def walk(paths: Sequence[Path]) -> list[SourceFile]:
        return discover(
            paths,
            settings.exclude,
            settings.root,
            cwd,
            warnings,
            cache=cache,
            without_manifest=without_manifest,
        )

    sources = walk(options.paths)
    workspace = _workspace_context(
        options.paths, settings, registry, cwd, walk, for_graph=for_graph
    )
    for warning in dict.fromkeys(warnings):  # a directory both walks pass over: said once
        print(f"roslint-names: warning: {warning}", file=sys.stderr)
    return registry, settings, sources, workspace, frozenset(without_manifest)


def _workspace_context(
    paths: Sequence[Path],
    settings: Settings,
    registry: Registry,
    cwd: Path,
    walk: Callable[[Sequence[Path]], list[SourceFile]],
    *,
    for_graph: bool,
) -> list[SourceFile]:
    """For a run over files (what pre-commit does): the rest of their workspaces, which
    the graph rules need to see, and whose launch files say which absolute names are
    wired (RN202). Nothing is reported in them, but what their ``walk`` passes over is
    said with what the walk of the files named passes over: the graph does not see it. A
    run over directories is taken to name its workspace."""
    enabled = enabled_codes(settings, registry)
    workspace_rules = any(
        (rule.check_workspace or rule.reads_wiring or rule.reads_plugins) and rule.code in enabled
        for rule in registry.rules
    )
    if not (workspace_rules or for_graph):
        return []
    files = [(cwd / path).absolute() for path in paths if (cwd / path).is_file()]
    roots = sorted({root for path in files if (root := workspace_root(path)) is not None})
    if not roots:
        return []
    return walk(roots)


def _run_server(options: argparse.Namespace) -> int:
    try:
        from .lsp import serve  # pygls is imported only by the server
    except ImportError as error:
        raise UsageError(
            f"the language server needs pygls ({error}); install roslint-names[server]"
        ) from error
    serve()
    return EXIT_CLEAN


def _run_graph(options: argparse.Namespace) -> int:
    from .render import RENDERERS  # only this command draws graphs

    overrides = Overrides(ros=_generation(options.ros))
    cache = _facts_cache(options)
    registry, settings, sources, workspace, without_manifest = _prepare(
        options, overrides, cache, for_graph=True
    )
    run = RunOptions(jobs=options.jobs, cache=cache, without_manifest=without_manifest)
    result = lint(sources, settings, registry, run, context=workspace, want_graph=True)
    assert result.graph is not None
    graph = result.graph
    launch_files = _launch_files_named(options.paths, sources)
    if launch_files:
        graph = launched_by(graph, launch_files)
    _write(RENDERERS[options.format](graph), options.output)
    return EXIT_CLEAN


def _launch_files_named(paths: Sequence[Path], sources: Sequence[SourceFile]) -> frozenset[str]:
    """The display paths of the launch files ``graph`` was given, when every path given
    is one: then it draws what they start, not their whole workspace."""
    named = {source.display for source in sources if _is_launch_file(source)}
    if not named or len(named) != len(sources) or any(Path(p).is_dir() for p in paths):
        return frozenset()
    return frozenset(named)


def _is_launch_file(source: SourceFile) -> bool:
    from .extract.python.extract import is_launch_path  # the graph command's only

    return source.language in (Language.LAUNCH_XML, Language.LAUNCH_YAML) or (
        source.language is Language.PYTHON and is_launch_path(source.display)
    )


def _facts_cache(options: argparse.Namespace) -> FactsCache | None:
    if options.no_cache:
        return None
    directory = options.cache_dir or default_cache_directory()
    return None if directory is None else FactsCache(directory.absolute())


def _print_run_details(
    result: LintResult, cache: FactsCache | None, directory: Path | None
) -> None:
    where = "off" if cache is None else str(cache.directory)
    if cache is None and directory is None:
        where = "off (no home directory)"
    # Files read: those checked plus, in a per-file run, the rest of their workspace.
    files = result.files_cached + result.files_extracted
    if result.reused:
        done = f"no file changed since a run over the same {files} files: its result reused"
    else:
        done = (
            f"{result.files_cached} of {files} files from the cache, "
            f"{result.files_extracted} extracted by "
            + (f"{result.workers} worker processes" if result.workers else "this process")
        )
    print(f"roslint-names: cache {where}; {done}", file=sys.stderr)
    for path, reason in result.skipped:
        print(f"roslint-names: skipped {path}: {reason}", file=sys.stderr)
    for path in result.unbuilt:
        print(
            f"roslint-names: {path}: no build file of its package compiles it; "
            "its findings about names are not reported",
            file=sys.stderr,
        )
    for path in result.rostest_named:
        print(
            f"roslint-names: {path}: only rostest starts what it is built into, naming the "
            "node; the node name it hands ros::init is not judged",
            file=sys.stderr,
        )
    for problem in cache.problems if cache is not None else []:
        print(f"roslint-names: warning: {problem}", file=sys.stderr)


def _files_below(paths: Sequence[Path], cwd: Path) -> bool:
    """Whether every path names a file below ``cwd``."""
    named = [(cwd / path).absolute() for path in paths]
    return bool(named) and all(path.is_relative_to(cwd) and os.path.isfile(path) for path in named)


def config_search_start(paths: Sequence[Path], cwd: Path) -> Path:
    """Where the search for a config file begins: the deepest directory holding every path.

    `roslint-names examples/` then uses `examples/roslint-names.toml`, and a pre-commit run
    over files of one package finds that package's config, as ruff and flake8 users expect.
    """
    directories = [
        absolute if _is_directory(absolute) else absolute.parent
        for absolute in ((cwd / path).absolute() for path in paths)
    ]
    try:
        return Path(os.path.commonpath(directories))
    except ValueError:
        return cwd


def _is_directory(path: Path) -> bool:
    """``Path.is_dir``, False where the path cannot be looked at (a directory above it that
    cannot be searched): discovery then says what is wrong with it, as for any path."""
    try:
        return path.is_dir()
    except OSError:
        return False


def _write(report: str, output: Path | None) -> None:
    if output is None:
        _print(report, end="")
        return
    # A CI's results directory may not exist yet (catkin's, colcon's per package):
    # ``write_new`` makes it.
    from .editing.files import write_new

    write_new(output, report.encode("utf-8"), "the report")


def _print(text: str, end: str = "\n") -> None:
    """Reports are UTF-8 whatever the locale says, as their formats promise."""
    sys.stdout.flush()
    sys.stdout.buffer.write((text + end).encode("utf-8"))
    sys.stdout.buffer.flush()


def _run_validate(options: argparse.Namespace) -> int:
    names = _read_names(options.names, sys.stdin)
    kind = Kind(options.kind)
    generation = Generation(int(options.ros))
    all_valid = True
    for name in names:
        problem = check_name(name, kind, generation)
        valid = problem is None or not problem.fatal
        all_valid = all_valid and valid
        if options.format == "json":
            record = {
                "name": name,
                "kind": kind.value,
                "ros": generation.value,
                "valid": valid,
                "code": problem.code if problem else None,
                "reason": problem.reason if problem else None,
                "index": problem.index if problem else None,
            }
            _print(json.dumps(record, ensure_ascii=False))
        else:
            _print(_validation_line(name, kind, generation, problem))
    return EXIT_CLEAN if all_valid else EXIT_FINDINGS


def _validation_line(name: str, kind: Kind, generation: Generation, problem: Problem | None) -> str:
    where = f"ROS {generation.value} {kind.value}"
    if problem is None:
        return f"{name!r}: valid {where} name"
    verdict = "invalid" if problem.fatal else "accepted, but"
    fix = f"; use {problem.suggestion!r}" if problem.suggestion else ""
    return f"{name!r}: {verdict} {where} name: {problem.reason}{fix} [{problem.code}]"


def _read_names(arguments: Sequence[str], stdin: TextIO) -> list[str]:
    if list(arguments) != ["-"]:
        if "-" in arguments:
            raise UsageError("validate: '-' (read names from stdin) must be the only argument")
        return list(arguments)
    data = stdin.buffer.read().decode("utf-8", errors="replace")
    lines = data.split("\n")
    if lines and lines[-1] == "":
        lines.pop()  # the final line break ends the last name; it does not start a new one
    # Only the line break is removed: "\r\n" ends a line, spaces are part of the name.
    return [line[:-1] if line.endswith("\r") else line for line in lines]


def _run_rule(options: argparse.Namespace) -> int:
    registry = load_registry()
    rule = registry.by_code_or_name(options.rule)
    if rule is None:
        raise UsageError(f"no rule {options.rule!r}; `roslint-names rules` lists them")
    _print(load_doc(rule.code, rule.name).markdown, end="")
    return EXIT_CLEAN


def _run_rules(options: argparse.Namespace) -> int:
    _print(rules_table(load_registry()))
    return EXIT_CLEAN


def rules_table(registry: Registry) -> str:
    """Code, slug, default severity, whether it judges test code by default, and summary
    of every rule, as a Markdown table."""
    lines = [
        "| Code | Name | Default severity | In test code | Summary |",
        "|---|---|---|---|---|",
    ]
    for rule in registry.rules:
        severity = rule.severity.value
        if rule.ros1_severity is not None and rule.ros1_severity != rule.severity:
            severity += f" (ROS 1: {rule.ros1_severity.value})"
        if not rule.enabled_by_default:
            severity += ", off by default"
        tests = "yes" if rule.judges_test_code else "no"
        lines.append(f"| {rule.code} | {rule.name} | {severity} | {tests} | {rule.summary} |")
    return "\n".join(lines)


if __name__ == "__main__":
    entry()

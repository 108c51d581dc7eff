"""The real CLI over a copy of the example workspace with one file damaged at a time.

Each input replaces one file of ``examples/`` (or adds a ``setup.py`` / ``setup.cfg``, which
the examples lack) with random bytes or a damaged version of it, and runs ``check`` (over
the workspace or, as pre-commit does, over that one file) or ``graph`` in-process, twice
with one facts cache: the graph rules see the damaged file's facts beside the real ones,
and the second run serves them from the cache. Invariants: exit code 0 or 1 (``graph``: 0),
nothing on stderr but the summary line (no traceback, no warning), UTF-8 output, at most
one RN001 for the damaged file, and the same output from the cache as from extraction.
"""

from __future__ import annotations

import io
import json
import os
import re
import shutil
import warnings
from contextlib import redirect_stderr, redirect_stdout
from dataclasses import dataclass
from pathlib import Path

import pytest
from conftest import chdir
from hypothesis import strategies as st

from fuzz.checks import QUIET_WARNINGS
from fuzz.inputs import REAL_FILES, ROOT
from fuzz.runner import fuzz, report_failures
from fuzz.strategies import MAX_RANDOM_BYTES, damaged
from roslint_names.cli import main
from roslint_names.model import Language

EXAMPLES = ROOT / "examples"
CONFIG = "roslint-names.toml"  # a broken config is a usage error (exit 2): not fuzzed here
ADDED = {
    "src/fleet_bringup/setup.py": REAL_FILES[Language.SETUP_PY][0][1],
    "src/fleet_bringup/setup.cfg": REAL_FILES[Language.SETUP_CFG][0][1],
}
ORIGINALS: dict[str, bytes] = {
    path.relative_to(EXAMPLES).as_posix(): path.read_bytes()
    for path in sorted(EXAMPLES.rglob("*"))
    if path.is_file() and path.name != CONFIG
} | ADDED
_SUMMARY = re.compile(
    r"Found \d+ problems? \(.*\) in \d+ files? \(\d+ files? checked\)\."
    r"|All checks passed: \d+ files? checked, no problems\."
)
# --verbose: where the cache is, files skipped (too large, binary), cache problems, what
# became of each file, and the sources whose findings the workspace spares (a build file
# fuzzed away leaves its package's sources compiled by nothing).
_VERBOSE = re.compile(
    r"roslint-names: (?:cache|skipped|warning:) .*"
    r"|roslint-names: \S.*: (?:checked|not (?:parsed|checked): .*|(?:test|example) code: .*)"
    r"|roslint-names: \S.*: no build file of its package compiles it; its findings about "
    r"names are not reported"
    r"|roslint-names: \S.*: only rostest starts what it is built into, naming the node; "
    r"the node name it hands ros::init is not judged"
)


@dataclass(frozen=True)
class CliSample:
    file: str  # relative to the workspace
    kind: str
    origin: str
    data: bytes
    arguments: tuple[str, ...]


@dataclass(frozen=True)
class Outcome:
    exit_code: int
    stdout: str
    stderr: str
    warnings: tuple[str, ...]


def _without_nul(data: bytes, strip: bool) -> bytes:
    return data.replace(b"\0", b"") if strip else data


@st.composite
def cli_samples(draw: st.DrawFn) -> CliSample:
    file = draw(st.sampled_from(tuple(ORIGINALS)))
    # Without NUL bytes too: the engine skips a file with one in its first 8,000 bytes.
    random = st.tuples(st.binary(max_size=MAX_RANDOM_BYTES), st.booleans()).map(
        lambda pair: ("random bytes", "random bytes", _without_nul(*pair))
    )
    kind, origin, data = draw(random | damaged(st.just(ORIGINALS[file])))
    command = draw(st.sampled_from(("check", "check", "check", "graph")))
    if command == "graph":
        graph_format = draw(st.sampled_from(("dot", "mermaid", "json")))
        arguments: tuple[str, ...] = ("graph", ".", "--format", graph_format)
    else:
        report = draw(st.sampled_from(("json", "json", "text", "sarif", "github")))
        where = draw(st.sampled_from((".", file)))  # the workspace, or one file (pre-commit)
        extras = draw(st.sets(st.sampled_from(("--show-source", "--statistics", "--verbose"))))
        ros = draw(st.sampled_from(((), ("--ros", "1"), ("--ros", "2"))))
        arguments = ("check", where, "--format", report, *sorted(extras), *ros)
    return CliSample(file, kind, f"{origin}; {file}", data, (*arguments, "--jobs", "1"))


def invoke(arguments: list[str], cwd: Path) -> Outcome:
    """``main`` in this process, its output captured as the bytes it wrote."""
    raw_out, raw_err = io.BytesIO(), io.BytesIO()
    out = io.TextIOWrapper(raw_out, encoding="utf-8")
    err = io.TextIOWrapper(raw_err, encoding="utf-8")
    with (
        chdir(cwd),
        redirect_stdout(out),
        redirect_stderr(err),
        warnings.catch_warnings(record=True) as caught,
    ):
        warnings.simplefilter("always")
        try:
            exit_code = main(arguments)
        except SystemExit as stop:
            exit_code = stop.code if isinstance(stop.code, int) else 2
    out.flush()
    err.flush()
    shown = tuple(str(w.message) for w in caught if not issubclass(w.category, QUIET_WARNINGS))
    # Strict: every report is UTF-8.
    return Outcome(exit_code, raw_out.getvalue().decode(), raw_err.getvalue().decode(), shown)


def check_outcome(sample: CliSample, outcome: Outcome) -> None:
    assert "Traceback" not in outcome.stderr, outcome.stderr
    assert outcome.exit_code in ((0,) if sample.arguments[0] == "graph" else (0, 1)), (
        outcome.exit_code,
        outcome.stderr,
    )
    assert not outcome.warnings, outcome.warnings
    for line in outcome.stderr.splitlines():
        assert _SUMMARY.fullmatch(line) or _VERBOSE.fullmatch(line), f"stderr: {line!r}"
    command, report = sample.arguments[0], sample.arguments[3]
    if command == "check" and report == "json" and "--statistics" not in sample.arguments:
        findings = json.loads(outcome.stdout)["findings"]
        parse_errors = [f for f in findings if f["code"] == "RN001" and f["path"] == sample.file]
        assert len(parse_errors) <= 1, parse_errors


def _raise_internal_error(arguments: list[str], cwd: Path) -> None:
    """Run again with ROSLINT_NAMES_DEBUG, so that the failure is the exception itself, with
    its traceback and where it was raised, not just the CLI's one-line message."""
    previous = os.environ.get("ROSLINT_NAMES_DEBUG")
    os.environ["ROSLINT_NAMES_DEBUG"] = "1"
    try:
        invoke(arguments, cwd)
    finally:
        if previous is None:
            del os.environ["ROSLINT_NAMES_DEBUG"]
        else:
            os.environ["ROSLINT_NAMES_DEBUG"] = previous


def _without_verbose(stderr: str) -> str:
    return "\n".join(line for line in stderr.splitlines() if not _VERBOSE.fullmatch(line))


def test_fuzz_cli(tmp_path: Path) -> None:
    workspace = tmp_path / "ws"
    shutil.copytree(EXAMPLES, workspace)
    cache = tmp_path / "cache"

    def check(sample: CliSample) -> None:
        target = workspace / sample.file
        target.write_bytes(sample.data)
        try:
            arguments = [*sample.arguments, "--cache-dir", str(cache)]
            first = invoke(arguments, workspace)
            if first.exit_code == 2 and "internal error" in first.stderr:
                _raise_internal_error(arguments, workspace)
            check_outcome(sample, first)
            again = invoke(arguments, workspace)  # the damaged file's facts from the cache
            assert (again.exit_code, again.stdout) == (first.exit_code, first.stdout)
            assert _without_verbose(again.stderr) == _without_verbose(first.stderr)
        finally:
            if sample.file in ADDED:
                target.unlink()
            else:
                target.write_bytes(ORIGINALS[sample.file])

    stats = fuzz(
        "cli.main",
        cli_samples(),
        check,
        data_of=lambda sample: sample.data,
        kind_of=lambda sample: sample.kind,
        describe=lambda sample: f"{sample.origin}; roslint-names {' '.join(sample.arguments)}",
    )
    assert stats.inputs > 0
    failures = report_failures(stats)
    if failures:
        pytest.fail(failures, pytrace=False)


def test_the_lines_of_a_build_file_fuzzed_away_are_known(tmp_path: Path) -> None:
    """The sample the fuzzer found: an empty CMakeLists.txt leaves its package's node
    compiled by nothing, which ``--verbose`` says in a line of its own."""
    workspace = tmp_path / "ws"
    shutil.copytree(EXAMPLES, workspace)
    sample = CliSample(
        file="src/turtle_bringup/CMakeLists.txt",
        kind="random bytes",
        origin="random bytes; src/turtle_bringup/CMakeLists.txt",
        data=b"",
        arguments=("check", ".", "--format", "json", "--verbose", "--jobs", "1"),
    )
    (workspace / sample.file).write_bytes(sample.data)
    outcome = invoke([*sample.arguments, "--no-cache"], workspace)
    assert "no build file of its package compiles it" in outcome.stderr
    check_outcome(sample, outcome)

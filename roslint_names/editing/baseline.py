"""A baseline: the findings a codebase had when it adopted the linter, to be let through.

``check --write-baseline FILE`` records the findings of a run; ``check --baseline FILE``
reports only findings not in it. A finding is recorded by what it is, not where: its
rule, its file (relative to the baseline file's directory), the name it points at and the
fingerprint of its source line (``fingerprint``). Lines inserted above it leave it
matched; editing its line, or a new finding on another line, is new. Equal entries are
counted, so a second copy of a baselined line is reported.

The file is JSON, sorted and indented one entry per block, meant to be committed and
reviewed in diffs; the line numbers of the run that wrote it are not in it, so it changes
only when findings come or go.

A finding that stands for a decision written at several places (``decisions``) is
recorded by each of them, and known only while each of them is: a copy of the name at a
new place makes it new again, as a second copy of a line does.
"""

from __future__ import annotations

import json
import os
from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from ..errors import UserError
from ..fingerprint import line_fingerprint, spelled_name
from ..model import Diagnostic
from .files import WriteError, read_regular, write_new

FORMAT = 1


class BaselineError(UserError):
    """A baseline file that cannot be read or written; the message names it."""


@dataclass(frozen=True, order=True)
class Entry:
    path: str  # '/'-separated, relative to the baseline file's directory
    code: str
    name: str  # the text the finding points at ("" when unknown)
    fingerprint: str


@dataclass(frozen=True)
class Applied:
    """A run's diagnostics with the baselined ones marked, and the entries nothing matched."""

    diagnostics: tuple[Diagnostic, ...]
    stale: tuple[Entry, ...]


def entry(diagnostic: Diagnostic, directory: Path, cwd: Path) -> Entry:
    absolute = os.path.normpath(os.path.join(cwd, diagnostic.path))
    relative = Path(os.path.relpath(absolute, directory)).as_posix()
    return Entry(relative, diagnostic.code, spelled_name(diagnostic), line_fingerprint(diagnostic))


def write(path: Path, diagnostics: Iterable[Diagnostic], cwd: Path) -> int:
    """Record every reported (not suppressed) diagnostic in ``path``, by each of its
    places; the count of diagnostics recorded."""
    directory = path.absolute().parent
    recorded = [d for d in diagnostics if not d.suppressed]
    entries = sorted(entry(place, directory, cwd) for d in recorded for place in _places(d))
    document = {
        "roslint-names-baseline": FORMAT,
        "findings": [
            {"path": e.path, "code": e.code, "name": e.name, "fingerprint": e.fingerprint}
            for e in entries
        ],
    }
    text = json.dumps(document, indent=2, ensure_ascii=False) + "\n"
    try:
        write_new(path, text.encode("utf-8"), "the baseline")
    except WriteError as error:
        raise BaselineError(str(error)) from error
    return len(recorded)


def load(path: Path) -> Counter[Entry]:
    """The entries of a baseline file, counted."""
    data, why = read_regular(path)
    if data is None:
        raise BaselineError(f"{path}: cannot read baseline: {why}")
    try:
        document = json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise BaselineError(f"{path}: not a roslint-names baseline: {error}") from error
    if not isinstance(document, dict) or document.get("roslint-names-baseline") != FORMAT:
        raise BaselineError(
            f"{path}: not a roslint-names baseline (format {FORMAT}); "
            "write one with `roslint-names check --write-baseline FILE`"
        )
    found: Counter[Entry] = Counter()
    for index, item in enumerate(document.get("findings", [])):
        fields = ("path", "code", "name", "fingerprint")
        if not isinstance(item, dict) or not all(isinstance(item.get(f), str) for f in fields):
            raise BaselineError(f"{path}: findings[{index}]: needs the strings {', '.join(fields)}")
        found[Entry(*(item[f] for f in fields))] += 1
    return found


def apply(
    diagnostics: Sequence[Diagnostic], baseline: Counter[Entry], directory: Path, cwd: Path
) -> Applied:
    """Mark the diagnostics the baseline holds (each entry absorbs as many places as it
    counts): a diagnostic is known when every place of it is."""
    left = Counter(baseline)
    marked: list[Diagnostic] = []
    for diagnostic in diagnostics:
        if diagnostic.suppressed:
            marked.append(diagnostic)
            continue
        wanted = Counter(entry(place, directory, cwd) for place in _places(diagnostic))
        known = all(left[key] >= count for key, count in wanted.items())
        for key, count in wanted.items():
            left[key] -= min(count, left[key])
        marked.append(replace(diagnostic, baselined=True) if known else diagnostic)
    stale = tuple(sorted(key for key, count in left.items() for _ in range(count)))
    return Applied(tuple(marked), stale)


def _places(diagnostic: Diagnostic) -> tuple[Diagnostic, ...]:
    """The diagnostic and the other places of its decision, each as its own finding."""
    return (diagnostic, *diagnostic.joined)

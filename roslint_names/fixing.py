"""``check --fix`` and ``--diff``: apply the rules' certain fixes at the spans found.

Each edit replaces the exact text the extractor located (``Diagnostic.edit``: the name as
the file spells it, nothing around it), so formatting, quotes and comments stay as they
are. Within a file edits are applied from the end; one that overlaps another is left for
the next run. A file is written only if, re-read, it parses no worse than before and
none of the fixed findings is still there (``Verify``); else it is left untouched and
named. Applying twice changes nothing the second time: a fixed name has no finding.
"""

from __future__ import annotations

import codecs
import difflib
from collections import defaultdict
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

from .lines import split_lines_keeping_ends
from .model import Diagnostic

# (path, new bytes) -> the file's parse errors and its findings as (code, line), re-read
Verify = Callable[[str, bytes], tuple[int, set[tuple[str, int]]]]


@dataclass(frozen=True)
class Fixed:
    """What a fix run changed: each file's old and new text, and what it refused."""

    changes: tuple[tuple[str, str, str], ...]  # (path, before, after)
    fixed: int  # findings fixed
    refused: tuple[tuple[str, str], ...]  # (path, why)

    def diff(self) -> str:
        return "".join(
            "".join(
                difflib.unified_diff(
                    split_lines_keeping_ends(before),
                    split_lines_keeping_ends(after),
                    fromfile=f"a/{path}",
                    tofile=f"b/{path}",
                )
            )
            for path, before, after in self.changes
        )


def plan(diagnostics: Iterable[Diagnostic], *, unsafe: bool, cwd: Path, verify: Verify) -> Fixed:
    """The fixes to make, verified, without writing anything."""
    by_file: dict[str, list[Diagnostic]] = defaultdict(list)
    for diagnostic in diagnostics:
        edit = diagnostic.edit
        if (
            edit is not None
            and (edit.safe or unsafe)
            and not diagnostic.suppressed
            and not diagnostic.baselined
        ):
            by_file[diagnostic.path].append(diagnostic)
    changes: list[tuple[str, str, str]] = []
    refused: list[tuple[str, str]] = []
    fixed = 0
    for path, found in sorted(by_file.items()):
        try:
            # utf-8-sig: a byte order mark is no column of line 1 for the extractors
            before = (cwd / path).read_bytes().decode("utf-8-sig")
        except (OSError, UnicodeDecodeError):
            refused.append((path, "not a UTF-8 file that can be read"))
            continue
        after, applied = _apply(before, found)
        if not applied:
            continue
        errors_before, _ = verify(path, before.encode("utf-8"))
        errors_after, remaining = verify(path, after.encode("utf-8"))
        still = [d for d in applied if (d.code, d.span.line) in remaining]
        if errors_after > errors_before or still:
            why = "it would no longer parse" if errors_after > errors_before else "no effect"
            refused.append((path, f"fixes not applied: {why}"))
            continue
        changes.append((path, before, after))
        fixed += len(applied)
    return Fixed(tuple(changes), fixed, tuple(refused))


def write(fixed: Fixed, cwd: Path) -> None:
    for path, _, after in fixed.changes:
        file = cwd / path
        mark = codecs.BOM_UTF8 if file.read_bytes().startswith(codecs.BOM_UTF8) else b""
        file.write_bytes(mark + after.encode("utf-8"))


def _apply(text: str, found: list[Diagnostic]) -> tuple[str, list[Diagnostic]]:
    """``text`` with the edits of ``found`` made, from the end; the diagnostics applied."""
    lines = split_lines_keeping_ends(text)
    applied: list[Diagnostic] = []
    taken: dict[int, list[tuple[int, int]]] = defaultdict(list)
    ordered = sorted(found, key=lambda d: d.edit.span if d.edit else d.span, reverse=True)
    for diagnostic in ordered:
        edit = diagnostic.edit
        assert edit is not None
        span = edit.span
        start, end = span.column - 1, span.end_column - 1
        if any(
            start < other_end and other_start < end for other_start, other_end in taken[span.line]
        ):
            continue  # two fixes on one span: only one this run
        line = lines[span.line - 1]
        lines[span.line - 1] = line[:start] + edit.text + line[end:]
        taken[span.line].append((start, end))
        applied.append(diagnostic)
    return "".join(lines), applied

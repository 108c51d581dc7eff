"""``check --fix`` and ``--diff``: apply the rules' certain fixes at the spans found.

Each edit replaces the exact text the extractor located (``Diagnostic.edit``: the name as
the file spells it, nothing around it), so formatting, quotes and comments stay as they
are. Within a file edits are applied from the end; one that overlaps another is left for
the next run. A file is written only if, re-read, it parses no worse than before and
none of the fixed findings is still there (``Verify``); else it is left untouched and
named. Applying twice changes nothing the second time: a fixed name has no finding.

The edits are made on the bytes the run first read (``files.Snapshot``): a file edited
since, a read-only one or one reached through a link leading out of the linted paths is
refused with every fix that touches it, and ``write`` writes all the files or none.
"""

from __future__ import annotations

import codecs
import difflib
from collections import defaultdict
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from ..lines import split_lines_keeping_ends
from ..model import Diagnostic, Edit, Fix, Span
from .files import Change, Snapshot

# (path, new bytes) -> the file's parse errors and its findings as (code, line), re-read
Verify = Callable[[str, bytes], tuple[int, set[tuple[str, int]]]]


@dataclass(frozen=True)
class Fixed:
    """What a fix run changed: each file's old and new text, and what it refused."""

    writes: tuple[Change, ...]  # each changed file's bytes, before and after
    fixed: int  # findings fixed
    refused: tuple[tuple[str, str], ...]  # (path, why)

    @property
    def changes(self) -> tuple[tuple[str, str, str], ...]:
        """(path, before, after) as text; a byte order mark is no part of it."""
        return tuple(
            (write.display, write.before.decode("utf-8-sig"), write.after.decode("utf-8-sig"))
            for write in self.writes
        )

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


def plan(
    diagnostics: Iterable[Diagnostic], *, unsafe: bool, snapshot: Snapshot, verify: Verify
) -> Fixed:
    """The fixes to make, verified, without writing anything.

    A fix is all its edits or none: a rename's edits in other files (``Diagnostic.also``)
    are made with its own, and a file refused takes every fix that touches it with it."""
    chosen = _without_overlaps(
        diagnostic
        for diagnostic in sorted(diagnostics, key=Diagnostic.sort_key)
        if diagnostic.edit is not None
        and (diagnostic.edit.safe or unsafe)
        and not diagnostic.suppressed
        and not diagnostic.baselined
    )
    refused: list[tuple[str, str]] = []
    texts: dict[str, tuple[bytes, str] | str] = {}  # the bytes and text, or why not
    while True:
        by_file: dict[str, dict[tuple[int, int, int], Edit]] = defaultdict(dict)
        for diagnostic in chosen:
            for path, edit in _edits(diagnostic):
                by_file[path][(edit.span.line, edit.span.column, edit.span.end_column)] = edit
        writes: list[Change] = []
        failed: dict[str, str] = {}
        for path, edits in sorted(by_file.items()):
            if path not in texts:
                texts[path] = _read(snapshot, path)
            read = texts[path]
            if isinstance(read, str):
                failed[path] = read
                continue
            data, before = read
            after = _apply(before, edits.values())
            errors_before, _ = verify(path, before.encode("utf-8"))
            errors_after, remaining = verify(path, after.encode("utf-8"))
            if errors_after > errors_before:
                failed[path] = "it would no longer parse"
            elif any(d.path == path and (d.code, d.span.line) in remaining for d in chosen):
                failed[path] = "no effect"
            else:
                mark = codecs.BOM_UTF8 if data.startswith(codecs.BOM_UTF8) else b""
                writes.append(Change(path, data, mark + after.encode("utf-8")))
        if not failed:
            return Fixed(tuple(writes), len(chosen), tuple(refused))
        for path, why in failed.items():
            # A rename reaching into the file goes first: the file's own fixes may pass.
            touching = [d for d in chosen if path in {p for p, _ in _edits(d)}]
            renames = [d for d in touching if d.also]
            dropped = renames or touching
            refused.append((path, f"{'renames' if renames else 'fixes'} not applied: {why}"))
            chosen = [d for d in chosen if d not in dropped]


def _edits(diagnostic: Diagnostic) -> list[tuple[str, Edit]]:
    """Every edit of a diagnostic's fix, with the file it is in."""
    assert diagnostic.edit is not None
    own = [(diagnostic.path, diagnostic.edit)]
    return own + [(edit.path or diagnostic.path, edit) for edit in diagnostic.also]


def _without_overlaps(diagnostics: Iterable[Diagnostic]) -> list[Diagnostic]:
    """The fixes, in order, less each that writes over another's span with other text:
    only one of two fixes on one span is made in a run (the next run sees the other)."""
    taken: dict[tuple[str, int], list[Edit]] = defaultdict(list)
    chosen: list[Diagnostic] = []
    for diagnostic in diagnostics:
        edits = _edits(diagnostic)
        if any(
            _overlap(edit, other) and (edit.span, edit.text) != (other.span, other.text)
            for path, edit in edits
            for other in taken[path, edit.span.line]
        ):
            continue
        for path, edit in edits:
            taken[path, edit.span.line].append(edit)
        chosen.append(diagnostic)
    return chosen


def _overlap(one: Edit, other: Edit) -> bool:
    return one.span.column < other.span.end_column and other.span.column < one.span.end_column


def _read(snapshot: Snapshot, path: str) -> tuple[bytes, str] | str:
    """The file's bytes and text to edit, or why it may not be edited."""
    data, why = snapshot.for_edit(path)
    if data is None:
        return why
    try:
        # utf-8-sig: a byte order mark is no column of line 1 for the extractors
        return data, data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return "not a UTF-8 file"


def write(fixed: Fixed, snapshot: Snapshot) -> None:
    """Every changed file written, or none (``files.WriteError`` says why)."""
    snapshot.replace_all(fixed.writes)


def _apply(text: str, edits: Iterable[Edit]) -> str:
    """``text`` with ``edits`` (one-line, not overlapping) made, from the end."""
    lines = split_lines_keeping_ends(text)
    for edit in sorted(edits, key=lambda edit: edit.span, reverse=True):
        span = edit.span
        line = lines[span.line - 1]
        lines[span.line - 1] = line[: span.column - 1] + edit.text + line[span.end_column - 1 :]
    return "".join(lines)


def located(fix: Fix, span: Span, line: str | None) -> Edit | None:
    """Where in the file the fix writes: the one place on the finding's line, within its
    span, that spells the name exactly (an escaped spelling gets no fix)."""
    if line is None or span.line != span.end_line or not fix.value:
        return None
    written = line[span.column - 1 : span.end_column - 1]
    start = written.find(fix.value)
    if start < 0 or written.find(fix.value, start + 1) >= 0:
        return None
    column = span.column + start
    return Edit(
        Span(span.line, column, span.line, column + len(fix.value)), fix.replacement, fix.safe
    )

"""Renames across the workspace (RN203's fix): offered only when every use is found.

Renaming ``minimumScore`` to ``minimum_score`` where the code reads the parameter breaks
every launch file and parameter file that sets it, unless they are renamed in the same
run. So a rename is offered only when each place its words appear in a name can be
renamed with it:

- every name the extractors found (any file, any kind) holding one of the words is
  renamed at the exact span where its file spells it; a name the file does not spell
  there (a constant folded in from elsewhere) or a frame id holding the word (not the
  rule's to rename) blocks the rename;
- every other place the words appear blocks it: in code, a name-shaped string literal
  that is not one of those names (a helper's argument, a constant); in launch files,
  URDF and configuration no extractor reads (parameter YAML, rviz, ``.cfg``), any
  occurrence at all. Identifiers and the words of comments do not count, they are not
  names; a quoted name in a comment does (the literals are found without a parse);
- a dynamic_reconfigure ``.cfg``'s parameter blocks it: the name is also a field of the
  class the build generates from it, which code reads as an identifier
  (``config.max_vel_x``), and renaming the ``.cfg`` alone would break the build.

A use a suppression keeps (``# noqa: RN203``) blocks the rename too: someone chose to keep
that spelling. Documentation is not searched (``discover.text_files``).
"""

from __future__ import annotations

import bisect
import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace

from ..extract.literals import name_literal_spans
from ..lines import line_starts, split_lines
from ..model import Diagnostic, Edit, FileFacts, Fix, Kind, Language, NameUse
from ..names import rename_tokens, token_pattern
from ..reading import decode_for_display
from .fixing import located

# Files whose names are string literals: elsewhere in them a word is an identifier.
_CODE = frozenset({Language.CPP, Language.PYTHON, Language.LAUNCH_PYTHON, Language.SETUP_PY})

# Files whose names become identifiers of generated code (``.cfg``: ``nameConfig`` fields).
_GENERATING = frozenset({Language.RECONFIGURE})

Read = Callable[[str], "bytes | None"]  # a display path's bytes; None when unreadable


@dataclass(frozen=True)
class _Use:
    """A name holding some of the words, and where its file spells it."""

    path: str
    use: NameUse
    edit: Edit


def resolve(
    diagnostics: Sequence[Diagnostic],
    facts: Iterable[FileFacts],
    files: Iterable[str],
    read: Read,
) -> list[Diagnostic]:
    """``diagnostics`` with each pending rename (``Diagnostic.renaming``) offered as edits
    of every use of its words, or dropped. ``files``: the display paths of the workspace's
    text files (``discover.text_files``), searched with ``facts`` for the words."""
    pending = [d.renaming for d in diagnostics if d.renaming is not None]
    if not pending:
        return list(diagnostics)
    renamed = {old: new for fix in pending for old, new in fix.tokens}
    blocked: dict[str, str] = {}  # word -> why it cannot be renamed (the first place found)
    for d in diagnostics:
        if d.suppressed and d.renaming is not None:
            for old, _ in d.renaming.tokens:
                blocked.setdefault(old, f"a suppression keeps it at {d.path}:{d.span.line}")
    facts_of = {file_facts.path: file_facts for file_facts in facts}
    search = _Search(renamed, read)
    uses: list[_Use] = []
    for path in sorted({*files, *facts_of}):
        found, blocking = search.file(path, facts_of.get(path))
        uses += found
        for word, why in blocking.items():
            blocked.setdefault(word, why)
    return [_resolved(d, uses, blocked) for d in diagnostics]


class _Search:
    """Finds, file by file, the uses of the words and the places that block them."""

    def __init__(self, renamed: dict[str, str], read: Read) -> None:
        self._renamed = renamed
        self._read = read
        self._words = token_pattern(renamed)
        # A first look at the bytes: nearly no file holds any of the words at all.
        self._any = re.compile(b"|".join(re.escape(word.encode("utf-8")) for word in renamed))

    def file(self, path: str, facts: FileFacts | None) -> tuple[list[_Use], dict[str, str]]:
        """The uses of the words in the file, and each word the file blocks, with why."""
        data = self._read(path)
        if data is None or self._any.search(data) is None:
            return [], {}
        text = decode_for_display(data)
        lines = split_lines(text)
        uses: list[_Use] = []
        blocked: dict[str, str] = {}
        for use in () if facts is None else facts.names:
            words = set(self._words.findall(use.value))
            if use.dynamic or not words:
                continue
            line = lines[use.span.line - 1] if 0 < use.span.line <= len(lines) else None
            fix = Fix(use.value, rename_tokens(use.value, self._renamed), safe=False)
            where = f"{path}:{use.span.line}"
            if use.kind is Kind.FRAME:
                why = f"{where} names a tf frame with it, which is not this rule's to rename"
            elif facts is not None and facts.language in _GENERATING:
                why = f"{where} generates code from it (a dynamic_reconfigure field)"
            elif (edit := located(fix, use.span, line)) is None:
                why = f"{where} does not spell the name where it is used (a constant)"
            else:
                uses.append(_Use(path, use, replace(edit, path=path)))
                continue
            for word in words:
                blocked.setdefault(word, why)
        covered = [use.edit.span for use in uses]
        starts: list[int] = []
        code = facts is not None and facts.language in _CODE
        for start, end in name_literal_spans(text) if code else [(0, len(text))]:
            for found in self._words.finditer(text, start, end):
                starts = starts or line_starts(text)
                number = bisect.bisect_right(starts, found.start())
                column = found.start() - starts[number - 1] + 1
                if not any(
                    span.line == number and span.column <= column < span.end_column
                    for span in covered
                ):
                    blocked.setdefault(
                        found.group(), f"{path}:{number} writes it where no name is read"
                    )
        return uses, blocked


def _resolved(diagnostic: Diagnostic, uses: list[_Use], blocked: dict[str, str]) -> Diagnostic:
    fix = diagnostic.renaming
    if fix is None:
        return diagnostic
    mine = dict(fix.tokens)
    edit = located(fix, diagnostic.span, diagnostic.source_line)
    if edit is None:
        return replace(diagnostic, renaming=None, held_back="the name is not spelled here")
    why = next((f"'{word}': {blocked[word]}" for word in sorted(mine) if word in blocked), None)
    if why is not None:
        return replace(diagnostic, renaming=None, held_back=why)
    words = token_pattern(mine)
    also = {
        (use.path, use.edit.span): replace(use.edit, text=rename_tokens(use.use.value, mine))
        for use in uses
        if words.search(use.use.value)
    }
    also.pop((diagnostic.path, edit.span), None)
    return replace(
        diagnostic,
        renaming=None,
        edit=edit,
        also=tuple(also[key] for key in sorted(also)),
    )

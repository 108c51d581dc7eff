"""The server's own application of a client's incremental edits (``lsp._apply``), against
the LSP definition: lines end at CR, LF or CRLF only, columns count code units of the
negotiated encoding, and a column past a line's end is its end."""

from __future__ import annotations

import random

import pytest
from conftest import code_units
from lsprotocol import types

from roslint_names.lines import split_lines_keeping_ends
from roslint_names.lsp import _apply, _LineHint

PIECES = ["ros", "::", "é", "😀", " ", "\n", "\r\n", "\r", "\f", "\u2028", "\x85", '"/cmd_vel"']


def _reference_offset(text: str, position: types.Position, encoding: str) -> int:
    lines = split_lines_keeping_ends(text)
    if position.line >= len(lines):
        return len(text)
    start = sum(len(line) for line in lines[: position.line])
    line = lines[position.line].rstrip("\r\n")
    for index in range(len(line) + 1):
        if code_units(line[:index], encoding) >= position.character:
            return start + index
    return start + len(line)


@pytest.mark.parametrize("encoding", ["utf-8", "utf-16", "utf-32"])
def test_edits_land_where_the_client_counts_them(encoding: str) -> None:
    chance = random.Random(26)
    for _ in range(40):
        text = "".join(chance.choice(PIECES) for _ in range(60))
        hint = _LineHint()
        for _ in range(30):
            lines = len(split_lines_keeping_ends(text)) + 1
            start = types.Position(chance.randrange(lines), chance.randrange(12))
            end = types.Position(start.line + chance.choice([0, 0, 1, 2]), chance.randrange(12))
            if (end.line, end.character) < (start.line, start.character):
                end = start
            new_text = "".join(chance.choice(PIECES) for _ in range(chance.randrange(3)))
            change = types.TextDocumentContentChangePartial(types.Range(start, end), new_text)
            first = _reference_offset(text, start, encoding)
            last = max(first, _reference_offset(text, end, encoding))
            expected = text[:first] + new_text + text[last:]
            text = _apply(text, change, encoding, hint)
            assert text == expected


def test_a_whole_document_change_replaces_the_text() -> None:
    hint = _LineHint(3, 40)
    change = types.TextDocumentContentChangeWholeDocument("<launch/>\n")
    assert _apply("old\n" * 10, change, "utf-16", hint) == "<launch/>\n"
    assert (hint.line, hint.start) == (0, 0)

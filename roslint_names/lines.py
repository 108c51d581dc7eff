"""Split decoded text into lines the way the parsers and editors count them.

``str.splitlines()`` also breaks at form feed, ``\\x1c``-``\\x1e`` and Unicode line
separators, which tree-sitter, lxml and libcst do not: line numbers would drift after such
a character. Only CRLF, CR and LF end a line here.
"""

from __future__ import annotations

import re

_LINE_BREAK = re.compile(r"\r\n|\r|\n")


def split_lines(text: str) -> list[str]:
    lines = _LINE_BREAK.split(text)
    if lines and lines[-1] == "":
        lines.pop()  # a final line break ends the last line; it does not start a new one
    return lines


def split_lines_keeping_ends(text: str) -> list[str]:
    """The lines of ``split_lines``, each with its own line break: joined, they are
    ``text`` again (what an editor of the file needs)."""
    lines = re.split(r"(?<=\r\n)|(?<=\r)(?!\n)|(?<=\n)", text)
    if lines and lines[-1] == "":
        lines.pop()
    return lines


def line_starts(text: str) -> list[int]:
    """The offset where each line of ``text`` starts, lines counted as ``split_lines``
    counts them (one more entry after a final line break)."""
    return [0, *(found.end() for found in _LINE_BREAK.finditer(text))]

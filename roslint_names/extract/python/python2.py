"""Python 2 source rewritten into Python 3 that means the same to the extractor.

ROS 1 up to Melodic runs Python 2, and its packages keep Python 2 scripts (a melodic-era
node with ``print "..."``). libcst parses Python 3 only; rather than a second parser, the
few Python 2 constructs that Python 3 refuses are rewritten, token by token, into Python 3
ones, and libcst parses the result:

- ``print x, y`` and ``print >>f, x`` become calls (``print( x, y)``, ``print( f, x)``);
  not where ``from __future__ import print_function`` makes ``print`` a function;
- ``exec code in ns`` becomes ``exec( code , ns)``;
- ``except X, e:`` becomes ``except X as  e:``, ``raise E, V`` becomes ``raise E( V)``;
- backticks become ``repr(...)``, ``<>`` becomes ``!=``;
- ``0777`` becomes ``0o777``, ``10L`` becomes ``10``, ``ur"..."`` becomes ``r"..."``;
- tabs in indentation become spaces up to the next multiple of 8, as Python 2 counted
  them (Python 3 refuses a block indented by tabs on one line and spaces on the next).

Every edit stays on its line, and ``Rewritten.original`` maps each offset of the new text
back to the user's bytes, so that a finding, a fix or a ``# noqa`` lands where the file
spells the name. What the rewrite does not cover (tuple parameters, ``async`` as a name)
still fails to parse, and the file stays one RN001.

Scanned by a regular expression of its own, not by ``tokenize``: that module's tokens of
Python 2 differ between Python versions (``0777`` and ``<>`` are one token in 3.12, two in
3.11; a backtick is an operator in 3.12, an error token in 3.11), and from 3.12 it raises
``TabError`` on the indentation Python 2 accepted. Imports nothing heavy.
"""

from __future__ import annotations

import re
from bisect import bisect_right
from collections.abc import Iterator
from dataclasses import dataclass

# Strings first (with any prefix of up to two letters, so that ``ur"..."`` is one token),
# then comments; an unterminated string falls through to ``other``.
_TOKEN = re.compile(
    r"""
    (?P<string>(?:(?<!\w)[rRuUbBfF]{1,2})?(?:
        '''[^'\\]*(?:(?:\\.|'(?!''))[^'\\]*)*'''
      | \"\"\"[^"\\]*(?:(?:\\.|"(?!""))[^"\\]*)*\"\"\"
      | '[^'\\\r\n]*(?:\\(?:\r\n|.)[^'\\\r\n]*)*'
      | "[^"\\\r\n]*(?:\\(?:\r\n|.)[^"\\\r\n]*)*"
    ))
    | (?P<comment>\#[^\r\n]*)
    | (?P<continuation>\\(?:\r\n|\r|\n))
    | (?P<newline>\r\n|\r|\n)
    | (?P<space>[ \t\f]+)
    | (?P<number>\.?\d(?:[eE][-+]|[\w.])*)
    | (?P<name>\w+)
    | (?P<operator><>|->|:=|\*\*=?|//=?|>>=?|<<=?|[-+*/%@&|^=<>!]=?|[~.,;:])
    | (?P<open>[(\[{])
    | (?P<close>[)\]}])
    | (?P<backtick>`)
    | (?P<other>.)
    """,
    re.VERBOSE | re.DOTALL,
)
_PRINT_FUNCTION = re.compile(
    r"^[ \t]*from[ \t]+__future__[ \t]+import[ \t]*(?:\([^)]*\)|[^\r\n#;]*)", re.MULTILINE
)
_OCTAL = re.compile(r"0([0-7]+)[lL]?")
_LONG = re.compile(r"(?:0[xX][0-9a-fA-F]+|0[oObB][0-7]+|0|[1-9][0-9]*)[lL]")
# What may follow ``print`` in a print statement: the start of an expression. A ``(``
# is left alone (``print ("x")`` is a call in either language), and so is whatever makes
# ``print`` a name (``print = ...``, ``print.x``).
_EXPRESSION_STARTS = frozenset({"string", "number", "name", "backtick"})
_EXPRESSION_OPERATORS = frozenset({"-", "+", "~", "[", "{"})
_NOT_OPERANDS = frozenset({"in", "is", "and", "or", "if", "else", "for", "as"})
_TAB_STOP = 8


@dataclass(frozen=True)
class _Token:
    kind: str
    text: str
    start: int

    @property
    def end(self) -> int:
        return self.start + len(self.text)


@dataclass(frozen=True)
class Rewritten:
    """The rewritten text, and where each of its pieces came from in the original."""

    text: str
    source: str  # the original
    _starts: tuple[int, ...]  # offsets in ``text`` where each piece starts
    _origins: tuple[tuple[int, int], ...]  # each piece's (start, end) in the original

    def original(self, offset: int) -> int:
        """The offset in the original text of ``offset`` in the rewritten one: copied
        text maps one to one; text put in place of other text maps onto what it
        replaced, as far as that reaches."""
        index = max(bisect_right(self._starts, offset) - 1, 0)
        start, end = self._origins[index]
        return min(start + offset - self._starts[index], end)


def rewrite(text: str) -> Rewritten | None:
    """``text`` with its Python 2 constructs rewritten into Python 3; None when it has
    none (it fails to parse for another reason)."""
    edits = sorted(_edits(text))
    if not edits:
        return None
    pieces: list[str] = []
    starts: list[int] = []
    origins: list[tuple[int, int]] = []
    copied = length = 0
    for start, end, replacement in edits:
        for piece, origin in ((text[copied:start], (copied, start)), (replacement, (start, end))):
            starts.append(length)
            origins.append(origin)
            pieces.append(piece)
            length += len(piece)
        copied = end
    starts.append(length)
    origins.append((copied, len(text)))
    pieces.append(text[copied:])
    return Rewritten("".join(pieces), text, tuple(starts), tuple(origins))


def _tokens(text: str) -> Iterator[_Token]:
    for match in _TOKEN.finditer(text):
        kind = match.lastgroup
        assert kind is not None
        yield _Token(kind, match.group(), match.start())


class _Statement:
    """What the statement being read needs at its end, and what its clauses rewrite."""

    def __init__(self) -> None:
        self.call = False  # made a call: a ``)`` closes it at its end
        self.keyword = ""  # ``except``, ``raise`` or ``exec``: a clause to rewrite
        self.lambdas = 0  # ``lambda`` heads whose ``:`` is still to come


def _edits(text: str) -> Iterator[tuple[int, int, str]]:
    """(start, end, replacement) edits of ``text``, never overlapping and never across a
    line break; the indentation's first, then the rest in order."""
    print_statement = not any(
        "print_function" in found.group() for found in _PRINT_FUNCTION.finditer(text)
    )
    tokens = list(_tokens(text))
    significant = [
        token for token in tokens if token.kind not in ("space", "continuation", "comment")
    ]
    yield from _indentation(tokens)
    brackets: list[str] = []
    statement = _Statement()
    at_start = True
    for index, token in enumerate(significant):
        following = significant[index + 1] if index + 1 < len(significant) else None
        starts_statement, at_start = at_start, False
        depth = len(brackets)
        if token.kind == "newline" or (token.text == ";" and depth == 0):
            if depth == 0:
                yield from _close(statement, significant[index - 1] if index else None)
                statement, at_start = _Statement(), True
            continue
        if starts_statement and token.kind == "name":
            yield from _statement_start(token, following, statement, print_statement)
        elif token.kind == "name" and token.text == "lambda" and depth == 0:
            statement.lambdas += 1
        elif token.text == ":" and depth == 0:
            if statement.lambdas:
                statement.lambdas -= 1
            else:  # ``if x: print "a"``: a statement follows on the line
                yield from _close(statement, significant[index - 1])
                statement, at_start = _Statement(), True
        elif token.text == "," and depth == 0 and statement.keyword in ("except", "raise"):
            yield token.start, token.end, " as " if statement.keyword == "except" else "("
            statement.call = statement.keyword == "raise"
            statement.keyword = ""
        elif token.text == "in" and depth == 0 and statement.keyword == "exec":
            yield token.start, token.end, ","
            statement.keyword = ""
        elif token.kind == "backtick":
            if brackets and brackets[-1] == "`":
                brackets.pop()
                yield token.start, token.end, ")"
            else:
                brackets.append("`")
                yield token.start, token.end, "repr("
        elif token.kind == "open":
            brackets.append(token.text)
        elif token.kind == "close" and brackets:
            brackets.pop()
        else:
            yield from _literal(token)
    # The file may end inside brackets (``print [`` and no more): the ``)`` goes after the
    # last token of the statement, never after a line break.
    last = next((token for token in reversed(significant) if token.kind != "newline"), None)
    yield from _close(statement, last)


def _statement_start(
    token: _Token, following: _Token | None, statement: _Statement, print_statement: bool
) -> Iterator[tuple[int, int, str]]:
    if token.text in ("except", "raise"):
        statement.keyword = token.text
        return
    if token.text == "exec" or (token.text == "print" and print_statement):
        if following is None or following.kind == "newline" or following.text == ";":
            if token.text == "print":  # a bare ``print``: an empty line
                yield token.end, token.end, "()"
            return
        if following.text == ">>" and token.text == "print":
            yield token.end, token.end, "("
            yield following.start, following.end, ""  # ``print >>f, x``: ``print( f, x)``
        elif _starts_expression(following):
            yield token.end, token.end, "("
        else:
            return
        statement.call = True
        statement.keyword = token.text


def _starts_expression(token: _Token) -> bool:
    if token.kind == "name":
        return token.text not in _NOT_OPERANDS
    return token.kind in _EXPRESSION_STARTS or token.text in _EXPRESSION_OPERATORS


def _close(statement: _Statement, last: _Token | None) -> Iterator[tuple[int, int, str]]:
    """The ``)`` a statement made into a call needs, after its last token."""
    if statement.call and last is not None:
        yield last.end, last.end, ")"
    statement.call = False


def _literal(token: _Token) -> Iterator[tuple[int, int, str]]:
    if token.kind == "number":
        octal = _OCTAL.fullmatch(token.text)
        if octal is not None and octal.group(1).strip("0"):
            yield token.start, token.end, "0o" + octal.group(1)
        elif _LONG.fullmatch(token.text):
            yield token.end - 1, token.end, ""
    elif token.kind == "string" and token.text[:2].lower() == "ur":
        # Python 3's raw strings are all unicode; the prefix's first column stays the
        # string's first column.
        yield token.start, token.start + 2, token.text[1]
    elif token.text == "<>":
        yield token.start, token.end, "!="


def _indentation(tokens: list[_Token]) -> Iterator[tuple[int, int, str]]:
    """Tabs in the indentation of a line, expanded as Python 2 counted them."""
    at_line_start = True
    for token in tokens:
        if at_line_start and token.kind == "space" and "\t" in token.text:
            yield token.start, token.end, _expanded(token.text)
        at_line_start = token.kind in ("newline", "continuation")


def _expanded(indentation: str) -> str:
    column = 0
    for character in indentation:
        column = (column // _TAB_STOP + 1) * _TAB_STOP if character == "\t" else column + 1
    return " " * column

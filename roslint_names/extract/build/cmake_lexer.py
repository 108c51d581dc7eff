"""The command invocations of a CMake file, as cmake-language(7) spells them.

A CMake file is a sequence of ``name(arguments)`` invocations separated by whitespace and
comments; nothing else is allowed at the top level. Arguments come in three forms:

* bracket arguments ``[[...]]``/``[=[...]=]``: literal text, no escapes, no references, a
  newline right after the opening bracket dropped;
* quoted arguments ``"..."``: escapes (``\\t``, ``\\n``, ``\\r``, ``\\;``, ``\\x`` for a
  literal ``x``, backslash-newline continues the line) and variable references;
* unquoted arguments: runs of anything but whitespace, ``()#"\\``, with the same escapes and
  references; evaluated, they split into a list at ``;``.

Parentheses inside an argument list nest (``if((a) OR b)``) and come back as ``(``/``)``
arguments, as CMake hands them to the command. Comments are ``#`` to the end of the line,
or a bracket comment ``#[[...]]``. Command names are case-insensitive: they come back
lower-cased. References (``${name}``, ``$ENV{name}``, ``$CACHE{name}``) are kept as
``VarRef`` pieces, because only the evaluator knows their values; a reference's name may
itself hold references (``${${PROJECT_NAME}_SOURCES}``).

Lexing stops at the first error (an unbalanced parenthesis, an unterminated string, text
that is no command); ``Lexed.error`` says where, and the commands before it stay valid.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from enum import Enum


class ArgKind(str, Enum):
    BRACKET = "bracket"
    QUOTED = "quoted"
    UNQUOTED = "unquoted"


@dataclass(frozen=True)
class VarRef:
    """``${name}`` (``namespace`` ""), ``$ENV{name}`` or ``$CACHE{name}``."""

    namespace: str
    name: tuple[Piece, ...]


Piece = str | VarRef


@dataclass(frozen=True)
class Argument:
    """One argument as written: its pieces and its raw text's offsets (quotes included)."""

    kind: ArgKind
    pieces: tuple[Piece, ...]
    start: int
    end: int


@dataclass(frozen=True)
class Command:
    name: str  # lower-cased
    start: int  # offset of the name
    arguments: tuple[Argument, ...]


@dataclass(frozen=True)
class Lexed:
    commands: tuple[Command, ...]
    error: int | None = None  # offset where lexing stopped; None when the whole file lexed


class _LexError(Exception):
    def __init__(self, offset: int) -> None:
        super().__init__(offset)
        self.offset = offset


_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_SPACE = re.compile(r"[ \t]*")
_WHITESPACE = re.compile(r"\s+")
_BRACKET_OPEN = re.compile(r"\[(=*)\[")
_QUOTED_RUN = re.compile(r'[^"\\$]+')
_UNQUOTED_RUN = re.compile(r'[^\s()#"\\$]+')
_NAME_RUN = re.compile(r"[A-Za-z0-9/_.+\-]+")
_REFERENCE_OPEN = re.compile(r"\$(ENV|CACHE)?\{")
_ENCODED = {"t": "\t", "n": "\n", "r": "\r"}
# References nest only a few levels in real files; the bound keeps a hostile file from
# exhausting the stack.
_MAX_REFERENCE_DEPTH = 50


def lex(text: str) -> Lexed:
    """Every command of ``text`` up to the first lexical error."""
    lexer = _Lexer(text)
    commands: list[Command] = []
    try:
        while lexer.skip_separation():
            commands.append(lexer.command())
    except _LexError as error:
        return Lexed(tuple(commands), error.offset)
    return Lexed(tuple(commands))


class _Lexer:
    def __init__(self, text: str) -> None:
        self.text = text
        self.pos = 0

    def skip_separation(self) -> bool:
        """Skip whitespace and comments; false at the end of the text."""
        text = self.text
        while self.pos < len(text):
            match = _WHITESPACE.match(text, self.pos)
            if match:
                self.pos = match.end()
            elif text[self.pos] == "#":
                self._comment()
            else:
                return True
        return False

    def _comment(self) -> None:
        bracket = _BRACKET_OPEN.match(self.text, self.pos + 1)
        if bracket:
            self.pos = self._bracket_close(bracket)[1]
            return
        newline = self.text.find("\n", self.pos)
        self.pos = len(self.text) if newline < 0 else newline

    def _bracket_close(self, opening: re.Match[str]) -> tuple[int, int]:
        """(content end, argument end) of the bracket text that ``opening`` opened."""
        closing = "]" + opening.group(1) + "]"
        end = self.text.find(closing, opening.end())
        if end < 0:
            raise _LexError(opening.start())
        return end, end + len(closing)

    def command(self) -> Command:
        start = self.pos
        match = _IDENTIFIER.match(self.text, start)
        if not match:
            raise _LexError(start)
        space = _SPACE.match(self.text, match.end())
        self.pos = space.end() if space else match.end()
        if not self.text.startswith("(", self.pos):
            raise _LexError(start)
        self.pos += 1
        return Command(match.group().lower(), start, self._arguments(start))

    def _arguments(self, command_start: int) -> tuple[Argument, ...]:
        arguments: list[Argument] = []
        depth = 0
        while True:
            if not self.skip_separation():
                raise _LexError(command_start)  # the file ends inside the parentheses
            char, start = self.text[self.pos], self.pos
            if char == ")" and depth == 0:
                self.pos += 1
                return tuple(arguments)
            if char in "()":
                depth += 1 if char == "(" else -1
                self.pos += 1
                arguments.append(Argument(ArgKind.UNQUOTED, (char,), start, self.pos))
            elif char == '"':
                arguments.append(self._quoted())
            elif bracket := _BRACKET_OPEN.match(self.text, self.pos):
                arguments.append(self._bracket(bracket))
            else:
                arguments.append(self._unquoted())

    def _bracket(self, opening: re.Match[str]) -> Argument:
        content_end, end = self._bracket_close(opening)
        content = self.text[opening.end() : content_end]
        # CMake drops one newline right after the opening bracket.
        if content.startswith("\r\n"):
            content = content[2:]
        elif content.startswith("\n"):
            content = content[1:]
        self.pos = end
        return Argument(ArgKind.BRACKET, (content,), opening.start(), end)

    def _quoted(self) -> Argument:
        start = self.pos
        self.pos += 1
        pieces = _Pieces()
        text = self.text
        while self.pos < len(text):
            char = text[self.pos]
            if char == '"':
                self.pos += 1
                return Argument(ArgKind.QUOTED, pieces.done(), start, self.pos)
            if char == "\\":
                if text.startswith("\\\n", self.pos) or text.startswith("\\\r\n", self.pos):
                    self.pos += 2 if text[self.pos + 1] == "\n" else 3  # line continuation
                else:
                    pieces.add(self._escape())
            elif char == "$" and _REFERENCE_OPEN.match(text, self.pos):
                pieces.add(self._reference(0))
            else:
                run = _QUOTED_RUN.match(text, self.pos)
                end = run.end() if run else self.pos + 1
                pieces.add(text[self.pos : end])
                self.pos = end
        raise _LexError(start)

    def _unquoted(self) -> Argument:
        start = self.pos
        pieces = _Pieces()
        text = self.text
        while self.pos < len(text):
            char = text[self.pos]
            if char.isspace() or char in "()#":
                break
            if char == "\\":
                pieces.add(self._escape())
            elif char == "$" and _REFERENCE_OPEN.match(text, self.pos):
                pieces.add(self._reference(0))
            elif char == '"':
                pieces.add(self._legacy_quote())
            else:
                run = _UNQUOTED_RUN.match(text, self.pos)
                end = run.end() if run else self.pos + 1
                pieces.add(text[self.pos : end])
                self.pos = end
        return Argument(ArgKind.UNQUOTED, pieces.done(), start, self.pos)

    def _legacy_quote(self) -> str:
        """``-Da="b c"``: a quote inside an unquoted argument is kept, quotes and all."""
        start = self.pos
        end = start + 1
        while end < len(self.text) and self.text[end] != '"':
            end += 2 if self.text[end] == "\\" else 1
        if end >= len(self.text):
            raise _LexError(start)
        self.pos = end + 1
        return self.text[start : self.pos]

    def _escape(self) -> str:
        """The text an escape sequence stands for; ``\\;`` stays itself (it blocks a split)."""
        if self.pos + 1 >= len(self.text):
            raise _LexError(self.pos)
        char = self.text[self.pos + 1]
        self.pos += 2
        if char == ";":
            return "\\;"
        return _ENCODED.get(char, char)

    def _reference(self, depth: int) -> VarRef:
        start = self.pos
        if depth > _MAX_REFERENCE_DEPTH:
            raise _LexError(start)
        opening = _REFERENCE_OPEN.match(self.text, self.pos)
        assert opening is not None
        self.pos = opening.end()
        pieces = _Pieces()
        text = self.text
        while self.pos < len(text):
            char = text[self.pos]
            if char == "}":
                self.pos += 1
                return VarRef(opening.group(1) or "", pieces.done())
            if char == "\\":
                pieces.add(self._escape())
            elif char == "$" and _REFERENCE_OPEN.match(text, self.pos):
                pieces.add(self._reference(depth + 1))
            else:
                run = _NAME_RUN.match(text, self.pos)
                if not run:
                    raise _LexError(start)  # CMake rejects this character in a name
                pieces.add(run.group())
                self.pos = run.end()
        raise _LexError(start)


class _Pieces:
    """Collects pieces, merging adjacent literal text."""

    def __init__(self) -> None:
        self._pieces: list[Piece] = []

    def add(self, piece: Piece) -> None:
        if isinstance(piece, str) and self._pieces and isinstance(self._pieces[-1], str):
            self._pieces[-1] += piece
        elif piece != "":
            self._pieces.append(piece)

    def done(self) -> tuple[Piece, ...]:
        return tuple(self._pieces)

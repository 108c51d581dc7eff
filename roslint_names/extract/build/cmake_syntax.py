"""The command invocations of a CMake file, read from tree-sitter-cmake's syntax tree.

A CMake file is a sequence of ``name(arguments)`` invocations; cmake-language(7) gives
arguments three forms:

* bracket arguments ``[[...]]``/``[=[...]=]``: literal text, no escapes, no references, a
  newline right after the opening bracket dropped;
* quoted arguments ``"..."``: escapes (``\\t``, ``\\n``, ``\\r``, ``\\;``, ``\\x`` for a
  literal ``x``, backslash-newline continues the line) and variable references;
* unquoted arguments: with the same escapes and references; evaluated, they split into a
  list at ``;``. A quote inside one (``-Da="b c"``, CMake's legacy form) is kept, quotes
  and all, as part of the one argument: tree-sitter-cmake reads it as two arguments, which
  are joined again here.

The tree nests ``if``/``foreach``/``function``/``macro``/``while``/``block`` bodies; here
every invocation comes back in file order, the block commands (``if``, ``endif``, ...)
included, as CMake runs them. Parentheses inside an argument list (``if((a) OR b)``) come
back as ``(``/``)`` arguments. Command names come back lower-cased. References (``${name}``,
``$ENV{name}``, ``$CACHE{name}``) are kept as ``VarRef`` pieces, because only the
evaluator knows their values; a reference's name may hold references
(``${${PROJECT_NAME}_SOURCES}``).

Reading stops at the first syntax error (an unbalanced parenthesis, an unterminated
string, text that is no command): ``Lexed.error`` is the offset of the command (or text)
where it is, and the commands before it stay valid. Offsets are in characters.

On the 653 CMakeLists.txt of the 28 benchmark repositories this gives exactly what the
hand-written lexer it replaces gave.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from functools import lru_cache
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from tree_sitter import Node, Parser


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


_BLOCK_KEYWORDS = ("if", "elseif", "else", "endif", "foreach", "endforeach", "while")
_COMMANDS = frozenset(
    {"normal_command"}
    | {
        f"{keyword}_command"
        for keyword in (
            *_BLOCK_KEYWORDS,
            "endwhile",
            "function",
            "endfunction",
            "macro",
            "endmacro",
            "block",
            "endblock",
        )
    }
)
# What holds commands (a block, its body, an ERROR node around a block left open), and
# what may stand between commands.
_CONTAINERS = frozenset(
    {"source_file", "body", "ERROR"}
    | {"if_condition", "foreach_loop", "while_loop", "function_def", "macro_def", "block_def"}
)
_COMMENTS = frozenset({"line_comment", "bracket_comment"})
_ENCODED = {"t": "\t", "n": "\n", "r": "\r"}
_NAMESPACES = {"normal_var": "", "env_var": "ENV", "cache_var": "CACHE"}
# References nest only a few levels in real files; the bound keeps a hostile file from
# exhausting the stack.
_MAX_REFERENCE_DEPTH = 50


@lru_cache(maxsize=1)
def _parser() -> Parser:
    import tree_sitter
    import tree_sitter_cmake

    return tree_sitter.Parser(tree_sitter.Language(tree_sitter_cmake.language()))


def _holds_commands(node: Node) -> bool:
    """Whether the node holds only commands, blocks and comments (an ERROR node: a block
    left open; not text that is no command)."""
    if node.type != "ERROR":
        return True
    return bool(node.children) and all(
        child.type in _COMMANDS or child.type in _CONTAINERS or child.type in _COMMENTS
        for child in node.children
    )


class _RefusedError(Exception):
    """A part of the file CMake would refuse: reading stops before its command."""


def lex(text: str) -> Lexed:
    """Every command of ``text`` up to the first syntax error."""
    return _Reader(text).read()


class _Reader:
    def __init__(self, text: str) -> None:
        self.data = text.encode("utf-8", errors="surrogatepass")
        # Byte offsets from the tree, character offsets out: the same for ASCII text.
        self._ascii = len(self.data) == len(text)

    def offset(self, byte: int) -> int:
        if self._ascii:
            return byte
        return len(self.data[:byte].decode("utf-8", errors="surrogatepass"))

    def source(self, node: Node) -> str:
        return self.data[node.start_byte : node.end_byte].decode("utf-8", errors="surrogatepass")

    def read(self) -> Lexed:
        commands: list[Command] = []
        pending = [_parser().parse(self.data).root_node]
        while pending:  # file order, depth first, without recursion
            node = pending.pop()
            if node.type in _COMMANDS:
                try:
                    if node.has_error:
                        raise _RefusedError
                    commands.append(self._command(node))
                except _RefusedError:
                    return Lexed(tuple(commands), self.offset(node.start_byte))
            elif node.type in _CONTAINERS and not node.is_missing and _holds_commands(node):
                # An ERROR node may only stand for a block left open (``if`` without
                # ``endif``, which CMake reports when it runs, not when it reads): what is
                # in it is read on; anything else in it stops the reading.
                pending.extend(reversed(node.children))
            elif node.type not in _COMMENTS:
                return Lexed(tuple(commands), self.offset(node.start_byte))
        return Lexed(tuple(commands))

    def _command(self, node: Node) -> Command:
        name = node.children[0]
        listed = next((child for child in node.children if child.type == "argument_list"), None)
        # An argument list; the closing commands (``endforeach(it)``) have bare arguments.
        items = (
            listed.children
            if listed is not None
            else [child for child in node.children if child.type == "argument"]
        )
        arguments: list[Argument] = []
        previous_end: int | None = None
        for item in items:
            if item.type in ("(", ")"):
                start, end = self.offset(item.start_byte), self.offset(item.end_byte)
                arguments.append(Argument(ArgKind.UNQUOTED, (item.type,), start, end))
                previous_end = None
            elif item.type == "argument":
                argument = self._argument(item.children[0])
                legacy = (
                    previous_end == item.start_byte
                    and arguments
                    and arguments[-1].kind is ArgKind.UNQUOTED
                    and argument.kind is ArgKind.QUOTED
                )
                if legacy:
                    # -Da="b c": one unquoted argument, its quoted part kept as written
                    last = arguments[-1]
                    pieces = _Pieces()
                    for piece in (*last.pieces, self.source(item)):
                        pieces.add(piece)
                    end = self.offset(item.end_byte)
                    arguments[-1] = Argument(ArgKind.UNQUOTED, pieces.done(), last.start, end)
                else:
                    arguments.append(argument)
                previous_end = item.end_byte
        return Command(self.source(name).lower(), self.offset(name.start_byte), tuple(arguments))

    def _argument(self, node: Node) -> Argument:
        start, end = self.offset(node.start_byte), self.offset(node.end_byte)
        if node.type == "bracket_argument":
            # Between the brackets as written: the grammar's content node leaves out
            # whitespace that starts it.
            opening, closing = node.children[0], node.children[-1]
            raw = self.data[opening.end_byte : closing.start_byte]
            text = raw.decode("utf-8", errors="surrogatepass")
            # CMake drops one newline right after the opening bracket.
            if text.startswith("\r\n"):
                text = text[2:]
            elif text.startswith("\n"):
                text = text[1:]
            return Argument(ArgKind.BRACKET, (text,), start, end)
        pieces = _Pieces()
        if node.type == "quoted_argument":
            for child in node.children:
                if child.type == "quoted_element":
                    self._pieces(child, pieces, 0)
            return Argument(ArgKind.QUOTED, pieces.done(), start, end)
        self._pieces(node, pieces, 0)
        return Argument(ArgKind.UNQUOTED, pieces.done(), start, end)

    def _pieces(self, node: Node, pieces: _Pieces, depth: int) -> None:
        """The text of ``node`` with its escapes decoded and its references as pieces."""
        if not node.children:
            pieces.add(self.source(node))
            return
        position = node.start_byte
        for child in node.children:
            if child.start_byte > position:
                pieces.add(self.data[position : child.start_byte].decode("utf-8", "surrogatepass"))
            if child.type == "variable_ref":
                pieces.add(self._reference(child, depth))
            elif child.type == "escape_sequence":
                pieces.add(self._escape(child))
            else:
                self._pieces(child, pieces, depth)
            position = child.end_byte
        if node.end_byte > position:
            pieces.add(self.data[position : node.end_byte].decode("utf-8", "surrogatepass"))

    def _escape(self, node: Node) -> str:
        """The text an escape stands for; ``\\;`` stays itself (it blocks a split), a line
        continuation is nothing."""
        text = self.source(node)
        if not text.startswith("\\"):
            return text  # the grammar calls a bare ';' in a quoted argument an escape
        char = text[1:]
        if char == ";":
            return "\\;"
        if char in ("\n", "\r\n"):
            return ""
        return _ENCODED.get(char, char)

    def _reference(self, node: Node, depth: int) -> VarRef:
        if depth >= _MAX_REFERENCE_DEPTH:
            raise _RefusedError
        inner = node.children[0]
        variable = next((child for child in inner.children if child.type == "variable"), None)
        pieces = _Pieces()
        if variable is not None:
            self._pieces(variable, pieces, depth + 1)
        return VarRef(_NAMESPACES.get(inner.type, ""), pieces.done())


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

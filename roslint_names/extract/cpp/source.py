"""The C++ source as the extractor reads it: spans, words, calls and string literals.

The extractor never walks the whole syntax tree: Python pays for every node it touches,
and a ROS file holds a few dozen interesting calls among tens of thousands of nodes.
Instead it finds the words it cares about (``advertise``, ``NodeHandle``...) with a regular
expression over the bytes, asks tree-sitter for the node at each match, and climbs from
there. ``Source.occurrences`` is that primitive, cached per word.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import Any

from tree_sitter import Node, Tree

from roslint_names.model import Span

IDENTIFIERS = frozenset(
    {"identifier", "field_identifier", "type_identifier", "namespace_identifier"}
)
FUNCTION_SCOPES = frozenset({"function_definition", "lambda_expression"})
STRING_LITERALS = frozenset({"string_literal", "raw_string_literal"})
MAX_CLIMB = 256  # ancestors looked at; hand-written C++ nests far less deeply
_WORD_BYTES = frozenset(b"abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_")
_WORDS_ONLY = bytes(byte if byte in _WORD_BYTES else ord(" ") for byte in range(256))
_STATEMENTS = frozenset(
    {
        "compound_statement",
        "expression_statement",
        "if_statement",
        "for_statement",
        "for_range_loop",
        "while_statement",
        "do_statement",
        "switch_statement",
        "return_statement",
        "try_statement",
    }
)
_SKIPPED_ARGUMENTS = frozenset({"comment", "(", ")", ",", "{", "}"})


class Source:
    """UTF-8 bytes, their syntax tree, and the conversions every fact needs."""

    def __init__(self, data: bytes, tree: Tree) -> None:
        self.data = data
        self.root = tree.root_node
        self._words_only = data.translate(_WORDS_ONLY)
        self._occurrences: dict[str, list[Node]] = {}

    def text(self, node: Node) -> str:
        return self.data[node.start_byte : node.end_byte].decode("utf-8", "replace")

    def span(self, node: Node) -> Span:
        """1-based lines and code-point columns of the node, end exclusive."""
        start, end = node.start_point, node.end_point
        return Span(
            start.row + 1,
            self._column(node.start_byte, start.column),
            end.row + 1,
            self._column(node.end_byte, end.column),
        )

    def _column(self, offset: int, byte_column: int) -> int:
        prefix = self.data[offset - byte_column : offset]
        return (byte_column if prefix.isascii() else len(prefix.decode("utf-8", "replace"))) + 1

    def line(self, node: Node) -> int:
        return node.start_point.row + 1

    def words(self, pattern: re.Pattern[bytes], parts: Iterable[bytes]) -> list[tuple[str, Node]]:
        """Each identifier ``pattern`` matches whole, in source order, with its node; every
        identifier it can match holds one of ``parts`` (identifier characters only).

        Matches inside comments, strings and macro bodies have no identifier node of their
        own and are dropped. The identifiers are found from their parts by bytes.find, in a
        copy of the file where all but identifier characters are spaces: re tries a pattern
        of alternatives at every offset, at a small multiple of the cost.
        """
        words_only = self._words_only
        spans = set()
        for part in parts:
            position = words_only.find(part)
            while position >= 0:
                start = words_only.rfind(b" ", 0, position) + 1
                end = words_only.find(b" ", position)
                end = len(words_only) if end < 0 else end
                spans.add((start, end))
                position = words_only.find(part, end)
        found = []
        for start, end in sorted(spans):
            word = self.data[start:end]
            if pattern.fullmatch(word):
                node = self._identifier_at(start, end)
                if node is not None:
                    found.append((word.decode("ascii"), node))
        return found

    def occurrences(self, word: str) -> list[Node]:
        """Every identifier node spelled ``word``, in source order."""
        found = self._occurrences.get(word)
        if found is None:
            # bytes.find and a boundary test: a regex starting with \b loses re's fast
            # literal search and made this the slowest step of the extractor.
            found = []
            encoded = word.encode("utf-8")
            # "" (a MISSING identifier of broken code) is found at every offset, forever.
            start = self.data.find(encoded) if encoded else -1
            while start >= 0:
                end = start + len(encoded)
                if self._bounded(start, end):
                    node = self._identifier_at(start, end)
                    if node is not None:
                        found.append(node)
                start = self.data.find(encoded, end)
            self._occurrences[word] = found
        return found

    def _bounded(self, start: int, end: int) -> bool:
        data = self.data
        return (start == 0 or data[start - 1] not in _WORD_BYTES) and (
            end == len(data) or data[end] not in _WORD_BYTES
        )

    def literals(self, spelling: str) -> list[Node]:
        """Every string literal spelled exactly ``spelling`` (quotes included)."""
        found = []
        for match in re.finditer(re.escape(spelling.encode("utf-8")), self.data):
            node = self.root.descendant_for_byte_range(match.start(), match.end())
            if node is not None and node.type == "string_content" and node.parent is not None:
                node = node.parent
            if (
                node is not None
                and node.type == "string_literal"
                and (node.start_byte, node.end_byte) == match.span()
            ):
                found.append(node)
        return found

    def _identifier_at(self, start: int, end: int) -> Node | None:
        node = self.root.descendant_for_byte_range(start, end)
        if node is None or node.start_byte != start or node.end_byte != end:
            return None
        return node if node.type in IDENTIFIERS else None


def word_pattern(words: Iterable[str]) -> re.Pattern[bytes]:
    """A regex matching any of ``words`` as a whole identifier.

    The alternatives are folded into a trie (``create_(?:publisher|service)``): Python's
    regex engine tries alternatives one by one, and the trie tries each character once.
    """
    return re.compile(rb"\b" + trie_regex(words).encode("ascii") + rb"\b")


def trie_regex(words: Iterable[str]) -> str:
    """An alternation of ``words`` as a trie: ``create_(?:publisher|service)``."""
    tree: dict[str, Any] = {}
    for word in words:
        node = tree
        for character in word:
            node = node.setdefault(character, {})
        node[""] = {}
    return _trie_regex(tree)


def _trie_regex(node: dict[str, Any]) -> str:
    branches = [re.escape(key) + _trie_regex(child) for key, child in sorted(node.items()) if key]
    if not branches:
        return ""
    ends_here = "" in node
    if len(branches) == 1 and not ends_here:
        return branches[0]
    return "(?:" + "|".join(branches) + ")" + ("?" if ends_here else "")


# ---------------------------------------------------------------------------------------
# Tree helpers


def field(node: Node | None, name: str) -> Node | None:
    return None if node is None else node.child_by_field_name(name)


def is_field(parent: Node | None, name: str, child: Node) -> bool:
    """Whether ``child`` is ``parent``'s field ``name`` (and not, say, its value)."""
    return parent is not None and parent.child_by_field_name(name) == child


def field_root(node: Node) -> Node | None:
    """What a chain of field accesses starts from: ``msg`` of ``msg.header.frame_id``
    (``node`` itself where it is no field access)."""
    root: Node | None = node
    while root is not None and root.type == "field_expression":
        root = root.child_by_field_name("argument")
    return root


def arguments(node: Node | None) -> list[Node]:
    """The argument expressions of an ``argument_list`` or ``initializer_list``."""
    if node is None:
        return []
    return [child for child in node.children if child.type not in _SKIPPED_ARGUMENTS]


def unparenthesized(node: Node) -> Node:
    while node.type == "parenthesized_expression" and node.named_child_count == 1:
        inner = node.named_children[0]
        node = inner
    return node


def enclosing_functions(node: Node) -> list[Node]:
    """Function definitions and lambdas around ``node``, innermost first.

    A statement outside any function belongs to a function whose head a macro hides
    (gtest's ``TEST_F(Suite, name) { ... }``): statements only exist in functions, so the
    outermost such statement counts as one. Past ``MAX_CLIMB`` ancestors (generated code),
    the last one reached stands for the unknown function around the node.
    """
    found: list[Node] = []
    block = None  # the outermost statement not yet known to belong to a function
    last = node
    for parent in _ancestors(node):
        last = parent
        if parent.type in FUNCTION_SCOPES:
            found.append(parent)
            block = None
        elif parent.type in _STATEMENTS:
            block = parent
    if last.parent is not None and last != node:
        block = last  # the climb was cut short: somewhere deep inside a function
    if block is not None:
        found.append(block)
    return found


def contains(outer: Node, inner: Node) -> bool:
    """Whether ``inner`` lies within ``outer`` (or is it)."""
    return outer.start_byte <= inner.start_byte and inner.end_byte <= outer.end_byte


def enclosing(node: Node, types: frozenset[str]) -> Node | None:
    """The nearest ancestor of one of ``types`` (within ``MAX_CLIMB`` levels)."""
    return next((parent for parent in _ancestors(node) if parent.type in types), None)


def _ancestors(node: Node) -> Iterator[Node]:
    # tree-sitter finds a parent by descending from the root, so climbing is quadratic in
    # the depth: the cap keeps pathological nesting (generated code) from stalling a run.
    parent = node.parent
    for _ in range(MAX_CLIMB):
        if parent is None:
            return
        yield parent
        parent = parent.parent


def compact(text: str) -> str:
    """A type or expression spelling without layout: ``std_msgs::String``."""
    text = re.sub(r"\s+", " ", text.strip())
    return re.sub(r"\s*(::|<|>|,)\s*", lambda match: match.group(1), text)


def template_types(source: Source, template: Node | None) -> list[str]:
    """The spellings of a ``template_argument_list``'s arguments."""
    if template is None:
        return []
    return [compact(source.text(child)) for child in template.named_children]


# ---------------------------------------------------------------------------------------
# Calls


@dataclass(frozen=True)
class Call:
    """A call seen from the word that names it.

    ``nh.advertise<T>("a", 1)``: name ``advertise``, receiver ``nh``, template ``<T>``;
    ``ros::service::call("b", srv)``: name ``call``, qualifier ``ros::service``.
    """

    node: Node  # the call_expression
    word: Node  # the identifier that names the function
    name: str
    qualifier: str
    receiver: Node | None
    template: Node | None
    arguments: tuple[Node, ...]


def call_named_by(source: Source, word: Node) -> Call | None:
    """The call whose callee ``word`` names, if ``word`` is the callee's last name."""
    node = word
    template = None
    parent = node.parent
    if parent is not None and parent.type in ("template_method", "template_function"):
        if not is_field(parent, "name", node):
            return None
        template, node, parent = parent.child_by_field_name("arguments"), parent, parent.parent
    if parent is not None and parent.type == "dependent_name":
        node, parent = parent, parent.parent  # ops.template init<M>(...)
    receiver = None
    qualifiers: list[str] = []
    if parent is not None and parent.type == "field_expression":
        if not is_field(parent, "field", node):
            return None
        receiver, node, parent = parent.child_by_field_name("argument"), parent, parent.parent
    while parent is not None and parent.type == "qualified_identifier":
        if not is_field(parent, "name", node):
            return None
        scope = parent.child_by_field_name("scope")
        qualifiers.insert(0, "" if scope is None else compact(source.text(scope)))
        node, parent = parent, parent.parent
    if parent is None or parent.type != "call_expression" or not is_field(parent, "function", node):
        return None
    return Call(
        node=parent,
        word=word,
        name=source.text(word),
        qualifier="::".join(qualifiers),
        receiver=receiver,
        template=template,
        arguments=tuple(arguments(parent.child_by_field_name("arguments"))),
    )


# ---------------------------------------------------------------------------------------
# String literals

_ESCAPE = re.compile(
    r"\\(?:x([0-9A-Fa-f]+)|u([0-9A-Fa-f]{4})|U([0-9A-Fa-f]{8})|([0-7]{1,3})|(.))", re.DOTALL
)
_SIMPLE_ESCAPES = {
    "n": "\n",
    "t": "\t",
    "r": "\r",
    "a": "\a",
    "b": "\b",
    "f": "\f",
    "v": "\v",
    "\\": "\\",
    '"': '"',
    "'": "'",
    "?": "?",
}


def unescape(text: str) -> str:
    """The characters a C++ string literal's body stands for."""

    def replace(match: re.Match[str]) -> str:
        hexadecimal, short, long, octal, simple = match.groups()
        number = hexadecimal or short or long
        if number is not None:
            return _character(int(number, 16))
        if octal is not None:
            return _character(int(octal, 8))
        return _SIMPLE_ESCAPES.get(simple, simple)

    return _ESCAPE.sub(replace, text) if "\\" in text else text


def _character(code: int) -> str:
    # No character above U+10FFFF, nor a UTF-16 surrogate (which no report could print).
    return chr(code) if code <= 0x10FFFF and not 0xD800 <= code <= 0xDFFF else "\ufffd"


def literal_value(source: Source, node: Node) -> str | None:
    """The value of one ``string_literal`` or ``raw_string_literal``; None for others."""
    if node.type == "raw_string_literal":
        content = next((c for c in node.children if c.type == "raw_string_content"), None)
        return "" if content is None else source.text(content)
    if node.type != "string_literal":
        return None
    text = source.text(node)
    opening, closing = text.find('"'), text.rfind('"')
    if opening < 0 or closing <= opening:
        return None  # an unterminated literal in broken code
    return unescape(text[opening + 1 : closing])


_LITERAL_SEQUENCE = re.compile(r'\s*(?:(?:u8|u|U|L)?"((?:[^"\\\n]|\\.)*)"\s*)+')
_ONE_LITERAL = re.compile(r'(?:u8|u|U|L)?"((?:[^"\\\n]|\\.)*)"')


def macro_literal(text: str) -> str | None:
    """The value of a ``#define`` body made of adjacent string literals only."""
    if not _LITERAL_SEQUENCE.fullmatch(text):
        return None
    return "".join(unescape(match.group(1)) for match in _ONE_LITERAL.finditer(text))

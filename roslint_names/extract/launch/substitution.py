"""The text layer shared by the launch XML, launch YAML and URDF/XACRO extractors.

Three things live here because all three extractors need them and none of them needs a
parser: where a piece of text sits in its file (``Source``, ``Located``), what the text
means once ``$(arg x)``, ``$(var x)`` and ``${x}`` are substituted (``substitute``,
``Bindings``), and how a ROS command line in ``args=`` / ``<argument>`` splits into
``a:=b`` assignments (``ros1_assignments``, ``ros2_assignments``).

A substitution is replaced only by a value known from the file itself (an argument
default, a ``<let>``, a XACRO property). Anything else (``$(find pkg)``, ``$(env X)``,
``$(eval ...)``, a XACRO expression, an argument with no default) makes the whole value
dynamic: the raw text is kept for display and rules skip it, because a guess would report
names that never exist at run time.
"""

from __future__ import annotations

import functools
import re
from bisect import bisect_right
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from enum import Enum

from roslint_names.model import Span

# ---------------------------------------------------------------------------------------
# Positions


_LINE_BREAK = re.compile(r"\r\n|\r|\n")


class Source:
    """Decoded file text with a line table: turns string offsets into spans.

    Columns count code points. A lone CR counts as a line break, as in every editor and in
    the XML spec's end-of-line handling; CRLF counts once.
    """

    def __init__(self, text: str) -> None:
        self.text = text
        self._line_starts = [0, *(m.end() for m in _LINE_BREAK.finditer(text))]

    def position(self, offset: int) -> tuple[int, int]:
        index = bisect_right(self._line_starts, offset) - 1
        return index + 1, offset - self._line_starts[index] + 1

    def offset(self, line: int, column: int) -> int:
        """The offset of a 1-based ``line`` and ``column``: ``position``'s inverse."""
        index = min(max(line, 1), len(self._line_starts)) - 1
        return self._line_starts[index] + max(column, 1) - 1

    def span(self, start: int, end: int) -> Span:
        line, column = self.position(start)
        end_line, end_column = self.position(max(start, end))
        return Span(line, column, end_line, end_column)


_SURROGATE = re.compile("[\ud800-\udfff]")


def without_surrogates(value: str) -> str:
    """``value`` with U+FFFD for each lone surrogate.

    An escape (``"\\ud800"`` in Python, or in a YAML double-quoted scalar) puts a UTF-16
    surrogate into a string: it is no character, no ROS runtime accepts it, and no report
    (all UTF-8) could print it. The C++ extractor decodes such escapes the same way.
    """
    return value if value.isascii() else _SURROGATE.sub("\ufffd", value)


@dataclass(frozen=True)
class Located:
    """A value as the parser delivered it, and where its raw text sits in the file.

    Parts of a value (``__name:=x`` inside ``args``) need their own spans, so a value may
    carry how its characters map to raw source offsets: ``base`` when they map one to one
    (the usual case: raw offset = ``base`` + index), else ``starts``/``ends`` per character
    (an ``&amp;`` is five raw characters for one parsed one). Without either, a slice
    falls back to the whole span. ``opaque`` marks text that still holds unexpanded entity
    references: its real value is unknown, so extractors treat it as dynamic.
    """

    text: str
    span: Span
    source: Source | None = field(default=None, compare=False, repr=False)
    base: int | None = field(default=None, compare=False, repr=False)
    starts: tuple[int, ...] | None = field(default=None, compare=False, repr=False)
    ends: tuple[int, ...] | None = field(default=None, compare=False, repr=False)
    opaque: bool = False

    def slice(self, start: int, end: int) -> Located:
        """The part ``text[start:end]``, with the span of its own raw characters."""
        text = self.text[start:end]
        start = min(start, len(self.text))
        end = max(start, min(end, len(self.text)))
        if self.source is not None and self.base is not None:
            first = self.base + start
            span = self.source.span(first, self.base + end)
            return Located(text, span, self.source, first, opaque=self.opaque)
        if self.source is None or self.starts is None or self.ends is None:
            return Located(text, self.span, opaque=self.opaque)
        starts, ends = self.starts[start:end], self.ends[start:end]
        if starts:
            span = self.source.span(starts[0], ends[-1])
        elif start < len(self.starts):
            span = self.source.span(self.starts[start], self.starts[start])
        elif self.ends:
            span = self.source.span(self.ends[-1], self.ends[-1])
        else:
            span = self.span
        return Located(text, span, self.source, None, starts, ends, self.opaque)

    def strip(self) -> Located:
        """Without surrounding XML whitespace (space, tab, CR, LF)."""
        stripped = self.text.strip(_XML_SPACE)
        if stripped == self.text:
            return self
        start = len(self.text) - len(self.text.lstrip(_XML_SPACE))
        return self.slice(start, start + len(stripped))


_XML_SPACE = " \t\r\n"

# ---------------------------------------------------------------------------------------
# Substitutions


class Dialect(Enum):
    """Which substitution syntax a file uses."""

    ROS1 = "ros1"  # roslaunch: $(arg x)
    ROS2 = "ros2"  # launch / launch_ros frontends: $(var x)
    XACRO = "xacro"  # ${x} properties and $(arg x) arguments


# The two kinds of names a substitution can look up.
ARG = "arg"  # $(arg x) in ROS 1 and XACRO, $(var x) in ROS 2
PROPERTY = "property"  # ${x} in XACRO

_LOOKUP_COMMAND = {Dialect.ROS1: "arg", Dialect.ROS2: "var", Dialect.XACRO: "arg"}
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
WHITESPACE = re.compile(r"\s")  # the characters str.isspace() accepts, every one


@dataclass(frozen=True)
class Value:
    """A value after substitution; when dynamic, ``text`` is the raw text, for display."""

    text: str
    dynamic: bool = False


Lookup = Callable[[str, str], "Value | None"]  # (ARG or PROPERTY, name) -> value, None unknown


class _NotStaticError(Exception):
    """Raised inside the expander as soon as one part of the value is not static."""


def substitute(raw: str, dialect: Dialect, lookup: Lookup) -> Value:
    """Replace every substitution in ``raw``; dynamic as a whole if any part is unknown."""
    if "$" not in raw:
        return Value(raw)
    try:
        return Value(_expand(raw, dialect, lookup))
    except _NotStaticError:
        return Value(raw, dynamic=True)


def _expand(raw: str, dialect: Dialect, lookup: Lookup) -> str:
    out: list[str] = []
    i = 0
    while (dollar := raw.find("$", i)) >= 0:  # text up to the next '$' is kept as it is
        out.append(raw[i:dollar])
        i = dollar
        if dialect is Dialect.XACRO and raw.startswith(("$${", "$$("), i):
            out.append(raw[i + 1 : i + 3])  # XACRO's escape for a literal ${ or $(
            i += 3
        elif raw.startswith("$(", i):
            end = _closing(raw, i + 2, "(", ")")
            out.append(_command(raw[i + 2 : end], dialect, lookup))
            i = end + 1
        elif dialect is Dialect.XACRO and raw.startswith("${", i):
            end = _closing(raw, i + 2, "{", "}")
            out.append(_property(raw[i + 2 : end].strip(), lookup))
            i = end + 1
        else:
            out.append("$")
            i += 1
    out.append(raw[i:])
    return "".join(out)


def _closing(raw: str, start: int, opening: str, closing: str) -> int:
    end = closing_bracket(raw, start, opening, closing)
    if end is None:
        raise _NotStaticError  # unbalanced: the launch system would fail, we just do not know
    return end


def closing_bracket(raw: str, start: int, opening: str = "(", closing: str = ")") -> int | None:
    """Index of the bracket closing the one just before ``start``; quotes hide brackets.
    None when it is never closed."""
    depth, quote = 1, ""
    for match in _bracket_or_quote(opening, closing).finditer(raw, start):
        char, i = match.group(), match.start()
        if quote:
            quote = "" if char == quote else quote
        elif char in "'\"":
            quote = char
        elif char == opening:
            depth += 1
        elif char == closing:
            depth -= 1
            if depth == 0:
                return i
    return None


@functools.cache
def _bracket_or_quote(opening: str, closing: str) -> re.Pattern[str]:
    """The characters ``closing_bracket`` acts on: every other one leaves it as it is."""
    return re.compile(f"[{re.escape(opening + closing)}'\"]")


def _command(body: str, dialect: Dialect, lookup: Lookup) -> str:
    command, _, argument = body.strip().partition(" ")
    if command != _LOOKUP_COMMAND[dialect]:
        raise _NotStaticError  # find, env, optenv, anon, eval, dirname, command, find-pkg-share...
    name = _unquote(_expand(argument.strip(), dialect, lookup).strip())
    if not name or WHITESPACE.search(name):
        raise _NotStaticError
    value = lookup(ARG, name)
    if value is None or value.dynamic:
        raise _NotStaticError
    return value.text


def _property(expression: str, lookup: Lookup) -> str:
    if not _IDENTIFIER.fullmatch(expression):
        raise _NotStaticError  # a Python expression: XACRO evaluates it, we do not
    value = lookup(PROPERTY, expression)
    if value is None or value.dynamic:
        raise _NotStaticError
    return value.text


def _unquote(text: str) -> str:
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"":
        return text[1:-1]
    return text


def truth(value: Value) -> bool | None:
    """A condition's static truth: roslaunch, launch and XACRO all accept true/false/1/0."""
    if value.dynamic:
        return None
    text = value.text.strip().lower()
    if text in ("true", "1"):
        return True
    if text in ("false", "0"):
        return False
    return None


def skipped(if_value: Value | None, unless_value: Value | None) -> bool:
    """True only when a condition is statically known to drop its element."""
    return (if_value is not None and truth(if_value) is False) or (
        unless_value is not None and truth(unless_value) is True
    )


@dataclass(frozen=True)
class Condition:
    """The raw ``if``/``unless`` text guarding a declaration (either may be absent)."""

    if_raw: str | None = None
    unless_raw: str | None = None


@dataclass(frozen=True)
class Declaration:
    """One declaration of a file-global binding: ``raw`` is None when it has no value."""

    raw: str | None
    conditions: tuple[Condition, ...] = ()


class Bindings:
    """File-global bindings, resolved on first use: ROS 1 args, XACRO args and properties.

    roslaunch and XACRO let a value refer to other bindings, so values are substituted
    lazily and cycles become dynamic. A binding declared more than once (``<arg>`` pairs
    guarded by ``if``/``unless``) keeps its value only if every declaration that is not
    statically excluded agrees. A child scope (a XACRO macro body) shadows the names in
    ``opaque`` (the macro's parameters, known only per call) with dynamic values.
    """

    def __init__(
        self,
        dialect: Dialect,
        parent: Bindings | None = None,
        opaque: Iterable[str] = (),
    ) -> None:
        self.dialect = dialect
        self._parent = parent
        self._opaque = frozenset(opaque)
        self._declarations: dict[tuple[str, str], list[Declaration]] = {}
        self._resolved: dict[tuple[str, str], Value | None] = {}
        self._resolving: set[tuple[str, str]] = set()

    def declare(self, space: str, name: str, declaration: Declaration) -> None:
        self._declarations.setdefault((space, name), []).append(declaration)

    def child(self, opaque: Iterable[str]) -> Bindings:
        return Bindings(self.dialect, self, opaque)

    def lookup(self, space: str, name: str) -> Value | None:
        key = (space, name)
        if key in self._declarations:
            return self._resolve(key)
        if space == PROPERTY and name in self._opaque:
            return Value(name, dynamic=True)
        return self._parent.lookup(space, name) if self._parent else None

    def substitute(self, raw: str) -> Value:
        return substitute(raw, self.dialect, self.lookup)

    def allows(self, conditions: Sequence[Condition]) -> bool:
        """False when one of the conditions statically excludes what it guards."""
        return not any(self._excludes(condition) for condition in conditions)

    def _excludes(self, condition: Condition) -> bool:
        if_value = None if condition.if_raw is None else self.substitute(condition.if_raw)
        unless_value = (
            None if condition.unless_raw is None else self.substitute(condition.unless_raw)
        )
        return skipped(if_value, unless_value)

    def _resolve(self, key: tuple[str, str]) -> Value | None:
        if key in self._resolved:
            return self._resolved[key]
        if key in self._resolving:
            return None  # a cycle: no static value
        self._resolving.add(key)
        try:
            value = self._agreed_value(self._declarations[key])
        finally:
            self._resolving.discard(key)
        self._resolved[key] = value
        return value

    def _agreed_value(self, declarations: Sequence[Declaration]) -> Value | None:
        live = [d for d in declarations if self.allows(d.conditions)]
        if not live:
            return None
        values = {
            Value("", dynamic=True) if d.raw is None else self.substitute(d.raw) for d in live
        }
        if len(values) != 1:
            return Value("", dynamic=True)
        return values.pop()


def mapping_lookup(values: Mapping[str, Value]) -> Lookup:
    """A lookup over already-substituted ``$(var x)`` values (ROS 2 launch scopes)."""

    def lookup(space: str, name: str) -> Value | None:
        return values.get(name) if space == ARG else None

    return lookup


# ---------------------------------------------------------------------------------------
# Command lines


def split_words(located: Located) -> list[Located]:
    """Whitespace-separated words; a ``$(...)`` or ``${...}`` holding spaces stays one word."""
    text, words, i = located.text, [], 0
    while i < len(text):
        if text[i].isspace():
            i += 1
            continue
        start, depth = i, 0
        while i < len(text) and (depth or not text[i].isspace()):
            if text.startswith(("$(", "${"), i):
                depth, i = depth + 1, i + 2
                continue
            if depth and text[i] in "({":
                depth += 1
            elif depth and text[i] in ")}":
                depth -= 1
            i += 1
        words.append(located.slice(start, i))
    return words


@dataclass(frozen=True)
class Assignment:
    """One ``key:=value`` word of a command line; ``flag`` is "", "-r" or "-p"."""

    flag: str
    key: Located
    value: Located


class Meaning(Enum):
    """What an assignment on a ROS command line sets."""

    NODE = "node"  # __name:= (ROS 1), __node:= / __name:= (ROS 2)
    NAMESPACE = "namespace"  # __ns:=
    REMAP = "remap"
    PRIVATE_PARAMETER = "private-parameter"  # ROS 1 _param:=value
    PARAMETER = "parameter"  # ROS 2 -p name:=value


def _assignment(flag: str, word: Located) -> Assignment | None:
    index = word.text.find(":=")
    if index <= 0:
        return None
    return Assignment(flag, word.slice(0, index), word.slice(index + 2, len(word.text)))


def ros1_assignments(located: Located) -> list[Assignment]:
    """Every ``a:=b`` word of a ROS 1 command line (``<node args>``)."""
    found = (_assignment("", word) for word in split_words(located))
    return [assignment for assignment in found if assignment is not None]


_ROS2_VALUE_FLAGS = {"-r": "-r", "--remap": "-r", "-p": "-p", "--param": "-p"}
_ROS2_SKIP_NEXT = frozenset(
    {"--params-file", "-e", "--enclave", "--log-level", "--log-config-file", "--log-file-name"}
)


def ros2_assignments(located: Located, *, all_ros_args: bool, bare: bool) -> list[Assignment]:
    """The remaps and parameters of a ROS 2 command line.

    Only words inside ``--ros-args`` ... ``--`` count (all of them for ``ros_args=``, which
    launch wraps itself). ``bare`` also accepts a ``a:=b`` word without ``-r``, the form
    gazebo_ros read from ``<argument>`` before ``--ros-args`` existed.
    """
    words = split_words(located)
    found: list[Assignment | None] = []
    inside, i = all_ros_args, 0
    while i < len(words):
        word = words[i].text
        if word == "--ros-args":
            inside = True
        elif inside and word == "--" and not all_ros_args:
            inside = False
        elif inside and word in _ROS2_VALUE_FLAGS and i + 1 < len(words):
            found.append(_assignment(_ROS2_VALUE_FLAGS[word], words[i + 1]))
            i += 1
        elif inside and word in _ROS2_SKIP_NEXT:
            i += 1  # its value may look like an assignment (--log-level rclcpp:=debug)
        elif bare and ":=" in word:
            found.append(_assignment("", words[i]))
        i += 1
    return [assignment for assignment in found if assignment is not None]


def strip_node_prefix(key: Located) -> Located:
    """``talker:chatter`` (a remap aimed at one node of a process) -> ``chatter``."""
    head, separator, _ = key.text.rpartition(":")
    if not separator or "$" in head:
        return key
    return key.slice(len(head) + 1, len(key.text))


def meaning(flag: str, key: str, dialect: Dialect) -> Meaning | None:
    """What ``key:=...`` sets; None for special arguments that hold no graph name."""
    if flag == "-p":
        return Meaning.PARAMETER
    if key == "__ns":
        return Meaning.NAMESPACE
    if key == "__name" or (key == "__node" and dialect is not Dialect.ROS1):
        return Meaning.NODE
    if key.startswith("__"):
        return None  # __log, __master, __ip, __hostname...
    if key.startswith("_") and dialect is Dialect.ROS1:
        return Meaning.PRIVATE_PARAMETER  # ROS 2 has no such form: _x is a hidden topic
    return Meaning.REMAP

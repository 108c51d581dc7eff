"""What CMake arguments evaluate to, as far as one build file can tell.

Values are plain strings in which two private characters stand for what the file does not
determine: ``DYNAMIC`` for text only the configured build knows (a variable this file
never sets, ``$ENV{X}``, a directory a function parameter names), ``SOURCE_DIR`` for the
build file's own directory (``${CMAKE_CURRENT_SOURCE_DIR}``, ``${PROJECT_SOURCE_DIR}``).
``clean`` removes both characters from the file's text before lexing, so in a value they
can mean nothing else. A list is its elements joined with ``;``, as in CMake, so a source
list can hold one unknown element among known ones and only that one is lost.

Only the commands that give variables values this module can follow are evaluated:
``project``, ``set``, ``unset`` and ``list(APPEND|PREPEND|REMOVE_ITEM)``; the commands that
compute a variable (``file(GLOB)``, ``string``, ``list(GET)``...) make it unknown. There is
no control flow: both branches of an ``if`` are read, in order, so the last ``set`` wins.
Function and macro bodies are read where they are defined, with their parameters unknown
and the variables they set kept to themselves, and again at each call with the arguments
bound (``cmake.py`` holds the bodies); a ``foreach`` over a list the file determines runs
once per item, and over anything else once, with its variable unknown.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from roslint_names.extract.build.cmake_syntax import ArgKind, Argument, Piece, VarRef

DYNAMIC = "\x00"
SOURCE_DIR = "\x01"

_MARKERS = re.compile("[\x00\x01]")
_UNESCAPED_SEMICOLON = re.compile(r"(?<!\\);")


def clean(text: str) -> str:
    """The file's text with the marker characters replaced (offsets do not move)."""
    return _MARKERS.sub("\ufffd", text)


@dataclass(frozen=True)
class Value:
    """One evaluated argument (one list element, for an unquoted argument) and the offsets
    of the raw argument it came from."""

    text: str
    start: int
    end: int

    @property
    def dynamic(self) -> bool:
        return DYNAMIC in self.text


def split_list(text: str) -> list[str]:
    """CMake's list split: at each ``;`` not escaped, empty elements dropped."""
    return [item.replace("\\;", ";") for item in _UNESCAPED_SEMICOLON.split(text) if item]


# Where the build file's directory is known under another name.
_SOURCE_DIR_VARIABLES = ("CMAKE_CURRENT_SOURCE_DIR", "CMAKE_CURRENT_LIST_DIR", "PROJECT_SOURCE_DIR")
# Commands that write the variable at this argument index, with a value never known here.
_COMPUTED_OUTPUT = {"file": 1, "aux_source_directory": 1, "get_filename_component": 0, "math": 1}
# Commands that may write any of their arguments: a known variable named there is lost.
_MAY_WRITE = frozenset(
    {
        "string",
        "cmake_path",
        "separate_arguments",
        "get_target_property",
        "get_property",
        "get_directory_property",
        "get_source_file_property",
        "find_file",
        "find_path",
        "find_library",
        "find_program",
        "execute_process",
        "cmake_parse_arguments",
    }
)
_LIST_READERS = frozenset({"LENGTH", "GET", "JOIN", "SUBLIST", "FIND"})
_LIST_KEEPS_ITEMS = frozenset({"REMOVE_DUPLICATES", "SORT", "REVERSE"})
_SCOPES = {"function": "function", "macro": "function", "block": "block", "foreach": "foreach"}
_SCOPE_ENDS = {
    "endfunction": "function",
    "endmacro": "function",
    "endblock": "block",
    "endforeach": "foreach",
}

# The commands ``Variables.apply`` follows; the others need not be evaluated for it.
FOLLOWED = frozenset(
    {"project", "set", "unset", "list", *_COMPUTED_OUTPUT, *_MAY_WRITE, *_SCOPES, *_SCOPE_ENDS}
)


@dataclass
class _Layer:
    kind: str  # "file", "function", "macro", "block" or "foreach"
    values: dict[str, str]


class Variables:
    """The variables of one build file, in layers for the bodies being read."""

    def __init__(self) -> None:
        self._layers = [_Layer("file", dict.fromkeys(_SOURCE_DIR_VARIABLES, SOURCE_DIR))]

    def get(self, name: str) -> str:
        for layer in reversed(self._layers):
            if name in layer.values:
                return layer.values[name]
        return DYNAMIC

    def is_set(self, name: str) -> bool:
        return any(name in layer.values for layer in self._layers)

    def set(self, name: str, text: str) -> None:
        # A foreach loop or a macro call opens no CMake scope: what its body sets outlives it.
        for layer in reversed(self._layers):
            if layer.kind not in ("foreach", "macro"):
                layer.values[name] = text
                return

    def enter(self, kind: str, bindings: dict[str, str]) -> None:
        """Open a layer holding ``bindings``: a call's arguments, a loop's item."""
        self._layers.append(_Layer(kind, bindings))

    def leave(self) -> None:
        del self._layers[-1]

    def evaluate(self, argument: Argument) -> list[Value]:
        """The values an argument stands for: one, or one per list element if unquoted."""
        if argument.kind is ArgKind.BRACKET:
            text = "".join(piece for piece in argument.pieces if isinstance(piece, str))
            return [Value(text, argument.start, argument.end)]
        text = self._expand(argument.pieces)
        if argument.kind is ArgKind.QUOTED:
            return [Value(text, argument.start, argument.end)]
        return [Value(item, argument.start, argument.end) for item in split_list(text)]

    def values(self, arguments: Iterable[Argument]) -> list[Value]:
        return [value for argument in arguments for value in self.evaluate(argument)]

    def _expand(self, pieces: Sequence[Piece]) -> str:
        return "".join(
            self._reference(piece) if isinstance(piece, VarRef) else piece for piece in pieces
        )

    def _reference(self, reference: VarRef) -> str:
        if reference.namespace:  # $ENV{X}, $CACHE{X}: the build machine's
            return DYNAMIC
        # A name with an unknown part names no variable set here: it is unknown too.
        return self.get(self._expand(reference.name))

    # -----------------------------------------------------------------------------------
    # Commands that change variables

    def apply(self, command: str, values: Sequence[Value]) -> None:
        """Follow ``command`` if it is one that changes variables or opens a body."""
        if command == "project":
            self._project(values)
        elif command == "set":
            self._set(values)
        elif command == "unset":
            if values and not values[0].dynamic and values[-1].text != "PARENT_SCOPE":
                self.set(values[0].text, "")
        elif command == "list":
            self._list(values)
        elif command in _COMPUTED_OUTPUT:
            self._lose(values[_COMPUTED_OUTPUT[command] : _COMPUTED_OUTPUT[command] + 1])
        elif command in _MAY_WRITE:
            self._lose(value for value in values if self.is_set(value.text))
        elif command in _SCOPES:
            self._open(_SCOPES[command], command, values)
        elif command in _SCOPE_ENDS:
            self._close(_SCOPE_ENDS[command])

    def _lose(self, values: Iterable[Value]) -> None:
        for value in values:
            if not value.dynamic:
                self.set(value.text, DYNAMIC)

    def _project(self, values: Sequence[Value]) -> None:
        if not values:
            return
        name = values[0].text
        self.set("PROJECT_NAME", name)
        if not values[0].dynamic:
            self.set(f"{name}_SOURCE_DIR", SOURCE_DIR)

    def _set(self, values: Sequence[Value]) -> None:
        if not values or values[0].dynamic or values[0].text.startswith("ENV{"):
            return
        name, items = values[0].text, [value.text for value in values[1:]]
        if items and items[-1] == "PARENT_SCOPE":
            return  # it sets the including directory's variable, not this file's
        if "CACHE" in items:
            items = items[: items.index("CACHE")]
            if self.is_set(name):
                return  # a normal variable hides the cache entry of the same name
        self.set(name, ";".join(items))

    def _list(self, values: Sequence[Value]) -> None:
        if len(values) < 2 or values[1].dynamic:
            return
        operation, name, items = values[0].text, values[1].text, [v.text for v in values[2:]]
        # A list never set is empty: appending to it is how source lists start.
        current = split_list(self.get(name)) if self.is_set(name) else []
        if operation == "APPEND":
            self.set(name, ";".join(current + items))
        elif operation == "PREPEND":
            self.set(name, ";".join(items + current))
        elif operation == "REMOVE_ITEM":
            if any(DYNAMIC in item for item in items):
                self.set(name, DYNAMIC)
            else:
                self.set(name, ";".join(item for item in current if item not in items))
        elif operation in _LIST_READERS:
            self._lose(values[-1:])
        elif operation.startswith("POP_"):
            self._lose(values[1:])  # the list and the variables it pops into
        elif operation not in _LIST_KEEPS_ITEMS:  # INSERT, FILTER, TRANSFORM...: it changes
            texts = [value.text for value in values]
            output = texts.index("OUTPUT_VARIABLE") + 1 if "OUTPUT_VARIABLE" in texts else 1
            self._lose(values[output : output + 1])

    def _open(self, kind: str, command: str, values: Sequence[Value]) -> None:
        texts = [value.text for value in values]
        if command == "foreach":
            shadowed = texts[: texts.index("IN")] if "IN" in texts else texts[:1]
        elif command == "block":
            shadowed = []
        else:
            shadowed = [*texts[1:], "ARGN", "ARGV", "ARGC"]
        self._layers.append(_Layer(kind, dict.fromkeys(shadowed, DYNAMIC)))

    def _close(self, kind: str) -> None:
        for index in range(len(self._layers) - 1, 0, -1):
            if self._layers[index].kind == kind:
                del self._layers[index:]
                return

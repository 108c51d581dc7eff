"""String constants a C++ header defines for other files, and the files C++ includes.

Read from the bytes without parsing: a header of constants (moveit's
``capability_names.hpp``: ``static const std::string MOVE_ACTION = "move_action";``)
holds no ROS marker and is never parsed. ``symbols`` gives a name argument that is such a
constant of an included header of the same package its value.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from .source import macro_literal

HEADER_SUFFIXES = (".h", ".hh", ".hpp", ".hxx", ".h++", ".ipp", ".inl")

_LITERAL = rb'(?:u8|u|U|L)?"(?:[^"\\\n]|\\.)*"'
_ASSIGNED_LITERAL = re.compile(rb'=\s*(?:u8|u|U|L)?"')
_CONSTANT = re.compile(
    rb"[ \t]*(?:(?:static|inline|extern)[ \t]+)*(?:const|constexpr)\b([^;{}()=\n]*?)"
    rb"\b([A-Za-z_]\w*)[ \t]*(?:\[[ \t]*\])?\s*=\s*((?:" + _LITERAL + rb"\s*)+);"
)
# Directives, found from their `#`: a pattern starting with (?m)^[ \t]* is tried at every
# offset, one starting with `#` only at each `#`; those with more than blanks before them
# on their line are dropped (`_directives`).
_DEFINE = re.compile(
    rb"(?m)#[ \t]*define[ \t]+([A-Za-z_]\w*)[ \t]+((?:" + _LITERAL + rb"[ \t]*)+)$"
)
_STRING_TYPE = re.compile(rb"\b(?:string|string_view|char)\b")
_INCLUDE = re.compile(rb'#[ \t]*include[ \t]*[<"]([^>"\n]+)[>"]')
# An included source file, not a header: ``#include "ikfast_solver.cpp"``.
_SOURCE_INCLUDE = re.compile(
    rb'#[ \t]*include[ \t]*[<"](?:[^>"\n]*/)?([^>"\n/]+\.(?:cpp|cc|cxx|c\+\+|c|C|cu))[>"]'
)


def is_header(path: str) -> bool:
    return path.lower().endswith(HEADER_SUFFIXES)


def header_constants(data: bytes) -> tuple[tuple[str, str], ...]:
    """(name, value) of each string constant and string macro the header defines."""
    found: list[tuple[str, str]] = []
    if b"const" in data:
        # Every header is scanned: find the `= "` of a definition first (a literal search),
        # then match the declaration from the start of its line, or of the line above
        # (`static const std::string NAME =` then the literal on the next line).
        checked: set[int] = set()
        for assignment in _ASSIGNED_LITERAL.finditer(data):
            line = data.rfind(b"\n", 0, assignment.start()) + 1
            for start in (line, data.rfind(b"\n", 0, max(line - 1, 0)) + 1):
                if start in checked:
                    continue
                checked.add(start)
                match = _CONSTANT.match(data, start)
                if match is not None and _STRING_TYPE.search(match.group(1)):
                    found += _constant(match.group(2), match.group(3))
    if b"define" in data:
        for match in _directives(_DEFINE, data):
            found += _constant(match.group(1), match.group(2))
    return tuple(sorted(set(found)))


def included_paths(data: bytes) -> tuple[str, ...]:
    """The paths of the file's ``#include`` lines, in order."""
    return tuple(
        match.group(1).decode("utf-8", "replace").strip() for match in _directives(_INCLUDE, data)
    )


def included_sources(data: bytes) -> tuple[str, ...]:
    """The names of the source files (not headers) the file includes, sorted: they are
    compiled as part of it, though no build file names them."""
    if b".c" not in data and b".C" not in data:
        return ()
    found = {
        match.group(1).decode("utf-8", "replace") for match in _directives(_SOURCE_INCLUDE, data)
    }
    return tuple(sorted(found))


def _directives(pattern: re.Pattern[bytes], data: bytes) -> Iterator[re.Match[bytes]]:
    """The matches of ``pattern`` (one line each) with only blanks before them on their line."""
    for match in pattern.finditer(data):
        line = data.rfind(b"\n", 0, match.start()) + 1
        if not data[line : match.start()].strip(b" \t"):
            yield match


def _constant(name: bytes, literals: bytes) -> list[tuple[str, str]]:
    value = macro_literal(literals.decode("utf-8", "replace").strip())
    return [] if value is None else [(name.decode("ascii"), value)]

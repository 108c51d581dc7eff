"""Inline suppressions, each in its language's own comment form.

- C++: ``// roslint-names: ignore RN202`` on the line, or alone on the line before. The
  form ``--add-noqa`` writes: cpplint (and ament_cpplint's copy, which ``colcon test`` runs)
  reports an unknown category in ``NOLINT(...)`` as ``readability/nolint``, so a
  suppression in that form would turn the ROS style gate red. ``// NOLINT(RN202)`` on the
  line and ``// NOLINTNEXTLINE(RN202)`` on the line before are still read.
- Python: ``# noqa: RN202`` on the line.
- XML (launch, URDF, XACRO): ``<!-- roslint-names: ignore RN202 -->`` after the markup
  on the line, or alone on the line before (before a start tag written over several
  lines, for every line of the tag); YAML launch files:
  ``# roslint-names: ignore RN202`` likewise.

Codes and slugs both work (``NOLINT(hard-coded-absolute-name)``). A bare ``NOLINT`` or
``# noqa`` belongs to cpplint, clang-tidy or flake8 and silences nothing here, and the
other tools' codes in the same comment (``NOLINT(build/include, RN202)``) are left to them:
only an ``RN`` code we do not know is reported (RN003).

Comments are found by scanning lines, as flake8 does for ``noqa``: a suppression-shaped
text inside a string literal also counts, a price worth not parsing twice.
"""

from __future__ import annotations

import heapq
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

from .lines import split_lines
from .model import Language, Span

# Keys separated by a comma or blanks; the separator is never empty, so no backtracking blow-up.
_KEYS = r"([A-Za-z0-9_\-]+(?:(?:[ \t]*,[ \t]*|[ \t]+)[A-Za-z0-9_\-]+)*)"
_NOQA_LANGUAGES = frozenset({Language.PYTHON, Language.LAUNCH_PYTHON, Language.RECONFIGURE})
_XML_LANGUAGES = frozenset({Language.LAUNCH_XML, Language.URDF, Language.PACKAGE_XML})
_YAML_LANGUAGES = frozenset({Language.LAUNCH_YAML, Language.PARAMETERS})
_MARKERS = {
    Language.CPP: ("roslint-names", "NOLINT"),
    Language.PYTHON: ("noqa",),
    Language.LAUNCH_PYTHON: ("noqa",),
    Language.RECONFIGURE: ("noqa",),  # a .cfg is a Python script
    Language.LAUNCH_XML: ("roslint-names",),
    Language.LAUNCH_YAML: ("roslint-names",),
    Language.PARAMETERS: ("roslint-names",),
    Language.URDF: ("roslint-names",),
    Language.PACKAGE_XML: ("roslint-names",),
    Language.SERVICE_DEFINITION: ("roslint-names",),
}
NOLINT = re.compile(r"//\s*NOLINT(NEXTLINE)?\(([^)]*)\)")
NOQA = re.compile(r"#\s*noqa\s*:\s*" + _KEYS, re.IGNORECASE)
XML_IGNORE = re.compile(r"<!--\s*roslint-names\s*:\s*ignore\s+" + _KEYS + r".*?-->")
YAML_IGNORE = re.compile(r"#\s*roslint-names\s*:\s*ignore\s+" + _KEYS)
CPP_IGNORE = re.compile(r"//\s*roslint-names\s*:\s*ignore\s+" + _KEYS)
_LOOKS_LIKE_OUR_CODE = re.compile(r"^RN[0-9]+$", re.IGNORECASE)


@dataclass(frozen=True)
class Suppression:
    keys: tuple[str, ...]  # codes or slugs as written
    lines: frozenset[int]  # the lines whose findings it silences
    span: Span  # the comment, for RN002 and RN003


_BYTE_MARKERS = (b"NOLINT", b"noqa", b"NOQA", b"roslint-names")
_WIDE_BOMS = (b"\xff\xfe", b"\xfe\xff")  # UTF-16 and UTF-32: ASCII is not its own bytes


def may_hold_suppression(data: bytes) -> bool:
    """Whether ``data`` may hold a suppression of any language (a marker
    ``find_suppressions`` needs is in it); False only when it surely holds none."""
    return data.startswith(_WIDE_BOMS) or any(marker in data for marker in _BYTE_MARKERS)


def find_suppressions(text: str, language: Language) -> list[Suppression]:
    markers = _MARKERS.get(language)
    if markers is None:
        return []  # build files: context for the graph, nothing in them is reported
    markers = tuple(marker for marker in markers if marker in text)
    if not markers and not (
        language in _NOQA_LANGUAGES and "NOQA" in text  # flake8 accepts either case
    ):
        return []  # most files hold no suppression: one substring search, not a regex per line
    found: list[Suppression] = []
    if "\r" in text:  # old Mac or mixed line ends: every line, as ``split_lines`` counts them
        for index, line in enumerate(split_lines(text)):
            found.extend(_in_line(line, index + 1, language))
    else:
        # Only the lines holding the marker can hold a suppression (each pattern needs
        # it): a file with one NOLINT among thousands of lines is not split into them.
        number, start = 1, 0
        searching = _CASELESS_MARKER if language in _NOQA_LANGUAGES else None
        for at in _marker_positions(text, markers, searching):
            if at < start:
                continue  # a second marker on the line just scanned
            number += text.count("\n", start, at)
            start = text.rfind("\n", 0, at) + 1
            end = text.find("\n", at)
            end = len(text) if end < 0 else end
            found.extend(_in_line(text[start:end], number, language))
            number, start = number + 1, end + 1
    if language in _XML_LANGUAGES and any(len(s.lines) > 1 for s in found):
        found = _over_whole_tags(found, text)
    return found


_CASELESS_MARKER = re.compile("noqa", re.IGNORECASE)  # as ``NOQA`` matches it


def _marker_positions(
    text: str, markers: tuple[str, ...], caseless: re.Pattern[str] | None
) -> Iterator[int]:
    """Where any of ``markers`` occurs in ``text``, in order (in any case for
    ``caseless``)."""
    if caseless is not None:
        yield from (match.start() for match in caseless.finditer(text))
        return
    yield from heapq.merge(*(_positions(text, marker) for marker in markers))


def _positions(text: str, marker: str) -> Iterator[int]:
    at = text.find(marker)
    while at >= 0:
        yield at
        at = text.find(marker, at + 1)


def _over_whole_tags(found: list[Suppression], text: str) -> list[Suppression]:
    """A comment alone on the line before a start tag written over several lines covers
    every line of the tag: no comment can stand between its attributes."""
    from .extract.launch.xmlsafe import scan_start_tags  # only for files with such a comment

    last_line_of: dict[int, int] = {}
    for tag in scan_start_tags(text):
        first = text.count("\n", 0, tag.start) + 1
        last_line_of.setdefault(first, text.count("\n", 0, tag.end) + 1)
    return [_widened(suppression, last_line_of) for suppression in found]


def _widened(suppression: Suppression, last_line_of: dict[int, int]) -> Suppression:
    after = suppression.span.line + 1
    if len(suppression.lines) == 1 or last_line_of.get(after, after) == after:
        return suppression
    lines = suppression.lines | frozenset(range(after, last_line_of[after] + 1))
    return Suppression(suppression.keys, lines, suppression.span)


def _in_line(line: str, number: int, language: Language) -> Iterable[Suppression]:
    if language is Language.CPP:
        for match in NOLINT.finditer(line):
            target = number + 1 if match.group(1) else number
            yield _make(match.group(2), frozenset({target}), number, match)
        yield from _ignore_comments(line, number, CPP_IGNORE)
    elif language in _NOQA_LANGUAGES:
        for match in NOQA.finditer(line):
            yield _make(match.group(1), frozenset({number}), number, match)
    else:
        pattern = YAML_IGNORE if language in _YAML_LANGUAGES else XML_IGNORE
        yield from _ignore_comments(line, number, pattern)


def _ignore_comments(line: str, number: int, pattern: re.Pattern[str]) -> Iterator[Suppression]:
    """``roslint-names: ignore`` comments: alone on its line, one is about the next line;
    after code or markup, about its own."""
    for match in pattern.finditer(line):
        alone = not line[: match.start()].strip()
        lines = frozenset({number, number + 1}) if alone else frozenset({number})
        yield _make(match.group(1), lines, number, match)


def split_keys(keys_text: str) -> list[str]:
    """The codes or slugs of a suppression comment, as written."""
    return [key for key in re.split(r"[\s,]+", keys_text.strip()) if key]


def _make(keys_text: str, lines: frozenset[int], number: int, match: re.Match[str]) -> Suppression:
    keys = tuple(split_keys(keys_text))
    span = Span(number, match.start() + 1, number, match.end() + 1)
    return Suppression(keys, lines, span)


def is_our_code(key: str) -> bool:
    """A key that claims to be one of our codes (so an unknown one is worth RN003)."""
    return bool(_LOOKS_LIKE_OUR_CODE.match(key))

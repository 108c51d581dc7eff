"""``check --add-noqa``: a suppression comment for every current finding, in its file's form.

- C++: ``  // roslint-names: ignore RN202`` at the end of the line, or alone on the line
  before where the line would pass 80 columns (cpplint's default limit; ament_cpplint's
  is 100), merged into such a comment already there. cpplint reports any category it does
  not know inside ``NOLINT(...)``, so our codes never go there; ones an older version wrote
  there are moved out (``NOLINT(runtime/int, RN202)`` keeps ``runtime/int``);
- Python: ``  # noqa: RN202``, merged into a ``# noqa: E501`` already there;
- launch XML, URDF, XACRO: `` <!-- roslint-names: ignore RN202 -->`` after the markup; a
  finding inside a start tag written over several lines (an attribute on a line of its
  own) gets the comment alone on the line before the tag, which covers the whole tag;
- launch YAML: ``  # roslint-names: ignore RN202``.

A line whose end is not free for a comment (inside a Python string, after a C++ line
continuation) is left alone and named, as is a file that is not UTF-8, one edited since
the run read it, a read-only one and one reached through a link leading out of the
linted paths. Line endings and everything else of the file are kept byte for byte. The
comments of all files are written together or not at all (``files.replace_all``).
"""

from __future__ import annotations

import io
import re
import tokenize
from collections import defaultdict
from collections.abc import Iterable
from dataclasses import dataclass

from ..lines import split_lines, split_lines_keeping_ends
from ..model import Diagnostic, Language
from ..suppress import CPP_IGNORE, NOLINT, NOQA, XML_IGNORE, YAML_IGNORE, is_our_code, split_keys
from .files import Change, Snapshot


@dataclass(frozen=True)
class Outcome:
    added: int  # comments written or extended
    files: int  # files changed
    left: tuple[tuple[str, int, str], ...]  # (path, line, why) of findings not suppressed
    writes: tuple[Change, ...] = ()  # what to write: every file's new bytes


def add_noqa(
    diagnostics: Iterable[Diagnostic], languages: dict[str, Language | None], snapshot: Snapshot
) -> Outcome:
    """The suppression of each reported (not suppressed, not baselined) diagnostic in its
    file, to be written (``Snapshot.replace_all(outcome.writes)``).

    ``languages`` gives each diagnostic path's language (``discover.classify``)."""
    wanted: dict[str, dict[int, set[str]]] = defaultdict(lambda: defaultdict(set))
    for diagnostic in diagnostics:
        if not diagnostic.suppressed and not diagnostic.baselined:
            wanted[diagnostic.path][diagnostic.span.line].add(diagnostic.code)
        elif diagnostic.suppressed and languages.get(diagnostic.path) is Language.CPP:
            wanted[diagnostic.path]  # its suppressions may be in a form to move out of NOLINT
    added = files = 0
    left: list[tuple[str, int, str]] = []
    writes: list[Change] = []
    for path, by_line in sorted(wanted.items()):
        language = languages.get(path)
        data, why = snapshot.for_edit(path)
        if data is None:
            left.extend((path, line, why) for line in by_line)
            continue
        if not by_line and b"NOLINT" not in data:
            continue
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            left.extend((path, line, "not UTF-8") for line in by_line)
            continue
        suppressed = with_suppressions(text, language, by_line)
        if suppressed is None:
            left.extend((path, line, "no comment form for this file") for line in by_line)
            continue
        after, count, refused = suppressed
        left.extend((path, line, why) for line, why in refused)
        if count:
            writes.append(Change(path, data, after.encode("utf-8")))
            added += count
            files += 1
    return Outcome(added, files, tuple(left), tuple(writes))


def with_suppressions(
    text: str, language: Language | None, by_line: dict[int, set[str]]
) -> tuple[str, int, list[tuple[int, str]]] | None:
    """``text`` with a suppression of the codes ``by_line`` names on each line, the number
    of comments written, and the (line, why) of those refused; None when the language
    has no comment form."""
    editor = _EDITORS.get(language) if language is not None else None
    if editor is None:
        return None
    lines = split_lines_keeping_ends(text)
    count, refused = editor(lines, text, by_line)
    return "".join(lines), count, refused


_Edit = tuple[int, list[tuple[int, str]]]  # comments added, (line, why) refused


def _body_and_ending(line: str) -> tuple[str, str]:
    body = line.rstrip("\r\n")
    return body, line[len(body) :]


def _codes(existing: str, new: Iterable[str]) -> str:
    keys = split_keys(existing)
    keys += sorted(code for code in new if code not in keys)
    return ", ".join(keys)


def _append(
    lines: list[str],
    number: int,
    codes: set[str],
    pattern: re.Pattern[str],
    *,
    make: str,
    group: int = 1,
) -> None:
    """Merge ``codes`` into the comment ``pattern`` finds on the line (its keys are match
    group ``group``), else append ``make``."""
    body, ending = _body_and_ending(lines[number - 1])
    match = next((m for m in pattern.finditer(body) if m.group(group) is not None), None)
    if pattern is NOLINT and match is not None and match.group(1):
        match = None  # NOLINTNEXTLINE on this line is about the next one
    if match is not None:
        merged = _codes(match.group(group), codes)
        body = body[: match.start(group)] + merged + body[match.end(group) :]
    else:
        body = body.rstrip() + make.format(", ".join(sorted(codes)))
    lines[number - 1] = body + (ending or "")


def _cpp(lines: list[str], text: str, by_line: dict[int, set[str]]) -> _Edit:
    wanted: dict[int, set[str]] = defaultdict(set)
    refused: list[tuple[int, str]] = []
    for number, codes in by_line.items():
        if _in_macro(lines, number):
            refused.append((number, "the line continues a macro"))
        else:
            wanted[number] |= codes
    count = _move_out_of_nolint(lines, wanted)
    for number, codes in sorted(wanted.items(), reverse=True):  # bottom up: lines shift
        count += 1
        body, _ = _body_and_ending(lines[number - 1])
        fits = len(body.rstrip()) + len(_cpp_comment(codes)) + 2 <= CPP_LINE_LIMIT
        if CPP_IGNORE.search(body) is not None:
            _append(lines, number, codes, CPP_IGNORE, make="")
        elif fits and not _alone_before(lines, number, CPP_IGNORE):
            _append(lines, number, codes, CPP_IGNORE, make="  " + _cpp_comment(codes))
        else:
            _before(lines, number, codes, CPP_IGNORE, _cpp_comment(codes))
    return count, sorted(refused)


def _alone_before(lines: list[str], number: int, pattern: re.Pattern[str]) -> bool:
    """Whether the line before line ``number`` holds such a comment and nothing else."""
    previous = _body_and_ending(lines[number - 2])[0] if number >= 2 else ""
    match = pattern.search(previous)
    return match is not None and not previous[: match.start()].strip()


def _before(
    lines: list[str], number: int, codes: set[str], pattern: re.Pattern[str], comment: str
) -> None:
    """The codes in a comment alone on the line before line ``number``: merged into one
    already there, else ``comment`` written there with the line's indentation."""
    if _alone_before(lines, number, pattern):
        _append(lines, number - 1, codes, pattern, make="")
        return
    body, ending = _body_and_ending(lines[number - 1])
    indent = body[: len(body) - len(body.lstrip(" \t"))]
    lines.insert(number - 1, indent + comment + (ending or "\n"))


# cpplint's default --linelength: a comment that would push a line past it is written on
# the line before instead, so no line length check fails because of it.
CPP_LINE_LIMIT = 80


def _cpp_comment(codes: Iterable[str]) -> str:
    return f"// roslint-names: ignore {', '.join(sorted(codes))}"


def _in_macro(lines: list[str], number: int) -> bool:
    """Whether the line continues a macro or is continued: a ``//`` comment there would
    swallow the backslash, and a line inserted before it would end the macro."""
    body = _body_and_ending(lines[number - 1])[0]
    previous = _body_and_ending(lines[number - 2])[0] if number >= 2 else ""
    return body.endswith("\\") or previous.endswith("\\")


def _move_out_of_nolint(lines: list[str], wanted: dict[int, set[str]]) -> int:
    """Our codes out of every ``NOLINT(...)`` and ``NOLINTNEXTLINE(...)`` comment: a
    ``NOLINTNEXTLINE`` of ours alone on its line becomes our comment in its place, the
    others' codes join ``wanted`` for the line they silence, and a ``NOLINT`` left with no
    code goes. The number of comments rewritten in place."""
    rewritten = 0
    for number in range(1, len(lines) + 1):
        body, ending = _body_and_ending(lines[number - 1])
        for match in reversed(list(NOLINT.finditer(body))):
            keys = split_keys(match.group(2))
            ours = {key.upper() for key in keys if is_our_code(key)}
            target = number + 1 if match.group(1) else number
            if not ours or target > len(lines) or _in_macro(lines, target):
                continue
            kept = [key for key in keys if not is_our_code(key)]
            if kept:
                body = body[: match.start(2)] + ", ".join(kept) + body[match.end(2) :]
                wanted[target] |= ours
            elif match.group(1) and not (body[: match.start()] + body[match.end() :]).strip():
                body = body[: match.start()] + _cpp_comment(ours)
                rewritten += 1
            else:
                body = body[: match.start()].rstrip() + body[match.end() :]
                wanted[target] |= ours
        lines[number - 1] = body + ending
    return rewritten


def _python(lines: list[str], text: str, by_line: dict[int, set[str]]) -> _Edit:
    busy = _python_lines_without_room(text)
    refused: list[tuple[int, str]] = []
    count = 0
    for number, codes in sorted(by_line.items()):
        if number in busy:
            refused.append((number, "the line ends inside a string or continues"))
            continue
        _append(lines, number, codes, NOQA, make="  # noqa: {}")
        count += 1
    return count, refused


def _python_lines_without_room(text: str) -> set[int]:
    """Lines whose end lies inside a string, or that end with a backslash."""
    busy: set[int] = set()
    try:
        for token in tokenize.generate_tokens(io.StringIO(text).readline):
            if token.type == tokenize.STRING and token.end[0] > token.start[0]:
                busy.update(range(token.start[0], token.end[0]))
    except (tokenize.TokenError, SyntaxError):
        pass  # the file does not tokenize: RN001 says so; its other lines are fine
    for number, line in enumerate(split_lines(text), start=1):
        if line.endswith("\\"):
            busy.add(number)
    return busy


def _yaml(lines: list[str], text: str, by_line: dict[int, set[str]]) -> _Edit:
    for number, codes in sorted(by_line.items()):
        _append(lines, number, codes, YAML_IGNORE, make="  # roslint-names: ignore {}")
    return len(by_line), []


def _xml(lines: list[str], text: str, by_line: dict[int, set[str]]) -> _Edit:
    """After the markup on the line; inside a start tag over several lines, alone on the
    line before the tag (``suppress`` gives such a comment the whole tag)."""
    from ..extract.launch.xmlsafe import scan_start_tags

    offsets = [0]
    for line in lines:
        offsets.append(offsets[-1] + len(line))
    before_tag: dict[int, set[str]] = defaultdict(set)  # tag's first line -> codes
    at_end: dict[int, set[str]] = {}
    tags = scan_start_tags(text)
    for number, codes in by_line.items():
        body, _ = _body_and_ending(lines[number - 1])
        end_of_line = offsets[number - 1] + len(body)
        tag = next((t for t in tags if t.start < end_of_line < t.end), None)
        if tag is None:
            at_end[number] = codes
        else:
            first = text.count("\n", 0, tag.start) + 1
            before_tag[first] |= codes
    for number, codes in sorted(at_end.items()):
        _append(lines, number, codes, XML_IGNORE, make=" <!-- roslint-names: ignore {} -->")
    for first, codes in sorted(before_tag.items(), reverse=True):  # bottom up: lines shift
        comment = f"<!-- roslint-names: ignore {', '.join(sorted(codes))} -->"
        _before(lines, first, codes, XML_IGNORE, comment)
    return len(at_end) + len(before_tag), []


_EDITORS = {
    Language.CPP: _cpp,
    Language.PYTHON: _python,
    Language.LAUNCH_PYTHON: _python,
    Language.RECONFIGURE: _python,
    Language.LAUNCH_YAML: _yaml,
    Language.PARAMETERS: _yaml,
    Language.LAUNCH_XML: _xml,
    Language.URDF: _xml,
}

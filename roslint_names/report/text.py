"""The default report: one gcc-style line per finding.

::

    src/robot_bringup/launch/robot.launch:12:15: error: node name ... [RN101 illegal-name]

Editors read it with no setup: VS Code's ``$gcc`` problem matcher, vim's ``errorformat`` and
Emacs ``compilation-mode``. Related locations follow as gcc ``note:`` lines (which ``$gcc``
ignores). With ``show_source`` each finding is followed by its source line, indented by four
spaces, and a caret line under the span (``^~~~``). Colour only when the context asks.
"""

from __future__ import annotations

import unicodedata
from collections.abc import Sequence

from ..catalog import RuleMeta
from ..model import Diagnostic, Severity, Span
from .base import ReportContext, one_line, visible

TAB_SIZE = 8  # tab stops of the excerpt, counted from the start of the source line
INDENT = "    "

_RESET = "\x1b[0m"
_BOLD = "\x1b[1m"
_STYLE = {
    "error": "\x1b[1;31m",  # bold red
    "warning": "\x1b[1;33m",  # bold yellow
    "note": "\x1b[1;36m",  # bold cyan
}


def render_text(
    diagnostics: Sequence[Diagnostic], rules: Sequence[RuleMeta], context: ReportContext
) -> str:
    lines: list[str] = []
    for diagnostic in visible(diagnostics):
        lines.append(format_line(diagnostic, context.color))
        if context.show_source and diagnostic.source_line is not None:
            source = diagnostic.source_line
            lines.extend(excerpt(source, diagnostic.span, diagnostic.severity, context.color))
        for related in diagnostic.related:
            location = f"{related.path}:{related.span.line}:{related.span.column}:"
            lines.append(_line(location, "note", one_line(related.message), context.color))
    return "".join(line + "\n" for line in lines)


def format_line(diagnostic: Diagnostic, color: bool = False) -> str:
    """``path:line:col: severity: message [CODE slug]``, and `` [*]`` when ``--fix`` can
    fix it."""
    span = diagnostic.span
    location = f"{diagnostic.path}:{span.line}:{span.column}:"
    message = f"{one_line(diagnostic.message)} [{diagnostic.code} {diagnostic.rule_name}]"
    if diagnostic.edit is not None and diagnostic.edit.safe:
        message += " [*]"
    return _line(location, diagnostic.severity.value, message, color)


def _line(location: str, label: str, message: str, color: bool) -> str:
    if not color:
        return f"{location} {label}: {message}"
    return f"{_BOLD}{location}{_RESET} {_STYLE[label]}{label}:{_RESET} {message}"


def excerpt(source_line: str, span: Span, severity: Severity, color: bool = False) -> list[str]:
    """The source line and a caret line under ``span``, both indented by four spaces.

    Columns are code points; tabs are expanded to the same stops in both lines, wide (East
    Asian) characters take two cells and combining marks none, so the carets sit under the
    span as a terminal shows it. A span running past the end of its line is clipped there.
    """
    text = source_line.rstrip("\r\n")
    shown, starts = _cells(text)
    length = len(text)
    first = min(max(span.column, 1), length + 1) - 1  # 0-based code point index
    # exclusive end index; a span running onto the next lines is clipped at the line's end
    stop = min(max(span.end_column - 1, first), length) if span.end_line == span.line else length
    start_cell = starts[first]
    width = max(starts[stop] - start_cell, 1)
    carets = "^" + "~" * (width - 1)
    if color:
        carets = f"{_STYLE[severity.value]}{carets}{_RESET}"
    return [f"{INDENT}{shown}".rstrip(), f"{INDENT}{' ' * start_cell}{carets}"]


def _cells(text: str) -> tuple[str, list[int]]:
    """``text`` as displayed (tabs expanded, control characters replaced) and, for each
    code point index (and one past the end), the terminal cell where it starts."""
    shown: list[str] = []
    starts: list[int] = []
    cell = 0
    for char in text:
        starts.append(cell)
        if char == "\t":
            width = TAB_SIZE - cell % TAB_SIZE
            shown.append(" " * width)
        elif unicodedata.category(char) == "Cc":
            width = 1
            shown.append("\N{REPLACEMENT CHARACTER}")
        else:
            if unicodedata.combining(char) or unicodedata.category(char) in ("Mn", "Me", "Cf"):
                width = 0
            elif unicodedata.east_asian_width(char) in ("W", "F"):
                width = 2
            else:
                width = 1
            shown.append(char)
        cell += width
    starts.append(cell)
    return "".join(shown), starts

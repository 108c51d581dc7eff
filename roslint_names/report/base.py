"""What every reporter shares: the render context and a few small helpers.

Kept apart from ``__init__`` so that the format modules can import it without a cycle.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from ..catalog import RuleMeta
from ..model import Diagnostic


@dataclass(frozen=True)
class ReportContext:
    """What a reporter may know besides the diagnostics and the rule metadata."""

    tool_version: str
    root: Path  # the directory paths are relative to (the current directory)
    show_source: bool = False  # text: print the source line and a caret line under the span
    color: bool = False  # text: ANSI colours; the CLI sets it only on a TTY
    include_suppressed: bool = False  # SARIF only: keep suppressed results, marked as such
    baseline: bool = False  # a baseline is in use: SARIF marks each result's baselineState
    files: tuple[str, ...] = ()  # JUnit: the files checked, each a testcase, findings or not


def visible(diagnostics: Iterable[Diagnostic]) -> list[Diagnostic]:
    """The diagnostics a report shows: suppressed and baselined ones are left out, order
    is kept."""
    return [d for d in diagnostics if not d.suppressed and not d.baselined]


def rules_by_code(rules: Sequence[RuleMeta]) -> dict[str, RuleMeta]:
    """Rule metadata keyed by code; the first entry wins if a code is given twice."""
    table: dict[str, RuleMeta] = {}
    for rule in rules:
        table.setdefault(rule.code, rule)
    return table


def plural(count: int, noun: str) -> str:
    return f"{count} {noun}" if count == 1 else f"{count} {noun}s"


def one_line(text: str) -> str:
    """``text`` with its line breaks turned into spaces, for line-oriented formats."""
    return " ".join(text.splitlines()) if ("\n" in text or "\r" in text) else text

"""Where an edit moved a file's names, when it moved nothing else: the places a replay keeps
in that file, put where they are now (``same_facts``).

A line put above a node's code, a longer comment, a reformatted call: the file's facts
are those it had but for their spans, so the workspace graph is the one it was but for
the places of that file. Every place a graph finding holds comes from the facts (the
graph is built from nothing else), so each of the file's old spans has a new one, found
by walking the old and the new facts side by side (``moved_spans``); a place of the file
written into a message is ``path:line:column`` (``rules.graph_common.where``).

Left as facts that differ: a name, a role, any value but a span; the order of the facts
(extraction follows the text, so a name that moved past another of the file is another
tuple); and a span that would go to two places. Not compared: a runtime event's
``order`` (a byte offset) and ``scope`` (its function and the line it starts on), which
the graph never reads (it reads whether a file calls init), and the suppression marker
(which files a run reads to judge them). A kept place of the file that is no fact's
span, or a ``path:line:column`` of it no fact starts at, makes the replay refused
(``UnplacedError``): a run that builds the graph then says where it is.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import fields, is_dataclass, replace
from typing import Any

from .model import Diagnostic, FileFacts, Finding, RelatedLocation, RuntimeEvent, Span

# Fields compared by nothing: what the graph never reads (module docstring).
_NOT_COMPARED: dict[type, frozenset[str]] = {
    FileFacts: frozenset({"suppression_marker"}),
    RuntimeEvent: frozenset({"order", "scope"}),
}


def moved_finding(finding: Finding, path: str, moves: Sequence[Moves]) -> Finding:
    """A graph rule's finding in the file at ``path``, with every edited file's places
    where they are now."""
    for move in moves:
        finding = move.finding(finding, path)
    return finding


def moved_diagnostic(diagnostic: Diagnostic, moves: Sequence[Moves]) -> Diagnostic:
    """A kept finding of a file not edited, with every edited file's places where they are
    now."""
    for move in moves:
        diagnostic = move.diagnostic(diagnostic)
    return diagnostic


class UnplacedError(Exception):
    """A kept place of the edited file whose new place the facts do not tell."""


def moved_spans(before: FileFacts, now: FileFacts) -> dict[Span, Span] | None:
    """Each span of ``before`` and where it is in ``now``, when the two differ in spans
    alone (and in what is never compared); None otherwise."""
    pairs: dict[Span, Span] = {}

    def same(old: Any, new: Any) -> bool:
        if isinstance(old, Span):
            return isinstance(new, Span) and pairs.setdefault(old, new) == new
        if type(old) is not type(new):
            return False
        if isinstance(old, tuple):
            return len(old) == len(new) and all(map(same, old, new))
        if is_dataclass(old):
            skipped = _NOT_COMPARED.get(type(old), frozenset())
            return all(
                same(getattr(old, field.name), getattr(new, field.name))
                for field in fields(old)
                if field.name not in skipped
            )
        return bool(old == new)

    return pairs if same(before, now) else None


class Moves:
    """The places of one edited file (``display``) as they moved (``spans``)."""

    def __init__(self, display: str, spans: dict[Span, Span]) -> None:
        self.display = display
        self._spans = spans
        points: dict[tuple[int, int], tuple[int, int] | None] = {}
        for old, new in spans.items():
            point = (new.line, new.column)
            if points.setdefault((old.line, old.column), point) != point:
                points[(old.line, old.column)] = None  # two places start there: unknown
        self._points = points
        # Written where a message names a place: at its start, or after a space, a
        # bracket or a quote (not the end of another path that ends alike).
        self._written = re.compile(r"(?<![^\s(\[\"'])" + re.escape(display) + r":(\d+):(\d+)")
        self.still = all(old == new for old, new in spans.items())  # nothing moved

    def finding(self, finding: Finding, path: str) -> Finding:
        """A graph rule's finding in the file at ``path``, its places of the edited file
        moved."""
        span = self._span(finding.span) if path == self.display else finding.span
        return replace(
            finding,
            span=span,
            message=self._message(finding.message),
            related=self._related(finding.related),
        )

    def diagnostic(self, diagnostic: Diagnostic) -> Diagnostic:
        """A kept finding of another file, its places of the edited file moved."""
        message = self._message(diagnostic.message)
        related = self._related(diagnostic.related)
        if message == diagnostic.message and related == diagnostic.related:
            return diagnostic
        return replace(diagnostic, message=message, related=related)

    def _related(self, related: tuple[RelatedLocation, ...]) -> tuple[RelatedLocation, ...]:
        return tuple(
            replace(
                place,
                span=self._span(place.span) if place.path == self.display else place.span,
                message=self._message(place.message),
            )
            for place in related
        )

    def _span(self, span: Span) -> Span:
        moved = self._spans.get(span)
        if moved is None:
            raise UnplacedError(f"{self.display}:{span.line}:{span.column}")
        return moved

    def _message(self, message: str) -> str:
        if self.display not in message:
            return message

        def moved(match: re.Match[str]) -> str:
            point = self._points.get((int(match[1]), int(match[2])))
            if point is None:
                raise UnplacedError(match[0])
            return f"{self.display}:{point[0]}:{point[1]}"

        return self._written.sub(moved, message)

"""Code a C++ test expects to fail: what it holds is deliberately wrong, never a finding.

gtest's ``EXPECT_THROW``, ``ASSERT_THROW``, ``EXPECT_ANY_THROW``, ``ASSERT_ANY_THROW`` and
their wrappers (rclcpp's ``RCLCPP_EXPECT_THROW_EQ``) run a statement that must throw; the
death tests (``EXPECT_DEATH``, ``ASSERT_EXIT``...) one that must crash; ``EXPECT_FALSE`` and
``ASSERT_FALSE`` a call that must come out false, a probe of what is refused or absent
(tf2's ``EXPECT_FALSE(buffer.canTransform("", "a", ros::Time()))``). The fields set on a
variable by the statements just before such a macro, when the macro takes that variable,
are that failing input too (tf2's ``buffer_core_test.cpp``: ``tranStamped.header.frame_id
= "/"; EXPECT_FALSE(mBC.setTransform(tranStamped, "authority"));``). A ``try`` block
that reaches ``FAIL()`` or ``ADD_FAILURE()`` expects what runs before it to throw (ros_comm's
``test_roscpp``: ``try { ros::NodeHandle n(parent, "illegal_name!!!"); FAIL(); } catch``).
``EXPECT_NO_THROW`` and ``ASSERT_NO_THROW`` expect success: their names are judged.
"""

from __future__ import annotations

import re
from bisect import bisect_right

from tree_sitter import Node

from roslint_names.model import Span

from .source import Source, field, field_root

_EXPECTING = re.compile(
    rb"\b(?:\w+_)?(?:EXPECT|ASSERT)_(?:ANY_)?THROW(?:_EQ)?\b"
    rb"|\b(?:EXPECT|ASSERT)_(?:DEBUG_)?(?:DEATH|EXIT)(?:_IF_SUPPORTED)?\b"
    rb"|\b(?:EXPECT|ASSERT)_FALSE\b"
)
_MARKERS = (b"_THROW", b"_DEATH", b"_EXIT", b"_FALSE")  # one is in every macro of _EXPECTING
_FAILURES = ("FAIL", "ADD_FAILURE", "GTEST_FAIL")


Position = tuple[int, int]  # (line, column), as spans count them


class ExpectedFailures:
    """Where a file's code is expected to fail: ranges of positions, end exclusive."""

    def __init__(self, source: Source) -> None:
        ranges = sorted([*_macro_arguments(source), *_tries_that_fail(source)])
        self._starts = [start for start, _ in ranges]
        self._ranges = ranges

    def holds(self, span: Span) -> bool:
        """Whether what starts at ``span`` lies inside code expected to fail."""
        position = (span.line, span.column)
        for start, end in self._ranges[: bisect_right(self._starts, position)]:
            if start <= position < end:
                return True
        return False


def _start(source: Source, node: Node) -> Position:
    span = source.span(node)
    return span.line, span.column


def _end(source: Source, node: Node) -> Position:
    span = source.span(node)
    return span.end_line, span.end_column


def _macro_arguments(source: Source) -> list[tuple[Position, Position]]:
    found: list[tuple[Position, Position]] = []
    for _, word in source.words(_EXPECTING, _MARKERS):
        call = word.parent
        if call is None or call.type != "call_expression" or field(call, "function") != word:
            continue
        arguments = field(call, "arguments")
        if arguments is not None:
            found.append((_start(source, arguments), _end(source, arguments)))
            found.extend(_prepared(source, call.parent, _identifiers(source, arguments)))
    return found


def _prepared(
    source: Source, statement: Node | None, taken: frozenset[str]
) -> list[tuple[Position, Position]]:
    """The statements just before ``statement`` that set a field of a variable the macro
    takes (``msg.header.frame_id = "/";``), back to the first that sets no field."""
    found: list[tuple[Position, Position]] = []
    if statement is None or statement.type != "expression_statement":
        return found
    previous = statement.prev_named_sibling
    while previous is not None:
        if previous.type != "comment":
            variable = _field_set(source, previous)
            if variable is None:
                break
            if variable in taken:
                found.append((_start(source, previous), _end(source, previous)))
        previous = previous.prev_named_sibling
    return found


def _field_set(source: Source, statement: Node) -> str | None:
    """The variable whose field an assignment statement sets: ``a`` of ``a.b.c = x;``."""
    assignment = statement.named_children[0] if statement.named_child_count else None
    if statement.type != "expression_statement" or assignment is None:
        return None
    if assignment.type != "assignment_expression":
        return None
    target = field(assignment, "left")
    if target is None or target.type != "field_expression":
        return None
    root = field_root(target)
    return None if root is None or root.type != "identifier" else source.text(root)


def _identifiers(source: Source, node: Node) -> frozenset[str]:
    """The plain identifiers written in ``node`` (a macro's arguments: a few dozen nodes)."""
    found: set[str] = set()
    stack = [node]
    while stack:
        current = stack.pop()
        if current.type == "identifier":
            found.add(source.text(current))
        stack.extend(current.named_children)
    return frozenset(found)


def _tries_that_fail(source: Source) -> list[tuple[Position, Position]]:
    """From a ``try`` body's start to a failure call among its statements."""
    found = []
    for name in _FAILURES:
        for word in source.occurrences(name):
            call = word.parent
            statement = None if call is None else call.parent
            while statement is not None and statement.type == "binary_expression":
                statement = statement.parent  # FAIL() << "what was accepted"
            body = None if statement is None else statement.parent
            if (
                call is None
                or call.type != "call_expression"
                or statement is None
                or statement.type != "expression_statement"
                or body is None
                or body.type != "compound_statement"
                or body.parent is None
                or body.parent.type != "try_statement"
            ):
                continue
            found.append((_start(source, body), _start(source, word)))
    return found

"""RN205 frame-id-leading-slash: tf2 in ROS 2 rejects frame ids that start with '/'."""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Severity
from ..rule import Rule, RuleContext
from .common import fix_hint, grammar_problems


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    for use, problem in grammar_problems(facts, RULE.code):
        yield Finding(use.span, f"frame id '{use.value}' {problem.reason}{fix_hint(problem)}")


RULE = Rule(
    code="RN205",
    name="frame-id-leading-slash",
    summary="A tf frame id starting with '/' (tf2 rejects it in ROS 2)",
    severity=Severity.ERROR,
    ros1_severity=Severity.WARNING,
    check=check,
)

"""RN101 illegal-name: a name the ROS runtime of its generation rejects."""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Severity
from ..rule import Rule, RuleContext
from .common import fix_hint, grammar_problems, label


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    ros = f"ROS {facts.generation.value}"
    for use, problem in grammar_problems(facts, RULE.code):
        message = f"{label(use)} '{use.value}' {problem.reason} ({ros}){fix_hint(problem)}"
        yield Finding(use.span, message)


RULE = Rule(
    code="RN101",
    name="illegal-name",
    summary="A name the ROS runtime rejects for its kind and generation",
    severity=Severity.ERROR,
    check=check,
)

"""RN205 frame-id-leading-slash: tf2 in ROS 2 rejects frame ids that start with '/'."""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Generation, Severity
from ..rule import Rule, RuleContext
from .common import fix_hint, grammar_problems, suggested_fix


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    # tf2 in ROS 2 refuses the frame: dropping the slash cannot break what works. ROS 1's
    # tf (not tf2) kept '/map' and 'map' apart under tf_prefix: there it is not certain.
    safe = facts.generation is Generation.ROS2
    for use, problem in grammar_problems(facts, RULE.code):
        message = f"frame id '{use.value}' {problem.reason}{fix_hint(problem)}"
        yield Finding(use.span, message, fix=suggested_fix(use, problem, safe=safe))


RULE = Rule(
    code="RN205",
    name="frame-id-leading-slash",
    summary="A tf frame id starting with '/' (tf2 rejects it in ROS 2)",
    severity=Severity.ERROR,
    ros1_severity=Severity.WARNING,
    check=check,
)

"""RN102 trailing-slash: ROS 2 rejects a name ending in '/', ROS 1 strips it silently."""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Severity
from ..rule import Rule, RuleContext
from .common import fix_hint, grammar_problems, label, suggested_fix


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    for use, problem in grammar_problems(facts, RULE.code):
        message = f"{label(use)} '{use.value}' {problem.reason}{fix_hint(problem)}"
        # ROS 1 strips the slash itself; ROS 2 refuses the name: dropping it is safe.
        yield Finding(use.span, message, fix=suggested_fix(use, problem, safe=True))


RULE = Rule(
    code="RN102",
    name="trailing-slash",
    summary="A name ending in '/' (rejected by ROS 2, silently stripped by ROS 1)",
    severity=Severity.ERROR,
    ros1_severity=Severity.WARNING,
    check=check,
)

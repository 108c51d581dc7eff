"""RN102 trailing-slash: ROS 2 rejects a name ending in '/', ROS 1 strips it silently."""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Severity
from ..names import check_name
from ..rule import Rule, RuleContext
from .common import label, static_uses


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    for use in static_uses(facts):
        problem = check_name(use.value, use.kind, facts.generation)
        if problem is None or problem.code != RULE.code:
            continue
        fix = f"; use '{problem.suggestion}'" if problem.suggestion else ""
        yield Finding(use.span, f"{label(use)} '{use.value}' {problem.reason}{fix}")


RULE = Rule(
    code="RN102",
    name="trailing-slash",
    summary="A name ending in '/' (rejected by ROS 2, silently stripped by ROS 1)",
    severity=Severity.ERROR,
    ros1_severity=Severity.WARNING,
    check=check,
)

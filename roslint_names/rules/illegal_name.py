"""RN101 illegal-name: a name the ROS runtime of its generation rejects."""

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
        ros = f"ROS {facts.generation.value}"
        yield Finding(use.span, f"{label(use)} '{use.value}' {problem.reason} ({ros}){fix}")


RULE = Rule(
    code="RN101",
    name="illegal-name",
    summary="A name the ROS runtime rejects for its kind and generation",
    severity=Severity.ERROR,
    check=check,
)

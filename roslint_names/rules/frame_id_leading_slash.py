"""RN205 frame-id-leading-slash: tf2 in ROS 2 rejects frame ids that start with '/'."""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Kind, Severity
from ..names import check_name
from ..rule import Rule, RuleContext
from .common import static_uses


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    for use in static_uses(facts):
        if use.kind is not Kind.FRAME:
            continue
        problem = check_name(use.value, use.kind, facts.generation)
        if problem is None or problem.code != RULE.code:
            continue
        fix = f"; use '{problem.suggestion}'" if problem.suggestion else ""
        yield Finding(use.span, f"frame id '{use.value}' {problem.reason}{fix}")


RULE = Rule(
    code="RN205",
    name="frame-id-leading-slash",
    summary="A tf frame id starting with '/' (tf2 rejects it in ROS 2)",
    severity=Severity.ERROR,
    ros1_severity=Severity.WARNING,
    check=check,
)

"""RN001 parse-error: a file that cannot be decoded or parsed; the run goes on."""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Severity
from ..rule import Rule, RuleContext


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    for error in facts.parse_errors:
        yield Finding(error.span, error.message)


RULE = Rule(
    code="RN001",
    name="parse-error",
    summary="A file that cannot be decoded or parsed; its names are not checked",
    severity=Severity.ERROR,
    check=check,
)

"""RN206 naming-policy: a name that does not match the project's configured pattern.

Nothing is reported until a policy is configured under ``[naming]``.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from ..model import FileFacts, Finding, Severity
from ..names import is_valid
from ..rule import Rule, RuleContext
from .common import chosen_here, label, static_uses


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    if not context.policies:
        return
    compiled = [(policy, re.compile(policy.pattern)) for policy in context.policies]
    for use in static_uses(facts):
        if not chosen_here(use, facts) or not is_valid(use.value, use.kind, facts.generation):
            continue
        for policy, pattern in compiled:
            if policy.kind is use.kind and not pattern.fullmatch(use.value):
                yield Finding(
                    use.span,
                    f"{label(use)} '{use.value}' does not match the project's "
                    f"{use.kind.value} naming policy '{policy.description}'",
                )


RULE = Rule(
    code="RN206",
    name="naming-policy",
    summary="A name that does not match the naming policy configured for its kind",
    severity=Severity.WARNING,
    check=check,
    judges_test_code=False,
)

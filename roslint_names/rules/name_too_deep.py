"""RN201 name-too-deep: a graph name with more than ``max-depth`` tokens.

Deep names are hard to type, to remap and to read in rqt_graph; a name that is already
deep in a file ends deeper still once launch files push namespaces on it. Parameters are
left out: their nesting mirrors the configuration structure (``controller.gains.p``).
"""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Role, Severity
from ..names import depth, is_valid
from ..rule import Rule, RuleContext
from .common import GRAPH_KINDS, label, static_uses


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    for use in static_uses(facts):
        if use.kind not in GRAPH_KINDS or use.role is Role.REMAP_FROM:
            continue  # a remap's source is spelled by the node's code, not chosen here
        if not is_valid(use.value, use.kind, facts.generation):
            continue  # RN101 reports it; one problem, one finding
        levels = depth(use.value, use.kind)
        if levels > context.max_depth:
            yield Finding(
                use.span,
                f"{label(use)} '{use.value}' has {levels} levels; "
                f"the limit is {context.max_depth} (max-depth)",
            )


RULE = Rule(
    code="RN201",
    name="name-too-deep",
    summary="A name with more than max-depth tokens (default 4)",
    severity=Severity.WARNING,
    check=check,
)
